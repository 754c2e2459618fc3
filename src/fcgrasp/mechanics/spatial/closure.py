r"""Force closure of one solid grasp (definition 2.4 and theorem 3.1 in six dimensions),
mirrored by :mod:`fcgrasp.mechanics.planar.closure`.

The grasp is in force closure when its contacts' wrench cones sum to all of
:math:`\mathbb{R}^6`: the wrench map has rank 6 and internal forces keep every contact
strictly inside its exact quadratic cone (:func:`fcgrasp.spatial.closure.closure_margin`,
one second-order cone program).  Ties are not force closure.
"""

from __future__ import annotations

from numpy.typing import ArrayLike

from ...core._checks import FloatArray
from ...spatial.closure import SpatialClosure, closure_margin
from .contacts import checked

__all__ = ["force_closure", "unresisted_wrench"]


def _verdict(points: ArrayLike, normals: ArrayLike, mu: ArrayLike, torsion: ArrayLike,
             center: ArrayLike | None, radius: float | None) -> SpatialClosure:
    g, tor = checked(points, normals, mu, torsion, center, radius)
    return closure_margin(g.points, -g.normals, g.mu, tor, g.center, g.radius)


def force_closure(points: ArrayLike, normals: ArrayLike, mu: ArrayLike = 0.0,
                  torsion: ArrayLike = 0.0, *, center: ArrayLike | None = None,
                  radius: float | None = None) -> bool:
    """Whether contacts at ``points`` (k, 3) with the part's outward ``normals`` (k, 3),
    friction ``mu`` and soft fingers' ``torsion`` (one, or one per contact) hold the
    part against every force and torque.  ``center`` and ``radius`` only scale torques.

    >>> force_closure([[1, 0, 0], [-1, 0, 0]], [[1, 0, 0], [-1, 0, 0]], mu=0.3)
    False
    >>> force_closure([[1, 0, 0], [-1, 0, 0]], [[1, 0, 0], [-1, 0, 0]], mu=0.3,
    ...               torsion=0.01)
    True
    """
    return bool(_verdict(points, normals, mu, torsion, center, radius).closure)


def unresisted_wrench(points: ArrayLike, normals: ArrayLike, mu: ArrayLike = 0.0,
                      torsion: ArrayLike = 0.0, *, center: ArrayLike | None = None,
                      radius: float | None = None) -> FloatArray | None:
    """A unit wrench ``(f, m / radius)`` that no combination of the contacts' forces
    balances (every contact wrench does work >= 0 on it), or None when the grasp is in
    force closure.

    >>> d = unresisted_wrench([[1, 0, 0], [-1, 0, 0]], [[1, 0, 0], [-1, 0, 0]], mu=0.3)
    >>> abs(d.round(3)).tolist()
    [0.0, 0.0, 0.0, 1.0, 0.0, 0.0]
    """
    verdict = _verdict(points, normals, mu, torsion, center, radius)
    return None if verdict.closure else verdict.unresisted
