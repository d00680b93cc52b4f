# ruff: noqa: E702
"""roettger: shadow volumes without stencil planes, counted by blending (Roettger,
Irion and Ertl 2002, shared/seeds/004).

"Problem: dstColor = dstColor - 1 not available.  Solution: instead +1, x2 (double
values); instead -1, /2 (halve values)."  The window has no stencil planes
(``stensize(0)``); the shadow mask is counted in the alpha channel (``channel=
'alpha'``, "performs even faster") or in the colour buffer (``channel='colour'``,
the screen-buffer variant, for machines without alpha planes; the scene then has to
be drawn again per light and the lights are summed in the accumulation buffer).

With the VGX's blend (docs/numeric_model.md: ``out = min(255, (s fs + d fd + 127) //
255)``):

* x2: ``blendfunction(BF_DA, BF_ONE)`` (alpha) or ``(BF_DC, BF_ONE)`` (colour) with a
  white source: ``2 d`` exactly, clamped to 255;
* /2: ``blendfunction(BF_ZERO, BF_SA)`` with source alpha 128 (or ``(BF_ZERO,
  BF_SC)`` with source colour 128): ``(128 d + 127) // 255``, exactly d / 2 for
  d = 2 .. 128, and 255 -> 128 (so a clamped 255 still halves like 256);
* the mask starts at ``start`` = 2^s (the talk: "initialize all pixels with color
  value 1/4", i.e. 64): running counts 0 .. 8 - s are exact (2^s .. 128, then 255,
  which halves like 256); front faces are all drawn before back faces (Heidmann's
  order), so a pixel's running count never goes below its final count.  A final
  count below 0 (eye in shadow) halves toward 1 and reads as shadow, except that
  1 / 2 rounds back to 1: with ``start=1`` a count of -1 reads lit.

Normalisation ("Shadow Mask Normalization": x2, invert, x2): 7 - s doublings take
the start value to 128 and every count >= 1 to 255; invert (``BF_MDA``/``BF_MDC``,
``c = 1 - c``) gives 127 and 0; two doublings give 255 (lit) and 0 (shadow).  So
``start`` trades nesting depth for passes: 1 allows 8 nested volumes and costs 10
window-sized blends per light, 64 (Roettger's) allows 2 and costs 3.

Application ("Shadow Mask Application"):

* ``'black'``: the first pass sets z only; each light adds its diffuse and specular
  part times the mask (``BF_DA, BF_ONE``): shadows are black;
* ``'ambient'``: the article's ambient pass first, then as black -- with a 255/0 mask
  the sum equals Heidmann's ``BF_ONE, BF_ONE`` exactly;
* ``'quick'`` (QuickNDirty, alpha only): the scene drawn once with every component;
  per light the mask becomes 255/127 (halve, add 127) and multiplies the colour
  (``BF_ZERO, BF_DA``): shadowed pixels at half intensity.

``mask_scale = s > 1``: the alpha mask is counted at 1/s of the resolution in the
window's lower-left corner (z drawn again there), read with ``lrectread``, repeated
s x s on the host and written back with ``lrectwrite`` (the talk's "computation of
shadow mask with lower resolution ... rasterized much faster"; there it is applied as
a texture).  Not exact at shadow edges by design.
"""

from __future__ import annotations

import numpy as np

from vgxsim.gl import (
    AC_ACCUMULATE,
    AC_CLEAR_ACCUMULATE,
    AC_RETURN,
    BF_DA,
    BF_DC,
    BF_MDA,
    BF_MDC,
    BF_ONE,
    BF_SA,
    BF_SC,
    BF_ZERO,
    FALSE,
    GD_ZMAX,
    LIGHT0,
    TRUE,
    RGBmode,
    acbuf,
    acsize,
    backface,
    blendfunction,
    c4i,
    czclear,
    doublebuffer,
    frontface,
    gconfig,
    getgdesc,
    getsize,
    lmbind,
    loadmatrix,
    lrectread,
    lrectwrite,
    ortho2,
    popmatrix,
    pushmatrix,
    read_pixels,
    rectf,
    stensize,
    viewport,
    wmpack,
    zbuffer,
    zwritemask,
)
from vgxsim.shadow.scene import MATL_DIFFSPEC, MATL_EMITAMBIENT, MATL_FULL

from .base import Technique, TechniqueError
from .volumes import side_quads
from .zpass import SILHOUETTE_METHODS, edge_pairs

CHANNELS = ("alpha", "colour")
APPLICATIONS = ("black", "ambient", "quick")
ALPHA_ONLY = 0xff000000
RGB_ONLY = 0x00ffffff


class Roettger(Technique):
    """Counting by x2 and /2 blending, no stencil planes.

    Parameters
    ----------
    channel : {'alpha', 'colour'}
    application : {'black', 'ambient', 'quick'}
    mask_scale : int
        1: full resolution; s > 1: the mask at 1/s resolution (alpha only).
    start : {1, 2, 4, 8, 16, 32, 64}
        The mask's start value (see the module docstring).
    """

    name = "roettger"
    infinite_far = True

    def __init__(self, channel: str = "alpha", application: str = "ambient",
                 mask_scale: int = 1, silhouettes: str = "adjacency", start: int = 1):
        if channel not in CHANNELS:
            raise TechniqueError(f"roettger: channel must be one of {CHANNELS}")
        if application not in APPLICATIONS:
            raise TechniqueError(f"roettger: application must be one of {APPLICATIONS}")
        if channel == "colour" and (application == "quick" or mask_scale != 1):
            raise TechniqueError("roettger: quick application and mask_scale need the "
                                 "alpha channel (the colour buffer holds the mask)")
        if int(mask_scale) < 1:
            raise TechniqueError(f"roettger: mask_scale must be >= 1, not {mask_scale}")
        if silhouettes not in SILHOUETTE_METHODS:
            raise TechniqueError(f"roettger: silhouettes must be one of {SILHOUETTE_METHODS}")
        if start not in (1, 2, 4, 8, 16, 32, 64):
            raise TechniqueError(f"roettger: start must be a power of two 1..64, not {start}")
        self.start = int(start)
        self.channel = channel
        self.application = application
        self.mask_scale = int(mask_scale)
        self.silhouettes = silhouettes
        self.exact = mask_scale == 1
        self._low: list[np.ndarray] = []

    # -- configuration: no stencil planes ----------------------------------------------
    def config(self, prog, accumulate: bool) -> bool:
        if accumulate and self.channel == "colour":
            raise TechniqueError("roettger: the colour channel sums lights in the "
                                 "accumulation buffer; soft shadows cannot use it too")
        RGBmode()
        doublebuffer()
        stensize(0)                                   # the point: no stencil planes
        if accumulate or self.channel == "colour":
            acsize(16)
        gconfig()
        zbuffer(TRUE)
        prog.stencil_bits = 0
        prog.MYZERO = 0
        return True

    # -- the mask ----------------------------------------------------------------------
    def _fill(self, prog, sf: int, df: int, rgba: tuple[int, int, int, int]) -> None:
        """One window-sized rectangle through the blender (no z test)."""
        w, h = getsize()
        zbuffer(FALSE)
        pushmatrix()
        ortho2(-0.5, w - 0.5, -0.5, h - 0.5)
        loadmatrix(np.eye(4).reshape(-1).tolist())
        blendfunction(sf, df)
        c4i(*rgba)
        rectf(-0.5, -0.5, w - 0.5, h - 0.5)  # every pixel centre strictly inside
        popmatrix()
        prog.viewing()
        zbuffer(TRUE)

    def _factors(self):
        if self.channel == "alpha":
            return (BF_DA, BF_ONE), (BF_ZERO, BF_SA), (BF_MDA, BF_ZERO), ALPHA_ONLY
        return (BF_DC, BF_ONE), (BF_ZERO, BF_SC), (BF_MDC, BF_ZERO), RGB_ONLY

    def count(self, prog, i: int) -> None:
        """Count light ``i``'s volume faces into the mask (z already set)."""
        double, halve, _, mask = self._factors()
        zwritemask(0x0)
        wmpack(mask)
        self._fill(prog, BF_ONE, BF_ZERO, (self.start,) * 4)
        lt = self.light(prog, i)
        quads = [side_quads(m, edge_pairs(m, lt, "silhouette", self.silhouettes), lt, None)
                 for m in prog.scene.casters]
        quads = np.concatenate(quads) if quads else np.zeros((0, 4, 4))
        for cull, factors, rgba in ((backface, double, (255, 255, 255, 255)),
                                    (frontface, halve, (128, 128, 128, 128))):
            cull(TRUE)
            blendfunction(*factors)
            c4i(*rgba)
            self.draw_polygons(quads)
            cull(FALSE)
        self.normalise(prog)

    def normalise(self, prog) -> None:
        """Mask to 255 (lit) / 0 (shadow): x2 until the start value is 128, invert, x2
        twice."""
        double, _, invert, mask = self._factors()
        wmpack(mask)
        for _ in range(7 - self.start.bit_length() + 1):
            self._fill(prog, *double, (255, 255, 255, 255))
        self._fill(prog, *invert, (255, 255, 255, 255))
        for _ in range(2):
            self._fill(prog, *double, (255, 255, 255, 255))

    def before_frame(self, prog) -> None:
        """mask_scale > 1: count every light's mask at low resolution first."""
        self._low = []
        if self.mask_scale == 1:
            return
        w, h = getsize()
        s = self.mask_scale
        lw, lh = max(1, w // s), max(1, h // s)
        for i in range(prog.nLights):
            czclear(0x00000000, getgdesc(GD_ZMAX))
            viewport(0, lw - 1, 0, lh - 1)
            wmpack(0x0)
            zwritemask(0xffffffff)
            prog.DrawObjects(MATL_EMITAMBIENT)
            self.count_low(prog, i, lw, lh)
            words = np.frombuffer(lrectread(0, 0, lw - 1, lh - 1), "<u4").reshape(lh, lw)
            big = np.repeat(np.repeat(words, s, axis=0), s, axis=1)
            full = np.zeros((h, w), np.uint32)
            full[:min(h, big.shape[0]), :min(w, big.shape[1])] = big[:h, :w]
            if big.shape[0] < h:
                full[big.shape[0]:] = full[big.shape[0] - 1]
            if big.shape[1] < w:
                full[:, big.shape[1]:] = full[:, big.shape[1] - 1:big.shape[1]]
            self._low.append(full)
        prog.viewing()

    def count_low(self, prog, i: int, lw: int, lh: int) -> None:
        """:meth:`count` inside the low-resolution viewport."""
        saved = prog.viewing
        prog.viewing = lambda: (saved(), viewport(0, lw - 1, 0, lh - 1))
        try:
            self.count(prog, i)
        finally:
            prog.viewing = saved
        viewport(0, lw - 1, 0, lh - 1)

    def mark(self, prog, i: int) -> None:
        if self._low:
            w, h = getsize()
            wmpack(ALPHA_ONLY)
            lrectwrite(0, 0, w - 1, h - 1, self._low[i].astype('<u4').tobytes())
            return
        self.count(prog, i)

    # -- application -------------------------------------------------------------------
    def first_pass(self, prog) -> None:
        if self.application == "ambient":
            super().first_pass(prog)
            return
        for k in range(prog.nLights):
            lmbind(LIGHT0 + k, prog.light[k].index)
        zwritemask(0xffffffff)
        wmpack(0xffffffff if self.application == "quick" else 0x0)
        czclear(0x00000000, getgdesc(GD_ZMAX))
        blendfunction(BF_ONE, BF_ZERO)
        prog.DrawObjects(MATL_FULL if self.application == "quick" else MATL_EMITAMBIENT)
        wmpack(0xffffffff)
        for k in range(prog.nLights):
            lmbind(LIGHT0 + k, 0)

    def lit_pass(self, prog, i: int) -> None:
        zwritemask(0x0)
        wmpack(RGB_ONLY)
        if self.application == "quick":
            wmpack(ALPHA_ONLY)
            self._fill(prog, BF_ZERO, BF_SA, (128, 128, 128, 128))  # 255/0 -> 128/0
            self._fill(prog, BF_ONE, BF_ONE, (127, 127, 127, 127))  # -> 255/127
            wmpack(RGB_ONLY)
            self._fill(prog, BF_ZERO, BF_DA, (255, 255, 255, 255))  # colour x mask
        else:
            blendfunction(BF_DA, BF_ONE)              # + diffuse/specular x mask
            prog.DrawObjects(MATL_DIFFSPEC)
        zwritemask(0xffffffff)
        wmpack(0xffffffff)

    def draw_shadows(self, prog) -> None:
        if self.channel == "alpha":
            super().draw_shadows(prog)
            return
        # the colour buffer holds each light's mask: sum the lights in acbuf
        for i in range(prog.nLights):
            lmbind(LIGHT0, prog.light[i].index)
            czclear(0x00000000, getgdesc(GD_ZMAX))
            zwritemask(0xffffffff)
            wmpack(0x0)
            blendfunction(BF_ONE, BF_ZERO)
            prog.DrawObjects(MATL_EMITAMBIENT)        # z only
            self.count(prog, i)
            if prog.stencil_hook is not None:
                prog.stencil_hook(i)
            wmpack(0xffffffff)
            blendfunction(BF_DC, BF_ZERO)             # diffuse/specular x mask
            prog.DrawObjects(MATL_DIFFSPEC)
            acbuf(AC_CLEAR_ACCUMULATE if i == 0 else AC_ACCUMULATE, 1.0)
            lmbind(LIGHT0, 0)
        if self.application == "ambient":
            for k in range(prog.nLights):
                lmbind(LIGHT0 + k, prog.light[k].index)
            czclear(0x00000000, getgdesc(GD_ZMAX))
            zwritemask(0xffffffff)
            blendfunction(BF_ONE, BF_ZERO)
            prog.DrawObjects(MATL_EMITAMBIENT)
            for k in range(prog.nLights):
                lmbind(LIGHT0 + k, 0)
            acbuf(AC_CLEAR_ACCUMULATE if prog.nLights == 0 else AC_ACCUMULATE, 1.0)
        acbuf(AC_RETURN, 1.0)
        self.finish(prog)
        if self._volume_cache is not None:
            self._volume_cache.end_frame()

    def finish(self, prog) -> None:
        blendfunction(BF_ONE, BF_ZERO)

    def read_mask(self, prog, i: int) -> np.ndarray:
        rgba = read_pixels("back")
        return np.ascontiguousarray(rgba[..., 3] if self.channel == "alpha" else rgba[..., 1])

    def lit_value(self, prog) -> int:
        return 255
