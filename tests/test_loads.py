"""Loads with finger force limits (fcgrasp.model.loads): the payload of one
grasp against an independent linear program written over the finger forces' components
(the module parametrises the cones by their edges), the least-peak-force distribution
checked for equilibrium, cones and limits, and the certified scale of a plan's regions
against the payload of grasps sampled in the regions (their corners included)."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.model.loads import Load, grasp_payload, region_payload

from ._highs import linprog
from .shapes import random_polygon


def _reference_scale(points, normals, mu, W, per, total, groups=None):
    """Largest s with forces f_i = (fx, fy) per contact and load vertex: n.f >= 0,
    |t.f| <= mu n.f, n.f <= per_i, sum n.f <= total, sum f = -s F, sum p x f = -s tau.
    ``groups``: the contacts' fingers (a parallel jaw's pad touching at two points), the
    normal forces of a finger's contacts summing to at most its ``per``."""
    k, V = len(points), len(W)
    groups = np.arange(k) if groups is None else np.asarray(groups)
    n = normals / np.hypot(*normals.T)[:, None]
    t = np.c_[-n[:, 1], n[:, 0]]
    nvar = 1 + V * k * 2
    A_eq, b_eq, A_ub, b_ub = [], [], [], []

    def f(v, i):
        return 1 + (v * k + i) * 2
    for v in range(V):
        for r in range(3):
            row = np.zeros(nvar)
            row[0] = W[v, r]
            for i in range(k):
                if r < 2:
                    row[f(v, i) + r] = 1.0
                else:
                    row[f(v, i)] = -points[i, 1]
                    row[f(v, i) + 1] = points[i, 0]
            A_eq.append(row)
            b_eq.append(0.0)
        tot = np.zeros(nvar)
        finger = np.zeros((len(per), nvar))
        for i in range(k):
            nn = np.zeros(nvar)
            nn[f(v, i):f(v, i) + 2] = n[i]
            tt = np.zeros(nvar)
            tt[f(v, i):f(v, i) + 2] = t[i]
            A_ub += [-nn, tt - mu * nn, -tt - mu * nn]
            b_ub += [0.0, 0.0, 0.0]
            finger[groups[i]] += nn
            tot += nn
        for g in range(len(per)):
            if np.isfinite(per[g]):
                A_ub.append(finger[g])
                b_ub.append(per[g])
        if np.isfinite(total):
            A_ub.append(tot)
            b_ub.append(total)
    cost = np.zeros(nvar)
    cost[0] = -1
    bounds = [(0, None)] + [(None, None)] * (nvar - 1)
    res = linprog(cost, A_ub=np.array(A_ub), b_ub=np.array(b_ub), A_eq=np.array(A_eq),
                  b_eq=np.array(b_eq), bounds=bounds, method="highs")
    if res.status == 3:
        return np.inf
    assert res.status == 0
    return -res.fun


def _random_case(rng):
    k = int(rng.integers(2, 5))
    ang = rng.uniform(0, 2 * np.pi, k)
    if rng.random() < 0.3:                      # near-antipodal pairs: near-degenerate
        ang[1] = ang[0] + np.pi + rng.normal(0, 1e-3)
    points = np.c_[np.cos(ang), np.sin(ang)] * rng.uniform(5, 50) + rng.normal(0, 3, 2)
    normals = -np.c_[np.cos(ang), np.sin(ang)] + rng.normal(0, 0.2, (k, 2))
    mu = 0.0 if rng.random() < 0.25 else float(rng.uniform(0.05, 1.0))
    load = Load(float(rng.uniform(0.05, 3)), com=tuple(rng.normal(0, 5, 2)),
                accel=tuple(rng.choice([0.0, 1.0, 5.0], 2)),
                torque=(0.0, 0.0) if rng.random() < 0.5 else (-20.0, 35.0))
    per = None if rng.random() < 0.2 else (float(rng.uniform(1, 50)) if rng.random() < 0.5
                                           else rng.uniform(1, 50, k))
    total = None if rng.random() < 0.6 else float(rng.uniform(5, 80))
    return points, normals, mu, load, per, total


@pytest.mark.parametrize("seed", [*range(2), *(pytest.param(s, marks=pytest.mark.slow)
                                                 for s in range(2, 40))])
def test_grasp_payload_equals_a_program_over_force_components(seed):
    rng = np.random.default_rng(seed)
    for _ in range(60):
        points, normals, mu, load, per, total = _random_case(rng)
        got = grasp_payload(points, normals, mu, load, per, total)
        k = len(points)
        per_v = np.full(k, np.inf) if per is None else np.broadcast_to(per, (k,))
        want = _reference_scale(points, normals, mu, load.wrenches(),
                                per_v, np.inf if total is None else total)
        if np.isinf(want):
            assert np.isinf(got.scale)
        else:
            assert got.scale == pytest.approx(want, rel=1e-6, abs=1e-9)
        if got.holds:
            # the least-peak distribution: equilibrium with each load vertex, in the
            # cones, within the limits, and its peak is its largest normal force
            n = normals / np.hypot(*normals.T)[:, None]
            t = np.c_[-n[:, 1], n[:, 0]]
            for w, F in zip(load.wrenches(), got.forces, strict=True):
                assert np.allclose(F.sum(axis=0), -w[:2], atol=1e-6 * (1 + abs(w).max()))
                torque = np.sum(points[:, 0] * F[:, 1] - points[:, 1] * F[:, 0])
                assert torque == pytest.approx(-w[2], abs=1e-6 * (1 + abs(w).max()) * 50)
                fn, ft = np.einsum("kd,kd->k", F, n), np.einsum("kd,kd->k", F, t)
                assert np.all(fn >= -1e-7) and np.all(np.abs(ft) <= mu * fn + 1e-6)
                assert np.all(fn <= per_v + 1e-6) and fn.max() <= got.peak + 1e-6
                if total is not None:
                    assert fn.sum() <= total + 1e-6


def _limits_of(per, total, k):
    return (np.full(k, np.inf) if per is None else np.broadcast_to(per, (k,)).astype(float),
            np.inf if total is None else total)


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 10))])
def test_facets_of_the_fingers_wrenches_give_the_programs_scale(seed):
    """The exact scale from the facets of the fingers' wrench polytope (qhull, the
    load's support function in closed form) equals the program over the load's
    vertices on box loads: the machinery the ellipse relies on, checked where an
    independent answer is exact."""
    from fcgrasp.model.loads import _cone_edges, _facet_scale, _wrench_edges

    rng = np.random.default_rng(100 + seed)
    checked = 0
    for _ in range(80):
        points, normals, mu, load, per, total = _random_case(rng)
        k = len(points)
        per_v, total_v = _limits_of(per, total, k)
        n = normals / np.hypot(*normals.T)[:, None]
        E = _wrench_edges(points, _cone_edges(n, np.full(k, np.arctan(mu))))
        got = _facet_scale(E, load, None, per_v, total_v)
        if got is None:                       # unbounded (no limit) or a flat polytope
            assert not np.isfinite(per_v).all() and not np.isfinite(total_v) or mu == 0
            continue
        want = _reference_scale(points, normals, mu, load.wrenches(), per_v, total_v)
        assert got == pytest.approx(want, rel=1e-7, abs=1e-9)
        checked += 1
    assert checked >= 30


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 8))])
def test_an_ellipse_of_accelerations_between_its_polygons(seed):
    """An ellipse of accelerations: the scale lies between the program's over an
    inscribed polygon of 90 sides (its vertices are loads: an upper bound) and over the
    circumscribed one (a lower bound), which are 6e-4 apart; the least-peak forces
    resist points of the ellipse."""
    rng = np.random.default_rng(200 + seed)
    checked = 0
    for _ in range(7):
        points, normals, mu, load, per, total = _random_case(rng)
        load = Load(load.mass, com=load.com, accel=tuple(rng.uniform(0.5, 6.0, 2)),
                    torque=load.torque, accel_shape="ellipse")
        k = len(points)
        per_v, total_v = _limits_of(per, total, k)
        got = grasp_payload(points, normals, mu, load, per, total)
        inner = _reference_scale(points, normals, mu, load.wrenches(outer=False, sides=90),
                                 per_v, total_v)
        outer = _reference_scale(points, normals, mu, load.wrenches(outer=True, sides=90),
                                 per_v, total_v)
        if np.isinf(inner) and np.isinf(outer):
            assert np.isinf(got.scale)
            continue
        assert outer * (1 - 1e-7) - 1e-9 <= got.scale <= inner * (1 + 1e-7) + 1e-9
        if got.holds:
            W = load.wrenches(outer=False)
            assert got.forces.shape == (len(W), k, 2)
            for w, F in zip(W, got.forces, strict=True):
                assert np.allclose(F.sum(axis=0), -w[:2], atol=1e-6 * (1 + abs(w).max()))
        checked += 1
    assert checked >= 3


def test_an_ellipse_flattened_to_a_segment_is_the_box():
    load = dict(mass=0.8, com=(1.0, -2.0), accel=(4.0, 0.0), torque=(-3.0, 3.0))
    box, ell = Load(**load), Load(**load, accel_shape="ellipse")
    assert ell.is_polytope and np.array_equal(box.wrenches(), ell.wrenches())
    pts, nrm = [[-20, 0], [20, 0], [0, 15]], [[1, 0], [-1, 0], [0, -1]]
    assert grasp_payload(pts, nrm, 0.4, ell, 10).scale == \
        grasp_payload(pts, nrm, 0.4, box, 10).scale
    # the ellipse lies inside its box: a larger scale; and a circle's by hand.  Two
    # fingers at (-+20, 0) squeezing along x, the centre of mass between them: the
    # torque balance shares the vertical load F_y equally, the horizontal one takes
    # |F_x| off one finger's normal force, so mu (f - s |F_x|) >= s |F_y| / 2 with
    # F = m (g - a); the worst a on the circle of radius r makes |F_y| / 2 + mu |F_x|
    # as large as m (g / 2 + r sqrt(1/4 + mu^2))
    circle = Load(0.5, com=(0.0, 0.0), accel=(2.0, 2.0), accel_shape="ellipse")
    s = grasp_payload([[-20, 0], [20, 0]], [[1, 0], [-1, 0]], 0.5, circle, 10).scale
    assert s >= grasp_payload([[-20, 0], [20, 0]], [[1, 0], [-1, 0]], 0.5,
                              Load(0.5, com=(0.0, 0.0), accel=(2.0, 2.0)), 10).scale
    assert s == pytest.approx(0.5 * 10 / (0.5 * (9.80665 / 2 + 2.0 * np.sqrt(0.25 + 0.25))),
                              rel=1e-9)


def test_payload_of_a_squeeze_by_hand():
    """Two fingers squeezing horizontally hold the weight by friction alone: the scale
    is 2 mu f_max / (m g); a grip without friction holds nothing; without limits, any
    load (force closure is not needed: the weight alone is resisted)."""
    load = Load(0.5, com=(0.0, 0.0))
    p = grasp_payload([[-20, 0], [20, 0]], [[1, 0], [-1, 0]], 0.5, load, force_limit=10)
    assert p.scale == pytest.approx(2 * 0.5 * 10 / (0.5 * 9.80665))
    assert grasp_payload([[-20, 0], [20, 0]], [[1, 0], [-1, 0]], 0.0, load, 10).scale == 0
    assert np.isinf(grasp_payload([[-20, 0], [20, 0]], [[1, 0], [-1, 0]], 0.5, load).scale)
    # a total of 12 N shared by the two fingers: 2 mu * 6 N
    q = grasp_payload([[-20, 0], [20, 0]], [[1, 0], [-1, 0]], 0.5, load, total_limit=12)
    assert q.scale == pytest.approx(0.5 * 12 / (0.5 * 9.80665))


def _sample_grasps(rng, part, plan, count):
    """Points along each region (ends and vertices included), with its edge's normal."""
    out = []
    for _ in range(count):
        pts, nrm = [], []
        for r, edges in zip(plan.regions, plan.region_edges, strict=True):
            r = np.asarray(r, float)
            seg = np.hypot(*np.diff(r, axis=0).T)
            if len(r) == 1 or seg.sum() == 0:
                pts.append(r[0])
                nrm.append(-part.normals[edges[0]])
                continue
            j = int(rng.choice(len(seg), p=seg / seg.sum()))
            u = float(rng.choice([0.0, 1.0, rng.random()]))
            pts.append(r[j] + u * (r[j + 1] - r[j]))
            nrm.append(-part.normals[edges[j]])
        out.append((np.array(pts), np.array(nrm)))
    return out


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow) for s in (1, 2))])
def test_region_payload_is_below_every_grasp_of_the_regions(seed):
    """The certified scale of a plan's regions is at most the payload of every grasp
    sampled in them (and of the worst grasp reported), and within the requested gap."""
    rng = np.random.default_rng(seed)
    parts = [fc.read_part("demo:blob")]
    if seed:                                  # the others with -m slow
        parts += [fc.read_part("demo:quad"), random_polygon(rng, "star")]
    cases = 0
    for part in parts:
        for kw, boxes in ((dict(fingers=2, mu=0.4), 60), (dict(fingers=3, mu=0.4), 60),
                          (dict(fingers=4), 8)):
            for plan in fc.plan(part, top=1, **kw):
                load = Load(float(rng.uniform(0.1, 1.0)), accel=(2.0, 0.0),
                            torque=(-5.0, 5.0))
                limit = float(rng.uniform(5, 40))
                got = region_payload(part, plan, load, force_limit=limit, gap=0.02,
                                     max_boxes=boxes)
                assert got.lower <= got.upper
                if got.boxes < boxes:
                    assert got.gap <= 0.02 + 1e-9
                mu = plan.mu if plan.contact_type != "frictionless" else 0.0
                for pts, nrm in _sample_grasps(rng, part, plan, 15):
                    s = grasp_payload(pts, nrm, mu, load, limit, com=part.centroid).scale
                    assert got.lower <= s * (1 + 1e-7) + 1e-9
                cases += 1
    assert cases >= 3


@pytest.mark.parametrize("fingers", [2, pytest.param(3, marks=pytest.mark.slow)])
def test_region_payload_of_an_ellipse_is_below_its_grasps(fingers):
    """An ellipse of accelerations over a plan's regions: the certified scale (boxes
    over the ellipse's circumscribed polygon) is at most the exact scale of every grasp
    sampled in the regions, and the worst grasp's scale is an exact grasp's."""
    rng = np.random.default_rng(7)
    part = fc.read_part("demo:blob")
    load = Load(0.4, accel=(3.0, 1.5), torque=(-2.0, 2.0), accel_shape="ellipse")
    for kw in (dict(fingers=fingers, mu=0.4),):
        plan = fc.plan(part, top=1, **kw)[0]
        got = region_payload(part, plan, load, force_limit=12.0, gap=0.02, max_boxes=5)
        assert 0 < got.lower <= got.upper
        worst = grasp_payload(got.worst, [-part.normals[e[0]] for e in plan.region_edges],
                              plan.mu, load, 12.0, com=part.centroid).scale
        assert got.lower <= worst * (1 + 1e-7)
        for pts, nrm in _sample_grasps(rng, part, plan, 12):
            s = grasp_payload(pts, nrm, plan.mu, load, 12.0, com=part.centroid).scale
            assert got.lower <= s * (1 + 1e-7) + 1e-9


def test_load_and_payload_errors_name_the_argument():
    with pytest.raises(ValueError, match="mass"):
        Load(-1.0)
    with pytest.raises(ValueError, match="torque"):
        Load(1.0, torque=(3.0, -3.0))
    with pytest.raises(ValueError, match="accel"):
        Load(1.0, accel=(-1.0, 0.0))
    with pytest.raises(ValueError, match="com"):
        Load(1.0).wrenches()
    with pytest.raises(ValueError, match="accel_shape"):
        Load(1.0, accel=(1.0, 1.0), accel_shape="disc")
    load = Load(1.0, com=(0, 0))
    with pytest.raises(TypeError, match="load"):
        grasp_payload([[0, 0], [1, 0]], [[1, 0], [-1, 0]], 0.3, 5.0)
    with pytest.raises(ValueError, match="force_limit"):
        grasp_payload([[0, 0], [1, 0]], [[1, 0], [-1, 0]], 0.3, load, force_limit=[1, 2, 3])
    with pytest.raises(ValueError, match="normals"):
        grasp_payload([[0, 0], [1, 0]], [[0, 0], [-1, 0]], 0.3, load)
    with pytest.raises(TypeError, match="plan"):
        region_payload(fc.read_part("demo:blob"), "plan", load)


def test_plan_document_reports_the_payload_of_each_plan():
    """A request with a load: each grasp's certified payload in the JSON, equal to
    region_payload's; the load's options need --mass (the jaw's boxes:
    tests/test_jaw_payload.py)."""
    from fcgrasp.errors import RequestError
    from fcgrasp.planning import PlanRequest, plan_document

    doc = plan_document(PlanRequest(part="demo:quad", fingers=2, mu=0.4, top=2, mass=0.3,
                                    force_limit=10.0, accel=(1.0, 0.0)))
    assert doc.report["parameters"]["load"]["mass_kg"] == 0.3
    part = fc.read_part("demo:quad")
    for plan, g in zip(doc.plans, doc.report["grasps"], strict=True):
        want = region_payload(part, plan, Load(0.3, accel=(1.0, 0.0)), force_limit=10.0)
        assert g["payload"]["scale"] == pytest.approx(want.lower)
        assert g["payload"]["worst_grasp_scale"] == pytest.approx(want.upper)
    with pytest.raises(RequestError, match="--mass"):
        PlanRequest(part="demo:quad", force_limit=10.0)
    assert "--mass" in PlanRequest(part="demo:quad", mass=0.5).to_argv()


def test_plans_ranked_by_payload_are_the_pool_reranked():
    """rank_by="payload": the PAYLOAD_POOL x top plans of the smallest-region order,
    each with its certified payload, sorted by it (non-increasing); without a load it
    is refused, and so are force limits alone; the CLI needs --mass for it."""
    from fcgrasp.errors import RequestError
    from fcgrasp.planning import PlanRequest, plan_document
    from fcgrasp.planning.planner import PAYLOAD_POOL

    part = fc.read_part("demo:blob")
    load = Load(0.3, accel=(1.0, 0.0))
    pool = fc.plan(part, fingers=2, mu=0.4, top=PAYLOAD_POOL * 2)
    got = fc.plan(part, fingers=2, mu=0.4, top=2, load=load, force_limit=10.0,
                  rank_by="payload")
    scales = {p.edges: region_payload(part, p, load, force_limit=10.0).lower for p in pool}
    assert [p.payload.lower for p in got] == pytest.approx([scales[p.edges] for p in got])
    assert [p.edges for p in got] == sorted(scales, key=lambda e: -scales[e])[:2]
    assert got[0].payload.lower >= got[-1].payload.lower
    # the default order, each plan with its payload
    same = fc.plan(part, fingers=2, mu=0.4, top=2, load=load, force_limit=10.0)
    assert [p.edges for p in same] == [p.edges for p in pool[:2]]
    assert all(p.to_dict()["payload"]["scale"] == pytest.approx(scales[p.edges]) for p in same)
    with pytest.raises(ValueError, match="load"):
        fc.plan(part, rank_by="payload")
    from fcgrasp.pipeline import plan_spec
    with pytest.raises(ValueError, match="payload"):         # the search does not rank by it
        plan_spec(rank_by="payload")
    with pytest.raises(ValueError, match="force_limit"):
        fc.plan(part, force_limit=10.0)
    with pytest.raises(TypeError, match="load"):
        fc.plan(part, load=0.3)
    with pytest.raises(RequestError, match="--mass"):
        PlanRequest(part="demo:blob", rank_by="payload")
    doc = plan_document(PlanRequest(part="demo:blob", mu=0.4, top=2, mass=0.3,
                                    force_limit=10.0, accel=(1.0, 0.0), rank_by="payload"))
    assert [g["edges"] for g in doc.report["grasps"]] == [list(p.edges) for p in got]
