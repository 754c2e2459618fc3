"""Exact branch and bound: the pruned search gives the same top-k as solving
every candidate row, for every gripper and every ranking measure, on the test corpus;
and it does prune."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp import pipeline
from fcgrasp.core import jit
from fcgrasp.pipeline import _search, _spec, candidates, plan_spec, rank, search, solve
from fcgrasp.planning.planner import RANKINGS

from .grippers import grip
from .shapes import parallel_polygon, random_polygon

#: the measures the search itself ranks by ("payload" is fcgrasp.plan's re-ranking of
#: plans found by the smallest region; the pipeline refuses it: tests/test_loads.py)
SEARCHED = tuple(r for r in RANKINGS if r != "payload")

KINDS = ("convex", "star", "holes", "rectangle", "regular")
JOBS = [dict(fingers=2, mu=0.3), dict(fingers=2, mu=0.05), dict(fingers=3, gravity=(0.0, -1.0)),
        dict(fingers=4)]


def _key(plans):
    return [(p.edges, np.round(np.concatenate(p.regions), 9).tolist(), p.mode,
             np.round(p.lengths, 9).tolist()) for p in plans]


def _exhaustive(part, spec):
    """Every candidate row solved (no floor, no early stop), then ranked."""
    return rank(part, spec, (solve(part, spec, b) for b in candidates(part, spec)))


def _curved(rng, n):
    a = np.sort(rng.uniform(0, 2 * np.pi, n))
    r = 50 + rng.uniform(2, 10) * np.sin(3 * a + rng.uniform(0, 6)) + \
        rng.uniform(0, 5) * np.cos(5 * a)
    return fc.Polygon(np.c_[r * np.cos(a), r * np.sin(a)])


def _corpus(seed):
    rng = np.random.default_rng(seed)
    parts = [random_polygon(rng, k) for k in KINDS]
    parts += [parallel_polygon(rng), _curved(rng, int(rng.integers(14, 24)))]
    return parts


def _check(part, job, top, rank_by, hand=None, sizes=(1, 9, 64)):
    """Batches of one row (the floor rises after every row), a few rows, and more.

    With a measure other than ``min_region`` the floor is that of the
    ``KEEP_FOR_MEASURE`` rows the measure orders: made small here so that it prunes."""
    old = _spec.KEEP_FOR_MEASURE
    _spec.KEEP_FOR_MEASURE = 4 if rank_by != "min_region" else old
    try:
        spec = plan_spec(top=top, rank_by=rank_by, hand=hand, **job)
        want = _key(_exhaustive(part, spec))
        for size in sizes if rank_by == "min_region" else sizes[1:]:
            assert _key(search(part, spec, batch_size=size)) == want, size
    finally:
        _spec.KEEP_FOR_MEASURE = old


@pytest.mark.parametrize("rank_by", SEARCHED)
@pytest.mark.parametrize("job", JOBS, ids=lambda j: f"{j['fingers']}f{j.get('mu', '')}")
@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow)])
def test_pruned_top_k_is_the_exhaustive_top_k(seed, job, rank_by):
    # top 1 and top 3 on alternate parts of every other kind (all: -m slow)
    for i, part in enumerate(_corpus(seed)[::2]):
        _check(part, job, (1, 3)[i % 2], rank_by)


@pytest.mark.slow
@pytest.mark.parametrize("rank_by", SEARCHED)
@pytest.mark.parametrize("job", JOBS, ids=lambda j: f"{j['fingers']}f{j.get('mu', '')}")
@pytest.mark.parametrize("seed", range(2, 20))
def test_pruned_top_k_is_the_exhaustive_top_k_slow(seed, job, rank_by):
    for part in _corpus(seed):
        for top in (1, 5):
            _check(part, job, top, rank_by)


@pytest.mark.parametrize("name", ["blob", "triangle", "quad", "bracket", "rectangle",
                                  pytest.param("washer", marks=pytest.mark.slow)])
def test_demo_parts(name):
    part = fc.read_part(f"demo:{name}")
    for job in JOBS:
        _check(part, job, 5, "min_region", sizes=(1, 200) if job["fingers"] == 2
               else (7, 200))
    _check(part, JOBS[0], 3, "resistance")


def test_with_a_hand(rng):
    part = fc.read_part("demo:blob")
    hand = fc.Hand(workspace=(30, 20, 60), finger_radius=2)
    for job in JOBS:
        _check(part, job, 3, "min_region", hand)


def test_ties_at_the_floor_are_all_kept():
    """A regular polygon: every rotation of the best grasp ties, and each is kept."""
    a = np.arange(12) * 2 * np.pi / 12
    part = fc.Polygon(np.c_[np.cos(a), np.sin(a)])
    for job in JOBS:
        spec = plan_spec(top=2, **job)
        got, want = search(part, spec), _exhaustive(part, spec)
        assert _key(got) == _key(want)


def _flattened(rng):
    """A part of flattened arcs and long sides, as curves come out of an SVG or a DXF:
    each arc's edges equal (to float error: a rotation of one chord), so every row on
    them ties on its smallest region, and the rows are told apart by their second one
    (the leximin key of the search's last plan, TopK.key). A rounded rectangle, a D
    (a half disc and its diameter), a stadium or a heart-like cusp; the corners' arcs
    of a few equal edges, sometimes some arcs exactly equal to one another, sometimes
    one chord a hair longer (1e-10 of the size: at the ranking's rounding)."""
    kind = rng.choice(["rounded", "D", "stadium", "cusp"])
    k = int(rng.integers(3, 7))

    def arc(cx, cy, r, a0, a1):
        t = a0 + (a1 - a0) * np.arange(k + 1) / k
        return np.c_[cx + r * np.cos(t), cy + r * np.sin(t)]

    w, h = float(rng.uniform(20, 60)), float(rng.uniform(8, 30))
    r = float(rng.uniform(2, min(w, h) / 2 - 0.5))
    if kind == "rounded":
        pts = np.vstack([arc(w - r, r, r, -np.pi / 2, 0), arc(w - r, h - r, r, 0, np.pi / 2),
                         arc(r, h - r, r, np.pi / 2, np.pi), arc(r, r, r, np.pi, 1.5 * np.pi)])
    elif kind == "D":
        pts = arc(0, 0, h, 0, np.pi)
    elif kind == "stadium":
        pts = np.vstack([arc(w, 0, h, -np.pi / 2, np.pi / 2), arc(0, 0, h, np.pi / 2,
                                                                1.5 * np.pi)])
    else:
        pts = np.vstack([arc(h, 0, h, -np.pi / 4, np.pi), arc(-h, 0, h, 0, 1.25 * np.pi),
                         [[0.0, -2.5 * h]]])
    _, first = np.unique(np.round(pts, 9), axis=0, return_index=True)
    pts = pts[np.sort(first)]
    if rng.random() < 0.3:                      # one vertex moved out by a hair
        j = int(rng.integers(len(pts)))
        pts[j] *= 1 + 1e-10
    return fc.Polygon(pts)


#: A known inexactness, not of the key's pruning (the key applies to min_region only):
#: ranked by resistance with KEEP_FOR_MEASURE at 4, this part's chord a hair longer
#: (1.155810189 against 1.155810186) gives another fourth row kept than solving every
#: row does; not seen with the default KEEP_FOR_MEASURE (seeds 0-10 checked).
_RESISTANCE_NEAR_TIE = pytest.mark.xfail(strict=True, reason="resistance, near tie at the "
                                         "KEEP_FOR_MEASURE-th row (the notes)")


@pytest.mark.parametrize("seed", [0, 1, *(pytest.param(s, marks=pytest.mark.slow) if s != 11
                                        else pytest.param(s, marks=[pytest.mark.slow,
                                                                    _RESISTANCE_NEAR_TIE])
                                        for s in range(2, 60))])
def test_pruned_top_k_on_flattened_arcs_is_the_exhaustive_top_k(seed):
    """Three frictionless fingers with gravity and four: on arcs of equal edges every
    row ties the top's smallest region, and the search leaves out the rows whose
    bounds cannot reach the top's last leximin key (only the long features can hold
    the second region; a curve icon's 75 s became 0.14 s); the same top as solving
    every row, ties included, for several tops and batch sizes, and by another
    measure (which the key does not apply to)."""
    rng = np.random.default_rng(seed)
    part = _flattened(rng)
    for job in JOBS[2:]:
        _check(part, job, int(rng.choice([1, 3, 10])), "min_region", sizes=(1, 64))
    _check(part, JOBS[3], 3, "resistance", sizes=(1, 64))


@pytest.mark.parametrize("gather", [5, *(pytest.param(g, marks=pytest.mark.slow)
                                        for g in (1, 64, 10 ** 9))])
def test_rows_dropped_by_their_forces_and_gathered_give_the_exhaustive_top_k(gather,
                                                                              monkeypatch):
    """Four frictionless fingers and three with gravity, a search drops the
    rows whose forces cannot hold (theorem 4.2, compiled over rows of feature indices)
    before anything else reads them, and, when not strict, solves the rest in groups of
    ``GATHER_ROWS`` across batches (every row alone, a few, more; all at the end under
    ``-m slow``: the floor then stays low and every row is solved): the same
    top as solving every row, on the corpus and on flattened arcs (ties), for batches of
    one row and of 64; a strict search gives the same plans as without the test."""
    calls = []
    original, stream = _search.holding_rows, _search.candidates

    def holding(*args, **kwargs):
        keep = original(*args, **kwargs)
        calls.append(keep is not None and not keep.all())
        return keep

    def candidates_held(*args, **kwargs):     # rows dropped as the stream makes them
        for b in stream(*args, **kwargs):
            calls.append(b.held and b.read > len(b.feats))
            yield b

    monkeypatch.setattr(_search, "holding_rows", holding)
    monkeypatch.setattr(_search, "candidates", candidates_held)
    monkeypatch.setattr(_spec, "GATHER_ROWS", gather)
    rng = np.random.default_rng(77)
    for part in [*_corpus(3)[::2], _flattened(rng), _flattened(rng)]:
        for job in JOBS[2:]:
            monkeypatch.setattr(jit, "started", lambda: True)   # the test applies
            _check(part, job, int(rng.choice([1, 3, 10])), "min_region", sizes=(1, 64))
            spec = plan_spec(top=3, **job)
            strict = _key(search(part, spec, batch_size=16, strict=True))
            monkeypatch.setattr(jit, "started", lambda: False)  # no test: as before
            assert _key(search(part, spec, batch_size=16, strict=True)) == strict
    assert sum(calls) > 20          # rows were dropped


def _median_key(level):
    """A search's running key at the regions ``level`` (over the part's size): a row
    whose shortest feature can at best tie ``level`` is measured against it."""
    key = np.array([level, level])
    return lambda x: key if x <= level + 1e-9 else None


@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow)])
@pytest.mark.parametrize("compiled", [True, False], ids=["loop", "numpy"])
def test_a_held_stream_is_the_stream_less_the_rows_that_fail_the_force_test(seed, compiled,
                                                                            monkeypatch):
    """``candidates(..., held=True)``: batch for batch, the rows of the stream without it
    that pass the force-direction test (holding_rows), with their bounds, the same
    ceilings and how many rows each batch stands for; four fingers (every layout) and
    three with gravity, with and without a key that prunes (the stream's from a
    search's top), by the compiled loop and by numpy's blocks, and streamed again from
    the rows the features keep of the loop's; and it drops rows."""
    from fcgrasp.pipeline import _rows_kernels
    from fcgrasp.pipeline._candidates import features, holding_rows

    monkeypatch.setattr(jit, "started", lambda: True)
    if not compiled:
        monkeypatch.setattr(_rows_kernels, "holding_survivors", lambda *a, **k: None)
    rng = np.random.default_rng(seed)
    dropped = 0
    for part in [*_corpus(seed)[::2], _flattened(rng)]:
        for job in JOBS[2:]:
            spec = plan_spec(top=3, **job)
            # a key a search's top might have: every row's bound against it
            level = float(np.median(part.lengths)) / part.size
            for key in (None, _median_key(level)):
                plain = list(candidates(part, spec, batch_size=40, key=key))
                features(part, spec.mu).made.clear()
                held = list(candidates(part, spec, batch_size=40, key=key, held=True))
                # again, from the rows the features keep of the loop's
                again = list(candidates(part, spec, batch_size=40, key=key, held=True))
                assert len(plain) == len(held) == len(again)
                made = features(part, spec.mu).made
                assert not made if not compiled else \
                    bool(made) or not any(len(p.feats) for p in plain)
                for p, h, g in zip(plain, held, again, strict=True):
                    assert np.array_equal(g.feats, h.feats) and g.read == h.read
                    keep = holding_rows(part, spec, p.feats)
                    assert h.held and not p.held and h.read == len(p.feats)
                    assert np.array_equal(h.feats, p.feats[keep])
                    assert np.array_equal(h.bound, p.bound[keep])
                    assert h.ceiling == p.ceiling
                    dropped += len(p.feats) - len(h.feats)
    assert dropped > 1000


def test_a_row_left_out_by_the_key_is_worse_than_it():
    """lex_survivors against the ranking's own key (leximin_key): 3,000 random bounds
    (lengths drawn from a few values, so that they tie the key, and a hair off them),
    each left-out row's regions drawn under its bounds are strictly worse than the key
    by leximin_key; and a row whose bounds equal the key survives."""
    from fcgrasp.core._geom import leximin_key
    from fcgrasp.pipeline._candidates import lex_survivors

    rng = np.random.default_rng(5)
    size = 40.0
    for _ in range(3000):
        m = int(rng.integers(2, 5))
        vals = rng.choice([1.0, 2.0, 3.5, 7.0], m) * (1 + rng.choice([0, 1e-11, -1e-11, 1e-8],
                                                                    m))
        key_lengths = np.sort(rng.choice([1.0, 2.0, 3.5, 7.0], m))
        key = -np.array(leximin_key(key_lengths, size))
        bounds = np.sort(vals)[None, :]
        assert lex_survivors(np.sort(key_lengths)[None, :], key, size)[0]
        if lex_survivors(bounds, key, size)[0]:
            continue
        for _ in range(5):                       # regions at most their bounds
            regions = bounds[0] * rng.choice([1.0, rng.uniform(0.5, 1)], m)
            assert leximin_key(regions, size) > leximin_key(key_lengths, size)


def test_key_prunes_where_only_the_second_region_tells_rows_apart(monkeypatch):
    """The pruning by the top's last key is used (this fails if TopK.key is never
    read): a rounded rectangle whose corner arcs have many equal edges, four fingers;
    with the key the search solves a fraction of the rows it solves without."""
    a = np.linspace(0, np.pi / 2, 9)
    arcs = [np.c_[cx + 2 * np.cos(a + q), cy + 2 * np.sin(a + q)]
            for (cx, cy), q in zip([(38, 2), (38, 18), (2, 18), (2, 2)],
                                   [-np.pi / 2, 0, np.pi / 2, np.pi], strict=True)]
    part = fc.Polygon(np.vstack(arcs))
    spec = plan_spec(fingers=4, top=3)
    counted = []
    real_solve = _search.solve

    def counting(polygon, spec, sets, *args, **kw):
        counted.append(len(sets.feats))
        return real_solve(polygon, spec, sets, *args, **kw)

    monkeypatch.setattr(_search, "solve", counting)
    # the rows streamed by the compiled generators, as in a process whose numba has
    # started (run alone, before any other test starts it, the search takes the numpy
    # rows, which this count does not describe)
    monkeypatch.setattr(jit, "started", lambda: True)
    got = search(part, spec)
    with_key = sum(counted)
    counted.clear()
    monkeypatch.setattr(_search.TopK, "key", property(lambda self: None))
    assert _key(search(part, spec)) == _key(got)
    assert with_key < 0.1 * sum(counted), (with_key, sum(counted))


@pytest.mark.parametrize("fingers", [2, 3, 4])
def test_the_search_prunes(fingers, monkeypatch):
    """On a finely flattened outline the pruned search solves a small part of the rows
    (this test fails if the floor or the ceiling is never used)."""
    n = {2: 600, 3: 60, 4: 40}[fingers]
    ang = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 1 + 0.3 * np.sin(3 * ang) + 0.1 * np.cos(5 * ang + 1)
    part = fc.Polygon(np.column_stack([r * np.cos(ang), r * np.sin(ang)]) * 50.0)
    spec = plan_spec(**grip(fingers, 0.3), top=3)
    solved_rows = []
    real_solve = _search.solve

    def counting(polygon, spec, sets, *args, **kw):
        out = real_solve(polygon, spec, sets, *args, **kw)
        floor = kw.get("floor", 0.0)
        solved_rows.append(int(np.sum(sets.bound >= floor)))
        return out

    monkeypatch.setattr(_search, "solve", counting)
    got = search(part, spec)
    total = pipeline.search_size(part, spec).rows
    assert sum(solved_rows) < 0.2 * total
    monkeypatch.undo()
    assert _key(got) == _key(_exhaustive(part, spec))


def test_candidates_come_by_decreasing_bound(rng):
    part = random_polygon(rng, "star")
    for job in JOBS:
        spec = plan_spec(top=3, **job)
        batches = list(candidates(part, spec, batch_size=7))
        ceilings = [b.ceiling for b in batches]
        assert ceilings == sorted(ceilings, reverse=True)
        for b, nxt in zip(batches, batches[1:] + [None], strict=True):
            assert np.all(b.bound <= b.ceiling + 1e-12)
            if nxt is not None:
                assert np.all(nxt.bound <= b.ceiling + 1e-12)
        # the bound really bounds: every solved row's smallest region is within it
        for b in batches:
            s = solve(part, plan_spec(top=None, **job), b)
            real = s.cands.feats >= 0
            mins = np.where(real, s.lengths, np.inf).min(axis=1)
            lookup = {tuple(r): x for r, x in zip(b.feats.tolist(), b.bound, strict=True)}
            for row, m in zip(s.cands.feats.tolist(), mins, strict=True):
                assert m <= lookup[tuple(row)] * (1 + 1e-9)


def test_floor_is_checked():
    part = fc.read_part("demo:blob")
    spec = plan_spec(fingers=2, mu=0.3)
    batch = next(candidates(part, spec))
    with pytest.raises(ValueError, match="floor"):
        solve(part, spec, batch, floor=-1.0)
    with pytest.raises(TypeError, match="floor"):
        solve(part, spec, batch, floor="high")


def test_every_plan_streams_every_plan():
    from fcgrasp.pipeline import every_plan

    for part in _corpus(7)[:2]:
        for job in JOBS:
            spec = plan_spec(top=None, **job)
            got = sorted(_key(list(every_plan(part, spec, batch_size=13))))
            assert got == sorted(_key(search(part, spec)))


@pytest.mark.slow      # 13 s
def test_every_plan_memory_is_bounded_by_a_batch():
    """Consuming more plans does not hold more memory (10x the plans, same peak).

    Measured in a fresh interpreter: tracemalloc counts every thread's allocations, and
    in a pytest-xdist worker its messaging thread (and what earlier tests left) can add
    to the peak."""
    import json
    import subprocess
    import sys

    code = """
import itertools, json, tracemalloc
import numpy as np
import fcgrasp as fc
from fcgrasp.pipeline import every_plan, plan_spec
ang = np.linspace(0, 2 * np.pi, 1000, endpoint=False)
part = fc.Polygon(np.c_[np.cos(ang), (1 + 0.2 * np.sin(3 * ang)) * np.sin(ang)])
spec = plan_spec(fingers=2, mu=0.3)
# warm up: the caches a first plan fills (features, imports) are not the stream's
sum(1 for _ in itertools.islice(every_plan(part, spec, batch_size=20), 20))
out = []
for count in (40, 400):
    tracemalloc.start()
    n = sum(1 for _ in itertools.islice(every_plan(part, spec, batch_size=20), count))
    out.append([n, tracemalloc.get_traced_memory()[1]])
    tracemalloc.stop()
print(json.dumps(out))
"""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, r.stderr
    (n0, p0), (n1, p1) = json.loads(r.stdout)
    assert (n0, n1) == (40, 400)
    peaks = [p0, p1]
    assert peaks[1] < 1.5 * peaks[0]


@pytest.mark.parametrize("block", [1, 7, 4096])
def test_candidate_stream_does_not_depend_on_the_combination_blocks(block, monkeypatch):
    """The triples of :func:`~fcgrasp.pipeline._rows._combos` come in
    blocks of several first positions (fewer numpy calls on a flattened curve): every
    increasing triple once, in order, and the candidate stream of four fingers the same
    batches, row for row, as with a block per first position (``COMBO_BLOCK`` 1)."""
    from itertools import combinations

    from fcgrasp.pipeline import _rows

    monkeypatch.setattr(_rows, "COMBO_BLOCK", block)
    for s in (0, 1, 3, 4, 9, 40):
        got = [tuple(r) for b in _rows._combos(s, 3) for r in b.tolist()]
        assert got == list(combinations(range(s), 3))
    part = random_polygon(np.random.default_rng(5), "star")
    for job in ({"fingers": 4}, {"fingers": 3, "gravity": (0, -1)}):
        spec = plan_spec(top=3, **job)
        got = [(b.feats.tolist(), b.ceiling) for b in candidates(part, spec, batch_size=50)]
        monkeypatch.setattr(_rows, "COMBO_BLOCK", 1)
        want = [(b.feats.tolist(), b.ceiling) for b in candidates(part, spec, batch_size=50)]
        monkeypatch.setattr(_rows, "COMBO_BLOCK", block)
        assert got == want and len(got) > 1


def _tied_part(rng):
    """A flattened-curve-like part: arcs of equal edges (every short edge ties) and a few
    long ones, the ties the compiled rows skip over."""
    n = int(rng.integers(12, 40))
    a = np.sort(rng.choice(np.arange(n) * 2 * np.pi / n, size=int(rng.integers(6, n + 1)),
                           replace=False)) + rng.uniform(0, 1)
    return fc.Polygon(np.column_stack([np.cos(a), np.sin(a)]))


@pytest.mark.parametrize("cases", [pytest.param(30, id="seeded"),
                                   pytest.param(2000, id="sweep", marks=pytest.mark.slow)])
def test_compiled_survivor_rows_give_the_numpy_stream(cases, monkeypatch):
    """Once the top is full, the rows of each position that may reach its key
    are found by one compiled loop that skips the tuples a lower one already rules out
    (:func:`fcgrasp.pipeline._rows_kernels.survivors`).  Against the numpy path
    (``FCGRASP_JIT=0``: every tuple sorted, laid out, bounded and filtered by
    :func:`~fcgrasp.pipeline._candidates.lex_survivors`), on seeded parts with ties
    (arcs of equal edges, regular polygons) and keys drawn from the parts' own
    rounded bounds (halved, cut short, tied): the same batches, row for row; and
    without a key, where the compiled loop gives every row once numba runs."""
    from fcgrasp.core._geom import RANK_DIGITS
    from fcgrasp.pipeline._candidates import _bound_pad, _row_bounds, features

    jobs = ({"fingers": 4}, {"fingers": 3, "gravity": (0, -1)}, {"fingers": 3, "mu": 0.3})
    checked = kept = 0
    for seed in range(cases):
        rng = np.random.default_rng(seed)
        part = _tied_part(rng) if seed % 2 else random_polygon(rng)
        job = jobs[seed % 3]
        spec = plan_spec(top=3, **job)
        F = features(part, spec.mu)
        m = 4 if job["fingers"] == 4 else 3
        if rng.random() < 0.5:          # a row's own bounds: ties at every level
            rows = np.concatenate([b.feats for b in candidates(part, spec)])
            row = rows[rng.integers(len(rows))][None]
            twin = spec.shape.twin if spec.shape.three_edge else None
            pick = _row_bounds(F.lengths, row, twin)[0]
        else:
            lengths = np.sort(F.lengths)[::-1]
            pick = np.sort(rng.choice(lengths[:max(m, len(lengths) // 2)], size=m))
            if rng.random() < 0.3:
                pick[0] *= 0.5
        key = np.round((np.sort(pick) + _bound_pad(part.size)) / part.size, RANK_DIGITS)
        key = key[:int(rng.integers(1, m + 1))]
        reach = key[0] * (1 + rng.random())
        streams = []
        for setting in ("0", "1"):
            monkeypatch.setenv("FCGRASP_JIT", setting)
            streams.append([(b.feats.tolist(), b.ceiling, b.bound.tolist())
                            for b in candidates(part, spec, batch_size=64,
                                                key=lambda lv: key if lv <= reach else None)])
        assert streams[0] == streams[1], (seed, job)
        # and with no key: every row, by the compiled loop (a key every row reaches)
        plain, size = [], int(rng.choice([7, 64]))
        for setting in ("0", "1"):
            monkeypatch.setenv("FCGRASP_JIT", setting)
            plain.append([(b.feats.tolist(), b.ceiling) for b in
                          candidates(part, spec, batch_size=size)])
        assert plain[0] == plain[1], (seed, job)
        checked += 1
        kept += sum(len(b[0]) for b in streams[0]) > 0
    assert kept > checked // 2


def test_a_rows_bound_is_the_smallest_of_its_regions_bounds():
    """``_row_bound`` (taken column by column) is, bit for bit, the previous reduction
    along each row, kept here: rows of two, three and four fingers, with gravity (-1,
    no region) and a feature doubled (the first and the twin share it, one of them
    has at most half), lengths tied, zero and huge."""
    from fcgrasp.pipeline._candidates import _row_bound

    def reference(lengths, rows, twin):
        L = np.where(rows >= 0, lengths[np.maximum(rows, 0)], np.inf)
        if twin is not None:
            same = rows[:, 0] == rows[:, twin]
            L[same, 0] *= 0.5
            L[same, twin] = L[same, 0]
        return L.min(axis=1)

    rng = np.random.default_rng(95)
    for _ in range(300):
        F = int(rng.integers(1, 40))
        lengths = rng.choice([0.0, 1.0, 1e12, 3.5], F) * rng.uniform(0.5, 1.5, F)
        k = int(rng.integers(2, 5))
        rows = rng.integers(-1 if k == 3 else 0, F, (int(rng.integers(0, 500)), k))
        twin = None if k == 2 or rng.random() < 0.3 else int(rng.integers(1, k))
        if twin is not None and len(rows):
            rows[: len(rows) // 2, twin] = rows[: len(rows) // 2, 0]
        got, want = _row_bound(lengths, rows, twin), reference(lengths, rows, twin)
        assert got.shape == want.shape and got.tobytes() == want.tobytes()
