"""The planning pipeline: candidates -> solve -> rank (sections 6, 7 and 8).

Three public steps, each on batches of numpy arrays, in the shape of shapely's array
functions under thin objects; :func:`fcgrasp.plan` is these three calls::

    spec = plan_spec(fingers=2, mu=0.3, top=5)
    solved = (solve(part, spec, batch) for batch in candidates(part, spec))
    plans = rank(part, spec, solved)

* :func:`candidates` streams :class:`EdgeSets`: batches of candidate edge sets (feature
  indices, picklable, at most ``batch_size`` rows each, so memory stays bounded however
  large the part).
* :func:`solve` builds the grasp sets of a batch (the sectors of section 6, by
  :mod:`fcgrasp.core.sectors`), prunes it with the force-direction constraint, and solves the
  optimal regions of the rows that can still reach the top (theorem 7.1, by
  :mod:`fcgrasp.model.regions`).  A batch solved anywhere (another process, another machine)
  gives the same :class:`Solved` as solved in place.
* :func:`rank` merges solved batches, keeps the best by the leximin order and the chosen
  measure (:mod:`fcgrasp.model.ranking`), places the regions and returns
  :class:`~fcgrasp.GraspPlan` objects, best first.

Units: lengths in the polygon's units; ``margin`` in **degrees** in :class:`PlanSpec`
(radians only inside this module's solvers).
"""

from __future__ import annotations

import bisect
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field, replace
from functools import lru_cache, partial
from math import comb
from typing import Any

import numpy as np

from ..core._angles import margin_radians, wrap_positive
from ..core._checks import (
    FloatArray,
    check_direction,
    check_int,
    check_mu_scalar,
    check_scalar,
    check_tol,
)
from ..core._geom import midpoints
from ..core.closure import force_direction_closure
from ..core.kernels import pair_scores
from ..core.sectors import PAIRINGS, pairing_valid
from ..core.tolerances import LEXIMIN_STEP, RANK_TOL, SOLVER_TOL, SPAN_SLACK, TINY
from ..errors import SearchTooLarge
from ..model._regiongeom import four_finger_problems, two_finger_problems
from ..model.frictionless_stretches import FrictionlessStretches, grow_stretches
from ..model.hand import Hand
from ..model.plans import GraspPlan, geometric_key, leximin_key, rank_key
from ..model.polygon import Polygon
from ..model.quality import characteristic_length
from ..model.ranking import MEASURES
from ..model.regions import (
    DEFAULT_MARGIN_DEG,
    KnapsackProblem,
    leximin,
    max_min_length,
    place_regions,
)
from ..model.stretches import StretchPair, crosses_a_vertex, two_finger_stretches

__all__ = ["PlanSpec", "plan_spec", "EdgeSets", "Features", "Candidates", "Solved",
           "features", "candidates", "grasp_geometry", "solve", "rank", "region_levels",
           "BATCH_SIZE", "TUPLE_BATCH_SIZE", "MAX_MEMORY", "SearchSize", "SearchTooLarge",
           "search_size", "check_search", "boundary_plans", "stretch_plan", "KEEP_STRETCHES",
           "grown_plans", "frictionless_plan", "GROW_SEEDS", "TopK", "search",
           "every_plan", "FIRST_BATCH", "MAP_WINDOW", "regions_plan", "ranked_unique"]

#: Candidate rows per batch of two fingers: large parts are streamed in batches of at most
#: this size (fewer when the memory budget asks for it, see :func:`search_size`).
BATCH_SIZE = 262_144
#: The same for three or four fingers, whose rows are about four times heavier: batches
#: that stay in cache (measured on a 500-edge outline: 42 s at 32,768 rows, 56 s at
#: 262,144, 60 s at 2,000,000).
TUPLE_BATCH_SIZE = 32_768
#: :func:`rank` folds the solved batches into their running top whenever it holds this many
#: rows beyond it, so what it keeps does not grow with the number of batches.
REDUCE_ROWS = 20_000
#: Default memory budget of a search, in bytes (``max_memory``, ``--max-memory``).
MAX_MEMORY = 2 ** 31
#: Smallest memory budget accepted.
MIN_MEMORY = 2 ** 24
#: Measured peak bytes per candidate row while a batch is solved (two fingers; three or
#: four), rounded up (``benchmarks/bench_scale.py`` prints them).
ROW_BYTES = {2: 450, 3: 1700, 4: 1700}
#: Bytes kept per candidate row when every plan is asked for (``top=None``): the solved
#: row and its GraspPlan, rounded up.
KEPT_ROW_BYTES = 3000
#: Peak bytes of the stretch search (regions along the boundary) per pair of edges, in
#: the worst case: every edge long enough to hold a region on its own, so the end
#: intervals of every edge against every vertex are held at once (measured 57; a curved
#: outline needs about 3: 61 MB of peak resident memory at 2,000 edges).
STRETCH_BYTES = 64
#: With a ranking measure other than ``min_region``, how many stretch configurations
#: (by their leximin order) are scored besides the single-edge plans.
KEEP_STRETCHES = 200
#: Three or four fingers along the boundary: how many of the best single-edge plans are
#: grown into stretches (:func:`fcgrasp.model.frictionless_stretches.grow_stretches`).
GROW_SEEDS = 10
#: Batches a search hands to a ``map`` at a time (see :func:`search`).
MAP_WINDOW = 8
#: Rows of the first batch of a search with a ``top`` (then doubling up to the batch size).
FIRST_BATCH = 4096
#: Measured seconds per candidate row (two fingers; three or four), for the time estimate.
ROW_SECONDS = {2: 1e-6, 3: 3e-5, 4: 3e-5}
#: With a measure other than ``min_region`` and a ``top``, the rows of a batch kept for
#: the measure: the best by the smallest region (the measures are computed per plan).
KEEP_FOR_MEASURE = 20_000


# ----------------------------------------------------------------------------- the spec


@dataclass(frozen=True)
class PlanSpec:
    """What to plan: the gripper, the margin and the ranking (validated by
    :func:`plan_spec`).  Picklable, so a batch can be solved elsewhere.

    ``margin`` is in degrees; ``gravity`` is a unit direction (three frictionless fingers
    and gravity) or None (with three fingers: three fingers with friction);
    ``disturbance`` is (translation in the part's units, rotation in degrees).
    """

    fingers: int = 2
    mu: float = 0.0
    margin: float = DEFAULT_MARGIN_DEG
    top: int | None = 10
    rank_by: str = "min_region"
    hand: Hand | None = None
    gravity: tuple[float, float] | None = None
    disturbance: tuple[float, float] = (10.0, 15.0)
    tol: float = SOLVER_TOL
    max_memory: int = 2 ** 31
    along_boundary: bool = True

    @property
    def stretches(self) -> bool:
        """Whether the two-finger stretch search runs (two fingers without a hand)."""
        return self.along_boundary and self.fingers == 2 and self.hand is None

    @property
    def grows(self) -> bool:
        """Whether single-edge plans of three or four fingers are grown along the
        boundary (without a hand)."""
        return (self.along_boundary and self.contact_type == "frictionless"
                and self.hand is None)

    @property
    def margin_rad(self) -> float:
        return float(margin_radians(self.margin))

    @property
    def contact_type(self) -> str:
        return "friction" if self.fingers == 2 or (self.fingers == 3 and self.gravity is None) \
            else "frictionless"


def plan_spec(fingers: Any = 2, mu: Any = 0.0, top: Any = 10, rank_by: Any = "min_region",
              hand: Any = None, margin: Any = DEFAULT_MARGIN_DEG, gravity: Any = None,
              disturbance: Any = (10.0, 15.0), tol: Any = SOLVER_TOL,
              max_memory: Any = None, along_boundary: Any = True) -> PlanSpec:
    """A validated :class:`PlanSpec` (arguments as for :func:`fcgrasp.plan`).

    Raises :class:`TypeError` or :class:`ValueError` naming the argument, also for an
    argument the planner would not use: a ``mu`` with four fingers or with gravity, a
    ``gravity`` with two or four fingers.  Three fingers are three fingers with friction
    (``mu > 0``) or, with ``gravity``, three frictionless fingers and gravity.

    >>> plan_spec(fingers=2, mu=0.3).contact_type
    'friction'
    """
    mu_v = check_mu_scalar(mu, "mu")
    margin_v = check_scalar(margin, "margin", nonnegative=True)
    if margin_v >= 90.0:
        raise ValueError(f"margin is an angle in degrees below 90, got {margin!r}")
    if hand is not None and not isinstance(hand, Hand):
        raise TypeError(f"hand must be a Hand or None, got {type(hand).__name__}")
    fingers = check_int(fingers, "fingers", choices=(2, 3, 4))
    if not isinstance(rank_by, str):
        raise TypeError(f"rank_by must be a string, got {rank_by!r}")
    if rank_by not in MEASURES:
        raise ValueError(f"rank_by must be one of {', '.join(MEASURES)}, got {rank_by!r}")
    if top is not None:
        top = check_int(top, "top", minimum=1)
    dist = check_disturbance(disturbance)
    g = None
    if gravity is not None:
        if fingers != 3:
            raise ValueError(f"gravity is a contact of three frictionless fingers; with "
                             f"{fingers} fingers it would not be used, got gravity={gravity!r}")
        gv = check_direction(gravity, "gravity")
        g = (float(gv[0]), float(gv[1]))
        if mu_v != 0:
            raise ValueError(f"three fingers with gravity are frictionless: mu would not be "
                             f"used, got mu={mu!r} (drop gravity to plan three fingers with "
                             f"friction)")
    elif fingers == 3 and mu_v == 0:
        raise ValueError("three fingers need friction (mu > 0), or gravity=(gx, gy) for "
                         "three frictionless fingers and gravity; got mu=0 and no gravity")
    if fingers == 4 and mu_v != 0:
        raise ValueError(f"four fingers are planned frictionless (theorem 7.1): mu would not "
                         f"be used, got mu={mu!r}")
    budget = MAX_MEMORY if max_memory is None else check_int(max_memory, "max_memory",
                                                              minimum=MIN_MEMORY)
    if not isinstance(along_boundary, bool):
        raise TypeError(f"along_boundary must be a bool, got {along_boundary!r}")
    return PlanSpec(fingers, mu_v, margin_v, top, rank_by, hand, g,
                    dist, check_tol(tol), budget, along_boundary)


def check_disturbance(disturbance: Any) -> tuple[float, float]:
    if isinstance(disturbance, (str, bytes)) or np.ndim(disturbance) != 1 \
            or len(disturbance) != 2:
        raise ValueError(f"disturbance must be (translation, rotation in degrees), got "
                         f"{disturbance!r}")
    return (check_scalar(disturbance[0], "disturbance[0]", positive=True),
            check_scalar(disturbance[1], "disturbance[1]", positive=True))



# ----------------------------------------------------------------------------- features

@dataclass
class Features:
    """Contactable pieces of edges (whole edges, or their feasible parts under a hand).

    The fingers of a candidate are indices into these arrays."""

    edge: np.ndarray        # (F,) parent edge
    a: FloatArray           # (F, 2)
    b: FloatArray           # (F, 2)
    offset: FloatArray      # (F,) arc length of a along the parent edge
    center: FloatArray      # (F,) angle of -n
    half: FloatArray        # (F,) friction half-angle


def features(polygon: Polygon, mu: float = 0.0, hand: Hand | None = None,
             edges: Any = None) -> Features:
    """Contactable pieces of the edges (of ``edges`` only, if given): whole usable edges,
    or their parts a :class:`~fcgrasp.Hand` can reach (section 8.2).

    Every step of the pipeline needs them for every batch, so the last few are kept
    (the arrays are read-only)."""
    key = None if edges is None else tuple(sorted({int(e) for e in edges}))
    return _features(polygon, float(mu), hand, key)


@lru_cache(maxsize=8)
def _features(polygon: Polygon, mu: float, hand: Hand | None,
              edges: tuple[int, ...] | None) -> Features:
    rows = []
    if hand is None:
        ivs = [[(0.0, float(L))] if polygon.usable[e] else [] for e, L in
               enumerate(polygon.lengths)]
    else:
        ivs = hand.feasible_intervals(polygon, min_length=LEXIMIN_STEP * polygon.size)
    wanted = None if edges is None else set(int(e) for e in edges)
    for e, lst in enumerate(ivs):
        if wanted is not None and e not in wanted:
            continue
        for t0, t1 in lst:
            rows.append((e, t0, t1))
    if not rows:
        z = np.zeros((0, 2))
        return Features(np.zeros(0, int), z, z, np.zeros(0), np.zeros(0), np.zeros(0))
    ei = np.array([r[0] for r in rows])
    s0 = np.array([r[1] for r in rows])
    s1 = np.array([r[2] for r in rows])
    tan = polygon.tangents[ei]
    a = polygon.starts[ei] + s0[:, None] * tan
    b = polygon.starts[ei] + s1[:, None] * tan
    n = polygon.normals[ei]
    center = np.arctan2(-n[:, 1], -n[:, 0])
    out = Features(ei, a, b, s0, center, np.full(len(ei), float(np.arctan(mu))))
    for arr in (out.edge, out.a, out.b, out.offset, out.center, out.half):
        arr.flags.writeable = False
    return out


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


def _keep_best(score: FloatArray, keep: int) -> np.ndarray:
    """Indices (sorted) of the ``keep`` best scores and of every score tied with the last
    of them, so that which of equal candidates survive does not depend on numbering."""
    thr = np.partition(score, score.size - keep)[score.size - keep]
    return np.flatnonzero(score >= thr - RANK_TOL * abs(thr))


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


def _distinct_edges(F: Features, t: np.ndarray) -> np.ndarray:
    e = F.edge[t]
    k = t.shape[1]
    ok = np.ones(len(t), dtype=bool)
    for x in range(k):
        for y in range(x + 1, k):
            ok &= e[:, x] != e[:, y]
    return t[ok]


def _combos(s: int, r: int) -> Iterator[np.ndarray]:
    """Every increasing ``r``-tuple (r = 1, 2 or 3) of ``range(s)``, in blocks."""
    if r == 1:
        if s > 0:
            yield np.arange(s)[:, None]
        return
    if r == 2:
        a, b = np.triu_indices(s, 1)
        if a.size:
            yield np.stack([a, b], axis=1)
        return
    for first in range(s - 2):
        a, b = np.triu_indices(s - first - 1, 1)
        block = np.empty((a.size, 3), dtype=int)
        block[:, 0] = first
        block[:, 1] = a + first + 1
        block[:, 2] = b + first + 1
        yield block


def _layouts(t: np.ndarray, fingers: int, gravity: bool) -> np.ndarray:
    """Candidate rows of sorted feature tuples ``t``: pairs as they are; triples plus the
    gravity contact (-1); 4-tuples as they are; with four fingers on three edges (no
    gravity, ``t`` of width 3) the three layouts doubling each feature (first and third)."""
    if fingers == 2 or t.shape[1] == 4 or (fingers == 3 and not gravity):
        return t
    if gravity:
        return np.concatenate([t, -np.ones((len(t), 1), int)], axis=1)
    return np.concatenate([np.stack([t[:, x], t[:, y], t[:, x], t[:, z]], axis=1)
                           for x, y, z in ((0, 1, 2), (1, 0, 2), (2, 0, 1))])


def _row_bound(lengths: FloatArray, rows: np.ndarray) -> FloatArray:
    """Upper bound of the smallest region of each row: no region is longer than its
    feature, and two fingers on one feature (first and third) share it, so one of them
    has at most half of it.  Gravity (-1) has no region."""
    L = np.where(rows >= 0, lengths[np.maximum(rows, 0)], np.inf)
    if rows.shape[1] == 4:
        same = rows[:, 0] == rows[:, 2]
        L[same, 0] *= 0.5
        L[same, 2] = L[same, 0]
    return L.min(axis=1)




def _spans_plane(angles: FloatArray) -> bool:
    """Whether directions at sorted ``angles`` in [0, 2 pi) may positively span the plane
    (no gap between neighbours, cyclically, wider than half a turn plus the slack)."""
    if angles.size < 3:
        return False
    gaps = np.diff(np.concatenate([angles, angles[:1] + 2 * np.pi]))
    return bool(gaps.max() <= np.pi + SPAN_SLACK)


def _ordered_rows(F: Features, spec: PlanSpec, three_edge: bool, size: int,
                  first: int) -> Iterator[EdgeSets]:
    """Every candidate row, streamed by decreasing bound (branch and bound).

    Features are sorted by decreasing length; a row's *last* feature in that order is its
    shortest, so the rows are enumerated by their last position ``s``: every row whose
    features all come before ``s``'s has a bound at least the length at ``s``.  Batches
    grow from ``first`` rows, doubling, to ``size``, so that a search whose top is found
    early stops after little work.
    """
    lengths = np.hypot(*(F.b - F.a).T)
    n = lengths.size
    order = np.lexsort((np.arange(n), -lengths))
    g = spec.gravity
    gravity = g is not None
    widths = [1] if spec.fingers == 2 else [2] if spec.fingers == 3 else \
        ([3, 2] if three_edge else [3])
    # frictionless fingers hold only if their force directions positively span the plane
    # (theorem 4.2; gravity counts as one): rows whose features all come from positions
    # 0..s whose directions leave a gap of half a turn cannot, so such s are skipped
    seen = [] if g is None else [float(wrap_positive(np.arctan2(g[1], g[0])))]
    buf: list[np.ndarray] = []
    count = 0
    target = min(first, size)
    ceiling = np.inf
    for s in range(n):
        if not count:
            ceiling = float(lengths[order[s]])
        if spec.contact_type == "frictionless":
            bisect.insort(seen, float(wrap_positive(F.center[order[s]])))
            if not _spans_plane(np.array(seen)):
                continue
        for r in widths:
            for block in _combos(s, r):
                t = np.sort(order[np.concatenate([block, np.full((len(block), 1), s)],
                                                 axis=1)], axis=1)
                t = _distinct_edges(F, t)
                if not len(t):
                    continue
                buf.append(_layouts(t, spec.fingers, gravity))
                count += len(buf[-1])
                while count >= target:
                    rows = np.concatenate(buf)
                    yield EdgeSets(rows[:target], _row_bound(lengths, rows[:target]), ceiling)
                    # the rows left over come from position s: bounded by its length
                    buf, count = [rows[target:]], len(rows) - target
                    ceiling = float(lengths[order[s]])
                    target = min(2 * target, size)
    if count:
        rows = np.concatenate(buf)
        yield EdgeSets(rows, _row_bound(lengths, rows), ceiling)


def _quad_candidates(F: Features, margin: float, gravity: FloatArray | None,
                     centroid: FloatArray, feats: np.ndarray, tol: float = SOLVER_TOL,
                     floor: float = 0.0) -> Candidates:
    """Grasp-set geometry and problems of four-finger (or three plus gravity) rows.
    Pairings tied on the smallest region are told apart by the next leximin levels only
    in rows that reach ``floor`` (the others cannot enter the top; their score, the
    tied value, is the same whichever pairing is kept)."""
    B = len(feats)
    g_ang = 0.0 if gravity is None else float(np.arctan2(gravity[1], gravity[0]))
    real = feats >= 0
    fi = np.where(real, feats, 0)
    a = np.where(real[..., None], F.a[fi], centroid)
    b = np.where(real[..., None], F.b[fi], centroid)
    center = np.where(real, F.center[fi], g_ang)
    dirs = np.stack([np.cos(center), np.sin(center)], axis=-1)
    ok = force_direction_closure(dirs) if B else np.zeros(0, bool)
    feats, a, b, center, dirs = feats[ok], a[ok], b[ok], center[ok], dirs[ok]
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


@dataclass(frozen=True)
class SearchSize:
    """How big a search is, before it starts (see :func:`search_size`).

    ``rows``: candidate edge sets (an upper bound when a hand splits edges); ``batch_rows``:
    rows per streamed batch; ``peak_bytes``: memory of one batch being solved;
    ``kept_bytes``: memory of what is kept across batches (every row's plan with
    ``top=None``, else the top of each batch); ``seconds``: a rough time on one core.
    """

    features: int
    rows: int
    batch_rows: int
    peak_bytes: int
    kept_bytes: int
    seconds: float
    budget: int

    @property
    def fits(self) -> bool:
        return self.peak_bytes + self.kept_bytes <= self.budget


def _rows(fingers: int, n: int, three_edge: bool = True) -> int:
    if fingers == 2:
        return comb(n, 2)
    if fingers == 3:
        return comb(n, 3)
    return comb(n, 4) + (3 * comb(n, 3) if three_edge else 0)


def _estimate(spec: PlanSpec, n: int) -> tuple[int, int, int, int]:
    """(rows, batch rows, peak bytes, kept bytes) of a search over ``n`` features."""
    if spec.stretches:
        # the stretch search holds a few (n, n) arrays per ring pair; every
        # configuration of a curved outline (top=None) is about n**3 / 36 of them
        rows = n ** 3 // 36 if spec.top is None else comb(n, 2)
        held = rows if spec.top is None else min(rows, 2 * max(spec.top, KEEP_STRETCHES))
        return rows, rows, STRETCH_BYTES * n * n, held * KEPT_ROW_BYTES
    rows = _rows(spec.fingers, n)
    per = ROW_BYTES[spec.fingers]
    cap = BATCH_SIZE if spec.fingers == 2 else TUPLE_BATCH_SIZE
    batch = int(max(1, min(cap, spec.max_memory // 2 // per)))
    peak = min(rows, batch) * per
    if spec.top is None:
        held = rows
    else:
        keep = spec.top if spec.rank_by == "min_region" else KEEP_FOR_MEASURE
        held = min(rows, _reduce_rows(spec) + 2 * keep)
    return rows, batch, peak, held * KEPT_ROW_BYTES


def _reduce_rows(spec: PlanSpec) -> int:
    """Rows :func:`rank` holds beyond its running top before folding them in."""
    return int(min(REDUCE_ROWS, max(1000, spec.max_memory // 4 // KEPT_ROW_BYTES)))


def search_size(polygon: Polygon, spec: PlanSpec, edges: Any = None) -> SearchSize:
    """The size of the search :func:`candidates` -> :func:`solve` -> :func:`rank` will do,
    and the batch size that keeps it within ``spec.max_memory``.

    Batches take at most half the budget (``ROW_BYTES`` per row, at most
    :data:`BATCH_SIZE` rows of two fingers, :data:`TUPLE_BATCH_SIZE` of three or four);
    what :func:`rank` keeps across batches must fit as well (``KEPT_ROW_BYTES`` per
    row): its running top, at most ``REDUCE_ROWS`` (fewer on small
    budgets) plus twice the top, or with ``top=None`` every row; see :func:`check_search`.

    >>> from fcgrasp.io.parts import demo_part
    >>> s = search_size(demo_part("quad"), plan_spec(fingers=4))
    >>> s.rows, s.fits
    (13, True)
    """
    n = len(features(polygon, spec.mu, spec.hand, edges).edge)
    rows, batch, peak, kept = _estimate(spec, n)
    return SearchSize(n, rows, batch, peak, kept, rows * ROW_SECONDS[spec.fingers],
                      spec.max_memory)


def _fmt_bytes(b: float) -> str:
    for unit in ("B", "KB", "MB", "GB", "TB"):
        if b < 1024:
            return f"{b:.3g} {unit}"
        b /= 1024
    return f"{b:.3g} PB"


def check_search(polygon: Polygon, spec: PlanSpec) -> SearchSize:
    """The :func:`search_size` of a plan, or :class:`SearchTooLarge` (a ValueError) when it
    cannot fit ``spec.max_memory``, saying what would: how many edges fit, a ``top``, fewer
    fingers."""
    size = search_size(polygon, spec)
    if size.fits:
        return size
    fit = 2
    while fit < size.features and sum(_estimate(spec, fit + 1)[2:]) <= spec.max_memory:
        fit += 1
    what = {2: "two-finger", 3: "three-finger", 4: "four-finger"}[spec.fingers]
    hint = "plan on single edges (along_boundary=False, --single-edge), or " \
        if spec.stretches and spec.top is not None else \
        "give a top (--top K), or " if spec.top is None else \
        "ask for fewer plans (--top), " if spec.top * KEPT_ROW_BYTES > spec.max_memory // 4 \
        else ""
    raise SearchTooLarge(
        f"a {what} search of this part ({size.features} edges, {size.rows:.3g} candidate "
        f"edge sets) would need about {_fmt_bytes(size.peak_bytes + size.kept_bytes)}, above "
        f"the memory budget of {_fmt_bytes(spec.max_memory)} (max_memory, --max-memory): "
        f"{hint}simplify the outline to at most about {fit} edges (--simplify TOL), or plan "
        f"with fewer fingers")


def candidates(polygon: Polygon, spec: PlanSpec, edges: Any = None,
               batch_size: int | None = None) -> Iterator[EdgeSets]:
    """Stream the candidate edge sets of a part in batches of at most ``batch_size`` rows,
    by decreasing upper bound of their smallest region (:class:`EdgeSets`).

    Two fingers: every pair of features on distinct edges.  Four: every 4-tuple on
    distinct edges and every three edges with one doubled.  Three: every triple on
    distinct edges (with gravity, plus the gravity contact -1).  ``edges`` restricts
    the features to those edges (with four fingers and an edge given twice, only the
    layouts doubling that edge).  With a ``top``, batches
    start small and double up to ``batch_size``, so a search that finds its top among
    the first rows stops after little work (:func:`search`); the stream itself always
    holds every row.
    """
    F = features(polygon, spec.mu, spec.hand, edges)
    size = search_size(polygon, spec, edges).batch_rows if batch_size is None else \
        check_int(batch_size, "batch_size", minimum=1)
    first = size if spec.top is None else FIRST_BATCH
    doubled = None
    three_edge = spec.fingers == 4
    if edges is not None and spec.fingers == 4:
        idx = [int(e) for e in edges]
        twice = [e for e in set(idx) if idx.count(e) == 2]
        doubled = twice[0] if twice else None
        three_edge = doubled is not None
    for sets in _ordered_rows(F, spec, three_edge, size, first):
        if doubled is not None:
            rows = sets.feats
            keep = (F.edge[rows[:, 0]] == doubled) & (rows[:, 0] == rows[:, 2])
            if not keep.any():
                continue
            assert sets.bound is not None
            sets = EdgeSets(rows[keep], sets.bound[keep], sets.ceiling)
        yield sets


def grasp_geometry(polygon: Polygon, spec: PlanSpec, sets: EdgeSets,
                   edges: Any = None, floor: float = 0.0) -> Candidates:
    """The grasp sets of a batch (section 6) and their region problems, scored by the
    largest smallest region (stage 1, exact unless two fingers share an edge, when it is
    an upper bound).  Rows that fail the force-direction constraint are dropped; with two
    fingers, so are rows with no regions.  With a ``floor`` (:attr:`TopK.floor`) and a
    ``top``, two-finger rows below the floor are dropped too, and four-finger pairings
    tied on the smallest region are told apart only in the rows that reach it."""
    if spec.fingers == 3 and spec.gravity is None:
        raise ValueError("three fingers with friction are solved by linear programs: "
                         "fcgrasp.grippers.three_fingers.three_finger_plans, not grasp_geometry")
    F = features(polygon, spec.mu, spec.hand, edges)
    feats = np.asarray(sets.feats, dtype=int)
    if spec.fingers == 2:
        return _pair_candidates(F, spec.margin_rad, feats[:, 0], feats[:, 1], spec.tol,
                                floor if spec.top is not None else 0.0)
    gravity = None if spec.gravity is None else np.array(spec.gravity)
    return _quad_candidates(F, spec.margin_rad, gravity, polygon.centroid,
                            feats.reshape(-1, 4), spec.tol, floor)


# ----------------------------------------------------------------------------- regions

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


def _problems(c: Candidates, rows: np.ndarray, a: FloatArray, b: FloatArray,
              margin: float) -> list[KnapsackProblem]:
    """Region problems of candidate ``rows`` with the finger segments ``a``-``b``."""
    if c.feats.shape[1] == 2:
        return two_finger_problems(a[:, 0], b[:, 0], c.center[rows, 0], c.half[rows, 0],
                                   a[:, 1], b[:, 1], c.center[rows, 1], c.half[rows, 1],
                                   margin)[0]
    return four_finger_problems(a, b, c.center[rows], c.perm[rows], margin)[0]


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


def _place(c: Candidates, rows: np.ndarray, a: FloatArray, b: FloatArray,
           lengths: FloatArray, mode: np.ndarray, margin: float) -> FloatArray:
    """Region parameters (R, n, 2), finger order, for the chosen levels and modes."""
    probs = _problems(c, rows, a, b, margin)
    perm = c.perm[rows]
    ridx = np.arange(len(rows))[:, None]
    lev_p = np.maximum(lengths, 0.0)[ridx, perm]          # problem order
    inv = np.argsort(perm, axis=1)
    params = np.zeros(a.shape[:2] + (2,))
    for m, pr in enumerate(probs):
        sel = mode == m
        if sel.any():
            pp = place_regions(pr.take(np.flatnonzero(sel)), lev_p[sel])
            params[sel] = pp[np.arange(sel.sum())[:, None], inv[sel]]
    return params


def _split_search(c: Candidates, rows: np.ndarray, margin: float, iters: int = 80
                  ) -> tuple[FloatArray, FloatArray]:
    """Best split point of the edge shared by fingers 0 and 2 (golden-section search on
    the concave optimum of the smallest region).  Returns the segments (a, b)."""
    a0, b0 = c.a[rows, 0], c.b[rows, 0]
    L = np.hypot(*(b0 - a0).T)
    t = (b0 - a0) / np.where(L > 0, L, 1.0)[:, None]
    best = np.full(len(rows), -np.inf)
    best_a, best_b = c.a[rows].copy(), c.b[rows].copy()

    def segments(sig: FloatArray, first_low: bool) -> tuple[FloatArray, FloatArray]:
        a, b = c.a[rows].copy(), c.b[rows].copy()
        cut = a0 + sig[:, None] * t
        lo_f, hi_f = (0, 2) if first_low else (2, 0)
        b[:, lo_f] = cut
        a[:, hi_f] = cut
        return a, b

    def value(sig: FloatArray, first_low: bool) -> FloatArray:
        probs = _problems(c, rows, *segments(sig, first_low), margin)
        return np.max([np.where(pr.separable, max_min_length(pr, c.tol), -1.0) for pr in probs],
                      axis=0)

    gr = (np.sqrt(5) - 1) / 2
    for first_low in (True, False):
        lo, hi = np.zeros(len(rows)), L.copy()
        x1, x2 = hi - gr * (hi - lo), lo + gr * (hi - lo)
        f1, f2 = value(x1, first_low), value(x2, first_low)
        for _ in range(iters):
            left = f1 >= f2
            hi = np.where(left, x2, hi)
            lo = np.where(left, lo, x1)
            nx1 = np.where(left, hi - gr * (hi - lo), x2)
            nx2 = np.where(left, x1, lo + gr * (hi - lo))
            fnew = value(np.where(left, nx1, nx2), first_low)
            f1, f2 = np.where(left, fnew, f2), np.where(left, f1, fnew)
            x1, x2 = nx1, nx2
        sig = 0.5 * (lo + hi)
        val = value(sig, first_low)
        better = val > best
        a, b = segments(sig, first_low)
        best = np.where(better, val, best)
        best_a[better], best_b[better] = a[better], b[better]
    return best_a, best_b


def _levels(c: Candidates, rows: np.ndarray, margin: float
            ) -> tuple[FloatArray, FloatArray, FloatArray, np.ndarray]:
    """Leximin lengths (R, n) in finger order for candidate ``rows``, with the segments
    the fingers range over (split where two fingers share an edge) and the mode."""
    a, b = c.a[rows].copy(), c.b[rows].copy()
    lengths, mode = _best_levels([p.take(rows) for p in c.problems], c.perm[rows], c.tol)
    if c.feats.shape[1] == 4:
        same = (c.feats[rows, 0] == c.feats[rows, 2]) & (c.feats[rows, 0] >= 0)
        same &= lengths.min(axis=1) > 0
        if same.any():
            sub = np.flatnonzero(same)
            params = _place(c, rows[sub], a[sub], b[sub], lengths[sub], mode[sub], margin)
            over = np.minimum(params[:, 0, 1], params[:, 2, 1]) > \
                np.maximum(params[:, 0, 0], params[:, 2, 0])
            fix = sub[over]
            if fix.size:
                sa, sb = _split_search(c, rows[fix], margin)
                lv, md = _best_levels(_problems(c, rows[fix], sa, sb, margin),
                                      c.perm[rows[fix]], c.tol)
                a[fix], b[fix], lengths[fix], mode[fix] = sa, sb, lv, md
    return lengths, a, b, mode


def _region_ends(seg_a: FloatArray, seg_b: FloatArray, params: FloatArray) -> FloatArray:
    """End points (n, 2, 2) of regions at arc-length ``params`` (n, 2) along segments."""
    L = np.hypot(*(seg_b - seg_a).T)
    tdir = (seg_b - seg_a) / np.where(L > 0, L, 1.0)[:, None]
    return seg_a[:, None, :] + params[:, :, None] * tdir[:, None, :]



def region_levels(cands: Candidates, rows: np.ndarray, spec: PlanSpec
                  ) -> tuple[FloatArray, FloatArray, FloatArray, np.ndarray]:
    """Leximin region lengths (R, n) of candidate ``rows`` in finger order, the segments
    the fingers range over (split where two share an edge) and the mode."""
    return _levels(cands, np.asarray(rows, dtype=int), spec.margin_rad)


def _break_ties(polygon: Polygon, c: Candidates, rows: np.ndarray, a: FloatArray,
                b: FloatArray, lengths: FloatArray, mode: np.ndarray, margin: float
                ) -> np.ndarray:
    """Among pairings and modes with the same leximin levels (corollary 5.1 makes them
    equivalent without a margin), place the regions of each and keep the placement of
    least :func:`geometric_key`, so that a renumbered part gets the same regions.

    Updates ``c.perm`` for ``rows`` and returns the modes.  Rows where two fingers share
    an edge keep their split search's answer.
    """
    mode = mode.copy()
    if c.feats.shape[1] != 4 or rows.size == 0:
        return mode
    sel = np.flatnonzero(c.feats[rows, 0] != c.feats[rows, 2])
    if sel.size == 0:
        return mode
    # stage 1 first: only rows where a second option reaches the same smallest region
    # need the whole leximin order of every option
    built = []
    reach = np.zeros(sel.size, dtype=int)
    smallest = np.min(np.where(lengths[sel] > 0, lengths[sel], np.inf), axis=1)
    for P in PAIRINGS:
        perm = np.broadcast_to(P, (sel.size, 4)).copy()
        probs = four_finger_problems(a[sel], b[sel], c.center[rows[sel]], perm, margin)[0]
        for m, pr in enumerate(probs):
            mm = np.where(pr.separable, max_min_length(pr, c.tol), -1.0)
            reach += mm >= smallest - RANK_TOL * np.maximum(smallest, polygon.size)
            built.append((P, m, perm, pr))
    keep = reach >= 2
    if not keep.any():
        return mode
    sel = sel[keep]
    options = []                                   # (pairing, mode, levels in finger order)
    for P, m, perm, pr in built:
        inv = np.argsort(perm[keep], axis=1)
        lev = np.where(pr.separable[keep][:, None], leximin(pr.take(keep), c.tol), -1.0)
        options.append((P, m, lev[np.arange(sel.size)[:, None], inv]))
    for i, r in enumerate(sel):
        want = np.maximum(lengths[r], 0.0)[None]
        tied = [(P, m) for P, m, lev in options
                if not _lex_greater(want, lev[i:i + 1])[0]
                and not _lex_greater(lev[i:i + 1], want)[0]]
        if len(tied) < 2:
            continue
        best: tuple[Any, ...] | None = None
        for P, m in tied:
            c.perm[rows[r]] = P
            params = _place(c, rows[r:r + 1], a[r:r + 1], b[r:r + 1], lengths[r:r + 1],
                            np.array([m]), margin)[0]
            real = c.feats[rows[r]] >= 0
            key = geometric_key(_region_ends(a[r][real], b[r][real], params[real]), polygon)
            if best is None or key < best[0]:
                best = (key, P, m)
        assert best is not None
        c.perm[rows[r]] = best[1]
        mode[r] = best[2]
    return mode


def _build_plans(polygon: Polygon, F: Features, c: Candidates, rows: np.ndarray,
                 lengths: FloatArray, a: FloatArray, b: FloatArray, mode: np.ndarray,
                 mu: float, margin_deg: float, contact_type: str,
                 gravity: FloatArray | None, disturbance: tuple[float, float]
                 ) -> list[GraspPlan]:
    """GraspPlan objects for candidate ``rows`` with their leximin levels."""
    keep = np.all((lengths > 0) | (c.feats[rows] < 0), axis=1)
    rows, lengths, a, b, mode = rows[keep], lengths[keep], a[keep], b[keep], mode[keep]
    if rows.size == 0:
        return []
    margin = margin_radians(margin_deg)
    mode = _break_ties(polygon, c, rows, a, b, lengths, mode, margin)
    params = _place(c, rows, a, b, lengths, mode, margin)
    rho = characteristic_length(polygon.vertices, polygon.centroid)
    plans = []
    for r in range(len(rows)):
        real = c.feats[rows[r]] >= 0
        fi = c.feats[rows[r]][real]
        ends = _region_ends(a[r][real], b[r][real], params[r][real])
        edges = tuple(int(F.edge[f]) for f in fi)
        g = None
        if gravity is not None:
            g = {"center": polygon.centroid.copy(), "direction": gravity.copy()}
        plans.append(GraspPlan(edges, ends, lengths[r][real], ends.mean(axis=1),
                               polygon.normals[list(edges)], contact_type, mu,
                               c.modes[int(mode[r])], margin_deg, g,
                               centroid=polygon.centroid.copy(), radius=rho,
                               disturbance=disturbance))
    return plans



# ----------------------------------------------------------------------------- solve, rank


@dataclass
class Solved:
    """A solved batch: the candidates that can reach the top, with their leximin region
    lengths (finger order), segments and modes.  Picklable."""

    cands: Candidates
    lengths: FloatArray
    a: FloatArray
    b: FloatArray
    mode: np.ndarray

    @staticmethod
    def concat(parts: list[Solved]) -> Solved:
        parts = [p for p in parts if len(p.lengths)]
        if not parts:
            raise ValueError("nothing to concatenate")
        return Solved(Candidates.concat([p.cands for p in parts]),
                      np.concatenate([p.lengths for p in parts]),
                      np.concatenate([p.a for p in parts]),
                      np.concatenate([p.b for p in parts]),
                      np.concatenate([p.mode for p in parts]))

    def take(self, idx: Any) -> Solved:
        """The solved rows ``idx``."""
        return Solved(self.cands.take(idx), self.lengths[idx], self.a[idx], self.b[idx],
                      self.mode[idx])


def _select(lengths: FloatArray, feats: np.ndarray, size: float, top: int | None
            ) -> np.ndarray:
    """Rows (sorted) with positive regions, the ``top`` best by leximin and their ties."""
    real = feats >= 0
    ok = np.all((lengths > 0) | ~real, axis=1)
    keys = [(leximin_key(lengths[r][real[r]], size), r) for r in np.flatnonzero(ok)]
    keys.sort()
    if top is not None and len(keys) > top:
        keys = [kr for kr in keys if kr[0] <= keys[top - 1][0]]
    return np.array(sorted(r for _, r in keys), dtype=int)


def _smallest_region(feats: np.ndarray, lengths: FloatArray) -> FloatArray:
    """The smallest region of each row among its real fingers (gravity's region has
    length zero and would keep a top-k search from ever stopping)."""
    return np.where(feats >= 0, lengths, np.inf).min(axis=1)


def solve(polygon: Polygon, spec: PlanSpec, sets: EdgeSets, edges: Any = None,
          progress: Any = None, floor: float = 0.0) -> Solved:
    """Grasp sets and optimal regions of a batch of candidate edge sets.

    With ``spec.top``, only the rows that can still reach the top (ties included) get
    their leximin levels: rows are taken by their stage-1 bound, in chunks, until no
    later row can reach the top-th smallest region found.  The union of the batches'
    tops holds the global top, so :func:`rank` of the solved batches is the same as of
    one batch.  ``floor`` (:attr:`TopK.floor`): rows whose smallest region cannot reach
    it are dropped unsolved, first by the batch's bounds (before any geometry), then by
    their stage-1 bound; 0 keeps every row.
    """
    floor = check_scalar(floor, "floor", nonnegative=True)
    if spec.top is None:
        floor = 0.0
    if floor > 0 and sets.bound is not None:
        reach = sets.bound >= floor
        sets = EdgeSets(sets.feats[reach], sets.bound[reach], sets.ceiling)
    c = grasp_geometry(polygon, spec, sets, edges, floor)
    margin = spec.margin_rad
    good = np.flatnonzero((c.score > 0) & (c.score >= floor))
    order = good[np.lexsort((np.arange(good.size), -c.score[good]))]
    top = spec.top
    if top is not None and spec.rank_by == "min_region":
        parts = []
        start = 0
        chunk = max(2 * top, 16)
        best = np.zeros(0)          # the top smallest regions so far, largest first
        while start < order.size:
            rows = order[start:start + chunk]
            parts.append((rows, *_levels(c, rows, margin)))
            start += chunk
            chunk *= 2              # a long run of bounds above the top needs few calls
            if progress is not None:
                progress(min(start, order.size), order.size)
            mins = _smallest_region(c.feats[rows], parts[-1][1])
            best = np.sort(np.concatenate([best, mins]))[::-1][:top]
            # stop when no later candidate can reach (or tie) the top-th smallest region
            if start >= order.size or (best.size >= top and best[top - 1] >
                                       c.score[order[start]] + RANK_TOL * polygon.size):
                break
        if parts:
            rows = np.concatenate([x[0] for x in parts])
            lv = np.concatenate([x[1] for x in parts])
            a_ = np.concatenate([x[2] for x in parts])
            b_ = np.concatenate([x[3] for x in parts])
            md = np.concatenate([x[4] for x in parts])
        else:
            rows, lv, a_, b_, md = order, *_levels(c, order, margin)
    else:
        if top is not None and order.size > KEEP_FOR_MEASURE:
            # a subsequence of order: still by decreasing bound
            order = order[_keep_best(c.score[order], KEEP_FOR_MEASURE)]
        rows = order
        lv, a_, b_, md = _levels(c, rows, margin)
        if progress is not None:
            progress(order.size, order.size)
    pick = _select(lv, c.feats[rows], polygon.size, top if spec.rank_by == "min_region"
                   else None)
    return Solved(c.take(rows[pick]), lv[pick], a_[pick], b_[pick], md[pick])


class TopK:
    """The running top of a search: solved batches folded in as they come (the reduce
    of :func:`rank`), and the :attr:`floor` a row must reach to enter it.

    >>> from fcgrasp.io.parts import demo_part
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
                                              KEEP_FOR_MEASURE)
        self._parts: list[Solved] = []
        self._held = 0
        self._floor = 0.0

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
           batch_size: int | None = None, map: Any = None) -> list[GraspPlan]:
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

    >>> from fcgrasp.io.parts import demo_part
    >>> [p.edges for p in search(demo_part("quad"), plan_spec(fingers=4, top=1))]
    [(0, 1, 2, 3)]
    """
    top = TopK(polygon, spec, edges)
    total = search_size(polygon, spec, edges).rows if progress is not None else 0
    done = 0
    window: list[EdgeSets] = []

    def fold() -> None:
        nonlocal done
        floor = top.floor
        live = [b for b in window if b.ceiling >= floor]
        if map is None:
            results: Iterable[Solved] = [solve(polygon, spec, b, edges, floor=floor)
                                         for b in live]
        else:
            results = map(partial(solve, polygon, spec, edges=edges, floor=floor), live)
        for solved in results:
            top.add(solved)
        done += sum(len(b.feats) for b in window)
        window.clear()
        if progress is not None:
            progress(min(done, total), total)

    for batch in candidates(polygon, spec, edges, batch_size):
        if batch.ceiling < top.floor:
            break
        window.append(batch)
        if map is None or len(window) >= MAP_WINDOW:
            fold()
    if window:
        fold()
    if progress is not None and done < total:
        progress(total, total)
    return top.plans()


def every_plan(polygon: Polygon, spec: PlanSpec, edges: Any = None,
               batch_size: int | None = None) -> Iterator[GraspPlan]:
    """Every single-edge plan of a part (``top=None``), streamed: each batch of
    :func:`candidates` is solved and its plans yielded (in rank order within the batch;
    batches by decreasing bound of their rows), so memory is bounded by one batch
    whatever the part's size, where ``plan(..., top=None)`` must hold every plan to rank
    them and refuses parts whose plans would not fit (:class:`SearchTooLarge`).

    >>> from fcgrasp.io.parts import demo_part
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
                     radius=characteristic_length(polygon.vertices, polygon.centroid),
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


def ranked_unique(polygon: Polygon, spec: PlanSpec, plans: list[GraspPlan]
                   ) -> list[GraspPlan]:
    """Plans in :func:`rank_key` order (the best ``spec.top``), a grasp reached by two
    configurations of one mode once."""
    scores = MEASURES[spec.rank_by].score(plans) if plans else np.zeros(0)
    keyed = sorted((rank_key(p, polygon, spec.rank_by, float(q)), k)
                   for k, (p, q) in enumerate(zip(plans, scores, strict=True)))
    out: list[GraspPlan] = []
    seen = set()
    for key, k in keyed:
        if (key, plans[k].mode) in seen:
            continue
        seen.add((key, plans[k].mode))
        out.append(plans[k])
    return out if spec.top is None else out[:spec.top]


def _reaches_a_vertex(polygon: Polygon, p: GraspPlan) -> bool:
    """Some region of a single-edge plan ends at an end of its edge (elsewhere the
    regions are held back by each other, not by their edges)."""
    tol = LEXIMIN_STEP * polygon.size
    for e, (x, y) in zip(p.edges, p.ends, strict=True):
        for v in (polygon.starts[e], polygon.ends[e]):
            if min(np.hypot(*(x - v)), np.hypot(*(y - v))) <= tol:
                return True
    return False


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
    flat = replace(spec, along_boundary=False,
                   top=None if spec.top is None else max(spec.top, GROW_SEEDS))
    seeds = search(polygon, flat, progress=progress, map=map)
    rows = [p.edges for p in seeds[:GROW_SEEDS]
            if len(set(p.edges)) == len(p.edges) and _reaches_a_vertex(polygon, p)]
    plans = list(seeds)
    if rows:
        grown = grow_stretches(polygon, rows, spec.margin,
                               None if spec.gravity is None else np.array(spec.gravity),
                               keep_single=False)
        plans += [frictionless_plan(polygon, spec, r) for r in grown
                  if r is not None and max(len(e) for e in r.region_edges) > 1]
    return ranked_unique(polygon, spec, plans)


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
    by_min = spec.rank_by == "min_region"
    keep = spec.top if by_min or spec.top is None else max(spec.top, KEEP_STRETCHES)
    pairs = two_finger_stretches(polygon, spec.mu, spec.margin, top=keep, ties=by_min)
    multi = [p for p in pairs if max(len(e) for e in p.region_edges) > 1]
    plans = [stretch_plan(polygon, spec, p) for p in multi]
    if by_min:
        plans += _single_edge_plans(polygon, spec, [
            (p.region_edges[0][0], p.region_edges[1][0]) for p in pairs
            if max(len(e) for e in p.region_edges) == 1])
    else:
        plans += search(polygon, flat)
    return ranked_unique(polygon, spec, plans)
