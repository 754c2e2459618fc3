"""Configurations whose whole windows hold (fcgrasp.model.stretches._whole): the lower
bound read from the vertex matrix's runs is the exactly solved largest square, its
block of vertices holds in the dense vertex matrix, and distinct rounds that leave the
copies it proves unsolved give the plans of rounds that solve them."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc


def _outline(rng, n):
    """A seeded outline of ``n`` edges: smooth (an ellipse with a wave, equal or random
    angles), noisy (radial noise) or with a flat side (collinear edges)."""
    kind = rng.choice(["smooth", "random", "noisy", "flat"])
    a = np.sort(rng.uniform(0, 2 * np.pi, n)) if kind == "random" else \
        np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 1 + float(rng.uniform(0, 0.15)) * np.cos(int(rng.integers(2, 5)) * a)
    if kind == "noisy":
        r = r * (1 + 0.01 * rng.standard_normal(n))
    xy = np.c_[float(rng.uniform(30, 60)) * r * np.cos(a),
               float(rng.uniform(15, 30)) * r * np.sin(a)]
    if kind == "flat":
        xy[:, 1] = np.maximum(xy[:, 1], -0.6 * float(xy[:, 1].max()))
        keep = np.r_[True, np.any(np.abs(np.diff(xy, axis=0)) > 1e-9, axis=1)]
        xy = xy[keep]
    return fc.Polygon(xy)


def _collected(poly, mu):
    """Every configuration of the stretch search reaching a small floor, per job: the
    search, and ``[(job, cfg)]``."""
    from fcgrasp.model import stretches as S
    from fcgrasp.model.stretches._rounds import _candidates
    from fcgrasp.model.stretches._solve import _Keys
    from fcgrasp.model.stretches._windows import _Bound

    ss = S.StretchSearch(poly, mu, 0.5)
    keys = _Keys(ss.rings)
    bound = _Bound(1, 2 * keys.total, 1e-3 * poly.size)
    got = _candidates(ss.rings, bound, ss.intervals, ss.runs, keys, prebound=False)
    return ss, got


@pytest.mark.parametrize("seed", [*range(6), *(pytest.param(s, marks=pytest.mark.slow)
                                               for s in range(6, 120))])
def test_the_whole_windows_bound_is_the_solved_largest_square(seed):
    """Wherever :func:`whole_lower` shows a configuration's whole windows hold, the
    exact solve (numpy's elimination, no code shared) gives that largest square to
    1e-9 of the part's size, and the block of vertices is all True in the dense vertex
    matrix with both fans; where the dense block holds and the shorter stretch spans
    the longer's interior, the bound is shown (the runs miss none)."""
    from fcgrasp.model.stretches._lp import _system
    from fcgrasp.model.stretches._solve import _solve_any
    from fcgrasp.model.stretches._whole import _Whole
    from fcgrasp.model.stretches._windows import _ext, _inner, _stretch_bound, _vertex_matrix

    rng = np.random.default_rng(seed)
    poly = _outline(rng, int(rng.integers(12, 60)))
    mu = float(rng.uniform(0.1, 1.2))
    ss, got = _collected(poly, mu)
    whole = _Whole(ss.rings, ss.runs)
    shown = 0
    for job, cfg in got:
        x, y, sigma, _ = job
        assert whole.reads(job) == (x == y)
        if x != y or not cfg.iA.size:
            continue
        lb = whole(job, cfg)
        ring = ss.rings[x]
        m = ring.m
        M = _vertex_matrix(ring, ring, sigma, ss.beta)
        dense = np.array([M[np.ix_((a + np.arange(ka + 2)) % m, (c + np.arange(kc + 2)) % m)]
                          .all() if ka + 2 <= m and kc + 2 <= m else False
                          for a, ka, c, kc in zip(cfg.iA, cfg.kA, cfg.iC, cfg.kC, strict=True)])
        arc_a, arc_c = _ext(ring, cfg.iA, cfg.kA), _ext(ring, cfg.iC, cfg.kC)
        spans = np.where(arc_a <= arc_c, _inner(ring, cfg.iC, cfg.kC) <= arc_a,
                         _inner(ring, cfg.iA, cfg.kA) <= arc_c)
        assert np.array_equal(lb > 0, dense & spans), job
        at = np.flatnonzero(lb > 0)
        if not at.size:
            continue
        part = cfg.take(at)
        rows = _system(ring, ring, part, sigma, ss.beta, ss.intervals[x, x, sigma],
                       ss.intervals[x, x, sigma])
        t, _, _ = _solve_any(rows, _stretch_bound(ring, ring, part), poly.size, False)
        assert np.allclose(t, lb[at], rtol=0, atol=1e-9 * poly.size), job
        shown += at.size
    if seed < 6:
        assert shown > 0


def _smooth(rng):
    """A seeded smooth outline of a few hundred edges, its friction and the plans asked."""
    n = int(rng.integers(150, 400))
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 1 + float(rng.uniform(0.02, 0.15)) * np.cos(int(rng.integers(2, 5)) * a
                                                     + float(rng.uniform(0, 2 * np.pi)))
    part = fc.Polygon(np.c_[60 * r * np.cos(a), float(rng.uniform(25, 45)) * r * np.sin(a)])
    return part, float(rng.uniform(0.3, 1.0)), int(rng.integers(4, 11))


@pytest.mark.parametrize("seed", [0, 1, 2, *(pytest.param(s, marks=pytest.mark.slow)
                                             for s in range(3, 60))])
def test_copies_left_unsolved_by_their_whole_windows_change_no_plan(seed, monkeypatch):
    """Distinct rounds that leave unsolved the kept plans' copies whose whole windows
    prove them copies at their largest square (``WHOLE_WINDOWS``) give the plans and
    regions, bit for bit, of rounds that solve every one (the reference), on seeded
    smooth outlines where a grasp has thousands of shifted copies (the proof used in the
    default cases)."""
    from fcgrasp.model.stretches import _solve, _whole

    part, mu, top = _smooth(np.random.default_rng(seed))
    proved = []
    lower = _solve._lower

    def counted(job, J, idx, whole):
        out = lower(job, J, idx, whole)
        if out is not None:
            proved.append(int(np.count_nonzero(out > 0)))
        return out

    monkeypatch.setattr(_solve, "_lower", counted)
    got = fc.plan(part, fingers=2, mu=mu, top=top, time_limit=None)
    if seed < 3:
        assert sum(proved) > 0
    monkeypatch.setattr(_whole, "WHOLE_WINDOWS", False)
    ref = fc.plan(part, fingers=2, mu=mu, top=top, time_limit=None)
    assert [p.edges for p in got] == [p.edges for p in ref]
    for p, q in zip(got, ref, strict=True):
        for a, b in zip(p.regions, q.regions, strict=True):
            assert np.array_equal(a, b)


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 30))])
def test_a_rows_runs_hold_a_cyclic_window_as_its_cells_do(seed):
    """Whether a row's runs hold ``n`` cyclic columns from ``c0``, by the compiled
    bisection (``_row_holds``, the collection's) and by numpy's (``_RowRuns.holds``),
    is whether every one of those cells of the dense matrix is True, on seeded matrices
    (rows empty, full, with runs through the last and the first column)."""
    from fcgrasp.model.stretches import _kernels
    from fcgrasp.model.stretches._whole import _RowRuns
    from fcgrasp.model.stretches._windows import _row_intervals

    rng = np.random.default_rng(seed)
    holds = _kernels._load()["_row_holds"]
    for _ in range(20):
        m = int(rng.integers(3, 40))
        M = rng.random((m, m)) < rng.uniform(0.3, 0.98)
        M[rng.integers(m)] = True
        M[rng.integers(m)] = False
        row, first, last = _row_intervals(M)
        ptr = np.searchsorted(row, np.arange(m + 1))
        runs = _RowRuns((ptr, first, last), m)
        rows = rng.integers(0, m, 300)
        c0 = rng.integers(0, m, 300)
        n = rng.integers(1, m + 1, 300)
        want = np.array([M[r, (c + np.arange(k)) % m].all()
                         for r, c, k in zip(rows, c0, n, strict=True)])
        assert np.array_equal(runs.holds(rows, c0, n), want)
        got = [holds(ptr.astype(np.int64), first.astype(np.int64), last.astype(np.int64),
                     int(r), int(c), int(k), m) for r, c, k in zip(rows, c0, n, strict=True)]
        assert np.array_equal(got, want)


@pytest.mark.parametrize("seed", [0, 1, *(pytest.param(s, marks=pytest.mark.slow)
                                          for s in range(2, 40))])
def test_the_collection_leaves_out_the_copies_its_whole_windows_show(seed):
    """A distinct round's compiled collection on one ring leaves out, beside the copies
    at any smallest region from the floor (``exs[4]``), only configurations whose whole
    windows hold (:func:`whole_lower`, numpy's) with an arc bound above their threshold
    (:meth:`_Exclusion.thresholds`, numpy's) by the pad both ways, and every such one
    not within a thousandth of that boundary; with the pad 0 it leaves out none of them."""
    from fcgrasp.core.tolerances import DEFER_PAD
    from fcgrasp.model import stretches as S
    from fcgrasp.model.stretches import _kernels
    from fcgrasp.model.stretches._exclusion import _Exclusion
    from fcgrasp.model.stretches._memo import _Job
    from fcgrasp.model.stretches._whole import _RowRuns, whole_lower
    from fcgrasp.model.stretches._windows import _both_kept, _Configs, _stretch_bound

    part, mu, _ = _smooth(np.random.default_rng(seed))
    ss = S.StretchSearch(part, mu, 0.5)
    kept = ss.pairs(top=2)[:1]
    ring = ss.rings[0]
    excl = _Exclusion(ss.rings, part, [(p.regions, p.region_edges) for p in kept], 0.5, [],
                      False)
    floor = 0.3 * kept[0].min_length
    left = 0
    for sigma in (1.0, -1.0):
        ptr, first, last = ss.runs[0, 0][sigma]
        ex, exs = excl.copy_columns(ss.rings, 0, 0, floor)
        assert exs[5] == DEFER_PAD

        def collect(pad, ex=ex, exs=exs, ptr=ptr, first=first, last=last):
            _, *cfg = _kernels.windows(ptr, first, last, ring.U, ring.U, ring.m, ring.m,
                                       floor, True, True, 0.0, 1, ex=ex,
                                       exs=np.r_[exs[:5], pad])
            return _both_kept(_Configs(*cfg), ring, ring, True)

        every, some = collect(0.0), collect(DEFER_PAD)
        code = excl._codes(ss.rings, 0, 0, every.iA, every.kA, every.iC, every.kC)
        kept_codes = excl._codes(ss.rings, 0, 0, some.iA, some.kA, some.iC, some.kC)
        out = ~np.isin(code, kept_codes)
        assert np.isin(kept_codes, code).all()
        n = len(every.iA)
        J = _Job(every, _stretch_bound(ring, ring, every), np.full(n, np.nan), np.arange(n),
                 False, np.full(n, np.nan), np.full(n, np.nan), np.full(n, np.nan), np.zeros(n))
        tau = excl.thresholds(ss.rings, (0, 0, sigma, "m"), J, np.arange(n), ss.intervals)
        lb = whole_lower(ring, _RowRuns((ptr, first, last), ring.m), every)
        shown = (lb > 0) & (lb * (1 - DEFER_PAD) >= tau * (1 + DEFER_PAD))
        clear = (lb > 0) & (np.abs(lb - tau) > 1e-3 * np.maximum(lb, tau))
        assert not (out & ~shown & clear).any()
        assert not (~out & shown & clear).any()
        left += int(out.sum())
    if seed < 2:
        assert left > 0
