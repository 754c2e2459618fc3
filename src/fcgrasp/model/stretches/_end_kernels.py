"""Compiled loops of the two-finger stretch search: the intervals of a stretch's ends
against the other stretch's interior vertices (:func:`_window_boxes` and its shared and
memoised forms), the single-edge windows (:func:`_single`) and the configurations inside
a longer one.

Plain Python compiled by :mod:`fcgrasp.model.stretches._kernels` (one namespace for every
loop of the search, so that compiled loops call compiled ones); the search calls them
through that module's wrappers."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...core._checks import BoolArray, FloatArray, IntArray
from ._run_kernels import _grow
from ._window_kernels import _top_add


def _interval(ax: FloatArray, ay: FloatArray, tx: FloatArray, ty: FloatArray, L: FloatArray,
              gx: FloatArray, bx: FloatArray, by: FloatArray, gy: FloatArray, sigma: float,
              eps: float, e: int, w: int) -> Any:
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


def _window_boxes_shared(edge: IntArray, start: IntArray, count: IntArray, ax: FloatArray,
                         ay: FloatArray, tx: FloatArray, ty: FloatArray, L: FloatArray,
                         gx: FloatArray, bx: FloatArray, by: FloatArray, gy: FloatArray,
                         sigma: float, eps: float) -> Any:
    """:func:`_window_boxes` of a batch whose windows share edges (the shifted copies
    of a configuration): the windows of one edge whose span is shorter than their
    lengths added up read the cells of the span once (:func:`_interval`, most of the
    cost), then each window's maximum and minimum over them, by two look-ups in sparse
    tables where their levels cost less than reading every window's cells.  A max and
    a min are exact in any order: the same numbers; other edges' windows are read cell
    by cell."""
    n, mb = edge.size, bx.size
    lo, hi = np.zeros(n), np.full(n, np.inf)
    order = np.argsort(edge, kind="mergesort")
    g0 = 0
    while g0 < n:
        e = edge[order[g0]]
        g1 = g0
        total, first, end = 0, 1 << 62, -(1 << 62)
        while g1 < n and edge[order[g1]] == e:
            j = order[g1]
            if count[j] > 0:
                s = start[j] % mb
                first, end = min(first, s), max(end, s + count[j])
                total += count[j]
            g1 += 1
        span = end - first
        if total == 0 or span >= total or span > 2 * mb:
            for q in range(g0, g1):             # cell by cell (_window_boxes)
                j = order[q]
                if count[j] <= 0:
                    continue
                a_max, b_min = -np.inf, np.inf
                for k in range(count[j]):
                    a, b = _interval(ax, ay, tx, ty, L, gx, bx, by, gy, sigma, eps, e,
                                     (start[j] + k) % mb)
                    a_max, b_min = max(a_max, a), min(b_min, b)
                lo[j], hi[j] = a_max, b_min
            g0 = g1
            continue
        levels = 1
        while (1 << levels) <= span:
            levels += 1
        tabled = span * levels < total
        tmax = np.empty((levels if tabled else 1, span))
        tmin = np.empty((levels if tabled else 1, span))
        for i in range(span):
            tmax[0, i], tmin[0, i] = _interval(ax, ay, tx, ty, L, gx, bx, by, gy, sigma, eps,
                                               e, (first + i) % mb)
        if tabled:
            for v in range(1, levels):
                h = 1 << (v - 1)
                for i in range(span - (1 << v) + 1):
                    tmax[v, i] = max(tmax[v - 1, i], tmax[v - 1, i + h])
                    tmin[v, i] = min(tmin[v - 1, i], tmin[v - 1, i + h])
        for q in range(g0, g1):
            j = order[q]
            c = count[j]
            if c <= 0:
                continue
            i = start[j] % mb - first
            if tabled:
                v = 0
                while (2 << v) <= c:
                    v += 1
                i2 = i + c - (1 << v)
                lo[j] = max(tmax[v, i], tmax[v, i2])
                hi[j] = min(tmin[v, i], tmin[v, i2])
                continue
            a_max, b_min = -np.inf, np.inf
            for k in range(i, i + c):
                a_max, b_min = max(a_max, tmax[0, k]), min(b_min, tmin[0, k])
            lo[j], hi[j] = a_max, b_min
        g0 = g1
    return lo, hi


def _window_boxes_memo(edge: IntArray, start: IntArray, count: IntArray, ax: FloatArray,
                       ay: FloatArray, tx: FloatArray, ty: FloatArray, L: FloatArray,
                       gx: FloatArray, bx: FloatArray, by: FloatArray, gy: FloatArray,
                       sigma: float, eps: float, tlo: FloatArray, thi: FloatArray) -> Any:
    """:func:`_window_boxes` reading each cell ``(e, w)`` from the tables ``tlo``,
    ``thi`` (ma, mb), computed by :func:`_interval` on first use (NaN: not yet): the
    same numbers (the intersection is a max and a min, in any order), each cell once
    however many configurations' windows hold it."""
    n, mb = edge.size, bx.size
    lo, hi = np.zeros(n), np.full(n, np.inf)
    for i in range(n):
        if count[i] <= 0:
            continue
        e = edge[i]
        a_max, b_min = -np.inf, np.inf
        for k in range(count[i]):
            w = (start[i] + k) % mb
            a = tlo[e, w]
            if np.isnan(a):
                a, b = _interval(ax, ay, tx, ty, L, gx, bx, by, gy, sigma, eps, e, w)
                tlo[e, w], thi[e, w] = a, b
            else:
                b = thi[e, w]
            a_max, b_min = max(a_max, a), min(b_min, b)
        lo[i], hi[i] = a_max, b_min
    return lo, hi


def _by_start(a: IntArray, ka: IntArray, ma: int) -> Any:
    """The order of configurations by first start ``a`` (in ``[0, ma)``), then by
    decreasing ``ka`` (each from 0), ties by index: two counting sorts, linear where a
    sort of the hundreds of thousands of configurations a distinct search defers is
    not."""
    n = a.size
    top = 0
    for i in range(n):
        top = max(top, ka[i])
    count = np.zeros(top + 2, np.int64)
    for i in range(n):
        count[top - ka[i] + 1] += 1
    for k in range(1, top + 2):
        count[k] += count[k - 1]
    first = np.empty(n, np.int64)
    for i in range(n):
        k = top - ka[i]
        first[count[k]] = i
        count[k] += 1
    count = np.zeros(ma + 1, np.int64)
    for i in range(n):
        count[a[i] + 1] += 1
    for k in range(1, ma + 1):
        count[k] += count[k - 1]
    out = np.empty(n, np.int64)
    for q in range(n):
        i = first[q]
        out[count[a[i]]] = i
        count[a[i]] += 1
    return out


def _inside_supers(a: IntArray, ka: IntArray, cc: IntArray, kc: IntArray, ep: IntArray,
                   eroom: IntArray, es: IntArray, supers: IntArray, ma: int, mb: int,
                   out: BoolArray) -> None:
    """``_solve._inside_any``'s test, one way round, as one sweep over the first
    starts: ``out[i]`` set where configuration ``i`` (first start ``a`` reduced) lies
    inside one of ``supers`` (rows ``iA, kA, iC, kC``), cyclically.

    The configurations are read by first start, then by decreasing ``ka``
    (:func:`_by_start`); ``ep, eroom, es``: each super's entry at each first start
    ``p`` its first stretch covers (``p = iA + d``, the room left for ``ka``: ``kA -
    d``, the super), by ``p``, then by decreasing room.  At each ``p`` the supers whose
    room admits the configuration's ``ka`` are added in turn to ``reach`` (at each
    second start, the most interior vertices a second stretch starting there may have
    inside one of them), so each configuration is read once and each super once per
    first start it covers: the same test as reading, for every super, every
    configuration that starts in its first stretch (which is quadratic where hundreds
    of supers share long stretches)."""
    by = _by_start(a, ka, ma)
    n, m = by.size, ep.size
    reach = np.zeros(mb, np.int64)
    stamp = np.full(mb, -1, np.int64)
    i = 0
    e = 0
    while i < n:
        p = a[by[i]]
        j = i
        while j < n and a[by[j]] == p:
            j += 1
        while e < m and ep[e] < p:
            e += 1
        g = e
        for q in range(i, j):
            c = by[q]
            while g < m and ep[g] == p and eroom[g] >= ka[c]:
                s = es[g]
                iC, kC = supers[s, 2], supers[s, 3]
                for d in range(kC + 1):
                    x = (iC + d) % mb
                    if stamp[x] != p:
                        stamp[x] = p
                        reach[x] = kC - d
                    elif kC - d > reach[x]:
                        reach[x] = kC - d
                g += 1
            x = cc[c] % mb
            if stamp[x] == p and kc[c] <= reach[x]:
                out[c] = True
        i = j


def _single(A: IntArray, ax: FloatArray, ay: FloatArray, tx: FloatArray, ty: FloatArray,
            L: FloatArray, gx: FloatArray, va: FloatArray, bx: FloatArray, by: FloatArray,
            gy: FloatArray, order: IntArray, angle_b: FloatArray, width: float, Ub: FloatArray,
            sigma: float, eps: float, floor: float, collect: bool, same: bool, value: float,
            keep: int, ox: int, oy: int) -> Any:
    """Stretch 1 on one edge ``A``, stretch 2 with interior vertices ``p .. p+k-1``
    (``_windows_single`` of the numpy search, edge by edge).

    The interval of edge ``A`` against a vertex (the contacts on ``A`` that hold with
    both its normals: ``_Intervals.cells``, the same operations) is empty unless the
    two force directions are opposite within ``width``, so only those vertices are
    computed (``va``, ``angle_b``, ``order``: as in :func:`_vertex_runs`; ``gy`` in ring
    order here).  Returns the lower bounds ``(A, p, value)`` (the largest over ``k``)
    and, with ``collect``, the configurations whose bound reaches ``floor``.

    Without ``collect`` and with ``keep > 0`` (``A`` then longest first): an edge no
    longer than ``T`` is skipped, ``T`` the ``keep``-th largest of the lower bounds found
    so far, one per key (``min(ox + A, oy + p)``, the search's keys), or ``value`` if
    higher: its lower bounds are at most its length, never above the search's final
    ``keep``-th value, so the floor they give is the same."""
    mb = bx.size
    topv = np.zeros(max(keep, 1))
    topk = np.full(max(keep, 1), -1, np.int64)
    lo = np.full(mb, 0.0)
    hi = np.full(mb, -np.inf)
    touched = np.empty(mb, np.int64)
    cap = 1024
    wa, wp, wv = np.empty(cap, np.int64), np.empty(cap, np.int64), np.empty(cap)
    oA, oC, okC = np.empty(cap, np.int64), np.empty(cap, np.int64), np.empty(cap, np.int64)
    n_w, n_out = 0, 0
    for e in A:
        if not collect and keep > 0 and L[e] <= max(value, topv[0]):
            continue
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
                if keep > 0:
                    _top_add(topv, topk, min(ox + e, oy + p), best)
        for j in range(nt):                 # the columns back to empty
            lo[touched[j]], hi[touched[j]] = 0.0, -np.inf
    return wa[:n_w], wp[:n_w], wv[:n_w], oA[:n_out], oC[:n_out], okC[:n_out]
