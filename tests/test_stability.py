"""Grasp stability with fingers as springs (fcgrasp.model.stability, issue 32): the
stiffness matrix against central differences of the potential energy computed from the
moved part (the edge's line moved rigidly, the fingertips fixed), on seeded random
grasps in equilibrium; the classic cases by hand."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import linprog

import fcgrasp as fc
from fcgrasp.model.stability import grasp_stability, grasp_stiffness, least_stiffness


def _energy(q, p, n, kn, f, kt, g, rho):
    """Springs' energy after the part turns by q[2] about the origin and moves by q[:2]:
    each tip (centre p + rho n, fixed) pressed into the moved edge's line, each sticking
    tip stretched along the edge by its material point's displacement."""
    c, s = np.cos(q[2]), np.sin(q[2])
    R = np.array([[c, -s], [s, c]])
    total = 0.0
    for i in range(len(p)):
        moved = R @ p[i] + q[:2]
        normal = R @ n[i]
        centre = p[i] + rho[i] * n[i]
        depth = rho[i] - normal @ (centre - moved)          # how far the tip is pressed in
        u = np.array([-n[i, 1], n[i, 0]])
        stretch = u @ (moved - p[i])
        total += 0.5 * kn[i] * (depth + f[i] / kn[i]) ** 2
        if kt[i] > 0:
            total += 0.5 * kt[i] * (stretch - g[i] / kt[i]) ** 2
    return total


def _balanced(rng, k):
    """Random contacts with normal and tangential preloads that balance (None if the
    fingers cannot push in equilibrium)."""
    ang = np.sort(rng.uniform(0, 2 * np.pi, k))
    p = np.c_[np.cos(ang), np.sin(ang)] * rng.uniform(5, 20, (k, 1))
    n = np.c_[np.cos(ang), np.sin(ang)] + rng.normal(0, 0.3, (k, 2))
    n /= np.hypot(*n.T)[:, None]
    u = np.c_[-n[:, 1], n[:, 0]]
    stick = rng.random() < 0.5
    # variables f (k, >= 1) and g (k, free if sticking): sum of wrenches zero
    W = np.concatenate([-np.c_[n, p[:, 0] * n[:, 1] - p[:, 1] * n[:, 0]],
                        np.c_[u, p[:, 0] * u[:, 1] - p[:, 1] * u[:, 0]]]).T
    bounds = [(1.0, 10.0)] * k + ([(-3.0, 3.0)] if stick else [(0.0, 0.0)]) * k
    res = linprog(rng.normal(size=2 * k), A_eq=W, b_eq=np.zeros(3), bounds=bounds,
                  method="highs")
    if res.status != 0:
        return None
    return p, n, res.x[:k], res.x[k:], stick


@pytest.mark.parametrize("seed", range(3))
def test_stiffness_is_the_hessian_of_the_energy(seed):
    rng = np.random.default_rng(seed)
    done = 0
    while done < 40:
        case = _balanced(rng, int(rng.integers(2, 5)))
        if case is None:
            continue
        p, n, f, g, stick = case
        k = len(p)
        kn = rng.uniform(10, 200, k)
        kt = rng.uniform(10, 200, k) if stick else np.zeros(k)
        rho = rng.uniform(0, 3, k) if rng.random() < 0.5 else np.zeros(k)
        K = grasp_stiffness(p, n, kn, f, kt, g, rho)
        h = 1e-4
        E = np.eye(3) * h
        args = (p, n, kn, f, kt, g, rho)
        grad = np.array([(_energy(E[a], *args) - _energy(-E[a], *args)) / (2 * h)
                         for a in range(3)])
        fd = np.array([[(_energy(E[a] + E[b], *args) - _energy(E[a] - E[b], *args)
                         - _energy(-E[a] + E[b], *args) + _energy(-E[a] - E[b], *args))
                        / (4 * h * h) for b in range(3)] for a in range(3)])
        scale = np.abs(K).max()
        assert np.abs(grad).max() <= 1e-6 * scale          # at rest: in equilibrium
        assert np.allclose(K, fd, rtol=0, atol=1e-5 * scale), (K, fd)
        st = grasp_stability(p, n, kn, f, kt, g, rho)
        assert st.stable == bool(np.linalg.eigvalsh(fd)[0] > 1e-6 * scale) or \
            abs(np.linalg.eigvalsh(fd)[0]) <= 1e-4 * scale
        done += 1


def test_classic_grasps_by_hand():
    """A pinch of flat faces is stable in rotation (its faces tilt into the tips), tips
    that slide leave the pinch free along the faces; three tips on the faces of a
    triangle hold it; the preload must balance; the least stiffness meets the margin."""
    pinch = ([[-10, 0], [10, 0]], [[-1, 0], [1, 0]])
    sliding = grasp_stability(*pinch, stiffness=100, preload=[5, 5])
    assert not sliding.stable and "neutral" in sliding.reason
    assert np.allclose(np.abs(sliding.weakest), [0, 1, 0])
    assert sliding.matrix[2, 2] == pytest.approx(2 * 5 * 10)
    # a tip of radius 4 rolls on the face: the rotation stiffness grows by 2 f rho
    rolled = grasp_stiffness(*pinch, 100, [5, 5], finger_radius=4)
    assert rolled[2, 2] == pytest.approx(2 * 5 * (10 + 4))
    with pytest.raises(ValueError, match="preload must balance"):
        grasp_stability(*pinch, stiffness=100, preload=[5, 6])
    a = np.deg2rad([90, 210, 330])
    P = 10 * np.c_[np.cos(a), np.sin(a)]
    tri = grasp_stability(P, P / 10, 100, [5, 5, 5])
    assert tri.stable and tri.margin == pytest.approx(150)
    k = least_stiffness(P, P / 10, [5, 5, 5], margin=1.0)
    assert k == pytest.approx(1 / 1.5, rel=1e-8)
    assert np.linalg.eigvalsh(grasp_stiffness(P, P / 10, k, [5, 5, 5]))[0] >= 1 - 1e-7


def test_plans_of_the_demo_are_reported_with_a_reason():
    """The best frictionless plans of the built-in parts, fingers at their
    representative contacts with balancing preloads: a verdict and a reason each."""
    part = fc.read_part("demo:quad")
    best = fc.plan(part, fingers=4, top=1)[0]
    n = part.normals[list(best.edges)]
    W = np.c_[-n, -(best.contacts[:, 0] * n[:, 1] - best.contacts[:, 1] * n[:, 0])].T
    res = linprog(np.ones(4), A_eq=W, b_eq=np.zeros(3), bounds=[(1.0, None)] * 4,
                  method="highs")
    assert res.status == 0
    st = grasp_stability(best.contacts, n, 100.0, res.x, about=part.centroid)
    assert st.reason.split(":")[0] in ("stable", "neutral", "unstable")
    assert st.stable == bool(st.margin > 0)


def test_stability_errors_name_the_argument():
    with pytest.raises(ValueError, match="stiffness"):
        grasp_stiffness([[0, 0], [1, 0]], [[-1, 0], [1, 0]], -1.0, 1.0)
    with pytest.raises(ValueError, match="preload"):
        grasp_stiffness([[0, 0], [1, 0]], [[-1, 0], [1, 0]], 1.0, [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="normals"):
        grasp_stiffness([[0, 0], [1, 0]], [[0, 0], [1, 0]], 1.0, 1.0)
    with pytest.raises(ValueError, match="about"):
        grasp_stiffness([[0, 0], [1, 0]], [[-1, 0], [1, 0]], 1.0, 1.0, about=[1, 2, 3])
