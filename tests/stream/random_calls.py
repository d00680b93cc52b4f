"""Random IRIS GL call sequences (seeded) and a renderer for them.

A sequence is a list of (name, args) calls of vgxsim.gl: primitives of every kind
with random colours and normals per vertex, state changes between primitives
(stencil, zfunction, wmpack, shademodel, blendfunction, lmbind, lmcolor), matrix
calls.  ``render(calls, objects=...)`` draws a sequence in a fresh window, either
immediately or recorded into nested display objects, and returns its planes.
Used by test_random_streams.py and runnable on its own to compare two checkouts
(``python tests/stream/random_calls.py OUT.npz`` writes the planes of the seeds).
"""

from __future__ import annotations

import sys

import numpy as np

W, H = 48, 40
SEEDS = range(12)


def sequence(seed: int, n: int = 40, faces: bool = False) -> list[tuple[str, tuple]]:
    """A random call sequence (calls at primitive boundaries only).  ``faces``: only
    stencil() calls and polygons with their colours and normals, as the 1991 shadow
    faces (objects of nothing else are replayed from prepared blocks, callobj)."""
    rng = np.random.default_rng(seed)
    calls: list[tuple[str, tuple]] = []

    def pt():
        return (float(rng.uniform(-4, W + 4)), float(rng.uniform(-4, H + 4)),
                float(rng.uniform(-0.9, 0.9)))

    def attrs():
        r = rng.random()
        if r < 0.3:
            calls.append(("c3f", tuple(float(v) for v in rng.random(3))))
        elif r < 0.45:
            calls.append(("cpack", (int(rng.integers(0, 2**32)),)))
        elif r < 0.7:
            nrm = rng.normal(size=3)
            calls.append(("n3f", tuple(float(v) for v in nrm)))

    for _ in range(n):
        r = rng.random()
        if faces:  # a polygon or a stencil() call (r < 0.45: polygon, below)
            r = 0.0 if r < 0.6 else 0.56
        if r < 0.45:
            kind = "polygon" if faces else rng.choice(
                ["polygon", "tmesh", "qstrip", "line", "point"], p=[0.5, 0.15, 0.15, 0.1, 0.1])
            nv = int(rng.integers(3, 7))
            calls.append((f"bgn{kind}", ()))
            for k in range(nv):
                attrs()
                if kind == "tmesh" and k >= 2 and rng.random() < 0.3:
                    calls.append(("swaptmesh", ()))
                calls.append(("v3f", pt()))
            calls.append((f"end{kind}", ()))
        elif r < 0.55:
            calls.append(("rectf", tuple(float(v) for v in rng.uniform(0, W, 4))))
        elif r < 0.62:
            calls.append(("stencil", (1, int(rng.integers(0, 4)), int(rng.integers(0, 8)),
                                      0xFF, 0, int(rng.integers(0, 4)),
                                      int(rng.integers(0, 6)))))
        elif r < 0.66:
            calls.append(("zfunction", (int(rng.choice([1, 3, 4, 7])),)))
        elif r < 0.69:
            calls.append(("wmpack", (int(rng.choice([0, 0xFFFFFFFF, 0x00FF00FF])),)))
        elif r < 0.72:
            calls.append(("shademodel", (int(rng.integers(0, 2)),)))
        elif r < 0.75:
            calls.append(("blendfunction", (int(rng.choice([1, 4])),
                                            int(rng.choice([0, 1, 5])))))
        elif r < 0.80:
            calls.append(("lmbind", (1000, int(rng.integers(0, 2)))))  # MATERIAL 0 or 1
        elif r < 0.83:
            calls.append(("lmcolor", (int(rng.choice([0, 1, 2, 3, 4, 5, 6])),)))
        elif r < 0.88:
            calls.append(("pushmatrix", ()))
            calls.append(("translate", (float(rng.uniform(-5, 5)), float(rng.uniform(-5, 5)),
                                        0.0)))
        elif r < 0.93:
            if sum(c[0] == "pushmatrix" for c in calls) > sum(
                    c[0] == "popmatrix" for c in calls):
                calls.append(("popmatrix", ()))
        else:
            attrs()
    return calls


def _setup():
    from vgxsim import GL, gl

    gl.prefsize(W, H)
    gid = gl.winopen("random")
    gl.RGBmode()
    gl.stensize(8)
    gl.gconfig()
    gl.zbuffer(1)
    gl.ortho(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0)
    gl.lmdef(GL.DEFMATERIAL, 1, [GL.DIFFUSE, 0.8, 0.6, 0.4, GL.SPECULAR, 0.5, 0.5, 0.5,
                                 GL.SHININESS, 20.0, GL.LMNULL])
    gl.lmdef(GL.DEFLIGHT, 1, [GL.POSITION, 0.3, 0.4, 1.0, 0.0, GL.LMNULL])
    gl.lmdef(GL.DEFLMODEL, 1, [GL.LMNULL])
    gl.lmbind(GL.LIGHT0, 1)
    gl.lmbind(GL.LMODEL, 1)
    gl.czclear(0, gl.getgdesc(GL.GD_ZMAX))
    return gid


def _groups(calls, seed: int) -> list[list[tuple[int, int]]]:
    """The segments ``render`` records as objects (cut at primitive boundaries,
    seeded), as (start, stop) ranges of ``calls``, in groups of three (the middle
    objects)."""
    rng = np.random.default_rng(1000 + seed)
    cuts, depth = [0], 0
    for i, (name, _a) in enumerate(calls):
        depth += name.startswith("bgn") - name.startswith("end")
        if depth == 0 and rng.random() < 0.2:
            cuts.append(i + 1)
    cuts.append(len(calls))
    segs = list(zip(cuts[:-1], cuts[1:], strict=True))
    return [segs[i:i + 3] for i in range(0, len(segs), 3)]


def _moves(seed: int, passes: int, groups: int) -> tuple[list, list]:
    """Per pass and per group, a translation (dx, dy, 0) for ``render(passes=...)``."""
    rng = np.random.default_rng(2000 + seed)
    def t():
        return (float(rng.uniform(-6, 6)), float(rng.uniform(-6, 6)), 0.0)
    return [t() for _ in range(passes)], [t() for _ in range(groups)]


def render(calls, objects: bool = False, seed: int = 0,
           passes: int = 0) -> dict[str, np.ndarray]:
    """Draw ``calls`` in a fresh W x H window; with ``objects`` record them into
    display objects first (random segments, nested two and three deep) and draw
    them with one callobj.  Returns the colour, z and stencil planes.

    ``passes`` > 0: draw the whole sequence that many times, each pass under a
    translation of its own and each group of segments under one more (pushmatrix,
    translate, ..., popmatrix around the group's calls, or around the callobj of its
    middle object): the same objects called under changing matrices."""
    from vgxsim import gl
    from vgxsim.gl._core import current

    gid = _setup()
    try:
        groups = _groups(calls, seed)
        outer, inner = _moves(seed, passes, len(groups))
        if not objects and not passes:
            for name, args in calls:
                getattr(gl, name)(*args)
        elif not objects:
            for move in outer:
                gl.pushmatrix()
                gl.translate(*move)
                for g, members in enumerate(groups):
                    gl.pushmatrix()
                    gl.translate(*inner[g])
                    for a, b in members:
                        for name, args in calls[a:b]:
                            getattr(gl, name)(*args)
                    gl.popmatrix()
                gl.popmatrix()
        else:
            names = []
            for k, (a, b) in enumerate(seg for members in groups for seg in members):
                gl.makeobj(10 + k)
                for name, args in calls[a:b]:
                    getattr(gl, name)(*args)
                gl.closeobj()
                names.append(10 + k)
            # Groups of segments in middle objects, all in one top object.
            k = 0
            for g, members in enumerate(groups):
                gl.makeobj(500 + g)
                for _m in members:
                    gl.callobj(names[k])
                    k += 1
                gl.closeobj()
            gl.makeobj(900)
            for g in range(len(groups)):
                if passes:
                    gl.pushmatrix()
                    gl.translate(*inner[g])
                gl.callobj(500 + g)
                if passes:
                    gl.popmatrix()
            gl.closeobj()
            if not passes:
                gl.callobj(900)
            for move in outer:
                gl.pushmatrix()
                gl.translate(*move)
                gl.callobj(900)
                gl.popmatrix()
        ctx = current("render")
        ctx.flush()
        return {"rgba": ctx.read_rgba().copy(), "z": ctx.fb.z.copy(),
                "stencil": ctx.fb.stencil.copy()}
    finally:
        gl.winclose(gid)


if __name__ == "__main__":
    out = {}
    for s in SEEDS:
        for k, v in render(sequence(s)).items():
            out[f"{s}_{k}"] = v
    np.savez(sys.argv[1], **out)
