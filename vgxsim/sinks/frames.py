"""Frame sinks: where the frames of a headless run go.

Every sink receives framebuffer images as ``uint8`` arrays of shape
``(H, W, 4)`` (RGBA; ``(H, W, 3)`` RGB is accepted too) in the IRIS
convention: **row 0 is the bottom row** of the window.  Image files put the top
row first, so sinks flip the rows (``image[::-1]``) before writing.

Alpha: IRIS programs often leave the alpha byte at 0 (``cpack(0x00BBGGRR)``),
and the screen never shows alpha, so file sinks write RGB unless asked for
``alpha=True``; :class:`MemorySink` keeps all four channels.

* :class:`PNGSequenceSink` -- ``frame_0000.png``, ``frame_0001.png``, ... in a
  directory, each written atomically (temporary file + :func:`os.replace`), so
  a crash never leaves a half-written frame under a frame's name.
* :class:`MemorySink` -- a list of top-row-first copies.
* :class:`VideoSink` -- an animated GIF (:mod:`vgxsim.sinks.gif`) or an MP4
  (:mod:`vgxsim.sinks.mp4`, needs the ``imageio-ffmpeg`` package), both written
  as the frames come.
* :func:`open_sink` picks one from a path; :func:`write_png` writes one image
  (:func:`vgxsim.sinks.images.write_image` any of PNG, JPEG, TIFF).

File sinks try their target when they are made, so a bad one fails before a run
starts, and refuse to replace an earlier run's output unless asked to
(``overwrite=True``, ``vgxsim run --overwrite``).  Write failures raise
:class:`SinkError` (an :class:`OSError`) naming the file.
"""

from __future__ import annotations

import os
import re
from os import PathLike

import numpy as np

from vgxsim.sinks.atomic import TEMPORARY
from vgxsim.sinks.images import (
    SinkError,
    check_writable_file,
    check_writable_folder,
    image_format,
    write_image,
)

__all__ = [
    "FrameSink",
    "MemorySink",
    "PNGSequenceSink",
    "SinkError",
    "VideoSink",
    "open_sink",
    "to_top_down",
    "write_png",
]

VIDEO_SUFFIXES = (".gif", ".mp4")


def _check_image(image) -> np.ndarray:
    """Validate a framebuffer image and return it as an ndarray."""
    arr = np.asarray(image)
    if arr.dtype != np.uint8:
        raise TypeError(f"frame images must be uint8 arrays, got dtype {arr.dtype}")
    if arr.ndim != 3 or arr.shape[2] not in (3, 4) or arr.shape[0] < 1 or arr.shape[1] < 1:
        raise ValueError(f"frame images must have shape (H, W, 4) or (H, W, 3), got {arr.shape}")
    return arr


def to_top_down(image, alpha: bool = True) -> np.ndarray:
    """Return a bottom-up framebuffer image as a contiguous top-row-first copy.

    Parameters
    ----------
    image : ndarray
        ``uint8`` array of shape ``(H, W, 4)`` or ``(H, W, 3)``, row 0 at the bottom.
    alpha : bool
        Keep the alpha channel (if there is one); False returns RGB only.

    Returns
    -------
    ndarray
        ``(H, W, C)`` array with row 0 at the top.
    """
    arr = _check_image(image)
    if not alpha:
        arr = arr[:, :, :3]
    return np.ascontiguousarray(arr[::-1])


def write_png(path: str | PathLike, rgba_bottom_up, *, alpha: bool = False) -> None:
    """Write one framebuffer image to a PNG file, top row first, atomically.

    Parameters
    ----------
    path : str or path-like
        Output file; its folder must exist.
    rgba_bottom_up : ndarray
        ``uint8`` ``(H, W, 4)`` (or ``(H, W, 3)``) image with row 0 at the bottom.
    alpha : bool
        Write RGBA instead of RGB.

    Raises
    ------
    SinkError
        If the file cannot be written.
    """
    path = os.fspath(path)
    if image_format(path) != ".png":
        raise SinkError(f"write_png: {path} must end in .png (write_image takes other "
                        "formats)")
    write_image(path, to_top_down(rgba_bottom_up, alpha=alpha))


class FrameSink:
    """Base class of the frame sinks.

    Call :meth:`write` once per frame and :meth:`close` at the end (or use the
    sink as a context manager).

    Attributes
    ----------
    count : int
        Frames written so far.
    closed : bool
        True after :meth:`close`.
    """

    def __init__(self) -> None:
        self.count = 0
        self.closed = False

    def write(self, image) -> None:
        """Take one frame: a ``uint8`` ``(H, W, 4)`` array, row 0 at the bottom.

        Raises
        ------
        ValueError
            If the sink is closed or the image has the wrong shape.
        TypeError
            If the image is not ``uint8``.
        SinkError
            If writing fails.
        """
        if self.closed:
            raise ValueError(f"{type(self).__name__} is closed")
        self._write(_check_image(image))
        self.count += 1

    def _write(self, image: np.ndarray) -> None:  # pragma: no cover - abstract
        raise NotImplementedError

    def close(self) -> None:
        """Finish writing; further writes raise ValueError.  Idempotent."""
        self.closed = True

    def __enter__(self):
        return self

    def __exit__(self, *exc_info) -> None:
        self.close()


class MemorySink(FrameSink):
    """Keep every frame in memory as a top-row-first copy (RGBA kept).

    Attributes
    ----------
    frames : list of ndarray
        The frames, oldest first, each ``(H, W, C)`` with row 0 at the top.
    """

    def __init__(self) -> None:
        super().__init__()
        self.frames: list[np.ndarray] = []

    def _write(self, image: np.ndarray) -> None:
        self.frames.append(to_top_down(image))

    def __len__(self) -> int:
        return len(self.frames)

    def __getitem__(self, index):
        return self.frames[index]

    def __iter__(self):
        return iter(self.frames)


class PNGSequenceSink(FrameSink):
    """Write each frame to ``DIRECTORY/PREFIX####.png``, atomically.

    The folder is created and tried when the sink is made (a file written and
    removed), so an unwritable target fails before any frame.  Frame files of an
    earlier run -- ``PREFIX<digits>.png``, also behind a ``win<gid>_`` window prefix
    -- are refused unless ``overwrite``; with it they are all deleted at once, so the
    folder never holds two runs' frames mixed.  Other files are left alone.  Each
    frame is complete under its name the moment it has one (temporary file and
    rename): a killed run leaves every frame written before the kill.

    Parameters
    ----------
    directory : str or path-like
        Output folder, created (with parents) if missing.
    prefix : str
        File name prefix.
    digits : int
        Zero padding of the frame number (numbers past it just get longer).
    start : int
        Number of the first frame.
    alpha : bool
        Write RGBA instead of RGB.
    overwrite : bool
        Delete an earlier run's frame files instead of refusing the folder.

    Attributes
    ----------
    paths : list of str
        Files written so far, in order.

    Raises
    ------
    SinkError
        If the folder cannot be created or written, or holds earlier frames and
        ``overwrite`` is False; the message names the folder.
    """

    def __init__(
        self,
        directory: str | PathLike,
        prefix: str = "frame_",
        *,
        digits: int = 4,
        start: int = 0,
        alpha: bool = False,
        overwrite: bool = False,
    ):
        super().__init__()
        self.directory = os.fspath(directory)
        self.prefix = prefix
        self.digits = digits
        self.start = start
        self.alpha = alpha
        self.paths: list[str] = []
        check_writable_folder(self.directory)
        stale = self.earlier_frames()
        if stale and not overwrite:
            raise SinkError(
                f"frame folder {self.directory} already holds {len(stale)} frame files "
                f"({os.path.basename(stale[0])} ...) of an earlier run; give --overwrite "
                "(overwrite=True) to delete them, or choose another folder")
        for path in stale:
            try:
                os.unlink(path)
            except OSError as exc:
                raise SinkError(f"cannot delete the earlier frame {path}: {exc}") from exc

    def earlier_frames(self) -> list[str]:
        """Frame files in the folder named as this sink (or a window's) names them,
        and the temporary files of frames a killed run was writing."""
        name = rf"(win\d+_)?{re.escape(self.prefix)}\d+\.png"
        pattern = re.compile(rf"{name}|{TEMPORARY.format(name=name)}")
        with os.scandir(self.directory) as entries:
            return sorted(e.path for e in entries if pattern.fullmatch(e.name))

    def path_for(self, index: int) -> str:
        """Return the file name of frame number ``index`` (counting from ``start``)."""
        return os.path.join(self.directory, f"{self.prefix}{index:0{self.digits}d}.png")

    def _write(self, image: np.ndarray) -> None:
        path = self.path_for(self.start + self.count)
        write_image(path, to_top_down(image, alpha=self.alpha))
        self.paths.append(path)


class VideoSink(FrameSink):
    """Write the frames as an animated GIF or an MP4 movie (RGB), as they come.

    The format follows the suffix.  Both are streamed: memory stays one frame
    whatever the length of the run, and a killed run leaves a playable file of the
    frames written so far (see :mod:`vgxsim.sinks.gif` and :mod:`vgxsim.sinks.mp4`).
    GIF keeps up to 256 colours per frame exactly and stores delays in 10 ms units.
    MP4 needs the ``imageio-ffmpeg`` package and is written with libx264 / yuv420p;
    frames of odd width or height are padded by repeating the last column or row.
    All frames must have the same size.

    The target is tried when the sink is made -- its folder exists, it is not there
    already (unless ``overwrite``), a byte written to it reaches the file system, and
    for MP4 ffmpeg with libx264 is available -- so a bad target fails before the run.
    The file is created at the first frame; a sink closed without frames writes none.

    Parameters
    ----------
    path : str or path-like
        Output file ending in ``.gif`` or ``.mp4``; its folder must exist.
    fps : float
        Frames per second.
    overwrite : bool
        Replace an existing file.

    Raises
    ------
    ValueError
        If the suffix is neither ``.gif`` nor ``.mp4``, or ``fps`` <= 0.
    ImportError
        For ``.mp4`` when imageio-ffmpeg (or its libx264) is not available.
    SinkError
        When the file cannot be written, or exists and ``overwrite`` is False.
    """

    def __init__(self, path: str | PathLike, fps: float = 30, *, overwrite: bool = False):
        from vgxsim.sinks.gif import GIFStream
        from vgxsim.sinks.mp4 import FFmpegStream, ffmpeg_problem

        super().__init__()
        self.path = os.fspath(path)
        self.kind = os.path.splitext(self.path)[1].lower()
        if self.kind not in VIDEO_SUFFIXES:
            raise ValueError(f"VideoSink: {self.path!r} must end in .gif or .mp4")
        if not fps > 0:
            raise ValueError(f"VideoSink: fps must be > 0, got {fps}")
        if self.kind == ".mp4":
            problem = ffmpeg_problem()
            if problem is not None:
                raise ImportError(
                    f"cannot write {self.path}: {problem}: pip install imageio-ffmpeg "
                    "(or write a .gif or a PNG directory instead)", name="imageio_ffmpeg")
        check_writable_file(self.path, overwrite)
        self.fps = fps
        self._stream = (GIFStream if self.kind == ".gif" else FFmpegStream)(self.path, fps)
        self._shape: tuple[int, ...] | None = None

    def _write(self, image: np.ndarray) -> None:
        rgb = to_top_down(image, alpha=False)
        if self._shape is None:
            self._shape = rgb.shape
        elif rgb.shape != self._shape:
            raise ValueError(
                f"{self.path}: frame {self.count} is {rgb.shape[1]}x{rgb.shape[0]}, "
                f"earlier frames are {self._shape[1]}x{self._shape[0]}"
            )
        if self.kind == ".mp4":
            h, w = rgb.shape[:2]
            if h % 2 or w % 2:
                rgb = np.pad(rgb, ((0, h % 2), (0, w % 2), (0, 0)), mode="edge")
        try:
            self._stream.append(rgb)
        except OSError as exc:
            raise SinkError(f"cannot write video {self.path}: {exc}") from exc

    def close(self) -> None:
        """Finish the file.  Idempotent."""
        if self.closed:
            return
        super().close()
        try:
            self._stream.close()
        except OSError as exc:
            raise SinkError(f"cannot finish video {self.path}: {exc}") from exc


def open_sink(spec=None, *, fps: float = 30, prefix: str = "frame_", alpha: bool = False,
              overwrite: bool = False):
    """Choose a frame sink from a specification.

    Parameters
    ----------
    spec : None, FrameSink, str or path-like
        ``None`` gives a :class:`MemorySink`; a sink is returned unchanged; a
        path ending in ``.gif``/``.mp4`` gives a :class:`VideoSink`; an existing
        directory, a path ending in a separator, or a path without a suffix
        gives a :class:`PNGSequenceSink`.
    fps : float
        Video frame rate.
    prefix : str
        PNG file name prefix.
    alpha : bool
        PNG files keep the alpha channel.
    overwrite : bool
        Replace an existing video file or an earlier run's PNG frames (see the
        sinks); without it they are refused.

    Returns
    -------
    FrameSink

    Raises
    ------
    ValueError
        If the path is none of the above (for example ``out.png``).
    SinkError
        If the target cannot be written or holds an earlier run's output.
    """
    if spec is None:
        return MemorySink()
    if isinstance(spec, FrameSink):
        return spec
    path = os.fspath(spec)
    suffix = os.path.splitext(path)[1].lower()
    if suffix in VIDEO_SUFFIXES:
        return VideoSink(path, fps=fps, overwrite=overwrite)
    seps = (os.sep, os.altsep or os.sep)
    if os.path.isdir(path) or path.endswith(seps) or suffix == "":
        return PNGSequenceSink(path, prefix, alpha=alpha, overwrite=overwrite)
    raise ValueError(
        f"open_sink: cannot tell what to write for {path!r}: give a directory "
        "(PNG frames), a .gif or .mp4 file, or None (memory)"
    )
