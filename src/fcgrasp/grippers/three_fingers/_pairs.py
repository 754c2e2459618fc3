"""Three fingers with friction: two fingers that hold on their own and a third on the
longest free stretch (mode ``pair``; part of :mod:`fcgrasp.grippers.three_fingers`)."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from ...core import budget
from ...core._checks import FloatArray
from ...core.tolerances import PIECE_TIE, RANK_TOL
from ...model.plans import GraspPlan
from ...model.polygon import Polygon, check_polygon
from ...model.stretches import StretchSearch, crosses_a_vertex
from ...pipeline import PlanSpec, search
from .._boundary import regions_plan, stretch_plans_read, two_finger_plans_of, unread_below
from ._concurrent import KEEP_PAIRS


def _plan(polygon: Polygon, spec: PlanSpec, edges: tuple[int, ...], regions: FloatArray,
          mode: str) -> GraspPlan:
    regions = np.asarray(regions, float)
    return regions_plan(polygon, spec, regions, tuple((e,) for e in edges),
                        np.hypot(*(regions[:, 1] - regions[:, 0]).T), "friction", mode)


def _tie_step(length: Any, size: float) -> Any:
    """Lengths in steps of :data:`~fcgrasp.core.tolerances.PIECE_TIE` of the part's size:
    two levels of one step tie (the order found decides between them)."""
    return np.round(np.asarray(length) / size / PIECE_TIE)


def _pair_plans(polygon: Polygon, spec: PlanSpec, edges: Any, F: Any,
                keep: int | None, level: float = 0.0, first: bool = False,
                start: int | None = None, stretches: StretchSearch | None = None
                ) -> tuple[list[GraspPlan], tuple[int, float, StretchSearch | None] | None]:
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
    read on, the smallest region every pair not read is below (None: nothing left
    that can rank) and the stretch search to read on with (``stretches``).

    The first read is the ranked two-finger search's (by the smallest region: where the
    two fingers set the pair plans' level, it is the only read).  Each deeper read
    along the boundary reads the list in the order of each pair plan's bound
    (:data:`PAIR_CAP`: the smaller of its two fingers' smallest region and the third
    finger's widest free stretch, :meth:`~fcgrasp.model.stretches.StretchSearch.pairs`
    with ``third``), one search read deeper each time: on a smooth outline at a wide
    cone the two fingers' regions outrun the free stretch by far, and the list by the
    two fingers' regions alone reaches the pair plans' level only after millions of
    configurations.  Every pair plan not read is below a read's level either way (below
    its bound, which is below its two fingers' region)."""
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
        if boundary and PAIR_CAP and (out or start) and stretches is None:
            stretches = StretchSearch(polygon, spec.mu, spec.margin,
                                      max_bytes=spec.max_memory, share=PAIR_SHARE)
        if boundary and out:
            # a deeper read: the time budget may end it, and the pairs read are kept
            # (each plan holds; a complete read may rank others first)
            try:
                with budget.interruptible():
                    got, every, below = _read(polygon, two, stretches)
            except budget.BudgetExhausted:
                budget.cut_short()
                return out, None
        elif boundary:
            try:
                got, every, below = _read(polygon, two, stretches)
            except budget.BudgetExhausted:
                # the first read alone runs past the budget and its grace: the pairs of
                # regions on single edges instead, cut short (as two fingers do)
                budget.cut_short()
                boundary, free, stretches = False, None, None
                continue
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
        if budget.cut_if_over():
            return out, None
        ask = 2 * max(ask, len(got))
        if first and len(out) >= keep:  # enough for the triples' floor
            return out, (ask, below, stretches)


#: Whether :func:`_pair_plans` reads the two-finger list along the boundary in the order
#: of the pair plans' bounds (True), or by the two fingers' smallest region alone (False:
#: the reference, :func:`~fcgrasp.grippers._boundary.stretch_plans_read`).
PAIR_CAP = True


#: The share of the best two-finger region from which the bound-ordered read first
#: collects configurations (:class:`~fcgrasp.model.stretches.StretchSearch`'s
#: ``share``; lowered as the reading needs): the ranked list's pair plans lie near the
#: top, where a distinct search's rounds reach far below it.
PAIR_SHARE = 0.9


def _read(polygon: Polygon, two: PlanSpec, stretches: StretchSearch | None
          ) -> tuple[list[GraspPlan], bool, float]:
    """The two-finger plans of one read of ``two.top`` configurations (with ties), whether
    they are every one, and the level every configuration not read is below: by the pair
    plans' bounds from ``stretches``, or by the smallest region
    (:func:`~fcgrasp.grippers._boundary.stretch_plans_read`) without it."""
    if stretches is None:
        return stretch_plans_read(polygon, two)
    pairs = stretches.pairs(top=two.top, ties=True, third=True)
    below = unread_below(pairs, two.top)
    return two_finger_plans_of(polygon, two, pairs), below is None, \
        0.0 if below is None else below


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
