"""The options a plan request takes, grouped as the command line groups them, and the
checks of their kinds and values, each error naming its field (part of
:mod:`fcgrasp.planning.request`)."""

from __future__ import annotations

import math
from typing import Any

from ..errors import ArgumentTypeError, RequestError

#: The options of a request that say how to read its part (:func:`fcgrasp.io.parts.load_part`).
READING_OPTIONS = ("select", "units", "file_units", "flatten", "layer", "gap", "pixel_size",
                   "threshold", "y_down", "simplify", "no_clean", "max_bytes",
                   "max_elements", "max_vertices", "repair")


#: The options of a request that say how to plan (the gripper's and the search's).
PLAN_OPTIONS = ("gripper", "stroke", "pad", "certify", "fingers", "mu", "gravity", "top",
                "single_edge", "rank_by", "margin", "workspace", "finger_radius",
                "max_memory", "distinct", "hand", "thickness", "table", "rest",
                "rest_orientation", "in_plane")


#: The options of a request that bound the search: ``time_limit`` in seconds (None: the
#: default, :data:`fcgrasp.core.budget.DEFAULT_TIME_LIMIT`; 0: no limit).
SEARCH_OPTIONS = ("time_limit",)


#: The options of a request that give a load to carry (:class:`fcgrasp.Load`: each plan
#: then reports the scale of it its regions carry, :func:`fcgrasp.region_payload`) and a
#: placement error (each plan's probability of holding,
#: :func:`fcgrasp.placement_probability`), a pose error (:func:`fcgrasp.pose_probability`),
#: finger springs (each plan's stability, :func:`fcgrasp.plan_stability`), the top
#: of a friction range (``mu_high``: ``--mu LOW:HIGH``) and an upper bound on the best
#: smallest region (``bound``: :func:`fcgrasp.optimum_upper_bound`).
LOAD_OPTIONS = ("mass", "com", "accel", "accel_shape", "force_limit", "total_force",
                "placement_sigma", "pose_sigma", "stiffness", "grip_force", "mu_high", "bound")


def _fail(field_name: str, message: str) -> RequestError:
    return RequestError(message, field_name)


def _number(name: str, value: Any, *, integer: bool = False) -> None:
    kinds = (int,) if integer else (int, float)
    if isinstance(value, bool) or not isinstance(value, kinds):
        what = "a whole number" if integer else "a number"
        raise ArgumentTypeError(f"{name} must be {what}, got {value!r}", name)
    if not integer and not math.isfinite(value):
        raise _fail(name, f"--{name.replace('_', '-')} must be a finite number, got {value!r}")


def _numbers(name: str, value: Any, n: int) -> tuple[float, ...]:
    if isinstance(value, (str, bytes)) or not isinstance(value, (list, tuple)) \
            or len(value) != n:
        raise ArgumentTypeError(f"{name} must be a sequence of {n} numbers, got {value!r}", name)
    for v in value:
        _number(name, v)
    return tuple(float(v) for v in value)


#: Each option's kind: "int", "float", "bool", "str", or ("floats", n).
_KINDS: dict[str, Any] = {
    "fingers": "int", "top": "int", "max_memory": "int", "mu": "float", "pad": "float",
    "margin": "float", "finger_radius": "float", "flatten": "float", "gap": "float",
    "distinct": "float", "placement_sigma": "float", "mass": "float", "mu_high": "float",
    "force_limit": "float", "total_force": "float", "stiffness": "float",
    "grip_force": "float", "time_limit": "float", "thickness": "float", "table": "bool",
    "hand": "str", "rest": "int", "max_bytes": "int",
    "max_elements": "int", "max_vertices": "int",
    "com": ("floats", 2), "accel": ("floats", 2), "pose_sigma": ("floats", 3),
    "rest_orientation": ("floats", 4), "in_plane": "bool",
    "pixel_size": "float", "threshold": "float", "simplify": "float",
    "certify": "bool", "single_edge": "bool", "bound": "bool", "soft": "bool",
    "repair": "bool",
    "y_down": "bool", "no_clean": "bool",
    "gravity": ("floats", 2), "stroke": ("floats", 2), "workspace": ("floats", 3),
    "part": "str", "gripper": "str", "rank_by": "str", "select": "str", "units": "str",
    "file_units": "str", "layer": "str", "json": "str", "plot": "str", "accel_shape": "str"}


def _check_kind(name: str, value: Any) -> Any:
    """``value`` as option ``name`` takes it (tuples of floats for pairs), or TypeError."""
    kind = _KINDS[name]
    if value is None:
        return None
    if isinstance(kind, tuple):
        return _numbers(name, value, kind[1])
    if kind in ("int", "float"):
        _number(name, value, integer=kind == "int")
        return int(value) if kind == "int" else float(value)
    if kind == "bool" and not isinstance(value, bool):
        raise ArgumentTypeError(f"{name} must be true or false, got {value!r}", name)
    if kind == "str" and not isinstance(value, str):
        raise ArgumentTypeError(f"{name} must be a string, got {value!r}", name)
    return value
