"""Golden plans: the built-in parts and a seeded set of random parts, planned for every
gripper, must give the same JSON reports as when the file was recorded (issue 10: the
pipeline may be restructured, its answers may not change).

Re-record (only when a change of answers is intended and explained in the commit):
``FCGRASP_RECORD_GOLDEN=1 python -m pytest tests/test_golden.py``.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.parts import DEMO_PARTS, demo_part
from fcgrasp.report import dumps, plan_report

from .shapes import random_polygon

GOLDEN = Path(__file__).parent / "golden" / "plans.json"
JOBS = [(2, 0.3, "min_region"), (2, 0.5, "resistance"), (3, 0.0, "min_region"),
        (4, 0.0, "min_region"), (4, 0.0, "epsilon")]


def _parts():
    parts = {f"demo:{name}": demo_part(name) for name in DEMO_PARTS}
    rng = np.random.default_rng(20261123)
    for k in range(8):
        parts[f"random-{k}"] = random_polygon(rng)
    return parts


def _reports():
    out = {}
    for name, poly in _parts().items():
        for fingers, mu, rank_by in JOBS:
            if fingers > 2 and poly.n_edges > 12:
                continue
            plans = fc.plan(poly, fingers=fingers, mu=mu, top=4, rank_by=rank_by)
            params = {"fingers": fingers, "mu": mu, "top": 4, "rank_by": rank_by}
            out[f"{name} {fingers} {mu} {rank_by}"] = json.loads(
                dumps(plan_report(poly, plans, params, "mm")))
    return out


def _close(a, b, path=""):
    """Equal, floats to 1e-10 relative (of the part's size for coordinates near 0)."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and sorted(a) == sorted(b), path
        for k in a:
            if k != "fcgrasp":               # the version string
                _close(a[k], b[k], f"{path}.{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            _close(x, y, f"{path}[{i}]")
    elif isinstance(a, float) or isinstance(b, float):
        assert b == pytest.approx(a, rel=1e-10, abs=1e-10), path
    else:
        assert a == b, path


def test_golden_plans_unchanged():
    got = _reports()
    if os.environ.get("FCGRASP_RECORD_GOLDEN"):
        GOLDEN.parent.mkdir(exist_ok=True)
        GOLDEN.write_text(json.dumps(got, sort_keys=True, indent=1) + "\n")
    want = json.loads(GOLDEN.read_text())
    assert sorted(got) == sorted(want)
    for key in want:
        _close(want[key], got[key], key)
