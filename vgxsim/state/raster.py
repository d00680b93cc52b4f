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

# Comparison codes shared by SF_*, ZF_* and AF_* (gl.h): they are bit masks of
# "less" (1), "equal" (2) and "greater" (4).
CMP_NEVER, CMP_LESS, CMP_EQUAL, CMP_LEQUAL = 0, 1, 2, 3
CMP_GREATER, CMP_NOTEQUAL, CMP_GEQUAL, CMP_ALWAYS = 4, 5, 6, 7
# Stencil operations ST_* (gl.h).
OP_KEEP, OP_ZERO, OP_REPLACE, OP_INCR, OP_DECR, OP_INVERT = 0, 1, 2, 3, 4, 5
# Blend factors BF_* (gl.h); 2 and 3 mean DC/MDC as source, SC/MSC as destination.
BF_ZERO, BF_ONE, BF_DC, BF_MDC, BF_SA, BF_MSA, BF_DA, BF_MDA, BF_MIN_SA_MDA = range(9)
LO_SRC = 3
FLAT, GOURAUD = 0, 1
CULL_NONE, CULL_BACK, CULL_FRONT = 0, 1, 2  # bit mask: both bits cull everything


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


# Column of each field in a state-table row (int64).  Kernels import these indices.
_SCALAR_FIELDS = [f.name for f in fields(RasterState) if f.name not in ("scissor", "extra")]
ROW: dict[str, int] = {name: i for i, name in enumerate(_SCALAR_FIELDS)}
for _i, _n in enumerate(("sx0", "sx1", "sy0", "sy1")):
    ROW[_n] = len(_SCALAR_FIELDS) + _i
ROW_SIZE = len(ROW)


def needs_colour(rs: RasterState) -> bool:
    """Whether primitives drawn with ``rs`` need vertex colour at all: colour is
    written (a draw buffer and a non-zero wmpack) or the alpha test reads alpha."""
    writes = (rs.draw_front or rs.draw_back) and (rs.wmpack & 0xFFFFFFFF) != 0
    return writes or rs.afunc != CMP_ALWAYS
