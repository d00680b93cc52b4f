# Font Manager text in the style of the IRIX demos: import fm, find and scale a
# face, set it and print with fm.prstr.  ESC quits.
import fm
from DEVICE import *
from gl import *

prefsize(64, 40)
winopen('fmtext')
RGBmode()
gconfig()
qdevice(ESCKEY)

fm.init()
print('faces', ' '.join(fm.enumerate()))
fh = fm.findfont('Times-Roman').scalefont(26)
print('width', fh.getstrwidth('Ab'), 'info', fh.getfontinfo())


def draw():
    cpack(0xFF000000)
    clear()
    cpack(0xFFFFFFFF)
    fh.setfont()
    cmov2i(4, 10)
    fm.prstr('Ab')


while 1:
    dev, val = qread()
    if dev == REDRAW:
        draw()
    elif dev == ESCKEY:
        break
