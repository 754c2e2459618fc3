"""One configuration of two stretches as a small linear system, solved in closed form by
eliminating variables (part of :mod:`fcgrasp.model.stretches`)."""

from __future__ import annotations

from typing import cast

import numpy as np

from ...core._checks import FloatArray
from ...core._geom import cross2 as _cross
from ...core.tolerances import ROUND_TOL
from ._windows import _BLOCK, _EPS, _Configs, _gens_x, _gens_y, _inner, _Intervals, _Ring

# ----------------------------------------------------------------------------- one LP


def _ends(ra: _Ring, rb: _Ring, c: _Configs, Iab: _Intervals, Iba: _Intervals,
          compiled: bool, reach: int | None = None
          ) -> tuple[tuple[FloatArray, ...], tuple[FloatArray, FloatArray]]:
    """The intervals of each stretch's two end edges against the other stretch's
    interior vertices (``lo0, hi0`` first edge of stretch 1, ``lo1, hi1`` its last edge,
    ``ulo0 .. uhi1`` the same for stretch 2) and each stretch's offset from its start
    edge to its last edge.  With ``reach``, against at most the first and the last
    ``reach`` of those vertices (intervals that contain the exact ones: for a bound)."""
    mA, mB = ra.m, rb.m
    A, B = c.iA % mA, (c.iA + c.kA) % mA
    C, D = c.iC % mB, (c.iC + c.kC) % mB

    def box(iv: _Intervals, edge: np.ndarray, ring: _Ring, first: np.ndarray,
            count: np.ndarray, m: int) -> tuple[FloatArray, FloatArray]:
        if reach == 0:                  # against no vertex: the whole edge
            return np.zeros(edge.shape), ring.L[edge].astype(float)
        if reach is None:
            lo, hi = iv.window(edge, (first + 1) % m, count, compiled)
        else:
            k = np.minimum(count, reach)
            lo, hi = iv.window(edge, (first + 1) % m, k, compiled)
            lo2, hi2 = iv.window(edge, (first + 1 + count - k) % m, k, compiled)
            lo, hi = np.maximum(lo, lo2), np.minimum(hi, hi2)
        return lo, np.minimum(hi, ring.L[edge])

    lo0, hi0 = box(Iab, A, ra, c.iC, c.kC, mB)
    lo1, hi1 = box(Iab, B, ra, c.iC, c.kC, mB)
    ulo0, uhi0 = box(Iba, C, rb, c.iA, c.kA, mA)
    ulo1, uhi1 = box(Iba, D, rb, c.iA, c.kA, mA)
    off_s = np.where(c.kA > 0, ra.L[A] + _inner(ra, c.iA, c.kA), 0.0)
    off_u = np.where(c.kC > 0, rb.L[C] + _inner(rb, c.iC, c.kC), 0.0)
    return (lo0, hi0, lo1, hi1, ulo0, uhi0, ulo1, uhi1), (off_s, off_u)


#: Interior vertices at each end of the other stretch that :func:`_box_bound` reads (the
#: nearest constrain an end most; fewer vertices only loosen the bound).
BOX_REACH = 8


def _box_bound(ra: _Ring, rb: _Ring, c: _Configs, Iab: _Intervals, Iba: _Intervals,
               compiled: bool) -> FloatArray:
    """An upper bound of a configuration's common length ``t``, from its ends' boxes
    alone: stretch 1 starts no earlier than ``lo0`` on its first edge and ends no later
    than ``hi1`` on its last, so ``t <= hi1 + off_s - lo0``; the same for stretch 2.
    The intervals are those against the first and last :data:`BOX_REACH` interior
    vertices of the other stretch (they contain the exact ones), so the bound is never
    below the program's optimum (tested), and far below the arc length where the ends
    are confined (flattened curves)."""
    (lo0, _, _, hi1, ulo0, _, _, uhi1), (off_s, off_u) = _ends(ra, rb, c, Iab, Iba, compiled,
                                                               BOX_REACH)
    return cast("FloatArray", np.minimum(hi1 + off_s - lo0, uhi1 + off_u - ulo0))


def _system(ra: _Ring, rb: _Ring, c: _Configs, sigma: float, beta: float,
            Iab: _Intervals, Iba: _Intervals,
            fixed: tuple[int, FloatArray] | None = None, compiled: bool = False) -> FloatArray:
    """Rows ``c0 + cs s0 + cu u0 + ct t >= 0`` of a batch of configurations: both
    regions of length ``t`` (a square pair), or, with ``fixed = (side, length)``, the
    region of that side (0: stretch 1, 1: stretch 2) of the given length and the other
    of length ``t`` (the second level of the leximin order).  ``compiled``: the end
    intervals by the compiled loop (the same numbers)."""
    A, C = c.iA % ra.m, c.iC % rb.m
    (lo0, hi0, lo1, hi1, ulo0, uhi0, ulo1, uhi1), (off_s, off_u) = _ends(ra, rb, c, Iab, Iba,
                                                                         compiled)
    B, D = (c.iA + c.kA) % ra.m, (c.iC + c.kC) % rb.m
    # points, affine in z = (s0, u0, t): x0 + J z
    n = A.size
    zero = np.zeros((n, 2))
    one, zero1 = np.ones(n), np.zeros(n)
    # the length of each stretch: t (coefficient 1) or a fixed constant (coefficient 0)
    len_s, ct_s = zero1, one
    len_u, ct_u = zero1, one
    if fixed is not None:
        if fixed[0] == 0:
            len_s, ct_s = np.asarray(fixed[1], float), zero1
        else:
            len_u, ct_u = np.asarray(fixed[1], float), zero1
    pts = {
        "P0": (ra.a[A], ra.t[A], zero, zero, ra.f[A]),
        "P1": (ra.a[B] + (len_s - off_s)[:, None] * ra.t[B], ra.t[B], zero,
               ct_s[:, None] * ra.t[B], ra.f[B]),
        "Q0": (rb.a[C], zero, rb.t[C], zero, rb.f[C]),
        "Q1": (rb.a[D] + (len_u - off_u)[:, None] * rb.t[D], zero, rb.t[D],
               ct_u[:, None] * rb.t[D], rb.f[D]),
    }
    rows = []
    for xn in ("P0", "P1"):
        for yn in ("Q0", "Q1"):
            X, Y = pts[xn], pts[yn]
            d = [sigma * (Y[j] - X[j]) for j in range(4)]
            for g in _gens_x(X[4], beta) + _gens_y(Y[4], beta):
                rows.append(np.stack([_cross(g, dj) for dj in d], axis=1))
    # boxes: lo0 <= s0 <= hi0, lo1 <= s0 + t - off_s <= hi1, and the same for u0
    limits = [(-lo0, one, zero1, zero1), (hi0, -one, zero1, zero1),
              (len_s - lo1 - off_s, one, zero1, ct_s), (hi1 + off_s - len_s, -one, zero1, -ct_s),
              (-ulo0, zero1, one, zero1), (uhi0, zero1, -one, zero1),
              (len_u - ulo1 - off_u, zero1, one, ct_u), (uhi1 + off_u - len_u, zero1, -one, -ct_u),
              (zero1, zero1, zero1, one)]
    rows += [np.stack(r, axis=1) for r in limits]
    return np.stack(rows, axis=1)


def _eliminate(rows: FloatArray, var: int) -> FloatArray:
    """Fourier-Motzkin: rows ``c0 + sum_j c_j x_j >= 0`` (B, R, K) without ``x_var``.

    Every row with a positive coefficient of ``x_var`` is added to every row with a
    negative one (each divided by its coefficient's magnitude); rows without it stay.
    Each configuration's rows of either sign are gathered first (in their order, a
    block of the most of either that a configuration has), so that only those pairs
    are formed, in the order of every ordered pair.  The result is trimmed to the most
    valid rows of any problem of the batch (unused rows read ``1 >= 0``)."""
    B, _, K = rows.shape
    a = rows[:, :, var]
    pos, neg = a > _EPS, a < -_EPS
    with np.errstate(divide="ignore", invalid="ignore"):
        scaled = rows / np.abs(a)[..., None]
    first, ok_p = _true_first(pos)
    second, ok_n = _true_first(neg)
    rp = np.where(ok_p[..., None], np.take_along_axis(scaled, first[..., None], axis=1), 0.0)
    rn = np.where(ok_n[..., None], np.take_along_axis(scaled, second[..., None], axis=1), 0.0)
    n_pairs = first.shape[1] * second.shape[1]
    pairs = (rp[:, :, None, :] + rn[:, None, :, :]).reshape(B, n_pairs, K)
    valid = (ok_p[:, :, None] & ok_n[:, None, :]).reshape(B, n_pairs)
    zero = ~(pos | neg)
    out = np.concatenate([pairs, np.where(zero[..., None], rows, 0.0)], axis=1)
    valid = np.concatenate([valid, zero], axis=1)
    keep = np.delete(out, var, axis=2)
    trivial = np.zeros(K - 1)
    trivial[0] = 1.0
    keep = np.where(valid[..., None], keep, trivial)
    order, _ = _true_first(valid)
    return np.take_along_axis(keep, order[..., None], axis=1)


def _true_first(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per row of ``mask`` (B, R): the columns of its True entries first, in their
    order, as many as the row with the most has (at least one), and which of those are
    True."""
    width = max(int(mask.sum(axis=1).max(initial=0)), 1)
    order = np.argsort(~mask, axis=1, kind="stable")[:, :width]
    return order, np.take_along_axis(mask, order, axis=1)


def _bounds(rows: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """For rows ``c0 + c1 y >= 0`` in one unknown ``y``: the interval of ``y`` and the
    least constant of the rows without ``y``."""
    c0, c1 = rows[:, :, 0], rows[:, :, 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        q = -c0 / c1
    lo = np.max(np.where(c1 > _EPS, q, -np.inf), axis=1)
    hi = np.min(np.where(c1 < -_EPS, q, np.inf), axis=1)
    flat = np.min(np.where(np.abs(c1) <= _EPS, c0, np.inf), axis=1)
    return lo, hi, flat


def _t_bounds(r: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Bounds of t left by rows ``c0 + cu u0 + ct t >= 0`` once u0 is eliminated: every
    lower bound of u0 (``u0 >= al + ga t``) against every upper bound, and the rows
    without u0; with the least constant of the rows left without t.

    Each configuration's lower bounds are gathered first, then its upper bounds (a
    block of the most of either that a configuration has), so that only those pairs
    are formed; the pairs' quotients are the same numbers whatever the order, and the
    bounds their least and greatest."""
    c0, cu, ct = r[:, :, 0], r[:, :, 1], r[:, :, 2]
    pos, neg = cu > _EPS, cu < -_EPS
    with np.errstate(divide="ignore", invalid="ignore"):
        al = np.where(pos | neg, -c0 / cu, 0.0)
        ga = np.where(pos | neg, -ct / cu, 0.0)
    lower, ok_p = _true_first(pos)
    upper, ok_n = _true_first(neg)
    al_p, ga_p = np.take_along_axis(al, lower, axis=1), np.take_along_axis(ga, lower, axis=1)
    al_n, ga_n = np.take_along_axis(al, upper, axis=1), np.take_along_axis(ga, upper, axis=1)
    D = ga_p[:, :, None] - ga_n[:, None, :]            # (ga_p - ga_n) t <= al_n - al_p
    E = al_n[:, None, :] - al_p[:, :, None]
    valid = ok_p[:, :, None] & ok_n[:, None, :]
    zero = ~(pos | neg)
    with np.errstate(divide="ignore", invalid="ignore"):
        q = E / D
        qz = -c0 / ct
    hi = np.min(np.where(valid & (D > _EPS), q, np.inf), axis=(1, 2))
    lo = np.max(np.where(valid & (D < -_EPS), q, -np.inf), axis=(1, 2))
    hi = np.minimum(hi, np.min(np.where(zero & (ct < -_EPS), qz, np.inf), axis=1))
    lo = np.maximum(lo, np.max(np.where(zero & (ct > _EPS), qz, -np.inf), axis=1))
    flat = np.minimum(np.min(np.where(valid & (np.abs(D) <= _EPS), E, np.inf), axis=(1, 2)),
                      np.min(np.where(zero & (np.abs(ct) <= _EPS), c0, np.inf), axis=1))
    return lo, hi, flat


def _solve(rows: FloatArray, ub: FloatArray, scale: float
           ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Largest common length t of each configuration (-1 if none) and its placement.

    Exact: ``s0`` then ``u0`` are eliminated (Fourier-Motzkin), which leaves bounds on
    ``t`` alone; ``u0`` and ``s0`` are then read back as the middle of their intervals.
    ``rows``: (B, R, 4) rows ``c0 + cs s0 + cu u0 + ct t >= 0``; ``ub``: (B,) bound."""
    B = ub.size
    cap = np.stack([ub, np.zeros(B), np.zeros(B), -np.ones(B)], axis=1)[:, None, :]
    rows = np.concatenate([rows, cap], axis=1)
    r_ut = _eliminate(rows, 1)                       # (c0, cu, ct)
    tol = ROUND_TOL * scale
    # every pair of rows meets in _t_bounds: blocks of about _BLOCK * 32 pairs
    step = max(1, (_BLOCK * 32) // r_ut.shape[1] ** 2)
    parts = [_t_bounds(r_ut[b:b + step]) for b in range(0, B, step)]
    t_lo, t_hi, flat = (np.concatenate([p[j] for p in parts]) for j in range(3))
    ok = (t_lo <= t_hi + tol) & (flat >= -tol) & (t_hi >= 0) & np.isfinite(t_hi)
    t = np.where(ok, np.maximum(t_hi, 0.0), -1.0)
    tt = np.maximum(t, 0.0)
    u_lo, u_hi, _ = _bounds(np.stack([r_ut[:, :, 0] + r_ut[:, :, 2] * tt[:, None],
                                      r_ut[:, :, 1]], axis=2))
    u0 = np.where(ok, 0.5 * (u_lo + u_hi), 0.0)
    base = rows[:, :, 0] + rows[:, :, 2] * u0[:, None] + rows[:, :, 3] * tt[:, None]
    s_lo, s_hi, _ = _bounds(np.stack([base, rows[:, :, 1]], axis=2))
    s0 = np.where(ok, 0.5 * (s_lo + s_hi), 0.0)
    return t, s0, u0
