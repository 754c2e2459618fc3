r"""The load a parallel jaw carries over a whole box of poses ("the guaranteed
scale over every grasp of its regions (or jaw box)").

At a pose each pad presses the part at one feature (:func:`~._poses.jaw_poses`): a
vertex, pushing along the pad's face direction, or the pad's corner on an edge, pushing
along the edge's inward normal, with friction ``mu`` either way; each pad's **normal
force** (along that direction) is at most ``force_limit``, and with ``total_limit``
the two sum to at most that.  The scale of a load one pose carries is
:func:`fcgrasp.model.loads.grasp_payload`'s.  :func:`jaw_payload` certifies a scale
that **every** pose of the box carries, by branch and bound over sub-boxes of poses:

* **The features.**  In a sub-box each pad touches one of a few candidates, a superset
  of its features at every pose (the proofs' :func:`~._certify._pad_candidates`); the
  sub-box's bound is the least over the pairs of candidates, each pair taken as the
  contact at every pose of it (sound: the actual pair at a pose is one of them).
* **Both pads move together.**  At the sub-box's middle angle a pad's corner on an edge
  sits at a point affine in the offset (the edge met by the line at ``c +- w/2``), so
  at an offset ``c = l c_0 + (1 - l) c_1`` *both* pads sit at the same combination of
  where they sit at ``c_0`` and at ``c_1``: the box program of
  :mod:`fcgrasp.model.loads` over those two *joint* corners (not the four corners of
  independent positions, whose pairs never occur together and may not even hold)
  bounds every offset; at another angle of the sub-box the corner sits within
  ``eps = |d tau / d theta| |d| dtheta / 2`` of that point along its edge (bounded in
  closed form), which the program's torque slack covers (``eps_i (cbar_i + d_i)``).
* **The pad's face turns.**  A vertex's force keeps inside the cone common to every
  angle of the sub-box (half-angle ``atan(mu) - dtheta / 2`` about the middle face
  direction), and its normal force, measured along that middle direction, is held to
  ``force_limit`` divided by the most it grows along any face direction of the sub-box
  (``cos(max(alpha' - dtheta / 2, 0)) / cos(alpha')``).

The worst pose met (:data:`PERIMETER` poses along each side of the box, and each
sub-box's centre pose, with their exact contacts) gives the upper bound; the sub-box of
least bound is halved (along its angle where the corners' drift loosens its worst pair
more than their spread over the offsets, else along its offset; without either, the
longer side at the part's radius) until ``1 - lower / upper <= gap`` or ``max_boxes``
sub-boxes were bounded.
"""

from __future__ import annotations

import heapq
from typing import Any, NamedTuple

import numpy as np

from ...core._checks import FloatArray, check_int, check_scalar
from ...core.tolerances import ROUND_TOL
from ...model._payload_programs import _cone_edges, _limits, _wrench_edges
from ...model.loads import (
    Load,
    RegionPayload,
    _box_scale,
    grasp_payload,
)
from ...model.polygon import Polygon
from ._certify import _angle_cuts, _Candidates, _pad_signs, _pads
from ._plans import JawPlan, _contact_points
from ._poses import MAX_CONTACTS, _grip_edges, _sin_range, insertion_point, jaw_poses

__all__ = ["jaw_payload"]

#: Poses along each side of the box (its corners included) read for the upper bound.
PERIMETER = 5


class _PadPiece(NamedTuple):
    """One pad's candidate feature over a sub-box, as the box program reads it: where it
    sits at the joint corners (the offsets ``c0`` and ``c1`` at the middle angle), the
    direction it pushes, its cone's half-angle, its width along its edge between the
    corners, ``eps`` (its drift along the edge as the angle turns) and the divisor of the
    force limit (a vertex's normal force grows as the pad's face turns)."""

    p0: FloatArray
    p1: FloatArray
    push: FloatArray
    half: float
    width: float
    eps: float
    grow: float


def _piece(polygon: Polygon, edges: np.ndarray, cand: _Candidates, b: int, i: int,
           box: FloatArray, beta: float, half_pad: float) -> _PadPiece | None:
    """The pad's candidate ``i`` of sub-box ``b`` (:class:`_PadPiece`); None where its
    common cone is empty or its drift unbounded (the bound is then 0)."""
    t0, t1, c0, c1 = box
    tm, dt = 0.5 * (t0 + t1), t1 - t0
    g = polygon.centroid
    assert cand.kind is not None and cand.index is not None and cand.points is not None
    kind, index = int(cand.kind[b, i]), int(cand.index[b, i])
    if kind == 0:
        # a vertex under the pad's face: its force's direction is the face's, over an
        # arc (the candidate's centre and half-width: the sub-box's middle angle, dt / 2)
        face, turn = float(cand.centre[b, i]), float(cand.half[b, i])
        half = beta - turn
        if half < 0:
            return None
        grow = np.cos(max(half - turn, 0.0)) / np.cos(half)
        p = cand.points[index] + g
        return _PadPiece(p, p, np.array([np.cos(face), np.sin(face)]), half, 0.0, 0.0,
                         float(grow))
    e = int(edges[index])
    a, d = polygon.starts[e], polygon.ends[e] - polygon.starts[e]
    side = -half_pad if kind == 1 else half_pad
    lat = np.array([-np.sin(tm), np.cos(tm)])
    den = float(d @ lat)
    if den == 0:
        return None
    base = float((a - g) @ lat)
    tau0, tau1 = (c0 + side - base) / den, (c1 + side - base) / den
    # the corner's parameter as the angle turns: tau = (c + side - (a - g).l) / (d.l),
    # whose derivative is y / (d.l), y the corner's height (p - g).u: the corner moves
    # along its edge at |d| |y| / |d.l|, |y| at most the farthest end of the cut's
    # enclosure over the sub-box (p0, p1 from the centroid)
    lo, hi = _sin_range(d[1], -d[0], t0, t1)
    dmin = min(abs(float(lo)), abs(float(hi)))
    if float(lo) <= 0 <= float(hi) or dmin == 0:
        return None
    dl = float(np.hypot(*d))
    height = 0.0
    for end in (cand.p0[b, i], cand.p1[b, i]):           # y is linear along the cut
        y_lo, y_hi = _sin_range(end[0], end[1], t0, t1)
        height = max(height, abs(float(y_lo)), abs(float(y_hi)))
    eps = dl * height / dmin * 0.5 * dt
    n = -polygon.normals[e]
    return _PadPiece(a + tau0 * d, a + tau1 * d, n, beta, abs(tau1 - tau0) * dl, eps, 1.0)


def _pair_bound(pa: _PadPiece | None, pb: _PadPiece | None, W: FloatArray, per: FloatArray,
                total: float) -> float:
    """The box program's scale for one pair of candidates (:func:`_piece`)."""
    if pa is None or pb is None or not np.isfinite(pa.eps + pb.eps):
        return 0.0
    E = _cone_edges(np.array([pa.push, pb.push]), np.array([pa.half, pb.half]))
    widths = np.array([pa.width, pb.width])
    eps = np.array([pa.eps, pb.eps])
    grow = np.array([pa.grow, pb.grow])
    corners = [np.array([pa.p0, pb.p0])]
    if widths.max() > 0:
        corners.append(np.array([pa.p1, pb.p1]))
    rows = [(_wrench_edges(p, E), p) for p in corners]
    return _box_scale(rows, widths, W, per / grow, total / float(grow.max()),
                      eps if eps.max() > 0 else None)


def _pose_scale(polygon: Polygon, plan: Any, theta: float, offset: float, load: Load,
                force_limit: Any, total_limit: Any) -> tuple[float, FloatArray] | None:
    """The exact scale of the pose ``(theta, offset)`` with its contacts
    (:func:`jaw_poses`), and the contacts; None where a pad touches more than one point
    (a face flush with the pad: a set of measure zero, left to the lower bound)."""
    r = jaw_poses(polygon, plan.jaw, [theta], [offset], hole=plan.hole)
    sa, sb = _pad_signs(plan.hole is not None)
    pts, dirs = [], []
    for stop, lats, psi, sign in ((r.top[0], r.lat_a[0], r.psi_a[0], sa),
                                  (r.bottom[0], r.lat_b[0], r.psi_b[0], sb)):
        ok = np.flatnonzero(np.isfinite(lats[:, 0]))
        # a vertex is listed once per edge that meets there: one point, one force
        if not len(ok) or np.ptp(lats[ok]) > ROUND_TOL * polygon.size \
                or np.ptp(psi[ok]) > ROUND_TOL:
            return None
        k = int(ok[0])
        pts.append(_contact_points(polygon, theta, lats[k:k + 1], float(stop))[0])
        # the pad pushes along +u (sign < 0) or -u, and psi turns its force towards +l
        # (the lateral axis): from +u anticlockwise, from -u clockwise
        ang = theta + psi[k] if sign < 0 else theta + np.pi - psi[k]
        dirs.append([np.cos(ang), np.sin(ang)])
    P = np.array(pts)
    got = grasp_payload(P, np.array(dirs), plan.jaw.mu, load, force_limit=force_limit,
                        total_limit=total_limit, com=polygon.centroid)
    return got.scale, P


def jaw_payload(polygon: Polygon, plan: Any, load: Load, force_limit: Any = None,
                total_limit: Any = None, gap: float = 0.01, max_boxes: int = 64
                ) -> RegionPayload:
    """The scale of ``load`` that **every** pose of a parallel jaw's box carries (see
    the module docstring): a certified ``lower`` bound, the worst pose met (``worst``:
    its two contact points) and its scale ``upper``.

    ``plan``: a :class:`~fcgrasp.grippers.jaw.JawPlan`; ``force_limit``: each pad's
    normal force, N (one value or one per pad); ``total_limit``: their sum.  Each
    sub-box costs a small linear program per pair of candidate features (a few ms).

    >>> import fcgrasp as fc
    >>> part = fc.read_part("demo:triangle")
    >>> jaw = fc.ParallelJaw(stroke=(5, 60), pad_width=8, mu=0.5)
    >>> box = fc.plan(part, gripper=jaw, top=1)[0]          # 7.2 degrees x 4.6 mm
    >>> got = jaw_payload(part, box, fc.Load(mass=0.5), force_limit=10)
    >>> round(got.lower, 3), round(got.upper, 3), got.gap <= 0.01
    (0.953, 0.962, True)
    """
    from ...model.polygon import check_polygon

    polygon = check_polygon(polygon)
    if not isinstance(plan, JawPlan):
        raise TypeError(f"plan must be a parallel jaw's box (a JawPlan; point fingers' "
                        f"plans: fcgrasp.region_payload), got {type(plan).__name__}")
    if not isinstance(load, Load):
        raise TypeError(f"load must be a fcgrasp Load, got {type(load).__name__}")
    gap_v = check_scalar(gap, "gap", nonnegative=True)
    max_boxes = check_int(max_boxes, "max_boxes", minimum=1)
    per, total = _limits(force_limit, total_limit, 2)
    W = load.wrenches(polygon.centroid)             # an ellipse's circumscribed polygon
    jaw = plan.jaw
    ring = _grip_edges(polygon, plan.hole)
    edges = np.flatnonzero(ring)
    half_pad = jaw.pad_width / 2
    q = None if plan.hole is None else insertion_point(polygon, plan.hole) - polygon.centroid
    beta = float(np.arctan(jaw.mu))
    t0, t1 = (float(v) for v in plan.theta)
    c0, c1 = (float(v) for v in plan.offset)
    # no sub-box straddles a critical angle (an edge parallel to the closing direction)
    cuts = _angle_cuts(polygon, ring, t0, t1)
    todo = [np.array([a, b, c0, c1]) for a, b in zip(cuts[:-1], cuts[1:], strict=True)]
    upper, worst = np.inf, np.zeros((2, 2))
    heap: list[tuple[float, int, FloatArray, bool | None]] = []
    count = 0
    radius = polygon.radius

    def bound(boxes: list[FloatArray]) -> None:
        nonlocal upper, worst, count
        ca, cb, ok = _pads(polygon, ring, np.array(boxes), half_pad, q)
        # every candidate listed (a superset without the proofs' lower bound of the stop,
        # which needs narrow offsets: the payload's sub-boxes need not be)
        assert ca.count is not None and cb.count is not None
        ok &= (ca.count >= 1) & (ca.count <= MAX_CONTACTS) & (cb.count >= 1) \
            & (cb.count <= MAX_CONTACTS)
        for b, box in enumerate(boxes):
            count += 1
            at = _pose_scale(polygon, plan, 0.5 * (box[0] + box[1]),
                             0.5 * (box[2] + box[3]), load, force_limit, total_limit)
            if at is not None and at[0] < upper:
                upper, worst = at
            low, by_angle = np.inf, None
            if not ok[b]:
                low = 0.0
            else:
                for i in np.flatnonzero(ca.valid[b]):
                    pa = _piece(polygon, edges, ca, b, int(i), box, beta, half_pad)
                    for j in np.flatnonzero(cb.valid[b]):
                        pb = _piece(polygon, edges, cb, b, int(j), box, beta, half_pad)
                        got = _pair_bound(pa, pb, W, per, total)
                        if got < low:
                            low = got
                            # halve what loosens the worst pair most: the corners'
                            # drift as the angle turns, or their spread over the offsets
                            # (a pair that holds nothing may not occur at all, its
                            # candidates from a wide sub-box: the usual rule)
                            by_angle = None
                            if pa is not None and pb is not None and got > 0 \
                                    and pa.width + pa.eps + pb.width + pb.eps > 0:
                                by_angle = pa.eps + pb.eps > pa.width + pb.width
                        if low <= 0:
                            break
                    if low <= 0:
                        break
            heapq.heappush(heap, (float(low), count, box, by_angle))

    # the box's sides: its worst poses are often there (at the edge of the holding set),
    # PERIMETER poses along each, the corners among them
    f = np.linspace(0.0, 1.0, PERIMETER)
    sides = np.r_[np.c_[t0 + f * (t1 - t0), np.full(PERIMETER, c0)],
                  np.c_[t0 + f * (t1 - t0), np.full(PERIMETER, c1)],
                  np.c_[np.full(PERIMETER, t0), c0 + f * (c1 - c0)],
                  np.c_[np.full(PERIMETER, t1), c0 + f * (c1 - c0)]]
    for t, c in sides:
        at = _pose_scale(polygon, plan, float(t), float(c), load, force_limit, total_limit)
        if at is not None and at[0] < upper:
            upper, worst = at
    bound(todo)
    while heap and count < max_boxes:
        low, _, box, by_angle = heap[0]
        if low == np.inf or low >= upper * (1 - gap_v):
            break
        heapq.heappop(heap)
        bt0, bt1, bc0, bc1 = box
        if by_angle is None:
            by_angle = (bt1 - bt0) * radius >= bc1 - bc0
        if by_angle:
            mid = 0.5 * (bt0 + bt1)
            halves = [np.array([bt0, mid, bc0, bc1]), np.array([mid, bt1, bc0, bc1])]
        else:
            mid = 0.5 * (bc0 + bc1)
            halves = [np.array([bt0, bt1, bc0, mid]), np.array([bt0, bt1, mid, bc1])]
        bound(halves)
    lower = min(min(h[0] for h in heap), upper) if heap else upper
    return RegionPayload(float(lower), float(upper), np.asarray(worst, float), count)
