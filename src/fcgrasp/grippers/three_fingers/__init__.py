r"""Three fingers with friction: independent regions of concurrent grasps.

Three point fingers with friction ``mu`` hold a planar part when their forces can be in
*non-marginal equilibrium*: three lines of force, each strictly inside its friction
cone, meet in one point ``p``, and the three force directions positively span the plane.
Then the contact wrenches hold ``(d_i, 0)`` (the force through ``p``, no torque about
it) in the relative interior of their cones and a strictly positive combination of them
is zero, so the wrenches span the whole wrench space: the grasp is force closure (the
force directions satisfy theorem 4.2, three directions with a strictly positive null
combination; the friction cones add the torques of theorem 6.1's total convexe; this is
Ponce and Faverjon's sufficient condition for three fingers).

**A convex piece of the closure set.**  Choose, for each finger, a sub-arc ``D_i`` of its
friction cone shrunk by the ``margin``, such that *every* choice of one direction from
each sub-arc positively spans the plane (:func:`spanning_arcs`: with the arcs in
counter-clockwise order, the angle from the start of one arc to the end of the next is
below half a turn, minus the margin), and a side ``sigma_i``: the meeting point lies
ahead of finger ``i`` (``+1``, inside the part) or behind it (``-1``).  Then

.. math:: p - x_i(s_i) \in \sigma_i \, \mathrm{cone}(D_i), \qquad i = 1, 2, 3

is linear in the finger positions ``s`` and in ``p``: the grasps it admits are the
projection of a polytope, a convex set, and every one of them is force closure.  A box of
regions (one interval of positions per finger) lies in a convex set iff its eight corner
grasps do, each with its own witness point ``p_c``: one linear program per piece
maximises the smallest region (definition 7.1), and the leximin levels follow by fixing
the regions that cannot grow and maximising again.

**Two fingers side by side.**  Two fingers may share an edge (the first two of a row,
the third on another): their positions are measured from the same start, and the one
inequality ``hi_0 <= lo_1`` keeps their regions apart, one after the other; the piece
stays the projection of a polytope, so the same program solves it.  Such rows are not
grown along the boundary.

**Exact or a bound.**  The regions are *safe* (every grasp of them is force closure,
tested against the general wrench test) and optimal within each piece, but the union of
the pieces (the sides, the sub-arcs: :data:`SPLITS` of the half-turn excess) is not the
whole closure set: the optimum is a **lower bound** of the true one.  Two fingers that
hold the part on their own (a two-finger plan, algorithm 7.1, exact) with the third
anywhere on another edge are a candidate too, so three fingers never do worse than two
with the third placed on the longest remaining edge.  ``benchmarks/bench_three_fingers.py``
measures the gap: how far each returned box can grow before a sampled grasp fails the
general test.

**Along the boundary** (on outlines where a region can cover a vertex,
:func:`fcgrasp.model.stretches.crosses_a_vertex`): the two fingers that hold on their own are
the exact two-finger stretches, the third runs along the longest free stretch
(:func:`free_stretch`); and the best concurrent plans are grown into stretches
(:func:`grow_concurrent`): a contact anywhere on a stretch, on an interior vertex too,
keeps the friction cone common to the stretch's edges, so with those cones a piece is
again a projection of a polytope and a box of regions is inside it iff every grasp of
region ends and interior vertices is, each with its own witness.

Units: lengths in the part's units, ``margin`` in radians in this module's functions
(degrees in :class:`~fcgrasp.pipeline.PlanSpec`).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import replace
from typing import Any

import numpy as np

from ...core._checks import FloatArray
from ...core.budget import BudgetExhausted, PlanList, exhausted, incomplete, stop_reason
from ...core.tolerances import RANK_TOL
from ...model.distinct import Suppression
from ...model.plans import GraspPlan, leximin_key
from ...model.polygon import Polygon
from ...model.stretches import StretchSearch, crosses_a_vertex
from ...pipeline import PlanSpec, candidates, features, search_size
from .._boundary import (
    DISTINCT_READ,
    READ_GROWTH,
    ranked_keyed,
    ranked_unique,
    two_finger_plans_of,
    unread_below,
)
from . import _concurrency

__all__ = ["spanning_arcs", "Piece", "concurrent_regions", "three_finger_plans", "SPLITS",
           "KEEP_PAIRS", "free_stretch", "grow_concurrent", "stretch_polylines", "GROW_SEEDS",
           "MAX_CORNERS", "MAX_STEPS", "distinct_three_finger_plans"]
from ._concurrent import (
    KEEP_PAIRS,
    LP_ROWS,
    SPLITS,
    Piece,
    _best_blocks,
    _Block,
    _leximin,
    best_found,
    concurrent_regions,
    spanning_arcs,
)
from ._growth import (
    GROW_SEEDS,
    MAX_CORNERS,
    MAX_STEPS,
    _grown_plans,
    grow_concurrent,
    stretch_polylines,
)
from ._pairs import _FreeStretches, _pair_plans, _plan, _tie_step, _with_third, free_stretch

#: Candidate triples per compiled call (:mod:`fcgrasp.grippers.three_fingers._concurrency`).
KERNEL_ROWS = 1024


#: With a measure other than ``min_region``, how many plans (the best by their smallest
#: region) the measure orders.
KEEP_FOR_MEASURE = 50


def three_finger_plans(polygon: Polygon, spec: PlanSpec, edges: Any = None,
                       progress: Any = None) -> list[GraspPlan]:
    """Ranked plans of three fingers with friction (``plan(part, fingers=3, mu=...)``).

    Candidate triples of features on distinct edges, and on two edges with two fingers
    side by side on one (their regions apart along it), come from
    :func:`~fcgrasp.pipeline.candidates` by decreasing bound (the shortest feature): each
    gets its best concurrent piece (:func:`concurrent_regions`), and the stream stops when
    no later triple can reach the ``top``-th smallest region found (branch and bound,
    exact for the pieces).  The two-finger plans with the third finger anywhere on the
    longest feature of another edge (mode ``"pair"``) are candidates too, read down the
    two-finger list as far as one can rank (:func:`_pair_plans`).  Ranked as
    :func:`fcgrasp.pipeline.rank` ranks: the measure ``spec.rank_by`` (of the
    :data:`KEEP_FOR_MEASURE` best by smallest region when it is not ``min_region``),
    the leximin order, the geometric key.  ``progress(done, total)`` counts candidate
    triples.

    >>> from fcgrasp.io.parts import demo_part
    >>> from fcgrasp.pipeline import plan_spec
    >>> best = three_finger_plans(demo_part("triangle"), plan_spec(fingers=3, mu=0.5,
    ...                                                          gravity=None, top=1))[0]
    >>> best.mode, len(best.edges), best.contact_type
    ('concurrent', 3, 'friction')
    """
    if not spec.shape.lp:
        raise ValueError("three_finger_plans plans three fingers with friction "
                         "(fingers=3, gravity=None)")
    F = features(polygon, spec.mu, spec.hand, edges)
    size = polygon.size
    if spec.along_boundary:
        # numba starts now (the rows run compiled): then so does the stretch search,
        # from its first configuration (fcgrasp.core.jit.started)
        _concurrency.available()
    keep = None if spec.top is None else (spec.top if spec.rank_by == "min_region" else
                                          max(spec.top, KEEP_FOR_MEASURE))
    grow = (spec.along_boundary and spec.hand is None and edges is None
             and crosses_a_vertex(polygon, spec.mu, spec.margin))
    # two fingers that hold on their own, first: a triple whose smallest region cannot
    # reach the top-th of them cannot rank (on a smooth outline of equal edges, where
    # every triple's bound ties, this is what ends the search)
    # the first of them (KEEP_PAIRS, or keep); more after the triples, as far as one
    # can rank among every candidate (_pair_plans)
    pairs, more = _pair_plans(polygon, spec, edges, F, keep, first=True)
    floor = 0.0
    if keep is not None and len(pairs) >= keep:
        floor = sorted((float(min(p.lengths)) for p in pairs), reverse=True)[keep - 1] \
            - 2 * RANK_TOL * size
    plans = _concurrent_plans(polygon, spec, edges, F, keep, floor, grow, progress)[0]
    if more is not None and keep is not None:
        mins = sorted((float(min(p.lengths)) for p in plans + pairs), reverse=True)
        level = mins[keep - 1] if len(mins) >= keep else 0.0
        ask, below, stretches = more
        if below > level:
            pairs = _pair_plans(polygon, spec, edges, F, keep, level=level, start=ask,
                                stretches=stretches)[0]
    plans += pairs
    return _ranked(polygon, spec, plans, keep)


def _concurrent_plans(polygon: Polygon, spec: PlanSpec, edges: Any, F: Any,
                      keep: int | None, pair_floor: float, grow: bool, progress: Any = None,
                      grown: list[GraspPlan] | None = None, solved: _Solved | None = None
                      ) -> tuple[list[GraspPlan], float, list[GraspPlan]]:
    """The concurrent plans of :func:`three_finger_plans` (single edges, and with
    ``grow`` those grown along the boundary from the :data:`GROW_SEEDS` best): every
    triple whose smallest region reaches ``pair_floor`` and the ``keep``-th largest
    (all of them where ``keep`` is None and ``pair_floor`` 0), by branch and bound.
    Returns them, a level every concurrent plan of a single-edge triple left out is
    below (-inf: none was), and the grown plans alone: the same whatever ``keep`` and
    ``pair_floor`` (their seeds are read whatever the floor), so a caller that asks
    again passes them as ``grown``, and ``solved`` (:class:`_Solved`), the rows solved
    and the pieces placed by the calls before, which a call reads instead of solving
    them again."""
    size = polygon.size
    floor = pair_floor
    bounded = keep is not None or floor > 0
    # the rows that may rank, in the order found: while fewer than keep, all of them;
    # then those within the tie tolerance of the keep-th largest level (``levels``
    # theirs; sorted once at the end: on a flattened circle thousands tie, and sorting
    # and counting them at each batch cost more than solving the batch)
    found: list[tuple[float, tuple[int, ...], _Block]] = []
    levels = np.zeros(0)
    # the GROW_SEEDS best rows to grow along the boundary, exact ties (to PIECE_TIE of
    # the size) in the order found: (-level step, order, level, row, block)
    seeds: list[tuple[int, int, float, tuple[int, ...], _Block]] = []
    seed_step: int | None = None        # when full: rows with a bound of no more steps
    order = 0
    total = search_size(polygon, spec, edges).rows
    done = 0

    def useful(bnd: FloatArray) -> np.ndarray:
        out = bnd >= floor
        if grow:
            out |= (_tie_step(bnd, size) > seed_step) if seed_step is not None else True
        return out

    stream = candidates(polygon, spec, edges) if solved is None else \
        solved.batches(polygon, spec, edges)
    for number, batch in enumerate(stream):
        if bounded and not useful(np.array([batch.ceiling]))[0]:
            break
        rows = np.asarray(batch.feats, dtype=int)
        bound = np.asarray(batch.bound, dtype=float)
        # rows per program: one compiled call takes many more than one HiGHS program
        step = KERNEL_ROWS if _concurrency.available() else LP_ROWS
        for start in range(0, len(rows), step):
            sub, bnd = rows[start:start + step], bound[start:start + step]
            pick = useful(bnd) if bounded else None
            if pick is None or pick.any():
                if solved is not None:
                    got = [(lv * size, row, blk) for row, blk, lv in
                           solved.holding(F, (number, start), sub, pick, spec.margin_rad,
                                          size)]
                else:
                    sub = sub if pick is None else sub[pick]
                    res = _best_blocks(F.a[sub], F.b[sub], F.center[sub], F.half[sub],
                                       spec.margin_rad, size)
                    got = [(lv * size, tuple(int(f) for f in row), blk)
                           for row, (blk, lv) in zip(sub, res, strict=True)
                           if blk is not None and lv > 0]
                new = [g for g in got if keep is None or g[0] >= floor]
                found += new
                if keep is not None and new:
                    levels = np.concatenate([levels, [g[0] for g in new]])
                if grow:
                    # two fingers side by side on one edge are not grown along it
                    for lv, row, blk in got:
                        if blk.order:
                            continue
                        seeds.append((-int(_tie_step(lv, size)), order, lv, row, blk))
                        order += 1
                    seeds.sort(key=lambda r: r[:2])
                    del seeds[GROW_SEEDS:]
                    if bounded and len(seeds) == GROW_SEEDS:
                        seed_step = -seeds[-1][0]
                if keep is not None and len(found) >= keep:
                    last = float(np.partition(levels, levels.size - keep)[levels.size - keep])
                    cut = last - 2 * RANK_TOL * size        # the keep-th and its ties
                    hold = levels >= cut
                    if not hold.all():
                        found = [found[k] for k in np.flatnonzero(hold)]
                        levels = levels[hold]
                    floor = max(pair_floor, cut)
            done += step
            if progress is not None:
                progress(min(done, total), total)
            if bounded and len(bnd) and not useful(bnd[-1:])[0]:
                break
    if keep is not None and len(found) >= keep:    # cut: never fewer than keep again
        found.sort(key=lambda r: -r[0])
    plans = []
    for lv, row, blk in found:
        if bounded and lv < floor:
            continue
        piece = solved.piece(row, blk) if solved is not None else _leximin(blk)
        if piece is None:
            continue
        ends = np.stack([F.a[list(row)] + (piece.lo * size)[:, None] * blk.t0,
                         F.a[list(row)] + (piece.hi * size)[:, None] * blk.t0], axis=1)
        plans.append(_plan(polygon, spec, tuple(int(F.edge[f]) for f in row), ends,
                           "concurrent"))
    if not grow:
        grown = []
    elif grown is None:
        grown = _grown_plans(polygon, spec, [(lv, row, blk) for *_, lv, row, blk in seeds], F)
    plans += grown
    # bounded: a row left out had a bound below the floor of its time, or a level
    # below the last
    return plans, floor if bounded else -np.inf, grown


class _Solved:
    """What the rounds of :func:`distinct_three_finger_plans` solve again: each round
    runs :func:`_concurrent_plans` from the start, with a lower floor and a larger
    ``keep``, so it meets the rows of the rounds before.  A row's best piece
    (:func:`~fcgrasp.grippers.three_fingers._concurrent._best_blocks`) and its leximin placement
    (:func:`~fcgrasp.grippers.three_fingers._concurrent._leximin`) depend on its three features
    only, so they are kept by the row's feature indices and read back as they were."""

    def __init__(self) -> None:
        self._pieces: dict[tuple[int, ...], Any] = {}
        #: per chunk of the candidates (batch number, first row): its rows, which of
        #: them are solved, and the pieces of those that hold, by place
        self._chunks: dict[tuple[int, int], tuple[np.ndarray, np.ndarray,
                                                  dict[int, tuple[_Block, float]]]] = {}
        #: the candidates' stream (and what it was asked of), the batches made so far
        self._stream: tuple[Any, Iterator[Any]] | None = None
        self._made: list[Any] = []

    def batches(self, polygon: Polygon, spec: PlanSpec, edges: Any) -> Iterator[Any]:
        """:func:`~fcgrasp.pipeline.candidates` of the part, each batch made once: a
        round reads the batches the rounds before made, then goes on with the stream
        where they left it (the stream depends on its arguments only: the same part and
        spec objects, the rounds', and the same edges)."""
        asked = (polygon, spec, None if edges is None else tuple(int(e) for e in edges))
        if self._stream is None or self._stream[0][0] is not polygon \
                or self._stream[0][1] is not spec or self._stream[0][2] != asked[2]:
            self._stream, self._made = (asked, candidates(polygon, spec, edges)), []
        k = 0
        while True:
            if k == len(self._made):
                batch = next(self._stream[1], None)
                if batch is None:
                    return
                self._made.append(batch)
            yield self._made[k]
            k += 1

    def holding(self, F: Any, key: tuple[int, int], chunk: np.ndarray,
                pick: np.ndarray | None, margin: float, size: float
                ) -> list[tuple[tuple[int, ...], _Block, float]]:
        """The rows of ``chunk[pick]`` (all with ``pick`` None) whose best piece holds
        (:func:`_best_blocks`: a block, a level above 0), in order, each ``(row, block,
        level)``; each row solved once.  The rounds meet the candidates' chunks again
        (the same rows, more or fewer of them picked), so a chunk's answers are kept by
        place and read in numpy: of millions of rows read (4.3 million in the eight
        rounds on ``demo:cam``), a few thousand hold, and a dictionary of every row cost
        more than solving them (3 s of 5.4).  Each call solves the rows picked and not
        yet solved, in order, in one batch; a chunk met with other rows is read
        afresh."""
        got = self._chunks.get(key)
        if got is None or got[0].shape != chunk.shape or not np.array_equal(got[0], chunk):
            got = self._chunks[key] = (chunk.copy(), np.zeros(len(chunk), dtype=bool), {})
        rows, done, holds = got
        at = np.arange(len(chunk)) if pick is None else np.flatnonzero(pick)
        need = at[~done[at]]
        if need.size:
            idx = rows[need]
            done[need] = True
            for r, blk, lv in best_found(F.a[idx], F.b[idx], F.center[idx], F.half[idx],
                                         margin, size):
                if lv > 0:
                    holds[int(need[r])] = (blk, lv)
        return [(tuple(rows[k].tolist()), *holds[k]) for k in sorted(holds)
                if pick is None or pick[k]]

    def piece(self, row: tuple[int, ...], blk: _Block) -> Any:
        """:func:`_leximin` of the best piece ``blk`` of ``row``, placed once."""
        if row not in self._pieces:
            self._pieces[row] = _leximin(blk)
        return self._pieces[row]


def distinct_three_finger_plans(polygon: Polygon, spec: PlanSpec, fraction: float,
                                depth: int | None = None, progress: Any = None
                                ) -> PlanList | None:
    """The ``spec.top`` best plans of :func:`three_finger_plans` along the boundary that
    are distinct alternatives (:func:`fcgrasp.model.distinct.distinct_plans` over the
    whole ranked list, exactly), or None where this search does not apply (another
    ``rank_by``, ``top=None``, a hand, no region covering a vertex; or its first read
    alone runs past the time budget and its grace: the caller then suppresses the
    ranked list as usual, whose pairs are then on single edges, cut short).

    The ranked list merges two sources, each read in rounds, and each with a level
    every plan it has not given is below:

    * the pair plans (two fingers that hold on their own, a free third), from rounds
      of the two-finger stretch search that leave out the configurations whose pair
      plan is surely the same alternative as a plan kept so far
      (:meth:`~fcgrasp.model.stretches.StretchSearch.pairs` with ``third``: on a curved
      outline one grasp has hundreds of shifted copies, which filled the list) and
      those already read; a round's level is its last configuration's (its ties all
      read), and a pair plan's smallest region is at most its two fingers';
    * the concurrent plans (:func:`_concurrent_plans`), down to the pairs' level and
      the ``keep``-th best, ``keep`` doubled when they are what holds the reading back.

    The plans read that reach both levels (the concurrent one by two rounding steps
    of the ranking; the pairs' by the two-finger search's tie tolerance, as
    :func:`~fcgrasp.grippers._boundary.distinct_boundary_plans` reads them) come
    before every plan not read, so they are fed to suppression in rank order
    (:class:`~fcgrasp.model.distinct.Suppression`), until ``top`` are kept; a plan
    left out is dropped by suppression anyway, and dropped plans change nothing.
    Each kept plan's ``similar`` lists the plans it stands for among those read.

    A round that keeps no new plan makes the next read ``READ_GROWTH`` (twice) as
    many; with ``depth``, the reading stops once ``depth`` times ``top`` two-finger
    plans are read (as the ranked list's depth does for the other grippers): a copy
    is left out only where every free stretch its third finger can have (a region may
    end on a vertex and free the edge beyond; two free stretches may be within an edge
    of one length) makes it a copy.  ``progress(kept, top)`` after each round and each
    batch of the concurrent search.  The reading also stops when the time budget ends
    (:func:`fcgrasp.core.budget.deadline`) or a round's collection would exceed
    ``spec.max_memory``; stopped early, the plans kept are an exact prefix of the
    complete answer, returned incomplete (:class:`~fcgrasp.model.plans.PlanList`) with
    the level of the last finished search as the bound on every further alternative."""
    top = spec.top
    if top is None or spec.rank_by != "min_region" or fraction <= 0 \
            or spec.hand is not None or not spec.along_boundary \
            or not crosses_a_vertex(polygon, spec.mu, spec.margin):
        return None
    F = features(polygon, spec.mu, None, None)
    size = polygon.size
    _concurrency.available()                 # numba starts: the stretch search compiled
    band = 4 * RANK_TOL * size               # above the concurrent level, after rounding
    two = replace(spec, fingers=2, top=None, rank_by="min_region")
    suppression = Suppression(fraction, size)
    stretches = StretchSearch(polygon, spec.mu, spec.margin, max_bytes=spec.max_memory)
    free = _FreeStretches(polygon)
    read: list[GraspPlan] = []              # two-finger plans read: left out by name
    given: set[Any] = set()
    pairs: list[GraspPlan] = []
    others: list[GraspPlan] = []
    fed: set[Any] = set()                   # the (key, mode) of the plans fed
    grown: list[GraspPlan] | None = None
    solved = _Solved()
    keys: dict[int, Any] = {}              # each plan's rank key, once (ranked_keyed)
    ask = keep = max(2 * top, DISTINCT_READ)
    pair_level = other_level = np.inf
    cap = np.inf if depth is None else depth * top
    # each batch of the concurrent search a chance to report (and to be cancelled)
    beat = None if progress is None else \
        (lambda done, total: progress(len(suppression.kept), top))
    stopped: str | None = None
    level = np.inf                      # every plan not fed is below it

    def feed(line: float) -> None:
        """The plans read down to ``line``, in rank order, to suppression, each grasp
        once across the rounds, until ``top`` are kept."""
        for key, p in ranked_keyed(polygon, spec.rank_by, pairs + others, keys=keys):
            if float(min(p.lengths)) < line:
                break
            if key in fed:
                continue
            fed.add(key)
            if suppression.add(p) and len(suppression.kept) == top:
                break

    while len(suppression.kept) < top:
        if other_level <= pair_level - band:    # the pairs hold the reading back
            if len(read) >= cap:
                stopped = "depth"
                break
            try:
                got = stretches.pairs(top=ask, ties=True, exclude=suppression.kept,
                                      fraction=fraction, seen=read, third=True)
            except BudgetExhausted as exc:
                if not read and str(exc) == "time_limit":
                    # the first read alone runs past the budget and its grace: the
                    # ranked list, cut short, suppressed (the caller's rounds)
                    return None
                stopped = str(exc) or "time_limit"
                break
            new = two_finger_plans_of(polygon, two, got, given)
            read += new
            pairs += [q for q in (_with_third(polygon, spec, p, F, free) for p in new)
                      if q is not None]
            below = unread_below(got, ask)
            pair_level = -np.inf if below is None else below
        else:
            keep *= 2
        if other_level > pair_level - band:
            # read a band below the pairs' level: those at it then come first
            others, other_level, grown = _concurrent_plans(polygon, spec, None, F, keep,
                                                           pair_level - band, True, beat,
                                                           grown=grown, solved=solved)
        line = max(pair_level, other_level + band)
        had = len(suppression.kept)
        feed(line)
        level = line
        if progress is not None:        # plans kept of top, after each round
            progress(len(suppression.kept), top)
        if line == -np.inf or len(suppression.kept) >= top:
            break
        if exhausted():
            stopped = stop_reason()
            break
        if len(suppression.kept) == had:
            ask *= READ_GROWTH              # copies the search cannot leave out
    kept = suppression.plans()[:top]
    if stopped is None:
        return PlanList(kept)
    bound = float(level) if np.isfinite(level) else None
    if len(kept) < top:
        # the plans read below the level, in their order: each holds, but a plan not
        # read may rank before them (not an exact prefix); the plans above the level
        # are all read, so the complete answer's plans not among these are below it
        feed(-np.inf)
        more = suppression.plans()[:top]
        if len(more) > len(kept):
            return incomplete(more, stopped, bound, exact=False)
    return incomplete(kept, stopped, bound)


def _ranked(polygon: Polygon, spec: PlanSpec, plans: list[GraspPlan], keep: int | None
            ) -> list[GraspPlan]:
    """Plans in :func:`~fcgrasp.model.plans.rank_key` order (the measure of the ``keep`` best
    by the leximin order), each grasp once."""
    keys = [leximin_key(p.lengths, polygon.size) for p in plans]
    order = sorted(range(len(plans)), key=keys.__getitem__)
    if keep is not None and len(order) > keep:
        # the plans tied with the keep-th as well: the geometry orders them
        last = keys[order[keep - 1]]
        order = [k for i, k in enumerate(order) if i < keep or keys[k] == last]
    return ranked_unique(polygon, spec, [plans[k] for k in order])
