"""Three fingers with friction: every grasp of the planned regions is force
closure by the general wrench test of tests/oracle.py (an LP over the contact wrenches,
written without fcgrasp), the sub-arcs span, the branch and bound is exact, and a third
finger never makes things worse."""

import json

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.grippers.three_fingers import concurrent_regions, spanning_arcs, three_finger_plans
from fcgrasp.io.parts import DEMO_PARTS, demo_part
from fcgrasp.model.plans import leximin_key
from fcgrasp.pipeline import plan_spec

from ._highs import linprog
from .oracle import closure_margin_lp, grasp_wrenches
from .shapes import random_polygon, star
from .test_cli import run


def _spans(d):
    """Do unit directions d (3, 2) positively span the plane, strictly? (0 strictly
    inside their triangle: the three cross products share a sign)."""
    c = [d[0, 0] * d[1, 1] - d[0, 1] * d[1, 0], d[1, 0] * d[2, 1] - d[1, 1] * d[2, 0],
         d[2, 0] * d[0, 1] - d[2, 1] * d[0, 0]]
    return all(x > 0 for x in c) or all(x < 0 for x in c)


def _unit(a):
    return np.stack([np.cos(a), np.sin(a)], axis=-1)


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 8))])
def test_spanning_arcs_every_selection_spans(seed):
    rng = np.random.default_rng(seed)
    nonempty = 0
    for _ in range(500):
        center = rng.uniform(-np.pi, 3 * np.pi, 3)
        if rng.random() < 0.2:                       # near-degenerate: two axes opposite
            center[1] = center[0] + np.pi + rng.normal(0, 1e-3)
        half = rng.uniform(0.0, 0.9, 3)
        margin = rng.choice([0.0, 0.01, 0.1])
        arcs = spanning_arcs(center, half, margin)
        for lo, hi in arcs:
            nonempty += 1
            # inside the cones shrunk by the margin
            off_lo = (lo - center + np.pi) % (2 * np.pi) - np.pi
            off_hi = (hi - center + np.pi) % (2 * np.pi) - np.pi
            assert np.all(off_lo >= -half + margin - 1e-9)
            assert np.all(off_hi <= half - margin + 1e-9)
            assert np.all(off_hi >= off_lo - 1e-9)
            # every selection (ends included) positively spans; with no margin the
            # arcs are closed and their ends may be a tie (the closure, as everywhere)
            u = rng.random((60, 3))
            u[:8] = np.array(list(np.ndindex(2, 2, 2)))
            if margin == 0:
                u = 1e-6 + (1 - 2e-6) * u
            for uu in u:
                assert _spans(_unit(lo + uu * (hi - lo))), (center, half, margin, lo, hi)
        if not arcs and margin == 0:
            # none returned: no selection from the cones spans the plane
            for _ in range(200):
                d = _unit(center + rng.uniform(-1, 1, 3) * half * (1 - 1e-9))
                assert not _spans(d)
    assert nonempty > 100


def _corner_and_random(rng, lo, hi, n=24):
    u = rng.random((n, 3))
    u[:8] = np.array(list(np.ndindex(2, 2, 2)))
    return lo + u * (hi - lo)


def _check_piece(rng, poly, edges, mu, margin_deg=0.5):
    e = np.array(edges)
    a, b = poly.starts[e], poly.ends[e]
    nrm = poly.normals[e]
    center = np.arctan2(-nrm[:, 1], -nrm[:, 0])
    piece = concurrent_regions(a[None], b[None], center[None],
                               np.full((1, 3), np.arctan(mu)), np.radians(margin_deg),
                               poly.size)[0]
    if piece is None:
        return None
    tan = (b - a) / poly.lengths[e][:, None]
    assert np.all(piece.lo >= -1e-9 * poly.size)
    assert np.all(piece.hi <= poly.lengths[e] + 1e-9 * poly.size)
    for s in _corner_and_random(rng, piece.lo, piece.hi):
        pts = a + s[:, None] * tan
        m = closure_margin_lp(grasp_wrenches(pts, nrm, mu))
        # with no margin the regions are the closure of force-closure grasps: a grasp
        # at their ends may be a tie (m = 0), as documented for every planner
        # (a tie is zero to the oracle's rounding: -3e-13 on a HiGHS program)
        assert m > 0 if margin_deg > 0 else m >= -1e-9, (edges, mu, piece)
    return piece


def _random_cases(seed, count):
    rng = np.random.default_rng(seed)
    found = 0
    for _ in range(count):
        poly = random_polygon(rng)
        edges = rng.choice(poly.n_edges, 3, replace=False)
        mu = float(rng.choice([0.1, 0.3, 0.5, 1.0, rng.uniform(0.05, 1.5)]))
        if _check_piece(rng, poly, edges, mu, float(rng.choice([0.0, 0.5, 2.0]))) is not None:
            found += 1
    return found


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow) for s in (1, 2))])
def test_regions_force_closure_by_wrench_lp(seed):
    assert _random_cases(100 + seed, 25) > 5


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(3, 23))
def test_regions_force_closure_by_wrench_lp_slow(seed):
    assert _random_cases(100 + seed, 40) > 5


def _dense_max_min(a, t, L, lo_ang, hi_ang, sigma):
    """The max-min program of one piece written out densely, the straightforward way:
    variables lo (3), hi (3), level, and a witness per corner; constraints
    sigma (u x (p - x)) >= 0 on the low edge, <= 0 on the high edge."""
    corners = list(np.ndindex(2, 2, 2))
    nv = 7 + 16
    A, bnd = [], []
    for c, corner in enumerate(corners):
        for i in range(3):
            var = i if corner[i] == 0 else 3 + i
            for ang, sgn in ((lo_ang[i], 1.0), (hi_ang[i], -1.0)):
                u = np.array([np.cos(ang), np.sin(ang)])
                # sgn sigma (u_x (py - ay - s ty) - u_y (px - ax - s tx)) >= 0
                row = np.zeros(nv)
                k = sgn * sigma[i]
                row[7 + c] = k * u[1]          # -(-u_y) for px, as <= form
                row[15 + c] = -k * u[0]
                row[var] = k * (u[0] * t[i, 1] - u[1] * t[i, 0])
                A.append(row)
                bnd.append(-k * (u[0] * a[i, 1] - u[1] * a[i, 0]))
    for i in range(3):
        row = np.zeros(nv)
        row[6], row[3 + i], row[i] = 1, -1, 1
        A.append(row)
        bnd.append(0.0)
    c = np.zeros(nv)
    c[6] = -1
    bounds = [(0, L[i]) for i in range(3)] * 2 + [(0, L.max())] + [(None, None)] * 16
    res = linprog(c, A_ub=np.array(A), b_ub=np.array(bnd), bounds=bounds, method="highs")
    return -res.fun if res.status == 0 else -1.0


def test_max_min_matches_a_dense_program():
    from fcgrasp.grippers.three_fingers import SPLITS  # noqa: F401 - the pieces enumerated here
    rng = np.random.default_rng(7)
    checked = 0
    for _ in range(25):
        poly = random_polygon(rng)
        e = rng.choice(poly.n_edges, 3, replace=False)
        mu = 0.6
        a, b = poly.starts[e], poly.ends[e]
        nrm = poly.normals[e]
        center = np.arctan2(-nrm[:, 1], -nrm[:, 0])
        piece = concurrent_regions(a[None], b[None], center[None],
                                   np.full((1, 3), np.arctan(mu)), np.radians(0.5),
                                   poly.size)[0]
        size = poly.size
        L = poly.lengths[e] / size
        t = (b - a) / poly.lengths[e][:, None]
        best = -1.0
        for lo, hi in spanning_arcs(center, np.full(3, np.arctan(mu)), np.radians(0.5)):
            for sigma in np.array(list(np.ndindex(2, 2, 2))) * -2.0 + 1.0:
                best = max(best, _dense_max_min(a / size, t, L, lo, hi, sigma))
        if piece is None:
            assert best <= 1e-9
        else:
            checked += 1
            assert piece.levels.min() == pytest.approx(best * size, rel=1e-6, abs=1e-9 * size)
    assert checked > 6


# the washer's 20 equal outer edges tie everywhere: every triple is solved (slow suite)
PARTS = [pytest.param(name, marks=pytest.mark.slow) if name == "washer" else name
         for name in DEMO_PARTS if name not in ("cam",)]


def _side_by_side(p, part):
    """Two fingers on one edge (the first two), their regions apart along it."""
    if p.mode != "concurrent" or p.edges[0] != p.edges[1] or p.edges[2] == p.edges[0]:
        return False
    e = p.edges[0]
    t = (part.ends[e] - part.starts[e]) / part.lengths[e]
    s0, s1 = ((p.ends[i] - part.starts[e]) @ t for i in (0, 1))
    return bool(s0.max() <= s1.min() + 1e-9 * part.size)


@pytest.mark.parametrize("name", PARTS)
def test_plans_of_the_built_in_parts_hold(name):
    part = demo_part(name)
    rng = np.random.default_rng(3)
    plans = fc.plan(part, fingers=3, mu=0.5, top=3)
    assert plans and all(p.contact_type == "friction" and p.fingers == 3 for p in plans)
    for p in plans:
        assert p.mode in ("concurrent", "pair")
        assert len(set(p.edges)) == 3 or _side_by_side(p, part)
        # each point with its own edge's normal (regions may run along the boundary)
        for g, nrm in zip(*_plan_grasps(p, part, rng, 16), strict=True):
            m = closure_margin_lp(grasp_wrenches(g, nrm, 0.5))
            assert m > 0, (name, p.edges, p.mode)
    lex = [leximin_key(p.lengths, part.size) for p in plans]
    assert lex == sorted(lex)                     # best first


@pytest.mark.parametrize("seed", range(3))
def test_third_finger_only_helps(seed):
    """A third finger can only help: the best three-finger plan is at least as good as
    the best two-finger plan with the third finger anywhere on another edge."""
    rng = np.random.default_rng(50 + seed)
    for _ in range(4):
        part = random_polygon(rng)
        mu = float(rng.uniform(0.2, 0.8))
        two = fc.plan(part, fingers=2, mu=mu, top=1, along_boundary=False)
        three = fc.plan(part, fingers=3, mu=mu, top=1)
        if not two:
            continue
        other = max(L for e, L in enumerate(part.lengths) if e not in two[0].edges)
        assert three, "two fingers hold: three must too"
        assert three[0].min_length >= min(two[0].min_length, other) * (1 - 1e-9)
        # and every sampled grasp of the plan holds (general wrench test)
        p = three[0]
        for g, nrm in zip(*_plan_grasps(p, part, rng, 12), strict=True):
            assert closure_margin_lp(grasp_wrenches(g, nrm, mu)) > 0, (p.edges, p.mode)


def _plan_grasps(plan, polygon, rng, n):
    """Every combination of the regions' ends (each with the normal of the edge it ends
    on) and ``n`` grasps sampled along the regions (each point with its own edge's
    normal): ``(points (G, 3, 2), normals (G, 3, 2))``."""
    ends = [(np.asarray(line)[[0, -1]], polygon.normals[np.asarray(edges)[[0, -1]]])
            for line, edges in zip(plan.regions, plan.region_edges, strict=True)]
    pick = np.array(list(np.ndindex(*(2,) * plan.fingers)))
    pts = np.stack([ends[i][0][pick[:, i]] for i in range(plan.fingers)], axis=1)
    nrm = np.stack([ends[i][1][pick[:, i]] for i in range(plan.fingers)], axis=1)
    sp, sn = _sampled_with_normals(plan, polygon, rng, n)
    return np.concatenate([pts, sp]), np.concatenate([nrm, sn])


def _sampled_with_normals(plan, polygon, rng, n):
    """Grasps sampled along the plan's regions (polylines along the boundary), each point
    with the normal of the edge it lies on."""
    from fcgrasp.core._geom import along

    u = rng.random((n, plan.fingers))
    pts, nrm = [], []
    for i, line in enumerate(plan.regions):
        p, k = along(line, u[:, i])
        pts.append(p)
        nrm.append(polygon.normals[np.asarray(plan.region_edges[i])[k]])
    return np.stack(pts, axis=1), np.stack(nrm, axis=1)


def _curved(rng):
    """A finely flattened curved outline (ellipse or smooth star), where regions run
    along the boundary."""
    n = int(rng.integers(36, 54))
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 1 + float(rng.uniform(0, 0.25)) * np.sin(int(rng.integers(2, 5)) * a)
    return fc.Polygon(np.c_[float(rng.uniform(20, 60)) * r * np.cos(a),
                            float(rng.uniform(15, 40)) * r * np.sin(a)])


@pytest.mark.parametrize("seed", range(1))
def test_third_finger_only_helps_along_the_boundary(seed):
    """Against the default two-finger plans (regions along the boundary) on curved
    outlines: three fingers do at least as well as those with the third finger anywhere
    on the longest stretch they leave free, and every sampled grasp of their regions (each
    point with its own edge's normal) holds by the general wrench test."""
    _along_the_boundary_cases(seed, 1)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(1, 10))
def test_third_finger_only_helps_along_the_boundary_slow(seed):
    _along_the_boundary_cases(seed, 2)


def _along_the_boundary_cases(seed, n):
    rng = np.random.default_rng(70 + seed)
    for _ in range(n):
        part = _curved(rng)
        mu = float(rng.uniform(0.3, 0.7))
        two = fc.plan(part, fingers=2, mu=mu, top=1)
        three = fc.plan(part, fingers=3, mu=mu, top=2)
        assert two and three
        assert max(len(e) for e in two[0].region_edges) > 1     # really along the boundary
        # the third finger anywhere on the longest run of edges the two leave free (one
        # ring, edges in order): three fingers do at least as well as that
        covered = {e for st in two[0].region_edges for e in st}
        m = part.n_edges
        start = max(covered) + 1
        free, run = 0.0, 0.0
        for k in range(m):
            e = (start + k) % m
            run = 0.0 if e in covered else run + part.lengths[e]
            free = max(free, run)
        assert three[0].min_length >= min(two[0].min_length, free) * (1 - 1e-9)
        for p in three:
            pts, nrm = _sampled_with_normals(p, part, rng, 30)
            for g, n in zip(pts, nrm, strict=True):
                assert closure_margin_lp(grasp_wrenches(g, n, mu)) > 0, (p.mode, p.edges)


def _grown_cases(seed, n):
    """Concurrent regions grown along the boundary of random curved outlines from three
    random edges: every sampled grasp (each point with its own edge's normal) and every
    grasp of region ends and interior vertices (a vertex with either of its edges'
    normals) holds by the general wrench test.  Returns how many regions left their edge."""
    from fcgrasp.grippers.three_fingers import grow_concurrent, stretch_polylines

    rng = np.random.default_rng(300 + seed)
    grown = 0
    for _ in range(n):
        part = _curved(rng)
        mu = float(rng.uniform(0.2, 0.8))
        m = part.n_edges
        e0 = int(rng.integers(m))
        edges = [(e0 + k * m // 3 + int(rng.integers(-2, 3))) % m for k in range(3)]
        got = grow_concurrent(part, edges, mu, np.radians(0.5))
        if got is None:
            continue
        stretches, piece = got
        lines = stretch_polylines(part, stretches, piece)
        assert np.allclose([np.sum(np.hypot(*np.diff(ln, axis=0).T)) for ln in lines],
                           piece.levels, rtol=1e-9)
        plan = fc.GraspPlan(tuple(st[0] for st in stretches), lines, piece.levels,
                            np.array([ln[0] for ln in lines]),
                            part.normals[[st[0] for st in stretches]], "friction", mu,
                            "concurrent", 0.5, None, region_edges=tuple(stretches))
        grown += max(len(st) for st in stretches) > 1
        pts, nrm = _sampled_with_normals(plan, part, rng, 25)
        for g, n in zip(pts, nrm, strict=True):
            assert closure_margin_lp(grasp_wrenches(g, n, mu)) > 0, (seed, stretches)
        # ends and interior vertices, a vertex with either normal
        for _ in range(25):
            g, n = [], []
            for st, ln in zip(stretches, lines, strict=True):
                j = int(rng.integers(len(ln)))
                g.append(ln[j])
                e = st[0] if j == 0 else st[-1] if j == len(ln) - 1 \
                    else st[j - int(rng.integers(2))]          # vertex j: edge j-1 or j
                n.append(part.normals[e])
            assert closure_margin_lp(grasp_wrenches(np.array(g), np.array(n), mu)) > 0, \
                (seed, stretches)
    return grown


@pytest.mark.parametrize("seed", range(2))
def test_grown_concurrent_regions_hold(seed):
    assert _grown_cases(seed, 3) >= 1


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(2, 22))
def test_grown_concurrent_regions_hold_slow(seed):
    _grown_cases(seed, 4)


@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow),
                                  *(pytest.param(s, marks=pytest.mark.slow) for s in range(2, 8))])
def test_branch_and_bound_is_exact(seed):
    rng = np.random.default_rng(80 + seed)
    for _ in range(2):
        part = fc.Polygon(star(rng, n=int(rng.integers(6, 9))))
        spec_all = plan_spec(fingers=3, mu=0.4, top=None)
        every = three_finger_plans(part, spec_all)
        for top in (1, 3):
            pruned = three_finger_plans(part, plan_spec(fingers=3, mu=0.4, top=top))
            assert [p.edges for p in pruned] == [p.edges for p in every[:top]]
            for p, q in zip(pruned, every, strict=False):
                assert np.allclose(p.lengths, q.lengths, rtol=1e-9, atol=1e-9 * part.size)


@pytest.mark.parametrize("kind", ["ellipse", *(pytest.param(k, marks=pytest.mark.slow)
                                             for k in ("regular", "blob"))])
def test_branch_and_bound_is_exact_along_the_boundary(kind):
    """On smooth outlines, where every triple of equal edges ties on its bound and the
    two-finger plans end the search, and on a regular polygon with exact ties: the top
    of the pruned search is the head of the exhaustive one (seeds of the growth
    included: exact ties are taken in the order found, by both)."""
    n = {"regular": 18, "ellipse": 20, "blob": 18}[kind]
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = {"regular": np.full(n, 30.0), "ellipse": 30 / np.sqrt(np.cos(a) ** 2
                                                               + (np.sin(a) / 0.6) ** 2),
         "blob": 30 + 4 * np.sin(3 * a) + 2 * np.cos(5 * a)}[kind]
    part = fc.Polygon(np.c_[r * np.cos(a), r * np.sin(a)])
    every = three_finger_plans(part, plan_spec(fingers=3, mu=0.4, top=None))
    # above KEEP_PAIRS the two-finger list is read further (its floor holds for top 30)
    for top in (1, 3, 10, 30):
        pruned = three_finger_plans(part, plan_spec(fingers=3, mu=0.4, top=top))
        assert [(p.mode, p.region_edges) for p in pruned] == \
            [(p.mode, p.region_edges) for p in every[:top]]
        for p, q in zip(pruned, every, strict=False):
            assert np.allclose(p.lengths, q.lengths, rtol=1e-9, atol=1e-9 * part.size)


def test_independent_regions_on_three_edges():
    part = demo_part("triangle")
    reg = fc.independent_regions(part, (2, 0, 1), mu=0.5)
    assert reg.edges == (2, 0, 1) and reg.contact_type == "friction"
    assert reg.min_length > 0
    with pytest.raises(ValueError, match="distinct"):
        fc.independent_regions(part, (0, 0, 0), mu=0.5)
    # two fingers side by side on one edge: the planner's plan of that row
    quad = demo_part("quad")
    reg = fc.independent_regions(quad, (0, 0, 2), mu=0.5)
    best = fc.plan(quad, fingers=3, mu=0.5, top=1)[0]
    assert best.edges == (0, 0, 2) and _side_by_side(reg, quad)
    assert np.allclose(reg.lengths, best.lengths, rtol=1e-9)


def test_a_mu_the_planner_cannot_use_is_an_error():
    part = demo_part("quad")
    with pytest.raises(ValueError, match="mu"):
        fc.plan(part, fingers=4, mu=0.3)
    with pytest.raises(ValueError, match="mu"):
        fc.plan(part, fingers=3, mu=0.3, gravity=(0, -1))
    with pytest.raises(ValueError, match="friction"):
        fc.plan(part, fingers=3, mu=0)
    with pytest.raises(ValueError, match="gravity"):
        fc.plan(part, fingers=2, mu=0.3, gravity=(0, -1))
    # the explicit frictionless-with-gravity planner is still there
    assert fc.plan(demo_part("triangle"), fingers=3, gravity=(0, -1), top=1)[0].gravity


@pytest.mark.slow       # the default suite's time (3 minutes on two cores)
def test_cli_three_fingers_and_gravity(tmp_path):
    out = tmp_path / "p.json"
    r = run("plan", "demo:blob", "--fingers", "3", "--mu", "0.5", "--top", "2", "--json", out)
    assert r.returncode == 0, r.stderr
    d = json.loads(out.read_text())
    assert d["grasps"][0]["contact_type"] == "friction" and len(d["grasps"][0]["edges"]) == 3
    r = run("plan", "demo:triangle", "--fingers", "3", "--gravity", "0,-1", "--json", out)
    assert r.returncode == 0, r.stderr
    assert json.loads(out.read_text())["grasps"][0]["contact_type"] == "frictionless"
    for bad in (["--fingers", "4", "--mu", "0.3"], ["--fingers", "3", "--gravity", "0,-1",
                                                    "--mu", "0.2"],
                ["--fingers", "2", "--gravity", "0,-1"]):
        r = run("plan", "demo:quad", *bad, "--json", tmp_path / "bad.json")
        assert r.returncode != 0
        assert len(r.stderr.strip().splitlines()) == 1 and "Traceback" not in r.stderr
        assert not (tmp_path / "bad.json").exists()


def test_grow_concurrent_and_free_stretch_bad_arguments():
    from fcgrasp.grippers.three_fingers import free_stretch, grow_concurrent

    part = demo_part("quad")
    for bad, err, word in (((0, 1), ValueError, "three"), ((0, 0, 1), ValueError, "three"),
                           ((0, 1, 9), ValueError, "edges"), ((0, 1, 2.5), TypeError, "edges")):
        with pytest.raises(err, match=word):
            grow_concurrent(part, bad, 0.5, 0.01)
    with pytest.raises(ValueError, match="mu"):
        grow_concurrent(part, (0, 1, 2), -0.5, 0.01)
    with pytest.raises(ValueError, match="margin"):
        grow_concurrent(part, (0, 1, 2), 0.5, -1.0)
    with pytest.raises(ValueError, match="sigma"):
        grow_concurrent(part, (0, 1, 2), 0.5, 0.01, sigma=(1, 0, 1))
    with pytest.raises(TypeError, match="polygon"):
        grow_concurrent("quad", (0, 1, 2), 0.5, 0.01)
    with pytest.raises(ValueError, match="covered"):
        free_stretch(part, {7})
    assert free_stretch(part, {0, 1, 2, 3}) is None


def _side_rows(poly, mu):
    """Every row of two fingers side by side on one edge and a third on another, as
    ``concurrent_regions`` takes them: ``(edges, a, b, center, half)``."""
    nrm = poly.normals
    inward = np.arctan2(-nrm[:, 1], -nrm[:, 0])
    for e in range(poly.n_edges):
        for g in range(poly.n_edges):
            if g != e:
                idx = [e, e, g]
                yield (e, g), poly.starts[idx], poly.ends[idx], inward[idx], \
                    np.full(3, np.arctan(mu))


@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow)])
def test_side_by_side_regions_are_the_best_split(seed):
    """Two fingers side by side on one edge: their regions apart, in order, and as good
    as the best split of the edge in two (the split edge's halves are two distinct
    features, solved without the order): no split does better, and a split between the
    two regions does as well.  On the quad and random parts with every mu; the plans'
    grasps hold by the HiGHS test (corners and samples)."""
    rng = np.random.default_rng(70 + seed)
    margin = np.radians(0.5)
    checked = 0
    for poly in [demo_part("quad")] + [random_polygon(rng) for _ in range(4)]:
        mu = 0.5 if checked == 0 else float(rng.uniform(0.2, 0.9))
        for (e, g), a, b, c, h in _side_rows(poly, mu):
            piece = concurrent_regions(a[None], b[None], c[None], h[None], margin,
                                       poly.size)[0]
            if piece is None:
                continue
            best = float(piece.levels.min())
            assert piece.hi[0] <= piece.lo[1] + 1e-9 * poly.size
            t = (b[0] - a[0]) / poly.lengths[e]
            cuts = list(np.linspace(0.1, 0.9, 5) * poly.lengths[e])
            cuts.append((piece.hi[0] + piece.lo[1]) / 2)
            for k, s in enumerate(cuts):
                m = a[0] + s * t
                sa, sb = np.stack([a[0], m, a[2]]), np.stack([m, b[0], b[2]])
                split = concurrent_regions(sa[None], sb[None], c[None], h[None], margin,
                                           poly.size)[0]
                level = -np.inf if split is None else float(split.levels.min())
                assert level <= best + 1e-9 * poly.size, (e, g, s)
                if k == len(cuts) - 1:
                    assert level >= best - 1e-9 * poly.size, (e, g, s)
            checked += 1
    assert checked >= 6
    part = demo_part("quad")
    plan = fc.plan(part, fingers=3, mu=0.5, top=1)[0]
    for g, nrm in zip(*_plan_grasps(plan, part, rng, 64), strict=True):
        assert closure_margin_lp(grasp_wrenches(g, nrm, 0.5)) > 0


@pytest.mark.parametrize("seed", [3, 34, *(pytest.param(s, marks=pytest.mark.slow)
                                          for s in range(40) if s not in (3, 34))])
def test_pair_plans_read_every_pair_that_can_rank(seed, monkeypatch):
    """The two-finger list is read as far as a pair can rank: every pair plan that ranks
    among the best ``keep`` of all pair plans (by the leximin order, ties with the
    ``keep``-th included) is among those read.  Elongated and smooth outlines of 30-60
    edges, where the third finger's free stretch, not the two fingers, often sets a
    pair's smallest region, so the list must be read past the ``keep``-th two-finger
    plan (by default a stadium and an ellipse where reading it once misses a pair)."""
    from fcgrasp.grippers import three_fingers as T
    from fcgrasp.pipeline import features

    rng = np.random.default_rng(500 + seed)
    n = int(rng.integers(30, 60))
    if seed % 2:                # a stadium: the free stretch (an end) is the shortest
        h = np.linspace(-np.pi / 2, np.pi / 2, n // 2)
        w, r = rng.uniform(20, 60), rng.uniform(4, 10)
        pts = np.concatenate([np.c_[w + r * np.cos(h), r * np.sin(h)],
                              np.c_[-w - r * np.cos(h), -r * np.sin(h)]])
    else:
        a = np.linspace(0, 2 * np.pi, n, endpoint=False)
        ecc = rng.uniform(0.15, 0.7)
        r = 1 / np.sqrt(np.cos(a) ** 2 + (np.sin(a) / ecc) ** 2) * (1 + 0.05 * np.sin(3 * a))
        pts = 40 * np.c_[r * np.cos(a), r * np.sin(a)]
    part = fc.Polygon(pts)
    mu = float(rng.choice([0.2, 0.4, 0.8]))
    spec = plan_spec(fingers=3, mu=mu, top=None)
    F = features(part, mu, None, None)
    every = T._pair_plans(part, spec, None, F, None)[0]
    keyed = sorted((leximin_key(p.lengths, part.size), p.region_edges) for p in every)
    for keep in (3, 12, 30):
        got = {p.region_edges for p in T._pair_plans(part, spec, None, F, keep)[0]}
        if len(keyed) > keep:
            last = keyed[keep - 1][0]
            want = {e for k, e in keyed if k <= last}
        else:
            want = {e for _, e in keyed}
        assert want <= got
    # in the planner, the pairs read after the triples: every pair that ranks at or
    # above the keep-th plan of all (triples too) is a candidate
    calls = []
    pair_plans = T._pair_plans

    def spy(*args, **kw):
        out = pair_plans(*args, **kw)
        calls.append(out[0])
        return out

    monkeypatch.setattr(T, "_pair_plans", spy)
    for keep in (3, 12, 30):
        calls.clear()
        ranked = T.three_finger_plans(part, plan_spec(fingers=3, mu=mu, top=keep))
        read = {p.region_edges for p in calls[-1]}
        kth = leximin_key(ranked[-1].lengths, part.size) if len(ranked) >= keep else None
        assert {e for k, e in keyed if kth is None or k < kth} <= read


def _free_stretch_reference(polygon, covered):
    """free_stretch as first written: each ring walked edge by edge from just after its
    first covered edge (or its shortest), runs split at covered edges, the first
    strictly longest kept."""
    covered = set(covered)
    best, best_len = None, -1.0
    for r in np.unique(polygon.rings):
        usable = np.flatnonzero((polygon.rings == r) & polygon.usable)
        if usable.size < 2:
            continue
        taken = [int(e) for e in usable if int(e) in covered]
        first = taken[0] if taken else int(usable[np.argmin(polygon.lengths[usable])])
        order = [polygon.next_edge(first)]
        while len(order) < usable.size:
            order.append(polygon.next_edge(order[-1]))
        runs = [[]]
        for e in order[:-1] if not taken else order:
            if e in covered:
                runs.append([])
            else:
                runs[-1].append(e)
        for stretch in runs:
            length = float(polygon.lengths[stretch].sum()) if stretch else 0.0
            if stretch and length > best_len:
                best, best_len = tuple(stretch), length
    return best


@pytest.mark.parametrize("seed", [0, 1, 9, *(pytest.param(s, marks=pytest.mark.slow)
                                            for s in range(30) if s not in (0, 1, 9))])
def test_free_stretch_is_the_edge_by_edge_walk(seed):
    """The free stretches read in numpy are those of the edge-by-edge walk they replace,
    on parts with holes, regular rings (equal runs: the first met) and repeated
    vertices (an unusable edge), for random covered sets of every size (seed 9, by
    default: a regular ring with a hole, where the walk starts decides between
    equal runs)."""
    from fcgrasp.grippers.three_fingers import _FreeStretches, free_stretch

    rng = np.random.default_rng(900 + seed)
    n = int(rng.integers(6, 40))
    th = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 30 * (1 + (0 if seed % 3 == 0 else 0.2) * rng.uniform(-1, 1, n))
    outer = np.c_[r * np.cos(th), r * np.sin(th)]
    if seed % 4 == 1:                       # a repeated vertex: an unusable edge
        outer = np.r_[outer[:3], outer[2:]]
    holes = []
    if seed % 2:
        m = int(rng.integers(3, 9))
        ht = np.linspace(0, 2 * np.pi, m, endpoint=False)[::-1]
        holes = [np.c_[5 * np.cos(ht), 5 * np.sin(ht)]]
    part = fc.Polygon(outer, holes=holes)
    free = _FreeStretches(part)
    for k in range(60):
        size = int(rng.integers(0, part.n_edges + 1)) if k % 3 else int(rng.integers(0, 4))
        usable = np.flatnonzero(part.usable)
        covered = {int(e) for e in rng.choice(usable, min(size, usable.size), replace=False)}
        want = _free_stretch_reference(part, covered)
        assert free.longest(covered) == want
        assert free_stretch(part, covered) == want


def _pair_outline(rng):
    """A smooth outline (an ellipse with a harmonic) or a noisy star, 40-160 edges:
    where the third finger's free stretch, not the two fingers, sets the pair plans."""
    n = int(rng.integers(40, 160))
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    if rng.random() < 0.6:
        r = 1 + rng.uniform(0, 0.15) * np.cos(int(rng.integers(2, 5)) * a)
        w, h = rng.uniform(30, 70), rng.uniform(15, 40)
        return fc.Polygon(np.c_[w * r * np.cos(a), h * r * np.sin(a)])
    r = 40 * (1 + 0.3 * np.sin(5 * a)) * (1 + rng.uniform(0, 0.01) * rng.standard_normal(n))
    return fc.Polygon(np.c_[r * np.cos(a), r * np.sin(a)])


@pytest.mark.parametrize("seed", [*range(6), *(pytest.param(s, marks=pytest.mark.slow)
                                               for s in range(6, 206))])
def test_pair_plans_by_their_bound_are_the_reference_plans(seed, monkeypatch):
    """The two-finger list read in the order of the pair plans' bounds (``PAIR_CAP``)
    gives the plans of the list read by the two fingers' smallest region (the
    reference): the same regions, in the same order, ``top`` 1 to 12, friction 0.2 to
    1.0."""
    from fcgrasp.grippers.three_fingers import _pairs

    rng = np.random.default_rng(9100 + seed)
    part = _pair_outline(rng)
    spec = plan_spec(fingers=3, mu=float(rng.choice([0.2, 0.3, 0.5, 1.0])),
                     top=int(rng.integers(1, 13)))
    got = three_finger_plans(part, spec)
    monkeypatch.setattr(_pairs, "PAIR_CAP", False)
    want = three_finger_plans(part, spec)
    assert [p.region_edges for p in got] == [p.region_edges for p in want]
    for g, w in zip(got, want, strict=True):
        for a, b in zip(g.regions, w.regions, strict=True):
            assert np.allclose(a, b, rtol=0, atol=1e-9 * part.size)
