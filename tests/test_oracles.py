"""The tests' own linear programs (:mod:`tests._highs`) against scipy's ``linprog``."""

import numpy as np
import pytest
from scipy.optimize import linprog as scipy_linprog

from ._highs import linprog


@pytest.mark.parametrize("cases", [pytest.param(400, id="seeded"),
                                   pytest.param(4000, id="sweep", marks=pytest.mark.slow)])
def test_the_oracles_linprog_is_scipys(cases):
    """Seeded programs of 1-8 variables with inequalities, equalities or both, free,
    signed and boxed variables, integer data (degenerate vertices, ties), infeasible
    and unbounded ones among them: the same status (a program infeasible with an
    unbounded ray is either), and where optimal the same value
    to 1e-9 and a point that is feasible to 1e-9."""
    rng = np.random.default_rng(5)
    seen = {0: 0, 2: 0, 3: 0}
    for _ in range(cases):
        n = int(rng.integers(1, 9))
        m_ub, m_eq = int(rng.integers(0, 12)), int(rng.integers(0, 3))
        draw = (lambda *s: rng.integers(-3, 4, s).astype(float)) if rng.random() < 0.4 \
            else (lambda *s: rng.standard_normal(s))
        c = draw(n)
        A_ub, b_ub = (draw(m_ub, n), draw(m_ub) + 1.0) if m_ub else (None, None)
        A_eq, b_eq = (draw(m_eq, n), draw(m_eq)) if m_eq else (None, None)
        kind = rng.integers(4)
        bounds = [(0, None)] * n if kind == 0 else (None, None) if kind == 1 else \
            (-2.0, 3.0) if kind == 2 else \
            [(None, 1.0) if rng.random() < 0.5 else (-1.0, None) for _ in range(n)]
        want = scipy_linprog(c, A_ub=A_ub, b_ub=b_ub, A_eq=A_eq, b_eq=b_eq, bounds=bounds,
                             method="highs")
        got = linprog(c, A_ub=A_ub, b_ub=b_ub, A_eq=A_eq, b_eq=b_eq, bounds=bounds)
        # (a program both infeasible and with an unbounded ray may be called either)
        assert got.status == want.status or min(got.status, want.status) > 0, (got, want)
        if want.status in seen:
            seen[want.status] += 1
        if want.status != 0:
            continue
        assert got.success and abs(got.fun - want.fun) <= 1e-9 * max(1.0, abs(want.fun))
        x = got.x
        if A_ub is not None:
            assert np.all(A_ub @ x <= b_ub + 1e-9)
        if A_eq is not None:
            assert np.allclose(A_eq @ x, b_eq, atol=1e-9)
    assert min(seen.values()) >= cases // 40, seen
