"""The angle wraps of fcgrasp and the conversion of margins (private to the package;
tested in tests/test_angles.py).

:func:`wrap` and :func:`wrap_positive` are numpy's floor-modulo (``%``), the reduction
every module uses on floats and arrays.  :func:`wrap_floor` is the same wrap written with
``floor``, for the loops :mod:`fcgrasp.core.kernels` compiles (a machine instruction where
``fmod`` is a library call); the two agree to within an ulp of the angle, and each module
keeps the one it was verified with (the exhaustive checks are sensitive to the last bit on
near-degenerate parts).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from .values import Friction, Margin

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = ["wrap", "wrap_positive", "wrap_floor", "margin_radians", "shrunk_half_angle"]

_TWO_PI = 2.0 * np.pi


def wrap(angle: ArrayLike) -> Any:
    """Angles (radians) wrapped to ``[-pi, pi)``.

    >>> float(wrap(3 * np.pi / 2)), float(wrap(np.pi))
    (-1.5707963267948966, -3.141592653589793)
    """
    return (np.asarray(angle) + np.pi) % _TWO_PI - np.pi


def wrap_positive(angle: ArrayLike) -> Any:
    """Angles (radians) wrapped to ``[0, 2 pi)``: directions as counter-clockwise turns
    from the x axis.

    >>> float(wrap_positive(-np.pi / 2))
    4.71238898038469
    """
    return np.mod(angle, _TWO_PI)


def wrap_floor(angle: Any) -> Any:
    """:func:`wrap` written with ``floor``, for compiled loops (works on floats too).

    >>> float(wrap_floor(3 * np.pi / 2))
    -1.5707963267948966
    """
    return angle - _TWO_PI * np.floor((angle + np.pi) / _TWO_PI)


def margin_radians(margin: ArrayLike) -> Any:
    """A safety margin given in degrees (as every public function takes it), in radians:
    the one conversion of margins (a :class:`~fcgrasp.core.values.Margin` gives its
    own)."""
    if isinstance(margin, Margin):
        return margin.radians
    return np.radians(margin)


def shrunk_half_angle(mu: ArrayLike, margin: ArrayLike) -> Any:
    """The half-angle ``atan(mu) - margin`` (radians; ``margin`` in degrees) of a friction
    cone shrunk by the safety margin: a force inside it is inside the cone by at least
    the margin (theorem 6.3 with a margin).

    >>> round(float(np.degrees(shrunk_half_angle(1.0, 5.0))), 9)
    40.0
    """
    if isinstance(mu, Friction):
        mu = mu.mu
    return np.arctan(mu) - margin_radians(margin)
