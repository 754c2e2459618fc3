"""Grasp sets (section 6): soundness and completeness against the general test of the
core on seeded random polygons, the three pairings, the field-of-view restriction."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
import fcgrasp.model.graspsets
from fcgrasp.core.contacts import friction_cone_edges
from fcgrasp.model.graspsets import (
    FIELD_OF_VIEW,
    FORCE_DIRECTION,
    FrictionlessGraspSet,
    Vertex,
    grasp_set,
    grasp_sets,
    three_edge_grasp_sets,
)
from fcgrasp.model.polygon import Polygon

from .shapes import random_polygon

# ------------------------------------------------------------------ reference wrenches


def edge_points(poly, edges, rng, n):
    """n random points on each edge (uniform), shape (len(edges), n, 2)."""
    t = rng.random((len(edges), n))
    return np.stack([poly.starts[e] + t[i][:, None] * (poly.ends[e] - poly.starts[e])
                     for i, e in enumerate(edges)])


def soft_forces(poly, k, mu):
    """Edges of the soft finger's arc at the vertex starting edge k (independent of fcgrasp's
    Feature code): from the incoming edge's friction cone to the outgoing edge's."""
    ring = np.flatnonzero((poly.rings == poly.rings[k]) & poly.usable)
    prev = ring[(np.searchsorted(ring, k) - 1) % len(ring)]
    f_in, f_out = -poly.normals[prev], -poly.normals[k]
    phi = np.arctan(mu)
    sgn = np.sign(f_in[0] * f_out[1] - f_in[1] * f_out[0])
    half_gap = np.arctan2(abs(f_in[0] * f_out[1] - f_in[1] * f_out[0]), f_in @ f_out) / 2
    half = min(half_gap + phi, np.pi / 2 - 1e-6)
    mid = np.arctan2(f_in[1], f_in[0]) + sgn * half_gap
    return np.array([[np.cos(mid - half), np.sin(mid - half)],
                     [np.cos(mid + half), np.sin(mid + half)]])


def friction_wrenches(poly, feats, p, q, mu):
    """General-test wrenches of two friction contacts (edges or soft vertices)."""
    out = []
    p, q = np.broadcast_arrays(p, q)
    for f, pts in zip(feats, (p, q), strict=True):
        if isinstance(f, Vertex):
            forces = np.broadcast_to(soft_forces(poly, int(f), mu), pts.shape[:-1] + (2, 2))
        else:
            forces = np.broadcast_to(friction_cone_edges(poly.normals[f], mu),
                                     pts.shape[:-1] + (2, 2))
        out.append(fc.wrench_from_force(forces, pts[..., None, :]))
    return np.concatenate(out, axis=-2)


def frictionless_wrenches(poly, edges, pts, gravity=None):
    w = [fc.wrench_from_force(-poly.normals[e], p) for e, p in zip(edges, pts, strict=True)]
    if gravity is not None:
        g = np.asarray(gravity, float) / np.linalg.norm(gravity)
        w.append(np.broadcast_to(fc.wrench_from_force(g, poly.centroid), w[0].shape))
    return np.stack(w, axis=-2)


# ------------------------------------------------------------------ two fingers


def _two_finger_trial(rng, soft=False):
    poly = random_polygon(rng)
    idx = np.flatnonzero(poly.usable)
    feats = [int(x) for x in rng.choice(idx, 2, replace=False)]
    if soft:
        conv = np.flatnonzero(poly.convex_vertices())
        # vertex at the end of edge i starts the next usable edge
        starts = []
        for i in conv:
            ring = np.flatnonzero((poly.rings == poly.rings[i]) & poly.usable)
            starts.append(int(ring[(np.searchsorted(ring, i) + 1) % len(ring)]))
        if starts:
            feats[0] = Vertex(int(rng.choice(starts)))
    mu = float(np.exp(rng.uniform(np.log(1e-3), np.log(10))))
    return poly, feats, mu


def _points(poly, f, rng, n):
    if isinstance(f, Vertex):
        return np.broadcast_to(poly.starts[int(f)], (n, 2)).copy()
    return edge_points(poly, [f], rng, n)[0]


@pytest.mark.parametrize("soft", [False, True])
def test_two_finger_set_agrees_with_general_test(soft):
    rng = np.random.default_rng(1 + soft)
    total = agree_true = 0
    while total < 5_000:
        poly, feats, mu = _two_finger_trial(rng, soft)
        gs = grasp_set(poly, feats, mu=mu)
        p = _points(poly, feats[0], rng, 24)
        q = _points(poly, feats[1], rng, 24)
        if not gs.is_empty:
            sp, sq = gs.sample(8, rng)
            p, q = np.concatenate([p, sp]), np.concatenate([q, sq])
        got = gs.contains(p, q)
        ref = fc.is_force_closure(friction_wrenches(poly, feats, p, q, mu))
        assert np.array_equal(got, ref), (poly, feats, mu, p[got != ref], q[got != ref])
        total += len(p)
        agree_true += int(ref.sum())
    assert agree_true > 500


@pytest.mark.parametrize("cases", [4, pytest.param(50, marks=pytest.mark.slow)])
def test_restricted_edges_are_exactly_points_with_partners(cases):
    rng = np.random.default_rng(3)
    checked = 0
    while checked < cases:
        poly, feats, mu = _two_finger_trial(rng)
        gs = grasp_set(poly, feats, mu=mu)
        if gs.is_empty:
            continue
        e1, e2 = feats
        t = np.linspace(0, 1, 101)
        p = poly.starts[e1] + t[:, None] * (poly.ends[e1] - poly.starts[e1])
        u = np.linspace(0, 1, 801)
        q = poly.starts[e2] + u[:, None] * (poly.ends[e2] - poly.starts[e2])
        has_partner = fc.is_force_closure(
            friction_wrenches(poly, feats, p[:, None, :], q[None, :, :], mu)).any(axis=1)
        in_restricted = np.zeros_like(t, dtype=bool)
        near_end = np.zeros_like(t, dtype=bool)
        for r in gs.restricted.values():
            if r[0] is not None:
                in_restricted |= (t >= r[0][0]) & (t <= r[0][1])
                near_end |= (np.abs(t - r[0][0]) < 0.02) | (np.abs(t - r[0][1]) < 0.02)
        clear = ~near_end
        assert np.array_equal(in_restricted[clear], has_partner[clear])
        checked += 1


def test_squeezing_and_expanding_grasps_in_a_hole():
    part = Polygon([[0, 0], [4, 0], [4, 4], [0, 4]], holes=[[[1, 1], [3, 1], [3, 3], [1, 3]]])
    # edges 5 and 7 are the hole's right and left walls (normals into the hole)
    gs = grasp_set(part, (5, 7), mu=0.2)
    assert gs.restricted["expand"][0] is not None
    assert gs.contains([3, 2], [1, 2.1])      # fingers inside the hole pushing apart
    gs_out = grasp_set(part, (1, 3), mu=0.2)
    assert gs_out.restricted["squeeze"][0] is not None and gs_out.restricted["expand"][0] is None


def test_two_finger_mu_zero_is_empty():
    sq = Polygon([[0, 0], [1, 0], [1, 1], [0, 1]])
    assert grasp_set(sq, (1, 3), mu=0.0).is_empty
    assert list(grasp_sets(sq, 2, mu=0.0)) == []


def test_soft_finger_widens_the_set():
    # a soft finger on a corner sees more of the opposite edge than a point contact beside it
    sq = Polygon([[0, 0], [1, 0], [1, 1], [0, 1]])
    soft = grasp_set(sq, (Vertex(2), 0), mu=0.1)      # corner (1, 1) against the bottom edge
    point = grasp_set(sq, (1, 3), mu=0.1)
    assert not soft.is_empty and soft.restricted["squeeze"][1] is not None
    # a point contact at that corner on the right edge has no partner on the bottom edge
    assert grasp_set(sq, (1, 0), mu=0.1).is_empty
    assert not point.is_empty
    with pytest.raises(ValueError, match="convex"):
        grasp_set(Polygon([[0, 0], [2, 0], [2, 2], [1, 1], [0, 2]]), (Vertex(3), 0), mu=0.3)


# ------------------------------------------------------------------ four fingers


def _four_finger_trial(rng, mode):
    poly = random_polygon(rng)
    idx = np.flatnonzero(poly.usable)
    if mode == "four" and len(idx) >= 4:
        return poly, tuple(int(x) for x in rng.choice(idx, 4, replace=False)), None
    if mode == "three" or len(idx) < 4:
        a, b, c = (int(x) for x in rng.choice(idx, 3, replace=False))
        return poly, [(a, b, a, c), (a, b, b, c), (a, c, b, c)][int(rng.integers(3))], None
    a, b, c = (int(x) for x in rng.choice(idx, 3, replace=False))
    g = rng.normal(size=2)
    return poly, (a, b, c), g / np.linalg.norm(g)


@pytest.mark.parametrize("mode", ["four", "three", "gravity"])
def test_four_finger_set_agrees_with_general_test(mode):
    rng = np.random.default_rng({"four": 10, "three": 11, "gravity": 12}[mode])
    total = positives = 0
    while total < 2_500:
        poly, edges, g = _four_finger_trial(rng, mode)
        gs = grasp_set(poly, edges, gravity=g)
        pts = list(edge_points(poly, edges, rng, 24))
        if not gs.is_empty:
            extra = gs.sample(8, rng)
            pts = [np.concatenate([a, b]) for a, b in zip(pts, extra, strict=False)]
        if g is not None:
            pts = pts[:3] + [np.broadcast_to(poly.centroid, pts[0].shape)]
        got = gs.contains(*pts)
        ref = fc.is_force_closure(frictionless_wrenches(poly, edges, pts[:len(edges)], g))
        assert np.array_equal(got, ref), (poly, edges, g)
        total += len(pts[0])
        positives += int(ref.sum())
    assert positives > 125


def test_three_pairings_describe_the_same_set():
    rng = np.random.default_rng(20)
    compared = nonempty = 0
    while compared < 150:
        poly = random_polygon(rng)
        idx = np.flatnonzero(poly.usable)
        if len(idx) < 4:
            continue
        edges = [int(x) for x in rng.choice(idx, 4, replace=False)]
        feats = [fc.model.graspsets.edge_feature(poly, e) for e in edges]
        sets = []
        for perm in ((0, 1, 2, 3), (0, 2, 1, 3), (0, 3, 1, 2)):
            s = FrictionlessGraspSet(poly, [feats[i] for i in perm])
            if s.pairing == (0, 1, 2, 3):          # this order's own pairing was usable
                sets.append((perm, s))
        if len(sets) < 2:
            continue
        pts = edge_points(poly, edges, rng, 400)
        verdicts = [s.contains(*[pts[i] for i in perm]) for perm, s in sets]
        empties = {s.is_empty for _, s in sets}
        assert len(empties) == 1
        for v in verdicts[1:]:
            assert np.array_equal(v, verdicts[0])
        nonempty += not sets[0][1].is_empty
        compared += 1
    assert nonempty > 15


def test_empty_set_reasons_corollary_6_1():
    sq = Polygon([[0, 0], [1, 0], [1, 1], [0, 1]])
    gs = grasp_set(sq, (0, 1, 0, 1))                   # two normals only
    assert gs.is_empty and gs.failure == FORCE_DIRECTION
    assert grasp_set(sq, (0, 1, 2, 3)).failure is None  # a rectangle needs all four normals
    # field of view: a thin triangle's fingers whose parallelograms never see each other
    rng = np.random.default_rng(30)
    found = 0
    for _ in range(3000):
        poly, edges, _ = _four_finger_trial(rng, "four")
        gs = grasp_set(poly, edges)
        if gs.failure != FIELD_OF_VIEW:
            continue
        pts = edge_points(poly, edges, rng, 2000)
        assert not fc.is_force_closure(frictionless_wrenches(poly, edges, pts)).any()
        found += 1
        if found >= 5:
            break
    assert found >= 5


def test_regions_back_project_onto_the_sampled_grasps():
    rng = np.random.default_rng(31)
    done = 0
    while done < 10:
        poly, edges, _ = _four_finger_trial(rng, "four")
        gs = grasp_set(poly, edges)
        if gs.is_empty:
            continue
        pts = gs.sample(200, rng)
        for i in range(4):
            lo, hi = gs.restricted_interval(i)
            t, _ = gs.features[i].param_of(pts[i])
            assert np.all((t >= lo - 1e-9) & (t <= hi + 1e-9))
        done += 1


def test_grasp_sets_enumeration_matches_individual_sets():
    rng = np.random.default_rng(40)
    for _ in range(5):
        poly = random_polygon(rng, "star")
        listed = {s.edges for s in grasp_sets(poly, 4)}
        idx = np.flatnonzero(poly.usable)
        from itertools import combinations
        brute = set()
        for q in combinations(idx, 4):
            s = grasp_set(poly, tuple(int(x) for x in q))
            if not s.is_empty:
                brute.add(s.edges)
        for t in combinations(idx, 3):
            for s in three_edge_grasp_sets(poly, tuple(int(x) for x in t)):
                if not s.is_empty:
                    brute.add(s.edges)
        assert listed == brute
        two = {s.edges for s in grasp_sets(poly, 2, mu=0.4)}
        brute2 = {(int(a), int(b)) for a, b in combinations(idx, 2)
                  if not grasp_set(poly, (int(a), int(b)), mu=0.4).is_empty}
        assert two == brute2


def test_three_fingers_with_gravity():
    tri = Polygon([[0, 0], [2, 0], [1, 1.5]])
    sets = list(grasp_sets(tri, 3))
    assert len(sets) == 1 and sets[0].features[3].kind == "gravity"
    # upside down gravity cannot be balanced by fingers pushing into the bottom edge
    gs = grasp_set(tri, (0, 1, 2), gravity=(0, -1))
    assert not gs.is_empty


@pytest.mark.parametrize("call, exc, match", [
    (lambda sq: grasp_set(sq, (0, 9), mu=0.3), ValueError, "not an edge"),
    (lambda sq: grasp_set(sq, (0, 1), mu=-1), ValueError, "mu"),
    (lambda sq: grasp_set(sq, (0, 1, 2), mu=0), ValueError, "gravity"),
    (lambda sq: grasp_set(sq, (0, 1, 2, 3), mu=0.3), ValueError, "frictionless"),
    (lambda sq: grasp_set(sq, ("a", 1), mu=0.3), TypeError, "edge"),
    (lambda sq: grasp_set([[0, 0]], (0, 1), mu=0.3), TypeError, "Polygon"),
    (lambda sq: list(grasp_sets(sq, 5)), ValueError, "fingers"),
])
def test_bad_arguments(call, exc, match):
    sq = Polygon([[0, 0], [1, 0], [1, 1], [0, 1]])
    with pytest.raises(exc, match=match):
        call(sq)
