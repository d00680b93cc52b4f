"""The block update (kernels/blocks.py, CommandBatch.block_update) changes nothing
drawn and counts the same work.

A fully covered tile whose depth bounds prove that a triangle passes the z test
everywhere in it runs its rows without the z compare.  The scenes here make that
happen often: big triangles over a few 64 x 32 tiles, z clears and flat layers (so
bounds are exact and narrow), volume faces in front of, behind and across the
stored depths under every z-pass stencil op (arithmetic and by table) with the
stencil planes holding every value, depth passes, lit passes (zfunction EQUAL and
LEQUAL, z writes on and off, stencil test or not, blend replace, ONE+ONE and one
the path leaves alone), write masks.  Planes must be identical with the switch on
and off (1 and 2 threads, spans stepped or not, tight tiles or not, int32 packing
or not) and equal to the naive reference; every work counter but
``blocks_z_passed`` must be the same; a hand-counted scene checks that counter.
"""

import dataclasses

import numpy as np
import pytest
from kernel_helpers import (
    assert_planes_equal,
    full_state,
    kernel_framebuffer,
    queue_commands,
    random_planes,
    render_naive,
    render_switched,
)

from vgxsim import threads
from vgxsim.batch import CommandBatch
from vgxsim.reference.naive import GD_ZMAX, GD_ZMIN
from vgxsim.state.raster import (
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
    OP_DECR,
    OP_INCR,
    OP_INVERT,
    OP_KEEP,
    OP_REPLACE,
    OP_ZERO,
)

W, H = 200, 100  # 4 x 4 tiles (the last column part), several bands
ZFUNCS = [CMP_LESS, CMP_LEQUAL, CMP_GREATER, CMP_GEQUAL, CMP_EQUAL, CMP_NOTEQUAL,
          CMP_ALWAYS, CMP_NEVER]
Z_PASS_OPS = [OP_INCR, OP_DECR, OP_KEEP, OP_REPLACE, OP_INVERT, OP_ZERO]


def _render(cmds, cfg, init, nthreads=1, **switches):
    # The depth-writing colour passes' block rows too (CommandBatch.span_zwrite
    # leaves them out by default; the scenes below turn it on in turn).
    switches.setdefault("span_zwrite", False)
    return render_switched(cmds, W, H, cfg=cfg, init=init, nthreads=nthreads, **switches)


def _big(rng, zlo, zhi, flat=False):
    """A triangle over most of the window (many tiles wholly inside it)."""
    c = rng.uniform([0, 0], [W, H])
    z = float(rng.uniform(zlo, zhi))
    return tuple((float(c[0] + rng.uniform(-2.5 * W, 2.5 * W)),
                  float(c[1] + rng.uniform(-2.5 * H, 2.5 * H)),
                  z if flat else float(rng.uniform(zlo, zhi)),
                  tuple(float(v) for v in rng.uniform(0, 1, 4))) for _ in range(3))


def _scene(rng):
    cfg = dict(double=bool(rng.integers(2)), zbits=24, stencil=int(rng.choice([8, 8, 3, 1])))
    smax = (1 << cfg["stencil"]) - 1
    scissor = ((0, W - 1, 0, H - 1) if rng.random() < 0.8 else
               (int(rng.integers(0, 60)), int(rng.integers(120, W)),
                int(rng.integers(0, 30)), int(rng.integers(60, H))))
    zclear = int(rng.choice([GD_ZMAX, 0, -3000, 3000]))
    cmds = [("clear", {"color", "z", "stencil"},
             {"color": int(rng.integers(0, 1 << 32)), "z": zclear,
              "stencil": int(rng.integers(0, smax + 1))}, full_state(W, H))]
    # A depth pass: flat layers at the clear depth or over it, and sloped faces.
    for _ in range(int(rng.integers(0, 4))):
        depth = full_state(W, H, zbuffer=True, zfunc=int(rng.choice(ZFUNCS)),
                           wmpack=int(rng.choice([0, 0xFFFFFFFF])), scissor=scissor,
                           zwritemask=int(rng.choice([0xFFFFFF, 0xFFFFFF, 0xFFFF00])))
        flat = rng.random() < 0.5
        cmds.append(("triangle", _big(rng, zclear - 2000, zclear + 2000, flat), depth))
    for _ in range(int(rng.integers(4, 12))):
        r = rng.random()
        if r < 0.55:  # a volume face, in front of, behind or across the stored depths
            zfail = OP_KEEP if rng.random() < 0.8 else int(rng.choice([OP_DECR, OP_INCR]))
            rs = full_state(W, H, zbuffer=True, zfunc=int(rng.choice(ZFUNCS)),
                            zwritemask=0, wmpack=0, stencil=True,
                            sfunc=int(rng.choice([CMP_ALWAYS, CMP_ALWAYS, CMP_EQUAL])),
                            sref=int(rng.integers(0, smax + 1)),
                            szpass=int(rng.choice(Z_PASS_OPS)), spass=zfail,
                            swritemask=int(rng.choice([0xFF, 0xFF, 0xFF, 0x05])),
                            scissor=scissor)
            zr = [(GD_ZMIN, -6000), (6000, GD_ZMAX), (-8000, 8000)][int(rng.integers(3))]
            cmds.append(("triangle", _big(rng, *zr), rs))
        elif r < 0.9:  # a lit or ambient pass
            sf, df = [(BF_ONE, BF_ONE), (BF_ONE, BF_ONE), (BF_ONE, BF_ZERO),
                      (BF_SA, BF_MSA)][int(rng.integers(4))]
            zfunc = int(rng.choice([CMP_EQUAL, CMP_EQUAL, CMP_LEQUAL, CMP_LESS, CMP_ALWAYS]))
            rs = full_state(W, H, zbuffer=True, zfunc=zfunc,
                            zwritemask=int(rng.choice([0, 0xFFFFFF])),
                            stencil=bool(rng.integers(2)),
                            sfunc=int(rng.choice([CMP_EQUAL, CMP_NOTEQUAL, CMP_LESS,
                                                  CMP_ALWAYS])),
                            sref=int(rng.integers(0, smax + 1)), blend_sf=sf, blend_df=df,
                            wmpack=int(rng.choice([0xFFFFFFFF, 0xFFFFFFFF, 0x00FF00FF])),
                            shademodel=int(rng.integers(2)), scissor=scissor)
            if cfg["double"]:  # front, back or (the general path) both
                front, back = [(True, False), (False, True), (True, True)][rng.integers(3)]
                rs = dataclasses.replace(rs, draw_front=front, draw_back=back)
            flat = rng.random() < 0.6
            cmds.append(("triangle", _big(rng, zclear - 3000, zclear + 3000, flat), rs))
        else:
            if rng.random() < 0.5:
                cmds.append(("flush",))
            cmds.append(("clear", {"z"}, {"z": int(rng.choice([zclear, -5000, 5000]))},
                         full_state(W, H, scissor=(int(rng.integers(0, W)), W - 1,
                                                   int(rng.integers(0, H)), H - 1))))
    init = random_planes(rng, W, H, **cfg) if rng.random() < 0.2 else None
    return cfg, init, cmds


def _same_work(got, want):
    g = {k: v for k, v in got.items() if k != "blocks_z_passed"}
    w = {k: v for k, v in want.items() if k != "blocks_z_passed"}
    return g == w


def test_block_update_changes_no_plane_on_random_scenes():
    rng = np.random.default_rng(7301)
    passed = 0
    variants = [dict(), dict(step_spans=False), dict(tight_tiles=False),
                dict(vector_pack=False), dict(nthreads=2), dict(span_zwrite=True)]
    for i in range(36):
        cfg, init, cmds = _scene(rng)
        v = dict(variants[i % len(variants)])
        n = v.pop("nthreads", 1)
        want, off = _render(cmds, cfg, init, n, block_update=False, **v)
        got, on = _render(cmds, cfg, init, n, block_update=True, **v)
        assert_planes_equal(got, want, f"scene {i} {v} threads={n}")
        assert _same_work(on, off), (i, on, off)
        assert off["blocks_z_passed"] == 0
        passed += on["blocks_z_passed"]
    # The scenes do take the block update (197 times with stencil_bounds on, which
    # skips the tiles of a stencil-testing pass that no stored stencil value passes:
    # those are no longer z-passed blocks; 200+ before it).
    assert passed > 150


def test_block_update_matches_naive():
    rng = np.random.default_rng(7400)
    passed = 0
    for i in range(5):
        cfg, init, cmds = _scene(rng)
        got, on = _render(cmds, cfg, init)
        want = render_naive(cmds, W, H, init=init, **cfg)
        assert_planes_equal(got, want, f"scene {i}")
        passed += on["blocks_z_passed"]
    assert passed > 0


def _quad(z, colour=(1.0, 1.0, 1.0, 1.0)):
    """Two triangles over the whole window at constant depth ``z``."""
    q = [(-0.5 + x, -0.5 + y, z, colour) for x, y in ((0, 0), (W, 0), (W, H), (0, H))]
    return [(q[0], q[1], q[2]), (q[0], q[2], q[3])]


@pytest.mark.parametrize("planes", [8, 3, 1])
@pytest.mark.parametrize("op", Z_PASS_OPS)
def test_stencil_ops_at_every_value(planes, op):
    """The z-pass op over a stencil plane holding every value 0..smax (each many
    times), applied twice by faces in front of a z clear (every tile passes): INCR
    saturates at smax, DECR at 0, the table ops as the naive reference.  Hand-checked
    for INCR and DECR, and equal to the switch off and to the naive reference."""
    smax = (1 << planes) - 1
    cfg = dict(double=False, zbits=24, stencil=planes)
    init = random_planes(np.random.default_rng(planes), W, H, **cfg)
    values = np.arange(W * H).reshape(H, W) % (smax + 1)
    init["stencil"][:] = values.astype(np.uint8)
    init["z"][:] = 1000
    vol = full_state(W, H, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0, stencil=True,
                     szpass=op, sref=5 & smax)
    cmds = [("triangle", t, vol) for t in _quad(-2000.0) + _quad(-1500.0)]
    got, on = _render(cmds, cfg, init)
    want, off = _render(cmds, cfg, init, block_update=False)
    assert_planes_equal(got, want, f"op {op} planes {planes}")
    assert _same_work(on, off)
    assert_planes_equal(got, render_naive(cmds, W, H, init=init, **cfg), "naive")
    # Full tiles only are updated as blocks: 3 whole tile columns x 4 tile rows, in
    # each of the four triangles that covers them (the diagonal leaves none whole to
    # both), so at least 3 * 4 tiles over the two quads.
    assert on["blocks_z_passed"] >= 12
    s = got["stencil"].astype(np.int64)
    if op == OP_INCR:
        assert (s == np.minimum(values + 2, smax)).all()
    elif op == OP_DECR:
        assert (s == np.maximum(values - 2, 0)).all()
    elif op == OP_KEEP:
        assert (s == values).all()


@pytest.mark.parametrize("zfunc", ZFUNCS)
@pytest.mark.parametrize("zwrite", [True, False])
def test_lit_and_depth_passes_over_flat_layers(zfunc, zwrite):
    """Flat layers at, in front of and behind a flat stored depth, under each
    zfunction: the lit pass (stencil EQUAL, ONE+ONE), a replace pass and a depth-only
    pass; the block update happens exactly where the z test is known to pass."""
    cfg = dict(double=True, zbits=24, stencil=8)
    init = random_planes(np.random.default_rng(5), W, H, **cfg)
    init["z"][:] = 500
    init["stencil"][:, ::3] = 0
    zmask = 0xFFFFFF if zwrite else 0
    lit = full_state(W, H, zbuffer=True, zfunc=zfunc, zwritemask=zmask, stencil=True,
                     sfunc=CMP_EQUAL, sref=0, blend_sf=BF_ONE, blend_df=BF_ONE)
    rep = full_state(W, H, zbuffer=True, zfunc=zfunc, zwritemask=zmask,
                     wmpack=0xFF00FFFF, draw_front=False, draw_back=True)
    dep = full_state(W, H, zbuffer=True, zfunc=zfunc, wmpack=0)
    cmds = []
    for z in (500.0, 200.0, 900.0):
        cmds += [("triangle", t, lit) for t in _quad(z, (0.2, 0.5, 0.7, 0.1))]
        cmds += [("triangle", t, rep) for t in _quad(z, (0.9, 0.1, 0.3, 0.4))]
    cmds += [("triangle", t, dep) for t in _quad(300.0)]
    got, on = _render(cmds, cfg, init)
    want, off = _render(cmds, cfg, init, block_update=False)
    assert_planes_equal(got, want, f"zfunc {zfunc}")
    assert _same_work(on, off)
    assert_planes_equal(got, render_naive(cmds, W, H, init=init, **cfg), "naive")
    if zfunc in (CMP_ALWAYS, CMP_LEQUAL, CMP_EQUAL):
        assert on["blocks_z_passed"] > 0  # the first layer, at the stored depth


def test_blocks_z_passed_hand_counted():
    """256 x 64 (4 x 2 tiles), z cleared to 0, one triangle over the whole window
    whose depth is 10 * (x - 127.5): negative over tile columns 0 and 1, positive over
    2 and 3.  Under zfunction(ZF_LESS) with stencil INCR on z pass the left four tiles
    are z-passed blocks, the right four are skipped; stencil 1 on the left half."""
    w, h = 256, 64
    fb = kernel_framebuffer(w, h, double=False, zbits=24, stencil=8)
    batch = CommandBatch(fb)
    clear = full_state(w, h)
    vol = full_state(w, h, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0, stencil=True,
                     szpass=OP_INCR)
    white = (1.0, 1.0, 1.0, 1.0)
    tri = tuple((x, y, 10.0 * (x - 127.5), white)
                for x, y in ((-300.0, -300.0), (1000.0, -300.0), (-300.0, 1000.0)))
    queue_commands(batch, [("clear", {"z", "stencil"}, {"z": 0, "stencil": 0}, clear),
                           ("triangle", tri, vol)])
    batch.reset_counters()
    batch.flush()
    work = batch.work()
    assert work["blocks_covered"] == 4
    assert work["blocks_z_passed"] == 4
    assert work["tiles_skipped"] == 4
    assert work["fragments"] == 128 * 64
    assert (fb.stencil[:, :128] == 1).all() and (fb.stencil[:, 128:] == 0).all()
    # Switched off: the same planes, the same tiles, no block update.
    fb.stencil[:] = 0
    batch.block_update = False
    queue_commands(batch, [("clear", {"z", "stencil"}, {"z": 0, "stencil": 0}, clear),
                           ("triangle", tri, vol)])
    batch.reset_counters()
    batch.flush()
    off = batch.work()
    assert off["blocks_z_passed"] == 0 and _same_work(off, work)
    assert (fb.stencil[:, :128] == 1).all() and (fb.stencil[:, 128:] == 0).all()


def _heidmann(monkeypatch, on, nthreads, **kw):
    from vgxsim.examples import heidmann1991 as h91
    from vgxsim.gl._core import current, session

    monkeypatch.setattr(CommandBatch, "block_update", on)
    keep = threads._override  # None: follow numba.set_num_threads (tests/kernels/test_threads.py)
    threads.set_threads(nthreads)
    session.reset()
    planes = {}

    def hook(i):
        ctx = current("test")
        ctx.flush()
        planes[i] = (ctx.fb.stencil.copy(), ctx.fb.z.copy(), ctx.batch.work())

    try:
        img = h91.render(1280, 1024, stencil_hook=hook, **kw)  # 64 x 32 tiles wholly inside faces
    finally:
        session.reset()
        threads.set_threads(keep)
    return img, planes


@pytest.mark.parametrize("nthreads", [1, 2])
def test_heidmann_frame_is_identical(monkeypatch, nthreads):
    want_img, want = _heidmann(monkeypatch, False, nthreads)
    img, got = _heidmann(monkeypatch, True, nthreads)
    np.testing.assert_array_equal(img, want_img)
    assert got.keys() == want.keys() and want
    for light in want:
        np.testing.assert_array_equal(got[light][0], want[light][0])
        np.testing.assert_array_equal(got[light][1], want[light][1])
        assert _same_work(got[light][2], want[light][2])
        assert want[light][2]["blocks_z_passed"] == 0
    assert got[max(got)][2]["blocks_z_passed"] > 0
