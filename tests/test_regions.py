"""Optimal independent regions (section 7) against an independent LP formulation, and
every grasp inside returned regions against the general test of the core."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.model.polygon import Polygon
from fcgrasp.planning.planner import GraspPlan, independent_regions, plan

from .grippers import grip
from .oracle import region_lp
from .shapes import random_polygon

MARGIN = 0.5


def _lex_better(a, b, rtol=1e-9):
    """Leximin comparison of two length vectors with a relative tolerance."""
    a, b = np.sort(a), np.sort(b)
    scale = max(a.max(), b.max(), 1e-300)
    for x, y in zip(a, b, strict=True):
        if abs(x - y) > rtol * scale:
            return x > y
    return False


def _dir(a):
    return np.array([np.cos(a), np.sin(a)])


def _arc_meet(c1, h1, c2, h2):
    d = (c2 - c1 + np.pi) % (2 * np.pi) - np.pi
    lo, hi = max(-h1, d - h2), min(h1, d + h2)
    return c1 + (lo + hi) / 2, (hi - lo) / 2


def oracle_two(poly, i, j, mu, margin_deg=MARGIN):
    """Best leximin lengths over both modes, by LP; None if no regions."""
    phi = np.arctan(mu)
    ci = np.arctan2(-poly.normals[i][1], -poly.normals[i][0])
    cj = np.arctan2(-poly.normals[j][1], -poly.normals[j][0])
    cen, half = _arc_meet(ci, phi, cj + np.pi, phi)
    h = half - np.radians(margin_deg)
    if h <= 0:
        return None
    k1, k2 = _dir(cen - h), _dir(cen + h)
    best = None
    for s in (1, -1):
        res = region_lp(poly.starts[[i, j]], poly.ends[[i, j]],
                        -poly.normals[[i, j]], [0, 1], s * k1, s * k2)
        if res is not None and res.min() > 0:
            if best is None or _lex_better(res, best):
                best = res
    return best


def canonical(edges):
    """The layout fcgrasp pairs from: sorted edges, or (doubled, low, doubled, high)."""
    if len(set(edges)) == 4:
        return tuple(sorted(edges))
    d = [e for e in edges if list(edges).count(e) == 2][0]
    o = sorted(e for e in edges if e != d)
    return (d, o[0], d, o[1])


def oracle_four(poly, edges, margin_deg=MARGIN):
    """The LP optimum with the margin applied to the sector of the pairing that gives the
    best regions (fcgrasp's rule); the pairing only matters for the margin (corollary 5.1,
    see test_three_pairings_give_the_same_regions)."""
    edges = canonical(edges)
    f = -poly.normals[list(edges)]
    ang = np.arctan2(f[:, 1], f[:, 0])
    cr = lambda a, b: a[0] * b[1] - a[1] * b[0]  # noqa: E731
    best = None
    for p in ((0, 1, 2, 3), (0, 2, 1, 3), (0, 3, 1, 2)):
        if abs(cr(f[p[0]], f[p[1]])) <= 1e-9 or abs(cr(f[p[2]], f[p[3]])) <= 1e-9:
            continue
        g12 = (ang[p[1]] - ang[p[0]] + np.pi) % (2 * np.pi) - np.pi
        g34 = (ang[p[3]] - ang[p[2]] + np.pi) % (2 * np.pi) - np.pi
        cen, half = _arc_meet(ang[p[0]] + g12 / 2, abs(g12) / 2, ang[p[2]] + g34 / 2 + np.pi,
                              abs(g34) / 2)
        h = half - np.radians(margin_deg)
        if h <= 0:
            continue
        k1, k2 = _dir(cen - h), _dir(cen + h)
        order = list(p)
        st, en, ff = poly.starts[list(edges)][order], poly.ends[list(edges)][order], f[order]
        same = [(a, b) for a in range(4) for b in range(a + 1, 4)
                if edges[order[a]] == edges[order[b]]]
        for s in (1, -1):
            orders = [None] if not same else [same[0], same[0][::-1]]
            for o in orders:
                res = region_lp(st, en, ff, [0, 0, 1, 1], s * k1, s * k2, same_edge=same,
                                order=o)
                if res is None or res.min() <= 0:
                    continue
                # the first stage decides the pairing, as in fcgrasp
                if best is None or res.min() > best.min() * (1 + 1e-9) or (
                        abs(res.min() - best.min()) <= 1e-9 * best.min()
                        and _lex_better(res, best)):
                    best = res
    return best


def _check_plan_grasps(p: GraspPlan, rng, n=200):
    """Every corner grasp and n random grasps of the regions are force closure."""
    grasps = np.concatenate([p.corners(), p.sample(n, rng)])
    w = []
    for g in grasps:
        w.append(p.grasp(g).wrenches)
    ok = fc.is_force_closure(np.array(w))
    assert ok.all(), (p, grasps[~ok][:3])


def _two_finger_vs_lp(seed, count):
    rng = np.random.default_rng(seed)
    compared = positive = 0
    while compared < count:
        poly = random_polygon(rng)
        idx = np.flatnonzero(poly.usable)
        i, j = (int(x) for x in rng.choice(idx, 2, replace=False))
        mu = float(np.exp(rng.uniform(np.log(0.05), np.log(3))))
        got = independent_regions(poly, (i, j), mu=mu)
        ref = oracle_two(poly, i, j, mu)
        compared += 1
        if ref is None:
            assert got is None or got.min_length < 1e-9 * poly.size
            continue
        assert got is not None, (poly, i, j, mu, ref)
        assert np.allclose(np.sort(got.lengths), np.sort(ref), rtol=1e-9, atol=1e-9 * poly.size), \
            (got.lengths, ref)
        _check_plan_grasps(got, rng, 50)
        positive += 1
    assert positive > count // 5


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                      for s in range(1, 3))])
def test_two_finger_regions_match_lp(seed):
    _two_finger_vs_lp(seed, 150)


@pytest.mark.slow
def test_two_finger_regions_match_lp_exhaustive():
    _two_finger_vs_lp(100, 5000)


def _four_finger_vs_lp(kind, seed, count):
    rng = np.random.default_rng(seed)
    compared = positive = 0
    while positive < count and compared < 100 * count:
        poly = random_polygon(rng)
        idx = np.flatnonzero(poly.usable)
        if kind == "four":
            if len(idx) < 4:
                continue
            edges = tuple(int(x) for x in rng.choice(idx, 4, replace=False))
        else:
            a, b, c = (int(x) for x in rng.choice(idx, 3, replace=False))
            edges = (a, b, a, c)
        got = independent_regions(poly, edges)
        ref = oracle_four(poly, edges)
        compared += 1
        if ref is None:
            assert got is None
            continue
        assert got is not None, (poly, edges, ref)
        assert np.allclose(np.sort(got.lengths), np.sort(ref), rtol=1e-9, atol=1e-9 * poly.size), \
            (poly, edges, got.lengths, ref)
        _check_plan_grasps(got, rng, 50)
        positive += 1
    assert positive >= count


@pytest.mark.parametrize("kind", ["four", "three"])
def test_four_finger_regions_match_lp(kind):
    _four_finger_vs_lp(kind, 4 if kind == "four" else 5, 12)


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["four", "three"])
def test_four_finger_regions_match_lp_exhaustive(kind):
    _four_finger_vs_lp(kind, 70 if kind == "four" else 80, 1500)


def test_three_pairings_give_the_same_regions():
    """Corollary 5.1 / section 7.3: without margin the three pairings of four edges give the
    same optimal regions (with a margin, the margin is taken on the pairing's sector)."""
    from fcgrasp.model._regiongeom import four_finger_problems
    from fcgrasp.model.regions import leximin, place_regions

    rng = np.random.default_rng(9)
    done = 0
    while done < 60:
        poly = random_polygon(rng)
        idx = np.flatnonzero(poly.usable)
        if len(idx) < 4:
            continue
        e = np.array([int(x) for x in rng.choice(idx, 4, replace=False)])
        a, b = poly.starts[e][None], poly.ends[e][None]
        n = poly.normals[e]
        center = np.arctan2(-n[:, 1], -n[:, 0])[None]
        results = []
        for perm in ((0, 1, 2, 3), (0, 2, 1, 3), (0, 3, 1, 2)):
            probs, hm, valid = four_finger_problems(a, b, center, np.array([perm]), 0.0)
            if not valid[0] or hm[0] <= 0:
                continue
            best = None
            for pr in probs:
                lev = leximin(pr)[0]
                if lev.min() > 0 and (best is None or _lex_better(lev, best[0])):
                    inv = np.argsort(perm)
                    best = (lev[inv], place_regions(pr, lev[None])[0][inv])
            results.append(best)
        if len(results) < 2 or all(r is None for r in results):
            continue
        assert all(r is not None for r in results)
        for other in results[1:]:
            assert np.allclose(other[0], results[0][0], rtol=1e-9, atol=1e-12)
        done += 1


def test_parallel_edges_regions_are_centred():
    sq = Polygon([[0, 0], [10, 0], [10, 3], [0, 3]])
    r = independent_regions(sq, (0, 2), mu=0.3)
    assert np.allclose(r.ends[0, :, 0].mean(), 5.0)
    assert np.allclose(r.ends[1, :, 0].mean(), 5.0)
    assert np.isclose(r.min_length, 3 * np.tan(np.arctan(0.3) - np.radians(MARGIN)))


def test_margin_is_an_angle_inside_the_cones():
    sq = Polygon([[0, 0], [10, 0], [10, 3], [0, 3]])
    r0 = independent_regions(sq, (0, 2), mu=0.3, margin=0.0)
    r5 = independent_regions(sq, (0, 2), mu=0.3, margin=5.0)
    assert r5.min_length < r0.min_length
    assert np.isclose(r5.min_length, 3 * np.tan(np.arctan(0.3) - np.radians(5.0)))
    # every corner grasp points at least 5 degrees inside both friction cones
    for g in r5.corners():
        d = g[1] - g[0]
        ang = np.degrees(np.arctan2(abs(d[0]), abs(d[1])))
        assert ang <= np.degrees(np.arctan(0.3)) - 5.0 + 1e-9


def test_no_regions_without_friction_or_grasp():
    sq = Polygon([[0, 0], [1, 0], [1, 1], [0, 1]])
    assert independent_regions(sq, (0, 2), mu=0.0) is None
    assert independent_regions(sq, (0, 1), mu=0.3) is None


def test_expanding_regions_inside_a_hole():
    part = Polygon([[0, 0], [6, 0], [6, 6], [0, 6]], holes=[[[2, 2], [4, 2], [4, 4], [2, 4]]])
    r = independent_regions(part, (5, 7), mu=0.3)
    assert r is not None and r.mode == "expand"
    _check_plan_grasps(r, np.random.default_rng(0))


def test_plan_two_fingers_ranked_and_sound():
    rng = np.random.default_rng(11)
    for _ in range(10):
        poly = random_polygon(rng)
        plans = plan(poly, fingers=2, mu=0.4, top=5)
        lengths = [p.min_length for p in plans]
        assert all(a >= b - 1e-9 * poly.size for a, b in zip(lengths, lengths[1:], strict=False))
        for p in plans:
            _check_plan_grasps(p, rng, 30)
            ref = independent_regions(poly, p.region_edges, mu=0.4)
            assert np.isclose(ref.min_length, p.min_length, rtol=1e-9)


@pytest.mark.parametrize("fingers", [3, 4])
def test_plan_frictionless_sound(fingers):
    rng = np.random.default_rng(12 + fingers)
    seen = 0
    for _ in range(6):
        poly = random_polygon(rng, str(rng.choice(["convex", "star", "rectangle"])))
        plans = plan(poly, **grip(fingers), top=3)
        for p in plans:
            assert p.fingers == (3 if fingers == 3 else 4)
            _check_plan_grasps(p, rng, 30)
            seen += 1
    assert seen > 5


@pytest.mark.parametrize("rank_by, key", [("resistance", "resistance"), ("epsilon", "epsilon_l1")])
def test_plan_ranking_by_quality(rank_by, key):
    poly = Polygon([[0, 0], [3, 0], [4, 2], [1, 3], [-1, 1.5]])
    plans = plan(poly, fingers=2, mu=0.5, top=None, rank_by=rank_by)
    vals = [p.quality[key] for p in plans]
    assert vals == sorted(vals, reverse=True) and len(vals) > 2


def test_resistance_exact_never_exceeds_approximation_work():
    poly = Polygon([[0, 0], [3, 0], [4, 2], [1, 3], [-1, 1.5]])
    for p in plan(poly, fingers=2, mu=0.5, top=None):
        assert p.quality["resistance"] >= p.quality["resistance_approx"] - 1e-12


@pytest.mark.parametrize("kw, match", [
    ({"fingers": 5}, "fingers"), ({"rank_by": "fast"}, "rank_by"), ({"mu": -1}, "mu"),
    ({"top": 0}, "top"), ({"margin": -1}, "margin"), ({"margin": 95}, "margin"),
])
def test_plan_bad_arguments(kw, match):
    sq = Polygon([[0, 0], [1, 0], [1, 1], [0, 1]])
    with pytest.raises(ValueError, match=match):
        plan(sq, **kw)


def _random_two_region_problems(rng, B=100_000):
    """Random two-region knapsack problems, zero weights and negative budgets included."""
    from fcgrasp.model.regions import KnapsackProblem

    L = rng.uniform(0.1, 3, (B, 2))
    w1, w2 = rng.uniform(0, 2, (2, B, 2))
    w1[rng.random((B, 2)) < 0.1] = 0
    w2[rng.random((B, 2)) < 0.1] = 0
    K1, K2 = rng.uniform(-0.5, 4, (2, B))
    return KnapsackProblem(L, w1, w2, K1, K2, np.zeros((B, 2), bool), np.ones((B, 2), bool),
                           np.ones(B, bool))


def test_two_region_closed_form_equals_general_solver():
    from fcgrasp.model.regions import _max_level, _max_min_two, _order

    p = _random_two_region_problems(np.random.default_rng(21))
    B = p.batch
    a = _max_min_two(p)
    b = _max_level(p, np.zeros((B, 2)), np.ones((B, 2), bool), _order(p))
    assert np.allclose(a, b, rtol=1e-9, atol=1e-12)
    assert 0.3 < (a > 0).mean() < 0.9


def test_two_region_second_stage_closed_form_equals_general_solver():
    from fcgrasp.model.regions import _max_level, _order, _two_level

    rng = np.random.default_rng(22)
    p = _random_two_region_problems(rng)
    B = p.batch
    fixed = rng.uniform(0, 1.5, B)
    for k in (0, 1):
        lb0 = np.zeros((B, 2))
        lb0[:, k] = fixed
        fr = np.zeros((B, 2))
        fr[:, 1 - k] = 1
        a = _two_level(p, lb0, fr)
        b = _max_level(p, lb0, fr.astype(bool), _order(p))
        assert np.allclose(a, b, rtol=1e-9, atol=1e-12)
        assert 0.2 < (a > 0).mean() < 0.9


def _four_region_problems(rng, polys=40, rows=48):
    """Knapsack problems of four fingers (and three with gravity: a fixed point) on random
    polygons (regular ones tie their greedy ratios), every pairing, margins from 0; and
    random ones with zero weights, negative budgets and inactive regions."""
    from fcgrasp.model._regiongeom import four_finger_problems
    from fcgrasp.model.regions import KnapsackProblem
    from fcgrasp.pipeline._candidates import PAIRINGS, features

    out = []
    for _ in range(polys):
        poly = random_polygon(rng)
        F = features(poly, 0.0, None)
        feats = rng.integers(0, len(F.a), size=(rows, 4))
        a, b, center = F.a[feats], F.b[feats], F.center[feats]
        grav = rng.random(rows) < 0.25                # the fourth finger: gravity's point
        a[grav, 3] = b[grav, 3] = poly.centroid
        center[grav, 3] = rng.uniform(-np.pi, np.pi, grav.sum())
        margin = float(rng.choice([0.0, np.radians(rng.uniform(0.1, 5))]))
        for P in PAIRINGS:
            perm = np.broadcast_to(P, (rows, 4)).copy()
            out += list(four_finger_problems(a, b, center, perm, margin)[0])
    for n in (3, 4, 5):
        B = 2000
        L = rng.uniform(0.1, 3, (B, n))
        w1, w2 = rng.uniform(0, 2, (2, B, n))
        w1[rng.random((B, n)) < 0.15] = 0
        w2[rng.random((B, n)) < 0.15] = 0
        active = rng.random((B, n)) > 0.1
        w1[~active] = w2[~active] = 0
        K1, K2 = rng.uniform(-0.5, 4, (2, B))
        out.append(KnapsackProblem(L, w1, w2, K1, K2, np.zeros((B, n), bool), active,
                                   np.ones(B, bool)))
    return out


def test_compiled_leximin_equals_the_numpy_solver(monkeypatch):
    """The compiled knapsack loop (fcgrasp.model._leximin_kernels) gives numpy's leximin
    levels and first level (the reference, FCGRASP_JIT=0) to rounding, on problems of
    random parts and random ones: ties of the greedy order, zero weights, fixed points."""
    from fcgrasp.core.tolerances import LEXIMIN_STEP, SOLVER_TOL
    from fcgrasp.model._leximin_kernels import leximin_rows
    from fcgrasp.model.regions import leximin, max_min_length

    rows = positive = multi = 0
    for p in _four_region_problems(np.random.default_rng(31)):
        monkeypatch.setenv("FCGRASP_JIT", "0")
        ref_t, ref_lv = max_min_length(p), leximin(p)
        monkeypatch.setenv("FCGRASP_JIT", "1")
        got_t = leximin_rows(p.L, p.w1, p.w2, p.K1, p.K2, p.active, SOLVER_TOL,
                             LEXIMIN_STEP, True)[:, 0]
        got_lv = leximin_rows(p.L, p.w1, p.w2, p.K1, p.K2, p.active, SOLVER_TOL,
                              LEXIMIN_STEP, False)
        tol = 1e-9 * np.maximum(p.L.max(axis=1), 1.0)
        assert np.all(np.abs(got_t - ref_t) <= tol), np.max(np.abs(got_t - ref_t))
        assert np.all(np.abs(got_lv - ref_lv) <= tol[:, None])
        rows += p.batch
        positive += int(np.sum(ref_t > 0))
        # rows whose later levels exceed the first: the stages beyond the first ran
        multi += int(np.sum(np.any(ref_lv > ref_t[:, None] + 1e-6, axis=1) & (ref_t > 0)))
    assert rows > 10_000 and positive > 0.1 * rows and multi > 500, (rows, positive, multi)


@pytest.mark.parametrize("fingers, gravity", [(4, None), pytest.param(3, (0.0, -1.0),
                                                                     marks=pytest.mark.slow)])
def test_frictionless_plans_are_the_same_compiled_or_not(monkeypatch, fingers, gravity):
    """Four frictionless fingers (three with gravity) plan the same regions whether the
    knapsack solver runs by numpy or compiled (region ends to 1e-9 of the part)."""
    rng = np.random.default_rng(32 + fingers)
    for k in range(4):
        poly = random_polygon(rng)
        kw = dict(fingers=fingers, gravity=gravity, top=4, along_boundary=bool(k % 2))
        out = {}
        for setting in ("0", "1"):
            monkeypatch.setenv("FCGRASP_JIT", setting)
            out[setting] = plan(poly, **kw)
        assert len(out["0"]) == len(out["1"])
        for p, q in zip(out["0"], out["1"], strict=True):
            assert p.edges == q.edges and p.mode == q.mode
            assert np.allclose(p.lengths, q.lengths, rtol=1e-9, atol=1e-9 * poly.size)
            for r, s in zip(p.regions, q.regions, strict=True):
                assert np.allclose(r, s, rtol=1e-9, atol=1e-9 * poly.size)
