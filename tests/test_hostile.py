"""Hostile and broken inputs of every format (the readers' limits, :mod:`fcgrasp.io.limits`):
expansion bombs (an SVG's nested ``<use>``, a DXF's nested blocks), endless streams, files
past a limit, broken meshes and images.  Each is refused by every command that reads it
with exit 2 and one line on stderr, no traceback and no output, and (where a limit is
lowered to keep the suite fast) a file just inside the limit is still read.

The files are built by the test (a few kilobytes each): what they claim to hold is what
the readers must not expand.
"""

from __future__ import annotations

import json
import math
import struct
import zlib

import numpy as np
import pytest

from fcgrasp.apps.cli import main
from fcgrasp.io.parts import list_parts

SVG = '<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" ' \
      'width="100" height="100">{}</svg>'


def _use_bomb(levels=13, fan=4):
    defs = '<g id="a0"><rect width="1" height="1"/></g>'
    for k in range(1, levels + 1):
        defs += f'<g id="a{k}">' + "".join(f'<use xlink:href="#a{k - 1}" x="{j}"/>'
                                           for j in range(fan)) + "</g>"
    return SVG.format(f"<defs>{defs}</defs><use xlink:href=\"#a{levels}\"/>")


def _many_paths(n):
    return SVG.format("".join(f'<path d="M {i % 100} {i // 100} l 0.5 0 l 0 0.5 z"/>'
                              for i in range(n)))


def _dxf(build):
    import io

    import ezdxf

    doc = ezdxf.new()
    build(doc)
    stream = io.StringIO()
    doc.write(stream)
    return stream.getvalue().encode()


def _insert_bomb(doc, levels=8, fan=10):
    doc.blocks.new("B0").add_lwpolyline([(0, 0), (1, 0), (1, 1)], close=True)
    for k in range(1, levels + 1):
        blk = doc.blocks.new(f"B{k}")
        for j in range(fan):
            blk.add_blockref(f"B{k - 1}", (2 * j * fan ** (k - 1), 0))    # side by side
    doc.modelspace().add_blockref(f"B{levels}", (0, 0))


def _self_block(doc):
    blk = doc.blocks.new("LOOP")
    blk.add_lwpolyline([(0, 0), (1, 0), (1, 1)], close=True)
    blk.add_blockref("LOOP", (3, 0))
    doc.modelspace().add_blockref("LOOP", (0, 0))


def _png_header(w, h):
    """A PNG whose header claims ``w x h`` pixels (a decompression bomb's promise) and
    whose data is a few bytes."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + \
            struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    ihdr = struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + \
        chunk(b"IDAT", zlib.compress(b"\x00" * 64)) + chunk(b"IEND", b"")


def _ring(n, r=30.0):
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.c_[r * np.cos(a), 0.6 * r * np.sin(a)].round(6).tolist()


def _glb_huge_chunk():
    return struct.pack("<4sII", b"glTF", 2, 1000) + struct.pack("<I4s", 2 ** 31, b"JSON") + b"{}"


def _stl_claims(n):
    return b"\x00" * 80 + struct.pack("<I", n) + b"\x00" * 100


#: (file name, bytes, extra options, what the one line says)
HOSTILE = [
    ("use-bomb.svg", _use_bomb(), [], "--max-elements"),
    ("use-self.svg", SVG.format('<g id="a"><rect width="1" height="1"/><use href="#a"/></g>'),
     [], "refers to itself"),
    ("use-cycle.svg", SVG.format('<g id="a"><use href="#b"/></g><g id="b"><use href="#a"/>'
                                 '</g>'), [], "refers to itself"),
    ("deep.svg", SVG.format("<g>" * 3000 + '<rect width="1" height="1"/>' + "</g>" * 3000),
     [], "SVG"),
    ("many-paths.svg", _many_paths(600), ["--max-elements", "500"], "--max-elements"),
    ("entity-bomb.svg", '<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY a "aaaaaaaaaa">'
     + "".join(f'<!ENTITY a{k} "' + f"&a{k - 1};" * 10 + '">' if k else ""
               for k in range(1, 9)).replace("&a0;", "&a;")
     + ']><svg xmlns="http://www.w3.org/2000/svg"><text>&a8;</text></svg>', [], "SVG"),
    ("insert-bomb.dxf", _dxf(_insert_bomb), [], "--max-elements"),
    ("insert-self.dxf", _dxf(_self_block), [], "inserts itself"),
    ("many.json", json.dumps({"vertices": _ring(3000)}), ["--max-vertices", "2000"],
     "--max-vertices"),
    ("many-holes.json", json.dumps({"vertices": _ring(200, 60),
                                    "holes": [_ring(40, 0.5)] * 60}),
     ["--max-vertices", "1000"], "--max-vertices"),
    ("features.geojson", json.dumps({"type": "FeatureCollection", "features": [
        {"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [
            [[x, 0], [x + 1, 0], [x + 1, 1], [x, 1], [x, 0]]]}} for x in range(0, 60, 2)]}),
     ["--max-elements", "20"], "--max-elements"),
    ("big.json", json.dumps({"vertices": _ring(50)}) + " " * 5000, ["--max-bytes", "4K"],
     "--max-bytes"),
    ("bomb.png", _png_header(20000, 20000), [], "pixels"),
    ("bad-index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n", [], "not a readable mesh"),
    ("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n",
     [], ""),
    ("garbage.ply", b"ply\nformat binary_little_endian 1.0\nelement vertex 100000000\n"
     b"property float x\nend_header\n" + b"\x00" * 64, [], "not a readable mesh"),
    ("garbage.3mf", b"PK\x03\x04garbage", [], "not a readable mesh"),
    ("huge-chunk.glb", _glb_huge_chunk(), [], ""),
    ("claims.stl", _stl_claims(10 ** 9), [], ""),
    ("empty.stl", b"", [], ""),
    ("open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", [], ""),
    ("big.stl", _stl_claims(0), ["--max-bytes", "10"], "--max-bytes"),
]

def _blank_png(value, size, cut=None):
    import io

    from PIL import Image

    b = io.BytesIO()
    Image.fromarray(np.full((size, size), value, np.uint8)).save(b, "PNG")
    return b.getvalue()[:cut]


def _dxf_loop(points):
    return _dxf(lambda doc: doc.modelspace().add_lwpolyline(points, close=True))


#: broken files of every format: truncated, of another format, out of range, empty,
#: degenerate, or pointing outside themselves (external entities and buffers)
BROKEN = [
    ("huge-coords.svg", SVG.format('<path d="M 0 0 L 1e308 0 L 1e308 1e308 Z"/>'), [],
     "documented range"),
    ("nan.svg", SVG.format('<path d="M 0 0 L nan 0 L 10 10 Z"/>'), [], "no closed path"),
    ("html.svg", "<html><body>hello</body></html>", [], "not an SVG"),
    ("truncated.svg", '<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 10', [],
     "not a readable SVG"),
    ("xxe.svg", '<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY x SYSTEM "file:///etc/passwd">'
     ']><svg xmlns="http://www.w3.org/2000/svg"><text>&x;</text></svg>', [], "SVG"),
    ("external-use.svg", SVG.format('<use xlink:href="file:///etc/hosts#a"/>'
                                    '<use href="http://example.com/a.svg#b"/>'), [],
     "no closed path"),
    ("no-shapes.svg", SVG.format(""), [], "no closed path"),
    ("flat.svg", SVG.format('<path d="M 0 0 L 10 0 L 20 0 Z"/>'), [], "no closed path"),
    ("scale-zero.svg", SVG.format('<g transform="scale(0)"><rect width="10" height="10"/>'
                                  '</g>'), [], "no closed path"),
    ("garbage.dxf", bytes(range(256)) * 8, [], "not a readable DXF"),
    ("empty.dxf", _dxf(lambda doc: None), [], "no closed loop"),
    ("huge-coords.dxf", _dxf_loop([(0, 0), (1e300, 0), (1e300, 1e300)]), [],
     "documented range"),
    ("open-lines.dxf", _dxf(lambda doc: [doc.modelspace().add_line((0, 0), (10, 0)),
                                         doc.modelspace().add_line((20, 5), (30, 9))]), [],
     "no closed loop"),
    ("truncated.dxf", _dxf_loop([(0, 0), (10, 0), (10, 10)])[:9000], [], ""),
    ("nested.json", "[" * 100000 + "]" * 100000, [], "nested too deeply"),
    ("nan.json", '{"vertices": [[0, 0], [NaN, 0], [1, 1]]}', [], "non-finite"),
    ("inf.json", '{"vertices": [[0, 0], [1e999, 0], [1, 1]]}', [], "non-finite"),
    ("big-coords.json", '{"vertices": [[0, 0], [1e200, 0], [1e200, 1e200]]}', [],
     "documented range"),
    ("wrong-type.json", '{"vertices": "abc"}', [], "vertices"),
    ("two-vertices.json", '{"vertices": [[0, 0], [1, 0]]}', [], "at least 3"),
    ("bowtie.json", '{"vertices": [[0, 0], [10, 10], [10, 0], [0, 10]]}', [], "not simple"),
    ("same-point.json", '{"vertices": [[1, 1], [1, 1], [1, 1], [1, 1]]}', [], "at least 3"),
    ("bad.wkt", "POLYGON ((0 0, 1 1", [], "not valid WKT"),
    ("point.wkt", "POINT (1 2)", [], "no polygon"),
    ("big-coords.wkt", "POLYGON ((0 0, 1e200 0, 1e200 1e200, 0 0))", [], "documented range"),
    ("garbage.jpg", b"\xff\xd8\xff\xe0" + b"\x00" * 50, [], "not a readable image"),
    ("blank.png", _blank_png(255, 20), [], "no contrast"),
    ("truncated.png", _blank_png(0, 64, cut=60), [], "not a readable image"),
    ("ascii-bad.stl", "solid x\nfacet normal 0 0 0\nouter loop\nvertex a b c\nendloop\n"
     "endfacet\nendsolid\n", [], "not a readable mesh"),
    ("bad-counts.off", "OFF\n100000000 1 0\n0 0 0\n", [], "not a readable mesh"),
    ("external.gltf", json.dumps({"asset": {"version": "2.0"}, "buffers": [
        {"uri": "file:///etc/passwd", "byteLength": 100}]}), [], "not a readable mesh"),
    ("zero-area.stl", "solid z\n" + "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0"
     "\nvertex 2 0 0\nendloop\nendfacet\n" * 4 + "endsolid z\n", [], "not watertight"),
]
HOSTILE += BROKEN

#: meshes whose bodies can be listed (``fcgrasp parts``), though no plan can use them
LISTED = {"nan.obj", "open.obj", "zero-area.stl"}

#: how each file is read: every command that reads a part, and the grippers
COMMANDS = [
    ["parts", "{f}"],
    ["plan", "{f}", "--json", "{out}/plan.json"],
    ["plan", "{f}", "--fingers", "3", "--mu", "0.5", "--plot", "{out}/plan.png"],
    ["plan", "{f}", "--gripper", "jaw", "--stroke", "1,50", "--pad", "2"],
    ["check", "{f}", "--contacts", "{contacts}"],
]


def _argv(command, f, out, contacts):
    return [a.format(f=f, out=out, contacts=contacts) for a in command]


@pytest.fixture(scope="module")
def hostile(tmp_path_factory):
    folder = tmp_path_factory.mktemp("hostile")
    for name, data, _, _ in HOSTILE:
        (folder / name).write_bytes(data.encode() if isinstance(data, str) else data)
    contacts = folder / "contacts.txt"
    contacts.write_text(json.dumps({"contacts": [{"point": [0, 0], "mu": 0.5}]}))
    return folder


def test_there_are_at_least_150_hostile_runs():
    """This module's runs and the broken files and options of ``test_cli_fuzz``."""
    from .test_cli_fuzz import BAD_CONTACTS, BAD_OPTIONS, part_files

    assert len(HOSTILE) >= 50                     # files
    here = len(HOSTILE) * len(COMMANDS) + len(BAD_LIMITS)
    assert here >= 250
    assert here + len(part_files()) + len(BAD_OPTIONS) + len(BAD_CONTACTS) >= 150


@pytest.mark.parametrize("k", range(len(HOSTILE)))
def test_hostile_files_one_line_exit_2(hostile, tmp_path, capsys, k):
    name, _, extra, says = HOSTILE[k]
    f = hostile / name
    out = tmp_path / "out"
    out.mkdir()
    solid = name.rsplit(".", 1)[-1] in ("obj", "ply", "3mf", "glb", "gltf", "stl", "off")
    for command in COMMANDS:
        if solid and command[0] == "check":
            continue                     # contacts are planar
        if name in LISTED and command[0] == "parts":
            continue
        argv = _argv(command, f, out, hostile / "contacts.txt") + extra
        if solid and command[0] == "plan" and "--gripper" not in argv and \
                "--fingers" not in argv:
            argv += ["--soft"]
        code = main(argv)
        err = capsys.readouterr().err
        lines = err.strip().splitlines()
        assert code == 2, (argv, err)
        assert len(lines) == 1 and lines[0].startswith("fcgrasp: error:"), (argv, err)
        assert says in lines[0], (argv, lines[0])
        assert "Traceback" not in err
        assert list(out.iterdir()) == [], argv


def test_a_file_just_inside_a_limit_is_read(tmp_path):
    """The limits refuse what is past them only: the same drawings with the limit raised
    (or a copy fewer) are read."""
    svg = tmp_path / "many.svg"
    svg.write_text(_many_paths(600))
    assert len(list_parts(str(svg), max_elements=601)) == 600
    j = tmp_path / "ring.json"
    j.write_text(json.dumps({"vertices": _ring(3000)}))
    assert list_parts(str(j), max_vertices=3000)[0].polygon is not None
    bomb = tmp_path / "bomb.svg"
    bomb.write_text(_use_bomb(levels=3, fan=3))
    assert len(list_parts(str(bomb))) >= 1            # 27 copies: well inside
    dxf = tmp_path / "bomb.dxf"
    dxf.write_bytes(_dxf(lambda doc: _insert_bomb(doc, levels=2, fan=3)))
    assert len(list_parts(str(dxf))) == 9


def test_an_endless_stream_is_read_to_the_limit_only(capsys):
    code = main(["parts", "/dev/zero", "--max-bytes", "1M"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "--max-bytes" in err[0]


BAD_LIMITS = [["--max-bytes", "0"], ["--max-bytes", "lots"], ["--max-elements", "0"],
              ["--max-elements", "x"], ["--max-vertices", "-3"], ["--max-vertices", "1.5"]]


@pytest.mark.parametrize("opts", BAD_LIMITS)
def test_bad_limits_are_one_line(opts, capsys):
    code = main(["plan", "demo:blob", *opts])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1, err
    assert opts[0] in err[0] or opts[0][2:].replace("-", "_") in err[0], err[0]


def test_an_obj_split_by_normals_is_one_watertight_body(tmp_path):
    """Most exported OBJs repeat a vertex for each normal it carries: merged by position
    the box is closed, and planned."""
    import trimesh

    box = trimesh.creation.box((20, 10, 5))
    v = box.vertices[box.faces].reshape(-1, 3)
    n = np.repeat(box.face_normals, 3, axis=0)
    lines = [f"v {a} {b} {c}" for a, b, c in v] + [f"vn {a} {b} {c}" for a, b, c in n]
    lines += [f"f {3 * i + 1}//{3 * i + 1} {3 * i + 2}//{3 * i + 2} {3 * i + 3}//{3 * i + 3}"
              for i in range(len(box.faces))]
    f = tmp_path / "split.obj"
    f.write_text("\n".join(lines) + "\n")
    from fcgrasp.io.meshes import read_solid

    solid = read_solid(str(f))
    assert solid.mesh.is_watertight
    assert math.isclose(abs(solid.mesh.volume), 1000.0, rel_tol=1e-9)


def test_a_3mf_is_read(tmp_path):
    import trimesh

    f = tmp_path / "box.3mf"
    trimesh.creation.box((20, 10, 5)).export(f)
    from fcgrasp.io.meshes import read_solid

    assert math.isclose(abs(read_solid(str(f)).mesh.volume), 1000.0, rel_tol=1e-9)


def test_a_mesh_the_message_says_to_repair_is_repaired_by_the_option(tmp_path, capsys):
    """A mesh with one triangle turned over: refused with the option that fixes it named,
    planned with that option."""
    import trimesh

    box = trimesh.creation.box((20, 10, 5))
    faces = box.faces.copy()
    faces[0] = faces[0][::-1]
    lines = [f"v {a} {b} {c}" for a, b, c in box.vertices]
    lines += [f"f {i + 1} {j + 1} {k + 1}" for i, j, k in faces]
    f = tmp_path / "flipped.obj"
    f.write_text("\n".join(lines) + "\n")
    assert main(["plan", str(f), "--fingers", "2", "--soft", "--quiet"]) == 2
    assert "--repair" in capsys.readouterr().err
    out = tmp_path / "plan.json"
    assert main(["plan", str(f), "--fingers", "2", "--soft", "--repair", "--json", str(out),
                 "--quiet"]) == 0
    assert json.loads(out.read_text())["grasps"]
