"""A dense simplex for the many small linear programs of the planners:
``max c.x`` subject to ``A x <= b``, ``x >= 0``, with a few dozen rows and columns, where
a call of HiGHS through scipy costs about a millisecond of setting up.  Two phases (one
artificial variable raised to the most violated row), Bland's rule for the entering
column, Harris's ratio test (the bound with every row relaxed by
:data:`~fcgrasp.core.tolerances.SIMPLEX_SLACK`, then the largest pivot among the rows
that reach it: a tiny pivot on a degenerate row would blow the tableau up).  Compiled by
numba on first use (the machine code cached beside this file); tested against HiGHS on
thousands of random programs, degenerate ones included (``tests/test_concurrency.py``).
Callers check what they get: the solution of a program is verified by its user against
its own constraints before it is trusted.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ._checks import FloatArray, IntArray
from .jit import CompiledLoops, jit_setting
from .tolerances import LP_TOL, SIMPLEX_PIVOT, SIMPLEX_SLACK

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = ["compiled", "lp_max", "OPTIMAL", "INFEASIBLE", "UNBOUNDED", "ITERATIONS"]

#: Statuses of :func:`lp_max`.
OPTIMAL, INFEASIBLE, UNBOUNDED, ITERATIONS = 0, 1, 2, 3


def _pivot(T: FloatArray, r: int, e: int) -> None:
    rows, cols = T.shape
    inv = 1.0 / T[r, e]
    for j in range(cols):
        T[r, j] *= inv
    T[r, e] = 1.0
    for i in range(rows):
        if i != r:
            f = T[i, e]
            if f != 0.0:
                for j in range(cols):
                    T[i, j] -= f * T[r, j]
                T[i, e] = 0.0


def _iterate(T: FloatArray, basis: IntArray, skip: int, eps: float, slack: float, max_iter: int
             ) -> int:
    """Primal simplex on a feasible tableau (last row the reduced costs of a maximum,
    last column the right-hand sides), Bland's rule: 0 optimal, 2 unbounded, 3 out of
    iterations."""
    m = T.shape[0] - 1
    rhs = T.shape[1] - 1
    for _ in range(max_iter):
        e = -1
        for j in range(rhs):
            if j != skip and T[m, j] < -eps:
                e = j
                break
        if e < 0:
            return 0
        # Harris's ratio test: the bound with every row relaxed by ``slack``, then the
        # largest pivot among the rows that reach it (a tiny pivot on a degenerate row
        # would blow the tableau up); ties by the basis index (Bland)
        bound = np.inf
        for i in range(m):
            if T[i, e] > eps:
                bound = min(bound, (max(T[i, rhs], 0.0) + slack) / T[i, e])
        if bound == np.inf:
            return 2
        r = -1
        for i in range(m):
            if T[i, e] > eps and max(T[i, rhs], 0.0) / T[i, e] <= bound:
                if r < 0 or T[i, e] > T[r, e] or (T[i, e] == T[r, e] and basis[i] < basis[r]):
                    r = i
        _pivot(T, r, e)
        basis[r] = e
        for i in range(m):               # what Harris's test lets dip below zero
            if T[i, rhs] < 0.0:
                T[i, rhs] = 0.0
    return 3


def _lp_max(c: FloatArray, A: FloatArray, b: FloatArray, m: int, n: int, x: FloatArray,
            y: FloatArray, eps: float, feas: float) -> int:
    """``max c.x`` subject to ``A[:m, :n] x <= b[:m]``, ``x >= 0`` (two phases: one
    artificial variable raised to the most violated row, Bland's rule): 0 optimal (``x``
    filled, and ``y[:m]`` with the rows' multipliers: the reduced costs of their slacks),
    1 infeasible, 2 unbounded, 3 out of iterations."""
    ncol = n + m + 1
    art = n + m
    T = np.zeros((m + 1, ncol + 1))
    basis = np.empty(m, dtype=np.int64)
    low = 0
    for i in range(m):
        for j in range(n):
            T[i, j] = A[i, j]
        T[i, n + i] = 1.0
        T[i, art] = -1.0
        T[i, ncol] = b[i]
        basis[i] = n + i
        if b[i] < b[low]:
            low = i
    max_iter = 50 * (m + n) + 100
    if m > 0 and b[low] < 0.0:
        T[m, art] = 1.0                       # maximise -x0
        _pivot(T, low, art)
        basis[low] = art
        status = _iterate(T, basis, -1, eps, SIMPLEX_SLACK, max_iter)
        if status == 3:
            return 3
        if status != 0 or T[m, ncol] < -feas:
            return 1
        for i in range(m):
            if basis[i] == art:               # at zero: pivot it out where possible
                for j in range(n + m):
                    if abs(T[i, j]) > eps:
                        _pivot(T, i, j)
                        basis[i] = j
                        break
    for j in range(ncol + 1):
        T[m, j] = 0.0
    for j in range(n):
        T[m, j] = -c[j]
    for i in range(m):
        j = basis[i]
        if j < n and T[m, j] != 0.0:
            f = T[m, j]
            for k in range(ncol + 1):
                T[m, k] -= f * T[i, k]
            T[m, j] = 0.0
    status = _iterate(T, basis, art, eps, SIMPLEX_SLACK, max_iter)
    if status != 0:
        return status
    for j in range(n):
        x[j] = 0.0
    for i in range(m):
        if basis[i] < n:
            x[basis[i]] = T[i, ncol]
        y[i] = T[m, n + i]
    return 0


_LOOPS = CompiledLoops(globals(), (_pivot, _iterate, _lp_max))


def compiled() -> dict[str, Any] | None:
    """The compiled loops (``"_lp_max"`` and what it calls), None without a working
    numba or with ``FCGRASP_JIT=0``."""
    if jit_setting() is False:
        return None
    return _LOOPS.get()


def lp_max(c: ArrayLike, A: ArrayLike, b: ArrayLike, eps: float = SIMPLEX_PIVOT,
           feas: float = LP_TOL) -> tuple[int, np.ndarray]:
    """``max c.x`` subject to ``A x <= b``, ``x >= 0``: ``(status, x)`` with the statuses
    :data:`OPTIMAL` (``x`` filled), :data:`INFEASIBLE`, :data:`UNBOUNDED`,
    :data:`ITERATIONS`; run compiled when numba is there (:func:`compiled`), else as
    plain Python (slow: for the tests and a numba-less install).

    >>> st, x = lp_max([1.0, 1.0], [[1.0, 2.0], [3.0, 1.0]], [4.0, 6.0])
    >>> st, x.round(6).tolist()
    (0, [1.6, 1.2])
    """
    c = np.ascontiguousarray(c, float)
    A = np.ascontiguousarray(A, float).reshape(-1, len(c))
    b = np.ascontiguousarray(b, float)
    if b.shape != (len(A),):
        raise ValueError(f"b must hold one bound per row of A ({len(A)}), got shape {b.shape}")
    m, n = A.shape
    loops = compiled()
    run = _lp_max if loops is None else loops["_lp_max"]
    x, y = np.zeros(n), np.zeros(m)
    st = int(run(c, A, b, m, n, x, y, float(eps), float(feas)))
    return st, x
