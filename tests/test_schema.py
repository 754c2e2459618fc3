"""The plan report's JSON Schema (fcgrasp/schema/plan-report.schema.json): every
gripper's report on a planar part and on a solid validates, a solid's normals point out
of the mesh, a report of the previous format is read, and a broken report does not
validate."""

from __future__ import annotations

import json

import numpy as np
import pytest

from fcgrasp.apps.cli import main
from fcgrasp.errors import ArgumentError
from fcgrasp.io.report import FORMAT_VERSION, migrate_report
from fcgrasp.io.schema import schema, validate

pytest.importorskip("jsonschema")

PLANAR = [["--fingers", "2", "--mu", "0.3"], ["--fingers", "3", "--mu", "0.5"],
          ["--fingers", "4"],
          ["--gripper", "jaw", "--stroke", "5,60", "--pad", "8", "--mu", "0.5"],
          ["--gripper", "jaw", "--hand", "franka", "--mu", "0.5", "--table"],
          pytest.param(["--fingers", "3", "--gravity", "0,-1"], marks=pytest.mark.slow),
          pytest.param(["--fingers", "2", "--mu", "0.3", "--mass", "0.3", "--force-limit",
                        "10"], marks=pytest.mark.slow),
          pytest.param(["--fingers", "3", "--mu", "0.5", "--bound"], marks=pytest.mark.slow)]
SOLID = [["--fingers", "2", "--soft", "--mu", "0.5"], ["--fingers", "3", "--mu", "0.5"],
         ["--gripper", "jaw", "--stroke", "2,60", "--pad", "3", "--mu", "0.5"]]


def _report(tmp_path, part, argv):
    out = tmp_path / "plan.json"
    assert main(["plan", part, *argv, "--top", "3", "--json", str(out), "--quiet"]) == 0
    return json.loads(out.read_text())


def test_the_schema_is_a_valid_draft_2020_12_schema():
    import jsonschema

    jsonschema.Draft202012Validator.check_schema(schema())
    assert schema()["properties"]["format_version"]["const"] == FORMAT_VERSION


@pytest.mark.parametrize("argv", PLANAR, ids=lambda a: " ".join(a[:2]) if isinstance(a, list)
                         else None)
def test_every_planar_report_validates(tmp_path, argv):
    part = "demo:quad" if "--bound" in argv else "demo:blob"
    report = _report(tmp_path, part, argv)
    assert report["grasps"]
    validate(report)


@pytest.mark.parametrize(("name", "argv"), [
    ("angle", SOLID[0]), ("angle", SOLID[2]),
    *(pytest.param(n, a, marks=pytest.mark.slow)
      for n, a in (("box", SOLID[0]), ("box", SOLID[1]), ("angle", SOLID[1]),
                   ("box", SOLID[2])))],
    ids=lambda v: v if isinstance(v, str) else " ".join(v[:2]))
def test_every_solid_report_validates_with_normals_out_of_the_mesh(tmp_path, argv, name):
    """Each region's centre moved a hair along its normal leaves the solid; a hair
    against it enters (the parity of a ray's crossings with the mesh, the ray test of
    ``test_spatial_rays``)."""
    from fcgrasp.spatial.solid import demo_solid

    from .test_spatial_rays import _hits

    report = _report(tmp_path, f"demo:{name}", argv)
    assert report["grasps"]
    validate(report)
    mesh = demo_solid(name).mesh
    tri = np.asarray(mesh.vertices)[np.asarray(mesh.faces)]
    hair = 1e-4 * float(np.linalg.norm(mesh.extents))
    ray = np.array([0.3141, 0.5926, 0.7431])          # off every axis of the parts
    ray /= np.linalg.norm(ray)

    def inside(p):
        t, _ = _hits(tri, p, ray)
        return int(np.sum(t > 0)) % 2 == 1

    for g in report["grasps"]:
        c, n = np.asarray(g["centers"], float), np.asarray(g["normals"], float)
        assert np.allclose(np.linalg.norm(n, axis=1), 1.0)
        for p, m in zip(c, n, strict=True):
            assert not inside(p + hair * m) and inside(p - hair * m), (p, m)


def test_a_version_2_solid_report_is_migrated_and_validates(tmp_path):
    report = _report(tmp_path, "demo:box", SOLID[0])
    old = json.loads(json.dumps(report))
    old["format_version"] = 2
    for g in old["grasps"]:
        g["normals"] = [[-x for x in n] for n in g["normals"]]     # version 2: inward
    back = migrate_report(old)
    validate(back)
    assert [g["normals"] for g in back["grasps"]] == [g["normals"] for g in report["grasps"]]


@pytest.mark.parametrize("breaks", [
    lambda r: r.pop("complete"),
    lambda r: r.update(format_version=2),
    lambda r: r["grasps"][0].pop("regions"),
    lambda r: r["grasps"][0].update(normals=[[1.0, 0.0, 0.0]] * 2),
    lambda r: r.update(complete=False),                              # no gap
    lambda r: r["parameters"].update(top=0),
])
def test_a_broken_report_does_not_validate(tmp_path, breaks):
    report = _report(tmp_path, "demo:blob", PLANAR[0])
    breaks(report)
    with pytest.raises(ArgumentError, match="schema"):
        validate(report)


@pytest.mark.parametrize("breaks", [
    lambda r: r.pop("scene"),                                     # a hand without its scene
    lambda r: r["grasps"][0].pop("pose"),
    lambda r: r["grasps"][0]["pose"].update(orientation=[0.0, 0.0, 1.0]),
    lambda r: r["hand"]["boxes"][0].update(size=[1.0, -1.0, 1.0]),
    lambda r: r["scene"].update(table={"point": [0.0, 0.0, 0.0]}),
])
def test_a_broken_pick_does_not_validate(tmp_path, breaks):
    report = _report(tmp_path, "demo:rectangle", ["--gripper", "jaw", "--hand", "franka",
                                                  "--mu", "0.5", "--table"])
    validate(report)
    breaks(report)
    with pytest.raises(ArgumentError, match="schema"):
        validate(report)
