r"""Grasp sets: the complete set of force-closure grasps on chosen edges (paper section 6).

Each finger touches a *feature*: an edge (any point of a segment), a convex vertex
(a soft finger, end of section 6.3) or, for gravity, the centre of mass (a fixed point).
A feature carries the directions its force can take, an arc of directions given by
its centre angle and half-width: ``-n +- atan(mu)`` on an edge with friction, just
``-n`` without friction, the weight's direction for gravity.

* :class:`FrictionGraspSet`: two point contacts with friction on two features
  (theorems 6.3 and 6.4, eq. 41-42): the counter-overlapping sector
  :math:`\mathcal{C} = \mathcal{C}(-n_1, \phi) \cap \mathcal{C}(n_2, \phi)` and the
  edges restricted by the field-of-view constraint.  The squeezing grasps have
  ``Q - P`` in ``C``, the expanding ones (from inside a hole) in ``-C``.
* :class:`FrictionlessGraspSet`: four frictionless point contacts (algorithm 6.1,
  theorem 6.2, eq. 39-40): the parallelograms :math:`\Pi_{12}`, :math:`\Pi_{34}`, the
  counter-overlapping sector :math:`\mathcal{C}_{12} \cap -\mathcal{C}_{34}`, the
  convex regions :math:`\mathcal{R}_{12}`, :math:`\mathcal{R}_{34}`, and when empty
  which constraint of corollary 6.1 fails.  Two fingers may share an edge (section
  6.2) and one "finger" may be gravity (end of section 3.1).

:func:`grasp_set` builds one set, :func:`three_edge_grasp_sets` the three sets on three
edges, :func:`grasp_sets` iterates over every non-empty set of a polygon.

Membership is strict, as everywhere in fcgrasp: a grasp within ``tol`` of the boundary
of its set is not in it.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from itertools import combinations
from typing import TYPE_CHECKING, Any, cast

import numpy as np
import shapely
from shapely.geometry import MultiPoint

from ..core._angles import wrap as _wrap
from ..core._checks import FloatArray, check_array, check_direction, check_mu, check_tol
from ..core._geom import cross2 as _cross
from ..core._geom import direction as _dir
from ..core.sectors import (
    PAIRINGS,
    arc_intersection,
    line_meet,
    pairing_sector,
    pairing_valid,
)
from ..core.tolerances import ROUND_TOL, TINY, TOL
from .polygon import Polygon, check_polygon

__all__ = ["Feature", "Vertex", "FrictionGraspSet", "FrictionlessGraspSet", "grasp_set",
           "three_edge_grasp_sets", "grasp_sets", "FORCE_DIRECTION", "FIELD_OF_VIEW",
           "SOFT_HALF_ANGLE_CAP"]
from ._features import (
    FIELD_OF_VIEW,
    FORCE_DIRECTION,
    SOFT_HALF_ANGLE_CAP,
    Feature,
    Vertex,
    _fov_interval,
    _on_feature,
    edge_feature,
    gravity_feature,
    vertex_feature,
)

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


# ----------------------------------------------------------------------------- two fingers


class FrictionGraspSet:
    """Grasp set of two point contacts with friction (theorems 6.3, 6.4; eq. 41-42).

    Attributes
    ----------
    features : tuple of Feature
        Where fingers 1 and 2 go.
    sector : (float, float)
        Counter-overlapping sector ``C`` as (centre angle, half-width); the half-width is
        negative when it is empty.
    restricted : dict
        ``{"squeeze": ((t0, t1) or None, (u0, u1) or None), "expand": ...}``: the
        parameter intervals of ``e'_1`` and ``e'_2`` on the two features for each mode.
    """

    def __init__(self, polygon: Polygon, features: tuple[Feature, Feature], mu: float,
                 tol: float = TOL) -> None:
        self.polygon = polygon
        self.features = features
        self.mu = float(mu)
        self.tol = tol
        f1, f2 = features
        c, h = arc_intersection(f1.center, f1.half, f2.center + np.pi, f2.half)
        self.sector = (float(c), float(h))
        self.restricted: dict[str, tuple[tuple[float, float] | None,
                                         tuple[float, float] | None]] = {}
        for mode, sgn in (("squeeze", 1.0), ("expand", -1.0)):
            if h <= tol:
                self.restricted[mode] = (None, None)
                continue
            k1, k2 = _dir(c + sgn * 0.0 - h), _dir(c + h)
            if sgn < 0:
                k1, k2 = -k1, -k2
            # P in f2 (+) (-C_mode), Q in f1 (+) C_mode
            r1 = _fov_interval(f1, f2, -k1, -k2, tol)
            r2 = _fov_interval(f2, f1, k1, k2, tol)
            self.restricted[mode] = (r1, r2) if r1 is not None and r2 is not None else (None, None)

    # ------------------------------------------------------------------ queries
    @property
    def edges(self) -> tuple[int | None, ...]:
        return tuple(f.index for f in self.features)

    @property
    def is_empty(self) -> bool:
        return all(r[0] is None for r in self.restricted.values())

    def restricted_segments(self, finger: int) -> list[FloatArray]:
        """The restricted feature ``e'_finger`` as segments (one per mode), shape (2, 2) each."""
        f = self.features[finger]
        out = []
        for r in self.restricted.values():
            if r[finger] is not None:
                out.append(f.point_at(np.array(r[finger])))
        return out

    def contains(self, p: Any, q: Any) -> np.ndarray:
        """Whether the grasps with finger 1 at ``p`` and finger 2 at ``q`` are in the set.

        Parameters
        ----------
        p, q : array_like, shape (..., 2)

        Returns
        -------
        ndarray of bool, shape (...)
        """
        p = check_array(p, "p", last=2)
        q = check_array(q, "q", last=2)
        p, q = np.broadcast_arrays(p, q)
        tol_len = self.tol * self.polygon.size
        on = _on_feature(self.features[0], p, tol_len) & _on_feature(self.features[1], q, tol_len)
        c, h = self.sector
        d = q - p
        dn = np.hypot(d[..., 0], d[..., 1])
        ang = np.arctan2(d[..., 1], d[..., 0])
        lim = h - self.tol
        inside = (np.abs(_wrap(ang - c)) < lim) | (np.abs(_wrap(ang - c - np.pi)) < lim)
        return cast("np.ndarray", on & inside & (dn > tol_len))

    def partners(self, p: Any, mode: str = "squeeze") -> tuple[float, float] | None:
        """Parameter interval on feature 2 of the partners of ``p`` in ``mode``."""
        c, h = self.sector
        k1, k2 = _dir(c - h), _dir(c + h)
        if mode == "expand":
            k1, k2 = -k1, -k2
        pt = Feature("vertex", None, np.asarray(p, float), np.asarray(p, float), 0.0, 0.0)
        return _fov_interval(self.features[1], pt, k1, k2, 0.0)

    def sample(self, n: int, rng: np.random.Generator | None = None
               ) -> tuple[FloatArray, FloatArray]:
        """Draw ``n`` grasps of the set: ``P`` uniform on ``e'_1``, then ``Q`` uniform among
        the partners of ``P``.  Returns ``(P, Q)``, each shape (n, 2)."""
        if self.is_empty:
            raise ValueError("cannot sample an empty grasp set")
        rng = np.random.default_rng() if rng is None else rng
        modes = [(m, r1) for m, (r1, _) in self.restricted.items() if r1 is not None]
        weights = np.array([max(r1[1] - r1[0], ROUND_TOL) for _, r1 in modes])
        ps, qs = [], []
        got = 0
        for _ in range(200):
            pick = rng.choice(len(modes), size=n, p=weights / weights.sum())
            for mi, (mode, r1) in enumerate(modes):
                k = int(np.sum(pick == mi))
                if k == 0:
                    continue
                t = r1[0] + (r1[1] - r1[0]) * rng.random(k)
                p = self.features[0].point_at(t)
                for pp in p:
                    iv = self.partners(pp, mode)
                    if iv is None:
                        continue
                    u = iv[0] + (iv[1] - iv[0]) * rng.random()
                    ps.append(pp)
                    qs.append(self.features[1].point_at(u))
            p_arr, q_arr = np.array(ps).reshape(-1, 2), np.array(qs).reshape(-1, 2)
            keep = self.contains(p_arr, q_arr)
            ps, qs = list(p_arr[keep]), list(q_arr[keep])
            got = len(ps)
            if got >= n:
                break
        if got < n:
            raise RuntimeError(f"could only sample {got} of {n} grasps from a very thin set")
        return np.array(ps[:n]), np.array(qs[:n])

    def __repr__(self) -> str:
        names = ", ".join(f.label() for f in self.features)
        return f"FrictionGraspSet({names}, mu={self.mu}, empty={self.is_empty})"


# ----------------------------------------------------------------------------- four fingers


def _hull_coords(geom: Any) -> FloatArray:
    """Vertices of the convex hull of a shapely geometry (polygon, segment or point)."""
    hull = geom.convex_hull
    if hull.geom_type == "Polygon":
        return np.asarray(hull.exterior.coords)
    return np.asarray(hull.coords)



def _back_project(f: Feature, x: FloatArray) -> FloatArray:
    """The point of feature ``f`` whose line of force passes through ``x``."""
    d = f.b - f.a
    ln2 = float(d @ d)
    if ln2 == 0.0:
        return f.a.copy()
    return f.a + float((x - f.a) @ d) / ln2 * d


def _sample_geometry(geom: Any, k: int, rng: np.random.Generator) -> FloatArray:
    """``k`` points uniform in a union of convex pieces (by area; by length if flat)."""
    parts = list(getattr(geom, "geoms", [geom]))
    parts = [g for g in parts if not g.is_empty]
    areas = np.array([g.area for g in parts])
    if areas.sum() > 0:
        tris, weights = [], []
        for g in parts:
            if g.area <= 0:
                continue
            v = np.asarray(g.convex_hull.exterior.coords)[:-1]
            for i in range(1, len(v) - 1):
                t = np.stack([v[0], v[i], v[i + 1]])
                tris.append(t)
                weights.append(abs(_cross(t[1] - t[0], t[2] - t[0])) / 2)
        tri = np.array(tris)
        w = np.array(weights)
        pick = rng.choice(len(tri), size=k, p=w / w.sum())
        r1, r2 = rng.random(k), rng.random(k)
        flip = r1 + r2 > 1
        r1[flip], r2[flip] = 1 - r1[flip], 1 - r2[flip]
        t = tri[pick]
        points = t[:, 0] + r1[:, None] * (t[:, 1] - t[:, 0]) + r2[:, None] * (t[:, 2] - t[:, 0])
        return cast("FloatArray", points)
    segs: list[FloatArray] = []
    seg_weights: list[float] = []
    for g in parts:
        cs = _hull_coords(g)
        if len(cs) == 1:
            segs.append(np.stack([cs[0], cs[0]]))
            seg_weights.append(0.0)
        for i in range(len(cs) - 1):
            segs.append(cs[i:i + 2])
            seg_weights.append(float(np.hypot(*(cs[i + 1] - cs[i]))))
    seg = np.array(segs)
    w = np.array(seg_weights) + TINY
    pick = rng.choice(len(seg), size=k, p=w / w.sum())
    u = rng.random(k)[:, None]
    return cast("FloatArray", seg[pick, 0] + u * (seg[pick, 1] - seg[pick, 0]))


class FrictionlessGraspSet:
    """Grasp set of four frictionless point contacts (algorithm 6.1, theorem 6.2).

    Attributes
    ----------
    features : tuple of 4 Feature
    pairing : tuple of 4 int or None
        The order ``(a, b, c, d)`` pairing fingers ``a, b`` against ``c, d`` whose sectors
        ``C_ab``, ``C_cd`` are non-null (None if no pairing has two non-null sectors).
    sector : (float, float)
        ``C = C_ab & -C_cd`` as (centre angle, half-width), negative half-width if empty.
    pi12, pi34 : shapely geometry
        The parallelograms :math:`\\Pi_{ab}`, :math:`\\Pi_{cd}` (segments or points when a
        feature is a point).
    r12, r34 : shapely geometry
        The regions :math:`\\mathcal{R}_{ab}`, :math:`\\mathcal{R}_{cd}` of eq. 40.
    failure : str or None
        ``"force-direction"`` or ``"field-of-view"`` (corollary 6.1) when empty.
    """

    def __init__(self, polygon: Polygon, features: Sequence[Feature], tol: float = TOL) -> None:
        self.polygon = polygon
        self.features = tuple(features)
        self.tol = tol
        dirs = np.array([f.direction for f in self.features])
        self.pairing: tuple[int, int, int, int] | None = None
        self.sector = (0.0, -1.0)
        centers = np.array([f.center for f in self.features])
        for order in PAIRINGS:
            if not pairing_valid(dirs, order, tol):
                continue
            sec = pairing_sector(centers, order)
            self.pairing = (int(order[0]), int(order[1]), int(order[2]), int(order[3]))
            self.sector = (float(sec[0]), float(sec[1]))
            break
        self.pi12 = self.pi34 = self.r12 = self.r34 = None
        self.failure: str | None = None
        if self.pairing is None or self.sector[1] <= tol:
            self.failure = FORCE_DIRECTION
            return
        a, b, c, d = self.pairing
        self.pi12 = self._parallelogram(a, b)
        self.pi34 = self._parallelogram(c, d)
        self.r12 = self._region(self.pi12, self.pi34, toward=+1)
        self.r34 = self._region(self.pi34, self.pi12, toward=-1)
        if self.r12.is_empty or self.r34.is_empty:
            self.failure = FIELD_OF_VIEW

    def _parallelogram(self, a: int, b: int) -> Any:
        fa, fb = self.features[a], self.features[b]
        pts = [line_meet(pa, fa.direction, pb, fb.direction)
               for pa in (fa.a, fa.b) for pb in (fb.a, fb.b)]
        return MultiPoint(pts).convex_hull

    def _region(self, own: Any, other: Any, toward: int) -> Any:
        """Points of ``own`` seeing ``other`` through the two-sided sector ``+-C``.

        R_12 = Pi_12 & (Pi_34 (+) -C  |  Pi_34 (+) C): P34 - P12 in +-C.
        """
        c, h = self.sector
        k1, k2 = _dir(c - h), _dir(c + h)
        coords = _hull_coords(own)
        oc = _hull_coords(other)
        span = float(np.max(np.ptp(np.concatenate([coords, oc]), axis=0))) + 1.0
        far = 4.0 * span + float(np.max(np.abs(np.concatenate([coords, oc]))))
        pieces = []
        for sgn in (1.0, -1.0):
            # own point X with Y - X in sgn*C for some Y in other  <=>  X in other (+) (-sgn C)
            kk1, kk2 = -sgn * k1, -sgn * k2
            hull = MultiPoint(np.concatenate([oc, oc + far * kk1, oc + far * kk2])).convex_hull
            pieces.append(own.intersection(hull))
        return shapely.union(pieces[0], pieces[1])

    # ------------------------------------------------------------------ queries
    @property
    def edges(self) -> tuple[int | None, ...]:
        return tuple(f.index for f in self.features)

    @property
    def is_empty(self) -> bool:
        return self.failure is not None

    def restricted_interval(self, finger: int) -> tuple[float, float] | None:
        """Parameter interval of the feature of ``finger`` that back-projects from its region."""
        if self.is_empty:
            return None
        assert self.pairing is not None
        pos = self.pairing.index(finger)
        region = self.r12 if pos < 2 else self.r34
        f = self.features[finger]
        if f.length == 0:
            return (0.0, 1.0)
        t, _ = f.param_of(_hull_coords(region))
        lo, hi = max(0.0, float(t.min())), min(1.0, float(t.max()))
        return (lo, hi) if hi > lo else None

    def contains(self, *points: Any) -> np.ndarray:
        """Whether the grasps with fingers at ``P1, P2, P3, P4`` are in the set (batched).

        The lines of force of the paired fingers meet at ``P12`` and ``P34``; the grasp is
        in the set iff ``P34 - P12`` lies strictly inside ``C`` or ``-C`` (corollary 5.2).
        """
        if len(points) != 4:
            raise TypeError(f"contains takes four point arrays, got {len(points)}")
        pts = [check_array(p, f"P{i + 1}", last=2) for i, p in enumerate(points)]
        pts = list(np.broadcast_arrays(*pts))
        shape = pts[0].shape[:-1]
        if self.is_empty:
            return np.zeros(shape, dtype=bool)
        assert self.pairing is not None
        tol_len = self.tol * self.polygon.size
        on = np.ones(shape, dtype=bool)
        for f, p in zip(self.features, pts, strict=True):
            on &= _on_feature(f, p, tol_len)
        a, b, c, d = self.pairing
        fa, fb, fc, fd = (self.features[i].direction for i in (a, b, c, d))
        p12 = line_meet(pts[a], fa, pts[b], fb)
        p34 = line_meet(pts[c], fc, pts[d], fd)
        v = p34 - p12
        vn = np.hypot(v[..., 0], v[..., 1])
        ang = np.arctan2(v[..., 1], v[..., 0])
        cen, h = self.sector
        lim = h - self.tol
        inside = (np.abs(_wrap(ang - cen)) < lim) | (np.abs(_wrap(ang - cen - np.pi)) < lim)
        return cast("np.ndarray", on & inside & (vn > tol_len))

    def sample(self, n: int, rng: np.random.Generator | None = None) -> tuple[FloatArray, ...]:
        """Draw ``n`` grasps of the set: ``P12`` uniform in :math:`\\mathcal{R}_{12}`, then
        ``P34`` uniform in the part of :math:`\\Pi_{34}` it sees through ``+-C``, each
        back-projected onto its edges (algorithm 6.1, step 5).  Returns four arrays of
        shape (n, 2), in the order of the features."""
        if self.is_empty:
            raise ValueError(f"cannot sample an empty grasp set ({self.failure} constraint fails)")
        rng = np.random.default_rng() if rng is None else rng
        assert self.pairing is not None and self.pi34 is not None
        a, b, c, d = self.pairing
        cen, h = self.sector
        k1, k2 = _dir(cen - h), _dir(cen + h)
        far = 4.0 * float(np.max(np.ptp(np.concatenate([_hull_coords(self.pi12),
                                                        _hull_coords(self.pi34)]), axis=0)) + 1)
        found: list[FloatArray] = []
        need = n
        for _ in range(50):
            p12 = _sample_geometry(self.r12, need, rng)
            rows: list[FloatArray] = []
            for x in p12:
                cones = [MultiPoint([x, x + far * s * k1, x + far * s * k2]).convex_hull
                         for s in (1.0, -1.0)]
                part = shapely.union(self.pi34.intersection(cones[0]),
                                     self.pi34.intersection(cones[1]))
                if part.is_empty:
                    continue
                y = _sample_geometry(part, 1, rng)[0]
                pts: list[Any] = [None] * 4
                for idx, src in ((a, x), (b, x), (c, y), (d, y)):
                    pts[idx] = _back_project(self.features[idx], src)
                rows.append(np.stack(pts))
            if rows:
                arr = np.stack(rows)                                  # (m, 4, 2)
                ok = self.contains(*(arr[:, i] for i in range(4)))
                found.extend(arr[ok])
                need = n - len(found)
            if need <= 0:
                break
        if need > 0:
            raise RuntimeError(f"could only sample {n - need} of {n} grasps from a very thin set")
        out = np.stack(found[:n])
        return tuple(out[:, i] for i in range(4))

    def __repr__(self) -> str:
        names = ", ".join(f.label() for f in self.features)
        state = "empty: " + self.failure if self.failure else "non-empty"
        return f"FrictionlessGraspSet({names}; {state})"


# ----------------------------------------------------------------------------- builders


def _features(poly: Polygon, items: Sequence[Any], mu: float) -> list[Feature]:
    feats = []
    for it in items:
        if isinstance(it, Vertex):
            if not 0 <= int(it) < poly.n_edges:
                raise ValueError(f"edges holds {it!r}, not a vertex of this polygon")
            feats.append(vertex_feature(poly, int(it), mu))
        else:
            (i,) = poly.check_edges([it])
            feats.append(edge_feature(poly, i, mu))
    return feats


def grasp_set(polygon: Polygon, edges: Sequence[Any], mu: float = 0.0,
              gravity: ArrayLike | None = None,
              tol: float = TOL) -> FrictionGraspSet | FrictionlessGraspSet:
    """The complete set of force-closure grasps on the given edges.

    Parameters
    ----------
    polygon : Polygon
    edges : sequence
        Two features (edge indices, or :class:`Vertex` for a soft finger at a convex
        vertex) for two fingers with friction; four edge indices (repeats allowed: two
        fingers on one edge, section 6.2) for four frictionless fingers; three edge
        indices with ``gravity`` for three frictionless fingers held under gravity.
    mu : float
        Friction coefficient (two fingers).  Four-finger sets are frictionless.
    gravity : array_like, shape (2,), optional
        Direction of the weight, counted as a frictionless contact at the centroid.
    tol : float
        Membership tolerance.

    Examples
    --------
    >>> sq = Polygon([[0, 0], [1, 0], [1, 1], [0, 1]])
    >>> gs = grasp_set(sq, (1, 3), mu=0.2)
    >>> bool(gs.contains([1, 0.5], [0, 0.55])), bool(gs.contains([1, 0.1], [0, 0.9]))
    (True, False)
    """
    polygon = check_polygon(polygon)
    tol = check_tol(tol)
    mu_v = float(check_mu(mu, "mu"))
    items = list(edges)
    if len(items) == 2:
        if gravity is not None:
            raise ValueError("gravity is counted with three or four frictionless fingers, "
                             "not with two")
        f = _features(polygon, items, mu_v)
        return FrictionGraspSet(polygon, (f[0], f[1]), mu_v, tol)
    if any(isinstance(e, Vertex) for e in items):
        raise ValueError("soft fingers (Vertex) are supported in two-finger grasp sets only")
    if mu_v != 0.0:
        raise ValueError(f"grasp sets of {len(items)} fingers are frictionless: mu must be 0, "
                         f"got {mu}")
    if len(items) == 4 and gravity is None:
        return FrictionlessGraspSet(polygon, _features(polygon, items, 0.0), tol)
    if len(items) == 3 and gravity is not None:
        return FrictionlessGraspSet(polygon, [*_features(polygon, items, 0.0),
                                              gravity_feature(polygon, gravity)], tol)
    raise ValueError(f"edges must hold 2 features (friction), 4 edges (frictionless) or 3 "
                     f"edges with gravity, got {len(items)}"
                     + (" with gravity" if gravity is not None else ""))


def three_edge_grasp_sets(polygon: Polygon, edges: Sequence[int], tol: float = TOL
                          ) -> list[FrictionlessGraspSet]:
    """The three grasp sets of four frictionless fingers on three edges (section 6.2):
    ``G(e1, e2, e1, e3)``, ``G(e1, e2, e2, e3)`` and ``G(e1, e3, e2, e3)``."""
    e1, e2, e3 = polygon.check_edges(edges)
    return [grasp_set(polygon, t, tol=tol)  # type: ignore[misc]
            for t in ((e1, e2, e1, e3), (e1, e2, e2, e3), (e1, e3, e2, e3))]


def _spans_all_directions(dirs: FloatArray, tol: float) -> np.ndarray:
    """Batched: do the direction sets (..., k, 2) positively span the plane? (pruning)"""
    from ..core.closure import force_direction_closure

    return force_direction_closure(dirs, tol)


def grasp_sets(polygon: Polygon, fingers: int = 2, mu: float = 0.0, soft: bool = False,
               gravity: ArrayLike | None = None, tol: float = TOL
               ) -> Iterator[FrictionGraspSet | FrictionlessGraspSet]:
    """Iterate over every non-empty grasp set of the polygon (complexity 6.1).

    ``fingers=2``: all pairs of edges with friction ``mu`` (and, with ``soft=True``, pairs
    involving soft fingers at convex vertices).  ``fingers=4``: all 4-tuples of distinct
    edges and, for every three edges, the three sets with two fingers on one edge.
    ``fingers=3``: three frictionless fingers plus gravity (default direction (0, -1)).
    Candidates whose force directions cannot span the plane (the force-direction
    constraint) are pruned in one vectorised pass before any set is built.
    """
    polygon = check_polygon(polygon)
    if fingers not in (2, 3, 4) or isinstance(fingers, bool):
        raise ValueError(f"fingers must be 2, 3 or 4, got {fingers!r}")
    mu_v = float(check_mu(mu, "mu"))
    yield from _SETS[fingers](polygon, np.flatnonzero(polygon.usable), mu_v, soft, gravity,
                              tol)


def _pair_sets(polygon: Polygon, idx: np.ndarray, mu: float, soft: bool, gravity: ArrayLike | None,
               tol: float) -> Iterator[FrictionGraspSet | FrictionlessGraspSet]:
    """Two fingers: every pair of edges (and of soft fingers at convex vertices)."""
    feats: list[Any] = [int(i) for i in idx]
    if soft:
        conv = polygon.convex_vertices()
        feats += [Vertex(int(e)) for e in idx if conv[polygon.previous_edge(int(e))]]
    for a, b in combinations(feats, 2):
        gs = grasp_set(polygon, (a, b), mu=mu, tol=tol)
        if not gs.is_empty:
            yield gs


def _quad_sets(polygon: Polygon, idx: np.ndarray, mu: float, soft: bool, gravity: ArrayLike | None,
               tol: float) -> Iterator[FrictionGraspSet | FrictionlessGraspSet]:
    """Four frictionless fingers: 4-tuples, and three edges with one taken twice."""
    if mu != 0.0:
        raise ValueError(f"four-finger grasp sets are frictionless: mu must be 0, got {mu}")
    force = -polygon.normals
    quads = np.array(list(combinations(idx, 4)), dtype=int).reshape(-1, 4)
    ok = _spans_all_directions(force[quads], tol) if len(quads) else np.zeros(0, bool)
    for q in quads[ok]:
        gs = grasp_set(polygon, tuple(int(x) for x in q), tol=tol)
        if not gs.is_empty:
            yield gs
    trips = np.array(list(combinations(idx, 3)), dtype=int).reshape(-1, 3)
    ok3 = _spans_all_directions(force[trips], tol) if len(trips) else np.zeros(0, bool)
    for t in trips[ok3]:
        for gs in three_edge_grasp_sets(polygon, tuple(int(x) for x in t), tol=tol):
            if not gs.is_empty:
                yield gs


def _gravity_sets(polygon: Polygon, idx: np.ndarray, mu: float, soft: bool,
                  gravity: ArrayLike | None,
                  tol: float) -> Iterator[FrictionGraspSet | FrictionlessGraspSet]:
    """Three frictionless fingers and gravity (default straight down)."""
    g = check_direction((0.0, -1.0) if gravity is None else gravity, "gravity")
    force = -polygon.normals
    trips = np.array(list(combinations(idx, 3)), dtype=int).reshape(-1, 3)
    if len(trips) == 0:
        return
    dirs = np.concatenate([force[trips], np.broadcast_to(g, (len(trips), 1, 2))], axis=1)
    for t in trips[_spans_all_directions(dirs, tol)]:
        gs = grasp_set(polygon, tuple(int(x) for x in t), gravity=g, tol=tol)
        if not gs.is_empty:
            yield gs


#: The grasp sets :func:`grasp_sets` enumerates, by number of fingers.
_SETS = {2: _pair_sets, 3: _gravity_sets, 4: _quad_sets}
