"""The ``shadows`` program as a library: scenes in, numpy arrays and images out.

``vgxsim shadows`` is a thin layer over these functions::

    from vgxsim.shadow.api import load_scene, render, write_image

    scene = load_scene("teapot")               # a shipped scene, a .scn path, or None
    frame = render(scene, mode="shadows", size=(320, 256), soft=8)
    frame.colour          # (256, 320, 4) uint8, row 0 = top
    frame.depth           # (256, 320) int32 window z
    frame.lit[0]          # (256, 320) bool: the stencil of light 0 holds its zero
    write_image("teapot.png", frame.colour)

Scenes can also be built from trimesh meshes or numpy arrays with
:func:`scene_from_meshes`.  Every image array is top row first (as image files);
the framebuffer's own planes are bottom row first and are flipped once here.
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from .program import Shadows, accumulate, random_offsets
from .scene import (
    Camera,
    LightModel,
    PointLight,
    Polyhedron,
    Scene,
    SurfaceMaterial,
    default_scene,
    polyhedron_from_polygons,
)
from .viewpoint import eye_in_shadow

# Article, Figure 6: "created from thirty-two separate images".
SOFT_PRESETS = {"figure6": 32}
SOFT_MAX_DEFAULT = 64  # README: "The default maximum number of frames to accumulate is 64"


class ViewpointInShadowWarning(UserWarning):
    """The eye is inside a shadow volume: z-pass stencil counts are off there."""


@dataclass(frozen=True, eq=False)
class Frame:
    """One rendered frame.

    Attributes
    ----------
    colour : ndarray, shape (H, W, 4), uint8
        RGBA, row 0 = top.
    depth : ndarray, shape (H, W), int32
        Window z (GD_ZMIN .. GD_ZMAX), row 0 = top.
    stencil : ndarray, shape (L, H, W), uint8
        Per light, the stencil planes after its shadow faces ('shadows' mode: every
        light; 'mask' mode: the shown light; other modes and soft shadows: L = 0).
    stencil_zero : int
        The stencil value that means "count zero" (lit), from GD_BITS_STENCIL; in
        'mask' mode 0, "no face crossed" (the planes hold the ins in their top half
        and the outs in the bottom one: vgxsim.shadow.program.mask_fields).
    warnings : tuple of str
        E.g. the viewpoint-in-shadow report.
    """

    colour: np.ndarray
    depth: np.ndarray
    stencil: np.ndarray
    stencil_zero: int
    warnings: tuple[str, ...] = field(default=())

    @property
    def lit(self) -> np.ndarray:
        """(L, H, W) bool: the pixel is lit by each light (stencil == zero)."""
        return self.stencil == self.stencil_zero


def load_scene(source: str | os.PathLike | None = None, *, use_cache: bool = True) -> Scene:
    """A scene from a ``.scn`` file, a shipped scene's name, or the default.

    Parameters
    ----------
    source : str or PathLike, optional
        None: the default three cubes and two lights (README: "When run without any
        arguments, it displays a scene of three cubes lit with a red and a blue point
        light source"); a name of :data:`vgxsim.data.SCENES` (``"teapot"``); or a path.
    use_cache : bool
        Use the adjacency cache for ``.glo`` models.

    Raises
    ------
    vgxsim.formats.FormatError
        Naming the file and line.
    """
    from vgxsim.data import SCENES, scene_path
    from vgxsim.formats.scn import read_scene

    if source is None:
        return default_scene()
    text = os.fspath(source)
    stem = text[:-4] if text.endswith(".scn") else text
    if not os.path.exists(text) and stem in SCENES:
        text = str(scene_path(stem))
    return read_scene(text, use_cache=use_cache)


def scene_from_meshes(meshes: Iterable, *, materials: Sequence[SurfaceMaterial] | None = None,
                      casts: Sequence[bool] | None = None,
                      lights: Sequence[PointLight] | None = None,
                      camera: Camera | None = None, floor: bool = True) -> Scene:
    """A scene from trimesh meshes or ``(vertices, faces)`` numpy pairs.

    Parameters
    ----------
    meshes : iterable
        Each a ``trimesh.Trimesh`` or a pair ``(vertices (V, 3) float, faces (F, K) int)``
        of outward, counter-clockwise polygons.
    materials : sequence of SurfaceMaterial, optional
        One per mesh (default: the README's diffuse grey).
    casts : sequence of bool, optional
        One per mesh (default: every mesh casts).
    lights : sequence of PointLight, optional
        Default: the red and the blue light of the default scene.
    camera : Camera, optional
        Default: the default scene's camera.
    floor : bool
        Add the default scene's floor (a receiver, casting nothing) under the meshes.

    Returns
    -------
    Scene

    Raises
    ------
    vgxsim.shadow.scene.MeshError
        For a mesh with inconsistent winding or a non-manifold edge.
    """
    default = default_scene()
    objs: list[Polyhedron] = [default.objects[0]] if floor else []
    for k, m in enumerate(meshes):
        if hasattr(m, "vertices") and hasattr(m, "faces"):
            verts, faces = np.asarray(m.vertices), np.asarray(m.faces)
        else:
            verts, faces = m
        mat = materials[k] if materials is not None else None
        c = casts[k] if casts is not None else True
        objs.append(polyhedron_from_polygons(verts, faces, f"mesh{k}", mat, c))
    allv = np.concatenate([o.vertices for o in objs])
    diag = float(np.linalg.norm(allv.max(0) - allv.min(0)))
    return Scene(objects=tuple(objs), lights=tuple(lights) if lights else default.lights,
                 lmodel=LightModel(), camera=camera or default.camera,
                 volume_length=max(2.0 * diag, 40.0 if floor else 0.0))


def orbit(camera: Camera, rotate: tuple[float, float] = (0.0, 0.0),
          translate: tuple[float, float] = (0.0, 0.0), dolly: float = 0.0) -> Camera:
    """The original's trackball as numbers: turn, shift and track the camera.

    README: the middle mouse "lets the viewer rotate the scene trackball style", the
    left mouse "translates the scene", and both "track into and out of the scene".
    Here the eye moves instead of the scene (the same picture, and the eye point
    the shadow code uses stays exact).

    Parameters
    ----------
    camera : Camera
    rotate : (float, float)
        Degrees: azimuth about the vertical axis through the target (positive turns
        the scene counter-clockwise seen from above), then elevation (positive looks
        from higher up); the elevation stops 1 degree short of the poles.
    translate : (float, float)
        World units along the view's right and up directions (eye and target move).
    dolly : float
        World units towards the target (negative: away); the eye stays in front.

    Returns
    -------
    Camera
    """
    eye = np.asarray(camera.eye, np.float64)
    tgt = np.asarray(camera.target, np.float64)
    d = eye - tgt
    r = float(np.linalg.norm(d))
    az = math.atan2(d[0], d[2]) - math.radians(rotate[0])
    el = math.asin(max(-1.0, min(1.0, d[1] / r))) + math.radians(rotate[1])
    el = max(-math.radians(89.0), min(math.radians(89.0), el))
    if rotate[0] or rotate[1] or dolly:  # (untouched otherwise: no rounding of the eye)
        r = max(r - dolly, 1e-3 * r)
        d = r * np.array([math.cos(el) * math.sin(az), math.sin(el),
                          math.cos(el) * math.cos(az)])
    forward = -d / r
    right = np.cross(forward, [0.0, 1.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    shift = translate[0] * right + translate[1] * up
    if not (translate[0] or translate[1] or rotate[0] or rotate[1] or dolly):
        return camera
    tgt = tgt + shift
    return replace(camera, eye=tuple((tgt + d).tolist()), target=tuple(tgt.tolist()))


def _frames_for(soft: int | str) -> int:
    if isinstance(soft, str):
        if soft not in SOFT_PRESETS:
            raise ValueError(f"unknown soft-shadow preset {soft!r} (known: "
                             f"{', '.join(SOFT_PRESETS)})")
        return SOFT_PRESETS[soft]
    if soft < 0:
        raise ValueError(f"soft must be >= 0 frames, not {soft}")
    return int(soft)


def render(scene: Scene | None = None, *, mode: str = "shadows",
           size: tuple[int, int] = (640, 512), light: int = 0, soft: int | str = 0,
           seed: int = 1991, edges: str = "silhouette", subpixel: bool = False,
           display_objects: bool = True, signs: str = "screen",
           on_soft_frame: Callable[[int, np.ndarray], None] | None = None,
           technique=None, technique_options: dict | None = None,
           cache_volumes: bool = True, share_ambient: bool = True) -> Frame:
    """Render one frame of the ``shadows`` program in a window of its own.

    Parameters
    ----------
    scene : Scene, optional
        Default: the three cubes.
    mode : {'objects', 'volumes', 'mask', 'shadows'}
        The README's display modes.
    size : (int, int)
        Width and height in pixels.
    light : int
        The light the 'volumes' and 'mask' modes show.
    soft : int or str
        Soft shadows: the number of jittered frames accumulated (0: hard shadows), or
        a preset name (``"figure6"``: the article's 32).
    seed : int
        Random seed of the jitter (runs repeat).
    edges : {'silhouette', 'all'}
    subpixel : bool
        ``subpixel(TRUE)``: vertices keep sub-pixel positions.  IRIS default False:
        vertices snap to pixel centres.
    display_objects : bool
        Draw objects from display objects (False: immediate mode, same pixels).
    signs : {'screen', 'article'}
        How shadow faces pick INCR or DECR (see :class:`Shadows`); 'screen' (the
        default here) avoids the stray pixels of snapped, nearly edge-on faces.
    on_soft_frame : callable, optional
        ``on_soft_frame(n, colour)`` with the running average (H, W, 4) uint8, top
        row first, after each of the ``n`` soft-shadow frames.
    technique : str or vgxsim.shadow.techniques.Technique, optional
        A shadow technique for the 'shadows' mode (:data:`vgxsim.shadow.techniques.
        TECHNIQUES`: 'heidmann', 'zfail', 'auto', 'zpplus', 'counting', 'finite',
        'roettger', 'shadowmap'); None: the 1991 code as printed.  ``Frame.stencil``
        then holds the technique's mask plane (stencil, or alpha for 'roettger' and
        'shadowmap') and ``Frame.stencil_zero`` its lit value.
    technique_options : dict, optional
        Keyword options of the named technique (e.g. ``{"size": 1024}``).
    cache_volumes : bool
        Keep each light's shadow faces (and their display object) while the light
        stays put (see :class:`Shadows`); False: recompute and redraw them in
        immediate mode every frame (same pixels).
    share_ambient : bool
        Soft shadows: draw the ambient pass once and put its picture back for the
        other jittered frames where that gives the same pixels
        (:func:`vgxsim.shadow.program.accumulate`); False: draw it every frame.

    Returns
    -------
    Frame

    Warns
    -----
    ViewpointInShadowWarning
        When the eye is inside a shadow volume (README, Bugs).
    """
    scene = scene if scene is not None else default_scene()
    return _render_views(scene, [scene.camera], mode=mode, size=size, light=light, soft=soft,
                         seed=seed, edges=edges, subpixel=subpixel,
                         display_objects=display_objects, signs=signs,
                         on_soft_frame=on_soft_frame, technique=technique,
                         technique_options=technique_options,
                         cache_volumes=cache_volumes, share_ambient=share_ambient)[0]


def _render_views(scene: Scene, cameras: Sequence[Camera], *, mode: str,
                  size: tuple[int, int], light: int, soft: int | str, seed: int, edges: str,
                  subpixel: bool, display_objects: bool, signs: str,
                  on_soft_frame: Callable[[int, np.ndarray], None] | None,
                  technique=None, technique_options: dict | None = None,
                  cache_volumes: bool = True, share_ambient: bool = True) -> list[Frame]:
    """One window, one program set-up, one frame per camera (display objects made once)."""
    from vgxsim.gl import (
        TRUE,
        prefsize,
        read_pixels,
        swapbuffers,
        winclose,
        winopen,
        winset,
    )
    from vgxsim.gl import (
        subpixel as gl_subpixel,
    )
    from vgxsim.gl._core import session

    frames = _frames_for(soft)
    planes: dict[int, np.ndarray] = {}
    tech = None
    if technique is not None:
        from .techniques import make

        tech = make(technique, **(technique_options or {}))

    def hook(i: int) -> None:
        plane = tech.read_mask(prog, i) if tech is not None else read_pixels("back", "stencil")
        planes[i] = plane[::-1]

    w, h = (int(v) for v in size)
    prog = Shadows(scene, mode=mode, edges=edges, light=light, display_objects=display_objects,
                   signs=signs, stencil_hook=hook if frames == 0 else None, technique=tech,
                   cache_volumes=cache_volumes)
    previous = session.current
    prefsize(w, h)
    gid = winopen("shadows")
    out = []
    try:
        prog.setup(accumulate=frames > 0)
        if subpixel:
            gl_subpixel(TRUE)
        for cam in cameras:
            view = replace(scene, camera=cam)
            notes = tuple(f"the viewpoint is inside the shadow of light {e.light} "
                          f"({e.light_name}) cast by {e.caster}: z-pass stencil counts are off "
                          "by one where that volume reaches" for e in eye_in_shadow(view))
            for note in notes:
                warnings.warn(note, ViewpointInShadowWarning, stacklevel=3)
            prog.scene = view
            prog.viewing()
            planes.clear()
            if frames:
                callback = None
                if on_soft_frame is not None:
                    def callback(n: int) -> None:
                        on_soft_frame(n, read_pixels("back")[::-1].copy())
                accumulate(prog, random_offsets(scene, frames, seed), callback,
                           share_ambient=share_ambient)
            else:
                prog.DrawFrame()
            swapbuffers()
            colour = read_pixels("front")[::-1].copy()
            depth = read_pixels("front", "z")[::-1].copy()
            # mask mode counts ins and outs apart (program.mask_fields): 0 is "no face"
            zero = tech.lit_value(prog) if tech is not None and mode == "shadows" else (
                prog.MYZERO) if mode != "mask" else 0
            stencil = (np.stack([planes[i] for i in sorted(planes)]) if planes
                       else np.zeros((0, h, w), np.uint8))
            out.append(Frame(colour, depth, stencil, zero, notes))
    finally:
        prog.teardown()
        winclose(gid)
        if previous is not None and previous in session.windows:
            winset(previous)
    return out


def render_spin(scene: Scene | None, frames: int, **kw) -> list[np.ndarray]:
    """The original's continued spin: ``frames`` frames, the camera turned by
    360 / frames degrees of azimuth each, in one window.

    Parameters
    ----------
    scene : Scene, optional
    frames : int
    **kw
        As for :func:`render`.

    Returns
    -------
    list of ndarray, each (H, W, 4) uint8, row 0 = top
    """
    scene = scene if scene is not None else default_scene()
    if frames < 1:
        raise ValueError(f"frames must be >= 1, not {frames}")
    opts = dict(mode="shadows", size=(640, 512), light=0, soft=0, seed=1991,
                edges="silhouette", subpixel=False, display_objects=True, signs="screen",
                on_soft_frame=None, technique=None, technique_options=None,
                cache_volumes=True, share_ambient=True)
    opts.update(kw)
    cams = [orbit(scene.camera, rotate=(360.0 * k / frames, 0.0)) for k in range(frames)]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ViewpointInShadowWarning)
        return [f.colour for f in _render_views(scene, cams, **opts)]


def write_image(path: str | os.PathLike, colour: np.ndarray) -> None:
    """Write an (H, W, 4) or (H, W, 3) uint8 image, top row first, atomically, as RGB;
    the format follows the suffix (.png, .jpg/.jpeg, .tif/.tiff through
    :func:`vgxsim.sinks.images.write_image`; .rgb/.sgi as an SGI image), any other
    suffix is refused.  An existing file is replaced (the command line checks
    ``--overwrite`` before it renders)."""
    rgb = np.ascontiguousarray(np.asarray(colour, np.uint8)[..., :3])
    path = os.fspath(path)
    if path.lower().endswith((".rgb", ".sgi")):
        from vgxsim.formats.sgi import write_rgb

        write_rgb(path, rgb)
        return
    from vgxsim.sinks.images import write_image as write_any

    write_any(path, rgb, overwrite=True)


def write_animation(path: str | os.PathLike, frames: Sequence[np.ndarray],
                    fps: float = 15.0) -> None:
    """Write frames (each (H, W, 4) uint8, top row first) as .gif or .mp4, atomically."""
    from vgxsim.sinks.atomic import atomic_path
    from vgxsim.sinks.frames import VideoSink

    with atomic_path(path) as tmp:
        sink = VideoSink(tmp, fps=fps, overwrite=True)  # tmp: atomic_path's own new file
        for img in frames:
            sink.write(np.ascontiguousarray(img[::-1]))  # sinks take framebuffer order
        sink.close()
