"""The built-in 8x13 bitmap font."""

import numpy as np
import pytest

from vgxsim import font

PRINTABLE = [chr(c) for c in range(32, 127)]


def test_metrics():
    assert font.height == 13 and font.descender == 3 and font.width == 8
    assert font.advance("W") == 8 and font.advance("\x01") == 8
    assert font.string_width("") == 0 and font.string_width("t=1.0") == 40
    assert font.DEFAULT_FONT.height == 13


@pytest.mark.parametrize("ch", PRINTABLE)
def test_glyph_shape_and_layout(ch):
    rows = font.glyph(ch)
    assert rows.dtype == np.uint8 and rows.shape == (13,)
    assert not rows.flags.writeable
    assert rows[12] == 0  # top row: gap between lines
    assert not (rows & 0x01).any()  # rightmost column: gap between characters
    assert np.array_equal(font.glyph(ord(ch)), rows)


def test_space_is_blank_and_everything_else_differs_from_the_box():
    box = font.glyph("\x00")
    assert box.any()
    assert not font.glyph(" ").any()
    for ch in PRINTABLE[1:]:
        g = font.glyph(ch)
        assert g.any(), ch
        assert not np.array_equal(g, box), ch
        assert font.DEFAULT_FONT.has_glyph(ch)


def test_glyphs_are_all_different():
    seen = {}
    for ch in PRINTABLE:
        key = font.glyph(ch).tobytes()
        assert key not in seen, (ch, seen.get(key))
        seen[key] = ch


def test_unknown_characters_draw_the_box():
    box = font.glyph("\x7f")
    for ch in ("\n", "\t", "\xe9", "\u263a", 0x263A, -1):
        assert np.array_equal(font.glyph(ch), box)
    assert not font.DEFAULT_FONT.has_glyph("\n")
    with pytest.raises(ValueError):
        font.glyph("ab")


def test_baseline_and_descenders():
    # capitals sit on the baseline (row 3) and reach row 11; descenders go below
    for ch in "ABEHT0":
        rows = font.glyph(ch)
        assert rows[3] and rows[11] and not rows[:3].any(), ch
    for ch in "gjpqy":
        assert font.glyph(ch)[:3].any(), ch
    for ch in "acemnorsuvwxz":
        rows = font.glyph(ch)
        assert rows[3] and not rows[:3].any() and not rows[9:].any(), ch


def test_bitmap_matches_rows():
    bm = font.bitmap("L")
    assert bm.shape == (13, 8) and bm.dtype == bool
    rows = font.glyph("L")
    for y in range(13):
        assert sum(int(b) << (7 - x) for x, b in enumerate(bm[y])) == rows[y]
    # 'L': vertical stroke on the left, foot on the baseline (bottom-up rows)
    assert bm[3:12, 1].all() and bm[3, 1:6].all() and not bm[4, 2:6].any()


def test_string_bitmap():
    s = font.string_bitmap("Hi!")
    assert s.shape == (13, 24)
    assert np.array_equal(s[:, 8:16], font.bitmap("i"))
    assert font.string_bitmap("").shape == (13, 0)
