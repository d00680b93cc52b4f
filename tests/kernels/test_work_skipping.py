"""Exact work skipping (kernels/tiles.py) changes no pixel, stencil or depth value.

Scenes here are layered the way shadow algorithms layer them (a depth pass, then
faces in front of and behind the stored depths, then an EQUAL pass), over windows
wide and tall enough for several 64-column tiles and several bands, so that tiles
really are skipped and fully covered.  Each is rendered with every combination of
the switches (skip_tiles, cover_blocks, tight_tiles) on every rasterizer path (and
spans stepped or solved) and must give
identical planes, and a few are checked against the naive reference.
"""

import itertools

import numpy as np
import pytest
from kernel_helpers import (
    assert_planes_equal,
    full_state,
    kernel_batch,
    kernel_framebuffer,
    planes_of,
    queue_commands,
    random_planes,
    render_naive,
)

from vgxsim.batch import WORK_NAMES, CommandBatch
from vgxsim.reference.naive import GD_ZMAX, GD_ZMIN
from vgxsim.state.raster import (
    BF_MSA,
    BF_ONE,
    BF_SA,
    CMP_ALWAYS,
    CMP_EQUAL,
    CMP_GEQUAL,
    CMP_GREATER,
    CMP_LEQUAL,
    CMP_LESS,
    CMP_NEVER,
    CMP_NOTEQUAL,
    OP_DECR,
    OP_INCR,
    OP_INVERT,
    OP_KEEP,
    OP_REPLACE,
)

# (skip_tiles, cover_blocks, tight_tiles)
SWITCHES = list(itertools.product((True, False), repeat=3))


def render(cmds, w, h, cfg, init, mode="span", skip=True, cover=True, tight=True, step=True):
    fb = kernel_framebuffer(w, h, init=init, **cfg)
    batch = kernel_batch(fb, mode)
    batch.skip_tiles = skip
    batch.cover_blocks = cover
    batch.tight_tiles = tight
    batch.step_spans = step
    queue_commands(batch, cmds)
    batch.flush()
    return planes_of(fb), batch.work()


def _tri(rng, w, h, zlo, zhi, big):
    size = max(w, h) * (1.5 if big else 0.4)
    c = rng.uniform([0, 0], [w, h])
    return tuple((float(c[0] + rng.uniform(-size, size)), float(c[1] + rng.uniform(-size, size)),
                  float(rng.uniform(zlo, zhi)), tuple(float(v) for v in rng.uniform(0, 1, 4)))
                 for _ in range(3))


def layered_scene(rng, w, h):
    """Depth pass, volume faces (z test, stencil ops, no colour or z writes), lit
    pass (z EQUAL, stencil test, blends), with random states and clears between."""
    cfg = dict(double=bool(rng.integers(2)), zbits=24, stencil=int(rng.choice([8, 8, 3])))
    scissor = ((0, w - 1, 0, h - 1) if rng.random() < 0.7 else
               (int(rng.integers(0, w // 2)), int(rng.integers(w // 2, w)),
                int(rng.integers(0, h // 2)), int(rng.integers(h // 2, h))))
    zfunc = int(rng.choice([CMP_LEQUAL, CMP_LESS, CMP_LESS, CMP_GEQUAL, CMP_GREATER,
                            CMP_EQUAL, CMP_NOTEQUAL, CMP_NEVER, CMP_ALWAYS]))
    depth = full_state(w, h, zbuffer=True, zfunc=CMP_LEQUAL, scissor=scissor,
                       zwritemask=int(rng.choice([0xFFFFFFFF, 0xFFFFFFFF, 0xFFFF00])))
    volume = [full_state(w, h, zbuffer=True, zfunc=zfunc, zwritemask=0, wmpack=0,
                         stencil=True, sfunc=int(rng.choice([CMP_ALWAYS, CMP_ALWAYS, CMP_EQUAL])),
                         sref=int(rng.integers(3)),
                         spass=int(rng.choice([OP_KEEP, OP_KEEP, OP_KEEP, OP_INCR, OP_INVERT])),
                         szpass=int(rng.choice([OP_INCR, OP_DECR, OP_REPLACE])),
                         sfail=int(rng.choice([OP_KEEP, OP_KEEP, OP_INCR])),
                         cull=int(rng.integers(3)), scissor=scissor) for _ in range(2)]
    lit = full_state(w, h, zbuffer=True, zfunc=CMP_EQUAL, stencil=True, sfunc=CMP_EQUAL,
                     sref=0, blend_sf=int(rng.choice([BF_ONE, BF_ONE, BF_SA])),
                     blend_df=int(rng.choice([BF_ONE, 0, BF_MSA])),
                     shademodel=int(rng.integers(2)), scissor=scissor)
    cmds = []
    if rng.random() < 0.8:
        cmds.append(("clear", {"color", "z", "stencil"},
                     {"color": 0, "z": int(rng.choice([GD_ZMAX, 5000])),
                      "stencil": int(rng.choice([0, 1, 2, 128]))},
                     full_state(w, h, scissor=scissor)))
    scene = [_tri(rng, w, h, -3000, 3000, big=rng.random() < 0.3) for _ in range(4)]
    cmds += [("triangle", t, depth) for t in scene]
    for _ in range(int(rng.integers(4, 10))):
        r = rng.random()
        if r < 0.4:  # behind the scene's depths
            t = _tri(rng, w, h, 3500, GD_ZMAX, big=True)
        elif r < 0.7:  # in front
            t = _tri(rng, w, h, GD_ZMIN, -3500, big=True)
        else:  # straddling
            t = _tri(rng, w, h, -6000, 6000, big=True)
        cmds.append(("triangle", t, volume[int(rng.integers(2))]))
        if rng.random() < 0.15:
            cmds.append(("flush",))
        if rng.random() < 0.25:
            cmds.append(("clear", {"z"}, {"z": int(rng.integers(-4000, 4000))},
                         full_state(w, h, scissor=(int(rng.integers(0, w)), w - 1,
                                             int(rng.integers(0, h)), h - 1),
                                    zwritemask=int(rng.choice([0xFFFFFF, 0xFF0000])))))
        if rng.random() < 0.1:
            cmds.append(("line", (_tri(rng, w, h, -9000, 9000, True)[0],
                                  _tri(rng, w, h, -9000, 9000, True)[1]), depth, 0))
    cmds += [("triangle", t, lit) for t in scene]
    cmds += [("triangle", _tri(rng, w, h, 3500, 9000, big=True), lit)]
    init = random_planes(rng, w, h, **cfg) if rng.random() < 0.3 else None
    return cfg, init, cmds


def test_switches_change_no_plane_on_layered_scenes():
    rng = np.random.default_rng(7101)
    w, h = 200, 150
    total = dict.fromkeys(WORK_NAMES, 0)
    for i in range(40):
        cfg, init, cmds = layered_scene(rng, w, h)
        want, work = render(cmds, w, h, cfg, init, skip=False, cover=False, tight=False,
                            step=False)
        assert work["tiles_skipped"] == 0 and work["blocks_covered"] == 0
        assert work["tiles_scanned"] == 0
        for mode, step in (("span", True), ("span", False), ("general", True),
                           ("edge", True)):
            for skip, cover, tight in SWITCHES:
                got, work = render(cmds, w, h, cfg, init, mode, skip, cover, tight, step)
                assert_planes_equal(got, want, f"scene {i} mode={mode} step={step} "
                                               f"skip={skip} cover={cover} tight={tight}")
                if mode == "span" and step and skip and cover and tight:
                    for k in total:
                        total[k] += work[k]
    # The scenes exercise what they claim to: tiles skipped and blocks covered.
    assert total["tiles_skipped"] > 100
    assert total["blocks_covered"] > 100
    assert total["tiles_scanned"] > 0


@pytest.mark.parametrize("seed", range(4))
def test_layered_scenes_match_naive(seed):
    rng = np.random.default_rng(900 + seed)
    w, h = 140, 70
    cfg, init, cmds = layered_scene(rng, w, h)
    want = render_naive(cmds, w, h, init=init, **cfg)
    got, _ = render(cmds, w, h, cfg, init)
    assert_planes_equal(got, want, f"seed {seed}")


@pytest.mark.parametrize("tight", [False, True])
def test_counters_count_fragments_and_skipped_tiles(tight):
    """Hand-counted: a 128 x 64 rectangle (two triangles) drawn behind a z clear to 0
    fails the z test in every tile, so nothing is tested; drawn in front, all 8192
    pixels are tested, the stencil pass may write each of them, and the two tiles are
    covered by neither triangle alone.  Tiles are 64 columns by 32 rows: over
    bounding boxes each triangle meets all 2 x 2 tiles.  Over the triangles' own
    pixels: the diagonal from (0, 0) to (128, 64) crosses row 32 at x = 64, so each
    triangle has pixels in one tile of one tile row and both tiles of the other."""
    w, h = 128, 64
    fb = kernel_framebuffer(w, h, double=False, zbits=24, stencil=8)
    batch = CommandBatch(fb)
    batch.tight_tiles = tight
    clear = full_state(w, h)
    vol = full_state(w, h, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0, stencil=True,
                     szpass=OP_INCR)
    white = (1.0, 1.0, 1.0, 1.0)

    def quad(z):
        return [(-0.5 + x, -0.5 + y, z, white) for x, y in ((0, 0), (w, 0), (w, h), (0, h))]

    def draw(z):
        q = quad(z)
        queue_commands(batch, [("clear", {"z", "stencil"}, {"z": 0, "stencil": 0}, clear),
                               ("triangle", (q[0], q[1], q[2]), vol),
                               ("triangle", (q[0], q[2], q[3]), vol)])
        batch.reset_counters()
        batch.flush()
        return batch.work()

    behind = draw(1000.0)
    assert behind["fragments"] == 0
    assert behind["tiles_skipped"] == 2 * (3 if tight else 4)  # two triangles
    assert not fb.stencil.any()
    front = draw(-1000.0)
    assert front["fragments"] == w * h
    assert front["stencil_writes"] == w * h
    assert front["tiles_skipped"] == 0
    assert (fb.stencil == 1).all()


def test_loose_bounds_are_scanned_again_and_equal_writes_keep_them():
    """Hand-counted, one flush: a z clear to GD_ZMAX, a depth quad at z = 0 over the
    whole 128 x 64 window (its write widens each tile's bounds to [0, GD_ZMAX]:
    loose), a volume quad behind it (z = 1000), a ZF_EQUAL pass over the depth quad
    (writes z, but only values equal to the stored ones), a second volume quad
    behind.  Each triangle's rectangle covers each tile, so meeting loose bounds it
    pays for a scan at once; the bounds are then [0, 0] and every volume triangle is
    skipped in every tile (the EQUAL pass leaves them as they are).  Stencil and z as
    with skipping off."""
    w, h = 128, 64
    white = (1.0, 1.0, 1.0, 1.0)
    clear = full_state(w, h)
    depth = full_state(w, h, zbuffer=True, zfunc=CMP_LEQUAL)
    equal = full_state(w, h, zbuffer=True, zfunc=CMP_EQUAL)
    vol = full_state(w, h, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0, stencil=True,
                     szpass=OP_INCR)

    def quad(z, rs):
        q = [(-0.5 + x, -0.5 + y, z, white) for x, y in ((0, 0), (w, 0), (w, h), (0, h))]
        return [("triangle", (q[0], q[1], q[2]), rs), ("triangle", (q[0], q[2], q[3]), rs)]

    cmds = ([("clear", {"z", "stencil"}, {"z": GD_ZMAX, "stencil": 0}, clear)]
            + quad(0.0, depth) + quad(1000.0, vol) + quad(0.0, equal) + quad(1000.0, vol))
    cfg = dict(double=False, zbits=24, stencil=8)
    want, off = render(cmds, w, h, cfg, None, skip=False, cover=False)
    got, on = render(cmds, w, h, cfg, None, skip=True, cover=False, tight=False)
    assert_planes_equal(got, want, "loose bounds")
    assert off["fragments"] == 4 * w * h
    assert on["fragments"] == 2 * w * h  # the depth and EQUAL passes only
    assert 0 < on["tiles_scanned"] <= 3 * 4  # at most a scan per quad and tile
    assert on["tiles_skipped"] == 2 * 2 * 4  # two quads x two triangles x 2 x 2 tiles


def test_scissor_keeps_bands_outside_unvisited():
    """A triangle outside the raster rectangle's rows is binned into no band."""
    w, h = 64, 256
    fb = kernel_framebuffer(w, h, double=False, zbits=24, stencil=0)
    batch = CommandBatch(fb)
    rs = full_state(w, h, scissor=(0, w - 1, 200, 255))
    white = (1.0, 1.0, 1.0, 1.0)
    queue_commands(batch, [("triangle", ((0.0, 0.0, 0.0, white), (60.0, 0.0, 0.0, white),
                                         (0.0, 100.0, 0.0, white)), rs)])
    assert batch.p_y1[0] < batch.p_y0[0]  # nothing to bin
    batch.flush()
    assert batch.work()["fragments"] == 0
    assert not fb.front.any()


def _heidmann(monkeypatch, skip, cover, tight=True, **kw):
    """The 1991 frame at 320 x 256 with the switches set on every batch: the image,
    each light's stencil plane and z plane, and the work counted."""
    from vgxsim.examples import heidmann1991 as h91
    from vgxsim.gl._core import current, session

    monkeypatch.setattr(CommandBatch, "skip_tiles", skip)
    monkeypatch.setattr(CommandBatch, "cover_blocks", cover)
    monkeypatch.setattr(CommandBatch, "tight_tiles", tight)
    session.reset()
    planes = {}

    def hook(i):
        ctx = current("test")
        ctx.flush()
        planes[i] = (ctx.fb.stencil.copy(), ctx.fb.z.copy(), ctx.batch.work())

    try:
        img = h91.render(320, 256, stencil_hook=hook, **kw)
    finally:
        session.reset()
    return img, planes


@pytest.mark.parametrize("edges", ["silhouette", "all"])
def test_heidmann_frame_is_identical_with_each_switch(monkeypatch, edges):
    want_img, want = _heidmann(monkeypatch, False, False, False, edges=edges)
    assert want and all(w[2]["tiles_skipped"] == 0 for w in want.values())
    for skip, cover, tight in SWITCHES[:-1]:
        img, got = _heidmann(monkeypatch, skip, cover, tight, edges=edges)
        np.testing.assert_array_equal(img, want_img)
        assert got.keys() == want.keys()
        for light in want:
            np.testing.assert_array_equal(got[light][0], want[light][0])
            np.testing.assert_array_equal(got[light][1], want[light][1])
        if skip:  # the shadow faces behind the scene are skipped, not tested
            last = got[max(got)][2]
            assert last["tiles_skipped"] > 0
            assert last["fragments"] < want[max(want)][2]["fragments"]


def test_dense_scene_is_identical_with_each_switch():
    """The benchmarks' dense shadow scene (bench/dense_scene.py: 42 k scene triangles,
    20 spheres' shadow volumes for two lights, one flush at 1280 x 1024) gives the
    same colour, z and stencil planes with the skipping switches off, each one off,
    and all on; and with them on it really skips: fewer fragments, tiles skipped."""
    import importlib.util
    import pathlib

    pytest.importorskip("trimesh")
    path = pathlib.Path(__file__).resolve().parents[2] / "bench" / "dense_scene.py"
    spec = importlib.util.spec_from_file_location("dense_scene_for_test", path)
    dense = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(dense)
    passes, _, _ = dense.build()
    switches = ("skip_tiles", "cover_blocks", "tight_tiles")

    def frame(values):
        run, batch = dense.vgxsim_frame(passes)
        for sw, v in zip(switches, values, strict=True):
            setattr(batch, sw, v)
        run()
        fb = batch.fb
        return (fb.front.copy(), fb.z.copy(), fb.stencil.copy()), batch.work()

    want, off = frame((False, False, False))
    assert want[0].any() and want[2].any()  # lit pixels, and shadowed ones counted
    for values in ((True, True, True), (False, True, True), (True, False, True),
                   (True, True, False)):
        got, work = frame(values)
        for name, g, w in zip(("colour", "z", "stencil"), got, want, strict=True):
            np.testing.assert_array_equal(g, w, err_msg=f"{name} with {values}")
        if values == (True, True, True):
            assert work["tiles_skipped"] > 0
            assert work["fragments"] < off["fragments"]
