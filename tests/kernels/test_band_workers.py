"""CommandBatch.band_workers: a flush's bands taken by one loop per thread (the
caller one of them, vgxsim/threads.py run_each) instead of one pool task per band.
Bands are disjoint rows, so the planes and the work counters must not change; the
naive oracle checks the picture independently."""

import threading

import numpy as np
import pytest
from kernel_helpers import (
    assert_planes_equal,
    heidmann_images,
    kernel_batch,
    kernel_framebuffer,
    planes_of,
    queue_commands,
    random_planes,
    render_naive,
)
from test_threads import heavy_scene

from vgxsim import threads
from vgxsim.batch import CommandBatch


@pytest.fixture
def restore_threads():
    keep = threads._override
    yield
    threads.set_threads(keep)


def _render(cmds, w, h, init, cfg):
    fb = kernel_framebuffer(w, h, init=init, **cfg)
    batch = kernel_batch(fb)
    queue_commands(batch, cmds)
    batch.flush()
    return planes_of(fb), batch.counters.copy(), batch.flushes


@pytest.mark.parametrize("n", [2, 3])
def test_band_workers_on_off_identical_and_naive(monkeypatch, n, restore_threads):
    threads.set_threads(n)
    w, h = 96, 200  # 32-row bands (7), the last one partial
    rng = np.random.default_rng(77)
    cmds = heavy_scene(rng, w, h, 300)
    cfg = dict(double=True, zbits=24, stencil=8)
    init = random_planes(rng, w, h, **cfg)
    got = {}
    for on in (False, True, False, True):
        monkeypatch.setattr(CommandBatch, "band_workers", on)
        planes, counters, flushes = _render(cmds, w, h, init, cfg)
        if on in got:
            assert_planes_equal(planes, got[on][0], f"band_workers={on} repeat")
        got[on] = (planes, counters, flushes)
    assert_planes_equal(got[True][0], got[False][0], "band_workers on vs off")
    np.testing.assert_array_equal(got[True][1], got[False][1])
    assert got[True][1][0] > 0  # fragments were tested
    assert got[True][2] == got[False][2] > 1
    assert_planes_equal(got[True][0], render_naive(cmds, w, h, init=init, **cfg), "naive")


def test_band_workers_submit_one_task_per_extra_thread(monkeypatch, restore_threads):
    """With the switch on, a flush submits ``nthreads - 1`` pool tasks, not one per
    band; off, one per band (the switch really selects the path)."""
    threads.set_threads(2)
    submitted = []
    real = threads.pool

    class Counting:
        def __init__(self, ex):
            self.ex = ex

        def submit(self, fn, *args):
            submitted.append(fn)
            return self.ex.submit(fn, *args)

    monkeypatch.setattr(threads, "pool", lambda n: Counting(real(n)))
    rng = np.random.default_rng(3)
    w, h = 64, 512  # 2 threads: 32-row bands, 16 of them
    cmds = [c for c in heavy_scene(rng, w, h, 60) if c[0] != "flush"]
    cfg = dict(double=False, zbits=24, stencil=8)
    for on, want in ((True, 1), (False, 16)):
        monkeypatch.setattr(CommandBatch, "band_workers", on)
        submitted.clear()
        _render(cmds, w, h, None, cfg)
        assert len(submitted) == want, on


@pytest.mark.parametrize("n", [1, 2, 4])
def test_run_each_takes_every_item_once(n):
    seen, lock = [], threading.Lock()

    def fn(item):
        with lock:
            seen.append(item)

    threads.run_each(n, fn, list(range(37)))
    assert sorted(seen) == list(range(37))
    threads.run_each(n, fn, [])


def test_run_each_reraises():
    def fn(item):
        if item == 5:
            raise RuntimeError("band 5")

    with pytest.raises(RuntimeError, match="band 5"):
        threads.run_each(2, fn, list(range(10)))


@pytest.mark.parametrize("nthreads", [1, 2])
def test_heidmann_frame_is_identical(monkeypatch, nthreads):
    images = heidmann_images(monkeypatch, "band_workers", nthreads)
    np.testing.assert_array_equal(images[True], images[False])
    assert images[True].any()
