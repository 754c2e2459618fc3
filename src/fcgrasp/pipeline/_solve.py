"""Solving a batch of candidate edge sets: the grasp sets, the leximin levels and the
placement of the optimal regions (part of :mod:`fcgrasp.pipeline`; theorem 7.1,
algorithm 7.1)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, cast

import numpy as np

from ..core._angles import margin_radians
from ..core._checks import (
    FloatArray,
    check_scalar,
)
from ..core._geom import leximin_columns
from ..core.sectors import PAIRINGS
from ..core.tolerances import ESTIMATE_PAD, PLACE_SURE_GAP, RANK_TOL
from ..model._quad_estimates import below as estimate_below
from ..model._regiongeom import four_finger_problems, two_finger_problems
from ..model.plans import GraspPlan, geometric_key, leximin_key
from ..model.polygon import Polygon
from ..model.regions import (
    KnapsackProblem,
    leximin,
    max_min_length,
    place_regions,
    place_regions_sure,
)
from . import _spec  # the search's tunables, read when used
from ._candidates import (
    Candidates,
    EdgeSets,
    Features,
    _best_levels,
    _lex_greater,
    grasp_geometry,
    quad_estimates,
)
from ._rows import _keep_best
from ._spec import (
    PlanSpec,
)

# ----------------------------------------------------------------------------- regions



def _problems(c: Candidates, rows: np.ndarray, a: FloatArray, b: FloatArray,
              margin: float) -> list[KnapsackProblem]:
    """Region problems of candidate ``rows`` with the finger segments ``a``-``b``."""
    if c.feats.shape[1] == 2:
        return two_finger_problems(a[:, 0], b[:, 0], c.center[rows, 0], c.half[rows, 0],
                                   a[:, 1], b[:, 1], c.center[rows, 1], c.half[rows, 1],
                                   margin)[0]
    return four_finger_problems(a, b, c.center[rows], c.perm[rows], margin)[0]




def _place(c: Candidates, rows: np.ndarray, a: FloatArray, b: FloatArray,
           lengths: FloatArray, mode: np.ndarray, margin: float) -> FloatArray:
    """Region parameters (R, n, 2), finger order, for the chosen levels and modes."""
    return _placed(c, rows, a, b, lengths, mode, margin, False)[0]


def _placed(c: Candidates, rows: np.ndarray, a: FloatArray, b: FloatArray,
            lengths: FloatArray, mode: np.ndarray, margin: float, compiled: bool
            ) -> tuple[FloatArray, np.ndarray]:
    """:func:`_place`'s parameters and which rows are sure (all, by numpy);
    ``compiled``: placed by :func:`~fcgrasp.model.regions.place_regions_sure` where it
    runs, sure where it says so."""
    probs = _problems(c, rows, a, b, margin)
    perm = c.perm[rows]
    ridx = np.arange(len(rows))[:, None]
    lev_p = np.maximum(lengths, 0.0)[ridx, perm]          # problem order
    inv = np.argsort(perm, axis=1)
    params = np.zeros(a.shape[:2] + (2,))
    sure = np.ones(len(rows), bool)
    for m, pr in enumerate(probs):
        sel = mode == m
        if sel.any():
            sub = pr.take(np.flatnonzero(sel))
            got = place_regions_sure(sub, lev_p[sel]) if compiled else None
            if got is None:
                pp = place_regions(sub, lev_p[sel])
            else:
                pp, sure[sel] = got
            params[sel] = pp[np.arange(sel.sum())[:, None], inv[sel]]
    return params, sure


def _overlapping(c: Candidates, rows: np.ndarray, a: FloatArray, b: FloatArray,
                 lengths: FloatArray, mode: np.ndarray, margin: float) -> np.ndarray:
    """Whether the regions of fingers 0 and 2 (one feature) overlap where
    :func:`_place` puts them: by the compiled placement where it is sure and the
    overlap (or gap) exceeds :data:`~fcgrasp.core.tolerances.PLACE_SURE_GAP` of the
    feature, by :func:`_place` elsewhere (the same booleans)."""
    params, sure = _placed(c, rows, a, b, lengths, mode, margin, True)

    def gap(pp: FloatArray) -> FloatArray:
        return cast("FloatArray", np.minimum(pp[:, 0, 1], pp[:, 2, 1])
                    - np.maximum(pp[:, 0, 0], pp[:, 2, 0]))

    g = gap(params)
    feature = np.hypot(*(b[:, 0] - a[:, 0]).T)
    sure &= np.abs(g) > PLACE_SURE_GAP * feature
    if not sure.all():
        redo = np.flatnonzero(~sure)
        g[redo] = gap(_place(c, rows[redo], a[redo], b[redo], lengths[redo], mode[redo],
                             margin))
    return cast("np.ndarray", g > 0)


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
            over = _overlapping(c, rows[sub], a[sub], b[sub], lengths[sub], mode[sub],
                                margin)
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


def tie_options(polygon: Polygon, c: Candidates, rows: np.ndarray, a: FloatArray,
                b: FloatArray, lengths: FloatArray, margin: float
                ) -> tuple[np.ndarray, list[tuple[Any, int, FloatArray]]] | None:
    """The rows of four fingers (positions ``sel`` in ``rows``, fingers on distinct
    edges) where a second pairing or mode reaches the same smallest region, and every
    option's leximin levels there in finger order: ``(sel, [(pairing, mode, levels)])``,
    or None where no row has two such options (the tie-break's first stage)."""
    if c.feats.shape[1] != 4 or rows.size == 0:
        return None
    sel = np.flatnonzero(c.feats[rows, 0] != c.feats[rows, 2])
    if sel.size == 0:
        return None
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
        return None
    sel = sel[keep]
    options = []                                   # (pairing, mode, levels in finger order)
    for P, m, perm, pr in built:
        inv = np.argsort(perm[keep], axis=1)
        lev = np.where(pr.separable[keep][:, None], leximin(pr.take(keep), c.tol), -1.0)
        options.append((P, m, lev[np.arange(sel.size)[:, None], inv]))
    return sel, options


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
    found = tie_options(polygon, c, rows, a, b, lengths, margin)
    if found is None:
        return mode
    sel, options = found
    # the options tied with each row's levels (both ways not greater), all rows at once
    want = np.maximum(lengths[sel], 0.0)
    tied = np.array([~_lex_greater(want, lev) & ~_lex_greater(lev, want)
                     for _, _, lev in options])                  # (options, rows)
    many = np.flatnonzero(tied.sum(axis=0) >= 2)
    if many.size == 0:
        return mode
    # every tied option of those rows placed, one batch per option: the least key wins
    best: dict[int, tuple[Any, ...]] = {}
    saved = c.perm[rows[sel[many]]].copy()
    for o, (P, m, _) in enumerate(options):
        at = many[tied[o, many]]
        if at.size == 0:
            continue
        r = sel[at]
        c.perm[rows[r]] = P
        params = _place(c, rows[r], a[r], b[r], lengths[r], np.full(r.size, m), margin)
        for k, rr in enumerate(r):
            real = c.feats[rows[rr]] >= 0
            key = geometric_key(_region_ends(a[rr][real], b[rr][real], params[k][real]),
                                polygon)
            if int(rr) not in best or key < best[int(rr)][0]:
                best[int(rr)] = (key, P, m)
    c.perm[rows[sel[many]]] = saved
    for rr, (_, P, m) in best.items():
        c.perm[rows[rr]] = P
        mode[rr] = m
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
    rho = polygon.radius
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


class RowScores:
    """The stage-1 scores (the largest smallest region: :func:`grasp_geometry`'s
    ``score``, exact, -1 where a row holds nothing) of the rows that searches of one
    part and one spec's geometry have solved, remembered so that a later search drops
    a row whose score cannot reach its floor without computing its geometry again (a
    distinct search of four frictionless fingers reads in its rounds the rows its
    first round read: ``icons/heart.svg`` 120,000 rows twice), and upper bounds of the
    scores of the rows a search left out by their estimate (:func:`_estimated`).  A
    row's score depends on its features only, not on the batch it comes in nor on the
    floor, so dropping what the memo says is below the floor (a bound below it: the
    score is too) drops what :func:`solve` would."""

    def __init__(self) -> None:
        self._keys: list[np.ndarray] = []
        self._values: list[FloatArray] = []
        self._sorted: tuple[np.ndarray, FloatArray] | None = None

    @staticmethod
    def _key(feats: np.ndarray) -> np.ndarray | None:
        """One integer per row (16 bits per finger's feature, gravity's -1 as 0); None
        where the features do not fit."""
        f = np.asarray(feats, dtype=np.int64)
        if f.ndim != 2 or f.shape[1] > 4 or (f.size and int(f.max()) >= 2 ** 15 - 1):
            return None
        key = np.zeros(len(f), np.int64)
        for j in range(f.shape[1]):
            key |= (f[:, j] + 1) << (16 * j)
        return key

    def add(self, feats: np.ndarray, score: FloatArray) -> None:
        """Remember the scores of solved rows (or bounds of them)."""
        key = self._key(feats)
        if key is not None and len(key):
            self._keys.append(key)
            self._values.append(np.asarray(score, dtype=float))
            self._sorted = None

    def known(self, feats: np.ndarray) -> FloatArray:
        """The remembered score of each row, or a bound of it (nan where none is)."""
        out = np.full(len(feats), np.nan)
        key = self._key(feats)
        if key is None or not self._keys or not len(key):
            return out
        if self._sorted is None:
            keys, values = np.concatenate(self._keys), np.concatenate(self._values)
            order = np.argsort(keys, kind="stable")
            self._sorted = keys[order], values[order]
            self._keys, self._values = [self._sorted[0]], [self._sorted[1]]
        keys, values = self._sorted
        at = np.minimum(np.searchsorted(keys, key), len(keys) - 1)
        hit = keys[at] == key
        out[hit] = values[at[hit]]
        return out


def _select(lengths: FloatArray, feats: np.ndarray, size: float, top: int | None
            ) -> np.ndarray:
    """Rows (sorted) with positive regions, the ``top`` best by leximin and their ties.

    Where every row has as many real fingers (a search's rows do), the leximin keys
    (:func:`~fcgrasp.core._geom.leximin_columns`) are compared as columns, by
    :func:`numpy.lexsort` (ties by row, as sorting ``(key, row)`` pairs orders them);
    else row by row."""
    real = feats >= 0
    ok = np.all((lengths > 0) | ~real, axis=1)
    rows = np.flatnonzero(ok)
    if top is None or rows.size <= top:
        return rows
    if bool(np.all(real == real[:1])):
        keys = leximin_columns(lengths[np.ix_(rows, np.flatnonzero(real[0]))], size)
        by = np.lexsort((rows, *keys.T[::-1]))
        last = keys[by[top - 1]]
        # the rows whose key is at most the top-th's (lexicographically): the first
        # column where a key differs from it decides
        diff = keys != last
        first = np.argmax(diff, axis=1)
        at = np.arange(len(keys))
        keep = ~diff.any(axis=1) | (keys[at, first] < last[first])
        return rows[keep]
    keyed = sorted((leximin_key(lengths[r][real[r]], size), r) for r in rows)
    return np.array(sorted(r for k, r in keyed if k <= keyed[top - 1][0]), dtype=int)


def _smallest_region(feats: np.ndarray, lengths: FloatArray) -> FloatArray:
    """The smallest region of each row among its real fingers (gravity's region has
    length zero and would keep a top-k search from ever stopping)."""
    return np.where(feats >= 0, lengths, np.inf).min(axis=1)


def _estimated(polygon: Polygon, spec: PlanSpec, sets: EdgeSets, edges: Any, floor: float,
               scores: RowScores | None) -> EdgeSets:
    """The rows of four frictionless fingers (or three with gravity) but those whose
    compiled estimate (:func:`~fcgrasp.pipeline._candidates.quad_estimates`, never below
    the score) is below ``floor`` by more than its pad: :func:`grasp_geometry` would
    score them below it.  ``scores`` remembers each left-out row's estimate plus the
    pad, a bound of its score (:class:`RowScores`)."""
    est = quad_estimates(polygon, spec, sets.feats, edges)
    if est is None:
        return sets
    out = estimate_below(est, floor, polygon.size)
    if not out.any():
        return sets
    if scores is not None:
        scores.add(sets.feats[out], est[out] + ESTIMATE_PAD * polygon.size)
    return sets.take(~out)


def solve(polygon: Polygon, spec: PlanSpec, sets: EdgeSets, edges: Any = None,
          progress: Any = None, floor: float = 0.0, scores: RowScores | None = None
          ) -> Solved:
    """Grasp sets and optimal regions of a batch of candidate edge sets.

    With ``spec.top``, only the rows that can still reach the top (ties included) get
    their leximin levels: rows are taken by their stage-1 bound, in chunks, until no
    later row can reach the top-th smallest region found.  The union of the batches'
    tops holds the global top, so :func:`rank` of the solved batches is the same as of
    one batch.  ``floor`` (:attr:`TopK.floor`): rows whose smallest region cannot reach
    it are dropped unsolved, first by the batch's bounds (before any geometry), then by
    their stage-1 bound; 0 keeps every row.  ``scores``: a :class:`RowScores` that
    remembers the stage-1 score of every row whose geometry is computed here.
    """
    floor = check_scalar(floor, "floor", nonnegative=True)
    if spec.top is None:
        floor = 0.0
    if floor > 0 and sets.bound is not None:
        reach = sets.bound >= floor
        sets = sets.take(reach)
    if floor > 0:
        sets = _estimated(polygon, spec, sets, edges, floor, scores)
    c = grasp_geometry(polygon, spec, sets, edges, floor)
    if scores is not None:
        scores.add(c.feats, c.score)
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
        if top is not None and order.size > _spec.KEEP_FOR_MEASURE:
            # a subsequence of order: still by decreasing bound
            order = order[_keep_best(c.score[order], _spec.KEEP_FOR_MEASURE)]
        rows = order
        lv, a_, b_, md = _levels(c, rows, margin)
        if progress is not None:
            progress(order.size, order.size)
    pick = _select(lv, c.feats[rows], polygon.size, top if spec.rank_by == "min_region"
                   else None)
    return Solved(c.take(rows[pick]), lv[pick], a_[pick], b_[pick], md[pick])
