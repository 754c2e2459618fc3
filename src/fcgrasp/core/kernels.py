r"""Fused kernels for the closed forms of two fingers (algorithm 7.1, theorem 7.1).

Each closed form is written **once**, as an *elementwise* function of numbers built from
numpy's ufuncs only (arithmetic, comparisons, ``np.where``, ``np.minimum`` ...).  The same
source then runs two ways:

* **on numpy arrays** (numpy broadcasts it over the batch): no compilation, no import of
  numba; used first, so that a small plan is not start-up bound;
* **compiled by numba** into a fused, allocation-free loop over the rows of a batch
  (numba imported on first need by :mod:`fcgrasp.core.jit`, the machine code cached on
  disk beside this file):
  once the process has run :data:`JIT_AFTER_ROWS` rows by numpy, that is once the search
  is large enough to repay numba's start-up (about 0.45 s to import it and load the
  cached code; about 2.5 s the first time, to compile), and for every batch after that.

Both ways evaluate the same floating-point expressions in the same order, so they agree
to the last few units in the last place (tested to 1e-12 relative, with the previous pure
numpy implementation kept as the oracle in ``tests/previous_kernels.py``).  The loops
only gather the rows' inputs and skip rows whose sector is empty: no formula lives in
them.  ``FCGRASP_JIT=0`` in the environment never compiles (numpy everywhere);
``FCGRASP_JIT=1`` compiles for every batch.  Without numba installed, numpy runs
everything.

The formulas:

* :func:`pair_sector`: the counter-overlapping sector ``C`` of two friction cones
  (theorem 6.4), shrunk by the margin: centre and half-width ``hm``.
* :func:`pair_problem`: the region problem of two fingers in extension coordinates
  (:func:`fcgrasp.model.regions.build_problem` for fingers ``P = P12`` and ``Q = P34``,
  theorem 7.1), for one mode (squeeze ``sign = 1``, expand ``sign = -1``).
* :func:`two_level`: the largest level ``t`` two regions reach (the greedy fractional
  knapsack of :mod:`fcgrasp.model.regions` in closed form).
* :func:`pair_modes`: the largest smallest region of both modes and the better one
  (stage 1 of the leximin order).
"""

from __future__ import annotations

import math
import operator
import sys
import threading
import types
from typing import Any

import numpy as np

from ._angles import wrap_floor as _wrap  # compiled over this module's namespace
from ._checks import BoolArray, FloatArray, IntArray
from .jit import fell_back, import_numba, jit_setting, njit_all, started
from .tolerances import SOLVER_TOL, TINY

__all__ = ["JIT_AFTER_ROWS", "use_jit", "compiled", "plain", "arc_meet", "segment",
           "pair_sector", "pair_problem", "two_level", "pair_modes", "pair_scores",
           "pair_problems", "two_levels", "PROBLEM_FIELDS"]

#: A number or an array of numbers: the formulas run on both (a batch broadcast by numpy,
#: one row in a compiled loop, one grasp on Python floats).
Real = float | FloatArray
#: A truth value or an array of them (the formulas' conditions).
Cond = bool | BoolArray

#: Rows a process runs by numpy before the kernels are compiled (numpy takes about
#: 0.2-0.3 us a row, so about as long as the first compiled call of a process costs:
#: numba's import and its cache, about 0.45 s).
JIT_AFTER_ROWS = 2_000_000

#: The outputs of :func:`pair_problem`, in order (per finger: ``_1``, ``_2``).
PROBLEM_FIELDS = ("L1", "L2", "w1_1", "w1_2", "w2_1", "w2_2", "K1", "K2", "up_1", "up_2",
                  "separable")

_TWO_PI = 2.0 * np.pi


# ----------------------------------------------------------------------------- formulas


def _select(cond: Cond, x: Real, y: Real) -> Any:
    """``x`` where ``cond``, else ``y`` (``np.where``; a plain branch when compiled)."""
    return np.where(cond, x, y)


def _select_scalar(cond: Cond, x: Real, y: Real) -> Any:
    """:func:`_select` of numbers: what the compiled formulas call."""
    return x if cond else y


def arc_meet(c1: Real, h1: Real, c2: Real, h2: Real) -> tuple[Any, Any]:
    """Intersection of arcs of directions (centre, half-width), each narrower than pi:
    centre and half-width, the half-width negative where the open arcs do not meet
    (:func:`fcgrasp.core.sectors.arc_intersection`)."""
    delta = _wrap(c2 - c1)
    lo = np.maximum(-h1, delta - h2)
    hi = np.minimum(h1, delta + h2)
    return _wrap(c1 + (lo + hi) / 2), (hi - lo) / 2


def pair_sector(c1: Real, h1: Real, c2: Real, h2: Real, margin: Real) -> tuple[Any, Any]:
    """The sector ``C = V1 & -V2`` of two friction cones (theorem 6.4), shrunk by ``margin``.

    ``c, h``: centre and half-width of each cone's force directions (radians).  Returns
    the centre and the shrunk half-width ``hm`` (no regions where ``hm <= 0``).

    >>> c, hm = pair_sector(0.0, 0.5, np.pi + 0.4, 0.5, 0.1)
    >>> round(float(c), 6), round(float(hm), 6)
    (0.2, 0.2)
    """
    cen, half = arc_meet(c1, h1, c2 + np.pi, h2)
    return cen, half - margin


def _coefficient(vx: Real, vy: Real, ux: Real, uy: Real, vlen: Real, tol: float) -> Any:
    """``u x v`` of a cone edge ``u`` and a velocity ``v``; zero up to rounding is zero."""
    g = ux * vy - uy * vx
    return _select(np.abs(g) <= tol * vlen, 0.0, g)


def segment(ax: Real, ay: Real, bx: Real, by: Real) -> tuple[Any, Any, Any, Any]:
    """Length, unit tangent (``(0, 0)`` for a point) and the tangent's norm of ``a b``."""
    L = np.hypot(bx - ax, by - ay)
    d = _select(L > 0, L, 1.0)
    vx, vy = (bx - ax) / d, (by - ay) / d
    return L, vx, vy, np.hypot(vx, vy)


def _cone_edges(cen: Real, hm: Real) -> tuple[Any, Any, Any, Any]:
    """The unit edges ``k1`` (clockwise) and ``k2`` of the sector ``cen -+ hm``."""
    return np.cos(cen - hm), np.sin(cen - hm), np.cos(cen + hm), np.sin(cen + hm)


def pair_problem(ax1: Real, ay1: Real, bx1: Real, by1: Real, ax2: Real, ay2: Real, bx2: Real,
                 by2: Real, cen: Real, hm: Real, sign: float, tol: float = SOLVER_TOL
                 ) -> tuple[Any, ...]:
    """The region problem of two fingers on segments ``a1 b1`` and ``a2 b2`` (theorem 7.1
    with ``P12 = P`` and ``P34 = Q``, algorithm 7.1), for the shrunk sector of centre
    ``cen`` and half-width ``hm`` taken with ``sign`` (1: squeeze, -1: expand).

    Returns the fields :data:`PROBLEM_FIELDS`: lengths, the weights of the two
    knapsacks, their budgets, whether constraint 1 limits each region's upper end, and
    whether the problem is separable (see :class:`fcgrasp.model.regions.KnapsackProblem`).
    """
    L1, vx1, vy1, n1 = segment(ax1, ay1, bx1, by1)
    L2, vx2, vy2, n2 = segment(ax2, ay2, bx2, by2)
    k1x, k1y, k2x, k2y = _cone_edges(cen, hm)
    return _signed_problem(ax1, ay1, L1, vx1, vy1, n1, ax2, ay2, L2, vx2, vy2, n2,
                           sign * k1x, sign * k1y, sign * k2x, sign * k2y, hm, tol)


def _signed_problem(ax1: Real, ay1: Real, L1: Real, vx1: Real, vy1: Real, n1: Real, ax2: Real,
                    ay2: Real, L2: Real, vx2: Real, vy2: Real, n2: Real, k1x: Real, k1y: Real,
                    k2x: Real, k2y: Real, hm: Real, tol: float) -> tuple[Any, ...]:
    """:func:`pair_problem` from the segments' lengths and tangents and the cone's edges
    taken with the mode's sign."""
    # phi_1(x) = k1 x x and phi_2(x) = x x k2 = (-k2) x x
    g11 = _coefficient(vx1, vy1, k1x, k1y, n1, tol)
    g12 = _coefficient(vx2, vy2, k1x, k1y, n2, tol)
    g21 = _coefficient(vx1, vy1, -k2x, -k2y, n1, tol)
    g22 = _coefficient(vx2, vy2, -k2x, -k2y, n2, tol)
    # finger 1 moves P (the max of phi is at its upper end if g > 0), finger 2 moves Q
    # (the min of phi is at its upper end if g < 0)
    K1 = ((k1x * ay2 - k1y * ax2) - (k1x * ay1 - k1y * ax1)) \
        + (-np.minimum(g11, 0.0) * L1 + np.maximum(g12, 0.0) * L2)
    K2 = ((ax2 * k2y - ay2 * k2x) - (ax1 * k2y - ay1 * k2x)) \
        + (-np.minimum(g21, 0.0) * L1 + np.maximum(g22, 0.0) * L2)
    w11, w12, w21, w22 = np.abs(g11), np.abs(g12), np.abs(g21), np.abs(g22)
    up11, up12, up21, up22 = g11 > 0, g12 < 0, g21 > 0, g22 < 0
    act1, act2 = L1 > 0, L2 > 0
    separable = np.logical_not(((w11 > 0) & (w21 > 0) & act1 & (up11 == up21))
                               | ((w12 > 0) & (w22 > 0) & act2 & (up12 == up22)))
    # a region constraint 1 does not see has its binding end set by constraint 2
    upper1 = _select(w11 > 0, up11, np.logical_not(up21))
    upper2 = _select(w12 > 0, up12, np.logical_not(up22))
    # a constraint that no region can move and that is tight is a tie everywhere
    scale = np.maximum((w11 + w21) * L1 + (w12 + w22) * L2 + np.abs(K1) + np.abs(K2),
                       TINY)
    flat1 = np.logical_not(((w11 > 0) & act1) | ((w12 > 0) & act2))
    flat2 = np.logical_not(((w21 > 0) & act1) | ((w22 > 0) & act2))
    separable = (separable & np.logical_not(flat1 & (K1 <= tol * scale))
                 & np.logical_not(flat2 & (K2 <= tol * scale)))
    separable = separable & (hm > 0)     # a sector narrower than the margin has no regions
    return (L1, L2, _select(act1, w11, 0.0), _select(act2, w12, 0.0),
            _select(act1, w21, 0.0), _select(act2, w22, 0.0), K1, K2, upper1, upper2,
            separable)


def _greedy_slack(t: Real, r0: Real, af: Real, ap: Real, aq: Real, bp: Real, bq: Real, Lp: Real,
                  Lq: Real, fp: Real, fq: Real, c: Real) -> Any:
    """Slack of knapsack 2 at the greedy optimum of knapsack 1, at level ``t``."""
    R = r0 - t * af
    capp, capq = Lp - t * fp, Lq - t * fq
    fillp = _select(ap > 0, np.minimum(capp, R / _select(ap > 0, ap, 1.0)), capp)
    rest = np.maximum(R - ap * capp, 0.0)
    fillq = _select(aq > 0, np.minimum(capq, rest / _select(aq > 0, aq, 1.0)), capq)
    return bp * np.maximum(fillp, 0.0) + bq * np.maximum(fillq, 0.0) - c


def two_level(a1: Real, a2: Real, b1: Real, b2: Real, L1: Real, L2: Real, K1: Real, K2: Real,
              lb1: Real, lb2: Real, f1: Real, f2: Real, active: Cond, tol: float = SOLVER_TOL
              ) -> Any:
    """The largest ``t`` such that region ``i`` reaches ``lb_i + t f_i`` (algorithm 7.1
    in closed form; :func:`fcgrasp.model.regions.max_min_length` for two regions).

    ``a, b``: weights of knapsacks 1 and 2 (``w1``, ``w2``); ``K1, K2`` their budgets;
    ``active``: both regions are real.  With the greedy order fixed (item ``p`` first:
    the larger ratio ``b / a``), the slack of knapsack 2 at the greedy optimum of
    knapsack 1 is continuous, non-increasing and linear on both sides of the point where
    item ``p`` becomes full; the root is interpolated on its piece.  -1 where even
    ``t = 0`` is infeasible.
    """
    first = b1 * a2 >= b2 * a1
    ap, aq = _select(first, a1, a2), _select(first, a2, a1)
    bp, bq = _select(first, b1, b2), _select(first, b2, b1)
    Lp = _select(first, L1 - lb1, L2 - lb2)
    Lq = _select(first, L2 - lb2, L1 - lb1)
    fp, fq = _select(first, f1, f2), _select(first, f2, f1)
    r0 = K1 - a1 * lb1 - a2 * lb2                    # R(t) = r0 - t af
    af = a1 * f1 + a2 * f2
    c = b1 * L1 + b2 * L2 - K2
    t_cap = np.minimum(_select(fp > 0, Lp, np.inf), _select(fq > 0, Lq, np.inf))
    t_cap = np.minimum(t_cap, _select(af > 0, r0 / _select(af > 0, af, 1.0), np.inf))
    den = af - ap * fp
    t1 = _select(den != 0, (r0 - ap * Lp) / _select(den != 0, den, 1.0), np.inf)
    t_cap = _select(np.isfinite(t_cap), t_cap, 0.0)
    tolw = tol * np.maximum((a1 + b1) * L1 + (a2 + b2) * L2, TINY)
    d0 = _greedy_slack(0.0, r0, af, ap, aq, bp, bq, Lp, Lq, fp, fq, c)
    dc = _greedy_slack(t_cap, r0, af, ap, aq, bp, bq, Lp, Lq, fp, fq, c)
    mid = _select((t1 > 0) & (t1 < t_cap), t1, t_cap)
    dm = _greedy_slack(mid, r0, af, ap, aq, bp, bq, Lp, Lq, fp, fq, c)
    left = dm < -tolw
    ta, tb = _select(left, 0.0, mid), _select(left, mid, t_cap)
    da, db = _select(left, d0, dm), _select(left, dm, dc)
    step = _select(da - db > 0, da - db, 1.0)
    frac = _select(da - db > 0, np.minimum(np.maximum(da / step, 0.0), 1.0), 1.0)
    t = _select(dc >= -tolw, t_cap, ta + frac * (tb - ta))
    ok = ((d0 >= -tolw) & (t_cap >= 0) & (r0 >= -tolw) & (Lp >= -tolw) & (Lq >= -tolw)
          & active)
    return _select(ok, t, -1.0)


def _mode_value(ax1: Real, ay1: Real, L1: Real, vx1: Real, vy1: Real, n1: Real, ax2: Real,
                ay2: Real, L2: Real, vx2: Real, vy2: Real, n2: Real, k1x: Real, k1y: Real,
                k2x: Real, k2y: Real, hm: Real, tol: float) -> Any:
    """The largest smallest region of one mode (-1: none)."""
    _, _, w11, w12, w21, w22, K1, K2, _, _, sep = _signed_problem(
        ax1, ay1, L1, vx1, vy1, n1, ax2, ay2, L2, vx2, vy2, n2, k1x, k1y, k2x, k2y, hm, tol)
    t = two_level(w11, w12, w21, w22, L1, L2, K1, K2, 0.0, 0.0, 1.0, 1.0,
                  (L1 > 0) & (L2 > 0), tol)
    return _select(sep, t, -1.0)


def pair_modes(ax1: Real, ay1: Real, L1: Real, vx1: Real, vy1: Real, n1: Real, ax2: Real,
               ay2: Real, L2: Real, vx2: Real, vy2: Real, n2: Real, cen: Real, hm: Real,
               tol: float = SOLVER_TOL) -> tuple[Any, Any]:
    """Stage 1 of the leximin order of two fingers: the largest smallest region over both
    modes (squeeze, expand; -1 where neither has regions) and the better mode (0 or 1;
    0 on a tie).  Each finger's segment is given by its start ``a`` and
    :func:`segment` of it (computed once per feature, not per pair)."""
    k1x, k1y, k2x, k2y = _cone_edges(cen, hm)
    return _modes_of(ax1, ay1, L1, vx1, vy1, n1, ax2, ay2, L2, vx2, vy2, n2,
                     k1x, k1y, k2x, k2y, hm, tol)


def _modes_of(ax1: Real, ay1: Real, L1: Real, vx1: Real, vy1: Real, n1: Real, ax2: Real,
              ay2: Real, L2: Real, vx2: Real, vy2: Real, n2: Real, k1x: Real, k1y: Real,
              k2x: Real, k2y: Real, hm: Real, tol: float) -> tuple[Any, Any]:
    """:func:`pair_modes` given the shrunk sector's unit edges ``k1``, ``k2``."""
    v0 = _mode_value(ax1, ay1, L1, vx1, vy1, n1, ax2, ay2, L2, vx2, vy2, n2,
                     k1x, k1y, k2x, k2y, hm, tol)
    v1 = _mode_value(ax1, ay1, L1, vx1, vy1, n1, ax2, ay2, L2, vx2, vy2, n2,
                     -k1x, -k1y, -k2x, -k2y, hm, tol)
    return np.maximum(v0, v1), _select(v1 > v0, 1, 0)


def shrunk_edges(center: Real, half: Real, margin: float) -> Any:
    """Per cone (force directions ``center -+ half``), the unit vectors at
    ``center - half + margin`` and ``center + half - margin``, shape (F, 4): the edges of
    every pair's shrunk sector (theorem 6.4) are among them and their opposites
    (:func:`_sector_edges`), so a pair needs no cosine."""
    lo, hi = center - half + margin, center + half - margin
    return np.column_stack([np.cos(lo), np.sin(lo), np.cos(hi), np.sin(hi)])


def _sector_edges(c1: Real, h1: Real, c2: Real, h2: Real, margin: float,
                  e1: tuple[Real, ...], e2: tuple[Real, ...]
                  ) -> tuple[Any, Any, Any, Any, Any]:
    """:func:`pair_sector`'s shrunk half-width ``hm`` (the same arithmetic) and its unit
    edges ``k1``, ``k2`` from the cones' :func:`shrunk_edges` ``e1``, ``e2``: the sector's
    clockwise end is cone 1's (``c1 - h1``) or the opposite of cone 2's
    (``c2 + pi - h2``), whichever is further on; its other end likewise."""
    delta = _wrap(c2 + np.pi - c1)
    lo = np.maximum(-h1, delta - h2)
    hi = np.minimum(h1, delta + h2)
    hm = (hi - lo) / 2 - margin
    first_lo, first_hi = -h1 >= delta - h2, h1 <= delta + h2
    k1x = _select(first_lo, e1[0], -e2[0])
    k1y = _select(first_lo, e1[1], -e2[1])
    k2x = _select(first_hi, e1[2], -e2[2])
    k2y = _select(first_hi, e1[3], -e2[3])
    return hm, k1x, k1y, k2x, k2y


# ----------------------------------------------------------------------------- loops
# Compiled only: they gather each row's inputs and call the formulas above.


def _pair_scores_loop(seg: FloatArray, center: FloatArray, half: FloatArray, edges: FloatArray,
                      i: IntArray, j: IntArray, margin: float, tol: float, score: FloatArray,
                      mode: IntArray, hm_out: FloatArray) -> None:
    for k in range(i.shape[0]):
        p, q = i[k], j[k]
        hm, k1x, k1y, k2x, k2y = _sector_edges(center[p], half[p], center[q], half[q],
                                               margin, edges[p], edges[q])
        hm_out[k] = hm
        if hm > 0:
            s, m = _modes_of(seg[p, 0], seg[p, 1], seg[p, 2], seg[p, 3], seg[p, 4],
                             seg[p, 5], seg[q, 0], seg[q, 1], seg[q, 2], seg[q, 3],
                             seg[q, 4], seg[q, 5], k1x, k1y, k2x, k2y, hm, tol)
            score[k] = s
            mode[k] = m
        else:
            score[k] = -1.0
            mode[k] = 0


def _pair_problems_loop(a1: FloatArray, b1: FloatArray, a2: FloatArray, b2: FloatArray,
                        cen: FloatArray, hm: FloatArray, sign: float, tol: float, out: FloatArray,
                        flags: BoolArray) -> None:
    for k in range(cen.shape[0]):
        r = pair_problem(a1[k, 0], a1[k, 1], b1[k, 0], b1[k, 1], a2[k, 0], a2[k, 1],
                         b2[k, 0], b2[k, 1], cen[k], hm[k], sign, tol)
        out[0, k], out[1, k], out[2, k], out[3, k] = r[0], r[1], r[2], r[3]
        out[4, k], out[5, k], out[6, k], out[7, k] = r[4], r[5], r[6], r[7]
        flags[0, k], flags[1, k], flags[2, k] = r[8], r[9], r[10]


def _two_levels_loop(w1: FloatArray, w2: FloatArray, L: FloatArray, K1: FloatArray, K2: FloatArray,
                     lb: FloatArray, fr: FloatArray, active: BoolArray, tol: float, out: FloatArray
                     ) -> None:
    for k in range(K1.shape[0]):
        out[k] = two_level(w1[k, 0], w1[k, 1], w2[k, 0], w2[k, 1], L[k, 0], L[k, 1],
                           K1[k], K2[k], lb[k, 0], lb[k, 1], fr[k, 0], fr[k, 1],
                           active[k], tol)


def _rows_closure_loop(unit: FloatArray, rows: IntArray, tol: float, out: BoolArray) -> None:
    """:func:`fcgrasp.core.closure.force_direction_closure` of the forces
    ``unit[rows[r]]`` of every row (rows of indices into one table of forces), the same
    operations row by row without gathering them: each force of the table made unit
    once (the same operations whichever row reads it), then each row's read and
    :func:`_closed`."""
    k = rows.shape[1]
    table = np.empty((unit.shape[0], 2))
    for f in range(unit.shape[0]):
        x, y = unit[f, 0], unit[f, 1]
        n = np.sqrt(x * x + y * y)
        table[f, 0] = x / n if n > 0 else 0.0
        table[f, 1] = y / n if n > 0 else 0.0
    u = np.empty((k, 2))
    for r in range(rows.shape[0]):
        for i in range(k):
            u[i, 0], u[i, 1] = table[rows[r, i], 0], table[rows[r, i], 1]
        out[r] = _closed(u, k, tol)


def _closed(u: FloatArray, k: int, tol: float) -> bool:
    """Force-direction closure of ``k`` unit forces ``u`` (theorem 4.2): a strict
    triangle, or (four or more) two anti-parallel pairs not parallel to each other."""
    ok = False
    for a in range(k):
        for b in range(a + 1, k):
            for c in range(b + 1, k):
                s1 = u[a, 0] * u[b, 1] - u[a, 1] * u[b, 0]
                s2 = u[b, 0] * u[c, 1] - u[b, 1] * u[c, 0]
                s3 = u[c, 0] * u[a, 1] - u[c, 1] * u[a, 0]
                if (s1 > tol and s2 > tol and s3 > tol) or \
                        (s1 < -tol and s2 < -tol and s3 < -tol):
                    ok = True
    if not ok and k >= 4:
        for a in range(k):
            for b in range(a + 1, k):
                if not _anti(u, a, b, tol):
                    continue
                # a later pair (in the order of the pairs' combinations)
                for c in range(a, k):
                    for d in range(c + 1, k):
                        if c == a and d <= b or not _anti(u, c, d, tol):
                            continue
                        if abs(u[a, 0] * u[c, 1] - u[a, 1] * u[c, 0]) > tol:
                            ok = True
    return ok


def _anti(u: FloatArray, a: int, b: int, tol: float) -> bool:
    """Forces ``a`` and ``b`` of the unit rows ``u`` are non-zero and anti-parallel."""
    na = np.sqrt(u[a, 0] * u[a, 0] + u[a, 1] * u[a, 1])
    nb = np.sqrt(u[b, 0] * u[b, 0] + u[b, 1] * u[b, 1])
    return bool(na > 0 and nb > 0 and abs(u[a, 0] * u[b, 1] - u[a, 1] * u[b, 0]) <= tol
                and u[a, 0] * u[b, 0] + u[a, 1] * u[b, 1] < 0)


_FORMULAS = ("_select", "_wrap", "arc_meet", "pair_sector", "_coefficient", "segment",
             "_cone_edges", "pair_problem", "_signed_problem", "_greedy_slack", "two_level",
             "_mode_value", "pair_modes", "_modes_of", "_sector_edges")
_LOOPS = ("_pair_scores_loop", "_pair_problems_loop", "_two_levels_loop", "_anti",
          "_closed", "_rows_closure_loop")


# ----------------------------------------------------------------------------- plain floats


def _larger(x: Real, y: Real) -> Any:
    return x if x >= y else y


def _smaller(x: Real, y: Real) -> Any:
    return x if x <= y else y


#: The names of numpy the formulas call, for Python floats (one grasp, one edge pair:
#: a numpy call on a number costs about a microsecond, an operator on floats 30 ns).
#: Every division in the formulas is guarded by :func:`_select`, so none divides by zero.
_FLOAT_MATH = types.SimpleNamespace(
    pi=math.pi, inf=math.inf, maximum=_larger, minimum=_smaller, abs=abs,
    hypot=math.hypot, cos=math.cos, sin=math.sin, floor=math.floor,
    isfinite=math.isfinite, logical_not=operator.not_)

_plain: types.SimpleNamespace | None = None


def plain() -> types.SimpleNamespace:
    """The formulas above rebuilt to run on Python floats (``np`` bound to :mod:`math`
    and plain comparisons, :func:`_select` a branch): the same expressions in the same
    order as the batched and the compiled ways, for the per-call paths
    (:func:`fcgrasp.model.one_pair.pair_regions`).

    >>> c, hm = plain().pair_sector(0.0, 0.5, math.pi + 0.4, 0.5, 0.1)
    >>> round(c, 6), round(hm, 6)
    (0.2, 0.2)
    """
    global _plain
    if _plain is None:
        from . import _angles

        wrap = types.FunctionType(_angles.wrap_floor.__code__,
                                  {"np": _FLOAT_MATH, "_TWO_PI": _TWO_PI}, "_wrap")
        namespace = dict(globals(), np=_FLOAT_MATH, _select=_select_scalar, _wrap=wrap)
        module = sys.modules[__name__]
        for name in _FORMULAS:
            if name not in ("_select", "_wrap"):
                func = getattr(module, name)
                namespace[name] = types.FunctionType(func.__code__, namespace, name,
                                                     func.__defaults__)
        _plain = types.SimpleNamespace(**{name: namespace[name] for name in _FORMULAS})
    return _plain


# ----------------------------------------------------------------------------- dispatch

_compiled: dict[str, Any] | None = None
_no_numba = False
_rows_by_numpy = 0
_compiling = threading.Lock()


def use_jit(rows: int) -> bool:
    """Does a batch of ``rows`` rows run compiled?  Yes once numba started in this
    process for any of the package's compiled loops, these kernels included
    (:func:`started`: its start-up is paid, and the kernels load from its cache in
    milliseconds), or once it has run :data:`JIT_AFTER_ROWS` rows by numpy (this batch
    included: a batch that runs by numpy is counted); never with ``FCGRASP_JIT=0`` or
    without numba; always with ``FCGRASP_JIT=1``."""
    global _rows_by_numpy
    setting = jit_setting()
    if setting is False or _no_numba:
        return False
    if setting is True or started():
        return True
    _rows_by_numpy += rows
    return _rows_by_numpy > JIT_AFTER_ROWS


def _loops() -> dict[str, Any] | None:
    """The formulas and loops compiled by numba (once per process; None without numba).

    Every function is rebuilt over one shared namespace whose names are the compiled
    functions, so the loops call compiled formulas; the machine code is cached on disk
    beside this file."""
    global _compiled, _no_numba
    with _compiling:
        if _compiled is not None or _no_numba:
            return _compiled
        numba = import_numba()
        if numba is None:
            _no_numba = True
            return None
        module = sys.modules[__name__]
        _compiled = njit_all(numba, dict(globals()), [
            (name, getattr(module, "_select_scalar" if name == "_select" else name))
            for name in _FORMULAS + _LOOPS])
        return _compiled


def compiled() -> bool:
    """Whether this process runs the kernels compiled (loaded, and working)."""
    return _compiled is not None and not _no_numba


def _run(name: str, *args: Any) -> bool:
    """Run the compiled loop ``name``; False (and numpy from then on) if numba fails to
    compile it, so that a broken numba never breaks a plan."""
    global _no_numba
    loops = _loops()
    if loops is None:
        return False
    try:
        loops[name](*args)
    except Exception as exc:            # numba's typing or lowering errors
        fell_back(name, exc)
        _no_numba = True
        return False
    return True


def pair_scores(a: FloatArray, b: FloatArray, center: FloatArray, half: FloatArray,
                i: np.ndarray, j: np.ndarray, margin: float, tol: float = SOLVER_TOL
                ) -> tuple[FloatArray, np.ndarray, FloatArray]:
    """Stage 1 of every pair ``(i[k], j[k])`` of features (segments ``a``-``b`` (F, 2),
    cones ``center``, ``half`` (F,)): the largest smallest region (-1: none), the better
    mode and the shrunk sector's half-width ``hm`` (regions need ``hm > 0``)."""
    i = np.ascontiguousarray(i, dtype=np.int64)
    j = np.ascontiguousarray(j, dtype=np.int64)
    a, b = np.asarray(a, float), np.asarray(b, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        # per feature: start, length, unit tangent and its norm
        seg = np.column_stack([a[:, 0], a[:, 1], *segment(a[:, 0], a[:, 1], b[:, 0],
                                                          b[:, 1])])
    if use_jit(i.size):
        score = np.empty(i.size)
        mode = np.empty(i.size, dtype=np.int64)
        hm = np.empty(i.size)
        # contiguous and writable (read-only inputs copied): one compiled signature
        center = np.require(center, float, ("C", "W"))
        half = np.require(half, float, ("C", "W"))
        if _run("_pair_scores_loop", seg, center, half, shrunk_edges(center, half, margin),
                i, j, float(margin), float(tol), score, mode, hm):
            return score, mode, hm
    with np.errstate(divide="ignore", invalid="ignore"):
        cen, hm = pair_sector(center[i], half[i], center[j], half[j], margin)
        score = np.full(i.size, -1.0)
        mode = np.zeros(i.size, dtype=np.int64)
        ok = np.flatnonzero(hm > 0)
        sp, sq = seg[i[ok]].T, seg[j[ok]].T
        s, m = pair_modes(sp[0], sp[1], sp[2], sp[3], sp[4], sp[5], sq[0], sq[1], sq[2],
                          sq[3], sq[4], sq[5], cen[ok], hm[ok], tol)
    score[ok], mode[ok] = s, m
    return score, mode, hm


def pair_problems(a1: FloatArray, b1: FloatArray, a2: FloatArray, b2: FloatArray,
                  cen: FloatArray, hm: FloatArray, sign: float, tol: float = SOLVER_TOL
                  ) -> dict[str, np.ndarray]:
    """:func:`pair_problem` of every row (segments (B, 2), sectors (B,)), as a dict of
    arrays keyed by :data:`PROBLEM_FIELDS`."""
    cen = np.ascontiguousarray(cen, dtype=float)
    hm = np.ascontiguousarray(hm, dtype=float)
    if use_jit(cen.size):
        out = np.empty((8, cen.size))
        flags = np.empty((3, cen.size), dtype=np.bool_)
        if _run("_pair_problems_loop", *(np.ascontiguousarray(x, float)
                                         for x in (a1, b1, a2, b2)), cen, hm, float(sign),
                float(tol), out, flags):
            return dict(zip(PROBLEM_FIELDS, [*out, *flags], strict=True))
    with np.errstate(divide="ignore", invalid="ignore"):
        res = pair_problem(a1[:, 0], a1[:, 1], b1[:, 0], b1[:, 1], a2[:, 0], a2[:, 1],
                           b2[:, 0], b2[:, 1], cen, hm, sign, tol)
    return dict(zip(PROBLEM_FIELDS, (np.broadcast_to(x, cen.shape) for x in res),
                    strict=True))


def two_levels(w1: FloatArray, w2: FloatArray, L: FloatArray, K1: FloatArray,
               K2: FloatArray, lb: FloatArray, fr: FloatArray, active: np.ndarray,
               tol: float = SOLVER_TOL) -> FloatArray:
    """:func:`two_level` of every row: weights, lengths, levels and growth (B, 2),
    budgets (B,), ``active`` (B,) both regions real."""
    if use_jit(len(K1)):
        out = np.empty(len(K1))
        args = [np.ascontiguousarray(x, float) for x in (w1, w2, L, K1, K2, lb, fr)]
        if _run("_two_levels_loop", *args, np.ascontiguousarray(active, np.bool_),
                float(tol), out):
            return out
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.asarray(two_level(w1[:, 0], w1[:, 1], w2[:, 0], w2[:, 1], L[:, 0],
                                    L[:, 1], K1, K2, lb[:, 0], lb[:, 1], fr[:, 0], fr[:, 1],
                                    active, tol), dtype=float)
