"""Distinct alternatives on solids (issues 31 and 33): the kept plans are pairwise
distinct by the documented rule, every plan dropped stands under a better kept plan,
and ``--distinct`` asks the search for enough plans to keep ``top``."""

from __future__ import annotations

import json

import numpy as np
import pytest

from fcgrasp.spatial import (
    facet_pair_plans,
    point_triple_plans,
    soft_pair_plans,
    solid_jaw_plans,
)
from fcgrasp.spatial.alternatives import (
    distinct_solid_plans,
    same_solid_alternative,
    top_distinct,
)
from fcgrasp.spatial.solid import demo_solid, solid_from_mesh

trimesh = pytest.importorskip("trimesh")


def _angle(u, v):
    """Degrees between two vectors."""
    c = np.dot(u, v) / (np.linalg.norm(u) * np.linalg.norm(v))
    return float(np.degrees(np.arccos(np.clip(c, -1.0, 1.0))))


def _near(p, q, fraction):
    """The rule written out: some pairing of the fingers with every pair of centres
    closer than the sum of the radii over the fraction, and normals less than 45
    degrees apart (brute force over pairings)."""
    import itertools

    if len(p.centers) != len(q.centers):
        return False
    for perm in itertools.permutations(range(len(p.centers))):
        if all(np.linalg.norm(p.centers[i] - q.centers[j]) * fraction < p.radius + q.radius
               and _angle(p.normals[i], q.normals[j]) < 45.0
               for i, j in enumerate(perm)):
            return True
    return False


@pytest.fixture(scope="module")
def ranked():
    """Ranked plans of every solid gripper on tessellated surfaces (near-copies)."""
    ico = solid_from_mesh(trimesh.creation.icosphere(subdivisions=1, radius=20.0))
    cyl = demo_solid("cylinder")
    return [facet_pair_plans(ico, 0.5, top=80),
            point_triple_plans(cyl, 0.5, top=15, refine=False).plans,
            solid_jaw_plans(cyl, (5, 50), 1, 0.5, top=None)]


@pytest.mark.parametrize("fraction", [0.5, *(pytest.param(f, marks=pytest.mark.slow)
                                        for f in (0.25, 1.0))])
def test_kept_plans_are_distinct_and_stand_for_the_others(ranked, fraction):
    cases = ranked
    for plans in cases:
        kept = distinct_solid_plans(plans, fraction)
        assert len(kept) < len(plans)                    # the rule merges something
        for a in range(len(kept)):
            for b in range(a + 1, len(kept)):
                assert not _near(kept[a], kept[b], fraction)
                assert not same_solid_alternative(kept[a], kept[b], fraction)
        filed = {f for k in kept for f in k.similar} | {k.facets for k in kept}
        rank = {p.facets: r for r, p in enumerate(plans)}
        for p in plans:
            assert p.facets in filed
        for k in kept:                                   # under a better plan, near it
            for f in k.similar:
                q = plans[rank[f]]
                assert rank[f] > rank[k.facets]
                assert _near(k, q, fraction)
    assert distinct_solid_plans(cases[0], 0) == cases[0]


def test_the_command_line_keeps_top_distinct_plans(tmp_path):
    from fcgrasp.apps.cli import main

    out = tmp_path / "plan.json"
    assert main(["plan", "demo:cylinder", "--fingers", "2", "--soft", "--mu", "0.5",
                 "--top", "3", "--distinct", "0.5", "--json", str(out)]) == 0
    doc = json.loads(out.read_text())
    assert doc["parameters"]["distinct"] == 0.5 and len(doc["grasps"]) == 3
    assert any(g.get("similar") for g in doc["grasps"])
    cyl = demo_solid("cylinder")
    want = top_distinct(lambda n: soft_pair_plans(cyl, 0.5, top=n), 3, 0.5)
    assert len(want) == 3
    assert [g["facets"] for g in doc["grasps"]] == [list(p.facets) for p in want]
