"""What the rounds of one distinct search share (part of :mod:`fcgrasp.model.stretches`):
each job's configurations collected and their solutions (:class:`_Job`), the memo of
the collections and their floors (:class:`_Memo`), and what one collection carries to
the next (:class:`_Carried`, filed by :class:`_Codes`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ...core._checks import FloatArray
from ._windows import _Configs


@dataclass
class _Job:
    """A job's configurations, their bounds (arc length ``ub``, the ends' boxes
    ``box``), the order they are solved in and the solutions found (NaN: not yet)."""

    cfg: _Configs
    ub: FloatArray
    box: FloatArray
    order: np.ndarray
    compiled: bool
    t: FloatArray
    s0: FloatArray
    u0: FloatArray
    #: the floor each unsolved configuration was proved below (0: none)
    below: FloatArray
    #: each configuration's cap (:func:`_solve_jobs`' ``cap``), NaN until read
    caps: FloatArray | None = None
    #: the kept plans' thresholds of each configuration (:meth:`_Exclusion.thresholds`,
    #: which the rounds of one collection share)
    taus: Any = None
    #: a lower bound of each configuration's ``t``: its largest square where its whole
    #: windows hold (:func:`~fcgrasp.model.stretches._whole.whole_lower`; 0: not shown,
    #: NaN: not read yet), None where the job has none
    lower: FloatArray | None = None


_KEY = np.dtype([("iA", np.int64), ("kA", np.int64), ("iC", np.int64), ("kC", np.int64)])


def _config_keys(cfg: _Configs) -> np.ndarray:
    """One sortable key per configuration (its four numbers, compared in order)."""
    keys = np.empty(len(cfg.iA), _KEY)
    keys["iA"], keys["kA"], keys["iC"], keys["kC"] = cfg.iA, cfg.kA, cfg.iC, cfg.kC
    return keys


class _Codes:
    """Configurations as one integer each, in the order of :func:`_config_keys` (mixed
    radix over the ranges of the four numbers met when made): sorted and looked up ten
    times faster than the records (a smooth 10,000-edge outline's collection of a
    million configurations: 1 s per lookup).  ``of`` gives None where the product of
    the ranges would not fit an int64 (the records are used)."""

    def __init__(self, lo: np.ndarray, span: np.ndarray) -> None:
        self.lo, self.span = lo, span

    @staticmethod
    def of(cfg: _Configs) -> _Codes | None:
        cols = np.stack([np.asarray(c, np.int64) for c in (cfg.iA, cfg.kA, cfg.iC, cfg.kC)])
        if not cols.shape[1]:
            return None
        lo, hi = cols.min(axis=1), cols.max(axis=1)
        span = hi - lo + 1
        if float(np.prod(span.astype(float))) >= 2.0 ** 62:
            return None
        return _Codes(lo, span)

    def codes(self, cfg: _Configs) -> tuple[np.ndarray, np.ndarray]:
        """Each configuration's code, and which are in the ranges (the others have no
        code: their code is -1)."""
        cols = [np.asarray(c, np.int64) for c in (cfg.iA, cfg.kA, cfg.iC, cfg.kC)]
        inside = np.ones(len(cols[0]), bool)
        code = np.zeros(len(cols[0]), np.int64)
        for c, lo, span in zip(cols, self.lo, self.span, strict=True):
            d = c - lo
            inside &= (d >= 0) & (d < span)
            code = code * span + np.where(inside, d, 0)
        return np.where(inside, code, -1), inside


@dataclass
class _Carried:
    """What a job's configurations gave, carried from one collection to the next of a
    :class:`_Memo` (those solved, proved below a floor or bounded by their boxes), by
    sorted configuration keys (:class:`_Codes` where they fit, else the records of
    :func:`_config_keys`, the reference)."""

    keys: np.ndarray
    t: FloatArray
    s0: FloatArray
    u0: FloatArray
    below: FloatArray
    box: FloatArray
    caps: FloatArray | None
    codes: _Codes | None = None

    @staticmethod
    def of(J: _Job) -> _Carried:
        read = ~np.isnan(J.t) | (J.below > 0) | ~np.isnan(J.box)
        if J.caps is not None:
            read |= ~np.isnan(J.caps)
        idx = np.flatnonzero(read)
        cfg = J.cfg.take(idx)
        codes = _Codes.of(cfg) if CODES else None
        keys = _config_keys(cfg) if codes is None else codes.codes(cfg)[0]
        by = np.argsort(keys, kind="stable")
        idx = idx[by]
        return _Carried(keys[by], J.t[idx], J.s0[idx], J.u0[idx], J.below[idx], J.box[idx],
                        None if J.caps is None else J.caps[idx], codes)

    def into(self, J: _Job) -> None:
        if not self.keys.size:
            return
        if self.codes is None:
            keys = _config_keys(J.cfg)
            inside = np.ones(len(keys), bool)
        else:
            keys, inside = self.codes.codes(J.cfg)
        at = np.minimum(np.searchsorted(self.keys, keys), self.keys.size - 1)
        hit = np.flatnonzero((self.keys[at] == keys) & inside)
        src = at[hit]
        J.t[hit], J.s0[hit], J.u0[hit] = self.t[src], self.s0[src], self.u0[src]
        J.below[hit], J.box[hit] = self.below[src], self.box[src]
        if self.caps is not None:
            if J.caps is None:
                J.caps = np.full(len(J.ub), np.nan)
            J.caps[hit] = self.caps[src]


#: Whether :class:`_Carried` files configurations by :class:`_Codes` (False: by the
#: records of :func:`_config_keys` alone, the reference; the same configurations carried).
CODES = True


#: Bytes a collected configuration takes at the peak, the unit of :attr:`_Memo.max_bytes`:
#: four int64 of the configuration, seven arrays of :class:`_Job`, and the collection's
#: concatenation and sorts (measured: a 1,000-edge smooth outline at mu 1.0 grows by
#: about 124 bytes per configuration collected).
CONFIG_BYTES = 128


class _Memo:
    """What the runs of one search share (the rounds of ``distinct=``, whose floors
    differ): every configuration whose arc length reaches ``floor`` collected once, and
    each one's solution once solved.  A run whose ``top``-th configuration falls below
    ``floor`` may have missed one: the caller lowers the floor (:meth:`lower`) and runs
    again (:meth:`StretchSearch.pairs`); at or above it nothing is missed (a
    configuration below the floor can neither reach the ``top`` nor beat one that does
    in :func:`_own_optimum`)."""

    def __init__(self, floor: float = 0.0, max_bytes: int | None = None) -> None:
        self.floor = floor
        self.prepared: list[tuple[Any, _Configs]] | None = None
        self.jobs: dict[Any, _Job] = {}
        #: the most bytes the configurations collected and their solutions may take
        #: (:data:`CONFIG_BYTES` each): a collection over it ends the search
        #: (:class:`~fcgrasp.core.budget.BudgetExhausted`, ``"max_memory"``;
        #: :func:`_candidates`)
        self.max_bytes = max_bytes
        #: the most configurations a collection may hold for speed (None: no limit;
        #: :data:`fcgrasp.model.stretches.COLLECT_CAP`): a collection over it ends the
        #: run (``BudgetExhausted``, ``"collection"``) and the caller tries a higher
        #: floor, or collects in full where none would do
        self.cap: int | None = None
        #: each job's solutions and boxes of the last collection, for the next
        #: (:meth:`lower`)
        self.carried: dict[Any, _Carried] = {}

    @property
    def max_configs(self) -> int | None:
        """The most configurations a collection may hold (``max_bytes``)."""
        return None if self.max_bytes is None else self.max_bytes // CONFIG_BYTES

    def lower(self, floor: float) -> None:
        """Collect again, down to ``floor``: what the configurations solved or bounded so
        far gave is carried into the new collection (:meth:`restore`), each solved
        once whatever the floors it is collected at."""
        if self.jobs and CARRY:
            self.carried = {job: _Carried.of(J) for job, J in self.jobs.items()}
        self.floor, self.prepared, self.jobs = floor, None, {}

    def restore(self, job: Any, J: _Job) -> None:
        """Fill a new collection's job ``J`` with what an earlier collection of the same
        job solved and bounded (the same numbers: each configuration's solution and
        boxes depend on it alone)."""
        carried = self.carried.get(job)
        if carried is not None:
            carried.into(J)


#: Whether a memo's new collection takes what the last one solved (1; 0: every
#: collection solves its configurations anew, the reference).
CARRY = 1
