"""Four frictionless fingers on regular polygons: the coupled bound of a row
(:func:`fcgrasp.pipeline._pair_rows.coupled_bounds`) is at least the smallest region the
region solver gives it, every row that reaches a floor is among the pairs of nearly
opposite edges the search then reads (:meth:`PairRows.reaching`, checked against every
row solved), and the search that reads them gives the plans of the search that streams
every row (kept as the reference: the pairs switched off)."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.pipeline import _pair_rows, features, plan_spec
from fcgrasp.pipeline._candidates import EdgeSets, candidates
from fcgrasp.pipeline._pair_rows import PairRows, coupled_bounds, pair_keys
from fcgrasp.pipeline._search import search
from fcgrasp.pipeline._solve import solve

from .shapes import random_polygon


def _ngon(n, jitter=0.0, seed=0, radius=10.0, turn=0.0):
    """A regular ``n``-gon, its vertices' angles and radii jittered (relative)."""
    rng = np.random.default_rng(seed)
    a = turn + np.linspace(0, 2 * np.pi, n, endpoint=False)
    if jitter:
        a = np.sort(a + rng.normal(0, jitter, n))
    r = radius * (1 + (rng.normal(0, jitter, n) if jitter else 0.0))
    return fc.Polygon(np.c_[r * np.cos(a), r * np.sin(a)])


def _annulus(rng, n):
    """A regular ``n``-gon with a hole (a smaller regular polygon, off centre): the
    hole's edges run the other way round."""
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    m = int(rng.integers(4, 13))
    b = np.linspace(0, 2 * np.pi, m, endpoint=False)[::-1]
    r, off = float(rng.uniform(2, 5)), rng.uniform(-2, 2, 2)
    return fc.Polygon(np.c_[10 * np.cos(a), 10 * np.sin(a)],
                      holes=[np.c_[r * np.cos(b), r * np.sin(b)] + off])


def _two_arcs(k, off, turn=0.0, radius=10.0):
    """Two halves of a regular ``2k``-gon, the second's centre moved by ``off``, joined
    by two short edges (``icons/key.svg``: a circle drawn as two arcs whose centres
    differ by about an edge, and a tiny edge between them): no point is the foot of
    every edge's middle, and the short edges' feet are far off them."""
    a = np.linspace(0, np.pi, k + 1)
    up = np.c_[radius * np.cos(a), radius * np.sin(a)]
    down = np.c_[radius * np.cos(a + np.pi), radius * np.sin(a + np.pi)] + np.asarray(off)
    c, s = np.cos(turn), np.sin(turn)
    return fc.Polygon(np.r_[up, down] @ np.array([[c, s], [-s, c]]))


def _random_arcs(rng):
    """:func:`_two_arcs` of 5-17 edges a half, the centres apart by 0.01-1.2 edges
    (the second's moved down, so that the outline stays simple)."""
    k = int(rng.integers(5, 18))
    edge = 2 * 10.0 * np.sin(np.pi / (2 * k))
    angle = float(rng.uniform(np.pi + 0.2, 2 * np.pi - 0.2))    # down: a simple outline
    off = float(rng.choice([0.01, 0.05, 0.3, 0.7, 1.2])) * edge
    return _two_arcs(k, off * np.array([np.cos(angle), np.sin(angle)]),
                     turn=float(rng.uniform(0, 1)))


def _parts(seed):
    """Regular polygons (odd and even, turned), nearly regular ones, random ones,
    regular ones with a hole, and circles of two arcs whose centres differ."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(5, 37))
    if seed % 8 == 5:
        return _annulus(rng, n)
    if seed % 8 == 7:
        return _random_arcs(rng)
    kind = seed % 4
    if kind == 0:
        return _ngon(n, turn=float(rng.uniform(0, 1)), radius=float(rng.uniform(1, 100)))
    if kind == 1:
        return _ngon(n, jitter=float(rng.choice([1e-4, 1e-3, 1e-2])), seed=seed)
    if kind == 2:
        return _ngon(n, jitter=float(rng.choice([0.03, 0.1])), seed=seed)
    return random_polygon(rng)


def _every_row(poly, spec):
    """Every candidate row of the part (the stream, no top) with its solved smallest
    region (0 where it holds nothing)."""
    rows = np.concatenate([b.feats for b in candidates(poly, spec)])
    got = solve(poly, spec, EdgeSets(rows))
    value = np.zeros(len(rows))
    index = {tuple(r): k for k, r in enumerate(rows.tolist())}
    for r, lengths in zip(got.cands.feats.tolist(), got.lengths, strict=True):
        value[index[tuple(r)]] = float(np.min(lengths))
    return rows, value


def _tables(poly, spec):
    pairs = PairRows(poly, spec)
    return pairs, pairs.n, pairs.g, pairs.L


@pytest.mark.parametrize("seed", [*range(8), *(pytest.param(s, marks=pytest.mark.slow)
                                              for s in range(8, 80))])
def test_the_coupled_bound_is_at_least_every_rows_smallest_region(seed):
    """Every row of four edges (the seeded parts' rows, 2,000 at most), solved by the
    region solver (with the margin and theorem 7.1's pairings): its smallest region is
    at most the row's coupled bound; the compiled loop and the same loop in Python give
    the same bounds."""
    poly = _parts(seed)
    spec = plan_spec(fingers=4, top=None, along_boundary=False)
    pairs, n, g, L = _tables(poly, spec)
    rows = np.concatenate([b.feats for b in candidates(poly, spec)])
    rows = rows[np.all(np.diff(np.sort(rows, axis=1), axis=1) > 0, axis=1)]
    rng = np.random.default_rng(seed)
    if len(rows) > 2000:
        rows = rows[rng.choice(len(rows), 2000, replace=False)]
    got = solve(poly, spec, EdgeSets(rows))
    bound = coupled_bounds(n, g, L, got.cands.feats)
    value = got.lengths.min(axis=1)
    assert len(value) > 0
    assert np.all(value <= bound * (1 + 1e-9) + 1e-12 * poly.size), \
        float(np.max(value / bound))
    plain = np.empty(len(rows))
    _pair_rows._bounds_loop(n, g, L, np.ascontiguousarray(rows, np.int64),
                            _pair_rows.RAY_TOL, -1, plain)
    np.testing.assert_allclose(coupled_bounds(n, g, L, rows), plain, rtol=1e-12, atol=0)


@pytest.mark.parametrize("n", [5, 12, 24,
                               *(pytest.param(n, marks=pytest.mark.slow)
                                 for n in (8, 9, 16, 17, 31, 33, 40, 48, 56))])
@pytest.mark.parametrize("jitter", [0.0, 1e-4, 1e-3])
def test_every_row_reaching_a_floor_is_read(n, jitter):
    """Every row of the part (four edges, and three with one doubled) solved: for the
    floors of the 1st, 5th, 10th and 40th best rows and just below them, where the
    pairs answer (:meth:`PairRows.reaching` not None), every row reaching the floor is
    a seed row or among those read, each read once."""
    poly = _ngon(n, jitter=jitter, seed=n)
    spec = plan_spec(fingers=4, top=None, along_boundary=False)
    rows, value = _every_row(poly, spec)
    pairs = PairRows(poly, plan_spec(fingers=4, top=10, along_boundary=False))
    seed = pairs.seed(8)
    answered = 0
    best = np.sort(value)[::-1]
    for k in (1, 5, 10, 40):
        if k > len(best) or best[k - 1] <= 0:
            continue
        for floor in (best[k - 1], best[k - 1] * (1 - 1e-3)):
            got = pairs.reaching(floor)
            if got is None:
                continue
            answered += 1
            read = np.concatenate([seed.feats, got.feats])
            keys = pair_keys(np.sort(read, axis=1), pairs.n.shape[0])
            assert len(np.unique(keys)) == len(keys)
            want = rows[value >= floor]
            assert np.all(np.isin(pair_keys(np.sort(want, axis=1), pairs.n.shape[0]),
                                  keys)), (n, jitter, k)
    if n >= 8 and n % 2 == 0 and jitter <= 1e-4:     # opposite edges: the pairs answer
        assert answered > 0


def _reads_every_row_reaching(pairs, got, rows, bound, floor, share):
    """The rows read at ``floor`` (``got``, and the seed rows): each once, each with a
    bound at the floor, and every row of ``rows`` whose ``bound`` reaches it among them."""
    n = pairs.n.shape[0]
    assert np.all(got.bound >= floor * (1 - 1e-9))
    read = pair_keys(np.concatenate([pairs.seeded, got.feats]), n)
    assert len(np.unique(read)) == len(read)
    want = pair_keys(rows[bound >= floor], n)
    assert np.all(np.isin(want, read)), (share, int(np.sum(~np.isin(want, read))))


# the second half's centre moved by (x, y); at (-0.7, -0.2) the pairs do not answer
ARCS = [(8, (0.0, -0.1)), (12, (0.3, -0.5)), (16, (0.05, -0.02)),
        *(pytest.param(k, off, marks=pytest.mark.slow)
          for k in (9, 14, 17) for off in ((0.0, -0.1), (0.3, -0.5), (0.5, -1.0),
                                           (-0.7, -0.2)))]


@pytest.mark.parametrize(("k", "off"), ARCS)
def test_every_row_of_two_arcs_reaching_a_floor_is_read(k, off):
    """Circles of two arcs whose centres differ (:func:`_two_arcs`): every row solved,
    for the floors of the 1st, 5th, 10th and 40th best rows and just below them, every
    row reaching the floor is a seed row or read, each once; the pairs answer (the best
    rows: two pairs of opposite edges, as far off each other's lines as the centres
    let them, above half an edge)."""
    poly = _two_arcs(k, off, turn=0.2)
    spec = plan_spec(fingers=4, top=None, along_boundary=False)
    rows, value = _every_row(poly, spec)
    pairs = PairRows(poly, plan_spec(fingers=4, top=10, along_boundary=False))
    assert not pairs.hopeless
    seed = pairs.seed(8)
    answered = 0
    best = np.sort(value)[::-1]
    for j in (1, 5, 10, 40):
        for floor in (best[j - 1], best[j - 1] * (1 - 1e-3)):
            got = pairs.reaching(floor)
            if got is None:
                continue
            answered += 1
            read = pair_keys(np.sort(np.concatenate([seed.feats, got.feats]), axis=1),
                             pairs.n.shape[0])
            assert len(np.unique(read)) == len(read)
            want = pair_keys(np.sort(rows[value >= floor], axis=1), pairs.n.shape[0])
            assert np.all(np.isin(want, read)), (k, off, j)
    if off != (-0.7, -0.2):
        assert answered >= 4


@pytest.mark.parametrize(("k", "off"), ARCS)
def test_every_row_of_two_arcs_whose_bound_reaches_a_floor_is_read(k, off):
    """The lemma on two arcs: ``Gamma`` over the edges as long as the floor (a short
    edge's foot may be far off it), one pair carrying each circuit (``t < rho . g``,
    ``t < sigma . (L - g)``): every row of four edges whose bound reaches the floor is
    read, for floors from 0.999 down to 0.7 of that ``Gamma``; each row read once, its
    bound at the floor.  Rows are read only where the floor is above 7/8 of it."""
    import itertools

    poly = _two_arcs(k, off, turn=0.2)
    n = poly.n_edges
    pairs = PairRows(poly, plan_spec(fingers=4, top=10, along_boundary=False))
    pairs.seed(8)
    rows = np.array(list(itertools.combinations(range(n), 4)))
    bound = coupled_bounds(pairs.n, pairs.g, pairs.L, rows)
    long = float(np.sort(pairs.L)[2])       # the shortest of the arcs' edges
    gamma = pairs.gamma_at(long)
    answered = 0
    for share in (0.999, 0.99, 0.97, 0.95, 0.93, 0.9, 0.885, 0.876, 0.8, 0.7):
        floor = share * gamma
        got = pairs.reaching(floor)
        if floor <= long:
            assert (got is None) == (share < 7 / 8)
        if got is None:
            continue
        answered += 1
        _reads_every_row_reaching(pairs, got, rows, bound, floor, share)
    assert answered >= 5


@pytest.mark.parametrize("kind", ["ngon", "arcs", "gravity"])
def test_a_higher_floor_reads_the_rows_a_fresh_reading_would(kind):
    """:meth:`PairRows.reaching` keeps the rows of the lowest floor read, and takes a
    higher floor's among them: for floors up and down (each once more), the rows and
    bounds of a fresh :class:`PairRows` at each floor, in the same order."""
    spec = plan_spec(fingers=4, top=10, along_boundary=False) if kind != "gravity" \
        else plan_spec(fingers=3, gravity=(0.3, -1), top=10, along_boundary=False)
    poly = _two_arcs(12, (0.3, -0.5), turn=0.2) if kind == "arcs" else _ngon(24, turn=0.1)
    pairs = PairRows(poly, spec)
    pairs.seed(8)
    gamma = pairs.gamma_at(float(np.sort(pairs.L)[2]))
    answered = 0
    for share in (0.95, 0.97, 0.999, 0.9, 0.93, 0.99, 0.95, 0.88):
        floor = share * gamma
        fresh = PairRows(poly, spec)
        fresh.seed(8)
        want, got = fresh.reaching(floor), pairs.reaching(floor)
        assert (want is None) == (got is None), share
        if want is None:
            continue
        answered += 1
        np.testing.assert_array_equal(got.feats, want.feats)
        np.testing.assert_array_equal(got.bound, want.bound)
        assert got.ceiling == want.ceiling
    assert answered >= 6


def test_a_circuit_is_bounded_by_its_heavy_pair():
    """The lemma's step to one pair per circuit (:meth:`PairRows._sides`): a positive
    dependency ``rho`` of a nearly opposite pair ``(a, b)`` and a light third force
    ``x`` (``rho_x < eps``) has ``rho . g`` at most the pair's bound ``(g_a + g_b) / 2 +
    eps max(0, max g - min(g_a, g_b))``, and ``rho . (L - g)`` at most its sigma side's,
    for any feet and lengths (2,000 seeded triples; without the light force's share
    most fail)."""
    rng = np.random.default_rng(5)
    pairs = PairRows(_ngon(8), plan_spec(fingers=4, top=10, along_boundary=False))
    checked = 0
    for _ in range(2000):
        t = rng.uniform(0, 2 * np.pi)
        ang = np.array([t, t + np.pi + rng.uniform(-0.3, 0.3), rng.uniform(0, 2 * np.pi)])
        n = np.c_[np.cos(ang), np.sin(ang)]
        w = np.array([n[i, 0] * n[j, 1] - n[i, 1] * n[j, 0] for i, j in ((1, 2), (2, 0), (0, 1))])
        w = w if w.sum() > 0 else -w
        if np.any(w < 0) or w[2] >= 0.25 * w.sum():
            continue
        rho = w / w.sum()
        pairs.g = rng.uniform(-1, 2, 3)
        pairs.L = pairs.g + rng.uniform(0, 3, 3)
        for side, v in ((0, pairs.g), (1, pairs.L - pairs.g)):
            value = float(rho @ v)
            if np.any(pairs.L < value):       # x would not be in a row reaching it
                continue
            got = pairs._sides(np.array([0]), np.array([1]), rho[2] * (1 + 1e-12),
                               value)[side]
            assert got[0], (ang, rho, pairs.g, pairs.L, side)
            checked += 1
    assert checked > 500


@pytest.mark.parametrize("seed", range(40))
def test_a_hopeless_part_has_no_floor_the_pairs_answer(seed):
    """:attr:`PairRows.hopeless`, the quick test before numba: where it holds, no floor
    up to the fourth longest edge (the third with gravity) lets the pairs answer;
    regular polygons and two arcs a little apart are not hopeless."""
    rng = np.random.default_rng(seed)
    poly = [_parts(seed), random_polygon(rng), _random_arcs(rng)][seed % 3]
    for kw in (dict(fingers=4), dict(fingers=3, gravity=(0.2, -1))):
        pairs = PairRows(poly, plan_spec(**kw, top=10, along_boundary=False))
        real = 3 if "gravity" in kw else 4
        if pairs.hopeless and pairs.L.size >= real:
            for floor in np.unique(pairs.L)[::-1]:
                if floor <= np.sort(pairs.L)[-real]:
                    assert pairs.reaching(floor) is None, (seed, kw, floor)
    for poly in (_ngon(int(rng.integers(8, 40))),
                 _two_arcs(int(rng.integers(5, 18)), (0.3, -0.5), turn=0.3)):
        assert not PairRows(poly, plan_spec(fingers=4, top=10,
                                            along_boundary=False)).hopeless


@pytest.mark.parametrize("seed", [*range(3), *(pytest.param(s, marks=pytest.mark.slow)
                                              for s in range(3, 30))])
def test_two_arcs_through_the_pairs_give_the_previous_plans(seed, monkeypatch):
    """``fc.plan`` on circles of two arcs, four frictionless fingers and three with
    gravity, single-edge and by default: with the pairs and with every row streamed,
    the same plans."""
    rng = np.random.default_rng(seed)
    poly = _random_arcs(rng)
    for kw in (dict(fingers=4, along_boundary=False, top=int(rng.integers(1, 13)),
                    distinct=0), dict(fingers=4),
               dict(fingers=3, gravity=GRAVITY[seed % 3], along_boundary=False,
                    top=int(rng.integers(1, 13)), distinct=0)):
        _same_plans(_plans(poly, kw, True, monkeypatch), _plans(poly, kw, False, monkeypatch),
                    poly.size)


@pytest.mark.parametrize("n", [8, 12, 30, 40, *(pytest.param(n, marks=pytest.mark.slow)
                                                 for n in (10, 16, 24, 36, 48))])
@pytest.mark.parametrize("jitter", [0.0, 1e-4, 1e-3, 3e-3])
def test_every_row_whose_coupled_bound_reaches_a_floor_is_read(n, jitter):
    """The lemma itself: every row of four edges whose coupled bound reaches the floor
    is read, for floors from 0.999 down to 0.7 of ``Gamma`` (the pairs answer down to
    7/8 of it, and their width is what the lemma needs: 1.8 times less misses rows
    here: the regular 30-gon).  Each row read is read once, and its bound reaches the
    floor."""
    import itertools

    poly = _ngon(n, jitter=jitter, seed=n)
    pairs = PairRows(poly, plan_spec(fingers=4, top=10, along_boundary=False))
    pairs.seed(8)
    rows = np.array(list(itertools.combinations(range(n), 4)))
    bound = coupled_bounds(pairs.n, pairs.g, pairs.L, rows)
    answered = 0
    for share in (0.999, 0.99, 0.97, 0.95, 0.93, 0.9, 0.885, 0.876, 0.8, 0.7):
        floor = share * pairs.gamma
        got = pairs.reaching(floor)
        if pairs.gamma_at(floor) == pairs.gamma:    # (else fewer edges reach the floor)
            assert (got is None) == (share < 7 / 8)     # eps = 2 (1 - share) < 1/4
        if got is None:
            continue
        answered += 1
        _reads_every_row_reaching(pairs, got, rows, bound, floor, share)
    # (jittered by 3e-3, a foot may fall off its edge: Gamma is then above every edge,
    # and so are the highest floors)
    assert answered >= (6 if jitter < 3e-3 else 3)


_MIN_ROWS = _pair_rows.MIN_ROWS


@pytest.fixture(autouse=True)
def _small_parts_too(monkeypatch):
    """The pairs are tried from millions of rows; here on parts of a few dozen edges."""
    monkeypatch.setattr(_pair_rows, "MIN_ROWS", 0)


def _plans(poly, kw, use_pairs, monkeypatch):
    with monkeypatch.context() as m:
        if not use_pairs:
            m.setattr(PairRows, "applies", staticmethod(lambda *a, **k: False))
        return fc.plan(poly, **kw)


def _same_plans(a, b, size):
    assert [p.edges for p in a] == [p.edges for p in b]
    for p, q in zip(a, b, strict=True):
        np.testing.assert_allclose(p.lengths, q.lengths, rtol=0, atol=1e-9 * size)
        for x, y in zip(p.regions, q.regions, strict=True):
            np.testing.assert_allclose(x, y, rtol=0, atol=1e-9 * size)


@pytest.mark.parametrize("seed", [*range(3), *(pytest.param(s, marks=pytest.mark.slow)
                                              for s in range(3, 60))])
def test_the_search_through_the_pairs_gives_the_previous_plans(seed, monkeypatch):
    """``fc.plan`` of four frictionless fingers, single-edge (a top of 1-12, no
    distinct) and by default (the strict seeds' search, the growth, distinct
    alternatives), with the pairs and with every row streamed (the previous search):
    the same plans, regions to 1e-9 of the part's size.  Regular polygons (the pairs
    answer), nearly regular and random ones (the seed rows, then every other row)."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(5, 49 if seed % 4 == 0 else 37))
    poly = _ngon(n, turn=float(rng.uniform(0, 1))) if seed % 4 in (0, 1) else _parts(seed)
    for kw in (dict(fingers=4, along_boundary=False, top=int(rng.integers(1, 13)),
                    distinct=0), dict(fingers=4)):
        _same_plans(_plans(poly, kw, True, monkeypatch), _plans(poly, kw, False, monkeypatch),
                    poly.size)


@pytest.mark.parametrize("n", [12, 20, 33])
def test_strict_and_floored_searches_through_the_pairs(n, monkeypatch):
    """The search itself, not strict and with a caller's floor, on regular polygons: the
    same plans as the search streaming every row; strict (exact ties kept in the order
    found, which the pairs change: the 33-gon's best rows tie in pairs of mirror
    images), plans of the same region lengths; and the pairs answer each time (no row
    of the whole stream is read)."""
    poly = _ngon(n, turn=0.3)
    spec = plan_spec(fingers=4, top=5, along_boundary=False)
    read = []
    original = _pair_rows.PairRows.reaching

    def reaching(self, floor):
        got = original(self, floor)
        read.append(got is not None)
        return got

    monkeypatch.setattr(_pair_rows.PairRows, "reaching", reaching)
    for kw in (dict(strict=True), dict(strict=False), dict(floor=0.3 * poly.size / n)):
        new = search(poly, spec, **kw)
        with monkeypatch.context() as m:
            m.setattr(PairRows, "applies", staticmethod(lambda *a, **k: False))
            old = search(poly, spec, **kw)
        if kw.get("strict"):
            assert len(new) == len(old)
            for p, q in zip(new, old, strict=True):
                np.testing.assert_allclose(np.sort(p.lengths), np.sort(q.lengths), rtol=0,
                                           atol=1e-9 * poly.size)
        else:
            _same_plans(new, old, poly.size)
    assert read and all(read)


def test_the_pairs_apply_only_to_frictionless_fingers_on_single_edges():
    """Four frictionless fingers or three and gravity, on single edges; where the pairs
    do not apply the search streams every row: along the boundary, without a top,
    ranked by another measure, two fingers."""
    poly = _ngon(12)
    assert PairRows.applies(plan_spec(fingers=4, along_boundary=False), poly)
    with pytest.MonkeyPatch.context() as m:      # by default: millions of rows only
        m.setattr(_pair_rows, "MIN_ROWS", _MIN_ROWS)
        assert not PairRows.applies(plan_spec(fingers=4, along_boundary=False), poly)
        assert PairRows.applies(plan_spec(fingers=4, along_boundary=False), _ngon(120))
    assert PairRows.applies(plan_spec(fingers=3, gravity=(0, -1), along_boundary=False),
                            poly)
    for kw in (dict(fingers=3, gravity=(0, -1)),
               dict(fingers=4), dict(fingers=4, along_boundary=False, top=None),
               dict(fingers=4, along_boundary=False, rank_by="resistance"),
               dict(fingers=2, mu=0.3, along_boundary=False)):
        assert not PairRows.applies(plan_spec(**kw), poly), kw


def test_a_regular_polygon_of_many_edges_is_planned_from_the_pairs():
    """A regular 120-gon (``C(120, 4)`` = 8 million rows, every one tied on the
    stream's bound): the pairs answer after the seed rows, and the best plan is two
    exactly opposite pairs, each region a little under half an edge (the margin)."""
    poly = _ngon(120)
    spec = plan_spec(fingers=4, top=10, along_boundary=False)
    plans = search(poly, spec)
    assert len(plans) == 10
    edge = float(poly.lengths[0])
    best = plans[0]
    e = sorted(best.edges)
    assert {(e[0] + 60) % 120, (e[1] + 60) % 120} == {e[2], e[3]}
    assert 0.49 * edge < min(best.lengths) < 0.5 * edge
    F = features(poly, 0.0, None)
    assert F.lengths.size == 120


GRAVITY = [(0, -1), (0.3, -1), (1, 0.2)]


# 39: a part with a hole, whose edges run the other way round (a bound whose feet were
# read along each edge's own direction fell below a row's region there)
@pytest.mark.parametrize("seed", [*range(6), 39, *(pytest.param(s, marks=pytest.mark.slow)
                                                  for s in range(6, 60) if s != 39)])
def test_the_coupled_bound_of_three_fingers_and_gravity(seed):
    """Three frictionless fingers and gravity (a fixed force at the centroid, the point
    the feet are taken from: its terms vanish): every row's smallest region, solved,
    is at most its coupled bound; seeded parts (some with holes) and gravity
    directions."""
    poly = _parts(seed)
    spec = plan_spec(fingers=3, gravity=GRAVITY[seed % 3], top=None, along_boundary=False)
    pairs = PairRows(poly, spec)
    rows = np.concatenate([b.feats for b in candidates(poly, spec)])
    rows = rows[np.all(np.diff(np.sort(rows[:, :3], axis=1), axis=1) > 0, axis=1)]
    got = solve(poly, spec, EdgeSets(rows))
    feats = got.cands.feats.copy()
    feats[feats < 0] = pairs.fixed
    bound = coupled_bounds(pairs.kn, pairs.kg, pairs.kL, feats, pairs.fixed)
    value = np.where(got.cands.feats >= 0, got.lengths, np.inf).min(axis=1)
    assert len(value) > 0
    assert np.all(value <= bound * (1 + 1e-9) + 1e-12 * poly.size), \
        float(np.max(value / bound))


@pytest.mark.parametrize("n", [12, 30, 41, *(pytest.param(n, marks=pytest.mark.slow)
                                             for n in (8, 16, 24, 40, 60))])
@pytest.mark.parametrize("jitter", [0.0, 1e-3])
def test_every_row_of_gravity_whose_bound_reaches_a_floor_is_read(n, jitter):
    """The lemma with gravity: a row near ``Gamma`` has a force nearly opposite to
    gravity (whichever force the circuits share); every row of three edges whose
    coupled bound reaches the floor is read, floors from 0.999 down to 0.7 of
    ``Gamma``, each once."""
    import itertools

    poly = _ngon(n, jitter=jitter, seed=n)
    for down in GRAVITY:
        pairs = PairRows(poly, plan_spec(fingers=3, gravity=down, top=10,
                                         along_boundary=False))
        pairs.seed(8)
        rows = np.array([[*r, pairs.fixed] for r in itertools.combinations(range(n), 3)])
        bound = coupled_bounds(pairs.kn, pairs.kg, pairs.kL, rows, pairs.fixed)
        for share in (0.999, 0.99, 0.97, 0.95, 0.93, 0.9, 0.876, 0.8, 0.7):
            floor = share * pairs.gamma
            got = pairs.reaching(floor)
            assert (got is None) == (share < 7 / 8)
            if got is None:
                continue
            assert np.all(got.feats[:, 3] == -1)
            feats = np.concatenate([pairs.seeded, got.feats])
            feats[feats < 0] = pairs.fixed
            read = pair_keys(feats, n + 1)
            assert len(np.unique(read)) == len(read)
            want = pair_keys(rows[bound >= floor], n + 1)
            assert np.all(np.isin(want, read)), (down, share)


@pytest.mark.parametrize("seed", [*range(4), *(pytest.param(s, marks=pytest.mark.slow)
                                              for s in range(4, 40))])
def test_three_fingers_and_gravity_through_the_pairs_give_the_previous_plans(
        seed, monkeypatch):
    """``fc.plan`` of three frictionless fingers and gravity, single-edge and by
    default, with the pairs and with every row streamed: the same plans."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(6, 49))
    poly = _ngon(n, turn=float(rng.uniform(0, 1))) if seed % 3 != 2 else _parts(seed)
    down = GRAVITY[seed % 3]
    for kw in (dict(fingers=3, gravity=down, along_boundary=False,
                    top=int(rng.integers(1, 13)), distinct=0),
               dict(fingers=3, gravity=down)):
        _same_plans(_plans(poly, kw, True, monkeypatch), _plans(poly, kw, False, monkeypatch),
                    poly.size)
