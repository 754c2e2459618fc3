"""Distinct alternatives among ranked plans of any kind: suppression in rank order.

A ranked list of plans often holds one grasp many times (its regions shifted along a
curve, the next facet of a tessellated surface, the next slice of a jaw's poses).
:func:`keep_distinct` keeps, in rank order, each plan that is not *the same
alternative* as a plan kept before, and files it under the first such plan; what "the
same alternative" means is the plan kind's own (regions of contact that overlap by more
than a fraction, :func:`fcgrasp.model.distinct.same_alternative`; jaw boxes up to the
part's symmetries, :func:`fcgrasp.model.distinct.same_box`; regions on a solid grown
until they meet, :func:`fcgrasp.spatial.alternatives.same_solid_alternative`).  The
point fingers' :class:`fcgrasp.model.distinct.Suppression` gives the same groups as this
rule with its own bounds (tested against it).

Suppression keeps ``top`` distinct plans only if the ranked list it reads is long
enough; :func:`distinct_rounds` asks a ranked search for ever longer lists until it is
(every gripper's distinct search that does not leave out copies inside its own search:
planar parts through :func:`fcgrasp.planning.plan`, solids through
:func:`fcgrasp.spatial.alternatives.top_distinct`).  Suppression is prefix-stable (the
plans kept from the first ``n`` of a ranked list are the first of those kept from any
longer one), so however the lists grow, the plans kept are those of suppression along
the whole ranked list.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import TypeVar

from .budget import BudgetExhausted, exhausted, stop_reason

__all__ = ["keep_distinct", "Rounds", "distinct_rounds"]

P = TypeVar("P")


def keep_distinct(plans: Iterable[P], same: Callable[[P, P], bool],
                  chain: bool = False) -> list[list[P]]:
    """The ranked ``plans`` in groups, each led by the plan kept: a plan joins the first
    group whose leader it is the same alternative as (``same(kept, plan)``), or, with
    ``chain``, whose any member it is (a band of adjacent slices is one alternative);
    else it leads a new group.

    >>> keep_distinct([10, 9, 5, 4, 1], lambda a, b: abs(a - b) <= 1)
    [[10, 9], [5, 4], [1]]
    >>> keep_distinct([10, 9, 8, 7], lambda a, b: abs(a - b) <= 1, chain=True)
    [[10, 9, 8, 7]]
    """
    groups: list[list[P]] = []
    for p in plans:
        group = next((g for g in groups if any(same(q, p) for q in (g if chain else g[:1]))),
                     None)
        if group is None:
            groups.append([p])
        else:
            group.append(p)
    return groups


@dataclass(frozen=True)
class Rounds:
    """How :func:`distinct_rounds` asks a ranked search for longer lists.

    ``first``: the first request, this many times ``top``; ``factor``: each request at
    least this many times the one before; ``share``: and, where the share of distinct
    plans in the last list read says ``top`` need more, that many twice over (a search's
    time grows slowly with its ``top``: on a curved outline, where one grasp fills the
    ranked list with its copies, one long request costs less than many short ones);
    ``depth``: at most this many times ``top`` plans read (None: no limit), the whole
    depth asked at once where a request would pass half of it.
    """

    first: int = 1
    factor: int = 2
    share: bool = True
    depth: int | None = None

    def __post_init__(self) -> None:
        for name in ("first", "factor"):
            value = getattr(self, name)
            if not isinstance(value, int) or value < (1 if name == "first" else 2):
                raise ValueError(f"{name} must be an integer >= "
                                 f"{1 if name == 'first' else 2}, got {value!r}")
        if self.depth is not None and (not isinstance(self.depth, int) or self.depth < 1):
            raise ValueError(f"depth must be an integer >= 1 or None, got {self.depth!r}")

    def after(self, ask: int, kept: int, top: int) -> int:
        """The request after one of ``ask`` plans that kept ``kept`` (< ``top``).

        >>> Rounds().after(10, 2, 10), Rounds(depth=16).after(10, 2, 10)
        (100, 160)
        >>> Rounds(first=4, factor=4, share=False).after(40, 1, 10)
        160
        """
        need = self.factor * ask
        if self.share:                          # 2 ask top / kept, rounded up
            need = max(need, -(-2 * ask * top // max(kept, 1)))
        cap = None if self.depth is None else self.depth * top
        return cap if cap is not None and 2 * need >= cap else need


def distinct_rounds(search: Callable[[int | None], Sequence[P]],
                    suppress: Callable[[Sequence[P]], list[P]], top: int | None,
                    rounds: Rounds = Rounds()) -> tuple[list[P], Sequence[P], str | None]:
    """The first ``top`` plans that ``suppress`` keeps along the ranked list of
    ``search(n)`` (the best ``n`` plans; None: every plan), the list read last and why
    the rounds stopped short: None (complete: ``top`` kept, or the search has no
    more), ``"depth"`` (:attr:`Rounds.depth` times ``top`` read), ``"time_limit"`` or
    ``"max_memory"`` (a budget of :func:`fcgrasp.core.budget.deadline` ended between
    two requests, or a request after the first ran out of it) or ``"search"`` (the
    list read last is an incomplete :class:`~fcgrasp.core.budget.PlanList`: the search
    stopped itself).
    Whatever the reason, the plans kept are the complete answer's first.

    >>> ranked = [10, 9, 9, 8, 5, 4, 4, 1]
    >>> same = lambda ps: [g[0] for g in keep_distinct(ps, lambda a, b: a - b <= 2)]
    >>> distinct_rounds(lambda n: ranked[:n], same, 3)[::2]
    ([10, 5, 1], None)
    >>> distinct_rounds(lambda n: ranked[:n], same, 3, Rounds(depth=1))[::2]
    ([10], 'depth')
    """
    if top is None:
        plans = search(None)
        return suppress(plans), plans, None if getattr(plans, "complete", True) else "search"
    ask = rounds.first * top
    plans = search(ask)
    kept = suppress(plans)
    while len(kept) < top:
        if not getattr(plans, "complete", True):
            return kept, plans, "search"
        if len(plans) < ask:                    # the search has no more
            break
        if rounds.depth is not None and ask >= rounds.depth * top:
            return kept, plans, "depth"
        if exhausted():
            return kept, plans, stop_reason()
        ask = rounds.after(ask, len(kept), top)
        try:
            more = search(ask)
        except BudgetExhausted as exc:
            return kept, plans, str(exc) or "time_limit"
        plans, kept = more, suppress(more)
    return kept[:top], plans, None
