"""One grasp's arguments checked once for either space (:mod:`fcgrasp.mechanics`):
points and outward unit normals (k, D), friction per contact, and the centre and radius
that torques are taken about and divided by."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ..core._checks import FloatArray, check_array
from ..core.tolerances import TOL
from ..errors import ArgumentError


class GraspArgs(NamedTuple):
    """``points`` (k, D), outward unit ``normals`` (k, D), ``mu`` (k,), ``center``
    (D,) and ``radius`` (> 0)."""

    points: FloatArray
    normals: FloatArray
    mu: FloatArray
    center: FloatArray
    radius: float


def check_grasp(points: ArrayLike, normals: ArrayLike, mu: ArrayLike, center: ArrayLike | None,
                radius: float | None, dim: int) -> GraspArgs:
    """The arguments of one grasp in ``dim`` dimensions, each checked and named in its
    error: at least one contact, normals nonzero (normalised), ``mu >= 0`` finite,
    ``radius > 0``."""
    p = check_array(points, "points", last=dim, min_ndim=2)
    n = check_array(normals, "normals", last=dim, min_ndim=2)
    if p.ndim != 2 or len(p) == 0:
        raise ArgumentError(f"points must be one grasp, shape (k, {dim}) with k >= 1, got "
                            f"shape {p.shape}", "points")
    if n.shape != p.shape:
        raise ArgumentError(f"normals must have the shape of points {p.shape}, got "
                            f"{n.shape}", "normals")
    length = np.linalg.norm(n, axis=-1)
    if np.any(length <= TOL):
        raise ArgumentError(f"normals must be nonzero vectors, got {n.tolist()}", "normals")
    m = check_array(mu, "mu")
    if m.ndim > 1 or (m.ndim == 1 and len(m) != len(p)):
        raise ArgumentError(f"mu must be one number or one per contact ({len(p)}), got "
                            f"shape {m.shape}", "mu")
    if np.any(m < 0):
        raise ArgumentError(f"mu must be >= 0, got {m.tolist()}", "mu")
    c = p.mean(axis=0) if center is None else check_array(center, "center", last=dim)
    if c.ndim != 1:
        raise ArgumentError(f"center must be one point, shape ({dim},), got {c.shape}",
                            "center")
    if radius is None:
        r = max(float(np.max(np.linalg.norm(p - c, axis=1))), TOL)
    else:
        r = float(check_array(radius, "radius"))
        if not r > 0:
            raise ArgumentError(f"radius must be > 0, got {radius!r}", "radius")
    return GraspArgs(p, n / length[:, None], np.broadcast_to(m, len(p)).astype(float), c, r)
