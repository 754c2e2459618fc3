r"""Regions along the boundary for three and four frictionless fingers.

A *stretch* is a connected piece of one boundary ring (see :mod:`fcgrasp.model.stretches`);
strictly inside an edge a finger pushes along the edge's inward normal, at a vertex
strictly inside a stretch along **any** direction between the two edges' normals.

**The vertex lemma (why a finite check is exact).**  A frictionless contact at a point
``p`` pushing along ``f`` exerts the wrench :math:`w(p, f) = (f, p \times f)`: affine in
``p`` along an edge (``f`` fixed) and linear in ``f`` at a vertex (``p`` fixed).  Force
closure does not change when a wrench is scaled by a positive factor, and the
directions between ``f_k`` and ``f_{k+1}`` (an angle below pi) are the positive
combinations of the two, so up to scale a region exerts the wrenches of a *polygonal
chain*: from ``w(x_0, f)`` to ``w(v, f)`` along each piece of edge, from ``w(v, f_k)``
to ``w(v, f_{k+1})`` at each vertex ``v`` inside it.  A grasp is not force closure iff
a twist ``t != 0`` has :math:`t \cdot w_i \le 0` for every finger (theorem 6.1, the
repelling twists).  So *some* grasp of the regions fails iff some ``t != 0`` has, for
every finger, :math:`\min_{chain_i} t \cdot w \le 0`; a linear function's minimum
over a chain is reached at one of the chain's vertices.  Hence: **every grasp of the
regions is force closure iff every choice of chain vertices is**, that is, the region
ends with their edges' normals and every vertex inside a region with each of its two
edges' normals.  Grouped by the normal they carry, these are the ends of the pieces
of each covered edge inside the region: the regions hold iff, for every choice of one
covered edge per finger, those pieces hold as single-edge regions (theorem 7.1).  (A
contact with friction is two wrenches at one point and the lemma does not apply; two
fingers with friction are solved in :mod:`fcgrasp.model.stretches`.)  Gravity, as the third
"finger" of three, is one fixed wrench.

**The optimum of a configuration.**  A configuration fixes the covered edges of every
finger; only the first and the last piece of each region move.  For one pairing of the
fingers and one orientation of the two-sided cone (``"+C"``: ``P34 - P12`` in
``C = C_12 & -C_34`` shrunk by the margin, ``"-C"``: in ``-C``), theorem 7.1 on every
combination of covered edges is two linear inequalities in the end positions (the
functionals of :mod:`fcgrasp.model.regions` take, on each piece, the end their sign selects).
The largest smallest region and then the leximin levels (definition 7.1) are linear
programs (scipy's HiGHS): exact for the configuration, pairing and orientation.

**The search: a proven safe plan, a lower bound on the optimum.**  Configurations grow
as ``n**8``; instead each of the best single-edge plans is *grown*: at each step every
extension of one region by one edge, at either end, that keeps the fingers on distinct
edges is solved, and the best one that improves (the smallest region, then the total
length) is taken, until none improves; the best grown configurations are then *polished*:
where no single move improves, the best improving pair of moves on two regions (each
slid by one edge) is taken and the growth goes on (on a 24-edge ellipse
the four regions of four edges each are reached only by sliding two regions at once).
Every returned plan holds (the lemma) and ranks at least as high as the single-edge
plan it grew from; it can miss a configuration that is reached only through worse
ones.  ``benchmarks/bench_stretches.py`` measures that gap
against the exhaustive enumeration (:func:`all_frictionless_stretches`: feasible
configurations are closed under dropping an end edge, so growing every feasible single
edge set by one edge at a time reaches every one of them).  The tests sample every
returned region, vertices inside with every normal between their edges', with the
general force-closure test.
"""

from __future__ import annotations

import math
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core import _simplex, budget
from ..core._angles import margin_radians
from ..core._checks import FloatArray, check_scalar
from ..core._geom import cross2 as _cross
from ..core._geom import trim_vertex_ends
from ..core.sectors import PAIRINGS
from ..core.tolerances import (
    CHECK_TOL,
    NOISE_ROW,
    RANK_TOL,
    ROUND_TOL,
    SIMPLEX_PIVOT,
    TINY,
    TOL,
)
from . import _frictionless_kernels
from ._regiongeom import four_finger_geometry
from .polygon import Polygon
from .regions import DEFAULT_MARGIN_DEG

__all__ = ["FrictionlessStretches", "frictionless_stretch_regions", "grow_stretches",
           "all_frictionless_stretches", "MAX_COMBINATIONS"]

#: A configuration is solved only when its combinations of covered edges (one per
#: finger) are at most this many (one pair of inequalities each).
MAX_COMBINATIONS = 4096

#: Systems a search keeps (:class:`_Search`): the memory of a growth is bounded by this
#: many systems of :data:`MAX_COMBINATIONS` combinations, whatever the part.
KEEP_SYSTEMS = 64

#: Kinds of covered edge in a region: the only one, the first, the last, inside.
_SINGLE, _FIRST, _LAST, _INSIDE = range(4)

MODES = ("+C", "-C")


@dataclass(frozen=True)
class FrictionlessStretches:
    """Independent regions along the boundary for frictionless fingers.

    ``region_edges[i]`` lists the edges finger ``i`` covers in ring order,
    ``regions[i]`` is its polyline ``(m_i, 2)`` from one end to the other,
    ``lengths[i]`` its arc length; ``pairing`` and ``mode`` name the two-sided cone of
    theorem 7.1 that certifies them (the pairing indexes the fingers, gravity last).
    """

    region_edges: tuple[tuple[int, ...], ...]
    regions: tuple[FloatArray, ...]
    lengths: tuple[float, ...]
    pairing: tuple[int, ...]
    mode: str

    @property
    def min_length(self) -> float:
        return float(min(self.lengths))


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
    else:
        rows = _rows_numpy(polygon, edges, gravity, pairing, margin, s)
        if rows is None:
            return None
        A, bvec = rows
        some_fixed = True
    # rows without a variable (the compiled loop says whether there are any) are
    # checked here, not handed to the solver
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


def _rows_numpy(polygon: Polygon, edges: tuple[tuple[int, ...], ...], gravity: Any,
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


def _result(polygon: Polygon, cfg: _Config, x: FloatArray, pairing: np.ndarray,
            mode: str) -> FrictionlessStretches:
    x = np.asarray(x)[:2 * len(cfg.edges)]
    lines, covered = [], []
    tiny = ROUND_TOL * polygon.size
    for f, st in enumerate(cfg.edges):
        # a sub-region of the certified one: it holds
        pts, edges = trim_vertex_ends(_polyline(polygon, st, x[2 * f], x[2 * f + 1]), st,
                                      tiny)
        lines.append(pts)
        covered.append(edges)
    return FrictionlessStretches(tuple(covered), tuple(lines),
                                 tuple(float(v) for v in _lengths(cfg, x)),
                                 tuple(int(p) for p in pairing), mode)


def _check(polygon: Any, region_edges: Any, margin: Any, gravity: Any
           ) -> tuple[tuple[tuple[int, ...], ...], float, FloatArray | None]:
    if not isinstance(polygon, Polygon):
        raise TypeError(f"polygon must be a fcgrasp.Polygon, got {type(polygon).__name__}")
    margin = check_scalar(margin, "margin", nonnegative=True)
    g = None
    if gravity is not None:
        g = np.asarray(gravity, dtype=float)
        if g.shape != (2,) or not np.all(np.isfinite(g)) or not np.any(g != 0):
            raise ValueError(f"gravity must be a nonzero direction (gx, gy), got {gravity!r}")
    want = 3 if g is not None else 4
    if isinstance(region_edges, (str, bytes)) or len(region_edges) != want:
        raise ValueError(f"region_edges must hold {want} stretches (one per finger"
                         f"{', gravity is the fourth' if g is not None else ''}), "
                         f"got {region_edges!r}")
    edges = tuple(polygon.check_stretch(st, f"region_edges[{i}]")
                  for i, st in enumerate(region_edges))
    flat = [e for st in edges for e in st]
    if len(set(flat)) != len(flat):
        raise ValueError(f"region_edges must not share an edge, got {region_edges!r}")
    return edges, margin, g


class _Search:
    """Configurations solved so far (one part, margin and gravity): a configuration is
    keyed by its covered edges, pairing and orientation; its first level (the largest
    smallest region) and, for ties only, its largest total length are kept."""

    def __init__(self, polygon: Polygon, margin: float, gravity: FloatArray | None) -> None:
        self.polygon, self.margin, self.gravity = polygon, margin, gravity
        #: each configuration's first level (None: no regions)
        self.level: dict[tuple[Any, ...], float | None] = {}
        #: the systems of the configurations solved last, at most :data:`KEEP_SYSTEMS`
        #: (a system holds two rows per combination of covered edges, up to
        #: :data:`MAX_COMBINATIONS`; one is rebuilt when asked for again)
        self._systems: OrderedDict[tuple[Any, ...], _Config] = OrderedDict()
        self.totals: dict[tuple[Any, ...], float] = {}
        self._facts: dict[tuple[int, ...], tuple[float, float, float, float]] = {}
        self._arrays: Any = None
        #: whether the programs' rows come from the compiled loop (asked once)
        self.compiled = _frictionless_kernels.COMPILED.available()

    def facts(self, st: tuple[int, ...]) -> tuple[float, float, float, float]:
        """:func:`_stretch_facts` of a stretch, once per search (a stretch is met again
        in every move of the other regions)."""
        got = self._facts.get(st)
        if got is None:
            got = self._facts[st] = _stretch_facts(self.polygon, st)
        return got

    def arrays(self) -> Any:
        """The compiled rows' :func:`~._frictionless_kernels.edge_arrays`, once per
        search."""
        if self._arrays is None:
            self._arrays = _frictionless_kernels.edge_arrays(self.polygon, self.gravity)
        return self._arrays

    def solve(self, edges: tuple[tuple[int, ...], ...], pairing: int, mode: str,
              parent: tuple[Any, ...] | None = None) -> float | None:
        """The configuration's first level (None: no regions), solved once (its system
        then kept among the last :data:`KEEP_SYSTEMS`: :meth:`system`);
        ``parent``: the key of a solved configuration one move away (the same pairing
        and orientation), whose rows it shares are copied."""
        key = (edges, pairing, mode)
        if key not in self.level:
            cfg = self._build(key, parent)
            t = None if cfg is None else _first_level(cfg)
            self.level[key] = t
            if cfg is not None and t is not None:
                self._keep(key, cfg)
        return self.level[key]

    def _build(self, key: tuple[Any, ...], parent: tuple[Any, ...] | None = None
               ) -> _Config | None:
        """The system of a configuration (``parent``'s rows copied where it is kept)."""
        edges, pairing, mode = key
        near = None if parent is None else self._systems.get(parent)
        return _system(self.polygon, edges, PAIRINGS[pairing], mode, self.margin,
                       self.gravity, compiled=self.compiled, facts=self.facts,
                       arrays=self.arrays(), parent=near, checked=True)

    def _keep(self, key: tuple[Any, ...], cfg: _Config) -> None:
        self._systems[key] = cfg
        self._systems.move_to_end(key)
        while len(self._systems) > KEEP_SYSTEMS:
            self._systems.popitem(last=False)

    def system(self, key: tuple[Any, ...]) -> _Config:
        """The system of a configuration that holds regions (rebuilt if not kept: the
        same rows)."""
        cfg = self._systems.get(key)
        if cfg is None:
            cfg = self._build(key)
            assert cfg is not None
        self._keep(key, cfg)
        return cfg

    def reach(self, edges: tuple[tuple[int, ...], ...]) -> float:
        """The shortest stretch's arc length: a bound on the smallest region."""
        return min(self.facts(st)[3] for st in edges)

    def total(self, key: tuple[Any, ...], t: float) -> float:
        if key not in self.totals:
            self.totals[key] = _total(self.system(key), t)
        return self.totals[key]

    def better(self, a: tuple[Any, ...], b: tuple[Any, ...] | None) -> bool:
        """Configuration ``a`` beats ``b`` (keys of solved ones): a longer smallest
        region, or, tied, a longer total."""
        if b is None:
            return True
        ta, tb = self.level[a], self.level[b]
        assert ta is not None and tb is not None
        if ta > tb * (1 + RANK_TOL):
            return True
        if ta < tb * (1 - RANK_TOL):
            return False
        return self.total(a, ta) > self.total(b, tb) * (1 + RANK_TOL)

    def seed(self, edges: tuple[tuple[int, ...], ...]) -> tuple[Any, ...] | None:
        """The pairing and orientation with the best single-edge configuration."""
        best = None
        for pairing in range(len(PAIRINGS)):
            for mode in MODES:
                if self.solve(edges, pairing, mode) is not None and \
                        self.better((edges, pairing, mode), best):
                    best = (edges, pairing, mode)
        return best

    def grow(self, key: tuple[Any, ...], max_steps: int) -> tuple[Any, ...]:
        """Take the best improving move until none improves; then, if another pairing
        or orientation certifies the configuration better, go on with it."""
        for _ in range(max_steps):
            # single-edge configurations are the single-edge search's (the seeds)
            step = self._best_move(key, _moves(self.polygon, key[0]), single=False)
            if step is None:
                other = self.seed(key[0])
                if other is None or not self.better(other, key):
                    break
                step = other
            key = step
        return key

    def polish(self, key: tuple[Any, ...], max_steps: int) -> tuple[Any, ...]:
        """:meth:`grow`, then, where no move improves, the best improving *pair* of
        moves (:func:`_pair_moves`: two regions slid at once; a symmetric
        part's optimum can need two regions slid together, each slide alone shortening
        the smallest region), with the configuration's pairing and orientation, and
        grow again; until no pair improves either."""
        for _ in range(max_steps):
            key = self.grow(key, max_steps)
            step = self._best_move(key, _pair_moves(self.polygon, key[0]), single=True)
            if step is None:
                break
            key = step
        return key

    def _best_move(self, key: tuple[Any, ...], moves: list[tuple[tuple[int, ...], ...]],
                   single: bool) -> tuple[Any, ...] | None:
        """The best of ``moves`` (covered edges) that beats ``key`` with its pairing and
        orientation, or None; ``single`` False: single-edge configurations left out.  A
        region is never longer than the edges it covers: a move whose shortest stretch
        is below the best so far is not solved."""
        step = None
        for new in moves:
            if (not single and _size(new) == 1) or _size(new) > MAX_COMBINATIONS:
                continue
            ahead = self.level[key if step is None else step]
            assert ahead is not None
            if self.reach(new) < ahead * (1 - RANK_TOL):
                continue
            cand = (new, key[1], key[2])
            if self.solve(*cand, parent=key) is not None and \
                    self.better(cand, key if step is None else step):
                step = cand
        return step

    def result(self, key: tuple[Any, ...]) -> FrictionlessStretches | None:
        cfg = self.system(key)
        x = _leximin(cfg)
        return None if x is None else _result(self.polygon, cfg, x, PAIRINGS[key[1]], key[2])


def frictionless_stretch_regions(polygon: Polygon, region_edges: Any,
                                 margin: Any = DEFAULT_MARGIN_DEG, gravity: Any = None
                                 ) -> FrictionlessStretches | None:
    """Optimal independent regions covering exactly the given stretches (definition
    7.1 with the vertex lemma of this module), frictionless fingers.

    ``region_edges``: per finger (four, or three with ``gravity``, a direction), the
    consecutive edges of one ring its region covers, in ring order.  The best pairing
    and cone orientation is used; None when no regions cover these edges.

    >>> sq = Polygon([[0, 0], [10, 0], [10, 10], [0, 10]])
    >>> r = frictionless_stretch_regions(sq, [[0], [1], [2], [3]])
    >>> round(r.min_length, 3) > 0
    True
    """
    edges, margin, g = _check(polygon, region_edges, margin, gravity)
    search = _Search(polygon, margin, g)
    key = search.seed(edges)
    return None if key is None else search.result(key)


def _moves(polygon: Polygon, edges: tuple[tuple[int, ...], ...], grow_only: bool = False
           ) -> list[tuple[tuple[int, ...], ...]]:
    """Configurations one step away: one region longer by one edge at one end; unless
    ``grow_only``, also slid by one edge (one end added, the other dropped) or shorter
    by one end edge."""
    used = {e for st in edges for e in st}
    out = []
    for f, st in enumerate(edges):
        ring = int(np.sum((polygon.rings == polygon.rings[st[0]]) & polygon.usable))
        before, after = polygon.previous_edge(st[0]), polygon.next_edge(st[-1])
        news: list[tuple[tuple[int, ...], int | None]] = []
        if len(st) + 1 < ring:
            news += [((before, *st), before), ((*st, after), after)]
        if not grow_only:
            news += _slides(polygon, st)
            if len(st) > 1:
                news += [(st[1:], None), (st[:-1], None)]
        for new, added in news:
            if added is None or added not in used:
                out.append(tuple(new if i == f else s for i, s in enumerate(edges)))
    return out


def _pair_moves(polygon: Polygon, edges: tuple[tuple[int, ...], ...]
                ) -> list[tuple[tuple[int, ...], ...]]:
    """Configurations two moves away, two different regions each slid by one edge (the
    fingers still on distinct edges; growth extends one region at a time already)."""
    used = {e for st in edges for e in st}
    per = [[(new, add) for new, add in _slides(polygon, st) if add not in used]
           for st in edges]
    out = []
    for f in range(len(edges)):
        for g in range(f + 1, len(edges)):
            for a, add_a in per[f]:
                for b, add_b in per[g]:
                    if add_a != add_b:
                        out.append(tuple(a if i == f else b if i == g else s
                                         for i, s in enumerate(edges)))
    return out


def _slides(polygon: Polygon, st: tuple[int, ...]) -> list[tuple[tuple[int, ...], int]]:
    """A stretch slid by one edge either way, with the edge each slide adds."""
    before, after = polygon.previous_edge(st[0]), polygon.next_edge(st[-1])
    return [((before, *st[:-1]), before), ((*st[1:], after), after)]


def _size(edges: tuple[tuple[int, ...], ...]) -> int:
    return math.prod(len(st) for st in edges)


def _seeds(polygon: Polygon, edge_sets: Any, margin: Any, gravity: Any
           ) -> tuple[_Search, list[tuple[tuple[tuple[int, ...], ...], Any]]]:
    """One search for the rows of single edges, and each row's configuration with its
    best pairing and orientation (None where it holds no regions)."""
    if not isinstance(polygon, Polygon):
        raise TypeError(f"polygon must be a fcgrasp.Polygon, got {type(polygon).__name__}")
    search = _Search(polygon, 0.0, None)
    out = []
    for k, row in enumerate(np.ravel(np.asarray(r)).tolist() for r in edge_sets):
        edges, margin_v, g = _check(polygon, [[e] for e in row], margin, gravity)
        if k == 0:
            search = _Search(polygon, margin_v, g)
        out.append((edges, search.seed(edges)))
    return search, out


def load_kernels() -> bool:
    """Load the growth's compiled programs now (and with them numba and the compiled
    kernels of :mod:`fcgrasp.core.kernels`), where numba is there and ``FCGRASP_JIT``
    leaves the choice to the searches: four fingers and three with gravity grow their
    best single-edge plans by them, so the single-edge search before the growth runs
    compiled too, instead of first running :data:`~fcgrasp.core.kernels.JIT_AFTER_ROWS`
    rows by numpy to learn that numba's start-up repays itself.  Whether they run."""
    return _frictionless_kernels.COMPILED.available()


def _budget_left() -> bool:
    """Whether the time budget lets a growth go on (a budget check); recorded as cut
    short when not."""
    if budget.exhausted():
        budget.cut_short()
        return False
    return True


def grow_stretches(polygon: Polygon, edge_sets: Any, margin: Any = DEFAULT_MARGIN_DEG,
                   gravity: Any = None, max_steps: int = 400, keep_single: bool = True,
                   polish: int = 0) -> list[FrictionlessStretches | None]:
    """Grow single-edge regions along the boundary (the search of this module's
    docstring).

    ``edge_sets``: rows of edges, one per finger (four, or three with ``gravity``);
    from each, extend the region whose extension improves most until none does.  Rows
    share what they solve.  The ``polish`` best configurations grown then try pairs of
    moves where single moves are done (:meth:`_Search.polish`: on a 24-edge ellipse
    four regions of four edges each are reached only by sliding two regions at once).
    Returns, per row, a safe plan that ranks at least as high as
    the row's single-edge regions (a lower bound on the optimum), or None when the row's
    edges hold no regions (or, with ``keep_single=False``, when its regions do not leave
    their edges: the single-edge search has them already).

    >>> from fcgrasp.io.parts import demo_part
    >>> [r.region_edges for r in grow_stretches(demo_part("blob"), [[0, 1, 3, 4]])]
    [((0,), (1,), (3,), (4,))]
    """
    if not isinstance(max_steps, int) or max_steps < 0:
        raise ValueError(f"max_steps must be an integer >= 0, got {max_steps!r}")
    if not isinstance(polish, int) or polish < 0:
        raise ValueError(f"polish must be an integer >= 0, got {polish!r}")
    search, seeds = _seeds(polygon, edge_sets, margin, gravity)
    # each seed grown while the time budget lasts (:func:`fcgrasp.core.budget.cut_short`:
    # a seed not grown is its single-edge plan, which holds)
    keys = []
    for _, key in seeds:
        if key is not None and _budget_left():
            key = search.grow(key, max_steps)
        keys.append(key)
    # the best grown (distinct configurations, best first) polished
    best: list[tuple[Any, ...]] = []
    for key in keys:
        if key is not None and key not in best:
            at = next((i for i, b in enumerate(best) if search.better(key, b)), len(best))
            best.insert(at, key)
    polished = {key: search.polish(key, max_steps) for key in best[:polish]
                if _budget_left()}
    out: list[FrictionlessStretches | None] = []
    for key in keys:
        if key is not None:
            key = polished.get(key, key)
        if key is not None and not keep_single and _size(key[0]) == 1:
            key = None
        out.append(None if key is None else search.result(key))
    return out


def all_frictionless_stretches(polygon: Polygon, edge_sets: Any,
                               margin: Any = DEFAULT_MARGIN_DEG, gravity: Any = None,
                               limit: int = 200_000) -> FrictionlessStretches | None:
    """The best configuration that holds and covers one of the given single-edge sets
    (rows of edges, one per finger), over every pairing and cone orientation:
    exhaustive and slow, the reference that measures the gap of :func:`grow_stretches`.
    Given every single-edge set that holds (``fc.plan(part, fingers, top=None,
    along_boundary=False)``), it is the optimum over all configurations.

    A configuration that holds for a pairing and orientation still holds, for the same
    ones, with an end edge dropped; so every configuration that holds is reached from
    single edges by one-edge extensions that all hold, and a breadth-first search over
    them sees every one.  ``limit`` caps the configurations tried (``ValueError``
    beyond it).
    """
    search, seeds = _seeds(polygon, edge_sets, margin, gravity)
    top = None
    frontier = []
    for edges0, key in seeds:
        if key is not None:
            frontier.append(edges0)
            if search.better(key, top):
                top = key
    if top is None:
        return None
    seen = set(frontier)
    while frontier:
        nxt = []
        for cfg in frontier:
            for new in _moves(polygon, cfg, grow_only=True):
                if new in seen or _size(new) > MAX_COMBINATIONS:
                    continue
                seen.add(new)
                if len(seen) > limit:
                    raise ValueError(f"more than limit={limit} configurations to try")
                best = search.seed(new)
                if best is None:
                    continue
                nxt.append(new)
                if search.better(best, top):
                    top = best
        frontier = nxt
    return search.result(top)
