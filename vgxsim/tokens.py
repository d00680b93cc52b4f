"""Named numeric constants for the IRIS GL namespaces (:mod:`vgxsim.GL`, :mod:`vgxsim.DEVICE`).

IRIS GL programs pass bare numbers (``stencil(TRUE, 0, SF_EQUAL, ...)``), so every
constant here *is* a number: :class:`Token` subclasses :class:`int` and
:class:`FloatToken` subclasses :class:`float` (for the few ``gl.h`` constants that are
float literals, e.g. ``LMNULL 0.0``).  Each one also remembers the name it was defined
under, so ``repr(GL.SF_EQUAL) == 'SF_EQUAL'`` (and ``GL.SF_EQUAL.name``): state dumps,
containers and ``f"{tok!r}"`` error messages read like the C source.  ``str()`` and plain
``format()`` give the *number* (``str(GL.SF_EQUAL) == '2'``), exactly as
:class:`enum.IntEnum` does since Python 3.11, because Numba emits integer globals into
LLVM IR through ``str()``.  Arithmetic drops the name (``GL.SF_EQUAL + 1`` is the plain
int ``3``).

Where ``gl.h`` gives two names one value (``BF_DC`` and ``BF_SC`` are both 2), each name
gets its own token carrying its own name; the two compare and hash equal.

Helpers:

* :func:`define` -- create a token and store it in a namespace dict.
* :func:`lookup` -- the name of the token with a given value inside a prefix family,
  e.g. ``lookup(GL, "SF_", 2) == "SF_EQUAL"`` (for error messages).
* :func:`family` -- all tokens of a prefix family, in definition order.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import ModuleType
from typing import Any

__all__ = ["Token", "FloatToken", "define", "lookup", "family", "is_token"]


def _check_name(name: object) -> str:
    if not isinstance(name, str) or not name.isidentifier():
        raise TypeError(f"token name must be an identifier string, got {name!r}")
    return name


class Token(int):
    """An ``int`` that carries the IRIS GL name it was defined under.

    Behaves exactly like an int for arithmetic, comparison, hashing, indexing, pickling
    and numpy/numba use (as an argument or as a global inside ``@njit`` code); only
    ``repr`` and ``.name`` show the name.  ``str``/``format``/``"%d"``/``int`` give the
    number.
    """

    def __new__(cls, value: int, name: str) -> Token:
        _check_name(name)
        ivalue = int(value)
        if ivalue != value:
            raise ValueError(f"Token {name} needs an integral value, got {value!r}")
        self = super().__new__(cls, ivalue)
        object.__setattr__(self, "_name", name)
        return self

    @property
    def name(self) -> str:
        """The ``gl.h`` / ``device.h`` name of this constant."""
        return self._name

    @property
    def value(self) -> int:
        """The plain ``int`` value."""
        return int(self)

    def __repr__(self) -> str:
        return self._name

    # str() stays the decimal number, as for enum.IntEnum since Python 3.11: Numba (via
    # llvmlite) writes an integer global into LLVM IR with str(value), so a str() of
    # "SF_EQUAL" breaks every @njit kernel that reads GL.SF_EQUAL as a global.  It also
    # keeps f"{tok}", "%s" % tok and text serialisation numeric.  Use repr() / {tok!r}
    # (or lookup()) for the name.
    __str__ = int.__repr__

    # Inherited anyway (no __eq__ override); spelled out so the contract
    # hash(tok) == hash(int(tok)) is visible.
    __hash__ = int.__hash__

    def __reduce__(self):
        return (type(self), (int(self), self._name))

    def __copy__(self) -> Token:
        return self

    def __deepcopy__(self, memo: dict) -> Token:
        return self

    def __setattr__(self, key: str, value: Any) -> None:
        raise AttributeError(f"{type(self).__name__} {self._name} is read-only")

    def __delattr__(self, key: str) -> None:
        raise AttributeError(f"{type(self).__name__} {self._name} is read-only")


class FloatToken(float):
    """A ``float`` that carries its ``gl.h`` name (``LMNULL``, ``N_FILL``, ...)."""

    def __new__(cls, value: float, name: str) -> FloatToken:
        _check_name(name)
        self = super().__new__(cls, value)
        object.__setattr__(self, "_name", name)
        return self

    @property
    def name(self) -> str:
        """The ``gl.h`` name of this constant."""
        return self._name

    @property
    def value(self) -> float:
        """The plain ``float`` value."""
        return float(self)

    def __repr__(self) -> str:
        return self._name

    __str__ = float.__repr__  # numeric, like Token.__str__

    __hash__ = float.__hash__

    def __reduce__(self):
        return (type(self), (float(self), self._name))

    def __copy__(self) -> FloatToken:
        return self

    def __deepcopy__(self, memo: dict) -> FloatToken:
        return self

    def __setattr__(self, key: str, value: Any) -> None:
        raise AttributeError(f"{type(self).__name__} {self._name} is read-only")

    def __delattr__(self, key: str) -> None:
        raise AttributeError(f"{type(self).__name__} {self._name} is read-only")


def is_token(obj: object) -> bool:
    """True for :class:`Token` and :class:`FloatToken` instances."""
    return isinstance(obj, (Token, FloatToken))


def define(namespace: dict[str, Any], name: str, value: int | float) -> Token | FloatToken:
    """Create the token ``name`` = ``value`` and store it in ``namespace``.

    A Python ``float`` value gives a :class:`FloatToken`, anything else a :class:`Token`.
    Redefining a name with the same value is allowed (returns the existing token);
    redefining it with a different value raises :class:`ValueError`.
    """
    _check_name(name)
    existing = namespace.get(name)
    if is_token(existing):
        if existing == value and isinstance(existing, float) == isinstance(value, float):
            return existing
        raise ValueError(f"{name} is already defined as {existing.value!r}, not {value!r}")
    tok: Token | FloatToken
    if isinstance(value, float):
        tok = FloatToken(value, name)
    else:
        tok = Token(value, name)
    namespace[name] = tok
    return tok


def _names_in(module: ModuleType | Mapping[str, Any]) -> tuple[Mapping[str, Any], list[str]]:
    ns = module if isinstance(module, Mapping) else vars(module)
    names = ns.get("__all__")
    if names is None:
        names = list(ns)
    return ns, list(names)


def family(module: ModuleType | Mapping[str, Any], prefix: str) -> dict[str, Token | FloatToken]:
    """All tokens of ``module`` (a module or namespace dict) whose name starts with
    ``prefix``, as ``{name: token}`` in definition order."""
    ns, names = _names_in(module)
    out: dict[str, Token | FloatToken] = {}
    for n in names:
        if n.startswith(prefix):
            v = ns.get(n)
            if is_token(v):
                out[n] = v
    return out


def lookup(
    module: ModuleType | Mapping[str, Any], prefix: str, value: object, default: Any = None
) -> Any:
    """Name of the first token (in definition order) of the ``prefix`` family of
    ``module`` whose value equals ``value``; ``default`` if there is none.

    ``lookup(GL, "SF_", 2) == "SF_EQUAL"``; ``lookup(GL, "BF_", 2) == "BF_DC"`` (the
    first of the names sharing 2).  Meant for error messages such as
    ``f"bad stencil function {lookup(GL, 'SF_', f, f)}"``.
    """
    for n, tok in family(module, prefix).items():
        try:
            if bool(tok == value):
                return n
        except (TypeError, ValueError):  # arrays, odd types: no match
            return default
    return default
