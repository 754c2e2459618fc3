"""Three and four frictionless fingers along the boundary (fcgrasp.model.frictionless_stretches)
against methods that share none of its code: the general closure test (an LP over the
wrenches, tests/oracle.py) on sampled grasps, vertices inside regions with every normal
between the two edges'; and, for regions on single edges, the single-edge solver."""

from __future__ import annotations

from itertools import product

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.io.parts import demo_part
from fcgrasp.model.frictionless_stretches import (
    all_frictionless_stretches,
    frictionless_stretch_regions,
    grow_stretches,
)

from .grippers import grip
from .oracle import closure_margin_lp, grasp_wrenches
from .shapes import random_polygon
from .test_stretches import KINDS, seeds, smooth_outline


def _chain(plan, i, polygon, rng, extra):
    """Contacts (point, outward normal) of region ``i``: every end and interior vertex
    with each normal it carries, a vertex with a random normal of its fan, and random
    points of every piece."""
    pts, edges = plan.regions[i], plan.region_edges[i]
    normals = polygon.normals[list(edges)]
    out = []
    for k in range(len(edges)):
        a, b = pts[k], pts[k + 1]
        for u in np.r_[0.0, 1.0, rng.uniform(0, 1, extra)]:
            out.append((a + u * (b - a), normals[k]))
        if k > 0:                       # interior vertex a: a normal inside its fan
            th0 = np.arctan2(normals[k - 1][1], normals[k - 1][0])
            dth = np.angle(np.exp(1j * (np.arctan2(normals[k][1], normals[k][0]) - th0)))
            th = th0 + dth * rng.uniform(0, 1)
            out.append((a, np.array([np.cos(th), np.sin(th)])))
    return out


def _check_plan_holds(plan, polygon, rng, grasps=150):
    """Random grasps of the plan's regions (fans included) are force closure."""
    chains = [_chain(plan, i, polygon, rng, 2) for i in range(plan.fingers)]
    for _ in range(grasps):
        picks = [c[rng.integers(len(c))] for c in chains]
        pts = [p for p, _ in picks]
        nrm = [n for _, n in picks]
        if plan.gravity is not None:
            g = np.asarray(plan.gravity["direction"], float)
            pts.append(np.asarray(plan.gravity["center"], float))
            nrm.append(-g)                  # a "finger" pushing along g
        w = grasp_wrenches(np.array(pts), np.array(nrm), 0.0)
        assert closure_margin_lp(w) > 0, (plan.region_edges, pts)


def _curved(seed):
    rng = np.random.default_rng(seed)
    kind = KINDS[seed % len(KINDS)]
    n = int(rng.choice([16, 20, 24, 28]))
    return fc.Polygon(smooth_outline(rng, kind, n)), rng


@pytest.mark.parametrize("seed", seeds(1, 100))
@pytest.mark.parametrize("fingers", [3, 4])
def test_plans_along_the_boundary_hold(seed, fingers):
    """Every returned plan (grown along the boundary or not) holds for every sampled
    grasp, and ranks at least as high as the single-edge search's best."""
    poly, rng = _curved(seed)
    plans = fc.plan(poly, **grip(fingers), top=3)
    flat = fc.plan(poly, **grip(fingers), top=1, along_boundary=False)
    assert bool(plans) == bool(flat)
    if not plans:
        return
    assert plans[0].min_length >= flat[0].min_length * (1 - 1e-9)
    for p in plans:
        _check_plan_holds(p, poly, rng)


def test_curved_parts_gain():
    """On a flattened ellipse the regions run along the boundary and are several times
    longer than the single-edge ones."""
    t = np.linspace(0, 2 * np.pi, 20, endpoint=False)
    poly = fc.Polygon(np.c_[40 * np.cos(t), 25 * np.sin(t)])
    flat = fc.plan(poly, fingers=4, top=1, along_boundary=False)[0]
    grown = fc.plan(poly, fingers=4, top=1)[0]
    assert max(len(e) for e in grown.region_edges) > 1
    assert grown.min_length > 2 * flat.min_length
    _check_plan_holds(grown, poly, np.random.default_rng(1), grasps=400)


@pytest.mark.parametrize("seed", range(30))
def test_single_edges_match_the_single_edge_solver(seed):
    """On single edges the linear program of a configuration reaches the single-edge
    solver's optimum (the knapsack bisection of fcgrasp.model.regions)."""
    rng = np.random.default_rng(seed)
    poly = random_polygon(rng)
    plans = fc.plan(poly, fingers=4, top=3, along_boundary=False)
    for p in plans:
        if len(set(p.edges)) < 4:
            continue
        r = frictionless_stretch_regions(poly, [[e] for e in p.edges])
        assert r is not None
        assert r.min_length == pytest.approx(p.min_length, rel=1e-6)


def _corners(plan, i, polygon):
    """The chain vertices of region ``i``: its ends with their edges' normals and every
    interior vertex with both."""
    pts, edges = plan.regions[i], plan.region_edges[i]
    normals = polygon.normals[list(edges)]
    out = [(pts[0], normals[0]), (pts[-1], normals[-1])]
    for k in range(1, len(edges)):
        out += [(pts[k], normals[k - 1]), (pts[k], normals[k])]
    return out


def test_regions_are_maximal():
    """Lengthening the smallest region past the optimum (margin 0) at an end inside its
    edge lets some grasp fail: the optimum is as long as the condition allows."""
    t = np.linspace(0, 2 * np.pi, 20, endpoint=False)
    poly = fc.Polygon(np.c_[40 * np.cos(t), 25 * np.sin(t)])
    best = fc.plan(poly, fingers=4, top=1, margin=0.0)[0]
    assert max(len(e) for e in best.region_edges) > 1
    k = int(np.argmin(best.lengths))
    line, edges = best.regions[k], best.region_edges[k]
    checked = 0
    for end, e, inner in ((0, edges[0], line[1]), (-1, edges[-1], line[-2])):
        at_vertex = min(np.hypot(*(line[end] - poly.starts[e])),
                        np.hypot(*(line[end] - poly.ends[e]))) < 1e-9 * poly.size
        if at_vertex:
            continue
        d = line[end] - inner
        beyond = line[end] + 0.02 * best.lengths[k] * d / np.hypot(*d)
        others = [_corners(best, i, poly) for i in range(4) if i != k]
        worst = np.inf
        for picks in product(*others):
            pts = [p for p, _ in picks]
            nrm = [n for _, n in picks]
            pts.insert(k, beyond)
            nrm.insert(k, poly.normals[e])
            worst = min(worst, closure_margin_lp(grasp_wrenches(np.array(pts),
                                                                np.array(nrm), 0.0)))
        checked += 1
        assert worst <= 1e-9
    assert checked


@pytest.mark.parametrize("n", [10, pytest.param(16, marks=pytest.mark.slow)])
def test_grow_is_a_lower_bound_of_the_exhaustive_search(n):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    poly = fc.Polygon(np.c_[40 * np.cos(t), 25 * np.sin(t)])
    flat = fc.plan(poly, fingers=4, top=1, along_boundary=False)[0]
    g = grow_stretches(poly, [flat.edges])[0]
    ex = all_frictionless_stretches(poly, [flat.edges])
    assert ex.min_length >= g.min_length * (1 - 1e-9)
    assert g.min_length >= flat.min_length * (1 - 1e-9)


def test_independent_regions_on_given_stretches():
    t = np.linspace(0, 2 * np.pi, 20, endpoint=False)
    poly = fc.Polygon(np.c_[40 * np.cos(t), 25 * np.sin(t)])
    best = fc.plan(poly, fingers=4, top=1)[0]
    again = fc.independent_regions(poly, [list(e) for e in best.region_edges])
    assert again.region_edges == best.region_edges
    assert again.min_length == pytest.approx(best.min_length, rel=1e-9)
    three = fc.plan(poly, fingers=3, gravity=(0, -1), top=1)[0]
    got = fc.independent_regions(poly, [list(e) for e in three.region_edges],
                                 gravity=(0, -1))
    assert got.min_length == pytest.approx(three.min_length, rel=1e-9)


@pytest.mark.parametrize("stretches, kwargs, match", [
    ([[0, 2], [5], [9], [14]], {}, "consecutive"),
    ([[0, 1], [1, 2], [9], [14]], {}, "share"),
    ([[0], [5], [9]], {}, "gravity"),
    ([[0], [5], [9], [14]], {"gravity": (0, -1)}, "four stretches take no gravity"),
    ([[0], [5], [9], [14]], {"mu": 0.3}, "frictionless"),
    ([[0], [5], [9], [99]], {}, "not an edge"),
])
def test_bad_stretches(stretches, kwargs, match):
    t = np.linspace(0, 2 * np.pi, 20, endpoint=False)
    poly = fc.Polygon(np.c_[40 * np.cos(t), 25 * np.sin(t)])
    with pytest.raises(ValueError, match=match):
        fc.independent_regions(poly, stretches, **kwargs)


def test_bad_arguments_of_the_module():
    poly = demo_part("blob")
    with pytest.raises(ValueError, match="region_edges must hold 4"):
        frictionless_stretch_regions(poly, [[0], [1]])
    with pytest.raises(ValueError, match="gravity must be a nonzero"):
        frictionless_stretch_regions(poly, [[0], [1], [3]], gravity=(0, 0))
    with pytest.raises(TypeError, match="polygon must be"):
        grow_stretches("blob", [[0, 1, 3, 4]])
    with pytest.raises(ValueError, match="max_steps"):
        grow_stretches(poly, [[0, 1, 3, 4]], max_steps=-1)


@pytest.mark.parametrize("kind", [pytest.param("ellipse", marks=pytest.mark.slow),
                                  pytest.param("blob", marks=pytest.mark.slow), "quad",
                                  "bracket"])
def test_plans_by_the_compiled_simplex_equal_highs(kind, monkeypatch):
    """Four fingers along the boundary with the growth's programs solved by the compiled
    simplex (fcgrasp.core._simplex) and by HiGHS (``FCGRASP_JIT=0``, the reference):
    the same configurations and region lengths (to 1e-9 of the size)."""
    from fcgrasp.io.parts import demo_part
    if kind in ("quad", "bracket"):
        part = demo_part(kind)
    else:
        t = np.linspace(0, 2 * np.pi, 24, endpoint=False)
        r = 30 / np.sqrt(np.cos(t) ** 2 + (np.sin(t) / 0.6) ** 2) if kind == "ellipse" \
            else 30 + 4 * np.sin(3 * t) + 2 * np.cos(5 * t)
        part = fc.Polygon(np.c_[r * np.cos(t), r * np.sin(t)])
    got = []
    for jit in ("1", "0"):
        monkeypatch.setenv("FCGRASP_JIT", jit)
        got.append(fc.plan(part, fingers=4, top=5))
    assert [(p.mode, p.region_edges) for p in got[0]] == [(p.mode, p.region_edges)
                                                          for p in got[1]]
    for a, b in zip(*got, strict=True):
        assert np.allclose(a.lengths, b.lengths, rtol=0, atol=1e-9 * part.size)


@pytest.mark.parametrize("kind", ["regular", "ellipse"])
@pytest.mark.parametrize("grip", [dict(fingers=4), dict(fingers=3, gravity=(0, -1))])
def test_pruned_growth_is_the_head_of_the_exhaustive(kind, grip):
    """The seeds grown along the boundary come from their own search (exact ties in the
    order found), and the single-edge search stops below the top-th grown plan: the
    pruned plans are still the head of the exhaustive list, on a regular polygon whose
    rows all tie and on an ellipse."""
    n = 12
    t = np.linspace(0, 2 * np.pi, n, endpoint=False) + 0.1
    r = np.full(n, 30.0) if kind == "regular" else \
        30 / np.sqrt(np.cos(t) ** 2 + (np.sin(t) / 0.6) ** 2)
    part = fc.Polygon(np.c_[r * np.cos(t), r * np.sin(t)])
    every = fc.plan(part, top=None, **grip)
    for top in (1, 4):
        pruned = fc.plan(part, top=top, **grip)
        assert [(p.mode, p.region_edges) for p in pruned] == \
            [(p.mode, p.region_edges) for p in every[:top]]
        for p, q in zip(pruned, every, strict=False):
            assert np.allclose(p.lengths, q.lengths, rtol=0, atol=1e-9 * part.size)


@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow)])
def test_programs_solved_on_generated_rows_are_solved(seed):
    """Tall programs (few variables, up to a thousand rows, as the vertex lemma builds
    them for long stretches) solved on rows added as they are violated: the optimum of
    the whole program (HiGHS on every row), a feasible point of it, and infeasible
    exactly where HiGHS says so; with repeated and nearly parallel rows."""
    from fcgrasp.core import _simplex
    from fcgrasp.model._frictionless_program import DIRECT_ROWS, _rows_generated

    from ._highs import linprog

    rng = np.random.default_rng(seed)
    solved = infeasible = 0
    for case in range(150 if seed == 0 else 3000):
        n = int(rng.integers(2, 10))
        m = int(rng.integers(DIRECT_ROWS + 1, 1000))
        A = rng.normal(size=(m, n))
        if case % 4 == 0:                           # repeated and nearly parallel rows
            A[m // 2:] = A[:m - m // 2] * (1 + 1e-9 * rng.normal(size=(m - m // 2, 1)))
        A /= np.abs(A).max(axis=1, keepdims=True)
        x0 = rng.uniform(0, 1, n)
        b = A @ x0 + rng.uniform(0.0 if case % 3 else -0.3, 1.0, m)
        full_A = np.r_[A, np.eye(n)]                # the bound rows last, as _lp_simplex
        full_b = np.r_[b, np.full(n, 2.0)]
        c = rng.normal(size=n)
        st, y = _rows_generated(c, full_A, full_b, m)
        ref = linprog(-c, A_ub=full_A, b_ub=full_b, bounds=[(0, None)] * n, method="highs")
        if ref.status == 2:
            assert st == _simplex.INFEASIBLE
            infeasible += 1
            continue
        assert st == _simplex.OPTIMAL
        assert np.all(full_A @ y <= full_b + 1e-8) and np.all(y >= -1e-12)
        assert c @ y == pytest.approx(-ref.fun, rel=1e-8, abs=1e-8)
        solved += 1
    assert solved >= 100 and infeasible >= 10


@pytest.mark.parametrize("jit", ["1", pytest.param("0", marks=pytest.mark.slow)])
def test_grown_regions_do_not_depend_on_the_scale(jit, monkeypatch):
    """The growth's programs are solved in units of the longest edge, rows scaled to a
    largest coefficient of 1, by the compiled simplex and by HiGHS alike: three
    frictionless fingers with gravity on a country outline (Lesotho) gave rank 3 a
    smallest region 3.4e-5 shorter (relative) at scale 1e-3 with HiGHS's absolute
    tolerances."""
    from pathlib import Path

    monkeypatch.setenv("FCGRASP_JIT", jit)
    path = Path(__file__).parents[1] / "benchmarks" / "corpus" / "countries" / "LSO.geo.json"
    part = fc.load_part(str(path)).polygon
    got = []
    for scale in (1.0, 1e-3, 1e3):
        scaled = fc.Polygon(part.vertices * scale, [h * scale for h in part.holes])
        got.append([(p.region_edges, np.array(p.lengths) / scale)
                    for p in fc.plan(scaled, fingers=3, gravity=(0, -1))])
    assert len(got[0]) >= 5 and any(max(len(e) for e in r) > 1 for r, _ in got[0])
    for other in got[1:]:
        assert [r for r, _ in other] == [r for r, _ in got[0]]
        for (_, a), (_, b) in zip(other, got[0], strict=True):
            np.testing.assert_allclose(a, b, rtol=1e-9)


def test_pairs_of_moves_reach_the_symmetric_optimum_of_an_ellipse():
    """The case: on a 24-edge ellipse, regions on edges 1-4, 7-10, 13-16 and
    19-22 are reached from the grown plan only by sliding two regions at once (each
    slide alone shortens the smallest region): growth one move at a time stops at 0.94
    of them, the plan (its best growth polished by pairs of moves) reaches them, and
    its grasps hold (the LP oracle)."""
    t = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    poly = fc.Polygon(np.c_[40 * np.cos(t), 25 * np.sin(t)])
    ref = frictionless_stretch_regions(poly, [[1, 2, 3, 4], [7, 8, 9, 10],
                                              [13, 14, 15, 16], [19, 20, 21, 22]])
    rows = [p.edges for p in fc.plan(poly, fingers=4, top=8, along_boundary=False)
            if len(set(p.edges)) == 4]
    greedy = max(r.min_length for r in grow_stretches(poly, rows) if r is not None)
    best = fc.plan(poly, fingers=4, top=1)[0]
    assert greedy < 0.99 * ref.min_length <= best.min_length
    _check_plan_holds(best, poly, np.random.default_rng(0))
    with pytest.raises(ValueError, match="polish"):
        grow_stretches(poly, rows, polish=-1)


@pytest.mark.slow
def test_the_polished_ellipse_plan_is_not_refuted_by_the_bound():
    from fcgrasp.model.bounds import optimum_upper_bound

    t = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    poly = fc.Polygon(np.c_[40 * np.cos(t), 25 * np.sin(t)])
    best = fc.plan(poly, fingers=4, top=1)[0]
    assert optimum_upper_bound(poly, 4, 0.0, lower=best.min_length).value >= best.min_length


@pytest.mark.parametrize("seed", seeds(2, 12))
def test_growth_keeps_few_systems_and_gives_the_same_plans(seed, monkeypatch):
    """A growth keeps at most KEEP_SYSTEMS systems (its memory bounded whatever the
    part); a system asked for again is rebuilt, so a cache of one gives the plans of a
    cache that keeps every system."""
    import fcgrasp.model.frictionless_stretches as fs

    poly, _ = _curved(seed)
    rows = [p.edges for p in fc.plan(poly, fingers=4, top=3, along_boundary=False)]
    monkeypatch.setattr(fs, "KEEP_SYSTEMS", 10 ** 9)
    every = grow_stretches(poly, rows, polish=1)
    monkeypatch.setattr(fs, "KEEP_SYSTEMS", 1)
    few = grow_stretches(poly, rows, polish=1)
    for a, b in zip(every, few, strict=True):
        assert (a is None) == (b is None)
        if a is not None:
            assert a.region_edges == b.region_edges and a.pairing == b.pairing
            np.testing.assert_array_equal(np.asarray(a.lengths), np.asarray(b.lengths))
