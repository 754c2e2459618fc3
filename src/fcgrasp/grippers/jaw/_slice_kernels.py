"""Compiled loops of the parallel jaw: the holding pieces of the pose grid's cells along
the offset (:func:`_slices_loop`: where each cell's verdict changes, from the pads'
features read as affine pieces).

Plain Python compiled by :mod:`._kernels` (one namespace for every loop of the jaw, so
that compiled loops call compiled ones), whose wrappers the jaw calls; the numpy model
stays the reference."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ._pose_kernels import K_MAX, _pose_one
from ._proof_kernels import _nan_max, _nan_min


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
