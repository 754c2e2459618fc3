r"""Independent regions of contact for two soft fingers on a solid (the 3-D
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

:func:`facet_pair_plans` searches every pair of facets' convex pieces whose cones can
meet (their normals within ``2 alpha`` of opposite), best bound first, and stops when
the next bound cannot enter the top ``top``.  Three upper bounds on ``r``, batched over
all pairs at once: the pieces' inscribed circles over ``cos(pi / 8)`` (an octagon of
circumradius ``r`` holds a disc of radius ``r cos(pi / 8)``); each octagon's own fit in
its piece, ignoring the cones (closed form in a triangle, the width across an edge in
any piece); ``tan(alpha)`` times each piece's height above the other facet's plane.
A pair whose tightened bound comes first and whose pieces a direction of the cones'
dual separates from them (every difference of their points outside a cone:
:func:`~fcgrasp.spatial._pieces.separated`) holds no regions and is bounded by 0
without a program: on a plate with round holes, three in four pairs the search reaches.
The pieces come in rounds, widest first, so that a mesh's thousands of facets do not
make millions of pairs unless they must.  A pair whose tightened bound comes first is
solved by the fits themselves when they pass the float check (then they reach the
bound, so they are optimal: the common case on finely tessellated surfaces, where the
cones are wide against the facets), otherwise by the cone program.  Tested against the
cone program on every pair (the search before these bounds).
"""

from __future__ import annotations

import bisect
import heapq
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core._checks import FloatArray, IntArray, check_int, check_mu_scalar, check_scalar
from ..core.budget import cut_if_over
from ..core.tolerances import (
    CONE_PROGRAM_TOL,
    FIT_ROUNDING,
    ROUNDING_SHRINK,
    TOL,
)
from ._pieces import (
    Halfplanes,
    _fit,
    _halfplanes,
    _pair_bounds,
    _pairs,
    _piece_fit,
    _piece_table,
    _Pieces,
    _ring,
    _ring_halfplanes,
    _ring_widths,
    separated,
)
from ._program import solve_linear
from .alternatives import SolidPlan
from .solid import Facet, Solid

__all__ = ["OctagonPlan", "SoftPairPlan", "soft_pair_regions", "facet_pair_plans", "OCTAGON",
           "DEFAULT_MARGIN_DEG"]

#: Corners of the unit regular octagon (first along the first axis).
OCTAGON = np.array([[math.cos(k * math.pi / 4), math.sin(k * math.pi / 4)] for k in range(8)])

#: Default safety margin inside the friction cones, degrees (as in the plane).
DEFAULT_MARGIN_DEG = 0.5


@dataclass(frozen=True)
class OctagonPlan(SolidPlan):
    """Octagon regions of fingers on pieces of facets (what two soft fingers and three
    point fingers with friction share): ``facets`` (one facet's index per finger),
    ``pieces`` (their convex pieces' indices), ``radius`` (the octagons' circumradius:
    each finger anywhere in its octagon), ``centers`` (fingers, 3), ``regions``
    (fingers, 8, 3: each octagon's corners in 3-D), inward ``normals`` (fingers, 3),
    ``mu`` and ``margin`` (degrees)."""

    facets: tuple[int, ...]
    pieces: tuple[int, ...]
    radius: float
    centers: FloatArray = field(repr=False)
    regions: FloatArray = field(repr=False)
    normals: FloatArray = field(repr=False)
    mu: float = 0.0
    margin: float = DEFAULT_MARGIN_DEG
    similar: tuple[tuple[int, ...], ...] = field(default=(), repr=False, compare=False)

    def _octagon_dict(self, contact_type: str) -> dict[str, Any]:
        """The JSON both kinds of plan share (``similar`` added by :meth:`to_dict`)."""
        return {"facets": list(self.facets), "pieces": list(self.pieces),
                "radius": self.radius, "centers": self.centers.tolist(),
                "regions": self.regions.tolist(),
                # the JSON's normals point out of the part, as the planar reports' do
                "normals": (-self.normals).tolist(),
                "mu": self.mu, "margin_deg": self.margin, "contact_type": contact_type}


@dataclass(frozen=True)
class SoftPairPlan(OctagonPlan):
    """Regions of two soft fingers (:class:`OctagonPlan`: two facets, two octagons).
    ``radius`` is the smaller octagon's circumradius (the plans' measure, definition
    7.1's first level); ``radii`` both, the other grown as far as it holds (the second
    level: :func:`_second_level`)."""

    radii: tuple[float, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        out = self._octagon_dict("soft")
        out["radii"] = [float(v) for v in (self.radii or (self.radius, self.radius))]
        return self._with_similar(out)


def checked_cone(mu: Any, margin: Any, solid: Any = None) -> tuple[float, float, float]:
    """``(mu, margin, alpha)`` checked, ``alpha = atan(mu) - margin`` the half-angle of
    the friction cones narrowed by the margin (degrees) that every solid gripper plans
    in; ``solid``, when given, checked to be a :class:`~fcgrasp.spatial.solid.Solid`."""
    if solid is not None and not isinstance(solid, Solid):
        raise TypeError(f"solid must be a fcgrasp Solid, got {type(solid).__name__}")
    mu_v = check_mu_scalar(mu, "mu")
    margin_v = check_scalar(margin, "margin", nonnegative=True)
    return mu_v, margin_v, math.atan(mu_v) - math.radians(margin_v)


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
                      margin: Any = DEFAULT_MARGIN_DEG, pieces: Any = (0, 0),
                      leximin: bool = True) -> SoftPairPlan | None:
    """The largest octagon regions (module docstring) of two soft fingers on two
    facets of ``solid`` (their convex pieces ``pieces``), with ``leximin`` one octagon
    then grown as far as it holds (:func:`_second_level`), or None when no regions hold.

    >>> from fcgrasp.spatial.solid import demo_solid
    >>> box = demo_solid("box")                         # 40 x 20 x 10 mm
    >>> x = [f.index for f in box.facets if abs(f.normal[0]) > 0.5]
    >>> round(soft_pair_regions(box, x, mu=0.3).radius, 4)   # the 10 mm height
    5.0
    """

    mu_v, margin_v, alpha = checked_cone(mu, margin, solid)
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
    if alpha <= 0:
        return None
    got = _pair_program(solid, (i, j), (a, b), alpha,
                        (_halfplanes(f1.pieces[a]), _halfplanes(f2.pieces[b])))
    return None if got is None else _plan(solid, (i, j), (a, b), *got, mu_v, margin_v,
                                          grow=leximin)


def _plan(solid: Solid, facets: tuple[int, int], pieces: tuple[int, int], c1: FloatArray,
          c2: FloatArray, r: float, mu: float, margin: float, grow: bool = False
          ) -> SoftPairPlan:
    """The plan of the first level's octagons (radius ``r``); with ``grow``, the second
    level grown (:func:`_second_level`)."""
    r1 = r2 = r
    if grow:
        alpha = math.atan(mu) - math.radians(margin)
        c1, c2, (r1, r2) = _second_level(solid, facets, pieces, c1, c2, r, alpha)
    f1, f2 = solid.facets[facets[0]], solid.facets[facets[1]]
    Q1, Q2 = _octagon_axes(f1, f2)
    regions = np.stack([c1 + r1 * Q1, c2 + r2 * Q2])
    return SoftPairPlan(facets, pieces, r, np.stack([c1, c2]), regions,
                        np.stack([f1.normal, f2.normal]), mu, margin, radii=(r1, r2))


def _pair_program(solid: Solid, facets: tuple[int, int], pieces: tuple[int, int],
                  alpha: float, halfplanes: tuple[Halfplanes, Halfplanes]
                  ) -> tuple[FloatArray, FloatArray, float] | None:
    """The cone program of the module docstring for one pair of pieces: the octagons'
    centres (3-D) and certified circumradius, or None when no regions hold."""
    import clarabel

    f1, f2 = solid.facets[facets[0]], solid.facets[facets[1]]
    Q1, Q2 = _octagon_axes(f1, f2)
    # variables z = (c1 (2), c2 (2), r); the corners p = origin + c A + r Q
    rows, rhs = _piece_rows((f1, f2), (Q1, Q2), halfplanes)
    cones: list[Any] = [clarabel.NonnegativeConeT(len(rows))]
    base = f2.origin - f1.origin
    # x = base + c2 A2 - c1 A1 + r (q2 - q1)
    _cone_rows(f1, f2, alpha, [(base, q2 - q1) for q1 in Q1 for q2 in Q2], rows, rhs,
               cones)
    z = _largest_last(rows, rhs, cones)
    if z is None:
        return None
    c1, c2 = f1.to_3d(z[0:2]), f2.to_3d(z[2:4])
    r = _certified_radius(c1, c2, Q1, Q2, (f1, f2), halfplanes, alpha, float(z[4]))
    if r <= CONE_PROGRAM_TOL * solid.size:
        return None
    return c1, c2, r


def _piece_rows(facets: tuple[Facet, Facet], axes: tuple[FloatArray, FloatArray],
                halfplanes: tuple[Halfplanes, Halfplanes],
                fixed: tuple[int, float] | None = None
                ) -> tuple[list[FloatArray], list[float]]:
    """The rows of a cone program in ``(c1 (2), c2 (2), g)`` keeping each octagon's
    corners inside its piece: ``e . (c + g q) <= h`` per edge ``e`` of the piece and
    corner ``q``; ``fixed = (k, r)``: octagon ``k`` of the constant radius ``r`` instead
    (its rows ``e . c <= h - r e . q``)."""
    rows: list[FloatArray] = []
    rhs: list[float] = []
    for k, (f, (E, h), Q) in enumerate(zip(facets, halfplanes, axes, strict=True)):
        q2 = Q @ f.axes.T                                         # corners in 2-D (8, 2)
        for e, hh in zip(E, h, strict=True):
            for q in q2:
                row = np.zeros(5)
                row[2 * k:2 * k + 2] = e
                if fixed is not None and fixed[0] == k:
                    rhs.append(float(hh - fixed[1] * (e @ q)))
                else:
                    row[4] = e @ q
                    rhs.append(float(hh))
                rows.append(row)
    return rows, rhs


def _largest_holding(holds: Any, lo: float, hi: float) -> float:
    """Bisection between a radius ``lo`` that ``holds`` and one ``hi`` that may not: the
    largest found to hold (60 halvings)."""
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if holds(mid):
            lo = mid
        else:
            hi = mid
    return lo


def _largest_last(rows: list[FloatArray], rhs: list[float], cones: list[Any],
                  almost: bool = False) -> FloatArray | None:
    """The cone program's solution with its last variable (a radius) largest, or None
    when Clarabel does not solve it (``almost``: nor nearly, for a caller that checks
    the answer itself)."""
    q = np.zeros(len(rows[0]))
    q[-1] = -1.0
    sol = solve_linear(q, rows, rhs, cones)
    status = str(sol.status)
    if not (status.startswith("Solved") or almost and status.startswith("AlmostSolved")):
        return None
    return np.asarray(sol.x, float)


def _cone_rows(f1: Facet, f2: Facet, alpha: float | tuple[float, float],
               pairs: list[tuple[FloatArray, FloatArray]], rows: list[FloatArray],
               rhs: list[float], cones: list[Any]) -> None:
    """Append to a cone program in ``(c1 (2), c2 (2), g)`` both friction cones' second-order
    constraints on each corner difference ``x = b + c2 A2 - c1 A1 + g m`` (one ``(b, m)``
    per pair of corners): ``(a . x / cos(alpha), x)`` in the cone, ``a`` each facet's
    inward normal (the second's reversed); ``alpha`` one half-angle, or one per facet.
    Every pair's rows at once (the products summed in the order of ``a @ M``: the same
    numbers as one pair at a time)."""
    import clarabel

    alphas = (alpha, alpha) if isinstance(alpha, float | int) else alpha
    P = len(pairs)
    if not P:
        return
    B = np.array([b for b, _ in pairs], float)                          # (P, 3)
    M = np.zeros((P, 3, 5))
    M[:, :, 0:2] = -f1.axes.T
    M[:, :, 2:4] = f2.axes.T
    M[:, :, 4] = np.array([m for _, m in pairs], float)
    for axis, half in ((f1.normal, alphas[0]), (-f2.normal, alphas[1])):
        cos_half = math.cos(half)
        block = np.empty((P, 4, 5))
        block[:, 0] = -(axis[0] * M[:, 0] + axis[1] * M[:, 1] + axis[2] * M[:, 2]) / cos_half
        block[:, 1:] = -M
        right = np.empty((P, 4))
        right[:, 0] = (axis[0] * B[:, 0] + axis[1] * B[:, 1] + axis[2] * B[:, 2]) / cos_half
        right[:, 1:] = B
        rows.extend(block.reshape(-1, 5))
        rhs.extend(right.ravel().tolist())
        cones.extend(clarabel.SecondOrderConeT(4) for _ in range(P))


def _holds(c1: FloatArray, c2: FloatArray, Q1: FloatArray, Q2: FloatArray,
           facets: tuple[Facet, Facet], halfplanes: tuple[Halfplanes, Halfplanes],
           alpha: float, r: float, r2: float | None = None) -> bool:
    """The octagons of radius ``r`` about ``c1`` and ``c2`` (``r2``: the second's, when
    it differs), checked in floats: every corner difference within ``alpha`` of ``n_1``
    and of ``-n_2`` (strictly), every corner inside its piece."""
    r2 = r if r2 is None else r2
    d = (c2 + r2 * Q2)[None, :, :] - (c1 + r * Q1)[:, None, :]         # (8, 8, 3)
    length = np.linalg.norm(d, axis=-1)
    for axis in (facets[0].normal, -facets[1].normal):
        if not np.all(d @ axis > math.cos(alpha) * length):
            return False
    for f, (E, h), c, Q, rr in ((facets[0], halfplanes[0], c1, Q1, r),
                                (facets[1], halfplanes[1], c2, Q2, r2)):
        if not np.all(f.to_2d(c + rr * Q) @ E.T <= h):
            return False
    return True


def _second_level(solid: Solid, facets: tuple[int, int], pieces: tuple[int, int],
                  c1: FloatArray, c2: FloatArray, r: float, alpha: float
                  ) -> tuple[FloatArray, FloatArray, tuple[float, float]]:
    """Definition 7.1's second level (leximin) for two octagons of the first level's
    radius ``r``: one octagon kept at ``r``, the other as large as it can be (its
    centre and the kept one's free), both ways tried, the larger growth kept (the first
    on a tie, within :data:`~fcgrasp.core.tolerances.TOL`).  Each is the cone program
    of :func:`_pair_program` with the kept radius a constant, its answer confirmed in
    floats (:func:`_holds`, shrunk by bisection towards ``r`` where it sits a rounding
    outside).  Returns the centres and the two radii (``(r, r)`` when neither grows)."""
    f1, f2 = solid.facets[facets[0]], solid.facets[facets[1]]
    rings = (_ring(f1.pieces[pieces[0]]), _ring(f2.pieces[pieces[1]]))
    halfplanes = (_ring_halfplanes(rings[0]), _ring_halfplanes(rings[1]))
    # each piece's width across its edges: the fit of a centrally symmetric piece (the
    # caps of round holes and bosses) in closed form (:func:`_fit`)
    widths = [_ring_widths(hp, ring) for hp, ring in zip(halfplanes, rings, strict=True)]
    Q1, Q2 = _octagon_axes(f1, f2)
    best = (c1, c2, (r, r))
    # bounds that skip the program where nothing can grow: an octagon's fit in its piece
    # alone; on parallel facets a distance h apart, h tan(alpha) - r (two antipodal
    # corners, r + g apart across, must stay inside the cone over the height h)
    parallel = float(f1.normal @ f2.normal) < -1 + TOL
    across = (math.tan(alpha) * abs(float((f2.origin - f1.origin) @ f1.normal)) - r
              if parallel else math.inf)
    for side in (0, 1):
        f, Q = (f1, Q1) if side == 0 else (f2, Q2)
        fit = _fit(halfplanes[side], Q @ f.axes.T, widths[side])[0]
        if min(fit, across) <= r * (1 + TOL):
            continue
        got = _grow_program(solid, facets, halfplanes, alpha, r, side)
        if got is None:
            continue
        d1, d2, g = got

        def holds(x: float, d1: FloatArray = d1, d2: FloatArray = d2, side: int = side
                  ) -> bool:
            r1, r2 = (x, r) if side == 0 else (r, x)
            return _holds(d1, d2, Q1, Q2, (f1, f2), halfplanes, alpha, r1, r2)

        if not holds(r):
            continue
        if not holds(g):
            g = _largest_holding(holds, r, g)
        if g > max(best[2]) * (1 + TOL):
            best = (d1, d2, (g, r) if side == 0 else (r, g))
    return best


def _grow_program(solid: Solid, facets: tuple[int, int],
                  halfplanes: tuple[Halfplanes, Halfplanes], alpha: float, r: float,
                  side: int) -> tuple[FloatArray, FloatArray, float] | None:
    """The cone program of :func:`_pair_program` with octagon ``1 - side`` of radius
    ``r`` (fixed) and octagon ``side`` of the largest radius ``g`` (variables ``c1, c2,
    g``): the centres (3-D) and ``g``, or None when it has no solution."""
    import clarabel

    f1, f2 = solid.facets[facets[0]], solid.facets[facets[1]]
    Q1, Q2 = _octagon_axes(f1, f2)
    rows, rhs = _piece_rows((f1, f2), (Q1, Q2), halfplanes, fixed=(1 - side, r))
    cones: list[Any] = [clarabel.NonnegativeConeT(len(rows) + 1)]
    row = np.zeros(5)
    row[4] = -1.0                                         # g >= r
    rows.append(row)
    rhs.append(-r)
    base = f2.origin - f1.origin
    # x = base + c2 A2 - c1 A1 + r2 q2 - r1 q1, one radius fixed
    _cone_rows(f1, f2, alpha, [(base + r * q2, -q1) if side == 0 else (base - r * q1, q2)
                               for q1 in Q1 for q2 in Q2], rows, rhs, cones)
    z = _largest_last(rows, rhs, cones)
    return None if z is None else (f1.to_3d(z[0:2]), f2.to_3d(z[2:4]), float(z[4]))


def _certified_radius(c1: FloatArray, c2: FloatArray, Q1: FloatArray, Q2: FloatArray,
                      facets: tuple[Facet, Facet], halfplanes: tuple[Halfplanes, Halfplanes],
                      alpha: float, r: float) -> float:
    """The program's radius, or the largest below it that :func:`_holds` confirms (an
    interior-point solution may sit a rounding outside a constraint): bisection."""
    for shrink in _SHRINKS:                               # the usual rounding first
        if _holds(c1, c2, Q1, Q2, facets, halfplanes, alpha, r * (1 - shrink)):
            return r * (1 - shrink)
    if not _holds(c1, c2, Q1, Q2, facets, halfplanes, alpha, 0.0):
        return 0.0
    return _largest_holding(lambda x: _holds(c1, c2, Q1, Q2, facets, halfplanes, alpha, x),
                            0.0, r)


#: The fractions a solution is shrunk by to absorb its rounding, smallest first.
_SHRINKS = (0.0, *(ROUNDING_SHRINK / 10.0 ** k for k in (5, 2, 0)))

#: Pieces in the search's first round (each round takes four times more).
_FIRST_ROUND = 256


#: Whether a pair whose pieces a direction separates from the cones
#: (:func:`~fcgrasp.spatial._pieces.separated`) is bounded by 0 without its cone program
#: (False: every pair the search reaches solved, the reference).
SEPARATE = True


@dataclass
class _Refined:
    """A candidate's tighter bound: both octagons' largest fits (scale, 2-D centre) and
    the exact heights (``tan(alpha)`` times each piece's highest vertex above the other
    facet's plane)."""

    bound: float
    fits: tuple[tuple[float, FloatArray], tuple[float, FloatArray]]


def _refine(solid: Solid, table: _Pieces, pa: int, pb: int, alpha: float) -> _Refined:
    f1, f2 = solid.facets[int(table.facet[pa])], solid.facets[int(table.facet[pb])]
    if SEPARATE and separated(table, pa, pb, alpha, solid.size):
        return _Refined(0.0, ((0.0, np.zeros(2)), (0.0, np.zeros(2))))   # no regions
    Q1, Q2 = _octagon_axes(f1, f2)
    q1, q2 = Q1 @ f1.axes.T, Q2 @ f2.axes.T
    (b1, fit1), (b2, fit2) = _piece_fit(table, pa, q1), _piece_fit(table, pb, q2)
    h1 = float(np.max((table.vertices[pb] - f1.origin) @ f1.normal))
    h2 = float(np.max((table.vertices[pa] - f2.origin) @ f2.normal))
    return _Refined(min(b1, b2, math.tan(alpha) * min(h1, h2)), (fit1, fit2))


def _solve(solid: Solid, table: _Pieces, pa: int, pb: int, alpha: float,
           refined: _Refined) -> tuple[FloatArray, FloatArray, float] | None:
    """The pair's regions: first the octagons at the pieces' own largest fits, of the
    smaller scale (the bound itself, so optimal) when they pass the float check
    (:func:`_holds`); else the cone program."""
    f1, f2 = solid.facets[int(table.facet[pa])], solid.facets[int(table.facet[pb])]
    halfplanes = (table.halfplanes[pa], table.halfplanes[pb])
    (s1, t1), (s2, t2) = refined.fits
    r = min(s1, s2)
    if r >= refined.bound * (1 - FIT_ROUNDING):    # the fits reach the bound: try them
        Q1, Q2 = _octagon_axes(f1, f2)
        c1, c2 = f1.to_3d(t1), f2.to_3d(t2)
        for shrink in _SHRINKS:                   # the fits' own rounding
            if _holds(c1, c2, Q1, Q2, (f1, f2), halfplanes, alpha, r * (1 - shrink)):
                return c1, c2, r * (1 - shrink)
    return _pair_program(solid, (f1.index, f2.index),
                         (int(table.local[pa]), int(table.local[pb])), alpha, halfplanes)


def facet_pair_plans(solid: Solid, mu: Any, top: int | None = 10,
                     margin: Any = DEFAULT_MARGIN_DEG, leximin: bool = True,
                     memo: dict[Any, Any] | None = None) -> list[SoftPairPlan]:
    """The best regions of two soft fingers on ``solid``, largest first (module
    docstring), by best-first search over every pair of convex pieces whose cones can
    meet: the pairs' bounds batched, round by round (:func:`_pairs`,
    :func:`_pair_bounds`), then in decreasing order each
    pair's bound tightened (:func:`_refine`: the octagons' exact fits and heights) and,
    when it is still the largest, the pair solved (:func:`_solve`: the fits themselves
    when they hold, which is then optimal, else the cone program); the search stops
    when no bound can enter the top ``top`` (None: every pair).  With ``leximin`` (the
    default) each plan's second level is grown (:func:`_second_level`; ``radius``, the
    first level, ranks them either way).  When the time budget ends
    (:func:`fcgrasp.core.budget.deadline`) the plans solved so far are returned and the
    search is recorded as cut short (a complete search may rank others first).
    ``memo``: a dict the searches of one solid share (a caller asking for more plans,
    :func:`fcgrasp.spatial.alternatives.top_distinct`): the pieces' table and each
    pair's refined bound and solution, computed once (each depends on the pair and the
    cone alone, so the plans are the same).

    >>> from fcgrasp.spatial.solid import demo_solid
    >>> [round(p.radius, 4) for p in facet_pair_plans(demo_solid("box"), mu=0.3, top=3)]
    [5.0, 2.9051, 1.4526]
    """
    mu_v, margin_v, alpha = checked_cone(mu, margin, solid)
    if not isinstance(leximin, bool):
        raise TypeError(f"leximin must be a bool, got {leximin!r}")
    if top is not None:
        top = check_int(top, "top", minimum=1)
    if alpha <= 0:
        return []
    table: _Pieces = _once(memo, "table", _piece_table, solid)
    cos_limit = math.cos(min(2 * alpha, math.pi))
    floor = CONE_PROGRAM_TOL * solid.size
    # rounds over the pieces, largest inscribed circle first: a pair not yet met has a
    # piece outside the round, so its radius is at most that piece's cap
    cap = table.inradius / math.cos(math.pi / 8)
    by_cap = np.argsort(-cap, kind="stable")
    # each round's pairs sorted by their batched bound (a run); refined pairs in a heap
    runs: list[_Run] = []
    heap: list[tuple[float, int, int, int, _Refined]] = []      # (-bound, seq, i, j, ...)
    plans: list[SoftPairPlan] = []
    seq = done = 0
    size = _FIRST_ROUND
    threshold = math.inf

    def key(p: SoftPairPlan) -> tuple[float, tuple[int, ...], tuple[int, ...]]:
        return (-p.radius, p.facets, p.pieces)

    while True:
        run = max(runs, key=_Run.head, default=None)
        raw = run.head() if run is not None else -math.inf
        ref = -heap[0][0] if heap else -math.inf
        best = max(raw, ref)
        if done < len(by_cap) and best <= threshold:
            new, old = by_cap[done:done + size], by_cap[:done]
            done += len(new)
            threshold = float(cap[by_cap[done]]) if done < len(by_cap) else floor
            pa, pb = _pairs(table, new, old, cos_limit)
            bound = _pair_bounds(table, pa, pb, alpha)
            keep = np.flatnonzero(bound > floor)
            order = keep[np.argsort(-bound[keep], kind="stable")]
            runs.append(_Run(bound[order], pa[order], pb[order]))
            size *= 4
            continue
        if best <= floor:
            break
        if top is not None and len(plans) >= top and best <= plans[top - 1].radius:
            break
        if cut_if_over():
            break               # the plans solved so far, each exact; the answer cut short
        if run is not None and raw > ref:      # tighten the bound; solve when still first
            i, j = run.pop()
            got = _once(memo, ("refine", alpha, i, j), _refine, solid, table, i, j, alpha)
            heapq.heappush(heap, (-got.bound, seq, i, j, got))
            seq += 1
            continue
        _, _, i, j, got = heapq.heappop(heap)
        sol: tuple[FloatArray, FloatArray, float] | None = _once(
            memo, ("solve", alpha, i, j), _solve, solid, table, i, j, alpha, got)
        if sol is not None:
            facets = (int(table.facet[i]), int(table.facet[j]))
            pieces = (int(table.local[i]), int(table.local[j]))
            bisect.insort(plans, _plan(solid, facets, pieces, *sol, mu_v, margin_v), key=key)
            if top is not None:
                del plans[top:]
    # the second level of the plans kept (their measure, the first, ranks them), each
    # grown once for the searches that share the memo
    return [_once(memo, ("grown", mu_v, margin_v, leximin, p.facets, p.pieces), _plan, solid,
                  (p.facets[0], p.facets[1]), (p.pieces[0], p.pieces[1]), p.centers[0],
                  p.centers[1], p.radius, mu_v, margin_v, leximin)
            for p in plans]


def _once(memo: dict[Any, Any] | None, key: Any, make: Callable[..., Any], *args: Any
          ) -> Any:
    """``make(*args)``, kept in ``memo`` under ``key`` and read from there again (no
    memo: made every time)."""
    if memo is None:
        return make(*args)
    if key not in memo:
        memo[key] = make(*args)
    return memo[key]


@dataclass
class _Run:
    """One round's pairs of pieces, largest bound first, and how far they were taken."""

    bound: FloatArray
    first: IntArray
    second: IntArray
    pos: int = 0

    def head(self) -> float:
        return float(self.bound[self.pos]) if self.pos < len(self.bound) else -math.inf

    def pop(self) -> tuple[int, int]:
        k = self.pos
        self.pos += 1
        return int(self.first[k]), int(self.second[k])
