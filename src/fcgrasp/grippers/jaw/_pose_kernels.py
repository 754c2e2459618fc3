"""Compiled loops of the parallel jaw: the pose model (:func:`_poses_loop`,
:func:`_grid_loop`: each pose's pads, the features they stop on and its verdict, with
the formulas of :mod:`._poses`) and the largest box of a pose grid (:func:`_box_loop`).

Plain Python compiled by :mod:`._kernels` (one namespace for every loop of the jaw, so
that compiled loops call compiled ones), whose wrappers the jaw calls; the numpy model
stays the reference."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

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
    nothing runs without reference counts, :func:`~fcgrasp.core.jit.njit_all`)."""
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
