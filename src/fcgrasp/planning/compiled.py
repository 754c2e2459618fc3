"""Compile every numba kernel of the planners ahead of time.

numba compiles a kernel on its first call and caches the machine code on disk beside its
module; a process that finds the cache loads it (about 0.3-0.5 s once) instead of
compiling (two to three minutes of CPU for all of them).  :func:`compile_kernels` makes
those first calls, on small built-in parts, so that a deployment (a container image, a
batch cluster's workers, ``python3 tasks.py test`` before the suite starts) pays the
compile once, and no plan of a user does.
"""

from __future__ import annotations

import os
import time
from typing import Any

import numpy as np

__all__ = ["compile_kernels"]


def compile_kernels() -> dict[str, float]:
    """Compile (or load from the cache) every compiled kernel: the closed forms of two
    fingers (:mod:`fcgrasp.core.kernels`; one edge pair's regions,
    :mod:`fcgrasp.model.one_pair`), the two-finger stretch search
    (:mod:`fcgrasp.model.stretches._kernels`), the dense simplex
    (:mod:`fcgrasp.core._simplex`), the knapsack solver of four fingers and three with
    gravity (:mod:`fcgrasp.model._leximin_kernels`), three fingers with friction
    (:mod:`fcgrasp.grippers.three_fingers._concurrency`), the parallel jaw's pose model and proofs
    (:mod:`fcgrasp.grippers.jaw._kernels`), the optimality bound's test of a box of
    regions (:mod:`fcgrasp.model.bounds`) and the zero-force slice of three fingers on
    solids (:mod:`fcgrasp.spatial._slice`).  Returns the seconds each took (near zero
    once cached); without numba (or with ``FCGRASP_JIT=0``) nothing is compiled and
    every entry is 0.

    >>> sorted(compile_kernels())  # doctest: +NORMALIZE_WHITESPACE
    ['four fingers', 'optimality bound', 'parallel jaw', 'solids', 'stretches',
     'three fingers', 'two fingers']
    """
    from ..core.jit import jit_setting
    from ..model.bounds import refutes
    from ..model.polygon import Polygon
    from .planner import independent_regions, plan

    out = {"two fingers": 0.0, "stretches": 0.0, "three fingers": 0.0, "four fingers": 0.0,
           "parallel jaw": 0.0, "optimality bound": 0.0, "solids": 0.0}
    if jit_setting() is False:
        return out
    try:
        import numba  # noqa: F401
    except ImportError:
        return out
    a = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    r = 50 + 8 * np.sin(3 * a) + 5 * np.cos(7 * a)
    blob = Polygon(np.c_[r * np.cos(a), r * np.sin(a)])
    small = Polygon(np.c_[r[::4] * np.cos(a[::4]), r[::4] * np.sin(a[::4])])
    saved = os.environ.get("FCGRASP_JIT")
    os.environ["FCGRASP_JIT"] = "1"         # every path compiled, whatever the size
    try:
        runs: list[tuple[str, Any]] = [
            ("two fingers", lambda: (plan(blob, fingers=2, mu=0.3, along_boundary=False),
                                     independent_regions(blob, (0, 20), mu=0.3))),
            ("stretches", lambda: _stretches(blob)),
            ("three fingers", lambda: plan(small, fingers=3, mu=0.3, top=1)),
            ("four fingers", lambda: _four(small)),
            ("parallel jaw", lambda: _jaw()),
            ("optimality bound", lambda: refutes(small, 3, 60.0, mu=0.3, max_nodes=200)),
            ("solids", _solids),
        ]
        for name, run in runs:
            t0 = time.perf_counter()
            run()
            out[name] = time.perf_counter() - t0
    finally:
        if saved is None:
            del os.environ["FCGRASP_JIT"]
        else:
            os.environ["FCGRASP_JIT"] = saved
    return out


def _stretches(blob: Any) -> None:
    from ..core.tolerances import RANK_TOL
    from ..model.stretches import _kernels as _stretch_kernels
    from .planner import plan

    plan(blob, fingers=2, mu=0.3, top=1)
    c = np.array([[0, 2, 5, 1], [1, 0, 5, 0]])
    _stretch_kernels.beaten(c, np.array([1.0, 2.0]), 10, 10, False, RANK_TOL)
    # the sweep behind the tables (taken when they cannot decide), compiled too
    cols = [np.ascontiguousarray(c[:, k], np.int64) for k in range(4)]
    _stretch_kernels._load()["_beaten"](*cols, np.array([1.0, 2.0]), 10, 10, False,
                                        float(RANK_TOL), np.arange(2, dtype=np.int64),
                                        np.ones(2, bool), np.ones(2, bool))
    # the distinct search's tests (exclusion of a kept plan's alternatives, deferred
    # configurations inside a found one), with the types of their calls
    z, zi = np.zeros(1), np.zeros(1, np.int64)
    cells = np.ones((1, 1), bool)
    _stretch_kernels.exclusion_rows(z, z, z, z, z, z, z, z, 1.0, 1.0, 0.0, 0.5, cells, False,
                                    z.copy())
    _stretch_kernels.similar_rows(np.zeros((1, 4)), np.zeros((1, 4)), z, z, z, z, 1.0, 1.0,
                                  0.0, 0.5, z, cells, False, np.zeros(1, bool))
    # the end intervals of windows sharing an edge, with the types of the search's calls
    from ..model.stretches._windows import _EPS, _Intervals, _rings

    ring = _rings(blob)[0]
    iv = _Intervals(ring, ring, 1.0, 0.2)
    one = np.ones(1, np.int64)
    _stretch_kernels.window_boxes_shared(0 * one, one, one, *iv._flat, 1.0, _EPS)
    # the compiled references the searches are checked against, with the types of those
    # checks' calls: each window's end boxes read cell by cell, and the vertex runs by
    # the window scan
    _stretch_kernels.window_boxes(0 * one, one, one, *iv._flat, 1.0, _EPS)
    from ..model.stretches._rounds import vertex_run_args

    _stretch_kernels.vertex_runs_scan(*vertex_run_args(ring, ring, 0.25))
    # three fingers' distinct rounds: a third finger's overlap of the kept plans
    # (the types of _Exclusion._third_mask_of's call)
    out = np.zeros((1, 1), bool)
    _stretch_kernels.third_rows(zi, z, z, z, z, zi, z, z, np.ones(1), 0.5, 0.0, out)
    # a collection read in blocks of rows (its sparse table built once)
    _stretch_kernels._load()["_table"](np.zeros(5, np.int64), np.zeros(0, np.int64),
                                       np.zeros(0, np.int64), 4)
    _stretch_kernels.inside_supers(zi, zi, zi, zi, zi, zi, zi, np.zeros((1, 4), np.int64), 1, 1,
                                   np.zeros(1, bool))
    # the fused scores of every feature pair (a top-k search's candidates)
    from ..core.kernels import pair_scores
    from ..pipeline._candidates import features

    F = features(blob, 0.3)
    i = np.arange(len(F.a), dtype=np.intp)
    pair_scores(F.a, F.b, F.center, F.half, i, i[::-1].copy(), 0.0, RANK_TOL)


def _solids() -> None:
    """Three fingers' slice on three faces of a cube (the loops of
    :mod:`fcgrasp.spatial._slice`, with the types of a search's calls)."""
    from ..core.tolerances import SLICE_WEIGHT_TOL, TOL
    from ..spatial._slice import _LOOPS, pattern_table, slice_radius, slice_radius_at
    from ..spatial.triples import PYRAMID_EDGES, _generators, _pyramid_forces

    points = np.array([[1.0, 0, 0], [-1.0, 0.2, 0], [0, 1.0, 0.3]])
    normals = np.array([[-1.0, 0, 0], [1.0, 0, 0], [0, -1.0, 0]])
    w = _generators(points, normals, 0.4)
    slice_radius(w, PYRAMID_EDGES)
    slice_radius_at(points, _pyramid_forces(normals, 0.4), None, TOL)
    # the loops on their own, as the checks against qhull call them
    loops = _LOOPS.get()
    if loops is not None:
        table = pattern_table(PYRAMID_EDGES)
        out = np.empty((len(table), 3))
        loops["_slice_points"](w, table, SLICE_WEIGHT_TOL, out)
        loops["_hull_inradius"](np.ascontiguousarray(w[:4, :3]), SLICE_WEIGHT_TOL)


def _four(small: Any) -> None:
    from ..model.polygon import Polygon
    from ..pipeline._rows_kernels import survivors
    from .planner import plan

    plan(small, fingers=4, top=1)
    # the growth's drop of rows without a variable (a curved outline's growth meets them)
    from ..model._frictionless_kernels import kept_rows

    kept_rows(np.zeros((2, 8)), np.zeros(2), -1.0)
    # the candidate rows that may reach a full top's key, with the types of the search's
    order, z = np.arange(6, dtype=np.int64), np.linspace(1.0, 0.5, 6)
    edge = order.copy()
    edge.flags.writeable = False        # the features' edges are read-only
    survivors(order, edge, z, z / 2, 5, 5, 3, "as_is", 4, 2, z[:4], 10)
    # the rows of a regular polygon from pairs of opposite edges, and their bounds
    from ..pipeline._pair_rows import PairRows, coupled_bounds
    from ..pipeline._spec import plan_spec

    a = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    ring = Polygon(np.c_[np.cos(a), np.sin(a)])
    # (four fingers, then three with gravity)
    for spec in (plan_spec(fingers=4, along_boundary=False),
                 plan_spec(fingers=3, gravity=(0, -1), along_boundary=False)):
        pairs = PairRows(ring, spec)
        pairs.seed(1)
        pairs.reaching(0.99 * pairs.gamma)
    coupled_bounds(pairs.n, pairs.g, pairs.L, np.array([[0, 3, 6, 9]]))
    # a row's estimate (the rows a search leaves out below its floor) and the compiled
    # placement (two fingers on one edge), with the types of the search's calls
    from ..model.regions import KnapsackProblem, place_regions_sure
    from ..pipeline._candidates import quad_estimates

    quad_estimates(ring, plan_spec(fingers=4, along_boundary=False), np.array([[0, 3, 6, 9]]))
    one, yes = np.ones((1, 4)), np.ones((1, 4), bool)
    place_regions_sure(KnapsackProblem(one, one, one, np.ones(1), np.ones(1), yes, yes,
                                       np.ones(1, bool)), 0.1 * one)


def _jaw() -> None:
    from ..grippers.jaw import ParallelJaw, jaw_plans
    from ..io.parts import demo_part

    # a part with a hole: the internal grips' paths too
    jaw_plans(demo_part("washer"), ParallelJaw(stroke=(5, 60), pad_width=8, mu=0.5), top=1,
              internal=True)
    # a batch of boxes proved at once (the loop behind the boxes' proofs)
    from ..core._angles import shrunk_half_angle
    from ..grippers.jaw import _certify, _poses

    part, jaw = demo_part("rectangle"), ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
    ring = _poses._grip_edges(part, None)
    boxes = np.array([[np.radians(80), np.radians(100), -30.0, 30.0]])
    _certify._box_proofs(part, ring, jaw, boxes, float(shrunk_half_angle(jaw.mu, 2.0)), None)
    # one pad alone at one pose (the reference of both pads found in one pass), called
    # from Python as its check calls it
    from ..grippers.jaw import _kernels as _jaw_kernels

    a, b, f, half, tol = _poses._pose_args(part, jaw, 2.0, None, ring)[:5]
    k = _jaw_kernels.K_MAX
    _jaw_kernels._run("_pad_loop", 0, 1.0, 0.0, 0.0, a, b, f, half, tol, 1.0, -1.0, -1,
                      np.empty(1), np.zeros(1, bool), np.empty((1, k, 2)), np.empty((1, k)),
                      np.empty((1, k), np.int64), np.empty((2, a.shape[0])), 0)
