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
from itertools import product
from typing import Any

import numpy as np

from ..core import budget
from ..core._angles import wrap
from ..core._checks import FloatArray, check_mu_scalar, check_scalar
from ..core.budget import BudgetExhausted, PlanList, exhausted, incomplete
from ..core.tolerances import LEVEL_TIE, PIECE_TIE, RANK_TOL
from ..model.distinct import Suppression
from ..model.plans import GraspPlan, leximin_key
from ..model.polygon import Polygon, check_polygon
from ..model.stretches import StretchSearch, crosses_a_vertex
from ..pipeline import (
    PlanSpec,
    candidates,
    features,
    search,
    search_size,
)
from . import _concurrency
from ._boundary import (
    DISTINCT_READ,
    ranked_keyed,
    ranked_unique,
    regions_plan,
    stretch_plans_read,
    two_finger_plans_of,
    unread_below,
)

__all__ = ["spanning_arcs", "Piece", "concurrent_regions", "three_finger_plans", "SPLITS",
           "KEEP_PAIRS", "free_stretch", "grow_concurrent", "stretch_polylines", "GROW_SEEDS",
           "MAX_CORNERS", "MAX_STEPS", "distinct_three_finger_plans"]
from ._concurrent import (
    _SIDES,
    KEEP_PAIRS,
    LP_ROWS,
    SPLITS,
    Piece,
    _best_blocks,
    _Block,
    _lengths,
    _leximin,
    _smallest,
    _solve_blocks,
    best_found,
    concurrent_regions,
    first_best,
    spanning_arcs,
)


def _plan(polygon: Polygon, spec: PlanSpec, edges: tuple[int, ...], regions: FloatArray,
          mode: str) -> GraspPlan:
    regions = np.asarray(regions, float)
    return regions_plan(polygon, spec, regions, tuple((e,) for e in edges),
                        np.hypot(*(regions[:, 1] - regions[:, 0]).T), "friction", mode)


#: Candidate triples per compiled call (:mod:`fcgrasp.grippers._concurrency`).
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
        # from its first configuration (fcgrasp.core.kernels.started)
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
        ask, below = more
        if below > level:
            pairs = _pair_plans(polygon, spec, edges, F, keep, level=level, start=ask)[0]
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
    (:func:`~fcgrasp.grippers._concurrent._best_blocks`) and its leximin placement
    (:func:`~fcgrasp.grippers._concurrent._leximin`) depend on its three features
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
    ``rank_by``, ``top=None``, a hand, no region covering a vertex: the caller then
    suppresses the ranked list as usual).

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

    A round that keeps no new plan reads twice as many the next time; with ``depth``,
    the reading stops once ``depth`` times ``top`` two-finger plans are read (as the
    ranked list's depth does for the other grippers): where a third finger's free
    stretch is not known before the regions are placed (a region may end on a vertex
    and free the edge beyond), copies are not left out, and a curved outline has
    thousands of them.  ``progress(kept, top)`` after each round and each batch of the
    concurrent search.  The reading also stops when the time budget ends
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
    while len(suppression.kept) < top:
        if other_level <= pair_level - band:    # the pairs hold the reading back
            if len(read) >= cap:
                stopped = "depth"
                break
            try:
                got = stretches.pairs(top=ask, ties=True, exclude=suppression.kept,
                                      fraction=fraction, seen=read, third=True)
            except BudgetExhausted as exc:
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
        for key, p in ranked_keyed(polygon, spec.rank_by, pairs + others, keys=keys):
            if float(min(p.lengths)) < line:
                break
            if key in fed:                  # each grasp once, across the rounds
                continue
            fed.add(key)
            if suppression.add(p) and len(suppression.kept) == top:
                break
        level = line
        if progress is not None:        # plans kept of top, after each round
            progress(len(suppression.kept), top)
        if line == -np.inf or len(suppression.kept) >= top:
            break
        if exhausted():
            stopped = "time_limit"
            break
        if len(suppression.kept) == had:
            ask *= 2                        # copies the search cannot leave out
    kept = suppression.plans()[:top]
    if stopped is None:
        return PlanList(kept)
    if len(kept) < top:
        # the plans read below the level, in their order: each holds, but a plan not
        # read may rank before them (not an exact prefix)
        for key, p in ranked_keyed(polygon, spec.rank_by, pairs + others, keys=keys):
            if key in fed:
                continue
            fed.add(key)
            if suppression.add(p) and len(suppression.kept) == top:
                break
        more = suppression.plans()[:top]
        if len(more) > len(kept):
            return incomplete(more, stopped, None, exact=False)
    return incomplete(kept, stopped, float(level) if np.isfinite(level) else None)


#: Concurrent plans of single edges grown along the boundary (the best ones).
GROW_SEEDS = 5
#: A grown configuration has at most this many corner grasps (points per region, multiplied).
MAX_CORNERS = 216
#: Growth steps at most (each lengthens the shortest regions by one edge each).
MAX_STEPS = 60


def _stretch_cone(polygon: Polygon, stretch: tuple[int, ...], mu: float
                  ) -> tuple[float, float]:
    """The friction cone every contact of a stretch has (centre and half-width of the
    force directions; negative where none): the intersection of its edges' cones (a
    fingertip on an interior vertex may push along any normal of the vertex's fan, whose
    cones all hold that intersection)."""
    n = polygon.normals[list(stretch)]
    c = np.arctan2(-n[:, 1], -n[:, 0])
    d = wrap(c - c[0])
    phi = float(np.arctan(mu))
    lo, hi = c[0] + d.max() - phi, c[0] + d.min() + phi
    return float((lo + hi) / 2), float((hi - lo) / 2)


def _stretch_blocks(polygon: Polygon, stretches: tuple[tuple[int, ...], ...], mu: float,
                    margin: float, sides: Any = None) -> list[_Block]:
    """The convex pieces of three fingers on three stretches (in units of the part's size):
    the sub-arcs of :func:`spanning_arcs` of the stretches' common cones times the sides
    (default all eight)."""
    size = polygon.size
    cones = [_stretch_cone(polygon, st, mu) for st in stretches]
    center = np.array([c for c, _ in cones])
    half = np.array([h for _, h in cones])
    if np.any(half <= margin):
        return []
    first = [st[0] for st in stretches]
    last = [st[-1] for st in stretches]
    L = polygon.lengths
    const = np.array([0.0 if len(st) == 1 else float(L[list(st[:-1])].sum())
                      for st in stretches]) / size
    inner = tuple(polygon.starts[list(st[1:])] / size for st in stretches)
    args = (polygon.starts[first] / size, polygon.tangents[first], L[first] / size,
            polygon.starts[last] / size, polygon.tangents[last], L[last] / size, const,
            inner)
    return [_Block(*args, lo, hi, np.asarray(sigma, float), 0)
            for lo, hi in spanning_arcs(center, half, margin)
            for sigma in (_SIDES if sides is None else sides)]


def _stretch_moves(polygon: Polygon, stretches: tuple[tuple[int, ...], ...], grow: Any
                   ) -> list[tuple[tuple[int, ...], ...]]:
    """Configurations with every region marked in ``grow`` one edge longer, each at one
    of its ends (on edges no region covers, never a whole ring): the smallest region can
    only grow when every region as short does."""
    used = {e for st in stretches for e in st}
    options = []
    for st, g in zip(stretches, grow, strict=True):
        ring = int(np.sum((polygon.rings == polygon.rings[st[0]]) & polygon.usable))
        opts = []
        if g and len(st) + 1 < ring:
            for new, added in (((polygon.previous_edge(st[0]), *st), polygon.previous_edge(st[0])),
                               ((*st, polygon.next_edge(st[-1])), polygon.next_edge(st[-1]))):
                if added not in used and polygon.usable[added]:
                    opts.append(new)
        options.append(opts if g else [st])
    out = []
    for combo in product(*options):
        edges = [e for st in combo for e in st]
        if len(edges) == len(set(edges)):
            out.append(tuple(combo))
    return out


def _corner_count(stretches: tuple[tuple[int, ...], ...]) -> int:
    return int(np.prod([len(st) + 1 for st in stretches]))


def _best_piece(blocks: list[_Block], xs: list[FloatArray | None]
                ) -> tuple[float, _Block | None, FloatArray | None]:
    got = [(_smallest(blk, x), blk, x) for blk, x in zip(blocks, xs, strict=True)
           if x is not None]
    return got[first_best([g[0] for g in got])] if got else (-1.0, None, None)


def _bottlenecks(blk: _Block, level: float) -> np.ndarray:
    """The regions of a piece that cannot be longer than ``level`` (the others kept at
    least that long): the ones that must all grow for the smallest to grow.  Decided by
    one program per region, so not by which optimal solution a solver returned."""
    fixed = np.full(3, level)
    out = np.ones(3, dtype=bool)
    for i in range(3):
        x = _solve_blocks([blk], fixed=fixed, grow=i)[0]
        out[i] = x is None or _lengths(blk, x)[i] <= level * (1 + LEVEL_TIE)
    return out


def grow_concurrent(polygon: Polygon, edges: Any, mu: float, margin: float,
                    sigma: Any = None) -> tuple[tuple[tuple[int, ...], ...], Piece] | None:
    """Concurrent regions of three fingers grown along the boundary from three edges.

    Each step solves, in one linear program, every configuration with the regions as
    short as the smallest one edge longer (:func:`_stretch_moves`; every contact of a
    stretch keeps the cone common to its edges, so a piece of it is convex as on single
    edges) with the sides ``sigma`` of the meeting point (default: all eight), and takes
    the best that lengthens the smallest region; it stops when none does.  The configuration reached
    is solved over every piece and its levels made leximin-optimal.  Returns the
    stretches and the :class:`Piece` (positions in the part's units), or None when the
    edges hold no concurrent grasp.  A safe lower bound, as on single edges: every grasp
    of the regions is force closure.

    >>> import numpy as np
    >>> a = np.linspace(0, 2 * np.pi, 60, endpoint=False)
    >>> part = Polygon(np.c_[40 * np.cos(a), 25 * np.sin(a)])
    >>> st, piece = grow_concurrent(part, (0, 20, 40), mu=0.5, margin=np.radians(0.5))
    >>> min(len(s) for s in st) > 1, bool(piece.levels.min() > part.lengths[0])
    (True, True)
    """
    polygon = check_polygon(polygon)
    idx = polygon.check_edges(edges, "edges")
    if len(idx) != 3 or len(set(idx)) != 3:
        raise ValueError(f"edges must be three distinct edges, got {edges!r}")
    mu = check_mu_scalar(mu, "mu")
    margin = check_scalar(margin, "margin", nonnegative=True)
    if sigma is not None and (np.shape(sigma) != (3,) or not np.all(np.abs(sigma) == 1)):
        raise ValueError(f"sigma must be three sides, each 1 or -1, got {sigma!r}")
    sides = None if sigma is None else [np.asarray(sigma, float)]
    cur: tuple[tuple[int, ...], ...] = tuple((e,) for e in idx)
    blocks = _stretch_blocks(polygon, cur, mu, margin, sides)
    level, blk, x = _best_piece(blocks, _solve_blocks(blocks)) if blocks else (-1.0, None, None)
    if blk is None or x is None:
        return None
    for _ in range(MAX_STEPS):
        # the regions as short as the smallest must all grow for it to grow
        short = _bottlenecks(blk, level)
        moves = [m for m in _stretch_moves(polygon, cur, short)
                 if _corner_count(m) <= MAX_CORNERS]
        per = [_stretch_blocks(polygon, m, mu, margin, [blk.sigma]) for m in moves]
        flat = [b for bs in per for b in bs]
        if not flat:
            break
        xs = _solve_blocks(flat)
        better = []
        k = 0
        for m, bs in zip(moves, per, strict=True):
            lv, b, xb = _best_piece(bs, xs[k:k + len(bs)])
            k += len(bs)
            if b is not None and xb is not None and lv > level * (1 + RANK_TOL):
                better.append((lv, m, b, xb))
        if not better:
            break
        level, cur, blk, x = better[first_best([g[0] for g in better])]
    blocks = _stretch_blocks(polygon, cur, mu, margin)
    _, blk, _ = _best_piece(blocks, _solve_blocks(blocks))
    piece = None if blk is None else _leximin(blk)
    if piece is None:
        return None
    size = polygon.size
    return cur, replace(piece, lo=piece.lo * size, hi=piece.hi * size,
                        levels=piece.levels * size, witness=piece.witness * size)


def _grown_plans(polygon: Polygon, spec: PlanSpec,
                 found: list[tuple[float, tuple[int, ...], _Block]], F: Any
                 ) -> list[GraspPlan]:
    """The :data:`GROW_SEEDS` best concurrent plans of single edges grown along the
    boundary (:func:`grow_concurrent`): the plans whose regions leave their edges."""
    out = []
    seen = set()
    for _, row, blk in found[:GROW_SEEDS]:
        got = grow_concurrent(polygon, [int(F.edge[f]) for f in row], spec.mu,
                              spec.margin_rad, blk.sigma)
        if got is None or max(len(st) for st in got[0]) == 1 or got[0] in seen:
            continue                    # two seeds may grow into one configuration
        stretches, piece = got
        seen.add(stretches)
        out.append(regions_plan(polygon, spec, stretch_polylines(polygon, stretches, piece),
                                stretches, piece.levels, "friction", "concurrent"))
    return out


def stretch_polylines(polygon: Polygon, stretches: Any, piece: Piece) -> list[FloatArray]:
    """The regions of a :class:`Piece` on stretches as polylines: from ``lo`` on each
    stretch's first edge through its interior vertices to ``hi`` on its last."""
    out = []
    for i, st in enumerate(stretches):
        a0, t0 = polygon.starts[st[0]], polygon.tangents[st[0]]
        a1, t1 = polygon.starts[st[-1]], polygon.tangents[st[-1]]
        out.append(np.concatenate([[a0 + piece.lo[i] * t0], polygon.starts[list(st[1:])],
                                   [a1 + piece.hi[i] * t1]]))
    return out


def _tie_step(length: Any, size: float) -> Any:
    """Lengths in steps of :data:`~fcgrasp.core.tolerances.PIECE_TIE` of the part's size:
    two levels of one step tie (the order found decides between them)."""
    return np.round(np.asarray(length) / size / PIECE_TIE)


def _pair_plans(polygon: Polygon, spec: PlanSpec, edges: Any, F: Any,
                keep: int | None, level: float = 0.0, first: bool = False,
                start: int | None = None) -> tuple[list[GraspPlan], tuple[int, float] | None]:
    """Two fingers that hold on their own (the exact two-finger plans) and a third
    anywhere on the longest feature of another edge: force closure whatever the third
    finger does.  Along the boundary (``spec.along_boundary``, no hand, no chosen edges,
    an outline where a region can cover a vertex) the two are the exact two-finger
    stretches (:func:`._boundary.stretch_plans_read`) and the third runs along the
    longest stretch of edges neither touches (:func:`free_stretch`): three fingers then
    never do worse than the two-finger stretches with the third finger so placed.

    Every two-finger plan is a candidate; ``keep`` given, the ranked two-finger list is
    read (at least :data:`KEEP_PAIRS` of it, or from ``start``, twice as many each
    time) until no plan after it can reach the ``keep``-th smallest region of those
    read, nor ``level`` (the ``keep``-th of the other candidates, found with the first
    pairs' floor: a pair's smallest region is at most its two fingers', which only
    falls along the list), so the pairs returned are all that can rank among the best
    ``keep`` or tie with the last (to the two-finger search's tie tolerance).  Returns
    them and, with ``first`` (the first read that has ``keep`` pairs only), where to
    read on and the smallest region every pair not read is below (None: nothing left
    that can rank)."""
    if edges is not None and len(set(int(e) for e in edges)) != 3:
        return [], None
    boundary = (spec.along_boundary and spec.hand is None and edges is None
                and crosses_a_vertex(polygon, spec.mu, spec.margin))
    size = polygon.size
    ask = None if keep is None else start or max(KEEP_PAIRS, keep)
    free = _FreeStretches(polygon) if boundary else None
    out: list[GraspPlan] = []
    while True:
        two = replace(spec, fingers=2, top=ask, rank_by="min_region",
                      along_boundary=boundary)
        if boundary and out:
            # a deeper read: the time budget may end it, and the pairs read are kept
            # (each plan holds; a complete read may rank others first)
            try:
                with budget.interruptible():
                    got, every, below = stretch_plans_read(polygon, two)
            except budget.BudgetExhausted:
                budget.cut_short()
                return out, None
        elif boundary:
            got, every, below = stretch_plans_read(polygon, two)
        else:
            got = search(polygon, two, edges=edges)
            every = ask is None or len(got) < ask
            # a plan not read ranks after the last read: no larger, to the rounding
            last = min((float(min(p.lengths)) for p in got), default=0.0)
            below = last * (1 + RANK_TOL) + 4 * RANK_TOL * size
        out = [q for q in (_with_third(polygon, spec, p, F, free) for p in got)
               if q is not None]
        if keep is None or ask is None or every:
            return out, None             # the whole list
        best = sorted((float(min(q.lengths)) for q in out), reverse=True)
        reach = max(level, best[keep - 1] if len(best) >= keep else 0.0)
        # every pair not read is below ``below``: none reaches the keep-th
        if below <= reach:
            return out, None
        if budget.exhausted():
            budget.cut_short()
            return out, None
        ask = 2 * max(ask, len(got))
        if first and len(out) >= keep:  # enough for the triples' floor
            return out, (ask, below)


def _with_third(polygon: Polygon, spec: PlanSpec, p: GraspPlan, F: Any,
                free: _FreeStretches | None) -> GraspPlan | None:
    """The two-finger plan ``p`` with a third finger anywhere on the longest stretch
    (``free``, the part's free stretches: along the boundary) or feature of the edges
    it does not touch; None where there is none."""
    if free is not None:
        run = free.longest({e for st in p.region_edges for e in st})
        if run is None:
            return None
        line = np.concatenate([polygon.starts[list(run[:1])], polygon.ends[list(run)]])
        return regions_plan(polygon, spec, [*p.regions, line], (*p.region_edges, run),
                            [*p.lengths, float(polygon.lengths[list(run)].sum())],
                            "friction", "pair")
    other = np.flatnonzero(~np.isin(F.edge, p.edges))
    if not other.size:
        return None
    f = int(other[np.argmax(F.lengths[other])])
    ends = np.concatenate([p.ends, np.stack([F.a[f], F.b[f]])[None]])
    return _plan(polygon, spec, (*p.edges, int(F.edge[f])), ends, "pair")


def free_stretch(polygon: Polygon, covered: Any) -> tuple[int, ...] | None:
    """The longest stretch (consecutive usable edges of one ring, in ring order, not the
    whole ring) none of whose edges is in ``covered`` (on a ring no edge of which is
    covered: all but its shortest edge); None when every edge is.  Of equally long ones,
    the first met: rings in order, each walked from just after its first covered edge
    (or its shortest).

    >>> sq = Polygon([[0, 0], [4, 0], [4, 3], [0, 3]])
    >>> free_stretch(sq, {0}), free_stretch(sq, set())
    ((1, 2, 3), (2, 3, 0))
    """
    polygon = check_polygon(polygon)
    covered = polygon.check_edges(list(covered), "covered") if len(covered) else []
    return _FreeStretches(polygon).longest(covered)


class _FreeStretches:
    """:func:`free_stretch` for many sets of covered edges on one part: each ring's
    usable edges walked once (``next_edge``), then every set read from the places of
    its covered edges (a plan covers a few runs of edges: the free runs are the gaps
    between them)."""

    def __init__(self, polygon: Polygon) -> None:
        self.polygon = polygon
        #: per edge: the number of its ring in ``rings`` (-1: none kept) and its place
        self.ring_of = np.full(polygon.n_edges, -1)
        self.place = np.zeros(polygon.n_edges, dtype=np.int64)
        #: per ring: its usable edges in walking order, twice over, the place of its
        #: shortest (first of ties), and the running sums of its lengths along two turns
        self.rings: list[tuple[np.ndarray, int, list[float]]] = []
        L = polygon.lengths
        for r in np.unique(polygon.rings):
            usable = np.flatnonzero((polygon.rings == r) & polygon.usable)
            if usable.size < 2:
                continue
            walk = [int(usable[0])]
            while len(walk) < usable.size:
                walk.append(polygon.next_edge(walk[-1]))
            cycle = np.array(walk)
            self.ring_of[cycle] = len(self.rings)
            self.place[cycle] = np.arange(cycle.size)
            shortest = int(usable[np.argmin(L[usable])])
            sums = np.concatenate(([0.0], np.cumsum(np.tile(L[cycle], 2)))).tolist()
            self.rings.append((np.tile(cycle, 2), int(self.place[shortest]), sums))

    def longest(self, covered: Any) -> tuple[int, ...] | None:
        """The longest free stretch (see :func:`free_stretch`); ``covered`` valid edges.

        Each ring is walked from just after its covered edge of least number (or its
        shortest edge, where none is covered: then all but that edge), and its free
        runs are the gaps between its covered places in that order.  A run's length is
        first read from the running sums (to their rounding), then the runs within
        :data:`~fcgrasp.core.tolerances.RANK_TOL` of the longest are summed as the
        plan sums them (numpy's sum of their lengths), and the first met of the
        longest is kept."""
        edges = np.fromiter(covered, dtype=np.int64)
        ring, place = self.ring_of[edges], self.place[edges]
        runs: list[tuple[np.ndarray, int, int, float]] = []  # walk, start, count, approx
        for k, (walk, shortest, sums) in enumerate(self.rings):
            m = walk.size // 2
            mine = ring == k
            if mine.any():
                first = int(edges[mine].argmin())           # least edge number
                start = int(place[mine][first]) + 1
                rel = np.sort((place[mine] - start) % m)    # the last is m - 1
                gaps = np.flatnonzero(np.diff(rel, prepend=-1) > 1)
                prev = np.concatenate(([-1], rel))[gaps]
                for a, n in zip(((start + prev + 1) % m).tolist(),
                                (rel[gaps] - prev - 1).tolist(), strict=True):
                    runs.append((walk, a, n, sums[a + n] - sums[a]))
            else:
                a = (shortest + 1) % m
                runs.append((walk, a, m - 1, sums[a + m - 1] - sums[a]))
        if not runs:
            return None
        top = max(r[3] for r in runs)
        L = self.polygon.lengths
        best: tuple[int, ...] | None = None
        best_len = -1.0
        for walk, a, n, approx in runs:
            if approx >= top * (1 - RANK_TOL):     # summed in another order: near it
                run = walk[a:a + n]
                length = float(L[run].sum())
                if length > best_len:
                    best, best_len = tuple(run.tolist()), length
        return best


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
