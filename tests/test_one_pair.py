"""One edge pair in plain floats (``independent_regions`` on two edges) against
the batched pipeline it replaced, kept as the reference (candidates -> solve -> rank on
the two edges): the same plan on thousands of seeded pairs, exactly parallel and
near-degenerate ones included (region ends to 1e-9 of the part's size).  Against an
independent formulation: ``tests/test_regions.py`` compares the lengths with the LP of
``tests/oracle.py`` and every corner grasp with the closure test."""

from __future__ import annotations

import math

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.grippers.fingers import _in_order, point_fingers
from fcgrasp.model import one_pair
from fcgrasp.pipeline import plan_spec
from tests.oracle import closure_margin_lp, grasp_wrenches
from tests.shapes import parallel_polygon, random_polygon


def _reference(poly, idx, mu, margin):
    """The batched pipeline on the two edges (what ``independent_regions`` ran before)."""
    spec = plan_spec(fingers=2, mu=mu, top=1, margin=margin)
    plans = point_fingers(2, mu=mu).search_edges(poly, spec, list(idx))
    return _in_order(plans[0], list(idx)) if plans else None


#: Regions shorter than this (relative to the part) lie in a sector opened by a hair
#: (the margin within 1e-9 of its width): the optimal face of the placement is then a
#: sliver thinner than the placement's own tolerance (FACE_TOL of the edge), so where
#: the regions sit along it turns on the last bits of a cosine in either way.  Their
#: lengths still agree; their places are compared only above this.
HAIR = 1e-6


def _same(got, ref, poly):
    size = poly.size
    tol = 1e-9 * size
    if ref is None or got is None:
        # a sector opened by less than rounding: regions of 1e-15 or none at all
        tiny = [p for p in (got, ref) if p is not None and p.min_length < tol]
        assert (got is None or got in tiny) and (ref is None or ref in tiny), (got, ref)
        return False
    assert got.edges == ref.edges and got.mode == ref.mode, (got, ref)
    assert np.allclose(got.lengths, ref.lengths, rtol=0, atol=tol), (got.lengths, ref.lengths)
    if ref.min_length >= HAIR * size:
        for a, b in zip(got.regions, ref.regions, strict=True):
            assert a.shape == b.shape and np.allclose(a, b, rtol=0, atol=tol), (a, b)
        assert np.allclose(got.contacts, ref.contacts, rtol=0, atol=tol)
    for e, region in zip(got.edges, got.regions, strict=True):      # on its edge
        rel = region - poly.starts[e]
        along = rel @ poly.tangents[e]
        assert np.all(np.abs(rel @ poly.normals[e]) <= tol), (e, region)
        assert np.all((along >= -tol) & (along <= poly.lengths[e] + tol)), (e, region)
    assert np.array_equal(got.normals, ref.normals)
    assert (got.mu, got.margin, got.contact_type) == (ref.mu, ref.margin, ref.contact_type)
    assert got.radius == pytest.approx(ref.radius, rel=1e-15)
    return True


def _near_margin(poly, i, j, mu, rng):
    """A margin (degrees) within a hair of the width of the pair's sector: the sector
    shrinks to nothing, or barely opens."""
    c = [math.atan2(-poly.normals[e][1], -poly.normals[e][0]) for e in (i, j)]
    delta = (c[1] + math.pi - c[0] + math.pi) % (2 * math.pi) - math.pi
    half = math.atan(mu) - abs(delta) / 2
    return math.degrees(max(half, 0.0)) * (1 + float(rng.choice([-1e-9, 0.0, 1e-9, 1e-4])))


def _compare(seed, count):
    rng = np.random.default_rng(seed)
    positive = 0
    for n in range(count):
        poly = parallel_polygon(rng) if n % 3 == 0 else random_polygon(rng)
        usable = np.flatnonzero(poly.usable)
        i, j = (int(x) for x in rng.choice(usable, 2, replace=False))
        mu = float(np.exp(rng.uniform(np.log(0.02), np.log(3))))
        kind = n % 4
        margin = (0.0, 0.5, float(rng.uniform(0, 10)), _near_margin(poly, i, j, mu, rng))[kind]
        got = fc.independent_regions(poly, (i, j), mu=mu, margin=margin)
        positive += _same(got, _reference(poly, (i, j), mu, margin), poly)
    assert positive > count // 5, positive     # enough pairs with regions compared


@pytest.fixture(params=["floats", "compiled"])
def way(request, monkeypatch):
    """Each way of :func:`fcgrasp.model.one_pair.pair_regions`: on Python floats, or
    compiled by numba (the same functions); the compiled way must not have fallen back."""
    compiled = request.param == "compiled"
    if compiled:
        pytest.importorskip("numba")
    monkeypatch.setattr(one_pair, "_use_compiled", lambda: compiled)
    yield request.param
    assert not (compiled and one_pair.COMPILED.broken)
    assert one_pair.COMPILED.loaded or not compiled


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                      for s in range(1, 11))])
def test_one_pair_equals_the_pipeline(seed, way):
    _compare(seed, 200 if seed == 0 else 1000)


def test_one_pair_both_ways_agree():
    """The compiled and the float ways of the same functions: the same mode, lengths
    and ends on seeded pairs (numba's libm may differ from Python's in a last bit)."""
    pytest.importorskip("numba")
    rng = np.random.default_rng(11)
    found = 0
    for n in range(300):
        poly = parallel_polygon(rng) if n % 3 == 0 else random_polygon(rng)
        i, j = (int(x) for x in rng.choice(np.flatnonzero(poly.usable), 2, replace=False))
        (ax1, ay1, bx1, by1, nx1, ny1), (ax2, ay2, bx2, by2, nx2, ny2) = (
            poly.edge_floats[i], poly.edge_floats[j])
        args = (ax1, ay1, bx1, by1, ax2, ay2, bx2, by2, math.atan2(-ny1, -nx1),
                math.atan2(-ny2, -nx2), math.atan(float(rng.uniform(0.05, 2))),
                math.radians(float(rng.choice([0.0, 0.5, 3.0]))), 1e-9)
        ok, got = one_pair.COMPILED.run("_pair_core", *args)
        ref = one_pair._plain()(*args)
        assert ok and got[0] == ref[0], (got, ref)
        assert np.allclose(got[1:], ref[1:], rtol=0, atol=1e-9 * poly.size), (got, ref)
        found += ref[0] >= 0
    assert found > 50, found


def test_one_pair_regions_hold_at_every_corner():
    """Independent of both ways: every corner grasp of the regions is force closure by
    the LP of ``tests/oracle.py`` (its own wrenches, HiGHS), strictly."""
    rng = np.random.default_rng(7)
    checked = 0
    while checked < 60:
        poly = random_polygon(rng)
        i, j = (int(x) for x in rng.choice(np.flatnonzero(poly.usable), 2, replace=False))
        mu = float(rng.uniform(0.1, 1.5))
        p = fc.independent_regions(poly, (i, j), mu=mu)
        if p is None:
            continue
        for corner in p.corners():
            normals = poly.normals[[i, j]]
            assert closure_margin_lp(grasp_wrenches(corner, normals, mu)) > 0, (p, corner)
        checked += 1


def test_one_pair_fingers_in_the_order_asked():
    sq = fc.Polygon([[0, 0], [10, 0], [10, 3], [0, 3]])
    a, b = fc.independent_regions(sq, (0, 2), mu=0.3), fc.independent_regions(sq, (2, 0), mu=0.3)
    assert a.edges == (0, 2) and b.edges == (2, 0)
    assert np.array_equal(a.regions[0], b.regions[1]) and np.array_equal(a.contacts[::-1],
                                                                         b.contacts)
    # a zero-length edge, a pair that cannot hold, no friction: no regions
    assert fc.independent_regions(sq, (0, 1), mu=0.3) is None
    assert fc.independent_regions(sq, (0, 2), mu=0.0) is None
    with pytest.raises(ValueError, match="mu"):
        fc.independent_regions(sq, (0, 2), mu=-1)
