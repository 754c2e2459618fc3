"""JSON-ready values: numpy to Python, floats to 12 significant digits (core helper)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np


def _float(v: float) -> float | None:
    """One float: 12 significant digits, -0.0 to 0.0, non-finite to None."""
    if not math.isfinite(v):
        return None
    v = float(f"{v:.12g}")
    return 0.0 if v == 0 else v


def _floats(x: Any, ndim: int) -> Any:
    """A float array's ``tolist()`` (``ndim`` levels of lists of Python floats), each
    float as :func:`_float` makes it: comprehensions, not one call of :func:`json_ready`
    per number (a 2,000-edge plan's report holds thousands)."""
    if ndim == 1:
        return [_float(v) for v in x]
    if ndim == 2:
        return [[_float(v) for v in row] for row in x]
    return [_floats(v, ndim - 1) for v in x]


def json_ready(x: Any) -> Any:
    """JSON-ready copy: numpy to Python, floats to 12 significant digits (not decimals: a
    part in metres keeps its precision, one in micrometres drops its noise), -0.0 to 0.0,
    non-finite to None."""
    if isinstance(x, dict):
        return {str(k): json_ready(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [json_ready(v) for v in x]
    if isinstance(x, np.ndarray):
        if x.dtype.kind == "f" and x.ndim:
            return _floats(x.tolist(), x.ndim)
        return json_ready(x.tolist())
    if isinstance(x, (np.bool_, bool)):
        return bool(x)
    if isinstance(x, (np.integer, int)):
        return int(x)
    if isinstance(x, (np.floating, float)):
        return _float(float(x))
    return x
