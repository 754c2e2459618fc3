"""Shared helpers: independent reference methods (LP with HiGHS, tests._highs) and seeds."""

from __future__ import annotations

import ast
import gc
from functools import cache
from pathlib import Path

import numpy as np
import pytest

from ._highs import linprog

#: The longest tests, run first: on two workers a long test left for the end runs
#: alone while the other worker has nothing left.
FIRST = ("tests/test_typing.py::test_mypy_clean",
         "tests/test_cli.py::test_demo_command_writes_json_and_figures")


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    items.sort(key=lambda item: item.nodeid not in FIRST)       # stable: the rest in order


#: The test processes' garbage collection, once the tests are collected: what the
#: imports and the collection made lives to the end (frozen: never traversed again),
#: and the youngest generation is collected every 20,000 allocations instead of 700
#: (garbage collection costs the suite about 4 s of CPU so, 10 s with Python's defaults).
GC_THRESHOLD = (20_000, 20, 20)


def pytest_collection_finish(session: pytest.Session) -> None:
    gc.collect()
    gc.freeze()
    gc.set_threshold(*GC_THRESHOLD)


#: The package's sources (their syntax trees read once per test process).
PACKAGE = Path(__file__).resolve().parents[1] / "src" / "fcgrasp"


def source_nodes(path: Path) -> tuple[ast.AST, ...]:
    """Every node of a source file's syntax tree (``ast.walk``'s order): a module of the
    package's listed once per test process (the layout, tolerance and typing checks
    each read every module, several times; none changes a tree), any other file (a
    test's probe) read anew."""
    path = Path(path)
    if path.is_relative_to(PACKAGE):
        return _package_nodes(path)
    return tuple(ast.walk(ast.parse(path.read_text())))


@cache
def _package_nodes(path: Path) -> tuple[ast.AST, ...]:
    return tuple(ast.walk(ast.parse(path.read_text())))


@pytest.fixture
def rng() -> np.random.Generator:
    return np.random.default_rng(20261122)


def lp_positive_margin(vectors: np.ndarray) -> float:
    """max t s.t. sum_i l_i v_i = 0, sum l_i = 1, l_i >= t  (HiGHS).

    Positive iff some strictly positive combination of the (unit-normalised) vectors
    vanishes.  Together with full rank this is "the cone is the whole space".
    """
    v = np.asarray(vectors, dtype=float)
    n = np.linalg.norm(v, axis=1)
    v = v[n > 0] / n[n > 0, None]
    k, d = v.shape
    if k == 0:
        return -1.0
    # variables: l (k), t ; maximise t
    c = np.zeros(k + 1)
    c[-1] = -1.0
    a_eq = np.zeros((d + 1, k + 1))
    a_eq[:d, :k] = v.T
    a_eq[d, :k] = 1.0
    b_eq = np.zeros(d + 1)
    b_eq[d] = 1.0
    a_ub = np.hstack([-np.eye(k), np.ones((k, 1))])   # t - l_i <= 0
    res = linprog(c, A_ub=a_ub, b_ub=np.zeros(k), A_eq=a_eq, b_eq=b_eq,
                  bounds=[(0, None)] * k + [(None, None)], method="highs")
    if res.status != 0:
        return -1.0
    return float(-res.fun)


def lp_is_total(vectors: np.ndarray, band: float = 1e-7) -> bool | None:
    """Independent test that the cone of ``vectors`` is the whole space.

    Returns None when the configuration is within ``band`` of the boundary (ambiguous).
    """
    v = np.asarray(vectors, dtype=float)
    n = np.linalg.norm(v, axis=1)
    v = v[n > 0] / n[n > 0, None]
    if v.shape[0] == 0:
        return False
    s = np.linalg.svd(v, compute_uv=False)
    if s[-1] < band if v.shape[0] >= v.shape[1] else True:
        return False if (v.shape[0] < v.shape[1] or s[-1] < 1e-12) else None
    m = lp_positive_margin(v)
    if abs(m) < band:
        return None
    return m > 0


def normalized_frame(wrenches: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Wrenches about the centroid of ``points`` with torques over the spread (test helper)."""
    c = points.mean(axis=0)
    spread = max(float(np.max(np.linalg.norm(points - c, axis=1))), 1e-300)
    f = wrenches[:, :2]
    tau = wrenches[:, 2] - (c[0] * f[:, 1] - c[1] * f[:, 0])
    return np.column_stack([f, tau / spread])
