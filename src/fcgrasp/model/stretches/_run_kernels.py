"""Compiled loops of the two-finger stretch search: the runs of True of each row of the
vertex matrix ``M`` (:func:`_vertex_runs_tree` under a tree of bounds,
:func:`_vertex_runs` the window scan kept as its reference) and the growable arrays they
fill.

Plain Python compiled by :mod:`fcgrasp.model.stretches._kernels` (one namespace for every
loop of the search, so that compiled loops call compiled ones); the search calls them
through that module's wrappers."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...core._checks import BoolArray, FloatArray, IntArray


def _grow(a: FloatArray | IntArray, n: int) -> Any:
    """``a`` with room for at least ``n`` elements (doubling)."""
    if n <= a.size:
        return a
    out = np.empty(max(n, 2 * a.size), a.dtype)
    out[:a.size] = a
    return out


def _append(first: IntArray, last: IntArray, n: int, a: int, b: int) -> Any:
    first, last = _grow(first, n + 1), _grow(last, n + 1)
    first[n], last[n] = a, b
    return first, last


def _in_order(c: Any, mark: BoolArray) -> Any:
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


def _cell(ax: FloatArray, ay: FloatArray, gx: FloatArray, v: int, bx: FloatArray, by: FloatArray,
          gy: FloatArray, q: int) -> Any:
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


def _column_tree(bx: FloatArray, by: FloatArray, gy: FloatArray, angle: FloatArray) -> Any:
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


def _vertex_runs_tree(ax: FloatArray, ay: FloatArray, gx: FloatArray, va: FloatArray,
                      bx: FloatArray, by: FloatArray, gy: FloatArray, angle: FloatArray,
                      width: float, pad: float) -> Any:
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
