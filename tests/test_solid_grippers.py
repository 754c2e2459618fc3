"""Solids through the same planner and grippers as planar parts: ``fc.plan(solid,
...)`` gives the plans of ``fcgrasp plan part.stl`` for every gripper that plans solids
(two soft fingers, three fingers with friction, the parallel jaw), and the grippers
that plan planar parts only say so (the time budget on solids: ``test_budget``)."""

from __future__ import annotations

import json

import pytest

import fcgrasp as fc
from fcgrasp.apps.cli import main
from fcgrasp.grippers.solids import plans_solids
from fcgrasp.spatial.solid import demo_solid

trimesh = pytest.importorskip("trimesh")

CASES = [("box", dict(fingers=2, mu=0.3), ["--fingers", "2", "--soft", "--mu", "0.3"]),
         ("prism", dict(fingers=3, mu=0.5), ["--fingers", "3", "--mu", "0.5"]),
         ("angle", dict(gripper=fc.ParallelJaw(stroke=(5, 50), pad_width=8, mu=0.5)),
          ["--gripper", "jaw", "--stroke", "5,50", "--pad", "8", "--mu", "0.5"])]


@pytest.mark.parametrize(("name", "kw", "argv"), CASES, ids=[c[0] for c in CASES])
def test_fc_plan_of_a_solid_is_fcgrasp_plan_of_it(tmp_path, name, kw, argv):
    plans = fc.plan(demo_solid(name), top=3, **kw)
    out = tmp_path / "plan.json"
    assert main(["plan", f"demo:{name}", *argv, "--top", "3", "--json", str(out),
                 "--quiet"]) == 0
    report = json.loads(out.read_text())
    assert plans and plans.complete
    assert [list(p.facets) for p in plans] == [g["facets"] for g in report["grasps"]]
    assert [p.radius for p in plans] == pytest.approx([g["radius"] for g in report["grasps"]],
                                                      rel=1e-11)


def test_a_trimesh_mesh_is_a_solid_in_millimetres():
    box = trimesh.creation.box((40, 20, 10))
    best = fc.plan(box, fingers=2, mu=0.3, top=1)[0]
    assert best.radius == pytest.approx(fc.plan(demo_solid("box"), top=1)[0].radius)


@pytest.mark.parametrize(("kw", "words"), [
    (dict(fingers=4), "4 fingers plan planar parts only"),
    (dict(fingers=3, gravity=(0.0, -1.0)), "gravity"),
    (dict(fingers=2, rank_by="epsilon"), "rank_by"),
    (dict(fingers=2, hand=fc.Hand(finger_radius=1.0)), "hand"),
])
def test_what_a_solid_does_not_take_is_refused_by_name(kw, words):
    with pytest.raises(ValueError, match=words):
        fc.plan(demo_solid("box"), **kw)


def test_every_built_in_gripper_says_whether_it_plans_solids():
    from fcgrasp.grippers.fingers import point_fingers

    assert plans_solids(point_fingers(2, 0.3, None, None, True))
    assert plans_solids(point_fingers(3, 0.3, None, None, True))
    assert plans_solids(fc.ParallelJaw(stroke=(1, 2), pad_width=1, mu=0.3))
    assert not plans_solids(point_fingers(4, 0.0, None, None, True))
    assert not plans_solids(point_fingers(3, 0.0, (0.0, -1.0), None, True))


@pytest.mark.parametrize("kind", [{"fingers": 2}, {"fingers": 3, "mu": 0.5},
                                  {"gripper": "jaw", "stroke": (5.0, 60.0), "pad": 8.0}])
def test_a_solid_request_takes_the_options_its_gripper_takes_there(kind):
    """A request on a solid is checked against the options its gripper's solid plans
    take (``solid_options``): each of the others, given, is refused naming its field,
    and the explorer offers on a solid the choices whose gripper plans solids, with
    those options."""
    from fcgrasp.apps._explorer_data import solid_choices
    from fcgrasp.errors import RequestError
    from fcgrasp.grippers.base import gripper_type
    from fcgrasp.planning import PlanRequest

    cls = gripper_type(kind.get("gripper", "fingers"), kind)
    takes = set(cls.solid_options)
    assert {"mu", "top", "margin", "distinct", "time_limit", "max_memory"} <= takes
    PlanRequest(part="demo:box", **kind)
    others = {"rank_by": "epsilon", "single_edge": True,
              "certify": True, "thickness": 3.0, "mass": 1.0, "bound": True,
              "in_plane": True, "finger_radius": 1.0}
    refused = 0
    for name, value in others.items():
        if name in takes:
            continue
        with pytest.raises(RequestError) as err:
            PlanRequest(part="demo:box", **kind, **{name: value})
        assert "on a solid" in str(err.value) and err.value.field == name, (name, err.value)
        refused += 1
    assert refused >= 7
    choices = solid_choices()
    assert set(choices) == {"2", "3", "jaw"}
    assert all(set(v) <= {"mu", "margin", "top", "distinct", "time_limit", "max_memory",
                          "stroke", "pad", "hand", "table", "rest", "rest_orientation"}
               for v in choices.values())


def test_read_part_reads_a_solid_as_the_command_line_does(tmp_path, capsys):
    """One entry for every part: ``fc.read_part`` of a mesh file or a built-in solid is
    the solid ``read_solid`` gives (a two-body file: the body asked for, by default the
    largest), planned as ``fcgrasp plan`` plans it; the options that read drawings are
    refused by name, and ``fcgrasp parts`` lists a built-in solid's body."""
    import numpy as np
    import trimesh

    from fcgrasp.io.meshes import read_solid

    two = trimesh.util.concatenate([demo_solid("box").mesh,
                                    demo_solid("cylinder").mesh.apply_translation([80, 0, 0])])
    path = tmp_path / "two.stl"
    two.export(path)
    for part in (None, 0, 1):
        got, want = fc.read_part(path, part), read_solid(str(path), select=part)
        assert isinstance(got, fc.Solid)
        assert np.array_equal(got.mesh.vertices, want.mesh.vertices)
    assert fc.read_part(path).size == fc.read_part(path, 0).size != fc.read_part(path, 1).size
    solid = fc.read_part("demo:box", units="cm")
    assert solid.units == "cm" and solid.size == pytest.approx(demo_solid("box").size / 10)
    plans = fc.plan(fc.read_part("demo:box"), fingers=2, mu=0.5, top=3)
    out = tmp_path / "box.json"
    assert main(["plan", "demo:box", "--fingers", "2", "--soft", "--mu", "0.5", "--top", "3",
                 "--json", str(out), "--quiet"]) == 0
    assert [g["radius"] for g in json.loads(out.read_text())["grasps"]] == \
        [pytest.approx(p.radius, rel=1e-9) for p in plans]
    for bad in ({"flatten": 0.1}, {"layer": "0"}, {"y_down": True}):
        with pytest.raises(ValueError, match=next(iter(bad))):
            fc.read_part(path, **bad)
    capsys.readouterr()
    assert main(["parts", "demo:box"]) == 0 and "1 body" in capsys.readouterr().out
