# A NURBS patch with a trim curve, in the style of CPython's Demo/sgi/gl/nurbs.py:
# nurbssurface with the binding's nested control points, a pwlcurve hole; 't'
# toggles the trim, ESC quits.
import GL
from DEVICE import *
from gl import *

prefsize(80, 80)
winopen('nurbs')
RGBmode()
gconfig()
qdevice(ESCKEY)
qdevice(KEYBD)

knots = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]
ctl = [[[10.0 + 20.0 * j, 10.0 + 20.0 * i, 0.0] for j in range(4)] for i in range(4)]
outer = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]]
hole = [[0.25, 0.25], [0.5, 0.75], [0.75, 0.25], [0.25, 0.25]]   # clockwise
trimmed = 1


def draw():
    cpack(0xFF000000)
    clear()
    cpack(0xFFFFFFFF)
    setnurbsproperty(GL.N_PIXEL_TOLERANCE, 10.0)
    bgnsurface()
    nurbssurface(knots, knots, ctl, 4, 4, GL.N_XYZ)
    if trimmed:
        bgntrim()
        pwlcurve(outer, GL.N_ST)
        endtrim()
        bgntrim()
        pwlcurve(hole, GL.N_ST)
        endtrim()
    endsurface()


while 1:
    dev, val = qread()
    if dev == REDRAW:
        draw()
    elif dev == KEYBD and val == ord('t'):
        trimmed = not trimmed
        draw()
    elif dev == ESCKEY:
        break
