r"""Grasp quality (paper section 8.1), computed at a plan's representative grasp.

* ``min_region``: the length of the smallest independent region, the paper's tolerance
  measure.
* ``resistance`` and ``resistance_approx``: the grasp resistance of section 8.1, made
  precise as follows.  The part is disturbed by a translation of ``d`` (1 cm) in any
  direction and a rotation of ``theta`` (15 degrees) about its centroid.  A translation
  disturbance is resisted by the contact forces balancing a unit force through the
  centroid along the direction of motion; a rotation disturbance by those balancing a
  pure torque ``+-rho`` (a unit force at the part's radius ``rho``).  Among the balancing
  force distributions the one of least total force is used, for any number of
  generating forces (for four it is unique: the least non-negative solution; with more,
  the cheapest balancing triple).  A grasp that is not force closure cannot balance
  every disturbance: its resistance is 0.  The *work* of finger ``i`` is
  its force for the translation times ``d`` plus its force for the rotation times the
  distance its contact point moves, ``theta |p_i - c|``.  The **exact** resistance takes,
  for the worst disturbance, the largest over fingers of that sum (the two parts for the
  same finger, as the paper requires); the paper's **approximation** adds the largest
  translational work and the largest rotational work, each maximised on its own (it is
  never smaller).  Translation directions are sampled every 0.5 degree.  Both are
  reported as ``1 / work`` so that **larger is better**, matching the paper's ranking in
  decreasing order of resistance.
* ``epsilon_l1`` and ``epsilon_linf``: the Ferrari-Canny measure, the radius of the
  largest wrench ball around the origin inside the convex hull of the unit contact
  wrenches (L1: the sum of finger forces is at most 1) or inside the Minkowski sum of
  the fingers' hulls (L-infinity: every finger force at most 1).  Torques are divided by
  the characteristic length ``rho``, the largest distance from the part's centroid to
  its vertices, and taken about the centroid.
"""

from __future__ import annotations

from itertools import combinations, product
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from ..core._checks import FloatArray
from ..core._geom import unique_rows
from ..core.tolerances import DEGENERATE_TOL, RANK_RTOL, ROUND_TOL, TINY

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = ["epsilon_metrics", "resistance_metrics", "characteristic_length", "ball_radius"]


def characteristic_length(vertices: FloatArray, centroid: FloatArray) -> float:
    """Largest distance from the centroid to a vertex (the part's radius)."""
    return float(np.max(np.hypot(*(vertices - centroid).T)))


def _scaled_wrenches(points: FloatArray, forces: FloatArray, centroid: FloatArray,
                     rho: float) -> FloatArray:
    r = points - centroid
    tau = (r[:, 0] * forces[:, 1] - r[:, 1] * forces[:, 0]) / rho
    return np.column_stack([forces, tau])


#: Points from which :func:`ball_radius` reads the hull's facets from qhull (scipy's
#: ``ConvexHull``) instead of trying every plane through three of them, whose work
#: grows as ``k^4``: four frictionless fingers' 16 L-infinity sums and three fingers
#: with friction's 27 are enumerated (2.5 ms for 27 points, qhull 0.1 ms, but importing
#: ``scipy.spatial`` costs a fresh process 0.2-0.3 s of CPU, a third of a small plan's).
HULL_POINTS = 32


def ball_radius(points: FloatArray, tol: float = DEGENERATE_TOL) -> float:
    """Distance from the origin to the boundary of ``conv(points)`` in 3-D (0 when the
    origin is outside or on the boundary, or the hull is flat).

    The hull's facets are found directly: every plane through three of the points that
    has all the others on one side (a supporting plane).  Exact and fast for the few
    points of a grasp; the distance is the smallest offset of a supporting plane from
    the origin.  From :data:`HULL_POINTS` points qhull gives the facets (the same
    distance to rounding, tested against the enumeration).

    >>> cube = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
    >>> ball_radius(cube)
    1.0
    """
    P = unique_rows(np.asarray(points, float))
    k = len(P)
    if k < 4:
        return 0.0
    scale = max(float(np.max(np.abs(P))), TINY)
    Q = P / scale
    if np.linalg.matrix_rank(Q - Q.mean(axis=0), tol=RANK_RTOL) < 3:
        return 0.0
    if k > HULL_POINTS:
        from scipy.spatial import ConvexHull, QhullError  # on first use

        try:
            eq = ConvexHull(Q).equations            # n . x + d <= 0 inside, n outward
        except QhullError:                          # nearly flat: the enumeration below
            pass
        else:
            return float(max(0.0, float((-eq[:, 3]).min()))) * scale
    t = np.array(list(combinations(range(k), 3)))
    a, b, c = Q[t[:, 0]], Q[t[:, 1]], Q[t[:, 2]]
    n = np.cross(b - a, c - a)
    nn = np.linalg.norm(n, axis=1)
    keep = nn > RANK_RTOL
    a, n = a[keep], n[keep] / nn[keep, None]
    side = (Q[None, :, :] - a[:, None, :]) @ n[..., None]           # (T, k, 1)
    side = side[..., 0]
    below = np.all(side <= tol, axis=1)
    above = np.all(side >= -tol, axis=1)
    n = np.where(above[:, None] & ~below[:, None], -n, n)             # outward normals
    support = below | above
    if not support.any():
        return 0.0
    offsets = np.einsum("ij,ij->i", a[support], n[support])           # a . n_out
    return float(max(0.0, offsets.min())) * scale


def epsilon_metrics(points: FloatArray, forces: FloatArray, finger: np.ndarray,
                    centroid: FloatArray, rho: float) -> dict[str, float]:
    """Ferrari-Canny L1 and L-infinity measures of one grasp.

    ``points``, ``forces``: (k, 2) generating forces (unit); ``finger``: (k,) finger index
    of each generator.
    """
    w = _scaled_wrenches(points, forces, centroid, rho)
    l1 = ball_radius(w)
    groups = [np.concatenate([np.zeros((1, 3)), w[finger == f]])
              for f in sorted(set(finger.tolist()))]
    sums = np.array([np.sum(c, axis=0) for c in product(*groups)])
    linf = ball_radius(sums)
    return {"epsilon_l1": l1, "epsilon_linf": linf}


def _least_solutions(w: FloatArray, targets: FloatArray) -> FloatArray | None:
    """Non-negative ``lambda`` with ``lambda @ w = target`` and the least total force.

    The balancing distributions of a target form a polyhedron; the one of least
    ``sum(lambda)`` is one of its vertices, which use at most three generators (the
    wrench space has three dimensions).  All triples are solved at once and the cheapest
    feasible one is kept (ties: the first triple in index order).  With four generators
    whose null vector is positive (a force-closure grasp) this is the unique least
    non-negative solution.  Returns None when some target cannot be balanced (the grasp
    is not force closure).
    """
    k = len(w)
    if k < 3:
        return None
    trip = np.array(list(combinations(range(k), 3)))                    # (T, 3)
    M = np.transpose(w[trip], (0, 2, 1))                                  # (T, 3, 3)
    det = np.linalg.det(M)
    ok = np.abs(det) > DEGENERATE_TOL * np.max(np.abs(M), axis=(1, 2)) ** 3
    if not ok.any():
        return None
    M, trip = M[ok], trip[ok]
    # one factorisation per triple, every target a right-hand side of it
    lam = np.transpose(np.linalg.solve(M, targets.T[None]), (0, 2, 1))   # (T, m, 3)
    scale = np.max(np.abs(targets), axis=1)[None, :]
    feasible = np.all(lam >= -ROUND_TOL * np.maximum(scale, TINY)[..., None], axis=2)
    cost = np.where(feasible, lam.sum(axis=2), np.inf)                    # (T, m)
    best = np.argmin(cost, axis=0)
    if not np.all(np.isfinite(cost[best, np.arange(len(targets))])):
        return None
    out = np.zeros((len(targets), k))
    cols = trip[best]                                                     # (m, 3)
    rows = np.arange(len(targets))[:, None]
    out[rows, cols] = np.maximum(lam[best, np.arange(len(targets))], 0.0)
    return out


def resistance_metrics(points: FloatArray, forces: FloatArray, finger: np.ndarray,
                       centroid: FloatArray, rho: float, translation: float,
                       rotation_deg: float, counts: np.ndarray | None = None
                       ) -> dict[str, float]:
    """Exact and approximate grasp resistance (see the module docstring).

    ``counts`` marks which generators belong to real fingers (gravity is not a finger).
    """
    theta = np.radians(rotation_deg)
    w = _scaled_wrenches(points, forces, centroid, rho)
    ang = np.radians(np.arange(0.0, 360.0, 0.5))
    trans = -np.column_stack([np.cos(ang), np.sin(ang), np.zeros_like(ang)])
    rot = -np.array([[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]])   # torque +-rho, scaled by rho
    lt = _least_solutions(w, trans)
    lr = _least_solutions(w, rot)
    if lt is None or lr is None:
        return {"resistance": 0.0, "resistance_approx": 0.0}
    fingers = sorted(set(finger.tolist()))
    real = np.ones(len(points), bool) if counts is None else counts
    dist = np.hypot(*(points - centroid).T)

    def finger_force(lam: FloatArray, f: int) -> FloatArray:
        sel = (finger == f) & real
        vec = lam[:, sel, None] * forces[sel][None]
        return cast("FloatArray", np.hypot(*vec.sum(axis=1).T))

    wt = np.stack([finger_force(lt, f) * translation for f in fingers], axis=1)     # (m, F)
    wr = np.stack([finger_force(lr, f) * theta * float(np.max(dist[finger == f]))
                   for f in fingers], axis=1)                                          # (2, F)
    exact = float(np.max(wt[:, None, :] + wr[None, :, :]))
    approx = float(wt.max() + wr.max())
    return {"resistance": 1.0 / exact if exact > 0 else float("inf"),
            "resistance_approx": 1.0 / approx if approx > 0 else float("inf")}


def quality_of(points: ArrayLike, forces: ArrayLike, finger: Any, centroid: ArrayLike, rho: float,
               translation: float, rotation_deg: float, real: Any = None) -> dict[str, float]:
    """Every quality measure of one grasp (section 8.1; see the module docstring).

    Parameters
    ----------
    points, forces : array_like, shape (k, 2)
        The grasp's generating forces (unit) and where they act.
    finger : array_like of int, shape (k,)
        The finger of each generator.
    centroid : array_like, shape (2,)
        The part's centroid: torques are taken about it.
    rho : float
        The part's radius: torques are divided by it (units of length).
    translation, rotation_deg : float
        The disturbance of the resistance measure (part's units, degrees).
    real : array_like of bool, shape (k,), optional
        Which generators are real fingers (gravity is not).

    Returns
    -------
    dict
        ``epsilon_l1``, ``epsilon_linf`` (dimensionless), ``resistance`` and
        ``resistance_approx`` (1 / work; 0 when the grasp is not force closure).
    """
    p, f = np.asarray(points, float), np.asarray(forces, float)
    fi = np.asarray(finger)
    out = epsilon_metrics(p, f, fi, np.asarray(centroid, float), rho)
    out.update(resistance_metrics(p, f, fi, np.asarray(centroid, float), rho, translation,
                                  rotation_deg, None if real is None else np.asarray(real)))
    return out
