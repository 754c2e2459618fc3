r"""Independent regions of contact for two soft fingers on a solid (issue 33: the 3-D
analogue of the paper's section 7 for the primitive its conclusion names first).

Two soft fingers at ``p_1`` and ``p_2`` are in force closure exactly when the segment
joining them lies strictly inside both friction cones
(:func:`~fcgrasp.spatial.closure.two_soft_closure`).  With each finger on a planar facet
(inward normals ``n_1``, ``n_2``), the condition is that ``p_2 - p_1`` lies in the convex
cone ``C`` of directions within ``alpha = atan(mu) - margin`` of ``n_1`` and of ``-n_2``.
For convex regions ``R_1`` and ``R_2``, every pair of points is in force closure exactly
when every pair of their **corners** is: ``R_2 - R_1`` is the convex hull of the corners'
differences and ``C`` is convex.

**The regions.**  Each region is a regular octagon of circumradius ``r`` (its inscribed
radius is ``r cos(pi / 8)``) inside a convex piece of its facet, both octagons the same
size, turned alike: their first corners point along one direction (the first facet's
first axis, projected into the second facet), so that on opposite parallel faces they
are mirror images.  :func:`soft_pair_regions` finds the largest ``r`` and the octagons'
centres by one second-order cone program (Clarabel) in ``(c_1, c_2, r)``: the corners
inside the pieces (linear), and each of the 64 corner differences in both cones
(:math:`\|x\| \cos\alpha \le a \cdot x`, a second-order cone constraint of an affine
function).  The program is exact for this family of regions: no larger pair of such
octagons holds.  Measure: ``r`` (the paper's "largest smallest region", for discs of
contact).

:func:`soft_pair_plans` searches every pair of facets' convex pieces whose cones can
meet (their normals within ``2 alpha`` of opposite), largest bound first (an octagon
of circumradius ``r`` holds a disc of radius ``r cos(pi / 8)``, so ``r`` is at most the
pieces' inscribed radius over ``cos(pi / 8)``), and stops when the next bound cannot
enter the top ``top``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core._checks import FloatArray, check_int, check_mu_scalar, check_scalar
from ..core.tolerances import CONE_PROGRAM_TOL, INRADIUS_STEP, TOL
from ._program import solve_linear
from .solid import Facet, Solid

__all__ = ["SoftPairPlan", "soft_pair_regions", "soft_pair_plans", "OCTAGON",
           "DEFAULT_MARGIN_DEG"]

#: Corners of the unit regular octagon (first along the first axis).
OCTAGON = np.array([[math.cos(k * math.pi / 4), math.sin(k * math.pi / 4)] for k in range(8)])

#: Default safety margin inside the friction cones, degrees (as in the plane).
DEFAULT_MARGIN_DEG = 0.5


@dataclass(frozen=True)
class SoftPairPlan:
    """Regions of two soft fingers: ``facets`` (the two facets' indices), ``pieces``
    (their convex pieces' indices), ``radius`` (the octagons' circumradius),
    ``centers`` (2, 3), ``regions`` (2, 8, 3: each octagon's corners in 3-D),
    inward ``normals`` (2, 3), ``mu`` and ``margin`` (degrees)."""

    facets: tuple[int, int]
    pieces: tuple[int, int]
    radius: float
    centers: FloatArray = field(repr=False)
    regions: FloatArray = field(repr=False)
    normals: FloatArray = field(repr=False)
    mu: float = 0.0
    margin: float = DEFAULT_MARGIN_DEG

    @property
    def min_length(self) -> float:
        """The measure the plans are ranked by: the octagons' circumradius."""
        return self.radius

    def to_dict(self) -> dict[str, Any]:
        return {"facets": list(self.facets), "pieces": list(self.pieces),
                "radius": self.radius, "centers": self.centers.tolist(),
                "regions": self.regions.tolist(), "normals": self.normals.tolist(),
                "mu": self.mu, "margin_deg": self.margin, "contact_type": "soft"}


def _halfplanes(piece: Any) -> tuple[FloatArray, FloatArray]:
    """``E x <= h`` for a convex shapely polygon (counter-clockwise made)."""
    from shapely.geometry.polygon import orient

    ring = np.asarray(orient(piece, 1.0).exterior.coords)[:-1]
    d = np.roll(ring, -1, axis=0) - ring
    length = np.hypot(d[:, 0], d[:, 1])
    keep = length > 0
    ring, d, length = ring[keep], d[keep], length[keep]
    E = np.c_[d[:, 1], -d[:, 0]] / length[:, None]                # outward
    return E, np.einsum("ij,ij->i", E, ring)


def _octagon_axes(f1: Facet, f2: Facet) -> tuple[FloatArray, FloatArray]:
    """Each facet's octagon corners as 3-D unit vectors (8, 3), turned alike."""
    u = f1.axes[0]
    out = []
    for f in (f1, f2):
        v = u - (u @ f.normal) * f.normal
        nv = float(np.linalg.norm(v))
        v = v / nv if nv > TOL else f.axes[0]         # the direction lies in the plane
        w = np.cross(f.normal, v)
        out.append(np.outer(OCTAGON[:, 0], v) + np.outer(OCTAGON[:, 1], w))
    return out[0], out[1]


def soft_pair_regions(solid: Solid, facets: Any, mu: Any,
                      margin: Any = DEFAULT_MARGIN_DEG, pieces: Any = (0, 0)
                      ) -> SoftPairPlan | None:
    """The largest octagon regions (module docstring) of two soft fingers on two
    facets of ``solid`` (their convex pieces ``pieces``), or None when no regions hold.

    >>> from fcgrasp.spatial.solid import demo_solid
    >>> box = demo_solid("box")                         # 40 x 20 x 10 mm
    >>> x = [f.index for f in box.facets if abs(f.normal[0]) > 0.5]
    >>> round(soft_pair_regions(box, x, mu=0.3).radius, 4)   # the 10 mm height
    5.0
    """
    import clarabel

    if not isinstance(solid, Solid):
        raise TypeError(f"solid must be a fcgrasp Solid, got {type(solid).__name__}")
    mu_v = check_mu_scalar(mu, "mu")
    margin_v = check_scalar(margin, "margin", nonnegative=True)
    try:
        i, j = (int(f) for f in facets)
        a, b = (int(p) for p in pieces)
    except (TypeError, ValueError):
        raise ValueError(f"facets and pieces must be two indices each, got {facets!r}, "
                         f"{pieces!r}") from None
    n = len(solid.facets)
    if not (0 <= i < n and 0 <= j < n) or i == j:
        raise ValueError(f"facets must be two different facets in [0, {n}), got {facets!r}")
    f1, f2 = solid.facets[i], solid.facets[j]
    if not (0 <= a < len(f1.pieces) and 0 <= b < len(f2.pieces)):
        raise ValueError(f"pieces must index the facets' convex pieces, got {pieces!r}")
    alpha = math.atan(mu_v) - math.radians(margin_v)
    if alpha <= 0:
        return None
    Q1, Q2 = _octagon_axes(f1, f2)
    # variables z = (c1 (2), c2 (2), r); the corners p = origin + c A + r Q
    rows: list[FloatArray] = []
    rhs: list[float] = []
    lin = 0
    for f, piece, col, Q in ((f1, f1.pieces[a], 0, Q1), (f2, f2.pieces[b], 2, Q2)):
        E, h = _halfplanes(piece)
        q2 = Q @ f.axes.T                                         # corners in 2-D (8, 2)
        for e, hh in zip(E, h, strict=True):
            for q in q2:                                           # e.(c + r q) <= h
                row = np.zeros(5)
                row[col:col + 2] = e
                row[4] = e @ q
                rows.append(row)
                rhs.append(float(hh))
                lin += 1
    cones: list[Any] = [clarabel.NonnegativeConeT(lin)]
    base = f2.origin - f1.origin
    for axis in (f1.normal, -f2.normal):
        for q1 in Q1:
            for q2 in Q2:
                # x = base + c2 A2 - c1 A1 + r (q2 - q1); s = (a.x / cos(alpha), x) in SOC
                M = np.zeros((3, 5))
                M[:, 0:2] = -f1.axes.T
                M[:, 2:4] = f2.axes.T
                M[:, 4] = q2 - q1
                rows.append(-(axis @ M) / math.cos(alpha))
                rhs.append(float(axis @ base) / math.cos(alpha))
                for k in range(3):
                    rows.append(-M[k])
                    rhs.append(float(base[k]))
                cones.append(clarabel.SecondOrderConeT(4))
    q = np.zeros(5)
    q[4] = -1.0
    sol = solve_linear(q, rows, rhs, cones)
    if not str(sol.status).startswith("Solved"):
        return None
    z = np.asarray(sol.x, float)
    c1, c2 = f1.to_3d(z[0:2]), f2.to_3d(z[2:4])
    r = _certified_radius(c1, c2, Q1, Q2, (f1, f2), (f1.pieces[a], f2.pieces[b]),
                          alpha, float(z[4]))
    if r <= CONE_PROGRAM_TOL * solid.size:
        return None
    regions = np.stack([c1 + r * Q1, c2 + r * Q2])
    return SoftPairPlan((i, j), (a, b), r, np.stack([c1, c2]), regions,
                        np.stack([f1.normal, f2.normal]), mu_v, margin_v)


def _holds(c1: FloatArray, c2: FloatArray, Q1: FloatArray, Q2: FloatArray,
           facets: tuple[Facet, Facet], pieces: tuple[Any, Any], alpha: float,
           r: float) -> bool:
    """The octagons of radius ``r`` about ``c1`` and ``c2``, checked in floats: every
    corner difference within ``alpha`` of ``n_1`` and of ``-n_2`` (strictly), every
    corner inside its piece."""
    d = (c2 + r * Q2)[None, :, :] - (c1 + r * Q1)[:, None, :]          # (8, 8, 3)
    length = np.linalg.norm(d, axis=-1)
    for axis in (facets[0].normal, -facets[1].normal):
        if not np.all(d @ axis > math.cos(alpha) * length):
            return False
    for f, piece, c, Q in ((facets[0], pieces[0], c1, Q1), (facets[1], pieces[1], c2, Q2)):
        E, h = _halfplanes(piece)
        if not np.all(f.to_2d(c + r * Q) @ E.T <= h):
            return False
    return True


def _certified_radius(c1: FloatArray, c2: FloatArray, Q1: FloatArray, Q2: FloatArray,
                      facets: tuple[Facet, Facet], pieces: tuple[Any, Any], alpha: float,
                      r: float) -> float:
    """The program's radius, or the largest below it that :func:`_holds` confirms (an
    interior-point solution may sit a rounding outside a constraint): bisection."""
    if _holds(c1, c2, Q1, Q2, facets, pieces, alpha, r):
        return r
    lo, hi = 0.0, r
    if not _holds(c1, c2, Q1, Q2, facets, pieces, alpha, lo):
        return 0.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if _holds(c1, c2, Q1, Q2, facets, pieces, alpha, mid):
            lo = mid
        else:
            hi = mid
    return lo


def _inradius(piece: Any) -> float:
    """The radius of the largest disc inside a convex piece: an octagon of circumradius
    ``r`` holds the disc of radius ``r cos(pi / 8)``, so ``r <= inradius / cos(pi/8)``."""
    from shapely import maximum_inscribed_circle

    # shapely finds the centre to within ``tolerance``: the radius is at most that more
    lo_x, lo_y, hi_x, hi_y = piece.bounds
    tol = INRADIUS_STEP * max(hi_x - lo_x, hi_y - lo_y)
    return float(maximum_inscribed_circle(piece, tol).length) + tol


def soft_pair_plans(solid: Solid, mu: Any, top: int | None = 10,
                    margin: Any = DEFAULT_MARGIN_DEG) -> list[SoftPairPlan]:
    """The best regions of two soft fingers on ``solid``, largest first (module
    docstring): every pair of convex pieces whose cones can meet, the largest bound first,
    until the next bound cannot enter the top ``top`` (None: every pair).

    >>> from fcgrasp.spatial.solid import demo_solid
    >>> [round(p.radius, 4) for p in soft_pair_plans(demo_solid("box"), mu=0.3, top=3)]
    [5.0, 2.9051, 1.4526]
    """
    if not isinstance(solid, Solid):
        raise TypeError(f"solid must be a fcgrasp Solid, got {type(solid).__name__}")
    mu_v = check_mu_scalar(mu, "mu")
    margin_v = check_scalar(margin, "margin", nonnegative=True)
    if top is not None:
        top = check_int(top, "top", minimum=1)
    alpha = math.atan(mu_v) - math.radians(margin_v)
    if alpha <= 0:
        return []
    normals = np.array([f.normal for f in solid.facets])
    # the cones about n_1 and -n_2 meet only when the normals are within 2 alpha of
    # opposite (one batch over every facet pair)
    cos = -(normals @ normals.T)
    ii, jj = np.nonzero(np.triu(cos > math.cos(min(2 * alpha, math.pi)), 1))
    cands = []
    for i, j in zip(ii.tolist(), jj.tolist(), strict=True):
        for a, pa in enumerate(solid.facets[i].pieces):
            for b, pb in enumerate(solid.facets[j].pieces):
                bound = min(_inradius(pa), _inradius(pb)) / math.cos(math.pi / 8)
                cands.append((bound, i, j, a, b))
    cands.sort(key=lambda c: -c[0])
    plans: list[SoftPairPlan] = []
    for bound, i, j, a, b in cands:
        if top is not None and len(plans) >= top and bound <= plans[top - 1].radius:
            break
        got = soft_pair_regions(solid, (i, j), mu_v, margin_v, (a, b))
        if got is not None:
            plans.append(got)
            plans.sort(key=lambda p: (-p.radius, p.facets, p.pieces))
    return plans if top is None else plans[:top]
