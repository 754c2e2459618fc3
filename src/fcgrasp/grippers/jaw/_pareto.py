"""The parallel jaw's Pareto list (part of :mod:`fcgrasp.grippers.jaw`): proved boxes that
trade the closing angle's range against the offset's, one per weight of the two sides."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...core.tolerances import TOL
from ...model.polygon import Polygon
from ...model.regions import DEFAULT_MARGIN_DEG
from ._boxes import _proved
from ._grid import _box_scores, _checked_box, _grid
from ._plans import JawPlan, ParallelJaw, _plan_of
from ._poses import _check_jaw_args

#: The weights :func:`jaw_pareto` gives the angle side against the offset side: for
#: each, the box of largest ``min(c1 - c0, w radius (t1 - t0))``.
PARETO_WEIGHTS = tuple(2.0 ** k for k in range(-3, 4))


def jaw_pareto(polygon: Polygon, jaw: ParallelJaw, margin: float = DEFAULT_MARGIN_DEG,
               hole: int | None = None, weights: Any = PARETO_WEIGHTS) -> list[JawPlan]:
    """Boxes that trade the closing angle's range against the offset's (a
    Pareto list, for a user who cares about one side): for each weight ``w`` of
    ``weights``, the box of the pose grid with the largest ``min(c1 - c0, w R (t1 -
    t0))`` (``R`` the part's radius), checked on the fine grid and proved by
    :func:`certify_box` (shrunk by grid steps; with ``jaw.certify``), then those no
    other beats on both sides; by angle range, largest first.  A grip on the outline,
    or (``hole``) inside that hole.  The boxes are the grid's, proved, not grown to the
    exact set as :func:`jaw_plans`' are; each box's ``measure`` is the usual one.

    >>> from fcgrasp.io.parts import demo_part
    >>> jaw = ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
    >>> front = jaw_pareto(demo_part("rectangle"), jaw)
    >>> sides = [(round(float(np.degrees(p.theta[1] - p.theta[0])), 1),
    ...           round(p.offset[1] - p.offset[0], 1)) for p in front]
    >>> sides[0][0] > sides[-1][0] and sides[0][1] < sides[-1][1]  # one side for the other
    True
    """
    margin = _check_jaw_args(polygon, jaw, margin)
    ws = np.atleast_1d(np.asarray(weights, float)).ravel()
    if ws.size == 0 or not np.all(np.isfinite(ws) & (ws > 0)):
        raise ValueError(f"weights must be positive numbers, got {weights!r}")
    radius = polygon.radius
    thetas, offsets, H = _grid(polygon, jaw, margin, hole)
    K = thetas.size
    dth, dc = 2 * np.pi / K, offsets[1] - offsets[0]
    found: list[JawPlan] = []
    for w in ws:
        score, k0, k1, j0, j1 = _box_scores(H.copy(), dth, dc, radius * float(w), K // 2)
        if score <= 0:
            continue
        box = _checked_box(polygon, jaw, margin, hole,
                           thetas[k0] + np.array([0, k1 - k0]) * dth, offsets[[j0, j1]],
                           dth, dc)
        if box is None:
            continue
        if jaw.certify:
            proved = _proved(polygon, jaw, margin, hole, box[0], box[1], dth, dc)
            if proved is None:
                continue
            box = _checked_box(polygon, jaw, margin, hole, np.array(proved[0]),
                               np.array(proved[1]), dth, dc)
            if box is None:
                continue
        found.append(_plan_of(polygon, jaw, margin, hole, box, jaw.certify))

    def sides(p: JawPlan) -> tuple[float, float]:
        return p.theta[1] - p.theta[0], p.offset[1] - p.offset[0]

    front: list[JawPlan] = []
    for p in sorted(found, key=lambda q: (-sides(q)[0], -sides(q)[1])):
        a, c = sides(p)
        # beaten (or matched: a mirror, the same box again) by one kept before
        if not any(sides(q)[0] >= a - TOL and sides(q)[1] >= c - TOL * polygon.size
                   for q in front):
            front.append(p)
    return front
