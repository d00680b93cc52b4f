# Programs that never end on their own, for `vgxsim run --timeout/--max-frames` and
# signals.  The first argument chooses, the second is the window size (default 16x12);
# each frame's number is printed once it is shown.
import sys

import gl

mode = sys.argv[1] if len(sys.argv) > 1 else 'swap'
w, h = map(int, sys.argv[2].split('x')) if len(sys.argv) > 2 else (16, 12)
gl.prefsize(w, h)
gl.winopen('forever')
if mode == 'swap':  # double-buffered: one frame per swapbuffers, a new colour each
    gl.RGBmode()
    gl.doublebuffer()
    gl.gconfig()
    i = 0
    while 1:
        gl.cpack(0xFF000000 | (i * 0x010203 & 0xFFFFFF))
        gl.clear()
        gl.swapbuffers()
        print('frame', i, flush=True)
        i += 1
if mode == 'noswap':  # single-buffered, never swaps, flushes or reads the queue
    print('drawing', flush=True)
    i = 0
    while 1:
        gl.color(1 + i % 7)
        gl.clear()
        i += 1
if mode == 'busy':  # no IRIS GL call at all after winopen
    print('spinning', flush=True)
    try:
        while 1:
            pass
    except Exception:  # cannot catch the end of the run
        print('caught', flush=True)
