"""The fused kernels against the previous pure-numpy implementation
(``tests/previous_kernels.py``), numpy mode and compiled mode, on seeded random edge sets,
near-degenerate ones included; and whole plans equal in both modes."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.core import jit, kernels
from fcgrasp.model._regiongeom import two_finger_problems
from fcgrasp.model.regions import KnapsackProblem, _two_level

from . import previous_kernels as prev
from .shapes import random_polygon

RTOL = 1e-12
MODES = ["numpy", "compiled"]


@pytest.fixture(params=MODES)
def mode(request, monkeypatch):
    """Run the kernels by numpy, or compiled for every batch however small (and check
    that they really ran compiled)."""
    monkeypatch.setenv("FCGRASP_JIT", "0" if request.param == "numpy" else "1")
    yield request.param
    if request.param == "compiled":
        assert kernels.compiled()


def _edge_sets(rng: np.random.Generator, n: int) -> dict[str, np.ndarray]:
    """Random pairs of segments with friction cones, some of them near-degenerate:
    parallel opposed edges, cones touching within rounding, a zero-length segment; tiny
    and huge scales (the tests take the margin, zero among them)."""
    scale = 10.0 ** rng.uniform(-3, 3, n)
    a1, a2 = rng.normal(size=(n, 2)) * scale[:, None], rng.normal(size=(n, 2)) * scale[:, None]
    d1, d2 = rng.normal(size=(n, 2)) * scale[:, None], rng.normal(size=(n, 2)) * scale[:, None]
    c1 = rng.uniform(-np.pi, np.pi, n)
    c2 = c1 + np.pi + rng.normal(0, 0.6, n)
    h = np.arctan(rng.uniform(0.0, 1.2, n))
    kind = rng.integers(0, 8, n)
    par = kind == 1                              # parallel opposed edges
    c2[par] = c1[par] + np.pi
    d2[par] = -d1[par] * rng.uniform(0.2, 3, par.sum())[:, None]
    touch = kind == 2                            # cones that just meet
    c2[touch] = c1[touch] + np.pi + 2 * h[touch] * (1 - 1e-13)
    d1[kind == 5] = 0.0                           # a point contact
    b1, b2 = a1 + d1, a2 + d2
    return dict(a1=a1, b1=b1, c1=c1, h1=h, a2=a2, b2=b2, c2=c2, h2=h.copy())


def _close(new: np.ndarray, old: np.ndarray, scale: np.ndarray) -> np.ndarray:
    return np.abs(np.asarray(new, float) - np.asarray(old, float)) <= RTOL * scale


@pytest.mark.parametrize("seed", range(3))
def test_pair_problems_equal_the_previous_implementation(seed, mode):
    e = _edge_sets(np.random.default_rng(seed), 3000)
    for m in (np.radians(0.5), 0.0):
        new, hm_new = two_finger_problems(e["a1"], e["b1"], e["c1"], e["h1"], e["a2"],
                                          e["b2"], e["c2"], e["h2"], m)
        old, hm_old = prev.two_finger_problems(e["a1"], e["b1"], e["c1"], e["h1"], e["a2"],
                                               e["b2"], e["c2"], e["h2"], m)
        assert np.all(_close(hm_new, hm_old, 1.0))
        for pn, po in zip(new, old, strict=True):
            size = np.maximum(po.L.max(axis=1), 1e-300)
            wscale = np.sum((po.w1 + po.w2) * po.L, axis=1) + abs(po.K1) + abs(po.K2)
            assert np.all(_close(pn.L, po.L, size[:, None]))
            assert np.all(_close(pn.w1, po.w1, 1.0)) and np.all(_close(pn.w2, po.w2, 1.0))
            assert np.all(_close(pn.K1, po.K1, wscale))
            assert np.all(_close(pn.K2, po.K2, wscale))
            for f in ("upper1", "active", "separable"):
                same = getattr(pn, f) == getattr(po, f)
                # a flag may only differ where its deciding quantity is a rounding tie
                assert same.mean() > 0.999, f
            # the solved levels agree wherever the flags do
            ok = pn.separable & po.separable
            lv_new = _two_level(pn, np.zeros_like(pn.L), np.ones_like(pn.L))
            lv_old = prev.two_level(po, np.zeros_like(po.L), np.ones_like(po.L))
            assert np.all(_close(lv_new, lv_old, size)[ok])


def _random_problems(rng: np.random.Generator, B: int) -> KnapsackProblem:
    L = rng.uniform(0, 2, (B, 2))
    L[rng.random(B) < 0.05, 0] = 0.0
    w1, w2 = rng.uniform(0, 1, (B, 2)), rng.uniform(0, 1, (B, 2))
    w1[rng.random((B, 2)) < 0.1] = 0.0
    w2[rng.random((B, 2)) < 0.05] = 0.0
    # budgets around the interesting range, some exactly at a breakpoint
    K1 = rng.uniform(-0.2, 1.0, B) * np.sum(w1 * L, axis=1)
    K2 = rng.uniform(-0.2, 1.0, B) * np.sum(w2 * L, axis=1)
    tie = rng.random(B) < 0.1
    K1[tie] = w1[tie, 0] * L[tie, 0]
    up = rng.random((B, 2)) < 0.5
    return KnapsackProblem(L, w1, w2, K1, K2, up, L > 0, np.ones(B, bool))


@pytest.mark.parametrize("seed", range(3))
def test_two_level_equals_the_previous_implementation(seed, mode):
    rng = np.random.default_rng(100 + seed)
    p = _random_problems(rng, 5000)
    B = p.batch
    for lb0, fr in ((np.zeros((B, 2)), np.ones((B, 2))),
                    (np.stack([rng.uniform(0, 1, B), np.zeros(B)], 1),
                     np.tile([0.0, 1.0], (B, 1))),
                    (np.stack([np.zeros(B), rng.uniform(0, 1, B)], 1),
                     np.tile([1.0, 0.0], (B, 1)))):
        new = _two_level(p, lb0, fr)
        old = prev.two_level(p, lb0, fr)
        scale = np.maximum(p.L.max(axis=1), 1e-300)
        assert np.all(_close(new, old, scale)), np.flatnonzero(~_close(new, old, scale))[:5]
        assert 0.1 < (new > 0).mean() < 0.95       # both outcomes are exercised


@pytest.mark.parametrize("seed", range(3))
def test_pair_scores_equal_the_previous_implementation(seed, mode):
    rng = np.random.default_rng(200 + seed)
    n = 120
    e = _edge_sets(rng, n)
    a, b = np.concatenate([e["a1"], e["a2"]]), np.concatenate([e["b1"], e["b2"]])
    center, half = np.concatenate([e["c1"], e["c2"]]), np.concatenate([e["h1"], e["h2"]])
    i, j = np.triu_indices(2 * n, 1)
    margin = np.radians(0.5)
    score, best, hm = kernels.pair_scores(a, b, center, half, i, j, margin)
    probs, hm_old = prev.two_finger_problems(a[i], b[i], center[i], half[i], a[j], b[j],
                                             center[j], half[j], margin)
    vals = np.stack([np.where(p.separable, prev.two_level(p, np.zeros_like(p.L),
                                                           np.ones_like(p.L)), -1.0)
                     for p in probs])
    size = np.maximum(probs[0].L.max(axis=1), 1e-300)
    assert np.all(_close(hm, hm_old, 1.0))
    ok = hm_old > 1e-12
    assert np.all(_close(score, vals.max(axis=0), size)[ok])
    clear = ok & (np.abs(vals[0] - vals[1]) > 1e-9 * size)
    assert np.array_equal(best[clear], np.argmax(vals, axis=0)[clear])
    assert 0.05 < (score > 0).mean() < 0.9


def test_plans_are_the_same_compiled_and_by_numpy(monkeypatch):
    rng = np.random.default_rng(7)
    for k in range(12):
        poly = random_polygon(rng)
        kw = dict(fingers=2, mu=float(rng.uniform(0.1, 0.8)), top=5,
                  along_boundary=bool(k % 2))
        out = {}
        for setting in ("0", "1"):
            monkeypatch.setenv("FCGRASP_JIT", setting)
            out[setting] = fc.plan(poly, **kw)
        assert len(out["0"]) == len(out["1"])
        for p, q in zip(out["0"], out["1"], strict=True):
            assert p.edges == q.edges and p.mode == q.mode
            assert np.allclose(p.lengths, q.lengths, rtol=1e-9, atol=0)
            for r, s in zip(p.regions, q.regions, strict=True):
                assert np.allclose(r, s, rtol=1e-9, atol=1e-9 * poly.size)


def test_small_batches_do_not_load_numba():
    """A small plan in a fresh process runs by numpy: numba is not even imported."""
    code = ("import sys, fcgrasp as fc\nfrom fcgrasp.io.parts import demo_part\n"
            "fc.plan(demo_part('blob'), fingers=2, mu=0.5, along_boundary=False)\n"
            "print('numba' in sys.modules)")
    env = {"PATH": "/usr/bin:/bin"}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, env=env)
    assert out.stdout.strip() == "False"


def test_use_jit_follows_the_setting(monkeypatch):
    monkeypatch.setenv("FCGRASP_JIT", "0")
    assert not kernels.use_jit(10 ** 9)
    monkeypatch.setenv("FCGRASP_JIT", "1")
    assert kernels.use_jit(1)


def test_a_large_search_switches_to_the_compiled_kernels():
    """Once a process has run JIT_AFTER_ROWS rows by numpy, the kernels are compiled (and
    the plans are the same as by numpy alone)."""
    code = ("import sys, json, numpy as np, fcgrasp as fc\nfrom fcgrasp.core import jit, kernels\n"
            "kernels.JIT_AFTER_ROWS = int(sys.argv[1])\n"
            "a = np.linspace(0, 2 * np.pi, 120, endpoint=False)\n"
            "r = 1 + 0.3 * np.sin(3 * a)\n"
            "part = fc.Polygon(np.c_[r * np.cos(a), r * np.sin(a)])\n"
            "p = fc.plan(part, fingers=2, mu=0.4, top=3, along_boundary=False)\n"
            "print(json.dumps(['numba' in sys.modules, [q.lengths.tolist() for q in p]]))")
    env = {"PATH": "/usr/bin:/bin"}
    runs = [json.loads(subprocess.run([sys.executable, "-c", code, str(after)],
                                      capture_output=True, text=True, check=True,
                                      env=env).stdout) for after in (100, 10 ** 9)]
    assert runs[0][0] is True and runs[1][0] is False
    assert np.allclose(runs[0][1], runs[1][1], rtol=1e-9)


def test_numba_started_by_other_loops_runs_the_kernels_compiled_at_once():
    """Once any compiled loops of the package started numba in a process, the searches
    that wait for their work to repay its start-up run compiled at once (the core
    kernels, the stretch search); before, they wait."""
    code = ("import json, fcgrasp as fc\nfrom fcgrasp.core import jit, kernels\n"
            "from fcgrasp.model import stretches, _frictionless_kernels\n"
            "def state():\n"
            "    return [jit.started(), kernels.use_jit(1),\n"
            "            stretches.stretch_kernels_for(1)]\n"
            "before = state()\n"
            "_frictionless_kernels.COMPILED.get()\n"
            "print(json.dumps([before, state()]))")
    env = {"PATH": "/usr/bin:/bin"}
    before, after = json.loads(subprocess.run([sys.executable, "-c", code],
                                              capture_output=True, text=True, check=True,
                                              env=env).stdout)
    assert before == [False, False, False]
    assert after == [True, True, True]


def test_numba_starts_without_importing_scipy_linalg_and_keeps_its_blas():
    """numba started by the package's loops does not import ``scipy.linalg`` (its BLAS
    check's import, 0.15 s of the start-up), and leaves numba as its own import would:
    ``arraymath`` says BLAS is there, ``ensure_blas`` is numba's own again, and a jitted
    ``np.dot`` compiles and runs (importing scipy's BLAS then)."""
    code = ("import json, sys, numpy as np\nimport fcgrasp as fc\n"
            "from fcgrasp.model import _frictionless_kernels\n"
            "_frictionless_kernels.COMPILED.get()\n"
            "fc.plan(fc.load_part('demo:quad').polygon, fingers=4, top=1)\n"
            "from numba.np import arraymath, linalg\n"
            "import numba\n"
            "state = ['scipy.linalg' in sys.modules, arraymath._HAVE_BLAS,\n"
            "         arraymath.ensure_blas is linalg.ensure_blas,\n"
            "         linalg.ensure_blas.__module__]\n"
            "dot = numba.njit(lambda a, b: np.dot(a, b))\n"
            "x = np.arange(6.0).reshape(2, 3)\n"
            "state += [float(dot(x, x.T).sum()), 'scipy.linalg' in sys.modules]\n"
            "print(json.dumps(state))")
    env = {"PATH": "/usr/bin:/bin", "FCGRASP_JIT": "1"}
    got = json.loads(subprocess.run([sys.executable, "-c", code], capture_output=True,
                                    text=True, check=True, env=env).stdout)
    assert got[:4] == [False, True, True, "numba.np.linalg"]
    assert got[4] == float((np.arange(6.0).reshape(2, 3) @ np.arange(6.0).reshape(2, 3).T)
                           .sum())
    assert got[5] is True


def test_a_loop_numba_cannot_compile_falls_back_to_numpy(monkeypatch):
    """A numba that fails (a typing error, say) never breaks a plan: numpy runs instead."""
    def boom(*args):
        raise TypeError("numba failed")

    e = _edge_sets(np.random.default_rng(9), 50)
    a, b = np.concatenate([e["a1"], e["a2"]]), np.concatenate([e["b1"], e["b2"]])
    c, h = np.concatenate([e["c1"], e["c2"]]), np.concatenate([e["h1"], e["h2"]])
    i, j = np.triu_indices(100, 1)
    monkeypatch.setenv("FCGRASP_JIT", "0")
    want = kernels.pair_scores(a, b, c, h, i, j, 0.01)
    monkeypatch.setenv("FCGRASP_JIT", "1")
    monkeypatch.setattr(kernels, "_loops", lambda: {"_pair_scores_loop": boom})
    monkeypatch.setattr(kernels, "_no_numba", False)
    monkeypatch.setattr(jit, "_fallen", set())
    monkeypatch.delenv("FCGRASP_REQUIRE_JIT", raising=False)
    with pytest.warns(jit.KernelFallbackWarning, match="_pair_scores_loop"):
        got = kernels.pair_scores(a, b, c, h, i, j, 0.01)
    for x, y in zip(got, want, strict=True):
        assert np.array_equal(x, y)
    assert not kernels.compiled()


@pytest.mark.parametrize("k", [3, 4, 5])
def test_direction_closure_compiled_is_the_numpy_test(k, monkeypatch):
    """Force-direction closure (theorem 4.2) of a batch compiled, against
    ``force_direction_closure`` by numpy: the same booleans on random forces and on
    degenerate ones (axis-aligned, so opposite and parallel pairs are exact; zero
    forces; directions a hair off parallel)."""
    from fcgrasp.core.closure import direction_closure, force_direction_closure

    pytest.importorskip("numba")
    monkeypatch.setenv("FCGRASP_JIT", "1")
    rng = np.random.default_rng(40 + k)
    ang = rng.uniform(0, 2 * np.pi, (30000, k))
    ang[::3] = np.round(ang[::3] / (np.pi / 2)) * (np.pi / 2)
    ang[1::5, 1] = ang[1::5, 0] + np.pi + rng.choice([0.0, 1e-13, -1e-13, 1e-6], 6000)
    f = np.stack([np.cos(ang), np.sin(ang)], axis=-1) * rng.uniform(0.1, 10, (30000, k, 1))
    f[::7, 0] = 0.0
    got = direction_closure(f)
    assert kernels.compiled()
    want = force_direction_closure(f)
    np.testing.assert_array_equal(got, want)
    assert 0.05 < want.mean() < 0.95

    # rows of indices into a table of forces: the same booleans, compiled and not
    from fcgrasp.core.closure import rows_closure

    table = f.reshape(-1, 2)
    rows = rng.integers(0, len(table), (30000, k))
    rows[::4] = np.arange(30000 * k).reshape(-1, k)[::4]      # every row of f as it is
    want_rows = force_direction_closure(table[rows])
    np.testing.assert_array_equal(rows_closure(table, rows), want_rows)
    np.testing.assert_array_equal(rows_closure(table, rows[::4]), want[::4])
    monkeypatch.setenv("FCGRASP_JIT", "0")
    np.testing.assert_array_equal(rows_closure(table, rows), want_rows)
    assert 0.05 < want_rows.mean() < 0.95


def _scale_rows(x, out, k):
    for i in range(x.shape[0]):
        out[i] = k * x[i]


def _scale_all(x):
    out = np.empty_like(x)
    for k in range(3):
        _scale_rows(x, out, 1.0 + k)
    return out


@pytest.mark.skipif(jit.import_numba() is None, reason="numba not available")
def test_a_borrowing_loop_runs_without_reference_counts_and_gives_the_same_numbers():
    """``njit_all``'s ``borrowing``: the named loops are compiled with numba's runtime
    off (no reference counts on the arrays they are given), the others as before, and a
    caller that allocates still calls them: the same numbers as the plain loop."""
    numba = jit.import_numba()
    space = {"np": np}
    loops = jit.njit_all(numba, space, [("_scale_rows", _scale_rows),
                                            ("_scale_all", _scale_all)],
                             frozenset({"_scale_rows"}))
    x = np.random.default_rng(3).normal(size=50)
    np.testing.assert_array_equal(loops["_scale_all"](x), _scale_all(x))
    assert loops["_scale_rows"].targetoptions.get("_nrt") is False
    assert "_nrt" not in loops["_scale_all"].targetoptions


@pytest.mark.skipif(jit.import_numba() is None, reason="numba not available")
def test_a_numba_without_the_option_compiles_the_borrowing_loops_as_the_others(
        monkeypatch):
    """Where numba's CPU target has no ``_nrt`` option (it would fail only at the first
    call, leaving every loop to numpy), ``borrowing`` loops are compiled as the others,
    and run."""
    numba = jit.import_numba()
    monkeypatch.setattr(jit, "_takes_nrt_option", lambda: False)
    loops = jit.njit_all(numba, {"np": np}, [("_scale_rows", _scale_rows),
                                                 ("_scale_all", _scale_all)],
                             frozenset({"_scale_rows"}))
    assert "_nrt" not in loops["_scale_rows"].targetoptions
    x = np.arange(5.0)
    np.testing.assert_array_equal(loops["_scale_all"](x), _scale_all(x))


def _triple(x, out):
    for i in range(x.shape[0]):
        out[i] = 3.0 * x[i] + 1.0


@pytest.mark.skipif(jit.import_numba() is None, reason="numba not available")
def test_a_loop_loads_from_the_cache_without_refreshing_numba(monkeypatch):
    """``njit_all``'s dispatchers load their machine code from numba's cache without
    numba's registry refresh (``_light_loads``): a second dispatcher of the same loop
    (a new process's, in effect) is a cache hit through the light class, never calls
    the target context's ``refresh``, and gives the loop's numbers."""
    numba = jit.import_numba()
    x = np.random.default_rng(4).normal(size=40)
    first = jit.njit_all(numba, {}, [("_triple", _triple)])["_triple"]
    want = np.empty_like(x)
    first(x, want)                           # compiled (and cached) or loaded
    refreshed = []
    ctx = type(first.targetctx)
    monkeypatch.setattr(ctx, "refresh", lambda self: refreshed.append(1))
    second = jit.njit_all(numba, {}, [("_triple", _triple)])["_triple"]
    assert type(second._cache).__name__ == "_LightCache"
    got = np.empty_like(x)
    second(x, got)
    assert second.stats.cache_hits and not second.stats.cache_misses
    assert refreshed == []
    np.testing.assert_array_equal(got, 3.0 * x + 1.0)
    np.testing.assert_array_equal(got, want)


def test_a_loop_that_fails_to_compile_warns_once_or_fails_when_required(monkeypatch):
    """A compiled loop that numba cannot type falls back to numpy with one warning per
    loop; with ``FCGRASP_REQUIRE_JIT=1`` (the suite's setting) it raises instead."""
    from fcgrasp.core import jit

    def bad(x):
        raise TypeError("cannot type")

    loops = jit.CompiledLoops({}, ())
    monkeypatch.setattr(loops, "get", lambda: {"bad_loop": bad})
    monkeypatch.setattr(jit, "_fallen", set())
    monkeypatch.delenv("FCGRASP_REQUIRE_JIT", raising=False)
    with pytest.warns(jit.KernelFallbackWarning, match="bad_loop"):
        assert loops.run("bad_loop", 1) == (False, None)
    assert loops.broken
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        jit.fell_back("bad_loop", TypeError("again"))     # said once only
    monkeypatch.setenv("FCGRASP_REQUIRE_JIT", "1")
    with pytest.raises(RuntimeError, match="FCGRASP_REQUIRE_JIT"):
        jit.fell_back("bad_loop", TypeError("again"))
