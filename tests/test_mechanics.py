"""The mirrored mechanics (:mod:`fcgrasp.mechanics`): the planar and spatial modules have
the same names and parameters, take outward normals, and agree with methods that share
none of their code: a linear program on the generators for closure (the exact planar
cones; the inscribed and circumscribed pyramids of the solid cones), the generators'
work on the unresisted wrench, and an exhaustive enumeration of the hull's facets for
epsilon and volume."""

from __future__ import annotations

import inspect
from itertools import combinations

import numpy as np
import pytest

from fcgrasp.errors import FcgraspError
from fcgrasp.mechanics import planar, spatial

from .conftest import lp_positive_margin

#: parameters only a solid contact has: a soft finger's torsion, the pyramid's edges
SOLID_ONLY = ("torsion", "facets")


# ------------------------------------------------------------------------ the mirror


@pytest.mark.parametrize("module", ["contacts", "closure", "quality"])
def test_the_same_functions_with_the_same_parameters(module):
    flat, solid = getattr(planar, module), getattr(spatial, module)
    assert flat.__all__ == solid.__all__
    for name in flat.__all__:
        a, b = getattr(flat, name), getattr(solid, name)
        if not callable(a):
            continue
        pa = inspect.signature(a).parameters
        pb = inspect.signature(b).parameters
        assert list(pa) == [p for p in pb if p not in SOLID_ONLY], name
        for p in pa:
            assert (pa[p].kind, pa[p].default) == (pb[p].kind, pb[p].default), (name, p)
    assert planar.__all__ == spatial.__all__


# ------------------------------------------------------------ independent references


def _frame(n):
    """Two unit tangents completing the unit normal ``n`` (any right-handed choice)."""
    a = np.array([1.0, 0, 0]) if abs(n[0]) < 0.9 else np.array([0, 1.0, 0])
    t1 = np.cross(n, a)
    t1 /= np.linalg.norm(t1)
    return t1, np.cross(n, t1)


def _generators_2d(p, n, mu, c, r):
    rows = []
    for pi, ni, mi in zip(p, n, mu, strict=True):
        ni = ni / np.linalg.norm(ni)
        t = np.array([-ni[1], ni[0]])
        for s in (1, -1):
            f = -ni + s * mi * t
            x, y = (pi - c) / r
            rows.append([f[0], f[1], x * f[1] - y * f[0]])
    return np.array(rows)


def _generators_3d(p, n, mu, tor, c, r, edges, widen=1.0):
    """The pyramid of ``edges`` edges of each cone (``widen``: its friction scaled), with
    a soft finger's two torsion extremes on every edge (the circumscribed box) or only
    the pure torsions (inscribed: ``widen == 1``)."""
    rows = []
    for pi, ni, mi, ti in zip(p, n, mu, tor, strict=True):
        push = -ni / np.linalg.norm(ni)
        t1, t2 = _frame(push)
        arm = (pi - c) / r
        for a in 2 * np.pi * np.arange(edges) / edges:
            f = push + widen * mi * (np.cos(a) * t1 + np.sin(a) * t2)
            m = np.cross(arm, f)
            if ti > 0 and widen > 1:
                rows += [[*f, *(m + ti * push / r)], [*f, *(m - ti * push / r)]]
            else:
                rows.append([*f, *m])
        if ti > 0 and widen == 1:
            m = np.cross(arm, push)
            rows += [[*push, *(m + ti * push / r)], [*push, *(m - ti * push / r)]]
    return np.array(rows)


def _spans(w):
    """Whether the rows of ``w`` positively span their space, by a linear program
    (:func:`~tests.conftest.lp_positive_margin`: positive only when some strictly
    positive combination of them vanishes), with full rank.  Returns the program's
    margin (-1: rank deficient)."""
    if np.linalg.matrix_rank(w, tol=1e-9 * np.abs(w).max()) < w.shape[1]:
        return -1.0
    return lp_positive_margin(w)


def _facets(points, tol=1e-9):
    """Every supporting hyperplane of the hull of ``points`` through ``d`` of them, by
    trying every ``d``-subset: unit normals ``u`` and offsets ``h`` with ``u . x <= h``
    for every point."""
    pts = np.unique(np.round(points, 12), axis=0)
    d = pts.shape[1]
    out = []
    for idx in combinations(range(len(pts)), d):
        base = pts[list(idx)]
        diffs = base[1:] - base[0]
        _, s, vt = np.linalg.svd(diffs)
        if s[-1] < 1e-9:
            continue
        u = vt[-1]
        side = (pts - base[0]) @ u
        if np.all(side <= tol):
            out.append((u, float(u @ base[0])))
        elif np.all(side >= -tol):
            out.append((-u, float(-u @ base[0])))
    return out, pts


def _epsilon_by_facets(points):
    facets, pts = _facets(points)
    if not facets or np.linalg.matrix_rank(pts - pts.mean(axis=0), tol=1e-9) < pts.shape[1]:
        return 0.0                       # a flat hull holds no ball
    h = min(off for _, off in facets)
    return max(h, 0.0) if h > 1e-9 else 0.0


def _area_2d(q):
    """The area of the convex hull of 2-D points (monotone chain, shoelace)."""
    q = sorted(map(tuple, np.round(q, 12)))
    def half(seq):
        h = []
        for x in seq:
            while len(h) >= 2 and ((h[-1][0] - h[-2][0]) * (x[1] - h[-2][1])
                                   - (h[-1][1] - h[-2][1]) * (x[0] - h[-2][0])) <= 0:
                h.pop()
            h.append(x)
        return h
    ring = half(q)[:-1] + half(q[::-1])[:-1]
    return 0.5 * abs(sum(a[0] * b[1] - b[0] * a[1]
                         for a, b in zip(ring, ring[1:] + ring[:1], strict=True)))


def _volume_3d(points):
    """The volume of the hull of 3-D points: a cone from their mean over each facet
    (the facet's polygon: the points on its plane, their 2-D hull)."""
    facets, pts = _facets(points)
    o = pts.mean(axis=0)
    seen, vol = set(), 0.0
    for u, h in facets:
        key = tuple(np.round(np.r_[u, h], 7))
        if key in seen:
            continue
        seen.add(key)
        on = pts[np.abs(pts @ u - h) <= 1e-9]
        t1, t2 = _frame(u)
        vol += _area_2d(np.c_[on @ t1, on @ t2]) * (h - o @ u) / 3
    return vol


def _planar_cases(seed, count):
    rng = np.random.default_rng(seed)
    for _ in range(count):
        k = int(rng.integers(2, 5))
        ang = rng.uniform(0, 2 * np.pi, k)
        p = np.c_[np.cos(ang), 0.6 * np.sin(ang)] * rng.uniform(0.5, 3)
        p += rng.normal(0, 0.3, p.shape)
        tilt = ang + rng.normal(0, 0.6, k)
        n = np.c_[np.cos(tilt), np.sin(tilt)]
        if rng.random() < 0.2:             # near-degenerate: a finger on a neighbour's line
            n[-1] = -n[0] + rng.normal(0, 1e-6, 2)
            p[-1] = p[0] - rng.uniform(0.5, 2) * n[0]
        mu = rng.uniform(0, 1, k) if rng.random() < 0.5 else float(rng.uniform(0, 1))
        if rng.random() < 0.15:
            mu = 0.0
        yield p, n, mu


# ----------------------------------------------------------------- planar vs the LP

#: seeded cases by default, a sweep under ``-m slow``
COUNTS = [pytest.param(1, id="sample"), pytest.param(8, id="sweep", marks=pytest.mark.slow)]


@pytest.mark.parametrize("scale", COUNTS)
def test_planar_closure_is_the_linear_programs(scale):
    decided = 0
    for p, n, mu in _planar_cases(0, 400 * scale):
        c = p.mean(axis=0)
        r = np.linalg.norm(p - c, axis=1).max()
        t = _spans(_generators_2d(p, n, np.broadcast_to(mu, len(p)), c, r))
        if abs(t) < 1e-6:                   # within the LP's tolerance of a tie
            continue
        decided += 1
        assert planar.force_closure(p, n, mu) == (t > 0), (p, n, mu, t)
    assert decided > 380 * scale


def test_the_unresisted_wrench_is_done_no_negative_work():
    seen = 0
    for p, n, mu in _planar_cases(1, 1000):
        d = planar.unresisted_wrench(p, n, mu)
        if d is None:
            assert planar.force_closure(p, n, mu)
            continue
        seen += 1
        assert np.linalg.norm(d) == pytest.approx(1.0)
        w = planar.contact_wrenches(p, n, mu).reshape(-1, 3)
        assert np.all(w @ d >= -1e-7), (p, n, mu, d)
    assert seen > 200


def test_planar_epsilon_and_volume_are_the_hulls_facets():
    checked = 0
    for p, n, mu in _planar_cases(2, 150):
        w = planar.contact_wrenches(p, n, mu).reshape(-1, 3)
        ref = _epsilon_by_facets(w)
        assert planar.epsilon(p, n, mu) == pytest.approx(ref, abs=1e-9)
        if np.linalg.matrix_rank(w - w.mean(axis=0), tol=1e-6) == 3:
            assert planar.volume(p, n, mu) == pytest.approx(_volume_3d(w), rel=1e-6)
        checked += ref > 0
    assert checked > 15


def test_planar_generators_are_the_contacts_forces():
    rng = np.random.default_rng(3)
    for p, n, mu in _planar_cases(3, 200):
        c, r = rng.normal(size=2), float(rng.uniform(0.5, 4))
        got = planar.contact_wrenches(p, n, mu, center=c, radius=r).reshape(-1, 3)
        want = _generators_2d(p, n, np.broadcast_to(mu, len(p)), c, r)
        np.testing.assert_allclose(got, want, atol=1e-12)


# ---------------------------------------------------------------- spatial vs the LPs


def _spatial_cases(seed, count):
    rng = np.random.default_rng(seed)
    for _ in range(count):
        k = int(rng.integers(2, 5))
        d = rng.normal(size=(k, 3))
        d /= np.linalg.norm(d, axis=1)[:, None]
        p = d * rng.uniform(0.5, 2, (k, 1))
        n = d + rng.normal(0, 0.4, (k, 3))                     # roughly outward
        mu = float(rng.uniform(0.1, 1))
        tor = float(rng.uniform(0.01, 0.3)) if k == 2 or rng.random() < 0.3 else 0.0
        if k == 2 and rng.random() < 0.5:                       # nearly opposite
            p[1] = -p[0] * rng.uniform(0.5, 2)
            n[1] = -n[0] + rng.normal(0, 0.3, 3)
        yield p, n, mu, tor


@pytest.mark.parametrize("scale", COUNTS)
def test_spatial_closure_between_the_pyramids_linear_programs(scale):
    """A grasp the inscribed pyramids prove is in force closure; one the circumscribed
    pyramids refute is not (32 edges: the two differ by 0.5 %)."""
    proved = refuted = 0
    edges = 32
    for p, n, mu, tor in _spatial_cases(4, 80 * scale):
        c = p.mean(axis=0)
        r = np.linalg.norm(p - c, axis=1).max()
        mus, tors = np.full(len(p), mu), np.full(len(p), tor)
        got = spatial.force_closure(p, n, mu, tor)
        if _spans(_generators_3d(p, n, mus, tors, c, r, edges)) > 1e-7:
            proved += 1
            assert got, (p, n, mu, tor)
        widen = 1 / np.cos(np.pi / edges)
        if _spans(_generators_3d(p, n, mus, tors, c, r, edges, widen)) < -1e-7:
            refuted += 1
            assert not got, (p, n, mu, tor)
    assert proved > 8 * scale and refuted > 8 * scale


def test_spatial_unresisted_wrench_is_done_no_negative_work():
    seen = 0
    for p, n, mu, tor in _spatial_cases(5, 150):
        d = spatial.unresisted_wrench(p, n, mu, tor)
        assert (d is None) == spatial.force_closure(p, n, mu, tor)
        if d is None:
            continue
        seen += 1
        w = spatial.contact_wrenches(p, n, mu, tor, facets=16).reshape(-1, 6)
        assert np.all(w @ d >= -1e-5 * np.abs(w).max()), (p, n, mu, tor)
    assert seen > 20


@pytest.mark.parametrize("scale", COUNTS)
def test_spatial_epsilon_is_the_hulls_facets(scale):
    checked = 0
    for p, n, mu, tor in _spatial_cases(6, 20 * scale):
        if len(p) > 3:
            continue
        w = spatial.contact_wrenches(p, n, mu, tor, facets=4).reshape(-1, 6)
        ref = _epsilon_by_facets(w)
        assert spatial.epsilon(p, n, mu, tor, facets=4) == pytest.approx(ref, abs=1e-8)
        checked += ref > 0
    assert checked > scale


# ----------------------------------------------------------------- outward normals


def test_normals_point_out_of_the_part():
    """On a mesh the normals of the faces (out of the solid) and on a polygon those of
    its edges: the contacts push into the part, and squeezing two opposite faces holds it;
    with one normal reversed (one finger pushing, the other pulling) it does not."""
    import trimesh

    from fcgrasp import Polygon

    box = trimesh.creation.box([2, 1, 1])
    pts, faces = trimesh.sample.sample_surface_even(box, 200, seed=0)
    normals = box.face_normals[faces]
    assert np.all(np.einsum("ij,ij->i", normals, pts - box.center_mass) > 0)
    right = np.flatnonzero(normals[:, 0] > 0.99)[0]
    left = np.flatnonzero(normals[:, 0] < -0.99)[0]
    two = pts[[right, left]]
    two[1, 1:] = two[0, 1:]
    out = normals[[right, left]]
    forces = spatial.contact_wrenches(two, out, 0.5, 0.05)[..., :3]
    assert np.all(np.einsum("kgi,ki->kg", forces, out) < 0)
    assert spatial.force_closure(two, out, 0.5, 0.05)
    assert not spatial.force_closure(two, out * [[1], [-1]], 0.5, 0.05)

    square = Polygon([[0, 0], [2, 0], [2, 1], [0, 1]])
    out2 = square.normals[[1, 3]]                 # the right and left edges, outward
    assert np.all(out2 @ np.array([1.0, 0]) * np.array([1, -1]) > 0)
    mid = np.array([[2, 0.5], [0, 0.5]])
    forces = planar.contact_wrenches(mid, out2, 0.3)[..., :2]
    assert np.all(np.einsum("kgi,ki->kg", forces, out2) < 0)
    assert planar.force_closure(mid, out2, 0.3)
    assert not planar.force_closure(mid, out2 * [[1], [-1]], 0.3)


# ---------------------------------------------------------------------- bad input


@pytest.mark.parametrize("space, dim", [(planar, 2), (spatial, 3)])
@pytest.mark.parametrize("field, kwargs", [
    ("points", {"points": [[0.0] * 4]}),
    ("normals", {"normals": [[0.0] * 9]}),
    ("mu", {"mu": -0.1}),
    ("mu", {"mu": [0.1, 0.2, 0.3]}),
    ("radius", {"radius": 0.0}),
    ("center", {"center": [[0.0, 0.0, 0.0]]}),
])
def test_bad_input_names_the_argument(space, dim, field, kwargs):
    args = {"points": np.eye(dim)[:2], "normals": np.eye(dim)[:2], "mu": 0.3}
    for key, value in kwargs.items():
        if key == "normals":
            value = [[0.0] * dim] * 2
        args[key] = value
    for func in (space.force_closure, space.epsilon, space.contact_wrenches):
        with pytest.raises(FcgraspError) as err:
            func(**args)
        assert err.value.field == field
        assert field in str(err.value)
