"""Solid parts: a triangle mesh checked and cut into planar facets (issue 33).

A :class:`Solid` holds a watertight, consistently wound triangle mesh (read with trimesh:
STL, OBJ, PLY, GLB, 3MF...) and its **facets**: maximal sets of adjacent coplanar
triangles, so that a face of a CAD part is one facet, and a curved surface is the facets
of its tessellation.  Each :class:`Facet` is a planar polygon (holes allowed) in its own
2-D frame, with the **inward** normal the fingers push along and its convex pieces (the
polygon itself when convex; otherwise triangles merged while they stay convex), on which
regions of contact are placed.

Built-in solids for the demo and the tests: ``demo:box`` (40 x 20 x 10), ``demo:cylinder``
(radius 10, height 30, 32 sides), ``demo:prism`` (a triangular prism) and ``demo:angle``
(an L-shaped extrusion), all in millimetres.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core._checks import FloatArray
from ..core.tolerances import TOL
from .contacts import contact_frames

__all__ = ["Facet", "Solid", "solid_from_mesh", "read_solid", "demo_solid", "DEMO_SOLIDS",
           "MESH_SUFFIXES", "is_solid_source"]

#: File suffixes read as meshes (by trimesh).
MESH_SUFFIXES = (".stl", ".obj", ".ply", ".glb", ".gltf", ".3mf", ".off")

#: The built-in solids (``demo:NAME``).
DEMO_SOLIDS = ("box", "cylinder", "prism", "angle")


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

    @property
    def size(self) -> float:
        """The diagonal of the bounding box (lengths are relative to it)."""
        lo, hi = self.mesh.bounds
        return float(np.linalg.norm(hi - lo))


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
                         f"part needs a closed surface (repair=True cannot close holes)")
    if not mesh.is_winding_consistent:
        raise ValueError(f"{where}: the triangles' winding is not consistent "
                         f"(repair=True fixes it)")
    if np.any(mesh.area_faces <= TOL * mesh.scale ** 2):
        raise ValueError(f"{where}: the mesh has degenerate (zero-area) triangles "
                         f"(repair=True drops them)")
    if mesh.volume < 0:
        mesh.invert()
    return Solid(mesh, units, _facets(mesh), np.asarray(mesh.center_mass, float),
                 float(np.max(np.linalg.norm(mesh.vertices - mesh.center_mass, axis=1))),
                 source)


def _facets(mesh: Any) -> list[Facet]:
    """Every triangle in one facet: trimesh's coplanar groups and the triangles left."""
    from shapely import Polygon as ShapelyPolygon
    from shapely import union_all

    groups = [tuple(int(f) for f in g) for g in mesh.facets]
    grouped = {f for g in groups for f in g}
    groups += [(int(f),) for f in range(len(mesh.faces)) if f not in grouped]
    groups.sort(key=lambda g: min(g))
    out = []
    for k, g in enumerate(groups):
        normal = -np.asarray(mesh.face_normals[g[0]], float)         # inward
        t1, t2 = contact_frames(normal[None, :])
        axes = np.vstack([t1[0], t2[0]])
        origin = np.asarray(mesh.vertices[mesh.faces[g[0]][0]], float)
        tris = (mesh.vertices[mesh.faces[list(g)]] - origin) @ axes.T   # (m, 3, 2)
        poly = union_all([ShapelyPolygon(t) for t in tris]).buffer(0)
        if poly.geom_type != "Polygon":       # pieces touching at a point: the largest
            poly = max(poly.geoms, key=lambda p: p.area)
        out.append(Facet(k, g, normal, origin, axes, poly, float(poly.area),
                         tuple(_convex_pieces(poly))))
    return out


def _convex_pieces(poly: Any) -> list[Any]:
    """The polygon itself when convex, else its constrained triangles merged greedily
    while each union stays convex (largest pieces first)."""
    from shapely import constrained_delaunay_triangles

    if poly.area >= poly.convex_hull.area * (1 - TOL):
        return [poly]
    tris = sorted(constrained_delaunay_triangles(poly).geoms, key=lambda t: -t.area)
    pieces: list[Any] = []
    for t in tris:
        for i, p in enumerate(pieces):
            u = p.union(t)
            if u.geom_type == "Polygon" and u.area >= u.convex_hull.area * (1 - TOL):
                pieces[i] = u
                break
        else:
            pieces.append(t)
    return sorted(pieces, key=lambda p: -p.area)


def is_solid_source(source: str) -> bool:
    """``source`` names a solid: ``demo:`` one of :data:`DEMO_SOLIDS`, or a mesh file."""
    if source.startswith("demo:"):
        return source[5:] in DEMO_SOLIDS
    return source.lower().endswith(MESH_SUFFIXES)


def demo_solid(name: str) -> Solid:
    """A built-in solid (:data:`DEMO_SOLIDS`), in millimetres."""
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
    else:
        raise ValueError(f"name must be one of {', '.join(DEMO_SOLIDS)}, got {name!r}")
    assert isinstance(mesh, trimesh.Trimesh)
    return solid_from_mesh(mesh, "mm", f"demo:{name}")


def read_solid(source: str, units: str | None = None, repair: bool = False) -> Solid:
    """A solid from a mesh file (anything trimesh reads: STL, OBJ, PLY, GLB, 3MF, OFF)
    or ``demo:NAME``.  ``units``: the file's (default: its own where it records them,
    else millimetres)."""
    import trimesh

    if not isinstance(source, str):
        raise TypeError(f"source must be a path or demo:NAME, got {type(source).__name__}")
    if source.startswith("demo:"):
        return demo_solid(source[5:])
    try:
        loaded = trimesh.load(source, force="mesh")
    except (OSError, ValueError) as exc:
        raise ValueError(f"{source}: not a readable mesh ({exc})") from None
    own = getattr(loaded, "units", None)
    return solid_from_mesh(loaded, units or own or "mm", source, repair)
