# Exit-status checks for `vgxsim run`: behaviour chosen by the first argument.
import sys

import gl

mode = sys.argv[1] if len(sys.argv) > 1 else 'none'
if mode == 'exit3':
    sys.exit(3)
if mode == 'raise':
    raise RuntimeError('deliberate failure')
if mode == 'glerror':
    gl.winopen('w')
    gl.stensize(9)
if mode == 'wait':
    gl.winopen('w')
    while 1:
        gl.qread()
if mode == 'echo':
    print('argv', sys.argv[1:])
    print('stdin', sys.stdin.readline().strip())
    print('size', gl.winopen('w') and gl.getsize())
    print('name', __name__)
if mode == 'spin':
    gl.prefsize(8, 6)
    gl.winopen('w')
    gl.RGBmode()
    gl.doublebuffer()
    gl.gconfig()
    i = 0
    while 1:  # alternate green and red frames until --max-frames ends the run
        gl.cpack(0xFF0000FF if i % 2 else 0xFF00FF00)
        gl.clear()
        gl.swapbuffers()
        i += 1
if mode == 'two':
    gl.prefsize(4, 4)
    gl.winopen('one')
    gl.prefsize(2, 2)
    gl.winopen('two')
