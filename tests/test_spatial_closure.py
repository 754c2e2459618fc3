"""Force closure and quality of solid grasps, against methods that share no
code with fcgrasp.spatial: linear programs over linearised cones written here (an inner
pyramid proves force closure, an outer one refutes it), a second-order cone program over
the dual cones (no wrench the contacts cannot oppose), and facets of the wrench hull
found by brute force over every six generators (no qhull)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.spatial import (
    closure_margin,
    contact_frames,
    spatial_force_closure,
    spatial_quality,
    two_soft_closure,
)

from ._highs import linprog

# ------------------------------------------------------------------ independent oracles


def _frame(n):
    """Any two unit tangents of ``n`` (a different construction from fcgrasp's)."""
    a = np.array([1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    t1 = np.cross(n, a)
    t1 /= np.linalg.norm(t1)
    return t1, np.cross(n, t1)


def _generators(points, normals, mu, torsion, facets, outer, center, radius):
    rows = []
    widen = 1.0 / np.cos(np.pi / facets) if outer else 1.0
    for p, n, m, g in zip(points, normals, mu, torsion, strict=True):
        n = n / np.linalg.norm(n)
        t1, t2 = _frame(n)
        r = (p - center) / radius
        forces = [(n, 0.0)] if m == 0 else \
            [(n + m * widen * (np.cos(a) * t1 + np.sin(a) * t2), 0.0)
             for a in 2 * np.pi * (np.arange(facets) + 0.37) / facets]
        if g > 0:
            if outer:
                forces = [(f, s * g) for f, _ in forces for s in (1.0, -1.0)]
            else:
                forces += [(n, g), (n, -g)]
        for f, tw in forces:
            rows.append(np.r_[f, np.cross(r, f) + tw * n / radius])
    return np.array(rows)


def _lp_closure(W):
    """max t: sum l_i w_i = 0, sum l_i = 1, l_i >= t; force closure iff t > 0, rank 6."""
    W = W / np.linalg.norm(W, axis=1)[:, None]
    if np.linalg.matrix_rank(W, tol=1e-9) < 6:
        return False
    k = len(W)
    res = linprog(np.r_[np.zeros(k), -1.0],
                  A_ub=np.hstack([-np.eye(k), np.ones((k, 1))]), b_ub=np.zeros(k),
                  A_eq=np.vstack([np.hstack([W.T, np.zeros((6, 1))]),
                                  np.r_[np.ones(k), 0.0]]),
                  b_eq=np.r_[np.zeros(6), 1.0],
                  bounds=[(0, None)] * k + [(None, None)], method="highs")
    return res.status == 0 and -res.fun > 1e-9


def _dual_socp(points, normals, mu, torsion, center, radius):
    """The largest sum of normal components of G_i^T d over unit d with every G_i^T d
    in its dual cone (y_n >= mu |y_t|, with the soft finger's torsion scaled): 0 in
    force closure (only d = 0), positive when some wrench is not resisted."""
    import clarabel
    from scipy import sparse

    rows, b, cones = [], [], []
    q = np.zeros(6)
    for p, n, m, g in zip(points, normals, mu, torsion, strict=True):
        n = n / np.linalg.norm(n)
        t1, t2 = _frame(n)
        r = (p - center) / radius
        cols = [np.r_[d, np.cross(r, d)] for d in (n, t1, t2)]
        yn = cols[0]
        q -= yn                                     # maximise the sum of y_n
        if m == 0:
            rows.append(-yn)                        # y_n >= 0
            b.append(0.0)
            cones.append(clarabel.NonnegativeConeT(1))
            continue
        block = [-yn * 1.0, -cols[1] * m, -cols[2] * m]
        if g > 0:                                   # dual of |(f_t, mu m / g)| <= mu f_n
            block.append(-np.r_[np.zeros(3), n / radius] * g)
        rows += block
        b += [0.0] * len(block)
        cones.append(clarabel.SecondOrderConeT(len(block)))
    rows.append(np.zeros(6))                        # |d| <= 1
    b.append(1.0)
    rows += list(-np.eye(6))
    b += [0.0] * 6
    cones.append(clarabel.SecondOrderConeT(7))
    settings = clarabel.DefaultSettings()
    settings.verbose = False
    sol = clarabel.DefaultSolver(sparse.csc_matrix((6, 6)), q, sparse.csc_matrix(
        np.array(rows)), np.array(b), cones, settings).solve()
    return -float(sol.obj_val)


def _vertices(points):
    """The points that are not convex combinations of the others (one LP each)."""
    keep = []
    for i, p in enumerate(points):
        others = np.delete(points, i, axis=0)
        res = linprog(np.zeros(len(others)), A_eq=np.vstack([others.T, np.ones(len(others))]),
                      b_eq=np.r_[p, 1.0], bounds=[(0, None)] * len(others), method="highs")
        if res.status != 0:
            keep.append(i)
    return points[keep]


def _facet_epsilon(points):
    """Distance from the origin to the hull's boundary by brute force: every six
    vertices spanning a hyperplane with all points on one side is a facet's."""
    pts = _vertices(np.unique(np.round(np.asarray(points, float), 12), axis=0))
    combos = np.array(list(itertools.combinations(range(len(pts)), 6)))
    A = np.concatenate([pts[combos], np.ones(combos.shape + (1,))], axis=-1)   # (c, 6, 7)
    _, sv, vt = np.linalg.svd(A)
    h = vt[:, -1, :]
    nrm = np.linalg.norm(h[:, :6], axis=1)
    ok = (sv[:, -1] > 1e-9) & (nrm > 1e-12)             # one hyperplane through six
    h = h[ok] / nrm[ok, None]
    side = pts @ h[:, :6].T + h[:, 6]                   # (points, planes)
    below, above = np.all(side <= 1e-9, axis=0), np.all(side >= -1e-9, axis=0)
    h = np.vstack([h[below], -h[above]])                # outward normals, facets only
    if len(h) == 0 or np.any(h[:, 6] >= -1e-12):        # the origin on or outside one
        return 0.0
    return float(np.min(-h[:, 6]))


# ------------------------------------------------------------------ random grasps


def _random_grasp(rng, kind):
    """A random grasp of one contact type, some of them on a tie."""
    if kind == "soft2":
        p1 = rng.normal(size=3)
        d = rng.normal(size=3)
        d /= np.linalg.norm(d)
        p2 = p1 + rng.uniform(0.5, 3) * d
        mu = float(rng.choice([0.2, 0.5, 1.0]))
        half = np.arctan(mu)
        normals = []
        for axis in (d, -d):
            # the normal at an angle from the segment: inside, outside or on the cone
            ang = float(rng.choice([rng.uniform(0, 2 * half), half]))
            t1, _ = _frame(axis)
            normals.append(np.cos(ang) * axis + np.sin(ang) * t1)
        return np.array([p1, p2]), np.array(normals), np.full(2, mu), \
            np.full(2, float(rng.choice([0.01, 0.1])))
    k = {"friction3": 3, "friction4": 4, "soft3": 3, "frictionless7": 7}[kind]
    # points on a random ellipsoid, normals inward, tilted
    axes = rng.uniform(0.5, 2.0, 3)
    u = rng.normal(size=(k, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    points = u * axes
    normals = -u / axes**2
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    normals += rng.normal(scale=0.3, size=(k, 3))
    if rng.random() < 0.2:                          # every normal through one point: a tie
        normals = -(points - points.mean(axis=0))
    mu = 0.0 if kind == "frictionless7" else float(rng.choice([0.1, 0.3, 0.8]))
    torsion = 0.05 if kind == "soft3" else 0.0
    return points, normals, np.full(k, mu), np.full(k, torsion)


KINDS = ("soft2", "friction3", "friction4", "soft3", "frictionless7")


def _cases(seed, n):
    rng = np.random.default_rng(seed)
    return [_random_grasp(rng, KINDS[i % len(KINDS)]) for i in range(n)]


@pytest.mark.parametrize("seed,n", [(0, 150), pytest.param(1, 5000, marks=pytest.mark.slow)])
def test_closure_agrees_with_pyramid_lps_and_the_dual_cone_program(seed, n):
    """Inner pyramid proves => fcgrasp says closure; outer pyramid refutes => it says
    not; the dual program decides the rest (away from its accuracy)."""
    counts = {"inner": 0, "outer": 0, "dual": 0, "closure": 0}
    for points, normals, mu, torsion in _cases(seed, n):
        c = points.mean(axis=0)
        radius = float(np.max(np.linalg.norm(points - c, axis=1)))
        got = closure_margin(points, normals, mu, torsion)
        counts["closure"] += got.closure
        inner = _lp_closure(_generators(points, normals, mu, torsion, 16, False, c, radius))
        if inner:
            assert got.closure
            counts["inner"] += 1
            continue
        outer = _lp_closure(_generators(points, normals, mu, torsion, 16, True, c, radius))
        if not outer:
            assert not got.closure
            counts["outer"] += 1
            continue
        dual = _dual_socp(points, normals, mu, torsion, c, radius)
        if dual > 1e-5:
            assert not got.closure
        elif got.margin > 1e-5:
            assert dual < 1e-6
        counts["dual"] += 1
    assert counts["inner"] > n // 10 and counts["outer"] > n // 10, counts
    assert 0 < counts["closure"] < n


def test_two_soft_fingers_closed_form_equals_the_cone_program():
    """The batched closed form (segment inside both cones) and the cone program agree on
    random pairs, those on a cone's edge included (not force closure: a tie)."""
    rng = np.random.default_rng(5)
    cases = [_random_grasp(rng, "soft2") for _ in range(400)]
    P = np.array([c[0] for c in cases])
    N = np.array([c[1] for c in cases])
    mu = np.array([c[2][0] for c in cases])
    fast = two_soft_closure(P, N, mu)
    batch = spatial_force_closure(P, N, mu[:, None], 0.05)
    assert np.array_equal(fast, batch)
    agree = 0
    for i, (p, n, m, g) in enumerate(cases):
        slow = closure_margin(p, n, m, g)
        if slow.margin > 1e-5 or slow.margin < 1e-7:      # away from its accuracy
            assert fast[i] == slow.closure
            agree += 1
    assert agree > 350 and 10 < fast.sum() < 350
    # two points with friction and no torsion never hold
    assert not spatial_force_closure(P[:20], N[:20], mu[:20, None]).any()


def test_unresisted_wrench_is_opposed_by_no_contact():
    """When a grasp fails, every contact wrench does work >= 0 on the reported wrench,
    so the contacts cannot supply its opposite."""
    rng = np.random.default_rng(7)
    seen = 0
    for points, normals, mu, torsion in _cases(11, 120):
        got = closure_margin(points, normals, mu, torsion)
        if got.closure:
            continue
        c = points.mean(axis=0)
        radius = float(np.max(np.linalg.norm(points - c, axis=1)))
        W = _generators(points, normals, mu, torsion, 32, False, c, radius)
        W /= np.linalg.norm(W, axis=1)[:, None]
        assert np.all(W @ got.unresisted >= -1e-6), got.explain()
        assert "not force closure" in got.explain()
        seen += 1
    assert seen > 20
    del rng


@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow)])
def test_epsilon_l1_and_linf_equal_brute_force_facets(seed):
    """Ferrari-Canny L1 and L-infinity against facets found over every six generators."""
    rng = np.random.default_rng(seed)
    checked = 0
    for _ in range(12 if seed == 0 else 30):
        k = int(rng.choice([2, 3]))
        points = rng.normal(size=(k, 3))
        normals = -(points - points.mean(axis=0)) + rng.normal(scale=0.3, size=(k, 3))
        torsion = 0.05 if k == 2 else 0.0
        mu = float(rng.uniform(0.2, 0.8))
        facets = 4 if k == 3 else 3
        c = points.mean(axis=0)
        radius = float(np.max(np.linalg.norm(points - c, axis=1)))
        got = spatial_quality(points, normals, mu, torsion, facets=facets, linf=True)
        # the same generators as fcgrasp's (its frame), so the hulls are the same sets
        t1, t2 = contact_frames(normals / np.linalg.norm(normals, axis=1)[:, None])
        gens = []
        for i in range(k):
            n = normals[i] / np.linalg.norm(normals[i])
            r = (points[i] - c) / radius
            fs = [(n + mu * (np.cos(a) * t1[i] + np.sin(a) * t2[i]), 0.0)
                  for a in 2 * np.pi * np.arange(facets) / facets]
            if torsion:                             # the pure torsions (inner)
                fs += [(n, torsion), (n, -torsion)]
            gens.append(np.array([np.r_[f, np.cross(r, f) + tw * n / radius]
                                  for f, tw in fs]))
        want1 = _facet_epsilon(np.vstack(gens))
        assert got.epsilon_l1 == pytest.approx(want1, abs=1e-9)
        if want1 > 0 and k == 2 and seed:            # 36 sums: seconds each, -m slow
            sums = [np.zeros(6)]
            for g in gens:
                sums = [s + w for s in sums for w in np.vstack([np.zeros((1, 6)), g])]
            assert got.epsilon_linf == pytest.approx(_facet_epsilon(np.unique(
                np.round(sums, 12), axis=0)), abs=1e-9)
        if want1 > 0:                                # the L1 set is inside the L-inf one,
            assert want1 - 1e-9 <= got.epsilon_linf <= k * want1 + 1e-9   # k times it holds it
        checked += want1 > 0
    assert checked >= 2


def test_spatial_errors_name_the_argument():
    with pytest.raises(ValueError, match="normals"):
        closure_margin([[0, 0, 0], [1, 0, 0]], [[0, 0, 0], [1, 0, 0]], 0.3)
    with pytest.raises(ValueError, match="torsion"):
        closure_margin([[0, 0, 0], [1, 0, 0]], [[1, 0, 0], [-1, 0, 0]], 0.0, 0.1)
    with pytest.raises(ValueError, match="mu"):
        closure_margin([[0, 0, 0], [1, 0, 0]], [[1, 0, 0], [-1, 0, 0]], -0.1)
    with pytest.raises(ValueError, match="points"):
        closure_margin([[0, 0], [1, 0]], [[1, 0], [-1, 0]], 0.3)
    with pytest.raises(ValueError, match="facets"):
        spatial_quality([[0, 0, 0], [1, 0, 0]], [[1, 0, 0], [-1, 0, 0]], 0.3, facets=2)


@pytest.mark.parametrize("mu", [0.5, [0.5, 0.6]])
def test_one_grasp_of_shape_k_by_3(mu):
    """One grasp, shape (k, 3) as the docstring allows: a 0-d answer, the same as the
    batch of one's, through the closed form and through the general test."""
    p = np.array([[-1.0, 0, 0], [1.0, 0, 0]])
    n = np.array([[1.0, 0, 0], [-1.0, 0, 0]])
    one = fc.spatial_force_closure(p, n, mu=mu, torsion=0.1)
    batch = fc.spatial_force_closure(p[None], n[None], mu=mu, torsion=0.1)
    assert np.shape(one) == () and batch.shape == (1,)
    assert bool(one) == bool(batch[0]) is True
    tilted = fc.spatial_force_closure(p, [[1.0, 0, 0], [0, 0, 1.0]], mu=mu, torsion=0.1)
    assert np.shape(tilted) == () and not tilted
