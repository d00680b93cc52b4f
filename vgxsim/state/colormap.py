"""The colour map of cmode windows (makemap(1G) layout).

0-7 are the named colours (BLACK, RED, GREEN, YELLOW, BLUE, MAGENTA, CYAN, WHITE),
8-15 pastel workspace shades, 16-31 left for X clients (black here), 32-55 a grey
ramp, 56-255 a 5x8x5 colour cube; entries above 255 start black.  4096 entries
(12-bit colour index, GD_BITS_NORM_SNG_CMODE on the VGX).
"""

from __future__ import annotations

import numpy as np

MAP_SIZE = 4096


def default_colormap() -> np.ndarray:
    """(4096, 3) uint8 RGB table with the IRIS default entries."""
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
    for r in range(5):
        for g in range(8):
            for b in range(5):
                cmap[i] = (round(r * 255 / 4), round(g * 255 / 7), round(b * 255 / 4))
                i += 1
    return cmap
