"""The linear programs of frictionless fingers along the boundary: theorem 7.1 on every
combination of covered edges (the vertex lemma), solved compiled or by HiGHS, and the
leximin levels (part of :mod:`fcgrasp.model.frictionless_stretches`)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core import _simplex
from ..core._angles import margin_radians
from ..core._checks import FloatArray
from ..core._geom import cross2 as _cross
from ..core.tolerances import (
    CHECK_TOL,
    NOISE_ROW,
    RANK_TOL,
    SIMPLEX_PIVOT,
    TINY,
    TOL,
)
from . import _frictionless_kernels
from ._regiongeom import four_finger_geometry
from .polygon import Polygon

if TYPE_CHECKING:
    pass


#: Kinds of covered edge in a region: the only one, the first, the last, inside.
_SINGLE, _FIRST, _LAST, _INSIDE = range(4)


@dataclass
class _Config:
    """The linear system of one configuration: ``A x <= b`` over
    ``x = (lo_0, hi_0, .., lo_k, hi_k)`` (the first piece starts at ``lo`` on the first
    edge, the last ends at ``hi`` on the last, arc lengths from each edge's start), the
    bounds of ``x``, and each region's length as ``hi - lo + const``."""

    edges: tuple[tuple[int, ...], ...]
    A: FloatArray
    b: FloatArray
    bounds: list[tuple[float, float]]
    const: FloatArray
    #: the compiled loop's rows before those without a variable are left out (a move
    #: from here copies the rows of the combinations it keeps), None from numpy
    rows: tuple[FloatArray, FloatArray] | None = None


def _stretch_facts(polygon: Polygon, st: tuple[int, ...]
                   ) -> tuple[float, float, float, float]:
    """A stretch's first and last edges' lengths, the length of the edges before its
    last (a region's constant, 0 for one edge) and its arc length (a bound on the
    region it holds)."""
    L = polygon.lengths
    Lf, Ll = float(L[st[0]]), float(L[st[-1]])
    const = Lf + float(sum(L[list(st[1:-1])])) if len(st) > 1 else 0.0
    return Lf, Ll, const, float(L[list(st)].sum())


def _system(polygon: Polygon, edges: tuple[tuple[int, ...], ...], pairing: np.ndarray,
            mode: str, margin: float, gravity: FloatArray | None,
            compiled: bool = True, facts: Callable[[tuple[int, ...]], Any] | None = None,
            arrays: Any = None, parent: _Config | None = None, checked: bool = False
            ) -> _Config | None:
    """Theorem 7.1 on every combination of covered edges (the vertex lemma), or None
    when some combination's pairing is null or its sector narrower than the margin.
    The rows come from the compiled loop of :mod:`._frictionless_kernels` where it runs
    and ``compiled``, else from numpy (:func:`_rows_numpy`, the reference).
    ``facts(stretch)``: :func:`_stretch_facts` of a stretch, remembered by a search
    that meets each stretch in many configurations; ``arrays``: the compiled loop's
    :func:`~._frictionless_kernels.edge_arrays`, built once by such a search;
    ``parent``: a configuration of the same pairing and orientation one move away,
    whose rows of the combinations both have are copied (the same numbers);
    ``checked``: ``compiled`` says the compiled loop runs (a search asked once)."""
    k = len(edges)
    s = 1.0 if mode == "+C" else -1.0
    from_parent = None if parent is None or parent.rows is None else \
        (parent.edges, *parent.rows)
    got = _frictionless_kernels.system_rows(
        polygon, edges, gravity, pairing, float(margin_radians(margin)), s, TOL,
        arrays, from_parent, checked) if compiled else None
    if got is False:
        return None
    compiled_rows = None
    if got is not None:
        A, bvec, some_fixed = got
        compiled_rows = (A, bvec)
        if some_fixed:              # the rows without a variable checked and left out
            kept = _frictionless_kernels.kept_rows(A, bvec, -RANK_TOL * polygon.size)
            if kept is False:
                return None
            if kept is not None:
                (A, bvec), some_fixed = kept, False
    else:
        rows = _rows_numpy(polygon, edges, gravity, pairing, margin, s)
        if rows is None:
            return None
        A, bvec = rows
        some_fixed = True
    # rows without a variable (the compiled loop says whether there are any, and
    # checks and drops them itself where it runs) are checked here, not handed to the
    # solver
    if some_fixed:
        fixed = ~A.any(axis=1)
        if fixed.any():
            if np.any(bvec[fixed] < -RANK_TOL * polygon.size):
                return None
            A, bvec = A[~fixed], bvec[~fixed]
    bounds = []
    const = np.zeros(k)
    for f, st in enumerate(edges):
        Lf, Ll, const[f], _ = facts(st) if facts is not None else _stretch_facts(polygon, st)
        bounds += [(0.0, Lf), (0.0, Ll)]
    return _Config(edges, A, bvec, bounds, const, compiled_rows)


def _rows_numpy(polygon: Polygon, edges: tuple[tuple[int, ...], ...], gravity: FloatArray | None,
                pairing: np.ndarray, margin: float, s: float
                ) -> tuple[FloatArray, FloatArray] | None:
    """Theorem 7.1's two rows per combination of covered edges, by numpy: ``(A, rhs)``,
    or None when some combination's pairing is null or its sector narrower than the
    margin."""
    k = len(edges)
    # every combination, in the order of itertools.product (the last finger fastest)
    combos = np.indices([len(e) for e in edges]).reshape(k, -1).T
    C = len(combos)
    nf = 4
    a = np.empty((C, nf, 2))
    b = np.empty((C, nf, 2))
    center = np.empty((C, nf))
    kind = np.full((C, nf), -1)
    for f, st in enumerate(edges):
        e = np.array(st)[combos[:, f]]
        a[:, f] = polygon.starts[e]
        b[:, f] = polygon.ends[e]
        n = polygon.normals[e]
        center[:, f] = np.arctan2(-n[:, 1], -n[:, 0])
        pos = combos[:, f]
        m = len(st) - 1
        kind[:, f] = np.where(m == 0, _SINGLE, np.where(pos == 0, _FIRST,
                                                        np.where(pos == m, _LAST, _INSIDE)))
    if gravity is not None:
        a[:, 3] = b[:, 3] = polygon.centroid
        center[:, 3] = np.arctan2(gravity[1], gravity[0])
    perm = np.broadcast_to(pairing, (C, nf)).copy()
    o12, o34, vel, L, k1, k2, hm, valid = four_finger_geometry(
        a, b, center, perm, margin_radians(margin))
    if not np.all(valid & (hm > 0)):
        return None
    k1, k2 = s * k1, s * k2
    nv = 2 * k
    rows_A, rows_b = [], []
    phis: tuple[Callable[[FloatArray], FloatArray], ...] = (lambda x: _cross(k1, x),
                                                          lambda x: -_cross(k2, x))
    for phi in phis:
        A = np.zeros((C, nv))
        rhs = phi(o34) - phi(o12)
        for p in range(4):
            f = int(pairing[p])
            if f >= k:                      # gravity: a fixed point
                continue
            c = phi(vel[:, p])
            use_hi = c > 0 if p < 2 else c <= 0
            g = c if p < 2 else -c
            kd = kind[:, f]
            hi_var = use_hi & ((kd == _SINGLE) | (kd == _LAST))
            lo_var = ~use_hi & ((kd == _SINGLE) | (kd == _FIRST))
            const = np.where(use_hi & ((kd == _FIRST) | (kd == _INSIDE)), L[:, p], 0.0)
            A[:, 2 * f + 1] += np.where(hi_var, g, 0.0)
            A[:, 2 * f] += np.where(lo_var, g, 0.0)
            rhs = rhs - g * const
        rows_A.append(A)
        rows_b.append(rhs)
    return np.concatenate(rows_A), np.concatenate(rows_b)


def _lp(cfg: _Config, objective: FloatArray, floors: FloatArray, t_var: bool
        ) -> tuple[float, FloatArray] | None:
    """Maximise ``objective @ (x, t)`` with each region at least ``floors[f]`` long,
    or at least ``t`` where ``floors[f]`` is nan (``t_var``)."""
    k = len(cfg.edges)
    nv = 2 * k + 1
    simplex = _simplex.compiled() is not None
    if simplex and COMPILED_LP:
        # the same program, built, scaled and solved in one compiled call
        his = [hi for _, hi in cfg.bounds]
        ub = np.array(his)
        unit = max(float(max(his)), TINY)
        cols = 2 * k + 1 if t_var else 2 * k
        one = _frictionless_kernels.lp_rows(
            cfg.A, cfg.b, cfg.const, floors, ub, objective[:cols], t_var, unit, NOISE_ROW,
            TINY, CHECK_TOL, SIMPLEX_PIVOT, DIRECT_ROWS, ROWS_PER_ROUND, checked=True)
        if one is not None and one[0] == _simplex.INFEASIBLE:
            return None
        if one is not None and one[0] == _simplex.OPTIMAL:
            x = one[1] * unit if t_var else np.r_[one[1] * unit, 0.0]
            return float(objective @ x), x
        simplex = one is None           # undecided by the simplex: HiGHS decides
    rows = [np.c_[cfg.A, np.zeros(len(cfg.A))]]
    rhs = [cfg.b]
    for f in range(k):
        r = np.zeros(nv)
        r[2 * f], r[2 * f + 1] = 1.0, -1.0          # -(hi - lo) ...
        if np.isnan(floors[f]):
            r[-1] = 1.0                              # ... + t <= const
            rhs.append(np.array([cfg.const[f]]))
        else:
            rhs.append(np.array([cfg.const[f] - floors[f]]))
        rows.append(r[None])
    A, b = np.concatenate(rows), np.concatenate(rhs)
    if simplex:
        got = _lp_simplex(cfg, A, b, objective, t_var)
        if got is None or isinstance(got, tuple):
            return got
        # a row of rounding noise, the simplex out of iterations, or an answer that does
        # not hold: HiGHS decides
    from scipy.optimize import linprog  # on first use: two-finger plans never load scipy

    # in units of the longest edge, rows scaled to a largest coefficient of 1 (rounding
    # noise left as it is): HiGHS's absolute tolerances then mean the same on any scale
    unit, M, scaled_b, _ = _scaled(cfg, A, b, len(objective))
    res = linprog(-objective, A_ub=M, b_ub=scaled_b,
                  bounds=[*((lo / unit, hi / unit) for lo, hi in cfg.bounds),
                          (0.0, None) if t_var else (0.0, 0.0)],
                  method="highs")
    if res.status != 0:
        return None
    x = res.x * unit
    return float(objective @ x), x


def _scaled(cfg: _Config, A: FloatArray, b: FloatArray, cols: int
            ) -> tuple[float, FloatArray, FloatArray, np.ndarray]:
    """The program ``A x <= b`` (its first ``cols`` columns) in units of the longest
    edge of ``cfg`` (``x = unit * y``), each row divided by its largest coefficient
    unless that is rounding noise (below :data:`~fcgrasp.core.tolerances.NOISE_ROW` of
    the largest: scaling it up would make the noise a constraint): ``(unit, rows,
    right-hand sides, which rows are noise)``."""
    unit = max(float(max(hi for _, hi in cfg.bounds)), TINY)
    As = A[:, :cols] * unit
    norm = np.abs(As).max(axis=1)
    noise = norm <= NOISE_ROW * max(float(norm.max(initial=0.0)), TINY)
    scale = np.where(noise, unit, norm)
    return unit, As / scale[:, None], b / scale, noise


def _lp_simplex(cfg: _Config, A: FloatArray, b: FloatArray, objective: FloatArray,
                t_var: bool) -> tuple[float, FloatArray] | None | bool:
    """:func:`_lp` by the compiled dense simplex (:mod:`fcgrasp.core._simplex`): in
    units of the longest edge, each row scaled to a largest coefficient of 1, the upper
    bounds as rows (``x >= 0`` is the simplex's own), ``t``'s column dropped when it is
    not a variable.  False where it does not decide: a row whose coefficients are
    rounding noise (below :data:`~fcgrasp.core.tolerances.NOISE_ROW` of the largest:
    scaling it up would make the noise a constraint), the simplex out of iterations, or
    an answer that misses the rows as given."""
    k = len(cfg.edges)
    nx = 2 * k
    ub = np.array([hi for _, hi in cfg.bounds])
    cols = nx + 1 if t_var else nx
    unit, M, scaled_b, noise = _scaled(cfg, A, b, cols)
    if np.any(noise):
        return False
    full = np.zeros((len(A) + nx, cols))
    full[:len(A)] = M
    full[len(A):, :nx] = np.eye(nx)
    rhs = np.r_[scaled_b, ub / unit]
    st, y = _rows_generated(objective[:cols], full, rhs, len(A) - k)
    if st == _simplex.INFEASIBLE:
        return None
    if st != _simplex.OPTIMAL or np.any(full @ y > rhs + CHECK_TOL):
        return False
    x = y * unit if t_var else np.r_[y * unit, 0.0]
    return float(objective @ x), x


#: Whether :func:`_lp` runs its program in one compiled call
#: (:func:`fcgrasp.model._frictionless_kernels.lp_rows`) where numba runs; False: the
#: numpy steps (the reference, kept for the tests).
COMPILED_LP = True


#: A program with more rows than this is solved on a subset of them, the rows its
#: solution violates added until it violates none (:func:`_rows_generated`).
DIRECT_ROWS = 64


#: Rows added per round of :func:`_rows_generated`, per variable.
ROWS_PER_ROUND = 2


def _rows_generated(c: FloatArray, A: FloatArray, b: FloatArray, n_cut: int
                    ) -> tuple[int, FloatArray]:
    """``max c.x`` subject to ``A x <= b``, ``x >= 0`` by the dense simplex, where the
    first ``n_cut`` rows (the vertex lemma's, up to thousands for long stretches of a
    smooth outline) are taken as needed: the program is solved on the other rows and
    the ``ROWS_PER_ROUND`` rows per variable most violated at the origin, then again with
    the rows its solution violates most (by more than the simplex's own feasibility
    tolerance) until it violates none.  The answer solves the whole program: it is
    optimal for a relaxation and feasible for the program (a relaxation that is
    infeasible, the program is too).  Programs of at most :data:`DIRECT_ROWS` rows are
    solved as they are."""
    feas = CHECK_TOL / 10
    if len(A) <= DIRECT_ROWS or n_cut <= 0:
        return _simplex.lp_max(c, A, b, feas=feas)
    per_round = ROWS_PER_ROUND * A.shape[1]
    active = np.zeros(len(A), dtype=bool)
    active[n_cut:] = True
    active[_smallest(b[:n_cut], per_round)] = True
    while True:
        rows = np.flatnonzero(active)
        st, y = _simplex.lp_max(c, A[rows], b[rows], feas=feas)
        if st != _simplex.OPTIMAL:
            return st, y
        over = A[:n_cut] @ y - b[:n_cut]
        over[active[:n_cut]] = -np.inf
        worst = _smallest(-over, per_round)
        worst = worst[over[worst] > feas]
        if not worst.size:
            return st, y
        active[worst] = True


def _smallest(v: FloatArray, k: int) -> np.ndarray:
    """``np.argsort(v, kind="stable")[:k]`` without sorting all of ``v``: the values up
    to the ``k``-th smallest (ties included, in index order) sorted stably."""
    if len(v) <= k:
        return np.argsort(v, kind="stable")
    kth = np.partition(v, k - 1)[k - 1]
    if np.isnan(kth):
        return np.argsort(v, kind="stable")[:k]
    near = np.flatnonzero(v <= kth)
    return near[np.argsort(v[near], kind="stable")[:k]]


def _lengths(cfg: _Config, x: FloatArray) -> FloatArray:
    k = len(cfg.edges)
    return np.array([x[2 * f + 1] - x[2 * f] + cfg.const[f] for f in range(k)])


def _length_objective(k: int, fingers: Any = None) -> FloatArray:
    """``(x, t)`` weights of the summed lengths (less their constants) of the given
    fingers (default all), or of ``t`` alone with ``fingers=()``."""
    obj = np.zeros(2 * k + 1)
    if fingers is not None and not len(fingers):
        obj[-1] = 1.0
        return obj
    for f in range(k) if fingers is None else fingers:
        obj[2 * f + 1], obj[2 * f] = 1.0, -1.0
    return obj


def _first_level(cfg: _Config) -> float | None:
    """The largest smallest region of a configuration (None: no regions)."""
    k = len(cfg.edges)
    got = _lp(cfg, _length_objective(k, ()), np.full(k, np.nan), True)
    return None if got is None or got[0] <= 0 else got[0]


def _total(cfg: _Config, t: float) -> float:
    """The largest total length with every region at least ``t`` (nearly) long."""
    k = len(cfg.edges)
    more = _lp(cfg, _length_objective(k), np.full(k, t * (1 - RANK_TOL / 4)), False)
    return t * k if more is None else more[0] + float(cfg.const.sum())


def _leximin(cfg: _Config) -> FloatArray | None:
    """End positions at the leximin optimum (definition 7.1): raise the smallest
    region, fix those that cannot grow further, repeat."""
    k = len(cfg.edges)
    floors = np.full(k, np.nan)
    x = None
    while np.isnan(floors).any():
        got = _lp(cfg, _length_objective(k, ()), floors, True)
        if got is None:
            return x
        t, x = got
        t_floor = t * (1 - RANK_TOL / 4)
        free = np.flatnonzero(np.isnan(floors))
        stuck = []
        for f in free:
            fl = np.where(np.isnan(floors), t_floor, floors)
            best = _lp(cfg, _length_objective(k, [f]), fl, False)
            if best is None or best[0] + cfg.const[f] <= t * (1 + RANK_TOL / 4):
                stuck.append(f)
        for f in (stuck or list(free)):
            floors[f] = t_floor
    last = _lp(cfg, _length_objective(k), np.where(np.isnan(floors), 0.0, floors), False)
    return x if last is None else last[1]


def _polyline(polygon: Polygon, st: tuple[int, ...], lo: float, hi: float) -> FloatArray:
    first, last = st[0], st[-1]
    pts = [polygon.starts[first] + lo * polygon.tangents[first]]
    pts += [polygon.starts[e] for e in st[1:]]
    pts.append(polygon.starts[last] + hi * polygon.tangents[last])
    return np.array(pts)
