"""The parallel jaw's pose model compiled: :func:`poses` evaluates a batch of
poses in one loop, pose by pose and edge by edge, with the same formulas, in the same
order, as the numpy model of :mod:`._poses` (``_pad``, ``_sides_of``, ``_inside``,
``_verdict``), which stays the reference (``FCGRASP_JIT=0``, and the tests: verdicts
equal wherever a slack is not within rounding of zero, values to 1e-12 of the size).

numpy spends its time on calls over arrays of a few elements (a pose batch of a grid
tile, a cell's three points, a box's centre); the loop pays none of them and allocates
only its outputs.  Compiled by numba on first use, cached on disk beside this file
(:func:`fcgrasp.compile_kernels` does it ahead of time); without numba, or with
``FCGRASP_JIT=0``, :func:`available` is False and the numpy model runs.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ...core.kernels import CompiledLoops
from ...core.tolerances import ROUND_TOL

#: At most this many contact features per pad (as ``_poses.MAX_CONTACTS``).
K_MAX = 4


def _pad_loop(p: int, th_c: float, th_s: float, c: float, a: Any, b: Any, f: Any,
              half: float, tol: float, sign: float, fsign: float, use: int,
              stop_out: Any, ok_out: Any, lat: Any, psi: Any, col: Any, hs: Any,
              r: int) -> None:
    """One pad at pose ``p`` (``_poses._pad``): the stop (``sign`` times the extreme of
    ``sign * y``), whether it is valid, and its first :data:`K_MAX` touching edges'
    lateral spans, force angles and columns.  ``use``: the row of ``hs`` that marks the
    edges it may meet (> 0), -1 for all; ``fsign``: the sign of the force's ``u``
    component in ``arctan2``; rows ``r`` and ``r + 1`` of ``hs``: scratch (E,) (rows
    of one array, not views: a compiled function that makes no view and allocates
    nothing runs without reference counts, :func:`~fcgrasp.core.kernels.njit_all`)."""
    s0, s1 = c - half, c + half
    E = a.shape[0]
    stop = -np.inf
    for e in range(E):
        xa = -th_s * a[e, 0] + th_c * a[e, 1]
        xb = -th_s * b[e, 0] + th_c * b[e, 1]
        lo_x, hi_x = min(xa, xb), max(xa, xb)
        inside = hi_x >= s0 and lo_x <= s1 and (use < 0 or hs[use, e] > 0)
        if not inside:
            hs[r, e] = -np.inf
            hs[r + 1, e] = -np.inf
            continue
        ya = sign * (th_c * a[e, 0] + th_s * a[e, 1])
        yb = sign * (th_c * b[e, 0] + th_s * b[e, 1])
        cl_lo = min(max(lo_x, s0), s1)
        cl_hi = min(max(hi_x, s0), s1)
        dx = xb - xa
        if abs(dx) <= tol:
            hs[r, e] = max(ya, yb)
            hs[r + 1, e] = max(ya, yb)
        else:
            slope = (yb - ya) / dx
            hs[r, e] = ya + (cl_lo - xa) * slope
            hs[r + 1, e] = ya + (cl_hi - xa) * slope
        stop = max(stop, hs[r, e], hs[r + 1, e])
    _features(p, th_c, th_s, c, a, b, f, half, tol, sign, fsign, stop, hs, r, stop_out,
              ok_out, lat, psi, col)


def _features(p: int, th_c: float, th_s: float, c: float, a: Any, b: Any, f: Any,
              half: float, tol: float, sign: float, fsign: float, stop: float, hs: Any,
              r: int, stop_out: Any, ok_out: Any, lat: Any, psi: Any, col: Any) -> None:
    """The end of :func:`_pad_loop`: the pad's stop ``stop`` (the highest of the edges'
    heights at the ends of their parts in the strip, rows ``r`` and ``r + 1`` of ``hs``,
    -inf for an edge out of it) and its first :data:`K_MAX` touching edges (within
    ``tol`` of it), in order: their lateral spans, force angles and columns."""
    s0, s1 = c - half, c + half
    E = a.shape[0]
    count = 0
    finite = stop > -np.inf
    for e in range(E):
        at_lo = hs[r, e] >= stop - tol
        at_hi = hs[r + 1, e] >= stop - tol
        if not (finite and (at_lo or at_hi)):
            continue
        if count < K_MAX:
            k = count
            xa = -th_s * a[e, 0] + th_c * a[e, 1]
            xb = -th_s * b[e, 0] + th_c * b[e, 1]
            ya = sign * (th_c * a[e, 0] + th_s * a[e, 1])
            yb = sign * (th_c * b[e, 0] + th_s * b[e, 1])
            lo_x, hi_x = min(xa, xb), max(xa, xb)
            g_lo = min(max(lo_x, s0), s1)
            g_hi = min(max(hi_x, s0), s1)
            level = abs(ya - yb) <= tol
            along = abs(xb - xa) <= tol
            cut_lo = g_lo > lo_x + tol and not level and not along
            cut_hi = g_hi < hi_x - tol and not level and not along
            corner = (at_lo and cut_lo) or (at_hi and cut_hi)
            if level and at_lo and at_hi:
                lat[p, k, 0], lat[p, k, 1] = g_lo, g_hi
            else:
                lat[p, k, 0] = g_lo if at_lo else g_hi
                lat[p, k, 1] = g_hi if at_hi else g_lo
            if corner:
                fx = -th_s * f[e, 0] + th_c * f[e, 1]
                fy = th_c * f[e, 0] + th_s * f[e, 1]
                psi[p, k] = math.atan2(fx, fsign * fy)
            else:
                psi[p, k] = 0.0
            col[p, k] = e
        count += 1
    for k in range(min(count, K_MAX), K_MAX):
        lat[p, k, 0], lat[p, k, 1], psi[p, k], col[p, k] = np.nan, np.nan, np.nan, -1
    stop_out[p] = sign * stop
    ok_out[p] = finite and count <= K_MAX


def _outer_pads(p: int, th_c: float, th_s: float, c: float, a: Any, b: Any, f: Any,
                half: float, tol: float, top: Any, ok_a: Any, lat_a: Any, psi_a: Any,
                col_a: Any, bottom: Any, ok_b: Any, lat_b: Any, psi_b: Any, col_b: Any,
                scratch: Any) -> None:
    """Both pads of an external grip at pose ``p``: :func:`_pad_loop` for the upper pad
    (``sign`` 1) and the lower (-1), the edges' positions computed once for both, the
    same numbers (each pad's heights by its own formula).  ``scratch`` (4, E)."""
    s0, s1 = c - half, c + half
    E = a.shape[0]
    stop_a, stop_b = -np.inf, -np.inf
    for e in range(E):
        xa = -th_s * a[e, 0] + th_c * a[e, 1]
        xb = -th_s * b[e, 0] + th_c * b[e, 1]
        lo_x, hi_x = min(xa, xb), max(xa, xb)
        if not (hi_x >= s0 and lo_x <= s1):
            for r in range(4):
                scratch[r, e] = -np.inf
            continue
        ya = th_c * a[e, 0] + th_s * a[e, 1]
        yb = th_c * b[e, 0] + th_s * b[e, 1]
        na, nb = -1.0 * ya, -1.0 * yb
        dx = xb - xa
        if abs(dx) <= tol:
            scratch[0, e] = scratch[1, e] = max(ya, yb)
            scratch[2, e] = scratch[3, e] = max(na, nb)
        else:
            cl_lo = min(max(lo_x, s0), s1)
            cl_hi = min(max(hi_x, s0), s1)
            slope = (yb - ya) / dx
            scratch[0, e] = ya + (cl_lo - xa) * slope
            scratch[1, e] = ya + (cl_hi - xa) * slope
            slope = (nb - na) / dx
            scratch[2, e] = na + (cl_lo - xa) * slope
            scratch[3, e] = na + (cl_hi - xa) * slope
        stop_a = max(stop_a, scratch[0, e], scratch[1, e])
        stop_b = max(stop_b, scratch[2, e], scratch[3, e])
    _features(p, th_c, th_s, c, a, b, f, half, tol, 1.0, -1.0, stop_a, scratch, 0, top,
              ok_a, lat_a, psi_a, col_a)
    _features(p, th_c, th_s, c, a, b, f, half, tol, -1.0, 1.0, stop_b, scratch, 2, bottom,
              ok_b, lat_b, psi_b, col_b)


def _hole_sides(th_c: float, th_s: float, c: float, a: Any, b: Any, half: float,
                tol: float, level: float, sides: Any) -> bool:
    """``_poses._sides_of`` at one pose: which edges meet the strip wholly above the
    height ``level``, which wholly below (into rows 2 and 3 of ``sides``), and whether
    the strip's segment at that height is free (every edge meeting it one or the
    other)."""
    s0, s1 = c - half, c + half
    free = True
    for e in range(a.shape[0]):
        xa = -th_s * a[e, 0] + th_c * a[e, 1]
        xb = -th_s * b[e, 0] + th_c * b[e, 1]
        ya = th_c * a[e, 0] + th_s * a[e, 1]
        yb = th_c * b[e, 0] + th_s * b[e, 1]
        lo_x, hi_x = min(xa, xb), max(xa, xb)
        meets = hi_x >= s0 and lo_x <= s1
        if abs(xb - xa) <= tol:
            h0, h1 = ya, yb
        else:
            slope = (yb - ya) / (xb - xa)
            h0 = ya + (min(max(lo_x, s0), s1) - xa) * slope
            h1 = ya + (min(max(hi_x, s0), s1) - xa) * slope
        up = meets and min(h0, h1) > level + tol
        down = meets and max(h0, h1) < level - tol
        sides[2, e] = 1.0 if up else 0.0
        sides[3, e] = 1.0 if down else 0.0
        if meets and not up and not down:
            free = False
    return free


def _inside_ring(th_c: float, th_s: float, a: Any, b: Any, x: float, y: float) -> bool:
    """``_poses._inside`` at one pose: is ``(x, y)`` inside the ring (even-odd, the ray
    along ``+u``)?"""
    crossings = 0
    for e in range(a.shape[0]):
        xa = -th_s * a[e, 0] + th_c * a[e, 1]
        xb = -th_s * b[e, 0] + th_c * b[e, 1]
        if (xa > x) != (xb > x):
            ya = th_c * a[e, 0] + th_s * a[e, 1]
            yb = th_c * b[e, 0] + th_s * b[e, 1]
            if ya + (x - xa) * (yb - ya) / (xb - xa) > y:
                crossings += 1
    return crossings % 2 == 1


def _poses_loop(th: Any, c: Any, a: Any, b: Any, f: Any, half: float, tol: float,
                internal: bool, q: Any, stroke0: float, stroke1: float, beta: float,
                flip: float, round_tol: float, top: Any, bottom: Any, ok_a: Any,
                ok_b: Any, lat_a: Any, lat_b: Any, psi_a: Any, psi_b: Any, col_a: Any,
                col_b: Any, holds: Any, slacks: Any) -> None:
    """Every pose of the batch: both pads, the verdict and its slacks
    (``_poses._evaluate``)."""
    E = a.shape[0]
    scratch = np.empty((4, E))
    for p in range(th.shape[0]):
        _pose_one(p, th[p], c[p], a, b, f, half, tol, internal, q, stroke0, stroke1, beta,
                  flip, round_tol, top, bottom, ok_a, ok_b, lat_a, lat_b, psi_a, psi_b,
                  col_a, col_b, holds, slacks, scratch)


def _grid_loop(th: Any, c: Any, a: Any, b: Any, f: Any, half: float, tol: float,
               internal: bool, q: Any, stroke0: float, stroke1: float, beta: float,
               flip: float, round_tol: float, H: Any, details: bool, opening: Any,
               edge_a: Any, edge_b: Any) -> None:
    """Whether each pose of the grid ``th x c`` holds (``H``, (K, M)); with
    ``details``, its opening (``opening``, (K, M)) and the edges (indices of ``a``)
    each pad touches (``edge_a``, ``edge_b``, (K, M, K_MAX), -1 for none), as
    :func:`_poses_loop` decides it, but each pose reads only the edges that may meet its
    strip: per closing angle, every edge's span across the closing direction is
    computed once and filed under the columns (offsets, ``c`` evenly spaced and
    increasing) whose strips it may meet, one column to each side spare.  The edges a
    pose does not read never meet its strip, and :func:`_pose_one` passes over them
    (no stop, no feature, neither above nor below the closed jaws, no crossing of the
    ray from their middle), so the verdicts are those of every edge, in the same
    order."""
    K, M, E = th.shape[0], c.shape[0], a.shape[0]
    KK = K_MAX
    top, bottom = np.empty(1), np.empty(1)
    ok_a, ok_b = np.zeros(1, np.bool_), np.zeros(1, np.bool_)
    lat_a, lat_b = np.empty((1, KK, 2)), np.empty((1, KK, 2))
    psi_a, psi_b = np.empty((1, KK)), np.empty((1, KK))
    col_a, col_b = np.empty((1, KK), np.int64), np.empty((1, KK), np.int64)
    holds = np.zeros(1, np.bool_)
    slacks = np.empty((1, 2 * KK * KK + 2))
    scratch = np.empty((4, E))
    j_lo = np.empty(E, np.int64)
    j_hi = np.empty(E, np.int64)
    count = np.zeros(M + 1, np.int64)
    fill = np.empty(M, np.int64)
    sa, sb, sf = np.empty((E, 2)), np.empty((E, 2)), np.empty((E, 2))
    dc = (c[M - 1] - c[0]) / (M - 1) if M > 1 else 0.0
    spread = dc > 0 and math.isfinite(dc)      # else every edge is read at every pose
    for k in range(K):
        tc, ts = math.cos(th[k]), math.sin(th[k])
        for j in range(M + 1):
            count[j] = 0
        for e in range(E):
            xa = -ts * a[e, 0] + tc * a[e, 1]
            xb = -ts * b[e, 0] + tc * b[e, 1]
            lo_x, hi_x = min(xa, xb), max(xa, xb)
            # columns whose strip [c - half, c + half] may meet [lo_x, hi_x]
            lo, hi = 0, M - 1
            if spread:
                u = (lo_x - half - c[0]) / dc
                v = (hi_x + half - c[0]) / dc
                if u > M:
                    lo = M
                elif u > 0:
                    lo = max(int(math.floor(u)) - 1, 0)
                if v < -1:
                    hi = -1
                elif v < M:
                    hi = min(int(math.ceil(v)) + 1, M - 1)
            j_lo[e], j_hi[e] = lo, hi
            if lo <= hi:
                count[lo] += 1
                count[hi + 1] -= 1
        # how many edges each column reads, and where its list starts
        run = 0
        total = 0
        for j in range(M):
            run += count[j]
            fill[j] = total
            total += run
        lists = np.empty(max(total, 1), np.int64)
        for e in range(E):             # ascending: each column's list in edge order
            for j in range(j_lo[e], j_hi[e] + 1):
                lists[fill[j]] = e
                fill[j] += 1
        start = 0
        for j in range(M):
            n = fill[j] - start
            for i in range(n):
                e = lists[start + i]
                sa[i, 0], sa[i, 1] = a[e, 0], a[e, 1]
                sb[i, 0], sb[i, 1] = b[e, 0], b[e, 1]
                sf[i, 0], sf[i, 1] = f[e, 0], f[e, 1]
            _pose_at(0, tc, ts, c[j], sa[:n], sb[:n], sf[:n], half, tol, internal, q,
                     stroke0, stroke1, beta, flip, round_tol, top, bottom, ok_a, ok_b,
                     lat_a, lat_b, psi_a, psi_b, col_a, col_b, holds, slacks,
                     scratch[:, :n])
            H[k, j] = holds[0]
            if details:
                opening[k, j] = top[0] - bottom[0]
                for i in range(KK):
                    edge_a[k, j, i] = lists[start + col_a[0, i]] if col_a[0, i] >= 0 else -1
                    edge_b[k, j, i] = lists[start + col_b[0, i]] if col_b[0, i] >= 0 else -1
            start = fill[j]


def _pose_one(p: int, theta: float, c: float, a: Any, b: Any, f: Any, half: float,
              tol: float, internal: bool, q: Any, stroke0: float, stroke1: float,
              beta: float, flip: float, round_tol: float, top: Any, bottom: Any, ok_a: Any,
              ok_b: Any, lat_a: Any, lat_b: Any, psi_a: Any, psi_b: Any, col_a: Any,
              col_b: Any, holds: Any, slacks: Any, scratch: Any) -> None:
    """The pose ``(theta, c)`` into row ``p`` of the outputs: both pads, the verdict and
    its slacks (``_poses._evaluate``; NaN and -1 where a feature is missing).
    ``scratch`` (4, E)."""
    _pose_at(p, math.cos(theta), math.sin(theta), c, a, b, f, half, tol, internal, q,
             stroke0, stroke1, beta, flip, round_tol, top, bottom, ok_a, ok_b, lat_a, lat_b,
             psi_a, psi_b, col_a, col_b, holds, slacks, scratch)


def _pose_at(p: int, tc: float, ts: float, c: float, a: Any, b: Any, f: Any, half: float,
             tol: float, internal: bool, q: Any, stroke0: float, stroke1: float,
             beta: float, flip: float, round_tol: float, top: Any, bottom: Any, ok_a: Any,
             ok_b: Any, lat_a: Any, lat_b: Any, psi_a: Any, psi_b: Any, col_a: Any,
             col_b: Any, holds: Any, slacks: Any, scratch: Any) -> None:
    """:func:`_pose_one` given the cosine ``tc`` and sine ``ts`` of its angle (a grid's
    row computes them once)."""
    E = a.shape[0]
    K = K_MAX
    for s in range(2 * K * K + 2):
        slacks[p, s] = np.nan
    if internal:
        # rows 2 and 3 of scratch: the edges each pad may meet, above and below
        y_q = tc * q[0] + ts * q[1]
        free = _hole_sides(tc, ts, c, a, b, half, tol, y_q, scratch)
        for e in range(E):
            fy = tc * f[e, 0] + ts * f[e, 1]
            scratch[2, e] = 1.0 if fy > 0 and scratch[2, e] > 0 else 0.0
            scratch[3, e] = 1.0 if fy < 0 and scratch[3, e] > 0 else 0.0
        _pad_loop(p, tc, ts, c, a, b, f, half, tol, -1.0, 1.0, 2, top, ok_a,
                  lat_a, psi_a, col_a, scratch, 0)
        _pad_loop(p, tc, ts, c, a, b, f, half, tol, 1.0, -1.0, 3, bottom, ok_b,
                  lat_b, psi_b, col_b, scratch, 0)
        ok_a[p] = ok_a[p] and free and _inside_ring(tc, ts, a, b, c, y_q)
    else:
        _outer_pads(p, tc, ts, c, a, b, f, half, tol, top, ok_a, lat_a, psi_a, col_a,
                    bottom, ok_b, lat_b, psi_b, col_b, scratch)
    opening = top[p] - bottom[p]
    any_pair = False
    # the cone's edges where both forces are along the closing direction (psi 0, the
    # usual case), computed once
    tan_hi = math.tan(min(beta, math.pi / 2 - round_tol))
    tan_lo = math.tan(max(-beta, -math.pi / 2 + round_tol))
    for i in range(K):
        for j in range(K):
            pa = flip * psi_a[p, i]
            pb = -flip * psi_b[p, j]
            lo = max(pa, pb) - beta
            hi = min(pa, pb) + beta
            if lo < hi:         # False where a feature is missing (NaN)
                t_hi = tan_hi if hi == beta else math.tan(min(hi, math.pi / 2 - round_tol))
                t_lo = tan_lo if lo == -beta else math.tan(max(lo, -math.pi / 2 + round_tol))
                s_hi = opening * t_hi - (lat_b[p, j, 0] - lat_a[p, i, 1])
                s_lo = (lat_b[p, j, 1] - lat_a[p, i, 0]) - opening * t_lo
                slacks[p, i * K + j] = s_hi
                slacks[p, K * K + i * K + j] = s_lo
                if s_hi > 0 and s_lo > 0:
                    any_pair = True
    s_min, s_max = opening - stroke0, stroke1 - opening
    slacks[p, 2 * K * K] = s_min
    slacks[p, 2 * K * K + 1] = s_max
    holds[p] = ok_a[p] and ok_b[p] and beta > 0 and any_pair and s_min >= 0 \
        and s_max >= 0


def poses(th: Any, c: Any, a: Any, b: Any, f: Any, half: float, tol: float,
          q: Any, stroke: tuple[float, float], beta: float, round_tol: float
          ) -> tuple[Any, ...] | None:
    """Every pose ``(th[p], c[p])`` of the batch against the edges ``a``-``b`` (E, 2,
    from the centroid) whose contact forces are ``f`` (E, 2); ``q``: the insertion point
    from the centroid (internal grip) or None.  Returns ``(top, bottom, ok_a, ok_b,
    lat_a, lat_b, psi_a, psi_b, col_a, col_b, holds, slacks)`` as ``_poses._evaluate``
    builds them, or None when the compiled loop cannot run."""
    P, K = th.shape[0], K_MAX
    top, bottom = np.empty(P), np.empty(P)
    ok_a, ok_b = np.zeros(P, bool), np.zeros(P, bool)
    lat_a, lat_b = np.full((P, K, 2), np.nan), np.full((P, K, 2), np.nan)
    psi_a, psi_b = np.full((P, K), np.nan), np.full((P, K), np.nan)
    col_a, col_b = np.full((P, K), -1, np.int64), np.full((P, K), -1, np.int64)
    holds = np.zeros(P, bool)
    slacks = np.full((P, 2 * K * K + 2), np.nan)
    internal = q is not None
    qq = np.zeros(2) if q is None else np.ascontiguousarray(q, dtype=float)
    if not _run("_poses_loop", np.ascontiguousarray(th, dtype=float),
                np.ascontiguousarray(c, dtype=float),
                np.ascontiguousarray(a, dtype=float),
                np.ascontiguousarray(b, dtype=float),
                np.ascontiguousarray(f, dtype=float), float(half), float(tol),
                internal, qq, float(stroke[0]), float(stroke[1]), float(beta),
                -1.0 if internal else 1.0, float(round_tol), top, bottom, ok_a,
                ok_b, lat_a, lat_b, psi_a, psi_b, col_a, col_b, holds, slacks):
        return None
    return (top, bottom, ok_a, ok_b, lat_a, lat_b, psi_a, psi_b, col_a, col_b, holds,
            slacks)


def grid(th: Any, c: Any, a: Any, b: Any, f: Any, half: float, tol: float, q: Any,
         stroke: tuple[float, float], beta: float, round_tol: float,
         details: bool = False) -> Any:
    """Whether each pose of the grid ``th x c`` (``c`` evenly spaced, increasing) holds,
    (K, M) booleans (:func:`_grid_loop`: the verdicts of :func:`poses`, each pose
    reading only the edges near its strip); with ``details``, ``(holds, opening,
    edge_a, edge_b)`` (the edges as indices of ``a``, -1 for none); None when the
    compiled loop cannot run."""
    K, M = len(th), len(c)
    H = np.zeros((K, M), dtype=np.bool_)
    shape = (K, M) if details else (1, 1)
    opening = np.full(shape, np.nan)
    edge_a = np.full((*shape, K_MAX), -1, np.int64)
    edge_b = np.full((*shape, K_MAX), -1, np.int64)
    internal = q is not None
    qq = np.zeros(2) if q is None else np.ascontiguousarray(q, dtype=float)
    if not _run("_grid_loop", np.ascontiguousarray(th, dtype=float),
                np.ascontiguousarray(c, dtype=float), np.ascontiguousarray(a, dtype=float),
                np.ascontiguousarray(b, dtype=float), np.ascontiguousarray(f, dtype=float),
                float(half), float(tol), internal, qq, float(stroke[0]), float(stroke[1]),
                float(beta), -1.0 if internal else 1.0, float(round_tol), H, bool(details),
                opening, edge_a, edge_b):
        return None
    return (H, opening, edge_a, edge_b) if details else H


def _box_loop(H: Any, dth: float, dc: float, radius: float, max_rows: int,
              out: Any) -> None:
    """``_grid._box_scores_numpy`` as one loop: for each first row, the rows from it
    AND-ed one by one, the longest run of the intersection read at each; a first row
    stops once its longest run cannot beat the best (runs only shorten), so the best
    box and its ties are those of the numpy search (first row, then first prefix, then
    first run)."""
    K, M = H.shape
    best = -1.0
    acc = np.empty(M, dtype=np.bool_)
    for k0 in range(K):
        for j in range(M):
            acc[j] = H[k0, j]
        for r in range(max_rows):
            if r:
                row = (k0 + r) % K
                for j in range(M):
                    acc[j] = acc[j] and H[row, j]
            length, end, run = 0, 0, 0
            for j in range(M):
                run = run + 1 if acc[j] else 0
                if run > length:
                    length, end = run, j
            if length == 0 or (length - 1) * dc <= best:
                break
            score = min((length - 1) * dc, r * dth * radius)
            if score > best:
                best = score
                out[0], out[1], out[2], out[3], out[4] = score, k0, k0 + r, \
                    end - length + 1, end


def box_scores(H: Any, dth: float, dc: float, radius: float, max_rows: int
               ) -> tuple[float, int, int, int, int] | None:
    """The largest box of True cells of the pose grid ``H`` (``_grid._box_scores``),
    compiled; None when the loop cannot run."""
    out = np.array([-1.0, 0, 0, 0, 0])
    if not _run("_box_loop", np.ascontiguousarray(H, dtype=np.bool_), float(dth), float(dc),
                float(radius), int(max_rows), out):
        return None
    return float(out[0]), int(out[1]), int(out[2]), int(out[3]), int(out[4])


# ----------------------------------------------------------------------------- proofs

_TWO_PI = 2.0 * math.pi
#: Relative room left by the shortcuts of :func:`_candidates` (bounds that skip work only
#: where the full test must fail by more than rounding).
_SLACK = ROUND_TOL


def _sin_range(a: float, b: float, t0: float, t1: float) -> tuple[float, float]:
    """``_poses._sin_range`` of numbers: the exact range of ``a cos t + b sin t`` over
    ``[t0, t1]``."""
    return _range(a, b, math.hypot(a, b), math.atan2(b, a), t0, t1, math.cos(t0),
                  math.sin(t0), math.cos(t1), math.sin(t1))


def _range(a: float, b: float, r: float, phi: float, t0: float, t1: float, c0: float,
           s0: float, c1: float, s1: float) -> tuple[float, float]:
    """:func:`_sin_range` given ``r = hypot(a, b)``, ``phi = atan2(b, a)`` and the
    cosines and sines of ``t0``, ``t1`` (the same numbers, computed once)."""
    v0 = a * c0 + b * s0
    v1 = a * c1 + b * s1
    has_max = _wrap_positive(phi - t0) <= t1 - t0
    has_min = _wrap_positive(phi + math.pi - t0) <= t1 - t0
    return (-r if has_min else min(v0, v1)), (r if has_max else max(v0, v1))


def _wrap_positive(x: float) -> float:
    """``x % (2 pi)`` (numpy's ``mod``, to the last bit) without ``fmod`` where
    ``-4 pi <= x < 2 pi``: there ``x + 2 pi`` is exact for ``x <= -2 pi`` (Sterbenz), and
    ``fmod`` would return ``x`` itself, then add ``2 pi`` once if negative."""
    if x >= _TWO_PI or x < -2 * _TWO_PI:
        return x % _TWO_PI
    if x < -_TWO_PI:
        x = x + _TWO_PI
    return x + _TWO_PI if x < 0 else x


def _polar(x: Any, y: Any) -> Any:
    """Rows ``(x, y, hypot, atan2)`` (n, 4) of the vectors ``(x, y)``, for :func:`_range`."""
    out = np.empty((x.shape[0], 4))
    for k in range(x.shape[0]):
        out[k, 0], out[k, 1] = x[k], y[k]
        out[k, 2], out[k, 3] = math.hypot(x[k], y[k]), math.atan2(y[k], x[k])
    return out


def _vrange(v: Any, k: int, t0: float, t1: float, trig: Any) -> tuple[float, float]:
    """:func:`_range` of row ``k`` of a :func:`_polar` table."""
    return _range(v[k, 0], v[k, 1], v[k, 2], v[k, 3], t0, t1, trig[0], trig[1], trig[2],
                  trig[3])


def _nan_min(x: float, y: float) -> float:
    """numpy's ``minimum``: NaN if either is."""
    return x + y if (x != x or y != y) else min(x, y)


def _nan_max(x: float, y: float) -> float:
    """numpy's ``maximum``: NaN if either is."""
    return x + y if (x != x or y != y) else max(x, y)


def _candidates(box: Any, trig: Any, ids: Any, n: int, a: Any, b: Any, nrm: Any,
                uniq: Any, inv: Any, sign: float, internal: bool, ahead: Any, half: float,
                zero: float, contact_tol: float, ys: Any, xs: Any, dxr: Any, dy: Any,
                fn: Any, ranges: Any, vmask: Any, touched: Any, facing: Any, p0: Any,
                p1: Any, centre: Any, hw: Any, x_known: bool) -> tuple[float, float, int]:
    """``_certify._pad_candidates`` for one box ``(t0, t1, c0, c1)`` (``trig``: the
    cosines and sines of its ends) over the edges ``ids[:n]`` (increasing; every edge
    that may meet the strip over the box among them): the first :data:`K_MAX` candidate
    contacts into ``p0``, ``p1`` (K, 2), ``centre``, ``hw`` (K,) in the numpy order
    (vertices by their unique index, then the cuts by the strip's side ``-half``, then
    ``+half``, each by edge), and ``(lower, high, count)``: the bounds of the pad's stop
    and how many candidates there are.  :func:`_polar` tables: ``ys``, ``xs`` (2m) the
    heights (``sign`` times) and lateral positions of the edges' ends (starts, then
    ends), ``dxr``, ``dy`` (m) of the edges' directions, ``fn`` (m) of the normals this
    pad's facing is read from.  ``ranges`` (2m, 4): the ends' lateral and height
    ranges over the box, the lateral ones already there with ``x_known`` (the same for
    both pads);  ``vmask`` (U,; all False, left so), ``touched`` (2m,), ``facing``
    (m, 2): scratch."""
    t0, t1, c0, c1 = box[0], box[1], box[2], box[3]
    m = a.shape[0]
    lower = -np.inf
    for k in range(n):
        for idx in (ids[k], m + ids[k]):
            y_lo, y_hi = _vrange(ys, idx, t0, t1, trig)
            if not x_known:
                ranges[idx, 0], ranges[idx, 1] = _vrange(xs, idx, t0, t1, trig)
            ranges[idx, 2], ranges[idx, 3] = y_lo, y_hi
    # which edges the pad may meet (maybe) and surely faces (surely); per edge
    tm, cm = (t0 + t1) / 2, (c0 + c1) / 2
    sin_m, cos_m = math.sin(tm), math.cos(tm)
    w_y, w_u = -np.inf, -1          # the dominating vertex (``_certify._dominated``)
    for k in range(n):
        e = ids[k]
        f_lo, f_hi = _vrange(fn, e, t0, t1, trig)
        if internal:
            if -sign > 0:
                maybe, surely = f_hi > 0 and ahead[e], f_lo > 0 and ahead[e]
            else:
                maybe, surely = f_lo < 0 and ahead[e], f_hi < 0 and ahead[e]
        else:
            maybe, surely = f_hi > contact_tol, True
        facing[e, 0], facing[e, 1] = maybe, surely
        for idx in (e, m + e):
            if surely and ranges[idx, 0] >= c1 - half and ranges[idx, 1] <= c0 + half:
                lower = _nan_max(lower, ranges[idx, 2])
                y = ranges[idx, 2]
                if y > w_y or (y == w_y and inv[idx] < w_u):
                    w_y, w_u = y, inv[idx]
        xa_m = -a[e, 0] * sin_m + a[e, 1] * cos_m
        xb_m = -b[e, 0] * sin_m + b[e, 1] * cos_m
        dx_m = xb_m - xa_m
        tt = (cm - xa_m) / dx_m if abs(dx_m) > 0 else np.nan
        if surely and tt >= 0 and tt <= 1:
            qx = a[e, 0] + tt * (b[e, 0] - a[e, 0])
            qy = a[e, 1] + tt * (b[e, 1] - a[e, 1])
            # its height's lower bound is at most its height at either end angle: only
            # a point that may raise the running bound is looked at
            y_end = min(sign * qx * trig[0] + sign * qy * trig[1],
                        sign * qx * trig[2] + sign * qy * trig[3])
            if not y_end > lower - _SLACK * (abs(lower) + abs(y_end)):
                continue
            px_lo, px_hi = _range(qy, -qx, math.hypot(qy, -qx), math.atan2(-qx, qy), t0,
                                  t1, trig[0], trig[1], trig[2], trig[3])
            if px_lo >= c1 - half and px_hi <= c0 + half:
                sx, sy = sign * qx, sign * qy
                py_lo, _ = _range(sx, sy, math.hypot(sx, sy), math.atan2(sy, sx), t0, t1,
                                  trig[0], trig[1], trig[2], trig[3])
                lower = _nan_max(lower, py_lo)
    high = -np.inf
    n_touched = 0
    for k in range(n):
        for idx in (ids[k], m + ids[k]):
            if facing[idx % m, 0] and ranges[idx, 1] >= c0 - half \
                    and ranges[idx, 0] <= c1 + half and ranges[idx, 3] >= lower \
                    and not _below(uniq, w_u, uniq[inv[idx], 0], uniq[inv[idx], 1], sign,
                                   t0, t1, 2 * zero):
                if not vmask[inv[idx]]:
                    vmask[inv[idx]] = True
                    touched[n_touched] = inv[idx]
                    n_touched += 1
                high = _nan_max(high, ranges[idx, 3])
    count = 0
    face = (t0 + t1) / 2 + (0.0 if sign < 0 else math.pi)
    for u in np.sort(touched[:n_touched]):
        vmask[u] = False
        if count < K_MAX:
            p0[count, 0], p0[count, 1] = uniq[u, 0], uniq[u, 1]
            p1[count, 0], p1[count, 1] = uniq[u, 0], uniq[u, 1]
            centre[count], hw[count] = face, (t1 - t0) / 2
        count += 1
    for side in (-half, half):
        s_lo, s_hi = c0 + side, c1 + side
        for k in range(n):
            e = ids[k]
            if not facing[e, 0]:
                continue
            xa_lo, xa_hi = ranges[e, 0], ranges[e, 1]
            e_lo, e_hi = min(xa_lo, ranges[m + e, 0]), max(xa_hi, ranges[m + e, 1])
            if not (e_hi >= s_lo and e_lo <= s_hi):
                continue
            dxr_lo, dxr_hi = _vrange(dxr, e, t0, t1, trig)
            dy_lo, dy_hi = _vrange(dy, e, t0, t1, trig)
            rise = (1 if dy_lo > 0 else (-1 if dy_hi < 0 else 0)) \
                * (1 if dxr_lo >= -zero else (-1 if dxr_hi <= zero else 0))
            if rise * (1.0 if side > 0 else -1.0) < 0:      # the edge falls there
                continue
            if dxr_lo <= 0 and dxr_hi >= 0:
                t_lo, t_hi = 0.0, 1.0
            else:
                q0, q1 = (s_lo - xa_hi) / dxr_lo, (s_hi - xa_lo) / dxr_lo
                q2, q3 = (s_lo - xa_hi) / dxr_hi, (s_hi - xa_lo) / dxr_hi
                t_lo = _nan_max(0.0, _nan_min(_nan_min(q0, q1), _nan_min(q2, q3)))
                t_hi = _nan_min(1.0, _nan_max(_nan_max(q0, q1), _nan_max(q2, q3)))
            if not t_lo <= t_hi:
                continue
            ex, ey = b[e, 0] - a[e, 0], b[e, 1] - a[e, 1]
            x0, y0 = a[e, 0] + t_lo * ex, a[e, 1] + t_lo * ey
            x1, y1 = a[e, 0] + t_hi * ex, a[e, 1] + t_hi * ey
            # a height is at most the point's distance from the centroid: a cut that
            # cannot reach the bound is dropped before its angles are looked at
            reach = max(math.hypot(x0, y0), math.hypot(x1, y1))
            if reach < lower - _SLACK * (abs(lower) + reach):
                continue
            h0 = _range(sign * x0, sign * y0, math.hypot(sign * x0, sign * y0),
                        math.atan2(sign * y0, sign * x0), t0, t1, trig[0], trig[1],
                        trig[2], trig[3])[1]
            h1 = _range(sign * x1, sign * y1, math.hypot(sign * x1, sign * y1),
                        math.atan2(sign * y1, sign * x1), t0, t1, trig[0], trig[1],
                        trig[2], trig[3])[1]
            hh = max(h0, h1)
            if not hh >= lower:
                continue
            if _below(uniq, w_u, x0, y0, sign, t0, t1, 2 * zero) \
                    and _below(uniq, w_u, x1, y1, sign, t0, t1, 2 * zero):
                continue
            high = _nan_max(high, hh)
            if count < K_MAX:
                p0[count, 0], p0[count, 1] = x0, y0
                p1[count, 0], p1[count, 1] = x1, y1
                centre[count], hw[count] = math.atan2(-nrm[e, 1], -nrm[e, 0]), 0.0
            count += 1
    return lower, high, count


def _below(uniq: Any, w: int, px: float, py: float, sign: float, t0: float, t1: float,
           gap: float) -> bool:
    """``_certify._dominated`` for one point: lower than the dominating vertex ``uniq[w]``
    (none: ``w`` -1) by more than ``gap`` at every angle of ``[t0, t1]``."""
    if w < 0:
        return False
    d_lo, _ = _sin_range(sign * (uniq[w, 0] - px), sign * (uniq[w, 1] - py), t0, t1)
    return d_lo > gap


def _arc_holds(ax: float, ay: float, bx: float, by: float, cx: float, cy: float,
               dx: float, dy: float, turn: float, ca: float, ha: float, cb: float,
               hb: float, beta: float, tol: float) -> bool:
    """``_certify._pairs_hold`` for one pair: the smallest arc holding the four corner
    chords (``_arc_of``), each force within ``beta`` of every chord's direction."""
    a0 = math.atan2(ay, ax)
    lo, hi = 0.0, 0.0
    shortest = math.hypot(ax, ay)
    for vx, vy in ((bx, by), (cx, cy), (dx, dy)):
        rel = (math.atan2(vy, vx) - a0 + math.pi) % _TWO_PI - math.pi
        lo, hi = min(lo, rel), max(hi, rel)
        shortest = min(shortest, math.hypot(vx, vy))
    if hi - lo >= math.pi - tol or shortest <= 0:
        return False
    d, hd = a0 + (lo + hi) / 2, (hi - lo) / 2
    if abs((d + turn - ca + math.pi) % _TWO_PI - math.pi) + hd + ha >= beta:
        return False
    return abs((d + math.pi + turn - cb + math.pi) % _TWO_PI - math.pi) + hd + hb < beta


class _Tables:
    """(Documentation only: what :func:`_tables` returns, in order.)  The polar tables of
    the fixed vectors (:func:`_polar`): the ends' heights for pads A and B, their
    lateral positions, the edges' directions (lateral, and heights per pad), the normals
    each pad's facing is read from; then the scratch of :func:`_candidates` and
    :func:`_prove_box`."""


def _tables(a: Any, b: Any, nrm: Any, uniq: Any, internal: bool) -> Any:
    """The tables :func:`_prove_box` reads (see :class:`_Tables`)."""
    m = a.shape[0]
    ends = np.concatenate((a, b))
    sa, sb = (-1.0, 1.0) if internal else (1.0, -1.0)
    ys_a = _polar(sa * ends[:, 0], sa * ends[:, 1])
    ys_b = _polar(sb * ends[:, 0], sb * ends[:, 1])
    xs = _polar(ends[:, 1], -ends[:, 0])
    ex, ey = b[:, 0] - a[:, 0], b[:, 1] - a[:, 1]
    dxr = _polar(ey, -ex)
    dy_a, dy_b = _polar(sa * ex, sa * ey), _polar(sb * ex, sb * ey)
    if internal:
        fn_a = _polar(-nrm[:, 0], -nrm[:, 1])
        fn_b = fn_a
    else:
        fn_a = _polar(sa * nrm[:, 0], sa * nrm[:, 1])
        fn_b = _polar(sb * nrm[:, 0], sb * nrm[:, 1])
    return (ys_a, ys_b, xs, dxr, dy_a, dy_b, fn_a, fn_b, np.empty((2 * m, 4)),
            np.zeros(uniq.shape[0], dtype=np.bool_), np.empty(2 * m, dtype=np.int64),
            np.empty((m, 2), dtype=np.bool_), np.ones(m, dtype=np.bool_),
            np.ones(m, dtype=np.bool_), np.empty(4), np.zeros((4, K_MAX, 2)),
            np.zeros((4, K_MAX)))


def _prove_box(box: Any, ids: Any, n: int, a: Any, b: Any, nrm: Any, uniq: Any,
               inv: Any, half: float, zero: float, contact_tol: float, tol: float,
               internal: bool, q: Any, beta: float, stroke0: float, stroke1: float,
               tables: Any, x_known: bool) -> tuple[bool, float, float]:
    """``_certify._box_proofs_numpy`` for one box over the edges ``ids[:n]``: whether it
    is proved (both pads' candidates few, the opening's enclosure within the stroke,
    every pair of candidates force closure over the box; inside a hole, the closed
    jaws' segment free; the centre pose is the caller's) and that enclosure."""
    (ys_a, ys_b, xs, dxr, dy_a, dy_b, fn_a, fn_b, ranges, vmask, touched, facing, up,
     down, trig, pts, arcs) = tables
    m = a.shape[0]
    sa, sb = (-1.0, 1.0) if internal else (1.0, -1.0)
    t0, t1, c0, c1 = box[0], box[1], box[2], box[3]
    trig[0], trig[1], trig[2], trig[3] = (math.cos(t0), math.sin(t0), math.cos(t1),
                                          math.sin(t1))
    free = True
    if internal:
        yq_lo, yq_hi = _sin_range(q[0], q[1], t0, t1)
        for k in range(n):
            e = ids[k]
            ya_lo, ya_hi = _sin_range(a[e, 0], a[e, 1], t0, t1)
            yb_lo, yb_hi = _sin_range(b[e, 0], b[e, 1], t0, t1)
            xa_lo, xa_hi = _vrange(xs, e, t0, t1, trig)
            xb_lo, xb_hi = _vrange(xs, m + e, t0, t1, trig)
            meet = max(xa_hi, xb_hi) >= c0 - half and min(xa_lo, xb_lo) <= c1 + half
            up[e] = min(ya_lo, yb_lo) > yq_hi
            down[e] = max(ya_hi, yb_hi) < yq_lo
            if meet and not up[e] and not down[e]:
                free = False
    pa0, pa1, pb0, pb1 = pts[0], pts[1], pts[2], pts[3]
    ca, ha, cb, hb = arcs[0], arcs[1], arcs[2], arcs[3]
    lo_a, hi_a, n_a = _candidates(box, trig, ids, n, a, b, nrm, uniq, inv, sa, internal,
                                  up, half, zero, contact_tol, ys_a, xs, dxr, dy_a, fn_a,
                                  ranges, vmask, touched, facing, pa0, pa1, ca, ha, x_known)
    lo_b, hi_b, n_b = _candidates(box, trig, ids, n, a, b, nrm, uniq, inv, sb, internal,
                                  down, half, zero, contact_tol, ys_b, xs, dxr, dy_b, fn_b,
                                  ranges, vmask, touched, facing, pb0, pb1, cb, hb, True)
    ok = free and lo_a > -np.inf and 1 <= n_a <= K_MAX and lo_b > -np.inf \
        and 1 <= n_b <= K_MAX
    al, ah = _nan_min(sa * lo_a, sa * hi_a), _nan_max(sa * lo_a, sa * hi_a)
    bl, bh = _nan_min(sb * lo_b, sb * hi_b), _nan_max(sb * lo_b, sb * hi_b)
    o_lo, o_hi = al - bh, ah - bl
    ok = ok and stroke0 <= o_lo and o_hi <= stroke1
    turn = math.pi if internal else 0.0
    for i in range(n_a if ok else 0):
        for j in range(n_b):
            if not _arc_holds(pb0[j, 0] - pa0[i, 0], pb0[j, 1] - pa0[i, 1],
                              pb0[j, 0] - pa1[i, 0], pb0[j, 1] - pa1[i, 1],
                              pb1[j, 0] - pa0[i, 0], pb1[j, 1] - pa0[i, 1],
                              pb1[j, 0] - pa1[i, 0], pb1[j, 1] - pa1[i, 1], turn,
                              ca[i], ha[i], cb[j], hb[j], beta, tol):
                ok = False
                break
    return ok, o_lo, o_hi


def _prove_loop(boxes: Any, a: Any, b: Any, nrm: Any, uniq: Any, inv: Any, half: float,
                zero: float, contact_tol: float, tol: float, internal: bool, q: Any,
                beta: float, stroke0: float, stroke1: float, proved: Any, o_lo: Any,
                o_hi: Any) -> None:
    """:func:`_prove_box` for each box of a batch, over every edge."""
    tables = _tables(a, b, nrm, uniq, internal)
    ids = np.arange(a.shape[0])
    for k in range(boxes.shape[0]):
        proved[k], o_lo[k], o_hi[k] = _prove_box(
            boxes[k], ids, ids.shape[0], a, b, nrm, uniq, inv, half, zero, contact_tol, tol,
            internal, q, beta, stroke0, stroke1, tables, False)


#: Levels of halving the depth-first proof goes to (a box halved this often is below
#: the floats' resolution: it is not proved).
MAX_DEPTH = 120


def _certify_loop(boxes: Any, a: Any, b: Any, nrm: Any, uniq: Any, inv: Any, half: float,
                  zero: float, contact_tol: float, tol: float, internal: bool, q: Any,
                  beta: float, stroke0: float, stroke1: float, max_boxes: int,
                  radius: float, near: float, round_tol: float, out: Any) -> None:
    """``_certify.certify_box``'s subdivision, depth first: each box is proved
    (:func:`_prove_box`) or its centre pose is decided (:func:`_pose_one`: a failing
    one ends the proof, as it would end numpy's) and it is halved along its longer side
    (the angle range as the arc it sweeps at ``radius``).  Each box reads only the edges
    of its parent that may meet its strip (within ``near``), gathered per depth.  The
    boxes examined are those of numpy's breadth-first search, in another order, so the
    answer is the same: ``out = (proved, lo, hi, boxes examined)`` with ``proved`` 0
    when more than ``max_boxes`` boxes are needed or a centre pose fails."""
    m = a.shape[0]
    tables = _tables(a, b, nrm, uniq, internal)
    xs, ranges = tables[2], tables[8]
    lists = np.empty((MAX_DEPTH + 1, m), dtype=np.int64)
    counts = np.zeros(MAX_DEPTH + 1, dtype=np.int64)
    ga, gb, gf = np.empty((m, 2)), np.empty((m, 2)), np.empty((m, 2))
    for e in range(m):
        lists[0, e] = e
    counts[0] = m
    top, bottom = np.empty(1), np.empty(1)
    ok_a, ok_b, holds = np.zeros(1, np.bool_), np.zeros(1, np.bool_), np.zeros(1, np.bool_)
    lat_a, lat_b = np.empty((1, K_MAX, 2)), np.empty((1, K_MAX, 2))
    psi_a, psi_b = np.empty((1, K_MAX)), np.empty((1, K_MAX))
    col_a, col_b = np.empty((1, K_MAX), np.int64), np.empty((1, K_MAX), np.int64)
    slacks = np.empty((1, 2 * K_MAX * K_MAX + 2))
    scratch = np.empty((4, m))
    box = np.empty(4)
    trig = np.empty(4)
    stack = [(boxes[k, 0], boxes[k, 1], boxes[k, 2], boxes[k, 3], 1)
             for k in range(boxes.shape[0] - 1, -1, -1)]
    lo_open, hi_open = np.inf, -np.inf
    done = 0
    out[0] = 0.0
    while len(stack):
        t0, t1, c0, c1, depth = stack.pop()
        done += 1
        out[3] = done
        if done > max_boxes or depth > MAX_DEPTH:
            return
        box[0], box[1], box[2], box[3] = t0, t1, c0, c1
        trig[0], trig[1], trig[2], trig[3] = (math.cos(t0), math.sin(t0), math.cos(t1),
                                              math.sin(t1))
        # the parent's edges that may meet this box's strip (their ends' lateral ranges
        # kept for the proof)
        n = 0
        for k in range(counts[depth - 1]):
            e = lists[depth - 1, k]
            xa_lo, xa_hi = _vrange(xs, e, t0, t1, trig)
            xb_lo, xb_hi = _vrange(xs, m + e, t0, t1, trig)
            if max(xa_hi, xb_hi) >= c0 - half - near and min(xa_lo, xb_lo) <= c1 + half + near:
                lists[depth, n] = e
                n += 1
                ranges[e, 0], ranges[e, 1] = xa_lo, xa_hi
                ranges[m + e, 0], ranges[m + e, 1] = xb_lo, xb_hi
        counts[depth] = n
        ids = lists[depth]
        ok, o_lo, o_hi = _prove_box(box, ids, n, a, b, nrm, uniq, inv, half, zero,
                                    contact_tol, tol, internal, q, beta, stroke0, stroke1,
                                    tables, True)
        if internal or not ok:
            for k in range(n):
                e = ids[k]
                ga[k, 0], ga[k, 1] = a[e, 0], a[e, 1]
                gb[k, 0], gb[k, 1] = b[e, 0], b[e, 1]
                gf[k, 0], gf[k, 1] = -nrm[e, 0], -nrm[e, 1]
            _pose_one(0, (t0 + t1) / 2, (c0 + c1) / 2, ga[:n], gb[:n], gf[:n], half, zero,
                      internal, q, stroke0, stroke1, beta, -1.0 if internal else 1.0,
                      round_tol, top, bottom, ok_a, ok_b, lat_a, lat_b, psi_a, psi_b,
                      col_a, col_b, holds, slacks, scratch)
            if not holds[0]:
                return
        if ok:
            lo_open, hi_open = min(lo_open, o_lo), max(hi_open, o_hi)
            continue
        mt, mc = (t0 + t1) / 2, (c0 + c1) / 2
        if (t1 - t0) * radius >= c1 - c0:
            stack.append((mt, t1, c0, c1, depth + 1))
            stack.append((t0, mt, c0, c1, depth + 1))
        else:
            stack.append((t0, t1, mc, c1, depth + 1))
            stack.append((t0, t1, c0, mc, depth + 1))
    out[0], out[1], out[2] = 1.0, lo_open, hi_open


def _proof_args(boxes: Any, a: Any, b: Any, nrm: Any, uniq: Any, inv: Any, half: float,
                zero: float, contact_tol: float, tol: float, q: Any, beta: float,
                stroke: tuple[float, float]) -> tuple[Any, ...]:
    """The arguments :func:`_prove_loop` and :func:`_certify_loop` begin with, typed."""
    def floats(x: Any) -> Any:
        return np.ascontiguousarray(x, dtype=float)

    qq = np.zeros(2) if q is None else floats(q)
    return (floats(boxes), floats(a), floats(b), floats(nrm), floats(uniq),
            np.ascontiguousarray(inv, dtype=np.int64), float(half), float(zero),
            float(contact_tol), float(tol), q is not None, qq, float(beta),
            float(stroke[0]), float(stroke[1]))


def prove(boxes: Any, a: Any, b: Any, nrm: Any, uniq: Any, inv: Any, half: float,
          zero: float, contact_tol: float, tol: float, q: Any, beta: float,
          stroke: tuple[float, float]) -> tuple[Any, Any, Any] | None:
    """The proofs of a batch of boxes (``_certify._box_proofs_numpy``): ``(proved,
    o_lo, o_hi)``, compiled; None when the loop cannot run."""
    B = boxes.shape[0]
    proved, o_lo, o_hi = np.zeros(B, bool), np.empty(B), np.empty(B)
    if not _run("_prove_loop", *_proof_args(boxes, a, b, nrm, uniq, inv, half, zero,
                                            contact_tol, tol, q, beta, stroke),
                proved, o_lo, o_hi):
        return None
    return proved, o_lo, o_hi


# ----------------------------------------------------------------------------- slices


def _slices_loop(cell_t: Any, cell_lo: Any, cell_hi: Any, th: Any, a: Any, b: Any, f: Any,
                 half: float, tol: float, internal: bool, q: Any, stroke0: float,
                 stroke1: float, beta: float, flip: float, round_tol: float,
                 slice_tol: float, tiny: float, atol: float, near: float, stop_gap: float,
                 failed: Any, upward: bool, prune: bool) -> Any:
    """``_slices.holding_offsets``'s cells (sorted by angle), each decided to the end (a
    stack instead of numpy's rounds): a cell affine at three points is cut at its
    slacks' roots and its pieces decided at their middles; one that is not is split
    (``_slices._kinks``) until it is shorter than ``4 slice_tol``, then decided at its
    middle.  Each cell's poses read only the edges that may meet its strips (within
    ``near``), in their order.  Returns the holding pieces (N, 3): ``(angle index, lo,
    hi)``.  With ``stop_gap`` > 0, an angle with a piece longer than that which does not
    hold is given up at once (``failed[angle]`` True; its pieces are then incomplete):
    its slice cannot be one interval across the cells (``_slices.holds_across``).
    ``upward``: each angle's cells are read from the lowest offset up (else from the
    highest down), so that a stop leaves the interval through that end complete
    (``_slices.near_intervals``).

    ``prune`` (an external grip): a cell's poses read only the edges that may come
    within ``tol`` of a pad's stop somewhere in the cell (:func:`_stop_reach`), in their
    order; an edge left out is below the stop by more than ``tol`` at every pose of the
    cell, so it gives neither the stop (a maximum of the edges' heights) nor a feature
    (an edge within ``tol`` of it): the pieces are those of every edge, bit for bit."""
    E = a.shape[0]
    K = K_MAX
    S = 2 * K * K + 2
    top, bottom = np.empty(3), np.empty(3)
    ok_a, ok_b, holds = (np.zeros(3, np.bool_), np.zeros(3, np.bool_),
                         np.zeros(3, np.bool_))
    lat_a, lat_b = np.empty((3, K, 2)), np.empty((3, K, 2))
    psi_a, psi_b = np.empty((3, K)), np.empty((3, K))
    col_a, col_b = np.empty((3, K), np.int64), np.empty((3, K), np.int64)
    slacks = np.empty((3, S))
    scratch = np.empty((4, E))
    where = np.empty(S + 2)
    qs = np.empty((5, 2 + 4 * K))
    x_lo, x_hi = np.empty(E), np.empty(E)
    xy = np.empty((E, 7))
    ga, gb, gf = np.empty((E, 2)), np.empty((E, 2)), np.empty((E, 2))
    near_ids = np.empty(E, np.int64)
    out_t, out_lo, out_hi = [0], [0.0], [0.0]
    out_t.pop()
    out_lo.pop()
    out_hi.pop()
    first = 0
    while first < cell_t.shape[0]:
        last = first
        while last < cell_t.shape[0] and cell_t[last] == cell_t[first]:
            last += 1
        t = cell_t[first]
        theta = th[t]
        tc, ts = math.cos(theta), math.sin(theta)
        for e in range(E):
            xa = -ts * a[e, 0] + tc * a[e, 1]
            xb = -ts * b[e, 0] + tc * b[e, 1]
            x_lo[e], x_hi[e] = min(xa, xb), max(xa, xb)
            if prune:               # what _stop_reach reads of the edge at this angle
                xy[e, 0], xy[e, 1] = xa, xb
                ya = tc * a[e, 0] + ts * a[e, 1]
                yb = tc * b[e, 0] + ts * b[e, 1]
                xy[e, 2], xy[e, 3] = ya, yb
                xy[e, 4] = (yb - ya) / (xb - xa) if abs(xb - xa) > tol else np.nan
                xy[e, 5], xy[e, 6] = max(ya, yb), max(-ya, -yb)
        if upward:
            stack_lo = list(cell_lo[first:last][::-1])
            stack_hi = list(cell_hi[first:last][::-1])
        else:
            stack_lo = list(cell_lo[first:last])
            stack_hi = list(cell_hi[first:last])
        first = last
        while len(stack_lo):
            if failed[t]:
                break                   # the angle given up: its cells left unread
            lo, hi = stack_lo.pop(), stack_hi.pop()
            m = 0
            for e in range(E):
                if x_hi[e] >= lo - half - near and x_lo[e] <= hi + half + near:
                    near_ids[m] = e
                    m += 1
            if prune:
                m = _stop_reach(near_ids, m, x_lo, x_hi, xy, lo, hi, half, tol)
            for n in range(m):
                e = near_ids[n]
                ga[n, 0], ga[n, 1] = a[e, 0], a[e, 1]
                gb[n, 0], gb[n, 1] = b[e, 0], b[e, 1]
                gf[n, 0], gf[n, 1] = f[e, 0], f[e, 1]
            n = m
            if _cell(t, theta, lo, hi, ga[:n], gb[:n], gf[:n], half, tol, internal, q,
                     stroke0, stroke1, beta, flip, round_tol, slice_tol, tiny, atol, top,
                     bottom, ok_a, ok_b, lat_a, lat_b, psi_a, psi_b, col_a, col_b, holds,
                     slacks, scratch, where, qs, stack_lo, stack_hi, out_t, out_lo, out_hi,
                     stop_gap, upward):
                failed[t] = True
    rows = np.empty((len(out_t), 3))
    for k in range(len(out_t)):
        rows[k, 0], rows[k, 1], rows[k, 2] = out_t[k], out_lo[k], out_hi[k]
    return rows


def _stop_reach(ids: Any, m: int, x_lo: Any, x_hi: Any, xy: Any, lo: float, hi: float,
                half: float, tol: float) -> int:
    """The edges among ``ids[:m]`` (in order) that may come within ``tol`` of either
    pad's stop at some pose of the cell ``[lo, hi]`` (:func:`_slices_loop`'s
    ``prune``), moved to the front of ``ids``; returns how many.  ``xy``: per edge its
    ends across (``xa, xb``) and along (``ya, yb``) the closing direction, its slope
    (NaN where :func:`_pad_loop` takes it as level across, ``|xb - xa| <= tol``), and
    its highest ``y`` and ``-y``.

    A lower bound of each stop over the cell: an edge that meets every pose's strip
    (``x_hi >= hi - half`` and ``x_lo <= lo + half``, the strips' ends being monotone in
    the offset) raises the stop to at least its height over the part of it every strip
    covers (a pad's stop is the highest point of the edges in its strip), or its lowest
    end where no part is in every strip.  An upper bound of each edge's height: its
    highest over the union of the strips (``[lo - half, hi + half]``).  An edge whose
    upper bound is below both lower bounds by more than twice ``tol`` (one ``tol`` the
    contact's, one for rounding: the coordinates are within the part's size of the
    centroid and ``tol`` is a billionth of it) is never within ``tol`` of a stop."""
    s_hi, s_lo = hi - half, lo + half
    u_lo, u_hi = lo - half, hi + half
    low_top, low_bottom = -np.inf, -np.inf
    for k in range(m):
        e = ids[k]
        if x_hi[e] < s_hi or x_lo[e] > s_lo \
                or (xy[e, 5] <= low_top and xy[e, 6] <= low_bottom):
            continue
        slope = xy[e, 4]
        if slope != slope:
            top, bottom = xy[e, 5], xy[e, 6]
        else:
            p0, p1 = max(x_lo[e], s_hi), min(x_hi[e], s_lo)
            if p0 <= p1:        # a part of the edge in every strip
                xa, ya = xy[e, 0], xy[e, 2]
                y0, y1 = ya + (p0 - xa) * slope, ya + (p1 - xa) * slope
                top, bottom = max(y0, y1), max(-y0, -y1)
            else:               # some point of it in each strip
                top, bottom = -xy[e, 6], -xy[e, 5]
        low_top, low_bottom = max(low_top, top), max(low_bottom, bottom)
    if low_top == -np.inf or low_bottom == -np.inf:
        return m
    low_top -= 2 * tol
    low_bottom -= 2 * tol
    n = 0
    for k in range(m):
        e = ids[k]
        if xy[e, 5] < low_top and xy[e, 6] < low_bottom:
            continue
        slope = xy[e, 4]
        if slope != slope:
            up, down = xy[e, 5], xy[e, 6]
        else:
            xa, ya = xy[e, 0], xy[e, 2]
            p0, p1 = max(x_lo[e], u_lo), min(x_hi[e], u_hi)
            y0, y1 = ya + (p0 - xa) * slope, ya + (p1 - xa) * slope
            up, down = max(y0, y1), max(-y0, -y1)
        if up >= low_top or down >= low_bottom:
            ids[n] = e
            n += 1
    return n


def _cell(t: int, theta: float, lo: float, hi: float, a: Any, b: Any, f: Any, half: float,
          tol: float, internal: bool, q: Any, stroke0: float, stroke1: float, beta: float,
          flip: float, round_tol: float, slice_tol: float, tiny: float, atol: float,
          top: Any, bottom: Any, ok_a: Any, ok_b: Any, lat_a: Any, lat_b: Any, psi_a: Any,
          psi_b: Any, col_a: Any, col_b: Any, holds: Any, slacks: Any, scratch: Any,
          where: Any, qs: Any, stack_lo: Any, stack_hi: Any, out_t: Any, out_lo: Any,
          out_hi: Any, stop_gap: float, upward: bool) -> bool:
    """One cell ``[lo, hi]`` of the angle ``t`` (:func:`_slices_loop`): its holding
    pieces appended to ``out_*``, or its two parts pushed on the stack (the lower one
    read first when ``upward``).  Returns whether a piece longer than ``stop_gap`` (> 0)
    was found not to hold."""
    gap = False
    S = slacks.shape[1]
    inset = min((hi - lo) / 4, slice_tol)
    pts = (lo + inset, (lo + hi) / 2, hi - inset)
    for i in range(3):
        _pose_one(i, theta, pts[i], a, b, f, half, tol, internal, q, stroke0, stroke1,
                  beta, flip, round_tol, top, bottom, ok_a, ok_b, lat_a, lat_b, psi_a,
                  psi_b, col_a, col_b, holds, slacks, scratch)
    if _affine(top, bottom, lat_a, lat_b, psi_a, psi_b, ok_a, ok_b, atol):
        n = 2
        where[0], where[1] = lo, hi
        for s in range(S):
            s0, s2 = slacks[0, s], slacks[2, s]
            if s0 * s2 < 0 or ((s0 == 0) != (s2 == 0)):
                root = pts[0] + s0 / (s0 - s2) * (pts[2] - pts[0])
                if root == root:
                    where[n] = min(max(root, lo), hi)
                    n += 1
        cuts = np.sort(where[:n])
        for k in range(n - 1):
            if cuts[k + 1] - cuts[k] > tiny:
                _pose_one(0, theta, (cuts[k] + cuts[k + 1]) / 2, a, b, f, half, tol,
                          internal, q, stroke0, stroke1, beta, flip, round_tol, top,
                          bottom, ok_a, ok_b, lat_a, lat_b, psi_a, psi_b, col_a, col_b,
                          holds, slacks, scratch)
                if holds[0]:
                    out_t.append(t)
                    out_lo.append(cuts[k])
                    out_hi.append(cuts[k + 1])
                elif stop_gap > 0 and cuts[k + 1] - cuts[k] > stop_gap:
                    gap = True
    elif hi - lo <= 4 * slice_tol:
        if holds[1]:
            out_t.append(t)
            out_lo.append(lo)
            out_hi.append(hi)
        elif stop_gap > 0 and hi - lo > stop_gap:
            gap = True
    else:
        # two more points, a step in from each end (``_slices._kinks``)
        e0, e2 = lo + 2 * inset, hi - 2 * inset
        _quantities(top, bottom, lat_a, lat_b, qs, 0, 0)
        _quantities(top, bottom, lat_a, lat_b, qs, 1, 2)
        _quantities(top, bottom, lat_a, lat_b, qs, 2, 4)
        _pose_one(0, theta, e0, a, b, f, half, tol, internal, q, stroke0, stroke1,
                  beta, flip, round_tol, top, bottom, ok_a, ok_b, lat_a, lat_b, psi_a,
                  psi_b, col_a, col_b, holds, slacks, scratch)
        _pose_one(1, theta, e2, a, b, f, half, tol, internal, q, stroke0, stroke1,
                  beta, flip, round_tol, top, bottom, ok_a, ok_b, lat_a, lat_b, psi_a,
                  psi_b, col_a, col_b, holds, slacks, scratch)
        _quantities(top, bottom, lat_a, lat_b, qs, 0, 1)
        _quantities(top, bottom, lat_a, lat_b, qs, 1, 3)
        cut = _kink(pts[0], e0, pts[1], e2, pts[2], qs, lo, hi, inset, atol)
        if upward:
            stack_lo.append(cut)
            stack_hi.append(hi)
            stack_lo.append(lo)
            stack_hi.append(cut)
        else:
            stack_lo.append(lo)
            stack_hi.append(cut)
            stack_lo.append(cut)
            stack_hi.append(hi)
    return gap


def _quantities(top: Any, bottom: Any, lat_a: Any, lat_b: Any, qs: Any, i: int,
                row: int) -> None:
    """Row ``row`` of ``qs``: the stops and lateral spans of pose ``i`` in the order of
    ``_slices`` (top, bottom, A's spans, B's spans)."""
    K = lat_a.shape[1]
    qs[row, 0], qs[row, 1] = top[i], bottom[i]
    for k in range(K):
        qs[row, 2 + 2 * k], qs[row, 3 + 2 * k] = lat_a[i, k, 0], lat_a[i, k, 1]
        qs[row, 2 + 2 * K + 2 * k] = lat_b[i, k, 0]
        qs[row, 3 + 2 * K + 2 * k] = lat_b[i, k, 1]


def _kink(p0: float, e0: float, p1: float, e2: float, p2: float, qs: Any, lo: float,
          hi: float, inset: float, atol: float) -> float:
    """``_slices._kinks`` for one cell, the five points' quantities the rows of ``qs``."""
    best, j = -1.0, 0
    for k in range(qs.shape[1]):
        fin = True
        for row in range(5):
            if not math.isfinite(qs[row, k]):
                fin = False
        dev = abs(qs[2, k] - (qs[0, k] + qs[4, k]) / 2) if fin else -1.0
        if dev > best:
            best, j = dev, k
    a0, b0, m1, b2, a2 = qs[0, j], qs[1, j], qs[2, j], qs[3, j], qs[4, j]
    s_l = (b0 - a0) / (e0 - p0)
    s_r = (a2 - b2) / (p2 - e2)
    x = (a2 - a0 + s_l * p0 - s_r * p2) / (s_l - s_r)
    left = a0 + s_l * (p1 - p0)
    right = a2 + s_r * (p1 - p2)
    if m1 < (a0 + a2) / 2:
        model = _nan_max(left, right)
    else:
        model = _nan_min(left, right)
    if best > atol and abs(model - m1) <= atol and x > lo + 2 * inset \
            and x < hi - 2 * inset:
        return x
    return p1


def _kind(ok: bool, psi: Any, i: int) -> int:
    """A pad's kind at pose ``i`` (``_poses._contacts``): 0 not valid, 2 on a pad corner,
    1 otherwise."""
    if not ok:
        return 0
    for k in range(psi.shape[1]):
        if abs(psi[i, k]) > 0:          # False for NaN
            return 2
    return 1


def _affine(top: Any, bottom: Any, lat_a: Any, lat_b: Any, psi_a: Any, psi_b: Any,
            ok_a: Any, ok_b: Any, atol: float) -> bool:
    """``_slices.holding_offsets``'s test of a cell at its three points: the same
    contacts (kinds, force angles, which quantities are finite) and every stop and
    lateral span affine to ``atol`` (its middle value the mean of its ends')."""
    for i in (0, 2):
        if _kind(ok_a[i], psi_a, i) != _kind(ok_a[1], psi_a, 1) \
                or _kind(ok_b[i], psi_b, i) != _kind(ok_b[1], psi_b, 1):
            return False
    for k in range(psi_a.shape[1]):
        for psi in (psi_a, psi_b):
            v0, v1, v2 = psi[0, k], psi[1, k], psi[2, k]
            w0 = 9.0 if v0 != v0 else v0
            w1 = 9.0 if v1 != v1 else v1
            w2 = 9.0 if v2 != v2 else v2
            if w0 != w1 or w1 != w2:
                return False
    if not _affine3(top[0], top[1], top[2], atol) \
            or not _affine3(bottom[0], bottom[1], bottom[2], atol):
        return False
    for k in range(lat_a.shape[1]):
        for j in range(2):
            if not _affine3(lat_a[0, k, j], lat_a[1, k, j], lat_a[2, k, j], atol) \
                    or not _affine3(lat_b[0, k, j], lat_b[1, k, j], lat_b[2, k, j], atol):
                return False
    return True


def _affine3(v0: float, v1: float, v2: float, atol: float) -> bool:
    """Finite at all three points or at none, and (non-finite taken as 0) the middle
    within ``atol`` of the ends' mean."""
    f0, f1, f2 = math.isfinite(v0), math.isfinite(v1), math.isfinite(v2)
    if f0 != f1 or f1 != f2:
        return False
    z0 = v0 if f0 else 0.0
    z1 = v1 if f1 else 0.0
    z2 = v2 if f2 else 0.0
    return abs(z1 - (z0 + z2) / 2) <= atol


def slices(cell_t: Any, cell_lo: Any, cell_hi: Any, th: Any, a: Any, b: Any, f: Any,
           half: float, tol: float, q: Any, stroke: tuple[float, float], beta: float,
           round_tol: float, slice_tol: float, tiny: float, atol: float, near: float,
           stop_gap: float = 0.0, failed: Any = None, upward: bool = False,
           prune: bool = True) -> Any:
    """The holding pieces of the cells (``_slices.holding_offsets``; sorted by angle),
    compiled: rows ``(angle index, lo, hi)``; None when the loop cannot run.
    ``stop_gap`` > 0: an angle is given up at its first piece longer than that which does
    not hold (``failed``, a boolean array over the angles, set there), each angle read
    from its lowest offset up with ``upward`` (else from the highest down)."""
    internal = q is not None
    if failed is None:
        failed = np.zeros(len(th), dtype=np.bool_)
    qq = np.zeros(2) if q is None else np.ascontiguousarray(q, dtype=float)
    out: list[Any] = []
    if not _run("_slices_loop",
                np.ascontiguousarray(cell_t, dtype=np.int64),
                np.ascontiguousarray(cell_lo, dtype=float),
                np.ascontiguousarray(cell_hi, dtype=float),
                np.ascontiguousarray(th, dtype=float), np.ascontiguousarray(a, dtype=float),
                np.ascontiguousarray(b, dtype=float), np.ascontiguousarray(f, dtype=float),
                float(half), float(tol), internal, qq, float(stroke[0]), float(stroke[1]),
                float(beta), -1.0 if internal else 1.0, float(round_tol), float(slice_tol),
                float(tiny), float(atol), float(near), float(stop_gap), failed,
                bool(upward), bool(prune) and not internal, answer=out):
        return None
    return out[0]


# ----------------------------------------------------------------------------- loading

#: The loops called per pose, per edge or per cell that allocate nothing and make no
#: view: compiled without reference counts (:func:`~fcgrasp.core.kernels.njit_all`).
_BORROWING = (_features, _pad_loop, _outer_pads, _hole_sides, _inside_ring, _pose_at,
              _pose_one, _sin_range, _range, _wrap_positive, _vrange, _nan_min, _nan_max,
              _below, _arc_holds, _kind, _affine3, _affine, _quantities, _kink, _stop_reach)

_LOOPS = CompiledLoops(globals(), (
    *_BORROWING, _poses_loop, _grid_loop, _box_loop, _polar, _candidates, _tables,
    _prove_box, _prove_loop, _certify_loop, _cell, _slices_loop), borrowing=_BORROWING)


def _run(name: str, *args: Any, answer: list[Any] | None = None) -> bool:
    """Run the compiled loop ``name`` (:meth:`CompiledLoops.run`; its return value
    appended to ``answer``): False when it cannot run (numpy then)."""
    ok, got = _LOOPS.run(name, *args)
    if ok and answer is not None:
        answer.append(got)
    return ok


def available() -> bool:
    """Are the jaw's poses evaluated compiled here?  Always, but with ``FCGRASP_JIT=0``
    or without a working numba (then by the numpy model)."""
    return _LOOPS.available()


def certify(boxes: Any, a: Any, b: Any, nrm: Any, uniq: Any, inv: Any, half: float,
            zero: float, contact_tol: float, tol: float, q: Any, beta: float,
            stroke: tuple[float, float], max_boxes: int, radius: float, near: float,
            round_tol: float) -> tuple[bool, float, float, int] | None:
    """``_certify.certify_box``'s subdivision from the boxes ``boxes`` (B, 4), compiled
    (:func:`_certify_loop`): ``(proved, lo, hi, boxes examined)``; None when the loop
    cannot run."""
    out = np.zeros(4)
    if not _run("_certify_loop", *_proof_args(boxes, a, b, nrm, uniq, inv, half, zero,
                                              contact_tol, tol, q, beta, stroke),
                int(max_boxes), float(radius), float(near), float(round_tol), out):
        return None
    return bool(out[0]), float(out[1]), float(out[2]), int(out[3])
