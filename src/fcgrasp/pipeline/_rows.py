"""The candidate rows of a search: edge sets enumerated in blocks, their layouts, the
bounds that order and prune them (part of :mod:`fcgrasp.pipeline`)."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from ..core._checks import (
    FloatArray,
)
from ..core._geom import RANK_DIGITS
from ..core.tolerances import RANK_TOL, SOLVER_TOL, SPAN_SLACK
from ._features import (
    Features,
)
from ._spec import (
    SearchShape,
)


def _keep_best(score: FloatArray, keep: int) -> np.ndarray:
    """Indices (sorted) of the ``keep`` best scores and of every score tied with the last
    of them, so that which of equal candidates survive does not depend on numbering."""
    thr = np.partition(score, score.size - keep)[score.size - keep]
    return np.flatnonzero(score >= thr - RANK_TOL * abs(thr))


def _distinct_edges(F: Features, t: np.ndarray) -> np.ndarray:
    e = F.edge[t]
    k = t.shape[1]
    ok = np.ones(len(t), dtype=bool)
    for x in range(k):
        for y in range(x + 1, k):
            ok &= e[:, x] != e[:, y]
    return t[ok]


#: Rows per block of :func:`_combos` (triples): the blocks of consecutive first positions
#: are joined up to this many, in the same order (on a flattened curve a position's own
#: block is a handful of rows, and the numpy calls per block were the cost).
COMBO_BLOCK = 4096


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
    parts, rows = [], 0
    for first in range(s - 2):
        a, b = np.triu_indices(s - first - 1, 1)
        block = np.empty((a.size, 3), dtype=int)
        block[:, 0] = first
        block[:, 1] = a + first + 1
        block[:, 2] = b + first + 1
        parts.append(block)
        rows += a.size
        if rows >= COMBO_BLOCK:     # blocks of several first positions: fewer numpy calls
            yield np.concatenate(parts)
            parts, rows = [], 0
    if parts:
        yield np.concatenate(parts)


def _layouts(t: np.ndarray, shape: SearchShape, fingers: int) -> np.ndarray:
    """Candidate rows of sorted feature tuples ``t`` (:attr:`SearchShape.layout`): as they
    are; triples plus the gravity contact (-1); with four fingers on three edges (``t`` of
    width 3) the three layouts doubling each feature (first and third); with three on two
    edges (width 2) the two layouts doubling each (first and second)."""
    layout = shape.layout
    if layout == "gravity":
        return np.concatenate([t, -np.ones((len(t), 1), int)], axis=1)
    if layout == "as_is" or t.shape[1] == fingers:
        return t
    rows = []
    for x in range(t.shape[1]):
        rest = [t[:, y] for y in range(t.shape[1]) if y != x]
        cols = rest[:shape.twin - 1] + [t[:, x]] + rest[shape.twin - 1:]
        rows.append(np.stack([t[:, x], *cols], axis=1))
    return np.concatenate(rows)


def _row_bound(lengths: FloatArray, rows: np.ndarray, twin: int | None) -> FloatArray:
    """Upper bound of the smallest region of each row: no region is longer than its
    feature, and two fingers on one feature (first and ``twin``: the third of four, the
    second of three; None where no row doubles one) share it, so one of them has at most
    half of it.  Gravity (-1) has no region.  (The columns' minimum taken column by
    column: numpy's reduction along a row of four costs ten times more.)"""
    ext = np.append(np.asarray(lengths, dtype=float), np.inf)   # the last: no region
    L = ext[np.where(rows >= 0, rows, -1)]
    if twin is not None:
        same = rows[:, 0] == rows[:, twin]
        L[same, 0] *= 0.5
        L[same, twin] = L[same, 0]
    out = L[:, 0].copy()
    for k in range(1, L.shape[1]):
        np.minimum(out, L[:, k], out=out)
    return out


def _row_bounds(lengths: FloatArray, rows: np.ndarray, twin: int | None) -> FloatArray:
    """Upper bounds of each row's region lengths, sorted ascending (one column per real
    finger; gravity, -1, has no region): no region is longer than its feature, and of
    two fingers on one feature (first and ``twin``) one has at most half of it, the
    other at most all of it.  A row's sorted regions are at most these, component by
    component (pair each region with its own bound), so its leximin key is never better
    than theirs (:func:`lex_survivors`)."""
    real = rows[0] >= 0 if len(rows) else np.zeros(0, bool)
    L = lengths[np.maximum(rows[:, real], 0)]
    if twin is not None:
        same = rows[:, 0] == rows[:, twin]
        L[same, 0] *= 0.5
    return np.sort(L, axis=1)


def _bound_pad(size: float) -> float:
    """What a region's length may exceed its feature's by: float error (the solver
    caps its levels at the features' lengths), far below the ranking's rounding."""
    return 10 * SOLVER_TOL * size


def lex_survivors(bounds: FloatArray, key: FloatArray | None, size: float) -> np.ndarray:
    """Which rows (their :func:`_row_bounds`) may still reach or tie the leximin key
    ``key`` (the running top's last, :attr:`~fcgrasp.pipeline.TopK.key`: its region
    lengths sorted ascending, over ``size``, rounded as
    :func:`~fcgrasp.core._geom.leximin_key` rounds).  Rounding keeps order, so a row is
    surely worse when, at the first length where its bound and the key round apart,
    the bound rounds below (its regions are at most the bounds: the solver's levels
    are capped by the features' lengths; each bound is padded by :func:`_bound_pad`
    for the float error).  None keeps every row.

    >>> size = 10.0
    >>> key = np.array([0.1, 0.5])                # regions 1 and 5 of a part of size 10
    >>> lex_survivors(np.array([[1.0, 4.0], [1.0, 6.0], [2.0, 2.0], [0.5, 9.0]]), key, size)
    array([False,  True,  True, False])
    """
    if key is None or not len(bounds):
        return np.ones(len(bounds), bool)
    b = np.round((bounds + _bound_pad(size)) / size, RANK_DIGITS)
    alive = np.ones(len(b), bool)
    open_ = np.ones(len(b), bool)          # every length so far rounds to the key's
    for j in range(min(b.shape[1], key.size)):
        alive &= ~(open_ & (b[:, j] < key[j]))
        open_ &= b[:, j] == key[j]
    return alive


def _spans_plane(angles: FloatArray) -> bool:
    """Whether directions at sorted ``angles`` in [0, 2 pi) may positively span the plane
    (no gap between neighbours, cyclically, wider than half a turn plus the slack)."""
    if angles.size < 3:
        return False
    gaps = np.diff(np.concatenate([angles, angles[:1] + 2 * np.pi]))
    return bool(gaps.max() <= np.pi + SPAN_SLACK)
