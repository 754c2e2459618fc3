"""Optimal independent regions of two fingers with friction on one edge pair, in plain
floats (algorithm 7.1, theorem 7.1; issue 30: a per-call path without per-call overhead).

:func:`fcgrasp.independent_regions` on two edges asks one question about one pair; the
batched pipeline answers it with a few hundred numpy calls on arrays of one row (about
2 ms).  Here the same closed forms run on Python floats
(:func:`fcgrasp.core.kernels.plain`: the formulas the pipeline runs, rebuilt over
:mod:`math`), in the pipeline's order:

1. the counter-overlapping sector of the two friction cones, shrunk by the margin
   (theorem 6.4);
2. for each mode (squeeze, expand) the region problem in extension coordinates
   (theorem 7.1) and its leximin levels: the largest smallest region, then (where the
   two modes' first levels tie) the larger of what either region reaches while the
   other keeps it (algorithm 7.1, the greedy knapsack in closed form); the better mode
   by the leximin order, squeeze on a tie;
3. the regions placed at the mean of the vertices of the optimal face
   (:func:`fcgrasp.model.regions.place_regions` for two regions: the 15 pairs of
   constraints, each a 2 x 2 system).

The batched pipeline stays the reference: the tests compare both on thousands of seeded
pairs, near-degenerate ones included, and the regions' corner grasps against an
independent linear program.
"""

from __future__ import annotations

import math
from itertools import combinations
from typing import Any

from ..core.kernels import plain
from ..core.tolerances import FACE_TOL, RANK_TOL, SOLVER_TOL, TINY

__all__ = ["pair_regions"]

#: The six constraint rows of the placement (``x_m = lo_m``, ``x_m = L_m``, knapsack 1,
#: knapsack 2), in the order of :func:`fcgrasp.model.regions._centre`, taken two by two.
_SUBSETS = tuple(combinations(range(6), 2))


def _second(f: Any, t1: float, w11: float, w12: float, w21: float, w22: float,
            L1: float, L2: float, K1: float, K2: float, tol: float) -> tuple[float, float]:
    """Leximin levels of one mode whose smallest region reaches ``t1 >= 0``
    (:func:`fcgrasp.model.regions._leximin_two`): the larger of what either region
    reaches while the other keeps ``t1``."""
    active = L1 > 0 and L2 > 0
    t2a = f.two_level(w11, w12, w21, w22, L1, L2, K1, K2, t1, 0.0, 0.0, 1.0, active, tol)
    t2b = f.two_level(w11, w12, w21, w22, L1, L2, K1, K2, 0.0, t1, 1.0, 0.0, active, tol)
    lv = (t1, t2a) if t2a >= t2b else (t2b, t1)
    return max(lv[0], t1), max(lv[1], t1)


def _lex_greater(a: tuple[float, float], b: tuple[float, float]) -> bool:
    """``a > b`` in the leximin order with the ranking's relative tolerance
    (:func:`fcgrasp.pipeline._candidates._lex_greater` for one row of two)."""
    sa, sb = sorted(a), sorted(b)
    scale = max(abs(sa[0]), abs(sa[1]), abs(sb[0]), abs(sb[1]), TINY)
    for x, y in zip(sa, sb, strict=True):
        if abs(x - y) > RANK_TOL * scale:
            return x > y
    return False


def _place(L: tuple[float, float], w1: tuple[float, float], w2: tuple[float, float],
           K1: float, K2: float, up: tuple[bool, bool], levels: tuple[float, float]
           ) -> tuple[tuple[float, float], tuple[float, float]]:
    """Each region's ``(lo, hi)`` along its edge (:func:`fcgrasp.model.regions.place_regions`
    for two active regions): the mean of the vertices of the optimal face, the greedy
    point where none is found."""
    lo = (max(levels[0], 0.0), max(levels[1], 0.0))
    r2 = w2[0] * (L[0] + lo[0]) + w2[1] * (L[1] + lo[1]) - K2
    rows = ((1.0, 0.0), (0.0, 1.0), (1.0, 0.0), (0.0, 1.0), w1, w2)
    rhs = (lo[0], lo[1], L[0], L[1], K1, r2)
    tol = FACE_TOL * max(L[0], L[1], TINY)
    wtol = FACE_TOL * max((w1[0] + w2[0]) * L[0] + (w1[1] + w2[1]) * L[1], TINY)
    sx = sy = 0.0
    count = 0
    for p, q in _SUBSETS:
        (g00, g01), (g10, g11) = rows[p], rows[q]
        det = g00 * g11 - g01 * g10
        scale = max(abs(g00), abs(g01), abs(g10), abs(g11)) ** 2
        if not abs(det) > SOLVER_TOL * max(scale, TINY):
            continue
        x = (rhs[p] * g11 - g01 * rhs[q]) / det
        y = (g00 * rhs[q] - rhs[p] * g10) / det
        if (lo[0] - tol <= x <= L[0] + tol and lo[1] - tol <= y <= L[1] + tol
                and x * w1[0] + y * w1[1] <= K1 + wtol
                and x * w2[0] + y * w2[1] >= r2 - wtol):
            sx += x
            sy += y
            count += 1
    if count:
        e1 = (min(max(sx / count, lo[0]), L[0]), min(max(sy / count, lo[1]), L[1]))
    else:                                   # the greedy point of knapsack 1
        ratio = [w2[m] / w1[m] if w1[m] > 0 else math.inf for m in (0, 1)]
        order = (1, 0) if ratio[1] > ratio[0] else (0, 1)
        room = K1 - (w1[0] * lo[0] + w1[1] * lo[1])
        x_ = list(lo)
        for m in order:
            cap = L[m] - lo[m]
            take = min(cap, max(room, 0.0) / w1[m]) if w1[m] > 0 else cap
            x_[m] += max(take, 0.0)
            room -= w1[m] * cap
        e1 = (x_[0], x_[1])
    out = []
    for m in (0, 1):
        e2 = L[m] + lo[m] - e1[m]
        hi = e1[m] if up[m] else e2
        out.append((L[m] - (e2 if up[m] else e1[m]), hi))
    return out[0], out[1]


def pair_regions(seg1: tuple[float, float, float, float], seg2: tuple[float, float, float, float],
                 center1: float, center2: float, half: float, margin: float,
                 tol: float = SOLVER_TOL) -> tuple[int, tuple[float, float],
                                                   tuple[tuple[float, float], ...]] | None:
    """The optimal independent regions of two fingers on segments ``seg = (ax, ay, bx,
    by)`` whose friction cones (force directions) are centred at ``center`` with
    half-width ``half`` (``atan(mu)``), ``margin`` in radians.

    Returns ``(mode, levels, params)``: the mode (0 squeeze, 1 expand), the leximin
    lengths of the two regions and each region's ``(lo, hi)`` arc-length parameters along
    its segment from ``a``; None where the pair has no regions (definition 7.1).

    >>> mode, levels, params = pair_regions((0, 0, 10, 0), (10, 3, 0, 3), math.pi / 2,
    ...                                     -math.pi / 2, math.atan(0.3), math.radians(0.5))
    >>> mode, [round(v, 3) for v in levels], [tuple(round(v, 3) for v in p) for p in params]
    (0, [0.872, 0.872], [(4.564, 5.436), (4.564, 5.436)])
    """
    f = plain()
    cen, hm = f.pair_sector(center1, half, center2, half, margin)
    if not hm > 0:
        return None
    ax1, ay1, bx1, by1 = (float(v) for v in seg1)
    ax2, ay2, bx2, by2 = (float(v) for v in seg2)
    modes = []
    for sign in (1.0, -1.0):
        L1, L2, w11, w12, w21, w22, K1, K2, up1, up2, sep = f.pair_problem(
            ax1, ay1, bx1, by1, ax2, ay2, bx2, by2, cen, hm, sign, tol)
        t1 = f.two_level(w11, w12, w21, w22, L1, L2, K1, K2, 0.0, 0.0, 1.0, 1.0,
                         L1 > 0 and L2 > 0, tol) if sep else -1.0
        modes.append((t1, (L1, L2), (w11, w12), (w21, w22), K1, K2, (up1, up2)))
    # a mode whose smallest region is below the other's by more than the ranking's
    # tolerance of the longest edge (twice: every level is at most its edge) loses at the
    # first level: its second is not needed
    top = max(modes[0][0], modes[1][0])
    gap = 2 * RANK_TOL * max(modes[0][1][0], modes[0][1][1], TINY)
    best: tuple[float, float] = (-1.0, -1.0)
    chosen = None
    for m, (t1, L, w1, w2, K1, K2, up) in enumerate(modes):
        if t1 < 0 or t1 < top - gap:
            continue
        lev = _second(f, t1, w1[0], w1[1], w2[0], w2[1], L[0], L[1], K1, K2, tol)
        if _lex_greater(lev, best):
            best, chosen = lev, (m, L, w1, w2, K1, K2, up)
    if chosen is None or not (best[0] > 0 and best[1] > 0):
        return None
    m, L, w1, w2, K1, K2, up = chosen
    return m, best, _place(L, w1, w2, K1, K2, up, best)
