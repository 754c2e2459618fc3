"""Robustness: never a wrong "force closure", degenerate geometry, invariance
under rigid motions, scaling, mirroring and renumbering, extreme coordinates."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import fcgrasp as fc
import fcgrasp.core.contacts
from fcgrasp import Polygon, grasp_set, independent_regions, plan

from .grippers import grip
from .shapes import random_polygon

STRICT = 1e-7      # a positive margin for the general test: stricter than the default


def plan_grasps_ok(p, rng, n):
    grasps = np.concatenate([p.corners(), p.sample(n, rng)])
    w = np.array([p.grasp(g).wrenches for g in grasps])
    return fc.is_force_closure(w, tol=STRICT)


# ------------------------------------------------------------------ no false closure

@settings(max_examples=20, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1), kind=st.sampled_from(["convex", "star", "holes",
                                                             "rectangle", "regular"]),
       log_mu=st.floats(np.log(1e-3), np.log(10.0)), fingers=st.sampled_from([2, 2, 3, 4]))
def test_no_false_force_closure_in_plans(seed, kind, log_mu, fingers):
    rng = np.random.default_rng(seed)
    poly = random_polygon(rng, kind)
    if fingers == 4 and poly.n_edges > 9:
        fingers = 2
    plans = plan(poly, **grip(fingers, float(np.exp(log_mu))), top=3)
    for p in plans:
        assert plan_grasps_ok(p, rng, 20).all()


@settings(max_examples=20, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1), log_mu=st.floats(np.log(1e-3), np.log(10.0)))
def test_no_false_force_closure_in_grasp_sets(seed, log_mu):
    rng = np.random.default_rng(seed)
    poly = random_polygon(rng)
    idx = np.flatnonzero(poly.usable)
    pair = tuple(int(x) for x in rng.choice(idx, 2, replace=False))
    gs = grasp_set(poly, pair, mu=float(np.exp(log_mu)))
    if not gs.is_empty:
        p, q = gs.sample(30, rng)
        feats = gs.features
        w = np.concatenate([
            fc.wrench_from_force(fc.core.contacts.friction_cone_edges(poly.normals[feats[0].index],
                                                                 gs.mu), p[:, None]),
            fc.wrench_from_force(fc.core.contacts.friction_cone_edges(poly.normals[feats[1].index],
                                                                 gs.mu), q[:, None])], axis=1)
        assert fc.is_force_closure(w).all()


def _sweep(seed, target):
    rng = np.random.default_rng(seed)
    checked = 0
    while checked < target:
        poly = random_polygon(rng)
        fingers = int(rng.choice([2, 2, 3, 4])) if poly.n_edges <= 8 else 2
        mu = float(np.exp(rng.uniform(np.log(1e-3), np.log(10))))
        for p in plan(poly, **grip(fingers, mu), top=3):
            ok = plan_grasps_ok(p, rng, 200)
            assert ok.all(), (poly, p)
            checked += ok.size
    return checked


def test_sampled_grasps_from_regions_are_force_closure():
    assert _sweep(1, 2_500) >= 2_500


@pytest.mark.slow
def test_sampled_grasps_from_regions_are_force_closure_sweep():
    assert _sweep(2, 100_000) >= 100_000


# ------------------------------------------------------------------ degenerate geometry

def test_parallel_edges_pairing():
    rect = Polygon([[0, 0], [8, 0], [8, 3], [0, 3]])
    plans = plan(rect, fingers=4, top=5)
    assert plans and sorted(plans[0].edges) == [0, 1, 2, 3]   # all four normals needed
    assert all(len(set(p.edges)) == 4 for p in plans)          # no three-edge grasp exists
    rng = np.random.default_rng(0)
    assert all(plan_grasps_ok(p, rng, 50).all() for p in plans)


def test_collinear_consecutive_edges():
    poly = Polygon([[0, 0], [3, 0], [6, 0], [6, 2], [0, 2]])
    plans = plan(poly, fingers=2, mu=0.3, top=5)
    assert plans and all(set(p.edges) != {0, 1} for p in plans)
    rng = np.random.default_rng(1)
    assert all(plan_grasps_ok(p, rng, 50).all() for p in plans)


def test_very_short_edges():
    eps = 1e-9 * 6
    poly = Polygon([[0, 0], [6, 0], [6, 2], [3 + eps, 2], [3, 2], [0, 2]])
    plans = plan(poly, fingers=2, mu=0.3, top=5)
    assert plans
    rng = np.random.default_rng(2)
    assert all(plan_grasps_ok(p, rng, 50).all() for p in plans)
    assert plan(poly, fingers=4, top=3)


def test_right_angle_exactly_on_cone_boundary():
    # mu = 1: half-angle 45 degrees; P and Q at exactly 45 degrees from the normals
    p, q = np.array([0.0, 0.5]), np.array([1.0, 1.5])
    assert not fc.friction_pair_closure(p, [-1, 0], q, [1, 0], 1.0)
    g = fc.Grasp([fc.FrictionPoint(p, [-1, 0], 1.0), fc.FrictionPoint(q, [1, 0], 1.0)])
    assert not g.is_force_closure()
    assert fc.friction_pair_closure(p, [-1, 0], q - [0, 1e-6], [1, 0], 1.0)


def test_three_lines_of_force_through_one_point():
    c = np.array([0.5, 0.5])
    g = fc.Grasp([fc.FrictionlessPoint([0, 0.5], [-1, 0]), fc.FrictionlessPoint([0.5, 0], [0, -1]),
                  fc.FrictionlessPoint([1, 0.5], [1, 0]), fc.FrictionlessPoint([0.7, 1], [0, 1])])
    rep = g.explain()
    assert not rep.force_closure and rep.failed == "torque"
    assert np.allclose(fc.rotation_center(rep.escape_twist), c)
    assert not fc.torque_closure(g.points, g.forces)


def test_contacts_on_a_shared_vertex():
    sq = Polygon([[0, 0], [1, 0], [1, 1], [0, 1]])
    # two friction fingers at opposite corners, each with the normal of one incident edge
    g = fc.Grasp([fc.FrictionPoint([0, 0], sq.normals[3], 1.5),
                  fc.FrictionPoint([1, 1], sq.normals[1], 1.5)])
    assert g.is_force_closure() == bool(fc.friction_pair_closure([0, 0], sq.normals[3], [1, 1],
                                                                   sq.normals[1], 1.5))
    # regions may end at vertices: every corner grasp is still force closure
    r = independent_regions(sq, (1, 3), mu=1.5)
    assert np.isclose(r.min_length, 1.0)
    assert plan_grasps_ok(r, np.random.default_rng(3), 20).all()


def test_mu_zero_two_fingers_no_grasp_and_reason():
    sq = Polygon([[0, 0], [1, 0], [1, 1], [0, 1]])
    assert plan(sq, fingers=2, mu=0.0) == []
    assert independent_regions(sq, (1, 3), mu=0.0) is None
    g = fc.Grasp([fc.FrictionPoint([0, 0.5], [-1, 0], 0.0),
                  fc.FrictionPoint([1, 0.5], [1, 0], 0.0)])
    assert g.explain().failed == "force-direction"


def test_very_large_mu():
    poly = random_polygon(np.random.default_rng(4), "star")
    plans = plan(poly, fingers=2, mu=1e6, top=5)
    assert plans
    assert all(plan_grasps_ok(p, np.random.default_rng(5), 30).all() for p in plans)


def test_polygon_given_clockwise():
    ccw = np.array([[0, 0], [5, 0], [6, 3], [2, 5], [-1, 2]], float)
    a = plan(Polygon(ccw), fingers=2, mu=0.3, top=None)
    b = plan(Polygon(ccw[::-1]), fingers=2, mu=0.3, top=None)
    n = len(ccw)
    # reversing the vertices maps edge i to edge n - 2 - i
    assert _signature(a) == _signature(b, lambda e: (n - 2 - e) % n)


def test_repeated_closing_vertex():
    v = [[0, 0], [5, 0], [6, 3], [2, 5], [-1, 2]]
    assert _signature(plan(Polygon(v), fingers=4, top=None)) == \
        _signature(plan(Polygon(v + [v[0]]), fingers=4, top=None))


# ------------------------------------------------------------------ invariance

def _signature(plans, mapping=lambda e: e, scale=1.0):
    """Plans as {sorted mapped edges: min length (relative)} for comparison."""
    out = {}
    for p in plans:
        key = (p.fingers, tuple(sorted(mapping(e) for e in p.edges)))
        out[key] = max(out.get(key, 0.0), round(p.min_length / scale, 6))
    return out


def _transformed(v, kind, rng):
    v = np.asarray(v, float)
    if kind == "translate":
        return v + rng.uniform(-1e3, 1e3, 2), 1.0, lambda e: e
    if kind == "rotate":
        a = rng.uniform(0, 2 * np.pi)
        r = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
        return v @ r.T, 1.0, lambda e: e
    if kind == "scale":
        s = float(rng.uniform(0.01, 100))
        return v * s, s, lambda e: e
    if kind == "mirror":
        return v * [-1, 1], 1.0, lambda e: e
    if kind == "start":
        k = int(rng.integers(1, len(v)))
        n = len(v)
        return np.roll(v, -k, axis=0), 1.0, lambda e: (e + k) % n
    raise AssertionError(kind)


MOVES = ("translate", "rotate", "scale", "mirror", "start")


@pytest.mark.parametrize("kind", MOVES)
@pytest.mark.parametrize("fingers", [2, 3, pytest.param(4, marks=pytest.mark.slow)])
def test_plans_invariant(kind, fingers):
    # seeded by position: hash() of a string changes from one process to the next
    rng = np.random.default_rng([MOVES.index(kind), fingers])
    for _ in range(2):
        poly = random_polygon(rng, str(rng.choice(["convex", "star"])))
        if fingers != 2 and poly.n_edges > 8:
            continue
        v2, s, emap = _transformed(poly.vertices, kind, rng)
        base = plan(poly, **grip(fingers, 0.4), top=None)
        if kind == "rotate" and fingers == 3:
            # gravity turns with the part
            continue
        moved = plan(Polygon(v2), **grip(fingers, 0.4), top=None)
        a = _signature(base)
        b = _signature(moved, scale=s)
        inv = {}
        for key, val in b.items():
            inv[(key[0], tuple(sorted(emap(e) for e in key[1])))] = val
        assert a.keys() == inv.keys()
        for key in a:
            assert np.isclose(a[key], inv[key], rtol=1e-6, atol=1e-9 * poly.size)


@pytest.mark.parametrize("scale", [1e-3, 1e6])
def test_coordinates_far_from_one(scale):
    rng = np.random.default_rng(7)
    for _ in range(3):
        poly = random_polygon(rng, "star")
        big = Polygon(poly.vertices * scale)
        for fingers in (2, 4):
            if fingers == 4 and poly.n_edges > 8:
                continue
            a = _signature(plan(poly, **grip(fingers, 0.3), top=None))
            b = _signature(plan(big, **grip(fingers, 0.3), top=None), scale=scale)
            assert a.keys() == b.keys()
            for k in a:
                assert np.isclose(a[k], b[k], rtol=1e-6)
        p = plan(big, fingers=2, mu=0.3, top=1)[0]
        assert plan_grasps_ok(p, rng, 50).all()


def test_large_polygon_batches_match_single_batch(monkeypatch):
    import fcgrasp.pipeline._spec as pipeline  # the search's tunables

    ang = np.linspace(0, 2 * np.pi, 160, endpoint=False)
    r = 1 + 0.3 * np.sin(3 * ang)
    poly = Polygon(np.column_stack([r * np.cos(ang), r * np.sin(ang)]))
    whole = plan(poly, fingers=2, mu=0.3, top=8)
    monkeypatch.setattr(pipeline, "BATCH_SIZE", 1000)
    batched = plan(poly, fingers=2, mu=0.3, top=8)
    assert [p.edges for p in whole] == [p.edges for p in batched]
    assert np.allclose([p.min_length for p in whole], [p.min_length for p in batched])


# ------------------------------------------------------------------ bad input everywhere

@pytest.mark.parametrize("verts, holes, exc", [
    ([[0, 0], [1, np.nan], [0, 1]], (), ValueError),
    ([[0, 0], [1, np.inf], [0, 1]], (), ValueError),
    ([], (), ValueError),
    ([[0, 0], [1, 0], [0, 1]], [[]], ValueError),
    ([[0, 0], [[1, 0]], [0, 1]], (), ValueError),
    ([[0, 0], ["1", "a"], [0, 1]], (), TypeError),
    ([[0, 0], [4, 0], [4, 4], [0, 4]], [[[5, 5], [6, 5], [6, 6]]], ValueError),
    ([[0, 0], [4, 0], [4, 4], [0, 4]], [[[1, 1], [3, 1], [3, 3]], [[1, 2], [3, 0.5], [3, 2.5]]],
     ValueError),
    ([[0, 0], [4, 0], [4, 4], [0, 4]], [[[1, 1], [3, 1], ["x", 3]]], TypeError),
])
def test_bad_polygons_raise(verts, holes, exc):
    with pytest.raises(exc):
        Polygon(verts, holes)


def test_bad_plan_inputs_name_the_argument():
    sq = Polygon([[0, 0], [1, 0], [1, 1], [0, 1]])
    with pytest.raises(ValueError, match="mu"):
        plan(sq, mu=float("nan"))
    with pytest.raises(TypeError, match="polygon"):
        plan([[0, 0], [1, 0], [1, 1]])
    with pytest.raises(TypeError, match="hand"):
        plan(sq, hand=(0, 0, 1))
    with pytest.raises(ValueError, match="workspace"):
        fc.Hand(workspace=(0, 0, -1))
    with pytest.raises(ValueError, match="finger_radius"):
        fc.Hand(finger_radius=-1)
