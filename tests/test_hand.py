"""The hand model (section 8.2): feasible contacts (the tip's disc, and a finger's body
held in the plane) against a brute-force check with shapely distances, and plans whose
regions stay inside the feasible parts."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import fcgrasp as fc
from fcgrasp import Hand, Polygon, plan

from .grippers import grip
from .shapes import random_polygon

U_PART = Polygon([[0, 0], [4, 0], [4, 3], [2.5, 3], [2.5, 1], [1.5, 1], [1.5, 3], [0, 3]])


def brute_feasible(poly, hand, e, t):
    """Is a contact at arc length t of edge e feasible? (shapely distances)"""
    p = poly.starts[e] + t * poly.tangents[e]
    c = p + hand.finger_radius * poly.normals[e]
    if hand.workspace is not None:
        cx, cy, r = hand.workspace
        if np.hypot(c[0] - cx, c[1] - cy) > r:
            return False
    if hand.finger_radius > 0:
        d = shapely.distance(poly.to_shapely(), shapely.Point(c))
        if d < hand.finger_radius * (1 - 1e-6):
            return False
    if hand.finger_length > 0:          # the body behind the tip, along the normal
        body = shapely.LineString([c, c + hand.finger_length * poly.normals[e]])
        if shapely.distance(poly.to_shapely(), body) < hand.finger_radius * (1 - 1e-6):
            return False
    return True


def _against_brute_force(seed: int) -> tuple[int, int]:
    """Seeded polygons' feasible intervals against the brute-force check: the samples
    checked, and those a tip alone takes that a body rules out."""
    rng = np.random.default_rng(seed)
    checked = by_body = 0
    for _ in range(6):
        poly = random_polygon(rng, str(rng.choice(["star", "holes", "convex"])))
        rho = float(rng.uniform(0.01, 0.2)) * poly.size
        ws = None
        if rng.random() < 0.5:
            c = poly.centroid + rng.normal(size=2) * 0.2 * poly.size
            ws = (float(c[0]), float(c[1]), float(rng.uniform(0.3, 0.8)) * poly.size)
        # half of them held in the plane: a body behind the tip
        body = float(rng.uniform(0.1, 1.0)) * poly.size if rng.random() < 0.5 else 0.0
        hand = Hand(workspace=ws, finger_radius=rho, finger_length=body)
        ivs = hand.feasible_intervals(poly)
        for e in np.flatnonzero(poly.usable):
            for t in np.linspace(0, poly.lengths[e], 41):
                inside = any(a <= t <= b for a, b in ivs[e])
                near = any(min(abs(t - a), abs(t - b)) < 1e-6 * poly.size for a, b in ivs[e])
                if near:
                    continue
                assert inside == brute_feasible(poly, hand, e, t), (e, t, ivs[e])
                checked += 1
                if body and not inside:
                    by_body += brute_feasible(poly, Hand(workspace=ws, finger_radius=rho),
                                              e, t)
    return checked, by_body


@pytest.mark.parametrize("seed", range(4))
def test_feasible_intervals_match_brute_force(seed):
    assert _against_brute_force(seed)[0] > 500


def test_a_body_in_the_plane_rules_out_contacts_the_tip_alone_would_take():
    """Over the seeded polygons, some contacts a tip alone takes are ruled out by the
    finger's body (the brute-force check sees them too: the test can fail)."""
    assert sum(_against_brute_force(s)[1] for s in range(4)) > 10


def test_slot_too_narrow_for_the_finger():
    wide = Hand(finger_radius=0.3).feasible_intervals(U_PART)
    fat = Hand(finger_radius=0.6).feasible_intervals(U_PART)
    assert wide[4] and np.allclose(wide[4], [(0.3, 0.7)], atol=1e-6)   # slot floor
    assert fat[3] == [] and fat[4] == [] and fat[5] == []


def test_plans_stay_in_reach():
    hand = Hand(workspace=(2.0, 1.5, 2.2), finger_radius=0.35)
    ivs = hand.feasible_intervals(U_PART)
    for fingers, mu in ((2, 0.4), (4, 0.0)):
        plans = plan(U_PART, **grip(fingers, mu), hand=hand, top=5)
        assert plans
        for p in plans:
            for e, reg in zip(p.edges, p.regions, strict=True):
                t = (reg - U_PART.starts[e]) @ U_PART.tangents[e]
                assert any(a - 1e-9 <= t.min() and t.max() <= b + 1e-9 for a, b in ivs[e])
            ok = fc.is_force_closure(np.array([p.grasp(g).wrenches for g in p.corners()]))
            assert ok.all()


def test_hand_that_cannot_reach():
    hand = Hand(workspace=(100, 100, 1))
    assert all(iv == [] for iv in hand.feasible_intervals(U_PART))
    assert plan(U_PART, fingers=2, mu=0.5, hand=hand) == []
