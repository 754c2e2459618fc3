"""Optimal independent regions of two fingers with friction on one edge pair, per call
(algorithm 7.1, theorem 7.1; a per-call path without per-call overhead).

:func:`fcgrasp.independent_regions` on two edges asks one question about one pair; the
batched pipeline answers it with a few hundred numpy calls on arrays of one row (about
2 ms).  Here the same closed forms run on numbers, in the pipeline's order:

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

The functions below are written once, on scalars, and run two ways
(:func:`pair_regions`): compiled by numba over the compiled formulas of
:mod:`fcgrasp.core.kernels` once the process runs its kernels compiled (about 2 us a
pair), else on Python floats over :func:`fcgrasp.core.kernels.plain` (about 40 us; no
compile for one call).  The batched pipeline stays the reference: the tests compare
both ways with it on thousands of seeded pairs, near-degenerate ones included, and the
regions' corner grasps against an independent linear program.
"""

from __future__ import annotations

import math
import sys
import types
from itertools import combinations
from typing import Any, cast

from ..core import jit, kernels
from ..core.kernels import pair_problem, pair_sector, two_level
from ..core.tolerances import FACE_TOL, RANK_TOL, SOLVER_TOL, TINY

__all__ = ["pair_regions", "pair_core"]

#: The six constraint rows of the placement (``x_m = lo_m``, ``x_m = L_m``, knapsack 1,
#: knapsack 2), in the order of :func:`fcgrasp.model.regions._centre`, taken two by two.
_SUBSETS = tuple(combinations(range(6), 2))

#: What one call counts for in :func:`fcgrasp.core.kernels.use_jit`'s tally of rows run
#: by numpy (a call on floats costs about as much as this many rows): after
#: ``JIT_AFTER_ROWS / ONE_PAIR_ROWS`` calls (200) a process loads the compiled kernels.
ONE_PAIR_ROWS = 10_000


def _second(t1: float, w11: float, w12: float, w21: float, w22: float,
            L1: float, L2: float, K1: float, K2: float, tol: float) -> tuple[float, float]:
    """Leximin levels of one mode whose smallest region reaches ``t1 >= 0``
    (:func:`fcgrasp.model.regions._leximin_two`): the larger of what either region
    reaches while the other keeps ``t1``."""
    active = L1 > 0 and L2 > 0
    t2a = two_level(w11, w12, w21, w22, L1, L2, K1, K2, t1, 0.0, 0.0, 1.0, active, tol)
    t2b = two_level(w11, w12, w21, w22, L1, L2, K1, K2, 0.0, t1, 1.0, 0.0, active, tol)
    if t2a >= t2b:
        return t1, max(t2a, t1)
    return max(t2b, t1), t1


def _lex_greater(a0: float, a1: float, b0: float, b1: float) -> bool:
    """``(a0, a1) > (b0, b1)`` in the leximin order with the ranking's relative
    tolerance (:func:`fcgrasp.pipeline._candidates._lex_greater` for one row of two)."""
    sa0, sa1 = min(a0, a1), max(a0, a1)
    sb0, sb1 = min(b0, b1), max(b0, b1)
    scale = max(abs(sa0), abs(sa1), abs(sb0), abs(sb1), TINY)
    if abs(sa0 - sb0) > RANK_TOL * scale:
        return sa0 > sb0
    if abs(sa1 - sb1) > RANK_TOL * scale:
        return sa1 > sb1
    return False


def _place(L: tuple[float, float], w1: tuple[float, float], w2: tuple[float, float],
           K1: float, K2: float, up1: bool, up2: bool, lev0: float, lev1: float
           ) -> tuple[float, float, float, float]:
    """Each region's ``lo, hi`` along its edge (:func:`fcgrasp.model.regions.place_regions`
    for two active regions): the mean of the vertices of the optimal face, the greedy
    point where none is found."""
    lo = (max(lev0, 0.0), max(lev1, 0.0))
    r2 = w2[0] * (L[0] + lo[0]) + w2[1] * (L[1] + lo[1]) - K2
    rows = ((1.0, 0.0), (0.0, 1.0), (1.0, 0.0), (0.0, 1.0), w1, w2)
    rhs = (lo[0], lo[1], L[0], L[1], K1, r2)
    tol = FACE_TOL * max(L[0], L[1], TINY)
    wtol = FACE_TOL * max((w1[0] + w2[0]) * L[0] + (w1[1] + w2[1]) * L[1], TINY)
    sx = sy = 0.0
    count = 0
    for p, q in _SUBSETS:
        g00, g01 = rows[p]
        g10, g11 = rows[q]
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
        e10 = min(max(sx / count, lo[0]), L[0])
        e11 = min(max(sy / count, lo[1]), L[1])
    else:                                   # the greedy point of knapsack 1
        ratio0 = w2[0] / w1[0] if w1[0] > 0 else math.inf
        ratio1 = w2[1] / w1[1] if w1[1] > 0 else math.inf
        first = 1 if ratio1 > ratio0 else 0
        room = K1 - (w1[0] * lo[0] + w1[1] * lo[1])
        e10, e11 = lo[0], lo[1]
        for k in range(2):
            m = first if k == 0 else 1 - first
            cap = L[m] - lo[m]
            take = min(cap, max(room, 0.0) / w1[m]) if w1[m] > 0 else cap
            if m == 0:
                e10 += max(take, 0.0)
            else:
                e11 += max(take, 0.0)
            room -= w1[m] * cap
    e20 = L[0] + lo[0] - e10
    e21 = L[1] + lo[1] - e11
    return (L[0] - (e20 if up1 else e10), e10 if up1 else e20,
            L[1] - (e21 if up2 else e11), e11 if up2 else e21)


def _pair_core(ax1: float, ay1: float, bx1: float, by1: float, ax2: float, ay2: float,
               bx2: float, by2: float, center1: float, center2: float, half: float,
               margin: float, tol: float
               ) -> tuple[int, float, float, float, float, float, float]:
    """:func:`pair_regions` as numbers: ``(mode, level_1, level_2, lo_1, hi_1, lo_2,
    hi_2)``, mode -1 where the pair has no regions."""
    none = (-1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    cen, hm = pair_sector(center1, half, center2, half, margin)
    if not hm > 0:
        return none
    # squeeze (sign 1) and expand (sign -1)
    L1, L2, a11, a12, a21, a22, A1, A2, u1, u2, sep0 = pair_problem(
        ax1, ay1, bx1, by1, ax2, ay2, bx2, by2, cen, hm, 1.0, tol)
    _, _, b11, b12, b21, b22, B1, B2, v1, v2, sep1 = pair_problem(
        ax1, ay1, bx1, by1, ax2, ay2, bx2, by2, cen, hm, -1.0, tol)
    active = L1 > 0 and L2 > 0
    t0 = two_level(a11, a12, a21, a22, L1, L2, A1, A2, 0.0, 0.0, 1.0, 1.0, active,
                   tol) if sep0 else -1.0
    t1 = two_level(b11, b12, b21, b22, L1, L2, B1, B2, 0.0, 0.0, 1.0, 1.0, active,
                   tol) if sep1 else -1.0
    # a mode whose smallest region is below the other's by more than the ranking's
    # tolerance of the longest edge (twice: every level is at most its edge) loses at the
    # first level: its second is not needed
    top = max(t0, t1)
    gap = 2 * RANK_TOL * max(L1, L2, TINY)
    best0 = best1 = -1.0
    chosen = -1
    if not (t0 < 0 or t0 < top - gap):
        best0, best1 = _second(t0, a11, a12, a21, a22, L1, L2, A1, A2, tol)
        chosen = 0
    if not (t1 < 0 or t1 < top - gap):
        lev0, lev1 = _second(t1, b11, b12, b21, b22, L1, L2, B1, B2, tol)
        if _lex_greater(lev0, lev1, best0, best1):
            best0, best1, chosen = lev0, lev1, 1
    if chosen < 0 or not (best0 > 0 and best1 > 0):
        return none
    if chosen == 0:
        lo1, hi1, lo2, hi2 = _place((L1, L2), (a11, a12), (a21, a22), A1, A2, u1, u2,
                                    best0, best1)
    else:
        lo1, hi1, lo2, hi2 = _place((L1, L2), (b11, b12), (b21, b22), B1, B2, v1, v2,
                                    best0, best1)
    return chosen, best0, best1, lo1, hi1, lo2, hi2


_FUNCS = (_second, _lex_greater, _place, _pair_core)
_plain_core: Any = None


def _plain() -> Any:
    """:func:`_pair_core` on Python floats, over the formulas of
    :func:`fcgrasp.core.kernels.plain`."""
    global _plain_core
    if _plain_core is None:
        f = kernels.plain()
        namespace = dict(vars(sys.modules[__name__]), pair_sector=f.pair_sector,
                         pair_problem=f.pair_problem, two_level=f.two_level)
        for func in _FUNCS:
            namespace[func.__name__] = types.FunctionType(func.__code__, namespace,
                                                          func.__name__, func.__defaults__)
        _plain_core = namespace["_pair_core"]
    return _plain_core


#: :func:`_pair_core` compiled over the compiled formulas (loaded with them).
COMPILED = jit.CompiledLoops(dict(globals()), _FUNCS, kernels._loops)


def _use_compiled() -> bool:
    """Whether this call runs compiled (:func:`fcgrasp.core.kernels.use_jit`, a call
    counted as :data:`ONE_PAIR_ROWS` rows)."""
    return kernels.use_jit(ONE_PAIR_ROWS)


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

    Compiled once the process runs the kernels compiled (:func:`fcgrasp.compile_kernels`,
    or after :data:`ONE_PAIR_ROWS` worth of calls), on Python floats before.

    >>> mode, levels, params = pair_regions((0, 0, 10, 0), (10, 3, 0, 3), math.pi / 2,
    ...                                     -math.pi / 2, math.atan(0.3), math.radians(0.5))
    >>> mode, [round(v, 3) for v in levels], [tuple(round(v, 3) for v in p) for p in params]
    (0, [0.872, 0.872], [(4.564, 5.436), (4.564, 5.436)])
    """
    mode, l1, l2, lo1, hi1, lo2, hi2 = pair_core(
        *(float(v) for v in seg1), *(float(v) for v in seg2), float(center1),
        float(center2), float(half), float(margin), float(tol))
    if mode < 0:
        return None
    return int(mode), (l1, l2), ((lo1, hi1), (lo2, hi2))


def pair_core(*args: float) -> tuple[int, float, float, float, float, float, float]:
    """:func:`pair_regions` of floats ``ax1, ay1, bx1, by1, ax2, ay2, bx2, by2, center1,
    center2, half, margin, tol``, as ``(mode, level_1, level_2, lo_1, hi_1, lo_2, hi_2)``
    (mode -1: no regions), compiled or on floats as :func:`pair_regions` says."""
    if _use_compiled():
        ok, found = COMPILED.run("_pair_core", *args)
        if ok:
            return cast("tuple[int, float, float, float, float, float, float]", found)
    return cast("tuple[int, float, float, float, float, float, float]", _plain()(*args))
