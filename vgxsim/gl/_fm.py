"""Raster fonts: defrasterfont, and the font table that font, charstr, strwidth,
getheight, getdescender and the font manager (:mod:`vgxsim.fm`) share.

A raster font is a table of glyph bitmaps with per-glyph placement and advance
(:class:`RasterFont`).  Font 0 is vgxsim's built-in font (:mod:`vgxsim.font`) and
cannot be redefined; ``defrasterfont(n, ...)`` defines others; the font manager
builds its scaled faces as raster fonts too (as IRIS fm did through defrasterfont),
so ``fmsetfont`` is ``font(n)`` for the face's number and everything text-related
agrees with what ``charstr`` draws.

Metrics of font 0 (the built-in design): every character cell is 8 pixels wide and
13 high; the baseline is 3 rows above the cell's bottom, so ``getheight()`` is 13,
``getdescender()`` is 3 and ``strwidth(s)`` is 8 per character the font defines
(printable ASCII 32..126; other characters are ignored and have no width).  Capitals
and digits are 9 rows above the baseline, the x-height is 6, descenders use the 3
rows below it; the top row and the right column of each cell are blank.  As a font
manager face (``fmfindfont`` and any of the names in :data:`vgxsim.fm.FACES`), the
unscaled font is its 13-pixel design: ``fmscalefont(fh, size)`` scales the cell to
``size`` pixels high (1 point = 1 pixel, as fm did on the screen).

defrasterfont in Python.  CPython's binding did not wrap defrasterfont ("too
complicated"), so vgxsim gives it the C argument order with the counts optional:
``defrasterfont(n, ht, nc, chars, nr, raster)`` or ``defrasterfont(n, ht, chars,
raster)``; ``chars[i]`` describes character code ``i`` as the C ``Fontchar``
``(offset, w, h, xoff, yoff, width)``: the glyph's bitmap starts at
``raster[offset]``, is ``w`` x ``h`` pixels stored bottom row first, each row in
``ceil(w / 16)`` 16-bit words with the most significant bit leftmost
(defrasterfont(3G)); its lower-left corner is ``(xoff, yoff)`` from the character
position and the position then advances by ``width``.  ``nc == 0`` deletes the font.
A character whose entry is all zeros is not defined.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from vgxsim import font as _builtin

from ._core import (
    GLTypeError,
    GLValueError,
    as_int,
    describe,
    gl_function,
    topic_state,
)

__all__ = ["defrasterfont"]


@dataclass(frozen=True)
class Glyph:
    """One character: ``bitmap`` (h, w) bool, row 0 at the bottom; its lower-left
    corner ``(xoff, yoff)`` from the character position; the ``advance``."""

    bitmap: np.ndarray
    xoff: int
    yoff: int
    advance: int


class RasterFont:
    """A raster font: glyphs by character code, the font height ``ht``.

    Parameters
    ----------
    glyphs : dict of int to Glyph
    height : int
        The font's height (getheight).
    """

    def __init__(self, glyphs: dict[int, Glyph], height: int):
        self.glyphs = glyphs
        self.height = int(height)
        #: The longest descender (getdescender): rows of any glyph below the baseline.
        self.descender = max([0, *(-g.yoff for g in glyphs.values())])

    def defined(self, s: str) -> str:
        """The characters of ``s`` the font defines (charstr ignores the others)."""
        return "".join(ch for ch in s if ord(ch) in self.glyphs)

    def string_width(self, s: str) -> int:
        """strwidth: the sum of the advances of the defined characters."""
        return sum(self.glyphs[ord(ch)].advance for ch in s if ord(ch) in self.glyphs)

    def pixels(self, s: str) -> tuple[np.ndarray, np.ndarray, int]:
        """The lit pixels of ``s`` drawn from the origin (0, 0) on the baseline.

        Returns
        -------
        x, y : ndarray, shape (K,), int64
            Pixel offsets from the character position.
        advance : int
            How far the character position moves.
        """
        xs, ys, pen = [], [], 0
        for ch in s:
            g = self.glyphs.get(ord(ch))
            if g is None:
                continue
            r, c = np.nonzero(g.bitmap)
            xs.append(pen + g.xoff + c)
            ys.append(g.yoff + r)
            pen += g.advance
        if not xs:
            return np.zeros(0, np.int64), np.zeros(0, np.int64), pen
        return (np.concatenate(xs).astype(np.int64), np.concatenate(ys).astype(np.int64),
                pen)

    def info(self) -> tuple[int, int, int, int, int, int, int, int]:
        """fmgetfontinfo's fields: (printermatched, fixed_width, xorig, yorig, xsize,
        ysize, height, nglyphs) -- xorig/yorig the largest left overhang and
        descent, xsize/ysize the largest glyph box."""
        gl = list(self.glyphs.values())
        advances = {g.advance for g in gl}
        xorig = max([0, *(-g.xoff for g in gl)])
        xsize = max([0, *(g.bitmap.shape[1] for g in gl)])
        ysize = max([0, *(g.bitmap.shape[0] for g in gl)])
        return (0, int(len(advances) <= 1), xorig, self.descender, xsize, ysize,
                self.height, len(gl))

    def scaled(self, factor: float) -> RasterFont:
        """The font scaled by ``factor`` (nearest-neighbour: the scaled pixel whose
        centre maps into a source pixel takes its value; every size rounded)."""
        glyphs = {}
        for code, g in self.glyphs.items():
            h, w = g.bitmap.shape
            nh, nw = max(1, round(h * factor)), max(1, round(w * factor))
            rows = np.minimum((np.arange(nh) + 0.5) * h / nh, h - 1).astype(np.int64)
            cols = np.minimum((np.arange(nw) + 0.5) * w / nw, w - 1).astype(np.int64)
            glyphs[code] = Glyph(g.bitmap[rows][:, cols], round(g.xoff * factor),
                                 round(g.yoff * factor), max(1, round(g.advance * factor)))
        return RasterFont(glyphs, max(1, round(self.height * factor)))


def builtin_font() -> RasterFont:
    """Font 0 as a :class:`RasterFont` (metrics in the module docstring)."""
    f = _builtin.DEFAULT_FONT
    glyphs = {code: Glyph(f.bitmap(chr(code)), 0, -f.descender, f.advance(chr(code)))
              for code in range(32, 127) if f.has_glyph(chr(code))}
    return RasterFont(glyphs, f.height)


_FONT0 = builtin_font()


@dataclass
class FontTable:
    """The session's raster fonts by number (0: the built-in font)."""

    fonts: dict[int, RasterFont] = field(default_factory=lambda: {0: _FONT0})
    next_private: int = 0x4000  # numbers the font manager gives its faces


def font_table() -> FontTable:
    """The session's :class:`FontTable` (dropped by ``session.reset()``)."""
    return topic_state("fonts", FontTable)


def raster_font(n: int) -> RasterFont | None:
    """Raster font ``n``, or None if it is not defined."""
    return font_table().fonts.get(int(n))


def add_private_font(f: RasterFont) -> int:
    """Give ``f`` a font number of its own (the font manager's faces)."""
    t = font_table()
    n = t.next_private
    t.next_private += 1
    t.fonts[n] = f
    return n


def _glyph_from_raster(name: str, args: tuple, code: int, entry, raster: Sequence[int]
                       ) -> Glyph | None:
    if not isinstance(entry, (list, tuple)) or len(entry) != 6:
        raise GLTypeError(f"{describe(name, args)}: chars[{code}] must be a 6-tuple "
                          f"(offset, w, h, xoff, yoff, width)")
    offset, w, h, xoff, yoff, width = (as_int(name, args, f"chars[{code}]", v) for v in entry)
    if not any((offset, w, h, xoff, yoff, width)):
        return None
    if w < 0 or h < 0 or offset < 0:
        raise GLValueError(f"{describe(name, args)}: chars[{code}] has a negative size or "
                           f"offset")
    words = math.ceil(w / 16)
    need = offset + words * h
    if need > len(raster):
        raise GLValueError(f"{describe(name, args)}: chars[{code}] needs raster words up to "
                           f"{need}, the raster has {len(raster)}")
    data = np.asarray(raster[offset:need], dtype=np.uint16).reshape(h, words)
    bits = ((data[:, :, None] >> np.arange(15, -1, -1, dtype=np.uint16)) & 1).astype(bool)
    return Glyph(bits.reshape(h, words * 16)[:, :w], xoff, yoff, width)


@gl_function(record=False)
def defrasterfont(*args) -> None:
    """defrasterfont(n, ht, [nc,] chars, [nr,] raster): define raster font ``n``
    (defrasterfont(3G); the Python form is in the module docstring)."""
    name = "defrasterfont"
    if len(args) == 6:
        n, ht, nc, chars, nr, raster = args
    elif len(args) == 4:
        n, ht, chars, raster = args
        nc = len(chars) if isinstance(chars, (list, tuple)) else None
        nr = len(raster) if isinstance(raster, (list, tuple, np.ndarray)) else None
    else:
        raise GLTypeError(f"{describe(name, args)}: expected (n, ht, nc, chars, nr, raster) "
                          f"or (n, ht, chars, raster), got {len(args)} arguments")
    n = as_int(name, args, "n", n)
    ht = as_int(name, args, "ht", ht)
    if not isinstance(chars, (list, tuple)):
        raise GLTypeError(f"{describe(name, args)}: chars must be a list of Fontchar tuples")
    if isinstance(raster, np.ndarray):
        raster = raster.reshape(-1).tolist()
    if not isinstance(raster, (list, tuple)):
        raise GLTypeError(f"{describe(name, args)}: raster must be a list of 16-bit words")
    nc = as_int(name, args, "nc", nc)
    nr = as_int(name, args, "nr", nr)
    if n == 0:
        raise GLValueError(f"{describe(name, args)}: font 0 is the built-in font and cannot "
                           f"be redefined")
    if not 0 <= nc <= len(chars) or not 0 <= nr <= len(raster):
        raise GLValueError(f"{describe(name, args)}: nc/nr exceed the lists given")
    table = font_table()
    if nc == 0:
        table.fonts.pop(n, None)
        return
    words = [as_int(name, args, "raster word", v) & 0xFFFF for v in raster[:nr]]
    glyphs = {}
    for code in range(nc):
        g = _glyph_from_raster(name, args, code, chars[code], words)
        if g is not None:
            glyphs[code] = g
    table.fonts[n] = RasterFont(glyphs, ht)
