"""Stage 1 of four frictionless fingers (or three with gravity) estimated in one compiled
loop, to leave out the rows of a top-k search that cannot reach its floor before their
geometry is built.

:func:`fcgrasp.pipeline._candidates._quad_candidates` scores a row by the largest
smallest region over its pairings and modes (theorem 7.1: the knapsack problems of
:func:`fcgrasp.model._regiongeom.four_finger_problems`, solved by
:func:`fcgrasp.model.regions.max_min_length`), in numpy, a hundred calls per batch; on a
curved outline most rows that pass the force-direction test score far below the top's
floor (``icons/heart.svg``: 108,000 of 131,000), and building their problems is most of
the search.  :func:`estimates` computes, per row, from the same formulas, a bound of
that score that rounding cannot put below it: the problems' weights and budgets as
:func:`~fcgrasp.model.regions.build_problem` makes them, then, instead of the greedy
solver's breakpoints (whose positions a coefficient near zero moves far), the largest
level by linear programming duality (:func:`_dual_level`: every pair of multipliers of
the two knapsacks bounds the level, and the least of the bounds at the multipliers'
breakpoints is the level), with both budgets raised by :data:`~fcgrasp.core.tolerances.
ESTIMATE_TOL` of the weights' scale (far above the solver's slack); the problems'
separability is not asked, and a pairing whose non-null test, shrunk sector or a
coefficient's rounding to zero is within rounding of its threshold gives an infinite
estimate.  The rows whose estimate is below the floor by more than
:data:`~fcgrasp.core.tolerances.ESTIMATE_PAD` of the part are left out; the others are
scored by numpy as before, so the plans are the same (the tests compare the estimate
with the numpy score on thousands of seeded rows, parallel and equal edges and margins
of zero among them, and the plans of searches with and without it).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core import jit
from ..core._checks import BoolArray, FloatArray, IntArray
from ..core.kernels import arc_meet
from ..core.sectors import PAIRINGS
from ..core.tolerances import (
    ESTIMATE_BAND,
    ESTIMATE_PAD,
    ESTIMATE_TOL,
    ESTIMATE_ZERO_BAND,
    SOLVER_TOL,
    TINY,
    TOL,
)
from . import _frictionless_kernels
from ._frictionless_kernels import _edge, _pair_arc


def _problem_row(o12x: float, o12y: float, o34x: float, o34y: float, vel: FloatArray,
                 L: FloatArray, k1x: float, k1y: float, k2x: float, k2y: float, zero_tol: float,
                 band: float, w1: FloatArray, w2: FloatArray, active: BoolArray
                 ) -> tuple[float, float, bool]:
    """:func:`fcgrasp.model.regions.build_problem`'s weights and budgets of one row
    (fingers 0, 1 meet in ``P12``, 2, 3 in ``P34``; a coefficient within ``zero_tol``
    of its velocity's length is zero): ``w1``, ``w2``, ``active`` filled, ``(K1, K2,
    undecided)`` returned, undecided where a coefficient is within ``band`` (relative)
    of that threshold (numpy may round it the other way)."""
    K1 = (k1x * o34y - k1y * o34x) - (k1x * o12y - k1y * o12x)
    K2 = (o34x * k2y - o34y * k2x) - (o12x * k2y - o12y * k2x)
    undecided = False
    for m in range(4):
        vx, vy = vel[m, 0], vel[m, 1]
        g1 = k1x * vy - k1y * vx
        g2 = vx * k2y - vy * k2x
        cut = zero_tol * math.hypot(vx, vy)
        if cut > 0 and (abs(abs(g1) - cut) <= band * cut or
                        abs(abs(g2) - cut) <= band * cut):
            undecided = True
        g1 = 0.0 if abs(g1) <= cut else g1
        g2 = 0.0 if abs(g2) <= cut else g2
        active[m] = L[m] > 0
        if m >= 2:
            K1 += max(g1, 0.0) * L[m]
            K2 += max(g2, 0.0) * L[m]
        else:
            K1 -= min(g1, 0.0) * L[m]
            K2 -= min(g2, 0.0) * L[m]
        w1[m] = abs(g1) if active[m] else 0.0
        w2[m] = abs(g2) if active[m] else 0.0
    return K1, K2, undecided


def _meet_row(i: int, fx: FloatArray, fy: FloatArray, ax: FloatArray, ay: FloatArray,
              tx: FloatArray, ty: FloatArray, vel: FloatArray) -> tuple[float, float]:
    """Where the lines of force of fingers ``i`` and ``i + 1`` meet with both at their
    segments' starts, and the meet's velocity as each slides (rows ``i``, ``i + 1`` of
    ``vel``): :func:`fcgrasp.core.sectors.meet_and_velocities` of numbers."""
    j = i + 1
    den = fx[i] * fy[j] - fy[i] * fx[j]
    s = ((ax[j] - ax[i]) * fy[j] - (ay[j] - ay[i]) * fx[j]) / den
    c = (tx[i] * fy[j] - ty[i] * fx[j]) / den
    vel[i, 0], vel[i, 1] = tx[i] - c * fx[i], ty[i] - c * fy[i]
    c = (tx[j] * fy[j] - ty[j] * fx[j]) / den
    vel[j, 0], vel[j, 1] = c * fx[i], c * fy[i]
    return ax[i] + s * fx[i], ay[i] + s * fy[i]


def _dual_level(L: FloatArray, w1: FloatArray, w2: FloatArray, K1: float, K2: float,
                active: BoolArray) -> float:
    """The largest level ``t`` every active region reaches (:func:`fcgrasp.model.
    regions.max_min_length`, negative where none), by duality: ``t`` is feasible iff
    some box ``t <= x <= L`` meets ``w1 . x <= K1`` and ``w2 . x >= w2 . (L + t) -
    K2``, and for multipliers ``(lam, 1)`` of the two (Farkas) that requires
    ``t <= (K2 + lam K1 - sum min(lam w1, w2) L) / sum max(lam w1, w2)``; each bound is
    monotone between the breakpoints ``lam = w2_m / w1_m``, so the least over ``lam``
    in ``{0, inf}`` and the breakpoints is the level (with the regions' lengths)."""
    n = L.shape[0]
    s1 = s2 = 0.0
    best = math.inf
    for m in range(n):
        if active[m]:
            s1 += w1[m]
            s2 += w2[m]
            best = min(best, L[m])
    if s1 > 0:
        best = min(best, K1 / s1)                   # lam infinite: knapsack 1 alone
    elif K1 < 0:
        return -1.0
    if s2 > 0:
        best = min(best, K2 / s2)                   # lam = 0: knapsack 2 alone
    elif K2 < 0:
        return -1.0
    for j in range(n):
        if not (active[j] and w1[j] > 0):
            continue
        lam = w2[j] / w1[j]
        num = K2 + lam * K1
        den = 0.0
        for m in range(n):
            if active[m]:
                a, b = lam * w1[m], w2[m]
                num -= min(a, b) * L[m]
                den += max(a, b)
        if den > 0:
            best = min(best, num / den)
    return best


def _estimate_loop(ea: FloatArray, eb: FloatArray, ec: FloatArray, rows: IntArray,
                   pairings: IntArray, margin: float, sine_tol: float, band: float,
                   zero_tol: float, band_rel: float, knapsack_tol: float, out: FloatArray) -> None:
    """Each row's estimate into ``out``: the largest smallest region over its pairings
    and modes, never below :func:`~fcgrasp.pipeline._candidates._quad_candidates`'
    score (-inf: no pairing has a sector; inf: a pairing undecided).  ``ea, eb, ec``:
    each feature's segment ends and force angle, gravity's last (a point, the
    centroid); ``rows`` (B, 4) indices into them; ``sine_tol``: the non-null test's
    (:func:`fcgrasp.core.sectors.pairing_valid`); ``band``: how near its threshold a
    sine or an angle is undecided; ``zero_tol``, ``band_rel``: a coefficient's
    rounding to zero (:func:`~fcgrasp.model.regions.build_problem`'s), and how near
    (relative) it is undecided; ``knapsack_tol``: what the budgets are raised by,
    relative to the weights' scale."""
    n = 4
    fx, fy = np.empty(n), np.empty(n)
    ax, ay = np.empty(n), np.empty(n)
    tx, ty = np.empty(n), np.empty(n)
    L, vel = np.empty(n), np.empty((n, 2))
    w1, w2, active = np.empty(n), np.empty(n), np.empty(n, np.bool_)
    for r in range(rows.shape[0]):
        best = -math.inf
        for p in range(pairings.shape[0]):
            undecided = False
            for k in range(n):
                e = rows[r, pairings[p, k]]
                fx[k], fy[k], L[k], tx[k], ty[k] = _edge(e, ea, eb, ec)
                ax[k], ay[k] = ea[e, 0], ea[e, 1]
            s12 = abs(fx[0] * fy[1] - fy[0] * fx[1])
            s34 = abs(fx[2] * fy[3] - fy[2] * fx[3])
            if s12 <= sine_tol - band or s34 <= sine_tol - band:
                continue                        # a null sector: no regions
            if s12 <= sine_tol + band or s34 <= sine_tol + band:
                undecided = True
            c12, h12 = _pair_arc(ec[rows[r, pairings[p, 0]]], ec[rows[r, pairings[p, 1]]])
            c34, h34 = _pair_arc(ec[rows[r, pairings[p, 2]]], ec[rows[r, pairings[p, 3]]])
            cen, half = arc_meet(c12, h12, c34 + math.pi, h34)
            hm = half - margin
            if hm < -band:
                continue                        # narrower than the margin: no regions
            if hm <= band or undecided:
                best = math.inf
                break
            # P12 and P34 with every finger at its segment's start, and their velocities
            o12x, o12y = _meet_row(0, fx, fy, ax, ay, tx, ty, vel)
            o34x, o34y = _meet_row(2, fx, fy, ax, ay, tx, ty, vel)
            for k in range(n):
                if not L[k] > 0:
                    vel[k, 0] = vel[k, 1] = 0.0
            for sign in (1.0, -1.0):
                k1x, k1y = sign * math.cos(cen - hm), sign * math.sin(cen - hm)
                k2x, k2y = sign * math.cos(cen + hm), sign * math.sin(cen + hm)
                K1, K2, close = _problem_row(o12x, o12y, o34x, o34y, vel, L, k1x, k1y, k2x,
                                             k2y, zero_tol, band_rel, w1, w2, active)
                scale = 0.0
                for k in range(n):
                    scale += (w1[k] + w2[k]) * L[k]
                slack = knapsack_tol * max(scale, TINY)
                t = _dual_level(L, w1, w2, K1 + slack, K2 + slack, active)
                if close or not t == t:         # undecided, or nan: a degenerate row
                    t = math.inf
                best = max(best, t)
            if best == math.inf:
                break
        out[r] = best


_BORROWING = (_problem_row, _meet_row, _dual_level)
_FUNCS = (*_BORROWING, _estimate_loop)


def _helpers() -> dict[str, Any] | None:
    """The compiled helpers the loop calls: a feature's direction and segment and a
    pair's arc (:mod:`._frictionless_kernels`, with ``arc_meet``)."""
    frictionless = _frictionless_kernels.COMPILED.get()
    if frictionless is None:
        return None
    return {"_edge": frictionless["_edge"], "_pair_arc": frictionless["_pair_arc"],
            "arc_meet": frictionless["arc_meet"]}


_LOOPS = jit.CompiledLoops(dict(globals()), _FUNCS, _helpers, borrowing=_BORROWING)


def estimates(ea: Any, eb: Any, ec: Any, rows: np.ndarray, margin: float
              ) -> np.ndarray | None:
    """Each row's estimate (:func:`_estimate_loop`), None where the loop does not run
    (numpy then scores every row)."""
    out = np.empty(len(rows))
    ok, _ = _LOOPS.run("_estimate_loop", np.ascontiguousarray(ea, float),
                       np.ascontiguousarray(eb, float), np.ascontiguousarray(ec, float),
                       np.ascontiguousarray(rows, np.int64), PAIRINGS, float(margin),
                       float(TOL), float(ESTIMATE_BAND), float(SOLVER_TOL),
                       float(ESTIMATE_ZERO_BAND), float(ESTIMATE_TOL), out)
    return out if ok else None


def below(estimate: np.ndarray, floor: float, size: float) -> np.ndarray:
    """Which rows surely score below ``floor`` (their estimate below it by more than
    :data:`~fcgrasp.core.tolerances.ESTIMATE_PAD` of the part's ``size``)."""
    return np.asarray(estimate < floor - ESTIMATE_PAD * size)
