"""Popup menus drawn in the window: the :class:`~vgxsim.gl._menus.MenuPresenter` of a
window session.

``dopup`` hands the menu model to :meth:`WindowMenuPresenter.present`, which draws the
menu under the pointer over the window's picture -- in the look of the PUPDRAW planes:
a title bar, light grey entries in black, the entry under the pointer inverted, greyed
entries in grey, PUP_BOX/PUP_CHECK boxes, ``%l`` separator lines, ``%m`` submenus
opening to the right -- and follows the pointer until the button is released (dopup(3G):
the choice is made by releasing the menu button; a menu opened with no button held
waits for a click).  It returns the path of entry numbers under the pointer, ``()``
outside every entry (dismissed: -1), and the model turns the path into dopup's value,
as it does for a scripted ``menu`` step.  The menu is an overlay: it is drawn on the
screen only, never into the window's colour planes or the recorded frames, so
``--record`` and a headless replay see the same frames.

Input the menu consumed (the release, the pointer's last position) is handed on to the
IRIS queue after it closes, so ``getbutton`` and ``MOUSEX/MOUSEY`` read as on the
workstation; the choice is written to ``--record-events`` as a ``menu`` statement.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from .sdl import pygame

__all__ = ["WindowMenuPresenter", "MenuPanel"]

ROW = 16
PAD = 8
BACKGROUND = (200, 200, 200)
TITLE_BACKGROUND = (90, 90, 90)
TITLE_TEXT = (255, 255, 255)
TEXT = (0, 0, 0)
GREY_TEXT = (130, 130, 130)
HIGHLIGHT = (40, 40, 40)
HIGHLIGHT_TEXT = (255, 255, 255)
BORDER = (0, 0, 0)


@dataclass
class MenuPanel:
    """One menu level on the screen (window pixels, y down).

    Attributes
    ----------
    menu : PopupMenu
    x, y : int
        Top-left corner.
    width : int
    title_rows : int
        1 with a ``%t`` title, else 0.
    """

    menu: object
    x: int
    y: int
    width: int
    title_rows: int

    @property
    def height(self) -> int:
        return ROW * (self.title_rows + len(self.menu.items))

    def entry_rect(self, number: int) -> pygame.Rect:
        """Screen rectangle of entry ``number`` (1 = first)."""
        return pygame.Rect(self.x, self.y + ROW * (self.title_rows + number - 1),
                           self.width, ROW)

    def entry_at(self, pos: tuple[int, int]) -> int | None:
        for n in range(1, len(self.menu.items) + 1):
            if self.entry_rect(n).collidepoint(pos):
                return n
        return None


class WindowMenuPresenter:
    """Shows menus in the window under the pointer (see the module docstring).

    Parameters
    ----------
    backend : WindowBackend
    """

    def __init__(self, backend):
        self.backend = backend
        self._font = None
        self.panels: list[MenuPanel] = []  # the menu levels now shown (for tests)

    @property
    def font(self):
        if self._font is None:
            pygame.font.init()
            self._font = pygame.font.Font(None, 18)
        return self._font

    def _panel(self, menu, x: int, y: int, bounds: tuple[int, int]) -> MenuPanel:
        labels = [it.label for it in menu.items] + ([menu.title] if menu.title else [])
        width = max([self.font.size(t)[0] for t in labels] + [40]) + 2 * PAD + ROW
        panel = MenuPanel(menu, x, y, width, 1 if menu.title else 0)
        panel.x = max(0, min(x, bounds[0] - panel.width))
        panel.y = max(0, min(y, bounds[1] - panel.height))
        return panel

    def _draw(self, surface, pointer) -> None:
        for panel in self.panels:
            rect = pygame.Rect(panel.x, panel.y, panel.width, panel.height)
            pygame.draw.rect(surface, BACKGROUND, rect)
            if panel.title_rows:
                title = pygame.Rect(panel.x, panel.y, panel.width, ROW)
                pygame.draw.rect(surface, TITLE_BACKGROUND, title)
                text = self.font.render(panel.menu.title, True, TITLE_TEXT)
                surface.blit(text, text.get_rect(center=title.center))
            for n, item in enumerate(panel.menu.items, start=1):
                r = panel.entry_rect(n)
                lit = r.collidepoint(pointer) and not item.grey
                if lit:
                    pygame.draw.rect(surface, HIGHLIGHT, r)
                colour = HIGHLIGHT_TEXT if lit else GREY_TEXT if item.grey else TEXT
                if item.box or item.check:
                    box = pygame.Rect(r.x + 4, r.y + 4, ROW - 8, ROW - 8)
                    pygame.draw.rect(surface, colour, box, 0 if item.check else 1)
                surface.blit(self.font.render(item.label, True, colour),
                             (r.x + ROW + 2, r.y + 2))
                if item.submenu is not None:
                    pygame.draw.polygon(surface, colour, [(r.right - 12, r.y + 5),
                                                          (r.right - 12, r.bottom - 5),
                                                          (r.right - 5, r.centery)])
                if item.separator:
                    pygame.draw.line(surface, BORDER, (r.x, r.bottom - 1),
                                     (r.right - 1, r.bottom - 1))
            pygame.draw.rect(surface, BORDER, rect, 1)

    def _path(self, menus, pointer) -> tuple[int, ...]:
        """Entry numbers from the top menu down to the level under the pointer; opens
        the submenu of a hovered ``%m`` entry and closes deeper levels."""
        for depth in range(len(self.panels) - 1, -1, -1):
            n = self.panels[depth].entry_at(pointer)
            if n is None:
                continue
            del self.panels[depth + 1:]
            path = self._levels[:depth] + [n]
            self._levels = path
            item = self.panels[depth].menu.items[n - 1]
            if item.submenu is not None and item.submenu in menus:
                r = self.panels[depth].entry_rect(n)
                self.panels.append(self._panel(menus[item.submenu], r.right - 4, r.y,
                                               self._bounds))
            return tuple(path)
        return ()

    def present(self, pup: int, menus: dict) -> Sequence[int]:
        """Show menu ``pup`` until the user chooses; return the chosen path."""
        backend = self.backend
        backend.pump()  # input that came before the menu goes to the queue first
        screen = backend.pointer_screen()
        if screen is None:
            return ()
        held = backend.mouse_held()
        self._bounds = screen.size
        pointer = backend.pointer_position(screen)
        self.panels = [self._panel(menus[pup], pointer[0] - 10, pointer[1] - ROW // 2,
                                   self._bounds)]
        self._levels: list[int] = []
        path = self._path(menus, pointer)
        released = []
        armed = not held  # no button held: the next press arms, its release chooses
        pressed_now = False
        while True:
            screen.blit(lambda s, at=pointer: self._draw(s, at))
            done = False
            for ev in backend.menu_events():
                if ev.type == pygame.MOUSEMOTION and backend.screen_of(ev) is screen:
                    pointer = ev.pos
                elif ev.type == pygame.MOUSEBUTTONDOWN and ev.button in (1, 2, 3):
                    pressed_now = True
                    if backend.screen_of(ev) is screen:
                        pointer = ev.pos
                elif ev.type == pygame.MOUSEBUTTONUP and ev.button in (1, 2, 3):
                    if backend.screen_of(ev) is screen:
                        pointer = ev.pos
                    released.append(ev)
                    if not armed or pressed_now:
                        done = True
                elif ev.type == pygame.KEYDOWN and ev.key == pygame.K_ESCAPE:
                    pointer, done = (-1, -1), True
                elif ev.type == pygame.WINDOWCLOSE:
                    backend.repost(ev)  # the queue sees it after the menu
                    pointer, done = (-1, -1), True
                if done:
                    break
                path = self._path(menus, pointer)
            if done:
                path = self._path(menus, pointer)
                break
        self.panels = []
        screen.blit()
        backend.menu_closed(screen, pointer, released, path)
        return path
