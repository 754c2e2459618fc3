r"""Optimal independent regions of contact (paper section 7).

Definition 7.1: regions ``r_1 .. r_n``, one segment on each chosen edge, such that
every grasp with finger ``i`` anywhere in ``r_i`` (end points included) is force
closure; optimal when the smallest region is as long as possible, then the next
smallest, and so on (the *leximin* order).

**The exact method.**  Let ``C`` be the counter-overlapping sector of the grasp set
(theorem 6.4 for two fingers with friction, ``C_12 & -C_34`` for four frictionless
fingers), shrunk by the safety ``margin`` on both sides, with edges ``k1`` (clockwise)
and ``k2``.  Write :math:`\phi_1(x) = k_1 \times x` and :math:`\phi_2(x) = x \times k_2`.
All grasps of the box of regions are force closure iff, for both ``i``,

.. math:: \min_{P_{34}} \phi_i(P_{34}) \ge \max_{P_{12}} \phi_i(P_{12})

(theorem 7.1: the two-sided cone of vertex ``I`` with sector ``C`` splits the
restricted parallelograms :math:`\Pi'_{12}` and :math:`\Pi'_{34}`; for two fingers
``P12 = P`` and ``P34 = Q``, algorithm 7.1).  ``P12`` is affine in the positions of
its fingers along their edges, so each side of the inequality is reached at one end
of every region.  Because ``C`` lies strictly inside the sectors of the forces, the
two functionals always pick **opposite** ends of a region.  In *extension*
coordinates (how far each end reaches from the far end of its edge) the problem is

.. math::
   \text{leximin } \ell_m = e^{(1)}_m + e^{(2)}_m - L_m \quad\text{s.t.}\quad
   \sum_m w^{(1)}_m e^{(1)}_m \le K_1,\;
   \sum_m w^{(2)}_m e^{(2)}_m \le K_2,\; 0 \le e \le L

two fractional knapsacks over the two ends of every region, coupled only through the
lengths.  For a target length ``t`` the best split is the greedy fill of knapsack 1
by the ratio ``w2 / w1``, so feasibility of ``t`` is a closed-form test and the
optimum is found by bisection to machine precision; the leximin levels follow by
fixing the regions that cannot grow and repeating (at most ``n`` stages).  The
regions are then placed at a canonical point of the optimal face: as near the middle
of the admissible ranges as the constraints allow (the paper's "anywhere on this
segment" for parallel edges).

**Margin zero.**  With ``margin=0`` the shrunk sector is the sector itself and the
inequalities above are not strict: the regions returned are then the *closure* of a set
of force-closure grasps.  Every grasp with every finger strictly inside its region is
force closure; a grasp with a finger at a region's end may be a tie (not force closure,
as everywhere in fcgrasp).  A constraint that no region can move (a cone edge parallel
to every motion of ``P12`` and ``P34``) and that is tight is a tie everywhere: such an
edge set has no regions.  With a positive margin the ends hold too.

Two fingers on one edge (section 6.2) must not overlap: the unconstrained optimum is
used when its regions are disjoint, otherwise the edge is split at the best point
(the optimum is concave in the split point; golden-section search).

The tests compare the optimum with an independent linear program over the region end
points (every corner grasp of the box inside the shrunk cones, solved with scipy's
HiGHS) on thousands of seeded random edge sets.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from itertools import combinations
from typing import Any, cast

import numpy as np

from ..core._checks import FloatArray
from ..core._geom import cross2 as _cross
from ..core.kernels import two_levels
from ..core.tolerances import (
    FACE_TOL,
    LEXIMIN_STEP,
    PLACE_NOISE_DET,
    PLACE_SURE_BAND,
    PLACE_SURE_DET,
    SOLVER_TOL,
    TINY,
)

__all__ = [
    "KnapsackProblem",
    "build_problem",
    "max_min_length",
    "leximin",
    "place_regions",
    "DEFAULT_MARGIN_DEG",
]

#: Default safety margin: every grasp of a region box points at least this far (degrees)
#: inside the friction cones (two fingers) or the sectors (four fingers).
DEFAULT_MARGIN_DEG = 0.5




@dataclass
class KnapsackProblem:
    """A batch of region problems in extension coordinates (shapes (B, n) and (B,)).

    ``upper1[b, m]`` says whether constraint 1 limits the upper end of region ``m``
    (then constraint 2 limits its lower end).  ``active[b, m]`` is False for fixed points
    (gravity), which have no region.  ``separable`` is False where the two constraints
    would limit the same end of some region (cannot happen with a positive margin).
    """

    L: FloatArray
    w1: FloatArray
    w2: FloatArray
    K1: FloatArray
    K2: FloatArray
    upper1: np.ndarray
    active: np.ndarray
    separable: np.ndarray

    FIELDS = ("L", "w1", "w2", "K1", "K2", "upper1", "active", "separable")

    @property
    def batch(self) -> int:
        return int(self.L.shape[0])

    def take(self, rows: Any) -> KnapsackProblem:
        """The problems of the given rows (indices or a mask)."""
        return KnapsackProblem(*(getattr(self, f)[rows] for f in self.FIELDS))

    def repeat(self, m: int) -> KnapsackProblem:
        """Every row repeated ``m`` times (to evaluate m points of a row at once)."""
        return KnapsackProblem(*(np.repeat(getattr(self, f), m, axis=0) for f in self.FIELDS))

    @staticmethod
    def concat(parts: list[KnapsackProblem]) -> KnapsackProblem:
        """The rows of several batches, in order."""
        return KnapsackProblem(*(np.concatenate([getattr(p, f) for p in parts])
                                 for f in KnapsackProblem.FIELDS))


def build_problem(side: np.ndarray, origin12: FloatArray, origin34: FloatArray,
                  vel: FloatArray, L: FloatArray, k1: FloatArray, k2: FloatArray,
                  tol: float = SOLVER_TOL) -> KnapsackProblem:
    """Knapsack form of "P34 - P12 inside the cone (k1, k2) for every corner grasp".

    Parameters
    ----------
    side : ndarray of int, shape (n,)
        0 for fingers meeting in ``P12``, 1 for fingers meeting in ``P34``.
    origin12, origin34 : ndarray, shape (B, 2)
        ``P12`` and ``P34`` with every finger at the start of its edge.
    vel : ndarray, shape (B, n, 2)
        Derivative of ``P12`` (or ``P34``) with respect to the arc length of finger ``m``.
    L : ndarray, shape (B, n)
        Edge lengths (0 for a fixed point).
    k1, k2 : ndarray, shape (B, 2)
        Unit edges of the (shrunk) cone, ``k1`` clockwise of ``k2``.
    """
    B, n = L.shape
    w = np.empty((2, B, n))
    up = np.empty((2, B, n), dtype=bool)
    K = np.empty((2, B))
    is34 = (np.asarray(side) == 1)[None, :]
    phis: tuple[Callable[[FloatArray], FloatArray], ...] = (
        lambda x: _cross(k1[:, None, :], x) if x.ndim == 3 else _cross(k1, x),
        lambda x: _cross(x, k2[:, None, :]) if x.ndim == 3 else _cross(x, k2))
    for i, phi in enumerate(phis):
        g = phi(vel)                                        # (B, n)
        # a coefficient that is zero up to rounding (a cone edge parallel to a force, as
        # with a zero margin) is zero: that end is then free for this constraint
        g = np.where(np.abs(g) <= tol * np.hypot(vel[..., 0], vel[..., 1]), 0.0, g)
        w[i] = np.abs(g)
        # P12 side: the max is at the upper end if g > 0; P34 side: the min is at the
        # upper end if g < 0
        up[i] = np.where(is34, g < 0, g > 0)
        base = np.where(is34, np.maximum(g, 0.0) * L, -np.minimum(g, 0.0) * L)
        K[i] = phi(origin34) - phi(origin12) + np.sum(base, axis=1)
    active = L > 0
    nz = (w[0] > 0) & (w[1] > 0) & active
    separable = ~np.any(nz & (up[0] == up[1]), axis=1)
    # A region that constraint 1 does not see (coefficient zero: with a zero margin a cone
    # edge is parallel to the motion of P12 or P34) has its one binding end set by
    # constraint 2; constraint 1's free extension is then the *other* end.  Reading the
    # side from the sign of a zero would put both extensions on the same end and place
    # the region on the wrong side (false closure at margin 0, parallel edges).
    upper1 = np.where(w[0] > 0, up[0], ~up[1])
    # A constraint that no region can move and that is tight (P34 - P12 on a cone edge
    # whatever the fingers do) holds with equality everywhere: a tie, never closure.
    scale = np.maximum(np.sum((w[0] + w[1]) * L, axis=1) + np.abs(K[0]) + np.abs(K[1]), TINY)
    for i in range(2):
        flat = ~np.any((w[i] > 0) & active, axis=1)
        separable &= ~(flat & (K[i] <= tol * scale))
    return KnapsackProblem(L, np.where(active, w[0], 0.0), np.where(active, w[1], 0.0),
                           K[0], K[1], upper1, active, separable)


# ----------------------------------------------------------------------------- the solver


def _order(p: KnapsackProblem) -> np.ndarray:
    """Greedy order of knapsack 1: the largest gain in knapsack 2 per unit of cost first."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(p.w1 > 0, p.w2 / np.where(p.w1 > 0, p.w1, 1.0), np.inf)
    ratio = np.where(p.active, ratio, -np.inf)
    return np.argsort(-ratio, axis=1, kind="stable")


def _fill(p: KnapsackProblem, lb: FloatArray, order: np.ndarray
          ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Greedy fill of x = e^(1) from ``lb`` up to ``L`` within budget ``K1``.

    Returns (x at the greedy optimum, the budget slack of knapsack 1 at ``x = lb``, and
    the value ``sum w2 x``).
    """
    L = np.where(p.active, p.L, 0.0)
    lb = np.where(p.active, lb, 0.0)
    slack = p.K1 - np.sum(p.w1 * lb, axis=1)
    rows = np.arange(p.batch)[:, None]
    w1s, caps = p.w1[rows, order], (L - lb)[rows, order]
    cost = w1s * caps
    before = np.cumsum(cost, axis=1) - cost
    room = np.maximum(slack[:, None] - before, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        take = np.where(w1s > 0, np.minimum(caps, room / np.where(w1s > 0, w1s, 1.0)), caps)
    take = np.maximum(take, 0.0)
    x = lb.copy()
    x[rows, order] += take
    return x, slack, np.sum(p.w2 * x, axis=1)


def _feasible(p: KnapsackProblem, lb: FloatArray, order: np.ndarray, eps: FloatArray
              ) -> np.ndarray:
    """Is there a box of regions with lengths at least ``lb`` (per region)?"""
    ok = np.all((lb <= p.L + eps[:, None]) | ~p.active, axis=1)
    _, slack, value = _fill(p, lb, order)
    need = np.sum(p.w2 * (np.where(p.active, p.L + lb, 0.0)), axis=1) - p.K2
    scale = eps * _wscale(p)
    return cast("np.ndarray", ok & (slack >= -scale) & (value >= need - scale))


def _wscale(p: KnapsackProblem) -> FloatArray:
    return cast("FloatArray", np.maximum(np.sum((p.w1 + p.w2) * p.L, axis=1), TINY))


def _max_level(p: KnapsackProblem, lb_fixed: FloatArray, free: np.ndarray,
               order: np.ndarray, tol: float = SOLVER_TOL) -> FloatArray:
    """Largest ``t`` such that the free regions reach ``t`` and the fixed ones their levels.

    Exact: with the greedy order fixed, the slack ``D(t)`` of knapsack 2 at the greedy
    optimum of knapsack 1 is continuous, non-increasing and linear between the values of
    ``t`` at which the greedy fill moves to the next region.  Those breakpoints are solved
    for, ``D`` is evaluated there, and the root is interpolated on its linear piece.
    Returns -1 where even ``t = 0`` is infeasible.
    """
    B, n = p.L.shape
    fr = free & p.active
    L = np.where(p.active, p.L, 0.0)
    lb0 = np.where(fr, 0.0, np.where(p.active, lb_fixed, 0.0))      # lb(t) = lb0 + t * fr
    a = p.w1
    af = np.sum(a * fr, axis=1)
    r0 = p.K1 - np.sum(a * lb0, axis=1)                              # R(t) = r0 - t af
    t_cap = np.min(np.where(fr, L, np.inf), axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        t_cap = np.minimum(t_cap, np.where(af > 0, r0 / np.where(af > 0, af, 1.0), np.inf))
    t_cap = np.where(np.isfinite(t_cap), t_cap, 0.0)
    rows = np.arange(B)[:, None]
    a_s, fr_s = a[rows, order], fr[rows, order].astype(float)
    cap0 = (L - lb0)[rows, order]                                    # capacity(t) = cap0 - t fr
    s0 = np.cumsum(a_s * cap0, axis=1) - a_s * cap0                  # cost of items before j
    s1 = np.cumsum(a_s * fr_s, axis=1) - a_s * fr_s
    with np.errstate(divide="ignore", invalid="ignore"):
        tj = (r0[:, None] - s0) / (af[:, None] - s1)
    valid = np.isfinite(tj) & (tj > 0) & (tj < t_cap[:, None])
    # at a breakpoint the greedy fill holds exactly the items before it, full: the slack of
    # knapsack 2 there is a cumulative sum; only t = 0 and t_cap need the general fill
    b_s = p.w2[rows, order]
    c = np.sum(p.w2 * L, axis=1) - p.K2
    s0b = np.cumsum(b_s * cap0, axis=1) - b_s * cap0
    s1b = np.cumsum(b_s * fr_s, axis=1) - b_s * fr_s
    with np.errstate(invalid="ignore"):
        d_j = np.where(valid, s0b - tj * s1b - c[:, None], np.inf)
    ends = np.stack([np.zeros(B), t_cap], axis=1)                     # (B, 2)
    lb = (lb0[:, None, :] + ends[:, :, None] * fr[:, None, :]).reshape(B * 2, n)
    pt = p.repeat(2)
    _, slack, value = _fill(pt, lb, np.repeat(order, 2, axis=0))
    need = np.sum(pt.w2 * (pt.L * pt.active + lb), axis=1) - pt.K2
    tolw = tol * _wscale(p)
    d_ends = np.where(slack >= -np.repeat(tolw, 2), value - need, -np.inf).reshape(B, 2)
    pts = np.concatenate([ends[:, :1], np.where(valid, tj, np.inf), ends[:, 1:]], axis=1)
    D = np.concatenate([d_ends[:, :1], d_j, d_ends[:, 1:]], axis=1)
    srt = np.argsort(pts, axis=1, kind="stable")
    pts = np.take_along_axis(pts, srt, axis=1)
    D = np.take_along_axis(D, srt, axis=1)
    keep = np.isfinite(pts)
    # invalid breakpoints sort to the end (inf); give them the value at t_cap
    pts = np.where(keep, pts, t_cap[:, None])
    D = np.where(keep, D, d_ends[:, 1:])
    m = pts.shape[1]
    ok = D >= -tolw[:, None]
    feasible0 = ok[:, 0] & (t_cap >= 0) & np.all((lb0 <= L + tol * L) | ~p.active, axis=1)
    last = m - 1 - np.argmax(ok[:, ::-1], axis=1)                    # last feasible point
    nxt = np.minimum(last + 1, m - 1)
    r = np.arange(B)
    t_a, t_b = pts[r, last], pts[r, nxt]
    d_a, d_b = D[r, last], D[r, nxt]
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.where((nxt > last) & np.isfinite(d_b) & (d_a - d_b > 0),
                        np.clip(d_a / (d_a - d_b), 0.0, 1.0), 0.0)
    t = t_a + frac * (t_b - t_a)
    return np.where(feasible0, t, -1.0)


def _two_level(p: KnapsackProblem, lb0: FloatArray, fr: FloatArray,
               tol: float = SOLVER_TOL) -> FloatArray:
    """:func:`_max_level` for two regions in closed form (algorithm 7.1): region ``i``
    must reach ``lb0[i] + t fr[i]``; returns the largest ``t`` (-1 where none).

    The formula is :func:`fcgrasp.core.kernels.two_level`, run on the batch by numpy or by
    its compiled loop (:func:`fcgrasp.core.kernels.two_levels`)."""
    return two_levels(p.w1, p.w2, p.L, p.K1, p.K2, lb0, fr, np.all(p.active, axis=1), tol)


def _max_min_two(p: KnapsackProblem, tol: float = SOLVER_TOL) -> FloatArray:
    """:func:`max_min_length` for two regions, in closed form."""
    return _two_level(p, np.zeros_like(p.L), np.ones_like(p.L), tol)


def max_min_length(p: KnapsackProblem, tol: float = SOLVER_TOL) -> FloatArray:
    """Largest achievable length of the smallest region (-1 where none is possible).

    ``tol``: relative slack of the solver (:data:`fcgrasp.core.tolerances.SOLVER_TOL`)."""
    if p.L.shape[1] == 2:
        return _max_min_two(p, tol)
    got = _compiled(p, tol, first_only=True)
    if got is not None:
        return got[:, 0].copy()
    order = _order(p)
    free = p.active.copy()
    return _max_level(p, np.zeros_like(p.L), free, order, tol)


def _compiled(p: KnapsackProblem, tol: float, first_only: bool) -> FloatArray | None:
    """:func:`leximin` (``first_only``: its first level) by the compiled loop of
    :mod:`fcgrasp.model._leximin_kernels`, where this process runs compiled kernels
    (:func:`fcgrasp.core.kernels.use_jit`: loaded already, or a large search); None:
    numpy."""
    from ..core.kernels import use_jit

    if p.batch == 0 or not use_jit(p.batch):
        return None
    from ._leximin_kernels import leximin_rows

    return cast("FloatArray | None", leximin_rows(p.L, p.w1, p.w2, p.K1, p.K2, p.active,
                                                  tol, LEXIMIN_STEP, first_only))


def _leximin_two(p: KnapsackProblem, tol: float = SOLVER_TOL) -> FloatArray:
    """Leximin for two regions: the largest smallest region ``t1`` (closed form), then the
    larger of what either region reaches while the other keeps ``t1`` (closed form)."""
    t1 = _max_min_two(p, tol)
    s = np.maximum(t1, 0.0)
    z = np.zeros_like(s)
    t2a = _two_level(p, np.stack([s, z], 1), np.stack([z, z + 1], 1), tol)   # region 2 grows
    t2b = _two_level(p, np.stack([z, s], 1), np.stack([z + 1, z], 1), tol)   # region 1 grows
    lv = np.where((t2a >= t2b)[:, None], np.stack([t1, t2a], 1), np.stack([t2b, t1], 1))
    lv = np.maximum(lv, t1[:, None])
    lv[t1 < 0] = -1.0
    return lv


def leximin(p: KnapsackProblem, tol: float = SOLVER_TOL) -> FloatArray:
    """Leximin-optimal region lengths (definition 7.1), shape (B, n); -1 rows if infeasible.

    ``tol``: relative slack of the solver (:data:`fcgrasp.core.tolerances.SOLVER_TOL`)."""
    if p.L.shape[1] == 2 and bool(np.all(p.active)):
        return _leximin_two(p, tol)
    got = _compiled(p, tol, first_only=False)
    if got is not None:
        return got
    order = _order(p)
    levels = np.zeros_like(p.L)
    free = p.active.copy()
    dead = np.zeros(p.batch, dtype=bool)
    n = p.L.shape[1]
    first_stage = True
    for _ in range(n):
        rows = np.flatnonzero(free.any(axis=1))
        if rows.size == 0:
            break
        sub = p.take(rows)
        lv, fr, od = levels[rows], free[rows], order[rows]
        t = _max_level(sub, lv, fr, od, tol)
        if first_stage:
            dead[rows] |= t < 0
            first_stage = False
        t = np.maximum(t, 0.0)
        lv = np.where(fr, t[:, None], lv)
        # which free regions cannot grow beyond t while the others stay at their levels?
        scale = np.maximum(np.max(sub.L, axis=1), TINY)
        trial = lv[:, None, :] + np.eye(n)[None] * (LEXIMIN_STEP * scale)[:, None, None]
        grow = _feasible(sub.repeat(n), trial.reshape(-1, n), np.repeat(od, n, axis=0),
                         np.repeat(0.1 * tol * scale, n))
        blocked = fr & ~grow.reshape(-1, n)
        none = fr.any(axis=1) & ~blocked.any(axis=1)
        blocked |= fr & none[:, None]          # numerical stall: fix all
        levels[rows] = lv
        free[rows] = fr & ~blocked
    levels = np.where(p.active, levels, 0.0)
    levels[dead] = -1.0
    return levels


@cache
def _subsets(n: int) -> np.ndarray:
    """The candidate active sets of :func:`_centre` for ``n`` regions: every ``n`` of
    its ``2 n + 2`` constraint rows, in :func:`itertools.combinations` order (read
    only: shared by every call)."""
    got = np.array(list(combinations(range(2 * n + 2), n)), dtype=int)
    got.flags.writeable = False
    return got


def _centre(p: KnapsackProblem, lb: FloatArray) -> tuple[FloatArray, np.ndarray]:
    """Mean of the vertices of {x in [lb, L] : w1.x <= K1, w2.x >= R2}: a canonical interior
    point of the optimal face (its midpoint when the face is a segment)."""
    B, n = p.L.shape
    L = np.where(p.active, p.L, 0.0)
    lo = np.where(p.active, lb, 0.0)
    r2 = np.sum(p.w2 * (L + lo), axis=1) - p.K2
    # constraint rows G x = h for the candidate active sets: x_m = lo_m, x_m = L_m,
    # w1 . x = K1, w2 . x = R2
    eye = np.eye(n)
    rows = np.concatenate([np.broadcast_to(eye, (B, n, n)), np.broadcast_to(eye, (B, n, n)),
                           p.w1[:, None, :], p.w2[:, None, :]], axis=1)     # (B, 2n+2, n)
    rhs = np.concatenate([lo, L, p.K1[:, None], r2[:, None]], axis=1)       # (B, 2n+2)
    subsets = _subsets(n)                                                   # (S, n)
    G = rows[:, subsets]                                                     # (B, S, n, n)
    h = rhs[:, subsets]                                                      # (B, S, n)
    det = np.linalg.det(G)
    # each matrix's largest entry: the largest of its rows' (read once per row)
    scale = np.maximum(np.abs(rows).max(axis=2)[:, subsets].max(axis=2) ** n, TINY)
    ok = np.abs(det) > SOLVER_TOL * scale
    G = np.where(ok[..., None, None], G, np.eye(n))
    x = np.linalg.solve(G, h[..., None])[..., 0]                             # (B, S, n)
    tol = FACE_TOL * np.maximum(np.max(L, axis=1), TINY)[:, None]
    wtol = FACE_TOL * _wscale(p)[:, None]
    feas = (ok & np.all(x >= lo[:, None, :] - tol[..., None], axis=2)
            & np.all(x <= L[:, None, :] + tol[..., None], axis=2)
            & (np.einsum("bsn,bn->bs", x, p.w1) <= p.K1[:, None] + wtol)
            & (np.einsum("bsn,bn->bs", x, p.w2) >= r2[:, None] - wtol))
    cnt = feas.sum(axis=1)
    mean = np.einsum("bs,bsn->bn", feas.astype(float), x) / np.maximum(cnt, 1)[:, None]
    return np.clip(mean, lo, L), cnt > 0


def place_regions(p: KnapsackProblem, levels: FloatArray) -> FloatArray:
    """Region end points (parameters along each edge) for the given lengths.

    Returns an array (B, n, 2) of ``[lo, hi]`` arc-length parameters.  Among the optimal
    placements, the mean of the vertices of the optimal face is chosen (the midpoint when
    the regions can slide, as between parallel edges), so ties are broken symmetrically.
    """
    lb = np.where(p.active, np.maximum(levels, 0.0), 0.0)
    x, found = _centre(p, lb)
    return _ends(p, lb, x, found)


def place_regions_sure(p: KnapsackProblem, levels: FloatArray
                       ) -> tuple[FloatArray, np.ndarray] | None:
    """:func:`place_regions` by the compiled vertex enumeration
    (:func:`fcgrasp.model._leximin_kernels.centre_rows`), and which rows are sure to
    agree with it to rounding (no near-singular active set, no vertex within a band of
    a test's tolerance: the same vertices); None where the loop does not run."""
    lb = np.where(p.active, np.maximum(levels, 0.0), 0.0)
    from ._leximin_kernels import centre_rows

    got = centre_rows(p.L, p.w1, p.w2, p.K1, p.K2, p.active, lb, _subsets(p.L.shape[1]),
                      SOLVER_TOL, FACE_TOL, PLACE_NOISE_DET, PLACE_SURE_DET,
                      PLACE_SURE_BAND)
    if got is None:
        return None
    x, found, sure = got
    return _ends(p, lb, x, found), sure


def _ends(p: KnapsackProblem, lb: FloatArray, x: FloatArray, found: np.ndarray
          ) -> FloatArray:
    """:func:`place_regions`' region ends of the face's centre ``x`` (the greedy
    point where the face has no vertex: ``found`` False)."""
    L = np.where(p.active, p.L, 0.0)
    if not np.all(found):
        xg, _, _ = _fill(p, lb, _order(p))        # the greedy point is feasible too
        x = np.where(found[:, None], x, xg)
    e1 = x
    e2 = L + lb - x
    hi = np.where(p.upper1, e1, e2)
    lo = L - np.where(p.upper1, e2, e1)
    out = np.stack([lo, hi], axis=-1)
    return np.where(p.active[..., None], out, 0.0)
