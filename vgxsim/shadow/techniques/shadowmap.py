"""shadowmap: Williams' (1978) shadow maps, for comparison with the volumes.

Per light, the casters' depth is drawn from the light into a window of its own
(``size`` x ``size`` pixels, a perspective view that holds the scene's box for point
and spot lights, an orthographic one along the direction for w = 0), and read back
(``read_pixels(..., 'z')``).  The camera's z-buffer after the first pass is read the
same way; each visible pixel is taken back to the world, into the light's view, and
is lit iff its distance from the light's eye plane is at most the map's there plus
``bias`` world units (nearest texel).  The 1991 machine had no shadow-map texture
test, so the comparison is done on the host and its result is written into the
alpha planes with ``lrectwrite``; the lit pass then adds the light times that mask
(``blendfunction(BF_DA, BF_ONE)``, as :mod:`.roettger`).  The stencil planes are not
used.  Only casters are drawn into the map (a receiver never shadows anything).

Not exact: texel size and bias misclassify pixels near shadow edges and on surfaces
nearly parallel to the light (speed_vs_error.py measures how many).
"""

from __future__ import annotations

import numpy as np

from vgxsim.gl import (
    BF_DA,
    BF_ONE,
    BF_ZERO,
    GD_ZMAX,
    MPROJECTION,
    MVIEWING,
    TRUE,
    RGBmode,
    blendfunction,
    czclear,
    gconfig,
    getgdesc,
    getsize,
    loadmatrix,
    lrectwrite,
    mmode,
    prefsize,
    read_pixels,
    winclose,
    winget,
    winopen,
    winset,
    wmpack,
    zbuffer,
    zwritemask,
)
from vgxsim.shadow.scene import MATL_DIFFSPEC

from .base import Technique, TechniqueError

ALPHA_ONLY = 0xff000000
RGB_ONLY = 0x00ffffff
ZMIN, ZMAX = -0x800000, 0x7FFFFF


def look_from(eye: np.ndarray, target: np.ndarray) -> np.ndarray:
    """(4, 4) row-vector world -> eye matrix looking from ``eye`` at ``target``."""
    f = target - eye
    f = f / np.linalg.norm(f)
    up = np.array([0.0, 1.0, 0.0]) if abs(f[1]) < 0.9 else np.array([1.0, 0.0, 0.0])
    r = np.cross(f, up)
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2] = r, u, -f
    m[3, :3] = -np.array([r @ eye, u @ eye, -f @ eye])
    return m


def light_view(scene, light: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(view, projection) row-vector matrices of a light's depth map."""
    from vgxsim.geometry import transform

    allv = np.concatenate([o.vertices for o in scene.casters] or [np.zeros((1, 3))])
    lo, hi = allv.min(axis=0), allv.max(axis=0)  # only casters need to be in the map
    centre = 0.5 * (lo + hi)
    corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
                        for z in (lo[2], hi[2])])
    radius = float(np.linalg.norm(hi - lo)) / 2.0 + 1e-9
    if light[3] == 0.0:
        d = light[:3] / np.linalg.norm(light[:3])
        eye = centre + 2.0 * radius * d
        view = look_from(eye, centre)
        return view, transform.orthographic(-radius, radius, -radius, radius,
                                            radius * 0.5, radius * 3.5)
    eye = light[:3]
    dist = float(np.linalg.norm(centre - eye))
    if dist <= radius:
        raise TechniqueError("shadowmap: the light is inside the casters' bounding sphere; "
                             "one perspective map cannot see every direction (a cube map "
                             "would be needed)")
    view = look_from(eye, centre)
    pts = np.concatenate([corners, np.ones((8, 1))], axis=1) @ view
    depth = -pts[:, 2]
    half = float(np.max(np.abs(pts[:, :2]) / np.maximum(depth, 1e-9)[:, None]))
    near = max(dist - radius, 1e-3 * dist)
    far = dist + radius
    return view, transform.frustum(-half * near, half * near, -half * near, half * near,
                                   near, far)


class ShadowMap(Technique):
    """Shadow maps of ``size`` x ``size`` texels with a depth ``bias`` (world units)."""

    name = "shadowmap"

    def __init__(self, size: int = 512, bias: float = 0.05):
        if int(size) < 1:
            raise TechniqueError(f"shadowmap: size must be >= 1, not {size}")
        self.size = int(size)
        self.bias = float(bias)
        self.exact = False
        self._maps: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []

    def before_frame(self, prog) -> None:
        main = winget()
        self._maps = []
        n = self.size
        for i in range(prog.nLights):
            lt = self.light(prog, i)
            view, proj = light_view(prog.scene, lt)
            prefsize(n, n)
            gid = winopen("shadowmap")
            try:
                RGBmode()
                gconfig()
                zbuffer(TRUE)
                mmode(MPROJECTION)
                loadmatrix(proj.reshape(-1).tolist())
                mmode(MVIEWING)
                loadmatrix(view.reshape(-1).tolist())
                zwritemask(0xffffffff)
                czclear(0, getgdesc(GD_ZMAX))
                for obj in prog.scene.casters:
                    prog.draw_polygons(obj)
                depth = read_pixels("back", "z").astype(np.float64)
            finally:
                winclose(gid)
                winset(main)
            self._maps.append((view, proj, depth))

    def lit_mask(self, prog, i: int) -> np.ndarray:
        """(H, W) bool, row 0 = bottom: the shadow-map test for light ``i``."""
        view, proj, depth = self._maps[i]
        w, h = getsize()
        cam = prog.scene.camera
        mvp = cam.modelview() @ cam.projection(w / h)
        zw = read_pixels("back", "z").astype(np.float64)
        xs = (2.0 * np.arange(w) + 1.0) / w - 1.0
        ys = (2.0 * np.arange(h) + 1.0) / h - 1.0
        xx, yy = np.meshgrid(xs, ys)
        zn = (zw - ZMIN) * 2.0 / (ZMAX - ZMIN) - 1.0
        world = np.stack([xx, yy, zn, np.ones_like(zn)], axis=-1) @ np.linalg.inv(mvp)
        world = world / world[..., 3:4]
        eye_l = world @ view
        clip = eye_l @ proj
        ndc = clip[..., :3] / clip[..., 3:4]
        n = self.size
        tx = np.clip(np.floor((ndc[..., 0] + 1.0) * n / 2.0).astype(np.int64), 0, n - 1)
        ty = np.clip(np.floor((ndc[..., 1] + 1.0) * n / 2.0).astype(np.int64), 0, n - 1)
        mz = (depth[ty, tx] - ZMIN) * 2.0 / (ZMAX - ZMIN) - 1.0
        # map depth back to distance along the light's view axis
        pinv = np.linalg.inv(proj)
        mp = np.stack([ndc[..., 0], ndc[..., 1], mz, np.ones_like(mz)], axis=-1) @ pinv
        map_dist = -mp[..., 2] / mp[..., 3]
        own = -eye_l[..., 2]
        inside = (np.abs(ndc[..., 0]) <= 1) & (np.abs(ndc[..., 1]) <= 1)
        empty = depth[ty, tx] >= getgdesc(GD_ZMAX)
        return ~inside | empty | (own <= map_dist + self.bias)

    def mark(self, prog, i: int) -> None:
        lit = self.lit_mask(prog, i)
        w, h = getsize()
        words = np.where(lit, np.uint32(0xff000000), np.uint32(0)).astype(np.uint32)
        wmpack(ALPHA_ONLY)
        lrectwrite(0, 0, w - 1, h - 1, words.astype('<u4').tobytes())
        wmpack(0xffffffff)

    def lit_pass(self, prog, i: int) -> None:
        zwritemask(0x0)
        wmpack(RGB_ONLY)
        blendfunction(BF_DA, BF_ONE)
        prog.DrawObjects(MATL_DIFFSPEC)
        zwritemask(0xffffffff)
        wmpack(0xffffffff)

    def finish(self, prog) -> None:
        blendfunction(BF_ONE, BF_ZERO)

    def read_mask(self, prog, i: int) -> np.ndarray:
        return np.ascontiguousarray(read_pixels("back")[..., 3])

    def lit_value(self, prog) -> int:
        return 255
