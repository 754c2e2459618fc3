r"""An upper bound on the best smallest region of any plan (optimality bounds).

Three fingers with friction and four frictionless fingers along the boundary are planned
as a *safe lower bound* (convex pieces of the closure set; stretches grown from the best
single-edge plans).  This module bounds the optimum from above, so a plan's gap is known:
it proves that no choice of regions, one connected arc of the boundary per finger, each
at least ``L`` long, has every grasp force closure.  The regions are those the planner
chooses from: disjoint, and two may share an edge (the planner's single-edge plans
double one: two fingers side by side on it, with three fingers as with four).  The
proof uses none of the planner's constructions, only the definition of force closure
(theorem 6.1: a twist repelling or reciprocal to every wrench,
:func:`clearly_not_closure`).

**The argument.**  Put each region on a boundary ring by its *start*: the arc-length
``a`` at which it begins, in the ring's edge order, so the region is ``[a, a + L]``.
Fingers are interchangeable (force closure does not depend on their order), so the
starts can be taken in order along each ring, each region ending before the next one's
first edge (:func:`_apart` narrows the starts to those).  A *node* is a box of starts: per
finger a ring and an interval ``[lo, hi]`` of starts with ``hi - lo < L``.  Every region
whose start lies in ``[lo, hi]`` contains the *common arc* ``[hi, lo + L]``; so if one
grasp with each finger on its common arc is not force closure, no choice of regions in
the node holds (each contains that grasp).  The node is then *refuted*.  A node that is
not is split in two along its widest interval.  ``L`` is an upper bound of the optimum
once every node of a cover of all starts (chunks of ``L / 2``) is refuted; and then so is
every longer ``L`` (a longer region contains a shorter one, and regions inside holding
ones hold).

The test grasps of a node are the products of test points of each common arc: its ends
and middle; for the nodes those do not refute, its ends and both sides of the first and
the last vertex inside it (where the normal turns).  Every test point is moved inside its
edge by a hair, so each is an actual contact of every region of the node with one normal,
pushing along the edge's inward normal (frictionless) or anywhere inside its friction
cone (``mu``).  The ``margin`` of the plans is honoured where it has a meaning of its own:
with friction the cones are shrunk by it (a plan's witness directions lie inside the
shrunk cones, so its grasps are force closure with them: the bound is on that optimum);
frictionless fingers are bounded without a margin (their plans' margin is a property of
the sector construction, not of a grasp), so the gap of a frictionless plan includes what
its margin costs.

The bound is found by bisection (on a log scale) between the best plan found (``lower``)
and the first refuted length, until their ratio is within ``1 + gap`` or the attempts
run out of nodes; the smallest refuted length is the bound.  Ties are decided as the
general test decides them (a grasp within ``1e-9`` of the boundary is not force closure),
so the bound is exact up to that tolerance, as the plans are.

>>> from fcgrasp.io.parts import demo_part
>>> b = optimum_upper_bound(demo_part("quad"), 4, lower=19.0, gap=0.05)   # plan: 19.59
>>> b.value >= 19.59, b.gap < 0.05
(True, True)
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core._angles import margin_radians
from ..core._checks import FloatArray, check_scalar
from ..core.jit import CompiledLoops
from ..core.tolerances import TINY, TOL, VERTEX_HAIR
from .polygon import Polygon, check_polygon
from .regions import DEFAULT_MARGIN_DEG

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = ["UpperBound", "optimum_upper_bound", "refutes", "clearly_not_closure"]

#: Nodes examined per attempted length before it is given up as not refuted.
MAX_NODES = 5000

#: Nodes whose intervals are all narrower than this fraction of the length tried are not
#: split further: the length is then not refuted (a choice of regions there may hold).
MIN_WIDTH = 1e-3

#: The cover of all starts is built only when it has at most this many times the budget
#: of nodes (most of it is discarded at once by the order and the gaps between regions).
_ROOTS = 100

#: Nodes tested in one batch (a few megabytes of wrenches).
_BATCH = 4096


@dataclass(frozen=True)
class UpperBound:
    """A certified upper bound on the best smallest region of ``fingers`` fingers.

    ``value``: no regions each at least this long hold (``inf`` when nothing was
    refuted within the budget); ``lower``: the best smallest region found by the planner;
    ``gap = 1 - lower / value``; ``nodes``: boxes of starts examined in all attempts."""

    value: float
    lower: float
    nodes: int

    @property
    def gap(self) -> float:
        if not np.isfinite(self.value) or self.value <= 0:
            return 1.0 if self.value != 0 else 0.0
        return max(0.0, 1.0 - self.lower / self.value)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``upper_bound`` (``None`` when not proved), ``gap``, ``nodes``."""
        return {"upper_bound": float(self.value) if np.isfinite(self.value) else None,
                "gap": float(self.gap), "nodes": int(self.nodes)}


class _Boundary:
    """The part's boundary by arc-length, ring by ring, in coordinates about the centroid
    divided by the part's radius (so the general test sees unit-sized lever arms)."""

    def __init__(self, polygon: Polygon) -> None:
        self.scale = polygon.radius
        self.rings: list[tuple[np.ndarray, FloatArray, float]] = []
        for r in np.unique(polygon.rings):
            idx = np.flatnonzero((polygon.rings == r) & polygon.usable)
            cum = np.concatenate([[0.0], np.cumsum(polygon.lengths[idx])])
            self.rings.append((idx, cum, float(cum[-1])))
        self.starts = (polygon.starts - polygon.centroid) / self.scale
        self.tangents = polygon.tangents
        self.normals = polygon.normals
        self.hair = VERTEX_HAIR * polygon.size
        self.perimeters = np.array([per for _, _, per in self.rings])

    def vertex_at_or_after(self, ring: np.ndarray, s: FloatArray) -> FloatArray:
        """Arc-length of the first vertex of ``ring`` at or after ``s`` (within a hair; ``s``
        up to two perimeters; ``inf`` beyond)."""
        out = np.full(s.shape, np.inf)
        for r, (_, cum, per) in enumerate(self.rings):
            on = ring == r
            if on.any():
                ext = np.concatenate([cum[:-1], cum + per])
                j = np.searchsorted(ext, s[on] - self.hair, side="left")
                out[on] = np.concatenate([ext, [np.inf]])[j]
        return out

    def vertex_at_or_before(self, ring: np.ndarray, s: FloatArray) -> FloatArray:
        """Arc-length of the last vertex of ``ring`` at or before ``s`` (within a hair;
        ``-inf`` before 0)."""
        out = np.full(s.shape, -np.inf)
        for r, (_, cum, per) in enumerate(self.rings):
            on = ring == r
            if on.any():
                ext = np.concatenate([cum[:-1], cum + per])
                j = np.searchsorted(ext, s[on] + self.hair, side="right") - 1
                out[on] = np.concatenate([[-np.inf], ext])[j + 1]
        return out

    def contacts(self, ring: np.ndarray, s: np.ndarray, mid: np.ndarray
                 ) -> tuple[FloatArray, FloatArray]:
        """Points (scaled) and outward normals at arc-lengths ``s`` of rings ``ring``; a
        point within a hair of a vertex moves toward ``mid`` (its common arc's middle)."""
        pts = np.empty(s.shape + (2,))
        nrm = np.empty(s.shape + (2,))
        for r, (idx, cum, per) in enumerate(self.rings):
            on = ring == r
            if not on.any():
                continue
            ss = np.mod(s[on], per)
            mm = np.mod(mid[on], per)
            k = np.clip(np.searchsorted(cum, ss, side="right") - 1, 0, idx.size - 1)
            near_lo = ss - cum[k] < self.hair
            near_hi = cum[k + 1] - ss < self.hair
            near = near_lo | near_hi
            if near.any():
                # toward the middle of the common arc (shortest way round the ring)
                step = np.mod(mm - ss + per / 2, per) - per / 2
                ss = np.where(near, np.mod(ss + 2 * self.hair * np.sign(step), per), ss)
                k = np.clip(np.searchsorted(cum, ss, side="right") - 1, 0, idx.size - 1)
            e = idx[k]
            pts[on] = self.starts[e] + ((ss - cum[k]) / self.scale)[:, None] * self.tangents[e]
            nrm[on] = self.normals[e]
        return pts, nrm


def _wrenches(points: FloatArray, normals: FloatArray, half: float | None) -> FloatArray:
    """Contact wrenches, shape (..., fingers * (2 or 1), 3): the friction cone's two edges
    of half-angle ``half`` or the inward normal alone (``None``)."""
    f = -normals
    if half is not None:
        c, s = np.cos(half), np.sin(half)
        f1 = np.stack([c * f[..., 0] - s * f[..., 1], s * f[..., 0] + c * f[..., 1]], -1)
        f2 = np.stack([c * f[..., 0] + s * f[..., 1], -s * f[..., 0] + c * f[..., 1]], -1)
        f = np.stack([f1, f2], axis=-2)                      # (..., k, 2, 2)
        p = np.broadcast_to(points[..., None, :], f.shape)
    else:
        p = points
    tau = p[..., 0] * f[..., 1] - p[..., 1] * f[..., 0]
    w = np.concatenate([f, tau[..., None]], axis=-1)
    return w.reshape(w.shape[:-3] + (-1, 3)) if half is not None else w


_PAIRS: dict[int, tuple[np.ndarray, np.ndarray, np.ndarray]] = {}


def clearly_not_closure(wrenches: ArrayLike, tol: float = TOL) -> np.ndarray:
    """Is the wrench convexe not total (theorem 6.1)?  True where the plane through the
    origin and two (non-parallel) of the wrenches has every other wrench on one side of
    it, ties within ``tol`` (on unit wrenches) counted on that side as the general test
    counts them: the plane's normal is then a twist repelling or reciprocal to every
    wrench.  Batched (shape (..., m, 3) -> (...)); it shares no code with
    :func:`~fcgrasp.is_force_closure` (the tests hold them to the same verdicts).  A
    cone that is not the whole space has a face through the origin spanned by two of its
    generators, or all of them lie on one line (every pair parallel, also "not total"),
    so the test is exact."""
    w = np.asarray(wrenches, dtype=float)
    m = w.shape[-2]
    if m not in _PAIRS:
        i, j = np.array(list(itertools.combinations(range(m), 2))).T
        others = np.ones((i.size, m), dtype=bool)
        others[np.arange(i.size), i] = False
        others[np.arange(i.size), j] = False
        _PAIRS[m] = (i, j, others)
    i, j, others = _PAIRS[m]
    u = w / np.maximum(np.sqrt(np.sum(w * w, axis=-1, keepdims=True)), TINY)
    x, y, z = u[..., 0], u[..., 1], u[..., 2]
    cx = y[..., i] * z[..., j] - z[..., i] * y[..., j]              # (..., P)
    cy = z[..., i] * x[..., j] - x[..., i] * z[..., j]
    cz = x[..., i] * y[..., j] - y[..., i] * x[..., j]
    norm = np.sqrt(cx * cx + cy * cy + cz * cz)
    d = (cx[..., None] * x[..., None, :] + cy[..., None] * y[..., None, :]
         + cz[..., None] * z[..., None, :]) / np.maximum(norm, TINY)[..., None]
    above = np.where(others, d >= -tol, True).all(axis=-1)
    below = np.where(others, d <= tol, True).all(axis=-1)
    on_a_line = np.all(norm <= tol, axis=-1)                    # every pair parallel
    return np.asarray(np.any((above | below) & (norm > tol), axis=-1) | on_a_line)


def _fails_loop(pts: FloatArray, nrm: FloatArray, c: float, s: float, friction: bool,
               tol: float, out: np.ndarray) -> None:
    """:func:`_fails_numpy` in one compiled loop: per node (``pts``, ``nrm``: shape
    (N, k, m, 2)), the grasps of the product of its fingers' test points in turn, each
    tested as :func:`clearly_not_closure` tests it (the same expressions in the same
    order), stopping at the first that is not force closure."""
    n, k, m = pts.shape[0], pts.shape[1], pts.shape[2]
    per = 2 if friction else 1
    nw = k * per
    u = np.empty((nw, 3))
    pick = np.zeros(k, dtype=np.int64)
    for a in range(n):
        out[a] = False
        for f in range(k):
            pick[f] = 0
        while True:
            for f in range(k):
                px, py = pts[a, f, pick[f], 0], pts[a, f, pick[f], 1]
                fx, fy = -nrm[a, f, pick[f], 0], -nrm[a, f, pick[f], 1]
                for e in range(per):
                    if not friction:
                        gx, gy = fx, fy
                    elif e == 0:
                        gx, gy = c * fx - s * fy, s * fx + c * fy
                    else:
                        gx, gy = c * fx + s * fy, -s * fx + c * fy
                    gz = px * gy - py * gx
                    r = math.sqrt(gx * gx + gy * gy + gz * gz)
                    r = max(r, TINY)
                    w = f * per + e
                    u[w, 0], u[w, 1], u[w, 2] = gx / r, gy / r, gz / r
            fails = True                  # every pair parallel, unless one is not
            found = False
            for i in range(nw):
                for j in range(i + 1, nw):
                    cx = u[i, 1] * u[j, 2] - u[i, 2] * u[j, 1]
                    cy = u[i, 2] * u[j, 0] - u[i, 0] * u[j, 2]
                    cz = u[i, 0] * u[j, 1] - u[i, 1] * u[j, 0]
                    norm = math.sqrt(cx * cx + cy * cy + cz * cz)
                    if norm > tol:
                        fails = False
                    else:
                        continue
                    above = True
                    below = True
                    den = max(norm, TINY)
                    for o in range(nw):
                        if o == i or o == j:
                            continue
                        d = (cx * u[o, 0] + cy * u[o, 1] + cz * u[o, 2]) / den
                        if d < -tol:
                            above = False
                        if d > tol:
                            below = False
                        if not above and not below:
                            break
                    if above or below:
                        found = True
                        break
                if found:
                    break
            if found or fails:
                out[a] = True
                break
            f = k - 1                     # the next grasp of the product
            while f >= 0:
                pick[f] += 1
                if pick[f] < m:
                    break
                pick[f] = 0
                f -= 1
            if f < 0:
                break


_LOOPS = CompiledLoops(globals(), (_fails_loop,))


def _fails(bd: _Boundary, ring: np.ndarray, s: FloatArray, mid: FloatArray,
           half: float | None) -> np.ndarray:
    """Per node: is one grasp of the product of its fingers' test points (``s``: shape
    (N, k, m), arc-lengths) not force closure?  Compiled (:func:`_fails_loop`) where
    numba runs, else :func:`_fails_numpy` (the reference)."""
    pts, nrm = bd.contacts(np.broadcast_to(ring[..., None], s.shape), s,
                           np.broadcast_to(mid[..., None], s.shape))
    if _LOOPS.available():
        out = np.empty(s.shape[0], dtype=bool)
        c, sn = (1.0, 0.0) if half is None else (float(np.cos(half)), float(np.sin(half)))
        ok, _ = _LOOPS.run("_fails_loop", np.ascontiguousarray(pts),
                           np.ascontiguousarray(nrm), c, sn, half is not None, TOL, out)
        if ok:
            return out
    return _fails_numpy(pts, nrm, half)


def _fails_numpy(pts: FloatArray, nrm: FloatArray, half: float | None) -> np.ndarray:
    """Per node: is one grasp of the product of its fingers' test points (``pts``,
    ``nrm``: shape (N, k, m, 2)) not force closure?  Batched numpy over every grasp."""
    k, m = pts.shape[1], pts.shape[2]
    combos = np.array(list(itertools.product(range(m), repeat=k)))   # (m**k, k)
    fingers = np.arange(k)
    gp = pts[:, fingers[None, :], combos]                     # (N, m**k, k, 2)
    gn = nrm[:, fingers[None, :], combos]
    return np.asarray(clearly_not_closure(_wrenches(gp, gn, half)).any(axis=1))


def _refuted(bd: _Boundary, ring: np.ndarray, lo: np.ndarray, hi: np.ndarray, L: float,
             half: float | None) -> np.ndarray:
    """Per node (rows of ``ring``, ``lo``, ``hi``: shape (N, k)): is one grasp of its
    common arcs not force closure?  First the arcs' ends and middles; for the nodes that
    pass, the ends and both sides of the first and the last vertex inside each arc."""
    c0, c1 = hi + 2 * bd.hair, lo + L - 2 * bd.hair          # the common arcs
    mid = (c0 + c1) / 2
    out = _fails(bd, ring, np.stack([c0, mid, c1], axis=-1), mid, half)
    rest = np.flatnonzero(~out)
    if rest.size:
        r, a, b, m = ring[rest], c0[rest], c1[rest], mid[rest]
        v0 = np.minimum(bd.vertex_at_or_after(r, a), b)
        v1 = np.maximum(bd.vertex_at_or_before(r, b), a)
        h = 2 * bd.hair
        s = np.stack([a, np.maximum(v0 - h, a), np.minimum(v0 + h, b),
                      np.maximum(v1 - h, a), np.minimum(v1 + h, b), b], axis=-1)
        out[rest] = _fails(bd, r, s, m, half)
    return out


def _apart(ring: np.ndarray, lo: np.ndarray, hi: np.ndarray, L: float, bd: _Boundary
           ) -> np.ndarray:
    """Narrow each node's intervals, in place, to starts of disjoint arcs in order along
    each ring; returns the nodes where some starts are left."""
    k = lo.shape[1]
    per = bd.perimeters[ring]
    for _ in range(2):
        for i in range(k - 1):
            same = ring[:, i] == ring[:, i + 1]
            nxt = lo[:, i] + L
            lo[:, i + 1] = np.where(same, np.maximum(lo[:, i + 1], nxt), lo[:, i + 1])
        for i in range(k - 2, -1, -1):
            same = ring[:, i] == ring[:, i + 1]
            prv = hi[:, i + 1] - L
            hi[:, i] = np.where(same, np.minimum(hi[:, i], prv), hi[:, i])
        # the last arc of a ring ends before its first one comes round
        for i in range(k):
            for j in range(i + 1, k):
                first = (ring[:, j] == ring[:, i]) & ((i == 0) | (ring[:, i - 1] != ring[:, i]))
                last = first & ((j == k - 1) | (ring[:, min(j + 1, k - 1)] != ring[:, j]))
                p = per[:, i]
                nxt = lo[:, j] + L - p
                prv = hi[:, i] + p - L
                lo[:, i] = np.where(last, np.maximum(lo[:, i], nxt), lo[:, i])
                hi[:, j] = np.where(last, np.minimum(hi[:, j], prv), hi[:, j])
    return np.asarray(np.all(lo <= hi, axis=1))


def _halves(lo: FloatArray, hi: FloatArray
            ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Each node split in two along its widest interval: ``(lo, hi1)`` and ``(lo2, hi)``."""
    rows = np.arange(lo.shape[0])
    j = np.argmax(hi - lo, axis=1)
    cut = (lo[rows, j] + hi[rows, j]) / 2
    lo2, hi1 = lo.copy(), hi.copy()
    hi1[rows, j] = cut
    lo2[rows, j] = cut
    return lo, hi1, lo2, hi


def _dive(bd: _Boundary, ring: np.ndarray, lo: FloatArray, hi: FloatArray, L: float,
          half: float | None, floor: float) -> tuple[bool, int]:
    """Follow one node that is not refuted down through halves that are not either, to a
    box of starts narrower than ``floor`` (True: the length cannot be refuted) or to one
    whose halves both are (False).  A length shorter than the optimum is given up after
    one dive instead of a whole level of nodes.  Returns the verdict and the nodes tried."""
    tried = 0
    while np.max(hi - lo) > floor:
        lo_a, hi_a, lo_b, hi_b = _halves(lo, hi)
        r2 = np.concatenate([ring, ring])
        l2, h2 = np.concatenate([lo_a, lo_b]), np.concatenate([hi_a, hi_b])
        keep = _apart(r2, l2, h2, L, bd)
        alive = keep.copy()
        alive[keep] = ~_refuted(bd, r2[keep], l2[keep], h2[keep], L, half)
        tried += 2
        if not alive.any():
            return False, tried
        k = int(np.flatnonzero(alive)[0])
        ring, lo, hi = r2[k:k + 1], l2[k:k + 1], h2[k:k + 1]
    return True, tried


def refutes(polygon: Polygon, fingers: int, length: float, mu: float = 0.0,
            margin: float = 0.0, max_nodes: int = MAX_NODES) -> tuple[bool | None, int]:
    """Is ``length`` proved too long: no regions of ``fingers`` fingers, each an arc of the
    boundary at least ``length`` long and disjoint, have every grasp force closure?
    Returns the verdict and the number of nodes examined (the module docstring has the
    proof): True (proved), False (a box of starts narrower than
    :data:`MIN_WIDTH` of ``length`` was not refuted: regions there may hold) or None
    (``max_nodes`` examined first).

    ``mu`` 0 is frictionless; with friction the cones are shrunk by ``margin`` (radians)."""
    bd = _Boundary(polygon)
    L = float(length)
    half = None if mu == 0 else float(np.arctan(mu)) - margin
    if half is not None and half <= 0:
        return True, 0                    # the margin leaves no cone: nothing holds
    # the cover of all starts: per ring, chunks of width L / 2 (common arcs >= L / 2)
    chunks = []
    for r, (_, _, per) in enumerate(bd.rings):
        if per < L:
            continue                      # an arc of the ring cannot be this long
        m = int(np.ceil(per / (L / 2)))
        edges = np.linspace(0.0, per, m + 1)
        chunks += [(r, edges[j], edges[j + 1]) for j in range(m)]
    if not chunks:
        return True, 0
    if math.comb(len(chunks) + fingers - 1, fingers) > _ROOTS * max_nodes:
        return None, 0                    # the cover alone is far over the budget
    roots = np.array(list(itertools.combinations_with_replacement(range(len(chunks)), fingers)))
    table = np.array(chunks)
    ring = table[roots, 0].astype(int)
    lo, hi = table[roots, 1], table[roots, 2]
    floor = MIN_WIDTH * L
    seen = 0
    while ring.shape[0]:
        if seen >= max_nodes:
            return None, seen
        take = slice(0, min(_BATCH, max_nodes - seen))
        r_, l_, h_ = ring[take], lo[take], hi[take]
        ring, lo, hi = ring[take.stop:], lo[take.stop:], hi[take.stop:]
        keep = _apart(r_, l_, h_, L, bd)
        r_, l_, h_ = r_[keep], l_[keep], h_[keep]
        seen += r_.shape[0]
        if not r_.shape[0]:
            continue
        alive = ~_refuted(bd, r_, l_, h_, L, half)
        if not alive.any():
            continue
        r_, l_, h_ = r_[alive], l_[alive], h_[alive]
        if np.any(np.max(h_ - l_, axis=1) <= floor):
            return False, seen            # a box of starts too small to refute
        dived, cost = _dive(bd, r_[:1], l_[:1], h_[:1], L, half, floor)
        seen += cost
        if dived:
            return False, seen            # a box of starts too small to refute
        l_, h1, l2, h_ = _halves(l_, h_)
        ring = np.concatenate([r_, r_, ring])
        lo = np.concatenate([l_, l2, lo])
        hi = np.concatenate([h1, h_, hi])
    return True, seen


def optimum_upper_bound(polygon: Polygon, fingers: int, mu: ArrayLike = 0.0,
                        margin: ArrayLike | None = None,
                        lower: ArrayLike = 0.0, gap: ArrayLike = 0.01,
                        max_nodes: int = MAX_NODES) -> UpperBound:
    """A certified upper bound on the best smallest region (definition 7.1) of any plan
    of ``fingers`` point fingers (3 or 4; ``mu`` 0: frictionless) whose regions are arcs
    of the boundary, by bisection between ``lower`` (the best smallest region found) and
    the first length :func:`refutes` proves too long, to within ``1 + gap``.

    ``margin`` in degrees (the plans' default when ``None``) shrinks friction cones.
    ``value`` is ``inf`` when no length up to the longest ring was refuted within the
    budget ``max_nodes`` per attempt."""
    polygon = check_polygon(polygon)
    if not isinstance(fingers, (int, np.integer)) or isinstance(fingers, bool) \
            or fingers not in (3, 4):
        raise ValueError(f"fingers must be 3 or 4, got {fingers!r}")
    mu_v = check_scalar(mu, "mu", nonnegative=True)
    margin_r = float(margin_radians(DEFAULT_MARGIN_DEG if margin is None
                                    else check_scalar(margin, "margin", nonnegative=True)))
    low = check_scalar(lower, "lower", nonnegative=True)
    gap_v = check_scalar(gap, "gap", nonnegative=True)
    if not 0 < gap_v < 1:
        raise ValueError(f"gap must be in (0, 1), got {gap_v}")
    longest = max(float(np.sum(polygon.lengths[polygon.rings == r]))
                  for r in np.unique(polygon.rings))
    nodes = 0
    refuted = np.inf
    trial = max(low, TINY) * (1 + gap_v) if low > 0 else longest * gap_v
    open_ = low                           # longest length not refuted (the plan's holds)
    while trial <= longest * (1 + gap_v):
        ok, seen = refutes(polygon, fingers, trial, mu_v, margin_r, max_nodes)
        nodes += seen
        if ok:
            refuted = trial
            break
        open_ = trial
        trial *= 2
    while np.isfinite(refuted) and refuted > open_ * (1 + gap_v) and open_ > 0:
        trial = float(np.sqrt(refuted * open_))
        ok, seen = refutes(polygon, fingers, trial, mu_v, margin_r, max_nodes)
        nodes += seen
        if ok:
            refuted = trial
        else:
            open_ = trial
    return UpperBound(float(refuted), low, nodes)
