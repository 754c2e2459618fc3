"""The CLI under malformed input: at least a hundred broken files of every
format and broken option sets.  Each must give exit code 2, exactly one line on stderr,
no traceback, no output file left behind, and the inputs unchanged."""

from __future__ import annotations

import hashlib
import json
import os
import sys

import numpy as np
import pytest

from fcgrasp.apps.cli import main

GOOD = [[0, 0], [42, -6], [70, 14], [64, 46], [30, 58], [-4, 36]]


def _svg(body):
    return f'<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">{body}</svg>'


def _dxf_bytes(kind):
    import io

    import ezdxf

    doc = ezdxf.new()
    msp = doc.modelspace()
    if kind == "open":
        msp.add_lwpolyline([(0, 0), (10, 0), (10, 10)], close=False)
    elif kind == "bowtie":
        msp.add_lwpolyline([(0, 0), (10, 10), (10, 0), (0, 10)], close=True)
    elif kind == "two-points":
        msp.add_lwpolyline([(0, 0), (10, 0)], close=True)
    stream = io.StringIO()
    doc.write(stream)
    return stream.getvalue().encode()


def _png_bytes(kind):
    import imageio.v3 as iio

    img = np.full((40, 40), 255, np.uint8)
    if kind == "1x1":
        img = np.zeros((1, 1), np.uint8)
    return iio.imwrite("<bytes>", img, extension=".png")


def part_files():
    """(name, bytes) of broken part files, every format."""
    ring = json.dumps(GOOD)
    j = {
        "truncated.json": ring[: len(ring) // 2],
        "garbage.json": "\x00\x01\x02binary",
        "empty.json": "",
        "list-of-numbers.json": "[1, 2, 3]",
        "string-vertices.json": json.dumps({"vertices": "square"}),
        "string-coords.json": json.dumps({"vertices": [["0", "0"], ["1", "0"], ["1", "1"]]}),
        "bool-coords.json": json.dumps({"vertices": [[True, 0], [1, 0], [1, 1]]}),
        "nan.json": '{"vertices": [[0, 0], [NaN, 0], [1, 1]]}',
        "inf.json": '{"vertices": [[0, 0], [Infinity, 0], [1, 1]]}',
        "huge.json": json.dumps({"vertices": [[0, 0], [1e300, 0], [1e300, 1e300]]}),
        "two-vertices.json": json.dumps({"vertices": [[0, 0], [1, 1]]}),
        "collinear.json": json.dumps({"vertices": [[0, 0], [1, 1], [2, 2]]}),
        "bowtie.json": json.dumps({"vertices": [[0, 0], [10, 10], [10, 0], [0, 10]]}),
        "hole-outside.json": json.dumps({"vertices": GOOD,
                                         "holes": [[[100, 100], [110, 100], [105, 110]]]}),
        "holes-overlap.json": json.dumps({"vertices": GOOD, "holes": [
            [[20, 10], [40, 10], [40, 30], [20, 30]], [[30, 20], [50, 20], [50, 40],
                                                       [30, 40]]]}),
        "holes-not-list.json": json.dumps({"vertices": GOOD, "holes": 5}),
        "unknown-key.json": json.dumps({"vertices": GOOD, "colour": "red"}),
        "ragged.json": json.dumps({"vertices": [[0, 0], [1], [1, 1, 1]]}),
        "nested-deep.json": json.dumps({"vertices": [[[0, 0]], [[1, 0]], [[1, 1]]]}),
        "null.json": "null",
        "fc-non-object.geojson": json.dumps({"type": "FeatureCollection", "features": [5]}),
        "fc-no-features.geojson": json.dumps({"type": "FeatureCollection"}),
        "fc-empty.geojson": json.dumps({"type": "FeatureCollection", "features": []}),
        "feature-no-geom.geojson": json.dumps({"type": "Feature", "geometry": None}),
        "linestring.geojson": json.dumps({"type": "LineString", "coordinates": GOOD}),
        "polygon-no-rings.geojson": json.dumps({"type": "Polygon", "coordinates": []}),
        "polygon-bad-ring.geojson": json.dumps({"type": "Polygon", "coordinates": [5]}),
        "multipolygon-empty.geojson": json.dumps({"type": "MultiPolygon", "coordinates": []}),
        "multipolygon-bad.geojson": json.dumps({"type": "MultiPolygon", "coordinates": 3}),
        "geom-string.geojson": json.dumps({"type": "Feature", "geometry": "x"}),
        "truncated.wkt": "POLYGON ((0 0, 10 0, 10",
        "point.wkt": "POINT (1 2)",
        "garbage.wkt": "hello world",
        "empty-poly.wkt": "POLYGON EMPTY",
        "bowtie.wkt": "POLYGON ((0 0, 10 10, 10 0, 0 10, 0 0))",
        "nan.wkt": "POLYGON ((0 0, nan 0, 1 1, 0 0))",
        "line.svg": _svg('<line x1="0" y1="0" x2="10" y2="10"/>'),
        "open-path.svg": _svg('<path d="M 0 0 L 10 0 L 10 10" fill="none" stroke="#000"/>'),
        "truncated.svg": _svg('<path d="M 0 0 L 10 0 Z"/>')[:40],
        "garbage.svg": "<svg>\x00\x01",
        "empty.svg": _svg(""),
        "flat.svg": _svg('<path d="M 0 0 L 10 0 L 20 0 Z"/>'),
        "garbage.dxf": "0\nSECTION\n2\nBOGUS\n",
        "truncated.dxf": _dxf_bytes("open")[:200],
        "empty.dxf": _dxf_bytes("none"),
        "open.dxf": _dxf_bytes("open"),
        "bowtie.dxf": _dxf_bytes("bowtie"),
        "two-points.dxf": _dxf_bytes("two-points"),
        "empty.png": _png_bytes("blank"),
        "one-pixel.png": _png_bytes("1x1"),
        "zero-bytes.png": b"",
        "truncated.png": _png_bytes("blank")[:30],
        "garbage.png": b"\x89PNG\r\n\x1a\nnot really",
        "noext": "something that is no format",
        "binary-noext": bytes(range(256)),
    }
    return {k: (v.encode() if isinstance(v, str) else v) for k, v in j.items()}


BAD_OPTIONS = [
    ["--mu", "-1"], ["--mu", "nan"], ["--mu", "inf"], ["--mu", "abc"], ["--margin", "90"],
    ["--margin", "-1"], ["--margin", "nan"], ["--top", "0"], ["--top", "1.5"],
    ["--fingers", "5"], ["--fingers", "two"], ["--workspace", "1,2"],
    ["--workspace", "0,0,-1"], ["--workspace", "a,b,c"], ["--workspace", "0,0,nan"],
    ["--finger-radius", "-1"], ["--finger-radius", "nan"], ["--flatten", "0"],
    ["--flatten", "-1"], ["--flatten", "nan"], ["--flatten", "inf"], ["--flatten", "1"],
    ["--plot", "OUT/fig.txt"], ["--plot", "OUT/fig"], ["--rank-by", "beauty"],
    ["--units", "furlong"], ["--id", "x"], ["--bogus"], ["--json", "OUT/"],
    ["--workspace", "1000,1000,1"],
    # reading options: wrong for the format, out of range, unknown
    ["--part", "7"], ["--part", "-1"], ["--layer", "CUT"], ["--gap", "0.1"],
    ["--pixel-size", "0.1"], ["--threshold", "0.5"], ["--units", "px"],
    ["--file-units", "furlong"], ["--simplify", "0"], ["--simplify", "1e9"],
    ["--max-memory", "lots"], ["--max-memory", "0"], ["--max-memory", "1k"],
    ["--json", "-", "--plot", "-"],
]

BAD_CONTACTS = {
    "no-contacts.json": {"contacts": []},
    "not-list.json": {"contacts": 5},
    "gravity-list.json": {"contacts": [{"point": [21, -3], "mu": 0.5}], "gravity": [0, -1]},
    "gravity-true.json": {"contacts": [{"point": [21, -3], "mu": 0.5}], "gravity": True},
    "gravity-typo.json": {"contacts": [{"point": [21, -3], "mu": 0.5}],
                          "gravity": {"directon": [0, -1]}},
    "edge-true.json": {"contacts": [{"point": [21, -3], "mu": 0.5, "edge": True}]},
    "edge-out.json": {"contacts": [{"point": [21, -3], "mu": 0.5, "edge": 99}]},
    "point-string.json": {"contacts": [{"point": "here", "mu": 0.5}]},
    "point-short.json": {"contacts": [{"point": [1], "mu": 0.5}]},
    "off-edge.json": {"contacts": [{"point": [30, 20], "mu": 0.5}]},
    "mu-negative.json": {"contacts": [{"point": [21, -3], "mu": -1}]},
    "mu-string.json": {"contacts": [{"point": [21, -3], "mu": "high"}]},
    "type-bad.json": {"contacts": [{"point": [21, -3], "type": "magnetic"}]},
    "soft-no-vertex.json": {"contacts": [{"type": "soft", "mu": 0.3}]},
    "soft-vertex-bad.json": {"contacts": [{"type": "soft", "vertex": 77, "mu": 0.3}]},
    "unknown-key.json": {"contacts": [{"point": [21, -3], "mu": 0.5, "force": 3}]},
    "top-unknown.json": {"contacts": [{"point": [21, -3], "mu": 0.5}], "units": "mm"},
    "normal-zero.json": {"contacts": [{"point": [21, -3], "normal": [0, 0]}]},
    "contact-not-object.json": {"contacts": [5]},
}


def _digest(folder):
    return {p: hashlib.sha256((folder / p).read_bytes()).hexdigest()
            for p in sorted(os.listdir(folder))}


def _cases(tmp_path):
    inp = tmp_path / "in"
    inp.mkdir()
    good = inp / "good.json"
    good.write_text(json.dumps({"vertices": GOOD}))
    cases = []
    for name, data in part_files().items():
        (inp / name).write_bytes(data)
        cases.append(["plan", inp / name, "--json", "OUT/plan.json", "--plot", "OUT/plan.png"])
    for opts in BAD_OPTIONS:
        cases.append(["plan", good, "--json", "OUT/plan.json", *opts])
    for name, data in BAD_CONTACTS.items():
        c = inp / f"contacts-{name}"
        c.write_text(json.dumps(data))
        cases.append(["check", good, "--contacts", c, "--json", "OUT/check.json"])
    cases += [["plan", inp / "missing.json"], ["plan", inp], ["check", good],
              ["plan", "demo:nothing"], ["plan", good, "--json", good],
              ["check", good, "--contacts", inp / "contacts-not-list.json", "--json",
               inp / "contacts-not-list.json"], ["frobnicate"],
              ["plan", "demo:blob", "--flatten", "0.5"]]
    return inp, cases


def test_cli_fuzz_malformed_inputs(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    inp, cases = _cases(tmp_path)
    assert len(cases) >= 100
    before = _digest(inp)
    for args in cases:
        out = tmp_path / "OUT"
        out.mkdir(exist_ok=True)
        argv = [str(a) for a in args]
        try:
            code = main(argv)
        except SystemExit as exc:        # argparse usage errors
            code = exc.code
        _, err = capsys.readouterr()
        if os.environ.get("FCGRASP_FUZZ_SHOW"):
            print(" ".join(argv[:2]), "->", err.strip(), file=sys.__stderr__)
        assert code == 2, (argv, code, err)
        lines = err.strip().splitlines()
        assert len(lines) == 1, (argv, err)
        assert "Traceback" not in err and "internal error" not in err, (argv, err)
        left = sorted(os.listdir(out))
        assert left == [], (argv, left)
        assert sorted(os.listdir(tmp_path)) == ["OUT", "in"], argv
        assert _digest(inp) == before, argv


@pytest.mark.parametrize("args", [["plan", "demo:blob", "--mu", "-1"],
                                  ["plan", "/nonexistent/part.svg"]])
def test_cli_errors_as_a_process(args):
    import subprocess
    import sys

    r = subprocess.run([sys.executable, "-m", "fcgrasp", *args], capture_output=True,
                       text=True, timeout=600)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1
    assert "Traceback" not in r.stderr
