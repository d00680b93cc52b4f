"""One freshness stamp for every cached kernel: the content of all kernel sources.

Numba's on-disk cache (``cache=True``, kernels/options.py) keys a compiled function
by the content of the one file that defines it.  A vgxsim kernel also compiles in
what it inlines from other files (kernels/spans.py, tiles.py, texture.py into
render.py's band kernel) and the codes it reads as compile-time constants
(vgxsim/state/codes.py, vgxsim/stream/opcodes.py).  Change only one of those and
Numba would load the old machine code, silently drawing with the old rules (it
happened twice while the raster and texture stages were being changed).

So for functions defined under kernels/ the stamp is the pair (Numba's own stamp,
a SHA-256 of every file listed above): any change to any of them recompiles every
kernel once.  The hook wraps Numba's cache locators; it uses Numba's internal
``CacheImpl._locator_classes`` list and does nothing if a Numba release renames it
(the cache then behaves as Numba's own, as before).
"""

from __future__ import annotations

import functools
import hashlib
import os

_KERNELS = os.path.dirname(os.path.abspath(__file__))
_PACKAGE = os.path.join(os.path.dirname(_KERNELS), "vgxsim")
#: Files outside kernels/ whose values the kernels compile in as constants.
_CONSTANT_SOURCES = (os.path.join("state", "codes.py"), os.path.join("stream", "opcodes.py"))


def _sources() -> list[str]:
    files = sorted(os.path.join(_KERNELS, f) for f in os.listdir(_KERNELS) if f.endswith(".py"))
    package = _PACKAGE
    if not os.path.isdir(package):  # installed: kernels/ is vgxsim/kernels
        package = os.path.dirname(_KERNELS)
    files += [os.path.join(package, f) for f in _CONSTANT_SOURCES]
    return files


@functools.lru_cache(maxsize=1)
def kernel_sources_digest() -> str:
    """SHA-256 (hex) of the kernel sources and the code tables they compile in."""
    digest = hashlib.sha256()
    for path in _sources():
        digest.update(os.path.basename(path).encode())
        try:
            with open(path, "rb") as f:
                digest.update(f.read())
        except OSError:
            digest.update(b"<missing>")
    return digest.hexdigest()


def _in_kernels(py_file: str) -> bool:
    return os.path.dirname(os.path.abspath(py_file)) == _KERNELS


def _stamped(locator_class: type) -> type:
    class Stamped(locator_class):  # type: ignore[misc, valid-type]
        @classmethod
        def from_function(cls, py_func, py_file):
            if not _in_kernels(py_file):
                return None
            return super().from_function(py_func, py_file)

        def get_source_stamp(self):
            return (super().get_source_stamp(), kernel_sources_digest())

    Stamped.__name__ = "VgxsimStamped" + locator_class.__name__
    return Stamped


def install() -> bool:
    """Put the stamped locators ahead of Numba's own (idempotent).

    Returns
    -------
    bool
        Whether the hook is in place (False when this Numba has no locator list).
    """
    try:
        from numba.core.caching import CacheImpl
    except ImportError:
        return False
    classes = getattr(CacheImpl, "_locator_classes", None)
    if not isinstance(classes, list):
        return False
    if any(getattr(c, "__name__", "").startswith("VgxsimStamped") for c in classes):
        return True
    CacheImpl._locator_classes = [_stamped(c) for c in classes] + classes
    return True
