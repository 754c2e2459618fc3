"""The explorer's server (``fcgrasp serve``), through its HTTP interface: the plans are
those of ``fcgrasp plan``, the verdicts those of ``fcgrasp check``, slow plans report
progress and can be cancelled, and no request, however malformed, stops the server."""

from __future__ import annotations

import json
import re
import time

import numpy as np
import pytest

pytest.importorskip("starlette")
pytest.importorskip("httpx2")

from starlette.testclient import TestClient  # noqa: E402

from fcgrasp import Grasp, Polygon  # noqa: E402
from fcgrasp.apps._explorer_data import plan_request  # noqa: E402
from fcgrasp.apps.cli import main  # noqa: E402
from fcgrasp.apps.serve import create_app  # noqa: E402
from fcgrasp.core.contacts import FrictionlessPoint, FrictionPoint  # noqa: E402
from fcgrasp.errors import RequestError  # noqa: E402
from fcgrasp.io.parts import load_part  # noqa: E402
from fcgrasp.io.schema import validate  # noqa: E402

from .test_batch import _ring, make_parts  # noqa: E402

BLOB = load_part("demo:blob").polygon.vertices.tolist()


def page_token(client):
    """The session token the explorer writes into a page it serves."""
    html = client.get("/").text
    return re.search(r'name="fcgrasp-token" content="([^"]+)"', html).group(1)


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(max_upload=64 * 1024), base_url="http://127.0.0.1:8000") as c:
        c.headers["X-Fcgrasp-Token"] = page_token(c)
        yield c


def _plan(client, part, options, hang=600.0):
    """Plan through the API, polling until the job ends (``hang`` seconds only stop a
    hung job: no test depends on how busy the machine is)."""
    r = client.post("/api/plan", json={"part": part, "options": options})
    assert r.status_code == 200, r.text
    ans = r.json()
    deadline = time.monotonic() + hang
    while ans["state"] == "running" and time.monotonic() < deadline:
        time.sleep(0.05)
        ans = client.get(f"/api/jobs/{ans['job']}").json()
    return ans


def _cli_report(tmp_path, vertices, argv):
    path = tmp_path / "part.json"
    path.write_text(json.dumps({"vertices": vertices}))
    out = tmp_path / "plan.json"
    code = main(["plan", str(path), "--no-clean", "--json", str(out), "--quiet", *argv])
    assert code == 0
    return json.loads(out.read_text())


CASES = [
    {"gripper": "2", "mu": 0.3},
    {"gripper": "2", "mu": 0.5, "along_boundary": False, "rank_by": "epsilon", "top": 4},
    {"gripper": "3", "mu": 0.4, "along_boundary": False, "top": 3},
    {"gripper": "3g", "along_boundary": False, "top": 3},
    {"gripper": "4", "top": 5, "margin": 1.0, "along_boundary": False},
    {"gripper": "jaw", "mu": 0.5, "stroke": [5, 60], "pad": 6, "top": 2},
    {"gripper": "jaw", "mu": 0.5, "stroke": [5, 60], "pad": 6, "top": 1, "certify": True},
    {"gripper": "2", "mu": 0.3, "top": 4, "distinct": 0.5},
]


@pytest.mark.parametrize("options", CASES, ids=lambda o: o["gripper"])
@pytest.mark.parametrize("both", [False, pytest.param(True, marks=pytest.mark.slow)])
def test_plans_are_those_of_fcgrasp_plan(client, tmp_path, options, both):
    """The blob and a random part (one of them by default, alternately)."""
    rng = np.random.default_rng(len(json.dumps(options)))
    parts = (BLOB, _ring(rng, 7).tolist())
    for vertices in parts if both else parts[CASES.index(options) % 2:][:1]:
        ans = _plan(client, {"outer": vertices, "units": "mm"}, options)
        assert ans["state"] == "done", ans
        validate(ans["report"])
        cli = _cli_report(tmp_path, vertices, ans["argv"])
        assert ans["report"]["grasps"] == cli["grasps"]
        assert ans["report"]["parameters"] == cli["parameters"]
        assert ans["report"]["reason"] == cli["reason"]
        assert len(ans["overlays"]) == len(ans["report"]["grasps"])


def test_the_page_options_become_the_cli_options(client):
    ans = _plan(client, {"outer": BLOB}, {"gripper": "2", "mu": 0.7, "top": 2,
                                          "along_boundary": False, "margin": 2})
    assert ans["argv"] == ["--fingers", "2", "--mu", "0.7", "--top", "2", "--single-edge",
                           "--margin", "2.0"]
    params = ans["report"]["parameters"]
    assert (params["mu"], params["top"], params["margin_deg"], params["along_boundary"]) == \
        (0.7, 2, 2.0, False)
    assert len(ans["report"]["grasps"]) <= 2


def test_two_finger_overlay_is_the_restricted_edges_of_the_plan(client):
    ans = _plan(client, {"outer": BLOB}, {"gripper": "2", "mu": 0.3, "along_boundary": False})
    poly = Polygon(BLOB)
    for g, ov in zip(ans["report"]["grasps"], ans["overlays"], strict=True):
        assert ov["kind"] == "e'" and ov["segments"]
        # every e'_i segment lies on one of the plan's two edges, and the regions lie in it
        for seg in ov["segments"]:
            d = [poly.distance_to_edges(p)[g["edges"]].min() for p in seg]
            assert max(d) < 1e-9 * poly.size
        covered = 0.0
        for reg in g["regions"]:
            for seg in ov["segments"]:
                a, b = np.asarray(seg)
                t = [(np.asarray(p) - a) @ (b - a) / ((b - a) @ (b - a)) for p in reg]
                off = (np.asarray(reg) - a) @ np.array([-(b - a)[1], (b - a)[0]])
                if all(-1e-9 <= x <= 1 + 1e-9 for x in t) and np.allclose(off, 0, atol=1e-6):
                    covered += 1
                    break
        assert covered == 2


def test_four_finger_overlay_has_the_parallelograms_and_the_sector(client):
    quad = load_part("demo:quad").polygon.vertices.tolist()
    ans = _plan(client, {"outer": quad}, {"gripper": "4", "along_boundary": False, "top": 2})
    ov = ans["overlays"][0]
    assert ov["kind"] == "Pi"
    assert len(ov["polygons"]) + len(ov["segments"]) == 2
    assert len(ov["cones"]) == 1 and 0 < ov["cones"][0]["half"] < np.pi / 2


def test_check_is_the_verdict_of_fcgrasp_check(client, rng):
    rect = [[0, 0], [80, 0], [80, 30], [0, 30]]
    poly = Polygon(rect)
    for _ in range(40):
        k = int(rng.integers(2, 5))
        edges = rng.integers(0, 4, k)
        t = rng.random(k)
        pts = poly.starts[edges] + t[:, None] * (poly.ends[edges] - poly.starts[edges])
        mu = float(rng.choice([0.0, 0.2, 0.6]))
        kind = "friction" if mu else "frictionless"
        contacts = [{"point": p.tolist(), "edge": int(e), "type": kind, "mu": mu}
                    for p, e in zip(pts, edges, strict=True)]
        r = client.post("/api/check", json={"part": {"outer": rect}, "contacts": contacts})
        assert r.status_code == 200, r.text
        ans = r.json()
        rep = Grasp([FrictionPoint(p, poly.normals[e], mu) if mu else
                     FrictionlessPoint(p, poly.normals[e])
                     for p, e in zip(pts, edges, strict=True)]).explain()
        assert ans["force_closure"] == rep.force_closure
        assert ans["failed"] == rep.failed
        if not rep.force_closure:
            assert np.allclose(ans["escape_twist"], rep.escape_twist)
            assert ans["escape"] == rep.escape_description


def test_gravity_check(client):
    tri = [[0, 0], [60, 0], [22, 48]]
    contacts = [{"point": [30, 0], "type": "frictionless"},
                {"point": [11, 24], "type": "frictionless"}]
    ans = client.post("/api/check", json={"part": {"outer": tri}, "contacts": contacts,
                                          "gravity": {"direction": [0, -1]}}).json()
    assert ans["contacts"][-1]["type"] == "gravity"


def test_a_slow_plan_reports_progress_and_can_be_cancelled(client):
    # seconds of planning (12 s here; cancelled below), running whatever the machine
    part = {"outer": _star(1000).tolist()}
    # the ranked list (distinct=0): three fingers' search reports each batch solved
    r1 = client.post("/api/plan", json={"part": part, "options": {"gripper": "3", "mu": 0.3,
                                                                  "distinct": 0}})
    ans = r1.json()
    assert ans["state"] == "running"
    seen = []
    for _ in range(1200):           # a hung plan only: it reports within a second here
        time.sleep(0.05)
        ans = client.get(f"/api/jobs/{ans['job']}").json()
        seen.append(ans["progress"])
        if ans["progress"][1] > 0:
            break
    assert seen[-1][1] > 0, "no progress reported"
    cancelled = client.delete(f"/api/jobs/{ans['job']}").json()
    assert cancelled["state"] == "cancelled"
    for _ in range(12000):          # a hung process only: it is killed at once
        time.sleep(0.05)
        ans = client.get(f"/api/jobs/{ans['job']}").json()
        if ans["seconds"] is not None:
            break
    assert ans["state"] == "cancelled" and ans["seconds"] is not None
    assert "report" not in ans


def test_a_long_poll_answers_when_the_plan_ends(client):
    """``GET /api/jobs/ID?wait=S`` (the page's poll) waits while the plan runs, at most
    ``S`` seconds, and answers as soon as it ends (done, or cancelled); a bad ``wait``
    is a bad request naming it."""
    # seconds of planning (12 s here; cancelled below): it runs on through the wait
    part = {"outer": _star(1000).tolist()}
    slow = client.post("/api/plan", json={"part": part, "options": {
        "gripper": "3", "mu": 0.3, "distinct": 0}}).json()
    assert slow["state"] == "running"
    t0 = time.monotonic()
    ans = client.get(f"/api/jobs/{slow['job']}?wait=0.2").json()
    assert ans["state"] == "running" and time.monotonic() - t0 >= 0.2
    client.delete(f"/api/jobs/{slow['job']}")
    for _ in range(600):            # a hung job only: each poll ends when it does
        ans = client.get(f"/api/jobs/{slow['job']}?wait=1").json()
        if ans["seconds"] is not None:
            break
    assert ans["state"] == "cancelled" and ans["seconds"] is not None
    quick = client.post("/api/plan", json={"part": {"outer": _star(12).tolist()},
                                           "options": {"gripper": "2", "mu": 0.5}}).json()
    for _ in range(600):
        if quick["state"] != "running":
            break
        quick = client.get(f"/api/jobs/{quick['job']}?wait=1").json()
    assert quick["state"] == "done" and quick["report"]["grasps"]
    again = client.get(f"/api/jobs/{quick['job']}?wait=1").json()
    assert again["state"] == "done"
    for bad in ("x", "-1", "2", "nan", ""):
        r = client.get(f"/api/jobs/{quick['job']}?wait={bad}")
        assert r.status_code == 400, (bad, r.text)
        assert r.json()["field"] == "wait" and "wait must be" in r.json()["error"]


def test_uploads_in_every_format(client, tmp_path):
    names = make_parts(tmp_path / "parts")
    for name in names:
        body = (tmp_path / "parts" / name).read_bytes()
        r = client.post(f"/api/part?name={name}", content=body)
        broken = name in {"broken.json", "open.svg", "crossing.json", "blank.png"}
        if broken:
            assert r.status_code == 400, (name, r.text)
            assert r.json()["field"] == "file" and name in r.json()["error"]
            continue
        assert r.status_code == 200, (name, r.text)
        expect = load_part(tmp_path / "parts" / name)
        got = r.json()
        assert np.allclose(got["outer"], expect.polygon.vertices)
        assert got["units"] == expect.units and got["edges"] == expect.polygon.n_edges


def test_oversized_uploads_are_refused(client):
    big = b"x" * (64 * 1024 + 1)
    r = client.post("/api/part?name=big.json", content=big)
    assert r.status_code == 413 and "too large" in r.json()["error"]

    def chunks():                     # no Content-Length: the stream is cut off
        for _ in range(80):
            yield b"y" * 1024
    r = client.post("/api/part?name=big.json", content=chunks())
    assert r.status_code == 413


@pytest.mark.parametrize(("body", "field", "words"), [
    ({"part": {"outer": [[0, 0], [10, 10], [10, 0], [0, 10]]}}, "part", "intersect"),
    ({"part": {"outer": [[0, 0], [1, 0]]}}, "part", "at least 3"),
    ({"part": {"outer": [[0, 0], [1, 0], [0, "a"]]}}, "part", "part.outer[2]"),
    ({"part": {"outer": BLOB}, "options": {"gripper": "5"}}, "gripper", "gripper"),
    ({"part": {"outer": BLOB}, "options": {"mu": -1}}, "mu", "mu"),
    ({"part": {"outer": BLOB}, "options": {"top": 0}}, "top", "top"),
    ({"part": {"outer": BLOB}, "options": {"rank_by": "x"}}, "rank_by", "--rank-by"),
    ({"part": {"outer": BLOB}, "options": {"gripper": "jaw", "pad": 4}}, "stroke", "stroke"),
    ({"part": {"outer": BLOB}, "options": {"colour": 1}}, "options", "colour"),
    ({"part": {"outer": BLOB}, "options": {"gripper": "jaw", "stroke": [5, 60], "pad": 6,
                                           "certify": "yes"}}, "certify", "certify"),
    ({"part": {"outer": BLOB}, "options": {"gripper": "2", "mu": 0}}, None, "friction"),
])
def test_bad_plan_requests_say_what_is_wrong(client, body, field, words):
    r = client.post("/api/plan", json=body)
    if field is None:                 # accepted, and the answer says why there is no grasp
        ans = r.json()
        while ans["state"] == "running":
            ans = client.get(f"/api/jobs/{ans['job']}").json()
        assert ans["report"]["grasps"] == [] and words in ans["report"]["reason"]
        return
    assert r.status_code == 400, r.text
    assert r.json()["field"] == field and words in r.json()["error"]


def test_junk_never_stops_the_server(client):
    rng = np.random.default_rng(3)
    junk = [b"", b"{", b"[]", b"null", b'"x"', b"\xff\xfe", b'{"part": 3}',
            b'{"part": {"outer": {}}}', b'{"contacts": 1, "part": {"outer": [[0,0],[1,0],[0,1]]}}',
            b'{"part": {"outer": [[0,0],[1,0],[0,1]]}, "contacts": [{"point": [5, 5]}]}',
            b'{"part": {"outer": [[0,0],[1,0],[0,1]], "units": "furlong"}}',
            b'{"part": {"outer": [[0,0],[1e308,0],[0,1e308]]}}']
    junk += [bytes(rng.integers(0, 256, int(rng.integers(1, 200)), dtype=np.uint8))
             for _ in range(12)]
    for body in junk:
        for url in ("/api/plan", "/api/check", "/api/part?name=x.svg", "/api/part"):
            r = client.post(url, content=body)
            assert r.status_code in (400, 413), (url, body, r.status_code, r.text)
            assert r.json()["error"]
    assert client.get("/api/jobs/nope").status_code == 404
    assert client.get("/api/demo/nope").status_code == 404
    assert client.get("/api/state").status_code == 200


def test_page_and_static_files_are_served(client):
    page = client.get("/")
    assert page.status_code == 200 and "fcgrasp explorer" in page.text
    for name in ("app.js", "style.css"):
        assert client.get(f"/static/{name}").status_code == 200
    st = client.get("/api/state").json()
    assert st["part"]["outer"] == BLOB and "blob" in st["demos"]
    assert client.get("/api/demo/rectangle").json()["edges"] == 4


def _star(n, seed=5):
    rng = np.random.default_rng(seed)
    ang = np.sort(rng.uniform(0, 2 * np.pi, n))
    r = 50 * (1 + 0.3 * rng.random(n))
    return np.c_[r * np.cos(ang), r * np.sin(ang)]


def test_jobs_kill_any_planner_and_replace_the_process():
    from fcgrasp.apps.serve import Jobs, RequestError

    jobs = Jobs(workers=1)
    try:
        big = Polygon(_star(2000))
        # the two-finger stretch search reports no progress: only killing stops it
        job = jobs.start(big, "mm", {"gripper": "2", "mu": 0.3})
        time.sleep(0.3)
        assert job.state == "running"
        with pytest.raises(RequestError) as exc:          # one worker: the next must wait
            jobs.start(big, "mm", {"gripper": "2", "mu": 0.3})
        assert exc.value.status == 429
        pid = job.process.pid
        jobs.cancel(job.id)
        assert job.done.wait(10) and job.state == "cancelled" and job.result is None
        assert not job.process.is_alive()
        # the next plan runs in a fresh process and is right
        small = jobs.start(Polygon(BLOB), "mm", {"gripper": "2", "mu": 0.3})
        assert small.done.wait(60) and small.state == "done"
        assert small.process.pid != pid
        # a planning process that dies is an error, and the pool goes on
        dying = jobs.start(big, "mm", {"gripper": "2", "mu": 0.3})
        time.sleep(0.2)
        dying.process.kill()
        assert dying.done.wait(10) and dying.state == "error"
        assert "stopped" in dying.error
        again = jobs.start(Polygon(BLOB), "mm", {"gripper": "4", "along_boundary": False})
        assert again.done.wait(60) and again.state == "done"
    finally:
        jobs.close()


def test_a_new_plan_replaces_the_stale_one(client):
    big = {"outer": _star(2000).tolist()}
    first = client.post("/api/plan", json={"part": big, "options": {"gripper": "2"}}).json()
    assert first["state"] == "running"
    second = client.post("/api/plan", json={"part": {"outer": BLOB}, "options": {},
                                            "replaces": first["job"]}).json()
    assert client.get(f"/api/jobs/{first['job']}").json()["state"] == "cancelled"
    while second["state"] == "running":
        time.sleep(0.05)
        second = client.get(f"/api/jobs/{second['job']}").json()
    assert second["state"] == "done" and second["report"]["grasps"]


def test_fcgrasp_serve_command_errors_are_one_line(capsys):
    import subprocess
    import sys

    from .test_cli import run_here

    proc = subprocess.Popen([sys.executable, "-m", "fcgrasp", "serve", "--port", "0"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        line = proc.stdout.readline()
        assert line.startswith("fcgrasp explorer: http://127.0.0.1:")
        port = line.split(":")[3].split("/")[0]
        taken = subprocess.run([sys.executable, "-m", "fcgrasp", "serve", "--port", port],
                               capture_output=True, text=True, timeout=600)
        assert taken.returncode == 2
        assert taken.stderr.count("\n") == 1 and "cannot listen" in taken.stderr
    finally:
        proc.terminate()
        proc.wait(10)
    # refused before a server starts: the command's entry point in this process
    for argv, words in ((["--port", "70000"], "--port"), (["nope.svg"], "nope.svg")):
        r = run_here(capsys, "serve", *argv)
        assert r.returncode == 2 and r.stderr.count("\n") == 1 and words in r.stderr
        assert "Traceback" not in r.stderr


def test_an_idle_planning_process_that_died_is_replaced():
    from fcgrasp.apps.serve import Jobs

    jobs = Jobs(workers=2)
    try:
        jobs.warm(1)
        idle = jobs.start(Polygon(BLOB), "mm", {"gripper": "2"})
        assert idle.done.wait(60) and idle.state == "done"
        idle.process.kill()                   # dies while idle, back in the pool
        idle.process.join(5)
        job = jobs.start(Polygon(BLOB), "mm", {"gripper": "2"})
        assert job.done.wait(60) and job.state == "done", job.error
        assert job.process.pid != idle.process.pid
    finally:
        jobs.close()


@pytest.mark.parametrize(("body", "field", "words"), [
    ({"part": {"outer": BLOB}, "options": {"gripper": "jaw", "stroke": [50, 10], "pad": 8}},
     "gripper", "min_opening <= max_opening"),
    ({"part": {"outer": BLOB}, "options": {"margin": 1e9}}, "margin", "--margin"),
    ({"part": {"outer": BLOB}, "replaces": {"x": 1}}, "replaces", "replaces"),
])
def test_a_plan_request_is_checked_whole_before_a_job_starts(client, body, field, words):
    """These got 200 and a job id, and failed only when polled."""
    r = client.post("/api/plan", json=body)
    assert r.status_code == 400, r.text
    assert r.json()["field"] == field and words in r.json()["error"]


def test_deeply_nested_json_is_a_bad_request_not_an_internal_error(client):
    r = client.post("/api/plan", content=b"[" * 100_000 + b"]" * 100_000,
                    headers={"content-type": "application/json"})
    assert r.status_code == 400 and "nested too deeply" in r.json()["error"]


def test_parts_and_options_are_checked_off_the_event_loop(client, monkeypatch):
    """A 60,000-vertex outline was checked on the event loop (54 s, every other request
    waiting): the checks run in a worker thread, where no event loop runs."""
    import asyncio

    import fcgrasp.apps.serve as serve

    where = []
    real_page_part, real_plan_request = serve.page_part, serve.plan_request

    def on_loop() -> bool:
        try:
            asyncio.get_running_loop()
        except RuntimeError:
            return False
        return True

    def page_part(data):
        where.append(("part", on_loop()))
        return real_page_part(data)

    def plan_request(options, *args):
        where.append(("options", on_loop()))
        return real_plan_request(options, *args)

    monkeypatch.setattr(serve, "page_part", page_part)
    monkeypatch.setattr(serve, "plan_request", plan_request)
    ans = _plan(client, {"outer": BLOB}, {"gripper": "2", "mu": 0.3, "top": 1})
    assert ans["report"]["grasps"]
    assert ("part", False) in where and ("options", False) in where
    assert not any(loop for _, loop in where), where


# ----------------------------------------------------------------------------- solids


def _solid_cli(tmp_path, source, argv):
    out = tmp_path / "solid.json"
    assert main(["plan", source, "--json", str(out), "--quiet", *argv]) == 0
    return json.loads(out.read_text())


@pytest.mark.parametrize("options, argv", [
    ({"gripper": "2", "mu": 0.3, "top": 3}, ["--fingers", "2", "--soft", "--mu", "0.3",
                                             "--top", "3"]),
    pytest.param({"gripper": "3", "mu": 0.5, "top": 2},
                 ["--fingers", "3", "--mu", "0.5", "--top", "2"], marks=pytest.mark.slow),
    ({"gripper": "jaw", "mu": 0.5, "stroke": [5, 50], "pad": 8, "top": 3},
     ["--gripper", "jaw", "--mu", "0.5", "--stroke", "5,50", "--pad", "8", "--top", "3"]),
    ({"gripper": "2", "mu": 0.3, "top": 3, "distinct": 0.5},
     ["--fingers", "2", "--soft", "--mu", "0.3", "--top", "3", "--distinct", "0.5"])])
def test_solids_plan_as_fcgrasp_plan_does(client, tmp_path, options, argv):
    """A built-in solid by name, and the same solid sent as the page's triangles (as an
    uploaded mesh is), plan exactly as ``fcgrasp plan demo:NAME`` on the command line."""
    name = "prism" if options["gripper"] == "3" else "box" if options["gripper"] == "2" \
        else "angle"
    part = client.get(f"/api/demo/{name}").json()
    assert part["solid"] and part["source"] == f"demo:{name}" and part["units"] == "mm"
    assert len(part["faces"]) == part["triangles"] and len(part["vertices"]) >= 6
    want = _solid_cli(tmp_path, f"demo:{name}", argv)["grasps"]
    assert want
    for sent in (part, dict(part, source=f"{name}.stl")):     # by name; by its triangles
        ans = _plan(client, sent, options)
        assert ans["state"] == "done", ans
        validate(ans["report"])
        got = ans["report"]["grasps"]
        assert [g["facets"] for g in got] == [g["facets"] for g in want]
        for g, w in zip(got, want, strict=True):
            for a, b in zip(g["regions"], w["regions"], strict=True):
                assert np.allclose(a, b, atol=1e-9 * part["size"])
        assert ans["overlays"] == [None] * len(got)


def test_a_mesh_upload_is_a_solid(client, tmp_path):
    trimesh = pytest.importorskip("trimesh")
    body = trimesh.creation.icosphere(subdivisions=1, radius=10.0).export(file_type="stl")
    r = client.post("/api/part?name=ball.stl", content=body)
    assert r.status_code == 200, r.text
    part = r.json()
    assert part["solid"] and part["source"] == "ball.stl" and part["triangles"] == 80
    ans = _plan(client, part, {"gripper": "2", "mu": 0.5, "top": 2})
    assert ans["state"] == "done" and len(ans["report"]["grasps"]) == 2
    assert ans["argv"][:2] == ["--fingers", "2"]
    assert ans["report"]["parameters"]["contact_type"] == "soft"


@pytest.mark.parametrize("part, options, field, words", [
    ({"solid": True, "source": "demo:box"}, {"gripper": "4"}, "gripper", "on a solid"),
    ({"solid": True, "source": "demo:teapot"}, {"gripper": "2"}, "part", "built-in solid"),
    ({"solid": True, "source": "x.stl", "vertices": [[0, 0, 0]], "faces": [[0, 1, 2]]},
     {"gripper": "2"}, "part", "faces"),
    ({"solid": True, "source": "x.stl", "units": "furlong"}, {"gripper": "2"}, "part",
     "units")])
def test_bad_solids_say_what_is_wrong(client, part, options, field, words):
    r = client.post("/api/plan", json={"part": part, "options": options})
    assert r.status_code == 400, r.text
    assert r.json()["field"] == field and words in r.json()["error"], r.json()


def test_state_lists_the_solids(client):
    st = client.get("/api/state").json()
    assert st["solids"] == ["box", "cylinder", "prism", "angle", "mug"]
    assert st["solid_grippers"] == ["2", "3", "jaw"]


@pytest.mark.parametrize(("name", "options"),
                         [pytest.param("triangle", {"gripper": "3", "mu": 0.5, "top": 2,
                                                    "bound": True}, marks=pytest.mark.slow),
                          ("quad", {"gripper": "4", "top": 2, "bound": True})],
                         ids=["3", "4"])
def test_the_optimality_bound_is_that_of_fcgrasp_plan(client, tmp_path, name, options):
    """``bound`` (three fingers with friction, four frictionless): the page's plan
    carries the upper bound ``fcgrasp plan --bound`` proves, and says so in its argv
    (three fingers under ``-m slow``: the browser's test compares their line with the
    CLI's by default)."""
    vertices = load_part(f"demo:{name}").polygon.vertices.tolist()
    ans = _plan(client, {"outer": vertices, "units": "mm"}, options)
    assert ans["state"] == "done", ans
    assert "--bound" in ans["argv"]
    cli = _cli_report(tmp_path, vertices, ans["argv"])
    got, want = ans["report"]["optimality"], cli["optimality"]
    # the page's planning processes run the compiled knapsack loop, a short command
    # numpy's: the plans agree to rounding, and so does the bound (its count of boxes
    # may differ where a box's test meets the best plan's length within rounding)
    assert got["upper_bound"] is not None
    assert got["upper_bound"] == pytest.approx(want["upper_bound"], rel=1e-9)
    assert got["gap"] == pytest.approx(want["gap"], rel=1e-9, abs=1e-12)
    best = max(g["min_region_length"] for g in ans["report"]["grasps"])
    assert got["upper_bound"] >= best
    # another gripper leaves the page's bound unused, as it leaves the jaw's options
    two = _plan(client, {"outer": vertices}, {"gripper": "2", "mu": 0.5, "top": 1,
                                              "bound": True})
    assert "optimality" not in two["report"] and "--bound" not in two["argv"]


def test_a_bound_without_friction_is_refused_by_name(client):
    r = client.post("/api/plan", json={"part": {"outer": BLOB},
                                       "options": {"gripper": "3", "mu": 0, "bound": True}})
    assert r.status_code == 400, r.text
    assert r.json()["field"] == "bound" and "--bound" in r.json()["error"]


def test_a_part_sent_again_is_not_checked_again(monkeypatch):
    """The page sends its part with every plan: the same JSON gives the polygon checked
    before (a 2,000-edge outline takes 25 ms to check); a part that differs in a number
    or only in its types (``true`` for ``1``) is checked anew, and a bad one is still
    refused."""
    from fcgrasp.apps import _explorer_data as data
    from fcgrasp.errors import RequestError

    checked = []
    real = data._polygon_of
    monkeypatch.setattr(data, "_polygon_of", lambda d: checked.append(1) or real(d))
    monkeypatch.setattr(data, "_CHECKED", type(data._CHECKED)())
    square = {"outer": [[0, 0], [1, 0], [1, 1], [0, 1]], "holes": [], "units": "mm"}
    first = data.polygon_of(square)
    again = data.polygon_of(json.loads(json.dumps(square)))
    assert again is first and len(checked) == 1
    moved = json.loads(json.dumps(square))
    moved["outer"][2] = [1, 2]
    assert data.polygon_of(moved)[0].vertices.max() == 2 and len(checked) == 2
    typed = json.loads(json.dumps(square))
    typed["outer"][1] = [True, 0]
    with pytest.raises(RequestError):
        data.polygon_of(typed)
    with pytest.raises(RequestError):
        data.polygon_of(typed)          # refused again, never kept
    for k in range(data._CHECKED_SIZE + 2):
        data.polygon_of({**square, "outer": [[0, 0], [1 + k, 0], [1, 1], [0, 1]]})
    assert len(data._CHECKED) == data._CHECKED_SIZE


# ----------------------------------------------------------------------------- security

def _bare(client):
    """Headers without the page's session token (the client's own is overridden)."""
    return {"X-Fcgrasp-Token": ""}


@pytest.mark.parametrize("host", ["evil.example", "evil.example:8000", "10.0.0.1:8000",
                                  "127.0.0.1.evil.example"])
def test_a_dns_rebinding_host_is_refused(client, host):
    """A page whose name resolves to the loopback still names its own host: refused on
    every path, the page (with its token), the files and the API."""
    for path in ("/", "/static/app.js", "/api/state"):
        r = client.get(path, headers={"Host": host})
        assert r.status_code == 403, (path, r.status_code)
        assert r.json()["field"] == "origin" and "fcgrasp-token" not in r.text


@pytest.mark.parametrize("origin", ["http://evil.example", "http://127.0.0.1:9999",
                                    "https://127.0.0.1:8000", "null"])
def test_a_request_from_another_origin_is_refused(client, origin):
    r = client.post("/api/plan", json={"part": {"outer": BLOB}, "options": {"gripper": "2"}},
                    headers={"Origin": origin})
    assert r.status_code == 403 and r.json()["field"] == "origin"
    ok = client.get("/api/state", headers={"Origin": "http://127.0.0.1:8000"})
    assert ok.status_code == 200


def test_the_api_needs_the_pages_session_token(client):
    """A text/plain POST (what a cross-origin form or no-cors fetch can send) without the
    token starts nothing; a made-up token neither."""
    bare = _bare(client)
    body = json.dumps({"part": {"outer": BLOB}, "options": {"gripper": "2"}})
    for headers in (bare, {**bare, "X-Fcgrasp-Token": "guess"}):
        r = client.post("/api/plan", content=body,
                        headers={**headers, "Content-Type": "text/plain"})
        assert r.status_code == 403 and r.json()["field"] == "token"
        for method, path in (("GET", "/api/state"), ("GET", "/api/demo/blob"),
                             ("POST", "/api/part?name=x.json"), ("POST", "/api/check"),
                             ("GET", "/api/jobs/x"), ("DELETE", "/api/jobs/x")):
            r = client.request(method, path, headers=headers, content=b"{}")
            assert r.status_code == 403, (method, path)
    assert client.get("/").status_code == 200      # the page itself needs no token


def test_jobs_are_unguessable_and_belong_to_their_session(client):
    other = {"X-Fcgrasp-Token": page_token(client)}
    ids = []
    for _ in range(2):
        r = client.post("/api/plan", json={"part": {"outer": BLOB},
                                           "options": {"gripper": "2", "top": 1}})
        ids.append(r.json()["job"])
    assert ids[0] != ids[1] and all(len(i) >= 20 and not i.isdigit() for i in ids)
    for job in ids:
        assert client.get(f"/api/jobs/{job}", headers=other).status_code == 404
        assert client.delete(f"/api/jobs/{job}", headers=other).status_code == 404
        assert client.get(f"/api/jobs/{job}?wait=1").status_code == 200


def test_an_upload_is_read_in_a_process_killed_at_its_time(client, monkeypatch):
    """The reading process is killed past READ_SECONDS (here none at all): the answer is
    one error naming the file, and the server plans on."""
    from fcgrasp.apps import _serve_jobs

    monkeypatch.setattr(_serve_jobs, "READ_SECONDS", 0.0)
    r = client.post("/api/part?name=slow.json",
                    content=json.dumps({"vertices": BLOB}).encode())
    assert r.status_code == 413 and "slow.json" in r.json()["error"]
    monkeypatch.undo()
    ok = client.post("/api/part?name=fine.json", content=json.dumps({"vertices": BLOB}))
    assert ok.status_code == 200 and ok.json()["name"] == "fine.json"


def test_an_expanding_upload_is_refused_by_the_readers_limits(client):
    from .test_hostile import _use_bomb

    r = client.post("/api/part?name=bomb.svg", content=_use_bomb().encode())
    assert r.status_code == 400 and "--max-elements" in r.json()["error"]


def test_an_upload_lists_its_parts_and_takes_the_one_asked_in_its_units(client):
    """A drawing of two parts: the largest by default, every part listed as fcgrasp
    parts lists them; ``part`` takes another, ``units`` converts (a bracket DXF's small
    rectangle was the only way in)."""
    import io

    import ezdxf

    doc = ezdxf.new()
    doc.header["$INSUNITS"] = 4                       # millimetres
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (4, 0), (4, 4), (0, 4)], close=True)
    msp.add_lwpolyline([(10, 0), (40, 0), (40, 20), (10, 20)], close=True)
    text = io.StringIO()
    doc.write(text)
    body = text.getvalue().encode()
    r = client.post("/api/part?name=two.dxf", content=body)
    assert r.status_code == 200, r.text
    got = r.json()
    assert len(got["parts"]) == 2 and all(p["usable"] for p in got["parts"])
    big = max(got["parts"], key=lambda p: p["area"])
    small = min(got["parts"], key=lambda p: p["area"])
    assert got["part"] == big["index"] and got["units"] == "mm"
    r = client.post(f"/api/part?name=two.dxf&part={small['index']}&units=in", content=body)
    other = r.json()
    assert other["part"] == small["index"] and other["units"] == "in"
    side = np.ptp(np.array(other["outer"]), axis=0)
    assert np.allclose(side, [4 / 25.4, 4 / 25.4], rtol=1e-9)
    bad = client.post("/api/part?name=two.dxf&units=furlong", content=body)
    assert bad.status_code == 400 and bad.json()["field"] == "units"


def _smooth(n=1000):
    """An ellipse with a third harmonic, ``n`` edges (120 x 70 mm): at mu 1.0 its ten
    distinct alternatives take the complete search many seconds."""
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 1 + 0.08 * np.cos(3 * a)
    return np.c_[60 * r * np.cos(a), 35 * r * np.sin(a)].round(9).tolist()


def test_the_page_time_limit_is_fcgrasp_plans(client, tmp_path):
    """The page's time limit is ``--time-limit``: a search it stops says so in the
    report (``complete`` false, the gap)."""
    options = {"gripper": "2", "mu": 1.0, "top": 10, "distinct": 0.5, "time_limit": 0.01}
    ans = _plan(client, {"outer": _smooth(), "units": "mm"}, options)
    assert ans["state"] == "done", ans
    argv = ans["argv"]
    assert argv[argv.index("--time-limit") + 1] == "0.01"
    report = ans["report"]
    assert report["complete"] is False
    assert report["gap"]["stopped_by"] == "time_limit"
    assert report["gap"]["found"] == len(report["grasps"]) < 10
    assert report["parameters"]["top"] == 10
    with pytest.raises(RequestError, match="time"):
        plan_request({"gripper": "2", "time_limit": -1})


@pytest.mark.parametrize("options, parallel", [
    ({"gripper": "jaw", "mu": 0.5, "stroke": [5, 60], "pad": 6, "top": 2}, True),
    ({"gripper": "2", "mu": 0.4, "top": 2}, True),
    ({"gripper": "3", "mu": 0.4, "along_boundary": False, "top": 2}, False)])
def test_a_parallel_grippers_plans_come_with_their_moveit_grasps(client, options, parallel):
    """The page's "MoveIt grasps" export: a jaw's or two fingers' plans answered with
    what ``fcgrasp plan --moveit`` writes for the same report; other grippers' with
    none."""
    from fcgrasp.io.moveit import moveit_grasps

    ans = _plan(client, {"outer": BLOB}, options)
    assert ans["state"] == "done" and ans["report"]["grasps"]
    if parallel:
        assert ans["moveit"] == moveit_grasps(ans["report"])
    else:
        assert ans["moveit"] is None
