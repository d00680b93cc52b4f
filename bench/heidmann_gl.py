"""The Heidmann 1991 frame as an OpenGL immediate-mode program, timed on llvmpipe.

    python bench/heidmann_gl.py THREADS [WIDTH HEIGHT]

A transliteration of vgxsim/examples/heidmann1991.py (``Shadows.draw_shadows``,
``DrawObjects``) into PyOpenGL 1.x calls on an OSMesa context: the same scene
(:func:`vgxsim.shadow.scene.default_scene`), the same polygons, normals and shadow
faces, the same passes (ambient pass with all lights; per light: stencil reset,
shadow faces with glStencilOp INCR/DECR and colour and z writes off, then the lit
pass with additive blending where the stencil equals 128).  Materials and lights
are OpenGL's (the lighting equation differs in detail from IRIS GL's; what is
timed is the same calls and the same pixels touched).  Prints one JSON object:
the median frame time in seconds over the rounds, the renderer string and the
number of polygons per frame.  llvmpipe reads LP_NUM_THREADS once, so each thread
count runs in its own process (bench/calls.py starts them).
"""

from __future__ import annotations

import json
import sys
import time

import numpy as np

MYZERO = 128


def main() -> None:
    threads = int(sys.argv[1])
    w, h = (int(sys.argv[2]), int(sys.argv[3])) if len(sys.argv) > 3 else (1280, 1024)
    from vgxsim.reference import mesa

    mesa.set_threads(threads)
    if not mesa.mesa_available():
        print(json.dumps({"error": "OSMesa/PyOpenGL not available"}))
        return
    from OpenGL import GL as G

    from vgxsim.examples.heidmann1991 import Shadows
    from vgxsim.shadow.scene import (
        MATL_DIFFSPEC,
        MATL_EMITAMBIENT,
        default_scene,
        shadow_faces,
    )

    peer = mesa.MesaPeer(w, h)
    peer._make_current()
    scene = default_scene()
    prog = Shadows(scene)
    faces = [shadow_faces(scene, i, prog.edges) for i in range(len(scene.lights))]
    cam = scene.camera
    G.glViewport(0, 0, w, h)
    G.glMatrixMode(G.GL_PROJECTION)
    G.glLoadMatrixd(cam.projection(w / h))  # row-vector IRIS = column-major OpenGL
    G.glMatrixMode(G.GL_MODELVIEW)
    G.glLoadMatrixd(cam.modelview())
    G.glEnable(G.GL_DEPTH_TEST)
    G.glDepthFunc(G.GL_LEQUAL)
    G.glEnable(G.GL_LIGHTING)
    G.glShadeModel(G.GL_SMOOTH)
    for i, lt in enumerate(scene.lights):
        G.glLightfv(G.GL_LIGHT0 + i, G.GL_POSITION, (*lt.position, 1.0))
        G.glLightfv(G.GL_LIGHT0 + i, G.GL_DIFFUSE, (*lt.colour, 1.0))
        G.glLightfv(G.GL_LIGHT0 + i, G.GL_SPECULAR, (*lt.colour, 1.0))
    glBegin, glEnd, glNormal3fv, glVertex3fv = (G.glBegin, G.glEnd, G.glNormal3fv,
                                                G.glVertex3fv)
    POLYGON = G.GL_POLYGON

    def material(obj, part):
        m = obj.material
        zero = (0.0, 0.0, 0.0, 1.0)
        amb = (*m.ambient, 1.0) if part != MATL_DIFFSPEC else zero
        emi = (*m.emission, 1.0) if part != MATL_DIFFSPEC else zero
        dif = (*m.diffuse, 1.0) if part != MATL_EMITAMBIENT else zero
        spe = (*m.specular, 1.0) if part != MATL_EMITAMBIENT else zero
        G.glMaterialfv(G.GL_FRONT, G.GL_AMBIENT, amb)
        G.glMaterialfv(G.GL_FRONT, G.GL_EMISSION, emi)
        G.glMaterialfv(G.GL_FRONT, G.GL_DIFFUSE, dif)
        G.glMaterialfv(G.GL_FRONT, G.GL_SPECULAR, spe)

    def draw_objects(part):  # DrawObjects: bgnpolygon / n3f / v3f / endpolygon
        for obj in scene.objects:
            material(obj, part)
            for f, poly in enumerate(obj.polygons):
                glBegin(POLYGON)
                glNormal3fv(obj.normals[f])
                for vi in poly:
                    glVertex3fv(obj.vertices[vi])
                glEnd()

    def frame():
        n = len(scene.lights)
        for i in range(n):
            G.glEnable(G.GL_LIGHT0 + i)
        G.glDepthMask(G.GL_TRUE)
        G.glClearColor(0, 0, 0, 0)
        G.glClear(G.GL_COLOR_BUFFER_BIT | G.GL_DEPTH_BUFFER_BIT)
        G.glDisable(G.GL_BLEND)
        draw_objects(MATL_EMITAMBIENT)
        for i in range(n):
            G.glDisable(G.GL_LIGHT0 + i)
        for i in range(n):
            G.glEnable(G.GL_LIGHT0 + i)
            G.glClearStencil(MYZERO)
            G.glClear(G.GL_STENCIL_BUFFER_BIT)
            G.glDepthMask(G.GL_FALSE)
            G.glColorMask(G.GL_FALSE, G.GL_FALSE, G.GL_FALSE, G.GL_FALSE)
            G.glEnable(G.GL_STENCIL_TEST)
            G.glStencilFunc(G.GL_ALWAYS, 0, 0xFF)
            quads, ingoing = faces[i]
            for q, inc in zip(quads, ingoing, strict=True):
                G.glStencilOp(G.GL_KEEP, G.GL_KEEP, G.GL_INCR if inc else G.GL_DECR)
                glBegin(POLYGON)
                glVertex3fv(q[0])
                glVertex3fv(q[1])
                glVertex3fv(q[2])
                glVertex3fv(q[3])
                glEnd()
            G.glDepthMask(G.GL_TRUE)
            G.glColorMask(G.GL_TRUE, G.GL_TRUE, G.GL_TRUE, G.GL_TRUE)
            G.glEnable(G.GL_BLEND)
            G.glBlendFunc(G.GL_ONE, G.GL_ONE)
            G.glStencilFunc(G.GL_EQUAL, MYZERO, 0xFF)
            G.glStencilOp(G.GL_KEEP, G.GL_KEEP, G.GL_KEEP)
            draw_objects(MATL_DIFFSPEC)
            G.glDisable(G.GL_LIGHT0 + i)
        G.glDisable(G.GL_STENCIL_TEST)
        G.glDisable(G.GL_BLEND)
        G.glFinish()

    frame()
    ts = []
    for _ in range(7):
        t = time.perf_counter()
        frame()
        ts.append(time.perf_counter() - t)
    polygons = 3 * sum(len(o.polygons) for o in scene.objects) + sum(
        len(f[0]) for f in faces)
    print(json.dumps({"frame_s": float(np.median(ts)), "threads": threads,
                      "renderer": mesa.mesa_renderer_string(), "polygons": polygons}))


if __name__ == "__main__":
    main()
