"""Values checked once at the edge and trusted inside: a friction coefficient with its
cone's half-angle, a safety margin with its radians.

A :class:`Friction` or a :class:`Margin` is built from a user's number by the same
check as every public function's (:func:`~fcgrasp.core._checks.check_mu_scalar`,
:func:`~fcgrasp.core._checks.check_margin`), and those checks pass one through without
checking it again, so a value made at the edge (:func:`fcgrasp.pipeline.plan_spec`)
travels through the layers as it is.  The conversions live here once: the half-angle
``atan(mu)`` of the friction cone (theorem 6.3, figure 3) and the margin's radians, and
the cone shrunk by the margin (:meth:`Friction.shrunk`).

>>> f, m = Friction.of(0.5), Margin.of(2.0)
>>> round(f.half_angle, 6), round(m.radians, 6), round(f.shrunk(m), 6)
(0.463648, 0.034907, 0.428741)
>>> Friction.of(f) is f
True
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from ._checks import check_margin, check_mu_scalar

__all__ = ["Friction", "Margin"]


@dataclass(frozen=True)
class Friction:
    """A Coulomb friction coefficient ``mu`` (finite, >= 0) and its cone's half-angle
    ``atan(mu)`` in radians (the cone of section 2's contact with friction)."""

    mu: float
    #: what the checks of :mod:`~fcgrasp.core._checks` take it for, unchecked
    CHECKED: ClassVar[str] = "mu"

    def __post_init__(self) -> None:
        object.__setattr__(self, "mu", check_mu_scalar(self.mu, "mu"))

    @classmethod
    def of(cls, value: Any, name: str = "mu") -> Friction:
        """``value`` as a Friction: one as it is, a number checked (errors name
        ``name``)."""
        if isinstance(value, Friction):
            return value
        got = cls.__new__(cls)                  # checked once, naming ``name``
        object.__setattr__(got, "mu", check_mu_scalar(value, name))
        return got

    @property
    def half_angle(self) -> float:
        """The friction cone's half-angle ``atan(mu)`` (radians; numpy's, as
        :func:`~fcgrasp.core._angles.shrunk_half_angle` computes it)."""
        return float(np.arctan(self.mu))

    def shrunk(self, margin: Margin) -> float:
        """The half-angle of the cone shrunk by ``margin`` (radians; negative when the
        margin is wider than the cone): a force inside it is inside the cone by at least
        the margin."""
        return self.half_angle - margin.radians

    def __float__(self) -> float:
        return self.mu


@dataclass(frozen=True)
class Margin:
    """A safety margin in degrees (``[0, 90)``, as every public function takes it) and
    its radians: every grasp of a plan points at least that far inside its cones."""

    deg: float
    #: what the checks of :mod:`~fcgrasp.core._checks` take it for, unchecked
    CHECKED: ClassVar[str] = "margin"

    def __post_init__(self) -> None:
        object.__setattr__(self, "deg", check_margin(self.deg, "margin"))

    @classmethod
    def of(cls, value: Any, name: str = "margin") -> Margin:
        """``value`` as a Margin: one as it is, a number of degrees checked (errors
        name ``name``)."""
        if isinstance(value, Margin):
            return value
        got = cls.__new__(cls)                  # checked once, naming ``name``
        object.__setattr__(got, "deg", check_margin(value, name))
        return got

    @property
    def radians(self) -> float:
        """The margin in radians (:func:`~fcgrasp.core._angles.margin_radians`)."""
        return float(np.radians(self.deg))

    def __float__(self) -> float:
        return self.deg
