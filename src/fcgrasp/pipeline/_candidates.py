"""Candidates: the features of a part and the candidate edge sets of a search, streamed
by decreasing bound, with the memory estimate that refuses a search too large (part
of :mod:`fcgrasp.pipeline`; sections 6 and 7.2)."""

from __future__ import annotations

import bisect
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from math import comb
from typing import Any, cast

import numpy as np

from ..core import jit
from ..core._angles import wrap_positive
from ..core._checks import (
    FloatArray,
    check_int,
)
from ..core._geom import RANK_DIGITS
from ..core.closure import rows_closure
from ..core.kernels import pair_scores
from ..core.sectors import PAIRINGS, pairing_valid
from ..core.tolerances import RANK_TOL, SOLVER_TOL, TINY, TOL
from ..model import _quad_estimates
from ..model._regiongeom import four_finger_problems, two_finger_problems
from ..model.polygon import Polygon
from ..model.regions import (
    KnapsackProblem,
    leximin,
    max_min_length,
)
from . import _rows_kernels, _spec  # _spec: the search's tunables, read when used
from ._features import (
    Features,
    features,
)
from ._rows import (
    _bound_pad,
    _combos,
    _distinct_edges,
    _layouts,
    _row_bound,
    _row_bounds,
    _spans_plane,
    lex_survivors,
)
from ._size import (
    search_size,
)
from ._spec import (
    PlanSpec,
)

# ----------------------------------------------------------------------------- candidates


@dataclass
class Candidates:
    """A batch of candidate edge sets with their grasp-set geometry (section 6) and region
    problems (section 7), scored by the largest smallest region (stage 1)."""

    feats: np.ndarray            # (B, n) feature index per finger (-1: gravity)
    a: FloatArray                # (B, n, 2)
    b: FloatArray
    center: FloatArray           # (B, n)
    half: FloatArray             # (B, n) friction half-angles
    perm: np.ndarray             # (B, n) problem order -> finger order
    problems: list[KnapsackProblem]   # one per mode, in problem order
    modes: tuple[str, str]
    score: FloatArray = field(default_factory=lambda: np.zeros(0))
    best_mode: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    tol: float = SOLVER_TOL          # relative slack of the region solver

    def take(self, idx: Any) -> Candidates:
        """The candidates of the given rows."""
        out = Candidates(self.feats[idx], self.a[idx], self.b[idx], self.center[idx],
                         self.half[idx], self.perm[idx], [p.take(idx) for p in self.problems],
                         self.modes, tol=self.tol)
        out.score, out.best_mode = self.score[idx], self.best_mode[idx]
        return out

    @staticmethod
    def concat(parts: list[Candidates]) -> Candidates:
        """The rows of several batches, in order."""
        def cat(xs: list[Any]) -> Any:
            return np.concatenate(xs)

        probs = [KnapsackProblem.concat([p.problems[m] for p in parts]) for m in range(2)]
        out = Candidates(cat([p.feats for p in parts]), cat([p.a for p in parts]),
                         cat([p.b for p in parts]), cat([p.center for p in parts]),
                         cat([p.half for p in parts]), cat([p.perm for p in parts]), probs,
                         parts[0].modes, tol=parts[0].tol)
        out.score = cat([p.score for p in parts])
        out.best_mode = cat([p.best_mode for p in parts])
        return out


def _pair_candidates(F: Features, margin: float, i: np.ndarray, j: np.ndarray,
                     tol: float = SOLVER_TOL, floor: float = 0.0) -> Candidates:
    """Two-finger candidates of the feature pairs ``(i, j)`` on distinct edges that have
    regions (reaching ``floor``, if given), scored by one fused pass over every pair
    (:func:`fcgrasp.core.kernels.pair_scores`, exact: the two fingers are on distinct edges);
    the problems are built for those pairs only."""
    keep = F.edge[i] != F.edge[j]
    i, j = i[keep], j[keep]
    score, mode, _ = pair_scores(F.a, F.b, F.center, F.half, i, j, margin, tol)
    ok = np.flatnonzero((score > 0) & (score >= floor))
    i, j, score, mode = i[ok], j[ok], score[ok], mode[ok]
    probs, _ = two_finger_problems(F.a[i], F.b[i], F.center[i], F.half[i],
                                   F.a[j], F.b[j], F.center[j], F.half[j], margin)
    c = Candidates(np.stack([i, j], axis=1), np.stack([F.a[i], F.a[j]], 1),
                   np.stack([F.b[i], F.b[j]], 1), np.stack([F.center[i], F.center[j]], 1),
                   np.stack([F.half[i], F.half[j]], 1), np.tile([0, 1], (len(i), 1)), probs,
                   ("squeeze", "expand"), tol=tol)
    c.score, c.best_mode = score, mode
    return c


def _ordered_rows(F: Features, spec: PlanSpec, three_edge: bool, size: int,
                  first: int, key: Callable[[float], FloatArray | None] | None = None,
                  part_size: float = 1.0, held: bool = False) -> Iterator[EdgeSets]:
    """Every candidate row, streamed by decreasing bound (branch and bound).

    Features are sorted by decreasing length; a row's *last* feature in that order is its
    shortest, so the rows are enumerated by their last position ``s``: every row whose
    features all come before ``s``'s has a bound at least the length at ``s``.  Batches
    grow from ``first`` rows, doubling, to ``size``, so that a search whose top is found
    early stops after little work.

    ``key(level)``: the running top's last leximin key (:attr:`~fcgrasp.pipeline.TopK.key`)
    where a smallest region of ``level`` (over the part's size, rounded) can at best tie
    its first, else None (and None until the top is full).  Where the shortest feature's
    length can at best tie the key's smallest region, the rows that cannot reach or tie
    the key (:func:`lex_survivors`) are left out, and a row can only tie it if its
    second smallest region ties or beats the key's second, and that region is at most
    the second shortest feature's length (halving a feature for two fingers only
    lowers it): the other features are then drawn from the
    positions long enough for that (on a flattened curve, where every short edge ties
    the top's smallest region, the few long edges), not from every position before
    ``s``.

    ``held``: only the rows whose forces pass the force-direction test (theorem 4.2),
    in batches that hold the rows that passed of the batches without it (each batch's
    ``read``: the rows it stands for).
    """
    lengths = F.lengths
    n = lengths.size
    order = np.lexsort((np.arange(n), -lengths))
    # each position's length as a leximin key rounds it (padded as lex_survivors pads)
    rounded = np.round((lengths[order] + _bound_pad(part_size)) / part_size, RANK_DIGITS)
    # the same of half of each (two fingers on one feature), for the compiled rows
    rounded_half = np.round((lengths[order] * 0.5 + _bound_pad(part_size)) / part_size,
                            RANK_DIGITS)
    order_i = np.ascontiguousarray(order, dtype=np.int64)
    edge_i = np.ascontiguousarray(F.edge, dtype=np.int64)
    g = spec.gravity
    widths = spec.shape.widths if three_edge else spec.shape.widths[:1]
    twin = spec.shape.twin if three_edge else None
    # frictionless fingers hold only if their force directions positively span the plane
    # (theorem 4.2; gravity counts as one): rows whose features all come from positions
    # 0..s whose directions leave a gap of half a turn cannot, so such s are skipped
    seen = [] if g is None else [float(wrap_positive(np.arctan2(g[1], g[0])))]
    compiled_rows = jit.jit_setting() is True or jit.started()
    # the rows that fail the force-direction test left out as they are made (by the
    # compiled loop, else by rows_closure on numpy's blocks), each batch the rows held
    # of the batch it would be without the test
    forces = _force_table(F, 0.0 if g is None else float(np.arctan2(g[1], g[0]))) \
        if held else None
    table = None if forces is None else _unit(forces)
    buf: list[np.ndarray] = []
    where: list[np.ndarray] = []        # each buffered row's place among the rows read
    count = 0                           # rows read (held or not) in the buffer
    target = min(first, size)
    ceiling = np.inf
    for s in range(n):
        if not count:
            ceiling = float(lengths[order[s]])
        if spec.contact_type == "frictionless":
            bisect.insort(seen, float(wrap_positive(F.center[order[s]])))
            if not _spans_plane(np.array(seen)):
                continue
        # the key where the shortest feature can at best tie its smallest region
        current = key(float(rounded[s])) if key is not None else None
        if current is not None and rounded[s] < current[0]:
            break           # no row from here on reaches the key's smallest region
        pool = s
        if current is not None and current.size > 1:
            # the other features must reach the key's second region
            pool = min(s, int(np.searchsorted(-rounded, -current[1], side="right")))
        # without a key every row: by the compiled loop too (with a key every row
        # reaches) where it runs anyway, numba started in this process
        reach = current if current is not None else _EVERY_ROW if compiled_rows else None
        for r in widths:
            # the rows that may reach the key: by one compiled loop, else numpy blocks
            got = None if reach is None else _made_rows(
                F, order_i, edge_i, rounded, rounded_half, s, pool, r, spec, reach, table,
                part_size)
            for rows_s, at, read in ([got] if got is not None else
                                     (_held(rows_b, forces) for rows_b in
                                      _row_blocks(F, spec, order, s, pool, r, current, twin,
                                                  part_size))):
                if not read:
                    continue
                buf.append(rows_s)
                where.append(at + count)
                count += read
                while count >= target:
                    rows, at = np.concatenate(buf), np.concatenate(where)
                    cut = int(np.searchsorted(at, target))
                    yield EdgeSets(rows[:cut], _row_bound(lengths, rows[:cut], twin),
                                   ceiling, held=table is not None, read=target)
                    # the rows left over come from position s: bounded by its length
                    buf, where, count = [rows[cut:]], [at[cut:] - target], count - target
                    ceiling = float(lengths[order[s]])
                    target = min(2 * target, size)
    if count:
        rows = np.concatenate(buf)
        yield EdgeSets(rows, _row_bound(lengths, rows, twin), ceiling, held=table is not None,
                       read=count)


#: The rows a part's features keep of the compiled stream (:func:`_made_rows`), at most.
MADE_ROWS = 250_000


def _made_rows(F: Features, order: np.ndarray, edge: np.ndarray, rounded: FloatArray,
               rounded_half: FloatArray, s: int, pool: int, r: int, spec: PlanSpec,
               reach: FloatArray, table: FloatArray | None, part_size: float
               ) -> tuple[np.ndarray, np.ndarray, int] | None:
    """:func:`fcgrasp.pipeline._rows_kernels.holding_survivors` of one position, kept
    on the features (:attr:`Features.made`, up to :data:`MADE_ROWS` rows) by its
    arguments: a distinct search's rounds and the ranked list's search stream the same
    rows of a part (``icons/heart.svg``: 4.6 million rows twice), and the loop is a
    function of them (the features' order, bounds and forces follow from ``F``, the
    spec's layout and gravity, and the part's size)."""
    key = (s, pool, r, spec.shape.layout, spec.fingers, spec.shape.twin, spec.gravity,
           reach.tobytes(), table is None, part_size)
    got = F.made.get(key)
    if got is not None:
        return cast("tuple[np.ndarray, np.ndarray, int]", got)
    got = _rows_kernels.holding_survivors(order, edge, rounded, rounded_half, s, pool, r,
                                          spec.shape.layout, spec.fingers, spec.shape.twin,
                                          reach, comb(pool, r), table, TOL)
    if got is not None:
        kept = F.made.get("rows", 0) + len(got[0])
        if kept <= MADE_ROWS:
            # copies (the loop's are views of its grown buffers), read only
            rows, where = got[0].copy(), got[1].copy()
            rows.flags.writeable = where.flags.writeable = False
            got = rows, where, got[2]
            F.made[key], F.made["rows"] = got, kept
    return got


def _unit(forces: FloatArray) -> FloatArray:
    """A table of forces made unit as :func:`~fcgrasp.core.closure.rows_closure` makes
    its table (the same operations, so the same numbers)."""
    n = np.sqrt(forces[:, 0] * forces[:, 0] + forces[:, 1] * forces[:, 1])
    safe = np.where(n > 0, n, 1.0)
    return np.ascontiguousarray(np.where((n > 0)[:, None], forces / safe[:, None], 0.0))


def _held(rows: np.ndarray, forces: FloatArray | None
          ) -> tuple[np.ndarray, np.ndarray, int]:
    """A numpy block's rows whose ``forces`` (each feature's, gravity's last) pass the
    force-direction test (all without a table), their places in the block, and the
    block's size."""
    if forces is None or not len(rows):
        return rows, np.arange(len(rows)), len(rows)
    ok = rows_closure(forces, np.where(rows >= 0, rows, len(forces) - 1))
    return rows[ok], np.flatnonzero(ok), len(rows)


#: The key of :func:`_ordered_rows`' compiled rows where the search has none: every row
#: reaches it (:func:`lex_survivors` keeps all), so the loop gives every row, in the
#: numpy path's order.
_EVERY_ROW = np.array([-np.inf])


def _row_blocks(F: Features, spec: PlanSpec, order: np.ndarray, s: int, pool: int, r: int,
                current: FloatArray | None, twin: int | None, part_size: float
                ) -> Iterator[np.ndarray]:
    """The rows of position ``s`` (``r`` positions drawn from ``range(pool)``), in numpy
    blocks: the features sorted, on distinct edges, laid out, and with a ``current``
    key only those whose bounds may reach or tie it (:func:`lex_survivors`); the
    reference of :func:`fcgrasp.pipeline._rows_kernels.survivors`."""
    for block in _combos(pool, r):
        t = np.sort(order[np.concatenate([block, np.full((len(block), 1), s)], axis=1)],
                    axis=1)
        t = _distinct_edges(F, t)
        if not len(t):
            continue
        rows_s = _layouts(t, spec.shape, spec.fingers)
        if current is not None:
            rows_s = rows_s[lex_survivors(_row_bounds(F.lengths, rows_s, twin), current,
                                          part_size)]
        yield rows_s


def _force_table(F: Features, g_ang: float) -> FloatArray:
    """Each feature's unit force, and gravity's last (``g_ang``)."""
    angles = np.append(F.center, g_ang)
    return np.stack([np.cos(angles), np.sin(angles)], axis=-1)


def holding_rows(polygon: Polygon, spec: PlanSpec, feats: np.ndarray, edges: Any = None
                 ) -> np.ndarray | None:
    """Which rows of four frictionless fingers (or three with gravity) pass the
    force-direction test (theorem 4.2) that :func:`grasp_geometry` starts with, by the
    compiled loop; None for other fingers, or where the loop is not running already
    (:func:`fcgrasp.core.jit.started`: a search then leaves the test to
    :func:`grasp_geometry`, as before).  A row that fails it gives no candidate, so a
    search may drop it before anything else reads it (most rows of a curved outline's
    four-finger search do: ``icons/heart.svg`` 97 %)."""
    got = _quad_rows(polygon, spec, feats, edges)
    if got is None:
        return None
    F, g_ang, rows = got
    return rows_closure(_force_table(F, g_ang), rows)


def _quad_rows(polygon: Polygon, spec: PlanSpec, feats: np.ndarray, edges: Any
               ) -> tuple[Features, float, np.ndarray] | None:
    """Four frictionless fingers (or three with gravity), once numba runs in the
    process: the features, gravity's angle and the rows as indices into the features'
    tables with gravity's last (-1 read as it); None else (or no rows)."""
    if spec.shape.pairs or spec.shape.lp or not jit.started() or not len(feats):
        return None
    F = features(polygon, spec.mu, spec.hand, edges)
    g_ang = 0.0 if spec.gravity is None else float(np.arctan2(spec.gravity[1],
                                                            spec.gravity[0]))
    rows = np.asarray(feats, dtype=int).reshape(len(feats), -1)
    return F, g_ang, np.where(rows >= 0, rows, len(F.center))


def quad_estimates(polygon: Polygon, spec: PlanSpec, feats: np.ndarray, edges: Any = None
                   ) -> FloatArray | None:
    """Four frictionless fingers (or three with gravity): each row's estimate of its
    stage-1 score, never below the score :func:`grasp_geometry` gives it
    (:mod:`fcgrasp.model._quad_estimates`, compiled); None for other fingers, or where
    the loop is not running already (:func:`fcgrasp.core.jit.started`)."""
    got = _quad_rows(polygon, spec, feats, edges)
    if got is None:
        return None
    F, g_ang, rows = got
    c = polygon.centroid
    return _quad_estimates.estimates(np.vstack([F.a, c]), np.vstack([F.b, c]),
                                     np.append(F.center, g_ang), rows, spec.margin_rad)


def _quad_candidates(F: Features, margin: float, gravity: FloatArray | None,
                     centroid: FloatArray, feats: np.ndarray, tol: float = SOLVER_TOL,
                     floor: float = 0.0) -> Candidates:
    """Grasp-set geometry and problems of four-finger (or three plus gravity) rows.
    Pairings tied on the smallest region are told apart by the next leximin levels only
    in rows that reach ``floor`` (the others cannot enter the top; their score, the
    tied value, is the same whichever pairing is kept)."""
    B = len(feats)
    g_ang = 0.0 if gravity is None else float(np.arctan2(gravity[1], gravity[0]))
    # the force directions first (each feature's once), the rows that hold none cut
    # before anything is gathered (the same numbers: cos and sin of each angle)
    unit = _force_table(F, g_ang)
    ok = rows_closure(unit, np.where(feats >= 0, feats, len(F.center))) if B \
        else np.zeros(0, bool)
    feats = feats[ok]
    real = feats >= 0
    fi = np.where(real, feats, 0)
    center = np.where(real, F.center[fi], g_ang)
    dirs = unit[np.where(real, feats, len(F.center))]
    a = np.where(real[..., None], F.a[fi], centroid)
    b = np.where(real[..., None], F.b[fi], centroid)
    B = len(feats)
    # every pairing whose two sectors are non-null describes the same grasp set
    # (corollary 5.1); the margin is taken on the sector of the pairing that gives the
    # largest smallest region, so the plan does not depend on how edges are numbered
    good = np.stack([pairing_valid(dirs, p) for p in PAIRINGS], axis=1) if B \
        else np.zeros((0, 3), bool)
    has = good.any(axis=1)
    feats, a, b, center, good = feats[has], a[has], b[has], center[has], good[has]
    B = len(feats)
    scores = np.full((B, 3), -np.inf)
    per_mode = np.full((B, 3, 2), -1.0)
    built: dict[int, tuple[np.ndarray, list[KnapsackProblem]]] = {}
    for k, p in enumerate(PAIRINGS):
        rows = np.flatnonzero(good[:, k])
        if rows.size == 0:
            continue
        probs, _, _ = four_finger_problems(a[rows], b[rows], center[rows],
                                           np.broadcast_to(p, (rows.size, 4)), margin)
        for m, pr in enumerate(probs):
            per_mode[rows, k, m] = np.where(pr.separable, max_min_length(pr, tol), -1.0)
        scores[rows, k] = per_mode[rows, k].max(axis=1)
        built[k] = (rows, probs)
    choice = np.argmax(scores, axis=1)
    top_s = scores[np.arange(B), choice]
    tied = np.flatnonzero((top_s > 0) & (top_s >= floor) &
                          (np.sum(scores >= top_s[:, None] - RANK_TOL *
                                  np.abs(top_s[:, None]), axis=1) > 1))
    if tied.size:
        # equal smallest regions: the next levels of the leximin order decide
        best_lv = np.full((tied.size, 4), -1.0)
        for k, p in enumerate(PAIRINGS):
            cand = scores[tied, k] >= top_s[tied] - RANK_TOL * np.abs(top_s[tied])
            if not cand.any():
                continue
            rows_k, probs_k = built[k]
            pos = np.searchsorted(rows_k, tied[cand])
            lv, _ = _best_levels([pr.take(pos) for pr in probs_k],
                                 np.broadcast_to(p, (pos.size, 4)).copy(), tol)
            better = _lex_greater(lv, best_lv[cand])
            idx = np.flatnonzero(cand)[better]
            best_lv[idx] = lv[better]
            choice[tied[idx]] = k
    # gather the chosen pairing's problems (already built), back in row order
    if built:
        sels = {k: np.flatnonzero(choice[rows_k] == k) for k, (rows_k, _) in built.items()}
        back = np.argsort(np.concatenate([built[k][0][sel] for k, sel in sels.items()]))
        probs = [KnapsackProblem.concat([built[k][1][m].take(sel) for k, sel in sels.items()])
                 .take(back) for m in range(2)]
    else:
        probs = four_finger_problems(a, b, center, np.zeros((0, 4), int), margin)[0]
    perm = PAIRINGS[choice]
    c = Candidates(feats, a, b, center, np.zeros_like(center), perm, probs, ("+C", "-C"),
                   tol=tol)
    pm = per_mode[np.arange(B), choice]
    c.best_mode = np.argmax(pm, axis=1)
    c.score = pm.max(axis=1)
    return c


# ----------------------------------------------------------------------------- candidates


@dataclass
class EdgeSets:
    """A batch of candidate edge sets: ``feats[r, k]`` is the feature (see
    :func:`features`) of finger ``k`` in row ``r``, -1 for gravity.  Picklable.

    ``bound[r]`` is an upper bound of row ``r``'s smallest region (no region is longer
    than its feature; two fingers on one feature share it), ``ceiling`` a bound of every
    row of this batch *and of every later batch* of the stream: :func:`candidates`
    yields rows by decreasing bound, so a search whose running top already beats a
    batch's ceiling can stop there (:func:`search`).
    """

    feats: np.ndarray
    bound: FloatArray | None = None
    ceiling: float = float("inf")
    #: every row passes the force-direction test (a stream that left out the others)
    held: bool = False
    #: the rows of the stream this batch stands for, those left out by the
    #: force-direction test included (None: its rows)
    read: int | None = None

    def take(self, keep: np.ndarray) -> EdgeSets:
        """The rows ``keep`` (a mask or indices) with their bounds, the same ceiling."""
        return EdgeSets(self.feats[keep], None if self.bound is None else self.bound[keep],
                        self.ceiling, self.held)


def candidates(polygon: Polygon, spec: PlanSpec, edges: Any = None,
               batch_size: int | None = None,
               key: Callable[[float], FloatArray | None] | None = None,
               held: bool = False) -> Iterator[EdgeSets]:
    """Stream the candidate edge sets of a part in batches of at most ``batch_size`` rows,
    by decreasing upper bound of their smallest region (:class:`EdgeSets`).

    Two fingers: every pair of features on distinct edges.  Four: every 4-tuple on
    distinct edges and every three edges with one doubled.  Three: every triple on
    distinct edges (with gravity, plus the gravity contact -1; with friction also every
    two edges with one doubled, fingers 0 and 1 side by side on it).  ``edges`` restricts
    the features to those edges (with four fingers and an edge given twice, only the
    layouts doubling that edge).  With a ``top``, batches
    start small and double up to ``batch_size``, so a search that finds its top among
    the first rows stops after little work (:func:`search`); the stream itself always
    holds every row, unless ``key`` (a search's running top,
    :attr:`~fcgrasp.pipeline.TopK.key`) leaves out the rows that cannot reach its last.
    ``held``: four frictionless fingers (or three with gravity), once numba runs in the
    process, the rows that fail the force-direction test are left out as they are made
    (:func:`holding_rows`' test; each batch holds the rows that pass of the batch
    without it, :attr:`EdgeSets.held`); elsewhere ignored.
    """
    F = features(polygon, spec.mu, spec.hand, edges)
    held = held and not (spec.shape.pairs or spec.shape.lp) and jit.started()
    size = search_size(polygon, spec, edges).batch_rows if batch_size is None else \
        check_int(batch_size, "batch_size", minimum=1)
    first = size if spec.top is None else _spec.FIRST_BATCH
    doubled = None
    three_edge = spec.shape.three_edge
    if edges is not None and three_edge:
        idx = [int(e) for e in edges]
        twice = [e for e in set(idx) if idx.count(e) == 2]
        doubled = twice[0] if twice else None
        three_edge = doubled is not None
    for sets in _ordered_rows(F, spec, three_edge, size, first, key, polygon.size, held):
        if doubled is not None:
            rows = sets.feats
            twin = spec.shape.twin
            keep = (F.edge[rows[:, 0]] == doubled) & (rows[:, 0] == rows[:, twin])
            if not keep.any():
                continue
            assert sets.bound is not None
            sets = sets.take(keep)
        yield sets


def grasp_geometry(polygon: Polygon, spec: PlanSpec, sets: EdgeSets,
                   edges: Any = None, floor: float = 0.0) -> Candidates:
    """The grasp sets of a batch (section 6) and their region problems, scored by the
    largest smallest region (stage 1, exact unless two fingers share an edge, when it is
    an upper bound).  Rows that fail the force-direction constraint are dropped; with two
    fingers, so are rows with no regions.  With a ``floor`` (:attr:`TopK.floor`) and a
    ``top``, two-finger rows below the floor are dropped too, and four-finger pairings
    tied on the smallest region are told apart only in the rows that reach it."""
    if spec.shape.lp:
        raise ValueError("three fingers with friction are solved by linear programs: "
                         "fcgrasp.grippers.three_fingers.three_finger_plans, not grasp_geometry")
    F = features(polygon, spec.mu, spec.hand, edges)
    feats = np.asarray(sets.feats, dtype=int)
    if spec.shape.pairs:
        return _pair_candidates(F, spec.margin_rad, feats[:, 0], feats[:, 1], spec.tol,
                                floor if spec.top is not None else 0.0)
    gravity = None if spec.gravity is None else np.array(spec.gravity)
    return _quad_candidates(F, spec.margin_rad, gravity, polygon.centroid,
                            feats.reshape(-1, 4), spec.tol, floor)


def _lex_greater(a: FloatArray, b: FloatArray, rtol: float = RANK_TOL) -> np.ndarray:
    """Row-wise leximin comparison ``a > b`` of length vectors, with a relative tolerance.

    Entries equal to 0 with a negative counterpart are regions of fixed points (gravity).
    """
    sa, sb = np.sort(a, axis=1), np.sort(b, axis=1)
    scale = np.maximum(np.maximum(np.abs(sa).max(axis=1), np.abs(sb).max(axis=1)), TINY)
    diff = sa - sb
    big = np.abs(diff) > rtol * scale[:, None]
    first = np.argmax(big, axis=1)
    rows = np.arange(len(a))
    return big.any(axis=1) & (diff[rows, first] > 0)


def _best_levels(probs: list[KnapsackProblem], perm: np.ndarray, tol: float = SOLVER_TOL
                 ) -> tuple[FloatArray, np.ndarray]:
    """Leximin lengths (finger order) of the better mode, and that mode."""
    R = len(perm)
    inv = np.argsort(perm, axis=1)
    ridx = np.arange(R)[:, None]
    lengths = np.full(perm.shape, -1.0)
    mode = np.zeros(R, dtype=int)
    for m, pr in enumerate(probs):
        # both modes are solved: when their smallest regions tie, the next levels decide
        lev = np.where(pr.separable[:, None], leximin(pr, tol), -1.0)[ridx, inv]
        better = _lex_greater(lev, lengths)
        lengths[better] = lev[better]
        mode[better] = m
    return lengths, mode
