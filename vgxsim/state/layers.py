"""The overlay, underlay, pop-up and cursor framebuffers of drawmode(3G), and how the
monitor shows them together with the normal planes.

drawmode(3G): "The IRIS physical framebuffer is divided into 4 separate GL
framebuffers: pop-up, overlay, normal, and underlay ... each framebuffer maintains its
own current color and its own color map, but linewidth is shared among all
framebuffers."  The modes kept once per framebuffer (the same page's list: colour,
mapcolor, writemask, frontbuffer/backbuffer, readsource, cmode/RGBmode) live in one
:class:`PlaneSet` each; everything else (matrices, linewidth, the fragment registers)
is shared.  The three extra framebuffers are colour-index planes only ("they can be
used only in color index mode, and they do not support Gouraud shading", the AIX GL
guide on overlays; overlay(3G): "In OVERDRAW, FLAT is the only available shading
model"), single-buffered, with no z, stencil or accumulation planes.

Plane counts (getgdesc): [pstech] s.3 gives the VGX 4 overlay planes; vgxsim gives the
underlay its own 4 planes too (GD_OVERUNDER_SHARED 0: an overlay(n) request never
takes planes from underlay(m)), the pop-up framebuffer 2 (GD_BITS_PUP_SNG_CMODE, the
PUP_CLEAR..PUP_WHITE colours of gl.h) and the cursor none (nothing is drawn headless,
GD_BITS_CURSOR 0: drawmode(CURSORDRAW) keeps a colour map that mapcolor edits and
nothing shows).

Data only: planes are allocated by the pipeline (vgxsim.pipeline.layers), when a
window's gconfig grants them or when a drawmode first selects a framebuffer.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import colormap
from .planes import Framebuffer, PlaneConfig

#: Framebuffers besides the normal one, by name -> the most planes each may have.
MAX_BITS: dict[str, int] = {"overlay": 4, "underlay": 4, "popup": 2, "cursor": 0}

#: What a framebuffer's planes show until mapcolor changes them: the normal map's
#: default entries (makemap(1G): 0 black, 1 red, 2 green, 3 yellow, ...) for the
#: overlay, underlay and cursor -- *assumed*, no manual page gives the layer maps'
#: start -- and for the pop-up planes the colours gl.h's names promise (PUP_CLEAR 0,
#: PUP_COLOR 1 -- red here, assumed --, PUP_BLACK 2, PUP_WHITE 3).
POPUP_MAP = ((0, 0, 0), (255, 0, 0), (0, 0, 0), (255, 255, 255))


def default_layer_map(name: str) -> np.ndarray:
    """(4096, 3) uint8: the colour map a framebuffer starts with (see ``POPUP_MAP``)."""
    cmap = colormap.default_colormap()
    if name == "popup":
        cmap[:len(POPUP_MAP)] = POPUP_MAP
    return cmap


@dataclass
class PlaneSet:
    """One GL framebuffer's planes and the modes drawmode(3G) keeps per framebuffer.

    While a framebuffer is selected its modes live on the window (the context's
    ``config``, ``fb``, ``colormap``, ``colour`` ... and the raster registers'
    ``wmpack``/``frontbuffer``/``backbuffer``); this record holds them while another
    one is selected.

    Attributes
    ----------
    name : str
        'normal', 'overlay', 'underlay', 'popup' or 'cursor'.
    bits : int
        Planes granted (0: none; drawing then stores nothing and nothing is shown).
    fb : Framebuffer or None
        Its planes (None until first needed).
    modes : dict
        The per-framebuffer modes while not selected, by context attribute name.
    """

    name: str
    bits: int = 0
    fb: Framebuffer | None = None
    modes: dict = field(default_factory=dict)

    @property
    def mask(self) -> int:
        """The index planes that exist: ``2**bits - 1``."""
        return (1 << self.bits) - 1


def layer_config(width: int, height: int) -> PlaneConfig:
    """Planes of an overlay, underlay or pop-up framebuffer: one single-buffered
    colour-index buffer, no z, stencil or accumulation."""
    return PlaneConfig(width, height, double=False, zbits=0, stencil=0, acbits=0, rgb=False)


def composite(normal_rgba: np.ndarray, normal_nonzero: np.ndarray,
              layers: dict[str, tuple[np.ndarray, int, np.ndarray]]) -> np.ndarray:
    """What the monitor shows at each pixel (underlay(3G)'s hierarchical rule).

    "if the popup pixel contents are non-zero then display the popup bitplanes else if
    overlay bitplanes are allocated AND the overlay pixel contents are non-zero then
    display the overlay bitplanes else if the normal pixel contents are non-zero OR no
    underlay bitplanes are allocated then display the normal bitplanes else display
    the underlay bitplanes".  Each layer's index is looked up in its own map.

    Parameters
    ----------
    normal_rgba : ndarray, shape (H, W, 4), uint8
        The normal planes as shown (RGB, or colour-mapped indices).
    normal_nonzero : ndarray, shape (H, W), bool
        Where the normal planes' colour bits are not all zero.
    layers : dict
        'underlay', 'overlay', 'popup' -> (index words (H, W) uint32, planes, colour
        map (4096, 3) uint8), for the framebuffers that have planes.

    Returns
    -------
    ndarray, shape (H, W, 4), uint8
        ``normal_rgba`` itself when no layer has planes, else a new image.
    """
    if not layers:
        return normal_rgba
    out = normal_rgba.copy()
    for name in ("underlay", "overlay", "popup"):  # later ones cover earlier ones
        if name not in layers:
            continue
        words, bits, cmap = layers[name]
        index = (words & ((1 << bits) - 1)).astype(np.intp)
        show = ~normal_nonzero if name == "underlay" else index != 0
        out[show, :3] = cmap[index[show]]
        out[show, 3] = 255
    return out


def nonzero_colour(packed: np.ndarray, rgb: bool, index_bits: int) -> np.ndarray:
    """(H, W) bool: where the normal planes' contents are non-zero for
    :func:`composite` -- the 24 colour bits in RGB mode (alpha is not a colour the
    monitor shows), the index bits in colour-map mode."""
    mask = 0xFFFFFF if rgb else (1 << index_bits) - 1
    return (packed & np.uint32(mask)) != 0
