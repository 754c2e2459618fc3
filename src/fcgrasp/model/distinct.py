"""Distinct alternatives among ranked plans: non-maximum suppression, as object detectors
do, on the regions of contact.

Two plans of point fingers are **the same alternative** when their fingers can be paired
so that every finger's region overlaps its partner's by more than ``fraction`` of the
shorter of the two (overlap measured along the boundary, exactly: the length of the
common part of the two polylines).  A plan shifted along the outline by an edge is then
the same alternative; a plan that moves even one finger elsewhere is another.  Regions
reduced to a point (gravity's, at the centroid) overlap when they coincide.

:func:`distinct_plans` keeps, in rank order, each plan that is not the same alternative
as a plan already kept, and records on each kept plan the plans it stands for
(``GraspPlan.similar``: their edges).  ``fraction=0`` keeps every plan.
"""

from __future__ import annotations

from dataclasses import replace
from itertools import permutations
from typing import Any

import numpy as np
import shapely

from ..core.tolerances import ROUND_TOL
from .plans import GraspPlan

__all__ = ["DEFAULT_DISTINCT", "region_overlap", "same_alternative", "distinct_plans"]

#: The documented default of ``distinct=`` / ``--distinct``: half of the shorter region.
DEFAULT_DISTINCT = 0.5


def region_overlap(a: Any, b: Any, tol: float) -> float:
    """Length of the common part of two region polylines along the boundary (points
    within ``tol`` of each other are on both).

    >>> region_overlap([[0, 0], [4, 0]], [[3, 0], [6, 0]], 1e-9)
    1.0
    """
    la, lb = shapely.LineString(np.asarray(a, float)), shapely.LineString(np.asarray(b, float))
    return float(shapely.intersection(la, shapely.buffer(lb, tol, cap_style="flat")).length)


def _overlaps(a: Any, b: Any, la: float, lb: float, fraction: float, tol: float) -> bool:
    short = min(la, lb)
    if short <= tol:                            # a point region (gravity): coincide
        return la <= tol and lb <= tol and \
            float(np.hypot(*(np.mean(a, axis=0) - np.mean(b, axis=0)))) <= tol
    return region_overlap(a, b, tol) > fraction * short


def same_alternative(p: GraspPlan, q: GraspPlan, fraction: float, tol: float) -> bool:
    """Whether two plans are the same alternative (see the module's docstring)."""
    k = len(p.regions)
    if k != len(q.regions):
        return False
    hit = [[_overlaps(p.regions[i], q.regions[j], float(p.lengths[i]), float(q.lengths[j]),
                      fraction, tol) for j in range(k)] for i in range(k)]
    return any(all(hit[i][perm[i]] for i in range(k)) for perm in permutations(range(k)))


def distinct_plans(plans: list[Any], fraction: float, size: float) -> list[Any]:
    """The ranked ``plans`` less those that are the same alternative as a better one,
    each kept plan's ``similar`` listing the edges of the plans it stands for.  Plans
    that are not :class:`~fcgrasp.GraspPlan` (a jaw's boxes) are kept as they are.
    ``size`` is the part's size (the tolerance is :data:`ROUND_TOL` of it).

    >>> import fcgrasp as fc
    >>> part = fc.read_part("demo:cam")                 # a curved outline of 360 edges
    >>> plans = fc.plan(part, fingers=2, mu=0.3, top=10)
    >>> kept = distinct_plans(plans, 0.5, part.size)
    >>> len(plans), len(kept), len(kept[0].similar)     # ten shifts of one grasp
    (10, 1, 9)
    """
    if not 0 <= fraction <= 1:
        raise ValueError(f"distinct must be a fraction in [0, 1], got {fraction!r}")
    if fraction == 0:
        return list(plans)
    tol = ROUND_TOL * size
    kept: list[Any] = []
    stands: dict[int, list[tuple[int, ...]]] = {}
    for p in plans:
        if isinstance(p, GraspPlan):
            twin = next((q for q in kept if isinstance(q, GraspPlan)
                         and same_alternative(q, p, fraction, tol)), None)
            if twin is not None:
                stands[id(twin)].append(tuple(p.edges))
                continue
            stands[id(p)] = []
        kept.append(p)
    # copies: the plans given are left as they are
    return [replace(p, similar=tuple(stands[id(p)])) if id(p) in stands else p
            for p in kept]
