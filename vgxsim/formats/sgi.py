"""SGI image files (``.rgb``, ``.sgi``, ``.bw``): the ``shadows`` program's textures.

README of ``shadows``: "Textures are stored in SGI image format with a ".rgb"
suffix."  Read and written through Pillow (its SGI plugin), which imageio also uses.
"""

from __future__ import annotations

import os

import numpy as np

from vgxsim.sinks.atomic import atomic_path

from .errors import FormatError


def read_rgb(path: str | os.PathLike) -> np.ndarray:
    """Read an SGI image.

    Returns
    -------
    ndarray, shape (H, W, C), uint8
        C = 1 (bw), 3 (rgb) or 4 (rgba); row 0 is the top row, as Pillow gives it.

    Raises
    ------
    FormatError
        If the file is missing or is not an SGI image.
    """
    from PIL import Image, UnidentifiedImageError

    path = os.fspath(path)
    try:
        with Image.open(path) as im:
            if im.format != "SGI":
                raise FormatError(path, None, f"expected an SGI image (.rgb), found {im.format}")
            arr = np.asarray(im)
    except FileNotFoundError:
        raise FormatError(path, None, "no such texture file") from None
    except (UnidentifiedImageError, OSError, SyntaxError, ValueError) as exc:
        raise FormatError(path, None, f"not a readable SGI image ({exc})") from None
    if arr.dtype != np.uint8:
        arr = (arr >> 8).astype(np.uint8) if arr.dtype == np.uint16 else arr.astype(np.uint8)
    return arr if arr.ndim == 3 else arr[:, :, None]


def write_rgb(path: str | os.PathLike, image: np.ndarray) -> None:
    """Write an (H, W, 3) or (H, W, 4) uint8 image (row 0 = top) as SGI, atomically."""
    from PIL import Image

    img = np.ascontiguousarray(image, dtype=np.uint8)
    with atomic_path(path) as tmp:
        Image.fromarray(img).save(tmp, format="SGI")
