"""Regions along the boundary (fcgrasp.model.stretches) against methods that share none of its
code: a fine raster of the two contact parameters (largest square of force-closure
samples on the torus of the two arc lengths) and the general closure test on sampled
grasps, vertices inside regions with every normal between the two edges'."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.ndimage import minimum_filter
from shapely.geometry import Polygon as ShapelyPolygon

from fcgrasp.core.closure import is_force_closure
from fcgrasp.model.polygon import Polygon
from fcgrasp.model.stretches import two_finger_stretches

from .shapes import random_polygon


def smooth_outline(rng, kind, n):
    """A counter-clockwise ring of ``n`` vertices on a smooth closed curve."""
    th = np.linspace(0, 2 * np.pi, n, endpoint=False) + rng.uniform(0, 2 * np.pi / n)
    size = rng.uniform(5, 200)
    if kind == "ellipse":
        a, b = 1.0, rng.uniform(0.3, 1.0)
        pts = np.c_[a * np.cos(th), b * np.sin(th)]
    elif kind == "star":
        r = np.ones_like(th)
        for k in range(2, 6):
            r += rng.uniform(0, 0.06) * np.cos(k * th + rng.uniform(0, 2 * np.pi))
        pts = np.c_[r * np.cos(th), r * np.sin(th)]
    elif kind == "cam":
        c, w = rng.uniform(0, 2 * np.pi), rng.uniform(0.4, 1.0)
        dth = np.angle(np.exp(1j * (th - c)))
        r = 1 + rng.uniform(0.2, 0.5) * np.exp(-(dth / w) ** 2)
        pts = np.c_[r * np.cos(th), r * np.sin(th)]
    else:                                               # rounded rectangle
        w, h, rad = 1.0, rng.uniform(0.3, 1.0), rng.uniform(0.05, 0.3)
        box = ShapelyPolygon([(0, 0), (w, 0), (w, h), (0, h)]).buffer(
            rad, quad_segs=max(2, n // 8))
        pts = np.asarray(box.exterior.coords)[:-1]
        if ShapelyPolygon(pts).exterior.is_ccw is False:
            pts = pts[::-1]
    return pts * size


def raster_optimum(ring, mu, margin_deg, samples):
    """Largest smallest region of two friction fingers on a fine raster: arc-length
    samples of the ring, each with its edge's normal; the largest k x k block of
    force-closure pairs (one mode), on the torus.  Returns (length, spacing)."""
    ring = np.asarray(ring, float)
    seg = np.roll(ring, -1, axis=0) - ring
    L = np.hypot(*seg.T)
    cum = np.concatenate([[0], np.cumsum(L)])
    h = cum[-1] / samples
    s = (np.arange(samples) + 0.5) * h
    e = np.searchsorted(cum, s, side="right") - 1
    pts = ring[e] + (s - cum[e])[:, None] * (seg[e] / L[e, None])
    tang = seg[e] / L[e, None]
    inward = np.c_[-tang[:, 1], tang[:, 0]]            # counter-clockwise ring
    beta = np.arctan(mu) - np.radians(margin_deg)
    d = pts[None, :, :] - pts[:, None, :]
    ang_i = np.arctan2(inward[:, None, 1], inward[:, None, 0])
    ang_j = np.arctan2(inward[None, :, 1], inward[None, :, 0])
    a_d = np.arctan2(d[..., 1], d[..., 0])

    def within(a, b):
        return np.abs(np.angle(np.exp(1j * (a - b)))) <= beta

    nz = np.hypot(d[..., 0], d[..., 1]) > 0
    best = 0
    for sign in (1.0, -1.0):
        a_ij = a_d if sign > 0 else a_d + np.pi
        ok = nz & within(a_ij, ang_i) & within(a_ij + np.pi, ang_j)
        lo, hi = 1, samples // 2
        if not ok.any():
            continue
        while lo < hi:
            k = (lo + hi + 1) // 2
            if minimum_filter(ok, size=k, mode="wrap").any():
                lo = k
            else:
                hi = k - 1
        best = max(best, lo)
    return (best - 1) * h if best else 0.0, h


def sampled_grasps(pair, polygon, rng, per_region=40):
    """Grasps (P, n_P, Q, n_Q) sampled in the two regions: random points of every piece,
    every end and interior vertex, a vertex with random normals of its fan too."""
    sides = []
    for pts, edges in zip(pair.regions, pair.region_edges, strict=True):
        normals = polygon.normals[list(edges)]
        cand_p, cand_n = [], []
        for k in range(len(edges)):
            a, b = pts[k], pts[k + 1]
            u = rng.uniform(0, 1, per_region // len(edges) + 2)
            u[:2] = (0.0, 1.0)
            cand_p.append(a + u[:, None] * (b - a))
            cand_n.append(np.repeat(normals[k][None], u.size, axis=0))
            if k > 0:                                   # interior vertex: its fan
                th0 = np.arctan2(*normals[k - 1][::-1])
                dth = np.angle(np.exp(1j * (np.arctan2(*normals[k][::-1]) - th0)))
                ths = th0 + dth * np.r_[0, 1, rng.uniform(0, 1, 3)]
                cand_p.append(np.repeat(a[None], ths.size, axis=0))
                cand_n.append(np.c_[np.cos(ths), np.sin(ths)])
        sides.append((np.concatenate(cand_p), np.concatenate(cand_n)))
    (p, n_p), (q, n_q) = sides
    i, j = np.meshgrid(np.arange(len(p)), np.arange(len(q)), indexing="ij")
    return p[i.ravel()], n_p[i.ravel()], q[j.ravel()], n_q[j.ravel()]


def wrenches(p, n_p, q, n_q, mu):
    """Friction-cone edge wrenches (B, 4, 3) about each grasp's midpoint."""
    out = []
    c = 0.5 * (p + q)
    scale = np.maximum(np.hypot(*(q - p).T), 1e-300)[:, None]
    for x, n in ((p, n_p), (q, n_q)):
        f = -n / np.hypot(*n.T)[:, None]
        for a in (np.arctan(mu), -np.arctan(mu)):
            g = np.c_[np.cos(a) * f[:, 0] - np.sin(a) * f[:, 1],
                      np.sin(a) * f[:, 0] + np.cos(a) * f[:, 1]]
            r = (x - c) / scale
            out.append(np.c_[g, r[:, 0] * g[:, 1] - r[:, 1] * g[:, 0]])
    return np.stack(out, axis=1)


KINDS = ("ellipse", "star", "cam", "rounded")


def _case(seed):
    rng = np.random.default_rng(seed)
    kind = KINDS[seed % len(KINDS)]
    # the default seeds stay small; the slow ones reach 2,000 edges
    n = int(rng.choice([100, 150, 250, 400] if seed < 8 else [100, 250, 400, 1000, 2000]))
    mu = float(rng.uniform(0.15, 0.8))
    return rng, kind, n, mu


def _check_against_raster(seed, samples=900):
    rng, kind, n, mu = _case(seed)
    ring = smooth_outline(rng, kind, n)
    poly = Polygon(ring)
    got = two_finger_stretches(poly, mu, margin=0.5, top=1)
    want, h = raster_optimum(ring, mu, 0.5, samples)
    t = got[0].min_length if got else 0.0
    # a feasible pair of regions holds a raster square of side t - 2h, and the raster
    # optimum's square, sampled h apart, is within about 2h of a feasible one
    assert t == pytest.approx(want, abs=3 * h), (kind, n, mu)
    if got:
        p, n_p, q, n_q = sampled_grasps(got[0], poly, rng)
        assert is_force_closure(wrenches(p, n_p, q, n_q, mu)).all(), (kind, n, mu)


def seeds(default, total):
    """Seeds 0 .. total - 1, those from ``default`` on marked slow (the exhaustive run)."""
    return [*range(default), *(pytest.param(s, marks=pytest.mark.slow)
                               for s in range(default, total))]


@pytest.mark.parametrize("seed", seeds(2, 208))
def test_stretches_match_raster(seed):
    _check_against_raster(seed)


def test_tessellated_circle_converges():
    """On a circle of radius R the optimum tends to 2 R (atan(mu) - margin)."""
    R, mu, margin = 30.0, 0.3, 0.5
    limit = 2 * R * (np.arctan(mu) - np.radians(margin))
    errs = []
    for n in (100, 400, 1600):
        a = np.linspace(0, 2 * np.pi, n, endpoint=False)
        t = two_finger_stretches(Polygon(np.c_[R * np.cos(a), R * np.sin(a)]), mu, margin,
                                 top=1)[0].min_length
        assert t <= limit * (1 + 1e-9)
        errs.append(limit - t)
    assert errs[-1] < 0.005 * limit
    assert errs[-1] < errs[0]


@pytest.mark.parametrize("seed", range(20))
def test_long_edges_no_worse_than_single_edges(seed):
    """On outlines of long edges the single-edge optimum (fc.plan) is still reached."""
    import fcgrasp as fc

    rng = np.random.default_rng(1000 + seed)
    poly = random_polygon(rng)
    mu = float(rng.uniform(0.1, 0.8))
    old = fc.plan(poly, fingers=2, mu=mu, top=1)
    new = two_finger_stretches(poly, mu, top=1)
    if old:
        assert new[0].min_length >= old[0].min_length * (1 - 1e-9)


def test_bad_arguments():
    poly = Polygon([[0, 0], [1, 0], [1, 1], [0, 1]])
    with pytest.raises(TypeError, match="polygon"):
        two_finger_stretches([[0, 0]], 0.3)
    with pytest.raises(ValueError, match="mu"):
        two_finger_stretches(poly, -1)
    with pytest.raises(ValueError, match="top"):
        two_finger_stretches(poly, 0.3, top=0)
    from fcgrasp.model.stretches import StretchSearch

    for share in (0, -0.5, 1.5, float("nan")):
        with pytest.raises(ValueError, match="share"):
            StretchSearch(poly, 0.3, share=share)


def _check_plans(seed):
    """fc.plan on a smooth outline: every plan's regions hold (sampled grasps, vertex
    fans included, through the general test); the best reaches the stretch optimum; each
    plan is the optimum of its own edges (independent_regions on its stretches); and the
    longer region of a plan cannot be pushed further along its end edge."""
    import fcgrasp as fc

    rng, kind, n, mu = _case(seed)
    poly = Polygon(smooth_outline(rng, kind, min(n, 400)))
    plans = fc.plan(poly, fingers=2, mu=mu, top=3)
    best = two_finger_stretches(poly, mu, top=1)
    assert bool(plans) == bool(best)
    if not plans:
        return
    assert plans[0].min_length == pytest.approx(best[0].min_length, rel=1e-9)
    for p in plans:
        g = sampled_grasps(p, poly, rng, per_region=24)
        assert is_force_closure(wrenches(*g, mu)).all(), (kind, n, mu, p.region_edges)
        again = fc.independent_regions(poly, p.region_edges, mu=mu)
        assert again.min_length == pytest.approx(p.min_length, rel=1e-9)
        long_side = int(np.argmax(p.lengths))
        if p.lengths[long_side] > p.lengths[1 - long_side] * (1 + 1e-6):
            _check_longest(p, long_side, poly, mu, rng)


def _check_longest(p, side, poly, mu, rng):
    """The second level of the leximin order is the largest: extended by 1% of its
    length at either end, staying on its end edges, the longer region fails (with
    friction cones shrunk by nearly the planner's margin of 0.5 degree)."""
    mu_margin = np.tan(np.arctan(mu) - np.radians(0.45))
    from dataclasses import replace as dc_replace

    pts = p.regions[side]
    grow = 0.01 * p.lengths[side]
    failed = []
    for end in (0, -1):
        nb = -2 if end == -1 else 1
        d = pts[end] - pts[nb]
        d = d / np.hypot(*d)
        e = p.region_edges[side][end]
        a, b = poly.starts[e], poly.starts[e] + poly.lengths[e] * poly.tangents[e]
        new_end = pts[end] + grow * d
        # still on the edge (between its ends)?
        u = np.dot(new_end - a, b - a) / np.dot(b - a, b - a)
        if not 0 <= u <= 1:
            continue
        longer = [np.array(r, float) for r in p.regions]
        longer[side] = longer[side].copy()
        longer[side][end] = new_end
        q = dc_replace(p, regions=tuple(longer))
        g = sampled_grasps(q, poly, rng, per_region=24)
        failed.append(not is_force_closure(wrenches(*g, mu_margin)).all())
    assert not failed or any(failed), p.region_edges


@pytest.mark.parametrize("seed", [1, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in (0, *range(2, 104)))])
def test_plans_along_the_boundary(seed):
    _check_plans(seed)


def test_single_edge_plans_unchanged_on_long_edges():
    """Where no region gains by crossing a vertex, fc.plan gives the single-edge plans."""
    import fcgrasp as fc
    from fcgrasp.io.parts import demo_part

    for name in ("blob", "triangle", "quad", "bracket", "washer", "rectangle"):
        poly = demo_part(name)
        a = fc.plan(poly, mu=0.3, top=4)
        b = fc.plan(poly, mu=0.3, top=4, along_boundary=False)
        assert [(p.edges, p.mode) for p in a] == [(p.edges, p.mode) for p in b], name
        for p, q in zip(a, b, strict=True):
            np.testing.assert_array_equal(p.ends, q.ends)
            assert p.region_edges == tuple((e,) for e in q.edges)


# ------------------------------------------------------------- no vertex can be covered


def _plan_key(plans):
    return [(p.edges, [np.round(r, 9).tolist() for r in p.regions], p.region_edges, p.mode,
             np.round(p.lengths, 9).tolist()) for p in plans]


@pytest.mark.parametrize("seed", range(6))
def test_sharp_corners_skip_the_stretch_search(seed, monkeypatch):
    """Where every vertex turns more than twice the shrunk friction angle
    (``crosses_a_vertex`` False) the plans are the single-edge search's, and exactly
    those of the full stretch search (forced here); and the full search indeed covers no
    vertex there."""
    import fcgrasp as fc
    from fcgrasp.grippers import _boundary as pipeline  # where boundary_plans asks
    from fcgrasp.model.stretches import crosses_a_vertex

    rng = np.random.default_rng(seed)
    seen = 0
    for kind in ("convex", "star", "holes", "rectangle", "regular"):
        part = random_polygon(rng, kind)
        for mu, rank_by in ((0.3, "min_region"), (0.15, "min_region"), (0.3, "epsilon")):
            if crosses_a_vertex(part, mu, 0.5):
                continue
            seen += 1
            fast = fc.plan(part, fingers=2, mu=mu, top=4, rank_by=rank_by)
            every = two_finger_stretches(part, mu, 0.5, top=None)
            assert all(len(e) == 1 for p in every for e in p.region_edges)
            with monkeypatch.context() as m:
                m.setattr(pipeline, "crosses_a_vertex", lambda *a: True)
                full = fc.plan(part, fingers=2, mu=mu, top=4, rank_by=rank_by)
            assert _plan_key(fast) == _plan_key(full)
    assert seen >= 5


def test_crosses_a_vertex_is_the_fan_condition():
    """A regular n-gon turns 2 pi / n at every vertex: a region may cover a vertex
    exactly when that is below 2 (atan(mu) - margin)."""
    from fcgrasp.model.stretches import crosses_a_vertex

    for n in (8, 12, 24, 60):
        a = np.arange(n) * 2 * np.pi / n
        part = Polygon(np.c_[np.cos(a), np.sin(a)])
        for mu in (0.1, 0.2, 0.3, 0.6):
            beta = np.arctan(mu) - np.radians(0.5)
            want = 2 * np.pi / n < 2 * beta
            assert crosses_a_vertex(part, mu, 0.5) == want
            if 2 * np.pi / n < beta / 2:          # well inside: the best covers vertices
                best = two_finger_stretches(part, mu, 0.5, top=1)[0]
                assert max(len(e) for e in best.region_edges) > 1


def _previous_polyline(ring, i, k, s0, t):
    """The region polyline as it was built before the round (a numpy row per
    vertex, then one array of them): the reference of ``_polyline``."""
    from fcgrasp.core._geom import trim_vertex_ends
    from fcgrasp.core.tolerances import ROUND_TOL

    m = ring.m
    first = ring.a[i % m] + s0 * ring.t[i % m]
    verts = [ring.a[(i + j) % m] for j in range(1, k + 1)]
    end_edge = (i + k) % m
    if k == 0:
        last = first + t * ring.t[i % m]
    else:
        off = ring.L[i % m] - s0 + float(ring.U[i % m + m + k] - ring.U[i % m + m + 1])
        last = ring.a[end_edge] + (t - off) * ring.t[end_edge]
    pts = np.array([first, *verts, last])
    edges = [int(ring.edges[(i + j) % m]) for j in range(k + 1)]
    return trim_vertex_ends(pts, edges, ROUND_TOL * float(ring.U[m]))


def random_ring(rng):
    """The ring of a seeded outline of 3-59 edges (an ellipse's points at random
    angles), as the stretch search reads it."""
    from fcgrasp.model.stretches._windows import _rings

    m = int(rng.integers(3, 60))
    a = np.sort(rng.uniform(0, 2 * np.pi, m))
    return _rings(Polygon(np.c_[np.cos(a) * rng.uniform(1, 50),
                                np.sin(a) * rng.uniform(1, 50)]))[0]


def test_region_polylines_are_the_previous_ones_bit_for_bit():
    """A stretch's region polyline (``_polyline``: the interior vertices gathered at
    once) is the previous implementation's, points bit for bit and edges as Python
    ints: seeded outlines of 3-59 edges, starts around the ring and beyond, regions
    from a vertex (trimmed) and crossing up to every vertex."""
    from fcgrasp.model.stretches._placement import _polyline

    rng = np.random.default_rng(3)
    for _ in range(150):
        ring = random_ring(rng)
        for _ in range(40):
            i, k = int(rng.integers(0, 3 * ring.m)), int(rng.integers(0, ring.m - 1))
            s0 = 0.0 if rng.random() < 0.2 else float(rng.uniform(0, ring.L[i % ring.m]))
            t = float(rng.uniform(0, 10))
            p, e = _polyline(ring, i, k, s0, t)
            q, f = _previous_polyline(ring, i, k, s0, t)
            assert np.array_equal(p, q) and e == f
            assert all(type(x) is int for x in e)


def test_exact_ties_are_ordered_by_the_job_then_the_covered_edges():
    """:func:`_tie_keys`: the job's rings and mode, then each stretch's start reduced
    modulo its ring's length and its interior vertices, on configurations of every ring
    pair and mode of a part with a hole, wrapped starts included."""
    from fcgrasp.model.stretches._placement import _tie_keys
    from fcgrasp.model.stretches._solve import _Found
    from fcgrasp.model.stretches._windows import _rings

    rng = np.random.default_rng(5)
    outer = np.c_[np.cos(np.linspace(0, 6.2, 40)), np.sin(np.linspace(0, 6.2, 40))] * 50
    hole = np.c_[np.cos(np.linspace(6.2, 0, 11)), np.sin(np.linspace(6.2, 0, 11))] * 10
    rings = _rings(Polygon(outer, [hole]))
    assert len(rings) == 2
    tie = _tie_keys(rings)
    for _ in range(500):
        x, y = (int(v) for v in rng.integers(0, len(rings), 2))
        cfg = tuple(int(v) for v in (rng.integers(0, 3 * rings[x].m), rng.integers(0, 5),
                                      rng.integers(0, 3 * rings[y].m), rng.integers(0, 5)))
        job = (x, y, float(rng.choice([-1.0, 1.0])), str(rng.choice(["squeeze", "expand"])))
        f = _Found(job, cfg, float(rng.random()), 0.0, 0.0)
        assert tie(f) == ((x, y), job[3], cfg[0] % rings[x].m, cfg[1], cfg[2] % rings[y].m,
                          cfg[3])


def _plate(rng, holes):
    """A rounded plate with ``holes`` small round holes on a grid (a CAD drawing's)."""
    corners = []
    for cx, cy, a0 in ((150, 90, 0), (10, 90, 90), (10, 10, 180), (150, 10, 270)):
        a = np.radians(np.linspace(a0, a0 + 90, 8))
        corners += list(np.c_[cx + 10 * np.cos(a), cy + 10 * np.sin(a)])
    rings = []
    for k in range(holes):
        c = (22 + 18 * (k % 7), 22 + 20 * (k // 7))
        a = np.linspace(0, 2 * np.pi, int(rng.integers(8, 20)), endpoint=False)[::-1]
        r = rng.uniform(2.0, 5.0)
        rings.append(np.c_[c[0] + r * np.cos(a), c[1] + r * np.sin(a)])
    return Polygon(np.array(corners), holes=rings)


# seed 4: one of the plates where a search that left out rings ten times too long
# returns other pairs
@pytest.mark.parametrize("seed", [4, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(12) if s != 4)])
def test_a_plates_top_pairs_leave_out_the_rings_shorter_than_the_floor(seed, monkeypatch):
    """On a plate with round holes the ranked search leaves out, once its floor passes
    them, the ring pairs whose shorter ring is shorter than the floor: the top pairs are
    those of the search that reads every ring pair, edge for edge."""
    from fcgrasp.model.stretches import _rounds

    rng = np.random.default_rng(seed)
    plate = _plate(rng, int(rng.integers(4, 10)))
    mu = float(rng.choice([0.3, 0.5, 1.0]))
    for top in (1, 5, 60):
        got = two_finger_stretches(plate, mu, top=top)
        with monkeypatch.context() as m:
            m.setattr(_rounds, "_reach", lambda ring: np.inf)
            want = two_finger_stretches(plate, mu, top=top)
        assert [(p.region_edges, p.mode) for p in got] == \
            [(p.region_edges, p.mode) for p in want]
        for a, b in zip(got, want, strict=True):
            assert a.lengths == b.lengths


@pytest.mark.parametrize("seed", [3, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(12) if s != 3)])
def test_the_ranked_top_grasps_are_the_head_of_every_grasp(seed):
    """Two fingers' ranked plans (``distinct=0``) on a plate with round holes, where a
    region as long as a short side lies anywhere along a longer one: many
    configurations of the best reads are one grasp, and the read grows until ``top``
    grasps are read.  For each ``top`` the plans are the first ``top`` of every grasp
    (``top=None``, which reads every configuration), as many as there are (seed 3: the
    first five configurations are one grasp)."""
    import fcgrasp as fc

    rng = np.random.default_rng(seed)
    plate = _plate(rng, int(rng.integers(4, 10)))
    mu = 0.5 if seed == 3 else float(rng.choice([0.3, 0.5, 1.0]))
    every = fc.plan(plate, fingers=2, mu=mu, top=None, distinct=0, time_limit=None)

    def key(p):
        return p.region_edges, p.mode, tuple(np.round(p.lengths, 9))

    for top in (1, 2, 5, 20):
        got = fc.plan(plate, fingers=2, mu=mu, top=top, distinct=0, time_limit=None)
        assert got.complete and len(got) == min(top, len(every))
        assert [key(p) for p in got] == [key(p) for p in every[:top]], top


def _equal_bits(a, b):
    return all(np.array_equal(x, y, equal_nan=True) for x, y in zip(a, b, strict=True))


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 40))])
def test_the_closed_form_of_sign_blocks_is_that_of_every_pair_bit_for_bit(seed):
    """The closed form's elimination of a variable (``_lp._eliminate``: each
    configuration's rows with a positive coefficient against those with a negative one)
    and its bounds of t (``_lp._t_bounds``: lower bounds of u0 against upper bounds)
    give the rows, in their order, and the bounds of every ordered pair of rows
    (``tests/previous_lp.py``), bit for bit: on 150 random batches of configurations of
    1 to 47 rows each (each variable eliminated, and the bounds of t), with rows that
    miss a variable, coefficients at the elimination's threshold and either side of it,
    rows repeated, the ``1 >= 0`` rows a batch is padded with, and batches of one sign
    only; and on the rows the numpy search eliminates on a random part and a random
    ellipse of 40 to 80 edges (40 seeds with ``-m slow``)."""
    from fcgrasp.model.stretches import _lp
    from fcgrasp.model.stretches._windows import _EPS

    from .previous_lp import eliminate_every_pair, t_bounds_every_pair

    rng = np.random.default_rng(900 + seed)
    special = np.array([0.0, _EPS, -_EPS, 2 * _EPS, -2 * _EPS, 0.5 * _EPS, 1.0, -1.0])
    for _ in range(150):
        B, R = int(rng.integers(1, 30)), int(rng.integers(1, 48))
        r = rng.normal(size=(B, R, 3)) * rng.choice([1e-3, 1.0, 1e3], size=(B, R, 1))
        pick = rng.random((B, R, 3)) < 0.15
        r[pick] = rng.choice(special, size=int(pick.sum()))
        r[rng.random((B, R)) < 0.1] = [1.0, 0.0, 0.0]          # the padding rows
        if R > 1:
            r[:, -1] = r[:, 0]                                  # a row repeated
        sign = rng.integers(3)
        if sign:                                                # one sign of cu only
            r[:, :, 1] = np.abs(r[:, :, 1]) * (1 if sign == 1 else -1)
        assert _equal_bits(_lp._t_bounds(r), t_bounds_every_pair(r))
        empty = r[:0]
        assert _equal_bits(_lp._t_bounds(empty), t_bounds_every_pair(empty))
        r4 = np.concatenate([r, rng.normal(size=(B, R, 1))], axis=2)
        r4[rng.random((B, R, 4)) < 0.1] = 0.0
        for var in range(1, 4):
            assert np.array_equal(_lp._eliminate(r4, var), eliminate_every_pair(r4, var),
                                  equal_nan=True)
    # the rows of real searches (numpy's solve, as a fresh process runs a small part)
    seen, eliminated = [], []
    solve, eliminate = _lp._t_bounds, _lp._eliminate

    def spy(r):
        seen.append(r.copy())
        return solve(r)

    def spy_eliminate(rows, var):
        eliminated.append((rows.copy(), var))
        return eliminate(rows, var)

    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("FCGRASP_JIT", "0")
        mp.setattr(_lp, "_t_bounds", spy)
        mp.setattr(_lp, "_eliminate", spy_eliminate)
        mu = 0.3 + 0.2 * (seed % 3)
        two_finger_stretches(random_polygon(rng), mu, top=5)
        a = np.linspace(0, 2 * np.pi, int(rng.integers(40, 81)), endpoint=False)
        two_finger_stretches(Polygon(np.c_[rng.uniform(30, 60) * np.cos(a),
                                           rng.uniform(10, 30) * np.sin(a)]), mu, top=5)
    assert len(seen) >= 2 and len(eliminated) >= 2
    for r in seen:
        assert _equal_bits(solve(r), t_bounds_every_pair(r))
    for rows, var in eliminated:
        assert np.array_equal(eliminate(rows, var), eliminate_every_pair(rows, var),
                              equal_nan=True)
