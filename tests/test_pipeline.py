"""The public pipeline: candidates -> solve -> rank gives plan()'s answer, in
any batch size, with batches pickled and solved in other processes."""

from __future__ import annotations

import pickle
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.pipeline import EdgeSets, PlanSpec, candidates, plan_spec, rank, solve

from .grippers import grip
from .shapes import random_polygon

JOBS = [dict(fingers=2, mu=0.4), dict(fingers=4, mu=0.0),
        dict(fingers=3, mu=0.0, gravity=(0.0, -1.0)),
        dict(fingers=2, mu=0.4, rank_by="epsilon"), dict(fingers=4, mu=0.0, top=None)]


def _key(plans):
    return [(p.edges, np.round(p.ends, 9).tolist(), p.mode) for p in plans]


def _solve_remote(args):
    part_pickle, spec, batch = args
    return solve(pickle.loads(part_pickle), spec, batch)


@pytest.mark.parametrize("job", JOBS)
@pytest.mark.parametrize("batch_size", [1, 7, 1000])
def test_batches_give_the_plan(job, batch_size, rng):
    part = random_polygon(rng, "star")
    spec = plan_spec(top=job.get("top", 4), rank_by=job.get("rank_by", "min_region"),
                     fingers=job["fingers"], mu=job["mu"], gravity=job.get("gravity"))
    want = fc.plan(part, fingers=job["fingers"], mu=job["mu"], gravity=job.get("gravity"),
                   top=spec.top,
                   rank_by=spec.rank_by, along_boundary=False)
    batches = list(candidates(part, spec, batch_size=batch_size))
    assert all(len(b.feats) <= batch_size for b in batches)
    got = rank(part, spec, (solve(part, spec, b) for b in batches))
    assert _key(got) == _key(want)


def test_batches_solved_in_other_processes():
    part = fc.read_part("demo:blob")
    spec = plan_spec(fingers=4, mu=0.0, top=5)
    batches = [pickle.loads(pickle.dumps(b)) for b in candidates(part, spec, batch_size=5)]
    assert all(isinstance(b, EdgeSets) for b in batches) and len(batches) > 3
    with ProcessPoolExecutor(2) as pool:
        solved = list(pool.map(_solve_remote, [(pickle.dumps(part), spec, b)
                                               for b in batches]))
    solved = [pickle.loads(pickle.dumps(s)) for s in solved]
    assert _key(rank(part, spec, solved)) == _key(fc.plan(part, fingers=4, mu=0, top=5))


def test_candidates_stream_in_bounded_batches():
    ang = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    part = fc.Polygon(np.column_stack([np.cos(ang), np.sin(ang)]))
    spec = plan_spec(fingers=2, mu=0.3)
    sizes = [len(b.feats) for b in candidates(part, spec, batch_size=10_000)]
    assert max(sizes) <= 10_000 and sum(sizes) == 400 * 399 // 2


def test_plan_spec_is_checked_and_picklable():
    spec = plan_spec(fingers=3, gravity=(0, -2))
    assert spec.gravity == (0.0, -1.0) and spec.mu == 0.0
    assert pickle.loads(pickle.dumps(spec)) == spec
    assert isinstance(spec, PlanSpec)
    with pytest.raises(TypeError, match="fingers"):
        plan_spec(fingers="2")
    with pytest.raises(ValueError, match="rank_by"):
        plan_spec(rank_by="nope")
    with pytest.raises(TypeError, match="batch_size"):
        list(candidates(fc.read_part("demo:blob"), spec, batch_size=1.5))


# ------------------------------------------------------------------ memory


@pytest.mark.parametrize("size", [1, 5, 1000])
@pytest.mark.parametrize("shape", ["spiral", "lobe"])
def test_candidates_are_every_combination_once(size, shape):
    """The stream (by decreasing bound) holds every row exactly once, less (three or four
    frictionless fingers) rows whose force directions cannot span the plane."""
    from itertools import combinations

    from fcgrasp.core.closure import force_direction_closure

    a = np.linspace(0, 2 * np.pi, 10, endpoint=False)
    # "lobe": the longest edges all face one way, so whole positions are skipped
    r = 1 + 0.1 * a if shape == "spiral" else 1 + 0.8 * np.exp(-((a - 1) / 0.6) ** 2)
    part = fc.Polygon(np.c_[np.cos(a) * r, np.sin(a) * r])
    n = len(part.lengths)
    force = -part.normals
    want = {2: list(combinations(range(n), 2)),
            3: [(*t, -1) for t in combinations(range(n), 3)],
            4: list(combinations(range(n), 4)) +
            [(t[x], t[y], t[x], t[z]) for t in combinations(range(n), 3)
             for x, y, z in ((0, 1, 2), (1, 0, 2), (2, 0, 1))]}
    skipped = 0
    for fingers, rows in want.items():
        spec = plan_spec(**grip(fingers, 0.3))
        blocks = list(candidates(part, spec, batch_size=size))
        assert all(len(b.feats) <= size for b in blocks)
        got = [tuple(r) for b in blocks for r in b.feats.tolist()]
        assert len(got) == len(set(got)) and set(got) <= set(rows)
        missing = sorted(set(rows) - set(got))
        if fingers == 2:
            assert not missing
        for row in missing:
            dirs = [force[e] if e >= 0 else np.array(spec.gravity) for e in row]
            assert not force_direction_closure(np.array(dirs))
        skipped += len(missing)
    if shape == "lobe":
        assert skipped > 0


def test_search_too_large_is_refused_at_once():
    from fcgrasp.pipeline import SearchTooLarge, check_search, search_size

    a = np.linspace(0, 2 * np.pi, 301)[:-1]
    r = 50 + 8 * np.sin(3 * a) + 5 * np.cos(7 * a)
    big = fc.Polygon(np.c_[r * np.cos(a), r * np.sin(a)])
    spec = plan_spec(fingers=4, top=None)
    size = search_size(big, spec)
    assert not size.fits and size.rows > 3e8
    with pytest.raises(SearchTooLarge, match=r"give a top.*simplify the outline to at most "
                                             r"about \d+ edges"):
        check_search(big, spec)
    with pytest.raises(ValueError, match="memory budget"):       # before any work
        fc.plan(big, fingers=4, top=None)
    # with a top the search streams: batches sized to the budget
    small = plan_spec(fingers=4, top=3, max_memory=2 ** 25)
    s = search_size(big, small)
    assert s.fits and s.peak_bytes + s.kept_bytes <= 2 ** 25
    first = next(candidates(big, small))
    assert len(first.feats) <= s.batch_rows
    with pytest.raises(ValueError, match="max_memory"):
        plan_spec(max_memory=1000)


def test_rank_folds_batches_into_a_running_top(rng):
    from fcgrasp.pipeline import _spec as pipeline  # the search's tunables

    part = random_polygon(rng, "star")
    spec = plan_spec(fingers=4, top=2, max_memory=2 ** 24)
    want = fc.plan(part, fingers=4, top=2)
    batches = [solve(part, spec, b) for b in candidates(part, spec, batch_size=5)]
    old = pipeline.REDUCE_ROWS
    try:
        pipeline.REDUCE_ROWS = 1        # fold after every batch
        got = rank(part, spec, iter(batches))
    finally:
        pipeline.REDUCE_ROWS = old
    assert _key(got) == _key(want)


def test_three_finger_search_stops_early(monkeypatch):
    """The top-k stop ignores gravity's zero-length region (it never stopped before)."""
    from fcgrasp.pipeline import _search as pipeline  # where the search calls solve

    a = np.linspace(0, 2 * np.pi, 41)[:-1]
    r = 50 + 8 * np.sin(3 * a) + 5 * np.cos(7 * a)
    part = fc.Polygon(np.c_[r * np.cos(a), r * np.sin(a)])
    calls, rows = [], []
    real = pipeline.solve

    def counting(polygon, spec, sets, *args, **kw):
        rows.append(int(np.sum(sets.bound >= kw.get("floor", 0.0))))
        return real(polygon, spec, sets, *args, **kw)

    monkeypatch.setattr(pipeline, "solve", counting)
    got = fc.plan(part, fingers=3, gravity=(0, -1), top=2, distinct=0,
                  progress=lambda d, t: calls.append((d, t)), along_boundary=False)
    monkeypatch.undo()
    total = calls[-1][1]
    assert calls[-1][0] == total and sum(rows) < total / 2
    every = fc.plan(part, fingers=3, gravity=(0, -1), top=None, along_boundary=False,
                    distinct=0)
    assert _key(got) == _key(every[:2])


def test_batched_tie_break_equals_the_one_by_one(monkeypatch):
    """Four fingers: the tie-break that places every tied pairing and mode of all rows in
    one batch per option gives the plans of the one that placed them row by row (kept in
    ``tests/previous_break_ties.py``), on seeded parts where options tie: regular
    polygons, exactly parallel edges, random parts."""
    from fcgrasp.pipeline import _solve

    from .previous_break_ties import break_ties
    from .shapes import parallel_polygon

    rng = np.random.default_rng(11)
    parts = [random_polygon(rng, "regular") for _ in range(6)] + \
        [parallel_polygon(rng) for _ in range(6)] + [random_polygon(rng) for _ in range(6)]
    compared = 0
    for poly in parts:
        new = fc.plan(poly, fingers=4, along_boundary=False, top=None)
        with monkeypatch.context() as m:
            m.setattr(_solve, "_break_ties", break_ties)
            old = fc.plan(poly, fingers=4, along_boundary=False, top=None)
        assert [(p.edges, p.mode) for p in new] == [(p.edges, p.mode) for p in old]
        for p, q in zip(new, old, strict=True):
            for a, b in zip(p.regions, q.regions, strict=True):
                assert np.allclose(a, b, rtol=0, atol=1e-12 * poly.size)
        compared += len(new)
    assert compared > 50
