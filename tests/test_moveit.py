"""MoveIt grasps of jaw plans (fcgrasp.io.moveit): the messages' fields against the
message definition, the quaternion against scipy's rotations, and the pose against the
jaw's own pose model (pads placed by ``jaw_poses``, no code shared with the export)."""

from __future__ import annotations

import json
import math
from functools import cache
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from fcgrasp.apps.cli import main
from fcgrasp.errors import ArgumentError
from fcgrasp.grippers.jaw import jaw_poses
from fcgrasp.io.moveit import GRASP_FIELDS, moveit_grasps, quaternion
from fcgrasp.planning import PlanRequest, plan_document

DATA = Path(__file__).parent / "data" / "moveit_msgs"

#: The message type of each field that holds a message (the rest are numbers, strings
#: and lists of them).
NESTED = {"pre_grasp_posture": "trajectory_msgs/JointTrajectory",
          "grasp_posture": "trajectory_msgs/JointTrajectory",
          "grasp_pose": "geometry_msgs/PoseStamped", "pose": "geometry_msgs/Pose",
          "pre_grasp_approach": "moveit_msgs/GripperTranslation",
          "post_grasp_retreat": "moveit_msgs/GripperTranslation",
          "post_place_retreat": "moveit_msgs/GripperTranslation",
          "direction": "geometry_msgs/Vector3Stamped", "header": "std_msgs/Header",
          "stamp": "builtin_interfaces/Time", "time_from_start": "builtin_interfaces/Time",
          "points": "trajectory_msgs/JointTrajectoryPoint"}


def _msg_fields(path: Path) -> tuple[str, ...]:
    """The field names of a ROS message definition (``type name`` lines)."""
    out = []
    for line in path.read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            out.append(line.split()[1])
    return tuple(out)


def _check_message(value, kind):
    assert tuple(value) == GRASP_FIELDS[kind], (kind, tuple(value))
    for key, sub in value.items():
        if key in NESTED:
            for item in sub if isinstance(sub, list) else [sub]:
                _check_message(item, NESTED[key])


@cache
def _jaw_documents():
    jaw = dict(gripper="jaw", stroke=(5, 130), pad=8, mu=0.5, top=3)
    return [plan_document(PlanRequest(part=f"demo:{name}", **jaw))
            for name in ("rectangle", "cam", "washer", "triangle")]


def test_the_grasp_fields_are_the_message_definitions():
    assert GRASP_FIELDS["moveit_msgs/Grasp"] == _msg_fields(DATA / "Grasp.msg")
    for doc in _jaw_documents():
        grasps = moveit_grasps(doc.report)
        assert len(grasps) == len(doc.report["grasps"]) > 0
        for g in grasps:
            _check_message(g, "moveit_msgs/Grasp")


def test_the_pose_is_the_jaws_pose_at_the_boxs_centre():
    """Each grasp's tool frame: at the midpoint of the two pads the jaw's pose model
    places at the box's centre, its y axis the closing direction, its z axis down onto
    the part's plane; the fingers' joints at half the opening in metres."""
    for doc in _jaw_documents():
        assert doc.plans
        for plan, g in zip(doc.plans, moveit_grasps(doc.report), strict=True):
            th, c = (plan.theta[0] + plan.theta[1]) / 2, (plan.offset[0] + plan.offset[1]) / 2
            part = doc.polygon
            r = jaw_poses(part, plan.jaw, [th], [c], 0.5, plan.hole)
            top, bottom = float(r.top[0]), float(r.bottom[0])
            u = np.array([math.cos(th), math.sin(th)])
            n = np.array([-u[1], u[0]])
            pads = [part.centroid + s * u + c * n for s in (top, bottom)]
            want = (pads[0] + pads[1]) / 2 / 1000.0
            pos = g["grasp_pose"]["pose"]["position"]
            assert np.allclose([pos["x"], pos["y"]], want, atol=1e-9) and pos["z"] == 0.0
            q = g["grasp_pose"]["pose"]["orientation"]
            R = Rotation.from_quat([q["x"], q["y"], q["z"], q["w"]]).as_matrix()
            assert np.allclose(R[:, 1], [*u, 0.0], atol=1e-9)
            assert np.allclose(R[:, 2], [0.0, 0.0, -1.0], atol=1e-9)
            joints = g["grasp_posture"]["points"][0]["positions"]
            assert np.allclose(joints, abs(top - bottom) / 2 / 1000.0, atol=1e-12)


def test_the_quaternion_is_scipys_rotation():
    """Seeded rotations, half of them near a half turn (where the trace is near -1 and
    the usual formula divides by almost nothing): the quaternion turns back into the
    same matrix, unit, with w >= 0."""
    rng = np.random.default_rng(7)
    mats = list(Rotation.random(500, random_state=3).as_matrix())
    for _ in range(500):
        axis = rng.normal(size=3)
        angle = math.pi - rng.uniform(0, 1e-6) * rng.choice([0.0, 1.0])
        mats.append(Rotation.from_rotvec(axis / np.linalg.norm(axis) * angle).as_matrix())
    for R in mats:
        q = np.array(quaternion(R))
        assert abs(np.linalg.norm(q) - 1) < 1e-12 and q[3] >= 0
        assert np.allclose(Rotation.from_quat(q).as_matrix(), R, atol=1e-12)


def test_a_solid_jaw_plan_closes_along_its_axis():
    doc = plan_document(PlanRequest(part="demo:box", gripper="jaw", stroke=(5, 130), pad=8,
                                    mu=0.5, top=2))
    for g, grasp in zip(moveit_grasps(doc.report), doc.report["grasps"], strict=True):
        q = g["grasp_pose"]["pose"]["orientation"]
        R = Rotation.from_quat([q["x"], q["y"], q["z"], q["w"]]).as_matrix()
        assert abs(abs(R[:, 1] @ np.asarray(grasp["axis"])) - 1) < 1e-9
        assert abs(R[:, 2] @ np.asarray(grasp["axis"])) < 1e-9
        mid = np.mean(grasp["centers"], axis=0) / 1000.0
        pos = g["grasp_pose"]["pose"]["position"]
        assert np.allclose([pos["x"], pos["y"], pos["z"]], mid, atol=1e-12)


@pytest.mark.parametrize("name", ["blob", "cam", "washer", "bracket"])
def test_two_fingers_close_along_their_contacts_inside_both_cones(name):
    """A two-finger plan as a parallel gripper's grasp: the tool between the two
    representative contacts, its y axis along the line through them (which lies inside
    both friction cones: the squeeze is a force both contacts take, checked from the
    report's normals), the joints at half the opening, approaching wider by the
    clearance; an expanding plan opens from narrower."""
    doc = plan_document(PlanRequest(part=f"demo:{name}", fingers=2, mu=0.4, top=5))
    assert doc.plans
    for grasp, g in zip(doc.report["grasps"], moveit_grasps(doc.report, clearance=0.01),
                        strict=True):
        a, b = (np.asarray(p, float) for p in grasp["contacts"])
        chord = (a - b) / np.linalg.norm(a - b)
        for n, d in ((grasp["normals"][0], chord), (grasp["normals"][1], -chord)):
            inward = -np.asarray(n, float)
            push = -d if grasp["mode"] == "squeeze" else d      # the finger's force
            assert push @ inward >= math.cos(math.atan(0.4)) - 1e-9
        pos = g["grasp_pose"]["pose"]["position"]
        assert np.allclose([pos["x"], pos["y"], pos["z"]], [*((a + b) / 2000.0), 0.0],
                           atol=1e-12)
        q = g["grasp_pose"]["pose"]["orientation"]
        R = Rotation.from_quat([q["x"], q["y"], q["z"], q["w"]]).as_matrix()
        assert np.allclose(R[:, 1], [*chord, 0.0], atol=1e-9)
        assert np.allclose(R[:, 2], [0.0, 0.0, -1.0], atol=1e-9)
        opening = np.linalg.norm(a - b) / 1000.0
        assert np.allclose(g["grasp_posture"]["points"][0]["positions"], opening / 2)
        wide = opening + (0.02 if grasp["mode"] == "squeeze" else -0.02)
        assert np.allclose(g["pre_grasp_posture"]["points"][0]["positions"],
                           max(wide, 0.0) / 2)


def test_a_soft_pair_closes_through_its_centres():
    doc = plan_document(PlanRequest(part="demo:box", fingers=2, soft=True, top=2))
    for g, grasp in zip(moveit_grasps(doc.report), doc.report["grasps"], strict=True):
        c = np.asarray(grasp["centers"], float)
        q = g["grasp_pose"]["pose"]["orientation"]
        R = Rotation.from_quat([q["x"], q["y"], q["z"], q["w"]]).as_matrix()
        axis = (c[0] - c[1]) / np.linalg.norm(c[0] - c[1])
        assert np.allclose(R[:, 1], axis, atol=1e-9) and abs(R[:, 2] @ axis) < 1e-9
        pos = g["grasp_pose"]["pose"]["position"]
        assert np.allclose([pos["x"], pos["y"], pos["z"]], c.mean(axis=0) / 1000.0)


def test_bad_arguments_name_the_field():
    doc = _jaw_documents()[0]
    with pytest.raises(ArgumentError, match="approach") as exc:
        moveit_grasps(doc.report, approach=-1.0)
    assert exc.value.field == "approach"
    three = plan_document(PlanRequest(part="demo:blob", fingers=3, mu=0.5, top=1))
    with pytest.raises(ArgumentError, match="parallel gripper"):
        moveit_grasps(three.report)


def test_the_cli_writes_yaml_and_json_alike(tmp_path, capsys):
    yaml = pytest.importorskip("yaml")
    argv = ["plan", "demo:rectangle", "--gripper", "jaw", "--stroke", "10,50", "--pad", "8",
            "--mu", "0.5", "--top", "2", "--quiet"]
    assert main([*argv, "--moveit", str(tmp_path / "g.yaml")]) == 0
    assert main([*argv, "--moveit", str(tmp_path / "g.json")]) == 0
    got = yaml.safe_load((tmp_path / "g.yaml").read_text())
    assert got == json.loads((tmp_path / "g.json").read_text()) and len(got) == 2
    capsys.readouterr()
    assert main(["plan", "demo:rectangle", "--fingers", "3", "--moveit",
                 str(tmp_path / "x.yaml")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--gripper jaw or two fingers" in err[0]
    assert not (tmp_path / "x.yaml").exists()
