# Overlay planes in the style of the IRIS GL examples: a scene drawn once in the
# normal planes, and a marker in the overlay planes that follows left clicks; the
# scene is never redrawn, the overlay is cleared to transparent and drawn anew.
# ESC erases the marker and quits.
from DEVICE import *
from gl import *

prefsize(100, 100)
winopen('overlay')
RGBmode()
overlay(2)
gconfig()
qdevice(LEFTMOUSE)
qdevice(ESCKEY)
print('overlay bits', getgdesc(GD_BITS_OVER_SNG_CMODE))

drawmode(OVERDRAW)
print('overlay planes', getplanes())
mapcolor(1, 255, 255, 0)       # marker: yellow
mapcolor(2, 0, 255, 255)       # its frame: cyan
drawmode(NORMALDRAW)
ox, oy = getorigin()


def scene():
    cpack(0xFF400000)          # dark blue background
    clear()
    cpack(0xFF0000FF)          # a red square
    rectf(20, 20, 80, 80)
    gflush()


def overlay_clear():
    drawmode(OVERDRAW)
    color(0)                   # index 0 is transparent: the scene shows
    clear()
    drawmode(NORMALDRAW)


def marker(x, y):
    overlay_clear()
    drawmode(OVERDRAW)
    color(2)
    recti(x - 5, y - 5, x + 5, y + 5)
    color(1)
    rectfi(x - 2, y - 2, x + 3, y + 3)
    drawmode(NORMALDRAW)
    gflush()


while 1:
    dev, val = qread()
    if dev == REDRAW:
        scene()
    elif dev == LEFTMOUSE and val:
        marker(getvaluator(MOUSEX) - ox, getvaluator(MOUSEY) - oy)
    elif dev == ESCKEY:
        overlay_clear()
        gflush()
        break
print('overlay done', getdrawmode() == NORMALDRAW)
