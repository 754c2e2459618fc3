"""The seeded corpus of meshes beyond the built-in solids: brackets made by
constructive geometry (plates with holes and slots, L and T brackets with fillets: 2-D
booleans extruded) and convex decompositions of curved parts (a torus and a capsule cut
into sectors, each sector's hull a body of its own).  Every gripper's plans on each
(two soft fingers on facets and across them, three fingers with friction, the parallel
jaw) pass the independent tests of their own test modules."""

from __future__ import annotations

import math

import numpy as np
import pytest

from fcgrasp.spatial import closure_margin, soft_pair_plans, three_finger_plans
from fcgrasp.spatial.jaw import solid_jaw_plans
from fcgrasp.spatial.solid import solid_from_mesh
from fcgrasp.spatial.surfaces import SurfacePairPlan, SurfaceTriplePlan

from .test_spatial_jaw import _axes_inside
from .test_spatial_jaw import _holds as jaw_holds
from .test_spatial_regions import _grasps as pair_grasps
from .test_spatial_surfaces import _check_plans, _region_points
from .test_spatial_triples import _grasps as triple_grasps

trimesh = pytest.importorskip("trimesh")
shapely = pytest.importorskip("shapely")


def _bracket(seed):
    """A bracket by 2-D booleans, extruded: a plate with round holes and a slot, an L or
    a T with a fillet in its inner corner (a quarter circle of 16 segments)."""
    rng = np.random.default_rng(seed)
    kind = seed % 3
    w, h, t = (float(v) for v in rng.uniform([30, 20, 4], [80, 60, 12]))
    if kind == 0:
        plate = shapely.box(0, 0, w, h)
        holes = [shapely.Point(rng.uniform(6, w - 6), rng.uniform(6, h - 6)).buffer(
            float(rng.uniform(1.5, 3.5)), 8) for _ in range(int(rng.integers(1, 4)))]
        slot = shapely.LineString([(w * 0.3, h * 0.5), (w * 0.7, h * 0.5)]).buffer(2.0, 4)
        shape = plate.difference(shapely.union_all([*holes, slot]))
    else:
        leg = shapely.box(0, 0, t, h)
        foot = shapely.box(0, 0, w, t) if kind == 1 else shapely.box(-w / 2, 0, w / 2, t)
        fillet = shapely.box(t, t, t + 4, t + 4).difference(
            shapely.Point(t + 4, t + 4).buffer(4, 16))
        shape = shapely.union_all([leg, foot, fillet])
    if shape.geom_type != "Polygon":
        shape = max(shape.geoms, key=lambda g: g.area)
    shape = shape.simplify(1e-6 * w)          # no slivers where the pieces were joined
    depth = float(rng.uniform(8, 30))
    return solid_from_mesh(trimesh.creation.extrude_polygon(shape, depth), "mm",
                           f"bracket{seed}")


def _decomposed(seed):
    """One convex piece of a curved part: a torus's or a capsule's sector (the hull of
    the part's vertices within an angle about its axis)."""
    rng = np.random.default_rng(seed)
    if seed % 2:
        mesh = trimesh.creation.torus(major_radius=float(rng.uniform(20, 30)),
                                      minor_radius=float(rng.uniform(5, 9)),
                                      major_sections=48, minor_sections=24)
    else:
        mesh = trimesh.creation.capsule(height=float(rng.uniform(20, 40)),
                                        radius=float(rng.uniform(6, 12)), count=[24, 24])
    v = np.asarray(mesh.vertices)
    angle = np.arctan2(v[:, 1], v[:, 0])
    start = float(rng.uniform(-math.pi, math.pi))
    width = 2 * math.pi / int(rng.integers(3, 7))
    inside = np.mod(angle - start, 2 * math.pi) <= width
    return solid_from_mesh(trimesh.convex.convex_hull(v[inside]), "mm", f"piece{seed}")


def _check_every_gripper(solid, rng):
    """Every gripper's top plans on ``solid``, each grasp checked as its own test module
    checks it; returns how many plans were checked."""
    from fcgrasp.spatial import two_soft_closure

    checked = 0
    mu = 0.5
    soft = soft_pair_plans(solid, mu, top=4)
    across = [p for p in soft if isinstance(p, SurfacePairPlan)]
    checked += _check_plans(rng, solid, mu, across, inside=10)
    for plan in (p for p in soft if not isinstance(p, SurfacePairPlan)):
        P = pair_grasps(rng, plan, 20)
        assert two_soft_closure(P, np.broadcast_to(plan.normals, P.shape), mu).all()
        checked += 1
    tight = math.tan(math.atan(mu) - math.radians(0.5))
    for plan in three_finger_plans(solid, mu, top=2, margin=0.5).plans:
        if isinstance(plan, SurfaceTriplePlan):    # points found on the mesh by rays
            regions = [_region_points(rng, solid, plan, k, 4) for k in range(3)]
            for _ in range(20):
                pick = [rng.integers(len(P)) for P, _ in regions]
                P = np.array([regions[k][0][i] for k, i in enumerate(pick)])
                N = np.array([regions[k][1][i] for k, i in enumerate(pick)])
                assert closure_margin(P, N, tight).closure
        else:
            for P in triple_grasps(rng, plan, 20, 4):
                assert closure_margin(P, plan.normals, tight).closure
        checked += 1
    for plan in solid_jaw_plans(solid, (2, 120), 6, mu, top=2, margin=0.5):
        for x in _axes_inside(rng, solid, plan, 8):
            assert jaw_holds(solid, plan, x)
        checked += 1
    return checked


@pytest.mark.parametrize("seed", [pytest.param(s, marks=pytest.mark.slow)
                                  for s in range(12)])
def test_every_gripper_holds_on_brackets_made_by_booleans(seed):
    rng = np.random.default_rng(seed)
    assert _check_every_gripper(_bracket(seed), rng) >= 2


@pytest.mark.parametrize("seed", [1, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in (0, *range(2, 12)))])
def test_every_gripper_holds_on_convex_pieces_of_curved_parts(seed):
    rng = np.random.default_rng(seed)
    solid = _decomposed(seed)
    assert _check_every_gripper(solid, rng) >= 2
