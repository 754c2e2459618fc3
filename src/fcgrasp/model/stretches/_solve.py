"""The two-finger stretch search's solving: configurations collected per job, bounded,
solved in chunks behind the bound and shared by the runs of a distinct search (part of
:mod:`fcgrasp.model.stretches`)."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any, cast

import numpy as np

from ...core import budget
from ...core._checks import FloatArray
from ...core.tolerances import DEFER_PAD, ROUND_TOL
from . import _kernels, _windows
from ._exclusion import _Exclusion
from ._lp import _box_bound, _solve, _system
from ._memo import _Job, _Memo
from ._windows import (
    _EPS,
    KERNEL_CELLS,
    KERNEL_CONFIGS,
    TIE,
    _Bound,
    _Configs,
    _Intervals,
    _Ring,
    _stretch_bound,
    stretch_kernels_for,
)


@dataclass(slots=True)
class _Found:
    """A solved configuration: ring pair and mode (the job), covered edges, the common
    length ``t`` and the placement; after the second level, both lengths."""

    job: tuple[int, int, float, str]
    cfg: tuple[int, int, int, int]
    t: float
    s0: float
    u0: float
    lengths: tuple[float, float] = (0.0, 0.0)
    #: the same alternative as a plan the caller excludes (:class:`_Exclusion`)
    similar: bool = False
    #: :func:`_pairs`' placement, with the ``(s0, u0, lengths)`` it was placed at
    placed: tuple[Any, Any] | None = field(default=None, repr=False, compare=False)
    #: what the search ranks it by: ``t``, or with a cap (three fingers' pair plans) the
    #: smaller of ``t`` and the cap, a bound on its pair plan's smallest region
    value: float = -1.0

    def __post_init__(self) -> None:
        if self.value < 0:
            self.value = self.t


def _jobs(n_rings: int) -> list[tuple[int, int, float, str]]:
    return [(x, y, sigma, mode) for x in range(n_rings) for y in range(n_rings)
            for sigma, mode in ((1.0, "squeeze"), (-1.0, "expand"))]


class _Keys:
    """Keys of :class:`_Bound`: a mode and the first start edge of a configuration's two
    stretches (rings numbered one after the other)."""

    def __init__(self, rings: list[_Ring]) -> None:
        self.offset = np.concatenate([[0], np.cumsum([r.m for r in rings])]).astype(int)
        self.total = int(self.offset[-1])

    def _edge(self, ring: int, pos: Any, sigma: float) -> np.ndarray:
        m = self.offset[ring + 1] - self.offset[ring]
        return cast("np.ndarray", self.offset[ring] + np.asarray(pos) % m
                    + (0 if sigma > 0 else self.total))

    def __call__(self, job: tuple[int, int, float, str], a: Any, b: Any) -> np.ndarray:
        """The key of pairs starting at edges ``a`` (ring x) and ``b`` (ring y)."""
        x, y, sigma, _ = job
        return cast("np.ndarray", np.minimum(self._edge(x, a, sigma), self._edge(y, b, sigma)))

    def first(self, job: tuple[int, int, float, str], a: Any) -> np.ndarray:
        """The key of pairs whose stretch 1 (edge ``a`` of ring x) comes first."""
        return self._edge(job[0], a, job[2])


def _solve_any(rows: FloatArray, ub: FloatArray, scale: float, compiled: bool,
               floor: float = 0.0) -> tuple[FloatArray, FloatArray, FloatArray]:
    """:func:`~fcgrasp.model.stretches._lp._solve`, or its compiled loop; there, with
    ``floor`` > 0, a configuration whose largest ``t`` is surely below it gets NaN
    (unsolved: see :func:`_solve_in`)."""
    if compiled:
        t, s0, u0 = _kernels.solve_rows(rows, ub, ROUND_TOL * scale, _EPS, floor)
        return t, s0, u0
    with _windows.numpy_counted():
        return _solve(rows, ub, scale)


def _job(rings: list[_Ring], job: Any, cfg: _Configs, intervals: dict[Any, _Intervals],
         floor: float, lazy: bool = False) -> _Job:
    """A job's configurations reaching ``floor``, ordered by the ends' boxes; ``lazy``
    (a job kept for later runs, whose floors are not known yet): ordered by arc
    length, the boxes NaN until :func:`_fill_boxes` reads them."""
    x, y, sigma, _ = job
    ra, rb = rings[x], rings[y]
    ub = _stretch_bound(ra, rb, cfg)
    keep = ub >= floor
    cfg, ub = cfg.take(keep), ub[keep]
    # many to solve: the compiled loops repay numba's start-up
    compiled = stretch_kernels_for(ra.m * rb.m if ub.size < KERNEL_CONFIGS
                                   else KERNEL_CELLS)
    if lazy:
        nan = np.full(ub.size, np.nan)
        return _Job(cfg, ub, nan.copy(), np.argsort(-ub, kind="stable"), compiled, nan,
                    nan.copy(), nan.copy(), np.zeros(ub.size))
    # the ends' boxes bound a configuration far below its arc length where the ends are
    # confined: solved in that order, pruned by it (the arc length stays the program's
    # cap, so each configuration's solution is unchanged)
    box = np.minimum(ub, _box_bound(ra, rb, cfg, intervals[x, y, sigma],
                                    intervals[y, x, sigma], compiled))
    nan = np.full(ub.size, np.nan)
    return _Job(cfg, ub, box, np.argsort(-box, kind="stable"), compiled, nan,
                nan.copy(), nan.copy(), np.zeros(ub.size))


def _lower(job: Any, J: _Job, idx: np.ndarray, whole: Any) -> FloatArray | None:
    """The lower bounds ``J.lower`` of the configurations ``idx``, read by ``whole``
    (:func:`_solve_jobs`) where not read yet; None where it does not read the job."""
    if whole is None or not whole.reads(job):
        return None
    if J.lower is None:
        J.lower = np.full(len(J.ub), np.nan)
    todo = idx[np.isnan(J.lower[idx])]
    if todo.size:
        J.lower[todo] = whole(job, J.cfg.take(todo))
    out: FloatArray = J.lower[idx]
    return out


def _fill_boxes(rings: list[_Ring], job: Any, J: _Job, chunk: np.ndarray,
                intervals: dict[Any, _Intervals], whole: Any = None) -> None:
    """The ends' boxes of a lazy job's configurations ``chunk`` not yet bounded; with
    ``whole`` (:func:`_solve_jobs`), first their lower bounds: where the whole windows
    hold, the largest square is the arc length bound itself, the box."""
    todo = chunk[np.isnan(J.box[chunk])]
    if not todo.size:
        return
    x, y, sigma, _ = job
    lb = _lower(job, J, todo, whole)
    if lb is not None:
        shown = lb > 0
        J.box[todo[shown]] = J.ub[todo[shown]]
        todo = todo[~shown]
        if not todo.size:
            return
    J.box[todo] = np.minimum(J.ub[todo], _box_bound(
        rings[x], rings[y], J.cfg.take(todo), intervals[x, y, sigma],
        intervals[y, x, sigma], J.compiled))


#: Whether the compiled solve leaves the configurations it proves below the run's floor
#: unsolved (1; 0: every configuration solved in full, the reference).
FLOOR_SOLVE = 1


#: Configurations :func:`_solve_jobs` reads at a time: the first chunk (the floor
#: rises with each), and the largest a lazy job's chunks grow to (each twice the last:
#: most of a distinct search's configurations are a kept plan's copies, only
#: bounded and deferred, at a numpy call's cost per chunk, not per configuration).
CHUNK, LAZY_CHUNK = 256, 16384


def _chunks(order: np.ndarray, grow: bool) -> Any:
    """``order`` in chunks of :data:`CHUNK`, growing to :data:`LAZY_CHUNK` if ``grow``."""
    s, size = 0, CHUNK
    while s < order.size:
        yield order[s:s + size]
        s += size
        if grow:
            size = min(2 * size, LAZY_CHUNK)


def _solve_in(rings: list[_Ring], job: Any, J: _Job, todo: np.ndarray, beta: float,
              intervals: dict[Any, _Intervals], scale: float, floor: float = 0.0) -> None:
    """Solve the configurations ``todo`` of ``job`` into its arrays ``J.t``, ``J.s0``,
    ``J.u0``.  With ``floor`` (the run's: the bound's, or the memo's, below which a run's
    answer is not taken; a configuration below it can neither reach an answer taken
    nor beat one of its configurations), the compiled solve leaves those it proves
    below it NaN, unsolved (:func:`~fcgrasp.model.stretches._solve_kernels._below`): not kept,
    and solved again by a later run whose floor is lower."""
    if not todo.size:
        return
    x, y, sigma, _ = job
    if not J.compiled and stretch_kernels_for(0):     # the numpy budget spent
        J.compiled = True
    rows = _system(rings[x], rings[y], J.cfg.take(todo), sigma, beta, intervals[x, y, sigma],
                   intervals[y, x, sigma], compiled=J.compiled)
    J.t[todo], J.s0[todo], J.u0[todo] = _solve_any(rows, J.ub[todo], scale, J.compiled,
                                                   floor)
    if floor > 0:
        J.below[todo[np.isnan(J.t[todo])]] = floor


@dataclass
class _Run:
    """One job of :func:`_solve_jobs`: what :meth:`settle` reads and where it files."""

    rings: list[_Ring]
    job: Any
    J: _Job
    beta: float
    intervals: dict[Any, _Intervals]
    scale: float
    exclude: _Exclusion | None
    similar: dict[Any, tuple[_Job, list[np.ndarray]]] | None
    found: list[_Found]
    bound: _Bound
    keys: _Keys
    #: the memo's floor (0 without one): below it the run's answer is not taken
    least: float = 0.0
    #: each configuration's cap (:func:`_solve_jobs`' ``cap``), read before it is settled
    caps: FloatArray | None = None

    def settle(self, chunk: np.ndarray) -> None:
        """Solve what of ``chunk`` is not yet solved, then file (a kept plan's copies in
        ``similar``), keep and count (the bound) the chunk."""
        J, job, cfg = self.J, self.job, self.J.cfg
        floor = FLOOR_SOLVE * max(self.bound.floor, self.least)
        # not solved yet, nor proved below this floor by an earlier run
        proved = J.below[chunk]         # below that floor, so below this one if higher
        todo = chunk[np.isnan(J.t[chunk]) & ~((proved > 0) & (proved <= floor))]
        _solve_in(self.rings, job, J, todo, self.beta, self.intervals, self.scale, floor)
        part = cfg.take(chunk)
        t, s0, u0 = J.t[chunk], J.s0[chunk], J.u0[chunk]
        ok = np.flatnonzero(t > 0)
        whole = J.lower[chunk[ok]] > 0 if J.lower is not None else None
        sim = self.exclude.similar(self.rings, job, part.take(ok), t[ok], self.intervals,
                                   whole) if self.exclude else np.zeros(ok.size, bool)
        if self.similar is not None and sim.any():
            self.similar.setdefault(job, (J, []))[1].append(chunk[ok[sim]])
            ok, sim = ok[~sim], sim[~sim]
        value = t if self.caps is None else np.minimum(t, self.caps[chunk])
        # one conversion per column (Python numbers, as int() and float() of each give)
        at = chunk[ok]
        append = self.found.append
        for a, b, c, d, tj, sj, uj, same, vj in zip(
                cfg.iA[at].tolist(), cfg.kA[at].tolist(), cfg.iC[at].tolist(),
                cfg.kC[at].tolist(), t[ok].tolist(), s0[ok].tolist(), u0[ok].tolist(),
                sim.tolist(), value[ok].tolist(), strict=True):
            append(_Found(job, (a, b, c, d), tj, sj, uj, similar=same, value=vj))
        ok = ok[~sim]
        self.bound.add(self.keys(job, part.iA[ok], part.iC[ok]), value[ok])


def _solve_jobs(rings: list[_Ring], beta: float, prepared: list[tuple[Any, _Configs]],
                intervals: dict[Any, _Intervals], bound: _Bound, scale: float,
                keys: _Keys, exclude: _Exclusion | None = None,
                memo: _Memo | None = None,
                similar: dict[Any, tuple[_Job, list[np.ndarray]]] | None = None,
                deferred: dict[Any, tuple[_Job, list[np.ndarray]]] | None = None,
                cap: Any = None, whole: Any = None) -> list[_Found]:
    """The largest square pair of every configuration that can still reach the top
    (largest bound first, in chunks; ties with the ``k``-th kept).  With ``exclude``,
    the configurations that are surely a kept plan's alternative do not raise the
    bound: marked ``similar``, or, given the dict ``similar``, filed there (their
    indices in their job's configurations: on a curved outline they are tens of
    thousands, and only :func:`_own_optimum` reads them).  With ``memo``,
    configurations solved by an earlier run are not solved again.  Given the dict
    ``deferred`` as well, a configuration that is surely a kept plan's alternative at
    any smallest region above a threshold (:meth:`_Exclusion.threshold`) below its
    bound can be a plan only below that threshold: it waits until the job's other
    configurations are done, then is solved in the order of the thresholds while they
    reach the floor.  Those left are excluded or below the floor, filed in
    ``deferred``; only :func:`_own_optimum` could read them, as beaters
    (:func:`_solve_deferred`).

    ``cap(job, cfg)``: for each configuration a length its value cannot exceed (three
    fingers' pair plans: the third finger's widest free stretch); the search then ranks,
    bounds and prunes by the smaller of ``t`` and the cap (a configuration whose cap is
    below the floor is not solved), each still solved for its own ``t``.

    ``whole(job, cfg)`` (:class:`~fcgrasp.model.stretches._whole._Whole`, for the jobs
    it reads): a lower bound of each configuration's ``t`` where its whole windows hold
    (0 where that is not shown), then exactly its ``t``: that is its box,
    its spans are its whole end edges (:meth:`_Exclusion.similar`), and a deferred
    configuration whose bound reaches its threshold is a kept plan's copy at its
    largest square, filed in ``deferred`` unsolved."""
    found: list[_Found] = []
    for job, cfg in prepared:
        if memo is None:
            J = _job(rings, job, cfg, intervals, bound.floor)
        elif job in memo.jobs:
            J = memo.jobs[job]
        else:
            J = memo.jobs[job] = _job(rings, job, cfg, intervals, memo.floor, lazy=True)
            memo.restore(job, J)
        cfg, ub, box, order = J.cfg, J.ub, J.box, J.order

        if cap is not None and J.caps is None:
            J.caps = np.full(len(J.ub), np.nan)         # read chunk by chunk
        caps = J.caps if cap is not None else None
        run = _Run(rings, job, J, beta, intervals, scale, exclude, similar, found, bound,
                   keys, 0.0 if memo is None else memo.floor, caps)
        later_idx: list[np.ndarray] = []
        later_tau: list[FloatArray] = []
        for chunk in _chunks(order, memo is not None):
            if exclude:                     # a distinct round: the budget may end it
                budget.check()
            else:                           # a deeper read of the ranked list may end
                budget.poll()
            if memo is not None:            # lazy: by arc length, boxes as they come
                if ub[chunk[0]] < bound.floor:
                    break
                _fill_boxes(rings, job, J, chunk, intervals, whole)
                chunk = chunk[_capped(box, caps, chunk, cap, job, cfg) >= bound.floor]
                if chunk.size == 0:
                    continue
            else:
                if box[chunk[0]] < bound.floor:
                    break                   # in the order of the boxes: none after
                chunk = chunk[_capped(box, caps, chunk, cap, job, cfg) >= bound.floor]
                if chunk.size == 0:
                    continue
            if deferred is not None and exclude:
                # a kept plan's copies: a plan only below their threshold, so they
                # wait for it (most never reach the floor)
                fresh = np.isnan(J.t[chunk])
                tau = exclude.thresholds(rings, job, J, chunk[fresh], intervals)
                later = np.zeros(chunk.size, bool)
                later[fresh] = tau * (1 + DEFER_PAD) < box[chunk[fresh]]
                if later.any():
                    li, lt = chunk[later], tau[later[fresh]]
                    lb = _lower(job, J, li, whole)
                    if lb is not None:
                        # surely copies at their largest square: read only as beaters
                        copy = lb * (1 - DEFER_PAD) >= lt * (1 + DEFER_PAD)
                        if copy.any():
                            deferred.setdefault(job, (J, []))[1].append(li[copy])
                            li, lt = li[~copy], lt[~copy]
                    later_idx.append(li)
                    later_tau.append(lt)
                    chunk = chunk[~later]
            run.settle(chunk)
        if later_idx:
            idx, tau = np.concatenate(later_idx), np.concatenate(later_tau)
            by = np.argsort(-tau, kind="stable")
            idx, tau = idx[by], tau[by]
            # the thresholds fall and the floor only rises: once one falls short of
            # the floor (or the memo's, below which no answer is taken), every one
            # after it does
            short = 0
            for s in range(0, idx.size, CHUNK):
                budget.check()              # a distinct round: the budget may end it
                e = min(s + CHUNK, idx.size)
                short = s + int(np.count_nonzero(tau[s:e] * (1 + DEFER_PAD)
                                                 >= max(bound.floor, run.least)))
                run.settle(idx[s:short])
                if short < e:
                    break
            if short < idx.size:
                assert deferred is not None
                deferred.setdefault(job, (J, []))[1].append(idx[short:])
    return found


def _capped(box: FloatArray, caps: FloatArray | None, chunk: np.ndarray, cap: Any,
            job: Any, cfg: _Configs) -> FloatArray:
    """The bounds of the configurations ``chunk``: their boxes, each no more than its cap
    (:func:`_solve_jobs`' ``cap``, read into ``caps`` for those not read yet)."""
    if caps is None:
        bounds: FloatArray = box[chunk]
        return bounds
    todo = chunk[np.isnan(caps[chunk])]
    if todo.size:
        caps[todo] = cap(job, cfg.take(todo))
    out: FloatArray = np.minimum(box[chunk], caps[chunk])
    return out


def _inside_any(c: _Configs, supers: np.ndarray, ma: int, mb: int, same: bool,
                compiled: bool = False) -> np.ndarray:
    """Which configurations ``c`` lie inside one of ``supers`` (rows ``iA, kA, iC,
    kC``; cyclically; on one ring either way round): for each super, only the
    configurations whose first start lies in its first stretch are read (sorted;
    ``compiled``: the same test by one sweep over the first starts,
    :func:`fcgrasp.model.stretches._kernels.inside_supers`)."""
    out = np.zeros(len(c.iA), bool)
    if compiled:
        sup = np.ascontiguousarray(supers, np.int64).reshape(-1, 4)
        # each super's entry at each first start its first stretch covers, with the room
        # it leaves for a configuration's interior vertices there (both ways round)
        rep = sup[:, 1] + 1
        es = np.repeat(np.arange(len(sup)), rep)
        d = np.arange(es.size) - np.repeat(np.cumsum(rep) - rep, rep)
        ep, eroom = (sup[es, 0] + d) % ma, sup[es, 1] - d
        entries = np.lexsort((-eroom, ep))
        ep, eroom, es = ep[entries], eroom[entries], es[entries]
    for flip in ((False, True) if same else (False,)):
        a, ka, cc, kc = (c.iC, c.kC, c.iA, c.kA) if flip else (c.iA, c.kA, c.iC, c.kC)
        a = a % ma
        if compiled:
            _kernels.inside_supers(
                *(np.ascontiguousarray(v, np.int64) for v in (a, ka, cc, kc, ep, eroom, es)),
                sup, int(ma), int(mb), out)
            continue
        by = np.argsort(a, kind="stable")
        sa = a[by]
        for iA, kA, iC, kC in supers:
            lo = iA % ma
            spans = ((lo, lo + kA + 1),) if lo + kA < ma else \
                ((lo, ma), (0, lo + kA + 1 - ma))
            for s0, s1 in spans:
                sel = by[np.searchsorted(sa, s0):np.searchsorted(sa, s1)]
                if sel.size:
                    out[sel] |= ((a[sel] - iA) % ma + ka[sel] <= kA) \
                        & ((cc[sel] - iC) % mb + kc[sel] <= kC)
    return out


def _solve_deferred(rings: list[_Ring], beta: float, intervals: dict[Any, _Intervals],
                    scale: float, found: list[_Found], floor: float,
                    deferred: dict[Any, tuple[_Job, list[np.ndarray]]],
                    similar: dict[Any, tuple[_Job, list[np.ndarray]]]) -> None:
    """Solve the deferred configurations (:func:`_solve_jobs`) that may beat a found
    configuration reaching ``floor`` in :func:`_own_optimum` (those inside it, either
    way round on one ring), and file the feasible ones in ``similar`` as beaters."""
    for job, (J, parts) in deferred.items():
        budget.check()
        supers = np.array([f.cfg for f in found if f.job == job and f.t >= floor],
                          dtype=np.int64).reshape(-1, 4)
        supers = supers[supers[:, [1, 3]].max(axis=1) > 0]
        if not len(supers):
            continue
        # the union of the parts, sorted (a mask: numpy's hashed unique takes 0.7 s on
        # the 800,000 configurations a curved outline defers)
        mask = np.zeros(len(J.t), bool)
        for part in parts:
            mask[part] = True
        idx = np.flatnonzero(mask)
        # a beater's smallest region exceeds the found one's (at least the floor) by
        # the tie tolerance, and its box bounds it
        idx = idx[np.isnan(J.t[idx]) & (J.box[idx] > floor * (1 + TIE))]
        todo = idx[_inside_any(J.cfg.take(idx), supers, rings[job[0]].m, rings[job[1]].m,
                               job[0] == job[1], J.compiled)]
        _solve_in(rings, job, J, todo, beta, intervals, scale)
        done = np.concatenate(parts)
        done = done[J.t[done] > 0]
        if done.size:
            similar.setdefault(job, (J, []))[1].append(done)


@contextmanager
def _address_space(max_bytes: int | None, base: int | None = None) -> Iterator[None]:
    """The block's new memory capped at ``max_bytes`` more than the process's address
    space now (Linux, ``RLIMIT_AS``; elsewhere nothing is capped): one job's collection
    of a smooth outline can ask for gigabytes at once, inside a compiled loop, before
    its count can be checked.  ``base``: the address space to count from (default now:
    the search's rounds count from where the first began, not from what the last
    kept).  An allocation past the cap ends the search
    (:class:`~fcgrasp.core.budget.BudgetExhausted`, ``"max_memory"``), and the limit in
    force before is put back.  (While the block runs, every thread of the process is
    under the cap.)"""
    held = budget.address_held() if base is None else base
    try:
        import resource

        before = resource.getrlimit(resource.RLIMIT_AS)
    except (ImportError, OSError, ValueError):
        before = None
    if max_bytes is None or before is None or held is None:
        yield
        return
    cap = held + max_bytes
    if before[0] != resource.RLIM_INFINITY:
        cap = min(cap, before[0])
    try:
        resource.setrlimit(resource.RLIMIT_AS, (cap, before[1]))
    except (ValueError, OSError):
        yield
        return
    try:
        yield
    except MemoryError:
        raise budget.BudgetExhausted("max_memory") from None
    finally:
        resource.setrlimit(resource.RLIMIT_AS, before)
