"""Compiled loops of the two-finger stretch search for large rings (part of
:mod:`fcgrasp.model.stretches`).

The numpy search of :mod:`fcgrasp.model._stretch_windows` holds the vertex matrix ``M``
as ``m_a x m_b`` booleans and widens every window of rows at once; on a 10,000-edge
outline that is 10^8 cells per mode and hundreds of passes over every row's runs.  These
loops do the same work row by row, with nothing of size ``m_a x m_b`` in memory:

* :func:`vertex_runs_tree` finds the runs of True of each row of ``M`` for both modes
  (squeeze ``M+`` and expand ``M-``: the expand test of a cell is the squeeze test with
  the chord reversed, so the same eight cross products, with the opposite sign) under a
  tree of bounds over ring b's columns: a block of columns whose cells surely all hold,
  or surely all fail, is decided at once, and only the blocks along a run's ends are
  read cell by cell, with the arithmetic of :func:`vertex_runs` (the window scan that
  reads every cell of a row's window of angles, kept as the reference), so the runs
  agree bit for bit;
* :func:`windows` widens one row's window of interior vertices at a time, intersecting
  its runs with the next row's (two monotone pointers over two sorted lists of runs),
  and stops as soon as no run is long enough to reach the bound: the lower bound of
  each first row (its vertex-aligned stretches), or the configurations whose bound
  reaches the floor, enumerated only over the start vertices that can reach it.  A
  sparse table of the rows' runs (the runs common to every window of ``2^j`` rows)
  gives any window's runs in two look-ups: the lower bounds are read only for the rows
  whose upper bound (found by bisection over the window's length) can still raise the
  search's floor, and the configurations from each row's first window long enough to
  reach it.  On a smooth outline of ``n`` edges both are ``O(n log n)``.

numba is imported on first use (the machine code cached on disk beside this file); the
search uses these loops only on rings large enough to repay it
(:data:`fcgrasp.model.stretches.KERNEL_CELLS`), and ``FCGRASP_JIT=0`` never does.
"""

from __future__ import annotations

import hashlib
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


def _cell(ax: Any, ay: Any, gx: Any, v: int, bx: Any, by: Any, gy: Any, q: int) -> Any:
    """Cell ``(v, q)`` of the vertex matrix: the least and the largest of the eight cross
    products ``cross(g, d)`` of the chord ``d`` from vertex ``v`` to vertex ``q``
    (without a branch: ``M+`` holds where all are >= 0, ``M-`` where all are <= 0, the
    chord reversed), and whether the chord has a length.  The scan and the tree's
    leaves both read cells through it, so they agree bit for bit."""
    d0, d1 = bx[q] - ax[v], by[q] - ay[v]
    lo_c, hi_c = np.inf, -np.inf
    for j in range(4):
        c = gx[v, j, 0] * d1 - gx[v, j, 1] * d0
        lo_c, hi_c = min(lo_c, c), max(hi_c, c)
        c = gy[q, j, 0] * d1 - gy[q, j, 1] * d0
        lo_c, hi_c = min(lo_c, c), max(hi_c, c)
    return lo_c, hi_c, (d0 != 0.0) | (d1 != 0.0)


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
                    lo_c, hi_c, moved = _cell(ax, ay, gx, v, bx, by, gy, q)
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


#: Columns per leaf of the tree of :func:`_vertex_runs_tree` (read cell by cell).
_LEAF = 16


def _column_tree(bx: Any, by: Any, gy: Any, angle: Any) -> Any:
    """Bounds over blocks of consecutive columns (a complete binary tree over blocks of
    :data:`_LEAF`, node 1 the root, node ``i``'s children ``2i`` and ``2i + 1``): per node
    its box of points, its range of force angles and, per generator ``j`` of ring b, the
    ranges of the generator's two components and of ``cross(g, b)``.  Empty nodes hold
    an empty range (``+inf`` below ``-inf``)."""
    mb = bx.size
    nblocks = (mb + _LEAF - 1) // _LEAF
    size = 1
    while size < nblocks:
        size *= 2
    lo = np.full((2 * size, 15), np.inf)     # bx by angle (g0x g0y c0) x 4
    hi = np.full((2 * size, 15), -np.inf)
    for q in range(mb):
        node = size + q // _LEAF
        vals = np.empty(15)
        vals[0], vals[1], vals[2] = bx[q], by[q], angle[q]
        for j in range(4):
            vals[3 + 3 * j] = gy[q, j, 0]
            vals[4 + 3 * j] = gy[q, j, 1]
            vals[5 + 3 * j] = gy[q, j, 0] * by[q] - gy[q, j, 1] * bx[q]
        for t in range(15):
            lo[node, t] = min(lo[node, t], vals[t])
            hi[node, t] = max(hi[node, t], vals[t])
    for node in range(size - 1, 0, -1):
        for t in range(15):
            lo[node, t] = min(lo[2 * node, t], lo[2 * node + 1, t])
            hi[node, t] = max(hi[2 * node, t], hi[2 * node + 1, t])
    return lo, hi, size


def _vertex_runs_tree(ax: Any, ay: Any, gx: Any, va: Any, bx: Any, by: Any, gy: Any,
                      angle: Any, width: float, pad: float) -> Any:
    """:func:`_vertex_runs` without reading every cell of a row's window: ring b's
    columns in their own order (``angle`` their force angles, not sorted), under a tree
    of bounds (:func:`_column_tree`).  A node whose every cell surely holds (each cross
    product's lower bound above ``pad``, every angle inside the window) is one run; one
    whose every cell surely fails is skipped; a leaf in between is read cell by cell
    with :func:`_vertex_runs`'s own arithmetic, so the runs are the same bit for bit
    (the bounds only decide which cells need reading; ``pad`` is far above their
    rounding).  On a smooth outline a row reads the nodes along the ends of its runs:
    ``O(log n)`` instead of the window's ``O(n)``."""
    ma, mb = ax.size, bx.size
    lo, hi, size = _column_tree(bx, by, gy, angle)
    ptr = (np.zeros(ma + 1, np.int64), np.zeros(ma + 1, np.int64))
    fp, lp = np.empty(4 * ma + 16, np.int64), np.empty(4 * ma + 16, np.int64)
    fm, lm = np.empty(4 * ma + 16, np.int64), np.empty(4 * ma + 16, np.int64)
    counts = np.zeros(2, np.int64)
    stack = np.empty(64, np.int64)
    # one row's ranges of holding columns, in column order (disjoint: at most mb)
    rf, rl = np.empty(mb + 1, np.int64), np.empty(mb + 1, np.int64)
    wlo, whi = np.empty(3), np.empty(3)
    for v in range(ma):
        if np.isnan(va[v]):
            ptr[0][v + 1], ptr[1][v + 1] = counts[0], counts[1]
            continue
        for t in range(3):
            wlo[t] = va[v] + 2 * np.pi * (t - 1) - width
            whi[t] = va[v] + 2 * np.pi * (t - 1) + width
        for s in range(2):
            sign = 1.0 if s == 0 else -1.0
            nr = 0
            stack[0] = 1
            top = 1
            while top > 0:
                top -= 1
                node = stack[top]
                if lo[node, 0] > hi[node, 0]:
                    continue                    # an empty node
                # the window of angles
                w_all, w_none = width >= np.pi, width < np.pi
                if width < np.pi:
                    for t in range(3):
                        if lo[node, 2] >= wlo[t] and hi[node, 2] <= whi[t]:
                            w_all = True
                        if not (hi[node, 2] < wlo[t] or lo[node, 2] > whi[t]):
                            w_none = False
                if w_none:
                    continue
                # bounds of sign * cross(g, b - a) over the node, for the eight g
                # least: the smallest lower bound (every product surely >= it); fail:
                # the smallest upper bound (some product surely below it everywhere)
                least, fail = np.inf, np.inf
                for j in range(4):
                    g0, g1 = gx[v, j, 0], gx[v, j, 1]
                    # g0 (by - ay) - g1 (bx - ax): linear over the box
                    c_lo = min(g0 * lo[node, 1], g0 * hi[node, 1]) \
                        - max(g1 * lo[node, 0], g1 * hi[node, 0]) - (g0 * ay[v] - g1 * ax[v])
                    c_hi = max(g0 * lo[node, 1], g0 * hi[node, 1]) \
                        - min(g1 * lo[node, 0], g1 * hi[node, 0]) - (g0 * ay[v] - g1 * ax[v])
                    if sign < 0:
                        c_lo, c_hi = -c_hi, -c_lo
                    least, fail = min(least, c_lo), min(fail, c_hi)
                    # cross(h, b) - h0 ay + h1 ax, h ranging over its box
                    k = 3 + 3 * j
                    c_lo = lo[node, k + 2] - max(lo[node, k] * ay[v], hi[node, k] * ay[v]) \
                        + min(lo[node, k + 1] * ax[v], hi[node, k + 1] * ax[v])
                    c_hi = hi[node, k + 2] - min(lo[node, k] * ay[v], hi[node, k] * ay[v]) \
                        + max(lo[node, k + 1] * ax[v], hi[node, k + 1] * ax[v])
                    if sign < 0:
                        c_lo, c_hi = -c_hi, -c_lo
                    least, fail = min(least, c_lo), min(fail, c_hi)
                if fail < -pad:
                    continue                    # a product surely negative everywhere
                # the node's columns
                first_block, n_blocks = node, 1
                while first_block < size:
                    first_block, n_blocks = 2 * first_block, 2 * n_blocks
                c0 = (first_block - size) * _LEAF
                c1 = min((first_block - size + n_blocks) * _LEAF, mb) - 1
                if w_all and least > pad:
                    rf[nr], rl[nr] = c0, c1     # every cell holds
                    nr += 1
                elif node >= size:
                    for q in range(c0, c1 + 1):     # a leaf: cell by cell
                        inside = width >= np.pi
                        for t in range(3):
                            inside |= (angle[q] >= wlo[t]) & (angle[q] <= whi[t])
                        if not inside:
                            continue
                        lo_c, hi_c, moved = _cell(ax, ay, gx, v, bx, by, gy, q)
                        if moved & ((lo_c >= 0.0) if s == 0 else (hi_c <= 0.0)):
                            rf[nr], rl[nr] = q, q
                            nr += 1
                else:
                    if top + 2 > stack.size:
                        stack = _grow(stack, top + 2)
                    stack[top] = 2 * node + 1   # the left child is read first
                    stack[top + 1] = 2 * node
                    top += 2
            # adjacent ranges are one run
            j = 0
            while j < nr:
                e = j
                while e + 1 < nr and rf[e + 1] == rl[e] + 1:
                    e += 1
                if s == 0:
                    fp, lp = _append(fp, lp, counts[0], rf[j], rl[e])
                else:
                    fm, lm = _append(fm, lm, counts[1], rf[j], rl[e])
                counts[s] += 1
                j = e + 1
        ptr[0][v + 1], ptr[1][v + 1] = counts[0], counts[1]
    return ptr[0], fp[:counts[0]], lp[:counts[0]], ptr[1], fm[:counts[1]], lm[:counts[1]]


def _intersect(a0: int, a1: int, fa: Any, la: Any, b0: int, b1: int, fb: Any, lb: Any,
               out_f: Any, out_l: Any, n: int) -> Any:
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


def _run_table(ptr: Any, first: Any, last: Any, ma: int, levels: int) -> Any:
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


def _window_of(tptr: Any, tf: Any, tl: Any, r: int, k: int, ma: int, cs: Any, ce: Any) -> Any:
    """The runs of the AND of rows ``r .. r + k - 1`` (cyclic) into ``cs``, ``ce``, read
    from the sparse table: their count."""
    j = 0
    while (2 << j) <= k:
        j += 1
    r2 = (r + k - (1 << j)) % ma
    cs, ce, n = _intersect(tptr[j, r], tptr[j, r + 1], tf, tl, tptr[j, r2], tptr[j, r2 + 1],
                           tf, tl, cs, ce, 0)
    return n


def _cyclic(cs: Any, ce: Any, nc: int, mb: int, rp0: Any, rlen: Any) -> int:
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


def _measures(rp0: Any, rlen: Any, nr: int, mb: int, Ub: Any) -> Any:
    """The most any stretch 2 inside these cyclic runs reaches (its edges), and the
    longest vertex-aligned one (its interior vertices)."""
    reach, vert = 0.0, 0.0
    for j in range(nr):
        jb = (rp0[j] - 1) % mb + mb
        reach = max(reach, Ub[jb + min(rlen[j], mb - 1) + 1] - Ub[jb])
        vert = max(vert, Ub[jb + min(rlen[j], mb - 2)] - Ub[jb + 1])
    return reach, vert


def _row_bound(tptr: Any, tf: Any, tl: Any, r: int, ma: int, mb: int, k_max: int, Ua: Any,
               Ub: Any, cs: Any, ce: Any, rp0: Any, rlen: Any) -> float:
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


def _copy_columns(a0: float, a1: float, ex: Any, exs: Any, app: Any) -> int:
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


def _copies_from(c0: float, c1: float, ex: Any, exs: Any, app: Any, n_app: int) -> bool:
    """Whether the stretch 2 ``[c0, c1]`` makes a copy with a stretch 1 whose columns
    are ``app`` (:func:`_copy_columns`): some column's threshold on ring b below
    ``exs[4]`` as well, so the configuration's least threshold (the larger of the two)
    is."""
    for j in range(n_app):
        if _copy_side(c0, c1, ex, exs, 1, app[j]):
            return True
    return False


def _copy_side(a0: float, a1: float, ex: Any, exs: Any, side: int, c: int) -> bool:
    """Whether column ``c`` of ``ex`` leaves the stretch ``[a0, a1]`` on ring ``side``
    (0: a) a threshold below ``exs[4]``, its arc there longer than that threshold."""
    u = 2 * side
    ta = _side_threshold(a0, a1, ex[u, c], ex[u + 1, c], exs[side], exs[2], exs[3])
    return bool(ta < exs[4] and ex[u + 1, c] - ex[u, c] > ta)


def _copy_run(p: int, room: int, ext_s: float, run_end: int, Ub: Any, mb: int, ex: Any,
              exs: Any, app: Any, n_app: int) -> int:
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


def _copy_until(p: int, d: int, c0: float, ext_s: float, run_end: int, Ub: Any, mb: int,
                ex: Any, exs: Any, app: Any, n_app: int) -> bool:
    """Whether every stretch 2 from the starts ``p .. p + d`` is a copy: they lie in the
    span from ``p``'s start ``c0`` to the last edge a stretch from ``p + d`` reaches
    (:func:`_window_row`'s ``q_hi``: as far as ``ext_s`` past its start's edge, within
    the run's end ``run_end`` and short of the ring)."""
    q = min(np.searchsorted(Ub, Ub[p + d] + ext_s, side="right") - 1, run_end,
            p + d + mb - 3)
    return _copy_span(c0, c0 + (Ub[q + 1] - Ub[p - 1]), ex, exs, app, n_app)


def _copy_span(c0: float, c1: float, ex: Any, exs: Any, app: Any, n_app: int) -> bool:
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
    """``_stretch_exclusion._Exclusion.threshold``'s length of one side: the stretch
    ``[a0, a1]``'s arc outside ``[u0, u1]`` (:func:`_outside_one`) plus ``tol``, over
    ``keep`` (the same operations)."""
    return (_outside_one(a0, a1, u0, u1, per) + tol) / keep


def _window_row(r: int, k: int, nc: int, cs: Any, ce: Any, ns: Any, ne: Any, rp0: Any,
                rlen: Any, ptr: Any, first: Any, last: Any, Ua: Any, Ub: Any, ma: int,
                mb: int, floor: float, collect: bool, same: bool, best: Any, thresh: float,
                oA: Any, okA: Any, oC: Any, okC: Any, n_out: int, ex: Any, exs: Any,
                gallop: bool) -> Any:
    """Row ``r`` of :func:`_windows` from window length ``k`` on (its runs ``cs``,
    ``ce``: the AND of rows ``r .. r + k - 1``).  Without ``collect`` the widening stops
    once no window can beat ``max(best[r], thresh)``.  With ``collect`` and kept plans'
    arcs ``ex`` (:func:`_copy_columns`), the configurations that are surely a kept
    plan's copy at any smallest region from ``exs[4]`` on are not collected
    (:func:`_copies_from`); with ``gallop``, the starts of stretch 2 whose every
    stretch is a copy are passed over in runs (:func:`_copy_run`), else one by one
    (the reference)."""
    i = (r - 1) % ma + ma
    n_ex = ex.shape[1]
    app = np.empty(n_ex, np.int64)
    while k < ma - 1 and nc > 0:
        ext_s = Ua[i + k + 1] - Ua[i]
        inner_s = Ua[i + k] - Ua[i + 1]
        # the kept plans whose arc on ring a holds this stretch 1 closely enough that
        # its configurations are copies wherever stretch 2 is close to their other arc
        n_app = 0
        if collect and n_ex > 0 and ext_s >= floor:
            a0 = Ua[(r - 1) % ma]
            n_app = _copy_columns(a0, a0 + ext_s, ex, exs, app)
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
                jb = (rp0[j] - 1) % mb
                c0 = Ub[jb]
                if _copies_from(c0, c0 + (Ub[jb + mb + rlen[j] + 1] - Ub[jb + mb]), ex,
                                exs, app, n_app):
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
                n_new = n_out + q_hi - q_lo + 1
                oA, okA = _grow(oA, n_new), _grow(okA, n_new)
                oC, okC = _grow(oC, n_new), _grow(okC, n_new)
                for q in range(q_lo, q_hi + 1):
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


def _top_add(topv: Any, topk: Any, key: int, v: float) -> None:
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


def _every_row(ptr: Any, first: Any, last: Any, Ua: Any, Ub: Any, ma: int, mb: int,
               floor: float, collect: bool, same: bool, ex: Any, exs: Any, gallop: bool,
               r0: int, r1: int) -> Any:
    """:func:`_windows` reading every row of ``r0 .. r1 - 1`` from its first window on."""
    best = np.zeros(ma)
    cs, ce, ns, ne, rp0, rlen, oA, okA, oC, okC = _buffers(mb)
    n_out = 0
    for r in range(r0, r1 if ptr[ma] > 0 else r0):  # no runs: no window
        nc = 0
        for q in range(ptr[r], ptr[r + 1]):
            cs[nc], ce[nc] = first[q], last[q]
            nc += 1
        oA, okA, oC, okC, n_out = _window_row(
            r, 1, nc, cs, ce, ns, ne, rp0, rlen, ptr, first, last, Ua, Ub, ma, mb,
            floor, collect, same, best, 0.0, oA, okA, oC, okC, n_out, ex, exs, gallop)
    return best, oA[:n_out], okA[:n_out], oC[:n_out], okC[:n_out]


def _table(ptr: Any, first: Any, last: Any, ma: int) -> Any:
    """:func:`_run_table` with as many levels as a window of ``ma - 2`` rows needs."""
    levels = 1
    while (1 << levels) <= ma - 2:
        levels += 1
    return _run_table(ptr, first, last, ma, levels)


def _windows(ptr: Any, first: Any, last: Any, Ua: Any, Ub: Any, ma: int, mb: int,
             floor: float, collect: bool, same: bool, value: float, keep: int,
             short: int, ex: Any, exs: Any, gallop: bool, r0: int, r1: int, tptr: Any,
             tf: Any, tl: Any, levels: int) -> Any:
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
                floor, collect, same, best, 0.0, oA, okA, oC, okC, n_out, ex, exs, gallop)
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
            floor, collect, same, best, thresh, oA, okA, oC, okC, n_out, ex, exs, gallop)
        _top_add(top, top_rows, r, best[r])
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


def _window_boxes_shared(edge: Any, start: Any, count: Any, ax: Any, ay: Any, tx: Any,
                         ty: Any, L: Any, gx: Any, bx: Any, by: Any, gy: Any, sigma: float,
                         eps: float) -> Any:
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


def _window_boxes_memo(edge: Any, start: Any, count: Any, ax: Any, ay: Any, tx: Any,
                       ty: Any, L: Any, gx: Any, bx: Any, by: Any, gy: Any, sigma: float,
                       eps: float, tlo: Any, thi: Any) -> Any:
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


def _outside_one(a0: float, a1: float, u0: float, u1: float, per: float) -> float:
    """``_stretch_exclusion._Exclusion._outside`` of one stretch ``[a0, a1]`` and one arc
    ``[u0, u1]``: the same operations in the same order."""
    common = 0.0
    for j in range(3):
        shift = (-per, 0.0, per)[j]
        common += max(0.0, min(a1, u1 + shift) - max(a0, u0 + shift))
    return (a1 - a0) - common


def _exclusion_rows(a0x: Any, a1x: Any, a0y: Any, a1y: Any, ax0: Any, ax1: Any, ay0: Any,
                    ay1: Any, perx: float, pery: float, tol: float, keep: float,
                    mask: Any, masked: bool, out: Any) -> None:
    """``_stretch_exclusion._Exclusion.threshold``: ``out`` lowered to each configuration's least
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
    two of them inside (-inf: no region).  ``_stretch_exclusion._Exclusion._least_excess`` of
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


def _similar_rows(sx: Any, sy: Any, ax0: Any, ax1: Any, ay0: Any, ay1: Any, perx: float,
                  pery: float, tol: float, f: float, t: Any, mask: Any, masked: bool,
                  out: Any) -> None:
    """``_stretch_exclusion._Exclusion.similar``: ``out[r]`` set where, for some kept plan's
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


def _by_start(a: Any, ka: Any, ma: int) -> Any:
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


def _inside_supers(a: Any, ka: Any, cc: Any, kc: Any, ep: Any, eroom: Any, es: Any,
                   supers: Any, ma: int, mb: int, out: Any) -> None:
    """``_stretch_solve._inside_any``'s test, one way round, as one sweep over the first
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


def _single(A: Any, ax: Any, ay: Any, tx: Any, ty: Any, L: Any, gx: Any, va: Any,
            bx: Any, by: Any, gy: Any, order: Any, angle_b: Any, width: float, Ub: Any,
            sigma: float, eps: float, floor: float, collect: bool, same: bool,
            value: float, keep: int, ox: int, oy: int) -> Any:
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


#: Steps :func:`_below` takes at most along the lower bounds of ``t``.
_BELOW_STEPS = 16


def _below(el: Any, m: int, floor: float, tol: float, eps: float) -> bool:
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


def _solve_rows(rows: Any, ub: Any, tol: float, eps: float, floor: float = 0.0) -> Any:
    """``_stretch_lp._solve`` one configuration at a time: the same Fourier-Motzkin
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
            tie: float, order: Any, keep: Any, check: Any) -> None:
    """:func:`fcgrasp.model._stretch_search._own_optimum` of one job, without its matrix of
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
                   same: bool, tie: float, keep: Any, check: Any) -> bool:
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


#: Cells of the own-optimum filter's tables (:func:`_group_tables`) above which it
#: scans configurations by start instead (:func:`_beaten`).
TABLE_CELLS = 50_000_000


_LOOPS = CompiledLoops(globals(), (_grow, _append, _in_order, _cell, _vertex_runs, _column_tree,
                                   _vertex_runs_tree, _intersect, _run_table, _window_of,
                                   _cyclic, _measures, _row_bound, _copy_columns, _copies_from,
                                   _copy_run, _copy_until, _copy_span,
                                   _copy_side, _side_threshold, _table,
                                   _window_row, _buffers,
                                   _every_row, _top_add, _windows,
                                   _interval, _window_boxes, _window_boxes_shared,
                                   _window_boxes_memo, _single,
                                   _below, _solve_rows, _by_start, _inside_supers, _outside_one,
                                   _exclusion_rows, _excess_at, _least_excess, _surely_copy,
                                   _similar_rows,
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


def available() -> bool:
    """Do the compiled loops run here (loaded now, on first use)?  Not with
    ``FCGRASP_JIT=0`` or without a working numba."""
    return _LOOPS.available()


def loaded() -> bool:
    """Whether this process has loaded the compiled loops (then they cost nothing more)."""
    return _LOOPS.loaded


def vertex_runs(ax: Any, ay: Any, gx: Any, va: Any, bx: Any, by: Any, gy: Any, order: Any,
                angle_b: Any, width: float) -> Any:
    """Compiled :func:`_vertex_runs`."""
    return _load()["_vertex_runs"](ax, ay, gx, va, bx, by, gy, order, angle_b, float(width))


def vertex_runs_tree(ax: Any, ay: Any, gx: Any, va: Any, bx: Any, by: Any, gy: Any,
                     angle: Any, width: float, pad: float) -> Any:
    """Compiled :func:`_vertex_runs_tree`."""
    return _load()["_vertex_runs_tree"](ax, ay, gx, va, bx, by, gy, angle, float(width),
                                        float(pad))


#: Rows of ring a :func:`vertex_runs_blocks` reads at a time (a block of a 100,000-edge
#: noisy outline's rows takes a few tenths of a second at mu 1.0).
VERTEX_ROWS = 4096


def vertex_runs_blocks(ax: Any, ay: Any, gx: Any, va: Any, bx: Any, by: Any, gy: Any,
                       angle: Any, width: float, pad: float, between: Any) -> Any:
    """:func:`vertex_runs_tree` over blocks of :data:`VERTEX_ROWS` rows, calling
    ``between`` before each block after the first (a budget's clock may end it there):
    the same runs (each row's runs depend on that row alone)."""
    ma = ax.size
    if ma <= VERTEX_ROWS:
        return vertex_runs_tree(ax, ay, gx, va, bx, by, gy, angle, width, pad)
    parts = []
    for r0 in range(0, ma, VERTEX_ROWS):
        if r0:
            between()
        r1 = min(r0 + VERTEX_ROWS, ma)
        parts.append(vertex_runs_tree(ax[r0:r1].copy(), ay[r0:r1].copy(),
                                      np.ascontiguousarray(gx[r0:r1]), va[r0:r1].copy(),
                                      bx, by, gy, angle, width, pad))
    out = []
    for s in (0, 3):
        ptr, first, last = [np.zeros(1, np.int64)], [], []
        for part in parts:
            ptr.append(part[s][1:] + ptr[-1][-1])
            first.append(part[s + 1])
            last.append(part[s + 2])
        out += [np.concatenate(ptr), np.concatenate(first), np.concatenate(last)]
    return tuple(out)


def vertex_runs_scan(ax: Any, ay: Any, gx: Any, va: Any, bx: Any, by: Any, gy: Any,
                     angle: Any, width: float, pad: float) -> Any:
    """:func:`vertex_runs_tree`'s runs by the window scan (:func:`vertex_runs`, the
    previous kernel, kept as the reference; ``pad`` unused): ring b sorted by angle."""
    order = np.argsort(angle, kind="stable")
    return vertex_runs(ax, ay, gx, va, bx[order], by[order], gy[order], order,
                       angle[order], width)


def windows(ptr: Any, first: Any, last: Any, Ua: Any, Ub: Any, ma: int, mb: int,
            floor: float, collect: bool, same: bool, value: float = 0.0, keep: int = 0,
            short: int = _SHORT, ex: Any = None, exs: Any = None, between: Any = None,
            cap: int | None = None, gallop: bool = True) -> Any:
    """Compiled :func:`_windows` (index arrays made contiguous: one compiled signature
    for every caller; ``ex``, ``exs``: no kept plans where not given).  ``between``: a
    collection reads the rows in blocks (:data:`COLLECT_ROWS`, the sparse table built
    once) and calls it before each (a budget's check may end the collection there);
    ``cap``: a collection that holds more windows than this after a block ends there
    (:class:`~fcgrasp.core.budget.BudgetExhausted`, ``"collection"``); ``gallop``
    False: every start of stretch 2 read one by one (:func:`_window_row`'s reference)."""
    loops = _load()
    ptr, first, last = (np.ascontiguousarray(x, np.int64) for x in (ptr, first, last))
    ex = np.zeros((4, 0)) if ex is None else np.ascontiguousarray(ex, float)
    exs = np.zeros(5) if exs is None else np.ascontiguousarray(exs, float)
    args = (ptr, first, last, Ua, Ub, ma, mb, float(floor), collect, same, float(value),
            int(keep), int(short), ex, exs, bool(gallop))
    none = (np.zeros((0, 0), np.int64), np.zeros(0, np.int64), np.zeros(0, np.int64), 0)
    if not collect or between is None:
        return loops["_windows"](*args, 0, ma, *none)
    table = loops["_table"](ptr, first, last, ma) if ma >= 4 and ptr[ma] > 0 else none
    parts = []
    held = 0
    for r0 in range(0, ma, COLLECT_ROWS):
        between()
        parts.append(loops["_windows"](*args, r0, min(r0 + COLLECT_ROWS, ma), *table))
        held += int(parts[-1][1].size)
        if cap is not None and held > cap:
            from ..core.budget import BudgetExhausted

            raise BudgetExhausted("collection")
    return (parts[0][0], *(np.concatenate([p[j] for p in parts]) for j in range(1, 5)))


#: Rows of a block of a collection of :func:`windows`, with a budget check before each:
#: a block of a smooth 10,000-edge outline's collection takes at most a few tenths of a
#: second, and a ring of fewer rows is one block.
COLLECT_ROWS = 256


def single(*args: Any) -> Any:
    """Compiled :func:`_single`."""
    return _load()["_single"](*args)


def solve_rows(rows: Any, ub: Any, tol: float, eps: float, floor: float = 0.0) -> Any:
    """Compiled :func:`_solve_rows`."""
    return _load()["_solve_rows"](np.ascontiguousarray(rows, float), np.asarray(ub, float),
                                 float(tol), float(eps), float(floor))


def window_boxes(*args: Any) -> Any:
    """Compiled :func:`_window_boxes`."""
    return _load()["_window_boxes"](*args)


def exclusion_rows(*args: Any) -> None:
    """Compiled :func:`_exclusion_rows`."""
    _load()["_exclusion_rows"](*args)


def similar_rows(*args: Any) -> None:
    """Compiled :func:`_similar_rows`."""
    _load()["_similar_rows"](*args)


def inside_supers(*args: Any) -> None:
    """Compiled :func:`_inside_supers`."""
    _load()["_inside_supers"](*args)


def window_boxes_shared(*args: Any) -> Any:
    """Compiled :func:`_window_boxes_shared`."""
    return _load()["_window_boxes_shared"](*args)


def window_boxes_memo(*args: Any) -> Any:
    """Compiled :func:`_window_boxes_memo`."""
    return _load()["_window_boxes_memo"](*args)


def beaten(c: Any, t: Any, ma: int, mb: int, same: bool, tie: float,
           check: Any = None) -> Any:
    """Compiled :func:`_beaten` of configurations ``c`` (F, 4: first start, its interior
    vertices, second start, its interior vertices) with smallest regions ``t``: the
    ones to keep (with ``check``, a mask, only those rows are decided; every row is a
    beater)."""
    c = np.array(c, np.int64)
    c[:, 0] %= ma                               # starts as ring positions
    c[:, 2] %= mb
    t = np.ascontiguousarray(t, float)
    check = np.ones(len(c), bool) if check is None else np.ascontiguousarray(check, bool)
    if len(c) < BEATEN_MEMO_ROWS:
        return _beaten_keep(c, t, ma, mb, same, tie, check)
    # the rounds of a distinct search ask again about the same configurations, in
    # another order: each one's answer depends on the set only, so the set is
    # remembered sorted
    o = np.lexsort((t, c[:, 3], c[:, 2], c[:, 1], c[:, 0]))
    h = hashlib.blake2b(np.ascontiguousarray(c[o]).tobytes(), digest_size=16)
    h.update(np.ascontiguousarray(t[o]).tobytes())
    h.update(np.ascontiguousarray(check[o]).tobytes())
    h.update(repr((int(ma), int(mb), bool(same), float(tie))).encode())
    digest = h.digest()
    if digest in _beaten_memo:
        keep = np.empty(len(c), bool)
        keep[o] = _beaten_memo[digest]
        return keep
    keep = _beaten_keep(c, t, ma, mb, same, tie, check)
    _beaten_memo[digest] = keep[o]
    while len(_beaten_memo) > BEATEN_MEMO_SIZE:
        del _beaten_memo[next(iter(_beaten_memo))]
    return keep


#: Configurations from which :func:`beaten` remembers its answer (by a digest of its
#: arguments), and how many answers it keeps.
BEATEN_MEMO_ROWS, BEATEN_MEMO_SIZE = 50_000, 4
_beaten_memo: dict[bytes, np.ndarray] = {}


def _beaten_keep(c: Any, t: Any, ma: int, mb: int, same: bool, tie: float,
                 check: Any) -> Any:
    """:func:`beaten` of ring positions ``c``, computed."""
    keep = np.ones(len(c), bool)
    cols = [np.ascontiguousarray(c[:, j]) for j in range(4)]
    if _load()["_beaten_tables"](*cols, t, int(ma), int(mb), bool(same), float(tie), keep,
                                 check):
        return keep
    order = np.lexsort((-t, c[:, 0]))           # by first start, then the longest first
    _load()["_beaten"](np.ascontiguousarray(c[:, 0]), np.ascontiguousarray(c[:, 1]),
                       np.ascontiguousarray(c[:, 2]), np.ascontiguousarray(c[:, 3]), t,
                       int(ma), int(mb), bool(same), float(tie), order.astype(np.int64),
                       keep, check)
    return keep
