r"""Regions that run along the boundary: two fingers with friction.

A *stretch* is a connected piece of one boundary ring, from a point on one edge to a
point on another, covering the edges and vertices between them.  Two stretches
``R1, R2`` are independent regions of contact (definition 7.1) when every grasp with
one finger anywhere in ``R1`` and the other anywhere in ``R2`` is force closure, with
the contact normal of the edge strictly inside an edge and, at a vertex strictly
inside a stretch, **every** normal between the two edges' normals (a fingertip on a
corner).  A stretch's end point takes the normal of the edge the stretch covers there.

**The condition (theorem 6.3 with a margin).**  Write ``beta = atan(mu) - margin`` and
``W(f)`` for the cone of directions within ``beta`` of the force direction ``f``
(the inward normal).  Two contacts ``X`` (force ``f``) and ``Y`` (force ``g``) hold
the part, squeezing, iff ``Y - X`` lies in ``W(f)`` and ``X - Y`` in ``W(g)``
(expanding: the opposite signs).  ``W(f)`` is the intersection of two half-planes
whose edges turn with ``f``; *for a fixed chord the set of force directions that
contain it is an arc of width 2 beta*, convex in the normal's angle, so a fan of
normals at a vertex holds iff its two extreme normals (the two edges') hold.  Hence
the stretches hold iff every pair of *points* ``(X, Y)`` taken among the end points
and interior vertices of ``R1`` and ``R2`` holds with every normal those points carry
(end: one; interior vertex: both), because on every pair of edge pieces the chord
``Y - X`` is affine in the two positions and the cones are convex: the pair of pieces
holds iff its four corners do.

**The optimum.**  The smallest region as long as possible (definition 7.1).  A
*configuration* fixes which edges the two stretches cover (its interior vertices and
end edges); for a configuration the condition is linear in the two start positions
and the common length ``t`` of a square pair of regions (a longer region can be cut
to the shorter's length, so the largest smallest region is reached by a square pair):

* the end points against the other stretch's interior vertices bound each end to an
  interval of its edge (a running max/min over the window of vertices);
* the four corner pairs (end against end) give 16 half-planes in ``(s0, u0, t)``.

The largest ``t`` of a configuration is found by bisection on ``t`` with an exact
feasibility test of the remaining two-variable system (Fourier-Motzkin elimination of
``s0``), to machine precision.  Configurations are enumerated exhaustively behind a
bound: every interior vertex pair must hold with both fans (the boolean matrix
``M``), so the interior windows are runs of the intersection of rows of ``M`` (each
row held as its sorted runs of columns, so widening a window costs the runs it still
has, not a row of ``M``; the intervals of the ends are computed only for the cells
the search reads); a configuration is never longer than the arc length it can reach
(``_stretch_bound``); the vertex-aligned stretches of every window are feasible and
give the lower bound that prunes the others.  The search is exact: every
configuration that could beat the best found is solved.

The tests compare the optimum with an independent fine raster of the two contact
parameters (the largest square of force-closure samples, sharing no code with this
module) and sample every returned pair of regions with the general test.
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np

from ...core import budget
from ...core._angles import shrunk_half_angle
from ...core._checks import FloatArray, check_int, check_mu_scalar, check_scalar
from ...core.tolerances import ROUND_TOL, TOL
from ..polygon import Polygon, check_polygon
from ..regions import DEFAULT_MARGIN_DEG
from ._exclusion import THIRD_PAD, _Exclusion, _positions
from ._free_third import FreeThird
from ._memo import _Memo
from ._placement import StretchPair, _finish, _pairs
from ._rounds import _configs_in, _search, _vertex_runs
from ._solve import _address_space, _jobs, _Keys, _solve_jobs
from ._windows import TIE, _Bound, _Intervals, _load_for_depth, _rings, _turns
from ._windows import stretch_kernels_for as stretch_kernels_for

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = ["StretchPair", "StretchSearch", "two_finger_stretches", "stretch_regions",
           "crosses_a_vertex"]


def _check_args(polygon: Polygon, mu: ArrayLike, margin: ArrayLike) -> float:
    """The half-angle ``beta = atan(mu) - margin`` of the shrunk friction cones."""
    polygon = check_polygon(polygon)
    mu_v = check_mu_scalar(mu, "mu")
    margin_v = check_scalar(margin, "margin", nonnegative=True)
    return float(shrunk_half_angle(mu_v, margin_v))


def crosses_a_vertex(polygon: Polygon, mu: ArrayLike,
                     margin: ArrayLike = DEFAULT_MARGIN_DEG) -> bool:
    """Whether a region of two fingers with friction can cover some vertex.

    A vertex inside a region pushes along both its edges' normals, and for any chord to
    the other finger both must hold it: each within ``beta = atan(mu) - margin`` of the
    chord (the arc of the module docstring), so the two normals are less than
    ``2 beta`` apart.  Where every vertex turns by at least that much (every corner of
    a CAD polygon at ordinary friction), no region covers a vertex and the regions along
    the boundary are the single-edge regions of algorithm 7.1.

    >>> sq = Polygon([[0, 0], [10, 0], [10, 3], [0, 3]])
    >>> crosses_a_vertex(sq, mu=0.3)
    False
    >>> import numpy as np
    >>> a = np.linspace(0, 2 * np.pi, 360, endpoint=False)
    >>> crosses_a_vertex(Polygon(np.c_[np.cos(a), np.sin(a)]), mu=0.3)
    True
    """
    beta = _check_args(polygon, mu, margin)
    if beta <= 0:
        return False
    for ring in _rings(polygon):
        # a relative 1e-9 on the angle: a vertex at the limit is left to the exact search
        if np.any(_turns(ring) < 2 * beta * (1 + TOL) + ROUND_TOL):
            return True
    return False


def two_finger_stretches(polygon: Polygon, mu: ArrayLike, margin: ArrayLike = DEFAULT_MARGIN_DEG,
                         top: Any = 5, ties: bool = False, exclude: Any = (),
                         fraction: float = 0.5, seen: Any = ()) -> list[StretchPair]:
    """Optimal independent regions along the boundary for two fingers with friction.

    Regions are stretches of the rings (see the module docstring).  The pairs are
    ordered by definition 7.1's leximin order: the smallest region first, then the
    other (the second level: one region at the optimal smallest length, the other as
    long as the same covered edges allow).  Exact up to about 1e-12 of the part's size.

    Parameters
    ----------
    polygon : Polygon
    mu : float
        Friction coefficient of both fingers.
    margin : float
        Safety margin in degrees inside the friction cones.
    top : int or None
        How many pairs of regions to return (distinct configurations: which edges each
        region covers); None: every configuration that holds (small parts only: their
        number grows with the cube of the edges of a curved outline).
    ties : bool
        Also return every configuration whose smallest region ties the ``top``-th's
        (to a relative 1e-9), so that a later order (leximin, then geometry) is exact.
    exclude : sequence of plans
        Plans already kept (objects with ``regions`` and ``region_edges``, two
        regions each): the pairs returned are the best of those that are not surely
        the same alternative as one of them (their regions, wherever placed in their
        stretches, overlapping by more than ``fraction`` of the shorter,
        :func:`fcgrasp.model.distinct.same_alternative`); used by ``distinct=``.
    fraction : float
        The overlap of ``exclude``.
    seen : sequence of plans
        Plans already read (objects with ``region_edges`` and ``mode``): their
        configurations are not returned again.

    Returns
    -------
    list of StretchPair

    Examples
    --------
    >>> import numpy as np
    >>> a = np.linspace(0, 2 * np.pi, 360, endpoint=False)
    >>> disc = Polygon(np.c_[50 * np.cos(a), 50 * np.sin(a)])
    >>> best = two_finger_stretches(disc, mu=0.3, margin=0.5, top=1)[0]
    >>> round(best.min_length, 1), len(best.region_edges[0]) > 20
    (27.9, True)
    """
    return StretchSearch(polygon, mu, margin).pairs(top, ties, exclude, fraction, seen)


class StretchSearch:
    """:func:`two_finger_stretches` of one part, ``mu`` and ``margin``, asked several
    times (the rounds of ``distinct=``, :func:`fcgrasp.grippers._boundary.distinct_boundary_plans`):
    the rings' vertex matrices once, and for the runs that exclude plans every
    configuration collected once and each solved once.  ``max_bytes``: the memory
    budget of those runs' collections; ``share``: the share of the best smallest
    region down to which they first collect (default :data:`MEMO_SHARE`; three
    fingers' ranked pair plans, near the top, read from 0.9).

    >>> sq = Polygon([[0, 0], [10, 0], [10, 3], [0, 3]])
    >>> [p.region_edges for p in StretchSearch(sq, 0.3).pairs(top=1)]
    [((1,), (3,))]
    """

    def __init__(self, polygon: Polygon, mu: ArrayLike, margin: ArrayLike = DEFAULT_MARGIN_DEG,
                 max_bytes: int | None = None, share: float | None = None) -> None:
        self.beta = _check_args(polygon, mu, margin)
        #: the share of the best smallest region from which the runs that share a memo
        #: first collect (None: :data:`MEMO_SHARE`; lowered as the answers need)
        self.share = MEMO_SHARE if share is None else check_scalar(share, "share",
                                                                     positive=True)
        if self.share > 1:
            raise ValueError(f"share must be in (0, 1], got {share!r}")
        self.max_bytes = None if max_bytes is None else check_int(max_bytes, "max_bytes",
                                                                  minimum=1)
        self.polygon = check_polygon(polygon)
        self.rings = rings = _rings(self.polygon)
        if self.beta <= 0:
            return
        # every ordered ring pair is a job, so a job's reverse intervals are another's
        self.intervals = {(x, y, sigma): _Intervals(rings[x], rings[y], sigma, self.beta)
                          for x, y, sigma, _ in _jobs(len(rings))}
        self.runs = {(x, y): _vertex_runs(rings[x], rings[y], self.beta)
                     for x in range(len(rings)) for y in range(x, len(rings))}
        self._memo = _Memo(max_bytes=self.max_bytes)
        #: the address space when the first distinct round began: every round's memory
        #: budget counts from it (:func:`_address_space`)
        self._held: int | None = None
        #: the best smallest region (the first run without exclusion), from which the
        #: memo's floor starts (:data:`MEMO_SHARE`)
        self._best: float | None = None
        #: the cap of the runs with ``third``, made once (the memo's jobs keep what it
        #: read)
        self._third: _WidestFree | None = None

    def pairs(self, top: Any = 5, ties: bool = False, exclude: Any = (),
              fraction: float = 0.5, seen: Any = (), third: bool = False
              ) -> list[StretchPair]:
        """:func:`two_finger_stretches`'s answer (the same arguments).

        With ``third``, each configuration stands for the three-finger plan of its two
        regions and a third finger anywhere on the longest free stretch (mode
        ``"pair"`` of :mod:`fcgrasp.grippers.three_fingers`), and ``exclude`` holds
        three-finger plans (three regions each): a configuration is left out when that
        plan is surely the same alternative as one of them (two of its regions as
        above, and its free stretch overlapping the third by more than ``fraction`` of
        the shorter).  ``seen`` still holds two-finger plans."""
        top_v = None if top is None else check_int(top, "top", minimum=1)
        if not isinstance(ties, bool):
            raise TypeError(f"ties must be a bool, got {ties!r}")
        fraction_v = check_scalar(fraction, "fraction", nonnegative=True)
        if fraction_v > 1:
            raise ValueError(f"fraction must be in [0, 1], got {fraction!r}")
        if self.beta <= 0:
            return []
        rings, polygon = self.rings, self.polygon
        _load_for_depth(top_v)
        kept = [(p.regions, p.region_edges) for p in exclude
                if len(p.regions) == (3 if third else 2)]
        read = [(p.region_edges, p.mode) for p in seen if len(p.region_edges) == 2]
        # (nothing to exclude: no map of the edges, 36 ms on 10,000 edges)
        excl = _Exclusion(rings, polygon, kept, fraction_v, read, third) \
            if kept or read else None
        # a pair plan's smallest region is at most its third finger's widest free
        # stretch: the search ranks by that bound (the same FreeThird as the exclusion's)
        if third and self._third is None:
            free = excl.free if excl is not None and excl.free is not None else \
                FreeThird(rings, polygon, THIRD_PAD * ROUND_TOL * polygon.size)
            self._third = _WidestFree(free)
        cap = self._third if third else None
        memo = self._memo
        # the rounds that share a memo: those that exclude, and those with a cap (their
        # values have no vertex-aligned lower bound to start from: the memo's floor
        # starts from the best smallest region of a search without the cap)
        shared = excl is not None or cap is not None
        if cap is not None and self._best is None:
            self.pairs(top=top_v)
        if shared and memo.prepared is None and self._best is not None and memo.floor == 0.0:
            memo.lower(self.share * self._best)
        # the highest floor whose collection did not fit the memory budget: a run that
        # needs to collect down to it or below cannot be made
        overflow = -np.inf
        # the collection's cap for speed (COLLECT_CAP; two fingers' rounds: three
        # fingers' rank by their cap, and higher floors only repeat their collections):
        # the highest floor whose collection went over it, the lowest floor a run found
        # fewer than ``top`` at, and whether the floor now tried is one the answer needs
        # (a run's ``top``-th found below its floor: no higher floor will do)
        if shared and memo.prepared is None:
            memo.cap = None if third else COLLECT_CAP
        over_cap, too_few, needed, tries = -np.inf, np.inf, False, 0
        while True:
            if shared:
                budget.check()
            began = time.monotonic()
            try:
                # a round of the distinct search under the memory budget (its collection
                # of a smooth outline can ask for gigabytes at once)
                if shared and self._held is None:
                    self._held = budget.address_held()
                with _address_space(memo.max_bytes if shared else None, self._held):
                    found = _search(rings, self.beta, self.intervals, self.runs, top_v,
                                    polygon.size, excl or None, memo if shared else None,
                                    cap)
            except budget.BudgetExhausted as exc:
                best = self._best
                if str(exc) == "collection":
                    # too many configurations reach this floor to collect quickly (a
                    # smooth outline's next alternative and its thousands of shifted
                    # copies): half way up to the lowest floor that found too few, or
                    # in full where the answer needs this floor, the two meet or the
                    # tries run out
                    over_cap, tries = max(over_cap, memo.floor), tries + 1
                    upper = min(too_few, best if best is not None else np.inf)
                    if needed or not np.isfinite(upper) or tries > CAP_TRIES or \
                            upper - memo.floor <= CAP_CLOSE * upper:
                        memo.cap = None
                        memo.lower(memo.floor)
                    else:
                        memo.lower((memo.floor + upper) / 2)
                    continue
                if str(exc) == "max_memory" and excl is None and cap is not None:
                    # a first round whose capped collection does not fit: the ranking by
                    # the smallest region alone, which needs none (each pair's smallest
                    # region bounds its pair plan's too)
                    return self.pairs(top=top, ties=ties)
                if str(exc) != "max_memory" or not shared or best is None \
                        or memo.floor <= 0.0:
                    raise
                # the collection down to this floor does not fit: collect from higher
                # up (half way to the best plan), which the floor's rule keeps exact
                # (a run whose answer needs more lowers it again, if that fits)
                overflow = max(overflow, memo.floor)
                higher = memo.floor + (best - memo.floor) / 2
                # (not when the time left would not see another such attempt through)
                if higher >= best * OVERFLOW_SHARE or \
                        budget.remaining() < time.monotonic() - began:
                    raise
                memo.lower(higher)
                continue
            if not shared or memo.floor == 0.0:
                break
            # the top-th found at or above the memo's floor: nothing missed; below it,
            # collect down to it; fewer than top found: a step down (a small one where
            # some were: the collection grows steeply as its floor falls, and the
            # top-th is then just below)
            if top_v is not None and len(found) >= top_v:
                need = found[top_v - 1].value * (1 - TIE)
                if need >= memo.floor:
                    break
                low, needed = need * (1 - TIE), True
            else:
                too_few = min(too_few, memo.floor)
                # (an outline of tens of edges: a long step, each run costing its fixed
                # cost, not its few configurations')
                low = memo.floor * (FLOOR_STEP_SMALL if polygon.n_edges <= SMALL_OUTLINE
                                    else FLOOR_STEP_SOME if found else FLOOR_STEP_NONE)
                if memo.cap is not None and low <= over_cap:
                    # (a floor that went over the cap: half way down to it instead, or
                    # the usual step collected in full once the two meet)
                    tries += 1
                    if tries > CAP_TRIES or memo.floor - over_cap <= CAP_CLOSE * memo.floor:
                        memo.cap = None
                    else:
                        low = (memo.floor + over_cap) / 2
            if low <= overflow:         # what the answer needs does not fit the budget
                raise budget.BudgetExhausted("max_memory")
            # below a thousandth of the best plan: every configuration
            memo.lower(low if low > 1e-3 * (self._best or 0.0) else 0.0)
        if not shared and found:
            best = found[0].t
            self._best = best if self._best is None else max(self._best, best)
        if not found:
            return []
        if top_v is not None:
            kth = found[min(top_v, len(found)) - 1].value
            found = [f for f in found if f.value >= kth * (1 - TIE)] if ties \
                else found[:top_v]
        found = _finish(rings, self.beta, found, self.intervals, polygon)
        pairs = _pairs(rings, found if ties or top_v is None else found[:top_v])
        if cap is not None:
            # each pair with the bound it was ranked by (its pair plan's at most)
            pairs = [replace(p, bound=f.value) for p, f in zip(pairs, found, strict=False)]
        return pairs


class _WidestFree:
    """The cap of a three-finger round (:func:`~fcgrasp.model.stretches._solve._solve_jobs`'s
    ``cap``): each configuration's third finger's widest free stretch
    (:meth:`~fcgrasp.model.stretches._free_third.FreeThird.widest`)."""

    def __init__(self, free: FreeThird) -> None:
        self.free = free

    def __call__(self, job: Any, cfg: Any) -> FloatArray:
        return self.free.widest(job[0], job[1], cfg)


#: The distinct search's memo (:class:`_Memo`) first collects the configurations whose arc
#: length reaches this share of the best smallest region (lowered when a run's
#: ``top``-th falls below it): a smooth outline of 2,000 edges has tens of millions of
#: configurations, most far below any plan kept.  (``StretchSearch``'s ``share``.)
MEMO_SHARE = 0.5


#: The most configurations a two-finger distinct round collects at once (a fraction of a
#: second): where more reach its floor, a higher floor is tried (half way up to one that
#: found too few), until the two are within :data:`CAP_CLOSE` of each other; then the
#: collection is made in full.  A smooth 10,000-edge outline at mu 1.0 has fifteen
#: million configurations within a tenth of its second alternative.
COLLECT_CAP = 500_000


#: How close (a share of the higher) the floors that went over :data:`COLLECT_CAP` and
#: found too few may come before the collection is made in full.
CAP_CLOSE = 1e-3


#: Floors a round tries for :data:`COLLECT_CAP` at most before it collects in full.
CAP_TRIES = 24


#: The share of the best plan above which a distinct round whose collection did not fit
#: the memory budget is not tried again from a higher floor.
OVERFLOW_SHARE = 0.85


#: The factors a distinct round's memo floor is lowered by when fewer than ``top`` were
#: found above it: some, none.
FLOOR_STEP_SOME, FLOOR_STEP_NONE = 0.95, 0.9


#: On an outline of at most this many edges a distinct round's memo floor is lowered by
#: :data:`FLOOR_STEP_SMALL` when fewer than ``top`` were found above it: its collections
#: hold hundreds of configurations, and a run costs its fixed cost (on a smooth outline
#: of hundreds of edges the collection grows steeply as the floor falls).
SMALL_OUTLINE, FLOOR_STEP_SMALL = 100, 0.5


def stretch_regions(polygon: Polygon, stretches: Any, mu: ArrayLike,
                    margin: ArrayLike = DEFAULT_MARGIN_DEG) -> StretchPair | None:
    """Optimal independent regions inside two given stretches (definition 7.1).

    ``stretches``: for each finger, the consecutive edges of one ring it may cover, in
    ring order (a single edge is a stretch of one edge).  Every configuration inside
    them is solved exactly; the best by the leximin order, squeezing or expanding.
    None when no pair of regions holds.

    >>> sq = Polygon([[0, 0], [10, 0], [10, 3], [0, 3]])
    >>> r = stretch_regions(sq, [[0], [2]], mu=0.3)
    >>> r.region_edges, round(r.min_length, 3)
    (((0,), (2,)), 0.872)
    """
    beta = _check_args(polygon, mu, margin)
    if isinstance(stretches, (str, bytes)) or len(stretches) != 2:
        raise ValueError(f"stretches must hold two sequences of edges, got {stretches!r}")
    rings = _rings(polygon)
    where = _positions(rings)
    runs = []
    for k, st in enumerate(stretches):
        edges = polygon.check_stretch(st, f"stretches[{k}]")
        runs.append((where[edges[0]][0], [where[e][1] for e in edges]))
    if set(map(int, stretches[0])) & set(map(int, stretches[1])):
        raise ValueError(f"the two stretches share an edge, got {stretches!r}")
    if beta <= 0:
        return None
    x, y = runs[0][0], runs[1][0]
    ra, rb = rings[x], rings[y]
    intervals = {(a, b, sigma): _Intervals(rings[a], rings[b], sigma, beta)
                 for a, b in ((x, y), (y, x)) for sigma in (1.0, -1.0)}
    cfg = _configs_in(ra, rb, x == y, (runs[0][1], runs[1][1]))
    # every sub-configuration, longest bound first, in chunks behind the best found
    prepared = [((x, y, sigma, mode), cfg) for sigma, mode in ((1.0, "squeeze"),
                                                               (-1.0, "expand"))]
    keys = _Keys(rings)
    found = _solve_jobs(rings, beta, prepared, intervals, _Bound(1, 2 * keys.total),
                        polygon.size, keys)
    if not found:
        return None
    best = max(f.t for f in found)
    found = _finish(rings, beta, [f for f in found if f.t >= best * (1 - TIE)], intervals,
                    polygon)
    return _pairs(rings, found[:1])[0]
