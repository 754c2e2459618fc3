"""The part: a simple polygon with holes, its edges, outward normals and size.

Edge numbering follows the input: edge ``i`` of the outer ring runs from input vertex
``i`` to vertex ``i + 1`` (the last back to the first); hole edges are numbered after
the outer ring's, hole by hole, in each hole's input order.  Either orientation is
accepted for every ring; normals are the object's **outward** normals (on a hole edge
they point into the hole).

Degenerate input is handled one documented way:

* a repeated closing vertex (the last equal to the first, as GeoJSON and WKT write
  rings) is dropped;
* other duplicate consecutive vertices give **zero-length edges**: they keep their
  number, so the numbering still matches the input, but have no normal and are never
  touched by a finger (``Polygon.usable`` is False for them);
* collinear consecutive edges are kept as separate edges, each with its number (they
  share a normal and form separate grasp sets; :func:`fcgrasp.model.outline.clean_outline`
  merges them, as the file readers do);
* a hole may touch the outer ring or another hole at a single point (a valid polygon in
  the OGC sense); touching along a segment or at two points is refused.

Invalid outlines raise :class:`ValueError` saying what is wrong and where: non-finite
coordinates (which vertex), fewer than three distinct vertices, zero area, edges that
cross (which edges, and where), holes outside the outer ring or crossing each other.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any, cast

import numpy as np
import shapely
from shapely.geometry import Polygon as ShapelyPolygon

from ..core._checks import FloatArray, _short, numeric_array
from ..core._geom import signed_area, unique_rows
from ..core.tolerances import COLLINEAR_TOL, MAX_MAGNITUDE, NEIGHBOUR_TURN, TINY

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = ["Polygon", "Edge", "check_polygon"]


@dataclass(frozen=True)
class Edge:
    """One edge of a polygon: ``start -> end`` with unit ``tangent`` and outward ``normal``."""

    index: int
    start: FloatArray
    end: FloatArray
    tangent: FloatArray
    normal: FloatArray
    length: float
    ring: int  # 0 for the outer ring, h + 1 for hole h

    def point_at(self, t: Any) -> FloatArray:
        """Points ``start + t (end - start)`` for parameters ``t`` in [0, 1]."""
        t = np.asarray(t, dtype=float)
        return cast("FloatArray", self.start + t[..., None] * (self.end - self.start))


def _check_ring(value: Any, name: str) -> FloatArray:
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be a list of [x, y] pairs, got {_short(value)}")
    try:
        arr = numeric_array(value, name)
    except ValueError as exc:
        raise ValueError(f"{name} must be a list of [x, y] pairs (shape (n, 2)), got "
                         f"{_short(value)}") from exc
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must have shape (n, 2), got shape {arr.shape}: {_short(value)}")
    bad = np.flatnonzero(~np.all(np.isfinite(arr), axis=1))
    if bad.size:
        raise ValueError(f"{name} has a non-finite coordinate at vertex {int(bad[0])}: "
                         f"{arr[bad[0]].tolist()}")
    big = float(np.max(np.abs(arr))) if arr.size else 0.0
    if big > MAX_MAGNITUDE:
        raise ValueError(f"{name} has a coordinate of magnitude {big:.3g}, above fcgrasp's "
                         f"documented range ({MAX_MAGNITUDE:g}): rescale the part")
    if arr.shape[0] >= 2 and np.array_equal(arr[0], arr[-1]):
        arr = arr[:-1]
    distinct = unique_rows(arr).shape[0]
    if distinct < 3:
        raise ValueError(f"{name} needs at least 3 distinct vertices, got {distinct}")
    return arr



def _crossing_edges(rings: list[FloatArray], offsets: list[int]) -> tuple[int, int, Any] | None:
    """First pair of edges (global numbers) that intersect other than at a shared vertex.

    Every candidate pair (their boxes meet) comes from one spatial index query and is
    intersected in one vectorised call; only the pairs left (none, for a valid part)
    are looked at.  Two neighbours along a ring that turn (:data:`NEIGHBOUR_TURN`) meet
    only at their common vertex, so they are not intersected: shapely's answer for them
    is that vertex."""
    starts, ends, ids, ring_of, after = [], [], [], [], []
    count = 0
    for r, (ring, off) in enumerate(zip(rings, offsets, strict=True)):
        nxt = np.roll(ring, -1, axis=0)
        keep = np.flatnonzero(np.any(ring != nxt, axis=1))
        starts.append(ring[keep])
        ends.append(nxt[keep])
        ids.append(off + keep)
        ring_of.append(np.full(keep.size, r))
        # each kept edge's neighbour after it (the zero-length edges between left out:
        # they repeat the vertex the two share)
        after.append(count + np.roll(np.arange(keep.size), -1))
        count += keep.size
    p0, p1 = np.concatenate(starts), np.concatenate(ends)
    edge, ring_id, nxt_of = np.concatenate(ids), np.concatenate(ring_of), np.concatenate(after)
    segs = shapely.linestrings(np.stack([p0, p1], axis=1))
    # the pairs whose boxes meet (those that do not intersect have an empty
    # intersection below: fine)
    left, right = shapely.STRtree(segs).query(segs)
    sel = left < right
    left, right = left[sel], right[sel]
    u, w = p1[left] - p0[left], p1[right] - p0[right]
    turn = np.abs(u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]) > NEIGHBOUR_TURN * \
        np.hypot(u[:, 0], u[:, 1]) * np.hypot(w[:, 0], w[:, 1])
    apart = turn & ((nxt_of[left] == right) | (nxt_of[right] == left))
    left, right = left[~apart], right[~apart]
    order = np.lexsort((right, left))
    left, right = left[order], right[order]
    inter = shapely.intersection(segs[left], segs[right])
    point = shapely.get_type_id(inter) == 0
    xy = np.full((left.size, 2), np.nan)
    xy[point] = shapely.get_coordinates(inter[point])

    def at(p: FloatArray) -> np.ndarray:
        return cast("np.ndarray", np.all(xy == p, axis=1))

    in_a = at(p0[left]) | at(p1[left])
    in_b = at(p0[right]) | at(p1[right])
    same = ring_id[left] == ring_id[right]
    shared = (at(p0[left]) & (at(p0[right]) | at(p1[right]))) \
        | (at(p1[left]) & (at(p0[right]) | at(p1[right])))
    # neighbours meeting at their common vertex; rings touching at a vertex are valid
    # if shapely says so (the caller checks)
    fine = shapely.is_empty(inter) | (point & np.where(same, shared, in_a | in_b))
    bad = np.flatnonzero(~fine)
    if bad.size == 0:
        return None
    j = bad[0]
    return int(edge[left[j]]), int(edge[right[j]]), inter[j]


class Polygon:
    """A planar part: outer ring and holes, either orientation.

    Parameters
    ----------
    vertices : array_like, shape (n, 2)
        Outer ring.
    holes : sequence of array_like, shape (m, 2)
        Holes, each a ring inside the outer one.

    Attributes
    ----------
    starts, ends, tangents, normals : ndarray, shape (E, 2)
        Per edge, in the numbering of the module docstring; normals are outward.
    lengths : ndarray, shape (E,)
    rings : ndarray of int, shape (E,)
        0 for outer-ring edges, ``h + 1`` for edges of hole ``h``.
    usable : ndarray of bool, shape (E,)
        False for zero-length edges.

    Examples
    --------
    >>> sq = Polygon([[0, 0], [0, 1], [1, 1], [1, 0]])     # clockwise is fine
    >>> sq.normals[0].tolist(), sq.area
    ([-1.0, 0.0], 1.0)
    """

    def __init__(self, vertices: ArrayLike, holes: Sequence[Any] = ()) -> None:
        outer = _check_ring(vertices, "vertices")
        if isinstance(holes, (str, bytes)) or not isinstance(holes, (Sequence, np.ndarray)):
            raise TypeError(f"holes must be a list of rings (each of shape (m, 2)), got "
                            f"{_short(holes)}")
        if isinstance(holes, np.ndarray) and holes.ndim == 2:
            raise ValueError("holes must be a list of rings (each of shape (m, 2)), got one "
                             "array of shape " + str(holes.shape))
        hole_rings = [_check_ring(h, f"holes[{k}]") for k, h in enumerate(holes)]
        rings = [outer, *hole_rings]
        areas = [signed_area(r) for r in rings]
        scale = float(np.max(np.ptp(np.concatenate(rings), axis=0)))
        if scale < 1.0 / MAX_MAGNITUDE:
            raise ValueError(f"vertices span {scale:.3g}, below fcgrasp's documented range "
                             f"(parts at least {1.0 / MAX_MAGNITUDE:g} across): rescale the "
                             f"part")
        for k, r in enumerate(rings):
            rel = r - r[0]
            far = rel[np.argmax(np.hypot(rel[:, 0], rel[:, 1]))]
            off_line = np.abs(rel[:, 0] * far[1] - rel[:, 1] * far[0])
            if np.max(off_line) <= COLLINEAR_TOL * scale * scale:
                where = "vertices" if k == 0 else f"holes[{k - 1}]"
                raise ValueError(f"{where} has zero area: all its vertices lie on one line")
        offsets = list(np.cumsum([0] + [len(r) for r in rings[:-1]]))
        cross = _crossing_edges(rings, offsets)
        if cross is not None:
            i, j, inter = cross
            at = np.asarray(inter.representative_point().coords[0]).round(12).tolist()
            raise ValueError(f"outline is not simple: edges {i} and {j} intersect at {at}")
        shp = ShapelyPolygon(outer, hole_rings)
        if not shp.is_valid:
            reason = shapely.is_valid_reason(shp)
            for k, h in enumerate(hole_rings):
                if not ShapelyPolygon(outer).contains(ShapelyPolygon(h)):
                    raise ValueError(f"holes[{k}] is not inside the outer ring")
            raise ValueError(f"invalid polygon: {reason}")
        self.vertices = outer
        self.holes = hole_rings
        self._shapely = shp
        starts, ends, rid = [], [], []
        for k, r in enumerate(rings):
            starts.append(r)
            ends.append(np.roll(r, -1, axis=0))
            rid.append(np.full(len(r), k))
        self.starts = np.concatenate(starts)
        self.ends = np.concatenate(ends)
        self.rings = np.concatenate(rid)
        d = self.ends - self.starts
        self.lengths = np.hypot(d[:, 0], d[:, 1])
        self.usable = self.lengths > 0
        # neighbours along each ring among the usable edges (zero-length edges skipped)
        self._next: np.ndarray = np.full(len(self.rings), -1)
        self._prev: np.ndarray = np.full(len(self.rings), -1)
        for ring_id in range(len(rings)):
            idx = np.flatnonzero((self.rings == ring_id) & self.usable)
            self._next[idx] = np.roll(idx, -1)
            self._prev[idx] = np.roll(idx, 1)
        with np.errstate(invalid="ignore", divide="ignore"):
            t = np.where(self.usable[:, None], d / np.where(self.usable, self.lengths, 1)[:, None],
                         0.0)
        self.tangents = t
        # outward normal: right of the tangent on a counter-clockwise outer ring; a hole's
        # outward normal points into the hole, i.e. left of a counter-clockwise hole ring
        sign = np.array([1.0 if areas[0] > 0 else -1.0]
                        + [-1.0 if a > 0 else 1.0 for a in areas[1:]])[self.rings]
        self.normals = sign[:, None] * np.stack([t[:, 1], -t[:, 0]], axis=1)
        self._object_left = sign   # +1 where the object lies left of the edge's direction
        self.area = float(shp.area)
        c = shp.centroid
        self.centroid = np.array([c.x, c.y])
        lo, hi = np.min(outer, axis=0), np.max(outer, axis=0)
        #: characteristic size: the diagonal of the bounding box
        self.size = float(np.hypot(*(hi - lo)))

    # ---------------------------------------------------------------- access
    @cached_property
    def radius(self) -> float:
        """The part's radius: the largest distance from the centroid to a vertex of the
        outer ring (:func:`fcgrasp.model.quality.characteristic_length`), computed once."""
        from .quality import characteristic_length

        return characteristic_length(self.vertices, self.centroid)

    @cached_property
    def edge_floats(self) -> list[tuple[float, ...]]:
        """Per edge ``(ax, ay, bx, by, nx, ny)`` as Python floats: its start, its end
        along the tangent, and its outward normal, for the per-call paths (one edge pair
        in plain floats: no numpy call per edge), computed once."""
        b = self.starts + self.lengths[:, None] * self.tangents
        return [tuple(r) for r in np.column_stack([self.starts, b, self.normals]).tolist()]

    @property
    def n_edges(self) -> int:
        """Number of edges, zero-length ones included."""
        return int(self.starts.shape[0])

    def edge(self, i: int) -> Edge:
        """Edge ``i`` (input numbering)."""
        if not isinstance(i, (int, np.integer)) or isinstance(i, bool):
            raise TypeError(f"edge index must be an integer, got {i!r}")
        if not 0 <= i < self.n_edges:
            raise ValueError(f"edge index must be in [0, {self.n_edges - 1}], got {i}")
        return Edge(int(i), self.starts[i], self.ends[i], self.tangents[i], self.normals[i],
                    float(self.lengths[i]), int(self.rings[i]))

    @property
    def edges(self) -> list[Edge]:
        return [self.edge(i) for i in range(self.n_edges)]

    def check_edges(self, edges: Any, name: str = "edges") -> tuple[int, ...]:
        """Validate a tuple of edge indices of this polygon (usable edges only)."""
        try:
            idx = tuple(int(e) for e in edges)
        except (TypeError, ValueError) as exc:
            raise TypeError(f"{name} must be a sequence of edge indices, got {edges!r}") from exc
        for e, raw in zip(idx, edges, strict=True):
            if isinstance(raw, bool) or (isinstance(raw, float) and raw != int(raw)):
                raise TypeError(f"{name} must hold integers, got {edges!r}")
            if not 0 <= e < self.n_edges:
                raise ValueError(f"{name} holds {e}, not an edge of this polygon "
                                 f"(0 to {self.n_edges - 1})")
            if not self.usable[e]:
                raise ValueError(f"{name} holds {e}, a zero-length edge (duplicate vertex)")
        return idx

    def check_stretch(self, edges: Any, name: str = "stretch") -> tuple[int, ...]:
        """Validate a stretch: consecutive usable edges of one ring, in ring order
        (wrapping around), not the whole ring.

        >>> Polygon([[0, 0], [4, 0], [4, 3], [0, 3]]).check_stretch([3, 0, 1])
        (3, 0, 1)
        """
        idx = self.check_edges(edges, name)
        ring = np.flatnonzero((self.rings == self.rings[idx[0]]) & self.usable) if idx else ()
        if not idx or len(idx) >= len(ring) or any(
                int(self._next[a]) != b for a, b in zip(idx, idx[1:], strict=False)):
            raise ValueError(f"{name} must be consecutive edges of one ring in ring order "
                             f"(not all of it), got {list(edges)!r}")
        return idx

    def vertex_normals(self) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Per edge end vertex: (point, normal of the incoming edge, of the outgoing edge).

        Row ``i`` describes the vertex at the end of edge ``i`` (skipping zero-length edges).
        """
        return self.ends, self.normals, self.normals[np.where(self.usable, self._next, 0)]

    def previous_edge(self, k: int) -> int:
        """The usable edge that ends where edge ``k`` starts (same ring)."""
        return int(self._prev[k])

    def next_edge(self, k: int) -> int:
        """The usable edge that starts where edge ``k`` ends (same ring)."""
        return int(self._next[k])

    def convex_vertices(self) -> FloatArray:
        """Boolean per edge: is the vertex at the end of the edge convex for the object?"""
        _, n_in, n_out = self.vertex_normals()
        # walking with the object on the left, normals turn counter-clockwise at convex
        # vertices; in input order that walk is reversed where the object is on the right
        turn = (n_in[:, 0] * n_out[:, 1] - n_in[:, 1] * n_out[:, 0]) * self._object_left
        return cast("FloatArray", (turn > 0) & self.usable)

    def distance_to_edges(self, point: ArrayLike) -> FloatArray:
        """Distance from ``point`` to every edge, shape (E,) (inf for zero-length edges)."""
        pt = np.asarray(point, dtype=float)
        d = self.ends - self.starts
        ln2 = np.maximum(np.sum(d * d, axis=1), TINY)
        t = np.clip(np.sum((pt - self.starts) * d, axis=1) / ln2, 0, 1)
        proj = self.starts + t[:, None] * d
        out = np.hypot(*(proj - pt).T)
        return np.where(self.usable, out, np.inf)

    def convex_corner(self, vertex: int) -> int:
        """Check that ``vertex`` (the start of edge ``vertex``) is a convex corner, where a
        soft finger can sit; return the edge that ends there."""
        if not self.usable[vertex]:
            raise ValueError(f"vertex {vertex} starts a zero-length edge: use the next vertex")
        prev = self.previous_edge(vertex)
        if not self.convex_vertices()[prev]:
            raise ValueError(f"vertex {vertex} is not a convex vertex of the part: a soft "
                             f"finger needs a convex corner")
        return prev

    def soft_finger_at(self, vertex: int, mu: float) -> Any:
        """A soft finger (figure 4.e) on the convex vertex ``vertex`` (the start of edge
        ``vertex``), spanning a twentieth of each adjacent edge."""
        from ..core.contacts import SoftFinger

        prev = self.convex_corner(vertex)
        v = self.starts[vertex]
        a = v - 0.05 * self.lengths[prev] * self.tangents[prev]
        b = v + 0.05 * self.lengths[vertex] * self.tangents[vertex]
        return SoftFinger.corner(a, v, b, self.normals[prev], self.normals[vertex], mu)

    def to_shapely(self) -> ShapelyPolygon:
        return self._shapely

    def contains(self, points: ArrayLike) -> np.ndarray:
        """Whether points lie in the part (boundary included)."""
        pts = np.asarray(points, dtype=float)
        return cast("np.ndarray", shapely.covers(self._shapely, shapely.points(pts)))

    def __repr__(self) -> str:
        return f"Polygon({self.vertices.tolist()}, holes={[h.tolist() for h in self.holes]})"


def _from_rings(coordinates: Any) -> Polygon:
    """A Polygon of GeoJSON rings (each ring's last point repeating its first)."""
    rings = [np.asarray(r, dtype=float)[:-1, :2] for r in coordinates]
    return Polygon(rings[0], rings[1:])


def check_polygon(value: Any, name: str = "polygon") -> Polygon:
    """``value`` as a :class:`Polygon`: a Polygon as it is; a shapely Polygon, or any
    object with a ``__geo_interface__`` of type Polygon (GeoJSON's coordinates, the last
    point repeating the first), converted; a MultiPolygon's largest polygon (as the
    readers take a file's largest part); an array of vertices, shape (n, 2), the
    outline.  Anything else: a :class:`TypeError` naming the argument and what it
    received (the one check of every function taking a part).

    >>> import shapely
    >>> check_polygon(shapely.box(0, 0, 10, 5)).n_edges
    4
    >>> check_polygon(np.array([[0, 0], [4, 0], [0, 3]])).n_edges
    3
    >>> check_polygon(shapely.MultiPolygon([shapely.box(0, 0, 1, 1),
    ...                                     shapely.box(5, 0, 9, 4)])).area
    16.0
    """
    if isinstance(value, Polygon):
        return value
    if isinstance(value, np.ndarray) and value.ndim == 2 and value.shape[1] == 2:
        return Polygon(value)
    geo = getattr(value, "__geo_interface__", None)
    if isinstance(geo, dict) and geo.get("type") == "Polygon" and geo.get("coordinates"):
        return _from_rings(geo["coordinates"])
    if isinstance(geo, dict) and geo.get("type") == "MultiPolygon" and geo.get("coordinates"):
        return max((_from_rings(c) for c in geo["coordinates"] if c),
                   key=lambda p: p.area)
    what = type(value).__name__
    if isinstance(geo, dict):
        what += f" (a {geo.get('type')} geometry)"
    raise TypeError(f"{name} must be a fcgrasp Polygon, a shapely Polygon or MultiPolygon, "
                    f"an object with such a __geo_interface__ or an array of vertices of "
                    f"shape (n, 2), got {what}")
