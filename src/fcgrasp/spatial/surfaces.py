r"""Regions of two soft fingers across the facets of a curved surface (a curved
surface is the facets of its tessellation, and a region held inside one of them is a
sliver on a finely tessellated cylinder; the paper's regions of contact "along curved
outlines", section 7, in three dimensions).

**A patch** is a connected set of the mesh's triangles whose inward normals lie within
``beta`` of an axis ``n_0``, grown from a seed triangle across shared edges.  It is
drawn in the plane through the seed's centroid across ``n_0``: each patch point projects
into the union ``U`` of its triangles' projections, at a height (along ``n_0``) within
the patch's ``[low, high]``.

**A region** is a regular octagon ``P`` (as in :mod:`~fcgrasp.spatial.regions`) inside
a convex piece of ``U`` (:func:`_kernel`: ``U``'s hull cut at its reflex corners, checked
inside ``U``, else ``U``'s kernel); a finger may touch any patch point that projects
into ``P``.  Those points lie in the prism ``P x [low, high]``, and the surface's normal
at each of them is within ``beta`` of ``n_0``.

**The condition (sufficient).**  A friction cone of half-angle ``alpha`` about a normal
within ``beta`` of ``n_0`` contains the cone of half-angle ``alpha - beta`` about ``n_0``.
Two soft fingers hold when the segment joining them lies inside both friction cones
(:func:`~fcgrasp.spatial.closure.two_soft_closure`), so they hold anywhere in two regions
when every difference of the two prisms' corners (16 each) lies in the cone of
``alpha - beta_1`` about ``n_{0,1}`` and of ``alpha - beta_2`` about ``-n_{0,2}``: both
cones are convex, and the differences of the prisms are the convex hull of their
corners' (:mod:`~fcgrasp.spatial.regions`).  The largest pair of octagons under that
condition is one second-order cone program (Clarabel), its answer confirmed in floats.
The regions are **certified** (every grasp in them holds), not proved the largest: the
condition is sufficient, not necessary, and the patches are a finite family.

**The family.**  Seeds cover the mesh: a triangle is a seed unless it lies in the patch
(spread ``alpha / 4`` about its own normal) of a seed before it, largest first (at most
:data:`MAX_SEEDS`; the covering patch is widened until they fit).  Two seeds whose
normals are within ``2 alpha`` of opposite, and each seed with the triangle facing it
most squarely, make a pair; its patches lie about the bisector ``d`` of their normals
(``-d`` for the second, so their planes are parallel), at ``beta`` a quarter, half and
three quarters of the way from the seeds' own tilt from ``d`` to ``alpha`` (a smaller
``beta`` keeps more of the cone, a larger one more of the surface).  A pair whose two
patches cover two facets in all is left to :mod:`~fcgrasp.spatial.regions` (exact there).

**The search.**  Pairs are taken best bound first (the solid's extent along ``d``, the
patches' widths and heights, their projections' inscribed circles), each solved first
for a lower bound (octagons about the convex pieces' centroids or the projections'
inscribed centres, or one of them and the point facing it), and the search stops when
no pair left can beat the ``top`` kept by more than :data:`GAP`; the cone program then
polishes each kept pair whose lower bound is further than that below its bound.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass, field
from itertools import combinations
from typing import Any

import numpy as np

from ..core._checks import FloatArray, IntArray
from ..core.budget import cut_if_over
from ..core.tolerances import (
    CONE_PROGRAM_TOL,
    SURFACE_STEP,
    TINY,
)
from ._patches import (
    _COS8,
    MAX_SEEDS,
    _bisect,
    _certified,
    _facing,
    _graph,
    _grow,
    _holds,
    _kernel,
    _lift,
    _on_surface,
    _pair_bound,
    _Patch,
    _patch,
    _program,
    _room,
    _seeds,
)
from ._pieces import _fit
from .regions import (
    DEFAULT_MARGIN_DEG,
    OCTAGON,
    OctagonPlan,
    SoftPairPlan,
    _octagon_axes,
    _once,
    checked_cone,
    facet_pair_plans,
)
from .solid import Solid
from .triples import (
    PointTriplePlan,
    PointTripleSearch,
    _certificate,
    _unbalance,
    point_triple_plans,
)

__all__ = ["SurfacePairPlan", "surface_pair_plans", "soft_pair_plans", "SurfaceTriplePlan",
           "surface_triple_plans", "three_finger_plans", "SPREADS", "MAX_SEEDS", "GAP",
           "TRIPLE_CANDIDATES"]

#: The patches' spreads ``beta``, as fractions of the cone's half-angle ``alpha``.
SPREADS = (0.25, 0.5, 0.75)

#: The search across facets stops when no pair of patches left can beat the plans kept
#: by more than this fraction (on a symmetric solid, every pair around it ties).
GAP = 0.1

#: Triples of seeds certified across facets (:func:`surface_triple_plans`), those whose
#: normals balance a force with the most slack over the widest reach first.
TRIPLE_CANDIDATES = 48

#: Points drawn along each side of an octagon for its outline on the surface.
OUTLINE_STEPS = 6


@dataclass(frozen=True)
class _AcrossFacets(OctagonPlan):
    """What a plan across facets adds to its octagons (:class:`SurfacePairPlan`,
    :class:`SurfaceTriplePlan`; listed first among their bases, so these fields come
    after the plan's own): ``surfaces`` (the facets each region covers), ``triangles``
    (the mesh triangles of each patch), ``spread`` (each patch's ``beta``, degrees),
    ``outlines`` (each region's boundary on the surface) and ``surface_triangles``
    (each region on the surface, triangles (k, 3, 3))."""

    surfaces: tuple[tuple[int, ...], ...] = ()
    triangles: tuple[IntArray, ...] = field(default=(), repr=False)
    spread: tuple[float, ...] = ()
    outlines: tuple[FloatArray, ...] = field(default=(), repr=False)
    surface_triangles: tuple[FloatArray, ...] = field(default=(), repr=False)

    def _with_across(self, out: dict[str, Any]) -> dict[str, Any]:
        """The plan's JSON ``out`` with these (``spread_deg`` for ``spread``)."""
        out.update({"across_facets": True, "surfaces": [list(s) for s in self.surfaces],
                    "spread_deg": list(self.spread),
                    "outlines": [o.tolist() for o in self.outlines],
                    "surface_triangles": [t.tolist() for t in self.surface_triangles]})
        return out


@dataclass(frozen=True)
class SurfacePairPlan(_AcrossFacets, SoftPairPlan):
    """Regions of two soft fingers across facets (module docstring): a
    :class:`~fcgrasp.spatial.SoftPairPlan` whose ``facets`` are the seeds' facets,
    ``normals`` the patches' reference normals ``n_0``, ``regions`` the octagons'
    corners lifted onto the surface and ``radius`` their circumradius (in the plane
    across ``n_0``), with ``surfaces`` (the facets each region covers), ``triangles``
    (the mesh triangles of each patch: a finger may touch any of their points that
    projects into the octagon), ``spread`` (each patch's ``beta``, degrees),
    ``outlines`` (each region's boundary on the surface, 3-D points) and
    ``surface_triangles`` (each region on the surface, triangles (k, 3, 3))."""

    def to_dict(self) -> dict[str, Any]:
        return self._with_across(super().to_dict())


def _surface_plan(solid: Solid, p: _Patch, q: _Patch, c1: FloatArray, c2: FloatArray,
                  r: float, mu: float, margin: float, facet_of: IntArray,
                  radii: tuple[float, float] | None = None) -> SurfacePairPlan:
    """The plan of octagons of radius ``r`` (the measure) about ``c1`` and ``c2``, or of
    ``radii`` when the second level grew one of them."""
    Q1, Q2 = _octagon_axes(p.frame, q.frame)
    radii = (r, r) if radii is None else radii
    regions, centers, outlines, pieces = [], [], [], []
    steps = np.arange(OUTLINE_STEPS) / OUTLINE_STEPS
    for patch, c, Q, rr in ((p, c1, Q1, radii[0]), (q, c2, Q2, radii[1])):
        corners = patch.frame.to_2d(c + rr * Q)
        ring = corners[:, None, :] + steps[None, :, None] * (
            np.roll(corners, -1, axis=0) - corners)[:, None, :]
        regions.append(_lift(solid, patch, corners))
        centers.append(_lift(solid, patch, patch.frame.to_2d(c)[None, :])[0])
        outlines.append(_lift(solid, patch, ring.reshape(-1, 2)))
        pieces.append(_on_surface(solid, patch, corners))
    surfaces = tuple(tuple(sorted({int(v) for v in facet_of[t.triangles]})) for t in (p, q))
    facets = (int(facet_of[p.seed]), int(facet_of[q.seed]))
    return SurfacePairPlan(facets, (-1, -1), r, np.stack(centers), np.stack(regions),
                           np.stack([p.frame.normal, q.frame.normal]), mu, margin,
                           radii=radii, surfaces=surfaces,
                           triangles=(p.triangles, q.triangles),
                           spread=(math.degrees(p.beta), math.degrees(q.beta)),
                           outlines=tuple(outlines), surface_triangles=tuple(pieces))


def _second_level(p: _Patch, q: _Patch, c1: FloatArray, c2: FloatArray, r: float,
                  alphas: tuple[float, float]
                  ) -> tuple[FloatArray, FloatArray, tuple[float, float]]:
    """Definition 7.1's second level (leximin) across facets: one octagon kept at the
    first level's ``r``, the other grown about its centre as far as the module's
    condition holds in floats (bisection up to its room in its convex piece), both ways
    tried, the larger growth kept.  Unlike the facets' second level
    (:func:`~fcgrasp.spatial.regions._second_level`) the centres stay where the first
    level put them (a cone program per side cost 20 ms a plan, the bisection about 1 ms):
    a certified growth, not the largest.  A side whose projection's inscribed circle holds
    no larger octagon is not tried.  Returns the centres and the two radii (``(r, r)``
    when neither grows)."""
    Q1, Q2 = _octagon_axes(p.frame, q.frame)
    best = (r, r)
    for side in (0, 1):
        patch, c, Q = ((p, c1, Q1), (q, c2, Q2))[side]
        top = min(patch.inradius / _COS8, _room(patch, c, Q))
        if top <= r * (1 + SURFACE_STEP):
            continue

        def holds(x: float, side: int = side) -> bool:
            r1, r2 = (x, r) if side == 0 else (r, x)
            return _holds(c1, c2, Q1, Q2, (p, q), alphas, r1, r2)

        g = top if holds(top) else _bisect(holds, r, top)
        if g > max(best) * (1 + SURFACE_STEP):
            best = (g, r) if side == 0 else (r, g)
    return c1, c2, best


def soft_pair_plans(solid: Solid, mu: Any, top: int | None = 10,
                    margin: Any = DEFAULT_MARGIN_DEG, leximin: bool = True,
                    across: bool = True, memo: dict[Any, Any] | None = None,
                    grow_facets: bool = True) -> list[SoftPairPlan]:
    """The best regions of two soft fingers on ``solid``, largest first: the exact
    regions on pairs of facets (:func:`~fcgrasp.spatial.regions.facet_pair_plans`, with
    ``leximin`` their second level grown) and, with ``across`` (the default), the
    certified regions across the facets of curved surfaces (:func:`surface_pair_plans`,
    searched only above the facets' ``top``-th), ranked together by ``radius``;
    ``memo``: what the searches of one solid share (:func:`~fcgrasp.spatial.regions.
    facet_pair_plans`); ``grow_facets=False``: the plans on pairs of facets at their
    first level, for a caller that grows those it keeps
    (:func:`fcgrasp.spatial._grown.grown`).

    >>> from fcgrasp.spatial.solid import demo_solid
    >>> [round(p.radius, 2) for p in soft_pair_plans(demo_solid("mug"), mu=0.5, top=2)]
    [9.03, 9.03]
    >>> type(soft_pair_plans(demo_solid("mug"), mu=0.5, top=1)[0]).__name__
    'SurfacePairPlan'
    """
    if not isinstance(across, bool):
        raise TypeError(f"across must be a bool, got {across!r}")
    out = facet_pair_plans(solid, mu, top, margin, leximin and grow_facets, memo)
    if not across:
        return out
    mu_v, margin_v, alpha = checked_cone(mu, margin, solid)
    return _ranked_with(out, top, lambda last: surface_pair_plans(
        solid, mu_v, alpha, top, margin_v, last, leximin=leximin, memo=memo))


def _ranked_with(plans: list[Any], top: int | None, across: Any) -> list[Any]:
    """A facet search's ``plans`` ranked by ``radius`` with those ``across(last)`` finds
    above ``last``, the facets' ``top``-th radius (0 when they are fewer), the best
    ``top`` kept."""
    last = plans[top - 1].radius if top is not None and len(plans) >= top else 0.0
    return sorted([*plans, *across(last)], key=lambda p: -p.radius)[:top]


def surface_pair_plans(solid: Solid, mu: float, alpha: float, top: int | None = 10,
                       margin: float = DEFAULT_MARGIN_DEG, floor: float = 0.0,
                       gap: float = GAP, leximin: bool = True,
                       memo: dict[Any, Any] | None = None) -> list[SurfacePairPlan]:
    """The best regions of two soft fingers across facets (module docstring), largest
    first, at most ``top`` (None: every pair of patches), each larger than ``floor``;
    the search stops when no pair of patches left has a bound above ``1 + gap`` times
    the ``top``-th kept (``gap=0``: the best of the whole family, for the lower bound of
    each pair that the search computes before the cone program polishes those kept; when
    the time budget ends, those found so far, neither polished nor grown, the search
    recorded as cut short);
    with ``leximin``, each plan's second level grown (:func:`_second_level`):
    ``mu`` and ``margin`` as :func:`~fcgrasp.spatial.soft_pair_plans` checked them,
    ``alpha = atan(mu) - margin`` in radians.  An empty list where no patch spans two
    facets (a box, a prism).  ``memo``: a dict the searches of one solid share (the
    distinct rounds asking for more plans): each pair's patches, lower bound and plan,
    computed once (each depends on the pair, the cone and the options alone)."""
    if alpha <= 0:
        return []
    normals, adj, facet_of = _graph(solid)
    areas = np.asarray(solid.mesh.area_faces, float)
    seeds = np.array(_seeds(normals, adj, areas, SPREADS[0] * alpha), np.intp)
    # pairs of seeds whose normals are within 2 alpha of opposite; each pair's patches
    # about the bisector ``d`` of its normals (``-d`` for the second), spread from the
    # seeds' own tilt ``theta`` towards alpha
    ns = normals[seeds]
    ii, jj = np.nonzero(np.triu(-(ns @ ns.T) > math.cos(min(2 * alpha, math.pi)), 1))
    # and each seed with the triangle facing it most squarely (its normal the most
    # nearly opposite), the pair a smooth surface grasps best across
    facing = np.argmin(ns @ normals.T, axis=1)
    keep = -np.einsum("ij,ij->i", ns, normals[facing]) > math.cos(min(2 * alpha, math.pi))
    first = np.concatenate([seeds[ii], seeds[keep]])
    second = np.concatenate([seeds[jj], facing[keep]])
    d = normals[first] - normals[second]
    d /= np.linalg.norm(d, axis=1)[:, None]
    theta = np.arccos(np.clip(np.einsum("ij,ij->i", normals[first], d), -1, 1))
    beta = (theta[:, None] + np.asarray(SPREADS)[None, :] * (alpha - theta)[:, None]).ravel()
    # a first bound, before any patch is grown: the solid's extent along d for H
    reach = np.asarray(solid.mesh.vertices, float) @ d.T
    extent = np.repeat(reach.max(axis=0) - reach.min(axis=0), len(SPREADS))
    bound = extent * np.tan(alpha - beta) / 2
    floor = max(floor, CONE_PROGRAM_TOL * solid.size)
    heap = [(-float(bound[k]), 0, k) for k in np.flatnonzero(bound > floor).tolist()]
    heapq.heapify(heap)
    pairs: dict[int, tuple[_Patch, _Patch]] = {}
    found: list[tuple[float, int, FloatArray, FloatArray, float]] = []
    search = ("surface pairs", mu, margin, alpha, gap, leximin)     # the memo's keys
    while heap:
        if cut_if_over():
            break               # the pairs found so far, each certified; cut short
        neg, stage, k = heapq.heappop(heap)
        full = top is not None and len(found) >= top
        limit = found[-1][0] if full else floor               # the top-th kept
        if -neg <= (limit * (1 + gap) if full else floor):
            break
        if stage == 0:                        # grow the patches, bound by their extent
            grown = _once(memo, (*search, "grown", k), _grown_pair, solid, alpha, k, d, beta,
                          normals, first, second, adj, facet_of)
            if grown is None:
                continue                      # one facet each: the exact case of regions.py
            pairs[k], pair_bound = grown
            tight = min(-neg, pair_bound)
            if tight > limit:
                heapq.heappush(heap, (-tight, 1, k))
            continue
        p, q = pairs[k]
        alphas = (alpha - p.beta, alpha - q.beta)
        _kernel(solid, p), _kernel(solid, q)
        if stage == 1:            # tighten by the projections' inscribed circles, queue
            tight = min(-neg, p.inradius / _COS8, q.inradius / _COS8)
            if tight > limit:
                heapq.heappush(heap, (-tight, 2, k))
            continue
        # a lower bound the cone program improves for the pairs kept
        r, c1, c2 = _once(memo, (*search, "lower", k), _lower, p, q, alphas, -neg)
        if r > limit:
            found.append((r, k, c1, c2, -neg))
            found.sort(key=lambda x: -x[0])
            del found[top or len(found):]
    plans = []
    for r, k, c1, c2, bound in found:
        p, q = pairs[k]
        alphas = (alpha - p.beta, alpha - q.beta)
        # past the time budget a pair is kept as its lower bound certified it: neither
        # polished nor grown
        late = cut_if_over()
        args = (solid, p, q, alphas, r, c1, c2, bound, gap, leximin, late, mu, margin, facet_of)
        plans.append(_polished(*args) if late else
                     _once(memo, (*search, "plan", k), _polished, *args))
    return sorted(plans, key=lambda x: -x.radius)


def _grown_pair(solid: Solid, alpha: float, k: int, d: FloatArray, beta: FloatArray,
                normals: FloatArray, first: Any, second: Any, adj: Any, facet_of: Any
                ) -> tuple[tuple[_Patch, _Patch], float] | None:
    """Candidate ``k`` of :func:`surface_pair_plans`: its two patches grown about the
    bisector and its bound from their extent, or None where each patch is one facet
    (the exact case of :mod:`fcgrasp.spatial.regions`)."""
    m = k // len(SPREADS)
    axis, b = d[m], float(beta[k])
    along = normals @ axis
    i, j = int(first[m]), int(second[m])
    a = _grow(i, (along >= math.cos(b)).tolist(), adj)
    c = _grow(j, (-along >= math.cos(b)).tolist(), adj)
    if not a or not c or len(set(facet_of[a].tolist())) + len(set(facet_of[c].tolist())) < 3:
        return None
    pair = (_patch(solid, i, b, a, normals, axis), _patch(solid, j, b, c, normals, -axis))
    return pair, _pair_bound(*pair, alpha)


def _lower(p: _Patch, q: _Patch, alphas: tuple[float, float], bound: float
           ) -> tuple[float, FloatArray, FloatArray]:
    """A pair's lower bound, the cone program to improve it for the pairs kept: the
    octagons as large as they hold about the inscribed centres, or about one of them and
    the point facing it on the other patch (the pieces' centroids first: between equal
    octagons, the one in the middle); ``(r, c1, c2)``."""
    r, c1, c2 = max(_facing(p, q, alphas, (p.middle, q.middle), bound),
                    _facing(p, q, alphas, (p.centre, q.centre), bound),
                    key=lambda x: x[0])
    if r <= 0:                # the centres outside the convex pieces: their fits'
        Q1, Q2 = _octagon_axes(p.frame, q.frame)
        t1 = _fit(p.kernel, Q1 @ p.frame.axes.T)[1]  # type: ignore[arg-type]
        t2 = _fit(q.kernel, Q2 @ q.frame.axes.T)[1]  # type: ignore[arg-type]
        r, c1, c2 = _facing(p, q, alphas, (t1, t2), bound)
    return r, c1, c2


def _polished(solid: Solid, p: _Patch, q: _Patch, alphas: tuple[float, float], r: float,
              c1: FloatArray, c2: FloatArray, bound: float, gap: float, leximin: bool,
              late: bool, mu: float, margin: float, facet_of: Any) -> SurfacePairPlan:
    """A pair's plan from its lower bound ``(r, c1, c2)``: the cone program where that
    may fall short of the pair's ``bound`` by more than the ``gap``, then with
    ``leximin`` the second level; neither when ``late`` (past the time budget)."""
    got = _program(p, q, alphas) if r * (1 + gap) < bound and not late else None
    if got is not None:
        d1, d2, g = got
        g = _certified(d1, d2, p, q, alphas, g)
        if g > r:
            r, c1, c2 = g, d1, d2
    c1, c2, radii = _second_level(p, q, c1, c2, r, alphas) if leximin and not late \
        else (c1, c2, (r, r))
    return _surface_plan(solid, p, q, c1, c2, r, mu, margin, facet_of, radii)


# ----------------------------------------------------------------------------- triples


@dataclass(frozen=True)
class SurfaceTriplePlan(_AcrossFacets, PointTriplePlan):
    """Certified regions of three point fingers with friction across facets
    (:func:`surface_triple_plans`): a :class:`~fcgrasp.spatial.PointTriplePlan` whose
    ``facets`` are the seeds' facets, ``normals`` the patches' axes ``n_0``,
    ``regions`` the octagons' corners lifted onto the surface, ``centers`` the
    certificate's points (each octagon's centre at its patch's middle height) and
    ``delta`` its radius, with ``surfaces``, ``triangles``, ``spread``, ``outlines`` and
    ``surface_triangles`` as :class:`SurfacePairPlan` has them."""

    def to_dict(self) -> dict[str, Any]:
        return self._with_across(super().to_dict())


def _triple_radius(patches: tuple[_Patch, ...], mids: list[FloatArray], alpha: float
                   ) -> tuple[float, float, FloatArray]:
    """The certified circumradius of three octagons about the 2-D centres ``mids`` (one
    per patch, turned along each patch's first axis), the certificate's radius ``delta``
    and its three points (3, 3).  The certificate
    (:func:`~fcgrasp.spatial.triples.perturbation_radius`'s, theorem 3.1 in 6-D) is
    taken with each contact's pyramid in the cone of ``alpha - beta`` about ``n_0`` (so
    inside the friction cone of every normal of the patch) at the octagon's centre
    raised to the middle of the patch's heights; a patch point over the octagon is then
    within ``sqrt(r^2 + H^2)`` of it (``H`` half the patch's height range), so ``r`` is at
    most ``sqrt(delta^2 - H^2)`` and the octagon's room in its convex piece."""
    points = np.array([p.frame.to_3d(m) + 0.5 * (p.low + p.high) * p.frame.normal
                       for p, m in zip(patches, mids, strict=True)])
    normals = np.array([p.frame.normal for p in patches])
    delta = _certificate(points, normals, np.array([alpha - p.beta for p in patches]))
    r = delta
    for p, m in zip(patches, mids, strict=True):
        half = 0.5 * (p.high - p.low)
        if delta <= half:
            return 0.0, delta, points
        r = min(r, math.sqrt(delta * delta - half * half),
                _room(p, p.frame.to_3d(m), _own_octagon(p)))
    return max(r, 0.0), delta, points


def _own_octagon(p: _Patch) -> FloatArray:
    """The unit octagon's corners (8, 3) in the patch's plane, turned along its first
    axis."""
    return np.asarray(OCTAGON @ p.frame.axes)


def three_finger_plans(solid: Solid, mu: Any, top: int | None = 10,
                       margin: Any = DEFAULT_MARGIN_DEG, across: bool = True
                       ) -> PointTripleSearch:
    """Certified regions of three point fingers with friction on ``solid``, largest
    first: on triples of facets (:func:`~fcgrasp.spatial.point_triple_plans`) and, with
    ``across`` (the default), across the facets of curved surfaces
    (:func:`surface_triple_plans`, above the facets' ``top``-th), ranked together by
    ``radius``; ``certified`` and ``exhaustive`` are the facet search's.

    >>> from fcgrasp.spatial.solid import demo_solid
    >>> got = three_finger_plans(demo_solid("cylinder"), mu=0.5, top=2)
    >>> [type(p).__name__ for p in got.plans]
    ['SurfaceTriplePlan', 'SurfaceTriplePlan']
    """
    if not isinstance(across, bool):
        raise TypeError(f"across must be a bool, got {across!r}")
    search = point_triple_plans(solid, mu, top=top, margin=margin)
    if not across:
        return search
    mu_v, margin_v, alpha = checked_cone(mu, margin, solid)
    plans = _ranked_with(list(search.plans), top, lambda last: surface_triple_plans(
        solid, mu_v, alpha, top, margin_v, last))
    return PointTripleSearch(plans, search.certified, search.exhaustive)


def surface_triple_plans(solid: Solid, mu: float, alpha: float, top: int | None = 10,
                         margin: float = DEFAULT_MARGIN_DEG, floor: float = 0.0,
                         candidates: int = TRIPLE_CANDIDATES) -> list[SurfaceTriplePlan]:
    """Certified regions of three point fingers with friction across the facets of
    curved surfaces, largest first, at most ``top``, each larger than ``floor``:
    ``alpha = atan(mu) - margin`` (radians).  Triples of seeds (module docstring) are
    ranked by how well their normals balance a force (the slack ``sin(alpha)`` less
    :func:`~fcgrasp.spatial.triples._unbalance`) times the inscribed radius of their
    triangle (the certificate's radius grows with both); the first ``candidates`` are
    certified
    (:func:`_triple_radius`) with each seed's patch about its own normal at the three
    spreads, the largest kept.  A lower bound: not every triple is certified."""
    if alpha <= 0:
        return []
    normals, adj, facet_of = _graph(solid)
    areas = np.asarray(solid.mesh.area_faces, float)
    seeds = np.array(_seeds(normals, adj, areas, SPREADS[0] * alpha), np.intp)
    if len(seeds) < 3:
        return []
    where = solid.triangles[seeds].mean(axis=1)
    trio = np.array(list(combinations(range(len(seeds)), 3)), np.intp)
    slack = math.sin(alpha) - _unbalance(normals[seeds][trio])
    pts = where[trio]
    sides = np.linalg.norm(pts - np.roll(pts, 1, axis=1), axis=2)
    area = 0.5 * np.linalg.norm(np.cross(pts[:, 1] - pts[:, 0], pts[:, 2] - pts[:, 0]),
                                axis=1)
    score = slack * 2 * area / np.maximum(sides.sum(axis=1), TINY)   # their inradius
    keep = np.flatnonzero(slack > 0)
    keep = keep[np.argsort(-score[keep], kind="stable")][:candidates]
    made: dict[tuple[int, float], _Patch] = {}

    def patch(seed: int, f: float) -> _Patch:
        if (seed, f) not in made:
            tris = _grow(seed, (normals @ normals[seed] >= math.cos(f * alpha)).tolist(),
                         adj)
            got = _patch(solid, seed, f * alpha, tris, normals)
            _kernel(solid, got)
            made[seed, f] = got
        return made[seed, f]

    floor = max(floor, CONE_PROGRAM_TOL * solid.size)
    found: list[tuple[float, tuple[_Patch, ...], float, FloatArray]] = []
    for t in keep.tolist():
        best: tuple[float, tuple[_Patch, ...], float, FloatArray] | None = None
        for f in SPREADS:
            trip = tuple(patch(int(seeds[x]), f) for x in trio[t])
            sets = [set(p.triangles.tolist()) for p in trip]
            if sets[0] & sets[1] or sets[1] & sets[2] or sets[0] & sets[2]:
                continue                       # two fingers would share a triangle
            r, delta, points = _triple_radius(trip, [p.middle for p in trip], alpha)
            if r > floor and (best is None or r > best[0]):
                best = (r, trip, delta, points)
        if best is not None:
            found.append(best)
    found.sort(key=lambda e: -e[0])
    return [_triple_plan(solid, list(trip), r, delta, points, mu, margin, facet_of)
            for r, trip, delta, points in found[:top]]


def _triple_plan(solid: Solid, trip: list[_Patch], r: float, delta: float,
                 points: FloatArray, mu: float, margin: float, facet_of: IntArray
                 ) -> SurfaceTriplePlan:
    regions, outlines, pieces = [], [], []
    steps = np.arange(OUTLINE_STEPS) / OUTLINE_STEPS
    for p in trip:
        corners = p.middle + r * (OCTAGON @ p.frame.axes @ p.frame.axes.T)
        ring = corners[:, None, :] + steps[None, :, None] * (
            np.roll(corners, -1, axis=0) - corners)[:, None, :]
        regions.append(_lift(solid, p, corners))
        outlines.append(_lift(solid, p, ring.reshape(-1, 2)))
        pieces.append(_on_surface(solid, p, corners))
    return SurfaceTriplePlan(
        tuple(int(facet_of[p.seed]) for p in trip), (-1, -1, -1), r, points,
        np.stack(regions), np.array([p.frame.normal for p in trip]), mu, margin,
        delta=delta, surfaces=tuple(tuple(sorted({int(v) for v in facet_of[p.triangles]}))
                                    for p in trip),
        triangles=tuple(p.triangles for p in trip),
        spread=tuple(math.degrees(p.beta) for p in trip), outlines=tuple(outlines),
        surface_triangles=tuple(pieces))
