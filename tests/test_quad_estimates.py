"""Four frictionless fingers (and three with gravity) leave out the rows whose
compiled estimate is below a search's floor before building their geometry, and
decide whether two fingers on one edge overlap by a compiled placement where it is
sure.  Both are shortcuts with a reference that shares none of their code: the numpy
score of :func:`~fcgrasp.pipeline._candidates._quad_candidates` and the numpy
placement of :func:`~fcgrasp.model.regions.place_regions`."""

from __future__ import annotations

import numpy as np
import pytest

from fcgrasp.core import jit
from fcgrasp.core.tolerances import ESTIMATE_PAD
from fcgrasp.model import regions
from fcgrasp.pipeline import _solve, candidates, plan_spec, search
from fcgrasp.pipeline._candidates import grasp_geometry, quad_estimates

from .shapes import parallel_polygon, random_polygon
from .test_pruning import KINDS, _curved, _flattened, _key

JOBS = [dict(fingers=4), dict(fingers=3, gravity=(0.0, -1.0)),
        dict(fingers=4, margin=0.0), dict(fingers=4, margin=5.0),
        dict(fingers=3, gravity=(0.3, -1.0), margin=0.0)]


def _parts(seed):
    rng = np.random.default_rng(seed)
    parts = [random_polygon(rng, k) for k in KINDS]
    return parts + [parallel_polygon(rng), _curved(rng, int(rng.integers(12, 20))),
                    _flattened(rng)]


def _rows(part, spec, most=4000, seed=0):
    """Every candidate row of a part (each layout), a seeded sample of at most
    ``most`` of them."""
    rows = np.concatenate([b.feats for b in candidates(part, spec)])
    if len(rows) > most:
        rows = rows[np.random.default_rng(seed).choice(len(rows), most, replace=False)]
    return rows


@pytest.fixture
def started(monkeypatch):
    """The estimate runs where numba started in the process (as in a search)."""
    monkeypatch.setattr(jit, "started", lambda: True)


@pytest.mark.parametrize("seed", [0, 1, pytest.param(2, marks=pytest.mark.slow),
                                  pytest.param(3, marks=pytest.mark.slow)])
def test_the_estimate_is_never_below_the_score(seed, started):
    """On every kind of part (parallel and equal edges, flattened arcs whose rows tie),
    with margins of 0, 0.5 and 5 degrees and with gravity: no row scores above its
    estimate by more than the pad, and the estimate is the score to rounding on most
    rows that hold, to the budgets' raise (it prunes)."""
    tight = total = 0
    for part in _parts(seed):
        for job in JOBS:
            spec = plan_spec(**job)
            rows = _rows(part, spec, seed=seed)
            est = quad_estimates(part, spec, rows)
            assert est is not None
            c = grasp_geometry(part, spec, _solve.EdgeSets(rows))
            at = {tuple(r): k for k, r in enumerate(rows.tolist())}
            e = est[[at[tuple(r)] for r in c.feats.tolist()]]
            held = c.score > 0
            assert np.all(c.score[held] <= e[held] + ESTIMATE_PAD * part.size), job
            tight += int(np.sum(np.abs(e[held] - c.score[held]) <= 1e-5 * part.size))
            total += int(held.sum())
    assert total > 1000 and tight >= 0.9 * total, (tight, total)


@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow)])
def test_a_search_with_estimates_finds_the_same_plans(seed, monkeypatch):
    """Searches with a floor (tops of 1 and 10; strict ones too) give the same plans
    with and without the estimate, which leaves rows out (half the jobs on each part;
    all of them under ``-m slow``), and with a hand."""
    monkeypatch.setattr(jit, "started", lambda: True)
    left_out = []
    original = _solve.estimate_below

    def counted(est, floor, size):
        out = original(est, floor, size)
        left_out.append(int(out.sum()))
        return out

    monkeypatch.setattr(_solve, "estimate_below", counted)
    for k, part in enumerate(_parts(seed)):
        for job in JOBS[:4][k % 2::2] if seed == 0 else JOBS[:4]:
            for top in (1, 10):
                spec = plan_spec(top=top, along_boundary=False, **job)
                with_est = [_key(search(part, spec)),
                            _key(search(part, spec, batch_size=8, strict=True))]
                with monkeypatch.context() as m:
                    m.setattr(_solve, "quad_estimates", lambda *a, **k: None)
                    without = [_key(search(part, spec)),
                               _key(search(part, spec, batch_size=8, strict=True))]
                assert with_est == without, (job, top)
    # a hand's reachable pieces of edges are the features (section 8.2)
    import fcgrasp as fc

    part = fc.read_part("demo:blob")
    hand = fc.Hand(workspace=(30, 20, 60), finger_radius=2)
    for job in JOBS[:2]:
        spec = plan_spec(top=5, hand=hand, along_boundary=False, **job)
        with_est = _key(search(part, spec))
        with monkeypatch.context() as m:
            m.setattr(_solve, "quad_estimates", lambda *a, **k: None)
            assert _key(search(part, spec)) == with_est, job
    assert sum(left_out) > 100


def _problems(part, spec, rows):
    """The chosen pairing's problems of the rows that hold, with their leximin levels
    (problem order) and modes."""
    c = grasp_geometry(part, spec, _solve.EdgeSets(rows))
    keep = np.flatnonzero(c.score > 0)
    out = []
    for pr in c.problems:
        sub = pr.take(keep)
        lv = regions.leximin(sub, c.tol)
        ok = np.all(lv >= 0, axis=1) & sub.separable
        out.append((sub.take(np.flatnonzero(ok)), lv[ok]))
    return out


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in (1, 2))])
def test_the_compiled_placement_is_numpys_where_sure(seed):
    """The compiled vertex enumeration against numpy's (batched LAPACK): where it says
    sure, the same region ends to 1e-9 of the longest edge; sure on most rows; at the
    optimal levels and at levels below them (a face of many vertices)."""
    sure_rows = total = 0
    rng = np.random.default_rng(seed)
    for part in _parts(seed):
        for job in JOBS:
            spec = plan_spec(**job)
            for pr, lv in _problems(part, spec, _rows(part, spec, most=300 if seed == 0 else 600,
                                                      seed=seed)):
                if not pr.batch:
                    continue
                for levels in (lv, lv * rng.uniform(0, 1, lv.shape)):
                    want = regions.place_regions(pr, levels)
                    got = regions.place_regions_sure(pr, levels)
                    assert got is not None
                    params, sure = got
                    scale = np.maximum(pr.L.max(axis=1), 1e-300)[:, None, None]
                    assert np.all(np.abs(params - want)[sure] <= 1e-9 * scale[sure])
                    sure_rows += int(sure.sum())
                    total += pr.batch
    assert total > 1000 and sure_rows >= 0.8 * total, (sure_rows, total)


def test_the_overlap_of_two_fingers_on_one_edge_is_numpys(started):
    """Rows with two fingers on one edge (the doubled layouts), at their leximin
    levels: whether the two regions overlap, by the compiled placement where sure, is
    numpy's answer, on hundreds of rows (none of these overlap: the placement puts
    the two regions apart, and the gap's sign is compared)."""
    compared = 0
    for seed in (0, 1):
        for part in _parts(seed):
            for job in JOBS[:1] + JOBS[2:4]:
                spec = plan_spec(**job)
                rows = _rows(part, spec, most=3000, seed=seed)
                rows = rows[rows[:, 0] == rows[:, 2]]
                if not len(rows):
                    continue
                c = grasp_geometry(part, spec, _solve.EdgeSets(rows))
                at = np.flatnonzero(c.score > 0)
                if not at.size:
                    continue
                lengths, mode = _solve._best_levels([p.take(at) for p in c.problems],
                                                    c.perm[at], c.tol)
                ok = lengths.min(axis=1) > 0
                at, lengths, mode = at[ok], lengths[ok], mode[ok]
                a, b = c.a[at], c.b[at]
                got = _solve._overlapping(c, at, a, b, lengths, mode, spec.margin_rad)
                params = _solve._place(c, at, a, b, lengths, mode, spec.margin_rad)
                want = np.minimum(params[:, 0, 1], params[:, 2, 1]) > \
                    np.maximum(params[:, 0, 0], params[:, 2, 0])
                assert np.array_equal(got, want)
                compared += len(want)
    assert compared > 500


def test_the_estimate_applies_to_frictionless_rows_once_numba_runs(monkeypatch):
    """None (every row scored by numpy) for two fingers, and before numba started in
    the process; an estimate per row else."""
    part = random_polygon(np.random.default_rng(3), "convex")
    spec = plan_spec(fingers=4)
    rows = _rows(part, spec, most=20)
    monkeypatch.setattr(jit, "started", lambda: False)
    assert quad_estimates(part, spec, rows) is None
    monkeypatch.setattr(jit, "started", lambda: True)
    assert quad_estimates(part, plan_spec(fingers=2, mu=0.3), rows[:, :2]) is None
    est = quad_estimates(part, spec, rows)
    assert est is not None and est.shape == (len(rows),)


def _previous_select(lengths, feats, size, top):
    """``_solve._select`` as it was (a leximin key per row in Python): the reference."""
    from fcgrasp.core._geom import leximin_key

    real = feats >= 0
    ok = np.all((lengths > 0) | ~real, axis=1)
    keys = [(leximin_key(lengths[r][real[r]], size), r) for r in np.flatnonzero(ok)]
    keys.sort()
    if top is not None and len(keys) > top:
        keys = [kr for kr in keys if kr[0] <= keys[top - 1][0]]
    return np.array(sorted(r for _, r in keys), dtype=int)


def test_the_top_rows_by_columns_are_the_rows_by_keys():
    """``_select`` compares the leximin keys as columns where every row has as many real
    fingers: the rows of the previous row-by-row selection, on 3,000 seeded batches of
    lengths drawn from a few values (ties at every level), a hair off them (at the
    ranking's rounding), with gravity's column, rows with a region of zero, mixed
    layouts and tops of 1 to more than the rows."""
    rng = np.random.default_rng(11)
    vals = np.array([0.0, 1.0, 2.0, 2.0 + 1e-10, 3.5, 7.0])
    for _ in range(3000):
        B, n = int(rng.integers(1, 40)), int(rng.choice([2, 4]))
        lengths = rng.choice(vals, (B, n)) * rng.choice([1.0, 1 + 1e-13], (B, n))
        feats = rng.integers(0, 9, (B, n))
        if rng.random() < 0.3:
            feats[:, -1] = -1                       # gravity
            lengths[:, -1] = 0.0
        if rng.random() < 0.1:
            feats[0, -1] = -1                       # a mixed batch (row by row)
        top = int(rng.integers(1, B + 3))
        size = float(rng.choice([1.0, 7.3]))
        want = _previous_select(lengths, feats, size, top)
        assert np.array_equal(_solve._select(lengths, feats, size, top), want)
        assert np.array_equal(_solve._select(lengths, feats, size, None),
                              _previous_select(lengths, feats, size, None))
