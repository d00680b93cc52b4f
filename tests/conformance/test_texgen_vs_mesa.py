"""texgen(3G) coordinates against Mesa's glTexGen (feedback mode), vertex by vertex.

TG_LINEAR, TG_CONTOUR and TG_SPHEREMAP are OpenGL's GL_OBJECT_LINEAR, GL_EYE_LINEAR
and GL_SPHERE_MAP (MSDN "Translating texgen").  Each case gives the planes under one
random modelview and draws a random triangle (with random unit normals) under
another; vgxsim's coordinates (float64, vgxsim/geometry/texgen.py, the plane taken
through vgxsim.gl's texgen) and Mesa's (float32 transforms, read back by
glFeedbackBuffer) agree to float32 rounding: measured max difference 5.3e-7 relative
to the coordinates' size; the test allows 1e-5.
"""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim import GL
from vgxsim.geometry.texgen import eye_texture_coords, texture_coords
from vgxsim.gl import loadmatrix, mmode
from vgxsim.gl._core import session
from vgxsim.gl._texture import tevbind, tevdef, texbind, texdef2d, texgen
from vgxsim.pipeline.context import Context
from vgxsim.reference import mesa
from vgxsim.reference.mesa_texture import texgen_feedback
from vgxsim.state.textures import binding

if not mesa.mesa_available():
    pytest.skip("OSMesa + PyOpenGL not available", allow_module_level=True)

pytestmark = pytest.mark.mesa

TOKENS = {"linear": GL.TG_LINEAR, "contour": GL.TG_CONTOUR, "spheremap": GL.TG_SPHEREMAP}


def _rigid(rng) -> np.ndarray:
    """A random rotation, uniform scale and translation (row vectors)."""
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    m = np.eye(4)
    m[:3, :3] = q * rng.uniform(0.5, 2.0)
    m[3, :3] = rng.uniform(-3, 3, 3) + (0.0, 0.0, -8.0)
    return m


@pytest.fixture(scope="module")
def peer():
    p = mesa.MesaPeer(8, 8)
    yield p
    p.close()
    session.reset()


@pytest.mark.parametrize("modes", [("linear", "linear"), ("contour", "contour"),
                                   ("spheremap", "spheremap"), ("contour", "linear"),
                                   ("spheremap", "contour")])
@pytest.mark.parametrize("seed", range(4))
def test_generated_coordinates_match_mesa(peer, modes, seed):
    rng = np.random.default_rng(seed * 10 + len(modes[0]))
    m0, m1 = _rigid(rng), _rigid(rng)
    planes = [tuple(rng.uniform(-1, 1, 4)) for _ in range(2)]
    obj = rng.uniform(-1, 1, (3, 3))
    normals = rng.normal(size=(3, 3))
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    ctx = Context(8, 8)
    session.reset()
    session.windows[1] = ctx
    session.current = 1
    mmode(GL.MVIEWING)
    loadmatrix(m0.reshape(-1).tolist())
    texdef2d(1, 4, 1, 1, np.zeros((1, 1, 4), np.uint8), 1, (GL.TX_NULL,))
    tevdef(1, 1, (GL.TV_NULL,))
    texbind(GL.TX_TEXTURE_0, 1)
    tevbind(GL.TV_ENV0, 1)
    for coord, mode, plane in zip((GL.TX_S, GL.TX_T), modes, planes, strict=True):
        texgen(coord, TOKENS[mode], plane if mode != "spheremap" else None)
        texgen(coord, GL.TG_ON, None)
    loadmatrix(m1.reshape(-1).tolist())
    rs = ctx.raster.snapshot()
    gen = binding(rs.texture).texgen
    st = eye_texture_coords(gen, obj, ctx.matrices.modelview_matrix(),
                            ctx.matrices.normal_matrix(), normals)
    got = texture_coords(rs, obj, st)
    want = texgen_feedback(peer, modes, planes, m0, m1, obj, normals)
    scale = max(1.0, float(np.abs(want).max()))
    assert np.abs(got - want).max() <= 1e-5 * scale, (got, want)

