"""JSON-ready values: numpy to Python, floats to 12 significant digits (core helper)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np


def json_ready(x: Any) -> Any:
    """JSON-ready copy: numpy to Python, floats to 12 significant digits (not decimals: a
    part in metres keeps its precision, one in micrometres drops its noise), -0.0 to 0.0,
    non-finite to None."""
    if isinstance(x, dict):
        return {str(k): json_ready(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [json_ready(v) for v in x]
    if isinstance(x, np.ndarray):
        return json_ready(x.tolist())
    if isinstance(x, (np.bool_, bool)):
        return bool(x)
    if isinstance(x, (np.integer, int)):
        return int(x)
    if isinstance(x, (np.floating, float)):
        v = float(x)
        if not math.isfinite(v):
            return None
        v = float(f"{v:.12g}")
        return 0.0 if v == 0 else v
    return x
