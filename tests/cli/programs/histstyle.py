# A program in the style of CPython's historical IRIX `gl` demos (Demo/sgi/gl):
# module-level imports of gl, GL and DEVICE, a colour-map window, a qread loop.
# Keys: g = clear green, b = paint the bottom half blue, ESC = quit.
import sys

import DEVICE
import GL
import gl
from DEVICE import *
from gl import *

prefsize(64, 48)
win = winopen('histstyle')          # cmode, single-buffered: the IRIS defaults
qdevice(ESCKEY)
qdevice(KEYBD)

# getmatrix() round trip through loadmatrix() (zrgb.py does this): 16 flat floats
m = [2.0, 0.0, 0.0, 0.0,
     0.0, 3.0, 0.0, 0.0,
     0.0, 0.0, 4.0, 0.0,
     5.0, 6.0, 7.0, 1.0]
loadmatrix(m)
if getmatrix() != m:
    print('getmatrix mismatch:', getmatrix(), file=sys.stderr)
    sys.exit(5)
loadmatrix([1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0])

colour = GL.RED
bottom = None


def redraw():
    reshapeviewport()
    color(colour)
    clear()
    if bottom is not None:
        xsize, ysize = getsize()
        scrmask(0, xsize - 1, 0, ysize // 2 - 1)
        color(bottom)
        clear()
        reshapeviewport()


while 1:
    dev, val = qread()
    if dev == DEVICE.REDRAW:
        redraw()
    elif dev == KEYBD:
        if val == ord('g'):
            colour = GL.GREEN
        elif val == ord('b'):
            bottom = GL.BLUE
        redraw()
    elif dev == ESCKEY and val == 1:
        break

gl.winclose(win)
print('histstyle done', getgdesc(GL.GD_XPMAX))
