"""The IRIS Font Manager, as CPython's historical ``fm`` module had it.

Under ``vgxsim run`` this module is importable as ``fm`` (like ``gl``, ``GL`` and
``DEVICE``).  Two spellings of every call are provided:

* the binding's (CPython ``Modules/fmmodule.c``): module functions ``init()``,
  ``findfont(name)``, ``enumerate()``, ``prstr(s)``, ``setpath(path)``,
  ``fontpath()``, and methods of the font handle ``findfont`` returns:
  ``fh.scalefont(size)``, ``fh.setfont()``, ``fh.getfontname()``,
  ``fh.getcomment()``, ``fh.getfontinfo()``, ``fh.getstrwidth(s)``;
* the C library's (fmclient.h), for programs ported from C: ``fminit()``,
  ``fmenumerate(callback)``, ``fmfindfont(name)``, ``fmscalefont(fh, size)``,
  ``fmsetfont(fh)``, ``fmprstr(s)``, ``fmgetstrwidth(fh, s)``, ``fmgetfontinfo(fh)``,
  ``fmgetfontname(fh)``, ``fmfreefont(fh)``.

Faces.  vgxsim ships one design, its built-in bitmap font (font 0, metrics in
:mod:`vgxsim.gl._fm`).  It is offered under the names in :data:`FACES` -- the face
names IRIS programs commonly ask for -- so that such programs run; every face draws
the same fixed-width design (``getfontinfo`` says so: ``fixed_width`` is 1).  An
unknown name makes ``findfont`` raise RuntimeError, as the binding did when the C
call returned no handle (``fmfindfont`` returns None, the C NULL).

Sizes.  ``findfont`` returns a 1-point face, which programs scale
(``findfont('Times-Roman').scalefont(12)``); ``scalefont`` multiplies the size, and a
face of ``s`` points draws the 13-pixel cell ``s`` pixels high (1 point = 1 pixel on
the screen): the glyph bitmaps are resampled nearest-neighbour, advances and the
baseline offset rounded to whole pixels (:meth:`RasterFont.scaled`).  ``setfont``
makes the face the current raster font (it defines it with a font number of its own
and calls ``font``), so ``prstr`` is ``charstr`` in that face and ``strwidth``,
``getheight`` and ``getdescender`` describe it.

``fmgetfontinfo`` / ``getfontinfo`` return the binding's 8-tuple
``(printermatched, fixed_width, xorig, yorig, xsize, ysize, height, nglyphs)``; for
the 13-point face (the unscaled design): ``(0, 1, 0, 3, 8, 13, 13, 95)``.
"""

from __future__ import annotations

from collections.abc import Callable

from vgxsim.gl import _fm
from vgxsim.gl._core import GLTypeError, GLValueError, describe, topic_state

__all__ = [
    "FACES", "FontHandle", "init", "findfont", "enumerate", "prstr", "setpath", "fontpath",
    "fminit", "fmenumerate", "fmfindfont", "fmscalefont", "fmsetfont", "fmprstr",
    "fmgetstrwidth", "fmgetfontinfo", "fmgetfontname", "fmfreefont",
]

#: Face names fm offers; all draw vgxsim's built-in design.
FACES = ("Screen", "Courier", "Helvetica", "Times-Roman", "Iris")

_DESIGN_POINTS = 13  # the built-in cell height in pixels: the unscaled design's size
_FONT_PATH = "vgxsim:built-in"


class FontHandle:
    """An fm font handle: a face at a size in points (pixels)."""

    def __init__(self, name: str, points: float):
        self.name = name
        self.points = float(points)

    def __repr__(self) -> str:
        return f"<font handle {self.name!r} {self.points:g} pt>"

    def _font(self) -> _fm.RasterFont:
        return _scaled(self.points)

    # -- the binding's methods --
    def scalefont(self, size: float) -> FontHandle:
        """A handle to this face scaled by ``size`` (fmscalefont(3G))."""
        s = _number("scalefont", (size,), size)
        if s <= 0:
            raise GLValueError(f"{describe('scalefont', (size,))}: the scale must be > 0")
        return FontHandle(self.name, self.points * s)

    def setfont(self) -> None:
        """Make this face the current raster font (fmsetfont(3G))."""
        import vgxsim.gl as gl

        state = _fm_state()
        n = state.get(self.points)
        if n is None or _fm.raster_font(n) is not self._font():
            n = state[self.points] = _fm.add_private_font(self._font())
        gl.font(n)

    def getfontname(self) -> str:
        """The face's name."""
        return self.name

    def getcomment(self) -> str:
        """The face's comment."""
        return "vgxsim built-in 8x13 bitmap design"

    def getfontinfo(self) -> tuple[int, int, int, int, int, int, int, int]:
        """(printermatched, fixed_width, xorig, yorig, xsize, ysize, height, nglyphs)."""
        return self._font().info()

    def getstrwidth(self, s: str) -> int:
        """Width of ``s`` in pixels in this face (fmgetstrwidth(3G))."""
        return self._font().string_width(_text("getstrwidth", s))


def _number(name: str, args: tuple, v) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise GLTypeError(f"{describe(name, args)}: expected a number, not "
                          f"{type(v).__name__}")
    return float(v)


def _text(name: str, s) -> str:
    if not isinstance(s, str):
        raise GLTypeError(f"{describe(name, (s,))}: expected a str, not {type(s).__name__}")
    return s


def _fm_state() -> dict:
    return topic_state("fm", dict)  # points -> raster font number


def _scaled(points: float) -> _fm.RasterFont:
    cache = topic_state("fm-faces", dict)
    f = cache.get(points)
    if f is None:
        f = cache[points] = _fm.raster_font(0).scaled(points / _DESIGN_POINTS)
    return f


def _handle(name: str, fh) -> FontHandle:
    if not isinstance(fh, FontHandle):
        raise GLTypeError(f"{name}: expected a font handle (fmfindfont), not "
                          f"{type(fh).__name__}")
    return fh


# -- the binding's module functions ----------------------------------------------------
def init() -> None:
    """fminit: nothing to set up (the faces are built in)."""


def findfont(name: str) -> FontHandle:
    """A 1-point handle to face ``name``; RuntimeError for a face fm does not have."""
    if _text("findfont", name) not in FACES:
        raise RuntimeError("error creating new font handle")
    return FontHandle(name, 1.0)


def enumerate() -> list[str]:  # noqa: A001 - the binding's name
    """The names of the faces fm has."""
    return list(FACES)


def prstr(s: str) -> None:
    """Draw ``s`` at the current character position in the current font (fmprstr)."""
    import vgxsim.gl as gl

    gl.charstr(_text("prstr", s))


def setpath(path: str) -> None:
    """fmsetpath: accepted; the faces do not come from files."""
    _text("setpath", path)


def fontpath() -> str:
    """fmfontpath: where the faces come from."""
    return _FONT_PATH


# -- the C library's names ----------------------------------------------------------------
def fminit() -> None:
    """fminit(): see :func:`init`."""
    init()


def fmenumerate(callback: Callable[[str], object] | None = None) -> list[str]:
    """fmenumerate(callback): call ``callback(name)`` for every face; also returns the
    names (the binding's ``enumerate()``)."""
    names = enumerate()
    if callback is not None:
        for n in names:
            callback(n)
    return names


def fmfindfont(name: str) -> FontHandle | None:
    """fmfindfont(name): a 1-point handle, or None (the C NULL) for an unknown face."""
    try:
        return findfont(name)
    except RuntimeError:
        return None


def fmscalefont(fh: FontHandle, size: float) -> FontHandle:
    """fmscalefont(fh, size): ``fh`` scaled by ``size``."""
    return _handle("fmscalefont", fh).scalefont(size)


def fmsetfont(fh: FontHandle) -> None:
    """fmsetfont(fh): make ``fh`` the current raster font."""
    _handle("fmsetfont", fh).setfont()


def fmprstr(s: str) -> None:
    """fmprstr(s): see :func:`prstr`."""
    prstr(s)


def fmgetstrwidth(fh: FontHandle, s: str) -> int:
    """fmgetstrwidth(fh, s): width of ``s`` in pixels in ``fh``."""
    return _handle("fmgetstrwidth", fh).getstrwidth(s)


def fmgetfontinfo(fh: FontHandle) -> tuple[int, int, int, int, int, int, int, int]:
    """fmgetfontinfo(fh): the binding's 8-tuple (module docstring)."""
    return _handle("fmgetfontinfo", fh).getfontinfo()


def fmgetfontname(fh: FontHandle) -> str:
    """fmgetfontname(fh): the face's name."""
    return _handle("fmgetfontname", fh).getfontname()


def fmfreefont(fh: FontHandle) -> None:
    """fmfreefont(fh): nothing to free."""
    _handle("fmfreefont", fh)
