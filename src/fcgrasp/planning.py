"""Grasp plans: optimal independent regions on every edge set, ranked (sections 7, 8).

:func:`independent_regions` gives the optimal regions of contact on chosen edges;
:func:`plan` enumerates every edge pair (two fingers with friction), every 4-tuple and
3-edge combination (four frictionless fingers), or every triple with gravity (three
frictionless fingers), and returns the best :class:`GraspPlan` objects.

Everything is computed in batches: all candidate edge sets of a polygon are pruned with
the force-direction constraint, their sectors computed, and their region problems solved
together (see :mod:`fcgrasp.regions` for the exact method).

Units: lengths are in the polygon's units; ``margin`` is an angle in **degrees**: every
grasp of the returned regions points at least that far inside the friction cones (two
fingers) or inside the sector ``C_12 & -C_34`` (four fingers; the pairing of the four
fingers is the one giving the largest regions, so a plan does not depend on how the edges
are numbered).  The default is
:data:`fcgrasp.regions.DEFAULT_MARGIN_DEG` (0.5 degree).  Three fingers means three
frictionless fingers holding the part against gravity (counted as a frictionless contact
at the centroid, section 3.1); friction, if any, can only help such a grasp.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from itertools import combinations
from typing import Any

import numpy as np

from ._checks import FloatArray, check_direction, check_int, check_mu_scalar, check_scalar
from ._regiongeom import four_finger_problems, two_finger_problems
from .closure import force_direction_closure
from .contacts import FrictionlessPoint, FrictionPoint, Gravity
from .grasp import Grasp
from .graspsets import Vertex
from .hand import Hand
from .polygon import Polygon
from .quality import characteristic_length, quality_of
from .ranking import MEASURES
from .regions import DEFAULT_MARGIN_DEG, KnapsackProblem, leximin, max_min_length, place_regions
from .sectors import PAIRINGS, arc_intersection, pairing_valid
from .tolerances import RANK_TOL

__all__ = ["GraspPlan", "plan", "independent_regions", "RANKINGS"]

#: Names of the ranking measures (see :mod:`fcgrasp.ranking`).
RANKINGS = tuple(MEASURES)


@dataclass
class GraspPlan:
    """One planned grasp: an edge per finger and an independent region on each.

    Attributes
    ----------
    edges : tuple of int
        Edge index per finger (input numbering).
    regions : ndarray, shape (fingers, 2, 2)
        Each region's two end points.
    lengths : ndarray, shape (fingers,)
    contacts : ndarray, shape (fingers, 2)
        The representative grasp: each region's midpoint.
    normals : ndarray, shape (fingers, 2)
        Outward normals of the edges (the fingers push along ``-normal``).
    contact_type : {"friction", "frictionless"}
    mu : float
    mode : str
        ``"squeeze"``/``"expand"`` for two fingers; ``"+C"``/``"-C"`` for four.
    margin : float
        Safety margin in degrees.
    gravity : dict or None
        ``{"center": [x, y], "direction": [gx, gy]}`` when gravity is a contact.
    quality : dict
        ``min_region``, ``resistance``, ``resistance_approx``, ``epsilon_l1``,
        ``epsilon_linf`` (see :mod:`fcgrasp.quality`).
    """

    edges: tuple[int, ...]
    regions: FloatArray
    lengths: FloatArray
    contacts: FloatArray
    normals: FloatArray
    contact_type: str
    mu: float
    mode: str
    margin: float
    gravity: dict[str, Any] | None = None
    _quality: dict[str, float] | None = field(default=None, repr=False)
    _context: tuple[Any, ...] | None = field(default=None, repr=False, compare=False)

    @property
    def quality(self) -> dict[str, float]:
        """Quality metrics at the representative grasp (computed on first use)."""
        if self._quality is None:
            self._quality = self._compute_quality()
        return self._quality

    def _compute_quality(self) -> dict[str, float]:
        if self._context is None:
            return {"min_region": self.min_length}
        centroid, rho, disturbance = self._context
        grasp = self.grasp()
        finger = np.concatenate([np.full(len(ct.points), i) for i, ct in
                                 enumerate(grasp.contacts)])
        q = quality_of(grasp.points, grasp.forces, finger, centroid, rho,
                       disturbance[0], disturbance[1], finger < self.fingers)
        q["min_region"] = self.min_length
        return q

    @property
    def min_length(self) -> float:
        """Length of the smallest region (the paper's tolerance measure)."""
        return float(np.min(self.lengths))

    @property
    def fingers(self) -> int:
        return len(self.edges)

    def contacts_for(self, points: Any) -> list[Any]:
        pts = np.asarray(points, dtype=float)
        out: list[Any] = []
        for p, n in zip(pts, self.normals, strict=True):
            if self.contact_type == "friction":
                out.append(FrictionPoint(p, n, self.mu))
            else:
                out.append(FrictionlessPoint(p, n))
        if self.gravity is not None:
            out.append(Gravity(self.gravity["center"], self.gravity["direction"]))
        return out

    def grasp(self, points: Any = None) -> Grasp:
        """The :class:`~fcgrasp.Grasp` at ``points`` (default: the representative grasp)."""
        return Grasp(self.contacts_for(self.contacts if points is None else points))

    def sample(self, n: int, rng: np.random.Generator | None = None) -> FloatArray:
        """``n`` grasps with each finger uniform in its region, shape (n, fingers, 2)."""
        rng = np.random.default_rng() if rng is None else rng
        u = rng.random((n, self.fingers))
        a, b = self.regions[:, 0], self.regions[:, 1]
        return a[None] + u[..., None] * (b - a)[None]

    def corners(self) -> FloatArray:
        """All corner grasps of the box of regions, shape (2**fingers, fingers, 2)."""
        idx = np.array(list(np.ndindex(*(2,) * self.fingers)))
        return self.regions[np.arange(self.fingers)[None, :], idx]

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready description (floats rounded to 12 significant digits)."""
        from .report import json_ready

        d: dict[str, Any] = {
            "edges": [int(e) for e in self.edges],
            "contact_type": self.contact_type,
            "mu": self.mu,
            "mode": self.mode,
            "regions": self.regions,
            "region_lengths": self.lengths,
            "min_region_length": self.min_length,
            "contacts": self.contacts,
            "normals": self.normals,
            "quality": dict(sorted(self.quality.items())),
        }
        if self.gravity is not None:
            d["gravity"] = dict(self.gravity)
        return json_ready(d)


# ----------------------------------------------------------------------------- features


@dataclass
class _Features:
    """Contactable pieces of edges (whole edges, or their feasible parts under a hand)."""

    edge: np.ndarray        # (F,) parent edge
    a: FloatArray           # (F, 2)
    b: FloatArray           # (F, 2)
    offset: FloatArray      # (F,) arc length of a along the parent edge
    center: FloatArray      # (F,) angle of -n
    half: FloatArray        # (F,) friction half-angle


def _features(polygon: Polygon, mu: float, hand: Hand | None,
              edges: Any = None) -> _Features:
    """Contactable pieces of the edges (of ``edges`` only, if given)."""
    rows = []
    if hand is None:
        ivs = [[(0.0, float(L))] if polygon.usable[e] else [] for e, L in
               enumerate(polygon.lengths)]
    else:
        ivs = hand.feasible_intervals(polygon, min_length=1e-9 * polygon.size)
    wanted = None if edges is None else set(int(e) for e in edges)
    for e, lst in enumerate(ivs):
        if wanted is not None and e not in wanted:
            continue
        for t0, t1 in lst:
            rows.append((e, t0, t1))
    if not rows:
        z = np.zeros((0, 2))
        return _Features(np.zeros(0, int), z, z, np.zeros(0), np.zeros(0), np.zeros(0))
    ei = np.array([r[0] for r in rows])
    s0 = np.array([r[1] for r in rows])
    s1 = np.array([r[2] for r in rows])
    tan = polygon.tangents[ei]
    a = polygon.starts[ei] + s0[:, None] * tan
    b = polygon.starts[ei] + s1[:, None] * tan
    n = polygon.normals[ei]
    center = np.arctan2(-n[:, 1], -n[:, 0])
    return _Features(ei, a, b, s0, center, np.full(len(ei), float(np.arctan(mu))))


# ----------------------------------------------------------------------------- candidates


@dataclass
class _Candidates:
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


def _score(c: _Candidates) -> None:
    vals = np.stack([np.where(p.separable, max_min_length(p), -1.0) for p in c.problems])
    c.best_mode = np.argmax(vals, axis=0)
    c.score = vals.max(axis=0)


def _cand_take(c: _Candidates, idx: np.ndarray) -> _Candidates:
    out = _Candidates(c.feats[idx], c.a[idx], c.b[idx], c.center[idx], c.half[idx], c.perm[idx],
                      [p.take(idx) for p in c.problems], c.modes)
    out.score, out.best_mode = c.score[idx], c.best_mode[idx]
    return out


def _cand_concat(parts: list[_Candidates]) -> _Candidates:
    def cat(xs: list[Any]) -> Any:
        return np.concatenate(xs)

    probs = [KnapsackProblem.concat([p.problems[m] for p in parts]) for m in range(2)]
    out = _Candidates(cat([p.feats for p in parts]), cat([p.a for p in parts]),
                      cat([p.b for p in parts]), cat([p.center for p in parts]),
                      cat([p.half for p in parts]), cat([p.perm for p in parts]), probs,
                      parts[0].modes)
    out.score = cat([p.score for p in parts])
    out.best_mode = cat([p.best_mode for p in parts])
    return out


def _pair_candidates(F: _Features, margin: float, i: np.ndarray, j: np.ndarray) -> _Candidates:
    keep = F.edge[i] != F.edge[j]
    i, j = i[keep], j[keep]
    # quick sector test before building anything
    _, half = arc_intersection(F.center[i], F.half[i], F.center[j] + np.pi, F.half[j])
    ok = half - margin > 0
    i, j = i[ok], j[ok]
    probs, _ = two_finger_problems(F.a[i], F.b[i], F.center[i], F.half[i],
                                   F.a[j], F.b[j], F.center[j], F.half[j], margin)
    c = _Candidates(np.stack([i, j], axis=1), np.stack([F.a[i], F.a[j]], 1),
                    np.stack([F.b[i], F.b[j]], 1), np.stack([F.center[i], F.center[j]], 1),
                    np.stack([F.half[i], F.half[j]], 1), np.tile([0, 1], (len(i), 1)), probs,
                    ("squeeze", "expand"))
    _score(c)
    return c


#: Edge pairs solved per batch; larger polygons are processed in batches of about this
#: size, keeping only the best candidates of each, so memory stays bounded.
PAIR_BATCH = 2_000_000


def _keep_best(score: FloatArray, keep: int) -> np.ndarray:
    """Indices (sorted) of the ``keep`` best scores and of every score tied with the last
    of them, so that which of equal candidates survive does not depend on numbering."""
    thr = np.partition(score, score.size - keep)[score.size - keep]
    return np.flatnonzero(score >= thr - RANK_TOL * abs(thr))


def _two_finger(F: _Features, margin: float, keep: int | None = None) -> _Candidates:
    """All candidate pairs (or, for large polygons, the ``keep`` best by smallest region)."""
    n = len(F.edge)
    if n * (n - 1) // 2 <= PAIR_BATCH or keep is None:
        i, j = np.triu_indices(n, k=1)
        return _pair_candidates(F, margin, i, j)
    parts: list[_Candidates] = []
    start = 0
    while start < n - 1:
        # rows start..stop-1 hold about PAIR_BATCH pairs
        rows_left = np.arange(start, n - 1)
        cum = np.cumsum(n - 1 - rows_left)
        stop = start + max(1, int(np.searchsorted(cum, PAIR_BATCH)))
        ii = np.concatenate([np.full(n - 1 - r, r) for r in range(start, min(stop, n - 1))])
        jj = np.concatenate([np.arange(r + 1, n) for r in range(start, min(stop, n - 1))])
        c = _pair_candidates(F, margin, ii, jj)
        if len(c.score) > keep:
            c = _cand_take(c, _keep_best(c.score, keep))
        parts.append(c)
        merged = _cand_concat(parts)
        if len(merged.score) > keep:
            merged = _cand_take(merged, _keep_best(merged.score, keep))
        parts = [merged]
        start = min(stop, n - 1)
    return parts[0]


def _four_finger(F: _Features, margin: float, gravity: FloatArray | None,
                 centroid: FloatArray, three_edge: bool = True) -> _Candidates:
    nF = len(F.edge)
    tuples: list[np.ndarray] = []
    if gravity is None:
        q = np.array(list(combinations(range(nF), 4)), dtype=int).reshape(-1, 4)
        q = q[np.all((F.edge[q][:, :, None] != F.edge[q][:, None, :])
                     | np.eye(4, dtype=bool)[None], axis=(1, 2))]
        tuples.append(q)
        t = np.array(list(combinations(range(nF), 3)), dtype=int).reshape(-1, 3)
        t = t[(F.edge[t[:, 0]] != F.edge[t[:, 1]]) & (F.edge[t[:, 1]] != F.edge[t[:, 2]])
              & (F.edge[t[:, 0]] != F.edge[t[:, 2]])]
        for x, y, z in ((0, 1, 2), (1, 0, 2), (2, 0, 1)) if three_edge else ():
            # the doubled feature first
            tuples.append(np.stack([t[:, x], t[:, y], t[:, x], t[:, z]], axis=1))
        feats = np.concatenate(tuples) if tuples else np.zeros((0, 4), int)
    else:
        t = np.array(list(combinations(range(nF), 3)), dtype=int).reshape(-1, 3)
        t = t[(F.edge[t[:, 0]] != F.edge[t[:, 1]]) & (F.edge[t[:, 1]] != F.edge[t[:, 2]])
              & (F.edge[t[:, 0]] != F.edge[t[:, 2]])]
        feats = np.concatenate([t, -np.ones((len(t), 1), int)], axis=1)
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
            per_mode[rows, k, m] = np.where(pr.separable, max_min_length(pr), -1.0)
        scores[rows, k] = per_mode[rows, k].max(axis=1)
        built[k] = (rows, probs)
    choice = np.argmax(scores, axis=1)
    top_s = scores[np.arange(B), choice]
    tied = np.flatnonzero((top_s > 0) & (np.sum(scores >= top_s[:, None] - RANK_TOL *
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
                                 np.broadcast_to(p, (pos.size, 4)).copy())
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
    c = _Candidates(feats, a, b, center, np.zeros_like(center), perm, probs, ("+C", "-C"))
    pm = per_mode[np.arange(B), choice]
    c.best_mode = np.argmax(pm, axis=1)
    c.score = pm.max(axis=1)
    return c


# ----------------------------------------------------------------------------- regions


def _lex_greater(a: FloatArray, b: FloatArray, rtol: float = RANK_TOL) -> np.ndarray:
    """Row-wise leximin comparison ``a > b`` of length vectors, with a relative tolerance.

    Entries equal to 0 with a negative counterpart are regions of fixed points (gravity).
    """
    sa, sb = np.sort(a, axis=1), np.sort(b, axis=1)
    scale = np.maximum(np.maximum(np.abs(sa).max(axis=1), np.abs(sb).max(axis=1)), 1e-300)
    diff = sa - sb
    big = np.abs(diff) > rtol * scale[:, None]
    first = np.argmax(big, axis=1)
    rows = np.arange(len(a))
    return big.any(axis=1) & (diff[rows, first] > 0)


def _problems(c: _Candidates, rows: np.ndarray, a: FloatArray, b: FloatArray,
              margin: float) -> list[KnapsackProblem]:
    """Region problems of candidate ``rows`` with the finger segments ``a``-``b``."""
    if c.feats.shape[1] == 2:
        return two_finger_problems(a[:, 0], b[:, 0], c.center[rows, 0], c.half[rows, 0],
                                   a[:, 1], b[:, 1], c.center[rows, 1], c.half[rows, 1],
                                   margin)[0]
    return four_finger_problems(a, b, c.center[rows], c.perm[rows], margin)[0]


def _best_levels(probs: list[KnapsackProblem], perm: np.ndarray
                 ) -> tuple[FloatArray, np.ndarray]:
    """Leximin lengths (finger order) of the better mode, and that mode."""
    R = len(perm)
    inv = np.argsort(perm, axis=1)
    ridx = np.arange(R)[:, None]
    lengths = np.full(perm.shape, -1.0)
    mode = np.zeros(R, dtype=int)
    for m, pr in enumerate(probs):
        # both modes are solved: when their smallest regions tie, the next levels decide
        lev = np.where(pr.separable[:, None], leximin(pr), -1.0)[ridx, inv]
        better = _lex_greater(lev, lengths)
        lengths[better] = lev[better]
        mode[better] = m
    return lengths, mode


def _place(c: _Candidates, rows: np.ndarray, a: FloatArray, b: FloatArray,
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


def _split_search(c: _Candidates, rows: np.ndarray, margin: float, iters: int = 80
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
        return np.max([np.where(pr.separable, max_min_length(pr), -1.0) for pr in probs],
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


def _levels(c: _Candidates, rows: np.ndarray, margin: float
            ) -> tuple[FloatArray, FloatArray, FloatArray, np.ndarray]:
    """Leximin lengths (R, n) in finger order for candidate ``rows``, with the segments
    the fingers range over (split where two fingers share an edge) and the mode."""
    a, b = c.a[rows].copy(), c.b[rows].copy()
    lengths, mode = _best_levels([p.take(rows) for p in c.problems], c.perm[rows])
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
                                      c.perm[rows[fix]])
                a[fix], b[fix], lengths[fix], mode[fix] = sa, sb, lv, md
    return lengths, a, b, mode


def _region_ends(seg_a: FloatArray, seg_b: FloatArray, params: FloatArray) -> FloatArray:
    """End points (n, 2, 2) of regions at arc-length ``params`` (n, 2) along segments."""
    L = np.hypot(*(seg_b - seg_a).T)
    tdir = (seg_b - seg_a) / np.where(L > 0, L, 1.0)[:, None]
    return seg_a[:, None, :] + params[:, :, None] * tdir[:, None, :]


def geometric_key(regions: FloatArray, polygon: Polygon) -> tuple[float, ...]:
    """A key of a set of regions that does not depend on how the part is numbered.

    Each region's two ends are sorted, the regions are sorted, and the coordinates
    (relative to the part's centroid and size, rounded to 1e-9) are read in that order.
    Used to break ties between equally good plans or placements.
    """
    rel = np.round((np.asarray(regions, float) - polygon.centroid) / polygon.size, 9) + 0.0
    segs = sorted(tuple(sorted(map(tuple, r.tolist()))) for r in rel)
    return tuple(x for seg in segs for pt in seg for x in pt)


def _break_ties(polygon: Polygon, c: _Candidates, rows: np.ndarray, a: FloatArray,
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
    R = rows[sel]
    options = []                                   # (pairing, mode, levels in finger order)
    for P in PAIRINGS:
        perm = np.broadcast_to(P, (sel.size, 4)).copy()
        probs = four_finger_problems(a[sel], b[sel], c.center[R], perm, margin)[0]
        inv = np.argsort(perm, axis=1)
        for m, pr in enumerate(probs):
            lev = np.where(pr.separable[:, None], leximin(pr), -1.0)
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


def _build_plans(polygon: Polygon, F: _Features, c: _Candidates, rows: np.ndarray,
                 lengths: FloatArray, a: FloatArray, b: FloatArray, mode: np.ndarray,
                 mu: float, margin_deg: float, contact_type: str,
                 gravity: FloatArray | None, disturbance: tuple[float, float]
                 ) -> list[GraspPlan]:
    """GraspPlan objects for candidate ``rows`` with their leximin levels."""
    keep = np.all((lengths > 0) | (c.feats[rows] < 0), axis=1)
    rows, lengths, a, b, mode = rows[keep], lengths[keep], a[keep], b[keep], mode[keep]
    if rows.size == 0:
        return []
    mode = _break_ties(polygon, c, rows, a, b, lengths, mode, np.radians(margin_deg))
    params = _place(c, rows, a, b, lengths, mode, np.radians(margin_deg))
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
                               _context=(polygon.centroid, rho, disturbance)))
    return plans


def _check_common(polygon: Any, mu: Any, margin: Any, hand: Any
                  ) -> tuple[float, float]:
    if not isinstance(polygon, Polygon):
        raise TypeError(f"polygon must be a Polygon, got {type(polygon).__name__}")
    mu_v = check_mu_scalar(mu, "mu")
    margin_v = check_scalar(margin, "margin", nonnegative=True)
    if margin_v >= 90.0:
        raise ValueError(f"margin is an angle in degrees below 90, got {margin!r}")
    if hand is not None and not isinstance(hand, Hand):
        raise TypeError(f"hand must be a Hand or None, got {type(hand).__name__}")
    return mu_v, margin_v


def _leximin_key(lengths: FloatArray, size: float) -> tuple[float, ...]:
    """Sort key of the leximin order (definition 7.1): smaller is better."""
    return tuple(-np.round(np.sort(np.asarray(lengths, float)) / size, 9))


def rank_key(p: GraspPlan, polygon: Polygon, rank_by: str = "min_region",
             score: float | None = None) -> tuple[Any, ...]:
    """The sort key of :func:`plan` (smaller is better), independent of numbering.

    ``min_region``: the leximin order of the region lengths (definition 7.1); any other
    measure of :data:`fcgrasp.ranking.MEASURES`: its score (larger first, to 9
    significant digits), then the leximin order.  Remaining ties are broken by
    :func:`geometric_key`.
    """
    lex = _leximin_key(p.lengths, polygon.size)
    geo = geometric_key(p.regions, polygon)
    if rank_by == "min_region":
        return (lex, geo)
    q = MEASURES[rank_by].score([p])[0] if score is None else score
    q = -1.0 if not np.isfinite(q) else float(f"{q:.9g}")
    return (-q, lex, geo)


def _check_disturbance(disturbance: Any) -> tuple[float, float]:
    if isinstance(disturbance, (str, bytes)) or np.ndim(disturbance) != 1 \
            or len(disturbance) != 2:
        raise ValueError(f"disturbance must be (translation, rotation in degrees), got "
                         f"{disturbance!r}")
    return (check_scalar(disturbance[0], "disturbance[0]", positive=True),
            check_scalar(disturbance[1], "disturbance[1]", positive=True))


def plan(polygon: Polygon, fingers: int = 2, mu: float = 0.0, top: int | None = 10,
         rank_by: str = "min_region", hand: Hand | None = None,
         margin: float = DEFAULT_MARGIN_DEG, gravity: Any = (0.0, -1.0),
         disturbance: tuple[float, float] = (10.0, 15.0),
         progress: Any = None) -> list[GraspPlan]:
    """Ranked grasp plans of a polygon (sections 7.2, 7.3 and 8).

    Parameters
    ----------
    polygon : Polygon
    fingers : {2, 3, 4}
        2: two fingers with friction ``mu``; 4: four frictionless fingers on four edges or
        on three edges (two on one edge); 3: three frictionless fingers and gravity.
    mu : float
        Friction coefficient (two fingers).
    top : int or None
        How many plans to return (None: all).
    rank_by : {"min_region", "resistance", "epsilon"}
        Largest smallest region first; largest resistance first (the paper's order); or
        largest Ferrari-Canny L1 measure first.
    hand : Hand, optional
        Workspace and finger radius (section 8.2): regions lie in the feasible parts.
    margin : float
        Safety margin in degrees inside the cones and sectors.
    gravity : array_like, shape (2,)
        Direction of the weight for ``fingers=3``.
    disturbance : (float, float)
        Translation (in the polygon's units) and rotation (degrees) of the resistance
        measure; default 10 units (1 cm in millimetres) and 15 degrees.
    progress : callable, optional
        Called as ``progress(done, total)`` while candidate edge sets are solved.

    Returns
    -------
    list of GraspPlan
        Best first; empty when the part admits no such grasp.

    Examples
    --------
    >>> part = Polygon([[0, 0], [4, 0], [4, 1], [0, 1]])
    >>> best = plan(part, fingers=2, mu=0.3, top=1)[0]
    >>> best.edges, round(best.min_length, 4)      # the short sides face each other
    ((1, 3), 1.0)
    """
    mu_v, margin_v = _check_common(polygon, mu, margin, hand)
    fingers = check_int(fingers, "fingers", choices=(2, 3, 4))
    if not isinstance(rank_by, str):
        raise TypeError(f"rank_by must be a string, got {rank_by!r}")
    if rank_by not in MEASURES:
        raise ValueError(f"rank_by must be one of {', '.join(MEASURES)}, got {rank_by!r}")
    if top is not None:
        top = check_int(top, "top", minimum=1)
    dist = _check_disturbance(disturbance)
    if progress is not None and not callable(progress):
        raise TypeError(f"progress must be a callable progress(done, total) or None, "
                        f"got {progress!r}")
    margin_r = np.radians(margin_v)
    if fingers == 2:
        F = _features(polygon, mu_v, hand)
        # for very large polygons only the best candidates by smallest region are kept
        keep = None if top is None else (max(64 * top, 1024) if rank_by == "min_region"
                                         else 20_000)
        c = _two_finger(F, margin_r, keep)
        g = None
        ctype = "friction"
    else:
        F = _features(polygon, 0.0, hand)
        g = check_direction(gravity, "gravity") if fingers == 3 else None
        c = _four_finger(F, margin_r, g, polygon.centroid)
        ctype = "frictionless"
    good = np.flatnonzero(c.score > 0)
    if good.size == 0:
        return []
    order = good[np.lexsort((np.arange(good.size), -c.score[good]))]
    mu_plan = mu_v if fingers == 2 else 0.0
    if rank_by == "min_region" and top is not None:
        # the stage-1 score is the smallest region unless two fingers share an edge, when
        # it is an upper bound: take candidates in chunks until no later one can compete
        parts = []
        start = 0
        chunk = max(2 * top, 16)
        while start < order.size:
            rows = order[start:start + chunk]
            parts.append((rows, *_levels(c, rows, margin_r)))
            start += chunk
            if progress is not None:
                progress(min(start, order.size), order.size)
            mins_so_far = np.sort(np.concatenate([p[1].min(axis=1) for p in parts]))[::-1]
            # stop when no later candidate can reach (or tie) the top-th smallest region
            if start >= order.size or (mins_so_far.size >= top and mins_so_far[top - 1] >
                                       c.score[order[start]] + RANK_TOL * polygon.size):
                break
        rows = np.concatenate([x[0] for x in parts])
        lv = np.concatenate([x[1] for x in parts])
        a_ = np.concatenate([x[2] for x in parts])
        b_ = np.concatenate([x[3] for x in parts])
        md = np.concatenate([x[4] for x in parts])
        real = c.feats[rows] >= 0
        ok = np.all((lv > 0) | ~real, axis=1)
        keys = [_leximin_key(lv[r][real[r]], polygon.size) for r in range(len(rows))]
        ranked = sorted((k, r) for r, k in enumerate(keys) if ok[r])
        if len(ranked) > top:      # the top plans and every plan tied with the last of them
            ranked = [kr for kr in ranked if kr[0] <= ranked[top - 1][0]]
        pick = np.array(sorted(r for _, r in ranked), dtype=int)
        plans = _build_plans(polygon, F, c, rows[pick], lv[pick], a_[pick], b_[pick], md[pick],
                             mu_plan, margin_v, ctype, g, dist)
    else:
        lv, a_, b_, md = _levels(c, order, margin_r)
        if progress is not None:
            progress(order.size, order.size)
        plans = _build_plans(polygon, F, c, order, lv, a_, b_, md, mu_plan, margin_v, ctype,
                             g, dist)
    scores = MEASURES[rank_by].score(plans) if plans else np.zeros(0)
    order_ = sorted(range(len(plans)),
                    key=lambda k: rank_key(plans[k], polygon, rank_by, float(scores[k])))
    plans = [plans[k] for k in order_]
    return plans if top is None else plans[:top]


def independent_regions(polygon: Polygon, edges: Any, mu: float = 0.0,
                        margin: float = DEFAULT_MARGIN_DEG, hand: Hand | None = None,
                        gravity: Any = None) -> GraspPlan | None:
    """Optimal independent regions of contact on the given edges (definition 7.1).

    Parameters
    ----------
    edges : sequence of int
        Two edges (fingers with friction ``mu``: algorithm 7.1, squeezing and expanding
        grasps), four edges (frictionless: theorem 7.1; an edge may repeat, then its two
        regions do not overlap) or three edges with ``gravity``.
    margin : float
        Safety margin in degrees.

    Returns
    -------
    GraspPlan or None
        None when the edges admit no force-closure grasp with that margin.

    Examples
    --------
    >>> sq = Polygon([[0, 0], [10, 0], [10, 3], [0, 3]])
    >>> r = independent_regions(sq, (0, 2), mu=0.3)
    >>> r.regions.round(3).tolist()
    [[[4.564, 0.0], [5.436, 0.0]], [[5.436, 3.0], [4.564, 3.0]]]
    """
    mu_v, margin_v = _check_common(polygon, mu, margin, hand)
    if isinstance(edges, (str, bytes)) or np.ndim(edges) != 1:
        raise TypeError(f"edges must be a sequence of edge indices, got {edges!r}")
    if any(isinstance(e, Vertex) for e in edges):
        raise ValueError(f"edges holds a Vertex (a soft finger), got {list(edges)!r}: "
                         f"independent regions lie on edges; use grasp_set or grasp_sets "
                         f"for a soft finger at a vertex")
    idx = polygon.check_edges(edges)
    margin_r = np.radians(margin_v)
    n = len(idx)
    # only the pieces of the asked edges are enumerated
    if n == 2:
        if gravity is not None:
            raise ValueError("gravity is counted with three frictionless fingers, not two")
        F = _features(polygon, mu_v, hand, edges=idx)
        c = _two_finger(F, margin_r)
        g = None
    elif n in (3, 4):
        if mu_v != 0:
            raise ValueError(f"regions of {n} fingers are frictionless: mu must be 0, got {mu}")
        if (n == 3) != (gravity is not None):
            raise ValueError("three edges need gravity=..., four edges take no gravity")
        F = _features(polygon, 0.0, hand, edges=idx)
        g = None if gravity is None else check_direction(gravity, "gravity")
        doubled = [e for e in set(idx) if idx.count(e) == 2]
        if n == 4 and (len(doubled) != 1 or len(set(idx)) != 3) and len(set(idx)) != 4:
            raise ValueError(f"four fingers need four distinct edges or three with one twice, "
                             f"got {list(idx)}")
        c = _four_finger(F, margin_r, g, polygon.centroid, three_edge=bool(doubled))
        if doubled:    # keep the layout with the asked edge doubled
            keep = np.flatnonzero((F.edge[c.feats[:, 0]] == doubled[0])
                                  & (c.feats[:, 0] == c.feats[:, 2]))
            c = _cand_take(c, keep)
    else:
        raise ValueError(f"edges must hold 2, 3 (with gravity) or 4 edge indices, got {n}")
    rows = np.flatnonzero(c.score > 0)
    if rows.size == 0:
        return None
    lv, a_, b_, md = _levels(c, rows, margin_r)
    best = 0
    for k in range(1, len(rows)):
        if _lex_greater(lv[k:k + 1], lv[best:best + 1])[0]:
            best = k
    sel = np.array([best])
    plans = _build_plans(polygon, F, c, rows[sel], lv[sel], a_[sel], b_[sel], md[sel],
                         mu_v if n == 2 else 0.0, margin_v,
                         "friction" if n == 2 else "frictionless", g, (10.0, 15.0))
    if not plans:
        return None
    p = plans[0]
    # report the fingers in the order asked for
    order: list[int] = []
    for e in idx:
        order.append(next(k for k, pe in enumerate(p.edges) if pe == e and k not in order))
    o = np.array(order)
    return GraspPlan(tuple(p.edges[k] for k in o), p.regions[o], p.lengths[o], p.contacts[o],
                     p.normals[o], p.contact_type, p.mu, p.mode, p.margin, p.gravity,
                     _context=p._context)
