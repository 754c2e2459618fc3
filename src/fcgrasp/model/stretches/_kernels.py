"""Compiled loops of the two-finger stretch search for large rings (part of
:mod:`fcgrasp.model.stretches`).

The numpy search of :mod:`fcgrasp.model.stretches._windows` holds the vertex matrix ``M``
as ``m_a x m_b`` booleans and widens every window of rows at once; on a 10,000-edge
outline that is 10^8 cells per mode and hundreds of passes over every row's runs.  These
loops do the same work row by row, with nothing of size ``m_a x m_b`` in memory:

* :func:`vertex_runs_tree` finds the runs of True of each row of ``M`` for both modes
  (squeeze ``M+`` and expand ``M-``: the expand test of a cell is the squeeze test with
  the chord reversed, so the same eight cross products, with the opposite sign) under a
  tree of bounds over ring b's columns: a block of columns whose cells surely all hold,
  or surely all fail, is decided at once, and only the blocks along a run's ends are
  read cell by cell, with the arithmetic of :func:`vertex_runs` (the window scan that
  reads every cell of a row's window of angles, kept as the reference), so the runs
  agree bit for bit;
* :func:`windows` widens one row's window of interior vertices at a time, intersecting
  its runs with the next row's (two monotone pointers over two sorted lists of runs),
  and stops as soon as no run is long enough to reach the bound: the lower bound of
  each first row (its vertex-aligned stretches), or the configurations whose bound
  reaches the floor, enumerated only over the start vertices that can reach it.  A
  sparse table of the rows' runs (the runs common to every window of ``2^j`` rows)
  gives any window's runs in two look-ups: the lower bounds are read only for the rows
  whose upper bound (found by bisection over the window's length) can still raise the
  search's floor, and the configurations from each row's first window long enough to
  reach it.  On a smooth outline of ``n`` edges both are ``O(n log n)``.

numba is imported on first use (the machine code cached on disk beside each loop's module,
:mod:`._run_kernels`, :mod:`._window_kernels`, :mod:`._copy_kernels`,
:mod:`._end_kernels` and :mod:`._solve_kernels`); the
search uses these loops only on rings large enough to repay it
(:data:`fcgrasp.model.stretches.KERNEL_CELLS`), and ``FCGRASP_JIT=0`` never does.
"""

from __future__ import annotations

import hashlib
from typing import Any

import numpy as np

from ...core._checks import BoolArray, FloatArray, IntArray
from ...core.jit import CompiledLoops
from . import _copy_kernels, _end_kernels, _run_kernels, _solve_kernels, _window_kernels
from ._window_kernels import _SHORT

_LOOPS = CompiledLoops.of_modules((_run_kernels, _window_kernels,
                                   _copy_kernels, _end_kernels,
                                   _solve_kernels))


def _load() -> dict[str, Any]:
    """The loops compiled (once per process; :class:`fcgrasp.core.jit.CompiledLoops`).
    The stretch search runs them only where :func:`~fcgrasp.model.stretches.stretch_kernels_for`
    says so, which needs numba."""
    loops = _LOOPS.get()
    if loops is None:
        raise ImportError("the stretch search's compiled loops need numba")
    return loops


def available() -> bool:
    """Do the compiled loops run here (loaded now, on first use)?  Not with
    ``FCGRASP_JIT=0`` or without a working numba."""
    return _LOOPS.available()


def loaded() -> bool:
    """Whether this process has loaded the compiled loops (then they cost nothing more)."""
    return _LOOPS.loaded


def vertex_runs(ax: FloatArray, ay: FloatArray, gx: FloatArray, va: FloatArray, bx: FloatArray,
                by: FloatArray, gy: FloatArray, order: IntArray, angle_b: FloatArray, width: float
                ) -> Any:
    """Compiled :func:`_vertex_runs`."""
    return _load()["_vertex_runs"](ax, ay, gx, va, bx, by, gy, order, angle_b, float(width))


def vertex_runs_tree(ax: FloatArray, ay: FloatArray, gx: FloatArray, va: FloatArray,
                     bx: FloatArray, by: FloatArray, gy: FloatArray, angle: FloatArray,
                     width: float, pad: float) -> Any:
    """Compiled :func:`_vertex_runs_tree`."""
    return _load()["_vertex_runs_tree"](ax, ay, gx, va, bx, by, gy, angle, float(width),
                                        float(pad))


#: Rows of ring a :func:`vertex_runs_blocks` reads at a time (a block of a 100,000-edge
#: noisy outline's rows takes a few tenths of a second at mu 1.0).
VERTEX_ROWS = 4096


def vertex_runs_blocks(ax: FloatArray, ay: FloatArray, gx: FloatArray, va: FloatArray,
                       bx: FloatArray, by: FloatArray, gy: FloatArray, angle: FloatArray,
                       width: float, pad: float, between: Any) -> Any:
    """:func:`vertex_runs_tree` over blocks of :data:`VERTEX_ROWS` rows, calling
    ``between`` before each block after the first (a budget's clock may end it there):
    the same runs (each row's runs depend on that row alone)."""
    ma = ax.size
    if ma <= VERTEX_ROWS:
        return vertex_runs_tree(ax, ay, gx, va, bx, by, gy, angle, width, pad)
    parts = []
    for r0 in range(0, ma, VERTEX_ROWS):
        if r0:
            between()
        r1 = min(r0 + VERTEX_ROWS, ma)
        parts.append(vertex_runs_tree(ax[r0:r1].copy(), ay[r0:r1].copy(),
                                      np.ascontiguousarray(gx[r0:r1]), va[r0:r1].copy(),
                                      bx, by, gy, angle, width, pad))
    out = []
    for s in (0, 3):
        ptr, first, last = [np.zeros(1, np.int64)], [], []
        for part in parts:
            ptr.append(part[s][1:] + ptr[-1][-1])
            first.append(part[s + 1])
            last.append(part[s + 2])
        out += [np.concatenate(ptr), np.concatenate(first), np.concatenate(last)]
    return tuple(out)


def vertex_runs_scan(ax: FloatArray, ay: FloatArray, gx: FloatArray, va: FloatArray,
                     bx: FloatArray, by: FloatArray, gy: FloatArray, angle: FloatArray,
                     width: float, pad: float) -> Any:
    """:func:`vertex_runs_tree`'s runs by the window scan (:func:`vertex_runs`, the
    previous kernel, kept as the reference; ``pad`` unused): ring b sorted by angle."""
    order = np.argsort(angle, kind="stable")
    return vertex_runs(ax, ay, gx, va, bx[order], by[order], gy[order], order,
                       angle[order], width)


def windows(ptr: IntArray, first: IntArray, last: IntArray, Ua: FloatArray, Ub: FloatArray,
            ma: int, mb: int, floor: float, collect: bool, same: bool, value: float = 0.0,
            keep: int = 0, short: int = _SHORT, ex: FloatArray | None = None,
            exs: FloatArray | None = None, between: Any = None, cap: int | None = None,
            gallop: bool = True) -> Any:
    """Compiled :func:`_windows` (index arrays made contiguous: one compiled signature
    for every caller; ``ex``, ``exs``: no kept plans where not given).  ``between``: a
    collection reads the rows in blocks (:data:`COLLECT_ROWS`, the sparse table built
    once) and calls it before each (a budget's check may end the collection there);
    ``cap``: a collection that holds more windows than this after a block ends there
    (:class:`~fcgrasp.core.budget.BudgetExhausted`, ``"collection"``); ``gallop``
    False: every start of stretch 2 read one by one (:func:`_window_row`'s reference)."""
    loops = _load()
    ptr, first, last = (np.ascontiguousarray(x, np.int64) for x in (ptr, first, last))
    ex = np.zeros((4, 0)) if ex is None else np.ascontiguousarray(ex, float)
    exs = np.zeros(5) if exs is None else np.ascontiguousarray(exs, float)
    args = (ptr, first, last, Ua, Ub, ma, mb, float(floor), collect, same, float(value),
            int(keep), int(short), ex, exs, bool(gallop))
    none = (np.zeros((0, 0), np.int64), np.zeros(0, np.int64), np.zeros(0, np.int64), 0)
    if not collect or between is None:
        return loops["_windows"](*args, 0, ma, *none)
    table = loops["_table"](ptr, first, last, ma) if ma >= 4 and ptr[ma] > 0 else none
    parts = []
    held = 0
    for r0 in range(0, ma, COLLECT_ROWS):
        between()
        parts.append(loops["_windows"](*args, r0, min(r0 + COLLECT_ROWS, ma), *table))
        held += int(parts[-1][1].size)
        if cap is not None and held > cap:
            from ...core.budget import BudgetExhausted

            raise BudgetExhausted("collection")
    return (parts[0][0], *(np.concatenate([p[j] for p in parts]) for j in range(1, 5)))


#: Rows of a block of a collection of :func:`windows`, with a budget check before each:
#: a block of a smooth 10,000-edge outline's collection takes at most a few tenths of a
#: second, and a ring of fewer rows is one block.
COLLECT_ROWS = 256


def single(*args: Any) -> Any:
    """Compiled :func:`_single`."""
    return _load()["_single"](*args)


def solve_rows(rows: FloatArray, ub: FloatArray, tol: float, eps: float, floor: float = 0.0) -> Any:
    """Compiled :func:`_solve_rows`."""
    return _load()["_solve_rows"](np.ascontiguousarray(rows, float), np.asarray(ub, float),
                                 float(tol), float(eps), float(floor))


def window_boxes(*args: Any) -> Any:
    """Compiled :func:`_window_boxes`."""
    return _load()["_window_boxes"](*args)


def exclusion_rows(*args: Any) -> None:
    """Compiled :func:`_exclusion_rows`."""
    _load()["_exclusion_rows"](*args)


def similar_rows(*args: Any) -> None:
    """Compiled :func:`_similar_rows`."""
    _load()["_similar_rows"](*args)


def third_rows(*args: Any) -> None:
    """Compiled :func:`_third_rows`."""
    _load()["_third_rows"](*args)


def inside_supers(*args: Any) -> None:
    """Compiled :func:`_inside_supers`."""
    _load()["_inside_supers"](*args)


def window_boxes_shared(*args: Any) -> Any:
    """Compiled :func:`_window_boxes_shared`."""
    return _load()["_window_boxes_shared"](*args)


def window_boxes_memo(*args: Any) -> Any:
    """Compiled :func:`_window_boxes_memo`."""
    return _load()["_window_boxes_memo"](*args)


def beaten(c: IntArray, t: FloatArray, ma: int, mb: int, same: bool, tie: float,
           check: BoolArray | None = None) -> BoolArray:
    """Compiled :func:`_beaten` of configurations ``c`` (F, 4: first start, its interior
    vertices, second start, its interior vertices) with smallest regions ``t``: the
    ones to keep (with ``check``, a mask, only those rows are decided; every row is a
    beater)."""
    c = np.array(c, np.int64)
    c[:, 0] %= ma                               # starts as ring positions
    c[:, 2] %= mb
    t = np.ascontiguousarray(t, float)
    check = np.ones(len(c), bool) if check is None else np.ascontiguousarray(check, bool)
    if len(c) < BEATEN_MEMO_ROWS:
        return _beaten_keep(c, t, ma, mb, same, tie, check)
    # the rounds of a distinct search ask again about the same configurations, in
    # another order: each one's answer depends on the set only, so the set is
    # remembered sorted
    o = np.lexsort((t, c[:, 3], c[:, 2], c[:, 1], c[:, 0]))
    h = hashlib.blake2b(np.ascontiguousarray(c[o]).tobytes(), digest_size=16)
    h.update(np.ascontiguousarray(t[o]).tobytes())
    h.update(np.ascontiguousarray(check[o]).tobytes())
    h.update(repr((int(ma), int(mb), bool(same), float(tie))).encode())
    digest = h.digest()
    if digest in _beaten_memo:
        keep = np.empty(len(c), bool)
        keep[o] = _beaten_memo[digest]
        return keep
    keep = _beaten_keep(c, t, ma, mb, same, tie, check)
    _beaten_memo[digest] = keep[o]
    while len(_beaten_memo) > BEATEN_MEMO_SIZE:
        del _beaten_memo[next(iter(_beaten_memo))]
    return keep


#: Configurations from which :func:`beaten` remembers its answer (by a digest of its
#: arguments), and how many answers it keeps.
BEATEN_MEMO_ROWS, BEATEN_MEMO_SIZE = 50_000, 4
_beaten_memo: dict[bytes, np.ndarray] = {}


def _beaten_keep(c: IntArray, t: FloatArray, ma: int, mb: int, same: bool, tie: float,
                 check: BoolArray | None) -> BoolArray:
    """:func:`beaten` of ring positions ``c``, computed."""
    keep = np.ones(len(c), bool)
    cols = [np.ascontiguousarray(c[:, j]) for j in range(4)]
    if _load()["_beaten_tables"](*cols, t, int(ma), int(mb), bool(same), float(tie), keep,
                                 check):
        return keep
    order = np.lexsort((-t, c[:, 0]))           # by first start, then the longest first
    _load()["_beaten"](np.ascontiguousarray(c[:, 0]), np.ascontiguousarray(c[:, 1]),
                       np.ascontiguousarray(c[:, 2]), np.ascontiguousarray(c[:, 3]), t,
                       int(ma), int(mb), bool(same), float(tie), order.astype(np.int64),
                       keep, check)
    return keep
