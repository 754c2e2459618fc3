"""Geometry of region problems: from features to knapsack problems (batched).

Shared by :mod:`fcgrasp.planning.planner`: two fingers with friction (algorithm 7.1) and four
frictionless fingers, possibly with gravity (theorem 7.1).
"""

from __future__ import annotations

import numpy as np

from ..core._checks import FloatArray
from ..core._geom import direction as _dir
from ..core.kernels import pair_problems, pair_sector
from ..core.sectors import arc_intersection, meet_and_velocities, pair_arc, pairing_valid
from ..core.tolerances import TOL
from .regions import KnapsackProblem, build_problem


def two_finger_problems(a1: FloatArray, b1: FloatArray, c1: FloatArray, h1: FloatArray,
                        a2: FloatArray, b2: FloatArray, c2: FloatArray, h2: FloatArray,
                        margin: float) -> tuple[list[KnapsackProblem], FloatArray]:
    """Problems for the squeezing and expanding modes of two friction fingers.

    ``a, b``: (B, 2) segment ends; ``c, h``: (B,) arcs of force directions.
    Returns ``([squeeze, expand], half_width_of_shrunk_sector)``.  The formulas are
    :func:`fcgrasp.core.kernels.pair_sector` and :func:`fcgrasp.core.kernels.pair_problem`.
    """
    with np.errstate(invalid="ignore"):
        cen, hm = pair_sector(np.asarray(c1, float), np.asarray(h1, float),
                              np.asarray(c2, float), np.asarray(h2, float), margin)
    cen, hm = np.broadcast_to(cen, (len(a1),)), np.broadcast_to(hm, (len(a1),))
    return [problem_from_pair(pair_problems(a1, b1, a2, b2, cen, hm, s))
            for s in (1.0, -1.0)], hm


def problem_from_pair(f: dict[str, np.ndarray]) -> KnapsackProblem:
    """The :class:`KnapsackProblem` of :func:`fcgrasp.core.kernels.pair_problems`' fields."""
    L = np.stack([f["L1"], f["L2"]], axis=1)
    return KnapsackProblem(L, np.stack([f["w1_1"], f["w1_2"]], axis=1),
                           np.stack([f["w2_1"], f["w2_2"]], axis=1), np.array(f["K1"]),
                           np.array(f["K2"]), np.stack([f["up_1"], f["up_2"]], axis=1),
                           L > 0, np.array(f["separable"]))


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
