"""Measure the allowed differences of the OpenGL backend (docs/opengl_backend.md).

    python bench/backend_differences.py [--seed N] [--scenes [--size WxH]]

Draws randomised workloads through the library API (:class:`Context.draw_arrays`)
on the software and the OpenGL backend and prints, per workload, how many pixels
(or channel values) differ and by how much.  Each workload isolates one entry of
the list: Gouraud colour, blending rounding, z interpolation, the alpha test, the
shadows scene under subpixel(FALSE) and subpixel(TRUE), and the shipped scenes
through the shadows program (``--scenes`` for those alone, at ``--size``; the
textured floor also with 8-bit texels and with bilinear textures left to the
software batch, D6).
"""

from __future__ import annotations

import argparse

import numpy as np

from vgxsim import backends
from vgxsim.geometry.transform import orthographic
from vgxsim.gl._core import current, session
from vgxsim.pipeline.context import Context

W, H = 256, 256


def _ctx(backend: str) -> Context:
    backends.set_backend(backend)
    ctx = Context(W, H, stencil=8)
    ctx.matrices.load_projection(orthographic(-0.5, W - 0.5, -0.5, H - 0.5, -1, 1))
    return ctx


def _random_triangles(rng, n, size=40.0):
    centre = rng.uniform(0, [W, H], (n, 1, 2))
    xy = centre + rng.uniform(-size, size, (n, 3, 2))
    z = rng.uniform(-0.9, 0.9, (n, 3, 1))
    return np.concatenate([xy, z], axis=2).reshape(-1, 3)


def _run(backend, draw):
    ctx = _ctx(backend)
    draw(ctx)
    ctx.flush()
    fb = ctx.fb
    backends.set_backend(None)
    return (fb.front.view(np.uint8).reshape(H, W, 4).astype(np.int64),
            fb.z.astype(np.int64), fb.stencil.astype(np.int64))


def _report(name, a, b, what="colour"):
    plane = {"colour": 0, "z": 1, "stencil": 2}[what]
    d = np.abs(a[plane] - b[plane])
    if d.ndim == 3:
        px = int((d.max(axis=2) > 0).sum())
        vals = f", channel values {int((d > 0).sum())} of {d.size}"
    else:
        px, vals = int((d > 0).sum()), f", by more than 2 units {int((d > 2).sum())}"
    print(f"{name:38s} {what:8s} differing pixels {px:6d} of {W * H}{vals}, "
          f"max {int(d.max())}")


def gouraud(rng):
    obj = _random_triangles(rng, 2000)
    col = rng.random((obj.shape[0], 4))

    def draw(ctx):
        ctx.draw_arrays("triangles", obj, col, indices=np.arange(obj.shape[0]).reshape(-1, 3))
    return draw


def blending(rng, sf, df):
    obj = _random_triangles(rng, 400)
    col = np.repeat(rng.random((400, 4)), 3, axis=0)  # flat per triangle

    def draw(ctx):
        ctx.raster.set(blend=(sf, df))
        ctx.draw_arrays("triangles", obj, col, indices=np.arange(obj.shape[0]).reshape(-1, 3))
    return draw


def zbuffered(rng):
    obj = _random_triangles(rng, 2000)

    def draw(ctx):
        ctx.raster.set(zbuffer=True)
        ctx.draw_arrays("triangles", obj, np.ones((obj.shape[0], 4)),
                        indices=np.arange(obj.shape[0]).reshape(-1, 3))
    return draw


def alpha_test(rng):
    obj = _random_triangles(rng, 2000)
    col = rng.random((obj.shape[0], 4))

    def draw(ctx):
        ctx.raster.set(afunction=(128, 4))  # AF_GREATER
        ctx.draw_arrays("triangles", obj, col, indices=np.arange(obj.shape[0]).reshape(-1, 3))
    return draw


def shadows(subpixel: bool, size=(640, 512)):
    from vgxsim.examples import heidmann1991 as h91

    out = {}
    for backend in backends.BACKENDS:
        planes: list = []

        def hook(_i, planes=planes):
            c = current("bench")
            c.flush()
            planes.append((c.fb.stencil.copy(), c.fb.z.copy()))
        backends.set_backend(backend)
        img = h91.render(*size, subpixel_mode=subpixel, stencil_hook=hook)
        backends.set_backend(None)
        session.reset()
        out[backend] = (img, planes)
    (ia, pa), (ib, pb) = out["software"], out["opengl"]
    n = size[0] * size[1]
    masks = [int(((a[0] == 128) != (b[0] == 128)).sum()) for a, b in zip(pa, pb, strict=True)]
    zmax = max(int(np.abs(a[1].astype(np.int64) - b[1]).max()) for a, b in zip(pa, pb,
                                                                            strict=True))
    cd = np.abs(ia.astype(int) - ib.astype(int)).max(axis=2)
    print(f"shadows {size[0]}x{size[1]} subpixel({'TRUE' if subpixel else 'FALSE'}): "
          f"stencil mask pixels differing per light {masks} of {n}, z max {zmax}, "
          f"colour pixels {int((cd > 0).sum())} (> 1 level: {int((cd > 1).sum())})")


SCENES = ("cubes", "balls", "textured_floor", "dense", "teapot")


TEXTURE_VARIANTS = {
    None: {},
    "8-bit texels": {"float_texels": False},  # GL's usual formats: llvmpipe's 8-bit filter
    "NATIVE_BILINEAR off": {"native_bilinear": False},  # the software batch draws it
}


def shipped_scene(name: str, subpixel: bool, size=(160, 128), variant=None) -> None:
    """One shipped scene through the shadows program (vgxsim.shadow.api.render) on
    both backends: stencil-mask pixels differing per light, colour differences.
    ``variant``: a key of :data:`TEXTURE_VARIANTS` (how the OpenGL backend draws
    bilinear textures)."""
    from vgxsim.backends.opengl import batch as gl_batch
    from vgxsim.backends.opengl import surface as gl_surface
    from vgxsim.shadow import api

    opts = TEXTURE_VARIANTS[variant]
    scene = api.load_scene(name)
    frames = {}
    for backend in backends.BACKENDS:
        backends.set_backend(backend)
        gl_batch.NATIVE_BILINEAR = opts.get("native_bilinear", True)
        gl_surface.Surface.float_texels = opts.get("float_texels", True)
        try:
            frames[backend] = api.render(scene, size=size, subpixel=subpixel)
        finally:
            gl_batch.NATIVE_BILINEAR = True
            gl_surface.Surface.float_texels = True
            backends.set_backend(None)
            session.reset()
    a, b = frames["software"], frames["opengl"]
    masks = [int((x != y).sum()) for x, y in zip(a.lit, b.lit, strict=True)]
    cd = np.abs(a.colour.astype(int) - b.colour.astype(int)).max(axis=2)
    label = name if variant is None else f"{name} ({variant})"
    print(f"{label:36s} {size[0]}x{size[1]} subpixel({'TRUE' if subpixel else 'FALSE'}): "
          f"stencil mask pixels differing per light {masks} of {size[0] * size[1]}, "
          f"colour pixels {int((cd > 0).sum())} (> 1 level: {int((cd > 1).sum())}), "
          f"max {int(cd.max())}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--scenes", action="store_true",
                    help="only the shipped scenes, at --size")
    ap.add_argument("--size", default="160x128", help="window of the shipped scenes")
    ns = ap.parse_args(argv)
    size = tuple(int(v) for v in ns.size.lower().split("x"))
    if ns.scenes:
        for sub in (True, False):
            for name in SCENES:
                shipped_scene(name, sub, size)
            for variant in TEXTURE_VARIANTS:
                if variant is not None:
                    shipped_scene("textured_floor", sub, size, variant)
        return 0
    for name, make, what in (("Gouraud, 2000 random triangles", gouraud, "colour"),
                             ("z-buffered, 2000 random sloped", zbuffered, "z"),
                             ("alpha test AF_GREATER 128, Gouraud", alpha_test, "colour")):
        a = _run("software", make(np.random.default_rng(ns.seed)))
        b = _run("opengl", make(np.random.default_rng(ns.seed)))
        _report(name, a, b, what)
    for sf, df, label in ((4, 5, "BF_SA, BF_MSA"), (1, 1, "BF_ONE, BF_ONE"),
                          (2, 0, "BF_DC, BF_ZERO"), (6, 7, "BF_DA, BF_MDA")):
        a = _run("software", blending(np.random.default_rng(ns.seed), sf, df))
        b = _run("opengl", blending(np.random.default_rng(ns.seed), sf, df))
        _report(f"blend {label}, 400 flat triangles", a, b)
    for sub in (True, False):
        shadows(sub)
    for sub in (True, False):
        for name in SCENES:
            shipped_scene(name, sub)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
