"""The physics stress test (fcgrasp.physics, MuJoCo): grasps sampled in the plans'
regions hold up to their certified payload, controls that are not force closure slip,
the squeeze is in equilibrium, and a seeded run repeats exactly.  The simulator shares
no code with the certificate (fcgrasp.grasp_payload) it is compared with."""

from __future__ import annotations

import json

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.apps.cli import main
from fcgrasp.errors import ArgumentError
from fcgrasp.io.parts import demo_part

mujoco = pytest.importorskip("mujoco")

from fcgrasp.physics import (  # noqa: E402
    VARIANTS,
    animate,
    balance_forces,
    control,
    escape_direction,
    sample_grasps,
    sensitivity,
    simulate,
    squeeze_forces,
    stress_test,
)

CASES = [("blob", dict(fingers=2, mu=0.5)), ("blob", dict(fingers=3, mu=0.5)),
         ("quad", dict(fingers=4))]
SLOW_CASES = [("cam", dict(fingers=2, mu=0.3)), ("bracket", dict(fingers=3, mu=0.4)),
              ("rectangle", dict(fingers=4)), ("triangle", dict(fingers=2, mu=0.3)),
              ("washer", dict(fingers=2, mu=0.5)), ("quad", dict(fingers=3, mu=0.3)),
              ("triangle", dict(fingers=3, mu=0.5)), ("washer", dict(fingers=3, mu=0.5))]


def _held(cases, samples):
    runs = held = 0
    for name, kw in cases:
        poly = demo_part(name)
        out = simulate(poly, fc.plan(poly, top=2, **kw), samples=samples, directions=2,
                       seed=3, workers=1)
        runs += sum(o["runs"] for o in out)
        held += sum(o["held"] for o in out)
        for o in out:
            for g in o["grasps"]:
                assert g["certified_payload"] > 0 and g["settle_motion"] < 0.01 * poly.size
    return held, runs


def test_grasps_in_the_regions_hold_up_to_their_certified_payload():
    """At least 95 % of the runs (grasps at the regions' two ends, two seeded
    disturbances each, on two and three fingers with friction and four frictionless
    fingers; their middles and seeded points too, on every built-in part, under ``-m
    slow``) hold every load below the certified payload."""
    held, runs = _held(CASES, 2)
    assert runs == 24 and held >= 0.95 * runs, (held, runs)


@pytest.mark.slow
def test_grasps_in_the_regions_hold_on_every_built_in_part():
    held, runs = _held(CASES + SLOW_CASES, 10)
    assert held >= 0.95 * runs, (held, runs)


@pytest.mark.parametrize(("name", "kw"), CASES)
def test_controls_that_are_not_force_closure_slip(name, kw):
    poly = demo_part(name)
    plan = fc.plan(poly, top=1, **kw)[0]
    rng = np.random.default_rng(5)
    for pts, nrm in sample_grasps(poly, plan.regions, 3, rng):
        cp, cn, cmu = control(pts, nrm, plan.mu)
        wrenches = [fc.FrictionPoint(p, n, cmu) if cmu > 0 else fc.FrictionlessPoint(p, n)
                    for p, n in zip(cp, cn, strict=True)]
        assert not fc.Grasp(wrenches).is_force_closure()
        res = stress_test(poly, cp, cn, cmu, escape_direction(poly, cp, cn, cmu))
        assert res.slip_load is not None and res.slip_load < 0.1 * 10.0


def test_the_squeeze_is_in_equilibrium_within_the_cones():
    """The squeeze's forces: positive normal forces, the largest the grip force, and
    (with tangential forces within the cones) a zero net wrench, checked by an LP of
    this test's own."""
    from ._highs import linprog

    rng = np.random.default_rng(11)
    poly = demo_part("blob")
    for kw in (dict(fingers=2, mu=0.5), dict(fingers=3, mu=0.4), dict(fingers=4)):
        plan = fc.plan(poly, top=1, **kw)[0]
        for pts, nrm in sample_grasps(poly, plan.regions, 4, rng):
            f = squeeze_forces(pts, nrm, plan.mu, 7.0)
            assert f is not None and f.max() == pytest.approx(7.0) and f.min() > 0
            # tangential forces t_i with |t_i| <= mu f_i balancing the normal forces
            inward = -nrm
            tang = np.c_[-inward[:, 1], inward[:, 0]]
            k = len(pts)
            F0 = (f[:, None] * inward).sum(axis=0)
            T0 = float(np.sum(f * (pts[:, 0] * inward[:, 1] - pts[:, 1] * inward[:, 0])))
            A = np.vstack([tang[:, 0], tang[:, 1],
                           pts[:, 0] * tang[:, 1] - pts[:, 1] * tang[:, 0]])
            res = linprog(np.zeros(k), A_eq=A, b_eq=-np.r_[F0, T0],
                          bounds=[(-plan.mu * fi, plan.mu * fi) for fi in f],
                          method="highs")
            assert res.status == 0
    # two frictionless fingers on parallel edges squeeze in equilibrium (not closure);
    # on edges that are not parallel they cannot
    assert squeeze_forces([[0, 0], [10, 0]], [[-1, 0], [1, 0]], 0.0, 5.0) is not None
    assert squeeze_forces([[0, 0], [10, 0]], [[-1, 0], [0.8, 0.6]], 0.0, 5.0) is None


def _tangential_balance(pts, nrm, mu, pushes, wrench):
    """Whether tangential forces within the cones of the normal forces ``pushes`` make
    the contacts balance ``wrench`` (about the origin): an LP of this test's own."""
    from ._highs import linprog

    inward = -nrm / np.linalg.norm(nrm, axis=1)[:, None]
    tang = np.c_[-inward[:, 1], inward[:, 0]]
    F0 = (pushes[:, None] * inward).sum(axis=0)
    T0 = float(np.sum(pushes * (pts[:, 0] * inward[:, 1] - pts[:, 1] * inward[:, 0])))
    A = np.vstack([tang[:, 0], tang[:, 1], pts[:, 0] * tang[:, 1] - pts[:, 1] * tang[:, 0]])
    res = linprog(np.zeros(len(pts)), A_eq=A, b_eq=-(np.r_[F0, T0] + wrench),
                  bounds=[(-mu * f, mu * f) for f in pushes], method="highs")
    return res.status == 0


@pytest.mark.parametrize(("name", "kw"), [("blob", dict(fingers=2, mu=0.5)),
                                          ("triangle", dict(fingers=3, mu=0.5)),
                                          ("washer", dict(fingers=3, mu=0.3))])
def test_the_balancing_forces_hold_the_load_up_to_the_payload(name, kw):
    """The balancing fingers' forces (grasp force optimisation along the ramp): each
    level's normal forces within their limits balance its load with tangential forces
    inside the cones (an LP of this test's own), and the levels reached stop within one
    step of the payload with those limits (fcgrasp.grasp_payload)."""
    from fcgrasp.model.loads import Load, grasp_payload

    rng = np.random.default_rng(17)
    poly = demo_part(name)
    cx, cy = (float(v) for v in poly.centroid)
    plan = fc.plan(poly, top=1, **kw)[0]
    for pts, nrm in sample_grasps(poly, plan.regions, 4, rng):
        limits = 2 * squeeze_forces(pts, nrm, plan.mu, 10.0)
        for _ in range(3):
            u = rng.normal(size=3)
            u[2] *= poly.size
            wrench = np.array([u[0], u[1], u[2] + cx * u[1] - cy * u[0]])
            load = Load(1.0, com=(cx, cy), gravity=(u[0], u[1]), torque=(u[2], u[2]))
            payload = grasp_payload(pts, -nrm, plan.mu, load, force_limit=list(limits)).scale
            top = 2 * payload
            levels, pushes = balance_forces(pts, nrm, plan.mu, limits, wrench, top,
                                            levels=20)
            step = top / 20
            assert len(levels) >= 2
            assert levels[-1] <= payload * (1 + 1e-6) and levels[-1] > payload - step * 1.001
            for k, f in zip(levels, pushes, strict=True):
                assert np.all(f <= limits * (1 + 1e-7)) and np.all(f >= -1e-9 * limits.max())
                assert _tangential_balance(pts, nrm, plan.mu, f, k * wrench)


def test_servo_fingers_run_and_a_bad_control_is_named():
    poly = demo_part("blob")
    plan = fc.plan(poly, fingers=3, mu=0.5, top=1)[0]
    out = simulate(poly, [plan], samples=2, directions=1, seed=2, workers=1,
                   control="servo")
    assert out[0]["runs"] == 2
    with pytest.raises(ArgumentError, match="control"):
        simulate(poly, [plan], samples=1, directions=1, control="torque")


def test_the_cone_margin_of_two_fingers_is_the_angle_to_their_line():
    """A two-finger grasp's reported margin to its cones is the half angle less the
    larger angle between a normal and the line of the contacts (theorem 5.1's test,
    in closed form), to the bisection's step."""
    rng = np.random.default_rng(23)
    poly = demo_part("blob")
    plan = fc.plan(poly, fingers=2, mu=0.5, top=1)[0]
    for pts, nrm in sample_grasps(poly, plan.regions, 6, rng):
        res = stress_test(poly, pts, nrm, 0.5, np.array([1.0, 0.0, 0.0]))
        d = (pts[1] - pts[0]) / np.linalg.norm(pts[1] - pts[0])
        worst = max(np.degrees(np.arccos(np.clip(-nrm[0] @ d, -1, 1))),
                    np.degrees(np.arccos(np.clip(nrm[1] @ d, -1, 1))))
        expected = max(np.degrees(np.arctan(0.5)) - worst, 0.0)
        assert res.cone_margin_deg == pytest.approx(expected, abs=0.011)
        assert res.to_dict()["cone_margin_deg"] == res.cone_margin_deg


@pytest.mark.slow
def test_the_sensitivity_study_runs_every_setting_on_the_same_grasps(tmp_path, capsys):
    poly = demo_part("blob")
    plans = fc.plan(poly, fingers=3, mu=0.5, top=1)
    rows = sensitivity(poly, plans, samples=2, directions=1, seed=1, workers=1)
    assert [r["variant"] for r in rows] == list(VARIANTS)
    for r in rows:
        assert r["runs"] == 2 and r["held"] == 2 and r["slipped"] == r["controls"] > 0
        assert 1.0 <= r["least_ratio"] <= r["median_ratio"]
    with pytest.raises(ArgumentError, match="variant"):
        simulate(poly, plans, samples=1, directions=1, variant="gentle")
    report = tmp_path / "plan.json"
    out = tmp_path / "stress.json"
    assert main(["plan", "demo:blob", "--fingers", "3", "--mu", "0.5", "--top", "1",
                 "--json", str(report), "--quiet"]) == 0
    assert main(["simulate", str(report), "--samples", "1", "--directions", "1",
                 "--workers", "1", "--sensitivity", "--json", str(out)]) == 0
    doc = json.loads(out.read_text())
    assert [r["variant"] for r in doc["sensitivity"]] == [v for v in VARIANTS
                                                          if v != "default"]
    assert "pyramidal cones" in capsys.readouterr().out


def test_a_seeded_run_repeats_exactly():
    poly = demo_part("blob")
    plan = fc.plan(poly, fingers=2, mu=0.5, top=1)[0]
    a = simulate(poly, [plan], samples=2, directions=1, seed=4, workers=1)
    b = simulate(poly, [plan], samples=2, directions=1, seed=4, workers=1)
    assert a == b


def test_fcgrasp_simulate_on_a_report_and_on_contacts(tmp_path, capsys):
    plan = tmp_path / "plan.json"
    assert main(["plan", "demo:blob", "--mu", "0.5", "--top", "2", "--json", str(plan),
                 "--quiet"]) == 0
    out = tmp_path / "stress.json"
    assert main(["simulate", str(plan), "--samples", "2", "--directions", "1",
                 "--workers", "1", "--json", str(out)]) == 0
    doc = json.loads(out.read_text())
    assert doc["kind"] == "stress_test" and len(doc["plans"]) == 2
    g = doc["plans"][0]["grasps"][0]
    for key in ("rank", "contacts", "grip_force", "certified_payload", "slip_load",
                "displacement", "wrench_direction"):
        assert key in g
    assert doc["plans"][0]["wrench_directions"]
    assert all(c["slipped"] for c in doc["controls"])
    assert "controls (not force closure)" in capsys.readouterr().out
    contacts = tmp_path / "grasp.json"
    contacts.write_text(json.dumps({"contacts": [{"point": [0, 15], "mu": 0.5},
                                                 {"point": [80, 16], "mu": 0.5}]}))
    assert main(["simulate", "demo:rectangle", "--contacts", str(contacts), "--samples", "1",
                 "--directions", "2", "--workers", "1", "--quiet"]) == 0


@pytest.mark.parametrize(("argv", "words"), [
    (["simulate", "demo:blob"], "not a plan report"),
    (["simulate", "{empty}"], "no plan to simulate"),
    (["simulate", "{broken}"], "grasps/0"),
    (["simulate", "{plan}", "--samples", "0"], "--samples"),
    (["simulate", "{plan}", "--grip-force", "-1"], "--grip-force"),
])
def test_simulate_refuses_in_one_line(tmp_path, capsys, argv, words):
    plan = tmp_path / "plan.json"
    main(["plan", "demo:blob", "--top", "1", "--json", str(plan), "--quiet"])
    solid = tmp_path / "solid.json"
    main(["plan", "demo:box", "--fingers", "2", "--soft", "--top", "1", "--json", str(solid),
          "--quiet"])
    report = json.loads(plan.read_text())
    empty = tmp_path / "empty.json"
    empty.write_text(json.dumps(dict(report, grasps=[], reason="none")))
    broken = tmp_path / "broken.json"
    report["grasps"][0]["mu"] = "a"
    broken.write_text(json.dumps(report))
    capsys.readouterr()
    code = main([a.format(plan=plan, solid=solid, empty=empty, broken=broken) for a in argv])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and words in err[0], err


def test_a_solids_animation_is_drawn(tmp_path):
    """A solid's recorded stress test: the motion is the part's (its rotation a unit
    quaternion, its shift within the displacement it reports), drawn frame by frame."""
    from fcgrasp.physics import animate_solid, sample_solid_grasps, solid_stress_test
    from fcgrasp.spatial.solid import demo_solid

    solid = demo_solid("angle")
    grasp = fc.plan(solid, fingers=3, mu=0.5, top=1)[0]
    pts, nrm = sample_solid_grasps(grasp, 1, np.random.default_rng(0))[0]
    res = solid_stress_test(solid, pts, nrm, 0.5, [1.0, 0, 0, 0, 0, 0], record=True)
    h = res.history
    assert h.shape[1] == 11 and len(h) > 5
    assert np.allclose(np.linalg.norm(h[:, 7:11], axis=1), 1.0)
    assert np.all(np.linalg.norm(h[:, 4:7], axis=1) <= h[:, 2] + 1e-12)
    _blitted_frames_are_whole_drawings(
        lambda path: animate_solid(solid, res, path, frames=3), tmp_path, pixels=200)
    # (a whole 3-D drawing sorts the fingers and the part by depth; the frames draw
    # the fingers over the part)


@pytest.mark.slow
def test_simulate_gif_of_a_solids_report(tmp_path):
    plan = tmp_path / "plan.json"
    assert main(["plan", "demo:angle", "--fingers", "3", "--mu", "0.5", "--top", "1",
                 "--json", str(plan), "--quiet"]) == 0
    gif = tmp_path / "a.gif"
    assert main(["simulate", str(plan), "--samples", "1", "--directions", "1", "--workers",
                 "1", "--gif", str(gif), "--quiet"]) == 0
    assert gif.read_bytes()[:6] in (b"GIF87a", b"GIF89a")


def test_the_animation_is_drawn(tmp_path):
    poly = demo_part("blob")
    plan = fc.plan(poly, fingers=2, mu=0.5, top=1)[0]
    pts, nrm = sample_grasps(poly, plan.regions, 1, np.random.default_rng(0))[0]
    res = stress_test(poly, pts, nrm, 0.5, [1.0, 0.0, 0.0], record=True)
    assert len(res.history) > 5
    _blitted_frames_are_whole_drawings(
        lambda path: animate(poly, res, path, frames=3), tmp_path, pixels=20)


def _blitted_frames_are_whole_drawings(draw, tmp_path, pixels: int) -> None:
    """An animation's frames, each drawn over one drawing of the still figure (the
    default), are the frames of the whole figure drawn anew for each (``BLIT`` off, the
    reference): a GIF of the frames asked, each the reference's but for at most
    ``pixels`` pixels of another colour, and the frames differ (the part moves, the
    load's curve grows)."""
    import imageio.v3 as iio

    from fcgrasp.physics import _runs

    got, want = tmp_path / "blit.gif", tmp_path / "whole.gif"
    draw(str(got))
    with pytest.MonkeyPatch.context() as m:
        m.setattr(_runs, "BLIT", False)
        draw(str(want))
    assert got.read_bytes()[:6] in (b"GIF87a", b"GIF89a")
    a, b = (iio.imread(f).astype(float) for f in (got, want))
    assert a.shape == b.shape and a.shape[0] == 3
    differ = np.abs(a - b).max(axis=-1) > 60            # pixels of another colour
    assert differ.sum(axis=(1, 2)).max() <= pixels, differ.sum(axis=(1, 2))
    assert all(np.abs(a[k] - a[-1]).max(axis=-1).__gt__(60).mean() > 1e-4
               for k in range(2))


def test_the_prism_inertia_is_the_closed_form_of_a_box_and_of_a_disc():
    from fcgrasp.physics._planar import PART_MASS, _prism_inertia

    w, d, h = 0.08, 0.03, 0.01
    tris = [np.array([[0, 0], [w, 0], [w, d]]), np.array([[0, 0], [w, d], [0, d]])]
    mass, com, inertia = _prism_inertia(tris, h)
    m = PART_MASS
    assert mass == pytest.approx(m) and com == pytest.approx([w / 2, d / 2])
    assert inertia == pytest.approx([m * (d * d + h * h) / 12, m * (w * w + h * h) / 12,
                                     m * (w * w + d * d) / 12])
    # a 400-gon about its centre: a disc's m r^2 / 2, to the polygon's rounding
    a = np.linspace(0, 2 * np.pi, 401)[:-1]
    ring = 0.05 * np.c_[np.cos(a), np.sin(a)] + [0.2, -0.1]
    fan = [np.array([ring.mean(axis=0), ring[i], ring[(i + 1) % 400]]) for i in range(400)]
    mass, com, inertia = _prism_inertia(fan, h)
    assert com == pytest.approx([0.2, -0.1])
    assert inertia[2] == pytest.approx(mass * 0.05 ** 2 / 2, rel=1e-4)


@pytest.mark.parametrize("name", ["quad", pytest.param("blob", marks=pytest.mark.slow),
                                  pytest.param("triangle", marks=pytest.mark.slow)])
def test_the_jaws_poses_hold_and_without_friction_slip(tmp_path, name):
    """The parallel jaw: poses of its boxes (centre, corners, seeded) hold up to their
    certified payload; the same poses without friction slip (here through the command
    line, which runs those controls)."""
    plan = tmp_path / "jaw.json"
    assert main(["plan", f"demo:{name}", "--gripper", "jaw", "--stroke", "5,60", "--pad",
                 "8", "--mu", "0.5", "--top", "2", "--json", str(plan), "--quiet"]) == 0
    out = tmp_path / "stress.json"
    assert main(["simulate", str(plan), "--samples", "4", "--directions", "2",
                 "--workers", "1", "--json", str(out), "--quiet"]) == 0
    doc = json.loads(out.read_text())
    runs = sum(p["runs"] for p in doc["plans"])
    held = sum(p["held"] for p in doc["plans"])
    assert runs >= 12 and held >= 0.95 * runs, (held, runs)
    assert doc["controls"] and all(c["slipped"] for c in doc["controls"])


def _solid_stress(tmp_path, name, argv):
    """The top two plans of ``demo:NAME`` and their stress test (3 grasps by 2
    directions): the report and the test's JSON; 95 % of the runs held."""
    plan = tmp_path / "plan.json"
    assert main(["plan", f"demo:{name}", *argv, "--top", "2", "--json", str(plan),
                 "--quiet"]) == 0
    out = tmp_path / "stress.json"
    assert main(["simulate", str(plan), "--samples", "3", "--directions", "2", "--workers",
                 "1", "--json", str(out), "--quiet"]) == 0
    doc = json.loads(out.read_text())
    runs = sum(p["runs"] for p in doc["plans"])
    held = sum(p["held"] for p in doc["plans"])
    assert runs == 12 and held >= 0.95 * runs, (held, runs)
    return json.loads(plan.read_text()), doc


@pytest.mark.parametrize(("name", "argv"), [
    ("box", ["--fingers", "2", "--soft"]),
    pytest.param("angle", ["--fingers", "3"], marks=pytest.mark.slow),
    pytest.param("angle", ["--fingers", "2", "--soft"], marks=pytest.mark.slow),
    pytest.param("prism", ["--fingers", "3"], marks=pytest.mark.slow),
    pytest.param("cylinder", ["--fingers", "2", "--soft"], marks=pytest.mark.slow),
    pytest.param("box", ["--fingers", "3"], marks=pytest.mark.slow)])
def test_solids_hold_up_to_their_certified_payload_and_controls_slip(tmp_path, name, argv):
    """Solids, soft fingers and three fingers with friction: the regions' grasps hold to
    their certified payload (the Ferrari-Canny L1 measure times the least squeeze), the
    same contacts without friction slip; a solid that is not convex (``demo:angle``, an
    L) as the convex pieces of its facets under the fingers."""
    _, doc = _solid_stress(tmp_path, name, [*argv, "--mu", "0.5"])
    for p in doc["plans"]:
        for g in p["grasps"]:
            assert g["certified_payload"] > 0 and len(g["wrench_direction"]["torque"]) == 3
    assert doc["controls"] and all(c["slipped"] for c in doc["controls"])


@pytest.mark.parametrize("name", ["angle", pytest.param("box", marks=pytest.mark.slow)])
def test_the_jaw_on_a_solid_holds_up_to_its_certified_payload(tmp_path, name):
    """The jaw's pads on a solid as soft contacts on one closing axis (the torsion of a
    round flat pad, ``mu pad / 3`` per newton): the axes sampled in each region hold to
    their certified payload, the same contacts without friction slip."""
    report, doc = _solid_stress(tmp_path, name, ["--gripper", "jaw", "--stroke", "5,50",
                                                 "--pad", "8", "--mu", "0.5"])
    for p, g in zip(doc["plans"], report["grasps"], strict=True):
        axis = np.asarray(g["axis"])
        for run in p["grasps"]:
            a, b = np.asarray(run["contacts"])
            # both pads on one closing axis, the opening apart
            assert np.allclose(np.cross(b - a, axis), 0, atol=1e-9)
            assert abs(float((b - a) @ axis) - g["opening"]) < 1e-9
    assert doc["controls"] and all(c["slipped"] for c in doc["controls"])


def test_the_pieces_under_a_contact_are_the_part_itself():
    """The prisms under the fingers of a solid that is not convex lie inside the part (each
    corner within the mesh or on its surface) and their faces hold the contact."""
    from fcgrasp.physics._solids import _contact_prisms
    from fcgrasp.spatial.solid import demo_solid

    solid = demo_solid("angle")
    size = float(np.linalg.norm(solid.mesh.extents))
    for point, outward in (([5.0, 5.0, 0.0], [0, 0, -1.0]), ([40.0, 4.0, 10.0], [1.0, 0, 0]),
                           ([4.0, 30.0, 10.0], [0, 1.0, 0]), ([6.0, 20.0, 10.0], [1.0, 0, 0])):
        prisms = _contact_prisms(solid, np.array(point), np.array(outward))
        assert prisms
        for pr in prisms:
            inside = solid.mesh.contains(pr - 1e-6 * size * np.array(outward))
            on = np.abs(solid.mesh.nearest.signed_distance(pr)) <= 1e-9 * size
            assert np.all(inside | on), (point, pr)
        # the contact is on one of them (a corner of the hull of its top face)
        assert any(trimesh_contains(pr, np.array(point)) for pr in prisms)


def trimesh_contains(points, q):
    import trimesh

    hull = trimesh.convex.convex_hull(points)
    return bool(abs(hull.nearest.signed_distance([q])[0]) <= 1e-9 or hull.contains([q])[0])


def test_a_reports_fingertips_are_the_simulated_ones(tmp_path, monkeypatch):
    """A plan with ``--hand tip=R`` is shaken with fingertips of that radius (the
    MJCF's spheres, in metres), the report's settings say so, and its grasps hold."""
    from fcgrasp.physics import _planar

    seen = []
    bodies = _planar._finger_bodies

    def spy(points, normals, r, *a, **k):
        seen.append(r)
        return bodies(points, normals, r, *a, **k)

    monkeypatch.setattr(_planar, "_finger_bodies", spy)
    report = tmp_path / "plan.json"
    out = tmp_path / "stress.json"
    assert main(["plan", "demo:bracket", "--mu", "0.5", "--hand", "tip=2,length=30",
                 "--in-plane", "--thickness", "10", "--top", "1", "--json", str(report),
                 "--quiet"]) == 0
    assert main(["simulate", str(report), "--samples", "2", "--directions", "1",
                 "--workers", "1", "--json", str(out), "--quiet"]) == 0
    doc = json.loads(out.read_text())
    assert doc["settings"]["tip_radius"] == 2.0
    assert seen and all(r == pytest.approx(2e-3) for r in seen)
    assert doc["plans"][0]["held"] == doc["plans"][0]["runs"] == 2
