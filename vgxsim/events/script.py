"""Plain-text input scripts for headless runs.

A script stands in for the user at the keyboard and mouse: it lists the input
the program will receive, and when.  It is parsed into :class:`Step` objects
for an :class:`~vgxsim.events.queue.EventSource`; the
:class:`~vgxsim.events.queue.EventQueue` delivers them.

Format
------
One statement per line.  ``#`` starts a comment that runs to the end of the
line; blank lines are ignored.  A line is split into tokens like a POSIX shell
command line (:func:`shlex.split`): quote with ``'...'`` or ``"..."`` to put
spaces or ``#`` in a token (``key '#'``).  Keywords are case-insensitive.
Device names are looked up as written, then in upper case, so ``leftmouse``
works; a plain integer is taken as a raw device number.

Grammar (EBNF)::

    script    = { line } ;
    line      = [ statement ] [ "#" comment ] newline ;
    statement = [ "after" FRAME ] action
              | "wait" FRAMES ;
    action    = DEVICE VALUE            (* one raw event: DEVICE gets VALUE *)
              | "press" DEVICE         (* DEVICE 1 *)
              | "release" DEVICE       (* DEVICE 0 *)
              | "click" DEVICE         (* DEVICE 1, then DEVICE 0 *)
              | "move" X Y             (* MOUSEX X, then MOUSEY Y *)
              | "key" KEY              (* one keystroke, see below *)
              | "type" TEXT            (* one keystroke per character *)
              | "tick" [ COUNT ]       (* COUNT timer ticks, default 1 *)
              | "menu" CHOICE { CHOICE } (* answer the next dopup, see below *)
              | "resize" W H [ GID ]   (* the user reshapes a window, see below *)
              | "stop" ;               (* end the run *)
    DEVICE    = NAME | INT ;           (* LEFTMOUSE, ESCKEY, MOUSEX, 103, ... *)
    VALUE     = INT ;  X = INT ;  Y = INT ;
    W         = INT >= 1 ;  H = INT >= 1 ;  GID = INT >= 1 ;
    FRAME     = NAT ;  FRAMES = NAT ;  COUNT = NAT ;
    KEY       = CHAR | KEYNAME ;       (* "a", "'#'", "ESC", "SPACE", ... *)
    TEXT      = TOKEN ;                (* quote it if it has spaces *)
    INT       = [ "+" | "-" ] ( DIGITS | "0x" HEXDIGITS ) ;
    NAT       = INT >= 0 ;
    CHOICE    = NAT | LABEL ;          (* entry number (1 = first) or its label *)

KEYNAME is one of SPACE, RETURN (RET, ENTER), TAB, ESC (ESCAPE), BACKSPACE
(BS), DELETE (DEL) or LINEFEED (LF).

Timing
------
Each statement is one *step*, delivered as a whole (see
:mod:`vgxsim.events.queue` for when steps are delivered).  ``after FRAME``
holds its step back until FRAME frames have been drawn (``swapbuffers``
calls).  ``wait FRAMES`` makes the next statement wait FRAMES frames after the
previous step was delivered; consecutive waits add up, and a wait at the end
of the script becomes an empty step that holds the run open that long (for
programs driven by timers).  ``stop`` ends the run when it is delivered.

Keystrokes
----------
``key c`` with a character that has a key on a US keyboard produces, in this
order: ``LEFTSHIFTKEY 1`` (shifted characters only), ``<key> 1``,
``KEYBD ord(c)``, ``<key> 0``, ``LEFTSHIFTKEY 0`` (shifted only).  For example
``key a`` gives AKEY 1, KEYBD 97, AKEY 0, and ``key A`` wraps the same in
LEFTSHIFTKEY.  Latin-1 characters without a key give KEYBD alone.  As every
event, these only reach the queue for queued devices, but they always update
``getbutton`` state.

Popup menus
-----------
``menu CHOICE ...`` is the user's pick in the popup menu a program opens with
``dopup`` (vgxsim.gl._menus).  It is not delivered through the queue: ``dopup``
takes the next script step if it is a ``menu`` step, whatever its ``after``/``wait``
(the menu is modal; the user's next action answers it); if the next step is
anything else, or there is none, ``dopup`` returns -1, as for a menu dismissed
without a choice.  Frames (``swapbuffers``) and ``qtest`` do not deliver a ``menu``
step, so a program may draw or poll between reading MENUBUTTON and calling
``dopup``; only a blocking ``qread`` that reaches it while no menu is up drops it.

Each CHOICE picks an entry of one menu level, the first in the menu ``dopup``
shows and each further one in the submenu (``%m``) of the entry before.  An
integer is the entry's number as ``setpup`` counts them (1 = first entry, the
``%t`` title not counted); anything else is compared with the entries' labels
(their text without the ``%`` directives, case-sensitive).  ``menu 0`` dismisses
the menu.  ``click MENUBUTTON`` then ``menu Quit`` is what a user does to choose
Quit from a program that calls ``dopup`` on ``(MENUBUTTON, 1)``.

Resizing
--------
``resize W H [GID]`` is the user dragging a window's corner until it is W x H
pixels: window GID (default: the current window when the step is delivered) keeps
its lower-left corner, its planes take the new size (their contents are lost, as
after a reshape on the workstation) and ``(REDRAW, GID)`` is entered, so the
program's ``reshapeviewport`` and ``getsize`` see the new size when it reads the
REDRAW.  A window session's ``--record-events`` writes one for each resize the user
made (``after 12 resize 800 600 1``).  No window with that gid, or a size past
vgxsim's limit, is an error naming the script line when the step is delivered.

Example::

    move 320 240          # MOUSEX 320, MOUSEY 240
    press LEFTMOUSE
    wait 5                # hold the button for 5 frames...
    move 400 240          # ...then drag
    release LEFTMOUSE
    type "hi there"
    after 30 key ESC      # escape once 30 frames have been drawn

Errors raise :class:`ScriptError`, a :class:`ValueError` naming the file, the
line number and the offending token.
"""

from __future__ import annotations

import operator
import shlex
from collections.abc import Callable
from dataclasses import dataclass
from os import PathLike

from vgxsim.events import _devices
from vgxsim.events.queue import EventSource, Step

__all__ = ["ScriptError", "parse_script", "load_script", "keystroke", "KEY_NAMES",
           "MenuChoice"]


@dataclass(frozen=True)
class MenuChoice(Step):
    """A script ``menu`` statement: the user's choice in the next ``dopup``.

    It makes no input events (``events`` is empty); ``dopup`` reads ``path`` (see
    "Popup menus" in the module docstring).

    Parameters
    ----------
    path : tuple of (int or str)
        One entry per menu level: a 1-based entry number or a label; ``(0,)``
        dismisses the menu.
    """

    path: tuple[int | str, ...] = ()
    #: The queue's frames and qtest do not deliver it; it waits for dopup.
    modal = True

Resolver = Callable[[str], int]

#: Names accepted by ``key`` for characters that are awkward to write.
KEY_NAMES: dict[str, str] = {
    "SPACE": " ",
    "RETURN": "\r",
    "RET": "\r",
    "ENTER": "\r",
    "TAB": "\t",
    "ESC": "\x1b",
    "ESCAPE": "\x1b",
    "BACKSPACE": "\b",
    "BS": "\b",
    "DELETE": "\x7f",
    "DEL": "\x7f",
    "LINEFEED": "\n",
    "LF": "\n",
}

# Character -> (key device name, shifted) for a US keyboard.
_UNSHIFTED = {
    " ": "SPACEKEY",
    ";": "SEMICOLONKEY",
    ".": "PERIODKEY",
    ",": "COMMAKEY",
    "'": "QUOTEKEY",
    "`": "ACCENTGRAVEKEY",
    "-": "MINUSKEY",
    "/": "VIRGULEKEY",
    "\\": "BACKSLASHKEY",
    "=": "EQUALKEY",
    "[": "LEFTBRACKETKEY",
    "]": "RIGHTBRACKETKEY",
    "\t": "TABKEY",
    "\r": "RETKEY",
    "\n": "LINEFEEDKEY",
    "\x1b": "ESCKEY",
    "\b": "BACKSPACEKEY",
    "\x7f": "DELKEY",
}
_SHIFTED = {
    ":": ";",
    ">": ".",
    "<": ",",
    '"': "'",
    "~": "`",
    "_": "-",
    "?": "/",
    "|": "\\",
    "+": "=",
    "{": "[",
    "}": "]",
    "!": "1",
    "@": "2",
    "#": "3",
    "$": "4",
    "%": "5",
    "^": "6",
    "&": "7",
    "*": "8",
    "(": "9",
    ")": "0",
}
_DIGIT_KEYS = (
    "ZEROKEY",
    "ONEKEY",
    "TWOKEY",
    "THREEKEY",
    "FOURKEY",
    "FIVEKEY",
    "SIXKEY",
    "SEVENKEY",
    "EIGHTKEY",
    "NINEKEY",
)


def _key_for(ch: str) -> tuple[str | None, bool]:
    """Return (key device name or None, shifted) for one character."""
    shifted = False
    if ch in _SHIFTED:
        ch, shifted = _SHIFTED[ch], True
    elif "A" <= ch <= "Z":
        ch, shifted = ch.lower(), True
    if "a" <= ch <= "z":
        return ch.upper() + "KEY", shifted
    if "0" <= ch <= "9":
        return _DIGIT_KEYS[ord(ch) - ord("0")], shifted
    return _UNSHIFTED.get(ch), shifted


class ScriptError(ValueError):
    """A script could not be parsed.

    The message reads ``"FILE:LINE: MESSAGE (at 'TOKEN')"``.

    Attributes
    ----------
    filename : str
        Script file name (``"<script>"`` for text).
    lineno : int
        1-based line number.
    token : str
        The offending token (or the line, for quoting errors).
    message : str
        What is wrong.
    """

    def __init__(self, filename: str, lineno: int, token: str, message: str):
        self.filename = filename
        self.lineno = lineno
        self.token = token
        self.message = message
        super().__init__(f"{filename}:{lineno}: {message} (at {token!r})")


def _lookup_builtin(name: str, resolve: Resolver) -> int:
    """Resolve a device name vgxsim itself needs, trusting the local table last."""
    try:
        dev = resolve(name)
    except (LookupError, ValueError, TypeError, AttributeError):
        dev = None
    return int(dev) if dev is not None else _devices.TABLE[name]


def keystroke(ch: str, resolve: Resolver | None = None) -> tuple[tuple[int, int], ...]:
    """Return the raw events of one keystroke (see "Keystrokes" above).

    Parameters
    ----------
    ch : str
        One character (code point below 256).
    resolve : callable, optional
        Device-name resolver; the default uses ``vgxsim.DEVICE`` when present.

    Returns
    -------
    tuple of (int, int)
        ``(device, value)`` events.

    Raises
    ------
    ValueError
        If ``ch`` is not one character below U+0100.
    """
    if len(ch) != 1 or ord(ch) > 255:
        raise ValueError(f"not a single Latin-1 character: {ch!r}")
    resolve = resolve or _devices.resolve
    keybd = _lookup_builtin("KEYBD", resolve)
    name, shifted = _key_for(ch)
    if name is None:
        return ((keybd, ord(ch)),)
    key = _lookup_builtin(name, resolve)
    events = [(key, 1), (keybd, ord(ch)), (key, 0)]
    if shifted:
        shift = _lookup_builtin("LEFTSHIFTKEY", resolve)
        events = [(shift, 1), *events, (shift, 0)]
    return tuple(events)


class _Line:
    """Token cursor over one script line; raises ScriptError with context."""

    def __init__(self, filename: str, lineno: int, tokens: list[str], resolve: Resolver):
        self.filename, self.lineno, self.tokens = filename, lineno, tokens
        self.resolve = resolve
        self.pos = 0

    def error(self, token: str, message: str) -> ScriptError:
        return ScriptError(self.filename, self.lineno, token, message)

    def next(self, what: str) -> str:
        if self.pos >= len(self.tokens):
            last = self.tokens[self.pos - 1] if self.pos else ""
            raise self.error(last, f"missing {what}")
        tok = self.tokens[self.pos]
        self.pos += 1
        return tok

    def integer(self, what: str, minimum: int | None = None) -> int:
        tok = self.next(what)
        try:
            val = int(tok, 0)
        except ValueError:
            raise self.error(tok, f"expected an integer {what}") from None
        if minimum is not None and val < minimum:
            raise self.error(tok, f"{what} must be >= {minimum}")
        return val

    def device(self) -> int:
        tok = self.next("device name or number")
        return self.device_of(tok)

    def device_of(self, tok: str) -> int:
        try:
            dev = int(tok, 0)
        except ValueError:
            pass
        else:
            if dev < 0:
                raise self.error(tok, "device numbers must be >= 0")
            return dev
        try:
            dev = self.resolve(tok)
        except (LookupError, ValueError, TypeError, AttributeError):
            dev = None
        if dev is None:
            raise self.error(tok, "unknown device")
        return operator.index(dev)

    def end(self) -> None:
        if self.pos < len(self.tokens):
            raise self.error(self.tokens[self.pos], "unexpected extra token")


def _action(line: _Line, word: str) -> tuple[tuple[tuple[int, int], ...], int, bool]:
    """Parse the action starting at ``word``; return (events, ticks, stop)."""
    kw = word.lower()
    res = line.resolve
    if kw in ("press", "release", "click"):
        dev = line.device()
        events = {"press": ((dev, 1),), "release": ((dev, 0),), "click": ((dev, 1), (dev, 0))}[kw]
        return events, 0, False
    if kw == "move":
        x = line.integer("X coordinate")
        y = line.integer("Y coordinate")
        return ((_lookup_builtin("MOUSEX", res), x), (_lookup_builtin("MOUSEY", res), y)), 0, False
    if kw == "key":
        tok = line.next("key (one character or a key name)")
        if len(tok) == 1:
            ch = tok
        elif tok.upper() in KEY_NAMES:
            ch = KEY_NAMES[tok.upper()]
        else:
            raise line.error(
                tok,
                "'key' takes one character or one of "
                + ", ".join(KEY_NAMES)
                + "; use 'type' for text",
            )
        try:
            return keystroke(ch, res), 0, False
        except ValueError as exc:
            raise line.error(tok, str(exc)) from None
    if kw == "type":
        tok = line.next("text")
        try:
            events = tuple(ev for ch in tok for ev in keystroke(ch, res))
        except ValueError as exc:
            raise line.error(tok, str(exc)) from None
        return events, 0, False
    if kw == "tick":
        count = line.integer("tick count", 0) if line.pos < len(line.tokens) else 1
        return (), count, False
    if kw == "stop":
        return (), 0, True
    if kw in ("after", "wait"):
        raise line.error(word, f"'{kw}' must start the line")
    try:
        dev = line.device_of(word)
    except ScriptError:
        raise line.error(word, "unknown statement or device") from None
    return ((dev, line.integer("value")),), 0, False


def _menu_path(line: _Line) -> tuple[int | str, ...]:
    """The CHOICEs of a ``menu`` statement: ints (entry numbers) or labels."""
    path: list[int | str] = [line.next("menu entry (a number or a label)")]
    path += line.tokens[line.pos:]
    line.pos = len(line.tokens)
    out: list[int | str] = []
    for tok in path:
        try:
            num = int(tok, 0)
        except ValueError:
            out.append(tok)
            continue
        if num < 0:
            raise line.error(tok, "menu entry numbers must be >= 0 (0 dismisses the menu)")
        out.append(num)
    if 0 in out and out != [0]:
        raise line.error("0", "'menu 0' dismisses the menu and takes no other choice")
    return tuple(out)


def parse_script(
    text: str, filename: str = "<script>", resolve: Resolver | None = None
) -> list[Step]:
    """Parse script text into steps.

    Parameters
    ----------
    text : str
        The script (grammar in the module docstring).
    filename : str
        Name used in error messages and in :attr:`Step.where`.
    resolve : callable, optional
        ``resolve(name) -> int`` for device names; it may raise
        KeyError/ValueError or return None for unknown names.  The default
        uses ``vgxsim.DEVICE.by_name`` when that module exists and a built-in
        table otherwise.

    Returns
    -------
    list of Step
        One step per statement, in order.

    Raises
    ------
    ScriptError
        On the first bad line.
    """
    resolve = resolve or _devices.resolve
    steps: list[Step] = []
    pending_wait = 0
    last_lineno = 0
    for lineno, raw in enumerate(text.splitlines(), start=1):
        last_lineno = lineno
        try:
            tokens = shlex.split(raw, comments=True, posix=True)
        except ValueError as exc:
            raise ScriptError(filename, lineno, raw.strip(), f"cannot split line: {exc}") from None
        if not tokens:
            continue
        line = _Line(filename, lineno, tokens, resolve)
        word = line.next("statement")
        if word.lower() == "wait":
            pending_wait += line.integer("frame count", 0)
            line.end()
            continue
        after = 0
        if word.lower() == "after":
            after = line.integer("frame number", 0)
            word = line.next("statement after the frame number")
        if word.lower() == "resize":
            width = line.integer("window width", 1)
            height = line.integer("window height", 1)
            gid = line.integer("window gid", 1) if line.pos < len(line.tokens) else 0
            line.end()
            steps.append(Step(after=after, wait=pending_wait, where=f"{filename}:{lineno}",
                              resize=(gid, width, height)))
            pending_wait = 0
            continue
        if word.lower() == "menu":
            steps.append(MenuChoice(after=after, wait=pending_wait, where=f"{filename}:{lineno}",
                                    path=_menu_path(line)))
            pending_wait = 0
            continue
        events, ticks, stop = _action(line, word)
        line.end()
        steps.append(
            Step(
                events=events,
                after=after,
                wait=pending_wait,
                ticks=ticks,
                stop=stop,
                where=f"{filename}:{lineno}",
            )
        )
        pending_wait = 0
    if pending_wait:
        steps.append(Step(wait=pending_wait, where=f"{filename}:{last_lineno}"))
    return steps


def load_script(path: str | PathLike, resolve: Resolver | None = None) -> EventSource:
    """Read a script file and return its steps as an :class:`EventSource`.

    Parameters
    ----------
    path : str or path-like
        The script file (UTF-8).
    resolve : callable, optional
        Device-name resolver, as for :func:`parse_script`.

    Returns
    -------
    EventSource

    Raises
    ------
    OSError
        If the file cannot be read.
    ScriptError
        If it is not UTF-8 text or does not parse (naming the file and line).
    """
    with open(path, "rb") as fh:
        raw = fh.read()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        lineno = raw.count(b"\n", 0, exc.start) + 1
        line = raw.split(b"\n")[lineno - 1]
        raise ScriptError(str(path), lineno, line.decode("utf-8", "replace").strip(),
                          f"not UTF-8 text (byte 0x{raw[exc.start]:02x} at offset "
                          f"{exc.start})") from None
    return EventSource(parse_script(text, filename=str(path), resolve=resolve))
