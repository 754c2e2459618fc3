"""The two-finger closed forms as they were before :mod:`fcgrasp.core.kernels` (commit 185015f,
pure numpy): the oracle of ``tests/test_kernels.py`` ("kernels vs the previous
implementation identical to 1e-12 relative").  Frozen: do not edit."""

from __future__ import annotations

import numpy as np

from fcgrasp.core._checks import FloatArray
from fcgrasp.core._geom import direction as _dir
from fcgrasp.model.regions import KnapsackProblem, build_problem


def _arc_intersection(c1, h1, c2, h2):
    wrap = lambda x: (x + np.pi) % (2 * np.pi) - np.pi  # noqa: E731
    delta = wrap(c2 - c1)
    lo = np.maximum(-h1, delta - h2)
    hi = np.minimum(h1, delta + h2)
    return wrap(c1 + (lo + hi) / 2), (hi - lo) / 2


def two_finger_problems(a1: FloatArray, b1: FloatArray, c1: FloatArray, h1: FloatArray,
                        a2: FloatArray, b2: FloatArray, c2: FloatArray, h2: FloatArray,
                        margin: float) -> tuple[list[KnapsackProblem], FloatArray]:
    """Problems for the squeezing and expanding modes of two friction fingers.

    ``a, b``: (B, 2) segment ends; ``c, h``: (B,) arcs of force directions.
    Returns ``([squeeze, expand], half_width_of_shrunk_sector)``.
    """
    cen, half = _arc_intersection(c1, h1, c2 + np.pi, h2)
    hm = half - margin
    k1, k2 = _dir(cen - hm), _dir(cen + hm)
    L = np.stack([np.hypot(*(b1 - a1).T), np.hypot(*(b2 - a2).T)], axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        t1 = (b1 - a1) / np.where(L[:, :1] > 0, L[:, :1], 1.0)
        t2 = (b2 - a2) / np.where(L[:, 1:] > 0, L[:, 1:], 1.0)
    vel = np.stack([t1, t2], axis=1)
    side = np.array([0, 1])
    probs = [build_problem(side, a1, a2, vel, L, s * k1, s * k2) for s in (1.0, -1.0)]
    for pr in probs:
        pr.separable &= hm > 0           # a sector narrower than the margin has no regions
    return probs, hm


def two_level(p: KnapsackProblem, lb0: FloatArray, fr: FloatArray,
               tol: float = 1e-12) -> FloatArray:
    """:func:`_max_level` for two regions in closed form on 1-D arrays (algorithm 7.1).

    Region ``i`` must reach ``lb0[i] + t fr[i]``; returns the largest ``t``.  With the
    greedy order fixed (item ``p`` first), the slack of knapsack 2 at the greedy optimum
    of knapsack 1 is ``D(t) = b_p fill_p + b_q fill_q - (b . L - K2)``: continuous,
    non-increasing and linear on both sides of the point where item ``p`` becomes full.
    """
    a1, a2 = p.w1[:, 0], p.w1[:, 1]
    b1, b2 = p.w2[:, 0], p.w2[:, 1]
    L1, L2 = p.L[:, 0], p.L[:, 1]
    first = b1 * a2 >= b2 * a1                                   # ratio b/a of item 1 larger

    def sel(u: FloatArray, v: FloatArray) -> FloatArray:
        return np.where(first, u, v)

    ap, aq, bp, bq = sel(a1, a2), sel(a2, a1), sel(b1, b2), sel(b2, b1)
    Lp, Lq = sel(L1 - lb0[:, 0], L2 - lb0[:, 1]), sel(L2 - lb0[:, 1], L1 - lb0[:, 0])
    fp, fq = sel(fr[:, 0], fr[:, 1]), sel(fr[:, 1], fr[:, 0])
    r0 = p.K1 - a1 * lb0[:, 0] - a2 * lb0[:, 1]                  # R(t) = r0 - t af
    af = a1 * fr[:, 0] + a2 * fr[:, 1]
    c = b1 * L1 + b2 * L2 - p.K2
    inf = np.inf
    with np.errstate(divide="ignore", invalid="ignore"):
        t_cap = np.minimum(np.where(fp > 0, Lp, inf), np.where(fq > 0, Lq, inf))
        t_cap = np.minimum(t_cap, np.where(af > 0, r0 / np.where(af > 0, af, 1.0), inf))
        den = af - ap * fp
        t1 = np.where(den != 0, (r0 - ap * Lp) / np.where(den != 0, den, 1.0), inf)

        def D(t: FloatArray) -> FloatArray:
            R = r0 - t * af
            capp, capq = Lp - t * fp, Lq - t * fq
            fillp = np.where(ap > 0, np.minimum(capp, R / np.where(ap > 0, ap, 1.0)), capp)
            rest = np.maximum(R - ap * capp, 0.0)
            fillq = np.where(aq > 0, np.minimum(capq, rest / np.where(aq > 0, aq, 1.0)), capq)
            return bp * np.maximum(fillp, 0.0) + bq * np.maximum(fillq, 0.0) - c

    t_cap = np.where(np.isfinite(t_cap), t_cap, 0.0)
    tolw = tol * np.maximum((a1 + b1) * L1 + (a2 + b2) * L2, 1e-300)
    zero = np.zeros_like(t_cap)
    d0, dc = D(zero), D(t_cap)
    mid = np.where((t1 > 0) & (t1 < t_cap), t1, t_cap)
    dm = D(mid)
    left = dm < -tolw
    ta, tb = np.where(left, 0.0, mid), np.where(left, mid, t_cap)
    da, db = np.where(left, d0, dm), np.where(left, dm, dc)
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.where(da - db > 0, np.clip(da / (da - db), 0.0, 1.0), 1.0)
    t = np.where(dc >= -tolw, t_cap, ta + frac * (tb - ta))
    ok = ((d0 >= -tolw) & (t_cap >= 0) & (r0 >= -tolw) & (Lp >= -tolw) & (Lq >= -tolw)
          & np.all(p.active, axis=1))
    return np.where(ok, t, -1.0)

