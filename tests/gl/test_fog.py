"""fogvertex(3G): vertex fog against hand-computed colours and Mesa glFog.

MVIEWING with ortho(-0.5, 7.5, -0.5, 7.5, 0, 10): a polygon at object z = -Z is at
eye distance Z.  Colours round as floor(255 c + 0.5) (docs/numeric_model.md s. 4).
"""

import math

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl._core import GLTypeError, GLUsageError, GLValueError

W = H = 8


@pytest.fixture
def win(gl_window):
    def make(**kw):
        ctx = gl_window(W, H, **kw)
        gl.mmode(GL.MVIEWING)
        gl.ortho(-0.5, 7.5, -0.5, 7.5, 0.0, 10.0)
        return ctx
    return make


def square_at(z, rgb=(1.0, 0.0, 0.0)):
    gl.c3f(rgb)
    gl.bgnpolygon()
    for x, y in ((-0.5, -0.5), (7.5, -0.5), (7.5, 7.5), (-0.5, 7.5)):
        gl.v3f(x, y, z)
    gl.endpolygon()


def pixel(ctx):
    ctx.flush()
    return tuple(int(c) for c in ctx.read_rgba()[3, 3, :3])


def rnd(c):
    return math.floor(255 * c + 0.5)


def test_linear_fog_halfway(win):
    ctx = win()
    gl.fogvertex(GL.FG_VTX_LIN, (1.0, 5.0, 0.0, 0.0, 1.0))  # start 1, end 5, blue
    gl.fogvertex(GL.FG_ON, ())
    square_at(-3.0)
    # f = (5 - 3) / (5 - 1) = 0.5: red 0.5, blue 0.5 -> floor(127.5 + 0.5) = 128.
    assert pixel(ctx) == (128, 0, 128)


def test_exponential_fogs(win):
    ctx = win()
    gl.fogvertex(GL.FG_VTX_EXP, (0.25, 0.0, 0.0, 1.0))
    gl.fogvertex(GL.FG_ON, ())
    square_at(-2.0)
    # f = exp(-ln 255 * 0.25 * 2) = 255 ** -0.5 = 0.0626...: r 16, b 239.
    f = 255 ** -0.5
    assert pixel(ctx) == (rnd(f), 0, rnd(1 - f)) == (16, 0, 239)
    gl.fogvertex(GL.FG_VTX_EXP2, (0.25, 0.0, 1.0, 0.0))  # redefining takes effect
    square_at(-2.0)
    # f = exp(-ln 255 * (0.5)^2) = 255 ** -0.25 = 0.2506...: r 64, g 191.
    f = 255 ** -0.25
    assert pixel(ctx) == (rnd(f), rnd(1 - f), 0) == (64, 191, 0)


def test_density_is_one_over_the_full_fog_distance_and_off_restores(win):
    ctx = win()
    gl.fogvertex(GL.FG_DEFINE, (0.5, 1.0, 1.0, 1.0))  # FG_DEFINE is FG_VTX_EXP
    gl.fogvertex(GL.FG_ON, ())
    square_at(-2.0, (0.0, 0.0, 0.0))  # Z = 1/density: 1/255 of black is left
    assert pixel(ctx) == (254, 254, 254)  # 255 * (1 - 1/255) = 254 exactly
    gl.fogvertex(GL.FG_OFF, ())
    square_at(-2.0, (0.0, 0.0, 0.0))
    assert pixel(ctx) == (0, 0, 0)


def test_pixel_modes_and_lines_are_fogged_per_vertex(win):
    ctx = win()
    gl.fogvertex(GL.FG_PIX_LIN, (0.0, 4.0, 1.0, 1.0, 1.0))
    gl.fogvertex(GL.FG_ON, ())
    gl.c3f(0.0, 0.0, 0.0)
    gl.bgnline()
    gl.v3f(0.0, 3.0, -1.0)  # f = 3/4: 255/4 = 63.75 -> 64
    gl.v3f(7.0, 3.0, -1.0)
    gl.endline()
    assert pixel(ctx) == (64, 64, 64)
    assert gl.getgdesc(GL.GD_FOGVERTEX) == 1 and gl.getgdesc(GL.GD_FOGPIXEL) == 0


def test_fog_is_recorded_in_objects_and_checked(win):
    ctx = win()
    gl.makeobj(3)
    gl.fogvertex(GL.FG_VTX_LIN, (1.0, 5.0, 0.0, 0.0, 1.0))
    gl.fogvertex(GL.FG_ON, ())
    gl.closeobj()
    square_at(-3.0)
    assert pixel(ctx) == (255, 0, 0)
    gl.callobj(3)
    square_at(-3.0)
    assert pixel(ctx) == (128, 0, 128)
    with pytest.raises(GLValueError, match="FG_"):
        gl.fogvertex(9, ())
    with pytest.raises(GLTypeError, match="expected 5 numbers"):
        gl.fogvertex(GL.FG_VTX_LIN, (1.0, 2.0, 3.0, 4.0))
    with pytest.raises(GLValueError, match="density"):
        gl.fogvertex(GL.FG_VTX_EXP, (-1.0, 0.0, 0.0, 0.0))


def test_fog_in_colour_map_mode_is_refused(win):
    win(rgb=False)
    with pytest.raises(GLUsageError, match="colour-map mode"):
        gl.fogvertex(GL.FG_ON, ())


# -- Mesa glFog as an independent peer ----------------------------------------------------
def _mesa_colours(cases, fogc=(0.2, 0.6, 0.9)):
    """Mesa's colour of a constant-depth quad per case (GL mode, params, z, rgb)."""
    from vgxsim.reference.mesa import MesaPeer, _import_gl

    GLm, _ = _import_gl()
    peer = MesaPeer(W, H)
    out = []
    try:
        GLm.glViewport(0, 0, W, H)
        GLm.glDisable(GLm.GL_SCISSOR_TEST)
        GLm.glDisable(GLm.GL_DEPTH_TEST)
        GLm.glDisable(GLm.GL_DEPTH_CLAMP)
        GLm.glMatrixMode(GLm.GL_PROJECTION)
        GLm.glLoadIdentity()
        GLm.glOrtho(-0.5, 7.5, -0.5, 7.5, 0.0, 10.0)
        GLm.glMatrixMode(GLm.GL_MODELVIEW)
        GLm.glLoadIdentity()
        GLm.glEnable(GLm.GL_FOG)
        GLm.glHint(GLm.GL_FOG_HINT, GLm.GL_FASTEST)
        GLm.glFogfv(GLm.GL_FOG_COLOR, (*fogc, 1.0))
        for mode, params, z, rgb in cases:
            GLm.glFogi(GLm.GL_FOG_MODE, mode)
            for key, val in params.items():
                GLm.glFogf(key, val)
            GLm.glColor3f(*rgb)
            GLm.glBegin(GLm.GL_QUADS)
            for x, y in ((-0.5, -0.5), (7.5, -0.5), (7.5, 7.5), (-0.5, 7.5)):
                GLm.glVertex3f(x, y, z)
            GLm.glEnd()
            GLm.glFinish()
            c = int(peer.color()[3, 3])
            out.append((c & 0xFF, (c >> 8) & 0xFF, (c >> 16) & 0xFF))
    finally:
        peer.close()
    return out


def test_fog_matches_mesa(win):
    from vgxsim.reference import mesa

    if not mesa.mesa_available():
        pytest.skip("OSMesa is not available")
    GLm, _ = mesa._import_gl()
    fogc = (0.2, 0.6, 0.9)
    ours, cases = [], []
    ctx = win()
    rng = np.random.default_rng(5)
    for i in range(12):
        z = -float(rng.uniform(0.2, 9.5))
        rgb = tuple(float(v) for v in rng.uniform(0, 1, 3))
        d = float(rng.uniform(0.05, 0.6))
        kind = i % 3
        if kind == 0:
            start, end = sorted(float(v) for v in rng.uniform(0, 10, 2))
            gl.fogvertex(GL.FG_VTX_LIN, (start, end, *fogc))
            cases.append((GLm.GL_LINEAR, {GLm.GL_FOG_START: start, GLm.GL_FOG_END: end},
                          z, rgb))
        elif kind == 1:
            gl.fogvertex(GL.FG_VTX_EXP, (d, *fogc))
            cases.append((GLm.GL_EXP, {GLm.GL_FOG_DENSITY: math.log(255) * d}, z, rgb))
        else:
            gl.fogvertex(GL.FG_VTX_EXP2, (d, *fogc))
            cases.append((GLm.GL_EXP2, {GLm.GL_FOG_DENSITY: math.sqrt(math.log(255)) * d},
                          z, rgb))
        gl.fogvertex(GL.FG_ON, ())
        square_at(z, rgb)
        ours.append(pixel(ctx))
    theirs = _mesa_colours(cases, fogc)
    # Mesa fogs in float32 and rounds its own way: within one unit.
    diff = np.abs(np.array(ours) - np.array(theirs))
    assert diff.max() <= 1, (ours, theirs)
    assert len({c for c in ours}) > 6  # the cases really differ
