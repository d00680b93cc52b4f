"""``vgxsim compare``: one IRIS GL program on both backends, frame by frame.

The program runs twice through :func:`vgxsim.runner.run_program`, once on the
software backend and once on the OpenGL backend, with the same event script, so
both runs see the same input.  Every frame a window shows (swapbuffers, or a
single-buffered window's changed screen) is captured with the window's z and
stencil planes as they are at that moment.  Per frame the report gives, per
plane, the pixels that differ by more than the tolerated amount, the PSNR of the
colour image, and optionally a difference image.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from os import PathLike

import numpy as np

from vgxsim.sinks import FrameSink

__all__ = ["Frame", "FrameDiff", "capture_run", "compare_frames", "compare_program",
           "difference_image", "psnr"]


@dataclass
class Frame:
    """One captured frame of one window.

    Attributes
    ----------
    window : int
    rgba : ndarray, shape (H, W, 4), uint8
        What the window shows (front buffer, colour-mapped in cmode).
    z : ndarray, shape (H, W), int32, or None
    stencil : ndarray, shape (H, W), uint8, or None
    """

    window: int
    rgba: np.ndarray
    z: np.ndarray | None
    stencil: np.ndarray | None


class _CaptureSink(FrameSink):
    """A sink that keeps every frame of window ``gid`` with its z and stencil."""

    def __init__(self, gid: int, frames: list[Frame]):
        super().__init__()
        self.gid = gid
        self.frames = frames

    def _write(self, image) -> None:
        from vgxsim.gl._core import session

        ctx = session.windows.get(self.gid)
        fb = None if ctx is None else ctx.fb
        z = None if fb is None or fb.z is None else fb.z.copy()
        st = None if fb is None or fb.stencil is None else fb.stencil.copy()
        self.frames.append(Frame(self.gid, np.array(image, np.uint8), z, st))


def capture_run(program: str | PathLike, args=(), *, backend: str, events=None,
                size=None, max_frames: int | None = None) -> tuple[int, list[Frame]]:
    """Run ``program`` on ``backend`` and capture its frames.

    Returns
    -------
    (int, list of Frame)
        The program's exit status and its frames, in the order shown.
    """
    from vgxsim.runner import run_program

    frames: list[Frame] = []
    sinks: dict[int, _CaptureSink] = {}

    def factory(gid: int) -> _CaptureSink:
        if gid not in sinks:
            sinks[gid] = _CaptureSink(gid, frames)
        return sinks[gid]

    status = run_program(program, list(args), events=events, frames=None, size=size,
                         max_frames=max_frames, backend=backend, sink_factory=factory)
    return status, frames


def psnr(a: np.ndarray, b: np.ndarray) -> float:
    """PSNR in dB of two uint8 RGB(A) images over their RGB channels (inf if equal)."""
    d = a[..., :3].astype(np.float64) - b[..., :3].astype(np.float64)
    mse = float(np.mean(d * d))
    return math.inf if mse == 0 else 10.0 * math.log10(255.0 * 255.0 / mse)


def difference_image(a: np.ndarray, b: np.ndarray, gain: int = 16) -> np.ndarray:
    """(H, W, 4) uint8 picture of where two frames differ: ``|a - b| * gain`` per
    RGB channel (clipped), opaque; identical pixels are black."""
    d = np.abs(a.astype(np.int64) - b.astype(np.int64))[..., :3] * gain
    out = np.full(a.shape[:2] + (4,), 255, np.uint8)
    out[..., :3] = np.clip(d, 0, 255)
    return out


@dataclass
class FrameDiff:
    """How frame ``index`` differs between the backends.

    Attributes
    ----------
    index, window : int
    colour_pixels : int
        Pixels whose RGBA differs by more than the colour tolerance in any channel.
    colour_max : int
        Largest channel difference (levels).
    psnr : float
        dB over RGB; inf when identical.
    z_pixels, stencil_pixels : int or None
        Differing pixels of the plane (z beyond the z tolerance); None when the
        window has no such plane.
    z_max : int or None
    pixels : int
        Pixels in the frame.
    """

    index: int
    window: int
    pixels: int
    colour_pixels: int
    colour_max: int
    psnr: float
    z_pixels: int | None = None
    z_max: int | None = None
    stencil_pixels: int | None = None
    over: list[str] = field(default_factory=list)


def compare_frames(a: Frame, b: Frame, index: int, *, levels: int = 0, z_units: int = 0,
                   tolerance: float = 0.0) -> FrameDiff:
    """Compare one frame of the software run (``a``) with the OpenGL run's (``b``).

    Parameters
    ----------
    levels : int
        Colour differences up to this many levels per channel are not counted.
    z_units : int
        z differences up to this many units of the 24-bit z are not counted.
    tolerance : float
        Fraction of the frame's pixels that may differ in each plane; ``over``
        names the planes past it.
    """
    n = a.rgba.shape[0] * a.rgba.shape[1]
    cd = np.abs(a.rgba.astype(np.int64) - b.rgba.astype(np.int64)).max(axis=2)
    out = FrameDiff(index, a.window, n, int((cd > levels).sum()), int(cd.max()),
                    psnr(a.rgba, b.rgba))
    if a.z is not None and b.z is not None:
        zd = np.abs(a.z.astype(np.int64) - b.z.astype(np.int64))
        out.z_pixels = int((zd > z_units).sum())
        out.z_max = int(zd.max())
    if a.stencil is not None and b.stencil is not None:
        out.stencil_pixels = int((a.stencil != b.stencil).sum())
    limit = tolerance * n
    for name, count in (("colour", out.colour_pixels), ("z", out.z_pixels),
                        ("stencil", out.stencil_pixels)):
        if count is not None and count > limit:
            out.over.append(name)
    return out


def compare_program(program: str | PathLike, args=(), *, events=None, size=None,
                    max_frames: int | None = None, levels: int = 0, z_units: int = 0,
                    tolerance: float = 0.0, diff_dir: str | PathLike | None = None,
                    out=print) -> int:
    """Run a program on both backends and report frame by frame.

    Returns
    -------
    int
        0 when every frame is within the tolerance, 1 when one is not (or the
        runs' frames or exit statuses differ), the program's status when that is
        non-zero on both backends alike.
    """
    from vgxsim.backends import BackendError
    from vgxsim.backends.opengl.surface import available
    from vgxsim.sinks import write_png

    if not available():
        raise BackendError("the opengl backend needs PyOpenGL and libOSMesa "
                           "(pip install 'vgxsim[opengl]'; apt install libosmesa6)")
    status_s, frames_s = capture_run(program, args, backend="software", events=events,
                                     size=size, max_frames=max_frames)
    status_g, frames_g = capture_run(program, args, backend="opengl", events=events,
                                     size=size, max_frames=max_frames)
    bad = False
    if status_s != status_g:
        out(f"exit status differs: software {status_s}, opengl {status_g}")
        bad = True
    if len(frames_s) != len(frames_g):
        out(f"frame count differs: software {len(frames_s)}, opengl {len(frames_g)}")
        bad = True
    if diff_dir is not None:
        os.makedirs(diff_dir, exist_ok=True)
    out(f"{'frame':>5} {'win':>3} {'colour px':>10} {'max':>4} {'PSNR dB':>8} "
        f"{'z px':>8} {'z max':>6} {'stencil px':>10}")
    for i, (a, b) in enumerate(zip(frames_s, frames_g, strict=False)):
        if a.rgba.shape != b.rgba.shape or a.window != b.window:
            out(f"{i:5d} frames of different windows or sizes")
            bad = True
            continue
        d = compare_frames(a, b, i, levels=levels, z_units=z_units, tolerance=tolerance)

        def fmt(v):
            return "-" if v is None else str(v)

        ps = "inf" if math.isinf(d.psnr) else f"{d.psnr:.2f}"
        flag = "" if not d.over else "  past tolerance: " + ", ".join(d.over)
        out(f"{i:5d} {d.window:3d} {d.colour_pixels:10d} {d.colour_max:4d} {ps:>8} "
            f"{fmt(d.z_pixels):>8} {fmt(d.z_max):>6} {fmt(d.stencil_pixels):>10}{flag}")
        if diff_dir is not None:
            write_png(os.path.join(os.fspath(diff_dir), f"diff_{i:04d}.png"),
                      difference_image(a.rgba, b.rgba))
        bad = bad or bool(d.over)
    if bad:
        return 1
    return status_s
