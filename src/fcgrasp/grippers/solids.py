"""Grippers on solid parts: the same gripper objects as on planar parts, each planning a
mesh its own way (the gripper interface's ``solid_plans``, :class:`~fcgrasp.grippers.
base.Gripper`).

Two fingers with friction on a solid are **soft fingers** (two point contacts never
hold a solid: nothing resists the turn about the line between them), planned by
:func:`fcgrasp.spatial.soft_pair_plans`; three fingers with friction by
:func:`fcgrasp.spatial.three_finger_plans`; a parallel jaw with flat pads by
:func:`fcgrasp.spatial.jaw.solid_jaw_plans`.  Frictionless fingers and gravity plan
planar parts only, and say so.  Every solid search takes ``top``, ``margin``, the
``distinct`` fraction (:func:`fcgrasp.spatial.alternatives.top_distinct`) and the time
budget of :func:`fcgrasp.core.budget.deadline`.

>>> from fcgrasp.grippers.fingers import TwoFingers
>>> from fcgrasp.grippers.base import SearchOptions
>>> from fcgrasp.spatial.solid import demo_solid
>>> best = solid_plans(TwoFingers(mu=0.3), demo_solid("box"), SearchOptions(top=1), 0.5)[0]
>>> best.facets, round(best.radius, 3)
((0, 5), 5.0)
"""

from __future__ import annotations

from typing import Any

from ..core.budget import PlanList
from .base import SearchOptions

__all__ = ["solid_plans", "solid_parameters", "plans_solids", "check_solid_options",
           "solid_title", "solid_no_grasp_reason", "is_solid", "check_on", "parameters_on",
           "title_on", "no_grasp_reason_on"]


def plans_solids(gripper: Any) -> bool:
    """Whether ``gripper`` plans solid parts (it has ``solid_plans``)."""
    return callable(getattr(gripper, "solid_plans", None))


def _refusal(gripper: Any) -> str:
    return (f"{gripper.title} plan planar parts only: on a solid (a mesh) two fingers "
            "with friction are soft fingers, and three fingers with friction and the "
            "parallel jaw plan it too")


def check_solid_options(gripper: Any, options: SearchOptions) -> None:
    """Refuse, naming it, what a solid search does not take: a gripper that plans
    planar parts only, a ranking other than the regions' size, ``top=None``."""
    if not plans_solids(gripper):
        raise ValueError(_refusal(gripper))
    if options.rank_by != "min_region":
        raise ValueError(f"plans of a solid are ranked by their regions' radius: "
                         f"rank_by={options.rank_by!r} would not be used")
    if options.top is None:
        raise ValueError("plans of a solid need a top (how many plans), got top=None")


def solid_plans(gripper: Any, solid: Any, options: SearchOptions,
                fraction: float) -> PlanList:
    """The gripper's ``options.top`` best plans of ``solid`` that are distinct
    alternatives (``fraction``: their regions overlap a better plan's by at most that
    share; 0 keeps every plan), best first; a :class:`~fcgrasp.core.budget.PlanList`
    that says when the time budget ended the search first."""
    check_solid_options(gripper, options)
    plans: PlanList = gripper.solid_plans(solid, options, fraction)
    return plans


def solid_parameters(gripper: Any, options: SearchOptions, plans: Any = None
                     ) -> dict[str, Any]:
    """The parameters a solid plan's report records (the gripper's, and what its
    search says of itself: ``plans.details``)."""
    if not plans_solids(gripper):
        raise ValueError(_refusal(gripper))
    params: dict[str, Any] = gripper.solid_parameters(options)
    params.update(getattr(plans, "details", None) or {})
    return params


def solid_title(gripper: Any) -> str:
    """How a figure and the command line name the gripper on a solid."""
    return str(gripper.solid_title)


def solid_no_grasp_reason(gripper: Any, margin: float) -> str:
    """One line saying why a solid has no plan for the gripper."""
    return str(gripper.solid_no_grasp_reason(margin))


# ----------------------------------------------------------------------------- either kind

def is_solid(part: Any) -> bool:
    """Whether ``part`` (what a gripper plans: a :class:`~fcgrasp.Polygon` or a
    :class:`~fcgrasp.spatial.solid.Solid`) is a solid."""
    from ..model.polygon import Polygon

    return not isinstance(part, Polygon)


def check_on(gripper: Any, part: Any, options: SearchOptions) -> Any:
    """The gripper's refusal of a part it cannot plan before any search, and the
    search's size (``check_part``); a solid's search has no size to tell (None)."""
    if is_solid(part):
        return None
    return gripper.check_part(part, options)


def parameters_on(gripper: Any, part: Any, options: SearchOptions, plans: Any = None
                  ) -> dict[str, Any]:
    """The parameters a report of the gripper's plans of ``part`` records."""
    if is_solid(part):
        return solid_parameters(gripper, options, plans)
    params: dict[str, Any] = gripper.parameters(options)
    return params


def title_on(gripper: Any, part: Any) -> str:
    """How a figure and the command line name the gripper on ``part``."""
    return solid_title(gripper) if is_solid(part) else str(gripper.title)


def no_grasp_reason_on(gripper: Any, part: Any, margin: float) -> str:
    """One line saying why ``part`` has no plan for the gripper."""
    if is_solid(part):
        return solid_no_grasp_reason(gripper, margin)
    return str(gripper.no_grasp_reason(margin))
