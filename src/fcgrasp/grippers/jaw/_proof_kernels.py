"""Compiled loops of the parallel jaw: the proofs of boxes of poses (:func:`_prove_loop`,
:func:`_certify_loop`: every pose of an angle and offset box holds, by interval bounds
of the pads' features, with subdivision).

Plain Python compiled by :mod:`._kernels` (one namespace for every loop of the jaw, so
that compiled loops call compiled ones), whose wrappers the jaw calls; the numpy model
stays the reference."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ...core.tolerances import ROUND_TOL
from ._pose_kernels import K_MAX, _pose_one

_TWO_PI = 2.0 * math.pi


#: Relative room left by the shortcuts of :func:`_candidates` (bounds that skip work only
#: where the full test must fail by more than rounding).
_SLACK = ROUND_TOL


def _sin_range(a: float, b: float, t0: float, t1: float) -> tuple[float, float]:
    """``_poses._sin_range`` of numbers: the exact range of ``a cos t + b sin t`` over
    ``[t0, t1]``."""
    return _range(a, b, math.hypot(a, b), math.atan2(b, a), t0, t1, math.cos(t0),
                  math.sin(t0), math.cos(t1), math.sin(t1))


def _range(a: float, b: float, r: float, phi: float, t0: float, t1: float, c0: float,
           s0: float, c1: float, s1: float) -> tuple[float, float]:
    """:func:`_sin_range` given ``r = hypot(a, b)``, ``phi = atan2(b, a)`` and the
    cosines and sines of ``t0``, ``t1`` (the same numbers, computed once)."""
    v0 = a * c0 + b * s0
    v1 = a * c1 + b * s1
    has_max = _wrap_positive(phi - t0) <= t1 - t0
    has_min = _wrap_positive(phi + math.pi - t0) <= t1 - t0
    return (-r if has_min else min(v0, v1)), (r if has_max else max(v0, v1))


def _wrap_positive(x: float) -> float:
    """``x % (2 pi)`` (numpy's ``mod``, to the last bit) without ``fmod`` where
    ``-4 pi <= x < 2 pi``: there ``x + 2 pi`` is exact for ``x <= -2 pi`` (Sterbenz), and
    ``fmod`` would return ``x`` itself, then add ``2 pi`` once if negative."""
    if x >= _TWO_PI or x < -2 * _TWO_PI:
        return x % _TWO_PI
    if x < -_TWO_PI:
        x = x + _TWO_PI
    return x + _TWO_PI if x < 0 else x


def _polar(x: Any, y: Any) -> Any:
    """Rows ``(x, y, hypot, atan2)`` (n, 4) of the vectors ``(x, y)``, for :func:`_range`."""
    out = np.empty((x.shape[0], 4))
    for k in range(x.shape[0]):
        out[k, 0], out[k, 1] = x[k], y[k]
        out[k, 2], out[k, 3] = math.hypot(x[k], y[k]), math.atan2(y[k], x[k])
    return out


def _vrange(v: Any, k: int, t0: float, t1: float, trig: Any) -> tuple[float, float]:
    """:func:`_range` of row ``k`` of a :func:`_polar` table."""
    return _range(v[k, 0], v[k, 1], v[k, 2], v[k, 3], t0, t1, trig[0], trig[1], trig[2],
                  trig[3])


def _nan_min(x: float, y: float) -> float:
    """numpy's ``minimum``: NaN if either is."""
    return x + y if (x != x or y != y) else min(x, y)


def _nan_max(x: float, y: float) -> float:
    """numpy's ``maximum``: NaN if either is."""
    return x + y if (x != x or y != y) else max(x, y)


def _candidates(box: Any, trig: Any, ids: Any, n: int, a: Any, b: Any, nrm: Any,
                uniq: Any, inv: Any, sign: float, internal: bool, ahead: Any, half: float,
                zero: float, contact_tol: float, ys: Any, xs: Any, dxr: Any, dy: Any,
                fn: Any, ranges: Any, vmask: Any, touched: Any, facing: Any, p0: Any,
                p1: Any, centre: Any, hw: Any, x_known: bool, pool: Any
                ) -> tuple[float, float, int]:
    """``_certify._pad_candidates`` for one box ``(t0, t1, c0, c1)`` (``trig``: the
    cosines and sines of its ends) over the edges ``ids[:n]`` (increasing; every edge
    that may meet the strip over the box among them): the first :data:`K_MAX` candidate
    contacts into ``p0``, ``p1`` (K, 2), ``centre``, ``hw`` (K,) in the numpy order
    (vertices by their unique index, then the cuts by the strip's side ``-half``, then
    ``+half``, each by edge), and ``(lower, high, count)``: the bounds of the pad's stop
    and how many candidates there are.  :func:`_polar` tables: ``ys``, ``xs`` (2m) the
    heights (``sign`` times) and lateral positions of the edges' ends (starts, then
    ends), ``dxr``, ``dy`` (m) of the edges' directions, ``fn`` (m) of the normals this
    pad's facing is read from.  ``ranges`` (2m, 4): the ends' lateral and height
    ranges over the box, the lateral ones already there with ``x_known`` (the same for
    both pads);  ``vmask`` (U,; all False, left so), ``touched`` (2m,), ``facing``
    (m, 2): scratch.  ``pool`` (6,): every candidate pooled (``_certify._pooled``),
    the box of their points ``(x_lo, x_hi, y_lo, y_hi)`` and the arc of their forces
    from the pad's face ``(lo, hi)``."""
    t0, t1, c0, c1 = box[0], box[1], box[2], box[3]
    m = a.shape[0]
    lower = -np.inf
    for k in range(n):
        for idx in (ids[k], m + ids[k]):
            y_lo, y_hi = _vrange(ys, idx, t0, t1, trig)
            if not x_known:
                ranges[idx, 0], ranges[idx, 1] = _vrange(xs, idx, t0, t1, trig)
            ranges[idx, 2], ranges[idx, 3] = y_lo, y_hi
    # which edges the pad may meet (maybe) and surely faces (surely); per edge
    tm, cm = (t0 + t1) / 2, (c0 + c1) / 2
    sin_m, cos_m = math.sin(tm), math.cos(tm)
    w_y, w_u = -np.inf, -1          # the dominating vertex (``_certify._dominated``)
    for k in range(n):
        e = ids[k]
        f_lo, f_hi = _vrange(fn, e, t0, t1, trig)
        if internal:
            if -sign > 0:
                maybe, surely = f_hi > 0 and ahead[e], f_lo > 0 and ahead[e]
            else:
                maybe, surely = f_lo < 0 and ahead[e], f_hi < 0 and ahead[e]
        else:
            maybe, surely = f_hi > contact_tol, True
        facing[e, 0], facing[e, 1] = maybe, surely
        for idx in (e, m + e):
            if surely and ranges[idx, 0] >= c1 - half and ranges[idx, 1] <= c0 + half:
                lower = _nan_max(lower, ranges[idx, 2])
                y = ranges[idx, 2]
                if y > w_y or (y == w_y and inv[idx] < w_u):
                    w_y, w_u = y, inv[idx]
        xa_m = -a[e, 0] * sin_m + a[e, 1] * cos_m
        xb_m = -b[e, 0] * sin_m + b[e, 1] * cos_m
        dx_m = xb_m - xa_m
        tt = (cm - xa_m) / dx_m if abs(dx_m) > 0 else np.nan
        if surely and tt >= 0 and tt <= 1:
            qx = a[e, 0] + tt * (b[e, 0] - a[e, 0])
            qy = a[e, 1] + tt * (b[e, 1] - a[e, 1])
            # its height's lower bound is at most its height at either end angle: only
            # a point that may raise the running bound is looked at
            y_end = min(sign * qx * trig[0] + sign * qy * trig[1],
                        sign * qx * trig[2] + sign * qy * trig[3])
            if not y_end > lower - _SLACK * (abs(lower) + abs(y_end)):
                continue
            px_lo, px_hi = _range(qy, -qx, math.hypot(qy, -qx), math.atan2(-qx, qy), t0,
                                  t1, trig[0], trig[1], trig[2], trig[3])
            if px_lo >= c1 - half and px_hi <= c0 + half:
                sx, sy = sign * qx, sign * qy
                py_lo, _ = _range(sx, sy, math.hypot(sx, sy), math.atan2(sy, sx), t0, t1,
                                  trig[0], trig[1], trig[2], trig[3])
                lower = _nan_max(lower, py_lo)
    high = -np.inf
    n_touched = 0
    for k in range(n):
        for idx in (ids[k], m + ids[k]):
            if facing[idx % m, 0] and ranges[idx, 1] >= c0 - half \
                    and ranges[idx, 0] <= c1 + half and ranges[idx, 3] >= lower \
                    and not _below(uniq, w_u, uniq[inv[idx], 0], uniq[inv[idx], 1], sign,
                                   t0, t1, 2 * zero):
                if not vmask[inv[idx]]:
                    vmask[inv[idx]] = True
                    touched[n_touched] = inv[idx]
                    n_touched += 1
                high = _nan_max(high, ranges[idx, 3])
    count = 0
    face = (t0 + t1) / 2 + (0.0 if sign < 0 else math.pi)
    pool[0], pool[1], pool[2], pool[3] = np.inf, -np.inf, np.inf, -np.inf
    pool[4], pool[5] = np.inf, -np.inf
    for u in np.sort(touched[:n_touched]):
        vmask[u] = False
        _pool_add(pool, uniq[u, 0], uniq[u, 1], uniq[u, 0], uniq[u, 1], 0.0,
                  (t1 - t0) / 2)
        if count < K_MAX:
            p0[count, 0], p0[count, 1] = uniq[u, 0], uniq[u, 1]
            p1[count, 0], p1[count, 1] = uniq[u, 0], uniq[u, 1]
            centre[count], hw[count] = face, (t1 - t0) / 2
        count += 1
    for side in (-half, half):
        s_lo, s_hi = c0 + side, c1 + side
        for k in range(n):
            e = ids[k]
            if not facing[e, 0]:
                continue
            xa_lo, xa_hi = ranges[e, 0], ranges[e, 1]
            e_lo, e_hi = min(xa_lo, ranges[m + e, 0]), max(xa_hi, ranges[m + e, 1])
            if not (e_hi >= s_lo and e_lo <= s_hi):
                continue
            dxr_lo, dxr_hi = _vrange(dxr, e, t0, t1, trig)
            dy_lo, dy_hi = _vrange(dy, e, t0, t1, trig)
            rise = (1 if dy_lo > 0 else (-1 if dy_hi < 0 else 0)) \
                * (1 if dxr_lo >= -zero else (-1 if dxr_hi <= zero else 0))
            if rise * (1.0 if side > 0 else -1.0) < 0:      # the edge falls there
                continue
            if dxr_lo <= 0 and dxr_hi >= 0:
                t_lo, t_hi = 0.0, 1.0
            else:
                q0, q1 = (s_lo - xa_hi) / dxr_lo, (s_hi - xa_lo) / dxr_lo
                q2, q3 = (s_lo - xa_hi) / dxr_hi, (s_hi - xa_lo) / dxr_hi
                t_lo = _nan_max(0.0, _nan_min(_nan_min(q0, q1), _nan_min(q2, q3)))
                t_hi = _nan_min(1.0, _nan_max(_nan_max(q0, q1), _nan_max(q2, q3)))
            if not t_lo <= t_hi:
                continue
            ex, ey = b[e, 0] - a[e, 0], b[e, 1] - a[e, 1]
            x0, y0 = a[e, 0] + t_lo * ex, a[e, 1] + t_lo * ey
            x1, y1 = a[e, 0] + t_hi * ex, a[e, 1] + t_hi * ey
            # a height is at most the point's distance from the centroid: a cut that
            # cannot reach the bound is dropped before its angles are looked at
            reach = max(math.hypot(x0, y0), math.hypot(x1, y1))
            if reach < lower - _SLACK * (abs(lower) + reach):
                continue
            h0 = _range(sign * x0, sign * y0, math.hypot(sign * x0, sign * y0),
                        math.atan2(sign * y0, sign * x0), t0, t1, trig[0], trig[1],
                        trig[2], trig[3])[1]
            h1 = _range(sign * x1, sign * y1, math.hypot(sign * x1, sign * y1),
                        math.atan2(sign * y1, sign * x1), t0, t1, trig[0], trig[1],
                        trig[2], trig[3])[1]
            hh = max(h0, h1)
            if not hh >= lower:
                continue
            if _below(uniq, w_u, x0, y0, sign, t0, t1, 2 * zero) \
                    and _below(uniq, w_u, x1, y1, sign, t0, t1, 2 * zero):
                continue
            high = _nan_max(high, hh)
            force = math.atan2(-nrm[e, 1], -nrm[e, 0])
            _pool_add(pool, x0, y0, x1, y1, (force - face + math.pi) % _TWO_PI - math.pi, 0.0)
            if count < K_MAX:
                p0[count, 0], p0[count, 1] = x0, y0
                p1[count, 0], p1[count, 1] = x1, y1
                centre[count], hw[count] = force, 0.0
            count += 1
    # (the pool's arc from the face, as an absolute centre and half-width)
    lo, hi = pool[4], pool[5]
    pool[4], pool[5] = face + (lo + hi) / 2, (hi - lo) / 2
    return lower, high, count


def _pool_add(pool: Any, x0: float, y0: float, x1: float, y1: float, rel: float,
              half: float) -> None:
    """Add the segment ``(x0, y0)-(x1, y1)`` and the force arc ``rel +- half`` (from the
    pad's face) to the pool of :func:`_candidates`."""
    pool[0] = min(pool[0], x0, x1)
    pool[1] = max(pool[1], x0, x1)
    pool[2] = min(pool[2], y0, y1)
    pool[3] = max(pool[3], y0, y1)
    pool[4] = min(pool[4], rel - half)
    pool[5] = max(pool[5], rel + half)


def _below(uniq: Any, w: int, px: float, py: float, sign: float, t0: float, t1: float,
           gap: float) -> bool:
    """``_certify._dominated`` for one point: lower than the dominating vertex ``uniq[w]``
    (none: ``w`` -1) by more than ``gap`` at every angle of ``[t0, t1]``."""
    if w < 0:
        return False
    d_lo, _ = _sin_range(sign * (uniq[w, 0] - px), sign * (uniq[w, 1] - py), t0, t1)
    return d_lo > gap


def _corners_hold(pa: Any, na: int, pb: Any, nb: int, turn: float, ca: float, ha: float,
                  cb: float, hb: float, beta: float, tol: float) -> bool:
    """``_certify._pairs_hold`` for one pair of candidates (or pools), given by the
    corners of their convex point sets ``pa[:na]``, ``pb[:nb]``: the smallest arc
    holding the differences of the corners (``_arc_of``; the first, ``pb[0] - pa[0]``,
    its reference), each force within ``beta`` of every chord's direction."""
    a0 = math.atan2(pb[0, 1] - pa[0, 1], pb[0, 0] - pa[0, 0])
    lo, hi = 0.0, 0.0
    shortest = np.inf
    for i in range(na):
        for j in range(nb):
            vx, vy = pb[j, 0] - pa[i, 0], pb[j, 1] - pa[i, 1]
            rel = (math.atan2(vy, vx) - a0 + math.pi) % _TWO_PI - math.pi
            lo, hi = min(lo, rel), max(hi, rel)
            shortest = min(shortest, math.hypot(vx, vy))
    if hi - lo >= math.pi - tol or shortest <= 0:
        return False
    d, hd = a0 + (lo + hi) / 2, (hi - lo) / 2
    if abs((d + turn - ca + math.pi) % _TWO_PI - math.pi) + hd + ha >= beta:
        return False
    return abs((d + math.pi + turn - cb + math.pi) % _TWO_PI - math.pi) + hd + hb < beta


def _as_corners(out: Any, k: int, p0: Any, p1: Any, pool: Any) -> int:
    """The corners of candidate ``k`` (its segment's two ends) into ``out``, or, with
    ``k`` -1, of the pool's box (four): how many."""
    if k >= 0:
        out[0, 0], out[0, 1] = p0[k, 0], p0[k, 1]
        out[1, 0], out[1, 1] = p1[k, 0], p1[k, 1]
        return 2
    out[0, 0], out[0, 1] = pool[0], pool[2]
    out[1, 0], out[1, 1] = pool[1], pool[2]
    out[2, 0], out[2, 1] = pool[0], pool[3]
    out[3, 0], out[3, 1] = pool[1], pool[3]
    return 4


class _Tables:
    """(Documentation only: what :func:`_tables` returns, in order.)  The polar tables of
    the fixed vectors (:func:`_polar`): the ends' heights for pads A and B, their
    lateral positions, the edges' directions (lateral, and heights per pad), the normals
    each pad's facing is read from; then the scratch of :func:`_candidates` and
    :func:`_prove_box` (the pads' pools and their corners last)."""


def _tables(a: Any, b: Any, nrm: Any, uniq: Any, internal: bool) -> Any:
    """The tables :func:`_prove_box` reads (see :class:`_Tables`)."""
    m = a.shape[0]
    ends = np.concatenate((a, b))
    sa, sb = (-1.0, 1.0) if internal else (1.0, -1.0)
    ys_a = _polar(sa * ends[:, 0], sa * ends[:, 1])
    ys_b = _polar(sb * ends[:, 0], sb * ends[:, 1])
    xs = _polar(ends[:, 1], -ends[:, 0])
    ex, ey = b[:, 0] - a[:, 0], b[:, 1] - a[:, 1]
    dxr = _polar(ey, -ex)
    dy_a, dy_b = _polar(sa * ex, sa * ey), _polar(sb * ex, sb * ey)
    if internal:
        fn_a = _polar(-nrm[:, 0], -nrm[:, 1])
        fn_b = fn_a
    else:
        fn_a = _polar(sa * nrm[:, 0], sa * nrm[:, 1])
        fn_b = _polar(sb * nrm[:, 0], sb * nrm[:, 1])
    return (ys_a, ys_b, xs, dxr, dy_a, dy_b, fn_a, fn_b, np.empty((2 * m, 4)),
            np.zeros(uniq.shape[0], dtype=np.bool_), np.empty(2 * m, dtype=np.int64),
            np.empty((m, 2), dtype=np.bool_), np.ones(m, dtype=np.bool_),
            np.ones(m, dtype=np.bool_), np.empty(4), np.zeros((4, K_MAX, 2)),
            np.zeros((4, K_MAX)), np.empty((2, 6)), np.empty((2, 4, 2)))


def _prove_box(box: Any, ids: Any, n: int, a: Any, b: Any, nrm: Any, uniq: Any,
               inv: Any, half: float, zero: float, contact_tol: float, tol: float,
               internal: bool, q: Any, beta: float, stroke0: float, stroke1: float,
               tables: Any, x_known: bool, pooled: bool) -> tuple[bool, float, float]:
    """``_certify._box_proofs_numpy`` for one box over the edges ``ids[:n]``: whether it
    is proved (both pads' candidates few, or ``pooled``, the opening's enclosure within
    the stroke, every pair of candidates force closure over the box, a pad with more
    than :data:`K_MAX` read as their pool; inside a hole, the closed jaws' segment free;
    the centre pose is the caller's) and that enclosure."""
    (ys_a, ys_b, xs, dxr, dy_a, dy_b, fn_a, fn_b, ranges, vmask, touched, facing, up,
     down, trig, pts, arcs, pools, corners) = tables
    m = a.shape[0]
    sa, sb = (-1.0, 1.0) if internal else (1.0, -1.0)
    t0, t1, c0, c1 = box[0], box[1], box[2], box[3]
    trig[0], trig[1], trig[2], trig[3] = (math.cos(t0), math.sin(t0), math.cos(t1),
                                          math.sin(t1))
    free = True
    if internal:
        yq_lo, yq_hi = _sin_range(q[0], q[1], t0, t1)
        for k in range(n):
            e = ids[k]
            ya_lo, ya_hi = _sin_range(a[e, 0], a[e, 1], t0, t1)
            yb_lo, yb_hi = _sin_range(b[e, 0], b[e, 1], t0, t1)
            xa_lo, xa_hi = _vrange(xs, e, t0, t1, trig)
            xb_lo, xb_hi = _vrange(xs, m + e, t0, t1, trig)
            meet = max(xa_hi, xb_hi) >= c0 - half and min(xa_lo, xb_lo) <= c1 + half
            up[e] = min(ya_lo, yb_lo) > yq_hi
            down[e] = max(ya_hi, yb_hi) < yq_lo
            if meet and not up[e] and not down[e]:
                free = False
    pa0, pa1, pb0, pb1 = pts[0], pts[1], pts[2], pts[3]
    ca, ha, cb, hb = arcs[0], arcs[1], arcs[2], arcs[3]
    lo_a, hi_a, n_a = _candidates(box, trig, ids, n, a, b, nrm, uniq, inv, sa, internal,
                                  up, half, zero, contact_tol, ys_a, xs, dxr, dy_a, fn_a,
                                  ranges, vmask, touched, facing, pa0, pa1, ca, ha, x_known,
                                  pools[0])
    lo_b, hi_b, n_b = _candidates(box, trig, ids, n, a, b, nrm, uniq, inv, sb, internal,
                                  down, half, zero, contact_tol, ys_b, xs, dxr, dy_b, fn_b,
                                  ranges, vmask, touched, facing, pb0, pb1, cb, hb, True,
                                  pools[1])
    ok = free and lo_a > -np.inf and n_a >= 1 and lo_b > -np.inf and n_b >= 1 \
        and (pooled or (n_a <= K_MAX and n_b <= K_MAX))
    al, ah = _nan_min(sa * lo_a, sa * hi_a), _nan_max(sa * lo_a, sa * hi_a)
    bl, bh = _nan_min(sb * lo_b, sb * hi_b), _nan_max(sb * lo_b, sb * hi_b)
    o_lo, o_hi = al - bh, ah - bl
    ok = ok and stroke0 <= o_lo and o_hi <= stroke1
    turn = math.pi if internal else 0.0
    # each pad's items: its candidates, or -1 for their pool
    items_a = n_a if n_a <= K_MAX else 1
    items_b = n_b if n_b <= K_MAX else 1
    for i in range(items_a if ok else 0):
        ia = i if n_a <= K_MAX else -1
        k_a = _as_corners(corners[0], ia, pa0, pa1, pools[0])
        c_a, h_a = (ca[i], ha[i]) if ia >= 0 else (pools[0, 4], pools[0, 5])
        for j in range(items_b):
            jb = j if n_b <= K_MAX else -1
            k_b = _as_corners(corners[1], jb, pb0, pb1, pools[1])
            c_b, h_b = (cb[j], hb[j]) if jb >= 0 else (pools[1, 4], pools[1, 5])
            if not _corners_hold(corners[0], k_a, corners[1], k_b, turn, c_a, h_a, c_b,
                                 h_b, beta, tol):
                ok = False
                break
        if not ok:
            break
    return ok, o_lo, o_hi


def _prove_loop(boxes: Any, a: Any, b: Any, nrm: Any, uniq: Any, inv: Any, half: float,
                zero: float, contact_tol: float, tol: float, internal: bool, q: Any,
                beta: float, stroke0: float, stroke1: float, pooled: bool, proved: Any,
                o_lo: Any, o_hi: Any) -> None:
    """:func:`_prove_box` for each box of a batch, over every edge."""
    tables = _tables(a, b, nrm, uniq, internal)
    ids = np.arange(a.shape[0])
    for k in range(boxes.shape[0]):
        proved[k], o_lo[k], o_hi[k] = _prove_box(
            boxes[k], ids, ids.shape[0], a, b, nrm, uniq, inv, half, zero, contact_tol, tol,
            internal, q, beta, stroke0, stroke1, tables, False, pooled)


#: Levels of halving the depth-first proof goes to (a box halved this often is below
#: the floats' resolution: it is not proved).
MAX_DEPTH = 120


def _certify_loop(boxes: Any, a: Any, b: Any, nrm: Any, uniq: Any, inv: Any, half: float,
                  zero: float, contact_tol: float, tol: float, internal: bool, q: Any,
                  beta: float, stroke0: float, stroke1: float, pooled: bool, max_boxes: int,
                  radius: float, near: float, round_tol: float, out: Any) -> None:
    """``_certify.certify_box``'s subdivision, depth first: each box is proved
    (:func:`_prove_box`) or its centre pose is decided (:func:`_pose_one`: a failing
    one ends the proof, as it would end numpy's) and it is halved along its longer side
    (the angle range as the arc it sweeps at ``radius``).  Each box reads only the edges
    of its parent that may meet its strip (within ``near``), gathered per depth.  The
    boxes examined are those of numpy's breadth-first search, in another order, so the
    answer is the same: ``out = (proved, lo, hi, boxes examined)`` with ``proved`` 0
    when more than ``max_boxes`` boxes are needed or a centre pose fails."""
    m = a.shape[0]
    tables = _tables(a, b, nrm, uniq, internal)
    xs, ranges = tables[2], tables[8]
    lists = np.empty((MAX_DEPTH + 1, m), dtype=np.int64)
    counts = np.zeros(MAX_DEPTH + 1, dtype=np.int64)
    ga, gb, gf = np.empty((m, 2)), np.empty((m, 2)), np.empty((m, 2))
    for e in range(m):
        lists[0, e] = e
    counts[0] = m
    top, bottom = np.empty(1), np.empty(1)
    ok_a, ok_b, holds = np.zeros(1, np.bool_), np.zeros(1, np.bool_), np.zeros(1, np.bool_)
    lat_a, lat_b = np.empty((1, K_MAX, 2)), np.empty((1, K_MAX, 2))
    psi_a, psi_b = np.empty((1, K_MAX)), np.empty((1, K_MAX))
    col_a, col_b = np.empty((1, K_MAX), np.int64), np.empty((1, K_MAX), np.int64)
    slacks = np.empty((1, 2 * K_MAX * K_MAX + 2))
    scratch = np.empty((4, m))
    box = np.empty(4)
    trig = np.empty(4)
    stack = [(boxes[k, 0], boxes[k, 1], boxes[k, 2], boxes[k, 3], 1)
             for k in range(boxes.shape[0] - 1, -1, -1)]
    lo_open, hi_open = np.inf, -np.inf
    done = 0
    out[0] = 0.0
    while len(stack):
        t0, t1, c0, c1, depth = stack.pop()
        done += 1
        out[3] = done
        if done > max_boxes or depth > MAX_DEPTH:
            return
        box[0], box[1], box[2], box[3] = t0, t1, c0, c1
        trig[0], trig[1], trig[2], trig[3] = (math.cos(t0), math.sin(t0), math.cos(t1),
                                              math.sin(t1))
        # the parent's edges that may meet this box's strip (their ends' lateral ranges
        # kept for the proof)
        n = 0
        for k in range(counts[depth - 1]):
            e = lists[depth - 1, k]
            xa_lo, xa_hi = _vrange(xs, e, t0, t1, trig)
            xb_lo, xb_hi = _vrange(xs, m + e, t0, t1, trig)
            if max(xa_hi, xb_hi) >= c0 - half - near and min(xa_lo, xb_lo) <= c1 + half + near:
                lists[depth, n] = e
                n += 1
                ranges[e, 0], ranges[e, 1] = xa_lo, xa_hi
                ranges[m + e, 0], ranges[m + e, 1] = xb_lo, xb_hi
        counts[depth] = n
        ids = lists[depth]
        ok, o_lo, o_hi = _prove_box(box, ids, n, a, b, nrm, uniq, inv, half, zero,
                                    contact_tol, tol, internal, q, beta, stroke0, stroke1,
                                    tables, True, pooled)
        if internal or not ok:
            for k in range(n):
                e = ids[k]
                ga[k, 0], ga[k, 1] = a[e, 0], a[e, 1]
                gb[k, 0], gb[k, 1] = b[e, 0], b[e, 1]
                gf[k, 0], gf[k, 1] = -nrm[e, 0], -nrm[e, 1]
            _pose_one(0, (t0 + t1) / 2, (c0 + c1) / 2, ga[:n], gb[:n], gf[:n], half, zero,
                      internal, q, stroke0, stroke1, beta, -1.0 if internal else 1.0,
                      round_tol, top, bottom, ok_a, ok_b, lat_a, lat_b, psi_a, psi_b,
                      col_a, col_b, holds, slacks, scratch)
            if not holds[0]:
                return
        if ok:
            lo_open, hi_open = min(lo_open, o_lo), max(hi_open, o_hi)
            continue
        mt, mc = (t0 + t1) / 2, (c0 + c1) / 2
        if (t1 - t0) * radius >= c1 - c0:
            stack.append((mt, t1, c0, c1, depth + 1))
            stack.append((t0, mt, c0, c1, depth + 1))
        else:
            stack.append((t0, t1, mc, c1, depth + 1))
            stack.append((t0, t1, c0, mc, depth + 1))
    out[0], out[1], out[2] = 1.0, lo_open, hi_open
