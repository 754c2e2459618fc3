"""Three fingers with friction: concurrent plans grown along the boundary, one edge at a
time (part of :mod:`fcgrasp.grippers.three_fingers`)."""

from __future__ import annotations

from dataclasses import replace
from itertools import product
from typing import Any

import numpy as np

from ...core._angles import wrap
from ...core._checks import FloatArray, check_mu_scalar, check_scalar
from ...core.tolerances import LEVEL_TIE, RANK_TOL
from ...model.plans import GraspPlan
from ...model.polygon import Polygon, check_polygon
from ...pipeline import PlanSpec
from .._boundary import regions_plan
from ._concurrent import (
    _SIDES,
    Piece,
    _Block,
    _lengths,
    _leximin,
    _smallest,
    _solve_blocks,
    first_best,
    spanning_arcs,
)

#: Concurrent plans of single edges grown along the boundary (the best ones).
GROW_SEEDS = 5


#: A grown configuration has at most this many corner grasps (points per region, multiplied).
MAX_CORNERS = 216


#: Growth steps at most (each lengthens the shortest regions by one edge each).
MAX_STEPS = 60


def _stretch_cone(polygon: Polygon, stretch: tuple[int, ...], mu: float
                  ) -> tuple[float, float]:
    """The friction cone every contact of a stretch has (centre and half-width of the
    force directions; negative where none): the intersection of its edges' cones (a
    fingertip on an interior vertex may push along any normal of the vertex's fan, whose
    cones all hold that intersection)."""
    n = polygon.normals[list(stretch)]
    c = np.arctan2(-n[:, 1], -n[:, 0])
    d = wrap(c - c[0])
    phi = float(np.arctan(mu))
    lo, hi = c[0] + d.max() - phi, c[0] + d.min() + phi
    return float((lo + hi) / 2), float((hi - lo) / 2)


def _stretch_blocks(polygon: Polygon, stretches: tuple[tuple[int, ...], ...], mu: float,
                    margin: float, sides: Any = None) -> list[_Block]:
    """The convex pieces of three fingers on three stretches (in units of the part's size):
    the sub-arcs of :func:`spanning_arcs` of the stretches' common cones times the sides
    (default all eight)."""
    size = polygon.size
    cones = [_stretch_cone(polygon, st, mu) for st in stretches]
    center = np.array([c for c, _ in cones])
    half = np.array([h for _, h in cones])
    if np.any(half <= margin):
        return []
    first = [st[0] for st in stretches]
    last = [st[-1] for st in stretches]
    L = polygon.lengths
    const = np.array([0.0 if len(st) == 1 else float(L[list(st[:-1])].sum())
                      for st in stretches]) / size
    inner = tuple(polygon.starts[list(st[1:])] / size for st in stretches)
    args = (polygon.starts[first] / size, polygon.tangents[first], L[first] / size,
            polygon.starts[last] / size, polygon.tangents[last], L[last] / size, const,
            inner)
    return [_Block(*args, lo, hi, np.asarray(sigma, float), 0)
            for lo, hi in spanning_arcs(center, half, margin)
            for sigma in (_SIDES if sides is None else sides)]


def _stretch_moves(polygon: Polygon, stretches: tuple[tuple[int, ...], ...], grow: Any
                   ) -> list[tuple[tuple[int, ...], ...]]:
    """Configurations with every region marked in ``grow`` one edge longer, each at one
    of its ends (on edges no region covers, never a whole ring): the smallest region can
    only grow when every region as short does."""
    used = {e for st in stretches for e in st}
    options = []
    for st, g in zip(stretches, grow, strict=True):
        ring = int(np.sum((polygon.rings == polygon.rings[st[0]]) & polygon.usable))
        opts = []
        if g and len(st) + 1 < ring:
            for new, added in (((polygon.previous_edge(st[0]), *st), polygon.previous_edge(st[0])),
                               ((*st, polygon.next_edge(st[-1])), polygon.next_edge(st[-1]))):
                if added not in used and polygon.usable[added]:
                    opts.append(new)
        options.append(opts if g else [st])
    out = []
    for combo in product(*options):
        edges = [e for st in combo for e in st]
        if len(edges) == len(set(edges)):
            out.append(tuple(combo))
    return out


def _corner_count(stretches: tuple[tuple[int, ...], ...]) -> int:
    return int(np.prod([len(st) + 1 for st in stretches]))


def _best_piece(blocks: list[_Block], xs: list[FloatArray | None]
                ) -> tuple[float, _Block | None, FloatArray | None]:
    got = [(_smallest(blk, x), blk, x) for blk, x in zip(blocks, xs, strict=True)
           if x is not None]
    return got[first_best([g[0] for g in got])] if got else (-1.0, None, None)


def _bottlenecks(blk: _Block, level: float) -> np.ndarray:
    """The regions of a piece that cannot be longer than ``level`` (the others kept at
    least that long): the ones that must all grow for the smallest to grow.  Decided by
    one program per region, so not by which optimal solution a solver returned."""
    fixed = np.full(3, level)
    out = np.ones(3, dtype=bool)
    for i in range(3):
        x = _solve_blocks([blk], fixed=fixed, grow=i)[0]
        out[i] = x is None or _lengths(blk, x)[i] <= level * (1 + LEVEL_TIE)
    return out


def grow_concurrent(polygon: Polygon, edges: Any, mu: float, margin: float,
                    sigma: Any = None) -> tuple[tuple[tuple[int, ...], ...], Piece] | None:
    """Concurrent regions of three fingers grown along the boundary from three edges.

    Each step solves, in one linear program, every configuration with the regions as
    short as the smallest one edge longer (:func:`_stretch_moves`; every contact of a
    stretch keeps the cone common to its edges, so a piece of it is convex as on single
    edges) with the sides ``sigma`` of the meeting point (default: all eight), and takes
    the best that lengthens the smallest region; it stops when none does.  The configuration reached
    is solved over every piece and its levels made leximin-optimal.  Returns the
    stretches and the :class:`Piece` (positions in the part's units), or None when the
    edges hold no concurrent grasp.  A safe lower bound, as on single edges: every grasp
    of the regions is force closure.

    >>> import numpy as np
    >>> a = np.linspace(0, 2 * np.pi, 60, endpoint=False)
    >>> part = Polygon(np.c_[40 * np.cos(a), 25 * np.sin(a)])
    >>> st, piece = grow_concurrent(part, (0, 20, 40), mu=0.5, margin=np.radians(0.5))
    >>> min(len(s) for s in st) > 1, bool(piece.levels.min() > part.lengths[0])
    (True, True)
    """
    polygon = check_polygon(polygon)
    idx = polygon.check_edges(edges, "edges")
    if len(idx) != 3 or len(set(idx)) != 3:
        raise ValueError(f"edges must be three distinct edges, got {edges!r}")
    mu = check_mu_scalar(mu, "mu")
    margin = check_scalar(margin, "margin", nonnegative=True)
    if sigma is not None and (np.shape(sigma) != (3,) or not np.all(np.abs(sigma) == 1)):
        raise ValueError(f"sigma must be three sides, each 1 or -1, got {sigma!r}")
    sides = None if sigma is None else [np.asarray(sigma, float)]
    cur: tuple[tuple[int, ...], ...] = tuple((e,) for e in idx)
    blocks = _stretch_blocks(polygon, cur, mu, margin, sides)
    level, blk, x = _best_piece(blocks, _solve_blocks(blocks)) if blocks else (-1.0, None, None)
    if blk is None or x is None:
        return None
    for _ in range(MAX_STEPS):
        # the regions as short as the smallest must all grow for it to grow
        short = _bottlenecks(blk, level)
        moves = [m for m in _stretch_moves(polygon, cur, short)
                 if _corner_count(m) <= MAX_CORNERS]
        per = [_stretch_blocks(polygon, m, mu, margin, [blk.sigma]) for m in moves]
        flat = [b for bs in per for b in bs]
        if not flat:
            break
        xs = _solve_blocks(flat)
        better = []
        k = 0
        for m, bs in zip(moves, per, strict=True):
            lv, b, xb = _best_piece(bs, xs[k:k + len(bs)])
            k += len(bs)
            if b is not None and xb is not None and lv > level * (1 + RANK_TOL):
                better.append((lv, m, b, xb))
        if not better:
            break
        level, cur, blk, x = better[first_best([g[0] for g in better])]
    blocks = _stretch_blocks(polygon, cur, mu, margin)
    _, blk, _ = _best_piece(blocks, _solve_blocks(blocks))
    piece = None if blk is None else _leximin(blk)
    if piece is None:
        return None
    size = polygon.size
    return cur, replace(piece, lo=piece.lo * size, hi=piece.hi * size,
                        levels=piece.levels * size, witness=piece.witness * size)


def _grown_plans(polygon: Polygon, spec: PlanSpec,
                 found: list[tuple[float, tuple[int, ...], _Block]], F: Any
                 ) -> list[GraspPlan]:
    """The :data:`GROW_SEEDS` best concurrent plans of single edges grown along the
    boundary (:func:`grow_concurrent`): the plans whose regions leave their edges."""
    out = []
    seen = set()
    for _, row, blk in found[:GROW_SEEDS]:
        got = grow_concurrent(polygon, [int(F.edge[f]) for f in row], spec.mu,
                              spec.margin_rad, blk.sigma)
        if got is None or max(len(st) for st in got[0]) == 1 or got[0] in seen:
            continue                    # two seeds may grow into one configuration
        stretches, piece = got
        seen.add(stretches)
        out.append(regions_plan(polygon, spec, stretch_polylines(polygon, stretches, piece),
                                stretches, piece.levels, "friction", "concurrent"))
    return out


def stretch_polylines(polygon: Polygon, stretches: Any, piece: Piece) -> list[FloatArray]:
    """The regions of a :class:`Piece` on stretches as polylines: from ``lo`` on each
    stretch's first edge through its interior vertices to ``hi`` on its last."""
    out = []
    for i, st in enumerate(stretches):
        a0, t0 = polygon.starts[st[0]], polygon.tangents[st[0]]
        a1, t1 = polygon.starts[st[-1]], polygon.tangents[st[-1]]
        out.append(np.concatenate([[a0 + piece.lo[i] * t0], polygon.starts[list(st[1:])],
                                   [a1 + piece.hi[i] * t1]]))
    return out
