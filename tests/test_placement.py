"""Placement errors: the probability that a two-finger plan holds under Gaussian errors
along the boundary (fcgrasp.model.robustness): the exact integral over the force-closure
polygons of the edge pairs against a Monte Carlo estimate of 250,000 landings (a million
under ``-m slow``) decided
by ``friction_pair_closure`` (theorem 6.3 as the library's batch test states it; no code
shared with the polygons), within 4.5 standard errors."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.model.robustness import placement_probability

from .shapes import random_polygon


def _landings(part, edge, point, s):
    """Where fingers land at boundary offsets ``s`` from ``point`` (on ``edge``),
    walking the ring edge by edge (NaN beyond one turn either way)."""
    ring = np.flatnonzero(part.rings == part.rings[edge])
    L = part.lengths[ring]
    pos = int(np.flatnonzero(ring == edge)[0])
    P = np.full((len(s), 2), np.nan)
    N = np.full((len(s), 2), np.nan)
    start = float(np.hypot(*(point - part.starts[edge])))
    for direction in (1, -1):
        acc, j = -start, pos
        for _ in range(len(ring) + 1):
            if direction < 0:
                j = (j - 1) % len(ring)
                acc -= L[j]
            lo, hi = acc, acc + L[j]
            m = (s >= lo) & (s < hi) & np.isnan(P[:, 0])
            e = ring[j]
            P[m] = part.starts[e] + (s[m] - lo)[:, None] * part.tangents[e]
            N[m] = part.normals[e]
            if direction > 0:
                acc += L[j]
                j = (j + 1) % len(ring)
    return P, N


def _monte_carlo(part, plan, sigma, mu, n, rng):
    lands = [_landings(part, int(e), np.asarray(c, float), rng.normal(0, sigma, n))
             for e, c in zip(plan.edges, plan.contacts, strict=True)]
    (P, NP), (Q, NQ) = lands
    ok = np.isfinite(P[:, 0]) & np.isfinite(Q[:, 0])
    held = np.zeros(n, bool)
    held[ok] = fc.friction_pair_closure(P[ok], NP[ok], Q[ok], NQ[ok], mu)
    return held.mean()


@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow),
                                  pytest.param(2, marks=pytest.mark.slow)])
def test_placement_probability_matches_the_landings(seed):
    rng = np.random.default_rng(seed)
    parts = [fc.read_part("demo:quad")]
    if seed:                                  # the others with -m slow
        parts += [random_polygon(rng, "star"), fc.read_part("demo:blob")]
    checked = 0
    for part in parts:
        mu = float(rng.uniform(0.15, 0.5))
        for plan in fc.plan(part, fingers=2, mu=mu, top=2, along_boundary=False):
            sigma = float(rng.uniform(0.3, 2.0)) * float(min(plan.lengths))
            per = part.lengths[part.rings == part.rings[plan.edges[0]]].sum()
            sigma = min(sigma, per / 20)
            exact = placement_probability(part, plan, sigma)
            n = 250_000 if seed == 0 else 1_000_000
            mc = _monte_carlo(part, plan, sigma, mu, n, rng)
            se = max(np.sqrt(mc * (1 - mc) / n), 1 / n)
            assert abs(exact - mc) <= 4.5 * se + 1e-9, (exact, mc, se)
            checked += 1
    assert checked >= 2


def test_friction_range_is_the_average_over_mu():
    """With ``mu_range`` the probability is the mean over friction uniform in it: the
    composite Simpson average of the probabilities at fixed friction."""
    part = fc.read_part("demo:quad")
    plan = fc.plan(part, fingers=2, mu=0.3, top=1, along_boundary=False)[0]
    sigma = float(min(plan.lengths))
    mid = placement_probability(part, plan, sigma, (0.2, 0.6))
    grid = np.linspace(0.2, 0.6, 41)
    at = np.array([placement_probability(part, plan, sigma, mu=m) for m in grid])
    simpson = (at[0] + at[-1] + 4 * at[1:-1:2].sum() + 2 * at[2:-1:2].sum()) / (3 * 40)
    assert at.min() <= mid <= at.max()
    assert mid == pytest.approx(simpson, abs=2e-3)


def test_robustness_errors_name_the_argument():
    part = fc.read_part("demo:quad")
    plan = fc.plan(part, fingers=2, mu=0.3, top=1)[0]
    with pytest.raises(ValueError, match="placement_sigma"):
        placement_probability(part, plan, -1.0)
    with pytest.raises(ValueError, match="placement_sigma"):
        placement_probability(part, plan, 1e6)
    with pytest.raises(ValueError, match="mu_range"):
        placement_probability(part, plan, 1.0, (0.5, 0.2))
    four = fc.plan(part, fingers=4, top=1)[0]
    with pytest.raises(ValueError, match="two-finger"):
        placement_probability(part, four, 1.0)


def test_plan_document_reports_the_probability():
    from fcgrasp.errors import RequestError
    from fcgrasp.planning import PlanRequest, plan_document

    doc = plan_document(PlanRequest(part="demo:quad", mu=0.3, top=2, placement_sigma=2.0))
    part = fc.read_part("demo:quad")
    assert doc.report["parameters"]["placement_sigma"] == 2.0
    for plan, g in zip(doc.plans, doc.report["grasps"], strict=True):
        assert g["probability"] == pytest.approx(placement_probability(part, plan, 2.0))
    with pytest.raises(RequestError, match="two fingers"):
        PlanRequest(part="demo:quad", fingers=4, placement_sigma=2.0)
