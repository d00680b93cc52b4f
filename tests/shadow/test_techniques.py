"""Technique invariants: optimisations and equivalent constructions change no
stencil value; the silhouette methods agree; library and CLI select techniques."""

from __future__ import annotations

import subprocess
import sys
import warnings

import numpy as np
import pytest

from vgxsim.shadow import api
from vgxsim.shadow.techniques import TechniqueError, make
from vgxsim.shadow.techniques.hard_cases import baseline, eye_in_shadow
from vgxsim.shadow.techniques.volumes import (
    light4,
    silhouettes_by_adjacency,
    silhouettes_by_toggle,
)

W, H = 96, 80


def render(sc, technique, **opts):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", api.ViewpointInShadowWarning)
        return api.render(sc, size=(W, H), technique=technique, technique_options=opts)


def test_toggle_set_equals_adjacency_silhouettes():
    sc = api.load_scene(None)
    for li in range(len(sc.lights)):
        lt = light4(sc.lights[li])
        for obj in sc.casters:
            a = {tuple(p) for p in silhouettes_by_adjacency(obj, lt).tolist()}
            b = {tuple(p) for p in silhouettes_by_toggle(obj, lt).tolist()}
            assert a == b and a


@pytest.mark.parametrize("technique", ["heidmann", "zfail", "finite"])
def test_silhouette_methods_give_identical_stencils(technique):
    sc = api.load_scene(None)
    a = render(sc, technique, silhouettes="adjacency")
    b = render(sc, technique, silhouettes="toggle")
    assert np.array_equal(a.stencil, b.stencil)


@pytest.mark.parametrize("technique", ["heidmann", "zfail", "counting"])
def test_culling_changes_no_stencil_value(technique):
    sc = api.load_scene("balls")
    a = render(sc, technique, cull=False)
    b = render(sc, technique, cull=True)
    assert np.array_equal(a.stencil, b.stencil)


@pytest.mark.parametrize("build", [baseline, eye_in_shadow])
def test_automatic_choice_changes_no_stencil_value(build):
    sc = build()
    auto = render(sc, "auto")
    zfail = render(sc, "auto", force="zfail")
    assert np.array_equal(auto.stencil, zfail.stencil)


def test_automatic_choice_uses_zpass_when_safe_and_zfail_when_not():
    t = make("auto")
    render(baseline(), t)
    assert set(t.last_choice.values()) == {"zpass"}
    t = make("auto")
    render(eye_in_shadow(), t)
    assert set(t.last_choice.values()) == {"zfail"}


def test_counting_equals_all_edges_zpass_on_closed_casters():
    """Bergeron: the signed counts are the all-edge faces after opposite faces
    cancel, so the shadow is the one of z-pass from every edge.  (Not bit-identical
    stencils: a cancelled pair of opposite quads is split along different diagonals,
    so their pixels do not cancel one for one.)"""
    sc = api.load_scene(None)
    a = render(sc, "counting")
    b = render(sc, "heidmann", edges="all", length=None)
    assert np.array_equal(a.lit, b.lit)


def test_heidmann_technique_matches_the_1991_code():
    sc = api.load_scene(None)
    a = api.render(sc, size=(W, H))
    b = render(sc, "heidmann")
    assert np.array_equal(a.lit, b.lit)


def test_roettger_ambient_equals_heidmann_image_where_masks_agree():
    """With a 255/0 mask, BF_DA + BF_ONE adds exactly what BF_ONE + BF_ONE adds."""
    sc = baseline()
    r = render(sc, "roettger")
    z = render(sc, "zfail")
    seen = z.depth < z.depth.max()
    assert np.array_equal(r.lit[:, seen], z.lit[:, seen])
    assert np.array_equal(r.colour[..., :3], z.colour[..., :3])


def test_unknown_technique_and_option_are_clear_errors():
    with pytest.raises(TechniqueError, match="unknown shadow technique"):
        make("nope")
    with pytest.raises(TechniqueError, match="shadowmap"):
        make("shadowmap", sizee=3)


def test_cli_technique(tmp_path):
    out = tmp_path / "s.png"
    r = subprocess.run([sys.executable, "-m", "vgxsim", "shadows", "--technique", "zfail",
                        "--size", "48x40", "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert out.exists()
    r = subprocess.run([sys.executable, "-m", "vgxsim", "shadows", "--technique",
                        "shadowmap", "--option", "bogus=1", "-o", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "bogus" in r.stderr
