"""The rows of a frictionless configuration's program, compiled (a per-call
path without per-call overhead).

:func:`fcgrasp.model._frictionless_program._system` builds, for every combination of
covered edges (the vertex lemma), theorem 7.1's two rows: the affine maps of the fingers'
meets ``P12``, ``P34`` (:func:`fcgrasp.model._regiongeom.four_finger_geometry`), the
shrunk sector's edges, and each finger's coefficient on the variable its region's end
is.  In numpy that is a hundred calls on arrays of a few rows, and the growth of four
fingers' regions builds thousands of such programs (``icons/bell.svg``: 4,000 programs,
10 of its 17 s).  :func:`system_rows` runs the same formulas, in the same order, in one
compiled loop over the combinations; the numpy ``_system`` stays the reference (the
tests compare the rows on thousands of seeded configurations, bit for bit).
"""

from __future__ import annotations

import math
from typing import Any, Literal

import numpy as np

from ..core import _simplex, jit, kernels
from ..core._checks import FloatArray, IntArray
from ..core._simplex import _lp_max
from ..core.kernels import arc_meet
from .polygon import Polygon

#: The kinds of a finger's edge in its stretch (``frictionless_stretches``'s order).
_SINGLE, _FIRST, _LAST, _INSIDE = 0, 1, 2, 3


def _wrap_mod(x: float) -> float:
    """:func:`fcgrasp.core._angles.wrap` of a number (the same ``mod``: Python's and
    numpy's floored remainder agree to the bit)."""
    return (x + math.pi) % (2.0 * math.pi) - math.pi


def _pair_arc(ca: float, cb: float) -> tuple[float, float]:
    """:func:`fcgrasp.core.sectors.pair_arc` of numbers."""
    gap = _wrap_mod(cb - ca)
    return _wrap_mod(ca + gap / 2), abs(gap) / 2


def _edge(e: int, ea: FloatArray, eb: FloatArray, ec: FloatArray
          ) -> tuple[float, float, float, float, float]:
    """Edge ``e``'s force direction, length and unit tangent (``(0, 0)`` for a point),
    as ``four_finger_geometry`` computes them."""
    fx, fy = math.cos(ec[e]), math.sin(ec[e])
    dx, dy = eb[e, 0] - ea[e, 0], eb[e, 1] - ea[e, 1]
    L = math.hypot(dx, dy)
    d = L if L > 0 else 1.0
    return fx, fy, L, dx / d if L > 0 else 0.0, dy / d if L > 0 else 0.0


def _meets(ea: FloatArray, eb: FloatArray, ec: FloatArray, lo_i: int, hi_i: int, lo_j: int,
           hi_j: int, tol: float, out: FloatArray) -> None:
    """The meets of the lines of force of every edge ``i`` of one finger (rows
    ``lo_i:hi_i`` of the edges) with every edge ``j`` of another (``lo_j:hi_j``), as
    ``four_finger_geometry`` computes them for a pair of fingers: per pair (``i``
    slowest) the meet, the velocities of the first and second finger's positions, the
    pair's arc (centre, half-width), whether the forces are not parallel, and the two
    edges' lengths (``out`` rows of 11)."""
    r = 0
    for i in range(lo_i, hi_i):
        fix, fiy, Li, tix, tiy = _edge(i, ea, eb, ec)
        for j in range(lo_j, hi_j):
            fjx, fjy, Lj, tjx, tjy = _edge(j, ea, eb, ec)
            den = fix * fjy - fiy * fjx
            wx, wy = ea[j, 0] - ea[i, 0], ea[j, 1] - ea[i, 1]
            sm = (wx * fjy - wy * fjx) / den
            ga = (tix * fjy - tiy * fjx) / den
            gb = (tjx * fjy - tjy * fjx) / den
            out[r, 0] = ea[i, 0] + sm * fix
            out[r, 1] = ea[i, 1] + sm * fiy
            out[r, 2] = tix - ga * fix if Li > 0 else 0.0
            out[r, 3] = tiy - ga * fiy if Li > 0 else 0.0
            out[r, 4] = gb * fix if Lj > 0 else 0.0
            out[r, 5] = gb * fiy if Lj > 0 else 0.0
            out[r, 6], out[r, 7] = _pair_arc(ec[i], ec[j])
            out[r, 8] = 1.0 if abs(den) > tol else 0.0
            out[r, 9], out[r, 10] = Li, Lj
            r += 1


def _kind(pos: int, n: int) -> int:
    """The kind of the ``pos``-th of ``n`` edges of a stretch."""
    if n == 1:
        return _SINGLE
    if pos == 0:
        return _FIRST
    return _LAST if pos == n - 1 else _INSIDE


def _system_loop(ea: FloatArray, eb: FloatArray, ec: FloatArray, start: IntArray,
                 pairing: IntArray, margin: float, s: float, k: int, tol: float, ids: Any,
                 pA: FloatArray, prhs: FloatArray, pids: Any, pstart: IntArray, A: FloatArray,
                 rhs: FloatArray) -> int:
    """Rows ``A`` (2C, 2k; given zeroed) and right-hand sides ``rhs`` (2C) of every
    combination of the fingers' edges (finger ``f``'s edges are rows ``start[f]:start[f
    + 1]`` of the segment ends ``ea``, ``eb`` and force angles ``ec``; a fourth finger of
    gravity is one point; combinations in the order of ``itertools.product``, the last
    finger fastest).  The meets of each pair of fingers are computed once per pair of edges
    (:func:`_meets`).  Returns 0 (rows not all written) where a combination's pairing is
    null or its sector no wider than the margin, else 1, or 2 where some row has no
    variable (every coefficient zero).

    ``ids``: the part's edge of each row of ``ea``.  ``pA``, ``prhs``: the rows of a
    configuration one move away (none: no rows), its fingers' edges ``pids[pstart[f]:
    pstart[f + 1]]``.  A combination whose every edge is there with the same kind in its
    stretch (first, last, inside, single) has the same two rows there (they depend on
    the edges, their kinds, the pairing, the margin and the orientation only): they are
    copied, not computed."""
    n = np.empty(4, np.int64)
    for f in range(4):
        n[f] = start[f + 1] - start[f]
    p0, p1, p2, p3 = pairing[0], pairing[1], pairing[2], pairing[3]
    m12 = np.empty((n[p0] * n[p1], 11))
    m34 = np.empty((n[p2] * n[p3], 11))
    _meets(ea, eb, ec, start[p0], start[p0 + 1], start[p1], start[p1 + 1], tol, m12)
    _meets(ea, eb, ec, start[p2], start[p2 + 1], start[p3], start[p3 + 1], tol, m34)
    C = rhs.shape[0] // 2
    pos = np.zeros(4, np.int64)
    vel = np.empty((4, 2))
    L = np.empty(4)
    fixed = False
    PC = prhs.shape[0] // 2
    # each edge's position one move away, where its kind is the same there (else -1)
    width = 1
    for f in range(k):
        width = max(width, n[f])
    pmap = np.full((4, width), -1, np.int64)
    pn = np.ones(4, np.int64)
    if PC > 0:
        for f in range(k):
            pn[f] = pstart[f + 1] - pstart[f]
            for p in range(n[f]):
                e, kd = ids[start[f] + p], _kind(p, n[f])
                for q in range(pn[f]):
                    if pids[pstart[f] + q] == e and _kind(q, pn[f]) == kd:
                        pmap[f, p] = q
                        break
    for r in range(C):
        # finger positions of combination r (the last real finger fastest)
        rest = r
        for f in range(k - 1, -1, -1):
            pos[f] = rest % n[f]
            rest //= n[f]
        if PC > 0:
            # the same combination one move away: its rows, copied
            q = 0
            for f in range(k):
                at = pmap[f, pos[f]]
                if at < 0:
                    q = -1
                    break
                q = q * pn[f] + at
            if q >= 0:
                for side in range(2):
                    row, prow = side * C + r, side * PC + q
                    for j in range(2 * k):
                        A[row, j] = pA[prow, j]
                    rhs[row] = prhs[prow]
                    fixed = fixed or _no_variable(A, row, 2 * k)
                continue
        a12 = m12[pos[p0] * n[p1] + pos[p1]]
        a34 = m34[pos[p2] * n[p3] + pos[p3]]
        valid = a12[8] > 0 and a34[8] > 0
        cen, half = arc_meet(a12[6], a12[7], a34[6] + math.pi, a34[7])
        hm = half - margin if valid else -1.0
        if not hm > 0:
            return 0
        vel[0, 0], vel[0, 1], vel[1, 0], vel[1, 1] = a12[2], a12[3], a12[4], a12[5]
        vel[2, 0], vel[2, 1], vel[3, 0], vel[3, 1] = a34[2], a34[3], a34[4], a34[5]
        L[0], L[1], L[2], L[3] = a12[9], a12[10], a34[9], a34[10]
        k1x, k1y = s * math.cos(cen - hm), s * math.sin(cen - hm)
        k2x, k2y = s * math.cos(cen + hm), s * math.sin(cen + hm)
        for side in range(2):               # phi = k1 x . , then -(k2 x .)
            row = side * C + r
            if side == 0:
                kx, ky, sg = k1x, k1y, 1.0
            else:
                kx, ky, sg = k2x, k2y, -1.0
            v34 = kx * a34[1] - ky * a34[0]
            v12 = kx * a12[1] - ky * a12[0]
            value = (v34 if sg > 0 else -v34) - (v12 if sg > 0 else -v12)
            for p in range(4):
                fi = pairing[p]
                if fi >= k:                 # gravity: a fixed point
                    continue
                cv = kx * vel[p, 1] - ky * vel[p, 0]
                if sg < 0:
                    cv = -cv
                use_hi = cv > 0 if p < 2 else cv <= 0
                g = cv if p < 2 else -cv
                kd = _kind(pos[fi], n[fi])
                hi_var = use_hi and (kd == _SINGLE or kd == _LAST)
                lo_var = (not use_hi) and (kd == _SINGLE or kd == _FIRST)
                const = L[p] if use_hi and (kd == _FIRST or kd == _INSIDE) else 0.0
                A[row, 2 * fi + 1] += g if hi_var else 0.0
                A[row, 2 * fi] += g if lo_var else 0.0
                value = value - g * const
            rhs[row] = value
            fixed = fixed or _no_variable(A, row, 2 * k)
    return 2 if fixed else 1


def _no_variable(A: FloatArray, row: int, width: int) -> bool:
    """Whether row ``row`` of ``A`` has every coefficient zero."""
    for j in range(width):
        if A[row, j] != 0:
            return False
    return True


def _system_rows(ea_all: FloatArray, eb_all: FloatArray, ec_all: FloatArray, layout: IntArray,
                 pairing: IntArray, margin: float, s: float, k: int, tol: float, pA: FloatArray,
                 prhs: FloatArray, playout: IntArray) -> Any:
    """:func:`_system_loop` on the fingers' edges gathered from every edge's rows
    (``layout``: the four fingers' edge counts, then their edges in order; ``playout``
    the same of the configuration one move away, its counts 0 for none), its rows
    allocated here: ``(status, A, rhs)``."""
    start = np.zeros(5, np.int64)
    for f in range(4):
        start[f + 1] = start[f] + layout[f]
    ids = layout[4:]
    m = start[4]
    ea, eb, ec = np.empty((m, 2)), np.empty((m, 2)), np.empty(m)
    for i in range(m):
        e = ids[i]
        ea[i, 0], ea[i, 1] = ea_all[e, 0], ea_all[e, 1]
        eb[i, 0], eb[i, 1] = eb_all[e, 0], eb_all[e, 1]
        ec[i] = ec_all[e]
    C = 1
    for f in range(k):
        C *= layout[f]
    A = np.zeros((2 * C, 2 * k))
    rhs = np.empty(2 * C)
    pstart = np.zeros(5, np.int64)
    for f in range(4):
        pstart[f + 1] = pstart[f] + playout[f]
    status = _system_loop(ea, eb, ec, start, pairing, margin, s, k, tol, ids, pA, prhs,
                          playout[4:], pstart, A, rhs)
    return status, A, rhs


def _kept_rows(A: FloatArray, rhs: FloatArray, floor: float) -> Any:
    """The rows of ``(A, rhs)`` with a variable, copied in order, and whether every row
    without one holds (its right-hand side at least ``floor``): ``(ok, A, rhs)``, the
    check ``_frictionless_program._system`` makes with numpy (a row with a NaN
    coefficient has a variable, as ``ndarray.any`` says)."""
    n, width = A.shape
    keep = np.empty(n, np.bool_)
    count = 0
    ok = True
    for i in range(n):
        keep[i] = not _no_variable(A, i, width)
        if keep[i]:
            count += 1
        elif rhs[i] < floor:
            ok = False
    A2, rhs2 = _rows_where(A, rhs, keep, count, width)
    return ok, A2, rhs2


def _rows_where(M: FloatArray, rhs: FloatArray, keep: Any, count: int, cols: int) -> Any:
    """The ``count`` rows of ``M`` (their first ``cols`` columns) and ``rhs`` where
    ``keep``, in order."""
    out, out_rhs = np.empty((count, cols)), np.empty(count)
    r = 0
    for i in range(keep.shape[0]):
        if keep[i]:
            for j in range(cols):
                out[r, j] = M[i, j]
            out_rhs[r] = rhs[i]
            r += 1
    return out, out_rhs


def _before(a: float, b: float) -> bool:
    """Whether ``a`` sorts strictly before ``b`` (nan last, as numpy sorts)."""
    return a < b or (not np.isnan(a) and np.isnan(b))


def _first_k(v: FloatArray, k: int) -> Any:
    """``np.argsort(v, kind="stable")[:k]``: the ``k`` smallest, ties in index order
    (``_frictionless_program._smallest``), by one pass keeping the ``k`` best in
    order (a program's rows are thousands, ``k`` a few tens)."""
    n = min(k, v.size)
    out = np.empty(n, np.int64)
    size = 0
    for i in range(v.size):
        x = v[i]
        if size == n:
            if not _before(x, v[out[n - 1]]):
                continue
            size -= 1                  # the last one drops out
        # after every one it does not sort before (ties: the earlier index first)
        p = size
        while p > 0 and _before(x, v[out[p - 1]]):
            out[p] = out[p - 1]
            p -= 1
        out[p] = i
        size += 1
    return out


def _lp_loop(A0: FloatArray, b0: FloatArray, const: FloatArray, floors: FloatArray, ub: FloatArray,
             c: FloatArray, t_var: bool, unit: float, noise_row: float, tiny: float,
             check_tol: float, eps: float, direct_rows: int, per_var: int, y_out: FloatArray
             ) -> int:
    """``frictionless_stretches._lp_simplex`` of one configuration's program, in one
    compiled call, the same steps in the same order: its rows ``A0 x <= b0`` and the
    fingers' length rows (``floors``: nan where the length is at least ``t``), in units
    of ``unit``, each row scaled to a largest coefficient of 1, the upper bounds ``ub``
    as rows; solved by the dense simplex on the rows the solution needs
    (``_rows_generated``).  Returns 0 (``y_out`` the solution, in units), 1 infeasible,
    2 undecided (a noise row, the simplex out of iterations or unbounded, an answer
    that misses the rows): HiGHS then."""
    m0, nx = A0.shape
    k = nx // 2
    cols = nx + 1 if t_var else nx
    m = m0 + k
    # (the rows of A0 scaled as they are written: each product A0 * unit, then over
    # its row's largest, the numbers of a copy scaled afterwards, in two passes not four)
    M = np.empty((m + nx, cols))
    rhs = np.empty(m + nx)
    norm = np.empty(m)
    for i in range(m0):
        big = 0.0
        for j in range(nx):
            big = max(big, abs(A0[i, j] * unit))
        norm[i] = big
        rhs[i] = b0[i]
    for i in range(m0, m):
        f = i - m0
        for j in range(cols):
            M[i, j] = 0.0
        M[i, 2 * f] = 1.0 * unit
        M[i, 2 * f + 1] = -1.0 * unit
        if np.isnan(floors[f]):
            if t_var:
                M[i, nx] = 1.0 * unit
            rhs[i] = const[f]
        else:
            rhs[i] = const[f] - floors[f]
        big = 0.0
        for j in range(cols):
            big = max(big, abs(M[i, j]))
        norm[i] = big
    top = 0.0
    for i in range(m):
        top = max(top, norm[i])
    for i in range(m):
        if norm[i] <= noise_row * max(top, tiny):
            return 2
    for i in range(m0):
        for j in range(nx):
            M[i, j] = A0[i, j] * unit / norm[i]
        if t_var:
            M[i, nx] = 0.0 / norm[i]
    for i in range(m0, m):
        for j in range(cols):
            M[i, j] = M[i, j] / norm[i]
    for i in range(m):
        rhs[i] = rhs[i] / norm[i]
    for j in range(nx):
        for col in range(cols):
            M[m + j, col] = 0.0
        M[m + j, j] = 1.0
        rhs[m + j] = ub[j] / unit
    feas = check_tol / 10
    rows_all = m + nx
    per_round = per_var * cols
    active = np.zeros(rows_all, np.bool_)
    if rows_all <= direct_rows or m0 <= 0:
        active[:] = True
    else:
        active[m0:] = True
        for i in _first_k(rhs[:m0], per_round):
            active[i] = True
    y = np.zeros(cols)
    while True:
        nr = 0
        for i in range(rows_all):
            if active[i]:
                nr += 1
        Ar, br = _rows_where(M, rhs, active, nr, cols)
        dual = np.zeros(nr)
        st = _lp_max(c, Ar, br, nr, cols, y, dual, eps, feas)
        if st != 0 or nr == rows_all:
            break
        over = np.empty(m0)
        for i in range(m0):
            if active[i]:
                over[i] = np.inf           # -over: never among the worst
            else:
                acc = 0.0
                for j in range(cols):
                    acc += M[i, j] * y[j]
                over[i] = -(acc - rhs[i])
        more = False
        for i in _first_k(over, per_round):
            if -over[i] > feas:
                active[i] = True
                more = True
        if not more:
            break
    if st == 1:
        return 1
    if st != 0:
        return 2
    for i in range(rows_all):
        acc = 0.0
        for j in range(cols):
            acc += M[i, j] * y[j]
        if acc > rhs[i] + check_tol:
            return 2
    for j in range(cols):
        y_out[j] = y[j]
    return 0


_FUNCS = (_wrap_mod, _pair_arc, _edge, _meets, _kind, _no_variable, _system_loop,
          _system_rows, _rows_where, _kept_rows, _before, _first_k, _lp_loop)


def _with_simplex() -> dict[str, Any] | None:
    """The compiled formulas of :mod:`fcgrasp.core.kernels` and the dense simplex of
    :mod:`fcgrasp.core._simplex` (``_lp_max``), None where they do not run."""
    core, simplex = kernels._loops(), _simplex.compiled()
    if core is None or simplex is None:
        return None
    return {**core, "_lp_max": simplex["_lp_max"]}


#: compiled over the compiled formulas of :mod:`fcgrasp.core.kernels` (``arc_meet``) and
#: the dense simplex
COMPILED = jit.CompiledLoops(dict(globals()), _FUNCS, _with_simplex)


def kept_rows(A: FloatArray, rhs: FloatArray, floor: float
              ) -> tuple[FloatArray, FloatArray] | Literal[False] | None:
    """:func:`_kept_rows`: the rows with a variable, False where a row without one fails
    (its right-hand side below ``floor``), None where the loop does not run."""
    ok, got = COMPILED.run("_kept_rows", A, rhs, float(floor))
    if not ok:
        return None
    holds, A2, rhs2 = got
    return (A2, rhs2) if holds else False


def lp_rows(A0: FloatArray, b0: FloatArray, const: FloatArray, floors: FloatArray, ub: FloatArray,
            c: FloatArray, t_var: bool, unit: float, noise_row: float, tiny: float,
            check_tol: float, eps: float, direct_rows: int, per_var: int, checked: bool = False
            ) -> tuple[int, Any] | None:
    """:func:`_lp_loop`'s ``(status, y)``, None where the loop does not run
    (``checked``: the caller has asked whether compiled loops run here, this call
    does not ask again)."""
    if not checked and not COMPILED.available():
        return None
    cols = A0.shape[1] + 1 if t_var else A0.shape[1]
    y = np.zeros(cols)
    ok, st = COMPILED.run("_lp_loop", np.ascontiguousarray(A0, dtype=float),
                          np.ascontiguousarray(b0, dtype=float),
                          np.ascontiguousarray(const, dtype=float),
                          np.ascontiguousarray(floors, dtype=float),
                          np.ascontiguousarray(ub, dtype=float),
                          np.ascontiguousarray(c, dtype=float), bool(t_var), float(unit),
                          float(noise_row), float(tiny), float(check_tol), float(eps),
                          int(direct_rows), int(per_var), y)
    return (int(st), y) if ok else None


def edge_arrays(polygon: Polygon, gravity: Any) -> tuple[Any, Any, Any]:
    """Every edge's start, end and force angle (the inward normal's), as
    :func:`system_rows` reads them (a search builds them once: its thousands of programs
    then only gather their edges' rows); with ``gravity``, one more row: the centroid (a
    point) and gravity's angle."""
    ea, eb, nrm = polygon.starts, polygon.ends, polygon.normals
    ec = np.arctan2(-nrm[:, 1], -nrm[:, 0])
    if gravity is not None:
        cen = np.asarray(polygon.centroid, float)[None]
        ea, eb = np.r_[ea, cen], np.r_[eb, cen]
        ec = np.r_[ec, np.arctan2(gravity[1], gravity[0])]
    return (np.ascontiguousarray(ea, dtype=float), np.ascontiguousarray(eb, dtype=float),
            np.ascontiguousarray(ec, dtype=float))


#: no configuration one move away: no rows, its fingers' edge counts 0
_NO_ROWS, _NO_PARENT = np.zeros(0), np.zeros(4, np.int64)


def system_rows(polygon: Polygon, edges: Any, gravity: Any, pairing: IntArray, margin: float,
                s: float, tol: float, arrays: Any = None, parent: Any = None,
                checked: bool = False) -> tuple[Any, Any, bool] | Literal[False] | None:
    """The rows ``(A, rhs)`` of ``_frictionless_program._system`` (the fingers'
    stretches ``edges``; with ``gravity``, a fourth finger at the centroid) before its
    check of the rows without a variable, and whether there is such a row, by the
    compiled loop; False where some combination's pairing is null or its sector too
    narrow (no program), None where the loop does not run (numpy then).  ``arrays``:
    :func:`edge_arrays` of the part and gravity, built once by a search; ``parent``:
    ``(stretches, A, rhs)`` of a configuration of the same pairing and orientation one
    move away, whose rows of the combinations it shares are copied (the same numbers);
    ``checked``: the caller (a search) has asked whether the loop runs here."""
    if not checked and not COMPILED.available():
        return None
    k = len(edges)
    ea_all, eb_all, ec_all = edge_arrays(polygon, gravity) if arrays is None else arrays
    sizes = [len(st) for st in edges]
    ids = [e for st in edges for e in st]
    if gravity is not None:
        sizes.append(1)
        ids.append(polygon.n_edges)     # the centroid's row
    layout = np.array(sizes + [0] * (4 - len(sizes)) + ids, np.int64)
    if parent is None:
        pA, prhs, playout = np.zeros((0, 2 * k)), _NO_ROWS, _NO_PARENT
    else:
        pst, pA, prhs = parent
        playout = np.array([len(st) for st in pst] + [0] * (4 - k) +
                           [e for st in pst for e in st], np.int64)
    ok, got = COMPILED.run("_system_rows", ea_all, eb_all, ec_all, layout,
                           np.ascontiguousarray(pairing, dtype=np.int64), float(margin),
                           float(s), int(k), float(tol), pA, prhs, playout)
    if not ok:
        return None
    whole, A, rhs = got
    return (A, rhs, whole == 2) if whole else False
