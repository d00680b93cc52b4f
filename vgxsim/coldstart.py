"""Cold start: compile the raster and geometry kernels in two processes at once.

With an empty Numba cache the first image waits for every kernel it needs to
compile, one after another (Numba compiles under one global lock, so threads do
not help).  The kernels fall into two trees that share nothing: the band kernel
(``render_bands_lean_borrowed``, the copy a first image without points, lines or
general-path states uses, and everything it calls) and the geometry kernels (transform,
clip, project, set-up, the command-stream decoder, edge adjacency and Newell
normals of shadow-casting meshes).  When the band kernel's cache entry is missing,
the first :class:`~vgxsim.batch.CommandBatch` of a process starts one helper
process that draws a tiny image through both front ends (``Context.draw_arrays``
and the IRIS GL calls) and builds the adjacency of a tetrahedron, with flushing
switched off (so it compiles, and caches, only the geometry kernels); meanwhile
this process compiles the band kernel by flushing a one-clear batch, then waits
for the helper.  The geometry kernels then load from the cache.  The band kernel
is the longer of the two, so the helper's extra kernels (those of ``vgxsim run``
programs, ``vgxsim shadows`` and the examples) come at no cost to a first image
that does not use them.  The helper's kernels must be compiled for the argument
types the real first image passes (array layouts included: a signature the helper
did not compile is compiled again, serially, in this process; see
docs/cold_start.md for the two that were).

Set ``VGXSIM_PARALLEL_COMPILE=0`` to compile in-process only (also the default on a
single CPU, and whenever the cache cannot be inspected).
"""

from __future__ import annotations

import os
import subprocess
import sys

_ENV = "VGXSIM_PARALLEL_COMPILE"
_started = False

_GEOMETRY = r"""
import vgxsim.batch as B
B.CommandBatch.flush = lambda self: B.CommandBatch._reset(self)  # geometry only
from vgxsim.geometry.transform import orthographic
from vgxsim.pipeline.context import Context
ctx = Context(32, 32, stencil=8)
ctx.matrices.load_projection(orthographic(-0.5, 31.5, -0.5, 31.5, -1, 1))
ctx.raster.set(zbuffer=True)
ctx.draw_arrays("polygon", [[1, 1, 0], [30, 2, 0], [16, 30, 0]],
                [[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1]])
ctx.flush()
from vgxsim import gl
gl.prefsize(16, 12)
w = gl.winopen("coldstart")
gl.RGBmode()
gl.doublebuffer()
gl.gconfig()
gl.zbuffer(1)
gl.ortho(-1, 1, -1, 1, -1, 1)
gl.bgnpolygon()
gl.c3f((1, 0, 0))
for v in ((-0.5, -0.5, 0), (0.5, -0.5, 0), (0, 0.5, 0)):
    gl.v3f(v)
gl.endpolygon()
gl.swapbuffers()
gl.winclose(w)
from vgxsim.shadow.scene import polyhedron_from_polygons
polyhedron_from_polygons([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
                         [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], "tetrahedron")
"""


def _band_kernel_cached(batch_type) -> bool | None:
    """Whether the band kernel a first batch of ``batch_type`` compiles (the copy of
    its ``lean_kernel`` and ``borrow_arrays`` switches: each copy has its own cache
    entry) is loaded or has a cache index on disk (None: cannot tell)."""
    try:
        kernel = batch_type.band_kernel(batch_type.lean_kernel, batch_type.borrow_arrays)
        if kernel.signatures:
            return True
        return os.path.exists(kernel._cache._cache_file._index_path)
    except (AttributeError, OSError):
        return None


def prepare(batch_type) -> None:
    """Compile the kernels of a first image in parallel if the cache is cold.

    Called by the first ``CommandBatch``, and by ``vgxsim shadows`` before it builds
    its scene (whose edge adjacency would otherwise compile alone, before any
    batch exists); later calls return at once.

    Parameters
    ----------
    batch_type : type
        :class:`vgxsim.batch.CommandBatch` (passed in to keep the import one-way).
    """
    global _started
    if _started:
        return
    _started = True
    if os.environ.get(_ENV, "1") == "0" or (os.cpu_count() or 1) < 2:
        return
    if _band_kernel_cached(batch_type) is not False:
        return
    env = dict(os.environ, **{_ENV: "0"})
    try:
        helper = subprocess.Popen([sys.executable, "-c", _GEOMETRY], env=env,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    except OSError:
        return
    try:
        from vgxsim.state.planes import Framebuffer, PlaneConfig
        from vgxsim.state.raster import RasterState

        batch = batch_type(Framebuffer(PlaneConfig(8, 8, stencil=8)))
        batch.add_clear(7, 0, 0, 0, RasterState(scissor=(0, 7, 0, 7)))
        batch.flush()  # compiles the batch's lean band kernel and the kernels it calls
    finally:
        try:
            helper.wait(timeout=600)
        except subprocess.TimeoutExpired:  # never block drawing on the helper
            helper.kill()
