r"""Compiled loops of the zero-force slice of three contacts' wrench hull
(:mod:`fcgrasp.spatial.triples`): the slice's candidate vertices, their duplicates
dropped, and the inradius of a 3-D point set's hull.

Plain Python compiled by :mod:`fcgrasp.spatial._slice` (one namespace for every loop);
where they do not run, qhull's 6-D hull (``triples._hull_slice``) is the reference."""

from __future__ import annotations

import math
from typing import Any

import numpy as np


def _slice_points(w: Any, table: Any, tol: float, out: Any) -> int:
    """The moments of the zero-force slice's candidate vertices, written to ``out``
    (P, 3); returns how many.  Each row of ``table`` names four generators of ``w``
    (n, 6); their weights ``x`` solve ``sum x_j f_j = 0, sum x_j = 1`` (Gaussian
    elimination with partial pivoting; a pivot below ``tol`` skips the row) and the
    point ``sum x_j m_j`` is kept where every weight is at least ``-tol`` and the
    balance holds to ``tol``: a point of the hull at zero force, whatever the
    conditioning of the solve.  Rows that share their first three generators with the
    row before (the table's runs of eight) share the elimination of those columns
    (the pivots and factors depend on them alone): the fourth column replays it, the
    same operations in the same order as a whole elimination."""
    n = 0
    M = np.empty((4, 5))
    x = np.empty(4)
    v = np.empty(4)
    piv_at = np.empty(3, np.int64)
    fct_at = np.empty((3, 4))
    prefix_ok = False
    for r in range(table.shape[0]):
        if r == 0 or table[r, 0] != table[r - 1, 0] or table[r, 1] != table[r - 1, 1] \
                or table[r, 2] != table[r - 1, 2]:
            # the first three columns and the right-hand side, eliminated
            for q in range(3):
                j = table[r, q]
                M[0, q], M[1, q], M[2, q], M[3, q] = w[j, 0], w[j, 1], w[j, 2], 1.0
            M[0, 4], M[1, 4], M[2, 4], M[3, 4] = 0.0, 0.0, 0.0, 1.0
            prefix_ok = True
            for col in range(3):
                piv, big = col, abs(M[col, col])
                for rr in range(col + 1, 4):
                    if abs(M[rr, col]) > big:
                        piv, big = rr, abs(M[rr, col])
                if big < tol:
                    prefix_ok = False
                    break
                piv_at[col] = piv
                if piv != col:
                    for cc in range(col, 5):
                        if cc != 3:
                            M[col, cc], M[piv, cc] = M[piv, cc], M[col, cc]
                for rr in range(col + 1, 4):
                    fct = M[rr, col] / M[col, col]
                    fct_at[col, rr] = fct
                    for cc in range(col, 5):
                        if cc != 3:
                            M[rr, cc] -= fct * M[col, cc]
        if not prefix_ok:
            continue
        j = table[r, 3]
        v[0], v[1], v[2], v[3] = w[j, 0], w[j, 1], w[j, 2], 1.0
        for col in range(3):
            piv = piv_at[col]
            if piv != col:
                v[col], v[piv] = v[piv], v[col]
            for rr in range(col + 1, 4):
                v[rr] -= fct_at[col, rr] * v[col]
        if abs(v[3]) < tol:
            continue
        feasible = True
        for col in range(3, -1, -1):
            s = M[col, 4]
            for cc in range(col + 1, 4):
                s -= (v[col] if cc == 3 else M[col, cc]) * x[cc]
            x[col] = s / (v[3] if col == 3 else M[col, col])
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


def _slice_inradius(w: Any, table: Any, tol: float, out: Any) -> Any:
    """The slice's inradius from its candidate vertices (:func:`_slice_points`, their
    duplicates dropped, :func:`_hull_inradius`), in one call: ``(status, r_s, points,
    scale, moment)``, status 0 where fewer than four distinct points are found (no 3-D
    slice), 1 with the radius ``r_s``, 2 where the hull of the distinct ``points`` does
    not close; ``scale`` and ``moment`` the largest generator and moment lengths."""
    scale = moment = 0.0
    for j in range(w.shape[0]):
        mm = w[j, 3] * w[j, 3] + w[j, 4] * w[j, 4] + w[j, 5] * w[j, 5]
        ff = w[j, 0] * w[j, 0] + w[j, 1] * w[j, 1] + w[j, 2] * w[j, 2]
        scale = max(scale, (ff + mm) ** 0.5)
        moment = max(moment, mm ** 0.5)
    n = _slice_points(w, table, tol, out)
    keep = _distinct_points(out, n, tol)
    pts = np.empty((keep.shape[0], 3))
    for a in range(keep.shape[0]):
        for k in range(3):
            pts[a, k] = out[keep[a], k]
    if pts.shape[0] < 4:
        return 0, 0.0, pts, scale, moment
    closed, r = _hull_inradius(pts, tol)
    return (1 if closed else 2), r, pts, scale, moment


def _slice_at(points: Any, forces: Any, table: Any, tol: float, least: float,
              out: Any) -> Any:
    """:func:`_slice_inradius` of the generators of three contacts at ``points`` (3, 3)
    with the pyramids' unit ``forces`` (3, E, 3), built as ``triples._generators``
    builds them (moments about the points' mean over their reach, at least ``least``),
    with the reach: ``(status, r_s, points, scale, moment, reach)``."""
    E = forces.shape[1]
    w = np.empty((3 * E, 6))
    cx = (points[0, 0] + points[1, 0] + points[2, 0]) / 3.0
    cy = (points[0, 1] + points[1, 1] + points[2, 1]) / 3.0
    cz = (points[0, 2] + points[1, 2] + points[2, 2]) / 3.0
    arm = np.empty((3, 3))
    reach = 0.0
    for i in range(3):
        arm[i, 0], arm[i, 1], arm[i, 2] = points[i, 0] - cx, points[i, 1] - cy, \
            points[i, 2] - cz
        reach = max(reach, math.sqrt(arm[i, 0] * arm[i, 0] + arm[i, 1] * arm[i, 1]
                                     + arm[i, 2] * arm[i, 2]))
    unit = max(reach, least)
    for i in range(3):
        a0, a1, a2 = arm[i, 0], arm[i, 1], arm[i, 2]
        for e in range(E):
            b0, b1, b2 = forces[i, e, 0], forces[i, e, 1], forces[i, e, 2]
            j = i * E + e
            w[j, 0], w[j, 1], w[j, 2] = b0, b1, b2
            w[j, 3] = (a1 * b2 - a2 * b1) / unit
            w[j, 4] = (a2 * b0 - a0 * b2) / unit
            w[j, 5] = (a0 * b1 - a1 * b0) / unit
    status, r, pts, scale, moment = _slice_inradius(w, table, tol, out)
    return status, r, pts, scale, moment, reach


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


def _hull_inradius(p: Any, tol: float) -> Any:
    """The hull of the 3-D points ``p`` by the incremental method (the faces a new point
    sees replaced by a fan to their horizon; a point within ``tol`` of the hull left
    out; the points read farthest from the first tetrahedron's centre first), and the
    distance from the origin to its nearest face plane: ``(status, r)``, status 1 when
    the faces close (each edge once each way) and every point lies behind every face
    (within ``tol``): then they are the hull; 0 otherwise (flat points, or rounding
    that broke the faces)."""
    n = p.shape[0]
    if n < 4:
        return 0, 0.0
    first = _tetrahedron(p, tol)
    if first[0] < 0:
        return 0, 0.0
    cap = 16 * n + 64
    F = np.empty((cap, 3), np.int64)
    plane = np.empty((cap, 4))
    inner = np.zeros(3)
    for q in range(4):
        for k in range(3):
            inner[k] += p[first[q], k] / 4
    count = 0
    for f0, f1, f2 in ((0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)):
        if not _add_face(p, F, plane, count, first[f0], first[f1], first[f2], inner, tol):
            return 0, 0.0
        count += 1
    far = np.empty(n)
    for i in range(n):
        dx, dy, dz = p[i, 0] - inner[0], p[i, 1] - inner[1], p[i, 2] - inner[2]
        far[i] = -(dx * dx + dy * dy + dz * dz)
    order = np.argsort(far)
    edges = np.empty((3 * cap, 2), np.int64)
    for o in range(n):
        i = order[o]
        if i == first[0] or i == first[1] or i == first[2] or i == first[3]:
            continue
        m = 0
        f = 0
        while f < count:                # the faces seen, each moved out of the list
            if plane[f, 0] * p[i, 0] + plane[f, 1] * p[i, 1] + plane[f, 2] * p[i, 2] \
                    - plane[f, 3] > tol:
                for e in range(3):
                    edges[m, 0], edges[m, 1] = F[f, e], F[f, (e + 1) % 3]
                    m += 1
                count -= 1
                for k in range(3):
                    F[f, k] = F[count, k]
                for k in range(4):
                    plane[f, k] = plane[count, k]
            else:
                f += 1
        for e in range(m):              # the horizon: edges whose reverse was not seen
            u, v = edges[e, 0], edges[e, 1]
            shared = False
            for g in range(m):
                if edges[g, 0] == v and edges[g, 1] == u:
                    shared = True
                    break
            if not shared:
                if count >= cap or not _add_face(p, F, plane, count, u, v, i, inner, tol):
                    return 0, 0.0
                count += 1
    # closed: each directed edge of a face once, and its reverse once
    seen = np.zeros(n * n, np.int32)
    for f in range(count):
        for e in range(3):
            seen[F[f, e] * n + F[f, (e + 1) % 3]] += 1
    for f in range(count):
        for e in range(3):
            u, v = F[f, e], F[f, (e + 1) % 3]
            if seen[u * n + v] != 1 or seen[v * n + u] != 1:
                return 0, 0.0
    r = np.inf
    for f in range(count):
        for i in range(n):
            if plane[f, 0] * p[i, 0] + plane[f, 1] * p[i, 1] + plane[f, 2] * p[i, 2] \
                    - plane[f, 3] > tol:
                return 0, 0.0
        r = min(r, plane[f, 3])
    return 1, r


def _tetrahedron(p: Any, tol: float) -> Any:
    """Four points of ``p`` spanning space: the extremes along x, the farthest from
    their line, the farthest from their plane; -1 in the first place where the points
    are flat (within ``tol``)."""
    n = p.shape[0]
    out = np.full(4, -1, np.int64)
    a = b = 0
    for i in range(n):
        if p[i, 0] < p[a, 0]:
            a = i
        if p[i, 0] > p[b, 0]:
            b = i
    ux, uy, uz = p[b, 0] - p[a, 0], p[b, 1] - p[a, 1], p[b, 2] - p[a, 2]
    c, best = -1, tol
    for i in range(n):
        vx, vy, vz = p[i, 0] - p[a, 0], p[i, 1] - p[a, 1], p[i, 2] - p[a, 2]
        cx, cy, cz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
        d = (cx * cx + cy * cy + cz * cz) ** 0.5
        if d > best:
            c, best = i, d
    if c < 0:
        return out
    vx, vy, vz = p[c, 0] - p[a, 0], p[c, 1] - p[a, 1], p[c, 2] - p[a, 2]
    nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
    length = (nx * nx + ny * ny + nz * nz) ** 0.5
    nx, ny, nz = nx / length, ny / length, nz / length
    d, best = -1, tol
    for i in range(n):
        h = abs(nx * (p[i, 0] - p[a, 0]) + ny * (p[i, 1] - p[a, 1])
                + nz * (p[i, 2] - p[a, 2]))
        if h > best:
            d, best = i, h
    if d >= 0:
        out[0], out[1], out[2], out[3] = a, b, c, d
    return out


def _add_face(p: Any, F: Any, plane: Any, at: int, i: int, j: int, k: int, inner: Any,
              tol: float) -> bool:
    """Write the face ``(i, j, k)`` at ``at``, turned so that its normal points away
    from ``inner`` (a point inside the hull), with its unit normal and offset; False
    for a sliver (its sides' cross product within ``tol``)."""
    ux, uy, uz = p[j, 0] - p[i, 0], p[j, 1] - p[i, 1], p[j, 2] - p[i, 2]
    vx, vy, vz = p[k, 0] - p[i, 0], p[k, 1] - p[i, 1], p[k, 2] - p[i, 2]
    nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
    length = (nx * nx + ny * ny + nz * nz) ** 0.5
    if not length > tol:
        return False
    nx, ny, nz = nx / length, ny / length, nz / length
    h = nx * p[i, 0] + ny * p[i, 1] + nz * p[i, 2]
    if nx * inner[0] + ny * inner[1] + nz * inner[2] > h:
        F[at, 0], F[at, 1], F[at, 2] = i, k, j
        nx, ny, nz, h = -nx, -ny, -nz, -h
    else:
        F[at, 0], F[at, 1], F[at, 2] = i, j, k
    plane[at, 0], plane[at, 1], plane[at, 2], plane[at, 3] = nx, ny, nz, h
    return True
