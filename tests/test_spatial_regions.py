"""Regions of two soft fingers on solids: every grasp of the regions (every
pair of corners and sampled points) passes the 6-D force-closure test, the regions on a
box, a cylinder and a prism equal their analytic optimum, the bounded search equals
solving every pair, and meshes are read and checked."""

from __future__ import annotations

import math

import numpy as np
import pytest

from fcgrasp.io.meshes import read_solid
from fcgrasp.spatial import closure_margin, soft_pair_plans, two_soft_closure
from fcgrasp.spatial._pieces import separated as P_separated
from fcgrasp.spatial.regions import facet_pair_plans, soft_pair_regions
from fcgrasp.spatial.solid import demo_solid, solid_from_mesh

trimesh = pytest.importorskip("trimesh")


def _octagon(phi):
    """The unit octagon's corners, the first at angle ``phi``."""
    return np.c_[np.cos(phi + np.arange(8) * math.pi / 4),
                 np.sin(phi + np.arange(8) * math.pi / 4)]


def _lp_fit(linprog, E, h, k):
    """The octagon's fit as the LP over its centre and scale (``E t + s k <= h``)."""
    return linprog([0, 0, -1], A_ub=np.c_[E, k], b_ub=h,
                   bounds=[(None, None), (None, None), (0, None)], method="highs")


def _random_convex(seed):
    rng = np.random.default_rng(seed)
    pts = rng.normal(size=(int(rng.integers(6, 14)), 3)) * rng.uniform(5, 20, 3)
    return solid_from_mesh(trimesh.convex.convex_hull(pts), "mm", f"hull{seed}")


def _grasps(rng, plan, n):
    """Every pair of corners, then ``n`` pairs of points inside the octagons."""
    A, B = plan.regions
    pairs = [(a, b) for a in A for b in B]
    for _ in range(n):
        wa, wb = rng.dirichlet(np.ones(8)), rng.dirichlet(np.ones(8))
        pairs.append((wa @ A, wb @ B))
    return np.array(pairs)


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 40))])
def test_every_grasp_of_the_regions_is_force_closure(seed):
    rng = np.random.default_rng(seed)
    solids = [demo_solid(n) for n in ("box", "cylinder", "prism", "angle", "mug")] \
        if seed == 0 else [_random_convex(seed)]
    checked = 0
    for solid in solids:
        mu = float(rng.choice([0.3, 0.6]))
        for plan in facet_pair_plans(solid, mu, top=4):
            P = _grasps(rng, plan, 40)
            N = np.broadcast_to(plan.normals, P.shape)
            # the closed form at the cone's own edge (no margin) ...
            assert two_soft_closure(P, N, mu).all()
            # ... and the cone program on a few of them, torsional friction included
            for k in rng.choice(len(P), 6, replace=False):
                assert closure_margin(P[k], plan.normals, mu, 0.5).closure
            # the corners lie on their facets, inside the solid's surface
            for f, reg in zip(plan.facets, plan.regions, strict=True):
                facet = solid.facets[f]
                assert np.allclose((reg - facet.origin) @ facet.normal, 0, atol=1e-9 * solid.size)
                poly = facet.polygon.buffer(1e-7 * solid.size)
                from shapely import points
                assert poly.contains(points(facet.to_2d(reg))).all()
            checked += 1
        if not facet_pair_plans(solid, mu, top=1):   # no pair of facets holds
            n = len(solid.facets)
            assert all(soft_pair_regions(solid, (i, j), mu) is None
                       for i in range(n) for j in range(n) if i != j)
    assert checked >= 1 or seed


def test_regions_equal_the_analytic_optimum():
    """Opposite parallel faces a distance h apart: octagons of circumradius
    min(h tan(alpha) / 2, the face's half width), alpha = atan(mu) - margin."""
    mu, margin = 0.3, 0.5
    t = math.tan(math.atan(mu) - math.radians(margin))
    box = demo_solid("box")                                  # 40 x 20 x 10
    got = {tuple(sorted(int(np.argmax(np.abs(box.facets[f].normal))) for f in p.facets)):
           p.radius for p in facet_pair_plans(box, mu, top=None, leximin=False)}
    want = {(0, 0): min(40 * t / 2, 10 / 2), (1, 1): min(20 * t / 2, 10 / 2),
            (2, 2): min(10 * t / 2, 20 / 2)}
    assert got == pytest.approx(want, rel=1e-7)
    cyl = facet_pair_plans(demo_solid("cylinder"), mu, top=1)[0]      # the two caps
    assert cyl.radius == pytest.approx(30 * t / 2, rel=1e-6)
    assert abs(cyl.normals[0] @ cyl.normals[1] + 1) < 1e-9
    prism = facet_pair_plans(demo_solid("prism"), mu, top=1)[0]       # the ends, 25 apart
    assert prism.radius == pytest.approx(25 * t / 2, rel=1e-6)


def test_the_second_level_grows_the_other_octagon_as_far_as_it_holds():
    """Leximin (definition 7.1's second level) on a frustum whose small top (a 64-gon of
    radius 2) limits the first level: the octagons of radius ``r`` (the top's fit, 2 to
    0.12 % since the 64-gon's inradius is 2 cos(pi / 64)), then the bottom one grown to
    ``h tan(alpha) - r``: the widest corner chord, ``r`` plus the grown radius across,
    must stay inside the cone over the height ``h``.  Its regions hold at every pair of
    corners; one a little larger does not (the cone program's optimum is reached)."""
    mu, margin, h = 0.5, 0.5, 20.0
    t = math.tan(math.atan(mu) - math.radians(margin))
    a = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    ring = np.c_[np.cos(a), np.sin(a)]
    pts = np.r_[np.c_[2 * ring, np.full(64, h)], np.c_[15 * ring, np.zeros(64)]]
    solid = solid_from_mesh(trimesh.convex.convex_hull(pts), "mm", "frustum")
    plan = next(p for p in facet_pair_plans(solid, mu, top=5)
                if abs(p.normals[0][2]) > 0.999 and abs(p.normals[1][2]) > 0.999)
    r = plan.radius
    assert 2 * math.cos(math.pi / 64) * (1 - 1e-6) <= r <= 2 * (1 + 1e-6)
    small, large = sorted(plan.radii)
    assert small == r and large == pytest.approx(h * t - r, rel=1e-4)
    assert plan.to_dict()["radii"] == list(plan.radii)
    first = soft_pair_regions(solid, plan.facets, mu, margin, plan.pieces, leximin=False)
    assert first.radius == pytest.approx(r, rel=1e-9) and first.radii == (first.radius,) * 2
    P = _grasps(np.random.default_rng(3), plan, 20)
    assert two_soft_closure(P, np.broadcast_to(plan.normals, P.shape), mu).all()
    # the grown octagon 0.1 % larger about its centre: some corner pair leaves the cone
    # narrowed by the margin
    k = int(np.argmax(plan.radii))
    bigger = plan.regions.copy()
    bigger[k] = plan.centers[k] + 1.001 * (plan.regions[k] - plan.centers[k])
    d = bigger[1][None, :, :] - bigger[0][:, None, :]
    cos_a = math.cos(math.atan(mu) - math.radians(margin))
    inside = (d @ plan.normals[0]) > cos_a * np.linalg.norm(d, axis=-1)
    assert not inside.all()


def _every_pair(solid, mu, margin=0.5):
    """The reference: the cone program on every pair of pieces of every pair of facets
    (the search before its bounds and fits), sorted."""
    plans = []
    for i, fi in enumerate(solid.facets):
        for j in range(i + 1, len(solid.facets)):
            for a in range(len(fi.pieces)):
                for b in range(len(solid.facets[j].pieces)):
                    got = soft_pair_regions(solid, (i, j), mu, margin, (a, b),
                                            leximin=False)
                    if got is not None:
                        plans.append(got)
    return sorted(plans, key=lambda p: -p.radius)


def _search_corpus(seed):
    """Solids with many small facets and near-ties: random hulls, icospheres (every
    facet a triangle of nearly one size), a tessellated cylinder (rectangles and caps),
    an L-shaped extrusion (non-convex facets cut into pieces)."""
    rng = np.random.default_rng(seed)
    kind = seed % 4
    if kind == 0:
        return _random_convex(seed)
    if kind == 1:
        mesh = trimesh.creation.icosphere(subdivisions=int(seed >= 4),
                                          radius=float(rng.uniform(5, 30)))
        mesh.vertices *= rng.uniform(0.7, 1.3, 3)                 # an ellipsoid
        return solid_from_mesh(mesh, "mm", f"ico{seed}")
    if kind == 2:
        return solid_from_mesh(trimesh.creation.cylinder(
            radius=float(rng.uniform(3, 20)), height=float(rng.uniform(5, 40)),
            sections=int(rng.integers(6, 14))), "mm", f"cyl{seed}")
    return demo_solid("angle")


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 40))])
def test_bounded_search_equals_every_pair(seed):
    """The best-first search (batched bounds, fits in closed form, cone program only
    where the fits fail) gives the cone program's radii on every pair, in order."""
    solid = _search_corpus(seed)
    rng = np.random.default_rng(seed)
    for mu in (float(rng.choice([0.2, 0.4])), float(rng.choice([0.8, 1.5]))):
        every = _every_pair(solid, mu)
        for top in (1, 5):
            some = facet_pair_plans(solid, mu, top=top)
            assert [p.radius for p in some] == pytest.approx(
                [p.radius for p in every[:top]], rel=1e-6, abs=1e-9 * solid.size)
        everything = facet_pair_plans(solid, mu, top=None, leximin=False)   # first levels
        assert len(everything) == len(every)
        assert [p.radius for p in everything] == pytest.approx(
            [p.radius for p in every], rel=1e-6, abs=1e-9 * solid.size)


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 10))])
def test_bounds_and_fits_against_the_cone_program(seed):
    """For sampled pairs of pieces: the batched bound is at least the refined one, which
    is at least the cone program's radius; where the fits hold they equal it."""
    from fcgrasp.spatial import _pieces as P
    from fcgrasp.spatial import regions as R

    solid = _search_corpus(seed)
    rng = np.random.default_rng(100 + seed)
    mu = float(rng.uniform(0.2, 1.5))
    alpha = math.atan(mu) - math.radians(0.5)
    table = P._piece_table(solid)
    pa, pb = P._pairs(table, np.arange(len(table.facet)), np.zeros(0, np.intp),
                      math.cos(min(2 * alpha, math.pi)))
    pick = rng.choice(len(pa), min(len(pa), 60), replace=False)
    bounds = P._pair_bounds(table, pa[pick], pb[pick], alpha)
    for bound, i, j in zip(bounds, pa[pick], pb[pick], strict=True):
        facets = (int(table.facet[i]), int(table.facet[j]))
        pieces = (int(table.local[i]), int(table.local[j]))
        want = soft_pair_regions(solid, facets, mu, 0.5, pieces)
        r = 0.0 if want is None else want.radius
        refined = R._refine(solid, table, int(i), int(j), alpha)
        assert bound >= refined.bound * (1 - 1e-12)
        assert refined.bound >= r * (1 - 1e-6)
        got = R._solve(solid, table, int(i), int(j), alpha, refined)
        assert (0.0 if got is None else got[2]) == pytest.approx(r, rel=1e-6,
                                                                  abs=1e-9 * solid.size)


@pytest.mark.parametrize("cases", [300, pytest.param(3000, marks=pytest.mark.slow)])
def test_octagon_fits_equal_an_lp(cases):
    """The closed-form fit of a turned octagon in a triangle against scipy's LP over the
    centre and scale, on seeded triangles (thin ones too), and the batched fits of a
    mesh's triangles against the one-at-a-time closed form."""
    from shapely import Polygon

    from fcgrasp.spatial import _pieces as P
    from fcgrasp.spatial import regions as R

    from ._highs import linprog

    rng = np.random.default_rng(cases)
    for _ in range(cases):
        tri = rng.normal(size=(3, 2)) * rng.uniform(0.1, 10)
        if rng.random() < 0.2:                                   # a sliver
            tri[2] = tri[0] + rng.uniform(0.01, 0.99) * (tri[1] - tri[0]) \
                + rng.normal(size=2) * 1e-3
        poly = Polygon(tri)
        if poly.area < 1e-9:
            continue
        E, h = P._halfplanes(poly)
        phi = rng.uniform(0, 2 * math.pi)
        corners = _octagon(phi)
        s, t = P._fit((E, h), corners)
        k = (E @ corners.T).max(axis=1)
        lp = _lp_fit(linprog, E, h, k)
        assert s == pytest.approx(lp.x[2], rel=1e-7, abs=1e-8 * np.abs(tri).max())
        assert np.all(E @ t + s * k <= h + 1e-9 * np.abs(h).max())
    solid = solid_from_mesh(trimesh.creation.icosphere(subdivisions=2, radius=7.0))
    table = P._piece_table(solid)
    for f, fit in zip(solid.facets, table.own_fit, strict=True):
        Q1, _ = R._octagon_axes(f, f)
        assert fit == pytest.approx(P._fit(P._halfplanes(f.pieces[0]), Q1 @ f.axes.T)[0],
                                    rel=1e-12)


def test_meshes_are_read_and_checked(tmp_path):
    path = tmp_path / "box.stl"
    trimesh.creation.box((30.0, 10.0, 10.0)).export(path)
    solid = read_solid(str(path))
    assert len(solid.facets) == 6 and solid.units == "mm"
    assert facet_pair_plans(solid, 0.5, top=1)[0].radius == pytest.approx(5.0, rel=1e-6)
    open_mesh = trimesh.creation.box((1, 1, 1))
    open_mesh.update_faces(np.arange(10))
    with pytest.raises(ValueError, match="watertight"):
        solid_from_mesh(open_mesh)
    with pytest.raises(TypeError, match="mesh"):
        solid_from_mesh("box")
    with pytest.raises(ValueError, match="name"):
        demo_solid("teapot")
    with pytest.raises(ValueError, match="not a readable mesh"):
        read_solid(str(tmp_path / "missing.stl"))
    with pytest.raises(ValueError, match="facets"):
        soft_pair_regions(solid, (0, 0), 0.5)
    with pytest.raises(ValueError, match="mu"):
        soft_pair_plans(solid, -1.0)


def test_cli_plans_soft_fingers_on_a_mesh(tmp_path, capsys):
    """``fcgrasp plan part.stl --fingers 2 --soft``: the JSON's regions are the library's,
    the figure is written; the same without --soft, and --soft on a polygon changes
    nothing."""
    import json

    from fcgrasp.apps.cli import main

    path = tmp_path / "box.stl"
    trimesh.creation.box((30.0, 10.0, 10.0)).export(path)
    out, fig = tmp_path / "plan.json", tmp_path / "plan.png"
    assert main(["plan", str(path), "--fingers", "2", "--soft", "--mu", "0.5", "--top", "2",
                 "--json", str(out), "--plot", str(fig)]) == 0
    doc = json.loads(out.read_text())
    want = soft_pair_plans(read_solid(str(path)), 0.5, top=2)
    assert [g["radius"] for g in doc["grasps"]] == pytest.approx([p.radius for p in want])
    assert np.allclose(doc["grasps"][0]["regions"], want[0].regions)
    assert fig.stat().st_size > 0
    capsys.readouterr()
    # two fingers on a solid are soft fingers without --soft; on a planar part --soft
    # changes nothing
    plain = tmp_path / "plain.json"
    assert main(["plan", str(path), "--mu", "0.5", "--top", "2", "--json", str(plain)]) == 0
    assert json.loads(plain.read_text())["grasps"] == doc["grasps"]
    assert main(["plan", "demo:blob", "--soft", "--json", str(plain)]) == 0
    soft = json.loads(plain.read_text())["grasps"]
    assert main(["plan", "demo:blob", "--json", str(plain)]) == 0
    assert soft == json.loads(plain.read_text())["grasps"]


def test_bodies_units_and_the_parts_command(tmp_path, capsys):
    """A file of two bodies: listed largest first by ``fcgrasp parts`` (table and JSON),
    the largest planned by default and the other by ``--part 1``; a GLB in metres is
    converted to millimetres and inches, --file-units overrides an STL's silence, and a
    body that does not exist is a one-line error."""
    import json

    from fcgrasp.apps.cli import main
    from fcgrasp.io.meshes import read_bodies

    big, small = trimesh.creation.box((10, 10, 10)), trimesh.creation.box((2, 4, 6))
    small.apply_translation((20, 0, 0))
    mesh = trimesh.util.concatenate([small, big])
    stl = tmp_path / "two.stl"
    mesh.export(stl)
    bodies, units, note = read_bodies(str(stl))
    assert [b.volume for b in bodies] == pytest.approx([1000.0, 48.0])
    assert units == "mm" and "no units" in note
    assert main(["parts", str(stl), "--json", str(tmp_path / "parts.json")]) == 0
    doc = json.loads((tmp_path / "parts.json").read_text())
    assert doc["default"] == 0 and [b["triangles"] for b in doc["bodies"]] == [12, 12]
    assert main(["parts", str(stl)]) == 0
    out = capsys.readouterr().out
    assert "2 bodies" in out and "10 x 10 x 10" in out
    assert read_solid(str(stl)).mesh.volume == pytest.approx(1000.0)
    assert read_solid(str(stl), select=1).mesh.volume == pytest.approx(48.0)
    # the small body: its best pair is the two 2 x 4 faces 6 apart, or the 4 x 6 faces 2
    # apart...: whatever it is, the CLI gives the library's answer for that body
    out_json = tmp_path / "plan.json"
    assert main(["plan", str(stl), "--fingers", "2", "--soft", "--part", "1", "--top", "1",
                 "--json", str(out_json)]) == 0
    want = soft_pair_plans(read_solid(str(stl), select=1), 0.3, top=1)[0]
    assert json.loads(out_json.read_text())["grasps"][0]["radius"] == pytest.approx(
        want.radius)
    # units: a GLB in metres
    mesh.units = "m"
    glb = tmp_path / "two.glb"
    mesh.export(glb)
    assert read_solid(str(glb)).mesh.volume == pytest.approx(1000.0 * 1e9)
    inches = read_solid(str(glb), units="in")
    assert inches.units == "in" and inches.mesh.volume == pytest.approx(1e12 / 25.4 ** 3)
    assert read_solid(str(stl), file_units="cm").mesh.volume == pytest.approx(1e6)
    assert read_solid("demo:box", units="cm").mesh.volume == pytest.approx(8.0)
    capsys.readouterr()
    assert main(["plan", str(stl), "--fingers", "2", "--soft", "--part", "7"]) != 0
    err = capsys.readouterr().err
    assert "body 7" in err and len(err.strip().splitlines()) == 1
    with pytest.raises(ValueError, match="units"):
        read_bodies(str(stl), units="furlong")


def test_the_mug_is_a_cup_with_a_handle():
    """``demo:mug``: one watertight body; its flat faces are the 48-gons of the design
    (the bottom of radius 40, the inside bottom of radius 36 at 6 mm, the rim between
    them at 90 mm); the handle stands out on +x to 72 mm."""
    mug = demo_solid("mug")
    assert mug.mesh.is_watertight and mug.mesh.is_winding_consistent
    assert len(mug.mesh.split(only_watertight=False)) == 1

    def gon(r):
        return 0.5 * 48 * r * r * np.sin(2 * np.pi / 48)

    flat = sorted((round(float(f.origin[2]), 9), f.area) for f in mug.facets
                  if abs(abs(f.normal[2]) - 1) < 1e-9)
    assert [z for z, _ in flat] == [0.0, 6.0, 90.0]
    assert [a for _, a in flat] == pytest.approx([gon(40), gon(36), gon(40) - gon(36)],
                                                 rel=1e-9)
    lo, hi = mug.mesh.bounds
    assert np.allclose(lo, [-40, -40, 0]) and np.allclose(hi, [72, 40, 90])


@pytest.mark.parametrize("cases", [300, pytest.param(5000, marks=pytest.mark.slow)])
def test_the_vertex_fit_equals_highs(cases):
    """The octagon's fit in a convex piece of four to ten edges by the vertices of its
    three-variable program equals HiGHS' optimum, on seeded convex polygons (hulls of
    random points, thin ones, near-parallel edges) and turned octagons; its centre is
    feasible."""
    from shapely import MultiPoint

    from fcgrasp.spatial import _pieces as P

    from ._highs import linprog

    rng = np.random.default_rng(cases)
    done = 0
    for _ in range(cases):
        pts = rng.normal(size=(int(rng.integers(4, 14)), 2)) * rng.uniform(0.01, 100, 2)
        poly = MultiPoint(pts).convex_hull
        if poly.geom_type != "Polygon" or poly.area < 1e-9:
            continue
        E, h = P._halfplanes(poly)
        if not 4 <= len(E) <= P._VERTEX_FIT_EDGES:
            continue
        phi = rng.uniform(0, 2 * math.pi)
        corners = _octagon(phi)
        k = (E @ corners.T).max(axis=1)
        s, t = P._vertex_fit(E, h, k)
        lp = _lp_fit(linprog, E, h, k)
        assert s == pytest.approx(lp.x[2], rel=1e-7, abs=1e-9 * np.abs(pts).max())
        assert np.all(E @ t + s * k <= h + 1e-9 * np.abs(h).max())
        done += 1
    assert done > cases // 3


def _convex_pieces_every_piece(poly):
    """The greedy merge trying every piece for every triangle: the reference of
    :func:`fcgrasp.spatial.solid._convex_pieces`, which tries only the pieces whose
    bounding box meets the triangle's."""
    import shapely

    from fcgrasp.core.tolerances import TOL

    if poly.area >= poly.convex_hull.area * (1 - TOL):
        return [poly]
    tris = sorted(shapely.constrained_delaunay_triangles(poly).geoms, key=lambda t: -t.area)
    pieces = []
    for t in tris:
        for i, p in enumerate(pieces):
            u = p.union(t)
            if u.geom_type == "Polygon" and u.area >= u.convex_hull.area * (1 - TOL):
                pieces[i] = u
                break
        else:
            pieces.append(t)
    return sorted(pieces, key=lambda p: -p.area)


@pytest.mark.parametrize("seed", range(6))
def test_convex_pieces_equal_the_merge_over_every_piece(seed):
    """Facets with holes and notches (seeded): the same convex pieces, in the same order,
    as the merge that tries every piece."""
    import shapely

    from fcgrasp.spatial.solid import _convex_pieces

    rng = np.random.default_rng(seed)
    w, h = rng.uniform(20, 60, 2)
    holes = []
    for _ in range(int(rng.integers(1, 12))):
        r = float(rng.uniform(0.5, 3))
        c = shapely.Point(rng.uniform(r + 1, w - r - 1), rng.uniform(r + 1, h - r - 1))
        disc = c.buffer(r, int(rng.integers(3, 12)))
        if all(disc.distance(o) > 0.5 for o in holes):
            holes.append(disc)
    outer = shapely.Polygon([(0, 0), (w, 0), (w, h), (w / 2, h * 0.6), (0, h)])
    poly = shapely.Polygon(outer.exterior.coords,
                           [list(o.exterior.coords)[::-1] for o in holes
                            if outer.contains(o)])
    mine, ref = _convex_pieces(poly), _convex_pieces_every_piece(poly)
    assert len(mine) == len(ref)
    assert all(a.equals_exact(b, 0.0) for a, b in zip(mine, ref, strict=True))


@pytest.mark.parametrize("seed", [2, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in (0, 1, *range(3, 16)))])
def test_searches_sharing_a_memo_give_the_plans_of_searches_alone(seed):
    """The searches of one solid asked for more and more plans (as the distinct
    alternatives ask them) sharing a memo of each pair's refined bound and solution,
    and of each plan's second level, give, round after round, the plans of searches
    that share nothing (their regions too), and the later rounds read what the earlier
    computed."""
    solid = _search_corpus(seed)
    rng = np.random.default_rng(seed)
    mu = float(rng.uniform(0.3, 0.9))
    memo: dict = {}
    for top in (3, 12, 48):
        shared = soft_pair_plans(solid, mu, top=top, memo=memo)
        alone = soft_pair_plans(solid, mu, top=top)
        assert [(p.facets, p.pieces) for p in shared] == [(p.facets, p.pieces) for p in alone]
        for p, q in zip(shared, alone, strict=True):
            assert p.radius == q.radius
            for a, b in zip(p.centers, q.centers, strict=True):
                np.testing.assert_array_equal(a, b)
            np.testing.assert_array_equal(p.regions, q.regions)
            assert p.radii == q.radii
    keys = {k[0] for k in memo if isinstance(k, tuple)}
    assert "table" in memo and {"solve", "grown"} <= keys


def test_cone_rows_of_every_pair_at_once_are_those_of_one_pair_at_a_time():
    """The soft pair's cone program: the rows, right-hand sides and cones of every pair
    of corners built at once (``_cone_rows``) are those built one pair at a time (the
    reference, ``tests/previous_cone_rows.py``), number for number to rounding, on facets of seeded
    convex solids, one half-angle or one per facet, with shifts as the patches use."""
    from fcgrasp.spatial.regions import _cone_rows

    from .previous_cone_rows import cone_rows_loop

    rng = np.random.default_rng(11)
    checked = 0
    for seed in range(6):
        solid = _random_convex(seed)
        facets = solid.facets
        for _ in range(5):
            f1, f2 = (facets[int(i)] for i in rng.choice(len(facets), 2, replace=False))
            pairs = [(rng.normal(size=3) * rng.choice([1e-3, 1.0, 1e3]), rng.normal(size=3))
                     for _ in range(int(rng.integers(0, 70)))]
            alpha = float(rng.uniform(0.05, 1.2)) if rng.random() < 0.5 else \
                (float(rng.uniform(0.05, 1.2)), float(rng.uniform(0.05, 1.2)))
            got, want = ([], [], []), ([], [], [])
            _cone_rows(f1, f2, alpha, pairs, *got)
            cone_rows_loop(f1, f2, alpha, pairs, *want)
            assert len(got[0]) == len(want[0]) == 8 * len(pairs)
            # the same numbers to rounding (numpy's vectorised sums and the loop's may
            # round the last bit apart)
            for a, b in zip(got[0], want[0], strict=True):
                np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-12 * np.abs(b).max())
            np.testing.assert_allclose(got[1], want[1], rtol=1e-12,
                                       atol=1e-12 * max(1.0, np.abs(want[1]).max(initial=0)))
            assert [c.__class__ for c in got[2]] == [c.__class__ for c in want[2]]
            assert len(got[2]) == len(want[2])
            checked += len(pairs)
    assert checked > 500


def test_a_soft_pair_search_the_clock_ends_keeps_regions_that_hold(monkeypatch):
    """The clock ending inside the soft pair's searches (on pairs of facets and across
    the facets of curved surfaces, the checks between their steps): the plans kept hold
    (every corner pair and sampled grasps by the closed form), each of them among the
    complete search's candidates, and the answer says it was cut short (not exact)."""
    import fcgrasp as fc
    from fcgrasp.spatial import regions, surfaces

    from .clock import clock_ending_after

    rng = np.random.default_rng(8)
    solid = demo_solid("mug")
    full = fc.plan(solid, fingers=2, mu=0.5, top=6, time_limit=None)
    assert full.complete
    seen = 0
    for ends_after in (0, 2, 8, 30, 120):
        clock = clock_ending_after(ends_after)
        monkeypatch.setattr(regions, "cut_if_over", clock)
        monkeypatch.setattr(surfaces, "cut_if_over", clock)
        plans = fc.plan(solid, fingers=2, mu=0.5, top=6, time_limit=None)
        assert not plans.complete and not plans.exact
        for plan in plans:
            P = _grasps(rng, plan, 20)
            N = np.broadcast_to(plan.normals, P.shape)
            assert two_soft_closure(P, N, 0.5).all()
            seen += 1
    assert seen >= 6


def _slack_program(v1, v2, a1, a2, alpha):
    """The largest ``t`` with some point ``x_1`` of hull(``v1``) and ``x_2`` of
    hull(``v2``) such that ``|x| <= a . x / cos(alpha) - t`` for both axes, ``x = x_2 -
    x_1``: Clarabel over the points' convex weights (no code of the separation test)."""
    import clarabel
    from scipy import sparse

    k1, k2 = len(v1), len(v2)
    n = k1 + k2 + 1                                  # (lambda, mu, t)
    X = np.c_[-v1.T, v2.T, np.zeros(3)]              # x = X z
    rows, rhs = [], []
    # the weights sum to one (zero cone), then are nonnegative
    rows += [np.r_[np.ones(k1), np.zeros(k2 + 1)], np.r_[np.zeros(k1), np.ones(k2), 0]]
    rhs += [1.0, 1.0]
    rows += list(-np.eye(n)[:-1])
    rhs += [0.0] * (n - 1)
    for a in (a1, a2):
        # (a . x / cos(alpha) - t, x) in the second-order cone
        rows.append(-(np.r_[a @ X[:, :-1] / math.cos(alpha), -1.0]))
        rows += list(-X)
        rhs += [0.0] * 4
    cones = [clarabel.ZeroConeT(2), clarabel.NonnegativeConeT(n - 1),
             clarabel.SecondOrderConeT(4), clarabel.SecondOrderConeT(4)]
    q = np.zeros(n)
    q[-1] = -1.0
    settings = clarabel.DefaultSettings()
    settings.verbose = False
    sol = clarabel.DefaultSolver(sparse.csc_matrix((n, n)), q,
                                 sparse.csc_matrix(np.array(rows, float)),
                                 np.array(rhs, float), cones, settings).solve()
    # (a case within a millionth of the cones' edge may end a rounding short)
    assert str(sol.status) in ("Solved", "AlmostSolved"), sol.status
    return -sol.obj_val


@pytest.mark.parametrize("cases", [400, pytest.param(5000, marks=pytest.mark.slow)])
def test_separated_pieces_hold_no_point_pair(cases):
    """A pair of pieces the sampled dual directions separate from the friction cones
    (:func:`fcgrasp.spatial._pieces.separates`) has no two points whose difference lies
    in both cones, by a cone program over the pieces' points (its largest slack below
    zero), on seeded pieces placed about the cones' edge, some within a millionth of
    it; and the test proves most pairs that miss the cones by a margin (a test that
    never separates fails)."""
    from fcgrasp.spatial import _pieces as P

    rng = np.random.default_rng(cases)
    wide = caught = 0
    for _ in range(cases):
        alpha = float(rng.uniform(0.05, 1.2))
        a1 = rng.normal(size=3)
        a1 /= np.linalg.norm(a1)
        # the second facet's inward normal within 2.4 alpha of opposite the first's
        tilt = rng.normal(size=3)
        tilt -= (tilt @ a1) * a1
        tilt /= np.linalg.norm(tilt)
        turn = float(rng.uniform(0, 1.2)) * 2 * alpha
        a2 = math.cos(turn) * a1 + math.sin(turn) * tilt
        u = np.cross(a1, tilt)

        def piece(normal, centre, size):
            e1 = np.cross(normal, [1.0, 0, 0] if abs(normal[0]) < 0.9 else [0, 1.0, 0])
            e1 /= np.linalg.norm(e1)
            e2 = np.cross(normal, e1)
            pts = rng.normal(size=(int(rng.integers(3, 7)), 2)) * size
            return centre + pts[:, :1] * e1 + pts[:, 1:] * e2

        height = float(rng.uniform(1, 50))
        # the second piece across the first, its centre near a cone's edge (a relative
        # offset about 1 there), or both pieces specks within a millionth of it
        speck = rng.random() < 0.3
        edge = 1 + (rng.uniform(-1e-6, 1e-6) if speck else rng.uniform(-0.8, 1.5))
        side = tilt if rng.random() < 0.5 else u
        centre = height * a1 + edge * height * math.tan(alpha) * side
        scale = (10 ** rng.uniform(-9, -7) if speck else rng.uniform(0.01, 0.3)) * height
        v1 = piece(a1, np.zeros(3), scale)
        v2 = piece(-a2, centre, scale)
        size = float(np.ptp(np.r_[v1, v2], axis=0).max())
        sep = P.separates(v1, v2, P._dual_rays(a1, alpha), P._dual_rays(a2, alpha),
                          1e-9 * size)
        slack = _slack_program(v1, v2, a1, a2, alpha)
        if sep:
            assert slack < 1e-8 * size, (alpha, slack / size)
        if slack < -1e-2 * size:
            wide += 1
            caught += sep
    assert wide > cases // 10 and caught >= 0.9 * wide, (wide, caught)


def test_a_search_without_the_separation_test_gives_the_same_plans(monkeypatch):
    """The pairs the separation test bounds by 0 are those whose cone program holds no
    regions: the plans of the search with it and of the search solving every pair it
    reaches (``SEPARATE = False``, the reference) are equal, on a coarse torus where it
    bounds 40 pairs by 0."""
    from fcgrasp.spatial import regions as R

    solid = solid_from_mesh(trimesh.creation.torus(major_radius=30, minor_radius=10,
                                                   major_sections=8, minor_sections=6))
    separated = []

    def counted(*args):
        separated.append(P_separated(*args))
        return separated[-1]

    monkeypatch.setattr(R, "separated", counted)

    def plans():
        return [(p.facets, p.pieces, p.radius, p.radii, p.centers.tolist(),
                 p.regions.tolist()) for p in facet_pair_plans(solid, 0.5, top=2)]

    with_test = plans()
    assert sum(separated) >= 20
    monkeypatch.setattr(R, "SEPARATE", False)
    assert plans() == with_test


@pytest.mark.parametrize("cases", [200, pytest.param(3000, marks=pytest.mark.slow)])
def test_symmetric_piece_fits_equal_an_lp(cases, monkeypatch):
    """The fit of a turned octagon in a centrally symmetric piece, in closed form from
    the piece's widths (:func:`fcgrasp.spatial._pieces._fit` given them: the caps of
    round holes and bosses; its other ways, the vertices and scipy's LP, refused here),
    against HiGHS's LP over the centre and scale, on seeded regular polygons of 4 to 64
    sides stretched and sheared (still symmetric)."""
    import scipy.optimize
    import shapely

    from fcgrasp.spatial import _pieces as P

    from ._highs import linprog

    def refused(*args, **kwargs):
        raise AssertionError("the closed form was not taken")

    monkeypatch.setattr(P, "_vertex_fit", refused)
    monkeypatch.setattr(scipy.optimize, "linprog", refused)
    rng = np.random.default_rng(cases)
    checked = 0
    for _ in range(cases):
        n = 2 * int(rng.integers(2, 33))
        ang = rng.uniform(0, 2 * math.pi) + np.arange(n) * 2 * math.pi / n
        ring = np.c_[np.cos(ang), np.sin(ang)] @ (rng.normal(size=(2, 2)) + 2 * np.eye(2))
        ring = ring * rng.uniform(0.1, 50) + rng.normal(size=2) * 20
        E, h = P._halfplanes(shapely.Polygon(ring).convex_hull)
        if len(E) != n:
            continue
        phi = rng.uniform(0, 2 * math.pi)
        corners = _octagon(phi)
        ring2 = P._ring(shapely.Polygon(ring).convex_hull)
        width = h - (E @ ring2.T).min(axis=1)
        s, t = P._fit((E, h), corners, width)
        k = (E @ corners.T).max(axis=1)
        lp = _lp_fit(linprog, E, h, k)
        assert s == pytest.approx(lp.x[2], rel=1e-7, abs=1e-9 * np.abs(ring).max())
        assert np.all(E @ t + s * k <= h + 1e-9 * np.abs(h).max())
        checked += 1
    assert checked > cases // 2
