r"""Grasp quality of one solid grasp, mirrored by :mod:`fcgrasp.mechanics.planar.quality`.

On the generators of :func:`~fcgrasp.mechanics.spatial.contacts.contact_wrenches` (the
inscribed pyramids' edges with unit normal forces, moments over ``radius``):
**epsilon**, Ferrari and Canny's L1 measure, the radius of the largest ball about the
origin inside their convex hull (0 when the grasp is not in force closure), and
**volume**, the volume of that hull in the 6-D wrench space
(:func:`fcgrasp.spatial.quality.spatial_quality`, Dex-Net's ``ferrari_canny_L1`` and
GraspIt!'s ``QualEpsilon`` and ``QualVolume``).
"""

from __future__ import annotations

from numpy.typing import ArrayLike

from ...spatial.quality import SpatialQuality, spatial_quality
from .contacts import checked

__all__ = ["epsilon", "volume"]


def _quality(points: ArrayLike, normals: ArrayLike, mu: ArrayLike, torsion: ArrayLike,
             center: ArrayLike | None, radius: float | None, facets: int) -> SpatialQuality:
    g, tor = checked(points, normals, mu, torsion, center, radius)
    return spatial_quality(g.points, -g.normals, g.mu, tor, g.center, g.radius, facets)


def epsilon(points: ArrayLike, normals: ArrayLike, mu: ArrayLike = 0.0,
            torsion: ArrayLike = 0.0, *, center: ArrayLike | None = None,
            radius: float | None = None, facets: int = 8) -> float:
    """Ferrari-Canny's L1 epsilon of contacts at ``points`` (k, 3) with the part's
    outward ``normals``: the largest wrench ball inside the hull of the pyramids'
    generators (0 without force closure).

    >>> box = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0]]
    >>> epsilon(box, box, mu=0.5) > 0
    True
    """
    return _quality(points, normals, mu, torsion, center, radius, facets).epsilon_l1


def volume(points: ArrayLike, normals: ArrayLike, mu: ArrayLike = 0.0,
           torsion: ArrayLike = 0.0, *, center: ArrayLike | None = None,
           radius: float | None = None, facets: int = 8) -> float:
    """The volume of the hull of the generators in the 6-D wrench space (GraspIt!'s
    volume quality; 0 when they do not span it).

    >>> box = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0]]
    >>> volume(box, box, mu=0.5) > 0
    True
    """
    return _quality(points, normals, mu, torsion, center, radius, facets).volume
