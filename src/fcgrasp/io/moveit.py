"""The plans of a report as MoveIt grasps of a parallel gripper: ``moveit_msgs/Grasp``
messages written as plain data (YAML or JSON), without ROS installed.

A jaw plan (a box of closing angles and offsets on a planar part, or a pair of opposite
parallel facets on a solid) becomes one grasp at its representative pose, the box's
centre, where every pose of the box holds.  A two-finger plan (point fingers with
friction on a planar part, or a solid's soft pair) becomes the grasp of a parallel
gripper with small fingertips closing along the line through its two representative
contacts: two fingers hold exactly when that line lies in both friction cones (theorem
6.3), so the gripper's squeeze is along a force the contacts can take; a plan that
expands (in a hole) is an internal grip.

* **Frames and units** (REP 103): metres; the frame ``frame_id`` is the part's own (the
  report's coordinates).  A planar part lies in its ``z = 0`` plane, picked from above
  (the paper's chopsticks), its tool frame at ``height`` above that plane.  The tool
  frame is the hand's (``ee_frame``, the Franka Hand's ``panda_hand`` by default): its
  ``y`` axis the closing axis (the fingers move along it), its ``z`` axis the approach
  direction, ``x = y x z``; the orientation is a unit quaternion ``(x, y, z, w)``.
* **The fingers' joints**: each of ``joint_names`` at ``joint_per_opening`` times the
  opening in metres (the Franka Hand: two prismatic joints at half the opening each).
  An external grip approaches open (the jaw's largest stroke; for a two-finger plan the
  opening plus twice ``clearance``) and closes to the contacts; an internal one (inside
  a hole) approaches closed (the smallest stroke, or the opening less twice
  ``clearance``) and opens to them.
* **Approach and retreat**: along the tool's ``z`` axis by ``approach`` metres (at least
  ``min_approach``), and away along the part frame's ``z`` (up) by ``retreat`` (at least
  ``min_retreat``).
* ``grasp_quality``: the plan's measure in metres (the box's smallest side, or a solid's
  pad radius); ``max_contact_force``: the grip force where the report certifies a
  payload, else 0 (no limit).

The field names are the messages' own (``moveit_msgs/Grasp``, ``GripperTranslation``,
``trajectory_msgs/JointTrajectory``, ``geometry_msgs/PoseStamped``, ROS 2's
``builtin_interfaces`` times), listed in :data:`GRASP_FIELDS` and checked by the tests
against the message definitions.

>>> report = {"units": "mm", "parameters": {"gripper": "parallel_jaw", "stroke": [10, 50]},
...           "grasps": [{"rank": 1, "gripper": "parallel_jaw", "mode": "external",
...                       "centre": [1.5707963267948966, 0.0], "centroid": [40.0, 15.0],
...                       "contacts": {"a": {"stop": 15.0}, "b": {"stop": -15.0}},
...                       "measure": 18.08}]}
>>> g = moveit_grasps(report)[0]
>>> g["grasp_pose"]["pose"]["position"]
{'x': 0.04, 'y': 0.015, 'z': 0.0}
>>> g["grasp_posture"]["points"][0]["positions"]
[0.015, 0.015]
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..errors import ArgumentError
from .units import MM_PER

__all__ = ["moveit_grasps", "parallel_gripper", "grasps_text", "GRASP_FIELDS", "tool_rotation",
           "quaternion", "jaw_tool_pose"]

#: The fields of each message as its definition names them (moveit_msgs, trajectory_msgs,
#: geometry_msgs and std_msgs of ROS 2).
GRASP_FIELDS = {
    "moveit_msgs/Grasp": ("id", "pre_grasp_posture", "grasp_posture", "grasp_pose",
                          "grasp_quality", "pre_grasp_approach", "post_grasp_retreat",
                          "post_place_retreat", "max_contact_force", "allowed_touch_objects"),
    "moveit_msgs/GripperTranslation": ("direction", "desired_distance", "min_distance"),
    "trajectory_msgs/JointTrajectory": ("header", "joint_names", "points"),
    "trajectory_msgs/JointTrajectoryPoint": ("positions", "velocities", "accelerations",
                                             "effort", "time_from_start"),
    "geometry_msgs/PoseStamped": ("header", "pose"),
    "geometry_msgs/Pose": ("position", "orientation"),
    "geometry_msgs/Vector3Stamped": ("header", "vector"),
    "std_msgs/Header": ("stamp", "frame_id"),
    "builtin_interfaces/Time": ("sec", "nanosec"),
}

#: The default hand: the Franka Hand's frame and finger joints (franka_description).
FRANKA_HAND = ("panda_hand", ("panda_finger_joint1", "panda_finger_joint2"), 0.5)


def tool_rotation(closing: Any, approach: Any) -> np.ndarray:
    """The tool frame's axes as columns (3, 3): ``y`` along ``closing``, ``z`` along
    ``approach`` made perpendicular to it, ``x = y x z`` (right-handed)."""
    y = np.asarray(closing, float)
    y = y / np.linalg.norm(y)
    z = np.asarray(approach, float)
    z = z - (z @ y) * y
    z = z / np.linalg.norm(z)
    return np.stack([np.cross(y, z), y, z], axis=1)


def rotation(q: Any) -> np.ndarray:
    """The rotation matrix of a quaternion ``(x, y, z, w)`` (made unit)."""
    x, y, z, w = np.asarray(q, float) / np.linalg.norm(np.asarray(q, float))
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def quaternion(R: Any) -> tuple[float, float, float, float]:
    """The unit quaternion ``(x, y, z, w)`` of a rotation matrix (``w >= 0``), by the
    largest of its four squared components (exact to rounding)."""
    R = np.asarray(R, float)
    t = np.trace(R)
    squares = [1 + t, 1 + 2 * R[0, 0] - t, 1 + 2 * R[1, 1] - t, 1 + 2 * R[2, 2] - t]
    k = int(np.argmax(squares))
    s = 2 * math.sqrt(squares[k])
    if k == 0:
        q = (R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1], s * s / 4)
    elif k == 1:
        q = (s * s / 4, R[0, 1] + R[1, 0], R[0, 2] + R[2, 0], R[2, 1] - R[1, 2])
    elif k == 2:
        q = (R[0, 1] + R[1, 0], s * s / 4, R[1, 2] + R[2, 1], R[0, 2] - R[2, 0])
    else:
        q = (R[0, 2] + R[2, 0], R[1, 2] + R[2, 1], s * s / 4, R[1, 0] - R[0, 1])
    v = np.asarray(q) / s
    v = v / np.linalg.norm(v)
    return tuple(float(c) for c in (-v if v[3] < 0 else v))  # type: ignore[return-value]


def _down(axis: np.ndarray) -> np.ndarray:
    """The approach to a solid closing along ``axis``: down, from the side where the
    axis is (nearly) vertical."""
    down = np.array([0.0, 0.0, -1.0])
    if np.linalg.norm(down - (down @ axis) * axis) < 0.1:
        down = np.array([-1.0, 0.0, 0.0])
    return down


def _pose(grasp: dict[str, Any], height: float) -> tuple[np.ndarray, np.ndarray, float, str]:
    """The tool's position and axes (report units), the opening and the grip's mode of
    one plan."""
    if isinstance(grasp.get("contacts"), list) or ("centers" in grasp and "axis" not in grasp):
        # two fingers: the line through the two contacts is the closing axis
        pts = np.asarray(grasp["contacts"] if "contacts" in grasp else grasp["centers"],
                         float)
        if pts.shape[0] != 2:
            raise ArgumentError(f"a parallel gripper takes two-finger plans: plan "
                                f"{grasp.get('rank')} has {pts.shape[0]} contacts", "report")
        if pts.shape[1] == 2:                   # a planar part, picked from above
            pts = np.c_[pts, np.full(2, height)]
        chord = pts[0] - pts[1]
        opening = float(np.linalg.norm(chord))
        approach = _down(chord / opening) if "centers" in grasp else \
            np.array([0.0, 0.0, -1.0])
        mode = "internal" if grasp.get("mode") == "expand" else "external"
        return pts.mean(axis=0), tool_rotation(chord, approach), opening, mode
    if "axis" in grasp:                          # a solid: pads on two parallel facets
        axis = np.asarray(grasp["axis"], float)
        centers = np.asarray(grasp["centers"], float)
        return centers.mean(axis=0), tool_rotation(axis, _down(axis)), \
            float(grasp["opening"]), "external"
    theta, offset = (float(v) for v in grasp["centre"])
    stops = float(grasp["contacts"]["a"]["stop"]), float(grasp["contacts"]["b"]["stop"])
    where, axes = jaw_tool_pose(grasp["centroid"], theta, offset, stops, height)
    return where, axes, abs(stops[0] - stops[1]), str(grasp.get("mode", "external"))


def jaw_tool_pose(centroid: Any, theta: float, offset: float, stops: tuple[float, float],
                  height: float, side: int = 0, pad_centre: float = 0.0
                  ) -> tuple[np.ndarray, np.ndarray]:
    """The tool frame of a planar part's jaw pose (part frame, its units): the origin
    between the pads' faces (stops ``stops`` along the closing direction ``theta`` =
    ``u``, ``offset`` across it along ``n`` from ``centroid``) at ``height``, and the axes
    as columns, ``y`` along ``u``.  Picked from above (``side`` 0) ``z`` points down;
    held in the plate's plane with the hand on the ``side`` of the strip (+1: ``+n``),
    ``z`` is ``-side n`` and the origin stands back along it so that the pad's centre
    (at tool ``z`` = ``pad_centre``) lies on the strip's centre line."""
    u = np.array([math.cos(theta), math.sin(theta)])
    n = np.array([-u[1], u[0]])
    across = offset + side * pad_centre
    xy = np.asarray(centroid, float) + (stops[0] + stops[1]) / 2 * u + across * n
    approach = [0.0, 0.0, -1.0] if side == 0 else np.r_[-side * n, 0.0]
    return np.r_[xy, height], tool_rotation(np.r_[u, 0.0], approach)


def _ee_pose(pose: dict[str, Any], hand: dict[str, Any]) -> tuple[np.ndarray, np.ndarray]:
    """The end effector's position (report units) and axes of a hand's pick: the tool
    frame's pose (``pose``) composed with where the hand's ``ee_frame`` lies in the tool
    frame (``ee_offset``, ``ee_axes``: its axes in tool coordinates, as rows)."""
    from scipy.spatial.transform import Rotation

    R_tool = Rotation.from_quat(np.asarray(pose["orientation"], float)).as_matrix()
    axes = np.asarray(hand.get("ee_axes", np.eye(3)), float).T
    where = np.asarray(pose["position"], float) + R_tool @ np.asarray(
        hand.get("ee_offset", (0.0, 0.0, 0.0)), float)
    return where, R_tool @ axes


def _header(frame_id: str) -> dict[str, Any]:
    return {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": frame_id}


def _posture(frame_id: str, joints: tuple[str, ...], position: float, effort: float | None
             ) -> dict[str, Any]:
    point = {"positions": [position] * len(joints), "velocities": [], "accelerations": [],
             "effort": [] if effort is None else [effort] * len(joints),
             "time_from_start": {"sec": 1, "nanosec": 0}}
    return {"header": _header(frame_id), "joint_names": list(joints), "points": [point]}


def _translation(frame_id: str, direction: Any, desired: float, least: float
                 ) -> dict[str, Any]:
    x, y, z = (float(v) for v in direction)
    return {"direction": {"header": _header(frame_id), "vector": {"x": x, "y": y, "z": z}},
            "desired_distance": desired, "min_distance": least}


def _distance(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or not math.isfinite(value) or value < 0:
        raise ArgumentError(f"{name} must be a distance in metres >= 0, got {value!r}", name)
    return float(value)


def parallel_gripper(report: dict[str, Any]) -> bool:
    """Whether a report's plans are a parallel gripper's: a jaw's, or two fingers'."""
    params = report.get("parameters", {})
    return params.get("gripper") in ("parallel_jaw", "jaw") or params.get("fingers") == 2


def moveit_grasps(report: dict[str, Any], *, frame_id: str = "part",
                  ee_frame: str = FRANKA_HAND[0], joint_names: Any = FRANKA_HAND[1],
                  joint_per_opening: float = FRANKA_HAND[2], height: float = 0.0,
                  approach: float = 0.1, min_approach: float = 0.05,
                  retreat: float = 0.1, min_retreat: float = 0.05,
                  clearance: float = 0.01) -> list[dict[str, Any]]:
    """One ``moveit_msgs/Grasp`` (as a dict) per plan of ``report`` (a ``fcgrasp plan
    --json`` report of a parallel jaw or of two fingers, planar or on a solid), best
    first (the module's docstring: frames, units and postures).  Distances in metres;
    ``height``: the tool frame above a planar part's plane; ``clearance``: how much
    wider (narrower, inside a hole) than its opening a two-finger grasp approaches."""
    if not isinstance(report, dict) or not isinstance(report.get("grasps"), list):
        raise ArgumentError("report must be a plan report (fcgrasp plan --json), got "
                            f"{type(report).__name__}", "report")
    params = report.get("parameters", {})
    if not parallel_gripper(report):
        raise ArgumentError(f"MoveIt grasps are a parallel gripper's: plans of a jaw or of "
                            f"two fingers, got {params.get('fingers')} fingers", "report")
    units = str(report.get("units", "mm"))
    if units not in MM_PER:
        raise ArgumentError(f"the report's units must be one of {sorted(MM_PER)}, got "
                            f"{units!r}", "units")
    metres = MM_PER[units] / 1000.0
    joints = tuple(str(j) for j in joint_names)
    if not joints:
        raise ArgumentError("joint_names must name at least one finger joint", "joint_names")
    d = {k: _distance(k, v) for k, v in (("height", height), ("approach", approach),
                                          ("min_approach", min_approach),
                                          ("retreat", retreat), ("min_retreat", min_retreat),
                                          ("clearance", clearance))}
    stroke = [float(v) * metres for v in params.get("stroke", (0.0, 0.0))]
    hand = report.get("hand")
    if isinstance(hand, dict) and hand.get("kind") == "fingertips":
        hand = None                 # point fingers on bodies: two fingers as a jaw
    if isinstance(hand, dict):
        # a hand's pick (fcgrasp.grippers.jaw._pick): its own frame, joints and poses
        ee_frame = str(hand.get("ee_frame") or ee_frame)
        joints = tuple(j["name"] for j in hand.get("joints", ())) or joints
    out = []
    for k, grasp in enumerate(report["grasps"]):
        where, axes, opening, mode = _pose(grasp, d["height"] / metres)
        if isinstance(hand, dict) and isinstance(grasp.get("pose"), dict):
            where, axes = _ee_pose(grasp["pose"], hand)
        qx, qy, qz, qw = quaternion(axes)
        p = where * metres
        payload = grasp.get("payload") or {}
        force = payload.get("grip_force_n") if isinstance(payload, dict) else None
        if "stroke" in params:
            start = stroke[1] if mode == "external" else stroke[0]
        else:
            wide = opening * metres + (2 if mode == "external" else -2) * d["clearance"]
            start = max(wide, 0.0)
        if isinstance(hand, dict):
            start = float(grasp.get("pre_grasp_opening", hand["stroke"][1]))
            j = hand["joints"][0] if hand.get("joints") else {}
            per, at0 = float(j.get("per_opening", 0.0)), float(j.get("at_zero_opening", 0.0))
            open_q, grip_q = at0 + per * start, at0 + per * opening
        else:
            open_q = joint_per_opening * start
            grip_q = joint_per_opening * opening * metres
        out.append({
            "id": f"fcgrasp-{grasp.get('rank', k + 1)}",
            "pre_grasp_posture": _posture(ee_frame, joints, open_q, None),
            "grasp_posture": _posture(ee_frame, joints, grip_q,
                                      None if force is None else float(force)),
            "grasp_pose": {"header": _header(frame_id), "pose": {
                "position": {"x": float(p[0]), "y": float(p[1]), "z": float(p[2])},
                "orientation": {"x": qx, "y": qy, "z": qz, "w": qw}}},
            "grasp_quality": float(grasp.get("measure", grasp.get(
                "radius", grasp.get("min_region_length", 0.0)))) * metres,
            "pre_grasp_approach": _translation(ee_frame, (0, 0, 1), d["approach"],
                                               d["min_approach"]),
            "post_grasp_retreat": _translation(frame_id, (0, 0, 1), d["retreat"],
                                               d["min_retreat"]),
            "post_place_retreat": _translation(ee_frame, (0, 0, -1), d["retreat"],
                                               d["min_retreat"]),
            "max_contact_force": 0.0 if force is None else float(force),
            "allowed_touch_objects": [],
        })
    return out


def grasps_text(grasps: list[dict[str, Any]], path: str) -> str:
    """The grasps as the file ``path`` asks: YAML (``.yaml``, ``.yml``; PyYAML) or JSON."""
    import json

    if path.lower().endswith((".yaml", ".yml")):
        try:
            import yaml
        except ImportError:
            # JSON is YAML: the same messages, in flow style
            return json.dumps(grasps, indent=1) + "\n"
        return str(yaml.safe_dump(grasps, sort_keys=False))
    return json.dumps(grasps, indent=1) + "\n"
