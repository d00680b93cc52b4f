"""Pick and select (vgxsim.gl._pick, vgxsim.geometry.hit_test).

Hit lists are worked out by hand from the picking region (pixels cx +- 5 around the
cursor for the default 10 x 10 picksize, integer coordinates on pixel centres under
the new window's ortho2) and compared with Mesa's GL_SELECT where it is available.
"""

import numpy as np
import pytest

import vgxsim.gl as gl
from vgxsim import DEVICE, GL
from vgxsim.events import EventQueue
from vgxsim.geometry.hit_test import point_inside, polygon_hits, segment_hits
from vgxsim.gl._core import GLUsageError, session

pytestmark = pytest.mark.usefixtures("fresh_session")  # tests/gl/conftest.py

W = H = 100


@pytest.fixture
def win():
    gl.prefsize(W, H)
    gl.winopen("pick")
    gl.RGBmode()
    gl.gconfig()
    return session.windows[gl.winget()]


def cursor(x: int, y: int) -> None:
    if session.queue is None:
        session.queue = EventQueue()
    session.queue.post(DEVICE.MOUSEX, x)
    session.queue.post(DEVICE.MOUSEY, y)


def square(x0, y0, x1, y1):
    gl.rectf(x0, y0, x1, y1)


def test_pick_region_around_the_cursor(win):
    cursor(50, 50)
    gl.pick(50)
    gl.initnames()
    gl.loadname(1)
    square(40, 40, 60, 60)  # contains the cursor
    gl.loadname(2)
    square(0, 0, 10, 10)  # far away
    gl.loadname(3)
    gl.bgnpoint()
    gl.v2i(55, 50)  # on the region's edge (50 + 10/2): inside the closed volume
    gl.endpoint()
    gl.loadname(4)
    gl.bgnpoint()
    gl.v2i(56, 50)  # one pixel beyond
    gl.endpoint()
    assert gl.endpick() == [1, 1, 1, 3]


def test_lines_and_polygons_hit_without_a_vertex_in_the_region(win):
    cursor(50, 50)
    gl.pick(50)
    gl.loadname(7)
    gl.bgnline()
    gl.v2f(0, 0)
    gl.v2f(100, 100)  # crosses the region's centre
    gl.endline()
    gl.loadname(8)
    gl.bgnpolygon()
    for v in ((0, 0), (99, 0), (0, 99)):  # its hypotenuse passes below (50, 50)...
        gl.v2i(*v)
    gl.endpolygon()  # ...at x + y = 99, inside the region (45..55)
    gl.loadname(9)
    gl.bgnline()
    gl.v2f(0, 80)
    gl.v2f(100, 80)  # 30 pixels above
    gl.endline()
    assert gl.endpick() == [1, 7, 1, 8]


def test_picksize_changes_the_region(win):
    cursor(50, 50)
    gl.picksize(30, 2)
    gl.pick(10)
    gl.loadname(1)
    gl.bgnpoint()
    gl.v2i(64, 50)  # within +-15 in x
    gl.endpoint()
    gl.loadname(2)
    gl.bgnpoint()
    gl.v2i(50, 52)  # beyond +-1 in y
    gl.endpoint()
    assert gl.endpick() == [1, 1]


def test_name_stack_records_and_overflow(win):
    cursor(50, 50)
    gl.pick(7)  # room for 7 shorts
    gl.pushname(1)
    gl.pushname(2)
    square(45, 45, 55, 55)
    gl.popname()  # records [2, 1, 2]
    square(45, 45, 55, 55)
    gl.pushname(-3)  # records [1, 1]: 5 shorts used
    gl.pushname(0x18000)  # a C short: wraps to -32768
    square(45, 45, 55, 55)
    gl.popname()  # [3, 1, -3, -32768] would need 5 + 4 > 7: dropped
    assert gl.endpick() == [2, 1, 2, 1, 1]


def test_names_wrap_like_c_shorts(win):
    cursor(50, 50)
    gl.pick(10)
    gl.pushname(-3)
    gl.pushname(0x18000)  # -32768
    square(45, 45, 55, 55)
    assert gl.endpick() == [2, -3, -32768]


def test_nothing_is_drawn_and_the_matrices_come_back(win):
    gl.cpack(0xFF102030)
    gl.clear()
    before = gl.lrectread(0, 0, W - 1, H - 1)
    m = gl.getmatrix()
    cursor(20, 30)
    gl.pick(10)
    gl.cpack(0xFFFFFFFF)
    gl.clear()
    gl.ortho2(-0.5, W - 0.5, -0.5, H - 0.5)
    square(0, 0, 99, 99)
    assert gl.endpick() == [0]  # a hit with an empty name stack
    assert gl.getmatrix() == m
    assert gl.lrectread(0, 0, W - 1, H - 1) == before


def test_projection_loaded_during_pick_is_narrowed(win):
    # The program reloads its own projection after pick() (pick(3G)); the pick
    # matrix still applies.  ortho2(0, 10, 0, 10): cursor pixel 50 is world 5.05.
    cursor(50, 50)
    gl.pick(10)
    gl.ortho2(-0.05, 9.95, -0.05, 9.95)  # world x = pixel / 10
    gl.loadname(1)
    gl.bgnpoint()
    gl.v2f(5.0, 5.0)
    gl.endpoint()
    gl.loadname(2)
    gl.bgnpoint()
    gl.v2f(6.0, 5.0)  # pixel 60: outside 45..55
    gl.endpoint()
    assert gl.endpick() == [1, 1]


def test_gselect_uses_the_programs_volume(win):
    gl.gselect(20)
    gl.ortho2(0, 10, 0, 10)
    gl.loadname(1)
    square(2, 2, 3, 3)
    gl.loadname(2)
    square(20, 20, 30, 30)
    gl.loadname(3)
    gl.bgnline()
    gl.v2f(-5, 5)
    gl.v2f(15, 5)
    gl.endline()
    assert gl.endselect() == [1, 1, 1, 3]


def test_mode_errors(win):
    with pytest.raises(GLUsageError, match="without pick"):
        gl.endpick()
    gl.gselect(5)
    with pytest.raises(GLUsageError, match=r"gselect\(\) is already in effect"):
        gl.pick(5)
    with pytest.raises(GLUsageError, match="without pick"):
        gl.endpick()
    gl.endselect()
    with pytest.raises(GLUsageError, match="empty"):
        gl.popname()


def test_hit_test_functions_by_hand():
    inside = np.array([0.5, 0.5, 0.0, 1.0])
    assert point_inside(inside)
    assert not point_inside(np.array([0.5, 0.5, 0.0, -1.0]))  # behind the eye
    assert not point_inside(np.array([0.0, 0.0, 0.0, 0.0]))
    # A segment through the volume with both ends outside; one that misses a corner.
    assert segment_hits(np.array([-3.0, 0, 0, 1]), np.array([3.0, 0, 0, 1]))
    assert not segment_hits(np.array([-3.0, 1.5, 0, 1]), np.array([-1.5, 3.0, 0, 1]))
    # A segment to a point at infinity (w = 0) along +x from inside hits.
    assert segment_hits(inside, np.array([1.0, 0, 0, 0]))
    big = np.array([[-5.0, -5, 0, 1], [5, -5, 0, 1], [0, 5, 0, 1]])
    assert polygon_hits(big)  # contains the volume's cross-section
    off = np.array([[2.0, 2, 0, 1], [3, 2, 0, 1], [2, 3, 0, 1]])
    assert not polygon_hits(off)
    # Concave L with its notch over the volume: misses.
    ell = np.array([[-3.0, -3, 0, 1], [3, -3, 0, 1], [3, -2, 0, 1], [-2, -2, 0, 1],
                    [-2, 3, 0, 1], [-3, 3, 0, 1]])
    assert not polygon_hits(ell)
    assert polygon_hits(ell * np.array([0.5, 0.5, 1, 1]))  # shrunk: its arm crosses


# -- Mesa's GL_SELECT as an independent peer ----------------------------------------------
def _mesa_hits(prims, proj, planes=()):
    """Names of Mesa's hit records for ``prims`` [(name, kind, (N, 4) clip-space-ready
    object vertices)] under the row-vector matrix ``proj`` (loaded as IRIS GL bytes),
    with the user clip planes ``planes`` (a, b, c, d) on (identity modelview)."""
    import ctypes

    from vgxsim.reference.mesa import MesaPeer, _import_gl

    GLm, _ = _import_gl()
    from OpenGL.raw.GL.VERSION import GL_1_0 as raw  # PyOpenGL's wrapper of glRenderMode
    # fails on GL_SELECT (ctypes.voidp); the raw entry points return the plain count.

    peer = MesaPeer(8, 8)
    buf = (ctypes.c_uint * 4096)()
    try:
        GLm.glDisable(GLm.GL_DEPTH_CLAMP)
        raw.glSelectBuffer(4096, buf)
        raw.glRenderMode(GLm.GL_SELECT)
        GLm.glMatrixMode(GLm.GL_PROJECTION)
        GLm.glLoadMatrixd(np.ascontiguousarray(proj, dtype=np.float64).reshape(-1))
        GLm.glMatrixMode(GLm.GL_MODELVIEW)
        GLm.glLoadIdentity()
        for i, q in enumerate(planes):
            GLm.glClipPlane(GLm.GL_CLIP_PLANE0 + i, np.asarray(q, np.float64))
            GLm.glEnable(GLm.GL_CLIP_PLANE0 + i)
        GLm.glInitNames()
        GLm.glPushName(0)
        mode = {"point": GLm.GL_POINTS, "line": GLm.GL_LINE_STRIP,
                "polygon": GLm.GL_POLYGON}
        for name, kind, verts in prims:
            GLm.glLoadName(name)
            GLm.glBegin(mode[kind])
            for v in verts:
                GLm.glVertex4d(*v)
            GLm.glEnd()
        count = raw.glRenderMode(GLm.GL_RENDER)
    finally:
        peer.close()
    names, i = [], 0
    for _ in range(count):  # records: n, z min, z max, n names
        n = buf[i]
        names.append(int(buf[i + 2 + n]))
        i += 3 + n
    return sorted(names)


def _random_prims(seed: int):
    rng = np.random.default_rng(seed)
    prims = []
    for name in range(1, 61):
        kind = ("point", "line", "polygon")[name % 3]
        n = {"point": 1, "line": 3, "polygon": 3}[kind]
        centre = rng.uniform(-7, 7, size=3)
        pts = centre + rng.uniform(-2.5, 2.5, size=(n, 3))
        prims.append((name, kind, np.hstack([pts, np.ones((n, 1))])))
    return prims


def _select_names(prims, proj, planes=()) -> list[int]:
    """Our hit names for ``prims`` under ``proj`` with ``planes`` on."""
    gl.mmode(GL.MVIEWING)
    gl.mmode(GL.MPROJECTION)
    gl.loadmatrix(list(proj.reshape(-1)))
    gl.mmode(GL.MVIEWING)
    for i, q in enumerate(planes):
        gl.clipplane(i, GL.CP_DEFINE, q)
        gl.clipplane(i, GL.CP_ON)
    gl.gselect(1000)
    for name, kind, verts in prims:
        gl.loadname(name)
        opener, closer = {"point": (gl.bgnpoint, gl.endpoint),
                          "line": (gl.bgnline, gl.endline),
                          "polygon": (gl.bgnpolygon, gl.endpolygon)}[kind]
        opener()
        for v in verts:
            gl.v4d(*v)
        closer()
    hits = gl.endselect()
    return sorted(hits[i + 1] for i in range(0, len(hits), 2))


def test_select_applies_user_clip_planes_by_hand(win):
    # Volume +-4 (ortho); plane x >= 1 (1, 0, 0, -1).  A square at x in [2, 3] is
    # inside the plane, one at x in [-3, -2] is clipped away by it, one at [0.5, 1.5]
    # straddles it (its part x >= 1 is drawn, so it hits), and a point at x = 0.5 is
    # outside it.
    proj = np.eye(4)
    proj[0, 0], proj[1, 1], proj[2, 2] = 0.25, 0.25, -0.25

    def sq(x0, x1):
        return np.array([[x0, -1, 0, 1], [x1, -1, 0, 1], [x1, 1, 0, 1], [x0, 1, 0, 1]],
                        float)

    prims = [(1, "polygon", sq(2, 3)), (2, "polygon", sq(-3, -2)),
             (3, "polygon", sq(0.5, 1.5)), (4, "point", np.array([[0.5, 0, 0, 1.0]])),
             (5, "line", np.array([[-3, 0, 0, 1.0], [0, 0, 0, 1], [3, 0, 0, 1]]))]
    assert _select_names(prims, proj) == [1, 2, 3, 4, 5]
    assert _select_names(prims, proj, [(1.0, 0.0, 0.0, -1.0)]) == [1, 3, 5]
    # A second plane y >= 2 leaves nothing of these (all lie in -1 <= y <= 1).
    assert _select_names(prims, proj, [(1.0, 0.0, 0.0, -1.0), (0, 1.0, 0, -2.0)]) == []


def test_pick_applies_user_clip_planes(win):
    # Pick at the window centre; a square around it hits, unless a user plane (in
    # the window's ortho2 coordinates, x <= 40) clips it away.
    cursor(50, 50)
    for planes, expect in (((), [1, 1]), (((-1.0, 0.0, 0.0, 40.0),), [])):
        for i, q in enumerate(planes):
            gl.clipplane(i, GL.CP_DEFINE, q)
            gl.clipplane(i, GL.CP_ON)
        gl.pick(50)
        gl.initnames()
        gl.loadname(1)
        square(45, 45, 55, 55)
        assert gl.endpick() == expect


@pytest.mark.parametrize("planes", [(), [(1.0, 0.3, 0.0, 0.5)],
                                    [(1.0, 0.3, 0.0, 0.5), (-0.2, 1.0, 0.4, 1.0)]])
def test_select_hits_with_clip_planes_match_mesa(win, planes):
    from vgxsim.reference import mesa

    if not mesa.mesa_available():
        pytest.skip("OSMesa is not available")
    proj = np.eye(4)
    proj[0, 0], proj[1, 1], proj[2, 2] = 0.25, 0.25, -0.25  # volume +-4
    prims = _random_prims(11)
    ours = _select_names(prims, proj, planes)
    theirs = _mesa_hits(prims, proj, planes)
    assert 3 < len(ours) < 55  # a real mix of hits and misses
    assert ours == theirs


def test_select_hits_match_mesa(win):
    from vgxsim.reference import mesa

    if not mesa.mesa_available():
        pytest.skip("OSMesa is not available")
    rng = np.random.default_rng(10)
    proj = np.eye(4)
    proj[0, 0], proj[1, 1], proj[2, 2] = 0.25, 0.25, -0.25  # volume +-4
    prims = []
    for name in range(1, 61):
        kind = ("point", "line", "polygon")[name % 3]
        n = {"point": 1, "line": 3, "polygon": 3}[kind]
        centre = rng.uniform(-7, 7, size=3)
        pts = centre + rng.uniform(-2.5, 2.5, size=(n, 3))
        prims.append((name, kind, np.hstack([pts, np.ones((n, 1))])))
    gl.mmode(GL.MVIEWING)
    gl.mmode(GL.MPROJECTION)
    gl.loadmatrix(list(proj.reshape(-1)))
    gl.mmode(GL.MVIEWING)
    gl.gselect(1000)
    for name, kind, verts in prims:
        gl.loadname(name)
        opener, closer = {"point": (gl.bgnpoint, gl.endpoint),
                          "line": (gl.bgnline, gl.endline),
                          "polygon": (gl.bgnpolygon, gl.endpolygon)}[kind]
        opener()
        for v in verts:
            gl.v4d(*v)
        closer()
    hits = gl.endselect()
    ours = sorted(hits[i + 1] for i in range(0, len(hits), 2))
    theirs = _mesa_hits(prims, proj)
    assert 5 < len(ours) < 55  # the draw is a real mix of hits and misses
    assert ours == theirs
