"""Pose errors (fcgrasp.pose_probability): the quasi-Monte Carlo estimate of
the probability that a plan holds when the part sits off its pose, against an independent
Monte Carlo (the part moved with numpy and shapely, each finger's approach line cut with
the moved outline by shapely, contacts decided by ``friction_pair_closure``: no code
shared with the estimate's rays in the part's frame); with a placement error alone,
against the exact integral of :func:`fcgrasp.placement_probability`."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import fcgrasp as fc
from fcgrasp.core.closure import friction_pair_closure
from fcgrasp.model.robustness import pose_probability

from .shapes import random_polygon


def _plans(seed, fingers=2):
    """A seeded part without holes and its best plans (mu from the seed)."""
    rng = np.random.default_rng([77, seed, fingers])
    for _ in range(50):
        part = random_polygon(rng, str(rng.choice(["convex", "star", "regular"])))
        mu = float(rng.uniform(0.15, 0.6))
        plans = fc.plan(part, fingers=fingers, mu=mu if fingers != 4 else 0.0, top=2)
        if plans:
            return part, plans, rng
    raise AssertionError("no plan")


def _moved_landings(part, plan, sig, n, rng, standoff):
    """Monte Carlo landings: poses drawn, the outline moved, each finger's approach
    line cut with the moved outline; returns (points, outward normals) per finger,
    NaN where a finger misses or starts inside the material."""
    dx, dy = rng.normal(0, sig[0], n), rng.normal(0, sig[1], n)
    th = rng.normal(0, np.radians(sig[2]), n)
    cen = part.centroid
    v = part.vertices - cen
    c, s = np.cos(th)[:, None], np.sin(th)[:, None]
    moved = np.stack([c * v[:, 0] - s * v[:, 1] + cen[0] + dx[:, None],
                      s * v[:, 0] + c * v[:, 1] + cen[1] + dy[:, None]], axis=-1)
    polys = shapely.polygons(moved)
    out = []
    for x, nrm in zip(plan.contacts, plan.normals, strict=True):
        nrm = np.asarray(nrm) / np.hypot(*nrm)
        start = np.asarray(x) + standoff * nrm
        end = start - (standoff + 4 * part.size) * nrm
        line = shapely.linestrings([start, end])
        cut = shapely.intersection(line, shapely.boundary(polys))
        pts, idx = shapely.get_coordinates(cut, return_index=True)
        P = np.full((n, 2), np.nan)
        N = np.full((n, 2), np.nan)
        dist = np.hypot(*(pts - start).T)
        order = np.lexsort((dist, idx))
        first = order[np.r_[True, idx[order][1:] != idx[order][:-1]]]
        inside = shapely.contains_xy(polys, *start)
        for k in first:
            i = idx[k]
            if inside[i]:
                continue
            # the outward normal of the moved edge nearest the point
            a, b = moved[i], np.roll(moved[i], -1, axis=0)
            t = np.clip(np.einsum("ij,ij->i", pts[k] - a, b - a)
                        / np.einsum("ij,ij->i", b - a, b - a), 0, 1)
            j = int(np.argmin(np.hypot(*(a + t[:, None] * (b - a) - pts[k]).T)))
            e = b[j] - a[j]
            ccw = shapely.Polygon(moved[i]).exterior.is_ccw
            N[i] = np.array([e[1], -e[0]] if ccw else [-e[1], e[0]]) / np.hypot(*e)
            P[i] = pts[k]
        out.append((P, N))
    return out


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 12))])
def test_pose_error_matches_an_independent_monte_carlo(seed):
    part, plans, rng = _plans(seed)
    n = 2000
    for plan in plans:
        scale = part.size * float(rng.uniform(0.01, 0.06))
        sig = (scale, scale * float(rng.uniform(0.3, 1.5)), float(rng.uniform(0.5, 6.0)))
        est = pose_probability(part, plan, sig, samples=4096, seed=seed)
        reach = float(np.max(np.hypot(*(np.asarray(plan.contacts) - part.centroid).T)))
        standoff = 6.0 * (np.hypot(sig[0], sig[1]) + np.radians(sig[2]) * reach)
        (P, NP), (Q, NQ) = _moved_landings(part, plan, sig, n, rng, standoff)
        ok = ~np.isnan(P[:, 0]) & ~np.isnan(Q[:, 0])
        holds = np.zeros(n, bool)
        holds[ok] = friction_pair_closure(P[ok], NP[ok], Q[ok], NQ[ok], plan.mu)
        mc = holds.mean()
        se = np.sqrt(max(mc * (1 - mc), 1 / n) / n)
        assert abs(est.probability - mc) <= 4 * se + est.error + 1e-3, \
            (seed, plan.edges, sig, est, mc, se)


@pytest.mark.parametrize("seed", range(3))
def test_placement_alone_is_the_exact_integral(seed):
    """A vanishing pose error and a placement error: the estimate's interval holds the
    exact probability (fcgrasp.placement_probability)."""
    part, plans, rng = _plans(100 + seed)
    for plan in plans:
        sigma = float(rng.uniform(0.02, 0.05)) * float(part.lengths.sum()) / 2
        exact = fc.placement_probability(part, plan, sigma)
        est = pose_probability(part, plan, 1e-12, placement_sigma=sigma, seed=seed)
        assert abs(est.probability - exact) <= 1.5 * est.error + 1e-3, (seed, est, exact)


def test_more_error_holds_less_often_and_friction_ranges():
    part = fc.read_part("demo:quad")
    best = fc.plan(part, fingers=2, mu=0.2, top=1)[0]
    small = pose_probability(part, best, (0.5, 0.5, 0.5))
    large = pose_probability(part, best, (4.0, 4.0, 6.0))
    assert large.probability + large.error < small.probability - small.error
    low = pose_probability(part, best, (4.0, 4.0, 6.0), mu_range=(0.05, 0.2))
    assert low.probability < large.probability
    assert 0 < large.error < 0.02 and large.samples == 8192 and large.replicas == 16


def test_frictionless_four_fingers_and_three_with_friction():
    """Other grippers' plans: probability one for tiny errors, lower for large ones."""
    part = fc.read_part("demo:quad")
    for kw in (dict(fingers=4), dict(fingers=3, mu=0.4)):
        best = fc.plan(part, top=1, **kw)[0]
        assert pose_probability(part, best, (1e-6, 1e-6, 1e-6)).probability == 1.0
        assert pose_probability(part, best, (6.0, 6.0, 10.0)).probability < 0.99


def test_bad_pose_inputs_name_the_argument():
    part = fc.read_part("demo:quad")
    best = fc.plan(part, fingers=2, mu=0.3, top=1)[0]
    for bad in (-1.0, (1, 2), (1, -1, 0), (0, 0, 0), (np.nan, 1, 1), 0.0):
        with pytest.raises(ValueError, match="pose_sigma"):
            pose_probability(part, best, bad)
    with pytest.raises(TypeError, match="plan"):
        pose_probability(part, "best", 1.0)
    with pytest.raises(ValueError, match="samples"):
        pose_probability(part, best, 1.0, samples=3)
    with pytest.raises(ValueError, match="mu_range"):
        pose_probability(part, best, 1.0, mu_range=(0.5, 0.2))
    tri = fc.read_part("demo:triangle")
    grav = fc.plan(tri, fingers=3, gravity=(0, -1), top=1)[0]
    with pytest.raises(ValueError, match="gravity"):
        pose_probability(tri, grav, 1.0)


def test_cli_pose_sigma(tmp_path, capsys):
    import json

    from fcgrasp.apps.cli import main

    out = tmp_path / "p.json"
    assert main(["plan", "demo:quad", "--mu", "0.2", "--top", "2", "--pose-sigma", "2,2,3",
                 "--json", str(out)]) == 0
    text = capsys.readouterr().out
    assert "pose error x 2, y 2, 3 deg" in text and "+-" in text
    d = json.loads(out.read_text())
    assert d["parameters"]["pose_sigma"] == [2.0, 2.0, 3.0]
    part = fc.read_part("demo:quad")
    for g, p in zip(d["grasps"], fc.plan(part, fingers=2, mu=0.2, top=2), strict=True):
        assert g["pose_probability"] == pose_probability(part, p, (2, 2, 3)).to_dict()
    for bad in (["--pose-sigma", "1,1"], ["--pose-sigma", "1,1,1", "--gripper", "jaw",
                                          "--stroke", "10,60", "--pad", "5"]):
        assert main(["plan", "demo:quad", *bad, "--json", str(tmp_path / "bad.json")]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and "pose" in err[0]
        assert not (tmp_path / "bad.json").exists()


def test_robustness_is_the_exact_integral_or_the_estimate():
    """fc.robustness (the name): two fingers under a placement error alone, the
    exact integral (no samples, no error); with a pose error, pose_probability's
    estimate; with neither, a clear error."""
    part = fc.read_part("demo:quad")
    best = fc.plan(part, fingers=2, mu=0.4, top=1)[0]
    r = fc.robustness(part, best, placement_sigma=1.5, mu_range=(0.3, 0.5))
    assert r.probability == fc.placement_probability(part, best, 1.5, mu_range=(0.3, 0.5))
    assert r.probability < 1 and (r.error, r.samples) == (0.0, 0)
    est = fc.robustness(part, best, pose_sigma=(2.0, 2.0, 3.0), placement_sigma=0.5, seed=3)
    assert est == pose_probability(part, best, (2.0, 2.0, 3.0), placement_sigma=0.5, seed=3)
    with pytest.raises(ValueError, match="placement_sigma"):
        fc.robustness(part, best)
