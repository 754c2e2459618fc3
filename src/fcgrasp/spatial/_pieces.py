"""The convex pieces of a solid's facets as one table, the inscribed-circle bound of a
pair of pieces and the largest octagon a piece fits (part of
:mod:`fcgrasp.spatial.regions`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core._checks import FloatArray, IntArray
from ..core.tolerances import (
    FIT_ROUNDING,
    INRADIUS_STEP,
    PROJECTED_AXIS,
    SEPARATION_PAD,
)
from .solid import Solid

#: A convex piece as ``E x <= h``: outward unit normals (m, 2) and offsets (m,).
Halfplanes = tuple[FloatArray, FloatArray]


def inscribed_radius_bound(geoms: Any) -> FloatArray:
    """An upper bound on each polygon's inscribed radius (a numpy array of shapely
    polygons): shapely's largest inscribed circle, found to within ``INRADIUS_STEP`` of
    the polygon's extent, plus that tolerance."""
    import shapely

    lo_x, lo_y, hi_x, hi_y = shapely.bounds(geoms).T
    tol = INRADIUS_STEP * np.maximum(hi_x - lo_x, hi_y - lo_y)
    return np.asarray(shapely.length(shapely.maximum_inscribed_circle(geoms, tol)) + tol)


def _ring(piece: Any) -> FloatArray:
    """The vertices (m, 2) of a convex shapely polygon, counter-clockwise."""
    from shapely.geometry.polygon import orient

    return np.asarray(orient(piece, 1.0).exterior.coords)[:-1]


def _halfplanes(piece: Any) -> Halfplanes:
    """``E x <= h`` for a convex shapely polygon."""
    return _ring_halfplanes(_ring(piece))


def _ring_widths(halfplanes: Halfplanes, ring: FloatArray) -> FloatArray:
    """The widths of a convex ring across its edges: along each edge's normal, from the
    edge's line to the farthest vertex (``halfplanes``: the ring's, :func:`_ring_halfplanes`)."""
    E, h = halfplanes
    return np.asarray(h - (E @ ring.T).min(axis=1))


def _ring_halfplanes(ring: FloatArray) -> Halfplanes:
    """``E x <= h`` for a counter-clockwise convex ring (zero-length edges dropped)."""
    d = np.roll(ring, -1, axis=0) - ring
    length = np.hypot(d[:, 0], d[:, 1])
    keep = length > 0
    ring, d, length = ring[keep], d[keep], length[keep]
    E = np.c_[d[:, 1], -d[:, 0]] / length[:, None]                # outward
    return E, np.einsum("ij,ij->i", E, ring)


@dataclass(frozen=True)
class _Pieces:
    """Every convex piece of a solid's facets, flattened: its ``facet`` and index in it
    (``local``), half-planes, 3-D vertices, centroid and ``reach`` (largest distance of a
    vertex from it), inscribed radius; ``start`` and ``count`` per facet."""

    facet: IntArray
    local: IntArray
    halfplanes: list[Halfplanes]
    vertices: list[FloatArray]
    centroid: FloatArray
    reach: FloatArray
    inradius: FloatArray
    start: IntArray
    count: IntArray
    triangle: Any = field(repr=False)      # bool (P,)
    edge_angle: FloatArray = field(repr=False)   # triangles: edges' normal angles (P, 3)
    edge_weight: FloatArray = field(repr=False)  # triangles: lengths / (2 area) (P, 3)
    normal: FloatArray = field(repr=False)       # the facet's inward normal (P, 3)
    origin: FloatArray = field(repr=False)       # ... its plane's origin (P, 3)
    axes: FloatArray = field(repr=False)         # ... and in-plane axes (P, 2, 3)
    own_fit: FloatArray = field(repr=False)      # the octagon along the facet's own axis
    width: list[FloatArray] = field(repr=False)  # the piece's width across each edge
    narrow_angle: FloatArray = field(repr=False)  # the narrowest widths' normal angles
    narrow_width: FloatArray = field(repr=False)  # ... and widths (P, NARROW), inf pad
    #: each piece's octagon fit along its facet's own axis (:func:`own_octagon_fit`),
    #: found once a search asks for it
    own_octagon: dict[int, tuple[float, FloatArray]] = field(default_factory=dict,
                                                            repr=False)
    #: each facet's dual rays (:func:`_dual_rays`) by facet, side and half-angle, made
    #: once a separation test asks for them
    dual: dict[tuple[int, float, float], tuple[FloatArray, FloatArray]] = field(
        default_factory=dict, repr=False)


def _piece_table(solid: Solid, batched: bool = True) -> _Pieces:
    """The table of ``solid``'s pieces.  ``batched``: the pieces' rings, half-planes,
    centroids, reaches and widths read for every piece of one vertex count at once (a
    100,000-triangle mesh has 50,000 pieces), the same numbers; False: piece by piece,
    the reference."""
    import shapely

    facet, local, polys, owner = [], [], [], []
    for f in solid.facets:
        for k, piece in enumerate(f.pieces):
            facet.append(f.index)
            local.append(k)
            polys.append(piece)
            owner.append(f)
    geoms = np.array(polys, dtype=object)
    n = len(polys)
    if batched:
        rings, hps, width = _batched_rings(geoms)
        verts = [f.to_3d(ring) for f, ring in zip(owner, rings, strict=True)]
        centroid, reach = _batched_centres(verts)
    else:
        rings = [_ring(piece) for piece in polys]
        hps = [_ring_halfplanes(ring) for ring in rings]
        verts = [f.to_3d(ring) for f, ring in zip(owner, rings, strict=True)]
        centroid = np.array([v.mean(axis=0) for v in verts])
        reach = np.array([np.max(np.linalg.norm(v - c, axis=1))
                          for v, c in zip(verts, centroid, strict=True)])
        # the width across each edge (its normal's direction)
        width = [_ring_widths(hp, ring) for hp, ring in zip(hps, rings, strict=True)]
    area, length = shapely.area(geoms), shapely.length(geoms)
    inradius = 2 * area / length                              # exact for triangles
    other = np.array([len(v) != 3 for v in verts], bool)
    if other.any():
        inradius[other] = inscribed_radius_bound(geoms[other])
    count = np.array([len(f.pieces) for f in solid.facets], np.intp)
    start = np.concatenate([[0], np.cumsum(count)[:-1]]).astype(np.intp)
    triangle = ~other
    edge_angle = np.zeros((n, 3))
    edge_weight = np.zeros((n, 3))
    tri = np.flatnonzero(triangle)
    if tri.size:
        E3 = np.array([hps[k][0] for k in tri.tolist()])                   # (T, 3, 2)
        lengths = _triangle_lengths(E3)
        edge_angle[tri] = np.arctan2(E3[..., 1], E3[..., 0])
        # sum(l h) is twice the area
        twice = np.array([ll @ hps[k][1] for ll, k in zip(lengths, tri.tolist(), strict=True)])
        edge_weight[tri] = lengths / twice[:, None]
    # the narrowest few widths
    narrow_angle = np.zeros((n, _NARROW))
    narrow_width = np.full((n, _NARROW), np.inf)
    for k, ((E, _), w) in enumerate(zip(hps, width, strict=True)):
        keep = np.argsort(w)[:_NARROW]
        narrow_angle[k, :len(keep)] = np.arctan2(E[keep, 1], E[keep, 0])
        narrow_width[k, :len(keep)] = w[keep]
    table = _Pieces(np.array(facet, np.intp), np.array(local, np.intp), hps, verts,
                    centroid, reach, inradius, start, count, triangle, edge_angle,
                    edge_weight, np.array([f.normal for f in owner]),
                    np.array([f.origin for f in owner]), np.array([f.axes for f in owner]),
                    np.zeros(n), width, narrow_angle, narrow_width)
    table.own_fit[:] = _fit_bounds(table, np.arange(n), np.zeros(n))
    return table


def _batched_rings(geoms: np.ndarray
                   ) -> tuple[list[FloatArray], list[Halfplanes], list[FloatArray]]:
    """:func:`_piece_table`'s rings (:func:`_ring`), half-planes
    (:func:`_ring_halfplanes`) and widths across the edges, each group of pieces with
    one vertex count at once (the same elementwise arithmetic; a ring with a
    zero-length edge alone)."""
    import shapely

    n = len(geoms)
    coords, which = shapely.get_coordinates(
        shapely.get_exterior_ring(shapely.orient_polygons(geoms)), return_index=True)
    ends = np.searchsorted(which, np.arange(n + 1))
    rings: list[FloatArray] = [coords[ends[i]:ends[i + 1] - 1] for i in range(n)]
    hps: list[Halfplanes] = [(np.zeros((0, 2)), np.zeros(0))] * n
    width: list[FloatArray] = [np.zeros(0)] * n
    sizes = ends[1:] - ends[:-1] - 1
    for m in np.unique(sizes).tolist():
        idx = np.flatnonzero(sizes == m)
        R = np.stack([rings[i] for i in idx.tolist()])                    # (g, m, 2)
        d = np.roll(R, -1, axis=1) - R
        length = np.hypot(d[..., 0], d[..., 1])
        whole = np.all(length > 0, axis=1)
        E = np.stack([d[..., 1], -d[..., 0]], axis=-1) / length[..., None]
        h = np.einsum("gij,gij->gi", E, R)
        W = h - np.matmul(E, R.transpose(0, 2, 1)).min(axis=2)
        for j, i in enumerate(idx.tolist()):
            if whole[j]:
                hps[i], width[i] = (E[j], h[j]), W[j]
            else:
                hps[i] = _ring_halfplanes(rings[i])
                width[i] = _ring_widths(hps[i], rings[i])
    return rings, hps, width


def _batched_centres(verts: list[FloatArray]) -> tuple[FloatArray, FloatArray]:
    """Each piece's centroid and largest distance of a vertex from it, pieces of one
    vertex count at once."""
    centroid, reach = np.zeros((len(verts), 3)), np.zeros(len(verts))
    sizes = np.array([len(v) for v in verts])
    for m in np.unique(sizes).tolist():
        idx = np.flatnonzero(sizes == m)
        V = np.stack([verts[i] for i in idx.tolist()])                    # (g, m, 3)
        centroid[idx] = V.mean(axis=1)
        reach[idx] = np.max(np.linalg.norm(V - centroid[idx, None, :], axis=2), axis=1)
    return centroid, reach


def own_octagon_fit(table: _Pieces, p: int, corners: FloatArray) -> tuple[float, FloatArray]:
    """:func:`_fit` of the octagon ``corners`` (along the facet's own axis) in piece ``p``
    of ``table``, kept in the table: the triples of a search share their pieces."""
    got = table.own_octagon.get(p)
    if got is None:
        got = table.own_octagon[p] = _fit(table.halfplanes[p], corners, table.width[p])
    return got


def _triangle_lengths(E: FloatArray) -> FloatArray:
    """A triangle's edge lengths up to a common factor, from its edges' unit normals
    (..., 3, 2): each is the sine of the opposite angle (the law of sines), the cross
    product of the other two normals."""
    a, b = E[..., [1, 2, 0], :], E[..., [2, 0, 1], :]
    return np.asarray(np.abs(a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]))


def _support(angle: FloatArray) -> FloatArray:
    """The unit octagon's support along directions at ``angle`` from its first corner:
    ``cos`` of the angle to the nearest corner."""
    d = np.mod(angle, math.pi / 4)
    return np.asarray(np.cos(np.minimum(d, math.pi / 4 - d)))


def _fit_bounds(table: _Pieces, pieces: IntArray, phi: FloatArray) -> FloatArray:
    """An upper bound on the largest octagon (first corner at angle ``phi`` in the
    facet's 2-D frame) in each piece, batched: in a triangle the exact fit
    (:func:`_fit`'s closed form, ``1 / sum(w_i k_i)``, ``k_i`` the octagon's support
    along edge ``i``'s normal); in any piece, its width across an edge over the
    octagon's width ``2 k_i`` there (exact for centrally symmetric pieces)."""
    with np.errstate(divide="ignore"):
        tri = 1.0 / np.einsum("ij,ij->i", table.edge_weight[pieces],
                              _support(table.edge_angle[pieces] - phi[:, None]))
        across = np.min(table.narrow_width[pieces] / (
            2 * _support(table.narrow_angle[pieces] - phi[:, None])), axis=1)
    return np.where(table.triangle[pieces], np.minimum(tri, across), across)


#: The narrowest widths of each piece kept for the batched bound.
_NARROW = 4


#: Piece rows compared at once when looking for opposite facets (memory: rows x facets).
_ROWS = 512


def _pairs(table: _Pieces, new: IntArray, old: IntArray, cos_limit: float
           ) -> tuple[IntArray, IntArray]:
    """The pairs of pieces, one in ``new`` and the other in ``old`` or ``new``, on
    different facets whose (inward) normals are within ``2 alpha`` of opposite
    (``-n_1 . n_2 > cos_limit``), each once, the piece of the lower facet first."""
    pool = np.concatenate([old, new])
    firsts, seconds = [], []
    for s in range(0, len(new), _ROWS):
        rows = new[s:s + _ROWS]
        ii, jj = np.nonzero(-(table.normal[rows] @ table.normal[pool].T) > cos_limit)
        p, q = rows[ii], pool[jj]
        fp, fq = table.facet[p], table.facet[q]
        # a pair of two new pieces is met twice: keep it once
        keep = (fp != fq) & ((jj < len(old)) | (fp < fq))
        p, q, fp, fq = p[keep], q[keep], fp[keep], fq[keep]
        firsts.append(np.where(fp < fq, p, q))
        seconds.append(np.where(fp < fq, q, p))
    if not firsts:
        return np.zeros(0, np.intp), np.zeros(0, np.intp)
    return np.concatenate(firsts), np.concatenate(seconds)


def _pair_bounds(table: _Pieces, pa: IntArray, pb: IntArray, alpha: float) -> FloatArray:
    """An upper bound on each pair's radius, batched: the smaller inscribed circle over
    ``cos(pi / 8)`` (an octagon holds the disc of ``r cos(pi / 8)``), the octagons'
    fits in the pieces (:func:`_fit_bounds`), and ``tan(alpha)`` times the height of
    each piece above the other's plane (the corners of one region, seen from any corner of the
    other, span a width of ``2 r`` across the normal at that height: the cone holds
    them only if ``r <= tan(alpha) * height``)."""
    disc = np.minimum(table.inradius[pa], table.inradius[pb]) / math.cos(math.pi / 8)
    h1 = np.einsum("ij,ij->i", table.centroid[pb] - table.origin[pa], table.normal[pa]) \
        + table.reach[pb]
    h2 = np.einsum("ij,ij->i", table.centroid[pa] - table.origin[pb], table.normal[pb]) \
        + table.reach[pa]
    # the first octagon turned along its facet's first axis (its fit is the piece's
    # own), the second along that axis projected into its plane (:func:`_octagon_axes`)
    along = np.einsum("ij,ikj->ik", table.axes[pa, 0], table.axes[pb])   # (pairs, 2)
    projected = np.hypot(along[:, 0], along[:, 1]) > PROJECTED_AXIS
    phi = np.arctan2(along[:, 1], along[:, 0])
    fits = np.minimum(table.own_fit[pa],
                      np.where(projected, _fit_bounds(table, pb, phi), np.inf))
    return np.minimum(np.minimum(disc, fits * (1 + FIT_ROUNDING)),
                      math.tan(alpha) * np.minimum(h1, h2))


def _fit(halfplanes: Halfplanes, corners: FloatArray, width: FloatArray | None = None
         ) -> tuple[float, FloatArray]:
    """The largest scale ``s`` and centre ``t`` with ``t + s * corners`` inside the piece
    (a translate of the octagon scaled about its centre): in closed form for a triangle
    (the three edges tight: ``s = 2 A / sum(l_i k_i)``, ``k_i`` the octagon's support
    along edge ``i``'s normal); for a centrally symmetric piece (given its ``width``
    across each edge) about its centre, where the octagon's width meets the piece's
    (the fit is symmetric too, and convex); else a three-variable LP (HiGHS)."""
    E, h = halfplanes
    k = (E @ corners.T).max(axis=1)                  # the octagon's support per edge
    if width is not None and len(E) % 2 == 0 and len(E) > 3:
        half = len(E) // 2
        opposite = np.roll(np.arange(len(E)), -half)
        if np.allclose(E[opposite], -E, rtol=0, atol=FIT_ROUNDING) and \
                np.allclose(width[opposite], width, rtol=FIT_ROUNDING, atol=0):
            # the centre: halfway between each pair of opposite edges
            c = np.linalg.lstsq(E[:half], (h[:half] - h[half:]) / 2,
                                rcond=None)[0].astype(float)
            s = float(np.min((h - E @ c) / k))
            return max(s, 0.0), c
    if len(E) == 3:
        length = _triangle_lengths(E)
        s = float(length @ h / (length @ k))
        t = np.linalg.solve(E[:2], h[:2] - s * k[:2])
        return s, t
    if len(E) <= _VERTEX_FIT_EDGES:
        return _vertex_fit(E, h, k)
    from scipy.optimize import linprog

    res = linprog([0.0, 0.0, -1.0], A_ub=np.c_[E, k], b_ub=h,
                  bounds=[(None, None), (None, None), (0, None)], method="highs")
    if res.status != 0:
        return 0.0, np.zeros(2)
    return float(res.x[2]), np.asarray(res.x[:2], float)


#: Pieces of at most this many edges have their octagon's fit by the vertices of its
#: linear program (:func:`_vertex_fit`), not by HiGHS (about 1 ms a call).
_VERTEX_FIT_EDGES = 10


def _vertex_fit(E: FloatArray, h: FloatArray, k: FloatArray) -> tuple[float, FloatArray]:
    """The three-variable program of :func:`_fit` (largest ``s`` with ``E t + s k <=
    h``) by its vertices: every three constraints tight, solved at once, the feasible
    one of largest ``s`` (a bounded program's optimum is at a vertex); ``(0, 0)`` when
    none is feasible with ``s >= 0``."""
    from itertools import combinations

    A = np.c_[E, k]
    idx = np.array(list(combinations(range(len(E)), 3)), np.intp)
    M, b = A[idx], h[idx]
    det = np.linalg.det(M)
    scale = float(np.max(np.abs(A))) ** 3
    ok = np.abs(det) > FIT_ROUNDING * scale
    if not ok.any():
        return 0.0, np.zeros(2)
    z = np.linalg.solve(M[ok], b[ok][..., None])[..., 0]          # (c, 3)
    slack = FIT_ROUNDING * (float(np.max(np.abs(h))) + float(np.max(np.abs(z))))
    feasible = np.all(z @ A.T <= h + slack, axis=1) & (z[:, 2] >= 0)
    if not feasible.any():
        return 0.0, np.zeros(2)
    best = z[feasible][int(np.argmax(z[feasible, 2]))]
    return float(best[2]), np.asarray(best[:2], float)


def _piece_fit(table: _Pieces, piece: int, corners: FloatArray
               ) -> tuple[float, tuple[float, FloatArray]]:
    """The octagon's fit in one piece (:func:`_fit`) and an upper bound on it: the
    widths across every edge (as :func:`_fit_bounds`, every edge), and in a triangle
    the closed-form fit itself (exact)."""
    E, _ = table.halfplanes[piece]
    fit = _fit(table.halfplanes[piece], corners, table.width[piece])
    across = float(np.min(table.width[piece] / (2 * (E @ corners.T).max(axis=1))))
    return (min(fit[0], across) if len(E) == 3 else across), fit


#: The separation test's candidate directions (:func:`separated`): azimuths about each
#: cone's axis, and the angles from it, as fractions of the dual cone's half-angle
#: ``pi / 2 - alpha`` (1: its boundary).
DUAL_AZIMUTHS, DUAL_FRACTIONS = 24, (1.0, 2.0 / 3.0, 1.0 / 3.0)


def _dual_rays(axis: FloatArray, alpha: float) -> tuple[FloatArray, FloatArray]:
    """Unit directions of the dual of the cone of half-angle ``alpha`` about the unit
    ``axis`` (every ``w`` within ``pi / 2 - alpha`` of the axis, so ``w . x >= 0`` for
    every ``x`` in the cone): the axis and rings at :data:`DUAL_FRACTIONS` of that angle
    (all of them), and the ring on the boundary alone."""
    t = np.array([1.0, 0.0, 0.0]) if abs(axis[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = np.cross(axis, t)
    u /= np.linalg.norm(u)
    v = np.cross(axis, u)
    phi = np.linspace(0.0, 2 * math.pi, DUAL_AZIMUTHS, endpoint=False)
    ring = np.cos(phi)[:, None] * u + np.sin(phi)[:, None] * v
    rings = [math.cos(f * (math.pi / 2 - alpha)) * axis
             + math.sin(f * (math.pi / 2 - alpha)) * ring for f in DUAL_FRACTIONS]
    return np.concatenate([axis[None], *rings]), rings[0]


def separated(table: _Pieces, pa: int, pb: int, alpha: float, size: float) -> bool:
    """Whether no point of piece ``pb`` seen from any point of piece ``pa`` lies inside
    both friction cones (half-angle ``alpha`` about ``pa``'s inward normal and about
    ``pb``'s reversed): :func:`separates` with each facet's dual rays, made once."""
    rays = []
    for p, side in ((pa, 1.0), (pb, -1.0)):
        key = (int(table.facet[p]), side, alpha)
        got = table.dual.get(key)
        if got is None:
            got = table.dual[key] = _dual_rays(side * table.normal[p], alpha)
        rays.append(got)
    return separates(table.vertices[pa], table.vertices[pb], rays[0], rays[1],
                     SEPARATION_PAD * size)


def separates(v1: FloatArray, v2: FloatArray, rays1: tuple[FloatArray, FloatArray],
              rays2: tuple[FloatArray, FloatArray], pad: float) -> bool:
    """Whether a direction ``w`` of the dual of two cones' intersection (a ray of either
    cone's dual, or the sum of a boundary ray of each: :func:`_dual_rays`' ``rays1`` and
    ``rays2``) has ``w . (x_2 - x_1) < -pad |w|`` for every vertex ``x_1`` of ``v1`` and
    ``x_2`` of ``v2`` (3-D, the vertices of two convex pieces).  Every difference of the
    pieces' points is then outside a cone, so no two soft fingers hold there (the
    module :mod:`fcgrasp.spatial.regions`: regions of radius 0).  The directions are
    sampled (:data:`DUAL_AZIMUTHS`, :data:`DUAL_FRACTIONS`): True is a proof, False
    proves nothing."""
    (w1, b1), (w2, b2) = rays1, rays2
    W = np.concatenate([w1, w2, (b1[:, None, :] + b2[None, :, :]).reshape(-1, 3)])
    reach = (W @ v2.T).max(axis=1) - (W @ v1.T).min(axis=1)
    return bool(np.any(reach < -pad * np.linalg.norm(W, axis=1)))
