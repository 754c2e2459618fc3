"""Section 6 geometry on arrays (fcgrasp.core.sectors), against direct constructions."""

from __future__ import annotations

import numpy as np
import pytest

from fcgrasp.core.sectors import (
    PAIRINGS,
    arc_intersection,
    line_meet,
    meet_and_velocities,
    pair_arc,
    pairing_sector,
    pairing_valid,
)


def test_line_meet_solves_the_two_lines(rng):
    p1, p2 = rng.normal(size=(2, 500, 2))
    a1, a2 = rng.uniform(0, 2 * np.pi, (2, 500))
    f1 = np.stack([np.cos(a1), np.sin(a1)], -1)
    f2 = np.stack([np.cos(a2), np.sin(a2)], -1)
    keep = np.abs(np.sin(a2 - a1)) > 0.05
    x = line_meet(p1, f1, p2, f2)[keep]
    for xi, q1, g1, q2, g2 in zip(x, p1[keep], f1[keep], p2[keep], f2[keep], strict=True):
        st = np.linalg.solve(np.column_stack([g1, -g2]), q2 - q1)
        np.testing.assert_allclose(xi, q1 + st[0] * g1, atol=1e-9)


def test_meet_velocities_are_derivatives(rng):
    pa, pb, ta, tb = rng.normal(size=(4, 2))
    ta, tb = ta / np.hypot(*ta), tb / np.hypot(*tb)
    fa, fb = np.array([1.0, 0.2]), np.array([-0.3, 1.0])
    x, va, vb = meet_and_velocities(pa, ta, fa, pb, tb, fb)
    h = 1e-6
    np.testing.assert_allclose((line_meet(pa + h * ta, fa, pb, fb) - x) / h, va, atol=1e-5)
    np.testing.assert_allclose((line_meet(pa, fa, pb + h * tb, fb) - x) / h, vb, atol=1e-5)


def test_pair_arc_and_intersection(rng):
    ca, cb = rng.uniform(-np.pi, np.pi, (2, 1000))
    c, h = pair_arc(ca, cb)
    # both directions lie on the arc's ends
    for end in (ca, cb):
        d = (end - c + np.pi) % (2 * np.pi) - np.pi
        np.testing.assert_allclose(np.abs(d), h, atol=1e-12)
    cen, half = arc_intersection(0.0, 0.3, np.pi, 0.3)
    assert half < 0


@pytest.mark.parametrize("order", range(3))
def test_pairing_sector_and_validity(order):
    ang = np.array([np.pi / 2, np.pi, -np.pi / 2, 0.0])      # up, left, down, right
    dirs = np.stack([np.cos(ang), np.sin(ang)], -1)
    valid = pairing_valid(dirs, PAIRINGS[order])
    assert bool(valid) == (order != 1)                           # (up, down) is null
    if valid:
        _, half = pairing_sector(ang, PAIRINGS[order])
        assert half == pytest.approx(np.pi / 4)
