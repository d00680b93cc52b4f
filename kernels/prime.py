"""Cold start: the band kernel's block-update callees, compiled ahead of it.

With an empty Numba cache the band kernel (kernels/render.py, the lean copy a
first image takes) compiles in the main process with all its callees, while the
helper process of vgxsim/coldstart.py compiles the geometry kernels; the band
tree is the longer of the two by several seconds (docs/cold_start.md, s23).  Its
largest callee tree, the block update (:func:`.blocks.z_passed_row`, with
:func:`.blocks._colour_passed` and :func:`.lit.lit_span_lanes`: about 4 s of CPU),
is a ``callee``: cached on its own, so a process that finds its cache entry loads
it instead of compiling it.  :func:`prime_band_callees` calls it with the
argument types of its call in ``_triangle_rows``, made the way the borrowed band
kernel makes them; the helper runs it first, so the entry is written before the
main process's typing of the band kernel reaches that call (several seconds into
its compile: inlining, SSA and the code before it come first).

The call sits behind a run-time ``run`` flag that the helper passes as False:
typing compiles the callee, nothing is drawn.  Numba looks a callee's cache up by
its full signature, array types and layouts included: a type here that differs
from the band kernel's only costs time (the main process compiles its own, as
before); tests/test_coldstart.py checks that the main process then compiles none
of the three.
"""

from __future__ import annotations

import numpy as np

from vgxsim.state.codes import S_DRAW_BACK

from .blocks import z_passed_row
from .borrow import borrow, keep_alive
from .options import jit


@jit(cache=False)
def prime_band_callees(run, t_col, states, derived, tables, front, back, zbuf, sten,
                       vector_pack, lit_lanes):
    """Compile :func:`.blocks.z_passed_row` for the band kernel's argument types.

    Parameters
    ----------
    run : bool
        False: only compile (the call is not made).
    t_col : ndarray, shape (T, 4, 3), float64
        A batch's colour planes (``CommandBatch.t_col``).
    states, derived, tables : ndarray
        A batch's state tables (``CommandBatch._state_tables``), at least one row.
    front, back, zbuf, sten : ndarray
        ``Framebuffer.kernel_planes()``.
    vector_pack, lit_lanes : bool
        The batch's switches (their type only matters).
    """
    # As render_bands_lean_borrowed and _bands_body make them: the arguments
    # borrowed, each state's rows borrowed views of them.
    t_col_b = borrow(t_col)
    states_b = borrow(states)
    derived_b = borrow(derived)
    tables_b = borrow(tables)
    front_b = borrow(front)
    back_b = borrow(back)
    st = borrow(states_b[0])
    dv = borrow(derived_b[0])
    tab = borrow(tables_b[0])
    cbuf = back_b if st[S_DRAW_BACK] else front_b
    if run:
        z_passed_row(np.int64(0), np.uintp(0), np.int64(0), np.int64(-1), 0.0, 0.0, 0.0,
                     0.0, np.int64(0), np.int64(0), t_col_b, st, dv, tab, cbuf, borrow(zbuf),
                     borrow(sten), vector_pack, lit_lanes)
    keep_alive(states, derived, tables)
