"""Atomic outputs: write under a temporary name beside the target, then rename.

A run that fails part way (a bad scene, a full disk, a signal) leaves no
half-written file: the target is the old file, absent, or complete
(``os.replace`` is atomic within one directory on POSIX and Windows).  Every
writer of vgxsim -- images, frame folders, .glo models, caches, SGI textures --
goes through :func:`atomic_path`, so there is one naming of temporary files and
:data:`TEMPORARY` recognises a killed run's leftovers.
"""

from __future__ import annotations

import contextlib
import itertools
import os
from collections.abc import Iterator

__all__ = ["atomic_path", "temporary_name", "TEMPORARY"]

_counter = itertools.count()

#: Regular expression (a format string of the target's escaped file name) matching
#: the temporary names :func:`temporary_name` gives it.
TEMPORARY = r"\.{name}\.\d+\.\d+\.tmp(?:\.[^/]*)?"


def temporary_name(path: str | os.PathLike) -> str:
    """A fresh name beside ``path``: ``.NAME.PID.N.tmp`` plus NAME's own suffixes, so
    writers that choose a format by suffix (imageio, gzip for ``.glo.gz``) still do."""
    folder, name = os.path.split(os.path.abspath(os.fspath(path)))
    suffix = name[name.find("."):] if "." in name.lstrip(".") else ""
    return os.path.join(folder, f".{name}.{os.getpid()}.{next(_counter)}.tmp{suffix}")


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[str]:
    """Yield a temporary path beside ``path``; when the block ends normally it is
    renamed to ``path``, when it raises (or is interrupted) it is removed."""
    tmp = temporary_name(path)
    try:
        yield tmp
        os.replace(tmp, os.fspath(path))
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(tmp)
        raise
