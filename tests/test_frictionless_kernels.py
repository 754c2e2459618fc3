"""The compiled rows of frictionless configurations against numpy's, bit for
bit: on the programs the growth of four fingers (and three with gravity) builds on the
built-in parts, and on seeded random configurations, null pairings and narrow sectors
included; and the partial sort of the row generation against numpy's stable sort."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.core._angles import margin_radians
from fcgrasp.core.sectors import PAIRINGS
from fcgrasp.core.tolerances import TOL
from fcgrasp.io.parts import demo_part
from fcgrasp.model import _frictionless_kernels, _frictionless_program, frictionless_stretches
from fcgrasp.model._frictionless_program import _smallest, _system

from .shapes import random_polygon

#: whether each program compared had a row without a variable
FIXED: list[bool] = []

pytestmark = pytest.mark.skipif(not _frictionless_kernels.COMPILED.available(),
                                reason="numba not available")


def _same(args, facts=None, arrays=None, parent=None):
    """Both ways give the same program (or both none); returns whether there is one.
    ``facts``: the stretches' lengths as a search remembers them, ``arrays`` the edges'
    rows it gathers from, ``parent`` a configuration one move away whose rows it copies,
    for the compiled way (the reference computes them)."""
    got = _system(*args, facts=facts, arrays=arrays, parent=parent)
    ref = _system(*args, compiled=False)
    assert (got is None) == (ref is None), args[1:]
    # the compiled loop says whether some row has no variable (then checked, not solved)
    polygon, edges, pairing, mode, margin, gravity = args
    rows = _frictionless_kernels.system_rows(polygon, edges, gravity, pairing,
                                             float(margin_radians(margin)),
                                             1.0 if mode == "+C" else -1.0, TOL, arrays)
    if rows:
        A, _, some_fixed = rows
        assert some_fixed == bool((~A.any(axis=1)).any())
        FIXED.append(some_fixed)
    if ref is None:
        return False
    np.testing.assert_array_equal(got.A, ref.A)
    np.testing.assert_array_equal(got.b, ref.b)
    assert got.bounds == ref.bounds
    np.testing.assert_array_equal(got.const, ref.const)
    return True


def test_compiled_rows_of_the_growths_programs(monkeypatch):
    calls = []
    original = frictionless_stretches._system

    def record(*args, **kwargs):
        calls.append((args, kwargs.get("facts"), kwargs.get("arrays"), kwargs.get("parent")))
        return original(*args, **kwargs)

    monkeypatch.setattr(frictionless_stretches, "_system", record)
    for name in ("blob", "quad", "bracket", "washer"):
        part = demo_part(name)
        fc.plan(part, fingers=4, top=2)
        fc.plan(part, fingers=3, gravity=(0, -1), top=2)
    monkeypatch.undo()
    assert len(calls) >= 300
    # the growth's search remembers its stretches' lengths and its edges' rows
    assert all(facts is not None and arrays is not None for _, facts, arrays, _ in calls)
    # most of the growth's programs are built from a configuration one move away
    assert sum(parent is not None for *_, parent in calls) >= len(calls) // 3
    programs = sum(_same(*call) for call in calls)
    assert programs >= 200


def test_rows_copied_from_a_configuration_one_move_away():
    """A configuration built from one a move away (its rows of the combinations both
    have copied) against numpy's, bit for bit: every move (longer, slid, shorter, and
    two regions slid at once) of seeded configurations of random parts, both
    orientations, every pairing, with and without gravity."""
    rng = np.random.default_rng(23)
    programs = copied = 0
    for _ in range(60):
        part = random_polygon(rng, str(rng.choice(["convex", "star", "regular", "holes"])))
        m = part.n_edges
        ang = np.arctan2(-part.normals[:, 1], -part.normals[:, 0])
        for _ in range(20):
            gravity = rng.random() < 0.3
            k = 3 if gravity else 4
            want = rng.uniform(0, 2 * np.pi) + np.arange(k) * 2 * np.pi / k
            firsts = [int(np.argmin(np.abs(np.angle(np.exp(1j * (ang - w))))))
                      for w in want]
            edges = tuple(tuple((e0 + i) % m for i in range(int(rng.integers(1, 4))))
                          for e0 in firsts)
            if len({e for st in edges for e in st}) < sum(map(len, edges)):
                continue
            args = (part, edges, PAIRINGS[rng.integers(0, 3)], str(rng.choice(["+C", "-C"])),
                    float(rng.choice([0.0, 0.5, 3.0])),
                    np.array([0.0, -1.0]) if gravity else None)
            parent = _system(*args)
            if parent is None:
                continue
            moves = frictionless_stretches._moves(part, edges) + \
                frictionless_stretches._pair_moves(part, edges)
            for new in moves:
                programs += _same((part, new, *args[2:]), parent=parent)
                copied += 1
    assert copied >= 1000 and programs >= 300


def test_compiled_rows_of_random_configurations():
    rng = np.random.default_rng(21)
    cases = programs = 0
    FIXED.clear()
    for _ in range(150):
        part = random_polygon(rng, str(rng.choice(["convex", "star", "regular", "holes",
                                                   "rectangle"])))
        m = part.n_edges
        search = frictionless_stretches._Search(part, 0.0, None)   # shared by the rows
        for _ in range(12):
            gravity = rng.random() < 0.3
            k = 3 if gravity else 4
            if rng.random() < 0.5:
                # fingers near the four quarter turns: most pairings hold
                ang = np.arctan2(-part.normals[:, 1], -part.normals[:, 0])
                want = rng.uniform(0, 2 * np.pi) + np.arange(k) * 2 * np.pi / k
                firsts = [int(np.argmin(np.abs(np.angle(np.exp(1j * (ang - w))))))
                          for w in want]
            else:
                firsts = [int(rng.integers(0, m)) for _ in range(k)]
            edges = tuple(tuple((e0 + i) % m for i in range(int(rng.integers(1, 5))))
                          for e0 in firsts)
            args = (part, edges, PAIRINGS[rng.integers(0, 3)], str(rng.choice(["+C", "-C"])),
                    float(rng.choice([0.0, 0.5, 3.0, 10.0])),
                    np.array([0.0, -1.0]) if gravity else None)
            arrays = _frictionless_kernels.edge_arrays(part, args[5]) \
                if rng.random() < 0.5 else None
            programs += _same(args, search.facts if rng.random() < 0.5 else None, arrays)
            cases += 1
    assert cases >= 1500 and programs >= 50
    # rows without a variable (every finger inside its stretch) met, and rows without
    assert 0 < sum(FIXED) < len(FIXED)


@pytest.mark.parametrize("compiled", [False, True])
def test_smallest_is_the_stable_sorts_head(compiled):
    """The row generation's pick of the rows to add against numpy's stable sort: ties
    in index order, nan last, -inf first; numpy's partial sort (``_smallest``) and the
    compiled program's one pass (``_first_k``)."""
    pick = _frictionless_kernels.COMPILED.get()["_first_k"] if compiled else _smallest
    rng = np.random.default_rng(22 + compiled)
    for t in range(5000):
        n, k = int(rng.integers(0, 80)), int(rng.integers(1, 24))
        v = rng.integers(-3, 4, n).astype(float) if t % 2 else rng.random(n)
        if t % 5 == 0 and n:
            v[rng.integers(0, n, 3)] = np.nan
        if t % 7 == 0 and n:
            v[rng.integers(0, n, 2)] = -np.inf
        np.testing.assert_array_equal(pick(v, k), np.argsort(v, kind="stable")[:k])


def _programs(parts, monkeypatch):
    calls = []
    original = _frictionless_program._lp

    def record(cfg, objective, floors, t_var):
        calls.append((cfg, objective.copy(), floors.copy(), t_var))
        return original(cfg, objective, floors, t_var)

    monkeypatch.setattr(_frictionless_program, "_lp", record)
    for part in parts:
        fc.plan(part, fingers=4, top=3)
        fc.plan(part, fingers=3, gravity=(0, -1), top=3)
    monkeypatch.undo()
    return calls


@pytest.mark.parametrize("parts", [pytest.param(1, id="seeded"),
                                   pytest.param(40, id="sweep", marks=pytest.mark.slow)])
def test_growths_programs_solved_in_one_compiled_call_equal_numpys(parts, monkeypatch):
    """The growth's programs (``_frictionless_program._lp``) built, scaled and
    solved by row generation in one compiled call (``_frictionless_kernels.lp_rows``)
    against the numpy steps (``COMPILED_LP`` False, the reference): the same answer,
    bit for bit, on every program four fingers and three with gravity solve on the
    built-in parts and on smooth outlines (tall programs: row generation), noise rows
    and infeasible programs included."""
    rng = np.random.default_rng(31)
    shapes = [demo_part(name) for name in ("blob", "quad", "bracket")]
    for _ in range(parts):
        n = int(rng.integers(16, 60))
        t = np.sort(rng.uniform(0, 2 * np.pi, n))
        r = 30 + rng.uniform(1, 6) * np.sin(3 * t + rng.uniform(0, 6)) + \
            rng.uniform(0, 3) * np.cos(5 * t)
        shapes.append(fc.Polygon(np.c_[r * np.cos(t), r * np.sin(t)]))
    calls = _programs(shapes, monkeypatch)
    tall = sum(len(c[0].A) + 2 * len(c[0].edges) > _frictionless_program.DIRECT_ROWS
               for c in calls)
    assert len(calls) >= 200 and tall >= 20
    solved = 0
    for args in calls:
        monkeypatch.setattr(_frictionless_program, "COMPILED_LP", True)
        got = _frictionless_program._lp(*args)
        monkeypatch.setattr(_frictionless_program, "COMPILED_LP", False)
        ref = _frictionless_program._lp(*args)
        assert (got is None) == (ref is None)
        if ref is not None:
            assert got[0] == ref[0]
            np.testing.assert_array_equal(got[1], ref[1])
            solved += 1
    assert solved >= 100


@pytest.mark.parametrize("seed", range(40))
def test_rows_kept_compiled_are_numpys(seed):
    """The compiled check and drop of the rows without a variable against numpy's
    (``~A.any(axis=1)``; a NaN coefficient counts as a variable, a NaN right-hand side
    does not fail): the same rows in the same order, the same verdict."""
    rng = np.random.default_rng(seed)
    n, width = int(rng.integers(0, 40)), int(rng.integers(1, 9))
    A = rng.choice([0.0, 0.0, 1.5, -2.0, np.nan], (n, width))
    A[rng.random(n) < 0.4] = 0.0
    rhs = rng.choice([-1.0, -1e-9, 0.0, 3.0, np.nan], n)
    floor = float(rng.choice([-1e-9, -0.5, 0.0]))
    got = _frictionless_kernels.kept_rows(A, rhs, floor)
    fixed = ~A.any(axis=1)
    if np.any(rhs[fixed] < floor):
        assert got is False
    else:
        np.testing.assert_array_equal(got[0], A[~fixed])
        np.testing.assert_array_equal(got[1], rhs[~fixed])
