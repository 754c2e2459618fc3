"""Curved surfaces of a solid as patches: triangles grown from a seed while their normals
stay within the cone, each patch's kernel, points lifted back onto its triangles, and the
cone programs and bounds of two patches facing each other (part of
:mod:`fcgrasp.spatial.surfaces`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core._checks import FloatArray, IntArray
from ..core.tolerances import (
    SURFACE_CENTRE,
    SURFACE_STEP,
    SURFACE_TOL,
    TINY,
)
from ._pieces import Halfplanes, _ring_halfplanes
from .contacts import contact_frames
from .regions import (
    _SHRINKS,
    _cone_rows,
    _largest_last,
    _octagon_axes,
    _piece_rows,
)
from .solid import Facet, Solid

#: The most seeds of patches on one solid.
MAX_SEEDS = 32


_COS8 = math.cos(math.pi / 8)


@dataclass
class _Patch:
    """One patch (module docstring): its seed triangle and spread ``beta``, reference
    frame (a :class:`~fcgrasp.spatial.solid.Facet` across ``n_0``), triangles, heights
    ``[low, high]``, projected vertices (m, 2) and, once asked (:func:`_kernel`), its
    convex piece's half-planes and centroid (``middle``), the centre of the projection's
    largest inscribed circle and a bound on that circle's radius."""

    seed: int
    beta: float
    frame: Facet
    triangles: IntArray
    low: float
    high: float
    flat: FloatArray
    width_bound: float
    kernel: Halfplanes | None = None
    centre: FloatArray = field(default_factory=lambda: np.zeros(2))
    middle: FloatArray = field(default_factory=lambda: np.zeros(2))
    inradius: float = math.inf


def _graph(solid: Solid) -> tuple[FloatArray, list[list[int]], IntArray]:
    """The mesh's inward unit normals (F, 3), each triangle's neighbours across its
    edges, and the facet of each triangle."""
    mesh = solid.mesh
    normals = -np.asarray(mesh.face_normals, float)
    adj: list[list[int]] = [[] for _ in range(len(normals))]
    for a, b in np.asarray(mesh.face_adjacency).reshape(-1, 2).tolist():
        adj[a].append(b)
        adj[b].append(a)
    facet_of = np.empty(len(normals), np.intp)
    for f in solid.facets:
        facet_of[list(f.faces)] = f.index
    return normals, adj, facet_of


def _grow(seed: int, near: list[bool], adj: list[list[int]]) -> list[int]:
    """The triangles reached from ``seed`` across edges, every one (the seed too) ``near``
    the patch's axis (within its spread); empty when the seed is not."""
    if not near[seed]:
        return []
    seen = {seed}
    todo = [seed]
    while todo:
        for u in adj[todo.pop()]:
            if near[u] and u not in seen:
                seen.add(u)
                todo.append(u)
    return sorted(seen)


def _seeds(normals: FloatArray, adj: list[list[int]], areas: FloatArray, beta: float
           ) -> list[int]:
    """Seeds covering the mesh, largest triangle first: each triangle not in the patch
    (spread ``beta``) of a seed before it; the spread widened by half until there are
    at most :data:`MAX_SEEDS`."""
    order = np.argsort(-areas, kind="stable").tolist()
    while True:
        covered = np.zeros(len(normals), bool)
        seeds: list[int] = []
        for t in order:
            if covered[t]:
                continue
            seeds.append(t)
            if len(seeds) > MAX_SEEDS:
                break
            covered[_grow(t, (normals @ normals[t] >= math.cos(beta)).tolist(),
                          adj)] = True
        if len(seeds) <= MAX_SEEDS or beta >= math.pi / 2:
            return seeds
        beta = min(1.5 * beta, math.pi / 2)


def _patch(solid: Solid, seed: int, beta: float, triangles: list[int], normals: FloatArray,
           axis: FloatArray | None = None) -> _Patch:
    """The patch of ``triangles`` grown from ``seed`` within ``beta`` of ``axis`` (its
    ``n_0``; the seed's normal by default), drawn in the plane across ``axis`` through the
    seed's centroid; its spread the largest angle of its triangles' inward ``normals``
    (:func:`_graph`'s) from the axis (at most ``beta``)."""
    axis = normals[seed] if axis is None else axis
    beta = min(beta, math.acos(min(max(float(np.min(normals[triangles] @ axis)), -1.0),
                                   1.0)))
    vertices = np.asarray(solid.mesh.vertices, float)
    faces = np.asarray(solid.mesh.faces)
    t1, t2 = contact_frames(axis[None, :])
    axes = np.stack([t1[0], t2[0]])
    origin = vertices[faces[seed]].mean(axis=0)
    frame = Facet(seed, tuple(triangles), axis, origin, axes, None)
    used = vertices[np.unique(faces[triangles])] - origin
    height = used @ axis
    flat = used @ axes.T
    angles = np.arange(8) * math.pi / 8
    proj = flat @ np.c_[np.cos(angles), np.sin(angles)].T
    width = float(np.min(proj.max(axis=0) - proj.min(axis=0)))
    return _Patch(seed, beta, frame, np.asarray(triangles, np.intp), float(height.min()),
                  float(height.max()), flat, width / (2 * _COS8))


def _kernel(solid: Solid, patch: _Patch) -> Halfplanes:
    """A convex piece of the union ``U`` of the patch's projected triangles, as
    half-planes: ``U``'s convex hull cut at each reflex corner ``v`` (and each corner of a
    hole) by the line through ``v`` across the direction from ``U``'s inscribed centre;
    checked inside ``U`` by shapely, else ``U``'s kernel (every edge of its boundary as a
    half-plane, the polygon on its left: inside ``U`` always)."""
    import shapely
    from shapely.geometry.polygon import orient

    if patch.kernel is not None:
        return patch.kernel
    tri = (solid.triangles[patch.triangles] - patch.frame.origin) @ patch.frame.axes.T
    polys = shapely.polygons(tri)
    try:
        union = shapely.coverage_union_all(polys)      # edge-matched: the fast union
    except shapely.errors.GEOSException:               # GEOS finds them overlapping
        union = None
    if union is None or \
            abs(union.area - float(np.sum(shapely.area(polys)))) > SURFACE_TOL * union.area:
        union = shapely.union_all(polys)               # they overlap: the full one
    union = union.simplify(SURFACE_TOL * solid.size)
    if union.geom_type != "Polygon":          # touching at points: the seed's part
        seed = shapely.Point(0.0, 0.0)
        union = min(union.geoms, key=lambda g: g.distance(seed))
    union = orient(union, 1.0)
    hull = _ring_halfplanes(np.asarray(orient(union.convex_hull, 1.0).exterior.coords)[:-1])
    step = SURFACE_CENTRE * math.sqrt(union.area)
    circle = shapely.maximum_inscribed_circle(union, step)
    centre = np.asarray(circle.coords[0])
    patch.centre, patch.inradius = centre, float(circle.length) + step
    ring = np.asarray(union.exterior.coords)[:-1]
    before, after = ring - np.roll(ring, 1, axis=0), np.roll(ring, -1, axis=0) - ring
    reflex = ring[before[:, 0] * after[:, 1] - before[:, 1] * after[:, 0] < 0]
    cuts = np.concatenate([reflex, *(np.asarray(h.coords)[:-1] for h in union.interiors)])
    away = cuts - centre
    length = np.hypot(away[:, 0], away[:, 1])
    ok = length > 0
    E = np.concatenate([hull[0], away[ok] / length[ok, None]])
    h = np.concatenate([hull[1], np.einsum("ij,ij->i", E[len(hull[0]):], cuts[ok])])
    piece = _clip(union.convex_hull, E[len(hull[0]):], h[len(hull[0]):])
    if piece is not None and union.buffer(SURFACE_TOL * solid.size).contains(piece):
        patch.kernel = (E, h)
        patch.middle = np.asarray(piece.centroid.coords[0])
        return patch.kernel
    patch.middle = centre
    E_, h_ = [], []
    for r in (union.exterior, *union.interiors):
        e, hh = _ring_halfplanes(np.asarray(r.coords)[:-1])
        E_.append(e)
        h_.append(hh)
    patch.kernel = (np.concatenate(E_), np.concatenate(h_))
    return patch.kernel


def _clip(hull: Any, E: FloatArray, h: FloatArray) -> Any:
    """The convex polygon ``hull`` cut by the half-planes ``E x <= h`` (each a box
    covering the hull, intersected in turn), or None when nothing is left."""
    import shapely

    lo_x, lo_y, hi_x, hi_y = hull.bounds
    big = 4.0 * (abs(lo_x) + abs(lo_y) + abs(hi_x) + abs(hi_y) + TINY)
    poly = hull
    for e, c in zip(E, h, strict=True):
        t = np.array([-e[1], e[0]])
        base = e * c
        box = shapely.Polygon([base + big * t, base - big * t, base - big * t - 2 * big * e,
                               base + big * t - 2 * big * e])
        poly = poly.intersection(box)
        if poly.is_empty:
            return None
    return poly if poly.geom_type == "Polygon" else None


def _holds(c1: FloatArray, c2: FloatArray, Q1: FloatArray, Q2: FloatArray,
           patches: tuple[_Patch, _Patch], alphas: tuple[float, float], r: float,
           r2: float | None = None) -> bool:
    """The module's condition checked in floats: every difference of the two prisms'
    corners (octagons of circumradius ``r`` about ``c1`` and ``r2``, default ``r``, about
    ``c2``, 3-D) strictly inside both narrowed cones, every octagon corner inside its
    convex piece."""
    p, q = patches
    r2 = r if r2 is None else r2
    P1 = _prism(c1 + r * Q1, p)
    P2 = _prism(c2 + r2 * Q2, q)
    d = P2[None, :, :] - P1[:, None, :]
    length = np.linalg.norm(d, axis=-1)
    for axis, a in ((p.frame.normal, alphas[0]), (-q.frame.normal, alphas[1])):
        if not np.all(d @ axis > math.cos(a) * length):
            return False
    for c, Q, pt, rr in ((c1, Q1, p, r), (c2, Q2, q, r2)):
        E, h = pt.kernel  # type: ignore[misc]
        if not np.all(pt.frame.to_2d(c + rr * Q) @ E.T <= h):
            return False
    return True


def _prism(corners: FloatArray, patch: _Patch) -> FloatArray:
    """The octagon's corners (in the patch's plane) at both heights (16, 3)."""
    n0 = patch.frame.normal
    return np.concatenate([corners + patch.low * n0, corners + patch.high * n0])


def _program(p: _Patch, q: _Patch, alphas: tuple[float, float]
             ) -> tuple[FloatArray, FloatArray, float] | None:
    """The largest octagons under the module's condition: one cone program as
    :func:`~fcgrasp.spatial.regions._pair_program`, over the prisms' corners."""
    import clarabel

    fp, fq = p.frame, q.frame
    Q1, Q2 = _octagon_axes(fp, fq)
    halfplanes = (p.kernel, q.kernel)
    rows, rhs = _piece_rows((fp, fq), (Q1, Q2), halfplanes)  # type: ignore[arg-type]
    cones: list[Any] = [clarabel.NonnegativeConeT(len(rows))]
    base = fq.origin - fp.origin
    shifts = [hq * fq.normal - hp * fp.normal for hp in (p.low, p.high)
              for hq in (q.low, q.high)]
    _cone_rows(fp, fq, alphas, [(base + s, q2 - q1) for s in shifts for q1 in Q1
                                for q2 in Q2], rows, rhs, cones)
    z = _largest_last(rows, rhs, cones, almost=True)        # certified after
    if z is None:
        return None
    return fp.to_3d(z[0:2]), fq.to_3d(z[2:4]), float(z[4])


def _certified(c1: FloatArray, c2: FloatArray, p: _Patch, q: _Patch,
               alphas: tuple[float, float], r: float) -> float:
    """The radius ``r`` or the largest below it that :func:`_holds` confirms."""
    Q1, Q2 = _octagon_axes(p.frame, q.frame)

    def holds(x: float) -> bool:
        return _holds(c1, c2, Q1, Q2, (p, q), alphas, x)

    for shrink in _SHRINKS:
        if holds(r * (1 - shrink)):
            return r * (1 - shrink)
    if not holds(0.0):
        return 0.0
    return _bisect(holds, 0.0, r)


def _bisect(holds: Any, lo: float, hi: float) -> float:
    """The largest radius found to hold between ``lo`` (which does) and ``hi`` (which
    may not), halving to :data:`~fcgrasp.core.tolerances.SURFACE_STEP` of ``hi``."""
    step = SURFACE_STEP * hi
    while hi - lo > step:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if holds(mid) else (lo, mid)
    return lo


def _lift(solid: Solid, patch: _Patch, xy: FloatArray) -> FloatArray:
    """Points (k, 2) of the patch's plane lifted onto its triangles along ``n_0`` (the
    first triangle whose projection holds each point; the nearest for a point a rounding
    outside every one)."""
    f = patch.frame
    tri3 = solid.triangles[patch.triangles] - f.origin                  # (m, 3, 3)
    tri = tri3 @ f.axes.T                                               # (m, 3, 2)
    h = tri3 @ f.normal                                                 # (m, 3)
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    det = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    x = xy[:, None, :] - a[None, :, :]                                  # (k, m, 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        u = (x[..., 0] * (c[:, 1] - a[:, 1]) - x[..., 1] * (c[:, 0] - a[:, 0])) / det
        v = ((b[:, 0] - a[:, 0]) * x[..., 1] - (b[:, 1] - a[:, 1]) * x[..., 0]) / det
    w = np.stack([1 - u - v, u, v], axis=-1)                             # (k, m, 3)
    worst = np.nan_to_num(w.min(axis=-1), nan=-np.inf)
    pick = np.argmax(worst, axis=1)
    wk = np.clip(w[np.arange(len(xy)), pick], 0, 1)
    wk /= wk.sum(axis=1, keepdims=True)
    height = np.einsum("kj,kj->k", wk, h[pick])
    return np.asarray(f.to_3d(xy) + height[:, None] * f.normal)


def _on_surface(solid: Solid, patch: _Patch, corners: FloatArray) -> FloatArray:
    """The region on the surface as triangles (k, 3, 3): each patch triangle's
    projection clipped to the octagon (``corners``, 2-D), fanned, and lifted back onto
    that triangle's plane along ``n_0`` (batched)."""
    import shapely

    f = patch.frame
    tri3 = solid.triangles[patch.triangles]
    clipped = shapely.intersection(shapely.polygons((tri3 - f.origin) @ f.axes.T),
                                   shapely.Polygon(corners))
    idx = np.flatnonzero((shapely.get_type_id(clipped) == 3) & (shapely.area(clipped) > 0))
    if not len(idx):
        return np.zeros((0, 3, 3))
    coords, which = shapely.get_coordinates(clipped[idx], return_index=True)
    counts = np.bincount(which, minlength=len(idx))
    keep = np.ones(len(coords), bool)
    keep[np.cumsum(counts) - 1] = False               # each ring's closing point
    coords, which, counts = coords[keep], which[keep], counts - 1
    starts = np.cumsum(counts) - counts
    t = tri3[idx]
    n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])[which]
    pts = f.to_3d(coords)
    pts = pts + (np.einsum("ij,ij->i", t[which, 0] - pts, n) / (n @ f.normal))[:, None] \
        * f.normal                                      # up along n_0 onto each triangle
    fan = counts - 2                                    # triangles of each polygon's fan
    poly = np.repeat(np.arange(len(idx)), fan)
    k = np.arange(int(fan.sum())) - np.repeat(np.cumsum(fan) - fan, fan)
    first = starts[poly]
    return np.stack([pts[first], pts[first + k + 1], pts[first + k + 2]], axis=1)


def _facing(p: _Patch, q: _Patch, alphas: tuple[float, float],
            fits: tuple[FloatArray, FloatArray], bound: float
            ) -> tuple[float, FloatArray, FloatArray]:
    """The largest octagons (at most ``bound``) that hold about three choices of
    centres: ``fits`` (2-D, one in each patch's plane); one of them and the point of
    the other plane it faces along the bisector of ``n_0`` and ``-n_0``.  The radius and
    both centres (3-D)."""
    fp, fq = p.frame, q.frame
    Q1, Q2 = _octagon_axes(fp, fq)
    axis = fp.normal - fq.normal
    axis = axis / np.linalg.norm(axis)
    a1, a2 = fp.to_3d(fits[0]), fq.to_3d(fits[1])
    best = (0.0, a1, a2)
    for c1, c2 in ((a1, a2), (a1, _facing_point(a1, axis, fq)),
                   (_facing_point(a2, -axis, fp), a2)):
        if c1 is None or c2 is None:
            continue
        room = min(_room(p, c1, Q1), _room(q, c2, Q2), bound)
        if room <= best[0]:
            continue
        r = _certified(c1, c2, p, q, alphas, room)
        if r > best[0]:
            best = (r, c1, c2)
    return best


def _facing_point(c: FloatArray, axis: FloatArray, frame: Facet) -> FloatArray | None:
    """Where the line from ``c`` along ``axis`` meets ``frame``'s plane (None when it runs
    along it)."""
    along = float(axis @ frame.normal)
    if abs(along) < SURFACE_TOL:
        return None
    return np.asarray(c + (float((frame.origin - c) @ frame.normal) / along) * axis)


def _room(patch: _Patch, c: FloatArray, Q: FloatArray) -> float:
    """The largest octagon about ``c`` (3-D, in the patch's plane) inside its kernel."""
    E, h = patch.kernel  # type: ignore[misc]
    k = (E @ (Q @ patch.frame.axes.T).T).max(axis=1)
    return max(float(np.min((h - E @ patch.frame.to_2d(c)) / k)), 0.0)


def _pair_bound(p: _Patch, q: _Patch, alpha: float) -> float:
    """An upper bound on the octagons' radius on two patches (P first, Q second, their
    planes parallel: ``n_0`` of Q is ``-n_0`` of P): the narrower patch's width over the
    octagon's least width ``2 r cos(pi / 8)``; and the cones.  The octagons are turned
    alike (:func:`~fcgrasp.spatial.regions._octagon_axes`), so for a corner direction
    ``u`` of both, the corner differences ``(c_2 - r u) - (c_1 + r u)`` and ``(c_2 + r u)
    - (c_1 - r u)`` are ``4 r`` apart across ``n_0``: one of them is at least ``2 r`` off
    the axis, inside the cone of ``alpha - beta`` below the height ``H`` of Q's highest
    prism corner over P's lowest, so ``r <= H tan(alpha - beta) / 2``; the same for P
    over Q."""
    cone = math.inf
    for a, b in ((p, q), (q, p)):
        f, g = a.frame, b.frame
        high = float(np.max((g.origin + b.flat @ g.axes) @ f.normal)) \
            + max(b.low * float(g.normal @ f.normal), b.high * float(g.normal @ f.normal))
        rise = high - float(f.origin @ f.normal) - a.low
        cone = min(cone, rise * math.tan(alpha - a.beta) / 2)
    return min(p.width_bound, q.width_bound, cone)
