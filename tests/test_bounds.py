"""The upper bound on the best smallest region (optimality bounds): its one-sided
closure test against the general one, its soundness against every plan the planner and
the exhaustive stretch search prove, its tightness where the search is known to be
optimal, and the request, CLI and JSON around it."""

from __future__ import annotations

import json

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.core.closure import is_force_closure
from fcgrasp.core.tolerances import TOL
from fcgrasp.errors import RequestError
from fcgrasp.io.parts import demo_part
from fcgrasp.model.bounds import (
    _LOOPS,
    MAX_NODES,
    _Boundary,
    _fails_loop,
    _fails_numpy,
    _wrenches,
    clearly_not_closure,
    optimum_upper_bound,
    refutes,
)
from fcgrasp.model.frictionless_stretches import all_frictionless_stretches
from fcgrasp.model.regions import DEFAULT_MARGIN_DEG
from fcgrasp.planning import PlanRequest

from .shapes import random_polygon


def _wrench_sets(rng, n, m):
    """``n`` sets of ``m`` wrenches: generic ones and ties (parallel, coplanar,
    rank-deficient, exactly opposite, all on one line), and small perturbations."""
    w = rng.normal(size=(n, m, 3))
    q = n // 8
    w[:q, 1] = 2.5 * w[:q, 0]                                    # parallel
    w[q:2 * q, 2] = 0.7 * w[q:2 * q, 0] + 1.3 * w[q:2 * q, 1]    # three in a plane
    w[2 * q:3 * q, :, 2] = 0.0                                    # all in a plane
    w[3 * q:4 * q, 1] = -w[3 * q:4 * q, 0]                        # opposite
    w[4 * q:5 * q] = w[q:2 * q] + 1e-6 * rng.normal(size=(q, m, 3))
    w[5 * q:6 * q] = w[2 * q:3 * q] + 1e-6 * rng.normal(size=(q, m, 3))
    w[6 * q:6 * q + q // 4] = rng.normal(size=(q // 4, m, 1)) * rng.normal(size=(q // 4, 1, 3))
    return w


@pytest.mark.parametrize("m", [3, 4, 5, 6, 8])
def test_one_sided_test_agrees_with_the_general_test(m):
    rng = np.random.default_rng(100 + m)
    w = _wrench_sets(rng, 5000, m)
    assert np.array_equal(clearly_not_closure(w), ~is_force_closure(w))


def test_one_sided_test_on_grasps_of_random_parts():
    """Grasps as the bound builds them (points on edges, cones of three fingers, normals
    of four), on seeded random parts, agree with the general test."""
    rng = np.random.default_rng(7)
    for _ in range(60):
        poly = random_polygon(rng)
        bd = _Boundary(poly)
        per = bd.perimeters[0]
        for k, half in ((3, np.arctan(rng.uniform(0.1, 1.0))), (4, None)):
            s = rng.uniform(0, per, (200, k))
            pts, nrm = bd.contacts(np.zeros(s.shape, int), s, s)
            w = _wrenches(pts, nrm, half)
            assert np.array_equal(clearly_not_closure(w), ~is_force_closure(w))


@pytest.mark.parametrize("compiled", [True, False], ids=["numba", "python"])
def test_the_compiled_nodes_test_is_the_batched_one(compiled):
    """The loop that tests a node's grasps one by one (:func:`_fails_loop`, compiled and
    as plain Python) gives the batched numpy verdicts (:func:`_fails_numpy`, the
    reference) on nodes of seeded random parts, three fingers with friction and four
    without, test points on edges, at vertices (within a hair), doubled, with opposite
    normals, and
    on the built-in parts whose parallel sides tie."""
    if compiled and not _LOOPS.available():
        pytest.skip("numba does not run here")
    loop = _LOOPS.get()["_fails_loop"] if compiled else _fails_loop
    rng = np.random.default_rng(31)
    seen = {True: 0, False: 0}
    for trial in range(40 if compiled else 6):
        poly = (demo_part(("rectangle", "quad", "triangle")[trial]) if trial < 3
                else random_polygon(rng, ("convex", "star")[trial % 2]))   # ties: parallel
        bd = _Boundary(poly)
        per = bd.perimeters[0]
        for k, half in ((3, float(np.arctan(rng.uniform(0.05, 1.2)))), (4, None),
                        (3, None), (4, 0.3)):
            m = int(rng.integers(1, 4))
            s = rng.uniform(0, per, (60, k, m))
            cum = bd.rings[0][1]
            s[::3] = cum[rng.integers(0, cum.size - 1, s[::3].shape)]   # at vertices
            pts, nrm = bd.contacts(np.zeros(s.shape, int), s, s)
            pts[::5, 1] = pts[::5, 0]                                    # one point twice
            nrm[::7, 2] = -nrm[::7, 0]                                   # opposite normals
            want = _fails_numpy(pts, nrm, half)
            out = np.empty(s.shape[0], dtype=bool)
            c, sn = (1.0, 0.0) if half is None else (float(np.cos(half)), float(np.sin(half)))
            loop(np.ascontiguousarray(pts), np.ascontiguousarray(nrm), c, sn,
                 half is not None, TOL, out)
            assert np.array_equal(out, want), (trial, k, half)
            for v in (True, False):
                seen[v] += int(np.sum(want == v))
    assert min(seen.values()) > 50, seen          # both verdicts were tested


def _parts(rng, n):
    out = [demo_part(name) for name in ("triangle", "quad", "blob")]
    out += [random_polygon(rng, kind) for kind in ("convex", "star") for _ in range(n)]
    return out


@pytest.mark.parametrize("fingers, n", [pytest.param(3, 2, marks=pytest.mark.slow), (4, 2),
                                        pytest.param(3, 40, marks=pytest.mark.slow),
                                        pytest.param(4, 40, marks=pytest.mark.slow)])
def test_no_plan_is_refuted(fingers, n):
    """The plans hold, so their smallest region is never proved too long (a refuter that
    refuted a node it should not would say True here)."""
    rng = np.random.default_rng(fingers + n)
    seen = decided = 0
    for poly in _parts(rng, n):
        mu = float(rng.uniform(0.2, 0.8)) if fingers == 3 else 0.0
        # four fingers need 1,500 nodes to decide: their first plan only (suite time)
        plans = fc.plan(poly, fingers=fingers, top=2 if fingers == 3 or n > 2 else 1,
                        **({"mu": mu} if mu else {}))
        for p in plans:
            verdict, nodes = refutes(poly, fingers, p.min_length * (1 - 1e-6), mu,
                                     np.radians(p.margin),
                                     max_nodes=300 if fingers == 3 else 1500)
            assert verdict is not True, (poly.vertices.tolist(), p.edges)
            seen += 1
            decided += verdict is False       # a box of starts shrank to nothing
    assert seen >= 7 and decided >= 3, decided


@pytest.mark.parametrize("seed, n", [(12, 1), pytest.param(11, 20, marks=pytest.mark.slow)])
def test_bound_above_the_exhaustive_four_finger_optimum(seed, n):
    """Four frictionless fingers: the exhaustive search over every configuration of
    stretches (from every single-edge set that holds) never beats the bound."""
    rng = np.random.default_rng(seed)
    checked = 0
    for poly in [demo_part("triangle"), demo_part("quad")] + \
            [random_polygon(rng, "convex") for _ in range(n)]:
        flat = fc.plan(poly, fingers=4, top=None, along_boundary=False)
        if not flat:
            continue
        best = all_frictionless_stretches(
            poly, [p.edges for p in flat if len(set(p.edges)) == 4])  # stretches: distinct
        if best is None:
            continue
        b = optimum_upper_bound(poly, 4, lower=best.min_length, gap=0.05, max_nodes=3000)
        assert b.value >= best.min_length * (1 - 1e-9)
        assert b.value >= max(p.min_length for p in flat)
        checked += 1
    assert checked >= 2


@pytest.mark.parametrize("n", [1, pytest.param(12, marks=pytest.mark.slow)])
def test_bound_above_every_three_finger_plan(n):
    rng = np.random.default_rng(12)
    for poly in [demo_part("triangle")] + [random_polygon(rng, "convex") for _ in range(n)]:
        plans = fc.plan(poly, fingers=3, mu=0.4, top=20)
        if not plans:
            continue
        lower = plans[-1].min_length          # start below the best: the bound must rise
        b = optimum_upper_bound(poly, 3, 0.4, lower=lower, gap=0.05, max_nodes=1500)
        assert b.value >= max(p.min_length for p in plans)


def test_refutation_is_monotone_and_reaches_a_verdict():
    poly = demo_part("quad")
    margin = np.radians(DEFAULT_MARGIN_DEG)
    lo = fc.plan(poly, fingers=4, top=1)[0].min_length
    assert refutes(poly, 4, 1.05 * lo, 0.0, margin)[0] is True
    assert refutes(poly, 4, 1.5 * lo, 0.0, margin)[0] is True
    assert refutes(poly, 4, 3 * lo, 0.0, margin)[0] is True
    # far below the optimum a box of starts shrinks to nothing without a refutation
    assert refutes(poly, 4, 0.3 * lo, 0.0, margin, max_nodes=MAX_NODES * 20)[0] is False


def test_bound_is_tight_where_the_search_is_optimal():
    """Where the plans are (nearly) optimal the bound is close: within 2 % of three
    fingers on a triangle (one triple of edges) and of four on the quad (measured 1 %;
    a bound that refuted too little would drift away)."""
    tri = demo_part("triangle")
    best = fc.plan(tri, fingers=3, mu=0.3, top=1)[0].min_length
    b = optimum_upper_bound(tri, 3, 0.3, lower=best, gap=0.01)
    assert best <= b.value <= best * 1.02
    quad = demo_part("quad")
    best = fc.plan(quad, fingers=4, top=1)[0].min_length
    b = optimum_upper_bound(quad, 4, lower=best, gap=0.01)
    assert best <= b.value <= best * 1.02
    assert b.to_dict()["upper_bound"] == pytest.approx(b.value)
    assert b.gap == pytest.approx(1 - best / b.value)


def test_bad_arguments_name_themselves():
    tri = demo_part("triangle")
    with pytest.raises(ValueError, match="fingers must be 3 or 4, got 2"):
        optimum_upper_bound(tri, 2)
    with pytest.raises(ValueError, match="gap must be in"):
        optimum_upper_bound(tri, 3, 0.3, gap=1.5)
    with pytest.raises(ValueError, match="mu"):
        optimum_upper_bound(tri, 3, -0.3)
    with pytest.raises(TypeError, match="polygon"):
        optimum_upper_bound("triangle", 3, 0.3)


@pytest.mark.parametrize("options", [
    {"fingers": 2}, {"gripper": "jaw"}, {"fingers": 3, "gravity": (0.0, -1.0)},
    {"fingers": 3, "mu": 0.0}])
def test_request_refuses_bound_where_it_has_no_meaning(options):
    with pytest.raises(RequestError) as err:
        PlanRequest(part="demo:quad", bound=True, **options)
    assert err.value.field == "bound"


def test_cli_prints_and_writes_the_bound(tmp_path, capsys):
    from fcgrasp.apps.cli import main

    out = tmp_path / "plan.json"
    assert main(["plan", "demo:triangle", "--fingers", "3", "--mu", "0.3", "--bound",
                 "--json", str(out)]) == 0
    report = json.loads(out.read_text())
    best = max(g["min_region_length"] for g in report["grasps"])
    opt = report["optimality"]
    assert opt["upper_bound"] >= best
    assert opt["gap"] == pytest.approx(1 - best / opt["upper_bound"], abs=1e-9)
    assert main(["plan", "demo:triangle", "--fingers", "3", "--mu", "0.3", "--bound"]) == 0
    assert "optimum: no regions of 3 fingers each" in capsys.readouterr().out
