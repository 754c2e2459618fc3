"""fcgrasp: force-closure grasps of planar objects, after Nguyen's paper.

Modules mirror the paper: :mod:`~fcgrasp.screws` (section 2.1-2.2, 2.4),
:mod:`~fcgrasp.convexes` (2.3), :mod:`~fcgrasp.contacts` (3.1),
:mod:`~fcgrasp.grasp` (3.2), :mod:`~fcgrasp.closure` (4, 5, 6),
:mod:`~fcgrasp.polygon` (the part), :mod:`~fcgrasp.graspsets` (6),
:mod:`~fcgrasp.regions` and :mod:`~fcgrasp.planning` (7, 8), :mod:`~fcgrasp.quality`
(8.1), :mod:`~fcgrasp.hand` (8.2), :mod:`~fcgrasp.parts` (reading part files).
"""

from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING, Any

from .closure import (
    closure_escape,
    force_direction_closure,
    friction_pair_closure,
    friction_pair_modes,
    is_force_closure,
    torque_closure,
)
from .contacts import (
    Contact,
    FrictionEdge,
    FrictionlessEdge,
    FrictionlessPoint,
    FrictionPoint,
    Gravity,
    SoftFinger,
)
from .convexes import Cone
from .grasp import ClosureReport, Grasp
from .hand import Hand
from .polygon import Polygon
from .screws import (
    CONTRARY,
    RECIPROCAL,
    REPELLING,
    classify_twist_wrench,
    rotation_center,
    spatial_transpose,
    spatial_twist_about_axis,
    spatial_twist_translation,
    spatial_virtual_work,
    spatial_wrench_from_force,
    twist_about_point,
    twist_translation,
    twist_transpose,
    velocity_at,
    virtual_work,
    wrench_from_force,
)
from .tolerances import TOL

if TYPE_CHECKING:   # for type checkers; at run time these load on first use
    from .graspsets import (
        FrictionGraspSet,
        FrictionlessGraspSet,
        Vertex,
        grasp_set,
        grasp_sets,
        three_edge_grasp_sets,
    )
    from .parts import read_part
    from .planning import GraspPlan, independent_regions, plan

#: Names loaded on first use (PEP 562), so that ``import fcgrasp`` stays light: the grasp
#: sets, the planner and the readers are imported when a program first asks for them.
_LAZY = {
    "FrictionGraspSet": "graspsets", "FrictionlessGraspSet": "graspsets",
    "Vertex": "graspsets", "grasp_set": "graspsets", "grasp_sets": "graspsets",
    "three_edge_grasp_sets": "graspsets", "read_part": "parts", "GraspPlan": "planning",
    "independent_regions": "planning", "plan": "planning",
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        value = getattr(import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'fcgrasp' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


#: The package version (kept equal to pyproject.toml's by tests/test_imports.py; a literal,
#: because importlib.metadata alone costs more than the rest of ``import fcgrasp``).
__version__ = "0.1.0"

__all__ = [
    "TOL",
    "CONTRARY",
    "RECIPROCAL",
    "REPELLING",
    "ClosureReport",
    "Cone",
    "Contact",
    "FrictionEdge",
    "FrictionPoint",
    "FrictionlessEdge",
    "FrictionlessPoint",
    "FrictionGraspSet",
    "FrictionlessGraspSet",
    "Grasp",
    "GraspPlan",
    "Gravity",
    "Hand",
    "Polygon",
    "Vertex",
    "SoftFinger",
    "classify_twist_wrench",
    "closure_escape",
    "force_direction_closure",
    "friction_pair_closure",
    "friction_pair_modes",
    "grasp_set",
    "independent_regions",
    "plan",
    "read_part",
    "grasp_sets",
    "three_edge_grasp_sets",
    "is_force_closure",
    "rotation_center",
    "spatial_transpose",
    "spatial_twist_about_axis",
    "spatial_twist_translation",
    "spatial_virtual_work",
    "spatial_wrench_from_force",
    "torque_closure",
    "twist_about_point",
    "twist_translation",
    "twist_transpose",
    "velocity_at",
    "virtual_work",
    "wrench_from_force",
]
