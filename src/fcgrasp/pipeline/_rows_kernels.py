"""The candidate rows that may still reach the running top, compiled (four
fingers on a flattened curve).

Once the top of a four-finger search (or three with gravity) is full, every row the
branch and bound streams (:func:`fcgrasp.pipeline._candidates._ordered_rows`) is
checked against the top's last leximin key, and on a flattened curve, where every short
edge ties the key's smallest region, tens of millions of rows are built and dropped:
``icons/cloud.svg`` builds 40 million in 10,000 numpy blocks (sorting, the distinct
edges, the layouts, the bounds, :func:`~fcgrasp.pipeline._candidates.lex_survivors`:
10 of its 17 s).  :func:`survivors` runs the same steps in one compiled loop over the
combinations of one position ``s`` and gives the surviving rows in the numpy path's
order; the numpy path stays the reference (the tests compare the candidate streams,
batch for batch and row for row).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core import kernels
from ..core.jit import CompiledLoops
from ..core.kernels import _closed

#: The layouts of :func:`fcgrasp.pipeline._candidates._layouts`.
AS_IS, GRAVITY, DOUBLED = 0, 1, 2


def _row_of(t: Any, w: int, layout: int, x: int, twin: int, row: Any) -> int:
    """Row ``x`` of the layout of the sorted features ``t[:w]`` into ``row``; its width."""
    if layout == AS_IS:
        for c in range(w):
            row[c] = t[c]
        return w
    if layout == GRAVITY:
        for c in range(w):
            row[c] = t[c]
        row[w] = -1
        return w + 1
    # doubled: feature x first and at column twin, the others in order around it
    row[0] = t[x]
    c = 1
    for y in range(w):
        if y == x:
            continue
        if c == twin:
            row[c] = t[x]
            c += 1
        row[c] = t[y]
        c += 1
    if c == twin:
        row[c] = t[x]
        c += 1
    return c


def sort_first(v: Any, w: int) -> None:
    """Sort ``v[:w]`` in place (insertion: a row's few features)."""
    for c in range(1, w):
        y = v[c]
        d = c - 1
        while d >= 0 and v[d] > y:
            v[d + 1] = v[d]
            d -= 1
        v[d + 1] = y


def _alive(v: Any, real: int, key: Any) -> bool:
    """:func:`~fcgrasp.pipeline._candidates.lex_survivors` of one row's rounded bounds
    ``v`` (ascending, ``real`` of them)."""
    for j in range(min(real, key.size)):
        if v[j] < key[j]:
            return False
        if v[j] != key[j]:
            return True
    return True


def _bounds(pos: Any, r: int, s: int, R: Any, RH: Any, doubled: bool, x: int, order: Any,
            t: Any, v: Any) -> int:
    """The rounded bounds of a row, ascending, into ``v``; their count.  ``R``, ``RH``:
    each position's bound (its feature's length, and half of it), never rising along
    the positions.  As is: the positions' bounds, ``s``'s first.  Doubled with
    ``x`` < 0: above every layout's (the doubled feature's half bound taken as the
    longest feature's whole); with ``x`` >= 0: the layout doubling ``t[x]`` (the
    features sorted)."""
    v[0] = R[s]
    for c in range(r):
        v[1 + c] = R[pos[r - 1 - c]]
    if not doubled:
        return r + 1
    if x < 0:
        v[r + 1] = R[pos[0]]
        return r + 2
    # the half bound of the doubled feature, at its place
    p = s
    for c in range(r):
        if order[pos[c]] == t[x]:
            p = pos[c]
    y = RH[p]
    d = r
    while d >= 0 and v[d] > y:
        v[d + 1] = v[d]
        d -= 1
    v[d + 1] = y
    return r + 2


def _survivor_loop(order: Any, edge: Any, R: Any, RH: Any, s: int, pool: int, r: int,
                   layout: int, fingers: int, twin: int, key: Any, out: Any, table: Any,
                   tol: float, where: Any) -> Any:
    """Every increasing ``r``-tuple of positions ``range(pool)`` with position ``s``:
    its features sorted, on distinct edges, laid out, kept where its bounds may reach or
    tie ``key``; rows in the numpy path's order (a doubled layout's ``x`` slowest).
    Returns ``(rows, where, count, read)`` (``out`` and ``where`` grown as needed).

    With a ``table`` of unit forces (each feature's, gravity's last; empty: no test),
    only the rows whose forces pass the force-direction test (theorem 4.2,
    :func:`fcgrasp.core.kernels._closed` with ``tol``, as
    :func:`fcgrasp.core.closure.rows_closure` reads them) are given, each with its
    place among the rows the loop would give without the test (``where``); ``read``
    counts those.

    The tuples run in lexicographic order, and a tuple's bounds only fall as a position
    rises: once a tuple is below the key, so is every later one that keeps its first
    ``d`` positions, where its later positions follow the ``d``-th one's without gaps
    (each of them is at or after its own); those are skipped.  Doubled layouts skip by
    a bound above all of them."""
    w = r + 1
    lay = layout
    if lay == DOUBLED and w == fingers:
        lay = AS_IS
    doubled = lay == DOUBLED
    n_x = w if doubled else 1
    pos = np.empty(4, np.int64)
    t = np.empty(4, np.int64)
    row = np.empty(5, np.int64)
    v = np.empty(5)
    u = np.empty((5, 2))
    test = table.shape[0] > 0
    # a key every row reaches (:data:`~fcgrasp.pipeline._candidates._EVERY_ROW`): no
    # bounds to compare
    every = key.shape[0] == 1 and key[0] == -math.inf
    last = table.shape[0] - 1
    n = 0
    read = 0
    if r > pool:
        return out, where, n, read
    for x in range(n_x):
        for c in range(r):
            pos[c] = c
        while True:
            skip = -1                   # the level to advance (r - 1: the next tuple)
            if not every and not _alive(v, _bounds(pos, r, s, R, RH, doubled, -1, order, t, v),
                                        key):
                # the first level from which the positions follow without gaps
                d = r - 1
                while d > 0 and pos[d] == pos[d - 1] + 1:
                    d -= 1
                skip = d - 1
                if skip < 0:
                    break
            else:
                skip = r - 1
                # the tuple's features, with s's, sorted
                for c in range(r):
                    t[c] = order[pos[c]]
                t[r] = order[s]
                sort_first(t, w)
                ok = True
                for a in range(w):
                    for b in range(a + 1, w):
                        if edge[t[a]] == edge[t[b]]:
                            ok = False
                if ok and doubled and not every:
                    ok = _alive(v, _bounds(pos, r, s, R, RH, True, x, order, t, v), key)
                if ok:
                    width = _row_of(t, w, lay, x, twin, row)
                    read += 1
                    if test:
                        for c in range(width):
                            f = row[c] if row[c] >= 0 else last
                            u[c, 0], u[c, 1] = table[f, 0], table[f, 1]
                        ok = _closed(u, width, tol)
                if ok:
                    if n == out.shape[0]:
                        bigger = np.empty((2 * out.shape[0], out.shape[1]), np.int64)
                        bigger[:n] = out[:n]
                        out = bigger
                        more = np.empty(2 * where.shape[0], np.int64)
                        more[:n] = where[:n]
                        where = more
                    for c in range(width):
                        out[n, c] = row[c]
                    where[n] = read - 1
                    n += 1
            # advance level ``skip`` (lexicographic, as numpy's triu_indices)
            c = skip
            while c >= 0 and pos[c] == pool - r + c:
                c -= 1
            if c < 0:
                break
            pos[c] += 1
            for d in range(c + 1, r):
                pos[d] = pos[d - 1] + 1
    return out, where, n, read


#: The per-row helpers, which allocate nothing and make no view: compiled without
#: reference counts (:func:`~fcgrasp.core.jit.njit_all`).
_BORROWING = (_row_of, sort_first, _alive, _bounds)


def _with_closure() -> dict[str, Any] | None:
    """The compiled force-direction test of :mod:`fcgrasp.core.kernels` (``_closed``)."""
    core = kernels._loops()
    return None if core is None else {"_closed": core["_closed"]}


_LOOPS = CompiledLoops(globals(), (*_BORROWING, _survivor_loop), _with_closure,
                       borrowing=_BORROWING)

#: No force test (:func:`_survivor_loop`'s empty table).
_NO_TABLE = np.zeros((0, 2))

#: Combinations of one position from which :func:`survivors` runs compiled before the
#: loop is loaded in this process (loading it costs about 0.1 s from numba's cache).
KERNEL_ROWS = 200_000


def survivors(order: np.ndarray, edge: np.ndarray, R: np.ndarray, RH: np.ndarray, s: int,
              pool: int, r: int, layout: str, fingers: int, twin: int, key: np.ndarray,
              combos: int) -> np.ndarray | None:
    """:func:`holding_survivors` without the force test: the rows alone."""
    got = holding_survivors(order, edge, R, RH, s, pool, r, layout, fingers, twin, key,
                            combos)
    return None if got is None else got[0]


def holding_survivors(order: np.ndarray, edge: np.ndarray, R: np.ndarray, RH: np.ndarray,
                      s: int, pool: int, r: int, layout: str, fingers: int, twin: int,
                      key: np.ndarray, combos: int, table: np.ndarray | None = None,
                      tol: float = 0.0) -> tuple[np.ndarray, np.ndarray, int] | None:
    """The rows of position ``s`` (``r`` positions drawn from ``range(pool)``) whose
    bounds may reach or tie ``key``, in the order of the numpy path of
    :func:`~fcgrasp.pipeline._candidates._ordered_rows`; None where the compiled loop
    does not run (without numba, ``FCGRASP_JIT=0``, or below :data:`KERNEL_ROWS`
    ``combos`` before numba started in this process, this loop's or another's:
    :func:`fcgrasp.core.jit.started`): the numpy path then.

    ``order``: the features by position (decreasing length); ``edge``: each feature's
    edge; ``R``, ``RH``: each position's bound (its feature's length, and half of it)
    as the ranking rounds it (:func:`~fcgrasp.pipeline._candidates.lex_survivors`).

    With a ``table`` of unit forces (:func:`~fcgrasp.core.closure.rows_closure`'s, made
    unit as it makes them) only the rows that pass the force-direction test with
    ``tol``; returns ``(rows, where, read)``: the rows, the place of each among the
    rows without the test, and how many those are."""
    from ..core.jit import jit_setting, started

    setting = jit_setting()
    if setting is False or (setting is None and not started() and combos < KERNEL_ROWS):
        return None
    if not _LOOPS.available():
        return None
    code = {"as_is": AS_IS, "gravity": GRAVITY, "doubled": DOUBLED}[layout]
    # as the loop lays out: a doubled layout of as many features as fingers is as is
    width = r + 1 if code == AS_IS or (code == DOUBLED and r + 1 == fingers) else r + 2
    ok, res = _LOOPS.run("_survivor_loop", order, edge, R, RH, int(s), int(pool), int(r),
                         code, int(fingers), int(twin), key,
                         np.empty((64, width), np.int64),
                         _NO_TABLE if table is None else table, float(tol),
                         np.empty(64, np.int64))
    if not ok:
        return None
    rows, where, n, read = res
    out: np.ndarray = rows[:n, :width]
    return out, where[:n], int(read)
