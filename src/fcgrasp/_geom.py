"""Small planar helpers shared by the modules (batched over leading axes)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ._checks import FloatArray


def cross2(a: FloatArray, b: FloatArray) -> FloatArray:
    """Scalar cross product ``a x b`` of planar vectors (..., 2)."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def direction(angle: Any) -> FloatArray:
    """Unit vectors (..., 2) at the given angles (radians)."""
    angle = np.asarray(angle, dtype=float)
    return np.stack([np.cos(angle), np.sin(angle)], axis=-1)


def wrap(angle: Any) -> Any:
    """Angles wrapped to [-pi, pi)."""
    return (np.asarray(angle) + np.pi) % (2 * np.pi) - np.pi
