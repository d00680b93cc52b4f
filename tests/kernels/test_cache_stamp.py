"""Cached kernels are keyed by every kernel source, not only their own file
(kernels/cache_stamp.py): a change in an inlined helper or a code table must
recompile them."""

from __future__ import annotations

import os

import vgxsim.kernels.render as render
from vgxsim.kernels import cache_stamp


def _locator(dispatcher):
    return dispatcher._cache._impl.locator


def test_kernel_dispatchers_use_the_stamped_locator():
    locator = _locator(render.render_bands)
    assert type(locator).__name__.startswith("VgxsimStamped")
    own, digest = locator.get_source_stamp()
    assert digest == cache_stamp.kernel_sources_digest()


def test_digest_covers_inlined_helpers_and_code_tables():
    names = {os.path.relpath(p, os.path.dirname(cache_stamp._KERNELS))
             for p in cache_stamp._sources()}
    for needed in ("kernels/spans.py", "kernels/tiles.py", "kernels/texture.py",
                   "kernels/render.py", "vgxsim/state/codes.py", "vgxsim/stream/opcodes.py"):
        assert needed in names


def test_stamp_changes_when_any_source_changes(tmp_path, monkeypatch):
    a, b = tmp_path / "a.py", tmp_path / "b.py"
    a.write_text("X = 1\n")
    b.write_text("Y = 2\n")
    monkeypatch.setattr(cache_stamp, "_sources", lambda: [str(a), str(b)])
    cache_stamp.kernel_sources_digest.cache_clear()
    try:
        locator = _locator(render.render_bands)
        before = locator.get_source_stamp()
        cache_stamp.kernel_sources_digest.cache_clear()
        assert locator.get_source_stamp() == before  # nothing changed: same stamp
        b.write_text("Y = 3\n")  # only a file the kernel does not define changes
        cache_stamp.kernel_sources_digest.cache_clear()
        after = locator.get_source_stamp()
        assert after[0] == before[0] and after[1] != before[1]
    finally:
        cache_stamp.kernel_sources_digest.cache_clear()


def test_functions_outside_kernels_keep_numbas_locator():
    import numba

    @numba.njit(cache=True)
    def outside(x):  # defined in tests/: not a kernel
        return x + 1

    assert not type(_locator(outside)).__name__.startswith("VgxsimStamped")
