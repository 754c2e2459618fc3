"""The parallel jaw as a gripper (:class:`ParallelJaw`) and its plans: the largest
boxes of holding poses, proved and grown (:func:`jaw_plans`, :class:`JawPlan`)."""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any, ClassVar

import numpy as np

from ...core import budget
from ...core._checks import FloatArray, check_int
from ...core._json import json_ready
from ...core.budget import PlanList
from ...core.tolerances import CONTACT_TOL, TOL
from ...model.distinct import (
    DEFAULT_DISTINCT,
    box_images,
    distinct_boxes,
    grip_symmetries,
)
from ...model.hands import ParallelHand, hand_from_params, hand_named, params_of
from ...model.polygon import Polygon
from ...model.regions import DEFAULT_MARGIN_DEG
from ..base import DEFAULT_MU, register
from ._boxes import (
    GROW_TOO,
    REFINE_TOP,
    _clear_of,
    _proved,
    _proved_grown,
    _proved_refined,
)
from ._grid import (
    _box_scores,
    _checked_box,
    _clear_images,
    _grid,
    _measure,
)
from ._pick import Scene, TopPick, plate_scene, top_pick
from ._plane_pick import PlaneReach, plane_pick_dict, plane_plans, plane_reach
from ._poses import (
    OFFSET_STEPS,
    THETA_STEP_DEG,
    JawParameters,
    _check_jaw_args,
    _contact_points,
    insertion_point,
    jaw_poses,
)


@dataclass(frozen=True)
class ParallelJaw(JawParameters):
    """A parallel-jaw gripper: its stroke ``(min_opening, max_opening)``, the width of
    its flat pads and their friction coefficient ``mu`` (lengths in the part's units).

    >>> ParallelJaw(stroke=(10, 50), pad_width=12, mu=0.4).stroke
    (10.0, 50.0)
    """

    #: the hand's geometry (:class:`~fcgrasp.model.hands.ParallelHand`, in the part's
    #: units): the part is then a plate picked from above (``scene``), every plan's box
    #: collision free (:mod:`fcgrasp.grippers.jaw._pick`), each with its pose
    hand: ParallelHand | None = None
    #: the plate and the table of a pick with a hand (:class:`Scene`)
    scene: Scene | None = None

    name: ClassVar[str] = "jaw"
    #: ``distinct=`` when none is given: the boxes are distinct
    #: alternatives, mirror images and neighbouring slices of one contact configuration
    #: merged (:meth:`distinct_plans`); ``distinct=0`` gives every box, as ranked
    default_distinct: ClassVar[float] = DEFAULT_DISTINCT

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.hand is None:
            if self.scene is not None:
                raise ValueError("scene needs a hand: a plate and a table are for a hand "
                                 "model's pick")
            return
        if not isinstance(self.hand, ParallelHand):
            raise TypeError(f"hand must be a ParallelHand, got {type(self.hand).__name__}")
        # held in the plane the strip is the pad's height along the approach
        in_plane = self.scene is not None and self.scene.in_plane
        pad = self.hand.pad_height if in_plane else self.hand.pad_width
        if abs(self.pad_width - pad) > TOL * pad:
            raise ValueError(f"pad_width must be the hand's pad "
                             f"{'height' if in_plane else 'width'} ({pad:g}), got "
                             f"{self.pad_width:g}")
        lo, hi = self.hand.stroke
        if self.stroke[0] < lo * (1 - TOL) or self.stroke[1] > hi * (1 + TOL):
            raise ValueError(f"stroke must be within the hand's ({lo:g}, {hi:g}), got "
                             f"{self.stroke!r}")
        if self.scene is None:
            object.__setattr__(self, "scene", Scene(self.hand.pad_height))
        elif not isinstance(self.scene, Scene):
            raise TypeError(f"scene must be a Scene, got {type(self.scene).__name__}")

    @classmethod
    def of_hand(cls, hand: ParallelHand, mu: float, scene: Scene | None = None,
                certify: bool = True) -> ParallelJaw:
        """The jaw of a hand: its stroke and pad width, picking a plate from above
        (``scene``; by default a plate as thick as the pad is tall, on no table)."""
        pad = hand.pad_height if scene is not None and scene.in_plane else hand.pad_width
        return cls(stroke=hand.stroke, pad_width=pad, mu=mu, certify=certify, hand=hand,
                   scene=scene)

    @property
    def pick(self) -> TopPick | PlaneReach | str | None:
        """How the hand picks the plate (:func:`top_pick`; held in its plane,
        :func:`plane_reach`), why it cannot, or None without a hand."""
        if self.hand is None or self.scene is None:
            return None
        if self.scene.in_plane:
            return plane_reach(self.hand, self.scene)
        return top_pick(self.hand, self.scene)

    # the gripper interface (fcgrasp.grippers.base.Gripper)
    def distinct_plans(self, polygon: Polygon, plans: list[JawPlan],
                       fraction: float) -> list[JawPlan]:
        """The boxes that are distinct alternatives, up to the part's symmetries, the
        neighbouring boxes of one contact configuration (apart by at most two steps of
        the pose grid: a box is moved in from the holding set's boundary by a fraction
        of a step before its proof) merged
        (:func:`fcgrasp.model.distinct.distinct_boxes`)."""
        reach = polygon.radius \
            + self.pad_width / 2
        steps = (2 * np.radians(THETA_STEP_DEG), 2 * 2 * reach / (OFFSET_STEPS - 1))
        return distinct_boxes(polygon, plans, fraction, adjacent=steps)

    def plan(self, polygon: Polygon, options: Any) -> list[JawPlan]:
        """The jaw's boxes (:func:`jaw_plans`) for a plan's search options."""
        if options.top is None:
            raise ValueError("a parallel jaw needs a top (how many boxes), got top=None")
        if options.rank_by != "min_region":
            raise ValueError(f"a parallel jaw ranks its boxes by their measure: "
                             f"rank_by={options.rank_by!r} would not be used")
        pick = self.pick
        if isinstance(pick, str):
            return []                   # the hand cannot reach the plate (the reason)
        if isinstance(pick, PlaneReach):
            return plane_plans(polygon, self, pick, options.top, options.margin,
                               lambda keep, most: jaw_plans(
                                   polygon, self, top=options.top, margin=options.margin,
                                   certify=self.certify, internal=False, keep=keep,
                                   most=most))
        # a hand's closed fingers need room in a hole, which the pick does not bound
        return jaw_plans(polygon, self, top=options.top, margin=options.margin,
                         certify=self.certify, internal=self.hand is None)

    def check_part(self, polygon: Polygon, options: Any) -> None:
        """Nothing to refuse before the search."""

    def parameters(self, options: Any) -> dict[str, Any]:
        out = {"gripper": "parallel_jaw", "stroke": list(self.stroke),
               "pad_width": self.pad_width, "mu": self.mu, "top": options.top,
               "margin_deg": options.margin, "certify": self.certify}
        if self.hand is not None and self.scene is not None:
            out["hand"] = self.hand.to_dict()
            out["scene"] = self.scene.to_dict()
        return out

    def no_grasp_reason(self, margin: float) -> str:
        pick = self.pick
        if isinstance(pick, str):
            return pick
        return (f"no pose of the jaw holds the part (stroke {self.stroke[0]:g} to "
                f"{self.stroke[1]:g}, pads {self.pad_width:g} wide, mu = {self.mu:g}, "
                f"margin {margin:g} degrees)")

    @property
    def title(self) -> str:
        return "parallel jaw"

    # on a solid: flat pads on opposite parallel facets (fcgrasp.grippers.solids)
    solid_title: ClassVar[str] = "a parallel jaw"
    #: the plan request's options a solid's plans take (the others are refused there)
    solid_options: ClassVar[tuple[str, ...]] = ("mu", "stroke", "pad", "margin", "top",
                                                "distinct", "time_limit", "max_memory",
                                                "hand", "table", "rest", "rest_orientation")

    def solid_plans(self, solid: Any, options: Any, fraction: float) -> PlanList:
        """The regions of closing axes on pairs of opposite parallel facets
        (:func:`fcgrasp.spatial.jaw.solid_jaw_plans`)."""
        from ...spatial.alternatives import top_distinct
        from ...spatial.jaw import solid_jaw_plans

        if self.scene is not None and self.scene.in_plane:
            raise ValueError("--in-plane holds a planar part in its plane: a solid is "
                             "picked from its own surface (leave --in-plane out)")
        if self.hand is not None and self.scene is not None:
            from ._solid_pick import hand_solid_plans

            return hand_solid_plans(self, solid, options.top, options.margin, fraction)
        return top_distinct(lambda n: solid_jaw_plans(solid, self.stroke, self.pad_width,
                                                      self.mu, top=n, margin=options.margin),
                            options.top, fraction)

    def solid_parameters(self, options: Any) -> dict[str, Any]:
        out = {"gripper": "jaw", "contact_type": "jaw", "stroke": list(self.stroke),
               "pad": self.pad_width, "mu": self.mu, "top": options.top,
               "margin_deg": options.margin}
        if self.hand is not None:
            from ._solid_pick import pad_diameter

            # the round pad that covers the hand's pad (fcgrasp.spatial.jaw's model)
            out["pad"] = pad_diameter(self.hand)
            out["hand"] = self.hand.to_dict()
        return out

    def solid_no_grasp_reason(self, margin: float) -> str:
        if self.hand is not None:
            return (f"no two opposite parallel facets {self.stroke[0]:g} to "
                    f"{self.stroke[1]:g} apart take the {self.hand.name} hand's pads with mu "
                    f"{self.mu:g} and a margin of {margin:g} degrees, the hand clear of the "
                    f"part{' and the table' if self.scene and self.scene.table else ''}")
        return (f"no two opposite parallel facets {self.stroke[0]:g} to {self.stroke[1]:g} "
                f"apart (the stroke) take the jaw's {self.pad_width:g} pads with mu "
                f"{self.mu:g} and a margin of {margin:g} degrees")


def jaw_from_options(options: Mapping[str, Any]) -> ParallelJaw:
    """The parallel jaw of a plan request (``--gripper jaw``): ``stroke``, ``pad``,
    ``mu`` (default 0.3), ``certify`` (default True); none of the point fingers'
    options."""
    for opt, given in (("--fingers", options.get("fingers") is not None),
                       ("--gravity", options.get("gravity") is not None),
                       ("--workspace", options.get("workspace") is not None),
                       ("--finger-radius", bool(options.get("finger_radius"))),
                       ("--rank-by", options.get("rank_by", "min_region")
                        not in ("min_region", "payload")),
                       ("--single-edge", bool(options.get("single_edge")))):
        if given:
            raise ValueError(f"{opt} is an option of point fingers, not of --gripper jaw")
    stroke, pad = options.get("stroke"), options.get("pad")
    mu = DEFAULT_MU if options.get("mu") is None else options["mu"]
    hand = options.get("hand")
    if hand is not None:
        return _jaw_of_hand(options, hand, mu)
    for opt, name in (("--thickness", "thickness"), ("--table", "table"), ("--rest", "rest"),
                      ("--rest-orientation", "rest_orientation"), ("--in-plane", "in_plane")):
        if options.get(name) is not None and options.get(name) is not False:
            raise ValueError(f"{opt} is for a pick with a hand: give --hand too")
    if stroke is None or pad is None:
        missing = "--stroke MIN,MAX" if stroke is None else "--pad WIDTH"
        raise ValueError(f"{missing} is needed: --gripper jaw needs --stroke MIN,MAX and "
                         f"--pad WIDTH (in the part's units)")
    if not (math.isfinite(mu) and mu > 0):
        raise ValueError(f"--mu of a parallel jaw must be a finite number > 0, got {mu:g}")
    return ParallelJaw(stroke=(stroke[0], stroke[1]), pad_width=pad, mu=mu,
                       certify=options.get("certify") is not False)


def _hand_of(text: str) -> ParallelHand:
    """``--hand``: a built-in hand's name (:data:`~fcgrasp.model.hands.HANDS`), a URDF
    file (:func:`fcgrasp.io.urdf.hand_from_urdf`), or parameters
    ``stroke=MIN:MAX,pad=W,height=H,thickness=T[,length=L]`` (millimetres,
    :func:`~fcgrasp.model.hands.hand_from_params`)."""
    if "=" in text:
        given = params_of(text)
        known = {"stroke", "pad", "height", "thickness", "length"}
        if set(given) - known or not {"stroke", "pad", "height", "thickness"} <= set(given):
            raise ValueError(f"--hand parameters are stroke=MIN:MAX,pad=W,height=H,"
                             f"thickness=T[,length=L], got {text!r}")
        try:
            lo, hi = (float(v) for v in given["stroke"].split(":"))
            values = {k: float(given[k]) for k in known - {"stroke"} if k in given}
        except ValueError:
            raise ValueError(f"--hand parameters must be numbers, got {text!r}") from None
        return hand_from_params((lo, hi), values["pad"], values["height"],
                                values["thickness"], values.get("length", 50.0))
    if text.lower().endswith(".urdf"):
        from ...io.urdf import hand_from_urdf

        try:
            return hand_from_urdf(text)
        except ValueError as exc:
            raise ValueError(f"--{exc}") from None
    try:
        return hand_named(text)
    except ValueError as exc:
        raise ValueError(f"--hand {exc}") from None


def _jaw_of_hand(options: Mapping[str, Any], name: Any, mu: float) -> ParallelJaw:
    """The jaw of ``--hand`` (:func:`_hand_of`), in the part's units, picking a plate
    ``--thickness`` thick (by default as thick as the pad is tall) from above, on a
    table with ``--table``."""
    from ...io.units import MM_PER

    if options.get("stroke") is not None or options.get("pad") is not None:
        raise ValueError("--stroke and --pad are the hand's: give --hand alone")
    if not (math.isfinite(mu) and mu > 0):
        raise ValueError(f"--mu of a parallel jaw must be a finite number > 0, got {mu:g}")
    hand = _hand_of(str(name))
    per_mm = 1.0 / MM_PER[options.get("units") or "mm"]
    hand = hand.scaled(per_mm, options.get("units") or "mm")
    rest, turned = options.get("rest"), options.get("rest_orientation")
    for opt, given in (("--rest", rest), ("--rest-orientation", turned)):
        if given is not None and not options.get("table"):
            raise ValueError(f"{opt} is a solid's pose on the table: give --table too")
    if rest is not None and turned is not None:
        raise ValueError("--rest and --rest-orientation both place the part on the table: "
                         "give one")
    # held in its plane, the pad's width covers the plate's thickness
    in_plane = bool(options.get("in_plane"))
    scene = plate_scene(options, hand.pad_width if in_plane else hand.pad_height, per_mm,
                        rest=0 if rest is None else rest, orientation=turned,
                        in_plane=in_plane)
    return ParallelJaw.of_hand(hand, mu, scene, certify=options.get("certify") is not False)


register("jaw", jaw_from_options, lambda options: ParallelJaw)


@dataclass
class JawPlan:
    """A box of jaw poses that hold: ``theta`` (t0, t1) in radians, ``offset`` (c0, c1)
    from the centroid, the ``opening`` range over the box's checked poses (every pose of
    the box fits the stroke; between checked poses the opening may pass the range by a
    little), the contacts at the box's
    centre pose (``contacts``: per pad, the contact points; ``kinds``: ``"vertex"``,
    ``"edge"`` or ``"corner"``; ``stops``: where pads A and B stop, along ``u`` from the
    centroid), the ranking ``measure``: ``min(c1 - c0, (t1 - t0) * radius)``, and the
    grip: ``mode`` ``"external"`` (closing on the outline) or ``"internal"`` (opening in
    the hole ``hole``, an index into the part's holes, the closed jaws put in at
    ``insert``: :func:`insertion_point`); ``features``: the part's edges each pad touches
    at some checked pose of the box (the contact features over the box; a vertex as the
    edges that meet there)."""

    theta: tuple[float, float]
    offset: tuple[float, float]
    opening: tuple[float, float]
    contacts: list[FloatArray]
    kinds: tuple[str, str]
    stops: tuple[float, float]
    measure: float
    jaw: ParallelJaw
    centroid: FloatArray = field(repr=False)
    radius: float = field(repr=False)
    mode: str = "external"
    hole: int | None = None
    certified: bool = False
    insert: FloatArray | None = None
    features: tuple[list[int], list[int]] = ([], [])
    #: with distinct plans: how many lower-ranked boxes this one stands for
    similar: int = 0
    #: held in the plane by a hand: the side of the strip the hand lies on (``+1``:
    #: ``+n``, coming in along ``-n``; :mod:`fcgrasp.grippers.jaw._plane_pick`), else 0
    side: int = 0
    #: with a load (``plan(..., load=)``): the scale of it every pose of the box carries
    #: (:func:`fcgrasp.grippers.jaw.jaw_payload`, a
    #: :class:`~fcgrasp.model.loads.RegionPayload`); in the JSON as ``payload``
    payload: Any = field(default=None, repr=False, compare=False)

    @property
    def regions(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """The :class:`~fcgrasp.Plan` regions: the box of poses ``(theta, offset)``."""
        return (self.theta, self.offset)

    @property
    def centre(self) -> tuple[float, float]:
        """The box's centre pose ``(theta, offset)``."""
        return (sum(self.theta) / 2, sum(self.offset) / 2)

    def cut_to(self, polygon: Polygon, theta: tuple[float, float],
               offset: tuple[float, float], margin: float, side: int = 0) -> JawPlan:
        """The plan of a sub-box of this one (a hand held in the plane on ``side``:
        :mod:`fcgrasp.grippers.jaw._plane_pick`): its measure, and its contacts at its
        own centre pose; the opening range and the features stay this box's (they hold
        over the sub-box too)."""
        pts, kinds, stops = _centre_contacts(polygon, self.jaw, sum(theta) / 2,
                                             sum(offset) / 2, margin, self.hole)
        return replace(self, theta=theta, offset=offset, side=side, contacts=pts,
                       kinds=kinds, stops=stops,
                       measure=_measure(theta, offset, polygon.radius))

    def sample(self, n: int, rng: np.random.Generator | None = None) -> FloatArray:
        """``n`` poses uniform in the box, shape (n, 2): ``(theta, offset)``."""
        rng = np.random.default_rng() if rng is None else rng
        u = rng.random((n, 2))
        return np.c_[self.theta[0] + u[:, 0] * (self.theta[1] - self.theta[0]),
                     self.offset[0] + u[:, 1] * (self.offset[1] - self.offset[0])]

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready description (angles also in degrees)."""
        extra: dict[str, Any] = {"similar": self.similar} if self.similar else {}
        if self.payload is not None:
            extra["payload"] = self.payload.to_dict()
        pick = self.jaw.pick
        if isinstance(pick, TopPick):
            extra.update(self.pick_dict(pick))
        elif isinstance(pick, PlaneReach):
            extra.update(plane_pick_dict(self, pick))
        return json_ready({**extra,
            "gripper": "parallel_jaw", "mode": self.mode, "hole": self.hole,
            "insert": self.insert,
            "theta_rad": list(self.theta), "theta_deg": list(np.degrees(self.theta)),
            "offset": list(self.offset), "opening": list(self.opening),
            "contacts": {"a": {"kind": self.kinds[0], "points": self.contacts[0],
                               "stop": self.stops[0], "edges": self.features[0]},
                         "b": {"kind": self.kinds[1], "points": self.contacts[1],
                               "stop": self.stops[1], "edges": self.features[1]}},
            "measure": self.measure, "centre": list(self.centre), "centroid": self.centroid,
            "certified": self.certified,
            "stroke": list(self.jaw.stroke), "pad_width": self.jaw.pad_width,
            "mu": self.jaw.mu,
        })


    def pick_dict(self, pick: TopPick) -> dict[str, Any]:
        """The pick of the box's centre pose with the jaw's hand: the tool frame's pose
        (:func:`fcgrasp.io.moveit.jaw_tool_pose`), the opening it comes down at, the
        approach and the retreat (part frame, the part's units); every pose of the box is
        collision free (:mod:`fcgrasp.grippers.jaw._pick`)."""
        assert self.jaw.hand is not None and self.jaw.scene is not None
        from ...io.moveit import jaw_tool_pose, quaternion

        where, axes = jaw_tool_pose(self.centroid, self.centre[0], self.centre[1],
                                    self.stops, pick.height)
        position = [float(v) for v in where]
        orientation = list(quaternion(axes))
        return {"pose": {"position": position, "orientation": orientation, "frame": "part"},
                "pre_grasp_opening": self.jaw.hand.stroke[1],
                **self.jaw.scene.motions((0.0, 0.0, -1.0), (0.0, 0.0, 1.0)),
                "collision_free": True, "contact_height": pick.contact_height}


def _kind(lat: FloatArray, psi: FloatArray, size: float) -> str:
    """How a pad touches at one pose: on a pad corner, an edge flat on it, or vertices."""
    real = np.isfinite(lat[:, 0])
    if np.any(np.abs(psi[real]) > 0):
        return "corner"
    return "edge" if np.any(lat[real, 1] - lat[real, 0] > CONTACT_TOL * size) else "vertex"


def jaw_plans(polygon: Polygon, jaw: ParallelJaw, top: int = 5,
              margin: float = DEFAULT_MARGIN_DEG, internal: bool = True,
              certify: bool = True, keep: Callable[[JawPlan], JawPlan | None] | None = None,
              most: int | None = None) -> list[JawPlan]:
    """The ``top`` largest boxes of jaw poses that hold, best first (see the module's
    docstring): external grips, and with ``internal`` grips inside each hole (the jaws
    put in at its :func:`insertion_point`).  For each grip, each found box's poses are
    removed from the grid before the next is sought, with their mirror (``theta + pi``,
    ``-c``: the same grasp, pads swapped) and their images under the part's symmetries
    (:func:`fcgrasp.model.distinct.grip_symmetries`: the same grasp turned or mirrored;
    for an internal grip, those that keep its hole and insertion point); a returned box
    as grown is removed too, with its images.
    With ``certify`` (the default) each box is also *proved* by :func:`certify_box` (shrunk
    by up to :data:`CERTIFY_SHRINKS` grid steps until the proof succeeds within
    :data:`CERTIFY_BOXES` sub-boxes; a box it cannot prove is dropped and the next one
    sought); then the largest box near it on a raster of the exact set
    (:func:`~fcgrasp.grippers.jaw.holding_offsets`; for the :data:`REFINE_TOP` best of
    each grip), moved in by :data:`REFINE_BACKOFF`, or the box grown to the set's exact
    boundary, moved in by :data:`GROW_BACKOFF`, is proved and kept where it measures more
    and overlaps no box returned before nor its images: every returned plan then has
    ``certified`` True. ``certify=False`` returns the boxes verified on the fine grid only.
    ``keep(plan)`` makes each box found into the plan returned, or leaves it out (None;
    its poses still taken), until ``top`` are kept or ``most`` boxes were found (a hand
    held in the plane cuts each box to its collision-free poses).

    >>> from fcgrasp.io.parts import demo_part
    >>> jaw = ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
    >>> best = jaw_plans(demo_part("rectangle"), jaw, top=1)[0]   # across the 30 mm
    >>> [round(float(np.degrees(t)), 1) % 180 for t in best.theta], best.kinds
    ([77.9, 102.1], ('edge', 'edge'))
    >>> best.certified, round(best.offset[1], 2)       # proved: every pose of the box holds
    (True, 39.73)
    >>> grid = jaw_plans(demo_part("rectangle"), jaw, top=1, certify=False)[0]
    >>> [round(float(np.degrees(t))) % 180 for t in grid.theta], grid.certified
    ([78, 102], False)
    """
    margin = _check_jaw_args(polygon, jaw, margin)
    top = check_int(top, "top", minimum=1)
    if not isinstance(internal, bool):
        raise TypeError(f"internal must be a bool, got {internal!r}")
    if not isinstance(certify, bool):
        raise TypeError(f"certify must be a bool, got {certify!r}")
    holes: list[int | None] = [None]
    if internal:
        holes += list(range(len(polygon.holes)))
    plans = [p for h in holes
             for p in _grip_plans(polygon, jaw, top, margin, h, certify, keep, most)]
    plans.sort(key=lambda p: -p.measure)
    return plans[:top]


def _grip_plans(polygon: Polygon, jaw: ParallelJaw, top: int, margin: float,
                hole: int | None, certify: bool = True,
                keep: Callable[[JawPlan], JawPlan | None] | None = None,
                most: int | None = None) -> list[JawPlan]:
    """The best boxes of one grip (external, or internal in ``hole``); with ``keep``,
    each box found as ``keep`` makes it (None: left out, its poses still taken), until
    ``top`` are kept or ``most`` boxes were found."""
    radius = polygon.radius
    thetas, offsets, H = _grid(polygon, jaw, margin, hole)
    K, M = thetas.size, offsets.size
    dth, dc = 2 * np.pi / K, offsets[1] - offsets[0]
    # inside a hole, the symmetries that keep the hole and the point the jaws go in at
    symmetries = grip_symmetries(polygon, None if hole is None
                                 else insertion_point(polygon, hole))
    plans: list[JawPlan] = []
    taken: list[tuple[float, float, float, float]] = []    # the plans' boxes and images
    found = 0
    while len(plans) < top and (most is None or found < most):
        # the time budget: the boxes proved so far (none, where the grid's boxes could
        # not be proved in time: the answer then says the search stopped)
        if (plans and budget.cut_if_over()) or budget.cut_if_over(counted=False):
            break
        score, k0, k1, j0, j1 = _box_scores(H, dth, dc, radius, K // 2)
        if score <= 0:
            break
        H[np.arange(k0, k1 + 1) % K, j0:j1 + 1] = False
        H[(np.arange(k0, k1 + 1) + K // 2) % K, M - 1 - j1:M - j0] = False
        # the box's images under the part's symmetries are the same grasps
        _clear_images(H, thetas[k0] + (k1 - k0) * dth * np.array([0.0, 1.0]),
                      offsets[[j0, j1]], symmetries, dth, offsets, thetas[0])
        box = _checked_box(polygon, jaw, margin, hole,
                           thetas[k0] + np.array([0, k1 - k0]) * dth, offsets[[j0, j1]],
                           dth, dc)
        if box is None:
            continue
        if certify:
            # the grid box proved (shrunk by grid steps); then, for the REFINE_TOP
            # first, the largest box near it on a raster of the exact slices, apart from
            # the plans so far, proved, kept where it measures more (the back-off from
            # the boundary can cost more than the search gives); where there is none
            # or it gains little, the grid box grown to the exact boundary and proved
            proved = _proved(polygon, jaw, margin, hole, box[0], box[1], dth, dc)
            if proved is None:
                continue
            floor = _measure(*proved, radius)
            # past the time budget (after the first box) the grid's box, proved, is kept
            # as it is: neither refined nor grown
            late = bool(plans) and budget.cut_if_over()
            better = None if len(plans) >= REFINE_TOP or late else _proved_refined(
                polygon, jaw, margin, hole, box[0], box[1], dth, dc, taken, floor)
            if not late and (better is None
                             or _measure(*better, radius) < floor * (1 + GROW_TOO)):
                grown = _proved_grown(polygon, jaw, margin, hole, box[0], box[1], dth, dc)
                # (grown into a plan found before, or its image, it is not kept)
                if grown is not None and _clear_of(grown, taken) and _measure(
                        *grown, radius) > max(floor, _measure(*better, radius)
                                              if better is not None else 0.0):
                    better = grown
            if better is not None:
                proved = better
            # the opening range over the proved box's checked poses
            box = _checked_box(polygon, jaw, margin, hole, np.array(proved[0]),
                               np.array(proved[1]), dth, dc)
            if box is None:
                continue
        (t0, t1), (c0, c1), _, _ = box
        # the box as grown (past the grid box found) and its images are off the grid
        # too: a later box would overlap it or mirror it
        _clear_images(H, np.array([t0, t1]), np.array([c0, c1]), symmetries, dth, offsets,
                      thetas[0])
        taken += box_images((float(t0), float(t1)), (float(c0), float(c1)), symmetries)
        found += 1
        plan = _plan_of(polygon, jaw, margin, hole, box, certify)
        kept = plan if keep is None else keep(plan)
        if kept is not None:
            plans.append(kept)
    return plans


def _plan_of(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
             box: Any, certified: bool) -> JawPlan:
    """The :class:`JawPlan` of a checked box (:func:`_checked_box`: its ranges, opening
    and features), with the contacts at its centre pose."""
    (t0, t1), (c0, c1), opening, features = box
    pts, kinds, stops = _centre_contacts(polygon, jaw, (t0 + t1) / 2, (c0 + c1) / 2, margin,
                                         hole)
    radius = polygon.radius
    return JawPlan((float(t0), float(t1)), (float(c0), float(c1)), opening, pts, kinds,
                   stops, _measure((t0, t1), (c0, c1), radius),
                   jaw, polygon.centroid.copy(), radius,
                   "external" if hole is None else "internal", hole, certified,
                   None if hole is None else insertion_point(polygon, hole), features)


def _centre_contacts(polygon: Polygon, jaw: ParallelJaw, theta: float, offset: float,
                     margin: float, hole: int | None
                     ) -> tuple[list[FloatArray], tuple[str, str], tuple[float, float]]:
    """A box's contacts at its centre pose ``(theta, offset)``: each pad's contact
    points, how each touches (:func:`_kind`) and where each stops."""
    r = jaw_poses(polygon, jaw, [theta], [offset], margin, hole)
    pts = [_contact_points(polygon, theta, r.lat_a[0], float(r.top[0])),
           _contact_points(polygon, theta, r.lat_b[0], float(r.bottom[0]))]
    kinds = (_kind(r.lat_a[0], r.psi_a[0], polygon.size),
             _kind(r.lat_b[0], r.psi_b[0], polygon.size))
    return pts, kinds, (float(r.top[0]), float(r.bottom[0]))


