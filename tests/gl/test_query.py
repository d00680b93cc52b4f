"""getgdesc answers what vgxsim really does (getgdesc(3G); issue 10).

Hand-written expectations: the gl.h inquiry numbers with no GD_ name, and for each
feature inquiry the call a program would go on to use.  A feature that answers
non-zero must be callable in vgxsim.gl; one that is absent must answer 0.
"""

import pytest

import vgxsim.gl as gl
from vgxsim import GL
from vgxsim.gl._core import GLTypeError

pytestmark = pytest.mark.usefixtures("fresh_session")  # tests/gl/conftest.py

# Numbers between and beyond the gl.h GD_ values (GL.py has none of them).
NOT_INQUIRIES = (20, 29, 32, 34, 38, 45, 46, 47, 49, 56, 59, 60, 65, 75, 94, 500, -1, -2)

# Feature inquiry -> the gl call a program asking it would use next.
FEATURE_CALL = {
    "GD_TEXTURE": "texdef2d", "GD_TEXTURE_PERSP": "texdef2d", "GD_CLIPPLANES": "clipplane",
    "GD_FOGVERTEX": "fogvertex", "GD_ZDRAW_GEOM": "zdraw", "GD_ZDRAW_PIXELS": "zdraw",
    "GD_BITS_OVER_SNG_CMODE": "drawmode", "GD_BITS_UNDR_SNG_CMODE": "drawmode",
    "GD_BITS_PUP_SNG_CMODE": "drawmode", "GD_NBLINKS": "blink",
    "GD_NURBS_ORDER": "nurbssurface", "GD_TRIMCURVE_ORDER": "bgntrim",
}


def test_invalid_inquiry_answers_minus_one():
    for bad in NOT_INQUIRIES:
        assert gl.getgdesc(bad) == -1, bad


def test_getgdesc_still_rejects_non_ints():
    for bad in (1.0, "GD_XPMAX", None):
        with pytest.raises(GLTypeError, match="getgdesc"):
            gl.getgdesc(bad)


@pytest.mark.parametrize("name", sorted(FEATURE_CALL))
def test_feature_inquiries_match_the_calls_that_exist(name):
    answer = gl.getgdesc(getattr(GL, name))
    present = callable(getattr(gl, FEATURE_CALL[name], None))
    assert (answer > 0) == present, (name, answer, present)


def test_features_vgxsim_does_not_model_answer_zero():
    # Stereo windows, smoothing, polymode other than fill, textports and cursors are
    # accepted or absent but never drawn: a program must not be told they exist.
    for name in ("GD_STEREO", "GD_LINESMOOTH_RGB", "GD_LINESMOOTH_CMODE",
                 "GD_PNTSMOOTH_RGB", "GD_PNTSMOOTH_CMODE", "GD_POLYSMOOTH", "GD_POLYMODE",
                 "GD_TEXTPORT", "GD_BITS_CURSOR", "GD_DITHER", "GD_MULTISAMPLE"):
        assert gl.getgdesc(getattr(GL, name)) == 0, name


def test_features_vgxsim_models_answer_as_the_vgx():
    # Stencil, blend, logicop, afunction, two-sided lighting and spotlights are drawn.
    assert gl.getgdesc(GL.GD_BITS_STENCIL) == 8
    for name in ("GD_BLEND", "GD_LOGICOP", "GD_AFUNCTION", "GD_LIGHTING_TWOSIDE",
                 "GD_LIGHTING_SPOTLIGHT", "GD_SUBPIXEL_POLY", "GD_READSOURCE_ZBUFFER"):
        assert gl.getgdesc(getattr(GL, name)) == 1, name
    for call in ("stencil", "blendfunction", "logicop", "afunction", "lmdef", "subpixel",
                 "readsource"):
        assert callable(getattr(gl, call))
