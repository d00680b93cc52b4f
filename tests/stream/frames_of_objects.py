"""Seeded multi-frame programs that replay display objects, as the 1991 shadow program
does with its volume cache: objects of stencil() calls and quads (which callobj
replays from a prepared block), objects of coloured and lit quads, parents that nest
them between lmbind calls (one parent of only lmbind and stencil calls between
them, which callobj replays from a prepared block), lights rebound every frame, and
between frames the edits that must make any kept replay or draw-state record stale: editobj with
objreplace / objinsert / objdelete, delobj, makeobj of the same number with new
contents, lmdef of the bound material and light, a new modelview before a light is
rebound, lmcolor changes.  ``render_frames(seed)`` returns the colour, z and stencil
planes after every frame.
"""

from __future__ import annotations

import numpy as np

W, H = 40, 32
FRAME_SEEDS = range(6)
_OPS = (3, 4)  # ST_INCR, ST_DECR (the 1991 faces' two settings)
_EDITS = ("editobj", "delobj", "makeobj", "material", "light", "modelview", "none",
          "editobj", "material")


def _quad(rng) -> list:
    x, y = rng.uniform(-4, W, 2)
    w, h = rng.uniform(4, 24, 2)
    z = rng.uniform(-0.8, 0.8, 4)
    return [(float(x), float(y), float(z[0])), (float(x + w), float(y), float(z[1])),
            (float(x + w), float(y + h), float(z[2])), (float(x), float(y + h), float(z[3]))]


def _face_calls(gl, rng, n: int, tags: set) -> None:
    """n shadow-face-like routines: a stencil() call, then a quad (sometimes with a
    colour or a normal), as the 1991 edge loop records them; sometimes a tag (1..3,
    each once: ``tags`` holds the object's)."""
    for _ in range(n):
        op = _OPS[int(rng.integers(0, 2))]
        if rng.random() < 0.15:
            gl.stencil(0, 0, 7, 0xFF, 0, 0, 0)  # stencil off: keeps the other fields
        else:
            gl.stencil(1, int(rng.integers(0, 3)), 7, 0xFF, 0, 0, op)
        t = int(rng.integers(1, 4))
        if rng.random() < 0.2 and t not in tags:
            gl.maketag(t)
            tags.add(t)
        gl.bgnpolygon()
        r = rng.random()
        if r < 0.25:
            gl.cpack(int(rng.integers(0, 2**32)))
        elif r < 0.45:
            gl.n3f(*(float(v) for v in rng.normal(size=3)))
        for v in _quad(rng):
            gl.v3f(v)
        gl.endpolygon()


def _define(gl, rng, name: int, kind: str, leaves: list, tags: dict) -> None:
    gl.makeobj(name)
    tags[name] = set()
    if kind == "faces":
        _face_calls(gl, rng, int(rng.integers(1, 6)), tags[name])
    elif kind == "lit":  # coloured and lit quads, no stencil: a chunk-only object
        for _ in range(int(rng.integers(1, 3))):
            gl.bgnpolygon()
            gl.c3f(*(float(v) for v in rng.random(3)))
            gl.n3f(*(float(v) for v in rng.normal(size=3)))
            for v in _quad(rng):
                gl.v3f(v)
            gl.endpolygon()
    elif kind == "plain parent":  # lmbind, then leaves between lmbind and stencil calls
        material = 0
        for k, leaf in enumerate(rng.choice(leaves, size=4)):
            if k == 0 or rng.random() < 0.6:
                material = int(rng.integers(0, 3))
                gl.lmbind(1000, material)  # MATERIAL 0, 1 or 2
            elif rng.random() < 0.5:
                gl.stencil(1, int(rng.integers(0, 3)), 7, 0xFF, 0, 0, int(rng.choice(_OPS)))
            gl.callobj(int(leaf))
        if rng.random() < 0.6:  # (a binding after the last draw, another: the next draw's)
            gl.lmbind(1000, (material + 1 + int(rng.integers(0, 2))) % 3)
    else:  # a parent: nested leaves between lmbind and zwritemask calls
        for leaf in rng.choice(leaves, size=3):
            gl.lmbind(1000, int(rng.integers(0, 3)))  # MATERIAL 0, 1 or 2
            gl.callobj(int(leaf))
            if rng.random() < 0.3:
                gl.zwritemask(int(rng.choice([0, 0xFFFFFFFF])))
    gl.closeobj()


def _edit(gl, rng, name: int, tags: set) -> None:
    """One edit of a face object: replace, insert or delete after a tag (tags 1..3
    may be absent, then a positioning call raises and the edit is a plain append)."""
    gl.editobj(name)
    try:
        r = rng.random()
        t = int(rng.integers(1, 4))
        try:
            if r < 0.35:
                gl.objreplace(t)
            elif r < 0.7:
                gl.objinsert(t)
            else:
                gl.objdelete(t, 3)  # (tags themselves stay)
        except gl.GLValueError:
            pass  # no such tag: append at the end
        _face_calls(gl, rng, int(rng.integers(1, 3)), tags)
    finally:
        gl.closeobj()


def render_frames(seed: int) -> list[dict[str, np.ndarray]]:
    """Draw the frames of the seeded program in a fresh window (one more than there
    are kinds of edit); the planes after each frame."""
    from vgxsim import GL, gl
    from vgxsim.gl._core import current

    rng = np.random.default_rng(7000 + seed)
    gl.prefsize(W, H)
    gid = gl.winopen("frames")
    try:
        gl.RGBmode()
        gl.stensize(8)
        gl.gconfig()
        gl.zbuffer(1)
        gl.mmode(GL.MVIEWING)
        gl.ortho(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0)
        for m in (1, 2):
            gl.lmdef(GL.DEFMATERIAL, m, [GL.DIFFUSE, 0.8, 0.3 * m, 0.4, GL.LMNULL])
        gl.lmdef(GL.DEFLIGHT, 1, [GL.POSITION, 0.3, 0.4, 1.0, 0.0, GL.LMNULL])
        gl.lmdef(GL.DEFLIGHT, 2, [GL.POSITION, 20.0, 10.0, 5.0, 1.0, GL.LCOLOR, 0.9, 0.2,
                                  0.1, GL.LMNULL])
        gl.lmdef(GL.DEFLMODEL, 1, [GL.LMNULL])
        gl.lmbind(GL.LMODEL, 1)
        faces, lit = [10, 11, 12], [20, 21]
        tags: dict[int, set] = {}
        for name in faces:
            _define(gl, rng, name, "faces", [], tags)
        for name in lit:
            _define(gl, rng, name, "lit", [], tags)
        _define(gl, rng, 30, "parent", faces + lit, tags)
        # (its own generator: the scenes above stay those of the seeds before it)
        _define(gl, np.random.default_rng(9000 + seed), 31, "plain parent", faces + lit,
                tags)
        out = []
        ctx = current("frames")
        # One frame's calls, drawn every frame (as a program redraws its scene), so
        # that what callobj and the state table keep from one frame is found again in
        # the next -- unless an edit between the frames made it stale.
        # It starts by setting what it changes, so every frame starts alike.
        script: list[tuple[str, tuple]] = [
            ("lmbind", (GL.LIGHT0, 1)), ("lmbind", (GL.MATERIAL, 1)), ("lmcolor", (0,)),
            ("zwritemask", (0xFFFFFFFF,)), ("cpack", (0xFF808080,)),
            ("stencil", (1, 0, 7, 0xFF, 0, 0, 3))]
        for _step in range(10):
            r = rng.random()
            if r < 0.25:
                script.append(("lmbind", (GL.LIGHT0, int(rng.integers(0, 3)))))
                script.append(("lmbind", (GL.MATERIAL, int(rng.integers(0, 3)))))
            elif r < 0.33:
                script.append(("lmcolor", (int(rng.choice([0, 1, 2])),)))  # COLOR, EMISSION,
            elif r < 0.41:                                                 # AMBIENT
                script.append(("zwritemask", (int(rng.choice([0, 0xFFFFFFFF])),)))
            elif r < 0.47:
                script.append(("cpack", (int(rng.integers(0, 2**32)),)))
            script.append(("callobj", (int(rng.choice(faces + lit + [30, 30])),)))
        script += [("callobj", (name,)) for name in faces]  # each face object at least once
        # The plain parent (replayed from a ParentBlock, one per lighting binding: the
        # two calls find the blocks of the frame before), between other calls.
        script += [("lmbind", (GL.MATERIAL, 1)), ("callobj", (31,)), ("cpack", (0xFF4080C0,)),
                   ("lmbind", (GL.MATERIAL, 2)), ("callobj", (31,)),
                   # what the block leaves: the lighting binding and serial, the
                   # stencil and the stream's last state, read by the next draws
                   ("callobj", (20,)), ("stencil", (1, 0, 7, 0xFF, 0, 0, 3)),
                   ("callobj", (21,)), ("lmbind", (GL.LIGHT0, 2)), ("callobj", (20,)),
                   ("callobj", (30,))]
        kinds = list(rng.permutation(_EDITS))
        for _f in range(len(kinds) + 1):
            gl.czclear(0, gl.getgdesc(GL.GD_ZMAX))
            gl.sclear(128)
            for name, args in script:
                getattr(gl, name)(*args)
            # The edits between frames: none after the first, so that the second finds
            # what the first kept, then each kind once, in a seeded order.
            kind = kinds[_f - 1] if _f else "none"
            if kind == "editobj":
                name = int(rng.choice([f for f in faces if gl.isobj(f)]))
                _edit(gl, rng, name, tags[name])
            elif kind == "delobj":
                name = int(rng.choice(faces))
                gl.delobj(name)
                if rng.random() < 0.5:
                    _define(gl, rng, name, "faces", [], tags)
            elif kind == "makeobj":
                _define(gl, rng, int(rng.choice(faces)), "faces", [], tags)  # over it
            elif kind == "material":
                m = int(rng.integers(1, 3))
                gl.lmdef(GL.DEFMATERIAL, m, [GL.DIFFUSE, *(float(v) for v in rng.random(3)),
                                             GL.LMNULL])
            elif kind == "light":
                gl.lmdef(GL.DEFLIGHT, 1, [GL.POSITION, *(float(v) for v in rng.normal(size=3)),
                                          0.0, GL.LMNULL])
            elif kind == "modelview":
                gl.rot(float(rng.uniform(10, 40)), "z")  # (the lights are rebound after it)
                gl.translate(float(rng.uniform(-2, 2)), float(rng.uniform(-2, 2)), 0.0)
            ctx.flush()
            out.append({"rgba": ctx.read_rgba().copy(), "z": ctx.fb.z.copy(),
                        "stencil": ctx.fb.stencil.copy()})
        return out
    finally:
        gl.winclose(gid)
