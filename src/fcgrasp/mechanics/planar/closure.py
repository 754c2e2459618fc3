r"""Force closure of one planar grasp (theorem 6.1), mirrored by
:mod:`fcgrasp.mechanics.spatial.closure`.

The grasp is in force closure when its contacts' wrench cones sum to all of
:math:`\mathbb{R}^3`: every plane through the origin spanned by two generators has
generators strictly on both sides (:func:`fcgrasp.core.closure.closure_escape`, exact:
a planar friction cone is its two edges).  Ties are not force closure.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ...core._checks import FloatArray
from ...core.closure import closure_escape
from .contacts import distinct_wrenches

__all__ = ["force_closure", "unresisted_wrench"]


def _verdict(points: ArrayLike, normals: ArrayLike, mu: ArrayLike,
             center: ArrayLike | None, radius: float | None) -> tuple[bool, FloatArray]:
    closed, twist = closure_escape(distinct_wrenches(points, normals, mu, center, radius))
    return bool(closed), twist


def force_closure(points: ArrayLike, normals: ArrayLike, mu: ArrayLike = 0.0, *,
                  center: ArrayLike | None = None, radius: float | None = None) -> bool:
    """Whether contacts at ``points`` (k, 2) with the part's outward ``normals`` (k, 2)
    and friction ``mu`` (one, or one per contact) hold the part against every force and
    torque (theorem 6.1).  ``center`` and ``radius`` only scale torques.

    >>> force_closure([[1, 0], [-1, 0]], [[1, 0], [-1, 0]], mu=0.3)
    True
    >>> force_closure([[1, 0], [-1, 0.5]], [[1, 0], [-1, 0]], mu=0.2)
    False
    """
    return _verdict(points, normals, mu, center, radius)[0]


def unresisted_wrench(points: ArrayLike, normals: ArrayLike, mu: ArrayLike = 0.0, *,
                      center: ArrayLike | None = None, radius: float | None = None
                      ) -> FloatArray | None:
    """A unit wrench ``(fx, fy, tau / radius)`` that no combination of the contacts'
    forces balances (every contact wrench does work >= 0 on it: the escape twist of
    theorem 6.1 written as a wrench), or None when the grasp is in force closure.

    >>> unresisted_wrench([[1, 0], [-1, 0]], [[1, 0], [-1, 0]], mu=0.3) is None
    True
    >>> abs(unresisted_wrench([[1, 0], [-1, 0]], [[1, 0], [-1, 0]])).round(3).tolist()
    [0.0, 0.0, 1.0]
    """
    closed, twist = _verdict(points, normals, mu, center, radius)
    if closed:
        return None
    omega, vx, vy = twist
    d = np.array([vx, vy, omega], dtype=float)
    out: FloatArray = d / np.linalg.norm(d)
    return out
