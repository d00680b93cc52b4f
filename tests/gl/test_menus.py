"""Popup menus (vgxsim.gl._menus) and the script's ``menu`` statement.

Expected values are worked out by hand from addtopup(3G)/dopup(3G) as summarised in
the module docstring: an entry's value is its number (1 = first, the title not
counted) unless %x; %f then %F are applied; greyed, submenu and dismissed entries
give -1.
"""

import pytest

import vgxsim.gl as gl
from vgxsim import GL
from vgxsim.events import EventQueue, EventSource
from vgxsim.events.script import MenuChoice, ScriptError, parse_script
from vgxsim.gl._core import GLTypeError, GLUsageError, GLValueError, session
from vgxsim.gl._menus import menu_state

pytestmark = pytest.mark.usefixtures("fresh_session")  # tests/gl/conftest.py


def script(text: str) -> None:
    session.queue = EventQueue(EventSource.from_text(text))


def test_dopup_without_a_script_is_dismissed():
    p = gl.newpup()
    gl.addtopup(p, "Menu %t|one|two", 0)
    assert gl.dopup(p) == -1


def test_entries_are_numbered_from_one_without_the_title():
    p = gl.defpup("Colours %t|red|green|blue")
    script("menu 3\nmenu green\nmenu 0")
    assert gl.dopup(p) == 3
    assert gl.dopup(p) == 2
    assert gl.dopup(p) == -1
    assert gl.dopup(p) == -1  # script used up: dismissed
    m = menu_state().menus[p]
    assert m.title == "Colours" and [i.label for i in m.items] == ["red", "green", "blue"]


def test_x_values_and_l_separators():
    p = gl.defpup("a %x10|b %l|c %x-4")
    items = menu_state().menus[p].items
    assert [(i.value, i.separator) for i in items] == [(10, False), (None, True), (-4, False)]
    script("menu a\nmenu b\nmenu c")
    assert [gl.dopup(p), gl.dopup(p), gl.dopup(p)] == [10, 2, -4]


def test_item_and_menu_functions_compose_and_n_skips_the_menu_function():
    calls = []

    def menu_fn(v):
        calls.append(("F", v))
        return v * 100

    def item_fn(v):
        calls.append(("f", v))
        return v + 1

    p = gl.defpup("Tools %t %F|first %f %x5|second|third %n %x7", menu_fn, item_fn)
    script("menu 1\nmenu 2\nmenu 3")
    assert gl.dopup(p) == 600  # %f: 5 + 1, then %F: * 100
    assert gl.dopup(p) == 200
    assert gl.dopup(p) == 7  # %n: no %F
    assert calls == [("f", 5), ("F", 6), ("F", 2)]


def test_submenus_return_the_submenu_value():
    sub = gl.defpup("Size %t %F|small %x1|large %x2", lambda v: -v * 10)
    top = gl.newpup()
    gl.addtopup(top, "Main %t|size %m|quit %x99", sub)
    script("menu size large\nmenu 1\nmenu quit\nmenu 1 1")
    assert gl.dopup(top) == -20  # the submenu's own %F
    assert gl.dopup(top) == -1  # released on the submenu entry itself
    assert gl.dopup(top) == 99
    assert gl.dopup(top) == -10


def test_setpup_grey_box_check():
    p = gl.defpup("one|two|three")
    gl.setpup(p, 2, GL.PUP_GREY)
    gl.setpup(p, 3, GL.PUP_CHECK)
    gl.setpup(p, 1, GL.PUP_BOX)
    items = menu_state().menus[p].items
    assert [(i.grey, i.box, i.check) for i in items] == [
        (False, True, False), (True, False, False), (False, False, True)]
    script("menu 2\nmenu 3")
    assert gl.dopup(p) == -1  # greyed entries cannot be chosen
    assert gl.dopup(p) == 3  # a checked entry can
    gl.setpup(p, 2, GL.PUP_NONE)
    assert not items[1].grey
    with pytest.raises(GLValueError, match=r"setpup\(1, 4, PUP_NONE\)"):
        gl.setpup(p, 4, GL.PUP_NONE)
    with pytest.raises(GLValueError, match="PUP_NONE"):
        gl.setpup(p, 1, 3)


def test_addtopup_appends_and_freepup_deletes():
    p = gl.newpup()
    gl.addtopup(p, "A %t|x", 0)
    gl.addtopup(p, "y|z", 0)
    assert [i.label for i in menu_state().menus[p].items] == ["x", "y", "z"]
    q = gl.newpup()
    assert q != p
    gl.freepup(p)
    with pytest.raises(GLValueError, match=r"dopup\(1\)"):
        gl.dopup(p)
    assert gl.newpup() not in (p, q)


def test_bad_menu_strings_name_the_call():
    p = gl.newpup()
    with pytest.raises(GLValueError, match=r"unknown menu directive %q"):
        gl.addtopup(p, "x %q", 0)
    with pytest.raises(GLTypeError, match="%f needs a function"):
        gl.addtopup(p, "x %f", 0)
    with pytest.raises(GLTypeError, match="%F needs an argument"):
        gl.defpup("x %F")
    with pytest.raises(GLValueError, match="%m submenu 42"):
        gl.addtopup(p, "x %m", 42)
    with pytest.raises(GLValueError, match="%x needs an integer"):
        gl.addtopup(p, "x %x", 0)
    with pytest.raises(GLTypeError, match="addtopup"):
        gl.addtopup(p, 5, 0)


def test_a_script_choice_naming_no_entry_names_the_script_line():
    p = gl.defpup("one|two")
    script("# a comment\nmenu three")
    with pytest.raises(GLUsageError, match=r"<script>:2: no entry 'three'"):
        gl.dopup(p)


def test_menu_steps_answer_dopup_whatever_their_timing():
    # The menu is modal: the next step answers it even if it waits for frames.
    p = gl.defpup("one|two")
    script("after 50 menu 2")
    assert gl.dopup(p) == 2


def test_a_non_menu_step_next_dismisses_and_stays_queued():
    p = gl.defpup("one|two")
    script("key a\nmenu 2")
    assert gl.dopup(p) == -1
    assert len(session.queue.source) == 2  # nothing consumed


def test_script_menu_statement_parses():
    steps = parse_script("menu 2 'Big Red'\nafter 3 menu 0\nwait 2\nmenu x 0x3")
    assert [type(s) for s in steps] == [MenuChoice] * 3
    assert steps[0].path == (2, "Big Red") and steps[0].events == ()
    assert steps[1].path == (0,) and steps[1].after == 3
    assert steps[2].path == ("x", 3) and steps[2].wait == 2
    for bad in ("menu", "menu -1", "menu 0 2"):
        with pytest.raises(ScriptError):
            parse_script(bad)


def test_frames_and_qtest_leave_a_menu_step_for_dopup():
    from vgxsim import DEVICE

    p = gl.defpup("one|two")
    script("click MENUBUTTON\nmenu 2\nkey a")
    q = session.queue
    q.qdevice(DEVICE.MENUBUTTON)
    q.frame_done()  # delivers the click
    q.frame_done()  # a timer-driven program draws again: the menu step waits
    assert q.qtest() == DEVICE.MENUBUTTON
    assert q.qread() == (DEVICE.MENUBUTTON, 1)
    assert gl.dopup(p) == 2
    assert q.qread() == (DEVICE.MENUBUTTON, 0)


def test_a_blocking_qread_drops_a_menu_step_with_no_menu_up():
    from vgxsim import DEVICE

    script("menu 2\nkey a")
    q = session.queue
    q.qdevice(DEVICE.KEYBD)
    assert q.qread() == (DEVICE.KEYBD, ord("a"))
    assert len(q.source) == 0
