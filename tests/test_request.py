"""The typed plan request, the gripper interface and registry, and the defects the request
and the app layer now own (each a regression test named after what broke)."""

from __future__ import annotations

import os
import pickle
import signal
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.apps.cli import build_parser, main, plan_options
from fcgrasp.errors import RequestError
from fcgrasp.grippers import REGISTRY, FourFingers, ThreeFingers, TwoFingers, register
from fcgrasp.grippers.base import Gripper, SearchOptions
from fcgrasp.planning import PlanRequest, plan_document

REQUESTS = [
    PlanRequest(part="demo:blob"),
    PlanRequest(part="demo:quad", fingers=3, mu=0.5, top=3, margin=1.0),
    PlanRequest(part="demo:triangle", fingers=3, gravity=(0.0, -1.0), single_edge=True),
    PlanRequest(part="demo:quad", fingers=4, rank_by="epsilon", max_memory=2 ** 30),
    PlanRequest(part="demo:blob", fingers=2, mu=0.4, workspace=(0.0, 0.0, 80.0),
                finger_radius=1.5),
    PlanRequest(part="demo:rectangle", gripper="jaw", stroke=(10.0, 50.0), pad=8.0, mu=0.5,
                certify=False, top=2),
    PlanRequest(part="demo:cam", units="in", simplify=0.01, no_clean=True, y_down=True),
]


@pytest.mark.parametrize("request_", REQUESTS, ids=lambda r: " ".join(r.to_argv()) or "-")
def test_a_request_pickles_and_is_what_its_command_line_parses_to(request_):
    assert pickle.loads(pickle.dumps(request_)) == request_
    args = build_parser().parse_args(["plan", request_.part, *request_.to_argv()])
    assert PlanRequest(part=args.part, **plan_options(args)) == request_


def test_the_gripper_of_a_request():
    kinds = [type(r.gripper_object()).__name__ for r in REQUESTS[:6]]
    assert kinds == ["TwoFingers", "ThreeFingers", "ThreeFrictionless", "FourFingers",
                     "TwoFingers", "ParallelJaw"]
    assert all(isinstance(r.gripper_object(), Gripper) for r in REQUESTS)


@pytest.mark.parametrize(("kw", "error", "field", "words"), [
    ({"top": "3"}, TypeError, None, "top must be a whole number"),
    ({"mu": True}, TypeError, None, "mu must be a number"),
    ({"stroke": "10,50", "gripper": "jaw", "pad": 8}, TypeError, None, "stroke must be"),
    ({"margin": 1e9}, RequestError, "margin", "--margin is an angle"),
    ({"margin": float("nan")}, RequestError, "margin", "finite"),
    ({"top": 0}, RequestError, "top", "--top must be at least 1"),
    ({"gripper": "jaw", "stroke": (50, 10), "pad": 8}, RequestError, "gripper",
     "min_opening <= max_opening"),
    ({"gripper": "jaw", "pad": 8}, RequestError, "stroke", "--gripper jaw needs"),
    ({"gripper": "jaw", "stroke": (5, 50), "pad": 8, "fingers": 3}, RequestError,
     "fingers", "an option of point fingers"),
    ({"stroke": (5, 50)}, RequestError, "stroke", "an option of --gripper jaw"),
    ({"fingers": 4, "mu": 0.3}, RequestError, "mu", "would not be used"),
    ({"fingers": 2, "gravity": (0, -1)}, RequestError, "gravity", "three frictionless"),
    ({"gripper": "magnet"}, RequestError, "gripper", "gripper must be one of"),
    ({"json": "out.png", "plot": "out.png"}, RequestError, None, "same file"),
    ({"plot": "figure.gif"}, RequestError, "plot", "--plot must end in"),
])
def test_a_bad_request_says_which_option(kw, error, field, words):
    with pytest.raises(error) as exc:
        PlanRequest(part="demo:blob", **kw)
    assert words in str(exc.value)
    if field is not None:
        assert exc.value.field == field


def test_an_output_that_is_the_input_is_refused_through_links(tmp_path):
    part = tmp_path / "p.json"
    part.write_text('{"vertices": [[0,0],[40,0],[40,20],[0,20]]}')
    (tmp_path / "link.json").symlink_to(part)
    os.link(part, tmp_path / "hard.json")
    for out in (part, tmp_path / "link.json", tmp_path / "hard.json"):
        with pytest.raises(RequestError, match="input of this run"):
            PlanRequest(part=str(part), json=str(out))


def test_batch_never_overwrites_an_input_part(tmp_path, capsys):
    """``fcgrasp batch d --out d/p.json`` overwrote the part with its results (exit 0)."""
    d = tmp_path / "d"
    d.mkdir()
    part = d / "p.json"
    text = '{"vertices": [[0, 0], [40, 0], [40, 20], [0, 20]]}\n'
    part.write_text(text)
    (d / "link.json").symlink_to(part)
    for out in (part, d / "link.json"):
        assert main(["batch", str(d), "--out", str(out), "--workers", "1", "--quiet"]) == 2
        assert "input of this run" in capsys.readouterr().err
        assert part.read_text() == text
    with pytest.raises(ValueError, match="input of this run"):
        fc.plan_many  # noqa: B018 - the public name loads
        from fcgrasp.apps.batch import run_batch
        run_batch([str(part)], str(part), workers=1)
    assert part.read_text() == text


# ----------------------------------------------------------------------------- a toy gripper


@dataclass(frozen=True)
class Poke:
    edge: int
    depth: float

    def to_dict(self):
        return {"edge": self.edge, "depth": self.depth}


@dataclass(frozen=True)
class Poker:
    """A toy gripper: one frictionless finger pushing at the middle of the longest edge
    (not force closure; it only shows what a new gripper needs)."""

    depth: float = 1.0
    name = "poker"

    def check_part(self, polygon, options):
        return None

    def plan(self, polygon, options):
        k = int(np.argmax(polygon.lengths))
        return [Poke(k, self.depth)][: options.top]

    def parameters(self, options):
        return {"gripper": "poker", "depth": self.depth, "top": options.top}

    def no_grasp_reason(self, margin):
        return "nothing to poke"

    @property
    def title(self):
        return "poker"


def test_a_new_gripper_is_one_class_and_one_registry_line(monkeypatch):
    monkeypatch.setitem(REGISTRY, "poker", lambda options: Poker())
    assert isinstance(Poker(), Gripper)
    part = fc.Polygon([[0, 0], [40, 0], [40, 20], [0, 20]])
    assert fc.plan(part, gripper=Poker(2.0)) == [Poke(0, 2.0)]
    doc = plan_document(PlanRequest(part="demo:rectangle", gripper="poker", top=3))
    assert doc.report["parameters"] == {"gripper": "poker", "depth": 1.0, "top": 3}
    assert doc.title == "demo:rectangle: poker"
    assert doc.report["grasps"] == [{"edge": 0, "depth": 1.0, "rank": 1}]
    with pytest.raises(ValueError, match="would not be used"):
        fc.plan(part, gripper=Poker(), mu=0.3)


def test_register_checks_its_arguments():
    with pytest.raises(ValueError, match="name"):
        register("", lambda options: Poker())
    with pytest.raises(TypeError, match="builder"):
        register("x", "not callable")


def test_the_short_form_is_the_gripper_objects():
    part = fc.Polygon([[0, 0], [40, 0], [40, 20], [0, 20]])
    pairs = [({"fingers": 2, "mu": 0.3}, TwoFingers(mu=0.3)),
             ({"fingers": 3, "mu": 0.5}, ThreeFingers(mu=0.5)),
             ({"fingers": 4, "along_boundary": False}, FourFingers(along_boundary=False))]
    for short, gripper in pairs:
        a = fc.plan(part, top=3, **short)
        b = fc.plan(part, gripper=gripper, top=3)
        assert [(p.edges, p.lengths.tolist()) for p in a] == \
            [(p.edges, p.lengths.tolist()) for p in b]
        assert a, short


def test_search_options_check_their_arguments():
    with pytest.raises(ValueError, match="rank_by"):
        SearchOptions(rank_by="biggest")
    with pytest.raises(ValueError, match="margin"):
        SearchOptions(margin=95)
    with pytest.raises(TypeError, match="progress"):
        SearchOptions(progress=3)


# ----------------------------------------------------------------------------- readers


def test_deeply_nested_contacts_json_is_one_error_line(tmp_path, capsys):
    deep = tmp_path / "deep.json"
    deep.write_text("[" * 100_000 + "]" * 100_000)
    assert main(["check", "demo:blob", "--contacts", str(deep)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"fcgrasp: error: {deep}: JSON nested too deeply"]


@pytest.mark.parametrize(("name", "text"), [
    ("nan.wkt", "POLYGON ((0 0, 10 0, 10 NaN, 0 10, 0 0))"),
    ("nan.geojson", '{"type": "Polygon", "coordinates": '
                    '[[[0, 0], [10, 0], [10, NaN], [0, 10], [0, 0]]]}'),
])
def test_nan_in_wkt_or_geojson_is_one_line_on_stderr(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    r = subprocess.run([sys.executable, "-m", "fcgrasp", "plan", str(path)],
                       capture_output=True, text=True, timeout=600,
                       env=dict(os.environ, PYTHONWARNINGS="default"))
    assert r.returncode == 2
    assert r.stderr.strip().splitlines() == [
        f"fcgrasp: error: {path}: vertices has a non-finite coordinate at vertex 2: "
        f"[10.0, nan]"]


# ----------------------------------------------------------------------------- batch workers


def _children(pid: int) -> list[int]:
    out = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                stat = (d / "stat").read_text()
            except OSError:
                continue
            if int(stat.rsplit(")", 1)[1].split()[1]) == pid:
                out.append(int(d.name))
    return out


def _ignores_sigint(pid: int) -> bool:
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    for line in status.splitlines():
        if line.startswith("SigIgn:"):
            return bool(int(line.split()[1], 16) & (1 << (signal.SIGINT - 1)))
    return False


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


#: Stops only a hang, never reached.
HANG = 600


def _batch_with_workers(tmp_path, *extra, **popen):
    """A running ``fcgrasp batch`` of demo:cam copies with two local workers, and their
    pids once both are seen.  Forty copies (about a second each): the batch is still
    running when a test stops it."""
    folder = tmp_path / "parts"
    folder.mkdir()
    for k in range(40):
        (folder / f"cam{k}.json").write_text(
            '{"vertices": ' + str(fc.io.parts.demo_part("cam").vertices.tolist()) + "}")
    proc = subprocess.Popen([sys.executable, "-m", "fcgrasp", "batch", str(folder), "--out",
                             str(tmp_path / "r.jsonl"), "--workers", "2", "--fingers", "3",
                             "--mu", "0.5", *extra], **popen)
    workers: list[int] = []
    deadline = time.monotonic() + HANG
    while len(workers) < 2 and proc.poll() is None and time.monotonic() < deadline:
        workers = [c for c in _children(proc.pid) if _alive(c)]
        time.sleep(0.05)
    assert len(workers) == 2, "the batch ended before its workers were seen"
    return proc, workers


def _gone(workers):
    deadline = time.monotonic() + HANG
    while any(_alive(w) for w in workers) and time.monotonic() < deadline:
        time.sleep(0.05)
    return not any(_alive(w) for w in workers)


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs Linux's /proc")
def test_workers_die_with_a_killed_batch(tmp_path):
    """kill -9 of a local-pool batch left its workers alive (reparented, minutes later)."""
    proc, workers = _batch_with_workers(tmp_path, "--quiet")
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    assert _gone(workers)


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs Linux's /proc")
def test_ctrl_c_in_a_batch_is_one_line_and_no_worker_traceback(tmp_path):
    """Ctrl-C (SIGINT to the terminal's process group) printed a worker's traceback.
    The batch starts with SIGINT's default disposition whatever the test runner's (a
    runner started in the background of a shell ignores SIGINT, and its children
    inherit that: the batch then planned every part and exited 0)."""
    proc, workers = _batch_with_workers(
        tmp_path, stderr=subprocess.PIPE, text=True, start_new_session=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    # Ctrl-C is the batch's to handle: its workers ignore SIGINT (bit 2 of SigIgn)
    deadline = time.monotonic() + HANG
    while not all(_ignores_sigint(w) for w in workers) and all(map(_alive, workers)) \
            and time.monotonic() < deadline:
        time.sleep(0.05)
    assert all(_ignores_sigint(w) for w in workers)
    time.sleep(0.5)                            # the workers are planning
    os.killpg(proc.pid, signal.SIGINT)
    err = proc.communicate(timeout=HANG)[1]
    assert proc.returncode == 130, err
    assert "Traceback" not in err and err.strip().splitlines()[-1] == "fcgrasp: interrupted"
    assert _gone(workers)
