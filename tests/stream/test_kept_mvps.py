"""vgxsim.state.matrices.KEEP_MVPS: the composite kept per top matrix, so popmatrix
returns to the mvp object of the matrix it pops back to (and pushmatrix keeps it).
Random IRIS GL call sequences with matrix calls between primitives (push/translate/
rot/scale/pop, projections loaded while pushed, mmode switches) give identical
colour, z and stencil planes with the switch on and off, immediately and through
nested display objects; the matrices read back are the products mmode(3G) and
pushmatrix(3G) define, computed here with numpy; and the kept product is found
again only for the very top and projection it was made of."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl._core import session
from vgxsim.state import matrices

from .random_calls import SEEDS, render, sequence

W, H = 48, 40


@pytest.fixture(autouse=True)
def _fresh():
    session.reset()
    yield
    session.reset()


def _with_matrices(calls: list, seed: int) -> list:
    """``calls`` with more matrix traffic at primitive boundaries: rotations and
    scalings inside push/pop pairs, an ortho (which loads the single matrix) while
    pushed, and now and then pushmatrix/popmatrix around nothing."""
    rng = np.random.default_rng(700 + seed)
    out, depth, open_prim = [], 0, 0
    for name, args in calls:
        if name == "pushmatrix":
            depth += 1
        elif name == "popmatrix":
            depth -= 1
        open_prim += name.startswith("bgn") - name.startswith("end")
        out.append((name, args))
        if open_prim or not name.startswith("end"):
            continue
        r = rng.random()
        if r < 0.15 and depth < 20:
            out.append(("pushmatrix", ()))
            out.append(("rot", (float(rng.uniform(-20, 20)), "z")))
            out.append(("scale", (float(rng.uniform(0.8, 1.2)), 1.0, 1.0)))
            depth += 1
        elif r < 0.22 and depth < 20:
            out.append(("pushmatrix", ()))
            out.append(("ortho", (-0.5 + float(rng.uniform(-3, 3)), W - 0.5, -0.5, H - 0.5,
                                  -1.0, 1.0)))
            depth += 1
        elif r < 0.3 and depth:
            out.append(("popmatrix", ()))
            depth -= 1
        elif r < 0.34 and depth < 20:
            out.append(("pushmatrix", ()))
            out.append(("popmatrix", ()))
    return out


def _render(calls, objects: bool, seed: int, keep: bool, monkeypatch) -> dict:
    monkeypatch.setattr(matrices, "KEEP_MVPS", keep)
    session.reset()
    try:
        return render(calls, objects=objects, seed=seed)
    finally:
        session.reset()


@pytest.mark.parametrize("objects", [False, True])
@pytest.mark.parametrize("seed", list(SEEDS))
def test_kept_mvps_switch_gives_identical_planes(seed, objects, monkeypatch):
    calls = _with_matrices(sequence(seed, n=60), seed)
    assert sum(c[0] == "popmatrix" for c in calls) >= 2
    a = _render(calls, objects, seed, True, monkeypatch)
    b = _render(calls, objects, seed, False, monkeypatch)
    assert a["rgba"][..., :3].any() or a["stencil"].any()
    for k in a:
        assert np.array_equal(a[k], b[k]), k
    if not objects:
        c = _render(calls, True, seed, True, monkeypatch)
        for k in a:
            assert np.array_equal(a[k], c[k]), k


def _translation(x, y, z):
    m = np.eye(4)
    m[3, :3] = (x, y, z)
    return m


@pytest.mark.parametrize("keep", [True, False])
def test_popmatrix_returns_to_the_product_of_the_matrix_below(keep, monkeypatch):
    """In MVIEWING the composite is modelview @ projection (row vectors, IRIS
    premultiplies); after push, translate and pop it is the product before the
    push again -- the same object with KEEP_MVPS -- and a projection loaded while
    pushed is not forgotten by the pop."""
    monkeypatch.setattr(matrices, "KEEP_MVPS", keep)
    gl.prefsize(W, H)
    gl.winopen("kept mvps")
    mats = session.windows[session.current].matrices
    gl.mmode(GL.MVIEWING)
    gl.ortho(-4.0, 4.0, -3.0, 3.0, -5.0, 5.0)
    proj = np.array(mats.projection)
    gl.translate(1.0, 0.5, 0.0)
    mv = _translation(1.0, 0.5, 0.0)
    before = mats.mvp()
    assert np.array_equal(before, mv @ proj)
    gl.pushmatrix()
    assert mats.mvp() is before or not keep
    gl.translate(0.0, 2.0, 1.0)
    inner = mats.mvp()
    assert np.array_equal(inner, _translation(0.0, 2.0, 1.0) @ mv @ proj)
    gl.popmatrix()
    after = mats.mvp()
    assert np.array_equal(after, mv @ proj)
    assert (after is before) == keep
    # A projection loaded while pushed: the pop keeps it, and the kept product of
    # the old projection is not taken for the new one.
    gl.pushmatrix()
    gl.ortho(-8.0, 8.0, -6.0, 6.0, -5.0, 5.0)
    proj2 = np.array(mats.projection)
    gl.popmatrix()
    assert np.array_equal(mats.mvp(), mv @ proj2)
    assert not np.array_equal(mv @ proj2, mv @ proj)
    # The normal matrix follows the modelview alike.
    nm = mats.normal_matrix()
    gl.pushmatrix()
    gl.rot(30.0, "x")
    assert not np.array_equal(mats.normal_matrix(), nm)
    gl.popmatrix()
    assert np.array_equal(mats.normal_matrix(), np.linalg.inv(mv[:3, :3]).T)
