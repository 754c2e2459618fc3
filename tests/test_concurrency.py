"""Three fingers with friction without HiGHS (fcgrasp.grippers.three_fingers._concurrency)
against the HiGHS programs it replaces, kept in the package as the reference
(``FCGRASP_JIT=0``): the dense simplex against HiGHS on random programs, degenerate ones
included; the closed form of the concurrency region (Helly, Farkas) against a program
that looks for a common point of the six half-planes; every objective of every piece;
the best piece of each row; the growth along the boundary; whole plans."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.core import _simplex
from fcgrasp.grippers.three_fingers import _concurrency as K
from fcgrasp.grippers.three_fingers import _concurrent as C
from fcgrasp.grippers.three_fingers import grow_concurrent
from fcgrasp.io.parts import DEMO_PARTS, demo_part
from fcgrasp.model.polygon import Polygon

from ._highs import linprog
from .shapes import random_polygon
from .test_stretches import smooth_outline


@pytest.fixture(autouse=True)
def _compiled(monkeypatch):
    """Each test chooses its path; the compiled one is loaded (compiled once, cached)."""
    monkeypatch.setenv("FCGRASP_JIT", "1")
    assert K._LOOPS.get() is not None


def _lp_cases(rng, count):
    for it in range(count):
        m, n = int(rng.integers(1, 30)), int(rng.integers(1, 9))
        A = rng.normal(size=(m, n))
        b = rng.normal(size=m)
        if it % 4 == 1:                         # sparse rows, zero right-hand sides
            A[rng.random((m, n)) < 0.5] = 0
            b[rng.random(m) < 0.5] = 0.0
        if it % 4 == 2:                         # repeated and parallel rows
            k = int(rng.integers(0, m))
            A = np.vstack([A, A[k], 2 * A[k]])
            b = np.r_[b, b[k], 2 * b[k]]
        if it % 4 == 3:                         # integers: exact ties everywhere
            A = rng.integers(-2, 3, size=A.shape).astype(float)
            b = rng.integers(-1, 3, size=len(A)).astype(float)
        if it % 5 != 4:                         # bounded, but for some
            A = np.vstack([A, np.ones((1, n))])
            b = np.r_[b, 10.0]
        yield rng.normal(size=n), A, b


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1])
def test_dense_simplex_matches_highs(seed):
    """Status, optimum and feasibility of the simplex against HiGHS on 1,500 programs."""
    rng = np.random.default_rng(seed)
    solved = 0
    for c, A, b in _lp_cases(rng, 1500):
        m, n = A.shape
        st, x = _simplex.lp_max(c, A, b)
        ref = linprog(-c, A_ub=A, b_ub=b, bounds=[(0, None)] * n, method="highs")
        assert (st == 0) == (ref.status == 0), (st, ref.status, A, b, c)
        if ref.status == 2:
            assert st == 1
        if ref.status == 3:
            assert st == 2
        if st == 0:
            solved += 1
            assert c @ x == pytest.approx(-ref.fun, abs=1e-7, rel=1e-9)
            assert (A @ x - b).max() <= 1e-9 and x.min() >= -1e-12
    assert solved > 200


def _random_block(rng):
    """A piece of three random features: arcs narrower than pi (zero-width ones too), a
    random side; positions of order one."""
    a = rng.uniform(-1, 1, (3, 2))
    ang = rng.uniform(0, 2 * np.pi, 3)
    t = np.c_[np.cos(ang), np.sin(ang)]
    L = rng.uniform(0.05, 1, 3)
    c = rng.uniform(0, 2 * np.pi, 3)
    w = rng.uniform(0, 1.2, 3) * (rng.random(3) > 0.1)
    sigma = rng.choice([-1.0, 1.0], 3)
    return C._Block.on_edges(a, t, L, c - w, c + w, sigma, 0)


def _depth_lp(blk, x):
    """How deep a common point of the six half-planes of finger points x (3, 2) can be
    (HiGHS, written from the definition: p - x_i in sigma_i cone(arc_i)): > 0 they meet
    with room, < 0 they miss."""
    rows, rhs = [], []
    for i in range(3):
        for ang, s in ((blk.lo_ang[i], blk.sigma[i]), (blk.hi_ang[i], -blk.sigma[i])):
            u = np.array([np.cos(ang), np.sin(ang)])
            # s (u x (p - x)) >= delta  ->  -s(-u_y px + u_x py) + delta <= -s (u x x)
            rows.append([s * u[1], -s * u[0], 1.0])
            rhs.append(-s * (u[0] * x[i, 1] - u[1] * x[i, 0]))
    res = linprog([0, 0, -1], A_ub=rows, b_ub=rhs, bounds=[(None, None)] * 2 + [(None, 1.0)],
                  method="highs")
    return -res.fun


@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow)])
def test_closed_form_decides_whether_the_half_planes_meet(seed):
    """sum_i W[f, i] . x_i <= 0 for every facet iff the wedges' half-planes meet, on
    1,000 random pieces and finger points (the closed form's depth: its largest facet
    value, against the program's)."""
    rng = np.random.default_rng(10 + seed)
    both = [0, 0]
    for _ in range(1000):
        blk = _random_block(rng)
        W = K.facets(blk)
        x = rng.uniform(-1.5, 1.5, (3, 2))
        depth = _depth_lp(blk, x)
        closed = -max((np.sum(W[f] * x) for f in range(len(W))), default=-np.inf)
        if abs(depth) < 1e-9:
            continue                            # a tie: either answer is right
        normals_span = len(W) > 0
        if normals_span:
            assert (closed > 0) == (depth > 0), (depth, closed)
            if depth < 1:                       # bounded depth: the same number
                assert closed == pytest.approx(depth, abs=1e-9)
        both[depth > 0] += 1
    assert min(both) > 100


def _triples(rng, count):
    """Random rows of three features; every third has two fingers side by side on one
    edge (its first two features one: their regions apart, in order)."""
    for k in range(count):
        poly = random_polygon(rng)
        e = rng.choice(poly.n_edges, 3, replace=False)
        if k % 3 == 2:
            e[1] = e[0]
        mu = float(rng.choice([0.1, 0.3, 0.5, 1.0, rng.uniform(0.05, 1.5)]))
        margin = float(np.radians(rng.choice([0.0, 0.5, 2.0])))
        a, b = poly.starts[e] / poly.size, poly.ends[e] / poly.size
        nrm = poly.normals[e]
        center = np.arctan2(-nrm[:, 1], -nrm[:, 0])
        L = np.hypot(*(b - a).T)
        yield a, (b - a) / L[:, None], L, center, np.full(3, np.arctan(mu)), margin


def _same(ref, got, ok, key):
    for r, g, o in zip(ref, got, ok, strict=True):
        if r is None or key(r) <= 1e-9:
            # HiGHS found nothing, or regions of no length: a tie, and the kernel may
            # reject a piece whose regions are points (witnesses to its tolerance)
            assert not o or key(g) <= 1e-7
        else:
            assert o, key(r)
            assert key(g) == pytest.approx(key(r), abs=1e-9)


SEEDS = [0] + [pytest.param(k, marks=pytest.mark.slow) for k in range(1, 8)]


@pytest.mark.parametrize("seed", SEEDS)
def test_every_objective_matches_highs(seed):
    """The four programs of a piece (max-min, free levels, one region grown, deepest
    placement) by the kernel and by HiGHS, on every piece of 8 random triples (120
    under ``-m slow``)."""
    rng = np.random.default_rng(20 + seed)
    count = 0
    doubled = 0
    for a, t, L, center, half, margin in _triples(rng, 8):
        order = bool(np.all(a[0] == a[1]))
        blocks = C._blocks(a, t, L, center, half, margin, 0, order)
        if not blocks:
            continue
        ref = C._solve_blocks_lp(blocks)
        doubled += order and any(x is not None for x in ref)
        got, ok = K.solve(blocks)
        _same(ref, got, ok, lambda x: x[6])
        count += len(blocks)
        for blk, x in zip(blocks, ref, strict=True):
            if x is None or C._smallest(blk, x) <= 1e-6:
                continue
            levels = C._lengths(blk, x)
            fixed = levels * np.array([1.0, 0.9, 0.8])
            free = np.array([False, True, True])
            for kind, kw, key in (
                    (K.FREE, dict(fixed=fixed, free=free), lambda v: v[6]),
                    (K.GROW, dict(fixed=fixed, grow=1), lambda v, b=blk: C._lengths(b, v)[1]),
                    (K.DEEP, dict(fixed=fixed, deep=True), lambda v: v[6])):
                r = C._solve_blocks_lp([blk], **kw)
                g, o = K.solve([blk], kind, fixed, free if kind == K.FREE else None,
                               kw.get("grow", 0))
                _same(r, g, o, key)
                for v in (*r, *(g[o] if o.any() else [])):
                    if v is not None and blk.order:      # the regions apart, in order
                        assert v[3] <= v[1] + 1e-9
    assert count > 50 and doubled > 0, (count, doubled)


@pytest.mark.parametrize("seed", SEEDS)
def test_best_piece_of_each_row_matches(seed, monkeypatch):
    """The compiled search of a row's pieces (sub-arcs written as loops) finds the level
    the HiGHS search finds, on 20 random triples with and without a margin (160 under
    ``-m slow``)."""
    rng = np.random.default_rng(30 + seed)
    rows = list(_triples(rng, 20))
    A = np.array([r[0] for r in rows])
    b = A + np.array([r[1] * r[2][:, None] for r in rows])
    center, half = np.array([r[3] for r in rows]), np.array([r[4] for r in rows])
    for margin in (0.0, np.radians(0.5)):
        got = C._best_blocks(A, b, center, half, margin, 1.0)
        monkeypatch.setenv("FCGRASP_JIT", "0")
        ref = C._best_blocks(A, b, center, half, margin, 1.0)
        monkeypatch.setenv("FCGRASP_JIT", "1")
        held = doubled = 0
        for (rb, rl), (gb, gl) in zip(ref, got, strict=True):
            if rb is None:
                assert gb is None or gl <= 1e-7
                continue
            held += 1
            doubled += rb.order
            assert gb is not None and gl == pytest.approx(rl, abs=1e-9)
            assert gb.order == rb.order
        assert held > 5 and doubled > 0


@pytest.mark.parametrize("kind", ["ellipse", pytest.param("star", marks=pytest.mark.slow)])
def test_growth_along_the_boundary_matches(kind, monkeypatch):
    """Stretches grown by the kernel (an auxiliary variable per finger and facet) and by
    HiGHS: the same stretches, the same levels."""
    rng = np.random.default_rng(5)
    for _ in range(2 if kind == "ellipse" else 6):      # the star: -m slow
        poly = Polygon(smooth_outline(rng, kind, 48))
        n = poly.n_edges
        e0 = int(rng.integers(n))
        edges = (e0, (e0 + n // 3) % n, (e0 + 2 * n // 3) % n)
        got = grow_concurrent(poly, edges, mu=0.5, margin=np.radians(0.5))
        monkeypatch.setenv("FCGRASP_JIT", "0")
        ref = grow_concurrent(poly, edges, mu=0.5, margin=np.radians(0.5))
        monkeypatch.setenv("FCGRASP_JIT", "1")
        assert (got is None) == (ref is None)
        if ref is not None:
            assert got[0] == ref[0]
            assert np.sort(got[1].levels) == pytest.approx(np.sort(ref[1].levels),
                                                           abs=1e-9 * poly.size)


def _plans(part, monkeypatch, jit):
    monkeypatch.setenv("FCGRASP_JIT", jit)
    return fc.plan(part, fingers=3, mu=0.5, top=5)


PARTS = [pytest.param(n, marks=pytest.mark.slow) if n in ("cam", "washer", "blob") else n
         for n in DEMO_PARTS]


@pytest.mark.parametrize("name", PARTS)
def test_plans_equal_the_highs_plans(name, monkeypatch):
    """Whole plans: the same configurations (edges, mode), the same region lengths to
    1e-9 of the part's size (where the optimum is not unique, as on a rectangle's
    symmetric sides, the placement may differ: both are optima)."""
    part = demo_part(name)
    _same_plans(part, _plans(part, monkeypatch, "1"), _plans(part, monkeypatch, "0"))


def test_witnesses_lie_in_every_half_plane():
    """The witness reported for each corner grasp of a piece is a common point of its
    six half-planes (the definition, evaluated here)."""
    rng = np.random.default_rng(8)
    checked = 0
    for _ in range(40):
        poly = random_polygon(rng)
        e = rng.choice(poly.n_edges, 3, replace=False)
        a, b = poly.starts[e], poly.ends[e]
        nrm = poly.normals[e]
        center = np.arctan2(-nrm[:, 1], -nrm[:, 0])
        piece = C.concurrent_regions(a[None], b[None], center[None],
                                     np.full((1, 3), np.arctan(0.6)), np.radians(0.5),
                                     poly.size)[0]
        if piece is None:
            continue
        tan = (b - a) / poly.lengths[e][:, None]
        for corner, p in zip(np.array(list(np.ndindex(2, 2, 2))), piece.witness, strict=True):
            s = np.where(corner == 0, piece.lo, piece.hi)
            x = a + s[:, None] * tan
            for i in range(3):
                for ang, sg in ((piece.arcs[0][i], piece.sigma[i]),
                                (piece.arcs[1][i], -piece.sigma[i])):
                    u = np.array([np.cos(ang), np.sin(ang)])
                    d = p - x[i]
                    assert sg * (u[0] * d[1] - u[1] * d[0]) >= -1e-9 * poly.size
            checked += 1
    assert checked > 40


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(10))
def test_random_parts_plans_equal_the_highs_plans(seed, monkeypatch):
    rng = np.random.default_rng(40 + seed)
    for _ in range(5):
        part = random_polygon(rng)
        _same_plans(part, _plans(part, monkeypatch, "1"), _plans(part, monkeypatch, "0"))


def _same_plans(part, got, ref):
    """Rank by rank the same sorted lengths (to 1e-9 of the size); the same configuration
    at every rank not tied with another (tied plans are ordered by their placement, which
    is not unique where the optimum is not)."""
    assert len(got) == len(ref)
    tol = 1e-9 * part.size
    keys = [np.sort(p.lengths) for p in ref]
    for k, (g, r) in enumerate(zip(got, ref, strict=True)):
        assert np.sort(g.lengths) == pytest.approx(keys[k], abs=tol)
        tied = any(j != k and len(keys[j]) == len(keys[k])
                   and np.allclose(keys[j], keys[k], rtol=0, atol=1e-6 * part.size)
                   for j in range(len(keys)))
        if not tied:
            assert (g.mode, g.region_edges) == (r.mode, r.region_edges)
