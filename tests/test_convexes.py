"""Convexes (section 2.3): lemma 2.1 as properties of random cones, and checks of the
cone algebra against independent linear programs (scipy's HiGHS)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import fcgrasp as fc
from fcgrasp.core.convexes import halfspace_rays

from ._highs import linprog
from .conftest import lp_is_total

SETTINGS = settings(max_examples=60, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])


def random_generators(seed: int, dim: int, kind: str) -> np.ndarray:
    rng = np.random.default_rng(seed)
    k = int(rng.integers(1, 7 if dim < 6 else 5))
    if kind == "general":
        return rng.normal(size=(k, dim))
    if kind == "low":            # lower-dimensional: generators in a random subspace
        r = int(rng.integers(1, dim))
        basis = rng.normal(size=(r, dim))
        return rng.normal(size=(k, r)) @ basis
    if kind == "lines":          # non-pointed: some generators come with their opposite
        g = rng.normal(size=(k, dim))
        return np.concatenate([g, -g[: int(rng.integers(1, k + 1))]])
    if kind == "total":
        g = rng.normal(size=(dim + 1 + k, dim))
        return np.concatenate([g, -g.sum(axis=0, keepdims=True)])
    raise AssertionError(kind)


SPACE = {2: None, 3: "wrench", 6: "spatial_wrench"}
cones = st.builds(
    lambda seed, dim, kind: fc.Cone(random_generators(seed, dim, kind), SPACE[dim]),
    st.integers(0, 2**32 - 1), st.sampled_from([2, 3, 3, 6]),
    st.sampled_from(["general", "low", "lines", "total"]))


def pair_of_cones():
    return st.integers(0, 2**32 - 1).flatmap(lambda seed: st.tuples(
        st.sampled_from(["general", "low", "lines", "total"]),
        st.sampled_from(["general", "low", "lines"]),
        st.sampled_from([2, 3, 6])).map(lambda t: (
            fc.Cone(random_generators(seed, t[2], t[0]), SPACE[t[2]]),
            fc.Cone(random_generators(seed + 1, t[2], t[1]), SPACE[t[2]]))))


# ------------------------------------------------------------------ lemma 2.1

@SETTINGS
@given(cones)
def test_lemma_2_1_1_double_dual(c):
    assert c.dual().dual() == c


@SETTINGS
@given(cones)
def test_lemma_2_1_2_dual_maps_wrenches_to_twists(c):
    d = c.dual()
    assert d.space == {None: None, "wrench": "twist",
                       "spatial_wrench": "spatial_twist"}[c.space]
    assert d.dual().space == c.space


@SETTINGS
@given(cones)
def test_lemma_2_1_3_polar_decomposition(c):
    p = c.polar()
    assert (c & p).is_null()
    assert (c + p).is_total()


def test_lemma_2_1_3_literal_dual_form_is_false():
    quadrant = fc.Cone([[1.0, 0.0], [0.0, 1.0]])
    assert quadrant.dual() == quadrant            # self-dual
    assert not (quadrant & quadrant.dual()).is_null()


@SETTINGS
@given(pair_of_cones())
def test_lemma_2_1_4_dual_is_injective(pair):
    c1, c2 = pair
    assert (c1.dual() == c2.dual()) == (c1 == c2)
    # a cone given by another generating set of itself has the same dual
    extra = c1.generators.sum(axis=0, keepdims=True)
    c1b = fc.Cone(np.concatenate([c1.generators, extra]), c1.space)
    assert c1b == c1 and c1b.dual() == c1.dual()


@SETTINGS
@given(pair_of_cones())
def test_lemma_2_1_5_dual_of_intersection(pair):
    c1, c2 = pair
    assert (c1 & c2).dual() == c1.dual() + c2.dual()


@SETTINGS
@given(pair_of_cones())
def test_lemma_2_1_6_dual_of_sum(pair):
    c1, c2 = pair
    assert (c1 + c2).dual() == c1.dual() & c2.dual()


# ------------------------------------------------------------------ against LPs

def lp_contains(gens: np.ndarray, v: np.ndarray) -> bool:
    g = gens / np.linalg.norm(gens, axis=1, keepdims=True)
    res = linprog(np.zeros(len(g)), A_eq=g.T, b_eq=v / np.linalg.norm(v),
                  bounds=[(0, None)] * len(g), method="highs")
    return res.status == 0


@pytest.mark.parametrize("dim", [2, 3, 6])
def test_contains_agrees_with_lp(dim):
    rng = np.random.default_rng(10 + dim)
    checked = 0
    for _ in range(150):
        g = rng.normal(size=(int(rng.integers(1, 8)), dim))
        cone = fc.Cone(g)
        # points inside (positive combinations) and random points
        inside = rng.random(len(g)) @ g
        assert cone.contains(inside)
        v = rng.normal(size=dim)
        assert cone.contains(v) == lp_contains(g, v)
        checked += 1
    assert checked == 150


@pytest.mark.parametrize("dim", [2, 3, 6])
def test_is_total_agrees_with_lp(dim):
    rng = np.random.default_rng(20 + dim)
    seen = {True: 0, False: 0}
    for _ in range(200):
        g = rng.normal(size=(int(rng.integers(1, 2 * dim + 4)), dim))
        ref = lp_is_total(g)
        if ref is None:
            continue
        assert fc.Cone(g).is_total() == ref
        seen[ref] += 1
    assert seen[True] > 20 and seen[False] > 20


@pytest.mark.parametrize("dim", [2, 3, 6])
def test_dual_is_the_set_of_nonnegative_work(dim):
    rng = np.random.default_rng(30 + dim)
    space = SPACE[dim]
    for _ in range(40):
        g = rng.normal(size=(int(rng.integers(1, 7)), dim))
        cone = fc.Cone(g, space)
        dual = cone.dual()
        perm = {None: list(range(dim)), "wrench": [1, 2, 0],
                "spatial_wrench": [3, 4, 5, 0, 1, 2]}[space]
        ys = rng.normal(size=(60, dim))
        work = g @ ys[:, perm].T                                  # (k, 60)
        clear = np.min(np.abs(work), axis=0) > 1e-6
        expect = np.all(work >= 0, axis=0)
        got = dual.contains(ys)
        assert np.array_equal(got[clear], expect[clear])
        for gen in dual.generators:                              # generators are feasible
            assert np.all(g @ gen[perm] >= -1e-9)


def test_minimal_rays_are_extreme():
    rng = np.random.default_rng(40)
    for _ in range(80):
        dim = int(rng.choice([2, 3, 6]))
        g = random_generators(int(rng.integers(2**31)), dim,
                              str(rng.choice(["general", "low", "lines"])))
        cone = fc.Cone(g)
        m = cone.minimal()
        assert m == cone
        assert np.allclose(m.lines @ m.lines.T, np.eye(len(m.lines)), atol=1e-9)
        for i, r in enumerate(m.rays):
            others = np.concatenate([np.delete(m.rays, i, axis=0), m.lines, -m.lines])
            assert len(others) == 0 or not lp_contains(others, r)


def test_non_pointed_cone_lineality():
    c = fc.Cone([[1, 0, 0], [-1, 0, 0], [0, 1, 0]])
    m = c.minimal()
    assert m.lineality_dim == 1 and len(m.rays) == 1
    assert np.allclose(np.abs(m.lines[0]), [1, 0, 0])
    assert np.allclose(m.rays[0], [0, 1, 0])


def test_null_and_total():
    assert fc.Cone(np.zeros((0, 3)), dim=3).is_null()
    assert fc.Cone([[0.0, 0.0, 0.0]]).is_null()
    assert not fc.Cone([[0.0, 0.0, 1.0]]).is_null()
    octa = np.concatenate([np.eye(3), -np.eye(3)])
    assert fc.Cone(octa).is_total()
    assert not fc.Cone(octa[:5]).is_total()
    assert fc.Cone(octa).dual().is_null()


def test_halfspace_rays_of_orthant():
    rays, lines = halfspace_rays(np.eye(3))
    assert lines.shape == (0, 3)
    assert sorted(map(tuple, np.round(rays, 9))) == sorted(map(tuple, np.eye(3)))


def test_operations_check_kinds():
    with pytest.raises(ValueError, match="wrench"):
        fc.Cone([[1.0, 0.0, 0.0]], "wrench") + fc.Cone([[1.0, 0.0, 0.0]], "twist")
    with pytest.raises(TypeError):
        fc.Cone([[1.0, 0.0]]) & [[1.0, 0.0]]
    with pytest.raises(ValueError, match="length 3"):
        fc.Cone([[1.0, 0.0]], "wrench")
    with pytest.raises(ValueError, match="space"):
        fc.Cone([[1.0, 0.0]], "force")
    with pytest.raises(ValueError, match="generators"):
        fc.Cone([[np.nan, 0.0]])
