"""Planning: what the user asks for, and the one dispatch that answers it.

- :mod:`~fcgrasp.planning.request`: :class:`PlanRequest`, a typed, validated, picklable
  description of a plan (part source, gripper, margin, ranking, top, outputs), and
  :func:`plan_document`, the one function that turns a request into a JSON document;
- :mod:`~fcgrasp.planning.planner`: :func:`plan` and :func:`independent_regions`, which
  dispatch once through the gripper registry (:mod:`fcgrasp.grippers`).
"""

from __future__ import annotations

from .planner import (
    RANKINGS,
    FrictionCurve,
    GraspPlan,
    friction_curve,
    geometric_key,
    independent_regions,
    plan,
    rank_key,
)
from .request import (
    LOAD_OPTIONS,
    PLAN_OPTIONS,
    READING_OPTIONS,
    SEARCH_OPTIONS,
    PlanDocument,
    PlanRequest,
    plan_document,
    template_request,
)

__all__ = ["GraspPlan", "plan", "independent_regions", "RANKINGS", "geometric_key",
           "rank_key", "PlanRequest", "PlanDocument", "plan_document", "PLAN_OPTIONS",
           "READING_OPTIONS", "LOAD_OPTIONS", "SEARCH_OPTIONS", "FrictionCurve", "friction_curve",
           "template_request"]
