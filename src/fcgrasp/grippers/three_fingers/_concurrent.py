"""Concurrent grasps of three fingers with friction: the arcs of force directions that
span the plane, and the largest regions whose every triple of points has concurrent
lines of force in non-marginal equilibrium (LP blocks; part of
:mod:`fcgrasp.grippers.three_fingers`)."""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache
from itertools import product
from typing import Any

import numpy as np

from ...core._angles import wrap_positive
from ...core._checks import FloatArray
from ...core.tolerances import CHECK_TOL, LEXIMIN_STEP, LP_TOL, PIECE_TIE, ROUND_TOL, TINY
from . import _concurrency

#: How the half-turn excess between two neighbouring cones is split between them (the
#: share taken from the first arc's start): each split gives one convex piece.
SPLITS = _concurrency.SPLITS
#: Two-finger plans (fingers holding on their own) read first, to be tried with a third
#: finger anywhere (more where they may rank: ``three_fingers._pair_plans``).
KEEP_PAIRS = 20
#: Rows of candidate triples solved per linear program (blocks of one sparse LP).
LP_ROWS = 24

_CORNERS = np.array(list(product((0, 1), repeat=3)))          # (8, 3): 0 low end, 1 high
_SIDES = _concurrency._SIDES                                  # (8, 3) sigma


def spanning_arcs(center: Any, half: Any, margin: float) -> list[tuple[FloatArray, FloatArray]]:
    """Sub-arcs of three friction cones every selection of which positively spans the
    plane (three force directions in non-marginal equilibrium, section 3).

    ``center`` (3,): angles of the cones' axes (the inward normals); ``half`` (3,): their
    half-widths; ``margin``: how far inside the cones the arcs stay, and how far below
    half a turn every gap between chosen directions stays.  Returns a list of
    ``(low, high)`` angle arrays (3,), one per split of the excess (:data:`SPLITS`);
    empty when the cones cannot span the plane.

    >>> arcs = spanning_arcs(np.radians([90, 210, 330]), np.radians([20] * 3), 0.0)
    >>> len(arcs), np.degrees(arcs[0][0]).round(1).tolist()   # wide enough already
    (1, [70.0, 190.0, 310.0])
    """
    c = wrap_positive(np.asarray(center, float))
    w = np.asarray(half, float) - margin
    if np.any(w < 0):
        return []
    # called once per triple of features: plain floats, not arrays of three
    cl, wl = c.tolist(), w.tolist()
    limit = np.pi - margin
    turn = 2 * np.pi
    out: list[tuple[FloatArray, FloatArray]] = []
    seen = set()
    # the chosen directions go round in one of two cyclic orders; between two centres
    # the unwrapped gap is the turn from one to the next, or that less a full turn (an
    # arc reaching back past its neighbour's centre); the third gap closes the turn
    for cur in ((0, 1, 2), (0, 2, 1)):
        nxt = (cur[1], cur[2], cur[0])
        base = [(cl[nxt[i]] - cl[cur[i]]) % turn for i in range(3)]
        wc, wn = [wl[k] for k in cur], [wl[k] for k in nxt]
        for k1, k2 in ((0, 0), (0, -1), (-1, 0), (-1, -1)):
            g0, g1 = base[0] + turn * k1, base[1] + turn * k2
            g2 = turn - g0 - g1
            # some turn exceeds the limit even from the end of one arc to the start of
            # the next: no sub-arcs
            if g0 - wc[0] - wn[0] > limit or g1 - wc[1] - wn[1] > limit \
                    or g2 - wc[2] - wn[2] > limit:
                continue
            for lo, hi in _split_excess((g0, g1, g2), wl, wc, wn, cur, nxt, limit):
                key = tuple(round(v, 12) for v in lo + hi)
                if key not in seen:
                    seen.add(key)
                    out.append((c + lo, c + hi))
    return out


def _split_excess(gap: tuple[float, float, float], w: list[float], w_cur: list[float],
                  w_next: list[float], cur: tuple[int, ...], nxt: tuple[int, ...],
                  limit: float) -> list[tuple[list[float], list[float]]]:
    """Offsets ``(lo, hi)`` of the sub-arcs (from the cones' axes, half-widths ``w``) that
    keep every turn from the start of one arc to the end of the next below ``limit`` (the
    cyclic order ``cur -> nxt`` with unwrapped ``gap`` between the axes, no turn beyond
    the limit from the end of one arc to the start of the next): the excess of each turn
    is taken from the two arcs in the shares of :data:`SPLITS` (``w_cur``, ``w_next``:
    the half-widths of each turn's two arcs)."""
    excess = [max(gap[i] + w_cur[i] + w_next[i] - limit, 0.0) for i in range(3)]
    out = []
    for split in product(*[SPLITS if e > 0 else (0.0,) for e in excess]):
        lo, hi = [-v for v in w], list(w)
        for i, r in enumerate(split):
            e = excess[i]
            x = min(max(r * e, e - 2 * w_next[i]), 2 * w_cur[i])   # raise cur's start by x
            lo[cur[i]] += x
            hi[nxt[i]] -= e - x                                     # lower nxt's end
        if lo[0] <= hi[0] + ROUND_TOL and lo[1] <= hi[1] + ROUND_TOL and lo[2] <= hi[2] + ROUND_TOL:
            out.append((lo, [max(h, v) for h, v in zip(hi, lo, strict=True)]))
    return out


@dataclass
class Piece:
    """The optimal box of regions of three features (or stretches) in one convex piece.

    ``lo``, ``hi`` (3,): region ends as arc lengths, ``lo`` from the start of the first
    edge a region covers, ``hi`` from the start of its last (one edge: both from its
    start); ``levels`` (3,): the regions' lengths; ``sigma`` (3,): the side of each finger
    the meeting point lies on; ``arcs``: the ``(low, high)`` force-direction angles (3,);
    ``witness`` (N, 2): a meeting point for each corner grasp (on single edges N = 8, in
    the order of :data:`_CORNERS`).
    """

    lo: FloatArray
    hi: FloatArray
    levels: FloatArray
    sigma: FloatArray
    arcs: tuple[FloatArray, FloatArray]
    witness: FloatArray


@dataclass
class _Block:
    """One convex piece of one row of three fingers, as a block of a linear program
    (positions in units of the part's size).  Finger ``i``'s region starts at
    ``a0[i] + lo_i t0[i]`` (``0 <= lo_i <= L0[i]``), passes the fixed points
    ``inner[i]`` (the interior vertices of a stretch) and ends at ``a1[i] + hi_i t1[i]``
    (``0 <= hi_i <= L1[i]``); its length is ``hi_i - lo_i + const[i]`` (on one edge
    ``a0 = a1``, no inner point and ``const`` 0).  ``order``: fingers 0 and 1 are on one
    feature, finger 0's region before finger 1's (``hi_0 <= lo_1``: two fingers side by
    side on one edge, regions apart)."""

    a0: FloatArray          # (3, 2) starts of the first edges
    t0: FloatArray          # (3, 2) their unit tangents
    L0: FloatArray          # (3,) their lengths
    a1: FloatArray          # (3, 2) the same for the last edges
    t1: FloatArray
    L1: FloatArray
    const: FloatArray       # (3,) length of a region less hi - lo
    inner: tuple[FloatArray, ...]   # (k_i, 2) fixed points of each region
    lo_ang: FloatArray      # (3,) force-direction arcs
    hi_ang: FloatArray
    sigma: FloatArray       # (3,) side of the meeting point
    row: int
    order: bool = False

    @staticmethod
    def on_edges(a: FloatArray, t: FloatArray, L: FloatArray, lo_ang: FloatArray,
                 hi_ang: FloatArray, sigma: FloatArray, row: int, order: bool = False
                 ) -> _Block:
        """A block of three single features (``order``: the first two are one)."""
        none = np.zeros((0, 2))
        return _Block(a, t, L, a, t, L, np.zeros(3), (none, none, none), lo_ang, hi_ang,
                      sigma, row, bool(order))

    def corners(self) -> np.ndarray:
        """The corner grasps (N, 3): per finger, 0 its start, 1 its end, ``2 + j`` its
        ``j``-th fixed point (on single edges the order of :data:`_CORNERS`)."""
        return _corner_grid(tuple(2 + len(p) for p in self.inner))


@lru_cache(maxsize=256)
def _corner_grid(points: tuple[int, ...]) -> np.ndarray:
    """Every combination of one point index per finger, ``points[i]`` points each."""
    out = np.array(list(product(*(range(n) for n in points))), dtype=int).reshape(-1, 3)
    out.flags.writeable = False
    return out


def _cone_rows(blk: _Block) -> tuple[FloatArray, FloatArray, FloatArray, np.ndarray,
                                     FloatArray]:
    """The cone constraints of a block (N corners x 3 fingers x 2 cone edges), each
    ``S (u x p - s (u x t) - u x a) >= 0`` at a variable end ``a + s t`` and
    ``S (u x p - u x v) >= 0`` at a fixed point ``v`` (``S`` the side, negated on the arc's
    high edge): ``(cpx, cpy, cs, svar, rhs)`` of ``cpx px + cpy py + cs s >= rhs``, shapes
    (N, 3, 2), ``svar`` the index of ``s`` (``lo_i``: ``i``, ``hi_i``: ``3 + i``; -1 at
    a fixed point, where ``cs`` is 0)."""
    ang = np.stack([blk.lo_ang, blk.hi_ang], axis=-1)               # (3, 2)
    ux, uy = np.cos(ang), np.sin(ang)
    S = blk.sigma[:, None] * np.array([1.0, -1.0])
    C = blk.corners()
    N = len(C)
    cs = np.empty((N, 3, 2))
    svar = np.empty((N, 3), dtype=int)
    rhs = np.empty((N, 3, 2))
    for i in range(3):
        # finger i's points: its start, its end (variable), its fixed points
        pts = np.concatenate([[blk.a0[i], blk.a1[i]], blk.inner[i]])          # (n_i, 2)
        tan = np.zeros_like(pts)
        tan[0], tan[1] = blk.t0[i], blk.t1[i]
        p_cs = -S[i] * (ux[i] * tan[:, 1, None] - uy[i] * tan[:, 0, None])    # (n_i, 2)
        p_rhs = S[i] * (ux[i] * pts[:, 1, None] - uy[i] * pts[:, 0, None])
        p_var = np.full(len(pts), -1)
        p_var[:2] = (i, 3 + i)
        cs[:, i], rhs[:, i], svar[:, i] = p_cs[C[:, i]], p_rhs[C[:, i]], p_var[C[:, i]]
    shape = (N, 3, 2)
    return (np.broadcast_to(-S * uy, shape), np.broadcast_to(S * ux, shape), cs,
            np.broadcast_to(svar[:, :, None], shape), rhs)


def _cone_values(blk: _Block, x: FloatArray) -> FloatArray:
    """How far inside its piece every corner grasp's witness is (>= 0 inside), (N, 3, 2)."""
    cpx, cpy, cs, svar, rh = _cone_rows(blk)
    N = len(cpx)
    s = np.where(svar >= 0, x[np.maximum(svar, 0)], 0.0)
    return cpx * x[7:7 + N, None, None] + cpy * x[7 + N:7 + 2 * N, None, None] + cs * s - rh


def _lengths(blk: _Block, x: FloatArray) -> FloatArray:
    """The regions' lengths at a solution ``x`` of the block."""
    return x[3:6] - x[:3] + blk.const


def _solve_blocks(blocks: list[_Block], fixed: FloatArray | None = None,
                  free: np.ndarray | None = None, grow: int | None = None,
                  deep: bool = False) -> list[FloatArray | None]:
    """Solve independent blocks in one sparse HiGHS program; per block its solution
    vector ``(lo (3), hi (3), level, px (N), py (N), v)``, or None where it is
    infeasible (the answer is checked, not trusted).

    Every cone constraint may use the block's violation ``v`` at a large cost, so an
    infeasible block does not make the program infeasible.  Default objective: the
    largest ``level`` with every region at least it (max-min, definition 7.1).  With
    ``fixed`` (3,): regions keep at least their fixed length, and either the ``free``
    ones reach the largest common ``level``, or region ``grow`` is made as long as it
    can, or (``deep``) the witnesses are placed as far inside the cones as they can be
    (``level`` is then that depth): the placement.

    Solved by the compiled closed form of :mod:`fcgrasp.grippers.three_fingers._concurrency` once it
    runs (:func:`fcgrasp.grippers.three_fingers._concurrency.available`), the solution vectors then
    ``(lo, hi, level)`` only (no witnesses); else by HiGHS (the reference).
    """
    if _concurrency.available():
        got = _concurrency.solve(blocks, _KINDS[(deep, grow is not None, fixed is not None)],
                                 fixed, free, 0 if grow is None else grow)
        if got is not None:
            return [x if ok else None for x, ok in zip(got[0], got[1], strict=True)]
    return _solve_blocks_lp(blocks, fixed, free, grow, deep)


#: The kernel's objective by ``(deep, grow given, fixed given)``.
_KINDS = {(True, False, True): _concurrency.DEEP, (False, True, True): _concurrency.GROW,
          (False, False, True): _concurrency.FREE, (False, False, False): _concurrency.MAXMIN}


def _solve_blocks_lp(blocks: list[_Block], fixed: FloatArray | None = None,
                     free: np.ndarray | None = None, grow: int | None = None,
                     deep: bool = False) -> list[FloatArray | None]:
    """:func:`_solve_blocks` by one sparse HiGHS program (the reference)."""
    from scipy.optimize import linprog
    from scipy.sparse import coo_array

    rows = [_cone_rows(blk) for blk in blocks]
    sizes = [8 + 2 * len(r[0]) for r in rows]
    starts = np.concatenate([[0], np.cumsum(sizes)]).astype(int)
    ri: list[np.ndarray] = []
    ci: list[np.ndarray] = []
    vals: list[np.ndarray] = []
    rhs: list[np.ndarray] = []
    cost = np.zeros(starts[-1])
    bounds = np.zeros((starts[-1], 2))
    r0 = 0
    for k, (blk, (cpx, cpy, cs, svar, rh)) in enumerate(zip(blocks, rows, strict=True)):
        base, N = int(starts[k]), len(cpx)
        nr = 6 * N
        # -(cpx px + cpy py + cs s) - v (+ level when deep) <= -rh
        rid = r0 + np.arange(nr).reshape(N, 3, 2)
        var_s = svar >= 0
        for var, coef, use in ((base + 7 + np.arange(N)[:, None, None], cpx, None),
                               (base + 7 + N + np.arange(N)[:, None, None], cpy, None),
                               (base + svar, cs, var_s)):
            var = np.broadcast_to(var, (N, 3, 2))
            m = np.ones((N, 3, 2), bool) if use is None else use
            ri.append(rid[m])
            ci.append(var[m])
            vals.append(-coef[m])
        ri.append(rid.ravel())
        ci.append(np.full(nr, base + 7 + 2 * N))
        vals.append(np.full(nr, -1.0))
        if deep:
            ri.append(rid.ravel())
            ci.append(np.full(nr, base + 6))
            vals.append(np.ones(nr))
        rhs.append(-rh.ravel())
        r0 += nr
        for i in range(3):
            reach = fixed is None or (free is not None and bool(free[i]))
            if reach:       # level - (hi - lo) <= const
                ri.append(np.full(3, r0))
                ci.append(np.array([base + 6, base + 3 + i, base + i]))
                vals.append(np.array([1.0, -1.0, 1.0]))
                rhs.append(np.array([blk.const[i]]))
            else:           # lo - hi <= const - fixed
                assert fixed is not None
                ri.append(np.full(2, r0))
                ci.append(np.array([base + 3 + i, base + i]))
                vals.append(np.array([-1.0, 1.0]))
                rhs.append(np.array([blk.const[i] - float(fixed[i]) * (1 - ROUND_TOL)]))
            r0 += 1
        if blk.order:       # hi_0 - lo_1 <= 0
            ri.append(np.full(2, r0))
            ci.append(np.array([base + 3, base + 1]))
            vals.append(np.array([1.0, -1.0]))
            rhs.append(np.zeros(1))
            r0 += 1
        bounds[base:base + 6] = np.c_[np.zeros(6), np.r_[blk.L0, blk.L1]]
        bounds[base + 6] = (0.0, 1.0 if deep else float((blk.L0 + blk.L1 + blk.const).max()))
        bounds[base + 7:base + 7 + 2 * N] = (-np.inf, np.inf)
        bounds[base + 7 + 2 * N] = (0.0, np.inf)
        cost[base + 7 + 2 * N] = 1e4
        if grow is not None:
            cost[base + 3 + grow], cost[base + grow] = -1.0, 1.0
        else:
            cost[base + 6] = -1.0
    A = coo_array((np.concatenate(vals), (np.concatenate(ri), np.concatenate(ci))),
                  shape=(r0, int(starts[-1]))).tocsr()
    res = linprog(cost, A_ub=A, b_ub=np.concatenate(rhs), bounds=bounds, method="highs",
                  options={"primal_feasibility_tolerance": LP_TOL,
                           "dual_feasibility_tolerance": LP_TOL})
    if res.status != 0 or res.x is None:
        # one block's numerical trouble must not lose the others: each on its own
        if len(blocks) > 1:
            return [x for blk in blocks
                    for x in _solve_blocks_lp([blk], fixed, free, grow, deep)]
        return [None]
    out: list[FloatArray | None] = []
    for k, blk in enumerate(blocks):
        x = np.array(res.x[starts[k]:starts[k + 1]])
        ok = (_cone_values(blk, x).min() >= -CHECK_TOL
              and bool(np.all(_lengths(blk, x) >= -CHECK_TOL))
              and not (blk.order and x[3] > x[1] + CHECK_TOL))
        out.append(x if ok else None)
    return out


def _blocks(a: FloatArray, t: FloatArray, L: FloatArray, center: FloatArray,
            half: FloatArray, margin: float, row: int, order: bool = False) -> list[_Block]:
    """Every convex piece of one row: the sub-arcs of :func:`spanning_arcs` times the
    eight sides of the meeting point (``order``: the first two features are one)."""
    return [_Block.on_edges(a, t, L, lo, hi, sigma, row, order)
            for lo, hi in spanning_arcs(center, half, margin) for sigma in _SIDES]


def shared_first(a: FloatArray, b: FloatArray) -> np.ndarray:
    """Rows (R, 3, 2 ends) whose first two features are one segment: two fingers side by
    side on one edge, their regions apart (``hi_0 <= lo_1``).  A row repeating another
    pair of its features is refused: the shared feature comes first."""
    def same(i: int, j: int) -> np.ndarray:
        return np.all(a[:, i] == a[:, j], axis=-1) & np.all(b[:, i] == b[:, j], axis=-1)

    bad = same(0, 2) | same(1, 2)
    if bad.any():
        r = int(np.flatnonzero(bad)[0])
        raise ValueError(f"a, b: two fingers on one feature must be the first two of a row; "
                         f"row {r} repeats its third feature, got a={a[r].tolist()}")
    return same(0, 1)


def _smallest(blk: _Block, x: FloatArray) -> float:
    return float(np.min(_lengths(blk, x)))


def _best_blocks(a: FloatArray, b: FloatArray, center: FloatArray, half: FloatArray,
                 margin: float, size: float) -> list[tuple[_Block | None, float]]:
    """Per row of three features, the piece with the largest smallest region and that
    region's length in units of ``size`` (-1 where no piece holds a grasp).  A row whose
    first two features are one (:func:`shared_first`) keeps their regions apart."""
    out: list[tuple[_Block | None, float]] = [(None, -1.0)] * len(a)
    for r, blk, level in best_found(a, b, center, half, margin, size):
        out[r] = (blk, level)
    return out


def best_found(a: FloatArray, b: FloatArray, center: FloatArray, half: FloatArray,
               margin: float, size: float) -> list[tuple[int, _Block, float]]:
    """:func:`_best_blocks` of the rows where a piece holds a grasp, each ``(row,
    block, level)`` in order: a batch of which few hold makes no entry for the others
    (the three-finger rounds read millions of rows, a few thousand hold)."""
    d = b - a
    L = np.hypot(d[..., 0], d[..., 1])
    t = d / np.where(L > 0, L, 1.0)[..., None]
    an, Ln = a / size, L / size
    order = shared_first(a, b)
    if _concurrency.available():
        got = _concurrency.best_rows(an, t, Ln, center, half, margin, order)
        if got is not None:
            found, level, lo, hi, sg = got
            return [(r, _Block.on_edges(an[r], t[r], Ln[r], lo[r], hi[r], sg[r], r, order[r]),
                     float(level[r])) for r in np.flatnonzero(found).tolist()]
    out: list[tuple[int, _Block, float]] = []
    for start in range(0, len(a), LP_ROWS):
        stop = min(start + LP_ROWS, len(a))
        blocks = [blk for r in range(start, stop)
                  for blk in _blocks(an[r], t[r], Ln[r], center[r], half[r], margin, r,
                                     order[r])]
        per: dict[int, list[tuple[float, _Block]]] = {}
        for blk, x in zip(blocks, _solve_blocks(blocks) if blocks else [], strict=True):
            if x is not None:
                per.setdefault(blk.row, []).append((_smallest(blk, x), blk))
        for r in range(start, stop):
            row = per.get(r)
            if row:
                v, blk = row[first_best([v for v, _ in row])]
                out.append((r, blk, v))
    return out


def first_best(values: list[float]) -> int:
    """The first of ``values`` within :data:`PIECE_TIE` of the largest."""
    top = max(values)
    return next(i for i, v in enumerate(values) if v >= top - PIECE_TIE)


def _leximin(blk: _Block) -> Piece | None:
    """Leximin-optimal levels (definition 7.1) in one piece, then the placement whose
    witnesses are deepest inside the cones at those levels."""
    x = _solve_blocks([blk])[0]
    if x is None:
        return None
    levels = np.full(3, _smallest(blk, x))
    free = np.ones(3, dtype=bool)
    step = LEXIMIN_STEP * max(float((blk.L0 + blk.L1 + blk.const).max()), TINY)
    for _ in range(3):                    # each round fixes at least one region
        if not free.any():
            break
        grows = np.zeros(3, dtype=bool)
        for i in np.flatnonzero(free):
            xi = _solve_blocks([blk], fixed=levels, grow=int(i))[0]
            grows[i] = xi is not None and _lengths(blk, xi)[i] > levels[i] + step
        free &= grows
        if not free.any():
            break
        xf = _solve_blocks([blk], fixed=levels, free=free)[0]
        if xf is None:
            break
        levels[free] = max(float(np.min(_lengths(blk, xf)[free])), float(levels[free].max()))
    xd = _solve_blocks([blk], fixed=levels, deep=True)[0]
    x = x if xd is None else xd
    N = len(blk.corners())
    witness = (np.stack([x[7:7 + N], x[7 + N:7 + 2 * N]], axis=1) if len(x) > 7 else
               _concurrency.witnesses(blk, x[:3], x[3:6]))
    return Piece(x[:3].copy(), x[3:6].copy(), _lengths(blk, x), blk.sigma.copy(),
                 (blk.lo_ang.copy(), blk.hi_ang.copy()), witness)


def concurrent_regions(a: Any, b: Any, center: Any, half: Any, margin: float,
                       size: float = 1.0) -> list[Piece | None]:
    """The best box of regions of concurrent grasps on each of a batch of three features.

    ``a``, ``b`` (R, 3, 2): the features' ends; ``center``, ``half`` (R, 3): their
    friction cones (angle of the inward normal, half-width ``atan(mu)``, radians);
    ``margin`` (radians); ``size``: a length scale of the part (the programs are solved
    in units of it).  Returns per row the :class:`Piece` with the largest smallest
    region, its levels leximin-optimal within that piece (definition 7.1) and its
    witnesses as deep inside the cones as the levels allow (positions and witnesses in
    the part's units), or None when no piece holds a grasp.  Two fingers side by side
    on one edge: give its feature first and second; their regions come apart, in order
    along it (``hi_0 <= lo_1``).

    >>> tri = np.array([[0.0, 0.0], [4.0, 0.0], [2.0, 3.0]])
    >>> a, b = tri[None], np.roll(tri, -1, axis=0)[None]
    >>> d = b - a
    >>> inward = np.arctan2(d[..., 0], -d[..., 1])          # the left normal: inside
    >>> piece = concurrent_regions(a, b, inward, np.full((1, 3), np.arctan(0.5)),
    ...                            np.radians(0.5))[0]
    >>> bool(piece.levels.min() > 0.5)
    True
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    center, half = np.asarray(center, float), np.asarray(half, float)
    out: list[Piece | None] = []
    for blk, _ in _best_blocks(a, b, center, half, margin, size):
        p = None if blk is None else _leximin(blk)
        if p is not None:
            p = replace(p, lo=p.lo * size, hi=p.hi * size, levels=p.levels * size,
                        witness=p.witness * size)
        out.append(p)
    return out
