"""Proofs that every pose of a box of jaw poses holds (:func:`certify_box`): interval
bounds over sub-boxes, sound, not complete."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ...core import budget
from ...core._angles import shrunk_half_angle, wrap
from ...core._checks import FloatArray, check_int
from ...core.tolerances import CONTACT_TOL, ROUND_TOL, TOL
from ...model.polygon import Polygon
from ...model.regions import DEFAULT_MARGIN_DEG
from . import _kernels
from ._poses import (
    MAX_CONTACTS,
    NEAR_STRIP,
    JawParameters,
    _check_jaw_args,
    _grip_edges,
    _near_strip,
    _sin_range,
    insertion_point,
    jaw_poses,
)

# ----------------------------------------------------------------------------- certificates


def _arc_of(vectors: FloatArray) -> tuple[FloatArray, FloatArray, np.ndarray]:
    """The smallest arcs (centre, half-width) holding the directions of each row of
    ``vectors`` (B, k, 2) (corners of a convex set), and where there is none (the set may
    hold the origin)."""
    ang = np.arctan2(vectors[..., 1], vectors[..., 0])
    rel = wrap(ang - ang[:, :1])
    lo, hi = rel.min(axis=1), rel.max(axis=1)
    none = (hi - lo >= np.pi - TOL) | (np.min(np.hypot(vectors[..., 0], vectors[..., 1]),
                                               axis=1) <= 0)
    return ang[:, 0] + (lo + hi) / 2, (hi - lo) / 2, none


@dataclass
class _Candidates:
    """Everything a pad may touch at some pose of each box of a batch (B boxes): up to
    :data:`MAX_CONTACTS` point sets (segments ``p0-p1`` (B, K, 2), a point when equal)
    with their contact force's direction as an arc (``centre``, ``half`` (B, K)),
    ``valid`` (B, K); bounds ``lo``, ``hi`` (B,) of the pad's stop over the box; ``ok``
    (B,): False where no feature surely reaches the strip or too many may touch."""

    p0: FloatArray
    p1: FloatArray
    centre: FloatArray
    half: FloatArray
    valid: np.ndarray
    lo: FloatArray
    hi: FloatArray
    ok: np.ndarray
    #: what each candidate is (the payload's bound follows it over the box): 0 a vertex
    #: (``index`` into ``points``, from the centroid), 1 or 2 the cut of the grip's edge
    #: ``index`` by the strip's side at ``-w/2`` or ``+w/2`` (the pad's corner on it)
    kind: np.ndarray | None = None
    index: np.ndarray | None = None
    points: FloatArray | None = None
    #: how many candidates (B,), those beyond :data:`MAX_CONTACTS` not listed
    count: np.ndarray | None = None
    #: all the candidates pooled (made with ``pooled``, :data:`POOLED`): the corners of
    #: the box holding their points (B, 4, 2) and the arc holding their forces
    #: (``pool_centre``, ``pool_half`` (B,)); None otherwise
    pool: FloatArray | None = None
    pool_centre: FloatArray | None = None
    pool_half: FloatArray | None = None


def _pad_candidates(polygon: Polygon, ring: np.ndarray, sign: float, internal: bool,
                    boxes: FloatArray, half: float, ahead: np.ndarray | None = None,
                    pooled: bool = False) -> _Candidates:
    """The pad of ``sign`` (+1: pad A of an external grip, the extreme of ``sign * y``)
    over each box ``(t0, t1, c0, c1)`` of ``boxes`` (B, 4): a superset of its contacts
    (``ok`` False when too many features could touch: more than :data:`MAX_CONTACTS`,
    as :func:`jaw_poses`; with ``pooled``, the candidates are pooled instead,
    :func:`_pooled`, and ``ok`` does not count them).  Inside a hole, ``ahead`` (B, m):
    the edges ahead of the pad (on its side of the closed jaws) at every pose of the
    box."""
    t0, t1, c0, c1 = (boxes[:, k:k + 1] for k in range(4))        # (B, 1) each
    B = len(boxes)
    cen = polygon.centroid
    a = polygon.starts[ring] - cen
    b = polygon.ends[ring] - cen
    m = len(a)
    f = -polygon.normals[ring]                          # the force on the part at an edge
    # y = p . u = px cos t + py sin t;  x = p . n = -px sin t + py cos t
    if internal:                                        # the edges this pad can meet
        fy_lo, fy_hi = _sin_range(f[:, 0], f[:, 1], t0, t1)
        pad_force = -sign                               # the force's sign along u
        maybe = fy_hi > 0 if pad_force > 0 else fy_lo < 0
        surely = fy_lo > 0 if pad_force > 0 else fy_hi < 0
        if ahead is not None:
            maybe, surely = maybe & ahead, surely & ahead
    else:
        # only an edge facing the pad (outward normal towards it) can hold its extreme:
        # below the strip's side line a part's boundary point faces away
        nu_lo, nu_hi = _sin_range(sign * polygon.normals[ring][:, 0],
                                  sign * polygon.normals[ring][:, 1], t0, t1)
        maybe = nu_hi > CONTACT_TOL
        surely = np.ones((B, m), dtype=bool)
    ends = np.concatenate([a, b])
    y_lo, y_hi = _sin_range(sign * ends[:, 0], sign * ends[:, 1], t0, t1)      # (B, 2m)
    x_lo, x_hi = _sin_range(ends[:, 1], -ends[:, 0], t0, t1)
    ok2 = np.concatenate([maybe, maybe], axis=1)
    sure2 = np.concatenate([surely, surely], axis=1)
    # a lower bound of the stop: a vertex inside the strip at every pose of the box
    always = sure2 & (x_lo >= c1 - half) & (x_hi <= c0 + half)
    lower = np.max(np.where(always, y_lo, -np.inf), axis=1)
    # an edge point inside the strip at every pose: the one at the strip's centre line
    # at the box's centre pose, if its lateral range stays inside
    tm, cm = (t0 + t1) / 2, (c0 + c1) / 2
    xa_m = -a[:, 0] * np.sin(tm) + a[:, 1] * np.cos(tm)
    xb_m = -b[:, 0] * np.sin(tm) + b[:, 1] * np.cos(tm)
    dx_m = xb_m - xa_m
    with np.errstate(divide="ignore", invalid="ignore"):
        tt = np.where(np.abs(dx_m) > 0, (cm - xa_m) / dx_m, np.nan)
    good = surely & (tt >= 0) & (tt <= 1)
    ttg = np.where(good, tt, 0.0)
    pts = a + ttg[..., None] * (b - a)                                         # (B, m, 2)
    px_lo, px_hi = _sin_range(pts[..., 1], -pts[..., 0], t0, t1)
    py_lo, _ = _sin_range(sign * pts[..., 0], sign * pts[..., 1], t0, t1)
    inside = good & (px_lo >= c1 - half) & (px_hi <= c0 + half)
    lower = np.maximum(lower, np.max(np.where(inside, py_lo, -np.inf), axis=1))
    uniq, inv = np.unique(ends, axis=0, return_inverse=True)
    zero = CONTACT_TOL * polygon.size                   # dx = 0 at a critical angle
    dominated = _dominated(uniq, inv.ravel(), always, y_lo, sign, t0, t1, 2 * zero)
    # vertices that may be in the strip and reach the lower bound (one entry per point:
    # an edge's end is the next edge's start), and are not always below another
    vert = ok2 & (x_hi >= c0 - half) & (x_lo <= c1 + half) & (y_hi >= lower[:, None])
    vert &= ~dominated(np.broadcast_to(ends, (B,) + ends.shape))
    vmask = np.zeros((B, len(uniq)), dtype=bool)
    rows, cols = np.nonzero(vert)
    vmask[rows, inv.ravel()[cols]] = True
    high = np.max(np.where(vert, y_hi, -np.inf), axis=1)
    # a vertex (or a level edge) touches the pad's face: its force is the pad's, -sign u
    face = ((t0 + t1) / 2)[:, 0] + (0.0 if sign < 0 else np.pi)
    face_half = ((t1 - t0) / 2)[:, 0]
    P0 = [np.broadcast_to(uniq, (B, len(uniq), 2))]
    P1 = [P0[0]]
    cen_f = [np.broadcast_to(face[:, None], vmask.shape)]
    half_f = [np.broadcast_to(face_half[:, None], vmask.shape)]
    use = [vmask]
    kinds = [np.zeros(vmask.shape, np.int64)]
    idx = [np.broadcast_to(np.arange(len(uniq)), vmask.shape)]
    # edge cuts by the strip's sides: the pad's corner on the edge (the lateral ranges of
    # the edges' ends are those of the vertices above: starts first, then ends)
    xa_lo, xa_hi = x_lo[:, :m], x_hi[:, :m]
    dxr_lo, dxr_hi = _sin_range(b[:, 1] - a[:, 1], -(b[:, 0] - a[:, 0]), t0, t1)
    e_lo, e_hi = np.minimum(xa_lo, x_lo[:, m:]), np.maximum(xa_hi, x_hi[:, m:])
    # a cut is the extreme of its clipped edge only if the edge rises (for this pad)
    # towards the strip's side there: drop the cuts where it surely falls
    dy_lo, dy_hi = _sin_range(sign * (b[:, 0] - a[:, 0]), sign * (b[:, 1] - a[:, 1]), t0, t1)
    # (an edge along u at the box's edge, dx = 0, has its extreme at a vertex: its cut is
    # dropped with the side it leans to inside the box, soundly; a level edge keeps both)
    rise_sign = np.where(dy_lo > 0, 1, np.where(dy_hi < 0, -1, 0)) * \
        np.where(dxr_lo >= -zero, 1, np.where(dxr_hi <= zero, -1, 0))
    # the edge may turn along u: its cut can be anywhere on it
    turns = (dxr_lo <= 0) & (dxr_hi >= 0)
    edge_force = np.arctan2(f[:, 1], f[:, 0])
    for side in (-half, half):
        s_lo, s_hi = c0 + side, c1 + side
        falls = rise_sign * np.sign(side) < 0
        sel = maybe & (e_hi >= s_lo) & (e_lo <= s_hi) & ~falls
        with np.errstate(divide="ignore", invalid="ignore"):
            q = np.stack([(s_lo - xa_hi) / dxr_lo, (s_hi - xa_lo) / dxr_lo,
                          (s_lo - xa_hi) / dxr_hi, (s_hi - xa_lo) / dxr_hi])
        t_lo = np.where(turns, 0.0, np.maximum(0.0, q.min(axis=0)))
        t_hi = np.where(turns, 1.0, np.minimum(1.0, q.max(axis=0)))
        sel &= t_lo <= t_hi
        t_lo, t_hi = np.where(sel, t_lo, 0.0), np.where(sel, t_hi, 0.0)
        p0 = a + t_lo[..., None] * (b - a)
        p1 = a + t_hi[..., None] * (b - a)
        _, h0 = _sin_range(sign * p0[..., 0], sign * p0[..., 1], t0, t1)
        _, h1 = _sin_range(sign * p1[..., 0], sign * p1[..., 1], t0, t1)
        hh = np.maximum(h0, h1)
        sel &= hh >= lower[:, None]
        sel &= ~(dominated(p0) & dominated(p1))     # the cut's points lie between its ends
        high = np.maximum(high, np.max(np.where(sel, hh, -np.inf), axis=1))
        P0.append(p0)
        P1.append(p1)
        cen_f.append(np.broadcast_to(edge_force, sel.shape))
        half_f.append(np.zeros(sel.shape))
        use.append(sel)
        kinds.append(np.full(sel.shape, 1 if side < 0 else 2, np.int64))
        idx.append(np.broadcast_to(np.arange(m), sel.shape))
    use_all = np.concatenate(use, axis=1)
    count = use_all.sum(axis=1)
    ok = np.isfinite(lower) & (count >= 1)
    pool = pool_centre = pool_half = None
    if pooled:
        pool, pool_centre, pool_half = _pooled(np.concatenate(P0, axis=1),
                                               np.concatenate(P1, axis=1),
                                               np.concatenate(cen_f, axis=1),
                                               np.concatenate(half_f, axis=1), use_all, face)
    else:
        ok &= count <= MAX_CONTACTS
    # the candidates first, at most MAX_CONTACTS of them
    order = np.argsort(~use_all, axis=1, kind="stable")[:, :MAX_CONTACTS]
    r = np.arange(B)[:, None]

    def pick(parts: list[Any]) -> Any:
        return np.concatenate(parts, axis=1)[r, order]

    return _Candidates(pick(P0), pick(P1), pick(cen_f), pick(half_f), use_all[r, order],
                       lower, high, ok, pick(kinds), pick(idx), uniq, count, pool,
                       pool_centre, pool_half)


#: Whether a pad with more than :data:`MAX_CONTACTS` candidates over a box is proved
#: with its candidates pooled (:func:`_pooled`: any of the points with any of the
#: forces), rather than left unproved: on a finely flattened curve a box of poses
#: sweeps many vertices under each pad, and the proof would otherwise cut it until
#: each pad has at most four (a smooth 1,000-edge outline at mu 1.0: 100,000 sub-boxes
#: for a box of 55 degrees).  False: the proof of individual candidates alone, the
#: reference (wherever it proves a box, the pooled proof does too: a pad with at most
#: four candidates is read the same way).
POOLED = True


def _pooled(p0: FloatArray, p1: FloatArray, centre: FloatArray, half: FloatArray,
            use: np.ndarray, face: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The candidates ``use`` (B, N) of each box pooled into one: the corners (B, 4, 2)
    of the axis-aligned box holding their segments ``p0``-``p1`` (B, N, 2), and the
    arc ``(centre, half)`` (B,) holding their forces' arcs, measured from the pad's face
    ``face`` (B,) (an arc across the face's opposite direction reads as nearly a whole
    turn, which no pair test passes: sound, and the forces a pad exerts all point
    within about a quarter turn of its face).  No candidate: NaN."""
    inf = np.where(use[..., None], 0.0, np.inf)
    lo = np.minimum(p0, p1) + inf
    hi = np.maximum(p0, p1) - inf
    x_lo, y_lo = lo[..., 0].min(axis=1), lo[..., 1].min(axis=1)
    x_hi, y_hi = hi[..., 0].max(axis=1), hi[..., 1].max(axis=1)
    corners = np.stack([np.stack([x_lo, y_lo], 1), np.stack([x_hi, y_lo], 1),
                        np.stack([x_lo, y_hi], 1), np.stack([x_hi, y_hi], 1)], axis=1)
    rel = wrap(centre - face[:, None])
    a_lo = np.where(use, rel - half, np.inf).min(axis=1)
    a_hi = np.where(use, rel + half, -np.inf).max(axis=1)
    with np.errstate(invalid="ignore"):
        return (np.where(np.any(use, axis=1)[:, None, None], corners, np.nan),
                face + (a_lo + a_hi) / 2, (a_hi - a_lo) / 2)


def _dominated(uniq: FloatArray, inv: np.ndarray, always: np.ndarray, y_lo: FloatArray,
               sign: float, t0: FloatArray, t1: FloatArray, gap: float) -> Any:
    """A test of points (B, n, 2) over each box (``t0``, ``t1``: (B, 1)): is the point
    lower (``sign`` times its height along ``u``) by more than ``gap`` at every angle of
    the box than the *dominating vertex*, the vertex surely in the strip at every pose
    (``always``, (B, 2m) over the edges' ends, ``y_lo`` their heights' lower bounds)
    whose height's lower bound is largest (ties: the first of the distinct points
    ``uniq``, ``inv`` the ends' indices among them)?  Such a point never touches the
    pad: the stop is at least the dominating vertex's height.  The difference of the
    two heights is bounded as one ``a cos t + b sin t`` (exact, :func:`_sin_range`),
    where bounding each height alone would widen both by the box's angle times the
    distance from the centroid: on a finely flattened curve every neighbour of the
    contact would stay a candidate down to tiny boxes."""
    key = np.where(always, y_lo, -np.inf)
    best = key.max(axis=1, keepdims=True)
    big = np.iinfo(np.int64).max
    first = np.where(always & (key == best), inv[None, :], big).min(axis=1)
    has = first < big
    w = uniq[np.where(has, first, 0)]                                       # (B, 2)

    def test(points: FloatArray) -> np.ndarray:
        d_lo, _ = _sin_range(sign * (w[:, None, 0] - points[..., 0]),
                             sign * (w[:, None, 1] - points[..., 1]), t0, t1)
        return np.asarray(has[:, None] & (d_lo > gap))

    return test


def _items(c: _Candidates) -> list[tuple[FloatArray, FloatArray, FloatArray, np.ndarray]]:
    """A pad's candidates as the pair test reads them, each ``(corners (B, k, 2), force
    arc's centre, half (B,), valid (B,))``: its listed candidates (the two ends of each
    segment) where it has at most :data:`MAX_CONTACTS`, else their pool
    (:func:`_pooled`)."""
    many = np.asarray(c.count > MAX_CONTACTS) if c.count is not None \
        else np.zeros(len(c.lo), bool)
    out: list[tuple[FloatArray, FloatArray, FloatArray, np.ndarray]] = [
        (np.stack([c.p0[:, i], c.p1[:, i]], axis=1), c.centre[:, i], c.half[:, i],
            c.valid[:, i] & ~many) for i in range(c.valid.shape[1])]
    if c.pool is not None and c.pool_centre is not None and c.pool_half is not None:
        out.append((c.pool, c.pool_centre, c.pool_half, many))
    return out


def _pairs_hold(ca: _Candidates, cb: _Candidates, beta: float, expand: bool) -> np.ndarray:
    """Per box: every pair of candidate contacts is force closure at every pose of it
    (theorem 6.3: the segment joining the contacts lies strictly inside both friction
    cones, with the directions of both ranging over arcs; squeezing for an external grip,
    expanding inside a hole).  The directions of a pair's chords are the smallest arc
    holding the differences of their corners (the chords of two convex sets form a
    convex set, the hull of those differences); none when the set may hold the origin.
    A pad with more than :data:`MAX_CONTACTS` candidates is read as their pool."""
    turn = np.pi if expand else 0.0
    holds = np.ones(len(ca.lo), dtype=bool)
    for pa, ca_c, ca_h, va in _items(ca):
        for pb, cb_c, cb_h, vb in _items(cb):
            corners = (pb[:, None, :, :] - pa[:, :, None, :]).reshape(len(pa), -1, 2)
            with np.errstate(invalid="ignore"):
                d, hd, no_arc = _arc_of(corners)
                # squeezing, A's force is within beta of every direction A -> B and B's
                # of B -> A; expanding, of the opposite directions
                fail = (no_arc | (np.abs(wrap(d + turn - ca_c)) + hd + ca_h >= beta)
                        | (np.abs(wrap(d + np.pi + turn - cb_c)) + hd + cb_h >= beta))
            holds &= ~(va & vb & fail)
    return holds


def _hole_sides(polygon: Polygon, ring: np.ndarray, q: FloatArray, boxes: FloatArray,
                half: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Over each box (B, 4) of an internal grip with insertion point ``q`` (from the
    centroid): the hole's edges wholly above the insertion height at every pose, those
    wholly below (B, m), and whether every edge that may meet the strip is one or the
    other (B,): the closed jaws' segment is then free at every pose."""
    t0, t1, c0, c1 = (boxes[:, k:k + 1] for k in range(4))
    a = polygon.starts[ring] - polygon.centroid
    b = polygon.ends[ring] - polygon.centroid
    ya_lo, ya_hi = _sin_range(a[:, 0], a[:, 1], t0, t1)
    yb_lo, yb_hi = _sin_range(b[:, 0], b[:, 1], t0, t1)
    xa_lo, xa_hi = _sin_range(a[:, 1], -a[:, 0], t0, t1)
    xb_lo, xb_hi = _sin_range(b[:, 1], -b[:, 0], t0, t1)
    yq_lo, yq_hi = _sin_range(q[0], q[1], t0, t1)
    may_meet = (np.maximum(xa_hi, xb_hi) >= c0 - half) & (np.minimum(xa_lo, xb_lo) <= c1 + half)
    up = np.minimum(ya_lo, yb_lo) > yq_hi
    down = np.maximum(ya_hi, yb_hi) < yq_lo
    return up, down, ~np.any(may_meet & ~up & ~down, axis=1)


def _edges(polygon: Polygon, ring: np.ndarray
           ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, np.ndarray]:
    """The edges of ``ring`` as the compiled proofs read them: starts and ends from the
    centroid, outward normals, the distinct ends and each end's index among them
    (starts first)."""
    a = polygon.starts[ring] - polygon.centroid
    b = polygon.ends[ring] - polygon.centroid
    uniq, inv = np.unique(np.concatenate([a, b]), axis=0, return_inverse=True)
    return a, b, polygon.normals[ring], uniq, inv.ravel()


def _pad_signs(internal: bool) -> tuple[float, float]:
    """The signs of pads A and B (:func:`_pad_candidates`' ``sign``): outside, A holds the
    extreme of ``+y`` and B of ``-y``; inside a hole the other way round."""
    return (-1.0, 1.0) if internal else (1.0, -1.0)


def _pads(polygon: Polygon, ring: np.ndarray, boxes: FloatArray, half: float,
          q: FloatArray | None, pooled: bool = False
          ) -> tuple[_Candidates, _Candidates, np.ndarray]:
    """Both pads' candidates over each box (B, 4), and whether the closed jaws' segment
    is free at every pose of it (always outside; inside a hole with insertion point
    ``q`` from the centroid, each edge that may meet the strip wholly above or below the
    insertion height, pad A meeting only edges above, pad B below); ``pooled``: as
    :func:`_pad_candidates` (the proofs pool, the payload's bound lists)."""
    sa, sb = _pad_signs(q is not None)
    if q is None:
        return (_pad_candidates(polygon, ring, sa, False, boxes, half, pooled=pooled),
                _pad_candidates(polygon, ring, sb, False, boxes, half, pooled=pooled),
                np.ones(len(boxes), dtype=bool))
    up, down, free = _hole_sides(polygon, ring, q, boxes, half)
    return (_pad_candidates(polygon, ring, sa, True, boxes, half, up, pooled),
            _pad_candidates(polygon, ring, sb, True, boxes, half, down, pooled), free)


def _angle_cuts(polygon: Polygon, ring: np.ndarray, t0: float, t1: float) -> FloatArray:
    """``t0``, the critical angles strictly between (where an edge of ``ring`` turns
    parallel to the closing direction: its facing and its lateral direction change sign
    there) and ``t1``, sorted: no sub-box of a proof or a payload straddles one."""
    d = polygon.ends[ring] - polygon.starts[ring]
    crit = np.mod(np.arctan2(d[:, 1], d[:, 0]), np.pi)
    crit = np.concatenate([crit + k * np.pi for k in range(int(np.floor(t0 / np.pi)) - 1,
                                                             int(np.ceil(t1 / np.pi)) + 1)])
    return np.unique(np.r_[t0, crit[(crit > t0) & (crit < t1)], t1])


def _box_proofs(polygon: Polygon, ring: np.ndarray, jaw: JawParameters, boxes: FloatArray,
                beta: float, q: FloatArray | None
                ) -> tuple[np.ndarray, FloatArray, FloatArray]:
    """For each box (B, 4) of a batch: whether it is proved (the features each pad may
    touch few, every pair of them force closure over the box, the opening's enclosure
    within the stroke; inside a hole, with insertion point ``q`` from the centroid, the
    closed jaws' segment free: the centre pose is the caller's), and that enclosure
    ``(o_lo, o_hi)``.  By the compiled loop of :mod:`._kernels` where it runs, else by
    numpy (:func:`_box_proofs_numpy`, the reference)."""
    if _kernels.available():
        out = _kernels.prove(boxes, *_edges(polygon, ring), jaw.pad_width / 2,
                             CONTACT_TOL * polygon.size, CONTACT_TOL, TOL, q, beta,
                             jaw.stroke, POOLED)
        if out is not None:
            return out
    return _box_proofs_numpy(polygon, ring, jaw, boxes, beta, q)


def _box_proofs_numpy(polygon: Polygon, ring: np.ndarray, jaw: JawParameters,
                      boxes: FloatArray, beta: float, q: FloatArray | None
                      ) -> tuple[np.ndarray, FloatArray, FloatArray]:
    """:func:`_box_proofs` by numpy (the reference of the compiled loop)."""
    internal = q is not None
    sa, sb = _pad_signs(internal)
    ca, cb, free = _pads(polygon, ring, boxes, jaw.pad_width / 2, q, POOLED)
    proved = ca.ok & cb.ok & free
    # the stops as heights along u: sign * stop lies in [lo, hi]
    a_lo, a_hi = np.minimum(sa * ca.lo, sa * ca.hi), np.maximum(sa * ca.lo, sa * ca.hi)
    b_lo, b_hi = np.minimum(sb * cb.lo, sb * cb.hi), np.maximum(sb * cb.lo, sb * cb.hi)
    with np.errstate(invalid="ignore"):
        o_lo, o_hi = a_lo - b_hi, a_hi - b_lo
        proved &= (jaw.stroke[0] <= o_lo) & (o_hi <= jaw.stroke[1])
    proved &= _pairs_hold(ca, cb, beta, internal)
    return proved, o_lo, o_hi


#: Sub-boxes :func:`certify_box` examines at a time.
CERTIFY_BATCH = 512

#: Slabs the compiled proof (:func:`_certify_compiled`) reads at a time, the time budget
#: checked between: the slabs are proved one after another, depth first, so the
#: proof is the same in pieces, and a box of a 10,000-edge outline (thousands of slabs,
#: seconds) stops soon after the budget ends.
CERTIFY_SLABS = 64


def _certify_compiled(polygon: Polygon, ring: np.ndarray, jaw: JawParameters,
                      todo: FloatArray, q: FloatArray | None, beta: float, max_boxes: int,
                      radius: float) -> tuple[bool, float, float, int] | None:
    """:func:`certify_box`'s compiled subdivision of the slabs ``todo``, in runs of
    :data:`CERTIFY_SLABS` slabs, each given the sub-boxes the runs before left of
    ``max_boxes`` (the same sub-boxes examined, so the same answer); not proved once the
    time budget has ended before a run (the search is then recorded as cut short).
    None where the compiled loop does not run."""
    edges = _edges(polygon, ring)
    lo, hi, used = np.inf, -np.inf, 0
    for i in range(0, len(todo), CERTIFY_SLABS):
        if budget.cut_if_over(counted=False):
            return False, lo, hi, used
        found = _kernels.certify(todo[i:i + CERTIFY_SLABS], *edges, jaw.pad_width / 2,
                                 CONTACT_TOL * polygon.size, CONTACT_TOL, TOL, q, beta,
                                 jaw.stroke, POOLED, max_boxes - used, radius,
                                 NEAR_STRIP * CONTACT_TOL * polygon.size, ROUND_TOL)
        if found is None:
            return None
        used += found[3]
        if not found[0]:
            return False, lo, hi, used
        lo, hi = min(lo, found[1]), max(hi, found[2])
    return True, lo, hi, used

#: :func:`certify_box`'s budget of sub-boxes counts for this many slabs between critical
#: angles (a box cut into more has that budget again for each such group).
SLABS_PER_BUDGET = 8


def certify_box(polygon: Polygon, jaw: JawParameters, theta: Any, offset: Any,
                margin: float = DEFAULT_MARGIN_DEG, hole: int | None = None,
                max_boxes: int = 4096) -> tuple[float, float] | None:
    """Prove that **every** pose of the box ``theta = (t0, t1)``, ``offset = (c0, c1)``
    holds (the model of :func:`jaw_poses`): the box is cut into sub-boxes until, in each,
    the features each pad may touch at some pose (vertices that may lie in the strip and
    reach a lower bound of the pad's stop; the strip's sides cut edges on segments
    enclosed by interval arithmetic; all bounds of ``a cos t + b sin t`` exact) are
    few, every pair of them is force closure over all its positions and directions
    (theorem 6.3 on arcs of directions), and the opening's enclosure is within the
    stroke.  Returns that enclosure of the opening over the box, or None when the proof
    fails within ``max_boxes`` sub-boxes for every :data:`SLABS_PER_BUDGET` slabs the
    critical angles cut the box into (a box on a curved outline sweeps a vertex every
    fraction of a degree, and each slab needs its own proof: a disc of 368 edges takes
    about 20,000 sub-boxes over 72 degrees), or when a sub-box's centre pose does not hold
    (then the box does not hold either).  Sound, not complete: None does not say that
    some pose fails.  The sub-boxes are examined in batches, level by level (compiled,
    :func:`._kernels.certify`: depth first, each reading only its parent's edges near its
    strip; the same sub-boxes, so the same answer).

    >>> from fcgrasp.io.parts import demo_part

    >>> from fcgrasp.grippers.jaw import ParallelJaw
    >>> jaw = ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
    >>> lo, hi = certify_box(demo_part("rectangle"), jaw, np.radians([80, 100]), (-30, 30))
    >>> bool(10 <= lo <= 30 and 30 / np.cos(np.radians(10)) <= hi <= 50)   # encloses 30-30.46
    True
    """
    t0, t1 = (float(v) for v in theta)
    c0, c1 = (float(v) for v in offset)
    if not (t1 >= t0 and c1 >= c0 and t1 - t0 < np.pi):
        raise ValueError(f"theta and offset must be increasing ranges (theta under pi), "
                         f"got {theta!r}, {offset!r}")
    margin = _check_jaw_args(polygon, jaw, margin)
    max_boxes = check_int(max_boxes, "max_boxes", minimum=1)
    ring = _grip_edges(polygon, hole)
    if t1 - t0 < np.pi / 2:
        ring = _near_strip(polygon, ring, t0, t1, c0, c1, jaw.pad_width / 2)
    beta = float(shrunk_half_angle(jaw.mu, margin))
    if beta <= 0:
        return None
    radius = polygon.radius
    q = None if hole is None else insertion_point(polygon, hole) - polygon.centroid
    # cut the box at the critical angles: no sub-box straddles one
    cuts = _angle_cuts(polygon, ring, t0, t1)
    todo = np.column_stack([cuts[:-1], cuts[1:], np.full(cuts.size - 1, c0),
                            np.full(cuts.size - 1, c1)])
    max_boxes *= max(1, -(-len(todo) // SLABS_PER_BUDGET))
    if _kernels.available():
        found = _certify_compiled(polygon, ring, jaw, todo, q, beta, max_boxes, radius)
        if found is not None:
            return (found[1], found[2]) if found[0] else None
    lo_open, hi_open = np.inf, -np.inf
    done = 0
    while len(todo):
        boxes, todo = todo[:CERTIFY_BATCH], todo[CERTIFY_BATCH:]
        done += len(boxes)
        if done > max_boxes:
            return None
        proved, o_lo, o_hi = _box_proofs(polygon, ring, jaw, boxes, beta, q)
        centre_holds = None
        if q is not None:
            # inside a hole, the closed jaws' segment is inside the hole at the centre
            # pose, hence at every pose (its middle would have to cross an edge to leave)
            centre_holds = jaw_poses(polygon, jaw, (boxes[:, 0] + boxes[:, 1]) / 2,
                                     (boxes[:, 2] + boxes[:, 3]) / 2, margin, hole).holds
            proved &= centre_holds
        if proved.any():
            lo_open = min(lo_open, float(o_lo[proved].min()))
            hi_open = max(hi_open, float(o_hi[proved].max()))
        rest = boxes[~proved]
        if not len(rest):
            continue
        # a sub-box whose centre pose fails cannot be proved: neither can the box (inside
        # a hole every centre pose was evaluated above)
        if centre_holds is None:
            centre_holds = jaw_poses(polygon, jaw, (rest[:, 0] + rest[:, 1]) / 2,
                                     (rest[:, 2] + rest[:, 3]) / 2, margin, hole).holds
        else:
            centre_holds = centre_holds[~proved]
        if not centre_holds.all():
            return None
        bt0, bt1, bc0, bc1 = rest.T
        by_angle = (bt1 - bt0) * radius >= bc1 - bc0
        mt, mc = (bt0 + bt1) / 2, (bc0 + bc1) / 2
        first = np.column_stack([bt0, np.where(by_angle, mt, bt1), bc0,
                                 np.where(by_angle, bc1, mc)])
        second = np.column_stack([np.where(by_angle, mt, bt0), bt1,
                                  np.where(by_angle, bc0, mc), bc1])
        todo = np.concatenate([todo, first, second])
    return lo_open, hi_open
