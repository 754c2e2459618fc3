r"""A parallel jaw with flat pads on a solid: the region of closing axes on a
pair of parallel faces such that the pads close flush on both faces and the grasp holds.

**The model.**  The jaw closes two round flat pads (diameter ``pad``) along an axis
``d``.  A pad lies flush on a planar facet only when the facet faces the pad, so the jaw
grasps two **opposite parallel facets** ``A`` and ``B`` (inward normals ``n_A`` and
``n_B = -n_A`` within :data:`~fcgrasp.core.tolerances.PARALLEL_FACETS` radians) a
distance ``h`` apart, ``d = n_A`` (the bisector when they are within the tolerance),
with ``h`` inside the jaw's stroke.  The axis meets ``A`` at ``x`` and ``B`` at ``x + h
d``; each pad presses flush on its facet with friction ``mu``, an area contact that
resists a torsion about ``d`` (a soft finger, as the paper's conclusion names it).  Two
soft contacts are in force closure exactly when the segment joining them lies strictly
inside both friction cones (:func:`~fcgrasp.spatial.closure.two_soft_closure`); the
segment is along ``d``, inside both cones by ``atan(mu)`` less the facets' tilt, so
every axis point ``x`` in both facets holds when ``atan(mu) - margin`` exceeds the
tilt.

**The region** of axis points, in ``A``'s plane, is ``A`` intersected with ``B``
projected along ``d``, less every point whose pad would meet the part before its facet:
the part outside each facet's plane (on its pad's side: the triangles clipped to that
half-space, projected along ``d``) grown by the pad's radius (a round pad centred at
``x`` covers the disc of radius ``pad / 2``).  The jaw's fingers beyond the pads are not
modelled.  On a convex part nothing lies outside a face's plane, so the region is the
overlap of the two faces.  Plans are ranked by the region's **inscribed radius** (how
far the axis may land from the region's centre in any direction), and carry the
region's area and the opening ``h``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, cast

import numpy as np

from ..core._checks import FloatArray, check_int, check_scalar
from ..core.budget import PlanList, exhausted, incomplete, stop_reason
from ..core.tolerances import INRADIUS_STEP, PARALLEL_FACETS, PLANAR_TOL, ROUND_TOL, TOL
from ._pieces import inscribed_radius_bound
from .alternatives import MEASURE, SolidPlan
from .regions import DEFAULT_MARGIN_DEG, checked_cone
from .solid import Facet, Solid

__all__ = ["SolidJawPlan", "solid_jaw_plans", "solid_jaw_region", "region_fields",
           "largest_piece"]


@dataclass(frozen=True)
class SolidJawPlan(SolidPlan):
    """A parallel jaw's region on two opposite facets: ``facets`` (``A``, ``B``), the
    closing ``axis`` (``A``'s inward normal), the ``opening`` between the facets,
    ``radius`` (the region's inscribed radius), ``area``, ``centers`` (2, 3: the best
    axis point on ``A`` and on ``B``), ``regions`` (two rings of 3-D points: the outer
    boundary of the region on ``A`` and on ``B``), ``holes`` (for each region, the rings
    of the holes in it: closing axes through a hole meet no part, and are not in the
    region), ``surface_triangles`` (each region, holes left out, as triangles (k, 3, 3)),
    inward ``normals`` (2, 3), ``mu``, ``margin``, ``pad``."""

    facets: tuple[int, int]
    axis: FloatArray = field(repr=False)
    opening: float = 0.0
    radius: float = 0.0
    area: float = 0.0
    centers: FloatArray = field(default_factory=lambda: np.zeros((2, 3)), repr=False)
    regions: tuple[FloatArray, FloatArray] = field(default=(np.zeros((0, 3)),
                                                            np.zeros((0, 3))), repr=False)
    normals: FloatArray = field(default_factory=lambda: np.zeros((2, 3)), repr=False)
    mu: float = 0.0
    margin: float = DEFAULT_MARGIN_DEG
    pad: float = 0.0
    similar: tuple[tuple[int, ...], ...] = field(default=(), repr=False, compare=False)
    holes: tuple[tuple[FloatArray, ...], tuple[FloatArray, ...]] = field(
        default=((), ()), repr=False)
    surface_triangles: tuple[FloatArray, ...] = field(default=(), repr=False)
    #: with a hand (:mod:`fcgrasp.grippers.jaw._solid_pick`): the pick of the region's
    #: centre (pose, approach, retreat), in the JSON beside the region
    pick: dict[str, Any] | None = field(default=None, repr=False, compare=False)

    def to_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {"facets": list(self.facets), "axis": self.axis.tolist(),
                             "opening": self.opening, "radius": self.radius, "area": self.area,
                             "centers": self.centers.tolist(),
                             "regions": [r.tolist() for r in self.regions],
                             "holes": [[h.tolist() for h in side] for side in self.holes],
                             "surface_triangles": [t.tolist()
                                                   for t in self.surface_triangles],
                             "normals": (-self.normals).tolist(), "mu": self.mu,
                             "margin_deg": self.margin, "pad": self.pad,
                             "contact_type": "jaw", **(self.pick or {})}
        return self._with_similar(d)


def _check(solid: Any, stroke: Any, pad: Any, mu: Any, margin: Any
           ) -> tuple[tuple[float, float], float, float, float, float]:
    if not isinstance(solid, Solid):
        raise TypeError(f"solid must be a fcgrasp Solid, got {type(solid).__name__}")
    try:
        lo, hi = (float(v) for v in stroke)
    except (TypeError, ValueError):
        raise ValueError(f"stroke must be (min_opening, max_opening), got {stroke!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 <= lo <= hi):
        raise ValueError(f"stroke must have 0 <= min_opening <= max_opening, got {stroke!r}")
    pad_v = check_scalar(pad, "pad", nonnegative=True)
    return (lo, hi), pad_v, *checked_cone(mu, margin)


def _opposite_pairs(solid: Solid, tilt: float) -> list[tuple[int, int]]:
    """Pairs of facets (lower index first) whose inward normals are opposite within
    ``tilt`` radians, the second in front of the first (across the part)."""
    from scipy.spatial import cKDTree

    normals = np.array([f.normal for f in solid.facets])
    # the candidates by a tree of the normals (a mesh of thousands of facets: no F x F
    # matrix), then the exact test on each: the same pairs, in the same order
    reach = math.sqrt(max(0.0, 2.0 - 2.0 * math.cos(tilt))) * (1 + TOL) + ROUND_TOL
    near = cKDTree(normals).query_ball_point(-normals, reach)
    cand = sorted((i, j) for i, js in enumerate(near) for j in js if j > i)
    keep = [(i, j) for i, j in cand if -(normals[i] @ normals[j]) >= math.cos(tilt)]
    out = []
    for i, j in keep:
        a, b = solid.facets[i], solid.facets[j]
        if (b.origin - a.origin) @ a.normal > 0:
            out.append((i, j))
    return out


def _facing(solid: Solid, pairs: list[tuple[int, int]], stroke: tuple[float, float]
            ) -> list[tuple[int, int]]:
    """The pairs that can give a region (necessary conditions, all pairs at once): the
    opening along the pair's axis within the stroke (with the rounding of
    :func:`_region`'s), and the two facets' bounding circles overlapping seen along the
    axis (else the facets' shadows do not meet).  A part with hundreds of holes has
    hundreds of thousands of opposite pairs of wall facets, most far apart."""
    if not pairs:
        return pairs
    facets = solid.facets
    ij = np.array(pairs, dtype=np.int64)
    normal = np.array([f.normal for f in facets])
    origin = np.array([f.origin for f in facets])
    centre, radius = np.empty((len(facets), 3)), np.empty(len(facets))
    for k, f in enumerate(facets):
        ring = np.asarray(f.polygon.exterior.coords)[:-1]
        c = ring.mean(axis=0)
        centre[k] = f.to_3d(c)
        radius[k] = float(np.max(np.hypot(*(ring - c).T)))
    a, b = ij[:, 0], ij[:, 1]
    axis = normal[a] - normal[b]
    axis /= np.linalg.norm(axis, axis=1)[:, None]
    h = np.einsum("ij,ij->i", origin[b] - origin[a], axis)
    d = centre[b] - centre[a]
    across = np.linalg.norm(d - np.einsum("ij,ij->i", d, axis)[:, None] * axis, axis=1)
    slack = PLANAR_TOL * solid.size
    ok = (h >= stroke[0] - slack) & (h <= stroke[1] + slack) \
        & (across <= radius[a] + radius[b] + slack)
    return [pairs[k] for k in np.flatnonzero(ok)]


def _outside(solid: Solid, facet: Facet, level: float, near: Any = None) -> Any:
    """The part outside ``facet``'s plane (its pad's side, beyond ``level`` below it),
    projected into the facet's 2-D frame along its normal: the triangles clipped to
    that half-space (shapely, a union), or None.  ``near(tris)``: a mask of the
    triangles (T, 3, 3) that can matter (their projections meet the region's window);
    the others are left out."""
    import shapely

    tris = solid.triangles                                              # (T, 3, 3)
    s = (tris - facet.origin) @ facet.normal                            # (T, 3)
    hit, on_side = _sides(s, level)
    if near is not None and hit.any():
        hit[hit] = near(tris[hit])
    if not hit.any():
        return None
    tris, s = tris[hit], s[hit]
    # a triangle wholly on the pad's side is its own shadow (the clip keeps its three
    # corners in order): those are made at once, the few the plane cuts one by one, in
    # the triangles' order
    whole = on_side[hit]
    shadows = np.empty(len(tris), dtype=object)
    shadows[whole] = shapely.polygons(facet.to_2d(tris[whole].reshape(-1, 3))
                                      .reshape(-1, 3, 2))
    for k in np.flatnonzero(~whole):
        ring = _clip(tris[k], s[k])
        shadows[k] = shapely.Polygon(facet.to_2d(ring)) if len(ring) >= 3 else None
    made = np.array([p is not None for p in shadows], dtype=bool)
    keep = np.zeros(len(tris), dtype=bool)
    keep[made] = shapely.is_valid(shadows[made]) & (shapely.area(shadows[made]) > 0)
    polys = list(shadows[keep])
    # united on a grid of the rounding (GEOS's snap-rounding overlay): GEOS 3.14's
    # floating overlay can lose whole triangles of a mesh's shadow that share sides
    # with their neighbours (on a 2,048-triangle torus one union of ten shadows keeps
    # 44.7 of their 53.1 mm^2), and a pad would then be placed on the part
    return shapely.union_all(polys, grid_size=ROUND_TOL * solid.size) if polys else None


def _sides(height: FloatArray, level: float) -> tuple[np.ndarray, np.ndarray]:
    """Of triangles whose corners are ``height`` (T, 3) above a facet's plane (its pad's
    side below): those with a corner beyond ``level`` on the pad's side, and those
    wholly on it.  Column by column: numpy's reductions along an axis of three cost ten
    times as much."""
    s0, s1, s2 = height[:, 0], height[:, 1], height[:, 2]
    return np.minimum(np.minimum(s0, s1), s2) < -level, np.maximum(np.maximum(s0, s1), s2) <= 0


#: Whether :func:`_region` first tries to show its overlap covered by one triangle's
#: grown shadow (:func:`_one_shadow_covers`: then no region, without the union of the
#: shadows); False: every pair's shadows united and cut out (the reference).
SHADOW_SCREEN = True


#: Points per quarter circle of shapely's buffer (its default): its polygon holds the
#: exact buffer of its radius times ``cos(pi / (4 * BUFFER_QUAD_SEGS))``, so the cut
#: buffers by the pad's radius over that.
BUFFER_QUAD_SEGS = 8


def _one_shadow_covers(solid: Solid, facets: tuple[Facet, Facet], to_a: tuple[Any, Any],
                       region: Any, level: float, pad: float, shift: FloatArray) -> bool:
    """Whether :func:`_region`'s cut leaves nothing of ``region`` (a polygon in the first
    facet's plane), shown by one triangle wholly on a pad's side of its facet (its
    shadow, ``to_a`` of each facet: into the first facet's frame, a triangle, convex):
    every vertex of the region within the pad's radius of that shadow, less
    :data:`PLANAR_TOL` of the part's size (which also holds the rounding of the
    triangles' sides of the plane, read here from the vertices').  The distance to a
    convex set is convex, so the whole region (inside its vertices' hull) is then
    within the pad's radius of the shadow, inside the buffer the cut takes away (which
    holds that radius's: :data:`BUFFER_QUAD_SEGS`).  The triangles near the region on
    each facet (``shift``: from the first facet to the second along the axis) are
    tried first, within the region's radius and the pad's of its centre
    (:attr:`~fcgrasp.spatial.solid.Solid.triangle_tree`: a few of a large mesh's),
    then every triangle.  False says nothing (the cut then decides)."""
    import shapely

    reach = pad / 2 - PLANAR_TOL * solid.size
    if reach <= 0:
        return False
    rings = [np.asarray(p.exterior.coords, float) for p in shapely.get_parts(region)
             if isinstance(p, shapely.Polygon)]
    if not rings:
        return False
    pts = np.concatenate(rings)
    box = pts.min(axis=0), pts.max(axis=0)
    mid = (box[0] + box[1]) / 2
    tree, spread = solid.triangle_tree
    ball = float(np.hypot(*(box[1] - box[0]))) / 2 + reach + spread
    verts, faces = solid.vertices, solid.faces
    # the triangles about the region first (where a curved part rises beyond the
    # facet's plane), then every one (a wall across a pocket)
    near = [np.asarray(tree.query_ball_point(facets[0].to_3d(mid) + moved, ball), int)
            for moved in (0.0, shift)]
    for every in (False, True):
        for facet, into, rows in zip(facets, to_a, near, strict=True):
            if (every or len(rows)) and _a_shadow_covers(
                    verts, faces if every else faces[rows], facet, into, pts, box, level,
                    reach, solid.size, every):
                return True
    return False


def _a_shadow_covers(verts: FloatArray, rows: np.ndarray, facet: Facet, into: Any,
                     pts: FloatArray, box: tuple[FloatArray, FloatArray], level: float,
                     reach: float, size: float, every: bool) -> bool:
    """:func:`_one_shadow_covers` of the triangles ``rows`` (their corners' indices into
    ``verts``; ``every``: all the mesh's, read through its vertices once) on the side
    of ``facet``; ``box``: the least and greatest corner of the region's vertices
    ``pts``."""
    if every:
        height = (verts @ facet.normal - facet.origin @ facet.normal)[rows]     # (m, 3)
    else:
        corners = verts[rows]                                               # (m, 3, 3)
        height = corners @ facet.normal - facet.origin @ facet.normal
    hit, on_side = _sides(height, level)
    whole = hit & on_side
    if not whole.any():
        return False
    if every:
        flat = np.asarray(into(verts))[rows[whole]]                         # (m, 3, 2)
    else:
        flat = np.asarray(into(corners[whole].reshape(-1, 3))).reshape(-1, 3, 2)
    c0, c1, c2 = flat[:, 0], flat[:, 1], flat[:, 2]                         # (m, 2) each
    lo, hi = box
    low = np.minimum(np.minimum(c0, c1), c2) - reach
    high = np.maximum(np.maximum(c0, c1), c2) + reach
    # a shadow whose box grown by the reach does not hold the region's box misses some
    # vertex by more than the reach
    held = (low[:, 0] <= lo[0]) & (low[:, 1] <= lo[1]) & (high[:, 0] >= hi[0]) \
        & (high[:, 1] >= hi[1])
    return bool(held.any()) and bool(_within(
        pts, np.stack([c0[held], c1[held], c2[held]], axis=1), reach, size).any())


def _within(pts: FloatArray, tris: FloatArray, reach: float, size: float) -> np.ndarray:
    """For each triangle (m, 3, 2) of positive area (above the rounding of ``size``),
    whether every point (k, 2) is within ``reach`` of it (inside, or that near an
    edge)."""
    A, B, C = tris[:, 0], tris[:, 1], tris[:, 2]
    area = (B[:, 0] - A[:, 0]) * (C[:, 1] - A[:, 1]) - (B[:, 1] - A[:, 1]) * (C[:, 0] - A[:, 0])
    far = np.full((len(tris), len(pts)), np.inf)
    side = []
    for U, V in ((A, B), (B, C), (C, A)):
        e = V - U                                               # (m, 2)
        w = pts[None] - U[:, None]                              # (m, k, 2)
        ee = np.einsum("ij,ij->i", e, e)
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.clip(np.einsum("mkj,mj->mk", w, e) / ee[:, None], 0.0, 1.0)
        d = w - t[..., None] * e[:, None]
        far = np.minimum(far, np.hypot(d[..., 0], d[..., 1]))
        side.append(e[:, None, 0] * w[..., 1] - e[:, None, 1] * w[..., 0])
    c = np.stack(side)                                          # (3, m, k)
    inside = np.all(c >= 0, axis=0) | np.all(c <= 0, axis=0)
    far[inside] = 0.0
    ok: np.ndarray = (np.abs(area) > (TOL * size) ** 2) & np.all(far <= reach, axis=1)
    return ok


def _clip(tri: FloatArray, level: FloatArray) -> FloatArray:
    """The part of a triangle where ``level <= 0`` (Sutherland-Hodgman on one plane)."""
    out = []
    for k in range(3):
        p, q = tri[k], tri[(k + 1) % 3]
        a, b = level[k], level[(k + 1) % 3]
        if a <= 0:
            out.append(p)
        if (a < 0 < b) or (b < 0 < a):
            out.append(p + (q - p) * (a / (a - b)))
    return np.array(out)


def largest_piece(region: Any) -> Any:
    """The part of a (multi)polygon with the largest inscribed circle."""
    import shapely

    parts = list(region.geoms) if hasattr(region, "geoms") else [region]
    parts = [p for p in parts if isinstance(p, shapely.Polygon) and p.area > 0]
    if not parts:
        return None, 0.0, None
    best = None
    for p in parts:
        lo_x, lo_y, hi_x, hi_y = p.bounds
        tol = INRADIUS_STEP * max(hi_x - lo_x, hi_y - lo_y)
        line = shapely.maximum_inscribed_circle(p, tol)
        # the centre found to within ``tol``: the radius is at least the distance to the
        # boundary from the centre returned
        centre = np.asarray(line.coords[0])
        r = float(p.boundary.distance(shapely.Point(centre)))
        if best is None or r > best[1]:
            best = (p, r, centre)
    return best


def solid_jaw_region(solid: Solid, facets: Any, stroke: Any, pad: Any, mu: Any,
                     margin: Any = DEFAULT_MARGIN_DEG) -> SolidJawPlan | None:
    """The region of closing axes (module docstring) of a parallel jaw with round pads
    of diameter ``pad`` and the given ``stroke`` on two opposite parallel facets of
    ``solid``, or None when none holds (facets not opposite, opening outside the
    stroke, friction not above the tilt, or nothing left of the overlap).

    >>> from fcgrasp.spatial.solid import demo_solid
    >>> box = demo_solid("box")                         # 40 x 20 x 10 mm
    >>> z = [f.index for f in box.facets if abs(f.normal[2]) > 0.5]
    >>> plan = solid_jaw_region(box, z, stroke=(5, 50), pad=8, mu=0.5)
    >>> plan.opening, round(plan.radius, 3), round(plan.area, 1)
    (10.0, 10.0, 800.0)
    """
    (lo, hi), pad_v, mu_v, margin_v, alpha = _check(solid, stroke, pad, mu, margin)
    try:
        i, j = (int(f) for f in facets)
    except (TypeError, ValueError):
        raise ValueError(f"facets must be two indices, got {facets!r}") from None
    n = len(solid.facets)
    if not (0 <= i < n and 0 <= j < n) or i == j:
        raise ValueError(f"facets must be two different facets in [0, {n}), got {facets!r}")
    return _region(solid, i, j, (lo, hi), pad_v, mu_v, margin_v, alpha)


def _region(solid: Solid, i: int, j: int, stroke: tuple[float, float], pad: float,
            mu: float, margin: float, alpha: float) -> SolidJawPlan | None:
    import shapely

    a, b = solid.facets[i], solid.facets[j]
    cos_tilt = float(-(a.normal @ b.normal))
    tilt = math.acos(min(1.0, cos_tilt))
    if tilt > PARALLEL_FACETS or alpha <= tilt:
        return None
    axis = a.normal - b.normal
    axis /= np.linalg.norm(axis)
    h = float((b.origin - a.origin) @ axis)
    if not stroke[0] <= h <= stroke[1]:
        return None

    def along(coords: Any) -> FloatArray:
        """Points of B's frame (..., 2) moved along the axis into A's plane and frame."""
        pts = b.to_3d(np.asarray(coords)[:, :2])
        return a.to_2d(pts - np.outer((pts - a.origin) @ a.normal, axis)
                       / float(axis @ a.normal))

    def into_a(geom: Any) -> Any:
        """Polygons of B's frame moved along the axis into A's plane and frame: every
        coordinate moved, the parts kept as they are (disjoint parts stay disjoint; an
        overlay of the moved parts, as in :func:`_outside`, can lose some), made valid
        where the move's rounding crosses rings (a hole touching its shell)."""
        parts = [p for p in shapely.get_parts(geom) if isinstance(p, shapely.Polygon)]
        moved = shapely.transform(shapely.multipolygons(parts), along)
        return moved if moved.is_valid else shapely.make_valid(moved)

    region = shapely.intersection(a.polygon, into_a(b.polygon))
    if region.is_empty:
        return None
    level = PLANAR_TOL * solid.size
    # only triangles whose shadow comes within the pad's half width of the region's box
    # can cut it (their shadows' boxes hold their clipped shadows)
    lo_x, lo_y, hi_x, hi_y = region.bounds
    grow = pad / 2 + PLANAR_TOL * solid.size

    def window(to_a: Any) -> Any:
        def near(tris: FloatArray) -> np.ndarray:
            q = to_a(tris.reshape(-1, 3)).reshape(-1, 3, 2)
            return cast("np.ndarray",
                        (q[..., 0].min(axis=1) <= hi_x + grow)
                        & (q[..., 0].max(axis=1) >= lo_x - grow)
                        & (q[..., 1].min(axis=1) <= hi_y + grow)
                        & (q[..., 1].max(axis=1) >= lo_y - grow))
        return near

    def b_into_a(pts: FloatArray) -> FloatArray:
        """3-D points projected on B's plane, then moved into A's frame."""
        return along(b.to_2d(pts))

    # the pad's radius to buffer by: shapely's buffer puts its arcs' points on the circle
    # of that radius, so that its chords stay outside the pad's (the region holds no
    # axis whose pad meets a shadow)
    grown = pad / 2 / math.cos(math.pi / (4 * BUFFER_QUAD_SEGS))
    if SHADOW_SCREEN and _one_shadow_covers(solid, (a, b), (a.to_2d, b_into_a), region,
                                            level, pad, h * axis):
        return None                     # the grown shadows cover the whole overlap
    for facet in (a, b):
        blocked = _outside(solid, facet, level,
                           window(a.to_2d if facet is a else b_into_a))
        if blocked is not None:
            if facet is b:
                blocked = into_a(blocked)
            region = shapely.difference(region, shapely.buffer(blocked, grown))
    piece, r, centre = largest_piece(region)
    if piece is None or r <= 0:
        return None
    return SolidJawPlan((i, j), axis, h, r, normals=np.stack([a.normal, b.normal]), mu=mu,
                        margin=margin, pad=pad, **region_fields(a, piece, centre, h * axis))


def region_fields(a: Facet, piece: Any, centre: Any, shift: Any) -> dict[str, Any]:
    """The fields of a :class:`SolidJawPlan` that its region decides: ``piece`` (a shapely
    polygon in facet ``a``'s plane) and its inscribed ``centre`` there, on ``a`` and moved
    by ``shift`` (3,) onto the second facet: ``area``, ``centers``, ``regions``,
    ``holes`` and ``surface_triangles``."""
    import shapely

    shift = np.asarray(shift, float)
    ca = a.to_3d(centre)
    ring_a = a.to_3d(np.asarray(piece.exterior.coords)[:-1])
    holes_a = tuple(a.to_3d(np.asarray(q.coords)[:-1]) for q in piece.interiors)
    # the region as triangles, its holes left out (what a figure or a viewer fills)
    tris = shapely.get_parts(shapely.constrained_delaunay_triangles(piece))
    flat = np.array([np.asarray(t.exterior.coords)[:3] for t in tris], float).reshape(-1, 2)
    tri_a = a.to_3d(flat).reshape(-1, 3, 3)
    return {"area": float(piece.area), "centers": np.stack([ca, ca + shift]),
            "regions": (ring_a, ring_a + shift),
            "holes": (holes_a, tuple(q + shift for q in holes_a)),
            "surface_triangles": (tri_a, tri_a + shift)}


def solid_jaw_plans(solid: Solid, stroke: Any, pad: Any, mu: Any, top: int | None = 10,
                    margin: Any = DEFAULT_MARGIN_DEG) -> PlanList:
    """The best regions of a parallel jaw on ``solid`` (module docstring), largest
    inscribed radius first: every pair of opposite parallel facets whose opening is in
    the stroke, taken by their bound (the smaller of the two facets' inscribed
    circles, an upper bound on the overlap's) until the bound cannot enter the top
    ``top`` (None: every pair).  When the time budget ends
    (:func:`fcgrasp.core.budget.deadline`), the plans above the next pair's bound are
    returned, incomplete, with that bound on every other region's radius
    (:class:`~fcgrasp.core.budget.PlanList`).

    >>> from fcgrasp.spatial.solid import demo_solid
    >>> [round(p.radius, 3) for p in solid_jaw_plans(demo_solid("box"), (5, 50), 8, 0.5)]
    [10.0, 5.0, 5.0]
    """
    import shapely

    stroke_v, pad_v, mu_v, margin_v, alpha = _check(solid, stroke, pad, mu, margin)
    if top is not None:
        top = check_int(top, "top", minimum=1)
    pairs = _facing(solid, _opposite_pairs(solid, PARALLEL_FACETS), stroke_v)
    if not pairs or alpha <= 0:
        return PlanList(measure=MEASURE)
    used = sorted({k for p in pairs for k in p})
    geoms = np.array([solid.facets[k].polygon for k in used], dtype=object)
    inradius = dict(zip(used, inscribed_radius_bound(geoms).tolist(), strict=True))
    cands = sorted(pairs, key=lambda p: (-min(inradius[p[0]], inradius[p[1]]), p))
    plans: list[SolidJawPlan] = []
    for i, j in cands:
        bound = min(inradius[i], inradius[j])
        if top is not None and len(plans) >= top and plans[top - 1].radius >= bound:
            break
        if exhausted():
            # every pair left is below its bound: the plans above it are the answer's
            # first, exactly
            proved = [p for p in plans if p.radius > bound]
            return incomplete(proved if top is None else proved[:top], stop_reason(), bound,
                              MEASURE)
        try:
            got = _region(solid, i, j, stroke_v, pad_v, mu_v, margin_v, alpha)
        except shapely.errors.GEOSException:
            # GEOS cannot build this pair's overlap (degenerate facets of a real CAD
            # mesh): no region is claimed for it
            got = None
        if got is not None:
            plans.append(got)
            plans.sort(key=lambda p: (-p.radius, p.facets))
    return PlanList(plans if top is None else plans[:top], measure=MEASURE)
