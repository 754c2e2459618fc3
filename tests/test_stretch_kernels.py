"""The compiled loops of the two-finger stretch search (fcgrasp.model.stretches._kernels)
against the numpy search they replace on large rings, kept as the reference: the same
vertex runs bit for bit, the same configurations, the same plans; the lower bounds of
the windows against a dense brute force written here; and the top ``k`` of the search
against the head of every configuration (``top=None``), which the bound must never
cut short."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.core.contacts import rotate
from fcgrasp.model import stretches as S
from fcgrasp.model.polygon import Polygon
from fcgrasp.model.stretches import _exclusion as X
from fcgrasp.model.stretches import _kernels as _stretch_kernels
from fcgrasp.model.stretches import _placement as P
from fcgrasp.model.stretches import _rounds as Q
from fcgrasp.model.stretches import _solve as V
from fcgrasp.model.stretches import _windows as W
from fcgrasp.model.stretches._windows import _Intervals, _rings, _windows_both, _windows_single

from .test_stretches import seeds, smooth_outline

KINDS = ("ellipse", "star", "cam", "rounded", "noisy", "regular", "collinear")


def outline(rng, kind, n):
    """Outlines of every kind the search meets, near-degenerate ones included: exact
    symmetric ties (a regular polygon), straight runs of collinear vertices (turn 0),
    and noise that makes most vertices too sharp to cover."""
    if kind == "noisy":
        th = np.sort(rng.uniform(0, 2 * np.pi, n))
        r = (1 + 0.3 * np.sin(5 * th)) * (1 + rng.uniform(0.002, 0.03) * rng.standard_normal(n))
        return 50 * np.c_[r * np.cos(th), r * np.sin(th)]
    if kind == "regular":
        th = np.arange(n) * 2 * np.pi / n
        return 40 * np.c_[np.cos(th), np.sin(th)]
    if kind == "collinear":
        side = max(2, n // 4)
        t = np.arange(side) / side
        w, h = 60.0, rng.uniform(10, 60)
        return np.concatenate([np.c_[w * t, 0 * t], np.c_[w + 0 * t, h * t],
                               np.c_[w * (1 - t), h + 0 * t], np.c_[0 * t, h * (1 - t)]])
    return smooth_outline(rng, kind, n)


def part(seed, n=None):
    rng = np.random.default_rng(seed)
    kind = KINDS[seed % len(KINDS)]
    pts = outline(rng, kind, n or int(rng.integers(12, 90)))
    holes = []
    if seed % 3 == 0:                       # a hole: ring pairs of two rings
        c = pts.mean(axis=0)
        r = 0.15 * np.min(np.ptp(pts, axis=0))
        th = np.linspace(0, 2 * np.pi, int(rng.integers(5, 30)), endpoint=False)[::-1]
        holes = [c + r * np.c_[np.cos(th), np.sin(th)]]
    mu = float(rng.choice([0.15, 0.3, 0.6, 1.2]))
    return Polygon(pts, holes=holes), mu, float(rng.choice([0.0, 0.5, 2.0]))


def _beta(mu, margin):
    return float(np.arctan(mu) - np.radians(margin))


def _runs(monkeypatch, setting, ra, rb, beta):
    monkeypatch.setenv("FCGRASP_JIT", setting)
    return S._vertex_runs(ra, rb, beta)


@pytest.mark.parametrize("seed", seeds(2, 300))
def test_vertex_runs_are_the_numpy_matrix(seed, monkeypatch):
    poly, mu, margin = part(seed)
    beta = _beta(mu, margin)
    rings = _rings(poly)
    for x in range(len(rings)):
        for y in range(x, len(rings)):
            fast = _runs(monkeypatch, "1", rings[x], rings[y], beta)
            slow = _runs(monkeypatch, "0", rings[x], rings[y], beta)
            for sigma in (1.0, -1.0):
                for got, want in zip(fast[sigma], slow[sigma], strict=True):
                    np.testing.assert_array_equal(got, want)


def _dense(runs, ma, mb):
    ptr, first, last = runs
    M = np.zeros((ma, mb), bool)
    for r in range(ma):
        for q in range(ptr[r], ptr[r + 1]):
            M[r, first[q]:last[q] + 1] = True
    return M


def _brute_lower_bounds(M, ra, rb, same):
    """For each first row: the best vertex-aligned pair of every window of rows (the
    AND of the rows, its cyclic runs), by plain loops over a dense matrix."""
    ma, mb = M.shape
    best = np.zeros(ma)
    arc_a = lambda i, k: ra.U[(i - 1) % ma + ma + k] - ra.U[(i - 1) % ma + ma + 1]  # noqa: E731
    arc_b = lambda i, k: rb.U[(i - 1) % mb + mb + k] - rb.U[(i - 1) % mb + mb + 1]  # noqa: E731
    for r in range(ma):
        cols = M[r].copy()
        for k in range(1, ma - 1):
            if not cols.any():
                break
            if cols.all():
                runs = [(0, mb)]
            else:
                start = int(np.flatnonzero(~cols)[0]) + 1       # after a False column
                runs, j = [], 0
                while j < mb:
                    c = (start + j) % mb
                    if cols[c]:
                        n = 0
                        while n < mb and cols[(c + n) % mb]:
                            n += 1
                        runs.append((c, n))
                        j += n
                    else:
                        j += 1
            for p0, n in runs:
                rr = min(n, mb - 2)
                if rr >= 1 and (not same or p0 > r):
                    best[r] = max(best[r], min(arc_a(r, k), arc_b(p0, rr)))
            cols &= M[(r + k) % ma]
    return best


def _config_set(cfg, ma, mb):
    return set(zip((cfg.iA % ma).tolist(), cfg.kA.tolist(), (cfg.iC % mb).tolist(),
                   cfg.kC.tolist(), strict=True))


@pytest.mark.parametrize("seed", seeds(2, 200))
def test_windows_are_the_numpy_windows(seed, monkeypatch):
    poly, mu, margin = part(seed)
    beta = _beta(mu, margin)
    rings = _rings(poly)
    ra = rb = rings[0]
    runs = _runs(monkeypatch, "0", ra, rb, beta)
    for sigma in (1.0, -1.0):
        M = _dense(runs[sigma], ra.m, rb.m)
        brute = _brute_lower_bounds(M, ra, rb, True)
        monkeypatch.setenv("FCGRASP_JIT", "1")
        best, _ = Q._both(runs[sigma], ra, rb, True, 0.0, False)
        np.testing.assert_allclose(best, brute, rtol=0, atol=1e-12 * poly.size)
        # the numpy search reads fewer window lengths: its bounds are never higher
        slow, _ = _windows_both(runs[sigma], ra, rb, True, 0.0, False)
        assert np.all(slow <= best + 1e-12 * poly.size)
        for floor in (0.0, 0.5 * best.max(initial=0.0), best.max(initial=0.0)):
            _, fast = Q._both(runs[sigma], ra, rb, True, floor, True)
            _, want = _windows_both(runs[sigma], ra, rb, True, floor, True)
            assert _config_set(fast, ra.m, rb.m) == _config_set(want, ra.m, rb.m)


@pytest.mark.parametrize("seed", seeds(2, 200))
def test_single_edge_windows_are_the_numpy_ones(seed, monkeypatch):
    poly, mu, margin = part(seed)
    beta = _beta(mu, margin)
    rings = _rings(poly)
    pairs = [(0, 0)] + ([(0, 1), (1, 0)] if len(rings) > 1 else [])
    for x, y in pairs:
        for sigma in (1.0, -1.0):
            iv = _Intervals(rings[x], rings[y], sigma, beta)
            lengths = rings[x].L
            for floor in (0.0, float(np.median(lengths)), float(lengths.max())):
                monkeypatch.setenv("FCGRASP_JIT", "1")
                (a, p, v), fast = Q._single(iv, rings[x], rings[y], x == y, floor, True)
                (a2, p2, v2), want = _windows_single(iv, rings[x], rings[y], x == y, floor,
                                                     True)
                m_a, m_b = rings[x].m, rings[y].m
                assert _config_set(fast, m_a, m_b) == _config_set(want, m_a, m_b)
                got = dict(zip(zip(a.tolist(), p.tolist(), strict=True), v.tolist(),
                               strict=True))
                ref = dict(zip(zip(a2.tolist(), p2.tolist(), strict=True), v2.tolist(),
                               strict=True))
                assert got.keys() == ref.keys()
                for key, val in ref.items():
                    assert got[key] == pytest.approx(val, rel=0, abs=1e-12 * poly.size)


def _plans(poly, mu, margin, top, ties=True):
    return [(p.region_edges, p.mode, p.lengths, p.regions)
            for p in S.two_finger_stretches(poly, mu, margin, top=top, ties=ties)]


def _assert_same_plans(got, want, size):
    assert len(got) == len(want)
    for g, w in zip(got, want, strict=True):
        assert g[0] == w[0] and g[1] == w[1]
        np.testing.assert_allclose(g[2], w[2], rtol=0, atol=1e-9 * size)
        for rg, rw in zip(g[3], w[3], strict=True):
            np.testing.assert_allclose(rg, rw, rtol=0, atol=1e-9 * size)


@pytest.mark.parametrize("seed", seeds(1, 400))
def test_compiled_search_gives_the_numpy_plans(seed, monkeypatch):
    poly, mu, margin = part(seed)
    monkeypatch.setenv("FCGRASP_JIT", "1")
    fast = _plans(poly, mu, margin, 8)
    monkeypatch.setenv("FCGRASP_JIT", "0")
    _assert_same_plans(fast, _plans(poly, mu, margin, 8), poly.size)


@pytest.mark.parametrize("seed", seeds(2, 200))
def test_a_search_that_turns_compiled_half_way_gives_the_numpy_plans(seed, monkeypatch):
    """Past :data:`NUMPY_SOLVE_BUDGET` of numpy solves a process solves the rest
    of its configurations compiled, in the middle of a job: the plans stay those of the
    numpy search."""
    poly, mu, margin = part(seed)
    monkeypatch.setenv("FCGRASP_JIT", "0")
    want = _plans(poly, mu, margin, 8)
    monkeypatch.setenv("FCGRASP_JIT", "auto")
    monkeypatch.setattr(W, "started", lambda: False)     # numba not started
    monkeypatch.setattr(W, "NUMPY_SOLVE_BUDGET", 0.0)
    monkeypatch.setattr(W, "_numpy_spent", [0.0])
    calls = []
    solve = V._solve_any
    for module in (V, Q):               # the first level's solves, and the second's
        monkeypatch.setattr(module, "_solve_any",
                            lambda *a, **k: calls.append(a[3]) or solve(*a, **k))
    _assert_same_plans(_plans(poly, mu, margin, 8), want, poly.size)
    assert calls == sorted(calls) and calls[0] is False and (len(calls) == 1 or calls[-1])


def _plan_tuples(poly, **kw):
    return [(p.region_edges, p.mode, p.lengths, p.regions) for p in fc.plan(poly, **kw)]


@pytest.mark.parametrize("seed", seeds(3, 150))
def test_configurations_proved_below_the_floor_change_no_plan(seed, monkeypatch):
    """The compiled solve leaves unsolved the configurations it proves below
    the run's floor (the bound's, or the distinct rounds' memo's), and a later round
    solves them only where its floor is lower (``FLOOR_SOLVE``).  The plans of two
    fingers and of three with friction at default options (distinct rounds along the
    boundary) are those of every configuration solved in full."""
    poly, mu, margin = part(seed)
    monkeypatch.setenv("FCGRASP_JIT", "1")
    proved = []
    solve = _stretch_kernels.solve_rows

    def counted(*a):
        out = solve(*a)
        proved.append(int(np.isnan(out[0]).sum()))
        return out

    monkeypatch.setattr(_stretch_kernels, "solve_rows", counted)
    jobs = [dict(fingers=2, mu=mu, margin=margin)] + \
        ([dict(fingers=3, mu=mu, margin=margin)] if seed % 3 == 0 else [])
    for job in jobs:
        got = _plan_tuples(poly, **job)
        monkeypatch.setattr(V, "FLOOR_SOLVE", 0)
        want = _plan_tuples(poly, **job)
        monkeypatch.setattr(V, "FLOOR_SOLVE", 1)
        _assert_same_plans(got, want, poly.size)
    if seed < 3:
        assert sum(proved) > 0          # the floor did leave some unsolved


@pytest.mark.parametrize("seed", [18, *(pytest.param(s, marks=pytest.mark.slow)
                                        for s in range(120) if s != 18)])
def test_rounds_sharing_a_memo_solve_again_what_their_lower_floor_needs(seed, monkeypatch):
    """Rounds of one distinct search share their solved configurations
    (``_Memo``), those proved below one round's floor left unsolved; a later round
    whose floor is lower solves them again.  Three rounds (the best, then with a plan
    read, then more plans) give what a fresh search gives the last round.  (Seed 18
    caught a round skipping what an earlier, higher floor had left.)"""
    poly, mu, margin = part(seed)
    monkeypatch.setenv("FCGRASP_JIT", "1")
    first = S.two_finger_stretches(poly, mu, margin, top=1)
    assert first

    def last_round(rounds):
        search = S.StretchSearch(poly, mu, margin)
        search.pairs(top=1)
        for top in rounds:
            got = search.pairs(top=top, seen=first, ties=True)
        return [(p.region_edges, p.mode, p.lengths, p.regions) for p in got]

    _assert_same_plans(last_round((1, 12)), last_round((12,)), poly.size)


@pytest.mark.parametrize("seed", seeds(1, 300))
def test_top_k_is_the_head_of_every_configuration(seed, monkeypatch):
    """The bound prunes, but the top ``k`` (ties included) are the first of all the
    configurations, found with no bound at all."""
    poly, mu, margin = part(seed, n=int(np.random.default_rng(seed).integers(10, 36)))
    monkeypatch.setenv("FCGRASP_JIT", "1" if seed % 2 else "0")
    every = [p.min_length for p in S.two_finger_stretches(poly, mu, margin, top=None)]
    for k in (1, 3, 10):
        got = [p.min_length for p in S.two_finger_stretches(poly, mu, margin, top=k,
                                                            ties=True)]
        head = sorted(every, reverse=True)
        if len(head) > k:
            kth = head[k - 1]
            head = [t for t in head if t >= kth * (1 - S.TIE)]
        np.testing.assert_allclose(sorted(got, reverse=True), head, rtol=1e-9)


def test_angular_window_misses_no_cell(monkeypatch):
    """A chord exactly at the edge of both cones (the two normals exactly 2 beta from
    opposite) is read by the compiled loop: two parallel edges facing each other and
    tilted by the cone's full width."""
    mu, margin = 0.3, 0.0
    beta = _beta(mu, margin)
    d = rotate(np.array([0.0, 1.0]), beta)
    a, b = np.array([0.0, 0.0]), 30 * d
    poly = Polygon([a, a + [40, 0], b + [40, 0] + rotate(np.array([1.0, 0]), 2 * beta) * 0,
                    b])
    rings = _rings(poly)
    fast = _runs(monkeypatch, "1", rings[0], rings[0], beta)
    slow = _runs(monkeypatch, "0", rings[0], rings[0], beta)
    for sigma in (1.0, -1.0):
        for got, want in zip(fast[sigma], slow[sigma], strict=True):
            np.testing.assert_array_equal(got, want)


@pytest.mark.parametrize("seed", seeds(3, 60))
def test_compiled_solve_is_the_numpy_elimination(seed, monkeypatch):
    """The compiled per-configuration solve against the batched Fourier-Motzkin solve
    on the systems of every configuration of a part (feasible and not)."""
    from fcgrasp.model.stretches._kernels import solve_rows
    from fcgrasp.model.stretches._lp import _box_bound, _solve, _system
    from fcgrasp.model.stretches._windows import _Configs, _stretch_bound

    poly, mu, margin = part(seed)
    beta = _beta(mu, margin)
    ring = _rings(poly)[0]
    m = ring.m
    rng = np.random.default_rng(seed)
    n = 400
    iA, iC = rng.integers(0, m, n), rng.integers(0, m, n)
    kA, kC = rng.integers(0, 4, n), rng.integers(0, 4, n)
    far = (iA + kA + 1 + iC % np.maximum(1, m - kA - kC - 2)) % m
    # half of them across the part (about half a ring away), where most parts hold
    across = (iA + m // 2 + rng.integers(-2, 3, n)) % m
    cfg = _Configs(iA, kA, np.where(np.arange(n) % 2 == 0, far, across), kC)
    counts = []
    proved = [0, 0]         # infeasible, below the floor
    for sigma in (1.0, -1.0):
        iv = _Intervals(ring, ring, sigma, beta)
        rows = _system(ring, ring, cfg, sigma, beta, iv, iv)
        ub = _stretch_bound(ring, ring, cfg)
        want = _solve(rows, ub, poly.size)
        got = solve_rows(rows, ub, S.ROUND_TOL * poly.size, W._EPS)
        feasible = want[0] > 0
        np.testing.assert_array_equal(got[0] > 0, feasible)
        # the ends' boxes bound the optimum (the search prunes and orders by them)
        box = _box_bound(ring, ring, cfg, iv, iv, False)
        assert np.all(box[feasible] >= want[0][feasible] - 1e-9 * poly.size)
        np.testing.assert_array_equal(box, _box_bound(ring, ring, cfg, iv, iv, True))
        counts.append(int(feasible.sum()))
        for g, w in zip(got, want, strict=True):
            np.testing.assert_allclose(g, w, rtol=0, atol=1e-12 * poly.size)
        # with a floor: NaN only where the largest t is below it (or none holds), the
        # same numbers elsewhere; infeasible systems and feasible ones below proved so
        for q in (0.2, 0.5, 0.9):
            floor = float(np.quantile(want[0][feasible], q)) if feasible.any() else 1.0
            cut = solve_rows(rows, ub, S.ROUND_TOL * poly.size, W._EPS, floor)
            skipped = np.isnan(cut[0])
            assert np.all(want[0][skipped] < floor)
            for g, c in zip(got, cut, strict=True):
                np.testing.assert_array_equal(c[~skipped], g[~skipped])
            proved[0] += int(np.count_nonzero(skipped & ~feasible))
            proved[1] += int(np.count_nonzero(skipped & feasible))
    # infeasible systems met, and feasible ones but on noisy outlines (there, at a small
    # mu, no configuration of the sample may hold: seeds 18, 25, 53)
    assert sum(counts) < 2 * n
    assert sum(counts) > 0 or KINDS[seed % len(KINDS)] == "noisy"
    assert proved[0] > 0
    assert proved[1] > 0 or sum(counts) < 20


@pytest.mark.parametrize("seed", seeds(3, 80))
def test_shared_end_intervals_are_read_cell_by_cell(seed):
    """The end intervals of windows that share an edge (a configuration's shifted
    copies), answered from sparse tables of the cells their span covers
    (``window_boxes_shared``), are those read cell by cell (``window_boxes``, and numpy)
    bit for bit: windows of every length from 0 to a whole ring, through the ring's
    last vertex, a few edges each with many windows (tabled), edges with a few windows
    (their cells read once) and edges with one."""
    poly, mu, margin = part(seed)
    beta = _beta(mu, margin)
    rings = _rings(poly)
    rng = np.random.default_rng(seed)
    for x, y in [(0, 0)] + ([(0, 1)] if len(rings) > 1 else []):
        mb = rings[y].m
        for sigma in (1.0, -1.0):
            iv = _Intervals(rings[x], rings[y], sigma, beta)
            shared = rng.integers(0, rings[x].m, 4)         # many windows: tables
            few = rng.integers(0, rings[x].m, 30)           # a few: the cells read once
            n = 400
            u = rng.random(n)
            edge = np.where(u < 0.6, rng.choice(shared, n),
                            np.where(u < 0.9, rng.choice(few, n),
                                     rng.integers(0, rings[x].m, n)))
            centre = rng.integers(0, mb, rings[x].m)[edge]
            start = (centre + rng.integers(-6, 7, n)) % mb
            count = rng.integers(0, min(mb, 16), n)
            count[rng.random(n) < 0.05] = mb            # whole rings
            count[rng.random(n) < 0.1] = 0
            start[rng.random(n) < 0.1] = mb - 1         # through the last vertex
            args = (edge.astype(np.int64), start.astype(np.int64), count.astype(np.int64),
                    *iv._flat, sigma, W._EPS)
            got = _stretch_kernels.window_boxes_shared(*args)
            want = _stretch_kernels.window_boxes(*args)
            numpy = iv.window(edge, start, count)
            for g, w, v in zip(got, want, numpy, strict=True):
                np.testing.assert_array_equal(g, w)
                np.testing.assert_array_equal(g, v)


@pytest.mark.parametrize("seed", seeds(3, 80))
def test_compiled_end_intervals_are_the_numpy_ones(seed, monkeypatch):
    """The intersection of an edge's intervals against a window of vertices (the ends'
    boxes of every configuration's system), compiled and by numpy; compiled with the
    cells kept in a table (read from it the second time) and without."""
    from fcgrasp.model.stretches import _windows as _stretch_windows

    poly, mu, margin = part(seed)
    beta = _beta(mu, margin)
    rings = _rings(poly)
    rng = np.random.default_rng(seed)
    for x, y in [(0, 0)] + ([(0, 1), (1, 0)] if len(rings) > 1 else []):
        for sigma in (1.0, -1.0):
            iv = _Intervals(rings[x], rings[y], sigma, beta)
            n = 300
            edge = rng.integers(0, rings[x].m, n)
            start = rng.integers(0, rings[y].m, n)
            count = rng.integers(0, min(rings[y].m, 12), n)
            got = iv.window(edge, start, count, compiled=True)
            assert iv._memo is not None and np.isfinite(iv._memo[0]).any()
            again = iv.window(edge, start, count, compiled=True)
            with monkeypatch.context() as m:
                m.setattr(_stretch_windows, "MEMO_CELLS", 0)
                direct = iv.window(edge, start, count, compiled=True)
            want = iv.window(edge, start, count)
            for g, a, d, w in zip(got, again, direct, want, strict=True):
                for way in (g, a, d):
                    np.testing.assert_array_equal(way, w)
            assert np.any(got[0] <= got[1]) and np.any(got[0] > got[1])


def test_large_outline_fits_the_default_budget(monkeypatch):
    """The compiled search holds nothing of size n x n, so its memory estimate lets a
    6,000-edge outline through the default 2 GB budget (the numpy search's estimate,
    64 bytes per pair of edges, refuses it and says what would fit)."""
    import fcgrasp as fc
    from fcgrasp.errors import SearchTooLarge

    a = np.linspace(0, 2 * np.pi, 6000, endpoint=False)
    part = Polygon(np.c_[60 * np.cos(a), 30 * np.sin(a)])
    monkeypatch.setenv("FCGRASP_JIT", "0")
    with pytest.raises(SearchTooLarge, match="simplify"):
        fc.plan(part, fingers=2, mu=0.3, top=1)
    monkeypatch.setenv("FCGRASP_JIT", "auto")
    best = fc.plan(part, fingers=2, mu=0.3, top=1)[0]
    # the ellipse's regions run along the curve: far longer than one edge (0.05 mm)
    assert best.min_length > 20


@pytest.mark.parametrize("seed", range(6))
def test_own_optimum_filter_matches_every_pair(seed):
    """The compiled own-optimum filter (table look-ups, and the scan by start it falls
    back to) against the definition over every (sub, super) pair: a configuration is
    dropped iff one inside it, on both rings (on one ring either way round), has a
    longer smallest region; exact ties, wrapping stretches and unreduced starts
    included."""
    rng = np.random.default_rng(seed)
    for _ in range(20):
        ma, mb = int(rng.integers(5, 40)), int(rng.integers(5, 40))
        same = bool(rng.random() < 0.4)
        if same:
            mb = ma
        F = int(rng.integers(1, 300))
        wrap = 3 if rng.random() < 0.3 else 1   # starts past the ring's end, as stored
        c = np.c_[rng.integers(0, wrap * ma, F), rng.integers(0, ma // 2, F),
                  rng.integers(0, wrap * mb, F), rng.integers(0, mb // 2, F)]
        t = np.round(rng.random(F), 1)          # many exact ties
        if rng.random() < 0.5:                  # and ties within the tie factor
            t = t * (1 + S.TIE * rng.choice([-2.0, -0.5, 0.0, 0.5, 2.0], F))
        got = _stretch_kernels.beaten(c, t, ma, mb, same, S.TIE)
        # the scan by start, kept for tables too large to build
        scan = np.ones(F, bool)
        cols = [np.ascontiguousarray(c[:, j] % (ma, ma, mb, mb)[j], dtype=np.int64)
                for j in range(4)]
        _stretch_kernels._load()["_beaten"](*cols, t, ma, mb, same, S.TIE,
                                            np.lexsort((-t, cols[0])).astype(np.int64), scan,
                                            np.ones(F, bool))

        def inside(i, k, i2, k2, m):
            return (i[:, None] - i2[None, :]) % m + k[:, None] <= k2[None, :]

        sub = inside(c[:, 0], c[:, 1], c[:, 0], c[:, 1], ma) \
            & inside(c[:, 2], c[:, 3], c[:, 2], c[:, 3], mb)
        if same:
            sub |= inside(c[:, 0], c[:, 1], c[:, 2], c[:, 3], ma) \
                & inside(c[:, 2], c[:, 3], c[:, 0], c[:, 1], ma)
        want = ~(sub & (t[:, None] > t[None, :] * (1 + S.TIE))).any(axis=0)
        assert np.array_equal(got, want)
        assert np.array_equal(scan, want)


def test_own_optimum_filter_remembers_sets_not_orders(monkeypatch):
    """The rounds of a distinct search ask the own-optimum filter about the
    same configurations in another order; :func:`~fcgrasp.model.stretches._kernels.beaten`
    remembers the answer per set: a permuted set gets the answers permuted, a set with
    one region changed gets its own answers (the definition over every pair)."""
    monkeypatch.setattr(_stretch_kernels, "BEATEN_MEMO_ROWS", 1)
    monkeypatch.setattr(_stretch_kernels, "_beaten_memo", {})
    rng = np.random.default_rng(61)

    def definition(c, t, m, same):
        def inside(i, k, i2, k2):
            return (i[:, None] - i2[None, :]) % m + k[:, None] <= k2[None, :]
        sub = inside(c[:, 0], c[:, 1], c[:, 0], c[:, 1]) & inside(c[:, 2], c[:, 3], c[:, 2],
                                                                  c[:, 3])
        if same:
            sub |= inside(c[:, 0], c[:, 1], c[:, 2], c[:, 3]) & \
                inside(c[:, 2], c[:, 3], c[:, 0], c[:, 1])
        return ~(sub & (t[:, None] > t[None, :] * (1 + S.TIE))).any(axis=0)

    hits = 0
    for _ in range(60):
        m, same, F = int(rng.integers(5, 30)), bool(rng.random() < 0.5), int(rng.integers(2, 120))
        c = np.c_[rng.integers(0, m, F), rng.integers(0, m // 2, F), rng.integers(0, m, F),
                  rng.integers(0, m // 2, F)]
        t = np.round(rng.random(F), 1)
        first = _stretch_kernels.beaten(c, t, m, m, same, S.TIE)
        assert np.array_equal(first, definition(c, t, m, same))
        perm = rng.permutation(F)
        before = len(_stretch_kernels._beaten_memo)
        assert np.array_equal(_stretch_kernels.beaten(c[perm], t[perm], m, m, same, S.TIE),
                              first[perm])
        hits += len(_stretch_kernels._beaten_memo) == before
        t2 = t.copy()
        t2[rng.integers(F)] = 2.0                 # one region longer than every other
        assert np.array_equal(_stretch_kernels.beaten(c, t2, m, m, same, S.TIE),
                              definition(c, t2, m, same))
    assert hits == 60                             # each permuted set was remembered


def _scan_runs(monkeypatch, ra, rb, beta):
    """The runs by the window scan (the previous kernel, kept as the reference): every
    cell of each row's window of angles read."""
    monkeypatch.setattr(_stretch_kernels, "vertex_runs_tree", _stretch_kernels.vertex_runs_scan)
    return S._vertex_runs(ra, rb, beta)


# by default seed 37: a cam of 524 edges far from the origin, mu 0.6
@pytest.mark.parametrize("seed", [37, *(pytest.param(s, marks=pytest.mark.slow)
                                        for s in range(200) if s != 37)])
def test_tree_of_bounds_reads_the_runs_of_the_window_scan(seed, monkeypatch):
    """The tree of bounds over ring b's columns (:func:`_vertex_runs_tree`) against the
    window scan that reads every cell, on rings of hundreds to thousands of edges of
    every kind (exact ties of a regular polygon, collinear runs, noise; far from the
    origin too, where the bounds' rounding is largest): the same runs bit for bit; and
    read in blocks of rows (between which a budget's clock may end the search), the
    same runs again."""
    rng = np.random.default_rng(seed)
    kind = KINDS[seed % len(KINDS)]
    n = int(rng.integers(150, 2500))
    pts = outline(rng, kind, n) + (rng.uniform(-1e4, 1e4, 2) if seed % 4 == 1 else 0.0)
    poly = Polygon(pts)
    beta = _beta(float(rng.choice([0.1, 0.3, 0.6, 1.2])), float(rng.choice([0.0, 0.5])))
    ring = _rings(poly)[0]
    monkeypatch.setenv("FCGRASP_JIT", "1")
    tree = S._vertex_runs(ring, ring, beta)
    monkeypatch.setattr(_stretch_kernels, "VERTEX_ROWS", int(rng.integers(7, 300)))
    blocked = S._vertex_runs(ring, ring, beta)
    for sigma in (1.0, -1.0):
        for got, want in zip(blocked[sigma], tree[sigma], strict=True):
            np.testing.assert_array_equal(got, want)
    scan = _scan_runs(monkeypatch, ring, ring, beta)
    reads = 0
    for sigma in (1.0, -1.0):
        reads += scan[sigma][1].size
        for got, want in zip(tree[sigma], scan[sigma], strict=True):
            np.testing.assert_array_equal(got, want)
    assert seed % len(KINDS) == KINDS.index("regular") or reads > 0


def _kth(values, k):
    v = np.sort(np.asarray(values, float))[::-1]
    return float(v[k - 1]) if v.size >= k else 0.0


@pytest.mark.parametrize("seed", seeds(2, 300))
def test_pruned_windows_give_the_same_floor(seed, monkeypatch):
    """The windows read in order of their rows' upper bounds and cut below the
    ``keep``-th value (``_windows`` with ``keep``) against every row read: each row's
    lower bound is the full one wherever that passes the cut, never above it elsewhere,
    the ``keep``-th largest (with the search's value before) is the same, and the
    configurations collected are the same (each row starting at its first long enough
    window).  Short windows too (``short`` 0: the table read however short they are)."""
    rng = np.random.default_rng(seed)
    kind = KINDS[seed % len(KINDS)]
    short = 0 if seed % 2 else 64
    # a regular polygon ties everywhere: its configurations grow fastest
    poly = Polygon(outline(rng, kind, int(rng.integers(30, 300 if kind == "regular" else 1500))))
    beta = _beta(float(rng.choice([0.15, 0.3, 0.6, 1.2])), float(rng.choice([0.0, 0.5])))
    ring = _rings(poly)[0]
    monkeypatch.setenv("FCGRASP_JIT", "1")
    runs = S._vertex_runs(ring, ring, beta)
    for sigma in (1.0, -1.0):
        ptr, first, last = runs[sigma]
        for same in (True, False):
            full, *_ = _stretch_kernels.windows(ptr, first, last, ring.U, ring.U, ring.m,
                                                ring.m, 0.0, False, same)
            for keep in (1, 3, 10):
                for value in (0.0, 0.5 * _kth(full, keep), _kth(full, keep)):
                    got, *_ = _stretch_kernels.windows(ptr, first, last, ring.U, ring.U,
                                                       ring.m, ring.m, 0.0, False, same,
                                                       value, keep, short)
                    kth = max(value, _kth(full, keep))
                    assert max(value, _kth(got, keep)) == kth
                    assert np.all(got <= full)
                    np.testing.assert_array_equal(got[full > kth], full[full > kth])
            # every configuration (floor 0) only on small rings: they grow as n^3
            top = full.max(initial=0.0)
            for floor in ((0.0,) if ring.m <= 100 else ()) + (0.8 * top, top):
                want = _stretch_kernels.windows(ptr, first, last, ring.U, ring.U, ring.m,
                                                ring.m, floor, True, same)
                got = _stretch_kernels.windows(ptr, first, last, ring.U, ring.U, ring.m,
                                               ring.m, floor, True, same, 0.0, 10, short)
                for g, w in zip(got[1:], want[1:], strict=True):
                    np.testing.assert_array_equal(g, w)


@pytest.mark.parametrize("seed", seeds(2, 300))
def test_pruned_single_edge_windows_give_the_same_floor(seed, monkeypatch):
    """The single-edge windows read longest edge first and skipping an edge no longer
    than the ``keep``-th lower bound found so far (one per key) or the search's value
    before: every lower bound kept is the full one, each one left out is at most that
    cut, and the ``keep``-th largest per key (with the value before) is the same."""
    from types import SimpleNamespace

    rng = np.random.default_rng(seed)
    kind = KINDS[seed % len(KINDS)]
    longest = 300 if kind == "regular" else 1500 if seed >= 4 else 400   # (the default's)
    poly = Polygon(outline(rng, kind, int(rng.integers(30, longest))))
    beta = _beta(float(rng.choice([0.15, 0.3, 0.6, 1.2])), float(rng.choice([0.0, 0.5])))
    rings = _rings(poly)
    ring, keys = rings[0], S._Keys(rings)
    monkeypatch.setenv("FCGRASP_JIT", "1")

    def per_key(job, a, p, v):
        best = {}
        for k, val in zip(keys(job, a, p).tolist(), v.tolist(), strict=True):
            best[k] = max(best.get(k, 0.0), val)
        return list(best.values())

    pruned = 0
    for sigma in (1.0, -1.0):
        job = (0, 0, sigma, "squeeze" if sigma > 0 else "expand")
        iv = _Intervals(ring, ring, sigma, beta)
        for same in (True, False):
            (a, p, v), _ = Q._single(iv, ring, ring, same, 0.0, False)
            full = dict(zip(zip(a.tolist(), p.tolist(), strict=True), v.tolist(), strict=True))
            for keep in (1, 3, 10):
                kth_full = _kth(per_key(job, a, p, v), keep)
                for value in (0.0, 0.5 * kth_full, kth_full):
                    bound = SimpleNamespace(value=value, k=keep)
                    (a2, p2, v2), _ = Q._single(iv, ring, ring, same, 0.0, False, bound,
                                                (0, 0))
                    got = dict(zip(zip(a2.tolist(), p2.tolist(), strict=True), v2.tolist(),
                                   strict=True))
                    kth = max(value, kth_full)
                    assert max(value, _kth(per_key(job, a2, p2, v2), keep)) == kth
                    assert all(full[w] == val for w, val in got.items())
                    assert all(w in got for w, val in full.items() if val > kth)
                    pruned += len(full) - len(got)
    assert pruned > 0 or kind == "collinear" or len(full) < 20


def _previous_kernels(monkeypatch):
    """The previous compiled search, kept as the reference: the window scan for the
    runs, every row's windows widened from the first, every single-edge window read."""
    windows, single = _stretch_kernels.windows, Q._single
    monkeypatch.setattr(_stretch_kernels, "vertex_runs_tree", _stretch_kernels.vertex_runs_scan)
    monkeypatch.setattr(_stretch_kernels, "windows", lambda *a, **k: windows(*a[:10]))
    monkeypatch.setattr(Q, "_single", lambda *a: single(*a[:6]))


@pytest.mark.parametrize("seed", seeds(1, 24))
def test_large_outlines_give_the_previous_kernels_plans(seed, monkeypatch):
    """Plans of outlines of 1,000-4,000 edges (smooth, noisy, with a hole) through the
    tree of bounds and the pruned windows, against the previous kernels: the same
    configurations, regions to 1e-9 of the part's size."""
    rng = np.random.default_rng(1000 + seed)
    kind = ("ellipse", "noisy", "rounded", "cam")[seed % 4]
    pts = outline(rng, kind, int(rng.integers(1000, 4000)))
    holes = []
    if seed % 3 == 2:
        c = pts.mean(axis=0)
        r = 0.15 * np.min(np.ptp(pts, axis=0))
        th = np.linspace(0, 2 * np.pi, 400, endpoint=False)[::-1]
        holes = [c + r * np.c_[np.cos(th), np.sin(th)]]
    poly = Polygon(pts, holes=holes)
    mu, margin = float(rng.choice([0.2, 0.3, 0.6])), 0.5
    monkeypatch.setenv("FCGRASP_JIT", "1")
    fast = _plans(poly, mu, margin, 10)
    _previous_kernels(monkeypatch)
    _assert_same_plans(fast, _plans(poly, mu, margin, 10), poly.size)
    assert fast


@pytest.mark.parametrize("seed", [0, 1] + [pytest.param(s, marks=pytest.mark.slow)
                                     for s in range(2, 40)])
def test_inside_any_compiled_is_the_numpy_test_and_brute_force(seed):
    """Configurations inside one of the supers (the distinct search's deferred ones), by
    the compiled sweep, by numpy's loop over the supers, and by a brute force written
    here; starts past a ring's end (cyclic), supers that wrap, supers sharing a first
    stretch (the sweep adds them at one start in the order of their room), supers of
    no interior vertex, and one ring either way round."""
    from fcgrasp.model.stretches._solve import _inside_any
    from fcgrasp.model.stretches._windows import _Configs

    rng = np.random.default_rng(5 + seed)
    same = bool(seed % 2)
    ma, mb = (37, 37 if same else 23) if seed % 4 < 2 else (11, 11 if same else 7)
    n, k = 3000, int(rng.integers(1, 40))
    c = _Configs(rng.integers(0, 2 * ma, n), rng.integers(0, 9, n), rng.integers(0, 2 * mb, n),
                 rng.integers(0, 9, n))
    supers = np.c_[rng.integers(0, 2 * ma, k), rng.integers(0, 15, k),
                   rng.integers(0, 2 * mb, k), rng.integers(0, 15, k)]
    shared = rng.random(k) < 0.4
    supers[shared, :2] = supers[0, :2]
    got = _inside_any(c, supers, ma, mb, same, compiled=True)
    want = _inside_any(c, supers, ma, mb, same)

    def inside(i, k, i2, k2, m):
        return (i - i2) % m + k <= k2

    brute = np.zeros(n, bool)
    for q in range(n):
        for iA, kA, iC, kC in supers:
            ways = [(c.iA[q], c.kA[q], c.iC[q], c.kC[q])]
            if same:
                ways.append((c.iC[q], c.kC[q], c.iA[q], c.kA[q]))
            brute[q] |= any(inside(a, ka, iA, kA, ma) and inside(cc, kc, iC, kC, mb)
                            for a, ka, cc, kc in ways)
    np.testing.assert_array_equal(got, brute)
    np.testing.assert_array_equal(want, brute)
    assert brute.any() and (ma < 37 or not brute.all())


@pytest.mark.parametrize("fraction", [0.5, *(pytest.param(f, marks=pytest.mark.slow)
                                      for f in (0.3, 0.9))])
def test_exclusion_tests_compiled_are_the_numpy_ones(fraction, monkeypatch):
    """The distinct search's exclusion (which configurations are surely a kept plan's
    alternative, and from which smallest region on), by the fused compiled loop and by
    numpy's matrices: the same numbers, on configurations of a curved outline and of a
    part with a hole, around and far from the kept plans, of every smallest region."""
    import fcgrasp as fc

    monkeypatch.setenv("FCGRASP_JIT", "1")
    rng = np.random.default_rng(int(fraction * 10))
    checked = 0
    for name in ("cam", "washer"):
        checked += _exclusion_both_ways(fc.read_part("demo:" + name), fraction, rng,
                                        monkeypatch)
    assert checked > 100, checked


@pytest.mark.parametrize("fraction", [0.5, pytest.param(0.3, marks=pytest.mark.slow)])
def test_the_third_fingers_exclusion_compiled_is_numpys(fraction, monkeypatch):
    """Three fingers' distinct search: which configurations' third finger surely
    overlaps a kept plan's remaining region (``_Exclusion._third_masks``), and so the
    thresholds and copies it masks, by the fused compiled loop and by numpy's
    matrices: the same numbers."""
    import fcgrasp as fc

    monkeypatch.setenv("FCGRASP_JIT", "1")
    rng = np.random.default_rng(int(fraction * 10) + 1)
    checked = 0
    for name in ("cam", "washer"):
        checked += _exclusion_both_ways(fc.read_part("demo:" + name), fraction, rng,
                                        monkeypatch, third=True)
    assert checked > 100, checked


def _exclusion_both_ways(poly, fraction, rng, monkeypatch, third=False):
    import fcgrasp as fc
    from fcgrasp.model import stretches
    from fcgrasp.model.stretches._windows import _Configs

    plans = fc.plan(poly, fingers=3 if third else 2, mu=0.4, top=4)
    kept = [(p.regions, p.region_edges) for p in plans]
    rings = _rings(poly)
    excl = stretches._Exclusion(rings, poly, kept, fraction, third=third)
    beta = np.arctan(0.4) - np.radians(2.0)
    ivs = {(a, b, 1.0): _Intervals(rings[a], rings[b], 1.0, beta)
           for a in range(len(rings)) for b in range(len(rings))}
    checked = 0
    where = stretches._positions(rings)
    near = [[where[int(e[0])] for e in edges] for _, edges in kept]    # (ring, position)
    for x in range(len(rings)):
        for y in range(len(rings)):
            n = 4000
            k = 60 if rings[x].m > 100 else 6
            cfg = _Configs(rng.integers(0, 2 * rings[x].m, n), rng.integers(0, k, n),
                           rng.integers(0, 2 * rings[y].m, n), rng.integers(0, k, n))
            # half of them about a kept plan's regions
            for q in range(0, n, 2):
                (ra, pa), (rc, pc) = near[q % len(near)][:2]
                if (ra, rc) == (x, y):
                    cfg.iA[q] = pa + rng.integers(-k // 2, 3) + rings[x].m
                    cfg.iC[q] = pc + rng.integers(-k // 2, 3) + rings[y].m
            t = rng.uniform(0, 1.2, n) * poly.size / 8
            job = (x, y, 1.0, "squeeze")
            results = []
            for cells in (0, 10 ** 12):             # fused, then numpy
                monkeypatch.setattr(X, "FUSED_THIRD" if third else "FUSED_CELLS", cells)
                if not third:
                    monkeypatch.setattr(X, "FUSED_SIMILAR", cells)
                arcs = excl._arcs(x, y) if third else None
                results.append((excl.threshold(rings, job, cfg, ivs),
                                excl.similar(rings, job, cfg, t, ivs),
                                None if arcs is None else
                                np.array([m for _, _, m in excl._third_masks(x, y, cfg, arcs)])))
            (tf, sf, mf), (tn, sn, mn) = results
            np.testing.assert_array_equal(tf, tn)
            np.testing.assert_array_equal(sf, sn)
            checked += int(np.isfinite(tn).sum()) + int(sn.sum())
            if mn is not None:                      # the third finger's own test
                np.testing.assert_array_equal(mf, mn)
                checked += int(mn.sum())
    return checked


def _excess_cases(rng, n):
    """Regions' ends ``(s0, s1, e0, e1)``, smallest regions ``t`` and arcs ``[k0, k1]``,
    near-degenerate ones included: a start or end fixed to a point, ``t`` exactly the
    longest region, an arc of zero length, ends on the arc's ends, no region at all."""
    s0 = rng.uniform(0, 4, n)
    s1 = s0 + rng.choice([0.0, 0.5, 2.0], n) * rng.uniform(0, 1, n)
    e0 = s0 + rng.uniform(-1, 4, n)
    e1 = np.maximum(e0, s0) + rng.choice([0.0, 1.0, 3.0], n) * rng.uniform(0, 1, n)
    t = rng.uniform(0, 1, n) * (e1 - s0)
    t[::7] = (e1 - s0)[::7]                         # one region only: [s0, e1]
    t[::11] = (e1 - s0)[::11] + 0.5                 # none
    k0 = rng.uniform(-1, 7, n)
    k1 = k0 + rng.choice([0.0, 0.3, 2.0, 6.0], n) * rng.uniform(0, 1, n)
    for j, v in ((0, s0), (1, s1), (2, e0), (3, e1)):  # arc ends on the regions' ends
        pick = rng.uniform(0, 1, n) < 0.1
        (k0 if j % 2 == 0 else k1)[pick] = v[pick]
    k1 = np.maximum(k1, k0)
    return np.stack([s0, s1, e0, e1], axis=1), t, k0, k1


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 20))])
def test_least_excess_is_the_least_over_every_region(seed):
    """The distinct search's exact copy test (``_Exclusion._least_excess``: the least of
    ``overlap - fraction * min(length, partner's)`` over every region whose ends lie in
    their intervals and that is at least ``t`` long) against a dense raster of regions
    written here: never above the raster's least (it is the least), and below it by
    at most the raster's step times the function's slope (and the loosening ``eps``
    of the bounds, which the search sets to its tolerance: a region ``[a, a + t]``
    may measure ``t`` less a rounding); the compiled loop's cell (``_least_excess``)
    gives the same number bit for bit."""
    rng = np.random.default_rng(seed)
    n = 300
    s, t, k0, k1 = _excess_cases(rng, n)
    least_ = _stretch_kernels._load()["_least_excess"]
    for f in (0.25, 0.5, 0.8):
        eps = 1e-9
        got = np.array([S._Exclusion._least_excess(s[q:q + 1], t[q:q + 1], k0[q:q + 1],
                                                   k1[q:q + 1], f, eps)[0, 0]
                        for q in range(n)])
        cell = np.array([least_(*s[q], t[q], k0[q], k1[q], f, eps) for q in range(n)])
        np.testing.assert_array_equal(got, cell)
        g = np.linspace(0, 1, 161)
        for q in range(n):
            a = s[q, 0] + g[:, None] * (s[q, 1] - s[q, 0])
            b = s[q, 2] + g[None, :] * (s[q, 3] - s[q, 2])
            a, b = np.broadcast_arrays(a, b)
            # the raster, and the shortest regions exactly (b = a + t), where they fit
            a = np.r_[a.ravel(), a[:, 0], b[0] - t[q]]
            b = np.r_[b.ravel(), a[:161] + t[q], b[0]]
            ok = (b - a >= t[q]) & (a >= s[q, 0]) & (a <= s[q, 1]) & (b >= s[q, 2]) & \
                (b <= s[q, 3])
            if not ok.any():
                assert got[q] == -np.inf or t[q] > s[q, 3] - s[q, 0] - 1e-9, q
                continue
            a, b = a[ok], b[ok]
            raster = (np.maximum(0.0, np.minimum(b, k1[q]) - np.maximum(a, k0[q]))
                      - f * np.minimum(b - a, k1[q] - k0[q])).min()
            step = max(s[q, 1] - s[q, 0], s[q, 3] - s[q, 2]) / 160
            assert got[q] <= raster + 1e-12, (q, got[q], raster)
            assert got[q] >= raster - 2 * (1 + f) * (step + eps), (q, got[q], raster)


def test_member_is_isin():
    """The exclusion's look-up of configurations already read: np.isin by binary search."""
    from fcgrasp.model.stretches._exclusion import _member

    rng = np.random.default_rng(3)
    for size in (1, 2, 50, 3000):
        known = np.unique(rng.integers(0, 5000, size))
        codes = rng.integers(-10, 5010, 20000)
        np.testing.assert_array_equal(_member(codes, known), np.isin(codes, known))


@pytest.mark.parametrize("seed", [10, *(pytest.param(s, marks=pytest.mark.slow)
                                        for s in range(160) if s != 10)])
def test_guessed_floors_give_the_plans_of_no_guess(seed, monkeypatch):
    """Where the lower bounds fill fewer keys than ``top`` (one key holds many of the top
    configurations of a smooth outline), the floor guessed from the keys' values gives
    the plans of the search without a guess (which collects every configuration): the
    same configurations, ties included, regions to 1e-9 of the part's size.  The cases
    ask for half of the keys or all of them, so that most fill fewer keys than they ask
    for: the first search must guess exactly then.  Where the guesses keep too few
    (the own-optimum filter drops most configurations), the floor is halved and fixed:
    seeds 10 and 14, by default, need that to find ``top``."""
    rng = np.random.default_rng(7000 + seed)
    kind = ("ellipse", "cam", "rounded", "regular", "noisy", "star")[seed % 6]
    poly = Polygon(outline(rng, kind, int(rng.integers(16, 60))))
    mu, margin = float(rng.choice([0.15, 0.3, 0.6])), float(rng.choice([0.0, 0.5]))
    monkeypatch.setenv("FCGRASP_JIT", "1" if seed % 2 else "0")
    taken = []
    candidates = Q._candidates

    def spy(rings, bound, *args, **kw):
        guesses = kw.get("guesses")
        fixed = bound.fixed
        out = candidates(rings, bound, *args, **kw)
        if guesses is not None:     # the first search: it guesses where the keys allow
            seen = np.sort(bound.best[bound.best > 0])[::-1]
            m = min(bound.k, seen.size)
            ranks = [-(-m // 4), -(-m // 2)] + ([seen.size] if seen.size < bound.k else [])
            above = [g for g in (seen[r - 1] * (1 - S.TIE) for r in ranks if r)
                     if g > bound.value * (1 - S.TIE)]
            taken.append(bool(above))
            assert bound.fixed == fixed and bound.start == (above[0] if above else 0.0)
        return out

    monkeypatch.setattr(Q, "_candidates", spy)
    keys = 2 * sum(r.m for r in _rings(poly))
    top = int(rng.integers(1, 3) * keys // 2)          # half of every key, or all
    fast = _plans(poly, mu, margin, top)
    monkeypatch.setattr(Q, "_GUESS", False)
    _assert_same_plans(fast, _plans(poly, mu, margin, top), poly.size)


def test_a_stretchs_ends_are_its_polylines_ends():
    """``_stretch_ends`` (the two ends the ranking's geometric key reads, for the
    canonical placement) is bit for bit the first and last point of ``_polyline``'s
    region, trimming included: stretches from anywhere on an edge to anywhere along
    the ring, on every kind of outline, many starting or ending exactly at a vertex (or
    a hair from it) where the polyline drops its piece of the edge beyond."""
    rng = np.random.default_rng(81)
    trimmed = 0
    for case in range(60):
        poly = Polygon(outline(rng, KINDS[case % len(KINDS)], int(rng.integers(8, 60))))
        ring = _rings(poly)[0]
        m = ring.m
        for _ in range(40):
            i, k = int(rng.integers(0, 3 * m)), int(rng.integers(0, min(m - 1, 6)))
            L = float(ring.L[i % m])
            s0 = float(rng.choice([0.0, L, L * (1 - 1e-14), rng.uniform(0, L)]))
            # the stretch's length from s0 to a point of its last edge (or its ends)
            j = i % m + m
            to_last = L - s0 + float(ring.U[j + k] - ring.U[j + 1]) if k else -s0
            last = float(ring.L[(i + k) % m])
            t = to_last + float(rng.choice([0.0, 1e-14 * last, last, rng.uniform(0, last)]))
            if k == 0:
                t = float(rng.uniform(0, L - s0)) if L > s0 else 0.0
            pts, _ = P._polyline(ring, i, k, s0, t)
            got = np.array(P._stretch_ends(ring, i, k, s0, t))
            assert got.tobytes() == np.stack((pts[0], pts[-1])).tobytes()
            trimmed += len(pts) < k + 2
    assert trimmed > 200


@pytest.mark.parametrize("seed", seeds(2, 12))
def test_a_collection_read_in_blocks_of_rows_is_the_whole_one(seed):
    """The compiled collection read in blocks of rows (a budget check before each, the
    sparse table built once) gives the configurations of the collection read at once,
    in the same order, with and without a kept plan's copies left out."""
    rng = np.random.default_rng(seed)
    poly = smooth_outline(rng, "ellipse", int(rng.integers(500, 900)))
    ss = S.StretchSearch(poly, float(rng.uniform(0.3, 1.0)), 0.5)
    best = ss.pairs(top=1)[0]
    excl = X._Exclusion(ss.rings, poly, [(best.regions, best.region_edges)], 0.5)
    ring = ss.rings[0]
    floor = best.min_length * float(rng.uniform(0.5, 0.9))
    for sigma in (1.0, -1.0):
        ptr, first, last = ss.runs[0, 0][sigma]
        for copies in (None, excl.copy_columns(ss.rings, 0, 0, floor)):
            ex, exs = copies if copies is not None else (None, None)
            calls = []
            args = (ptr, first, last, ring.U, ring.U, ring.m, ring.m, floor, True, True)
            whole = _stretch_kernels.windows(*args, 0.0, 1, ex=ex, exs=exs)
            blocks = _stretch_kernels.windows(*args, 0.0, 1, ex=ex, exs=exs,
                                              between=lambda c=calls: c.append(1))
            assert len(calls) == -(-ring.m // _stretch_kernels.COLLECT_ROWS) > 1
            for w, b in zip(whole[1:], blocks[1:], strict=True):
                np.testing.assert_array_equal(w, b)


@pytest.mark.parametrize("seed", seeds(2, 60))
def test_a_collection_passing_over_copies_in_runs_is_the_one_read_start_by_start(seed):
    """The compiled collection of a distinct round passes over the starts of stretch 2
    whose every stretch is a kept plan's copy in runs, and the window lengths whose
    every configuration is one (``gallop``, the default), and on one ring makes only the
    configurations the search keeps: it gives the configurations the search keeps, in
    order, of the collection that reads and makes every one (the reference), at floors
    around the kept plans' lengths, with one kept plan or two (the first two plans), at
    fractions where copies are rare and common."""
    rng = np.random.default_rng(seed)
    kind = str(rng.choice(["ellipse", "star", "cam"]))
    poly = smooth_outline(rng, kind, int(rng.integers(300, 800)))
    ss = S.StretchSearch(poly, float(rng.uniform(0.2, 1.0)), 0.5)
    found = ss.pairs(top=2)
    kept = [(p.regions, p.region_edges) for p in found[:int(rng.integers(1, 3))]]
    fraction = float(rng.choice([0.25, 0.5, 0.8]))
    excl = X._Exclusion(ss.rings, poly, kept, fraction)
    ring = ss.rings[0]
    passed = 0
    for floor in found[0].min_length * rng.uniform(0.3, 1.0, 3):
        copies = excl.copy_columns(ss.rings, 0, 0, float(floor))
        assert copies is not None
        ex, exs = copies
        for sigma in (1.0, -1.0):
            ptr, first, last = ss.runs[0, 0][sigma]
            args = (ptr, first, last, ring.U, ring.U, ring.m, ring.m, float(floor), True,
                    True, 0.0, 1)
            runs = _stretch_kernels.windows(*args, ex=ex, exs=exs)
            each = _stretch_kernels.windows(*args, ex=ex, exs=exs, gallop=False)
            # (on one ring the fast collection makes only what the search keeps)
            kept = [W._both_kept(W._Configs(*got[1:]), ring, ring, True)
                    for got in (runs, each)]
            for f in ("iA", "kA", "iC", "kC"):
                np.testing.assert_array_equal(getattr(kept[0], f), getattr(kept[1], f))
            every = _stretch_kernels.windows(*args, gallop=False)
            passed += every[1].size - each[1].size
    assert passed > 0


@pytest.mark.parametrize("third", [False, True])
def test_thresholds_kept_across_rounds_are_each_rounds_own(third):
    """The rounds of one collection keep each configuration's threshold of the kept
    plans (``_Exclusion.thresholds``) and read only the plans kept since: round after
    round (one, two, then four plans kept, then a list that is not the earlier one
    continued, which starts again), on random subsets of a job's configurations, the
    thresholds are those the round's own exclusion computes from scratch."""
    from types import SimpleNamespace

    from fcgrasp.model import stretches
    from fcgrasp.model.stretches._windows import _Configs

    poly = fc.read_part("demo:cam")
    rng = np.random.default_rng(31 + third)
    plans = fc.plan(poly, fingers=3 if third else 2, mu=0.4, top=6)
    kept = [(p.regions, p.region_edges) for p in plans]
    rings = _rings(poly)
    beta = np.arctan(0.4) - np.radians(2.0)
    ivs = {(a, b, 1.0): _Intervals(rings[a], rings[b], 1.0, beta)
           for a in range(len(rings)) for b in range(len(rings))}
    where = stretches._positions(rings)
    (x, pa), (y, pc) = (where[int(e[0])] for e in kept[0][1][:2])
    n, k = 3000, 40
    cfg = _Configs(pa + rng.integers(-k, k, n) + rings[x].m, rng.integers(0, k, n),
                   pc + rng.integers(-k, k, n) + rings[y].m, rng.integers(0, k, n))
    J = SimpleNamespace(cfg=cfg, taus=None)
    job = (x, y, 1.0, "squeeze")
    finite = 0
    for upto in ([0], [0, 1], [0, 1, 2, 3], [1, 2], [1, 2, 4, 5]):
        excl = stretches._Exclusion(rings, poly, [kept[i] for i in upto], 0.5, third=third)
        for _ in range(2):
            idx = np.sort(rng.choice(n, n // 2, replace=False))
            got = excl.thresholds(rings, job, J, idx, ivs)
            want = excl.threshold(rings, job, cfg.take(idx), ivs)
            np.testing.assert_array_equal(got, want)
            finite += int(np.isfinite(want).sum())
    assert finite > 1000, finite


@pytest.mark.parametrize("m", [(7, 9), (3000, 5000), (60_000, 100_000), (100_000, 100_000)])
def test_the_exclusions_codes_tell_configurations_apart_on_long_rings(m):
    """The codes of configurations a distinct round has read (``_Exclusion._codes``)
    and their lookup (``_member``): equal only for the same configuration (starts
    taken round their ring) and found exactly, on rings of a few edges to 100,000 (where
    one int64 cannot hold a code: a record of two instead)."""
    from types import SimpleNamespace

    rng = np.random.default_rng(sum(m))
    rings = [SimpleNamespace(m=m[0]), SimpleNamespace(m=m[1])]
    n = 4000

    def draw():
        return (rng.integers(0, 2 * m[0], n), rng.integers(0, min(m[0], 60), n),
                rng.integers(0, 2 * m[1], n), rng.integers(0, min(m[1], 60), n))

    seen, asked = draw(), draw()
    # half of those asked are ones seen, some with their starts a turn further round
    half = rng.random(n) < 0.5
    for a, b, ring in zip(asked, seen, (m[0], 1, m[1], 1), strict=True):
        a[half] = b[half] + (ring if ring > 1 else 0) * rng.integers(0, 2, half.sum()) \
            * (b[half] < ring)
    known = np.unique(X._Exclusion._codes(rings, 0, 1, *seen))
    got = X._member(X._Exclusion._codes(rings, 0, 1, *asked), known)
    def reduced(rows):
        return [(int(a) % m[0], int(ka), int(c) % m[1], int(kc))
                for a, ka, c, kc in zip(*rows, strict=True)]

    as_set = set(reduced(seen))
    want = np.array([row in as_set for row in reduced(asked)])
    np.testing.assert_array_equal(got, want)
    assert want.sum() >= n // 3 and (~want).sum() >= n // 10


def test_two_configurations_a_wrapped_int64_would_confuse_have_two_codes():
    """On rings of 100,000 edges a code ``first * mb (mb + 1) + second`` passes 2**63:
    two configurations whose codes differ by 2**64 exactly (built here) would wrap to
    one int64; their codes differ, and neither is read as the other."""
    from types import SimpleNamespace

    ma = mb = 100_000
    rings = [SimpleNamespace(m=ma), SimpleNamespace(m=mb)]
    K = mb * (mb + 1)
    df = -(-2 ** 64 // K)                   # df K - 2**64 = r, 0 <= r < K
    r = df * K - 2 ** 64
    f1, s1 = 12_345, r + 17
    f2, s2 = f1 + df, s1 - r
    assert (f2 * K + s2) - (f1 * K + s1) == 2 ** 64 and f2 < ma * (ma + 1)
    # a code's parts: first = iA (ma + 1) + kA, second = iC (mb + 1) + kC
    iA, kA = np.divmod(np.array([f1, f2]), ma + 1)
    iC, kC = np.divmod(np.array([s1, s2]), mb + 1)
    codes = X._Exclusion._codes(rings, 0, 1, iA, kA, iC, kC)
    assert codes[0] != codes[1]
    known = np.unique(codes[:1])
    assert X._member(codes, known).tolist() == [True, False]
