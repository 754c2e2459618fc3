"""Where the third finger of a three-finger *pair* plan goes, for many two-finger stretch
configurations at once (the distinct search of three fingers with friction).

A pair plan is two fingers that hold the part on their own (a two-finger stretch
configuration) and a third finger anywhere on the longest *free stretch*: consecutive
usable edges of one ring that neither region covers
(:func:`fcgrasp.grippers.three_fingers.free_stretch`).  The third region depends only on
the edges the two regions cover, so it is known before a configuration is solved, up to
one thing: a region that ends exactly at a vertex does not cover the edge beyond it
(:func:`fcgrasp.core._geom.trim_vertex_ends`), which frees that edge; and two free
stretches of about one length (either side of a squeeze across an ellipse) may each be
the longest.  So for each configuration :meth:`FreeThird.options` gives every free
stretch that can be its third finger's, each with an arc every such third covers (the
*sure* arc) and one it stays inside (the sure arc and the end edges of the regions
beside it).  The distinct search uses them to say "surely the same alternative" of a
configuration whose third finger, on each of them, surely overlaps a kept plan's region
(:class:`~fcgrasp.model.stretches`'s ``_Exclusion``).
"""

from __future__ import annotations

from typing import Any, cast

import numpy as np

from ...core._checks import FloatArray
from ..polygon import Polygon
from ._windows import _Configs, _Ring


class FreeThird:
    """The free stretches of configurations on the stretch search's rings (see the
    module's docstring); ``tol`` the length by which one free stretch must beat another
    to be surely the longest (sums in another order differ by rounding)."""

    def __init__(self, rings: list[_Ring], polygon: Polygon, tol: float) -> None:
        self.rings, self.tol = rings, float(tol)
        #: per ring: its arc from just after its shortest edge (the first of ties) round
        #: to just before it, the free stretch of a ring neither region touches
        self.whole: list[tuple[float, float]] = []
        for ring in rings:
            s = (int(np.argmin(ring.L)) + 1) % ring.m        # the edge after it
            self.whole.append((float(ring.U[s]), float(ring.U[s + ring.m - 1])))
        # rings the search does not hold (fewer than three usable edges) may still hold
        # the longest free stretch: all but their shortest edge
        held = {int(e) for ring in rings for e in ring.edges}
        self.foreign = 0.0
        for r in np.unique(polygon.rings):
            usable = np.flatnonzero((polygon.rings == r) & polygon.usable)
            if usable.size >= 2 and not held.intersection(usable.tolist()):
                L = polygon.lengths[usable]
                self.foreign = max(self.foreign, float(L.sum() - L.min()))

    def _gap(self, x: int, start: Any, count: Any, before: Any, after: Any
             ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """The free run of ring ``x`` of ``count`` edges from position ``start``: its arc
        ``[g0, g1]`` (``g0`` in ``[0, P)``) and that arc widened by the edge before it
        where ``before`` and the edge after it where ``after`` (freed by a trim)."""
        ring = self.rings[x]
        m = ring.m
        s = np.asarray(start, np.int64) % m
        n = np.asarray(count, np.int64)
        g0, g1 = ring.U[s], ring.U[s + n]
        e0 = np.where(before, ring.U[s + m - 1] - ring.U[m], g0)
        e1 = np.where(after, ring.U[s + n + 1], g1)
        return g0, g1, e0, e1

    def trims(self, x: int, y: int, cfg: _Configs, spans: tuple[FloatArray, FloatArray]
              ) -> tuple[np.ndarray, ...]:
        """Which end edges of each configuration's regions a trim may free (first and
        last edge of the first region, then of the second), given where the regions
        can start and end (``spans``, as the exclusion's: first start, last start, first
        end, last end, arc lengths unrolled from each first edge's start): a region
        may lose its first edge only if it can start at that edge's end, its last only
        if it can end at that edge's start (to :attr:`tol`)."""
        out = []
        for r, i, k, sp in ((x, cfg.iA, cfg.kA, spans[0]), (y, cfg.iC, cfg.kC, spans[1])):
            U = self.rings[r].U
            i = np.asarray(i, np.int64) % self.rings[r].m
            k = np.asarray(k, np.int64)
            out.append((k > 0) & (sp[:, 1] >= U[i + 1] - self.tol))
            out.append((k > 0) & (sp[:, 2] <= U[i + k] + self.tol))
        return tuple(out)

    def widest(self, x: int, y: int, cfg: _Configs) -> FloatArray:
        """For each configuration of rings ``x`` and ``y``: a length its third finger's
        free stretch cannot exceed (every free run with the end edges beside it, and a
        foreign ring's, by :attr:`tol` more): with the smaller of its two regions, a
        bound on its pair plan's smallest region."""
        # every end edge counted as freed, even a one-edge region's: then a configuration
        # inside another (fewer edges) has at least its bound, so a configuration that
        # beats another in the own-optimum filter is never below it
        every = np.ones(np.asarray(cfg.iA).size, bool)
        cands = self._candidates(x, y, cfg, (every,) * 4)
        most = np.stack([c[4] - c[3] for c in cands])
        return cast("FloatArray", np.maximum(most.max(axis=0), self.foreign) + self.tol)

    def _candidates(self, x: int, y: int, cfg: _Configs,
                    trims: tuple[np.ndarray, ...] | None
                    ) -> list[tuple[int, FloatArray, FloatArray, FloatArray, FloatArray]]:
        """Every free run of each configuration: (ring, g0, g1, e0, e1) as
        :meth:`options` gives them."""
        iA, kA = np.asarray(cfg.iA, np.int64), np.asarray(cfg.kA, np.int64)
        iC, kC = np.asarray(cfg.iC, np.int64), np.asarray(cfg.kC, np.int64)
        n = iA.size
        a_first, a_last, c_first, c_last = (kA > 0, kA > 0, kC > 0, kC > 0) \
            if trims is None else trims
        cands: list[tuple[int, FloatArray, FloatArray, FloatArray, FloatArray]] = []
        if x == y:
            m = self.rings[x].m
            gap1 = (iC - (iA + kA + 1)) % m            # after A, up to C
            gap2 = (iA - (iC + kC + 1)) % m            # after C, up to A
            cands.append((x, *self._gap(x, iA + kA + 1, gap1, a_last, c_first)))
            cands.append((x, *self._gap(x, iC + kC + 1, gap2, c_last, a_first)))
        else:
            for r, i, k, first, last in ((x, iA, kA, a_first, a_last),
                                         (y, iC, kC, c_first, c_last)):
                m = self.rings[r].m
                cands.append((r, *self._gap(r, i + k + 1, m - k - 1, last, first)))
        for r, (w0, w1) in enumerate(self.whole):
            if r not in (x, y):
                g0, g1 = np.full(n, w0), np.full(n, w1)
                cands.append((r, g0, g1, g0, g1))
        return cands

    def options(self, x: int, y: int, cfg: _Configs,
                trims: tuple[np.ndarray, ...] | None = None
                ) -> list[tuple[np.ndarray, int, FloatArray, FloatArray, FloatArray,
                                FloatArray]]:
        """Every free stretch that can be each configuration's longest: one entry per
        candidate run, ``(possible, ring, g0, g1, e0, e1)`` with ``possible`` (per
        configuration) whether its length, at most its widest arc's, can reach every
        other run's sure length, its ring, and its sure arc ``[g0, g1]`` and widest
        ``[e0, e1]`` (arc lengths of that ring, ``g0`` in ``[0, P)``, the ends unrolled
        past it).  Where a foreign ring's stretch may be the longest, or no run has a
        length, no candidate is possible.  A configuration whose two free runs differ by
        less than an end edge has two possible thirds.  ``trims``: which end edges a
        trim may free (:meth:`trims`; default: every end edge of a region of two edges
        or more)."""
        cands = self._candidates(x, y, cfg, trims)
        sure = np.stack([c[2] - c[1] for c in cands])          # (candidates, n)
        most = np.stack([c[4] - c[3] for c in cands])
        n = sure.shape[1]
        cols = np.arange(n)
        best = np.argmax(sure, axis=0)
        top = sure[best, cols]
        second = sure.copy()
        second[best, cols] = -np.inf
        second = second.max(axis=0, initial=-np.inf)
        known = (top > self.foreign + self.tol) & (top > 0)
        out = []
        for k, (r, g0, g1, e0, e1) in enumerate(cands):
            others = np.where(best == k, second, top)
            out.append((known & (most[k] + self.tol >= others), int(r), g0, g1, e0, e1))
        return out
