"""fcgrasp: force-closure grasps of planar objects, after Nguyen's paper.

Subpackages show the architecture (imports only go down this list):

- :mod:`fcgrasp.core`: screws (sections 2.1-2.2, 2.4), convexes (2.3), contacts (3.1),
  grasps (3.2) and closure tests (4, 5, 6): mechanics, no notion of a part or a gripper;
- :mod:`fcgrasp.model`: the part (polygon, outline clean-up) and the paper's constructions
  on it: grasp sets (6), regions (7), stretches along the boundary, quality (8.1), hand (8.2);
- :mod:`fcgrasp.io`: every part reader, units, JSON reports, atomic outputs;
- :mod:`fcgrasp.pipeline`: the point fingers' search, candidates -> solve -> rank;
- :mod:`fcgrasp.grippers`: one object per gripper behind one interface, and the registry;
- :mod:`fcgrasp.planning`: :class:`~fcgrasp.planning.PlanRequest` and :func:`plan`;
- :mod:`fcgrasp.physics`: the stress test of plans in MuJoCo (an optional extra);
- :mod:`fcgrasp.plotting`: figures (matplotlib, imported inside its functions);
- :mod:`fcgrasp.apps`: the command line, the batch runner and the explorer.

Every name loads on first use (PEP 562): ``import fcgrasp`` costs almost nothing, and
the command line's ``--version`` answers at once.
"""

from __future__ import annotations

from typing import TYPE_CHECKING as _TYPE_CHECKING

from .core._lazy import lazy_names as _lazy_names
from .core.tolerances import TOL

if _TYPE_CHECKING:   # for type checkers; at run time these load on first use
    from .apps.batch import plan_many
    from .core.closure import (
        closure_escape,
        force_direction_closure,
        friction_pair_closure,
        friction_pair_modes,
        is_force_closure,
        torque_closure,
    )
    from .core.contacts import (
        Contact,
        FrictionEdge,
        FrictionlessEdge,
        FrictionlessPoint,
        FrictionPoint,
        Gravity,
        SoftFinger,
    )
    from .core.convexes import (
        Cone,
    )
    from .core.grasp import (
        ClosureReport,
        Grasp,
    )
    from .core.screws import (
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
    from .core.values import Friction, Margin
    from .grippers.jaw import JawPlan, ParallelJaw, Scene, jaw_pareto, jaw_payload, jaw_plans
    from .io.meshes import read_solid
    from .io.parts import (
        Part,
        list_parts,
        load_part,
        read_part,
    )
    from .model.bounds import UpperBound, optimum_upper_bound
    from .model.frictionless_stretches import FrictionlessStretches, grow_stretches
    from .model.graspsets import (
        FrictionGraspSet,
        FrictionlessGraspSet,
        Vertex,
        grasp_set,
        grasp_sets,
        three_edge_grasp_sets,
    )
    from .model.hand import (
        Hand,
    )
    from .model.hands import ParallelHand, hand_named
    from .model.loads import Load, Payload, RegionPayload, grasp_payload, region_payload
    from .model.outline import (
        clean_outline,
        fill_rings,
        simplify_outline,
    )
    from .model.plans import Plan
    from .model.polygon import (
        Polygon,
    )
    from .model.robustness import (
        Estimate,
        placement_probability,
        pose_probability,
        robustness,
    )
    from .model.stability import (
        PlanStability,
        Stability,
        grasp_stability,
        grasp_stiffness,
        least_stiffness,
        plan_stability,
        squeeze_preload,
    )
    from .model.stretches import StretchPair, two_finger_stretches
    from .physics import simulate
    from .planning import (
        FrictionCurve,
        GraspPlan,
        friction_curve,
        independent_regions,
        plan,
    )
    from .planning.compiled import compile_kernels
    from .spatial import (
        PointTriplePlan,
        SoftPairPlan,
        Solid,
        SpatialClosure,
        SpatialContact,
        SpatialQuality,
        perturbation_radius,
        point_triple_plans,
        soft_pair_plans,
        soft_pair_regions,
        solid_jaw_plans,
        spatial_force_closure,
        spatial_quality,
        two_soft_closure,
    )

#: Where each public name lives; loaded on first use (PEP 562), so that ``import fcgrasp``
#: stays light and the command line starts fast.
_LAZY = {
    "closure_escape": "core.closure",
    "force_direction_closure": "core.closure",
    "friction_pair_closure": "core.closure",
    "friction_pair_modes": "core.closure",
    "is_force_closure": "core.closure",
    "torque_closure": "core.closure",
    "Contact": "core.contacts",
    "FrictionEdge": "core.contacts",
    "FrictionlessEdge": "core.contacts",
    "FrictionlessPoint": "core.contacts",
    "FrictionPoint": "core.contacts",
    "Gravity": "core.contacts",
    "SoftFinger": "core.contacts",
    "Cone": "core.convexes",
    "Friction": "core.values",
    "Margin": "core.values",
    "ClosureReport": "core.grasp",
    "Grasp": "core.grasp",
    "Hand": "model.hand",
    "ParallelJaw": "grippers.jaw",
    "plan_many": "apps.batch",
    "simulate": "physics",
    "JawPlan": "grippers.jaw",
    "Scene": "grippers.jaw",
    "ParallelHand": "model.hands",
    "hand_named": "model.hands",
    "jaw_plans": "grippers.jaw",
    "jaw_payload": "grippers.jaw",
    "jaw_pareto": "grippers.jaw",
    "Polygon": "model.polygon",
    "Plan": "model.plans",
    "CONTRARY": "core.screws",
    "RECIPROCAL": "core.screws",
    "REPELLING": "core.screws",
    "classify_twist_wrench": "core.screws",
    "rotation_center": "core.screws",
    "spatial_transpose": "core.screws",
    "spatial_twist_about_axis": "core.screws",
    "spatial_twist_translation": "core.screws",
    "spatial_virtual_work": "core.screws",
    "spatial_wrench_from_force": "core.screws",
    "twist_about_point": "core.screws",
    "twist_translation": "core.screws",
    "twist_transpose": "core.screws",
    "velocity_at": "core.screws",
    "virtual_work": "core.screws",
    "wrench_from_force": "core.screws",
    "FrictionGraspSet": "model.graspsets",
    "FrictionlessGraspSet": "model.graspsets",
    "Vertex": "model.graspsets",
    "grasp_set": "model.graspsets",
    "grasp_sets": "model.graspsets",
    "three_edge_grasp_sets": "model.graspsets",
    "read_part": "io.parts",
    "load_part": "io.parts",
    "list_parts": "io.parts",
    "Part": "io.parts",
    "GraspPlan": "planning",
    "independent_regions": "planning",
    "two_finger_stretches": "model.stretches",
    "StretchPair": "model.stretches",
    "grow_stretches": "model.frictionless_stretches",
    "FrictionlessStretches": "model.frictionless_stretches",
    "plan": "planning",
    "friction_curve": "planning",
    "FrictionCurve": "planning",
    "compile_kernels": "planning.compiled",
    "clean_outline": "model.outline",
    "simplify_outline": "model.outline",
    "fill_rings": "model.outline",
    "optimum_upper_bound": "model.bounds",
    "UpperBound": "model.bounds",
    "Load": "model.loads",
    "Payload": "model.loads",
    "RegionPayload": "model.loads",
    "grasp_payload": "model.loads",
    "region_payload": "model.loads",
    "placement_probability": "model.robustness",
    "pose_probability": "model.robustness",
    "robustness": "model.robustness",
    "Estimate": "model.robustness",
    "Stability": "model.stability",
    "grasp_stability": "model.stability",
    "grasp_stiffness": "model.stability",
    "least_stiffness": "model.stability",
    "plan_stability": "model.stability",
    "squeeze_preload": "model.stability",
    "PlanStability": "model.stability",
    "SpatialContact": "spatial",
    "SpatialClosure": "spatial",
    "SpatialQuality": "spatial",
    "spatial_force_closure": "spatial",
    "spatial_quality": "spatial",
    "two_soft_closure": "spatial",
    "Solid": "spatial",
    "read_solid": "io.meshes",
    "SoftPairPlan": "spatial",
    "soft_pair_plans": "spatial",
    "soft_pair_regions": "spatial",
    "PointTriplePlan": "spatial",
    "point_triple_plans": "spatial",
    "perturbation_radius": "spatial",
    "solid_jaw_plans": "spatial",
}


__getattr__ = _lazy_names(__name__, _LAZY, globals())


def __dir__() -> list[str]:
    return sorted(__all__)


#: The package version (kept equal to pyproject.toml's by tests/test_imports.py; a literal,
#: because importlib.metadata alone costs more than the rest of ``import fcgrasp``).
__version__ = "0.1.0"

__all__ = ["TOL", "__version__", *_LAZY]
