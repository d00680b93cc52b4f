"""Atomic output: write to a temporary file beside the target, then rename.

A run that fails part way (a bad scene, an interrupt) leaves no half-written file:
the target is either the old file, or absent, or complete (``os.replace`` is atomic
on POSIX and Windows within one directory).
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Iterator


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[str]:
    """Yield a temporary path beside ``path`` with the same suffix; on success it is
    renamed to ``path``, on an exception it is removed."""
    path = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(path))
    base = os.path.basename(path)
    suffix = base[base.find("."):] if "." in base else ".tmp"  # writers pick formats by it
    fd, tmp = tempfile.mkstemp(prefix=f".{base}.", suffix=suffix, dir=folder)
    os.close(fd)
    umask = os.umask(0)
    os.umask(umask)
    try:
        yield tmp
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; give the usual permissions
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(tmp)
        raise
