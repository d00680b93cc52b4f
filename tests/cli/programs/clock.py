# A clock in the style of the historical IRIX demos (mclock): a double-buffered RGB
# window, a face and a minute hand, TIMER0 moving the hand on, and a popup menu on
# the right mouse button to change the face colour or quit.
import DEVICE
from DEVICE import *
from gl import *

prefsize(100, 100)
winopen('clock')
RGBmode()
doublebuffer()
gconfig()
qdevice(MENUBUTTON)
qdevice(TIMER0)
noise(TIMER0, 1000)            # one TIMER0 entry per 1000 ticks

menu = newpup()
addtopup(menu, 'Clock %t|red face %x1|blue face %x2|quit %x3', 0)
faces = {1: 0xFF0000FF, 2: 0xFFFF0000}
face = faces[1]
minutes = 0


def draw():
    cpack(0xFF000000)
    clear()
    cpack(face)
    circf(50, 50, 40)          # the default ortho2: integer coordinates are pixels
    pushmatrix()
    translate(50, 50, 0)
    rotate(-minutes * 60, 'z')  # 6 degrees a minute, clockwise
    cpack(0xFFFFFFFF)
    rectf(-1, 0, 1, 35)
    popmatrix()
    swapbuffers()


while 1:
    dev, val = qread()
    if dev == DEVICE.REDRAW:
        draw()
    elif dev == TIMER0:
        minutes = minutes + 15
        draw()
    elif dev == MENUBUTTON and val:
        choice = dopup(menu)
        if choice == 3:
            break
        if choice in faces:
            face = faces[choice]
            draw()
print('clock done', minutes)
