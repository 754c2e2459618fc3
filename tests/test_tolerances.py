"""Named tolerances (fcgrasp.core.tolerances): relative, so answers do not depend on units."""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np

import fcgrasp as fc
from fcgrasp.core import tolerances

from .conftest import source_nodes


def test_every_tolerance_is_named_and_small():
    for name in tolerances.__all__:
        v = getattr(tolerances, name)
        assert isinstance(v, float) and v > 0
        assert v < 1 or name == "MAX_MAGNITUDE"


def test_ties_within_tol_are_not_closure():
    # a force on the friction cone's edge, within TOL: not closure
    mu = 0.3
    q = np.array([1.0, mu])             # PQ on the cone edge at P
    assert not fc.friction_pair_closure([0, 0], [-1, 0], q, [1, 0], mu).item()
    assert fc.friction_pair_closure([0, 0], [-1, 0], q * [1, 0.99], [1, 0], mu).item()


def test_answers_do_not_depend_on_units():
    part = fc.read_part("demo:quad")
    mm = fc.plan(part, fingers=4, top=3)
    m = fc.plan(fc.Polygon(part.vertices / 1000), fingers=4, top=3)
    assert [p.edges for p in mm] == [p.edges for p in m]
    assert np.allclose([p.min_length / 1000 for p in mm], [p.min_length for p in m])


#: Small numbers that are not tolerances: unit factors, and the search's measured seconds
#: per candidate row (an estimate for the user, never a decision).
NOT_TOLERANCES = {("io/units.py", "MM_PER"), ("pipeline/_spec.py", "ROW_SECONDS"),
                  ("physics/_planar.py", "TIMESTEP"), ("physics/_planar.py", "_METRES"),
                  ("physics/_planar.py", "ROLL_FRICTION")}
SRC = Path(__file__).resolve().parents[1] / "src" / "fcgrasp"


def _bare_small_literals(path: Path, rel: str) -> list[str]:
    """Float literals below 1e-3 in a source file, outside the assignments of
    :data:`NOT_TOLERANCES`: each a tolerance that should be named in tolerances.py."""
    nodes = source_nodes(path)
    allowed: set[int] = set()
    for node in nodes:
        targets = node.targets if isinstance(node, ast.Assign) else \
            [node.target] if isinstance(node, ast.AnnAssign) else []
        if any(isinstance(t, ast.Name) and (rel, t.id) in NOT_TOLERANCES for t in targets):
            allowed |= {id(n) for n in ast.walk(node)}
    return [f"{rel}:{n.lineno}: {n.value!r}" for n in nodes
            if isinstance(n, ast.Constant) and isinstance(n.value, float)
            and 0 < abs(n.value) < 1e-3 and id(n) not in allowed]


def test_no_bare_tolerance_outside_tolerances_py():
    found = []
    files = [p for p in SRC.rglob("*.py") if p.name != "tolerances.py"]
    assert len(files) > 40
    for path in files:
        found += _bare_small_literals(path, path.relative_to(SRC).as_posix())
    assert not found, found


def test_the_bare_tolerance_check_can_fail(tmp_path):
    probe = tmp_path / "probe.py"
    probe.write_text("def f(x):\n    return x < 1e-9 * 2\nROW_SECONDS = {2: 1e-6}\n")
    assert sorted(_bare_small_literals(probe, "probe.py")) == ["probe.py:2: 1e-09",
                                                       "probe.py:3: 1e-06"]
    assert _bare_small_literals(probe, "pipeline/_spec.py") == [
        "pipeline/_spec.py:2: 1e-09"]
