"""The two-finger stretch search: the configurations collected behind the bound, the
runs until the ``top``-th holds and each configuration's own optimum (part of
:mod:`fcgrasp.model.stretches`; the leximin levels and the placement are
:mod:`._placement`')."""

from __future__ import annotations

from typing import Any, cast

import numpy as np

from ...core import budget
from ...core._checks import FloatArray
from ...core.jit import jit_setting
from ...core.tolerances import ANGLE_SLACK, ROUND_TOL
from . import _kernels
from ._exclusion import _Exclusion
from ._lp import _system
from ._memo import _Job, _Memo
from ._placement import _tie_keys
from ._solve import _Found, _jobs, _Keys, _solve_any, _solve_deferred, _solve_jobs
from ._whole import _Whole
from ._windows import (
    _BLOCK,
    _EPS,
    KERNEL_OWN,
    TIE,
    _both_kept,
    _Bound,
    _Configs,
    _disjoint,
    _empty,
    _fan,
    _gens_x,
    _gens_y,
    _Intervals,
    _pairs_single,
    _Ring,
    _row_intervals,
    _stretch_bound,
    _turns,
    _vertex_matrix,
    _windows_both,
    _windows_single,
    stretch_kernels_for,
)

# ----------------------------------------------------------------------------- search


def _configs_in(ra: _Ring, rb: _Ring, same: bool, runs: tuple[list[int], list[int]]
                ) -> _Configs:
    """Every configuration inside two runs of ring edges (for each stretch, the ring
    positions of its edges in order)."""
    cols = []
    for pos in runs:
        first, last = np.triu_indices(len(pos))
        cols.append((np.asarray(pos)[first], last - first))
    (ia, ka), (ic, kc) = cols
    ga = np.repeat(np.arange(ia.size), ic.size)
    gc = np.tile(np.arange(ic.size), ia.size)
    cfg = _Configs(ia[ga], ka[ga], ic[gc], kc[gc])
    return cfg.take(_disjoint(ra, cfg, same))


#: The arguments of the compiled vertex runs (:func:`vertex_run_args`).
VertexRunArgs = tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray,
                      FloatArray, FloatArray, float, float]


def vertex_run_args(ra: _Ring, rb: _Ring, beta: float) -> VertexRunArgs:
    """The arguments of the compiled vertex runs of rings ``ra`` and ``rb``
    (:func:`._kernels.vertex_runs_tree`: each ring's vertices, force generators and
    angles, the width of a cell's window and the tree's pad)."""
    gx = np.stack([g for f in _fan(ra) for g in _gens_x(f, beta)], axis=1)
    gy = np.stack([g for f in _fan(rb) for g in _gens_y(f, beta)], axis=1)
    # a cell holds only if the two force directions are opposite within 2 beta (each
    # within beta of the chord), and a vertex only if its two normals are within
    # 2 beta of each other: the kernel reads no other cell (a slack keeps it exact)
    width = 2 * beta + ANGLE_SLACK
    va = np.where(_turns(ra) <= width, np.arctan2(ra.f[:, 1], ra.f[:, 0]) + np.pi, np.nan)
    # the tree's bounds are decided with a pad far above their rounding (a few ulps
    # of the largest coordinate)
    pad = ROUND_TOL * 8 * max(float(np.abs(ra.a).max()), float(np.abs(rb.a).max()))
    return (ra.a[:, 0].copy(), ra.a[:, 1].copy(), gx, va, rb.a[:, 0].copy(),
            rb.a[:, 1].copy(), np.ascontiguousarray(gy), np.arctan2(rb.f[:, 1], rb.f[:, 0]),
            width, pad)


def _vertex_runs(ra: _Ring, rb: _Ring, beta: float) -> dict[float, Any]:
    """The runs of True of every row of the vertex matrix of each mode, as row pointers,
    first and last columns (compiled for large rings; :func:`_vertex_matrix` else)."""
    if stretch_kernels_for(ra.m * rb.m):
        out = _kernels.vertex_runs_blocks(*vertex_run_args(ra, rb, beta), budget.check_clock)
        return {1.0: out[:3], -1.0: out[3:]}
    runs = {}
    for sigma in (1.0, -1.0):
        row, first, last = _row_intervals(_vertex_matrix(ra, rb, sigma, beta))
        runs[sigma] = (np.searchsorted(row, np.arange(ra.m + 1)), first, last)
    return runs


def _both(runs: Any, ra: _Ring, rb: _Ring, same: bool, floor: float, collect: bool,
          bound: _Bound | None = None, copies: tuple[FloatArray, FloatArray] | None = None,
          between: Any = None, cap: int | None = None) -> tuple[FloatArray, _Configs]:
    """:func:`_windows_both`, compiled for large rings (pruned by ``bound``'s value: the
    lower bounds it leaves out could not raise it; ``copies``: the kept plans' columns
    whose surely copies from ``floor`` on the compiled collection leaves out,
    :meth:`_Exclusion.copy_columns`; ``between`` and ``cap``: called between the compiled
    collection's blocks of rows, and the most windows it may hold,
    :func:`fcgrasp.model.stretches._kernels.windows`)."""
    ptr, first, last = runs
    if stretch_kernels_for(ra.m * rb.m):
        # (a collection reads each row from its first window long enough, by the
        # sparse table of runs, whatever the bound)
        value, keep = (bound.value, bound.k) if bound is not None else (0.0, int(collect))
        ex, exs = copies if copies is not None else (None, None)
        best, *cfg = _kernels.windows(ptr, first, last, ra.U, rb.U, ra.m, rb.m, floor,
                                              collect, same, value, keep, ex=ex, exs=exs,
                                              between=between, cap=cap)
        return best, _both_kept(_Configs(*cfg), ra, rb, same)
    return _windows_both(runs, ra, rb, same, floor, collect)


def _single(iv: _Intervals, ra: _Ring, rb: _Ring, same: bool, floor: float, collect: bool,
            bound: _Bound | None = None, offsets: tuple[int, int] = (0, 0)
            ) -> tuple[tuple[np.ndarray, np.ndarray, FloatArray], _Configs]:
    """:func:`_windows_single`, compiled for large rings (without ``collect``, pruned by
    ``bound``'s value: the edges it skips could not raise it; ``offsets``: the rings'
    first keys, :class:`_Keys`)."""
    if not stretch_kernels_for(ra.m * rb.m):
        return _windows_single(iv, ra, rb, same, floor, collect)
    A = np.flatnonzero(ra.L >= floor)
    value, keep = (bound.value, bound.k) if bound is not None and not collect else (0.0, 0)
    if keep:
        A = A[np.argsort(-ra.L[A], kind="stable")]          # the longest first
    width = 2 * iv.beta + ANGLE_SLACK
    order, angle_b = _by_angle(rb)
    va = np.arctan2(ra.f[:, 1], ra.f[:, 0]) + np.pi
    wa, wp, wv, iA, iC, kC = _kernels.single(
        A, ra.a[:, 0].copy(), ra.a[:, 1].copy(), ra.t[:, 0].copy(), ra.t[:, 1].copy(), ra.L,
        iv.gx, va, rb.a[:, 0].copy(), rb.a[:, 1].copy(), iv.gy, order, angle_b, width, rb.U,
        iv.sigma, _EPS, floor, collect, same, value, keep, *offsets)
    cfg = _Configs(iA, np.zeros(iA.size, int), iC, kC)
    return (wa, wp, wv), cfg.take(_disjoint(ra, cfg, same))


def _by_angle(ring: _Ring) -> tuple[np.ndarray, FloatArray]:
    """The ring's edges in order of their force direction's angle, and those angles."""
    angle = np.arctan2(ring.f[:, 1], ring.f[:, 0])
    order = np.argsort(angle, kind="stable")
    return order, angle[order]


def _guessed_floors(bound: _Bound) -> list[float]:
    """The floors :func:`_candidates` guesses from the bound's keys, highest first, each
    above the bound's own floor."""
    seen = np.sort(bound.best[bound.best > 0])[::-1]
    if not seen.size:
        return []
    m = min(bound.k, seen.size)
    ranks = [-(-m // 4), -(-m // 2)] + ([seen.size] if seen.size < bound.k else [])
    assert len(ranks) <= _GUESSES
    out: list[float] = []
    for r in ranks:
        g = float(seen[r - 1]) * (1 - TIE)
        if g > bound.floor and (not out or g < out[-1]):
            out.append(g)
    return out


def _reach(ring: _Ring) -> float:
    """The longest region a ring holds, with rounding's room: its perimeter."""
    return float(ring.U[ring.m]) * (1 + ROUND_TOL)


def _candidates(rings: list[_Ring], bound: _Bound, intervals: dict[Any, _Intervals],
                runs: dict[Any, Any], keys: _Keys, prebound: bool = True,
                guesses: list[float] | None = None, lower: bool = True,
                max_configs: int | None = None, exclude: _Exclusion | None = None,
                cap: int | None = None) -> list[tuple[Any, _Configs]]:
    """Every configuration that can reach the bound, per job (exhaustive: the bound
    only rises with feasible configurations, one per key).  ``prebound`` False: the
    vertex-aligned stretches do not raise the bound (an excluded plan's copies would);
    with a fixed floor, without ``prebound`` or without ``lower``, they are not
    computed.

    ``guesses`` (an empty list): floors above the bound's own, guessed from the keys'
    values, are put in it, highest first, and the bound starts at the first
    (``bound.start``).  One key holds many of the top configurations of a smooth
    outline, so the ``top``-th key is far below the ``top``-th configuration (and 0
    where fewer keys are filled): the keys a quarter and half of the way down (of
    ``top`` or of those filled), and the last filled when fewer than ``top``.
    :func:`_search` checks that the ``top``-th found reaches the floor, and takes the
    next guess when not.

    ``max_configs``: the most configurations to collect; one job's collection that
    takes the count over it ends the search (:class:`~fcgrasp.core.budget.
    BudgetExhausted`, ``"max_memory"``), before the next job's.  ``exclude``: the
    windows of both stretches that are surely a kept plan's copies at any smallest
    region from the floor on are not collected (:meth:`_Exclusion.copy_columns`;
    :func:`_search` then solves their beaters on demand, :func:`_inner_beaters`).
    ``cap``: the most configurations a collection may hold, for speed: more end it
    (``BudgetExhausted``, ``"collection"``) within a block of rows of going over, and
    :meth:`~fcgrasp.model.stretches.StretchSearch.pairs` tries another floor."""
    count = 0
    prepared = []
    for collect in (False, True):          # the lower bound first, then the candidates
        if not collect and (not (prebound and lower) or bound.fixed is not None):
            continue                        # no lower bound would count
        if collect and guesses is not None and bound.fixed is None:
            guesses[:] = _guessed_floors(bound)
            if guesses:
                bound.start = guesses.pop(0)
        for job in _jobs(len(rings)):
            budget.check_clock()
            x, y, sigma, _ = job
            ra, rb = rings[x], rings[y]
            both = _empty()
            if collect and min(_reach(ra), _reach(rb)) < bound.floor:
                # none of this job reaches the floor (the holes of a plate, once a plan
                # on the outline sets it)
                prepared.append((job, both))
                continue
            if x <= y:
                copies = exclude.copy_columns(rings, x, y, bound.floor) \
                    if collect and exclude is not None else None
                # a distinct round's collection may be ended by the budget; the ranked
                # search's first answer only inside a deeper read (budget.poll)
                best, both = _both(runs[x, y][sigma], ra, rb, x == y, bound.floor, collect,
                                   bound if prebound and bound.fixed is None else None,
                                   copies, budget.check if exclude else budget.poll,
                                   None if cap is None or not collect else cap - count)
                if not collect and prebound:
                    # stretch 1 comes first (ring x <= y; on one ring, it starts first)
                    rows = np.flatnonzero(best > 0)
                    bound.add(keys.first(job, rows), best[rows])
            (a, p, v), single = _single(
                intervals[x, y, sigma], ra, rb, x == y, bound.floor, collect,
                bound if prebound and bound.fixed is None else None,
                (int(keys.offset[x]), int(keys.offset[y])))
            if not collect and prebound:
                bound.add(keys(job, a, p), v)
            if collect:
                pairs = _pairs_single(ra, rb, x == y, bound.floor) if x <= y else _empty()
                prepared.append((job, _Configs.cat([both, single, pairs])))
                count += int(prepared[-1][1].iA.size)
                if max_configs is not None and count > max_configs:
                    raise budget.BudgetExhausted("max_memory")
                if cap is not None and count > cap:
                    raise budget.BudgetExhausted("collection")
    return prepared


#: Searches :func:`_search` runs at most before it solves every configuration.
_ATTEMPTS = 5


#: Whether the first search guesses floors from its keys' values (:func:`_candidates`).
_GUESS = True


#: Floors :func:`_guessed_floors` guesses at most (a quarter and half of the way down
#: the keys, and the last key filled).
_GUESSES = 3


#: Times a guessed floor that keeps fewer than ``top`` (the own-optimum filter drops
#: most of a smooth outline's configurations, while the bound, which counts them, rises
#: above the floor) is halved and fixed before the bound's own is tried.
_HALVINGS = 3


def _search(rings: list[_Ring], beta: float, intervals: dict[Any, _Intervals],
            runs: dict[Any, Any], top: int | None, scale: float,
            exclude: _Exclusion | None = None, memo: _Memo | None = None,
            cap: Any = None) -> list[_Found]:
    """The configurations optimal on their own edges (:func:`_own_optimum`), largest
    ``t`` first: all of them (``top`` None), or at least every one that ties the
    ``top``-th (to the relative tie tolerance).

    The bound counts feasible configurations, but a configuration beaten by one of its
    own sub-configurations is dropped afterwards, so the ``top``-th kept can fall below
    the floor the search pruned with.  The search is then run again with the floor
    fixed at that ``top``-th (every configuration that reaches it solved, its
    sub-configurations with it), until the floor it pruned with is below the
    ``top``-th it kept; when fewer than ``top`` are kept, with a bound of four times as
    many; the last attempt prunes nothing.  ``exclude``: configurations surely the
    same alternative as a kept plan are left out (after the filter, which they still
    take part in); they then run without the vertex-aligned lower bound, on every
    configuration, shared with other runs through ``memo``.  ``cap``
    (:func:`~fcgrasp.model.stretches._solve._solve_jobs`): the configurations are ranked by
    their ``value``, ``t`` capped, and run without the vertex-aligned lower bound (a
    bound on ``t``, not on the value); the own-optimum filter still compares ``t``."""
    keys = _Keys(rings)
    if not exclude and cap is None:
        memo = None
    whole = _Whole(rings, runs) if exclude else None
    want, fixed = top, None
    # floors guessed by the first search (_candidates), tried in turn while too high
    guesses: list[float] | None = [] if _GUESS and top is not None and cap is None else None
    guessing, start, halve = False, 0.0, 0
    attempts = _ATTEMPTS + (_GUESSES + _HALVINGS if _GUESS else 0)
    for attempt in range(attempts):
        if top is None or attempt == attempts - 1:
            fixed = 0.0
        # an excluded plan's copies add no lower bounds: each configuration counts once
        bound = _Bound(want or 1, 2 * keys.total, fixed, start,
                       each=bool(exclude) or cap is not None)
        if memo is not None and memo.prepared is not None:
            prepared = memo.prepared
        elif memo is not None:
            prepared = memo.prepared = _candidates(
                rings, _Bound(1, 2 * keys.total, memo.floor), intervals, runs, keys,
                prebound=False, max_configs=memo.max_configs, exclude=exclude,
                cap=memo.cap)
        else:
            prepared = _candidates(rings, bound, intervals, runs, keys,
                                   prebound=not exclude and cap is None,
                                   guesses=guesses if attempt == 0 else None,
                                   lower=not start)
        if attempt == 0:
            guessing = bound.start > 0
        similar: dict[Any, tuple[_Job, list[np.ndarray]]] = {}
        deferred: dict[Any, tuple[_Job, list[np.ndarray]]] = {}
        found = _solve_jobs(rings, beta, prepared, intervals, bound, scale, keys, exclude,
                            memo, similar, deferred, cap, whole)
        if deferred:
            _solve_deferred(rings, beta, intervals, scale, found, bound.floor, deferred,
                            similar)
        tie = _tie_keys(rings)
        found.sort(key=lambda f: (-f.value, *tie(f)))
        if memo is None:
            found = [f for f in _own_optimum(rings, found, similar) if not f.similar]
        else:
            # the copies the collection left out beat some found configurations: asked
            # on demand of those that would be returned
            floor_m = memo.floor
            found = _own_optimum(
                rings, found, similar, top,
                lambda head, f=floor_m: _beaten_on_demand(rings, beta, intervals, scale,
                                                          head, f))
        if top is None or bound.floor == 0.0:
            break                           # nothing was pruned
        if len(found) >= top:
            kth = found[top - 1].value * (1 - TIE)
            if bound.floor <= kth:
                break
            fixed, start, guessing = kth, 0.0, False
        elif guessing and guesses:          # the next guess (then the bound's own)
            start = guesses.pop(0)
        elif guessing and halve < _HALVINGS:   # then half the last floor, fixed
            fixed, start, halve = bound.floor / 2, 0.0, halve + 1
        elif guessing:
            fixed, start, guessing = None, 0.0, False
        else:
            want, fixed = 4 * (want or 1), None
    return found


def _beaten_on_demand(rings: list[_Ring], beta: float, intervals: dict[Any, _Intervals],
                      scale: float, head: list[_Found], floor: float) -> set[int]:
    """The ``id`` of each configuration of ``head`` beaten by one inside it that the
    collection left out as a kept plan's copy (:func:`_inner_beaters`)."""
    extra = _inner_beaters(rings, beta, intervals, scale, head, floor)
    if not extra:
        return set()
    kept = {id(f) for f in _own_optimum(rings, head + extra) if not f.similar}
    return {id(f) for f in head if id(f) not in kept}


def _inner_beaters(rings: list[_Ring], beta: float, intervals: dict[Any, _Intervals],
                   scale: float, found: list[_Found], floor: float) -> list[_Found]:
    """Every configuration inside a found one reaching ``floor`` that could beat it in
    :func:`_own_optimum` (its arc bound above the found one's ``t`` by the tie
    tolerance), solved, as ``similar`` entries: the beaters of the configurations a
    distinct round's collection leaves out as a kept plan's copies
    (:meth:`_Exclusion.copy_columns`).  A found configuration's stretches are about as
    long as its regions, so it holds few such configurations (every one is counted
    against the time budget)."""
    by_job: dict[Any, list[np.ndarray]] = {}
    for f in found:
        if f.t < floor or f.similar or max(f.cfg[1], f.cfg[3]) == 0:
            continue
        x, y, _, _ = f.job
        need = f.t * (1 + TIE)
        subs = [_sub_stretches(rings[x], f.cfg[0], f.cfg[1], need),
                _sub_stretches(rings[y], f.cfg[2], f.cfg[3], need)]
        if not (subs[0].size and subs[1].size):
            continue
        ga = np.repeat(np.arange(len(subs[0])), len(subs[1]))
        gc = np.tile(np.arange(len(subs[1])), len(subs[0]))
        by_job.setdefault(f.job, []).append(np.concatenate([subs[0][ga], subs[1][gc]], axis=1))
    out: list[_Found] = []
    for job, parts in by_job.items():
        budget.check()
        x, y, sigma, _ = job
        ra, rb = rings[x], rings[y]
        c = np.unique(np.concatenate(parts), axis=0)
        cfg = _Configs(c[:, 0], c[:, 1], c[:, 2], c[:, 3])
        cfg = cfg.take(_disjoint(ra, cfg, x == y))
        if not cfg.iA.size:
            continue
        compiled = stretch_kernels_for(ra.m * rb.m)
        rows = _system(ra, rb, cfg, sigma, beta, intervals[x, y, sigma],
                       intervals[y, x, sigma], compiled=compiled)
        t, s0, u0 = _solve_any(rows, _stretch_bound(ra, rb, cfg), scale, compiled)
        for j in np.flatnonzero(t > 0):
            out.append(_Found(job, (int(cfg.iA[j]), int(cfg.kA[j]), int(cfg.iC[j]),
                                    int(cfg.kC[j])), float(t[j]), float(s0[j]),
                              float(u0[j]), similar=True))
    return out


def _sub_stretches(ring: _Ring, i: int, k: int, need: float) -> np.ndarray:
    """The stretches inside edges ``i .. i + k`` of ``ring`` whose arc length reaches
    ``need``, as rows ``(first edge, interior vertices)``: for each first edge, the
    last edges from the first that reaches it on."""
    m = ring.m
    i0 = i % m + m
    U = ring.U
    starts = i0 + np.arange(k + 1)
    end = U[i0 + k + 1]
    starts = starts[U[starts] + need <= end]
    if not starts.size:
        return np.zeros((0, 2), np.int64)
    # the first last edge e with U[e + 1] - U[start] >= need, up to the last edge i0 + k
    first_last = np.searchsorted(U, U[starts] + need, side="left") - 1
    first_last = np.maximum(first_last, starts)
    n = i0 + k - first_last + 1             # at least 1: every start reaches ``need``
    s = np.repeat(starts, n)
    last = np.repeat(first_last, n) + (np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n))
    return np.stack([s - m, last - s], axis=1).astype(np.int64)


def _own_optimum(rings: list[_Ring], found: list[_Found],
                 similar: dict[Any, tuple[_Job, list[np.ndarray]]] | None = None,
                 top: int | None = None, demand: Any = None) -> list[_Found]:
    """The configurations that are optimal on their own edges: a configuration whose
    smallest region is beaten by one of its sub-configurations (fewer edges on either
    side, all of them found, since they rank higher) is not a plan of those edges.
    ``similar`` (:func:`_solve_jobs`): configurations found but filed by index, which
    take part as beaters; only ``found`` is returned.  With ``top`` (``found`` in the
    search's order), only its head is decided and returned: the first ``top`` own
    optima and every one that ties the ``top``-th (a distinct round's collection holds
    thousands of configurations below them, each a beater, none an answer).  ``demand``:
    a function of the own optima decided (a list) that gives the ``id`` of those beaten
    by configurations not in ``found`` (asked once per configuration); they are left
    out, and those behind move up."""
    if top is None or demand is None and len(found) <= 2 * top:
        alive = _own_optimum_of(rings, found, np.ones(len(found), bool), similar)
        return [f for f in alive if not f.similar]
    limit = min(2 * top, len(found))
    # the order ``found`` is in (the search's ranking value: ``t``, or capped)
    ts = np.array([f.value for f in found], float)
    asked: set[int] = set()
    beaten: set[int] = set()
    groups = _job_groups(found, similar)
    while True:
        check = ts >= (ts[limit - 1] * (1 - TIE) if limit else np.inf)
        check[:limit] = True
        alive = [f for f in _own_optimum_of(rings, found, check, similar, groups)
                 if not f.similar]
        if demand is not None:
            new = [f for f in alive if id(f) not in asked]
            asked.update(id(f) for f in new)
            if new:
                beaten |= demand(new)
            alive = [f for f in alive if id(f) not in beaten]
        n_checked = int(check.sum())
        # decided: the top-th own optimum and its ties lie above every row not checked
        if n_checked == len(found) or (len(alive) >= top and alive[top - 1].value * (1 - TIE)
                                       > ts[n_checked]):
            return alive
        limit = min(2 * limit, len(found))


def _job_groups(found: list[_Found],
                similar: dict[Any, tuple[_Job, list[np.ndarray]]] | None = None
                ) -> list[tuple[Any, list[int], np.ndarray, FloatArray]]:
    """The rows of ``found`` by job, each job's configurations and ``t`` as arrays (its
    rows first, then those ``similar`` files under it): what :func:`_own_optimum_of`
    reads, made once for the calls of one :func:`_own_optimum`."""
    by_job: dict[Any, list[int]] = {}
    for j, f in enumerate(found):
        by_job.setdefault(f.job, []).append(j)
    out = []
    for job, idx in by_job.items():
        c = np.array([found[j].cfg for j in idx], dtype=np.int64).reshape(-1, 4)
        t = np.array([found[j].t for j in idx], dtype=float)
        if similar is not None and job in similar:
            J, parts = similar[job]
            extra = np.concatenate(parts)
            c = np.concatenate([c, np.stack([J.cfg.iA[extra], J.cfg.kA[extra],
                                             J.cfg.iC[extra], J.cfg.kC[extra]], axis=1)])
            t = np.concatenate([t, J.t[extra]])
        out.append((job, idx, c, t))
    return out


def _own_optimum_of(rings: list[_Ring], found: list[_Found], check: np.ndarray,
                    similar: dict[Any, tuple[_Job, list[np.ndarray]]] | None = None,
                    groups: list[tuple[Any, list[int], np.ndarray, FloatArray]] | None = None
                    ) -> list[_Found]:
    """:func:`_own_optimum` of the rows of ``found`` that ``check`` marks (every row a
    beater), those kept in order; ``groups``: :func:`_job_groups` of ``found`` and
    ``similar``, made by the caller."""
    keep = check.copy()
    for job, idx, c, t in _job_groups(found, similar) if groups is None else groups:
        ra, rb = rings[job[0]], rings[job[1]]
        if c[:, [1, 3]].max() == 0 or not check[idx].any():
            continue
        n = len(idx)
        if len(c) >= KERNEL_OWN and jit_setting() is not False:
            rows = np.zeros(len(c), bool)
            rows[:n] = check[idx]
            keep[np.asarray(idx)] &= _kernels.beaten(c, t, ra.m, rb.m,
                                                             job[0] == job[1], TIE, rows)[:n]
            continue

        def inside(i: np.ndarray, k: np.ndarray, i2: np.ndarray, k2: np.ndarray,
                   m: int) -> np.ndarray:
            # [sub] stretch (rows) inside [super] stretch (columns), cyclically
            return cast("np.ndarray", (i[:, None] - i2[None, :]) % m + k[:, None] <= k2[None, :])

        at = np.asarray(idx)
        # supers (the found ones checked) in blocks of columns: the (sub, super) matrix
        # stays about 1M cells; every configuration, filed ones too, a sub
        sel = np.flatnonzero(check[at])
        step = max(1, (_BLOCK * 32) // len(c))
        for b0 in range(0, sel.size, step):
            cols = sel[b0:b0 + step]
            cs, ts = c[cols], t[cols]
            sub = inside(c[:, 0], c[:, 1], cs[:, 0], cs[:, 1], ra.m) \
                & inside(c[:, 2], c[:, 3], cs[:, 2], cs[:, 3], rb.m)
            if job[0] == job[1]:        # one ring: a pair may be stored either way round
                sub |= inside(c[:, 0], c[:, 1], cs[:, 2], cs[:, 3], ra.m) \
                    & inside(c[:, 2], c[:, 3], cs[:, 0], cs[:, 1], ra.m)
            beaten = sub & (t[:, None] > ts[None, :] * (1 + TIE))
            keep[at[cols][beaten.any(axis=0)]] = False
    return [f for f, k in zip(found, keep, strict=True) if k]


