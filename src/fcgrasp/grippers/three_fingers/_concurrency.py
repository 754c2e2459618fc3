r"""Three fingers with friction without a general LP solver (part of
:mod:`fcgrasp.grippers.three_fingers`).

A convex piece of concurrent grasps (:mod:`fcgrasp.grippers.three_fingers._concurrent`) asks,
for each corner grasp of a box of regions, for a witness point ``p`` inside three wedges: finger
``i`` at ``x_i`` gives the wedge ``x_i + sigma_i cone(D_i)``, two half-planes
``n_k . p >= n_k . x_i`` whose unit normals ``n_k`` are the arc's edges turned a quarter
turn (signed by the side).  Six half-planes of the plane meet iff every three of them do
(Helly's theorem in the plane), and three half-planes with normals ``n_1, n_2, n_3`` miss
each other iff their null combination ``lambda = (n_2 x n_3, n_3 x n_1, n_1 x n_2)`` is
of one sign and ``sum lambda_k n_k . x_k > 0`` (Farkas' lemma).  So the grasps of a
piece are, **in closed form**,

.. math:: \sum_i w_{T,i} \cdot x_i \le 0 \quad \text{for every triple } T \text{ with }
          \lambda_T \ge 0, \qquad w_{T,i} = \sum_{k \in T \text{ of finger } i}
          \lambda_k n_k ,

a handful of linear inequalities in the fingers' positions (the *concurrency region*,
the intersection of the planar sectors that theorem 4.2's positive span leaves; with
``lambda`` normalised to sum 1, shifting every half-plane inward by ``delta`` adds
``delta`` to each).  A box of regions lies in it iff, for each inequality, the sum over
the fingers of the largest ``w_{T,i} . x`` over finger ``i``'s region does: on one edge
``w.a + max(w.t lo, w.t hi)``, linear in the ends since ``lo <= hi``; along a stretch the
largest over its two variable ends and its interior vertices (an auxiliary variable per
finger and triple).  The witnesses are gone from the program: definition 7.1's max-min
over one piece is a linear program in the seven numbers ``lo, hi, level``, solved here by
a dense simplex with Bland's rule, compiled by numba (microseconds per piece, where the
sparse HiGHS program with its 16 witness coordinates took milliseconds).  The HiGHS
program of :func:`fcgrasp.grippers.three_fingers._concurrent._solve_blocks` is kept as the reference
(``FCGRASP_JIT=0``, and the tests' oracle); every answer here is checked against the
closed form at the returned ends before it is used.

The witnesses a :class:`~fcgrasp.grippers.three_fingers._concurrent.Piece` reports are computed
at the end, per corner grasp, as the point deepest inside the six half-planes (the best of the
twenty vertices of the 3-variable program ``max delta: n_k . p - delta >= n_k . x_k``).
"""

from __future__ import annotations

from itertools import product
from typing import Any

import numpy as np

from ...core import _simplex
from ...core._simplex import _lp_max
from ...core.jit import CompiledLoops
from ...core.tolerances import (
    CHECK_TOL,
    LP_TOL,
    NULL_TOL,
    PARALLEL_TOL,
    PIECE_TIE,
    ROUND_TOL,
    SIMPLEX_PIVOT,
)

__all__ = ["available", "solve", "best_rows", "witnesses", "facets", "MAXMIN", "FREE",
           "GROW", "DEEP"]

#: Objectives (as :func:`fcgrasp.grippers.three_fingers._concurrent._solve_blocks` has them): the
#: largest common level; with fixed lengths, the largest level of the free regions; one
#: region as long as it can be; the witnesses as deep inside the cones as they can be.
MAXMIN, FREE, GROW, DEEP = 0, 1, 2, 3


#: How the excess of a half turn is split between two arcs (as
#: :data:`fcgrasp.grippers.three_fingers._concurrent.SPLITS`), and the eight sides in its order.
SPLITS = (0.0, 0.5, 1.0)
_SIDES = np.array(list(product((1.0, -1.0), repeat=3)))
_TRIPLES = np.array([(i, j, k) for i in range(6) for j in range(i + 1, 6)
                     for k in range(j + 1, 6)], dtype=np.int64)


# ----------------------------------------------------------------------------- loops


def _normals(lo_ang: Any, hi_ang: Any, sigma: Any, nx: Any, ny: Any) -> None:
    """The six half-planes' unit normals of one piece, finger ``k // 2``: the low edge
    of its arc (``k`` even) and the high edge."""
    for i in range(3):
        for j in range(2):
            ang = lo_ang[i] if j == 0 else hi_ang[i]
            s = sigma[i] if j == 0 else -sigma[i]
            nx[2 * i + j] = -s * np.sin(ang)
            ny[2 * i + j] = s * np.cos(ang)


def _facets(nx: Any, ny: Any, triples: Any, W: Any) -> int:
    """The inequalities ``sum_i W[f, i] . x_i <= 0`` of the concurrency region (one per
    triple of half-planes with a null combination of one sign, normalised to sum 1);
    returns their number."""
    f = 0
    for t in range(triples.shape[0]):
        a, b, c = triples[t, 0], triples[t, 1], triples[t, 2]
        la = nx[b] * ny[c] - ny[b] * nx[c]
        lb = nx[c] * ny[a] - ny[c] * nx[a]
        lc = nx[a] * ny[b] - ny[a] * nx[b]
        big = max(abs(la), abs(lb), abs(lc))
        if big <= NULL_TOL:
            continue
        if la + lb + lc < 0:
            la, lb, lc = -la, -lb, -lc
        tol = -10 * NULL_TOL * big
        if la < tol or lb < tol or lc < tol:
            continue
        la, lb, lc = max(la, 0.0), max(lb, 0.0), max(lc, 0.0)
        tot = la + lb + lc
        for i in range(3):
            W[f, i, 0] = 0.0
            W[f, i, 1] = 0.0
        W[f, a // 2, 0] += la / tot * nx[a]
        W[f, a // 2, 1] += la / tot * ny[a]
        W[f, b // 2, 0] += lb / tot * nx[b]
        W[f, b // 2, 1] += lb / tot * ny[b]
        W[f, c // 2, 0] += lc / tot * nx[c]
        W[f, c // 2, 1] += lc / tot * ny[c]
        f += 1
    return f


def _facet_value(W: Any, f: int, i: int, px: float, py: float) -> float:
    return W[f, i, 0] * px + W[f, i, 1] * py


def _region_max(W: Any, f: int, i: int, a0: Any, t0: Any, a1: Any, t1: Any, lo: float,
                hi: float, inner: Any, start: int, count: int) -> float:
    """The largest ``W[f, i] . x`` over finger ``i``'s region (its two ends and its
    interior vertices)."""
    v = max(_facet_value(W, f, i, a0[i, 0] + lo * t0[i, 0], a0[i, 1] + lo * t0[i, 1]),
            _facet_value(W, f, i, a1[i, 0] + hi * t1[i, 0], a1[i, 1] + hi * t1[i, 1]))
    for k in range(start, start + count):
        v = max(v, _facet_value(W, f, i, inner[k, 0], inner[k, 1]))
    return v


def _solve_one(a0: Any, t0: Any, L0: Any, a1: Any, t1: Any, L1: Any, const: Any,
               istart: Any, icount: Any, inner: Any, lo_ang: Any, hi_ang: Any, sigma: Any,
               kind: int, fixed: Any, free: Any, grow: int, triples: Any, eps: float,
               feas: float, check: float, round_tol: float, order: bool, nx: Any, ny: Any,
               W: Any, out: Any) -> int:
    """One block's program (the objective ``kind``): ``out = (lo (3), hi (3), level)``;
    returns 0 when solved and checked against the closed form at its ends.  ``order``:
    fingers 0 and 1 share one feature, finger 0's region ending where finger 1's may
    begin at the earliest (``hi_0 <= lo_1``: disjoint regions)."""
    _normals(lo_ang, hi_ang, sigma, nx, ny)
    nf = _facets(nx, ny, triples, W)
    # variables: lo (3), hi (3), level, then one per (facet, stretch finger)
    nstretch = 0
    for i in range(3):
        if icount[i] > 0:
            nstretch += 1
    n = 7 + nf * nstretch
    rows = nf * (1 + 3 * nstretch) + 9 + 1 + 1       # the last: the order row
    A = np.zeros((rows, n))
    b = np.zeros(rows)
    m = 0
    zi = 7
    for f in range(nf):
        rf = m
        m += 1
        rhs = 0.0
        for i in range(3):
            wx, wy = W[f, i, 0], W[f, i, 1]
            if wx == 0.0 and wy == 0.0:
                continue
            alpha0 = wx * a0[i, 0] + wy * a0[i, 1]
            beta0 = wx * t0[i, 0] + wy * t0[i, 1]
            if icount[i] == 0:
                # one edge: w.a + max(beta lo, beta hi) = w.a + beta+ hi - beta- lo
                rhs -= alpha0
                if beta0 > 0:
                    A[rf, 3 + i] += beta0
                else:
                    A[rf, i] += beta0
                continue
            alpha1 = wx * a1[i, 0] + wy * a1[i, 1]
            beta1 = wx * t1[i, 0] + wy * t1[i, 1]
            zmin = min(alpha0, alpha0 + beta0 * L0[i])
            # z = zmin + z' >= every point's value; the facet sums the z
            A[rf, zi] = 1.0
            rhs -= zmin
            A[m, i] = beta0
            A[m, zi] = -1.0
            b[m] = zmin - alpha0
            m += 1
            A[m, 3 + i] = beta1
            A[m, zi] = -1.0
            b[m] = zmin - alpha1
            m += 1
            g = -np.inf
            for k in range(istart[i], istart[i] + icount[i]):
                g = max(g, wx * inner[k, 0] + wy * inner[k, 1])
            A[m, zi] = -1.0
            b[m] = zmin - g
            m += 1
            zi += 1
        if kind == DEEP:
            A[rf, 6] = 1.0              # every half-plane moved in by the level
        b[rf] = rhs
    for i in range(3):
        A[m, i] = 1.0
        b[m] = L0[i]
        m += 1
        A[m, 3 + i] = 1.0
        b[m] = L1[i]
        m += 1
        # the region's length: hi - lo + const
        if kind == MAXMIN or (kind == FREE and free[i]):     # level - (hi - lo) <= const
            A[m, 6] = 1.0
            A[m, 3 + i] = -1.0
            A[m, i] = 1.0
            b[m] = const[i]
        else:                                                # lo - hi <= const - fixed
            A[m, 3 + i] = -1.0
            A[m, i] = 1.0
            b[m] = const[i] - fixed[i] * (1 - round_tol)
        m += 1
    if order:                       # hi_0 - lo_1 <= 0: one feature, two regions apart
        A[m, 3] = 1.0
        A[m, 1] = -1.0
        m += 1
    A[m, 6] = 1.0
    if kind == DEEP:
        b[m] = 1.0
    else:
        top = 0.0
        for i in range(3):
            top = max(top, L0[i] + L1[i] + const[i])
        b[m] = top
    m += 1
    c = np.zeros(n)
    if kind == GROW:
        c[3 + grow] = 1.0
        c[grow] = -1.0
    else:
        c[6] = 1.0
    x = np.zeros(n)
    y = np.zeros(m)
    st = _lp_max(c, A, b, m, n, x, y, eps, feas)
    for j in range(7):
        out[j] = x[j]
    if st != 0:
        return st
    # the closed form at the ends found: every triple's inequality holds
    for f in range(nf):
        tot = 0.0
        for i in range(3):
            if W[f, i, 0] != 0.0 or W[f, i, 1] != 0.0:
                tot += _region_max(W, f, i, a0, t0, a1, t1, x[i], x[3 + i], inner,
                                   istart[i], icount[i])
        if kind == DEEP:
            tot += x[6]
        if tot > check:
            return 4
    for i in range(3):
        if x[3 + i] - x[i] + const[i] < -check:
            return 4
    if order and x[3] > x[1] + check:
        return 4
    # and, independently of the closed form, a witness for every corner grasp: a point
    # of its six half-planes (moved in by the level when deep)
    shift = x[6] if kind == DEEP else 0.0
    cx = np.empty(6)
    for c0 in range(2 + icount[0]):
        for c1 in range(2 + icount[1]):
            for c2 in range(2 + icount[2]):
                for k in range(6):
                    i = k // 2
                    j = c0 if i == 0 else (c1 if i == 1 else c2)
                    if j == 0:
                        qx, qy = a0[i, 0] + x[i] * t0[i, 0], a0[i, 1] + x[i] * t0[i, 1]
                    elif j == 1:
                        qx, qy = a1[i, 0] + x[3 + i] * t1[i, 0], a1[i, 1] + x[3 + i] * t1[i, 1]
                    else:
                        qx, qy = inner[istart[i] + j - 2, 0], inner[istart[i] + j - 2, 1]
                    cx[k] = nx[k] * qx + ny[k] * qy + shift
                if not _meet(nx, ny, cx, check):
                    return 5
    return 0


def _meet(nx: Any, ny: Any, c: Any, tol: float) -> bool:
    """Do the six half-planes ``n_k . p >= c_k`` have a common point (to ``tol``)?  A
    non-empty one with normals spanning the plane has a vertex, where two of the lines
    cross; with parallel normals only, the offsets along the normal decide."""
    for a in range(6):
        for b in range(a + 1, 6):
            det = nx[a] * ny[b] - ny[a] * nx[b]
            if abs(det) <= PARALLEL_TOL:
                continue
            px = (c[a] * ny[b] - ny[a] * c[b]) / det
            py = (nx[a] * c[b] - c[a] * nx[b]) / det
            worst = np.inf
            for k in range(6):
                worst = min(worst, nx[k] * px + ny[k] * py - c[k])
            if worst >= -tol:
                return True
    low, high = -np.inf, np.inf
    for k in range(6):
        if abs(nx[k] * ny[0] - ny[k] * nx[0]) > PARALLEL_TOL:
            return False                # spanning normals and no vertex: empty
        if nx[k] * nx[0] + ny[k] * ny[0] > 0:
            low = max(low, c[k])
        else:
            high = min(high, -c[k])
    return low <= high + tol


def _solve_loop(A0: Any, T0: Any, L0: Any, A1: Any, T1: Any, L1: Any, const: Any,
                istart: Any, icount: Any, inner: Any, lo_ang: Any, hi_ang: Any, sigma: Any,
                kind: int, fixed: Any, free: Any, grow: int, triples: Any, eps: float,
                feas: float, check: float, round_tol: float, order: Any, out: Any,
                status: Any) -> None:
    """Each block's program (:func:`_solve_one`): ``out[b]``, ``status[b]``."""
    nx = np.empty(6)
    ny = np.empty(6)
    W = np.empty((20, 3, 2))
    for blk in range(A0.shape[0]):
        status[blk] = _solve_one(A0[blk], T0[blk], L0[blk], A1[blk], T1[blk], L1[blk],
                                 const[blk], istart[blk], icount[blk], inner, lo_ang[blk],
                                 hi_ang[blk], sigma[blk], kind, fixed[blk], free[blk], grow,
                                 triples, eps, feas, check, round_tol, order[blk], nx, ny,
                                 W, out[blk])


def _row_arcs(center: Any, half: Any, margin: float, splits: Any, round_tol: float,
              lo_out: Any, hi_out: Any) -> int:
    """:func:`fcgrasp.grippers.three_fingers._concurrent.spanning_arcs` of one row, written as loops
    (the same expressions in the same order; a sub-arc found twice is kept twice):
    the arcs in ``lo_out[:k]``, ``hi_out[:k]``, returns ``k``."""
    turn = 2 * np.pi
    c = np.empty(3)
    w = np.empty(3)
    for i in range(3):
        c[i] = center[i] % turn
        w[i] = half[i] - margin
        if w[i] < 0:
            return 0
    limit = np.pi - margin
    cur = np.empty(3, np.int64)
    nxt = np.empty(3, np.int64)
    g = np.empty(3)
    wc = np.empty(3)
    wn = np.empty(3)
    ex = np.empty(3)
    lo = np.empty(3)
    hi = np.empty(3)
    pick = np.empty(3, np.int64)
    count = 0
    for order in range(2):
        cur[0], cur[1], cur[2] = (0, 1, 2) if order == 0 else (0, 2, 1)
        for i in range(3):
            nxt[i] = cur[(i + 1) % 3]
        for kk in range(4):
            k1 = 0 if kk < 2 else -1
            k2 = 0 if kk % 2 == 0 else -1
            g[0] = (c[nxt[0]] - c[cur[0]]) % turn + turn * k1
            g[1] = (c[nxt[1]] - c[cur[1]]) % turn + turn * k2
            g[2] = turn - g[0] - g[1]
            skip = False
            for i in range(3):
                wc[i], wn[i] = w[cur[i]], w[nxt[i]]
                if g[i] - wc[i] - wn[i] > limit:
                    skip = True
            if skip:
                continue
            nsplit = np.empty(3, np.int64)
            for i in range(3):
                ex[i] = max(g[i] + wc[i] + wn[i] - limit, 0.0)
                nsplit[i] = splits.shape[0] if ex[i] > 0 else 1
            for p0 in range(nsplit[0]):
                for p1 in range(nsplit[1]):
                    for p2 in range(nsplit[2]):
                        pick[0], pick[1], pick[2] = p0, p1, p2
                        for i in range(3):
                            lo[i] = -w[i]
                            hi[i] = w[i]
                        for i in range(3):
                            e = ex[i]
                            r = splits[pick[i]] if e > 0 else 0.0
                            x = min(max(r * e, e - 2 * wn[i]), 2 * wc[i])
                            lo[cur[i]] += x
                            hi[nxt[i]] -= e - x
                        if lo[0] <= hi[0] + round_tol and lo[1] <= hi[1] + round_tol \
                                and lo[2] <= hi[2] + round_tol:
                            for i in range(3):
                                lo_out[count, i] = c[i] + lo[i]
                                hi_out[count, i] = c[i] + max(hi[i], lo[i])
                            count += 1
    return count


def _best_rows(A: Any, T: Any, L: Any, center: Any, half: Any, margin: float, splits: Any,
               sides: Any, triples: Any, eps: float, feas: float, check: float,
               round_tol: float, tie: float, order: Any, level: Any, lo_ang: Any,
               hi_ang: Any, side: Any) -> None:
    """Per row of three single features (``A``, ``T`` (R, 3, 2), ``L`` (R, 3), in units
    of the part's size), its best piece
    (:func:`fcgrasp.grippers.three_fingers._concurrent._best_blocks`:
    every sub-arc of :func:`_row_arcs` with every side, the first with the largest
    smallest region): ``level[r]`` (-1 where none holds a grasp), the piece's arcs and
    side.  ``order[r]``: fingers 0 and 1 share their feature (regions apart, in order)."""
    nx = np.empty(6)
    ny = np.empty(6)
    W = np.empty((20, 3, 2))
    arc_lo = np.empty((2 * 4 * 27, 3))
    arc_hi = np.empty((2 * 4 * 27, 3))
    const = np.zeros(3)
    zero = np.zeros(3, np.int64)
    inner = np.zeros((1, 2))
    free = np.zeros(3, np.bool_)
    x = np.empty(7)
    vals = np.empty(arc_lo.shape[0] * sides.shape[0])
    for r in range(A.shape[0]):
        level[r] = -1.0
        k = _row_arcs(center[r], half[r], margin, splits, round_tol, arc_lo, arc_hi)
        ns = sides.shape[0]
        top = -np.inf
        for a in range(k):
            for s in range(ns):
                st = _solve_one(A[r], T[r], L[r], A[r], T[r], L[r], const, zero, zero, inner,
                                arc_lo[a], arc_hi[a], sides[s], MAXMIN, const, free, 0,
                                triples, eps, feas, check, round_tol, order[r], nx, ny, W,
                                x)
                vals[a * ns + s] = -np.inf
                if st == 0:
                    vals[a * ns + s] = min(x[3] - x[0], x[4] - x[1], x[5] - x[2])
                    top = max(top, vals[a * ns + s])
        if top == -np.inf:
            continue
        for q in range(k * ns):             # the first within the tie of the best
            if vals[q] >= top - tie:
                level[r] = vals[q]
                for i in range(3):
                    lo_ang[r, i] = arc_lo[q // ns, i]
                    hi_ang[r, i] = arc_hi[q // ns, i]
                    side[r, i] = sides[q % ns, i]
                break


def _simplex_loop() -> dict[str, Any] | None:
    """The loops call the simplex compiled once, in its own module (None without it:
    no numba, or ``FCGRASP_JIT=0``)."""
    simplex = _simplex.compiled()
    return None if simplex is None else {"_lp_max": simplex["_lp_max"]}


_LOOPS = CompiledLoops(globals(), (_normals, _facets, _facet_value, _region_max, _meet,
                                   _solve_one, _solve_loop, _row_arcs, _best_rows),
                       extra=_simplex_loop)


def available() -> bool:
    """Are three fingers with friction solved here (the compiled loops loaded, on first
    use)?  Always, but with ``FCGRASP_JIT=0`` or without a working numba: then by the
    HiGHS programs.  Not a matter of size, so that a plan does not depend on what the
    process did before (the two solvers may place regions differently where the optimum
    is not unique)."""
    return _LOOPS.available()


def solve(blocks: list[Any], kind: int = MAXMIN, fixed: Any = None, free: Any = None,
          grow: int = 0) -> tuple[np.ndarray, np.ndarray] | None:
    """Solve the programs of ``blocks``
    (:class:`~fcgrasp.grippers.three_fingers._concurrent._Block`,
    positions in units of the part's size) for the objective ``kind``: ``(x (B, 7),
    ok (B,))`` with ``x = (lo (3), hi (3), level)``, ``ok`` where it is solved and the
    closed form holds at its ends; None when the compiled loops cannot run (numba
    missing or broken: the caller solves them by HiGHS)."""
    if _LOOPS.get() is None:
        return None
    B = len(blocks)
    A0 = np.array([blk.a0 for blk in blocks], float).reshape(B, 3, 2)
    T0 = np.array([blk.t0 for blk in blocks], float).reshape(B, 3, 2)
    L0 = np.array([blk.L0 for blk in blocks], float).reshape(B, 3)
    A1 = np.array([blk.a1 for blk in blocks], float).reshape(B, 3, 2)
    T1 = np.array([blk.t1 for blk in blocks], float).reshape(B, 3, 2)
    L1 = np.array([blk.L1 for blk in blocks], float).reshape(B, 3)
    const = np.array([blk.const for blk in blocks], float).reshape(B, 3)
    counts = np.array([[len(p) for p in blk.inner] for blk in blocks], np.int64).reshape(B, 3)
    starts = np.concatenate([[0], np.cumsum(counts.ravel())[:-1]]).reshape(B, 3)
    pts = [p for blk in blocks for p in blk.inner if len(p)]
    inner = np.concatenate(pts).astype(float) if pts else np.zeros((1, 2))
    lo_ang = np.array([blk.lo_ang for blk in blocks], float).reshape(B, 3)
    hi_ang = np.array([blk.hi_ang for blk in blocks], float).reshape(B, 3)
    sigma = np.array([blk.sigma for blk in blocks], float).reshape(B, 3)
    fx = np.zeros((B, 3)) if fixed is None else np.broadcast_to(
        np.asarray(fixed, float), (B, 3)).copy()
    fr = np.zeros((B, 3), bool) if free is None else np.broadcast_to(
        np.asarray(free, bool), (B, 3)).copy()
    order = np.array([blk.order for blk in blocks], np.bool_).reshape(B)
    out = np.zeros((B, 7))
    status = np.zeros(B, np.int64)
    ok, _ = _LOOPS.run("_solve_loop", A0, T0, L0, A1, T1, L1, const, starts.astype(np.int64),
                       counts, inner, lo_ang, hi_ang, sigma, int(kind), fx, fr, int(grow),
                       _TRIPLES, SIMPLEX_PIVOT, LP_TOL, CHECK_TOL, ROUND_TOL, order, out,
                       status)
    return (out, status == 0) if ok else None


def best_rows(a: Any, t: Any, L: Any, center: Any, half: Any, margin: float,
              order: Any = None) -> tuple[np.ndarray, ...] | None:
    """Compiled :func:`_best_rows` (features' starts ``a``, tangents ``t`` (R, 3, 2),
    lengths ``L`` (R, 3), in units of the part's size; cones ``center``, ``half``
    (R, 3); ``order`` (R,): fingers 0 and 1 share their feature): ``(found, level,
    lo_ang, hi_ang, sigma)`` per row; None when the compiled loops cannot run."""
    if _LOOPS.get() is None:
        return None
    R = len(a)
    level = np.empty(R)
    lo, hi, side = np.empty((R, 3)), np.empty((R, 3)), np.zeros((R, 3))
    ok, _ = _LOOPS.run("_best_rows", np.ascontiguousarray(a, float),
                       np.ascontiguousarray(t, float), np.ascontiguousarray(L, float),
                       np.ascontiguousarray(center, float), np.ascontiguousarray(half, float),
                       float(margin), np.asarray(SPLITS, float), _SIDES, _TRIPLES,
                       SIMPLEX_PIVOT, LP_TOL, CHECK_TOL, ROUND_TOL, PIECE_TIE,
                       np.zeros(R, np.bool_) if order is None else
                       np.ascontiguousarray(order, np.bool_), level, lo, hi, side)
    return (side[:, 0] != 0, level, lo, hi, side) if ok else None


def _block_normals(blk: Any) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_normals` of a block (plain Python)."""
    nx, ny = np.empty(6), np.empty(6)
    _normals(np.asarray(blk.lo_ang, float), np.asarray(blk.hi_ang, float),
             np.asarray(blk.sigma, float), nx, ny)
    return nx, ny


def facets(blk: Any) -> np.ndarray:
    """The concurrency region's inequalities of a block, ``W`` (F, 3, 2): its grasps are
    the finger points ``x`` with ``sum_i W[f, i] . x_i <= 0`` for every ``f`` (plain
    Python; what the compiled loop builds, for tests and :func:`witnesses`)."""
    nx, ny = _block_normals(blk)
    W = np.empty((20, 3, 2))
    return W[:_facets(nx, ny, _TRIPLES, W)].copy()


def witnesses(blk: Any, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """For each corner grasp of ``blk`` (in :meth:`_Block.corners` order) at region ends
    ``lo``, ``hi``, the point deepest inside its six half-planes (N, 2): the best vertex
    of ``max delta: n_k . p - delta >= n_k . x_k`` (three of the six rows tight)."""
    nx, ny = _block_normals(blk)
    pts_per = []
    for i in range(3):
        pts_per.append(np.concatenate([[blk.a0[i] + lo[i] * blk.t0[i],
                                        blk.a1[i] + hi[i] * blk.t1[i]],
                                       np.reshape(blk.inner[i], (-1, 2))]))
    C = blk.corners()
    X = np.stack([pts_per[i][C[:, i]] for i in range(3)], axis=1)          # (N, 3, 2)
    owner = np.arange(6) // 2
    c = nx * X[:, owner, 0] + ny * X[:, owner, 1]                     # (N, 6)
    M = np.stack([nx, ny, -np.ones(6)], axis=1)                       # rows n.p - delta
    trip = _TRIPLES
    sub = M[trip]                                                     # (20, 3, 3)
    ok = np.abs(np.linalg.det(sub)) > PARALLEL_TOL
    sol = np.full((len(C), len(trip), 3), np.nan)
    if ok.any():
        rhs = c[:, trip[ok]]                                          # (N, K, 3)
        sol[:, ok] = np.linalg.solve(sub[ok][None], rhs[..., None])[..., 0]
    slack = (np.einsum("kj,ntj->ntk", M, np.nan_to_num(sol)) - c[:, None, :]).min(axis=2)
    slack = np.where(np.isnan(sol[..., 0]), -np.inf, slack)
    depth = np.where(slack >= -CHECK_TOL, sol[..., 2], -np.inf)
    best = np.argmax(depth, axis=1)
    return sol[np.arange(len(C)), best, :2]
