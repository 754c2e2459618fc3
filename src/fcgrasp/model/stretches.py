r"""Regions that run along the boundary: two fingers with friction (issue 12).

A *stretch* is a connected piece of one boundary ring, from a point on one edge to a
point on another, covering the edges and vertices between them.  Two stretches
``R1, R2`` are independent regions of contact (definition 7.1) when every grasp with
one finger anywhere in ``R1`` and the other anywhere in ``R2`` is force closure, with
the contact normal of the edge strictly inside an edge and, at a vertex strictly
inside a stretch, **every** normal between the two edges' normals (a fingertip on a
corner).  A stretch's end point takes the normal of the edge the stretch covers there.

**The condition (theorem 6.3 with a margin).**  Write ``beta = atan(mu) - margin`` and
``W(f)`` for the cone of directions within ``beta`` of the force direction ``f``
(the inward normal).  Two contacts ``X`` (force ``f``) and ``Y`` (force ``g``) hold
the part, squeezing, iff ``Y - X`` lies in ``W(f)`` and ``X - Y`` in ``W(g)``
(expanding: the opposite signs).  ``W(f)`` is the intersection of two half-planes
whose edges turn with ``f``; *for a fixed chord the set of force directions that
contain it is an arc of width 2 beta*, convex in the normal's angle, so a fan of
normals at a vertex holds iff its two extreme normals (the two edges') hold.  Hence
the stretches hold iff every pair of *points* ``(X, Y)`` taken among the end points
and interior vertices of ``R1`` and ``R2`` holds with every normal those points carry
(end: one; interior vertex: both), because on every pair of edge pieces the chord
``Y - X`` is affine in the two positions and the cones are convex: the pair of pieces
holds iff its four corners do.

**The optimum.**  The smallest region as long as possible (definition 7.1).  A
*configuration* fixes which edges the two stretches cover (its interior vertices and
end edges); for a configuration the condition is linear in the two start positions
and the common length ``t`` of a square pair of regions (a longer region can be cut
to the shorter's length, so the largest smallest region is reached by a square pair):

* the end points against the other stretch's interior vertices bound each end to an
  interval of its edge (a running max/min over the window of vertices);
* the four corner pairs (end against end) give 16 half-planes in ``(s0, u0, t)``.

The largest ``t`` of a configuration is found by bisection on ``t`` with an exact
feasibility test of the remaining two-variable system (Fourier-Motzkin elimination of
``s0``), to machine precision.  Configurations are enumerated exhaustively behind a
bound: every interior vertex pair must hold with both fans (the boolean matrix
``M``), so the interior windows are runs of the intersection of rows of ``M`` (each
row held as its sorted runs of columns, so widening a window costs the runs it still
has, not a row of ``M``; the intervals of the ends are computed only for the cells
the search reads); a configuration is never longer than the arc length it can reach
(``_stretch_bound``); the vertex-aligned stretches of every window are feasible and
give the lower bound that prunes the others.  The search is exact: every
configuration that could beat the best found is solved.

The tests compare the optimum with an independent fine raster of the two contact
parameters (the largest square of force-closure samples, sharing no code with this
module) and sample every returned pair of regions with the general test.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core._angles import shrunk_half_angle
from ..core._checks import FloatArray, check_int, check_mu_scalar, check_scalar
from ..core._geom import cross2 as _cross
from ..core._geom import geometric_key, leximin_key, midpoints, trim_vertex_ends
from ..core.contacts import rotate
from ..core.tolerances import RANK_TOL, ROUND_TOL, TOL
from .polygon import Polygon, check_polygon
from .regions import DEFAULT_MARGIN_DEG

__all__ = ["StretchPair", "two_finger_stretches", "stretch_regions", "crosses_a_vertex"]

#: A coefficient of the linear system smaller than this (a cross product of unit
#: vectors) is zero.
_EPS = ROUND_TOL

#: Relative tolerance within which two smallest regions tie (the ranking's).
TIE = RANK_TOL


@dataclass(frozen=True)
class StretchPair:
    """Two independent regions along the boundary (two fingers with friction).

    ``regions[i]`` is the polyline ``(m_i, 2)`` of region ``i`` from one end to the
    other through the vertices it covers; ``region_edges[i]`` the edges it covers in
    order; ``lengths[i]`` its arc length; ``mode`` "squeeze" or "expand".
    """

    regions: tuple[FloatArray, FloatArray]
    region_edges: tuple[tuple[int, ...], tuple[int, ...]]
    lengths: tuple[float, float]
    mode: str

    @property
    def min_length(self) -> float:
        return min(self.lengths)

    def midpoints(self) -> tuple[FloatArray, tuple[int, int]]:
        """Each region's point halfway along it (the representative contact) and the
        edge holding it."""
        pts, edges = midpoints(self.regions, self.region_edges)
        return pts, (edges[0], edges[1])


@dataclass
class _Ring:
    """One ring's usable edges in ring order (the sequence wraps around)."""

    edges: np.ndarray      # (m,) polygon edge ids
    a: FloatArray          # (m, 2) start points (vertex k is a[k])
    t: FloatArray          # (m, 2) unit tangents
    f: FloatArray          # (m, 2) force directions (inward normals)
    L: FloatArray          # (m,)
    U: FloatArray          # (4m,) arc position of vertex k, unrolled: U[k + m] = U[k] + P

    @property
    def m(self) -> int:
        return int(self.edges.size)


def _rings(polygon: Polygon) -> list[_Ring]:
    out = []
    for r in np.unique(polygon.rings):
        idx = np.flatnonzero((polygon.rings == r) & polygon.usable)
        if idx.size < 3:
            continue
        L = polygon.lengths[idx]
        per = float(L.sum())
        base = np.concatenate([[0.0], np.cumsum(L)[:-1]])
        U = np.concatenate([base + j * per for j in range(4)])
        out.append(_Ring(idx, polygon.starts[idx], polygon.tangents[idx], -polygon.normals[idx],
                         L, U))
    return out


def _gens_x(f: FloatArray, beta: float) -> list[FloatArray]:
    """Generators g with ``cross(g, d) >= 0`` iff ``d`` is in ``W(f)`` (chord from X)."""
    return [rotate(f, -beta), -rotate(f, beta)]


def _gens_y(f: FloatArray, beta: float) -> list[FloatArray]:
    """Generators g with ``cross(g, d) >= 0`` iff ``-d`` is in ``W(f)`` (chord to Y)."""
    return [-rotate(f, -beta), rotate(f, beta)]


def _fan(ring: _Ring) -> tuple[FloatArray, FloatArray]:
    """The two force directions at every vertex (edge before, edge after)."""
    return np.roll(ring.f, 1, axis=0), ring.f


#: Elements per block of a ring-by-ring array: blocks of rows this size stay in cache.
_BLOCK = 1 << 15


def _row_blocks(rows: int, cols: int) -> list[slice]:
    """Slices of ``rows`` whose blocks of ``cols`` columns hold about ``_BLOCK`` cells."""
    step = max(1, _BLOCK // max(cols, 1))
    return [slice(s, s + step) for s in range(0, rows, step)]


def _vertex_matrix(ra: _Ring, rb: _Ring, sigma: float, beta: float) -> np.ndarray:
    """``M[v, w]``: vertices ``v`` (ring a) and ``w`` (ring b) hold with both fans."""
    gx = [g for f in _fan(ra) for g in _gens_x(f, beta)]
    gy = [g[None, :, :] for f in _fan(rb) for g in _gens_y(f, beta)]
    out = np.empty((ra.m, rb.m), bool)
    for sl in _row_blocks(ra.m, rb.m):
        d = sigma * (rb.a[None, :, :] - ra.a[sl, None, :])
        ok = (d[..., 0] != 0) | (d[..., 1] != 0)
        for g in [g[sl, None, :] for g in gx] + gy:
            ok &= _cross(g, d) >= 0
        out[sl] = ok
    return out


class _Intervals:
    """``[lo, hi][e, w]``: positions on edge ``e`` (ring a, arc length from its start)
    where a contact holds against vertex ``w`` of ring b with both its fan normals
    (empty where ``lo > hi``).  Computed for the cells asked for: the searches read
    whole rows only for edges long enough to matter, and windows of a few cells."""

    def __init__(self, ra: _Ring, rb: _Ring, sigma: float, beta: float) -> None:
        self.ra, self.rb, self.sigma = ra, rb, sigma
        self.gx = np.stack(_gens_x(ra.f, beta), axis=1)                      # (ma, 2, 2)
        self.gy = np.stack([g for f in _fan(rb) for g in _gens_y(f, beta)], axis=1)

    def cells(self, e: np.ndarray, w: np.ndarray) -> tuple[FloatArray, FloatArray]:
        """The intervals of the cells ``(e, w)`` (integer arrays, broadcast together)."""
        ra, sigma = self.ra, self.sigma
        e, w = np.broadcast_arrays(e, w)
        d0 = sigma * (self.rb.a[w] - ra.a[e])          # chord at p = 0
        d1 = -sigma * ra.t[e]                          # its derivative in p
        lo = np.zeros(e.shape)
        hi = ra.L[e].astype(float)
        for g in [self.gx[e, j] for j in range(2)] + [self.gy[w, j] for j in range(4)]:
            c0, c1 = _cross(g, d0), _cross(g, d1)
            with np.errstate(divide="ignore", invalid="ignore"):
                r = -c0 / c1
            np.maximum(lo, r, out=lo, where=c1 > _EPS)
            np.minimum(hi, r, out=hi, where=c1 < -_EPS)
            hi[(np.abs(c1) <= _EPS) & (c0 < 0)] = -np.inf
        return lo, hi

    def rows(self, edges: np.ndarray) -> tuple[FloatArray, FloatArray]:
        """Whole rows ``[lo, hi][edges, :]``, in blocks that stay in cache."""
        lo = np.empty((edges.size, self.rb.m))
        hi = np.empty_like(lo)
        cols = np.arange(self.rb.m)[None, :]
        for sl in _row_blocks(edges.size, self.rb.m):
            lo[sl], hi[sl] = self.cells(edges[sl, None], cols)
        return lo, hi

    def window(self, edge: np.ndarray, start: np.ndarray, count: np.ndarray
               ) -> tuple[FloatArray, FloatArray]:
        """For each edge, the intersection of its intervals against vertices
        ``start .. start + count - 1`` (cyclic): ``(0, inf)`` when ``count`` is 0."""
        lo, hi = np.zeros(edge.size), np.full(edge.size, np.inf)
        has = np.flatnonzero(count > 0)
        if has.size:
            c = count[has]
            offs, k = _segments(c)
            flo, fhi = self.cells(np.repeat(edge[has], c),
                                  (np.repeat(start[has], c) + k) % self.rb.m)
            lo[has] = np.maximum.reduceat(flo, offs)
            hi[has] = np.minimum.reduceat(fhi, offs)
        return lo, hi


def _row_intervals(M: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The maximal runs of True in every row of ``M``, not wrapping around: (row, first
    column, last column), sorted by row then column."""
    pad = np.zeros((M.shape[0], 1), bool)
    step = np.diff(np.concatenate([pad, M, pad], axis=1).view(np.int8), axis=1)
    r0, c0 = np.nonzero(step == 1)
    _, c1 = np.nonzero(step == -1)
    return r0, c0, c1 - 1


def _intersect_rows(c: tuple[np.ndarray, np.ndarray, np.ndarray],
                    m: tuple[np.ndarray, np.ndarray, np.ndarray], ptr: np.ndarray,
                    shift: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Row ``i`` of ``c`` AND row ``i + shift`` (cyclic) of ``m`` (``ptr``: where each
    row's intervals start in ``m``), as intervals sorted like the inputs."""
    row, s, e = c
    other = (row + shift) % (ptr.size - 1)
    first, n = ptr[other], ptr[other + 1] - ptr[other]
    one = n == 1                      # the common case: one interval to meet
    q = first[one]
    r1, s1, e1 = row[one], np.maximum(s[one], m[1][q]), np.minimum(e[one], m[2][q])
    if not one.all():
        many = ~one
        n = n[many]
        _, j = _segments(n)
        q = np.repeat(first[many], n) + j
        r2 = np.repeat(row[many], n)
        s2 = np.maximum(np.repeat(s[many], n), m[1][q])
        e2 = np.minimum(np.repeat(e[many], n), m[2][q])
        # back in order of row and column: rows of one interval first, then merge
        r1, s1, e1 = (np.concatenate(v) for v in ((r1, r2), (s1, s2), (e1, e2)))
        order = np.lexsort((s1, r1))
        r1, s1, e1 = r1[order], s1[order], e1[order]
    keep = s1 <= e1
    return r1[keep], s1[keep], e1[keep]


def _group_starts(row: np.ndarray) -> np.ndarray:
    """Where each group of equal values starts in a sorted array."""
    return np.flatnonzero(np.diff(row, prepend=-1))


def _cyclic_runs(c: tuple[np.ndarray, np.ndarray, np.ndarray], rows: np.ndarray, m: int
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Maximal cyclic runs (row, start, length) of the given rows of a matrix of ``m``
    columns held as intervals: a row's run through its last column continues into its
    first; runs in order of row and start, whole rows (start 0, length ``m``) last."""
    row, s, e = c
    wanted = np.zeros(int(row.max(initial=rows.max(initial=0))) + 1, bool)
    wanted[rows] = True
    sel = wanted[row]
    row, s, e = row[sel], s[sel], e[sel]
    if row.size == 0:
        return row, s, e
    first = _group_starts(row)
    last = np.append(first[1:] - 1, row.size - 1)
    full = (first == last) & (s[first] == 0) & (e[first] == m - 1)
    wrap = (first != last) & (s[first] == 0) & (e[last] == m - 1)
    length = e - s + 1
    length[last[wrap]] += e[first[wrap]] + 1
    drop = np.zeros(row.size, bool)
    drop[first[wrap]] = True
    drop[first[full]] = True
    fr = row[first[full]]
    return (np.concatenate([row[~drop], fr]), np.concatenate([s[~drop], np.zeros(fr.size, int)]),
            np.concatenate([length[~drop], np.full(fr.size, m)]))


def _segments(counts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For consecutive segments of the given lengths: where each starts in the flat
    sequence, and each element's position within its segment."""
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(int)
    return starts, np.arange(int(np.sum(counts))) - np.repeat(starts, counts)


@dataclass
class _Configs:
    """Configurations of one ring pair and mode: stretch 1 covers edges iA .. iA + kA of
    ring a (kA interior vertices), stretch 2 edges iC .. iC + kC of ring b."""

    iA: np.ndarray
    kA: np.ndarray
    iC: np.ndarray
    kC: np.ndarray

    @staticmethod
    def cat(parts: list[_Configs]) -> _Configs:
        return _Configs(*(np.concatenate([getattr(p, f) for p in parts])
                          for f in ("iA", "kA", "iC", "kC")))

    def take(self, idx: Any) -> _Configs:
        return _Configs(self.iA[idx], self.kA[idx], self.iC[idx], self.kC[idx])


def _ext(ring: _Ring, i: np.ndarray, k: np.ndarray) -> FloatArray:
    """Arc length of the edges i .. i + k (the most a stretch covering them reaches)."""
    i = np.asarray(i) % ring.m + ring.m
    return ring.U[i + k + 1] - ring.U[i]


def _inner(ring: _Ring, i: np.ndarray, k: np.ndarray) -> FloatArray:
    """Arc length between the first and last interior vertex (the least it covers)."""
    i = np.asarray(i) % ring.m + ring.m
    return np.where(k > 0, ring.U[i + np.maximum(k, 1)] - ring.U[i + 1], 0.0)


def _stretch_bound(ra: _Ring, rb: _Ring, c: _Configs) -> FloatArray:
    """Upper bound of a configuration's smallest region: each stretch reaches at most the
    arc length of the edges it covers."""
    return np.minimum(_ext(ra, c.iA, c.kA), _ext(rb, c.iC, c.kC))


def _disjoint(ra: _Ring, c: _Configs, same: bool) -> np.ndarray:
    if not same:
        return np.ones(c.iA.size, bool)
    m = ra.m
    # edges of stretch 2 relative to the first edge of stretch 1
    rel = (c.iC - c.iA) % m
    return (rel > c.kA) & (rel + c.kC < m)


class _Bound:
    """The ``k``-th largest smallest region among distinct feasible configurations seen
    so far (0 until ``k`` are seen): no configuration below it can reach the top ``k``.
    ``floor`` is that value less the relative tie tolerance, so ties are kept."""

    def __init__(self, k: int) -> None:
        self.k = k
        self.vals = np.zeros(0)

    def add(self, values: FloatArray) -> None:
        v = np.asarray(values, float).ravel()
        v = v[v > max(self.value, 0.0)]
        if v.size == 0:
            return
        v = np.concatenate([self.vals, v])
        if v.size > self.k:
            v = -np.partition(-v, self.k - 1)[:self.k]
        self.vals = v

    @property
    def value(self) -> float:
        return float(self.vals.min()) if self.vals.size >= self.k else 0.0

    @property
    def floor(self) -> float:
        return self.value * (1 - TIE)


def _windows_both(M: np.ndarray, ra: _Ring, rb: _Ring, same: bool, bound: _Bound,
                  collect: bool) -> _Configs:
    """Configurations with interior vertices on both stretches: stretch 1's interior
    window i .. i+k-1 leaves for stretch 2 the runs of the AND of those rows of ``M``.

    Returns the configurations whose bound reaches the lower bound (if ``collect``),
    and raises the lower bound with the vertex-aligned stretches of every run
    (feasible: all their cells have their four corners in ``M``)."""
    parts: list[_Configs] = []
    Mi = _row_intervals(M)
    ptr = np.searchsorted(Mi[0], np.arange(ra.m + 1))
    C = Mi
    k = 1
    while k < ra.m - 1:
        live = C[0][_group_starts(C[0])]
        if live.size == 0:
            break
        ks = np.full(live.size, k)
        ext_s = _ext(ra, live - 1, ks)
        live = live[ext_s >= bound.floor]
        # the lower bound only has to be feasible, not the largest: without collecting,
        # runs are read at about eight window lengths per doubling
        if live.size and (collect or k <= 8 or k % (k // 8) == 0):
            row, p0, r = _cyclic_runs(C, live, rb.m)
            kr = np.full(row.size, k)
            inner_s, ext_s = _inner(ra, row - 1, kr), _ext(ra, row - 1, kr)
            rr = np.minimum(r, rb.m - 2)
            vert_u = np.where(rr > 0, _inner(rb, p0 - 1, rr), 0.0)
            bound.add(np.minimum(inner_s, vert_u))
            keep = (ext_s >= bound.floor) & (rr >= 1)
            if collect and keep.any():
                parts.append(_sub_windows(rb, row[keep], p0[keep], rr[keep], k,
                                          inner_s[keep], ext_s[keep], bound.floor))
        C = _intersect_rows(C, Mi, ptr, k)
        k += 1
    if not parts:
        return _empty()
    cfg = _Configs.cat(parts)
    keep = _disjoint(ra, cfg, same)
    if same:                      # each unordered pair once
        keep &= cfg.iA % ra.m < cfg.iC % rb.m
    return cfg.take(keep)


def _empty() -> _Configs:
    return _Configs(*(np.zeros(0, int) for _ in range(4)))


def _sub_windows(rb: _Ring, row: np.ndarray, p0: np.ndarray, r: np.ndarray, k: int,
                 inner_s: FloatArray, ext_s: FloatArray, lb: float) -> _Configs:
    """Every interior window p..q of stretch 2 inside the runs whose spans are
    compatible with a square pair of side at least ``lb``."""
    # expand runs to their start vertices p (absolute, unrolled in [m, 2m))
    _, j = _segments(r)
    p = (np.repeat(p0, r) + j) % rb.m + rb.m
    run_end = np.repeat(p0 + r - 1, r) % rb.m + rb.m
    run_end = np.where(run_end < p, run_end + rb.m, run_end)
    run_end = np.minimum(run_end, p + rb.m - 3)
    e_s, i_s = np.repeat(ext_s, r), np.repeat(inner_s, r)
    need = np.maximum(lb, i_s)
    U = rb.U
    q_hi = np.searchsorted(U, U[p] + e_s, side="right") - 1
    q_lo = np.searchsorted(U, U[p - 1] + need, side="left") - 1
    q_lo = np.maximum(q_lo, p)
    q_hi = np.minimum(q_hi, run_end)
    n = np.maximum(q_hi - q_lo + 1, 0)
    rows = np.repeat(np.repeat(row, r), n)
    q = np.repeat(q_lo, n) + _segments(n)[1]
    pp = np.repeat(p, n)
    return _Configs(rows - 1, np.full(rows.size, k), pp - 1, q - pp + 1)


def _windows_single(iv: _Intervals, ra: _Ring, rb: _Ring, same: bool, bound: _Bound,
                    collect: bool) -> _Configs:
    """Stretch 1 on one edge A, stretch 2 with interior vertices p .. p+k-1: those
    vertices confine stretch 1 to the intersection of their intervals on A (the
    vertex-aligned stretch 2 with that whole intersection is feasible: lower bound)."""
    A = np.flatnonzero(ra.L >= bound.floor)
    parts: list[_Configs] = []
    if A.size == 0:
        return _empty()
    mb = rb.m
    loA, hiA = iv.rows(A)
    cl, ch = loA.copy(), hiA.copy()
    pidx = np.arange(mb)
    k = 1
    while k < mb - 1:
        room = ch - cl
        ok = room >= bound.floor
        if not ok.any():
            break
        ks = np.full(mb, k)
        inner_u = _inner(rb, pidx - 1, ks)[None, :]
        ext_u = _ext(rb, pidx - 1, ks)[None, :]
        bound.add(np.minimum(room, inner_u)[ok])
        best = bound.floor
        if collect:
            a_i, p_i = np.nonzero(ok & (room >= best) & (ext_u >= best) & (room >= inner_u))
            if a_i.size:
                parts.append(_Configs(A[a_i], np.zeros(a_i.size, int), p_i - 1,
                                      np.full(a_i.size, k)))
        nxt = (pidx + k) % mb
        cl = np.maximum(cl, loA[:, nxt])
        ch = np.minimum(ch, hiA[:, nxt])
        k += 1
    if not parts:
        return _empty()
    cfg = _Configs.cat(parts)
    return cfg.take(_disjoint(ra, cfg, same))


def _pairs_single(ra: _Ring, rb: _Ring, same: bool, lb: float) -> _Configs:
    """Both stretches on single edges: every pair of edges long enough."""
    A = np.flatnonzero(ra.L >= lb)
    C = np.flatnonzero(rb.L >= lb)
    ga, gc = np.meshgrid(A, C, indexing="ij")
    a, c = ga.ravel(), gc.ravel()
    if same:
        keep = a < c
        a, c = a[keep], c[keep]
    z = np.zeros(a.size, int)
    return _Configs(a, z, c, z)


# ----------------------------------------------------------------------------- one LP


def _system(ra: _Ring, rb: _Ring, c: _Configs, sigma: float, beta: float,
            Iab: _Intervals, Iba: _Intervals,
            fixed: tuple[int, FloatArray] | None = None) -> FloatArray:
    """Rows ``c0 + cs s0 + cu u0 + ct t >= 0`` of a batch of configurations: both
    regions of length ``t`` (a square pair), or, with ``fixed = (side, length)``, the
    region of that side (0: stretch 1, 1: stretch 2) of the given length and the other
    of length ``t`` (the second level of the leximin order)."""
    mA, mB = ra.m, rb.m
    A, B = c.iA % mA, (c.iA + c.kA) % mA
    C, D = c.iC % mB, (c.iC + c.kC) % mB
    # ends against the other stretch's interior vertices

    def box(iv: _Intervals, edge: np.ndarray, ring: _Ring, first: np.ndarray,
            count: np.ndarray, m: int) -> tuple[FloatArray, FloatArray]:
        lo, hi = iv.window(edge, (first + 1) % m, count)
        return lo, np.minimum(hi, ring.L[edge])

    lo0, hi0 = box(Iab, A, ra, c.iC, c.kC, mB)
    lo1, hi1 = box(Iab, B, ra, c.iC, c.kC, mB)
    ulo0, uhi0 = box(Iba, C, rb, c.iA, c.kA, mA)
    ulo1, uhi1 = box(Iba, D, rb, c.iA, c.kA, mA)
    off_s = np.where(c.kA > 0, ra.L[A] + _inner(ra, c.iA, c.kA), 0.0)
    off_u = np.where(c.kC > 0, rb.L[C] + _inner(rb, c.iC, c.kC), 0.0)
    # points, affine in z = (s0, u0, t): x0 + J z
    n = A.size
    zero = np.zeros((n, 2))
    one, zero1 = np.ones(n), np.zeros(n)
    # the length of each stretch: t (coefficient 1) or a fixed constant (coefficient 0)
    len_s, ct_s = zero1, one
    len_u, ct_u = zero1, one
    if fixed is not None:
        if fixed[0] == 0:
            len_s, ct_s = np.asarray(fixed[1], float), zero1
        else:
            len_u, ct_u = np.asarray(fixed[1], float), zero1
    pts = {
        "P0": (ra.a[A], ra.t[A], zero, zero, ra.f[A]),
        "P1": (ra.a[B] + (len_s - off_s)[:, None] * ra.t[B], ra.t[B], zero,
               ct_s[:, None] * ra.t[B], ra.f[B]),
        "Q0": (rb.a[C], zero, rb.t[C], zero, rb.f[C]),
        "Q1": (rb.a[D] + (len_u - off_u)[:, None] * rb.t[D], zero, rb.t[D],
               ct_u[:, None] * rb.t[D], rb.f[D]),
    }
    rows = []
    for xn in ("P0", "P1"):
        for yn in ("Q0", "Q1"):
            X, Y = pts[xn], pts[yn]
            d = [sigma * (Y[j] - X[j]) for j in range(4)]
            for g in _gens_x(X[4], beta) + _gens_y(Y[4], beta):
                rows.append(np.stack([_cross(g, dj) for dj in d], axis=1))
    # boxes: lo0 <= s0 <= hi0, lo1 <= s0 + t - off_s <= hi1, and the same for u0
    limits = [(-lo0, one, zero1, zero1), (hi0, -one, zero1, zero1),
              (len_s - lo1 - off_s, one, zero1, ct_s), (hi1 + off_s - len_s, -one, zero1, -ct_s),
              (-ulo0, zero1, one, zero1), (uhi0, zero1, -one, zero1),
              (len_u - ulo1 - off_u, zero1, one, ct_u), (uhi1 + off_u - len_u, zero1, -one, -ct_u),
              (zero1, zero1, zero1, one)]
    rows += [np.stack(r, axis=1) for r in limits]
    return np.stack(rows, axis=1)


def _eliminate(rows: FloatArray, var: int) -> FloatArray:
    """Fourier-Motzkin: rows ``c0 + sum_j c_j x_j >= 0`` (B, R, K) without ``x_var``.

    Every row with a positive coefficient of ``x_var`` is added to every row with a
    negative one (each divided by its coefficient's magnitude); rows without it stay.
    The result is trimmed to the most valid rows of any problem of the batch (unused
    rows read ``1 >= 0``)."""
    B, R, K = rows.shape
    a = rows[:, :, var]
    pos, neg = a > _EPS, a < -_EPS
    with np.errstate(divide="ignore", invalid="ignore"):
        rp = np.where(pos[..., None], rows / np.abs(a)[..., None], 0.0)
        rn = np.where(neg[..., None], rows / np.abs(a)[..., None], 0.0)
    pairs = (rp[:, :, None, :] + rn[:, None, :, :]).reshape(B, R * R, K)
    valid = (pos[:, :, None] & neg[:, None, :]).reshape(B, R * R)
    zero = ~(pos | neg)
    out = np.concatenate([pairs, np.where(zero[..., None], rows, 0.0)], axis=1)
    valid = np.concatenate([valid, zero], axis=1)
    keep = np.delete(out, var, axis=2)
    trivial = np.zeros(K - 1)
    trivial[0] = 1.0
    keep = np.where(valid[..., None], keep, trivial)
    width = max(int(valid.sum(axis=1).max(initial=0)), 1)
    order = np.argsort(~valid, axis=1, kind="stable")[:, :width]
    return np.take_along_axis(keep, order[..., None], axis=1)


def _bounds(rows: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """For rows ``c0 + c1 y >= 0`` in one unknown ``y``: the interval of ``y`` and the
    least constant of the rows without ``y``."""
    c0, c1 = rows[:, :, 0], rows[:, :, 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        q = -c0 / c1
    lo = np.max(np.where(c1 > _EPS, q, -np.inf), axis=1)
    hi = np.min(np.where(c1 < -_EPS, q, np.inf), axis=1)
    flat = np.min(np.where(np.abs(c1) <= _EPS, c0, np.inf), axis=1)
    return lo, hi, flat


def _t_bounds(r: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Bounds of t left by rows ``c0 + cu u0 + ct t >= 0`` once u0 is eliminated: every
    lower bound of u0 (``u0 >= al + ga t``) against every upper bound, and the rows
    without u0; with the least constant of the rows left without t."""
    c0, cu, ct = r[:, :, 0], r[:, :, 1], r[:, :, 2]
    pos, neg = cu > _EPS, cu < -_EPS
    with np.errstate(divide="ignore", invalid="ignore"):
        al = np.where(pos | neg, -c0 / cu, 0.0)
        ga = np.where(pos | neg, -ct / cu, 0.0)
    D = ga[:, :, None] - ga[:, None, :]                # (ga_p - ga_n) t <= al_n - al_p
    E = al[:, None, :] - al[:, :, None]
    valid = pos[:, :, None] & neg[:, None, :]
    zero = ~(pos | neg)
    with np.errstate(divide="ignore", invalid="ignore"):
        q = E / D
        qz = -c0 / ct
    hi = np.min(np.where(valid & (D > _EPS), q, np.inf), axis=(1, 2))
    lo = np.max(np.where(valid & (D < -_EPS), q, -np.inf), axis=(1, 2))
    hi = np.minimum(hi, np.min(np.where(zero & (ct < -_EPS), qz, np.inf), axis=1))
    lo = np.maximum(lo, np.max(np.where(zero & (ct > _EPS), qz, -np.inf), axis=1))
    flat = np.minimum(np.min(np.where(valid & (np.abs(D) <= _EPS), E, np.inf), axis=(1, 2)),
                      np.min(np.where(zero & (np.abs(ct) <= _EPS), c0, np.inf), axis=1))
    return lo, hi, flat


def _solve(rows: FloatArray, ub: FloatArray, scale: float
           ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Largest common length t of each configuration (-1 if none) and its placement.

    Exact: ``s0`` then ``u0`` are eliminated (Fourier-Motzkin), which leaves bounds on
    ``t`` alone; ``u0`` and ``s0`` are then read back as the middle of their intervals.
    ``rows``: (B, R, 4) rows ``c0 + cs s0 + cu u0 + ct t >= 0``; ``ub``: (B,) bound."""
    B = ub.size
    cap = np.stack([ub, np.zeros(B), np.zeros(B), -np.ones(B)], axis=1)[:, None, :]
    rows = np.concatenate([rows, cap], axis=1)
    r_ut = _eliminate(rows, 1)                       # (c0, cu, ct)
    tol = ROUND_TOL * scale
    # every pair of rows meets in _t_bounds: blocks of about _BLOCK * 32 pairs
    step = max(1, (_BLOCK * 32) // r_ut.shape[1] ** 2)
    parts = [_t_bounds(r_ut[b:b + step]) for b in range(0, B, step)]
    t_lo, t_hi, flat = (np.concatenate([p[j] for p in parts]) for j in range(3))
    ok = (t_lo <= t_hi + tol) & (flat >= -tol) & (t_hi >= 0) & np.isfinite(t_hi)
    t = np.where(ok, np.maximum(t_hi, 0.0), -1.0)
    tt = np.maximum(t, 0.0)
    u_lo, u_hi, _ = _bounds(np.stack([r_ut[:, :, 0] + r_ut[:, :, 2] * tt[:, None],
                                      r_ut[:, :, 1]], axis=2))
    u0 = np.where(ok, 0.5 * (u_lo + u_hi), 0.0)
    base = rows[:, :, 0] + rows[:, :, 2] * u0[:, None] + rows[:, :, 3] * tt[:, None]
    s_lo, s_hi, _ = _bounds(np.stack([base, rows[:, :, 1]], axis=2))
    s0 = np.where(ok, 0.5 * (s_lo + s_hi), 0.0)
    return t, s0, u0


# ----------------------------------------------------------------------------- search


def _polyline(ring: _Ring, i: int, k: int, s0: float, t: float) -> tuple[FloatArray, tuple]:
    """Points of the stretch starting at s0 on edge i, length t, k interior vertices."""
    m = ring.m
    first = ring.a[i % m] + s0 * ring.t[i % m]
    verts = [ring.a[(i + j) % m] for j in range(1, k + 1)]
    end_edge = (i + k) % m
    if k == 0:
        last = first + t * ring.t[i % m]
    else:
        off = ring.L[i % m] - s0 + float(_inner(ring, np.array([i]), np.array([k]))[0])
        last = ring.a[end_edge] + (t - off) * ring.t[end_edge]
    pts = np.array([first, *verts, last])
    edges = [int(ring.edges[(i + j) % m]) for j in range(k + 1)]
    # the vertex is held with both normals, so either is its end normal
    return trim_vertex_ends(pts, edges, ROUND_TOL * float(ring.U[m]))


@dataclass
class _Found:
    """A solved configuration: ring pair and mode (the job), covered edges, the common
    length ``t`` and the placement; after the second level, both lengths."""

    job: tuple[int, int, float, str]
    cfg: tuple[int, int, int, int]
    t: float
    s0: float
    u0: float
    lengths: tuple[float, float] = (0.0, 0.0)


def _jobs(n_rings: int) -> list[tuple[int, int, float, str]]:
    return [(x, y, sigma, mode) for x in range(n_rings) for y in range(n_rings)
            for sigma, mode in ((1.0, "squeeze"), (-1.0, "expand"))]


def _configs_in(ra: _Ring, rb: _Ring, same: bool, runs: tuple[list[int], list[int]]
                ) -> _Configs:
    """Every configuration inside two runs of ring edges (for each stretch, the ring
    positions of its edges in order)."""
    cols = []
    for pos in runs:
        first, last = np.triu_indices(len(pos))
        cols.append((np.asarray(pos)[first], last - first))
    (ia, ka), (ic, kc) = cols
    ga = np.repeat(np.arange(ia.size), ic.size)
    gc = np.tile(np.arange(ic.size), ia.size)
    cfg = _Configs(ia[ga], ka[ga], ic[gc], kc[gc])
    return cfg.take(_disjoint(ra, cfg, same))


def _candidates(rings: list[_Ring], bound: _Bound, intervals: dict[Any, _Intervals],
                matrices: dict[Any, Any]) -> list[tuple[Any, _Configs]]:
    """Every configuration that can reach the bound, per job (exhaustive: the bound
    only rises with feasible configurations)."""
    prepared = []
    for collect in (False, True):          # the lower bound first, then the candidates
        for job in _jobs(len(rings)):
            x, y, sigma, _ = job
            ra, rb = rings[x], rings[y]
            both = _empty()
            if x <= y:
                both = _windows_both(matrices[x, y, sigma], ra, rb, x == y, bound, collect)
            single = _windows_single(intervals[x, y, sigma], ra, rb, x == y, bound, collect)
            if collect:
                pairs = _pairs_single(ra, rb, x == y, bound.floor) if x <= y else _empty()
                prepared.append((job, _Configs.cat([both, single, pairs])))
    return prepared


def _solve_jobs(rings: list[_Ring], beta: float, prepared: list[tuple[Any, _Configs]],
                intervals: dict[Any, _Intervals], bound: _Bound, scale: float) -> list[_Found]:
    """The largest square pair of every configuration that can still reach the top
    (largest bound first, in chunks; ties with the ``k``-th kept)."""
    found: list[_Found] = []
    for job, cfg in prepared:
        x, y, sigma, _ = job
        ra, rb = rings[x], rings[y]
        ub = _stretch_bound(ra, rb, cfg)
        keep = ub >= bound.floor
        cfg, ub = cfg.take(keep), ub[keep]
        order = np.argsort(-ub, kind="stable")
        for s in range(0, order.size, 256):
            chunk = order[s:s + 256]
            if ub[chunk[0]] < bound.floor:
                break
            rows = _system(ra, rb, cfg.take(chunk), sigma, beta, intervals[x, y, sigma],
                           intervals[y, x, sigma])
            t, s0, u0 = _solve(rows, ub[chunk], scale)
            ok = np.flatnonzero(t > 0)
            for j in ok:
                c = chunk[j]
                found.append(_Found(job, (int(cfg.iA[c]), int(cfg.kA[c]), int(cfg.iC[c]),
                                          int(cfg.kC[c])), float(t[j]), float(s0[j]),
                                    float(u0[j])))
            bound.add(t[ok])
    return found


def _second_level(rings: list[_Ring], beta: float, found: list[_Found],
                  intervals: dict[Any, _Intervals], scale: float) -> None:
    """The second level of the leximin order (definition 7.1) of each configuration:
    one region at the optimal smallest length, the other as long as possible (both
    sides tried; exact, the same three-variable program with one length fixed)."""
    by_job: dict[Any, list[_Found]] = {}
    for f in found:
        by_job.setdefault(f.job, []).append(f)
    for job, items in by_job.items():
        x, y, sigma, _ = job
        ra, rb = rings[x], rings[y]
        cfg = _Configs(*(np.array([f.cfg[j] for f in items]) for j in range(4)))
        t1 = np.array([f.t for f in items])
        best_len = t1.copy()
        best_side = np.full(t1.size, -1)
        best_s0 = np.array([f.s0 for f in items])
        best_u0 = np.array([f.u0 for f in items])
        for side in (0, 1):
            ub = _ext(rb, cfg.iC, cfg.kC) if side == 0 else _ext(ra, cfg.iA, cfg.kA)
            rows = _system(ra, rb, cfg, sigma, beta, intervals[x, y, sigma],
                           intervals[y, x, sigma], fixed=(side, t1))
            t2, s0, u0 = _solve(rows, ub, scale)
            better = t2 > best_len * (1 + TIE)
            best_len = np.where(better, t2, best_len)
            best_side = np.where(better, side, best_side)
            best_s0 = np.where(better, s0, best_s0)
            best_u0 = np.where(better, u0, best_u0)
        for j, f in enumerate(items):
            f.s0, f.u0 = float(best_s0[j]), float(best_u0[j])
            long_ = float(best_len[j])
            f.lengths = ((f.t, long_) if best_side[j] == 0 else (long_, f.t)
                         if best_side[j] == 1 else (f.t, f.t))


def _own_optimum(rings: list[_Ring], found: list[_Found]) -> list[_Found]:
    """The configurations that are optimal on their own edges: a configuration whose
    smallest region is beaten by one of its sub-configurations (fewer edges on either
    side, all of them found, since they rank higher) is not a plan of those edges."""
    keep = np.ones(len(found), bool)
    by_job: dict[Any, list[int]] = {}
    for j, f in enumerate(found):
        by_job.setdefault(f.job, []).append(j)
    for job, idx in by_job.items():
        ra, rb = rings[job[0]], rings[job[1]]
        c = np.array([found[j].cfg for j in idx])
        t = np.array([found[j].t for j in idx])
        if c[:, [1, 3]].max() == 0:
            continue

        def inside(i: np.ndarray, k: np.ndarray, i2: np.ndarray, k2: np.ndarray,
                   m: int) -> np.ndarray:
            # [sub] stretch (rows) inside [super] stretch (columns), cyclically
            return (i[:, None] - i2[None, :]) % m + k[:, None] <= k2[None, :]

        at = np.asarray(idx)
        # supers in blocks of columns: the (sub, super) matrix stays about 1M cells
        step = max(1, (_BLOCK * 32) // len(idx))
        for b in range(0, len(idx), step):
            cs, ts = c[b:b + step], t[b:b + step]
            sub = inside(c[:, 0], c[:, 1], cs[:, 0], cs[:, 1], ra.m) \
                & inside(c[:, 2], c[:, 3], cs[:, 2], cs[:, 3], rb.m)
            if job[0] == job[1]:        # one ring: a pair may be stored either way round
                sub |= inside(c[:, 0], c[:, 1], cs[:, 2], cs[:, 3], ra.m) \
                    & inside(c[:, 2], c[:, 3], cs[:, 0], cs[:, 1], ra.m)
            beaten = sub & (t[:, None] > ts[None, :] * (1 + TIE))
            keep[at[b:b + step][beaten.any(axis=0)]] = False
    return [f for f, k in zip(found, keep, strict=True) if k]


def _canonical(rings: list[_Ring], beta: float, found: list[_Found],
               intervals: dict[Any, _Intervals], polygon: Polygon) -> list[_Found]:
    """The placement of a pair on one ring, independent of which stretch the search
    called the first: both ways round are placed, and the one whose end points come
    first (relative to the part, rounded) is kept, so a renumbered part gets the same
    regions."""
    same = [j for j, f in enumerate(found) if f.job[0] == f.job[1]]
    if not same:
        return found
    swapped = [_Found(found[j].job, found[j].cfg[2:] + found[j].cfg[:2], found[j].t,
                      found[j].u0, found[j].s0) for j in same]
    _second_level(rings, beta, swapped, intervals, polygon.size)
    out = list(found)

    def key(f: _Found) -> tuple[Any, ...]:
        # the ranking's own order: leximin, then the geometric tie-break
        pair = _pairs(rings, [f])[0]
        return (leximin_key(np.array(pair.lengths), polygon.size),
                geometric_key(pair.regions, polygon))

    for j, g in zip(same, swapped, strict=True):
        if key(g) < key(found[j]):
            out[j] = g
    return out


def _finish(rings: list[_Ring], beta: float, found: list[_Found], intervals: dict[Any, _Intervals],
            polygon: Polygon) -> list[_Found]:
    """The second leximin level and the numbering-free placement of the configurations
    kept, in the leximin order."""
    _second_level(rings, beta, found, intervals, polygon.size)
    found = _canonical(rings, beta, found, intervals, polygon)
    found.sort(key=lambda f: (-min(f.lengths), -max(f.lengths)))
    return found


def _pairs(rings: list[_Ring], found: list[_Found]) -> list[StretchPair]:
    out = []
    for f in found:
        x, y, _, mode = f.job
        iA, kA, iC, kC = f.cfg
        p1, e1 = _polyline(rings[x], iA, kA, f.s0, f.lengths[0])
        p2, e2 = _polyline(rings[y], iC, kC, f.u0, f.lengths[1])
        out.append(StretchPair((p1, p2), (e1, e2), f.lengths, mode))
    return out


def _check_args(polygon: Any, mu: Any, margin: Any) -> float:
    """The half-angle ``beta = atan(mu) - margin`` of the shrunk friction cones."""
    polygon = check_polygon(polygon)
    mu_v = check_mu_scalar(mu, "mu")
    margin_v = check_scalar(margin, "margin", nonnegative=True)
    return float(shrunk_half_angle(mu_v, margin_v))


def crosses_a_vertex(polygon: Polygon, mu: Any, margin: Any = DEFAULT_MARGIN_DEG) -> bool:
    """Whether a region of two fingers with friction can cover some vertex.

    A vertex inside a region pushes along both its edges' normals, and for any chord to
    the other finger both must hold it: each within ``beta = atan(mu) - margin`` of the
    chord (the arc of the module docstring), so the two normals are less than
    ``2 beta`` apart.  Where every vertex turns by at least that much (every corner of
    a CAD polygon at ordinary friction), no region covers a vertex and the regions along
    the boundary are the single-edge regions of algorithm 7.1.

    >>> sq = Polygon([[0, 0], [10, 0], [10, 3], [0, 3]])
    >>> crosses_a_vertex(sq, mu=0.3)
    False
    >>> import numpy as np
    >>> a = np.linspace(0, 2 * np.pi, 360, endpoint=False)
    >>> crosses_a_vertex(Polygon(np.c_[np.cos(a), np.sin(a)]), mu=0.3)
    True
    """
    beta = _check_args(polygon, mu, margin)
    if beta <= 0:
        return False
    for ring in _rings(polygon):
        f, g = ring.f, np.roll(ring.f, -1, axis=0)      # force directions at vertex k + 1
        turn = np.arctan2(np.abs(_cross(f, g)), np.sum(f * g, axis=1))
        # a relative 1e-9 on the angle: a vertex at the limit is left to the exact search
        if np.any(turn < 2 * beta * (1 + TOL) + ROUND_TOL):
            return True
    return False


def two_finger_stretches(polygon: Polygon, mu: Any, margin: Any = DEFAULT_MARGIN_DEG,
                         top: Any = 5, ties: bool = False) -> list[StretchPair]:
    """Optimal independent regions along the boundary for two fingers with friction.

    Regions are stretches of the rings (see the module docstring).  The pairs are
    ordered by definition 7.1's leximin order: the smallest region first, then the
    other (the second level: one region at the optimal smallest length, the other as
    long as the same covered edges allow).  Exact up to about 1e-12 of the part's size.

    Parameters
    ----------
    polygon : Polygon
    mu : float
        Friction coefficient of both fingers.
    margin : float
        Safety margin in degrees inside the friction cones.
    top : int or None
        How many pairs of regions to return (distinct configurations: which edges each
        region covers); None: every configuration that holds (small parts only: their
        number grows with the cube of the edges of a curved outline).
    ties : bool
        Also return every configuration whose smallest region ties the ``top``-th's
        (to a relative 1e-9), so that a later order (leximin, then geometry) is exact.

    Returns
    -------
    list of StretchPair

    Examples
    --------
    >>> import numpy as np
    >>> a = np.linspace(0, 2 * np.pi, 360, endpoint=False)
    >>> disc = Polygon(np.c_[50 * np.cos(a), 50 * np.sin(a)])
    >>> best = two_finger_stretches(disc, mu=0.3, margin=0.5, top=1)[0]
    >>> round(best.min_length, 1), len(best.region_edges[0]) > 20
    (27.9, True)
    """
    beta = _check_args(polygon, mu, margin)
    top_v = None if top is None else check_int(top, "top", minimum=1)
    if not isinstance(ties, bool):
        raise TypeError(f"ties must be a bool, got {ties!r}")
    if beta <= 0:
        return []
    rings = _rings(polygon)
    # every ordered ring pair is a job, so a job's reverse intervals are another's
    intervals = {(x, y, sigma): _Intervals(rings[x], rings[y], sigma, beta)
                 for x, y, sigma, _ in _jobs(len(rings))}
    matrices = {(x, y, sigma): _vertex_matrix(rings[x], rings[y], sigma, beta)
                for x, y, sigma, _ in _jobs(len(rings)) if x <= y}
    want = top_v
    for _ in range(4):
        # configurations beaten on their own edges are dropped; ask for more until
        # ``top`` remain (or every configuration was seen)
        bound = _Bound(2 ** 62 if want is None else want)
        prepared = _candidates(rings, bound, intervals, matrices)
        found = _solve_jobs(rings, beta, prepared, intervals, bound, polygon.size)
        found.sort(key=lambda f: -f.t)
        found = _own_optimum(rings, found)
        if want is None or top_v is None or len(found) >= top_v or bound.value == 0.0:
            break
        want = 4 * want
    if not found:
        return []
    if top_v is not None:
        kth = found[min(top_v, len(found)) - 1].t
        found = [f for f in found if f.t >= kth * (1 - TIE)] if ties else found[:top_v]
    found = _finish(rings, beta, found, intervals, polygon)
    return _pairs(rings, found if ties or top_v is None else found[:top_v])


def stretch_regions(polygon: Polygon, stretches: Any, mu: Any,
                    margin: Any = DEFAULT_MARGIN_DEG) -> StretchPair | None:
    """Optimal independent regions inside two given stretches (definition 7.1).

    ``stretches``: for each finger, the consecutive edges of one ring it may cover, in
    ring order (a single edge is a stretch of one edge).  Every configuration inside
    them is solved exactly; the best by the leximin order, squeezing or expanding.
    None when no pair of regions holds.

    >>> sq = Polygon([[0, 0], [10, 0], [10, 3], [0, 3]])
    >>> r = stretch_regions(sq, [[0], [2]], mu=0.3)
    >>> r.region_edges, round(r.min_length, 3)
    (((0,), (2,)), 0.872)
    """
    beta = _check_args(polygon, mu, margin)
    if isinstance(stretches, (str, bytes)) or len(stretches) != 2:
        raise ValueError(f"stretches must hold two sequences of edges, got {stretches!r}")
    rings = _rings(polygon)
    where = {int(e): (r, p) for r, ring in enumerate(rings) for p, e in enumerate(ring.edges)}
    runs = []
    for k, st in enumerate(stretches):
        edges = polygon.check_stretch(st, f"stretches[{k}]")
        runs.append((where[edges[0]][0], [where[e][1] for e in edges]))
    if set(map(int, stretches[0])) & set(map(int, stretches[1])):
        raise ValueError(f"the two stretches share an edge, got {stretches!r}")
    if beta <= 0:
        return None
    x, y = runs[0][0], runs[1][0]
    ra, rb = rings[x], rings[y]
    intervals = {(a, b, sigma): _Intervals(rings[a], rings[b], sigma, beta)
                 for a, b in ((x, y), (y, x)) for sigma in (1.0, -1.0)}
    cfg = _configs_in(ra, rb, x == y, (runs[0][1], runs[1][1]))
    # every sub-configuration, longest bound first, in chunks behind the best found
    prepared = [((x, y, sigma, mode), cfg) for sigma, mode in ((1.0, "squeeze"),
                                                               (-1.0, "expand"))]
    found = _solve_jobs(rings, beta, prepared, intervals, _Bound(1), polygon.size)
    if not found:
        return None
    best = max(f.t for f in found)
    found = _finish(rings, beta, [f for f in found if f.t >= best * (1 - TIE)], intervals,
                    polygon)
    return _pairs(rings, found[:1])[0]
