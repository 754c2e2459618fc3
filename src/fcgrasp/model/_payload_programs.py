"""The payload's programs: the largest scale of a wrench set that force-limited contacts
with friction resist, over its vertices or facets (part of :mod:`fcgrasp.model.loads`)."""

from __future__ import annotations

import itertools
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core._checks import (
    FloatArray,
    check_scalar,
)

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


# ----------------------------------------------------------------------------- one grasp


def _limits(force_limit: ArrayLike | None, total_limit: ArrayLike | None, k: int
            ) -> tuple[FloatArray, float]:
    per = np.full(k, np.inf)
    if force_limit is not None:
        try:
            given = np.asarray(force_limit, float)
        except (TypeError, ValueError):
            given = np.full(0, np.nan)
        if given.ndim > 1 or given.size not in (1, k) or not np.all(given > 0):
            raise ValueError(f"force_limit must be a positive number or one per finger "
                             f"({k}), got {force_limit!r}")
        per = np.broadcast_to(given.ravel(), (k,)).astype(float)
    total = np.inf if total_limit is None else check_scalar(total_limit, "total_limit",
                                                            positive=True)
    return per, total


def _cone_edges(n: FloatArray, half: FloatArray) -> FloatArray:
    """(k, 2, 2): the two edges of each finger's cone, scaled to a unit normal part."""
    t = np.stack([-n[:, 1], n[:, 0]], axis=1)
    m = np.tan(half)[:, None]
    return np.stack([n + m * t, n - m * t], axis=1)


def _program(E: FloatArray, W: FloatArray, per: FloatArray, total: float,
             minimize_peak: bool = False) -> Any:
    """The linear program of :func:`grasp_payload`: ``E`` the cone edges' wrenches
    (k, 2, 3) of one grasp, ``W`` the load's vertices (V, 3).  Variables: the scale (or,
    with ``minimize_peak``, the peak normal force at scale 1), then each vertex's cone
    coefficients (V, k, 2); a finger's normal force is the sum of its two."""
    from scipy.optimize import linprog  # on first use

    V, k = len(W), E.shape[0]
    # equilibrium, per vertex: sum of the edges' wrenches = -s w (or -w at scale 1)
    A_eq = np.zeros((V * 3, 1 + V * k * 2))
    A_eq[:, 1:] = np.kron(np.eye(V), E.reshape(k * 2, 3).T)
    if minimize_peak:
        b_eq = -W.reshape(-1)
    else:
        A_eq[:, 0] = W.reshape(-1)
        b_eq = np.zeros(V * 3)
    # normal forces (V * k rows) from the coefficients
    normal = np.kron(np.eye(V * k), np.ones((1, 2)))
    rows, rhs = [], []
    if minimize_peak:
        rows.append(np.c_[-np.ones(V * k), normal])
        rhs.append(np.zeros(V * k))
    limited = np.tile(np.isfinite(per), V)
    if limited.any():
        rows.append(np.c_[np.zeros(limited.sum()), normal[limited]])
        rhs.append(np.tile(per, V)[limited])
    if np.isfinite(total):
        rows.append(np.c_[np.zeros(V), np.kron(np.eye(V), np.ones((1, 2 * k)))])
        rhs.append(np.full(V, total))
    cost = np.zeros(1 + V * k * 2)
    cost[0] = 1.0 if minimize_peak else -1.0
    return linprog(cost, A_ub=np.concatenate(rows) if rows else None,
                   b_ub=np.concatenate(rhs) if rhs else None, A_eq=A_eq, b_eq=b_eq,
                   bounds=[(0, None)] * len(cost), method="highs")


def _wrench_edges(p: FloatArray, E: FloatArray) -> FloatArray:
    """(k, 2, 3): the wrenches of the cone edges ``E`` (k, 2, 2) applied at ``p``."""
    tau = p[:, None, 0] * E[..., 1] - p[:, None, 1] * E[..., 0]
    return np.concatenate([E, tau[..., None]], axis=-1)


def _force_vertices(per: FloatArray, total: float) -> FloatArray | None:
    """(N, k, 2): the vertices of the fingers' cone coefficients allowed by the limits
    (each finger's triangle ``c >= 0, c_1 + c_2 <= per``, cut by ``sum <= total``: the
    product's vertices under the total and the total's crossings of the product's
    edges); None where the set is unbounded."""
    k = len(per)
    per = np.minimum(per, total)                   # the total bounds every finger too
    if not np.all(np.isfinite(per)):
        return None
    tri = [np.array([[0.0, 0.0], [p, 0.0], [0.0, p]]) for p in per]
    out = [c for c in (np.array([tri[i][j] for i, j in enumerate(ch)])
                       for ch in itertools.product(range(3), repeat=k))
           if c.sum() <= total]
    if np.isfinite(total):
        for j in range(k):
            for ch in itertools.product(range(3), repeat=k - 1):
                c = np.array([tri[i][x] for i, x in zip([i for i in range(k) if i != j], ch,
                                                          strict=True)])
                rest = float(c.sum())
                for a, b in ((0, 1), (0, 2)):
                    sa, sb = rest + tri[j][a].sum(), rest + tri[j][b].sum()
                    if (sa - total) * (sb - total) < 0:
                        t = (total - sa) / (sb - sa)
                        out.append(np.insert(c, j, tri[j][a] + t * (tri[j][b] - tri[j][a]),
                                             axis=0))
    return np.array(out)


def _scale(E: FloatArray, W: FloatArray, per: FloatArray, total: float) -> float:
    """The largest scale of one grasp (``E``: its cone edges' wrenches)."""
    res = _program(E, W, per, total)
    if res.status == 3:
        return float("inf")
    if res.status != 0:
        # only s = 0 can fail to be feasible when W is not resisted at all; HiGHS
        # reports that as infeasible or unbounded-or-infeasible
        return 0.0
    return max(0.0, float(-res.fun))
