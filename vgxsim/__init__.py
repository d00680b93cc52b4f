"""vgxsim: a software emulation of the SGI IRIS GL / Power Series VGX pipeline.

The IRIS GL namespace lives in :mod:`vgxsim.gl` (functions and constants),
:mod:`vgxsim.GL` (gl.h constants) and :mod:`vgxsim.DEVICE` (device numbers).
The numeric model every rasterizer follows is written in docs/numeric_model.md.
"""

__version__ = "0.1.0"
