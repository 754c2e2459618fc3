"""Independent formulation of the optimal regions: an LP over the region end points in
which every corner grasp of the box of regions lies inside the shrunk cone (HiGHS).

It shares no code with fcgrasp.model.regions: corner points are computed directly from the
edges, lines of force are intersected by solving 2x2 systems, and the leximin order is
obtained by solving one LP per stage.
"""

from __future__ import annotations

from itertools import product

import numpy as np

from ._highs import linprog


def _meet(p1, f1, p2, f2):
    m = np.array([[f1[0], -f2[0]], [f1[1], -f2[1]]])
    s = np.linalg.solve(m, p2 - p1)
    return p1 + s[0] * f1


def region_lp(starts, ends, forces, side, k1, k2, same_edge=(), order=None):
    """Leximin regions by LP stages.

    starts, ends: (n, 2) edges (a fixed point has start == end); forces: (n, 2) finger
    force directions (only used to intersect lines when two fingers share a side);
    side: (n,) 0 for P12, 1 for P34; k1, k2: the shrunk cone's edges (P34 - P12 inside).
    same_edge: pairs (i, j) of fingers on one edge; order gives which is below.
    Returns lengths (n,) sorted as the fingers, or None when infeasible.
    """
    starts, ends = np.asarray(starts, float), np.asarray(ends, float)
    n = len(starts)
    L = np.hypot(*(ends - starts).T)
    active = L > 0
    t = np.where(L[:, None] > 0, (ends - starts) / np.where(L > 0, L, 1)[:, None], 0)
    idx12 = [i for i in range(n) if side[i] == 0]
    idx34 = [i for i in range(n) if side[i] == 1]

    def point_of(side_idx, params):
        pts = [starts[i] + params[j] * t[i] for j, i in enumerate(side_idx)]
        if len(side_idx) == 1:
            return pts[0]
        return _meet(pts[0], forces[side_idx[0]], pts[1], forces[side_idx[1]])

    # affine maps: P(side) = o + sum_j params_j * d_j, evaluated numerically
    def affine(side_idx):
        z = np.zeros(len(side_idx))
        o = point_of(side_idx, z)
        cols = []
        for j in range(len(side_idx)):
            e = z.copy()
            e[j] = 1.0
            cols.append(point_of(side_idx, e) - o)
        return o, cols

    o12, d12 = affine(idx12)
    o34, d34 = affine(idx34)
    cr = lambda a, b: a[0] * b[1] - a[1] * b[0]  # noqa: E731
    # variables: lo_0, hi_0, ..., lo_{n-1}, hi_{n-1}, t
    nv = 2 * n + 1
    a_ub, b_ub = [], []
    for phi in (lambda x: cr(k1, x), lambda x: cr(x, k2)):
        for c12 in product((0, 1), repeat=len(idx12)):
            for c34 in product((0, 1), repeat=len(idx34)):
                row = np.zeros(nv)
                # phi(P12) - phi(P34) <= phi(o34) - phi(o12)
                for j, i in enumerate(idx12):
                    row[2 * i + c12[j]] += phi(d12[j])
                for j, i in enumerate(idx34):
                    row[2 * i + c34[j]] -= phi(d34[j])
                a_ub.append(row)
                b_ub.append(phi(o34) - phi(o12))
    for i in range(n):
        row = np.zeros(nv)
        row[2 * i], row[2 * i + 1] = 1, -1          # lo <= hi
        a_ub.append(row)
        b_ub.append(0.0)
    for (i, j) in same_edge:
        lo_i, hi_i, lo_j, hi_j = 2 * i, 2 * i + 1, 2 * j, 2 * j + 1
        row = np.zeros(nv)
        if order == (i, j):
            row[hi_i], row[lo_j] = 1, -1
        else:
            row[hi_j], row[lo_i] = 1, -1
        a_ub.append(row)
        b_ub.append(0.0)
    bounds = []
    for i in range(n):
        bounds += [(0, L[i]), (0, L[i])]
    bounds.append((None, None))
    fixed = {}
    lengths = np.zeros(n)
    free = [i for i in range(n) if active[i]]
    while free:
        A = [r.copy() for r in a_ub]
        B = list(b_ub)
        for i in range(n):
            if not active[i]:
                continue
            row = np.zeros(nv)
            row[2 * i], row[2 * i + 1] = 1, -1
            if i in fixed:
                A.append(row)
                B.append(-fixed[i])
            else:
                row[-1] = 1                               # t <= hi - lo
                A.append(row)
                B.append(0.0)
        c = np.zeros(nv)
        c[-1] = -1
        res = linprog(c, A_ub=np.array(A), b_ub=np.array(B), bounds=bounds, method="highs")
        if res.status != 0:
            return None
        tval = -res.fun
        if not fixed and tval < 0:
            return None
        # fix the free regions that cannot exceed tval
        blocked = []
        for i in free:
            c2 = np.zeros(nv)
            c2[2 * i], c2[2 * i + 1] = 1, -1             # minimise lo - hi
            A2, B2 = [r.copy() for r in A], list(B)
            for j in free:
                row = np.zeros(nv)
                row[2 * j], row[2 * j + 1] = 1, -1
                A2.append(row)
                B2.append(-tval)
            r2 = linprog(c2, A_ub=np.array(A2), b_ub=np.array(B2),
                         bounds=bounds[:-1] + [(None, None)], method="highs")
            if r2.status != 0 or -r2.fun <= tval + 1e-9 * max(L.max(), 1e-300):
                blocked.append(i)
        if not blocked:
            blocked = list(free)
        for i in blocked:
            fixed[i] = tval
            lengths[i] = tval
        free = [i for i in free if i not in blocked]
    return lengths


# ----------------------------------------------------------------------------- grasps


def grasp_wrenches(points, normals, mu):
    """Unit contact wrenches of point fingers, written without fcgrasp: a frictionless
    finger pushes along ``-n``; one with friction along the two edges of its cone,
    ``-n`` turned by ``+-atan(mu)``.  Torques about the grasp's centre, over its spread.
    """
    points, normals = np.asarray(points, float), np.asarray(normals, float)
    c = points.mean(axis=0)
    spread = max(float(np.max(np.hypot(*(points - c).T))), 1e-300)
    rows = []
    for p, n in zip(points, normals, strict=True):
        f = -n / np.hypot(*n)
        angles = (0.0,) if mu == 0 else (np.arctan(mu), -np.arctan(mu))
        for a in angles:
            g = np.array([np.cos(a) * f[0] - np.sin(a) * f[1],
                          np.sin(a) * f[0] + np.cos(a) * f[1]])
            r = (p - c) / spread
            rows.append([g[0], g[1], r[0] * g[1] - r[1] * g[0]])
    return np.array(rows)


def closure_margin_lp(wrenches):
    """How strictly the wrenches positively span their space (the plane's, 3-D; a
    solid's, 6-D) (HiGHS).

    max t  s.t.  sum_i l_i w_i = 0,  sum_i l_i = 1,  l_i >= t, with the unit wrenches;
    a grasp is force closure iff t > 0 and the wrenches have full rank.  Returns t; 0 (a
    tie, the limit of closure grasps at best) for a lower rank; -1 when the LP is
    infeasible.
    """
    w = np.asarray(wrenches, float)
    w = w / np.linalg.norm(w, axis=1)[:, None]
    k, d = w.shape
    if np.linalg.matrix_rank(w, tol=1e-10) < d:
        return 0.0
    c = np.zeros(k + 1)
    c[-1] = -1.0
    a_eq = np.zeros((d + 1, k + 1))
    a_eq[:d, :k] = w.T
    a_eq[d, :k] = 1.0
    b_eq = np.r_[np.zeros(d), 1.0]
    a_ub = np.hstack([-np.eye(k), np.ones((k, 1))])
    res = linprog(c, A_ub=a_ub, b_ub=np.zeros(k), A_eq=a_eq, b_eq=b_eq,
                  bounds=[(0, None)] * k + [(None, None)], method="highs")
    return float(-res.fun) if res.status == 0 else -1.0
