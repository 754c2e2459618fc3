"""Solid parts: a triangle mesh checked and cut into planar facets.

A :class:`Solid` holds a watertight, consistently wound triangle mesh (read with trimesh:
STL, OBJ, PLY, GLB, 3MF...) and its **facets**: maximal sets of adjacent coplanar
triangles, so that a face of a CAD part is one facet, and a curved surface is the facets
of its tessellation.  Each :class:`Facet` is a planar polygon (holes allowed) in its own
2-D frame, with the **inward** normal the fingers push along and its convex pieces (the
polygon itself when convex; otherwise triangles merged while they stay convex), on which
regions of contact are placed.

Built-in solids for the demo and the tests: ``demo:box`` (40 x 20 x 10), ``demo:cylinder``
(radius 10, height 30, 32 sides), ``demo:prism`` (a triangular prism), ``demo:angle``
(an L-shaped extrusion, a bracket) and ``demo:mug`` (a cup of radius 40 and height 90
with a handle: 1,584 triangles, curved walls), all in millimetres.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from ..core._checks import FloatArray
from ..core.tolerances import PLANAR_TOL, TOL
from .contacts import contact_frames

__all__ = ["Facet", "Solid", "solid_from_mesh", "demo_solid", "demo_mesh", "DEMO_SOLIDS"]

#: The built-in solids (``demo:NAME``).
DEMO_SOLIDS = ("box", "cylinder", "prism", "angle", "mug")


@dataclass(frozen=True)
class Facet:
    """One planar facet: ``index``, ``faces`` (mesh triangles), inward unit ``normal``,
    the plane's ``origin`` and ``axes`` (2, 3) (in-plane unit vectors), ``polygon`` (a
    shapely polygon in those 2-D coordinates), ``area`` and ``pieces`` (its convex
    pieces, shapely polygons)."""

    index: int
    faces: tuple[int, ...]
    normal: FloatArray = field(repr=False)
    origin: FloatArray = field(repr=False)
    axes: FloatArray = field(repr=False)
    polygon: Any = field(repr=False)
    area: float = 0.0
    pieces: tuple[Any, ...] = field(default=(), repr=False)

    def to_3d(self, xy: Any) -> FloatArray:
        """Points (..., 2) of the facet's plane in 3-D (..., 3)."""
        xy = np.asarray(xy, float)
        return np.asarray(self.origin + xy @ self.axes)

    def to_2d(self, points: Any) -> FloatArray:
        """Points (..., 3) projected into the facet's 2-D coordinates (..., 2)."""
        return np.asarray((np.asarray(points, float) - self.origin) @ self.axes.T)


@dataclass
class Solid:
    """A checked triangle mesh (``mesh``, a ``trimesh.Trimesh``) in ``units``, its
    ``facets``, centre of mass ``center`` and ``radius`` (largest distance of a vertex
    from it), and where it came from (``source``)."""

    mesh: Any
    units: str
    facets: list[Facet]
    center: FloatArray
    radius: float
    source: str = ""
    units_note: str = ""

    @property
    def size(self) -> float:
        """The diagonal of the bounding box (lengths are relative to it)."""
        lo, hi = self.mesh.bounds
        return float(np.linalg.norm(hi - lo))

    @cached_property
    def vertices(self) -> FloatArray:
        """The mesh's vertices (V, 3), read once."""
        return np.asarray(self.mesh.vertices, float)

    @cached_property
    def faces(self) -> np.ndarray:
        """The mesh's triangles as rows of three vertex indices (T, 3), read once."""
        return np.asarray(self.mesh.faces)

    @cached_property
    def triangle_tree(self) -> tuple[Any, float]:
        """A k-d tree of the triangles' centroids and the largest distance from a
        triangle's centroid to its corners (a ball about a point holds every triangle
        that comes within ``r`` of it once the tree's ball of ``r`` plus that is read),
        made once."""
        from scipy.spatial import cKDTree

        tris = self.triangles
        centre = tris.mean(axis=1)
        reach = float(np.sqrt(((tris - centre[:, None]) ** 2).sum(axis=2)).max())
        return cKDTree(centre), reach

    @cached_property
    def triangles(self) -> FloatArray:
        """The mesh's triangles' corners (T, 3, 3), read once (trimesh hashes its arrays
        on every access: the jaw's shadows read them for every facet it tries)."""
        return self.vertices[self.faces]


def solid_from_mesh(mesh: Any, units: str = "mm", source: str = "",
                    repair: bool = False) -> Solid:
    """A :class:`Solid` from a ``trimesh.Trimesh``: checked (watertight, consistent
    winding, no degenerate triangles; ``repair=True`` merges duplicate vertices, drops
    degenerate triangles and fixes the winding and normals first) and cut into facets.

    >>> import trimesh
    >>> s = solid_from_mesh(trimesh.creation.box((2, 2, 2)))
    >>> len(s.facets), s.facets[0].area
    (6, 4.0)
    """
    import trimesh

    if not isinstance(mesh, trimesh.Trimesh):
        raise TypeError(f"mesh must be a trimesh.Trimesh, got {type(mesh).__name__}")
    if len(mesh.faces) == 0:
        raise ValueError(f"mesh must have triangles, got an empty mesh ({source or 'mesh'})")
    mesh = mesh.copy()
    if repair:
        mesh.merge_vertices()
        mesh.update_faces(mesh.nondegenerate_faces())
        mesh.remove_unreferenced_vertices()
        trimesh.repair.fix_winding(mesh)
        trimesh.repair.fix_normals(mesh)
    where = source or "mesh"
    if not mesh.is_watertight:
        raise ValueError(f"{where}: the mesh is not watertight (it has open edges): a solid "
                         f"part needs a closed surface (--repair cannot close holes)")
    if not mesh.is_winding_consistent:
        raise ValueError(f"{where}: the triangles' winding is not consistent "
                         f"(--repair, repair=True, fixes it)")
    if np.any(mesh.area_faces <= TOL * mesh.scale ** 2):
        raise ValueError(f"{where}: the mesh has degenerate (zero-area) triangles "
                         f"(--repair, repair=True, drops them)")
    if mesh.volume < 0:
        mesh.invert()
    return Solid(mesh, units, _facets(mesh), np.asarray(mesh.center_mass, float),
                 float(np.max(np.linalg.norm(mesh.vertices - mesh.center_mass, axis=1))),
                 source)


def _facets(mesh: Any, batched: bool = True) -> list[Facet]:
    """Every triangle in one facet: trimesh's coplanar groups and the triangles left
    (those batched: one polygon each, convex).  ``batched``: the groups of at most
    :data:`GROUP_BATCH` triangles united at once (shapely's ``union_all`` along an
    axis, the same union of each group: a torus's quads are 50,000 such groups), their
    convexity read at once; False: each group on its own, the reference."""
    import shapely
    from shapely import Polygon as ShapelyPolygon
    from shapely import union_all

    # plain arrays, read once (trimesh hashes its arrays on every access)
    vertices = np.asarray(mesh.vertices, float)
    faces = np.asarray(mesh.faces)
    groups = _coplanar_groups(mesh, vertices, faces)
    first = np.array([g[0] for g in groups])
    normals = -np.asarray(mesh.face_normals, float)[first]               # inward
    t1, t2 = contact_frames(normals)
    axes = np.stack([t1, t2], axis=1)                                     # (F, 2, 3)
    origins = vertices[faces[first, 0]]
    # single triangles: their own polygons, batched (counter-clockwise in the frame)
    single = np.array([len(g) == 1 for g in groups])
    tri = np.einsum("fvk,fjk->fvj", vertices[faces[first]] - origins[:, None, :], axes)
    d1, d2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    ccw = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0] > 0
    tri[~ccw] = tri[~ccw][:, ::-1]
    polys = np.empty(len(groups), dtype=object)
    polys[single] = shapely.polygons(tri[single])
    convex = np.zeros(len(groups), bool)
    if batched:
        _united(groups, vertices, faces, origins, axes, polys, convex)
    out = []
    for k, g in enumerate(groups):
        if single[k]:
            poly = polys[k]
            pieces: tuple[Any, ...] = (poly,)
        else:
            if polys[k] is None:
                tris = (vertices[faces[list(g)]] - origins[k]) @ axes[k].T     # (m, 3, 2)
                poly = union_all([ShapelyPolygon(t) for t in tris]).buffer(0)
            else:
                poly = polys[k]
            if poly.geom_type != "Polygon":   # pieces touching at a point: the largest
                poly = max(poly.geoms, key=lambda p: p.area)
                convex[k] = False
            pieces = (poly,) if convex[k] else tuple(_convex_pieces(poly))
        out.append(Facet(k, g, normals[k], origins[k], axes[k], poly, float(poly.area),
                         pieces))
    return out


#: Groups of at most this many triangles are united together (:func:`_facets`).
GROUP_BATCH = 8


def _united(groups: list[tuple[int, ...]], vertices: FloatArray, faces: Any,
            origins: FloatArray, axes: FloatArray, polys: np.ndarray,
            convex: np.ndarray) -> None:
    """Into ``polys`` the union (``buffer(0)``) of each group of 2 to
    :data:`GROUP_BATCH` triangles in its facet's frame, in one call, and into
    ``convex`` whether it is convex as :func:`_convex_pieces` reads it."""
    import shapely

    small = [k for k, g in enumerate(groups) if 1 < len(g) <= GROUP_BATCH]
    if not small:
        return
    idx = np.array(small)
    sizes = np.array([len(groups[k]) for k in small])
    # (each group's triangles as the reference computes them: the same coordinates)
    tris = np.concatenate([(vertices[faces[list(groups[k])]] - origins[k]) @ axes[k].T
                           for k in small])
    grid = np.full((len(small), GROUP_BATCH), None, dtype=object)
    slot = np.arange(len(tris)) - np.repeat(np.cumsum(sizes) - sizes, sizes)
    grid[np.repeat(np.arange(len(small)), sizes), slot] = shapely.polygons(tris)
    united = shapely.buffer(shapely.union_all(grid, axis=1), 0)
    polys[idx] = united
    convex[idx] = _convex(shapely.area(united), shapely.area(shapely.convex_hull(united)))


def _coplanar_groups(mesh: Any, vertices: FloatArray, faces: Any) -> list[tuple[int, ...]]:
    """The mesh's triangles in groups of adjacent coplanar ones (each group's vertices
    within :data:`PLANAR_TOL` of its plane; a chain of nearly coplanar triangles that
    drifts further, such as the side of a finely tessellated cylinder, is split into
    its triangles), ordered by their first triangle."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    n = len(faces)
    normals = np.asarray(mesh.face_normals, float)
    limit = PLANAR_TOL * float(mesh.scale)
    pairs = np.asarray(mesh.face_adjacency).reshape(-1, 2)
    unshared = np.asarray(mesh.face_adjacency_unshared).reshape(-1, 2)
    a, b = pairs[:, 0], pairs[:, 1]
    off_a = np.abs(np.einsum("ij,ij->i", vertices[unshared[:, 1]] - vertices[faces[a, 0]],
                             normals[a]))
    off_b = np.abs(np.einsum("ij,ij->i", vertices[unshared[:, 0]] - vertices[faces[b, 0]],
                             normals[b]))
    same = (np.einsum("ij,ij->i", normals[a], normals[b]) > 0) \
        & (np.maximum(off_a, off_b) <= limit)
    graph = coo_matrix((np.ones(int(same.sum())), (a[same], b[same])), shape=(n, n))
    _, labels = connected_components(graph, directed=False)
    order = np.argsort(labels, kind="stable")
    cuts = np.flatnonzero(np.diff(labels[order])) + 1
    groups: list[tuple[int, ...]] = []
    for g in np.split(order, cuts):
        if len(g) > 1:
            corners = vertices[faces[g]].reshape(-1, 3)
            if np.max(np.abs((corners - vertices[faces[g[0], 0]]) @ normals[g[0]])) > limit:
                groups += [(int(f),) for f in g]             # drifts: each triangle alone
                continue
        groups.append(tuple(int(f) for f in g))
    groups.sort(key=lambda g: min(g))
    return groups


def _convex(area: Any, hull_area: Any) -> Any:
    """Whether a polygon of ``area`` is convex as a facet's pieces are read: within
    :data:`~fcgrasp.core.tolerances.TOL` of its convex hull's ``hull_area`` (elementwise
    on arrays)."""
    return area >= hull_area * (1 - TOL)


def _convex_pieces(poly: Any) -> list[Any]:
    """The polygon itself when convex, else its constrained triangles merged greedily
    while each union stays convex (largest pieces first)."""
    from shapely import constrained_delaunay_triangles

    if _convex(poly.area, poly.convex_hull.area):
        return [poly]
    tris = sorted(constrained_delaunay_triangles(poly).geoms, key=lambda t: -t.area)
    pieces: list[Any] = []
    # each piece's bounding box: a triangle is tried only against the pieces whose box
    # meets its own (closed boxes: one sharing an edge is tried), in the same order,
    # since a union with any other is not one polygon (a facet with hundreds of holes
    # has thousands of triangles: trying every piece made the merge quadratic)
    boxes = np.empty((len(tris), 4))
    for t in tris:
        tb = t.bounds
        near = np.flatnonzero((boxes[:len(pieces), 0] <= tb[2]) & (boxes[:len(pieces), 2] >= tb[0])
                               & (boxes[:len(pieces), 1] <= tb[3])
                               & (boxes[:len(pieces), 3] >= tb[1]))
        for i in near:
            u = pieces[i].union(t)
            if u.geom_type == "Polygon" and _convex(u.area, u.convex_hull.area):
                pieces[i] = u
                boxes[i] = u.bounds
                break
        else:
            boxes[len(pieces)] = tb
            pieces.append(t)
    return sorted(pieces, key=lambda p: -p.area)


def demo_solid(name: str) -> Solid:
    """A built-in solid (:data:`DEMO_SOLIDS`), in millimetres."""
    return solid_from_mesh(demo_mesh(name), "mm", f"demo:{name}")


def demo_mesh(name: str) -> Any:
    """The triangle mesh (a ``trimesh.Trimesh``, millimetres) of a built-in solid."""
    import trimesh
    from shapely import Polygon as ShapelyPolygon
    from trimesh.creation import box, cylinder, extrude_polygon

    if name == "box":
        mesh = box((40.0, 20.0, 10.0))
    elif name == "cylinder":
        mesh = cylinder(radius=10.0, height=30.0, sections=32)
    elif name == "prism":
        mesh = extrude_polygon(ShapelyPolygon([(0, 0), (30, 0), (10, 20)]), 25.0)
    elif name == "angle":
        mesh = extrude_polygon(ShapelyPolygon([(0, 0), (40, 0), (40, 8), (8, 8), (8, 30),
                                               (0, 30)]), 20.0)
    elif name == "mug":
        # a cup with a handle, joined by an exact boolean union when it was made
        # (docs/make_mug.py); its triangles are shipped with the package
        from importlib.resources import files

        with files("fcgrasp.spatial").joinpath("data", "mug.npz").open("rb") as fh:
            data = np.load(fh)
            mesh = trimesh.Trimesh(data["vertices"], data["faces"], process=False)
    else:
        raise ValueError(f"name must be one of {', '.join(DEMO_SOLIDS)}, got {name!r}")
    assert isinstance(mesh, trimesh.Trimesh)
    return mesh
