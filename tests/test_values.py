"""The values checked once at the edge (:mod:`fcgrasp.core.values`): a friction
coefficient with its cone's half-angle, a margin with its radians, taken by every
planner as the numbers they stand for."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.core._angles import margin_radians, shrunk_half_angle
from fcgrasp.core._checks import check_margin, check_mu_scalar
from fcgrasp.errors import ArgumentError, ArgumentTypeError


def test_values_are_checked_when_made_and_passed_through_after():
    for bad, err in ((-0.1, ArgumentError), (float("inf"), ArgumentError),
                     ("0.3", ArgumentTypeError), (True, ArgumentTypeError)):
        with pytest.raises(err) as got:
            fc.Friction(bad)
        assert got.value.field == "mu"
    for bad in (-1.0, 90.0, float("nan")):
        with pytest.raises(ArgumentError) as got:
            fc.Margin(bad)
        assert got.value.field == "margin"
    f, m = fc.Friction(0.4), fc.Margin(3)
    assert fc.Friction.of(f) is f and fc.Margin.of(m) is m
    assert check_mu_scalar(f) == 0.4 and check_margin(m) == 3.0
    assert isinstance(m.deg, float) and float(f) == 0.4 and float(m) == 3.0
    rng = np.random.default_rng(3)
    for mu, deg in zip(rng.uniform(0, 3, 200), rng.uniform(0, 89, 200), strict=True):
        f, m = fc.Friction(mu), fc.Margin(deg)
        # the one conversion, bit for bit
        assert f.shrunk(m) == float(shrunk_half_angle(mu, deg)) \
            == float(shrunk_half_angle(f, m))
        assert m.radians == float(margin_radians(deg)) == margin_radians(m)


@pytest.mark.parametrize("kw", [{"fingers": 2}, {"fingers": 3},
                                {"gripper": "jaw"}, {"solid": True}])
def test_planners_take_the_values_as_their_numbers(kw):
    """A plan made with ``Friction`` and ``Margin`` is the plan made with the numbers,
    for point fingers, the jaw and a solid."""
    if kw.get("solid"):
        from fcgrasp.spatial.solid import demo_solid

        part, args = demo_solid("box"), {"fingers": 2}
    else:
        part, args = fc.read_part("demo:blob"), {k: v for k, v in kw.items()
                                                 if k == "fingers"}
    plans = []
    for mu, margin in ((0.5, 1.5), (fc.Friction(0.5), fc.Margin(1.5))):
        if kw.get("gripper") == "jaw":
            got = fc.plan(part, gripper=fc.ParallelJaw(stroke=(5, 60), pad_width=8, mu=mu),
                          margin=margin, top=3)
        else:
            got = fc.plan(part, mu=mu, margin=margin, top=3, **args)
        plans.append([p.to_dict() for p in got])
    assert plans[0] == plans[1] and plans[0]
