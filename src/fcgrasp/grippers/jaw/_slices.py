"""The exact holding set of a parallel jaw, slice by slice: per closing angle, the offsets
that hold as intervals (:func:`holding_offsets`)."""

from __future__ import annotations

from typing import Any, cast

import numpy as np

from ...core import budget
from ...core._checks import FloatArray
from ...core.tolerances import CONTACT_TOL, ROUND_TOL, SLICE_TOL
from ...model.polygon import Polygon
from ...model.regions import DEFAULT_MARGIN_DEG
from . import _kernels
from ._poses import (
    NEAR_STRIP,
    POSE_BATCH,
    JawParameters,
    PoseContacts,
    _check_jaw_args,
    _evaluate,
    _grip_edges,
    _near_strip,
    _pose_args,
    insertion_point,
)


def holding_offsets(polygon: Polygon, jaw: JawParameters, theta: Any,
                    margin: float = DEFAULT_MARGIN_DEG, hole: int | None = None,
                    offsets: tuple[float, float] | None = None) -> list[FloatArray]:
    """The exact slices of the set of holding poses: for each closing angle of ``theta``
    (T,), the offsets at which the jaw holds (the model of :func:`jaw_poses`), as sorted
    disjoint intervals, an array (k, 2) per angle.  ``offsets`` ``(lo, hi)`` limits the
    slices to a window (an interval reaching its end is cut there; default: every offset
    at which a pad can touch the part).

    At a fixed angle every quantity of the model is piecewise affine in the offset ``c``:
    a vertex enters or leaves the strip at ``c = x +- pad_width / 2`` (these cut the
    slice into *cells*), and inside a cell a pad's stop is the largest (pad B: smallest)
    of affine functions - a vertex's height, the height of an edge cut by a side of the
    strip - so it is convex (concave) and kinks where the extreme passes from one
    feature to another.  A cell on which the stops and the contacts' lateral spans are
    affine at three points (near its ends and at its middle: a convex function affine at
    three points is affine between them) has affine verdict slacks (theorem 6.3's two
    lateral conditions per pair of contacts, and the stroke), so the verdict changes only
    at their roots, found in closed form; the pieces between roots are decided by
    :func:`jaw_poses` at their middles.  A cell holding a kink is split until it is
    shorter than ``4 * SLICE_TOL`` times the part's size, then decided at its middle: at
    the kink itself where one kink explains the model at five points (the lines through
    the two points nearest each end cross there, and their larger, or smaller, is the
    middle value), else at its middle.
    Exact up to :data:`SLICE_TOL` of the part's size: the three points stand that far
    inside a cell's ends (where a vertex entering the strip ties with the stop within
    :data:`CONTACT_TOL`), so a kink closer to an end than that is not seen.

    >>> from fcgrasp.io.parts import demo_part

    >>> from fcgrasp.grippers.jaw import ParallelJaw
    >>> jaw = ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
    >>> sl = holding_offsets(demo_part("rectangle"), jaw, [np.pi / 2])[0]   # across 30 mm
    >>> sl.round(6).tolist()    # on the long faces, while the pads overlap them (80 + 8)
    [[-44.0, 44.0]]
    """
    margin = _check_jaw_args(polygon, jaw, margin)
    th = np.atleast_1d(np.asarray(theta, dtype=float)).ravel()
    if not np.all(np.isfinite(th)):
        raise ValueError(f"theta must be finite angles, got {theta!r}")
    ring, cell_t, cell_lo, cell_hi = _cells(polygon, jaw, th, hole, offsets)
    rows = _holding_pieces(polygon, jaw, th, margin, hole, ring, cell_t, cell_lo, cell_hi)
    # pieces apart by less than the contact tolerance are one (at a vertex entering the
    # strip a contact's span starts from zero: its slack's root is the cell's end, give
    # or take rounding)
    return _merge_intervals(rows, th.size, CONTACT_TOL * polygon.size)


def holds_across(polygon: Polygon, jaw: JawParameters, theta: Any, margin: float,
                 hole: int | None, offsets: tuple[float, float]) -> np.ndarray:
    """Whether the exact slice (:func:`holding_offsets`) at each angle of ``theta`` holds
    at every offset of ``offsets = (c0, c1)``: one interval from ``c0`` to ``c1`` (each
    within the contact tolerance).  The same answers as reading :func:`holding_offsets`;
    the compiled loop gives an angle up at its first piece longer than the tolerance that
    does not hold (the merged slice then has a gap there, or misses an end)."""
    margin = _check_jaw_args(polygon, jaw, margin)
    th = np.atleast_1d(np.asarray(theta, dtype=float)).ravel()
    tol = CONTACT_TOL * polygon.size
    c0, c1 = (float(v) for v in offsets)
    failed = np.zeros(th.size, dtype=bool)
    slices = _stopping_slices(polygon, jaw, th, margin, hole, (c0, c1), failed, False)
    return np.array([not failed[k] and iv.shape[0] == 1 and iv[0, 0] <= c0 + tol
                     and iv[0, 1] >= c1 - tol for k, iv in enumerate(slices)], dtype=bool)


def near_intervals(polygon: Polygon, jaw: JawParameters, theta: Any, margin: float,
                   hole: int | None, window: tuple[float, float], side: int) -> FloatArray:
    """Per angle of ``theta``, the far end of the exact slice's interval (within
    ``window``) that starts at the window's end away from ``side`` (+1: its low end,
    the interval's high end returned; -1: its high end, the interval's low end), NaN
    where no interval reaches that end within the contact tolerance.  The same answers
    as reading :func:`holding_offsets`; the compiled loop reads each angle's cells from
    that end and stops at its first piece longer than the tolerance that does not hold
    (the interval ends there)."""
    margin = _check_jaw_args(polygon, jaw, margin)
    th = np.atleast_1d(np.asarray(theta, dtype=float)).ravel()
    tol = CONTACT_TOL * polygon.size
    w0, w1 = (float(v) for v in window)
    slices = _stopping_slices(polygon, jaw, th, margin, hole, (w0, w1),
                              np.zeros(th.size, dtype=bool), side > 0)
    out = np.full(th.size, np.nan)
    for k, iv in enumerate(slices):
        at = (iv[:, 0] <= w0 + tol) if side > 0 else (iv[:, 1] >= w1 - tol)
        if at.any():
            out[k] = iv[at][0, 1] if side > 0 else iv[at][-1, 0]
    return out


#: Angles :func:`_stopping_slices` reads at a time, the time budget checked between
#: (on a 10,000-edge outline a few milliseconds each: a raster of hundreds would run
#: seconds past the budget).
SLICE_CHUNK = 32


def _stopping_slices(polygon: Polygon, jaw: JawParameters, th: FloatArray, margin: float,
                     hole: int | None, window: tuple[float, float], failed: np.ndarray,
                     upward: bool) -> list[FloatArray]:
    """The slices at ``th`` within ``window`` (merged as :func:`holding_offsets` merges
    them), by the compiled loop each angle given up at its first piece longer than the
    contact tolerance that does not hold (``failed`` set there), read from the low end up
    with ``upward``; where the loop does not run, :func:`holding_offsets` whole.  Read
    :data:`SLICE_CHUNK` angles at a time (each angle's slice is its own): once the time
    budget has ended (before any) the angles left are given up (``failed``, no interval: read as not
    holding, so the boxes made of them are smaller, never wrong) and the search is
    recorded as cut short."""
    out: list[FloatArray] = []
    for i in range(0, th.size, SLICE_CHUNK):
        j = min(i + SLICE_CHUNK, th.size)
        if budget.cut_if_over(counted=False):
            failed[i:] = True
            out += [np.zeros((0, 2)) for _ in range(i, th.size)]
            break
        out += _slices_of(polygon, jaw, th[i:j], margin, hole, window, failed[i:j], upward)
    return out


def _slices_of(polygon: Polygon, jaw: JawParameters, th: FloatArray, margin: float,
               hole: int | None, window: tuple[float, float], failed: np.ndarray,
               upward: bool) -> list[FloatArray]:
    """:func:`_stopping_slices` of the angles ``th`` at once."""
    tol = CONTACT_TOL * polygon.size
    rows = None
    if _kernels.available():
        ring, cell_t, cell_lo, cell_hi = _cells(polygon, jaw, th, hole, window)
        rows = _kernels.slices(
            cell_t, cell_lo, cell_hi, th, *_pose_args(polygon, jaw, margin, hole, ring),
            SLICE_TOL * polygon.size, ROUND_TOL * polygon.size, tol,
            NEAR_STRIP * CONTACT_TOL * polygon.size, stop_gap=tol, failed=failed,
            upward=upward)
    if rows is None:
        return holding_offsets(polygon, jaw, th, margin, hole, window)
    return _merge_intervals(rows, th.size, tol)


def _cells(polygon: Polygon, jaw: JawParameters, th: FloatArray, hole: int | None,
           offsets: tuple[float, float] | None
           ) -> tuple[np.ndarray, np.ndarray, FloatArray, FloatArray]:
    """The edges the slices at angles ``th`` read (near their strips) and their cells
    (:func:`holding_offsets`): per cell its angle's index and offset range, sorted by
    angle."""
    ring = _grip_edges(polygon, hole)
    rel = _grip_points(polygon, hole, ring)
    X = -np.sin(th)[:, None] * rel[:, 0] + np.cos(th)[:, None] * rel[:, 1]    # (T, V)
    half = jaw.pad_width / 2
    if offsets is None:
        w_lo, w_hi = X.min(axis=1) - half, X.max(axis=1) + half
    else:
        lo_hi = np.asarray(offsets, dtype=float)
        if lo_hi.shape != (2,) or not np.all(np.isfinite(lo_hi)) or lo_hi[1] < lo_hi[0]:
            raise ValueError(f"offsets must be an increasing range (lo, hi), got "
                             f"{offsets!r}")
        w_lo, w_hi = np.full(th.size, lo_hi[0]), np.full(th.size, lo_hi[1])
    cuts = [X - half, X + half]
    if hole is not None:
        # inside a hole the closed jaws' segment is blocked while an edge crosses the
        # insertion height within the strip: where an edge crosses that height, +- w/2
        q = insertion_point(polygon, int(hole)) - polygon.centroid
        cs, sn = np.cos(th)[:, None], np.sin(th)[:, None]
        a = polygon.starts[ring] - polygon.centroid
        b = polygon.ends[ring] - polygon.centroid
        ya, yb = cs * a[:, 0] + sn * a[:, 1], cs * b[:, 0] + sn * b[:, 1]
        xa, xb = -sn * a[:, 0] + cs * a[:, 1], -sn * b[:, 0] + cs * b[:, 1]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (cs * q[0] + sn * q[1] - ya) / (yb - ya)
        xc = np.where((t >= 0) & (t <= 1), xa + t * (xb - xa), w_lo[:, None])
        cuts += [xc - half, xc + half, xc]
    brk = np.sort(np.clip(np.concatenate(cuts + [w_lo[:, None], w_hi[:, None]], axis=1),
                          w_lo[:, None], w_hi[:, None]), axis=1)
    tiny = ROUND_TOL * polygon.size
    keep = brk[:, 1:] - brk[:, :-1] > tiny
    cells = np.nonzero(keep)
    cell_t, cell_lo, cell_hi = cells[0], brk[:, :-1][cells], brk[:, 1:][cells]
    if th.size and np.ptp(th) < np.pi / 2:
        # only the edges that may meet a strip of these angles and offsets: the pads'
        # middles run over [w_lo, w_hi] (half a pad either side of it is the strip's)
        ring = _near_strip(polygon, ring, float(th.min()), float(th.max()),
                           float(w_lo.min()), float(w_hi.max()), half)
    return ring, cell_t, cell_lo, cell_hi


def _grip_points(polygon: Polygon, hole: int | None, ring: np.ndarray) -> FloatArray:
    """The distinct vertices of the grip's edges ``ring`` from the centroid, computed
    once per part and grip (the growth of a box asks for thousands of slices)."""
    cache = polygon.__dict__.setdefault("_jaw_grip_points", {})
    got = cache.get(hole)
    if got is None:
        pts = np.unique(np.concatenate([polygon.starts[ring], polygon.ends[ring]]), axis=0)
        got = cache[hole] = pts - polygon.centroid
    return cast("FloatArray", got)


def _holding_pieces(polygon: Polygon, jaw: JawParameters, th: FloatArray, margin: float,
                    hole: int | None, ring: np.ndarray, cell_t: np.ndarray,
                    cell_lo: FloatArray, cell_hi: FloatArray) -> FloatArray:
    """The holding pieces ``(angle index, lo, hi)`` of the cells (the method of
    :func:`holding_offsets`): by the compiled loop of :mod:`._kernels` where it runs,
    else by numpy (:func:`_holding_pieces_numpy`, the reference)."""
    if _kernels.available():
        rows = _kernels.slices(cell_t, cell_lo, cell_hi, th,
                               *_pose_args(polygon, jaw, margin, hole, ring),
                               SLICE_TOL * polygon.size, ROUND_TOL * polygon.size,
                               CONTACT_TOL * polygon.size,
                               NEAR_STRIP * CONTACT_TOL * polygon.size)
        if rows is not None:
            return rows
    return _holding_pieces_numpy(polygon, jaw, th, margin, hole, cell_t, cell_lo, cell_hi)


def _holding_pieces_numpy(polygon: Polygon, jaw: JawParameters, th: FloatArray,
                          margin: float, hole: int | None, cell_t: np.ndarray,
                          cell_lo: FloatArray, cell_hi: FloatArray) -> FloatArray:
    """:func:`_holding_pieces` by numpy, the cells of a round side by side."""
    tiny = ROUND_TOL * polygon.size
    found: list[FloatArray] = []                        # rows (angle index, lo, hi)
    atol = CONTACT_TOL * polygon.size
    while cell_t.size:
        inset = np.minimum((cell_hi - cell_lo) / 4, SLICE_TOL * polygon.size)
        ends = np.stack([cell_lo + inset, (cell_lo + cell_hi) / 2, cell_hi - inset])  # (3, C)
        r, slack = _evaluate_batched(polygon, jaw, np.tile(th[cell_t], 3), ends.ravel(),
                                     margin, hole)
        C = cell_t.size
        q = np.concatenate([r.top[:, None], r.bottom[:, None], r.lat_a.reshape(3 * C, -1),
                            r.lat_b.reshape(3 * C, -1)], axis=1).reshape(3, C, -1)
        fin = np.isfinite(q)
        qz = np.where(fin, q, 0.0)
        psi = np.nan_to_num(np.concatenate([r.psi_a, r.psi_b], axis=1), nan=9.0)
        psi = psi.reshape(3, C, -1)
        kinds = np.stack([r.kind_a, r.kind_b], axis=1).reshape(3, C, 2)
        affine = (np.all(fin[0] == fin[1], axis=1) & np.all(fin[1] == fin[2], axis=1)
                  & np.all(psi[0] == psi[1], axis=1) & np.all(psi[1] == psi[2], axis=1)
                  & np.all(kinds[0] == kinds[1], axis=1) & np.all(kinds[1] == kinds[2], axis=1)
                  & np.all(np.abs(qz[1] - (qz[0] + qz[2]) / 2) <= atol, axis=1))
        holds_mid = r.holds.reshape(3, C)[1]
        last = ~affine & (cell_hi - cell_lo <= 4 * SLICE_TOL * polygon.size)
        found.append(np.column_stack([cell_t[last & holds_mid], cell_lo[last & holds_mid],
                                      cell_hi[last & holds_mid]]))
        # affine cells: the roots of the slacks, then the pieces between them decided
        s = slack.reshape(3, C, -1)
        s0, s2 = s[0][affine], s[2][affine]
        a_t, a_lo, a_hi = cell_t[affine], cell_lo[affine], cell_hi[affine]
        p0, p2 = ends[0][affine], ends[2][affine]
        with np.errstate(invalid="ignore", divide="ignore"):
            cross = (s0 * s2 < 0) | ((s0 == 0) != (s2 == 0))
            frac = np.where(cross, s0 / (s0 - s2), np.nan)
        ci, si = np.nonzero(cross)
        roots = p0[ci] + frac[ci, si] * (p2[ci] - p0[ci])
        which = np.concatenate([np.arange(a_t.size), np.arange(a_t.size), ci])
        where = np.concatenate([a_lo, a_hi, np.clip(roots, a_lo[ci], a_hi[ci])])
        order = np.lexsort((where, which))
        which, where = which[order], where[order]
        piece = (which[1:] == which[:-1]) & (where[1:] - where[:-1] > tiny)
        plo, phi, pc = where[:-1][piece], where[1:][piece], which[:-1][piece]
        if plo.size:
            verdict = _evaluate_batched(polygon, jaw, th[a_t[pc]], (plo + phi) / 2, margin,
                                        hole)[0].holds
            found.append(np.column_stack([a_t[pc][verdict], plo[verdict], phi[verdict]]))
        split = ~affine & ~last
        cut = ends[1][split]
        if cut.size:
            # two more points, a step in from each end: where the lines through each
            # end's pair meet is the kink, if one kink explains the middle too
            lo_s, hi_s, ins = cell_lo[split], cell_hi[split], inset[split]
            e0, e2 = lo_s + 2 * ins, hi_s - 2 * ins
            S = cut.size
            r2 = _evaluate_batched(polygon, jaw, np.tile(th[cell_t[split]], 2),
                                   np.concatenate([e0, e2]), margin, hole)[0]
            q2 = np.concatenate([r2.top[:, None], r2.bottom[:, None],
                                 r2.lat_a.reshape(2 * S, -1), r2.lat_b.reshape(2 * S, -1)],
                                axis=1).reshape(2, S, -1)
            cut = _kinks(ends[0][split], e0, ends[1][split], e2, ends[2][split],
                         q[0][split], q2[0], q[1][split], q2[1], q[2][split], lo_s, hi_s,
                         ins, atol)
        cell_t = np.concatenate([cell_t[split], cell_t[split]])
        cell_lo, cell_hi = (np.concatenate([cell_lo[split], cut]),
                            np.concatenate([cut, cell_hi[split]]))
    return np.concatenate(found) if found else np.zeros((0, 3))


def _kinks(p0: FloatArray, e0: FloatArray, p1: FloatArray, e2: FloatArray, p2: FloatArray,
           q0: FloatArray, qe0: FloatArray, q1: FloatArray, qe2: FloatArray, q2: FloatArray,
           lo: FloatArray, hi: FloatArray, inset: FloatArray, atol: float) -> FloatArray:
    """Where to split each cell ``[lo, hi]`` (C,) that is not affine: the model's
    quantities (C, Q) at five points ``p0 < e0 < p1 < e2 < p2``; of the quantity finite at
    all five that strays most from its chord at ``p1``, the crossing of the line through
    ``(p0, e0)`` and the line through ``(e2, p2)``, when the larger (convex) or smaller
    (concave) of the two lines is that quantity at ``p1`` within ``atol`` (one kink
    explains it) and the crossing lies between ``e0`` and ``e2``; else the middle
    ``p1`` (``_kernels._kink`` is the same, number by number)."""
    fin = np.isfinite(q0) & np.isfinite(qe0) & np.isfinite(q1) & np.isfinite(qe2) \
        & np.isfinite(q2)
    with np.errstate(invalid="ignore"):
        dev = np.where(fin, np.abs(q1 - (q0 + q2) / 2), -1.0)
    j = np.argmax(dev, axis=1)
    r = np.arange(len(j))
    a0, b0, m1, b2, a2 = q0[r, j], qe0[r, j], q1[r, j], qe2[r, j], q2[r, j]
    with np.errstate(invalid="ignore", divide="ignore"):
        s_l = (b0 - a0) / (e0 - p0)
        s_r = (a2 - b2) / (p2 - e2)
        x = (a2 - a0 + s_l * p0 - s_r * p2) / (s_l - s_r)
        left = a0 + s_l * (p1 - p0)
        right = a2 + s_r * (p1 - p2)
        model = np.where(m1 < (a0 + a2) / 2, np.maximum(left, right), np.minimum(left, right))
        ok = (dev[r, j] > atol) & (np.abs(model - m1) <= atol) & (x > lo + 2 * inset) \
            & (x < hi - 2 * inset)
    return np.where(ok, x, p1)




def _evaluate_batched(polygon: Polygon, jaw: JawParameters, th: FloatArray, c: FloatArray,
                      margin: float, hole: int | None) -> tuple[PoseContacts, FloatArray]:
    """:func:`_evaluate` in batches of :data:`POSE_BATCH` poses, joined."""
    parts = [_evaluate(polygon, jaw, th[i:i + POSE_BATCH], c[i:i + POSE_BATCH], margin, hole)
             for i in range(0, max(th.size, 1), POSE_BATCH)]
    if len(parts) == 1:
        return parts[0]
    fields = {k: np.concatenate([getattr(p[0], k) for p in parts])
              for k in PoseContacts.__dataclass_fields__}
    return PoseContacts(**fields), np.concatenate([p[1] for p in parts])


def _merge_intervals(rows: FloatArray, count: int, tol: float) -> list[FloatArray]:
    """Rows ``(index, lo, hi)`` (``lo <= hi``) joined into sorted disjoint intervals per
    index (pieces that touch within ``tol`` are one), with whole-array operations: in
    order of (index, lo), a piece starts a new interval where its ``lo`` is beyond the
    highest ``hi`` before it of its index by more than ``tol``; an interval ends at the
    highest ``hi`` of its pieces.  That running highest is exact: a running maximum of
    integer keys, the index times the row count plus the rank of ``hi``."""
    n = len(rows)
    if n == 0:
        return [np.zeros((0, 2)) for _ in range(count)]
    r = rows[np.lexsort((rows[:, 1], rows[:, 0]))]
    k = r[:, 0].astype(np.int64)
    lo, hi = r[:, 1], r[:, 2]
    by_hi = np.argsort(hi, kind="stable")
    rank = np.empty(n, np.int64)
    rank[by_hi] = np.arange(n)
    top = hi[by_hi][np.maximum.accumulate(k * n + rank) - k * n]   # highest hi so far
    first = np.ones(n, bool)
    first[1:] = (k[1:] != k[:-1]) | (lo[1:] > top[:-1] + tol)
    starts = np.flatnonzero(first)
    ends = np.r_[starts[1:], n] - 1
    pieces = np.stack([lo[starts], top[ends]], axis=1)
    bounds = np.searchsorted(k[starts], np.arange(count + 1))
    return [pieces[bounds[i]:bounds[i + 1]] for i in range(count)]
