"""pygame-ce (SDL2), the ``window`` extra's one dependency, imported in one place.

Every module of :mod:`vgxsim.window` takes ``pygame`` from here, so the environment
SDL reads at import time is always set first (whichever module is imported first),
and a missing extra is one clear error instead of a bare ModuleNotFoundError from
deep inside the package.  Headless runs never import this package.
"""

from __future__ import annotations

import importlib
import os

os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
# SIGINT and SIGTERM stay the runner's (it ends the run cleanly between two calls).
os.environ.setdefault("SDL_NO_SIGNAL_HANDLERS", "1")

try:
    pygame = importlib.import_module("pygame")
except ImportError as exc:  # the optional extra is not installed
    raise ImportError("vgxsim.window needs pygame-ce (SDL2): pip install 'vgxsim[window]' "
                      "(or pip install pygame-ce)") from exc

__all__ = ["pygame"]
