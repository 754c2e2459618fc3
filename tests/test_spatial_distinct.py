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


def _soft_corpus(seed):
    """Tessellated solids whose distinct plans read copies on the next facets: a
    subdivided icosphere stretched into an ellipsoid, a cylinder, a torus, a corpus mesh."""
    from pathlib import Path

    from fcgrasp.io.meshes import read_solid

    rng = np.random.default_rng(seed)
    kind = seed % 4
    if kind == 0:
        mesh = trimesh.creation.icosphere(subdivisions=int(rng.integers(1, 3)), radius=20.0)
        mesh.vertices *= rng.uniform(0.6, 1.4, 3)
        return solid_from_mesh(mesh, "mm", f"ico{seed}")
    if kind == 1:
        return solid_from_mesh(trimesh.creation.cylinder(
            radius=float(rng.uniform(5, 20)), height=float(rng.uniform(10, 40)),
            sections=int(rng.integers(8, 40))), "mm", f"cyl{seed}")
    if kind == 2:
        return solid_from_mesh(trimesh.creation.torus(
            major_radius=30.0, minor_radius=float(rng.uniform(6, 14)),
            major_sections=int(rng.integers(8, 24)), minor_sections=int(rng.integers(6, 12))),
            "mm", f"torus{seed}")
    corpus = Path(__file__).resolve().parents[1] / "benchmarks" / "corpus" / "meshes"
    names = ["angle_block.STL", "plate_holes.STL", "round.stl", "idler_riser.STL"]
    return read_solid(str(corpus / names[(seed // 4) % len(names)]))


def _plan_record(p):
    return (type(p).__name__, p.facets, p.pieces, p.radius, tuple(p.radii),
            p.centers.tolist(), p.regions.tolist(), p.similar)


@pytest.mark.parametrize("seed", [2, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in (0, 1, *range(3, 24)))])
def test_plans_grown_where_the_rule_needs_them_are_every_plan_grown(seed):
    """Two soft fingers' distinct plans with each plan's second level grown only where
    it is kept or the bounds of its centres do not decide (``spatial._grown``) are
    those of every plan read grown, then suppressed (the reference): the same plans,
    centres, radii and ``similar``, at several fractions; and where the bounds decide,
    they give the rule's verdict on the grown plan."""
    from fcgrasp.spatial import _grown

    solid = _soft_corpus(seed)
    rng = np.random.default_rng(seed)
    mu = float(rng.choice([0.3, 0.5, 1.0]))
    for fraction in (0.5,) if seed == 2 else (0.3, 0.5, 1.0):
        memo: dict = {}
        want = top_distinct(lambda n, memo=memo: soft_pair_plans(
            solid, mu, top=n, margin=0.5, memo=memo), 10, fraction)
        got = _grown.soft_pair_distinct(solid, mu, 0.5, 10, fraction)
        assert [_plan_record(p) for p in got] == [_plan_record(p) for p in want]
    # the bounds' verdicts against the rule on the grown plans
    memo = {}
    first = soft_pair_plans(solid, mu, top=40, margin=0.5, memo=memo, grow_facets=False)
    facets = [p for p in first if type(p).__name__ == "SoftPairPlan"]
    leaders = [_grown.grown(solid, p, memo) for p in facets[:8]]
    assert all(type(p).__name__ == "SurfacePairPlan" or p.radii == (p.radius, p.radius)
               for p in first)                  # at their first level
    decided = 0
    for p in facets:
        pieces = _grown.pieces_of(solid, p, memo)
        full = _grown.grown(solid, p, memo)
        for leader in leaders:
            # fractions in fine steps: some plans sit near each reach
            for fraction in np.linspace(0.05, 1.0, 40).tolist():
                verdict = _grown._decided(leader, p, pieces, fraction)
                if verdict is not None:
                    decided += 1
                    assert verdict == same_solid_alternative(leader, full, fraction)
    assert decided > 0 or seed % 4 == 0     # (an icosphere's large pieces decide none)
