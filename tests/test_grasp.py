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
