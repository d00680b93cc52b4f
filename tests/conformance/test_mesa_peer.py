"""Checks of the Mesa (OSMesa/llvmpipe) peer itself, against hand-computed buffers.

The peer lives in ``vgxsim.reference.mesa``; these tests make sure it translates
IRIS GL conventions (pixel centres, 24-bit z, the stencil ``pass`` rule, blend
factors, scissor) correctly before it is used to judge vgxsim.
"""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

from vgxsim.reference import mesa
from vgxsim.state.raster import (
    BF_ONE,
    BF_ZERO,
    CMP_ALWAYS,
    CMP_GREATER,
    CMP_LESS,
    CMP_NEVER,
    CULL_BACK,
    CULL_FRONT,
    FLAT,
    OP_INCR,
    OP_INVERT,
    OP_KEEP,
    OP_REPLACE,
    OP_ZERO,
    RasterState,
)

if not mesa.mesa_available():
    pytest.skip("OSMesa + PyOpenGL not available", allow_module_level=True)

pytestmark = pytest.mark.mesa

W = H = 8
FULL = (0, W - 1, 0, H - 1)
GD_ZMAX = 0x7FFFFF
WHITE = (1.0, 1.0, 1.0, 1.0)


def st(**kw) -> RasterState:
    """A RasterState whose raster rectangle is the whole 8x8 window."""
    kw.setdefault("scissor", FULL)
    return RasterState(**kw)


def tri(pts, z=0, rgba=WHITE, state=None):
    """A triangle command with one z and colour for all three vertices."""
    return ("triangle", [(x, y, z, rgba) for x, y in pts], state or st())


def clear(state=None, color=0, z=GD_ZMAX, stencil=0, planes=("color", "z", "stencil")):
    return ("clear", set(planes), {"color": color, "z": z, "stencil": stencil}, state or st())


def mask(cells) -> np.ndarray:
    """Boolean (H, W) plane, True at the given (X, Y) pixels."""
    m = np.zeros((H, W), bool)
    for x, y in cells:
        m[y, x] = True
    return m


# Triangle A, subpixel(TRUE): (0.5, 0.5), (7.5, 0.5), (0.5, 4).  Its left and bottom
# edges run between pixel centres (x = 0.5, y = 0.5) and the hypotenuse is
# y = 4.25 - x/2, which is 0.25 or 0.75 off every pixel centre.  Covered: X >= 1,
# Y >= 1, Y < 4.25 - X/2:
#   X=1: Y<3.75 -> 1..3   X=2: Y<3.25 -> 1..3   X=3: Y<2.75 -> 1..2
#   X=4: Y<2.25 -> 1..2   X=5: Y<1.75 -> 1     X=6: Y<1.25 -> 1    X=7: none
TRI_A = [(0.5, 0.5), (7.5, 0.5), (0.5, 4.0)]
COVER_A = mask(
    [(1, 1), (1, 2), (1, 3), (2, 1), (2, 2), (2, 3), (3, 1), (3, 2), (4, 1), (4, 2),
     (5, 1), (6, 1)]
)
# Triangle B: A mirrored in the diagonal x = y, so its coverage is A's transposed.
TRI_B = [(y, x) for x, y in TRI_A]
COVER_B = COVER_A.T.copy()
SUB = st(subpixel=True)


@pytest.fixture(scope="module")
def peer():
    p = mesa.MesaPeer(W, H)
    yield p
    p.close()


def test_renderer_and_version_strings(peer):
    renderer = mesa.mesa_renderer_string()
    version = mesa.mesa_version_string()
    assert renderer and "Mesa" in version
    if "GALLIUM_DRIVER" not in os.environ:
        assert "llvmpipe" in renderer


def test_context_has_24_bit_depth_and_8_bit_stencil(peer):
    assert peer.depth_bits == 24
    assert peer.stencil_bits == 8


def test_full_window_clear(peer):
    peer.render([clear(color=0x80402010, z=-5, stencil=7)])
    assert peer.color().dtype == np.uint32
    assert (peer.color() == 0x80402010).all()
    assert (peer.depth_iris() == -5).all()
    assert np.allclose(peer.depth(), (-5 + 0x800000) / 0xFFFFFF, atol=1e-7)
    assert peer.stencil().dtype == np.uint8
    assert (peer.stencil() == 7).all()


@pytest.mark.parametrize("z", [-0x800000, -1, 0, 1, 12345, 0x7FFFFE, 0x7FFFFF])
def test_z_round_trip_is_exact_for_clears_and_flat_triangles(peer, z):
    peer.render([clear(z=z)])
    assert (peer.depth_iris() == z).all()
    big = [(-2, -2), (20, -2), (-2, 20)]
    peer.render([clear(z=0), tri(big, z=z, state=st(zbuffer=True, zfunc=CMP_ALWAYS))])
    assert (peer.depth_iris() == z).all()


def test_scissored_clear_uses_inclusive_raster_rectangle(peer):
    peer.render([clear(color=0), clear(state=st(scissor=(2, 4, 1, 3)), color=0xFFFFFFFF)])
    expect = np.zeros((H, W), bool)
    expect[1:4, 2:5] = True  # rows y0..y1, columns x0..x1, inclusive
    assert ((peer.color() != 0) == expect).all()


def test_triangle_between_pixel_centres_covers_hand_computed_pixels(peer):
    peer.render([clear(), tri(TRI_A, state=SUB)])
    got = peer.color() != 0
    assert (got == COVER_A).all(), got[::-1].astype(int)
    assert (peer.color()[COVER_A] == 0xFFFFFFFF).all()


def test_row_zero_is_bottom(peer):
    # A thin triangle over the bottom row only: centres y = 0, not y = 7.
    peer.render([clear(), tri([(-0.5, -0.4), (8.5, -0.4), (-0.5, 0.4)], state=SUB)])
    got = peer.color() != 0
    assert got[0, 0] and not got[1:, :].any() and not got[H - 1, 0]


def test_vertex_order_and_winding_do_not_change_coverage(peer):
    for order in ([0, 1, 2], [2, 1, 0], [1, 0, 2]):
        peer.render([clear(), tri([TRI_A[i] for i in order], state=SUB)])
        assert ((peer.color() != 0) == COVER_A).all()


def test_tie_rule_on_pixel_centre_edges_matches_numeric_model(peer):
    # subpixel(FALSE), integer vertices (1,1), (6,1), (1,6): every edge passes
    # through pixel centres.  numeric_model.md section 3: left and bottom edges are
    # inclusive, the top-right hypotenuse x + y = 7 is not.  llvmpipe (with the
    # peer's guard band, so nothing is clipped) applies the same rule.
    expect = mask([(x, y) for x in range(1, 7) for y in range(1, 7) if x + y < 7])
    assert expect.sum() == 15
    peer.render([clear(), tri([(1, 1), (6, 1), (1, 6)])])
    assert ((peer.color() != 0) == expect).all()
    # Upper-right right angle (6,1), (6,6), (1,6): top and right edges exclusive,
    # the bottom-left hypotenuse inclusive.
    expect = mask([(x, y) for x in range(1, 6) for y in range(1, 6) if x + y >= 7])
    peer.render([clear(), tri([(6, 1), (6, 6), (1, 6)])])
    assert ((peer.color() != 0) == expect).all()


def test_shared_edge_is_watertight_with_vertices_outside_window(peer):
    # Two triangles sharing the diagonal of a square much bigger than the window;
    # the diagonal goes through pixel centres.  Each pixel is covered exactly once.
    s = st(stencil=True, sfunc=CMP_ALWAYS, spass=OP_INCR)
    a, b, c, d = (-30, -30), (40, -30), (40, 40), (-30, 40)
    peer.render([clear(), tri([a, b, c], state=s), tri([a, c, d], state=s)])
    assert (peer.stencil() == 1).all()


def test_subpixel_false_snaps_vertices_to_pixel_centres(peer):
    # (0.6, 0.6), (6.4, 1.4), (0.6, 6.4) snap to (1, 1), (6, 1), (1, 6).
    expect = mask([(x, y) for x in range(1, 7) for y in range(1, 7) if x + y < 7])
    peer.render([clear(), tri([(0.6, 0.6), (6.4, 1.4), (0.6, 6.4)])])
    assert ((peer.color() != 0) == expect).all()


def test_stencil_incr_counts_overlapping_triangles(peer):
    s = st(subpixel=True, stencil=True, sfunc=CMP_ALWAYS, spass=OP_INCR, szpass=OP_INCR)
    peer.render([clear(), tri(TRI_A, state=s), tri(TRI_B, state=s), tri(TRI_A, state=s)])
    expect = 2 * COVER_A.astype(np.uint8) + COVER_B.astype(np.uint8)
    assert (peer.stencil() == expect).all()
    assert peer.stencil().max() == 3  # (1,1), (1,2), (2,1), (2,2) are in both


def test_stencil_incr_clamps_at_255(peer):
    s = st(stencil=True, sfunc=CMP_ALWAYS, spass=OP_INCR)
    full = [(-2, -2), (20, -2), (-2, 20)]
    peer.render([clear(stencil=254)] + [tri(full, state=s)] * 3)
    assert (peer.stencil() == 255).all()


def test_stencil_function_uses_masked_reference(peer):
    # Pass only where (ref & mask) == (stencil & mask): ref 0x13, mask 0x0F -> 3.
    s = st(subpixel=True, stencil=True, sref=0x13, smask=0x0F, sfunc=2,
           sfail=OP_ZERO, spass=OP_INVERT)
    peer.render([clear(stencil=0xA3, state=st(scissor=(0, 3, 0, 7))),
                 clear(stencil=0xA4, state=st(scissor=(4, 7, 0, 7)), planes=("stencil",)),
                 tri([(-1, -1), (20, -1), (-1, 20)], state=s)])
    got = peer.stencil()
    assert (got[:, :4] == 0x5C).all()  # passed: INVERT of 0xA3 (zbuffer off: `pass`)
    assert (got[:, 4:] == 0).all()  # failed: ZERO


def test_depth_test_ordering(peer):
    near, far = -1000, 1000
    red, green = (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0)
    z = st(subpixel=True, zbuffer=True, zfunc=CMP_LESS)
    for first, second in (((near, red), (far, green)), ((far, green), (near, red))):
        peer.render([clear(z=GD_ZMAX),
                     tri(TRI_A, z=first[0], rgba=first[1], state=z),
                     tri(TRI_A, z=second[0], rgba=second[1], state=z)])
        col, dep = peer.color(), peer.depth_iris()
        assert (col[COVER_A] == 0xFF0000FF).all()  # red (R in the low byte) wins
        assert (dep[COVER_A] == near).all()
        assert (dep[~COVER_A] == GD_ZMAX).all()
        assert (col[~COVER_A] == 0).all()


def test_depth_write_mask_and_zbuffer_off(peer):
    # zwritemask 0: test still applies, nothing written.
    z = st(subpixel=True, zbuffer=True, zfunc=CMP_LESS, zwritemask=0)
    peer.render([clear(z=0), tri(TRI_A, z=-10, state=z)])
    assert (peer.depth_iris() == 0).all() and (peer.color()[COVER_A] != 0).all()
    # zbuffer off: z neither tested nor written.
    peer.render([clear(z=0), tri(TRI_A, z=100, state=SUB)])
    assert (peer.depth_iris() == 0).all() and (peer.color()[COVER_A] != 0).all()


def test_zbuffer_off_applies_iris_pass_op(peer):
    # stencil(TRUE, 5, SF_ALWAYS, 0xFF, ST_KEEP, pass=ST_REPLACE, zpass=ST_INVERT):
    # with zbuffer(FALSE) IRIS applies `pass` (REPLACE -> 5), not zpass.
    base = dict(subpixel=True, stencil=True, sref=5, sfunc=CMP_ALWAYS,
                sfail=OP_KEEP, spass=OP_REPLACE, szpass=OP_INVERT)
    peer.render([clear(stencil=0), tri(TRI_A, state=st(**base))])
    assert (peer.stencil() == np.where(COVER_A, 5, 0)).all()
    # With zbuffer(TRUE) and a passing z test the zpass op (INVERT) applies ...
    peer.render([clear(stencil=0),
                 tri(TRI_A, state=st(**base, zbuffer=True, zfunc=CMP_ALWAYS))])
    assert (peer.stencil() == np.where(COVER_A, 255, 0)).all()
    # ... and with a failing z test the `pass` op (REPLACE).
    peer.render([clear(stencil=0),
                 tri(TRI_A, state=st(**base, zbuffer=True, zfunc=CMP_NEVER))])
    assert (peer.stencil() == np.where(COVER_A, 5, 0)).all()


def test_stencil_write_mask_is_per_bit(peer):
    s = st(subpixel=True, stencil=True, sref=0xFF, sfunc=CMP_ALWAYS, spass=OP_REPLACE,
           swritemask=0x0F)
    peer.render([clear(stencil=0x30), tri(TRI_A, state=s)])
    assert (peer.stencil() == np.where(COVER_A, 0x3F, 0x30)).all()


def test_blend_one_one_adds_and_saturates(peer):
    add = st(subpixel=True, blend_sf=BF_ONE, blend_df=BF_ONE)
    rgba = (0x11 / 255, 0x22 / 255, 0x33 / 255, 0xF0 / 255)
    peer.render([clear(color=0x10203040), tri(TRI_A, rgba=rgba, state=add)])
    col = peer.color()
    # R 0x40+0x11, G 0x30+0x22, B 0x20+0x33, A 0x10+0xF0 -> 0x100 saturates to 0xFF.
    assert (col[COVER_A] == 0xFF535251).all()
    assert (col[~COVER_A] == 0x10203040).all()


def test_blend_src_alpha(peer):
    # BF_SA, BF_MSA with alpha 0x80/255 over black: about half of 0xFF.
    s = st(subpixel=True, blend_sf=4, blend_df=5)
    peer.render([clear(color=0xFF000000), tri(TRI_A, rgba=(1.0, 0.0, 0.0, 128 / 255), state=s)])
    r = peer.color()[COVER_A] & 0xFF
    assert (abs(r.astype(int) - 128) <= 1).all()


def test_blend_factor_2_means_dst_as_source_and_src_as_destination(peer):
    # blendfunction(BF_DC, BF_ZERO): out = src * dst.  dst R = 0x80, src R = 1.0.
    s = st(subpixel=True, blend_sf=2, blend_df=BF_ZERO)
    peer.render([clear(color=0xFF000080), tri(TRI_A, rgba=(1.0, 0.5, 0.0, 1.0), state=s)])
    px = int(peer.color()[1, 1])
    assert px & 0xFF == 0x80 and (px >> 8) & 0xFF == 0 and px >> 24 == 0xFF
    # blendfunction(BF_ZERO, BF_SC): out = dst * src.
    s = st(subpixel=True, blend_sf=BF_ZERO, blend_df=2)
    peer.render([clear(color=0xFF0000FF), tri(TRI_A, rgba=(0.0, 0.0, 0.0, 1.0), state=s)])
    assert int(peer.color()[1, 1]) & 0xFF == 0
    with pytest.raises(ValueError):
        peer.render([tri(TRI_A, state=st(blend_sf=BF_ONE, blend_df=8))])


def test_scissor_limits_triangles(peer):
    s = st(scissor=(2, 4, 1, 3))
    peer.render([clear(), tri([(-2, -2), (20, -2), (-2, 20)], state=s)])
    expect = np.zeros((H, W), bool)
    expect[1:4, 2:5] = True
    assert ((peer.color() != 0) == expect).all()


def test_alpha_test(peer):
    s = st(subpixel=True, afunc=CMP_GREATER, aref=128)
    peer.render([clear(), tri(TRI_A, rgba=(1, 1, 1, 100 / 255), state=s)])
    assert (peer.color() == 0).all()
    peer.render([clear(), tri(TRI_A, rgba=(1, 1, 1, 200 / 255), state=s)])
    assert ((peer.color() != 0) == COVER_A).all()


def test_logicop_xor(peer):
    s = st(subpixel=True, logicop=6)  # LO_XOR
    peer.render([clear(color=0x0F0F0F0F), tri(TRI_A, rgba=WHITE, state=s)])
    assert (peer.color()[COVER_A] == 0xF0F0F0F0).all()
    # LO_ANDR = 2 is "src AND NOT dst" (X11/GL order), not "NOT src AND dst".
    s = st(subpixel=True, logicop=2)
    peer.render([clear(color=0x0F0F0F0F), tri(TRI_A, rgba=WHITE, state=s)])
    assert (peer.color()[COVER_A] == 0xF0F0F0F0).all()


def test_color_write_mask_per_component(peer):
    s = st(subpixel=True, wmpack=0x0000FF00)  # green only
    peer.render([clear(color=0x11223344), tri(TRI_A, rgba=WHITE, state=s)])
    assert (peer.color()[COVER_A] == 0x1122FF44).all()
    assert mesa.mesa_caveats(s) == []
    assert mesa.mesa_caveats(st(wmpack=0x0000F000))  # partial byte: not expressible


def test_culling(peer):
    ccw = TRI_A  # counter-clockwise in window coordinates: front-facing
    cw = [TRI_A[0], TRI_A[2], TRI_A[1]]
    for cull, pts, drawn in ((CULL_BACK, ccw, True), (CULL_BACK, cw, False),
                             (CULL_FRONT, ccw, False), (CULL_FRONT, cw, True)):
        peer.render([clear(), tri(pts, state=st(subpixel=True, cull=cull))])
        assert (peer.color() != 0).any() == drawn, (cull, pts)


def test_flat_shading_takes_last_vertex_and_gouraud_interpolates(peer):
    verts = [(x, y, 0, c) for (x, y), c in zip(
        [(-1, -1), (20, -1), (-1, 20)],
        [(1.0, 0, 0, 1), (0, 1.0, 0, 1), (0, 0, 1.0, 1)], strict=True)]
    peer.render([clear(), ("triangle", verts, st(shademodel=FLAT))])
    assert (peer.color() == 0xFFFF0000).all()  # blue, the last vertex
    peer.render([clear(), ("triangle", verts, st())])
    assert len(np.unique(peer.color())) > 10


def test_render_arrays_matches_immediate_mode(peer):
    rng = np.random.default_rng(7)
    n = 50
    pos = np.empty((n, 3, 3))
    pos[:, :, :2] = rng.uniform(-3, W + 3, (n, 3, 2))
    pos[:, :, 2] = rng.integers(-0x800000, 0x7FFFFF, (n, 3))
    col = rng.uniform(0, 1, (n, 3, 4))
    s = st(zbuffer=True, zfunc=CMP_LESS, stencil=True, sfunc=CMP_ALWAYS, spass=OP_INCR,
           szpass=OP_INCR, shademodel=FLAT)
    cmds = [clear()] + [("triangle", [(*pos[i, j], tuple(col[i, j])) for j in range(3)], s)
                        for i in range(n)]
    peer.render(cmds)
    ref = peer.color(), peer.depth_iris(), peer.stencil()
    peer.render([clear()])
    peer.render_arrays(pos, col, s)
    peer.finish()
    for a, b in zip(ref, (peer.color(), peer.depth_iris(), peer.stencil()), strict=True):
        assert (a == b).all()
    arrays = peer.upload_arrays(pos, col)
    peer.render([clear()])
    peer.draw_arrays(arrays, s)
    assert (peer.stencil() == ref[2]).all()
    arrays.delete()


def test_several_peers_in_one_process(peer):
    other = mesa.MesaPeer(5, 3)
    try:
        peer.render([clear(color=0xFF0000FF)])
        other.render([clear(color=0xFF00FF00, state=RasterState(scissor=(0, 4, 0, 2)))])
        peer.render([tri(TRI_A, rgba=(0, 0, 1.0, 1.0), state=SUB)])
        assert other.color().shape == (3, 5) and (other.color() == 0xFF00FF00).all()
        assert (peer.color()[COVER_A] == 0xFFFF0000).all()
        assert (peer.color()[~COVER_A] == 0xFF0000FF).all()
    finally:
        other.close()
    peer.render([clear(color=0x01020304)])  # still usable after the other is gone
    assert (peer.color() == 0x01020304).all()


def test_unknown_command_and_plane_raise(peer):
    with pytest.raises(ValueError):
        peer.render([("quad", [], st())])
    with pytest.raises(ValueError):
        peer.render([clear(planes=("accum",))])


def test_set_threads_after_first_context_raises(peer):
    current = os.environ.get("LP_NUM_THREADS")
    other = str(int(current) + 1) if current and current.isdigit() else "3"
    with pytest.raises(RuntimeError):
        mesa.set_threads(int(other))
    with pytest.raises(ValueError):
        mesa.set_threads(-1)


def test_set_threads_before_first_context():
    code = (
        "import os\n"
        "from vgxsim.reference import mesa\n"
        "assert mesa.mesa_available()\n"
        "mesa.set_threads(0)\n"
        "p = mesa.MesaPeer(4, 4)\n"
        "assert os.environ['LP_NUM_THREADS'] == '0'\n"
        "mesa.set_threads(0)\n"
        "try:\n"
        "    mesa.set_threads(2)\n"
        "except RuntimeError:\n"
        "    print('ok', mesa.mesa_renderer_string())\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "LP_NUM_THREADS"}
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    env["PYTHONPATH"] = root + os.pathsep + env.get("PYTHONPATH", "")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("ok")
