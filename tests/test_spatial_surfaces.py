"""Regions of two soft fingers across the facets of curved surfaces: every
grasp of every region, found on the mesh by casting rays (not by the planner's lifting),
with the normal of the triangle it lands on, passes the closed form at the cone's own
edge and the 6-D cone program; the regions are far larger than one facet allows on
curved solids, and nothing changes where no surface is curved."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from fcgrasp.spatial import closure_margin, soft_pair_plans, two_soft_closure
from fcgrasp.spatial.solid import demo_solid, solid_from_mesh
from fcgrasp.spatial.surfaces import SurfacePairPlan, surface_pair_plans

trimesh = pytest.importorskip("trimesh")


def _cast(mesh, triangles, starts, direction):
    """Every hit (point, triangle) of rays from ``starts`` along ``direction`` on the
    given triangles (Moller-Trumbore, written here): a list per ray."""
    tri = np.asarray(mesh.vertices)[np.asarray(mesh.faces)[triangles]]
    a, e1, e2 = tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    pvec = np.cross(direction, e2)                                  # (m, 3)
    det = np.einsum("ij,ij->i", e1, pvec)
    hits = []
    for s in starts:
        t = s - a
        u = np.einsum("ij,ij->i", t, pvec) / det
        q = np.cross(t, e1)
        v = (q @ direction) / det
        dist = np.einsum("ij,ij->i", e2, q) / det
        eps = 1e-9
        ok = (u >= -eps) & (v >= -eps) & (u + v <= 1 + eps) & (np.abs(det) > 1e-15)
        hits.append([(s + dist[k] * direction, int(triangles[k])) for k in np.flatnonzero(ok)])
    return hits


def _region_points(rng, solid, plan, k, n):
    """Points of region ``k`` on the surface with their inward normals: rays along the
    patch's axis through the octagon's corners, points along its outline, and ``n``
    random points inside it (the octagon in the plane across the axis)."""
    axis = plan.normals[k]
    corners = plan.regions[k]
    ring = np.concatenate([corners, plan.outlines[k]])
    inside = rng.dirichlet(np.ones(8), size=n) @ corners
    pts = np.concatenate([ring, inside])
    starts = pts - 2 * solid.size * axis
    out_p, out_n = [], []
    normals = -np.asarray(solid.mesh.face_normals)
    for hits in _cast(solid.mesh, plan.triangles[k], starts, axis):
        assert hits, "a point of the octagon is not over the patch"
        for p, t in hits:
            out_p.append(p)
            out_n.append(normals[t])
    return np.array(out_p), np.array(out_n)


def _solids():
    return {
        "cylinder": demo_solid("cylinder"),
        "mug": demo_solid("mug"),
        "sphere": solid_from_mesh(trimesh.creation.icosphere(subdivisions=3, radius=20.0)),
        "fine cylinder": solid_from_mesh(trimesh.creation.cylinder(radius=8.0, height=50.0,
                                                                   sections=200)),
        "capsule": solid_from_mesh(trimesh.creation.capsule(height=30.0, radius=10.0,
                                                            count=[24, 24])),
    }


def _random_smooth(seed):
    """A convex hull of points on a random ellipsoid (many nearly smooth facets)."""
    rng = np.random.default_rng(seed)
    pts = rng.normal(size=(int(rng.integers(60, 200)), 3))
    pts /= np.linalg.norm(pts, axis=1)[:, None]
    pts *= rng.uniform(5, 25, 3)
    return solid_from_mesh(trimesh.convex.convex_hull(pts), "mm", f"ellipsoid{seed}")


def _check_plans(rng, solid, mu, plans, inside=30):
    checked = 0
    for plan in plans:
        assert isinstance(plan, SurfacePairPlan)
        P1, N1 = _region_points(rng, solid, plan, 0, inside)
        P2, N2 = _region_points(rng, solid, plan, 1, inside)
        # every pair of the two regions' points (outlines and samples inside)
        i, j = (a.ravel() for a in np.meshgrid(np.arange(len(P1)), np.arange(len(P2))))
        P = np.stack([P1[i], P2[j]], axis=1)
        N = np.stack([N1[i], N2[j]], axis=1)
        assert two_soft_closure(P, N, mu).all()           # at the cone's own edge
        for k in rng.choice(len(P), 4, replace=False):    # torsional friction included
            assert closure_margin(P[k], N[k], mu, 0.5).closure
        assert plan.radius > 0 and set(plan.surfaces[0]) and set(plan.surfaces[1])
        for k in range(2):
            _check_surface_triangles(solid, plan, k)
        checked += 1
    return checked


def _check_surface_triangles(solid, plan, k):
    """The region's triangles lie on the patch (a ray along the axis through each
    one's centroid meets the patch there) and cover the octagon: their areas across
    the axis add up to the regular octagon's, ``2 sqrt(2) r^2``."""
    axis = plan.normals[k]
    tris = plan.surface_triangles[k]
    cent = tris.mean(axis=1)
    for c, hits in zip(cent, _cast(solid.mesh, plan.triangles[k],
                                   cent - 2 * solid.size * axis, axis), strict=True):
        assert min(np.linalg.norm(p - c) for p, _ in hits) < 1e-7 * solid.size
    e1, e2 = tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]
    across = np.abs(np.cross(e1, e2) @ axis) / 2
    r = plan.radii[k] if getattr(plan, "radii", ()) else plan.radius
    assert across.sum() == pytest.approx(2 * math.sqrt(2) * r ** 2, rel=1e-6)


@pytest.mark.parametrize("name", ["cylinder", "mug", "sphere",
                                  *(pytest.param(n, marks=pytest.mark.slow)
                                    for n in ("fine cylinder", "capsule"))])
def test_every_grasp_across_facets_holds_on_curved_solids(name):
    solid = _solids()[name]
    rng = np.random.default_rng(len(name))
    # the mug with both frictions; the others with one each by default
    mus = {"cylinder": (0.3,), "sphere": (0.6,)}.get(name, (0.3, 0.6))
    for mu in mus:
        alpha = math.atan(mu) - math.radians(0.5)
        plans = surface_pair_plans(solid, mu, alpha, top=4)
        assert plans, f"{name}: no region across facets"
        assert _check_plans(rng, solid, mu, plans) == len(plans)


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 30))])
def test_every_grasp_across_facets_holds_on_random_smooth_solids(seed):
    rng = np.random.default_rng(seed)
    solid = _random_smooth(seed)
    mu = float(rng.choice([0.25, 0.5, 1.0]))
    plans = surface_pair_plans(solid, mu, math.atan(mu) - math.radians(0.5), top=3)
    _check_plans(rng, solid, mu, plans, inside=15)


def test_regions_across_facets_are_far_larger_than_one_facet_allows():
    """On a 200-sided cylinder the side's facets are 0.25 mm strips: the exact facet
    regions there are slivers, the regions across facets are millimetres wide, below the
    bound of a true cylinder (two discs of radius ``rho`` on the side, facing across the
    diameter ``2 R``: some pair of their points is ``2 rho`` apart along the axis, so
    ``rho <= R tan(alpha)``), and they are ranked with the facets' own (the caps)."""
    R, mu = 8.0, 0.5
    alpha = math.atan(mu) - math.radians(0.5)
    solid = _solids()["fine cylinder"]
    strip = 2 * R * math.sin(math.pi / 200)            # a side facet's width
    one_facet = strip / (2 * math.cos(math.pi / 8))    # the widest octagon in it
    across = surface_pair_plans(solid, mu, alpha, top=3)
    assert all(isinstance(p, SurfacePairPlan) for p in across)
    assert across[0].radius > 10 * one_facet
    assert across[0].radius * math.cos(math.pi / 8) <= R * math.tan(alpha)
    mixed = soft_pair_plans(solid, mu, top=3)
    assert [p.radius for p in mixed] == sorted([p.radius for p in mixed], reverse=True)
    assert any(isinstance(p, SurfacePairPlan) for p in mixed)


def test_nothing_changes_where_no_surface_is_curved():
    for name in ("box", "prism", "angle"):
        solid = demo_solid(name)
        assert surface_pair_plans(solid, 0.5, math.atan(0.5), top=5) == []
        got = soft_pair_plans(solid, 0.5, top=5)
        want = soft_pair_plans(solid, 0.5, top=5, across=False)
        assert [(p.facets, p.radius) for p in got] == [(p.facets, p.radius) for p in want]


def test_a_plan_across_facets_in_json_and_on_the_command_line(tmp_path):
    import json

    from fcgrasp.apps.cli import main

    out = tmp_path / "mug.json"
    assert main(["plan", "demo:mug", "--fingers", "2", "--soft", "--mu", "0.5", "--top", "3",
                 "--json", str(out)]) == 0
    doc = json.loads(out.read_text())
    want = soft_pair_plans(demo_solid("mug"), 0.5, top=3)
    assert [g["radius"] for g in doc["grasps"]] == pytest.approx([p.radius for p in want])
    g = doc["grasps"][0]
    assert g["across_facets"] and len(g["surfaces"]) == 2 and len(g["outlines"][0]) > 8
    assert np.allclose(g["surface_triangles"][1], want[0].surface_triangles[1])
    assert len(g["spread_deg"]) == 2 and all(0 < s < 26.6 for s in g["spread_deg"])
    with pytest.raises(TypeError, match="across"):
        soft_pair_plans(demo_solid("mug"), 0.5, across="yes")


@pytest.mark.parametrize("name", ["sphere", pytest.param("mug", marks=pytest.mark.slow),
                                  pytest.param("capsule", marks=pytest.mark.slow)])
def test_the_bounds_hold_and_the_gap_is_kept(name):
    """Every pair's bound (extent, widths, cones, inscribed circles) is at least the
    cone program's radius on it; the search with its default gap keeps plans within
    ``1 + GAP`` of the search without one (the best of the whole family)."""
    from fcgrasp.spatial import _patches as P
    from fcgrasp.spatial import surfaces as S

    solid = _solids()[name]
    mu = 0.5
    alpha = math.atan(mu) - math.radians(0.5)
    normals, adj, _ = P._graph(solid)
    rng = np.random.default_rng(7)
    seeds = P._seeds(normals, adj, np.asarray(solid.mesh.area_faces), alpha / 4)
    checked = 0
    for i in rng.choice(seeds, 6, replace=False):
        j = int(np.argmin(normals @ normals[i]))
        d = normals[i] - normals[j]
        d /= np.linalg.norm(d)
        for f in S.SPREADS:
            beta = f * alpha
            along = normals @ d
            a = P._grow(int(i), (along >= math.cos(beta)).tolist(), adj)
            b = P._grow(j, (-along >= math.cos(beta)).tolist(), adj)
            if not a or not b:
                continue
            p = S._patch(solid, int(i), beta, a, normals, d)
            q = S._patch(solid, j, beta, b, normals, -d)
            S._kernel(solid, p), S._kernel(solid, q)
            bound = min(S._pair_bound(p, q, alpha), p.inradius / math.cos(math.pi / 8),
                        q.inradius / math.cos(math.pi / 8))
            got = S._program(p, q, (alpha - beta, alpha - beta))
            if got is None:
                continue
            r = S._certified(got[0], got[1], p, q, (alpha - beta,) * 2, got[2])
            assert r <= bound * (1 + 1e-9)
            checked += 1
    assert checked >= 3
    best = surface_pair_plans(solid, mu, alpha, top=2, gap=0.0)
    kept = surface_pair_plans(solid, mu, alpha, top=2)
    assert kept[0].radius * (1 + S.GAP) >= best[0].radius * (1 - 1e-9)


def test_regions_across_facets_scale_with_the_part():
    """In metres or in micrometres the same cylinder gives the same regions, scaled
    (no absolute length hides in the search: tolerances are relative to the part)."""
    mu = 0.5
    alpha = math.atan(mu) - math.radians(0.5)
    mesh = demo_solid("cylinder").mesh
    base = surface_pair_plans(solid_from_mesh(mesh), mu, alpha, top=2)
    for scale in (1e-3, 1e3):
        scaled = mesh.copy()
        scaled.apply_scale(scale)
        got = surface_pair_plans(solid_from_mesh(scaled), mu, alpha, top=2)
        assert [p.radius for p in got] == pytest.approx([p.radius * scale for p in base],
                                                        rel=1e-6)


@pytest.mark.parametrize("name", ["sphere", *(pytest.param(n, marks=pytest.mark.slow)
                                            for n in ("mug", "fine cylinder"))])
def test_every_triple_across_facets_holds(name):
    """Three fingers with friction across facets: triples of the regions' points (found
    on the mesh by rays, with their triangles' normals: outlines, corners and points
    inside) pass the exact 6-D cone program at the cone narrowed by the margin alone."""
    from fcgrasp.spatial.surfaces import SurfaceTriplePlan, surface_triple_plans

    solid = _solids()[name]
    rng = np.random.default_rng(3)
    mu = 0.5
    alpha = math.atan(mu) - math.radians(0.5)
    plans = surface_triple_plans(solid, mu, alpha, top=2)
    assert plans and all(isinstance(p, SurfaceTriplePlan) for p in plans)
    for plan in plans:
        regions = [_region_points(rng, solid, plan, k, 10) for k in range(3)]
        # the certificate's premises: every point within delta of its contact (the
        # corners at delta, to rounding: delta is already less the hull's rounding),
        # every normal within the patch's spread of its axis
        for k, (P, N) in enumerate(regions):
            reach = np.linalg.norm(P - plan.centers[k], axis=1)
            assert np.all(reach <= plan.delta * (1 + 1e-9))
            angle = np.degrees(np.arccos(np.clip(N @ plan.normals[k], -1, 1)))
            assert np.all(angle <= plan.spread[k] + 1e-6)
        for _ in range(60):
            picks = [rng.integers(len(P)) for P, _ in regions]
            P = np.array([regions[k][0][i] for k, i in enumerate(picks)])
            N = np.array([regions[k][1][i] for k, i in enumerate(picks)])
            assert closure_margin(P, N, math.tan(alpha)).closure
        for k in range(3):
            _check_surface_triangles(solid, plan, k)
        assert plan.radius <= plan.delta


@pytest.mark.slow       # the default suite's time: test_spatial_triples runs the CLI
def test_three_fingers_across_facets_on_the_command_line(tmp_path):
    """``fcgrasp plan demo:cylinder --fingers 3`` ranks regions across facets with the
    facet triples (:func:`three_finger_plans`), and writes them in the JSON."""
    import json

    from fcgrasp.apps.cli import main
    from fcgrasp.spatial import point_triple_plans, three_finger_plans

    out = tmp_path / "cyl3.json"
    assert main(["plan", "demo:cylinder", "--fingers", "3", "--mu", "0.5", "--top", "3",
                 "--json", str(out)]) == 0
    doc = json.loads(out.read_text())
    cyl = demo_solid("cylinder")
    want = three_finger_plans(cyl, 0.5, top=3)
    assert [g["radius"] for g in doc["grasps"]] == pytest.approx([p.radius for p in want.plans])
    assert doc["grasps"][0]["across_facets"] and len(doc["grasps"][0]["surfaces"]) == 3
    assert want.plans[0].radius > point_triple_plans(cyl, 0.5, top=1).plans[0].radius
    assert three_finger_plans(cyl, 0.5, top=3, across=False).plans[0].radius == \
        point_triple_plans(cyl, 0.5, top=1).plans[0].radius
    with pytest.raises(TypeError, match="across"):
        three_finger_plans(cyl, 0.5, across=1)


def test_the_second_level_across_facets_grows_one_region():
    """Leximin across facets (definition 7.1's second level): on the mug one region of
    the top plan grows past the first level's radius, the other keeps it, and every pair
    of their points found on the mesh by rays holds (:func:`_check_plans`, whose
    triangles' areas are checked against each region's own radius)."""
    solid = demo_solid("mug")
    mu = 0.5
    plan = soft_pair_plans(solid, mu, top=1)[0]
    assert isinstance(plan, SurfacePairPlan) and max(plan.radii) > plan.radius * 1.01
    assert min(plan.radii) == plan.radius
    _check_plans(np.random.default_rng(5), solid, mu, [plan], inside=20)
    flat = soft_pair_plans(solid, mu, top=1, leximin=False)[0]
    assert flat.radii == (flat.radius, flat.radius) and flat.radius == plan.radius


def test_a_patch_whose_projected_triangles_overlap_has_a_kernel(monkeypatch):
    """Triangles of a patch that overlap in its plane's projection (a fold) are united
    in full, also where GEOS's coverage union refuses them (it raises on some overlaps:
    ``fcgrasp plan angle_block.STL --mu 1.0 --distinct 0.3`` met one); the kernel's
    piece is inside the union."""
    from types import SimpleNamespace

    import shapely

    from fcgrasp.spatial._patches import _kernel

    vertices = np.array([[0.0, 0, 0], [10, 0, 0], [0, 10, 0], [2, 2, 1], [12, 2, 1],
                         [2, 12, 1]])
    faces = np.array([[0, 1, 2], [3, 4, 5]])
    solid = SimpleNamespace(mesh=SimpleNamespace(vertices=vertices, faces=faces),
                            triangles=vertices[faces], size=20.0)
    frame = SimpleNamespace(origin=np.zeros(3), axes=np.array([[1.0, 0, 0], [0, 1.0, 0]]))
    union = shapely.union_all(shapely.polygons(vertices[faces][:, :, :2]))

    def refused(*args, **kwargs):
        raise shapely.errors.GEOSException("CoverageUnion cannot process overlapping inputs")

    for coverage in (shapely.coverage_union_all, refused):
        monkeypatch.setattr(shapely, "coverage_union_all", coverage)
        patch = SimpleNamespace(kernel=None, triangles=np.array([0, 1]), frame=frame,
                                centre=np.zeros(2), middle=np.zeros(2), inradius=np.inf)
        E, h = _kernel(solid, patch)
        assert len(E) and np.all(E @ patch.middle <= h + 1e-9)
        assert union.buffer(1e-6).contains(shapely.Point(patch.middle))


@pytest.mark.slow
def test_the_mesh_whose_patch_geos_refused_plans(tmp_path, capsys):
    from fcgrasp.apps.cli import main

    mesh = Path(__file__).resolve().parents[1] / "benchmarks/corpus/meshes/angle_block.STL"
    out = tmp_path / "plans.json"
    assert main(["plan", str(mesh), "--mu", "1.0", "--distinct", "0.3", "--json",
                 str(out), "--quiet"]) == 0, capsys.readouterr().err
