"""No stray pixels on the shipped scenes (README, Bugs: "Stray pixels of the wrong shadow
value can appear ... a shared edge ... not getting drawn the same way").

Seen from outside, a closed surface is crossed as often going in as coming out: with
its front-facing polygons incrementing the stencil and its back-facing ones
decrementing it (z-buffer off), every pixel must end exactly at the starting value.
One pixel covered twice or missed along a shared edge breaks that, so this checks
watertight rasterization on every closed mesh the package ships, snapped
(subpixel off, the IRIS default) and unsnapped.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from vgxsim.gl import *
from vgxsim.gl import read_pixels
from vgxsim.gl._core import session
from vgxsim.shadow.api import load_scene, orbit

W, H = 120, 96
START = 100


@pytest.fixture(autouse=True)
def _fresh_session():
    session.reset()
    yield
    session.reset()


def winding_stencil(scene, objects, subpixel_on: bool) -> np.ndarray:
    prefsize(W, H)
    gid = winopen("watertight")
    try:
        RGBmode()
        stensize(8)
        gconfig()
        if subpixel_on:
            subpixel(TRUE)
        mmode(MVIEWING)
        cam = scene.camera
        if cam.near_height is not None:
            window(*cam.frustum(W / H))
        else:
            perspective(cam.fovy, W / H, cam.near, cam.far)
        loadmatrix(np.eye(4).reshape(-1).tolist())
        lookat(*cam.eye, *cam.target, 0)
        zbuffer(FALSE)
        wmpack(0)
        sclear(START)
        # with the z-buffer off IRIS applies stencil()'s `pass` op (stencil(3G))
        for cull, op in ((backface, ST_INCR), (frontface, ST_DECR)):
            cull(TRUE)
            stencil(TRUE, 0, SF_ALWAYS, 0xff, ST_KEEP, op, op)
            for obj in objects:
                verts = obj.vertices.tolist()  # Python floats: cheaper per call
                for poly in obj.polygons.tolist():
                    bgnpolygon()
                    for vi in poly:
                        v3f(verts[vi])
                    endpolygon()
            cull(FALSE)
        return read_pixels("front", "stencil")
    finally:
        winclose(gid)


@pytest.mark.parametrize("name", ["cubes", "balls", "dense", "textured_floor"])
@pytest.mark.parametrize("subpixel_on", [False, True])
def test_closed_shipped_meshes_leave_no_stray_pixel(name, subpixel_on):
    if name == "dense" and subpixel_on:
        pytest.skip("the 51,200-triangle torus once (subpixel off) keeps the suite short")
    scene = load_scene(name)
    closed = [o for o in scene.objects if o.is_closed and o.casts]
    assert closed
    # a second view from elsewhere, so that edges fall at other angles (one view of the
    # 51,200-triangle torus keeps the test short)
    views = [scene, replace(scene, camera=orbit(scene.camera, rotate=(37.0, 12.0)))]
    for view in views[:1] if name == "dense" else views:
        st = winding_stencil(view, closed, subpixel_on)
        assert np.all(st == START), f"{int((st != START).sum())} stray pixels"


def test_the_check_can_fail():
    # an open mesh (the teapot: lid gap, open spout) does not close up on screen
    scene = load_scene("teapot")
    teapot = [o for o in scene.objects if o.casts]
    assert not teapot[0].is_closed
    st = winding_stencil(scene, teapot, True)
    assert (st != START).any()
