r"""Regions that run along the boundary: two fingers with friction.

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

import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any, cast

import numpy as np

from ..core import budget
from ..core._angles import shrunk_half_angle
from ..core._checks import FloatArray, check_int, check_mu_scalar, check_scalar
from ..core._geom import ends_key, leximin_key, midpoints, trim_vertex_ends
from ..core.kernels import jit_setting, started
from ..core.tolerances import ANGLE_SLACK, DEFER_PAD, ROUND_TOL, TOL
from . import _stretch_kernels
from ._free_third import FreeThird
from ._stretch_lp import (
    BOX_REACH,
    _box_bound,
    _ends,
    _solve,
    _system,
)
from ._stretch_windows import (
    _BLOCK,
    _EPS,
    TIE,
    _both_kept,
    _Bound,
    _Configs,
    _disjoint,
    _empty,
    _ext,
    _fan,
    _gens_x,
    _gens_y,
    _Intervals,
    _pairs_single,
    _Ring,
    _rings,
    _row_intervals,
    _stretch_bound,
    _turns,
    _vertex_matrix,
    _windows_both,
    _windows_single,
)
from .polygon import Polygon, check_polygon
from .regions import DEFAULT_MARGIN_DEG

__all__ = ["StretchPair", "StretchSearch", "two_finger_stretches", "stretch_regions",
           "crosses_a_vertex"]


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


# ----------------------------------------------------------------------------- search


def _span(ring: _Ring, i: int, k: int, s0: float, t: float
          ) -> tuple[tuple[float, float], tuple[float, float]]:
    """The first and last point of the stretch starting at ``s0`` on edge ``i``, length
    ``t``, ``k`` interior vertices (before any trimming), in plain floats
    (:attr:`_Ring.floats`: a point or two per call, where numpy's calls cost more than
    the arithmetic; numpy's operations on the points, one coordinate at a time)."""
    A, T, L, U = ring.floats
    m = ring.m
    (ax, ay), (tx, ty) = A[i % m], T[i % m]
    first = (ax + s0 * tx, ay + s0 * ty)
    if k == 0:
        return first, (first[0] + t * tx, first[1] + t * ty)
    # _inner of the one stretch, read from the arc positions as it reads them
    end_edge = (i + k) % m
    j = i % m + m
    off = L[i % m] - s0 + (U[j + k] - U[j + 1])
    (ex, ey), (fx, fy) = A[end_edge], T[end_edge]
    return first, (ex + (t - off) * fx, ey + (t - off) * fy)


def _polyline(ring: _Ring, i: int, k: int, s0: float, t: float
              ) -> tuple[FloatArray, tuple[int, ...]]:
    """Points of the stretch starting at s0 on edge i, length t, k interior vertices."""
    m = ring.m
    at = (i + np.arange(k + 1)) % m                 # the edges covered, in ring order
    pts = np.empty((k + 2, 2))
    pts[0], pts[-1] = _span(ring, i, k, s0, t)
    pts[1:k + 1] = ring.a[at[1:]]                   # the interior vertices
    edges = ring.edges[at].tolist()
    # the vertex is held with both normals, so either is its end normal
    return trim_vertex_ends(pts, edges, ROUND_TOL * float(ring.U[m]))


def _stretch_ends(ring: _Ring, i: int, k: int, s0: float, t: float
                  ) -> tuple[tuple[float, float], tuple[float, float]]:
    """The two ends of :func:`_polyline`'s stretch (:func:`_span`), trimmed as
    ``trim_vertex_ends`` trims it (numpy's hypot), without the points between: all the
    ranking's geometric key reads of a region (:func:`_canonical`)."""
    first, last = _span(ring, i, k, s0, t)
    if k == 0:
        return first, last
    A, m = ring.floats[0], ring.m
    tiny = ROUND_TOL * ring.floats[3][m]
    inner_first, inner_last = A[(i + 1) % m], A[(i + k) % m]
    covered = k + 1
    if np.hypot(inner_first[0] - first[0], inner_first[1] - first[1]) <= tiny:
        first, covered = (inner_first[0], inner_first[1]), covered - 1
    if covered > 1 and np.hypot(last[0] - inner_last[0], last[1] - inner_last[1]) <= tiny:
        last = (inner_last[0], inner_last[1])
    return first, last


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
    #: the same alternative as a plan the caller excludes (:class:`_Exclusion`)
    similar: bool = False
    #: :func:`_pairs`' placement, with the ``(s0, u0, lengths)`` it was placed at
    placed: tuple[Any, StretchPair] | None = field(default=None, repr=False, compare=False)


def _positions(rings: list[_Ring]) -> dict[int, tuple[int, int]]:
    """Each usable polygon edge's ring and position in it."""
    return {int(e): (r, p) for r, ring in enumerate(rings) for p, e in enumerate(ring.edges)}


def _member(codes: np.ndarray, known: np.ndarray) -> np.ndarray:
    """``np.isin(codes, known)`` for ``known`` sorted and unique: a binary search
    each, without sorting ``codes`` (hundreds of thousands, read in every round)."""
    at = np.minimum(np.searchsorted(known, codes), len(known) - 1)
    return cast("np.ndarray", known[at] == codes)


class _Exclusion:
    """Plans already kept (``distinct=``): a configuration whose regions, whatever
    their placement, overlap a kept plan's regions by more than ``fraction`` of the
    shorter (:func:`fcgrasp.model.distinct.same_alternative`) is the same alternative as
    that plan.  Its regions start and end inside its end edges' intervals
    (:meth:`_spans`) and are at least ``t`` long; the least overlap over all such
    regions is exact (:meth:`_least_excess`), so :meth:`similar` says "surely a copy"
    only of configurations whose every placement is one.  Such configurations are
    solved (a configuration they beat is still no plan) but neither raise the search's
    bound nor are returned; so are the configurations of the plans ``seen`` (already
    read by the caller: their covered edges and mode).  Before a configuration is
    solved, :meth:`threshold` bounds the ``t`` above which it is surely a copy: when
    the arc from its first start to its last end outside the partner region is below
    ``(1 - fraction) min(t, partner's length)``.

    With ``third`` (the distinct search of three fingers with friction), a configuration
    stands for its *pair* plan, its two regions and a third finger on the longest free
    stretch (:mod:`fcgrasp.model._free_third`), and the kept plans have three regions: a
    configuration is surely a kept plan's copy when two of the plan's regions are surely
    its two regions' partners (as above) and the third finger's free stretch surely
    overlaps the plan's remaining region by more than ``fraction`` of the shorter
    (:meth:`_third_mask`)."""

    def __init__(self, rings: list[_Ring], polygon: Polygon, kept: Any,
                 fraction: float, seen: Any = (), third: bool = False) -> None:
        where = _positions(rings)
        #: configurations excluded as such (plans already read), per ring pair and
        #: mode: the codes (:meth:`_codes`) of their starts and interior vertices, on
        #: one ring both ways round
        found: dict[tuple[int, int, str], list[tuple[int, int, int, int]]] = {}
        for edges, mode in seen:
            # a region covers consecutive edges of one ring (or one edge): its two end
            # edges say whether it is on the rings (the rounds read thousands of plans
            # of hundreds of edges each)
            if all(int(st[0]) in where and int(st[-1]) in where for st in edges):
                (x, pa), (y, pc) = where[int(edges[0][0])], where[int(edges[1][0])]
                ka, kc = len(edges[0]) - 1, len(edges[1]) - 1
                for (r1, a, k1), (r2, c, k2) in (((x, pa, ka), (y, pc, kc)),
                                                 ((y, pc, kc), (x, pa, ka))):
                    found.setdefault((r1, r2, mode), []).append((a, k1, c, k2))
        self.seen: dict[tuple[int, int, str], np.ndarray] = {}
        for (r1, r2, mode), rows in found.items():
            a, k1, c, k2 = np.array(rows, np.int64).T
            self.seen[r1, r2, mode] = np.unique(self._codes(rings, r1, r2, a, k1, c, k2))
        self.fraction = float(fraction)
        self.tol = ROUND_TOL * polygon.size
        self.plans: list[list[tuple[int, float, float]]] = []
        self._by_rings: dict[tuple[int, int], tuple[FloatArray, ...]] = {}
        for regions, region_edges in kept:
            arcs: list[tuple[int, float, float]] = []
            for pts, edges in zip(regions, region_edges, strict=True):
                pts = np.asarray(pts, float)
                if int(edges[0]) not in where or int(edges[-1]) not in where:
                    arcs = []
                    break
                r0, p0 = where[int(edges[0])]
                r1, p1 = where[int(edges[-1])]
                ring = rings[r0]
                u0 = ring.U[p0] + float(np.hypot(*(pts[0] - ring.a[p0])))
                u1 = ring.U[p1] + float(np.hypot(*(pts[-1] - ring.a[p1])))
                if r1 != r0:
                    arcs = []
                    break
                if u1 < u0 - self.tol:                  # wraps past vertex 0
                    u1 += float(ring.U[ring.m])
                arcs.append((r0, u0, max(u1, u0)))
            if len(arcs) == (3 if third else 2):
                self.plans.append(arcs)
        #: the pair plans' third fingers (``third``): their free stretches
        self.free = FreeThird(rings, polygon, THIRD_PAD * self.tol) if third else None

    def __bool__(self) -> bool:
        return bool(self.plans) or bool(self.seen)

    @staticmethod
    def _codes(rings: list[_Ring], x: int, y: int, iA: Any, kA: Any, iC: Any, kC: Any
               ) -> np.ndarray:
        """One integer per configuration of rings ``x`` and ``y`` (starts reduced)."""
        ma, mb = rings[x].m, rings[y].m
        return cast("np.ndarray", ((np.asarray(iA, np.int64) % ma * (ma + 1) + kA) * mb
                                   + np.asarray(iC, np.int64) % mb) * (mb + 1) + kC)

    @staticmethod
    def _spans(rings: list[_Ring], job: tuple[int, int, float, str], cfg: _Configs,
               intervals: dict[Any, _Intervals], reach: int | None = None
               ) -> tuple[FloatArray, FloatArray]:
        """Where the regions of each configuration can start and end on its two rings,
        ``(n, 4)`` each: first start, last start, first end, last end, as arc lengths
        (every pair of regions that holds on those edges has its end points in its end
        edges' intervals, :func:`_ends`; a stretch that ends on a long edge reaches only
        the part of it that holds against the other stretch's interior vertices).  An
        empty interval (no region pair holds) gives a last start or end of -inf.  With
        ``reach``, intervals that contain those (:func:`_ends`'s, cheaper); ``reach=0``:
        against no vertex, the whole end edges (the whole stretches)."""
        x, y, sigma, _ = job
        ra, rb = rings[x], rings[y]
        (lo0, hi0, lo1, hi1, ulo0, uhi0, ulo1, uhi1), (off_s, off_u) = _ends(
            ra, rb, cfg, intervals[x, y, sigma], intervals[y, x, sigma],
            stretch_kernels_for(ra.m * rb.m), reach)
        a, c = ra.U[np.asarray(cfg.iA) % ra.m], rb.U[np.asarray(cfg.iC) % rb.m]
        return (np.stack([a + lo0, a + hi0, a + off_s + lo1, a + off_s + hi1], axis=1),
                np.stack([c + ulo0, c + uhi0, c + off_u + ulo1, c + off_u + uhi1], axis=1))

    @staticmethod
    def _least_excess(s: FloatArray, t: FloatArray, k0: FloatArray, k1: FloatArray,
                      f: float, eps: float) -> FloatArray:
        """For each configuration (rows: ``s`` as :meth:`_spans`, smallest region
        ``t``) and arc ``[k0, k1]`` (columns), the least of ``overlap([a, b], [k0, k1]) -
        f min(b - a, k1 - k0)`` over its regions ``[a, b]`` (start and end in their
        intervals, at least ``t`` long; each bound loosened by ``eps``).  The function is
        continuous and linear between the lines ``a = s0, s1, k0, k1``, ``b = e0, e1,
        k0, k1`` and ``b - a = t, k1 - k0``, so the least is at a crossing of two of them
        inside: every crossing is evaluated (-inf: no region)."""
        s0, s1, e0, e1 = (s[:, j, None] for j in range(4))
        tt, ln = t[:, None], k1 - k0
        starts, ends, gaps = (s0, s1, k0, k1), (e0, e1, k0, k1), (tt, ln)
        crossings = [(a, b) for a in starts for b in ends] + \
            [(a, a + d) for a in starts for d in gaps] + [(b - d, b) for b in ends for d in gaps]
        best = np.full((s.shape[0], k0.size), np.inf)
        for a, b in crossings:
            a, b = np.broadcast_arrays(a, b)
            inside = ~((a < s0 - eps) | (a > s1 + eps) | (b < e0 - eps) | (b > e1 + eps)
                       | (b - a < tt - eps))
            value = np.maximum(0.0, np.minimum(b, k1) - np.maximum(a, k0)) \
                - f * np.minimum(b - a, ln)
            best = np.where(inside, np.minimum(best, value), best)
        best[best == np.inf] = -np.inf
        return cast("FloatArray", best)

    def _surely_copy(self, per: float, s: FloatArray, t: FloatArray, k0: FloatArray,
                     k1: FloatArray) -> np.ndarray:
        """Whether every region of each configuration (rows) on one ring overlaps the
        arc ``[k0, k1]`` (columns; or its turn by a perimeter ``per``) by more than
        ``fraction`` of the shorter, plus the tolerance (:meth:`_least_excess`)."""
        out = np.zeros((s.shape[0], k0.size), bool)
        for shift in (-per, 0.0, per):
            out |= self._least_excess(s, t, k0 + shift, k1 + shift, self.fraction,
                                      self.tol) > self.tol
        return out

    @staticmethod
    def _common(per: float, a0: FloatArray, a1: FloatArray, u0: FloatArray,
                u1: FloatArray) -> FloatArray:
        """Arc the spans ``[a0, a1]`` (rows) share with the arcs [u0, u1] (columns) on a
        ring of perimeter ``per`` (either turned by a perimeter)."""
        a0, a1 = a0[:, None], a1[:, None]
        common = np.zeros((a0.shape[0], len(u0)))
        for shift in (-per, 0.0, per):
            common += np.maximum(0.0, np.minimum(a1, u1 + shift) - np.maximum(a0, u0 + shift))
        return common

    @staticmethod
    def _outside(per: float, a0: FloatArray, a1: FloatArray, u0: FloatArray,
                 u1: FloatArray) -> FloatArray:
        """Arc of the spans ``[a0, a1]`` (rows) outside the arcs [u0, u1] (columns) on a
        ring of perimeter ``per``."""
        return (a1 - a0)[:, None] - _Exclusion._common(per, a0, a1, u0, u1)

    def _fused(self, rings: list[_Ring], x: int, y: int, spans: tuple[FloatArray, ...],
               arcs: tuple[FloatArray, ...], t: FloatArray, threshold: bool,
               out: np.ndarray, mask: np.ndarray | None = None) -> bool:
        """:meth:`threshold` (``threshold``: ``spans`` the arcs ``a0x, a1x, a0y, a1y``) or
        :meth:`similar` (``spans`` as :meth:`_spans`) of many configurations by the
        compiled loop (the same numbers, without a matrix of configurations by
        kept plans for each step), writing ``out``; only the cells of ``mask`` (rows by
        columns) where given; False (nothing done) when the matrix is small or the
        loops do not run."""
        if len(spans[0]) * len(arcs[0]) < (FUSED_CELLS if threshold else FUSED_SIMILAR) \
                or not stretch_kernels_for(rings[x].m * rings[y].m):
            return False
        per = (float(rings[x].U[rings[x].m]), float(rings[y].U[rings[y].m]))
        arcs = tuple(np.ascontiguousarray(v, float) for v in arcs)
        cells = np.ones((1, 1), bool) if mask is None else np.ascontiguousarray(mask)
        if threshold:
            _stretch_kernels.exclusion_rows(
                *(np.ascontiguousarray(v, float) for v in spans), *arcs, *per,
                float(self.tol), float(1 - self.fraction), cells, mask is not None, out)
            return True
        work = np.zeros(len(out), bool)
        _stretch_kernels.similar_rows(
            *(np.ascontiguousarray(v, float) for v in spans), *arcs, *per, float(self.tol),
            float(self.fraction), np.ascontiguousarray(t, float), cells, mask is not None,
            work)
        out |= work
        return True

    def _arcs(self, x: int, y: int) -> tuple[FloatArray, ...] | None:
        """The kept plans' arcs on rings ``x`` (first region) and ``y`` (second), each
        plan both ways round: ``ax0, ax1, ay0, ay1``, one column per plan; with
        ``third``, one column per ordered pair of a plan's regions, then the remaining
        region's ring and arc: ``ax0, ax1, ay0, ay1, ring, k0, k1``."""
        got = self._by_rings.get((x, y))
        if got is None:
            cols = [(a[i][1], a[i][2], a[j][1], a[j][2],
                     *(a[3 - i - j] if len(a) == 3 else ()))
                    for a in self.plans for i in range(len(a)) for j in range(len(a))
                    if i != j and a[i][0] == x and a[j][0] == y]
            got = self._by_rings[x, y] = tuple(
                np.array(c, float) for c in zip(*cols, strict=True)) if cols else ()
        return got or None

    def _third_mask(self, x: int, y: int, cfg: _Configs, arcs: tuple[FloatArray, ...],
                    spans: tuple[FloatArray, FloatArray] | None = None) -> np.ndarray:
        """Which configurations (rows) have a third finger whose free stretch surely
        overlaps each column's remaining region (``arcs[4:]``) by more than ``fraction``
        of the shorter: every free stretch the configuration's plan can have
        (:meth:`FreeThird.of`: at least its sure arc, at most its widest) on that
        region's ring, the sure arc's overlap above ``fraction`` of the widest's
        length or the region's, whichever is less, by :data:`THIRD_PAD` tolerances.
        ``spans`` (:meth:`_spans`) say which end edges a trim may free
        (:meth:`FreeThird.trims`; without them, every end edge may be)."""
        assert self.free is not None
        trims = None if spans is None else self.free.trims(x, y, cfg, spans)
        ring, g0, g1, e0, e1 = self.free.of(x, y, cfg, trims)
        kr, k0, k1 = arcs[4].astype(np.int64), arcs[5], arcs[6]
        out = np.zeros((ring.size, kr.size), bool)
        for r in np.unique(kr):
            cols, rows = np.flatnonzero(kr == r), np.flatnonzero(ring == r)
            if not rows.size:
                continue
            ring_r = self.free.rings[int(r)]
            common = self._common(float(ring_r.U[ring_r.m]), g0[rows], g1[rows], k0[cols],
                                  k1[cols])
            short = np.minimum((e1 - e0)[rows, None], (k1 - k0)[cols])
            out[np.ix_(rows, cols)] = common - self.fraction * short > THIRD_PAD * self.tol
        return out

    def similar(self, rings: list[_Ring], job: tuple[int, int, float, str], cfg: _Configs,
                t: FloatArray, intervals: dict[Any, _Intervals]) -> np.ndarray:
        """Which configurations of ``job`` (smallest regions ``t``) are surely the same
        alternative as a kept plan (their regions inside :meth:`_spans`)."""
        x, y = job[0], job[1]
        out = np.zeros(len(t), bool)
        known = self.seen.get((x, y, job[3]))
        if known is not None:
            out |= _member(self._codes(rings, x, y, cfg.iA, cfg.kA, cfg.iC, cfg.kC), known)
        arcs = self._arcs(x, y)
        if arcs is None or not len(t):
            return out
        spans = self._spans(rings, job, cfg, intervals, BOX_REACH)
        mask = None if len(arcs) == 4 else self._third_mask(x, y, cfg, arcs, spans)
        if mask is not None:
            # only the configurations whose third finger can be a copy's
            live = np.flatnonzero(mask.any(axis=1))
            if live.size:
                sub = np.zeros(live.size, bool)
                self._similar_in(rings, job, (spans[0][live], spans[1][live]),
                                 np.asarray(t, float)[live], arcs[:4], mask[live], sub)
                out[live] |= sub
            return out
        self._similar_in(rings, job, spans, np.asarray(t, float), arcs, None, out)
        return out

    def _similar_in(self, rings: list[_Ring], job: tuple[int, int, float, str],
                    spans: tuple[FloatArray, FloatArray], t: FloatArray,
                    arcs: tuple[FloatArray, ...], mask: np.ndarray | None,
                    out: np.ndarray) -> None:
        """:meth:`similar`'s test of the kept plans' columns ``arcs`` (only those of
        ``mask``, rows by columns, where given) on configurations whose regions lie in
        ``spans``, or-ed into ``out``."""
        x, y = job[0], job[1]
        if self._fused(rings, x, y, spans, arcs, t, False, out, mask):
            return
        ax0, ax1, ay0, ay1 = arcs
        tt = t - self.tol
        both = self._surely_copy(float(rings[x].U[rings[x].m]), spans[0], tt, ax0, ax1) \
            & self._surely_copy(float(rings[y].U[rings[y].m]), spans[1], tt, ay0, ay1)
        out |= (both if mask is None else both & mask).any(axis=1)

    def threshold(self, rings: list[_Ring], job: tuple[int, int, float, str],
                  cfg: _Configs, intervals: dict[Any, _Intervals]) -> FloatArray:
        """For each configuration of ``job``, a length above which it is surely the same
        alternative as a kept plan (:meth:`similar` with any smallest region ``t``
        greater than it; ``inf``: none).  ``similar`` asks, for each kept plan, that
        each stretch's arc outside the partner region be below ``(1 - fraction)
        min(t, partner's length)`` less the tolerance: for ``t`` above ``(outside +
        tol) / (1 - fraction)`` on both sides, where each partner is longer than that.
        A configuration already read holds at any ``t > 0``."""
        x, y = job[0], job[1]
        out = np.full(len(cfg.iA), np.inf)
        known = self.seen.get((x, y, job[3]))
        if known is not None:
            out[_member(self._codes(rings, x, y, cfg.iA, cfg.kA, cfg.iC, cfg.kC), known)] = 0.0
        keep = 1 - self.fraction
        arcs = self._arcs(x, y)
        if keep <= 0 or arcs is None or not len(out):
            return out
        mask = None if len(arcs) == 4 else self._third_mask(x, y, cfg, arcs)
        rows = np.arange(len(out)) if mask is None else np.flatnonzero(mask.any(axis=1))
        if not rows.size:
            return out
        if mask is not None:
            cfg, mask = cfg.take(rows), mask[rows]
        sub = out[rows]
        # before the configurations are solved (all of them, in chunks of thousands): the
        # whole stretches, from the first edge's start to the last edge's end
        sx, sy = self._spans(rings, job, cfg, intervals, 0)
        a0x, a1x, a0y, a1y = spans = (sx[:, 0], sx[:, 3], sy[:, 0], sy[:, 3])
        if not self._fused(rings, x, y, spans, arcs[:4], sub, True, sub, mask):
            ax0, ax1, ay0, ay1 = arcs[:4]
            px, py = float(rings[x].U[rings[x].m]), float(rings[y].U[rings[y].m])
            ta = (self._outside(px, a0x, a1x, ax0, ax1) + self.tol) / keep
            tc = (self._outside(py, a0y, a1y, ay0, ay1) + self.tol) / keep
            tau = np.where((ax1 - ax0 > ta) & (ay1 - ay0 > tc), np.maximum(ta, tc), np.inf)
            if mask is not None:
                tau = np.where(mask, tau, np.inf)
            sub = np.minimum(sub, tau.min(axis=1))
        out[rows] = sub
        return out


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


#: Vertex pairs (``m_a * m_b``) from which the search runs the compiled loops of
#: :mod:`fcgrasp.model._stretch_kernels`: numba's start-up (about 0.4 s of CPU once per
#: process, to import it and load the cached code) is then less than what they save.
#: Once loaded, they run for every part; ``FCGRASP_JIT=0`` never runs them,
#: ``FCGRASP_JIT=1`` always.
KERNEL_CELLS = 1_500_000

#: CPU seconds of batched numpy solves (:func:`~fcgrasp.model._stretch_lp._solve`) after
#: which a process solves the rest compiled: on an outline of a few hundred edges whose
#: stretches hold many vertices (an icon's rounded corners) each chunk of configurations
#: costs tens of milliseconds of Fourier-Motzkin, and numba's start-up is soon repaid.
#: The two solve the same (``tests/test_stretch_kernels.py``).
NUMPY_SOLVE_BUDGET = 0.4
_numpy_spent = [0.0]

#: Configurations of one job to solve from which the compiled solve runs, whatever the
#: size of the rings (a noisy outline can leave tens of thousands).
KERNEL_CONFIGS = 20_000


#: Cells (configurations x kept plans' columns) from which the exclusion's tests run
#: compiled (:meth:`_Exclusion._fused`): the threshold, and :meth:`_Exclusion.similar`
#: (32 crossings of lines per cell and turn: compiled from a few cells on).
FUSED_CELLS, FUSED_SIMILAR = 20_000, 16

#: How many rounding tolerances a pair plan's third finger must beat the overlap a copy
#: needs by (:meth:`_Exclusion._third_mask`), and by which one free stretch must be
#: longer than another to be surely the third finger's (:class:`FreeThird`): their
#: lengths are sums of up to thousands of edges, in another order than the plan's.
THIRD_PAD = 64

#: Configurations of one job from which :func:`_own_optimum` runs compiled (the numpy
#: filter compares every pair: 41,000 configurations of an icon took 37 s).
KERNEL_OWN = 256


#: A search asked for more plans than this (or for all of them) loads the compiled loops
#: whatever the rings' size: a deep list of a smooth outline solves hundreds of
#: thousands of configurations (three fingers on ``icons/circle.svg``, whose pairs are
#: read to 512 two-finger plans: 6.6 s of CPU in numpy, 1.0 s compiled).
KERNEL_TOP = 64


def _load_for_depth(top: int | None) -> None:
    """Load the compiled loops for a search of ``top`` plans (:data:`KERNEL_TOP`), where
    numba is there and ``FCGRASP_JIT`` leaves the choice to the search."""
    if (top is None or top > KERNEL_TOP) and jit_setting() is None \
            and not _stretch_kernels.loaded():
        _stretch_kernels.available()


def stretch_kernels_for(cells: int) -> bool:
    """Whether the stretch search of rings of ``cells`` vertex pairs runs compiled (and
    so holds no array of every pair: the memory estimate of
    :func:`fcgrasp.pipeline.check_search` asks too): once numba started in this
    process for any of the package's loops, these included
    (:func:`fcgrasp.core.kernels.started`), from :data:`KERNEL_CELLS`, or once this
    process spent :data:`NUMPY_SOLVE_BUDGET` in numpy solves."""
    setting = jit_setting()
    if setting is not None:
        return setting
    return started() or cells >= KERNEL_CELLS or \
        _numpy_spent[0] > NUMPY_SOLVE_BUDGET


class _Keys:
    """Keys of :class:`_Bound`: a mode and the first start edge of a configuration's two
    stretches (rings numbered one after the other)."""

    def __init__(self, rings: list[_Ring]) -> None:
        self.offset = np.concatenate([[0], np.cumsum([r.m for r in rings])]).astype(int)
        self.total = int(self.offset[-1])

    def _edge(self, ring: int, pos: Any, sigma: float) -> np.ndarray:
        m = self.offset[ring + 1] - self.offset[ring]
        return cast("np.ndarray", self.offset[ring] + np.asarray(pos) % m
                    + (0 if sigma > 0 else self.total))

    def __call__(self, job: tuple[int, int, float, str], a: Any, b: Any) -> np.ndarray:
        """The key of pairs starting at edges ``a`` (ring x) and ``b`` (ring y)."""
        x, y, sigma, _ = job
        return cast("np.ndarray", np.minimum(self._edge(x, a, sigma), self._edge(y, b, sigma)))

    def first(self, job: tuple[int, int, float, str], a: Any) -> np.ndarray:
        """The key of pairs whose stretch 1 (edge ``a`` of ring x) comes first."""
        return self._edge(job[0], a, job[2])


def _vertex_runs(ra: _Ring, rb: _Ring, beta: float) -> dict[float, Any]:
    """The runs of True of every row of the vertex matrix of each mode, as row pointers,
    first and last columns (compiled for large rings; :func:`_vertex_matrix` else)."""
    if stretch_kernels_for(ra.m * rb.m):
        gx = np.stack([g for f in _fan(ra) for g in _gens_x(f, beta)], axis=1)
        gy = np.stack([g for f in _fan(rb) for g in _gens_y(f, beta)], axis=1)
        # a cell holds only if the two force directions are opposite within 2 beta (each
        # within beta of the chord), and a vertex only if its two normals are within
        # 2 beta of each other: the kernel reads no other cell (a slack keeps it exact)
        width = 2 * beta + ANGLE_SLACK
        va = np.where(_turns(ra) <= width, np.arctan2(ra.f[:, 1], ra.f[:, 0]) + np.pi, np.nan)
        # the tree's bounds are decided with a pad far above their rounding (a few ulps
        # of the largest coordinate)
        pad = ROUND_TOL * 8 * max(float(np.abs(ra.a).max()), float(np.abs(rb.a).max()))
        out = _stretch_kernels.vertex_runs_tree(
            ra.a[:, 0].copy(), ra.a[:, 1].copy(), gx, va, rb.a[:, 0].copy(),
            rb.a[:, 1].copy(), np.ascontiguousarray(gy), np.arctan2(rb.f[:, 1], rb.f[:, 0]),
            width, pad)
        return {1.0: out[:3], -1.0: out[3:]}
    runs = {}
    for sigma in (1.0, -1.0):
        row, first, last = _row_intervals(_vertex_matrix(ra, rb, sigma, beta))
        runs[sigma] = (np.searchsorted(row, np.arange(ra.m + 1)), first, last)
    return runs


def _both(runs: Any, ra: _Ring, rb: _Ring, same: bool, floor: float, collect: bool,
          bound: _Bound | None = None) -> tuple[FloatArray, _Configs]:
    """:func:`_windows_both`, compiled for large rings (pruned by ``bound``'s value: the
    lower bounds it leaves out could not raise it)."""
    ptr, first, last = runs
    if stretch_kernels_for(ra.m * rb.m):
        value, keep = (bound.value, bound.k) if bound is not None else (0.0, 0)
        best, *cfg = _stretch_kernels.windows(ptr, first, last, ra.U, rb.U, ra.m, rb.m, floor,
                                              collect, same, value, keep)
        return best, _both_kept(_Configs(*cfg), ra, rb, same)
    return _windows_both(runs, ra, rb, same, floor, collect)


def _single(iv: _Intervals, ra: _Ring, rb: _Ring, same: bool, floor: float, collect: bool,
            bound: _Bound | None = None, offsets: tuple[int, int] = (0, 0)
            ) -> tuple[tuple[np.ndarray, np.ndarray, FloatArray], _Configs]:
    """:func:`_windows_single`, compiled for large rings (without ``collect``, pruned by
    ``bound``'s value: the edges it skips could not raise it; ``offsets``: the rings'
    first keys, :class:`_Keys`)."""
    if not stretch_kernels_for(ra.m * rb.m):
        return _windows_single(iv, ra, rb, same, floor, collect)
    A = np.flatnonzero(ra.L >= floor)
    value, keep = (bound.value, bound.k) if bound is not None and not collect else (0.0, 0)
    if keep:
        A = A[np.argsort(-ra.L[A], kind="stable")]          # the longest first
    width = 2 * iv.beta + ANGLE_SLACK
    order, angle_b = _by_angle(rb)
    va = np.arctan2(ra.f[:, 1], ra.f[:, 0]) + np.pi
    wa, wp, wv, iA, iC, kC = _stretch_kernels.single(
        A, ra.a[:, 0].copy(), ra.a[:, 1].copy(), ra.t[:, 0].copy(), ra.t[:, 1].copy(), ra.L,
        iv.gx, va, rb.a[:, 0].copy(), rb.a[:, 1].copy(), iv.gy, order, angle_b, width, rb.U,
        iv.sigma, _EPS, floor, collect, same, value, keep, *offsets)
    cfg = _Configs(iA, np.zeros(iA.size, int), iC, kC)
    return (wa, wp, wv), cfg.take(_disjoint(ra, cfg, same))


def _solve_any(rows: FloatArray, ub: FloatArray, scale: float, compiled: bool,
               floor: float = 0.0) -> tuple[FloatArray, FloatArray, FloatArray]:
    """:func:`~fcgrasp.model._stretch_lp._solve`, or its compiled loop; there, with
    ``floor`` > 0, a configuration whose largest ``t`` is surely below it gets NaN
    (unsolved: see :func:`_solve_in`)."""
    if compiled:
        t, s0, u0 = _stretch_kernels.solve_rows(rows, ub, ROUND_TOL * scale, _EPS, floor)
        return t, s0, u0
    start = time.process_time()
    try:
        return _solve(rows, ub, scale)
    finally:
        _numpy_spent[0] += time.process_time() - start


def _by_angle(ring: _Ring) -> tuple[np.ndarray, FloatArray]:
    """The ring's edges in order of their force direction's angle, and those angles."""
    angle = np.arctan2(ring.f[:, 1], ring.f[:, 0])
    order = np.argsort(angle, kind="stable")
    return order, angle[order]


def _guessed_floors(bound: _Bound) -> list[float]:
    """The floors :func:`_candidates` guesses from the bound's keys, highest first, each
    above the bound's own floor."""
    seen = np.sort(bound.best[bound.best > 0])[::-1]
    if not seen.size:
        return []
    m = min(bound.k, seen.size)
    ranks = [-(-m // 4), -(-m // 2)] + ([seen.size] if seen.size < bound.k else [])
    assert len(ranks) <= _GUESSES
    out: list[float] = []
    for r in ranks:
        g = float(seen[r - 1]) * (1 - TIE)
        if g > bound.floor and (not out or g < out[-1]):
            out.append(g)
    return out


def _candidates(rings: list[_Ring], bound: _Bound, intervals: dict[Any, _Intervals],
                runs: dict[Any, Any], keys: _Keys, prebound: bool = True,
                guesses: list[float] | None = None, lower: bool = True,
                max_configs: int | None = None) -> list[tuple[Any, _Configs]]:
    """Every configuration that can reach the bound, per job (exhaustive: the bound
    only rises with feasible configurations, one per key).  ``prebound`` False: the
    vertex-aligned stretches do not raise the bound (an excluded plan's copies would);
    with a fixed floor, without ``prebound`` or without ``lower``, they are not
    computed.

    ``guesses`` (an empty list): floors above the bound's own, guessed from the keys'
    values, are put in it, highest first, and the bound starts at the first
    (``bound.start``).  One key holds many of the top configurations of a smooth
    outline, so the ``top``-th key is far below the ``top``-th configuration (and 0
    where fewer keys are filled): the keys a quarter and half of the way down (of
    ``top`` or of those filled), and the last filled when fewer than ``top``.
    :func:`_search` checks that the ``top``-th found reaches the floor, and takes the
    next guess when not.

    ``max_configs``: the most configurations to collect; one job's collection that
    takes the count over it ends the search (:class:`~fcgrasp.core.budget.
    BudgetExhausted`, ``"max_memory"``), before the next job's."""
    count = 0
    prepared = []
    for collect in (False, True):          # the lower bound first, then the candidates
        if not collect and (not (prebound and lower) or bound.fixed is not None):
            continue                        # no lower bound would count
        if collect and guesses is not None and bound.fixed is None:
            guesses[:] = _guessed_floors(bound)
            if guesses:
                bound.start = guesses.pop(0)
        for job in _jobs(len(rings)):
            x, y, sigma, _ = job
            ra, rb = rings[x], rings[y]
            both = _empty()
            if x <= y:
                best, both = _both(runs[x, y][sigma], ra, rb, x == y, bound.floor, collect,
                                   bound if prebound and bound.fixed is None else None)
                if not collect and prebound:
                    # stretch 1 comes first (ring x <= y; on one ring, it starts first)
                    rows = np.flatnonzero(best > 0)
                    bound.add(keys.first(job, rows), best[rows])
            (a, p, v), single = _single(
                intervals[x, y, sigma], ra, rb, x == y, bound.floor, collect,
                bound if prebound and bound.fixed is None else None,
                (int(keys.offset[x]), int(keys.offset[y])))
            if not collect and prebound:
                bound.add(keys(job, a, p), v)
            if collect:
                pairs = _pairs_single(ra, rb, x == y, bound.floor) if x <= y else _empty()
                prepared.append((job, _Configs.cat([both, single, pairs])))
                count += int(prepared[-1][1].iA.size)
                if max_configs is not None and count > max_configs:
                    raise budget.BudgetExhausted("max_memory")
    return prepared


@dataclass
class _Job:
    """A job's configurations, their bounds (arc length ``ub``, the ends' boxes
    ``box``), the order they are solved in and the solutions found (NaN: not yet)."""

    cfg: _Configs
    ub: FloatArray
    box: FloatArray
    order: np.ndarray
    compiled: bool
    t: FloatArray
    s0: FloatArray
    u0: FloatArray
    #: the floor each unsolved configuration was proved below (0: none)
    below: FloatArray


#: Bytes a collected configuration takes at the peak, the unit of :attr:`_Memo.max_bytes`:
#: four int64 of the configuration, seven arrays of :class:`_Job`, and the collection's
#: concatenation and sorts (measured: a 1,000-edge smooth outline at mu 1.0 grows by
#: about 124 bytes per configuration collected).
CONFIG_BYTES = 128


class _Memo:
    """What the runs of one search share (the rounds of ``distinct=``, whose floors
    differ): every configuration whose arc length reaches ``floor`` collected once, and
    each one's solution once solved.  A run whose ``top``-th configuration falls below
    ``floor`` may have missed one: the caller lowers the floor (:meth:`lower`) and runs
    again (:meth:`StretchSearch.pairs`); at or above it nothing is missed (a
    configuration below the floor can neither reach the ``top`` nor beat one that does
    in :func:`_own_optimum`)."""

    def __init__(self, floor: float = 0.0, max_bytes: int | None = None) -> None:
        self.floor = floor
        self.prepared: list[tuple[Any, _Configs]] | None = None
        self.jobs: dict[Any, _Job] = {}
        #: the most bytes the configurations collected and their solutions may take
        #: (:data:`CONFIG_BYTES` each): a collection over it ends the search
        #: (:class:`~fcgrasp.core.budget.BudgetExhausted`, ``"max_memory"``;
        #: :func:`_candidates`)
        self.max_bytes = max_bytes

    @property
    def max_configs(self) -> int | None:
        """The most configurations a collection may hold (``max_bytes``)."""
        return None if self.max_bytes is None else self.max_bytes // CONFIG_BYTES

    def lower(self, floor: float) -> None:
        """Collect again, down to ``floor``."""
        self.floor, self.prepared, self.jobs = floor, None, {}


def _job(rings: list[_Ring], job: Any, cfg: _Configs, intervals: dict[Any, _Intervals],
         floor: float, lazy: bool = False) -> _Job:
    """A job's configurations reaching ``floor``, ordered by the ends' boxes; ``lazy``
    (a job kept for later runs, whose floors are not known yet): ordered by arc
    length, the boxes NaN until :func:`_fill_boxes` reads them."""
    x, y, sigma, _ = job
    ra, rb = rings[x], rings[y]
    ub = _stretch_bound(ra, rb, cfg)
    keep = ub >= floor
    cfg, ub = cfg.take(keep), ub[keep]
    # many to solve: the compiled loops repay numba's start-up
    compiled = stretch_kernels_for(ra.m * rb.m if ub.size < KERNEL_CONFIGS
                                   else KERNEL_CELLS)
    if lazy:
        nan = np.full(ub.size, np.nan)
        return _Job(cfg, ub, nan.copy(), np.argsort(-ub, kind="stable"), compiled, nan,
                    nan.copy(), nan.copy(), np.zeros(ub.size))
    # the ends' boxes bound a configuration far below its arc length where the ends are
    # confined: solved in that order, pruned by it (the arc length stays the program's
    # cap, so each configuration's solution is unchanged)
    box = np.minimum(ub, _box_bound(ra, rb, cfg, intervals[x, y, sigma],
                                    intervals[y, x, sigma], compiled))
    nan = np.full(ub.size, np.nan)
    return _Job(cfg, ub, box, np.argsort(-box, kind="stable"), compiled, nan,
                nan.copy(), nan.copy(), np.zeros(ub.size))


def _fill_boxes(rings: list[_Ring], job: Any, J: _Job, chunk: np.ndarray,
                intervals: dict[Any, _Intervals]) -> None:
    """The ends' boxes of a lazy job's configurations ``chunk`` not yet bounded."""
    todo = chunk[np.isnan(J.box[chunk])]
    if todo.size:
        x, y, sigma, _ = job
        J.box[todo] = np.minimum(J.ub[todo], _box_bound(
            rings[x], rings[y], J.cfg.take(todo), intervals[x, y, sigma],
            intervals[y, x, sigma], J.compiled))


#: Whether the compiled solve leaves the configurations it proves below the run's floor
#: unsolved (1; 0: every configuration solved in full, the reference).
FLOOR_SOLVE = 1

#: Configurations :func:`_solve_jobs` reads at a time: the first chunk (the floor
#: rises with each), and the largest a lazy job's chunks grow to (each twice the last:
#: most of a distinct search's configurations are a kept plan's copies, only
#: bounded and deferred, at a numpy call's cost per chunk, not per configuration).
CHUNK, LAZY_CHUNK = 256, 16384


def _chunks(order: np.ndarray, grow: bool) -> Any:
    """``order`` in chunks of :data:`CHUNK`, growing to :data:`LAZY_CHUNK` if ``grow``."""
    s, size = 0, CHUNK
    while s < order.size:
        yield order[s:s + size]
        s += size
        if grow:
            size = min(2 * size, LAZY_CHUNK)


def _solve_in(rings: list[_Ring], job: Any, J: _Job, todo: np.ndarray, beta: float,
              intervals: dict[Any, _Intervals], scale: float, floor: float = 0.0) -> None:
    """Solve the configurations ``todo`` of ``job`` into its arrays ``J.t``, ``J.s0``,
    ``J.u0``.  With ``floor`` (the run's: the bound's, or the memo's, below which a run's
    answer is not taken; a configuration below it can neither reach an answer taken
    nor beat one of its configurations), the compiled solve leaves those it proves
    below it NaN, unsolved (:func:`~fcgrasp.model._stretch_kernels._below`): not kept,
    and solved again by a later run whose floor is lower."""
    if not todo.size:
        return
    x, y, sigma, _ = job
    if not J.compiled and stretch_kernels_for(0):     # the numpy budget spent
        J.compiled = True
    rows = _system(rings[x], rings[y], J.cfg.take(todo), sigma, beta, intervals[x, y, sigma],
                   intervals[y, x, sigma], compiled=J.compiled)
    J.t[todo], J.s0[todo], J.u0[todo] = _solve_any(rows, J.ub[todo], scale, J.compiled,
                                                   floor)
    if floor > 0:
        J.below[todo[np.isnan(J.t[todo])]] = floor


@dataclass
class _Run:
    """One job of :func:`_solve_jobs`: what :meth:`settle` reads and where it files."""

    rings: list[_Ring]
    job: Any
    J: _Job
    beta: float
    intervals: dict[Any, _Intervals]
    scale: float
    exclude: _Exclusion | None
    similar: dict[Any, tuple[_Job, list[np.ndarray]]] | None
    found: list[_Found]
    bound: _Bound
    keys: _Keys
    #: the memo's floor (0 without one): below it the run's answer is not taken
    least: float = 0.0

    def settle(self, chunk: np.ndarray) -> None:
        """Solve what of ``chunk`` is not yet solved, then file (a kept plan's copies in
        ``similar``), keep and count (the bound) the chunk."""
        J, job, cfg = self.J, self.job, self.J.cfg
        floor = FLOOR_SOLVE * max(self.bound.floor, self.least)
        # not solved yet, nor proved below this floor by an earlier run
        proved = J.below[chunk]         # below that floor, so below this one if higher
        todo = chunk[np.isnan(J.t[chunk]) & ~((proved > 0) & (proved <= floor))]
        _solve_in(self.rings, job, J, todo, self.beta, self.intervals, self.scale, floor)
        part = cfg.take(chunk)
        t, s0, u0 = J.t[chunk], J.s0[chunk], J.u0[chunk]
        ok = np.flatnonzero(t > 0)
        sim = self.exclude.similar(self.rings, job, part.take(ok), t[ok], self.intervals) \
            if self.exclude else np.zeros(ok.size, bool)
        if self.similar is not None and sim.any():
            self.similar.setdefault(job, (J, []))[1].append(chunk[ok[sim]])
            ok, sim = ok[~sim], sim[~sim]
        for j, same in zip(ok, sim, strict=True):
            c = chunk[j]
            self.found.append(_Found(job, (int(cfg.iA[c]), int(cfg.kA[c]), int(cfg.iC[c]),
                                           int(cfg.kC[c])), float(t[j]), float(s0[j]),
                                     float(u0[j]), similar=bool(same)))
        ok = ok[~sim]
        self.bound.add(self.keys(job, part.iA[ok], part.iC[ok]), t[ok])


def _solve_jobs(rings: list[_Ring], beta: float, prepared: list[tuple[Any, _Configs]],
                intervals: dict[Any, _Intervals], bound: _Bound, scale: float,
                keys: _Keys, exclude: _Exclusion | None = None,
                memo: _Memo | None = None,
                similar: dict[Any, tuple[_Job, list[np.ndarray]]] | None = None,
                deferred: dict[Any, tuple[_Job, list[np.ndarray]]] | None = None
                ) -> list[_Found]:
    """The largest square pair of every configuration that can still reach the top
    (largest bound first, in chunks; ties with the ``k``-th kept).  With ``exclude``,
    the configurations that are surely a kept plan's alternative do not raise the
    bound: marked ``similar``, or, given the dict ``similar``, filed there (their
    indices in their job's configurations: on a curved outline they are tens of
    thousands, and only :func:`_own_optimum` reads them).  With ``memo``,
    configurations solved by an earlier run are not solved again.  Given the dict
    ``deferred`` as well, a configuration that is surely a kept plan's alternative at
    any smallest region above a threshold (:meth:`_Exclusion.threshold`) below its
    bound can be a plan only below that threshold: it waits until the job's other
    configurations are done, then is solved in the order of the thresholds while they
    reach the floor.  Those left are excluded or below the floor, filed in
    ``deferred``; only :func:`_own_optimum` could read them, as beaters
    (:func:`_solve_deferred`)."""
    found: list[_Found] = []
    for job, cfg in prepared:
        if memo is None:
            J = _job(rings, job, cfg, intervals, bound.floor)
        elif job in memo.jobs:
            J = memo.jobs[job]
        else:
            J = memo.jobs[job] = _job(rings, job, cfg, intervals, memo.floor, lazy=True)
        cfg, ub, box, order = J.cfg, J.ub, J.box, J.order

        run = _Run(rings, job, J, beta, intervals, scale, exclude, similar, found, bound,
                   keys, 0.0 if memo is None else memo.floor)
        later_idx: list[np.ndarray] = []
        later_tau: list[FloatArray] = []
        for chunk in _chunks(order, memo is not None):
            if exclude:                     # a distinct round: the budget may end it
                budget.check()
            else:                           # a deeper read of the ranked list may end
                budget.poll()
            if memo is not None:            # lazy: by arc length, boxes as they come
                if ub[chunk[0]] < bound.floor:
                    break
                _fill_boxes(rings, job, J, chunk, intervals)
                chunk = chunk[box[chunk] >= bound.floor]
                if chunk.size == 0:
                    continue
            else:
                chunk = chunk[box[chunk] >= bound.floor]
                if chunk.size == 0:
                    break
            if deferred is not None and exclude:
                # a kept plan's copies: a plan only below their threshold, so they
                # wait for it (most never reach the floor)
                fresh = np.isnan(J.t[chunk])
                tau = exclude.threshold(rings, job, cfg.take(chunk[fresh]), intervals)
                later = np.zeros(chunk.size, bool)
                later[fresh] = tau * (1 + DEFER_PAD) < box[chunk[fresh]]
                if later.any():
                    later_idx.append(chunk[later])
                    later_tau.append(tau[later[fresh]])
                    chunk = chunk[~later]
            run.settle(chunk)
        if later_idx:
            idx, tau = np.concatenate(later_idx), np.concatenate(later_tau)
            by = np.argsort(-tau, kind="stable")
            idx, tau = idx[by], tau[by]
            # the thresholds fall and the floor only rises: once one falls short of
            # the floor, every one after it does
            short = 0
            for s in range(0, idx.size, CHUNK):
                budget.check()              # a distinct round: the budget may end it
                e = min(s + CHUNK, idx.size)
                short = s + int(np.count_nonzero(tau[s:e] * (1 + DEFER_PAD) >= bound.floor))
                run.settle(idx[s:short])
                if short < e:
                    break
            if short < idx.size:
                assert deferred is not None
                deferred.setdefault(job, (J, []))[1].append(idx[short:])
    return found


def _inside_any(c: _Configs, supers: np.ndarray, ma: int, mb: int, same: bool,
                compiled: bool = False) -> np.ndarray:
    """Which configurations ``c`` lie inside one of ``supers`` (rows ``iA, kA, iC,
    kC``; cyclically; on one ring either way round): for each super, only the
    configurations whose first start lies in its first stretch are read (sorted;
    ``compiled``: the same test by one sweep over the first starts,
    :func:`fcgrasp.model._stretch_kernels.inside_supers`)."""
    out = np.zeros(len(c.iA), bool)
    if compiled:
        sup = np.ascontiguousarray(supers, np.int64).reshape(-1, 4)
        # each super's entry at each first start its first stretch covers, with the room
        # it leaves for a configuration's interior vertices there (both ways round)
        rep = sup[:, 1] + 1
        es = np.repeat(np.arange(len(sup)), rep)
        d = np.arange(es.size) - np.repeat(np.cumsum(rep) - rep, rep)
        ep, eroom = (sup[es, 0] + d) % ma, sup[es, 1] - d
        entries = np.lexsort((-eroom, ep))
        ep, eroom, es = ep[entries], eroom[entries], es[entries]
    for flip in ((False, True) if same else (False,)):
        a, ka, cc, kc = (c.iC, c.kC, c.iA, c.kA) if flip else (c.iA, c.kA, c.iC, c.kC)
        a = a % ma
        if compiled:
            _stretch_kernels.inside_supers(
                *(np.ascontiguousarray(v, np.int64) for v in (a, ka, cc, kc, ep, eroom, es)),
                sup, int(ma), int(mb), out)
            continue
        by = np.argsort(a, kind="stable")
        sa = a[by]
        for iA, kA, iC, kC in supers:
            lo = iA % ma
            spans = ((lo, lo + kA + 1),) if lo + kA < ma else \
                ((lo, ma), (0, lo + kA + 1 - ma))
            for s0, s1 in spans:
                sel = by[np.searchsorted(sa, s0):np.searchsorted(sa, s1)]
                if sel.size:
                    out[sel] |= ((a[sel] - iA) % ma + ka[sel] <= kA) \
                        & ((cc[sel] - iC) % mb + kc[sel] <= kC)
    return out


def _solve_deferred(rings: list[_Ring], beta: float, intervals: dict[Any, _Intervals],
                    scale: float, found: list[_Found], floor: float,
                    deferred: dict[Any, tuple[_Job, list[np.ndarray]]],
                    similar: dict[Any, tuple[_Job, list[np.ndarray]]]) -> None:
    """Solve the deferred configurations (:func:`_solve_jobs`) that may beat a found
    configuration reaching ``floor`` in :func:`_own_optimum` (those inside it, either
    way round on one ring), and file the feasible ones in ``similar`` as beaters."""
    for job, (J, parts) in deferred.items():
        budget.check()
        supers = np.array([f.cfg for f in found if f.job == job and f.t >= floor],
                          dtype=np.int64).reshape(-1, 4)
        supers = supers[supers[:, [1, 3]].max(axis=1) > 0]
        if not len(supers):
            continue
        # the union of the parts, sorted (a mask: numpy's hashed unique takes 0.7 s on
        # the 800,000 configurations a curved outline defers)
        mask = np.zeros(len(J.t), bool)
        for part in parts:
            mask[part] = True
        idx = np.flatnonzero(mask)
        # a beater's smallest region exceeds the found one's (at least the floor) by
        # the tie tolerance, and its box bounds it
        idx = idx[np.isnan(J.t[idx]) & (J.box[idx] > floor * (1 + TIE))]
        todo = idx[_inside_any(J.cfg.take(idx), supers, rings[job[0]].m, rings[job[1]].m,
                               job[0] == job[1], J.compiled)]
        _solve_in(rings, job, J, todo, beta, intervals, scale)
        done = np.concatenate(parts)
        done = done[J.t[done] > 0]
        if done.size:
            similar.setdefault(job, (J, []))[1].append(done)


def _address_held() -> int | None:
    """The process's address space in bytes (Linux), None where it cannot be read."""
    try:
        import resource

        with open("/proc/self/statm") as fh:
            return int(fh.read().split()[0]) * resource.getpagesize()
    except (ImportError, OSError, ValueError):
        return None


@contextmanager
def _address_space(max_bytes: int | None, base: int | None = None) -> Iterator[None]:
    """The block's new memory capped at ``max_bytes`` more than the process's address
    space now (Linux, ``RLIMIT_AS``; elsewhere nothing is capped): one job's collection
    of a smooth outline can ask for gigabytes at once, inside a compiled loop, before
    its count can be checked.  ``base``: the address space to count from (default now:
    the search's rounds count from where the first began, not from what the last
    kept).  An allocation past the cap ends the search
    (:class:`~fcgrasp.core.budget.BudgetExhausted`, ``"max_memory"``), and the limit in
    force before is put back.  (While the block runs, every thread of the process is
    under the cap.)"""
    held = _address_held() if base is None else base
    try:
        import resource

        before = resource.getrlimit(resource.RLIMIT_AS)
    except (ImportError, OSError, ValueError):
        before = None
    if max_bytes is None or before is None or held is None:
        yield
        return
    cap = held + max_bytes
    if before[0] != resource.RLIM_INFINITY:
        cap = min(cap, before[0])
    try:
        resource.setrlimit(resource.RLIMIT_AS, (cap, before[1]))
    except (ValueError, OSError):
        yield
        return
    try:
        yield
    except MemoryError:
        raise budget.BudgetExhausted("max_memory") from None
    finally:
        resource.setrlimit(resource.RLIMIT_AS, before)


#: Searches :func:`_search` runs at most before it solves every configuration.
_ATTEMPTS = 5
#: Whether the first search guesses floors from its keys' values (:func:`_candidates`).
_GUESS = True
#: Floors :func:`_guessed_floors` guesses at most (a quarter and half of the way down
#: the keys, and the last key filled).
_GUESSES = 3
#: Times a guessed floor that keeps fewer than ``top`` (the own-optimum filter drops
#: most of a smooth outline's configurations, while the bound, which counts them, rises
#: above the floor) is halved and fixed before the bound's own is tried.
_HALVINGS = 3


def _search(rings: list[_Ring], beta: float, intervals: dict[Any, _Intervals],
            runs: dict[Any, Any], top: int | None, scale: float,
            exclude: _Exclusion | None = None, memo: _Memo | None = None) -> list[_Found]:
    """The configurations optimal on their own edges (:func:`_own_optimum`), largest
    ``t`` first: all of them (``top`` None), or at least every one that ties the
    ``top``-th (to the relative tie tolerance).

    The bound counts feasible configurations, but a configuration beaten by one of its
    own sub-configurations is dropped afterwards, so the ``top``-th kept can fall below
    the floor the search pruned with.  The search is then run again with the floor
    fixed at that ``top``-th (every configuration that reaches it solved, its
    sub-configurations with it), until the floor it pruned with is below the
    ``top``-th it kept; when fewer than ``top`` are kept, with a bound of four times as
    many; the last attempt prunes nothing.  ``exclude``: configurations surely the
    same alternative as a kept plan are left out (after the filter, which they still
    take part in); they then run without the vertex-aligned lower bound, on every
    configuration, shared with other runs through ``memo``."""
    keys = _Keys(rings)
    if not exclude:
        memo = None
    want, fixed = top, None
    # floors guessed by the first search (_candidates), tried in turn while too high
    guesses: list[float] | None = [] if _GUESS and top is not None else None
    guessing, start, halve = False, 0.0, 0
    attempts = _ATTEMPTS + (_GUESSES + _HALVINGS if _GUESS else 0)
    for attempt in range(attempts):
        if top is None or attempt == attempts - 1:
            fixed = 0.0
        # an excluded plan's copies add no lower bounds: each configuration counts once
        bound = _Bound(want or 1, 2 * keys.total, fixed, start, each=bool(exclude))
        if memo is not None and memo.prepared is not None:
            prepared = memo.prepared
        elif memo is not None:
            prepared = memo.prepared = _candidates(
                rings, _Bound(1, 2 * keys.total, memo.floor), intervals, runs, keys,
                prebound=False, max_configs=memo.max_configs)
        else:
            prepared = _candidates(rings, bound, intervals, runs, keys, prebound=not exclude,
                                   guesses=guesses if attempt == 0 else None,
                                   lower=not start)
        if attempt == 0:
            guessing = bound.start > 0
        similar: dict[Any, tuple[_Job, list[np.ndarray]]] = {}
        deferred: dict[Any, tuple[_Job, list[np.ndarray]]] = {}
        found = _solve_jobs(rings, beta, prepared, intervals, bound, scale, keys, exclude,
                            memo, similar, deferred)
        if deferred:
            _solve_deferred(rings, beta, intervals, scale, found, bound.floor, deferred,
                            similar)
        found.sort(key=lambda f: (-f.t, *_tie_key(rings, f)))
        found = [f for f in _own_optimum(rings, found, similar) if not f.similar]
        if top is None or bound.floor == 0.0:
            break                           # nothing was pruned
        if len(found) >= top:
            kth = found[top - 1].t * (1 - TIE)
            if bound.floor <= kth:
                break
            fixed, start, guessing = kth, 0.0, False
        elif guessing and guesses:          # the next guess (then the bound's own)
            start = guesses.pop(0)
        elif guessing and halve < _HALVINGS:   # then half the last floor, fixed
            fixed, start, halve = bound.floor / 2, 0.0, halve + 1
        elif guessing:
            fixed, start, guessing = None, 0.0, False
        else:
            want, fixed = 4 * (want or 1), None
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
        compiled = stretch_kernels_for(ra.m * rb.m)
        cfg = _Configs(*(np.array([f.cfg[j] for f in items]) for j in range(4)))
        t1 = np.array([f.t for f in items])
        best_len = t1.copy()
        best_side = np.full(t1.size, -1)
        best_s0 = np.array([f.s0 for f in items])
        best_u0 = np.array([f.u0 for f in items])
        for side in (0, 1):
            ub = _ext(rb, cfg.iC, cfg.kC) if side == 0 else _ext(ra, cfg.iA, cfg.kA)
            rows = _system(ra, rb, cfg, sigma, beta, intervals[x, y, sigma],
                           intervals[y, x, sigma], fixed=(side, t1), compiled=compiled)
            t2, s0, u0 = _solve_any(rows, ub, scale, compiled)
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


def _own_optimum(rings: list[_Ring], found: list[_Found],
                 similar: dict[Any, tuple[_Job, list[np.ndarray]]] | None = None
                 ) -> list[_Found]:
    """The configurations that are optimal on their own edges: a configuration whose
    smallest region is beaten by one of its sub-configurations (fewer edges on either
    side, all of them found, since they rank higher) is not a plan of those edges.
    ``similar`` (:func:`_solve_jobs`): configurations found but filed by index, which
    take part as beaters; only ``found`` is returned."""
    keep = np.ones(len(found), bool)
    by_job: dict[Any, list[int]] = {}
    for j, f in enumerate(found):
        by_job.setdefault(f.job, []).append(j)
    for job, idx in by_job.items():
        ra, rb = rings[job[0]], rings[job[1]]
        c = np.array([found[j].cfg for j in idx], dtype=np.int64).reshape(-1, 4)
        t = np.array([found[j].t for j in idx], dtype=float)
        if similar is not None and job in similar:
            J, parts = similar[job]
            extra = np.concatenate(parts)
            c = np.concatenate([c, np.stack([J.cfg.iA[extra], J.cfg.kA[extra],
                                             J.cfg.iC[extra], J.cfg.kC[extra]], axis=1)])
            t = np.concatenate([t, J.t[extra]])
        if c[:, [1, 3]].max() == 0:
            continue
        n = len(idx)
        if len(c) >= KERNEL_OWN and jit_setting() is not False:
            keep[np.asarray(idx)] = _stretch_kernels.beaten(c, t, ra.m, rb.m, job[0] == job[1],
                                                            TIE)[:n]
            continue

        def inside(i: np.ndarray, k: np.ndarray, i2: np.ndarray, k2: np.ndarray,
                   m: int) -> np.ndarray:
            # [sub] stretch (rows) inside [super] stretch (columns), cyclically
            return cast("np.ndarray", (i[:, None] - i2[None, :]) % m + k[:, None] <= k2[None, :])

        at = np.asarray(idx)
        # supers (the found ones only) in blocks of columns: the (sub, super) matrix
        # stays about 1M cells; every configuration, filed ones too, a sub
        step = max(1, (_BLOCK * 32) // len(c))
        for b in range(0, n, step):
            cs, ts = c[b:min(b + step, n)], t[b:min(b + step, n)]
            sub = inside(c[:, 0], c[:, 1], cs[:, 0], cs[:, 1], ra.m) \
                & inside(c[:, 2], c[:, 3], cs[:, 2], cs[:, 3], rb.m)
            if job[0] == job[1]:        # one ring: a pair may be stored either way round
                sub |= inside(c[:, 0], c[:, 1], cs[:, 2], cs[:, 3], ra.m) \
                    & inside(c[:, 2], c[:, 3], cs[:, 0], cs[:, 1], ra.m)
            beaten = sub & (t[:, None] > ts[None, :] * (1 + TIE))
            keep[at[b:min(b + step, n)][beaten.any(axis=0)]] = False
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
        # the ranking's own order: leximin, then the geometric tie-break, which reads
        # only the regions' ends (their polylines are placed for the one kept)
        x, y, _, _ = f.job
        iA, kA, iC, kC = f.cfg
        ends = (_stretch_ends(rings[x], iA, kA, f.s0, f.lengths[0]),
                _stretch_ends(rings[y], iC, kC, f.u0, f.lengths[1]))
        return leximin_key(f.lengths, polygon.size), ends_key(ends, polygon)

    for j, g in zip(same, swapped, strict=True):
        if key(g) < key(found[j]):
            out[j] = g
    return out


def _tie_key(rings: list[_Ring], f: _Found) -> tuple[Any, ...]:
    """The order of exact ties: the job, then the covered edges (whatever order the
    search met them in)."""
    iA, kA, iC, kC = f.cfg
    return (f.job[:2], f.job[3], iA % rings[f.job[0]].m, kA, iC % rings[f.job[1]].m, kC)


def _finish(rings: list[_Ring], beta: float, found: list[_Found], intervals: dict[Any, _Intervals],
            polygon: Polygon) -> list[_Found]:
    """The second leximin level and the numbering-free placement of the configurations
    kept, in the leximin order."""
    _second_level(rings, beta, found, intervals, polygon.size)
    found = _canonical(rings, beta, found, intervals, polygon)
    found.sort(key=lambda f: (-min(f.lengths), -max(f.lengths), *_tie_key(rings, f)))
    return found


def _pairs(rings: list[_Ring], found: list[_Found]) -> list[StretchPair]:
    """Each configuration's regions, placed once for its placement (:func:`_canonical`
    asks for them, then the caller)."""
    out = []
    for f in found:
        at = (f.s0, f.u0, f.lengths)
        if f.placed is None or f.placed[0] != at:
            x, y, _, mode = f.job
            iA, kA, iC, kC = f.cfg
            p1, e1 = _polyline(rings[x], iA, kA, f.s0, f.lengths[0])
            p2, e2 = _polyline(rings[y], iC, kC, f.u0, f.lengths[1])
            f.placed = (at, StretchPair((p1, p2), (e1, e2), f.lengths, mode))
        out.append(f.placed[1])
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
        # a relative 1e-9 on the angle: a vertex at the limit is left to the exact search
        if np.any(_turns(ring) < 2 * beta * (1 + TOL) + ROUND_TOL):
            return True
    return False


def two_finger_stretches(polygon: Polygon, mu: Any, margin: Any = DEFAULT_MARGIN_DEG,
                         top: Any = 5, ties: bool = False, exclude: Any = (),
                         fraction: float = 0.5, seen: Any = ()) -> list[StretchPair]:
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
    exclude : sequence of plans
        Plans already kept (objects with ``regions`` and ``region_edges``, two
        regions each): the pairs returned are the best of those that are not surely
        the same alternative as one of them (their regions, wherever placed in their
        stretches, overlapping by more than ``fraction`` of the shorter,
        :func:`fcgrasp.model.distinct.same_alternative`); used by ``distinct=``.
    fraction : float
        The overlap of ``exclude``.
    seen : sequence of plans
        Plans already read (objects with ``region_edges`` and ``mode``): their
        configurations are not returned again.

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
    return StretchSearch(polygon, mu, margin).pairs(top, ties, exclude, fraction, seen)


class StretchSearch:
    """:func:`two_finger_stretches` of one part, ``mu`` and ``margin``, asked several
    times (the rounds of ``distinct=``, :func:`fcgrasp.grippers._boundary.distinct_boundary_plans`):
    the rings' vertex matrices once, and for the runs that exclude plans every
    configuration collected once and each solved once.

    >>> sq = Polygon([[0, 0], [10, 0], [10, 3], [0, 3]])
    >>> [p.region_edges for p in StretchSearch(sq, 0.3).pairs(top=1)]
    [((1,), (3,))]
    """

    def __init__(self, polygon: Polygon, mu: Any, margin: Any = DEFAULT_MARGIN_DEG,
                 max_bytes: int | None = None) -> None:
        self.beta = _check_args(polygon, mu, margin)
        self.max_bytes = None if max_bytes is None else check_int(max_bytes, "max_bytes",
                                                                  minimum=1)
        self.polygon = check_polygon(polygon)
        self.rings = rings = _rings(self.polygon)
        if self.beta <= 0:
            return
        # every ordered ring pair is a job, so a job's reverse intervals are another's
        self.intervals = {(x, y, sigma): _Intervals(rings[x], rings[y], sigma, self.beta)
                          for x, y, sigma, _ in _jobs(len(rings))}
        self.runs = {(x, y): _vertex_runs(rings[x], rings[y], self.beta)
                     for x in range(len(rings)) for y in range(x, len(rings))}
        self._memo = _Memo(max_bytes=self.max_bytes)
        #: the address space when the first distinct round began: every round's memory
        #: budget counts from it (:func:`_address_space`)
        self._held: int | None = None
        #: the best smallest region (the first run without exclusion), from which the
        #: memo's floor starts (:data:`MEMO_SHARE`)
        self._best: float | None = None

    def pairs(self, top: Any = 5, ties: bool = False, exclude: Any = (),
              fraction: float = 0.5, seen: Any = (), third: bool = False
              ) -> list[StretchPair]:
        """:func:`two_finger_stretches`'s answer (the same arguments).

        With ``third``, each configuration stands for the three-finger plan of its two
        regions and a third finger anywhere on the longest free stretch (mode
        ``"pair"`` of :mod:`fcgrasp.grippers.three_fingers`), and ``exclude`` holds
        three-finger plans (three regions each): a configuration is left out when that
        plan is surely the same alternative as one of them (two of its regions as
        above, and its free stretch overlapping the third by more than ``fraction`` of
        the shorter).  ``seen`` still holds two-finger plans."""
        top_v = None if top is None else check_int(top, "top", minimum=1)
        if not isinstance(ties, bool):
            raise TypeError(f"ties must be a bool, got {ties!r}")
        fraction_v = check_scalar(fraction, "fraction", nonnegative=True)
        if fraction_v > 1:
            raise ValueError(f"fraction must be in [0, 1], got {fraction!r}")
        if self.beta <= 0:
            return []
        rings, polygon = self.rings, self.polygon
        _load_for_depth(top_v)
        kept = [(p.regions, p.region_edges) for p in exclude
                if len(p.regions) == (3 if third else 2)]
        read = [(p.region_edges, p.mode) for p in seen if len(p.region_edges) == 2]
        # (nothing to exclude: no map of the edges, 36 ms on 10,000 edges)
        excl = _Exclusion(rings, polygon, kept, fraction_v, read, third) \
            if kept or read else None
        memo = self._memo
        if excl and memo.prepared is None and self._best is not None and memo.floor == 0.0:
            memo.lower(MEMO_SHARE * self._best)
        # the highest floor whose collection did not fit the memory budget: a run that
        # needs to collect down to it or below cannot be made
        overflow = -np.inf
        while True:
            if excl:
                budget.check()
            began = time.monotonic()
            try:
                # a round of the distinct search under the memory budget (its collection
                # of a smooth outline can ask for gigabytes at once)
                if excl and self._held is None:
                    self._held = _address_held()
                with _address_space(memo.max_bytes if excl else None, self._held):
                    found = _search(rings, self.beta, self.intervals, self.runs, top_v,
                                    polygon.size, excl or None, memo)
            except budget.BudgetExhausted as exc:
                best = self._best
                if str(exc) != "max_memory" or not excl or best is None \
                        or memo.floor <= 0.0:
                    raise
                # the collection down to this floor does not fit: collect from higher
                # up (half way to the best plan), which the floor's rule keeps exact
                # (a run whose answer needs more lowers it again, if that fits)
                overflow = max(overflow, memo.floor)
                higher = memo.floor + (best - memo.floor) / 2
                # (not when the time left would not see another such attempt through)
                if higher >= best * (1 - MEMO_SHARE) or \
                        budget.remaining() < time.monotonic() - began:
                    raise
                memo.lower(higher)
                continue
            if not excl or memo.floor == 0.0:
                break
            # the top-th found at or above the memo's floor: nothing missed; below it,
            # collect down to it; fewer than top found: down to a quarter
            if top_v is not None and len(found) >= top_v:
                need = found[top_v - 1].t * (1 - TIE)
                if need >= memo.floor:
                    break
                low = need * (1 - TIE)
            else:
                low = memo.floor / 4
            if low <= overflow:         # what the answer needs does not fit the budget
                raise budget.BudgetExhausted("max_memory")
            # below a thousandth of the best plan: every configuration
            memo.lower(low if low > 1e-3 * (self._best or 0.0) else 0.0)
        if not excl and found:
            self._best = found[0].t if self._best is None else max(self._best, found[0].t)
        if not found:
            return []
        if top_v is not None:
            kth = found[min(top_v, len(found)) - 1].t
            found = [f for f in found if f.t >= kth * (1 - TIE)] if ties else found[:top_v]
        found = _finish(rings, self.beta, found, self.intervals, polygon)
        return _pairs(rings, found if ties or top_v is None else found[:top_v])


#: The distinct search's memo (:class:`_Memo`) first collects the configurations whose arc
#: length reaches this share of the best smallest region (lowered when a run's
#: ``top``-th falls below it): a smooth outline of 2,000 edges has tens of millions of
#: configurations, most far below any plan kept.
MEMO_SHARE = 0.15


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
    where = _positions(rings)
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
    keys = _Keys(rings)
    found = _solve_jobs(rings, beta, prepared, intervals, _Bound(1, 2 * keys.total),
                        polygon.size, keys)
    if not found:
        return None
    best = max(f.t for f in found)
    found = _finish(rings, beta, [f for f in found if f.t >= best * (1 - TIE)], intervals,
                    polygon)
    return _pairs(rings, found[:1])[0]
