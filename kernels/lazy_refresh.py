"""Warm start: load a cached kernel without refreshing Numba's registries first.

Before it loads a compiled function from the on-disk cache, Numba's
``Cache.load_overload`` (numba/core/caching.py) refreshes the target context:
``CPUContext.load_additional_registries`` imports every implementation module of
Numba (numpy maths, linear algebra, which imports SciPy to find BLAS, typed
containers, random generators...) and installs their registries.  Loading machine
code needs none of that: only the runtime (NRT) symbols that compiled code links
against, which ``rtsys.initialize`` provides.  The registries are needed to
*compile*, and every compile refreshes the context itself (``CompilerBase``
in numba/core/compiler.py), so a process that only loads cached kernels skips the
imports, and one that compiles pays them at its first compile, as before.

The edit applies to the CPU target only and only where both Numba methods are the
text it was written against (Numba 0.68.1); otherwise Numba runs as shipped.

Switch: ``VGXSIM_LAZY_REFRESH=0`` keeps the stock refresh.
"""

from __future__ import annotations

import hashlib
import inspect
import os
import textwrap

ENV = "VGXSIM_LAZY_REFRESH"

#: SHA-256 of the stock sources this edit relies on (Numba 0.68.1): the loader, and
#: the refresh whose only part a load needs is ``rtsys.initialize``.
_LOAD_SHA256 = "ce996aaf54591bdb49ecd77d55d830d8d31254ad0abd9280336c1cb8fb30f74a"
_REGISTRIES_SHA256 = "d05741badb450356d860611ded04ceb3b0192a739f5556b468fe6ffc0bbda3c2"

_installed = False


def enabled() -> bool:
    """Whether the switch is on (``VGXSIM_LAZY_REFRESH`` not ``0``)."""
    return os.environ.get(ENV, "1") != "0"


def _sha(func) -> str:
    return hashlib.sha256(textwrap.dedent(inspect.getsource(func)).encode()).hexdigest()


def install() -> bool:
    """Make cache loads on the CPU target skip the registry refresh (idempotent).

    Returns
    -------
    bool
        Whether the lazy loader is in place (False: switch off, or the Numba
        sources are not the expected ones, so the stock loader runs).
    """
    global _installed
    if _installed:
        return True
    if not enabled():
        return False
    try:
        from numba.core import caching, cpu
        from numba.core.runtime import rtsys

        stock = caching.Cache.load_overload
        if (_sha(stock) != _LOAD_SHA256
                or _sha(cpu.CPUContext.load_additional_registries) != _REGISTRIES_SHA256):
            return False
    except (ImportError, AttributeError, OSError, TypeError):
        return False

    def load_overload(self, sig, target_context):
        if type(target_context) is not cpu.CPUContext:
            return stock(self, sig, target_context)
        rtsys.initialize(target_context)  # the NRT symbols loaded code links against
        with self._guard_against_spurious_io_errors():
            return self._load_overload(sig, target_context)

    load_overload.__doc__ = stock.__doc__
    load_overload.__wrapped__ = stock
    caching.Cache.load_overload = load_overload
    _installed = True
    return True
