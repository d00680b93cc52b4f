"""Per-tile stencil bounds (CommandBatch.stencil_bounds, kernels/tiles.py) change
nothing drawn.

A stencil-testing colour pass (Heidmann's lit pass: stencil EQUAL to the "zero"
after the shadow faces) skips the tiles where its test fails for every stored
stencil value and runs those where it passes for every one without the test.
Random layered scenes (a depth pass, stencil-writing volume faces, clears, lines,
then lit passes with stencil tests; every rasterizer path, 1 and 2 threads) and the
Heidmann frame are rendered with the switch on and off and compared plane by
plane; a hand-counted quad checks the counters and that a stencil write after a
lit pass makes the next one read the plane again.
"""

import dataclasses

import numpy as np
from kernel_helpers import (
    assert_planes_equal,
    full_state,
    heidmann_images,
    render_naive,
    render_switched,
)
from test_work_skipping import layered_scene

from vgxsim.batch import WORK_NAMES, CommandBatch
from vgxsim.state.raster import BF_ONE, CMP_ALWAYS, CMP_EQUAL, CMP_LESS, OP_INCR


def _render(cmds, w, h, cfg, init, on, mode="span", nthreads=1):
    return render_switched(cmds, w, h, cfg=cfg, init=init, nthreads=nthreads, mode=mode,
                           stencil_bounds=on)


def test_stencil_bounds_change_no_plane_on_layered_scenes():
    rng = np.random.default_rng(4242)
    w, h = 200, 150
    skipped = untested = 0
    for i in range(30):
        cfg, init, cmds = layered_scene(rng, w, h)
        # Everything but the clears once more: stencil writes after a lit pass has
        # found bounds, then a lit pass that must read the plane again.
        cmds = cmds + [c for c in cmds if c[0] not in ("clear", "flush")]
        # And the lit triangles as the lit_equal_fill workload draws them: z writes
        # off, ONE+ONE (the ZF_EQUAL loop of lit_span_lanes).
        cmds += [("triangle", c[1], dataclasses.replace(c[2], zwritemask=0, blend_sf=BF_ONE,
                                                        blend_df=BF_ONE))
                 for c in cmds if c[0] == "triangle" and c[2].zfunc == CMP_EQUAL
                 and c[2].stencil and c[2].sfunc == CMP_EQUAL]
        n = 2 if i % 3 == 2 else 1
        modes = ("span", "general", "edge") if i % 5 == 0 else ("span",)
        for mode in modes:
            want, off = _render(cmds, w, h, cfg, init, False, mode, n)
            got, on = _render(cmds, w, h, cfg, init, True, mode, n)
            assert_planes_equal(got, want, f"scene {i} mode={mode} threads={n}")
            assert off["stencil_scanned"] == off["stencil_skipped"] == 0
            assert off["stencil_untested"] == 0
            assert on["fragments"] <= off["fragments"]
            if mode == "span":
                skipped += on["stencil_skipped"]
                untested += on["stencil_untested"]
        if i < 3:
            assert_planes_equal(got, render_naive(cmds, w, h, init=init, **cfg), "naive")
    assert skipped > 20 and untested > 20  # the scenes reach both decisions


def test_counters_and_a_stencil_write_between_lit_passes():
    """128 x 64, two tiles of 64 x 32 per tile row: stencil cleared to 0, a volume
    quad INCRs the left half (x < 64) to 1; a lit quad (stencil EQUAL 0, ONE+ONE)
    then draws the right half only: the left tiles are skipped, the right ones run
    without the stencil test, and exactly the 64 x 64 right pixels are tested.  A
    second volume quad INCRs the right half to 1, and a lit quad with stencil EQUAL 1
    must draw everywhere: the bounds the first lit pass found for the right tiles are
    forgotten (the left ones still hold)."""
    w, h = 128, 64
    cfg = dict(double=False, zbits=24, stencil=8)
    clear = full_state(w, h)
    vol = full_state(w, h, zbuffer=True, zfunc=CMP_ALWAYS, zwritemask=0, wmpack=0,
                     stencil=True, szpass=OP_INCR)

    def lit(ref):
        return full_state(w, h, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, stencil=True,
                          sfunc=CMP_EQUAL, sref=ref, blend_sf=BF_ONE, blend_df=BF_ONE)

    def quad(x0, x1, rgba, rs):
        q = [(x - 0.5, y - 0.5, 0.0, rgba) for x, y in ((x0, 0), (x1, 0), (x1, h), (x0, h))]
        return [("triangle", (q[0], q[1], q[2]), rs), ("triangle", (q[0], q[2], q[3]), rs)]

    red, green = (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0)
    first = ([("clear", {"color", "z", "stencil"}, {"color": 0, "z": 1000, "stencil": 0},
               clear)] + quad(0, 64, red, vol) + quad(0, w, red, lit(0)))
    want, off = _render(first, w, h, cfg, None, False)
    got, on = _render(first, w, h, cfg, None, True)
    assert_planes_equal(got, want, "first lit pass")
    colour = got["front"]
    assert (colour[:, 64:] == 0xFF0000FF).all() and (colour[:, :64] == 0).all()
    assert off["fragments"] == 64 * h + w * h
    assert on["fragments"] == 64 * h + 64 * h  # the volume's half, then the lit right half
    assert on["stencil_skipped"] > 0 and on["stencil_untested"] > 0
    assert on["stencil_scanned"] == 4  # each tile once (2 x 2 tiles)
    second = first + quad(64, w, red, vol) + quad(0, w, green, lit(1))
    want, _ = _render(second, w, h, cfg, None, False)
    got, on = _render(second, w, h, cfg, None, True)
    assert_planes_equal(got, want, "second lit pass")
    assert (got["front"][:, :64] == 0xFF00FF00).all()
    assert (got["front"][:, 64:] == 0xFF00FFFF).all()
    # The second volume quad wrote the right tiles only: those two are read again.
    assert on["stencil_scanned"] == 4 + 2


def test_heidmann_frame_is_identical(monkeypatch):
    for n in (1, 2):
        images = heidmann_images(monkeypatch, "stencil_bounds", n)
        np.testing.assert_array_equal(images[True], images[False])


def test_heidmann_frame_skips_shadowed_tiles(monkeypatch):
    """The 1991 frame's lit passes skip tiles inside shadows and leave the stencil
    test out over the unshadowed ones: fewer fragments tested, same image."""
    from vgxsim.examples import heidmann1991 as h91
    from vgxsim.gl._core import session

    real_flush = CommandBatch.flush
    work = {}
    images = {}
    for on in (False, True):
        total = np.zeros(len(WORK_NAMES), np.int64)

        def flush(self, total=total):
            before = self.counters.copy()
            real_flush(self)
            total += self.counters - before

        monkeypatch.setattr(CommandBatch, "flush", flush)
        monkeypatch.setattr(CommandBatch, "stencil_bounds", on)
        session.reset()
        try:
            images[on] = h91.render(640, 512)
        finally:
            session.reset()
        work[on] = {k: int(v) for k, v in zip(WORK_NAMES, total, strict=True)}
    np.testing.assert_array_equal(images[True], images[False])
    assert work[False]["stencil_skipped"] == 0
    assert work[True]["stencil_skipped"] > 0 and work[True]["stencil_untested"] > 0
    assert work[True]["fragments"] < work[False]["fragments"]

