"""Plans whose regions run along the boundary, shared by the point-finger grippers:
two fingers' stretches (exact), three or four frictionless fingers grown from their
best single-edge plans (a safe lower bound), and the plan builders they share."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from ..core._geom import midpoints
from ..core.budget import (
    BudgetExhausted,
    PlanList,
    cut_short,
    exhausted,
    incomplete,
    interruptible,
    stop_reason,
)
from ..core.tolerances import LEXIMIN_STEP, RANK_TOL
from ..model.distinct import Suppression
from ..model.frictionless_stretches import FrictionlessStretches, grow_stretches, load_kernels
from ..model.plans import GraspPlan, rank_key
from ..model.polygon import Polygon
from ..model.ranking import MEASURES
from ..model.stretches import (
    StretchPair,
    StretchSearch,
    crosses_a_vertex,
    two_finger_stretches,
)
from ..pipeline import (
    GROW_SEEDS,
    KEEP_STRETCHES,
    EdgeSets,
    PlanSpec,
    features,
    rank,
    search,
    solve,
)
from ..pipeline._solve import RowScores
from ._distinct_rows import RowCopies

# ----------------------------------------------------------------------------- stretches



def regions_plan(polygon: Polygon, spec: PlanSpec, regions: Any, region_edges: Any,
                   lengths: Any, contact_type: str, mode: str,
                   gravity: dict[str, Any] | None = None) -> GraspPlan:
    """The :class:`~fcgrasp.GraspPlan` of given regions, each a polyline along the edges
    ``region_edges[i]`` (representative contacts halfway along each region)."""
    contacts, edges = midpoints(regions, region_edges)
    return GraspPlan(edges, regions, np.array(lengths), contacts, polygon.normals[list(edges)],
                     contact_type, spec.mu, mode, spec.margin, gravity,
                     centroid=polygon.centroid.copy(),
                     radius=polygon.radius,
                     disturbance=spec.disturbance, region_edges=region_edges)


def stretch_plan(polygon: Polygon, spec: PlanSpec, pair: StretchPair) -> GraspPlan:
    """The :class:`~fcgrasp.GraspPlan` of a pair of stretches (representative contacts
    halfway along each region)."""
    return regions_plan(polygon, spec, pair.regions, pair.region_edges, pair.lengths,
                          "friction", pair.mode)


def _single_edge_plans(polygon: Polygon, spec: PlanSpec, pairs: list[tuple[int, int]]
                       ) -> list[GraspPlan]:
    """The single-edge pipeline's plans (exact leximin levels and placement) of chosen
    edge pairs."""
    if not pairs:
        return []
    F = features(polygon, spec.mu, None)
    feat = {int(e): i for i, e in enumerate(F.edge)}
    rows = np.array(sorted({tuple(sorted((feat[a], feat[b]))) for a, b in pairs}))
    sub = replace(spec, top=None, rank_by="min_region")
    return rank(polygon, sub, [solve(polygon, sub, EdgeSets(rows))])


def frictionless_plan(polygon: Polygon, spec: PlanSpec, r: FrictionlessStretches
                      ) -> GraspPlan:
    """The :class:`~fcgrasp.GraspPlan` of frictionless regions along the boundary
    (representative contacts halfway along each region)."""
    g = None if spec.gravity is None else {"center": polygon.centroid.copy(),
                                           "direction": np.array(spec.gravity)}
    return regions_plan(polygon, spec, r.regions, r.region_edges, r.lengths,
                          "frictionless", r.mode, g)


def ranked_unique(polygon: Polygon, spec: PlanSpec, plans: list[GraspPlan],
                  seen: set[Any] | None = None) -> list[GraspPlan]:
    """Plans in :func:`rank_key` order (the best ``spec.top``), a grasp reached by two
    configurations of one mode once (``seen``: the keys of grasps already given, which
    this call adds to)."""
    out = [p for _, p in ranked_keyed(polygon, spec.rank_by, plans, seen)]
    return out if spec.top is None else out[:spec.top]


def ranked_keyed(polygon: Polygon, rank_by: str, plans: list[GraspPlan],
                 seen: set[Any] | None = None, keys: dict[int, Any] | None = None
                 ) -> list[tuple[Any, GraspPlan]]:
    """:func:`ranked_unique`'s plans (all of them), each with its grasp's key
    ``(rank_key, mode)``, the one ``seen`` holds.  ``keys``: each plan's rank key as
    an earlier call computed it (by ``id``, with the plan and its score, so that a new
    plan at a reused address is keyed afresh), filled here: a search that ranks a
    growing list each round keys each plan once."""
    scores = MEASURES[rank_by].score(plans) if plans else np.zeros(0)

    def key_of(p: GraspPlan, q: float) -> Any:
        if keys is None:
            return rank_key(p, polygon, rank_by, q)
        got = keys.get(id(p))
        if got is None or got[0] is not p or got[1] != q:
            got = keys[id(p)] = (p, q, rank_key(p, polygon, rank_by, q))
        return got[2]

    keyed = sorted((key_of(p, float(q)), k)
                   for k, (p, q) in enumerate(zip(plans, scores, strict=True)))
    out: list[tuple[Any, GraspPlan]] = []
    seen = set() if seen is None else seen
    for key, k in keyed:
        if (key, plans[k].mode) in seen:
            continue
        seen.add((key, plans[k].mode))
        out.append(((key, plans[k].mode), plans[k]))
    return out


def _reaches_a_vertex(polygon: Polygon, p: GraspPlan) -> bool:
    """Some region of a single-edge plan ends at an end of its edge (elsewhere the
    regions are held back by each other, not by their edges)."""
    tol = LEXIMIN_STEP * polygon.size
    for e, (x, y) in zip(p.edges, p.ends, strict=True):
        for v in (polygon.starts[e], polygon.ends[e]):
            if min(np.hypot(*(x - v)), np.hypot(*(y - v))) <= tol:
                return True
    return False


#: The best grown configurations that also try pairs of moves
#: (:func:`~fcgrasp.model.frictionless_stretches.grow_stretches`'s ``polish``).
POLISH = 1


def grown_plans(polygon: Polygon, spec: PlanSpec, progress: Any = None, map: Any = None
                ) -> list[GraspPlan]:
    """Three or four frictionless fingers along the boundary: the single-edge plans and,
    grown from those of the :data:`GROW_SEEDS` best of them with the fingers on distinct
    edges and a region that reaches an end of its edge, regions along the boundary
    (:mod:`fcgrasp.model.frictionless_stretches`: every grasp of them holds; a lower bound on
    the optimum, not the optimum), ranked together.
    ``progress`` as for :func:`solve` (the single-edge search)."""
    if not spec.grows:
        raise ValueError("grown_plans plans three or four fingers without a hand "
                         "(spec.grows is False)")
    return _grown_ranked(polygon, spec, progress, map)[0]


def _grown_ranked(polygon: Polygon, spec: PlanSpec, progress: Any = None, map: Any = None,
                  scores: RowScores | None = None
                  ) -> tuple[list[GraspPlan], list[GraspPlan]]:
    """:func:`grown_plans`'s plans, and every grown plan (ranked or not); ``scores``
    remembers the rows its searches solve (:func:`search`)."""
    flat = replace(spec, along_boundary=False)
    seeds, grown = _grown(polygon, spec, map, scores)
    # a single-edge plan below the top-th of the plans found so far (grown, and the
    # seeds: single-edge plans of the exact search) cannot rank (on a smooth outline of
    # equal edges, where every row ties on its bound, this ends the search at once)
    floor = 0.0
    if spec.top is not None and spec.rank_by == "min_region" \
            and len(grown) + len(seeds) >= spec.top:
        distinct = ranked_unique(polygon, replace(spec, top=None), grown + seeds)
        if len(distinct) >= spec.top:
            floor = float(min(distinct[spec.top - 1].lengths)) - 2 * RANK_TOL * polygon.size
    plans = search(polygon, flat, progress=progress, map=map, floor=floor, scores=scores)
    return ranked_unique(polygon, spec, plans + grown), grown


def _grown(polygon: Polygon, spec: PlanSpec, map: Any = None,
           scores: RowScores | None = None) -> tuple[list[GraspPlan], list[GraspPlan]]:
    """:func:`grown_plans`'s seeds (the :data:`GROW_SEEDS` best single-edge plans) and
    the plans grown from them along the boundary."""
    flat = replace(spec, along_boundary=False)
    load_kernels()                      # the growth runs compiled: the seeds' search too
    # the seeds: the GROW_SEEDS best single-edge plans, whatever the top (exact ties on
    # the smallest region in the order found)
    seeds = search(polygon, replace(flat, top=GROW_SEEDS),
                   map=map, strict=True, scores=scores)
    rows = [p.edges for p in seeds[:GROW_SEEDS]
            if len(set(p.edges)) == len(p.edges) and _reaches_a_vertex(polygon, p)]
    grown: list[GraspPlan] = []
    if rows:
        got = grow_stretches(polygon, rows, spec.margin,
                             None if spec.gravity is None else np.array(spec.gravity),
                             keep_single=False, polish=POLISH)
        grown = [frictionless_plan(polygon, spec, r) for r in got
                 if r is not None and max(len(e) for e in r.region_edges) > 1]
    return seeds, grown


#: Below this ``distinct`` fraction :func:`distinct_single_edge_plans` leaves out the
#: rows inside kept regions unsolved (:class:`~fcgrasp.grippers._distinct_rows.RowCopies`:
#: a region inside another overlaps it by the whole of it, which a fraction of 1 does
#: not exceed).
SURE_FRACTION = 0.99


def distinct_single_edge_plans(polygon: Polygon, spec: PlanSpec, fraction: float,
                               progress: Any = None, map: Any = None
                               ) -> list[GraspPlan] | None:
    """The ``spec.top`` best single-edge plans (three or four frictionless fingers:
    with the plans grown along the boundary, as :func:`grown_plans` ranks them) that
    are distinct alternatives (:func:`fcgrasp.model.distinct.distinct_plans` over the
    whole ranked list, exactly), or None where this search does not apply (another
    ``rank_by``, ``top=None``, a hand, a fraction above :data:`SURE_FRACTION`: the
    caller then suppresses the ranked list as usual).

    The first round reads the ranked list's first ``top`` plans as the gripper ranks
    them (with the floors that end its search early; on most parts they are distinct
    already: a gear's ten best plans are grown ones, and asking for twenty would read
    its thousands of tied single-edge rows).  Then rounds of the single-edge search,
    each leaving out the rows read before and the rows whose every plan is surely the
    same alternative as a plan kept so far
    (:class:`~fcgrasp.grippers._distinct_rows.RowCopies`: on a curved outline a grown
    plan's regions cover hundreds of edges, whose rows would fill the ranked list).  A
    round gives the next plans of the ranked list less those suppression drops
    anyway, down to its last; the grown plans that rank before that last are fed with
    them, in rank order, to :class:`~fcgrasp.model.distinct.Suppression`, so the plans
    kept are those of suppression along the whole list.  Each kept plan's ``similar``
    lists the plans it stands for among those read (at least :data:`DISTINCT_READ`
    single-edge plans, twice ``top``, a round); copies left out unread are not
    listed.  ``progress(kept, top)`` before each round after the first, and at the
    end."""
    top = spec.top
    if top is None or spec.rank_by != "min_region" or spec.hand is not None \
            or not 0 < fraction <= SURE_FRACTION:
        return None
    flat = replace(spec, along_boundary=False)
    suppression = Suppression(fraction, polygon.size)
    ask = max(2 * top, DISTINCT_READ)
    # the rows' scores, remembered from round to round (the rounds read the same rows)
    scores = RowScores()
    # the first round: the ranked list's first plans, as the gripper ranks them (its
    # floors end the search early; most parts' first plans are distinct already)
    if spec.grows:
        first, grown = _grown_ranked(polygon, spec, map=map, scores=scores)
    else:
        first, grown = search(polygon, flat, map=map, scores=scores), []
    seen: set[Any] = set()              # one grasp reached twice (grown, single): once
    came = ranked_keyed(polygon, spec.rank_by, first, seen)
    for _, p in came:
        suppression.add(p)
    read = [p.edges for p in first if max(len(e) for e in p.region_edges) == 1]
    more = len(first) == top
    # the grown plans not read rank after the first round's last
    waiting = ranked_keyed(polygon, spec.rank_by, grown, seen)
    while more and len(suppression.kept) < top:
        if progress is not None:        # plans kept of top, before each round
            progress(len(suppression.kept), top)
        # a row below the ask-th waiting grown plan's smallest region ranks after it
        floor = float(min(waiting[ask - 1][1].lengths)) - 2 * RANK_TOL * polygon.size \
            if len(waiting) >= ask else 0.0
        copies = RowCopies(polygon, suppression.kept, read, suppression.tol)
        single = search(polygon, replace(flat, top=ask), map=map, exclude=copies,
                        floor=max(floor, 0.0), scores=scores)
        keyed = ranked_keyed(polygon, spec.rank_by, single)
        # each grasp once: not one read before, nor a waiting grown plan's
        merged = sorted(waiting + [kp for kp in keyed if kp[0] not in seen],
                        key=lambda kp: kp[0])
        if len(single) == ask:          # the rows not read rank after the last
            last = keyed[-1][0]
        elif floor > 0:                 # ... after the ask-th waiting grown plan
            last = waiting[ask - 1][0]
        else:                           # every row left was read
            last, more = merged[-1][0] if merged else None, False
        # read (left out of the searches that follow): the rows up to the last, a grasp that
        # is also a grown plan's among them
        read += [p.edges for key, p in keyed if last is not None and key <= last]
        now = [kp for kp in merged if last is not None and kp[0] <= last]
        waiting = [kp for kp in merged if last is None or kp[0] > last]
        for key, p in now:
            seen.add(key)
            suppression.add(p)
    if progress is not None:
        progress(top, top)
    return suppression.plans()[:top]


def stretch_plans_read(polygon: Polygon, spec: PlanSpec
                       ) -> tuple[list[GraspPlan], bool, float]:
    """The plans of the ``spec.top`` best two-finger stretch configurations and every
    tie of the last (``spec.top`` None: of all of them), ranked, each grasp once; whether
    they are all there are; and a smallest region every configuration left unread is
    below (the ``spec.top``-th's, less the search's relative tie tolerance: its ties
    are all read).  An outline where a region can cover a vertex; ``rank_by`` is
    ``min_region``."""
    pairs = two_finger_stretches(polygon, spec.mu, spec.margin, top=spec.top, ties=True)
    plans = two_finger_plans_of(polygon, spec, pairs)
    below = unread_below(pairs, spec.top)
    return plans, below is None, 0.0 if below is None else below


def _grasps_read(polygon: Polygon, spec: PlanSpec, plans: list[GraspPlan], every: bool
                 ) -> list[GraspPlan]:
    """The ``spec.top`` best grasps, ``plans`` those of the best ``spec.top``
    configurations (:func:`stretch_plans_read`; ``every``: all there are).  A grasp
    reached by several configurations (a region as long as it is anywhere along a
    longer edge) is one plan, so a read of ``top`` configurations can give fewer
    grasps than there are; the read then grows by :data:`READ_GROWTH` until ``top``
    grasps are read or every configuration is.  Every configuration not read is below
    every grasp read (the ties of the last read all read), so the first ``top`` read
    are the answer's.  The time budget may end a deeper read: the grasps read so far
    are then the answer, cut short (:func:`~fcgrasp.core.budget.cut_short`)."""
    assert spec.top is not None
    ask = spec.top
    while not every and len(plans) < spec.top:
        ask *= READ_GROWTH
        try:
            with interruptible():
                plans, every, _ = stretch_plans_read(polygon, replace(spec, top=ask))
        except BudgetExhausted:
            cut_short()
            break
    return plans[:spec.top]


def unread_below(pairs: list[StretchPair], top: int | None) -> float | None:
    """A smallest region every configuration left unread by a stretch search asked
    for ``top`` with ties is below (the ``top``-th's, less the search's relative tie
    tolerance: its ties are all read); None where the search gave all there are.  A
    search with ``third`` ranks by each pair's ``bound`` (its pair plan's smallest
    region at most): the level is then the ``top``-th bound."""
    if top is None or len(pairs) < top:
        return None
    kth = sorted((p.min_length if p.bound is None else p.bound for p in pairs),
                 reverse=True)[top - 1]
    return float(kth * (1 - RANK_TOL))


def two_finger_plans_of(polygon: Polygon, spec: PlanSpec, pairs: list[StretchPair],
                        given: set[Any] | None = None) -> list[GraspPlan]:
    """The plans of two-finger stretch configurations, ranked (:func:`ranked_unique`,
    whatever ``spec.top``), each grasp once (``given``: the grasps given before)."""
    return ranked_unique(polygon, replace(spec, top=None), _stretch_plans(polygon, spec, pairs),
                         given)


def _stretch_plans(polygon: Polygon, spec: PlanSpec, pairs: list[StretchPair]
                   ) -> list[GraspPlan]:
    """Plans of the stretch pairs found, those on single edges solved by the single-edge
    pipeline (the same leximin levels and placement as :func:`solve`)."""
    multi = [p for p in pairs if max(len(e) for e in p.region_edges) > 1]
    return [stretch_plan(polygon, spec, p) for p in multi] + _single_edge_plans(
        polygon, spec, [(p.region_edges[0][0], p.region_edges[1][0]) for p in pairs
                        if max(len(e) for e in p.region_edges) == 1])


#: Plans each round of :func:`distinct_boundary_plans` reads at least.
DISTINCT_READ = 10


#: The factor by which a distinct round that keeps no new plan multiplies the plans the
#: next one reads (1: each reads the plans still missing, at least
#: :data:`DISTINCT_READ`, the reference; three fingers' rounds grow by it too):
#: ``icons/lock.svg`` at mu 0.2 has thousands of copies of a region on its long edges,
#: which ten at a time take 386 rounds.
READ_GROWTH = 2


def distinct_boundary_plans(polygon: Polygon, spec: PlanSpec, fraction: float,
                            progress: Any = None, depth: int | None = None
                            ) -> PlanList | None:
    """The ``spec.top`` best two-finger plans along the boundary that are distinct
    alternatives (:func:`fcgrasp.model.distinct.distinct_plans` over the whole ranked
    list, exactly), or None where this search does not apply (another ``rank_by``,
    ``top=None``, no region covering a vertex: the caller then suppresses as usual).

    Rounds of the stretch search, each excluding the configurations that are surely
    the same alternative as a plan kept so far (:class:`~fcgrasp.model.stretches`'s
    ``exclude``: on a curved outline a grasp has thousands of shifted copies, which
    would otherwise fill the ranked list), and the plans already read.  The list a
    round returns is the ranked list less plans that suppression drops anyway, down to
    its last, so suppressing in rank order along it gives the same plans as along the
    whole list (:class:`~fcgrasp.model.distinct.Suppression`, fed round by round).
    Each kept plan's ``similar`` lists the plans it stands for among those the rounds
    read (each as many as are still missing, at least :data:`DISTINCT_READ`, times
    :data:`READ_GROWTH` for each round before it that kept no new plan); copies left out
    unread are not listed.  ``progress(kept, top)`` after each round.

    The search stops early when the time budget ends (:func:`fcgrasp.core.budget.
    deadline`: between rounds, or inside one, whose work is then dropped; the first
    round, the ranked search, finishes unless it takes
    :data:`~fcgrasp.core.budget.FIRST_ANSWER_GRACE` past the budget, and then the
    plans of regions on single edges are given, :func:`_on_single_edges`), when a
    round's collection of configurations would exceed ``spec.max_memory``, or with
    ``depth`` once ``depth`` times ``top`` plans are read (on a smooth outline, a
    region on a long edge can be placed anywhere along it before the plan is
    finished, so its shifted copies are not left out: a 2,000-edge half disc reads
    7,000 plans for ten alternatives).  The
    plans kept by the finished rounds are then returned, an exact prefix of the
    complete answer, incomplete (:class:`~fcgrasp.model.plans.PlanList`), with the
    last finished round's level as the bound: every configuration left unread is
    below it, so every further alternative is."""
    top = spec.top
    if top is None or spec.rank_by != "min_region" or fraction <= 0 \
            or not crosses_a_vertex(polygon, spec.mu, spec.margin):
        return None
    suppression = Suppression(fraction, polygon.size)
    read: list[GraspPlan] = []
    given: set[Any] = set()             # one grasp reached by two configurations: once
    try:
        stretches = StretchSearch(polygon, spec.mu, spec.margin, max_bytes=spec.max_memory)
    except BudgetExhausted:
        return _on_single_edges(polygon, spec, fraction)
    level: float | None = None          # every configuration left unread is below it
    stopped: str | None = None
    grow = 1                            # READ_GROWTH times each round that keeps none
    while len(suppression.kept) < top:
        ask = max(top - len(suppression.kept), DISTINCT_READ) * grow
        had = len(suppression.kept)
        try:
            pairs = stretches.pairs(top=ask, ties=True, exclude=suppression.kept,
                                    fraction=fraction, seen=read)
        except BudgetExhausted as exc:
            if not read and str(exc) == "time_limit":
                return _on_single_edges(polygon, spec, fraction)
            stopped = str(exc) or "time_limit"
            break
        ranked = two_finger_plans_of(polygon, spec, pairs, given)
        for p in ranked:
            suppression.add(p)
        read += ranked
        level = unread_below(pairs, ask)
        if progress is not None:
            progress(min(len(suppression.kept), top), top)
        if level is None:
            break                       # every plan left was read
        if len(suppression.kept) >= top:
            break
        if depth is not None and len(read) >= depth * top:
            stopped = "depth"
            break
        if exhausted():
            stopped = stop_reason()
            break
        # the plans read are left out by name, so each round reads further down; a
        # round whose plans were all copies the exclusion could not leave out (a region
        # on a long edge, placed anywhere along it) reads READ_GROWTH times as many next
        if len(suppression.kept) == had:
            grow *= READ_GROWTH
    kept = suppression.plans()[:top]
    return PlanList(kept) if stopped is None else incomplete(kept, stopped, level)


def _on_single_edges(polygon: Polygon, spec: PlanSpec, fraction: float = 0.0
                     ) -> PlanList:
    """The answer of a two-finger search whose first round the time budget ended (a
    large outline at a wide cone: the stretch search's first answer alone can take
    longer than the budget): the plans of regions on single edges (the paper's
    algorithm 7.1, a small fraction of the cost), distinct alternatives with
    ``fraction``; the search recorded as cut short, so the answer is incomplete, with no
    bound (:func:`fcgrasp.core.budget.cut_short`: regions across vertices were not
    searched)."""
    from ..core.budget import cut_short
    from ..model.distinct import distinct_plans

    cut_short()
    flat = replace(spec, along_boundary=False)
    if fraction > 0:
        got = distinct_single_edge_plans(polygon, flat, fraction)
        if got is None:
            every = ranked_unique(polygon, flat, search(polygon, replace(flat, top=None)))
            got = distinct_plans(every, fraction, polygon.size)[:spec.top]
        return PlanList(got)
    return PlanList(ranked_unique(polygon, spec, search(polygon, flat)))


def boundary_plans(polygon: Polygon, spec: PlanSpec) -> list[GraspPlan]:
    """Two-finger plans whose regions run along the boundary (stretches of the rings,
    :mod:`fcgrasp.model.stretches`), ranked as :func:`rank` ranks.

    The exact stretch search gives the best configurations and every tie of the
    ``top``-th; those on single edges are solved by the single-edge pipeline (the same
    leximin levels and placement as :func:`solve`), so on outlines where no region
    gains by crossing a vertex the plans are those of the single-edge search.  With a
    ranking measure other than ``min_region`` the single-edge search's plans and the
    :data:`KEEP_STRETCHES` best stretch configurations are scored.  ``top=None``: every
    configuration that holds (one plan per configuration: which edges each region
    covers), for small parts.
    """
    if not spec.stretches:
        raise ValueError("boundary_plans plans two fingers without a hand "
                         "(spec.stretches is False)")
    flat = replace(spec, along_boundary=False)
    if not crosses_a_vertex(polygon, spec.mu, spec.margin):
        # no region can cover a vertex: the regions are the single-edge ones
        return ranked_unique(polygon, spec, search(polygon, flat))
    if spec.rank_by == "min_region":
        try:
            plans, every, _ = stretch_plans_read(polygon, spec)
        except BudgetExhausted as exc:
            if str(exc) != "time_limit":
                raise
            return _on_single_edges(polygon, spec)
        return plans if spec.top is None else _grasps_read(polygon, spec, plans, every)
    keep = None if spec.top is None else max(spec.top, KEEP_STRETCHES)
    pairs = two_finger_stretches(polygon, spec.mu, spec.margin, top=keep, ties=False)
    multi = [p for p in pairs if max(len(e) for e in p.region_edges) > 1]
    plans = [stretch_plan(polygon, spec, p) for p in multi] + search(polygon, flat)
    return ranked_unique(polygon, spec, plans)
