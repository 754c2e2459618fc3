"""The knapsack solver of :mod:`fcgrasp.model.regions` compiled, one row at a time
(four fingers, or three with gravity, at interactive speed).

:func:`fcgrasp.model.regions.leximin` and :func:`~fcgrasp.model.regions.max_min_length`
solve definition 7.1's leximin order on batches of the knapsack form of theorem 7.1 with
numpy, a few dozen calls per stage on arrays of four columns: on the small batches of a
plan (tens of rows) the calls cost more than the arithmetic.  The loops below evaluate
the same expressions, row by row, in plain Python that numba compiles (the greedy order,
the greedy fill, the breakpoints of the slack ``D(t)`` and its root, the stage-by-stage
growth test); sums are taken in column order, so the two agree to rounding (tested to
1e-12 of the part against the numpy solver, which stays the reference and runs with
``FCGRASP_JIT=0``)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core._checks import BoolArray, FloatArray, IntArray
from ..core.jit import CompiledLoops
from ..core.tolerances import TINY


def _order_row(w1: FloatArray, w2: FloatArray, active: BoolArray, order: IntArray, key: FloatArray
               ) -> None:
    """The greedy order of knapsack 1 (largest ``w2 / w1`` first; ``w1 = 0``: first of
    all; inactive: last), stable: :func:`fcgrasp.model.regions._order`.  ``key`` (n,):
    scratch."""
    n = w1.shape[0]
    for i in range(n):
        if not active[i]:
            key[i] = math.inf                       # -(-inf)
        elif w1[i] > 0:
            key[i] = -(w2[i] / w1[i])
        else:
            key[i] = -math.inf
        order[i] = i
    for i in range(1, n):                           # insertion sort: stable
        j = i
        while j > 0 and key[order[j]] < key[order[j - 1]]:
            order[j], order[j - 1] = order[j - 1], order[j]
            j -= 1


def _fill_row(L: FloatArray, w1: FloatArray, w2: FloatArray, K1: float, active: BoolArray,
              lb: FloatArray, order: IntArray, x: FloatArray) -> tuple[float, float]:
    """Greedy fill of knapsack 1 from ``lb`` (into ``x``): the budget's slack at ``lb``
    and ``sum w2 x`` (:func:`fcgrasp.model.regions._fill`)."""
    n = L.shape[0]
    slack = K1
    for i in range(n):
        lbi = lb[i] if active[i] else 0.0
        x[i] = lbi
        slack -= w1[i] * lbi
    run = 0.0
    for j in range(n):
        i = order[j]
        Li = L[i] if active[i] else 0.0
        cap = Li - x[i]
        cost = w1[i] * cap
        run += cost
        room = slack - (run - cost)
        if room < 0.0:
            room = 0.0
        take = min(cap, room / w1[i]) if w1[i] > 0 else cap
        if take > 0.0:
            x[i] += take
    value = 0.0
    for i in range(n):
        value += w2[i] * x[i]
    return slack, value


def _wscale_row(L: FloatArray, w1: FloatArray, w2: FloatArray) -> float:
    s = 0.0
    for i in range(L.shape[0]):
        s += (w1[i] + w2[i]) * L[i]
    return max(s, TINY)


def _need_row(L: FloatArray, w2: FloatArray, K2: float, active: BoolArray, lb: FloatArray) -> float:
    """What knapsack 2 needs at lengths ``lb``: ``sum w2 (L + lb) - K2`` over the active
    regions."""
    need = 0.0
    for i in range(L.shape[0]):
        need += w2[i] * ((L[i] + lb[i]) if active[i] else 0.0)
    return need - K2


def _feasible_row(L: FloatArray, w1: FloatArray, w2: FloatArray, K1: float, K2: float,
                  active: BoolArray, lb: FloatArray, order: IntArray, eps: float, x: FloatArray
                  ) -> bool:
    """Is there a box of regions at least ``lb`` long (:func:`~.regions._feasible`)?"""
    n = L.shape[0]
    for i in range(n):
        if active[i] and not lb[i] <= L[i] + eps:
            return False
    slack, value = _fill_row(L, w1, w2, K1, active, lb, order, x)
    need = _need_row(L, w2, K2, active, lb)
    scale = eps * _wscale_row(L, w1, w2)
    return slack >= -scale and value >= need - scale


#: The rows of :func:`_max_level_row`'s scratch: the regions' lengths (0 where not
#: active), the fixed ones' levels, the free flags, then the fill's breakpoints ``t``
#: and ``D`` there, and both sorted by ``t``.
_LZ, _LB0, _FREE, _PTS, _D, _P, _Q = range(7)
_SCRATCH_ROWS = 7


def _max_level_row(L: FloatArray, w1: FloatArray, w2: FloatArray, K1: float, K2: float,
                   active: BoolArray, lbf: FloatArray, free: BoolArray, order: IntArray,
                   tol: float, x: FloatArray, lb: FloatArray, w: FloatArray, idx: IntArray
                   ) -> float:
    """The largest level ``t`` the free regions reach with the fixed ones at ``lbf``
    (-1: none): :func:`fcgrasp.model.regions._max_level`, the breakpoints of the greedy
    fill solved for and ``D`` interpolated on its linear piece.  Scratch, the caller's
    (a row allocates nothing, so it runs without reference counts): ``lb`` (n,), ``w``
    (:data:`_SCRATCH_ROWS`, n + 2), its rows :data:`_LZ` to :data:`_Q`; ``idx`` (n + 2,)
    ints."""
    n = L.shape[0]
    af = 0.0
    used = 0.0
    t_cap = math.inf
    for i in range(n):
        w[_LZ, i] = L[i] if active[i] else 0.0
        f = free[i] and active[i]
        w[_FREE, i] = 1.0 if f else 0.0
        w[_LB0, i] = 0.0 if f else (lbf[i] if active[i] else 0.0)
        af += w1[i] * w[_FREE, i]
        used += w1[i] * w[_LB0, i]
        if f and w[_LZ, i] < t_cap:
            t_cap = w[_LZ, i]
    r0 = K1 - used
    if af > 0 and r0 / af < t_cap:
        t_cap = r0 / af
    if not math.isfinite(t_cap):
        t_cap = 0.0
    c = 0.0
    for i in range(n):
        c += w2[i] * w[_LZ, i]
    c -= K2
    tolw = tol * _wscale_row(L, w1, w2)
    m = n + 2
    # the ends t = 0 and t = t_cap by the general fill
    d_end0 = d_end1 = 0.0
    for e in range(2):
        end = 0.0 if e == 0 else t_cap
        for i in range(n):
            lb[i] = w[_LB0, i] + end * w[_FREE, i]
        slack, value = _fill_row(L, w1, w2, K1, active, lb, order, x)
        d = value - _need_row(L, w2, K2, active, lb) if slack >= -tolw else -math.inf
        if e == 0:
            d_end0 = d
        else:
            d_end1 = d
    w[_PTS, 0], w[_D, 0] = 0.0, d_end0
    # the breakpoints, where the fill holds the items before j, full
    s0 = s1 = s0b = s1b = 0.0
    for j in range(n):
        i = order[j]
        cap0 = w[_LZ, i] - w[_LB0, i]
        tj = (r0 - s0) / (af - s1)
        if math.isfinite(tj) and tj > 0 and tj < t_cap:
            w[_PTS, j + 1] = tj
            w[_D, j + 1] = s0b - tj * s1b - c
        else:
            w[_PTS, j + 1] = math.inf
            w[_D, j + 1] = math.inf
        s0 += w1[i] * cap0
        s1 += w1[i] * w[_FREE, i]
        s0b += w2[i] * cap0
        s1b += w2[i] * w[_FREE, i]
    w[_PTS, m - 1], w[_D, m - 1] = t_cap, d_end1
    # sorted by t (stable), the invalid ones (inf) last with the value at t_cap
    for k in range(m):
        idx[k] = k
    for k in range(1, m):
        j = k
        while j > 0 and w[_PTS, idx[j]] < w[_PTS, idx[j - 1]]:
            idx[j], idx[j - 1] = idx[j - 1], idx[j]
            j -= 1
    for k in range(m):
        if math.isfinite(w[_PTS, idx[k]]):
            w[_P, k], w[_Q, k] = w[_PTS, idx[k]], w[_D, idx[k]]
        else:
            w[_P, k], w[_Q, k] = t_cap, d_end1
    if not (w[_Q, 0] >= -tolw and t_cap >= 0):
        return -1.0
    for i in range(n):
        if active[i] and not w[_LB0, i] <= w[_LZ, i] + tol * w[_LZ, i]:
            return -1.0
    last = m - 1
    for k in range(m - 1, -1, -1):
        if w[_Q, k] >= -tolw:
            last = k
            break
    nxt = min(last + 1, m - 1)
    d_a, d_b = w[_Q, last], w[_Q, nxt]
    frac = 0.0
    if nxt > last and math.isfinite(d_b) and d_a - d_b > 0:
        frac = min(max(d_a / (d_a - d_b), 0.0), 1.0)
    return float(w[_P, last] + frac * (w[_P, nxt] - w[_P, last]))


def _leximin_loop(L: FloatArray, w1: FloatArray, w2: FloatArray, K1: FloatArray, K2: FloatArray,
                  active: BoolArray, tol: float, step: float, first_only: bool, out: FloatArray
                  ) -> None:
    """Leximin levels of every row into ``out`` (B, n): -1 rows where none is
    possible (:func:`fcgrasp.model.regions.leximin`); ``first_only``: the first level
    alone, in ``out[:, 0]`` (:func:`~fcgrasp.model.regions.max_min_length`)."""
    B, n = L.shape
    order = np.empty(n, np.int64)
    free = np.empty(n, np.bool_)
    levels = np.empty(n)
    trial = np.empty(n)
    grow = np.empty(n, np.bool_)
    x = np.empty(n)
    key, lb, w = np.empty(n), np.empty(n), np.empty((_SCRATCH_ROWS, n + 2))
    idx = np.empty(n + 2, np.int64)
    for b in range(B):
        _order_row(w1[b], w2[b], active[b], order, key)
        for i in range(n):
            free[i] = active[b, i]
            levels[i] = 0.0
        if first_only:
            out[b, 0] = _max_level_row(L[b], w1[b], w2[b], K1[b], K2[b], active[b], levels,
                                       free, order, tol, x, lb, w, idx)
            continue
        dead = False
        first = True
        scale = TINY
        for i in range(n):
            scale = max(scale, L[b, i])
        for _ in range(n):
            anyfree = False
            for i in range(n):
                anyfree = anyfree or free[i]
            if not anyfree:
                break
            t = _max_level_row(L[b], w1[b], w2[b], K1[b], K2[b], active[b], levels, free,
                               order, tol, x, lb, w, idx)
            if first:
                dead = t < 0
                first = False
            t = max(t, 0.0)
            for i in range(n):
                if free[i]:
                    levels[i] = t
            # which free regions cannot grow beyond t while the others stay?
            blocked_any = False
            for i in range(n):
                for k in range(n):
                    trial[k] = levels[k]
                trial[i] += step * scale
                grow[i] = _feasible_row(L[b], w1[b], w2[b], K1[b], K2[b], active[b], trial,
                                        order, 0.1 * tol * scale, x)
                if free[i] and not grow[i]:
                    blocked_any = True
            for i in range(n):
                if free[i] and (not grow[i] or not blocked_any):
                    free[i] = False          # blocked (none: a numerical stall, all)
        for i in range(n):
            out[b, i] = -1.0 if dead else (levels[i] if active[b, i] else 0.0)


def _solve_small(G: FloatArray, h: FloatArray, x: FloatArray) -> float:
    """Gaussian elimination with partial pivoting of ``G x = h`` (n, n), in place
    (``G`` and ``h`` overwritten): the determinant, and ``x`` where it is not zero."""
    n = G.shape[0]
    det = 1.0
    for k in range(n):
        p = k
        for i in range(k + 1, n):
            if abs(G[i, k]) > abs(G[p, k]):
                p = i
        if G[p, k] == 0.0:
            return 0.0
        if p != k:
            det = -det
            for j in range(n):
                G[k, j], G[p, j] = G[p, j], G[k, j]
            h[k], h[p] = h[p], h[k]
        det *= G[k, k]
        for i in range(k + 1, n):
            f = G[i, k] / G[k, k]
            for j in range(k, n):
                G[i, j] -= f * G[k, j]
            h[i] -= f * h[k]
    for i in range(n - 1, -1, -1):
        v = h[i]
        for j in range(i + 1, n):
            v -= G[i, j] * x[j]
        x[i] = v / G[i, i]
    return det


def _centre_loop(L: FloatArray, w1: FloatArray, w2: FloatArray, K1: FloatArray, K2: FloatArray,
                 active: BoolArray, lb: FloatArray, subsets: IntArray, solver_tol: float,
                 face_tol: float, noise_det: float, sure_det: float, band: float, out: FloatArray,
                 found: BoolArray, sure: BoolArray) -> None:
    """:func:`fcgrasp.model.regions._centre` of every row into ``out`` (B, n), with
    ``found``, and whether the row is ``sure``: no subset's determinant between
    ``noise_det`` and ``sure_det`` of its scale (below: singular up to rounding, as
    numpy finds it too; above: far from the singular test's ``solver_tol``, and a
    vertex that rounding moves little), and no vertex's test within ``band`` of its
    tolerance, so that numpy's vertices are the same and the mean agrees to
    rounding.  ``subsets`` (S, n): the candidate active
    sets, in ``_centre``'s order."""
    B, n = L.shape
    m = 2 * n + 2
    # the constraint rows: x_m = lo_m, x_m = L_m (unit rows, the same for every row of
    # the batch), then w1 and w2 (the row's); each row's largest entry
    A = np.zeros((m, n))
    rowmax = np.ones(m)
    for i in range(n):
        A[i, i] = 1.0
        A[n + i, i] = 1.0
    rhs = np.empty(m)
    G = np.empty((n, n))
    h = np.empty(n)
    x = np.empty(n)
    acc = np.empty(n)
    lo = np.empty(n)
    Lz = np.empty(n)
    for b in range(B):
        ok_row = True
        r2 = 0.0
        big = TINY
        ws = 0.0
        for i in range(n):
            Lz[i] = L[b, i] if active[b, i] else 0.0
            lo[i] = lb[b, i] if active[b, i] else 0.0
            r2 += w2[b, i] * (Lz[i] + lo[i])
            big = max(big, Lz[i])
            ws += (w1[b, i] + w2[b, i]) * L[b, i]
        r2 -= K2[b]
        tol = face_tol * big
        wtol = face_tol * max(ws, TINY)
        rowmax[2 * n] = rowmax[2 * n + 1] = 0.0
        for i in range(n):
            A[2 * n, i] = w1[b, i]
            A[2 * n + 1, i] = w2[b, i]
            rowmax[2 * n] = max(rowmax[2 * n], abs(w1[b, i]))
            rowmax[2 * n + 1] = max(rowmax[2 * n + 1], abs(w2[b, i]))
            rhs[i], rhs[n + i] = lo[i], Lz[i]
        rhs[2 * n], rhs[2 * n + 1] = K1[b], r2
        cnt = 0
        for i in range(n):
            acc[i] = 0.0
        for s in range(subsets.shape[0]):
            v = 0.0
            for k in range(n):
                row = subsets[s, k]
                v = max(v, rowmax[row])
                for j in range(n):
                    G[k, j] = A[row, j]
                h[k] = rhs[row]
            scale = max(v ** n, TINY)
            det = _solve_small(G, h, x)
            if abs(det) > noise_det * scale and abs(det) <= sure_det * scale:
                ok_row = False              # near-singular: numpy's test or vertex may differ
            if abs(det) <= solver_tol * scale:
                continue
            feas = True
            d1 = 0.0
            d2 = 0.0
            for i in range(n):
                e_lo = x[i] - (lo[i] - tol)
                e_hi = (Lz[i] + tol) - x[i]
                if abs(e_lo) <= band * tol or abs(e_hi) <= band * tol:
                    ok_row = False
                if e_lo < 0 or e_hi < 0:
                    feas = False
                d1 += x[i] * w1[b, i]
                d2 += x[i] * w2[b, i]
            e1 = (K1[b] + wtol) - d1
            e2 = d2 - (r2 - wtol)
            if abs(e1) <= band * wtol or abs(e2) <= band * wtol:
                ok_row = False
            if e1 < 0 or e2 < 0:
                feas = False
            if feas:
                cnt += 1
                for i in range(n):
                    acc[i] += x[i]
        for i in range(n):
            v = acc[i] / max(cnt, 1)
            out[b, i] = min(max(v, lo[i]), Lz[i])
        found[b] = cnt > 0
        sure[b] = ok_row


#: The per-row helpers that allocate nothing and make no view: compiled without
#: reference counts (:func:`~fcgrasp.core.jit.njit_all`).
_BORROWING = (_order_row, _fill_row, _wscale_row, _need_row, _feasible_row, _max_level_row,
              _solve_small)

_LOOPS = CompiledLoops(globals(), (*_BORROWING, _leximin_loop, _centre_loop),
                       borrowing=_BORROWING)


def centre_rows(L: FloatArray, w1: FloatArray, w2: FloatArray, K1: Any, K2: Any, active: BoolArray,
                lb: FloatArray, subsets: IntArray, solver_tol: float, face_tol: float,
                noise_det: float, sure_det: float, band: float) -> tuple[Any, Any, Any] | None:
    """:func:`_centre_loop` on a batch: ``(centre, found, sure)``, None where it
    cannot run."""
    B, n = L.shape
    out, found, sure = np.zeros((B, n)), np.zeros(B, np.bool_), np.zeros(B, np.bool_)
    ok, _ = _LOOPS.run("_centre_loop", np.ascontiguousarray(L, float),
                       np.ascontiguousarray(w1, float), np.ascontiguousarray(w2, float),
                       np.ascontiguousarray(K1, float), np.ascontiguousarray(K2, float),
                       np.ascontiguousarray(active, np.bool_), np.ascontiguousarray(lb, float),
                       np.ascontiguousarray(subsets, np.int64), float(solver_tol),
                       float(face_tol), float(noise_det), float(sure_det), float(band),
                       out, found, sure)
    return (out, found, sure) if ok else None


def leximin_rows(L: FloatArray, w1: FloatArray, w2: FloatArray, K1: Any, K2: Any,
                 active: BoolArray, tol: float, step: float, first_only: bool) -> Any:
    """The compiled loop on a batch (None where it cannot run: numpy then)."""
    B, n = L.shape
    out = np.zeros((B, n))
    ok, _ = _LOOPS.run("_leximin_loop", np.ascontiguousarray(L, float),
                       np.ascontiguousarray(w1, float), np.ascontiguousarray(w2, float),
                       np.ascontiguousarray(K1, float), np.ascontiguousarray(K2, float),
                       np.ascontiguousarray(active, np.bool_), float(tol), float(step),
                       bool(first_only), out)
    return out if ok else None
