"""Friction known only to a range: plans made at its low end hold for every mu
of it, checked by an LP over the contact wrenches (tests/oracle.py, no fcgrasp code) at
grasps sampled in the regions; the best region against mu; the CLI's ``--mu LOW:HIGH``."""

from __future__ import annotations

import json

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.apps.cli import main

from .oracle import closure_margin_lp, grasp_wrenches
from .shapes import random_polygon


def _sampled(rng, plan, n):
    """``n`` grasps with each finger anywhere in its region (ends included)."""
    for _ in range(n):
        pts, nrm = [], []
        for line, sn in zip(plan.regions, plan.segment_normals(), strict=True):
            seg = np.hypot(*np.diff(line, axis=0).T)
            j = int(rng.choice(len(seg), p=seg / seg.sum()))
            u = float(rng.choice([0.0, 1.0, rng.random()]))
            pts.append(line[j] + u * (line[j + 1] - line[j]))
            nrm.append(sn[j])
        yield np.array(pts), np.array(nrm)


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 20))])
def test_plans_at_the_low_end_hold_for_every_mu_of_the_range(seed):
    rng = np.random.default_rng(seed)
    part = random_polygon(rng, "star") if seed else fc.read_part("demo:blob")
    lo, hi = 0.2, 0.6
    curve = fc.friction_curve(part, (lo, hi), points=5)
    assert np.all(np.diff(curve.min_region) >= -1e-9 * part.size)
    checked = 0
    for plan in fc.plan(part, fingers=2, mu=lo, top=3):
        for mu in (lo, 0.5 * (lo + hi), hi):
            for pts, nrm in _sampled(rng, plan, 20):
                assert closure_margin_lp(grasp_wrenches(pts, nrm, mu)) > 0
                checked += 1
    assert checked >= 60
    # the curve's ends are the plans at its ends
    for m, v in ((lo, curve.min_region[0]), (hi, curve.min_region[-1])):
        best = fc.plan(part, fingers=2, mu=m, top=1)
        assert v == pytest.approx(best[0].min_length if best else 0.0)


def test_friction_curve_errors_name_the_argument():
    part = fc.read_part("demo:blob")
    with pytest.raises(ValueError, match="mu_range"):
        fc.friction_curve(part, (0.5, 0.2))
    with pytest.raises(ValueError, match="mu_range"):
        fc.friction_curve(part, 0.5)
    with pytest.raises(ValueError, match="fingers"):
        fc.friction_curve(part, (0.2, 0.5), fingers=4)
    with pytest.raises(ValueError, match="top"):
        fc.friction_curve(part, (0.2, 0.5), top=3)


def test_cli_friction_range(tmp_path, capsys):
    out = tmp_path / "plan.json"
    assert main(["plan", "demo:blob", "--mu", "0.3:0.6", "--top", "2", "--placement-sigma",
                 "0.5", "--json", str(out)]) == 0
    doc = json.loads(out.read_text())
    assert doc["parameters"]["mu_range"] == [0.3, 0.6]
    assert doc["parameters"]["mu"] == 0.3
    curve = doc["friction_curve"]
    assert curve["mu"][0] == 0.3 and curve["mu"][-1] == 0.6
    assert curve["min_region"][0] == pytest.approx(doc["grasps"][0]["min_region_length"])
    assert all(0 <= g["probability"] <= 1 for g in doc["grasps"])
    capsys.readouterr()
    for bad in ("0.3:x", "0.6:0.3", "0.1:0.2:0.3"):
        assert main(["plan", "demo:blob", "--mu", bad]) != 0
        err = capsys.readouterr().err
        assert "--mu" in err and len(err.strip().splitlines()) == 1
