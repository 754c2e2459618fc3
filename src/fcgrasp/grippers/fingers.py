"""Point fingers: the grippers of sections 6-8, each one object behind
:class:`~fcgrasp.grippers.base.Gripper`.

- :class:`TwoFingers` with friction (theorem 6.4, algorithm 7.1; regions along the
  boundary by :mod:`fcgrasp.model.stretches`, exact);
- :class:`ThreeFingers` with friction (:mod:`fcgrasp.grippers.three_fingers`: concurrent
  grasps in non-marginal equilibrium, a safe lower bound of the optimum);
- :class:`ThreeFrictionless` fingers holding the part against gravity (gravity counted as
  a frictionless contact at the centroid, section 3.1);
- :class:`FourFingers`, frictionless (theorem 7.1, algorithm 6.1).

Each knows its parameters (checked when built), its search (candidates -> solve -> rank
of :mod:`fcgrasp.pipeline`, or its own) and how its plans are described.
:func:`point_fingers` is the short form ``fingers=, mu=, gravity=`` of
:func:`fcgrasp.plan`; :func:`fingers_from_options` builds one from a plan request.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any, ClassVar

import numpy as np

from ..core._checks import check_margin, check_mu_scalar, check_tol
from ..core.budget import PlanList
from ..core.tolerances import SOLVER_TOL
from ..model.distinct import DEFAULT_DISTINCT
from ..model.frictionless_stretches import frictionless_stretch_regions
from ..model.graspsets import Vertex
from ..model.hand import Hand
from ..model.hands import FingerTips
from ..model.one_pair import pair_core
from ..model.plans import GraspPlan
from ..model.polygon import Polygon
from ..model.regions import DEFAULT_MARGIN_DEG
from ..model.stretches import stretch_regions
from ..pipeline import (
    PlanSpec,
    check_search,
    plan_spec,
    search,
)
from ._boundary import (
    boundary_plans,
    distinct_boundary_plans,
    distinct_single_edge_plans,
    frictionless_plan,
    grown_plans,
    stretch_plan,
)
from .base import DEFAULT_MU, SearchOptions, register
from .three_fingers import distinct_three_finger_plans, three_finger_plans

__all__ = ["TwoFingers", "ThreeFingers", "ThreeFrictionless", "FourFingers",
           "point_fingers", "fingers_from_options", "regions_on"]


@dataclass(frozen=True)
class _PointFingers:
    """Point fingers: their count, friction and gravity (validated by
    :func:`fcgrasp.pipeline.plan_spec`), an optional :class:`~fcgrasp.Hand` and whether
    regions run along the boundary."""

    fingers: ClassVar[int]
    name: ClassVar[str]
    #: why a part has no plan (``{mu}``: the friction coefficient)
    NONE: ClassVar[str]
    mu: float = 0.0
    gravity: tuple[float, float] | None = None
    hand: Hand | None = None
    along_boundary: bool = True
    #: picked from above by fingers on finger bodies (:mod:`._tips_pick`): the fingers
    #: and the scene (``hand`` then has the tip's radius)
    tips: FingerTips | None = None
    scene: Any = None
    #: ``distinct=None``: the top plans are distinct alternatives (a curved
    #: outline's ranked list is one grasp shifted along it)
    default_distinct: ClassVar[float] = DEFAULT_DISTINCT
    #: on a solid (the grippers with ``solid_plans``): the contact model and why none holds
    solid_contact: ClassVar[str] = "friction"
    SOLID_NONE: ClassVar[str] = "no facets hold the fingers"
    #: the plan request's options a solid's plans take (the others are refused there)
    solid_options: ClassVar[tuple[str, ...]] = ("mu", "margin", "top", "distinct",
                                                "time_limit", "max_memory")

    def __post_init__(self) -> None:
        spec = plan_spec(fingers=self.fingers, mu=self.mu, gravity=self.gravity,
                         hand=self.hand, along_boundary=self.along_boundary)
        object.__setattr__(self, "mu", spec.mu)
        object.__setattr__(self, "gravity", spec.gravity)

    def spec(self, options: SearchOptions) -> PlanSpec:
        """The search's :class:`~fcgrasp.pipeline.PlanSpec` for these options."""
        return plan_spec(fingers=self.fingers, mu=self.mu, top=options.top,
                         rank_by=options.rank_by, hand=self.hand, margin=options.margin,
                         gravity=self.gravity, disturbance=options.disturbance,
                         tol=options.tol, max_memory=options.max_memory,
                         along_boundary=self.along_boundary)

    def check_part(self, polygon: Polygon, options: SearchOptions) -> Any:
        """Refuse at once what cannot be planned: a hand that reaches no edge, a search
        that cannot fit its memory (:class:`~fcgrasp.errors.SearchTooLarge`); the search's
        :class:`~fcgrasp.pipeline.SearchSize` otherwise."""
        if self.hand is not None and not any(self.hand.feasible_intervals(polygon)):
            ws = self.hand.workspace
            where = f"workspace {tuple(float(v) for v in ws)}" if ws is not None else \
                f"finger radius {self.hand.finger_radius:g}"
            raise ValueError(f"the hand cannot touch the part: no edge is reachable with "
                             f"the {where}")
        return check_search(polygon, self.spec(options))

    def plan(self, polygon: Polygon, options: SearchOptions) -> list[GraspPlan]:
        spec = self.spec(options)
        check_search(polygon, spec)
        return self._picked(self._search(polygon, spec, options))

    def _picked(self, plans: Any) -> Any:
        """``plans`` with each one's pick from above, where the fingers have bodies
        (:func:`~fcgrasp.grippers._tips_pick.tips_pick`)."""
        if self.tips is None or plans is None:
            return plans
        from ._tips_pick import tips_pick, tips_reach

        reach = tips_reach(self.tips, self.scene)
        assert not isinstance(reach, str)          # refused when the gripper was made
        for p in plans:
            p.pick = tips_pick(p, self.tips, self.scene, *reach)
        return plans

    def _search(self, polygon: Polygon, spec: PlanSpec,
                options: SearchOptions) -> list[GraspPlan]:
        if spec.grows:
            return grown_plans(polygon, spec, options.progress, map=options.map)
        return search(polygon, spec, progress=options.progress, map=options.map)

    def distinct_search(self, polygon: Polygon, options: SearchOptions, fraction: float
                        ) -> list[GraspPlan] | None:
        """The ``top`` distinct alternatives found by rounds of the single-edge search
        that leave out each kept plan's copies
        (:func:`~fcgrasp.grippers._boundary.distinct_single_edge_plans`), or None where
        the ranked list is suppressed as it comes."""
        spec = self.spec(options)
        check_search(polygon, spec)
        return self._picked(distinct_single_edge_plans(polygon, spec, fraction,
                                                       options.progress, options.map))

    def search_edges(self, polygon: Polygon, spec: PlanSpec,
                     edges: list[int]) -> list[GraspPlan]:
        """The single-edge search restricted to these edges (independent regions)."""
        return search(polygon, spec, edges=edges)

    def parameters(self, options: SearchOptions) -> dict[str, Any]:
        ws = None if self.hand is None or self.hand.workspace is None else \
            [float(v) for v in self.hand.workspace]
        return {"fingers": self.fingers, "mu": self.mu, "top": options.top,
                "rank_by": options.rank_by, "margin_deg": options.margin,
                "along_boundary": self.along_boundary and self.hand is None,
                "gravity": None if self.gravity is None else list(self.gravity),
                "workspace": ws,
                "finger_radius": 0.0 if self.hand is None else self.hand.finger_radius,
                "disturbance": {"translation": options.disturbance[0],
                                "rotation_deg": options.disturbance[1]},
                **({"hand": self.tips.to_dict(), "scene": self.scene.to_dict()}
                   if self.tips is not None else {})}

    def no_grasp_reason(self, margin: float) -> str:
        extra = f" with a margin of {margin:g} degrees"
        if self.hand is not None:
            extra += " within the hand's reach"
        return self.NONE.format(mu=self.mu) + extra

    @property
    def title(self) -> str:
        return f"{self.fingers} fingers"

    # the grippers that plan solids (those with ``solid_plans``) share these
    def solid_parameters(self, options: SearchOptions) -> dict[str, Any]:
        return {"fingers": self.fingers, "contact_type": self.solid_contact, "mu": self.mu,
                "top": options.top, "margin_deg": options.margin}

    def solid_no_grasp_reason(self, margin: float) -> str:
        return f"{self.SOLID_NONE} with mu {self.mu:g} and a margin of {margin:g} degrees"


@dataclass(frozen=True)
class TwoFingers(_PointFingers):
    """Two fingers with friction ``mu`` (theorem 6.4, algorithm 7.1)."""

    fingers: ClassVar[int] = 2
    name: ClassVar[str] = "two_fingers"
    NONE: ClassVar[str] = "no pair of edges admits two fingers with mu = {mu:g}"
    #: ``distinct=`` along the boundary reads at most this many times ``top`` plans
    #: (:func:`~fcgrasp.grippers._boundary.distinct_boundary_plans`): on a smooth
    #: outline some copies cannot be left out before they are read.
    distinct_depth: ClassVar[int] = 128

    def _search(self, polygon: Polygon, spec: PlanSpec,
                options: SearchOptions) -> list[GraspPlan]:
        if not spec.stretches:
            return super()._search(polygon, spec, options)
        plans = boundary_plans(polygon, spec)
        if options.progress is not None:
            options.progress(1, 1)
        return plans

    def distinct_search(self, polygon: Polygon, options: SearchOptions, fraction: float
                        ) -> list[GraspPlan] | None:
        """The ``top`` distinct alternatives along the boundary found by a search that
        leaves out each kept plan's copies
        (:func:`~fcgrasp.grippers._boundary.distinct_boundary_plans`), or None where the
        ranked list is suppressed as it comes."""
        spec = self.spec(options)
        if not spec.stretches:
            return super().distinct_search(polygon, options, fraction)
        check_search(polygon, spec)
        plans = distinct_boundary_plans(polygon, spec, fraction, options.progress,
                                        self.distinct_depth)
        if plans is None:               # no region crosses a vertex: the single edges'
            return super().distinct_search(polygon, options, fraction)
        return plans

    def no_grasp_reason(self, margin: float) -> str:
        if self.mu == 0:
            return "two fingers need friction: with mu = 0 no two-finger grasp is force closure"
        return super().no_grasp_reason(margin)

    # on a solid: two soft fingers (fcgrasp.grippers.solids)
    solid_title: ClassVar[str] = "two soft fingers"
    solid_contact: ClassVar[str] = "soft"
    SOLID_NONE: ClassVar[str] = "no two facets hold two soft fingers"

    def solid_plans(self, solid: Any, options: SearchOptions, fraction: float) -> PlanList:
        """Two soft fingers with friction ``mu`` on a solid, on facets and across the
        facets of curved surfaces (:func:`fcgrasp.spatial.soft_pair_plans`)."""
        from ..spatial._grown import soft_pair_distinct

        return soft_pair_distinct(solid, self.mu, options.margin, options.top, fraction)



@dataclass(frozen=True)
class ThreeFingers(_PointFingers):
    """Three fingers with friction ``mu`` (:mod:`fcgrasp.grippers.three_fingers`)."""

    fingers: ClassVar[int] = 3
    name: ClassVar[str] = "three_fingers"
    NONE: ClassVar[str] = "no three edges admit three fingers with mu = {mu:g}"
    #: ``distinct=``: the search is asked for at most this many times ``top`` plans
    #: (:data:`fcgrasp.planning.planner.DISTINCT_DEPTH` for the others), and along the
    #: boundary the distinct search reads at most this many times ``top`` two-finger
    #: plans (:func:`~fcgrasp.grippers.three_fingers.distinct_three_finger_plans`): on a
    #: curved outline the two-finger grasps with a free third finger have hundreds of
    #: copies, some of which that search cannot leave out.
    distinct_depth: ClassVar[int] = 128

    def _search(self, polygon: Polygon, spec: PlanSpec,
                options: SearchOptions) -> list[GraspPlan]:
        return three_finger_plans(polygon, spec, progress=options.progress)

    def distinct_search(self, polygon: Polygon, options: SearchOptions, fraction: float
                        ) -> list[GraspPlan] | None:
        """The ``top`` distinct alternatives along the boundary found by a search that
        leaves out each kept plan's copies
        (:func:`~fcgrasp.grippers.three_fingers.distinct_three_finger_plans`), or None
        where the ranked list is suppressed as it comes."""
        spec = self.spec(options)
        check_search(polygon, spec)
        return distinct_three_finger_plans(polygon, spec, fraction, self.distinct_depth,
                                           options.progress)

    def search_edges(self, polygon: Polygon, spec: PlanSpec,
                     edges: list[int]) -> list[GraspPlan]:
        return three_finger_plans(polygon, spec, edges=edges)

    # on a solid: three point fingers with friction (fcgrasp.grippers.solids)
    solid_title: ClassVar[str] = "three fingers with friction"
    SOLID_NONE: ClassVar[str] = "no three facets hold three fingers with friction"

    def solid_plans(self, solid: Any, options: SearchOptions, fraction: float) -> PlanList:
        """Three point fingers with friction ``mu`` on a solid: certified regions on
        three facets or across them (:func:`fcgrasp.spatial.three_finger_plans`); the
        plans' ``details`` say how many triples the last search certified and whether it
        was exhaustive."""
        from ..spatial.alternatives import top_distinct
        from ..spatial.surfaces import three_finger_plans as solid_triples

        searches: list[Any] = []

        def triples(n: int | None) -> list[Any]:
            searches.append(solid_triples(solid, self.mu, top=n, margin=options.margin))
            return list(searches[-1].plans)

        plans = top_distinct(triples, options.top, fraction)
        plans.details = {"certified_triples": searches[-1].certified,
                         "exhaustive": searches[-1].exhaustive}
        return plans



@dataclass(frozen=True)
class ThreeFrictionless(_PointFingers):
    """Three frictionless fingers holding the part against ``gravity`` (a direction)."""

    fingers: ClassVar[int] = 3
    name: ClassVar[str] = "three_frictionless"
    NONE: ClassVar[str] = "no three edges hold the part against gravity with frictionless fingers"
    gravity: tuple[float, float] | None = (0.0, -1.0)


@dataclass(frozen=True)
class FourFingers(_PointFingers):
    """Four frictionless fingers (theorem 7.1), on four edges or on three (two fingers
    on one edge)."""

    fingers: ClassVar[int] = 4
    name: ClassVar[str] = "four_fingers"
    NONE: ClassVar[str] = "no four edges (or three, two fingers on one) admit frictionless fingers"


#: The point-finger gripper of ``(fingers, with gravity)``.
_BY_COUNT: dict[tuple[int, bool], type[_PointFingers]] = {
    (2, False): TwoFingers, (3, False): ThreeFingers, (3, True): ThreeFrictionless,
    (4, False): FourFingers}


def fingers_type(options: Any) -> type[_PointFingers] | None:
    """The class of the point fingers a request's ``fingers`` (2 when not given) and
    ``gravity`` choose, its other options unread (None: no such fingers)."""
    fingers = options.get("fingers")
    return _BY_COUNT.get((2 if fingers is None else fingers, options.get("gravity") is not None))


def point_fingers(fingers: Any = 2, mu: Any = 0.0, gravity: Any = None,
                  hand: Hand | None = None, along_boundary: Any = True) -> _PointFingers:
    """The point-finger gripper of :func:`fcgrasp.plan`'s short form: ``fingers`` 2 or 3
    with friction ``mu``, 3 with ``gravity`` (frictionless), 4 frictionless.  Raises
    ValueError or TypeError naming the argument, also for one the gripper would not use.

    >>> point_fingers(3, mu=0.5).name
    'three_fingers'
    """
    spec = plan_spec(fingers=fingers, mu=mu, gravity=gravity, hand=hand,
                     along_boundary=along_boundary)
    cls = _BY_COUNT[(spec.fingers, spec.gravity is not None)]
    return cls(mu=spec.mu, gravity=spec.gravity, hand=hand, along_boundary=along_boundary)


def regions_on(polygon: Polygon, edges: Any, mu: float = 0.0,
               margin: float = DEFAULT_MARGIN_DEG, hand: Hand | None = None,
               gravity: Any = None, tol: float = SOLVER_TOL) -> GraspPlan | None:
    """Optimal independent regions of point fingers on the given edges or stretches
    (definition 7.1; :func:`fcgrasp.independent_regions` documents the arguments)."""
    if hand is None and gravity is None and type(edges) in (tuple, list) \
            and len(edges) == 2 and type(edges[0]) is int and type(edges[1]) is int \
            and edges[0] != edges[1] and 0 <= min(edges) and max(edges) < polygon.n_edges \
            and polygon.usable[edges[0]] and polygon.usable[edges[1]]:
        # one edge pair of valid indices (the common call, checked here without numpy;
        # anything else takes the checks below): the closed forms on numbers
        return _one_pair(polygon, check_mu_scalar(mu, "mu"), check_margin(margin),
                         check_tol(tol), list(edges))
    if not isinstance(edges, (str, bytes)) and len(edges) in (2, 3, 4) and all(
            np.ndim(e) == 1 for e in edges):
        return _stretch_regions(polygon, edges, mu, margin, hand, gravity)
    idx = _edge_indices(polygon, edges)
    if len(idx) == 2 and hand is None and gravity is None and idx[0] != idx[1]:
        # one edge pair: the closed forms on numbers (the same checks as above)
        spec = plan_spec(fingers=2, mu=mu, top=1, margin=margin, tol=tol)
        return _one_pair(polygon, spec.mu, spec.margin, spec.tol, idx)
    gripper = _gripper_on(idx, mu, hand, gravity)
    spec = plan_spec(fingers=gripper.fingers, mu=gripper.mu, top=1, hand=hand,
                     margin=margin, gravity=gripper.gravity, tol=tol)
    plans = gripper.search_edges(polygon, spec, idx)
    return _in_order(plans[0], idx) if plans else None


def _edge_indices(polygon: Polygon, edges: Any) -> list[int]:
    if isinstance(edges, (str, bytes)) or np.ndim(edges) != 1:
        raise TypeError(f"edges must be a sequence of edge indices, got {edges!r}")
    if any(isinstance(e, Vertex) for e in edges):
        raise ValueError(f"edges holds a Vertex (a soft finger), got {list(edges)!r}: "
                         f"independent regions lie on edges; use grasp_set or grasp_sets "
                         f"for a soft finger at a vertex")
    idx = polygon.check_edges(edges)
    if len(idx) not in (2, 3, 4):
        raise ValueError(f"edges must hold 2, 3 or 4 edge indices, got {len(idx)}")
    return list(idx)


#: Why gravity does not fit a number of edges.
_NO_GRAVITY = {2: "gravity is counted with three frictionless fingers, not two",
               4: "four edges take no gravity (gravity is counted with three frictionless "
                  "fingers)"}


def _gripper_on(idx: list[int], mu: float, hand: Hand | None,
                gravity: Any) -> _PointFingers:
    """The point fingers that ``idx`` (2, 3 or 4 edge indices) are regions of."""
    n, distinct = len(idx), len(set(idx))
    if gravity is not None and n in _NO_GRAVITY:
        raise ValueError(_NO_GRAVITY[n])
    if n == 3 and gravity is None and distinct < 2:
        raise ValueError(f"three fingers with friction need three distinct edges or two "
                         f"with one twice, got {idx}")
    frictionless = n == 4 or gravity is not None
    if frictionless and check_mu_scalar(mu, "mu") != 0:
        raise ValueError(f"regions of {n} frictionless fingers: mu would not be used, "
                         f"got mu={mu}")
    doubled = sum(idx.count(e) == 2 for e in set(idx))
    if n == 4 and distinct != 4 and (doubled != 1 or distinct != 3):
        raise ValueError(f"four fingers need four distinct edges or three with one twice, "
                         f"got {idx}")
    return point_fingers(n, 0.0 if frictionless else mu, gravity, hand)


def _one_pair(polygon: Polygon, mu: float, margin: float, tol: float, idx: list[int]
              ) -> GraspPlan | None:
    """Two fingers with friction on one edge pair of usable edges, without a hand (``mu``,
    ``margin`` and ``tol`` checked): the regions of
    :func:`fcgrasp.model.one_pair.pair_regions` (numbers, not arrays; the same plan as
    :meth:`_PointFingers.search_edges`, which the tests keep as the reference), the
    fingers in the order asked for."""
    i, j = (idx[0], idx[1]) if idx[0] < idx[1] else (idx[1], idx[0])
    rows = polygon.edge_floats
    (ax1, ay1, bx1, by1, nx1, ny1), (ax2, ay2, bx2, by2, nx2, ny2) = rows[i], rows[j]
    mode, l1, l2, lo1, hi1, lo2, hi2 = pair_core(
        ax1, ay1, bx1, by1, ax2, ay2, bx2, by2, math.atan2(-ny1, -nx1),
        math.atan2(-ny2, -nx2), math.atan(mu), math.radians(margin), tol)
    if mode < 0:
        return None
    order = 1 if idx[0] == i else -1    # the fingers in the order asked for
    ends: list[float] = []
    lengths: list[float] = []
    contacts: list[float] = []
    normals: list[float] = []
    for (ax, ay, bx, by, nx, ny), lo, hi, level in ((rows[i], lo1, hi1, l1),
                                                   (rows[j], lo2, hi2, l2))[::order]:
        dx, dy = bx - ax, by - ay
        d = math.hypot(dx, dy)
        ux, uy = dx / d, dy / d
        px, py, qx, qy = ax + lo * ux, ay + lo * uy, ax + hi * ux, ay + hi * uy
        ends += (px, py, qx, qy)
        lengths.append(level)
        contacts += ((px + qx) / 2, (py + qy) / 2)
        normals += (nx, ny)
    # one array, the plan's fields its contiguous pieces
    a = np.array(ends + lengths + contacts + normals)
    return GraspPlan((idx[0], idx[1]), a[:8].reshape(2, 2, 2), a[8:10],
                     a[10:14].reshape(2, 2), a[14:].reshape(2, 2), "friction", mu,
                     ("squeeze", "expand")[mode], margin, None,
                     centroid=polygon.centroid.copy(), radius=polygon.radius,
                     disturbance=_DISTURBANCE)


#: The quality's default disturbance (:class:`~fcgrasp.pipeline.PlanSpec`'s).
_DISTURBANCE = PlanSpec().disturbance


def _in_order(p: GraspPlan, idx: list[int]) -> GraspPlan:
    """The plan with its fingers in the order asked for."""
    order: list[int] = []
    for e in idx:
        order.append(next(k for k, pe in enumerate(p.edges) if pe == e and k not in order))
    o = np.array(order)
    return GraspPlan(tuple(p.edges[k] for k in o), [p.regions[k] for k in o], p.lengths[o],
                     p.contacts[o], p.normals[o], p.contact_type, p.mu, p.mode, p.margin,
                     p.gravity, centroid=p.centroid, radius=p.radius,
                     disturbance=p.disturbance)


def _stretch_regions(polygon: Polygon, stretches: Any, mu: float, margin: float,
                     hand: Hand | None, gravity: Any) -> GraspPlan | None:
    if hand is not None:
        raise ValueError("regions along given stretches are planned without a hand")
    if len(stretches) == 2:
        if gravity is not None:
            raise ValueError("gravity is counted with three frictionless fingers, not two")
        spec = plan_spec(fingers=2, mu=mu, top=1, margin=margin)
        pair = stretch_regions(polygon, stretches, spec.mu, spec.margin)
        return None if pair is None else stretch_plan(polygon, spec, pair)
    n = len(stretches)
    if n == 3 and gravity is None:
        raise ValueError("three stretches are three frictionless fingers with "
                         "gravity=(gx, gy); three fingers with friction are planned on "
                         "single edges (give three edge indices)")
    if check_mu_scalar(mu, "mu") != 0:
        raise ValueError(f"regions of {n} fingers are frictionless: mu must be 0, got {mu}")
    if (n == 3) != (gravity is not None):
        raise ValueError("three stretches need gravity=..., four stretches take no gravity")
    spec = plan_spec(fingers=n, mu=0.0, top=1, margin=margin,
                     gravity=gravity if n == 3 else None)
    r = frictionless_stretch_regions(polygon, stretches, spec.margin,
                                     None if spec.gravity is None else spec.gravity)
    return None if r is None else frictionless_plan(polygon, spec, r)


def _no_jaw_options(options: Mapping[str, Any]) -> None:
    for opt, key in (("--stroke", "stroke"), ("--pad", "pad"), ("--rest", "rest"),
                     ("--rest-orientation", "rest_orientation")):
        if options.get(key) is not None:
            raise ValueError(f"{opt} is an option of --gripper jaw")
    if options.get("hand") is None:
        for opt, key in (("--thickness", "thickness"), ("--table", "table"),
                         ("--in-plane", "in_plane")):
            if options.get(key) is not None and options.get(key) is not False:
                raise ValueError(f"{opt} is for a pick with a hand: give --hand too "
                                 f"(point fingers: --hand tip=R[,length=L])")
    if options.get("certify") is not None:
        raise ValueError(f"{'--certify' if options['certify'] else '--no-certify'} is an "
                         f"option of --gripper jaw")


#: The plate's thickness (millimetres) point fingers pick from above when none is given.
DEFAULT_PLATE_MM = 5.0


#: How far (millimetres) fingers held in the part's plane come in from.
IN_PLANE_APPROACH_MM = 20.0


def _tips(options: Mapping[str, Any]) -> tuple[FingerTips | None, Any]:
    """``--hand tip=R[,length=L]`` of point fingers, in the part's units, and the scene
    they pick from (``--thickness``, ``--table``), or ``(None, None)``."""
    if options.get("hand") is None:
        return None, None
    from ..io.units import MM_PER
    from ..model.hands import tips_from_params
    from ._tips_pick import tips_reach
    from .jaw._pick import plate_scene

    if options.get("finger_radius"):
        raise ValueError("--finger-radius is the hand's tip: give --hand tip=R alone")
    try:
        tips = tips_from_params(str(options["hand"]))
    except ValueError as exc:
        hint = "" if "tip=" in str(options["hand"]) else " (the jaw's hands need --gripper jaw)"
        raise ValueError(f"--{exc}{hint}") from None
    units = options.get("units") or "mm"
    per_mm = 1.0 / MM_PER[units]
    tips = tips.scaled(per_mm, units)
    in_plane = bool(options.get("in_plane"))
    scene = plate_scene(options, DEFAULT_PLATE_MM * per_mm, per_mm,
                        IN_PLANE_APPROACH_MM if in_plane else 100.0)
    tips = replace(tips, in_plane=in_plane)
    reach = tips_reach(tips, scene)
    if isinstance(reach, str):
        raise ValueError(f"--hand: {reach}")
    return tips, scene


def _hand(options: Mapping[str, Any], tips: FingerTips | None = None,
          scene: Any = None) -> Hand | None:
    if tips is not None:
        # held in the plane: the body, and the way it comes in, clear of the part
        body = tips.length + scene.approach if tips.in_plane else 0.0
        return Hand(workspace=options.get("workspace"), finger_radius=tips.radius,
                    finger_length=body)
    ws, radius = options.get("workspace"), options.get("finger_radius") or 0.0
    if ws is None and not radius:
        return None
    if ws is not None and ws[2] <= 0:
        raise ValueError(f"--workspace radius must be > 0, got {ws[2]:g}")
    if not (math.isfinite(radius) and radius >= 0):
        raise ValueError(f"--finger-radius must be a finite number >= 0, got {radius:g}")
    return Hand(workspace=ws, finger_radius=radius)


def fingers_from_options(options: Mapping[str, Any]) -> _PointFingers:
    """The point fingers of a plan request (``--gripper fingers``): ``fingers`` (default
    2), ``mu`` (default 0.3 with friction, 0 frictionless), ``gravity``, ``workspace``,
    ``finger_radius``, ``single_edge``; none of the jaw's options."""
    _no_jaw_options(options)
    fingers = 2 if options.get("fingers") is None else options["fingers"]
    gravity = options.get("gravity")
    if gravity is not None and fingers != 3:
        raise ValueError(f"--gravity is a contact of three frictionless fingers, not of "
                         f"{fingers} (drop it, or use --fingers 3)")
    frictionless = fingers == 4 or gravity is not None
    mu = options.get("mu")
    if mu is None:
        mu = 0.0 if frictionless else DEFAULT_MU
    elif frictionless and mu != 0:
        what = "four fingers" if fingers == 4 else "three fingers with --gravity"
        raise ValueError(f"--mu {mu:g} would not be used: {what} are planned frictionless "
                         f"(drop --mu)")
    if mu < 0 or not math.isfinite(mu):
        raise ValueError(f"--mu must be a finite number >= 0, got {mu:g}")
    tips, scene = _tips(options)
    gripper = point_fingers(fingers, mu, gravity, _hand(options, tips, scene),
                            not options.get("single_edge", False))
    return replace(gripper, tips=tips, scene=scene) if tips is not None else gripper


register("fingers", fingers_from_options, fingers_type)
