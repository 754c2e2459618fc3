"""Compiled loops of the two-finger stretch search for large rings (issue 30; part of
:mod:`fcgrasp.model.stretches`).

The numpy search of :mod:`fcgrasp.model._stretch_windows` holds the vertex matrix ``M``
as ``m_a x m_b`` booleans and widens every window of rows at once; on a 10,000-edge
outline that is 10^8 cells per mode and hundreds of passes over every row's runs.  These
loops do the same work row by row, with nothing of size ``m_a x m_b`` in memory:

* :func:`vertex_runs` scans each row of ``M`` once for both modes (squeeze ``M+`` and
  expand ``M-``: the expand test of a cell is the squeeze test with the chord reversed,
  so the same eight cross products, with the opposite sign) and keeps its runs of True
  (the evaluation is the numpy one's, operation for operation, so the cells agree bit
  for bit);
* :func:`windows` widens one row's window of interior vertices at a time, intersecting
  its runs with the next row's (two monotone pointers over two sorted lists of runs),
  and stops as soon as no run is long enough to reach the bound: the lower bound of
  each first row (its vertex-aligned stretches), or the configurations whose bound
  reaches the floor, enumerated only over the start vertices that can reach it.

numba is imported on first use (the machine code cached on disk beside this file); the
search uses these loops only on rings large enough to repay it
(:data:`fcgrasp.model.stretches.KERNEL_CELLS`), and ``FCGRASP_JIT=0`` never does.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core.kernels import CompiledLoops
from ..core.tolerances import ROUND_TOL


def _grow(a: Any, n: int) -> Any:
    """``a`` with room for at least ``n`` elements (doubling)."""
    if n <= a.size:
        return a
    out = np.empty(max(n, 2 * a.size), a.dtype)
    out[:a.size] = a
    return out


def _append(first: Any, last: Any, n: int, a: int, b: int) -> Any:
    first, last = _grow(first, n + 1), _grow(last, n + 1)
    first[n], last[n] = a, b
    return first, last


def _in_order(c: Any, mark: Any) -> Any:
    """The distinct column numbers ``c`` in increasing order: by marking them when they
    span little more than their number (a smooth outline's), else by sorting."""
    if c.size == 0:
        return c
    lo, hi = c.min(), c.max()
    if hi - lo > 8 * c.size:
        return np.sort(c)
    for w in c:
        mark[w] = True
    out = np.empty(c.size, np.int64)
    n = 0
    for w in range(lo, hi + 1):
        if mark[w]:
            out[n] = w
            n += 1
            mark[w] = False
    return out[:n]


def _vertex_runs(ax: Any, ay: Any, gx: Any, va: Any, bx: Any, by: Any, gy: Any, order: Any,
                 angle_b: Any, width: float) -> Any:
    """Runs of True of every row of ``M+`` (squeeze) and ``M-`` (expand): for each mode,
    the row pointers and the first and last column of each run.

    Only the columns a cell can hold are read: both modes need the two edges' force
    directions opposite within twice the cone's half-angle, so row ``v`` reads the
    columns whose angle ``angle_b`` is within ``width`` of ``va[v]`` (the opposite of
    its force direction's angle; NaN: a vertex whose two normals turn by more than
    that, which holds with nothing).  Ring b's arrays come sorted by that angle (so
    the window is read in order), ``order`` maps them back to columns."""
    ma, mb = ax.size, bx.size
    ptr_p, ptr_m = np.zeros(ma + 1, np.int64), np.zeros(ma + 1, np.int64)
    fp, lp = np.empty(4 * ma + 16, np.int64), np.empty(4 * ma + 16, np.int64)
    fm, lm = np.empty(4 * ma + 16, np.int64), np.empty(4 * ma + 16, np.int64)
    np_, nm = 0, 0
    cols_p, cols_m = np.empty(mb, np.int64), np.empty(mb, np.int64)
    mark = np.zeros(mb, np.bool_)
    for v in range(ma):
        cp, cm = 0, 0
        if not np.isnan(va[v]):
            for turn in range(-1, 2):           # the window, wrapped around +-pi
                lo, hi = 0, mb
                if width >= np.pi:              # every column, once
                    if turn != 0:
                        continue
                else:
                    lo = np.searchsorted(angle_b, va[v] + 2 * np.pi * turn - width,
                                         side="left")
                    hi = np.searchsorted(angle_b, va[v] + 2 * np.pi * turn + width,
                                         side="right")
                for q in range(lo, hi):
                    # the eight cross products cross(g, d), without a branch: M+ holds
                    # where all are >= 0, M- where all are <= 0 (the chord reversed)
                    d0, d1 = bx[q] - ax[v], by[q] - ay[v]
                    lo_c, hi_c = np.inf, -np.inf
                    for j in range(4):
                        c = gx[v, j, 0] * d1 - gx[v, j, 1] * d0
                        lo_c, hi_c = min(lo_c, c), max(hi_c, c)
                        c = gy[q, j, 0] * d1 - gy[q, j, 1] * d0
                        lo_c, hi_c = min(lo_c, c), max(hi_c, c)
                    moved = (d0 != 0.0) | (d1 != 0.0)
                    cols_p[cp] = order[q]
                    cp += moved & (lo_c >= 0.0)
                    cols_m[cm] = order[q]
                    cm += moved & (hi_c <= 0.0)
        for s in range(2):
            c = _in_order(cols_p[:cp] if s == 0 else cols_m[:cm], mark)
            j = 0
            while j < c.size:
                e = j
                while e + 1 < c.size and c[e + 1] == c[e] + 1:
                    e += 1
                if s == 0:
                    fp, lp = _append(fp, lp, np_, c[j], c[e])
                    np_ += 1
                else:
                    fm, lm = _append(fm, lm, nm, c[j], c[e])
                    nm += 1
                j = e + 1
        ptr_p[v + 1], ptr_m[v + 1] = np_, nm
    return ptr_p, fp[:np_], lp[:np_], ptr_m, fm[:nm], lm[:nm]


def _windows(ptr: Any, first: Any, last: Any, Ua: Any, Ub: Any, ma: int, mb: int,
             floor: float, collect: bool, same: bool) -> Any:
    """Windows of interior vertices of both stretches (``_windows_both`` of the numpy
    search, row by row).

    Without ``collect``: for each first row ``r`` (stretch 1 from vertex ``r``), the
    largest smallest region of the vertex-aligned stretch pairs it starts (its lower
    bound; 0 if none exceeds ``floor``; on one ring only pairs whose stretch 2 starts
    after ``r``, so that each unordered pair is counted by one row).  With ``collect``:
    every configuration ``(iA, kA, iC, kC)`` whose arc bound reaches ``floor``."""
    best = np.zeros(ma)
    cap = 1024
    oA, okA = np.empty(cap, np.int64), np.empty(cap, np.int64)
    oC, okC = np.empty(cap, np.int64), np.empty(cap, np.int64)
    n_out = 0
    cs = np.empty(mb + 1, np.int64)
    ce = np.empty(mb + 1, np.int64)
    ns = np.empty(mb + 1, np.int64)
    ne = np.empty(mb + 1, np.int64)
    rp0 = np.empty(mb + 1, np.int64)
    rlen = np.empty(mb + 1, np.int64)
    for r in range(ma):
        nc = 0
        for q in range(ptr[r], ptr[r + 1]):
            cs[nc], ce[nc] = first[q], last[q]
            nc += 1
        i = (r - 1) % ma + ma
        k = 1
        while k < ma - 1 and nc > 0:
            ext_s = Ua[i + k + 1] - Ua[i]
            inner_s = Ua[i + k] - Ua[i + 1]
            # the current window's cyclic runs: a run through the last column goes on
            # into the first
            nr = 0
            if nc == 1 and cs[0] == 0 and ce[0] == mb - 1:
                rp0[0], rlen[0] = 0, mb
                nr = 1
            else:
                wrap = nc > 1 and cs[0] == 0 and ce[nc - 1] == mb - 1
                for j in range(1 if wrap else 0, nc):
                    rp0[nr], rlen[nr] = cs[j], ce[j] - cs[j] + 1
                    if wrap and j == nc - 1:
                        rlen[nr] += ce[0] + 1
                    nr += 1
            # the most any stretch 2 inside these runs reaches (its edges), and the
            # longest vertex-aligned one (its interior vertices): runs only shrink as
            # the window grows, so neither grows with k
            reach, vert = 0.0, 0.0
            for j in range(nr):
                jb = (rp0[j] - 1) % mb + mb
                reach = max(reach, Ub[jb + min(rlen[j], mb - 1) + 1] - Ub[jb])
                vert = max(vert, Ub[jb + min(rlen[j], mb - 2)] - Ub[jb + 1])
            if collect:
                # a configuration's stretch 2 reaches the floor and stretch 1's interior
                # (inner_s, growing with k): stop when no run can
                if reach < max(floor, inner_s) * (1 - ROUND_TOL):
                    break
            elif reach < floor * (1 - ROUND_TOL) or vert <= best[r]:
                break                   # no later lower bound can beat this row's
            for j in range(nr):
                rr = min(rlen[j], mb - 2)
                if rr < 1:
                    continue
                jb = (rp0[j] - 1) % mb + mb
                vert_u = Ub[jb + rr] - Ub[jb + 1]
                if not collect:
                    if not same or rp0[j] % mb > r:
                        best[r] = max(best[r], min(inner_s, vert_u))
                    continue
                if ext_s < floor:
                    continue
                need = max(floor, inner_s)
                run_end0 = (rp0[j] + rlen[j] - 1) % mb + mb
                for jj in range(rlen[j]):
                    p = (rp0[j] + jj) % mb + mb
                    run_end = run_end0 if run_end0 >= p else run_end0 + mb
                    run_end = min(run_end, p + mb - 3)
                    # stretch 2 from edge p - 1 reaches at most the edges up to run_end,
                    # less with every later p (unless the run is nearly the whole ring)
                    if Ub[run_end + 1] < Ub[p - 1] + need:
                        if rlen[j] <= mb - 2:
                            break
                        continue
                    q_hi = np.searchsorted(Ub, Ub[p] + ext_s, side="right") - 1
                    q_lo = np.searchsorted(Ub, Ub[p - 1] + need, side="left") - 1
                    q_lo = max(q_lo, p)
                    q_hi = min(q_hi, run_end)
                    if q_hi < q_lo:
                        continue
                    n_new = n_out + q_hi - q_lo + 1
                    oA, okA = _grow(oA, n_new), _grow(okA, n_new)
                    oC, okC = _grow(oC, n_new), _grow(okC, n_new)
                    for q in range(q_lo, q_hi + 1):
                        oA[n_out], okA[n_out] = r - 1, k
                        oC[n_out], okC[n_out] = p - 1, q - p + 1
                        n_out += 1
            # the window grows by row r + k: intersect the runs
            row = (r + k) % ma
            a, b, n2 = 0, ptr[row], 0
            while a < nc and b < ptr[row + 1]:
                lo = max(cs[a], first[b])
                hi = min(ce[a], last[b])
                if lo <= hi:
                    ns[n2], ne[n2] = lo, hi
                    n2 += 1
                if ce[a] < last[b]:
                    a += 1
                else:
                    b += 1
            for j in range(n2):
                cs[j], ce[j] = ns[j], ne[j]
            nc = n2
            k += 1
    return best, oA[:n_out], okA[:n_out], oC[:n_out], okC[:n_out]


def _interval(ax: Any, ay: Any, tx: Any, ty: Any, L: Any, gx: Any, bx: Any, by: Any,
              gy: Any, sigma: float, eps: float, e: int, w: int) -> Any:
    """The positions on edge ``e`` (ring a) that hold against vertex ``w`` (ring b)
    with both its normals: ``_Intervals.cells`` of one cell, the same operations
    (empty where the first exceeds the second)."""
    d00, d01 = sigma * (bx[w] - ax[e]), sigma * (by[w] - ay[e])
    d10, d11 = -sigma * tx[e], -sigma * ty[e]
    a, b = 0.0, L[e]
    for j in range(6):
        if j < 2:
            g0, g1 = gx[e, j, 0], gx[e, j, 1]
        else:
            g0, g1 = gy[w, j - 2, 0], gy[w, j - 2, 1]
        c0 = g0 * d01 - g1 * d00
        c1 = g0 * d11 - g1 * d10
        r = -c0 / c1
        if c1 > eps:
            a = max(a, r)
        if c1 < -eps:
            b = min(b, r)
        if abs(c1) <= eps and c0 < 0:
            b = -np.inf
    return a, b


def _window_boxes(edge: Any, start: Any, count: Any, ax: Any, ay: Any, tx: Any, ty: Any,
                  L: Any, gx: Any, bx: Any, by: Any, gy: Any, sigma: float, eps: float
                  ) -> Any:
    """``_Intervals.window``: for each edge, the intersection of its intervals against
    vertices ``start .. start + count - 1`` (cyclic); ``(0, inf)`` when ``count`` is 0."""
    n, mb = edge.size, bx.size
    lo, hi = np.zeros(n), np.full(n, np.inf)
    for i in range(n):
        if count[i] <= 0:
            continue
        a_max, b_min = -np.inf, np.inf
        for k in range(count[i]):
            a, b = _interval(ax, ay, tx, ty, L, gx, bx, by, gy, sigma, eps, edge[i],
                             (start[i] + k) % mb)
            a_max, b_min = max(a_max, a), min(b_min, b)
        lo[i], hi[i] = a_max, b_min
    return lo, hi


def _single(A: Any, ax: Any, ay: Any, tx: Any, ty: Any, L: Any, gx: Any, va: Any,
            bx: Any, by: Any, gy: Any, order: Any, angle_b: Any, width: float, Ub: Any,
            sigma: float, eps: float, floor: float, collect: bool, same: bool) -> Any:
    """Stretch 1 on one edge ``A``, stretch 2 with interior vertices ``p .. p+k-1``
    (``_windows_single`` of the numpy search, edge by edge).

    The interval of edge ``A`` against a vertex (the contacts on ``A`` that hold with
    both its normals: ``_Intervals.cells``, the same operations) is empty unless the
    two force directions are opposite within ``width``, so only those vertices are
    computed (``va``, ``angle_b``, ``order``: as in :func:`_vertex_runs`; ``gy`` in ring
    order here).  Returns the lower bounds ``(A, p, value)`` (the largest over ``k``)
    and, with ``collect``, the configurations whose bound reaches ``floor``."""
    mb = bx.size
    lo = np.full(mb, 0.0)
    hi = np.full(mb, -np.inf)
    touched = np.empty(mb, np.int64)
    cap = 1024
    wa, wp, wv = np.empty(cap, np.int64), np.empty(cap, np.int64), np.empty(cap)
    oA, oC, okC = np.empty(cap, np.int64), np.empty(cap, np.int64), np.empty(cap, np.int64)
    n_w, n_out = 0, 0
    for e in A:
        nt = 0
        for turn in range(-1, 2):
            qlo, qhi = 0, mb
            if width >= np.pi:
                if turn != 0:
                    continue
            else:
                qlo = np.searchsorted(angle_b, va[e] + 2 * np.pi * turn - width, side="left")
                qhi = np.searchsorted(angle_b, va[e] + 2 * np.pi * turn + width, side="right")
            for q in range(qlo, qhi):
                w = order[q]
                a, b = _interval(ax, ay, tx, ty, L, gx, bx, by, gy, sigma, eps, e, w)
                lo[w], hi[w] = a, b
                touched[nt] = w
                nt += 1
        for jp in range(nt):
            p = touched[jp]
            if not hi[p] - lo[p] >= floor:
                continue
            cl, ch = lo[p], hi[p]
            best = 0.0
            k = 1
            while k < mb - 1:
                room = ch - cl
                if not room >= floor:
                    break
                i = (p - 1) % mb + mb
                inner_u = Ub[i + k] - Ub[i + 1]
                ext_u = Ub[i + k + 1] - Ub[i]
                if not same or (p >= e + 2 and p + k - 1 < mb + e):
                    best = max(best, min(room, inner_u))
                if collect and ext_u >= floor and room >= inner_u:
                    oA, oC = _grow(oA, n_out + 1), _grow(oC, n_out + 1)
                    okC = _grow(okC, n_out + 1)
                    oA[n_out], oC[n_out], okC[n_out] = e, p - 1, k
                    n_out += 1
                w = (p + k) % mb
                cl, ch = max(cl, lo[w]), min(ch, hi[w])
                k += 1
            if best > 0:
                wa, wp = _grow(wa, n_w + 1), _grow(wp, n_w + 1)
                wv = _grow(wv, n_w + 1)
                wa[n_w], wp[n_w], wv[n_w] = e, p, best
                n_w += 1
        for j in range(nt):                 # the columns back to empty
            lo[touched[j]], hi[touched[j]] = 0.0, -np.inf
    return wa[:n_w], wp[:n_w], wv[:n_w], oA[:n_out], oC[:n_out], okC[:n_out]


def _solve_rows(rows: Any, ub: Any, tol: float, eps: float) -> Any:
    """``_stretch_lp._solve`` one configuration at a time: the same Fourier-Motzkin
    elimination of ``s0`` (every row with a positive coefficient added to every row with
    a negative one, each divided by its coefficient's magnitude), the same bounds of
    ``t`` from every pair of the rows left, the same read-back of ``u0`` and ``s0``
    (the middle of their intervals), operation for operation: no ``B x R^2 x R^2``
    array, and the rows of a configuration stay in cache."""
    B, R, _ = rows.shape
    t_out, s_out, u_out = np.empty(B), np.empty(B), np.empty(B)
    rr = np.empty((R + 1, 4))
    el = np.empty(((R + 1) * (R + 1) + R + 1, 3))
    for b in range(B):
        for i in range(R):
            for j in range(4):
                rr[i, j] = rows[b, i, j]
        rr[R, 0], rr[R, 1], rr[R, 2], rr[R, 3] = ub[b], 0.0, 0.0, -1.0
        m = 0
        for i in range(R + 1):          # rows with a positive coefficient of s0 ...
            ai = rr[i, 1]
            if not ai > eps:
                continue
            for j in range(R + 1):      # ... plus rows with a negative one
                aj = rr[j, 1]
                if not aj < -eps:
                    continue
                el[m, 0] = rr[i, 0] / abs(ai) + rr[j, 0] / abs(aj)
                el[m, 1] = rr[i, 2] / abs(ai) + rr[j, 2] / abs(aj)
                el[m, 2] = rr[i, 3] / abs(ai) + rr[j, 3] / abs(aj)
                m += 1
        for i in range(R + 1):
            if not (rr[i, 1] > eps or rr[i, 1] < -eps):
                el[m, 0], el[m, 1], el[m, 2] = rr[i, 0], rr[i, 2], rr[i, 3]
                m += 1
        hi, lo, flat = np.inf, -np.inf, np.inf
        for p in range(m):
            cp = el[p, 1]
            if cp > eps:
                al_p, ga_p = -el[p, 0] / cp, -el[p, 2] / cp
                for q in range(m):
                    cq = el[q, 1]
                    if cq < -eps:
                        al_q, ga_q = -el[q, 0] / cq, -el[q, 2] / cq
                        d = ga_p - ga_q
                        e = al_q - al_p
                        if d > eps:
                            hi = min(hi, e / d)
                        elif d < -eps:
                            lo = max(lo, e / d)
                        else:
                            flat = min(flat, e)
            elif not cp < -eps:
                c0, ct = el[p, 0], el[p, 2]
                if ct < -eps:
                    hi = min(hi, -c0 / ct)
                elif ct > eps:
                    lo = max(lo, -c0 / ct)
                else:
                    flat = min(flat, c0)
        ok = lo <= hi + tol and flat >= -tol and hi >= 0 and np.isfinite(hi)
        t = max(hi, 0.0) if ok else -1.0
        tt = max(t, 0.0)
        u0 = 0.0
        if ok:
            ulo, uhi = -np.inf, np.inf
            for p in range(m):
                c1 = el[p, 1]
                c0 = el[p, 0] + el[p, 2] * tt
                if c1 > eps:
                    ulo = max(ulo, -c0 / c1)
                elif c1 < -eps:
                    uhi = min(uhi, -c0 / c1)
            u0 = 0.5 * (ulo + uhi)
        s0 = 0.0
        if ok:
            slo, shi = -np.inf, np.inf
            for i in range(R + 1):
                c1 = rr[i, 1]
                c0 = rr[i, 0] + rr[i, 2] * u0 + rr[i, 3] * tt
                if c1 > eps:
                    slo = max(slo, -c0 / c1)
                elif c1 < -eps:
                    shi = min(shi, -c0 / c1)
            s0 = 0.5 * (slo + shi)
        t_out[b], s_out[b], u_out[b] = t, s0, u0
    return t_out, s_out, u_out


def _scan_inside(order: Any, starts: Any, next_start: Any, lo: int, span: int, m: int,
                 iA: Any, kA: Any, iC: Any, kC: Any, lo2: int, span2: int, m2: int, t: Any,
                 thr: float) -> bool:
    """Is some configuration ``u`` whose first stretch starts in the cyclic range
    ``[lo, lo + span]`` of a ring of ``m`` (``order``: the configurations by start, then
    by smallest region, longest first; ``starts`` their starts sorted; ``next_start[q]``
    where the next start begins) inside it (``(iA - lo) % m + kA <= span``), its second
    stretch inside ``[lo2, lo2 + span2]`` of a ring of ``m2``, and ``t[u] > thr``?  Each
    start's configurations are read only while their smallest region passes ``thr``."""
    F = order.shape[0]
    for part in range(2):
        if part == 0:
            a = int(np.searchsorted(starts, lo, side="left"))
            b = int(np.searchsorted(starts, min(lo + span, m - 1), side="right"))
        else:
            if lo + span < m:
                break
            a = 0
            b = min(int(np.searchsorted(starts, lo + span - m, side="right")), F)
        q = a
        while q < b:
            u = order[q]
            if t[u] <= thr:             # the rest of this start's are shorter still
                q = next_start[q]
                continue
            if (iA[u] - lo) % m + kA[u] <= span and (iC[u] - lo2) % m2 + kC[u] <= span2:
                return True
            q += 1
    return False


def _beaten(iA: Any, kA: Any, iC: Any, kC: Any, t: Any, ma: int, mb: int, same: bool,
            tie: float, order: Any, keep: Any) -> None:
    """:func:`fcgrasp.model.stretches._own_optimum` of one job, without its matrix of
    every (sub, super) pair: ``keep[s]`` False where a configuration inside ``s`` (on
    both rings; on one ring, either way round) has a smallest region longer than
    ``t[s] (1 + tie)``.  Candidates are read from the configurations sorted by the
    start of their first stretch (a range of starts per ``s``), each start's longest
    first (``order``), and only those longer than ``s``'s."""
    starts = iA[order]
    F = order.shape[0]
    next_start = np.empty(F, np.int64)
    q = F
    for r in range(F - 1, -1, -1):
        if r == F - 1 or starts[r] != starts[r + 1]:
            q = r + 1
        next_start[r] = q
    for s in range(t.shape[0]):
        thr = t[s] * (1 + tie)
        if _scan_inside(order, starts, next_start, iA[s], kA[s], ma, iA, kA, iC, kC, iC[s],
                        kC[s], mb, t, thr):
            keep[s] = False
        elif same and _scan_inside(order, starts, next_start, iC[s], kC[s], ma, iA, kA, iC,
                                   kC, iA[s], kA[s], ma, t, thr):
            keep[s] = False


def _group_tables(iA: Any, kA: Any, iC: Any, kC: Any, t: Any, ma: int, mb: int) -> Any:
    """The configurations grouped by their two start edges ``(iA, iC)`` (groups with
    ``iA = p`` are ``ptr[p] .. ptr[p + 1]``, by ``iC``), each with a table over its
    ``(kA, kC)`` of the largest ``t`` at most that long on both sides (a prefix
    maximum): ``(ptr, g_iC, ka0, ka1, kc0, kc1, off, table)``; ``table`` is None-sized
    (empty) and ``off[-1]`` its would-be size when that passes :data:`TABLE_CELLS`."""
    F = iA.shape[0]
    key = iA * mb + iC
    order = np.argsort(key, kind="mergesort")
    G = 0
    for r in range(F):
        if r == 0 or key[order[r]] != key[order[r - 1]]:
            G += 1
    g_iA = np.empty(G, np.int64)
    g_iC = np.empty(G, np.int64)
    ka0 = np.empty(G, np.int64)
    ka1 = np.empty(G, np.int64)
    kc0 = np.empty(G, np.int64)
    kc1 = np.empty(G, np.int64)
    gid = np.empty(F, np.int64)
    g = -1
    for r in range(F):
        u = order[r]
        if r == 0 or key[u] != key[order[r - 1]]:
            g += 1
            g_iA[g], g_iC[g] = iA[u], iC[u]
            ka0[g], ka1[g], kc0[g], kc1[g] = kA[u], kA[u], kC[u], kC[u]
        gid[u] = g
        ka0[g] = min(ka0[g], kA[u])
        ka1[g] = max(ka1[g], kA[u])
        kc0[g] = min(kc0[g], kC[u])
        kc1[g] = max(kc1[g], kC[u])
    off = np.empty(G + 1, np.int64)
    off[0] = 0
    for g in range(G):
        off[g + 1] = off[g] + (ka1[g] - ka0[g] + 1) * (kc1[g] - kc0[g] + 1)
    ptr = np.zeros(ma + 1, np.int64)
    for g in range(G):
        ptr[g_iA[g] + 1] += 1
    for p in range(ma):
        ptr[p + 1] += ptr[p]
    if off[G] > TABLE_CELLS:
        return ptr, g_iC, ka0, ka1, kc0, kc1, off, np.empty(0)
    table = np.full(off[G], -np.inf)
    for u in range(F):
        g = gid[u]
        cols = kc1[g] - kc0[g] + 1
        at = off[g] + (kA[u] - ka0[g]) * cols + (kC[u] - kc0[g])
        table[at] = max(table[at], t[u])
    for g in range(G):                    # prefix maxima along kA, then along kC
        rows, cols = ka1[g] - ka0[g] + 1, kc1[g] - kc0[g] + 1
        for a in range(1, rows):
            for c in range(cols):
                at = off[g] + a * cols + c
                table[at] = max(table[at], table[at - cols])
        for a in range(rows):
            for c in range(1, cols):
                at = off[g] + a * cols + c
                table[at] = max(table[at], table[at - 1])
    return ptr, g_iC, ka0, ka1, kc0, kc1, off, table


def _any_inside(ptr: Any, g_iC: Any, ka0: Any, ka1: Any, kc0: Any, kc1: Any, off: Any,
                table: Any, lo: int, span: int, ma: int, lo2: int, span2: int, mb: int,
                thr: float) -> bool:
    """Is some configuration with its first stretch inside ``[lo, lo + span]`` (a ring
    of ``ma``, cyclically), its second inside ``[lo2, lo2 + span2]`` (of ``mb``) and a
    smallest region above ``thr``?  One look-up in the table of each start pair."""
    for d in range(min(span, ma - 1) + 1):
        p = (lo + d) % ma
        g0, g1 = ptr[p], ptr[p + 1]
        if g0 == g1:
            continue
        KA = span - d
        for part in range(2):
            if span2 >= mb - 1:
                if part == 1:
                    break
                qa, qb = 0, mb - 1
            elif lo2 + span2 < mb:
                if part == 1:
                    break
                qa, qb = lo2, lo2 + span2
            elif part == 0:
                qa, qb = lo2, mb - 1
            else:
                qa, qb = 0, lo2 + span2 - mb
            g = g0 + int(np.searchsorted(g_iC[g0:g1], qa))
            while g < g1 and g_iC[g] <= qb:
                KC = span2 - (g_iC[g] - lo2) % mb
                if KA >= ka0[g] and KC >= kc0[g]:
                    cols = kc1[g] - kc0[g] + 1
                    at = off[g] + (min(KA, ka1[g]) - ka0[g]) * cols + (min(KC, kc1[g]) - kc0[g])
                    if table[at] > thr:
                        return True
                g += 1
    return False


def _beaten_tables(iA: Any, kA: Any, iC: Any, kC: Any, t: Any, ma: int, mb: int,
                   same: bool, tie: float, keep: Any) -> bool:
    """:func:`_beaten` by table look-ups (:func:`_group_tables`): False, leaving
    ``keep`` as it is, when the tables would pass :data:`TABLE_CELLS`.  Starts are
    ring positions (``0 <= iA < ma``, ``0 <= iC < mb``)."""
    ptr, g_iC, ka0, ka1, kc0, kc1, off, table = _group_tables(iA, kA, iC, kC, t, ma, mb)
    if table.shape[0] != off[-1]:
        return False
    for s in range(t.shape[0]):
        thr = t[s] * (1 + tie)
        if _any_inside(ptr, g_iC, ka0, ka1, kc0, kc1, off, table, iA[s], kA[s], ma, iC[s],
                       kC[s], mb, thr):
            keep[s] = False
        elif same and _any_inside(ptr, g_iC, ka0, ka1, kc0, kc1, off, table, iC[s], kC[s],
                                  ma, iA[s], kA[s], mb, thr):
            keep[s] = False
    return True


#: Cells of the own-optimum filter's tables (:func:`_group_tables`) above which it
#: scans configurations by start instead (:func:`_beaten`).
TABLE_CELLS = 50_000_000


_LOOPS = CompiledLoops(globals(), (_grow, _append, _in_order, _vertex_runs, _windows,
                                   _interval, _window_boxes, _single, _solve_rows,
                                   _scan_inside, _beaten, _group_tables, _any_inside,
                                   _beaten_tables))


def _load() -> dict[str, Any]:
    """The loops compiled (once per process; :class:`fcgrasp.core.kernels.CompiledLoops`).
    The stretch search runs them only where :func:`~fcgrasp.model.stretches.stretch_kernels_for`
    says so, which needs numba."""
    loops = _LOOPS.get()
    if loops is None:
        raise ImportError("the stretch search's compiled loops need numba")
    return loops


def loaded() -> bool:
    """Whether this process has loaded the compiled loops (then they cost nothing more)."""
    return _LOOPS.loaded


def vertex_runs(ax: Any, ay: Any, gx: Any, va: Any, bx: Any, by: Any, gy: Any, order: Any,
                angle_b: Any, width: float) -> Any:
    """Compiled :func:`_vertex_runs`."""
    return _load()["_vertex_runs"](ax, ay, gx, va, bx, by, gy, order, angle_b, float(width))


def windows(ptr: Any, first: Any, last: Any, Ua: Any, Ub: Any, ma: int, mb: int,
            floor: float, collect: bool, same: bool) -> Any:
    """Compiled :func:`_windows` (index arrays made contiguous: one compiled signature
    for every caller)."""
    ptr, first, last = (np.ascontiguousarray(x, np.int64) for x in (ptr, first, last))
    return _load()["_windows"](ptr, first, last, Ua, Ub, ma, mb, float(floor), collect, same)


def single(*args: Any) -> Any:
    """Compiled :func:`_single`."""
    return _load()["_single"](*args)


def solve_rows(rows: Any, ub: Any, tol: float, eps: float) -> Any:
    """Compiled :func:`_solve_rows`."""
    return _load()["_solve_rows"](np.ascontiguousarray(rows, float), np.asarray(ub, float),
                                 float(tol), float(eps))


def window_boxes(*args: Any) -> Any:
    """Compiled :func:`_window_boxes`."""
    return _load()["_window_boxes"](*args)


def beaten(c: Any, t: Any, ma: int, mb: int, same: bool, tie: float) -> Any:
    """Compiled :func:`_beaten` of configurations ``c`` (F, 4: first start, its interior
    vertices, second start, its interior vertices) with smallest regions ``t``: the
    ones to keep."""
    c = np.array(c, np.int64)
    c[:, 0] %= ma                               # starts as ring positions
    c[:, 2] %= mb
    t = np.asarray(t, float)
    keep = np.ones(len(c), bool)
    cols = [np.ascontiguousarray(c[:, j]) for j in range(4)]
    if _load()["_beaten_tables"](*cols, t, int(ma), int(mb), bool(same), float(tie), keep):
        return keep
    order = np.lexsort((-t, c[:, 0]))           # by first start, then the longest first
    _load()["_beaten"](np.ascontiguousarray(c[:, 0]), np.ascontiguousarray(c[:, 1]),
                       np.ascontiguousarray(c[:, 2]), np.ascontiguousarray(c[:, 3]), t,
                       int(ma), int(mb), bool(same), float(tie), order.astype(np.int64),
                       keep)
    return keep
