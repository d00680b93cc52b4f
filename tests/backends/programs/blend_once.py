# One RGB frame: a half-transparent square blended with BF_SA/BF_MSA over a
# cleared window (test_raster.py's hand-computed case: blue 6400 + 9550 over 255
# is 62.55, which IRIS rounds to 63 and llvmpipe's blender to 62), then swapbuffers.
from GL import *
from gl import *

prefsize(16, 16)
winopen('blend_once')
RGBmode()
doublebuffer()
gconfig()
ortho2(-0.5, 15.5, -0.5, 15.5)
cpack(0x80_32_FF_00)
clear()
blendfunction(BF_SA, BF_MSA)
c4i(200, 0, 100, 64)
rectf(2.25, 2.25, 12.25, 12.25)
swapbuffers()
