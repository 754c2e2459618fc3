"""Distinct alternatives among a solid's ranked plans (the rule, on solids): the
top ``k`` should be ``k`` different grasps, not one grasp moved to the next facet of a
tessellated surface.

Two plans of a solid (two soft fingers, three fingers with friction, or a parallel
jaw's two facets) are **the same alternative** at ``fraction`` when their fingers can be
paired so that every pair of regions' centres is closer than ``(r_p + r_q) / fraction``
(``r`` the plans' radii): the regions grown by ``1 / fraction`` about their centres
overlap; and, where the plans carry their inward ``normals``, every pair's normals
are within :data:`SAME_SIDE_DEG` of each other (a grasp on the next facet of a
tessellated curve turns its normals by a facet's angle; a block gripped across its
width and across its height is two grasps, however close the faces' centres).  At
``fraction = 1`` the regions themselves overlap; smaller fractions merge plans further
apart, as the polygon's rule (:mod:`fcgrasp.model.distinct`) merges smaller overlaps.
``fraction = 0`` keeps every plan.

:func:`distinct_solid_plans` keeps, in rank order, each plan that is not the same
alternative as a plan kept before, and records on each kept plan the facets of the
plans it stands for (``similar``).
"""

from __future__ import annotations

from dataclasses import replace
from itertools import permutations
from typing import Any

import numpy as np

from ..core.alternatives import Rounds, distinct_rounds, keep_distinct
from ..core.budget import PlanList, incomplete

__all__ = ["SolidPlan", "same_solid_alternative", "distinct_solid_plans", "SAME_SIDE_DEG"]

#: Paired fingers of the same alternative press within this angle of each other
#: (degrees between their inward normals).
SAME_SIDE_DEG = 45.0


class SolidPlan:
    """What the plans of a solid's grippers share (:class:`~fcgrasp.spatial.SoftPairPlan`,
    :class:`~fcgrasp.spatial.PointTriplePlan`, :class:`~fcgrasp.spatial.SolidJawPlan`):
    ranked by their ``radius``, and the facets of the plans each stands for
    (``similar``, set by :func:`distinct_solid_plans`) in their JSON."""

    radius: float
    similar: tuple[tuple[int, ...], ...]
    centers: Any

    @property
    def min_length(self) -> float:
        """The measure the plans are ranked by: ``radius``."""
        return self.radius

    @property
    def measure(self) -> float:
        """The :class:`~fcgrasp.Plan` measure: ``radius``."""
        return self.radius

    @property
    def contacts(self) -> Any:
        """The :class:`~fcgrasp.Plan` contacts: the regions' ``centers`` (fingers, 3)."""
        return self.centers

    def _with_similar(self, d: dict[str, Any]) -> dict[str, Any]:
        """A plan's JSON ``d`` with ``similar`` when it stands for other plans."""
        if self.similar:
            d["similar"] = [list(f) for f in self.similar]
        return d


def same_solid_alternative(p: Any, q: Any, fraction: float) -> bool:
    """Whether two plans of a solid are the same alternative (module docstring).

    >>> from types import SimpleNamespace as P
    >>> a = P(centers=np.array([[0.0, 0, 0], [10, 0, 0]]), radius=1.0)
    >>> b = P(centers=np.array([[10.0, 3, 0], [0, 3, 0]]), radius=1.0)
    >>> same_solid_alternative(a, b, 0.5), same_solid_alternative(a, b, 1.0)
    (True, False)
    >>> z = P(centers=np.array([[0.0, 0, 5], [0, 0, -5]]), radius=3.0,
    ...       normals=np.array([[0.0, 0, -1], [0, 0, 1]]))
    >>> y = P(centers=np.array([[0.0, 10, 0], [0, -10, 0]]), radius=3.0,
    ...       normals=np.array([[0.0, -1, 0], [0, 1, 0]]))
    >>> same_solid_alternative(z, y, 0.5)     # centres within reach, faces at 90 degrees
    False
    """
    if fraction <= 0:
        return False
    if len(p.centers) != len(q.centers):
        return False
    reach = (p.radius + q.radius) / fraction
    d = np.linalg.norm(p.centers[:, None, :] - q.centers[None, :, :], axis=-1)
    return paired((d < reach) & same_sides(p, q))


def same_sides(p: Any, q: Any) -> Any:
    """Which fingers of ``p`` (rows) and ``q`` (columns) press within
    :data:`SAME_SIDE_DEG` of each other (their inward ``normals``; every pair where a
    plan has none)."""
    np_, nq = getattr(p, "normals", None), getattr(q, "normals", None)
    if np_ is None or nq is None:
        return np.ones((len(p.centers), len(q.centers)), bool)
    a = np.asarray(np_, float) / np.linalg.norm(np_, axis=-1, keepdims=True)
    b = np.asarray(nq, float) / np.linalg.norm(nq, axis=-1, keepdims=True)
    return a @ b.T > np.cos(np.radians(SAME_SIDE_DEG))


def paired(near: Any) -> bool:
    """Whether the fingers can be paired so that every pair is ``near`` (k, k)."""
    k = len(near)
    return any(all(near[i, perm[i]] for i in range(k)) for perm in permutations(range(k)))


def distinct_solid_plans(plans: list[Any], fraction: float) -> list[Any]:
    """The plans (ranked) that are distinct alternatives at ``fraction``, each with the
    facets of the plans it stands for in ``similar`` (module docstring)."""
    if not 0 <= fraction <= 1:
        raise ValueError(f"fraction must be in [0, 1], got {fraction!r}")
    if fraction == 0:
        return list(plans)
    groups = keep_distinct(plans, lambda q, p: same_solid_alternative(q, p, fraction))
    return [replace(g[0], similar=tuple(tuple(p.facets) for p in g[1:])) for g in groups]


#: What a solid's plans are ranked by, as an incomplete answer's gap names it.
MEASURE = "region radius"


def top_distinct(search: Any, top: int | None, fraction: float,
                 suppress: Any = None) -> PlanList:
    """The first ``top`` distinct plans of a ranked ``search(n)`` (the best ``n`` plans,
    None for every plan): asked for four times more plans than it keeps, and twice
    as many again until ``top`` are kept or the search has no more
    (:func:`fcgrasp.core.alternatives.distinct_rounds`, :data:`SOLID_ROUNDS`).  A search
    that stops early (:class:`~fcgrasp.core.budget.PlanList` incomplete), or a time or
    memory budget that ends between two rounds, ends the rounds: the plans kept are the
    answer's first, incomplete, with the bound of the search's (the last plan read's
    radius between rounds: every plan not read is below it).  ``suppress(plans)``: the
    plans kept of a list read (default :func:`distinct_solid_plans`)."""
    if fraction == 0:
        plans = search(top)
        return _like(plans, list(plans))
    if suppress is None:
        def suppress(ps: Any) -> list[Any]:
            return distinct_solid_plans(list(ps), fraction)
    kept, plans, stopped = distinct_rounds(search, suppress, top, SOLID_ROUNDS)
    if stopped == "search":
        return _like(plans, kept)
    if stopped in ("time_limit", "max_memory"):
        return incomplete(kept, stopped, float(plans[-1].radius), MEASURE)
    return PlanList(kept, measure=MEASURE)


#: How a solid's distinct search asks for longer lists: four times ``top`` plans, then
#: twice as many each round, with no depth (a solid's ranked search is cheap to extend:
#: its pieces, pairs and plans are kept between rounds, and a round that reads past the
#: plans the answer needs pays for each plan it reads).
SOLID_ROUNDS = Rounds(first=4, factor=2, share=False)


def _like(plans: Any, kept: list[Any]) -> PlanList:
    """``kept`` with the completeness and bound of the search's ``plans``."""
    if isinstance(plans, PlanList):
        return plans.same_answer(kept)
    return PlanList(kept, measure=MEASURE)
