"""No false force closure on parts with exactly parallel edges, margin 0 included.

At ``margin=0`` the returned regions are the closure of force-closure sets: every grasp
strictly inside the box of regions is force closure, and only grasps with a finger at a
region's end may be ties.  With a positive margin the ends hold too.  Every grasp is
judged by the independent LP of ``tests/oracle.py`` (wrenches written without fcgrasp).
"""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.model.regions import DEFAULT_MARGIN_DEG

from .grippers import grip
from .oracle import closure_margin_lp, grasp_wrenches
from .shapes import PARALLEL_KINDS, parallel_polygon

#: an LP margin above this is a clear "force closure"; below -this a clear "no"
LP_BAND = 1e-9
SETTINGS = ((2, 0.2), (2, 0.5), (4, 0.0))
MARGINS = (0.0, 1e-9, DEFAULT_MARGIN_DEG)


def _lp(p, grasps):
    return np.array([closure_margin_lp(grasp_wrenches(g, p.normals_at(g), p.mu))
                     for g in grasps])


def check_part(poly, rng, n_inside=12, settings=SETTINGS):
    """Plan every setting at every margin; return how many grasps the LP judged."""
    judged = 0
    for fingers, mu in settings:
        for margin in MARGINS:
            for p in fc.plan(poly, **grip(fingers, mu), margin=margin, top=3):
                inside = p.sample(n_inside, rng)
                mid = p.contacts[None]
                t_in = _lp(p, np.concatenate([mid, inside]))
                assert np.all(t_in > LP_BAND), (poly, fingers, mu, margin, p.edges,
                                                p.ends.tolist(), t_in.min())
                t_end = _lp(p, p.corners())
                if margin >= DEFAULT_MARGIN_DEG:
                    assert np.all(t_end > LP_BAND), (poly, fingers, margin, p.edges)
                elif margin > 0:
                    # ends within 1e-11 rad of a tie: the LP cannot resolve them, but none
                    # may be clearly outside
                    assert np.all(t_end > -LP_BAND), (poly, fingers, margin, p.edges)
                judged += len(t_in) + len(t_end)
    return judged


@pytest.mark.parametrize("kind", PARALLEL_KINDS)
@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                      for s in range(1, 3))])
def test_parallel_edges_no_false_closure(kind, seed):
    rng = np.random.default_rng([9, seed, PARALLEL_KINDS.index(kind)])
    # by default one setting per part, in turn (every setting on every part: -m slow)
    k = PARALLEL_KINDS.index(kind)
    settings = SETTINGS if seed else SETTINGS[k % 3:k % 3 + 1]
    assert check_part(parallel_polygon(rng, kind), rng, n_inside=5, settings=settings) > 0


@pytest.mark.slow
@pytest.mark.parametrize("kind", PARALLEL_KINDS)
def test_parallel_edges_no_false_closure_exhaustive(kind):
    rng = np.random.default_rng([9, 1000, PARALLEL_KINDS.index(kind)])
    judged = sum(check_part(parallel_polygon(rng, kind), rng, 30) for _ in range(40))
    assert judged > 10_000


def test_margin_zero_parallel_edges_l_shape():
    """The reported case: four frictionless fingers on an L, margin 0."""
    L = fc.Polygon([[0, 0], [60, 0], [60, 15], [15, 15], [15, 50], [0, 50]])
    plans = fc.plan(L, fingers=4, mu=0, margin=0, top=5)
    assert plans
    for p in plans:
        assert p.grasp().is_force_closure(), p.edges
        assert closure_margin_lp(grasp_wrenches(p.contacts, p.normals, 0.0)) > LP_BAND
    tiny = fc.plan(L, fingers=4, mu=0, margin=1e-6, top=5)
    assert plans[0].min_length == pytest.approx(tiny[0].min_length, rel=1e-6)


def test_margin_zero_constant_tie_is_not_closure():
    """Four fingers whose sector test is tight whatever the fingers do: a rectangle with
    two fingers on each long side never holds (forces pair up along two directions only)."""
    R = fc.Polygon([[0, 0], [40, 0], [40, 10], [0, 10]])
    p = fc.independent_regions(R, (0, 0, 2, 3), margin=0)
    if p is not None:
        t = _lp(p, np.concatenate([p.contacts[None], p.sample(20, np.random.default_rng(1))]))
        assert np.all(t > LP_BAND)
