# Picking in the style of the IRIS GL examples: three named squares; a left click
# picks at the cursor and the square hit turns yellow.  ESC quits.
from DEVICE import *
from gl import *

prefsize(100, 100)
winopen('picking')
RGBmode()
gconfig()
qdevice(LEFTMOUSE)
qdevice(ESCKEY)

squares = {1: (10, 10, 40, 40), 2: (60, 60, 90, 90), 3: (60, 10, 90, 40)}
chosen = 0


def shapes():
    for name, (x1, y1, x2, y2) in squares.items():
        loadname(name)
        if name == chosen:
            cpack(0xFF00FFFF)
        else:
            cpack(0xFF808080)
        rectf(x1, y1, x2, y2)


def draw():
    cpack(0xFF000000)
    clear()
    initnames()
    shapes()


while 1:
    dev, val = qread()
    if dev == REDRAW:
        draw()
    elif dev == LEFTMOUSE and val:
        pick(20)
        ortho2(-0.5, 99.5, -0.5, 99.5)
        initnames()
        pushname(0)
        shapes()
        hits = endpick()
        print('hits', hits)
        if hits:
            chosen = hits[-1]          # the name in the last hit record
        else:
            chosen = 0
        draw()
    elif dev == ESCKEY:
        break
