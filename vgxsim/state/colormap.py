"""The colour map of cmode windows (makemap(1G) layout) and index <-> word helpers.

0-7 are the named colours (BLACK, RED, GREEN, YELLOW, BLUE, MAGENTA, CYAN, WHITE),
8-15 pastel workspace shades, 16-31 left for X clients (black here), 32-55 a grey
ramp "from black to almost white", 56-255 a 5x8x5 colour cube in which "the 8 levels
of green change the fastest, then 5 levels of red, and finally the 5 levels of blue
change slowest" (makemap(1G)); entries above 255 start black.  4096 entries (12-bit
colour index, GD_BITS_NORM_SNG_CMODE on the VGX).

multimap(3G) splits the same hardware map into 16 maps of 256 entries; map ``n`` is
entries ``n*256 .. n*256+255`` here, so map 0 is the start of the one-map layout.

In cmode the colour planes hold the index itself: the packed uint32 word of a pixel
*is* its colour index, looked up through the map when the monitor shows it ("the map
is looked up at display time", color(3G)/mapcolor(3G)).  The kernels only know RGBA
bytes, so an index travels through them as the RGBA whose bytes spell the index
(:func:`index_rgba`): red carries bits 0-7, green bits 8-15.
"""

from __future__ import annotations

import numpy as np

MAP_SIZE = 4096  # onemap(): one map of 2**12 entries
MULTIMAP_SIZE = 256  # multimap(): 16 maps of 2**8 entries each
NMAPS = 16  # getgdesc(GD_NMMAPS)


def default_colormap() -> np.ndarray:
    """(4096, 3) uint8 RGB table with the IRIS default entries (makemap(1G))."""
    cmap = np.zeros((MAP_SIZE, 3), np.uint8)
    named = [(0, 0, 0), (255, 0, 0), (0, 255, 0), (255, 255, 0), (0, 0, 255),
             (255, 0, 255), (0, 255, 255), (255, 255, 255)]
    cmap[:8] = named
    pastel = [(85, 85, 85), (198, 113, 113), (113, 198, 113), (142, 142, 56),
              (113, 113, 198), (142, 56, 142), (56, 142, 142), (170, 170, 170)]
    cmap[8:16] = pastel
    for i in range(24):
        g = round(i * 255 / 24)
        cmap[32 + i] = (g, g, g)
    i = 56
    for b in range(5):  # slowest
        for r in range(5):
            for g in range(8):  # fastest
                cmap[i] = (round(r * 255 / 4), round(g * 255 / 7), round(b * 255 / 4))
                i += 1
    return cmap


def map_base(multi: bool, current: int) -> int:
    """First table entry of the map colour indices address (setmap(3G))."""
    return current * MULTIMAP_SIZE if multi else 0


def map_size(multi: bool) -> int:
    """Entries one map holds: 4096 with onemap, 256 with multimap."""
    return MULTIMAP_SIZE if multi else MAP_SIZE


def index_rgba(index: int) -> tuple[float, float, float, float]:
    """The float RGBA the kernels turn back into the word ``index`` (cmode drawing).

    Components are ``byte / 255``, which the kernels round back exactly with
    ``floor(c * 255 + 0.5)`` (docs/numeric_model.md section 4).
    """
    return ((index & 0xFF) / 255.0, ((index >> 8) & 0xFF) / 255.0, 0.0, 0.0)


def lookup(table: np.ndarray, packed: np.ndarray, multi: bool = False,
           current: int = 0) -> np.ndarray:
    """Colour-map a buffer of index words for display.

    Parameters
    ----------
    table : ndarray, shape (4096, 3), uint8
    packed : ndarray, shape (H, W), uint32
        Index words (cmode colour planes).
    multi, current : bool, int
        multimap() in effect and the map setmap() selected.

    Returns
    -------
    ndarray, shape (H, W, 4), uint8
        RGBA with alpha 255.
    """
    idx = (packed & (map_size(multi) - 1)).astype(np.int64) + map_base(multi, current)
    rgb = table[idx % table.shape[0]]
    return np.concatenate([rgb, np.full(packed.shape + (1,), 255, np.uint8)], axis=2)
