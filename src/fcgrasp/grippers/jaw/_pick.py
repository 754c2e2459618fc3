r"""A planar part picked from above by a real hand: the part a plate of some thickness
lying on a table (or held alone), the hand's fingers and palm as boxes
(:class:`~fcgrasp.model.hands.ParallelHand`), and when every pose of a jaw's box is
collision free (section 8.2: the hand's shape as a collision problem).

**The scene.**  The plate fills ``0 <= z <= thickness`` over the part's outline (its
holes open), the table (with ``table``) is the plane ``z = 0`` beneath it.  The hand
comes down along ``-z`` opened to its largest stroke, above the pose, then closes to
the part; its tool frame (:mod:`fcgrasp.model.hands`) has ``y`` along the jaw's closing
direction ``u``, ``z`` pointing down, and its origin at the pose's height ``height``.

**Why every pose of a box is collision free (exactly, not sampled).**  At each pose the
jaw's pad stops on the part's extreme material within its strip (the pad's width
across ``u``), so the strip beyond each pad's face holds no material:

* a finger box within the pad's width and behind the pad's face
  (:meth:`~fcgrasp.model.hands.ParallelHand.in_strip`) meets no material at any pose of
  the box, at the largest opening, while the hand closes, or at the contact, whatever
  its height;
* every other box (the palm, a mount wider than the pad) is held above the plate's top
  by ``clearance``, and every box above the table by ``clearance``, by the choice of
  ``height``: the pad centred on the plate's mid-thickness where that is enough, else
  raised, as long as the pad still covers a band of the plate's side
  (:attr:`TopPick.contact_height`); a plate the pad cannot reach that way gets no pick
  (:func:`top_pick` says why).

Internal grips (the hand opening inside a hole) need the closed fingers' room in the
hole, which this model does not bound: with a hand, the jaw plans external grips only.
The tests check the verdict on thousands of sampled poses of every plan against an
independent collision library (python-fcl through trimesh) on the extruded plate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...core._checks import check_scalar
from ...core.tolerances import TOL
from ...model.hands import ParallelHand

__all__ = ["Scene", "TopPick", "top_pick", "plate_scene"]


@dataclass(frozen=True)
class Scene:
    """A planar part as a plate ``thickness`` thick, on a ``table`` (the plane ``z =
    0``) or alone; ``clearance``: the least gap kept between the hand and the plate or
    the table; ``approach`` and ``retreat``: how far the hand comes down to the pose and
    goes up from it (all in the part's units); ``rest``: which stable pose a solid rests
    in."""

    thickness: float
    table: bool = True
    clearance: float = 1.0
    approach: float = 100.0
    retreat: float = 100.0
    #: a solid on the table: which of its stable poses it rests in (0: the most likely,
    #: :func:`~fcgrasp.grippers.jaw._solid_pick.resting_pose`)
    rest: int = 0
    #: or the orientation it is given on the table (a unit quaternion x, y, z, w from the
    #: part's frame to the table's; the part lowered onto the table), None: ``rest``
    orientation: tuple[float, float, float, float] | None = None
    #: a planar part held in its plane (:mod:`fcgrasp.grippers.jaw._plane_pick`), not
    #: picked from above
    in_plane: bool = False

    def __post_init__(self) -> None:
        for name in ("thickness", "clearance", "approach", "retreat"):
            object.__setattr__(self, name, check_scalar(getattr(self, name), name,
                                                        positive=name == "thickness",
                                                        nonnegative=True))
        for name in ("table", "in_plane"):
            if not isinstance(getattr(self, name), bool):
                raise TypeError(f"{name} must be a bool, got {getattr(self, name)!r}")
        if isinstance(self.rest, bool) or not isinstance(self.rest, int) or self.rest < 0:
            raise ValueError(f"rest must be a whole number >= 0, got {self.rest!r}")
        if self.orientation is not None:
            q = np.asarray(self.orientation, float)
            if q.shape != (4,) or not np.all(np.isfinite(q)) or np.linalg.norm(q) < TOL:
                raise ValueError(f"orientation must be a quaternion x, y, z, w (not zero), "
                                 f"got {self.orientation!r}")
            object.__setattr__(self, "orientation", tuple(float(v) for v in
                                                          q / np.linalg.norm(q)))

    def motions(self, approach: Any, retreat: Any) -> dict[str, Any]:
        """A pick's ``approach`` and ``retreat`` of the report: the hand comes in along
        ``approach`` over this scene's approach distance and leaves along ``retreat``
        over its retreat distance (part frame)."""
        return {"approach": {"direction": [float(v) for v in approach],
                             "distance": self.approach, "frame": "part"},
                "retreat": {"direction": [float(v) for v in retreat],
                            "distance": self.retreat, "frame": "part"}}

    def to_dict(self) -> dict[str, Any]:
        return {"part_pose": {"position": [0.0, 0.0, 0.0], "orientation": [0.0, 0.0, 0.0, 1.0]},
                "thickness": self.thickness,
                "table": {"point": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, 1.0]}
                if self.table else None,
                "clearance": self.clearance, "approach": self.approach,
                "retreat": self.retreat,
                "rest": self.rest if self.orientation is None else None,
                "rest_orientation": None if self.orientation is None
                else list(self.orientation),
                "held": "in_plane" if self.in_plane else "from_above"}


def plate_scene(options: Any, thickness: float, per_mm: float, away_mm: float = 100.0,
                **placed: Any) -> Scene:
    """The scene of a request's pick (``--thickness``, by default ``thickness``, the
    part's units; ``--table``): a 1 mm clearance and ``away_mm`` of approach and retreat
    (``per_mm``: the part's units per millimetre); ``placed``: a solid's ``rest`` or
    ``orientation``."""
    given = options.get("thickness")
    if given is not None:
        if not (math.isfinite(given) and given > 0):
            raise ValueError(f"--thickness must be a finite number > 0, got {given:g}")
        thickness = given
    return Scene(thickness, table=bool(options.get("table")), clearance=1.0 * per_mm,
                 approach=away_mm * per_mm, retreat=away_mm * per_mm, **placed)


@dataclass(frozen=True)
class TopPick:
    """How a hand picks the plate from above: the tool frame's ``height`` above the
    plate's bottom, and the band of the plate's side the pad covers
    (``contact_height``)."""

    height: float
    contact_height: float


def _lowest(boxes: Any) -> float:
    """The largest tool ``z`` (the lowest point, the tool's ``z`` pointing down) of
    boxes."""
    return max(float(b.corners()[:, 2].max()) for b in boxes)


def top_pick(hand: ParallelHand, scene: Scene) -> TopPick | str:
    """The height of the tool frame that keeps the hand clear of the plate and the table
    (the module's docstring), or why none does."""
    pz0, pz1 = hand.pad_span
    T, c = scene.thickness, scene.clearance
    height = T / 2 + (pz0 + pz1) / 2                # the pad centred on the plate's side
    if scene.table:
        height = max(height, _lowest(hand.boxes(hand.stroke[1])) + c)
    others = list(hand.palm) + [b for b in hand.finger if not hand.in_strip(b)]
    if others:
        height = max(height, _lowest(others) + T + c)
    # the pad spans heights height - pz1 .. height - pz0; the plate 0 .. T
    band = min(T, height - pz0) - max(0.0, height - pz1)
    if band <= 0:
        return (f"the hand's pads do not reach the plate's side: a {T:g} thick plate "
                f"needs the palm and the parts of the fingers wider than the pad "
                f"{c:g} above it (the pad would then be {-band:g} above the plate)")
    return TopPick(float(height), float(band))
