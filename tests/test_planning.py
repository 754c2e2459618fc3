"""The planning façade: plan() and independent_regions() over the pipeline."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc

from .grippers import grip

BLOB = fc.read_part("demo:blob")


@pytest.mark.parametrize("fingers, mu", [(2, 0.3), (3, 0.0), (4, 0.0)])
def test_plans_sorted_and_force_closure(fingers, mu):
    plans = fc.plan(BLOB, **grip(fingers, mu), top=6)
    assert plans
    mins = [p.min_length for p in plans]
    assert mins == sorted(mins, reverse=True)
    for p in plans:
        assert p.grasp().is_force_closure()
        assert p.ends.shape == (fingers if fingers != 3 else 3, 2, 2)
        assert [len(r) for r in p.regions] == [len(e) + 1 for e in p.region_edges]


def test_independent_regions_matches_the_plan_of_its_edges():
    best = fc.plan(BLOB, fingers=2, mu=0.3, top=1)[0]
    again = fc.independent_regions(BLOB, best.edges, mu=0.3)
    np.testing.assert_allclose(again.ends, best.ends)
    flipped = fc.independent_regions(BLOB, best.edges[::-1], mu=0.3)
    np.testing.assert_allclose(flipped.ends, best.ends[::-1])


def test_quality_inputs_are_explicit():
    p = fc.plan(BLOB, fingers=2, mu=0.3, top=1)[0]
    assert p.radius > 0 and p.centroid.shape == (2,) and p.disturbance == (10.0, 15.0)
    assert set(p.quality) >= {"min_region", "resistance", "epsilon_l1", "epsilon_linf"}


def test_top_none_returns_every_plan():
    every = fc.plan(BLOB, fingers=2, mu=0.3, top=None)
    assert len(every) >= 3 and len(fc.plan(BLOB, fingers=2, mu=0.3, top=2)) == 2


def test_a_plan_runs_with_the_cyclic_collector_paused_and_puts_it_back(monkeypatch):
    """``plan`` pauses Python's cyclic collector while it searches (its garbage is
    freed by reference counts) and puts it back as it found it: on after a plan, after
    a plan that raised, after plans in several threads at once; off where the caller
    turned it off."""
    import gc
    import threading

    from fcgrasp.planning import planner

    seen = []
    search = planner._distinct
    monkeypatch.setattr(planner, "_distinct",
                        lambda *a: seen.append(gc.isenabled()) or search(*a))
    part = fc.read_part("demo:blob")
    assert gc.isenabled()
    fc.plan(part, fingers=2, mu=0.3, top=2)
    assert seen == [False] and gc.isenabled()
    with pytest.raises(ValueError, match="distinct"):
        fc.plan(part, fingers=2, mu=0.3, distinct=2.0)
    assert gc.isenabled()
    threads = [threading.Thread(target=fc.plan, args=(part,), kwargs=dict(mu=0.3, top=1))
               for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert seen[-4:] == [False] * 4 and gc.isenabled()
    gc.disable()
    try:
        fc.plan(part, fingers=2, mu=0.3, top=1)
        assert not gc.isenabled()
    finally:
        gc.enable()


def test_the_short_form_defaults_to_the_command_lines_friction():
    """``fc.plan(part)`` plans two fingers at the command line's mu (0.3), not mu = 0 (no
    two-finger grasp at all); frictionless grippers still default to 0."""
    import shapely

    from fcgrasp.grippers.base import DEFAULT_MU

    box = shapely.box(0, 0, 40, 10)
    got = fc.plan(box, top=3)
    want = fc.plan(box, mu=DEFAULT_MU, top=3)
    assert got and [p.edges for p in got] == [p.edges for p in want]
    assert all(p.mu == DEFAULT_MU for p in got)
    assert fc.plan(box, fingers=4, top=1)[0].contact_type == "frictionless"
    with pytest.raises(ValueError, match="mu"):
        fc.plan(box, fingers=4, mu=0.3)


def test_an_array_and_a_multipolygon_are_parts():
    """What the readers take, the planner takes: an array of vertices, and a
    MultiPolygon's largest polygon."""
    import shapely

    v = np.array([[0, 0], [40, 0], [40, 10], [0, 10]], float)
    ref = fc.plan(fc.Polygon(v), mu=0.4, top=2)
    assert [p.edges for p in fc.plan(v, mu=0.4, top=2)] == [p.edges for p in ref]
    multi = shapely.MultiPolygon([shapely.box(100, 0, 101, 1), shapely.Polygon(v)])
    got = fc.plan(multi, mu=0.4, top=2)
    assert [p.edges for p in got] == [p.edges for p in ref]
    with pytest.raises(TypeError, match="polygon"):
        fc.plan("not a part")
