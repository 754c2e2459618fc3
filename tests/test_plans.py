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


def test_a_plans_contacts_halfway_are_alongs_bit_for_bit():
    """The representative contact of a region (``midpoints``, a plan's few regions, with few
    numpy calls) is :func:`~fcgrasp.core._geom.along` at one half, bit for bit, with
    its segment: seeded polylines of 2-299 points at scales 1e-6 to 1e4 and offsets, with
    repeated points and lines of one repeated point."""
    from fcgrasp.core._geom import _halfway, along, midpoints

    rng = np.random.default_rng(7)
    for _ in range(5000):
        m = int(rng.integers(2, 12) if rng.random() < 0.8 else rng.integers(12, 300))
        line = rng.normal(size=(m, 2)) * 10 ** rng.uniform(-6, 4) \
            + rng.normal(size=2) * 10 ** rng.uniform(-3, 5)
        if rng.random() < 0.3:
            line[int(rng.integers(1, m))] = line[int(rng.integers(0, m))]
        if rng.random() < 0.05:
            line[:] = line[0]
        p, k = along(line, 0.5)
        q, j = _halfway(line)
        assert (q, j) == ((p[0], p[1]), int(k)), line
        pts, edges = midpoints([line], [tuple(range(10, 10 + m - 1))])
        assert pts[0].tolist() == p.tolist() and edges == (10 + int(k),)
