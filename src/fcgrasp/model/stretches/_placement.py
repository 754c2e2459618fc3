"""The two-finger stretch search's answer (part of :mod:`fcgrasp.model.stretches`): the
pairs of regions (:class:`StretchPair`), each configuration's second leximin level (the
other region as long as the covered edges allow), the canonical placement of ties and
the regions' polylines along the rings."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...core._checks import FloatArray
from ...core._geom import ends_key, leximin_key, midpoints, trim_vertex_ends
from ...core.tolerances import ROUND_TOL
from ..polygon import Polygon
from ._lp import _system
from ._solve import _Found, _solve_any
from ._windows import TIE, _Configs, _ext, _Intervals, _Ring, stretch_kernels_for


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
    #: with ``third`` (:meth:`~fcgrasp.model.stretches.StretchSearch.pairs`): a bound on
    #: its three-finger pair plan's smallest region, the value the search ranked it by
    bound: float | None = None

    @property
    def min_length(self) -> float:
        return min(self.lengths)

    def midpoints(self) -> tuple[FloatArray, tuple[int, int]]:
        """Each region's point halfway along it (the representative contact) and the
        edge holding it."""
        pts, edges = midpoints(self.regions, self.region_edges)
        return pts, (edges[0], edges[1])


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


def _tie_keys(rings: list[_Ring]) -> Callable[[_Found], tuple[Any, ...]]:
    """The order of exact ties among configurations of ``rings``: the job, then the
    covered edges (whatever order the search met them in); the rings' lengths read once
    (the rounds sort millions)."""
    m = [r.m for r in rings]

    def key(f: _Found) -> tuple[Any, ...]:
        iA, kA, iC, kC = f.cfg
        job = f.job
        return (job[:2], job[3], iA % m[job[0]], kA, iC % m[job[1]], kC)

    return key


def _finish(rings: list[_Ring], beta: float, found: list[_Found], intervals: dict[Any, _Intervals],
            polygon: Polygon) -> list[_Found]:
    """The second leximin level and the numbering-free placement of the configurations
    kept, in the leximin order."""
    _second_level(rings, beta, found, intervals, polygon.size)
    found = _canonical(rings, beta, found, intervals, polygon)
    tie = _tie_keys(rings)
    found.sort(key=lambda f: (-min(f.lengths), -max(f.lengths), *tie(f)))
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
