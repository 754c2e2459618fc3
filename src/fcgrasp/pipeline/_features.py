"""The features a search places fingers on: the part's edges (or a hand's contact
features), their friction cones and lengths (part of :mod:`fcgrasp.pipeline`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

import numpy as np

from ..core._checks import (
    FloatArray,
)
from ..core.tolerances import LEXIMIN_STEP
from ..model.hand import Hand
from ..model.polygon import Polygon

# ----------------------------------------------------------------------------- features

@dataclass
class Features:
    """Contactable pieces of edges (whole edges, or their feasible parts under a hand).

    The fingers of a candidate are indices into these arrays."""

    edge: np.ndarray        # (F,) parent edge
    a: FloatArray           # (F, 2)
    b: FloatArray           # (F, 2)
    offset: FloatArray      # (F,) arc length of a along the parent edge
    center: FloatArray      # (F,) angle of -n
    half: FloatArray        # (F,) friction half-angle
    lengths: FloatArray = field(init=False)     # (F,) |b - a|
    #: the rows the compiled stream made of these features, by the call's arguments
    #: (:func:`_made_rows`: the searches of one plan stream the same rows)
    made: dict[Any, Any] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        self.lengths = np.hypot(*(self.b - self.a).T)
        self.made = {}


def features(polygon: Polygon, mu: float = 0.0, hand: Hand | None = None,
             edges: Any = None) -> Features:
    """Contactable pieces of the edges (of ``edges`` only, if given): whole usable edges,
    or their parts a :class:`~fcgrasp.Hand` can reach (section 8.2).

    Every step of the pipeline needs them for every batch, so the last few are kept
    (the arrays are read-only)."""
    key = None if edges is None else tuple(sorted({int(e) for e in edges}))
    return _features(polygon, float(mu), hand, key)


@lru_cache(maxsize=8)
def _features(polygon: Polygon, mu: float, hand: Hand | None,
              edges: tuple[int, ...] | None) -> Features:
    rows = []
    if hand is None:
        ivs = [[(0.0, float(L))] if polygon.usable[e] else [] for e, L in
               enumerate(polygon.lengths)]
    else:
        ivs = hand.feasible_intervals(polygon, min_length=LEXIMIN_STEP * polygon.size)
    wanted = None if edges is None else set(int(e) for e in edges)
    for e, lst in enumerate(ivs):
        if wanted is not None and e not in wanted:
            continue
        for t0, t1 in lst:
            rows.append((e, t0, t1))
    if not rows:
        z = np.zeros((0, 2))
        return Features(np.zeros(0, int), z, z, np.zeros(0), np.zeros(0), np.zeros(0))
    ei = np.array([r[0] for r in rows])
    s0 = np.array([r[1] for r in rows])
    s1 = np.array([r[2] for r in rows])
    tan = polygon.tangents[ei]
    a = polygon.starts[ei] + s0[:, None] * tan
    b = polygon.starts[ei] + s1[:, None] * tan
    n = polygon.normals[ei]
    center = np.arctan2(-n[:, 1], -n[:, 0])
    out = Features(ei, a, b, s0, center, np.full(len(ei), float(np.arctan(mu))))
    for arr in (out.edge, out.a, out.b, out.offset, out.center, out.half, out.lengths):
        arr.flags.writeable = False
    return out
