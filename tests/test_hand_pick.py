"""A real hand's pick of a plate from above: every sampled pose of every plan is collision
free by an independent collision library (python-fcl through trimesh: the plate extruded
from the outline, the table as a slab, the hand's boxes placed by their own
transforms), along the whole motion (coming down open, closing, at the contact); and
the same check finds the collisions the pick's rules are there to avoid."""

from __future__ import annotations

import math
from functools import cache

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.grippers.jaw import ParallelJaw, jaw_poses
from fcgrasp.grippers.jaw._pick import Scene, TopPick, top_pick
from fcgrasp.io.moveit import tool_rotation
from fcgrasp.model.hands import HandBox, ParallelHand, hand_from_params, hand_named
from fcgrasp.physics import jaw_contacts

trimesh = pytest.importorskip("trimesh")
pytest.importorskip("fcl")
shapely = pytest.importorskip("shapely")

#: how far each box is pulled in on every side before the check: touching at a contact
#: is no collision (a millionth of a millimetre, far below any plan's size)
SHRINK = 1e-6


def _plate(part: fc.Polygon, thickness: float) -> trimesh.Trimesh:
    holes = [h for h in getattr(part, "holes", [])]
    poly = shapely.Polygon(part.vertices, holes)
    return trimesh.creation.extrude_polygon(poly, thickness)


def _planned(name, hand, mu, scene, pick_type):
    """``demo:NAME`` planned by ``hand`` in ``scene`` (top 3, no budget): the part, the
    jaw (its pick a ``pick_type``), the plans and the scene's collision manager."""
    part = fc.read_part(f"demo:{name}")
    jaw = ParallelJaw.of_hand(hand, mu, scene)
    assert isinstance(jaw.pick, pick_type), jaw.pick
    plans = fc.plan(part, gripper=jaw, top=3, time_limit=None)
    assert plans, name
    return part, jaw, plans, _manager(part, scene)


def _manager(part: fc.Polygon, scene: Scene) -> trimesh.collision.CollisionManager:
    m = trimesh.collision.CollisionManager()
    m.add_object("plate", _plate(part, scene.thickness))
    if scene.table:
        slab = trimesh.creation.box(extents=(1e4, 1e4, 10.0))
        slab.apply_translation((0.0, 0.0, -5.0))
        m.add_object("table", slab)
    return m


@cache
def _box(size: tuple[float, ...]) -> trimesh.Trimesh:
    """A box mesh of ``size`` less :data:`SHRINK` on every side, centred at the origin,
    made once per size (fcl's geometry of it is then made once too, and each placement
    is a transform)."""
    return trimesh.creation.box(extents=np.asarray(size) - 2 * SHRINK)


def _hand_meshes(hand: ParallelHand, opening: float, origin: np.ndarray,
                 R: np.ndarray) -> list[tuple[trimesh.Trimesh, np.ndarray]]:
    """The hand's boxes at ``opening``, placed at ``origin`` turned by ``R``: each a
    box mesh and its transform."""
    out = []
    for b in hand.boxes(opening):
        T = np.eye(4)
        T[:3, :3] = R @ np.asarray(b.rotation)
        T[:3, 3] = origin + R @ np.asarray(b.centre)
        out.append((_box(tuple(float(v) for v in b.size)), T))
    return out


def _collides(manager, meshes) -> bool:
    """Whether any of ``meshes`` (placed meshes, or meshes with their transforms)
    meets an object of ``manager``, by python-fcl."""
    return any(manager.in_collision_single(*m) if isinstance(m, tuple)
               else manager.in_collision_single(m) for m in meshes)


def _motion(part, jaw: ParallelJaw, pick: TopPick, theta: float, offset: float):
    """The hand's placements along one pose's pick: coming down open, closing, at the
    contact (origin, rotation, opening)."""
    r = jaw_poses(part, jaw, [theta], [offset])
    top, bottom = float(r.top[0]), float(r.bottom[0])
    u = np.array([math.cos(theta), math.sin(theta)])
    n = np.array([-u[1], u[0]])
    xy = part.centroid + (top + bottom) / 2 * u + offset * n
    R = tool_rotation(np.r_[u, 0.0], [0.0, 0.0, -1.0])
    widest = jaw.hand.stroke[1]
    out = [(np.r_[xy, pick.height + dz], R, widest) for dz in (jaw.scene.approach, 5.0, 0.0)]
    out += [(np.r_[xy, pick.height], R, o) for o in
            np.linspace(widest, top - bottom, 4)[1:]]
    return out, bool(r.holds[0])


def _closes(part, jaw: ParallelJaw, mu: float, theta: float, offset: float) -> bool:
    """Force closure of a jaw pose by the general test (the wrench cone of the pads'
    contacts)."""
    pts, outward, _, _, _ = jaw_contacts(part, jaw, theta, offset)
    return fc.Grasp([fc.FrictionPoint(q, -m, mu) for q, m in zip(pts, outward, strict=True)]
                    ).is_force_closure()


CASES = [pytest.param("rectangle", 0.5, 5.0, True, marks=pytest.mark.slow),
         ("bracket", 0.5, 8.0, True),
         pytest.param("cam", 0.8, 12.0, False, marks=pytest.mark.slow),
         pytest.param("quad", 0.5, 40.0, True, marks=pytest.mark.slow),
         pytest.param("blob", 0.6, 3.0, True, marks=pytest.mark.slow)]


@pytest.mark.parametrize("name,mu,thickness,table", CASES)
def test_every_sampled_pose_of_every_plan_is_collision_free(name, mu, thickness, table):
    hand = hand_named("franka")
    scene = Scene(thickness, table=table)
    part, jaw, plans, manager = _planned(name, hand, mu, scene, TopPick)
    pick = jaw.pick
    rng = np.random.default_rng(7)
    checked = 0
    for p in plans:
        assert p.mode == "external"
        for theta, offset in p.sample(20, rng):
            placements, holds = _motion(part, jaw, pick, theta, offset)
            assert holds, (name, theta, offset)
            assert _closes(part, jaw, mu, theta, offset), (name, theta, offset)
            for origin, R, opening in placements:
                assert not _collides(manager, _hand_meshes(hand, opening, origin, R)), \
                    (name, theta, offset, opening, origin)
                checked += 1
    assert checked >= 150


def test_the_check_sees_the_table_and_a_thick_plate():
    """The rules the pick avoids are real collisions to the independent check: the hand
    at the plate's mid-height goes through the table, and on a plate thicker than the
    fingers' reach below the mounts the mounts go through the plate."""
    part = fc.read_part("demo:rectangle")
    hand = hand_named("franka")
    jaw = ParallelJaw.of_hand(hand, 0.5, Scene(5.0, table=True))
    plans = fc.plan(part, gripper=jaw, top=1, time_limit=None)
    theta, offset = plans[0].centre
    low = TopPick(5.0 / 2 + sum(hand.pad_span) / 2, 5.0)     # the pad centred, no table rule
    placements, _ = _motion(part, jaw, low, theta, offset)
    origin, R, opening = placements[-1]
    assert _collides(_manager(part, jaw.scene), _hand_meshes(hand, opening, origin, R))
    # a 60 mm plate with a bump just beside the pad's strip: the mounts (22 mm wide, 24
    # mm above the tool's origin, 11 mm behind the pad's face) go through the bump at the
    # plate's mid-height, and clear it at the height the rule gives
    bump = fc.Polygon([[0, 0], [40, 0], [40, 24.5], [60, 24.5], [60, 40], [0, 40]])
    thick = Scene(60.0, table=False)
    got = top_pick(hand, thick)
    assert isinstance(got, TopPick) and got.height >= 60.0 - 24.0 + 1.0 - 1e-9
    jaw = ParallelJaw.of_hand(hand, 0.5, thick)
    manager = _manager(bump, thick)
    offset = 15.0 - float(bump.centroid[1])             # the strip centred on y = 15
    hits = []
    for height in (60.0 / 2 + sum(hand.pad_span) / 2, got.height):
        placements, _ = _motion(bump, jaw, TopPick(height, 1.0), 0.0, offset)
        origin, R, opening = placements[-1]
        hits.append(_collides(manager, _hand_meshes(hand, opening, origin, R)))
    assert hits == [True, False]


def test_a_hand_wider_than_its_pad_is_kept_above_the_plate():
    """A finger box wider than the pad is not in the pad's strip: the pick raises the hand
    until it is above the plate, or says the pad cannot reach."""
    hand = hand_from_params((0, 60), pad_width=10, pad_height=10, finger_thickness=5,
                            finger_length=30)
    assert all(hand.in_strip(b) for b in hand.finger)
    wide = ParallelHand("wide", hand.stroke, hand.palm,
                        hand.finger + (HandBox("mount", (0.0, 4.0, -12.0), (16.0, 8.0, 4.0)),),
                        "pad")
    assert not wide.in_strip(wide.finger[-1])
    ok = top_pick(wide, Scene(4.0, table=False))
    assert isinstance(ok, TopPick) and ok.height >= -10.0 + 4.0 + 1.0 - 1e-9
    # a mount as low as the pad: the pad cannot touch the plate's side below it
    low = ParallelHand("low", hand.stroke, hand.palm,
                       hand.finger + (HandBox("mount", (0.0, 8.0, 3.0), (16.0, 4.0, 4.0)),),
                       "pad")
    reason = top_pick(low, Scene(4.0, table=False))
    assert isinstance(reason, str) and "do not reach" in reason
    jaw = ParallelJaw.of_hand(low, 0.5, Scene(4.0, table=False))
    assert fc.plan(fc.read_part("demo:rectangle"), gripper=jaw, top=1) == []
    assert jaw.no_grasp_reason(0.5) == reason


def test_the_report_has_the_hand_the_scene_and_each_pose(tmp_path):
    import json

    from fcgrasp.apps.cli import main

    out = tmp_path / "r.json"
    assert main(["plan", "demo:rectangle", "--gripper", "jaw", "--hand", "franka", "--mu",
                 "0.5", "--table", "--thickness", "5", "--top", "2", "--json", str(out),
                 "--quiet"]) == 0
    r = json.loads(out.read_text())
    assert r["hand"]["licence"] == "Apache-2.0" and r["hand"]["stroke"] == [0.0, 79.96]
    assert r["scene"]["table"] == {"point": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, 1.0]}
    for g in r["grasps"]:
        q = np.asarray(g["pose"]["orientation"])
        assert abs(np.linalg.norm(q) - 1) < 1e-12
        assert g["approach"]["direction"] == [0.0, 0.0, -1.0]
        assert g["collision_free"] is True and g["contact_height"] > 0
        # the tool's y axis (the closing axis) is the box centre's closing direction
        from scipy.spatial.transform import Rotation

        y = Rotation.from_quat(q).as_matrix()[:, 1]
        theta = sum(g["theta_rad"]) / 2
        assert abs(abs(y @ [math.cos(theta), math.sin(theta), 0.0]) - 1) < 1e-9


@pytest.mark.parametrize("argv,field", [
    (["--hand", "nope"], "--hand"), (["--hand", "franka", "--stroke", "1,2"], "--stroke"),
    (["--thickness", "3"], "--thickness"), (["--hand", "franka", "--thickness", "-1"],
                                             "--thickness")])
def test_hand_options_are_refused_in_one_line(capsys, argv, field):
    from fcgrasp.apps.cli import main

    code = main(["plan", "demo:rectangle", "--gripper", "jaw", "--mu", "0.5", *argv])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and field in err[0], err


HANDE = __import__("pathlib").Path(__file__).parent / "data" / "hands" / "robotiq_hande" / \
    "urdf" / "robotiq_hand_e.urdf"


def test_the_built_in_hande_is_its_description_read_again():
    from fcgrasp.io.urdf import hand_from_urdf
    from fcgrasp.model.hands import hand_description

    pytest.importorskip("yourdfpy")
    read = hand_description(hand_from_urdf(HANDE, name="robotiq_hande"))
    built = hand_description(hand_named("robotiq_hande"))
    for key in ("stroke", "joint_per_opening", "joint_offset", "ee_offset", "pad", "joints"):
        assert np.allclose(read[key], built[key], rtol=1e-12, atol=1e-12) \
            if key not in ("pad", "joints") else read[key] == built[key], key
    for part in ("palm", "finger"):
        assert len(read[part]) == len(built[part])
        for a, b in zip(read[part], built[part], strict=True):
            assert a["name"] == b["name"]
            assert np.allclose(a["centre"], b["centre"], atol=1e-9)
            assert np.allclose(a["size"], b["size"], atol=1e-9)
    hand = hand_named("robotiq_hande")
    assert hand.stroke[1] == pytest.approx(50.0, abs=0.01) and hand.pad_width == \
        pytest.approx(21.0, abs=1e-3)
    # the joints: open at 0, closed at 25 mm (the description's limits)
    assert hand.joint_offset == pytest.approx(0.025, abs=1e-6)
    assert hand.joint_offset + hand.joint_per_opening * hand.stroke[1] == \
        pytest.approx(0.0, abs=1e-6)


@pytest.mark.parametrize("name,thickness,table", [("rectangle", 4.0, True),
                                                  ("bracket", 25.0, True),
                                                  pytest.param("quad", 10.0, False,
                                                               marks=pytest.mark.slow)])
def test_the_hande_meshes_themselves_clear_the_plate_and_the_table(name, thickness, table):
    """The hand read from its URDF, placed by yourdfpy's own kinematics with its real
    collision meshes (not the boxes that cover them): no collision along any sampled
    pick of any plan."""
    yourdfpy = pytest.importorskip("yourdfpy")
    u = yourdfpy.URDF.load(str(HANDE), build_collision_scene_graph=True,
                           load_collision_meshes=True)
    hand = hand_named("robotiq_hande")
    part = fc.read_part(f"demo:{name}")
    scene = Scene(thickness, table=table)
    jaw = ParallelJaw.of_hand(hand, 0.5, scene)
    pick = jaw.pick
    assert isinstance(pick, TopPick)
    plans = fc.plan(part, gripper=jaw, top=2, time_limit=None)
    assert plans
    manager = _manager(part, scene)
    tool_T_palm = np.eye(4)
    tool_T_palm[:3, :3] = np.asarray(hand.ee_axes).T
    tool_T_palm[:3, 3] = hand.ee_offset
    (j1, j2), rng, checked = hand.joints, np.random.default_rng(3), 0
    for p in plans:
        for theta, offset in p.sample(6, rng):
            placements, holds = _motion(part, jaw, pick, theta, offset)
            assert holds
            for origin, R, opening in placements:
                # retracted by a thousandth of a millimetre: the pads touch at a contact
                q = hand.joint_offset + hand.joint_per_opening * min(opening + 2e-3,
                                                                     hand.stroke[1])
                u.update_cfg({j1: q, j2: q})
                world_T_tool = np.eye(4)
                world_T_tool[:3, :3], world_T_tool[:3, 3] = R, origin
                meshes = []
                for node in u.collision_scene.graph.nodes_geometry:
                    T, geom = u.collision_scene.graph[node]
                    m = u.collision_scene.geometry[geom].copy()
                    m.apply_transform(T)
                    m.apply_scale(1000.0)              # metres to the part's millimetres
                    m.apply_transform(world_T_tool @ tool_T_palm)
                    meshes.append(m)
                assert not _collides(manager, meshes), (name, theta, offset, opening)
                checked += 1
    assert checked >= 50


def test_the_moveit_grasp_of_a_pick_puts_the_hands_pads_on_the_part(tmp_path):
    """The exported grasp (the end effector's pose and the finger joints, metres) placed
    by yourdfpy's kinematics with the description's meshes: neither finger in the plate,
    and where the pads touch flat (edges, vertices) both within a thousandth of a
    millimetre of it (on a pad's corner the mesh's chamfer meets the part a little
    later than its covering box)."""
    import json

    from fcgrasp.apps.cli import main

    yourdfpy = pytest.importorskip("yourdfpy")
    out, grasps = tmp_path / "r.json", tmp_path / "g.json"
    assert main(["plan", "demo:rectangle", "--gripper", "jaw", "--hand", "robotiq_hande",
                 "--mu", "0.5", "--table", "--thickness", "4", "--top", "2", "--json",
                 str(out), "--moveit", str(grasps), "--quiet"]) == 0
    part = fc.read_part("demo:rectangle")
    manager = _manager(part, Scene(4.0, table=True))
    u = yourdfpy.URDF.load(str(HANDE), build_collision_scene_graph=True,
                           load_collision_meshes=True)
    from scipy.spatial.transform import Rotation

    report = json.loads(out.read_text())
    for g, plan in zip(json.loads(grasps.read_text()), report["grasps"], strict=True):
        flat = "corner" not in (plan["contacts"]["a"]["kind"], plan["contacts"]["b"]["kind"])
        assert g["grasp_pose"]["header"]["frame_id"] == "part"
        pose = g["grasp_pose"]["pose"]
        world_T_ee = np.eye(4)
        o = pose["orientation"]
        world_T_ee[:3, :3] = Rotation.from_quat([o["x"], o["y"], o["z"], o["w"]]).as_matrix()
        world_T_ee[:3, 3] = [1000 * pose["position"][k] for k in "xyz"]
        names = g["grasp_posture"]["joint_names"]
        q = g["grasp_posture"]["points"][0]["positions"]
        for retract, near in ((-1e-5, (1e-3, 0.02 if flat else 1.0)),
                              (0.0, (-1e-9, 1e-3 if flat else 1.0))):
            # the joints close as they grow: a negative step opens by 2 x 0.01 mm
            u.update_cfg({n: v + retract for n, v in zip(names, q, strict=True)})
            gaps = []
            for node in u.collision_scene.graph.nodes_geometry:
                T, geom = u.collision_scene.graph[node]
                if "finger" not in u.collision_scene.graph.transforms.parents[node]:
                    continue
                m = u.collision_scene.geometry[geom].copy()
                m.apply_transform(T)
                m.apply_scale(1000.0)
                m.apply_transform(world_T_ee)
                gaps.append(manager.min_distance_single(m))
            assert len(gaps) == 2 and all(near[0] <= d <= near[1] for d in gaps), gaps


def _solid_manager(solid, rest):
    """The mesh, and the table under it in the part's frame (``rest``: the part's pose
    on the table, None without one)."""
    m = trimesh.collision.CollisionManager()
    m.add_object("part", solid.mesh)
    if rest is not None:
        slab = trimesh.creation.box(extents=(1e4, 1e4, 10.0))
        slab.apply_translation((0.0, 0.0, -5.0))
        slab.apply_transform(np.linalg.inv(rest))
        m.add_object("table", slab)
    return m


def _in_region(plan, facet, n, rng):
    """``n`` axis points sampled in a solid jaw region (its holes left out), and its
    vertices."""
    poly = shapely.Polygon(facet.to_2d(np.asarray(plan.regions[0])),
                           [facet.to_2d(np.asarray(h)) for h in plan.holes[0]])
    lo_x, lo_y, hi_x, hi_y = poly.bounds
    pts = []
    while len(pts) < n:
        q = rng.uniform((lo_x, lo_y), (hi_x, hi_y))
        if poly.contains(shapely.Point(q)):
            pts.append(q)
    return facet.to_3d(np.array(pts + list(np.asarray(poly.exterior.coords)[:-1])))


def _placements_clear(solid, hand, plans, rest, count: int, seed: int) -> int:
    """Axis points sampled in each solid region (``count`` and its corners): the hand's
    boxes along the approach and the closing, each box on its own, asserted clear of
    the mesh and the table (``rest``: the part's pose on it, or None) by python-fcl;
    the placements checked."""
    from fcgrasp.grippers.jaw._solid_pick import solid_tool_frame, up_in_part

    m = _solid_manager(solid, rest)
    rng, checked = np.random.default_rng(seed), 0
    for p in plans:
        facet = solid.facets[p.facets[0]]
        origin, R = solid_tool_frame(p, up_in_part(rest))
        wide = min(hand.stroke[1], p.opening + 2.0)
        for v in _in_region(p, facet, count, rng):
            at = origin + (v - np.asarray(p.centers[0]))
            for dz, opening in [(-100.0, wide), (-30.0, wide), (0.0, wide),
                                (0.0, (wide + p.opening) / 2), (0.0, p.opening + 2e-3)]:
                meshes = _hand_meshes(hand, opening, at + dz * R[:, 2], R)
                assert not _collides(m, meshes), (p.facets, v, dz, opening)
                checked += 1
    return checked


@pytest.mark.parametrize("name,table", [("angle", False),
                                        pytest.param("angle", True, marks=pytest.mark.slow),
                                        ("tall", True),
                                        pytest.param("box", False, marks=pytest.mark.slow)])
def test_every_sampled_placement_of_a_solid_region_is_collision_free(name, table):
    """Axis points sampled in each region (and its corners): the hand's boxes along the
    approach and the closing, each box on its own (not the hulls the search sweeps),
    checked by python-fcl against the mesh and the table; the pads end on the facets."""
    from fcgrasp.grippers.jaw._solid_pick import resting_pose
    from fcgrasp.spatial.solid import demo_solid, solid_from_mesh

    # a block 30 x 20 x 40: the Franka's fingers reach its sides above the table
    solid = solid_from_mesh(trimesh.creation.box((30.0, 20.0, 40.0))) if name == "tall" \
        else demo_solid(name)
    hand = hand_named("franka")
    jaw = ParallelJaw.of_hand(hand, 0.5, Scene(1.0, table=table))
    plans = fc.plan(solid, gripper=jaw, top=3, time_limit=None)
    assert plans, name
    rest = resting_pose(solid) if table else None
    assert _placements_clear(solid, hand, plans, rest, 10, 5) >= 50


def test_a_solid_region_without_the_hand_collides():
    """The regions of the bare jaw on the resting bracket (the hand's pads, no hand):
    some placement puts the Franka through the table or the part."""
    from fcgrasp.grippers.jaw._solid_pick import (
        pad_diameter,
        resting_pose,
        solid_tool_frame,
        up_in_part,
    )
    from fcgrasp.spatial.jaw import solid_jaw_plans
    from fcgrasp.spatial.solid import demo_solid

    solid = demo_solid("angle")
    hand = hand_named("franka")
    rest = resting_pose(solid)
    m = _solid_manager(solid, rest)
    hits = 0
    for p in solid_jaw_plans(solid, hand.stroke, pad_diameter(hand), 0.5, top=5):
        origin, R = solid_tool_frame(p, up_in_part(rest))
        hits += _collides(m, _hand_meshes(hand, p.opening + 2e-3, origin, R))
    assert hits >= 1


def test_a_solid_picks_report_validates_with_its_resting_pose(tmp_path):
    import json

    from fcgrasp.apps.cli import main
    from fcgrasp.io.schema import validate

    pytest.importorskip("jsonschema")
    out = tmp_path / "r.json"
    assert main(["plan", "demo:angle", "--gripper", "jaw", "--hand", "franka", "--mu", "0.5",
                 "--table", "--top", "3", "--json", str(out), "--quiet"]) == 0
    r = json.loads(out.read_text())
    validate(r)
    assert r["hand"]["name"] == "franka" and r["scene"]["table"]["normal"] == [0.0, 0.0, 1.0]
    # the part's pose on the table puts its lowest point on it, and each pick's retreat
    # is the table's up, seen in the part's frame
    from scipy.spatial.transform import Rotation

    q = r["scene"]["part_pose"]["orientation"]
    R = Rotation.from_quat(q).as_matrix()
    from fcgrasp.spatial.solid import demo_solid

    pts = np.asarray(demo_solid("angle").mesh.vertices) @ R.T + \
        np.asarray(r["scene"]["part_pose"]["position"])
    assert abs(pts[:, 2].min()) < 1e-9
    for g in r["grasps"]:
        assert np.allclose(R @ np.asarray(g["retreat"]["direction"]), [0, 0, 1], atol=1e-9)
        # the approach comes down onto the table, across the closing axis
        assert (R @ np.asarray(g["approach"]["direction"]))[2] < 0
        assert abs(np.asarray(g["approach"]["direction"]) @ np.asarray(g["axis"])) < 1e-9


def test_a_page_names_a_built_in_hand_never_a_file():
    from fcgrasp.apps._explorer_data import plan_request
    from fcgrasp.errors import RequestError

    req = plan_request({"gripper": "jaw", "hand": "robotiq_hande", "stroke": [1, 2], "pad": 3,
                        "table": True, "thickness": 5, "mu": 0.5})
    assert req.hand == "robotiq_hande" and req.stroke is None and req.table
    for bad in ("tests/data/hands/robotiq_hande/urdf/robotiq_hand_e.urdf",
                "stroke=0:60,pad=10,height=12,thickness=6", "/etc/passwd"):
        with pytest.raises(RequestError) as err:
            plan_request({"gripper": "jaw", "hand": bad, "mu": 0.5})
        assert err.value.field == "hand"
    # without a hand the plate's options are not used
    assert plan_request({"gripper": "jaw", "stroke": [5, 50], "pad": 8, "table": True,
                         "mu": 0.5}).table is False


def test_a_batch_line_of_a_pick_carries_its_hand_and_scene(tmp_path):
    import json

    from fcgrasp.apps.cli import main

    (tmp_path / "parts").mkdir()
    (tmp_path / "parts" / "rect.json").write_text(
        json.dumps({"vertices": [[0, 0], [80, 0], [80, 30], [0, 30]]}))
    out = tmp_path / "r.jsonl"
    assert main(["batch", str(tmp_path / "parts"), "--out", str(out), "--gripper", "jaw",
                 "--hand", "franka", "--mu", "0.5", "--table", "--top", "2",
                 "--workers", "1"]) == 0
    (line,) = [json.loads(x) for x in out.read_text().splitlines()]
    assert line["hand"]["name"] == "franka" and line["scene"]["table"] is not None
    assert line["grasps"] and all("pose" in g for g in line["grasps"])


FRANKA_URDF = HANDE.parents[2] / "franka_boxes" / "franka_hand_boxes.urdf"


def test_the_urdf_reader_gives_the_built_in_franka_hand():
    """The Franka Hand's description expanded into a plain URDF, read by
    :func:`fcgrasp.io.urdf.hand_from_urdf` (yourdfpy): the same stroke, joints and boxes
    (every corner, relative to the pad) as the hand written from the xacro."""
    from fcgrasp.io.urdf import hand_from_urdf

    pytest.importorskip("yourdfpy")
    read, built = hand_from_urdf(FRANKA_URDF), hand_named("franka")
    assert read.stroke == pytest.approx(built.stroke, abs=1e-9)
    assert read.joint_per_opening == pytest.approx(built.joint_per_opening, rel=1e-12)
    assert read.joint_offset == pytest.approx(built.joint_offset, abs=1e-12)
    assert read.pad_width == pytest.approx(built.pad_width) and read.joints == built.joints

    def corners(hand, opening):
        boxes = hand.boxes(opening)
        pad = np.asarray(hand.boxes(opening)[len(hand.palm) + [b.name for b in hand.finger]
                                             .index(hand.pad)].centre)
        return sorted(tuple(np.round(np.sort(b.corners() - pad, axis=0).ravel(), 6))
                      for b in boxes)

    for opening in (0.0, 31.5, 79.96):
        assert corners(read, opening) == corners(built, opening)


@pytest.mark.parametrize("text,message", [
    ("<robot name='r'><link name='a'/></robot>", "two prismatic finger joints"),
    ("not a urdf at all", "not a URDF"),
    ("""<robot name='r'><link name='p'/>
        <link name='f1'><collision><geometry><mesh filename='missing.stl'/></geometry>
        </collision></link><link name='f2'/>
        <joint name='j1' type='prismatic'><parent link='p'/><child link='f1'/>
        <axis xyz='0 1 0'/><limit lower='0' upper='0.04' effort='1' velocity='1'/></joint>
        <joint name='j2' type='prismatic'><parent link='p'/><child link='f2'/>
        <axis xyz='0 -1 0'/><limit lower='0' upper='0.04' effort='1' velocity='1'/></joint>
        </robot>""", "missing"),
    ("""<robot name='r'><link name='p'/><link name='f1'/><link name='f2'/>
        <joint name='j1' type='revolute'><parent link='p'/><child link='f1'/>
        <axis xyz='1 0 0'/><limit lower='0' upper='1' effort='1' velocity='1'/></joint>
        <joint name='j2' type='revolute'><parent link='p'/><child link='f2'/>
        <axis xyz='1 0 0'/><limit lower='0' upper='1' effort='1' velocity='1'/></joint>
        </robot>""", "two prismatic finger joints"),
])
def test_a_urdf_the_reader_does_not_take_is_one_line(tmp_path, capsys, text, message):
    from fcgrasp.apps.cli import main

    pytest.importorskip("yourdfpy")
    path = tmp_path / "hand.urdf"
    path.write_text(text)
    code = main(["plan", "demo:rectangle", "--gripper", "jaw", "--mu", "0.5", "--hand",
                 str(path)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and message in err[0] and "--hand" in err[0], err


def test_a_solid_rests_in_the_stable_pose_asked(tmp_path, capsys):
    import json

    from fcgrasp.apps.cli import main
    from fcgrasp.io.schema import validate

    poses = []
    for rest in ("0", "1"):
        out = tmp_path / f"r{rest}.json"
        assert main(["plan", "demo:angle", "--gripper", "jaw", "--hand", "franka", "--mu",
                     "0.5", "--table", "--rest", rest, "--json", str(out), "--quiet"]) == 0
        r = json.loads(out.read_text())
        validate(r)
        assert r["scene"]["rest"] == int(rest) and 0 < r["scene"]["rest_probability"] <= 1
        poses.append(r["scene"]["part_pose"]["orientation"])
    assert not np.allclose(np.abs(poses[0]), np.abs(poses[1]))
    capsys.readouterr()
    for argv, words in ((["--table", "--rest", "99"], "rest must be from 0 to"),
                        (["--rest", "1"], "--rest")):
        code = main(["plan", "demo:angle", "--gripper", "jaw", "--hand", "franka", "--mu",
                     "0.5", *argv])
        err = capsys.readouterr().err.strip().splitlines()
        assert code == 2 and len(err) == 1 and words in err[0], err


def test_a_solid_rests_in_the_orientation_given(tmp_path, capsys):
    """``--rest-orientation``: the cylinder laid on its side (a quarter turn about x), its
    lowest point on the table; the report's part pose is that orientation; every sampled
    placement of the hand along each region is clear of the mesh and the table
    (python-fcl); a zero quaternion, one without --table and one beside --rest are
    refused in one line."""
    import json

    from fcgrasp.apps.cli import main
    from fcgrasp.io.schema import validate
    from fcgrasp.spatial.solid import demo_solid

    out = tmp_path / "side.json"
    q = [0.5, 0.0, 0.0, 0.5]                        # a quarter turn about x, not unit
    assert main(["plan", "demo:cylinder", "--gripper", "jaw", "--hand", "franka", "--mu",
                 "0.5", "--table", "--rest-orientation", ",".join(map(str, q)), "--top", "3",
                 "--json", str(out), "--quiet"]) == 0
    r = json.loads(out.read_text())
    validate(r)
    pose = r["scene"]["part_pose"]
    assert np.allclose(pose["orientation"], np.array(q) / np.linalg.norm(q))
    assert r["scene"]["rest"] is None and r["scene"]["rest_orientation"] == \
        pytest.approx(list(np.array(q) / np.linalg.norm(q)))
    solid = demo_solid("cylinder")
    x, y, z, w = pose["orientation"]
    R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    lifted = solid.mesh.vertices @ R.T + pose["position"]
    assert lifted[:, 2].min() == pytest.approx(0.0, abs=1e-9)
    rest = np.eye(4)
    rest[:3, :3], rest[:3, 3] = R, pose["position"]
    hand = hand_named("franka")
    jaw = ParallelJaw.of_hand(hand, 0.5, Scene(1.0, table=True, orientation=tuple(q)))
    plans = fc.plan(solid, gripper=jaw, top=3, time_limit=None)
    assert len(plans) == len(r["grasps"]) > 0
    assert _placements_clear(solid, hand, plans, rest, 6, 9) >= 20
    capsys.readouterr()
    for argv, words in ((["--table", "--rest-orientation", "0,0,0,0"], "not zero"),
                        (["--table", "--rest-orientation", "1,2"], "--rest-orientation must"),
                        (["--rest-orientation", "0,0,0,1"], "--table"),
                        (["--table", "--rest", "0", "--rest-orientation", "0,0,0,1"],
                         "give one")):
        code = main(["plan", "demo:cylinder", "--gripper", "jaw", "--hand", "franka", "--mu",
                     "0.5", *argv])
        err = capsys.readouterr().err.strip().splitlines()
        assert code == 2 and len(err) == 1 and words in err[0], err


def test_the_explorers_stress_test_refuses_what_it_cannot_run_in_one_line():
    from fcgrasp.apps._explorer_data import stress_result
    from fcgrasp.errors import RequestError

    pytest.importorskip("mujoco")
    part = fc.read_part("demo:rectangle")
    for bad in ("not a plan", {"regions": "x"}, {}):
        with pytest.raises(RequestError) as err:
            stress_result(part, "mm", bad)
        assert err.value.field == "plan"
    plan = fc.plan(part, fingers=2, mu=0.5, top=1)[0].to_dict()
    got = stress_result(part, "mm", {**plan, "rank": 1})
    assert got["runs"] == 4 and 0 <= got["held"] <= 4 and got["gif"]


@pytest.mark.parametrize("argv,field,hint", [
    (["--hand", "franka"], "--hand", "--gripper jaw"),
    (["--table"], "--table", "--hand tip="),
    (["--thickness", "4"], "--thickness", "--hand tip="),
    (["--hand", "tip=2", "--finger-radius", "2"], "--finger-radius", "--hand tip="),
    (["--hand", "tip=2,length=3", "--thickness", "6"], "--hand", "long"),
    (["--hand", "tip=2,width=3"], "--hand", "tip=R"),
    (["--hand", "tip=-1"], "--hand", "> 0, got 'tip=-1'"),
    (["--hand", "tip=2", "--rest", "1"], "--rest", "--gripper jaw")])
def test_point_fingers_refuse_a_hands_options_in_one_line(capsys, argv, field, hint):
    from fcgrasp.apps.cli import main

    code = main(["plan", "demo:rectangle", "--fingers", "2", "--mu", "0.5", *argv])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and field in err[0] and hint in err[0], err


@cache
def _cylinder(radius: float, length: float) -> trimesh.Trimesh:
    """A vertical cylinder of 64 sides (inside the true one), centred at the origin,
    made once per radius and length."""
    return trimesh.creation.cylinder(radius=radius, height=length, sections=64)


def _finger(axis_xy, radius: float, z0: float, length: float
            ) -> tuple[trimesh.Trimesh, np.ndarray]:
    """A finger body from ``z0`` up ``length``, its axis at ``axis_xy``: the cylinder
    (:func:`_cylinder`) and its transform, as ``in_collision_single`` takes them."""
    T = np.eye(4)
    T[:3, 3] = (axis_xy[0], axis_xy[1], z0 + length / 2)
    return _cylinder(radius, length), T


def _tip_placements(plan, count: int, rng) -> list[tuple[np.ndarray, np.ndarray]]:
    """Each finger's placements: its region's ends pulled in a thousandth, its middle and
    seeded points, with the plan's normal (regions on single edges)."""
    out = []
    for k in range(count):
        pts = []
        for r in plan.regions:
            r = np.asarray(r, float)
            t = (1e-3, 1 - 1e-3, 0.5)[k] if k < 3 else float(rng.uniform())
            pts.append(r[0] + t * (r[-1] - r[0]))
        out.append((np.array(pts), np.asarray(plan.normals, float)))
    return out


@pytest.mark.parametrize("name,fingers", [("bracket", 2), ("cam", 3),
                                          pytest.param("washer", 2, marks=pytest.mark.slow)])
def test_point_fingers_on_bodies_are_collision_free_by_fcl(tmp_path, name, fingers):
    """Point fingers with --hand tip=R picked from a table: every finger body placed
    along each region (ends, middle, seeded points) and along its descent meets neither
    the extruded plate nor the table (python-fcl through trimesh); the bare plans' own
    contacts on the bracket, with the same fingers, meet the plate (the check can
    fail)."""
    from fcgrasp.apps.cli import main
    from fcgrasp.io.schema import validate

    out = tmp_path / "plan.json"
    assert main(["plan", f"demo:{name}", "--fingers", str(fingers), "--mu", "0.5",
                 "--hand", "tip=4,length=40", "--table", "--thickness", "6", "--top", "5",
                 "--json", str(out), "--quiet"]) == 0
    import json

    doc = json.loads(out.read_text())
    validate(doc)
    assert doc["hand"]["tip_radius"] == 4 and doc["scene"]["thickness"] == 6
    from fcgrasp.io.parts import demo_part

    part = demo_part(name)
    scene = Scene(6.0, table=True)
    manager = _manager(part, scene)
    plans = fc.plan(part, fingers=fingers, mu=0.5, top=5, hand=fc.Hand(finger_radius=4.0))
    assert plans and len(doc["grasps"]) == len(plans)
    rng = np.random.default_rng(3)
    for plan, g in zip(plans, doc["grasps"], strict=True):
        assert g["collision_free"] and g["contact_height"] == pytest.approx(5.0)
        for tip, c, n in zip(g["fingertips"], plan.contacts, plan.normals, strict=True):
            assert tip["position"][:2] == pytest.approx(list(c + 4.0 * n))
            assert tip["position"][2] == pytest.approx(1.0)
        for pts, nrm in _tip_placements(plan, 8, rng):
            for q, n in zip(pts, nrm, strict=True):
                for z0 in (1.0, 30.0, 101.0):           # at the contact, coming down
                    assert not manager.in_collision_single(
                        *_finger(q + 4.0 * n, 4.0 * (1 - 1e-6), z0, 40.0)), (plan.edges, q)
    if name == "bracket":       # the control: its reflex corner takes no finger of 4
        bare = fc.plan(part, fingers=fingers, mu=0.5, top=20)
        hits = sum(manager.in_collision_single(*_finger(c + 4.0 * n, 4.0, 1.0, 40.0))
                   for p in bare for c, n in zip(p.contacts, p.normals, strict=True))
        assert hits > 0


#: a C-shaped plate whose pocket (open to the left) takes a fingertip from above but
#: not a finger lying in the plane across it
C_PLATE = [(0, 0), (60, 0), (60, 40), (0, 40), (0, 30), (50, 30), (50, 10), (0, 10)]


@pytest.mark.parametrize("part,fingers", [("c", 2), ("bracket", 2), ("cam", 3)])
def test_fingers_held_in_the_plane_sweep_clear_of_the_part(tmp_path, part, fingers):
    """--in-plane: every finger lying in the plate's plane along its contact's normal,
    at sampled placements along its region (ends pulled in a thousandth, middle, seeded
    points), swept from where it comes in to the contact, meets the part only there
    (shapely: the capsule of its centres' segment, a millionth thinner, against the
    outline); on the C plate the plans from above put a finger in the pocket, whose
    sweep in the plane would cross the pocket's lip (the check can fail)."""
    import json

    from fcgrasp.apps.cli import main
    from fcgrasp.io.parts import demo_part
    from fcgrasp.io.schema import validate

    src = tmp_path / "c.json"
    src.write_text(json.dumps({"vertices": C_PLATE}))
    name = str(src) if part == "c" else f"demo:{part}"
    poly = fc.Polygon(C_PLATE) if part == "c" else demo_part(part)
    shape = shapely.Polygon(poly.vertices, [h for h in getattr(poly, "holes", [])])
    R, L, away = 3.0, 30.0, 20.0

    def sweeps_clear(plan) -> bool:
        for r, n in zip(plan.regions, plan.normals, strict=True):
            r, n = np.asarray(r, float), np.asarray(n, float) / np.linalg.norm(n)
            for t in (1e-3, 0.5, 1 - 1e-3, *np.random.default_rng(2).uniform(size=5)):
                c = r[0] + t * (r[-1] - r[0]) + R * n
                body = shapely.LineString([c, c + (L + away) * n]).buffer(R * (1 - 1e-6))
                if body.intersection(shape).area > 1e-9 * shape.area:
                    return False
        return True

    out = tmp_path / "plan.json"
    assert main(["plan", name, "--fingers", str(fingers), "--mu", "0.5", "--hand",
                 f"tip={R:g},length={L:g}", "--in-plane", "--thickness", "10", "--top", "6",
                 "--json", str(out), "--quiet"]) == 0
    doc = json.loads(out.read_text())
    validate(doc)
    assert doc["hand"]["in_plane"] is True and doc["grasps"]
    for g in doc["grasps"]:
        for tip, n in zip(g["fingertips"], g["normals"], strict=True):
            assert tip["position"][2] == pytest.approx(5.0)
            assert tip["approach"]["direction"][:2] == pytest.approx([-n[0], -n[1]])
            assert tip["approach"]["distance"] == pytest.approx(away)
    hand = fc.Hand(finger_radius=R, finger_length=L + away)
    plans = fc.plan(poly, fingers=fingers, mu=0.5, top=6, hand=hand)
    assert [list(p.edges) for p in plans] == [g["edges"] for g in doc["grasps"]]
    assert all(sweeps_clear(p) for p in plans)
    if part == "c":
        above = fc.plan(poly, fingers=fingers, mu=0.5, top=6, hand=fc.Hand(finger_radius=R))
        assert not all(sweeps_clear(p) for p in above)


def test_in_plane_fingers_refuse_in_one_line(capsys):
    from fcgrasp.apps.cli import main

    for argv, words in ((["--in-plane"], "--hand"),
                        (["--hand", "tip=3", "--in-plane", "--table", "--thickness", "6"],
                         "off the table"),
                        (["--gripper", "jaw", "--stroke", "5,50", "--pad", "8", "--in-plane"],
                         "--in-plane")):
        code = main(["plan", "demo:rectangle", "--mu", "0.5", *argv])
        err = capsys.readouterr().err.strip().splitlines()
        assert code == 2 and len(err) == 1 and words in err[0], err
