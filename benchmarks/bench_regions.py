"""Speed of optimal independent regions and plans, against the LP baseline.

For each workload it prints fcgrasp's time, the time of the same optimum computed by
the linear program a user would write (region end points as variables, every corner
grasp of the box inside the shrunk cone, max-min length; scipy's HiGHS, one edge set at
a time; timed on a sample and scaled to the whole workload), the ratio, whether the
optima agree on the sample, and the issue's target.

    python benchmarks/bench_regions.py
"""

from __future__ import annotations

import time
from itertools import product

import numpy as np
from scipy.optimize import linprog

from fcgrasp import Polygon, plan
from fcgrasp.pipeline import candidates, grasp_geometry, plan_spec, region_levels

MARGIN = np.radians(0.5)


def blob(n: int) -> Polygon:
    """A smooth star-shaped part flattened to n edges."""
    ang = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 1 + 0.3 * np.sin(3 * ang) + 0.1 * np.cos(5 * ang + 1)
    return Polygon(np.column_stack([r * np.cos(ang), r * np.sin(ang)]) * 50.0)


def _meet(p1, f1, p2, f2):
    m = np.array([[f1[0], -f2[0]], [f1[1], -f2[1]]])
    s = np.linalg.solve(m, p2 - p1)
    return p1 + s[0] * f1


def lp_max_min(starts, ends, forces, side, k1, k2):
    """The baseline: max t s.t. every corner grasp has P34 - P12 in cone(k1, k2)."""
    n = len(starts)
    L = np.hypot(*(ends - starts).T)
    t = (ends - starts) / L[:, None]
    i12 = [i for i in range(n) if side[i] == 0]
    i34 = [i for i in range(n) if side[i] == 1]

    def pt(idx, par):
        pts = [starts[i] + par[j] * t[i] for j, i in enumerate(idx)]
        return pts[0] if len(idx) == 1 else _meet(pts[0], forces[idx[0]], pts[1], forces[idx[1]])

    def affine(idx):
        z = np.zeros(len(idx))
        o = pt(idx, z)
        return o, [pt(idx, np.eye(len(idx))[j]) - o for j in range(len(idx))]

    o12, d12 = affine(i12)
    o34, d34 = affine(i34)
    cr = lambda a, b: a[0] * b[1] - a[1] * b[0]  # noqa: E731
    nv = 2 * n + 1
    A, B = [], []
    for phi in (lambda x: cr(k1, x), lambda x: cr(x, k2)):
        for c12 in product((0, 1), repeat=len(i12)):
            for c34 in product((0, 1), repeat=len(i34)):
                row = np.zeros(nv)
                for j, i in enumerate(i12):
                    row[2 * i + c12[j]] += phi(d12[j])
                for j, i in enumerate(i34):
                    row[2 * i + c34[j]] -= phi(d34[j])
                A.append(row)
                B.append(phi(o34) - phi(o12))
    for i in range(n):
        row = np.zeros(nv)
        row[2 * i], row[2 * i + 1], row[-1] = 1, -1, 1
        A.append(row)
        B.append(0.0)
    c = np.zeros(nv)
    c[-1] = -1
    res = linprog(c, A_ub=np.array(A), b_ub=np.array(B),
                  bounds=[(0, L[i // 2]) for i in range(2 * n)] + [(None, None)], method="highs")
    return -res.fun if res.status == 0 else -1.0


def _dir(a):
    return np.array([np.cos(a), np.sin(a)])


def lp_candidate(c, r):
    """LP optimum (both modes) of candidate row r of a _Candidates batch."""
    n = c.feats.shape[1]
    perm = c.perm[r]
    a, b, cen = c.a[r][perm], c.b[r][perm], c.center[r][perm]
    f = np.stack([np.cos(cen), np.sin(cen)], axis=1)
    if n == 2:
        from fcgrasp.core.sectors import arc_intersection

        cc, hh = arc_intersection(cen[0], c.half[r][0], cen[1] + np.pi, c.half[r][1])
        side = [0, 1]
    else:
        from fcgrasp.core.sectors import arc_intersection

        g12 = (cen[1] - cen[0] + np.pi) % (2 * np.pi) - np.pi
        g34 = (cen[3] - cen[2] + np.pi) % (2 * np.pi) - np.pi
        cc, hh = arc_intersection(cen[0] + g12 / 2, abs(g12) / 2, cen[2] + g34 / 2 + np.pi,
                                  abs(g34) / 2)
        side = [0, 0, 1, 1]
    h = float(hh) - MARGIN
    if h <= 0:
        return -1.0
    k1, k2 = _dir(float(cc) - h), _dir(float(cc) + h)
    return max(lp_max_min(a, b, f, side, s * k1, s * k2) for s in (1, -1))


def timeit(fn, repeat=5):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main() -> None:
    rng = np.random.default_rng(0)
    rows = []

    # 1. regions for all edge pairs of a 200-edge polygon
    p200 = blob(200)
    spec2 = plan_spec(fingers=2, mu=0.5, margin=np.degrees(MARGIN), top=None)
    npairs = 200 * 199 // 2

    def stage1(part, spec):
        return [grasp_geometry(part, spec, batch) for batch in candidates(part, spec)][0]

    def all_regions(part, spec):
        c = stage1(part, spec)
        region_levels(c, np.flatnonzero(c.score > 0), spec)
        return c

    t, c2 = timeit(lambda: all_regions(p200, spec2))
    t_stage1, _ = timeit(lambda: stage1(p200, spec2))
    sample = rng.choice(len(c2.score), 60, replace=False)
    t0 = time.perf_counter()
    lp = np.array([lp_candidate(c2, r) for r in sample])
    t_lp = (time.perf_counter() - t0) / len(sample)
    agree = np.allclose(np.maximum(lp, 0), np.maximum(c2.score[sample], 0), rtol=1e-7, atol=1e-9)
    rows.append(("regions per edge pair (200-edge polygon)", t / npairs, t_lp, agree,
                 "<= 0.2 us"))
    rows.append(("  of which the smallest region alone", t_stage1 / npairs, t_lp, agree, ""))

    # 2. regions for all 4-tuples of a 20-edge polygon
    p20 = blob(20)
    spec4 = plan_spec(fingers=4, mu=0.0, margin=np.degrees(MARGIN), top=None)
    nquad = 4845

    def all_quads():
        c = stage1(p20, spec4)
        four = np.flatnonzero((c.feats[:, 0] != c.feats[:, 2]) & (c.score > 0))
        region_levels(c, four, spec4)
        return c

    t, c4 = timeit(all_quads, repeat=7)
    distinct = np.flatnonzero(c4.feats[:, 0] != c4.feats[:, 2])
    sample = rng.choice(distinct, min(40, distinct.size), replace=False)
    t0 = time.perf_counter()
    lp = np.array([lp_candidate(c4, r) for r in sample])
    t_lp = (time.perf_counter() - t0) / len(sample)
    agree = np.allclose(np.maximum(lp, 0), np.maximum(c4.score[sample], 0), rtol=1e-7, atol=1e-9)
    rows.append(("regions per 4-tuple (20-edge polygon)", t / nquad, t_lp, agree, "<= 20 us"))

    # 3-5. full plans
    for name, poly, fingers, mu, target in (
            ("four-finger plan, 6-edge blob", blob(6), 4, 0.0, "<= 2 ms"),
            ("two-finger plan, 1000-edge polygon", blob(1000), 2, 0.5, "<= 0.5 s"),
            ("four-finger plan, 40-edge polygon", blob(40), 4, 0.0, "<= 3 s")):
        # single-edge plans: the LP baseline is the single-edge optimum
        t, plans = timeit(lambda poly=poly, fingers=fingers, mu=mu: plan(
            poly, fingers=fingers, mu=mu, top=10, along_boundary=False),
                          repeat=3 if fingers == 4 and poly.n_edges > 10 else 5)
        cp = stage1(poly, plan_spec(fingers=fingers, mu=mu, margin=np.degrees(MARGIN),
                                    top=None))
        ncand = len(cp.score)
        sample = rng.choice(ncand, min(20, ncand), replace=False)
        t0 = time.perf_counter()
        lp = np.array([lp_candidate(cp, r) for r in sample])
        t_lp = (time.perf_counter() - t0) / len(sample) * ncand
        ok = (cp.feats[sample, 0] != cp.feats[sample, -2] if fingers == 4
              else np.ones(len(sample), bool))
        agree = np.allclose(np.maximum(lp[ok], 0), np.maximum(cp.score[sample][ok], 0),
                            rtol=1e-7, atol=1e-9)
        rows.append((name, t, t_lp, agree, target))

    print(f"{'workload':44s} {'fcgrasp':>12s} {'LP (HiGHS)':>12s} {'speed-up':>10s} "
          f"{'agree':>6s}  target")
    def fmt(x):
        if x < 1e-3:
            return f"{x * 1e6:.3g} us"
        return f"{x * 1e3:.3g} ms" if x < 1 else f"{x:.3g} s"

    for name, t, t_lp, agree, target in rows:
        print(f"{name:44s} {fmt(t):>12s} {fmt(t_lp):>12s} {t_lp / t:>9.0f}x "
              f"{str(agree):>6s}  {target}")


if __name__ == "__main__":
    main()
