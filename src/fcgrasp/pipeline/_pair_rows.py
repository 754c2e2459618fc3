"""Frictionless fingers on a regular polygon: the rows that can reach a floor, from
pairs of nearly opposite edges (``icons/circle.svg``, the regular 500-gon).

On a regular polygon every edge's normal passes through the centre, so every row of
four edges has the same bound (:func:`~fcgrasp.pipeline._candidates._row_bound`, and
the stage-1 score: half an edge), while the best rows, two exactly opposite pairs,
reach a little less (the margin).  The branch and bound then solves every one of
``C(n, 4)`` rows.  This module bounds a row by the *coupling* of its two force
circuits, and shows that a row near half an edge is made of two pairs of nearly
opposite edges, so that the rows reaching a high floor are found among pairs of pairs.

**The bound** (margin-free; the search's regions, with the margin and one pairing of
theorem 7.1, are no longer).  Let edge ``i`` have unit force ``n_i``, length ``L_i``,
and ``g_i`` the foot of a point ``c`` on it (arc length along the force turned back a
quarter turn, the same turn for every edge, from the edge's first end that way).  A
rotation of sense + about a point ``x`` is not resisted by contacts at ``s_i`` when
every torque ``s_i - g_i(x)`` is >= 0; with regions ``[a_i, b_i]`` some placement lets
it through when ``g_i(x) <= b_i`` for every ``i`` (and sense -: ``g_i(x) >= a_i``).
``g_i(x)`` is affine in ``x`` with gradient the tangent, so by Farkas' lemma every
placement holds exactly when there are positive dependencies ``rho``, ``sigma`` of the
forces (``sum rho_i n_i = 0``) with ``sum rho_i (b_i - g_i) < 0 < sum sigma_i (a_i -
g_i)`` (the sums do not depend on ``c``).  They can be taken among the two extreme rays
of the forces' dependencies, and they differ (else ``sum rho_i (b_i - a_i) < 0``).
Half of each inequality, normalised (``p = rho / 2|rho|``, ``q = sigma / 2|sigma|``),
summed, each region taken at its least (``b_i - a_i >= t``, ``0 <= a_i``, ``b_i <=
L_i``):

    t  <  sum |p_i - q_i| gamma_i / sum max(p_i, q_i),

``gamma_i = g_i`` where ``p_i >= q_i``, else ``L_i - g_i``: :func:`coupled_bounds`
(both assignments of the rays, the larger).  Each inequality alone bounds ``t`` too:
``t < rho . g`` and ``t < sigma . (L - g)`` (rays normalised to sum 1), and no region is
longer than its edge; the bound of a row is the least of the three (for the better
assignment).

**The short edges.**  A row reaching ``F`` has only edges of ``F`` or longer, so
``Gamma`` below is taken over those (:meth:`PairRows.gamma_at`): a tiny edge whose foot
is far off it (``icons/key.svg``, a circle drawn as two arcs, has one between them)
no longer hides every other edge's.

**The pairs.**  With ``Gamma >= max(g_i, L_i - g_i)`` over the edges and ``sum
max(p_i, q_i) <= 1``, a row reaching ``t >= F`` has ``sum_i min(rho^_i, sigma^_i) <
eps = 2 (1 - F / Gamma)`` (normalised rays).  Where ``eps < 1/4``: the rays' supports
(two or three forces each, all four together) share at most two forces ``u``, ``v``;
a ray's weights on a triple are the sines between the other two, so ``rho^_u + rho^_v
= 1 - rho^_k >= 1/2`` (the triangle inequality) and both shared forces cannot be light
in one ray; so ``u`` is light in one ray and ``v`` in the other, and a light weight
(``< eps``) means the other two forces of its triple have a cross product below
``2 eps / (1 - eps)`` and a negative dot product (at or above it they would weigh at
least ``1 / (1 + sqrt 2)``).  The row is then two disjoint pairs of nearly opposite
forces: :meth:`PairRows.reaching` enumerates the pairs of such pairs and keeps those
whose :func:`coupled_bounds` reach ``F``.  Two fingers on one edge share a force, so
their rays share the other two with equal weights (``sum min >= 1/2``): such rows
never reach ``F`` where ``eps < 1/4``.

**One pair per circuit.**  Each ray is then heavy on one of the pairs ``(a, b)``, its
weight on the third force ``x`` light (``rho_x < eps``); as ``|rho_a n_a + rho_b n_b| =
rho_x``, ``|rho_a - rho_b| <= rho_x``, so ``rho . g <= (g_a + g_b) / 2 + eps max(0,
max g - min(g_a, g_b))`` (the largest ``g`` over the edges of ``F`` or longer).  A row
reaching ``F`` has a pair whose bound on ``g`` reaches ``F`` (carrying ``rho``) and
another whose bound on ``L - g`` does (carrying ``sigma``): the pairs read are those of
one list and the other (:meth:`PairRows._sides`).  On a circle of two arcs whose
centres are apart, the best rows are two pairs of opposite edges as far off each
other's lines as the centres let them, above half an edge; the pairs whose offset is
on the wrong side for either circuit are left out (``icons/key.svg``, four fingers:
285,000 pairs of pairs read, of 8 million within the width, and of 744 million rows).

**Three fingers and gravity.**  Gravity is a fixed force at the centroid, the point
``c`` the feet are taken from: its terms vanish, and the sums above run over the three
fingers only (``sum max <= 1`` still), so ``sum min < eps`` over the fingers.  Where
gravity is not one of the two shared forces, the case above gives two pairs, one of
them gravity's; where it is, only the other shared force counts, and its light weight
makes gravity and a finger nearly opposite; where a ray is a pair, either it holds
gravity, or the other ray's triple holds gravity and a finger nearly opposite to it
(its shared force light).  So a row near ``Gamma`` has a finger nearly
opposite to gravity (the same width), and the rows read are those fingers with any
two others (tested against every row's bound, as above).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core._checks import FloatArray
from ..core.jit import CompiledLoops
from ..core.tolerances import PAIR_PAD, PAIR_RAY_TOL
from ..model.polygon import Polygon
from ._candidates import EdgeSets, features
from ._rows_kernels import sort_first
from ._spec import PlanSpec

#: Weights of a circuit's forces within this (cross products of unit forces) count as
#: zero: the circuit is kept, so a bound is never lost to rounding.
RAY_TOL = PAIR_RAY_TOL
#: What the bound of a row and the floor are padded by (relative), for rounding.
PAD = PAIR_PAD
#: Seed rows: at least this many of the best bounds among pairs of each edge's most
#: nearly opposite partners (with gravity: the rows of the two edges most nearly
#: opposite to it).
SEED_ROWS = 256
#: Features from which the pairs are not tried (their table of partners).
MAX_FEATURES = 20_000
#: Rows (``C(n, 4)``, with gravity ``C(n, 3)``) from which the pairs are tried: below,
#: the stream of every row is quick, and a strict search keeps its exact ties as it
#: met them.
MIN_ROWS = 5_000_000


def _circuits(n: Any, row: Any, rays: Any, tol: float) -> int:
    """The positive dependencies of the forces ``n[row]`` of each triple (the fourth
    dropped), normalised to sum 1, into ``rays`` (4, 4): row ``d`` for the triple
    without force ``d``, all zero where the triple has none.  Returns how many."""
    count = 0
    for d in range(4):
        i0, i1, i2 = (1, 2, 3) if d == 0 else (0, 2, 3) if d == 1 else \
            (0, 1, 3) if d == 2 else (0, 1, 2)
        a, b, c = row[i0], row[i1], row[i2]
        wa = n[b, 0] * n[c, 1] - n[b, 1] * n[c, 0]
        wb = n[c, 0] * n[a, 1] - n[c, 1] * n[a, 0]
        wc = n[a, 0] * n[b, 1] - n[a, 1] * n[b, 0]
        if wa + wb + wc < 0:
            wa, wb, wc = -wa, -wb, -wc
        for k in range(4):
            rays[d, k] = 0.0
        s = wa + wb + wc
        if wa >= -tol and wb >= -tol and wc >= -tol and s > tol:
            wa, wb, wc = max(wa, 0.0), max(wb, 0.0), max(wc, 0.0)
            s = wa + wb + wc
            rays[d, i0], rays[d, i1], rays[d, i2] = wa / s, wb / s, wc / s
            count += 1
    return count


def _coupled(n: Any, g: Any, L: Any, row: Any, rays: Any, tol: float, fixed: int) -> float:
    """:func:`coupled_bounds` of one row (its four features ``row``; ``fixed``: the
    index of gravity's force, a fixed point with no region, -1 for none): for the
    better assignment of the rays, the least of the coupled bound and each circuit's
    own, and at most the row's shortest edge."""
    if _circuits(n, row, rays, tol) < 2:
        return 0.0
    # the two most different circuits (a pair's circuit is found twice)
    best, bi, bj = -1.0, 0, 0
    for i in range(4):
        if rays[i, 0] + rays[i, 1] + rays[i, 2] + rays[i, 3] <= 0:
            continue
        for j in range(i + 1, 4):
            if rays[j, 0] + rays[j, 1] + rays[j, 2] + rays[j, 3] <= 0:
                continue
            d = 0.0
            for k in range(4):
                d += abs(rays[i, k] - rays[j, k])
            if d > best:
                best, bi, bj = d, i, j
    if best <= PAD:
        return 0.0
    out = 0.0
    for side in range(2):
        num, den = 0.0, 0.0
        # each circuit alone: sum rho (b - g) < 0 gives t < rho . g / rho's fingers,
        # sum sigma (a - g) > 0 gives t < sigma . (L - g) / sigma's fingers
        rg, rw, sh, sw = 0.0, 0.0, 0.0, 0.0
        for k in range(4):
            p = rays[bi, k] / 2 if side == 0 else rays[bj, k] / 2
            q = rays[bj, k] / 2 if side == 0 else rays[bi, k] / 2
            f = row[k]
            if f == fixed:              # gravity at the point c: its terms vanish
                continue
            gam = g[f] if p >= q else L[f] - g[f]
            num += abs(p - q) * gam
            den += max(p, q)
            rg += p * g[f]
            rw += p
            sh += q * (L[f] - g[f])
            sw += q
        value = num / den
        if rw > 0:
            value = min(value, rg / rw)
        if sw > 0:
            value = min(value, sh / sw)
        out = max(out, value)
    # no region is longer than its edge
    for k in range(4):
        if row[k] != fixed:
            out = min(out, L[row[k]])
    return out


def _bounds_loop(n: Any, g: Any, L: Any, rows: Any, tol: float, fixed: int,
                 out: Any) -> None:
    rays = np.empty((4, 4))
    for r in range(rows.shape[0]):
        out[r] = _coupled(n, g, L, rows[r], rays, tol, fixed)


def _kept(row: Any, v: float, m: int, rows: Any, bound: Any) -> Any:
    """Append a row and its bound (the arrays grown as needed); returns them."""
    if m == rows.shape[0]:
        bigger = np.empty((2 * m, 4), np.int64)
        bigger[:m] = rows[:m]
        rows = bigger
        more = np.empty(2 * m)
        more[:m] = bound[:m]
        bound = more
    for x in range(4):
        rows[m, x] = row[x]
    bound[m] = v
    return rows, bound


def _gravity_loop(xs: Any, m_feat: int, n: Any, g: Any, L: Any, floor: float, tol: float,
                  rows: Any, bound: Any) -> Any:
    """Three fingers and gravity (its force the last, ``m_feat``): every row of a
    feature of ``xs`` and two others, sorted, gravity last, whose :func:`_coupled`
    bound reaches ``floor``; ``(rows, bounds, count)``."""
    rays = np.empty((4, 4))
    row = np.empty(4, np.int64)
    m = 0
    for x in xs:
        for y in range(m_feat):
            if y == x:
                continue
            for z in range(y + 1, m_feat):
                if z == x:
                    continue
                row[0], row[1], row[2], row[3] = x, y, z, m_feat
                sort_first(row, 4)      # gravity's index is the largest: it stays last
                v = _coupled(n, g, L, row, rays, tol, m_feat)
                if v < floor:
                    continue
                rows, bound = _kept(row, v, m, rows, bound)
                m += 1
    return rows, bound, m


def _pairs_loop(pa: Any, pb: Any, qa: Any, qb: Any, same: bool, n: Any, g: Any, L: Any,
                floor: float, tol: float, rows: Any, bound: Any) -> Any:
    """Every row of two disjoint pairs ``(pa[i], pb[i])``, ``(qa[j], qb[j])`` (``same``:
    the two lists are one, and ``i < j``), its features sorted, whose :func:`_coupled`
    bound reaches ``floor``; returns ``(rows, bounds, count)``, the arrays grown as
    needed."""
    rays = np.empty((4, 4))
    row = np.empty(4, np.int64)
    m = 0
    for i in range(pa.shape[0]):
        for j in range(i + 1 if same else 0, qa.shape[0]):
            a, b, c, d = pa[i], pb[i], qa[j], qb[j]
            if a == c or a == d or b == c or b == d:
                continue
            row[0], row[1], row[2], row[3] = a, b, c, d
            sort_first(row, 4)          # sorted, as the stream's rows are
            v = _coupled(n, g, L, row, rays, tol, -1)
            if v < floor:
                continue
            rows, bound = _kept(row, v, m, rows, bound)
            m += 1
    return rows, bound, m


_LOOPS = CompiledLoops(globals(), (_circuits, _coupled, _bounds_loop, _kept, sort_first,
                                   _gravity_loop, _pairs_loop))


def coupled_bounds(n: FloatArray, g: FloatArray, L: FloatArray, rows: np.ndarray,
                   fixed: int = -1) -> FloatArray:
    """An upper bound of each row's smallest region, four frictionless fingers on four
    edges, by the coupling of its two force circuits, each circuit alone and its
    shortest edge, the least of them (the module's docstring): ``n``
    (E, 2) unit forces, ``g`` (E,) the feet of one point (arc length from each edge's
    start), ``L`` (E,) the lengths, ``rows`` (R, 4) feature indices; ``fixed``: the
    index of gravity's force (a fixed point at ``c``: no region, out of the sums), -1
    for none.  0 where the forces do not positively span the plane.  Compiled where
    numba runs, else the same loop in Python."""
    rows = np.ascontiguousarray(rows, dtype=np.int64).reshape(-1, 4)
    out = np.empty(len(rows))
    args = (np.ascontiguousarray(n, dtype=float), np.ascontiguousarray(g, dtype=float),
            np.ascontiguousarray(L, dtype=float), rows, RAY_TOL, int(fixed), out)
    ok, _ = _LOOPS.run("_bounds_loop", *args)
    if not ok:
        _bounds_loop(*args)
    return out


class PairRows:
    """The rows of four frictionless fingers, or three and gravity (single-edge), that
    may reach a floor, from pairs of nearly opposite edges (the module's docstring): a few
    :meth:`seed` rows to raise the search's floor, then :meth:`reaching` every row
    that can reach it, or None where the floor is too low for the pairs to hold them
    all (the search then streams every row as before).

    ``c`` is the part's centroid; ``Gamma`` the largest ``max(g, L - g)``."""

    def __init__(self, polygon: Polygon, spec: PlanSpec, edges: Any = None) -> None:
        F = features(polygon, spec.mu, spec.hand, edges)
        self.n = np.stack([np.cos(F.center), np.sin(F.center)], axis=1)
        d = F.b - F.a
        self.L = np.hypot(d[:, 0], d[:, 1])
        # the tangent the torques are read along: the force turned back a quarter turn,
        # the same for every edge (a hole's edges run the other way round)
        t = np.stack([self.n[:, 1], -self.n[:, 0]], axis=1)
        ends = np.stack([np.einsum("ij,ij->i", F.a, t), np.einsum("ij,ij->i", F.b, t)])
        c = np.asarray(polygon.centroid, dtype=float)
        self.g = t @ c - ends.min(axis=0)
        #: each edge's farther end from its foot, ``max(g, L - g)``
        self.far = np.maximum(self.g, self.L - self.g)
        self.gamma = float(np.max(self.far)) if len(F.a) else 0.0
        self.angle = np.mod(F.center, 2 * np.pi)
        self.seeded: np.ndarray | None = None
        #: the rows of the lowest floor read so far (with the seed rows then left out):
        #: a higher floor's are among them
        self._read: tuple[Any, float, np.ndarray, FloatArray] | None = None
        m = self.L.size
        #: three fingers and gravity: gravity's force the last of the kernels' tables
        #: (a fixed point at the centroid ``c``: no region, its foot 0), else -1
        self.fixed = m if spec.gravity is not None else -1
        self.kn, self.kg, self.kL = self.n, self.g, self.L
        if self.fixed >= 0:
            d = np.asarray(spec.gravity, dtype=float)
            self.down = d / np.hypot(d[0], d[1])
            self.kn = np.ascontiguousarray(np.vstack([self.n, self.down]))
            self.kg, self.kL = np.append(self.g, 0.0), np.append(self.L, 0.0)
        #: no region is longer than its edge, so a row reaching ``F`` has only edges of
        #: ``F`` or longer, and ``Gamma`` is taken over those (:meth:`gamma_at`); the
        #: pairs answer from 7/8 of it only: hopeless where no floor up to the fingers'
        #: ``real``-th longest edge is above 7/8 of the ``Gamma`` of the edges as long
        real = 3 if self.fixed >= 0 else 4
        by = np.argsort(-self.L, kind="stable")
        reach = np.maximum.accumulate(self.far[by]) if m else self.far
        self.hopeless = m < real or not np.any(
            7 / 8 * reach[real - 1:] < self.L[by][real - 1:] * (1 + PAD))

    @staticmethod
    def applies(spec: PlanSpec, polygon: Polygon, edges: Any = None) -> bool:
        """Four frictionless fingers, or three and gravity, on single edges, no hand, a
        top, ranked by the smallest region, at least :data:`MIN_ROWS` rows (numba, for
        the pairs' loops, is asked only past :attr:`hopeless`: :meth:`loops`)."""
        real = 3 if spec.gravity is not None else 4
        return (spec.fingers == real and spec.contact_type == "frictionless"
                and spec.hand is None and spec.top is not None
                and spec.rank_by == "min_region" and not spec.along_boundary
                and 4 <= polygon.n_edges <= MAX_FEATURES
                and math.comb(polygon.n_edges, real) >= MIN_ROWS)

    @staticmethod
    def loops() -> bool:
        """Whether the pairs' compiled loops run here (numba started if not yet)."""
        return _LOOPS.available()

    def _out(self, rows: np.ndarray) -> np.ndarray:
        """The kernels' rows as the stream's (gravity -1)."""
        if self.fixed >= 0 and len(rows):
            rows = rows.copy()
            rows[rows == self.fixed] = -1
        return rows

    def _loop_rows(self, name: str, *args: Any) -> tuple[np.ndarray, FloatArray]:
        """The rows and bounds of one of the pairs' loops (its leading arguments
        ``args``), each row once, in the order of their features (a row of two pairs
        may be two other pairs as well; a row with gravity, two of its fingers nearly
        opposite to it)."""
        ok, got = _LOOPS.run(name, *args, np.empty((64, 4), np.int64), np.empty(64))
        if not ok:
            return np.zeros((0, 4), np.int64), np.zeros(0)
        rows, bound, m = got
        _, first = np.unique(pair_keys(rows[:m], self.kn.shape[0]), return_index=True)
        return rows[first], bound[first]

    def _gravity_rows(self, xs: np.ndarray, floor: float) -> tuple[np.ndarray, FloatArray]:
        return self._loop_rows("_gravity_loop", np.ascontiguousarray(xs, np.int64),
                               int(self.fixed), self.kn, self.kg, self.kL, float(floor),
                               RAY_TOL)

    def _opposite_gravity(self, half_width: float | None) -> np.ndarray:
        """The forces within ``half_width`` of opposite to gravity (None: the two
        nearest), with a negative dot product."""
        dot = self.n @ self.down
        cross = np.abs(self.n[:, 0] * self.down[1] - self.n[:, 1] * self.down[0])
        up = np.flatnonzero(dot < 0)
        if half_width is None:
            return up[np.argsort(cross[up], kind="stable")[:2]]
        return up[cross[up] < math.sin(half_width)]

    def _pairs(self, half_width: float) -> tuple[np.ndarray, np.ndarray]:
        """The pairs ``x < y`` of forces with a negative dot product and a cross product
        below ``sin(half_width)`` (at most ``half_width`` from opposite; found from the
        sorted angles, then tested exactly)."""
        ang = self.angle
        order = np.argsort(ang, kind="stable")
        s = ang[order]
        lo = np.searchsorted(s, np.mod(s + np.pi - half_width - PAD, 2 * np.pi))
        hi = np.searchsorted(s, np.mod(s + np.pi + half_width + PAD, 2 * np.pi),
                             side="right")
        count = np.where(hi >= lo, hi - lo, hi + s.size - lo)
        x = np.repeat(np.arange(s.size), count)
        start = np.repeat(lo, count)
        k = np.arange(x.size) - np.repeat(np.cumsum(count) - count, count)
        y = (start + k) % s.size
        a, b = order[x], order[y]
        n = self.n
        cross = np.abs(n[a, 0] * n[b, 1] - n[a, 1] * n[b, 0])
        keep = (a < b) & (np.einsum("ij,ij->i", n[a], n[b]) < 0) \
            & (cross < math.sin(half_width))
        return a[keep], b[keep]

    def _rows(self, pa: np.ndarray, pb: np.ndarray, floor: float,
              qa: np.ndarray | None = None, qb: np.ndarray | None = None
              ) -> tuple[np.ndarray, FloatArray]:
        """The rows of a pair ``(pa, pb)`` and another, ``(qa, qb)`` (None: the same
        list, each two once), whose bound reaches ``floor``."""
        same = qa is None
        qa, qb = (pa, pb) if qa is None or qb is None else (qa, qb)
        return self._loop_rows("_pairs_loop", np.ascontiguousarray(pa, np.int64),
                               np.ascontiguousarray(pb, np.int64),
                               np.ascontiguousarray(qa, np.int64),
                               np.ascontiguousarray(qb, np.int64), same, self.n, self.g,
                               self.L, float(floor), RAY_TOL)

    def _nearest(self) -> tuple[np.ndarray, np.ndarray]:
        """Each force's two most nearly opposite partners (by angle), as pairs ``x <
        y`` with a negative dot product, each once."""
        ang = self.angle
        order = np.argsort(ang, kind="stable")
        s = ang[order]
        at = np.searchsorted(s, np.mod(s + np.pi, 2 * np.pi))
        x = np.repeat(np.arange(s.size), 2)
        y = np.stack([at - 1, at], axis=1).ravel() % s.size
        a, b = order[x], order[y]
        a, b = np.minimum(a, b), np.maximum(a, b)
        keep = (a < b) & (np.einsum("ij,ij->i", self.n[a], self.n[b]) < 0)
        pairs = np.unique(np.stack([a[keep], b[keep]], axis=1), axis=0)
        return pairs[:, 0], pairs[:, 1]

    def seed(self, count: int) -> EdgeSets:
        """The ``count`` rows (at least :data:`SEED_ROWS`) of the best bounds among the
        pairs of each force's most nearly opposite partners (with gravity: the rows of
        the two forces most nearly opposite to it); their ceiling is none."""
        if self.angle.size < (3 if self.fixed >= 0 else 4):
            self.seeded = np.zeros((0, 4), np.int64)
            return EdgeSets(self.seeded, np.zeros(0), np.inf)
        rows, bound = self._gravity_rows(self._opposite_gravity(None), 0.0) \
            if self.fixed >= 0 else self._rows(*self._nearest(), 0.0)
        keep = np.argsort(-bound, kind="stable")[:max(count, SEED_ROWS)]
        rows, bound = rows[keep], bound[keep]
        order = np.lexsort(rows.T[::-1])
        self.seeded = rows[order]
        return EdgeSets(self._out(rows[order]), bound[order], np.inf)

    def gamma_at(self, floor: float) -> float:
        """``Gamma`` for the rows that may reach ``floor``: the largest ``max(g, L -
        g)`` of the edges of ``floor`` or longer (with rounding's pad); 0 for none."""
        long = self.L >= floor * (1 - PAD)
        return float(np.max(self.far[long])) if long.any() else 0.0

    def _sides(self, pa: np.ndarray, pb: np.ndarray, eps: float, floor: float
               ) -> tuple[np.ndarray, np.ndarray]:
        """Which pairs ``(pa, pb)`` can carry each circuit of a row reaching ``floor``
        (the module's docstring, "one pair per circuit"): the circuit of ``rho`` (``t < rho .
        g``), and that of ``sigma`` (``t < sigma . (L - g)``), as masks."""
        long = self.L >= floor * (1 - PAD)
        out = []
        for v in (self.g, self.L - self.g):
            top = float(np.max(v[long]))
            low = np.minimum(v[pa], v[pb])
            most = (v[pa] + v[pb]) / 2 + eps * np.maximum(top - low, 0.0)
            out.append(most >= floor * (1 - PAD) - PAD * abs(top))
        return out[0], out[1]

    def reaching(self, floor: float) -> EdgeSets | None:
        """Every row whose smallest region may reach ``floor`` (its coupled bound does),
        but the :meth:`seed` rows; None where ``floor`` is too low for the pairs to hold
        them all (``eps >= 1/4``)."""
        gamma = self.gamma_at(floor)
        if floor <= 0 or gamma <= 0:
            return None
        eps = 2 * (1 - floor * (1 - PAD) / gamma) + PAD
        if eps >= 0.25:
            return None
        eps = max(eps, 0.0)
        read = self._read
        if read is not None and read[0] is self.seeded and floor >= read[1]:
            # a lower floor's rows hold these: the same rows as read afresh (each of the
            # enumeration's sets only grows as the floor falls), filtered as the loops do
            _, _, rows, bound = read
            keep = bound >= floor * (1 - PAD)
            rows, bound = rows[keep], bound[keep]
            return EdgeSets(self._out(rows), bound,
                            float(bound.max()) if bound.size else -np.inf)
        width = math.asin(min(2 * eps / (1 - eps), 1.0)) + PAD
        if self.fixed >= 0:     # a force nearly opposite to gravity, and any two others
            rows, bound = self._gravity_rows(self._opposite_gravity(width),
                                             floor * (1 - PAD))
        else:                   # one pair carries rho's circuit, the other sigma's
            pa, pb = self._pairs(width)
            long = (self.L[pa] >= floor * (1 - PAD)) & (self.L[pb] >= floor * (1 - PAD))
            pa, pb = pa[long], pb[long]
            rho, sigma = self._sides(pa, pb, eps, floor)
            if np.array_equal(rho, sigma):
                rows, bound = self._rows(pa[rho], pb[rho], floor * (1 - PAD))
            else:
                rows, bound = self._rows(pa[rho], pb[rho], floor * (1 - PAD),
                                         pa[sigma], pb[sigma])
        base = self.kn.shape[0]
        if self.seeded is not None and len(self.seeded) and len(rows):
            fresh = ~np.isin(pair_keys(rows, base), pair_keys(self.seeded, base))
            rows, bound = rows[fresh], bound[fresh]
        order = np.lexsort(rows.T[::-1])
        rows, bound = rows[order], bound[order]
        self._read = (self.seeded, floor, rows, bound)
        return EdgeSets(self._out(rows), bound, float(bound.max()) if bound.size else -np.inf)


def pair_keys(rows: np.ndarray, base: int) -> np.ndarray:
    """Each sorted row as one integer (features in base ``base``)."""
    r = rows.astype(np.int64)
    return ((r[:, 0] * base + r[:, 1]) * base + r[:, 2]) * base + r[:, 3]
