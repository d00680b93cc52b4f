"""The flush-time front end in a constant number of passes (``draw.FLUSH_FRONT``,
vgxsim/pipeline/flush_front.py) changes no plane.

The switch is checked on the 1991 shadow frame (lit floor and cubes under two
lights, shadow faces whose records differ in stencil state only, clears between the
passes) and on the random IRIS GL call sequences of tests/stream (every primitive
kind, lines and points between triangles, lmcolor, materials, shading model and
write masks changing between primitives), drawn immediately and from display
objects: colour, z and stencil must be identical, and the flush pass must really
have drawn.  Its kernel is checked against the kernels it stands for:
``light_object_runs`` (lighting) and ``transform_points`` (clip coordinates).
"""

import numpy as np
import pytest
from stream.random_calls import SEEDS, render, sequence

from vgxsim.geometry.pipeline import _tame
from vgxsim.gl._core import session
from vgxsim.kernels.front import light_transform_rows
from vgxsim.kernels.lighting import light_object_runs
from vgxsim.kernels.transform import transform_points
from vgxsim.pipeline import draw, flush_front


def _counting(monkeypatch):
    calls = [0]
    real = flush_front.draw_rows

    def counted(*a, **k):
        calls[0] += 1
        return real(*a, **k)

    monkeypatch.setattr(flush_front, "draw_rows", counted)
    return calls


def _heidmann(monkeypatch, on: bool):
    from vgxsim.examples import heidmann1991 as h91
    from vgxsim.gl._core import current

    monkeypatch.setattr(draw, "FLUSH_FRONT", on)
    calls = _counting(monkeypatch)
    session.reset()
    planes = {}

    def hook(i):
        ctx = current("test")
        ctx.flush()
        planes[i] = (ctx.fb.stencil.copy(), ctx.fb.z.copy())

    try:
        img = h91.render(320, 256, stencil_hook=hook)
    finally:
        session.reset()
    return img, planes, calls[0]


def test_flush_front_gives_the_same_heidmann_frame(monkeypatch):
    want_img, want, none = _heidmann(monkeypatch, False)
    img, got, passes = _heidmann(monkeypatch, True)
    assert none == 0 and passes > 0  # the switch really selects the path
    assert want and got.keys() == want.keys()
    np.testing.assert_array_equal(img, want_img)
    for light in want:
        np.testing.assert_array_equal(got[light][0], want[light][0])
        np.testing.assert_array_equal(got[light][1], want[light][1])


@pytest.mark.parametrize("objects", [False, True])
def test_flush_front_switch_gives_identical_planes_on_random_calls(objects, monkeypatch):
    calls_seen = _counting(monkeypatch)
    for seed in SEEDS:
        for n in (40, 120):
            calls = sequence(seed, n)
            session.reset()
            monkeypatch.setattr(draw, "FLUSH_FRONT", False)
            want = render(calls, objects=objects, seed=seed)
            session.reset()
            monkeypatch.setattr(draw, "FLUSH_FRONT", True)
            got = render(calls, objects=objects, seed=seed)
            session.reset()
            for k in want:
                assert np.array_equal(got[k], want[k]), (seed, n, k)
    assert calls_seen[0] > len(SEEDS)  # the flush pass drew in most sequences


def test_light_transform_rows_gives_the_lighting_and_transform_kernels_values():
    """Rows of three records (two lit, one lit where the normal was sent last, one
    unlit) under two light tables: per vertex, the colour light_object_runs gives
    with the record's run and lights, and the clip position transform_points gives
    with the record's matrix."""
    rng = np.random.default_rng(5)
    nv, nrec = 60, 3
    pos = np.concatenate([rng.normal(size=(nv, 3)) * 4, np.ones((nv, 1))], axis=1)
    pos[7, 3] = 0.0  # w = 0 in eye space too: divided by 1
    pos[8, :3] = [1e305, -3e304, 2e305]  # clip coordinates rescaled near overflow
    col = rng.random((nv, 4))
    nrm = rng.normal(size=(nv, 3))
    nrm[3] = 0.0  # zero normal: emission and ambient only
    sent = rng.random(nv) < 0.6
    row_v0 = np.array([0, 10, 25, 40], np.int64)
    row_v1 = np.array([10, 25, 40, 60], np.int64)
    row_rec = np.array([0, 1, 2, 0], np.int64)
    mvp = rng.normal(size=(nrec, 4, 4))
    light_mode = np.array([2, 1, 0], np.int64)
    modelview = rng.normal(size=(nrec, 4, 4))
    normal_matrix = rng.normal(size=(nrec, 3, 3))
    terms = [rng.random((nrec, 3)) for _ in range(4)]
    shininess = np.array([20.0, 0.5, 3.0])
    alpha = rng.random(nrec)
    lights = rng.random((3, 16))
    lights[:, 0] = [1.0, 0.0, 1.0]  # local, directional, local
    lights[:, 10] = [0.0, 0.0, 1.0]  # the last one a spot
    lights[2, 14] = 0.2
    light_lo = np.array([0, 2, 0], np.int64)
    light_hi = np.array([2, 3, 0], np.int64)
    lmodel = np.array([[0.2, 0.2, 0.2, 0.0, 1.0, 0.0, 0.0],
                       [0.1, 0.0, 0.3, 1.0, 1.0, 0.05, 0.01],
                       [0.0] * 7])
    clip_v = np.zeros((nv, 4))
    rgba = np.zeros((nv, 4))
    light_transform_rows(pos, col, nrm, sent, row_v0, row_v1, row_rec, mvp, light_mode,
                         modelview, normal_matrix, *terms, shininess, alpha, light_lo,
                         light_hi, lights, lmodel, 1.0, clip_v, rgba)
    for a, b, r in zip(row_v0, row_v1, row_rec, strict=True):
        np.testing.assert_array_equal(clip_v[a:b],
                                      _tame(transform_points(pos[a:b], mvp[r])))
        lit = sent[a:b] if light_mode[r] == 1 else np.full(b - a, light_mode[r] == 2)
        want = light_object_runs(pos[a:b], nrm[a:b], col[a:b], lit, np.zeros(b - a, np.int64),
                                 modelview[r:r + 1], normal_matrix[r:r + 1],
                                 *(t[r:r + 1] for t in terms), shininess[r:r + 1],
                                 alpha[r:r + 1], lights[light_lo[r]:light_hi[r]],
                                 lmodel[r], 1.0)
        np.testing.assert_array_equal(rgba[a:b], want)
    assert not np.array_equal(rgba[0:10], col[0:10])  # lit rows really changed colour
    np.testing.assert_array_equal(rgba[25:40], col[25:40])  # the unlit record kept it


def _with_projection_changes(calls, seed: int):
    """``calls`` with viewport, lsetdepth, subpixel and clipplane calls inserted at
    primitive boundaries, so one flush holds records of several projections (the
    flush pass then clips and projects per run of rows)."""
    from stream.random_calls import H, W

    from vgxsim import GL

    rng = np.random.default_rng(500 + seed)
    out, depth = [], 0
    for name, args in calls:
        out.append((name, args))
        depth += name.startswith("bgn") - name.startswith("end")
        if depth or rng.random() > 0.25:
            continue
        r = rng.random()
        if r < 0.3:
            l, b = (int(v) for v in rng.integers(0, 12, 2))
            out.append(("viewport", (l, int(rng.integers(l + 8, W)), b,
                                     int(rng.integers(b + 8, H)))))
        elif r < 0.5:
            out.append(("lsetdepth", (0, int(rng.integers(0x100000, 0x7FFFFF)))))
        elif r < 0.7:
            out.append(("subpixel", (int(rng.integers(0, 2)),)))
        elif r < 0.85:
            out.append(("clipplane", (0, GL.CP_DEFINE,
                                      tuple(float(v) for v in (*rng.normal(size=2), 0.0,
                                                               rng.uniform(0, W))))))
            out.append(("clipplane", (0, GL.CP_ON)))
        else:
            out.append(("clipplane", (0, GL.CP_OFF)))
    return out


def test_flush_front_switch_gives_identical_planes_across_projections(monkeypatch):
    """Viewports, depth ranges, snapping modes and user clip planes changing
    between primitives of one flush: identical planes with the switch on and off."""
    calls_seen = _counting(monkeypatch)
    drawn = 0
    for seed in SEEDS:
        calls = _with_projection_changes(sequence(seed, 120), seed)
        session.reset()
        monkeypatch.setattr(draw, "FLUSH_FRONT", False)
        want = render(calls)
        session.reset()
        monkeypatch.setattr(draw, "FLUSH_FRONT", True)
        got = render(calls)
        session.reset()
        for k in want:
            assert np.array_equal(got[k], want[k]), (seed, k)
        drawn += bool(want["rgba"][..., :3].any())
    assert calls_seen[0] > len(SEEDS) and drawn > len(SEEDS) // 2


def _row(kind, v0, v1, rec, lms=0):
    return [kind, v0, v1, rec, lms, 0, 0]


def test_fast_rows_takes_clears_and_the_triangles_of_plain_records():
    from vgxsim.kernels.front import fast_rows
    from vgxsim.stream.opcodes import CLEAR_KIND, LINE, POLYGON, QSTRIP, TMESH

    prims = np.array([_row(CLEAR_KIND, 0, 0, -1), _row(POLYGON, 0, 4, 0),
                      _row(QSTRIP, 4, 8, 1), _row(LINE, 8, 10, 0),
                      _row(TMESH, 10, 14, 2), _row(TMESH, 14, 18, 2, lms=1),
                      _row(POLYGON, 18, 21, 3)], np.int64)
    code = np.array([1, 1, 2, 0], np.int64)  # plain, plain, overridden when set, not plain
    fast, n = fast_rows(prims, code)
    assert fast.tolist() == [True, True, True, False, True, False, False] and n == 4


def test_flush_rows_keeps_rows_with_vertices_and_counts_from_the_first():
    from vgxsim.kernels.front import flush_rows
    from vgxsim.stream.opcodes import CLEAR_KIND, POLYGON, QSTRIP

    prims = np.array([_row(CLEAR_KIND, 0, 0, -1), _row(POLYGON, 10, 14, 0),
                      _row(POLYGON, 14, 14, 1), _row(QSTRIP, 14, 18, 2)], np.int64)
    rows, tri_rows, rec_of, v0, v1, vlo, vhi, nproj = flush_rows(
        prims, np.array([0, 0, 1], np.int64))
    assert rows[:, 0].tolist() == [CLEAR_KIND, POLYGON, QSTRIP]
    assert v0.tolist() == [0, 4] and v1.tolist() == [4, 8] and (vlo, vhi) == (10, 18)
    assert rec_of.tolist() == [0, 2] and nproj == 2
    assert tri_rows[:, 1].tolist() == [0, 4]


def test_flush_rows_copies_every_column():
    """Random rows: ``rows`` and ``tri_rows`` are the kept rows whole, as numpy's
    masked selection gives them (vertex columns of ``tri_rows`` shifted by vlo)."""
    from vgxsim.kernels.front import flush_rows
    from vgxsim.stream.opcodes import CLEAR_KIND, P_KIND, P_STATE, P_V0, P_V1, POLYGON

    rng = np.random.default_rng(12)
    for _ in range(20):
        n = int(rng.integers(1, 30))
        prims = rng.integers(-1000, 1000, (n, len(_row(POLYGON, 0, 0, 0)))).astype(np.int64)
        prims[:, P_KIND] = rng.choice([CLEAR_KIND, POLYGON], n)
        v0 = np.cumsum(rng.integers(0, 3, n))
        prims[:, P_V0] = v0
        prims[:, P_V1] = v0 + rng.integers(0, 3, n)
        prims[:, P_STATE] = rng.integers(0, 4, n)
        rows, tri_rows, rec_of, *_ = flush_rows(prims, np.arange(4, dtype=np.int64))
        clear = prims[:, P_KIND] == CLEAR_KIND
        keep = clear | (prims[:, P_V1] > prims[:, P_V0])
        np.testing.assert_array_equal(rows, prims[keep])
        want = prims[~clear & keep].copy()
        if len(want):
            lo = want[0, P_V0]
            want[:, P_V0] -= lo
            want[:, P_V1] -= lo
        np.testing.assert_array_equal(tri_rows, want)
        np.testing.assert_array_equal(rec_of, want[:, P_STATE])


def test_flush_segments_cuts_at_clears_and_classes():
    """Rows: clear, two of class 0 (rasters 0 and 1), one of class 1, clear, one of
    class 1; clipped triangles 0..5 from assembled triangles whose rows are known,
    one assembled triangle clipped away and one fanned into two."""
    from vgxsim.kernels.front import flush_segments
    from vgxsim.stream.opcodes import CLEAR_KIND, POLYGON

    rows = np.array([_row(CLEAR_KIND, 0, 0, -1), _row(POLYGON, 0, 4, 0),
                     _row(POLYGON, 4, 8, 1), _row(POLYGON, 8, 12, 2),
                     _row(CLEAR_KIND, 0, 0, -1), _row(POLYGON, 12, 16, 3)], np.int64)
    rec_of = np.array([0, 1, 2, 3], np.int64)
    klass = np.array([0, 0, 1, 1], np.int64)
    rast = np.array([0, 1, 1, 2], np.int64)
    colour = np.array([0, 1, 0, 0], np.int64)
    tri_row = np.array([0, 0, 1, 1, 2, 2, 3, 3], np.int64)  # two triangles per row
    out_src = np.array([0, 1, 2, 2, 4, 6, 7], np.int64)  # 3 and 5 gone, 2 fanned
    segs, out_rast, present, local = flush_segments(rows, rec_of, klass, rast, colour,
                                                    tri_row, out_src)
    # first row, clear, t0, t1, several rasters, colour
    assert segs.tolist() == [[0, 1, 0, 0, 0, 0], [1, 0, 0, 4, 1, 1], [3, 0, 4, 5, 0, 0],
                             [4, 1, 0, 0, 0, 0], [5, 0, 5, 7, 0, 0]]
    assert out_rast.tolist() == [0, 0, 1, 1, 1, 2, 2]
    assert present[1].tolist() == [True, True, False] and present[4].tolist() == [
        False, False, True]
    assert local.tolist() == [0, 0, 1, 1, 0, 0, 0]


def test_tables_give_light_transform_rows_one_signature_for_any_record_count(monkeypatch):
    """The lighting columns are contiguous for one record and for many: a column
    view's layout follows the record count (numpy's flags), and Numba would compile
    light_transform_rows once per layout (cold start, docs/cold_start.md)."""
    import numba

    seen = []
    real = flush_front.Tables.__init__

    def spy(self, records, memo=None):
        seen.append(list(records))
        real(self, records, memo)

    monkeypatch.setattr(flush_front.Tables, "__init__", spy)
    _heidmann(monkeypatch, True)
    monkeypatch.setattr(flush_front.Tables, "__init__", real)
    records = max(seen, key=len)
    assert len(records) > 1

    def signature(tab):
        args = (tab.mvp, tab.light_mode, tab.modelview, tab.normal_matrix, *tab.terms,
                tab.shininess, tab.alpha, tab.light_lo, tab.light_hi, tab.lights, tab.lmodel)
        return tuple(numba.typeof(a) for a in args)

    one, many = signature(flush_front.Tables(records[:1])), signature(flush_front.Tables(records))
    assert one == many
    assert all(t.layout == "C" for t in many)
