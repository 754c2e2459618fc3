"""Distinct alternatives (fcgrasp.model.distinct): the overlap of two regions against an
independent estimate (dense points along one polyline, their distance to the other's
segments), and the suppression's invariants on seeded random parts and curved ones."""

from __future__ import annotations

import functools

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.model.distinct import distinct_plans, region_overlap, same_alternative

from .shapes import random_polygon, star


def _dist_to_polyline(p, line):
    a, d = line[:-1], np.diff(line, axis=0)
    dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    s = np.clip(np.einsum("kij,ij->ki", p[:, None, :] - a[None], d) / dd, 0, 1)
    q = a[None] + s[..., None] * d[None]
    return np.min(np.hypot(*(q - p[:, None, :]).transpose(2, 0, 1)), axis=1)


def _sampled_overlap(a, b, tol):
    """Length of ``a`` within ``tol`` of ``b``, by 4,000 points along each segment."""
    total = 0.0
    for p0, p1 in zip(a[:-1], a[1:], strict=True):
        t = (np.arange(4000) + 0.5) / 4000
        pts = p0 + t[:, None] * (p1 - p0)
        total += np.hypot(*(p1 - p0)) * np.mean(_dist_to_polyline(pts, b) <= tol)
    return total


@functools.cache
def _plans(seed):
    """Plans of three seeded parts (computed once per seed: the tests only read them)."""
    rng = np.random.default_rng(seed)
    parts = [fc.Polygon(star(rng, n=int(rng.integers(20, 60)))) for _ in range(2)]
    parts.append(random_polygon(rng, "star"))
    return tuple((part, fc.plan(part, fingers=2, mu=float(rng.uniform(0.2, 0.6)), top=25,
                                distinct=0))
                 for part in parts)


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                      for s in range(1, 6))])
def test_region_overlap_matches_a_sampled_estimate(seed):
    checked = 0
    for part, plans in _plans(seed):
        tol = 1e-9 * part.size
        regions = [r for p in plans for r in p.regions]
        for a in regions[:12]:
            for b in regions[:12]:
                exact = region_overlap(a, b, tol)
                est = _sampled_overlap(a, b, 1e-7 * part.size)
                la = float(np.sum(np.hypot(*np.diff(a, axis=0).T)))
                assert abs(exact - est) <= 2e-3 * la + 1e-9 * part.size, (exact, est, la)
                checked += 1
    assert checked > 200


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                      for s in range(1, 6))])
def test_remembered_overlaps_are_region_overlaps_bit_for_bit(seed):
    """Suppression's overlaps, each pair of regions computed once and each region
    buffered once (``_Overlaps``), are :func:`region_overlap`'s, asked in any order and
    again, both ways round (the overlap is not symmetric to the bit)."""
    from fcgrasp.model.distinct import _Overlaps

    rng = np.random.default_rng(seed)
    asked = 0
    for part, plans in _plans(seed):
        tol = 1e-9 * part.size
        regions = [np.asarray(r, float) for p in plans for r in p.regions][:30]
        measure = _Overlaps(tol)
        pairs = [(i, j) for i in range(len(regions)) for j in range(len(regions))]
        for k in [*rng.permutation(len(pairs)), *rng.permutation(len(pairs))]:
            i, j = pairs[k]
            assert measure(regions[i], regions[j]) == region_overlap(regions[i], regions[j],
                                                                     tol)
            asked += 1
        assert len(measure._pairs) <= len(pairs)
    assert asked > 2000


@pytest.mark.parametrize("fraction", [0.2, 0.5, 0.9])
@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow)])
def test_suppression_keeps_distinct_plans_and_accounts_for_the_rest(seed, fraction):
    for part, plans in _plans(seed):
        tol = 1e-12 * part.size
        kept = distinct_plans(plans, fraction, part.size)
        # copies of the plans kept, in rank order, the first plan always kept
        rank = {id(p): k for k, p in enumerate(plans)}
        for p in kept:
            rank[id(p)] = next(k for k, q in enumerate(plans) if q.edges == p.edges
                               and np.array_equal(q.lengths, p.lengths))
        assert [rank[id(p)] for p in kept] == sorted(rank[id(p)] for p in kept)
        assert rank[id(kept[0])] == 0 and all(not p.similar for p in plans)
        for i, p in enumerate(kept):
            for q in kept[i + 1:]:
                assert not same_alternative(p, q, fraction, tol)
        # every other plan is the same alternative as the first better kept plan it
        # matches, and that plan lists it
        kept_ranks = {rank[id(p)] for p in kept}
        for k, q in enumerate(plans):
            if k in kept_ranks:
                continue
            twin = next(p for p in kept if rank[id(p)] < k
                        and same_alternative(p, q, fraction, tol))
            assert q.edges in twin.similar
        assert sum(len(p.similar) for p in kept) == len(plans) - len(kept)
        assert distinct_plans(plans, 0.0, part.size) == plans


def test_a_curved_outline_has_one_grasp_shifted_and_plan_finds_others():
    """On demo:cam the ten best plans of the ranked list (distinct=0, the default) are
    one grasp shifted by an edge: with distinct=0.5 they are one alternative, and plan()
    searches deeper for the others."""
    cam = fc.read_part("demo:cam")
    ten = fc.plan(cam, fingers=2, mu=0.3, top=10, distinct=0)
    assert len(distinct_plans(ten, 0.5, cam.size)) == 1
    alt = fc.plan(cam, fingers=2, mu=0.3, top=2, distinct=0.5)
    assert alt[0].edges == ten[0].edges and len(alt[0].similar) >= 9
    for i, p in enumerate(alt):
        for q in alt[i + 1:]:
            assert not same_alternative(p, q, 0.5, 1e-12 * cam.size)
    again = fc.plan(cam, fingers=2, mu=0.3, top=10, distinct=0.0)
    assert [(p.edges, p.lengths.tolist()) for p in again] == \
        [(p.edges, p.lengths.tolist()) for p in ten]


@pytest.mark.parametrize("kw", [pytest.param(dict(fingers=3, mu=0.4), marks=pytest.mark.slow),
                                dict(fingers=4), dict(fingers=3, gravity=(0, -1))],
                         ids=["3", "4", "3g"])
def test_deeper_rounds_keep_the_plans_of_suppression_along_the_whole_list(kw):
    """Where no distinct search of the gripper's own applies (ranked by resistance:
    the ranked list is then read in rounds and suppressed): however the rounds grow, the
    plans kept are suppression's along the ranked list at the full depth
    (``DISTINCT_DEPTH`` times ``top``, or the gripper's ``distinct_depth``, asked for at
    once), on demo:cam (one grasp fills the list: the rounds reach the depth), the blob
    (and the bracket without friction)."""
    from fcgrasp.grippers.fingers import point_fingers
    from fcgrasp.planning.planner import DISTINCT_DEPTH

    depth = getattr(point_fingers(kw["fingers"], kw.get("mu", 0.0), kw.get("gravity")),
                    "distinct_depth", DISTINCT_DEPTH)
    rng = np.random.default_rng(5)
    names = ["cam", "blob"] if kw.get("mu") else ["blob", "bracket"]
    for part in map(fc.read_part, (f"demo:{n}" for n in names)):
        top, fraction = int(rng.integers(2, 5)), float(rng.choice([0.3, 0.5]))
        got = fc.plan(part, top=top, distinct=fraction, rank_by="resistance", **kw)
        whole = fc.plan(part, top=depth * top, distinct=0, rank_by="resistance", **kw)
        want = distinct_plans(whole, fraction, part.size)[:top]
        assert [p.edges for p in got] == [p.edges for p in want]
        for p, q in zip(got, want, strict=True):
            assert np.allclose(p.lengths, q.lengths, rtol=0, atol=1e-9 * part.size)


def test_distinct_is_checked_and_reported(tmp_path):
    from fcgrasp.planning import PlanRequest, plan_document

    with pytest.raises(ValueError, match="distinct"):
        fc.plan(fc.read_part("demo:blob"), mu=0.3, distinct=1.5)
    with pytest.raises(ValueError, match="--distinct"):
        PlanRequest(part="demo:blob", distinct=-0.1)
    doc = plan_document(PlanRequest(part="demo:cam", top=2, distinct=0.5))
    assert doc.report["parameters"]["distinct"] == 0.5
    assert len(doc.report["grasps"][0]["similar"]) >= 9
    plain = plan_document(PlanRequest(part="demo:cam", top=2, distinct=0))
    assert "distinct" not in plain.report["parameters"]
    assert all("similar" not in g for g in plain.report["grasps"])
    default = plan_document(PlanRequest(part="demo:cam", top=2))      # distinct=None
    assert default.report["parameters"]["distinct"] == 0.5
    assert [g["edges"] for g in default.report["grasps"]] == \
        [g["edges"] for g in doc.report["grasps"]]


def _image(poly, kind, ang):
    import shapely.affinity as aff

    g = poly.centroid
    shp = poly.to_shapely()
    if kind == "rot":
        return aff.rotate(shp, ang, origin=(g[0], g[1]), use_radians=True)
    moved = aff.translate(shp, -g[0], -g[1])
    c, s = np.cos(2 * ang), np.sin(2 * ang)
    return aff.translate(aff.affine_transform(moved, [c, s, s, -c, 0, 0]), g[0], g[1])


@pytest.mark.parametrize(("vertices", "count"), [
    ([[0, 0], [4, 0], [4, 2], [0, 2]], 4),                          # rectangle: D2
    ([[0, 0], [3, 0], [3, 3], [0, 3]], 8),                          # square: D4
    ([[0, 0], [2, 0], [1, np.sqrt(3)]], 6),                         # equilateral: D3
    ([[0, 0], [5, 0], [4, 2], [1, 3]], 1),                          # none but the identity
    ([[0, 0], [6, 0], [6, 1], [0, 1], [-1, 0.5]], 2),               # one mirror
])
def test_part_symmetries_against_shapely_images(vertices, count):
    from fcgrasp.model.distinct import part_symmetries

    poly = fc.Polygon(vertices)
    syms = part_symmetries(poly)
    assert len(syms) == count, syms
    shp = poly.to_shapely()
    for kind, ang in syms:                        # each maps the part onto itself
        assert _image(poly, kind, ang).symmetric_difference(shp).area < 1e-9 * shp.area
    rng = np.random.default_rng(7)
    for ang in rng.uniform(0, 2 * np.pi, 40):     # no other isometry does
        for kind in ("rot", "ref"):
            same = _image(poly, kind, ang).symmetric_difference(shp).area < 1e-9 * shp.area
            found = any(k == kind and abs(np.angle(np.exp(1j * (a - ang) * (1 if k == "rot"
                        else 2)))) < 1e-6 for k, a in syms)
            assert found or not same      # an isometry that maps the part is listed


@pytest.mark.slow      # 18 s: the jaw plans of the rectangle twice
def test_jaw_boxes_are_distinct_up_to_the_part_symmetries():
    """On demo:rectangle ranks 2-5 were one box and its images under the part's mirror
    symmetries."""
    from fcgrasp.model.distinct import part_symmetries, same_box

    part = fc.read_part("demo:rectangle")
    jaw = fc.ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
    every = fc.plan(part, gripper=jaw, top=5, distinct=0)
    syms = part_symmetries(part)
    # the plain list holds the same alternative twice by the jaw's rule (since the boxes
    # are searched on the exact holding set, as neighbouring slices of one configuration
    # rather than mirror images)
    assert len(jaw.distinct_plans(part, every, 0.5)) < len(every)
    kept = fc.plan(part, gripper=jaw, top=5, distinct=0.5)
    assert kept[0].theta == every[0].theta and kept[1].theta == every[1].theta
    for i, p in enumerate(kept):
        for q in kept[i + 1:]:
            assert not same_box(p, q, 0.5, syms) and not same_box(q, p, 0.5, syms)
    assert len(jaw.distinct_plans(part, kept, 0.5)) == len(kept)
    assert kept[1].similar >= 3 and kept[1].to_dict()["similar"] == kept[1].similar


def test_adjacent_jaw_boxes_of_one_contact_are_one_alternative():
    """On demo:triangle the boxes ranked 2-6 were adjacent 6.5-degree slices of one
    slanted band of poses (the same edges under each pad): with distinct=
    they are one alternative, the best standing for the rest; boxes apart by more than
    a grid step, or touching other edges, stay."""
    part = fc.read_part("demo:triangle")
    jaw = fc.ParallelJaw(stroke=(5, 90), pad_width=8, mu=0.5)
    every = fc.plan(part, gripper=jaw, top=6, distinct=0)
    key = [tuple(tuple(sorted(f)) for f in p.features) for p in every]
    assert len(set(key)) < len(key)               # slices touching the same edges
    kept = fc.plan(part, gripper=jaw, top=6, distinct=0.5)
    step_t, seen = np.radians(0.5), {}
    for p in kept:
        k = tuple(tuple(sorted(f)) for f in p.features)
        for q in seen.get(k, []):                  # the same contacts: not neighbours
            gap_t = max(q.theta[0] - p.theta[1], p.theta[0] - q.theta[1])
            gap_c = max(q.offset[0] - p.offset[1], p.offset[0] - q.offset[1])
            assert gap_t > step_t * 1.01 or gap_c > 0.0 or \
                gap_c > 2 * (p.offset[1] - p.offset[0])
        seen.setdefault(k, []).append(p)
    assert any(p.similar >= 2 for p in kept)
    assert kept[0].theta == every[0].theta


@pytest.mark.parametrize("name", ["bracket", *(
    pytest.param(n, marks=pytest.mark.slow) for n in ("blob", "quad", "triangle", "washer",
                                                      "rectangle"))])
def test_jaw_boxes_are_distinct_alternatives_by_default(name):
    """A parallel jaw's default top ten are distinct alternatives, the best of
    each group of boxes that are one grasp (a mirror image, a turn, a neighbouring slice
    of one contact configuration), by the jaw's own rule at DEFAULT_DISTINCT; the same
    boxes as distinct=0.5 asked for, and the ranked list (distinct=0) keeps its first
    box. Point fingers keep their ranked list by default."""
    from fcgrasp.model.distinct import DEFAULT_DISTINCT, grip_symmetries, same_box

    part = fc.read_part(f"demo:{name}")
    jaw = fc.ParallelJaw(stroke=(5, 90), pad_width=8, mu=0.5)
    plans = fc.plan(part, gripper=jaw)
    assert len(plans) >= 3
    assert [(p.theta, p.offset) for p in plans] == \
        [(p.theta, p.offset) for p in fc.plan(part, gripper=jaw, distinct=DEFAULT_DISTINCT)]
    assert len(jaw.distinct_plans(part, plans, DEFAULT_DISTINCT)) == len(plans)
    for i, p in enumerate(plans):
        syms = grip_symmetries(part, getattr(p, "insert", None))
        for q in plans[i + 1:]:
            assert p.hole != q.hole or not same_box(p, q, DEFAULT_DISTINCT, syms) \
                and not same_box(q, p, DEFAULT_DISTINCT, syms), (p, q)
    ranked = fc.plan(part, gripper=jaw, top=1, distinct=0)
    assert (ranked[0].theta, ranked[0].offset) == (plans[0].theta, plans[0].offset)
    fingers = fc.plan(part, fingers=2, mu=0.3, top=4)
    assert [p.edges for p in fingers] == \
        [p.edges for p in fc.plan(part, fingers=2, mu=0.3, top=4, distinct=0)]


def _smooth(rng, n):
    """A smooth outline of ``n`` edges (an ellipse with a wave), so that regions run
    along it and every grasp has shifted copies."""
    a = np.sort(rng.uniform(0, 2 * np.pi, n)) if rng.random() < 0.5 else \
        np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 1 + float(rng.uniform(0, 0.15)) * np.cos(int(rng.integers(2, 5)) * a)
    return fc.Polygon(np.c_[float(rng.uniform(30, 60)) * r * np.cos(a),
                            float(rng.uniform(15, 30)) * r * np.sin(a)])


def _searched_and_suppressed(seed):
    """A seeded smooth outline (a grasp has dozens of shifted copies) planned with
    ``distinct=`` by the search that leaves each kept plan's copies out, and suppression
    along the *whole* ranked list (every configuration, ``top=None``): ``(part, got,
    want)``, asserted the same edges and region lengths."""
    from fcgrasp.grippers._boundary import boundary_plans
    from fcgrasp.pipeline import plan_spec

    rng = np.random.default_rng(seed)
    part = _smooth(rng, int(rng.integers(24, 48)))
    mu = float(rng.uniform(0.2, 0.5))
    fraction = float(rng.choice([0.25, 0.5, 0.8]))
    top = int(rng.integers(3, 8))
    every = boundary_plans(part, plan_spec(fingers=2, mu=mu, top=None))
    want = distinct_plans(every, fraction, part.size)[:top]
    # (no time limit: the exact answer, however busy the machine)
    got = fc.plan(part, fingers=2, mu=mu, top=top, distinct=fraction, time_limit=None)
    assert [p.edges for p in got] == [p.edges for p in want]
    for p, q in zip(got, want, strict=True):
        assert np.allclose(p.lengths, q.lengths, rtol=0, atol=1e-9 * part.size)
    return part, got, want


def _planned_again(seed, part, got):
    """:func:`_searched_and_suppressed`'s plan of ``seed`` made again (the reference,
    under the caller's patches), asserted the same edges and regions as ``got``."""
    rng = np.random.default_rng(seed)
    _smooth(rng, int(rng.integers(24, 48)))
    mu = float(rng.uniform(0.2, 0.5))
    fraction = float(rng.choice([0.25, 0.5, 0.8]))
    top = int(rng.integers(3, 8))
    ref = fc.plan(part, fingers=2, mu=mu, top=top, distinct=fraction, time_limit=None)
    _same_plans(got, ref)


def _same_plans(got, ref):
    """The same edges, and regions equal to the bit."""
    assert [p.edges for p in got] == [p.edges for p in ref]
    for p, q in zip(got, ref, strict=True):
        for a, b in zip(p.regions, q.regions, strict=True):
            assert np.array_equal(a, b)


@pytest.mark.parametrize("seed", [0, 1, 78, *(pytest.param(s, marks=pytest.mark.slow)
                                                for s in range(2, 200) if s != 78)])
def test_distinct_search_equals_suppression_of_every_plan(seed):
    """Two fingers along the boundary with ``distinct=``: the search that leaves each
    kept plan's copies out (fcgrasp.grippers._boundary.distinct_boundary_plans) gives
    the plans that suppression along the *whole* ranked list gives (every
    configuration of the part, ``top=None``), same edges and region lengths, on seeded
    smooth outlines where a grasp has dozens of shifted copies (seed 78 by default: a
    kept plan's copy there is deferred and must still beat its super-configuration)."""
    _, got, want = _searched_and_suppressed(seed)
    assert len(want) > 1
    for p, q in zip(got, want, strict=True):
        assert set(p.similar) <= set(q.similar)


@pytest.mark.parametrize("seed", [4, *(pytest.param(s, marks=pytest.mark.slow)
                                    for s in (*range(5, 60), 78))])
def test_distinct_search_with_its_floor_lowered_equals_suppression(seed, monkeypatch):
    """The distinct search's memo collects only configurations long enough to reach a
    share of the best plan (MEMO_SHARE), and collects again lower when a round's
    ``top``-th falls below it: with the share at 0.9 (every search lowers it, most of
    them more than once) the plans are still suppression's along the whole list."""
    from fcgrasp.model import stretches

    lowered = []
    monkeypatch.setattr(stretches, "MEMO_SHARE", 0.9)
    original = stretches._Memo.lower
    monkeypatch.setattr(stretches._Memo, "lower",
                        lambda self, f: (lowered.append(f), original(self, f))[1])
    _searched_and_suppressed(seed)
    if seed in (4, 78):
        assert len(lowered) >= 2, lowered             # the first floor, then lower


@pytest.mark.parametrize("seed", [0, 1, *(pytest.param(s, marks=pytest.mark.slow)
                                      for s in range(2, 30))])
def test_rounds_that_keep_nothing_read_more_and_give_suppressions_plans(seed,
                                                                       monkeypatch):
    """A two-finger distinct round that keeps no new plan makes the next read
    READ_GROWTH times as many (a half disc's region on its long diameter has copies the
    exclusion cannot leave out, placed anywhere along the edge): the plans are
    suppression's along the whole ranked list and those of rounds that read only the
    plans still missing (``READ_GROWTH = 1``, the reference), in fewer rounds."""
    from fcgrasp.grippers import _boundary
    from fcgrasp.grippers._boundary import boundary_plans
    from fcgrasp.model.stretches import StretchSearch
    from fcgrasp.pipeline import plan_spec

    rng = np.random.default_rng(seed)
    a = np.linspace(0, np.pi, int(rng.integers(20, 40)))
    part = fc.Polygon(np.c_[40 * np.cos(a), float(rng.uniform(15, 40)) * np.sin(a)])
    mu = float(rng.uniform(0.2, 0.6))
    top = int(rng.integers(4, 8))
    rounds = []
    pairs = StretchSearch.pairs
    monkeypatch.setattr(StretchSearch, "pairs",
                        lambda self, *a, **k: (rounds.append(k.get("top")),
                                               pairs(self, *a, **k))[1])
    got = fc.plan(part, fingers=2, mu=mu, top=top, time_limit=None)
    grown = len(rounds)
    rounds.clear()
    monkeypatch.setattr(_boundary, "READ_GROWTH", 1)
    ref = fc.plan(part, fingers=2, mu=mu, top=top, time_limit=None)
    every = boundary_plans(part, plan_spec(fingers=2, mu=mu, top=None))
    want = distinct_plans(every, 0.5, part.size)[:top]
    assert [p.edges for p in ref] == [p.edges for p in want]
    _same_plans(got, ref)
    assert grown <= len(rounds)
    if seed == 0:
        assert grown < len(rounds), (grown, len(rounds))


@pytest.mark.parametrize("seed", [4, 78, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(5, 60))])
def test_a_small_collections_long_step_down_gives_the_plans_of_short_ones(seed,
                                                                         monkeypatch):
    """A round that finds too few above its floor lowers it by FLOOR_STEP_SMALL on an
    outline of at most SMALL_OUTLINE edges (each collection costs its fixed cost): the
    plans and regions are those of the short steps alone (``SMALL_OUTLINE = 0``, the
    reference), in no more collections (fewer where the floors step down, as in the
    default cases), with the first floor high (MEMO_SHARE 0.9)."""
    from fcgrasp.model import stretches

    floors = []
    original = stretches._Memo.lower
    monkeypatch.setattr(stretches, "MEMO_SHARE", 0.9)
    monkeypatch.setattr(stretches._Memo, "lower",
                        lambda self, f: (floors.append(f), original(self, f))[1])
    part, got, _ = _searched_and_suppressed(seed)
    long_steps = len(floors)
    floors.clear()
    monkeypatch.setattr(stretches, "SMALL_OUTLINE", 0)
    _planned_again(seed, part, got)
    assert long_steps <= len(floors), (long_steps, len(floors))
    if seed in (4, 78):                     # (floors that step down)
        assert long_steps < len(floors), (long_steps, len(floors))


@pytest.mark.parametrize("seed", [4, 78, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(5, 60))])
@pytest.mark.parametrize("jit", ["1", "0"])
def test_a_capped_collection_gives_the_plans_of_suppression(seed, jit, monkeypatch):
    """A distinct round collects at most COLLECT_CAP configurations at once and tries
    higher floors where more reach its own (half way up to one that found too few), or
    collects in full where the answer needs that floor: with the cap at 20 (most rounds
    go over it, compiled or not) the plans are still suppression's along the whole
    ranked list."""
    from fcgrasp.core.budget import BudgetExhausted
    from fcgrasp.model import stretches
    from fcgrasp.model.stretches import _rounds as _stretch_search

    monkeypatch.setenv("FCGRASP_JIT", jit)
    monkeypatch.setattr(stretches, "COLLECT_CAP", 20)
    over = []
    original = _stretch_search._candidates

    def candidates(*a, **k):
        try:
            return original(*a, **k)
        except BudgetExhausted as exc:
            over.append(str(exc))
            raise

    monkeypatch.setattr(_stretch_search, "_candidates", candidates)
    _searched_and_suppressed(seed)
    if seed in (4, 13, 78):
        assert "collection" in over, over


@pytest.mark.parametrize("seed", range(3))
def test_a_distinct_rounds_bound_is_the_kth_largest_configuration(seed):
    """A distinct round's bound counts each configuration (``_Bound(each=True)``: its
    rows add no lower bounds): its value is the ``k``-th largest value added so far (0
    before ``k``), read against a sort after every chunk, chunks of any size, values
    tied and repeated; the per-key bound stays at most one per key."""
    from fcgrasp.model.stretches._windows import TIE, _Bound

    rng = np.random.default_rng(seed)
    for _ in range(200):
        k = int(rng.integers(1, 30))
        each, keyed = _Bound(k, 7, each=True), _Bound(k, 7)
        added = []
        for _ in range(int(rng.integers(1, 12))):
            n = int(rng.integers(0, 40))
            v = rng.choice([0.0, 0.5, 1.0, 2.0], n) if rng.random() < 0.3 \
                else rng.uniform(0, 3, n)
            keys = rng.integers(0, 7, n)
            each.add(keys, v)
            keyed.add(keys, v)
            added += v.tolist()
            want = sorted(added, reverse=True)[k - 1] if len(added) >= k else 0.0
            assert each.value == want
            assert keyed.value <= want
            assert each.floor == want * (1 - TIE)


@pytest.mark.parametrize("seed", [0, 78, *(pytest.param(s, marks=pytest.mark.slow)
                                         for s in range(1, 40))])
def test_distinct_rounds_with_the_per_key_bound_give_the_same_plans(seed, monkeypatch):
    """The previous bound of a distinct round (one value per key: on a curved outline
    the kept plans leave most keys empty, so its floor stayed 0 and the round solved
    every configuration) is kept as the reference: the plans, their regions and what
    they stand for are the same, two fingers and three."""
    from fcgrasp.model import stretches

    rng = np.random.default_rng(seed)
    part = _smooth(rng, int(rng.integers(24, 60)))
    mu = float(rng.uniform(0.2, 0.5))
    fraction = float(rng.choice([0.25, 0.5, 0.8]))
    kw = [dict(fingers=2, mu=mu, top=int(rng.integers(3, 8)), distinct=fraction,
               time_limit=None),
          dict(fingers=3, mu=mu, top=int(rng.integers(3, 8)), distinct=fraction,
               time_limit=None)]
    got = [fc.plan(part, **k) for k in kw]
    from fcgrasp.model.stretches import _rounds as _stretch_search

    bound = stretches._Bound
    monkeypatch.setattr(_stretch_search, "_Bound",
                        lambda *a, each=False, **k: bound(*a, **k))
    want = [fc.plan(part, **k) for k in kw]
    for g, w in zip(got, want, strict=True):
        assert [p.edges for p in g] == [p.edges for p in w]
        for p, q in zip(g, w, strict=True):
            assert p.similar == q.similar
            for a, b in zip(p.regions, q.regions, strict=True):
                assert np.array_equal(a, b)


def test_internal_grips_use_the_symmetries_that_keep_their_hole():
    """A symmetry that keeps a hole and the point the jaws go in at maps an internal
    grip's boxes onto the same grasps (the washer's centred hole: its four turns); one
    that takes the hole to another, or moves the point, does not. The jaw's own search
    then returns no two boxes that are images of each other, internal ones included
    (the washer's internal boxes 90 degrees apart were two of its top ten)."""
    from fcgrasp.grippers.jaw import insertion_point
    from fcgrasp.model.distinct import grip_symmetries, part_symmetries, same_box

    part = fc.read_part("demo:washer")
    jaw = fc.ParallelJaw(stroke=(5, 60), pad_width=8, mu=0.5)
    plans = fc.plan(part, gripper=jaw, top=10, distinct=0)
    assert any(p.mode == "internal" for p in plans)
    assert len(grip_symmetries(part, insertion_point(part, 0))) == len(part_symmetries(part))
    for i, p in enumerate(plans):
        syms = grip_symmetries(part, p.insert)
        for q in plans[i + 1:]:
            assert not same_box(p, q, 0.5, syms) and not same_box(q, p, 0.5, syms), (p, q)
    # a plate with two square holes side by side: the turn by pi and the mirror across
    # the vertical axis swap them; the mirror across the horizontal axis keeps each
    square = np.array([[-4.0, -4], [4, -4], [4, 4], [-4, 4]])
    plate = fc.Polygon([[-30, -15], [30, -15], [30, 15], [-30, 15]],
                       holes=[square + [-15, 0], square + [15, 0]])
    assert len(part_symmetries(plate)) == 4
    for h in (0, 1):
        kept = grip_symmetries(plate, insertion_point(plate, h))
        assert len(kept) == 2 and ("rot", 0.0) in kept, kept
        assert all(k == "rot" and a == 0.0 or k == "ref" and abs(np.sin(a)) < 1e-9
                   for k, a in kept), kept


def test_suppression_with_a_limit_keeps_the_head_and_what_it_stands_for():
    """``distinct_plans(limit=)``: the first ``limit`` kept plans of suppression along the
    whole list, each with every plan it stands for (the planner's rounds use it)."""
    part = fc.read_part("demo:cam")
    # a grasp's copies along the curve, then single-edge plans elsewhere (suppression
    # reads any list in its order)
    plans = fc.plan(part, fingers=2, mu=0.3, top=60, distinct=0) + \
        fc.plan(part, fingers=2, mu=0.3, top=60, along_boundary=False, distinct=0)
    whole = distinct_plans(plans, 0.5, part.size)
    assert len(whole) > 5 and len(whole[0].similar) > 50
    for limit in (1, 2, 5):
        head = distinct_plans(plans, 0.5, part.size, limit=limit)
        assert [(p.edges, p.similar) for p in head] == \
            [(p.edges, p.similar) for p in whole[:limit]]


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(8))
@pytest.mark.parametrize("fraction", [0.2, 0.5, 0.9])
def test_suppression_reads_only_plans_whose_boxes_pair_and_keeps_the_same(seed, fraction):
    """(Under ``-m slow``: by default the first-twin rule is checked on two-finger lists by
    :func:`test_suppression_keeps_distinct_plans_and_accounts_for_the_rest`.)  Suppression
    reads, for each plan, only the kept plans whose regions' boxes pair
    with its own: the same plans kept, each standing for the same plans, as suppression
    that tests every kept plan in order (written here) on whole ranked lists of two,
    three with gravity and four fingers (regions of point fingers, gravity's point)."""
    from fcgrasp.core.tolerances import ROUND_TOL
    from fcgrasp.model.distinct import Suppression

    rng = np.random.default_rng(300 + seed)
    n = int(rng.integers(11, 15))
    a = np.sort(rng.uniform(0, 2 * np.pi, n))
    r = 30 + rng.uniform(2, 5) * np.sin(3 * a + rng.uniform(0, 6)) + 2 * np.cos(5 * a)
    part = fc.Polygon(np.c_[r * np.cos(a), r * np.sin(a)])     # regions along the boundary
    tol = ROUND_TOL * part.size
    lists = [fc.plan(part, fingers=2, mu=0.4, top=None, distinct=0),     # ranked lists
             fc.plan(part, fingers=3, gravity=(0, -1), top=None, distinct=0),
             fc.plan(part, fingers=4, top=None, distinct=0)]
    checked = 0
    for plans in lists:
        kept, stands = [], {}
        for p in plans:
            twin = next((q for q in kept if same_alternative(q, p, fraction, tol)), None)
            if twin is None:
                kept.append(p)
                stands[id(p)] = []
            else:
                stands[id(twin)].append(tuple(p.edges))
        suppression = Suppression(fraction, part.size)
        for p in plans:
            suppression.add(p)
        assert [id(p) for p in suppression.kept] == [id(p) for p in kept]
        assert [p.similar for p in suppression.plans()] == [tuple(stands[id(p)]) for p in kept]
        checked += len(plans) - len(kept)
    assert checked >= 5


_POINT_GRIPPERS = {"2f": dict(fingers=2, mu=0.3), "3f": dict(fingers=3, mu=0.4),
                   "3g": dict(fingers=3, gravity=(0.0, -1.0)), "4f": dict(fingers=4)}
_DEFAULT_CASES = [("cam", "2f"), ("bracket", "3g"), ("triangle", "4f"), ("blob", "3f")]


def _pairwise_distinct(plans, size):
    for i, p in enumerate(plans):
        for q in plans[:i]:
            assert not same_alternative(q, p, 0.5, 1e-12 * size), (q.edges, p.edges)


@pytest.mark.parametrize(("name", "grip"), [
    *_DEFAULT_CASES, *(pytest.param(n, g, marks=pytest.mark.slow)
                       for n in ("blob", "triangle", "quad", "bracket", "washer", "rectangle",
                                 "cam") for g in _POINT_GRIPPERS
                       if (n, g) not in _DEFAULT_CASES)])
def test_point_fingers_plans_are_distinct_alternatives_by_default(name, grip):
    """By default (distinct=None) the top ten plans of every point-finger
    gripper are pairwise distinct by the documented rule (no two the same alternative
    at half the shorter region), the plans of distinct=0.5, and where the ranked list
    has copies, fewer of them are copies than in the ranked list (demo:cam, two
    fingers: its ranked ten are one grasp)."""
    part = fc.read_part(f"demo:{name}")
    kw = _POINT_GRIPPERS[grip]
    got = fc.plan(part, top=10, **kw)
    _pairwise_distinct(got, part.size)
    assert [p.edges for p in got] == [p.edges for p in fc.plan(part, top=10, distinct=0.5,
                                                                 **kw)]
    ranked = fc.plan(part, top=10, distinct=0, **kw)
    assert [p.edges for p in got[:1]] == [p.edges for p in ranked[:1]]
    if (name, grip) == ("cam", "2f"):
        assert len(distinct_plans(ranked, 0.5, part.size)) < len(got)


@pytest.mark.slow
@pytest.mark.parametrize("grip", list(_POINT_GRIPPERS))
@pytest.mark.parametrize("path", ["icons/heart.svg", "dxf/forms.dxf", "gears/teeth-20.dxf",
                                  "countries/CHE.geo.json"])
def test_corpus_plans_are_distinct_alternatives_by_default(path, grip):
    """The same on public drawings of the real-file corpus (benchmarks/corpus)."""
    from pathlib import Path

    corpus = Path(__file__).parent.parent / "benchmarks" / "corpus"
    part = fc.load_part(str(corpus / path)).polygon
    _pairwise_distinct(fc.plan(part, **_POINT_GRIPPERS[grip]), part.size)


def _boundary_regions(rng, poly):
    """Pairs of regions along ``poly``'s boundary with the edges of their segments:
    one from anywhere, the other the same shifted a little, a lot, by whole edges,
    ending at a vertex, or elsewhere on the ring."""
    from fcgrasp.model.stretches._placement import _polyline
    from fcgrasp.model.stretches._windows import _rings

    ring = _rings(poly)[0]
    m = ring.m

    def region(i, k, s0, frac):
        L = float(ring.L[i % m])
        s0 = min(max(s0, 0.0), L)
        j = i % m + m
        to_last = L - s0 + float(ring.U[j + k] - ring.U[j + 1]) if k else -s0
        last = float(ring.L[(i + k) % m])
        t = to_last + frac * last if k else (L - s0) * frac
        return _polyline(ring, i, k, s0, t)

    for _ in range(12):
        i, k = int(rng.integers(0, m)), int(rng.integers(0, min(m - 2, 8)))
        s0, frac = float(rng.uniform(0, ring.L[i])), float(rng.uniform(0, 1))
        a = region(i, k, s0, frac)
        how = rng.integers(0, 5)
        if how == 0:            # a hair, or a little, along
            d = float(rng.choice([1e-13, 1e-9, 1e-4, 0.05])) * float(ring.L[i])
            b = region(i, k, s0 + d, frac)
        elif how == 1:          # whole edges on
            b = region(i + int(rng.integers(-2, 3)), k, s0, frac)
        elif how == 2:          # ending at a vertex
            b = region(i, k, float(rng.choice([0.0, float(ring.L[i])])),
                       float(rng.choice([0.0, 1.0])))
        elif how == 3:          # longer or shorter by whole edges
            b = region(i, max(k + int(rng.integers(-2, 3)), 0), s0, frac)
        else:                   # anywhere
            b = region(int(rng.integers(0, m)), int(rng.integers(0, min(m - 2, 8))),
                       float(rng.uniform(0, 1)) * float(ring.L[0]), float(rng.uniform(0, 1)))
        yield a, b


def _seeded_outlines(rng, cases):
    """Seeded outlines of every kind (exact ties, collinear runs, noise), scaled and
    moved near the origin or far from it, each with the overlap's tolerance."""
    from fcgrasp.core.tolerances import ROUND_TOL

    from .test_stretch_kernels import KINDS, outline

    for case in range(cases):
        pts = outline(rng, KINDS[case % len(KINDS)], int(rng.integers(8, 80)))
        pts = pts * float(rng.choice([1.0, 1e-3, 1e3])) + float(rng.choice([0.0, 1e4])) \
            * rng.normal(size=2)
        poly = fc.Polygon(pts)
        yield poly, ROUND_TOL * poly.size


@pytest.mark.parametrize("cases", [pytest.param(40, id="seeded"),
                                   pytest.param(1500, id="sweep", marks=pytest.mark.slow)])
def test_the_shared_pieces_bound_the_overlap_from_below(cases):
    """What two boundary regions' pieces on the same edges surely have in common
    (``_shared_length``, read from the regions' edges) is at most the overlap the
    buffer measures (``region_overlap``), on seeded outlines of every kind (exact ties,
    collinear runs, noise), near the origin and far from it, for regions shifted by a
    hair, a little, whole edges, ending at vertices, or elsewhere; and it is that
    overlap to within a few tolerances wherever they share an edge, so the search
    reads most same alternatives without the buffer.  Then ``same_alternative`` gives
    the same answers with the regions' edges (the bound first) and without them."""
    from fcgrasp.model import distinct as D

    rng = np.random.default_rng(91)
    tight = shared = pairs = 0
    answers = {True: 0, False: 0}
    for poly, tol in _seeded_outlines(rng, cases):
        for (a, ea), (b, eb) in _boundary_regions(rng, poly):
            pa, pb = D._pieces(a, ea), D._pieces(b, eb)
            assert pa is not None and pb is not None
            lb = D._shared_length(pa, pb, tol)
            exact = region_overlap(a, b, tol)
            assert lb <= exact, (lb, exact)
            pairs += 1
            if lb > 0:
                shared += 1
                tight += exact - lb <= 1e-9 * poly.size
            # the decision, with the regions' edges and without
            la = float(np.sum(np.hypot(*np.diff(a, axis=0).T)))
            lb_len = float(np.sum(np.hypot(*np.diff(b, axis=0).T)))
            plans = []
            for labelled in (True, False):
                kw = {"region_edges": (ea, eb)} if labelled else {}
                plans.append([fc.GraspPlan((ea[0], eb[0]), (r1, r2), np.array([l1, l2]),
                                           np.zeros((2, 2)), np.zeros((2, 2)), "friction",
                                           0.5, "squeeze", 0.0, **kw)
                              for r1, r2, l1, l2 in ((a, b, la, lb_len), (b, a, lb_len, la))])
            for fraction in (0.25, 0.5, 0.9):
                got = same_alternative(*plans[0], fraction, tol)
                assert got == same_alternative(*plans[1], fraction, tol)
                answers[got] += 1
    assert shared > pairs // 3 and tight > 0.9 * shared, (pairs, shared, tight)
    assert min(answers.values()) > cases, answers


def test_a_shared_measure_decides_as_a_fresh_one():
    """``_Overlaps.decide_regions`` keeps each answer by what it reads: over a ranked list's
    plans (regions along the boundary, repeated across copies) compared in every
    order, a measure shared by all the comparisons gives the answers of a new measure
    per comparison, and most answers come from the kept ones."""
    from fcgrasp.core.tolerances import ROUND_TOL
    from fcgrasp.model.distinct import _Overlaps

    rng = np.random.default_rng(9)
    a = np.sort(rng.uniform(0, 2 * np.pi, 40))
    r = 30 + 3 * np.sin(3 * a + 1.0) + 2 * np.cos(5 * a)
    part = fc.Polygon(np.c_[r * np.cos(a), r * np.sin(a)])
    tol = ROUND_TOL * part.size
    plans = fc.plan(part, fingers=2, mu=0.4, top=30, distinct=0)
    class Counted(_Overlaps):
        asked = 0

        def decide_regions(self, *args, **kwargs):
            Counted.asked += 1
            return super().decide_regions(*args, **kwargs)

    shared = Counted(tol)
    answers = set()
    for p in plans:
        for q in plans:
            for fraction in (0.2, 0.5):
                got = same_alternative(p, q, fraction, tol, shared)
                assert got == same_alternative(p, q, fraction, tol, _Overlaps(tol))
                answers.add(got)
    assert answers == {True, False}
    assert len(shared._decided) < 0.5 * Counted.asked


def _random_polylines(rng, poly):
    """Pairs of polylines off the boundary: random walks near each other (crossing,
    collinear, a hair apart, sharing a vertex, reduced to one segment)."""
    scale = poly.size
    for _ in range(6):
        m = int(rng.integers(2, 9))
        a = np.cumsum(rng.normal(size=(m, 2)), axis=0) * scale * 0.1
        how = rng.integers(0, 4)
        if how == 0:            # a hair off
            b = a + rng.normal(size=2) * float(rng.choice([1e-14, 1e-12, 1e-10])) * scale
        elif how == 1:          # part of it, then away
            k = int(rng.integers(1, m))
            b = np.r_[a[:k + 1], a[k] + np.cumsum(rng.normal(size=(2, 2)), axis=0) * scale * 0.1]
        elif how == 2:          # collinear along one segment
            t = np.sort(rng.uniform(-0.5, 1.5, 2))
            b = a[0] + t[:, None] * (a[1] - a[0])
        else:
            b = np.cumsum(rng.normal(size=(int(rng.integers(2, 9)), 2)), axis=0) * scale * 0.1
        yield a, b


@pytest.mark.parametrize("cases", [pytest.param(120, id="seeded"),
                                   pytest.param(1500, id="sweep", marks=pytest.mark.slow)])
def test_the_reach_bounds_the_overlap_from_above(cases):
    """A region's length inside another's grown box (``_Overlaps.reach``) is at least
    the overlap the buffer measures (``region_overlap``, which shares none of its
    code), on boundary regions of seeded outlines of every kind, near the origin and
    far from it, and on polylines off the boundary (a hair apart, collinear, crossing);
    so ``_overlaps``, which reads it first, decides as the buffer alone does, at
    fractions 0.25, 0.5 and 0.9; and it decides most pairs that are near and not the
    same alternative."""
    from fcgrasp.model import distinct as D

    rng = np.random.default_rng(93)
    decided = near_false = pairs = 0
    answers = {True: 0, False: 0}
    for poly, tol in _seeded_outlines(rng, cases):
        both = [(a, b, ea, eb) for (a, ea), (b, eb) in _boundary_regions(rng, poly)]
        both += [(a, b, None, None) for a, b in _random_polylines(rng, poly)]
        for a, b, ea, eb in both:
            a, b = np.asarray(a, float), np.asarray(b, float)
            exact = region_overlap(a, b, tol)
            measure = D._Overlaps(tol)
            assert measure.reach(a, b) >= exact, (measure.reach(a, b), exact)
            pairs += 1
            la = float(np.sum(np.hypot(*np.diff(a, axis=0).T)))
            lb = float(np.sum(np.hypot(*np.diff(b, axis=0).T)))
            if min(la, lb) <= tol:
                continue
            for fraction in (0.25, 0.5, 0.9):
                want = exact > fraction * min(la, lb)
                got = D._overlaps(a, b, la, lb, fraction, tol, D._Overlaps(tol), ea, eb)
                assert got == want
                answers[got] += 1
                if not want and exact > 0:
                    near_false += 1
                    decided += measure.reach(a, b) <= fraction * min(la, lb)
    assert min(answers.values()) > cases, answers
    assert decided > 0.5 * near_false, (decided, near_false)


@pytest.mark.parametrize("seed", [13, 32, 55, *(pytest.param(s, marks=pytest.mark.slow)
                                               for s in range(120) if s not in (13, 32, 55))])
def test_compiled_collection_leaving_copies_out_equals_suppression(seed, monkeypatch):
    """The compiled collection of a distinct round leaves out the windows that are surely
    a kept plan's copies (``_Exclusion.copy_columns``; their beaters solved on demand):
    the plans are still suppression's along the whole ranked list, and the collection
    with nothing left out (the reference) gives the same plans and regions."""
    from fcgrasp.model.stretches import _exclusion as _stretch_exclusion
    from fcgrasp.model.stretches import _rounds as _stretch_search

    monkeypatch.setenv("FCGRASP_JIT", "1")
    left_out = []
    windows = _stretch_search._kernels.windows

    def counted(*a, ex=None, exs=None, **k):
        out = windows(*a, ex=ex, exs=exs, **k)
        if ex is not None and a[8]:             # a collection that may leave copies out
            full = windows(*a, **k)
            left_out.append(full[1].size - out[1].size)
        return out

    monkeypatch.setattr(_stretch_search._kernels, "windows", counted)
    part, got, _ = _searched_and_suppressed(seed)
    monkeypatch.setattr(_stretch_exclusion._Exclusion, "copy_columns",
                        lambda self, *a: None)
    _planned_again(seed, part, got)
    if seed in (13, 32, 55):                # (32: a left-out copy beats a plan's edges)
        assert sum(left_out) > 0, left_out


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 40))])
def test_a_lower_floors_collection_takes_what_the_last_solved(seed, monkeypatch):
    """A distinct round whose floor falls collects again and takes each configuration's
    solution and boxes from the last collection (``_Memo.lower``, ``CARRY``): the plans
    and regions are those of rounds that solve every collection anew (the reference),
    on smooth outlines where the floors fall, and the carried solutions are read."""
    from fcgrasp.model.stretches import _memo as _stretch_memo

    rng = np.random.default_rng(seed)
    a = np.linspace(0, 2 * np.pi, int(rng.integers(300, 700)), endpoint=False)
    r = 1 + rng.uniform(0.02, 0.15) * np.cos(3 * a + rng.uniform(0, 2 * np.pi))
    part = fc.Polygon(np.c_[60 * r * np.cos(a), rng.uniform(25, 45) * r * np.sin(a)])
    mu = float(rng.uniform(0.4, 1.0))
    top = int(rng.integers(3, 7))
    restored = []
    into = _stretch_memo._Carried.into

    def counted(self, J):
        restored.append(int(np.count_nonzero(~np.isnan(self.t))))
        return into(self, J)

    monkeypatch.setattr(_stretch_memo._Carried, "into", counted)
    got = fc.plan(part, fingers=2, mu=mu, top=top, time_limit=None)
    monkeypatch.setattr(_stretch_memo, "CARRY", 0)
    ref = fc.plan(part, fingers=2, mu=mu, top=top, time_limit=None)
    assert [p.edges for p in got] == [p.edges for p in ref]
    for p, q in zip(got, ref, strict=True):
        for x, y in zip(p.regions, q.regions, strict=True):
            assert np.array_equal(x, y)
    if seed in (0, 4):                      # (floors that fall: solutions carried)
        assert sum(restored) > 0, restored


def test_configurations_carried_by_codes_are_those_carried_by_records(monkeypatch):
    """A collection's configurations are filed by one integer each (``_Codes``, mixed
    radix over the ranges met) where they fit: the codes sort as the records do, two
    are equal only for the same configuration, one outside the ranges has none, and a
    job takes from the last collection exactly what the records' lookup gives it, on
    seeded collections that share some configurations (negative numbers, a number past
    the ranges, repeats included)."""
    from fcgrasp.model.stretches import _memo as V
    from fcgrasp.model.stretches._windows import _Configs

    rng = np.random.default_rng(5)

    def job(cfg):
        n = len(cfg.iA)
        t = np.where(rng.random(n) < 0.5, rng.uniform(0, 9, n), np.nan)
        return V._Job(cfg, rng.uniform(0, 9, n), np.where(rng.random(n) < 0.3,
                                                           rng.uniform(0, 9, n), np.nan),
                      np.arange(n), False, t, rng.uniform(0, 1, n), rng.uniform(0, 1, n),
                      np.where(rng.random(n) < 0.2, 1.0, 0.0))

    hits = 0
    for _ in range(20):
        n = int(rng.integers(1, 3000))
        hi = int(rng.choice([3, 50, 20000]))
        old = _Configs(*(rng.integers(-hi // 3, hi, n) for _ in range(4)))
        keep = rng.random(n) < 0.5
        m = int(rng.integers(1, 3000))
        fresh = _Configs(*(rng.integers(-hi // 3, hi + hi // 2, m) for _ in range(4)))
        new = _Configs.cat([old.take(np.flatnonzero(keep)), fresh])
        codes = V._Codes.of(old)
        c, inside = codes.codes(old)
        assert inside.all()
        rec = V._config_keys(old)
        assert np.array_equal(np.argsort(c, kind="stable"), np.argsort(rec, kind="stable"))
        before = job(old)
        got = []
        for on in (True, False):
            monkeypatch.setattr(V, "CODES", on)
            carried = V._Carried.of(before)
            assert (carried.codes is not None) == on
            J = job(new)
            J.t[:], J.below[:], J.box[:] = np.nan, 0.0, np.nan
            carried.into(J)
            got.append((J.t.copy(), J.below.copy(), J.box.copy()))
        (t1, b1, x1), (t2, b2, x2) = got
        np.testing.assert_array_equal(t1, t2)
        np.testing.assert_array_equal(b1, b2)
        np.testing.assert_array_equal(x1, x2)
        hits += int(np.count_nonzero(~np.isnan(t1)))
    assert hits > 1000, hits
