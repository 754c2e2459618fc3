r"""Grasp quality of solid grasps: Ferrari-Canny's epsilon and the volume of the grasp
wrench space (the 3-D counterpart of :mod:`fcgrasp.model.quality`).

Each contact's cone is linearised by the pyramid of
:func:`~fcgrasp.spatial.contacts.contact_wrench_generators` (``facets`` edges, forces
with a unit normal component; soft fingers add their torsion), torques are taken about
``center`` and divided by ``radius`` (Ferrari and Canny's ``lambda``).

* **epsilon L1** (Ferrari and Canny 1992): the radius of the largest ball about the
  origin inside the convex hull of every contact's generators (the wrenches reachable
  with a unit sum of normal forces): the smallest distance from the origin to a facet
  of the hull; 0 when the origin is not strictly inside (not in force closure).
* **epsilon L-infinity**: the same for the Minkowski sum of the contacts' hulls with the
  origin (every normal force at most 1).
* **volume**: the 6-D volume of the L1 hull (GraspIt!'s volume quality).

The same definitions as Dex-Net's ``ferrari_canny_L1`` (with ``torque_scaling = 1 /
radius``, its friction cone of ``num_cone_faces`` edges ``n + mu t``) and GraspIt!'s
``QualEpsilon`` and ``QualVolume``.  Differences: Dex-Net finds each facet's nearest
point by a small quadratic program, which gives the same distance when the origin is
inside; GraspIt! reports a negative epsilon when it is outside, fcgrasp 0 (a grasp that
does not hold has no quality).  Facets are computed by qhull (scipy).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core._checks import FloatArray, check_array
from ..core.tolerances import TOL
from .contacts import check_spatial_grasp, contact_wrench_generators

__all__ = ["SpatialQuality", "spatial_quality", "hull_epsilon"]

#: More Minkowski-sum points than this (L-infinity of many contacts): refused.
MAX_SUM_POINTS = 200_000


@dataclass(frozen=True)
class SpatialQuality:
    """``epsilon_l1``, ``epsilon_linf`` (0 without force closure, or when not asked) and
    ``volume``."""

    epsilon_l1: float
    epsilon_linf: float
    volume: float


def hull_epsilon(points: Any) -> tuple[float, float]:
    """The distance from the origin to the boundary of the convex hull of ``points``
    (m, d) when the origin is strictly inside it (0 otherwise), and the hull's volume
    (0 when the points do not span d dimensions)."""
    from scipy.spatial import ConvexHull, QhullError

    pts = check_array(points, "points", min_ndim=2)
    scale = max(float(np.max(np.abs(pts))), TOL)
    if np.linalg.matrix_rank(pts - pts.mean(axis=0), tol=TOL * scale) < pts.shape[1]:
        return 0.0, 0.0
    try:
        hull = ConvexHull(pts)
    except QhullError:                        # flat to qhull's precision
        return 0.0, 0.0
    offsets = hull.equations[:, -1]           # normal . x + offset <= 0 inside
    eps = float(np.min(-offsets))
    return (eps if eps > TOL * scale else 0.0), float(hull.volume)


def spatial_quality(points: Any, normals: Any, mu: Any = 0.0, torsion: Any = 0.0,
                    center: Any = None, radius: float | None = None, facets: int = 8,
                    linf: bool = False) -> SpatialQuality:
    """Ferrari-Canny epsilon (L1 and L-infinity) and the wrench space's volume of one
    grasp (module docstring): ``points``, inward ``normals`` (k, 3); ``center`` (the
    part's centre of mass; default the contacts' mean) and ``radius`` (default the
    largest distance of a contact from it) scale torques; ``linf=True`` adds the
    L-infinity measure (a Minkowski sum of ``(g + 1)^k`` points in 6-D: seconds for
    four contacts of eight facets; 0 when not asked), Dex-Net's and GraspIt!'s default
    being L1 as here.

    >>> box = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0]]
    >>> q = spatial_quality(box, [[-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0]], mu=0.5)
    >>> q.epsilon_l1 > 0, q.volume > 0, q.epsilon_linf
    (True, True, 0.0)
    """
    p, n, m, tor, c, radius = check_spatial_grasp(points, normals, mu, torsion, center,
                                                  radius)
    gens = contact_wrench_generators(p, n, m, tor, facets=facets, center=c,
                                     radius=radius)                   # (k, g, 6)
    eps1, volume = hull_epsilon(gens.reshape(-1, 6))
    epsinf = 0.0
    if linf and eps1 > 0:
        per = [np.vstack([np.zeros((1, 6)), g]) for g in gens]
        count = int(np.prod([len(q) for q in per]))
        if count > MAX_SUM_POINTS:
            raise ValueError(f"linf: the Minkowski sum has {count} points (more than "
                             f"{MAX_SUM_POINTS}); use fewer facets or linf=False")
        total = np.zeros((1, 6))
        for q in per:                         # sum hull by hull, keeping vertices only
            total = (total[:, None, :] + q[None, :, :]).reshape(-1, 6)
            total = _hull_vertices(total)
        epsinf, _ = hull_epsilon(total)
    return SpatialQuality(eps1, epsinf, volume)


def _hull_vertices(points: FloatArray) -> FloatArray:
    """The vertices of the hull of ``points`` (all of them when it is flat)."""
    from scipy.spatial import ConvexHull, QhullError

    if len(points) <= points.shape[1] + 1:
        return points
    try:
        return np.asarray(points[ConvexHull(points).vertices])
    except QhullError:
        return np.unique(np.round(points, 14), axis=0)

