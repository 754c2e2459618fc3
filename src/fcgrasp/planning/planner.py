"""Grasp plans: optimal independent regions on every edge set, ranked (sections 7, 8).

:func:`plan` enumerates every edge pair (two fingers with friction), every 4-tuple and
3-edge combination (four frictionless fingers), or every triple with gravity (three
frictionless fingers), and returns the best :class:`~fcgrasp.GraspPlan` objects;
:func:`independent_regions` gives the optimal regions of contact on chosen edges.  Both
are thin façades over the public pipeline of :mod:`fcgrasp.pipeline` (candidates ->
solve -> rank), which a user, a benchmark or a distributed runner can call step by step.

Units: lengths are in the polygon's units; ``margin`` is an angle in **degrees**: every
grasp of the returned regions points at least that far inside the friction cones (two
fingers) or inside the sector ``C_12 & -C_34`` (four fingers; the pairing of the four
fingers is the one giving the largest regions, so a plan does not depend on how the edges
are numbered).  The default is :data:`fcgrasp.model.regions.DEFAULT_MARGIN_DEG` (0.5 degree).
Three fingers are three fingers with friction (:mod:`fcgrasp.grippers.three_fingers`: concurrent
grasps in non-marginal equilibrium, a safe lower bound of the optimum), or, given
``gravity``, three frictionless fingers holding the part against gravity (counted as a
frictionless contact at the centroid, section 3.1).
"""

from __future__ import annotations

import gc
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from typing import Any

from ..core._checks import check_int, check_scalar
from ..core.alternatives import Rounds, distinct_rounds
from ..core.budget import (
    DEFAULT_TIME_LIMIT,
    PlanList,
    check_time_limit,
    deadline,
    incomplete,
    settle,
)
from ..core.tolerances import SOLVER_TOL
from ..grippers.base import DEFAULT_MU, Gripper, SearchOptions
from ..grippers.fingers import point_fingers, regions_on
from ..model.distinct import distinct_plans
from ..model.hand import Hand
from ..model.plans import GraspPlan, geometric_key, rank_key
from ..model.polygon import Polygon, check_polygon
from ..model.ranking import MEASURES
from ..model.regions import DEFAULT_MARGIN_DEG
from ..pipeline import check_disturbance as _check_disturbance

__all__ = ["GraspPlan", "plan", "independent_regions", "RANKINGS", "geometric_key",
           "rank_key", "FrictionCurve", "friction_curve"]

#: Names of the ranking measures (see :mod:`fcgrasp.model.ranking`).
RANKINGS = tuple(MEASURES)

_paused = 0                     # plans running with the cyclic collector paused
_pause_lock = threading.Lock()
_collector_was_on = False


@contextmanager
def collector_paused() -> Iterator[None]:
    """Python's cyclic garbage collector paused while a plan runs, then as it was.

    A search allocates millions of short-lived arrays, tuples and plans, freed by
    their reference counts (none is built into a cycle), and each 700 allocations the
    collector would walk the young objects, and now and then the whole heap (numba's
    many objects in a process that loaded the kernels): 2 to 5 % of a fresh process's
    plan on the corpus.  Cycles made meanwhile are collected once it runs again.  Plans
    in several threads pause it once; the last to finish puts it back as the first
    found it (a caller that disabled it keeps it disabled)."""
    global _paused, _collector_was_on
    with _pause_lock:
        if _paused == 0:
            _collector_was_on = gc.isenabled()
            gc.disable()
        _paused += 1
    try:
        yield
    finally:
        with _pause_lock:
            _paused -= 1
            if _paused == 0 and _collector_was_on:
                gc.enable()


def plan(polygon: Polygon, fingers: int = 2, mu: float | None = None, top: int | None = 10,
         rank_by: str = "min_region", hand: Hand | None = None,
         margin: float = DEFAULT_MARGIN_DEG, gravity: Any = None,
         disturbance: tuple[float, float] = (10.0, 15.0),
         progress: Any = None, tol: float = SOLVER_TOL,
         max_memory: int | None = None, along_boundary: bool = True,
         gripper: Any = None, map: Any = None, distinct: float | None = None,
         load: Any = None, force_limit: Any = None, total_force: Any = None,
         time_limit: Any = DEFAULT_TIME_LIMIT) -> PlanList:
    """Ranked grasp plans of a polygon (sections 7.2, 7.3 and 8), or of a solid.

    Parameters
    ----------
    polygon : Polygon or Solid
        Or anything :func:`~fcgrasp.model.polygon.check_polygon` takes: a shapely
        Polygon or MultiPolygon (its largest polygon), an array of vertices.  A solid
        (:class:`fcgrasp.spatial.Solid`, or a watertight ``trimesh.Trimesh``, its
        lengths taken as millimetres) is planned by the same grippers
        (:mod:`fcgrasp.grippers.solids`): two fingers with friction as soft fingers,
        three fingers with friction, a parallel jaw; ``mu``, ``top``, ``margin``,
        ``distinct`` and ``time_limit`` apply.
    fingers : {2, 3, 4}
        2: two fingers with friction ``mu``; 3: three fingers with friction ``mu``
        (:mod:`fcgrasp.grippers.three_fingers`), or with ``gravity`` three frictionless fingers
        and gravity; 4: four frictionless fingers on four edges or on three edges (two
        on one edge).
    mu : float, optional
        Friction coefficient (two fingers, three without gravity; with four fingers or
        gravity it must be 0: a ``mu`` the planner cannot use is an error).  None (the
        default): :data:`fcgrasp.grippers.base.DEFAULT_MU` (0.3, as ``fcgrasp plan``)
        for fingers with friction, 0 for frictionless ones.
    top : int or None
        How many plans to return (None: all).
    rank_by : {"min_region", "resistance", "epsilon", "payload"}
        Largest smallest region first; largest resistance first (the paper's order);
        largest Ferrari-Canny L1 measure first; or, with a ``load``, the largest scale of
        it certified over every grasp of the regions first (the :data:`PAYLOAD_POOL`
        times ``top`` plans with the largest smallest regions, re-ranked).
    hand : Hand, optional
        Workspace and finger radius (section 8.2): regions lie in the feasible parts.
    margin : float
        Safety margin in degrees inside the cones and sectors.
    gravity : array_like, shape (2,), optional
        Direction of the weight: ``fingers=3`` then means three frictionless fingers
        holding the part against gravity.
    disturbance : (float, float)
        Translation (in the polygon's units) and rotation (degrees) of the resistance
        measure; default 10 units (1 cm in millimetres) and 15 degrees.
    progress : callable, optional
        Called as ``progress(done, total)`` while candidate edge sets are solved.
    tol : float
        Relative slack of the exact region solver
        (:data:`fcgrasp.core.tolerances.SOLVER_TOL`).
    max_memory : int, optional
        Memory budget of the search in bytes (default
        :data:`fcgrasp.pipeline.MAX_MEMORY`, 2 GiB).  The search streams its candidates in
        batches sized to it; a search that cannot fit (every plan of a large part with
        ``top=None``) raises :class:`fcgrasp.pipeline.SearchTooLarge`, a ValueError saying
        what would fit, before any work.  On a solid (default: none) it is the address
        space the search may take on, read at each check of its clock
        (:func:`fcgrasp.core.budget.deadline`): past it the search stops there as at its
        time limit, with the plans it proved.
    gripper : ParallelJaw, optional
        Plan for a parallel-jaw gripper instead of point fingers
        (:func:`fcgrasp.grippers.jaw.jaw_plans`: boxes of jaw poses, :class:`~fcgrasp.JawPlan`);
        its friction is the jaw's, so ``fingers``, ``mu``, ``hand``, ``gravity`` and
        ``rank_by`` must keep their defaults.
    map : callable, optional
        ``map(function, batches)`` to solve candidate batches elsewhere (processes, a
        Dask cluster): the single-edge search (:func:`fcgrasp.pipeline.search`) of two
        fingers without stretches, and of three frictionless or four fingers, uses it;
        the answer is the same (a solid's searches have no such batches: unused).
    distinct : float, optional
        0: every plan, as ranked.  A fraction in (0, 1]: the ``top``
        plans that are distinct alternatives, each standing for the lower-ranked plans
        whose regions overlap its own by more than that fraction (``similar``; see
        :mod:`fcgrasp.model.distinct`; :data:`~fcgrasp.model.distinct.DEFAULT_DISTINCT`
        is 0.5).  The search is asked for more plans until ``top`` distinct ones are
        found or :data:`DISTINCT_DEPTH` times ``top`` were searched.  None (the
        default): the gripper's :func:`default_distinct`, 0.5 for every built-in
        gripper (a parallel jaw's mirror and neighbouring boxes merged; point fingers'
        plans shifted along the outline by an edge merged).
    load : Load, optional
        A load the grasp must carry (:class:`fcgrasp.Load`: mass, centre of mass,
        accelerations, torque; point fingers only): each plan's ``payload`` is the scale
        of it every grasp of its regions carries (:func:`fcgrasp.region_payload`, a
        certified lower bound with its gap), within ``force_limit`` (newtons per finger:
        one value or one per finger) and ``total_force`` (the sum of the normal forces).
    time_limit : float or None
        Wall-clock seconds the search may take to look for distinct alternatives
        (default :data:`fcgrasp.core.budget.DEFAULT_TIME_LIMIT`; None: no limit).  The
        first answer, the ranked search, finishes within
        :data:`~fcgrasp.core.budget.FIRST_ANSWER_GRACE` past the limit (two fingers
        whose stretch search would take longer give the plans of regions on single
        edges instead, incomplete and not exact); the rounds after it stop at
        the limit, and the plans are then an exact prefix of the complete answer with
        ``complete`` False and a ``bound`` on every further alternative
        (:class:`~fcgrasp.model.plans.PlanList`).  ``max_memory`` ends those rounds the
        same way.
    along_boundary : bool
        Without a hand, regions are stretches of the boundary that may cover several
        edges and the vertices between them: for two fingers the exact optimum
        (:mod:`fcgrasp.model.stretches`); for three or four, the single-edge plans and regions
        grown from the best of them (:mod:`fcgrasp.model.frictionless_stretches`: safe, a lower
        bound on the optimum).  False keeps each region on one edge, as in the paper.

    Returns
    -------
    PlanList of GraspPlan (of JawPlan with a ``gripper``)
        Best first; empty when the part admits no such grasp.  A list, with
        ``complete`` and ``bound`` (:class:`~fcgrasp.model.plans.PlanList`).

    Examples
    --------
    >>> part = Polygon([[0, 0], [4, 0], [4, 1], [0, 1]])
    >>> best = plan(part, fingers=2, mu=0.3, top=1)[0]
    >>> best.edges, round(best.min_length, 4)      # the short sides face each other
    ((1, 3), 1.0)
    """
    limit = check_time_limit(time_limit)
    solid = _as_solid(polygon)
    if solid is not None:
        unused = {"rank_by": (rank_by, "min_region"), "hand": (hand, None),
                  "gravity": (gravity, None), "load": (load, None),
                  "force_limit": (force_limit, None), "total_force": (total_force, None),
                  "along_boundary": (along_boundary, True)}
        for name, (value, default) in unused.items():
            if value is not default and value != default:
                raise ValueError(f"{name}={value!r} is not used on a solid (its plans take "
                                 f"fingers or gripper, mu, top, margin, distinct, "
                                 f"time_limit and max_memory)")
        if max_memory is not None:
            max_memory = check_int(max_memory, "max_memory", minimum=1)
        if gripper is None:
            if mu is None:
                mu = DEFAULT_MU if fingers in (2, 3) else 0.0
            gripper = point_fingers(fingers, mu, None, None, True)
        else:
            _short_form_unused(gripper, fingers=(fingers, 2), mu=(mu, None))
        from ..grippers.solids import solid_plans

        # the solids' searches read their memory budget at each check of the clock
        with collector_paused(), deadline(limit, max_memory=max_memory) as spent:
            return settle(solid_plans(gripper, solid, SearchOptions(top=top, margin=margin),
                                      check_scalar(default_distinct(gripper) if distinct is None
                                                   else distinct, "distinct",
                                                   nonnegative=True)), spent)
    polygon = check_polygon(polygon)
    if gripper is None:
        if mu is None:                      # the command line's default, with friction
            mu = DEFAULT_MU if fingers in (2, 3) and gravity is None else 0.0
        gripper = point_fingers(fingers, mu, gravity, hand, along_boundary)
    else:
        _short_form_unused(gripper, fingers=(fingers, 2), mu=(mu, None), hand=(hand, None),
                           gravity=(gravity, None), along_boundary=(along_boundary, True))
    options = SearchOptions(top=top, rank_by=rank_by, margin=margin,
                            disturbance=_check_disturbance(disturbance), tol=tol,
                            max_memory=max_memory, progress=progress, map=map)
    if load is None:
        for name, value in (("force_limit", force_limit), ("total_force", total_force),
                            ("rank_by", None if rank_by != "payload" else rank_by)):
            if value is not None:
                raise ValueError(f"{name}={value!r} needs a load (load=fcgrasp.Load(mass, "
                                 f"...)), got load=None")
        with collector_paused(), deadline(limit) as spent:
            return settle(_distinct(polygon, gripper, options, distinct), spent)
    with collector_paused(), deadline(limit) as spent:
        return settle(_with_payload(polygon, gripper, options, distinct, load, force_limit,
                                    total_force), spent)


def _as_solid(part: Any) -> Any:
    """``part`` as a :class:`fcgrasp.spatial.Solid` when it is one (or a trimesh mesh),
    None for a planar part (the solids' modules are imported only for a solid)."""
    module = type(part).__module__
    if module.startswith("fcgrasp.spatial"):
        from ..spatial.solid import Solid

        return part if isinstance(part, Solid) else None
    if module.startswith("trimesh"):
        from ..spatial.solid import solid_from_mesh

        return solid_from_mesh(part, "mm", "mesh")
    return None


#: ``rank_by="payload"``: the plans with the largest smallest regions, this many times
#: ``top`` of them, are re-ranked by the payload their regions certify.
PAYLOAD_POOL = 4


def _with_payload(polygon: Polygon, gripper: Any, options: SearchOptions, distinct: Any,
                  load: Any, force_limit: Any, total_force: Any) -> PlanList:
    """The plans with each one's certified payload (:func:`fcgrasp.region_payload`);
    ranked by it for ``rank_by="payload"``: the :data:`PAYLOAD_POOL` times ``top`` plans
    with the largest smallest regions, re-ranked (ties: the smallest region order)."""
    from ..model.loads import Load, region_payload

    if not isinstance(load, Load):
        raise TypeError(f"load must be a fcgrasp.Load, got {type(load).__name__}")
    jaw = gripper.name == "jaw"
    by_payload = options.rank_by == "payload"
    if by_payload:
        pool = None if options.top is None else PAYLOAD_POOL * options.top
        options = replace(options, rank_by="min_region", top=pool)
    plans = _distinct(polygon, gripper, options, distinct)
    if jaw:                   # a box of poses: every pose of it (its pads' limits)
        from ..grippers.jaw import jaw_payload
    for p in plans:
        p.payload = jaw_payload(polygon, p, load, force_limit=force_limit,
                                total_limit=total_force) if jaw else \
            region_payload(polygon, p, load, force_limit=force_limit,
                           total_limit=total_force)
    if not by_payload:
        return plans
    if not plans.complete:            # a pool cut short: its bound is not on payloads
        plans = incomplete(plans, plans.stopped or "time_limit", None)
    score = MEASURES["payload"].score(plans)
    # boxes: the larger certified scale first, then the jaw's own order (its measure)
    order = sorted(range(len(plans)), key=lambda i: (
        (-float(f"{score[i]:.9g}"),) if jaw else
        rank_key(plans[i], polygon, "payload", float(score[i])), i))
    top = len(plans) if options.top is None else options.top // PAYLOAD_POOL
    return plans.same_answer([plans[i] for i in order[:top]])


#: ``distinct=``: the search is asked for at most this many times ``top`` plans.
DISTINCT_DEPTH = 32


def default_distinct(gripper: Any) -> float:
    """The ``distinct`` fraction a gripper's plans get when none is given: its
    ``default_distinct`` (:class:`~fcgrasp.grippers.base.Gripper`; a parallel jaw's is
    :data:`~fcgrasp.model.distinct.DEFAULT_DISTINCT`), 0 (the ranked list) where it has
    none.

    >>> from fcgrasp.grippers.jaw import ParallelJaw
    >>> default_distinct(ParallelJaw(stroke=(5, 60), pad_width=8, mu=0.5))
    0.5
    >>> default_distinct(point_fingers(2, 0.3, None, None, True))
    0.5
    """
    return float(getattr(gripper, "default_distinct", 0.0))


def _distinct(polygon: Polygon, gripper: Any, options: SearchOptions,
              distinct: Any) -> PlanList:
    """The gripper's plans, with ``distinct`` the top ones that are distinct alternatives
    (:func:`fcgrasp.model.distinct.distinct_plans`): the search is asked for more plans
    (:func:`fcgrasp.core.alternatives.distinct_rounds`, each request at least twice the
    one before, as :class:`~fcgrasp.core.alternatives.Rounds` says) until ``top``
    distinct ones are found, it has no more, or it was asked for
    :data:`DISTINCT_DEPTH` times ``top`` (a gripper's ``distinct_depth`` where it has
    one).  The plans kept are those of suppression along the ranked list, however long
    the last list read was.

    The requests after the first stop when the time budget ends
    (:func:`fcgrasp.core.budget.deadline`) or at the depth; the plans kept are then an
    exact prefix of the complete answer, incomplete, with the last plan read's smallest
    region as the bound where the plans are ranked by it (every plan not read is below
    it)."""
    fraction = check_scalar(default_distinct(gripper) if distinct is None else distinct,
                            "distinct", nonnegative=True)
    if fraction > 1:
        raise ValueError(f"distinct must be a fraction in [0, 1], got {distinct!r}")
    if fraction == 0:
        return PlanList(gripper.plan(polygon, options))
    # a gripper may search for distinct plans itself (two fingers along the boundary:
    # each kept plan's shifted copies left out of the search)
    direct = getattr(gripper, "distinct_search", None)
    found = direct(polygon, options, fraction) if direct is not None else None
    if found is not None:
        return found if isinstance(found, PlanList) else PlanList(found)
    # a gripper may say what distinct means for its plans (the jaw: boxes up to the
    # part's symmetries); regions of contact otherwise
    suppress = getattr(gripper, "distinct_plans", None) or \
        (lambda poly, ps, f: distinct_plans(ps, f, poly.size, limit=options.top))
    kept, plans, stopped = distinct_rounds(
        lambda n: list(gripper.plan(polygon, replace(options, top=n))),
        lambda ps: suppress(polygon, ps, fraction), options.top,
        Rounds(depth=getattr(gripper, "distinct_depth", DISTINCT_DEPTH)))
    if stopped is None:
        return PlanList(kept)
    last = plans[-1] if plans else None
    # point fingers ranked by the smallest region: every plan not read is below the last
    if options.rank_by == "min_region" and isinstance(last, GraspPlan):
        return incomplete(kept, stopped, float(last.min_length))
    return incomplete(kept, stopped, None)


def _short_form_unused(gripper: Any, **given: tuple[Any, Any]) -> None:
    """With a gripper object, the short form's arguments must keep their defaults."""
    if not isinstance(gripper, Gripper):
        raise TypeError(f"gripper must be a gripper (fcgrasp.grippers.base.Gripper: a "
                        f"ParallelJaw, TwoFingers, ...) or None, got "
                        f"{type(gripper).__name__}")
    unused = [f"{name}={value!r}" for name, (value, default) in given.items()
              if value is not default and value != default]
    if unused:
        raise ValueError(f"a gripper object carries its own parameters: "
                         f"{', '.join(unused)} would not be used")


def independent_regions(polygon: Polygon, edges: Any, mu: float = 0.0,
                        margin: float = DEFAULT_MARGIN_DEG, hand: Hand | None = None,
                        gravity: Any = None, tol: float = SOLVER_TOL) -> GraspPlan | None:
    """Optimal independent regions of contact on the given edges (definition 7.1).

    Parameters
    ----------
    edges : sequence of int, or two sequences of int
        Two edges (fingers with friction ``mu``: algorithm 7.1, squeezing and expanding
        grasps), four edges (frictionless: theorem 7.1; an edge may repeat, then its two
        regions do not overlap), three edges (fingers with friction ``mu``,
        :mod:`fcgrasp.grippers.three_fingers`; an edge may repeat, then its two regions
        come one after the other along it) or three edges with ``gravity`` (frictionless).
        Two fingers may also be given a *stretch* each, the consecutive edges of one
        ring it may run along (``[[3, 4, 5], [9]]``): the regions are then the best
        stretches inside them (:func:`fcgrasp.model.stretches.stretch_regions`), covering the
        vertices between.
        Three (with ``gravity``) or four frictionless fingers given stretches get the
        optimal regions covering exactly those edges
        (:func:`fcgrasp.model.frictionless_stretches.frictionless_stretch_regions`).
    margin : float
        Safety margin in degrees.

    Returns
    -------
    GraspPlan or None
        None when the edges admit no force-closure grasp with that margin.

    Examples
    --------
    >>> sq = Polygon([[0, 0], [10, 0], [10, 3], [0, 3]])
    >>> reg = independent_regions(sq, (0, 2), mu=0.3)
    >>> [r.round(3).tolist() for r in reg.regions]
    [[[4.564, 0.0], [5.436, 0.0]], [[5.436, 3.0], [4.564, 3.0]]]
    """
    polygon = check_polygon(polygon)
    return regions_on(polygon, edges, mu=mu, margin=margin, hand=hand, gravity=gravity,
                      tol=tol)


@dataclass(frozen=True)
class FrictionCurve:
    """The best plan at each friction coefficient of a range (:func:`friction_curve`):
    ``mu`` (n,), ``min_region`` (n,: the best plan's smallest region, 0 where there is
    none) and the plans themselves (None where there is none)."""

    mu: Any
    min_region: Any
    plans: list[Any] = field(repr=False)

    def to_dict(self) -> dict[str, Any]:
        return {"mu": [float(m) for m in self.mu],
                "min_region": [float(v) for v in self.min_region]}


def friction_curve(polygon: Polygon, mu_range: Any, points: int = 9, fingers: int = 2,
                   **kwargs: Any) -> FrictionCurve:
    """The best plan's smallest region against friction, at ``points`` coefficients
    evenly spaced over ``mu_range = (low, high)`` (both ends included), for fingers with
    friction (two or three); ``kwargs`` go to :func:`plan` (``margin``, ``hand``,
    ``along_boundary``...).

    Friction known only to lie in the range: a plan made at ``low`` holds for every
    ``mu`` of it (a larger ``mu`` only widens the friction cones, so a grasp in force
    closure at ``low`` stays so, with the same margin); the curve says what a better
    known friction would gain.

    >>> part = Polygon([[0, 0], [4, 0], [4, 1], [0, 1]])
    >>> c = friction_curve(part, (0.1, 0.4), points=4)
    >>> [round(float(v), 3) for v in c.min_region]     # 1.0: the whole short side
    [0.365, 0.764, 1.0, 1.0]
    """
    import numpy as np

    lo, hi = _mu_range(mu_range)
    points = check_int(points, "points", minimum=2)
    if fingers not in (2, 3):
        raise ValueError(f"fingers must be 2 or 3 (fingers with friction), got {fingers!r}")
    for name in ("mu", "top", "gravity", "gripper", "load", "rank_by"):
        if name in kwargs:
            raise ValueError(f"{name}={kwargs[name]!r}: friction_curve plans the best "
                             f"plan by the smallest region at each mu itself")
    mus = np.linspace(lo, hi, points)
    plans = []
    for m in mus:
        best = plan(polygon, fingers=fingers, mu=float(m), top=1, **kwargs)
        plans.append(best[0] if best else None)
    sizes = np.array([0.0 if p is None else p.min_length for p in plans])
    return FrictionCurve(mus, sizes, plans)


def _mu_range(mu_range: Any) -> tuple[float, float]:
    from ..core._checks import check_mu_scalar

    if isinstance(mu_range, (str, bytes)) or not hasattr(mu_range, "__len__") \
            or len(mu_range) != 2:
        raise ValueError(f"mu_range must be (low, high), got {mu_range!r}")
    lo, hi = (check_mu_scalar(m, "mu_range") for m in mu_range)
    if not lo < hi:
        raise ValueError(f"mu_range must be (low, high) with low < high, got {mu_range!r}")
    return lo, hi
