r"""Grasp quality of one planar grasp (section 8.1), mirrored by
:mod:`fcgrasp.mechanics.spatial.quality`.

On the generators of :func:`~fcgrasp.mechanics.planar.contacts.contact_wrenches` (unit
normal forces, torques over ``radius``): **epsilon**, Ferrari and Canny's L1 measure, the
radius of the largest ball about the origin inside their convex hull (0 when the grasp
is not in force closure), and **volume**, the volume of that hull in the 3-D wrench
space.  The planner's reported ``epsilon_l1`` (:mod:`fcgrasp.model.quality`) scales each
force to unit length instead, as the paper's generating forces are.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ...spatial.quality import hull_epsilon
from .contacts import contact_wrenches

__all__ = ["epsilon", "volume"]


def _hull(points: ArrayLike, normals: ArrayLike, mu: ArrayLike, center: ArrayLike | None,
          radius: float | None) -> tuple[float, float]:
    w = contact_wrenches(points, normals, mu, center=center, radius=radius)
    return hull_epsilon(np.unique(w.reshape(-1, 3), axis=0))


def epsilon(points: ArrayLike, normals: ArrayLike, mu: ArrayLike = 0.0, *,
            center: ArrayLike | None = None, radius: float | None = None) -> float:
    """Ferrari-Canny's L1 epsilon of contacts at ``points`` (k, 2) with the part's
    outward ``normals``: the largest wrench ball inside the hull of the unit-normal-force
    generators (0 without force closure).

    >>> round(epsilon([[1, 0], [-1, 0]], [[1, 0], [-1, 0]], mu=0.5), 4)
    0.3333
    """
    return _hull(points, normals, mu, center, radius)[0]


def volume(points: ArrayLike, normals: ArrayLike, mu: ArrayLike = 0.0, *,
           center: ArrayLike | None = None, radius: float | None = None) -> float:
    """The volume of the hull of the generators in the 3-D wrench space (GraspIt!'s
    volume quality; 0 when they do not span it).

    >>> round(volume([[1, 0], [-1, 0]], [[1, 0], [-1, 0]], mu=0.5), 4)
    0.6667
    """
    return _hull(points, normals, mu, center, radius)[1]
