"""Display-object editing: editobj, maketag, gentag, istag, deltag, objinsert,
objdelete, objreplace, chunksize, compactify (editobj(3G) and its pages).

Expected frames are the same calls made in immediate mode, in the order the edit
must leave them (an independent path: no object is involved).
"""

import functools

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl._core import GLTypeError, GLUsageError, GLValueError

W = H = 8


@pytest.fixture
def win(gl_window):
    return functools.partial(gl_window, W, H)


RED, GREEN, BLUE = 0xFF0000FF, 0xFF00FF00, 0xFFFF0000


def frame(ctx, draw) -> np.ndarray:
    gl.cpack(0)
    gl.clear()
    draw()
    ctx.flush()
    return ctx.read_rgba().copy()


def expect(ctx, *calls) -> None:
    """The object 1's frame equals ``calls`` [(func, args)] made in immediate mode."""
    got = frame(ctx, lambda: gl.callobj(1))

    def immediate():
        gl.pushmatrix()
        for f, a in calls:
            f(*a)
        gl.popmatrix()

    want = frame(ctx, immediate)
    assert want.any()
    assert np.array_equal(got, want)


def make_object():
    """Object 1: [tag 10] translate(1,0,0) [tag 11] cpack(RED) rectfi [tag 12]."""
    gl.makeobj(1)
    gl.pushmatrix()
    gl.maketag(10)
    gl.translate(1.0, 0.0, 0.0)
    gl.maketag(11)
    gl.cpack(RED)
    gl.rectfi(0, 0, 2, 2)
    gl.maketag(12)
    gl.popmatrix()
    gl.closeobj()


def test_objreplace_overwrites_the_routine_after_the_tag(win):
    ctx = win()
    make_object()
    gl.editobj(1)
    gl.objreplace(10)
    gl.translate(4.0, 2.0, 0.0)  # replaces translate(1, 0, 0), nothing else
    gl.closeobj()
    expect(ctx, (gl.translate, (4.0, 2.0, 0.0)), (gl.cpack, (RED,)),
           (gl.rectfi, (0, 0, 2, 2)))


def test_objreplace_stops_at_a_tag_and_inserts_from_there(win):
    ctx = win()
    make_object()
    gl.editobj(1)
    gl.objreplace(10)
    gl.translate(3.0, 0.0, 0.0)  # overwrites the translate
    gl.scale(1.0, 2.0, 1.0)  # tag 11 follows: inserted before it
    gl.closeobj()
    expect(ctx, (gl.translate, (3.0, 0.0, 0.0)), (gl.scale, (1.0, 2.0, 1.0)),
           (gl.cpack, (RED,)), (gl.rectfi, (0, 0, 2, 2)))


def test_objinsert_adds_after_the_tag_and_editobj_appends(win):
    ctx = win()
    make_object()
    gl.editobj(1)
    gl.objinsert(12)  # after the red square, before popmatrix
    gl.cpack(GREEN)
    gl.rectfi(4, 4, 6, 6)
    gl.closeobj()
    gl.editobj(1)  # the pointer at the end: after popmatrix
    gl.cpack(BLUE)
    gl.rectfi(0, 5, 1, 7)
    gl.closeobj()
    expect(ctx, (gl.translate, (1.0, 0.0, 0.0)), (gl.cpack, (RED,)),
           (gl.rectfi, (0, 0, 2, 2)), (gl.cpack, (GREEN,)), (gl.rectfi, (4, 4, 6, 6)),
           (gl.popmatrix, ()), (gl.cpack, (BLUE,)), (gl.rectfi, (0, 5, 1, 7)),
           (gl.pushmatrix, ()))


def test_objdelete_removes_between_tags_and_starttag_inserts_first(win):
    ctx = win()
    make_object()
    gl.editobj(1)
    gl.objdelete(10, 11)  # the translate goes; the pointer is at the end
    gl.cpack(GREEN)
    gl.rectfi(5, 5, 6, 6)
    gl.objinsert(GL.STARTTAG)
    gl.cpack(BLUE)
    gl.rectfi(6, 0, 7, 1)
    gl.closeobj()
    expect(ctx, (gl.cpack, (BLUE,)), (gl.rectfi, (6, 0, 7, 1)), (gl.cpack, (RED,)),
           (gl.rectfi, (0, 0, 2, 2)), (gl.cpack, (GREEN,)), (gl.rectfi, (5, 5, 6, 6)))


def test_tags_gentag_istag_deltag(win):
    win()
    make_object()
    gl.editobj(1)
    assert [gl.istag(t) for t in (10, 11, 12, 13)] == [1, 1, 1, 0]
    assert gl.istag(GL.STARTTAG) == 1 and gl.istag(GL.ENDTAG) == 1
    t = gl.gentag()
    assert t not in (10, 11, 12) and gl.istag(t) == 0
    gl.maketag(t)
    assert gl.istag(t) == 1
    gl.deltag(11)
    assert gl.istag(11) == 0
    with pytest.raises(GLValueError, match="tag 11 is not in object 1"):
        gl.objinsert(11)
    with pytest.raises(GLValueError, match="already exists"):
        gl.maketag(10)
    with pytest.raises(GLValueError, match="tag2 comes before tag1"):
        gl.objdelete(12, 10)
    gl.closeobj()
    with pytest.raises(GLUsageError, match="no object is open"):
        gl.maketag(3)
    with pytest.raises(GLUsageError, match="no object is open"):
        gl.objreplace(10)


def test_editobj_chunksize_compactify_errors_and_drawing_kept(win):
    ctx = win()
    with pytest.raises(GLValueError, match="object 9 is not defined"):
        gl.editobj(9)
    gl.chunksize(1020)
    with pytest.raises(GLValueError, match="positive"):
        gl.chunksize(0)
    make_object()
    gl.compactify(1)
    with pytest.raises(GLValueError, match="not defined"):
        gl.compactify(2)
    gl.editobj(1)
    with pytest.raises(GLUsageError, match="still open"):
        gl.makeobj(2)
    with pytest.raises(GLUsageError, match="an object is open"):
        gl.chunksize(512)
    gl.closeobj()
    expect(ctx, (gl.translate, (1.0, 0.0, 0.0)), (gl.cpack, (RED,)),
           (gl.rectfi, (0, 0, 2, 2)))


def test_newtag_counts_routines_after_a_tag(win):
    ctx = win()
    make_object()
    gl.editobj(1)
    # Routines after tag 10: translate, [tag 11], the red chunk, ... offset 2 puts
    # tag 20 after the chunk (tags are not routines).
    gl.newtag(20, 10, 2)
    gl.objinsert(20)
    gl.cpack(GREEN)
    gl.rectfi(4, 4, 6, 6)
    with pytest.raises(GLValueError, match="fewer than 9 routines"):
        gl.newtag(21, 12, 9)
    gl.closeobj()
    expect(ctx, (gl.translate, (1.0, 0.0, 0.0)), (gl.cpack, (RED,)),
           (gl.rectfi, (0, 0, 2, 2)), (gl.cpack, (GREEN,)), (gl.rectfi, (4, 4, 6, 6)))


# -- callfunc and bbox2 (routines that act when the object is drawn) ---------------------
def test_callfunc_runs_now_and_at_each_callobj(win):
    win()
    calls = []
    gl.callfunc(calls.append, "now")
    gl.makeobj(4)
    gl.callfunc(calls.append, "drawn")
    gl.closeobj()
    assert calls == ["now"]
    gl.callobj(4)
    gl.callobj(4)
    assert calls == ["now", "drawn", "drawn"]
    with pytest.raises(GLTypeError, match="fctn must be callable"):
        gl.callfunc(3)


def _boxed(box_call, *box):
    gl.makeobj(5)
    box_call(*box)
    gl.cpack(RED)
    gl.rectfi(0, 0, 7, 7)
    gl.closeobj()


@pytest.mark.parametrize("box, drawn", [
    ((gl.bbox2, 0, 0, 1.0, 1.0, 3.0, 3.0), True),  # inside the viewport
    ((gl.bbox2i, 0, 0, 20, 20, 30, 30), False),  # wholly to the upper right
    ((gl.bbox2s, 0, 0, -9, 0, -2, 5), False),  # wholly to the left
    ((gl.bbox2i, 2, 2, 2, 2, 4, 4), True),  # 2 pixels each way: not under 2x2
    ((gl.bbox2, 3, 3, 2.0, 2.0, 3.0, 3.0), False),  # 1x1 pixel, under 3x3: too small
    ((gl.bbox2, 3, 1, 2.0, 2.0, 3.0, 6.0), True),  # thin but tall enough
])
def test_bbox2_culls_the_rest_of_the_object(win, box, drawn):
    ctx = win()
    _boxed(*box)
    img = frame(ctx, lambda: gl.callobj(5))
    assert bool(img[..., 0].any()) == drawn
