"""The built-in parts (``demo:NAME``): the paper's figure-1 shapes, a washer, a
rectangle and a cam of 360 edges, for the demo, the tests and the examples."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..model.polygon import Polygon


def _regular(n: int, r: float = 1.0, phase: float = 0.0) -> list[list[float]]:
    a = phase + np.arange(n) * 2 * np.pi / n
    return np.round(np.column_stack([r * np.cos(a), r * np.sin(a)]), 12).tolist()


def _cam(n: int = 360) -> list[list[float]]:
    """A smooth cam (base circle of radius 40 mm with a lobe), flattened to ``n`` edges."""
    a = np.arange(n) * 2 * np.pi / n
    r = 40.0 * (1 + 0.3 * np.exp(-(np.angle(np.exp(1j * (a - 1.0))) / 0.6) ** 2))
    return np.round(np.column_stack([r * np.cos(a), r * np.sin(a)]), 12).tolist()


#: Built-in parts, in millimetres, in the spirit of the paper's figure 1 (and a curved
#: part, whose regions run along the boundary).
DEMO_PARTS: dict[str, dict[str, Any]] = {
    # figure 1.a: grasps with friction on two edges of an irregular blob
    "blob": {"vertices": [[0, 0], [42, -6], [70, 14], [64, 46], [30, 58], [-4, 36]]},
    # figure 1.b: frictionless grasps on three edges
    "triangle": {"vertices": [[0, 0], [60, 0], [22, 48]]},
    # figure 1.c: frictionless grasps on four edges
    "quad": {"vertices": [[0, 0], [56, 8], [50, 44], [6, 38]]},
    "bracket": {"vertices": [[0, 0], [60, 0], [60, 14], [16, 14], [16, 50], [0, 50]]},
    "washer": {"vertices": _regular(12, 30.0, 0.1),
               "holes": [_regular(8, 12.0, 0.3)]},
    "rectangle": {"vertices": [[0, 0], [80, 0], [80, 30], [0, 30]]},
    "cam": {"vertices": _cam()},
}


def demo_part(name: str) -> Polygon:
    """A built-in part by name (see :data:`DEMO_PARTS`)."""
    if name not in DEMO_PARTS:
        from ..spatial.solid import DEMO_SOLIDS

        raise ValueError(f"unknown demo part {name!r}: choose from {', '.join(DEMO_PARTS)} "
                         f"(solids: {', '.join(DEMO_SOLIDS)})")
    d = DEMO_PARTS[name]
    return Polygon(d["vertices"], d.get("holes", ()))
