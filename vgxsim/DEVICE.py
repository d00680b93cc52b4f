"""IRIS GL ``<gl/device.h>`` device numbers as named :class:`~vgxsim.tokens.Token`\\ s.

Usage mirrors the old Python ``DEVICE`` module::

    from vgxsim.DEVICE import *      # or: from vgxsim import DEVICE
    qdevice(ESCKEY); qdevice(REDRAW)
    dev, val = qread()
    if dev == ESCKEY and val == 0: ...

Each constant is an ``int`` whose ``repr`` is its name.  Several names share a number
(``RIGHTMOUSE`` = ``MENUBUTTON`` = ``MOUSE1`` = ``BUT100`` = 101, ``CTRLKEY`` =
``LEFTCTRLKEY`` = 3, ``TIMER0`` = ``TIMOFFSET`` = 515, ...); each name is its own token.
:func:`name_of` picks one canonical name per number (the device name, never an
offset/count, a ``BUTn`` or an alias such as ``MENUBUTTON``); :func:`by_name` maps any
name back to its number, for parsing scripted-event files.

The keyboard numbers are SGI keyboard *positions* (``BUTn`` = position n + 1), not ASCII:
``AKEY`` is 11, ``ESCKEY`` 7, ``RETKEY`` 51, ``SPACEKEY`` 83.

Sources (as collected in the project reference notes ``irisgl_reference.md`` and
``cpython_gl_module.md``): CPython ``Lib/plat-irix5/DEVICE.py`` (python/cpython, commit
b3be23a), a transcription of IRIX 5 ``<gl/device.h>``, for every name and value; the same
numbers (with each key's position comment, and the ``ISBUTTON``/``ISVALUATOR``/...
macros that :func:`is_button` etc. follow) appear in IGL 0.4.2 ``include/igl.h``
(irixxxx/irix-igl).  Alice 4's ``WINQUIT 2002`` is an invented value and is not used.
"""

from vgxsim.tokens import Token as _T

# Device-number ranges (offsets and counts; not devices themselves)
NULLDEV = _T(0, "NULLDEV")
BUTOFFSET = _T(1, "BUTOFFSET")
VALOFFSET = _T(256, "VALOFFSET")
PSEUDOFFSET = _T(512, "PSEUDOFFSET")
BUT2OFFSET = _T(3840, "BUT2OFFSET")
TIMOFFSET = _T(515, "TIMOFFSET")
XKBDOFFSET = _T(143, "XKBDOFFSET")
BUTCOUNT = _T(255, "BUTCOUNT")
VALCOUNT = _T(256, "VALCOUNT")
TIMCOUNT = _T(4, "TIMCOUNT")
XKBDCOUNT = _T(28, "XKBDCOUNT")
USERBUTOFFSET = _T(4096, "USERBUTOFFSET")
USERVALOFFSET = _T(12288, "USERVALOFFSET")
USERPSEUDOFFSET = _T(16384, "USERPSEUDOFFSET")

# Buttons by number: BUTn = n + BUTOFFSET (keyboard positions 0-82)
BUT0 = _T(1, "BUT0")
BUT1 = _T(2, "BUT1")
BUT2 = _T(3, "BUT2")
BUT3 = _T(4, "BUT3")
BUT4 = _T(5, "BUT4")
BUT5 = _T(6, "BUT5")
BUT6 = _T(7, "BUT6")
BUT7 = _T(8, "BUT7")
BUT8 = _T(9, "BUT8")
BUT9 = _T(10, "BUT9")
BUT10 = _T(11, "BUT10")
BUT11 = _T(12, "BUT11")
BUT12 = _T(13, "BUT12")
BUT13 = _T(14, "BUT13")
BUT14 = _T(15, "BUT14")
BUT15 = _T(16, "BUT15")
BUT16 = _T(17, "BUT16")
BUT17 = _T(18, "BUT17")
BUT18 = _T(19, "BUT18")
BUT19 = _T(20, "BUT19")
BUT20 = _T(21, "BUT20")
BUT21 = _T(22, "BUT21")
BUT22 = _T(23, "BUT22")
BUT23 = _T(24, "BUT23")
BUT24 = _T(25, "BUT24")
BUT25 = _T(26, "BUT25")
BUT26 = _T(27, "BUT26")
BUT27 = _T(28, "BUT27")
BUT28 = _T(29, "BUT28")
BUT29 = _T(30, "BUT29")
BUT30 = _T(31, "BUT30")
BUT31 = _T(32, "BUT31")
BUT32 = _T(33, "BUT32")
BUT33 = _T(34, "BUT33")
BUT34 = _T(35, "BUT34")
BUT35 = _T(36, "BUT35")
BUT36 = _T(37, "BUT36")
BUT37 = _T(38, "BUT37")
BUT38 = _T(39, "BUT38")
BUT39 = _T(40, "BUT39")
BUT40 = _T(41, "BUT40")
BUT41 = _T(42, "BUT41")
BUT42 = _T(43, "BUT42")
BUT43 = _T(44, "BUT43")
BUT44 = _T(45, "BUT44")
BUT45 = _T(46, "BUT45")
BUT46 = _T(47, "BUT46")
BUT47 = _T(48, "BUT47")
BUT48 = _T(49, "BUT48")
BUT49 = _T(50, "BUT49")
BUT50 = _T(51, "BUT50")
BUT51 = _T(52, "BUT51")
BUT52 = _T(53, "BUT52")
BUT53 = _T(54, "BUT53")
BUT54 = _T(55, "BUT54")
BUT55 = _T(56, "BUT55")
BUT56 = _T(57, "BUT56")
BUT57 = _T(58, "BUT57")
BUT58 = _T(59, "BUT58")
BUT59 = _T(60, "BUT59")
BUT60 = _T(61, "BUT60")
BUT61 = _T(62, "BUT61")
BUT62 = _T(63, "BUT62")
BUT63 = _T(64, "BUT63")
BUT64 = _T(65, "BUT64")
BUT65 = _T(66, "BUT65")
BUT66 = _T(67, "BUT66")
BUT67 = _T(68, "BUT67")
BUT68 = _T(69, "BUT68")
BUT69 = _T(70, "BUT69")
BUT70 = _T(71, "BUT70")
BUT71 = _T(72, "BUT71")
BUT72 = _T(73, "BUT72")
BUT73 = _T(74, "BUT73")
BUT74 = _T(75, "BUT74")
BUT75 = _T(76, "BUT75")
BUT76 = _T(77, "BUT76")
BUT77 = _T(78, "BUT77")
BUT78 = _T(79, "BUT78")
BUT79 = _T(80, "BUT79")
BUT80 = _T(81, "BUT80")
BUT81 = _T(82, "BUT81")
BUT82 = _T(83, "BUT82")
MAXKBDBUT = _T(83, "MAXKBDBUT")

# Buttons by number: mouse, light pen, bitpad (100-109), button box (110-141)
BUT100 = _T(101, "BUT100")
BUT101 = _T(102, "BUT101")
BUT102 = _T(103, "BUT102")
BUT103 = _T(104, "BUT103")
BUT104 = _T(105, "BUT104")
BUT105 = _T(106, "BUT105")
BUT106 = _T(107, "BUT106")
BUT107 = _T(108, "BUT107")
BUT108 = _T(109, "BUT108")
BUT109 = _T(110, "BUT109")
BUT110 = _T(111, "BUT110")
BUT111 = _T(112, "BUT111")
BUT112 = _T(113, "BUT112")
BUT113 = _T(114, "BUT113")
BUT114 = _T(115, "BUT114")
BUT115 = _T(116, "BUT115")
BUT116 = _T(117, "BUT116")
BUT117 = _T(118, "BUT117")
BUT118 = _T(119, "BUT118")
BUT119 = _T(120, "BUT119")
BUT120 = _T(121, "BUT120")
BUT121 = _T(122, "BUT121")
BUT122 = _T(123, "BUT122")
BUT123 = _T(124, "BUT123")
BUT124 = _T(125, "BUT124")
BUT125 = _T(126, "BUT125")
BUT126 = _T(127, "BUT126")
BUT127 = _T(128, "BUT127")
BUT128 = _T(129, "BUT128")
BUT129 = _T(130, "BUT129")
BUT130 = _T(131, "BUT130")
BUT131 = _T(132, "BUT131")
BUT132 = _T(133, "BUT132")
BUT133 = _T(134, "BUT133")
BUT134 = _T(135, "BUT134")
BUT135 = _T(136, "BUT135")
BUT136 = _T(137, "BUT136")
BUT137 = _T(138, "BUT137")
BUT138 = _T(139, "BUT138")
BUT139 = _T(140, "BUT139")
BUT140 = _T(141, "BUT140")
BUT141 = _T(142, "BUT141")

# Buttons by number: extended keyboard (142-168)
BUT142 = _T(143, "BUT142")
BUT143 = _T(144, "BUT143")
BUT144 = _T(145, "BUT144")
BUT145 = _T(146, "BUT145")
BUT146 = _T(147, "BUT146")
BUT147 = _T(148, "BUT147")
BUT148 = _T(149, "BUT148")
BUT149 = _T(150, "BUT149")
BUT150 = _T(151, "BUT150")
BUT151 = _T(152, "BUT151")
BUT152 = _T(153, "BUT152")
BUT153 = _T(154, "BUT153")
BUT154 = _T(155, "BUT154")
BUT155 = _T(156, "BUT155")
BUT156 = _T(157, "BUT156")
BUT157 = _T(158, "BUT157")
BUT158 = _T(159, "BUT158")
BUT159 = _T(160, "BUT159")
BUT160 = _T(161, "BUT160")
BUT161 = _T(162, "BUT161")
BUT162 = _T(163, "BUT162")
BUT163 = _T(164, "BUT163")
BUT164 = _T(165, "BUT164")
BUT165 = _T(166, "BUT165")
BUT166 = _T(167, "BUT166")
BUT167 = _T(168, "BUT167")
BUT168 = _T(169, "BUT168")

# Buttons by number: Spaceball buttons (181-189)
BUT181 = _T(182, "BUT181")
BUT182 = _T(183, "BUT182")
BUT183 = _T(184, "BUT183")
BUT184 = _T(185, "BUT184")
BUT185 = _T(186, "BUT185")
BUT186 = _T(187, "BUT186")
BUT187 = _T(188, "BUT187")
BUT188 = _T(189, "BUT188")
BUT189 = _T(190, "BUT189")

# Mouse and other buttons (LEFTMOUSE is the highest-numbered mouse button)
MOUSE1 = _T(101, "MOUSE1")
MOUSE2 = _T(102, "MOUSE2")
MOUSE3 = _T(103, "MOUSE3")
LEFTMOUSE = _T(103, "LEFTMOUSE")
MIDDLEMOUSE = _T(102, "MIDDLEMOUSE")
RIGHTMOUSE = _T(101, "RIGHTMOUSE")
LPENBUT = _T(104, "LPENBUT")
BPAD0 = _T(105, "BPAD0")
BPAD1 = _T(106, "BPAD1")
BPAD2 = _T(107, "BPAD2")
BPAD3 = _T(108, "BPAD3")
LPENVALID = _T(109, "LPENVALID")

# Button box switches
SWBASE = _T(111, "SWBASE")
SW0 = _T(111, "SW0")
SW1 = _T(112, "SW1")
SW2 = _T(113, "SW2")
SW3 = _T(114, "SW3")
SW4 = _T(115, "SW4")
SW5 = _T(116, "SW5")
SW6 = _T(117, "SW6")
SW7 = _T(118, "SW7")
SW8 = _T(119, "SW8")
SW9 = _T(120, "SW9")
SW10 = _T(121, "SW10")
SW11 = _T(122, "SW11")
SW12 = _T(123, "SW12")
SW13 = _T(124, "SW13")
SW14 = _T(125, "SW14")
SW15 = _T(126, "SW15")
SW16 = _T(127, "SW16")
SW17 = _T(128, "SW17")
SW18 = _T(129, "SW18")
SW19 = _T(130, "SW19")
SW20 = _T(131, "SW20")
SW21 = _T(132, "SW21")
SW22 = _T(133, "SW22")
SW23 = _T(134, "SW23")
SW24 = _T(135, "SW24")
SW25 = _T(136, "SW25")
SW26 = _T(137, "SW26")
SW27 = _T(138, "SW27")
SW28 = _T(139, "SW28")
SW29 = _T(140, "SW29")
SW30 = _T(141, "SW30")
SW31 = _T(142, "SW31")

# Spaceball buttons
SBBASE = _T(182, "SBBASE")
SBPICK = _T(182, "SBPICK")
SBBUT1 = _T(183, "SBBUT1")
SBBUT2 = _T(184, "SBBUT2")
SBBUT3 = _T(185, "SBBUT3")
SBBUT4 = _T(186, "SBBUT4")
SBBUT5 = _T(187, "SBBUT5")
SBBUT6 = _T(188, "SBBUT6")
SBBUT7 = _T(189, "SBBUT7")
SBBUT8 = _T(190, "SBBUT8")

# Standard keyboard: letters
AKEY = _T(11, "AKEY")
BKEY = _T(36, "BKEY")
CKEY = _T(28, "CKEY")
DKEY = _T(18, "DKEY")
EKEY = _T(17, "EKEY")
FKEY = _T(19, "FKEY")
GKEY = _T(26, "GKEY")
HKEY = _T(27, "HKEY")
IKEY = _T(40, "IKEY")
JKEY = _T(34, "JKEY")
KKEY = _T(35, "KKEY")
LKEY = _T(42, "LKEY")
MKEY = _T(44, "MKEY")
NKEY = _T(37, "NKEY")
OKEY = _T(41, "OKEY")
PKEY = _T(48, "PKEY")
QKEY = _T(10, "QKEY")
RKEY = _T(24, "RKEY")
SKEY = _T(12, "SKEY")
TKEY = _T(25, "TKEY")
UKEY = _T(33, "UKEY")
VKEY = _T(29, "VKEY")
WKEY = _T(16, "WKEY")
XKEY = _T(21, "XKEY")
YKEY = _T(32, "YKEY")
ZKEY = _T(20, "ZKEY")

# Standard keyboard: digits
ZEROKEY = _T(46, "ZEROKEY")
ONEKEY = _T(8, "ONEKEY")
TWOKEY = _T(14, "TWOKEY")
THREEKEY = _T(15, "THREEKEY")
FOURKEY = _T(22, "FOURKEY")
FIVEKEY = _T(23, "FIVEKEY")
SIXKEY = _T(30, "SIXKEY")
SEVENKEY = _T(31, "SEVENKEY")
EIGHTKEY = _T(38, "EIGHTKEY")
NINEKEY = _T(39, "NINEKEY")

# Standard keyboard: modifiers, control and punctuation keys
BREAKKEY = _T(1, "BREAKKEY")
SETUPKEY = _T(2, "SETUPKEY")
CTRLKEY = _T(3, "CTRLKEY")
LEFTCTRLKEY = _T(3, "LEFTCTRLKEY")
CAPSLOCKKEY = _T(4, "CAPSLOCKKEY")
RIGHTSHIFTKEY = _T(5, "RIGHTSHIFTKEY")
LEFTSHIFTKEY = _T(6, "LEFTSHIFTKEY")
NOSCRLKEY = _T(13, "NOSCRLKEY")
ESCKEY = _T(7, "ESCKEY")
TABKEY = _T(9, "TABKEY")
RETKEY = _T(51, "RETKEY")
SPACEKEY = _T(83, "SPACEKEY")
LINEFEEDKEY = _T(60, "LINEFEEDKEY")
BACKSPACEKEY = _T(61, "BACKSPACEKEY")
DELKEY = _T(62, "DELKEY")
SEMICOLONKEY = _T(43, "SEMICOLONKEY")
PERIODKEY = _T(52, "PERIODKEY")
COMMAKEY = _T(45, "COMMAKEY")
QUOTEKEY = _T(50, "QUOTEKEY")
ACCENTGRAVEKEY = _T(55, "ACCENTGRAVEKEY")
MINUSKEY = _T(47, "MINUSKEY")
VIRGULEKEY = _T(53, "VIRGULEKEY")
BACKSLASHKEY = _T(57, "BACKSLASHKEY")
EQUALKEY = _T(54, "EQUALKEY")
LEFTBRACKETKEY = _T(49, "LEFTBRACKETKEY")
RIGHTBRACKETKEY = _T(56, "RIGHTBRACKETKEY")

# Standard keyboard: arrow keys
LEFTARROWKEY = _T(73, "LEFTARROWKEY")
DOWNARROWKEY = _T(74, "DOWNARROWKEY")
RIGHTARROWKEY = _T(80, "RIGHTARROWKEY")
UPARROWKEY = _T(81, "UPARROWKEY")

# Standard keyboard: numeric pad
PAD0 = _T(59, "PAD0")
PAD1 = _T(58, "PAD1")
PAD2 = _T(64, "PAD2")
PAD3 = _T(65, "PAD3")
PAD4 = _T(63, "PAD4")
PAD5 = _T(69, "PAD5")
PAD6 = _T(70, "PAD6")
PAD7 = _T(67, "PAD7")
PAD8 = _T(68, "PAD8")
PAD9 = _T(75, "PAD9")
PADPF1 = _T(72, "PADPF1")
PADPF2 = _T(71, "PADPF2")
PADPF3 = _T(79, "PADPF3")
PADPF4 = _T(78, "PADPF4")
PADPERIOD = _T(66, "PADPERIOD")
PADMINUS = _T(76, "PADMINUS")
PADCOMMA = _T(77, "PADCOMMA")
PADENTER = _T(82, "PADENTER")

# Extended keyboard
LEFTALTKEY = _T(143, "LEFTALTKEY")
RIGHTALTKEY = _T(144, "RIGHTALTKEY")
RIGHTCTRLKEY = _T(145, "RIGHTCTRLKEY")
F1KEY = _T(146, "F1KEY")
F2KEY = _T(147, "F2KEY")
F3KEY = _T(148, "F3KEY")
F4KEY = _T(149, "F4KEY")
F5KEY = _T(150, "F5KEY")
F6KEY = _T(151, "F6KEY")
F7KEY = _T(152, "F7KEY")
F8KEY = _T(153, "F8KEY")
F9KEY = _T(154, "F9KEY")
F10KEY = _T(155, "F10KEY")
F11KEY = _T(156, "F11KEY")
F12KEY = _T(157, "F12KEY")
PRINTSCREENKEY = _T(158, "PRINTSCREENKEY")
SCROLLLOCKKEY = _T(159, "SCROLLLOCKKEY")
PAUSEKEY = _T(160, "PAUSEKEY")
INSERTKEY = _T(161, "INSERTKEY")
HOMEKEY = _T(162, "HOMEKEY")
PAGEUPKEY = _T(163, "PAGEUPKEY")
ENDKEY = _T(164, "ENDKEY")
PAGEDOWNKEY = _T(165, "PAGEDOWNKEY")
NUMLOCKKEY = _T(166, "NUMLOCKKEY")
PADVIRGULEKEY = _T(167, "PADVIRGULEKEY")
PADASTERKEY = _T(168, "PADASTERKEY")
PADPLUSKEY = _T(169, "PADPLUSKEY")

# Valuators: dials, mouse, light pen, bitpad, cursor, ghost
SGIRESERVED = _T(256, "SGIRESERVED")
DIAL0 = _T(257, "DIAL0")
DIAL1 = _T(258, "DIAL1")
DIAL2 = _T(259, "DIAL2")
DIAL3 = _T(260, "DIAL3")
DIAL4 = _T(261, "DIAL4")
DIAL5 = _T(262, "DIAL5")
DIAL6 = _T(263, "DIAL6")
DIAL7 = _T(264, "DIAL7")
DIAL8 = _T(265, "DIAL8")
MOUSEX = _T(266, "MOUSEX")
MOUSEY = _T(267, "MOUSEY")
LPENX = _T(268, "LPENX")
LPENY = _T(269, "LPENY")
BPADX = _T(270, "BPADX")
BPADY = _T(271, "BPADY")
CURSORX = _T(272, "CURSORX")
CURSORY = _T(273, "CURSORY")
GHOSTX = _T(274, "GHOSTX")
GHOSTY = _T(275, "GHOSTY")

# Valuators: Spaceball
SBTX = _T(276, "SBTX")
SBTY = _T(277, "SBTY")
SBTZ = _T(278, "SBTZ")
SBRX = _T(279, "SBRX")
SBRY = _T(280, "SBRY")
SBRZ = _T(281, "SBRZ")
SBPERIOD = _T(282, "SBPERIOD")

# Timers
TIMER0 = _T(515, "TIMER0")
TIMER1 = _T(516, "TIMER1")
TIMER2 = _T(517, "TIMER2")
TIMER3 = _T(518, "TIMER3")

# Pseudo-devices (window-manager and queue events)
KEYBD = _T(513, "KEYBD")
RAWKEYBD = _T(514, "RAWKEYBD")
VALMARK = _T(523, "VALMARK")
GERROR = _T(524, "GERROR")
REDRAW = _T(528, "REDRAW")
WMSEND = _T(529, "WMSEND")
WMREPLY = _T(530, "WMREPLY")
WMGFCLOSE = _T(531, "WMGFCLOSE")
WMTXCLOSE = _T(532, "WMTXCLOSE")
MODECHANGE = _T(533, "MODECHANGE")
INPUTCHANGE = _T(534, "INPUTCHANGE")
QFULL = _T(535, "QFULL")
PIECECHANGE = _T(536, "PIECECHANGE")
WINCLOSE = _T(537, "WINCLOSE")
QREADERROR = _T(538, "QREADERROR")
WINFREEZE = _T(539, "WINFREEZE")
WINTHAW = _T(540, "WINTHAW")
REDRAWICONIC = _T(541, "REDRAWICONIC")
WINQUIT = _T(542, "WINQUIT")
DEPTHCHANGE = _T(543, "DEPTHCHANGE")
KEYBDFNAMES = _T(544, "KEYBDFNAMES")
KEYBDFSTRINGS = _T(545, "KEYBDFSTRINGS")
WINSHUT = _T(546, "WINSHUT")
DRAWOVERLAY = _T(547, "DRAWOVERLAY")
VIDEO = _T(548, "VIDEO")

# The button dopup() menus use
MENUBUTTON = _T(101, "MENUBUTTON")

# Highest SGI-reserved device number
MAXSGIDEVICE = _T(20000, "MAXSGIDEVICE")


#: Every device name, in definition order (``from vgxsim.DEVICE import *`` exports these).
__all__ = [_n for _n, _v in globals().items() if isinstance(_v, _T)]

# Names that are never the canonical name of a number: range offsets/counts, the
# numbered BUTn aliases, and the secondary names of devices that have a primary one.
_NOT_CANONICAL = frozenset(
    """
    BUTOFFSET VALOFFSET PSEUDOFFSET BUT2OFFSET TIMOFFSET XKBDOFFSET BUTCOUNT VALCOUNT
    TIMCOUNT XKBDCOUNT USERBUTOFFSET USERVALOFFSET USERPSEUDOFFSET MAXKBDBUT MAXSGIDEVICE
    MOUSE1 MOUSE2 MOUSE3 SWBASE SBBASE LEFTCTRLKEY MENUBUTTON
    """.split()
)


def _build_tables() -> tuple[dict[str, _T], dict[int, _T]]:
    by_name: dict[str, _T] = {}
    primary: dict[int, _T] = {}
    fallback: dict[int, _T] = {}
    g = globals()
    for name in __all__:
        tok = g[name]
        by_name[name] = tok
        secondary = name in _NOT_CANONICAL or (name.startswith("BUT") and name[3:].isdigit())
        table = fallback if secondary else primary
        table.setdefault(int(tok), tok)
    canonical = dict(fallback)
    canonical.update(primary)
    return by_name, dict(sorted(canonical.items()))


_BY_NAME, _CANONICAL = _build_tables()

_MISSING = object()


def by_name(name: str) -> _T:
    """The device number (a Token) called ``name``.

    Case-insensitive and ignores surrounding blanks: ``by_name("esckey") == 7``.
    Any defined name works, aliases included (``by_name("MENUBUTTON") == 101``).
    Raises :class:`KeyError` for an unknown name.
    """
    if not isinstance(name, str):
        raise TypeError(f"device name must be a string, got {type(name).__name__}")
    key = name.strip().upper()
    try:
        return _BY_NAME[key]
    except KeyError:
        raise KeyError(f"unknown IRIS GL device name {name!r}") from None


def name_of(number: int, default: object = _MISSING) -> str:
    """The canonical name of device ``number``: ``name_of(101) == "RIGHTMOUSE"``,
    ``name_of(515) == "TIMER0"``, ``name_of(7) == "ESCKEY"``.

    Numbers known only under a ``BUTn`` name give that (``name_of(110) == "BUT109"``).
    An unknown number raises :class:`KeyError` unless ``default`` is given.
    """
    tok = _CANONICAL.get(int(number))
    if tok is None:
        if default is _MISSING:
            raise KeyError(f"no IRIS GL device numbered {number!r}")
        return default  # type: ignore[return-value]
    return tok.name


def device(number: int) -> _T:
    """The canonical :class:`~vgxsim.tokens.Token` for ``number`` (``device(7)`` reprs as
    ``ESCKEY``), e.g. to turn a raw ``qread()`` number into a readable one.
    Unknown numbers raise :class:`KeyError`."""
    tok = _CANONICAL.get(int(number))
    if tok is None:
        raise KeyError(f"no IRIS GL device numbered {number!r}")
    return tok


# Device classes: the ISBUTTON, ISVALUATOR, ISTIMER and ISKEYBD macros of device.h.


def is_button(dev: int) -> bool:
    """True for button devices (keys, mouse buttons, switches; user buttons too)."""
    return BUTOFFSET <= dev < VALOFFSET or BUT2OFFSET <= dev < USERVALOFFSET


def is_valuator(dev: int) -> bool:
    """True for valuators (MOUSEX/MOUSEY, dials, ...; user valuators too)."""
    return VALOFFSET <= dev < PSEUDOFFSET or USERVALOFFSET <= dev < USERPSEUDOFFSET


def is_timer(dev: int) -> bool:
    """True for TIMER0..TIMER3."""
    return TIMOFFSET <= dev < TIMOFFSET + TIMCOUNT


def is_keyboard(dev: int) -> bool:
    """True for standard (BUT0..MAXKBDBUT) and extended-keyboard keys."""
    return BUT0 <= dev <= MAXKBDBUT or XKBDOFFSET <= dev < XKBDOFFSET + XKBDCOUNT
