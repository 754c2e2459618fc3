"""The jaw's pose grid: which poses of a grid of closing angles and offsets hold, the
largest box of holding poses on it, and a box checked on a finer grid (part of
:mod:`fcgrasp.grippers.jaw`)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ...core._checks import FloatArray
from ...core.tolerances import TOL
from ...model.distinct import (
    box_images,
)
from ...model.polygon import Polygon
from . import _kernels
from ._poses import (
    CHECK_DENSITY,
    OFFSET_STEPS,
    POSE_BATCH,
    THETA_STEP_DEG,
    JawParameters,
    _grip_edges,
    _pose_args,
    jaw_poses,
)


def _box_scores(H: np.ndarray, dth: float, dc: float, radius: float, max_rows: int
                ) -> tuple[float, int, int, int, int]:
    """The largest box of True cells of the pose grid ``H`` (theta rows, cyclic; offset
    columns) by ``min(offset range, theta range * radius)``: ``(score, k0, k1, j0, j1)``
    with inclusive grid indices (``k1`` may pass the last row: it wraps).  By the
    compiled loop (:func:`._kernels.box_scores`) where it runs."""
    found = _kernels.box_scores(H, dth, dc, radius, max_rows) if _kernels.available() \
        else None
    return found if found is not None else _box_scores_numpy(H, dth, dc, radius, max_rows)


def _box_scores_numpy(H: np.ndarray, dth: float, dc: float, radius: float, max_rows: int
                      ) -> tuple[float, int, int, int, int]:
    """:func:`_box_scores` by numpy (the reference): for each first row ``k0``, the rows
    from it are AND-ed cumulatively and the longest run of True of every prefix is read
    off at once (run lengths by cumulative sums)."""
    K, M = H.shape
    best = (-1.0, 0, 0, 0, 0)
    span = np.arange(max_rows)
    for k0 in np.flatnonzero(H.any(axis=1)):
        acc = np.logical_and.accumulate(H[(k0 + span) % K], axis=0)
        alive = acc.any(axis=1)
        rows = int(np.argmin(alive)) if not alive.all() else max_rows
        acc = acc[:rows]
        count = np.cumsum(acc, axis=1)
        last_false = np.maximum.accumulate(np.where(acc, 0, count), axis=1)
        run = count - last_false                     # length of the run ending here
        length = run.max(axis=1)
        score = np.minimum((length - 1) * dc, np.arange(rows) * dth * radius)
        r = int(np.argmax(score))
        if score[r] > best[0]:
            end = int(np.argmax(run[r]))
            best = (float(score[r]), int(k0), int(k0 + r), end - int(length[r]) + 1, end)
    return best


def _clear_images(H: np.ndarray, theta: FloatArray, offset: FloatArray,
                  symmetries: list[tuple[str, float]], dth: float, offsets: FloatArray,
                  start: float = 0.0) -> None:
    """Clear from the pose grid ``H`` (rows every ``dth`` from angle ``start``, columns at
    ``offsets``) the poses inside the images of the box ``theta x offset`` under the
    part's symmetries (:func:`fcgrasp.model.distinct.part_symmetries`): a box found
    there would hold the part the same way, mirrored or turned."""
    K = H.shape[0]
    eps = TOL * float(offsets[-1] - offsets[0])      # rounding of the images' ends
    for t0, t1, c0, c1 in box_images((float(theta[0]), float(theta[1])),
                                      (float(offset[0]), float(offset[1])), symmetries):
        k_lo = int(math.ceil((t0 - start - TOL) / dth))
        k_hi = int(math.floor((t1 - start + TOL) / dth))
        j_lo = int(np.searchsorted(offsets, c0 - eps, side="left"))
        j_hi = int(np.searchsorted(offsets, c1 + eps, side="right"))
        if k_hi >= k_lo and j_hi > j_lo:
            H[np.arange(k_lo, k_hi + 1) % K, j_lo:j_hi] = False


def _measure(theta: tuple[float, float], offset: tuple[float, float], radius: float
             ) -> float:
    """The ranking measure of a box: ``min(c1 - c0, (t1 - t0) * radius)``."""
    return min(offset[1] - offset[0], (theta[1] - theta[0]) * radius)


def grid_anchor(polygon: Polygon) -> float:
    """The closing angle the pose grid starts from: three quarters of a grid step
    (:data:`THETA_STEP_DEG`) past the direction of the outward normal of the part's
    longest edge (the first of those within a relative 1e-9 of it, in the input order),
    so that the grid turns, moves and scales with the part, and the boxes found on a
    rotated, moved, scaled or renumbered part are its images.  (Edges tied by a
    symmetry of the part give grids that are images of each other.)  The offset keeps
    the rows off the pads' exact alignment with that edge, a kink of the holding set
    where a row of grid poses is a poor start for a box (on ``demo:triangle`` the top
    box came out 4 % smaller there); at three quarters every built-in part's top box
    is within 1 % of the exact set's largest (``tests/test_jaw.py``).

    >>> sq = Polygon([[0, 0], [10, 0], [10, 3], [0, 3]])
    >>> round(float(np.degrees(grid_anchor(sq))), 6)       # the long side's normal, on
    -89.625
    """
    L = np.where(polygon.usable, polygon.lengths, -np.inf)
    k = int(np.flatnonzero(L >= L.max() * (1 - TOL))[0])
    n = polygon.normals[k]
    return float(np.arctan2(n[1], n[0])) + 0.75 * np.radians(THETA_STEP_DEG)


def _grid(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None
          ) -> tuple[FloatArray, FloatArray, np.ndarray]:
    """The pose grid a grip's boxes are sought on: its closing angles (every
    :data:`THETA_STEP_DEG`, from the part's own direction, :func:`grid_anchor`), its
    offsets (:data:`OFFSET_STEPS` across the part and a pad) and whether each pose
    holds."""
    K = int(round(360 / THETA_STEP_DEG))
    thetas = grid_anchor(polygon) + np.arange(K, dtype=float) * (2 * np.pi / K)
    reach = polygon.radius + jaw.pad_width / 2
    offsets = np.linspace(-reach, reach, OFFSET_STEPS)
    return thetas, offsets, _pose_grid(polygon, jaw, margin, hole, thetas, offsets)


#: A part with more edges than this evaluates the pose grid in tiles (each tile's poses
#: meet only the edges near its strips); fewer, in large batches.
TILE_AFTER_EDGES = 64


#: Grid rows and columns of a tile.
TILE = (16, 20)


def _pose_grid(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None,
               thetas: np.ndarray, offsets: np.ndarray) -> np.ndarray:
    """Whether each pose of the grid ``thetas x offsets`` holds (K, M): by the compiled
    grid loop (:func:`._kernels.grid`, each pose reading the edges near its strip) where
    it runs, else by :func:`_pose_grid_batches`, the reference."""
    H = _compiled_grid(polygon, jaw, margin, hole, thetas, offsets)
    return H if H is not None else _pose_grid_batches(polygon, jaw, margin, hole, thetas,
                                                      offsets)


def _compiled_grid(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None,
                   thetas: FloatArray, offsets: FloatArray, details: bool = False) -> Any:
    """:func:`._kernels.grid` on the grip's edges (with ``details``, the edges each pad
    touches as the part's edges, -1 for none, as :func:`jaw_poses` gives them); None
    where the compiled loop does not run."""
    if not _kernels.available():
        return None
    ring = _grip_edges(polygon, hole)
    got = _kernels.grid(thetas, offsets, *_pose_args(polygon, jaw, margin, hole, ring),
                        details=details)
    if got is None or not details:
        return got
    H, opening, e_a, e_b = got
    ids = np.flatnonzero(ring)
    return H, opening, np.where(e_a >= 0, ids[e_a], -1), np.where(e_b >= 0, ids[e_b], -1)


def _pose_grid_batches(polygon: Polygon, jaw: JawParameters, margin: float,
                       hole: int | None, thetas: np.ndarray, offsets: np.ndarray
                       ) -> np.ndarray:
    """:func:`_pose_grid` by :func:`jaw_poses` in batches (tiles of the grid, each with
    the edges near its strips, on a part of many edges)."""
    K, M = thetas.size, offsets.size
    if polygon.n_edges <= TILE_AFTER_EDGES:
        tt, cc = np.meshgrid(thetas, offsets, indexing="ij")
        return np.concatenate([
            jaw_poses(polygon, jaw, tt.ravel()[i:i + POSE_BATCH], cc.ravel()[i:i + POSE_BATCH],
                      margin, hole).holds
            for i in range(0, tt.size, POSE_BATCH)]).reshape(K, M)
    H = np.zeros((K, M), dtype=bool)
    for k in range(0, K, TILE[0]):
        for j in range(0, M, TILE[1]):
            tt, cc = np.meshgrid(thetas[k:k + TILE[0]], offsets[j:j + TILE[1]], indexing="ij")
            H[k:k + TILE[0], j:j + TILE[1]] = jaw_poses(
                polygon, jaw, tt.ravel(), cc.ravel(), margin, hole).holds.reshape(tt.shape)
    return H


def _checked_box(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None,
                 th: FloatArray, off: FloatArray, dth: float, dc: float,
                 compiled_grid: bool = True
                 ) -> tuple[tuple[float, float], tuple[float, float],
                            tuple[float, float], tuple[list[int], list[int]]] | None:
    """Shrink a box by grid steps until every pose of a grid :data:`CHECK_DENSITY`
    times finer holds; returns ``(theta range, offset range, opening range, the edges
    each pad touches at those poses)`` or None.  The fine grid is evaluated by the
    compiled grid loop (:func:`._kernels.grid`) where it runs and ``compiled_grid``,
    else by :func:`jaw_poses` in batches (the reference: the same answer)."""
    (t0, t1), (c0, c1) = th, off
    for _ in range(4):
        if t1 < t0 or c1 < c0:
            return None
        nt = max(2, int(round((t1 - t0) / dth)) * CHECK_DENSITY + 1)
        nc = max(2, int(round((c1 - c0) / dc)) * CHECK_DENSITY + 1)
        held = _fine_grid(polygon, jaw, margin, hole, np.linspace(t0, t1, nt),
                          np.linspace(c0, c1, nc), compiled_grid)
        if held is not None:
            return ((t0, t1), (c0, c1), *held)
        t0, t1, c0, c1 = t0 + dth, t1 - dth, c0 + dc, c1 - dc
    return None


def _fine_grid(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None,
               thetas: FloatArray, offsets: FloatArray, compiled: bool = True
               ) -> tuple[tuple[float, float], tuple[list[int], list[int]]] | None:
    """The opening range over every pose of the grid ``thetas x offsets`` and the edges
    each pad touches there, or None where some pose does not hold: by the compiled grid
    loop (:func:`_compiled_grid`) where it runs and ``compiled``, else by
    :func:`jaw_poses` in batches, stopping at the first batch that fails (the
    reference)."""
    got = _compiled_grid(polygon, jaw, margin, hole, thetas, offsets, details=True) \
        if compiled else None
    if got is not None:
        holds, opening, e_a, e_b = got
        if not holds.all():
            return None
        return ((float(opening.min()), float(opening.max())),
                (sorted(set(e_a[e_a >= 0].tolist())), sorted(set(e_b[e_b >= 0].tolist()))))
    grid = np.meshgrid(thetas, offsets, indexing="ij")
    tt, cc = grid[0].ravel(), grid[1].ravel()
    lo, hi = np.inf, -np.inf
    edges: tuple[set[int], set[int]] = (set(), set())
    for i in range(0, tt.size, POSE_BATCH):
        r = jaw_poses(polygon, jaw, tt[i:i + POSE_BATCH], cc[i:i + POSE_BATCH], margin, hole)
        if not np.all(r.holds):
            return None
        lo, hi = min(lo, float(r.opening.min())), max(hi, float(r.opening.max()))
        edges[0].update(r.edge_a[r.edge_a >= 0].tolist())
        edges[1].update(r.edge_b[r.edge_b >= 0].tolist())
    return (lo, hi), (sorted(edges[0]), sorted(edges[1]))
