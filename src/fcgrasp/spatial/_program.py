"""The linear cone programs of solid grasps, solved by Clarabel: one place that sets the
solver up (quiet, no quadratic term)."""

from __future__ import annotations

from typing import Any

import numpy as np


def solve_linear(q: Any, rows: Any, b: Any, cones: list[Any]) -> Any:
    """Minimise ``q . x`` subject to ``b - A x`` in the product of ``cones`` (Clarabel's
    cone types, in the order of ``A``'s ``rows``); Clarabel's solution (``x``, ``z``,
    ``status``, ``obj_val``)."""
    import clarabel
    from scipy import sparse

    n = len(q)
    settings = clarabel.DefaultSettings()
    settings.verbose = False
    return clarabel.DefaultSolver(sparse.csc_matrix((n, n)), np.asarray(q, float),
                                  sparse.csc_matrix(np.array(rows, float)),
                                  np.asarray(b, float), cones, settings).solve()
