"""Hand-computed checks of the naive reference pipeline (docs/numeric_model.md).

Every expected value below was worked out by hand from the model's formulas; the
arithmetic is written next to the less obvious ones.
"""

import itertools
import random

import numpy as np
import pytest

from vgxsim.reference.naive import (
    AC_ACCUMULATE,
    AC_ADD,
    AC_CLEAR,
    AC_CLEAR_ACCUMULATE,
    AC_MULT,
    AC_RETURN,
    GD_ZMAX,
    NaiveFramebuffer,
    accum,
    covered_pixels,
    render,
    snap,
)
from vgxsim.state.raster import (
    BF_DA,
    BF_DC,
    BF_MDA,
    BF_MDC,
    BF_MIN_SA_MDA,
    BF_MSA,
    BF_ONE,
    BF_SA,
    BF_ZERO,
    CMP_ALWAYS,
    CMP_EQUAL,
    CMP_GEQUAL,
    CMP_GREATER,
    CMP_LEQUAL,
    CMP_LESS,
    CMP_NEVER,
    CMP_NOTEQUAL,
    CULL_BACK,
    CULL_FRONT,
    FLAT,
    OP_DECR,
    OP_INCR,
    OP_INVERT,
    OP_KEEP,
    OP_REPLACE,
    OP_ZERO,
    RasterState,
)

WHITE = (1.0, 1.0, 1.0, 1.0)
WHITE_PACKED = 0xFFFFFFFF

# Pass pattern of "lhs FUNC rhs" for lhs > rhs, lhs == rhs, lhs < rhs.
FUNC_TABLE = {
    CMP_NEVER: (False, False, False),
    CMP_LESS: (False, False, True),
    CMP_EQUAL: (False, True, False),
    CMP_LEQUAL: (False, True, True),
    CMP_GREATER: (True, False, False),
    CMP_NOTEQUAL: (True, False, True),
    CMP_GEQUAL: (True, True, False),
    CMP_ALWAYS: (True, True, True),
}


def st(fb, **kw):
    """RasterState with the scissor set to the whole framebuffer."""
    kw.setdefault("scissor", (0, fb.width - 1, 0, fb.height - 1))
    return RasterState(**kw)


def tri(p0, p1, p2, z=(0.0, 0.0, 0.0), colors=(WHITE, WHITE, WHITE)):
    return tuple((p[0], p[1], zz, c) for p, zz, c in zip((p0, p1, p2), z, colors, strict=True))


def written(plane, value=0):
    """Set of (X, Y) where ``plane`` differs from ``value``."""
    ys, xs = np.nonzero(plane != value)
    return {(int(x), int(y)) for x, y in zip(xs, ys, strict=True)}


def c255(*ints):
    """Float colour whose components round back to the given 0..255 ints."""
    return tuple(i / 255 for i in ints)


# ------------------------------------------------------------------ framebuffer


def test_framebuffer_planes():
    fb = NaiveFramebuffer(5, 3)
    assert fb.front.shape == (3, 5) and fb.front.dtype == np.uint32
    assert fb.back.shape == (3, 5) and fb.back.dtype == np.uint32
    assert fb.z.dtype == np.int32 and (fb.z == 0x7FFFFF).all()
    assert fb.stencil.dtype == np.uint8 and not fb.stencil.any()
    assert not fb.front.any() and not fb.back.any()
    fb1 = NaiveFramebuffer(2, 2, stencil_planes=0, double=False)
    assert fb1.stencil is None and fb1.back is None


# --------------------------------------------------------------------- snapping


def test_snap():
    # subpixel FALSE: floor(x + 0.5) * 256, ties upward.
    assert snap(0.3, 3.4, False) == (0, 768)
    assert snap(-0.5, 0.5, False) == (0, 256)
    assert snap(-0.51, 1.49, False) == (-256, 256)
    # subpixel TRUE: floor(x*256 + 0.5): 0.3*256 = 76.8 -> 77, 3.4*256 = 870.4 -> 870.
    assert snap(0.3, 3.4, True) == (77, 870)
    assert snap(-0.5, 1.0, True) == (-128, 256)


# --------------------------------------------------------------------- coverage

# Right triangle (0,0) (4,0) (0,4): bottom edge inclusive (Y >= 0), left edge
# inclusive (X >= 0), hypotenuse 262144*(4 - X - Y) > 0 exclusive (X + Y <= 3).
RIGHT_TRI = {
    (0, 0), (1, 0), (2, 0), (3, 0),
    (0, 1), (1, 1), (2, 1),
    (0, 2), (1, 2),
    (0, 3),
}  # fmt: skip


def test_right_triangle_coverage():
    pts = [(0, 0), (1024, 0), (0, 1024)]
    assert set(covered_pixels(pts)) == RIGHT_TRI
    assert len(covered_pixels(pts)) == 10
    # Clockwise order covers the same pixels.
    assert set(covered_pixels(pts[::-1])) == RIGHT_TRI


def test_right_triangle_render_and_scissor():
    fb = NaiveFramebuffer(6, 6)
    render(fb, [("triangle", tri((0, 0), (4, 0), (0, 4)), st(fb))])
    assert written(fb.back) == RIGHT_TRI
    assert (fb.back[fb.back != 0] == WHITE_PACKED).all()
    assert not fb.front.any()
    fb = NaiveFramebuffer(6, 6)
    render(fb, [("triangle", tri((0, 0), (4, 0), (0, 4)), st(fb, scissor=(1, 2, 0, 1)))])
    assert written(fb.back) == {(1, 0), (2, 0), (1, 1), (2, 1)}


def test_tie_rule_vertices_on_pixel_centres():
    # (1,1) (3,1) (1,3): the vertex (1,1) is owned, (3,1) and (1,3) are not, nor
    # the hypotenuse centre (2,2).
    pts = [(256, 256), (768, 256), (256, 768)]
    assert set(covered_pixels(pts)) == {(1, 1), (2, 1), (1, 2)}
    # The mirror image (3,1) (3,3) (1,3): the right edge (going up) and the top
    # edge (going left) are exclusive, the hypotenuse (1,3)->(3,1) (going down) is
    # inclusive: X < 3, Y < 3, X + Y >= 4 -> only (2,2).
    pts = [(768, 256), (768, 768), (256, 768)]
    assert set(covered_pixels(pts)) == {(2, 2)}
    # Zero area covers nothing.
    assert covered_pixels([(0, 0), (256, 256), (512, 512)]) == []


def test_shared_diagonal_covers_square_once():
    # T1 covers 0 <= Y <= X <= 3, T2 covers 0 <= X < Y <= 3.
    fb = NaiveFramebuffer(6, 6)
    s = st(fb, stencil=True, sfunc=CMP_ALWAYS, spass=OP_INCR, wmpack=0)
    render(
        fb,
        [
            ("triangle", tri((0, 0), (4, 0), (4, 4)), s),
            ("triangle", tri((0, 0), (4, 4), (0, 4)), s),
        ],
    )
    expected = np.zeros((6, 6), dtype=np.uint8)
    expected[0:4, 0:4] = 1
    np.testing.assert_array_equal(fb.stencil, expected)


def test_fan_is_watertight_property():
    # Not hand-computed: a subpixel fan around a centre covers no pixel twice, and
    # the union of the fan is the same as the union of its two halves' hulls.
    rng = random.Random(1234)
    fb = NaiveFramebuffer(24, 24)
    s = st(fb, stencil=True, spass=OP_INCR, wmpack=0, subpixel=True)
    cx, cy = 11.37, 12.11
    ring = []
    for k in range(9):
        ang = 2 * np.pi * k / 9 + rng.uniform(-0.2, 0.2)
        r = rng.uniform(6, 10)
        ring.append((cx + r * np.cos(ang), cy + r * np.sin(ang)))
    cmds = []
    for k in range(9):
        cmds.append(("triangle", tri((cx, cy), ring[k], ring[(k + 1) % 9]), s))
    render(fb, cmds)
    assert fb.stencil.max() == 1
    assert fb.stencil.sum() > 100


def test_subpixel_true_vs_false():
    verts = tri((0.3, 0.3), (3.4, 0.3), (0.3, 3.4))
    # FALSE: snaps to (0,0) (3,0) (0,3) -> X, Y >= 0, X + Y <= 2.
    fb = NaiveFramebuffer(5, 5)
    render(fb, [("triangle", verts, st(fb, subpixel=False))])
    assert written(fb.back) == {(0, 0), (1, 0), (2, 0), (0, 1), (1, 1), (0, 2)}
    # TRUE: (77,77) (870,77) (77,870): X*256 >= 77, Y*256 >= 77 -> X, Y >= 1;
    # hypotenuse 793*(947 - 256*(X+Y)) > 0 -> X + Y <= 3.
    fb = NaiveFramebuffer(5, 5)
    render(fb, [("triangle", verts, st(fb, subpixel=True))])
    assert written(fb.back) == {(1, 1), (2, 1), (1, 2)}


def test_culling():
    ccw = tri((0, 0), (4, 0), (0, 4))
    cw = tri((0, 0), (0, 4), (4, 0))
    for verts, cull, drawn in [
        (ccw, CULL_BACK, True),
        (cw, CULL_BACK, False),
        (ccw, CULL_FRONT, False),
        (cw, CULL_FRONT, True),
        (ccw, CULL_BACK | CULL_FRONT, False),
    ]:
        fb = NaiveFramebuffer(6, 6)
        render(fb, [("triangle", verts, st(fb, cull=cull))])
        assert (written(fb.back) == RIGHT_TRI) if drawn else not fb.back.any()


# ------------------------------------------------------------ depth and colour


def test_triangle_depth_values():
    # (0,0,z=0) (4,0,z=400) (0,4,z=800): det = 16, dadx = 1600/16 = 100,
    # dady = 3200/16 = 200, so z = 100*X + 200*Y.
    fb = NaiveFramebuffer(5, 5)
    render(
        fb,
        [
            (
                "triangle",
                tri((0, 0), (4, 0), (0, 4), z=(0.0, 400.0, 800.0)),
                st(fb, zbuffer=True, zfunc=CMP_ALWAYS),
            )
        ],
    )
    M = GD_ZMAX
    expected = np.array(
        [  # row Y = 0 first (bottom row)
            [0, 100, 200, 300, M],
            [200, 300, 400, M, M],
            [400, 500, M, M, M],
            [600, M, M, M, M],
            [M, M, M, M, M],
        ],
        dtype=np.int32,
    )
    np.testing.assert_array_equal(fb.z, expected)


def test_triangle_depth_rounding_ties_up():
    # z = 0, 1, 2: dadx = 4/16 = 0.25, dady = 8/16 = 0.5;
    # z(X,Y) = 0.25 X + 0.5 Y, floor(z + 0.5).
    fb = NaiveFramebuffer(5, 5)
    render(
        fb,
        [
            (
                "triangle",
                tri((0, 0), (4, 0), (0, 4), z=(0.0, 1.0, 2.0)),
                st(fb, zbuffer=True, zfunc=CMP_ALWAYS),
            )
        ],
    )
    M = GD_ZMAX
    expected = np.array(
        [
            [0, 0, 1, 1, M],  # 0, .25, .5, .75
            [1, 1, 1, M, M],  # .5, .75, 1.0
            [1, 1, M, M, M],  # 1.0, 1.25
            [2, M, M, M, M],  # 1.5
            [M, M, M, M, M],
        ],
        dtype=np.int32,
    )
    np.testing.assert_array_equal(fb.z, expected)


def test_gouraud_colour_and_vertex_order_independence():
    # red at (0,0), green at (4,0), blue at (0,4): at (1,1),
    # r = 255 - 63.75 - 63.75 = 127.5 -> 128, g = 63.75 -> 64, b = 63.75 -> 64.
    cols = ((1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0))
    verts = tri((0, 0), (4, 0), (0, 4), colors=cols)
    fb = NaiveFramebuffer(5, 5)
    render(fb, [("triangle", verts, st(fb))])
    assert int(fb.back[1, 1]) == 0xFF404080
    assert int(fb.back[0, 0]) == 0xFF0000FF
    # Any permutation of subpixel vertices gives identical planes.
    sv = tri(
        (0.3, 0.2),
        (7.7, 1.9),
        (2.1, 6.6),
        z=(10.3, -20.7, 33.3),
        colors=((0.9, 0.1, 0.3, 0.5), (0.2, 0.8, 0.6, 0.1), (0.4, 0.4, 0.9, 1.0)),
    )
    ref = None
    for perm in itertools.permutations(range(3)):
        fb = NaiveFramebuffer(9, 8)
        s = st(fb, subpixel=True, zbuffer=True, zfunc=CMP_ALWAYS)
        render(fb, [("triangle", tuple(sv[i] for i in perm), s)])
        if ref is None:
            ref = (fb.back.copy(), fb.z.copy())
        else:
            np.testing.assert_array_equal(fb.back, ref[0])
            np.testing.assert_array_equal(fb.z, ref[1])


def test_flat_uses_last_vertex():
    cols = (c255(1, 2, 3, 4), c255(5, 6, 7, 8), (0.5, 0.5, 0.5, 1.0))
    fb = NaiveFramebuffer(5, 5)
    render(fb, [("triangle", tri((0, 0), (4, 0), (0, 4), colors=cols), st(fb, shademodel=FLAT))])
    # 0.5*255 = 127.5 -> 128 = 0x80.
    assert set(np.unique(fb.back[fb.back != 0]).tolist()) == {0xFF808080}
    # Same positions, last vertex now colour (5,6,7,8).
    cols2 = (cols[2], cols[0], cols[1])
    fb = NaiveFramebuffer(5, 5)
    v = tri((0, 4), (0, 0), (4, 0), colors=cols2)
    render(fb, [("triangle", v, st(fb, shademodel=FLAT))])
    assert set(np.unique(fb.back[fb.back != 0]).tolist()) == {0x08070605}


# ----------------------------------------------------------------------- stencil


def _point_cmds(fb, xs, state, z=0.0, color=WHITE):
    return [("point", (x, 0, z, color), state) for x in xs]


@pytest.mark.parametrize(
    "op, planes, before, ref, after",
    [
        (OP_KEEP, 8, [5, 255], 9, [5, 255]),
        (OP_ZERO, 8, [5, 255], 9, [0, 0]),
        (OP_REPLACE, 8, [5, 255], 0x1AB, [0xAB, 0xAB]),  # ref & 0xFF
        (OP_INCR, 8, [5, 254, 255], 0, [6, 255, 255]),  # clamps at 255
        (OP_DECR, 8, [5, 1, 0], 0, [4, 0, 0]),  # clamps at 0
        (OP_INVERT, 8, [0x0F, 0, 0xA5], 0, [0xF0, 0xFF, 0x5A]),
        (OP_INCR, 4, [14, 15], 0, [15, 15]),  # smax = 15
        (OP_REPLACE, 4, [0, 3], 0x1F, [0xF, 0xF]),
        (OP_INVERT, 4, [0x3, 0xF], 0, [0xC, 0x0]),
    ],
)
def test_stencil_ops(op, planes, before, ref, after):
    fb = NaiveFramebuffer(len(before), 1, stencil_planes=planes)
    fb.stencil[0, :] = before
    s = st(fb, stencil=True, sref=ref, sfunc=CMP_ALWAYS, spass=op)
    render(fb, _point_cmds(fb, range(len(before)), s))
    assert fb.stencil[0].tolist() == after


def test_stencil_writemask():
    # (0xA0 & ~0x0F) | (0xFF & 0x0F) = 0xAF.
    fb = NaiveFramebuffer(1, 1)
    fb.stencil[0, 0] = 0xA0
    s = st(fb, stencil=True, sref=0xFF, spass=OP_REPLACE, swritemask=0x0F)
    render(fb, _point_cmds(fb, [0], s))
    assert fb.stencil[0, 0] == 0xAF


@pytest.mark.parametrize("func", sorted(FUNC_TABLE))
def test_stencil_functions(func):
    # ref 5 against stored 4, 5, 6; failing pixels take sfail = INVERT.
    fb = NaiveFramebuffer(3, 1)
    fb.stencil[0, :] = [4, 5, 6]
    s = st(fb, stencil=True, sref=5, sfunc=func, sfail=OP_INVERT)
    render(fb, _point_cmds(fb, range(3), s))
    passed = FUNC_TABLE[func]
    assert [bool(v) for v in fb.back[0]] == list(passed)
    assert fb.stencil[0].tolist() == [
        v if p else 255 - v for v, p in zip([4, 5, 6], passed, strict=True)
    ]


def test_stencil_mask():
    # (0x15 & 0x0F) == (0x25 & 0x0F) passes; (0x15 & 0xFF) != 0x25 fails.
    fb = NaiveFramebuffer(2, 1)
    fb.stencil[0, :] = [0x25, 0x25]
    render(
        fb,
        [
            ("point", (0, 0, 0.0, WHITE), st(fb, stencil=True, sref=0x15, smask=0x0F,
                                            sfunc=CMP_EQUAL)),
            ("point", (1, 0, 0.0, WHITE), st(fb, stencil=True, sref=0x15, smask=0xFF,
                                            sfunc=CMP_EQUAL)),
        ],
    )  # fmt: skip
    assert fb.back[0].tolist() == [WHITE_PACKED, 0]


def test_stencil_test_masks_ref_literally():
    # 4 planes, ref 0x15, mask 0xFF, stored 5: (0x15 & 0xFF) != (5 & 0xFF) -> fails
    # (the model masks the reference with ``mask`` only, not with smax).
    fb = NaiveFramebuffer(1, 1, stencil_planes=4)
    fb.stencil[0, 0] = 5
    s = st(fb, stencil=True, sref=0x15, smask=0xFF, sfunc=CMP_EQUAL, sfail=OP_ZERO)
    render(fb, _point_cmds(fb, [0], s))
    assert fb.back[0, 0] == 0 and fb.stencil[0, 0] == 0


def test_alpha_test_applies_with_wmpack_zero():
    # The alpha test is step 1 even when no colour is written.
    fb = NaiveFramebuffer(1, 1)
    s = st(fb, wmpack=0, afunc=CMP_NEVER, stencil=True, spass=OP_INCR)
    render(fb, _point_cmds(fb, [0], s))
    assert fb.stencil[0, 0] == 0


def test_stencil_disabled_without_planes():
    fb = NaiveFramebuffer(1, 1, stencil_planes=0)
    render(fb, _point_cmds(fb, [0], st(fb, stencil=True, sfunc=CMP_NEVER)))
    assert fb.back[0, 0] == WHITE_PACKED


@pytest.mark.parametrize("func", sorted(FUNC_TABLE))
def test_z_functions(func):
    # incoming 20 against stored 10, 20, 30.
    fb = NaiveFramebuffer(3, 1)
    fb.z[0, :] = [10, 20, 30]
    s = st(fb, zbuffer=True, zfunc=func)
    render(fb, _point_cmds(fb, range(3), s, z=20.0))
    passed = FUNC_TABLE[func]
    assert [bool(v) for v in fb.back[0]] == list(passed)
    assert fb.z[0].tolist() == [20 if p else v for v, p in zip([10, 20, 30], passed, strict=True)]


@pytest.mark.parametrize("func", sorted(FUNC_TABLE))
def test_alpha_functions(func):
    # alpha 0.5 -> 128, against refs 127, 128, 129 (one pixel each).
    fb = NaiveFramebuffer(3, 1)
    color = (1.0, 1.0, 1.0, 0.5)
    cmds = [
        ("point", (x, 0, 0.0, color), st(fb, afunc=func, aref=ref))
        for x, ref in enumerate([127, 128, 129])
    ]
    render(fb, cmds)
    assert [bool(v) for v in fb.back[0]] == list(FUNC_TABLE[func])


def test_alpha_fail_changes_nothing():
    fb = NaiveFramebuffer(1, 1)
    fb.stencil[0, 0] = 7
    s = st(fb, afunc=CMP_NEVER, stencil=True, sfail=OP_ZERO, spass=OP_ZERO, szpass=OP_ZERO,
           zbuffer=True, zfunc=CMP_ALWAYS)  # fmt: skip
    render(fb, _point_cmds(fb, [0], s, z=5.0))
    assert fb.stencil[0, 0] == 7 and fb.z[0, 0] == GD_ZMAX and fb.back[0, 0] == 0


def test_iris_pass_vs_zpass():
    common = dict(stencil=True, sfunc=CMP_ALWAYS, sfail=OP_INVERT, spass=OP_INCR,
                  szpass=OP_ZERO)  # fmt: skip
    # zbuffer off: a passing stencil applies `pass` (INCR), not `zpass` (ZERO).
    fb = NaiveFramebuffer(1, 1)
    fb.stencil[0, 0] = 5
    render(fb, _point_cmds(fb, [0], st(fb, zbuffer=False, **common)))
    assert fb.stencil[0, 0] == 6
    # zbuffer on, z passes: zpass.
    fb = NaiveFramebuffer(1, 1)
    fb.stencil[0, 0] = 5
    render(fb, _point_cmds(fb, [0], st(fb, zbuffer=True, zfunc=CMP_ALWAYS, **common)))
    assert fb.stencil[0, 0] == 0
    # zbuffer on, z fails: pass, colour untouched.
    fb = NaiveFramebuffer(1, 1)
    fb.stencil[0, 0] = 5
    render(fb, _point_cmds(fb, [0], st(fb, zbuffer=True, zfunc=CMP_NEVER, **common)))
    assert fb.stencil[0, 0] == 6 and fb.back[0, 0] == 0


def test_zwritemask_partial():
    fb = NaiveFramebuffer(2, 1)
    fb.z[0, 1] = 0
    render(
        fb,
        [
            # stored 0x7FFFFF, zf = 0, mask 0x00FFFF -> 0x7F0000.
            ("point", (0, 0, 0.0, WHITE),
             st(fb, zbuffer=True, zfunc=CMP_ALWAYS, zwritemask=0x00FFFF)),
            # stored 0, zf = -1 = 0xFFFFFF, mask 0xFF0000 -> 0xFF0000 -> -65536.
            ("point", (1, 0, -1.0, WHITE),
             st(fb, zbuffer=True, zfunc=CMP_ALWAYS, zwritemask=0xFF0000)),
        ],
    )  # fmt: skip
    assert fb.z[0].tolist() == [0x7F0000, -65536]


# ---------------------------------------------------------------- blend / masks

SRC = (200, 100, 50, 128)
DST = 0x401E140A  # r 10, g 20, b 30, a 64


@pytest.mark.parametrize(
    "sf, df, dst, expected",
    [
        # r (200*128 + 10*127 + 127)//255 = 105, g 60, b 40, a 96
        (BF_SA, BF_MSA, DST, 0x60283C69),
        (BF_ONE, BF_ZERO, DST, 0x803264C8),  # source unchanged
        (BF_ZERO, BF_ONE, DST, DST),
        (BF_ONE, BF_ONE, DST, 0xC05078D2),  # 210, 120, 80, 192
        (BF_ONE, BF_ONE, 0xC81E1464, 0xFF5078FF),  # 300 and 328 clamp to 255
        # fs = da = 64: (200*64 + 127)//255 = 50, 25, 13, 32
        (BF_DA, BF_ZERO, DST, 0x200D1932),
        # fs = min(128, 191) = 128 for rgb, 255 for alpha; fd = 255:
        # r (25600 + 2550 + 127)//255 = 110, g 70, b 55, a 192
        (BF_MIN_SA_MDA, BF_ONE, DST, 0xC037466E),
        # dst alpha 200: fs = min(128, 55) = 55: r 53, g 42, b 41, a 328 -> 255
        (BF_MIN_SA_MDA, BF_ONE, 0xC81E140A, 0xFF292A35),
        # fs = dst colour: (200*10 + 127)//255 = 8, 8, 6, 32
        (BF_DC, BF_ZERO, DST, 0x20060808),
        # fd = src colour (BF_SC): same products
        (BF_ZERO, BF_DC, DST, 0x20060808),
        # fs = 255 - dst: r 200*245 -> 192, g 100*235 -> 92, b 50*225 -> 44, a 128*191 -> 96
        (BF_MDC, BF_ZERO, DST, 0x602C5CC0),
        # fd = 255 - src (BF_MSC): r 10*55 -> 2, g 20*155 -> 12, b 30*205 -> 24, a 64*127 -> 32
        (BF_ZERO, BF_MDC, DST, 0x20180C02),
        # fd = 255 - da = 191: r 10*191 -> 7, g 20*191 -> 15, b 30*191 -> 22, a 64*191 -> 48
        (BF_ZERO, BF_MDA, DST, 0x30160F07),
        # fd = da = 64: r 10*64 -> 3, g 20*64 -> 5, b 30*64 -> 8, a 64*64 -> 16
        (BF_ZERO, BF_DA, DST, 0x10080503),
    ],
)
def test_blend(sf, df, dst, expected):
    fb = NaiveFramebuffer(1, 1)
    fb.back[0, 0] = dst
    render(fb, _point_cmds(fb, [0], st(fb, blend_sf=sf, blend_df=df), color=c255(*SRC)))
    assert int(fb.back[0, 0]) == expected


def test_wmpack():
    # (0x11223344 & ~0x00FF00FF) | (0xDDCCBBAA & 0x00FF00FF) = 0x11CC33AA.
    fb = NaiveFramebuffer(1, 1)
    fb.back[0, 0] = 0x11223344
    s = st(fb, wmpack=0x00FF00FF)
    render(fb, _point_cmds(fb, [0], s, color=c255(0xAA, 0xBB, 0xCC, 0xDD)))
    assert int(fb.back[0, 0]) == 0x11CC33AA


@pytest.mark.parametrize(
    "op, expected",
    [
        (0x0, 0x00000000),  # LO_ZERO
        (0x1, 0x11003300),  # LO_AND
        (0x3, 0xDDCCBBAA),  # LO_SRC (blend path, source unchanged)
        (0x5, 0x11223344),  # LO_DST
        (0x6, 0xCCEE88EE),  # LO_XOR
        (0x7, 0xDDEEBBEE),  # LO_OR
        (0x2, 0xCCCC88AA),  # LO_ANDR: src & ~dst
        (0xC, 0x22334455),  # LO_NSRC
        (0xF, 0xFFFFFFFF),  # LO_ONE
    ],
)
def test_logicop(op, expected):
    fb = NaiveFramebuffer(1, 1)
    fb.back[0, 0] = 0x11223344
    s = st(fb, logicop=op)
    render(fb, _point_cmds(fb, [0], s, color=c255(0xAA, 0xBB, 0xCC, 0xDD)))
    assert int(fb.back[0, 0]) == expected


def test_draw_buffers():
    fb = NaiveFramebuffer(1, 1)
    render(fb, _point_cmds(fb, [0], st(fb, draw_front=True, draw_back=True)))
    assert fb.front[0, 0] == WHITE_PACKED and fb.back[0, 0] == WHITE_PACKED
    fb = NaiveFramebuffer(1, 1)
    render(fb, _point_cmds(fb, [0], st(fb, draw_front=True, draw_back=False)))
    assert fb.front[0, 0] == WHITE_PACKED and fb.back[0, 0] == 0
    # single-buffered: the only buffer is the target of back-buffer drawing too
    fb = NaiveFramebuffer(1, 1, double=False)
    render(fb, _point_cmds(fb, [0], st(fb)))
    assert fb.front[0, 0] == WHITE_PACKED


# ------------------------------------------------------------------ points/lines


def test_points_sizes():
    for size, expected in [
        (1, {(2, 2)}),
        (2, {(2, 2), (3, 2), (2, 3), (3, 3)}),
        (3, {(x, y) for x in (1, 2, 3) for y in (1, 2, 3)}),
        (4, {(x, y) for x in (1, 2, 3, 4) for y in (1, 2, 3, 4)}),
    ]:
        fb = NaiveFramebuffer(6, 6)
        render(fb, [("point", (2.2, 1.8, 0.0, WHITE), st(fb, pntsize=size))])
        assert written(fb.back) == expected


def _line(fb, p0, p1, state, z=(0.0, 0.0), start=None, colors=(WHITE, WHITE)):
    verts = ((p0[0], p0[1], z[0], colors[0]), (p1[0], p1[1], z[1], colors[1]))
    cmd = ("line", verts, state) if start is None else ("line", verts, state, start)
    render(fb, [cmd])
    return written(fb.back)


def test_line_closed_vs_half_open():
    # subpixel(3G): (0,0)->(0,2)
    fb = NaiveFramebuffer(4, 4)
    assert _line(fb, (0, 0), (0, 2), st(fb, subpixel=False)) == {(0, 0), (0, 1), (0, 2)}
    fb = NaiveFramebuffer(4, 4)
    assert _line(fb, (0, 0), (0, 2), st(fb, subpixel=True)) == {(0, 0), (0, 1)}


def test_line_x_major_rounding():
    # (0,0)->(4,1): y = X/4 -> floor(X/4 + 0.5) = 0, 0, 1 (tie up), 1, 1.
    expected = {(0, 0), (1, 0), (2, 1), (3, 1), (4, 1)}
    fb = NaiveFramebuffer(6, 3)
    assert _line(fb, (0, 0), (4, 1), st(fb)) == expected
    fb = NaiveFramebuffer(6, 3)
    assert _line(fb, (4, 1), (0, 0), st(fb)) == expected
    fb = NaiveFramebuffer(6, 3)
    assert _line(fb, (4, 1), (0, 0), st(fb, subpixel=True)) == expected - {(0, 0)}


def test_line_width():
    fb = NaiveFramebuffer(5, 5)
    # width 3 on an x-major line: offsets -1..1 along y.
    got = _line(fb, (0, 2), (3, 2), st(fb, linewidth=3))
    assert got == {(x, y) for x in range(4) for y in (1, 2, 3)}
    fb = NaiveFramebuffer(5, 5)
    # width 2 on a y-major line: offsets 0..1 along x.
    got = _line(fb, (2, 0), (2, 3), st(fb, linewidth=2))
    assert got == {(x, y) for x in (2, 3) for y in range(4)}


def test_line_depth_interpolation():
    # z 0 -> 10 over 4 steps: 0, 2.5, 5, 7.5, 10 -> 0, 3, 5, 8, 10.
    fb = NaiveFramebuffer(5, 1)
    _line(fb, (0, 0), (4, 0), st(fb, zbuffer=True, zfunc=CMP_ALWAYS), z=(0.0, 10.0))
    assert fb.z[0].tolist() == [0, 3, 5, 8, 10]


def test_line_subpixel_interpolation_uses_endpoint_positions():
    # (0.25,0,z=0) -> (4.25,0,z=16), subpixel TRUE: xf 64 -> 1088, columns 0..4,
    # half-open so 0..3. t = (X - 0.25) / 4: z = 16t = -1, 3, 7, 11 -> floor(z+0.5)
    # = -1 (clamped to 0), 3, 7, 11.
    fb = NaiveFramebuffer(5, 1)
    s = st(fb, subpixel=True, zbuffer=True, zfunc=CMP_ALWAYS)
    _line(fb, (0.25, 0), (4.25, 0), s, z=(0.0, 16.0))
    assert fb.z[0].tolist() == [0, 3, 7, 11, GD_ZMAX]


def test_line_gouraud_and_flat():
    # red -> blue over 2 steps: r 255, 127.5 -> 128, 0; b the mirror.
    cols = ((1.0, 0.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0))
    fb = NaiveFramebuffer(3, 1)
    _line(fb, (0, 0), (2, 0), st(fb), colors=cols)
    assert fb.back[0].tolist() == [0xFF0000FF, 0xFF800080, 0xFFFF0000]
    fb = NaiveFramebuffer(3, 1)
    _line(fb, (0, 0), (2, 0), st(fb, shademodel=FLAT), colors=cols)
    assert fb.back[0].tolist() == [0xFFFF0000] * 3


def test_linestyle():
    cases = [
        (0x0005, 1, 0, 8, {0, 2}),
        (0x0005, 2, 0, 8, {0, 1, 4, 5}),
        (0x0005, 1, 1, 8, {1}),  # pattern_start 1
        (0x8001, 1, 0, 18, {0, 15, 16}),
    ]
    for pattern, rep, start, length, xs in cases:
        fb = NaiveFramebuffer(length, 1)
        s = st(fb, linestyle=pattern, lsrepeat=rep)
        got = _line(fb, (0, 0), (length - 1, 0), s, start=start)
        assert got == {(x, 0) for x in xs}


# ------------------------------------------------------------------------ clears


def test_clears_scissor_and_masks():
    fb = NaiveFramebuffer(4, 4)
    fb.back[:] = 0xAAAAAAAA
    fb.stencil[:] = 0x30
    s = st(fb, scissor=(1, 2, 1, 2), wmpack=0xFFFF0000, zwritemask=0xFFFF00,
           swritemask=0x0F)  # fmt: skip
    render(fb, [("clear", {"color", "z", "stencil"},
                 {"color": 0x12345678, "z": 0, "stencil": 0xFF}, s)])  # fmt: skip
    inside = np.zeros((4, 4), dtype=bool)
    inside[1:3, 1:3] = True
    np.testing.assert_array_equal(fb.back, np.where(inside, 0x1234AAAA, 0xAAAAAAAA))
    assert not fb.front.any()
    # (0x7FFFFF & ~0xFFFF00) | (0 & 0xFFFF00) = 0xFF
    np.testing.assert_array_equal(fb.z, np.where(inside, 0xFF, GD_ZMAX))
    np.testing.assert_array_equal(fb.stencil, np.where(inside, 0x3F, 0x30))


def test_clear_planes_selection_and_stencil_planes():
    fb = NaiveFramebuffer(2, 2, stencil_planes=4)
    s = st(fb, draw_front=True, draw_back=False)
    render(fb, [("clear", {"color", "stencil"}, {"color": 0x01020304, "stencil": 0xFF}, s)])
    assert (fb.front == 0x01020304).all() and not fb.back.any()
    assert (fb.stencil == 0x0F).all() and (fb.z == GD_ZMAX).all()
    # z clear with a negative value sign-extends
    render(fb, [("clear", {"z"}, {"z": -5}, s)])
    assert (fb.z == -5).all()


# ------------------------------------------------------------------ accumulation


def test_accum_ops():
    fb = NaiveFramebuffer(2, 1)
    fb.back[0, 0] = 0x281E140A  # (10, 20, 30, 40)
    fb.back[0, 1] = 0x018000FF  # (255, 0, 128, 1)
    acc = np.zeros((1, 2, 4), dtype=np.int16)
    full = (0, 1, 0, 0)
    accum(fb, acc, AC_CLEAR, 2.5, full, 0xFFFFFFFF, "back")  # floor(3.0)
    assert acc.tolist() == [[[3] * 4, [3] * 4]]
    accum(fb, acc, AC_CLEAR, 0.0, full, 0xFFFFFFFF, "back")
    # 0.5*c: 5, 10, 15, 20; 127.5 -> 128, 0, 64, 0.5 -> 1
    accum(fb, acc, AC_ACCUMULATE, 0.5, full, 0xFFFFFFFF, "back")
    assert acc.tolist() == [[[5, 10, 15, 20], [128, 0, 64, 1]]]
    accum(fb, acc, AC_ACCUMULATE, 0.5, full, 0xFFFFFFFF, "back")
    assert acc.tolist() == [[[10, 20, 30, 40], [256, 0, 128, 2]]]
    accum(fb, acc, AC_CLEAR_ACCUMULATE, 2.0, full, 0xFFFFFFFF, "back")
    assert acc.tolist() == [[[20, 40, 60, 80], [510, 0, 256, 2]]]
    accum(fb, acc, AC_MULT, 0.5, full, 0xFFFFFFFF, "back")
    assert acc.tolist() == [[[10, 20, 30, 40], [255, 0, 128, 1]]]
    # round(-1.5) = floor(-1.0) = -1
    accum(fb, acc, AC_ADD, -1.5, full, 0xFFFFFFFF, "back")
    assert acc.tolist() == [[[9, 19, 29, 39], [254, -1, 127, 0]]]
    # return with v = 2: 18, 38, 58, 78; 508 -> 255, -2 -> 0, 254, 0
    accum(fb, acc, AC_RETURN, 2.0, full, 0xFFFFFFFF, "back")
    assert int(fb.back[0, 0]) == 0x4E3A2612
    assert int(fb.back[0, 1]) == 0x00FE00FF
    assert not fb.front.any()


def test_accum_saturation_scissor_and_wmpack():
    fb = NaiveFramebuffer(2, 1)
    fb.front[0, :] = 0xFFFFFFFF
    acc = np.zeros((1, 2, 4), dtype=np.int16)
    full = (0, 1, 0, 0)
    accum(fb, acc, AC_CLEAR_ACCUMULATE, 200.0, full, 0xFFFFFFFF, "front")  # 51000
    assert (acc == 32767).all()
    accum(fb, acc, AC_ADD, -70000.0, full, 0xFFFFFFFF, "front")
    assert (acc == -32768).all()
    # scissor to pixel 1 only
    accum(fb, acc, AC_CLEAR, 7.0, (1, 1, 0, 0), 0xFFFFFFFF, "front")
    assert acc[0, 0].tolist() == [-32768] * 4 and acc[0, 1].tolist() == [7] * 4
    # return through wmpack: only the red byte of pixel 1 changes
    accum(fb, acc, AC_RETURN, 1.0, (1, 1, 0, 0), 0x000000FF, "front")
    assert fb.front[0].tolist() == [0xFFFFFFFF, 0xFFFFFF07]
