r"""Grasp quality of one planar grasp (section 8.1), mirrored by
:mod:`fcgrasp.mechanics.spatial.quality`.

On the generators of :func:`~fcgrasp.mechanics.planar.contacts.contact_wrenches` (unit
normal forces, torques over ``radius``): **epsilon**, Ferrari and Canny's L1 measure, the
radius of the largest ball about the origin inside their convex hull (0 when the grasp
is not in force closure; :func:`fcgrasp.model.quality.ball_radius`, the planner's), and
**volume**, the volume of that hull in the 3-D wrench space.  The planner's reported
``epsilon_l1`` (:mod:`fcgrasp.model.quality`) scales each force to unit length instead,
as the paper's generating forces are.
"""

from __future__ import annotations

from numpy.typing import ArrayLike

from ...model.quality import ball_radius
from ...spatial.quality import hull_epsilon
from .contacts import distinct_wrenches

__all__ = ["epsilon", "volume"]


def epsilon(points: ArrayLike, normals: ArrayLike, mu: ArrayLike = 0.0, *,
            center: ArrayLike | None = None, radius: float | None = None) -> float:
    """Ferrari-Canny's L1 epsilon of contacts at ``points`` (k, 2) with the part's
    outward ``normals``: the largest wrench ball inside the hull of the unit-normal-force
    generators (0 without force closure).

    >>> round(epsilon([[1, 0], [-1, 0]], [[1, 0], [-1, 0]], mu=0.5), 4)
    0.3333
    """
    return ball_radius(distinct_wrenches(points, normals, mu, center, radius))


def volume(points: ArrayLike, normals: ArrayLike, mu: ArrayLike = 0.0, *,
           center: ArrayLike | None = None, radius: float | None = None) -> float:
    """The volume of the hull of the generators in the 3-D wrench space (GraspIt!'s
    volume quality; 0 when they do not span it).

    >>> round(volume([[1, 0], [-1, 0]], [[1, 0], [-1, 0]], mu=0.5), 4)
    0.6667
    """
    return hull_epsilon(distinct_wrenches(points, normals, mu, center, radius))[1]
