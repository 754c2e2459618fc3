r"""A planar part held in its plane by a real hand: the part a plate of some thickness (on
a table or alone), the hand lying in the plate's plane with its fingers closing across the
outline and its palm on one side (section 8.2: the hand's shape as a collision problem),
and each jaw box cut to the poses where the whole pick is collision free.

**The pose.**  At a jaw pose (closing direction ``u`` at angle ``theta``, the pads' strip
across it at ``offset`` ``c`` along ``n``) the tool frame's ``y`` is ``u``, its ``z`` (the
approach, from the palm to the fingertips) is ``-side n``: with ``side = +1`` the hand lies
on the ``+n`` side of the strip and comes in along ``-n``.  The pad's extent along ``z``
is the strip (the jaw's ``pad_width`` is the hand's :attr:`~fcgrasp.model.hands.
ParallelHand.pad_height`), its centre on the strip's centre line; the tool's ``x`` is
``-side`` times the part's ``z``, and the tool's origin is at the plate's mid-thickness
(raised where a table needs it, while the pad still covers a band of the plate's side,
:func:`plane_reach`).  The hand comes in along ``z`` from ``approach`` away, opened to its
largest stroke, then closes.

**Why every pose of a cut box is collision free (proved, not sampled).**  In the rotating
frame a point of the hand stands at fixed coordinates: along ``n`` at ``c`` plus a
constant, along ``u`` (for finger A) at the pad's stop ``h_A`` plus a constant ``y >= y0``,
and ``h_A`` is the largest ``u . x`` over the outline within the strip.  So finger A's box
meets material within ``clearance`` only if the largest ``u . x`` of the outline in the
box's band along ``n`` (the band it sweeps on the approach and while closing, the strip
itself left out for boxes behind the pad's face: the strip holds no material past the
stop) reaches ``h_A + y0 - clearance``; the palm only if the outline enters its swept band
at all.  Over a box of poses ``[t0, t1] x [c0, c1]`` these bands are widened by ``rho (t1 -
t0) / 2`` (``rho``: the outline's largest distance from the centroid, about which the
frame turns), the largest ``u . x`` in a band is bounded above by its value at the middle
angle plus the same amount, and ``h_A`` below by the largest ``u . x`` in the band every
strip of the box holds, minus it; each is exact on the outline's edges clipped to a band.
A box whose bound fails is split on a grid (:data:`PLANE_CELLS` by side) and cut to its
largest rectangle of proved cells (by the jaw's measure); a plan keeps the side whose cut
measures more, and is dropped where neither side proves a cell.  The tests check the
verdict on sampled poses along the whole motion with python-fcl on the extruded plate.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...core._checks import FloatArray
from ...core.tolerances import STRIP_TOL
from ...model.hands import ParallelHand
from ...model.polygon import Polygon
from ._pick import Scene
from ._poses import _grip_edges

__all__ = ["PlaneReach", "plane_reach", "PlaneCut", "plane_cut", "band_support"]

#: A box that its bound cannot prove at once is split into this many cells along each
#: side and cut to its largest rectangle of proved cells.
PLANE_CELLS = 8


@dataclass(frozen=True)
class PlaneReach:
    """Where the hand lies across the plate, for each ``side``: the part ``z`` of the tool
    frame's origin (``height``) and the band of the plate's side the pad covers
    (``contact_height``)."""

    height: dict[int, float]
    contact_height: dict[int, float]


def _x_range(box: Any, turned: bool) -> tuple[float, float]:
    x = box.corners()[:, 0]
    return (-float(x.max()), -float(x.min())) if turned else (float(x.min()), float(x.max()))


def plane_reach(hand: ParallelHand, scene: Scene) -> PlaneReach | str:
    """The tool's height for each side (the module's docstring), or why the hand cannot
    hold the plate in its plane.  A point at tool ``x`` stands at part ``z = height -
    side x``: the height is the plate's mid-thickness, raised until every box clears the
    table by ``clearance``, as long as the pad still covers part of the plate's side."""
    T, clr = scene.thickness, scene.clearance
    boxes = [(b, False) for b in hand.palm + hand.finger] + [(b, True) for b in hand.finger]
    height, band = {}, {}
    for side in (1, -1):
        z0 = T / 2
        if scene.table:
            top = max(side * x for b, turned in boxes for x in _x_range(b, turned))
            z0 = max(z0, top + clr)
        # each pad's band of the plate's side (finger 2's pad turned: its x reversed)
        cover = math.inf
        for turned in (False, True):
            x0, x1 = _x_range(hand.pad_box, turned)
            lo, hi = sorted((z0 - side * x0, z0 - side * x1))
            cover = min(cover, min(T, hi) - max(0.0, lo))
        if cover <= 0:
            return (f"the hand's pads do not reach the plate's side held in its plane: on "
                    f"the table the hand's lowest point must be {clr:g} above it, which "
                    f"puts the pad {-cover:g} above a {T:g} thick plate (pick it from "
                    f"above, or hold the part off the table)")
        height[side], band[side] = float(z0), float(cover)
    return PlaneReach(height, band)


def band_support(a: FloatArray, b: FloatArray, lo: float, hi: float) -> float:
    """The largest ``a`` over the segments whose coordinates run from ``(a[:, 0], b[:,
    0])`` to ``(a[:, 1], b[:, 1])``, clipped to ``lo <= b <= hi`` (``-inf`` where none
    enters the band): exact, a linear function's largest value on a segment in a band
    being at an end of the clipped segment."""
    if hi < lo:
        return -math.inf
    b0, b1 = b[:, 0], b[:, 1]
    db = b1 - b0
    flat = db == 0
    with np.errstate(divide="ignore", invalid="ignore"):
        s_lo = np.where(flat, -np.inf, (lo - b0) / db)
        s_hi = np.where(flat, np.inf, (hi - b0) / db)
    first, last = np.minimum(s_lo, s_hi), np.maximum(s_lo, s_hi)
    t0 = np.where(flat, 0.0, np.clip(first, 0.0, 1.0))
    t1 = np.where(flat, 1.0, np.clip(last, 0.0, 1.0))
    inside = np.where(flat, (b0 >= lo) & (b0 <= hi), (first <= 1.0) & (last >= 0.0))
    if not np.any(inside):
        return -math.inf
    a0, a1 = a[inside, 0], a[inside, 1]
    ends = np.maximum(a0 + t0[inside] * (a1 - a0), a0 + t1[inside] * (a1 - a0))
    return float(ends.max())


@dataclass(frozen=True)
class _Band:
    """A hand box's band along ``n`` relative to the strip's centre ``c`` (``lo``,
    ``hi``), the finger it belongs to (``+1`` pad A, ``-1`` pad B, 0 the palm), its
    least ``y`` behind its pad's face (``y0``) and the gap it keeps."""

    lo: float
    hi: float
    finger: int
    y0: float
    #: the gap kept between the box and the material (0: touching is allowed)
    gap: float


def _bands(hand: ParallelHand, scene: Scene, side: int, height: float,
           pad: float) -> list[_Band]:
    """Every band a box of the hand sweeps along ``n`` (relative to ``c``), on the way in
    and while closing, for the boxes that reach the plate's thickness (within the
    clearance); a finger box behind its pad's face without the strip itself."""
    T, clr, far = scene.thickness, scene.clearance, scene.approach
    zc = sum(hand.pad_span) / 2
    out = []
    for boxes, finger in ((hand.palm, 0), (hand.finger, 1), (hand.finger, -1)):
        for box in boxes:
            x0, x1 = _x_range(box, finger == -1)
            z_lo, z_hi = sorted((height - side * x0, height - side * x1))
            if z_lo > T + clr or z_hi < -clr:
                continue                      # above or below the plate
            corners = box.corners()
            q = side * (zc - corners[:, 2])  # along n from c
            lo, hi = float(q.min()), float(q.max())
            # coming in along -side n from `far` away: the band grows on the hand's side
            lo, hi = (lo, hi + far) if side > 0 else (lo - far, hi)
            y0 = float(corners[:, 1].min())
            if finger and y0 >= -STRIP_TOL * max(1.0, float(np.abs(corners).max())):
                # behind the face: the strip holds no material past the stop, and the
                # box may touch what lies flush with the pad's face (no overlap)
                for a, b in ((lo, -pad / 2), (pad / 2, hi)):
                    if b > a:
                        out.append(_Band(a, b, finger, max(y0, 0.0), 0.0))
            else:
                out.append(_Band(lo - clr, hi + clr, finger, y0, clr))
    return out


def _cell_clear(rel: FloatArray, theta: tuple[float, float], offset: tuple[float, float],
                bands: list[_Band], pad: float, rho: float) -> bool:
    """Whether every pose of the cell is clear (the module's docstring's bound)."""
    tm = (theta[0] + theta[1]) / 2
    d = rho * (theta[1] - theta[0]) / 2
    u = np.array([math.cos(tm), math.sin(tm)])
    n = np.array([-u[1], u[0]])
    a, b = rel @ u, rel @ n                    # (E, 2) along u and n at the middle angle
    c0, c1 = offset
    # the band every strip of the cell holds: each pad's stop is at least its support
    core = (c1 - pad / 2 + d, c0 + pad / 2 - d)
    stop = {f: band_support(f * a, b, *core) - d for f in (1, -1)}
    for band in bands:
        lo, hi = c0 + band.lo - d, c1 + band.hi + d
        if band.finger == 0:
            if band_support(a, b, lo, hi) > -math.inf:
                return False
            continue
        if not math.isfinite(stop[band.finger]):
            return False
        if band_support(band.finger * a, b, lo, hi) + d + band.gap > \
                stop[band.finger] + band.y0:
            return False
    return True


@dataclass(frozen=True)
class PlaneCut:
    """A jaw box cut to where the hand held in the plane is clear: its ``theta`` and
    ``offset`` ranges and the ``side`` the hand lies on."""

    theta: tuple[float, float]
    offset: tuple[float, float]
    side: int


def _largest_rectangle(ok: np.ndarray, dt: float, dc: float, radius: float
                       ) -> tuple[int, int, int, int] | None:
    """The rectangle of True cells ``(i0, i1, j0, j1)`` (inclusive; ``i`` along theta)
    of the largest jaw measure ``min(cells_c dc, cells_t dt radius)``, or None."""
    best, where = 0.0, None
    K, M = ok.shape
    for i0 in range(K):
        run = np.ones(M, bool)
        for i1 in range(i0, K):
            run &= ok[i1]
            if not run.any():
                break
            j = 0
            while j < M:
                if not run[j]:
                    j += 1
                    continue
                j1 = j
                while j1 + 1 < M and run[j1 + 1]:
                    j1 += 1
                score = min((j1 - j + 1) * dc, (i1 - i0 + 1) * dt * radius)
                if score > best:
                    best, where = score, (i0, i1, j, j1)
                j = j1 + 1
    return where


def plane_cut(polygon: Polygon, hand: ParallelHand, scene: Scene, reach: PlaneReach,
              theta: tuple[float, float], offset: tuple[float, float], pad: float
              ) -> PlaneCut | None:
    """The box ``theta x offset`` cut to where every pose's pick in the plane is clear,
    on the side whose cut measures more (the module's docstring), or None."""
    ring = _grip_edges(polygon, None)
    rel = np.stack([polygon.starts[ring] - polygon.centroid,
                    polygon.ends[ring] - polygon.centroid], axis=1)   # (E, 2 ends, 2)
    rho = float(np.linalg.norm(rel.reshape(-1, 2), axis=1).max())
    radius = polygon.radius
    best: tuple[float, PlaneCut] | None = None
    for side in (1, -1):
        bands = _bands(hand, scene, side, reach.height[side], pad)

        def clear(t: tuple[float, float], c: tuple[float, float],
                  bands: list[_Band] = bands) -> bool:
            return _cell_clear(rel, t, c, bands, pad, rho)

        if clear(theta, offset):
            cut = PlaneCut(theta, offset, side)
        else:
            K = PLANE_CELLS
            ts = np.linspace(theta[0], theta[1], K + 1)
            cs = np.linspace(offset[0], offset[1], K + 1)
            ok = np.array([[clear((ts[i], ts[i + 1]), (cs[j], cs[j + 1])) for j in range(K)]
                           for i in range(K)])
            rect = _largest_rectangle(ok, ts[1] - ts[0], cs[1] - cs[0], radius)
            if rect is None:
                continue
            i0, i1, j0, j1 = rect
            cut = PlaneCut((float(ts[i0]), float(ts[i1 + 1])),
                           (float(cs[j0]), float(cs[j1 + 1])), side)
        score = min(cut.offset[1] - cut.offset[0], (cut.theta[1] - cut.theta[0]) * radius)
        if best is None or score > best[0]:
            best = (score, cut)
    return None if best is None else best[1]


#: Held in the plane, the jaw's search finds at most this many times ``top`` boxes while
#: the cuts drop some.
PLANE_ASK = 4


def plane_plans(polygon: Polygon, jaw: Any, reach: PlaneReach, top: int, margin: float,
                search: Callable[..., list[Any]]) -> list[Any]:
    """The jaw's ``top`` best boxes held in the plane, best first: each box the search
    finds (``search(keep, most)``: the jaw's boxes of external grips, each made by
    ``keep``, until ``top`` are kept or ``most`` found) cut by :func:`plane_cut` and
    re-centred (``JawPlan.cut_to``: its contacts at the cut box's centre pose), or left
    out where no pose is proved clear; at most :data:`PLANE_ASK` times ``top`` boxes are
    found."""

    def keep(p: Any) -> Any:
        cut = plane_cut(polygon, jaw.hand, jaw.scene, reach, p.theta, p.offset,
                        jaw.pad_width)
        return None if cut is None else p.cut_to(polygon, cut.theta, cut.offset, margin,
                                                 cut.side)

    out = search(keep, PLANE_ASK * top)
    out.sort(key=lambda p: -p.measure)
    return out[:top]


def plane_pick_dict(plan: Any, reach: PlaneReach) -> dict[str, Any]:
    """The pick of a box's centre pose held in the plane: the tool frame's pose, the
    opening it comes in at, the approach and the retreat (part frame, the part's units);
    every pose of the box is collision free (the module's docstring)."""
    from ...io.moveit import jaw_tool_pose, quaternion

    hand, scene = plan.jaw.hand, plan.jaw.scene
    side = plan.side
    theta, offset = plan.centre
    where, axes = jaw_tool_pose(plan.centroid, theta, offset, plan.stops,
                                reach.height[side], side, sum(hand.pad_span) / 2)
    approach = axes[:, 2]
    return {"pose": {"position": [float(v) for v in where],
                     "orientation": list(quaternion(axes)), "frame": "part"},
            "pre_grasp_opening": hand.stroke[1], "held": "in_plane", "side": side,
            **scene.motions(approach, -approach),
            "collision_free": True, "contact_height": reach.contact_height[side]}
