"""The hand model of section 8.2: chopstick fingers in a circular workspace.

Fingers are discs of radius ``finger_radius`` perpendicular to the plane (the
paper's chop sticks).  A contact at point ``P`` of an edge with outward normal ``n`` is
*feasible* when

* the fingertip centre ``P + rho n`` lies inside the workspace disc, and
* the fingertip disc touching the edge at ``P`` does not overlap the part anywhere
  else: its centre is at least ``rho`` from every other edge (this is what rules out
  narrow slots, small holes and the insides of reflex corners);
* with a ``finger_length`` (a finger held in the plane: its body a ``2 rho`` wide strip
  behind the tip, along the outward normal), every centre of the segment from
  ``P + rho n`` to ``P + (rho + finger_length) n`` is at least ``rho`` from every other
  edge: the body, the capsule of that segment, meets the part nowhere else.

:meth:`Hand.feasible_intervals` returns, per edge, the arc-length intervals of feasible
contacts, computed exactly: the set of centres within ``rho`` of a segment is a
capsule, and a line meets a capsule in one interval; a body's segment comes within
``rho`` of an edge ``g`` where its tip centre lies in ``g``'s capsule swept back along
``-n`` by the length, a convex set whose meeting with the line is the span of its
meetings with the capsules of the parallelogram's four sides (``g``, ``g`` moved back
and the two segments its ends sweep).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import shapely

from ..core._checks import check_array, check_scalar
from ..core.tolerances import TOL
from .polygon import Polygon

__all__ = ["Hand"]


def _roots_inside(c0: np.ndarray, d: np.ndarray, q: np.ndarray, r: float
                  ) -> tuple[np.ndarray, np.ndarray]:
    """t-interval where |c0 + t d - q| < r (d unit); empty as (inf, -inf)."""
    rel = c0 - q
    b = np.sum(rel * d, axis=-1)
    c = np.sum(rel * rel, axis=-1) - r * r
    disc = b * b - c
    ok = disc > 0
    s = np.sqrt(np.where(ok, disc, 0.0))
    return np.where(ok, -b - s, np.inf), np.where(ok, -b + s, -np.inf)


def _capsule_interval(cc: np.ndarray, dd: np.ndarray, s0: np.ndarray, s1: np.ndarray,
                      r: float) -> tuple[np.ndarray, np.ndarray]:
    """Per row, the t-interval where ``cc + t dd`` (``dd`` unit) lies within ``r`` of the
    segment ``s0 s1`` (its capsule: the two end discs and the strip between), empty as
    ``(inf, -inf)``."""
    lo_a, hi_a = _roots_inside(cc, dd, s0, r)
    lo_b, hi_b = _roots_inside(cc, dd, s1, r)
    seg = s1 - s0
    sl = np.hypot(seg[:, 0], seg[:, 1])
    u = seg / np.where(sl > 0, sl, 1.0)[:, None]
    # strip: 0 < (c - s0).u < |S| and |(c - s0) x u| < r, linear in t
    rel = cc - s0
    a_par, b_par = np.sum(rel * u, axis=1), np.sum(dd * u, axis=1)
    a_perp = rel[:, 0] * u[:, 1] - rel[:, 1] * u[:, 0]
    b_perp = dd[:, 0] * u[:, 1] - dd[:, 1] * u[:, 0]
    lo_s = np.full(len(cc), -np.inf)
    hi_s = np.full(len(cc), np.inf)
    for a_, b_, lo_v, hi_v in ((a_par, b_par, 0.0, sl), (a_perp, b_perp, -r, r)):
        with np.errstate(divide="ignore", invalid="ignore"):
            t1 = (lo_v - a_) / b_
            t2 = (hi_v - a_) / b_
        flat = b_ == 0
        inside_flat = (a_ > lo_v) & (a_ < hi_v)
        lo_s = np.where(flat, np.where(inside_flat, lo_s, np.inf),
                        np.maximum(lo_s, np.minimum(t1, t2)))
        hi_s = np.where(flat, np.where(inside_flat, hi_s, -np.inf),
                        np.minimum(hi_s, np.maximum(t1, t2)))
    lo_s = np.where(sl > 0, lo_s, np.inf)
    los = np.stack([lo_a, lo_b, np.where(lo_s < hi_s, lo_s, np.inf)])
    his = np.stack([hi_a, hi_b, np.where(lo_s < hi_s, hi_s, -np.inf)])
    return los.min(axis=0), his.max(axis=0)


@dataclass(frozen=True)
class Hand:
    """Circular workspace and finger radius (section 8.2).

    Parameters
    ----------
    workspace : (cx, cy, r), optional
        Fingertip centres must lie in this disc; None for no limit.
    finger_radius : float
        Radius ``rho >= 0`` of the fingertips.
    """

    workspace: Any = None
    finger_radius: float = 0.0
    #: a finger held in the plane: its body's length behind the tip centre, along the
    #: contact's outward normal (0: a chopstick from above, its body off the plane)
    finger_length: float = 0.0

    def __post_init__(self) -> None:
        rho = check_scalar(self.finger_radius, "finger_radius", nonnegative=True)
        object.__setattr__(self, "finger_radius", rho)
        body = check_scalar(self.finger_length, "finger_length", nonnegative=True)
        if body > 0 and rho <= 0:
            raise ValueError(f"finger_length needs a finger_radius > 0 (a body as wide as "
                             f"the tip), got finger_length={body:g}")
        object.__setattr__(self, "finger_length", body)
        if self.workspace is not None:
            ws = check_array(self.workspace, "workspace", last=3)
            if ws.ndim != 1 or not ws[2] > 0:
                raise ValueError(f"workspace must be (cx, cy, r) with r > 0, got "
                                 f"{np.asarray(self.workspace).tolist()}")
            object.__setattr__(self, "workspace", tuple(float(x) for x in ws))

    def feasible_intervals(self, polygon: Polygon, min_length: float = 0.0
                           ) -> list[list[tuple[float, float]]]:
        """Per edge, the sorted arc-length intervals ``(t0, t1)`` of feasible contacts."""
        E = polygon.n_edges
        L = polygon.lengths
        rho = self.finger_radius
        out: list[list[tuple[float, float]]] = []
        c0 = polygon.starts + rho * polygon.normals
        d = polygon.tangents
        forbidden: list[list[tuple[float, float]]] = [[] for _ in range(E)]
        if rho > 0:
            body = self.finger_length
            far = c0 + body * polygon.normals          # the body's far end's centres
            ends = c0 + d * L[:, None]
            lo_xy = np.minimum.reduce([c0, ends, far, far + d * L[:, None]]) - rho
            hi_xy = np.maximum.reduce([c0, ends, far, far + d * L[:, None]]) + rho
            boxes = shapely.box(lo_xy[:, 0], lo_xy[:, 1], hi_xy[:, 0], hi_xy[:, 1])
            segs = shapely.linestrings(np.stack([polygon.starts, polygon.ends], axis=1))
            tree = shapely.STRtree(segs)
            ei, gj = tree.query(boxes, predicate="intersects")
            keep = (ei != gj) & polygon.usable[ei]
            ei, gj = ei[keep], gj[keep]
            r = rho * (1 - TOL)
            cc, dd = c0[ei], d[ei]
            s0, s1 = polygon.starts[gj], polygon.ends[gj]
            lo_f, hi_f = _capsule_interval(cc, dd, s0, s1, r)
            if body > 0:
                # the capsule of g swept back along -n: the sides of its parallelogram
                back = -body * polygon.normals[ei]
                for a_, b_ in ((s0 + back, s1 + back), (s0, s0 + back), (s1, s1 + back)):
                    lo_k, hi_k = _capsule_interval(cc, dd, a_, b_, r)
                    hit = lo_k < hi_k
                    lo_f = np.where(hit, np.minimum(lo_f, lo_k), lo_f)
                    hi_f = np.where(hit, np.maximum(hi_f, hi_k), hi_f)
            for e, a_, b_ in zip(ei, lo_f, hi_f, strict=True):
                if a_ < b_:
                    forbidden[int(e)].append((float(a_), float(b_)))
        for e in range(E):
            if not polygon.usable[e]:
                out.append([])
                continue
            lo, hi = 0.0, float(L[e])
            if self.workspace is not None:
                cx, cy, R = self.workspace
                a_, b_ = _roots_inside(c0[e], d[e], np.array([cx, cy]), R)
                lo, hi = max(lo, float(a_)), min(hi, float(b_))
            ivs = [(lo, hi)] if hi > lo else []
            for fa, fb in sorted(forbidden[e]):
                nxt = []
                for a_, b_ in ivs:
                    if fb <= a_ or fa >= b_:
                        nxt.append((a_, b_))
                        continue
                    if fa > a_:
                        nxt.append((a_, fa))
                    if fb < b_:
                        nxt.append((fb, b_))
                ivs = nxt
            out.append([(a_, b_) for a_, b_ in ivs if b_ - a_ > max(min_length, 0.0)])
        return out
