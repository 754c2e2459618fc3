r"""The wrenches of a solid grasp's contacts (the paper's conclusion, grasps of 3-D
objects), mirrored by :mod:`fcgrasp.mechanics.planar.contacts`.

A contact at ``p`` with the part's outward unit normal ``n`` and friction ``mu`` pushes
with any force of the circular cone about ``-n``, and a soft finger (``torsion`` > 0,
a length) adds a moment about the normal; the cone is linearised by the ``facets`` edges
``-n + mu (cos a t_1 + sin a t_2)`` of the inscribed pyramid, each with a unit normal
component (:func:`fcgrasp.spatial.contacts.contact_wrench_generators`, which takes the
inward normal ``-n``).
"""

from __future__ import annotations

from numpy.typing import ArrayLike

from ...core._checks import FloatArray
from ...spatial.contacts import check_torsion, contact_wrench_generators
from .._grasp import GraspArgs, check_grasp

__all__ = ["DIM", "WRENCH_DIM", "contact_wrenches"]

#: The dimension of points and normals, and of wrenches ``(f, m)``.
DIM = 3
WRENCH_DIM = 6


def checked(points: ArrayLike, normals: ArrayLike, mu: ArrayLike, torsion: ArrayLike,
            center: ArrayLike | None, radius: float | None) -> tuple[GraspArgs, FloatArray]:
    """One solid grasp's arguments checked (:func:`fcgrasp.mechanics._grasp.check_grasp`)
    and its torsion per contact."""
    g = check_grasp(points, normals, mu, center, radius, DIM)
    return g, check_torsion(torsion, g.mu, mu)


def contact_wrenches(points: ArrayLike, normals: ArrayLike, mu: ArrayLike = 0.0,
                     torsion: ArrayLike = 0.0, *, center: ArrayLike | None = None,
                     radius: float | None = None, facets: int = 8) -> FloatArray:
    """Each contact's wrench generators ``(f, m / radius)``, shape (k, g, 6): the
    ``facets`` edges of its inscribed friction pyramid (``2 facets`` for a soft finger:
    with the torsion's two extremes; ``facets`` copies of ``-n`` without friction) at
    ``points`` (k, 3), moments about ``center`` (default: the contacts' mean) divided by
    ``radius`` (default: the largest distance of a contact from ``center``).

    >>> w = contact_wrenches([[0, 0, 1]], [[0, 0, 1]], 0.5, facets=4)
    >>> w.shape, w[0, 0, :3].round(3).tolist()
    ((1, 4, 6), [0.5, 0.0, -1.0])
    """
    g, tor = checked(points, normals, mu, torsion, center, radius)
    return contact_wrench_generators(g.points, -g.normals, g.mu, tor, facets=facets,
                                     center=g.center, radius=g.radius)
