"""The two-finger stretch search's windows: for each edge, the interval of opposite
vertices whose cones still meet, and the configurations (which edges each region
covers) bounded and pruned (part of :mod:`fcgrasp.model.stretches`)."""

from __future__ import annotations

import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from functools import cached_property
from typing import Any, cast

import numpy as np

from ...core._checks import FloatArray
from ...core._geom import cross2 as _cross
from ...core.contacts import rotate
from ...core.jit import jit_setting, started
from ...core.tolerances import RANK_TOL, ROUND_TOL
from ..polygon import Polygon
from . import _kernels

#: A coefficient of the linear system smaller than this (a cross product of unit
#: vectors) is zero.
_EPS = ROUND_TOL

#: Relative tolerance within which two smallest regions tie (the ranking's).
TIE = RANK_TOL


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

    @cached_property
    def floats(self) -> tuple[list[list[float]], list[list[float]], list[float], list[float]]:
        """``a``, ``t``, ``L`` and ``U`` as Python lists, for the plain-float code that
        reads a point or two per call."""
        return self.a.tolist(), self.t.tolist(), self.L.tolist(), self.U.tolist()


def _rings(polygon: Polygon) -> list[_Ring]:
    out = []
    for r in range(int(polygon.rings.max()) + 1):      # rings are numbered from 0
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


def _turns(ring: _Ring) -> FloatArray:
    """The angle between the two force directions at every vertex (the fan's width)."""
    before, after = _fan(ring)
    return cast("FloatArray", np.arctan2(np.abs(_cross(before, after)),
                                         np.sum(before * after, axis=1)))


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


#: The largest table of cells (edges x vertices) :meth:`_Intervals.window` keeps, per
#: ring pair and sign (16 bytes a cell: 67 MB; a ring of about 2,000 edges: a distinct
#: search on a smooth outline reads each cell many times).
MEMO_CELLS = 4_200_000


class _Intervals:
    """``[lo, hi][e, w]``: positions on edge ``e`` (ring a, arc length from its start)
    where a contact holds against vertex ``w`` of ring b with both its fan normals
    (empty where ``lo > hi``).  Computed for the cells asked for: the searches read
    whole rows only for edges long enough to matter, and windows of a few cells."""

    def __init__(self, ra: _Ring, rb: _Ring, sigma: float, beta: float) -> None:
        self.ra, self.rb, self.sigma, self.beta = ra, rb, sigma, beta
        self.gx = np.stack(_gens_x(ra.f, beta), axis=1)                      # (ma, 2, 2)
        self.gy = np.stack([g for f in _fan(rb) for g in _gens_y(f, beta)], axis=1)
        # the compiled windows' inputs, and their cells as computed (NaN: not yet), kept
        # while the table stays small (a distinct search reads the same cells in every
        # round, for the thousands of configurations whose windows share them)
        self._flat = (ra.a[:, 0].copy(), ra.a[:, 1].copy(), ra.t[:, 0].copy(),
                      ra.t[:, 1].copy(), ra.L, self.gx, rb.a[:, 0].copy(), rb.a[:, 1].copy(),
                      self.gy)
        self._memo: tuple[FloatArray, FloatArray] | None = None
        self._asked = 0                     # cells the compiled windows were asked for

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

    def window(self, edge: np.ndarray, start: np.ndarray, count: np.ndarray,
               compiled: bool = False) -> tuple[FloatArray, FloatArray]:
        """For each edge, the intersection of its intervals against vertices
        ``start .. start + count - 1`` (cyclic): ``(0, inf)`` when ``count`` is 0
        (``compiled``: by :func:`fcgrasp.model.stretches._kernels.window_boxes_shared`,
        which reads the cells an edge's windows share once, or the ``_memo`` form of
        ``window_boxes`` reading the cells from a table up to :data:`MEMO_CELLS`, once
        the windows have asked for an eighth of them)."""
        if compiled:
            args = (np.asarray(edge, np.int64), np.asarray(start, np.int64),
                    np.asarray(count, np.int64), *self._flat, self.sigma, _EPS)
            cells = self.ra.m * self.rb.m
            self._asked += int(np.sum(args[2]))
            # the table once the windows have read an eighth of its cells: filling it
            # costs about that (a noisy star's search reads under 1 %, a smooth curve's
            # more than half, a distinct search's each cell many times)
            if cells > MEMO_CELLS or (self._memo is None and 8 * self._asked < cells):
                return cast("tuple[FloatArray, FloatArray]",
                            _kernels.window_boxes_shared(*args))
            if self._memo is None:
                shape = (self.ra.m, self.rb.m)
                self._memo = (np.full(shape, np.nan), np.full(shape, np.nan))
            return cast("tuple[FloatArray, FloatArray]",
                        _kernels.window_boxes_memo(*args, *self._memo))
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
    return cast("FloatArray", ring.U[i + k + 1] - ring.U[i])


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
    return cast("np.ndarray", (rel > c.kA) & (rel + c.kC < m))


class _Bound:
    """The ``k``-th largest smallest region among feasible configurations seen so far,
    **at most one per key** (0 until ``k`` keys are seen): no configuration below it can
    reach the top ``k``.  ``floor`` is that value less the relative tie tolerance, so
    ties are kept.

    A key is a mode and a boundary edge: the start edge of the stretch that comes first
    (ring, then position in the ring) of a feasible configuration, so that two values
    under different keys are two different configurations.  A configuration reached
    twice (a lower bound from its vertex-aligned stretches, then its optimum; or the
    same pair from either stretch) only raises its own key, never counts twice.

    With ``fixed``, the floor is that number and never rises (a search that must solve
    every configuration reaching it); with ``start``, the floor is at least that number
    (a guess, checked by the search) and rises with the value above it.

    With ``each``, every value added is a configuration of its own (a search without
    lower bounds, which adds each configuration once): the ``k``-th largest value,
    keys ignored.  A key holds many configurations of a curved outline, and one whose
    plans leave most keys out (the rounds of a distinct search) would otherwise keep
    its floor at 0 and solve every configuration."""

    def __init__(self, k: int, keys: int, fixed: float | None = None,
                 start: float = 0.0, each: bool = False) -> None:
        self.k = k
        self.each = each
        self.best = np.zeros(0 if each else keys)
        self._value = 0.0
        self.fixed = fixed
        self.start = start

    def add(self, keys: Any, values: Any) -> None:
        if self.fixed is not None:
            return
        v = np.asarray(values, float).ravel()
        sel = v > self._value
        if not sel.any():
            return
        if self.each:                   # the k largest values so far
            best = np.concatenate([self.best, v[sel]])
            if best.size > self.k:
                best = np.partition(best, best.size - self.k)[best.size - self.k:]
            self.best = best
        else:
            np.maximum.at(self.best, np.asarray(keys).ravel()[sel], v[sel])
        n = self.best.size
        if n >= self.k:
            self._value = float(np.partition(self.best, n - self.k)[n - self.k])

    @property
    def value(self) -> float:
        return self._value

    @property
    def floor(self) -> float:
        if self.fixed is not None:
            return self.fixed
        return max(self.start, self.value * (1 - TIE))


def _windows_both(runs: tuple[np.ndarray, np.ndarray, np.ndarray], ra: _Ring, rb: _Ring,
                  same: bool, floor: float, collect: bool) -> tuple[FloatArray, _Configs]:
    """Configurations with interior vertices on both stretches: stretch 1's interior
    window i .. i+k-1 leaves for stretch 2 the runs of the AND of those rows of ``M``
    (``runs``: the runs of its rows as row pointers, first and last columns).

    Returns, for each first row ``i`` (stretch 1 from vertex ``i``), the largest
    smallest region of the vertex-aligned stretches of its runs (feasible: all their
    cells have their four corners in ``M``; a lower bound, on one ring only from pairs
    whose stretch 2 starts after ``i``), and, with ``collect``, the configurations whose
    bound reaches ``floor``."""
    best = np.zeros(ra.m)
    parts: list[_Configs] = []
    ptr, first, last = runs
    Mi = (np.repeat(np.arange(ra.m), np.diff(ptr)), first, last)
    C = Mi
    k = 1
    while k < ra.m - 1:
        live = C[0][_group_starts(C[0])]
        if live.size == 0:
            break
        ks = np.full(live.size, k)
        ext_s = _ext(ra, live - 1, ks)
        live = live[ext_s >= floor]
        # the lower bound only has to be feasible, not the largest: without collecting,
        # runs are read at about eight window lengths per doubling
        if live.size and (collect or k <= 8 or k % (k // 8) == 0):
            row, p0, r = _cyclic_runs(C, live, rb.m)
            kr = np.full(row.size, k)
            inner_s, ext_s = _inner(ra, row - 1, kr), _ext(ra, row - 1, kr)
            rr = np.minimum(r, rb.m - 2)
            vert_u = np.where(rr > 0, _inner(rb, p0 - 1, rr), 0.0)
            mine = (rr > 0) & ((p0 % rb.m > row) if same else True)
            np.maximum.at(best, row[mine], np.minimum(inner_s, vert_u)[mine])
            keep = (ext_s >= floor) & (rr >= 1)
            if collect and keep.any():
                parts.append(_sub_windows(rb, row[keep], p0[keep], rr[keep], k,
                                          inner_s[keep], ext_s[keep], floor))
        C = _intersect_rows(C, Mi, ptr, k)
        k += 1
    if not parts:
        return best, _empty()
    cfg = _Configs.cat(parts)
    return best, _both_kept(cfg, ra, rb, same)


def _both_kept(cfg: _Configs, ra: _Ring, rb: _Ring, same: bool) -> _Configs:
    """The configurations of two windows whose stretches are disjoint, each unordered
    pair of one ring once."""
    keep = _disjoint(ra, cfg, same)
    if same:
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


def _windows_single(iv: _Intervals, ra: _Ring, rb: _Ring, same: bool, floor: float,
                    collect: bool) -> tuple[tuple[np.ndarray, np.ndarray, FloatArray], _Configs]:
    """Stretch 1 on one edge A, stretch 2 with interior vertices p .. p+k-1: those
    vertices confine stretch 1 to the intersection of their intervals on A.

    Returns the lower bounds ``(A, p, value)``: the vertex-aligned stretch 2 with that
    whole intersection is feasible (on one ring only where stretch 2 starts after A,
    apart from it), the largest over ``k``; and, with ``collect``, the configurations
    whose bound reaches ``floor``."""
    A = np.flatnonzero(ra.L >= floor)
    parts: list[_Configs] = []
    none = (np.zeros(0, int), np.zeros(0, int), np.zeros(0))
    if A.size == 0:
        return none, _empty()
    mb = rb.m
    loA, hiA = iv.rows(A)
    cl, ch = loA.copy(), hiA.copy()
    pidx = np.arange(mb)
    best = np.zeros((A.size, mb))
    # on one ring: stretch 2 (vertices p .. p + k - 1) after A and clear of both its ends
    after = (pidx[None, :] >= A[:, None] + 2) if same else np.ones((A.size, mb), bool)
    k = 1
    while k < mb - 1:
        room = ch - cl
        ok = room >= floor
        if not ok.any():
            break
        ks = np.full(mb, k)
        inner_u = _inner(rb, pidx - 1, ks)[None, :]
        ext_u = _ext(rb, pidx - 1, ks)[None, :]
        mine = ok & after & ((pidx[None, :] + k - 1 < mb + A[:, None]) if same else True)
        np.maximum(best, np.where(mine, np.minimum(room, inner_u), 0.0), out=best)
        if collect:
            a_i, p_i = np.nonzero(ok & (ext_u >= floor) & (room >= inner_u))
            if a_i.size:
                parts.append(_Configs(A[a_i], np.zeros(a_i.size, int), p_i - 1,
                                      np.full(a_i.size, k)))
        nxt = (pidx + k) % mb
        cl = np.maximum(cl, loA[:, nxt])
        ch = np.minimum(ch, hiA[:, nxt])
        k += 1
    a_i, p_i = np.nonzero(best > 0)
    found = (A[a_i], p_i, best[a_i, p_i])
    if not parts:
        return found, _empty()
    cfg = _Configs.cat(parts)
    return found, cfg.take(_disjoint(ra, cfg, same))


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


#: Vertex pairs (``m_a * m_b``) from which the search runs the compiled loops of
#: :mod:`fcgrasp.model.stretches._kernels`: numba's start-up (about 0.4 s of CPU once per
#: process, to import it and load the cached code) is then less than what they save.
#: Once loaded, they run for every part; ``FCGRASP_JIT=0`` never runs them,
#: ``FCGRASP_JIT=1`` always.
KERNEL_CELLS = 1_500_000


#: CPU seconds of batched numpy solves (:func:`~fcgrasp.model.stretches._lp._solve`) after
#: which a process solves the rest compiled: on an outline of a few hundred edges whose
#: stretches hold many vertices (an icon's rounded corners) each chunk of configurations
#: costs tens of milliseconds of Fourier-Motzkin, and numba's start-up is soon repaid.
#: The two solve the same (``tests/test_stretch_kernels.py``).
NUMPY_SOLVE_BUDGET = 0.4


_numpy_spent = [0.0]


@contextmanager
def numpy_counted() -> Iterator[None]:
    """Counts the CPU time of the block toward :data:`NUMPY_SOLVE_BUDGET` (numpy work
    that the compiled loops would do: the exclusion's tests of a small outline, read
    round after round, as much as its solves)."""
    start = time.process_time()
    try:
        yield
    finally:
        _numpy_spent[0] += time.process_time() - start


#: Configurations of one job to solve from which the compiled solve runs, whatever the
#: size of the rings (a noisy outline can leave tens of thousands).
KERNEL_CONFIGS = 20_000


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
            and not _kernels.loaded():
        _kernels.available()


def stretch_kernels_for(cells: int) -> bool:
    """Whether the stretch search of rings of ``cells`` vertex pairs runs compiled (and
    so holds no array of every pair: the memory estimate of
    :func:`fcgrasp.pipeline.check_search` asks too): once numba started in this
    process for any of the package's loops, these included
    (:func:`fcgrasp.core.jit.started`), from :data:`KERNEL_CELLS`, or once this
    process spent :data:`NUMPY_SOLVE_BUDGET` in numpy solves."""
    setting = jit_setting()
    if setting is not None:
        return setting
    return started() or cells >= KERNEL_CELLS or \
        _numpy_spent[0] > NUMPY_SOLVE_BUDGET
