"""The hand model of section 8.2: chopstick fingers in a circular workspace.

Fingers are discs of radius ``finger_radius`` perpendicular to the plane (the
paper's chop sticks).  A contact at point ``P`` of an edge with outward normal ``n`` is
*feasible* when

* the fingertip centre ``P + rho n`` lies inside the workspace disc, and
* the fingertip disc touching the edge at ``P`` does not overlap the part anywhere
  else: its centre is at least ``rho`` from every other edge (this is what rules out
  narrow slots, small holes and the insides of reflex corners).

:meth:`Hand.feasible_intervals` returns, per edge, the arc-length intervals of feasible
contacts, computed exactly: the set of centres within ``rho`` of a segment is a
capsule, and a line meets a capsule in one interval.
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

    def __post_init__(self) -> None:
        rho = check_scalar(self.finger_radius, "finger_radius", nonnegative=True)
        object.__setattr__(self, "finger_radius", rho)
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
            boxes = shapely.box(np.minimum(c0, c0 + d * L[:, None])[:, 0] - rho,
                                np.minimum(c0, c0 + d * L[:, None])[:, 1] - rho,
                                np.maximum(c0, c0 + d * L[:, None])[:, 0] + rho,
                                np.maximum(c0, c0 + d * L[:, None])[:, 1] + rho)
            segs = shapely.linestrings(np.stack([polygon.starts, polygon.ends], axis=1))
            tree = shapely.STRtree(segs)
            ei, gj = tree.query(boxes, predicate="intersects")
            keep = (ei != gj) & polygon.usable[ei]
            ei, gj = ei[keep], gj[keep]
            r = rho * (1 - TOL)
            cc, dd = c0[ei], d[ei]
            s0, s1 = polygon.starts[gj], polygon.ends[gj]
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
            lo_s = np.full(len(ei), -np.inf)
            hi_s = np.full(len(ei), np.inf)
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
            lo_f, hi_f = los.min(axis=0), his.max(axis=0)
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
