"""The registry of ranking measures (fcgrasp.model.ranking): every measure documented, and a
new measure is one function and one line."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.model.ranking import MEASURES, register

BLOB = fc.read_part("demo:blob")


def test_every_measure_documented_and_batched():
    plans = fc.plan(BLOB, fingers=2, mu=0.3, top=5)
    assert set(MEASURES) >= {"min_region", "resistance", "epsilon"}
    for m in MEASURES.values():
        assert m.units and m.definition
        s = m.score(plans)
        assert s.shape == (len(plans),) and np.all(np.isfinite(s))


@pytest.mark.parametrize("name", ["resistance", "epsilon"])
def test_plans_sorted_by_measure(name):
    plans = fc.plan(BLOB, fingers=4, mu=0, top=None, rank_by=name)
    s = MEASURES[name].score(plans)
    assert np.all(np.diff(np.round(s, 9)) <= 0)


def test_new_measure_is_one_function_and_one_line():
    @register("widest_first", units="length", definition="largest region first (test)")
    def widest(plans):
        return np.array([p.lengths.max() for p in plans])

    try:
        plans = fc.plan(BLOB, fingers=2, mu=0.3, top=None, rank_by="widest_first")
        widths = [p.lengths.max() for p in plans]
        assert widths == sorted(widths, reverse=True)
    finally:
        del MEASURES["widest_first"]
