"""Grasp stability with fingers as springs (fcgrasp.model.stability): the
stiffness matrix against central differences of the potential energy computed from the
moved part (the edge's line moved rigidly, the fingertips fixed), on seeded random
grasps in equilibrium; the classic cases by hand."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.model.stability import grasp_stability, grasp_stiffness, least_stiffness

from ._highs import linprog


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


# ------------------------------------------------------------------ plans

def test_two_finger_preload_is_the_squeeze_along_the_chord():
    """Two fingers can only balance along the line between them: f_i = lam cos(a_i),
    with lam fixed by the total (closed form, no program) on seeded random plans."""
    from fcgrasp.model.stability import squeeze_preload

    from .shapes import random_polygon

    rng = np.random.default_rng(31)
    checked = 0
    while checked < 40:
        part = random_polygon(rng, "convex")
        for p in fc.plan(part, fingers=2, mu=float(rng.uniform(0.2, 0.8)), top=2):
            P, Q = p.contacts
            d = (Q - P) / np.hypot(*(Q - P))
            cos = np.array([d @ -p.normals[0], -d @ -p.normals[1]])
            total = float(rng.uniform(1, 50))
            f, g = squeeze_preload(p.contacts, p.normals, p.mu, total, part.centroid)
            assert np.allclose(f, total * cos / cos.sum(), rtol=1e-7)
            sin = np.sqrt(np.maximum(1 - cos ** 2, 0))
            assert np.allclose(np.abs(g), total * sin / cos.sum(), rtol=1e-6, atol=1e-9)
            checked += 1


def _hessian(points, normals, k_n, k_t, f, g):
    """The energy's Hessian at rest (about the origin) by central differences."""
    k = len(points)
    args = (points, normals, np.full(k, k_n), f, np.full(k, k_t), g, np.zeros(k))
    h = 1e-4
    E = np.eye(3) * h
    return np.array([[(_energy(E[a] + E[b], *args) - _energy(E[a] - E[b], *args)
                       - _energy(-E[a] + E[b], *args) + _energy(-E[a] - E[b], *args))
                      / (4 * h * h) for b in range(3)] for a in range(3)])


@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow)])
def test_plan_stability_is_the_energy_at_every_corner(seed):
    """For plans of every point gripper: the preload balances, squeezes (every finger
    pushing, inside its cone) and is the most even squeeze an LP over the same forces
    finds; the verdict and the margin are those of the energy's Hessian by central
    differences, at the representative grasp and the smallest over the corners."""
    from fcgrasp.model.stability import plan_stability, squeeze_preload

    from .shapes import random_polygon

    rng = np.random.default_rng(40 + seed)
    done = 0
    while done < 8:
        part = random_polygon(rng, str(rng.choice(["convex", "star", "regular"])))
        fingers = int(rng.choice([2, 3, 4]))
        mu = 0.0 if fingers == 4 else float(rng.uniform(0.2, 0.7))
        plans = fc.plan(part, fingers=fingers, mu=mu, top=1)
        if not plans:
            continue
        p = plans[0]
        k_n, F = float(rng.uniform(50, 500)), float(rng.uniform(2, 20))
        st = plan_stability(part, p, stiffness=k_n, grip_force=F)
        k_t = k_n if mu > 0 else 0.0
        c = part.centroid
        f, g = st.preload, st.tangential_preload
        n = p.normals / np.hypot(*p.normals.T)[:, None]
        u = np.c_[-n[:, 1], n[:, 0]]
        r = p.contacts - c
        force = -(f[:, None] * n).sum(0) + (g[:, None] * u).sum(0)
        torque = np.sum(-f * (r[:, 0] * n[:, 1] - r[:, 1] * n[:, 0])
                        + g * (r[:, 0] * u[:, 1] - r[:, 1] * u[:, 0]))
        assert np.hypot(*force) <= 1e-9 * F and abs(torque) <= 1e-9 * F * part.size
        assert f.sum() == pytest.approx(F) and f.min() > 0
        assert np.all(np.abs(g) <= mu * f + 1e-9 * F)
        # the most even squeeze: maximise min f by an LP written here
        k = len(f)
        W = np.c_[np.r_[-n[:, 0], u[:, 0]], np.r_[-n[:, 1], u[:, 1]],
                  np.r_[-(r[:, 0] * n[:, 1] - r[:, 1] * n[:, 0]),
                        r[:, 0] * u[:, 1] - r[:, 1] * u[:, 0]] / part.size].T
        A_eq = np.vstack([np.c_[W, np.zeros(3)], np.r_[np.ones(k), np.zeros(k), 0]])
        A_ub = np.vstack([np.c_[-np.eye(k), np.zeros((k, k)), np.ones(k)],
                          np.c_[-mu * np.eye(k), np.eye(k), np.zeros(k)],
                          np.c_[-mu * np.eye(k), -np.eye(k), np.zeros(k)]])
        ref = linprog(np.r_[np.zeros(2 * k), -1.0], A_ub=A_ub, b_ub=np.zeros(3 * k),
                      A_eq=A_eq, b_eq=np.r_[np.zeros(3), F],
                      bounds=[(None, None)] * (2 * k + 1), method="highs-ipm")
        assert f.min() == pytest.approx(-ref.fun, rel=1e-6)
        # the Hessian of the energy about the centroid, by central differences
        lam = np.linalg.eigvalsh(_hessian(p.contacts - c, n, k_n, k_t, f, g))
        scale = np.abs(lam).max()
        assert st.margin == pytest.approx(lam[0], abs=1e-5 * scale)
        assert st.stable == bool(lam[0] > 1e-6 * scale) or abs(lam[0]) <= 1e-4 * scale
        worst = np.inf
        for corner in p.corners():
            nc = p.normals_at(corner)
            fc_, gc = squeeze_preload(corner, nc, mu, F, c)
            worst = min(worst, np.linalg.eigvalsh(_hessian(corner - c, nc, k_n, k_t, fc_,
                                                           gc))[0])
        assert st.corners_margin == pytest.approx(worst, abs=1e-5 * scale)
        done += 1


def test_plan_stability_refuses_what_it_cannot_judge():
    from fcgrasp.model.stability import plan_stability

    part = fc.read_part("demo:quad")
    best = fc.plan(part, fingers=2, mu=0.3, top=1)[0]
    for bad in (0, -1, "x"):
        with pytest.raises((ValueError, TypeError), match="stiffness"):
            plan_stability(part, best, stiffness=bad)
    with pytest.raises(ValueError, match="grip_force"):
        plan_stability(part, best, stiffness=10, grip_force=0)
    with pytest.raises(TypeError, match="plan"):
        plan_stability(part, None, stiffness=10)
    tri = fc.read_part("demo:triangle")
    grav = fc.plan(tri, fingers=3, gravity=(0, -1), top=1)[0]
    with pytest.raises(ValueError, match="gravity"):
        plan_stability(tri, grav, stiffness=10)
    from fcgrasp.model.stability import squeeze_preload

    with pytest.raises(ValueError, match="not force closure"):     # two frictionless tips
        squeeze_preload([[0, 0], [10, 1]], [[-1, 0], [1, 0]], 0.0)


def test_cli_reports_each_plans_stability(tmp_path, capsys):
    import json

    from fcgrasp.apps.cli import main
    from fcgrasp.model.stability import plan_stability

    out = tmp_path / "s.json"
    assert main(["plan", "demo:quad", "--mu", "0.3", "--top", "2", "--stiffness", "200",
                 "--grip-force", "20", "--json", str(out)]) == 0
    assert "finger springs 200 N per mm, squeezing with 20 N" in capsys.readouterr().out
    d = json.loads(out.read_text())
    assert d["parameters"]["stiffness"] == 200 and d["parameters"]["grip_force_n"] == 20
    part = fc.read_part("demo:quad")
    for g, p in zip(d["grasps"], fc.plan(part, fingers=2, mu=0.3, top=2), strict=True):
        assert g["stability"] == plan_stability(part, p, 200, grip_force=20).to_dict()
    for bad in (["--grip-force", "5"], ["--stiffness", "-1"],
                ["--stiffness", "5", "--gripper", "jaw", "--stroke", "10,60", "--pad", "5"]):
        assert main(["plan", "demo:quad", *bad, "--json", str(tmp_path / "bad.json")]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and ("stiffness" in err[0] or "grip-force" in err[0])
        assert not (tmp_path / "bad.json").exists()
