"""IRIS GL popup menus: newpup, addtopup, defpup, dopup, freepup, setpup.

The menu *model* -- :class:`PopupMenu` holding :class:`MenuItem` s with their labels,
values, callbacks, submenus and display modes -- is kept apart from its
*presentation*: ``dopup`` hands the model to a :class:`MenuPresenter`, which returns
the user's choice as a path of entry numbers or labels, and the model turns that
path into dopup's return value (:meth:`PopupMenu.choose`).  Headless, the presenter
is :class:`ScriptedMenuPresenter`: the next ``menu`` statement of the event script
(:class:`vgxsim.events.script.MenuChoice`) answers the menu, and with nothing
scripted the menu is dismissed (-1).  A window that draws menus would supply its own
presenter (``menu_state().presenter``) over the same model.

Item syntax (addtopup(3G), defpup(3G); the reading of IGL's ``src/menu.c`` where
the manual is terse).  The string is a list of entries separated by ``|``; an
entry's label is its text up to the first ``%``; directives in an entry:

* ``%t``  -- this entry is the menu's title, not a selectable entry;
* ``%F``  -- the next argument is a function called with the value of any entry
  chosen from this menu; its result is what dopup returns;
* ``%f``  -- the next argument is a function called with this entry's value (before
  the ``%F`` function, which then gets its result);
* ``%xN`` -- the entry's value is the integer N (default: its number, 1 = first);
* ``%l``  -- a separator line is drawn under this entry;
* ``%m``  -- the next argument is a menu id: this entry opens that submenu;
* ``%n``  -- the menu's ``%F`` function is not called for this entry.

Arguments for ``%F``, ``%f`` and ``%m`` are taken in the order the directives appear.
CPython's binding declared ``addtopup(long, char *, long)`` -- exactly one extra
argument, usually an unused 0 -- so extra arguments are ignored; callbacks are
Python callables here (the binding could not pass functions at all).

Choosing (dopup(3G)).  An entry's value goes through its ``%f`` function, then the
menu's ``%F`` function unless ``%n``.  A choice inside a submenu returns what the
submenu's own entry and ``%F`` function give (as IGL does); releasing on the
submenu entry itself, on a greyed entry (``setpup(..., PUP_GREY)``) or outside the
menu returns -1.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Protocol

from vgxsim import GL

from ._core import (
    GLTypeError,
    GLUsageError,
    GLValueError,
    as_int,
    describe,
    gl_function,
    topic_state,
)

__all__ = ["newpup", "addtopup", "defpup", "dopup", "freepup", "setpup"]

#: setpup(3G) display modes.
PUP_MODES = (int(GL.PUP_NONE), int(GL.PUP_GREY), int(GL.PUP_BOX), int(GL.PUP_CHECK))


# -- the model ----------------------------------------------------------------------------
@dataclass
class MenuItem:
    """One selectable entry of a popup menu.

    Attributes
    ----------
    label : str
        The text shown (the entry without its ``%`` directives).
    value : int or None
        ``%xN``; None: the entry's number.
    routine : callable or None
        ``%f`` function.
    submenu : int or None
        ``%m`` menu id.
    separator : bool
        ``%l``: a line under this entry.
    skip_menu_routine : bool
        ``%n``: the menu's ``%F`` function is not called for this entry.
    grey, box, check : bool
        setpup(3G) modes: greyed out (cannot be chosen); an empty or a checked box.
    """

    label: str
    value: int | None = None
    routine: Callable | None = None
    submenu: int | None = None
    separator: bool = False
    skip_menu_routine: bool = False
    grey: bool = False
    box: bool = False
    check: bool = False


@dataclass
class PopupMenu:
    """A popup menu: an optional title, its ``%F`` function and its entries."""

    title: str = ""
    routine: Callable | None = None
    items: list[MenuItem] = field(default_factory=list)

    def find(self, choice: int | str) -> int | None:
        """The 1-based number of the entry ``choice`` names (a number or a label)."""
        if isinstance(choice, int):
            return choice if 1 <= choice <= len(self.items) else None
        for i, item in enumerate(self.items, start=1):
            if item.label == choice:
                return i
        return None

    def choose(self, menus: dict[int, PopupMenu], path: Sequence[int | str]):
        """dopup's result for the user's choice ``path`` (see the module docstring).

        Raises
        ------
        LookupError
            If an element of ``path`` names no entry (a mistake of the script).
        """
        if not path or path[0] == 0:
            return -1
        number = self.find(path[0])
        if number is None:
            labels = ", ".join(repr(it.label) for it in self.items) or "none"
            raise LookupError(f"no entry {path[0]!r} in menu {self.title!r} (entries: "
                              f"{labels})")
        item = self.items[number - 1]
        if item.grey:
            return -1
        if item.submenu is not None:
            sub = menus.get(item.submenu)
            if len(path) == 1 or sub is None:
                return -1
            return sub.choose(menus, path[1:])
        if len(path) > 1:
            raise LookupError(f"entry {item.label!r} of menu {self.title!r} has no submenu")
        value = number if item.value is None else item.value
        if item.routine is not None:
            value = item.routine(value)
        if self.routine is not None and not item.skip_menu_routine:
            value = self.routine(value)
        return value


def parse_entries(name: str, args: tuple, text: str, extra: Sequence,
                  menus: dict[int, PopupMenu]) -> tuple[str | None, Callable | None,
                                                         list[MenuItem]]:
    """Parse an addtopup/defpup string.

    Returns
    -------
    (title or None, %F routine or None, new items)
    """
    supply = list(extra)

    def take(directive: str):
        if not supply:
            raise GLTypeError(f"{describe(name, args)}: {directive} needs an argument "
                              f"after the string")
        return supply.pop(0)

    title = routine = None
    items: list[MenuItem] = []
    for entry in text.split("|"):
        cut = entry.find("%")
        item = MenuItem(label=(entry if cut < 0 else entry[:cut]).strip())
        is_title = False
        i = cut
        while 0 <= i < len(entry):
            d = entry[i + 1:i + 2]
            j = i + 2
            if d == "t":
                is_title = True
            elif d == "F":
                routine = _callable(name, args, "%F", take("%F"))
            elif d == "f":
                item.routine = _callable(name, args, "%f", take("%f"))
            elif d == "x":
                k = j + 1 if entry[j:j + 1] == "-" else j
                while k < len(entry) and entry[k].isdigit():
                    k += 1
                if k == j or entry[j:k] == "-":
                    raise GLValueError(f"{describe(name, args)}: %x needs an integer "
                                       f"value (%x3)")
                item.value = int(entry[j:k])
                j = k
            elif d == "l":
                item.separator = True
            elif d == "m":
                sub = as_int(name, args, "%m submenu", take("%m"))
                if sub not in menus:
                    raise GLValueError(f"{describe(name, args)}: %m submenu {sub} is not "
                                       f"a menu (newpup/defpup)")
                item.submenu = sub
            elif d == "n":
                item.skip_menu_routine = True
            else:
                raise GLValueError(f"{describe(name, args)}: unknown menu directive "
                                   f"%{d} (addtopup(3G): %t %F %f %x %l %m %n)")
            i = entry.find("%", j)
        if is_title:
            title = item.label
        elif entry.strip() or cut >= 0:
            items.append(item)
    return title, routine, items


def _callable(name: str, args: tuple, what: str, f):
    if not callable(f):
        raise GLTypeError(f"{describe(name, args)}: {what} needs a function, not "
                          f"{type(f).__name__}")
    return f


# -- presentation ---------------------------------------------------------------------------
class MenuPresenter(Protocol):
    """Shows a menu and returns the user's choice as a path (see PopupMenu.choose)."""

    def present(self, pup: int, menus: dict[int, PopupMenu]) -> Sequence[int | str]:
        ...


class ScriptedMenuPresenter:
    """Headless menus: the next ``menu`` step of the session's event script chooses
    (vgxsim.events.script, "Popup menus"); otherwise the menu is dismissed."""

    def present(self, pup: int, menus: dict[int, PopupMenu]) -> Sequence[int | str]:
        from vgxsim.events.script import MenuChoice

        from ._events import event_queue

        source = event_queue().source
        step = source.peek()
        if isinstance(step, MenuChoice):
            source.pop()
            self.where = step.where
            return step.path
        return ()


@dataclass
class MenuState:
    """The session's menus (ids from 1) and the presenter dopup uses."""

    menus: dict[int, PopupMenu] = field(default_factory=dict)
    next_id: int = 1
    presenter: MenuPresenter = field(default_factory=ScriptedMenuPresenter)


def menu_state() -> MenuState:
    """The session's :class:`MenuState` (dropped by ``session.reset()``)."""
    return topic_state("menus", MenuState)


def _menu(name: str, args: tuple, pup) -> PopupMenu:
    p = as_int(name, args, "pup", pup)
    menu = menu_state().menus.get(p)
    if menu is None:
        raise GLValueError(f"{describe(name, args)}: {p} is not a menu (newpup/defpup; "
                           f"freed menus are gone)")
    return menu


def _string(name: str, args: tuple, s) -> str:
    if not isinstance(s, str):
        raise GLTypeError(f"{describe(name, args)}: the menu string must be a str, not "
                          f"{type(s).__name__}")
    return s


def _add(name: str, args: tuple, menu: PopupMenu, text: str, extra: Sequence) -> None:
    title, routine, items = parse_entries(name, args, text, extra, menu_state().menus)
    if title is not None:
        menu.title = title
    if routine is not None:
        menu.routine = routine
    menu.items.extend(items)


# -- the calls --------------------------------------------------------------------------------
@gl_function(record=False)
def newpup() -> int:
    """newpup() -> int: a new, empty popup menu's id (newpup(3G))."""
    st = menu_state()
    pup = st.next_id
    st.next_id += 1
    st.menus[pup] = PopupMenu()
    return pup


@gl_function(record=False)
def addtopup(pup: int, text: str, *extra) -> None:
    """addtopup(pup, str, arg...): append entries to menu ``pup`` (addtopup(3G)).

    ``arg`` s feed the ``%F``, ``%f`` and ``%m`` directives in order; unused ones are
    ignored (the binding's form ``addtopup(p, 'Quit', 0)`` passes one).
    """
    args = (pup, text, *extra)
    _add("addtopup", args, _menu("addtopup", args, pup), _string("addtopup", args, text),
         extra)


@gl_function(record=False)
def defpup(text: str, *extra) -> int:
    """defpup(str, arg...) -> int: newpup() and addtopup() in one (defpup(3G))."""
    args = (text, *extra)
    s = _string("defpup", args, text)
    st = menu_state()
    menu = PopupMenu()
    _add("defpup", args, menu, s, extra)  # validate before the id is taken
    pup = st.next_id
    st.next_id += 1
    st.menus[pup] = menu
    return pup


@gl_function(record=False)
def dopup(pup: int):
    """dopup(pup) -> int: show menu ``pup`` and return the value chosen, or -1 when
    the menu is dismissed (dopup(3G)).

    Headless the choice comes from the event script's next ``menu`` statement
    (module docstring); a choice naming no entry is a GLUsageError that names the
    script line.
    """
    args = (pup,)
    _menu("dopup", args, pup)
    st = menu_state()
    p = as_int("dopup", args, "pup", pup)
    path = tuple(st.presenter.present(p, st.menus))
    try:
        return st.menus[p].choose(st.menus, path)
    except LookupError as exc:
        where = getattr(st.presenter, "where", "")
        raise GLUsageError(f"{describe('dopup', args)}: {where + ': ' if where else ''}"
                           f"{exc.args[0]}") from None


@gl_function(record=False)
def freepup(pup: int) -> None:
    """freepup(pup): delete menu ``pup`` (freepup(3G)); its id is not reused."""
    args = (pup,)
    _menu("freepup", args, pup)
    del menu_state().menus[as_int("freepup", args, "pup", pup)]


@gl_function(record=False)
def setpup(pup: int, entry: int, mode: int) -> None:
    """setpup(pup, entry, mode): display mode of entry ``entry`` (1 = first, the
    title not counted) (setpup(3G)).

    PUP_GREY greys the entry out (it cannot be chosen), PUP_BOX gives it an empty
    box, PUP_CHECK a checked box, PUP_NONE clears all three (IGL's reading).
    """
    args = (pup, entry, mode)
    menu = _menu("setpup", args, pup)
    n = as_int("setpup", args, "entry", entry)
    m = as_int("setpup", args, "mode", mode)
    if not 1 <= n <= len(menu.items):
        raise GLValueError(f"{describe('setpup', args)}: menu {pup} has entries "
                           f"1..{len(menu.items)}")
    if m not in PUP_MODES:
        raise GLValueError(f"{describe('setpup', args)}: mode {m} is not PUP_NONE, "
                           f"PUP_GREY, PUP_BOX or PUP_CHECK")
    item = menu.items[n - 1]
    if m == GL.PUP_NONE:
        item.grey = item.box = item.check = False
    elif m == GL.PUP_GREY:
        item.grey = True
    elif m == GL.PUP_BOX:
        item.box, item.check = True, False
    else:
        item.box, item.check = False, True

