"""Framebuffer planes, allocated only when configured (docs/numeric_model.md s. 7).

A plane that is not configured is not allocated and costs nothing: the kernels get
a (1, 1) dummy and the state tables never enable it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

ZMIN = -0x800000  # getgdesc(GD_ZMIN): signed 24-bit z (see irisgl_reference 1.2)
ZMAX = 0x7FFFFF  # getgdesc(GD_ZMAX)
MAX_STENCIL_PLANES = 8  # VGX: 8 stencil bitplanes (Power Series technical report s. 3)
DUMMY_U32 = np.zeros((1, 1), dtype=np.uint32)


@dataclass(frozen=True)
class PlaneConfig:
    """What ``gconfig`` grants: sizes of every plane.

    Attributes
    ----------
    width, height : int
        Window size in pixels.
    double : bool
        doublebuffer() (front and back colour buffers) or singlebuffer().
    zbits : int
        Depth bits (0 or 24 on the VGX).
    stencil : int
        Stencil planes, 0-8 (stensize).
    acbits : int
        Accumulation bits per component (0 or 16, acsize).
    rgb : bool
        RGBmode (True) or cmode (False); colour indices live in the same uint32 words.
    overlay, underlay : int
        Overlay and underlay bitplanes, overlay(3G) / underlay(3G) (0 to
        vgxsim.state.layers.MAX_BITS); their planes are not part of this
        framebuffer but a PlaneSet each (vgxsim.state.layers).
    """

    width: int
    height: int
    double: bool = False
    zbits: int = 24
    stencil: int = 0
    acbits: int = 0
    rgb: bool = True
    overlay: int = 0
    underlay: int = 0


class Framebuffer:
    """The planes of one window.

    Attributes
    ----------
    front, back : ndarray, shape (H, W), uint32 packed 0xAABBGGRR, or None
        ``back`` is None when single-buffered.
    z : ndarray, shape (H, W), int32, or None
    stencil : ndarray, shape (H, W), uint8, or None
    accum : ndarray, shape (H, W, 4), int16, or None
    """

    def __init__(self, config: PlaneConfig):
        self.config = config
        h, w = config.height, config.width
        self.front = np.zeros((h, w), dtype=np.uint32)
        self.back = np.zeros((h, w), dtype=np.uint32) if config.double else None
        self.z = np.full((h, w), ZMAX, dtype=np.int32) if config.zbits > 0 else None
        self.stencil = np.zeros((h, w), dtype=np.uint8) if config.stencil > 0 else None
        self.accum = np.zeros((h, w, 4), dtype=np.int16) if config.acbits > 0 else None

    @classmethod
    def view(cls, config: PlaneConfig, front: np.ndarray, back: np.ndarray | None,
             z: np.ndarray | None, stencil: np.ndarray | None) -> Framebuffer:
        """Planes made of other planes' arrays (nothing is allocated): what a
        command batch renders into when drawing goes to a different choice of
        buffers, as zdraw(3G)'s z-buffer used as a colour buffer."""
        fb = cls.__new__(cls)
        fb.config = config
        fb.front, fb.back, fb.z, fb.stencil, fb.accum = front, back, z, stencil, None
        return fb

    @property
    def width(self) -> int:
        return self.config.width

    @property
    def height(self) -> int:
        return self.config.height

    def swap(self) -> None:
        """swapbuffers(): exchange front and back (contents of the new back are kept)."""
        if self.back is not None:
            self.front, self.back = self.back, self.front

    def kernel_planes(self):
        """The four planes as kernels take them, dummies for missing ones."""
        back = self.back if self.back is not None else DUMMY_U32
        z = self.z if self.z is not None else np.zeros((1, 1), dtype=np.int32)
        st = self.stencil if self.stencil is not None else np.zeros((1, 1), dtype=np.uint8)
        return self.front, back, z, st


def unpack_rgba(packed: np.ndarray) -> np.ndarray:
    """View packed 0xAABBGGRR words as RGBA bytes.

    Parameters
    ----------
    packed : ndarray, shape (H, W), uint32

    Returns
    -------
    ndarray, shape (H, W, 4), uint8 (a copy, little-endian byte order R, G, B, A)
    """
    words = np.ascontiguousarray(packed, dtype="<u4")
    return words.view(np.uint8).reshape(packed.shape + (4,)).copy()
