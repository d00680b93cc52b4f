"""Screens and the window system: scrnselect, scrnattach, getwscrn, ismex.

The emulated workstation has one screen, number 0 (getgdesc(GD_NSCRNS) is 1), run by
a window manager (GD_WSYS_4S, GD_SCRNTYPE_WM).  scrnselect(3G) "returns the
previously selected screen, or -1 if there was an error (e.g., gsnr is not a valid
screen number)" and on error "leaves the current screen selection unchanged";
scrnattach(3G) answers the same way for the screen that takes keyboard and mouse
input.  Both may be called before any window is open.
"""

from __future__ import annotations

from ._core import as_int, current, gl_function
from ._query import GDESC

__all__ = ["scrnselect", "scrnattach", "getwscrn", "ismex"]


def _screen(name: str, gsnr) -> int:
    n = as_int(name, (gsnr,), "gsnr", gsnr)
    return 0 if 0 <= n < GDESC["GD_NSCRNS"] else -1


@gl_function(record=False)
def scrnselect(gsnr: int) -> int:
    """Select the screen new windows open on (scrnselect(3G)).

    Returns
    -------
    int
        The screen selected before (0, the only one), or -1 when ``gsnr`` is no
        screen (the selection is unchanged).
    """
    return _screen("scrnselect", gsnr)


@gl_function(record=False)
def scrnattach(gsnr: int) -> int:
    """Attach keyboard and mouse input to a screen (scrnattach(3G)): the previously
    attached screen (0), or -1 when ``gsnr`` is no screen."""
    return _screen("scrnattach", gsnr)


@gl_function(record=False)
def getwscrn() -> int:
    """The screen the current window is on: 0 (getwscrn(3G))."""
    current("getwscrn")
    return 0


@gl_function(record=False)
def ismex() -> int:
    """1 (TRUE): windows here are managed by a window manager (ismex(3G); getgdesc
    answers GD_WSYS_4S and GD_SCRNTYPE_WM), so programs take their windowed path."""
    return 1
