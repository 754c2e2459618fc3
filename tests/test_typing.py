"""The package ships ``py.typed``: ``mypy src`` must report no error."""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from .conftest import source_nodes

ROOT = Path(__file__).resolve().parents[1]


def test_mypy_clean():
    pytest.importorskip("mypy", reason="mypy is installed with the test extras")
    r = subprocess.run([sys.executable, "-m", "mypy", "--no-error-summary", "src"], cwd=ROOT,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr



def test_core_and_model_are_held_to_strict():
    """``mypy src`` (above) checks core and model with --strict's per-module flags: the
    overrides in pyproject.toml say so, and an untyped function there would fail it."""
    meta = tomllib.loads((ROOT / "pyproject.toml").read_text())
    strict = [o for o in meta["tool"]["mypy"]["overrides"]
              if {"fcgrasp.core.*", "fcgrasp.model.*", "fcgrasp.mechanics.*"} <= set(o["module"])]
    assert strict and all(strict[0].get(k) for k in (
        "disallow_untyped_defs", "disallow_any_generics", "warn_return_any",
        "disallow_untyped_calls", "no_implicit_reexport"))


#: The largest share of parameters of ``core`` and ``model`` annotated ``Any``.
MAX_ANY_SHARE = 0.10


@pytest.mark.parametrize("package", ["core", "model"])
def test_few_parameters_are_any(package):
    """Parameters carry their types (arrays by dtype, numbers, array-likes at the edge, the
    part's Polygon); ``Any`` is left where a value really is anything (the checks of
    user input, a formula that runs on numbers and arrays alike) and stays below
    :data:`MAX_ANY_SHARE` of the parameters of ``core`` and of ``model``."""
    import ast

    total = typed_any = 0
    for path in sorted((ROOT / "src" / "fcgrasp" / package).rglob("*.py")):
        for node in source_nodes(path):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                args = node.args
                for a in [*args.posonlyargs, *args.args, *args.kwonlyargs]:
                    if a.arg in ("self", "cls"):
                        continue
                    total += 1
                    typed_any += a.annotation is not None and ast.unparse(a.annotation) == "Any"
    assert typed_any <= MAX_ANY_SHARE * total, (package, typed_any, total)
