r"""The radius of the zero-force slice of three contacts' wrench hull from the slice
itself (theorem 3.1 in 6-D, :mod:`fcgrasp.spatial.triples`), without the 6-D hull.

**The slice as a 3-D polytope.**  The generators are three friction pyramids' edges,
``w_j = (f_j, m_j)``, each force of unit length.  The slice ``S = {m : (0, m) in W}`` is
the image under ``lambda -> sum lambda_j m_j`` of ``P = {lambda >= 0 : sum lambda_j f_j =
0, sum lambda_j = 1}``, four equations, so each vertex of ``S`` is the image of a vertex
of ``P`` with at most four generators in its support.  Written per contact (``y_i`` its
share of the force, in its pyramid ``K_i``), a vertex puts each ``y_i`` inside a face of
``K_i`` of dimension ``d_i`` (the apex 0, an edge 1, a side 2, the inside 3) with ``sum
d_i = 4`` where the pyramids are in general position; so the supports to read are two
adjacent edges of one pyramid with one edge of each other, two adjacent edges of two
pyramids, or three edges of one pyramid's fan triangulation with an edge of another
(:func:`pattern_table`, 2,016 of them against qhull's 6-D hull of 24 points).  A vertex
whose support is smaller (pyramids in special position, as on two parallel faces) is
read as the solution of a larger support from this table with zero weights (tested on
the faces of boxes, exactly opposite normals and seeded triples of every kind: the 6-D
hull's radius each time).  Every point kept is a point of ``S`` whatever the
conditioning (weights at least ``-tol``, the balance checked to ``tol``), so the radius
read from them never exceeds the slice's: a vertex missed could only lower it.

**The radius.**  ``delta`` is the inradius of ``S`` about the origin: the smallest
``b / |n_m|`` over the 6-D hull's facets ``n . w <= b`` equals the distance to the nearest
facet of ``S`` (a facet of ``W`` bounds ``S`` by ``n_m . m <= b``; a facet of ``S`` is cut
by a supporting hyperplane of ``W``, a positive combination of facets).  The 6-D hull's
rule that a facet with ``b <= HULL_ROUNDING * scale`` leaves no radius needs the 6-D
inradius ``rho``: ``rho >= r_S r_F / sqrt((r_S + M)^2 + r_F^2)`` from the slice's
inradius ``r_S``, the forces' ``r_F`` and the largest moment ``M`` (a unit direction
``(n_f, n_m)`` reaches ``|n_m| r_S`` in the slice and ``|n_f| r_F - |n_m| M`` over the
forces' ball).  Where that bound does not clear twice the rounding, or the loops do not
run, the 6-D hull decides (``None``).  ``r_S`` is read from the points' 3-D hull built
incrementally (qhull's where it does not close: flat points, slivers), ``r_F`` from the
forces' hull built the same way (a triple's refinement moves its contacts, not its
normals: once per triple); a triple's moves build their wrenches in the same compiled call
(:func:`slice_radius_at`, ``triples._generators``' numbers)."""

from __future__ import annotations

import math
from functools import cache

import numpy as np

from ..core._checks import FloatArray
from ..core.jit import CompiledLoops
from ..core.tolerances import HULL_ROUNDING, SLICE_WEIGHT_TOL
from . import _slice_kernels

_LOOPS = CompiledLoops.of_modules((_slice_kernels,))


@cache
def pattern_table(edges: int) -> np.ndarray:
    """The supports read (module docstring), four generator indices per row, for three
    pyramids of ``edges`` edges each, in the order of :func:`triples._generators`."""
    ids = [list(range(k * edges, (k + 1) * edges)) for k in range(3)]

    def sides(k: int) -> list[tuple[int, ...]]:
        return [(ids[k][a], ids[k][(a + 1) % edges]) for a in range(edges)]

    def fans(k: int) -> list[tuple[int, ...]]:
        return [(ids[k][0], ids[k][a], ids[k][a + 1]) for a in range(1, edges - 1)]

    rows: list[tuple[int, ...]] = []
    for i in range(3):
        j, k = (x for x in range(3) if x != i)
        rows += [(*s, a, b) for s in sides(i) for a in ids[j] for b in ids[k]]
    for i, j in ((0, 1), (0, 2), (1, 2)):
        rows += [(*s, *t) for s in sides(i) for t in sides(j)]
    for i in range(3):
        for j in range(3):
            if i != j:
                rows += [(*t, a) for t in fans(i) for a in ids[j]]
    return np.array(rows, dtype=np.int64)


def forces_radius(forces: FloatArray) -> float | None:
    """The inradius about the origin of the hull of the generators' ``forces`` (n, 3)
    (:func:`_hull_radius`); None where the loops do not run."""
    if not _LOOPS.available():
        return None
    points = np.ascontiguousarray(forces, dtype=float)
    ok, (closed, r_f) = _LOOPS.run("_hull_inradius", points, SLICE_WEIGHT_TOL)
    if not ok:
        return None
    return float(r_f) if closed else _hull_radius(points)


def _hull_radius(points: FloatArray) -> float:
    """The distance from the origin to the nearest facet plane of the hull of the 3-D
    ``points`` by qhull's hull (where the compiled one does not close): negative where
    the origin is outside, ``-inf`` where they are flat."""
    from scipy.spatial import ConvexHull, QhullError

    try:
        return float(np.min(-ConvexHull(points).equations[:, 3]))
    except (QhullError, ValueError):
        return -math.inf


def slice_radius_at(points: FloatArray, forces: FloatArray, forces_inradius: float | None,
                    least: float) -> tuple[float | None, float] | None:
    """:func:`slice_radius` of the generators of three contacts at ``points`` (3, 3)
    with the pyramids' unit ``forces`` (3, E, 3) (``triples._generators``' numbers,
    built in the compiled loop; moments over the contacts' reach, at least ``least``),
    and that reach; None where the loops do not run."""
    if not _LOOPS.available():
        return None
    forces = np.ascontiguousarray(forces, dtype=float)
    table = pattern_table(forces.shape[1])
    out = np.empty((table.shape[0], 3))
    ok, got = _LOOPS.run("_slice_at", np.ascontiguousarray(points, dtype=float), forces,
                         table, SLICE_WEIGHT_TOL, float(least), out)
    if not ok:
        return None
    *found, reach = got
    return _radius(tuple(found), forces.reshape(-1, 3), forces_inradius), float(reach)


def slice_radius(w: FloatArray, edges: int, forces_inradius: float | None = None
                 ) -> float | None:
    """The slice's radius less the rounding (``triples._hull_slice_radius``'s number), or
    None where the 6-D hull must decide (module docstring).  ``w`` (3 * edges, 6): the
    three pyramids' generators in order; ``forces_inradius``: :func:`forces_radius` of
    its forces, where the caller has it."""
    if not _LOOPS.available():
        return None
    w = np.ascontiguousarray(w, dtype=float)
    table = pattern_table(edges)
    out = np.empty((table.shape[0], 3))
    ok, got = _LOOPS.run("_slice_inradius", w, table, SLICE_WEIGHT_TOL, out)
    if not ok:
        return None
    return _radius(got, w[:, :3], forces_inradius)


def _radius(got: tuple[int, float, FloatArray, float, float], forces: FloatArray,
            forces_inradius: float | None) -> float | None:
    """The radius from ``_slice_inradius``'s answer ``got``, the 6-D hull's rounding
    rule applied (module docstring)."""
    status, r_s, points, scale, moment = got
    if status == 0:
        return 0.0                        # no 3-D slice: the origin is not inside
    if status == 2:                       # flat, or a sliver: qhull's 3-D hull decides
        r_s = _hull_radius(points)
    r_f = forces_radius(forces) if forces_inradius is None else forces_inradius
    if r_f is None:
        return None
    if r_s <= 0 or r_f <= 0:
        return 0.0
    rho = r_s * r_f / math.sqrt((r_s + moment) ** 2 + r_f ** 2)
    if rho <= 2 * HULL_ROUNDING * scale:
        return None
    return max(r_s - HULL_ROUNDING * scale, 0.0)
