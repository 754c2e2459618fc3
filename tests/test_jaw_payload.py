"""The load a parallel jaw's box carries (fcgrasp.grippers.jaw.jaw_payload): the
certified scale never exceeds the payload of any pose of the box, each computed without
fcgrasp (shapely's clip of the part to the strip for the contacts, as test_jaw's pose
model does, and test_loads' linear program over the contact forces, a pad's points
sharing its force limit)."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.grippers.jaw import ParallelJaw
from fcgrasp.grippers.jaw._payload import jaw_payload
from fcgrasp.io.parts import demo_part

from .test_jaw import _frame, _jaw_for, _random_part, independent_pose
from .test_loads import _reference_scale

G = 9.80665


def _load_wrenches(mass, com, accel, torque):
    """The load's vertices (fx, fy, tau about the origin), by hand: the weight and the
    inertia under the corners of the box of accelerations, each with both torques."""
    out = []
    for ax in (-accel[0], accel[0]):
        for ay in (-accel[1], accel[1]):
            F = mass * np.array([-ax, -G - ay])
            for tau in torque:
                out.append([F[0], F[1], com[0] * F[1] - com[1] * F[0] + tau])
    return np.array(out)


def _independent_scale(part, jaw, theta, c, hole, W, per, total):
    got = independent_pose(part, jaw, theta, c, 0.5, hole, contacts=True)
    if got is None:
        return None
    pts, nrm, pads = got
    u, n = _frame(part, theta)
    points = part.centroid + pts[:, :1] * n + pts[:, 1:] * u
    pushes = -(nrm[:, :1] * n + nrm[:, 1:] * u)
    # the linear program of test_loads, a pad's points sharing its limit
    return _reference_scale(points, pushes, jaw.mu, W, np.asarray(per, float), total,
                            groups=pads)


def _check(part, jaw, plans, rng, samples):
    """Every plan's certified scale against the independent payload of sampled poses
    (uniform, the box's corners and the middles of its sides). Returns (plans bounded
    above zero, plans within 1 % of the worst pose met)."""
    positive = tight = 0
    for plan in plans:
        mass = float(rng.uniform(0.05, 2.0))
        com = part.centroid + rng.normal(0, 0.05 * part.size, 2)
        accel = tuple(float(a) for a in rng.choice([0.0, 1.0, 4.0], 2))
        torque = (0.0, 0.0) if rng.random() < 0.6 else (-0.2 * part.size, 0.3 * part.size)
        load = fc.Load(mass, com=tuple(com), accel=accel, torque=torque)
        per = (np.inf, np.inf) if rng.random() < 0.2 else \
            tuple(float(x) for x in rng.uniform(5, 40, 2))
        total = np.inf if rng.random() < 0.6 else float(rng.uniform(10, 60))
        got = jaw_payload(part, plan, load,
                          force_limit=None if np.isinf(per[0]) else list(per),
                          total_limit=None if np.isinf(total) else total, max_boxes=48)
        W = _load_wrenches(mass, com, accel, torque)
        (t0, t1), (c0, c1) = plan.theta, plan.offset
        u = rng.random((samples, 2))
        tt = np.r_[t0 + u[:, 0] * (t1 - t0), t0, t0, t1, t1, t0, t1, (t0 + t1) / 2]
        cc = np.r_[c0 + u[:, 1] * (c1 - c0), c0, c1, c0, c1, (c0 + c1) / 2,
                   (c0 + c1) / 2, c0]
        scales = [_independent_scale(part, plan.jaw, t, c, plan.hole, W, per, total)
                  for t, c in zip(tt, cc, strict=True)]
        scales = [s for s in scales if s is not None]
        assert len(scales) > samples // 2
        assert got.lower <= got.upper * (1 + 1e-9)
        for s in scales:
            assert got.lower <= s * (1 + 1e-7) + 1e-9, (plan.theta, plan.offset, got, s)
        positive += got.lower > 0
        tight += got.gap <= 0.01
    return positive, tight


@pytest.mark.parametrize("name", ["triangle",
                                  *(pytest.param(n, marks=pytest.mark.slow)
                                    for n in ("quad", "blob", "bracket", "rectangle"))])
def test_the_boxes_certified_scale_is_below_every_pose(name):
    """Built-in parts: the certified scale of each of the top five boxes is at most the
    independent payload of 20 poses of the box; at least two are bounded above zero."""
    part = demo_part(name)
    jaw = ParallelJaw(stroke=(5, 60), pad_width=8, mu=0.5)
    plans = fc.plan(part, gripper=jaw, top=5)
    positive, _ = _check(part, jaw, plans, np.random.default_rng(7), 20)
    assert positive >= 2


def test_the_certified_scale_on_random_parts_and_holes():
    """Random parts with random jaws, and internal grips in the washer's hole."""
    rng = np.random.default_rng(11)
    positive = count = 0
    cases = [(demo_part("washer"), ParallelJaw(stroke=(2, 40), pad_width=4, mu=0.6), True)]
    while len(cases) < 2:
        part = _random_part(rng)
        cases.append((part, _jaw_for(part, rng), False))
    for part, jaw, internal in cases:
        plans = [p for p in fc.plan(part, gripper=jaw, top=4)
                 if (p.hole is not None) == internal][:2]
        got, _ = _check(part, jaw, plans[:1], rng, 12)
        positive += got
        count += len(plans)
    assert count >= 2 and positive >= count // 2, (count, positive)


@pytest.mark.slow
def test_the_bound_closes_on_the_blob():
    part, load = demo_part("blob"), fc.Load(0.5)
    box = fc.plan(part, gripper=ParallelJaw(stroke=(5, 60), pad_width=8, mu=0.5), top=1)[0]
    got = jaw_payload(part, box, load, force_limit=10, max_boxes=128)
    assert 0 < got.lower and got.gap <= 0.01, got


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(12))
def test_the_certified_scale_on_random_parts_slow(seed):
    rng = np.random.default_rng(100 + seed)
    for _ in range(4):
        part = _random_part(rng)
        jaw = _jaw_for(part, rng)
        _check(part, jaw, fc.plan(part, gripper=jaw, top=3), rng, 60)


def test_the_bound_closes_on_boxes_away_from_the_boundary():
    """Where no pose of the box is near slipping the bound closes: the triangle's top
    box within 1 % of the worst pose met (the blob's too: ``-m slow``)."""
    load = fc.Load(0.5)
    jaw = ParallelJaw(stroke=(5, 60), pad_width=8, mu=0.5)
    for name in ("triangle",):
        part = demo_part(name)
        box = fc.plan(part, gripper=jaw, top=1)[0]
        got = jaw_payload(part, box, load, force_limit=10, max_boxes=128)
        assert 0 < got.lower and got.gap <= 0.01, (name, got)


def test_plans_of_the_jaw_carry_their_payload_in_the_report_and_the_cli(tmp_path, capsys):
    """A jaw request with a load: each box's certified payload in the JSON, equal to
    jaw_payload's; the command line prints it per box."""
    from fcgrasp.planning import PlanRequest, plan_document

    from .test_cli import run_here

    req = dict(part="demo:triangle", gripper="jaw", stroke=(5.0, 60.0), pad=8.0, mu=0.5,
               mass=0.5, force_limit=10.0)
    doc = plan_document(PlanRequest(**req, top=1))
    part = fc.read_part("demo:triangle")
    assert doc.report["parameters"]["load"]["mass_kg"] == 0.5
    for box, g in zip(doc.plans, doc.report["grasps"], strict=True):
        want = jaw_payload(part, box, fc.Load(0.5), force_limit=10.0)
        assert g["payload"]["scale"] == pytest.approx(want.lower)
        assert g["payload"]["worst_grasp_scale"] == pytest.approx(want.upper)
    out = run_here(capsys, "plan", "demo:triangle", "--gripper", "jaw", "--stroke", "5,60",
                   "--pad", "8", "--mu", "0.5", "--mass", "0.5", "--force-limit", "10",
                   "--top", "1")
    assert out.returncode == 0, out.stderr
    assert "every pose of the box carries" in out.stdout
    assert f"{doc.report['grasps'][0]['payload']['scale']:.3g}x" in out.stdout


@pytest.mark.slow
def test_boxes_ranked_by_payload_are_the_pool_reranked():
    """``rank_by="payload"``: the PAYLOAD_POOL x top boxes of the jaw's order, each
    with its certified payload, the best first."""
    from fcgrasp.planning.planner import PAYLOAD_POOL

    part = fc.read_part("demo:triangle")
    jaw = ParallelJaw(stroke=(5.0, 60.0), pad_width=8.0, mu=0.5)
    pool = fc.plan(part, gripper=jaw, top=2 * PAYLOAD_POOL)
    got = fc.plan(part, gripper=jaw, top=2, load=fc.Load(0.5), force_limit=10.0,
                  rank_by="payload")
    scales = sorted((jaw_payload(part, b, fc.Load(0.5), force_limit=10.0).lower
                     for b in pool), reverse=True)
    assert [b.payload.lower for b in got] == pytest.approx(scales[:2])


def test_bad_arguments_name_themselves():
    part = demo_part("triangle")
    box = fc.plan(part, gripper=ParallelJaw(stroke=(5, 60), pad_width=8, mu=0.5), top=1)[0]
    fingers = fc.plan(part, fingers=3, mu=0.5, top=1)[0]
    for plan in ("plan", fingers):
        with pytest.raises(TypeError, match="plan must be a parallel jaw's box"):
            jaw_payload(part, plan, fc.Load(1.0))
    with pytest.raises(TypeError, match="load"):
        jaw_payload(part, box, "load")
    for kw, word in ((dict(force_limit=-1), "force_limit"), (dict(gap=-1), "gap"),
                     (dict(max_boxes=0), "max_boxes"), (dict(total_limit=0), "total_limit"),
                     (dict(force_limit=[1, 2, 3]), "force_limit")):
        with pytest.raises(ValueError, match=word):
            jaw_payload(part, box, fc.Load(1.0), **kw)
