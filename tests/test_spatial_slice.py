"""The zero-force slice of three contacts' wrench hull read from its own vertices
(:mod:`fcgrasp.spatial._slice`) against qhull's 6-D hull (the reference, sharing none of
its code): the same radius on seeded triples of every kind, pyramids in special position
included (the faces of a box: parallel and perpendicular normals, symmetric contacts);
every point it keeps lies in the hull; its 3-D inradius is qhull's; three fingers' plans
on solids are the plans of the hull."""

from __future__ import annotations

import numpy as np
import pytest

from fcgrasp.spatial import _slice
from fcgrasp.spatial import triples as T
from fcgrasp.spatial.solid import demo_solid

from .test_spatial_triples import _alpha, _random_convex, _random_grasp

trimesh = pytest.importorskip("trimesh")
spatial = pytest.importorskip("scipy.spatial")

def _box_grasp(rng):
    """Three contacts on faces of an axis-aligned box (two on opposite faces, or three
    on faces meeting at a corner, or two on one face's neighbours), at the faces'
    centres or anywhere on them: exactly parallel and perpendicular normals."""
    half = rng.uniform(0.5, 2.0, 3) * 10.0 ** rng.uniform(-2, 2)
    faces = rng.choice(6, size=3, replace=False)
    points, normals = [], []
    for f in faces:
        axis, sign = f % 3, 1.0 if f < 3 else -1.0
        p = np.zeros(3) if rng.random() < 0.4 else rng.uniform(-1, 1, 3) * half
        p[axis] = sign * half[axis]
        n = np.zeros(3)
        n[axis] = -sign                               # inward
        points.append(p)
        normals.append(n)
    return np.array(points), np.array(normals), float(rng.choice([0.3, 0.5, 1.0]))


def _grasps(seed, count):
    """Box grasps, and ``test_spatial_triples``' triples of every kind (nearly collinear,
    coplanar normals, two nearly opposite; scales 1e-3 to 1e3), a fifth of them with two
    normals made exactly opposite."""
    rng = np.random.default_rng(seed)
    for _ in range(count):
        if rng.random() < 0.4:
            yield _box_grasp(rng)
            continue
        p, n, mu = _random_grasp(rng)
        if rng.random() < 0.2:
            n[1] = -n[0]
        yield p, n, mu


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 8))])
def test_the_slices_vertices_give_the_hulls_radius(seed):
    """Where the vertices decide (not None), their radius is the 6-D hull's to 1e-12
    of the generators' scale; they decide most of the triples that hold."""
    decided = holding = 0
    for p, n, mu in _grasps(seed, 150 if seed == 0 else 2000):
        w = T._generators(p, n, _alpha(mu))
        want = T._hull_slice_radius(w)
        got = _slice.slice_radius(w, T.PYRAMID_EDGES)
        holding += want > 0
        if got is None:
            continue
        decided += want > 0
        scale = float(np.max(np.linalg.norm(w, axis=1)))
        assert abs(got - want) <= 1e-12 * scale, (got, want, p.tolist(), n.tolist(), mu)
    assert decided >= 0.9 * holding > 0, (decided, holding)


def test_the_generators_built_in_the_loop_are_the_searchs():
    """The slice read at three contacts with the generators built in the compiled loop
    (a triple's refinement) is the slice of ``_generators``' wrenches, number for
    number, and so is the reach its radius is in units of."""
    for p, n, mu in _grasps(5, 200):
        forces = T._pyramid_forces(n, _alpha(mu))
        want = _slice.slice_radius(T._generators(p, n, _alpha(mu), forces),
                                   T.PYRAMID_EDGES)
        got, reach = _slice.slice_radius_at(p, forces, None, T.TOL)
        assert got == want and reach == T._reach(p)


@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow)])
def test_every_point_the_slice_keeps_is_in_the_hull(seed):
    """Each moment the vertex reading keeps, at zero force, satisfies every facet of the
    6-D hull (qhull's) to 1e-12: the radius read from them cannot exceed the slice's."""
    table = _slice.pattern_table(T.PYRAMID_EDGES)
    loops = _slice._LOOPS.get()
    for p, n, mu in _grasps(100 + seed, 50 if seed == 0 else 1000):
        w = T._generators(p, n, _alpha(mu))
        try:
            eq = spatial.ConvexHull(w).equations
        except (spatial.QhullError, ValueError):
            continue
        out = np.empty((len(table), 3))
        count = loops["_slice_points"](w, table, 1e-12, out)
        scale = float(np.max(np.linalg.norm(w, axis=1)))
        assert np.all(out[:count] @ eq[:, 3:6].T + eq[:, 6] <= 1e-12 * scale)


def _point_sets(rng, count):
    """Point sets about the origin and beside it, with many points on one plane (prisms
    over regular polygons, a cube's corners and face centres: a slice's facets hold
    several vertices), and flat ones."""
    for k in range(count):
        kind = k % 5
        if kind == 0:
            pts = rng.normal(size=(int(rng.integers(4, 200)), 3))
        elif kind == 1:
            pts = rng.normal(size=(int(rng.integers(4, 60)), 3)) + rng.normal(size=3) * 2
        elif kind == 2:
            a = 2 * np.pi * np.arange(int(rng.integers(3, 12))) / 8
            ring = np.c_[np.cos(a), np.sin(a)]
            pts = np.concatenate([np.c_[ring, np.full(len(ring), z)]
                                  for z in rng.uniform(-1, 1, 2)])
        elif kind == 3:
            g = np.array(np.meshgrid([-1, 0, 1], [-1, 0, 1], [-1, 0, 1])).reshape(3, -1).T
            pts = g[np.abs(g).sum(axis=1) > 0] * rng.uniform(0.5, 2, 3) + \
                rng.normal(scale=0.3, size=3)
        else:
            pts = rng.normal(size=(int(rng.integers(4, 30)), 3))
            pts[:, 2] = 0.0
        yield kind, pts @ _rotation(rng)


def _rotation(rng):
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    return q


def test_the_3d_inradius_is_qhulls():
    """The 3-D inradius of a point set's hull (the incremental hull of the compiled
    loops, for the slice's vertices and the forces; ``forces_radius`` with qhull where
    it does not close) is qhull's smallest facet offset; a flat set has none (the hull
    does not close, no radius); the incremental hull closes on nearly all sets that are
    not flat."""
    rng = np.random.default_rng(7)
    loops = _slice._LOOPS.get()
    closed = solid = 0
    for kind, pts in _point_sets(rng, 400):
        status, r = loops["_hull_inradius"](pts, 1e-12)
        if kind == 4:
            assert status == 0 and _slice.forces_radius(pts) == -np.inf
            continue
        want = float(np.min(-spatial.ConvexHull(pts).equations[:, 3]))
        solid += 1
        if status:
            closed += 1
            assert r == pytest.approx(want, abs=1e-12)
        assert _slice.forces_radius(pts) == pytest.approx(want, abs=1e-12)
    assert closed >= 0.95 * solid, (closed, solid)


def _tied(plans):
    """Plans as compared across rounding: the radii in rank order, and each group of
    radii tied to 1e-9 as a set of (facets, regions by facet, rounded)."""
    radii = [p.radius for p in plans]
    groups, start = [], 0
    for i in range(1, len(plans) + 1):
        if i == len(plans) or abs(radii[i] - radii[start]) > 1e-9 * max(radii[start], 1):
            groups.append(sorted(
                (tuple(sorted(p.facets)),
                 tuple(tuple(np.round(r, 6).ravel()) for _, r in
                       sorted(zip(p.facets, p.regions, strict=True),
                              key=lambda fr: fr[0])))
                for p in plans[start:i]))
            start = i
    return radii, groups


@pytest.mark.parametrize("name", ["prism", pytest.param("box", marks=pytest.mark.slow),
                                  pytest.param("angle", marks=pytest.mark.slow),
                                  pytest.param("cylinder", marks=pytest.mark.slow),
                                  pytest.param("hull", marks=pytest.mark.slow)])
def test_three_finger_plans_are_those_of_the_hull(name, monkeypatch):
    """Three fingers' plans (the search, its refinement, the distinct alternatives) with
    the slice read from its vertices are the plans of the 6-D hull: the same radii, and
    among radii tied to rounding the same plans."""
    import fcgrasp as fc

    solids = [_random_convex(s) for s in range(3)] if name == "hull" else [demo_solid(name)]
    for solid in solids:
        got = []
        for on in (True, False):
            monkeypatch.setattr(T, "SLICE_VERTICES", on)
            got.append(_tied(fc.plan(solid, fingers=3, mu=0.5)))
        (ra, ga), (rb, gb) = got
        assert np.allclose(ra, rb, rtol=1e-9, atol=0)
        assert ga == gb
