"""The state record: RasterState.as_row() puts every field in the column that
vgxsim.state.codes names for it (the S_* indices the kernels read)."""

import dataclasses

import numpy as np

from vgxsim.state import codes
from vgxsim.state.raster import ROW_SIZE, RasterState


def test_as_row_puts_each_field_in_its_column():
    # Give every field a distinct value and read it back through the S_* columns.
    names = [f.name for f in dataclasses.fields(RasterState)
             if f.name not in ("scissor", "extra")]
    values = {name: 1000 + 17 * i for i, name in enumerate(names)}
    rs = RasterState(**values, scissor=(3, 11, 5, 13))
    row = rs.as_row()
    assert row.dtype == np.int64 and row.shape == (ROW_SIZE,)
    for name, val in values.items():
        assert row[getattr(codes, "S_" + name.upper())] == val, name
    assert (row[codes.S_SX0], row[codes.S_SX1], row[codes.S_SY0],
            row[codes.S_SY1]) == (3, 11, 5, 13)
    # Every column holds one of the values written: no field shares a column.
    assert sorted(row.tolist()) == sorted(list(values.values()) + [3, 11, 5, 13])


def test_wide_masks_survive_the_row():
    rs = RasterState(wmpack=0xFFFFFFFF, zwritemask=0xFFFFFFFF, linestyle=0xFFFF)
    row = rs.as_row()
    assert row[codes.S_WMPACK] == 0xFFFFFFFF
    assert row[codes.S_ZWRITEMASK] == 0xFFFFFFFF


def test_kept_row_is_as_row_made_once_and_read_only():
    """RasterState.kept_row (what CommandBatch.state_index stores per flush) is the
    as_row of the snapshot, made once and kept on it, and cannot be written."""
    a = RasterState(zbuffer=True, sref=128, sfunc=3, wmpack=0xFF, scissor=(1, 60, 2, 50))
    b = dataclasses.replace(a, sref=129)
    for rs in (a, b, RasterState()):
        row = rs.kept_row()
        assert np.array_equal(row, rs.as_row())
        assert rs.kept_row() is row
        assert not row.flags.writeable
    assert a.kept_row()[codes.S_SREF] == 128 and b.kept_row()[codes.S_SREF] == 129
    assert a == dataclasses.replace(b, sref=128)  # (the memo is no field)
