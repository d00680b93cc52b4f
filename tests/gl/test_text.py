"""Raster text (gl/_text.py): cmov, charstr, strwidth, fonts."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim import font as vfont
from vgxsim import gl
from vgxsim.gl import _core

W, H = 64, 32


@pytest.fixture
def ctx(gl_window):
    c = gl_window(W, H, projection=False)
    gl.ortho2(-0.5, W - 0.5, -0.5, H - 0.5)
    gl.cpack(0xFF00FFFF)  # yellow
    return c


def lit_pixels(c) -> set[tuple[int, int]]:
    ys, xs = np.nonzero(c.read_rgba()[..., :3].any(axis=2))
    return {(int(x), int(y)) for x, y in zip(xs, ys, strict=True)}


def glyph_pixels(ch: str, x0: int, y0: int) -> set[tuple[int, int]]:
    """Where font 0 puts ``ch`` with its baseline's left end at (x0, y0): the cell's
    bottom row is 3 (the descender) below the baseline."""
    rows = vfont.glyph(ch)  # bottom-up bytes, MSB = leftmost pixel
    return {(x0 + col, y0 - 3 + row) for row in range(13) for col in range(8)
            if rows[row] & (0x80 >> col)}


def test_charstr_draws_glyphs_at_the_character_position(ctx):
    gl.cmov2i(5, 10)
    assert ctx.cpos == (5, 10)
    gl.charstr("Ag")
    assert lit_pixels(ctx) == glyph_pixels("A", 5, 10) | glyph_pixels("g", 13, 10)
    assert ctx.cpos == (21, 10)  # advanced by 8 per character
    img = ctx.read_rgba()
    x, y = next(iter(glyph_pixels("A", 5, 10)))
    assert tuple(img[y, x]) == (255, 255, 0, 255)


def test_cmov_goes_through_the_matrix_but_glyphs_do_not(ctx):
    gl.translate(10, 4, 0)
    gl.scale(3, 3, 1)
    gl.cmov2(1.0, 2.0)  # -> (13, 10)
    assert ctx.cpos == (13, 10)
    gl.charstr("T")
    assert lit_pixels(ctx) == glyph_pixels("T", 13, 10)  # not scaled


def test_cmov_outside_the_viewport_makes_the_position_undefined(ctx):
    gl.cmov2i(W + 5, 3)
    assert not ctx.cpos_valid
    gl.charstr("X")
    assert not lit_pixels(ctx)
    gl.cmovi(2, 3, 0)
    assert ctx.cpos_valid and ctx.cpos == (2, 3)


def test_text_is_clipped_at_the_window_edge(ctx):
    gl.cmov2i(W - 4, 20)
    gl.charstr("M")
    expected = {p for p in glyph_pixels("M", W - 4, 20) if p[0] < W}
    assert lit_pixels(ctx) == expected and expected


def test_text_fragments_pass_the_z_and_mask_tests(ctx):
    ctx.raster.set(zbuffer=True)
    gl.cmov2i(5, 10)  # z = 0 in the middle of the depth range (ortho2: z in [-1, 1])
    assert ctx.cpos_z == 0
    ctx.fb.z[:] = -100  # everything already nearer: ZF_LEQUAL fails
    gl.charstr("A")
    assert not lit_pixels(ctx)
    ctx.fb.z[:] = 100
    gl.charstr("A")  # the position advanced: the second A is drawn 8 to the right
    assert lit_pixels(ctx) == glyph_pixels("A", 13, 10)
    assert (ctx.fb.z[10, 13:21] <= 100).all()
    ctx.fb.front[:] = 0
    ctx.raster.set(zbuffer=False, wmpack=0)
    gl.cmov2i(5, 10)
    gl.charstr("A")
    assert not lit_pixels(ctx)


def test_metrics_and_fonts(ctx):
    assert gl.strwidth("abc") == 24
    assert gl.getheight() == 13 and gl.getdescender() == 3
    assert gl.getfont() == 0
    gl.font(0)
    with pytest.raises(gl.GLValueError, match=r"font\(1\).*not defined"):
        gl.font(1)
    # Characters the font does not define are ignored and take no room (charstr(3G)).
    assert gl.strwidth("\x01A\n") == 8
    gl.cmov2i(5, 10)
    gl.charstr("\x01A")
    assert lit_pixels(ctx) == glyph_pixels("A", 5, 10) and ctx.cpos == (13, 10)


def test_text_argument_errors(ctx):
    with pytest.raises(gl.GLTypeError, match=r"charstr\(5\)"):
        gl.charstr(5)
    with pytest.raises(gl.GLTypeError, match="cmov2i"):
        gl.cmov2i(1.5, 2)
    with pytest.raises(gl.GLTypeError, match="strwidth"):
        gl.strwidth(["a"])
    _core.session.reset()
    with pytest.raises(gl.GLUsageError, match="charstr.*winopen"):
        gl.charstr("a")


def test_getcpos_follows_cmov_and_charstr(ctx):
    gl.cmov2i(7, 9)
    assert gl.getcpos() == (7, 9)
    gl.charstr("ab")
    assert gl.getcpos() == (23, 9)
