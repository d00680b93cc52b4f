"""The default scene of Heidmann's ``shadows`` program, as plain numpy data.

What the 1991 sources say about the scene, and what is chosen here:

* README of ``shadows``: "When run without any arguments, it displays a scene of
  three cubes lit with a red and a blue point light source", and "If no lights are
  specified for a scene, a red one and a blue one are created".  The cubes stand on a
  floor here (a large flat box), two on it and one floating above, so that they cast
  shadows on the floor and on each other.  The exact 1991 layout is lost (the program
  source was not found, shared/reference/irisgl_reference.md section 4); the numbers
  below are a choice.
* README: "The light model used ... specifies an ambient value of (0.2, 0.2, 0.2),
  with local viewer, attenuation, and two-sided lighting disabled" -- see
  :class:`LightModel`.
* README, "Show Shadows": the scene is drawn "using only the Ambient and Emitted parts
  for each object's material description", then again "using only the Diffuse and
  Specular components"; the article's code calls these material parts
  ``matl_emitambient`` and ``matl_diffspec``.  :meth:`SurfaceMaterial.props` builds
  the ``lmdef`` property list of each part.
* README: "The WINDOW command" gives the near and far clipping planes and "The LOOKAT
  command specifies look-from and look-to points"; :class:`Camera` keeps those as
  ``perspective`` + ``lookat`` parameters.
* Article: "Assume all polygons of the objects in your scene are drawn in a counter
  clockwise direction, so each polygon normal (Np) faces outward from the object";
  README: the program keeps "edge-adjacency lists".  :class:`Polyhedron` holds outward
  counter-clockwise polygons, per-face normals and, for every edge, its two faces.

Shadow-volume faces (article, "How do you calculate the vertices of the faces
bounding the shadow volumes?"): :func:`shadow_quad`, :func:`silhouette_edges`,
:func:`all_edges_faces`, :func:`is_ingoing` and :func:`shadow_faces`.

Coordinates are world coordinates with +y up; objects are stored already
transformed (the README's per-object Scale, Rotate z-y-x, Position is applied once
when the scene is built), so the drawing code needs no per-object matrices.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from vgxsim import GL
from vgxsim.geometry import transform
from vgxsim.shadow.rigid import box_mesh, object_transform

# trimesh (and networkx, its graph engine) is imported only where a caller hands in
# a trimesh mesh: importing it costs more than the rest of a warm start, and the
# boxes of the default scene are built in plain numpy (vgxsim/shadow/rigid.py).
if TYPE_CHECKING:
    import trimesh

# Material parts, the values ``DrawObjects(matl)`` takes (article: DrawObjects
# (matl_emitambient) / DrawObjects (matl_diffspec)); MATL_FULL is every component
# at once (README "Show Objects Only").
MATL_FULL, MATL_EMITAMBIENT, MATL_DIFFSPEC = 0, 1, 2
MATERIAL_PARTS = (MATL_FULL, MATL_EMITAMBIENT, MATL_DIFFSPEC)

Vec3 = tuple[float, float, float]


# --------------------------------------------------------------------------------------
# Materials, lights, light model, camera
# --------------------------------------------------------------------------------------
@dataclass(frozen=True)
class SurfaceMaterial:
    """An IRIS GL material (``lmdef(DEFMATERIAL, ...)``) split into its two parts.

    Attributes
    ----------
    emission, ambient, diffuse, specular : tuple of 3 float
        The EMISSION, AMBIENT, DIFFUSE and SPECULAR reflectances.
    shininess : float
        SHININESS (0..128).
    """

    emission: Vec3 = (0.0, 0.0, 0.0)
    ambient: Vec3 = (0.2, 0.2, 0.2)
    diffuse: Vec3 = (0.8, 0.8, 0.8)
    specular: Vec3 = (0.0, 0.0, 0.0)
    shininess: float = 0.0

    def props(self, part: int = MATL_FULL) -> list[float]:
        """The ``lmdef(DEFMATERIAL, index, props)`` list of one material part.

        Parameters
        ----------
        part : {MATL_FULL, MATL_EMITAMBIENT, MATL_DIFFSPEC}
            MATL_EMITAMBIENT keeps emission and ambient and zeroes diffuse and
            specular ("those components that would be visible in shadow", article);
            MATL_DIFFSPEC keeps diffuse and specular and zeroes the rest.  Every
            property is listed, so redefining an index never inherits a stale value.

        Returns
        -------
        list of float
            Tokens and values, terminated by LMNULL.
        """
        zero = (0.0, 0.0, 0.0)
        em, am, di, sp = self.emission, self.ambient, self.diffuse, self.specular
        if part == MATL_EMITAMBIENT:
            di, sp = zero, zero
        elif part == MATL_DIFFSPEC:
            em, am = zero, zero
        elif part != MATL_FULL:
            raise ValueError(f"unknown material part {part!r}")
        return [GL.EMISSION, *em, GL.AMBIENT, *am, GL.DIFFUSE, *di, GL.SPECULAR, *sp,
                GL.SHININESS, float(self.shininess), GL.LMNULL]


@dataclass(frozen=True)
class PointLight:
    """A local (w = 1) IRIS GL light, ``lmdef(DEFLIGHT, ...)``.

    Attributes
    ----------
    name : str
    position : tuple of 3 float
        World coordinates (bound with the viewing matrix current, so lmbind takes it
        to eye space).
    colour : tuple of 3 float
        LCOLOR.
    ambient : tuple of 3 float
        The light's own AMBIENT, which the article's first pass uses ("Turn on all
        the lights for ambient light value calculation").
    spot_direction : tuple of 3 float, optional
        SPOTDIRECTION.
    spot : tuple of 2 float, optional
        SPOTLIGHT (exponent, spread angle in degrees).
    jitter : tuple of 3 float
        README: "JITTER specified the dimensions of a cube within which the light is
        given a random position to simulate a non-point light source when jittering
        is enabled"; (0, 0, 0): not jitterable.
    """

    name: str
    position: Vec3
    colour: Vec3
    ambient: Vec3 = (0.0, 0.0, 0.0)
    spot_direction: Vec3 | None = None
    spot: tuple[float, float] | None = None
    jitter: Vec3 = (0.0, 0.0, 0.0)

    @property
    def jitterable(self) -> bool:
        return any(j > 0 for j in self.jitter)

    def props(self) -> list[float]:
        """The ``lmdef(DEFLIGHT, index, props)`` list (POSITION with w = 1: local)."""
        out = [GL.LCOLOR, *self.colour, GL.AMBIENT, *self.ambient,
               GL.POSITION, *self.position, 1.0]
        if self.spot_direction is not None:
            out += [GL.SPOTDIRECTION, *self.spot_direction]
        if self.spot is not None:
            out += [GL.SPOTLIGHT, *self.spot]
        return out + [GL.LMNULL]


@dataclass(frozen=True)
class LightModel:
    """README: "an ambient value of (0.2, 0.2, 0.2), with local viewer, attenuation,
    and two-sided lighting disabled" (``theLModel`` in shadow_scn.c).

    Attributes
    ----------
    ambient : tuple of 3 float
    local_viewer, two_side : bool
    attenuation : tuple of 2 float
        (k0, k1); (1, 0) is no attenuation.
    """

    ambient: Vec3 = (0.2, 0.2, 0.2)
    local_viewer: bool = False
    attenuation: tuple[float, float] = (1.0, 0.0)
    two_side: bool = False

    def props(self) -> list[float]:
        """The ``lmdef(DEFLMODEL, index, props)`` list."""
        return [GL.AMBIENT, *self.ambient, GL.LOCALVIEWER, float(self.local_viewer),
                GL.ATTENUATION, *self.attenuation, GL.TWOSIDE, float(self.two_side),
                GL.LMNULL]


@dataclass(frozen=True)
class Camera:
    """``perspective(fovy, aspect, near, far)`` + ``lookat(eye, target, twist)``.

    Attributes
    ----------
    fovy : int
        Vertical field of view in tenths of a degree (an IRIS Angle).
    near, far : float
    eye, target : tuple of 3 float
        lookat's viewpoint and reference point.
    twist : int
        lookat's twist, tenths of a degree.
    near_height : float, optional
        The README's WINDOW: "the height of the viewing frustrum at the near clipping
        plane".  When given, the projection is ``window(-w/2, w/2, -h/2, h/2, near,
        far)`` with ``w = h * aspect`` and ``fovy`` is not used.
    """

    fovy: int
    near: float
    far: float
    eye: Vec3
    target: Vec3
    twist: int = 0
    near_height: float | None = None

    def frustum(self, aspect: float) -> tuple[float, float, float, float, float, float]:
        """``window(left, right, bottom, top, near, far)`` arguments (near_height set)."""
        h = float(self.near_height)
        return (-0.5 * h * aspect, 0.5 * h * aspect, -0.5 * h, 0.5 * h, self.near, self.far)

    def projection(self, aspect: float) -> np.ndarray:
        """The 4x4 row-vector matrix ``perspective`` (or ``window``) loads."""
        if self.near_height is not None:
            return transform.frustum(*self.frustum(aspect))
        return transform.perspective(self.fovy, aspect, self.near, self.far)

    def modelview(self) -> np.ndarray:
        """The 4x4 row-vector matrix ``lookat`` multiplies onto an identity."""
        return transform.lookat(*self.eye, *self.target, self.twist)


# --------------------------------------------------------------------------------------
# Polyhedra with edge adjacency
# --------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class Polyhedron:
    """A closed polygon mesh with outward counter-clockwise faces and edge adjacency.

    Attributes
    ----------
    name : str
    vertices : ndarray, shape (V, 3), float64
    polygons : ndarray, shape (F, K), int64
        Vertex indices of each polygon, counter-clockwise seen from outside (every
        polygon of a box is a quad, K = 4).
    normals : ndarray, shape (F, 3), float64
        Unit outward normal of each polygon (the article's Np).
    edges : ndarray, shape (E, 2), int64
        Every edge once, as ``(a, b)`` in the direction polygon ``edge_faces[e, 0]``
        traverses it.
    edge_faces : ndarray, shape (E, 2), int64
        The polygon that traverses the edge a -> b, and the one that traverses it
        b -> a (-1 for an edge bounding only one polygon).
    triangles : ndarray, shape (T, 3), int64
        Fan triangulation of the polygons (for the ray cast), counter-clockwise.
    triangle_face : ndarray, shape (T,), int64
        The polygon each triangle belongs to.
    material : SurfaceMaterial
    casts : bool
        Whether the object casts shadows (the README's MODEL; XMODEL objects do not).
    vertex_normals : ndarray, shape (V, 3), float64, optional
        A normal per vertex (``.glo`` files may carry them); None: one per polygon.
    texture : str, optional
        The scene's TEXTURE file for this object.  Read and validated by the scene
        reader; the shadows program maps it onto the x-z plane with texgen
        (vgxsim.shadow.program.tex_sparams, tex_tparams).
    """

    name: str
    vertices: np.ndarray
    polygons: np.ndarray
    normals: np.ndarray
    edges: np.ndarray
    edge_faces: np.ndarray
    triangles: np.ndarray
    triangle_face: np.ndarray
    material: SurfaceMaterial = field(default_factory=SurfaceMaterial)
    casts: bool = True
    vertex_normals: np.ndarray | None = None
    texture: str | None = None

    @property
    def face_points(self) -> np.ndarray:
        """(F, 3) one point on each polygon's plane (its first vertex)."""
        return self.vertices[self.polygons[:, 0]]

    def facing(self, light_pos) -> np.ndarray:
        """(F,) bool: polygon faces the light, ``Np . (L - p) > 0`` (a polygon whose
        plane contains the light counts as facing away)."""
        lp = np.asarray(light_pos, dtype=np.float64)
        return np.einsum("ij,ij->i", self.normals, lp - self.face_points) > 0.0

    @property
    def is_closed(self) -> bool:
        """Every edge is shared by exactly two polygons."""
        return bool(np.all(self.edge_faces[:, 1] >= 0))


def _polygon_loops(mesh: trimesh.Trimesh) -> list[list[int]]:
    """Merge coplanar triangles (trimesh facets) into polygons, CCW from outside."""
    groups = [list(f) for f in mesh.facets]
    used = set(i for g in groups for i in g)
    groups += [[i] for i in range(len(mesh.faces)) if i not in used]
    loops = []
    for g in groups:
        directed = [(int(t[i]), int(t[(i + 1) % 3])) for t in mesh.faces[g] for i in range(3)]
        dset = set(directed)
        boundary = {a: b for a, b in directed if (b, a) not in dset}  # interior edges cancel
        start = min(boundary)
        loop = [start]
        while boundary[loop[-1]] != start:
            loop.append(boundary[loop[-1]])
            if len(loop) > len(boundary):
                raise ValueError("facet boundary is not a single loop")
        # drop vertices where the boundary goes straight on (collinear)
        v = mesh.vertices
        keep = []
        for i, c in enumerate(loop):
            p, n = loop[i - 1], loop[(i + 1) % len(loop)]
            if np.linalg.norm(np.cross(v[c] - v[p], v[n] - v[c])) > 1e-12:
                keep.append(c)
        loops.append(keep)
    loops.sort(key=lambda lp: min(lp))
    return loops


def _polygon_arrays(polygons) -> tuple[np.ndarray, np.ndarray]:
    """Polygons (an (F, K) array or a ragged list) as CSR arrays (start, verts)."""
    if isinstance(polygons, np.ndarray) and polygons.ndim == 2:
        f, k = polygons.shape
        return (np.arange(f + 1, dtype=np.int64) * k,
                np.ascontiguousarray(polygons, dtype=np.int64).reshape(-1))
    lens = np.array([len(p) for p in polygons], dtype=np.int64)
    start = np.zeros(len(lens) + 1, np.int64)
    np.cumsum(lens, out=start[1:])
    verts = (np.concatenate([np.asarray(p, np.int64) for p in polygons])
             if len(lens) else np.zeros(0, np.int64))
    return start, verts


def fan_triangles(start: np.ndarray, verts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Fan triangulation of CSR polygons, counter-clockwise kept.

    Returns
    -------
    triangles : ndarray, shape (T, 3), int64
    triangle_face : ndarray, shape (T,), int64
        The polygon of each triangle (triangles of a polygon are consecutive).
    """
    lens = np.diff(start)
    ntri = np.maximum(lens - 2, 0)
    face = np.repeat(np.arange(len(lens), dtype=np.int64), ntri)
    first = np.concatenate([[0], np.cumsum(ntri)[:-1]]) if len(lens) else np.zeros(0, np.int64)
    j = np.arange(len(face), dtype=np.int64) - np.repeat(first, ntri)  # 0 .. K-3
    s = start[face]
    tris = np.stack([verts[s], verts[s + j + 1], verts[s + j + 2]], axis=1)
    return tris, face


def newell_normals(vertices: np.ndarray, start: np.ndarray, verts: np.ndarray
                   ) -> np.ndarray:
    """Newell's normal of each CSR polygon (outward for CCW seen from outside), unit.

    See :func:`vgxsim.kernels.adjacency.newell_normals`.

    Returns
    -------
    ndarray, shape (F, 3), float64
        Zero for a polygon of zero area.
    """
    from vgxsim.kernels.adjacency import newell_normals as kernel

    return kernel(np.ascontiguousarray(vertices, np.float64), np.ascontiguousarray(start),
                  np.ascontiguousarray(verts))


class MeshError(ValueError):
    """A mesh the shadow code cannot use (inconsistent winding, non-manifold edge)."""


def polyhedron_from_polygons(vertices, polygons, name: str,
                             material: SurfaceMaterial | None = None,
                             casts: bool = True, *,
                             vertex_normals: np.ndarray | None = None,
                             texture: str | None = None) -> Polyhedron:
    """Build a :class:`Polyhedron` from outward counter-clockwise polygons.

    Edge adjacency comes from :func:`vgxsim.kernels.adjacency.edge_adjacency` (linear
    time): on a consistently wound mesh each shared edge is traversed once in each
    direction; an edge of only one polygon (an open mesh such as the teapot) gets -1
    as its second polygon.

    Parameters
    ----------
    vertices : array_like, shape (V, 3)
    polygons : array_like, shape (F, K), int, or a list of F index sequences
        Counter-clockwise seen from outside.  Polygons of mixed sizes are
        fan-triangulated (``Polyhedron.polygons`` is rectangular).
    name : str
    material : SurfaceMaterial, optional
    casts : bool
    vertex_normals : array_like, shape (V, 3), optional
        A normal per vertex (smooth shading); default: one normal per polygon.
    texture : str, optional
        Path of the object's texture image (kept; see :class:`Polyhedron`).

    Returns
    -------
    Polyhedron

    Raises
    ------
    MeshError
        If a directed edge occurs twice (inconsistent winding) or an edge has more
        than two polygons (non-manifold).
    """
    from vgxsim.kernels.adjacency import ADJ_OK, ADJ_SAME_DIRECTION, edge_adjacency

    verts = np.array(vertices, dtype=np.float64).reshape(-1, 3)
    start, flat = _polygon_arrays(polygons)
    lens = np.diff(start)
    if len(lens) and (lens.min() < 3 or flat.min() < 0 or flat.max() >= len(verts)):
        raise MeshError(f"{name}: polygons need >= 3 vertex indices in 0..{len(verts) - 1}")
    if len(lens) and lens.min() != lens.max():
        tris, _ = fan_triangles(start, flat)
        start, flat = _polygon_arrays(tris)
        lens = np.diff(start)
    kk = int(lens[0]) if len(lens) else 3
    polys = flat.reshape(-1, kk)
    edges, faces, status, where = edge_adjacency(start, flat)
    if status != ADJ_OK:
        f = int(np.searchsorted(start, where, side="right") - 1)
        why = ("traversed twice in the same direction (inconsistent winding)"
               if status == ADJ_SAME_DIRECTION else "shared by more than two polygons")
        raise MeshError(f"{name}: an edge of polygon {f} is {why}")
    tris, tri_face = fan_triangles(start, flat)
    vn = None
    if vertex_normals is not None:
        vn = np.array(vertex_normals, dtype=np.float64).reshape(len(verts), 3)
    return Polyhedron(name=name, vertices=verts, polygons=polys,
                      normals=newell_normals(verts, start, flat),
                      edges=edges, edge_faces=faces, triangles=tris, triangle_face=tri_face,
                      material=material or SurfaceMaterial(), casts=casts,
                      vertex_normals=vn, texture=texture)


def polyhedron_from_trimesh(mesh: trimesh.Trimesh, name: str,
                            material: SurfaceMaterial | None = None,
                            casts: bool = True) -> Polyhedron:
    """Build a :class:`Polyhedron` from a watertight, consistently wound trimesh.

    Coplanar triangles (trimesh ``facets``) become one polygon, so a box has six
    quads as in an IRIS GL program.

    Parameters
    ----------
    mesh : trimesh.Trimesh
    name : str
    material : SurfaceMaterial, optional
    casts : bool

    Returns
    -------
    Polyhedron

    Raises
    ------
    ValueError
        If the mesh is not watertight with consistent winding, or its polygons do not
        all have the same number of vertices.
    """
    if not (mesh.is_watertight and mesh.is_winding_consistent):
        raise ValueError(f"{name}: mesh must be watertight with consistent winding")
    loops = _polygon_loops(mesh)
    k = {len(lp) for lp in loops}
    if len(k) != 1:
        raise ValueError(f"{name}: polygons of different sizes {sorted(k)}")
    return polyhedron_from_polygons(mesh.vertices, loops, name, material, casts)


def make_box(name: str, extents: Vec3, *, position: Vec3 = (0.0, 0.0, 0.0),
             rotate: Vec3 = (0.0, 0.0, 0.0), material: SurfaceMaterial | None = None,
             casts: bool = True) -> Polyhedron:
    """A box (:func:`vgxsim.shadow.rigid.box_mesh`) rotated (z, y, x) and positioned.

    Parameters
    ----------
    name : str
    extents : tuple of 3 float
        Edge lengths before rotation.
    position : tuple of 3 float
        Centre.
    rotate : tuple of 3 float
        Degrees about x, y, z (applied z first, as the README says).
    material : SurfaceMaterial, optional
    casts : bool

    Returns
    -------
    Polyhedron
    """
    verts, quads = box_mesh(extents, object_transform(position, rotate))
    return polyhedron_from_polygons(verts, quads, name, material, casts)


def make_grid_box(name: str, extents: Vec3, divisions: tuple[int, int, int], *,
                  position: Vec3 = (0.0, 0.0, 0.0), rotate: Vec3 = (0.0, 0.0, 0.0),
                  material: SurfaceMaterial | None = None,
                  casts: bool = True) -> Polyhedron:
    """A box whose faces are grids of quads (a closed quad mesh, no T-junctions).

    IRIS GL lights per vertex, so a large polygon lit by a near local light is
    shaded only from its corners; the floor is therefore a subdivided box.  The mesh
    is checked to be closed, consistently wound and of positive volume.

    Parameters
    ----------
    name : str
    extents : tuple of 3 float
    divisions : tuple of 3 int
        Number of quads along x, y and z.
    position, rotate, material, casts
        As for :func:`make_box`.

    Returns
    -------
    Polyhedron
    """
    ext = np.asarray(extents, np.float64)
    div = [int(d) for d in divisions]
    pts: list[np.ndarray] = []
    quads: list[np.ndarray] = []
    base = 0
    for axis in range(3):
        for sign in (-1.0, 1.0):
            # u, v span the face with u x v = outward normal (sign * e_axis)
            u_ax, v_ax = (axis + 1) % 3, (axis + 2) % 3
            if sign < 0:
                u_ax, v_ax = v_ax, u_ax
            nu, nv = div[u_ax], div[v_ax]
            uu, vv = np.meshgrid(np.linspace(-0.5, 0.5, nu + 1),
                                 np.linspace(-0.5, 0.5, nv + 1), indexing="ij")
            grid = np.zeros((nu + 1, nv + 1, 3))
            grid[..., axis] = 0.5 * sign
            grid[..., u_ax] = uu
            grid[..., v_ax] = vv
            pts.append((grid * ext).reshape(-1, 3))
            ii, jj = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
            idx = (ii * (nv + 1) + jj).reshape(-1)
            quads.append(base + np.stack([idx, idx + nv + 1, idx + nv + 2, idx + 1], axis=1))
            base += (nu + 1) * (nv + 1)
    allp = np.concatenate(pts)
    uniq, inverse = np.unique(np.round(allp, 12), axis=0, return_inverse=True)
    polys = inverse.reshape(-1)[np.concatenate(quads)]
    m = object_transform(position, rotate)
    verts = uniq @ m[:3, :3].T + m[:3, 3]
    # Winding and manifold edges are checked by polyhedron_from_polygons (MeshError).
    poly = polyhedron_from_polygons(verts, polys, name, material, casts)
    if not (poly.is_closed and _volume(poly) > 0):
        raise ValueError(f"{name}: grid box is not a closed outward mesh")
    return poly


def _volume(poly: Polyhedron) -> float:
    """Signed volume of a closed mesh (divergence theorem: one tetrahedron from the
    origin per triangle); positive when the triangles wind counter-clockwise from
    outside."""
    a, b, c = (poly.vertices[poly.triangles[:, i]] for i in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


# --------------------------------------------------------------------------------------
# The scene
# --------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class Scene:
    """Objects, lights, light model and camera of one shadow scene.

    Attributes
    ----------
    objects : tuple of Polyhedron
        In drawing order.
    lights : tuple of PointLight
    lmodel : LightModel
    camera : Camera
    volume_length : float
        How far each shadow face is projected beyond its edge (article: "some
        arbitrary distance ... a length which will extend through every object
        potentially in shadow, but still lets us draw the resulting quadrilateral").
    background : int
        Packed ABGR clear colour (``czclear``).
    """

    objects: tuple[Polyhedron, ...]
    lights: tuple[PointLight, ...]
    lmodel: LightModel
    camera: Camera
    volume_length: float = 40.0
    background: int = 0x00000000

    @property
    def casters(self) -> tuple[Polyhedron, ...]:
        return tuple(o for o in self.objects if o.casts)

    def triangles(self) -> tuple[np.ndarray, np.ndarray]:
        """All triangles of all objects.

        Returns
        -------
        tris : ndarray, shape (T, 3, 3), float64
            Vertex coordinates.
        object_id : ndarray, shape (T,), int64
            Index into ``objects``.
        """
        tris = [o.vertices[o.triangles] for o in self.objects]
        ids = [np.full(len(o.triangles), i) for i, o in enumerate(self.objects)]
        return np.concatenate(tris), np.concatenate(ids).astype(np.int64)


def default_scene() -> Scene:
    """Three cubes over a floor, a red and a blue point light (README defaults).

    Returns
    -------
    Scene
        Floor: a 14 x 0.25 x 14 box whose top is the plane y = 0, its top and
        bottom cut into 8 x 8 quads for per-vertex lighting (a receiver only, like
        the README's XMODEL, so its volume does not have to be drawn); two cubes
        stand on the floor and a smaller one floats above them, so that each light
        makes the floating cube shadow a standing cube and the floor.
    """
    white = SurfaceMaterial(ambient=(0.9, 0.9, 0.9), diffuse=(0.9, 0.9, 0.9),
                            specular=(0.5, 0.5, 0.5), shininess=30.0)
    yellow = SurfaceMaterial(ambient=(0.9, 0.85, 0.45), diffuse=(0.9, 0.85, 0.45),
                             specular=(0.4, 0.4, 0.4), shininess=20.0)
    green = SurfaceMaterial(ambient=(0.5, 0.9, 0.55), diffuse=(0.5, 0.9, 0.55),
                            specular=(0.4, 0.4, 0.4), shininess=20.0)
    floor = SurfaceMaterial(ambient=(0.6, 0.6, 0.6), diffuse=(0.6, 0.6, 0.6))
    objects = (
        make_grid_box("floor", (14.0, 0.25, 14.0), (8, 1, 8), position=(0.0, -0.125, 0.0),
                      material=floor, casts=False),
        make_box("cube1", (1.4, 1.4, 1.4), position=(-1.3, 0.7, 0.2),
                 rotate=(0.0, 25.0, 0.0), material=white),
        make_box("cube2", (1.0, 1.0, 1.0), position=(1.3, 0.5, -0.6),
                 rotate=(0.0, -30.0, 0.0), material=yellow),
        make_box("cube3", (0.8, 0.8, 0.8), position=(0.0, 2.4, 0.45),
                 rotate=(35.0, 40.0, 0.0), material=green),
    )
    lights = (
        # README: "The lights in the default three-cube scene are jitterable"
        PointLight("red", (-3.5, 7.5, 1.5), (1.0, 0.25, 0.2), ambient=(0.1, 0.025, 0.02),
                   jitter=(0.6, 0.6, 0.6)),
        PointLight("blue", (4.0, 6.5, 3.0), (0.25, 0.35, 1.0), ambient=(0.025, 0.035, 0.1),
                   jitter=(0.6, 0.6, 0.6)),
    )
    camera = Camera(fovy=450, near=1.0, far=40.0, eye=(2.5, 4.8, 7.5),
                    target=(0.0, 0.9, 0.0))
    return Scene(objects=objects, lights=lights, lmodel=LightModel(), camera=camera)


# --------------------------------------------------------------------------------------
# Shadow-volume faces (the article's v3, v4 and ingoing)
# --------------------------------------------------------------------------------------
def shadow_quad(v1, v2, light, length: float) -> np.ndarray:
    """The shadow-volume face of an edge: ``(v1, v2, v3, v4)``.

    Article: "for every polygon edge in every object casting shadows, you need to
    project a line from the light source through the vertices on either end of the
    edge for some arbitrary distance to come up with two more vertices, which
    complete the quadrilateral face of a shadow volume".  ``v3`` is ``v2`` moved
    ``length`` away from the light, ``v4`` likewise from ``v1``; the face is drawn
    v1, v2, v3, v4 (it lies in the plane of the light and the edge, so it is planar).

    Parameters
    ----------
    v1, v2 : array_like, shape (..., 3)
        The edge, in the order the face is to be drawn.
    light : array_like, shape (3,) or (..., 3)
    length : float

    Returns
    -------
    ndarray, shape (..., 4, 3), float64
    """
    v1 = np.asarray(v1, dtype=np.float64)
    v2 = np.asarray(v2, dtype=np.float64)
    lp = np.asarray(light, dtype=np.float64)
    d1 = v1 - lp
    d2 = v2 - lp
    v4 = v1 + length * d1 / np.linalg.norm(d1, axis=-1, keepdims=True)
    v3 = v2 + length * d2 / np.linalg.norm(d2, axis=-1, keepdims=True)
    return np.stack([v1, v2, v3, v4], axis=-2)


def silhouette_edges(mesh: Polyhedron, light_pos) -> np.ndarray:
    """Silhouette edges, each oriented so its shadow face points out of the volume.

    Article: "A silhouette edge can be defined as an edge bounding only one polygon,
    or an edge shared by two polygons, one of which is facing toward the light and the
    other facing away"; "When a polygon is facing the light source, if the shadow
    volume face obtained by projecting an edge is drawn in the direction opposite
    that of the direction of the original edge, the normal of that face (Ns) will
    point outward from the shadow volume ... When the original polygon is facing away
    from the light source, these directions are reversed."  So each edge is returned
    opposite to its direction in the light-facing polygon (for an edge of only one
    polygon: opposite if that polygon faces the light, as is otherwise).

    Parameters
    ----------
    mesh : Polyhedron
    light_pos : array_like, shape (3,)

    Returns
    -------
    ndarray, shape (S, 2, 3), float64
        ``(v1, v2)`` per silhouette edge, for :func:`shadow_quad`.
    """
    facing = mesh.facing(light_pos)
    f0, f1 = mesh.edge_faces[:, 0], mesh.edge_faces[:, 1]
    single = f1 < 0
    fa = facing[f0]
    fb = np.where(single, ~fa, facing[np.where(single, 0, f1)])
    sil = fa != fb
    # f0 traverses a -> b.  If f0 faces the light the face is drawn b -> a; if f0 faces
    # away (then f1, which traverses b -> a, faces the light) it is drawn a -> b.
    a, b = mesh.edges[sil, 0], mesh.edges[sil, 1]
    first = np.where(fa[sil], b, a)
    second = np.where(fa[sil], a, b)
    return np.stack([mesh.vertices[first], mesh.vertices[second]], axis=1)


def all_edges(mesh: Polyhedron, light_pos) -> np.ndarray:
    """Every edge of every polygon (shared edges twice), oriented as the article says.

    For polygon f and its edge a -> b (counter-clockwise order): the shadow face is
    drawn b -> a when f faces the light and a -> b when it faces away, so that its
    normal Ns points out of f's own shadow volume.

    Parameters
    ----------
    mesh : Polyhedron
    light_pos : array_like, shape (3,)

    Returns
    -------
    ndarray, shape (F*K, 2, 3), float64
    """
    facing = mesh.facing(light_pos)
    a = mesh.polygons
    b = np.roll(mesh.polygons, -1, axis=1)
    fac = np.broadcast_to(facing[:, None], a.shape)
    first = np.where(fac, b, a).reshape(-1)
    second = np.where(fac, a, b).reshape(-1)
    return np.stack([mesh.vertices[first], mesh.vertices[second]], axis=1)


def is_ingoing(edges: np.ndarray, light_pos, eye) -> np.ndarray:
    """Whether each shadow face goes into shadow, seen from the eye.

    Article: "When the scene is viewed from the eye's position, front-facing polygons
    will be going into shadow, and back-facing polygons will be going out of the
    shadow."  With the edges oriented so Ns points out of the volume, the face is
    front-facing when the eye is on the side Ns points to:
    ``Ns . (eye - v1) > 0`` with ``Ns = (v2 - v1) x (v2 - L)`` (the direction of
    ``(v2 - v1) x (v3 - v2)``, since v3 - v2 is along v2 - L).

    Parameters
    ----------
    edges : ndarray, shape (N, 2, 3)
    light_pos, eye : array_like, shape (3,)

    Returns
    -------
    ndarray, shape (N,), bool
    """
    v1, v2 = edges[:, 0], edges[:, 1]
    lp = np.asarray(light_pos, dtype=np.float64)
    ns = np.cross(v2 - v1, v2 - lp)
    return np.einsum("ij,ij->i", ns, np.asarray(eye, np.float64) - v1) > 0.0


def all_edges_faces(mesh: Polyhedron, light_pos, eye) -> tuple[np.ndarray, np.ndarray]:
    """Every polygon edge of ``mesh`` with the article's ingoing flag.

    Parameters
    ----------
    mesh : Polyhedron
    light_pos, eye : array_like, shape (3,)

    Returns
    -------
    edges : ndarray, shape (F*K, 2, 3)
        Oriented as in :func:`all_edges`.
    ingoing : ndarray, shape (F*K,), bool
        True: ``ST_INCR`` (going into shadow); False: ``ST_DECR``.
    """
    edges = all_edges(mesh, light_pos)
    return edges, is_ingoing(edges, light_pos, eye)


def shadow_faces(scene: Scene, light: int, edges: str = "silhouette"
                 ) -> tuple[np.ndarray, np.ndarray]:
    """The shadow-volume faces of every caster for one light.

    Parameters
    ----------
    scene : Scene
    light : int
        Index into ``scene.lights``.
    edges : {'silhouette', 'all'}

    Returns
    -------
    quads : ndarray, shape (N, 4, 3)
        v1, v2, v3, v4 of each face (:func:`shadow_quad`).
    ingoing : ndarray, shape (N,), bool
    """
    lp = scene.lights[light].position
    eye = scene.camera.eye
    parts = []
    for obj in scene.casters:
        if edges == "silhouette":
            parts.append(silhouette_edges(obj, lp))
        elif edges == "all":
            parts.append(all_edges(obj, lp))
        else:
            raise ValueError(f"edges must be 'silhouette' or 'all', not {edges!r}")
    e = np.concatenate(parts) if parts else np.zeros((0, 2, 3))
    quads = shadow_quad(e[:, 0], e[:, 1], lp, scene.volume_length)
    return quads, is_ingoing(e, lp, eye)
