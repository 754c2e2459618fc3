r"""The geometry of section 6, once, on arrays: lines of force, their meets, pair arcs,
the three pairings of four fingers and the counter-overlapping sector.

Everything here is batched over leading axes and shared by the grasp-set objects of
:mod:`fcgrasp.model.graspsets` (thin views of one edge set), the closure tests of
:mod:`fcgrasp.core.closure` (theorem 5.2) and the planner's region problems.

* :data:`PAIRINGS`: the three ways of pairing four fingers ``(a, b)`` against ``(c, d)``
  (theorem 5.2; corollary 5.1 makes every pairing with two non-null sectors describe the
  same grasp set).
* :func:`line_meet`: where the lines of force ``p1 + s f1`` and ``p2 + t f2`` meet (the
  point ``P_ab`` of eq. 36); :func:`meet_and_velocities` adds how it moves as each finger
  slides along its edge (the affine map of theorem 7.1).
* :func:`pair_arc`: the sector ``C_ab`` of two force directions as (centre, half-width).
* :func:`arc_intersection`: intersection of two arcs of directions; with
  :func:`pairing_sector` it gives ``C = C_ab & -C_cd`` (theorem 6.2).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ._angles import wrap
from ._checks import FloatArray
from ._geom import cross2
from .kernels import arc_meet
from .tolerances import TOL

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = ["PAIRINGS", "line_meet", "meet_and_velocities", "pair_arc", "arc_intersection",
           "pairing_sector", "pairing_valid"]

#: The three pairings ``(a, b, c, d)``: fingers ``a, b`` against ``c, d`` (theorem 5.2).
PAIRINGS = np.array([[0, 1, 2, 3], [0, 2, 1, 3], [0, 3, 1, 2]])


def line_meet(p1: FloatArray, f1: FloatArray, p2: FloatArray, f2: FloatArray) -> FloatArray:
    """Intersection of the lines ``p1 + s f1`` and ``p2 + t f2``, shape (..., 2).

    >>> line_meet(np.array([0., 0.]), np.array([1., 0.]), np.array([2., -1.]),
    ...           np.array([0., 1.])).tolist()
    [2.0, 0.0]
    """
    s = cross2(p2 - p1, f2) / cross2(f1, f2)
    return p1 + s[..., None] * f1


def meet_and_velocities(pa: FloatArray, ta: FloatArray, fa: FloatArray,
                        pb: FloatArray, tb: FloatArray, fb: FloatArray
                        ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """:func:`line_meet` of the lines through ``pa`` and ``pb``, and the derivatives of
    that point with respect to the arc length of each finger along its edge (unit
    tangents ``ta``, ``tb``): the affine map from finger positions to ``P_ab``."""
    den = cross2(fa, fb)
    x = line_meet(pa, fa, pb, fb)
    va = ta - (cross2(ta, fb) / den)[..., None] * fa
    vb = (cross2(tb, fb) / den)[..., None] * fa
    return x, va, vb


def pair_arc(center_a: ArrayLike, center_b: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """The sector ``C_ab`` spanned by force directions at angles ``center_a`` and
    ``center_b`` (radians): (centre, half-width), the half-width below pi/2."""
    gap = wrap(np.asarray(center_b, float) - np.asarray(center_a, float))
    return wrap(np.asarray(center_a, float) + gap / 2), np.abs(gap) / 2


def arc_intersection(c1: ArrayLike, h1: ArrayLike, c2: ArrayLike,
                     h2: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Intersection of arcs of directions (centre, half-width), each narrower than pi.

    Returns the centre and half-width of the intersection; the half-width is negative
    where the open arcs do not meet.

    >>> c, h = arc_intersection(0.0, 0.5, 0.4, 0.5)
    >>> round(float(c), 6), round(float(h), 6)
    (0.2, 0.3)
    """
    c1, h1, c2, h2 = (np.asarray(x, dtype=float) for x in (c1, h1, c2, h2))
    return arc_meet(c1, h1, c2, h2)


def pairing_valid(directions: FloatArray, pairing: ArrayLike, tol: float = TOL) -> np.ndarray:
    """Are both sectors ``C_ab`` and ``C_cd`` of ``pairing`` non-null (the two forces of a
    pair not parallel, within ``tol`` as the sine of their angle)?

    ``directions``: unit force directions (..., 4, 2); ``pairing``: (4,) or (..., 4).
    """
    idx = np.broadcast_to(np.asarray(pairing), directions.shape[:-1])
    d = np.take_along_axis(directions, idx[..., None], axis=-2)
    return ((np.abs(cross2(d[..., 0, :], d[..., 1, :])) > tol)
            & (np.abs(cross2(d[..., 2, :], d[..., 3, :])) > tol))


def pairing_sector(centers: ArrayLike, pairing: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """``C = C_ab & -C_cd`` of four force directions at angles ``centers`` (..., 4) for
    ``pairing`` (theorem 6.2): (centre, half-width), negative where empty."""
    c = np.take_along_axis(np.asarray(centers, float),
                           np.broadcast_to(np.asarray(pairing), np.shape(centers)), axis=-1)
    c12, h12 = pair_arc(c[..., 0], c[..., 1])
    c34, h34 = pair_arc(c[..., 2], c[..., 3])
    return arc_intersection(c12, h12, c34 + np.pi, h34)
