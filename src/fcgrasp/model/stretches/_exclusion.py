"""The distinct search's exclusion of the two-finger stretch search: the configurations
surely the same alternative as a plan kept (part of :mod:`fcgrasp.model.stretches`)."""

from __future__ import annotations

from typing import Any, cast

import numpy as np

from ...core._checks import FloatArray
from ...core.tolerances import COPY_PAD, DEFER_PAD, ROUND_TOL
from ..polygon import Polygon
from . import _kernels, _whole
from ._free_third import FreeThird
from ._lp import BOX_REACH, _ends
from ._windows import _Configs, _Intervals, _Ring, numpy_counted, stretch_kernels_for


def _positions(rings: list[_Ring]) -> dict[int, tuple[int, int]]:
    """Each usable polygon edge's ring and position in it."""
    return {int(e): (r, p) for r, ring in enumerate(rings) for p, e in enumerate(ring.edges)}


#: A configuration's code on rings too long for one int64 (:meth:`_Exclusion._codes`).
_PAIR = np.dtype([("first", np.int64), ("second", np.int64)])


def _member(codes: np.ndarray, known: np.ndarray) -> np.ndarray:
    """``np.isin(codes, known)`` for ``known`` sorted and unique: a binary search
    each, without sorting ``codes`` (hundreds of thousands, read in every round)."""
    at = np.minimum(np.searchsorted(known, codes), len(known) - 1)
    return cast("np.ndarray", known[at] == codes)


class _Exclusion:
    """Plans already kept (``distinct=``): a configuration whose regions, whatever
    their placement, overlap a kept plan's regions by more than ``fraction`` of the
    shorter (:func:`fcgrasp.model.distinct.same_alternative`) is the same alternative as
    that plan.  Its regions start and end inside its end edges' intervals
    (:meth:`_spans`) and are at least ``t`` long; the least overlap over all such
    regions is exact (:meth:`_least_excess`), so :meth:`similar` says "surely a copy"
    only of configurations whose every placement is one.  Such configurations are
    solved (a configuration they beat is still no plan) but neither raise the search's
    bound nor are returned; so are the configurations of the plans ``seen`` (already
    read by the caller: their covered edges and mode).  Before a configuration is
    solved, :meth:`threshold` bounds the ``t`` above which it is surely a copy: when
    the arc from its first start to its last end outside the partner region is below
    ``(1 - fraction) min(t, partner's length)``.

    With ``third`` (the distinct search of three fingers with friction), a configuration
    stands for its *pair* plan, its two regions and a third finger on the longest free
    stretch (:mod:`fcgrasp.model.stretches._free_third`), and the kept plans have three regions: a
    configuration is surely a kept plan's copy when two of the plan's regions are surely
    its two regions' partners (as above) and the third finger's free stretch surely
    overlaps the plan's remaining region by more than ``fraction`` of the shorter
    (:meth:`_third_masks`)."""

    def __init__(self, rings: list[_Ring], polygon: Polygon, kept: Any,
                 fraction: float, seen: Any = (), third: bool = False) -> None:
        where = _positions(rings)
        #: configurations excluded as such (plans already read), per ring pair and
        #: mode: the codes (:meth:`_codes`) of their starts and interior vertices, on
        #: one ring both ways round
        found: dict[tuple[int, int, str], list[tuple[int, int, int, int]]] = {}
        for edges, mode in seen:
            # a region covers consecutive edges of one ring (or one edge): its two end
            # edges say whether it is on the rings (the rounds read thousands of plans
            # of hundreds of edges each)
            if all(int(st[0]) in where and int(st[-1]) in where for st in edges):
                (x, pa), (y, pc) = where[int(edges[0][0])], where[int(edges[1][0])]
                ka, kc = len(edges[0]) - 1, len(edges[1]) - 1
                for (r1, a, k1), (r2, c, k2) in (((x, pa, ka), (y, pc, kc)),
                                                 ((y, pc, kc), (x, pa, ka))):
                    found.setdefault((r1, r2, mode), []).append((a, k1, c, k2))
        self.seen: dict[tuple[int, int, str], np.ndarray] = {}
        for (r1, r2, mode), rows in found.items():
            a, k1, c, k2 = np.array(rows, np.int64).T
            self.seen[r1, r2, mode] = np.unique(self._codes(rings, r1, r2, a, k1, c, k2))
        self.fraction = float(fraction)
        self.tol = ROUND_TOL * polygon.size
        self.plans: list[list[tuple[int, float, float]]] = []
        self._by_rings: dict[tuple[int, int, int], tuple[FloatArray, ...]] = {}
        for regions, region_edges in kept:
            arcs: list[tuple[int, float, float]] = []
            for pts, edges in zip(regions, region_edges, strict=True):
                pts = np.asarray(pts, float)
                if int(edges[0]) not in where or int(edges[-1]) not in where:
                    arcs = []
                    break
                r0, p0 = where[int(edges[0])]
                r1, p1 = where[int(edges[-1])]
                ring = rings[r0]
                u0 = ring.U[p0] + float(np.hypot(*(pts[0] - ring.a[p0])))
                u1 = ring.U[p1] + float(np.hypot(*(pts[-1] - ring.a[p1])))
                if r1 != r0:
                    arcs = []
                    break
                if u1 < u0 - self.tol:                  # wraps past vertex 0
                    u1 += float(ring.U[ring.m])
                arcs.append((r0, u0, max(u1, u0)))
            if len(arcs) == (3 if third else 2):
                self.plans.append(arcs)
        #: the pair plans' third fingers (``third``): their free stretches
        self.free = FreeThird(rings, polygon, THIRD_PAD * self.tol) if third else None

    def __bool__(self) -> bool:
        return bool(self.plans) or bool(self.seen)

    @staticmethod
    def _codes(rings: list[_Ring], x: int, y: int, iA: np.ndarray, kA: np.ndarray,
               iC: np.ndarray, kC: np.ndarray) -> np.ndarray:
        """One code per configuration of rings ``x`` and ``y`` (starts reduced), sortable
        and equal only for the same configuration: an integer, or where the rings are
        too long for one int64 (``ma (ma + 1) mb (mb + 1)`` past 2**62: tens of
        thousands of edges each) a record of two, the first stretch's and the
        second's."""
        ma, mb = rings[x].m, rings[y].m
        first = np.asarray(iA, np.int64) % ma * (ma + 1) + np.asarray(kA, np.int64)
        second = np.asarray(iC, np.int64) % mb * (mb + 1) + np.asarray(kC, np.int64)
        if float(ma) * (ma + 1) * mb * (mb + 1) < 2.0 ** 62:
            return cast("np.ndarray", first * (mb * (mb + 1)) + second)
        out = np.empty(first.shape, _PAIR)
        out["first"], out["second"] = first, second
        return out

    @staticmethod
    def _spans(rings: list[_Ring], job: tuple[int, int, float, str], cfg: _Configs,
               intervals: dict[Any, _Intervals], reach: int | None = None,
               whole: np.ndarray | None = None) -> tuple[FloatArray, FloatArray]:
        """Where the regions of each configuration can start and end on its two rings,
        ``(n, 4)`` each: first start, last start, first end, last end, as arc lengths
        (every pair of regions that holds on those edges has its end points in its end
        edges' intervals, :func:`_ends`; a stretch that ends on a long edge reaches only
        the part of it that holds against the other stretch's interior vertices).  An
        empty interval (no region pair holds) gives a last start or end of -inf.  With
        ``reach``, intervals that contain those (:func:`_ends`'s, cheaper); ``reach=0``:
        against no vertex, the whole end edges (the whole stretches).  ``whole``: the
        configurations whose whole windows hold (:mod:`._whole`), whose end edges hold
        whole: read so, with no vertex."""
        if whole is not None and whole.any() and reach != 0:
            if whole.all():
                return _Exclusion._spans(rings, job, cfg, intervals, 0)
            ends, rest = np.flatnonzero(whole), np.flatnonzero(~whole)
            wx, wy = _Exclusion._spans(rings, job, cfg.take(ends), intervals, 0)
            rx, ry = _Exclusion._spans(rings, job, cfg.take(rest), intervals, reach)
            sx, sy = np.empty((whole.size, wx.shape[1])), np.empty((whole.size, wy.shape[1]))
            sx[ends], sy[ends], sx[rest], sy[rest] = wx, wy, rx, ry
            return sx, sy
        x, y, sigma, _ = job
        ra, rb = rings[x], rings[y]
        (lo0, hi0, lo1, hi1, ulo0, uhi0, ulo1, uhi1), (off_s, off_u) = _ends(
            ra, rb, cfg, intervals[x, y, sigma], intervals[y, x, sigma],
            stretch_kernels_for(ra.m * rb.m), reach)
        a, c = ra.U[np.asarray(cfg.iA) % ra.m], rb.U[np.asarray(cfg.iC) % rb.m]
        return (np.stack([a + lo0, a + hi0, a + off_s + lo1, a + off_s + hi1], axis=1),
                np.stack([c + ulo0, c + uhi0, c + off_u + ulo1, c + off_u + uhi1], axis=1))

    @staticmethod
    def _least_excess(s: FloatArray, t: FloatArray, k0: FloatArray, k1: FloatArray,
                      f: float, eps: float) -> FloatArray:
        """For each configuration (rows: ``s`` as :meth:`_spans`, smallest region
        ``t``) and arc ``[k0, k1]`` (columns), the least of ``overlap([a, b], [k0, k1]) -
        f min(b - a, k1 - k0)`` over its regions ``[a, b]`` (start and end in their
        intervals, at least ``t`` long; each bound loosened by ``eps``).  The function is
        continuous and linear between the lines ``a = s0, s1, k0, k1``, ``b = e0, e1,
        k0, k1`` and ``b - a = t, k1 - k0``, so the least is at a crossing of two of them
        inside: every crossing is evaluated (-inf: no region)."""
        s0, s1, e0, e1 = (s[:, j, None] for j in range(4))
        tt, ln = t[:, None], k1 - k0
        starts, ends, gaps = (s0, s1, k0, k1), (e0, e1, k0, k1), (tt, ln)
        crossings = [(a, b) for a in starts for b in ends] + \
            [(a, a + d) for a in starts for d in gaps] + [(b - d, b) for b in ends for d in gaps]
        best = np.full((s.shape[0], k0.size), np.inf)
        for a, b in crossings:
            a, b = np.broadcast_arrays(a, b)
            inside = ~((a < s0 - eps) | (a > s1 + eps) | (b < e0 - eps) | (b > e1 + eps)
                       | (b - a < tt - eps))
            value = np.maximum(0.0, np.minimum(b, k1) - np.maximum(a, k0)) \
                - f * np.minimum(b - a, ln)
            best = np.where(inside, np.minimum(best, value), best)
        best[best == np.inf] = -np.inf
        return cast("FloatArray", best)

    def _surely_copy(self, per: float, s: FloatArray, t: FloatArray, k0: FloatArray,
                     k1: FloatArray) -> np.ndarray:
        """Whether every region of each configuration (rows) on one ring overlaps the
        arc ``[k0, k1]`` (columns; or its turn by a perimeter ``per``) by more than
        ``fraction`` of the shorter, plus the tolerance (:meth:`_least_excess`)."""
        out = np.zeros((s.shape[0], k0.size), bool)
        for shift in (-per, 0.0, per):
            out |= self._least_excess(s, t, k0 + shift, k1 + shift, self.fraction,
                                      self.tol) > self.tol
        return out

    @staticmethod
    def _common(per: float, a0: FloatArray, a1: FloatArray, u0: FloatArray,
                u1: FloatArray) -> FloatArray:
        """Arc the spans ``[a0, a1]`` (rows) share with the arcs [u0, u1] (columns) on a
        ring of perimeter ``per`` (either turned by a perimeter)."""
        a0, a1 = a0[:, None], a1[:, None]
        common = np.zeros((a0.shape[0], len(u0)))
        for shift in (-per, 0.0, per):
            common += np.maximum(0.0, np.minimum(a1, u1 + shift) - np.maximum(a0, u0 + shift))
        return common

    @staticmethod
    def _outside(per: float, a0: FloatArray, a1: FloatArray, u0: FloatArray,
                 u1: FloatArray) -> FloatArray:
        """Arc of the spans ``[a0, a1]`` (rows) outside the arcs [u0, u1] (columns) on a
        ring of perimeter ``per``."""
        return (a1 - a0)[:, None] - _Exclusion._common(per, a0, a1, u0, u1)

    def _fused(self, rings: list[_Ring], x: int, y: int, spans: tuple[FloatArray, ...],
               arcs: tuple[FloatArray, ...], t: FloatArray, threshold: bool,
               out: np.ndarray, mask: np.ndarray | None = None) -> bool:
        """:meth:`threshold` (``threshold``: ``spans`` the arcs ``a0x, a1x, a0y, a1y``) or
        :meth:`similar` (``spans`` as :meth:`_spans`) of many configurations by the
        compiled loop (the same numbers, without a matrix of configurations by
        kept plans for each step), writing ``out``; only the cells of ``mask`` (rows by
        columns) where given; False (nothing done) when the matrix is small or the
        loops do not run."""
        if len(spans[0]) * len(arcs[0]) < (FUSED_CELLS if threshold else FUSED_SIMILAR) \
                or not stretch_kernels_for(rings[x].m * rings[y].m):
            return False
        per = (float(rings[x].U[rings[x].m]), float(rings[y].U[rings[y].m]))
        arcs = tuple(np.ascontiguousarray(v, float) for v in arcs)
        cells = np.ones((1, 1), bool) if mask is None else np.ascontiguousarray(mask)
        if threshold:
            _kernels.exclusion_rows(
                *(np.ascontiguousarray(v, float) for v in spans), *arcs, *per,
                float(self.tol), float(1 - self.fraction), cells, mask is not None, out)
            return True
        work = np.zeros(len(out), bool)
        _kernels.similar_rows(
            *(np.ascontiguousarray(v, float) for v in spans), *arcs, *per, float(self.tol),
            float(self.fraction), np.ascontiguousarray(t, float), cells, mask is not None,
            work)
        out |= work
        return True

    def _arcs(self, x: int, y: int, start: int = 0) -> tuple[FloatArray, ...] | None:
        """The kept plans' arcs on rings ``x`` (first region) and ``y`` (second), each
        plan both ways round: ``ax0, ax1, ay0, ay1``, one column per plan; with
        ``third``, one column per ordered pair of a plan's regions, then the remaining
        region's ring and arc: ``ax0, ax1, ay0, ay1, ring, k0, k1``.  ``start``: the
        plans from that one on."""
        got = self._by_rings.get((x, y, start))
        if got is None:
            cols = [(a[i][1], a[i][2], a[j][1], a[j][2],
                     *(a[3 - i - j] if len(a) == 3 else ()))
                    for a in self.plans[start:] for i in range(len(a)) for j in range(len(a))
                    if i != j and a[i][0] == x and a[j][0] == y]
            got = self._by_rings[x, y, start] = tuple(
                np.array(c, float) for c in zip(*cols, strict=True)) if cols else ()
        return got or None

    def similar(self, rings: list[_Ring], job: tuple[int, int, float, str], cfg: _Configs,
                t: FloatArray, intervals: dict[Any, _Intervals],
                whole: np.ndarray | None = None) -> np.ndarray:
        """Which configurations of ``job`` (smallest regions ``t``) are surely the same
        alternative as a kept plan (their regions inside :meth:`_spans`; with a third
        finger, whichever free stretch it can have, :meth:`_third_masks`).  ``whole``:
        the configurations whose whole windows hold (their spans read with no vertex)."""
        x, y = job[0], job[1]
        out = np.zeros(len(t), bool)
        known = self.seen.get((x, y, job[3]))
        if known is not None:
            out |= _member(self._codes(rings, x, y, cfg.iA, cfg.kA, cfg.iC, cfg.kC), known)
        arcs = self._arcs(x, y)
        if arcs is None or not len(t):
            return out
        spans = self._spans(rings, job, cfg, intervals, BOX_REACH, whole)
        t = np.asarray(t, float)
        if len(arcs) == 4:
            self._similar_in(rings, job, spans, t, arcs, None, out)
            return out
        # every third finger the configuration's plan can have (one free stretch, or two
        # of about one length) makes it a copy of some kept plan
        sure, some = np.ones(len(t), bool), np.zeros(len(t), bool)
        for _, possible, mask in self._third_masks(x, y, cfg, arcs, spans):
            some |= possible
            # only the configurations whose third finger can be a copy's
            live = np.flatnonzero(possible & sure)
            has = live[mask[live].any(axis=1)]
            sub = np.zeros(has.size, bool)
            if has.size:
                self._similar_in(rings, job, (spans[0][has], spans[1][has]), t[has],
                                 arcs[:4], mask[has], sub)
            sure[live] = False
            sure[has[sub]] = True
        out |= sure & some
        return out

    def _similar_in(self, rings: list[_Ring], job: tuple[int, int, float, str],
                    spans: tuple[FloatArray, FloatArray], t: FloatArray,
                    arcs: tuple[FloatArray, ...], mask: np.ndarray | None,
                    out: np.ndarray) -> None:
        """:meth:`similar`'s test of the kept plans' columns ``arcs`` (only those of
        ``mask``, rows by columns, where given) on configurations whose regions lie in
        ``spans``, or-ed into ``out``."""
        x, y = job[0], job[1]
        if self._fused(rings, x, y, spans, arcs, t, False, out, mask):
            return
        ax0, ax1, ay0, ay1 = arcs
        tt = t - self.tol
        with numpy_counted():
            both = self._surely_copy(float(rings[x].U[rings[x].m]), spans[0], tt, ax0, ax1) \
                & self._surely_copy(float(rings[y].U[rings[y].m]), spans[1], tt, ay0, ay1)
        out |= (both if mask is None else both & mask).any(axis=1)

    def _third_masks(self, x: int, y: int, cfg: _Configs, arcs: tuple[FloatArray, ...],
                     spans: tuple[FloatArray, FloatArray] | None = None,
                     options: list[Any] | None = None
                     ) -> list[tuple[int, np.ndarray, np.ndarray]]:
        """For each free stretch that some configuration's third finger can have
        (:meth:`FreeThird.options`): its place among the options, where it can (per
        configuration), and which of those configurations (rows) have a third finger on
        it that surely overlaps each column's remaining region (``arcs[4:]``) by more
        than ``fraction`` of the shorter (:meth:`_third_mask_of`).  ``spans``
        (:meth:`_spans`) say which end edges a trim may free (:meth:`FreeThird.trims`;
        without them, every end edge may be), ``options`` are those of
        :meth:`FreeThird.options` without trims, where already known."""
        assert self.free is not None
        if options is None:
            trims = None if spans is None else self.free.trims(x, y, cfg, spans)
            options = self.free.options(x, y, cfg, trims)
        return [(k, possible, self._third_mask_of(np.where(possible, r, -1), g0, g1, e0, e1,
                                                  arcs))
                for k, (possible, r, g0, g1, e0, e1) in enumerate(options)
                if possible.any()]

    def _third_mask_of(self, ring: np.ndarray, g0: FloatArray, g1: FloatArray,
                       e0: FloatArray, e1: FloatArray, arcs: tuple[FloatArray, ...]
                       ) -> np.ndarray:
        """Which configurations (rows: their third finger's ring, -1 for none, sure arc
        ``[g0, g1]`` and widest ``[e0, e1]``) have a third finger whose free stretch
        surely overlaps each column's remaining region (``arcs[4:]``) by more than
        ``fraction`` of the shorter: every free stretch from the sure arc to the widest
        on that region's ring, the sure arc's overlap above ``fraction`` of the
        widest's length or the region's, whichever is less, by :data:`THIRD_PAD`
        tolerances."""
        assert self.free is not None
        kr, k0, k1 = arcs[4].astype(np.int64), arcs[5], arcs[6]
        out = np.zeros((ring.size, kr.size), bool)
        if ring.size * kr.size >= FUSED_THIRD and stretch_kernels_for(ring.size * kr.size):
            # the same numbers, compiled, without a matrix of each
            per = np.array([float(q.U[q.m]) for q in self.free.rings])
            _kernels.third_rows(
                np.ascontiguousarray(ring, np.int64),
                *(np.ascontiguousarray(v, float) for v in (g0, g1, e0, e1)),
                np.ascontiguousarray(kr), *(np.ascontiguousarray(v, float) for v in (k0, k1)),
                per, float(self.fraction), float(THIRD_PAD * self.tol), out)
            return out
        for r in np.unique(kr):
            cols, rows = np.flatnonzero(kr == r), np.flatnonzero(ring == r)
            if not rows.size:
                continue
            ring_r = self.free.rings[int(r)]
            common = self._common(float(ring_r.U[ring_r.m]), g0[rows], g1[rows], k0[cols],
                                  k1[cols])
            short = np.minimum((e1 - e0)[rows, None], (k1 - k0)[cols])
            out[np.ix_(rows, cols)] = common - self.fraction * short > THIRD_PAD * self.tol
        return out

    def copy_columns(self, rings: list[_Ring], x: int, y: int, floor: float
                     ) -> tuple[FloatArray, FloatArray] | None:
        """The kept plans' arcs on rings ``x`` and ``y`` (rows ``ax0, ax1, ay0, ay1``,
        :meth:`_arcs`) and the numbers of :meth:`threshold` (``perx, pery, tol, keep``,
        then ``drop``, then ``whole``) for the compiled collection, which leaves out the
        configurations whose threshold is below ``drop``: surely a copy at any smallest
        region from ``floor`` on (``drop`` is :data:`~fcgrasp.core.tolerances.COPY_PAD`
        below it, and below :data:`~fcgrasp.core.tolerances.DEFER_PAD`'s margin too);
        on one ring with itself (``whole`` the pad, 0: not), also those whose whole
        windows hold with an arc bound above their threshold by that pad both ways
        (:mod:`._whole`: a copy at the largest square).  None where nothing is left out
        (no kept plan on these rings, three fingers' plans)."""
        arcs = self._arcs(x, y)
        keep = 1 - self.fraction
        if arcs is None or len(arcs) != 4 or keep <= 0 or floor <= 0 or self.free is not None:
            return None
        per = (float(rings[x].U[rings[x].m]), float(rings[y].U[rings[y].m]))
        drop = floor * (1 - COPY_PAD) / (1 + DEFER_PAD)
        # one ring with itself: its copies at their largest square left out too, where
        # their whole windows show it (the pad of that rule; 0: none)
        whole = DEFER_PAD if x == y and _whole.WHOLE_WINDOWS else 0.0
        return (np.stack(arcs).astype(float),
                np.array([*per, self.tol, keep, drop, whole], float))

    def threshold(self, rings: list[_Ring], job: tuple[int, int, float, str],
                  cfg: _Configs, intervals: dict[Any, _Intervals]) -> FloatArray:
        """For each configuration of ``job``, a length above which it is surely the same
        alternative as a kept plan (:meth:`similar` with any smallest region ``t``
        greater than it; ``inf``: none).  ``similar`` asks, for each kept plan, that
        each stretch's arc outside the partner region be below ``(1 - fraction)
        min(t, partner's length)`` less the tolerance: for ``t`` above ``(outside +
        tol) / (1 - fraction)`` on both sides, where each partner is longer than that.
        A configuration already read holds at any ``t > 0``."""
        out = self._seen_threshold(rings, job, cfg)
        options = self._options(job[0], job[1], cfg)
        return np.minimum(out, self._either_third(
            self._plans_threshold(rings, job, cfg, intervals, 0, options), options))

    def thresholds(self, rings: list[_Ring], job: tuple[int, int, float, str], J: Any,
                   idx: np.ndarray, intervals: dict[Any, _Intervals]) -> FloatArray:
        """:meth:`threshold` of the configurations ``idx`` of the collected job ``J``
        (:class:`~fcgrasp.model.stretches._solve._Job`), the same numbers: the kept plans'
        part of each is kept on ``J`` with the plans it covers, and a later round (whose
        kept plans begin with those) reads only the plans kept since.  The rounds of
        one collection threshold its unsolved configurations again and again
        (``icons/message-circle.svg``, three fingers: 3.6 million rows, 341,000
        configurations)."""
        cfg = J.cfg.take(idx)
        out = self._seen_threshold(rings, job, cfg)
        options = self._options(job[0], job[1], cfg)
        key = (self.fraction, self.tol)
        taus = J.taus
        if taus is None or taus[0] != key or \
                [tuple(p) for p in self.plans[:len(taus[1])]] != taus[1]:
            taus = J.taus = (key, [], np.full((1 if options is None else len(options),
                                               len(J.cfg.iA)), np.inf),
                             np.zeros(len(J.cfg.iA), np.int64))
        _, plans, value, covered = taus
        while len(plans) < len(self.plans):
            plans.append(tuple(self.plans[len(plans)]))
        every = len(plans)
        for start in np.unique(covered[idx]):
            if start == every:
                continue
            sel = covered[idx] == start
            rows = idx[sel]
            value[:, rows] = np.minimum(value[:, rows], self._plans_threshold(
                rings, job, J.cfg.take(rows), intervals, int(start),
                None if options is None else [tuple(v[sel] if isinstance(v, np.ndarray)
                                                    else v for v in o) for o in options]))
            covered[rows] = every
        got: FloatArray = np.minimum(out, self._either_third(value[:, idx], options))
        return got

    def _seen_threshold(self, rings: list[_Ring], job: tuple[int, int, float, str],
                        cfg: _Configs) -> FloatArray:
        """:meth:`threshold`'s part of the plans already read: 0 for each of them."""
        x, y = job[0], job[1]
        out = np.full(len(cfg.iA), np.inf)
        known = self.seen.get((x, y, job[3]))
        if known is not None:
            out[_member(self._codes(rings, x, y, cfg.iA, cfg.kA, cfg.iC, cfg.kC), known)] = 0.0
        return out

    def _plans_threshold(self, rings: list[_Ring], job: tuple[int, int, float, str],
                         cfg: _Configs, intervals: dict[Any, _Intervals], start: int,
                         options: list[Any] | None) -> FloatArray:
        """:meth:`threshold`'s part of the kept plans from ``start`` on, one row per third
        finger in ``options`` (:meth:`_options`; one row without a third): each the
        least over the plans of that row (inf for a third no configuration can have),
        so that a later round's plans lower it (:meth:`thresholds`) and
        :meth:`_either_third` takes the greatest over the thirds a configuration can
        have."""
        x, y = job[0], job[1]
        out = np.full((1 if options is None else len(options), len(cfg.iA)), np.inf)
        arcs = self._arcs(x, y, start)
        if self.fraction >= 1 or arcs is None or not len(cfg.iA):
            return out
        masks: list[tuple[int, np.ndarray | None]] = [(0, None)] if len(arcs) == 4 else \
            [(k, m) for k, _, m in self._third_masks(x, y, cfg, arcs, options=options)]
        # before the configurations are solved (all of them, in chunks of thousands): the
        # whole stretches, from the first edge's start to the last edge's end
        sx, sy = self._spans(rings, job, cfg, intervals, 0)
        whole = (sx[:, 0], sx[:, 3], sy[:, 0], sy[:, 3])
        for k, mask in masks:
            out[k] = self._arcs_threshold(rings, x, y, whole, arcs, mask)
        return out

    def _options(self, x: int, y: int, cfg: _Configs) -> list[Any] | None:
        """:meth:`FreeThird.options` of the configurations, without trims (None without a
        third finger)."""
        return None if self.free is None else self.free.options(x, y, cfg)

    @staticmethod
    def _either_third(value: FloatArray, options: list[Any] | None) -> FloatArray:
        """Of thresholds per third finger (rows, as :meth:`_plans_threshold`'s), each
        configuration's: the greatest over the thirds it can have (``options``, as
        :meth:`_options`; inf where it can have none the exclusion knows)."""
        if options is None:
            return cast("FloatArray", value[0])
        possible = np.stack([o[0] for o in options])
        out = np.where(possible, value, -np.inf).max(axis=0, initial=-np.inf)
        out[~possible.any(axis=0)] = np.inf
        return cast("FloatArray", out)

    def _arcs_threshold(self, rings: list[_Ring], x: int, y: int,
                        whole: tuple[FloatArray, ...], arcs: tuple[FloatArray, ...],
                        mask: np.ndarray | None) -> FloatArray:
        """:meth:`threshold` of configurations of rings ``x`` and ``y`` whose whole
        stretches are ``whole`` (``a0x, a1x, a0y, a1y``) against the kept plans'
        columns ``arcs`` (those of ``mask`` only, rows by columns, where given)."""
        out = np.full(len(whole[0]), np.inf)
        keep = 1 - self.fraction
        rows = np.arange(len(out)) if mask is None else np.flatnonzero(mask.any(axis=1))
        if not rows.size:
            return out
        if mask is not None:
            mask = mask[rows]
        sub = out[rows]
        a0x, a1x, a0y, a1y = spans = tuple(v[rows] for v in whole)
        if not self._fused(rings, x, y, spans, arcs[:4], sub, True, sub, mask):
            ax0, ax1, ay0, ay1 = arcs[:4]
            px, py = float(rings[x].U[rings[x].m]), float(rings[y].U[rings[y].m])
            ta = (self._outside(px, a0x, a1x, ax0, ax1) + self.tol) / keep
            tc = (self._outside(py, a0y, a1y, ay0, ay1) + self.tol) / keep
            tau = np.where((ax1 - ax0 > ta) & (ay1 - ay0 > tc), np.maximum(ta, tc), np.inf)
            if mask is not None:
                tau = np.where(mask, tau, np.inf)
            sub = np.minimum(sub, tau.min(axis=1))
        out[rows] = sub
        return out


#: Cells (configurations x kept plans' columns) from which the exclusion's tests run
#: compiled (:meth:`_Exclusion._fused`): the threshold, and :meth:`_Exclusion.similar`
#: (32 crossings of lines per cell and turn: compiled from a few cells on), and the
#: third finger's test (:meth:`_Exclusion._third_mask_of`).
FUSED_CELLS, FUSED_SIMILAR, FUSED_THIRD = 20_000, 16, 20_000


#: How many rounding tolerances a pair plan's third finger must beat the overlap a copy
#: needs by (:meth:`_Exclusion._third_mask_of`), and by which one free stretch must be
#: longer than another to be surely the third finger's (:class:`FreeThird`): their
#: lengths are sums of up to thousands of edges, in another order than the plan's.
THIRD_PAD = 64
