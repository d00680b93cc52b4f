"""The per-primitive raster state: everything the fragment stage needs to know.

One ``RasterState`` is a snapshot of the IRIS GL registers that decide what happens
to a fragment (see docs/numeric_model.md section 6).  The command batch stores each
distinct snapshot once and tags every primitive with its index, so state changes
between primitives (the 1991 shadow code changes ``stencil()`` before every volume
face) never force a flush.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields

import numpy as np

from . import codes
from .codes import (  # re-exported: the codes RasterState fields take
    BF_DA,
    BF_DC,
    BF_MDA,
    BF_MDC,
    BF_MIN_SA_MDA,
    BF_MSA,
    BF_ONE,
    BF_SA,
    BF_ZERO,
    CMP_ALWAYS,
    CMP_EQUAL,
    CMP_GEQUAL,
    CMP_GREATER,
    CMP_LEQUAL,
    CMP_LESS,
    CMP_NEVER,
    CMP_NOTEQUAL,
    CULL_BACK,
    CULL_FRONT,
    CULL_NONE,
    FLAT,
    GOURAUD,
    LO_SRC,
    OP_DECR,
    OP_INCR,
    OP_INVERT,
    OP_KEEP,
    OP_REPLACE,
    OP_ZERO,
    ROW_SIZE,
)

__all__ = [
    "BF_DA", "BF_DC", "BF_MDA", "BF_MDC", "BF_MIN_SA_MDA", "BF_MSA", "BF_ONE", "BF_SA",
    "BF_ZERO", "CMP_ALWAYS", "CMP_EQUAL", "CMP_GEQUAL", "CMP_GREATER", "CMP_LEQUAL",
    "CMP_LESS", "CMP_NEVER", "CMP_NOTEQUAL", "CULL_BACK", "CULL_FRONT", "CULL_NONE", "FLAT",
    "GOURAUD", "LO_SRC", "OP_DECR", "OP_INCR", "OP_INVERT", "OP_KEEP", "OP_REPLACE",
    "OP_ZERO", "ROW", "ROW_SIZE", "RasterState", "needs_colour",
]


@dataclass(frozen=True)
class RasterState:
    """Snapshot of the fragment-stage registers (all plain ints and bools).

    Attributes mirror IRIS GL calls: ``zbuffer``, ``zfunction``, ``zwritemask``,
    ``stencil(enable, ref, func, mask, fail, pass, zpass)``, ``swritemask``,
    ``blendfunction``, ``logicop``, ``wmpack``, ``afunction``, ``shademodel``,
    ``subpixel``, ``backface``/``frontface``, ``frontbuffer``/``backbuffer``, the
    raster rectangle (viewport intersected with scrmask and the window, inclusive
    bounds) and the line/point attributes.
    """

    zbuffer: bool = False
    zfunc: int = CMP_LEQUAL
    zwritemask: int = 0xFFFFFFFF
    stencil: bool = False
    sref: int = 0
    sfunc: int = CMP_ALWAYS
    smask: int = 0xFF
    sfail: int = OP_KEEP
    spass: int = OP_KEEP  # IRIS "pass": stencil passed, z failed
    szpass: int = OP_KEEP
    swritemask: int = 0xFF
    blend_sf: int = BF_ONE
    blend_df: int = BF_ZERO
    logicop: int = LO_SRC
    wmpack: int = 0xFFFFFFFF
    afunc: int = CMP_ALWAYS
    aref: int = 0
    shademodel: int = GOURAUD
    subpixel: bool = False
    cull: int = CULL_NONE
    draw_front: bool = False
    draw_back: bool = True
    scissor: tuple[int, int, int, int] = (0, 0, 0, 0)  # x0, x1, y0, y1 inclusive
    linewidth: int = 1
    linestyle: int = 0xFFFF
    lsrepeat: int = 1
    pntsize: int = 1
    texture: int = 0  # binding id (vgxsim.state.textures); 0: off
    extra: tuple = field(default=())  # reserved for later stages (texture, fog)

    def as_row(self) -> np.ndarray:
        """Pack into the int64 row layout the kernels read (see ``ROW``)."""
        row = np.zeros(ROW_SIZE, dtype=np.int64)
        for name, idx in ROW.items():
            if name in ("sx0", "sx1", "sy0", "sy1"):
                continue
            row[idx] = int(getattr(self, name))
        row[ROW["sx0"]], row[ROW["sx1"]], row[ROW["sy0"]], row[ROW["sy1"]] = self.scissor
        return row

    def kept_row(self) -> np.ndarray:
        """:meth:`as_row`, made once per snapshot and kept on it (read-only): a batch
        takes the rows of the snapshots it draws at every flush (CommandBatch.
        state_index), and a frame draws the same few snapshots again; the values
        never change (the snapshot is frozen)."""
        row = self.__dict__.get("_row")
        if row is None:
            row = self.as_row()
            row.flags.writeable = False
            object.__setattr__(self, "_row", row)  # (frozen: not a field, a memo)
        return row


# Column of each field in a state-table row: the S_* layout of vgxsim.state.codes,
# by field name (the scissor rectangle as sx0, sx1, sy0, sy1).
_SCALAR_FIELDS = [f.name for f in fields(RasterState) if f.name not in ("scissor", "extra")]
ROW: dict[str, int] = {name: getattr(codes, "S_" + name.upper())
                       for name in _SCALAR_FIELDS + ["sx0", "sx1", "sy0", "sy1"]}
if sorted(ROW.values()) != list(range(ROW_SIZE)):  # a field added without its column
    raise ImportError("vgxsim.state.codes S_* columns do not match RasterState's fields")


def needs_colour(rs: RasterState) -> bool:
    """Whether primitives drawn with ``rs`` need vertex colour at all: colour is
    written (a draw buffer and a non-zero wmpack) or the alpha test reads alpha."""
    writes = (rs.draw_front or rs.draw_back) and (rs.wmpack & 0xFFFFFFFF) != 0
    return writes or rs.afunc != CMP_ALWAYS
