r"""Compiled loops of the zero-force slice of three contacts' wrench hull
(:mod:`fcgrasp.spatial.triples`): the slice's candidate vertices, their duplicates
dropped, and the inradius of a small 3-D point set.

Plain Python compiled by :mod:`fcgrasp.spatial._slice` (one namespace for every loop);
where they do not run, qhull's 6-D hull (``triples._hull_slice``) is the reference."""

from __future__ import annotations

from typing import Any

import numpy as np


def _slice_points(w: Any, table: Any, tol: float, out: Any) -> int:
    """The moments of the zero-force slice's candidate vertices, written to ``out``
    (P, 3); returns how many.  Each row of ``table`` names four generators of ``w``
    (n, 6); their weights ``x`` solve ``sum x_j f_j = 0, sum x_j = 1`` (Gaussian
    elimination with partial pivoting; a pivot below ``tol`` skips the row) and the
    point ``sum x_j m_j`` is kept where every weight is at least ``-tol`` and the
    balance holds to ``tol``: a point of the hull at zero force, whatever the
    conditioning of the solve."""
    n = 0
    M = np.empty((4, 5))
    x = np.empty(4)
    for r in range(table.shape[0]):
        for q in range(4):
            j = table[r, q]
            M[0, q], M[1, q], M[2, q], M[3, q] = w[j, 0], w[j, 1], w[j, 2], 1.0
        M[0, 4], M[1, 4], M[2, 4], M[3, 4] = 0.0, 0.0, 0.0, 1.0
        ok = True
        for col in range(4):
            piv, big = col, abs(M[col, col])
            for rr in range(col + 1, 4):
                if abs(M[rr, col]) > big:
                    piv, big = rr, abs(M[rr, col])
            if big < tol:
                ok = False
                break
            if piv != col:
                for cc in range(col, 5):
                    M[col, cc], M[piv, cc] = M[piv, cc], M[col, cc]
            for rr in range(col + 1, 4):
                fct = M[rr, col] / M[col, col]
                for cc in range(col, 5):
                    M[rr, cc] -= fct * M[col, cc]
        if not ok:
            continue
        feasible = True
        for col in range(3, -1, -1):
            s = M[col, 4]
            for cc in range(col + 1, 4):
                s -= M[col, cc] * x[cc]
            x[col] = s / M[col, col]
            if x[col] < -tol:
                feasible = False
                break
        if not feasible:
            continue
        fx, fy, fz, total, mx, my, mz = 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
        for q in range(4):
            j = table[r, q]
            fx += x[q] * w[j, 0]
            fy += x[q] * w[j, 1]
            fz += x[q] * w[j, 2]
            total += x[q]
            mx += x[q] * w[j, 3]
            my += x[q] * w[j, 4]
            mz += x[q] * w[j, 5]
        if abs(fx) > tol or abs(fy) > tol or abs(fz) > tol or abs(total - 1.0) > tol:
            continue
        out[n, 0], out[n, 1], out[n, 2] = mx, my, mz
        n += 1
    return n


def _distinct_points(pts: Any, n: int, tol: float) -> Any:
    """The indices of ``pts[:n]`` less those within ``tol`` (each coordinate) of one
    kept before, read in order of the first coordinate."""
    order = np.argsort(pts[:n, 0])
    keep = np.empty(n, np.int64)
    m = 0
    for a in range(n):
        i = order[a]
        dup = False
        b = m - 1
        while b >= 0:
            j = keep[b]
            if pts[i, 0] - pts[j, 0] > tol:
                break
            if abs(pts[i, 1] - pts[j, 1]) <= tol and abs(pts[i, 2] - pts[j, 2]) <= tol:
                dup = True
                break
            b -= 1
        if not dup:
            keep[m] = i
            m += 1
    return keep[:m]


def _inradius3(p: Any, tol: float) -> float:
    """The distance from the origin to the nearest facet plane of the hull of the 3-D
    points ``p`` (negative where the origin is outside; ``-inf`` where the points are
    flat), by every plane through three of them that has all on one side (within
    ``tol``): a few tens of points, the forces of three pyramids."""
    n = p.shape[0]
    best = np.inf
    found = False
    for a in range(n):
        for b in range(a + 1, n):
            ux, uy, uz = p[b, 0] - p[a, 0], p[b, 1] - p[a, 1], p[b, 2] - p[a, 2]
            for c in range(b + 1, n):
                vx, vy, vz = p[c, 0] - p[a, 0], p[c, 1] - p[a, 1], p[c, 2] - p[a, 2]
                nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
                length = (nx * nx + ny * ny + nz * nz) ** 0.5
                if length < tol:
                    continue
                nx, ny, nz = nx / length, ny / length, nz / length
                h = nx * p[a, 0] + ny * p[a, 1] + nz * p[a, 2]
                above = below = False
                for k in range(n):
                    d = nx * p[k, 0] + ny * p[k, 1] + nz * p[k, 2] - h
                    if d > tol:
                        above = True
                    elif d < -tol:
                        below = True
                    if above and below:
                        break
                if above and below:
                    continue
                if not below and not above:
                    continue                    # every point on the plane: flat
                found = True
                # the outward normal points away from the points: offset h or -h
                off = -h if above else h
                if off < best:
                    best = off
    return best if found else -np.inf
