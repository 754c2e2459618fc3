r"""Screws: wrenches, twists and virtual work (paper section 2.1, 2.2 and 2.4).

Conventions, used everywhere in fcgrasp:

* a planar **wrench** is ``w = (fx, fy, tau)`` with ``tau = r x f = rx*fy - ry*fx``,
  the moment about the origin of a force ``f`` whose line passes through ``r``
  (eq. 3 and 11);
* a planar **twist** is ``t = (omega, vx, vy)``: the angular velocity and the
  velocity of the point of the body at the origin (eq. 10);
* the **virtual work** of ``w`` against ``t`` is
  :math:`w \cdot t^s = f_x v_x + f_y v_y + \tau\,\omega` (eq. 4), where
  ``t^s = (vx, vy, omega)`` is the spatial transpose of the twist.

A (twist, wrench) pair is *reciprocal* when the work is zero, *repelling* when it is
positive (the motion breaks contact) and *contrary* when it is negative (the contact
force resists the motion), definition 2.2.

The spatial (6-D Plücker) forms of eq. 1-4 are given for 3-D work:
``wrench = [f | r x f]``, ``twist = [omega | r x omega]`` or ``[0 | v]``, and
``w . t^s = f . dx + m . dalpha``.

All functions broadcast over leading axes: a batch of one is just an array.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, cast

import numpy as np

from ._checks import FloatArray, check_array, check_tol
from .tolerances import TOL

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = [
    "wrench_from_force",
    "twist_about_point",
    "twist_translation",
    "twist_transpose",
    "virtual_work",
    "classify_twist_wrench",
    "velocity_at",
    "rotation_center",
    "spatial_wrench_from_force",
    "spatial_twist_about_axis",
    "spatial_twist_translation",
    "spatial_transpose",
    "spatial_virtual_work",
    "RECIPROCAL",
    "REPELLING",
    "CONTRARY",
]

RECIPROCAL = "reciprocal"
REPELLING = "repelling"
CONTRARY = "contrary"


def wrench_from_force(force: ArrayLike, point: ArrayLike) -> FloatArray:
    """Planar wrench of a force whose line of action passes through ``point`` (eq. 3, 11).

    Parameters
    ----------
    force : array_like, shape (..., 2)
    point : array_like, shape (..., 2)

    Returns
    -------
    ndarray, shape (..., 3)
        ``(fx, fy, px*fy - py*fx)``.

    Examples
    --------
    >>> wrench_from_force([0.0, -1.0], [2.0, 1.0]).tolist()
    [0.0, -1.0, -2.0]
    """
    f = check_array(force, "force", last=2)
    p = check_array(point, "point", last=2)
    f, p = np.broadcast_arrays(f, p)
    tau = p[..., 0] * f[..., 1] - p[..., 1] * f[..., 0]
    return np.concatenate([f, tau[..., None]], axis=-1)


def twist_about_point(center: ArrayLike, omega: ArrayLike = 1.0) -> FloatArray:
    """Planar twist of a rotation at rate ``omega`` about ``center`` (eq. 2, 10).

    The velocity of the origin is ``omega * z x (0 - c) = omega * (cy, -cx)``.

    Examples
    --------
    >>> twist_about_point([1.0, 2.0]).tolist()
    [1.0, 2.0, -1.0]
    """
    c = check_array(center, "center", last=2)
    w = check_array(omega, "omega")
    c, w = np.broadcast_arrays(c, np.asarray(w)[..., None])
    w = w[..., 0]
    return np.stack([w, w * c[..., 1], -w * c[..., 0]], axis=-1)


def twist_translation(v: ArrayLike) -> FloatArray:
    """Planar twist of a pure translation with velocity ``v``: ``(0, vx, vy)``.

    Examples
    --------
    >>> twist_translation([0.0, -1.0]).tolist()
    [0.0, 0.0, -1.0]
    """
    v = check_array(v, "v", last=2)
    return np.concatenate([np.zeros(v.shape[:-1] + (1,)), v], axis=-1)


def twist_transpose(twist: ArrayLike) -> FloatArray:
    """Spatial transpose of a planar twist: ``(omega, vx, vy) -> (vx, vy, omega)``."""
    t = check_array(twist, "twist", last=3)
    return t[..., [1, 2, 0]]


def virtual_work(wrench: ArrayLike, twist: ArrayLike) -> FloatArray:
    r"""Virtual work :math:`w \cdot t^s = f_x v_x + f_y v_y + \tau\omega` (eq. 4).

    Broadcasts ``wrench`` (..., 3) against ``twist`` (..., 3).

    Examples
    --------
    >>> float(virtual_work([0.0, -1.0, 0.0], [0.0, 0.0, -1.0]))  # push down, move down
    1.0
    """
    w = check_array(wrench, "wrench", last=3)
    t = check_array(twist, "twist", last=3)
    return w[..., 0] * t[..., 1] + w[..., 1] * t[..., 2] + w[..., 2] * t[..., 0]


def classify_twist_wrench(twist: ArrayLike, wrench: ArrayLike, tol: float = TOL) -> np.ndarray:
    """Classify (twist, wrench) pairs as reciprocal, repelling or contrary (definition 2.2).

    The work is compared with ``tol * (|f| |v| + |tau| |omega|)``, so the decision does
    not depend on units; within that band the pair is reciprocal.

    Returns
    -------
    ndarray of str
        ``"reciprocal"``, ``"repelling"`` or ``"contrary"`` per pair.

    Examples
    --------
    >>> str(classify_twist_wrench([0.0, 0.0, -1.0], [0.0, -1.0, 0.0]))
    'repelling'
    """
    tol = check_tol(tol)
    w = check_array(wrench, "wrench", last=3)
    t = check_array(twist, "twist", last=3)
    work = virtual_work(w, t)
    scale = (np.hypot(w[..., 0], w[..., 1]) * np.hypot(t[..., 1], t[..., 2])
             + np.abs(w[..., 2] * t[..., 0]))
    out = np.where(work > tol * scale, REPELLING,
                   np.where(work < -tol * scale, CONTRARY, RECIPROCAL))
    return out


def velocity_at(twist: ArrayLike, point: ArrayLike) -> FloatArray:
    """Velocity of the body point at ``point`` under ``twist``: ``v + omega z x p``."""
    t = check_array(twist, "twist", last=3)
    p = check_array(point, "point", last=2)
    return np.stack([t[..., 1] - t[..., 0] * p[..., 1], t[..., 2] + t[..., 0] * p[..., 0]],
                    axis=-1)


def rotation_center(twist: ArrayLike) -> FloatArray:
    """Instantaneous centre of rotation ``(-vy/omega, vx/omega)``; NaN for translations."""
    t = check_array(twist, "twist", last=3)
    with np.errstate(divide="ignore", invalid="ignore"):
        c = np.stack([-t[..., 2] / t[..., 0], t[..., 1] / t[..., 0]], axis=-1)
    return np.where((t[..., 0] == 0)[..., None], np.nan, c)


# ----------------------------------------------------------------------------- spatial


def spatial_wrench_from_force(force: ArrayLike, point: ArrayLike) -> FloatArray:
    """Spatial wrench ``[f | r x f]`` of a 3-D force through ``point`` (eq. 1, 3)."""
    f = check_array(force, "force", last=3)
    r = check_array(point, "point", last=3)
    f, r = np.broadcast_arrays(f, r)
    return np.concatenate([f, np.cross(r, f)], axis=-1)


def spatial_twist_about_axis(direction: ArrayLike, point: ArrayLike,
                             omega: ArrayLike = 1.0) -> FloatArray:
    """Spatial twist ``[w | r x w]`` of a rotation about the axis through ``point`` (eq. 2)."""
    d = check_array(direction, "direction", last=3)
    r = check_array(point, "point", last=3)
    om = check_array(omega, "omega")
    norm = np.linalg.norm(d, axis=-1, keepdims=True)
    if np.any(norm == 0):
        raise ValueError(f"direction must be non-zero, got {direction!r}")
    w = d / norm * np.asarray(om)[..., None]
    w, r = np.broadcast_arrays(w, r)
    return np.concatenate([w, np.cross(r, w)], axis=-1)


def spatial_twist_translation(v: ArrayLike) -> FloatArray:
    """Spatial twist ``[0 | v]`` of a pure translation (a free vector)."""
    v = check_array(v, "v", last=3)
    return np.concatenate([np.zeros_like(v), v], axis=-1)


def spatial_transpose(s: ArrayLike) -> FloatArray:
    """Swap the upper and lower halves of a spatial vector: ``[a | b] -> [b | a]``."""
    s = check_array(s, "s", last=6)
    return np.concatenate([s[..., 3:], s[..., :3]], axis=-1)


def spatial_virtual_work(wrench: ArrayLike, twist: ArrayLike) -> FloatArray:
    """Virtual work ``f . dx + m . dalpha`` of a spatial wrench against a twist (eq. 4)."""
    w = check_array(wrench, "wrench", last=6)
    t = check_array(twist, "twist", last=6)
    work = np.sum(w[..., :3] * t[..., 3:], axis=-1) + np.sum(w[..., 3:] * t[..., :3], axis=-1)
    return cast("FloatArray", work)
