"""One SDL window per IRIS GL window, and the frame sink that shows frames in it.

A frame reaches the screen as the headless sinks get it (``(H, W, 4)`` RGBA, row 0 at
the bottom): its rows are flipped into one top-row-first buffer and that buffer is
blitted once into the window surface, then the window is flipped.  The pixels are
wrapped as ``RGBX`` (alpha ignored, as the monitor ignores it), which SDL copies
without blending -- about 0.7 ms at 640x512, against 18 ms for an ``RGBA`` blit.  A
double-buffered program's frame appears whole at its ``swapbuffers`` (no tearing:
the surface is only ever written from a finished front buffer).
"""

from __future__ import annotations

import time

import numpy as np

from .sdl import pygame

__all__ = ["ScreenWindow", "ScreenSink"]

#: SDL's height of the IRIS screen, for placing windows opened with prefposition
#: (getgdesc(GD_YPMAX) + 1 on the VGX).
IRIS_SCREEN_HEIGHT = 1024


class ScreenWindow:
    """The SDL window of one IRIS GL window.

    Parameters
    ----------
    gid : int
    title : str
    size : (int, int)
    origin : (int, int) or None
        The IRIS lower-left corner when the program placed the window
        (prefposition); None lets the window manager place it.

    Attributes
    ----------
    top_down : ndarray or None
        The picture on the screen, ``(H, W, 4)`` uint8, top row first.
    shown_at : float
        ``time.perf_counter()`` after the last flip.
    """

    def __init__(self, gid: int, title: str, size: tuple[int, int],
                 origin: tuple[int, int] | None = None):
        kw = {}
        if origin is not None:
            kw["position"] = (origin[0], max(0, IRIS_SCREEN_HEIGHT - origin[1] - size[1]))
        self.gid = gid
        self.window = pygame.Window(title, size, resizable=True, **kw)
        self.top_down: np.ndarray | None = None
        self.shown_at = 0.0
        self.count = 0

    @property
    def size(self) -> tuple[int, int]:
        return tuple(self.window.size)

    def show(self, image: np.ndarray, title: str | None = None,
             keep_size: bool = False) -> float:
        """Put a bottom-up RGBA (or RGB) frame on the screen; returns the flip time.
        The window takes the frame's size unless ``keep_size`` (the user has resized
        it and the program has not yet been told)."""
        h, w = image.shape[:2]
        if (w, h) != self.size and not keep_size:
            self.window.size = (w, h)
        if title is not None and self.window.title != title:
            self.window.title = title
        self.top_down = np.ascontiguousarray(image[::-1])
        self.blit()
        return self.shown_at

    def blit(self, overlay=None) -> None:
        """Blit the current picture (then ``overlay(surface)``, e.g. a menu) and flip."""
        if self.top_down is None:
            return
        h, w = self.top_down.shape[:2]
        fmt = "RGBX" if self.top_down.shape[2] == 4 else "RGB"
        surface = self.window.get_surface()
        surface.blit(pygame.image.frombuffer(self.top_down, (w, h), fmt), (0, 0))
        if overlay is not None:
            overlay(surface)
        self.window.flip()
        self.shown_at = time.perf_counter()
        self.count += 1

    def close(self) -> None:
        self.window.destroy()


class ScreenSink:
    """The frame sink of a window run on screen: shows each frame, then hands it to
    the recording sink (``--record``), so the recording holds exactly the frames a
    headless run of the same program would make.

    Parameters
    ----------
    backend : WindowBackend
    screen : ScreenWindow
    record : object with ``write(image)``, or None
    """

    def __init__(self, backend, screen: ScreenWindow, record=None):
        self.backend = backend
        self.screen = screen
        self.record = record

    def write(self, image) -> None:
        self.backend.show(self.screen, np.asarray(image))
        if self.record is not None:
            self.record.write(image)
