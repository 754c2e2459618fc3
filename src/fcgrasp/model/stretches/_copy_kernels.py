"""Compiled loops of the two-finger stretch search: the distinct search's exclusion (a
configuration surely a kept plan's copy: the arc outside a plan's region, its threshold,
the least overlap over every placement) and the collection's copies left out in runs.

Plain Python compiled by :mod:`fcgrasp.model.stretches._kernels` (one namespace for every
loop of the search, so that compiled loops call compiled ones); the search calls them
through that module's wrappers."""

from __future__ import annotations

import numpy as np

from ...core._checks import BoolArray, FloatArray, IntArray


def _copy_columns(a0: float, a1: float, ex: FloatArray, exs: FloatArray, app: IntArray) -> int:
    """The kept plans' columns of ``ex`` (rows ``ax0, ax1, ay0, ay1``) whose arc on ring
    a leaves the stretch 1 ``[a0, a1]`` a threshold below ``exs[4]``
    (:func:`_side_threshold`; ``exs``: ``perx, pery, tol, keep, drop``), written to
    ``app``: their count."""
    n = 0
    for c in range(ex.shape[1]):
        if _copy_side(a0, a1, ex, exs, 0, c):
            app[n] = c
            n += 1
    return n


def _copies_from(c0: float, c1: float, ex: FloatArray, exs: FloatArray, app: IntArray, n_app: int
                 ) -> bool:
    """Whether the stretch 2 ``[c0, c1]`` makes a copy with a stretch 1 whose columns
    are ``app`` (:func:`_copy_columns`): some column's threshold on ring b below
    ``exs[4]`` as well, so the configuration's least threshold (the larger of the two)
    is."""
    for j in range(n_app):
        if _copy_side(c0, c1, ex, exs, 1, app[j]):
            return True
    return False


def _copy_side(a0: float, a1: float, ex: FloatArray, exs: FloatArray, side: int, c: int) -> bool:
    """Whether column ``c`` of ``ex`` leaves the stretch ``[a0, a1]`` on ring ``side``
    (0: a) a threshold below ``exs[4]``, its arc there longer than that threshold."""
    u = 2 * side
    ta = _side_threshold(a0, a1, ex[u, c], ex[u + 1, c], exs[side], exs[2], exs[3])
    return bool(ta < exs[4] and ex[u + 1, c] - ex[u, c] > ta)


def _copy_run(p: int, room: int, ext_s: float, run_end: int, Ub: FloatArray, mb: int,
              ex: FloatArray, exs: FloatArray, app: IntArray, n_app: int) -> int:
    """How many starts after ``p`` (at most ``room``) have every stretch 2 a copy: the
    largest count ``d`` whose span from ``p``'s start to the farthest end of a stretch 2
    from ``p + d`` is a copy (:func:`_copy_span`; the ends only grow with the start),
    by doubling, then bisection."""
    c0 = Ub[(p - 1) % mb]
    if room <= 0 or not _copy_until(p, 1, c0, ext_s, run_end, Ub, mb, ex, exs, app, n_app):
        return 0
    lo, d = 1, 2
    while d <= room and _copy_until(p, d, c0, ext_s, run_end, Ub, mb, ex, exs, app, n_app):
        lo, d = d, 2 * d
    hi = min(d, room + 1)               # a copy up to lo; not to hi, or hi past room
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if _copy_until(p, mid, c0, ext_s, run_end, Ub, mb, ex, exs, app, n_app):
            lo = mid
        else:
            hi = mid
    return lo


def _copy_lengths(r: int, k: int, k_max: int, nr: int, rp0: IntArray, rlen: IntArray,
                  Ua: FloatArray, Ub: FloatArray, ma: int, mb: int, ex: FloatArray,
                  exs: FloatArray, app: IntArray, n_app: int) -> int:
    """The last window length of row ``r`` from ``k`` on (at most ``k_max``) whose every
    configuration is a copy of one kept plan's column, or ``k - 1``: a column of
    ``app`` (stretch 1 of length ``k`` holds its arc on ring a) that makes the widest
    stretch 2 of every one of the window's cyclic runs ``rp0, rlen`` a copy on ring b.
    The runs only shrink as the window grows, so they stay copies by that column for as
    long as stretch 1 does, which holds up to a length found by doubling, then
    bisection (stretch 1's arc outside only grows)."""
    i = (r - 1) % ma + ma
    a0 = Ua[(r - 1) % ma]
    for jc in range(n_app):
        c = app[jc]
        every = True
        for j in range(nr):
            if min(rlen[j], mb - 2) < 1:
                continue
            if rlen[j] >= mb - 2:
                every = False
                break
            c0, c1 = _run_span(rp0[j], rlen[j], Ub, mb)
            if not _copy_side(c0, c1, ex, exs, 1, c):
                every = False
                break
        if not every:
            continue
        # stretch 1 of length k holds: the longest that still does, up to k_max
        lo, d = k, 1
        while lo + d <= k_max and _copy_side(a0, a0 + (Ua[i + lo + d + 1] - Ua[i]), ex, exs,
                                             0, c):
            lo, d = lo + d, 2 * d
        hi = min(lo + d, k_max + 1)             # holds at lo; not at hi, or hi past k_max
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if _copy_side(a0, a0 + (Ua[i + mid + 1] - Ua[i]), ex, exs, 0, c):
                lo = mid
            else:
                hi = mid
        return lo
    return k - 1


def _run_span(start: int, length: int, Ub: FloatArray, mb: int) -> tuple[float, float]:
    """The widest stretch 2 of a cyclic run of ``length`` start vertices from ``start``
    (its edges from ``start - 1`` through ``length + 1`` of them) as an arc on ring b:
    every stretch 2 of the run lies inside it."""
    jb = (start - 1) % mb
    c0 = Ub[jb]
    return c0, c0 + (Ub[jb + mb + length + 1] - Ub[jb + mb])


def _copy_until(p: int, d: int, c0: float, ext_s: float, run_end: int, Ub: FloatArray, mb: int,
                ex: FloatArray, exs: FloatArray, app: IntArray, n_app: int) -> bool:
    """Whether every stretch 2 from the starts ``p .. p + d`` is a copy: they lie in the
    span from ``p``'s start ``c0`` to the last edge a stretch from ``p + d`` reaches
    (:func:`_window_row`'s ``q_hi``: as far as ``ext_s`` past its start's edge, within
    the run's end ``run_end`` and short of the ring)."""
    q = min(np.searchsorted(Ub, Ub[p + d] + ext_s, side="right") - 1, run_end,
            p + d + mb - 3)
    return _copy_span(c0, c0 + (Ub[q + 1] - Ub[p - 1]), ex, exs, app, n_app)


def _copy_span(c0: float, c1: float, ex: FloatArray, exs: FloatArray, app: IntArray, n_app: int
               ) -> bool:
    """:func:`_copies_from` of every stretch 2 inside ``[c0, c1]``: the span widened
    by the tolerance ``exs[2]`` is a copy by some column whose arc on ring b and the
    span fit in its perimeter together (then the span's arc outside is the measure of
    what lies outside the arc, which only shrinks for a stretch inside it)."""
    pad = exs[2]
    for j in range(n_app):
        c = app[j]
        if (c1 - c0) + 2 * pad + (ex[3, c] - ex[2, c]) <= exs[1] and \
                _copy_side(c0 - pad, c1 + pad, ex, exs, 1, c):
            return True
    return False


def _side_threshold(a0: float, a1: float, u0: float, u1: float, per: float, tol: float,
                    keep: float) -> float:
    """``_exclusion._Exclusion.threshold``'s length of one side: the stretch
    ``[a0, a1]``'s arc outside ``[u0, u1]`` (:func:`_outside_one`) plus ``tol``, over
    ``keep`` (the same operations)."""
    return (_outside_one(a0, a1, u0, u1, per) + tol) / keep


def _common_one(a0: float, a1: float, u0: float, u1: float, per: float) -> float:
    """``_exclusion._Exclusion._common`` of one stretch ``[a0, a1]`` and one arc
    ``[u0, u1]``: the same operations in the same order."""
    common = 0.0
    for j in range(3):
        shift = (-per, 0.0, per)[j]
        common += max(0.0, min(a1, u1 + shift) - max(a0, u0 + shift))
    return common


def _outside_one(a0: float, a1: float, u0: float, u1: float, per: float) -> float:
    """``_exclusion._Exclusion._outside`` of one stretch ``[a0, a1]`` and one arc
    ``[u0, u1]``: the same operations in the same order."""
    return (a1 - a0) - _common_one(a0, a1, u0, u1, per)


def _third_rows(ring: IntArray, g0: FloatArray, g1: FloatArray, e0: FloatArray,
                e1: FloatArray, kr: IntArray, k0: FloatArray, k1: FloatArray,
                per: FloatArray, fraction: float, pad: float, out: BoolArray) -> None:
    """``_exclusion._Exclusion._third_mask_of`` fused over rows (configurations:
    the third finger's ring, sure arc ``[g0, g1]`` and widest ``[e0, e1]``) and columns
    (the kept plans' remaining regions: ring ``kr``, arc ``[k0, k1]``; ``per`` each
    ring's perimeter): the same numbers, without a matrix of each."""
    for r in range(ring.size):
        for c in range(kr.size):
            if kr[c] != ring[r]:
                continue
            common = _common_one(g0[r], g1[r], k0[c], k1[c], per[kr[c]])
            short = min(e1[r] - e0[r], k1[c] - k0[c])
            out[r, c] = common - fraction * short > pad


def _exclusion_rows(a0x: FloatArray, a1x: FloatArray, a0y: FloatArray, a1y: FloatArray,
                    ax0: FloatArray, ax1: FloatArray, ay0: FloatArray, ay1: FloatArray,
                    perx: float, pery: float, tol: float, keep: float, mask: BoolArray,
                    masked: bool, out: FloatArray) -> None:
    """``_exclusion._Exclusion.threshold``: ``out`` lowered to each configuration's least
    ``tau`` over the kept plans' columns (with ``masked``, those of ``mask[r]`` only),
    fused over rows and columns: the same numbers."""
    for r in range(a0x.size):
        for c in range(ax0.size):
            if masked and not mask[r, c]:
                continue
            la, lc = ax1[c] - ax0[c], ay1[c] - ay0[c]
            ta = _side_threshold(a0x[r], a1x[r], ax0[c], ax1[c], perx, tol, keep)
            tc = _side_threshold(a0y[r], a1y[r], ay0[c], ay1[c], pery, tol, keep)
            if la > ta and lc > tc:
                out[r] = min(out[r], max(ta, tc))


def _excess_at(s: float, e: float, s0: float, s1: float, e0: float, e1: float, t: float,
               k0: float, k1: float, f: float, eps: float) -> float:
    """``overlap([s, e], [k0, k1]) - f min(e - s, k1 - k0)`` where ``[s, e]`` is one of
    the regions of :func:`_least_excess` (each bound loosened by ``eps``), else inf."""
    if s < s0 - eps or s > s1 + eps or e < e0 - eps or e > e1 + eps or e - s < t - eps:
        return np.inf
    return max(0.0, min(e, k1) - max(s, k0)) - f * min(e - s, k1 - k0)


def _least_excess(s0: float, s1: float, e0: float, e1: float, t: float, k0: float,
                  k1: float, f: float, eps: float) -> float:
    """The least of ``overlap([s, e], [k0, k1]) - f min(e - s, k1 - k0)`` over the
    regions ``[s, e]`` with ``s`` in ``[s0, s1]``, ``e`` in ``[e0, e1]`` and ``e - s >=
    t``: the function is continuous and linear between the lines ``s = s0, s1, k0, k1``,
    ``e = e0, e1, k0, k1`` and ``e - s = t, k1 - k0``, so its least is at a crossing of
    two of them inside (-inf: no region).  ``_exclusion._Exclusion._least_excess`` of
    one cell: the same operations."""
    best = np.inf
    for a in range(4):
        sa = (s0, s1, k0, k1)[a]
        for b in range(4):
            best = min(best, _excess_at(sa, (e0, e1, k0, k1)[b], s0, s1, e0, e1, t, k0, k1,
                                        f, eps))
        for d in range(2):
            best = min(best, _excess_at(sa, sa + (t, k1 - k0)[d], s0, s1, e0, e1, t, k0,
                                        k1, f, eps))
    for b in range(4):
        eb = (e0, e1, k0, k1)[b]
        for d in range(2):
            best = min(best, _excess_at(eb - (t, k1 - k0)[d], eb, s0, s1, e0, e1, t, k0,
                                        k1, f, eps))
    return -np.inf if best == np.inf else best


def _surely_copy(s0: float, s1: float, e0: float, e1: float, t: float, k0: float, k1: float,
                 per: float, f: float, tol: float) -> bool:
    """Every region of :func:`_least_excess` overlaps the arc ``[k0, k1]`` (or its turn
    by ``-per`` or ``per``) by more than ``f`` of the shorter, plus ``tol``."""
    for j in range(3):
        shift = (-per, 0.0, per)[j]
        if _least_excess(s0, s1, e0, e1, t, k0 + shift, k1 + shift, f, tol) > tol:
            return True
    return False


def _similar_rows(sx: FloatArray, sy: FloatArray, ax0: FloatArray, ax1: FloatArray,
                  ay0: FloatArray, ay1: FloatArray, perx: float, pery: float, tol: float, f: float,
                  t: FloatArray, mask: BoolArray, masked: bool, out: BoolArray) -> None:
    """``_exclusion._Exclusion.similar``: ``out[r]`` set where, for some kept plan's
    column (with ``masked``, one of ``mask[r]``), every region pair configuration ``r``
    allows (its ends' intervals ``sx[r]``, ``sy[r]``: first start, last start, first
    end, last end on each ring; smallest region ``t[r]``) overlaps that plan's on both
    sides (:func:`_surely_copy`)."""
    for r in range(t.size):
        for c in range(ax0.size):
            if masked and not mask[r, c]:
                continue
            if _surely_copy(sx[r, 0], sx[r, 1], sx[r, 2], sx[r, 3], t[r] - tol, ax0[c], ax1[c],
                            perx, f, tol) and \
                    _surely_copy(sy[r, 0], sy[r, 1], sy[r, 2], sy[r, 3], t[r] - tol, ay0[c],
                                 ay1[c], pery, f, tol):
                out[r] = True
                break


def _run_end(ptr: IntArray, first: IntArray, last: IntArray, row: int, c0: int, m: int
             ) -> int:
    """The last column of row ``row``'s run that holds column ``c0`` (``0 <= c0 < m``),
    past ``m - 1`` where the run through the last column goes on into the first (its
    first run's last plus ``m``); -1 where ``c0`` is in no run: by bisection over the
    row's runs, sorted by their first column."""
    lo, hi = ptr[row], ptr[row + 1]
    while lo < hi:                      # the first run starting after c0
        mid = (lo + hi) // 2
        if first[mid] <= c0:
            lo = mid + 1
        else:
            hi = mid
    if lo == ptr[row] or last[lo - 1] < c0:
        return -1
    end = last[lo - 1]
    if end == m - 1 and first[ptr[row]] == 0:
        end = m + last[ptr[row]]
    return int(end)


def _row_holds(ptr: IntArray, first: IntArray, last: IntArray, row: int, c0: int, n: int,
               m: int) -> bool:
    """Whether row ``row``'s runs hold the ``n`` cyclic columns from ``c0`` (at most
    ``m``; a run through the last column goes on into the first only where both are
    runs): :func:`_run_end` (``_whole._RowRuns.holds`` in numpy)."""
    return _run_end(ptr, first, last, row, c0, m) >= c0 + n - 1


def _stretch_thresholds(a0: float, a1: float, ex: FloatArray, exs: FloatArray,
                        ta: FloatArray) -> None:
    """Stretch 1 ``[a0, a1]``'s threshold against each kept plan's first arc (columns of
    ``ex``), into ``ta``; inf where that arc is not longer than it (the column gives
    the configuration no threshold: :func:`_exclusion_rows`)."""
    for c in range(ex.shape[1]):
        t = _side_threshold(a0, a1, ex[0, c], ex[1, c], exs[0], exs[2], exs[3])
        ta[c] = t if ex[1, c] - ex[0, c] > t else np.inf


def _copy_at_optimum(c0: float, c1: float, ub: float, ta: FloatArray, ex: FloatArray,
                     exs: FloatArray) -> bool:
    """Whether a configuration whose largest square is ``ub`` (its whole windows hold),
    stretch 2 ``[c0, c1]``, stretch 1's thresholds ``ta`` (:func:`_stretch_thresholds`),
    reaches its threshold (``_exclusion._Exclusion.threshold`` of the kept plans: the
    least over the columns of the larger side's, :func:`_exclusion_rows`'s numbers) by
    the pad ``exs[5]`` both ways: a kept plan's copy at its largest square."""
    lhs = ub * (1 - exs[5])
    for c in range(ex.shape[1]):
        if not lhs >= ta[c] * (1 + exs[5]):
            continue
        tc = _side_threshold(c0, c1, ex[2, c], ex[3, c], exs[1], exs[2], exs[3])
        if ex[3, c] - ex[2, c] > tc and lhs >= max(ta[c], tc) * (1 + exs[5]):
            return True
    return False
