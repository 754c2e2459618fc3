"""The candidate rows that may still reach the running top, compiled (issue 30: four
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

from typing import Any

import numpy as np

from ..core.kernels import CompiledLoops

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
                   layout: int, fingers: int, twin: int, key: Any, out: Any) -> Any:
    """Every increasing ``r``-tuple of positions ``range(pool)`` with position ``s``:
    its features sorted, on distinct edges, laid out, kept where its bounds may reach or
    tie ``key``; rows in the numpy path's order (a doubled layout's ``x`` slowest).
    Returns ``(rows, count)`` (``out`` grown as needed).

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
    n = 0
    if r > pool:
        return out, n
    for x in range(n_x):
        for c in range(r):
            pos[c] = c
        while True:
            m = _bounds(pos, r, s, R, RH, doubled, -1, order, t, v)
            skip = -1                   # the level to advance (r - 1: the next tuple)
            if not _alive(v, m, key):
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
                if ok and doubled:
                    m = _bounds(pos, r, s, R, RH, True, x, order, t, v)
                    ok = _alive(v, m, key)
                if ok:
                    width = _row_of(t, w, lay, x, twin, row)
                    if n == out.shape[0]:
                        bigger = np.empty((2 * out.shape[0], out.shape[1]), np.int64)
                        bigger[:n] = out[:n]
                        out = bigger
                    for c in range(width):
                        out[n, c] = row[c]
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
    return out, n


#: The per-row helpers, which allocate nothing and make no view: compiled without
#: reference counts (:func:`~fcgrasp.core.kernels.njit_all`).
_BORROWING = (_row_of, sort_first, _alive, _bounds)

_LOOPS = CompiledLoops(globals(), (*_BORROWING, _survivor_loop), borrowing=_BORROWING)

#: Combinations of one position from which :func:`survivors` runs compiled before the
#: loop is loaded in this process (loading it costs about 0.1 s from numba's cache).
KERNEL_ROWS = 200_000


def survivors(order: np.ndarray, edge: np.ndarray, R: np.ndarray, RH: np.ndarray, s: int,
              pool: int, r: int, layout: str, fingers: int, twin: int, key: np.ndarray,
              combos: int) -> np.ndarray | None:
    """The rows of position ``s`` (``r`` positions drawn from ``range(pool)``) whose
    bounds may reach or tie ``key``, in the order of the numpy path of
    :func:`~fcgrasp.pipeline._candidates._ordered_rows`; None where the compiled loop
    does not run (without numba, ``FCGRASP_JIT=0``, or below :data:`KERNEL_ROWS`
    ``combos`` before numba started in this process, this loop's or another's:
    :func:`fcgrasp.core.kernels.started`): the numpy path then.

    ``order``: the features by position (decreasing length); ``edge``: each feature's
    edge; ``R``, ``RH``: each position's bound (its feature's length, and half of it)
    as the ranking rounds it (:func:`~fcgrasp.pipeline._candidates.lex_survivors`)."""
    from ..core.kernels import jit_setting, started

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
                         np.empty((64, width), np.int64))
    if not ok:
        return None
    rows, n = res
    out: np.ndarray = rows[:n, :width]
    return out
