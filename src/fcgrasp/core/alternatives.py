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
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TypeVar

__all__ = ["keep_distinct"]

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
