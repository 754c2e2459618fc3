"""Time and memory budgets of a search: a deadline the search reads where it can stop
with an honest partial answer.

A planner that runs under :func:`deadline` checks it (:func:`check`) between units of
work whose results it can keep: a round of the distinct search, a chunk of
configurations.  When the deadline has passed, :class:`BudgetExhausted` unwinds to the
level that knows what its finished rounds prove, which returns them with a bound on
what a complete search could still find (:class:`fcgrasp.model.plans.PlanList`), as a
MIP solver returns its incumbent with its gap.

A deadline may carry a memory budget too (``max_memory``: bytes of address space the
process may take on past what it held when the deadline began): each check reads the
process's address space (:func:`address_held`), and a search past its budget stops at
that check as it would at the end of its time (:func:`stop_reason` says which ended).
The searches of solids take their memory budget this way; the planar stretch search
caps its collections' address space itself (``fcgrasp.model.stretches``), since one
compiled collection can ask for gigabytes between two checks.

The deadline is a context variable: a plan made in a thread (the explorer, a batch)
has its own, and nested deadlines keep the earlier one.

>>> with deadline(None):
...     check()                     # no budget: never stops
>>> with deadline(0.0):
...     exhausted()
True
>>> with deadline(None, checks=1):
...     exhausted(), exhausted()
(False, True)
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Any

from ..errors import FcgraspError

__all__ = ["DEFAULT_TIME_LIMIT", "BudgetExhausted", "deadline", "check", "exhausted",
           "remaining", "interruptible", "poll", "cut_if_over", "cut_short", "settle",
           "check_time_limit", "PlanList", "incomplete", "STOPPED_BY", "stopped_words",
           "stop_reason", "address_held"]

#: The time budget of :func:`fcgrasp.plan` and ``fcgrasp plan --time-limit`` in seconds
#: of wall-clock time, for interactive use: the search's first answer is complete
#: (within :data:`FIRST_ANSWER_GRACE` past it), and the rounds that look for further
#: distinct alternatives stop at it.
DEFAULT_TIME_LIMIT = 10.0

def address_held() -> int | None:
    """The process's address space in bytes (Linux), None where it cannot be read."""
    try:
        import resource

        with open("/proc/self/statm") as fh:
            return int(fh.read().split()[0]) * resource.getpagesize()
    except (ImportError, OSError, ValueError):
        return None


class _Budget:
    """One :func:`deadline`: when it ends (monotonic seconds, None: never), how many
    more checks it allows (None: any), the address space past which it ends
    (``limit``: the process's when it began plus its memory budget; None: any), the
    deadline around it, why a search under it returned less than a complete search
    would (:func:`cut_short`; None: none did) and whether its memory ran out
    (``spent``)."""

    __slots__ = ("at", "checks", "limit", "outer", "cut", "spent")

    def __init__(self, at: float | None, checks: int | None, outer: _Budget | None,
                 memory: int | None = None) -> None:
        self.at, self.checks, self.outer = at, checks, outer
        base = None if memory is None else address_held()
        self.limit = None if memory is None or base is None else base + memory
        self.cut: str | None = None
        self.spent = False

    def ended(self, count: bool) -> bool:
        """Whether this budget or one around it has ended (``count``: a check spends one
        of each one's checks)."""
        b: _Budget | None = self
        over = False
        now = None
        while b is not None:
            if b.at is not None:
                now = time.monotonic() if now is None else now
                over = over or now >= b.at
            if b.checks is not None:
                over = over or b.checks <= 0
                if count and b.checks > 0:
                    b.checks -= 1
            if b.limit is not None and not b.spent:
                held = address_held()
                b.spent = held is not None and held > b.limit
            over = over or b.spent
            b = b.outer
        return over


_CURRENT: ContextVar[_Budget | None] = ContextVar("fcgrasp_budget", default=None)


#: Why a search stopped early, as a report's ``gap`` says it (``stopped_by``): the
#: words, and the option that raises the budget.
STOPPED_BY = {"time_limit": ("its time limit", "--time-limit"),
              "max_memory": ("its memory budget", "--max-memory"),
              "depth": ("the most plans a distinct search reads", None)}


def stopped_words(stopped: str | None, raises: bool = False) -> str:
    """Why a search stopped (:data:`STOPPED_BY`), with its option: ``"its time limit
    (--time-limit)"``, or with ``raises`` ``"its time limit (--time-limit raises it)"``.

    >>> stopped_words("max_memory", raises=True)
    'its memory budget (--max-memory raises it)'
    """
    words, option = STOPPED_BY.get(stopped or "", ("its budget", None))
    if option is None:
        return words
    return f"{words} ({option}{' raises it' if raises else ''})"


class BudgetExhausted(FcgraspError):
    """The search's budget ended: raised by :func:`check`, caught by the search that
    keeps what its finished rounds prove (never seen by a user).  Its message says
    which budget (``"time_limit"`` or ``"max_memory"``; empty: the time limit)."""


def check_time_limit(value: object, name: str = "time_limit") -> float | None:
    """A time limit in seconds: a positive number, or None (no limit).

    >>> check_time_limit(2), check_time_limit(None)
    (2.0, None)
    """
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise TypeError(f"{name} must be a number of seconds or None, got {value!r}")
    v = float(value)
    if not v > 0 or math.isnan(v):
        raise ValueError(f"{name} must be a positive number of seconds, got {value!r}")
    return v


@contextmanager
def deadline(seconds: float | None, checks: int | None = None,
             max_memory: int | None = None) -> Iterator[_Budget]:
    """Run the block under a budget of ``seconds`` of wall-clock time from now (None: no
    time limit of its own), of ``checks`` budget checks (None: any; a count makes a
    partial answer reproducible, whatever the machine's speed, as the tests need) and
    of ``max_memory`` bytes of address space past the process's now (None: any; read at
    each check, so a search may pass it by what it allocates between two checks; where
    the address space cannot be read, no memory budget).  An enclosing deadline still
    holds: the first to end ends both.  The budget is given to the block: its ``cut``
    says whether a search under it was cut short (:func:`cut_short`).

    >>> import numpy as np
    >>> with deadline(None, max_memory=2 ** 20):
    ...     block = np.ones(2 ** 23)              # 64 MB
    ...     exhausted(), stop_reason()
    (True, 'max_memory')
    """
    at = None if seconds is None else time.monotonic() + seconds
    budget = _Budget(at, checks, _CURRENT.get(), max_memory)
    token = _CURRENT.set(budget)
    try:
        yield budget
    finally:
        _CURRENT.reset(token)


_INTERRUPTIBLE: ContextVar[bool] = ContextVar("fcgrasp_interruptible", default=False)


@contextmanager
def interruptible() -> Iterator[None]:
    """Inside the block, :func:`poll` checks the budget: a search whose caller keeps
    an answer without it (a deeper read of a ranked list) may be ended there."""
    token = _INTERRUPTIBLE.set(True)
    try:
        yield
    finally:
        _INTERRUPTIBLE.reset(token)


def poll() -> None:
    """:func:`check` inside :func:`interruptible`; nothing elsewhere (a search that
    must finish, such as the first answer, is not ended)."""
    if _INTERRUPTIBLE.get():
        check()


def cut_if_over(counted: bool = True) -> bool:
    """Whether the current budget has ended (a budget check, :func:`exhausted`; with
    ``counted`` False its clock only, :func:`remaining`, which a reproducible budget of
    checks does not end); when it has, the search is recorded as cut short
    (:func:`cut_short`)."""
    over = exhausted() if counted else remaining() <= 0
    if over:
        cut_short()
    return over


def cut_short(reason: str | None = None) -> None:
    """Record that a search stopped at its budget and returned what it had: plans that
    hold, each proved, but fewer, or found by less of the search, than a complete
    search would give (a heuristic's growth stopped, the jaw's boxes sought no
    further).  ``reason``: the budget that ended (default :func:`stop_reason`'s).
    Recorded on the current deadline and those around it; the planner then says the
    answer is incomplete (:func:`fcgrasp.plan`)."""
    reason = stop_reason() if reason is None else reason
    b = _CURRENT.get()
    while b is not None:
        if b.cut is None:
            b.cut = reason
        b = b.outer


def remaining() -> float:
    """Seconds left of the current time budget (infinity without one)."""
    b, left = _CURRENT.get(), math.inf
    now = time.monotonic()
    while b is not None:
        if b.at is not None:
            left = min(left, b.at - now)
        b = b.outer
    return left


def exhausted() -> bool:
    """Whether the current budget has ended (a budget check: it spends one check)."""
    b = _CURRENT.get()
    return b is not None and b.ended(count=True)


def stop_reason() -> str:
    """Which budget a search that found its deadline ended stops at: ``"max_memory"``
    where the current deadline or one around it has passed its memory budget, else
    ``"time_limit"`` (its time, or its count of checks)."""
    b = _CURRENT.get()
    while b is not None:
        if b.spent:
            return "max_memory"
        b = b.outer
    return "time_limit"


def check() -> None:
    """Raise :class:`BudgetExhausted` once the current budget has ended (a budget
    check), naming the budget (:func:`stop_reason`)."""
    if exhausted():
        raise BudgetExhausted(stop_reason())


#: Seconds past its budget a first answer may take (:func:`check_clock`): a search
#: that always finishes its first round does, unless that round alone takes longer.
FIRST_ANSWER_GRACE = 1.0


def check_clock() -> None:
    """Raise :class:`BudgetExhausted` once the current budget's clock has run out by
    :data:`FIRST_ANSWER_GRACE`, even in a search that otherwise always finishes (the
    first answer: its caller then gives a quicker one, cut short); a budget of checks
    is not spent."""
    if remaining() < -FIRST_ANSWER_GRACE:
        raise BudgetExhausted("time_limit")


class PlanList(list):  # type: ignore[type-arg]
    """Plans, best first, with what the search proved about the plans it did not return.

    ``complete`` True: these are the exact answer (every plan asked for that exists).
    False: the search stopped early (``stopped``: ``"time_limit"`` or
    ``"max_memory"``, the budgets of :func:`fcgrasp.core.budget.deadline`; ``"depth"``,
    the most plans a distinct search reads), and the plans are still an exact prefix
    of the complete answer, in order; ``bound`` is then a length no plan the complete
    search would add after them exceeds: every further alternative's smallest region
    is at most ``bound`` (None where the search proved none), the gap of an anytime
    search as a MIP solver reports its own.  ``exact`` False: a search was cut short
    inside (:func:`cut_short`), or gave plans read below its last level: every plan
    holds, but a complete search may rank others before them or find them larger
    (``bound``, where given, then bounds every plan of the complete answer that is not
    among them).

    >>> plans = PlanList([], complete=False, bound=2.5, stopped="time_limit")
    >>> plans.complete, plans.gap()["bound"]
    (False, 2.5)
    """

    def __init__(self, plans: Any = (), complete: bool = True, bound: float | None = None,
                 stopped: str | None = None, measure: str = "smallest region",
                 exact: bool = True) -> None:
        super().__init__(plans)
        self.complete = bool(complete)
        #: the plans are an exact prefix of the complete answer (False: :func:`cut_short`)
        self.exact = bool(exact) or self.complete
        self.bound = None if bound is None else float(bound)
        self.stopped = stopped
        #: what ``bound`` bounds: the plans' ranking measure
        self.measure = measure
        #: what a search says of itself for the report's parameters (a solid's three
        #: fingers: the triples certified and whether the search was exhaustive)
        self.details: dict[str, Any] = {}

    def gap(self) -> dict[str, Any] | None:
        """What the JSON report says of an incomplete search (None when complete):
        why it stopped, the plans it proved and the bound on the rest."""
        if self.complete:
            return None
        return {"stopped_by": self.stopped, "found": len(self), "bound": self.bound,
                "measure": self.measure, "exact": self.exact}

    def same_answer(self, plans: Any) -> PlanList:
        """Other plans with this list's completeness and bound."""
        return PlanList(plans, self.complete, self.bound, self.stopped, self.measure,
                        self.exact)


def incomplete(plans: Any, stopped: str, bound: float | None,
               measure: str = "smallest region", exact: bool = True) -> PlanList:
    """The plans of a search that stopped early (``stopped``), every further plan's
    ``measure`` at most ``bound`` (``exact`` False: not an exact prefix; ``bound``
    then bounds every plan of the complete answer that is not among them, None where
    the search proved none)."""
    return PlanList(plans, complete=False, bound=bound, stopped=stopped, measure=measure,
                    exact=exact)


def settle(plans: Any, budget: _Budget) -> Any:
    """``plans`` (a :class:`PlanList`, or plans) as the answer of a search run under
    ``budget``: incomplete, not exact, where a search inside was cut short
    (:func:`cut_short`)."""
    if budget.cut is None:
        return plans
    got = plans if isinstance(plans, PlanList) else PlanList(plans)
    return incomplete(got, got.stopped or budget.cut, None, got.measure, exact=False)
