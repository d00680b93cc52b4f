"""Input script parsing: statements, timing fields, keystrokes and errors."""

import pytest

from vgxsim.events import (
    EventQueue,
    EventSource,
    ScriptError,
    ScriptExhausted,
    keystroke,
    load_script,
    parse_script,
)

ESCKEY, AKEY, LEFTSHIFTKEY, SPACEKEY, THREEKEY, RETKEY = 7, 11, 6, 83, 15, 51
RIGHTMOUSE, LEFTMOUSE = 101, 103
MOUSEX, MOUSEY, KEYBD, WINQUIT = 266, 267, 513, 542


def events(text, **kw):
    return [s.events for s in parse_script(text, **kw)]


def test_raw_events_by_name_and_number():
    assert events("LEFTMOUSE 1\n103 0\nMOUSEX -5\nWINQUIT 0x2") == [
        ((LEFTMOUSE, 1),),
        ((LEFTMOUSE, 0),),
        ((MOUSEX, -5),),
        ((WINQUIT, 2),),
    ]


def test_names_are_case_insensitive():
    assert events("press leftmouse\nEscKey 1") == [((LEFTMOUSE, 1),), ((ESCKEY, 1),)]


def test_comments_and_blank_lines():
    text = "# a comment\n\n   \nESCKEY 1   # trailing comment\n  # indented\n"
    steps = parse_script(text, filename="demo.txt")
    assert [s.events for s in steps] == [((ESCKEY, 1),)]
    assert steps[0].where == "demo.txt:4"


def test_conveniences():
    assert events("press RIGHTMOUSE\nrelease RIGHTMOUSE\nclick LEFTMOUSE\nmove 12 34") == [
        ((RIGHTMOUSE, 1),),
        ((RIGHTMOUSE, 0),),
        ((LEFTMOUSE, 1), (LEFTMOUSE, 0)),
        ((MOUSEX, 12), (MOUSEY, 34)),
    ]


def test_key_events():
    assert events("key a") == [((AKEY, 1), (KEYBD, 97), (AKEY, 0))]
    assert events("key A") == [
        ((LEFTSHIFTKEY, 1), (AKEY, 1), (KEYBD, 65), (AKEY, 0), (LEFTSHIFTKEY, 0))
    ]
    assert events("key '#'") == [
        ((LEFTSHIFTKEY, 1), (THREEKEY, 1), (KEYBD, 35), (THREEKEY, 0), (LEFTSHIFTKEY, 0))
    ]
    assert events("key ESC\nkey return\nkey SPACE") == [
        ((ESCKEY, 1), (KEYBD, 27), (ESCKEY, 0)),
        ((RETKEY, 1), (KEYBD, 13), (RETKEY, 0)),
        ((SPACEKEY, 1), (KEYBD, 32), (SPACEKEY, 0)),
    ]
    assert keystroke("\xe9") == ((KEYBD, 0xE9),)


def test_type_text():
    (evs,) = events('type "a a"')
    assert [v for d, v in evs if d == KEYBD] == [97, 32, 97]
    assert evs[:3] == ((AKEY, 1), (KEYBD, 97), (AKEY, 0))


def test_timing_fields():
    steps = parse_script(
        "after 5 ESCKEY 1\nwait 2\nwait 3\nclick LEFTMOUSE\ntick 4\ntick\nstop\nwait 7"
    )
    assert [(s.after, s.wait, s.ticks, s.stop) for s in steps] == [
        (5, 0, 0, False),
        (0, 5, 0, False),
        (0, 0, 4, False),
        (0, 0, 1, False),
        (0, 0, 0, True),
        (0, 7, 0, False),  # trailing wait: an empty step
    ]
    assert steps[-1].events == ()


def test_custom_resolver():
    table = {"FIRE": 4000}
    assert events("press FIRE", resolve=table.__getitem__) == [((4000, 1),)]
    # built-in names still work with a resolver that does not know them
    assert events("move 1 2", resolve=table.__getitem__) == [((MOUSEX, 1), (MOUSEY, 2))]


@pytest.mark.parametrize(
    ("text", "lineno", "token"),
    [
        ("ESCKEY 1\nFROBKEY 1", 2, "FROBKEY"),
        ("\n\npress NOSUCHDEV", 3, "NOSUCHDEV"),
        ("ESCKEY one", 1, "one"),
        ("ESCKEY", 1, "ESCKEY"),
        ("press", 1, "press"),
        ("move 1", 1, "1"),
        ("after -1 ESCKEY 1", 1, "-1"),
        ("after x ESCKEY 1", 1, "x"),
        ("after 3 wait 2", 1, "wait"),
        ("wait 2 3", 1, "3"),
        ("ESCKEY 1 2", 1, "2"),
        ("key ab", 1, "ab"),
        ("key", 1, "key"),
        ("tick -2", 1, "-2"),
        ("type \u263a", 1, "\u263a"),
        ("press -4", 1, "-4"),
        ("resize 80", 1, "80"),
        ("resize 0 30", 1, "0"),
        ("resize 80 30 0", 1, "0"),
        ("resize 80 30 1 2", 1, "2"),
        ("resize wide 30", 1, "wide"),
    ],
)
def test_errors_name_file_line_and_token(text, lineno, token):
    with pytest.raises(ScriptError) as info:
        parse_script(text, filename="demo.script")
    err = info.value
    assert isinstance(err, ValueError)
    assert (err.filename, err.lineno, err.token) == ("demo.script", lineno, token)
    assert str(err).startswith(f"demo.script:{lineno}: ")
    assert repr(token) in str(err)


def test_unclosed_quote_is_an_error():
    with pytest.raises(ScriptError) as info:
        parse_script('ESCKEY 1\ntype "abc', filename="q")
    assert info.value.lineno == 2


def test_load_script_from_file(tmp_path):
    path = tmp_path / "run.script"
    path.write_text("after 2 key a\nESCKEY 1\n", encoding="utf-8")
    src = load_script(path)
    assert isinstance(src, EventSource) and len(src) == 2
    bad = tmp_path / "bad.script"
    bad.write_text("ESCKEY 1\n\nbogus\n", encoding="utf-8")
    with pytest.raises(ScriptError, match=r"bad\.script:3: "):
        load_script(bad)
    assert len(EventSource.from_file(path)) == 2


def test_script_drives_a_queue():
    src = EventSource.from_text("move 10 20\npress LEFTMOUSE\nafter 2 key ESC\n")
    q = EventQueue(src)
    q.qdevice(LEFTMOUSE)
    q.qdevice(ESCKEY)
    q.tie(LEFTMOUSE, MOUSEX, MOUSEY)
    assert q.qread() == (LEFTMOUSE, 1)
    assert q.qread() == (MOUSEX, 10)
    assert q.qread() == (MOUSEY, 20)
    q.frame_done()
    q.frame_done()  # frame 2: ESC keystroke delivered
    assert q.qread() == (ESCKEY, 1)
    assert q.qread() == (ESCKEY, 0)
    with pytest.raises(ScriptExhausted):
        q.qread()


def test_non_utf8_script_names_the_file_and_line(tmp_path):
    path = tmp_path / "latin1.events"
    path.write_bytes(b"press LEFTMOUSE\n# caf\xe9\nrelease LEFTMOUSE\n")
    with pytest.raises(ScriptError, match=r"latin1\.events:2: not UTF-8 text") as info:
        load_script(path)
    assert info.value.lineno == 2 and info.value.filename == str(path)


def test_resize_statement():
    steps = parse_script("resize 80 30\nafter 4 resize 800 600 2\nwait 3\nresize 9 9",
                         filename="r.events")
    assert [(s.resize, s.after, s.wait, s.events) for s in steps] == [
        ((0, 80, 30), 0, 0, ()), ((2, 800, 600), 4, 0, ()), ((0, 9, 9), 0, 3, ())]
    assert steps[1].where == "r.events:2"


def test_a_delivered_resize_calls_the_window_resizer_before_its_events():
    q = EventQueue(EventSource(parse_script("resize 80 30 2\nresize 5 5 9", filename="s")))
    seen = []

    def resizer(gid, w, h):
        if gid == 9:
            raise ValueError("no open window has gid 9")
        seen.append((gid, w, h))

    q.window_resizer = resizer
    q.qtest()
    assert seen == [(2, 80, 30)]
    with pytest.raises(ValueError, match=r"^s:2: no open window has gid 9$"):
        q.qtest()
    q = EventQueue(EventSource(parse_script("resize 80 30", filename="t")))
    with pytest.raises(ValueError, match=r"^t:1: resize: no window to resize"):
        q.qtest()
