"""Distinct alternatives of three frictionless fingers with gravity and of four fingers:
the rounds of the single-edge search that leave out the rows read and the
rows inside a kept plan's regions (fcgrasp.grippers._boundary.distinct_single_edge_plans,
fcgrasp.grippers._distinct_rows.RowCopies) give the plans of suppression along the
*whole* ranked list (every plan of the part, ``top=None``), on seeded parts where
regions grow along flattened arcs and a grown plan's regions hold dozens of rows."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.grippers import _boundary
from fcgrasp.grippers._distinct_rows import RowCopies
from fcgrasp.model.distinct import distinct_plans, same_alternative
from fcgrasp.pipeline import _search, features, plan_spec, search
from fcgrasp.pipeline._solve import RowScores

from .test_pruning import _flattened


def _part(rng):
    """A flattened-arc part (test_pruning), or a smooth blob of 10 - 18 edges."""
    if rng.random() < 0.6:
        return _flattened(rng)
    n = int(rng.integers(10, 19))
    a = np.sort(rng.uniform(0, 2 * np.pi, n))
    r = 1 + float(rng.uniform(0, 0.3)) * np.cos(int(rng.integers(2, 4)) * a)
    return fc.Polygon(np.c_[float(rng.uniform(20, 40)) * r * np.cos(a),
                            float(rng.uniform(10, 20)) * r * np.sin(a)])


def _case(seed):
    rng = np.random.default_rng(seed)
    part = _part(rng)
    kw = dict(fingers=4) if rng.random() < 0.6 else dict(fingers=3, gravity=(0.0, -1.0))
    fraction = float(rng.choice([0.2, 0.5, 0.8, 0.99]))
    top = int(rng.integers(2, 12))
    return part, kw, fraction, top


def _key(p, size):
    return (tuple(p.edges), p.mode, tuple(np.round(np.sort(p.lengths) / size, 8)))


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                      for s in range(1, 120))])
def test_distinct_rounds_equal_suppression_of_every_plan(seed):
    part, kw, fraction, top = _case(seed)
    every = fc.plan(part, top=None, distinct=0, **kw)
    if not every:
        pytest.skip("no plan")
    # no region as short as suppression's tolerance (a point, RowCopies' one exception)
    assert min(float(np.min(p.lengths)) for p in every) > 1e-9 * part.size
    want = distinct_plans(every, fraction, part.size)[:top]
    got = fc.plan(part, top=top, distinct=fraction, **kw)
    assert [_key(p, part.size) for p in got] == [_key(p, part.size) for p in want]
    for p, q in zip(got, want, strict=True):
        assert set(p.similar) <= set(q.similar)
    # pairwise distinct by the documented rule
    for i, p in enumerate(got):
        for q in got[:i]:
            assert not same_alternative(q, p, fraction, 1e-12 * part.size)


def test_row_scores_remember_what_was_added():
    """The memo of the rows' scores: each row's score as added (the first where a
    row was added twice), nan for a row never added, gravity's -1 a feature like any;
    features beyond its key's 15 bits are not remembered."""
    rng = np.random.default_rng(8)
    memo = RowScores()
    rows = rng.integers(-1, 3000, (5000, 4))
    rows[::7, 3] = -1
    score = rng.uniform(-1, 5, 5000)
    memo.add(rows[:3000], score[:3000])
    memo.add(rows[3000:], score[3000:])
    got = memo.known(rows)
    first = {}
    for r, v in zip(map(tuple, rows), score, strict=True):
        first.setdefault(r, v)
    np.testing.assert_array_equal(got, [first[tuple(r)] for r in rows])
    assert np.isnan(memo.known(rows[:50] + 4000)).all()
    memo.add(np.array([[40000, 1, 2, 3]]), np.array([1.0]))
    assert np.isnan(memo.known(np.array([[40000, 1, 2, 3]]))).all()


@pytest.mark.parametrize("seed", [0, 3, 5, *(pytest.param(s, marks=pytest.mark.slow)
                                            for s in range(6, 40))])
def test_rounds_sharing_their_rows_scores_give_the_plans_of_fresh_rounds(seed,
                                                                          monkeypatch):
    """The distinct search's rounds share the scores of the rows they solve (a row an
    earlier round knows to be below the floor is not solved again): the same plans as
    rounds that remember nothing, and rows were left out so."""
    part, kw, fraction, top = _case(seed)
    dropped = []
    original = _search._reaching

    def reaching(batch, memo, floor, size):
        out = original(batch, memo, floor, size)
        dropped.append(len(batch.feats) - len(out.feats))
        return out

    monkeypatch.setattr(_search, "_reaching", reaching)
    got = fc.plan(part, top=top, distinct=fraction, **kw)

    class Forgetting(RowScores):
        def add(self, feats, score):
            pass

    monkeypatch.setattr(_boundary, "RowScores", Forgetting)
    want = fc.plan(part, top=top, distinct=fraction, **kw)
    assert [_key(p, part.size) for p in got] == [_key(p, part.size) for p in want]
    for p, q in zip(got, want, strict=True):
        assert np.array_equal(np.concatenate(p.regions), np.concatenate(q.regions))
        assert p.similar == q.similar
    assert seed != 0 or sum(dropped) > 0


def _on_region(part, edge, region, tol):
    """Whether 50 points along the edge (its ends included) are within ``tol`` of the
    region's polyline (distance to each of its segments)."""
    a, b = part.starts[edge], part.ends[edge]
    pts = a + np.linspace(0, 1, 50)[:, None] * (b - a)
    line = np.asarray(region, float)
    s0, d = line[:-1], np.diff(line, axis=0)
    dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    t = np.clip(np.einsum("kij,ij->ki", pts[:, None, :] - s0[None], d) / dd, 0, 1)
    q = s0[None] + t[..., None] * d[None]
    return bool(np.all(np.min(np.hypot(*(q - pts[:, None, :]).transpose(2, 0, 1)),
                              axis=1) <= tol))


@pytest.mark.parametrize("n", [24, *(pytest.param(n, marks=pytest.mark.slow)
                                     for n in (28, 32))])
def test_rows_left_out_are_the_kept_plans_copies(n):
    """RowCopies leaves out exactly the rows (every set of four edges, and of three
    with one twice) whose edges can be paired one to one with a kept plan's regions,
    each edge on its partner (checked by points along it), on parts where grown plans'
    regions cover many edges; and every feasible row it leaves out, solved, is that
    plan's copy (same_alternative)."""
    from itertools import combinations, permutations

    rng = np.random.default_rng(n)
    t = np.sort(rng.uniform(0, 2 * np.pi, n)) if n == 28 else \
        np.linspace(0, 2 * np.pi, n, endpoint=False)
    part = fc.Polygon(np.c_[40 * np.cos(t), 25 * np.sin(t)])
    kept = [p for p in fc.plan(part, fingers=4, top=3, distinct=0)
            if max(len(e) for e in p.region_edges) > 1]
    assert kept
    tol = 1e-9 * part.size
    F = features(part)
    m = len(F.edge)
    rows = np.array([c for c in combinations(range(m), 4)]
                    + [(a, a, b, c) for a in range(m) for b, c in
                       combinations([x for x in range(m) if x != a], 2)])
    out = RowCopies(part, kept, [], tol)(rows)
    want = np.zeros(len(rows), bool)
    for k in kept:
        on = np.array([[_on_region(part, int(F.edge[f]), r, tol) for r in k.regions]
                       for f in range(m)])
        for perm in permutations(range(4)):
            want |= np.all([on[rows[:, i], perm[i]] for i in range(4)], axis=0)
    assert np.array_equal(out, want)
    hits = int(out.sum())
    every = search(part, plan_spec(fingers=4, top=None, along_boundary=False))
    rows = np.array([[int(np.flatnonzero(F.edge == e)[0]) for e in p.edges]
                     for p in every])
    for p, o in zip(every, RowCopies(part, kept, [], tol)(rows), strict=True):
        assert not o or any(same_alternative(k, p, 0.99, 1e-12 * part.size)
                            for k in kept), p.edges
    assert hits > 40


@pytest.mark.slow
def test_forms_like_part_gets_ten_alternatives_where_the_list_had_one():
    """A ring of flattened arcs where the best plan's regions are grown along eight
    edges each: the ranked list's next hundreds of plans lie inside them; the
    distinct search still finds ten alternatives, pairwise distinct."""
    t = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    part = fc.Polygon(np.c_[40 * np.cos(t), 25 * np.sin(t)])
    ranked = fc.plan(part, fingers=4, top=40, distinct=0)
    assert len(distinct_plans(ranked, 0.5, part.size)) < 10
    got = fc.plan(part, fingers=4, top=10, distinct=0.5)
    assert len(got) == 10
    for i, p in enumerate(got):
        for q in got[:i]:
            assert not same_alternative(q, p, 0.5, 1e-12 * part.size)


def test_rows_read_are_left_out_as_by_their_edge_tuples():
    """The rows a distinct search has read are found by one integer per
    sorted edge tuple (``RowCopies``' whole-array test) exactly where the tuple of the
    row's sorted edges is among those read (the set lookup it replaced): 400 seeded
    batches of four fingers, of three with gravity (-1) and mixed counts, repeated
    edges included."""
    rng = np.random.default_rng(51)
    part = fc.Polygon(np.c_[40 * np.cos(np.linspace(0, 6.2, 30)),
                            25 * np.sin(np.linspace(0, 6.2, 30))])
    m = part.n_edges
    checked = hits = 0
    for t in range(400):
        k = 4 if t % 2 else 3
        rows = rng.integers(0, m, (int(rng.integers(1, 60)), 4))
        if k == 3:
            rows[:, 3] = -1
            if t % 4 == 1:
                rows[rng.integers(0, len(rows)), :] = rng.integers(0, m, 4)
        read = [tuple(sorted(r[r >= 0].tolist())) for r in rows[rng.random(len(rows)) < 0.3]]
        read += [tuple(sorted(rng.integers(0, m, int(rng.integers(2, 5))).tolist()))
                 for _ in range(3)]
        out = RowCopies(part, [], read, 1e-9)(rows)
        real = (rows[0] >= 0).sum()
        want = np.array([(r >= 0).sum() == real and tuple(sorted(r[r >= 0].tolist())) in
                         set(read) for r in rows])
        assert np.array_equal(out, want), t
        checked += len(rows)
        hits += int(want.sum())
    assert hits > 500 and checked > 5000
