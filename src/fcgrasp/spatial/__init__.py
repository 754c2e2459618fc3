"""Solid parts: contacts, force closure and grasp quality in six dimensions.

- :mod:`~fcgrasp.spatial.contacts`: frictionless points, points with friction and soft
  fingers on a solid, their wrench maps and linearised cones;
- :mod:`~fcgrasp.spatial.closure`: force closure of a grasp (exact quadratic cones, one
  second-order cone program), two soft fingers batched in closed form;
- :mod:`~fcgrasp.spatial.quality`: Ferrari-Canny L1 and L-infinity epsilon and the
  volume of the grasp wrench space;
- :mod:`~fcgrasp.spatial.solid`: meshes read with trimesh, checked and cut into planar
  facets, and the built-in solids;
- :mod:`~fcgrasp.spatial.regions`: independent regions of two soft fingers on a pair of
  facets (one cone program each) and the search over every pair;
- :mod:`~fcgrasp.spatial.surfaces`: certified regions of two soft fingers and of three
  fingers with friction across the facets of curved surfaces, each ranked with its
  facet search (``soft_pair_plans``, ``three_finger_plans``);
- :mod:`~fcgrasp.spatial.triples`: certified regions of three point fingers with
  friction on three facets, and the search over triples;
- :mod:`~fcgrasp.spatial.jaw`: a parallel jaw's region of closing axes on two opposite
  parallel facets, and the search over such pairs;
- :mod:`~fcgrasp.spatial.alternatives`: distinct alternatives among a solid's plans.
"""

from __future__ import annotations

from typing import TYPE_CHECKING as _TYPE_CHECKING

from ..core._lazy import lazy_names as _lazy_names

#: Each public name and the submodule that defines it: imported on first use, so that a
#: module needing one of them (the mesh reader needs :mod:`.solid`) does not import the
#: cone programs of every gripper (a plane part's plan never does).
_LAZY = {
    **dict.fromkeys(("SpatialClosure", "closure_margin", "spatial_force_closure",
                     "two_soft_closure"), "closure"),
    **dict.fromkeys(("SpatialContact", "contact_frames", "contact_maps",
                     "contact_wrench_generators"), "contacts"),
    **dict.fromkeys(("SolidJawPlan", "solid_jaw_plans", "solid_jaw_region"), "jaw"),
    **dict.fromkeys(("SpatialQuality", "spatial_quality"), "quality"),
    **dict.fromkeys(("SoftPairPlan", "facet_pair_plans", "soft_pair_regions"), "regions"),
    **dict.fromkeys(("SurfacePairPlan", "soft_pair_plans", "surface_pair_plans",
                     "SurfaceTriplePlan", "surface_triple_plans", "three_finger_plans"),
                    "surfaces"),
    **dict.fromkeys(("Facet", "Solid", "demo_solid", "solid_from_mesh"), "solid"),
    **dict.fromkeys(("PointTriplePlan", "PointTripleSearch", "perturbation_radius",
                     "point_triple_plans", "point_triple_regions"), "triples"),
}

if _TYPE_CHECKING:
    from .closure import SpatialClosure, closure_margin, spatial_force_closure, two_soft_closure
    from .contacts import (
        SpatialContact,
        contact_frames,
        contact_maps,
        contact_wrench_generators,
    )
    from .jaw import SolidJawPlan, solid_jaw_plans, solid_jaw_region
    from .quality import SpatialQuality, spatial_quality
    from .regions import SoftPairPlan, facet_pair_plans, soft_pair_regions
    from .solid import Facet, Solid, demo_solid, solid_from_mesh
    from .surfaces import (
        SurfacePairPlan,
        SurfaceTriplePlan,
        soft_pair_plans,
        surface_pair_plans,
        surface_triple_plans,
        three_finger_plans,
    )
    from .triples import (
        PointTriplePlan,
        PointTripleSearch,
        perturbation_radius,
        point_triple_plans,
        point_triple_regions,
    )

__all__ = ["SpatialContact", "contact_frames", "contact_maps", "contact_wrench_generators",
           "SpatialClosure", "closure_margin", "spatial_force_closure", "two_soft_closure",
           "SpatialQuality", "spatial_quality", "SoftPairPlan", "soft_pair_plans",
           "soft_pair_regions", "facet_pair_plans", "SurfacePairPlan", "surface_pair_plans",
           "SurfaceTriplePlan", "surface_triple_plans", "three_finger_plans",
           "Facet", "Solid", "demo_solid", "solid_from_mesh",
           "PointTriplePlan", "PointTripleSearch", "perturbation_radius",
           "point_triple_plans", "point_triple_regions", "SolidJawPlan",
           "solid_jaw_plans", "solid_jaw_region"]


__getattr__ = _lazy_names(__name__, _LAZY, globals())


def __dir__() -> list[str]:
    return sorted(__all__)
