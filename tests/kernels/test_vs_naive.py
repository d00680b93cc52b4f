"""Random small scenes: CommandBatch (span path, general-only path, edge-function
path) against the naive oracle, bit for bit on every plane.

Each example draws a plane configuration (single/double buffer, z or not, 0-8
stencil planes), random initial plane contents, a pool of random RasterStates
covering every field the oracle reads, and 1-12 commands (triangles, lines, points,
clears; the kernel side also gets random extra flushes).
"""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from kernel_helpers import (
    assert_planes_equal,
    full_state,
    kernel_framebuffer,
    planes_of,
    random_planes,
    render_kernels,
    render_naive,
)

from vgxsim.batch import CommandBatch
from vgxsim.reference.naive import GD_ZMAX, GD_ZMIN
from vgxsim.state.codes import (
    D_MODE,
    MODE_COLOUR,
    MODE_GENERAL,
    MODE_ZONLY,
    MODE_ZSTENCIL,
    MODE_ZSTENCIL_ADD,
)
from vgxsim.state.derive import derive_states
from vgxsim.state.raster import (
    BF_MSA,
    BF_SA,
    CMP_ALWAYS,
    CMP_EQUAL,
    CMP_LEQUAL,
    CMP_LESS,
    OP_DECR,
    OP_INCR,
    OP_KEEP,
    ROW,
    RasterState,
)

W, H = 24, 20
MODES = ("span", "general", "edge")

SETTINGS = settings(max_examples=150, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


def _coord(lo, hi):
    return st.one_of(
        st.integers(lo, hi).map(float),  # pixel centres
        st.integers(lo * 2, hi * 2).map(lambda v: v / 2),  # snapping ties
        st.integers(lo * 256, hi * 256).map(lambda v: v / 256),  # exact fixed point
        st.floats(lo - 0.5, hi + 0.5, allow_nan=False, allow_infinity=False),
    )


XS = _coord(-4, W + 3)
YS = _coord(-4, H + 3)
ZS = st.one_of(
    st.sampled_from([0.0, 1000.0, -1000.0, float(GD_ZMIN), float(GD_ZMAX), 0.5, -0.5]),
    st.integers(GD_ZMIN, GD_ZMAX).map(float),
    st.floats(GD_ZMIN, GD_ZMAX),
    st.floats(-300.0, 300.0),
)
CHAN = st.one_of(st.sampled_from([0.0, 1.0, 0.5, 128 / 255, 127.5 / 255]),
                 st.floats(0.0, 1.0))
COLOUR = st.tuples(CHAN, CHAN, CHAN, CHAN)
VERT = st.tuples(XS, YS, ZS, COLOUR)
MASK32 = st.one_of(st.just(0xFFFFFFFF), st.just(0),
                   st.sampled_from([0xFF, 0xFF00FF00, 0x00FFFFFF, 0xFF000000, 0x00800000]),
                   st.integers(0, 0xFFFFFFFF))
MASK8 = st.one_of(st.just(0xFF), st.sampled_from([0, 1, 0x0F, 0xF0]), st.integers(0, 255))


@st.composite
def scissors(draw):
    if not draw(st.booleans()):
        return (0, W - 1, 0, H - 1)
    x0 = draw(st.integers(0, W - 1))
    x1 = draw(st.integers(x0, W - 1))
    y0 = draw(st.integers(0, H - 1))
    y1 = draw(st.integers(y0, H - 1))
    return (x0, x1, y0, y1)


def _often(default, strategy):
    """``default`` half of the time (so that most fragments get through), else any."""
    return st.one_of(st.just(default), strategy)


@st.composite
def random_states(draw):
    sf, df = draw(st.one_of(st.just((1, 0)), st.just((BF_SA, BF_MSA)),
                            st.tuples(st.integers(0, 8), st.integers(0, 7))))
    front = draw(st.booleans())
    return RasterState(
        zbuffer=draw(st.booleans()),
        zfunc=draw(_often(CMP_LEQUAL, st.integers(0, 7))),
        zwritemask=draw(MASK32),
        stencil=draw(st.booleans()),
        sref=draw(st.integers(0, 255)),
        sfunc=draw(_often(CMP_ALWAYS, st.integers(0, 7))),
        smask=draw(MASK8),
        sfail=draw(st.integers(0, 5)),
        spass=draw(st.integers(0, 5)),
        szpass=draw(st.integers(0, 5)),
        swritemask=draw(MASK8),
        blend_sf=sf,
        blend_df=df,
        logicop=draw(_often(3, st.integers(0, 15))),
        wmpack=draw(MASK32),
        afunc=draw(_often(CMP_ALWAYS, st.integers(0, 7))),
        aref=draw(st.integers(0, 255)),
        shademodel=draw(st.integers(0, 1)),
        subpixel=draw(st.booleans()),
        cull=draw(_often(0, st.integers(0, 3))),
        draw_front=front,
        draw_back=draw(st.booleans()) if front else True,
        scissor=draw(scissors()),
        linewidth=draw(st.integers(1, 4)),
        linestyle=draw(_often(0xFFFF, st.integers(0, 0xFFFF))),
        lsrepeat=draw(st.integers(1, 3)),
        pntsize=draw(st.integers(1, 4)),
    )


@st.composite
def shadow_states(draw):
    """States of the 1991 passes, which take the kernels' fast span paths."""
    kind = draw(st.sampled_from(["zstencil", "zonly", "lit"]))
    common = dict(
        zbuffer=True, subpixel=draw(st.booleans()), cull=draw(st.integers(0, 2)),
        draw_front=draw(st.booleans()), draw_back=draw(st.booleans()),
        scissor=draw(scissors()),
    )
    if kind == "zstencil":  # shadow-volume faces: no colour, no z write
        return RasterState(
            zfunc=draw(st.sampled_from([CMP_LESS, CMP_LEQUAL, CMP_EQUAL, CMP_ALWAYS])),
            zwritemask=0, stencil=True, sfunc=draw(st.sampled_from([CMP_ALWAYS, 3, 2])),
            sref=draw(st.integers(0, 3)),
            spass=draw(st.sampled_from([OP_KEEP, OP_INCR, OP_DECR])),
            szpass=draw(st.sampled_from([OP_KEEP, OP_INCR, OP_DECR, 5])),
            wmpack=draw(st.sampled_from([0, 0xFFFFFFFF])) if not (
                common["draw_front"] or common["draw_back"]) else 0,
            **common,
        )
    if kind == "zonly":  # depth pre-pass
        return RasterState(zfunc=draw(st.integers(0, 7)), wmpack=0, **common)
    return RasterState(  # lit pass: stencil EQUAL 0, z EQUAL
        zfunc=CMP_EQUAL, stencil=True, sfunc=CMP_EQUAL, sref=0,
        shademodel=draw(st.integers(0, 1)), **common,
    )


@st.composite
def commands(draw, pool):
    kind = draw(st.sampled_from(["triangle"] * 6 + ["line"] * 2 + ["point"] * 2
                                + ["clear", "flush"]))
    rs = pool[draw(st.integers(0, len(pool) - 1))]
    if kind == "triangle":
        return ("triangle", tuple(draw(st.tuples(VERT, VERT, VERT))), rs)
    if kind == "line":
        return ("line", tuple(draw(st.tuples(VERT, VERT))), rs, draw(st.integers(0, 40)))
    if kind == "point":
        return ("point", draw(VERT), rs)
    if kind == "clear":
        planes = draw(st.sets(st.sampled_from(["color", "z", "stencil"]), min_size=1))
        values = {"color": draw(st.integers(0, 0xFFFFFFFF)),
                  "z": draw(st.integers(GD_ZMIN, GD_ZMAX)),
                  "stencil": draw(st.integers(0, 255))}
        return ("clear", planes, values, rs)
    return ("flush",)


@st.composite
def scenes(draw):
    cfg = dict(double=draw(st.booleans()), zbits=draw(st.sampled_from([24, 24, 0])),
               stencil=draw(st.sampled_from([8, 8, 3, 1, 0])))
    pool = draw(st.lists(st.one_of(random_states(), random_states(), shadow_states()),
                         min_size=1, max_size=3))
    cmds = draw(st.lists(commands(pool), min_size=1, max_size=12))
    seed = draw(st.one_of(st.none(), st.integers(0, 2**32 - 1)))
    init = None
    if seed is not None:
        init = random_planes(np.random.default_rng(seed), W, H, **cfg)
    return cfg, init, cmds, draw(st.booleans())


def _check(cfg, init, cmds, group):
    want = render_naive(cmds, W, H, init=init, **cfg)
    for mode in MODES:
        got = render_kernels(cmds, W, H, init=init, mode=mode, group_triangles=group, **cfg)
        assert_planes_equal(got, want, f"mode={mode} cfg={cfg}")


@SETTINGS
@given(scenes())
def test_random_scenes_match_naive(scene):
    _check(*scene)


# Hand-picked scenes that a random search reaches rarely.


def test_shadow_volume_passes_match_naive():
    """Heidmann's passes: depth pre-pass, volume faces INCR/DECR, lit pass EQUAL."""
    rng = np.random.default_rng(7)
    cfg = dict(double=True, zbits=24, stencil=8)
    s0 = full_state(W, H)
    scene = full_state(W, H, zbuffer=True, zfunc=CMP_LEQUAL)
    front = full_state(W, H, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, stencil=True,
                       szpass=OP_INCR, wmpack=0, cull=1)
    back = full_state(W, H, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, stencil=True,
                      szpass=OP_DECR, wmpack=0, cull=2)
    lit = full_state(W, H, zbuffer=True, zfunc=CMP_EQUAL, stencil=True, sfunc=CMP_EQUAL,
                     sref=0, blend_sf=1, blend_df=1)
    cmds = [("clear", {"color", "z", "stencil"}, {"color": 0x10203040, "z": GD_ZMAX,
                                                  "stencil": 0}, s0)]

    def tri():
        return tuple((float(rng.uniform(-3, W + 2)), float(rng.uniform(-3, H + 2)),
                      float(rng.uniform(-4e6, 4e6)), tuple(rng.uniform(0, 1, 4)))
                     for _ in range(3))

    tris = [tri() for _ in range(10)]
    cmds += [("triangle", t, scene) for t in tris]
    vol = [tri() for _ in range(16)]
    cmds += [("triangle", t, front) for t in vol] + [("triangle", t, back) for t in vol]
    cmds += [("triangle", t, lit) for t in tris]
    _check(cfg, None, cmds, True)
    _check(cfg, None, cmds, False)


def test_single_buffer_front_and_back_draw_to_the_one_buffer():
    cfg = dict(double=False, zbits=24, stencil=0)
    white = (1.0, 1.0, 1.0, 1.0)
    t = ((1.0, 1.0, 0.0, white), (15.0, 2.0, 0.0, white), (3.0, 17.0, 0.0, white))
    for front, back in ((True, False), (False, True), (True, True), (False, False)):
        rs = full_state(W, H, draw_front=front, draw_back=back, blend_sf=1, blend_df=1)
        cmds = [("triangle", t, rs), ("point", (20.0, 3.0, 0.0, white), rs)]
        want = render_naive(cmds, W, H, **cfg)
        assert want["front"].any() == (front or back)
        for mode in MODES:
            assert_planes_equal(render_kernels(cmds, W, H, mode=mode, **cfg), want, mode)


# Seeded scenes: hypothesis favours small, simple examples; these are dense ones
# (many large overlapping primitives over random planes) drawn with numpy.


def _rng_state(rng, W, H):
    def often(default, value):
        return default if rng.random() < 0.5 else value

    def mask32():
        return int(rng.choice([0xFFFFFFFF, 0, int(rng.integers(0, 1 << 32))]))

    front = bool(rng.integers(2))
    x0, y0 = (int(v) for v in rng.integers(0, [W, H]))
    scissor = ((0, W - 1, 0, H - 1) if rng.random() < 0.6 else
               (x0, int(rng.integers(x0, W)), y0, int(rng.integers(y0, H))))
    sf, df = ((1, 0) if rng.random() < 0.3 else
              (int(rng.integers(0, 9)), int(rng.integers(0, 8))))
    return RasterState(
        zbuffer=bool(rng.integers(2)), zfunc=often(CMP_LEQUAL, int(rng.integers(8))),
        zwritemask=mask32(), stencil=bool(rng.integers(2)), sref=int(rng.integers(256)),
        sfunc=often(CMP_ALWAYS, int(rng.integers(8))),
        smask=often(0xFF, int(rng.integers(256))), sfail=int(rng.integers(6)),
        spass=int(rng.integers(6)), szpass=int(rng.integers(6)),
        swritemask=often(0xFF, int(rng.integers(256))), blend_sf=sf, blend_df=df,
        logicop=often(3, int(rng.integers(16))), wmpack=mask32(),
        afunc=often(CMP_ALWAYS, int(rng.integers(8))), aref=int(rng.integers(256)),
        shademodel=int(rng.integers(2)), subpixel=bool(rng.integers(2)),
        cull=often(0, int(rng.integers(4))), draw_front=front,
        draw_back=bool(rng.integers(2)) if front else True, scissor=scissor,
        linewidth=int(rng.integers(1, 5)), linestyle=often(0xFFFF, int(rng.integers(1 << 16))),
        lsrepeat=int(rng.integers(1, 4)), pntsize=int(rng.integers(1, 5)),
    )


def _rng_shadow_state(rng, W, H):
    """States of the 1991 passes (depth pass, volume faces, lit pass)."""
    kind = rng.choice(["zstencil", "zstencil", "zonly", "lit"])
    front = bool(rng.integers(2))
    common = dict(zbuffer=True, subpixel=bool(rng.integers(2)), cull=int(rng.integers(3)),
                  draw_front=front, draw_back=bool(rng.integers(2)) if front else True,
                  scissor=(0, W - 1, 0, H - 1))
    if kind == "zstencil":
        return RasterState(
            zfunc=int(rng.choice([CMP_LESS, CMP_LEQUAL, CMP_EQUAL, CMP_ALWAYS, 4])),
            zwritemask=0, stencil=True, wmpack=0,
            sfunc=int(rng.choice([CMP_ALWAYS, CMP_ALWAYS, CMP_EQUAL, 5])),
            sref=int(rng.integers(3)), swritemask=int(rng.choice([0xFF, 0xFF, 0x0F])),
            spass=int(rng.choice([OP_KEEP, OP_INCR, OP_DECR, 5])),
            szpass=int(rng.choice([OP_KEEP, OP_INCR, OP_DECR, 2])),
            sfail=int(rng.integers(6)), **common)
    if kind == "zonly":
        return RasterState(zfunc=int(rng.integers(8)), wmpack=0, **common)
    return RasterState(zfunc=CMP_EQUAL, stencil=True, sfunc=CMP_EQUAL, sref=0,
                       blend_sf=int(rng.choice([1, 1, BF_SA])),
                       blend_df=int(rng.choice([0, 1, BF_MSA])),
                       shademodel=int(rng.integers(2)), **common)


def _rng_vert(rng, W, H):
    def coord(hi):
        r = rng.random()
        v = rng.uniform(-4, hi + 4)
        if r < 0.25:
            return float(np.round(v))
        if r < 0.4:
            return float(np.round(v * 2) / 2)
        return float(v)

    z = float(rng.choice([rng.uniform(GD_ZMIN, GD_ZMAX), rng.uniform(-50, 50),
                          float(rng.integers(-3, 4)) * 1000.0]))
    col = tuple(float(c) for c in rng.choice([rng.uniform(0, 1, 4),
                                              rng.integers(0, 3, 4) / 2.0]))
    return (coord(W), coord(H), z, col)


def _rng_scene(rng, W, H):
    cfg = dict(double=bool(rng.integers(2)), zbits=int(rng.choice([24, 24, 0])),
               stencil=int(rng.choice([8, 8, 3, 1, 0])))
    pool = [_rng_shadow_state(rng, W, H) if rng.random() < 0.4 else _rng_state(rng, W, H)
            for _ in range(int(rng.integers(1, 4)))]
    cmds = []
    for _ in range(int(rng.integers(4, 13))):
        rs = pool[int(rng.integers(len(pool)))]
        kind = rng.choice(["triangle"] * 6 + ["line"] * 2 + ["point", "clear", "flush"])
        if kind == "triangle":
            cmds.append(("triangle", tuple(_rng_vert(rng, W, H) for _ in range(3)), rs))
        elif kind == "line":
            cmds.append(("line", (_rng_vert(rng, W, H), _rng_vert(rng, W, H)), rs,
                         int(rng.integers(40))))
        elif kind == "point":
            cmds.append(("point", _rng_vert(rng, W, H), rs))
        elif kind == "clear":
            planes = {p for p in ("color", "z", "stencil") if rng.random() < 0.5} or {"z"}
            cmds.append(("clear", planes, {"color": int(rng.integers(1 << 32)),
                                           "z": int(rng.integers(GD_ZMIN, GD_ZMAX + 1)),
                                           "stencil": int(rng.integers(256))}, rs))
        else:
            cmds.append(("flush",))
    init = random_planes(rng, W, H, **cfg) if rng.random() < 0.7 else None
    return cfg, init, cmds


def test_seeded_dense_scenes_match_naive():
    rng = np.random.default_rng(20240611)
    changed = 0
    modes = set()
    for i in range(120):
        # Every third scene is tall enough for two bands of rows (worker threads).
        W, H = (20, 44) if i % 3 == 0 else (24, 20)
        cfg, init, cmds = _rng_scene(rng, W, H)
        want = render_naive(cmds, W, H, init=init, **cfg)
        before = render_naive([], W, H, init=init, **cfg)
        changed += any(want[k] is not None and not np.array_equal(want[k], before[k])
                       for k in want)
        modes |= _fast_paths(cmds, cfg)
        for mode in MODES:
            got = render_kernels(cmds, W, H, init=init, mode=mode,
                                 group_triangles=bool(i % 2), **cfg)
            assert_planes_equal(got, want, f"scene {i} mode={mode} cfg={cfg}")
    assert changed >= 80  # the scenes really draw
    # Every fragment path of the kernels ran (general, z+stencil by table and by
    # addition, z only, colour spans).
    assert modes >= {MODE_GENERAL, MODE_ZSTENCIL, MODE_ZSTENCIL_ADD, MODE_ZONLY, MODE_COLOUR}


def _fast_paths(cmds, cfg):
    """Span modes derive_states picks for the scene's triangles."""
    rows = [c[2].as_row() for c in cmds if c[0] == "triangle"]
    if not rows:
        return set()
    states = np.stack(rows)
    if not cfg["double"]:  # as CommandBatch.flush does for a single buffer
        states[:, ROW["draw_front"]] |= states[:, ROW["draw_back"]]
        states[:, ROW["draw_back"]] = 0
    derived, _ = derive_states(states, cfg["stencil"], True, cfg["zbits"] > 0)
    return {int(m) for m in derived[:, D_MODE]}


@pytest.mark.parametrize("which", ["zonly", "colour"])
def test_depth_outside_24_bits_is_stored_as_24_bits(which):
    cfg = dict(double=False, zbits=24, stencil=0)
    white = (1.0, 1.0, 1.0, 1.0)
    z = 9000000.0  # > GD_ZMAX: reachable through add_window_triangles
    t = ((0.0, 0.0, z, white), (20.0, 0.0, z, white), (0.0, 15.0, z, white))
    rs = full_state(W, H, zbuffer=True, zfunc=CMP_ALWAYS,
                    wmpack=0 if which == "zonly" else 0xFFFFFFFF)
    want = render_naive([("triangle", t, rs)], W, H, **cfg)
    assert want["z"][0, 0] == 9000000 - (1 << 24)
    for mode in MODES:
        got = render_kernels([("triangle", t, rs)], W, H, mode=mode, **cfg)
        assert_planes_equal(got, want, mode)


def test_flat_shading_defaults_to_last_vertex_colour():
    cfg = dict(double=False, zbits=0, stencil=0)
    rs = full_state(W, H, shademodel=0)
    cols = [(1.0, 0.5, 0.25, 1.0), (0.0, 1.0, 0.0, 1.0), (0.2, 0.4, 0.6, 0.8)]
    t1 = ((0.0, 0.0, 0.0, cols[0]), (20.0, 0.0, 0.0, cols[1]), (0.0, 15.0, 0.0, cols[2]))
    t2 = ((2.0, 16.0, 0.0, cols[1]), (22.0, 1.0, 0.0, cols[2]), (22.0, 18.0, 0.0, cols[0]))
    want = render_naive([("triangle", t1, rs), ("triangle", t2, rs)], W, H, **cfg)
    fb = kernel_framebuffer(W, H, **cfg)
    batch = CommandBatch(fb)
    v = [p for t in (t1, t2) for p in t]
    batch.add_window_triangles([p[0] for p in v], [p[1] for p in v], [p[2] for p in v],
                               np.array([p[3] for p in v]), np.array([[0, 1, 2], [3, 4, 5]]),
                               rs)
    batch.flush()
    assert_planes_equal(planes_of(fb), want)
