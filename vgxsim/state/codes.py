"""Every code the pipeline interprets, and the state-record layout, in one place.

The IRIS GL tokens (:mod:`vgxsim.GL`), the state records
(:mod:`vgxsim.state.raster`, :mod:`vgxsim.state.derive`), the Numba kernels
(``vgxsim.kernels``) and the naive reference (:mod:`vgxsim.reference.naive`) all
read their numbers from here, so no module holds a hand-numbered second copy.

Plain ``int`` constants only, and no imports: Numba folds module-level ints into
compiled code as constants, and every layer may import this module without pulling
anything above the state layer in.  Values of the gl.h families are gl.h's (CPython
``Lib/plat-irix5/GL.py``, see ``shared/reference/irisgl_reference.md``).
"""

# --------------------------------------------------------------- gl.h families

# Comparison functions shared by zfunction (ZF_*), stencil (SF_*) and afunction
# (AF_*): bit masks of "less" (1), "equal" (2), "greater" (4)
# (docs/numeric_model.md section 6).
CMP_NEVER, CMP_LESS, CMP_EQUAL, CMP_LEQUAL = 0, 1, 2, 3
CMP_GREATER, CMP_NOTEQUAL, CMP_GEQUAL, CMP_ALWAYS = 4, 5, 6, 7
CMP_LESS_BIT, CMP_EQUAL_BIT, CMP_GREATER_BIT = 1, 2, 4

# Stencil operations, stencil(3G) fail / pass / zpass (ST_*).
OP_KEEP, OP_ZERO, OP_REPLACE, OP_INCR, OP_DECR, OP_INVERT = 0, 1, 2, 3, 4, 5

# blendfunction(3G) factors (BF_*) of the VGX; 2 and 3 mean DC/MDC as a source
# factor and SC/MSC as a destination factor.
BF_ZERO, BF_ONE, BF_DC, BF_MDC, BF_SA, BF_MSA, BF_DA, BF_MDA, BF_MIN_SA_MDA = range(9)
BF_SC, BF_MSC = BF_DC, BF_MDC

# logicop(3G) (LO_*): 4-bit truth tables; LO_SRC writes the source (no logic op).
LO_ZERO, LO_AND, LO_ANDR, LO_SRC, LO_ANDI, LO_DST, LO_XOR, LO_OR = range(8)
LO_NOR, LO_XNOR, LO_NDST, LO_ORR, LO_NSRC, LO_ORI, LO_NAND, LO_ONE = range(8, 16)

# shademodel(3G).
FLAT, GOURAUD = 0, 1

# acbuf(3G) operations (AC_*).
AC_CLEAR, AC_ACCUMULATE, AC_CLEAR_ACCUMULATE, AC_RETURN, AC_MULT, AC_ADD = range(6)

# ------------------------------------------------------------- pipeline codes

# Culling: a bit mask (backface(3G) culls clockwise, frontface(3G) counter-clockwise
# polygons in window coordinates; both bits cull everything).
CULL_NONE, CULL_BACK, CULL_FRONT = 0, 1, 2

# Planes a clear writes (bit mask).
CLEAR_COLOUR, CLEAR_Z, CLEAR_STENCIL = 1, 2, 4

# Primitive kinds of a command batch.
KIND_TRIANGLE, KIND_FRAGMENTS, KIND_CLEAR = 0, 1, 2

# ------------------------------------------------------- the state record (row)

# Column of each RasterState field in a state-table row (int64); the scissor
# rectangle (inclusive bounds) takes the last four columns.
S_ZBUFFER, S_ZFUNC, S_ZWRITEMASK, S_STENCIL = 0, 1, 2, 3
S_SREF, S_SFUNC, S_SMASK, S_SFAIL, S_SPASS, S_SZPASS, S_SWRITEMASK = 4, 5, 6, 7, 8, 9, 10
S_BLEND_SF, S_BLEND_DF, S_LOGICOP, S_WMPACK, S_AFUNC, S_AREF = 11, 12, 13, 14, 15, 16
S_SHADEMODEL, S_SUBPIXEL, S_CULL, S_DRAW_FRONT, S_DRAW_BACK = 17, 18, 19, 20, 21
S_LINEWIDTH, S_LINESTYLE, S_LSREPEAT, S_PNTSIZE = 22, 23, 24, 25
S_SX0, S_SX1, S_SY0, S_SY1 = 26, 27, 28, 29
# The bound texture (vgxsim.state.textures binding id; 0: texturing off).  In a
# batch's state table it is rewritten to 1 + the row of the batch's texture table.
S_TEXTURE = 30
ROW_SIZE = 31
Z24_MASK = 0xFFFFFF  # the 24 z bitplanes a zwritemask covers (zwritemask(3G))

# ------------------------------------------- the derived record (per state, per flush)

# Columns computed by vgxsim.state.derive.derive_states.
D_MODE, D_COLOUR, D_ZTEST, D_ZWRITE, D_STENCIL, D_BLEND, D_ZMASK = 0, 1, 2, 3, 4, 5, 6
D_SWM, D_RGBA = 7, 8  # stencil write mask limited to the planes; colour needed at all
D_DZPASS, D_DZFAIL, D_SMAX = 9, 10, 11  # arithmetic stencil form (MODE_ZSTENCIL_ADD)
D_CBLEND = 12  # MODE_COLOUR blend kind (CBLEND_*)
# Whether a fragment failing the z test changes nothing at all (no stencil op on z
# fail, or no stencil): a triangle wholly behind a tile's depths can skip the tile.
D_ZFAIL_NOOP = 13
D_SIZE = 14

# Fragment modes: which span loop runs a triangle (kernels/render.py).
MODE_GENERAL = 0
MODE_ZSTENCIL = 1  # shadow-volume pass: z test, stencil update, no colour, no z write
MODE_ZONLY = 2  # depth-only pass: z test and full z write, no colour, no stencil
# Shadow-volume pass whose stencil ops are KEEP/INCR/DECR with an always-passing
# stencil test and a full write mask (Heidmann's case): the new value is
# clamp(s + delta, 0, smax), branch-free and vectorizable, instead of a table look-up.
MODE_ZSTENCIL_ADD = 3
# Colour pass with no stencil writes (stencil off, or a test whose ops change
# nothing), alpha test off, no logicop, one draw buffer: the lit pass of Heidmann's
# algorithm (stencil EQUAL, blend ONE+ONE) and ordinary shaded drawing.
MODE_COLOUR = 4

# MODE_COLOUR blend kinds: replace (ONE, ZERO), add (ONE, ONE), alpha blend (SA, MSA),
# any other factors.
CBLEND_REPLACE, CBLEND_ADD, CBLEND_SA_MSA, CBLEND_GENERAL = 0, 1, 2, 3

# ------------------------------------------------------------- texture table

# Columns of a batch's texture table (int64, one row per texture binding used):
# texel offset into the flat texel array, width, height, components, filters
# (TEXF_*), wraps (TEXW_*), environment (TEV_*), mipmap levels (1: level 0 only;
# the levels follow level 0 in the texel array).  docs/numeric_model.md s. 14.
(X_OFFSET, X_WIDTH, X_HEIGHT, X_NC, X_MINFILTER, X_MAGFILTER, X_WRAP_S, X_WRAP_T,
 X_ENV, X_LEVELS) = range(10)
X_SIZE = 10
# Filters; the MIPMAP ones (minification only) are TEXF_MIPMAP_POINT and up:
# OpenGL's NEAREST_MIPMAP_NEAREST, NEAREST_MIPMAP_LINEAR, LINEAR_MIPMAP_NEAREST,
# LINEAR_MIPMAP_LINEAR (MSDN "Translating texdef").
TEXF_POINT, TEXF_BILINEAR = 0, 1
TEXF_MIPMAP_POINT, TEXF_MIPMAP_LINEAR, TEXF_MIPMAP_BILINEAR, TEXF_MIPMAP_TRILINEAR = 2, 3, 4, 5
TEXW_REPEAT, TEXW_CLAMP = 0, 1
TEV_MODULATE, TEV_DECAL, TEV_BLEND = 0, 1, 2

# ------------------------------------------------------------- work counters

# Columns of the per-flush work counters (CommandBatch.counters).
WORK_FRAGMENTS = 0  # fragments run through a z or stencil test (or written untested)
WORK_TILES_SKIPPED = 1  # (triangle, tile) pairs decided by the tile's depth bounds
WORK_BLOCKS_COVERED = 2  # tile rows of a triangle run without edge tests
WORK_STENCIL_WRITES = 3  # fragments whose stencil value the pass may change
WORK_TILES_SCANNED = 4  # tiles whose depth bounds were found by reading the z plane
WORK_BLOCKS_Z_PASSED = 5  # of those covered, tile rows run without z tests (z proven to pass)
# Stencil bounds (kernels/tiles.py, CommandBatch.stencil_bounds): tiles whose stencil
# bounds were found by reading the stencil plane; (triangle, tile) pairs of a
# stencil-testing colour pass skipped because the test fails for every stored value,
# and run without the per-fragment stencil test because it passes for every one.
WORK_STENCIL_SCANNED = 6
WORK_STENCIL_SKIPPED = 7
WORK_STENCIL_PASSED = 8
WORK_SIZE = 9
