r"""Primitive planar contacts and their convexes (paper section 3.1, figure 4).

A contact is described by its point(s) and the object's **outward** normal there;
the finger pushes along ``-n``.  Friction is the Coulomb coefficient ``mu`` and the
friction half-angle is ``phi = atan(mu)``.  Each contact exposes

* ``wrenches``: the generating wrenches ``(fx, fy, tau)``, shape (k, 3), each a unit
  force along a line of action;
* ``points`` and ``forces``: those lines of action, shapes (k, 2) and (k, 2);
* ``wrench_cone()``: the convexe of the wrenches it can exert;
* ``twist_cone()``: the total freedom it leaves, the dual of the wrench cone.

==================  ===========================================================  ====
contact             wrenches                                                     k
==================  ===========================================================  ====
FrictionlessPoint   ``-n`` through the point (fig. 4.a)                          1
FrictionPoint       the two edges ``rot(-n, +-phi)`` of the friction cone (4.b)  2
FrictionlessEdge    ``-n`` through both end points (4.c)                         2
FrictionEdge        friction cones at both end points (4.d)                      4
SoftFinger          as FrictionEdge on an edge; around a corner, the sum of      4/8
                    the friction-edge convexes of both sides (4.e)
Gravity             the weight through the centre of gravity (end of 3.1)        1
==================  ===========================================================  ====
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ._checks import FloatArray, check_direction, check_mu_scalar, check_point
from .convexes import Cone
from .screws import wrench_from_force
from .tolerances import MU_CLOSED, ON_EDGE_TOL

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = [
    "Contact",
    "FrictionlessPoint",
    "FrictionPoint",
    "FrictionlessEdge",
    "FrictionEdge",
    "SoftFinger",
    "Gravity",
    "rotate",
    "friction_cone_edges",
]


def rotate(v: ArrayLike, angle: ArrayLike) -> FloatArray:
    """Rotate planar vectors ``v`` (..., 2) counter-clockwise by ``angle`` (radians)."""
    v = np.asarray(v, dtype=float)
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


def friction_cone_edges(normal: ArrayLike, mu: ArrayLike) -> FloatArray:
    """The two edge directions ``rot(-n, +phi)``, ``rot(-n, -phi)`` of the friction cone.

    Parameters
    ----------
    normal : array_like, shape (..., 2)
        Outward unit normals.
    mu : array_like, shape (...)
        Friction coefficients.

    Returns
    -------
    ndarray, shape (..., 2, 2)
    """
    n = np.asarray(normal, dtype=float)
    # above MU_CLOSED a cone's sides are nearly the tangent's: built narrower, never wider
    phi = np.arctan(np.minimum(np.asarray(mu, dtype=float), MU_CLOSED))
    return np.stack([rotate(-n, phi), rotate(-n, -phi)], axis=-2)


def _check_edge(a: ArrayLike, b: ArrayLike, normal: ArrayLike
                ) -> tuple[FloatArray, FloatArray, FloatArray]:
    a = check_point(a, "a")
    b = check_point(b, "b")
    n = check_direction(normal, "normal")
    length = float(np.hypot(*(b - a)))
    if length == 0.0:
        raise ValueError(f"a and b must be distinct points, got a={a.tolist()} b={b.tolist()}")
    if abs(float(n @ (b - a))) > ON_EDGE_TOL * length:
        raise ValueError(f"normal must be perpendicular to the edge from a to b, got "
                         f"normal={n.tolist()} for edge {a.tolist()} -> {b.tolist()}")
    return a, b, n


class Contact:
    """Base class: a set of pure forces along lines of action."""

    points: FloatArray
    forces: FloatArray

    @property
    def wrenches(self) -> FloatArray:
        """Generating wrenches ``(fx, fy, tau)``, shape (k, 3)."""
        return wrench_from_force(self.forces, self.points)

    def wrench_cone(self) -> Cone:
        """The wrench convexe of the contact (figure 4, second column)."""
        return Cone(self.wrenches, space="wrench")

    def twist_cone(self) -> Cone:
        """The total freedom left by the contact: the dual twist convexe (figure 4, column 3)."""
        return self.wrench_cone().dual().minimal()

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self._describe()})"

    def _describe(self) -> str:  # pragma: no cover - overridden
        return ""


class FrictionlessPoint(Contact):
    """Frictionless point contact: one pure force ``-n`` through the point (figure 4.a).

    Examples
    --------
    >>> c = FrictionlessPoint([0.0, 0.0], [0.0, 1.0])
    >>> c.wrenches.tolist()
    [[-0.0, -1.0, 0.0]]
    """

    def __init__(self, point: ArrayLike, normal: ArrayLike) -> None:
        self.point = check_point(point, "point")
        self.normal = check_direction(normal, "normal")
        self.points = self.point[None, :]
        self.forces = -self.normal[None, :]

    def _describe(self) -> str:
        return f"point={self.point.tolist()}, normal={self.normal.tolist()}"


class FrictionPoint(Contact):
    """Point contact with Coulomb friction: the two edges of the friction cone (figure 4.b)."""

    def __init__(self, point: ArrayLike, normal: ArrayLike, mu: ArrayLike) -> None:
        self.point = check_point(point, "point")
        self.normal = check_direction(normal, "normal")
        self.mu = check_mu_scalar(mu, "mu")
        self.points = np.repeat(self.point[None, :], 2, axis=0)
        self.forces = friction_cone_edges(self.normal, self.mu)

    def _describe(self) -> str:
        return f"point={self.point.tolist()}, normal={self.normal.tolist()}, mu={self.mu}"


class FrictionlessEdge(Contact):
    """Frictionless edge contact from ``a`` to ``b``: ``-n`` through both ends (figure 4.c)."""

    def __init__(self, a: ArrayLike, b: ArrayLike, normal: ArrayLike) -> None:
        self.a, self.b, self.normal = _check_edge(a, b, normal)
        self.points = np.stack([self.a, self.b])
        self.forces = np.repeat(-self.normal[None, :], 2, axis=0)

    def _describe(self) -> str:
        return f"a={self.a.tolist()}, b={self.b.tolist()}, normal={self.normal.tolist()}"


class FrictionEdge(Contact):
    """Edge contact with friction: friction cones at both end points (figure 4.d)."""

    def __init__(self, a: ArrayLike, b: ArrayLike, normal: ArrayLike, mu: ArrayLike) -> None:
        self.a, self.b, self.normal = _check_edge(a, b, normal)
        self.mu = check_mu_scalar(mu, "mu")
        edges = friction_cone_edges(self.normal, self.mu)
        self.points = np.stack([self.a, self.a, self.b, self.b])
        self.forces = np.concatenate([edges, edges])

    def _describe(self) -> str:
        return (f"a={self.a.tolist()}, b={self.b.tolist()}, normal={self.normal.tolist()}, "
                f"mu={self.mu}")


class SoftFinger(Contact):
    """Soft finger contact (figure 4.e).

    On an edge it is, for force closure, an edge contact with friction.  Around a
    corner (:meth:`corner`) its wrench convexe is the convex addition of the two
    friction-edge convexes of the two sides, eight wrenches whose minimal generating
    set has six.
    """

    def __init__(self, a: ArrayLike, b: ArrayLike, normal: ArrayLike, mu: ArrayLike) -> None:
        self._parts = [FrictionEdge(a, b, normal, mu)]
        self.mu = self._parts[0].mu
        self._collect()

    def _collect(self) -> None:
        self.points = np.concatenate([p.points for p in self._parts])
        self.forces = np.concatenate([p.forces for p in self._parts])

    @classmethod
    def corner(cls, a: ArrayLike, vertex: ArrayLike, b: ArrayLike, normal_a: ArrayLike,
               normal_b: ArrayLike,
               mu: ArrayLike) -> SoftFinger:
        """A soft finger wrapped around the corner ``vertex``, touching ``a``-``vertex`` and
        ``vertex``-``b``, with the outward normals of the two sides."""
        obj = cls.__new__(cls)
        obj._parts = [FrictionEdge(a, vertex, normal_a, mu), FrictionEdge(vertex, b, normal_b, mu)]
        obj.mu = obj._parts[0].mu
        obj._collect()
        return obj

    def _describe(self) -> str:
        return ", ".join(p._describe() for p in self._parts)


class Gravity(Contact):
    """Gravity as a frictionless point contact at the centre of gravity (end of section 3.1).

    ``direction`` is the direction of the weight (default ``(0, -1)``).
    """

    def __init__(self, center: ArrayLike, direction: ArrayLike = (0.0, -1.0)) -> None:
        self.center = check_point(center, "center")
        self.direction = check_direction(direction, "direction")
        self.points = self.center[None, :]
        self.forces = self.direction[None, :]

    def _describe(self) -> str:
        return f"center={self.center.tolist()}, direction={self.direction.tolist()}"
