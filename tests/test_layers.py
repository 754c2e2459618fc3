"""The package layout drawn in the README: each module imports only from its own layer or
the layers above it (arrows go down); the CLI and the figures are leaves."""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "fcgrasp"
LAYERS = [
    ["tolerances", "_checks", "_geom", "_json", "units", "kernels"],
    ["screws", "convexes", "sectors"],
    ["contacts", "grasp", "closure"],
    ["polygon", "graspsets"],
    ["outline"],
    ["regions", "_regiongeom", "hand", "stretches", "frictionless_stretches"],
    ["quality", "ranking", "plans"],
    ["jaw"],
    ["pipeline"],
    ["three_fingers"],
    ["planning"],
    ["_drawing"],
    ["_read_svg", "_read_dxf", "_read_image"],
    ["parts", "report", "_atomic"],
    ["cli", "plotting", "batch", "__main__", "serve"],
]
LEVEL = {m: k for k, layer in enumerate(LAYERS) for m in layer}


def _imports(path):
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            if node.module:
                yield node.module.split(".")[0]
            else:
                yield from (a.name for a in node.names)


def test_every_module_has_a_layer():
    mods = {p.stem for p in SRC.glob("*.py")} - {"__init__"}
    assert mods == set(LEVEL), mods ^ set(LEVEL)


def test_imports_only_go_down():
    bad = []
    for path in SRC.glob("*.py"):
        if path.stem == "__init__":
            continue
        for dep in _imports(path):
            if dep in LEVEL and LEVEL[dep] > LEVEL[path.stem]:
                bad.append(f"{path.stem} -> {dep}")
    assert not bad, bad
