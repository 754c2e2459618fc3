"""Solid parts (issue 33): contacts, force closure and grasp quality in six dimensions.

- :mod:`~fcgrasp.spatial.contacts`: frictionless points, points with friction and soft
  fingers on a solid, their wrench maps and linearised cones;
- :mod:`~fcgrasp.spatial.closure`: force closure of a grasp (exact quadratic cones, one
  second-order cone program), two soft fingers batched in closed form;
- :mod:`~fcgrasp.spatial.quality`: Ferrari-Canny L1 and L-infinity epsilon and the
  volume of the grasp wrench space.
"""

from __future__ import annotations

from .closure import SpatialClosure, closure_margin, spatial_force_closure, two_soft_closure
from .contacts import SpatialContact, contact_frames, contact_maps, contact_wrench_generators
from .quality import SpatialQuality, spatial_quality

__all__ = ["SpatialContact", "contact_frames", "contact_maps", "contact_wrench_generators",
           "SpatialClosure", "closure_margin", "spatial_force_closure", "two_soft_closure",
           "SpatialQuality", "spatial_quality"]
