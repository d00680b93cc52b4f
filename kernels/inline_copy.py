"""Cold start: copy an ``inline='always'`` callee's IR in linear time.

Numba inlines an IR-level callee (kernels/options.py ``inline_ir``) by
``InlineWorker.inline_ir`` (numba/core/inline_closurecall.py), which copies the
callee's IR twice with ``copy.deepcopy`` block by block, each block with a memo of
its own.  Every ``ir.Var`` points at the function's ``ir.Scope``, which holds every
variable, so each block copy copies the whole scope again: time grows as blocks x
variables.  For the band kernel (``_triangle_rows`` and ``_colour_span`` inlined
into ``render_bands``) that was the larger part of its inline pass.

The fix shares one memo across the blocks of one copy, so the scope is copied once
per copy, not once per block.  It is Numba's own method with that one edit, made
from its source text at install time; where the text is not the one this was
written against (another Numba release) nothing is patched and Numba runs as
shipped.  Only the untyped inliner (the path ``inline='always'`` functions take)
uses the shared memo; the typed inliner (overloads) keeps the stock copy.  The
copies differ from the stock ones only in which equal objects are shared, never in
content: the LLVM IR of the band kernel is byte-identical with the switch on and
off (tests/test_coldstart_patches.py).

Switch: ``VGXSIM_LINEAR_INLINE=0`` keeps the stock method.
"""

from __future__ import annotations

import hashlib
import importlib.abc
import importlib.util
import inspect
import os
import sys
import textwrap

ENV = "VGXSIM_LINEAR_INLINE"

#: SHA-256 of the stock ``InlineWorker.inline_ir`` source this edit was made for
#: (Numba 0.68.1; another text means another release: left stock).
_STOCK_SHA256 = "a16b53c6f9e858e6acbd54f71eaad377dbe552fab09acc9124f558d07f86567a"

_OLD = """\
        for block_label, block in the_ir.blocks.items():
            new_block = copy.deepcopy(the_ir.blocks[block_label])
"""
# One memo per copy of one IR (the untyped inliner only, see the module docstring).
_NEW = """\
        memo = None if self._permit_update_type_and_call_maps else {}
        for block_label, block in the_ir.blocks.items():
            new_block = copy.deepcopy(the_ir.blocks[block_label], memo)
"""

_installed = False


def enabled() -> bool:
    """Whether the switch is on (``VGXSIM_LINEAR_INLINE`` not ``0``)."""
    return os.environ.get(ENV, "1") != "0"


def install() -> bool:
    """Put the linear-copy edit of ``InlineWorker.inline_ir`` in place (idempotent).

    Numba imports its inliner only when it first compiles (or refreshes), so while
    it has not, the edit waits for that import (a warm start never pays for the
    inliner's import).

    Returns
    -------
    bool
        Whether the edit is in place or waits for the import (False: switch off, or
        the Numba source is not the expected one, so the stock method runs).
    """
    if _installed:
        return True
    if not enabled():
        return False
    if _MODULE in sys.modules:
        return _patch()
    if not any(isinstance(f, _AfterImport) for f in sys.meta_path):
        sys.meta_path.insert(0, _AfterImport())
    return True


_MODULE = "numba.core.inline_closurecall"


class _AfterImport(importlib.abc.MetaPathFinder):
    """Finds Numba's inliner as Python would, and patches it once it has run."""

    def find_spec(self, name, path=None, target=None):
        if name != _MODULE:
            return None
        sys.meta_path.remove(self)
        spec = importlib.util.find_spec(name)
        loader = getattr(spec, "loader", None)
        if loader is None or not hasattr(loader, "exec_module"):
            return spec
        stock_exec = loader.exec_module

        def exec_module(module):
            stock_exec(module)
            sys.modules[_MODULE] = module  # the import system sets it after; _patch reads it
            _patch()

        loader.exec_module = exec_module
        return spec


def _patch() -> bool:
    global _installed
    if _installed:
        return True
    try:
        icc = sys.modules[_MODULE]
        stock = icc.InlineWorker.inline_ir
        src = textwrap.dedent(inspect.getsource(stock))
    except (KeyError, AttributeError, OSError, TypeError):
        return False
    if hashlib.sha256(src.encode()).hexdigest() != _STOCK_SHA256 or src.count(_OLD) != 1:
        return False
    namespace: dict = {}
    try:
        exec(compile(src.replace(_OLD, _NEW), icc.__file__, "exec"), vars(icc), namespace)
    except Exception:  # noqa: BLE001 - any failure leaves Numba as shipped
        return False
    edited = namespace.get("inline_ir")
    if edited is None:
        return False
    edited.__doc__ = stock.__doc__
    edited.__wrapped__ = stock
    icc.InlineWorker.inline_ir = edited
    _installed = True
    return True
