"""Grippers: one object per gripper behind one interface, and their registry.

- :mod:`~fcgrasp.grippers.base`: the :class:`~fcgrasp.grippers.base.Gripper` protocol
  (parameters and their checks, the search, the plans' JSON), :class:`SearchOptions` and
  the registry that plan requests build grippers from;
- :mod:`~fcgrasp.grippers.fingers`: point fingers, two or three with friction, three
  frictionless with gravity, four frictionless (sections 6-8);
- :mod:`~fcgrasp.grippers.three_fingers`: the search of three fingers with friction;
- :mod:`~fcgrasp.grippers.jaw`: a parallel jaw and its proved boxes of poses.

Adding a gripper is one module implementing the protocol and one
:func:`~fcgrasp.grippers.base.register` line; importing this package registers the
built-in ones.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from . import fingers
from .base import REGISTRY, Gripper, SearchOptions, register
from .fingers import FourFingers, ThreeFingers, ThreeFrictionless, TwoFingers, point_fingers

if TYPE_CHECKING:
    from . import jaw
    from .jaw import ParallelJaw


def __getattr__(name: str) -> Any:
    """The jaw on first use: a plan of point fingers does not pay its import."""
    if name in ("jaw", "ParallelJaw"):
        import importlib  # not "from . import jaw": that asks this function again

        jaw = importlib.import_module(f"{__name__}.jaw")
        return jaw if name == "jaw" else jaw.ParallelJaw
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

__all__ = ["Gripper", "SearchOptions", "REGISTRY", "register", "TwoFingers", "ThreeFingers",
           "ThreeFrictionless", "FourFingers", "ParallelJaw", "point_fingers", "fingers",
           "jaw"]
