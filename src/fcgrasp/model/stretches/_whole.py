"""Configurations whose whole windows hold: a lower bound of a configuration's smallest
region read from the vertex matrix's runs, with no system solved (part of
:mod:`fcgrasp.model.stretches`).

Along one edge the conditions of force closure are linear in the contact's position
(each a cross product with a generator of the friction cone, section 5 of the paper), so
two regions made of whole edges are independent (every pair of their points in force
closure, section 6) when every pair of their vertices holds against both normals of each
vertex: the cells of the vertex matrix ``M`` (:func:`._windows._vertex_matrix`).  A
configuration covering edges ``iA .. iA + kA`` and ``iC .. iC + kC`` whose block of
vertices ``iA .. iA + kA + 1`` by ``iC .. iC + kC + 1`` is all True then holds a square
pair of regions of length ``min(arcA, arcC)``: the shorter stretch whole and, in the
longer, a region of that length from its first edge to its last (which needs the
longer's interior arc to be at most that length).  Its largest square is that length
exactly (neither region can be longer than its stretch)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...core._checks import FloatArray
from ._windows import _Configs, _ext, _inner, _Ring


class _RowRuns:
    """The runs of True of every row of one ring's vertex matrix with itself (row
    pointers, first and last columns, not wrapping), searchable by (row, column)."""

    def __init__(self, runs: tuple[np.ndarray, np.ndarray, np.ndarray], m: int) -> None:
        ptr, first, last = (np.asarray(a, np.int64) for a in runs)
        self.ptr, self.last, self.m = ptr, last, m
        row = np.repeat(np.arange(m, dtype=np.int64), np.diff(ptr))
        #: one sorted key per run: its row, then its first column
        self.keys = row * (m + 1) + first[:ptr[m]]

    def _covers(self, rows: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Whether one run of each row ``rows`` holds its columns ``a .. b``."""
        if not self.keys.size:
            return np.zeros(rows.shape, bool)
        j = np.searchsorted(self.keys, rows * (self.m + 1) + a, side="right") - 1
        out: np.ndarray = (j >= self.ptr[rows]) & (self.last[np.maximum(j, 0)] >= b)
        return out

    def holds(self, rows: np.ndarray, c0: np.ndarray, n: np.ndarray) -> np.ndarray:
        """Whether each row of ``rows`` holds the ``n`` cyclic columns from ``c0``
        (``n`` at most the ring's size; a run through the last column goes on into the
        first only where both are runs)."""
        m = self.m
        c1 = c0 + n - 1
        ok = self._covers(rows, c0, np.minimum(c1, m - 1))
        wrap = np.flatnonzero(ok & (c1 >= m))
        ok[wrap] = self._covers(rows[wrap], np.zeros(wrap.size, np.int64), c1[wrap] - m)
        return ok


def whole_lower(ring: _Ring, runs: _RowRuns, cfg: _Configs) -> FloatArray:
    """Each configuration's largest square where its whole windows hold (one ring with
    itself, the mode's runs): the block's cells outside
    its interior are read from the runs of four rows (``M`` of a ring with itself is
    symmetric: the block's first and last columns are rows too); the interior block is
    all True in every configuration the search collects (its windows are read from the
    runs of its interior rows).  0 where not shown (the trivial lower bound)."""
    m = ring.m
    iA, kA = cfg.iA % m, np.asarray(cfg.kA, np.int64)
    iC, kC = cfg.iC % m, np.asarray(cfg.kC, np.int64)
    nA, nC = kA + 2, kC + 2
    ok = (nA <= m) & (nC <= m)
    for rows, c0, n in ((iA, iC, nC), ((iA + kA + 1) % m, iC, nC),
                        (iC, iA, nA), ((iC + kC + 1) % m, iA, nA)):
        at = np.flatnonzero(ok)
        ok[at] = runs.holds(rows[at], c0[at], n[at])
    arc_a, arc_c = _ext(ring, iA, kA), _ext(ring, iC, kC)
    spans = np.where(arc_a <= arc_c, _inner(ring, iC, kC) <= arc_a,
                     _inner(ring, iA, kA) <= arc_c)
    return np.where(ok & spans, np.minimum(arc_a, arc_c), 0.0)


#: Whether a distinct round leaves out of its collection, or unsolved, a kept plan's
#: copy whose whole windows prove its largest square above its threshold
#: (:func:`whole_lower`, the collection's ``_copy_kernels._copy_at_optimum``; False: every
#: such configuration collected and solved, the reference).
WHOLE_WINDOWS = True


class _Whole:
    """:func:`whole_lower` for the jobs of a search that it reads (:meth:`reads`), each
    ring's and mode's runs made searchable once."""

    def __init__(self, rings: list[_Ring], runs: dict[Any, Any]) -> None:
        self.rings, self.runs = rings, runs
        self._made: dict[Any, _RowRuns] = {}

    @staticmethod
    def reads(job: Any) -> bool:
        """Whether the job is one ring with itself (the vertex matrix symmetric), with
        :data:`WHOLE_WINDOWS`."""
        return bool(job[0] == job[1] and WHOLE_WINDOWS)

    def __call__(self, job: Any, cfg: _Configs) -> FloatArray:
        """:func:`whole_lower` of the configurations ``cfg`` of a job it reads."""
        x, _, sigma, _ = job
        key = (x, sigma)
        if key not in self._made:
            self._made[key] = _RowRuns(self.runs[x, x][sigma], self.rings[x].m)
        return whole_lower(self.rings[x], self._made[key], cfg)
