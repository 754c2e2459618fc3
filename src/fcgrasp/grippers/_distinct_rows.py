"""Rows of the single-edge search that a search for distinct alternatives leaves out
unsolved (:func:`~fcgrasp.grippers._boundary.distinct_single_edge_plans`).

A row of the single-edge search puts each finger on one feature: without a hand, one
whole edge.  Its plan's regions lie on those edges, wherever the solver places them.
When every finger's edge lies on a region of a kept plan, the fingers paired with the
kept plan's regions one to one, each region of the row's plan lies inside its partner:
their common part is the whole of the shorter, more than ``fraction`` of it for any
``fraction`` below 1, so the plan is the same alternative as the kept one
(:func:`fcgrasp.model.distinct.same_alternative`) and suppression would drop it.  Only
a region shorter than suppression's tolerance (a point, which overlaps no region) would
escape, and none is that short: the row is left out.
"""

from __future__ import annotations

from itertools import permutations
from typing import Any

import numpy as np
import shapely

from ..model.plans import GraspPlan
from ..model.polygon import Polygon
from ..pipeline import features

__all__ = ["RowCopies"]


class RowCopies:
    """``exclude`` of :func:`fcgrasp.pipeline.search`: which rows of a batch (features,
    -1 for gravity) a distinct search leaves out: those it has ``read`` (each plan's
    edges, sorted: a row without a hand is its edges) and those whose every plan is
    the same alternative as a ``kept`` plan (the module's docstring).  ``tol``: how
    near a region an edge's end must be to lie on it (suppression's tolerance).

    >>> from fcgrasp.io.parts import demo_part
    >>> from fcgrasp.pipeline import plan_spec, search
    >>> part = demo_part("quad")
    >>> [p.edges for p in search(part, plan_spec(fingers=4, top=2))]
    [(0, 1, 2, 3), (3, 0, 3, 1)]
    >>> copies = RowCopies(part, [], [(0, 1, 2, 3)], 1e-9)     # the best row read
    >>> [p.edges for p in search(part, plan_spec(fingers=4, top=1), exclude=copies)]
    [(3, 0, 3, 1)]
    """

    def __init__(self, polygon: Polygon, kept: list[GraspPlan], read: list[Any],
                 tol: float) -> None:
        self.edge = features(polygon).edge
        #: per kept plan: which feature's edge lies on each of its regions (F, regions)
        self.inside: list[np.ndarray] = []
        for p in kept:
            table = np.zeros((len(self.edge), len(p.regions)), bool)
            for j, (pts, edges) in enumerate(zip(p.regions, p.region_edges, strict=True)):
                e = np.unique(np.asarray(edges, int))
                ends = shapely.points(np.concatenate([polygon.starts[e], polygon.ends[e]]))
                near = shapely.distance(shapely.LineString(np.asarray(pts, float)), ends)
                on = e[(near.reshape(2, -1) <= tol).all(axis=0)]
                table[np.isin(self.edge, on), j] = True
            if table.any(axis=0).all():         # every region has an edge on it
                self.inside.append(table)
        self.read = {tuple(sorted(int(e) for e in r)) for r in read}
        self._base = int(self.edge.max(initial=0)) + 1
        #: per length, the sorted edge tuples read, each as one integer (digits in base
        #: ``_base``), where such integers fit in 64 bits
        self._read_keys: dict[int, np.ndarray] = {}
        for k in {len(r) for r in self.read}:
            if self._fits(k):
                self._read_keys[k] = np.array([r for r in self.read if len(r) == k],
                                              np.int64) @ self._weights(k)
        self._first = np.array(sorted({r[0] for r in self.read if r}), int)

    def _fits(self, k: int) -> bool:
        """Whether a tuple of ``k`` edges as one integer fits in 64 bits."""
        return float(self._base) ** k < 2.0 ** 62

    def _weights(self, k: int) -> np.ndarray:
        """The digits' weights of a tuple of ``k`` edges as one integer."""
        return self._base ** np.arange(k - 1, -1, -1, dtype=np.int64)

    def __call__(self, feats: np.ndarray) -> np.ndarray:
        feats = np.asarray(feats)
        out = np.zeros(len(feats), bool)
        if not len(feats):
            return out
        # the real fingers of each row (gravity's column, -1, last), rows of one count
        rows = np.sort(feats, axis=1)[:, ::-1]
        k = int((feats[0] >= 0).sum())
        same = (rows >= 0).sum(axis=1) == k
        rows = rows[:, :k]
        if self.read:
            e = np.sort(self.edge[np.maximum(rows, 0)], axis=1)
            if self._fits(k):
                keys = self._read_keys.get(k)
                if keys is not None:
                    out[same] = np.isin(e[same].astype(np.int64) @ self._weights(k), keys)
            else:
                for r in np.flatnonzero(same & np.isin(e[:, 0], self._first)):
                    out[r] = tuple(int(v) for v in e[r]) in self.read
        cols = np.arange(k)
        for table in self.inside:
            if table.shape[1] != k:
                continue
            on = table[np.maximum(rows, 0)]              # (rows, fingers, regions)
            live = np.flatnonzero(same & ~out & on.any(axis=2).all(axis=1)
                                  & on.any(axis=1).all(axis=1))
            if not live.size:
                continue
            sub = on[live]
            hit = np.zeros(live.size, bool)
            for perm in permutations(range(k)):
                hit |= sub[:, cols, list(perm)].all(axis=1)
            out[live[hit]] = True
        return out
