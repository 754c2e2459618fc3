"""Budgets of the search (``time_limit``, ``max_memory``): a search stopped early returns
an exact prefix of the complete answer and a bound on the rest that the complete search
never beats.

The stops are made reproducible by a budget of checks
(:func:`fcgrasp.core.budget.deadline` with ``checks``): every count of checks from 0 up
to the complete search is tried, so each way a search can stop (between rounds, inside
one, at the depth) is met on every case, whatever the machine's speed.
"""

from __future__ import annotations

import io
import json
from contextlib import redirect_stdout

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.apps.cli import main
from fcgrasp.core.budget import BudgetExhausted, check, check_time_limit, deadline, exhausted
from fcgrasp.io.report import migrate_report
from fcgrasp.model.plans import PlanList


def _wavy(rng, n=None):
    """A seeded smooth outline with lobes and a little noise: a grasp on it has shifted
    copies, so the distinct search reads in rounds."""
    n = int(rng.integers(50, 150)) if n is None else n
    th = np.linspace(0, 2 * np.pi, n, endpoint=False)
    lobes, amp = int(rng.integers(2, 5)), rng.uniform(0.05, 0.25)
    r = 1 + amp * np.cos(lobes * th + rng.uniform(0, 6)) + 0.01 * rng.standard_normal(n)
    a, b = rng.uniform(20, 60), rng.uniform(15, 40)
    return fc.Polygon(np.c_[a * r * np.cos(th), b * r * np.sin(th)])


def _same(p, q):
    """Two plans are the same grasp: the edges their regions cover, the mode, the
    lengths (to a relative 1e-9)."""
    return p.region_edges == q.region_edges and p.mode == q.mode and \
        np.allclose(p.lengths, q.lengths, rtol=1e-9, atol=0)


def _check_partial(full, part):
    """``part`` is an exact prefix of ``full`` and its bound is above every plan of
    ``full`` after it."""
    assert isinstance(part, PlanList)
    if part.complete:
        assert len(part) == len(full) and all(map(_same, full, part))
        return
    assert part.stopped in ("time_limit", "max_memory", "depth")
    if not part.exact:
        # a search cut short inside (a growth: no bound claimed,
        # test_a_growth_cut_short_gives_plans_that_hold), or plans read below the
        # search's last level: a bound on every plan of the complete answer left out
        assert part.gap()["exact"] is False
        assert len(part) <= len(full)
        if part.bound is not None:
            left = [q.min_length for q in full if not any(_same(q, p) for p in part)]
            assert not left or max(left) <= part.bound * (1 + 1e-9), (left, part.bound)
        return
    assert len(part) <= len(full)
    assert all(map(_same, full, part))
    rest = [p.min_length for p in full[len(part):]]
    if part.bound is not None and rest:
        assert max(rest) <= part.bound * (1 + 1e-9)


def _every_stop(plan_it, full, most=400, every=1, each=None):
    """Plan under budgets of 0, 1, 2 ... checks until one completes (past the first
    four, every ``every``-th: the default suite's sample); each answer checked against
    ``full`` (and given to ``each``).  The number of distinct partial answers seen."""
    seen = set()
    for checks in [*range(min(4, most)), *range(4, most, every)]:
        with deadline(None, checks=checks):
            part = plan_it()
        _check_partial(full, part)
        if each is not None:
            each(part)
        seen.add((len(part), part.complete))
        if part.complete:
            return seen
    raise AssertionError(f"not complete after {most} checks")


def test_deadline_nests_and_counts():
    with deadline(None):
        check()
        assert not exhausted()
    with deadline(None, checks=2):
        assert not exhausted() and not exhausted() and exhausted()
        with deadline(100.0):               # the outer budget still holds
            assert exhausted()
            with pytest.raises(BudgetExhausted):
                check()
    with deadline(0.0):
        assert exhausted()
    with deadline(3600.0, checks=None), deadline(None, checks=1):
        assert not exhausted() and exhausted()


@pytest.mark.parametrize("bad", [0, -1.0, float("nan")])
def test_time_limit_refused(bad):
    with pytest.raises(ValueError, match="time_limit"):
        check_time_limit(bad)
    with pytest.raises(ValueError, match="time_limit"):
        fc.plan(fc.read_part("demo:blob"), mu=0.3, time_limit=bad)


def test_time_limit_type_refused():
    with pytest.raises(TypeError, match="time_limit"):
        fc.plan(fc.read_part("demo:blob"), mu=0.3, time_limit="10")


@pytest.mark.parametrize(("seed", "every"), [
    *((s, 2) for s in range(2)), pytest.param(2, 2, marks=pytest.mark.slow),
    *(pytest.param(s, 1, marks=pytest.mark.slow) for s in range(12))])
def test_two_fingers_stopped_early_give_an_exact_prefix_and_a_sound_bound(seed, every):
    rng = np.random.default_rng(seed)
    poly = _wavy(rng)
    mu = float(rng.choice([0.3, 0.5, 0.8]))
    top = int(rng.integers(3, 7))

    def plan_it():
        return fc.plan(poly, fingers=2, mu=mu, top=top, time_limit=None)

    full = plan_it()
    assert full.complete and full.bound is None
    seen = _every_stop(plan_it, full, every=every)
    assert (len(full), True) in seen
    assert any(not complete for _, complete in seen)


def test_two_fingers_stop_at_the_time_limit_by_the_clock():
    """A real clock: a budget far below one distinct round of a 600-edge outline at mu
    1.0 stops after the ranked search, whose best plan is proved."""
    rng = np.random.default_rng(7)
    poly = _wavy(rng, 600)
    part = fc.plan(poly, fingers=2, mu=1.0, top=10, time_limit=1e-6)
    assert not part.complete and part.stopped == "time_limit" and len(part) >= 1
    best = fc.plan(poly, fingers=2, mu=1.0, top=1, distinct=0)[0]
    assert _same(part[0], best)
    assert part.bound is not None and part.bound <= best.min_length * (1 + 1e-9)


def test_two_fingers_memory_budget_stops_the_rounds(monkeypatch):
    """The smallest memory budget (16 MiB) and configurations counted as 1 MB each: the
    first distinct round's collection does not fit."""
    from fcgrasp.model.stretches import _memo as _stretch_memo

    rng = np.random.default_rng(3)
    poly = _wavy(rng, 120)
    full = fc.plan(poly, fingers=2, mu=0.5, top=6, time_limit=None)
    monkeypatch.setattr(_stretch_memo, "CONFIG_BYTES", 2 ** 20)
    part = fc.plan(poly, fingers=2, mu=0.5, top=6, time_limit=None, max_memory=2 ** 24)
    _check_partial(full, part)
    assert not part.complete and part.stopped == "max_memory"


# by default seed 1 with every count of checks
# (test_three_fingers_that_read_below_their_level_bound_the_plans_left_out)
@pytest.mark.parametrize(("seed", "every"), [pytest.param(s, 1, marks=pytest.mark.slow)
                                             for s in (0, 1, 2)])
def test_three_fingers_stopped_early_give_an_exact_prefix_and_a_sound_bound(seed, every):
    rng = np.random.default_rng(100 + seed)
    poly = _wavy(rng, int(rng.integers(40, 80)))
    mu = float(rng.choice([0.5, 0.8]))

    def plan_it():
        return fc.plan(poly, fingers=3, mu=mu, top=4, time_limit=None)

    full = plan_it()
    assert full.complete
    _every_stop(plan_it, full, every=every)


def test_three_fingers_that_read_below_their_level_bound_the_plans_left_out():
    """Three fingers stopped with fewer than ``top`` plans above the level the search
    reached give those read below it as well (not an exact prefix), and the level as
    a bound on every plan of the complete answer they leave out: on a seeded outline
    (52 edges, mu 0.8) stopped after the first four counts of checks and every twelfth
    after them up to the complete search (every count under ``-m slow``, seed 1 of
    test_three_fingers_stopped_early_give_an_exact_prefix_and_a_sound_bound), every such
    bound is above the complete answer's plans left out, and the CLI's line says it."""
    from fcgrasp.apps.cli import incomplete_note

    rng = np.random.default_rng(101)
    poly = _wavy(rng, int(rng.integers(40, 80)))
    mu = float(rng.choice([0.5, 0.8]))

    def plan_it():
        return fc.plan(poly, fingers=3, mu=mu, top=4, time_limit=None)

    below = []

    def look(part):
        if not part.exact and part.bound is not None:
            below.append(part.bound)
            line = incomplete_note({"complete": False, "units": "mm", "gap": part.gap(),
                                    "parameters": {"top": 4}})
            assert line is not None and f"at most {part.bound:.4g} mm" in line

    _every_stop(plan_it, plan_it(), every=12, each=look)
    assert below


@pytest.mark.parametrize(("fingers", "every"), [(3, 7), *(
    pytest.param(f, 1, marks=pytest.mark.slow) for f in (3, 4))])
def test_rounds_of_the_ranked_list_stopped_early(fingers, every):
    """Grippers whose distinct plans come from suppressing ever longer ranked lists:
    stopped between two lists, the plans kept are the complete answer's first."""
    poly = fc.read_part("demo:cam")
    kw = dict(fingers=fingers, top=6, time_limit=None)
    if fingers == 3:
        kw["gravity"] = (0, -1)

    def plan_it():
        return fc.plan(poly, **kw)

    full = plan_it()
    _every_stop(plan_it, full, most=50, every=every)


def test_the_report_says_incomplete_and_the_cli_prints_it(tmp_path):
    rng = np.random.default_rng(11)
    poly = _wavy(rng, 120)
    src = tmp_path / "wavy.json"
    src.write_text(json.dumps({"vertices": poly.vertices.tolist()}))
    out = tmp_path / "plan.json"
    text = io.StringIO()
    with deadline(None, checks=0), redirect_stdout(text):
        assert main(["plan", str(src), "--mu", "0.5", "--top", "5", "--json", str(out)]) == 0
    report = json.loads(out.read_text())
    assert report["complete"] is False
    assert report["gap"]["stopped_by"] == "time_limit"
    assert report["gap"]["found"] == len(report["grasps"]) < 5
    assert report["gap"]["bound"] <= report["grasps"][-1]["min_region_length"] * (1 + 1e-9)
    assert "search stopped at its time limit" in text.getvalue()
    # complete: said in the report, no gap, no line
    text = io.StringIO()
    with redirect_stdout(text):
        assert main(["plan", str(src), "--mu", "0.5", "--top", "5", "--json", str(out),
                     "--time-limit", "0"]) == 0
    report = json.loads(out.read_text())
    assert report["complete"] is True and "gap" not in report
    assert "search stopped" not in text.getvalue()


@pytest.mark.parametrize("bad", ["-1", "soon", "inf", "nan"])
def test_cli_refuses_a_bad_time_limit(bad, capsys):
    assert main(["plan", "demo:blob", "--time-limit", bad]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--time-limit" in err[0]


def test_a_report_without_complete_is_read_as_complete():
    old = {"format_version": 2, "grasps": []}
    assert migrate_report(old)["complete"] is True


@pytest.mark.parametrize("seed", range(2))
def test_a_solid_jaw_stopped_early_gives_an_exact_prefix_and_a_sound_bound(seed):
    """The parallel jaw on a plate with bolt holes, stopped after every count of budget
    checks: the plans are the complete answer's first and no later plan's radius is
    above the bound; the document says so."""
    from fcgrasp.spatial.jaw import solid_jaw_plans

    from .test_spatial_jaw import _plate_with_holes

    solid, _ = _plate_with_holes(10 + seed)

    def plan_it():
        return solid_jaw_plans(solid, (1.0, 80.0), 3.0, 0.5, top=6)

    full = plan_it()
    assert full.complete and len(full) >= 2
    partials = 0
    for checks in range(400):
        with deadline(None, checks=checks):
            part = plan_it()
        assert len(part) <= len(full)
        for p, q in zip(part, full, strict=False):
            assert p.facets == q.facets and p.radius == pytest.approx(q.radius, rel=1e-12)
        if part.complete:
            assert len(part) == len(full)
            break
        partials += 1
        assert part.measure == "region radius"
        assert all(q.radius <= part.bound * (1 + 1e-12) for q in full[len(part):])
    assert partials >= 1


@pytest.mark.parametrize("checks", [0, pytest.param(3, marks=pytest.mark.slow), 40])
def test_a_growth_cut_short_gives_plans_that_hold(checks):
    """Four fingers grown along the boundary, the growth stopped by the budget: the
    answer says it is not exact (no bound), and every plan holds (sampled grasps of
    its regions, vertex fans included, through the wrench LP)."""
    from .test_frictionless_stretches import _check_plan_holds

    rng = np.random.default_rng(checks)
    t = np.linspace(0, 2 * np.pi, 60, endpoint=False)
    poly = fc.Polygon(np.c_[40 * np.cos(t), 25 * np.sin(t)])
    full = fc.plan(poly, fingers=4, top=3, time_limit=None)
    with deadline(None, checks=checks):
        part = fc.plan(poly, fingers=4, top=3, time_limit=None)
    if checks < 10:                     # the growth needs more checks than that
        assert not part.complete and not part.exact and part.gap()["bound"] is None
    else:
        assert part.complete and all(map(_same, full, part))
    for p in part:
        _check_plan_holds(p, poly, rng, grasps=60)


def test_the_jaw_cut_short_keeps_the_boxes_it_proved():
    """The jaw seeks boxes one after another while the budget lasts (the first always):
    stopped, it returns those it proved (each the complete search's box of the same
    turn), not exact, no bound claimed."""
    poly = fc.read_part("demo:rectangle")
    jaw = fc.ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
    full = fc.plan(poly, gripper=jaw, top=3, distinct=0, time_limit=None)
    with deadline(None, checks=0):
        part = fc.plan(poly, gripper=jaw, top=3, distinct=0, time_limit=None)
    assert len(full) == 3 and len(part) == 1
    assert not part.complete and not part.exact and part.gap()["bound"] is None
    assert part[0].theta == full[0].theta and part[0].offset == full[0].offset


def test_the_cli_says_a_search_cut_short_is_not_exact(tmp_path):
    """A growth stopped by the budget: the report's gap says ``exact: false`` with no
    bound, and the command line prints that every plan holds but a complete search may
    rank others first (not the exact prefix's line)."""
    t = np.linspace(0, 2 * np.pi, 60, endpoint=False)
    src = tmp_path / "ellipse.json"
    src.write_text(json.dumps({"vertices": np.c_[40 * np.cos(t), 25 * np.sin(t)].tolist()}))
    out = tmp_path / "plan.json"
    text = io.StringIO()
    with deadline(None, checks=0), redirect_stdout(text):
        assert main(["plan", str(src), "--fingers", "4", "--top", "3",
                     "--json", str(out)]) == 0
    report = json.loads(out.read_text())
    assert report["complete"] is False and report["gap"]["exact"] is False
    assert report["gap"]["bound"] is None
    assert "plans, each proved to hold; a complete search may rank others first" \
        in text.getvalue()


def test_the_jaw_past_its_time_keeps_its_first_box_as_the_grid_proved_it(monkeypatch):
    """The time over once the grid's first box is proved: that box is kept as the grid
    proved it, neither refined nor grown (no larger than the complete search's), said
    not exact; every sampled pose of it holds by the jaw's pose model.  Over before
    that: no plan, and the report says the search stopped before it proved one."""
    from fcgrasp.core import budget
    from fcgrasp.grippers.jaw import _boxes, jaw_poses
    from fcgrasp.planning import PlanRequest, plan_document

    poly = fc.read_part("demo:rectangle")
    jaw = fc.ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
    full = fc.plan(poly, gripper=jaw, top=1, distinct=0, time_limit=None)
    with monkeypatch.context() as m:
        m.setattr(_boxes, "_past_time", lambda: budget.cut_short() or True)
        part = fc.plan(poly, gripper=jaw, top=1, distinct=0, time_limit=None)
    assert len(part) == 1 and not part.complete and not part.exact
    box = part[0]
    assert box.certified and box.measure < full[0].measure
    rng = np.random.default_rng(5)
    th = rng.uniform(*box.theta, 400)
    c = rng.uniform(*box.offset, 400)
    assert jaw_poses(poly, jaw, th, c, margin=0.5).holds.all()
    with deadline(0.0):
        none = fc.plan(poly, gripper=jaw, top=1, distinct=0, time_limit=None)
        doc = plan_document(PlanRequest(part="demo:rectangle", gripper="jaw", stroke=(10, 50),
                                        pad=8, mu=0.5, top=1, distinct=0))
    assert len(none) == 0 and not none.complete and not none.exact
    assert doc.reason is not None and "stopped at its time limit" in doc.reason


@pytest.mark.parametrize("distinct", [0.0, 0.5])
def test_three_fingers_whose_first_read_the_clock_ends_give_plans_cut_short(monkeypatch,
                                                                            distinct):
    """Three fingers whose first read of the two-finger stretches alone runs past the
    budget and its grace (the clock said to be past it at every check): plans, not an
    error, incomplete and not exact (no bound), their pairs on single edges, each grasp
    sampled along the single-edge regions (the others at their representative contact)
    force closure (theorem 6.1's test)."""
    from fcgrasp.core import budget

    def late() -> None:
        raise budget.BudgetExhausted("time_limit")

    monkeypatch.setattr(budget, "check_clock", late)
    part = fc.read_part("demo:cam")
    plans = fc.plan(part, fingers=3, mu=0.5, top=3, distinct=distinct)
    assert plans and not plans.complete and not plans.exact
    assert plans.gap()["bound"] is None
    rng = np.random.default_rng(6)
    for p in plans:
        if p.mode == "pair":
            assert sum(len(e) == 1 for e in p.region_edges) >= 2
        for _ in range(20):
            t = rng.uniform(size=3)
            pts = [reg[0] + s * (reg[-1] - reg[0]) if len(e) == 1 else c
                   for reg, s, e, c in zip(p.regions, t, p.region_edges, p.contacts,
                                           strict=True)]
            g = fc.Grasp([fc.FrictionPoint(q, n, 0.5)
                          for q, n in zip(pts, p.normals, strict=True)])
            assert g.is_force_closure()


def test_a_first_round_the_clock_ends_gives_single_edge_plans_cut_short(monkeypatch):
    """Two fingers on a large outline whose stretch search's first answer alone takes
    longer than the budget and its grace (none here; the clock checked between blocks of
    its rows): the plans of
    regions on single edges, incomplete and not exact (no bound), each one force
    closure at its representative contacts and inside the regions (checked by the
    closure test of theorem 6.1 on sampled grasps), distinct alternatives by default."""
    from fcgrasp.core import budget
    from fcgrasp.model.stretches import _kernels as _stretch_kernels

    monkeypatch.setattr(_stretch_kernels, "VERTEX_ROWS", 16)
    monkeypatch.setattr(budget, "FIRST_ANSWER_GRACE", 0.0)
    a = np.linspace(0, 2 * np.pi, 600, endpoint=False)
    r = 1 + 0.1 * np.cos(3 * a)
    part = fc.Polygon(np.c_[60 * r * np.cos(a), 35 * r * np.sin(a)])
    rng = np.random.default_rng(4)
    for distinct in (0.5, 0.0):
        plans = fc.plan(part, fingers=2, mu=1.0, top=5, distinct=distinct, time_limit=1e-6)
        assert plans and not plans.complete and plans.gap()["bound"] is None
        assert not plans.exact
        for p in plans:
            assert all(len(e) == 1 for e in p.region_edges)      # on single edges
            for _ in range(20):
                t = rng.uniform(size=2)
                pts = [reg[0] + s * (reg[-1] - reg[0]) for reg, s in zip(p.regions, t, strict=True)]
                g = fc.Grasp([fc.FrictionPoint(q, n, 1.0)
                              for q, n in zip(pts, p.normals, strict=True)])
                assert g.is_force_closure()
    full = fc.plan(part, fingers=2, mu=1.0, top=5, time_limit=None)
    assert full.complete


def test_a_memory_budget_ends_the_deadline_and_names_itself():
    """A deadline's memory budget is read at each check: within it the search goes on;
    past it (an allocation of 64 MB under a budget of 1 MB) the check ends it, and the
    stop is named ``max_memory``, for the deadlines inside it too; a deadline without
    one stops at its clock, named ``time_limit``."""
    from fcgrasp.core.budget import stop_reason

    with deadline(None, max_memory=2 ** 30):
        assert not exhausted()
        check()
    with deadline(None, max_memory=2 ** 20):
        block = np.ones(2 ** 23)
        with deadline(None):
            assert exhausted() and stop_reason() == "max_memory"
            with pytest.raises(BudgetExhausted, match="max_memory"):
                check()
        del block
    with deadline(None, checks=0):
        assert exhausted() and stop_reason() == "time_limit"
        with pytest.raises(BudgetExhausted, match="time_limit"):
            check()


@pytest.mark.parametrize("case", ["2 soft", "3 friction", "jaw"])
def test_a_solid_past_its_memory_budget_gives_an_exact_prefix_and_a_sound_bound(
        case, monkeypatch):
    """Solids plan under ``max_memory`` (``fcgrasp.plan``): the address space read at
    each check grows by one byte a check here (a seeded stand-in for a search that
    allocates), so a budget of ``k`` bytes ends the search at its ``k``-th check, for
    every other ``k`` up to the complete search.  Each answer stopped there says
    ``max_memory`` in its gap; exact, it is the complete answer's first plans with a
    bound no later plan's radius passes; cut short inside a search, its plans hold
    (a positive certified radius) and no bound is claimed."""
    from fcgrasp.core import budget
    from fcgrasp.spatial.solid import demo_solid

    from .test_spatial_jaw import _plate_with_holes

    if case == "jaw":
        solid = _plate_with_holes(10)[0]
        kw = dict(gripper=fc.ParallelJaw(stroke=(1.0, 80.0), pad_width=3.0, mu=0.5))
    else:
        solid = demo_solid("box" if case == "2 soft" else "prism")
        kw = dict(fingers=int(case[0]), mu=0.5)
    full = fc.plan(solid, top=4, time_limit=None, **kw)
    assert full.complete and len(full) >= 2
    reads = iter(range(10 ** 9))
    monkeypatch.setattr(budget, "address_held", lambda: next(reads))
    partials = 0
    for k in range(0, 400, 2):
        part = fc.plan(solid, top=4, time_limit=None, max_memory=k + 1, **kw)
        if part.complete:
            assert [p.facets for p in part] == [p.facets for p in full]
            break
        partials += 1
        gap = part.gap()
        assert part.stopped == gap["stopped_by"] == "max_memory"
        assert gap["measure"] == "region radius"
        if part.exact:
            assert [p.facets for p in part] == [p.facets for p in full[:len(part)]]
            rest = [q.radius for q in full[len(part):]]
            if part.bound is not None and rest:
                assert max(rest) <= part.bound * (1 + 1e-12)
        else:
            assert part.bound is None and all(p.radius > 0 for p in part)
    else:
        raise AssertionError("not complete after 400 checks")
    assert partials >= 1
