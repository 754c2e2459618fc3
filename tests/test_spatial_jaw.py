"""A parallel jaw with flat pads on solids: every axis of every returned
region meets both facets, holds (the 6-D cone program, soft contacts), and its pads
reach their facets before any other part of the solid (rays cast here, Moller-Trumbore,
against every triangle); axes just outside the region fail one of these; the box gives
its faces; the command line plans a mesh for the jaw."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from fcgrasp.spatial import closure_margin
from fcgrasp.spatial.jaw import solid_jaw_plans, solid_jaw_region
from fcgrasp.spatial.solid import demo_solid, solid_from_mesh

trimesh = pytest.importorskip("trimesh")
shapely = pytest.importorskip("shapely")

MU, MARGIN, PAD, STROKE = 0.5, 0.5, 6.0, (2.0, 80.0)


def _first_hit(mesh, origin, direction):
    """The distance along ``direction`` from ``origin`` to the first triangle it meets
    (Moller-Trumbore on every triangle), inf when none."""
    tri = mesh.vertices[mesh.faces]
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    p = np.cross(direction, e2)
    det = np.einsum("ij,ij->i", e1, p)
    ok = np.abs(det) > 1e-12
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = origin - tri[:, 0]
    u = np.einsum("ij,ij->i", s, p) * inv
    q = np.cross(s, e1)
    v = (q @ direction) * inv
    t = np.einsum("ij,ij->i", e2, q) * inv
    eps = 1e-9
    hit = ok & (u >= -eps) & (v >= -eps) & (u + v <= 1 + eps) & (t > 0)
    return float(t[hit].min()) if hit.any() else math.inf


def _pad_reaches(solid, centre, axis, pad, towards):
    """Whether a round pad of diameter ``pad`` centred at ``centre`` (on its facet's
    plane), closing ``towards`` the part along ``axis``, first touches the part in that
    plane: rays from far outside through 24 points of its rim and its centre."""
    far = 2 * solid.size
    u = np.cross(axis, [1.0, 0, 0] if abs(axis[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    w = np.cross(axis, u)
    ring = [centre] + [centre + 0.5 * pad * (math.cos(a) * u + math.sin(a) * w)
                       for a in np.linspace(0, 2 * np.pi, 24, endpoint=False)]
    d = towards * axis
    for q in ring:
        t = _first_hit(solid.mesh, q - far * d, d)
        if t < far - 1e-7 * solid.size:       # something before the facet's plane
            return False
    return True


def _holds(solid, plan, x):
    """Every check of an axis through ``x`` (a point of the first facet's plane): it
    meets both facets, the soft contacts hold, both pads reach their facets."""
    a, b = (solid.facets[f] for f in plan.facets)
    y = x + plan.opening * plan.axis
    on = [f.polygon.buffer(1e-9 * solid.size).contains(
        shapely.Point(f.to_2d(p))) for f, p in ((a, x), (b, y))]
    if not all(on):
        return False
    if not closure_margin(np.array([x, y]), plan.normals,
                          math.tan(math.atan(MU) - math.radians(MARGIN)), 0.1).closure:
        return False
    return _pad_reaches(solid, x, plan.axis, plan.pad, 1.0) and \
        _pad_reaches(solid, y, plan.axis, plan.pad, -1.0)


def _extruded(seed):
    """A union of random axis-aligned rectangles extruded: a non-convex prism with
    steps, many opposite parallel walls, and walls that block each other's pads."""
    rng = np.random.default_rng(seed)
    boxes = []
    for _ in range(int(rng.integers(2, 5))):
        x, y = rng.uniform(0, 20, 2)
        w, h = rng.uniform(6, 25, 2)
        boxes.append(shapely.box(x, y, x + w, y + h))
    merged = shapely.union_all(boxes)
    poly = max(shapely.get_parts(merged), key=lambda g: g.area)
    poly = shapely.Polygon(poly.exterior).simplify(0)
    mesh = trimesh.creation.extrude_polygon(poly, float(rng.uniform(5, 20)))
    return solid_from_mesh(mesh, "mm", f"steps{seed}")


def _region_polygon(solid, plan):
    """The region on the first facet, in its frame: the outer ring and its holes."""
    a = solid.facets[plan.facets[0]]
    return shapely.Polygon(a.to_2d(plan.regions[0]), [a.to_2d(h) for h in plan.holes[0]])


def _axes_inside(rng, solid, plan, n):
    """The region's centre, its corners pulled in by a hair (around its holes too), and
    ``n`` random points."""
    a = solid.facets[plan.facets[0]]
    poly = _region_polygon(solid, plan)
    shrunk = poly.buffer(-1e-6 * solid.size)
    pts = [a.to_2d(plan.centers[0])]
    for piece in shapely.get_parts(shrunk):
        for ring in (piece.exterior, *piece.interiors):
            pts += list(np.asarray(shapely.get_coordinates(ring))[:-1])
    lo_x, lo_y, hi_x, hi_y = poly.bounds
    while len(pts) < n + 1:
        p = rng.uniform([lo_x, lo_y], [hi_x, hi_y])
        if poly.contains(shapely.Point(p)):
            pts.append(p)
    return [a.to_3d(p) for p in pts]


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 30))])
def test_every_axis_of_the_regions_holds(seed):
    rng = np.random.default_rng(seed)
    # the mug (the slowest) with the slow seeds
    solids = [demo_solid(n) for n in ("box", "angle")] if seed == 0 \
        else [demo_solid("mug"), _extruded(seed)] if seed == 1 else [_extruded(seed)]
    checked = 0
    for solid in solids:
        for plan in solid_jaw_plans(solid, STROKE, PAD, MU, top=4, margin=MARGIN):
            for x in _axes_inside(rng, solid, plan, 12 if seed == 0 else 30):
                assert _holds(solid, plan, x)
            # the region is not needlessly small: just outside it, an axis fails
            a = solid.facets[plan.facets[0]]
            poly = shapely.Polygon(a.to_2d(plan.regions[0]))
            assert plan.area == pytest.approx(_region_polygon(solid, plan).area, rel=1e-9)
            ring = shapely.get_coordinates(poly.buffer(1e-3 * solid.size).exterior)
            lo_x, lo_y, hi_x, hi_y = a.polygon.bounds
            outside = [p for p in ring[:: max(1, len(ring) // 8)]]
            if plan.area >= a.polygon.area * (1 - 1e-9):
                continue                           # the whole facet: nothing outside
            failed = sum(not _holds(solid, plan, a.to_3d(p)) for p in outside)
            assert failed >= 1
            checked += 1
    assert checked >= 1 or seed


def test_the_box_gives_its_faces():
    box = demo_solid("box")                                  # 40 x 20 x 10
    plans = solid_jaw_plans(box, (5, 50), 8, 0.5, top=None)
    got = sorted((round(p.opening, 9), round(p.radius, 6), round(p.area, 6)) for p in plans)
    assert got == [(10.0, 10.0, 800.0), (20.0, 5.0, 400.0), (40.0, 5.0, 200.0)]
    # the stroke keeps the openings in it; friction below the margin holds nothing
    assert [p.opening for p in solid_jaw_plans(box, (15, 30), 8, 0.5)] == [20.0]
    assert solid_jaw_plans(box, (5, 50), 8, 0.005) == []
    z = [f.index for f in box.facets if abs(f.normal[2]) > 0.5]
    assert solid_jaw_region(box, z, (11, 50), 8, 0.5) is None


def test_a_step_blocks_the_pad():
    """An L-shaped extrusion: on its inner horizontal face, the pad keeps its radius
    away from the vertical leg."""
    angle = demo_solid("angle")
    plans = solid_jaw_plans(angle, (2, 80), 8, 0.5, top=None)
    for p in plans:
        a = angle.facets[p.facets[0]]
        region = shapely.Polygon(a.to_2d(p.regions[0]))
        assert region.area <= a.polygon.area + 1e-9
    small = solid_jaw_plans(angle, (2, 80), 2, 0.5, top=None)
    big = {p.facets: p.area for p in plans}
    # a smaller pad never loses area, and gains it where a step blocks the larger one
    assert all(p.area >= big.get(p.facets, 0) - 1e-9 for p in small)
    assert any(p.area > big.get(p.facets, 0) + 1e-6 for p in small)


def test_errors_name_the_argument():
    box = demo_solid("box")
    with pytest.raises(ValueError, match="stroke"):
        solid_jaw_plans(box, (50, 5), 8, 0.5)
    with pytest.raises(ValueError, match="pad"):
        solid_jaw_plans(box, (5, 50), -1, 0.5)
    with pytest.raises(TypeError, match="solid must be"):
        solid_jaw_plans("box", (5, 50), 8, 0.5)
    with pytest.raises(ValueError, match="facets must be two different"):
        solid_jaw_region(box, (1, 1), (5, 50), 8, 0.5)


def test_cli_plans_the_jaw_on_a_mesh(tmp_path, capsys):
    from fcgrasp.apps.cli import main

    path = tmp_path / "block.stl"
    trimesh.creation.box((30, 20, 10)).export(path)
    out = tmp_path / "plan.json"
    assert main(["plan", str(path), "--gripper", "jaw", "--stroke", "5,25", "--pad", "6",
                 "--mu", "0.5", "--json", str(out)]) == 0
    doc = json.loads(out.read_text())
    assert doc["parameters"]["gripper"] == "jaw"
    assert sorted(g["opening"] for g in doc["grasps"]) == pytest.approx([10.0, 20.0])
    capsys.readouterr()
    assert main(["plan", str(path), "--gripper", "jaw", "--stroke", "5,25", "--pad", "6",
                 "--mass", "1"]) == 2
    err = capsys.readouterr().err
    assert "--mass" in err and len(err.strip().splitlines()) == 1


def _plate_with_holes(seed):
    """A seeded plate with one to three round through-holes (a CAD part's bolt holes):
    the jaw squeezing its faces has regions with holes."""
    rng = np.random.default_rng(seed)
    w, d = rng.uniform(30, 60, 2)
    holes, tries = [], 0
    while len(holes) < int(rng.integers(1, 4)) and tries < 50:
        tries += 1
        r = float(rng.uniform(2, 6))
        c = shapely.Point(rng.uniform(r + 3, w - r - 3), rng.uniform(r + 3, d - r - 3))
        disc = c.buffer(r, 16)
        if all(disc.distance(h) > 2 for h in holes):
            holes.append(disc)
    poly = shapely.Polygon([(0, 0), (w, 0), (w, d), (0, d)],
                           [list(h.exterior.coords)[::-1] for h in holes])
    mesh = trimesh.creation.extrude_polygon(poly, float(rng.uniform(4, 15)))
    return solid_from_mesh(mesh, "mm", f"plate{seed}"), len(holes)


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in (1, 2, 3))])
def test_regions_keep_their_holes(seed):
    """The regions on a plate with through-holes: the holes are in the plan (its rings,
    its triangles, its area); every sampled axis (inside, at the corners, around each
    hole) meets both faces and holds, and the axes through a hole's middle meet no part
    at all and are not in the region (rays cast here)."""
    rng = np.random.default_rng(seed)
    solid, n_holes = _plate_with_holes(seed)
    plans = solid_jaw_plans(solid, STROKE, PAD, MU, top=3, margin=MARGIN)
    faces = [p for p in plans if len(p.holes[0])]
    assert faces, "the faces with the holes give a plan"
    for plan in faces:
        assert len(plan.holes[0]) == len(plan.holes[1]) <= n_holes
        region = _region_polygon(solid, plan)
        assert plan.area == pytest.approx(region.area, rel=1e-9)
        a = solid.facets[plan.facets[0]]
        tris = plan.surface_triangles[0]
        assert float(sum(0.5 * np.linalg.norm(np.cross(t[1] - t[0], t[2] - t[0]))
                         for t in tris)) == pytest.approx(region.area, rel=1e-9)
        for x in _axes_inside(rng, solid, plan, 20):
            assert _holds(solid, plan, x)
        for hole in plan.holes[0]:
            middle = hole.mean(axis=0)
            assert not region.contains(shapely.Point(a.to_2d(middle)))
            far = 2 * solid.size
            assert _first_hit(solid.mesh, middle - far * plan.axis, plan.axis) == math.inf


def test_a_pair_geos_cannot_build_gives_no_region(monkeypatch):
    """Real CAD meshes have facets whose overlap GEOS cannot compute ("Scale factor must
    be non-zero", "unable to assign free hole to a shell"): that pair gives no region,
    the others are planned, and nothing escapes as an error."""
    from fcgrasp.spatial import jaw

    solid = demo_solid("box")
    want = solid_jaw_plans(solid, STROKE, PAD, MU, top=4, margin=MARGIN)
    broken = want[0].facets
    real = jaw._region

    def fails_on_one(solid_, i, j, *args):
        if (i, j) == broken:
            raise shapely.errors.GEOSException("TopologyException: Scale factor must be "
                                               "non-zero")
        return real(solid_, i, j, *args)

    monkeypatch.setattr(jaw, "_region", fails_on_one)
    got = solid_jaw_plans(solid, STROKE, PAD, MU, top=4, margin=MARGIN)
    assert [p.facets for p in got] == [p.facets for p in want if p.facets != broken]


def _torus(major, minor):
    """A torus (radii 40 and 12 mm) of ``major`` by ``minor`` sections: no two facets
    coplanar, its inner faces with most of the part beyond their planes."""
    mesh = trimesh.creation.torus(40, 12, major_sections=major, minor_sections=minor)
    return solid_from_mesh(mesh, "mm", f"torus{major}x{minor}")


@pytest.mark.parametrize("sections", [(64, 16), pytest.param((48, 24), marks=pytest.mark.slow),
                                      pytest.param((96, 32), marks=pytest.mark.slow)])
def test_every_axis_on_a_torus_holds(sections):
    """The regions on a curved solid, whose pads meet the part beyond their facets
    everywhere but on the rim: every sampled axis of every region returned (pads of 2,
    6 and 10 mm) holds, its pads reaching their facets first (rays cast here): the
    union of a facet's shadows keeps every triangle (GEOS's floating overlay loses some
    that share sides), and the buffer by the pad's radius holds the pad's disc (its
    chords outside it)."""
    rng = np.random.default_rng(sum(sections))
    solid = _torus(*sections)
    seen = 0
    for pad in (2.0, 6.0, 10.0):
        for plan in solid_jaw_plans(solid, (2, 150), pad, MU, top=3, margin=MARGIN):
            for x in _axes_inside(rng, solid, plan, 6):
                assert _holds(solid, plan, x)
            seen += 1
    assert seen


def _screened(monkeypatch, solid, stroke, pad):
    """``solid_jaw_plans`` of every pair with and without the one-shadow screen, and how
    many pairs the screen decided."""
    from fcgrasp.spatial import jaw

    decided = []
    screen = jaw._one_shadow_covers

    def counted(*args):
        out = screen(*args)
        decided.append(out)
        return out

    monkeypatch.setattr(jaw, "_one_shadow_covers", counted)
    got = solid_jaw_plans(solid, stroke, pad, MU, top=None, margin=MARGIN)
    monkeypatch.setattr(jaw, "SHADOW_SCREEN", False)
    want = solid_jaw_plans(solid, stroke, pad, MU, top=None, margin=MARGIN)
    monkeypatch.setattr(jaw, "SHADOW_SCREEN", True)
    return got, want, sum(decided)


@pytest.mark.parametrize("seed", [0, 1, *(pytest.param(s, marks=pytest.mark.slow)
                                          for s in range(2, 14))])
def test_the_shadow_screen_gives_the_cut_plans(seed, monkeypatch):
    """A pair whose overlap lies within the pad's radius of one shadow is given no region
    without the union of the shadows: every plan is the one the cut gives (the same
    pairs, regions and radii, bit for bit), on tori and stepped prisms with pads of 1
    to 12 mm; the screen decides some pairs of a torus and leaves others to the cut."""
    rng = np.random.default_rng(700 + seed)
    torus = seed % 2 == 0
    solid = _torus(int(rng.choice([48, 64])), 24) if torus else _extruded(seed)
    pad = float(rng.uniform(4 if torus else 1, 12))
    got, want, decided = _screened(monkeypatch, solid, (1.0, 150.0), pad)
    assert [(p.facets, p.radius, p.area) for p in got] == \
        [(p.facets, p.radius, p.area) for p in want]
    for g, w in zip(got, want, strict=True):
        assert np.array_equal(g.regions[0], w.regions[0])
    if torus:
        assert decided > 0                       # the inner faces of a torus
