"""The fcgrasp command: real files of every format, driven as a subprocess (or through
its entry point in the test process, where what is tested is the command's own code),
compared with the library; every failure case checks the exit code, the one-line message
and that no output file is left behind."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from fcgrasp import Polygon, plan
from fcgrasp.apps.cli import main
from fcgrasp.io.parts import read_part
from fcgrasp.io.report import dumps, plan_report

OUTLINE = [[0.0, 0.0], [40.0, -6.0], [62.0, 18.0], [45.0, 44.0], [8.0, 38.0]]


def run(*args, timeout=600):
    env = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run([sys.executable, "-m", "fcgrasp", *map(str, args)],
                          capture_output=True, text=True, timeout=timeout, env=env)


def run_here(capsys, *args):
    """The command run in this test process, as :func:`run` reports it (the command's
    own code; its start as a process is :func:`run`'s, in this file's other tests)."""
    code = main([str(a) for a in args])
    cap = capsys.readouterr()
    return subprocess.CompletedProcess(args, code, cap.out, cap.err)


def library_grasps(poly, **kw):
    plans = plan(poly, **kw)
    return json.loads(dumps(plan_report(poly, plans, {}, "mm")))["grasps"]


# ------------------------------------------------------------------ writers of test files

def write_json(tmp):
    p = tmp / "part.json"
    p.write_text(json.dumps({"vertices": OUTLINE}))
    return p


def write_geojson(tmp):
    p = tmp / "part.geojson"
    ring = OUTLINE + [OUTLINE[0]]
    p.write_text(json.dumps({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon",
                                                           "coordinates": [ring]}}]}))
    return p


def write_wkt(tmp):
    p = tmp / "part.wkt"
    ring = OUTLINE + [OUTLINE[0]]
    p.write_text("POLYGON ((" + ", ".join(f"{x} {y}" for x, y in ring) + "))")
    return p


def write_svg(tmp):
    # drawn at half size, y down from the top of the 200 mm page, then put back by the
    # transform and the flip about the page's height
    pts = " ".join(f"{x / 2},{(200 - y) / 2}" for x, y in OUTLINE)
    p = tmp / "part.svg"
    p.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="200mm" height="200mm" '
                 'viewBox="0 0 200 200">'
                 '<path id="open" d="M 0 0 L 10 10" fill="none"/>'
                 f'<g transform="translate(0, 0) scale(2)"><polygon id="part" points="{pts}"/></g>'
                 '</svg>')
    return p


def write_dxf(tmp):
    import ezdxf

    doc = ezdxf.new()
    doc.units = 4                                 # millimetres ($INSUNITS)
    msp = doc.modelspace()
    # a slot with two semicircular ends: straight edges plus bulges (arcs)
    msp.add_lwpolyline([(0, 0, 0), (40, 0, 1), (40, 20, 0), (0, 20, 1)], format="xyb",
                       close=True)
    p = tmp / "slot.dxf"
    doc.saveas(p)
    return p


def write_png(tmp):
    from skimage import io

    img = np.full((120, 160), 255, dtype=np.uint8)
    yy, xx = np.mgrid[0:120, 0:160]
    img[(xx > 30) & (xx < 130) & (yy > 40) & (yy < 90)] = 0       # a dark rectangle
    p = tmp / "part.png"
    io.imsave(p, img, check_contrast=False)
    return p


WRITERS = {"json": write_json, "geojson": write_geojson, "wkt": write_wkt, "svg": write_svg}


@pytest.mark.parametrize("fmt", sorted(WRITERS))
def test_plan_command_matches_library(tmp_path, capsys, fmt):
    part = WRITERS[fmt](tmp_path)
    out = tmp_path / "plan.json"
    fig = tmp_path / "plan.png"
    # the figure drawn for one format (its reading is what differs between them), that
    # one as a process, the others in this one
    plot = ["--plot", fig] if fmt == "svg" else []
    args = ("plan", part, "--mu", "0.4", "--top", "3", "--json", out, *plot,
            *(["--id", "part"] if fmt == "svg" else []))
    r = run(*args) if fmt == "svg" else run_here(capsys, *args)
    assert r.returncode == 0, r.stderr
    assert "rank" in r.stdout and r.stderr == ""
    data = json.loads(out.read_text())
    assert data["format_version"] == 3 and data["units"] == "mm"
    poly = Polygon(OUTLINE)
    assert np.allclose(data["part"]["vertices"], poly.vertices, atol=1e-9)
    assert data["grasps"] == library_grasps(poly, fingers=2, mu=0.4, top=3)
    assert fig.stat().st_size > 1000 if plot else not fig.exists()


def test_svg_transform_applied_and_y_flipped(tmp_path):
    poly = read_part(write_svg(tmp_path), "part")
    assert np.allclose(poly.vertices, OUTLINE, atol=1e-9)


def test_dxf_with_bulges(tmp_path, capsys):
    part = write_dxf(tmp_path)
    poly = read_part(part)
    assert poly.n_edges > 20                      # the arcs were flattened
    # fine chords of ezdxf's Bezier arcs (within 3e-4 of the radius of the true arcs)
    assert 0.999 < poly.area / (40 * 20 + np.pi * 10 ** 2) < 1.001
    out = tmp_path / "dxf.json"
    r = run_here(capsys, "plan", part, "--top", "2", "--json", out)
    assert r.returncode == 0, r.stderr
    assert json.loads(out.read_text())["grasps"] == library_grasps(poly, fingers=2, mu=0.3,
                                                                   top=2)
    # four fingers on a curved outline: simplified to a few dozen edges first (in process)
    assert main(["plan", str(part), "--fingers", "4", "--top", "2", "--simplify", "0.05",
                 "--json", str(out), "--quiet"]) == 0
    small = read_part(part, simplify=0.05)
    assert small.n_edges < 50
    assert json.loads(out.read_text())["grasps"] == library_grasps(small, fingers=4, top=2)


def test_png_silhouette(tmp_path, capsys):
    part = write_png(tmp_path)
    poly = read_part(part)
    lo, hi = poly.vertices.min(axis=0), poly.vertices.max(axis=0)
    assert np.allclose(hi - lo, [98, 48], atol=2)
    out = tmp_path / "png.json"
    r = run_here(capsys, "plan", part, "--mu", "0.3", "--json", out, "--quiet")
    assert r.returncode == 0 and r.stdout == ""
    assert json.loads(out.read_text())["grasps"] == library_grasps(poly, fingers=2, mu=0.3,
                                                                   top=10)


def test_demo_command_writes_json_and_figures(tmp_path, capsys):
    # in process: the command's own code (the process's start and its one-line errors
    # are this file's other tests)
    assert main(["demo", "--out", str(tmp_path / "demo")]) == 0, capsys.readouterr().err
    files = sorted(p.name for p in (tmp_path / "demo").iterdir())
    assert "demo.json" in files and sum(f.endswith(".png") for f in files) >= 3
    summary = json.loads((tmp_path / "demo" / "demo.json").read_text())
    assert all(p.get("best_min_region", p.get("best_measure", p.get("best_radius"))) > 0
               for p in summary["plans"])
    solid = [p for p in summary["plans"] if p.get("contact_type") == "soft"]
    assert solid and json.loads((tmp_path / "demo" / solid[0]["json"]).read_text())[
        "grasps"][0]["radius"] == solid[0]["best_radius"]
    jaw = [p for p in summary["plans"] if p.get("gripper") == "parallel_jaw"]
    assert jaw and (tmp_path / "demo" / jaw[0]["figure"]).stat().st_size > 1000
    assert any(p.get("fingers") == 3 and p["mu"] > 0 for p in summary["plans"])


def test_check_command(tmp_path):
    good = tmp_path / "good.json"
    good.write_text(json.dumps({"contacts": [{"point": [0, 15], "mu": 0.3},
                                             {"point": [80, 16], "mu": 0.3}]}))
    r = run("check", "demo:rectangle", "--contacts", good, "--json", tmp_path / "c.json")
    assert r.returncode == 0 and r.stdout.startswith("force closure")
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"contacts": [{"point": [0, 15], "type": "frictionless"},
                                            {"point": [80, 15], "type": "frictionless"}]}))
    fig = tmp_path / "check.png"
    r = run("check", "demo:rectangle", "--contacts", bad, "--plot", fig)
    assert r.returncode == 1 and fig.stat().st_size > 1000     # not force closure: exit 1
    assert "force-direction closure fails" in r.stdout and "translation" in r.stdout
    assert "free" in r.stdout


def test_version_and_help():
    r = run("--version")
    assert r.returncode == 0 and r.stdout.startswith("fcgrasp ")
    for cmd in ("plan", "check", "demo"):
        r = run(cmd, "--help")
        assert r.returncode == 0 and "example" in r.stdout


def test_the_command_exits_with_mains_code_its_heap_frozen(monkeypatch, capsys):
    """``fcgrasp`` and ``python -m fcgrasp`` run :func:`~fcgrasp.apps.cli.run`: the
    command's code as the exit status, the heap frozen once the command is done (so the
    interpreter's finalization skips its collections), not before."""
    import gc

    from fcgrasp.apps import cli

    calls = []
    monkeypatch.setattr(cli, "main", lambda: calls.append("main") or 3)
    monkeypatch.setattr(gc, "freeze", lambda: calls.append("freeze"))
    with pytest.raises(SystemExit) as exc:
        cli.run()
    assert exc.value.code == 3 and calls == ["main", "freeze"]
    meta = (Path(__file__).resolve().parents[1] / "pyproject.toml").read_text()
    assert 'fcgrasp = "fcgrasp.apps.cli:run"' in meta
    assert "run()" in (Path(cli.__file__).parents[1] / "__main__.py").read_text()


def test_output_is_deterministic(tmp_path):
    part = write_json(tmp_path)
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    assert run("plan", part, "--fingers", "4", "--json", a).returncode == 0
    assert run("plan", part, "--fingers", "4", "--json", b).returncode == 0
    assert a.read_bytes() == b.read_bytes()


def test_no_grasp_is_a_valid_answer(tmp_path):
    out = tmp_path / "none.json"
    r = run("plan", "demo:rectangle", "--mu", "0", "--json", out)
    assert r.returncode == 0
    data = json.loads(out.read_text())
    assert data["grasps"] == [] and "friction" in data["reason"]


# ------------------------------------------------------------------ failures

def _bad_files(tmp):
    (tmp / "selfx.json").write_text(json.dumps({"vertices": [[0, 0], [1, 1], [1, 0], [0, 1]]}))
    (tmp / "nan.json").write_text('{"vertices": [[0, 0], [1, 0], ["x", 1]]}')
    (tmp / "open.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg">'
                                  '<path d="M 0 0 L 10 10 L 20 0" fill="none"/></svg>')
    (tmp / "part.xyz").write_text("hello")
    (tmp / "broken.json").write_text('{"vertices": [[0, 0], [1, 0]')
    (tmp / "hole.json").write_text(json.dumps({"vertices": [[0, 0], [1, 0], [1, 1], [0, 1]],
                                               "holes": [[[2, 2], [3, 2], [3, 3]]]}))
    return tmp


FAILURES = [
    (["plan", "{tmp}/missing.json"], "no such file"),
    (["plan", "{tmp}"], "folder"),
    (["plan", "{tmp}/part.xyz"], "unknown part format"),
    (["plan", "{tmp}/open.svg"], "no closed path"),
    (["plan", "{tmp}/selfx.json"], "edges 0 and 2 intersect"),
    (["plan", "{tmp}/nan.json"], "numbers"),
    (["plan", "{tmp}/broken.json"], "not valid JSON"),
    (["plan", "{tmp}/hole.json"], "holes[0] is not inside"),
    (["plan", "demo:rectangle", "--mu", "-0.5"], "--mu"),
    (["plan", "demo:rectangle", "--workspace", "500,500,10"], "cannot touch the part"),
    (["plan", "demo:rectangle", "--workspace", "1,2"], "--workspace"),
    (["plan", "demo:nothing"], "unknown demo part"),
    (["plan", "demo:rectangle", "--fingers", "5"], "invalid choice"),
    (["plan", "demo:rectangle", "--plot", "{tmp}/x.gif"], "--plot"),
    (["check", "demo:rectangle", "--contacts", "{tmp}/missing.json"], "no such file"),
    (["plan", "demo:rectangle", "--plot", "{tmp}/no/such/dir/x.png"], "does not exist"),
    (["plan", "demo:rectangle", "--time-limit", "-2"], "--time-limit"),
]


#: the failures run as a process (the rest call the command's main in process: the same
#: code, without a Python start-up each)
AS_PROCESS = {0, 7, 12}


@pytest.mark.parametrize("k", range(len(FAILURES)))
def test_failures_one_line_exit_2_no_output(tmp_path, capsys, k):
    args, message = FAILURES[k]
    _bad_files(tmp_path)
    out = tmp_path / "out.json"
    fig = tmp_path / "out.png"
    argv = [a.format(tmp=tmp_path) for a in args]
    if argv[0] == "plan" and "--plot" not in argv:
        argv += ["--json", str(out), "--plot", str(fig)]
    r = run(*argv) if k in AS_PROCESS else run_here(capsys, *argv)
    assert r.returncode == 2, (r.stdout, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("fcgrasp: error:"), r.stderr
    assert message in lines[0], lines[0]
    assert "Traceback" not in r.stderr
    assert not out.exists() and not fig.exists()
    assert not any(p.name.startswith(".out") for p in tmp_path.iterdir())
    assert not (tmp_path / "no").exists()            # no output folder made


def test_failed_plot_leaves_no_partial_json(tmp_path, monkeypatch, capsys):
    """A failure after the JSON is produced (while plotting) removes nothing already
    complete, and leaves no temporary file."""
    import fcgrasp.plotting as plotting

    def boom(*a, **k):
        raise ValueError("plotting failed on purpose")

    monkeypatch.setattr(plotting, "plan_figure", boom)
    fig = tmp_path / "f.png"
    code = main(["plan", "demo:blob", "--plot", str(fig), "--quiet"])
    assert code == 2 and not fig.exists()
    assert [p for p in tmp_path.iterdir()] == []
    assert "plotting failed" in capsys.readouterr().err


# ------------------------------------------------------------------ fuzz

def test_fuzz_readers_never_traceback(tmp_path, capsys):
    rng = np.random.default_rng(0)
    for k in range(60):
        kind = k % 4
        path = tmp_path / f"f{k}{['.json', '.svg', '.wkt', ''][kind]}"
        if kind == 0:
            choices = [None, 1, "a", [], {}, {"vertices": None},
                       {"vertices": rng.normal(size=(int(rng.integers(0, 6)), 2)).tolist()},
                       {"vertices": [[1, 2], [3]]}, {"type": "Polygon", "coordinates": 5},
                       {"vertices": [[0, 0], [1, 0], [0, 1]], "holes": 7},
                       {"type": "Feature", "geometry": {"type": "Point", "coordinates": [0, 0]}},
                       {"vertices": [[0, 0], [1e308, 0], [0, 1e308]]}]
            obj = choices[int(rng.integers(len(choices)))]
            path.write_text(json.dumps(obj))
        else:
            path.write_bytes(rng.integers(0, 256, int(rng.integers(0, 400))).astype(np.uint8)
                             .tobytes())
        code = main(["plan", str(path), "--quiet"])
        err = capsys.readouterr().err
        assert code in (0, 2), err
        if code:
            assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_the_resistance_column_says_its_unit(capsys):
    """The resistance changed 25.4 times between --units mm and --units in, unlabelled:
    it is 1 / work, per unit of the part's length."""
    for units in ("mm", "in"):
        assert main(["plan", "demo:blob", "--units", units, "--top", "1"]) == 0
        header = capsys.readouterr().out.splitlines()[0]
        assert f"resistance (1/{units})" in header and f"regions ({units})" in header


def test_the_parts_command_lists_a_drawings_parts_and_notes(tmp_path, capsys):
    """``fcgrasp parts`` on a drawing of two outlines and a stray open line: the table
    (the default marked, each outline's edges, holes and size) and the JSON (every part,
    the default, the reader's note on what it left out) say the same."""
    import ezdxf

    doc = ezdxf.new()
    doc.header["$INSUNITS"] = 4                          # millimetres
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (40, 0), (40, 20), (0, 20)], close=True)
    msp.add_lwpolyline([(60, 0), (70, 0), (70, 10)], close=True)
    msp.add_line((100, 0), (120, 5))                     # open: left out, with a note
    path = tmp_path / "two.dxf"
    doc.saveas(path)
    out = tmp_path / "parts.json"
    assert main(["parts", str(path), "--json", str(out)]) == 0
    text = capsys.readouterr().out.splitlines()
    report = json.loads(out.read_text())
    assert report["default"] == 0 and len(report["parts"]) == 2
    assert [p["part"]["edges"] for p in report["parts"]] == [4, 3]
    assert report["notes"] and any("left out" in n for n in report["notes"])
    assert text[0].startswith(f"{path}: 2 parts (dxf")
    rows = [t for t in text[2:] if not t.startswith("note:")]
    assert rows[0].startswith("*") and rows[1].startswith(" ")
    assert "40 x 20" in rows[0] and "10 x 10" in rows[1]
    assert [t[len("note: "):] for t in text if t.startswith("note: ")] == report["notes"]


def test_fewer_plans_than_asked_say_why(tmp_path, capsys):
    """A complete search that gives fewer plans than ``--top`` says why on one more
    line: distinct alternatives, every other plan a copy of one given (each given plan
    lists its copies in ``similar``, and ``--distinct 0`` gives more); without them,
    no other plan holds (every plan of the rectangle's two fingers: the two pairs of
    facing sides).  A search that gives ``top`` plans prints no such line."""
    out = tmp_path / "plan.json"
    assert main(["plan", "demo:rectangle", "--fingers", "3", "--mu", "0.5", "--json",
                 str(out)]) == 0
    report = json.loads(out.read_text())
    text = capsys.readouterr()
    found = len(report["grasps"])
    assert report["complete"] and 0 < found < 10
    assert f"{found} of 10 plans: every other plan that holds is the same alternative" \
        in text.out
    assert any(g.get("similar") for g in report["grasps"])
    assert len(plan(read_part("demo:rectangle"), fingers=3, mu=0.5, distinct=0)) > found
    assert main(["plan", "demo:rectangle", "--mu", "0.5", "--distinct", "0"]) == 0
    every = plan(read_part("demo:rectangle"), mu=0.5, top=None, distinct=0)
    assert f"{len(every)} of 10 plans: the search found no other plan that holds" \
        in capsys.readouterr().out
    assert main(["plan", "demo:rectangle", "--fingers", "3", "--mu", "0.5", "--top",
                 "3"]) == 0
    assert "plans: " not in capsys.readouterr().out
