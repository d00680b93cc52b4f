"""The 1991 ``shadows`` program, interactive: trackball, translate, dolly, spin, menu.

Run it on screen with ``vgxsim shadows --window`` (or ``vgxsim run THIS_FILE
--window``), or headless from an events script (``vgxsim shadows --events FILE
--record DIR``): it reads the event queue exactly as an IRIS GL program did, so a
recorded session (``--record-events``) replays headless to the same frames.

README of the original: the middle mouse rotates the scene trackball style and, if
released while the mouse is moving, the scene "will continue to spin"; the left mouse
translates; left and middle together "track into and out of the scene with the
vertical mouse motion"; the right mouse "presents a pop-up menu of several display
options.  The initial mode is 'Show Objects Only'".  With an accumulation buffer an
item "Turn Soft Shadows On/Off" appears; soft shadows accumulate while the scene is
still, up to the maximum (default 64), and "intermediate results will be displayed".
ESC, the menu's Quit and closing the window (WINQUIT, WINSHUT) end the program; it then
prints the final view on stdout.

Arguments: ``[SCENE] [--mode M] [--soft-max N] [--soft] [--seed N] [--edges E]
[--signs S]``; the window size is ``vgxsim run --size`` (default 640x512).
"""

from __future__ import annotations

import argparse
import sys

from vgxsim.DEVICE import *
from vgxsim.gl import *
from vgxsim.shadow import api
from vgxsim.shadow.interactive import InteractiveShadows, view_for
from vgxsim.shadow.program import EDGES, MODES, SIGNS, jittered_lights, random_offsets

MENU_MODES = {1: "objects", 2: "volumes", 3: "mask", 4: "shadows"}
SOFT_ITEM, QUIT_ITEM = 5, 6


def parse(argv: list[str]) -> argparse.Namespace:
    p = argparse.ArgumentParser(prog="shadows", description=__doc__.splitlines()[0])
    p.add_argument("scene", nargs="?")
    p.add_argument("--mode", choices=MODES, default="objects")
    p.add_argument("--soft", action="store_true", help="start with soft shadows on")
    p.add_argument("--soft-max", type=int, default=api.SOFT_MAX_DEFAULT)
    p.add_argument("--seed", type=int, default=1991)
    p.add_argument("--edges", choices=EDGES, default="silhouette")
    p.add_argument("--signs", choices=SIGNS, default="screen")
    return p.parse_args(argv)


def make_menu(has_acbuf: bool) -> int:
    menu = newpup()
    addtopup(menu, "shadows %t|Show Objects Only %x1|Show Volumes %x2|Show Mask %x3|"
                   "Show Shadows %x4%l", 0)
    if has_acbuf:  # README: the item appears only on workstations with an acbuf
        addtopup(menu, "Turn Soft Shadows On/Off %x5", 0)
    addtopup(menu, "Quit %x6", 0)
    return menu


def mark_menu(menu: int, mode: str, soft: bool, has_acbuf: bool) -> None:
    for item, name in MENU_MODES.items():
        setpup(menu, item, PUP_CHECK if name == mode else PUP_BOX)
    if has_acbuf:
        setpup(menu, SOFT_ITEM, PUP_CHECK if soft else PUP_BOX)


def main(argv: list[str]) -> int:
    opts = parse(argv)
    scene = api.load_scene(opts.scene)
    view = view_for(scene)
    prog = InteractiveShadows(scene, mode=opts.mode, edges=opts.edges, signs=opts.signs,
                              view=view)
    gid = winopen("shadows")
    has_acbuf = getgdesc(GD_BITS_ACBUF) > 0
    prog.setup(accumulate=has_acbuf)
    for dev in (LEFTMOUSE, MIDDLEMOUSE, MENUBUTTON, ESCKEY, WINQUIT, WINSHUT):
        qdevice(dev)
    menu = make_menu(has_acbuf)
    soft = opts.soft and has_acbuf
    offsets = random_offsets(scene, max(1, opts.soft_max), opts.seed)
    soft_done = 0          # jittered frames accumulated for the current view
    jittered = False       # the lights are lmdef'ed at a jittered position
    redraw = True
    while True:
        left, middle = getbutton(LEFTMOUSE), getbutton(MIDDLEMOUSE)
        still = not (left or middle) and view.spin is None
        idle = still and not redraw and (not soft or soft_done >= opts.soft_max)
        while idle or qtest():  # block in qread only when there is nothing to draw
            dev, val = qread()
            idle = False
            if dev in (ESCKEY, WINQUIT, WINSHUT) and (val or dev != ESCKEY):
                return finish(prog, view, gid)
            if dev == REDRAW:
                redraw = True
            elif dev in (LEFTMOUSE, MIDDLEMOUSE):
                if val:
                    view.press(getvaluator(MOUSEX), getvaluator(MOUSEY))
                else:
                    view.release(dev == MIDDLEMOUSE, getbutton(LEFTMOUSE),
                                 getbutton(MIDDLEMOUSE))
                redraw = True
            elif dev == MENUBUTTON and val:
                mark_menu(menu, prog.mode, soft, has_acbuf)
                choice = dopup(menu)
                if choice in MENU_MODES:
                    prog.mode = MENU_MODES[choice]
                elif choice == SOFT_ITEM:
                    soft = not soft
                elif choice == QUIT_ITEM:
                    return finish(prog, view, gid)
                redraw = redraw or choice != -1
        left, middle = getbutton(LEFTMOUSE), getbutton(MIDDLEMOUSE)
        moved = view.drag(getvaluator(MOUSEX), getvaluator(MOUSEY), bool(left), bool(middle),
                          getorigin(), getsize())
        moved = view.step_spin() or moved
        if moved or redraw:
            soft_done = 0
        redraw = False
        if soft and not moved and soft_done < opts.soft_max:
            # one more jittered image a frame, the running average shown each time
            prog.scene = jittered_lights(scene, offsets[soft_done])
            prog.define_lights()
            prog.viewing()
            prog.DrawFrame()
            acbuf(AC_CLEAR_ACCUMULATE if soft_done == 0 else AC_ACCUMULATE, 1.0)
            soft_done += 1
            acbuf(AC_RETURN, 1.0 / soft_done)
            prog.scene = scene
            jittered = True
        else:
            if jittered:  # put the lights back
                prog.define_lights()
                jittered = False
            prog.viewing()
            prog.DrawFrame()
        swapbuffers()


def finish(prog, view, gid) -> int:
    prog.teardown()
    winclose(gid)
    q = ", ".join(f"{c:.9f}" for c in view.quat)
    print(f"shadows: view rotation quaternion ({q}) shift ({view.shift[0]:.6f}, "
          f"{view.shift[1]:.6f}) dolly {view.dolly:.6f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
