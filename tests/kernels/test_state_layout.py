"""The kernels read state rows by column constants (kernels/fragment.py S_*); they
must name exactly the columns RasterState.as_row() writes (vgxsim/state/raster.py)."""

import dataclasses

import numpy as np

from vgxsim.kernels import fragment
from vgxsim.state.raster import ROW, ROW_SIZE, RasterState


def _kernel_columns():
    return {name[2:].lower(): getattr(fragment, name) for name in dir(fragment)
            if name.startswith("S_") and isinstance(getattr(fragment, name), int)}


def test_every_kernel_column_matches_row():
    cols = _kernel_columns()
    assert cols, "no S_* constants found"
    for name, idx in cols.items():
        assert name in ROW, f"S_{name.upper()} names no RasterState field"
        assert ROW[name] == idx, f"S_{name.upper()} = {idx}, ROW[{name!r}] = {ROW[name]}"


def test_every_row_column_has_a_kernel_constant():
    cols = _kernel_columns()
    assert set(cols) == set(ROW)
    assert sorted(cols.values()) == list(range(ROW_SIZE))
    assert len(set(ROW.values())) == ROW_SIZE


def test_as_row_puts_each_field_in_its_kernel_column():
    # Give every field a distinct value and read it back through the S_* columns.
    names = [f.name for f in dataclasses.fields(RasterState)
             if f.name not in ("scissor", "extra")]
    values = {name: 1000 + 17 * i for i, name in enumerate(names)}
    rs = RasterState(**values, scissor=(3, 11, 5, 13))
    row = rs.as_row()
    assert row.dtype == np.int64 and row.shape == (ROW_SIZE,)
    for name, val in values.items():
        assert row[getattr(fragment, "S_" + name.upper())] == val, name
    assert (row[fragment.S_SX0], row[fragment.S_SX1], row[fragment.S_SY0],
            row[fragment.S_SY1]) == (3, 11, 5, 13)


def test_wide_masks_survive_the_row():
    rs = RasterState(wmpack=0xFFFFFFFF, zwritemask=0xFFFFFFFF, linestyle=0xFFFF)
    row = rs.as_row()
    assert row[fragment.S_WMPACK] == 0xFFFFFFFF
    assert row[fragment.S_ZWRITEMASK] == 0xFFFFFFFF
