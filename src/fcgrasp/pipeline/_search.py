"""The running top, the exact branch and bound and the ranking of solved batches (part
of :mod:`fcgrasp.pipeline`; section 7.3 and 8)."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from dataclasses import replace
from functools import lru_cache, partial
from typing import Any

import numpy as np

from ..core._checks import FloatArray
from ..core._geom import RANK_DIGITS
from ..core.tolerances import RANK_TOL
from ..model.plans import GraspPlan, rank_key
from ..model.polygon import Polygon
from ..model.ranking import MEASURES
from . import _spec  # the search's tunables, read when used
from ._candidates import (
    EdgeSets,
    _bound_pad,
    _row_bounds,
    candidates,
    features,
    holding_rows,
    lex_survivors,
    search_size,
)
from ._pair_rows import SEED_ROWS, PairRows
from ._size import _reduce_rows
from ._solve import RowScores, Solved, _build_plans, _select, _smallest_region, solve
from ._spec import (
    MAP_WINDOW,
    PlanSpec,
)


class TopK:
    """The running top of a search: solved batches folded in as they come (the reduce
    of :func:`rank`), and the :attr:`floor` a row must reach to enter it.

    >>> from fcgrasp.io.parts import demo_part
    >>> from fcgrasp.pipeline import plan_spec
    >>> part, spec = demo_part("blob"), plan_spec(fingers=2, mu=0.3, top=2)
    >>> top = TopK(part, spec)
    >>> for batch in candidates(part, spec):
    ...     if batch.ceiling < top.floor:
    ...         break                       # no later row can enter the top
    ...     top.add(solve(part, spec, batch, floor=top.floor))
    >>> [p.edges for p in top.plans()]
    [(2, 5), (1, 4)]
    """

    def __init__(self, polygon: Polygon, spec: PlanSpec, edges: Any = None) -> None:
        self.polygon, self.spec, self.edges = polygon, spec, edges
        top = spec.top
        #: rows kept by the smallest region: the top, or with another measure the
        #: :data:`KEEP_FOR_MEASURE` best, which the measure then orders
        self.keep = None if top is None else (top if spec.rank_by == "min_region" else
                                              _spec.KEEP_FOR_MEASURE)
        self._parts: list[Solved] = []
        self._held = 0
        self._floor = 0.0
        self._key: FloatArray | None = None
        self._key_stale = False

    def add(self, solved: Solved) -> None:
        """Fold in a solved batch (from any process, in any order)."""
        if not len(solved.lengths):
            return
        self._parts.append(solved)
        self._held += len(solved.lengths)
        if self.keep is None:
            return
        if self._held > _reduce_rows(self.spec) + self.keep:
            # a running reduction: what the final selection would drop can go now
            merged = Solved.concat(self._parts)
            merged = merged.take(_select(merged.lengths, merged.cands.feats,
                                         self.polygon.size, self.keep))
            self._parts, self._held = [merged], len(merged.lengths)
        if self._held >= self.keep:
            mins = np.concatenate([_smallest_region(p.cands.feats, p.lengths)
                                   for p in self._parts])
            kth = float(np.partition(-mins, self.keep - 1)[self.keep - 1])
            # rounding of the ranking (leximin_key) is within RANK_TOL * size: a row
            # below this cannot tie the keep-th row
            self._floor = max(self._floor, -kth - 2 * RANK_TOL * self.polygon.size)
            self._key_stale = self.spec.rank_by == "min_region"

    @property
    def key(self) -> FloatArray | None:
        """The leximin key of the top's last row (ranked by the smallest region, once
        the top is full; None before, or with another measure): its region lengths
        sorted ascending, over the part's size, rounded as
        :func:`~fcgrasp.core._geom.leximin_key` rounds.  A row whose bounds cannot reach
        or tie it cannot enter the top (:func:`~fcgrasp.pipeline._candidates.lex_survivors`:
        on a flattened curve every short edge ties the top's smallest region, and the
        second smallest tells the rows apart)."""
        if self._key_stale:
            self._key_stale = False
            parts = [np.sort(np.where(p.cands.feats >= 0, p.lengths, np.inf), axis=1)
                     for p in self._parts]
            real = {int((p.cands.feats[0] >= 0).sum()) for p in self._parts}
            if len(real) == 1:          # rows of one layout (gravity's column or none)
                m = real.pop()
                L = np.concatenate([x[:, :m] for x in parts])
                L = L[np.all(L > 0, axis=1)]
                keep = self.keep or 0
                if len(L) >= keep > 0:
                    # the keep-th key's first length is the keep-th largest first
                    # length; only rows at or above it can come before it
                    first = np.round(L[:, 0] / self.polygon.size, RANK_DIGITS)
                    kth = np.partition(first, len(first) - keep)[len(first) - keep]
                    up = L[first >= kth]
                    keys = np.round(up / self.polygon.size, RANK_DIGITS)
                    order = np.lexsort(keys.T[::-1])         # the first length first
                    self._key = keys[order[len(keys) - keep]]
        return self._key

    @property
    def floor(self) -> float:
        """A row whose smallest region is below this cannot enter the top (0 until the
        top is full, and always 0 with ``top=None``)."""
        return self._floor

    def plans(self) -> list[GraspPlan]:
        """The best plans, best first: sorted by the measure ``spec.rank_by``
        (:mod:`fcgrasp.model.ranking`), then the leximin order of the region lengths, then
        :func:`~fcgrasp.model.plans.geometric_key`."""
        if not self._parts:
            return []
        polygon, spec, top = self.polygon, self.spec, self.spec.top
        s = Solved.concat(self._parts)
        if self.keep is not None:
            pick = _select(s.lengths, s.cands.feats, polygon.size, self.keep)
        else:
            pick = np.arange(len(s.lengths))
        F = features(polygon, spec.mu, spec.hand, self.edges)
        gravity = None if spec.gravity is None else np.array(spec.gravity)
        plans = _build_plans(polygon, F, s.cands, pick, s.lengths[pick], s.a[pick],
                             s.b[pick], s.mode[pick], spec.mu, spec.margin,
                             spec.contact_type, gravity, spec.disturbance)
        scores = MEASURES[spec.rank_by].score(plans) if plans else np.zeros(0)
        order = sorted(range(len(plans)), key=lambda k: rank_key(
            plans[k], polygon, spec.rank_by, float(scores[k])))
        plans = [plans[k] for k in order]
        return plans if top is None else plans[:top]


def search(polygon: Polygon, spec: PlanSpec, edges: Any = None, progress: Any = None,
           batch_size: int | None = None, map: Any = None, floor: float = 0.0,
           strict: bool = False,
           exclude: Callable[[np.ndarray], np.ndarray] | None = None,
           scores: RowScores | None = None) -> list[GraspPlan]:
    """The single-edge search, exact branch and bound: :func:`candidates` streams rows by
    decreasing bound, :func:`solve` drops the rows below the running top's
    :attr:`TopK.floor`, and the stream stops at the first batch whose ceiling is below
    it.  The same plans as solving every row (``rank`` of every batch), tested on the
    corpus for every ``rank_by``; with a measure other than ``min_region`` the floor is
    that of the :data:`KEEP_FOR_MEASURE` rows the measure orders.

    ``progress(done, total)`` counts candidate rows solved or pruned; ``batch_size`` as
    for :func:`candidates`.  ``map(function, batches)``, such as the built-in ``map``, an
    executor's ``map`` or one over a Dask client, solves :data:`MAP_WINDOW` batches at a
    time wherever it runs them (each with the floor known when the window was sent: a
    lower floor only keeps more rows, so the answer is the same).

    ``floor``: a smallest region a plan must reach to matter (the caller has ``top``
    plans at least that good elsewhere; rows below it are not solved).  ``strict``: a
    row that can at best tie the top's last on its smallest region is not solved either
    (exact ties are then kept in the order found, not all of them: on a flattened circle
    every row ties, and the search ends at once).  ``exclude(feats)``: which rows of a
    batch (True) are left out unsolved, as if they were not candidates (the rows a
    distinct search has read, or whose every plan is the same alternative as one it
    kept: :class:`~fcgrasp.grippers._distinct_rows.RowCopies`).  ``scores``: a
    :class:`~fcgrasp.pipeline._solve.RowScores` shared with earlier searches of the
    same part and spec (but ``top``): the rows it knows to be below the floor are
    dropped unsolved, and the rows solved here are added to it (without a ``map``: with
    one the rows are solved elsewhere).

    Four frictionless fingers (or three with gravity), once numba runs in the process:
    the rows that fail the force-direction test are dropped before anything else reads
    them (:func:`~fcgrasp.pipeline._candidates.holding_rows`: as the stream makes them,
    ``candidates(..., held=True)``, each batch holding the rows that pass of the batch
    it would be without the test), and a search that is not
    ``strict`` and has no ``map`` solves the rows left in groups of ``GATHER_ROWS``
    across batches once its top is full (its answer does not depend on the batching).
    On a part of millions of rows whose best rows are pairs of nearly opposite edges (a
    regular polygon), the search reads the rows those pairs give instead of every row
    (:func:`_paired`), when they hold every row that may reach the floor.

    >>> from fcgrasp.io.parts import demo_part
    >>> from fcgrasp.pipeline import plan_spec
    >>> [p.edges for p in search(demo_part("quad"), plan_spec(fingers=4, top=1))]
    [(0, 1, 2, 3)]
    """
    top = TopK(polygon, spec, edges)
    total = search_size(polygon, spec, edges).rows if progress is not None else 0
    done = 0
    window: list[EdgeSets] = []

    tie = 4 * RANK_TOL * polygon.size

    def current() -> float:
        f = top.floor + (tie if strict and top.floor > 0 else 0.0)
        return max(f, floor)

    lex = spec.top is not None and spec.rank_by == "min_region"
    step = 10.0 ** -RANK_DIGITS

    def key(level: float) -> FloatArray | None:
        # the top's last key where a smallest region at ``level`` can at best tie its
        # first (a rounding step's slack: None only prunes less)
        if not lex or top.floor <= 0 or \
                level > (top.floor + 2 * RANK_TOL * polygon.size) / polygon.size + step:
            return None
        k = top.key
        return k if k is not None and level <= k[0] else None

    # rows that pass the force-direction test, once the top is full, waiting to be
    # solved together (the answer of a search that is not strict does not depend on how
    # its rows are batched)
    gathered: list[EdgeSets] = []
    gather = map is None and not strict
    memo = scores if map is None else None

    def fold(last: bool = False) -> None:
        nonlocal done
        at = current()
        live = [b for b in window if b.ceiling >= at]
        # rows whose forces cannot hold give no candidate: dropped before the rest
        held = [(b, np.ones(len(b.feats), bool) if b.held else
                 holding_rows(polygon, spec, b.feats, edges)) for b in live]
        live = [b if keep is None or keep.all() else b.take(keep) for b, keep in held]
        live = [b for b in live if len(b.feats)]
        if exclude is not None:
            live = [b for b in (_left_in(b, exclude) for b in live) if len(b.feats)]
        if lex:                # the top's last key may have risen since the rows came
            live = [b for b in (_lex_pruned(b, key, lengths, twin, polygon.size)
                                for b in live) if len(b.feats)]
        if memo is not None:   # rows an earlier search solved, below the floor
            live = [b for b in (_reaching(b, memo, at, polygon.size) for b in live)
                    if len(b.feats)]
        # (once the top is full: until then each batch's rows raise its floor and key)
        if gather and (gathered or top.floor > 0 and
                       any(keep is not None for _, keep in held)):
            gathered.extend(live)
            if not last and sum(len(b.feats) for b in gathered) < _spec.GATHER_ROWS:
                live = []
            else:
                live = [_joined(gathered)] if gathered else []
                gathered.clear()
        if map is None:
            results: Iterable[Solved] = [solve(polygon, spec, b, edges, floor=at,
                                               scores=memo) for b in live]
        else:
            results = map(partial(solve, polygon, spec, edges=edges, floor=at), live)
        for solved in results:
            top.add(solved)
        done += sum(len(b.feats) if b.read is None else b.read for b in window)
        window.clear()
        if progress is not None:
            progress(min(done, total), total)

    lengths = features(polygon, spec.mu, spec.hand, edges).lengths
    twin = spec.shape.twin if spec.shape.three_edge else None
    paired = _paired(polygon, spec, edges, exclude, floor)
    stream = candidates(polygon, spec, edges, batch_size, key=key, held=True) \
        if paired is None else iter(paired)
    for batch in stream:
        if batch.ceiling < current():
            break
        window.append(batch)
        if map is None or len(window) >= MAP_WINDOW:
            fold()
    if window or gathered:
        fold(last=True)
    if progress is not None and done < total:
        progress(total, total)
    return top.plans()


@lru_cache(maxsize=4)
def _part_pairs(polygon: Polygon, spec: PlanSpec, edges: tuple[int, ...] | None,
                count: int) -> PairRows:
    """A part's :class:`PairRows` (``spec`` without a top), once per part (its quick
    test, :attr:`PairRows.hopeless`, asked by every search of a plan); ``count``: the
    seed rows :func:`_seeded` takes from it."""
    return PairRows(polygon, spec, edges)


@lru_cache(maxsize=4)
def _seeded(polygon: Polygon, spec: PlanSpec, edges: tuple[int, ...] | None, count: int
            ) -> tuple[PairRows, EdgeSets, np.ndarray, FloatArray]:
    """A part's :class:`PairRows` (:func:`_part_pairs`, past its quick test), its
    ``count`` seed rows and each seed row's smallest region, solved (the rows that
    hold), once per part: the searches of one plan (the grown plans' seeds, the ranked
    list, each distinct round) take their floors from the same rows."""
    pairs = _part_pairs(polygon, spec, edges, count)
    seed = pairs.seed(count)
    got = solve(polygon, spec, seed, edges)
    feats, mins = got.cands.feats, _smallest_region(got.cands.feats, got.lengths)
    for arr in (seed.feats, feats, mins):       # shared by the searches: read only
        arr.flags.writeable = False
    return pairs, seed, feats, mins


def _paired(polygon: Polygon, spec: PlanSpec, edges: Any,
            exclude: Callable[[np.ndarray], np.ndarray] | None, floor: float
            ) -> list[EdgeSets] | None:
    """Four frictionless fingers (or three and gravity) on a part with millions of rows
    whose best rows are pairs of nearly opposite edges (a regular polygon,
    :mod:`._pair_rows`): the seed rows, then every other row that may reach the floor
    their ``top``-th gives (solved here, the rows ``exclude`` leaves out left out, less
    the ranking's rounding, as :class:`TopK` sets it), by decreasing bound in batches;
    None where that floor is too low for the pairs to hold every such row, and the
    search streams every row as before.  Every row left out is below that floor, so a
    search that is not strict keeps the same plans (a strict one keeps exact ties in the
    order found: the seed rows first)."""
    if not PairRows.applies(spec, polygon, edges):
        return None
    top = spec.top or 1
    which = (polygon, replace(spec, top=None),
             None if edges is None else tuple(int(e) for e in edges), max(4 * top, SEED_ROWS))
    # numba, for the pairs' loops, is asked for only past the quick test (most parts
    # fail it: their feet are far off the edges)
    if _part_pairs(*which).hopeless or not PairRows.loops():
        return None
    pairs, seed, feats, mins = _seeded(*which)
    if exclude is not None and len(feats):
        out = np.asarray(exclude(feats), bool)
        mins = mins[~out] if out.any() else mins
    level = floor
    if len(mins) >= top:
        kth = float(np.partition(-mins, top - 1)[top - 1])
        level = max(level, -kth - 2 * RANK_TOL * polygon.size)
    rest = pairs.reaching(level)
    if rest is None:
        return None
    # by decreasing bound, in growing batches: the floor the first ones raise drops
    # the later ones before their geometry (solve), or ends the stream (their ceiling)
    bound = rest.bound
    assert bound is not None            # reaching bounds every row it reads
    by = np.argsort(-bound, kind="stable")
    batches, start, size = [seed], 0, _spec.GATHER_ROWS
    while start < by.size:
        part = rest.take(np.sort(by[start:start + size]))
        batches.append(EdgeSets(part.feats, part.bound, float(bound[by[start]])))
        start, size = start + size, 2 * size
    return batches


def _reaching(batch: EdgeSets, memo: RowScores, floor: float, size: float) -> EdgeSets:
    """The rows of a batch but those the memo knows :func:`solve` would drop: a score
    that holds nothing, or one below ``floor`` by more than rounding."""
    known = memo.known(batch.feats)
    drop = (known < 0) | (known < floor - RANK_TOL * size)
    return batch.take(~drop) if drop.any() else batch


def _joined(batches: list[EdgeSets]) -> EdgeSets:
    """Batches as one (their rows in order, each with its bound)."""
    if len(batches) == 1:
        return batches[0]
    bounds = [b.bound for b in batches if b.bound is not None]
    return EdgeSets(np.concatenate([b.feats for b in batches]),
                    np.concatenate(bounds) if len(bounds) == len(batches) else None,
                    max(b.ceiling for b in batches))


def _left_in(batch: EdgeSets, exclude: Callable[[np.ndarray], np.ndarray]) -> EdgeSets:
    """The rows of a batch that ``exclude`` does not leave out."""
    if not len(batch.feats):
        return batch
    out = np.asarray(exclude(batch.feats), bool)
    return batch.take(~out) if out.any() else batch


def _lex_pruned(batch: EdgeSets, key: Callable[[float], FloatArray | None],
                lengths: FloatArray, twin: int | None, size: float) -> EdgeSets:
    """The rows of a batch that may still reach or tie the running top's last key
    (``key(level)`` at the batch's ceiling: None, every row, above the tie)."""
    k = key(float(np.round((batch.ceiling + _bound_pad(size)) / size, RANK_DIGITS)))
    if k is None or not len(batch.feats):
        return batch
    keep = lex_survivors(_row_bounds(lengths, batch.feats, twin), k, size)
    if keep.all():
        return batch
    return batch.take(keep)


def every_plan(polygon: Polygon, spec: PlanSpec, edges: Any = None,
               batch_size: int | None = None) -> Iterator[GraspPlan]:
    """Every single-edge plan of a part (``top=None``), streamed: each batch of
    :func:`candidates` is solved and its plans yielded (in rank order within the batch;
    batches by decreasing bound of their rows), so memory is bounded by one batch
    whatever the part's size, where ``plan(..., top=None)`` must hold every plan to rank
    them and refuses parts whose plans would not fit (:class:`SearchTooLarge`).

    >>> from fcgrasp.io.parts import demo_part
    >>> from fcgrasp.pipeline import plan_spec
    >>> part = demo_part("quad")
    >>> spec = plan_spec(fingers=2, mu=0.5)
    >>> sorted(p.edges for p in every_plan(part, spec)) == sorted(
    ...     p.edges for p in search(part, plan_spec(fingers=2, mu=0.5, top=None)))
    True
    """
    spec = replace(spec, top=None)
    for batch in candidates(polygon, spec, edges, batch_size):
        top = TopK(polygon, spec, edges)
        top.add(solve(polygon, spec, batch, edges))
        yield from top.plans()


def rank(polygon: Polygon, spec: PlanSpec, solved: Iterable[Solved],
         edges: Any = None) -> list[GraspPlan]:
    """Merge solved batches and return the best plans, best first (a top-k reduce,
    :class:`TopK`).

    Sorted by the measure ``spec.rank_by`` (:mod:`fcgrasp.model.ranking`), then the leximin
    order of the region lengths, then :func:`~fcgrasp.model.plans.geometric_key`.
    """
    top = TopK(polygon, spec, edges)
    for batch in solved:
        top.add(batch)
    return top.plans()
