"""Make docs/jaw.png, the README's picture of the parallel-jaw model: an external grip
on ``demo:rectangle`` and an internal one in a zigzag hole, each the best proved box
(the pads at its centre pose, the strip its offsets sweep, the fan of its closing
angles, and for the internal grip where the closed jaws go in):

    .venv/bin/python docs/make_jaw_figure.py
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import shapely  # noqa: E402

import fcgrasp as fc  # noqa: E402
from fcgrasp.plotting import draw_jaw_plan, save_figure  # noqa: E402

OUT = Path(__file__).resolve().parent / "jaw.png"


def s_hole_plate() -> fc.Polygon:
    """A 14 x 18 plate with a zigzag hole (non-convex)."""
    bars = [(0, 8, 6, 10), (4, 4, 6, 10), (0, 4, 6, 6), (0, 0, 2, 6), (0, 0, 6, 2)]
    hole = shapely.union_all([shapely.box(*b) for b in bars]).simplify(0)
    return fc.Polygon(np.array(shapely.box(-4, -4, 10, 14).exterior.coords)[:-1],
                      [np.array(hole.exterior.coords)[:-1]])


def main() -> None:
    fig, axes = plt.subplots(1, 2, figsize=(9, 4.2))
    rect = fc.read_part("demo:rectangle")
    jaw = fc.ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
    best = fc.plan(rect, gripper=jaw, top=1)[0]
    draw_jaw_plan(axes[0], rect, best, units="mm",
                  title=f"external: demo:rectangle, box measure {best.measure:.3g} mm")
    plate = s_hole_plate()
    small = fc.ParallelJaw(stroke=(0.5, 12), pad_width=1.0, mu=0.6)
    inside = [p for p in fc.jaw_plans(plate, small, top=5) if p.mode == "internal"][0]
    draw_jaw_plan(axes[1], plate, inside,
                  title=f"internal: a zigzag hole, box measure {inside.measure:.3g}")
    fig.tight_layout()
    save_figure(fig, str(OUT))


if __name__ == "__main__":
    main()
