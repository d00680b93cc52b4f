"""scrnselect, scrnattach, getwscrn, ismex: one screen, number 0, under a window
manager (getgdesc GD_NSCRNS 1, GD_WSYS_4S, GD_SCRNTYPE_WM)."""

import pytest

import vgxsim.gl as gl
from vgxsim import GL
from vgxsim.gl._core import GLTypeError, GLUsageError

pytestmark = pytest.mark.usefixtures("fresh_session")  # tests/gl/conftest.py


def test_screen_zero_is_the_only_screen_even_before_winopen():
    assert gl.getgdesc(GL.GD_NSCRNS) == 1
    assert gl.scrnselect(0) == 0
    assert gl.scrnselect(1) == -1  # scrnselect(3G): -1 for no such screen
    assert gl.scrnselect(-3) == -1
    assert gl.scrnattach(0) == 0
    assert gl.scrnattach(2) == -1
    with pytest.raises(GLTypeError, match="scrnselect"):
        gl.scrnselect("0")


def test_getwscrn_needs_a_window_and_answers_0():
    with pytest.raises(GLUsageError, match="getwscrn"):
        gl.getwscrn()
    gl.prefsize(8, 8)
    gl.winopen("s")
    assert gl.getwscrn() == 0


def test_ismex_matches_the_window_system_getgdesc_reports():
    assert gl.getgdesc(GL.GD_WSYS) == GL.GD_WSYS_4S
    assert gl.getgdesc(GL.GD_SCRNTYPE) == GL.GD_SCRNTYPE_WM
    assert gl.ismex() == 1
