"""Ranking measures of grasp plans, in a registry: name -> batched score (section 8).

A measure is one function that takes a sequence of :class:`~fcgrasp.GraspPlan` and
returns one score per plan, larger is better, and one line that registers it::

    @register("name", units="...", definition="...")
    def name(plans): return np.array([...])

:func:`fcgrasp.plan` sorts by the chosen measure, then by the leximin order of the
region lengths (definition 7.1), then by a key of the regions' coordinates that does not
depend on how the part is numbered.  ``min_region`` *is* the leximin order.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core._checks import FloatArray

__all__ = ["Measure", "MEASURES", "register"]


@dataclass(frozen=True)
class Measure:
    """A registered ranking measure: ``score(plans)`` -> (n,) floats, larger is better."""

    name: str
    score: Callable[[Sequence[Any]], FloatArray]
    units: str
    definition: str


#: The registered measures, by name (the ``rank_by`` of :func:`fcgrasp.plan`).
MEASURES: dict[str, Measure] = {}


def register(name: str, units: str, definition: str
             ) -> Callable[[Callable[[Sequence[Any]], FloatArray]],
                           Callable[[Sequence[Any]], FloatArray]]:
    """Decorator: register ``func`` as the measure ``name``."""
    def add(func: Callable[[Sequence[Any]], FloatArray]) -> Callable[[Sequence[Any]],
                                                                      FloatArray]:
        MEASURES[name] = Measure(name, func, units, definition)
        return func
    return add


def _quality(plans: Sequence[Any], key: str) -> FloatArray:
    v = np.array([p.quality[key] for p in plans], dtype=float)
    return np.where(np.isfinite(v), v, -1.0)


@register("min_region", units="length, in the part's units",
          definition="the smallest independent region (the paper's tolerance measure); "
                     "ties by the next smallest, and so on (leximin, definition 7.1)")
def min_region(plans: Sequence[Any]) -> FloatArray:
    return np.array([p.min_length for p in plans], dtype=float)


@register("resistance", units="1 / work, work in force x the part's length units",
          definition="section 8.1 made precise in fcgrasp.model.quality: the inverse of the "
                     "largest work a finger does against the worst disturbance")
def resistance(plans: Sequence[Any]) -> FloatArray:
    return _quality(plans, "resistance")


@register("epsilon", units="dimensionless (torques over the part's radius)",
          definition="Ferrari-Canny L1: radius of the largest wrench ball inside the "
                     "convex hull of the unit contact wrenches")
def epsilon(plans: Sequence[Any]) -> FloatArray:
    return _quality(plans, "epsilon_l1")


@register("payload", units="multiples of the load (plan(..., load=))",
          definition="the scale of the load every grasp of the regions carries within the "
                     "finger force limits, certified (fcgrasp.region_payload); the plans "
                     "ranked first by the smallest region, PAYLOAD_POOL times top of them, "
                     "re-ranked by it")
def payload(plans: Sequence[Any]) -> FloatArray:
    out = []
    for p in plans:
        r = getattr(p, "payload", None)
        # no force limit: every grasp carries any scale (inf), they tie
        out.append(-1.0 if r is None else min(float(r.lower), _UNLIMITED))
    return np.array(out, dtype=float)


#: the score of an unlimited payload (JSON and the rank key want finite numbers)
_UNLIMITED = 1e300
