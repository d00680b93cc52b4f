"""A dense shadow scene for the benchmarks: 20 spheres over a floor, two lights.

About 42 k scene triangles (20 UV spheres of 2112 faces and a floor grid), drawn
with Heidmann's z-pass algorithm at 1280x1024: an ambient pass that writes depth,
then per light a stencil clear, the shadow-volume faces of every sphere's
silhouette (front faces ST_INCR with backface culling, back faces ST_DECR with
frontface culling; no colour, no z writes) and the lit pass (zfunction ZF_EQUAL,
stencil SF_EQUAL 0, blendfunction ONE+ONE).

The geometry is projected to IRIS window coordinates once, in numpy, so vgxsim's
library path (CommandBatch.add_window_triangles) and Mesa llvmpipe
(``python bench/dense_scene.py THREADS``, the pattern of bench/mesa_worker.py) get
the same window-space triangles and the timed region is raster only.
"""

from __future__ import annotations

import contextlib
import json
import sys
import time

import numpy as np
import trimesh

from vgxsim.batch import CLEAR_COLOUR, CLEAR_STENCIL, CLEAR_Z, CommandBatch
from vgxsim.state.codes import (
    CMP_ALWAYS,
    CMP_EQUAL,
    CMP_LESS,
    CULL_BACK,
    CULL_FRONT,
    OP_DECR,
    OP_INCR,
)
from vgxsim.state.planes import Framebuffer, PlaneConfig
from vgxsim.state.raster import RasterState

W, H = 1280, 1024
LIGHTS = (np.array([-6.0, 14.0, 4.0]), np.array([7.0, 12.0, -3.0]))


def _spheres():
    base = trimesh.creation.uv_sphere(radius=1.0, count=[24, 24])  # 2112 faces each: 42 k in all
    rng = np.random.default_rng(5)
    meshes = []
    for i in range(20):
        m = base.copy()
        r = rng.uniform(0.6, 1.1)
        m.apply_scale(r)
        m.apply_translation([(i % 5) * 3.2 - 6.4 + rng.uniform(-0.4, 0.4), r + 0.3,
                             (i // 5) * 3.0 - 4.5 + rng.uniform(-0.4, 0.4)])
        meshes.append(m)
    return meshes


def _floor(n=8, size=12.0):
    xs = np.linspace(-size, size, n + 1)
    gx, gz = np.meshgrid(xs, xs)
    v = np.stack([gx.ravel(), np.zeros(gx.size), gz.ravel()], axis=1)
    f = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            f += [[a, a + n + 1, a + 1], [a + 1, a + n + 1, a + n + 2]]
    return v, np.array(f)


def _project(p):
    """World -> IRIS window coordinates: a camera at (0, 9, 16) looking at the origin,
    60 degree field of view; depth mapped onto [-0x800000, 0x7FFFFF]."""
    eye = np.array([0.0, 9.0, 16.0])
    fwd = -eye / np.linalg.norm(eye)
    right = np.cross(fwd, [0.0, 1.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    d = p - eye
    x, y, z = d @ right, d @ up, d @ fwd  # z: distance along the view direction
    f = 1.0 / np.tan(np.radians(30.0))
    near, far = 0.5, 100.0
    xw = (W - 1) / 2 + (x / z) * f * (H / 2)
    yw = (H - 1) / 2 + (y / z) * f * (H / 2)
    zn = (far + near) / (far - near) - 2 * far * near / ((far - near) * z)  # NDC depth
    zw = -0x800000 + (zn + 1) / 2 * (0x7FFFFF + 0x800000)
    return np.stack([xw, yw, zw], axis=1), z > near


def _volumes(mesh, light, length=30.0):
    """Shadow quads of the silhouette edges of ``mesh`` seen from ``light`` (as two
    triangles each), oriented by the lit face's winding."""
    centres = mesh.triangles_center
    lit = np.einsum("ij,ij->i", mesh.face_normals, light - centres) > 0
    adj = mesh.face_adjacency
    edges = mesh.face_adjacency_edges
    sil = lit[adj[:, 0]] != lit[adj[:, 1]]
    quads = []
    v = mesh.vertices
    for (fa, fb), (a, b) in zip(adj[sil], edges[sil], strict=True):
        face = mesh.faces[fa if lit[fa] else fb]
        # The edge in the lit face's winding order.
        ia, ib = list(face).index(a), list(face).index(b)
        if (ib - ia) % 3 != 1:
            a, b = b, a
        pa, pb = v[a], v[b]
        qa = pa + (pa - light) / np.linalg.norm(pa - light) * length
        qb = pb + (pb - light) / np.linalg.norm(pb - light) * length
        quads.append([pb, pa, qa, qb])
    q = np.array(quads)
    return np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])


def build():
    """The frame as a list of passes ``(what, tris (n, 3, 3) window xyz,
    colours (n, 3, 4), state)`` and ``("clear", planes, state)`` entries."""
    full = (0, W - 1, 0, H - 1)
    spheres = _spheres()
    fv, ff = _floor()
    scene = np.concatenate([fv[ff]] + [m.triangles for m in spheres])
    rng = np.random.default_rng(3)
    scene_col = np.repeat(rng.uniform(0.2, 0.9, (scene.shape[0], 1, 4)), 3, axis=1)
    ambient = RasterState(scissor=full, zbuffer=True, cull=CULL_BACK, draw_front=True)
    front = RasterState(scissor=full, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0,
                        stencil=True, sfunc=CMP_ALWAYS, szpass=OP_INCR, cull=CULL_BACK,
                        draw_front=True)
    back = RasterState(scissor=full, zbuffer=True, zfunc=CMP_LESS, zwritemask=0, wmpack=0,
                       stencil=True, sfunc=CMP_ALWAYS, szpass=OP_DECR, cull=CULL_FRONT,
                       draw_front=True)
    lit = RasterState(scissor=full, zbuffer=True, zfunc=CMP_EQUAL, stencil=True,
                      sfunc=CMP_EQUAL, sref=0, blend_sf=1, blend_df=1, cull=CULL_BACK,
                      draw_front=True)
    clear_all = RasterState(scissor=full, draw_front=True)

    def window(tris):
        p, ok = _project(tris.reshape(-1, 3))
        keep = ok.reshape(-1, 3).all(axis=1)
        return p.reshape(-1, 3, 3)[keep], keep

    sw, keep = window(scene)
    passes = [("clear", CLEAR_COLOUR | CLEAR_Z | CLEAR_STENCIL, clear_all),
              ("ambient", sw, scene_col[keep] * 0.3, ambient)]
    nvol = 0
    for light in LIGHTS:
        vol = np.concatenate([_volumes(m, light) for m in spheres])
        vw, _ = window(vol)
        nvol += vw.shape[0]
        white = np.ones((vw.shape[0], 3, 4))
        passes += [("clear", CLEAR_STENCIL, clear_all),
                   ("volumes", vw, white, front), ("volumes", vw, white, back),
                   ("lit", sw, scene_col[keep] * 0.5, lit)]
    return passes, sw.shape[0], nvol


def vgxsim_frame(passes):
    """A callable drawing the frame through CommandBatch (raster only), and the batch."""
    fb = Framebuffer(PlaneConfig(W, H, stencil=8))
    batch = CommandBatch(fb)
    flat = []
    for p in passes:
        if p[0] == "clear":
            flat.append(p)
            continue
        _, tris, col, rs = p
        xyz = tris.reshape(-1, 3)
        idx = np.arange(xyz.shape[0]).reshape(-1, 3)
        flat.append((p[0], xyz[:, 0].copy(), xyz[:, 1].copy(), xyz[:, 2].copy(),
                     col.reshape(-1, 4).copy(), idx, rs))

    def run():
        for p in flat:
            if p[0] == "clear":
                batch.add_clear(p[1], 0, 0x7FFFFF, 0, p[2])
            else:
                batch.add_window_triangles(*p[1:])
        batch.flush()

    return run, batch


def mesa_frame(threads: int) -> dict:
    """Median frame time on llvmpipe with ``threads`` (one process per count)."""
    from vgxsim.reference import mesa

    mesa.set_threads(threads)
    if not mesa.mesa_available():
        return {"error": "OSMesa/PyOpenGL not available"}
    passes, ntri, nvol = build()
    peer = mesa.MesaPeer(W, H)
    names = {CLEAR_COLOUR: "color", CLEAR_Z: "z", CLEAR_STENCIL: "stencil"}
    uploaded = []
    for p in passes:
        if p[0] == "clear":
            planes = {n for bit, n in names.items() if p[1] & bit}
            uploaded.append(("clear", planes, {"color": 0, "z": 0x7FFFFF, "stencil": 0}, p[2]))
        else:
            uploaded.append((peer.upload_arrays(p[1], p[2]), p[3]))

    def frame():
        for u in uploaded:
            if u[0] == "clear":
                peer.render([u])
            else:
                peer.draw_arrays(*u)
        peer.finish()

    frame()
    ts = []
    for _ in range(5):
        t = time.perf_counter()
        frame()
        ts.append(time.perf_counter() - t)
    return {"frame": float(np.median(ts)), "triangles": ntri, "volume_triangles": nvol,
            "threads": threads}


@contextlib.contextmanager
def flush_cpu_time():
    """Count the process CPU time spent in CommandBatch.flush (the raster) while the
    block runs: yields a one-item list whose value the caller may reset between runs.
    The benchmarks of this directory share it so that they split time the same way."""
    spent = [0.0]
    real_flush = CommandBatch.flush

    def timed_flush(self, *a, **k):
        t = time.process_time()
        try:
            return real_flush(self, *a, **k)
        finally:
            spent[0] += time.process_time() - t

    CommandBatch.flush = timed_flush
    try:
        yield spent
    finally:
        CommandBatch.flush = real_flush


def vgxsim_work(rounds: int = 5) -> dict:
    """The dense frame on vgxsim with exact work skipping on and off (alternating
    round by round): median process CPU time of the raster (CommandBatch.flush) in
    s, and the work counters of one frame with each setting."""
    passes, ntri, nvol = build()
    run, batch = vgxsim_frame(passes)
    switches = ("skip_tiles", "cover_blocks", "tight_tiles")
    samples: dict = {True: [], False: []}
    work = {}
    try:
        with flush_cpu_time() as spent:
            for r in range(rounds + 1):
                for on in (True, False):
                    for sw in switches:
                        setattr(CommandBatch, sw, on)
                    spent[0] = 0.0
                    batch.reset_counters()
                    run()
                    work[on] = batch.work()
                    if r:
                        samples[on].append(spent[0])
    finally:
        for sw in switches:
            setattr(CommandBatch, sw, True)
    return {"raster_cpu": float(np.median(samples[True])),
            "raster_cpu_noskip": float(np.median(samples[False])),
            "work": work[True], "work_noskip": work[False],
            "triangles": ntri, "volume_triangles": nvol}


if __name__ == "__main__":
    # ``python bench/dense_scene.py THREADS``: Mesa llvmpipe (one process per count);
    # ``python bench/dense_scene.py vgxsim``: vgxsim's raster CPU and work counters.
    if sys.argv[1:] == ["vgxsim"]:
        print(json.dumps(vgxsim_work()))
    else:
        print(json.dumps(mesa_frame(int(sys.argv[1]))))
