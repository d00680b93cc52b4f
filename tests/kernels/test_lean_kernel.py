"""The lean band kernel (kernels/render.py render_bands_lean, CommandBatch.lean_kernel)
draws what the full one draws.

``render_bands_lean`` is the band kernel compiled without its rare paths (the general
per-fragment rows with the texture stage, the slow colour span, SA+MSA blend
spans, fragment runs), so
a cold start does not compile them for a first image that never runs them; the
batch takes it only where :func:`lean_fits` says no primitive can reach those
paths.  Checked: ``lean_fits`` on states of every derived mode, and random scenes
with the switch on and off -- scenes of span-loop states only (the lean kernel
must be the one that runs) and scenes with one rare-path state, line or point
mixed in (the full kernel must run) -- identical planes and work counters, and
the naive reference on a few.
"""

import dataclasses

import numpy as np
import pytest
from kernel_helpers import assert_planes_equal, full_state, render_naive
from test_lit_spans import H, W, _render, _scene, _tri

import vgxsim.batch as batch_mod
from vgxsim.kernels.render import lean_fits
from vgxsim.state.codes import LO_XOR
from vgxsim.state.derive import derive_states
from vgxsim.state.raster import (
    BF_MSA,
    BF_ONE,
    BF_SA,
    BF_ZERO,
    CMP_GREATER,
    CMP_LESS,
    OP_INCR,
)

#: States that only the full kernel draws, and why.
RARE = {
    "no z test": full_state(W, H, zbuffer=False),                     # _colour_span_slow
    "general blend": full_state(W, H, zbuffer=True, blend_sf=BF_SA,   # _colour_span_slow
                                blend_df=BF_ONE),
    "logicop": full_state(W, H, zbuffer=True, logicop=LO_XOR),         # _general_row
    "alpha test": full_state(W, H, zbuffer=True, afunc=CMP_GREATER,    # _general_row
                             aref=100),
    "both buffers": full_state(W, H, zbuffer=True, draw_front=True,  # _general_row
                               draw_back=True),  # (double-buffered windows only)
    "alpha blend": full_state(W, H, zbuffer=True, blend_sf=BF_SA,     # _alpha_span
                              blend_df=BF_MSA),
}
SPANS = {
    "depth": full_state(W, H, zbuffer=True),
    "volume": full_state(W, H, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0,
                         stencil=True, szpass=OP_INCR),
    "depth only": full_state(W, H, zbuffer=True, wmpack=0),
    "add": full_state(W, H, zbuffer=True, blend_sf=BF_ONE, blend_df=BF_ONE),
    "replace": full_state(W, H, zbuffer=True, blend_sf=BF_ONE, blend_df=BF_ZERO),
}


def _derived(*states, stencil=8):
    rows = np.stack([s.as_row() for s in states])
    return derive_states(rows, stencil, True, True)[0]


def test_lean_fits_span_states_only():
    assert lean_fits(_derived(*SPANS.values()), 0, False, False)
    assert lean_fits(_derived(*SPANS.values())[:0], 0, False, False)  # clears only
    for name, rare in RARE.items():
        assert not lean_fits(_derived(*SPANS.values(), rare), 0, False, False), name
    spans = _derived(*SPANS.values())
    assert not lean_fits(spans, 1, False, False)      # a point or line run
    assert not lean_fits(spans, 0, True, False)       # edge_mode
    assert not lean_fits(spans, 0, False, True)       # general_only


class _Spy:
    """Counts the calls of one band kernel (the batch calls it by module name)."""

    def __init__(self, monkeypatch, name):
        self.calls = 0
        if batch_mod.CommandBatch.borrow_arrays:  # its entry on borrowed arrays
            name += "_borrowed"
        real = getattr(batch_mod, name)

        def call(*args):
            self.calls += 1
            return real(*args)

        monkeypatch.setattr(batch_mod, name, call)


def _with_rare(rng, cmds, double):
    """``cmds`` with one rare-path triangle, line or point inserted somewhere."""
    cmds = list(cmds)
    rare = [rs for name, rs in RARE.items() if double or name != "both buffers"]
    kind = int(rng.integers(len(rare) + 2))
    at = int(rng.integers(1, len(cmds) + 1))
    if kind < len(rare):
        rs = rare[kind]
        cmds.insert(at, ("triangle", _tri(rng, 120, -3000, 3000), rs))
    else:
        white = (1.0, 0.5, 0.25, 1.0)
        rs = full_state(W, H, zbuffer=True)
        a = (float(rng.uniform(0, W)), float(rng.uniform(0, H)), 0.0, white)
        b = (float(rng.uniform(0, W)), float(rng.uniform(0, H)), 0.0, white)
        cmds.insert(at, ("line", (a, b), rs, 0) if kind == len(rare) else ("point", a, rs))
    return cmds


def _spans_only(cmds):
    """The lit scenes' SA+MSA layers made ONE+ONE: span-loop states only."""
    return [(c[0], c[1], dataclasses.replace(c[2], blend_df=BF_ONE, blend_sf=BF_ONE))
            if c[0] == "triangle" and c[2].blend_df == BF_MSA else c for c in cmds]


@pytest.mark.parametrize("rare", [False, True])
def test_lean_kernel_changes_no_plane(monkeypatch, rare):
    rng = np.random.default_rng(4411 + rare)
    for i in range(10):
        cfg, init, cmds = _scene(rng)
        if rare:
            cmds = _with_rare(rng, cmds, cfg["double"])
        else:
            cmds = _spans_only(cmds)
        n = 2 if i % 3 == 2 else 1
        want, off = _render(cmds, cfg, init, n, lean_kernel=False)
        lean = _Spy(monkeypatch, "render_bands_lean")
        full = _Spy(monkeypatch, "render_bands")
        got, on = _render(cmds, cfg, init, n, lean_kernel=True)
        # rare: the full kernel must have run (lean_fits said no); else the lean one
        ran, idle = (full, lean) if rare else (lean, full)
        assert ran.calls > 0 and idle.calls == 0, (i, rare)
        assert_planes_equal(got, want, f"scene {i} threads={n} rare={rare}")
        assert on == off and on["fragments"] > 0
        if i < 3:
            assert_planes_equal(got, render_naive(cmds, W, H, init=init, **cfg), "naive")
        monkeypatch.undo()


def test_rare_state_unused_by_triangles_keeps_lean(monkeypatch):
    """A clear's state does not pick the full kernel (only triangles' states count)."""
    rng = np.random.default_rng(5)
    cfg, init, cmds = _scene(rng)
    cmds = [(c[0], c[1], c[2], dataclasses.replace(c[3], zbuffer=False, logicop=LO_XOR))
            if c[0] == "clear" else c for c in _spans_only(cmds)]
    lean = _Spy(monkeypatch, "render_bands_lean")
    got, _ = _render(cmds, cfg, init, 1, lean_kernel=True)
    assert lean.calls == 1
    assert_planes_equal(got, render_naive(cmds, W, H, init=init, **cfg), "naive")
