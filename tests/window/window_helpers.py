"""Synthesized SDL input for the window tests (see conftest.py)."""

from __future__ import annotations

import pygame


class Feeder:
    """Posts groups of SDL events, each one a number of frames after the last.

    ``plan`` is a list of ``(gap, events)``: ``events`` (a list of ``(type, attrs)``)
    is posted at the first look at SDL once ``gap`` frames have been drawn since the
    previous group; ``gap == "menu"`` posts while a popup menu is up, and ``events``
    may then be a callable ``events(backend) -> list`` (to aim at a drawn entry).
    """

    def __init__(self, plan):
        self.plan = list(plan)
        self.index = 0
        self.frame = 0

    def __call__(self, backend, where: str) -> None:
        if self.index >= len(self.plan):
            return
        gap, events = self.plan[self.index]
        if gap == "menu":
            if where != "menu":
                return
        elif where != "pump" or backend.queue.frame < self.frame + gap:
            return
        if callable(events):
            events = events(backend)
        for kind, attrs in events:
            pygame.event.post(pygame.event.Event(kind, **attrs))
        self.index += 1
        self.frame = backend.queue.frame


def motion(pos):
    return (pygame.MOUSEMOTION, dict(pos=pos, rel=(0, 0), buttons=(0, 0, 0)))


def press(button, pos):
    return (pygame.MOUSEBUTTONDOWN, dict(button=button, pos=pos))


def release(button, pos):
    return (pygame.MOUSEBUTTONUP, dict(button=button, pos=pos))


def key(k, text="", down=True):
    kind = pygame.KEYDOWN if down else pygame.KEYUP
    return (kind, dict(key=k, unicode=text, mod=0, scancode=0))
