"""Two soft fingers' distinct alternatives with each plan's second level grown only
where the rule needs it (part of :mod:`fcgrasp.spatial.alternatives`).

The second level (definition 7.1, :func:`fcgrasp.spatial.regions._second_level`) moves
a plan's centres inside its pieces and leaves its measure and normals; the rule of
the same alternative (:func:`~fcgrasp.spatial.alternatives.same_solid_alternative`)
reads the centres.  A distinct search reads a ranked list several times as long as
the plans it keeps (on a tessellated curve most are a kept plan's copies on the next
facets), and growing each took half of its time.  Here a plan at its first level is
compared with each plan kept by the bounds of where its grown centres can be: the
farthest and the nearest point of each of its pieces from a kept plan's centre.  It is
grown only when it is kept, or when those bounds do not decide; after the ``top``-th
plan kept, only which of the first ``top`` a plan joins is read.  The groups, their
leaders (grown) and ``similar`` are those of every plan grown and then suppressed
(``tests/test_spatial_distinct.py``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np

from ..core.budget import PlanList
from ..core.tolerances import SIMILAR_PAD
from .alternatives import paired, same_sides, same_solid_alternative
from .solid import Solid

#: A piece holding a grown centre: its 3-D vertices (m, 3), its facet's origin, normal
#: and in-plane axes (2, 3), and its half-planes ``E x <= h`` in the facet's frame.
Piece = tuple[Any, Any, Any, Any, Any, Any]


def grown(solid: Solid, plan: Any, memo: dict[Any, Any]) -> Any:
    """``plan`` (a :class:`~fcgrasp.spatial.SoftPairPlan` of
    :func:`~fcgrasp.spatial.regions.facet_pair_plans` at its first level) with its
    second level grown, as that search grows it (the same memo entry)."""
    from .regions import _once, _plan

    key = ("grown", plan.mu, plan.margin, True, plan.facets, plan.pieces)
    return _once(memo, key, _plan, solid, (plan.facets[0], plan.facets[1]),
                 (plan.pieces[0], plan.pieces[1]), plan.centers[0], plan.centers[1],
                 plan.radius, plan.mu, plan.margin, True)


def pieces_of(solid: Solid, plan: Any, memo: dict[Any, Any]) -> list[Piece]:
    """The pieces (:data:`Piece`) that hold ``plan``'s centres, one per finger, read from
    the pieces' table the search made (the same memo entry)."""
    from ._pieces import _piece_table
    from .regions import _once

    table = _once(memo, "table", _piece_table, solid)
    out = []
    for f, k in zip(plan.facets, plan.pieces, strict=True):
        p = int(table.start[f]) + k
        E, h = table.halfplanes[p]
        out.append((table.vertices[p], table.origin[p], table.normal[p], table.axes[p], E, h))
    return out


def _decided(kept: Any, plan: Any, pieces: list[Piece] | None, fraction: float
             ) -> bool | None:
    """Whether ``plan`` (its centres anywhere in ``pieces``) is the same alternative as
    ``kept`` (:func:`~fcgrasp.spatial.alternatives.same_solid_alternative`), or None
    where the bounds of its centres do not decide (or no ``pieces`` are given)."""
    if pieces is None:
        return None
    k = len(kept.centers)
    if k != len(plan.centers):
        return False
    reach = (kept.radius + plan.radius) / fraction
    side = same_sides(kept, plan)                                    # (kept, plan)
    far, near = np.zeros((k, k)), np.zeros((k, k))
    for j, (V, o, n, A, E, h) in enumerate(pieces):
        for i, c in enumerate(np.asarray(kept.centers, float)):
            far[i, j] = float(np.max(np.linalg.norm(V - c, axis=1)))
            rel = c - o
            out = max(0.0, float(np.max(E @ (A @ rel) - h)))
            near[i, j] = math.hypot(float(rel @ n), out)
    if paired(side & (far < reach * (1 - SIMILAR_PAD))):
        return True
    if not paired(side & (near < reach * (1 + SIMILAR_PAD))):
        return False
    return None


def distinct_grown(plans: list[Any], fraction: float, top: int | None,
                   grow: Callable[[Any], Any],
                   where: Callable[[Any], list[Piece] | None]) -> list[Any]:
    """The first ``top`` (None: every) plans that
    :func:`~fcgrasp.spatial.alternatives.distinct_solid_plans` keeps of the ranked
    ``plans`` each grown by ``grow``, each with ``similar``: ``where(p)`` the pieces that
    hold ``p``'s grown centres (None where ``p``'s centres are final), a plan grown only
    where it is kept or the bounds do not decide (module docstring)."""
    groups: list[tuple[Any, list[Any]]] = []
    for p in plans:
        pieces = where(p)
        mine = p if pieces is None else None          # the grown plan, once made
        for leader, members in groups:
            verdict = _decided(leader, p, pieces, fraction) if mine is None else None
            if verdict is None:
                mine = grow(p) if mine is None else mine
                verdict = same_solid_alternative(leader, mine, fraction)
            if verdict:
                members.append(p)
                break
        else:
            if top is None or len(groups) < top:
                groups.append((mine if mine is not None else grow(p), []))
    return [replace(g, similar=tuple(tuple(q.facets) for q in m)) for g, m in groups]


def soft_pair_distinct(solid: Solid, mu: float, margin: float, top: int | None,
                       fraction: float) -> PlanList:
    """Two soft fingers' ``top`` distinct plans on ``solid``
    (:func:`~fcgrasp.spatial.alternatives.top_distinct` of
    :func:`~fcgrasp.spatial.soft_pair_plans`, the rounds sharing each pair's work), the
    plans on pairs of facets grown only where the rule needs it (module docstring)."""
    from .alternatives import top_distinct
    from .regions import SoftPairPlan
    from .surfaces import SurfacePairPlan, soft_pair_plans

    memo: dict[Any, Any] = {}
    if fraction == 0:                   # every plan kept: each grown by the search
        return top_distinct(lambda n: soft_pair_plans(solid, mu, top=n, margin=margin,
                                                      memo=memo), top, fraction)

    def on_facets(p: Any) -> bool:
        return isinstance(p, SoftPairPlan) and not isinstance(p, SurfacePairPlan)

    def suppress(plans: Any) -> list[Any]:
        return distinct_grown(
            list(plans), fraction, top,
            lambda p: grown(solid, p, memo) if on_facets(p) else p,
            lambda p: pieces_of(solid, p, memo) if on_facets(p) else None)

    return top_distinct(lambda n: soft_pair_plans(solid, mu, top=n, margin=margin,
                                                  memo=memo, grow_facets=False),
                        top, fraction, suppress)
