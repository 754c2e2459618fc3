r"""Regions along the boundary for three and four frictionless fingers.

A *stretch* is a connected piece of one boundary ring (see :mod:`fcgrasp.model.stretches`);
strictly inside an edge a finger pushes along the edge's inward normal, at a vertex
strictly inside a stretch along **any** direction between the two edges' normals.

**The vertex lemma (why a finite check is exact).**  A frictionless contact at a point
``p`` pushing along ``f`` exerts the wrench :math:`w(p, f) = (f, p \times f)`: affine in
``p`` along an edge (``f`` fixed) and linear in ``f`` at a vertex (``p`` fixed).  Force
closure does not change when a wrench is scaled by a positive factor, and the
directions between ``f_k`` and ``f_{k+1}`` (an angle below pi) are the positive
combinations of the two, so up to scale a region exerts the wrenches of a *polygonal
chain*: from ``w(x_0, f)`` to ``w(v, f)`` along each piece of edge, from ``w(v, f_k)``
to ``w(v, f_{k+1})`` at each vertex ``v`` inside it.  A grasp is not force closure iff
a twist ``t != 0`` has :math:`t \cdot w_i \le 0` for every finger (theorem 6.1, the
repelling twists).  So *some* grasp of the regions fails iff some ``t != 0`` has, for
every finger, :math:`\min_{chain_i} t \cdot w \le 0`; a linear function's minimum
over a chain is reached at one of the chain's vertices.  Hence: **every grasp of the
regions is force closure iff every choice of chain vertices is**, that is, the region
ends with their edges' normals and every vertex inside a region with each of its two
edges' normals.  Grouped by the normal they carry, these are the ends of the pieces
of each covered edge inside the region: the regions hold iff, for every choice of one
covered edge per finger, those pieces hold as single-edge regions (theorem 7.1).  (A
contact with friction is two wrenches at one point and the lemma does not apply; two
fingers with friction are solved in :mod:`fcgrasp.model.stretches`.)  Gravity, as the third
"finger" of three, is one fixed wrench.

**The optimum of a configuration.**  A configuration fixes the covered edges of every
finger; only the first and the last piece of each region move.  For one pairing of the
fingers and one orientation of the two-sided cone (``"+C"``: ``P34 - P12`` in
``C = C_12 & -C_34`` shrunk by the margin, ``"-C"``: in ``-C``), theorem 7.1 on every
combination of covered edges is two linear inequalities in the end positions (the
functionals of :mod:`fcgrasp.model.regions` take, on each piece, the end their sign selects).
The largest smallest region and then the leximin levels (definition 7.1) are linear
programs (scipy's HiGHS): exact for the configuration, pairing and orientation.

**The search: a proven safe plan, a lower bound on the optimum.**  Configurations grow
as ``n**8``; instead each of the best single-edge plans is *grown*: at each step every
extension of one region by one edge, at either end, that keeps the fingers on distinct
edges is solved, and the best one that improves (the smallest region, then the total
length) is taken, until none improves; the best grown configurations are then *polished*:
where no single move improves, the best improving pair of moves on two regions (each
slid by one edge) is taken and the growth goes on (on a 24-edge ellipse
the four regions of four edges each are reached only by sliding two regions at once).
Every returned plan holds (the lemma) and ranks at least as high as the single-edge
plan it grew from; it can miss a configuration that is reached only through worse
ones.  ``benchmarks/bench_stretches.py`` measures that gap
against the exhaustive enumeration (:func:`all_frictionless_stretches`: feasible
configurations are closed under dropping an end edge, so growing every feasible single
edge set by one edge at a time reaches every one of them).  The tests sample every
returned region, vertices inside with every normal between their edges', with the
general force-closure test.
"""

from __future__ import annotations

import math
from collections import OrderedDict
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core import budget
from ..core._checks import FloatArray, check_scalar
from ..core._geom import trim_vertex_ends
from ..core.sectors import PAIRINGS
from ..core.tolerances import (
    RANK_TOL,
    ROUND_TOL,
)
from . import _frictionless_kernels
from ._frictionless_program import (
    _Config,
    _first_level,
    _lengths,
    _leximin,
    _polyline,
    _stretch_facts,
    _system,
    _total,
)
from .polygon import Polygon
from .regions import DEFAULT_MARGIN_DEG

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = ["FrictionlessStretches", "frictionless_stretch_regions", "grow_stretches",
           "all_frictionless_stretches", "MAX_COMBINATIONS"]


#: A configuration is solved only when its combinations of covered edges (one per
#: finger) are at most this many (one pair of inequalities each).
MAX_COMBINATIONS = 4096


#: Systems a search keeps (:class:`_Search`): the memory of a growth is bounded by this
#: many systems of :data:`MAX_COMBINATIONS` combinations, whatever the part.
KEEP_SYSTEMS = 64


MODES = ("+C", "-C")


@dataclass(frozen=True)
class FrictionlessStretches:
    """Independent regions along the boundary for frictionless fingers.

    ``region_edges[i]`` lists the edges finger ``i`` covers in ring order,
    ``regions[i]`` is its polyline ``(m_i, 2)`` from one end to the other,
    ``lengths[i]`` its arc length; ``pairing`` and ``mode`` name the two-sided cone of
    theorem 7.1 that certifies them (the pairing indexes the fingers, gravity last).
    """

    region_edges: tuple[tuple[int, ...], ...]
    regions: tuple[FloatArray, ...]
    lengths: tuple[float, ...]
    pairing: tuple[int, ...]
    mode: str

    @property
    def min_length(self) -> float:
        return float(min(self.lengths))


def _result(polygon: Polygon, cfg: _Config, x: FloatArray, pairing: np.ndarray,
            mode: str) -> FrictionlessStretches:
    x = np.asarray(x)[:2 * len(cfg.edges)]
    lines, covered = [], []
    tiny = ROUND_TOL * polygon.size
    for f, st in enumerate(cfg.edges):
        # a sub-region of the certified one: it holds
        pts, edges = trim_vertex_ends(_polyline(polygon, st, x[2 * f], x[2 * f + 1]), st,
                                      tiny)
        lines.append(pts)
        covered.append(edges)
    return FrictionlessStretches(tuple(covered), tuple(lines),
                                 tuple(float(v) for v in _lengths(cfg, x)),
                                 tuple(int(p) for p in pairing), mode)


def _check(polygon: Polygon, region_edges: Any, margin: ArrayLike, gravity: ArrayLike | None
           ) -> tuple[tuple[tuple[int, ...], ...], float, FloatArray | None]:
    if not isinstance(polygon, Polygon):
        raise TypeError(f"polygon must be a fcgrasp.Polygon, got {type(polygon).__name__}")
    margin = check_scalar(margin, "margin", nonnegative=True)
    g = None
    if gravity is not None:
        g = np.asarray(gravity, dtype=float)
        if g.shape != (2,) or not np.all(np.isfinite(g)) or not np.any(g != 0):
            raise ValueError(f"gravity must be a nonzero direction (gx, gy), got {gravity!r}")
    want = 3 if g is not None else 4
    if isinstance(region_edges, (str, bytes)) or len(region_edges) != want:
        raise ValueError(f"region_edges must hold {want} stretches (one per finger"
                         f"{', gravity is the fourth' if g is not None else ''}), "
                         f"got {region_edges!r}")
    edges = tuple(polygon.check_stretch(st, f"region_edges[{i}]")
                  for i, st in enumerate(region_edges))
    flat = [e for st in edges for e in st]
    if len(set(flat)) != len(flat):
        raise ValueError(f"region_edges must not share an edge, got {region_edges!r}")
    return edges, margin, g


class _Search:
    """Configurations solved so far (one part, margin and gravity): a configuration is
    keyed by its covered edges, pairing and orientation; its first level (the largest
    smallest region) and, for ties only, its largest total length are kept."""

    def __init__(self, polygon: Polygon, margin: float, gravity: FloatArray | None) -> None:
        self.polygon, self.margin, self.gravity = polygon, margin, gravity
        #: each configuration's first level (None: no regions)
        self.level: dict[tuple[Any, ...], float | None] = {}
        #: the systems of the configurations solved last, at most :data:`KEEP_SYSTEMS`
        #: (a system holds two rows per combination of covered edges, up to
        #: :data:`MAX_COMBINATIONS`; one is rebuilt when asked for again)
        self._systems: OrderedDict[tuple[Any, ...], _Config] = OrderedDict()
        self.totals: dict[tuple[Any, ...], float] = {}
        self._facts: dict[tuple[int, ...], tuple[float, float, float, float]] = {}
        self._arrays: Any = None
        #: whether the programs' rows come from the compiled loop (asked once)
        self.compiled = _frictionless_kernels.COMPILED.available()

    def facts(self, st: tuple[int, ...]) -> tuple[float, float, float, float]:
        """:func:`_stretch_facts` of a stretch, once per search (a stretch is met again
        in every move of the other regions)."""
        got = self._facts.get(st)
        if got is None:
            got = self._facts[st] = _stretch_facts(self.polygon, st)
        return got

    def arrays(self) -> Any:
        """The compiled rows' :func:`~._frictionless_kernels.edge_arrays`, once per
        search."""
        if self._arrays is None:
            self._arrays = _frictionless_kernels.edge_arrays(self.polygon, self.gravity)
        return self._arrays

    def solve(self, edges: tuple[tuple[int, ...], ...], pairing: int, mode: str,
              parent: tuple[Any, ...] | None = None) -> float | None:
        """The configuration's first level (None: no regions), solved once (its system
        then kept among the last :data:`KEEP_SYSTEMS`: :meth:`system`);
        ``parent``: the key of a solved configuration one move away (the same pairing
        and orientation), whose rows it shares are copied."""
        key = (edges, pairing, mode)
        if key not in self.level:
            cfg = self._build(key, parent)
            t = None if cfg is None else _first_level(cfg)
            self.level[key] = t
            if cfg is not None and t is not None:
                self._keep(key, cfg)
        return self.level[key]

    def _build(self, key: tuple[Any, ...], parent: tuple[Any, ...] | None = None
               ) -> _Config | None:
        """The system of a configuration (``parent``'s rows copied where it is kept)."""
        edges, pairing, mode = key
        near = None if parent is None else self._systems.get(parent)
        return _system(self.polygon, edges, PAIRINGS[pairing], mode, self.margin,
                       self.gravity, compiled=self.compiled, facts=self.facts,
                       arrays=self.arrays(), parent=near, checked=True)

    def _keep(self, key: tuple[Any, ...], cfg: _Config) -> None:
        self._systems[key] = cfg
        self._systems.move_to_end(key)
        while len(self._systems) > KEEP_SYSTEMS:
            self._systems.popitem(last=False)

    def system(self, key: tuple[Any, ...]) -> _Config:
        """The system of a configuration that holds regions (rebuilt if not kept: the
        same rows)."""
        cfg = self._systems.get(key)
        if cfg is None:
            cfg = self._build(key)
            assert cfg is not None
        self._keep(key, cfg)
        return cfg

    def reach(self, edges: tuple[tuple[int, ...], ...]) -> float:
        """The shortest stretch's arc length: a bound on the smallest region."""
        return min(self.facts(st)[3] for st in edges)

    def total(self, key: tuple[Any, ...], t: float) -> float:
        if key not in self.totals:
            self.totals[key] = _total(self.system(key), t)
        return self.totals[key]

    def better(self, a: tuple[Any, ...], b: tuple[Any, ...] | None) -> bool:
        """Configuration ``a`` beats ``b`` (keys of solved ones): a longer smallest
        region, or, tied, a longer total."""
        if b is None:
            return True
        ta, tb = self.level[a], self.level[b]
        assert ta is not None and tb is not None
        if ta > tb * (1 + RANK_TOL):
            return True
        if ta < tb * (1 - RANK_TOL):
            return False
        return self.total(a, ta) > self.total(b, tb) * (1 + RANK_TOL)

    def seed(self, edges: tuple[tuple[int, ...], ...]) -> tuple[Any, ...] | None:
        """The pairing and orientation with the best single-edge configuration."""
        best = None
        for pairing in range(len(PAIRINGS)):
            for mode in MODES:
                if self.solve(edges, pairing, mode) is not None and \
                        self.better((edges, pairing, mode), best):
                    best = (edges, pairing, mode)
        return best

    def grow(self, key: tuple[Any, ...], max_steps: int) -> tuple[Any, ...]:
        """Take the best improving move until none improves; then, if another pairing
        or orientation certifies the configuration better, go on with it."""
        for _ in range(max_steps):
            # single-edge configurations are the single-edge search's (the seeds)
            step = self._best_move(key, _moves(self.polygon, key[0]), single=False)
            if step is None:
                other = self.seed(key[0])
                if other is None or not self.better(other, key):
                    break
                step = other
            key = step
        return key

    def polish(self, key: tuple[Any, ...], max_steps: int) -> tuple[Any, ...]:
        """:meth:`grow`, then, where no move improves, the best improving *pair* of
        moves (:func:`_pair_moves`: two regions slid at once; a symmetric
        part's optimum can need two regions slid together, each slide alone shortening
        the smallest region), with the configuration's pairing and orientation, and
        grow again; until no pair improves either."""
        for _ in range(max_steps):
            key = self.grow(key, max_steps)
            step = self._best_move(key, _pair_moves(self.polygon, key[0]), single=True)
            if step is None:
                break
            key = step
        return key

    def _best_move(self, key: tuple[Any, ...], moves: list[tuple[tuple[int, ...], ...]],
                   single: bool) -> tuple[Any, ...] | None:
        """The best of ``moves`` (covered edges) that beats ``key`` with its pairing and
        orientation, or None; ``single`` False: single-edge configurations left out.  A
        region is never longer than the edges it covers: a move whose shortest stretch
        is below the best so far is not solved."""
        step = None
        for new in moves:
            if (not single and _size(new) == 1) or _size(new) > MAX_COMBINATIONS:
                continue
            ahead = self.level[key if step is None else step]
            assert ahead is not None
            if self.reach(new) < ahead * (1 - RANK_TOL):
                continue
            cand = (new, key[1], key[2])
            if self.solve(*cand, parent=key) is not None and \
                    self.better(cand, key if step is None else step):
                step = cand
        return step

    def result(self, key: tuple[Any, ...]) -> FrictionlessStretches | None:
        cfg = self.system(key)
        x = _leximin(cfg)
        return None if x is None else _result(self.polygon, cfg, x, PAIRINGS[key[1]], key[2])


def frictionless_stretch_regions(polygon: Polygon, region_edges: Any,
                                 margin: ArrayLike = DEFAULT_MARGIN_DEG,
                                 gravity: ArrayLike | None = None
                                 ) -> FrictionlessStretches | None:
    """Optimal independent regions covering exactly the given stretches (definition
    7.1 with the vertex lemma of this module), frictionless fingers.

    ``region_edges``: per finger (four, or three with ``gravity``, a direction), the
    consecutive edges of one ring its region covers, in ring order.  The best pairing
    and cone orientation is used; None when no regions cover these edges.

    >>> sq = Polygon([[0, 0], [10, 0], [10, 10], [0, 10]])
    >>> r = frictionless_stretch_regions(sq, [[0], [1], [2], [3]])
    >>> round(r.min_length, 3) > 0
    True
    """
    edges, margin, g = _check(polygon, region_edges, margin, gravity)
    search = _Search(polygon, margin, g)
    key = search.seed(edges)
    return None if key is None else search.result(key)


def _moves(polygon: Polygon, edges: tuple[tuple[int, ...], ...], grow_only: bool = False
           ) -> list[tuple[tuple[int, ...], ...]]:
    """Configurations one step away: one region longer by one edge at one end; unless
    ``grow_only``, also slid by one edge (one end added, the other dropped) or shorter
    by one end edge."""
    used = {e for st in edges for e in st}
    out = []
    for f, st in enumerate(edges):
        ring = int(np.sum((polygon.rings == polygon.rings[st[0]]) & polygon.usable))
        before, after = polygon.previous_edge(st[0]), polygon.next_edge(st[-1])
        news: list[tuple[tuple[int, ...], int | None]] = []
        if len(st) + 1 < ring:
            news += [((before, *st), before), ((*st, after), after)]
        if not grow_only:
            news += _slides(polygon, st)
            if len(st) > 1:
                news += [(st[1:], None), (st[:-1], None)]
        for new, added in news:
            if added is None or added not in used:
                out.append(tuple(new if i == f else s for i, s in enumerate(edges)))
    return out


def _pair_moves(polygon: Polygon, edges: tuple[tuple[int, ...], ...]
                ) -> list[tuple[tuple[int, ...], ...]]:
    """Configurations two moves away, two different regions each slid by one edge (the
    fingers still on distinct edges; growth extends one region at a time already)."""
    used = {e for st in edges for e in st}
    per = [[(new, add) for new, add in _slides(polygon, st) if add not in used]
           for st in edges]
    out = []
    for f in range(len(edges)):
        for g in range(f + 1, len(edges)):
            for a, add_a in per[f]:
                for b, add_b in per[g]:
                    if add_a != add_b:
                        out.append(tuple(a if i == f else b if i == g else s
                                         for i, s in enumerate(edges)))
    return out


def _slides(polygon: Polygon, st: tuple[int, ...]) -> list[tuple[tuple[int, ...], int]]:
    """A stretch slid by one edge either way, with the edge each slide adds."""
    before, after = polygon.previous_edge(st[0]), polygon.next_edge(st[-1])
    return [((before, *st[:-1]), before), ((*st[1:], after), after)]


def _size(edges: tuple[tuple[int, ...], ...]) -> int:
    return math.prod(len(st) for st in edges)


def _seeds(polygon: Polygon, edge_sets: Any, margin: ArrayLike, gravity: ArrayLike | None
           ) -> tuple[_Search, list[tuple[tuple[tuple[int, ...], ...], Any]]]:
    """One search for the rows of single edges, and each row's configuration with its
    best pairing and orientation (None where it holds no regions)."""
    if not isinstance(polygon, Polygon):
        raise TypeError(f"polygon must be a fcgrasp.Polygon, got {type(polygon).__name__}")
    search = _Search(polygon, 0.0, None)
    out = []
    for k, row in enumerate(np.ravel(np.asarray(r)).tolist() for r in edge_sets):
        edges, margin_v, g = _check(polygon, [[e] for e in row], margin, gravity)
        if k == 0:
            search = _Search(polygon, margin_v, g)
        out.append((edges, search.seed(edges)))
    return search, out


def load_kernels() -> bool:
    """Load the growth's compiled programs now (and with them numba and the compiled
    kernels of :mod:`fcgrasp.core.kernels`), where numba is there and ``FCGRASP_JIT``
    leaves the choice to the searches: four fingers and three with gravity grow their
    best single-edge plans by them, so the single-edge search before the growth runs
    compiled too, instead of first running :data:`~fcgrasp.core.kernels.JIT_AFTER_ROWS`
    rows by numpy to learn that numba's start-up repays itself.  Whether they run."""
    return _frictionless_kernels.COMPILED.available()


def grow_stretches(polygon: Polygon, edge_sets: Any, margin: ArrayLike = DEFAULT_MARGIN_DEG,
                   gravity: ArrayLike | None = None, max_steps: int = 400, keep_single: bool = True,
                   polish: int = 0) -> list[FrictionlessStretches | None]:
    """Grow single-edge regions along the boundary (the search of this module's
    docstring).

    ``edge_sets``: rows of edges, one per finger (four, or three with ``gravity``);
    from each, extend the region whose extension improves most until none does.  Rows
    share what they solve.  The ``polish`` best configurations grown then try pairs of
    moves where single moves are done (:meth:`_Search.polish`: on a 24-edge ellipse
    four regions of four edges each are reached only by sliding two regions at once).
    Returns, per row, a safe plan that ranks at least as high as
    the row's single-edge regions (a lower bound on the optimum), or None when the row's
    edges hold no regions (or, with ``keep_single=False``, when its regions do not leave
    their edges: the single-edge search has them already).

    >>> from fcgrasp.io.parts import demo_part
    >>> [r.region_edges for r in grow_stretches(demo_part("blob"), [[0, 1, 3, 4]])]
    [((0,), (1,), (3,), (4,))]
    """
    if not isinstance(max_steps, int) or max_steps < 0:
        raise ValueError(f"max_steps must be an integer >= 0, got {max_steps!r}")
    if not isinstance(polish, int) or polish < 0:
        raise ValueError(f"polish must be an integer >= 0, got {polish!r}")
    search, seeds = _seeds(polygon, edge_sets, margin, gravity)
    # each seed grown while the time budget lasts (:func:`fcgrasp.core.budget.cut_short`:
    # a seed not grown is its single-edge plan, which holds)
    keys = []
    for _, key in seeds:
        if key is not None and not budget.cut_if_over():
            key = search.grow(key, max_steps)
        keys.append(key)
    # the best grown (distinct configurations, best first) polished
    best: list[tuple[Any, ...]] = []
    for key in keys:
        if key is not None and key not in best:
            at = next((i for i, b in enumerate(best) if search.better(key, b)), len(best))
            best.insert(at, key)
    polished = {key: search.polish(key, max_steps) for key in best[:polish]
                if not budget.cut_if_over()}
    out: list[FrictionlessStretches | None] = []
    for key in keys:
        if key is not None:
            key = polished.get(key, key)
        if key is not None and not keep_single and _size(key[0]) == 1:
            key = None
        out.append(None if key is None else search.result(key))
    return out


def all_frictionless_stretches(polygon: Polygon, edge_sets: Any,
                               margin: ArrayLike = DEFAULT_MARGIN_DEG,
                               gravity: ArrayLike | None = None,
                               limit: int = 200_000) -> FrictionlessStretches | None:
    """The best configuration that holds and covers one of the given single-edge sets
    (rows of edges, one per finger), over every pairing and cone orientation:
    exhaustive and slow, the reference that measures the gap of :func:`grow_stretches`.
    Given every single-edge set that holds (``fc.plan(part, fingers, top=None,
    along_boundary=False)``), it is the optimum over all configurations.

    A configuration that holds for a pairing and orientation still holds, for the same
    ones, with an end edge dropped; so every configuration that holds is reached from
    single edges by one-edge extensions that all hold, and a breadth-first search over
    them sees every one.  ``limit`` caps the configurations tried (``ValueError``
    beyond it).
    """
    search, seeds = _seeds(polygon, edge_sets, margin, gravity)
    top = None
    frontier = []
    for edges0, key in seeds:
        if key is not None:
            frontier.append(edges0)
            if search.better(key, top):
                top = key
    if top is None:
        return None
    seen = set(frontier)
    while frontier:
        nxt = []
        for cfg in frontier:
            for new in _moves(polygon, cfg, grow_only=True):
                if new in seen or _size(new) > MAX_COMBINATIONS:
                    continue
                seen.add(new)
                if len(seen) > limit:
                    raise ValueError(f"more than limit={limit} configurations to try")
                best = search.seed(new)
                if best is None:
                    continue
                nxt.append(new)
                if search.better(best, top):
                    top = best
        frontier = nxt
    return search.result(top)
