"""The gl event calls (vgxsim.gl._events) over a scripted EventQueue.

Expected queue contents follow qdevice(3G), qread(3G), tie(3G) and noise(3G) as the
events package models them (vgxsim/events/queue.py docstring), and the winopen rule
of vgxsim.gl._events: REDRAW at once, INPUTCHANGE at the next read or frame.
"""

import pytest

import vgxsim.gl as gl
from vgxsim import DEVICE as D
from vgxsim.events import EventQueue, EventSource, ScriptExhausted, parse_script
from vgxsim.gl._core import GLTypeError, GLValueError, session
from vgxsim.pipeline.context import CLEAR_COLOUR
from vgxsim.sinks import MemorySink

pytestmark = pytest.mark.usefixtures("fresh_session")  # tests/gl/conftest.py


def script(text: str) -> None:
    session.queue = EventQueue(EventSource(parse_script(text)))


def test_queue_is_created_lazily_and_works_before_winopen():
    assert session.queue is None
    gl.qdevice(D.ESCKEY)
    assert session.queue is not None
    assert gl.isqueued(D.ESCKEY) == 1 and gl.isqueued(D.AKEY) == 0
    gl.unqdevice(D.ESCKEY)
    assert gl.isqueued(D.ESCKEY) == 0


def test_winopen_queues_redraw_then_inputchange():
    g = gl.winopen("w")
    assert gl.qtest() == D.REDRAW
    assert gl.qread() == (D.REDRAW, g)
    assert gl.qread() == (D.INPUTCHANGE, g)
    with pytest.raises(ScriptExhausted):
        gl.qread()


def test_unqdevice_inputchange_right_after_winopen_suppresses_it():
    # mclock's idiom: the focus entry arrives after winopen returns, so it never comes
    g = gl.winopen("w")
    gl.unqdevice(D.INPUTCHANGE)
    assert gl.qread() == (D.REDRAW, g)
    assert gl.qtest() == 0


def test_inputchange_comes_before_input_delivered_at_a_frame():
    script("after 1 key a")
    g = gl.winopen("w")
    gl.qdevice(D.KEYBD)
    gl.swapbuffers()  # frame 1: the focus entry first, then the keystroke
    assert [gl.qread() for _ in range(3)] == [(D.REDRAW, g), (D.INPUTCHANGE, g),
                                              (D.KEYBD, ord("a"))]


def test_scripted_keys_and_the_end_of_the_script():
    script("key a\nkey ESC\n")
    gl.qdevice(D.ESCKEY)
    gl.qdevice(D.KEYBD)
    assert gl.qread() == (D.KEYBD, 97)
    assert gl.qread() == (D.ESCKEY, 1)
    assert gl.qread() == (D.KEYBD, 27)
    assert gl.qread() == (D.ESCKEY, 0)
    with pytest.raises(ScriptExhausted):
        gl.qread()


def test_getbutton_and_getvaluator_follow_unqueued_input():
    script("move 10 20\npress LEFTMOUSE\n")
    assert gl.getbutton(D.LEFTMOUSE) == 0
    gl.qtest()  # on an empty queue qtest delivers one due step
    assert gl.getvaluator(D.MOUSEX) == 10 and gl.getvaluator(D.MOUSEY) == 20
    gl.qtest()
    assert gl.getbutton(D.LEFTMOUSE) == 1
    assert gl.qtest() == 0  # LEFTMOUSE was not queued: state changed, no entry


def test_tie_enters_valuators_after_the_button():
    script("move 5 6\npress LEFTMOUSE\n")
    gl.qdevice(D.LEFTMOUSE)
    gl.tie(D.LEFTMOUSE, D.MOUSEX, D.MOUSEY)
    assert [gl.qread() for _ in range(3)] == [(D.LEFTMOUSE, 1), (D.MOUSEX, 5), (D.MOUSEY, 6)]
    with pytest.raises(GLValueError, match=r"tie\(MOUSEX, MOUSEY, 0\)"):
        gl.tie(D.MOUSEX, D.MOUSEY, 0)


def test_timers_tick_once_per_swapbuffers_with_noise():
    gl.prefsize(2, 2)
    gl.winopen("w")
    gl.qreset()
    gl.unqdevice(D.INPUTCHANGE)
    gl.qdevice(D.TIMER0)
    gl.noise(D.TIMER0, 2)  # one entry every second tick
    for _ in range(4):
        gl.swapbuffers()
    assert session.queue.entries == [(D.TIMER0, 0), (D.TIMER0, 0)]


def test_qenter_qtest_qreset():
    gl.qenter(D.REDRAW, 7)
    gl.qenter(D.KEYBD, 0x12345)  # values are C shorts: 0x12345 wraps to 0x2345
    assert gl.qtest() == D.REDRAW
    assert gl.qread() == (D.REDRAW, 7)
    assert gl.qread() == (D.KEYBD, 0x2345)
    gl.qenter(D.REDRAW, 1)
    gl.qreset()
    assert gl.qtest() == 0


def test_blkqread_reads_several_entries_as_shorts():
    for v in (1, 2, 3):
        gl.qenter(D.REDRAW, v)
    assert gl.blkqread(4) == [D.REDRAW, 1, D.REDRAW, 2]
    assert gl.blkqread(10) == [D.REDRAW, 3]
    with pytest.raises(GLValueError, match=r"blkqread\(1\)"):
        gl.blkqread(1)


def test_bad_devices():
    with pytest.raises(GLValueError, match=r"qdevice\(-1\)"):
        gl.qdevice(-1)
    with pytest.raises(GLValueError, match=r"qdevice\(70000\)"):
        gl.qdevice(70000)
    with pytest.raises(GLTypeError, match=r"qdevice\(1.0\)"):
        gl.qdevice(1.0)
    with pytest.raises(GLValueError, match=r"noise"):
        gl.noise(D.MOUSEX, -1)


def test_qread_shows_a_single_buffered_screen_before_waiting():
    gl.prefsize(3, 2)
    g = gl.winopen("w")
    gl.unqdevice(D.INPUTCHANGE)
    ctx = session.windows[g]
    sink = ctx.sink = MemorySink()
    assert gl.qread() == (D.REDRAW, g)  # queue not empty: nothing shown yet
    assert len(sink) == 0
    ctx.clear_planes(CLEAR_COLOUR, 4)  # cmode index 4 = BLUE in the default map
    with pytest.raises(ScriptExhausted):
        gl.qread()  # the queue is empty: the picture is shown, then the run ends
    assert len(sink) == 1
    assert (sink[0] == [0, 0, 255, 255]).all()


def test_scripted_resize_reshapes_the_window_and_enters_redraw():
    # events script "resize W H [GID]": the user drags the window's corner
    script("after 1 resize 40 24\nresize 16 12 1")
    g = gl.winopen("w")
    gl.unqdevice(D.INPUTCHANGE)
    gl.RGBmode()
    gl.gconfig()
    assert gl.qread() == (D.REDRAW, g) and gl.getsize() == (640, 512)
    gl.swapbuffers()  # frame 1: the resize is due
    assert gl.qread() == (D.REDRAW, g)
    gl.reshapeviewport()
    assert gl.getsize() == (40, 24) and gl.getviewport() == (0, 39, 0, 23)
    assert gl.qread() == (D.REDRAW, g)  # the second resize, once the queue was empty
    assert gl.getsize() == (16, 12)


def test_scripted_resize_of_a_window_that_is_not_open_names_the_line():
    script("resize 40 24 7")
    gl.winopen("w")
    gl.unqdevice(D.INPUTCHANGE)
    gl.qread()  # winopen's REDRAW
    with pytest.raises(ValueError, match=r"^<script>:1: .*no open window has gid 7"):
        gl.qread()
