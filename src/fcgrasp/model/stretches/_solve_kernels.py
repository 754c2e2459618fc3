"""Compiled loops of the two-finger stretch search: the exact solve of one configuration
(:func:`_solve_rows`: Fourier-Motzkin elimination of ``s0``, with :func:`_below`'s proof
that it cannot reach a floor) and the own-optimum filter (:func:`_beaten`,
:func:`_beaten_tables`).

Plain Python compiled by :mod:`fcgrasp.model.stretches._kernels` (one namespace for every
loop of the search, so that compiled loops call compiled ones); the search calls them
through that module's wrappers."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...core._checks import BoolArray, FloatArray, IntArray

#: Cells of the own-optimum filter's tables (:func:`_group_tables`) above which it
#: scans configurations by start instead (:func:`_beaten`).
TABLE_CELLS = 50_000_000


#: Steps :func:`_below` takes at most along the lower bounds of ``t``.
_BELOW_STEPS = 16


def _below(el: FloatArray, m: int, floor: float, tol: float, eps: float) -> bool:
    """Whether the eliminated system's largest ``t`` is surely below ``floor`` (> 0), or
    the system has none, proved by bounds of ``t`` that the full pass of
    :func:`_solve_rows` also takes, each computed by the same operations (so its
    ``hi`` is at most the least upper bound found here and its ``lo`` at least the
    greatest lower bound): an upper bound below ``floor``, a lower bound above an upper
    one by more than ``tol``, or a flat bound below ``-tol``.

    The bounds come from the rows without ``u0`` and from pairs of rows bounding ``u0``
    from below and above: at ``t`` (first ``floor`` or the greatest lower bound found),
    the pair furthest apart; where it is apart and parted further as ``t`` grows, its
    crossing is a lower bound, from which the next step starts (the gap between the
    highest lower and lowest upper row is concave in ``t``: a cutting-plane walk up to
    the first ``t`` where ``u0`` may fit).  False (solve in full) where no proof comes
    within :data:`_BELOW_STEPS` steps; each step one pass over the rows, where the
    full pass reads every pair."""
    lo, hi = -np.inf, np.inf
    for p in range(m):                  # the rows without u0
        c1 = el[p, 1]
        if not (c1 > eps or c1 < -eps):
            c0, ct = el[p, 0], el[p, 2]
            if ct < -eps:
                hi = min(hi, -c0 / ct)
            elif ct > eps:
                lo = max(lo, -c0 / ct)
            elif c0 < -tol:
                return True
    if hi < floor or lo > hi + tol:
        return True
    t = max(floor, lo)
    for _ in range(_BELOW_STEPS):
        lo_v, hi_v = -np.inf, np.inf
        lo_p, hi_q = -1, -1
        for p in range(m):
            c1 = el[p, 1]
            if c1 > eps:
                v = -el[p, 0] / c1 + (-el[p, 2] / c1) * t
                if v > lo_v:
                    lo_v, lo_p = v, p
            elif c1 < -eps:
                v = -el[p, 0] / c1 + (-el[p, 2] / c1) * t
                if v < hi_v:
                    hi_v, hi_q = v, p
        if lo_p < 0 or hi_q < 0 or not lo_v > hi_v:
            return False                # u0 may fit at t
        cp, cq = el[lo_p, 1], el[hi_q, 1]
        d = -el[lo_p, 2] / cp - (-el[hi_q, 2] / cq)
        e = -el[hi_q, 0] / cq - (-el[lo_p, 0] / cp)
        if d > eps:
            hi = min(hi, e / d)
            return bool(hi < floor or lo > hi + tol)
        if not d < -eps:
            return bool(e < -tol)
        x = e / d
        if not x > t:
            return False                # no progress (rounding)
        lo = max(lo, x)
        if lo > hi + tol:
            return True
        t = lo
    return False


def _solve_rows(rows: FloatArray, ub: FloatArray, tol: float, eps: float, floor: float = 0.0
                ) -> Any:
    """``_lp._solve`` one configuration at a time: the same Fourier-Motzkin
    elimination of ``s0`` (every row with a positive coefficient added to every row with
    a negative one, each divided by its coefficient's magnitude), the same bounds of
    ``t`` from every pair of the rows left, the same read-back of ``u0`` and ``s0``
    (the middle of their intervals), operation for operation: no ``B x R^2 x R^2``
    array, and the rows of a configuration stay in cache.  With ``floor`` > 0, a
    configuration whose largest ``t`` is surely below it (:func:`_below`) gets NaN
    (not solved: it can neither reach a search's top nor beat a configuration that
    does)."""
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
        if floor > 0 and _below(el, m, floor, tol, eps):
            t_out[b], s_out[b], u_out[b] = np.nan, np.nan, np.nan
            continue
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


def _scan_inside(order: Any, starts: Any, next_start: IntArray, lo: int, span: int, m: int,
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
            tie: float, order: Any, keep: Any, check: Any) -> None:
    """:func:`fcgrasp.model.stretches._rounds._own_optimum` of one job, without its matrix of
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
        if not check[s]:
            continue
        thr = t[s] * (1 + tie)
        if _scan_inside(order, starts, next_start, iA[s], kA[s], ma, iA, kA, iC, kC, iC[s],
                        kC[s], mb, t, thr):
            keep[s] = False
        elif same and _scan_inside(order, starts, next_start, iC[s], kC[s], ma, iA, kA, iC,
                                   kC, iA[s], kA[s], ma, t, thr):
            keep[s] = False


def _group_tables(iA: IntArray, kA: IntArray, iC: IntArray, kC: IntArray, t: FloatArray, ma: int,
                  mb: int) -> Any:
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


def _any_inside(ptr: IntArray, g_iC: IntArray, ka0: IntArray, ka1: IntArray, kc0: IntArray,
                kc1: IntArray, off: IntArray, table: FloatArray, lo: int, span: int, ma: int,
                lo2: int, span2: int, mb: int, thr: float) -> bool:
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


def _beaten_tables(iA: IntArray, kA: IntArray, iC: IntArray, kC: IntArray, t: FloatArray, ma: int,
                   mb: int, same: bool, tie: float, keep: BoolArray, check: BoolArray) -> bool:
    """:func:`_beaten` by table look-ups (:func:`_group_tables`): False, leaving
    ``keep`` as it is, when the tables would pass :data:`TABLE_CELLS`.  Starts are
    ring positions (``0 <= iA < ma``, ``0 <= iC < mb``)."""
    ptr, g_iC, ka0, ka1, kc0, kc1, off, table = _group_tables(iA, kA, iC, kC, t, ma, mb)
    if table.shape[0] != off[-1]:
        return False
    for s in range(t.shape[0]):
        if not check[s]:
            continue
        thr = t[s] * (1 + tie)
        if _any_inside(ptr, g_iC, ka0, ka1, kc0, kc1, off, table, iA[s], kA[s], ma, iC[s],
                       kC[s], mb, thr):
            keep[s] = False
        elif same and _any_inside(ptr, g_iC, ka0, ka1, kc0, kc1, off, table, iC[s], kC[s],
                                  ma, iA[s], kA[s], mb, thr):
            keep[s] = False
    return True
