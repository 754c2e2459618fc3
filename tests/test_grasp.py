"""Grasp (section 3.2, theorem 6.1): verdict, reason, escape twist and total freedom,
against the independent LP of tests/oracle.py."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc

from .oracle import closure_margin_lp, grasp_wrenches


def test_verdict_agrees_with_the_lp(rng):
    agree = 0
    for _ in range(300):
        k = int(rng.integers(2, 5))
        ang = rng.uniform(0, 2 * np.pi, k)
        pts = np.column_stack([np.cos(ang), np.sin(ang)])
        mu = float(rng.choice([0.0, 0.2, 0.6]))
        contacts = [fc.FrictionPoint(p, p, mu) if mu else fc.FrictionlessPoint(p, p)
                    for p in pts]
        lp = closure_margin_lp(grasp_wrenches(pts, pts, mu))
        if abs(lp) < 1e-6:
            continue                                   # too near a tie to judge
        assert fc.Grasp(contacts).is_force_closure() == (lp > 0)
        agree += 1
    assert agree > 200


def test_explain_names_the_failed_condition_and_an_escape():
    g = fc.Grasp([fc.FrictionlessPoint([0, 0.5], [-1, 0]),
                  fc.FrictionlessPoint([1, 0.5], [1, 0])])
    rep = g.explain()
    assert not rep.force_closure and rep.failed == "force-direction"
    om, vx, vy = rep.escape_twist
    # the escape motion does no negative work against any contact force
    w = g.wrenches
    assert np.all(w[:, 0] * vx + w[:, 1] * vy + w[:, 2] * om >= -1e-9)


def test_force_closure_has_null_total_freedom():
    g = fc.Grasp([fc.FrictionPoint([0, 0.5], [-1, 0], 0.3),
                  fc.FrictionPoint([1, 0.6], [1, 0], 0.3)])
    assert g.is_force_closure()
    free = g.total_freedom()
    assert len(free.rays) == 0 and len(free.lines) == 0


@pytest.mark.parametrize("tol", [-1, float("nan"), "x"])
def test_tol_checked(tol):
    g = fc.Grasp([fc.FrictionlessPoint([0, 0], [1, 0])])
    with pytest.raises((TypeError, ValueError), match="tol"):
        g.is_force_closure(tol=tol)


def _random_grasp(rng):
    """Grasps of one to five contacts of every kind, with degenerate ones on purpose:
    exactly opposite points, collinear contacts, repeated contacts, far offsets."""
    k = int(rng.integers(1, 6))
    kind = rng.integers(0, 4, k)
    off = rng.choice([0.0, 1e3]) * rng.standard_normal(2)
    scale = float(rng.choice([1e-2, 1.0, 1e3]))
    contacts = []
    for j in range(k):
        p = off + scale * rng.uniform(-1, 1, 2)
        n = rng.standard_normal(2)
        if rng.random() < 0.3 and contacts:               # exactly opposite the last one
            n = -contacts[-1][2]
        mu = float(rng.choice([0.1, 0.5, 1.5]))
        contacts.append((kind[j], p, n / np.linalg.norm(n), mu))
    if rng.random() < 0.2:                                 # collinear contact points
        d = rng.standard_normal(2)
        contacts = [(c[0], off + scale * rng.uniform(-1, 1) * d, c[2], c[3]) for c in contacts]
    out = []
    for kd, p, n, mu in contacts:
        t = np.array([-n[1], n[0]]) * scale * 0.1
        out.append([fc.FrictionlessPoint(p, n), fc.FrictionPoint(p, n, mu),
                    fc.FrictionlessEdge(p - t, p + t, n), fc.FrictionEdge(p - t, p + t, n, mu)
                    ][kd])
    return fc.Grasp(out)


@pytest.mark.parametrize("n", [1000, pytest.param(50_000, marks=pytest.mark.slow)])
def test_one_grasp_in_floats_is_the_batched_test(n):
    """``Grasp.is_force_closure`` (plain floats) against the batched general test on the
    same wrenches: 1,000 seeded grasps (50,000 with ``-m slow``)."""
    rng = np.random.default_rng(30)
    counts = {True: 0, False: 0}
    for _ in range(n):
        g = _random_grasp(rng)
        one = g.is_force_closure()
        batch = bool(fc.is_force_closure(g.wrenches))
        assert one == batch
        counts[one] += 1
    assert min(counts.values()) > n // 10      # both verdicts well represented


@pytest.mark.parametrize("scale", [1e-3, 1.0, 1e4])
def test_one_grasp_in_floats_at_the_tolerance(scale):
    """Near the boundary the verdict depends on the frame ``tol`` is measured in: four
    frictionless fingers in two opposite pairs, each pair's lines ``d`` apart (two
    couples of opposite signs: closure iff the arm ``d`` is resolved), with ``d`` from
    far below to far above the resolution, turned and moved at random."""
    rng = np.random.default_rng(int(scale * 7) % 1000)
    seen = set()
    for d in np.geomspace(1e-20, 1e-4, 120):
        ang = rng.uniform(0, 2 * np.pi)
        x = np.array([np.cos(ang), np.sin(ang)])
        y = np.array([-x[1], x[0]])
        c = rng.uniform(-1, 1, 2) * scale
        pts = c + scale * np.array([1, d, -1, 0, d, 1, 0, -1]).reshape(4, 2) @ np.stack([x, y])
        g = fc.Grasp([fc.FrictionlessPoint(p, n) for p, n in zip(pts, [x, -x, y, -y],
                                                                 strict=True)])
        one = g.is_force_closure()
        assert one == bool(fc.is_force_closure(g.wrenches)), d
        seen.add(one)
    assert seen == {True, False}


@pytest.mark.parametrize("mu", [1e6, 1e9, 1e10, 1e16, 1e100])
def test_an_antipodal_grasp_holds_at_any_large_friction(mu):
    """Cones of a huge ``mu`` are built at :data:`~fcgrasp.core.tolerances.MU_CLOSED`
    (their sides are within the tests' tolerance of the tangent above it): the antipodal grasp
    holds, as the closed form of theorem 6.3 says, and two fingers on the same side of
    a square still do not."""
    held = fc.Grasp([fc.FrictionPoint([0, 0.5], [-1, 0], mu),
                     fc.FrictionPoint([1, 0.5], [1, 0], mu)])
    assert held.is_force_closure()
    assert fc.friction_pair_closure([0, 0.5], [-1, 0], [1, 0.5], [1, 0], mu=mu)
    same_side = fc.Grasp([fc.FrictionPoint([0, 0.2], [-1, 0], mu),
                          fc.FrictionPoint([0, 0.8], [-1, 0], mu)])
    assert not same_side.is_force_closure()
