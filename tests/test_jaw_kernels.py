"""The parallel jaw's compiled loops (``fcgrasp.grippers.jaw._kernels``) against
the numpy model they replace, kept as the reference: the pose model (verdicts, stops,
contacts, slacks), the largest box of the pose grid, the proofs of boxes and the exact
slices, on seeded random parts with holes (internal grips too), at critical angles (an
edge parallel to the pads) and at offsets where a vertex enters the strip; then whole
plans, compiled and not, the same boxes."""

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.core._angles import shrunk_half_angle
from fcgrasp.grippers.jaw import ParallelJaw, _certify, _grid, _kernels, _poses, _slices
from fcgrasp.io.parts import demo_part

from .shapes import random_polygon

pytestmark = pytest.mark.skipif(not _kernels.available(), reason="numba not available")


def _part_and_jaw(rng):
    part = random_polygon(rng, str(rng.choice(["convex", "star", "rectangle", "holes",
                                               "regular"])))
    jaw = ParallelJaw(stroke=(0.05 * part.size, float(rng.uniform(0.6, 1.5)) * part.size),
                      pad_width=float(rng.uniform(0.02, 0.4)) * part.size,
                      mu=float(rng.uniform(0.2, 1.0)))
    return part, jaw


def _poses_of(rng, part, jaw, n):
    """Random poses, a third at the angles where an edge is parallel to the pads (and
    their opposites), a third at offsets where a vertex enters or leaves the strip."""
    th = rng.uniform(0, 2 * np.pi, n)
    c = rng.uniform(-0.7, 0.7, n) * part.size
    d = part.ends - part.starts
    crit = np.arctan2(d[:, 1], d[:, 0]) + np.pi / 2
    k = n // 3
    th[:k] = rng.choice(np.r_[crit, crit + np.pi], k)
    u = np.c_[np.cos(th[k:2 * k]), np.sin(th[k:2 * k])]
    v = part.vertices[rng.integers(0, len(part.vertices), k)] - part.centroid
    x = -u[:, 1] * v[:, 0] + u[:, 0] * v[:, 1]
    c[k:2 * k] = x + rng.choice([-1, 1], k) * jaw.pad_width / 2
    return th, c


def _holes(part):
    return [None] + list(range(len(part.holes)))


def test_compiled_poses_are_the_numpy_model():
    rng = np.random.default_rng(11)
    cases = agree = 0
    for _ in range(60):
        part, jaw = _part_and_jaw(rng)
        for hole in _holes(part):
            th, c = _poses_of(rng, part, jaw, 300)
            ring = _poses._grip_edges(part, hole)
            ref, s_ref = _poses._evaluate_numpy(part, jaw, th, c, 2.0, hole, ring)
            got, s_got = _poses._evaluate(part, jaw, th, c, 2.0, hole)
            tol = 1e-12 * part.size
            for name in ("top", "bottom", "opening", "lat_a", "lat_b", "psi_a", "psi_b"):
                np.testing.assert_allclose(getattr(got, name), getattr(ref, name), rtol=0,
                                           atol=tol, err_msg=name)
            for name in ("kind_a", "kind_b", "edge_a", "edge_b"):
                np.testing.assert_array_equal(getattr(got, name), getattr(ref, name),
                                              err_msg=name)
            np.testing.assert_allclose(s_got, s_ref, rtol=0, atol=1e-9 * part.size)
            # verdicts equal but where a slack is within rounding of zero
            near = np.any(np.abs(s_ref) <= 1e-9 * part.size, axis=1)
            assert np.array_equal(got.holds[~near], ref.holds[~near])
            cases += th.size
            agree += int(np.sum(ref.holds))
    assert cases >= 20000 and agree >= 500


def _grid_of(rng, part, jaw):
    """A grid of poses: evenly spaced offsets (sometimes one, or all equal), angles
    random or at the critical ones, offsets sometimes where a vertex meets the strip."""
    K = int(rng.integers(1, 12))
    th, _ = _poses_of(rng, part, jaw, 3 * K)
    th = rng.choice(th, K)
    kind = rng.integers(0, 4)
    M = 1 if kind == 0 else int(rng.integers(2, 40))
    if kind == 1:                           # a strip's edge on a vertex
        v = part.vertices[rng.integers(0, len(part.vertices))] - part.centroid
        x = -np.sin(th[0]) * v[0] + np.cos(th[0]) * v[1] + jaw.pad_width / 2
        c = x + np.arange(M) * rng.uniform(0.001, 0.05) * part.size
    elif kind == 2:                         # every offset the same
        c = np.full(M, rng.uniform(-0.5, 0.5) * part.size)
    else:
        c = np.linspace(*np.sort(rng.uniform(-0.8, 0.8, 2) * part.size), M)
    return th, c


def test_compiled_grid_reads_the_poses_of_every_edge():
    """The compiled grid (each pose reading only the edges near its strip) gives every
    pose the verdict, opening and pad edges of the pose loop over every edge."""
    rng = np.random.default_rng(17)
    poses = held = 0
    for _ in range(200):
        part, jaw = _part_and_jaw(rng)
        for hole in _holes(part):
            th, c = _grid_of(rng, part, jaw)
            ring = _poses._grip_edges(part, hole)
            args = _poses._pose_args(part, jaw, 2.0, hole, ring)
            H, opening, e_a, e_b = _kernels.grid(th, c, *args, details=True)
            tt, cc = np.meshgrid(th, c, indexing="ij")
            out = _kernels.poses(tt.ravel(), cc.ravel(), *args)
            top, bottom, col_a, col_b, holds = out[0], out[1], out[8], out[9], out[10]
            assert np.array_equal(H.ravel(), holds)
            np.testing.assert_array_equal(opening.ravel(), top - bottom)
            np.testing.assert_array_equal(e_a.reshape(-1, _kernels.K_MAX), col_a)
            np.testing.assert_array_equal(e_b.reshape(-1, _kernels.K_MAX), col_b)
            assert np.array_equal(_kernels.grid(th, c, *args), H)
            poses += H.size
            held += int(H.sum())
    assert poses >= 20000 and held >= 500


@pytest.mark.parametrize("name", ["washer", "bracket", pytest.param("cam", marks=pytest.mark.slow)])
def test_compiled_pose_grid_and_fine_check_are_the_batches(name):
    """The jaw's pose grid and each box's fine check, by the compiled grid and by
    :func:`jaw_poses` in batches (tiles of the edges near their strips)."""
    part = demo_part(name)
    rng = np.random.default_rng(18)
    for jaw in (ParallelJaw(stroke=(5, 60), pad_width=8, mu=0.5),
                ParallelJaw(stroke=(0, 1.2 * part.size), pad_width=0.1 * part.size,
                            mu=0.3)):
        for hole in _holes(part):
            thetas, offsets, H = _grid._grid(part, jaw, 2.0, hole)
            assert np.array_equal(
                H, _grid._pose_grid_batches(part, jaw, 2.0, hole, thetas, offsets))
            dth, dc = thetas[1] - thetas[0], offsets[1] - offsets[0]
            # boxes of the grid's holding poses, and random ones
            rows, cols = np.nonzero(H)
            for k in range(12):
                if k < 6 and rows.size:
                    i = int(rng.integers(0, rows.size))
                    t0, c0 = thetas[rows[i]], offsets[cols[i]]
                else:
                    t0, c0 = rng.uniform(0, 2 * np.pi), rng.uniform(-1, 1) * part.radius
                th = np.array([t0, t0 + dth * int(rng.integers(0, 8))])
                off = np.array([c0, c0 + dc * int(rng.integers(0, 8))])
                assert _grid._checked_box(part, jaw, 2.0, hole, th, off, dth, dc) == \
                    _grid._checked_box(part, jaw, 2.0, hole, th, off, dth, dc,
                                        compiled_grid=False)


def test_compiled_box_search_is_the_numpy_search():
    rng = np.random.default_rng(12)
    for t in range(1500):
        K, M = int(rng.integers(2, 40)), int(rng.integers(2, 30))
        H = rng.random((K, M)) < rng.uniform(0.3, 0.97)
        if t % 3 == 0:                  # one block, then noise holes in it
            H[:] = False
            k0, k1 = np.sort(rng.integers(0, K, 2))
            j0, j1 = np.sort(rng.integers(0, M, 2))
            H[k0:k1 + 1, j0:j1 + 1] = True
        dth, dc, radius = rng.uniform(0.01, 0.2), rng.uniform(0.1, 2), rng.uniform(1, 30)
        if t % 5 == 0:
            dc = dth * radius           # the two sides tie
        rows = int(rng.integers(1, K // 2 + 2))
        assert _grid._box_scores(H, dth, dc, radius, rows) \
            == _grid._box_scores_numpy(H, dth, dc, radius, rows)


def test_compiled_proofs_are_the_numpy_proofs():
    rng = np.random.default_rng(13)
    boxes_seen = proved = 0
    for _ in range(40):
        part, jaw = _part_and_jaw(rng)
        beta = float(shrunk_half_angle(jaw.mu, 2.0))
        for hole in _holes(part):
            ring = _poses._grip_edges(part, hole)
            q = None if hole is None else _poses.insertion_point(part, hole) - part.centroid
            th, c = _poses_of(rng, part, jaw, 300)
            w = rng.choice([1e-5, 1e-3, 1e-2, 0.05, 0.3], th.size) * rng.random(th.size)
            cw = rng.choice([1e-4, 1e-2, 0.1], th.size) * rng.random(th.size) * part.size
            boxes = np.c_[th, th + w, c, c + cw]
            ok_ref, lo_ref, hi_ref = _certify._box_proofs_numpy(part, ring, jaw, boxes,
                                                                beta, q)
            ok, lo, hi = _certify._box_proofs(part, ring, jaw, boxes, beta, q)
            assert np.array_equal(ok, ok_ref)
            np.testing.assert_allclose(lo[ok], lo_ref[ok], rtol=0, atol=1e-9 * part.size)
            np.testing.assert_allclose(hi[ok], hi_ref[ok], rtol=0, atol=1e-9 * part.size)
            boxes_seen += len(boxes)
            proved += int(ok.sum())
    assert boxes_seen >= 10000 and proved >= 500, (boxes_seen, proved)


def _numpy_only(monkeypatch):
    monkeypatch.setattr(_kernels, "available", lambda: False)


def test_a_slice_across_a_window_is_read_from_the_slices(monkeypatch):
    """``holds_across`` (the growth's question: does the exact slice at each angle hold
    at every offset of a window?) gives, compiled with its early stop at the first piece
    that does not hold and by numpy, what reading :func:`holding_offsets` gives: one
    interval from end to end within the contact tolerance; so does ``near_intervals``
    (the far end of the interval through either end of the window, each angle read from
    that end) (numpy's slices the reference
    on random parts with holes; the compiled ones, tested equal to them above, on
    filleted plates of a few hundred edges).  Windows inside, across and outside the
    holding slices, at random angles and where an edge turns parallel to the pads."""
    from fcgrasp.core.tolerances import CONTACT_TOL, ROUND_TOL, SLICE_TOL

    from .test_jaw import _filleted_plate

    def slices(part, jaw, th, hole, window, numpy):
        with monkeypatch.context() as m:
            if numpy:
                _numpy_only(m)
            return _slices.holding_offsets(part, jaw, th, 2.0, hole, window)

    rng = np.random.default_rng(18)
    seen = {True: 0, False: 0}
    stopped = 0
    for k in range(5):
        plate = k % 3 == 2
        if plate:
            part = _filleted_plate(rng)
            jaw = fc.ParallelJaw(stroke=(0.0, 1.5 * part.size), pad_width=0.1 * part.size,
                                 mu=float(rng.uniform(0.3, 0.8)))
        else:
            part, jaw = _part_and_jaw(rng)
        d = part.ends - part.starts
        crit = np.arctan2(d[:, 1], d[:, 0]) + np.pi / 2
        tol = CONTACT_TOL * part.size
        for hole in _holes(part):
            th = np.r_[rng.uniform(0, 2 * np.pi, 8), crit[:3]]
            whole = slices(part, jaw, th, hole, None, not plate)
            for iv in [w for w in whole if len(w)][:3]:
                lo, hi = iv[0]
                for c0, c1 in ((lo + 0.2 * (hi - lo), hi - 0.2 * (hi - lo)),
                               (lo - 0.1 * part.size, lo + 0.5 * (hi - lo)),
                               (lo, hi), (hi + 0.01 * part.size, hi + 0.2 * part.size)):
                    ref = [len(w) == 1 and w[0, 0] <= c0 + tol and w[0, 1] >= c1 - tol
                           for w in slices(part, jaw, th, hole, (c0, c1), not plate)]
                    got = _slices.holds_across(part, jaw, th, 2.0, hole, (c0, c1))
                    assert got.tolist() == ref
                    # the interval through either end (the growth's reach)
                    whole_w = slices(part, jaw, th, hole, (c0, c1), not plate)
                    for side in (1, -1):
                        want = np.full(th.size, np.nan)
                        for a, w in enumerate(whole_w):
                            at = (w[:, 0] <= c0 + tol) if side > 0 else (w[:, 1] >= c1 - tol)
                            if at.any():
                                want[a] = w[at][0, 1] if side > 0 else w[at][-1, 0]
                        near = _slices.near_intervals(part, jaw, th, 2.0, hole, (c0, c1),
                                                      side)
                        np.testing.assert_array_equal(near, want)
                    if not plate:
                        with monkeypatch.context() as m:
                            _numpy_only(m)
                            by_numpy = _slices.holds_across(part, jaw, th, 2.0, hole,
                                                            (c0, c1))
                        assert by_numpy.tolist() == ref
                    for v in ref:
                        seen[v] += 1
                    failed = np.zeros(th.size, dtype=bool)
                    ring, ct, clo, chi = _slices._cells(part, jaw, th, hole, (c0, c1))
                    _kernels.slices(ct, clo, chi, th,
                                    *_poses._pose_args(part, jaw, 2.0, hole, ring),
                                    SLICE_TOL * part.size, ROUND_TOL * part.size, tol,
                                    _poses.NEAR_STRIP * tol, stop_gap=tol, failed=failed)
                    assert not np.any(failed & np.array(ref))     # never a holding angle
                    stopped += int(failed.sum())
    assert min(seen.values()) >= 20 and stopped >= 10, (seen, stopped)


def test_compiled_slices_are_the_numpy_slices(monkeypatch):
    rng = np.random.default_rng(14)
    pieces = 0
    for _ in range(25):
        part, jaw = _part_and_jaw(rng)
        d = part.ends - part.starts
        crit = np.arctan2(d[:, 1], d[:, 0]) + np.pi / 2
        th = np.r_[rng.uniform(0, 2 * np.pi, 12), crit[:6]]
        for hole in _holes(part):
            got = _slices.holding_offsets(part, jaw, th, 2.0, hole)
            with monkeypatch.context() as m:
                _numpy_only(m)
                ref = _slices.holding_offsets(part, jaw, th, 2.0, hole)
            for g, r in zip(got, ref, strict=True):
                assert g.shape == r.shape
                np.testing.assert_allclose(g, r, rtol=0, atol=1e-9 * part.size)
                pieces += len(r)
    assert pieces >= 100


@pytest.mark.parametrize("name", [pytest.param("washer", marks=pytest.mark.slow),
                                  pytest.param("quad", marks=pytest.mark.slow),
                                  pytest.param("triangle", marks=pytest.mark.slow),
                                  pytest.param("rectangle", marks=pytest.mark.slow),
                                  "blob"])
def test_compiled_jaw_plans_are_the_numpy_plans(name, monkeypatch):
    part = demo_part(name)
    jaw = ParallelJaw(stroke=(5, 60), pad_width=8, mu=0.5)
    got = fc.jaw_plans(part, jaw, top=3, internal=True)
    with monkeypatch.context() as m:
        _numpy_only(m)
        ref = fc.jaw_plans(part, jaw, top=3, internal=True)
    assert len(got) == len(ref) >= 1
    for g, r in zip(got, ref, strict=True):
        np.testing.assert_allclose(g.theta, r.theta, rtol=0, atol=1e-12)
        np.testing.assert_allclose(g.offset, r.offset, rtol=0, atol=1e-9 * part.size)
        np.testing.assert_allclose(g.opening, r.opening, rtol=0, atol=1e-9 * part.size)
        assert (g.mode, g.hole, g.kinds, g.features) == (r.mode, r.hole, r.kinds, r.features)


def test_compiled_proofs_drop_the_dominated_candidates_as_numpy_does(monkeypatch):
    """Plates with finely flattened fillets, where the dominating vertex decides most
    candidates (``_certify._dominated``): the compiled proofs give numpy's answers on
    boxes around holding poses and on random boxes."""
    from .test_jaw import _filleted_plate

    rng = np.random.default_rng(17)
    seen = proved = 0
    for _ in range(2):
        part = _filleted_plate(rng)
        jaw = fc.ParallelJaw(stroke=(0.0, 1.5 * part.size), pad_width=0.1 * part.size,
                             mu=float(rng.uniform(0.3, 0.8)))
        th = rng.uniform(0, 2 * np.pi, 400)
        c = rng.uniform(-0.5, 0.5, 400) * part.size
        holds = _poses.jaw_poses(part, jaw, th, c, 2.0).holds
        for k in list(np.flatnonzero(holds)[:5]) + list(np.flatnonzero(~holds)[:2]):
            w = float(rng.uniform(0.002, 0.02))
            box_t, box_c = (th[k] - w, th[k] + w), (c[k] - w * part.size, c[k] + w * part.size)
            got = _certify.certify_box(part, jaw, box_t, box_c, 2.0, max_boxes=300)
            with monkeypatch.context() as m:
                _numpy_only(m)
                ref = _certify.certify_box(part, jaw, box_t, box_c, 2.0, max_boxes=300)
            assert (got is None) == (ref is None)
            if ref is not None:
                np.testing.assert_allclose(got, ref, rtol=0, atol=1e-9 * part.size)
            seen += 1
            proved += ref is not None
    assert seen >= 10 and proved >= 4, (seen, proved)


@pytest.mark.parametrize("seed, parts", [(15, 3), pytest.param(16, 60, marks=pytest.mark.slow)])
def test_compiled_certify_box_is_the_numpy_subdivision(seed, parts, monkeypatch):
    """The compiled proof goes depth first over the edges near each box; numpy goes
    breadth first over every edge: the same boxes are examined, so the same answer
    (proved or not, and the opening's enclosure), on the grid boxes of random parts,
    those boxes widened past the holding set, and random boxes."""
    rng = np.random.default_rng(seed)
    seen = proved = refused = 0
    for _ in range(parts):
        part, jaw = _part_and_jaw(rng)
        for hole in _holes(part):
            plans = fc.jaw_plans(part, jaw, top=2, certify=False, internal=hole is not None)
            boxes = [(p.theta, p.offset) for p in plans if p.hole == hole]
            for _ in range(2):
                t0, c0 = rng.uniform(0, 2 * np.pi), rng.uniform(-0.5, 0.5) * part.size
                boxes.append(((t0, t0 + rng.uniform(0, 0.3)),
                              (c0, c0 + rng.uniform(0, 0.3) * part.size)))
            for th, off in boxes:
                for grow in (0.0, 0.003):
                    th2 = (th[0] - grow, th[1] + grow)
                    off2 = (off[0] - grow * part.size, off[1] + grow * part.size)
                    got = _certify.certify_box(part, jaw, th2, off2, 2.0, hole,
                                               max_boxes=2000)
                    with monkeypatch.context() as m:
                        _numpy_only(m)
                        ref = _certify.certify_box(part, jaw, th2, off2, 2.0, hole,
                                                   max_boxes=2000)
                    assert (got is None) == (ref is None)
                    if ref is not None:
                        np.testing.assert_allclose(got, ref, rtol=0, atol=1e-9 * part.size)
                    seen += 1
                    proved += ref is not None
                    refused += ref is None
    assert seen >= 6 * parts and proved >= parts // 2 and refused >= parts


def _merge_intervals_loop(rows, count, tol):
    """The pieces joined one at a time (the loop :func:`_merge_intervals` replaced)."""
    out = [[] for _ in range(count)]
    for k, lo, hi in rows[np.lexsort((rows[:, 1], rows[:, 0]))]:
        cur = out[int(k)]
        if cur and lo <= cur[-1][1] + tol:
            cur[-1][1] = max(cur[-1][1], hi)
        else:
            cur.append([lo, hi])
    return [np.array(c, dtype=float).reshape(-1, 2) for c in out]


def test_merged_slices_equal_the_loop():
    """The jaw's slices of each pose joined into disjoint intervals by
    whole-array operations (a running maximum of exact integer keys) against the loop
    that joined them one piece at a time: the same intervals, bit for bit, on 3,000
    seeded cases with touching, nested, repeated and zero-length pieces."""
    from fcgrasp.grippers.jaw._slices import _merge_intervals

    rng = np.random.default_rng(41)
    for t in range(3000):
        count, n = int(rng.integers(1, 8)), int(rng.integers(0, 40))
        lo = rng.integers(0, 20, n).astype(float) if t % 2 else rng.uniform(0, 10, n)
        hi = lo + (rng.integers(0, 4, n) if t % 2 else rng.uniform(0, 2, n))
        rows = np.c_[rng.integers(0, count, n), lo, hi]
        tol = float(rng.choice([0.0, 0.5, 1e-9]))
        got, want = _merge_intervals(rows, count, tol), _merge_intervals_loop(rows, count, tol)
        assert len(got) == len(want) == count
        for a, b in zip(got, want, strict=True):
            np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("cases", [pytest.param(40, id="seeded"),
                                   pytest.param(400, id="sweep", marks=pytest.mark.slow)])
def test_compiled_slices_in_a_narrow_window_read_every_edge_a_pad_reaches(cases,
                                                                           monkeypatch):
    """The compiled slices of a window read only the edges near the pads' strip; the
    pads' middles run over the window, so an edge up to half a pad outside it is read
    too (it was dropped: the jaw's grown boxes on ``icons/star.svg`` stopped 5 % short
    of numpy's).  Windows narrower than a pad, near the part's features, on seeded
    star-shaped parts with wide pads: the compiled slices and ``near_intervals`` are
    numpy's (every edge read)."""
    from fcgrasp.core.tolerances import CONTACT_TOL
    from fcgrasp.grippers.jaw._slices import holding_offsets, near_intervals

    rng = np.random.default_rng(71)
    differ = 0
    for _ in range(cases):
        part = random_polygon(rng, "star")
        jaw = ParallelJaw(stroke=(0.0, 1.2 * part.size),
                          pad_width=float(rng.uniform(0.1, 0.4)) * part.size, mu=0.3)
        th = np.sort(rng.uniform(0, 2 * np.pi, 1)) + np.linspace(0, 0.3, 6)
        c = float(rng.uniform(-0.4, 0.4)) * part.size
        window = (c, c + float(rng.uniform(0.01, 0.5)) * jaw.pad_width)
        tol = CONTACT_TOL * part.size
        got = holding_offsets(part, jaw, th, 2.0, None, window)
        ends = [near_intervals(part, jaw, th, 2.0, None, window, s) for s in (1, -1)]
        with monkeypatch.context() as m:
            _numpy_only(m)
            want = holding_offsets(part, jaw, th, 2.0, None, window)
            want_ends = [near_intervals(part, jaw, th, 2.0, None, window, s) for s in (1, -1)]
        for g, w in zip(got, want, strict=True):
            assert g.shape == w.shape
            np.testing.assert_allclose(g, w, rtol=0, atol=tol)
        for g, w in zip(ends, want_ends, strict=True):
            np.testing.assert_allclose(g, w, rtol=0, atol=tol)
        differ += any(len(w) for w in want)
    assert differ > cases // 4             # windows with holding offsets among them


def _comb(rng):
    """A comb: teeth whose tips are level to within a few contact tolerances (some
    exactly level, some a hair above or below), the pads' stop tied over many edges."""
    k = int(rng.integers(5, 30))
    size = 50.0
    tips = 20.0 + rng.choice([0.0, 1.0, -1.0, 3.0, -3.0, 1e3], k) * 1e-9 * size
    x = np.linspace(-20.0, 20.0, 2 * k + 1)
    pts = [(x[0], -10.0)]
    for i in range(k):
        pts += [(x[2 * i], tips[i]), (x[2 * i + 1], tips[i]), (x[2 * i + 1], 10.0)]
    pts += [(x[-1], 10.0), (x[-1], -10.0)]
    ring = np.array(pts)
    ring = ring[np.r_[True, np.any(np.diff(ring, axis=0) != 0, axis=1)]]
    th = float(rng.uniform(0, 2 * np.pi))
    rot = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    return fc.Polygon(ring @ rot.T + 100 * rng.normal(size=2)), th


@pytest.mark.parametrize("cases", [pytest.param(30, id="seeded"),
                                   pytest.param(600, id="sweep", marks=pytest.mark.slow)])
def test_pruned_slices_are_every_edges_slices_bit_for_bit(cases):
    """The compiled slices of an external grip read, per cell, only the edges that may
    come within the contact tolerance of a pad's stop (``prune``, the default): their
    pieces, and the angles given up, are those of reading every edge near the strip, bit
    for bit.  Seeded random parts, filleted plates (hundreds of edges in a strip, most
    of them pruned) and combs whose teeth's tips are level to within a few tolerances
    (the stop tied over many edges, some just out of reach), at random and critical
    angles, whole and in windows, with and without the early stop."""
    from fcgrasp.core.tolerances import CONTACT_TOL, ROUND_TOL, SLICE_TOL

    from .test_jaw import _filleted_plate

    rng = np.random.default_rng(72)
    pieces = stops = 0
    for k in range(cases):
        kind = k % 3
        if kind == 0:
            part, jaw = _part_and_jaw(rng)
            crit = np.arctan2(*(part.ends - part.starts).T[::-1]) + np.pi / 2
        elif kind == 1:
            part = _filleted_plate(rng)
            jaw = fc.ParallelJaw(stroke=(0.0, 1.5 * part.size),
                                 pad_width=float(rng.uniform(0.05, 0.4)) * part.size,
                                 mu=float(rng.uniform(0.3, 0.8)))
            crit = np.arctan2(*(part.ends - part.starts).T[::-1]) + np.pi / 2
        else:
            part, turn = _comb(rng)
            jaw = fc.ParallelJaw(stroke=(0.0, 1.5 * part.size),
                                 pad_width=float(rng.uniform(0.05, 0.6)) * part.size,
                                 mu=float(rng.uniform(0.3, 0.8)))
            crit = turn + np.array([np.pi / 2, -np.pi / 2])
        th = np.r_[rng.uniform(0, 2 * np.pi, 4), rng.choice(crit, 3),
                   rng.choice(crit, 2) + rng.choice([-1, 1], 2) * 1e-9]
        tol = CONTACT_TOL * part.size
        c = float(rng.uniform(-0.3, 0.3)) * part.size
        for window in (None, (c, c + float(rng.uniform(0.01, 0.5)) * part.size)):
            ring, ct, clo, chi = _slices._cells(part, jaw, th, None, window)
            args = (ct, clo, chi, th, *_poses._pose_args(part, jaw, 2.0, None, ring),
                    SLICE_TOL * part.size, ROUND_TOL * part.size, tol,
                    _poses.NEAR_STRIP * tol)
            for gap, upward in ((0.0, False), (tol, True), (tol, False)):
                got_failed, want_failed = np.zeros(th.size, bool), np.zeros(th.size, bool)
                got = _kernels.slices(*args, stop_gap=gap, failed=got_failed, upward=upward)
                want = _kernels.slices(*args, stop_gap=gap, failed=want_failed,
                                       upward=upward, prune=False)
                np.testing.assert_array_equal(got, want)
                np.testing.assert_array_equal(got_failed, want_failed)
                pieces += len(want)
                stops += int(want_failed.sum())
    assert pieces > 20 * cases and stops > cases // 2, (pieces, stops)


def test_both_outer_pads_in_one_pass_are_each_pad_alone():
    """An external grip's pads are found in one pass over the edges (``_outer_pads``,
    the positions computed once for both): bit for bit what :func:`_pad_loop` finds for
    each pad alone (its stop, validity, features' spans, force angles and columns), at
    random poses, at critical angles and where a vertex enters the strip."""
    K = _kernels.K_MAX
    rng = np.random.default_rng(73)
    poses = touching = 0
    for _ in range(40):
        part, jaw = _part_and_jaw(rng)
        ring = _poses._grip_edges(part, None)
        a, b, f, half, tol = _poses._pose_args(part, jaw, 2.0, None, ring)[:5]
        th, c = _poses_of(rng, part, jaw, 60)
        E = a.shape[0]
        for t, x in zip(th, c, strict=True):
            tc, ts = float(np.cos(t)), float(np.sin(t))
            got = [np.empty(1), np.zeros(1, bool), np.empty((1, K, 2)), np.empty((1, K)),
                   np.empty((1, K), np.int64)]
            got_b = [np.empty(1), np.zeros(1, bool), np.empty((1, K, 2)), np.empty((1, K)),
                     np.empty((1, K), np.int64)]
            assert _kernels._run("_outer_pads", 0, tc, ts, float(x), a, b, f, half, tol,
                                 *got, *got_b, np.empty((4, E)))
            for sign, fsign, mine in ((1.0, -1.0, got), (-1.0, 1.0, got_b)):
                want = [np.empty(1), np.zeros(1, bool), np.empty((1, K, 2)),
                        np.empty((1, K)), np.empty((1, K), np.int64)]
                assert _kernels._run("_pad_loop", 0, tc, ts, float(x), a, b, f, half, tol,
                                     sign, fsign, -1, *want, np.empty((2, E)), 0)
                for g, w in zip(mine, want, strict=True):
                    assert g.tobytes() == w.tobytes()
                touching += int(np.sum(want[4] >= 0))
            poses += 1
    assert poses == 2400 and touching > 2000


@pytest.mark.parametrize("parts", [2, pytest.param(8, marks=pytest.mark.slow)])
def test_compiled_pooled_proofs_are_the_numpy_proofs_on_curves(parts):
    """On finely flattened curves and filleted plates, where a pad's candidates are
    pooled over most boxes a few degrees wide, the compiled proof gives numpy's verdict
    and opening enclosure box for box."""
    from .test_jaw import _curved_part, _filleted_plate

    rng = np.random.default_rng(17)
    pooled = proved = 0
    for k in range(parts):
        part = (_curved_part, _filleted_plate)[k % 2](rng)
        jaw = ParallelJaw(stroke=(0.05 * part.size, 1.5 * part.size),
                          pad_width=float(rng.uniform(0.02, 0.3)) * part.size,
                          mu=float(rng.uniform(0.3, 1.0)))
        beta = float(shrunk_half_angle(jaw.mu, 0.5))
        ring = _poses._grip_edges(part, None)
        th, c = _poses_of(rng, part, jaw, 200)
        w = rng.choice([1e-3, 1e-2, 0.05, 0.2], th.size) * rng.random(th.size)
        cw = rng.choice([1e-3, 1e-2, 0.1], th.size) * rng.random(th.size) * part.size
        boxes = np.c_[th, th + w, c, c + cw]
        ok_ref, lo_ref, hi_ref = _certify._box_proofs_numpy(part, ring, jaw, boxes, beta,
                                                            None)
        ok, lo, hi = _certify._box_proofs(part, ring, jaw, boxes, beta, None)
        assert np.array_equal(ok, ok_ref)
        np.testing.assert_allclose(lo[ok], lo_ref[ok], rtol=0, atol=1e-9 * part.size)
        np.testing.assert_allclose(hi[ok], hi_ref[ok], rtol=0, atol=1e-9 * part.size)
        ca, cb, _ = _certify._pads(part, ring, boxes, jaw.pad_width / 2, None)
        many = (ca.count > _poses.MAX_CONTACTS) | (cb.count > _poses.MAX_CONTACTS)
        pooled += int((ok & many).sum())
        proved += int(ok.sum())
    assert pooled >= 8 * parts and proved >= 40 * parts, (pooled, proved)


@pytest.mark.parametrize("parts", [1, pytest.param(4, marks=pytest.mark.slow)])
def test_proofs_and_slices_read_in_pieces_are_read_whole(parts, monkeypatch):
    """The compiled proof runs its slabs a few at a time (``CERTIFY_SLABS``, each run
    given the sub-boxes the runs before left) and the slices their angles a few at a
    time (``SLICE_CHUNK``), the time budget checked between: with one slab and two
    angles at a time, certify_box's answers on boxes of seeded curved outlines (proved
    or not, within few sub-boxes or many) and the jaw's plans are those of one run."""
    from .test_jaw import _curved_part

    rng = np.random.default_rng(23)
    seen = proved = refused = 0
    for _ in range(parts):
        part = _curved_part(rng)
        jaw = ParallelJaw(stroke=(0.05 * part.size, 1.5 * part.size),
                          pad_width=float(rng.uniform(0.05, 0.2)) * part.size,
                          mu=float(rng.uniform(0.4, 1.0)))
        th, c = _poses_of(rng, part, jaw, 30)
        widths = rng.choice([0.01, 0.1, 0.4], th.size)
        budgets = rng.choice([20, 400, 4000], th.size)
        answers = []
        for slabs, chunk in ((10 ** 6, 10 ** 6), (1, 2)):
            monkeypatch.setattr(_certify, "CERTIFY_SLABS", slabs)
            monkeypatch.setattr(_slices, "SLICE_CHUNK", chunk)
            got = [_certify.certify_box(part, jaw, (t, t + w), (x, x + 0.05 * part.size),
                                        0.5, max_boxes=int(budget))
                   for t, x, w, budget in zip(th, c, widths, budgets, strict=True)]
            plans = [p.to_dict() for p in fc.jaw_plans(part, jaw, top=1)]
            answers.append((got, plans))
        (whole, p_whole), (pieces, p_pieces) = answers
        assert p_whole == p_pieces
        for a, b in zip(whole, pieces, strict=True):
            assert (a is None) == (b is None)
            if a is not None:
                assert a == b
            seen += 1
            proved += a is not None
            refused += a is None
    assert seen >= 30 and proved >= 3 and refused >= 3, (seen, proved, refused)


def test_a_jaw_whose_clock_ends_inside_a_proof_keeps_only_proved_boxes(monkeypatch):
    """The clock ending inside the proofs and the slices (the checks between their runs
    of slabs and angles): the boxes kept are proved, every sampled pose of each holds,
    and the answer says the search stopped (not exact)."""
    from fcgrasp.core import budget

    from .test_jaw import _curved_part

    rng = np.random.default_rng(4)
    part = _curved_part(rng)
    jaw = ParallelJaw(stroke=(0.05 * part.size, 1.5 * part.size), pad_width=0.1 * part.size,
                      mu=0.8)
    real = budget.cut_if_over
    for ends_after in (0, 3, 12, 40):
        calls = [0]

        def clock(counted=True, calls=calls, ends_after=ends_after):
            if counted:
                return real(counted)
            calls[0] += 1
            if calls[0] > ends_after:
                budget.cut_short()
                return True
            return False

        monkeypatch.setattr(budget, "cut_if_over", clock)
        plans = fc.plan(part, gripper=jaw, top=4, distinct=0, time_limit=None)
        assert not plans.complete
        for p in plans:
            assert p.certified
            th = rng.uniform(*p.theta, 60)
            c = rng.uniform(*p.offset, 60)
            assert _poses.jaw_poses(part, jaw, th, c, margin=0.5).holds.all()


def test_a_proof_in_runs_of_slabs_spends_one_budget_of_sub_boxes():
    """The runs of slabs of one proof share its budget of sub-boxes: with the budget
    the whole proof needs, less one, and more, a run of one slab at a time gives the
    whole proof's answer (refused below what it needs, proved from it on)."""
    from fcgrasp.core._angles import shrunk_half_angle as half_angle

    from .test_jaw import _curved_part

    rng = np.random.default_rng(29)
    checked = 0
    for _ in range(4):
        part = _curved_part(rng)
        jaw = ParallelJaw(stroke=(0.05 * part.size, 1.5 * part.size),
                          pad_width=0.1 * part.size, mu=0.8)
        ring = _poses._grip_edges(part, None)
        beta = float(half_angle(jaw.mu, 0.5))
        th, c = _poses_of(rng, part, jaw, 40)
        holds = _poses.jaw_poses(part, jaw, th, c, 0.5).holds
        for t, x in zip(th[holds][:6], c[holds][:6], strict=True):
            t0, t1, c0, c1 = t, t + 0.2, x - 0.01 * part.size, x + 0.01 * part.size
            cuts = _certify._angle_cuts(part, ring, t0, t1)
            todo = np.column_stack([cuts[:-1], cuts[1:], np.full(cuts.size - 1, c0),
                                    np.full(cuts.size - 1, c1)])
            whole = _certify._certify_compiled(part, ring, jaw, todo, None, beta, 10 ** 7,
                                               part.radius)
            if not whole[0] or len(todo) < 3:
                continue
            used = whole[3]
            for b in (used - 1, used, used + 1):
                answers = []
                for slabs in (10 ** 6, 1):
                    _certify.CERTIFY_SLABS = slabs
                    try:
                        answers.append(_certify._certify_compiled(
                            part, ring, jaw, todo, None, beta, b, part.radius)[:3])
                    finally:
                        _certify.CERTIFY_SLABS = 64
                (ok, lo, hi), (ok1, lo1, hi1) = answers
                assert ok == ok1 == (b >= used)
                assert not ok or (lo, hi) == (lo1, hi1)
                checked += 1
    assert checked >= 9, checked
