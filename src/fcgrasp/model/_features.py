"""The features fingers touch (edges, convex vertices for soft fingers, gravity at the
centroid) and the field-of-view constraint between two of them (part of
:mod:`fcgrasp.model.graspsets`, section 6)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from ..core._checks import FloatArray, check_direction
from ..core._geom import cross2 as _cross
from ..core._geom import direction as _dir
from ..core.sectors import (
    pair_arc,
)
from ..core.tolerances import ANGLE_CAP_GAP, TINY
from .polygon import Polygon

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


FORCE_DIRECTION = "force-direction"
FIELD_OF_VIEW = "field-of-view"

#: A soft finger's arc of force directions is capped below a half-plane (conservative:
#: a grasp that holds with the smaller arc holds with the larger one).
SOFT_HALF_ANGLE_CAP = np.pi / 2 - ANGLE_CAP_GAP





# ----------------------------------------------------------------------------- features


class Vertex(int):
    """Marks a polygon vertex (the start of edge ``k``) as a soft-finger feature."""

    def __repr__(self) -> str:
        return f"Vertex({int(self)})"


@dataclass(frozen=True)
class Feature:
    """Where one finger goes and which force directions it can apply.

    Attributes
    ----------
    kind : {"edge", "vertex", "gravity"}
    index : int or None
        Edge index, vertex index (start of that edge) or None for gravity.
    a, b : ndarray, shape (2,)
        The segment the contact point ranges over (``a == b`` for a point).
    center, half : float
        Arc of force directions (radians): ``center +- half``.
    """

    kind: str
    index: int | None
    a: FloatArray
    b: FloatArray
    center: float
    half: float

    @property
    def direction(self) -> FloatArray:
        """Central force direction (unit)."""
        return _dir(self.center)

    @property
    def length(self) -> float:
        return float(np.hypot(*(self.b - self.a)))

    def point_at(self, t: Any) -> FloatArray:
        t = np.asarray(t, dtype=float)
        return cast("FloatArray", self.a + t[..., None] * (self.b - self.a))

    def param_of(self, p: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Parameter along the segment and distance from its line, for points ``p``."""
        d = self.b - self.a
        ln2 = float(d @ d)
        rel = p - self.a
        if ln2 == 0.0:
            return np.zeros(p.shape[:-1]), np.hypot(rel[..., 0], rel[..., 1])
        t = (rel @ d) / ln2
        off = np.abs(_cross(d, rel)) / np.sqrt(ln2)
        return t, off

    def label(self) -> str:
        return {"edge": f"e{self.index}", "vertex": f"v{self.index}", "gravity": "g"}[self.kind]


def edge_feature(poly: Polygon, i: int, mu: float = 0.0) -> Feature:
    n = poly.normals[i]
    return Feature("edge", int(i), poly.starts[i], poly.ends[i],
                   float(np.arctan2(-n[1], -n[0])), float(np.arctan(mu)))


def vertex_feature(poly: Polygon, k: int, mu: float) -> Feature:
    """Soft finger at the vertex that starts edge ``k``: the arc of directions covering the
    friction cones of both incident edges (capped below a half-plane)."""
    prev = poly.convex_corner(k)
    a1 = np.arctan2(-poly.normals[prev][1], -poly.normals[prev][0])
    a2 = np.arctan2(-poly.normals[k][1], -poly.normals[k][0])
    center, half_gap = pair_arc(a1, a2)
    half = min(float(half_gap) + float(np.arctan(mu)), SOFT_HALF_ANGLE_CAP)
    p = poly.starts[k]
    return Feature("vertex", int(k), p, p, float(center), float(half))


def gravity_feature(poly: Polygon, direction: ArrayLike = (0.0, -1.0)) -> Feature:
    g = check_direction(direction, "gravity")
    c = poly.centroid
    return Feature("gravity", None, c, c, float(np.arctan2(g[1], g[0])), 0.0)


def _fov_interval(fa: Feature, fb: Feature, k1: FloatArray, k2: FloatArray,
                  tol: float) -> tuple[float, float] | None:
    """Parameters of the points of ``fa`` inside ``fb (+) cone(k1, k2)``.

    ``cone(k1, k2)`` is the closed sector from ``k1`` counter-clockwise to ``k2``
    (narrower than pi).  The Minkowski sum of a segment and a cone is the intersection
    of the half-planes whose normals are the cone's outward facet normals and the
    segment's normals lying in the polar cone (definition 6.1, the field of view).
    """
    m1 = np.array([k1[1], -k1[0]])            # outward normal of the facet along k1
    m2 = np.array([-k2[1], k2[0]])            # outward normal of the facet along k2
    normals = [m1, m2]
    s = fb.b - fb.a
    if float(np.hypot(*s)) > 0:
        sp = np.array([s[1], -s[0]]) / np.hypot(*s)
        for m in (sp, -sp):
            if m @ k1 <= 0 and m @ k2 <= 0:
                normals.append(m)
    lo, hi = 0.0, 1.0
    a, d = fa.a, fa.b - fa.a
    for m in normals:
        h = max(float(m @ fb.a), float(m @ fb.b))
        num, den = h - float(m @ a), float(m @ d)
        if den == 0.0:
            if num < 0:
                return None
            continue
        t = num / den
        if den > 0:
            hi = min(hi, t)
        else:
            lo = max(lo, t)
    scale = max(fa.length, fb.length, float(np.hypot(*(fa.a - fb.a))), TINY)
    if hi < lo or (fa.length > 0 and (hi - lo) * fa.length <= tol * scale):
        return None
    return lo, hi


def _on_feature(f: Feature, p: FloatArray, tol_len: float) -> np.ndarray:
    t, off = f.param_of(p)
    ln = max(f.length, TINY)
    return (off <= tol_len) & (t >= -tol_len / ln) & (t <= 1 + tol_len / ln)
