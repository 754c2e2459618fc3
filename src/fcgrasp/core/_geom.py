"""Small planar helpers shared by the modules (batched over leading axes)."""

from __future__ import annotations

from bisect import bisect_right
from collections.abc import Iterable, Sequence
from itertools import accumulate
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from ._checks import FloatArray
from .tolerances import RANK_TOL

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


#: Decimal digits of the ranking's rounding (:data:`~fcgrasp.core.tolerances.RANK_TOL`).
RANK_DIGITS = int(round(-np.log10(RANK_TOL)))


def cross2(a: FloatArray, b: FloatArray) -> FloatArray:
    """Scalar cross product ``a x b`` of planar vectors (..., 2)."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def unique_rows(a: FloatArray) -> FloatArray:
    """``np.unique(a, axis=0)`` (the distinct rows, sorted by the first column, then the
    next), without importing ``numpy.ma`` as numpy's own does: part of a plan's start-up.

    >>> unique_rows(np.array([[1.0, 2.0], [0.0, 5.0], [1.0, 2.0]])).tolist()
    [[0.0, 5.0], [1.0, 2.0]]
    """
    if a.shape[0] == 0:
        return a
    srt = a[np.lexsort(a.T[::-1])]
    keep = np.concatenate([[True], np.any(np.diff(srt, axis=0) != 0, axis=1)])
    return cast("FloatArray", srt[keep])


def direction(angle: ArrayLike) -> FloatArray:
    """Unit vectors (..., 2) at the given angles (radians)."""
    angle = np.asarray(angle, dtype=float)
    return np.stack([np.cos(angle), np.sin(angle)], axis=-1)


def signed_area(ring: ArrayLike) -> float:
    """Signed area of a closed ring (n, 2), positive when counter-clockwise (shoelace
    about the ring's mean, so large offsets do not cancel it)."""
    r = np.asarray(ring, dtype=float)
    x, y = r[:, 0] - r[:, 0].mean(), r[:, 1] - r[:, 1].mean()
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def along(line: ArrayLike, u: ArrayLike) -> tuple[FloatArray, np.ndarray]:
    """Points at fractions ``u`` (any shape) of the arc length of a polyline (m, 2),
    and the index of the segment holding each."""
    line = np.asarray(line, dtype=float)
    u = np.asarray(u, dtype=float)
    seg = np.diff(line, axis=0)
    L = np.hypot(seg[:, 0], seg[:, 1])
    cum = np.concatenate([[0.0], np.cumsum(L)])
    target = u * cum[-1]
    k = np.clip(np.searchsorted(cum, target, side="right") - 1, 0, len(seg) - 1)
    frac = np.where(L[k] > 0, (target - cum[k]) / np.where(L[k] > 0, L[k], 1.0), 0.0)
    return line[k] + frac[..., None] * seg[k], k


def midpoints(regions: Iterable[ArrayLike],
              region_edges: Iterable[Sequence[int]]) -> tuple[FloatArray, tuple[int, ...]]:
    """Each region's point halfway along its polyline (the representative contact) and
    the edge holding it, from the edges each region covers in order."""
    pts, edges = [], []
    for line, covered in zip(regions, region_edges, strict=True):
        p, k = _halfway(line)
        pts.append(p)
        edges.append(int(covered[k]))
    return np.array(pts), tuple(edges)


def _halfway(line: ArrayLike) -> tuple[tuple[float, float], int]:
    """:func:`along` at ``u = 0.5`` of one polyline, with two numpy calls instead of a
    dozen (a plan's few regions: numpy's calls cost more than the arithmetic): the same
    operations in the same order (the running sum is numpy's, one addition after
    another), so the same numbers."""
    line = np.asarray(line, dtype=float)
    if len(line) < 2:                           # along's answer (an error)
        p, at = along(line, 0.5)
        return (float(p[0]), float(p[1])), int(at)
    seg = line[1:] - line[:-1]
    L = np.hypot(seg[:, 0], seg[:, 1]).tolist()
    cum = [0.0, *accumulate(L)]
    target = 0.5 * cum[-1]
    k = min(max(bisect_right(cum, target) - 1, 0), len(L) - 1)
    Lk = L[k]
    frac = (target - cum[k]) / Lk if Lk > 0 else 0.0
    (x, y), (x1, y1) = line[k].tolist(), line[k + 1].tolist()
    return (x + frac * (x1 - x), y + frac * (y1 - y)), k


def trim_vertex_ends(pts: FloatArray, edges: Iterable[int], tiny: float
                     ) -> tuple[FloatArray, tuple[int, ...]]:
    """A region polyline through the edges it covers, without a piece of length at most
    ``tiny`` at either end: a region that starts or ends exactly at a vertex does not
    cover the edge beyond it."""
    edges = list(edges)
    if len(edges) > 1 and np.hypot(*(pts[1] - pts[0])) <= tiny:
        pts, edges = pts[1:], edges[1:]
    if len(edges) > 1 and np.hypot(*(pts[-1] - pts[-2])) <= tiny:
        pts, edges = pts[:-1], edges[:-1]
    return pts, tuple(edges)


def leximin_key(lengths: ArrayLike, size: float) -> tuple[float, ...]:
    """Sort key of the leximin order (definition 7.1): smaller is better.

    Each length over ``size``, rounded to :data:`RANK_DIGITS` decimals as
    ``numpy.round`` rounds (times ``10**RANK_DIGITS``, to the nearest even integer,
    divided back), in plain floats: a plan's few lengths, where numpy's calls cost more
    than the arithmetic (:func:`_leximin_key_numpy` where a length is not finite)."""
    values = sorted(np.asarray(lengths, float).ravel().tolist())
    size = float(size)
    out = []
    for v in values:
        r = _round(v / size)
        if r is None:
            return _leximin_key_numpy(lengths, size)
        out.append(-r)
    return tuple(out)


def _leximin_key_numpy(lengths: ArrayLike, size: float) -> tuple[float, ...]:
    """:func:`leximin_key` in numpy (its first form, kept for the lengths that are not
    finite)."""
    return tuple(leximin_columns(np.asarray(lengths, float), size))


def leximin_columns(lengths: FloatArray, size: float) -> FloatArray:
    """:func:`leximin_key`'s numbers of each row of ``lengths`` (the last axis): sorted,
    over ``size``, rounded to :data:`RANK_DIGITS` decimals, negated; rows compared
    column by column (:func:`numpy.lexsort`) order as their keys do."""
    return -np.round(np.sort(lengths, axis=-1) / size, RANK_DIGITS)


#: ``10 ** RANK_DIGITS`` as ``numpy.round`` makes it (:func:`_round`).
_SCALE = float(10 ** RANK_DIGITS)


def _round(v: float) -> float | None:
    """``numpy.round(v, RANK_DIGITS)`` of one float (``rint(v * 10**d) / 10**d``; Python's
    ``round`` rounds half to even as ``rint`` does, and its integer converts back
    exactly), plus 0 (no negative zero); None where ``v`` is not finite."""
    y = v * _SCALE
    if y - y != 0.0:                    # inf or nan
        return None
    return round(y) / _SCALE + 0.0


def geometric_key(regions: Iterable[ArrayLike], polygon: Any) -> tuple[float, ...]:
    """A key of a set of regions that does not depend on how the part is numbered.

    Each region's two ends (of a polyline: its first and last points) are sorted, the
    regions are sorted, and the coordinates (relative to the part's centroid and size,
    rounded to 1e-9) are read in that order.  Used to break ties between equally good
    plans or placements.

    In plain floats, as :func:`_geometric_key_numpy` (its first form) computes it with
    numpy: a plan's few regions, where numpy's calls cost more than the arithmetic.
    """
    ends = []
    for r in regions:
        r = np.asarray(r, float)
        if r.ndim != 2 or r.shape[1] != 2 or not len(r):
            return _geometric_key_numpy(regions, polygon)
        ends.append((r[0].tolist(), r[-1].tolist()))
    return ends_key(ends, polygon)


def ends_key(ends: Iterable[Any], polygon: Any) -> tuple[float, ...]:
    """:func:`geometric_key` of regions given by their two ends, plain float pairs
    ``[((x0, y0), (x1, y1)), ...]`` (:func:`_geometric_key_numpy` of them where a
    coordinate is not finite: it reads only the ends)."""
    cx, cy = (float(c) for c in polygon.centroid)
    size = float(polygon.size)
    segs = []
    for (x0, y0), (x1, y1) in ends:
        a = (_round((x0 - cx) / size), _round((y0 - cy) / size))
        b = (_round((x1 - cx) / size), _round((y1 - cy) / size))
        if None in a or None in b:
            return _geometric_key_numpy(ends, polygon)
        segs.append((a, b) if a <= b else (b, a))
    segs.sort()
    return tuple(x for seg in segs for pt in seg for x in pt)  # type: ignore[misc]


def _geometric_key_numpy(regions: Iterable[ArrayLike], polygon: Any) -> tuple[float, ...]:
    """:func:`geometric_key` in numpy (its first form, kept for the regions that are not
    point arrays or not finite)."""
    ends = np.array([[r[0], r[-1]] for r in (np.asarray(x, float) for x in regions)])
    rel = np.round((ends.reshape(-1, 2, 2) - polygon.centroid) / polygon.size, RANK_DIGITS) + 0.0
    segs = sorted(tuple(sorted(map(tuple, r.tolist()))) for r in rel)
    return tuple(x for seg in segs for pt in seg for x in pt)
