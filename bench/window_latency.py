"""Input-to-photon latency of the interactive shadows program in a window.

A thread posts pointer motion into SDL at times unrelated to the frames (every 37 ms)
while the middle button is held, the way a hand drags; each event carries the time it
was posted.  The window backend notes the frame after which the queue delivered it,
and the time that frame's successor -- the first frame drawn with the new position --
was flipped onto the screen.  Latency = flip time - post time: the wait for the next
look at SDL, plus one frame of drawing, plus the blit.

Run (SDL's dummy driver unless a display is wanted)::

    SDL_VIDEODRIVER=dummy python bench/window_latency.py [--size 640x512] [--seconds 8]
        [--mode shadows]

Prints the median and 90th percentile latency, its two parts (post to delivery: the
wait for the program's next look at its input; delivery to flip: drawing the frame,
swapbuffers and the blit), the median frame time and the load average.  The floor of
a loop that reads its input once a frame is about half a frame of waiting plus one
frame of drawing.  Numbers on the shared 2-core machine are noisy: quote medians with
the load average, compare runs made side by side.
"""

from __future__ import annotations

import argparse
import os
import sys
import threading
import time

import numpy as np

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")


def main() -> int:
    p = argparse.ArgumentParser()
    p.add_argument("--size", default="640x512")
    p.add_argument("--seconds", type=float, default=8.0)
    p.add_argument("--mode", default="shadows")
    ns = p.parse_args()
    w, h = (int(v) for v in ns.size.split("x"))

    import pygame

    from vgxsim.runner import run_program
    from vgxsim.window.backend import WindowBackend

    program = os.path.join(os.path.dirname(__file__), os.pardir, "vgxsim", "examples",
                           "shadows_interactive.py")
    backend = WindowBackend()
    started = threading.Event()

    def start(b, where):
        if not started.is_set() and b.queue.frame >= 1:
            pygame.event.post(pygame.event.Event(pygame.MOUSEBUTTONDOWN, button=2,
                                                 pos=(w // 2, h // 2)))
            started.set()

    backend.feeders.append(start)

    def hand():
        started.wait()
        time.sleep(1.0)  # let the first frames (Numba compiles) pass
        t_end = time.perf_counter() + ns.seconds
        k = 0
        while time.perf_counter() < t_end:
            k += 1
            x = w // 2 + int(40 * np.sin(k / 7.0))
            pygame.event.post(pygame.event.Event(pygame.MOUSEMOTION, pos=(x, h // 2),
                                                 rel=(0, 0), buttons=(0, 1, 0),
                                                 posted=time.perf_counter()))
            time.sleep(0.037)
        pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_ESCAPE,
                                             unicode="\x1b", mod=0, scancode=0))

    threading.Thread(target=hand, daemon=True).start()
    run_program(program, ["--mode", ns.mode], window=backend, size=(w, h), timeout=600)
    lat = np.array(backend.latencies()) * 1000
    parts = np.array(backend.latency_parts()).reshape(-1, 2) * 1000
    flips = np.array(sorted(backend.present_times.values()))
    frame_ms = np.median(np.diff(flips)) * 1000 if len(flips) > 2 else float("nan")
    backend.close()
    if not len(lat):
        print("no latency samples", file=sys.stderr)
        return 1
    print(f"{ns.size} mode {ns.mode}: {len(lat)} samples; input-to-photon latency median "
          f"{np.median(lat):.1f} ms, p90 {np.percentile(lat, 90):.1f} ms; frame time median "
          f"{frame_ms:.1f} ms ({1000 / frame_ms:.1f} frames/s)")
    print(f"  parts: post to delivery median {np.median(parts[:, 0]):.1f} ms, delivery to "
          f"flip median {np.median(parts[:, 1]):.1f} ms; load average "
          + " ".join(f"{v:.2f}" for v in os.getloadavg()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
