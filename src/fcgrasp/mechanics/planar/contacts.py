r"""The wrenches of a planar grasp's contacts (paper section 3, eq. 3), mirrored by
:mod:`fcgrasp.mechanics.spatial.contacts`.

A contact at ``p`` with the part's outward unit normal ``n`` and friction ``mu`` pushes
with any force of its cone, spanned by the two edges ``-n +- mu t`` (``t`` the normal
turned a quarter turn counter-clockwise; one force ``-n`` without friction): each edge has
a unit normal component, as Ferrari and Canny's and Dex-Net's generators do.  The planar
cone is exactly these two edges.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ...core._checks import FloatArray
from ...core._geom import unique_rows
from .._grasp import check_grasp

__all__ = ["DIM", "WRENCH_DIM", "contact_wrenches"]

#: The dimension of points and normals, and of wrenches ``(fx, fy, tau)``.
DIM = 2
WRENCH_DIM = 3


def contact_wrenches(points: ArrayLike, normals: ArrayLike, mu: ArrayLike = 0.0, *,
                     center: ArrayLike | None = None, radius: float | None = None
                     ) -> FloatArray:
    """Each contact's wrench generators ``(fx, fy, tau / radius)``, shape (k, 2, 3): the
    forces ``-n + mu t`` and ``-n - mu t`` (the same force twice without friction) at
    ``points`` (k, 2), torques about ``center`` (default: the contacts' mean) divided by
    ``radius`` (default: the largest distance of a contact from ``center``).

    >>> contact_wrenches([[1, 0]], [[1, 0]], 0.5, center=[0, 0]).round(3).tolist()
    [[[-1.0, 0.5, 0.5], [-1.0, -0.5, -0.5]]]
    """
    g = check_grasp(points, normals, mu, center, radius, DIM)
    n = g.normals
    t = np.stack([-n[:, 1], n[:, 0]], axis=-1)
    side = np.array([1.0, -1.0])
    forces = -n[:, None, :] + side[None, :, None] * (g.mu[:, None, None] * t[:, None, :])
    r = (g.points - g.center) / g.radius
    torque = r[:, None, 0] * forces[..., 1] - r[:, None, 1] * forces[..., 0]
    return np.concatenate([forces, torque[..., None]], axis=-1)


def distinct_wrenches(points: ArrayLike, normals: ArrayLike, mu: ArrayLike,
                      center: ArrayLike | None, radius: float | None) -> FloatArray:
    """The grasp's generators (:func:`contact_wrenches`) as distinct rows (m, 3): a
    frictionless contact's one force once."""
    w = contact_wrenches(points, normals, mu, center=center, radius=radius)
    return unique_rows(w.reshape(-1, WRENCH_DIM))
