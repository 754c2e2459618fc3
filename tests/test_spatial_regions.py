"""Regions of two soft fingers on solids (issue 33): every grasp of the regions (every
pair of corners and sampled points) passes the 6-D force-closure test, the regions on a
box, a cylinder and a prism equal their analytic optimum, the bounded search equals
solving every pair, and meshes are read and checked."""

from __future__ import annotations

import math

import numpy as np
import pytest

from fcgrasp.spatial import closure_margin, two_soft_closure
from fcgrasp.spatial.regions import soft_pair_plans, soft_pair_regions
from fcgrasp.spatial.solid import demo_solid, read_solid, solid_from_mesh

trimesh = pytest.importorskip("trimesh")


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
    solids = [demo_solid(n) for n in ("box", "cylinder", "prism", "angle")] if seed == 0 \
        else [_random_convex(seed)]
    checked = 0
    for solid in solids:
        mu = float(rng.choice([0.3, 0.6]))
        for plan in soft_pair_plans(solid, mu, top=4):
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
        if not soft_pair_plans(solid, mu, top=1):      # then no pair of facets holds any
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
           p.radius for p in soft_pair_plans(box, mu, top=None)}
    want = {(0, 0): min(40 * t / 2, 10 / 2), (1, 1): min(20 * t / 2, 10 / 2),
            (2, 2): min(10 * t / 2, 20 / 2)}
    assert got == pytest.approx(want, rel=1e-7)
    cyl = soft_pair_plans(demo_solid("cylinder"), mu, top=1)[0]      # the two caps
    assert cyl.radius == pytest.approx(30 * t / 2, rel=1e-6)
    assert abs(cyl.normals[0] @ cyl.normals[1] + 1) < 1e-9
    prism = soft_pair_plans(demo_solid("prism"), mu, top=1)[0]       # the ends, 25 apart
    assert prism.radius == pytest.approx(25 * t / 2, rel=1e-6)


@pytest.mark.parametrize("seed", [3, pytest.param(4, marks=pytest.mark.slow)])
def test_bounded_search_equals_every_pair(seed):
    solid = _random_convex(seed)
    for mu in (0.4, 0.8):
        every = soft_pair_plans(solid, mu, top=None)
        some = soft_pair_plans(solid, mu, top=3)
        assert [p.radius for p in some] == pytest.approx([p.radius for p in every[:3]])
        # no pair the search left out beats what it kept: the exhaustive list is sorted
        assert all(a.radius >= b.radius for a, b in zip(every, every[1:], strict=False))


def test_meshes_are_read_and_checked(tmp_path):
    path = tmp_path / "box.stl"
    trimesh.creation.box((30.0, 10.0, 10.0)).export(path)
    solid = read_solid(str(path))
    assert len(solid.facets) == 6 and solid.units == "mm"
    assert soft_pair_plans(solid, 0.5, top=1)[0].radius == pytest.approx(5.0, rel=1e-6)
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
    the figure is written, and a solid without --soft (or --soft on a polygon) is a
    one-line error."""
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
    for argv in (["plan", str(path)], ["plan", "demo:blob", "--soft"]):
        assert main(argv) != 0
        err = capsys.readouterr().err
        assert "--soft" in err and len(err.strip().splitlines()) == 1
