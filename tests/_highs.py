"""The tests' linear programs, solved by HiGHS through its own Python binding (highspy).

``linprog`` takes the arguments of :func:`scipy.optimize.linprog` that the oracles use
(``c``, ``A_ub``/``b_ub``, ``A_eq``/``b_eq``, ``bounds``; ``method`` is always HiGHS's
dual simplex, as scipy's ``"highs"`` runs it) and answers with scipy's ``status``,
``success``, ``x`` and ``fun``.  The solver is the one scipy wraps; what differs is the
wrapper: scipy checks and converts every option and input on each call (about a
millisecond, four times HiGHS's own time on the oracles' small programs), this one
passes dense columns to one ``Highs`` object kept per process.
``test_oracles.py::test_the_oracles_linprog_is_scipys`` compares the two on seeded
programs (feasible, infeasible, unbounded, degenerate).
"""

from __future__ import annotations

from functools import cache
from types import SimpleNamespace
from typing import Any

import numpy as np

try:
    import highspy
except ImportError:                 # the test extra not installed: scipy's wrapper
    highspy = None

@cache
def _solver() -> Any:
    """The process's one HiGHS object (its model replaced by each program)."""
    h = highspy.Highs()
    h.setOptionValue("output_flag", False)
    h.setOptionValue("simplex_strategy", 1)             # dual simplex, as scipy asks
    return h


def _bounds(bounds: Any, n: int) -> tuple[np.ndarray, np.ndarray]:
    if bounds is None:
        return np.zeros(n), np.full(n, np.inf)
    b = list(bounds)
    if len(b) == 2 and not isinstance(b[0], (tuple, list)) and \
            not isinstance(b[1], (tuple, list)):
        b = [tuple(b)] * n
    if len(b) != n:
        raise ValueError(f"bounds must hold {n} pairs, got {len(b)}")
    lo = np.array([-np.inf if p[0] is None else float(p[0]) for p in b])
    hi = np.array([np.inf if p[1] is None else float(p[1]) for p in b])
    return lo, hi


def linprog(c: Any, A_ub: Any = None, b_ub: Any = None, A_eq: Any = None, b_eq: Any = None,
            bounds: Any = (0, None), method: str = "highs") -> SimpleNamespace:
    """min ``c @ x`` s.t. ``A_ub @ x <= b_ub``, ``A_eq @ x == b_eq``, ``bounds``; scipy's
    answer fields: ``status`` 0 optimal, 2 infeasible, 3 unbounded, 4 otherwise."""
    if highspy is None:
        from scipy.optimize import linprog as scipy_linprog

        return scipy_linprog(c, A_ub=A_ub, b_ub=b_ub, A_eq=A_eq, b_eq=b_eq, bounds=bounds,
                             method="highs")
    c = np.asarray(c, dtype=float).ravel()
    n = c.size
    rows, lo_r, hi_r = [], [], []
    if A_ub is not None and np.size(A_ub):
        a = np.asarray(A_ub, dtype=float).reshape(-1, n)
        rows.append(a)
        lo_r.append(np.full(len(a), -np.inf))
        hi_r.append(np.asarray(b_ub, dtype=float).ravel())
    if A_eq is not None and np.size(A_eq):
        a = np.asarray(A_eq, dtype=float).reshape(-1, n)
        rows.append(a)
        b = np.asarray(b_eq, dtype=float).ravel()
        lo_r.append(b)
        hi_r.append(b)
    A = np.concatenate(rows) if rows else np.zeros((0, n))
    lo_x, hi_x = _bounds(bounds, n)
    inf = highspy.kHighsInf
    lp = highspy.HighsLp()
    lp.num_col_, lp.num_row_ = n, A.shape[0]
    lp.col_cost_ = c
    lp.col_lower_ = np.where(np.isinf(lo_x), -inf, lo_x)
    lp.col_upper_ = np.where(np.isinf(hi_x), inf, hi_x)
    lo = np.concatenate(lo_r) if lo_r else np.zeros(0)
    hi = np.concatenate(hi_r) if hi_r else np.zeros(0)
    lp.row_lower_ = np.where(np.isinf(lo), -inf, lo)
    lp.row_upper_ = np.where(np.isinf(hi), inf, hi)
    nz = A.T != 0                                   # columns of A, dense to sparse
    m = lp.a_matrix_
    m.format_ = highspy.MatrixFormat.kColwise
    m.num_col_, m.num_row_ = n, A.shape[0]
    m.start_ = np.r_[0, np.cumsum(nz.sum(axis=1))].astype(np.int32)
    m.index_ = np.nonzero(nz)[1].astype(np.int32)
    m.value_ = A.T[nz]
    h = _solver()
    h.clearModel()
    h.passModel(lp)
    h.run()
    st = h.getModelStatus()
    S = highspy.HighsModelStatus
    status = {S.kOptimal: 0, S.kInfeasible: 2, S.kUnbounded: 3}.get(st, 4)
    if status != 0:
        return SimpleNamespace(status=status, success=False, x=None, fun=None)
    x = np.array(h.getSolution().col_value)
    return SimpleNamespace(status=0, success=True, x=x,
                           fun=float(h.getInfo().objective_function_value))
