"""The package layout: subpackages in layers, each importing only from its own layer or the
layers below it (``core`` <- ``spatial`` <- ``model`` <- ``mechanics`` <- ``io`` <-
``pipeline`` <- ``grippers`` <- ``planning`` <- ``plotting`` <- ``apps``), no cycle between
modules, front ends that never import one another and see only public names.  Imports inside
functions count too."""

from __future__ import annotations

import ast
from collections import defaultdict
from pathlib import Path

import pytest

from .conftest import source_nodes

SRC = Path(__file__).resolve().parents[1] / "src" / "fcgrasp"
#: bottom first; ``errors`` may be imported by every layer
LAYERS = ["errors", "core", "spatial", "model", "mechanics", "io", "pipeline", "grippers",
          "planning", "physics", "plotting", "apps"]
LEVEL = {name: k for k, name in enumerate(LAYERS)}
APPS = ("cli", "batch", "serve")


def _module(path: Path) -> str:
    """Dotted module name of a source file (``fcgrasp.core.screws``)."""
    parts = list(path.relative_to(SRC.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _package(path: Path) -> str:
    mod = _module(path)
    return mod if path.name == "__init__.py" else mod.rsplit(".", 1)[0]


def _imports(path: Path, annotations: bool = False):
    """Every fcgrasp module a file imports, anywhere in it (functions included), with the
    names taken from it: ``(module, names)``; ``annotations``: those for type checkers
    too."""
    nodes = source_nodes(path)
    pkg = _package(path).split(".")
    # imports for type checkers only never run: not an edge of the layers' graph
    typing_only = set() if annotations else {
        id(n) for node in nodes if isinstance(node, ast.If)
        and getattr(node.test, "id", "") == "TYPE_CHECKING" for n in ast.walk(node)}
    for node in nodes:
        if id(node) in typing_only:
            continue
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = pkg[: len(pkg) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            if mod.split(".")[0] != "fcgrasp":
                continue
            names = [a.name for a in node.names]
            # "from . import x" may name submodules
            yield mod, names
            for n in names:
                if (SRC.parent / (mod.replace(".", "/") + f"/{n}.py")).exists() or \
                        (SRC.parent / (mod.replace(".", "/") + f"/{n}/__init__.py")).exists():
                    yield f"{mod}.{n}", []
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.split(".")[0] == "fcgrasp":
                    yield a.name, []
        elif isinstance(node, ast.Call) and getattr(node.func, "id", None) == "import_module":
            if node.args and isinstance(node.args[0], ast.Constant):
                yield str(node.args[0].value), []


def _layer(module: str) -> str | None:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[1] in LEVEL else None


def _sources():
    return [p for p in SRC.rglob("*.py") if _module(p) not in ("fcgrasp", "fcgrasp.__main__")]


def test_every_module_has_a_layer():
    lost = [_module(p) for p in _sources() if _layer(_module(p)) is None]
    assert not lost, lost
    assert len(_sources()) > 40


def test_imports_only_go_down():
    bad = []
    for path in _sources():
        here = _layer(_module(path))
        for dep, names in _imports(path):
            there = _layer(dep)
            if dep == "fcgrasp" and names != ["__version__"]:
                there = "apps"        # the public façade sits above everything but the apps
            if there is not None and LEVEL[there] > LEVEL[here]:
                bad.append(f"{_module(path)} -> {dep}")
    assert not bad, bad


def test_the_checker_sees_imports_inside_functions(tmp_path):
    src = "def f():\n    from ..apps.cli import main\n    return main\n"
    probe = SRC / "core" / "_probe_for_layers.py"
    probe.write_text(src)
    try:
        assert ("fcgrasp.apps.cli", ["main"]) in list(_imports(probe))
    finally:
        probe.unlink()


def test_no_cycle_between_modules():
    """Not even through the imports of annotations (a module that needs another's type
    for its signatures takes it from below)."""
    graph: dict[str, set[str]] = defaultdict(set)
    mods = {_module(p) for p in _sources()}
    for path in _sources():
        for dep, _ in _imports(path, annotations=True):
            if dep in mods and dep != _module(path) and not dep.endswith(".__init__"):
                graph[_module(path)].add(dep)
    # a package's __init__ re-exporting its modules is not a cycle with them
    for m in list(graph):
        graph[m] = {d for d in graph[m] if not m.startswith(d + ".")}
    seen: dict[str, int] = {}
    cycles = []

    def visit(m: str, stack: list[str]) -> None:
        seen[m] = 1
        for d in sorted(graph[m]):
            if seen.get(d) == 1:
                cycles.append(stack[stack.index(d):] + [d])
            elif d not in seen:
                visit(d, [*stack, d])
        seen[m] = 2

    for m in sorted(mods):
        if m not in seen:
            visit(m, [m])
    assert not cycles, cycles


def test_front_ends_never_import_one_another_and_use_the_public_api():
    """The batch runner and the explorer build their own requests: neither imports the
    command line or the other.  The command line is the launcher of all three (``fcgrasp
    batch``, ``fcgrasp serve``): it calls their entry points, nothing more."""
    bad = []
    for app in APPS:
        path = SRC / "apps" / f"{app}.py"
        for dep, names in _imports(path):
            leaf = dep.rsplit(".", 1)[-1]
            if leaf in APPS and leaf != app and app != "cli":
                bad.append(f"{app} imports {dep}")
            if app == "cli" and leaf in APPS and not set(names) <= {
                    "run_batch", "part_files", "cluster", "serve"}:
                bad.append(f"cli takes more than an entry point of {dep}: {names}")
            if _layer(dep) != "apps" and (any(p.startswith("_") for p in dep.split("."))
                                          or any(n.startswith("_") for n in names
                                                 if n != "__version__")):
                bad.append(f"{app} imports private {dep} {names}")
    assert not bad, bad


#: The most lines a module may have: one role each, readable in one sitting.
MAX_LINES = 600


def test_no_module_is_longer_than_a_role():
    """Every source module is at most :data:`MAX_LINES` lines (the numba loops included:
    they sit in modules by role, compiled over one namespace by the module that loads
    them)."""
    long = {_module(p): n for p in _sources()
            if (n := len(p.read_text().splitlines())) > MAX_LINES}
    assert not long, long


#: The largest share of the parameters of ``core`` and ``model`` (the layers held to
#: ``mypy --strict``) annotated with ``Any``.
MAX_ANY = 0.10


def _parameters(paths):
    """Every annotated function parameter of ``paths`` (self and cls left out), and
    those whose annotation names ``Any``."""


    total = any_ = 0
    for p in paths:
        for node in source_nodes(p):
            if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            a = node.args
            for arg in (*a.posonlyargs, *a.args, *a.kwonlyargs,
                        *([a.vararg] if a.vararg else []), *([a.kwarg] if a.kwarg else [])):
                if arg.arg in ("self", "cls"):
                    continue
                total += 1
                any_ += arg.annotation is not None and "Any" in ast.unparse(arg.annotation)
    return total, any_


@pytest.mark.parametrize("layer", ["core", "model"])
def test_few_parameters_are_any(layer):
    """Public types, not ``Any``: under :data:`MAX_ANY` of the parameters of the layers
    held to ``--strict`` (a parameter written ``Any`` takes anything unchecked by mypy).
    The counter counts: a module of ``Any`` parameters alone is all ``Any``."""
    paths = [p for p in _sources() if _module(p).split(".")[1:2] == [layer]]
    total, any_ = _parameters(paths)
    assert total > 300 and any_ <= MAX_ANY * total, (layer, any_, total)
