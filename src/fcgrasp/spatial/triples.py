r"""Independent regions of three point contacts with friction on a solid (the
second primitive of the paper's conclusion, "grasps with three point contacts with
friction").

**The certificate.**  Take three contacts at nominal points ``c_i`` of three facets, and
the wrench generators ``w = (f, (c_i - o) x f)`` of each contact's friction pyramid
inscribed in its cone of half-angle ``alpha = atan(mu) - margin`` (eight edges, each
force of unit length; :func:`~fcgrasp.spatial.contacts.contact_wrench_generators`).
Let ``W`` be their convex hull and ``S`` its slice at zero force: the moments that unit
weights of zero net force make.  If ``W`` holds the origin in its interior and ``S``
holds the ball of radius ``delta`` about it, then **every** grasp that moves each finger
by less than ``delta`` within its facet is in force closure (theorem 3.1, in 6-D).

*Proof.*  For a unit wrench ``u = (u_f, u_m)`` the support ``h_W(u) = max_j u . w_j``
is at least ``delta |u_m|`` (the ball in the slice) and positive (the origin inside).
Moving contact ``i`` by ``d_i`` changes each of its generators by ``(0, d_i x f)``, of
length at most ``|d_i|``, so the moved generators' support is at least ``h_W(u) -
|d| |u_m| > 0`` for every ``u``: their hull still holds the origin inside, their cones
span the wrench space, and the pyramids lie inside the friction cones.  The slice does
not depend on the point ``o`` moments are taken about, so neither does ``delta``.

``delta`` is the smallest ratio ``b / |n_m|`` over the hull's facets ``n . w <= b``
(qhull), less a rounding.  The regions are regular octagons of circumradius ``r =
min(delta, the octagons' fits in their pieces)`` about the centres, each turned along its
facet's first axis: inside the discs of radius ``delta``, so every triple of points, one
in each region, holds.  This is a **certified lower bound**, not the optimum: the
certificate lets each generator move on its own, where a contact's generators move
together.  The gap, measured on the built-in solids by bisecting the radius at which
some triple of the octagons' corners fails the exact cone program
(:func:`~fcgrasp.spatial.closure.closure_margin`), is printed by
``benchmarks/bench_solids.py``.

:func:`point_triple_regions` starts each centre at its octagon's largest fit in the piece
and improves the three centres by a pattern search on ``r``.  :func:`point_triple_plans`
searches triples of convex pieces on three facets, best bound first (the smallest of
the three octagons' fits: no region can exceed it), skips triples whose friction cones
cannot balance a force (a necessary condition, batched), and stops when the bound
cannot enter the top ``top`` or after ``max_triples`` certificates (then the search is
not exhaustive; :attr:`PointTripleSearch.exhaustive` says which).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core._checks import FloatArray, check_int
from ..core.budget import cut_if_over
from ..core.tolerances import HULL_ROUNDING, TOL
from ._pieces import Halfplanes, _piece_table, own_octagon_fit
from ._slice import forces_radius, slice_radius, slice_radius_at
from .contacts import check_spatial_contacts, contact_frames
from .regions import (
    DEFAULT_MARGIN_DEG,
    OCTAGON,
    OctagonPlan,
    checked_cone,
)
from .solid import Solid

__all__ = ["PointTriplePlan", "PointTripleSearch", "perturbation_radius",
           "point_triple_regions", "point_triple_plans", "DEFAULT_MAX_TRIPLES"]

#: The certificates :func:`point_triple_plans` computes at most (about 2 ms each).
DEFAULT_MAX_TRIPLES = 600

#: Edges of the friction pyramid inscribed in each cone.
PYRAMID_EDGES = 8

#: Steps of the pattern search on the centres (each tries 12 moves).
REFINE_STEPS = 6


@dataclass(frozen=True)
class PointTriplePlan(OctagonPlan):
    """Regions of three point fingers with friction (:class:`~fcgrasp.spatial.regions.
    OctagonPlan`: three facets, three octagons, each finger anywhere in its octagon), and
    ``delta`` (the certificate's radius at these centres, before the fits)."""

    delta: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        d = self._octagon_dict("friction")
        d.update({"certificate_radius": self.delta, "bound": "certified lower bound"})
        return self._with_similar(d)


@dataclass(frozen=True)
class PointTripleSearch:
    """What :func:`point_triple_plans` searched: ``plans`` (largest first), how many
    triples of pieces it certified (``certified``: those whose cones could balance a
    force), and whether it was ``exhaustive`` (it stopped on the bound, not on
    ``max_triples``)."""

    plans: list[PointTriplePlan]
    certified: int
    exhaustive: bool


def _generators(points: FloatArray, normals: FloatArray, alpha: Any,
                forces: FloatArray | None = None) -> FloatArray:
    """The inscribed pyramids' wrench generators (..., 3 * PYRAMID_EDGES, 6): unit forces
    ``(n + tan(alpha) (cos a t_1 + sin a t_2)) cos(alpha)`` and their moments about the
    contacts' mean over the contacts' reach ``L`` (their largest distance from it; the
    slice's radius is then in units of ``L``); ``alpha`` one half-angle, or one per
    contact (..., 3).  ``forces``: :func:`_pyramid_forces` of these normals and
    ``alpha``, where the caller has them (a triple's moves keep its normals)."""
    f = _pyramid_forces(normals, alpha) if forces is None else forces
    arm = points - points.mean(axis=-2, keepdims=True)
    m = np.cross(arm[..., None, :], f)
    # moments over the contacts' reach, so that the hull's rounding is the part's scale's
    reach = np.max(np.linalg.norm(arm, axis=-1), axis=-1)[..., None, None]
    m = m / np.maximum(reach, TOL)
    w = np.concatenate([f, m], axis=-1)                          # (..., 3, edges, 6)
    return w.reshape(*w.shape[:-3], -1, 6)


def _pyramid_forces(normals: FloatArray, alpha: Any) -> FloatArray:
    """The unit forces of :func:`_generators` (..., 3, PYRAMID_EDGES, 3)."""
    t1, t2 = contact_frames(normals)
    a = 2 * np.pi * np.arange(PYRAMID_EDGES) / PYRAMID_EDGES
    if np.ndim(alpha) == 0:
        cos_a, tan_a = math.cos(alpha), math.tan(alpha)
    else:
        cos_a = np.cos(np.asarray(alpha, float))[..., None, None]
        tan_a = np.tan(np.asarray(alpha, float))[..., None, None]
    return np.asarray(cos_a * (normals[..., None, :] + tan_a * (
        np.cos(a)[:, None] * t1[..., None, :] + np.sin(a)[:, None] * t2[..., None, :])))


def _reach(points: FloatArray) -> float:
    """The contacts' largest distance from their mean: the unit of
    :func:`_generators`' moments, and so of the slice's radius."""
    return float(np.max(np.linalg.norm(points - points.mean(axis=0), axis=1)))


def _certificate(points: FloatArray, normals: FloatArray, alpha: Any) -> float:
    """The certified radius (module docstring) of three contacts, in lengths (``alpha``
    one half-angle, or one per contact)."""
    return _reach(points) * _slice_radius(_generators(points, normals, alpha))


def _facet_bound(w: FloatArray, facets: FloatArray) -> float:
    """An upper bound of :func:`_slice_radius` of the wrenches ``w`` (n, 6) from any
    directions ``facets`` (k, 6): a ball of radius ``delta`` in the zero-force slice lies
    in the hull only if, along each direction ``c``, the hull reaches ``delta |c_m|``
    (``max_i w_i . c >= delta |c_m|``).  The facets of a nearby hull (the same triple
    with one centre moved) make it nearly the radius itself."""
    moment = np.linalg.norm(facets[:, 3:6], axis=1)
    live = moment > 0
    if not live.any():
        return np.inf
    reach = (w @ facets[live].T).max(axis=0)
    return float(np.min(reach / moment[live]))


def _slice_radius(w: FloatArray) -> float:
    """The largest ``delta`` with the moment ball of radius ``delta`` in the zero-force
    slice of the hull of ``w`` (n, 6), 0 when the hull does not hold the origin inside
    (or is flat): the smallest ``b / |n_m|`` over its facets, less the rounding
    (:func:`_hull_slice_radius`).  Read from the slice's own vertices where the compiled
    loops run (:data:`SLICE_VERTICES`); else, or where those leave it to the hull, 0 at
    once where a direction with every wrench on or behind it is found
    (:func:`_separated`: a third of the triples of a search on a mesh, each a 6-D hull
    spared), and the hull's otherwise."""
    return _slice(w)[0]


def _slice(w: FloatArray, forces_inradius: float | None = None
           ) -> tuple[float, FloatArray | None]:
    """:func:`_slice_radius` and the facet normals of the hull it was read from (None
    where no hull was needed, or none exists); ``forces_inradius``: that of ``w``'s
    forces (:func:`fcgrasp.spatial._slice.forces_radius`), where the caller has it."""
    fast = slice_radius(w, PYRAMID_EDGES, forces_inradius) if SLICE_VERTICES else None
    if fast is not None:
        return fast, None
    if _separated(w):
        return 0.0, None
    return _hull_slice(w)


#: Whether :func:`_slice` reads the slice's radius from the slice's vertices
#: (:mod:`fcgrasp.spatial._slice`: the same radius to rounding, a fifth of the time)
#: before it builds the 6-D hull (False: the hull alone, the reference).
SLICE_VERTICES = True

#: Steps :func:`_separated` takes at most in search of a direction that separates.
SEPARATE_STEPS = 20


def _separated(w: FloatArray) -> bool:
    """Whether a unit direction ``c`` with ``w @ c <= 0`` for every wrench is found (the
    origin then not inside the hull of ``w``: no ball around it there, theorem 4.2's
    test fails), by a few perceptron steps from the wrenches' opposite mean: each moves
    ``c`` away from the wrenches in front of it.  False says nothing."""
    c = -w.sum(axis=0)
    for _ in range(SEPARATE_STEPS):
        norm = float(np.linalg.norm(c))
        if not norm > 0:
            return False
        c = c / norm
        d = w @ c
        ahead = d > 0
        if not ahead.any():
            return True
        c = c - 0.5 * w[ahead].mean(axis=0)
    return False


def _hull_slice_radius(w: FloatArray) -> float:
    """:func:`_slice_radius` from the hull of ``w`` (qhull): the reference."""
    return _hull_slice(w)[0]


def _hull_slice(w: FloatArray) -> tuple[float, FloatArray | None]:
    """:func:`_hull_slice_radius` and the hull's facet normals (k, 6; None where there is
    no hull)."""
    from scipy.spatial import ConvexHull, QhullError

    try:
        eq = ConvexHull(w).equations
    except (QhullError, ValueError):
        return 0.0, None                             # flat: the wrenches do not span
    b = -eq[:, 6]
    scale = float(np.max(np.linalg.norm(w, axis=1)))
    if np.any(b <= HULL_ROUNDING * scale):
        return 0.0, eq[:, :6]
    moment = np.linalg.norm(eq[:, 3:6], axis=1)
    with np.errstate(divide="ignore"):
        delta = float(np.min(np.where(moment > 0, b / moment, np.inf)))
    return max(delta - HULL_ROUNDING * scale, 0.0), eq[:, :6]


#: Whether a triple's refinement skips the hull of a move whose bound from the last
#: hulls' facets (:func:`_facet_bound`) shows it cannot beat the radius it has
#: (False: every move's hull, the reference; the same moves are taken).  The hulls of
#: nearby centres share most of their facets: on ``featuretype.STL`` (three fingers,
#: top 10, every slice from its hull) the bound is within 9 % of the radius for half
#: the moves, and a quarter of the hulls are spared.  The facets are those of the 6-D
#: hulls built: where the slice's vertices decide (:func:`_slice`), none.
FACET_BOUND = True

#: Triples :func:`point_triple_plans` certifies between two looks at the clock.
CLOCK_TRIPLES = 16


#: The most facet normals a triple keeps for :func:`_facet_bound` (the newest hulls'
#: first): a few hulls' worth.
FACETS_KEPT = 2000


def perturbation_radius(points: Any, normals: Any, mu: Any,
                        margin: Any = DEFAULT_MARGIN_DEG) -> float:
    """How far each of three point contacts with friction may move within its tangent
    plane and the grasp stays in force closure, certified (module docstring): 0 when
    the grasp is not in force closure by its inscribed pyramids.

    >>> p = [[10.0, 0, 0], [-10.0, 0, 0], [0, 5.0, 0]]          # a 20 x 10 box's sides
    >>> n = [[-1.0, 0, 0], [1.0, 0, 0], [0, -1.0, 0]]
    >>> round(perturbation_radius(p, n, mu=0.5), 3)
    0.628
    """
    p, n, _, _ = check_spatial_contacts(points, normals)        # normals made unit
    if p.shape != (3, 3):
        raise ValueError(f"points and normals must be three contacts, shape (3, 3), got "
                         f"{p.shape}")
    _, _, alpha = checked_cone(mu, margin)
    if alpha <= 0:
        return 0.0
    return _certificate(p, n, alpha)


@dataclass
class _Triple:
    """One triple of pieces being solved: the pieces' half-planes, the octagon's
    support along each edge normal, the facets' planes."""

    halfplanes: list[Halfplanes]
    support: list[FloatArray]
    origin: FloatArray
    axes: FloatArray
    normals: FloatArray
    #: the facet normals of the last hulls computed, newest first, at most
    #: :data:`FACETS_KEPT` (:func:`_facet_bound`)
    facets: FloatArray | None = None
    #: the pyramids' forces and their hull's inradius for one half-angle (the same for
    #: every move: the normals stay), ``(alpha, forces, inradius)``
    pyramids: tuple[float, FloatArray, float | None] | None = None

    def fits(self, t: FloatArray) -> FloatArray:
        """Each octagon's largest circumradius about the 2-D centres ``t`` (3, 2)."""
        return np.array([np.min((h - E @ tt) / k) for (E, h), k, tt
                         in zip(self.halfplanes, self.support, t, strict=True)])

    def centers(self, t: FloatArray) -> FloatArray:
        return np.asarray(self.origin + np.einsum("ki,kij->kj", t, self.axes))

    def radius(self, t: FloatArray, alpha: float, beat: float = 0.0) -> tuple[float, float]:
        """``(r, delta)`` at the 2-D centres ``t``; ``(0, 0)`` when the fits alone, or
        with :data:`FACET_BOUND` the certificate's bound from the last hull's facets,
        keep ``r`` at most ``beat`` (the certificate is not computed)."""
        fits = self.fits(t)
        fit = float(np.min(fits))
        if fit <= beat:
            return 0.0, 0.0
        points = self.centers(t)
        if self.pyramids is None or self.pyramids[0] != alpha:
            forces = _pyramid_forces(self.normals, alpha)
            self.pyramids = (alpha, forces, forces_radius(forces.reshape(-1, 3)))
        if SLICE_VERTICES and self.facets is None:
            # the generators built in the compiled loop with the slice read from them
            got = slice_radius_at(points, self.pyramids[1], self.pyramids[2], TOL)
            if got is not None and got[0] is not None:
                delta = got[1] * got[0]
                return min(delta, fit), delta
        reach = _reach(points)
        w = _generators(points, self.normals, alpha, self.pyramids[1])
        if beat > 0 and FACET_BOUND and self.facets is not None and \
                min(fit, reach * max(_facet_bound(w, self.facets), 0.0)) <= beat:
            return 0.0, 0.0
        slice_, facets = _slice(w, self.pyramids[2])
        if facets is not None:
            self.facets = facets if self.facets is None else \
                np.concatenate([facets, self.facets])[:FACETS_KEPT]
        delta = reach * slice_
        return min(delta, fit), delta


def _nominal(table: Any, pieces: tuple[int, int, int]) -> tuple[_Triple, FloatArray]:
    """A triple of pieces, and its nominal centres (3, 2): each octagon's largest fit in
    its piece."""
    hps = [table.halfplanes[p] for p in pieces]
    tri = _Triple(hps, [(E @ OCTAGON.T).max(axis=1) for E, _ in hps],
                  table.origin[list(pieces)], table.axes[list(pieces)],
                  table.normal[list(pieces)])
    start = np.array([own_octagon_fit(table, p, OCTAGON)[1] for p in pieces])
    return tri, start


def _solve_triple(tri: _Triple, start: FloatArray, alpha: float, refine: bool
                  ) -> tuple[FloatArray, float, float]:
    """The centres (3, 2), radius and certificate: from ``start``, improved by a
    pattern search (each centre moved along its two axes, the step halved when no move
    helps) when ``refine``."""
    t = start.copy()
    r, delta = tri.radius(t, alpha)
    if not refine or r <= 0:
        return t, r, delta
    step = 0.5 * r
    for _ in range(REFINE_STEPS):
        moved = False
        for k in range(3):
            for axis in range(2):
                for sign in (1.0, -1.0):
                    trial = t.copy()
                    trial[k, axis] += sign * step
                    got = tri.radius(trial, alpha, beat=r)
                    if got[0] > r:
                        t, (r, delta), moved = trial, got, True
        if not moved:
            step *= 0.5
    return t, r, delta


def _plan(solid: Solid, table: Any, pieces: tuple[int, int, int], tri: _Triple,
          t: FloatArray, r: float, delta: float, mu: float, margin: float
          ) -> PointTriplePlan:
    centers = tri.centers(t)
    regions = centers[:, None, :] + r * np.einsum("qi,kij->kqj", OCTAGON, tri.axes)
    facets = tuple(int(table.facet[p]) for p in pieces)
    local = tuple(int(table.local[p]) for p in pieces)
    return PointTriplePlan(facets, local, r, centers, regions, tri.normals.copy(), mu,
                           margin, delta=delta)


def point_triple_regions(solid: Solid, facets: Any, mu: Any,
                         margin: Any = DEFAULT_MARGIN_DEG, pieces: Any = (0, 0, 0),
                         refine: bool = True) -> PointTriplePlan | None:
    """Certified octagon regions (module docstring) of three point fingers with friction
    on three facets of ``solid`` (their convex pieces ``pieces``), or None when the
    certificate finds none.

    >>> from fcgrasp.spatial.solid import demo_solid
    >>> box = demo_solid("box")                         # 40 x 20 x 10 mm
    >>> sides = [f.index for f in box.facets if abs(f.normal[2]) < 0.5][:3]
    >>> plan = point_triple_regions(box, sides, mu=0.5)
    >>> plan.facets, round(plan.radius, 2)
    ((0, 1, 4), 2.25)
    """
    mu_v, margin_v, alpha = checked_cone(mu, margin, solid)
    try:
        ids = tuple(int(f) for f in facets)
        local = tuple(int(p) for p in pieces)
    except (TypeError, ValueError):
        raise ValueError(f"facets and pieces must be three indices each, got {facets!r}, "
                         f"{pieces!r}") from None
    n = len(solid.facets)
    if len(ids) != 3 or len(set(ids)) != 3 or not all(0 <= i < n for i in ids):
        raise ValueError(f"facets must be three different facets in [0, {n}), got "
                         f"{facets!r}")
    if len(local) != 3 or not all(0 <= p < len(solid.facets[i].pieces)
                                  for i, p in zip(ids, local, strict=True)):
        raise ValueError(f"pieces must index the facets' convex pieces, got {pieces!r}")
    if alpha <= 0:
        return None
    table = _piece_table(solid)
    rows = tuple(int(table.start[i] + p) for i, p in zip(ids, local, strict=True))
    return _certify(solid, table, rows, alpha, mu_v, margin_v, refine)  # type: ignore[arg-type]


def _certify(solid: Solid, table: Any, rows: tuple[int, int, int], alpha: float,
             mu: float, margin: float, refine: bool) -> PointTriplePlan | None:
    rows = tuple(sorted(rows, key=lambda p: (int(table.facet[p]), p)))  # type: ignore[assignment]
    tri, start = _nominal(table, rows)
    t, r, delta = _solve_triple(tri, start, alpha, refine)
    if r <= 0:
        return None
    return _plan(solid, table, rows, tri, t, r, delta, mu, margin)


def _balance(normals: FloatArray, alpha: float) -> Any:
    """Whether the friction cones of half-angle ``alpha`` about three inward
    ``normals`` (T, 3, 3) span the forces (no direction ``u`` every cone force opposes:
    ``u . n_i <= -sin(alpha)`` for all three), batched (:func:`_unbalance`)."""
    return _unbalance(normals) < math.sin(alpha)


def _unbalance(normals: FloatArray) -> FloatArray:
    """The largest ``min_i u . m_i`` over unit ``u`` (``m = -n``, three inward
    ``normals`` (T, 3, 3)), batched: reached at one ``m_i``, the normalised sum of two,
    or the point equidistant from all three.  The cones of half-angle ``alpha`` balance
    a force when it is below ``sin(alpha)``."""
    m = -normals
    cands = [m[:, 0], m[:, 1], m[:, 2], m[:, 0] + m[:, 1], m[:, 1] + m[:, 2],
             m[:, 0] + m[:, 2]]
    cross = np.cross(m[:, 1] - m[:, 0], m[:, 2] - m[:, 0])
    cands += [cross, -cross]
    best = np.full(len(m), -np.inf)
    for u in cands:
        length = np.linalg.norm(u, axis=1)
        ok = length > TOL
        u = u / np.where(ok, length, 1.0)[:, None]
        val = np.min(np.einsum("tj,tkj->tk", u, m), axis=1)
        best = np.where(ok, np.maximum(best, val), best)
    return best


def point_triple_plans(solid: Solid, mu: Any, top: int | None = 10,
                       margin: Any = DEFAULT_MARGIN_DEG,
                       max_triples: int = DEFAULT_MAX_TRIPLES, refine: bool = True
                       ) -> PointTripleSearch:
    """The best certified regions of three point fingers with friction on ``solid``,
    largest first (module docstring): triples of convex pieces on three facets in
    decreasing order of their bound (the smallest octagon fit of the three), among
    equal bounds the widest triangle of centroids first; each certified at the fits'
    centres; the search stops when the bound cannot enter the top ``top`` or after
    ``max_triples`` certificates, or at the time budget (the search then recorded as cut
    short, :func:`fcgrasp.core.budget.cut_short`); the plans kept are then refined
    (:func:`point_triple_regions`) unless ``refine`` is false or the budget has ended.

    >>> from fcgrasp.spatial.solid import demo_solid
    >>> got = point_triple_plans(demo_solid("prism"), mu=0.5, top=2)
    >>> [p.facets for p in got.plans], got.exhaustive
    ([(2, 3, 4), (0, 1, 3)], True)
    """
    mu_v, margin_v, alpha = checked_cone(mu, margin, solid)
    if top is not None:
        top = check_int(top, "top", minimum=1)
    max_triples = check_int(max_triples, "max_triples", minimum=1)
    if alpha <= 0:
        return PointTripleSearch([], 0, True)
    table = _piece_table(solid)
    fit = table.own_fit
    order = np.argsort(-fit, kind="stable")
    found: list[tuple[float, tuple[int, int, int]]] = []     # (nominal radius, pieces)
    certified, exhaustive = 0, True
    for level in range(2, len(order)):
        bound = float(fit[order[level]])
        if top is not None and len(found) >= top and found[top - 1][0] >= bound:
            break
        if certified >= max_triples or cut_if_over():
            exhaustive = False
            break
        k = order[level]
        a, b = np.triu_indices(level, 1)
        a, b = order[a], order[b]
        c = np.full(len(a), k)
        fa, fb, fc = table.facet[a], table.facet[b], table.facet[c]
        keep = (fa != fb) & (fb != fc) & (fa != fc)
        a, b, c = a[keep], b[keep], c[keep]
        normals = np.stack([table.normal[a], table.normal[b], table.normal[c]], axis=1)
        keep = _balance(normals, alpha)
        a, b, c = a[keep], b[keep], c[keep]
        p, q, s = table.centroid[a], table.centroid[b], table.centroid[c]
        area = np.linalg.norm(np.cross(q - p, s - p), axis=1)
        for i in np.argsort(-area, kind="stable").tolist():
            if certified >= max_triples or certified % CLOCK_TRIPLES == 0 and cut_if_over():
                break
            rows = (int(a[i]), int(b[i]), int(c[i]))
            tri, start = _nominal(table, rows)
            r, _ = tri.radius(start, alpha)
            certified += 1
            if r > 0:
                found.append((r, rows))
                found.sort(key=lambda x: (-x[0], x[1]))
                if top is not None:
                    del found[top:]
    plans = []
    for _, rows in found:
        # past the time budget a triple keeps its nominal centres: not refined
        got = _certify(solid, table, rows, alpha, mu_v, margin_v,
                       refine and not cut_if_over())
        if got is not None:
            plans.append(got)
    plans.sort(key=lambda p: (-p.radius, p.facets, p.pieces))
    return PointTripleSearch(plans, certified, exhaustive)
