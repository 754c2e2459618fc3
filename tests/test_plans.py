"""GraspPlan and the keys that order plans (fcgrasp.model.plans)."""

from __future__ import annotations

import numpy as np

import fcgrasp as fc
from fcgrasp.model.plans import geometric_key, leximin_key

PART = fc.read_part("demo:quad")


def test_leximin_key_orders_by_smallest_then_next():
    better = leximin_key(np.array([2.0, 5.0]), 10.0)
    worse = leximin_key(np.array([4.0, 2.0]), 10.0)     # same smallest, smaller next
    assert better < worse
    assert leximin_key(np.array([3.0, 1.0]), 10.0) > better


def test_geometric_key_ignores_order_of_regions_and_ends():
    r = np.array([[[0, 0], [1, 0]], [[5, 5], [5, 6]]], float)
    flipped = r[::-1, ::-1]
    assert geometric_key(r, PART) == geometric_key(flipped, PART)


def test_samples_and_corners_lie_in_the_regions(rng):
    p = fc.plan(PART, fingers=4, top=1)[0]
    s = p.sample(50, rng)
    assert s.shape == (50, 4, 2) and p.corners().shape == (16, 4, 2)
    for k in range(4):
        a, b = p.regions[k]
        d = b - a
        t = (s[:, k] - a) @ d / (d @ d)
        assert np.all((t >= -1e-12) & (t <= 1 + 1e-12))
        off = np.abs((s[:, k, 0] - a[0]) * d[1] - (s[:, k, 1] - a[1]) * d[0])
        assert np.all(off <= 1e-9 * PART.size * np.hypot(*d))


def test_to_dict_is_json_ready():
    import json

    d = fc.plan(PART, fingers=4, top=1)[0].to_dict()
    assert json.loads(json.dumps(d)) == d and d["contact_type"] == "frictionless"
