"""``fcgrasp batch`` and ``plan_many``: a folder of parts in every input format,
some broken on purpose, planned by the local pool and by a Dask LocalCluster; results
equal ``fcgrasp plan --json``; a second run does nothing; a batch killed half-way and run
again ends with the same file as one never interrupted."""

import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.apps import _batch_workers, batch
from fcgrasp.apps.cli import main
from fcgrasp.io.schema import validate

from .test_cli import run, run_here

OPTIONS = ["--fingers", "2", "--mu", "0.4", "--top", "3"]


def _ring(rng, n=None, radius=30.0):
    n = n or int(rng.integers(5, 9))
    ang = np.sort(rng.uniform(0, 2 * np.pi, n))
    r = rng.uniform(0.6, 1.0, n) * radius
    return np.c_[r * np.cos(ang), r * np.sin(ang)].round(4)


def make_parts(folder, seed=0):
    """One part in each format (JSON, GeoJSON, WKT, SVG, DXF, PNG) and four broken ones."""
    import ezdxf
    from PIL import Image, ImageDraw

    rng = np.random.default_rng(seed)
    folder.mkdir(exist_ok=True)
    v = _ring(rng)
    (folder / "a.json").write_text(json.dumps({"vertices": v.tolist()}))
    v = _ring(rng)
    (folder / "b.geojson").write_text(json.dumps({"type": "Feature", "geometry": {
        "type": "Polygon", "coordinates": [v.tolist() + [v[0].tolist()]]}}))
    v = _ring(rng)
    (folder / "c.wkt").write_text("POLYGON ((" + ", ".join(f"{x} {y}" for x, y in
                                                           np.r_[v, v[:1]]) + "))")
    v = _ring(rng) + 40
    pts = " ".join(f"{x},{y}" for x, y in v)
    (folder / "d.svg").write_text(f'<svg xmlns="http://www.w3.org/2000/svg" width="100mm" '
                                  f'height="100mm" viewBox="0 0 100 100">'
                                  f'<polygon points="{pts}"/></svg>')
    doc = ezdxf.new()
    doc.modelspace().add_lwpolyline(_ring(rng).tolist(), close=True)
    doc.saveas(folder / "e.dxf")
    img = Image.new("L", (120, 120), 255)
    ImageDraw.Draw(img).polygon([tuple(p) for p in (_ring(rng, 6, 50) + 60)], fill=0)
    img.save(folder / "f.png")
    (folder / "broken.json").write_text("{not json")
    (folder / "open.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg">'
                                     '<path d="M 0 0 L 10 10" fill="none"/></svg>')
    (folder / "crossing.json").write_text(json.dumps({"vertices": [[0, 0], [10, 10], [10, 0],
                                                                   [0, 10]]}))
    Image.new("L", (40, 40), 255).save(folder / "blank.png")
    return sorted(p.name for p in folder.iterdir())


def _lines(path):
    out = {}
    for line in path.read_text().splitlines():
        r = json.loads(line)
        assert r["path"] not in out, f"{r['path']} twice"
        out[r["path"]] = r
    return out


def _same(a, b):
    assert set(a) == set(b)
    for k in a:
        for key in ("hash", "parameters", "grasps", "reason", "error", "units"):
            assert a[k][key] == b[k][key], (k, key)


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    f = tmp_path_factory.mktemp("parts") / "in"
    make_parts(f)
    return f


@pytest.fixture(scope="module")
def local_results(folder, tmp_path_factory):
    out = tmp_path_factory.mktemp("res") / "local.jsonl"
    r = run("batch", folder, "--out", out, "--workers", "2", *OPTIONS, timeout=600)
    return r, out


def test_local_batch_equals_plan_json(folder, local_results, tmp_path):
    r, out = local_results
    assert r.returncode == 1, r.stderr                  # four parts are broken
    assert "failed                   4" in r.stdout
    got = _lines(out)
    assert len(got) == 10
    broken = {"broken.json", "open.svg", "crossing.json", "blank.png"}
    for path, res in got.items():
        name = os.path.basename(path)
        if name in broken:
            assert res["error"] and res["grasps"] is None and "\n" not in res["error"]
            continue
        assert res["error"] is None, (name, res["error"])
        want = tmp_path / f"{name}.plan.json"
        assert main(["plan", path, *OPTIONS, "--json", str(want), "--quiet"]) == 0
        report = json.loads(want.read_text())
        validate(report)                    # the batch's grasps are the report's
        assert res["grasps"] == report["grasps"] and res["reason"] == report["reason"]
        assert res["parameters"]["fingers"] == 2 and res["parameters"]["mu"] == 0.4
        assert len(res["hash"]) == 64 and res["seconds"] >= 0


@pytest.mark.slow
def test_a_second_run_does_nothing(folder, local_results):
    _, out = local_results
    before = out.read_bytes()
    r = run("batch", folder, "--out", out, *OPTIONS)
    assert r.returncode == 1                               # failures are still recorded
    assert "planned                  0" in r.stdout and "skipped (done before)    10" in r.stdout
    assert out.read_bytes() == before
    # other options are other results
    other = out.parent / "other.jsonl"
    other.write_bytes(before)
    r = run("batch", folder, "--out", other, "--fingers", "2", "--mu", "0.5", "--top", "3")
    assert len(other.read_text().splitlines()) == 20


@pytest.mark.slow
def test_dask_local_cluster_gives_the_same_results(folder, local_results, tmp_path):
    pytest.importorskip("distributed")
    _, out = local_results
    dask_out = tmp_path / "dask.jsonl"
    r = run("batch", folder, "--out", dask_out, "--scheduler", "local", "--workers", "2",
            *OPTIONS, timeout=600)
    assert r.returncode == 1, r.stderr
    want = {k: v for k, v in _lines(out).items()}
    _same(_lines(dask_out), want)


def test_killed_half_way_then_resumed_equals_uninterrupted(tmp_path):
    rng = np.random.default_rng(5)
    folder = tmp_path / "many"
    folder.mkdir()
    for k in range(16):
        (folder / f"p{k:02d}.json").write_text(json.dumps({"vertices": _ring(rng, 40).tolist()}))
    opts = ["--fingers", "4", "--top", "3", "--single-edge"]
    whole = tmp_path / "whole.jsonl"
    assert run("batch", folder, "--out", whole, "--workers", "1", *opts,
               timeout=600).returncode == 0
    cut = tmp_path / "cut.jsonl"
    cmd = [sys.executable, "-m", "fcgrasp", "batch", str(folder), "--out", str(cut),
           "--workers", "1", *opts]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    deadline = time.time() + 300
    while time.time() < deadline:
        if cut.exists() and cut.read_bytes().count(b"\n") >= 4:
            break
        time.sleep(0.02)
    os.killpg(proc.pid, signal.SIGKILL)                 # the batch and its workers
    proc.wait()
    # the lines written whole (a kill can cut the line being written: a fatal signal
    # ends a write between pages)
    n_cut = cut.read_bytes().count(b"\n")
    assert 4 <= n_cut < 16
    with open(cut, "ab") as f:                          # as if killed while writing a line
        f.write(b'{"path": "torn')
    r = run("batch", folder, "--out", cut, "--workers", "2", *opts, timeout=600)
    assert r.returncode == 0, r.stderr
    assert f"skipped (done before)    {n_cut}" in r.stdout
    _same(_lines(cut), _lines(whole))


#: The deadline of a part that never ends (only such a part runs under it, so no test
#: depends on how fast the machine plans).
NEVER_ENDING_LIMIT = 2.0
#: The deadline of a part that never ends and runs alone.
ALONE_LIMIT = 0.5


def test_a_part_timeout_and_a_dead_worker_are_recorded(tmp_path, monkeypatch):
    rng = np.random.default_rng(9)
    polys = [fc.Polygon(_ring(rng, 6)), fc.Polygon(_ring(rng, 7))]
    real = _batch_workers._plan_one

    def flaky(task):                 # inherited by the forked workers
        if task.path == "polygon:1":
            os._exit(3)
        return real(task)

    monkeypatch.setattr(_batch_workers, "_plan_one", flaky)
    res = {r["path"]: r for r in batch.plan_many(polys, workers=2, fingers=2, mu=0.4, top=2)}
    assert res["polygon:0"]["error"] is None and res["polygon:0"]["grasps"]
    assert "worker died" in res["polygon:1"]["error"]

    def never_ends(task):
        time.sleep(3600)             # stopped by its deadline, never by finishing

    monkeypatch.setattr(_batch_workers, "_plan_one", never_ends)
    res = {r["path"]: r for r in batch.plan_many([polys[0]], workers=1, fingers=2, mu=0.4,
                                                 top=2, part_timeout=ALONE_LIMIT)}
    assert "timeout" in res["polygon:0"]["error"]


def test_plan_many_from_python_local_and_on_a_client():
    distributed = pytest.importorskip("distributed")
    rng = np.random.default_rng(11)
    polys = [fc.Polygon(_ring(rng)) for _ in range(3)]
    local = {r["path"]: r for r in fc.plan_many(polys, fingers=3, mu=0.5, top=2, workers=2)}
    direct = [fc.plan(p, fingers=3, mu=0.5, top=2) for p in polys]
    for k, plans in enumerate(direct):
        assert [g["edges"] for g in local[f"polygon:{k}"]["grasps"]] == \
            [list(p.edges) for p in plans]
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=1,
                            dashboard_address=None) as client:
        on = {r["path"]: r for r in fc.plan_many(polys, client=client, fingers=3, mu=0.5,
                                                  top=2)}
    for k in local:
        assert on[k]["grasps"] == local[k]["grasps"]


def test_bad_batch_options(tmp_path, folder, capsys):
    """Refused in one line, exit 2, nothing written (the command line's own process:
    test_cli_fuzz; these through its entry point)."""
    for bad in (["--workers", "0"], ["--part-timeout", "-1"], ["--gripper", "jaw"],
                ["--fingers", "4", "--mu", "0.3"]):
        r = run_here(capsys, "batch", folder, "--out", tmp_path / "x.jsonl", *bad)
        assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, (bad, r.stderr)
        assert not (tmp_path / "x.jsonl").exists()
    r = run_here(capsys, "batch", tmp_path / "nothing-here", "--out", tmp_path / "x.jsonl")
    assert r.returncode == 2 and "no part files" in r.stderr
    with pytest.raises(TypeError, match="parts"):
        list(fc.plan_many([3.0]))
    with pytest.raises(ValueError, match="top"):
        list(fc.plan_many(["demo:quad"], top=None))


def test_a_large_part_is_split_across_the_cluster(monkeypatch):
    """A large part's candidate batches are solved by the cluster's workers (the public
    candidates -> solve -> rank pipeline): the same plans as planned whole."""
    distributed = pytest.importorskip("distributed")
    from fcgrasp.pipeline import _spec as pipeline  # the search's tunables

    rng = np.random.default_rng(21)
    polys = [fc.Polygon(_ring(rng, 14)) for _ in range(2)] + [fc.Polygon(_ring(rng, 6))]
    opts = {"fingers": 4, "top": 3, "single_edge": True}
    whole = {r["path"]: r for r in fc.plan_many(polys, workers=1, **opts)}
    monkeypatch.setattr(_batch_workers, "LARGE_EDGES", 10)
    monkeypatch.setattr(pipeline, "FIRST_BATCH", 64)       # several batches to share out
    with distributed.Client(processes=False, n_workers=2, threads_per_worker=1,
                            dashboard_address=None) as client:
        with distributed.get_task_stream(client) as stream:
            split = {r["path"]: r for r in fc.plan_many(polys, client=client, **opts)}
    names = [str(t["key"]) for t in stream.data]
    assert sum("solve" in k for k in names) >= 8          # batches solved as cluster tasks
    assert sum("_plan_group" in k for k in names) == 1     # the small part, as a group
    for k in whole:
        assert split[k]["error"] is None and split[k]["grasps"] == whole[k]["grasps"]


def test_a_folder_is_walked_and_only_part_files_are_parts(tmp_path):
    """`fcgrasp batch DIR` did not look into subfolders and counted a README or a .tsv
    as a failed part."""
    ring = '{"vertices": [[0, 0], [40, 0], [40, 20], [0, 20]]}'
    (tmp_path / "a.json").write_text(ring)
    (tmp_path / "sub" / "deeper").mkdir(parents=True)
    (tmp_path / "sub" / "b.json").write_text(ring)
    (tmp_path / "sub" / "deeper" / "c.wkt").write_text("POLYGON ((0 0, 9 0, 9 4, 0 4, 0 0))")
    (tmp_path / "README").write_text("parts of the widget")
    (tmp_path / "sub" / "table.tsv").write_text("a\tb\n")
    (tmp_path / ".hidden").mkdir()
    (tmp_path / ".hidden" / "d.json").write_text(ring)
    want = [str(tmp_path / "a.json"), str(tmp_path / "sub" / "b.json"),
            str(tmp_path / "sub" / "deeper" / "c.wkt")]
    assert batch.part_files(str(tmp_path)) == sorted(want)
    assert batch.part_files(str(tmp_path / "**" / "*")) == sorted(want)


@pytest.mark.slow       # the default suite's time (3 minutes on two cores)
def test_meshes_among_drawings_are_planned_for_the_batchs_gripper(tmp_path):
    """A folder of a drawing and two meshes (one in a subfolder): the meshes are planned
    for two soft fingers with the batch's friction and top, exactly as ``fcgrasp plan
    --soft``; with a jaw for the jaw, with three fingers for three fingers with
    friction, the drawing planned beside them."""
    trimesh = pytest.importorskip("trimesh")
    from fcgrasp.io.meshes import read_solid
    from fcgrasp.spatial import point_triple_plans, soft_pair_plans, solid_jaw_plans

    (tmp_path / "in" / "sub").mkdir(parents=True)
    (tmp_path / "in" / "plate.json").write_text('{"vertices": [[0, 0], [30, 0], [30, 10], '
                                                '[0, 10]]}')
    trimesh.creation.box((20.0, 12.0, 6.0)).export(tmp_path / "in" / "sub" / "block.stl")
    trimesh.creation.icosphere(subdivisions=2, radius=8.0).export(tmp_path / "in" / "b.stl")
    out = tmp_path / "soft.jsonl"
    summary = batch.run_batch(batch.part_files(str(tmp_path / "in")), str(out), workers=1,
                              mu=0.4, top=2)
    assert summary.planned == 3 and not summary.failed
    got = _lines(out)
    assert all(r["error"] is None for r in got.values())
    for name in ("sub/block.stl", "b.stl"):
        path = str(tmp_path / "in" / name)
        want = soft_pair_plans(read_solid(path), 0.4, top=2)
        assert [g["radius"] for g in got[path]["grasps"]] == pytest.approx(
            [p.radius for p in want], rel=1e-12)
    assert got[str(tmp_path / "in" / "plate.json")]["grasps"][0]["min_region_length"] > 0
    out = tmp_path / "jaw.jsonl"
    batch.run_batch(batch.part_files(str(tmp_path / "in")), str(out), workers=1,
                    gripper="jaw", stroke=(5.0, 40.0), pad=4.0)
    got = _lines(out)
    assert all(r["error"] is None for r in got.values())
    # the meshes for the jaw and for three fingers, as fcgrasp plan plans them
    block = str(tmp_path / "in" / "sub" / "block.stl")
    want = solid_jaw_plans(read_solid(block), (5.0, 40.0), 4.0, 0.3, top=10)
    assert [g["opening"] for g in got[block]["grasps"]] == pytest.approx(
        [p.opening for p in want], rel=1e-12)
    out = tmp_path / "three.jsonl"
    batch.run_batch([block, str(tmp_path / "in" / "plate.json")], str(out), workers=1,
                    fingers=3, mu=0.5, top=2)
    got = _lines(out)
    assert all(r["error"] is None for r in got.values())
    want3 = point_triple_plans(read_solid(block), 0.5, top=2).plans
    assert [g["radius"] for g in got[block]["grasps"]] == pytest.approx(
        [p.radius for p in want3], rel=1e-12)
    assert all(len(g["facets"]) == 3 for g in got[block]["grasps"])


def test_identical_files_are_two_parts(tmp_path):
    """Results are keyed by path and content: a folder holding two identical files gets
    a line for each, and a second run skips both."""
    folder = tmp_path / "in"
    folder.mkdir()
    body = json.dumps({"vertices": _ring(np.random.default_rng(4)).tolist()})
    (folder / "a.json").write_text(body)
    (folder / "b.json").write_text(body)
    out = tmp_path / "res.jsonl"
    assert main(["batch", str(folder), "--out", str(out), "--workers", "1", *OPTIONS,
                 "--quiet"]) == 0
    lines = _lines(out)
    assert sorted(os.path.basename(p) for p in lines) == ["a.json", "b.json"]
    a, b = (lines[str(folder / n)] for n in ("a.json", "b.json"))
    assert a["hash"] == b["hash"] and a["grasps"] == b["grasps"]
    summary = batch.run_batch([str(folder / "a.json"), str(folder / "b.json")], str(out),
                              workers=1, fingers=2, mu=0.4, top=3)
    assert (summary.planned, summary.skipped) == (0, 2)


def test_a_batchs_outputs_are_not_read_as_parts(tmp_path):
    """A results file and a figures folder inside the input folder: a second run reads
    neither as a part."""
    folder = tmp_path / "in"
    folder.mkdir()
    (folder / "a.json").write_text(json.dumps({"vertices": _ring(
        np.random.default_rng(5)).tolist()}))
    out, figures = folder / "results.json", folder / "figures"
    for _ in range(2):
        assert main(["batch", str(folder), "--out", str(out), "--figures", str(figures),
                     "--workers", "1", *OPTIONS, "--quiet"]) == 0
    assert list(_lines(out)) == [str(folder / "a.json")]
    assert [p.suffix for p in figures.iterdir()] == [".png"]


def test_a_part_that_never_ends_reading_times_out_on_a_cluster(tmp_path, monkeypatch):
    """On a Dask cluster, a part whose file never ends (a pipe nobody writes to: the read
    blocks, no check of the planner's runs) is recorded as timed out after its
    part_timeout and the grace, and the other parts of its group are planned."""
    pytest.importorskip("distributed")
    from distributed import Client, LocalCluster

    monkeypatch.setattr(_batch_workers, "TIMEOUT_GRACE", 0.5)
    pipe = tmp_path / "never.json"
    os.mkfifo(pipe)
    good = tmp_path / "good.json"
    good.write_text(json.dumps({"vertices": _ring(np.random.default_rng(2)).tolist()}))
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        start = time.perf_counter()
        res = {r["path"]: r for r in batch.plan_many([str(pipe), str(good)], client=client,
                                                     fingers=2, mu=0.4, top=2,
                                                     part_timeout=NEVER_ENDING_LIMIT)}
        took = time.perf_counter() - start
    assert "timeout" in res[str(pipe)]["error"]
    assert res[str(good)]["error"] is None and res[str(good)]["grasps"]
    assert took < 600                   # a generous limit: only a hang fails it
    with open(pipe, "wb"):              # the blocked reader's open returns: it ends
        pass
