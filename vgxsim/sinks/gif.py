"""An animated GIF written frame by frame, valid after every frame.

Why not imageio's pillow plugin: it keeps every frame in memory until ``close`` (about
1.25 MiB a frame at 640x512) and writes nothing before, so a killed run lost the
whole movie.  :class:`GIFStream` writes the GIF89a header at the first frame and
each frame as it comes, and always ends the file with the GIF trailer (``;``, GIF89a
spec s.27): a frame is appended by overwriting the trailer with the frame's blocks
followed by a new trailer, in one ``write`` call.  A run killed at any point
therefore leaves a playable GIF of every frame written before the kill (the kernel
finishes a ``write`` call even if the process is killed; only a power loss can cut
one).  A frame cut short by a full disk is taken back (truncated) before the error
is raised.  Memory is one frame, whatever the length of the movie.

Each frame has its own colour table (GIF89a s.21, local colour table): a frame with
at most 256 colours keeps them exactly; one with more is reduced by Pillow's fast
octree quantizer without dithering (IRIS GL frames are mostly flat-shaded).  Frame
delays are stored in 1/100 s (GIF89a s.23), so 30 fps is written as 0.03 s.  Every
frame is stored, identical or not, so the file holds exactly the frames written.

The LZW coding of each frame is Pillow's (``PIL.GifImagePlugin.getdata``).
"""

from __future__ import annotations

import os
import struct

import numpy as np

__all__ = ["GIFStream"]

TRAILER = b";"


def _header(width: int, height: int) -> bytes:
    """GIF89a signature, logical screen of the movie's size without a global colour
    table, and the NETSCAPE2.0 application extension that loops forever."""
    screen = struct.pack("<HHBBB", width, height, 0, 0, 0)
    loop = b"!\xff\x0bNETSCAPE2.0\x03\x01" + struct.pack("<H", 0) + b"\x00"
    return b"GIF89a" + screen + loop


def _palette_image(rgb: np.ndarray):
    """A Pillow "P" image of ``rgb`` (H, W, 3) uint8: exact when it has <= 256 colours."""
    from PIL import Image

    im = Image.fromarray(rgb, mode="RGB")
    found = im.getcolors(256)  # None when there are more than 256 colours
    if found is None:
        return im.quantize(256, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.NONE)
    pal = np.array(sorted(c for _, c in found), np.uint32).reshape(-1, 3)
    keys = (pal[:, 0] << 16) | (pal[:, 1] << 8) | pal[:, 2]  # sorted, as pal is
    packed = (rgb[..., 0].astype(np.uint32) << 16) | (rgb[..., 1].astype(np.uint32) << 8) \
        | rgb[..., 2]
    index = np.searchsorted(keys, packed).astype(np.uint8)
    out = Image.fromarray(index, mode="P")
    out.putpalette(pal.astype(np.uint8).reshape(-1).tobytes())
    return out


class GIFStream:
    """Append RGB frames to an animated GIF file; the file is valid after each one.

    Parameters
    ----------
    path : str
        The output file (created or truncated at the first frame).
    fps : float
        Frames per second (delays are stored in 1/100 s).

    Raises
    ------
    OSError
        From any write (the caller names the file).
    """

    def __init__(self, path: str, fps: float):
        self.path = path
        self.delay_ms = 1000.0 / fps
        self._fh = None
        self.size: tuple[int, int] | None = None

    def append(self, rgb: np.ndarray) -> None:
        """Write one ``(H, W, 3)`` uint8 frame, top row first."""
        from PIL import GifImagePlugin

        h, w = rgb.shape[:2]
        if self._fh is None:
            # unbuffered: each frame reaches the kernel in one write call
            self._fh = open(self.path, "wb", buffering=0)  # noqa: SIM115 - kept open
            self._write_all(_header(w, h) + TRAILER)
            self.size = (w, h)
        im = _palette_image(rgb)
        blocks = b"".join(GifImagePlugin.getdata(
            im, duration=self.delay_ms, include_color_table=True))
        end = self._fh.seek(-len(TRAILER), os.SEEK_END)
        try:
            self._write_all(blocks + TRAILER)
        except OSError:
            # a full disk or a file-size limit cut the frame: take it back, so the
            # file stays the valid GIF of the frames before, then report
            try:
                self._fh.truncate(end)
                self._fh.seek(end)
                self._write_all(TRAILER)
            except OSError:
                pass
            raise

    def _write_all(self, data: bytes) -> None:
        view = memoryview(data)
        while view:
            view = view[self._fh.write(view):]

    def close(self) -> None:
        """Close the file (already complete).  Idempotent."""
        fh, self._fh = self._fh, None
        if fh is not None:
            fh.close()
