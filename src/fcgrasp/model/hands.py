"""The geometry of a parallel gripper's hand: its fingers and palm as boxes in the tool
frame, the workspace-and-shape extension of section 8.2 for a real hand.

**The tool frame** (the frame MoveIt plans for, REP 103 axes): the origin at the centre
between the two pads' faces, ``y`` the closing axis (finger 1 on ``+y``, finger 2 on
``-y``, each moving by half the opening), ``z`` the approach direction (from the palm
towards the fingertips), ``x = y x z`` along the pads' width.  Lengths in millimetres
(:meth:`ParallelHand.scaled` gives other units).

A hand is a list of boxes: the palm's, fixed, and finger 1's at opening 0 (its inner
face on ``y = 0``), which move by ``+opening / 2``; finger 2 is finger 1 turned half a
turn about ``z`` (as the descriptions mount it).  The *pad* is the finger's box that
touches the part: its width along ``x`` is the jaw's ``pad_width``.

Built-in hands (:data:`HANDS`) are read from their makers' published descriptions, with
their sources and licences.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields, replace
from typing import Any

import numpy as np

from ..core._checks import FloatArray, check_scalar
from ..core.tolerances import STRIP_TOL

__all__ = ["HandBox", "ParallelHand", "HANDS", "hand_named", "hand_from_params",
           "hand_description", "hand_from_description", "FingerTips", "tips_from_params",
           "params_of"]


#: Metres per millimetre (a finger joint's unit per the hand's).
M_PER_MM = 1e-3


def _rot_x(angle: float) -> FloatArray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


@dataclass(frozen=True)
class HandBox:
    """A box of the hand: its name, centre and size (mm) and its rotation (3 x 3) in the
    tool frame."""

    name: str
    centre: tuple[float, float, float]
    size: tuple[float, float, float]
    rotation: tuple[tuple[float, ...], ...] = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0),
                                               (0.0, 0.0, 1.0))

    def corners(self, shrink: float = 0.0) -> FloatArray:
        """The eight corners (8, 3) in the tool frame (of the box pulled in by ``shrink``
        on every side)."""
        half = np.maximum(np.asarray(self.size, float) / 2 - shrink, 0.0)
        signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)],
                         float)
        out: FloatArray = np.asarray(self.centre, float) + \
            (signs * half) @ np.asarray(self.rotation, float).T
        return out

    def moved(self, dy: float, turned: bool = False) -> HandBox:
        """The box moved by ``dy`` along ``y`` (after a half turn about ``z`` if asked)."""
        x, y, z = self.centre
        R = np.asarray(self.rotation, float)
        if turned:
            R, x, y = np.diag([-1.0, -1.0, 1.0]) @ R, -x, -y
        return replace(self, centre=(x, y + dy, z),
                       rotation=tuple(tuple(float(v) for v in row) for row in R))

    def scaled(self, factor: float) -> HandBox:
        return replace(self, centre=tuple(factor * v for v in self.centre),  # type: ignore[arg-type]
                       size=tuple(factor * v for v in self.size))  # type: ignore[arg-type]

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "centre": list(self.centre), "size": list(self.size),
                "rotation": [list(r) for r in self.rotation]}


@dataclass(frozen=True)
class ParallelHand:
    """A parallel gripper's hand (the module's docstring: frame and boxes).

    ``stroke``: the least and largest opening between the pads' faces; ``pad``: the name
    of finger 1's box that touches the part; ``joints``: the finger joints' names, and
    each joint's position per unit of opening (in the joint's own unit per millimetre:
    the Franka Hand's two prismatic joints move by half the opening in metres, 0.0005);
    ``source`` and ``licence`` of the description the geometry was read from."""

    name: str
    stroke: tuple[float, float]
    palm: tuple[HandBox, ...]
    finger: tuple[HandBox, ...]
    pad: str
    joints: tuple[str, ...] = ()
    joint_per_opening: float = 0.5 * M_PER_MM
    #: the joints' position at opening 0 (``joint = joint_offset + joint_per_opening *
    #: opening``)
    joint_offset: float = 0.0
    source: str = ""
    licence: str = ""
    units: str = "mm"
    #: the description's link MoveIt plans the grasp pose for (the end effector), and
    #: where its origin lies in the tool frame and its axes (rows: its x, y, z in tool
    #: coordinates)
    ee_frame: str = ""
    ee_offset: tuple[float, float, float] = (0.0, 0.0, 0.0)
    ee_axes: tuple[tuple[float, ...], ...] = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0),
                                              (0.0, 0.0, 1.0))
    notes: str = field(default="", compare=False)

    def __post_init__(self) -> None:
        lo = check_scalar(self.stroke[0], "stroke[0]", nonnegative=True)
        hi = check_scalar(self.stroke[1], "stroke[1]", positive=True)
        if hi < lo:
            raise ValueError(f"stroke must have min_opening <= max_opening, got {self.stroke!r}")
        if self.pad not in {b.name for b in self.finger}:
            raise ValueError(f"pad must name one of the finger's boxes "
                             f"({', '.join(b.name for b in self.finger)}), got {self.pad!r}")
        object.__setattr__(self, "stroke", (lo, hi))
        corners = self.pad_box.corners()
        face = float(corners[:, 1].min())
        if abs(face) > STRIP_TOL * max(1.0, float(np.abs(corners).max())):
            raise ValueError(f"the pad's face must lie on y = 0 (the tool frame's "
                             f"closing plane at opening 0), got y = {face:g}")

    @property
    def pad_box(self) -> HandBox:
        return next(b for b in self.finger if b.name == self.pad)

    @property
    def pad_width(self) -> float:
        """The pad's width along ``x``: the jaw's ``pad_width``."""
        return float(self.pad_box.size[0])

    @property
    def pad_span(self) -> tuple[float, float]:
        """The pad's extent along the approach ``z`` (tool frame)."""
        z = self.pad_box.corners()[:, 2]
        return float(z.min()), float(z.max())

    @property
    def pad_height(self) -> float:
        """The pad's height along the approach: the plate a pick takes by default."""
        lo, hi = self.pad_span
        return hi - lo

    def boxes(self, opening: float) -> list[HandBox]:
        """Every box of the hand at ``opening`` (tool frame): the palm's, finger 1's, then
        finger 2's."""
        half = float(opening) / 2
        return list(self.palm) + [b.moved(half) for b in self.finger] + \
            [b.moved(-half, turned=True) for b in self.finger]

    def in_strip(self, box: HandBox) -> bool:
        """Whether a finger box (of finger 1 at opening 0) lies in the pad's strip and
        behind the pad's face: within the pad's width along ``x`` and at ``y >= 0``."""
        c = box.corners()
        tol = STRIP_TOL * max(1.0, float(np.abs(c).max()))
        return bool(np.all(np.abs(c[:, 0]) <= self.pad_width / 2 + tol)
                    and np.all(c[:, 1] >= -tol))

    def scaled(self, factor: float, units: str) -> ParallelHand:
        """The hand in other units (``factor`` of those per millimetre)."""
        f = check_scalar(factor, "factor", positive=True)
        return replace(self, stroke=(f * self.stroke[0], f * self.stroke[1]),
                       palm=tuple(b.scaled(f) for b in self.palm),
                       finger=tuple(b.scaled(f) for b in self.finger), units=units,
                       joint_per_opening=self.joint_per_opening / f,
                       ee_offset=tuple(f * v for v in self.ee_offset))  # type: ignore[arg-type]

    def to_dict(self, opening: float | None = None) -> dict[str, Any]:
        """JSON-ready: the source and licence, the joints and their limits, and the
        collision boxes in the tool frame at ``opening`` (the largest by default)."""
        at = self.stroke[1] if opening is None else float(opening)
        at_lo, at_hi = (self.joint_offset + self.joint_per_opening * v for v in self.stroke)
        return {"name": self.name, "source": self.source, "licence": self.licence,
                "units": self.units,
                "frame": "tool: origin between the pads' faces, y closing, z approach",
                "ee_frame": self.ee_frame, "ee_offset": list(self.ee_offset),
                "ee_axes": [list(r) for r in self.ee_axes],
                "stroke": list(self.stroke), "pad_width": self.pad_width,
                "joints": [{"name": j, "lower": min(at_lo, at_hi), "upper": max(at_lo, at_hi),
                            "at_zero_opening": self.joint_offset,
                            "per_opening": self.joint_per_opening} for j in self.joints],
                "opening": at, "finger_boxes": len(self.finger),
                "boxes": [b.to_dict() for b in self.boxes(at)]}


def hand_description(hand: ParallelHand) -> dict[str, Any]:
    """Every field of a hand as plain data (:func:`hand_from_description` reads it)."""
    out: dict[str, Any] = {}
    for f in fields(hand):
        v = getattr(hand, f.name)
        if f.name in ("palm", "finger"):
            v = [b.to_dict() for b in v]
        elif isinstance(v, tuple):
            v = [list(r) if isinstance(r, tuple) else r for r in v]
        out[f.name] = v
    return out


def hand_from_description(data: dict[str, Any]) -> ParallelHand:
    """The hand of :func:`hand_description`'s data."""
    def box(d: dict[str, Any]) -> HandBox:
        return HandBox(str(d["name"]), tuple(map(float, d["centre"])),  # type: ignore[arg-type]
                       tuple(map(float, d["size"])),  # type: ignore[arg-type]
                       tuple(tuple(map(float, r)) for r in d["rotation"]))

    kw = dict(data)
    kw["palm"] = tuple(box(b) for b in data["palm"])
    kw["finger"] = tuple(box(b) for b in data["finger"])
    for k in ("stroke", "joints", "ee_offset"):
        kw[k] = tuple(data[k])
    kw["ee_axes"] = tuple(tuple(map(float, r)) for r in data["ee_axes"])
    return ParallelHand(**kw)


def _described(name: str) -> ParallelHand:
    """A built-in hand stored as :func:`hand_description`'s data (``data/NAME.json``)."""
    import json
    from importlib.resources import files

    text = files("fcgrasp.model").joinpath(f"data/{name}.json").read_text()
    return hand_from_description(json.loads(text))


def _franka() -> ParallelHand:
    """The Franka Hand (``franka_description``, ``end_effectors/common/franka_hand.xacro``
    and ``meshes/robot_ee/franka_hand_white/collision/hand.stl``): the fingers' four
    collision boxes as published; the palm as the bounding box of its collision mesh.
    The tool frame is the description's ``hand_tcp`` (103.4 mm from the flange), whose
    origin is 0.25 mm from the rubber tips' centre; the finger joints sit 58.4 mm from
    the flange and move 0 to 40 mm each.  The rubber tip's face stands 0.02 mm in front
    of its joint's plane: the finger is moved back by that much, so that the opening is
    the distance between the tips' faces, 0 to 79.96 mm (each joint at half the
    opening plus 0.02 mm)."""
    z0 = 58.4 - 103.4                   # the finger joint's height in the tool frame
    dy = 0.02                           # the tip's face on y = 0
    finger = (
        HandBox("screw_mount", (0.0, 18.5 + dy, z0 + 11.0), (22.0, 15.0, 20.0)),
        HandBox("sledge", (0.0, 6.8 + dy, z0 + 2.2), (22.0, 8.8, 3.8)),
        HandBox("diagonal", (0.0, 15.9 + dy, z0 + 28.35), (17.5, 7.0, 23.5),
                tuple(tuple(float(v) for v in r) for r in _rot_x(math.pi / 6))),
        HandBox("tip", (0.0, 7.58 + dy, z0 + 45.25), (17.5, 15.2, 18.5)),
    )
    # hand.stl: x -31.64..31.62, y -103.99..100.43, z -25.92..65.96 mm from the flange
    palm = (HandBox("palm", (-0.01, -1.78, (-25.92 + 65.96) / 2 - 103.4),
                    (63.26, 204.42, 91.88)),)
    return ParallelHand(
        "franka", (0.0, 80.0 - 2 * dy), palm, finger, "tip",
        joints=("panda_finger_joint1", "panda_finger_joint2"), joint_per_opening=0.5 * M_PER_MM,
        joint_offset=0.02 * M_PER_MM,
        source="https://github.com/frankaemika/franka_description (franka_hand.xacro, "
               "collision/hand.stl)",
        licence="Apache-2.0", ee_frame="panda_hand_tcp")


def _hande() -> ParallelHand:
    """The Robotiq Hand-E (ROS-Industrial's ``robotiq_2f_hande_gripper_visualization``,
    BSD): read from its URDF and collision meshes by
    :func:`fcgrasp.io.urdf.hand_from_urdf` and stored (the tests read the description
    again and compare)."""
    return _described("robotiq_hande")


#: The built-in hands by name.
HANDS = {"franka": _franka, "robotiq_hande": _hande}


def hand_named(name: str) -> ParallelHand:
    """A built-in hand (:data:`HANDS`)."""
    if not isinstance(name, str) or name not in HANDS:
        raise ValueError(f"hand must be one of {', '.join(sorted(HANDS))}, a URDF file or "
                         f"parameters, got {name!r}")
    return HANDS[name]()


def hand_from_params(stroke: Any, pad_width: float, pad_height: float,
                     finger_thickness: float, finger_length: float = 50.0,
                     palm: Any = None, name: str = "parameters") -> ParallelHand:
    """A hand of two box fingers: each a box ``pad_width`` wide (``x``),
    ``finger_thickness`` thick (``y``) and ``finger_length`` long (``z``) whose last
    ``pad_height`` is the pad (the tool frame's origin at the pad's centre), on a palm of
    size ``palm`` (``x, y, z``; default as wide as the fingers at the largest stroke, 40
    deep) above the fingers."""
    w = check_scalar(pad_width, "pad_width", positive=True)
    h = check_scalar(pad_height, "pad_height", positive=True)
    t = check_scalar(finger_thickness, "finger_thickness", positive=True)
    L = check_scalar(finger_length, "finger_length", positive=True)
    if h > L:
        raise ValueError(f"pad_height must be at most finger_length ({L:g}), got {pad_height!r}")
    hi = float(stroke[1])
    pz = (w, 2 * t + hi, 40.0) if palm is None else tuple(float(v) for v in palm)
    if len(pz) != 3 or min(pz) <= 0:
        raise ValueError(f"palm must be three positive sizes (x, y, z), got {palm!r}")
    top = h / 2 - L                     # the finger's end at the palm
    finger: tuple[HandBox, ...] = (HandBox("pad", (0.0, t / 2, 0.0), (w, t, h)),)
    if L > h:
        finger += (HandBox("finger", (0.0, t / 2, (top - h / 2) / 2), (w, t, L - h)),)
    palm_box = (HandBox("palm", (0.0, 0.0, top - pz[2] / 2), pz),)
    return ParallelHand(name, (float(stroke[0]), hi), palm_box, finger, "pad",
                        joints=("finger_joint",), joint_per_opening=0.001,
                        source="parameters", licence="")


@dataclass(frozen=True)
class FingerTips:
    """Point fingers on finger bodies (the paper's chopsticks, section 8.2): each finger a
    vertical cylinder of ``radius`` (its tip: the contact is on its side, the section's
    disc of ``finger_radius``) and ``length`` from its flat end up to where the hand
    holds it; or, ``in_plane``, a cylinder of that radius lying in the part's plane along
    its contact's outward normal, ``length`` long behind its round tip.  Nothing of the
    hand beyond the fingers is modelled.  Lengths in the part's units
    (millimetres as given, :meth:`scaled` for others)."""

    radius: float
    length: float
    units: str = "mm"
    name: str = "fingertips"
    #: held in the part's plane: each finger lies in it along its contact's outward
    #: normal and comes in along the inward one (else: vertical, from above)
    in_plane: bool = False

    def __post_init__(self) -> None:
        object.__setattr__(self, "radius", check_scalar(self.radius, "radius", positive=True))
        object.__setattr__(self, "length", check_scalar(self.length, "length", positive=True))

    def scaled(self, factor: float, units: str) -> FingerTips:
        """The same fingers with lengths times ``factor``, in ``units``."""
        return replace(self, radius=self.radius * factor, length=self.length * factor,
                       units=units)

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "kind": "fingertips", "units": self.units,
                "tip_radius": self.radius, "finger_length": self.length,
                "in_plane": self.in_plane, "source": "parameters", "licence": ""}


def params_of(text: str) -> dict[str, str]:
    """The ``key=value`` pairs of a comma-separated ``--hand`` parameter form."""
    given: dict[str, str] = {}
    for item in str(text).split(","):
        key, _, value = item.partition("=")
        given[key.strip()] = value.strip()
    return given


def tips_from_params(text: str) -> FingerTips:
    """``--hand tip=R[,length=L]`` of point fingers (millimetres; the length 50 by
    default)."""
    given = params_of(text)
    if set(given) - {"tip", "length"} or "tip" not in given:
        raise ValueError(f"hand of point fingers must be tip=R[,length=L] (millimetres), "
                         f"got {text!r}")
    try:
        radius, length = float(given["tip"]), float(given.get("length", 50.0))
    except ValueError:
        raise ValueError(f"hand parameters must be numbers, got {text!r}") from None
    if not (math.isfinite(radius) and radius > 0 and math.isfinite(length) and length > 0):
        raise ValueError(f"hand tip and length must be finite numbers > 0, got {text!r}")
    return FingerTips(radius, length)
