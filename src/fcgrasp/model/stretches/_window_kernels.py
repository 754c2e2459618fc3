"""Compiled loops of the two-finger stretch search: the windows of interior vertices
(:func:`_windows`: each row's window widened by intersecting its runs with the next
row's, the sparse table of runs, the rows' upper bounds and the collection of
configurations).

Plain Python compiled by :mod:`fcgrasp.model.stretches._kernels` (one namespace for every
loop of the search, so that compiled loops call compiled ones); the search calls them
through that module's wrappers."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...core._checks import FloatArray, IntArray
from ...core.tolerances import ROUND_TOL
from ._copy_kernels import (
    _copies_from,
    _copy_at_optimum,
    _copy_columns,
    _copy_lengths,
    _copy_run,
    _row_holds,
    _run_end,
    _run_span,
    _stretch_thresholds,
)
from ._run_kernels import _append, _grow


def _intersect(a0: int, a1: int, fa: IntArray, la: IntArray, b0: int, b1: int, fb: IntArray,
               lb: IntArray, out_f: IntArray, out_l: IntArray, n: int) -> Any:
    """The runs common to two sorted lists of runs (``fa[a0:a1]``, ``la[a0:a1]`` and the
    same of b), appended to ``out_f``, ``out_l`` from position ``n`` (two monotone
    pointers; maximal runs stay maximal): the arrays (grown) and the new count."""
    while a0 < a1 and b0 < b1:
        lo = max(fa[a0], fb[b0])
        hi = min(la[a0], lb[b0])
        if lo <= hi:
            out_f, out_l = _append(out_f, out_l, n, lo, hi)
            n += 1
        if la[a0] < lb[b0]:
            a0 += 1
        else:
            b0 += 1
    return out_f, out_l, n


def _run_table(ptr: IntArray, first: IntArray, last: IntArray, ma: int, levels: int) -> Any:
    """The runs of the AND of rows ``r .. r + 2^j - 1`` (cyclic) for every row ``r`` and
    level ``j < levels``: row pointers ``tptr[j]`` into one pair of arrays (a sparse table:
    any window of rows is the AND of two overlapping entries).  Levels stop after the
    first with no run at all (no longer window has one either): the table and the number
    of its levels."""
    tptr = np.zeros((levels, ma + 1), np.int64)
    n = ptr[ma]
    tf, tl = np.empty(2 * n + 16, np.int64), np.empty(2 * n + 16, np.int64)
    tf[:n], tl[:n] = first[:n], last[:n]
    tptr[0, :] = ptr
    for j in range(1, levels):
        half = 1 << (j - 1)
        tptr[j, 0] = n
        for r in range(ma):
            r2 = (r + half) % ma
            tf, tl, n = _intersect(tptr[j - 1, r], tptr[j - 1, r + 1], tf, tl,
                                   tptr[j - 1, r2], tptr[j - 1, r2 + 1], tf, tl, tf, tl, n)
            tptr[j, r + 1] = n
        if n == tptr[j, 0]:
            return tptr, tf, tl, j + 1
    return tptr, tf, tl, levels


def _window_of(tptr: IntArray, tf: IntArray, tl: IntArray, r: int, k: int, ma: int, cs: IntArray,
               ce: IntArray) -> Any:
    """The runs of the AND of rows ``r .. r + k - 1`` (cyclic) into ``cs``, ``ce``, read
    from the sparse table: their count."""
    j = 0
    while (2 << j) <= k:
        j += 1
    r2 = (r + k - (1 << j)) % ma
    cs, ce, n = _intersect(tptr[j, r], tptr[j, r + 1], tf, tl, tptr[j, r2], tptr[j, r2 + 1],
                           tf, tl, cs, ce, 0)
    return n


def _cyclic(cs: IntArray, ce: IntArray, nc: int, mb: int, rp0: IntArray, rlen: IntArray) -> int:
    """A window's runs as cyclic runs (a run through the last column goes on into the
    first): starts ``rp0`` and lengths ``rlen``, their count."""
    nr = 0
    if nc == 1 and cs[0] == 0 and ce[0] == mb - 1:
        rp0[0], rlen[0] = 0, mb
        return 1
    wrap = nc > 1 and cs[0] == 0 and ce[nc - 1] == mb - 1
    for j in range(1 if wrap else 0, nc):
        rp0[nr], rlen[nr] = cs[j], ce[j] - cs[j] + 1
        if wrap and j == nc - 1:
            rlen[nr] += ce[0] + 1
        nr += 1
    return nr


def _measures(rp0: IntArray, rlen: IntArray, nr: int, mb: int, Ub: FloatArray) -> Any:
    """The most any stretch 2 inside these cyclic runs reaches (its edges), and the
    longest vertex-aligned one (its interior vertices)."""
    reach, vert = 0.0, 0.0
    for j in range(nr):
        jb = (rp0[j] - 1) % mb + mb
        reach = max(reach, Ub[jb + min(rlen[j], mb - 1) + 1] - Ub[jb])
        vert = max(vert, Ub[jb + min(rlen[j], mb - 2)] - Ub[jb + 1])
    return reach, vert


def _row_bound(tptr: IntArray, tf: IntArray, tl: IntArray, r: int, ma: int, mb: int, k_max: int,
               Ua: FloatArray, Ub: FloatArray, cs: IntArray, ce: IntArray, rp0: IntArray,
               rlen: IntArray) -> float:
    """An upper bound on row ``r``'s lower bound (:func:`_window_row` without
    ``collect``): the largest ``min(inner_s, vert)`` over the window lengths ``k``,
    every run counted (on one ring too).  ``inner_s`` grows with ``k`` and ``vert``
    shrinks (the runs only shrink), so the largest is where they cross: found by
    bisection over ``k`` on the sparse table's windows (``k_max``: the longest that may
    hold a run)."""
    i = (r - 1) % ma + ma
    lo_k, hi_k = 1, k_max                       # inner_s(lo_k) <= vert(lo_k) holds at 1
    if hi_k < 1:
        return 0.0
    best = 0.0
    while lo_k < hi_k:
        mid = (lo_k + hi_k + 1) // 2
        nr = _cyclic(cs, ce, _window_of(tptr, tf, tl, r, mid, ma, cs, ce), mb, rp0, rlen)
        vert = _measures(rp0, rlen, nr, mb, Ub)[1]
        inner_s = Ua[i + mid] - Ua[i + 1]
        if inner_s <= vert:
            lo_k = mid
            best = max(best, inner_s)
        else:
            hi_k = mid - 1
            best = max(best, vert)
    # the last k where inner_s <= vert, and the next one
    for k in range(lo_k, min(lo_k + 2, k_max + 1)):
        nr = _cyclic(cs, ce, _window_of(tptr, tf, tl, r, k, ma, cs, ce), mb, rp0, rlen)
        vert = _measures(rp0, rlen, nr, mb, Ub)[1]
        best = max(best, min(Ua[i + k] - Ua[i + 1], vert))
    return best


def _window_row(r: int, k: int, nc: int, cs: IntArray, ce: IntArray, ns: IntArray, ne: IntArray,
                rp0: IntArray, rlen: IntArray, ptr: IntArray, first: IntArray, last: IntArray,
                Ua: FloatArray, Ub: FloatArray, ma: int, mb: int, floor: float, collect: bool,
                same: bool, best: FloatArray, thresh: float, oA: IntArray, okA: IntArray,
                oC: IntArray, okC: IntArray, n_out: int, ex: FloatArray, exs: FloatArray,
                gallop: bool, tptr: IntArray, tf: IntArray, tl: IntArray, k_max: int) -> Any:
    """Row ``r`` of :func:`_windows` from window length ``k`` on (its runs ``cs``,
    ``ce``: the AND of rows ``r .. r + k - 1``).  Without ``collect`` the widening stops
    once no window can beat ``max(best[r], thresh)``.  With ``collect`` and kept plans'
    arcs ``ex`` (:func:`_copy_columns`), the configurations that are surely a kept
    plan's copy at any smallest region from ``exs[4]`` on are not collected
    (:func:`_copies_from`); with ``gallop``, the starts of stretch 2 whose every
    stretch is a copy are passed over in runs (:func:`_copy_run`), and so are the
    window lengths whose every configuration is one (:func:`_copy_lengths`; the window
    after them read from the sparse table ``tptr, tf, tl``, which holds windows of up
    to ``k_max`` rows; ``k_max`` 0: none), and on one ring (``same``) only the
    configurations the search keeps are made (:func:`_both_kept`'s: disjoint stretches,
    each unordered pair once), else each is read and made (the reference).  On one ring
    with the pad ``exs[5]`` > 0, a configuration whose whole windows hold (the runs of
    the rows of its four end vertices, the matrix symmetric) with an arc bound above its
    threshold by that pad both ways is not collected either: a kept plan's copy at its
    largest square (:func:`_copy_at_optimum`, :mod:`._whole`)."""
    i = (r - 1) % ma + ma
    n_ex = ex.shape[1]
    app = np.empty(n_ex, np.int64)
    # (one ring with itself, kept plans, and the pad of the whole windows' rule given)
    whole = collect and same and n_ex > 0 and exs.size > 5 and exs[5] > 0
    ta = np.full(n_ex, np.inf)
    while k < ma - 1 and nc > 0:
        ext_s = Ua[i + k + 1] - Ua[i]
        inner_s = Ua[i + k] - Ua[i + 1]
        # the kept plans whose arc on ring a holds this stretch 1 closely enough that
        # its configurations are copies wherever stretch 2 is close to their other arc
        n_app = 0
        if collect and n_ex > 0 and ext_s >= floor:
            a0 = Ua[(r - 1) % ma]
            n_app = _copy_columns(a0, a0 + ext_s, ex, exs, app)
            if whole:
                _stretch_thresholds(a0, a0 + ext_s, ex, exs, ta)
        # the current window's cyclic runs, the most any stretch 2 inside them reaches
        # and the longest vertex-aligned one: runs only shrink as the window grows,
        # so neither grows with k
        nr = _cyclic(cs, ce, nc, mb, rp0, rlen)
        reach, vert = _measures(rp0, rlen, nr, mb, Ub)
        if collect:
            # a configuration's stretch 2 reaches the floor and stretch 1's interior
            # (inner_s, growing with k): stop when no run can
            if reach < max(floor, inner_s) * (1 - ROUND_TOL):
                break
        elif reach < floor * (1 - ROUND_TOL) or vert <= max(best[r], thresh):
            break                   # no later lower bound can beat this row's
        if collect and gallop and n_app > 0 and k_max > 0:
            upto = _copy_lengths(r, k, k_max, nr, rp0, rlen, Ua, Ub, ma, mb, ex, exs, app,
                                 n_app)
            if upto >= k:
                # every configuration of the window lengths k .. upto is a copy: on
                # from the next, its runs read from the sparse table
                k = upto + 1
                if k >= ma - 1 or k > k_max:
                    break
                nc = _window_of(tptr, tf, tl, r, k, ma, cs, ce)
                continue
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
            if n_app > 0 and rlen[j] < mb - 2:
                # every stretch 2 of the run lies inside its widest: a copy of a plan
                # that the widest is one of is a copy too (the arc outside only shrinks)
                c0, c1 = _run_span(rp0[j], rlen[j], Ub, mb)
                if _copies_from(c0, c1, ex, exs, app, n_app):
                    continue
            jj = -1
            while jj + 1 < rlen[j]:
                jj += 1
                p = (rp0[j] + jj) % mb + mb
                run_last = run_end0 if run_end0 >= p else run_end0 + mb
                run_end = min(run_last, p + mb - 3)
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
                if n_app > 0:
                    # the copies of one start are the shortest stretches 2 (the arc
                    # outside a plan's grows with q): the first q that is none
                    c0 = Ub[(p - 1) % mb]
                    lo, hi = q_lo, q_hi + 1
                    while lo < hi:
                        mid = (lo + hi) // 2
                        if _copies_from(c0, c0 + (Ub[mid + 1] - Ub[p - 1]), ex, exs, app,
                                        n_app):
                            lo = mid + 1
                        else:
                            hi = mid
                    q_lo = lo
                    if q_hi < q_lo and gallop:
                        # every stretch 2 from p is a copy: so is every one from the
                        # later starts whose stretches lie in one span that is a copy
                        # (the arc outside only shrinks), found by galloping
                        jj += _copy_run(p, rlen[j] - 1 - jj, ext_s, run_last, Ub, mb,
                                        ex, exs, app, n_app)
                    if q_hi < q_lo:
                        continue
                if same and gallop:
                    # on one ring, each unordered pair of disjoint stretches once (the
                    # search's own filter, :func:`_both_kept`, applied as they are made)
                    rel = (p - r) % mb
                    if rel <= k or (r - 1) % mb >= (p - 1) % mb:
                        continue
                    q_hi = min(q_hi, p + mb - rel - 2)
                    if q_hi < q_lo:
                        continue
                n_new = n_out + q_hi - q_lo + 1
                oA, okA = _grow(oA, n_new), _grow(okA, n_new)
                oC, okC = _grow(oC, n_new), _grow(okC, n_new)
                c0, cp, ra0 = Ub[(p - 1) % mb], (p - 1) % mb, (r - 1) % ma
                if whole:
                    # the whole windows' block outside the interior (``_whole``): the
                    # rows of stretch 1's end vertices hold stretch 2's columns up to
                    # ``reach``; the row of stretch 2's first vertex holds stretch 1
                    reach = min(_run_end(ptr, first, last, ra0, cp, mb),
                                _run_end(ptr, first, last, (r + k) % ma, cp, mb))
                    starts = k + 2 <= ma and _row_holds(ptr, first, last, cp, ra0, k + 2, ma)
                for q in range(q_lo, q_hi + 1):
                    if whole and starts and cp + q - p + 2 <= reach and q - p + 3 <= mb and \
                            _row_holds(ptr, first, last, (q + 1) % mb, ra0, k + 2, ma):
                        # a kept plan's copy at its largest square, the arc bound
                        ext_u = Ub[q + 1] - Ub[p - 1]
                        if _copy_at_optimum(c0, c0 + ext_u, min(ext_s, ext_u), ta, ex, exs):
                            continue
                    oA[n_out], okA[n_out] = r - 1, k
                    oC[n_out], okC[n_out] = p - 1, q - p + 1
                    n_out += 1
        # the window grows by row r + k: intersect the runs
        row = (r + k) % ma
        ns, ne, n2 = _intersect(0, nc, cs, ce, ptr[row], ptr[row + 1], first, last, ns, ne,
                                0)
        for j in range(n2):
            cs[j], ce[j] = ns[j], ne[j]
        nc = n2
        k += 1
    return oA, okA, oC, okC, n_out


#: Windows of fewer rows than this are all read (no upper bounds, no ordering).
_SHORT = 64


def _top_add(topv: FloatArray, topk: IntArray, key: int, v: float) -> None:
    """Keep in ``topv`` (ascending) the largest values seen, at most one per key
    (``topk``): ``v`` under ``key``."""
    n = topv.size
    j = -1
    for q in range(n):
        if topk[q] == key:
            j = q
            break
    if j < 0:
        if v <= topv[0]:
            return
        j = 0
        topk[0] = key
    elif v <= topv[j]:
        return
    topv[j] = v
    while j + 1 < n and topv[j + 1] < topv[j]:
        topv[j], topv[j + 1] = topv[j + 1], topv[j]
        topk[j], topk[j + 1] = topk[j + 1], topk[j]
        j += 1


def _buffers(mb: int) -> Any:
    """Work arrays of :func:`_windows`: room for the runs of a window (``cs``, ``ce``),
    of the next one (``ns``, ``ne``), their cyclic runs (``rp0``, ``rlen``), and the
    configurations collected (``oA``, ``okA``, ``oC``, ``okC``, grown as needed)."""
    cs, ce = np.empty(mb + 1, np.int64), np.empty(mb + 1, np.int64)
    ns, ne = np.empty(mb + 1, np.int64), np.empty(mb + 1, np.int64)
    rp0, rlen = np.empty(mb + 1, np.int64), np.empty(mb + 1, np.int64)
    oA, okA = np.empty(1024, np.int64), np.empty(1024, np.int64)
    oC, okC = np.empty(1024, np.int64), np.empty(1024, np.int64)
    return cs, ce, ns, ne, rp0, rlen, oA, okA, oC, okC


def _every_row(ptr: IntArray, first: IntArray, last: IntArray, Ua: FloatArray, Ub: FloatArray,
               ma: int, mb: int, floor: float, collect: bool, same: bool, ex: FloatArray,
               exs: FloatArray, gallop: bool, r0: int, r1: int) -> Any:
    """:func:`_windows` reading every row of ``r0 .. r1 - 1`` from its first window on."""
    best = np.zeros(ma)
    cs, ce, ns, ne, rp0, rlen, oA, okA, oC, okC = _buffers(mb)
    no_table = np.zeros((1, 1), np.int64)         # (no window read from a table)
    n_out = 0
    for r in range(r0, r1 if ptr[ma] > 0 else r0):  # no runs: no window
        nc = 0
        for q in range(ptr[r], ptr[r + 1]):
            cs[nc], ce[nc] = first[q], last[q]
            nc += 1
        oA, okA, oC, okC, n_out = _window_row(
            r, 1, nc, cs, ce, ns, ne, rp0, rlen, ptr, first, last, Ua, Ub, ma, mb,
            floor, collect, same, best, 0.0, oA, okA, oC, okC, n_out, ex, exs, gallop,
            no_table, first, last, 0)
    return best, oA[:n_out], okA[:n_out], oC[:n_out], okC[:n_out]


def _table(ptr: IntArray, first: IntArray, last: IntArray, ma: int) -> Any:
    """:func:`_run_table` with as many levels as a window of ``ma - 2`` rows needs."""
    levels = 1
    while (1 << levels) <= ma - 2:
        levels += 1
    return _run_table(ptr, first, last, ma, levels)


def _windows(ptr: IntArray, first: IntArray, last: IntArray, Ua: FloatArray, Ub: FloatArray,
             ma: int, mb: int, floor: float, collect: bool, same: bool, value: float, keep: int,
             short: int, ex: FloatArray, exs: FloatArray, gallop: bool, r0: int, r1: int,
             tptr: IntArray, tf: IntArray, tl: IntArray, levels: int) -> Any:
    """Windows of interior vertices of both stretches (``_windows_both`` of the numpy
    search, row by row).

    Without ``collect``: for each first row ``r`` (stretch 1 from vertex ``r``), the
    largest smallest region of the vertex-aligned stretch pairs it starts (its lower
    bound; 0 if none exceeds ``floor``; on one ring only pairs whose stretch 2 starts
    after ``r``, so that each unordered pair is counted by one row).  With ``collect``:
    every configuration ``(iA, kA, iC, kC)`` whose arc bound reaches ``floor``.

    ``keep > 0`` prunes with a sparse table of the rows' runs (:func:`_run_table`).
    Without ``collect`` the rows are read in decreasing order of an upper bound
    (:func:`_row_bound`) and a row is skipped (its bound 0) once that bound cannot pass
    ``T``: the ``keep``-th largest of the rows read so far, or ``value`` (the search's
    ``keep``-th largest over every key) if higher; a row read stops widening below
    ``T`` too.  What is left out is at most ``T``, never above the search's final
    ``keep``-th value, so the floor it gives is the same.  With ``collect`` each row
    starts at the first window long enough for stretch 1 to reach ``floor`` (the
    shorter ones collect nothing; their break test only weakens with ``k``).  Where no
    window of ``short`` rows has a run, every row is read as without ``keep``.

    A collection reads the rows ``r0 .. r1 - 1`` (a block of them: :func:`windows`), with
    the sparse table ``tptr, tf, tl`` of ``levels`` levels (:func:`_table`; built here
    where ``levels`` is 0)."""
    if not collect:
        r0, r1 = 0, ma
    if keep <= 0 or ma < 4 or ptr[ma] == 0:
        return _every_row(ptr, first, last, Ua, Ub, ma, mb, floor, collect, same, ex, exs,
                          gallop, r0, r1)
    if levels == 0:
        tptr, tf, tl, levels = _table(ptr, first, last, ma)
    k_max = min(ma - 2, (1 << levels) - 1)     # a longer window contains an empty entry
    if k_max < short:
        # short windows only (a noisy outline): reading them all costs less than sorting
        return _every_row(ptr, first, last, Ua, Ub, ma, mb, floor, collect, same, ex, exs,
                          gallop, r0, r1)
    best = np.zeros(ma)
    cs, ce, ns, ne, rp0, rlen, oA, okA, oC, okC = _buffers(mb)
    n_out = 0
    if collect:
        for r in range(r0, r1):
            i = (r - 1) % ma + ma
            # the first k whose stretch 1 reaches the floor (by bisection: ext_s grows)
            k, k_hi = 1, k_max + 1
            while k < k_hi:
                mid = (k + k_hi) // 2
                if Ua[i + mid + 1] - Ua[i] < floor:
                    k = mid + 1
                else:
                    k_hi = mid
            if k > k_max:
                continue
            nc = _window_of(tptr, tf, tl, r, k, ma, cs, ce)
            oA, okA, oC, okC, n_out = _window_row(
                r, k, nc, cs, ce, ns, ne, rp0, rlen, ptr, first, last, Ua, Ub, ma, mb,
                floor, collect, same, best, 0.0, oA, okA, oC, okC, n_out, ex, exs, gallop,
                tptr, tf, tl, k_max)
        return best, oA[:n_out], okA[:n_out], oC[:n_out], okC[:n_out]
    upper = np.empty(ma)
    for r in range(ma):
        upper[r] = _row_bound(tptr, tf, tl, r, ma, mb, k_max, Ua, Ub, cs, ce, rp0, rlen)
    top = np.zeros(keep)                        # the keep largest read, ascending
    top_rows = np.full(keep, -1, np.int64)      # (each row its own key)
    for r in np.argsort(-upper):
        thresh = max(value, top[0])
        if upper[r] * (1 + ROUND_TOL) <= thresh:
            break
        nc = _window_of(tptr, tf, tl, r, 1, ma, cs, ce)         # the row's own runs
        oA, okA, oC, okC, n_out = _window_row(
            r, 1, nc, cs, ce, ns, ne, rp0, rlen, ptr, first, last, Ua, Ub, ma, mb,
            floor, collect, same, best, thresh, oA, okA, oC, okC, n_out, ex, exs, gallop,
            tptr, tf, tl, k_max)
        _top_add(top, top_rows, r, best[r])
    return best, oA[:n_out], okA[:n_out], oC[:n_out], okC[:n_out]
