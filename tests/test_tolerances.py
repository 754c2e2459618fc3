"""Named tolerances (fcgrasp.core.tolerances): relative, so answers do not depend on units."""

from __future__ import annotations

import numpy as np

import fcgrasp as fc
from fcgrasp.core import tolerances


def test_every_tolerance_is_named_and_small():
    for name in tolerances.__all__:
        v = getattr(tolerances, name)
        assert isinstance(v, float) and v > 0
        assert v < 1 or name == "MAX_MAGNITUDE"


def test_ties_within_tol_are_not_closure():
    # a force on the friction cone's edge, within TOL: not closure
    mu = 0.3
    q = np.array([1.0, mu])             # PQ on the cone edge at P
    assert not fc.friction_pair_closure([0, 0], [-1, 0], q, [1, 0], mu).item()
    assert fc.friction_pair_closure([0, 0], [-1, 0], q * [1, 0.99], [1, 0], mu).item()


def test_answers_do_not_depend_on_units():
    part = fc.read_part("demo:quad")
    mm = fc.plan(part, fingers=4, top=3)
    m = fc.plan(fc.Polygon(part.vertices / 1000), fingers=4, top=3)
    assert [p.edges for p in mm] == [p.edges for p in m]
    assert np.allclose([p.min_length / 1000 for p in mm], [p.min_length for p in m])
