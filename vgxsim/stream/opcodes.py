"""Opcodes of the command stream (the VGX's command FIFO, in software).

Every recordable drawing call of :mod:`vgxsim.gl` appends one opcode to the
stream's int64 ``ops`` buffer, followed by its integer payload there, and its float
payload to the float64 ``fl`` buffer.  The decoder (:mod:`vgxsim.kernels.decode`)
walks both buffers once.  Numba reads these names as global constants.

=========  ===========================  ===============================================
opcode     int payload (in ``ops``)     float payload (in ``fl``)
=========  ===========================  ===============================================
V          --                           x, y, z, w: a vertex with the current attributes
SYNC       sent_normal, lmcolor_set     r, g, b, a, nx, ny, nz: immediate-mode
                                        attributes, sent when they changed (gl side
                                        is the source of truth in immediate mode)
C          --                           r, g, b, a: colour call, colour wins (lighting
                                        off or LMC_COLOR: the vertex is coloured)
CM         --                           r, g, b, a: colour call changing the material
                                        (LMC_EMISSION .. LMC_AD: the vertex stays lit)
CSKIP      --                           r, g, b, a: colour call ignored (LMC_NULL)
CRAW       --                           r, g, b, a: a colour call recorded in a display
                                        object, rewritten to C, CM or CSKIP when the
                                        object is spliced (its meaning depends on the
                                        caller's lighting, lmcolor(3G))
N          --                           nx, ny, nz: n3f; the normal was sent last
BGN        primitive kind               --
END        --                           --
SWAP       --                           -- (swaptmesh)
STATE      state-record index           -- (the interned draw state for what follows)
T          --                           s, t: t2*, the current texture coordinate
CLEAR      index into the stream's      -- (clear, czclear, zclear, sclear: queued in
           ``clears``                   drawing order with the primitives, so a clear
                                        between two passes needs no flush of its own)
=========  ===========================  ===============================================
"""

from __future__ import annotations

from types import MappingProxyType

V, SYNC, C, CM, CSKIP, CRAW, N, BGN, END, SWAP, STATE = range(11)
#: t2*: s, t in the float payload; the vertices after it take that texture coordinate
#: (decoded by vgxsim.kernels.texture.decode_texcoords, only for streams that hold one).
T = 11
#: A clear of the raster rectangle; its planes, values and clear state are the
#: stream's ``clears[index]`` (vgxsim.stream.recorder.CommandStream).
CLEAR = 12

#: Primitive kinds carried by BGN.  PMV is the old-style pmv/pdr/pclos polygon.
POLYGON, TMESH, QSTRIP, LINE, CLOSEDLINE, POINT, PMV = range(7)
#: The primitive-table kind of a decoded CLEAR (no vertices; P_CLEAR names it).
CLEAR_KIND = 7
#: BGN kinds of one draw(3G) segment (gl/_oldstyle.py): two vertices, the current
#: graphics position and the new point, drawn as a line whose line-style pattern
#: starts where the last line drawn left it (Context.linestyle_pos, read when the
#: stream is decoded, in drawing order) -- or, DRAW_RESTART, at 0: a move(3G) under
#: resetls(TRUE) came first.  Recorded, not drawn at the call, so a move/draw
#: program costs no flush per segment.
DRAW_SEG, DRAW_RESTART = 8, 9
#: (Read-only mappings: constants, not process state.)
KIND_OF = MappingProxyType({"polygon": POLYGON, "tmesh": TMESH, "qstrip": QSTRIP,
                            "line": LINE, "closedline": CLOSEDLINE, "point": POINT,
                            "pmv": PMV})
NAME_OF = MappingProxyType({v: k for k, v in KIND_OF.items()})
#: Kinds drawn as triangles (and so merged into one geometry pass per state record).
TRIANGLE_KINDS = (POLYGON, TMESH, QSTRIP, PMV)

#: Columns of a decoded primitive row (int64).
P_KIND, P_V0, P_V1, P_STATE, P_LMCOLOR_SET, P_SWAP0, P_SWAP1 = range(7)
PRIM_COLUMNS = 7
#: A CLEAR row keeps its index into the stream's clears in the P_SWAP0 column.
P_CLEAR = P_SWAP0
