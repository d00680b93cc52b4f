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
* :class:`VideoSink` -- an animated GIF (imageio + pillow) or an MP4 (needs
  the ``imageio-ffmpeg`` package; constructing one without it raises
  ImportError naming the package).
* :func:`open_sink` picks one from a path; :func:`write_png` writes one image.

Write failures raise :class:`SinkError` (an :class:`OSError`) naming the file.
"""

from __future__ import annotations

import importlib.util
import itertools
import os
from os import PathLike

import numpy as np

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
_tmp_counter = itertools.count()


class SinkError(OSError):
    """A frame could not be written; the message names the file."""


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


def _atomic_write_png(path: str, top_down: np.ndarray) -> None:
    """Write ``top_down`` to ``path`` as PNG via a temporary file in the same folder."""
    import imageio.v3 as iio

    folder, name = os.path.split(os.path.abspath(path))
    tmp = os.path.join(folder, f".{name}.{os.getpid()}.{next(_tmp_counter)}.tmp")
    try:
        with open(tmp, "xb") as fh:
            iio.imwrite(fh, top_down, extension=".png")
        os.replace(tmp, path)
    except BaseException as exc:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if isinstance(exc, Exception):
            raise SinkError(f"cannot write PNG {path}: {exc}") from exc
        raise


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
    _atomic_write_png(os.fspath(path), to_top_down(rgba_bottom_up, alpha=alpha))


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
    """Write each frame to ``DIRECTORY/PREFIX####.png``.

    Parameters
    ----------
    directory : str or path-like
        Output folder, created (with parents) if missing.  Existing files are
        overwritten, and files from an earlier, longer run are left alone.
    prefix : str
        File name prefix.
    digits : int
        Zero padding of the frame number (numbers past it just get longer).
    start : int
        Number of the first frame.
    alpha : bool
        Write RGBA instead of RGB.

    Attributes
    ----------
    paths : list of str
        Files written so far, in order.
    """

    def __init__(
        self,
        directory: str | PathLike,
        prefix: str = "frame_",
        *,
        digits: int = 4,
        start: int = 0,
        alpha: bool = False,
    ):
        super().__init__()
        self.directory = os.fspath(directory)
        self.prefix = prefix
        self.digits = digits
        self.start = start
        self.alpha = alpha
        self.paths: list[str] = []
        try:
            os.makedirs(self.directory, exist_ok=True)
        except OSError as exc:
            raise SinkError(f"cannot create frame directory {self.directory}: {exc}") from exc

    def path_for(self, index: int) -> str:
        """Return the file name of frame number ``index`` (counting from ``start``)."""
        return os.path.join(self.directory, f"{self.prefix}{index:0{self.digits}d}.png")

    def _write(self, image: np.ndarray) -> None:
        path = self.path_for(self.start + self.count)
        _atomic_write_png(path, to_top_down(image, alpha=self.alpha))
        self.paths.append(path)


def _ffmpeg_available() -> bool:
    return importlib.util.find_spec("imageio_ffmpeg") is not None


class VideoSink(FrameSink):
    """Write the frames as an animated GIF or an MP4 movie (RGB).

    The format follows the suffix.  GIF goes through imageio's pillow plugin
    (colours are reduced to a 256-entry palette per frame, delays are stored in
    10 ms units, and pillow merges identical consecutive frames).  MP4 needs the
    ``imageio-ffmpeg`` package and is written with libx264 / yuv420p; frames of
    odd width or height are padded by repeating the last column or row.  All
    frames must have the same size.  The file is created at the first frame and
    completed by :meth:`close`; a sink closed without frames writes no file.

    Parameters
    ----------
    path : str or path-like
        Output file ending in ``.gif`` or ``.mp4``; its folder must exist.
    fps : float
        Frames per second.

    Raises
    ------
    ValueError
        If the suffix is neither ``.gif`` nor ``.mp4``, or ``fps`` <= 0.
    ImportError
        For ``.mp4`` when ``imageio-ffmpeg`` is not installed.
    """

    def __init__(self, path: str | PathLike, fps: float = 30):
        super().__init__()
        self.path = os.fspath(path)
        self.kind = os.path.splitext(self.path)[1].lower()
        if self.kind not in VIDEO_SUFFIXES:
            raise ValueError(f"VideoSink: {self.path!r} must end in .gif or .mp4")
        if not fps > 0:
            raise ValueError(f"VideoSink: fps must be > 0, got {fps}")
        if self.kind == ".mp4" and not _ffmpeg_available():
            raise ImportError(
                f"writing MP4 ({self.path}) needs the 'imageio-ffmpeg' package, which is "
                "not installed: pip install imageio-ffmpeg (or write a .gif or a PNG "
                "directory instead)",
                name="imageio_ffmpeg",
            )
        self.fps = fps
        self._writer = None
        self._shape: tuple[int, ...] | None = None

    def _open(self):
        if self.kind == ".gif":
            import imageio.v3 as iio

            return iio.imopen(self.path, "w", extension=".gif")
        import imageio.v2 as iio2

        return iio2.get_writer(
            self.path,
            format="FFMPEG",
            mode="I",
            fps=self.fps,
            codec="libx264",
            pixelformat="yuv420p",
            macro_block_size=1,
        )

    def _write(self, image: np.ndarray) -> None:
        rgb = to_top_down(image, alpha=False)
        if self._shape is None:
            self._shape = rgb.shape
        elif rgb.shape != self._shape:
            raise ValueError(
                f"{self.path}: frame {self.count} is {rgb.shape[1]}x{rgb.shape[0]}, "
                f"earlier frames are {self._shape[1]}x{self._shape[0]}"
            )
        try:
            if self._writer is None:
                self._writer = self._open()
            if self.kind == ".gif":
                self._writer.write(rgb, duration=1000.0 / self.fps, loop=0)
            else:
                h, w = rgb.shape[:2]
                if h % 2 or w % 2:
                    rgb = np.pad(rgb, ((0, h % 2), (0, w % 2), (0, 0)), mode="edge")
                self._writer.append_data(rgb)
        except Exception as exc:
            raise SinkError(f"cannot write video {self.path}: {exc}") from exc

    def close(self) -> None:
        """Finish the file.  Idempotent."""
        if self.closed:
            return
        super().close()
        writer, self._writer = self._writer, None
        if writer is not None:
            try:
                writer.close()
            except Exception as exc:
                raise SinkError(f"cannot finish video {self.path}: {exc}") from exc


def open_sink(spec=None, *, fps: float = 30, prefix: str = "frame_", alpha: bool = False):
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

    Returns
    -------
    FrameSink

    Raises
    ------
    ValueError
        If the path is none of the above (for example ``out.png``).
    """
    if spec is None:
        return MemorySink()
    if isinstance(spec, FrameSink):
        return spec
    path = os.fspath(spec)
    suffix = os.path.splitext(path)[1].lower()
    if suffix in VIDEO_SUFFIXES:
        return VideoSink(path, fps=fps)
    seps = (os.sep, os.altsep or os.sep)
    if os.path.isdir(path) or path.endswith(seps) or suffix == "":
        return PNGSequenceSink(path, prefix, alpha=alpha)
    raise ValueError(
        f"open_sink: cannot tell what to write for {path!r}: give a directory "
        "(PNG frames), a .gif or .mp4 file, or None (memory)"
    )
