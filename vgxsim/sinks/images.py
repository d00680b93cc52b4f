"""Single image files, written atomically, and the checks every output gets first.

* :func:`write_image` writes one image as PNG, JPEG or TIFF -- the format is taken
  from the file name (``.png``; ``.jpg``/``.jpeg``; ``.tif``/``.tiff``) and any other
  name is refused -- through a temporary file in the same folder and
  :func:`os.replace`, so the name holds either the old file or the complete new one,
  never half of one.  An existing file is replaced only with ``overwrite=True``.
* :func:`check_writable_file` and :func:`check_writable_folder` try the target
  before a run starts (a folder that is a file, a read-only or full file system, a
  device such as ``/dev/full``), so a bad target fails at once, not after the run.

Every failure raises :class:`SinkError` (an :class:`OSError`) naming the path.
"""

from __future__ import annotations

import itertools
import os
from os import PathLike

import numpy as np

from vgxsim.sinks.atomic import atomic_path

__all__ = ["IMAGE_FORMATS", "SinkError", "write_image", "image_format",
           "check_writable_file", "check_writable_folder", "atomic_write"]

#: File name suffix -> imageio extension of the format written.
IMAGE_FORMATS = {".png": ".png", ".jpg": ".jpg", ".jpeg": ".jpg", ".tif": ".tif",
                 ".tiff": ".tif"}

#: imageio extension -> Pillow's format name.
_PIL_FORMATS = {".png": "PNG", ".jpg": "JPEG", ".tif": "TIFF"}

_tmp_counter = itertools.count()


class SinkError(OSError):
    """An output could not be written; the message names the file."""


def _reason(exc: BaseException) -> str:
    return exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)


def image_format(path: str) -> str:
    """The imageio extension for an image file name; SinkError when unknown."""
    suffix = os.path.splitext(path)[1].lower()
    if suffix not in IMAGE_FORMATS:
        raise SinkError(f"cannot tell the image format of {path}: the name must end in "
                        f"{', '.join(IMAGE_FORMATS)}")
    return IMAGE_FORMATS[suffix]


def check_writable_folder(folder: str) -> None:
    """Create ``folder`` if missing and prove a file can be written in it."""
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as exc:
        raise SinkError(f"cannot create folder {folder}: {_reason(exc)}") from exc
    probe = os.path.join(folder, f".vgxsim-probe.{os.getpid()}.{next(_tmp_counter)}")
    try:
        with open(probe, "xb") as fh:
            fh.write(b"\0")
    except OSError as exc:
        raise SinkError(f"cannot write in folder {folder}: {_reason(exc)}") from exc
    finally:
        try:
            os.unlink(probe)
        except OSError:
            pass


def _holds_data(path: str) -> bool:
    """Whether replacing ``path`` could lose anything: an empty regular file (a
    placeholder such as ``tempfile.mkstemp`` makes) holds nothing."""
    return not (os.path.isfile(path) and os.path.getsize(path) == 0)


def check_writable_file(path: str, overwrite: bool) -> None:
    """Prove ``path`` can be written: its folder exists, it is not a folder, it does
    not exist unless ``overwrite`` (an empty file counts as absent: nothing can be
    lost), and a byte written to it reaches the file system (``/dev/full`` fails
    here).  Leaves no new file behind; an existing one is left empty, which
    ``overwrite`` (or its being empty already) allows."""
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise SinkError(f"cannot write {path}: its folder {folder} does not exist")
    if os.path.isdir(path):
        raise SinkError(f"cannot write {path}: it is a folder")
    existed = os.path.lexists(path)
    if existed and not overwrite and _holds_data(path):
        raise SinkError(f"{path} exists; give --overwrite (overwrite=True) to replace it")
    regular = not existed or os.path.isfile(path)
    try:
        with open(path, "wb") as fh:
            fh.write(b"\0")
            fh.flush()
            if regular:  # a full file system may only say so when the data goes out
                os.fsync(fh.fileno())
    except OSError as exc:
        raise SinkError(f"cannot write {path}: {_reason(exc)}") from exc
    finally:
        try:
            if regular and not existed:
                os.unlink(path)
            elif regular:
                os.truncate(path, 0)  # the probe byte goes; the (emptied) file stays
        except OSError:
            pass


def atomic_write(path: str, write) -> None:
    """Call ``write(fh)`` on a temporary file beside ``path`` (named by
    :func:`vgxsim.sinks.atomic.atomic_path`), then rename it to ``path``; any failure
    leaves ``path`` as before and raises SinkError naming it."""
    try:
        with atomic_path(path) as tmp, open(tmp, "xb") as fh:
            write(fh)
    except Exception as exc:
        raise SinkError(f"cannot write {path}: {_reason(exc)}") from exc


def write_image(path: str | PathLike, top_down: np.ndarray, *, overwrite: bool = True
                ) -> None:
    """Write one image, top row first, atomically, in the format its name says.

    Parameters
    ----------
    path : str or path-like
        ``.png``, ``.jpg``/``.jpeg`` or ``.tif``/``.tiff``; its folder must exist.
    top_down : ndarray
        ``uint8`` ``(H, W, 3)`` or ``(H, W, 4)``, row 0 at the top.  JPEG drops alpha.
    overwrite : bool
        Replace an existing file (False: an existing file raises SinkError).

    Raises
    ------
    SinkError
        For an unknown suffix, an existing file without ``overwrite``, or any write
        failure; the message names the file.
    """
    path = os.fspath(path)
    ext = image_format(path)
    if not overwrite and os.path.lexists(path) and _holds_data(path):
        raise SinkError(f"{path} exists; give --overwrite (overwrite=True) to replace it")
    if ext == ".jpg":
        top_down = np.ascontiguousarray(top_down[..., :3])
    # Pillow writes all three (imageio's vendored tifffile is deprecated), called
    # directly: imageio's pillow plugin asks Pillow for every registered extension,
    # which imports all of its ~40 format plugins (about 0.07 s CPU of a warm
    # `vgxsim shadows`, docs/cold_start.md); the bytes are the same.
    from PIL import Image

    atomic_write(path, lambda fh: Image.fromarray(np.ascontiguousarray(top_down)).save(
        fh, format=_PIL_FORMATS[ext]))
