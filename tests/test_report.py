"""JSON documents (fcgrasp.io.report): one FORMAT_VERSION, deterministic bytes, significant
digits, and the same shape from the library and the command."""

from __future__ import annotations

import json

import numpy as np

import fcgrasp as fc
from fcgrasp.io.report import (
    FORMAT_VERSION,
    check_report,
    demo_summary,
    dumps,
    json_ready,
    plan_report,
)


def test_json_ready_rounds_significant_digits_and_cleans():
    out = json_ready({"a": np.float64(1 / 3) * 1e-9, "b": [np.int64(3), -0.0, np.inf],
                      "c": np.array([[1.0, 2.0]])})
    assert out == {"a": float(f"{1 / 3 * 1e-9:.12g}"), "b": [3, 0.0, None], "c": [[1.0, 2.0]]}


def test_every_document_carries_the_format_version():
    part = fc.read_part("demo:blob")
    plans = fc.plan(part, fingers=2, mu=0.3, top=2)
    g = plans[0].grasp()
    docs = [plan_report(part, plans, {}, "mm"),
            check_report(part, [], g.explain(), g.total_freedom(), "mm"),
            demo_summary([], "mm")]
    for d in docs:
        assert json.loads(dumps(d))["format_version"] == FORMAT_VERSION


def test_dumps_is_deterministic():
    part = fc.read_part("demo:quad")
    a = dumps(plan_report(part, fc.plan(part, fingers=4, top=3), {"x": 1}, "mm"))
    b = dumps(plan_report(part, fc.plan(part, fingers=4, top=3), {"x": 1}, "mm"))
    assert a == b and a.endswith("\n")


def test_no_grasp_report_has_a_reason():
    part = fc.read_part("demo:blob")
    d = json.loads(dumps(plan_report(part, [], {}, "mm", "none here")))
    assert d["grasps"] == [] and d["reason"] == "none here"
