"""Spatial contact mechanics (the paper's conclusion: grasps of solids), mirrored by
:mod:`fcgrasp.mechanics.planar`: contacts, closure and quality of one grasp of a
solid part, with outward normals (:mod:`fcgrasp.mechanics`)."""

from . import closure, contacts, quality
from .closure import force_closure, unresisted_wrench
from .contacts import DIM, WRENCH_DIM, contact_wrenches
from .quality import epsilon, volume

__all__ = ["closure", "contacts", "quality", "DIM", "WRENCH_DIM", "contact_wrenches",
           "force_closure", "unresisted_wrench", "epsilon", "volume"]
