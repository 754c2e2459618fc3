"""One plan protocol (:class:`fcgrasp.Plan`): the plans of every gripper, on a polygon
and on a solid, offer their measure, regions, contacts, similar plans and JSON, and the
measure is the one their report ranks them by."""

from __future__ import annotations

import json

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.spatial.solid import demo_solid

JAW = dict(gripper=fc.ParallelJaw(stroke=(5, 130), pad_width=8, mu=0.5))
PLANAR = [("2 fingers", dict(fingers=2, mu=0.3), 2), ("3 fingers", dict(fingers=3, mu=0.5), 3),
          ("4 fingers", dict(fingers=4), 4), ("gravity", dict(fingers=3, gravity=(0, -1)), 3),
          ("jaw", JAW, 2)]
SOLID = [("box", dict(fingers=2, mu=0.3), 2), ("prism", dict(fingers=3, mu=0.5), 3),
         ("angle", dict(gripper=fc.ParallelJaw(stroke=(5, 50), pad_width=8, mu=0.5)), 2)]


def _report_measure(d):
    """The measure a plan's JSON object reports (its rank's key)."""
    for key in ("measure", "radius", "min_region_length"):
        if key in d:
            return d[key]
    raise KeyError(f"no measure in {sorted(d)}")


def _check(plans, fingers):
    assert plans
    for p in plans:
        assert isinstance(p, fc.Plan)
        assert float(p.measure) > 0
        assert len(p.regions) == fingers
        assert len(p.contacts) == fingers
        d = p.to_dict()
        json.dumps(d)
        assert _report_measure(d) == pytest.approx(float(p.measure), rel=1e-9)
        assert p.similar is not None
    measures = [float(p.measure) for p in plans]
    assert measures == sorted(measures, reverse=True)


@pytest.mark.parametrize(("name", "kw", "fingers"), PLANAR, ids=[c[0] for c in PLANAR])
def test_every_planar_gripper_plans_plans(name, kw, fingers):
    part = fc.read_part("demo:cam" if name != "gravity" else "demo:rectangle")
    _check(fc.plan(part, top=3, **kw), fingers)


@pytest.mark.parametrize(("name", "kw", "fingers"), SOLID, ids=[c[0] for c in SOLID])
def test_every_solid_gripper_plans_plans(name, kw, fingers):
    plans = fc.plan(demo_solid(name), top=3, **kw)
    _check(plans, fingers)
    for p in plans:                     # a solid's contacts are points on it
        assert np.asarray(p.contacts).shape == (fingers, 3)


def test_what_is_not_a_plan():
    assert not isinstance(object(), fc.Plan)
    assert not isinstance(fc.read_part("demo:cam"), fc.Plan)
