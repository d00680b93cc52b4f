"""Window-backend tests: SDL's dummy video driver and input synthesized with
``pygame.event.post``, fed to the backend at the points where it looks at SDL."""

from __future__ import annotations

import os

import pytest

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
pygame = pytest.importorskip("pygame")


@pytest.fixture
def backend_factory():
    """Make WindowBackends whose feeders run the given plan; all closed at the end."""
    from window_helpers import Feeder

    from vgxsim.window.backend import WindowBackend

    made = []

    def make(plan, **kw):
        b = WindowBackend(**kw)
        b.feeders.append(Feeder(plan))
        made.append(b)
        return b

    yield make
    for b in made:
        b.close()
