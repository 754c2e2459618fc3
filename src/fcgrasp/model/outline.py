"""Outlines from drawings: rings filled by a fill rule, and outlines cleaned for planning.

Drawings describe a part by closed curves, not by a polygon with holes.  :func:`fill_rings`
turns any set of rings into the polygons a viewer would fill: SVG's ``nonzero`` and
``evenodd`` rules, and even-odd nesting for CAD loops and traced images (a loop inside a
part is a hole, a loop inside that hole a new part).  Rings may nest, touch or cross.

:func:`clean_outline` prepares a polygon for planning.  A straight side drawn as several
pieces (a CAD export, a flattened path, a traced image) would cap every region at the
length of a piece, and rank the same grasp again on each neighbouring piece; so runs of
collinear edges are merged and edges shorter than the tolerance dropped.  The tolerance is
:data:`CLEAN_TOL` times the part's size: a vertex goes when it lies within that distance of
the segment joining its neighbours, which is far below any flattening tolerance (a
flattened arc's vertices lie about four flattening tolerances off that segment) and below
any manufacturing precision (0.01 um on a 100 mm part).  :func:`simplify_outline` is the
coarser, optional Douglas-Peucker simplification (``--simplify``), topology preserved.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, cast

import numpy as np
import shapely
from shapely.geometry import LineString
from shapely.geometry import Polygon as ShapelyPolygon

from ..core._checks import FloatArray, check_scalar
from ..core._geom import signed_area
from ..core.tolerances import CLEAN_TOL, MAX_MAGNITUDE
from .polygon import Polygon, check_polygon

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = ["CLEAN_TOL", "FILL_RULES", "fill_rings", "winding_numbers", "clean_ring",
           "clean_outline", "simplify_outline"]

#: Fill rules of :func:`fill_rings` (SVG's ``fill-rule``).
FILL_RULES = ("nonzero", "evenodd")


def winding_numbers(points: ArrayLike, ring: ArrayLike) -> np.ndarray:
    """Winding number of the closed ring around each point, shape (P,) (int).

    Positive for counter-clockwise rings; a point on the ring gets an arbitrary side.

    >>> winding_numbers([[0.5, 0.5], [2, 2]], [[0, 0], [1, 0], [1, 1], [0, 1]]).tolist()
    [1, 0]
    """
    p = np.asarray(points, dtype=float).reshape(-1, 2)
    a = np.asarray(ring, dtype=float)
    b = np.roll(a, -1, axis=0)
    px, py = p[:, 0:1], p[:, 1:2]
    side = (b[:, 0] - a[:, 0]) * (py - a[:, 1]) - (px - a[:, 0]) * (b[:, 1] - a[:, 1])
    up = (a[:, 1] <= py) & (b[:, 1] > py) & (side > 0)
    down = (a[:, 1] > py) & (b[:, 1] <= py) & (side < 0)
    return cast("np.ndarray", (up.sum(axis=1) - down.sum(axis=1)).astype(int))


def _ring_ok(r: FloatArray) -> bool:
    return len(np.unique(r, axis=0)) >= 3 and abs(signed_area(r)) > 0


def _check_range(ring: FloatArray) -> None:
    """A ring with a coordinate that is not a number or beyond fcgrasp's documented
    range (:data:`~fcgrasp.core.tolerances.MAX_MAGNITUDE`) is an error naming it (its
    area would overflow, and the ring would drop out unsaid)."""
    big = float(np.max(np.abs(ring))) if ring.size else 0.0
    if not big <= MAX_MAGNITUDE:
        raise ValueError(f"a ring has a coordinate of magnitude {big:.3g}, above "
                         f"fcgrasp's documented range ({MAX_MAGNITUDE:g}): rescale the part")


def fill_rings(rings: list[Any], rule: str = "evenodd") -> list[ShapelyPolygon]:
    """The polygons a viewer fills for these closed rings under a fill rule.

    Parameters
    ----------
    rings : list of array_like, shape (m, 2)
        Closed rings (the last vertex need not repeat the first), in any orientation; they
        may nest, touch or cross.
    rule : {"nonzero", "evenodd"}
        A point is filled when the sum of the rings' winding numbers around it is non-zero
        (``nonzero``, SVG's default), or odd (``evenodd``: nesting alternates part, hole,
        part; the rule for CAD loops and traced images).

    Returns
    -------
    list of shapely.Polygon
        The filled pieces, largest first.  A single simple ring comes back unchanged
        (same start and order of vertices).

    Examples
    --------
    >>> sq = lambda s, o=0: [[o, o], [o + s, o], [o + s, o + s], [o, o + s]]
    >>> [p.area for p in fill_rings([sq(4), sq(2, 1)], "evenodd")]
    [12.0]
    >>> [p.area for p in fill_rings([sq(4), sq(2, 1)], "nonzero")]    # same orientation
    [16.0]
    """
    if rule not in FILL_RULES:
        raise ValueError(f"rule must be one of {', '.join(FILL_RULES)}, got {rule!r}")
    arrs = []
    for r in rings:
        a = np.asarray(r, dtype=float).reshape(-1, 2)
        if len(a) >= 2 and np.array_equal(a[0], a[-1]):
            a = a[:-1]
        _check_range(a)
        if len(a) >= 3 and _ring_ok(a):
            arrs.append(a)
    if not arrs:
        return []
    if len(arrs) == 1:
        single = ShapelyPolygon(arrs[0])
        if single.is_valid:
            return [single]
    lines = shapely.unary_union([LineString(np.vstack([a, a[:1]])) for a in arrs])
    faces = list(shapely.get_parts(shapely.polygonize(shapely.get_parts(lines))))
    if not faces:
        return []
    pts = np.array([f.representative_point().coords[0] for f in faces])
    wind = np.zeros(len(faces), dtype=int)
    for a in arrs:
        wind += winding_numbers(pts, a)
    filled = wind != 0 if rule == "nonzero" else wind % 2 == 1
    kept = [f for f, k in zip(faces, filled, strict=True) if k]
    if not kept:
        return []
    union = shapely.unary_union(kept)
    parts = [p for p in shapely.get_parts(union) if p.geom_type == "Polygon" and p.area > 0]
    return sorted(parts, key=lambda p: -p.area)


def clean_ring(ring: ArrayLike, tol: float) -> FloatArray:
    """The ring without the vertices that lie within ``tol`` of the segment joining their
    neighbours (collinear runs merged, edges shorter than ``tol`` dropped).

    Vertices are removed a non-adjacent set at a time, each judged against its current
    neighbours, until none is left to remove; at least three vertices stay.

    >>> clean_ring([[0, 0], [1, 0], [2, 0], [2, 1], [0, 1]], 1e-9).tolist()
    [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]
    """
    r = np.asarray(ring, dtype=float)
    tol = check_scalar(tol, "tol", nonnegative=True)
    while len(r) > 3:
        prev, nxt = np.roll(r, 1, axis=0), np.roll(r, -1, axis=0)
        d = nxt - prev
        ln2 = np.sum(d * d, axis=1)
        t = np.clip(np.sum((r - prev) * d, axis=1) / np.where(ln2 > 0, ln2, 1.0), 0.0, 1.0)
        dev = np.hypot(*(prev + t[:, None] * d - r).T)
        cand = np.flatnonzero(dev <= tol)
        if cand.size == 0:
            break
        drop = np.zeros(len(r), dtype=bool)
        for i in cand[np.argsort(dev[cand], kind="stable")]:
            if not drop[i - 1] and not drop[(i + 1) % len(r)]:
                drop[i] = True
        if len(r) - drop.sum() < 3:
            keep_idx = np.flatnonzero(~drop)
            extra = np.flatnonzero(drop)[: 3 - len(keep_idx)]
            drop[extra] = False
        if not drop.any():
            break
        r = r[~drop]
    return r


def clean_outline(polygon: Polygon, tol: float | None = None) -> tuple[Polygon, int]:
    """The polygon with collinear runs merged and sub-tolerance edges dropped, on every
    ring, and the number of vertices removed.

    ``tol`` is a length in the polygon's units (default :data:`CLEAN_TOL` times its size).
    Edge numbers change when vertices go; a polygon with nothing to clean comes back as
    is.  If cleaning a ring would make the outline invalid, that ring is kept as it was.

    >>> p = Polygon([[0, 0], [1, 0], [2, 0], [2, 1], [0, 1]])
    >>> q, removed = clean_outline(p)
    >>> q.n_edges, removed
    (4, 1)
    """
    polygon = check_polygon(polygon)
    tol = CLEAN_TOL * polygon.size if tol is None else check_scalar(tol, "tol", nonnegative=True)
    rings = [polygon.vertices, *polygon.holes]
    cleaned = [clean_ring(r, tol) for r in rings]
    removed = sum(len(a) - len(b) for a, b in zip(rings, cleaned, strict=True))
    if removed == 0:
        return polygon, 0
    try:
        return Polygon(cleaned[0], cleaned[1:]), removed
    except ValueError:
        # keep the rings whose cleaning broke the outline as they were, one at a time
        out = list(rings)
        for k, c in enumerate(cleaned):
            trial = [*out[:k], c, *out[k + 1:]]
            try:
                Polygon(trial[0], trial[1:])
                out = trial
            except ValueError:
                pass
        removed = sum(len(a) - len(b) for a, b in zip(rings, out, strict=True))
        return Polygon(out[0], out[1:]), removed


def simplify_outline(polygon: Polygon, tol: float) -> Polygon:
    """Douglas-Peucker simplification of every ring to within ``tol`` (the polygon's
    units), topology preserved (shapely's ``simplify(preserve_topology=True)``).

    >>> p = Polygon([[0, 0], [1, 0.01], [2, 0], [2, 1], [0, 1]])
    >>> simplify_outline(p, 0.1).n_edges
    4
    """
    polygon = check_polygon(polygon)
    tol = check_scalar(tol, "tol", nonnegative=True)
    if tol >= polygon.size:
        raise ValueError(f"simplify tolerance {tol:g} is not below the part's size "
                         f"({polygon.size:.6g}): nothing of the outline would be kept")
    s = shapely.simplify(polygon.to_shapely(), tol, preserve_topology=True)
    if s.is_empty or s.geom_type != "Polygon":
        raise ValueError(f"simplifying with tol {tol:g} leaves no polygon: use a smaller "
                         f"tolerance")
    return Polygon(np.asarray(s.exterior.coords), [np.asarray(h.coords) for h in s.interiors])
