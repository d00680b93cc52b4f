"""Shared set-up of tests/gl: a Context installed as the current window of a fresh
session, without winopen.

Nothing here is autouse: a test file asks for ``gl_window`` (or ``fresh_session``)
by name, usually from a 2-3 line fixture of its own::

    @pytest.fixture
    def ctx(gl_window):
        return gl_window(W, H)
"""

import pytest

from vgxsim.geometry.transform import orthographic
from vgxsim.gl._core import session
from vgxsim.pipeline.context import Context


def install_window(width: int, height: int, *, rgb: bool = True, double: bool = False,
                   stencil: int = 8, acbits: int = 0, projection: bool = True) -> Context:
    """A ``width`` x ``height`` Context, installed as window 1 (and current) of a freshly
    reset session.

    With ``projection`` it gets the standard 2-D projection of subpixel(3G), integer
    coordinates on pixel centres: the matrix ``ortho2(-0.5, width - 0.5, -0.5,
    height - 0.5)`` loads in the default MSINGLE mode.
    """
    ctx = Context(width, height, rgb=rgb, double=double, stencil=stencil, acbits=acbits)
    session.reset()
    session.windows[1] = ctx
    session.current = 1
    if projection:
        ctx.matrices.load_projection(
            orthographic(-0.5, width - 0.5, -0.5, height - 0.5, -1, 1))
    return ctx


@pytest.fixture
def gl_window():
    """:func:`install_window` (call it once or more); the session is reset at teardown."""
    yield install_window
    session.reset()


@pytest.fixture
def fresh_session():
    """An empty session before the test and again after it."""
    session.reset()
    yield
    session.reset()
