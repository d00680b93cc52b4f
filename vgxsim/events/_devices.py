"""Local device numbers used by :mod:`vgxsim.events` (SGI ``device.h`` values).

:mod:`vgxsim.DEVICE` is the project's full device table.  The events package only
needs a few dozen numbers and must work without it, so it keeps this private copy
of the ones it uses (values as in SGI's ``device.h`` and the old CPython
``DEVICE.py``).  :func:`resolve` prefers ``vgxsim.DEVICE.by_name`` when that module
exists and falls back to this table.
"""

from __future__ import annotations

# Device number ranges (device.h: BUTOFFSET, VALOFFSET, PSEUDOFFSET, BUT2OFFSET,
# USERBUTOFFSET, USERVALOFFSET, USERPSEUDOFFSET).
BUTTON_RANGES = ((1, 256), (3840, 4096), (4096, 12288))
VALUATOR_RANGES = ((256, 512), (12288, 16384))

# Pseudo devices.
KEYBD = 513
TIMER0, TIMER1, TIMER2, TIMER3 = 515, 516, 517, 518
REDRAW = 528
INPUTCHANGE = 534
WINQUIT = 542
DEPTHCHANGE = 543
WINSHUT = 546
# Valuators.
MOUSEX = 266
MOUSEY = 267
# Buttons.
LEFTMOUSE = 103
MIDDLEMOUSE = 102
RIGHTMOUSE = 101
ESCKEY = 7
LEFTSHIFTKEY = 6

TIMERS = (TIMER0, TIMER1, TIMER2, TIMER3)

TABLE: dict[str, int] = {
    "NULLDEV": 0,
    "KEYBD": KEYBD,
    "RAWKEYBD": 514,
    "TIMER0": TIMER0,
    "TIMER1": TIMER1,
    "TIMER2": TIMER2,
    "TIMER3": TIMER3,
    "REDRAW": REDRAW,
    "INPUTCHANGE": INPUTCHANGE,
    "WINFREEZE": 539,
    "WINTHAW": 540,
    "REDRAWICONIC": 541,
    "WINQUIT": WINQUIT,
    "DEPTHCHANGE": DEPTHCHANGE,
    "WINSHUT": WINSHUT,
    "WINCLOSE": 537,
    "MOUSEX": MOUSEX,
    "MOUSEY": MOUSEY,
    "DIAL0": 257,
    "DIAL1": 258,
    "DIAL2": 259,
    "DIAL3": 260,
    "DIAL4": 261,
    "DIAL5": 262,
    "DIAL6": 263,
    "DIAL7": 264,
    "DIAL8": 265,
    "LEFTMOUSE": LEFTMOUSE,
    "MIDDLEMOUSE": MIDDLEMOUSE,
    "RIGHTMOUSE": RIGHTMOUSE,
    "MENUBUTTON": RIGHTMOUSE,
    "MOUSE1": 101,
    "MOUSE2": 102,
    "MOUSE3": 103,
    "BREAKKEY": 1,
    "SETUPKEY": 2,
    "CTRLKEY": 3,
    "LEFTCTRLKEY": 3,
    "CAPSLOCKKEY": 4,
    "RIGHTSHIFTKEY": 5,
    "LEFTSHIFTKEY": LEFTSHIFTKEY,
    "ESCKEY": ESCKEY,
    "TABKEY": 9,
    "NOSCRLKEY": 13,
    "RETKEY": 51,
    "SPACEKEY": 83,
    "LINEFEEDKEY": 60,
    "BACKSPACEKEY": 61,
    "DELKEY": 62,
    "LEFTALTKEY": 143,
    "RIGHTALTKEY": 144,
    "RIGHTCTRLKEY": 145,
    "AKEY": 11,
    "BKEY": 36,
    "CKEY": 28,
    "DKEY": 18,
    "EKEY": 17,
    "FKEY": 19,
    "GKEY": 26,
    "HKEY": 27,
    "IKEY": 40,
    "JKEY": 34,
    "KKEY": 35,
    "LKEY": 42,
    "MKEY": 44,
    "NKEY": 37,
    "OKEY": 41,
    "PKEY": 48,
    "QKEY": 10,
    "RKEY": 24,
    "SKEY": 12,
    "TKEY": 25,
    "UKEY": 33,
    "VKEY": 29,
    "WKEY": 16,
    "XKEY": 21,
    "YKEY": 32,
    "ZKEY": 20,
    "ZEROKEY": 46,
    "ONEKEY": 8,
    "TWOKEY": 14,
    "THREEKEY": 15,
    "FOURKEY": 22,
    "FIVEKEY": 23,
    "SIXKEY": 30,
    "SEVENKEY": 31,
    "EIGHTKEY": 38,
    "NINEKEY": 39,
    "SEMICOLONKEY": 43,
    "PERIODKEY": 52,
    "COMMAKEY": 45,
    "QUOTEKEY": 50,
    "ACCENTGRAVEKEY": 55,
    "MINUSKEY": 47,
    "VIRGULEKEY": 53,
    "BACKSLASHKEY": 57,
    "EQUALKEY": 54,
    "LEFTBRACKETKEY": 49,
    "RIGHTBRACKETKEY": 56,
    "LEFTARROWKEY": 73,
    "DOWNARROWKEY": 74,
    "RIGHTARROWKEY": 80,
    "UPARROWKEY": 81,
    "F1KEY": 146,
    "F2KEY": 147,
    "F3KEY": 148,
    "F4KEY": 149,
    "F5KEY": 150,
    "F6KEY": 151,
    "F7KEY": 152,
    "F8KEY": 153,
    "F9KEY": 154,
    "F10KEY": 155,
    "F11KEY": 156,
    "F12KEY": 157,
}


def is_button(dev: int) -> bool:
    """Return True if ``dev`` lies in one of IRIS GL's button ranges."""
    return any(lo <= dev < hi for lo, hi in BUTTON_RANGES)


def is_valuator(dev: int) -> bool:
    """Return True if ``dev`` lies in one of IRIS GL's valuator ranges."""
    return any(lo <= dev < hi for lo, hi in VALUATOR_RANGES)


def resolve(name: str) -> int:
    """Return the device number called ``name``.

    ``vgxsim.DEVICE.by_name`` is asked first when that module can be imported;
    the local table is the fallback.  Lookups also try the upper-case spelling,
    so ``leftmouse`` works like ``LEFTMOUSE``.

    Parameters
    ----------
    name : str
        A device name such as ``"LEFTMOUSE"``.

    Returns
    -------
    int
        The device number.

    Raises
    ------
    KeyError
        If neither table knows the name.
    """
    spellings = (name, name.upper()) if name != name.upper() else (name,)
    try:
        from vgxsim import DEVICE as device_module  # optional, written separately
    except ImportError:
        device_module = None
    by_name = getattr(device_module, "by_name", None)
    if by_name is not None:
        for spelling in spellings:
            try:
                dev = by_name(spelling)
            except (LookupError, ValueError, TypeError, AttributeError):
                continue
            if dev is not None:
                return int(dev)
    for spelling in spellings:
        if spelling in TABLE:
            return TABLE[spelling]
    raise KeyError(name)
