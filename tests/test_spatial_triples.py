"""Three point fingers with friction on solids: the certified radius is sound
(every grasp moved by less than it passes the exact cone program) and equals the
zero-force slice's inradius as an LP computes it; every grasp of the returned regions is
in force closure; the search equals certifying every triple; the filter on the normals
drops only triples that cannot hold; the command line plans meshes for three fingers."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from fcgrasp.spatial import closure_margin
from fcgrasp.spatial.contacts import contact_frames
from fcgrasp.spatial.solid import demo_solid, solid_from_mesh
from fcgrasp.spatial.triples import (
    PYRAMID_EDGES,
    _balance,
    _piece_table,
    perturbation_radius,
    point_triple_plans,
    point_triple_regions,
)

trimesh = pytest.importorskip("trimesh")

MARGIN = 0.5


def _alpha(mu):
    return math.atan(mu) - math.radians(MARGIN)


def _random_grasp(rng):
    """Three contacts near a sphere with inward normals turned by up to 25 degrees;
    some nearly collinear, some with coplanar normals, at scales 1e-3 to 1e3."""
    kind = rng.integers(4)
    d = rng.normal(size=(3, 3))
    d /= np.linalg.norm(d, axis=1)[:, None]
    if kind == 1:                          # nearly on a great circle: coplanar normals
        d[:, 2] = rng.normal(scale=1e-3, size=3)
        d /= np.linalg.norm(d, axis=1)[:, None]
    if kind == 2:                          # two contacts nearly opposite
        d[1] = -d[0] + rng.normal(scale=1e-3, size=3)
        d[1] /= np.linalg.norm(d[1])
    n = -d + rng.normal(scale=0.2, size=(3, 3))
    n /= np.linalg.norm(n, axis=1)[:, None]
    scale = 10.0 ** rng.uniform(-3, 3)
    mu = float(rng.uniform(0.2, 1.0))
    return scale * d * rng.uniform(0.5, 1.5, (3, 1)), n, mu


def _tangent_moves(rng, n, length):
    """Moves of the given length in each contact's tangent plane, random directions."""
    t1, t2 = contact_frames(n)
    a = rng.uniform(0, 2 * np.pi, 3)
    return length * (np.cos(a)[:, None] * t1 + np.sin(a)[:, None] * t2)


def _pyramids(points, normals, alpha):
    """The pyramids' unit forces and their moments about the contacts' mean, (3 edges, 3)
    each, built here from the contacts' frames."""
    t1, t2 = contact_frames(normals)
    f, m = [], []
    for k in range(PYRAMID_EDGES):
        a = 2 * np.pi * k / PYRAMID_EDGES
        fk = normals + math.tan(alpha) * (math.cos(a) * t1 + math.sin(a) * t2)
        fk /= np.linalg.norm(fk, axis=1)[:, None]
        f.append(fk)
        m.append(np.cross(points - points.mean(axis=0), fk))
    return np.concatenate(f), np.concatenate(m)


def _slice_support(points, normals, alpha, v):
    """The zero-force slice's support along ``v``: max v . sum(l m) over unit weights
    ``l >= 0`` of the pyramids' generators with zero net force (HiGHS)."""
    from ._highs import linprog

    F, M = _pyramids(points, normals, alpha)
    res = linprog(-(M @ v), A_eq=np.vstack([F.T, np.ones(len(F))]),
                  b_eq=np.r_[0, 0, 0, 1.0], bounds=(0, None), method="highs")
    return -res.fun if res.status == 0 else -math.inf


@pytest.mark.parametrize("cases", [200, pytest.param(4000, marks=pytest.mark.slow)])
def test_certified_radius_is_sound(cases):
    rng = np.random.default_rng(33)
    positive = 0
    for _ in range(cases):
        p, n, mu = _random_grasp(rng)
        delta = perturbation_radius(p, n, mu, margin=MARGIN)
        nominal = closure_margin(p, n, math.tan(_alpha(mu)))
        if delta == 0:
            continue
        positive += 1
        assert nominal.closure                       # a certificate implies closure
        for _ in range(3):                           # moved by (almost) the radius
            q = p + _tangent_moves(rng, n, delta * (1 - 1e-9))
            assert closure_margin(q, n, math.tan(_alpha(mu))).closure
        # the radius scales with the part
        assert perturbation_radius(3 * p, n, mu, MARGIN) == pytest.approx(3 * delta,
                                                                          rel=1e-6)
    assert positive >= cases // 5                    # the certificate is not vacuous


@pytest.mark.parametrize("cases", [5, pytest.param(600, marks=pytest.mark.slow)])
def test_certified_radius_is_the_slices_inradius(cases):
    """The slice's support (an LP) is at least the radius in 100 random directions, and
    equals it along the normal of the hull's nearest facet (the radius is not needlessly
    small): the hull taken here on unscaled moments."""
    from scipy.spatial import ConvexHull

    rng = np.random.default_rng(7)
    seen = 0
    while seen < cases:
        p, n, mu = _random_grasp(rng)
        delta = perturbation_radius(p, n, mu, margin=MARGIN)
        if delta == 0:
            continue
        seen += 1
        alpha = _alpha(mu)
        v = rng.normal(size=(100, 3))
        v /= np.linalg.norm(v, axis=1)[:, None]
        h = np.array([_slice_support(p, n, alpha, x) for x in v])
        assert h.min() >= delta * (1 - 1e-7)
        eq = ConvexHull(np.hstack(_pyramids(p, n, alpha))).equations
        moment = np.linalg.norm(eq[:, 3:6], axis=1)
        k = np.argmin(-eq[:, 6] / np.maximum(moment, 1e-300))
        reach = np.max(np.linalg.norm(p - p.mean(axis=0), axis=1))  # the rounding's scale
        assert _slice_support(p, n, alpha, eq[k, 3:6] / moment[k]) == \
            pytest.approx(delta, rel=1e-7, abs=1e-8 * reach)


def test_the_normals_filter_drops_only_triples_that_cannot_hold():
    rng = np.random.default_rng(5)
    dropped = 0
    for _ in range(400):
        p, n, mu = _random_grasp(rng)
        if rng.random() < 0.5:                           # normals in one half-space
            n[:, 2] = -np.abs(n[:, 2]) - 0.3
            n /= np.linalg.norm(n, axis=1)[:, None]
        alpha = _alpha(mu)
        if not _balance(n[None], alpha)[0]:
            dropped += 1
            assert not closure_margin(p, n, math.tan(alpha)).closure
            assert perturbation_radius(p, n, mu, MARGIN) == 0
    assert dropped >= 40


def _grasps(rng, plan, corners, inside):
    """``corners`` random triples of the octagons' corners, then ``inside`` triples of
    points inside them."""
    R = plan.regions
    out = [np.array([R[k, rng.integers(8)] for k in range(3)]) for _ in range(corners)]
    for _ in range(inside):
        out.append(np.array([rng.dirichlet(np.ones(8)) @ R[k] for k in range(3)]))
    return out


def _random_convex(seed):
    rng = np.random.default_rng(seed)
    pts = rng.normal(size=(int(rng.integers(6, 12)), 3)) * rng.uniform(5, 20, 3)
    return solid_from_mesh(trimesh.convex.convex_hull(pts), "mm", f"hull{seed}")


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 25))])
def test_every_grasp_of_the_regions_is_force_closure(seed):
    rng = np.random.default_rng(seed)
    # the mug (the slowest to plan) with the slow seeds
    solids = [demo_solid(n) for n in ("box", "prism", "angle")] if seed == 0 \
        else [demo_solid("mug"), _random_convex(seed)] if seed == 1 else [_random_convex(seed)]
    corners, inside = (20, 6) if seed == 0 else (512, 40)
    checked = 0
    for solid in solids:
        mu = float(rng.choice([0.4, 0.8]))
        for plan in point_triple_plans(solid, mu, top=3, margin=MARGIN).plans:
            tight = math.tan(_alpha(mu))
            for P in _grasps(rng, plan, corners, inside):
                assert closure_margin(P, plan.normals, tight).closure
            for f, reg in zip(plan.facets, plan.regions, strict=True):
                facet = solid.facets[f]
                assert np.allclose((reg - facet.origin) @ facet.normal, 0,
                                   atol=1e-9 * solid.size)
                from shapely import points
                poly = facet.polygon.buffer(1e-7 * solid.size)
                assert poly.contains(points(facet.to_2d(reg))).all()
            assert plan.radius <= plan.delta
            checked += 1
    assert checked >= 1 or seed


def _every_triple(solid, mu):
    """The nominal radius of every triple of pieces on three facets, largest first."""
    table = _piece_table(solid)
    n = len(table.facet)
    out = []
    for a in range(n):
        for b in range(a + 1, n):
            for c in range(b + 1, n):
                f = [int(table.facet[x]) for x in (a, b, c)]
                if len(set(f)) < 3:
                    continue
                local = [int(table.local[x]) for x in (a, b, c)]
                got = point_triple_regions(solid, f, mu, MARGIN, local, refine=False)
                if got is not None:
                    out.append(got.radius)
    return sorted(out, reverse=True)


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 12))])
def test_search_equals_certifying_every_triple(seed):
    solids = [demo_solid("prism")] if seed == 0 else [_random_convex(100 + seed)]
    for solid in solids:
        want = _every_triple(solid, 0.5)
        for top in (1, 4, None):
            got = point_triple_plans(solid, 0.5, top=top, margin=MARGIN, refine=False)
            assert got.exhaustive
            k = len(want) if top is None else min(top, len(want))
            assert [p.radius for p in got.plans] == pytest.approx(want[:k], rel=1e-12)
        # refining never shrinks a plan
        refined = point_triple_plans(solid, 0.5, top=1, margin=MARGIN)
        assert [p.radius for p in refined.plans][:1] >= want[:1]


@pytest.mark.slow
def test_gap_to_the_failing_radius():
    """At the top plan's centres, the radius at which some triple of the octagons'
    corners fails the cone program (bisection) is at most 3.5 times the certified one
    (measured: 1.5 - 2.5 on the built-in solids)."""
    for name in ("box", "prism", "angle"):
        solid = demo_solid(name)
        plan = point_triple_plans(solid, 0.5, top=1, margin=MARGIN).plans[0]
        tight = math.tan(_alpha(0.5))
        unit = (plan.regions - plan.centers[:, None, :]) / plan.radius

        def fails(r, plan=plan, unit=unit, tight=tight):
            R = plan.centers[:, None, :] + r * unit
            return any(not closure_margin(np.array([R[0, i], R[1, j], R[2, k]]),
                                          plan.normals, tight).closure
                       for i in range(8) for j in range(8) for k in range(8))

        assert not fails(plan.radius)
        assert fails(3.5 * plan.radius)


def test_errors_name_the_argument():
    box = demo_solid("box")
    with pytest.raises(ValueError, match="facets must be three different"):
        point_triple_regions(box, (0, 0, 1), 0.5)
    with pytest.raises(ValueError, match="mu"):
        point_triple_plans(box, -1.0)
    with pytest.raises(TypeError, match="solid must be"):
        point_triple_plans("box", 0.5)
    with pytest.raises(ValueError, match="points and normals must be three contacts"):
        perturbation_radius([[0, 0, 0]], [[1, 0, 0]], 0.5)


def test_cli_plans_three_fingers_on_a_mesh(tmp_path, capsys):
    from fcgrasp.apps.cli import main

    path = tmp_path / "block.stl"
    trimesh.creation.box((30, 20, 10)).export(path)
    out = tmp_path / "plan.json"
    assert main(["plan", str(path), "--fingers", "3", "--mu", "0.5", "--top", "2",
                 "--json", str(out)]) == 0
    doc = json.loads(out.read_text())
    assert doc["parameters"]["fingers"] == 3 and doc["parameters"]["exhaustive"]
    g = doc["grasps"][0]
    assert len(g["facets"]) == 3 and g["contact_type"] == "friction"
    assert np.asarray(g["regions"]).shape == (3, 8, 3)
    # two fingers on a solid are soft fingers, --soft given or not
    plain, soft = tmp_path / "plain.json", tmp_path / "soft.json"
    assert main(["plan", str(path), "--fingers", "2", "--top", "2", "--json", str(plain)]) == 0
    assert main(["plan", str(path), "--fingers", "2", "--soft", "--top", "2", "--json",
                 str(soft)]) == 0
    got, want = json.loads(plain.read_text()), json.loads(soft.read_text())
    assert got["grasps"] == want["grasps"] and got["grasps"][0]["contact_type"] == "soft"
    capsys.readouterr()
    assert main(["plan", str(path), "--fingers", "4"]) == 2
    err = capsys.readouterr().err
    assert "frictionless fingers hold planar parts only" in err \
        and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 10))])
def test_a_separating_direction_spares_the_hull_and_changes_no_radius(seed, monkeypatch):
    """The slice's radius with the separating direction's shortcut (``_separated``: 0 at
    once) is the radius read from the 6-D hull (the reference) on 1,000 seeded triples
    of every kind (nearly collinear contacts, coplanar normals, contacts nearly
    opposite, scales 1e-3 to 1e3, narrow and wide cones; 200 by default), and the
    shortcut decides a good share of those that fail (the hull's path: the slice's
    vertices, ``tests/test_spatial_slice.py``, left out)."""
    from fcgrasp.spatial import triples as T

    monkeypatch.setattr(T, "SLICE_VERTICES", False)
    rng = np.random.default_rng(seed)
    spared = failed = 0
    for _ in range(200 if seed == 0 else 1000):
        p, n, mu = _random_grasp(rng)
        if rng.random() < 0.3:                      # some far from holding
            n = n * np.where(rng.random(3) < 0.5, 1.0, -1.0)[:, None]
        w = T._generators(p, n, _alpha(mu))
        want = T._hull_slice_radius(w)
        assert T._slice_radius(w) == want
        failed += want == 0.0
        if T._separated(w):
            assert want == 0.0
            spared += 1
    assert spared > 0.3 * failed > 0, (spared, failed)


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 6))])
def test_the_facet_bound_is_never_below_the_hulls_radius(seed):
    """The bound of the slice's radius from other hulls' facets (``_facet_bound``) is
    never below the radius the hull gives (the reference), whatever the facets: those
    of the same contacts moved a little (as a triple's refinement reads them), of
    another triple, or random directions (a negative bound read as 0, the radius of a
    hull without the origin); and from the nearby hull it is close."""
    from fcgrasp.spatial import triples as T

    rng = np.random.default_rng(50 + seed)
    close = tight = 0
    for _ in range(80 if seed == 0 else 300):
        p, n, mu = _random_grasp(rng)
        w = T._generators(p, n, _alpha(mu))
        want, _ = T._hull_slice(w)
        moved = p + rng.normal(size=p.shape) * rng.choice([1e-3, 1e-2, 0.1]) \
            * float(np.ptp(p))
        _, near = T._hull_slice(T._generators(moved, n, _alpha(mu)))
        q, m, mu2 = _random_grasp(rng)
        _, other = T._hull_slice(T._generators(q, m, _alpha(mu2)))
        for facets in (near, other, rng.normal(size=(50, 6))):
            if facets is None:
                continue
            # (a negative bound: the origin is outside, the radius 0)
            bound = max(T._facet_bound(w, facets), 0.0)
            assert bound >= want - 1e-12 * max(1.0, abs(want)), (bound, want)
        if near is not None and want > 0:
            close += 1
            tight += T._facet_bound(w, near) <= 1.5 * want
    assert close > 12 and tight > 0.5 * close, (close, tight)


@pytest.mark.parametrize("names", [pytest.param(("cylinder", 4), marks=pytest.mark.slow),
                                   pytest.param(("box", 3), marks=pytest.mark.slow)])
def test_triples_refined_with_the_facet_bound_are_the_plans_without_it(names, monkeypatch):
    """The refinement that skips the hulls the facet bound rules out takes the same
    moves: three fingers' plans on meshes with and without it are equal."""
    import fcgrasp as fc
    from fcgrasp.spatial import triples as T

    spared = []
    hull = T._hull_slice
    for solid in (demo_solid(names[0]), _random_convex(names[1])):
        got = []
        for on in (False, True):
            calls = [0]

            def counted(w, calls=calls):
                calls[0] += 1
                return hull(w)

            monkeypatch.setattr(T, "FACET_BOUND", on)
            monkeypatch.setattr(T, "SLICE_VERTICES", False)     # every slice a hull
            monkeypatch.setattr(T, "_hull_slice", counted)
            got.append(([p.to_dict() for p in fc.plan(solid, fingers=3, mu=0.5, top=5)],
                        calls[0]))
        (off, n_off), (on_, n_on) = got
        assert json.dumps(off, sort_keys=True, default=str) == \
            json.dumps(on_, sort_keys=True, default=str)
        spared.append(n_off - n_on)
    assert sum(spared) > 0, spared


def test_a_triple_search_the_clock_ends_keeps_regions_that_hold(monkeypatch):
    """The clock ending inside three fingers' search of a solid (looked at every few
    triples certified, and before each plan's refinement): the plans kept hold at every
    sampled grasp by the cone program, and the answer says it was cut short."""
    import fcgrasp as fc
    from fcgrasp.spatial import triples as T

    from .clock import clock_ending_after

    rng = np.random.default_rng(6)
    solid = _random_convex(5)
    seen = 0
    for ends_after in (0, 1, 3, 12):
        monkeypatch.setattr(T, "cut_if_over", clock_ending_after(ends_after))
        plans = fc.plan(solid, fingers=3, mu=0.6, top=4, time_limit=None)
        assert not plans.complete and not plans.exact
        for plan in plans:
            if not hasattr(plan, "delta"):
                continue                    # a plan across facets (not this search's)
            for P in _grasps(rng, plan, 16, 4):
                assert closure_margin(P, plan.normals, math.tan(_alpha(0.6))).closure
            assert plan.radius <= plan.delta
            seen += 1
    assert seen >= 3, seen


def test_the_fits_a_search_keeps_are_each_pieces_own():
    """The octagon fits a search keeps per piece (``own_octagon_fit``) are ``_fit`` of
    that piece, whatever order the pieces are asked in, and a triple's nominal centres
    read them."""
    from fcgrasp.spatial._pieces import _fit, own_octagon_fit
    from fcgrasp.spatial.regions import OCTAGON
    from fcgrasp.spatial.triples import _nominal

    table = _piece_table(_random_convex(3))
    order = np.random.default_rng(3).permutation(len(table.facet))
    for p in order.tolist():
        want = _fit(table.halfplanes[p], OCTAGON, table.width[p])
        got = own_octagon_fit(table, p, OCTAGON)
        assert got[0] == want[0] and np.array_equal(got[1], want[1])
    assert len(table.own_octagon) == len(order)
    _, start = _nominal(table, (0, 1, 2))
    assert np.array_equal(start, [table.own_octagon[p][1] for p in (0, 1, 2)])
