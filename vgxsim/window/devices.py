"""SDL input to IRIS GL devices: keys, mouse buttons, screen coordinates.

The key devices are those of the IRIS keyboard (``device.h``): a key press makes
``(KEY, 1)``, its release ``(KEY, 0)``; a press that types a character also makes
``(KEYBD, code)`` after the key's entry (the order :func:`vgxsim.events.script.keystroke`
uses).  Keys without an IRIS counterpart (Super, Menu ...) make only KEYBD, if anything.

Mouse buttons: SDL 1/2/3 are the left, middle and right buttons: LEFTMOUSE, MIDDLEMOUSE,
RIGHTMOUSE (= MENUBUTTON).  MOUSEX/MOUSEY are screen coordinates with the origin at the
lower left (getvaluator(3G)): the window's IRIS origin (``getorigin``) plus the
position in the window, y counted from its bottom row.
"""

from __future__ import annotations

from .sdl import pygame

__all__ = ["KEY_DEVICES", "MOUSE_BUTTONS", "key_device", "screen_position"]

#: SDL mouse button number -> IRIS device name.
MOUSE_BUTTONS = {1: "LEFTMOUSE", 2: "MIDDLEMOUSE", 3: "RIGHTMOUSE"}

_NAMED = {
    pygame.K_ESCAPE: "ESCKEY", pygame.K_TAB: "TABKEY", pygame.K_RETURN: "RETKEY",
    pygame.K_SPACE: "SPACEKEY", pygame.K_BACKSPACE: "BACKSPACEKEY",
    pygame.K_DELETE: "DELKEY", pygame.K_LSHIFT: "LEFTSHIFTKEY",
    pygame.K_RSHIFT: "RIGHTSHIFTKEY", pygame.K_LCTRL: "LEFTCTRLKEY",
    pygame.K_RCTRL: "RIGHTCTRLKEY", pygame.K_LALT: "LEFTALTKEY",
    pygame.K_RALT: "RIGHTALTKEY", pygame.K_CAPSLOCK: "CAPSLOCKKEY",
    pygame.K_LEFT: "LEFTARROWKEY", pygame.K_RIGHT: "RIGHTARROWKEY",
    pygame.K_UP: "UPARROWKEY", pygame.K_DOWN: "DOWNARROWKEY",
    pygame.K_SEMICOLON: "SEMICOLONKEY", pygame.K_PERIOD: "PERIODKEY",
    pygame.K_COMMA: "COMMAKEY", pygame.K_QUOTE: "QUOTEKEY",
    pygame.K_BACKQUOTE: "ACCENTGRAVEKEY", pygame.K_MINUS: "MINUSKEY",
    pygame.K_SLASH: "VIRGULEKEY", pygame.K_BACKSLASH: "BACKSLASHKEY",
    pygame.K_EQUALS: "EQUALKEY", pygame.K_LEFTBRACKET: "LEFTBRACKETKEY",
    pygame.K_RIGHTBRACKET: "RIGHTBRACKETKEY", pygame.K_SCROLLLOCK: "NOSCRLKEY",
    pygame.K_PAUSE: "BREAKKEY",
}
_DIGITS = ("ZEROKEY", "ONEKEY", "TWOKEY", "THREEKEY", "FOURKEY", "FIVEKEY", "SIXKEY",
           "SEVENKEY", "EIGHTKEY", "NINEKEY")

#: SDL key code -> IRIS key device name.
KEY_DEVICES: dict[int, str] = dict(_NAMED)
KEY_DEVICES.update({getattr(pygame, f"K_{c}"): f"{c.upper()}KEY"
                    for c in "abcdefghijklmnopqrstuvwxyz"})
KEY_DEVICES.update({getattr(pygame, f"K_{d}"): _DIGITS[d] for d in range(10)})
KEY_DEVICES.update({getattr(pygame, f"K_F{n}"): f"F{n}KEY" for n in range(1, 13)})


def key_device(key: int) -> str | None:
    """The IRIS key device of an SDL key code, or None."""
    return KEY_DEVICES.get(key)


def screen_position(pos: tuple[int, int], origin: tuple[int, int],
                    height: int) -> tuple[int, int]:
    """IRIS screen coordinates of an SDL window position.

    Parameters
    ----------
    pos : (int, int)
        SDL position in the window, y down from the top row.
    origin : (int, int)
        The window's lower-left corner on the IRIS screen.
    height : int
        The window's height in pixels.
    """
    return origin[0] + int(pos[0]), origin[1] + (height - 1 - int(pos[1]))
