"""The parallel jaw as a gripper (:class:`ParallelJaw`) and its plans: the largest
boxes of holding poses, proved and grown (:func:`jaw_plans`, :class:`JawPlan`)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ...core import budget
from ...core._checks import FloatArray, check_int
from ...core._json import json_ready
from ...core.budget import PlanList
from ...core.tolerances import CONTACT_TOL, RANK_TOL, TOL
from ...model.distinct import (
    DEFAULT_DISTINCT,
    _interval_overlap,
    box_images,
    distinct_boxes,
    grip_symmetries,
)
from ...model.polygon import Polygon
from ...model.regions import DEFAULT_MARGIN_DEG
from ..base import DEFAULT_MU, register
from . import _kernels
from ._certify import (
    certify_box,
)
from ._poses import (
    CERTIFY_BOXES,
    CERTIFY_SHRINKS,
    CHECK_DENSITY,
    OFFSET_STEPS,
    POSE_BATCH,
    THETA_STEP_DEG,
    JawParameters,
    _check_jaw_args,
    _grip_edges,
    _pose_args,
    insertion_point,
    jaw_poses,
)
from ._slices import (
    holds_across,
    near_intervals,
)


@dataclass(frozen=True)
class ParallelJaw(JawParameters):
    """A parallel-jaw gripper: its stroke ``(min_opening, max_opening)``, the width of
    its flat pads and their friction coefficient ``mu`` (lengths in the part's units).

    >>> ParallelJaw(stroke=(10, 50), pad_width=12, mu=0.4).stroke
    (10.0, 50.0)
    """

    name: ClassVar[str] = "jaw"
    #: ``distinct=`` when none is given: the boxes are distinct
    #: alternatives, mirror images and neighbouring slices of one contact configuration
    #: merged (:meth:`distinct_plans`); ``distinct=0`` gives every box, as ranked
    default_distinct: ClassVar[float] = DEFAULT_DISTINCT

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
        return jaw_plans(polygon, self, top=options.top, margin=options.margin,
                         certify=self.certify)

    def check_part(self, polygon: Polygon, options: Any) -> None:
        """Nothing to refuse before the search."""

    def parameters(self, options: Any) -> dict[str, Any]:
        return {"gripper": "parallel_jaw", "stroke": list(self.stroke),
                "pad_width": self.pad_width, "mu": self.mu, "top": options.top,
                "margin_deg": options.margin, "certify": self.certify}

    def no_grasp_reason(self, margin: float) -> str:
        return (f"no pose of the jaw holds the part (stroke {self.stroke[0]:g} to "
                f"{self.stroke[1]:g}, pads {self.pad_width:g} wide, mu = {self.mu:g}, "
                f"margin {margin:g} degrees)")

    @property
    def title(self) -> str:
        return "parallel jaw"

    # on a solid: flat pads on opposite parallel facets (fcgrasp.grippers.solids)
    solid_title: ClassVar[str] = "a parallel jaw"

    def solid_plans(self, solid: Any, options: Any, fraction: float) -> PlanList:
        """The regions of closing axes on pairs of opposite parallel facets
        (:func:`fcgrasp.spatial.jaw.solid_jaw_plans`)."""
        from ...spatial.alternatives import top_distinct
        from ...spatial.jaw import solid_jaw_plans

        return top_distinct(lambda n: solid_jaw_plans(solid, self.stroke, self.pad_width,
                                                      self.mu, top=n, margin=options.margin),
                            options.top, fraction)

    def solid_parameters(self, options: Any) -> dict[str, Any]:
        return {"gripper": "jaw", "contact_type": "jaw", "stroke": list(self.stroke),
                "pad": self.pad_width, "mu": self.mu, "top": options.top,
                "margin_deg": options.margin}

    def solid_no_grasp_reason(self, margin: float) -> str:
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
    if stroke is None or pad is None:
        missing = "--stroke MIN,MAX" if stroke is None else "--pad WIDTH"
        raise ValueError(f"{missing} is needed: --gripper jaw needs --stroke MIN,MAX and "
                         f"--pad WIDTH (in the part's units)")
    mu = DEFAULT_MU if options.get("mu") is None else options["mu"]
    if not (math.isfinite(mu) and mu > 0):
        raise ValueError(f"--mu of a parallel jaw must be a finite number > 0, got {mu:g}")
    return ParallelJaw(stroke=(stroke[0], stroke[1]), pad_width=pad, mu=mu,
                       certify=options.get("certify") is not False)


register("jaw", jaw_from_options)




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
    #: with a load (``plan(..., load=)``): the scale of it every pose of the box carries
    #: (:func:`fcgrasp.grippers.jaw.jaw_payload`, a
    #: :class:`~fcgrasp.model.loads.RegionPayload`); in the JSON as ``payload``
    payload: Any = field(default=None, repr=False, compare=False)

    @property
    def centre(self) -> tuple[float, float]:
        """The box's centre pose ``(theta, offset)``."""
        return (sum(self.theta) / 2, sum(self.offset) / 2)

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


def _box_scores(H: np.ndarray, dth: float, dc: float, radius: float, max_rows: int
                ) -> tuple[float, int, int, int, int]:
    """The largest box of True cells of the pose grid ``H`` (theta rows, cyclic; offset
    columns) by ``min(offset range, theta range * radius)``: ``(score, k0, k1, j0, j1)``
    with inclusive grid indices (``k1`` may pass the last row: it wraps).  By the
    compiled loop (:func:`._kernels.box_scores`) where it runs."""
    found = _kernels.box_scores(H, dth, dc, radius, max_rows) if _kernels.available() \
        else None
    return found if found is not None else _box_scores_numpy(H, dth, dc, radius, max_rows)


def _box_scores_numpy(H: np.ndarray, dth: float, dc: float, radius: float, max_rows: int
                      ) -> tuple[float, int, int, int, int]:
    """:func:`_box_scores` by numpy (the reference): for each first row ``k0``, the rows
    from it are AND-ed cumulatively and the longest run of True of every prefix is read
    off at once (run lengths by cumulative sums)."""
    K, M = H.shape
    best = (-1.0, 0, 0, 0, 0)
    span = np.arange(max_rows)
    for k0 in np.flatnonzero(H.any(axis=1)):
        acc = np.logical_and.accumulate(H[(k0 + span) % K], axis=0)
        alive = acc.any(axis=1)
        rows = int(np.argmin(alive)) if not alive.all() else max_rows
        acc = acc[:rows]
        count = np.cumsum(acc, axis=1)
        last_false = np.maximum.accumulate(np.where(acc, 0, count), axis=1)
        run = count - last_false                     # length of the run ending here
        length = run.max(axis=1)
        score = np.minimum((length - 1) * dc, np.arange(rows) * dth * radius)
        r = int(np.argmax(score))
        if score[r] > best[0]:
            end = int(np.argmax(run[r]))
            best = (float(score[r]), int(k0), int(k0 + r), end - int(length[r]) + 1, end)
    return best


def _kind(lat: FloatArray, psi: FloatArray, size: float) -> str:
    """How a pad touches at one pose: on a pad corner, an edge flat on it, or vertices."""
    real = np.isfinite(lat[:, 0])
    if np.any(np.abs(psi[real]) > 0):
        return "corner"
    return "edge" if np.any(lat[real, 1] - lat[real, 0] > CONTACT_TOL * size) else "vertex"


def _contact_points(polygon: Polygon, theta: float, lat: FloatArray, stop: float
                    ) -> FloatArray:
    u = np.array([np.cos(theta), np.sin(theta)])
    n = np.array([-u[1], u[0]])
    ends = lat[np.isfinite(lat[:, 0])]
    pts = [polygon.centroid + stop * u + x * n for row in ends for x in np.unique(row)]
    return np.array(pts).reshape(-1, 2)




def jaw_plans(polygon: Polygon, jaw: ParallelJaw, top: int = 5,
              margin: float = DEFAULT_MARGIN_DEG, internal: bool = True,
              certify: bool = True) -> list[JawPlan]:
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
    plans = [p for h in holes for p in _grip_plans(polygon, jaw, top, margin, h, certify)]
    plans.sort(key=lambda p: -p.measure)
    return plans[:top]


def _proved(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
            th: tuple[float, float], off: tuple[float, float], dth: float, dc: float
            ) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The box, shrunk by whole grid steps (at most :data:`CERTIFY_SHRINKS`) until
    :func:`certify_box` proves it; None when it cannot."""
    for k in range(CERTIFY_SHRINKS + 1):
        t = (th[0] + k * dth, th[1] - k * dth)
        c = (off[0] + k * dc, off[1] - k * dc)
        if t[1] < t[0] or c[1] < c[0]:
            return None
        boxes = CERTIFY_BOXES if k else CERTIFY_BOXES // 8
        if certify_box(polygon, jaw, t, c, margin, hole, max_boxes=boxes):
            return t, c
    return None


#: A grown box is moved in from the set's boundary by these fractions of a grid step
#: until it is proved (a box on the boundary cannot be: its sub-boxes would have to
#: shrink to nothing there), each try with that many times :data:`CERTIFY_BOXES`
#: sub-boxes (the sub-boxes a proof needs grow as the inverse of the back-off:
#: ``demo:rectangle`` 7,900 at half a step, 15,800 at a quarter, 32,200 at an eighth).
GROW_BACKOFF = ((0.25, 5.0), (0.5, 2.5))


def _reach(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
           thetas: FloatArray, anchor: float, step: float, side: int) -> float | None:
    """How far from ``anchor`` (an offset at which every angle of ``thetas`` holds) the
    exact slices (:func:`~fcgrasp.grippers.jaw.holding_offsets`) hold at every one of
    ``thetas``, towards ``side`` (+1: larger offsets): the nearest end of the slices'
    intervals through ``anchor`` (:func:`._slices.near_intervals`).  Windows of
    ``2 * step`` are added until it is found (None: no interval through the anchor at
    some angle)."""
    tol = CONTACT_TOL * polygon.size
    far = anchor
    reach_max = polygon.radius + jaw.pad_width
    while True:
        near, far = far, far + side * 2 * step
        window = (min(near, far), max(near, far))
        # the interval through the window's end next to the anchor, at each angle
        ends = near_intervals(polygon, jaw, thetas, margin, hole, window, side)
        if np.isnan(ends).any():
            return None if near == anchor else near
        end = float(ends.min() if side > 0 else ends.max())
        if abs(end - far) > tol or abs(far) > reach_max:
            return end


def _holds_across(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
                  thetas: FloatArray, c0: float, c1: float) -> np.ndarray:
    """Whether the exact slice at each angle holds at every offset of ``[c0, c1]``
    (:func:`._slices.holds_across`)."""
    return holds_across(polygon, jaw, thetas, margin, hole, (c0, c1))


def _grown(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
           th: tuple[float, float], off: tuple[float, float], dth: float, dc: float
           ) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """A box found on the grid grown to the exact boundary of the holding set, the
    dimension that limits its measure first: its offset range to the nearest ends of the
    exact slices at :data:`CHECK_DENSITY` angles per grid step across it
    (:func:`~fcgrasp.grippers.jaw.holding_offsets`), and its angle range, with the offset
    range fixed, by bisection (to 1/4096 of a fine step) to the first angle whose slice
    does not hold across it.  None when the slices disagree with the grid."""
    (t0, t1), (c0, c1) = th, off
    radius = polygon.radius
    fine = dth / CHECK_DENSITY

    def offsets(t0: float, t1: float, c0: float, c1: float) -> tuple[float, float] | None:
        lines = np.linspace(t0, t1, max(2, int(round((t1 - t0) / fine)) + 1))
        mid = (c0 + c1) / 2
        lo = _reach(polygon, jaw, margin, hole, lines, min(c0 + dc, mid), dc, -1)
        hi = _reach(polygon, jaw, margin, hole, lines, max(c1 - dc, mid), dc, +1)
        return None if lo is None or hi is None or hi <= lo else (lo, hi)

    def angles(t0: float, t1: float, c0: float, c1: float) -> tuple[float, float]:
        grown = [t0, t1]
        for k, side in ((1, 1), (0, -1)):
            edge = grown[k]
            probes = edge + side * fine * np.arange(1, 2 * CHECK_DENSITY + 1)
            room = np.pi - 2 * dth - (grown[1] - grown[0])   # certify_box: under half a turn
            probes = probes[np.abs(probes - edge) < room]
            ok = _holds_across(polygon, jaw, margin, hole, probes, c0, c1)
            n_ok = int(np.argmin(ok)) if not ok.all() else ok.size
            good = edge + side * fine * n_ok
            if n_ok < probes.size:
                bad = probes[n_ok]
                for _ in range(12):
                    t = (good + bad) / 2
                    if _holds_across(polygon, jaw, margin, hole, np.array([t]), c0, c1)[0]:
                        good = t
                    else:
                        bad = t
            grown[k] = good
        return grown[0], grown[1]

    if (t1 - t0) * radius < c1 - c0:
        t0, t1 = angles(t0, t1, c0, c1)
    found = offsets(t0, t1, c0, c1)
    if found is None:
        return None
    c0, c1 = found
    t0, t1 = angles(t0, t1, c0, c1)
    return (t0, t1), (c0, c1)


def _proved_grown(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
                  th: tuple[float, float], off: tuple[float, float], dth: float, dc: float
                  ) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The grown box (:func:`_grown`) moved in from the boundary by each of
    :data:`GROW_BACKOFF` (fractions of a grid step) until :func:`certify_box` proves it;
    None when it cannot (the grid box is then proved instead)."""
    grown = _grown(polygon, jaw, margin, hole, th, off, dth, dc)
    if grown is None:
        return None
    (t0, t1), (c0, c1) = grown
    for f, boxes in GROW_BACKOFF:
        t = (t0 + f * dth, t1 - f * dth)
        c = (c0 + f * dc, c1 - f * dc)
        if t[1] < t[0] or c[1] < c[0]:
            return None
        if certify_box(polygon, jaw, t, c, margin, hole,
                       max_boxes=int(boxes * CERTIFY_BOXES)):
            return t, c
    return None


#: The raster of exact slices a box is refined on (:func:`_refined`): an angle step whose
#: arc at the part's radius is this fraction of the grid box's measure (at least
#: ``1/REFINE_DENSITY`` of a grid step, at most a quarter of one).
REFINE_STEP, REFINE_DENSITY = 0.002, 8
#: The best boxes of each grip (external, or in each hole) searched on the raster; the
#: rest are grown from the grid (the raster's slices cost most on curved outlines).
REFINE_TOP = 3
#: The grid box is also grown (:func:`_proved_grown`) where the raster's box gains less
#: than this fraction over it, and the larger kept.
GROW_TOO = 0.05
#: The raster is widened while its best run reaches an end, until the run's angle range
#: (as an arc at the part's radius) is this many times its offset range: longer runs add
#: area, not measure.
REFINE_SPAN = 2.0
#: A refined box is moved in from the raster's boundary by these fractions of each
#: side at each end, in turn, until it is proved, each try with that many times
#: :data:`CERTIFY_BOXES` sub-boxes: it keeps at least 99.5 % of its measure, else 99 %,
#: else 98 %.
REFINE_BACKOFF = ((0.0025, 25.0), (0.005, 10.0), (0.01, 5.0))


def _ends(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
          lines: FloatArray, anchor: float, width: float, side: int) -> FloatArray:
    """Per angle of ``lines``, the end towards ``side`` (+1: larger offsets) of the
    exact slice's interval through ``anchor`` (:func:`._slices.near_intervals`, which
    reads each angle's cells from the anchor on and stops where the interval ends: in a
    window of ``width``, then, for the angles whose interval reaches its end, one four
    times wider, up to where no pad touches); NaN where the slice does not hold at
    ``anchor``."""
    tol = CONTACT_TOL * polygon.size
    limit = side * (polygon.radius + jaw.pad_width)        # no pad touches beyond
    out = np.full(lines.size, np.nan)
    todo = np.arange(lines.size)
    near = anchor
    while todo.size and (limit - near) * side > 0:
        far = near + side * width
        if (far - limit) * side >= 0:
            far = limit
        ends = near_intervals(polygon, jaw, lines[todo], margin, hole,
                              (min(near, far), max(near, far)), side)
        done = np.isnan(ends) | (np.abs(ends - far) > tol) | (far == limit)
        # NaN past the first window: the interval ended at the window's near end
        got = np.where(np.isnan(ends), np.nan if near == anchor else near, ends)
        out[todo[done]] = got[done]
        todo = todo[~done]
        near, width = far, 4 * width
    return out


def _best_run(lines: FloatArray, lo: FloatArray, hi: FloatArray, radius: float,
              max_span: float, pad: float = 0.0
              ) -> tuple[float, int, int, float, float] | None:
    """The box of largest measure whose angles are a run ``lines[i .. j]`` and whose
    offsets the run's intervals ``[lo, hi]`` (NaN: none) all contain, of largest area
    among those of that measure (to :data:`RANK_TOL`): ``(measure, i, j, c0, c1)``,
    or None; its angle range under ``max_span``.  ``pad``: each run's angle range
    counted that much longer."""
    best: tuple[float, float, int, int, float, float] | None = None
    held = ~np.isnan(lo) & ~np.isnan(hi)
    for i in np.flatnonzero(held):
        stop = i + (int(np.argmin(held[i:])) if not held[i:].all() else held.size - i)
        c0 = np.maximum.accumulate(lo[i:stop])
        c1 = np.minimum.accumulate(hi[i:stop])
        span = lines[i:stop] - lines[i]
        score = np.where(span < max_span, np.minimum(c1 - c0, (span + pad) * radius), -1.0)
        top = float(score.max())
        if top <= 0 or (best is not None and top < best[0] * (1 - RANK_TOL)):
            continue
        area = np.where(score >= top * (1 - RANK_TOL), (c1 - c0) * span, -1.0)
        r = int(np.argmax(area))
        if best is None or top > best[0] * (1 + RANK_TOL) or area[r] > best[1]:
            best = (top, float(area[r]), int(i), int(i + r), float(c0[r]), float(c1[r]))
    return None if best is None else (best[0], best[2], best[3], best[4], best[5])


def _clip(lines: FloatArray, lo: FloatArray, hi: FloatArray, anchor: float,
          taken: list[tuple[float, float, float, float]]) -> None:
    """Cut the intervals ``[lo, hi]`` through ``anchor`` at each angle of ``lines`` (in
    place) where a box of ``taken`` (``(t0, t1, c0, c1)``, angles cyclic) covers that
    angle: to the gap beside it that holds the anchor, NaN when it holds the anchor."""
    for t0, t1, c0, c1 in taken:
        inside = np.mod(lines - t0, 2 * np.pi) <= t1 - t0
        inside &= (lo < c1) & (hi > c0)
        if anchor <= c0:
            hi[inside] = np.minimum(hi[inside], c0)
        elif anchor >= c1:
            lo[inside] = np.maximum(lo[inside], c1)
        else:
            lo[inside] = hi[inside] = np.nan


def _through(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
             lines: FloatArray, anchor: float, width: float,
             taken: list[tuple[float, float, float, float]]
             ) -> tuple[FloatArray, FloatArray]:
    """The exact slices' intervals ``(lo, hi)`` through ``anchor`` at the angles
    ``lines`` (:func:`_ends`, its first windows ``width``), less the boxes ``taken``."""
    lo = _ends(polygon, jaw, margin, hole, lines, anchor, width, -1)
    hi = _ends(polygon, jaw, margin, hole, lines, anchor, width, +1)
    _clip(lines, lo, hi, anchor, taken)
    return lo, hi


def _refined(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
             th: tuple[float, float], off: tuple[float, float], dth: float, dc: float,
             taken: list[tuple[float, float, float, float]], floor: float = 0.0
             ) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The largest box by the measure near a grid box, on a raster of the exact slices
    (:func:`~fcgrasp.grippers.jaw.holding_offsets`, their intervals through an anchor
    offset; :func:`_best_run`), apart from the boxes ``taken`` (the plans found so far
    and their images): first every grid step from two grid steps before the box to two
    after (its middle offset the anchor), widened, twice as far each time, while the
    best run reaches an end and is shorter than :data:`REFINE_SPAN` times its offset
    range; then, within a grid step of that run's ends, every :data:`REFINE_STEP` of its
    measure (as an arc at the part's radius; at least ``1/REFINE_DENSITY`` of a grid
    step).  Every angle and offset of the box returned holds on the raster, not between
    (:func:`_proved_refined` proves it).  None when no run holds, or when no run could
    measure more than ``floor`` (a finer run contains a run of the grid's angles at most
    two steps shorter)."""
    radius = polygon.radius
    coarse = dth
    max_span = np.pi - 2 * dth                      # certify_box: under half a turn
    anchor = (off[0] + off[1]) / 2
    lines = np.arange(th[0] - 2 * dth, th[1] + 2 * dth + coarse / 2, coarse)
    # (the first windows reach a little past the grid box's offsets)
    width = (off[1] - off[0]) / 2 + 2 * dc
    lo, hi = _through(polygon, jaw, margin, hole, lines, anchor, width, taken)
    grow = 8
    while True:
        run = _best_run(lines, lo, hi, radius, max_span)
        if run is None:
            return None
        m, i, j, c0, c1 = run
        ahead = coarse * np.arange(1.0, grow + 1)
        new: list[FloatArray] = [lines[0] - ahead[::-1] if i == 0 else ahead[:0],
                                 lines[-1] + ahead if j == lines.size - 1 else ahead[:0]]
        if not (new[0].size or new[1].size) or lines[-1] - lines[0] >= max_span \
                or (lines[j] - lines[i]) * radius >= REFINE_SPAN * (c1 - c0):
            break
        parts = [_through(polygon, jaw, margin, hole, t, anchor, width, taken) for t in new]
        lines = np.concatenate([new[0], lines, new[1]])
        lo = np.concatenate([parts[0][0], lo, parts[1][0]])
        hi = np.concatenate([parts[0][1], hi, parts[1][1]])
        grow *= 2
    box = (float(lines[i]), float(lines[j])), (c0, c1)
    # a finer run contains a run of these angles at most two steps shorter, whose
    # intervals contain its own
    bound = _best_run(lines, lo, hi, radius, max_span, 2 * coarse)
    if max(coarse * radius, bound[0] if bound is not None else 0.0) <= floor:
        return None
    step = min(max(REFINE_STEP * m / radius, dth / REFINE_DENSITY), coarse)
    if step > coarse / 2:
        return box
    # finer near the run's two ends (the coarse angles between are kept: the run's
    # intervals through the anchor are the same ones)
    a, b = max(i - 1, 0), min(j + 1, lines.size - 1)
    ends = [np.arange(lines[a], lines[min(a + 2, b)], step),
            np.arange(lines[max(b - 2, a + 2)], lines[b] + step / 2, step)]
    keep = np.arange(min(a + 2, b), max(b - 2, a + 2))
    got = [_through(polygon, jaw, margin, hole, t, anchor, (c1 - c0) / 2 + 2 * dc, taken)
           for t in ends]
    fine = np.concatenate([ends[0], lines[keep], ends[1]])
    run = _best_run(fine, np.concatenate([got[0][0], lo[keep], got[1][0]]),
                    np.concatenate([got[0][1], hi[keep], got[1][1]]), radius, max_span)
    if run is not None and run[0] > m:
        box = (float(fine[run[1]]), float(fine[run[2]])), (run[3], run[4])
    return box


def _clear_of(box: tuple[tuple[float, float], tuple[float, float]],
              taken: list[tuple[float, float, float, float]]) -> bool:
    """Whether ``box`` overlaps none of the boxes ``taken`` by more than
    :data:`~fcgrasp.core.tolerances.TOL` of its area (angles cyclic)."""
    (t0, t1), (c0, c1) = box
    area = (t1 - t0) * (c1 - c0)
    for b0, b1, d0, d1 in taken:
        dc = min(c1, d1) - max(c0, d0)
        if dc > 0 and _interval_overlap(t0, t1, b0, b1, 2 * np.pi) * dc > TOL * area:
            return False
    return True


def _proved_refined(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
                    th: tuple[float, float], off: tuple[float, float], dth: float,
                    dc: float, taken: list[tuple[float, float, float, float]],
                    floor: float = 0.0
                    ) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The refined box (:func:`_refined`) moved in from the raster's boundary by each of
    :data:`REFINE_BACKOFF` (fractions of each side) until :func:`certify_box` proves
    it; where its angle range is longer than its measure needs and no back-off is
    proved, the same with the angle range cut to what the measure needs, around the
    grid box's middle (a pose that fails at one angle, which no raster sees, may lie in
    the rest).  None when neither is proved, or when it would not measure more than
    ``floor``."""
    # (what cannot measure more than the floor once moved in is not refined)
    found = _refined(polygon, jaw, margin, hole, th, off, dth, dc, taken,
                     floor / (1 - 2 * REFINE_BACKOFF[0][0]))
    if found is None:
        return None
    radius = polygon.radius
    (t0, t1), (c0, c1) = found
    tries = [(t0, t1)]
    need = (c1 - c0) / radius
    if t1 - t0 > need * (1 + 2 * REFINE_BACKOFF[-1][0]):
        mid = min(max((th[0] + th[1]) / 2, t0 + need / 2), t1 - need / 2)
        tries.append((mid - need / 2, mid + need / 2))
    for a0, a1 in tries:
        for f, boxes in REFINE_BACKOFF:
            t = (a0 + f * (a1 - a0), a1 - f * (a1 - a0))
            c = (c0 + f * (c1 - c0), c1 - f * (c1 - c0))
            if t[1] <= t[0] or c[1] <= c[0] or _measure(t, c, radius) <= floor:
                break
            if certify_box(polygon, jaw, t, c, margin, hole,
                           max_boxes=int(boxes * CERTIFY_BOXES)):
                return t, c
    return None


def _clear_images(H: np.ndarray, theta: FloatArray, offset: FloatArray,
                  symmetries: list[tuple[str, float]], dth: float, offsets: FloatArray,
                  start: float = 0.0) -> None:
    """Clear from the pose grid ``H`` (rows every ``dth`` from angle ``start``, columns at
    ``offsets``) the poses inside the images of the box ``theta x offset`` under the
    part's symmetries (:func:`fcgrasp.model.distinct.part_symmetries`): a box found
    there would hold the part the same way, mirrored or turned."""
    K = H.shape[0]
    eps = TOL * float(offsets[-1] - offsets[0])      # rounding of the images' ends
    for t0, t1, c0, c1 in box_images((float(theta[0]), float(theta[1])),
                                      (float(offset[0]), float(offset[1])), symmetries):
        k_lo = int(math.ceil((t0 - start - TOL) / dth))
        k_hi = int(math.floor((t1 - start + TOL) / dth))
        j_lo = int(np.searchsorted(offsets, c0 - eps, side="left"))
        j_hi = int(np.searchsorted(offsets, c1 + eps, side="right"))
        if k_hi >= k_lo and j_hi > j_lo:
            H[np.arange(k_lo, k_hi + 1) % K, j_lo:j_hi] = False


def _measure(theta: tuple[float, float], offset: tuple[float, float], radius: float
             ) -> float:
    """The ranking measure of a box: ``min(c1 - c0, (t1 - t0) * radius)``."""
    return min(offset[1] - offset[0], (theta[1] - theta[0]) * radius)


def grid_anchor(polygon: Polygon) -> float:
    """The closing angle the pose grid starts from: three quarters of a grid step
    (:data:`THETA_STEP_DEG`) past the direction of the outward normal of the part's
    longest edge (the first of those within a relative 1e-9 of it, in the input order),
    so that the grid turns, moves and scales with the part, and the boxes found on a
    rotated, moved, scaled or renumbered part are its images.  (Edges tied by a
    symmetry of the part give grids that are images of each other.)  The offset keeps
    the rows off the pads' exact alignment with that edge, a kink of the holding set
    where a row of grid poses is a poor start for a box (on ``demo:triangle`` the top
    box came out 4 % smaller there); at three quarters every built-in part's top box
    is within 1 % of the exact set's largest (``tests/test_jaw.py``).

    >>> sq = Polygon([[0, 0], [10, 0], [10, 3], [0, 3]])
    >>> round(float(np.degrees(grid_anchor(sq))), 6)       # the long side's normal, on
    -89.625
    """
    L = np.where(polygon.usable, polygon.lengths, -np.inf)
    k = int(np.flatnonzero(L >= L.max() * (1 - TOL))[0])
    n = polygon.normals[k]
    return float(np.arctan2(n[1], n[0])) + 0.75 * np.radians(THETA_STEP_DEG)


def _grid(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None
          ) -> tuple[FloatArray, FloatArray, np.ndarray]:
    """The pose grid a grip's boxes are sought on: its closing angles (every
    :data:`THETA_STEP_DEG`, from the part's own direction, :func:`grid_anchor`), its
    offsets (:data:`OFFSET_STEPS` across the part and a pad) and whether each pose
    holds."""
    K = int(round(360 / THETA_STEP_DEG))
    thetas = grid_anchor(polygon) + np.arange(K, dtype=float) * (2 * np.pi / K)
    reach = polygon.radius + jaw.pad_width / 2
    offsets = np.linspace(-reach, reach, OFFSET_STEPS)
    return thetas, offsets, _pose_grid(polygon, jaw, margin, hole, thetas, offsets)


def _grip_plans(polygon: Polygon, jaw: ParallelJaw, top: int, margin: float,
                hole: int | None, certify: bool = True) -> list[JawPlan]:
    """The best boxes of one grip (external, or internal in ``hole``)."""
    radius = polygon.radius
    thetas, offsets, H = _grid(polygon, jaw, margin, hole)
    K, M = thetas.size, offsets.size
    dth, dc = 2 * np.pi / K, offsets[1] - offsets[0]
    # inside a hole, the symmetries that keep the hole and the point the jaws go in at
    symmetries = grip_symmetries(polygon, None if hole is None
                                 else insertion_point(polygon, hole))
    plans: list[JawPlan] = []
    taken: list[tuple[float, float, float, float]] = []    # the plans' boxes and images
    while len(plans) < top:
        if plans and budget.exhausted():    # the time budget: the boxes proved so far
            budget.cut_short()
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
            better = None if len(plans) >= REFINE_TOP else _proved_refined(
                polygon, jaw, margin, hole, box[0], box[1], dth, dc, taken, floor)
            if better is None or _measure(*better, radius) < floor * (1 + GROW_TOO):
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
        plans.append(_plan_of(polygon, jaw, margin, hole, box, certify))
    return plans


def _plan_of(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
             box: Any, certified: bool) -> JawPlan:
    """The :class:`JawPlan` of a checked box (:func:`_checked_box`: its ranges, opening
    and features), with the contacts at its centre pose."""
    (t0, t1), (c0, c1), opening, features = box
    tc, ccen = (t0 + t1) / 2, (c0 + c1) / 2
    r = jaw_poses(polygon, jaw, [tc], [ccen], margin, hole)
    pts = [_contact_points(polygon, tc, r.lat_a[0], float(r.top[0])),
           _contact_points(polygon, tc, r.lat_b[0], float(r.bottom[0]))]
    kinds = (_kind(r.lat_a[0], r.psi_a[0], polygon.size),
             _kind(r.lat_b[0], r.psi_b[0], polygon.size))
    radius = polygon.radius
    return JawPlan((float(t0), float(t1)), (float(c0), float(c1)), opening, pts, kinds,
                   (float(r.top[0]), float(r.bottom[0])), _measure((t0, t1), (c0, c1), radius),
                   jaw, polygon.centroid.copy(), radius,
                   "external" if hole is None else "internal", hole, certified,
                   None if hole is None else insertion_point(polygon, hole), features)


#: The weights :func:`jaw_pareto` gives the angle side against the offset side: for
#: each, the box of largest ``min(c1 - c0, w radius (t1 - t0))``.
PARETO_WEIGHTS = tuple(2.0 ** k for k in range(-3, 4))


def jaw_pareto(polygon: Polygon, jaw: ParallelJaw, margin: float = DEFAULT_MARGIN_DEG,
               hole: int | None = None, weights: Any = PARETO_WEIGHTS) -> list[JawPlan]:
    """Boxes that trade the closing angle's range against the offset's (a
    Pareto list, for a user who cares about one side): for each weight ``w`` of
    ``weights``, the box of the pose grid with the largest ``min(c1 - c0, w R (t1 -
    t0))`` (``R`` the part's radius), checked on the fine grid and proved by
    :func:`certify_box` (shrunk by grid steps; with ``jaw.certify``), then those no
    other beats on both sides; by angle range, largest first.  A grip on the outline,
    or (``hole``) inside that hole.  The boxes are the grid's, proved, not grown to the
    exact set as :func:`jaw_plans`' are; each box's ``measure`` is the usual one.

    >>> from fcgrasp.io.parts import demo_part
    >>> jaw = ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
    >>> front = jaw_pareto(demo_part("rectangle"), jaw)
    >>> sides = [(round(float(np.degrees(p.theta[1] - p.theta[0])), 1),
    ...           round(p.offset[1] - p.offset[0], 1)) for p in front]
    >>> sides[0][0] > sides[-1][0] and sides[0][1] < sides[-1][1]  # one side for the other
    True
    """
    margin = _check_jaw_args(polygon, jaw, margin)
    ws = np.atleast_1d(np.asarray(weights, float)).ravel()
    if ws.size == 0 or not np.all(np.isfinite(ws) & (ws > 0)):
        raise ValueError(f"weights must be positive numbers, got {weights!r}")
    radius = polygon.radius
    thetas, offsets, H = _grid(polygon, jaw, margin, hole)
    K = thetas.size
    dth, dc = 2 * np.pi / K, offsets[1] - offsets[0]
    found: list[JawPlan] = []
    for w in ws:
        score, k0, k1, j0, j1 = _box_scores(H.copy(), dth, dc, radius * float(w), K // 2)
        if score <= 0:
            continue
        box = _checked_box(polygon, jaw, margin, hole,
                           thetas[k0] + np.array([0, k1 - k0]) * dth, offsets[[j0, j1]],
                           dth, dc)
        if box is None:
            continue
        if jaw.certify:
            proved = _proved(polygon, jaw, margin, hole, box[0], box[1], dth, dc)
            if proved is None:
                continue
            box = _checked_box(polygon, jaw, margin, hole, np.array(proved[0]),
                               np.array(proved[1]), dth, dc)
            if box is None:
                continue
        found.append(_plan_of(polygon, jaw, margin, hole, box, jaw.certify))

    def sides(p: JawPlan) -> tuple[float, float]:
        return p.theta[1] - p.theta[0], p.offset[1] - p.offset[0]

    front: list[JawPlan] = []
    for p in sorted(found, key=lambda q: (-sides(q)[0], -sides(q)[1])):
        a, c = sides(p)
        # beaten (or matched: a mirror, the same box again) by one kept before
        if not any(sides(q)[0] >= a - TOL and sides(q)[1] >= c - TOL * polygon.size
                   for q in front):
            front.append(p)
    return front


#: A part with more edges than this evaluates the pose grid in tiles (each tile's poses
#: meet only the edges near its strips); fewer, in large batches.
TILE_AFTER_EDGES = 64
#: Grid rows and columns of a tile.
TILE = (16, 20)


def _pose_grid(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
               thetas: np.ndarray, offsets: np.ndarray) -> np.ndarray:
    """Whether each pose of the grid ``thetas x offsets`` holds (K, M): by the compiled
    grid loop (:func:`._kernels.grid`, each pose reading the edges near its strip) where
    it runs, else by :func:`_pose_grid_batches`, the reference."""
    H = _compiled_grid(polygon, jaw, margin, hole, thetas, offsets)
    return H if H is not None else _pose_grid_batches(polygon, jaw, margin, hole, thetas,
                                                      offsets)


def _compiled_grid(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
                   thetas: FloatArray, offsets: FloatArray, details: bool = False) -> Any:
    """:func:`._kernels.grid` on the grip's edges (with ``details``, the edges each pad
    touches as the part's edges, -1 for none, as :func:`jaw_poses` gives them); None
    where the compiled loop does not run."""
    if not _kernels.available():
        return None
    ring = _grip_edges(polygon, hole)
    got = _kernels.grid(thetas, offsets, *_pose_args(polygon, jaw, margin, hole, ring),
                        details=details)
    if got is None or not details:
        return got
    H, opening, e_a, e_b = got
    ids = np.flatnonzero(ring)
    return H, opening, np.where(e_a >= 0, ids[e_a], -1), np.where(e_b >= 0, ids[e_b], -1)


def _pose_grid_batches(polygon: Polygon, jaw: ParallelJaw, margin: float,
                       hole: int | None, thetas: np.ndarray, offsets: np.ndarray
                       ) -> np.ndarray:
    """:func:`_pose_grid` by :func:`jaw_poses` in batches (tiles of the grid, each with
    the edges near its strips, on a part of many edges)."""
    K, M = thetas.size, offsets.size
    if polygon.n_edges <= TILE_AFTER_EDGES:
        tt, cc = np.meshgrid(thetas, offsets, indexing="ij")
        return np.concatenate([
            jaw_poses(polygon, jaw, tt.ravel()[i:i + POSE_BATCH], cc.ravel()[i:i + POSE_BATCH],
                      margin, hole).holds
            for i in range(0, tt.size, POSE_BATCH)]).reshape(K, M)
    H = np.zeros((K, M), dtype=bool)
    for k in range(0, K, TILE[0]):
        for j in range(0, M, TILE[1]):
            tt, cc = np.meshgrid(thetas[k:k + TILE[0]], offsets[j:j + TILE[1]], indexing="ij")
            H[k:k + TILE[0], j:j + TILE[1]] = jaw_poses(
                polygon, jaw, tt.ravel(), cc.ravel(), margin, hole).holds.reshape(tt.shape)
    return H


def _checked_box(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
                 th: FloatArray, off: FloatArray, dth: float, dc: float,
                 compiled_grid: bool = True
                 ) -> tuple[tuple[float, float], tuple[float, float],
                            tuple[float, float], tuple[list[int], list[int]]] | None:
    """Shrink a box by grid steps until every pose of a grid :data:`CHECK_DENSITY`
    times finer holds; returns ``(theta range, offset range, opening range, the edges
    each pad touches at those poses)`` or None.  The fine grid is evaluated by the
    compiled grid loop (:func:`._kernels.grid`) where it runs and ``compiled_grid``,
    else by :func:`jaw_poses` in batches (the reference: the same answer)."""
    (t0, t1), (c0, c1) = th, off
    for _ in range(4):
        if t1 < t0 or c1 < c0:
            return None
        nt = max(2, int(round((t1 - t0) / dth)) * CHECK_DENSITY + 1)
        nc = max(2, int(round((c1 - c0) / dc)) * CHECK_DENSITY + 1)
        held = _fine_grid(polygon, jaw, margin, hole, np.linspace(t0, t1, nt),
                          np.linspace(c0, c1, nc), compiled_grid)
        if held is not None:
            return ((t0, t1), (c0, c1), *held)
        t0, t1, c0, c1 = t0 + dth, t1 - dth, c0 + dc, c1 - dc
    return None


def _fine_grid(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
               thetas: FloatArray, offsets: FloatArray, compiled: bool = True
               ) -> tuple[tuple[float, float], tuple[list[int], list[int]]] | None:
    """The opening range over every pose of the grid ``thetas x offsets`` and the edges
    each pad touches there, or None where some pose does not hold: by the compiled grid
    loop (:func:`_compiled_grid`) where it runs and ``compiled``, else by
    :func:`jaw_poses` in batches, stopping at the first batch that fails (the
    reference)."""
    got = _compiled_grid(polygon, jaw, margin, hole, thetas, offsets, details=True) \
        if compiled else None
    if got is not None:
        holds, opening, e_a, e_b = got
        if not holds.all():
            return None
        return ((float(opening.min()), float(opening.max())),
                (sorted(set(e_a[e_a >= 0].tolist())), sorted(set(e_b[e_b >= 0].tolist()))))
    grid = np.meshgrid(thetas, offsets, indexing="ij")
    tt, cc = grid[0].ravel(), grid[1].ravel()
    lo, hi = np.inf, -np.inf
    edges: tuple[set[int], set[int]] = (set(), set())
    for i in range(0, tt.size, POSE_BATCH):
        r = jaw_poses(polygon, jaw, tt[i:i + POSE_BATCH], cc[i:i + POSE_BATCH], margin, hole)
        if not np.all(r.holds):
            return None
        lo, hi = min(lo, float(r.opening.min())), max(hi, float(r.opening.max()))
        edges[0].update(r.edge_a[r.edge_a >= 0].tolist())
        edges[1].update(r.edge_b[r.edge_b >= 0].tolist())
    return (lo, hi), (sorted(edges[0]), sorted(edges[1]))
