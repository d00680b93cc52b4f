"""OpenGL conformance of vgxsim (issue 3): the same scenes through vgxsim and Mesa.

Each scene is a list of window-space commands in the format of
:mod:`vgxsim.reference.naive` (``("triangle", verts, state)`` and ``("clear", planes,
values, state)``).  vgxsim renders it with :class:`vgxsim.batch.CommandBatch` on a
:class:`vgxsim.state.planes.Framebuffer`; Mesa's llvmpipe renders it through
:class:`vgxsim.reference.mesa.MesaPeer` (which maps IRIS pixel centres to GL's).
The two must agree:

* stencil planes: identical;
* depth-test outcomes: identical.  llvmpipe interpolates z in float32, so the
  stored z of a sloped triangle may differ from ours by a few tens of units; the
  scenes therefore keep every sloped triangle's z inside a band of its own, far
  from every other depth in the scene, so that no depth comparison depends on that
  rounding, and constant-z triangles and clears (exact in both) sit on shared
  levels so that ZF_EQUAL has ties to find.  After the scene, probe layers
  (constant-z, ZF_LESS and ZF_EQUAL, counting in the stencil) turn the final depth
  buffer into stencil values that must be identical; the raw depth is also
  compared, with a tolerance;
* colour: within one level per channel (Gouraud interpolation and blending round
  differently in llvmpipe).  Inputs that would magnify a one-level difference are
  kept exact: the logic op and the alpha test only see constant colour / alpha
  (which both renderers reproduce exactly), and vertex colours are multiples of
  1/255.

States cover zbuffer on/off with every ZF_*, stencil with every SF_* and every ST_*
for fail/pass/zpass (and the IRIS ``pass`` rule with the z-buffer off), stencil
masks and write masks, every blend factor pair GL can express, every logic op, the
alpha test, culling, flat and Gouraud shading, colour and z write masks (whole bytes
only: see :func:`vgxsim.reference.mesa.mesa_caveats`) and scissor rectangles.

Pixel-centre ties: with ``subpixel(FALSE)`` every vertex is a pixel centre, so
edges through pixel centres are everywhere; llvmpipe's tie rule is the numeric
model's (left and horizontal bottom edges own their centres), so scenes with ties
are compared as strictly as scenes without (the ``no_ties`` variant rejects any
triangle with a pixel centre exactly on an edge line).
"""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim.batch import CLEAR_COLOUR, CLEAR_STENCIL, CLEAR_Z, CommandBatch
from vgxsim.reference import mesa
from vgxsim.state.planes import Framebuffer, PlaneConfig
from vgxsim.state.raster import (
    BF_MIN_SA_MDA,
    CMP_ALWAYS,
    CMP_EQUAL,
    CMP_LEQUAL,
    CMP_LESS,
    CULL_NONE,
    FLAT,
    GOURAUD,
    OP_DECR,
    OP_INCR,
    OP_KEEP,
    OP_REPLACE,
    RasterState,
)

if not mesa.mesa_available():
    pytest.skip("OSMesa + PyOpenGL not available", allow_module_level=True)

pytestmark = pytest.mark.mesa

W, H = 40, 32
FULL = (0, W - 1, 0, H - 1)
GD_ZMIN, GD_ZMAX = -0x800000, 0x7FFFFF
PLANE_BITS = {"color": CLEAR_COLOUR, "z": CLEAR_Z, "stencil": CLEAR_STENCIL}
ALL_PLANES = ("color", "z", "stencil")
BAND_STEP = 0x20000  # spacing of the private z bands of sloped triangles
BAND_HALF = 0x8000  # half-width of one band: bands are 0x10000 apart at least
CLEAR_OFFSET = 0xD0000  # scissored z clears: above every band, below the next level
Z_TOLERANCE = 64  # llvmpipe's float32 z interpolation error (seen up to ~30)
MYZERO = 128  # Heidmann 1991: the stencil "zero"


# ---------------------------------------------------------------- rendering


def render_vgxsim(commands, w=W, h=H):
    """Render commands with vgxsim's CommandBatch.

    Parameters
    ----------
    commands : list of tuple
        Naive-format triangle and clear commands.
    w, h : int
        Window size.

    Returns
    -------
    tuple of ndarray
        Colour (uint32 0xAABBGGRR), z (int32) and stencil (uint8), row 0 at the bottom.
    """
    fb = Framebuffer(PlaneConfig(w, h, double=False, zbits=24, stencil=8))
    batch = CommandBatch(fb)
    for cmd in commands:
        if cmd[0] == "clear":
            _, planes, values, rs = cmd
            bits = sum(PLANE_BITS[p] for p in planes)
            batch.add_clear(bits, values.get("color", 0), values.get("z", GD_ZMAX),
                            values.get("stencil", 0), rs)
        else:
            _, verts, rs = cmd
            xyz = np.array([v[:3] for v in verts], np.float64)
            col = np.array([v[3] for v in verts], np.float64)
            batch.add_window_triangles(xyz[:, 0], xyz[:, 1], xyz[:, 2], col,
                                       np.array([[0, 1, 2]]), rs, flat_col=col[2:3])
    batch.flush()
    return fb.front.copy(), fb.z.copy(), fb.stencil.copy()


def render_mesa(peer, commands):
    """Render commands on a MesaPeer and read back colour, IRIS z and stencil."""
    peer.render(commands)
    return peer.color(), peer.depth_iris(), peer.stencil()


def channel_diff(a, b):
    """Largest per-channel difference of packed colours, per pixel (int array)."""
    ca = a.view(np.uint8).reshape(a.shape + (4,)).astype(np.int16)
    cb = b.view(np.uint8).reshape(b.shape + (4,)).astype(np.int16)
    return np.abs(ca - cb).max(axis=-1)


@pytest.fixture(scope="module")
def peer():
    p = mesa.MesaPeer(W, H)
    yield p
    p.close()


# ---------------------------------------------------------------- scene generator


def clear_cmd(rs, color=0, z=GD_ZMAX, stencil=0, planes=ALL_PLANES):
    return ("clear", set(planes), {"color": color, "z": z, "stencil": stencil}, rs)


def on_edge_somewhere(pts):
    """Whether a pixel centre of the window lies exactly on an edge line of a triangle.

    Parameters
    ----------
    pts : ndarray, shape (3, 2)
        Vertices in window units, multiples of 1/256.

    Returns
    -------
    bool
    """
    f = np.round(np.asarray(pts) * 256).astype(np.int64)
    ys, xs = np.mgrid[0:H, 0:W]
    for i in range(3):
        (xi, yi), (xj, yj) = f[i], f[(i + 1) % 3]
        e = (xj - xi) * (ys * 256 - yi) - (yj - yi) * (xs * 256 - xi)
        if (e == 0).any():
            return True
    return False


class SceneMaker:
    """Random scenes whose depth comparisons never hinge on z rounding.

    Parameters
    ----------
    rng : numpy.random.Generator
    variant : {'pixel_centres', 'subpixel_ties', 'no_ties'}
        ``subpixel(FALSE)`` (vertices snap to pixel centres), ``subpixel(TRUE)`` with
        vertices on the half-pixel grid (edges through pixel centres are common), or
        ``subpixel(TRUE)`` with no pixel centre on any edge line.
    """

    def __init__(self, rng, variant):
        self.rng = rng
        self.variant = variant
        self.subpixel = variant != "pixel_centres"
        # Shared levels: clears and constant-z triangles (exact in both renderers).
        self.levels = [int(v) for v in sorted(rng.choice(np.arange(-6, 7), 5, replace=False)
                                              * 0x100000 + rng.integers(-999, 1000, 5))]
        self.next_band = 0

    def level(self):
        return int(self.rng.choice(self.levels))

    def sloped_z(self):
        """Three vertex z values inside a band no other depth in the scene reaches."""
        self.next_band += 1
        base = self.levels[self.next_band % len(self.levels)]
        centre = base + BAND_STEP * (1 + self.next_band // len(self.levels))
        assert BAND_STEP * (1 + self.next_band // len(self.levels)) + BAND_HALF < CLEAR_OFFSET
        return centre + self.rng.integers(-BAND_HALF, BAND_HALF + 1, 3)

    def vertices(self):
        rng = self.rng
        while True:
            lo, hi = np.array([-6.0, -6.0]), np.array([W + 6.0, H + 6.0])
            if rng.random() < 0.4:  # a small triangle
                c = rng.uniform(0, [W, H])
                pts = c + rng.uniform(-5, 5, (3, 2))
            else:
                pts = rng.uniform(lo, hi, (3, 2))
            if self.variant == "subpixel_ties":
                pts = np.round(pts * 2) / 2
            elif self.variant == "no_ties":
                pts = np.floor(pts * 256 + 0.5) / 256
                if on_edge_somewhere(pts):
                    continue
            return pts

    def colour(self):
        return self.rng.integers(0, 256, 4) / 255.0

    def state(self, kind):
        """A random RasterState for a triangle of the given colour kind.

        Parameters
        ----------
        kind : {'exact', 'single', 'gouraud_blend'}
            ``'exact'``: colour results are exact in both renderers (logic ops, or
            blend factors ZERO/ONE only; the triangle's colour will be constant).
            ``'single'``: any blend factor pair GL can express (the colour will be
            constant, or Gouraud under a ZERO/ONE blend): one rounding step, within
            one level.  ``'gouraud_blend'``: Gouraud colour under any blend factors.

        Returns
        -------
        tuple
            ``(state, constant_colour)``: whether the triangle's colour must be the
            same at its three vertices (Gouraud colour that a blend would scale).
        """
        rng = self.rng
        kw = dict(subpixel=self.subpixel, scissor=FULL)
        kw["zbuffer"] = bool(rng.random() < 0.7)
        kw["zfunc"] = int(rng.integers(8))
        kw["zwritemask"] = int(rng.choice([0, 0xFFFFFFFF, 0xFFFFFF, 0xFF000000]))
        kw["stencil"] = bool(rng.random() < 0.8)
        kw["sref"] = int(rng.integers(256))
        kw["sfunc"] = int(rng.integers(8))
        kw["smask"] = int(rng.choice([0xFF, rng.integers(256)]))
        kw["sfail"], kw["spass"], kw["szpass"] = (int(v) for v in rng.integers(0, 6, 3))
        kw["swritemask"] = int(rng.choice([0xFF, rng.integers(256)]))
        if kind == "exact" and rng.random() < 0.5:
            kw["logicop"] = int(rng.integers(16))
        elif kind == "exact":
            kw["blend_sf"], kw["blend_df"] = (int(v) for v in rng.integers(0, 2, 2))
        else:
            kw["blend_sf"] = int(rng.integers(BF_MIN_SA_MDA + 1))
            kw["blend_df"] = int(rng.integers(BF_MIN_SA_MDA))
        trivial_blend = kw.get("blend_sf", 1) <= 1 and kw.get("blend_df", 0) <= 1
        kw["shademodel"] = FLAT if rng.random() < 0.3 else GOURAUD
        # Flat colour (the last vertex's, a multiple of 1/255) is exact in both.
        constant = kw["shademodel"] == GOURAUD and (
            kind == "exact" or (kind == "single" and not trivial_blend))
        if rng.random() < 0.3:
            kw["afunc"] = int(rng.integers(7))
            kw["aref"] = int(rng.integers(256))
        kw["wmpack"] = int(sum(0xFF << (8 * i) for i in range(4) if rng.random() < 0.85))
        kw["cull"] = int(rng.integers(4)) if rng.random() < 0.3 else CULL_NONE
        if rng.random() < 0.3:
            x0, x1 = sorted(int(v) for v in rng.integers(0, W, 2))
            y0, y1 = sorted(int(v) for v in rng.integers(0, H, 2))
            kw["scissor"] = (x0, x1, y0, y1)
        rs = RasterState(**kw)
        assert mesa.mesa_caveats(rs) == [], mesa.mesa_caveats(rs)
        return rs, constant

    def triangle(self, kind="exact"):
        """A random triangle command (see :meth:`state` for ``kind``).

        Vertex colours are multiples of 1/255.  Under the alpha test the three
        vertices share one alpha, so that the test compares an exact value.
        """
        rs, constant = self.state(kind)
        rng = self.rng
        pts = self.vertices()
        zs = [self.level()] * 3 if rng.random() < 0.5 else self.sloped_z()
        if constant or (rs.shademodel != FLAT and rng.random() < 0.2):
            cols = [self.colour()] * 3
        else:
            cols = [self.colour() for _ in range(3)]
        if rs.afunc != CMP_ALWAYS:
            a = self.colour()[3]
            cols = [np.r_[c[:3], a] for c in cols]
        verts = [(float(p[0]), float(p[1]), float(z), tuple(float(v) for v in c))
                 for p, z, c in zip(pts, zs, cols, strict=True)]
        return ("triangle", verts, rs)

    def background(self):
        """A full clear, then a few scissored clears of random planes and masks.

        llvmpipe's scissored depth clear rounds the depth value differently from
        its full-window clear (one unit off for about 6% of values), so scissored
        clears write z values that nothing else in the scene uses and that lie
        between the sloped triangles' bands and the next level: no comparison
        depends on that unit.
        """
        rng = self.rng
        cmds = [clear_cmd(RasterState(scissor=FULL), int(rng.integers(1 << 32)), self.level(),
                          int(rng.integers(256)))]
        for _ in range(rng.integers(1, 4)):
            x0, x1 = sorted(int(v) for v in rng.integers(0, W, 2))
            y0, y1 = sorted(int(v) for v in rng.integers(0, H, 2))
            rs = RasterState(scissor=(x0, x1, y0, y1),
                             wmpack=int(rng.choice([0xFFFFFFFF, 0x00FF00FF])),
                             swritemask=int(rng.choice([0xFF, rng.integers(256)])),
                             zwritemask=int(rng.choice([0xFFFFFFFF, 0])))
            planes = [p for p in ALL_PLANES if rng.random() < 0.7] or ["stencil"]
            cmds.append(clear_cmd(rs, int(rng.integers(1 << 32)), self.level() + CLEAR_OFFSET,
                                  int(rng.integers(256)), planes))
        return cmds

    def scene(self, ntri):
        """Background clears and ``ntri`` triangles of the ``'exact'`` kind."""
        return self.background() + [self.triangle("exact") for _ in range(ntri)]

    def depth_probes(self):
        """Commands that turn the final depth buffer into stencil values.

        The stencil is reset to 0; then, with constant-z window-covering quads that
        write neither z nor colour, bits 0-2 count the levels ``L`` with ``L < z``
        (ZF_LESS, ST_INCR through write mask 0x07) and bit ``3 + k`` is set where
        ``z == L_k`` (ZF_EQUAL, ST_REPLACE of 0xFF through write mask ``1 << (3 + k)``).
        Sloped triangles' bands lie strictly between levels, so the result must be
        identical in both renderers.
        """
        cmds = [clear_cmd(RasterState(scissor=FULL), planes=["stencil"])]
        quad = [(-3.0, -3.0), (W + 3.0, -3.0), (W + 3.0, H + 3.0), (-3.0, H + 3.0)]
        base = dict(scissor=FULL, zbuffer=True, zwritemask=0, wmpack=0, stencil=True,
                    sfunc=CMP_ALWAYS, subpixel=self.subpixel)
        for k, lvl in enumerate(self.levels):
            less = RasterState(**base, zfunc=CMP_LESS, szpass=OP_INCR, swritemask=0x07)
            equal = RasterState(**base, zfunc=CMP_EQUAL, szpass=OP_REPLACE, sref=0xFF,
                                swritemask=1 << (3 + k))
            for rs in (less, equal):
                for tri in ((0, 1, 2), (0, 2, 3)):
                    verts = [(*quad[i], float(lvl), (1.0, 1.0, 1.0, 1.0)) for i in tri]
                    cmds.append(("triangle", verts, rs))
        return cmds


# ---------------------------------------------------------------- random scenes

VARIANTS = ["pixel_centres", "subpixel_ties", "no_ties"]


def compare_scene(peer, cmds, colour_tolerance):
    """Render ``cmds`` in both; check stencil, colour and raw depth; return the
    vgxsim planes."""
    ours = render_vgxsim(cmds)
    gl = render_mesa(peer, cmds)
    stencil_diff = int((ours[2] != gl[2]).sum())
    assert stencil_diff == 0, f"{stencil_diff} stencil pixels differ"
    cdiff = channel_diff(ours[0], gl[0])
    assert cdiff.max() <= colour_tolerance, (
        f"{int((cdiff > colour_tolerance).sum())} pixels differ by more than "
        f"{colour_tolerance} (max {int(cdiff.max())})")
    zdiff = np.abs(ours[1].astype(np.int64) - gl[1])
    assert zdiff.max() <= Z_TOLERANCE
    return ours


@pytest.mark.parametrize("variant", VARIANTS)
@pytest.mark.parametrize("seed", range(12))
def test_random_scene_matches_mesa(peer, variant, seed):
    rng = np.random.default_rng(1000 * seed + VARIANTS.index(variant))
    maker = SceneMaker(rng, variant)
    # A scene of 30 triangles whose colour operations are exact in both renderers.
    cmds = maker.scene(30)
    compare_scene(peer, cmds, colour_tolerance=0)
    # Depth outcome: probe the final depth buffers; the counts must be identical.
    probes = maker.depth_probes()
    ours_p = render_vgxsim(cmds + probes)
    gl_p = render_mesa(peer, probes)  # continues on the same GL buffers
    assert (ours_p[2] == gl_p[2]).all()
    # One more triangle with any blend factors (one rounding step) on that scene,
    # several times: colour within one level.
    for _ in range(6):
        compare_scene(peer, cmds + [maker.triangle("single")], colour_tolerance=1)


@pytest.mark.parametrize("seed", range(4))
def test_gouraud_colour_under_alpha_blending_within_two_levels(peer, seed):
    # Measured, not a design goal: llvmpipe's Gouraud colour is sometimes one level
    # off ours, and a blend whose factors use the source alpha (BF_SA, BF_MSA, ...)
    # then counts that level twice (as colour and as factor).
    rng = np.random.default_rng(77 + seed)
    maker = SceneMaker(rng, VARIANTS[seed % 3])
    cmds = maker.scene(20)
    for _ in range(6):
        compare_scene(peer, cmds + [maker.triangle("gouraud_blend")], colour_tolerance=2)


def test_random_scenes_cover_every_state_value():
    # The generator must reach every value the module docstring promises.
    seen = {k: set() for k in ("zfunc", "sfunc", "sfail", "spass", "szpass", "blend_sf",
                               "blend_df", "logicop", "afunc", "cull", "shademodel")}
    flags = set()
    for variant in VARIANTS:
        for seed in range(12):
            maker = SceneMaker(np.random.default_rng(1000 * seed + VARIANTS.index(variant)),
                               variant)
            for cmd in maker.scene(40):
                if cmd[0] != "triangle":
                    continue
                rs = cmd[2]
                for k in seen:
                    seen[k].add(getattr(rs, k))
                flags.add(("zbuffer", rs.zbuffer))
                flags.add(("stencil_off_pass", rs.stencil and not rs.zbuffer))
                flags.add(("scissor", rs.scissor != FULL))
                flags.add(("zwritemask", rs.zwritemask & 0xFFFFFF == 0))
                flags.add(("smask", rs.smask != 0xFF))
                flags.add(("swritemask", rs.swritemask != 0xFF))
                flags.add(("wmpack", rs.wmpack != 0xFFFFFFFF))
    for k in ("zfunc", "sfunc", "afunc"):
        assert seen[k] >= set(range(7)), k  # afunc 7 is "no test", the default
    for k in ("sfail", "spass", "szpass"):
        assert seen[k] == set(range(6)), k
    assert seen["blend_sf"] == set(range(9)) and seen["blend_df"] == set(range(8))
    assert seen["logicop"] == set(range(16))
    assert seen["cull"] == {0, 1, 2, 3} and seen["shademodel"] == {FLAT, GOURAUD}
    for name in ("zbuffer", "stencil_off_pass", "scissor", "zwritemask", "smask",
                 "swritemask", "wmpack"):
        assert {(name, True), (name, False)} <= flags, name


def test_zbuffer_off_pass_rule_and_every_stencil_op(peer):
    # Deterministic coverage of the IRIS rule: with zbuffer(FALSE) a fragment passing
    # the stencil test takes `pass`, never `zpass`; every op on every starting value.
    cmds = [clear_cmd(RasterState(scissor=FULL))]
    starts = [0, 1, 2, 127, 128, 254, 255]
    for k, s0 in enumerate(starts):
        band = RasterState(scissor=(0, W - 1, 4 * k, 4 * k + 3))
        cmds.append(clear_cmd(band, stencil=s0, planes=["stencil"]))
    for op in range(6):
        cols = (6 * op, 6 * op + 5)
        for zbuf, zfunc in ((False, CMP_ALWAYS), (True, CMP_ALWAYS), (True, 0)):
            rs = RasterState(scissor=(cols[0], cols[1], 0, H - 1), stencil=True, sref=0xA5,
                             sfunc=CMP_ALWAYS, sfail=OP_KEEP, spass=op,
                             szpass=(op + 1) % 6, zbuffer=zbuf, zfunc=zfunc, zwritemask=0)
            cmds.append(("triangle", [(-2.0, -2.0, 0.0, (1.0,) * 4), (W + 2.0, -2.0, 0.0,
                                                                       (1.0,) * 4),
                                      (-2.0, H + 2.0, 0.0, (1.0,) * 4)], rs))
            cmds.append(("triangle", [(W + 2.0, -2.0, 0.0, (1.0,) * 4),
                                      (W + 2.0, H + 2.0, 0.0, (1.0,) * 4),
                                      (-2.0, H + 2.0, 0.0, (1.0,) * 4)], rs))
    ours = render_vgxsim(cmds)[2]
    gl = render_mesa(peer, cmds)[2]
    assert (ours == gl).all()
    # Independent expectation for the zbuffer(FALSE) pass-rule column set: three draws
    # per op, first with `pass` (z off), then zpass=(op+1) (z on, passes), then
    # `pass` again (z on, ZF_NEVER fails).
    table = {0: lambda s: s, 1: lambda s: 0, 2: lambda s: 0xA5, 3: lambda s: min(s + 1, 255),
             4: lambda s: max(s - 1, 0), 5: lambda s: ~s & 0xFF}
    for op in range(6):
        for k, s0 in enumerate(starts):
            want = table[op](table[(op + 1) % 6](table[op](s0)))
            assert (gl[4 * k:4 * k + 4, 6 * op:6 * op + 6] == want).all(), (op, s0)


# ---------------------------------------------------------------- shadow volume


def perspective_window(points, w, h):
    """Project camera-space points (camera at the origin looking down -z) to IRIS
    window coordinates with a 50-degree perspective and near 1, far 40.

    Parameters
    ----------
    points : ndarray, shape (N, 3)
    w, h : int

    Returns
    -------
    ndarray, shape (N, 3)
        ``xw``, ``yw`` (pixel centres at integers) and ``zw`` in 24-bit units.
    """
    near, far = 1.0, 40.0
    f = 1.0 / np.tan(np.radians(25.0))
    p = np.asarray(points, np.float64)
    wc = -p[:, 2]  # clip w
    x = f * (h / w) * p[:, 0] / wc
    y = f * p[:, 1] / wc
    z = ((far + near) / (near - far) * p[:, 2] + 2 * far * near / (near - far)) / wc
    xw = -0.5 + (x + 1) * w / 2
    yw = -0.5 + (y + 1) * h / 2
    zw = GD_ZMIN + (z + 1) * (GD_ZMAX - GD_ZMIN) / 2
    return np.stack([xw, yw, zw], axis=1)


def box(lo, hi):
    """Corners and outward-wound quads (counter-clockwise seen from outside) of a box."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    c = np.array([[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
                  [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]], np.float64)
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5),
             (0, 4, 7, 3)]
    return c, quads


def frustum_volume(top, light, length):
    """Closed shadow volume of a horizontal quad ``top`` (4 x 3, counter-clockwise
    seen from above) lit by a point ``light``: the quad, its extrusion ``length``
    away from the light, and four sides; quads wound outward."""
    top = np.asarray(top, np.float64)
    d = top - np.asarray(light, np.float64)
    bottom = top + length * d / np.linalg.norm(d, axis=1, keepdims=True)
    c = np.concatenate([top, bottom])
    quads = [(0, 1, 2, 3), (7, 6, 5, 4), (0, 4, 5, 1), (1, 5, 6, 2), (2, 6, 7, 3),
             (3, 7, 4, 0)]
    return c, quads


def window_quads(corners, quads, w, h, colour):
    """Triangles (two per quad) in window coordinates, and each quad's facing."""
    win = perspective_window(corners, w, h)
    out, facing = [], []
    for q in quads:
        p = win[list(q)]
        area = 0.0
        for i in range(4):
            j = (i + 1) % 4
            area += p[i, 0] * p[j, 1] - p[j, 0] * p[i, 1]
        facing.append(area > 0)
        for a, b, c in ((0, 1, 2), (0, 2, 3)):
            out.append([(float(p[k, 0]), float(p[k, 1]), float(p[k, 2]), colour)
                        for k in (a, b, c)])
    return out, facing


def test_heidmann_shadow_volume_stencil_matches_mesa():
    w, h = 96, 80
    full = (0, w - 1, 0, h - 1)
    grey = (0.5, 0.5, 0.5, 1.0)
    # Receivers: a floor, a back wall and a block, seen in perspective (sloped z).
    floor = (np.array([[-6, -2, -4], [6, -2, -4], [6, -2, -22], [-6, -2, -22]]), [(0, 1, 2, 3)])
    wall = (np.array([[-6, -2, -22], [6, -2, -22], [6, 6, -22], [-6, 6, -22]]), [(0, 1, 2, 3)])
    block = box((1.0, -2.0, -13.0), (3.0, 0.5, -10.0))
    draw = RasterState(scissor=full, zbuffer=True, zfunc=CMP_LEQUAL)
    cmds = [clear_cmd(RasterState(scissor=full), 0, GD_ZMAX, 0)]
    receivers = []
    for corners, quads in (floor, wall, block):
        tris, _ = window_quads(corners, quads, w, h, grey)
        receivers += [("triangle", t, draw) for t in tris]
    cmds += receivers
    # Heidmann's pass: stencil "zero" 128, no z or colour writes, front faces INCR,
    # back faces DECR (z test ZF_LEQUAL, as the 1991 code leaves it).
    cmds.append(clear_cmd(RasterState(scissor=full), stencil=MYZERO, planes=["stencil"]))
    light = np.array([-4.0, 8.0, -6.0])
    volumes = [frustum_volume([[-2, 2, -12], [0, 2, -12], [0, 2, -14], [-2, 2, -14]],
                              light, 40.0),
               frustum_volume([[-1, 3, -15], [2, 3, -15], [2, 3, -16.5], [-1, 3, -16.5]],
                              light, 40.0)]
    vol_cmds = []
    for corners, quads in volumes:
        tris, facing = window_quads(corners, quads, w, h, grey)
        for k, t in enumerate(tris):
            ingoing = facing[k // 2]
            rs = RasterState(scissor=full, zbuffer=True, zfunc=CMP_LEQUAL, zwritemask=0,
                             wmpack=0, stencil=True, sref=0, sfunc=CMP_ALWAYS, smask=0xFF,
                             sfail=OP_KEEP, spass=OP_KEEP,
                             szpass=OP_INCR if ingoing else OP_DECR)
            vol_cmds.append(("triangle", t, rs))
    cmds += vol_cmds
    ours = render_vgxsim(cmds, w, h)
    p = mesa.MesaPeer(w, h)
    try:
        gl = render_mesa(p, cmds)
    finally:
        p.close()
    # Pixels where a volume face and the visible surface are within the z rounding
    # of llvmpipe could legitimately flip; find them with vgxsim's own z and require
    # there to be none, so that the exact comparison below is a fair one.
    recv_z = ours[1].astype(np.int64)
    near_tie = np.zeros((h, w), bool)
    for _, t, _rs in vol_cmds:
        probe = RasterState(scissor=full, zbuffer=True, zfunc=CMP_ALWAYS, stencil=True,
                            sfunc=CMP_ALWAYS, szpass=OP_INCR)
        _, fz, fs = render_vgxsim([clear_cmd(RasterState(scissor=full)),
                                   ("triangle", t, probe)], w, h)
        near_tie |= (fs > 0) & (np.abs(fz.astype(np.int64) - recv_z) <= 2 * Z_TOLERANCE)
    assert not near_tie.any(), int(near_tie.sum())
    st = ours[2]
    assert (st == gl[2]).all(), int((st != gl[2]).sum())
    # The volumes do shadow something and every pixel is inside 0, 1 or 2 volumes.
    assert set(np.unique(st)) <= {MYZERO, MYZERO + 1, MYZERO + 2}
    assert (st == MYZERO + 1).sum() > 100 and (st == MYZERO).sum() > 100
    # Colour and depth of the receivers also agree (no volume writes either).
    assert channel_diff(ours[0], gl[0]).max() <= 1
    assert np.abs(ours[1].astype(np.int64) - gl[1]).max() <= Z_TOLERANCE


# ---------------------------------------------------------------- sanity of the helpers


def test_channel_diff_and_edge_finder():
    a = np.array([[0x01020304, 0xFF000000]], np.uint32)
    b = np.array([[0x01020305, 0x00000000]], np.uint32)
    assert channel_diff(a, b).tolist() == [[1, 255]]
    # A vertex on a pixel centre is on two edge lines; the same triangle moved by a
    # quarter pixel in x and y puts no centre on any edge line (slopes 1/20 and 20).
    tri = np.array([[0.0, 0.0], [20.0, 1.0], [1.0, 20.0]])
    assert on_edge_somewhere(tri)
    assert not on_edge_somewhere(tri + 0.25)
