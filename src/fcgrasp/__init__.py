"""fcgrasp: force-closure grasps of planar objects, after Nguyen's paper.

Modules mirror the paper: :mod:`~fcgrasp.screws` (section 2.1-2.2, 2.4),
:mod:`~fcgrasp.convexes` (2.3), :mod:`~fcgrasp.contacts` (3.1),
:mod:`~fcgrasp.grasp` (3.2), :mod:`~fcgrasp.closure` (4, 5, 6),
:mod:`~fcgrasp.polygon` (the part), :mod:`~fcgrasp.graspsets` (6),
:mod:`~fcgrasp.regions` and :mod:`~fcgrasp.planning` (7, 8), :mod:`~fcgrasp.quality`
(8.1), :mod:`~fcgrasp.hand` (8.2), :mod:`~fcgrasp.parts` (reading part files, with
:mod:`~fcgrasp.units` and :mod:`~fcgrasp.outline`).

Every name loads on first use (PEP 562): ``import fcgrasp`` costs almost nothing, and
the command line's ``--version`` answers at once.
"""

from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING, Any

from .tolerances import TOL

if TYPE_CHECKING:   # for type checkers; at run time these load on first use
    from .batch import plan_many
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
    from .convexes import (
        Cone,
    )
    from .frictionless_stretches import FrictionlessStretches, grow_stretches
    from .grasp import (
        ClosureReport,
        Grasp,
    )
    from .graspsets import (
        FrictionGraspSet,
        FrictionlessGraspSet,
        Vertex,
        grasp_set,
        grasp_sets,
        three_edge_grasp_sets,
    )
    from .hand import (
        Hand,
    )
    from .jaw import JawPlan, ParallelJaw, jaw_plans
    from .outline import (
        clean_outline,
        fill_rings,
        simplify_outline,
    )
    from .parts import (
        Part,
        list_parts,
        load_part,
        read_part,
    )
    from .planning import (
        GraspPlan,
        independent_regions,
        plan,
    )
    from .polygon import (
        Polygon,
    )
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
    from .stretches import StretchPair, two_finger_stretches

#: Where each public name lives; loaded on first use (PEP 562), so that ``import fcgrasp``
#: stays light and the command line starts fast.
_LAZY = {
    "closure_escape": "closure",
    "force_direction_closure": "closure",
    "friction_pair_closure": "closure",
    "friction_pair_modes": "closure",
    "is_force_closure": "closure",
    "torque_closure": "closure",
    "Contact": "contacts",
    "FrictionEdge": "contacts",
    "FrictionlessEdge": "contacts",
    "FrictionlessPoint": "contacts",
    "FrictionPoint": "contacts",
    "Gravity": "contacts",
    "SoftFinger": "contacts",
    "Cone": "convexes",
    "ClosureReport": "grasp",
    "Grasp": "grasp",
    "Hand": "hand",
    "ParallelJaw": "jaw",
    "plan_many": "batch",
    "JawPlan": "jaw",
    "jaw_plans": "jaw",
    "Polygon": "polygon",
    "CONTRARY": "screws",
    "RECIPROCAL": "screws",
    "REPELLING": "screws",
    "classify_twist_wrench": "screws",
    "rotation_center": "screws",
    "spatial_transpose": "screws",
    "spatial_twist_about_axis": "screws",
    "spatial_twist_translation": "screws",
    "spatial_virtual_work": "screws",
    "spatial_wrench_from_force": "screws",
    "twist_about_point": "screws",
    "twist_translation": "screws",
    "twist_transpose": "screws",
    "velocity_at": "screws",
    "virtual_work": "screws",
    "wrench_from_force": "screws",
    "FrictionGraspSet": "graspsets",
    "FrictionlessGraspSet": "graspsets",
    "Vertex": "graspsets",
    "grasp_set": "graspsets",
    "grasp_sets": "graspsets",
    "three_edge_grasp_sets": "graspsets",
    "read_part": "parts",
    "load_part": "parts",
    "list_parts": "parts",
    "Part": "parts",
    "GraspPlan": "planning",
    "independent_regions": "planning",
    "two_finger_stretches": "stretches",
    "StretchPair": "stretches",
    "grow_stretches": "frictionless_stretches",
    "FrictionlessStretches": "frictionless_stretches",
    "plan": "planning",
    "clean_outline": "outline",
    "simplify_outline": "outline",
    "fill_rings": "outline",
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
    "closure_escape",
    "force_direction_closure",
    "friction_pair_closure",
    "friction_pair_modes",
    "is_force_closure",
    "torque_closure",
    "Contact",
    "FrictionEdge",
    "FrictionlessEdge",
    "FrictionlessPoint",
    "FrictionPoint",
    "Gravity",
    "SoftFinger",
    "Cone",
    "ClosureReport",
    "Grasp",
    "Hand",
    "ParallelJaw",
    "plan_many",
    "JawPlan",
    "jaw_plans",
    "Polygon",
    "CONTRARY",
    "RECIPROCAL",
    "REPELLING",
    "classify_twist_wrench",
    "rotation_center",
    "spatial_transpose",
    "spatial_twist_about_axis",
    "spatial_twist_translation",
    "spatial_virtual_work",
    "spatial_wrench_from_force",
    "twist_about_point",
    "twist_translation",
    "twist_transpose",
    "velocity_at",
    "virtual_work",
    "wrench_from_force",
    "FrictionGraspSet",
    "FrictionlessGraspSet",
    "Vertex",
    "grasp_set",
    "grasp_sets",
    "three_edge_grasp_sets",
    "read_part",
    "load_part",
    "list_parts",
    "Part",
    "GraspPlan",
    "independent_regions",
    "two_finger_stretches",
    "StretchPair",
    "grow_stretches",
    "FrictionlessStretches",
    "plan",
    "clean_outline",
    "simplify_outline",
    "fill_rings",
]
