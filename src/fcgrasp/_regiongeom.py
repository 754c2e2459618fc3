"""Geometry of region problems: from features to knapsack problems (batched).

Shared by :mod:`fcgrasp.planning`: two fingers with friction (algorithm 7.1) and four
frictionless fingers, possibly with gravity (theorem 7.1).
"""

from __future__ import annotations

import numpy as np

from ._checks import FloatArray
from ._geom import direction as _dir
from .regions import KnapsackProblem, build_problem
from .sectors import arc_intersection, meet_and_velocities, pair_arc, pairing_valid
from .tolerances import TOL


def two_finger_problems(a1: FloatArray, b1: FloatArray, c1: FloatArray, h1: FloatArray,
                        a2: FloatArray, b2: FloatArray, c2: FloatArray, h2: FloatArray,
                        margin: float) -> tuple[list[KnapsackProblem], FloatArray]:
    """Problems for the squeezing and expanding modes of two friction fingers.

    ``a, b``: (B, 2) segment ends; ``c, h``: (B,) arcs of force directions.
    Returns ``([squeeze, expand], half_width_of_shrunk_sector)``.
    """
    cen, half = arc_intersection(c1, h1, c2 + np.pi, h2)
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


def four_finger_geometry(a: FloatArray, b: FloatArray, center: FloatArray,
                         pairing: np.ndarray, margin: float, tol: float = TOL
                         ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray,
                                    FloatArray, FloatArray, FloatArray, np.ndarray]:
    """The affine maps and the shrunk sector of four frictionless fingers (theorem 7.1).

    ``a, b``: (B, 4, 2) segment ends (equal for a fixed point such as gravity);
    ``center``: (B, 4) force directions (angles); ``pairing``: (B, 4) order ``(p, q, r, s)``
    pairing fingers ``p, q`` against ``r, s``.  Returns, in pairing order,
    ``(o12, o34, vel, L, k1, k2, hm, valid)``: ``P12 = o12 + vel[:, 0] s_p + vel[:, 1] s_q``
    and ``P34`` likewise (``s`` the arc length from ``a`` along each segment), the
    segment lengths ``L`` (B, 4), the edges ``k1, k2`` of the sector
    ``C_12 & -C_34`` shrunk by ``margin`` on both sides, its half-width ``hm`` and
    ``valid`` (False where the pairing has a null sector).
    """
    B = a.shape[0]
    rows = np.arange(B)[:, None]
    A = a[rows, pairing]
    Bq = b[rows, pairing]
    c = center[rows, pairing]
    f = _dir(c)
    L = np.hypot(*(Bq - A).transpose(2, 0, 1))
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.where(L[..., None] > 0, (Bq - A) / np.where(L > 0, L, 1.0)[..., None], 0.0)
    valid = pairing_valid(f, np.arange(4), tol)
    c12, h12 = pair_arc(c[:, 0], c[:, 1])
    c34, h34 = pair_arc(c[:, 2], c[:, 3])
    cen, half = arc_intersection(c12, h12, c34 + np.pi, h34)
    hm = np.where(valid, half - margin, -1.0)
    # rows with a null pairing get stand-in directions, so nothing divides by zero
    fz = f.copy()
    fz[:, 1] = np.where(valid[:, None], f[:, 1], [1.0, 0.0])
    fz[:, 3] = np.where(valid[:, None], f[:, 3], [1.0, 0.0])
    fz[:, 0] = np.where(valid[:, None], f[:, 0], [0.0, 1.0])
    fz[:, 2] = np.where(valid[:, None], f[:, 2], [0.0, 1.0])
    o12, va, vb = meet_and_velocities(A[:, 0], t[:, 0], fz[:, 0], A[:, 1], t[:, 1], fz[:, 1])
    o34, vc, vd = meet_and_velocities(A[:, 2], t[:, 2], fz[:, 2], A[:, 3], t[:, 3], fz[:, 3])
    vel = np.stack([va, vb, vc, vd], axis=1)
    vel = np.where(L[..., None] > 0, vel, 0.0)
    return o12, o34, vel, L, _dir(cen - hm), _dir(cen + hm), hm, valid


def four_finger_problems(a: FloatArray, b: FloatArray, center: FloatArray,
                         pairing: np.ndarray, margin: float, tol: float = TOL
                         ) -> tuple[list[KnapsackProblem], FloatArray, np.ndarray]:
    """Problems of four frictionless fingers (``P34 - P12`` in ``C`` and in ``-C``).

    Arguments as :func:`four_finger_geometry`.  Returns ``([plus, minus], shrunk
    half-width, valid)``; ``valid`` is False where the pairing has a null sector.
    """
    o12, o34, vel, L, k1, k2, hm, valid = four_finger_geometry(a, b, center, pairing,
                                                               margin, tol)
    side = np.array([0, 0, 1, 1])
    probs = [build_problem(side, o12, o34, vel, L, s * k1, s * k2) for s in (1.0, -1.0)]
    for pr in probs:
        pr.separable &= valid & (hm > 0)  # null pairing, or a sector narrower than the margin
    return probs, hm, valid
