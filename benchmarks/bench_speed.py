"""The table: real parts at interactive speed.  Each workload runs in a fresh
process (the package imported and numba's cache loaded before the clock starts, unless
the row is the start-up itself), timed in CPU seconds, beside its target and a baseline
measured in the same run:

* the searches: the previous implementation kept in the package (``FCGRASP_JIT=0``:
  the numpy stretch search, whose vertex matrix is ``m x m`` booleans; HiGHS for the
  programs of three fingers with friction and of four fingers' growth);
* the per-call rows: the LP a user would write (scipy's HiGHS);
* rows not reworked yet: no baseline, the row says so.

The search rows are timed with numba's cached code already loaded (a long-lived process:
the explorer, a batch worker); loading it costs a process once, its own row.

    python benchmarks/bench_speed.py [--quick] [--rows a,b,...]

``--quick`` leaves out the rows whose baseline takes minutes.  Prints a Markdown table.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

CHILD = r"""
import json, os, resource, sys, time
import numpy as np
import fcgrasp as fc
sys.path.insert(0, os.environ["FCGRASP_BENCH_DIR"])
from bench_closure import lp_closure      # the LP a user would write (the baseline)

def star(n, noise, seed=0):
    rng = np.random.default_rng(seed)
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 50 * (1 + 0.3 * np.sin(5 * a)) * (1 + noise * rng.standard_normal(n))
    return fc.Polygon(np.c_[r * np.cos(a), r * np.sin(a)])

def ellipse(n):
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return fc.Polygon(np.c_[60 * np.cos(a), 30 * np.sin(a)])

def blob(n):
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 50 + 8 * np.sin(3 * a) + 5 * np.cos(7 * a)
    return fc.Polygon(np.c_[r * np.cos(a), r * np.sin(a)])

def lp_regions(poly, e1, e2, mu):
    # the LP a user would write for the regions of two fingers on two edges (squeezing):
    # variables s1, e1, s2, e2 (arc positions of the region ends) and t; each region at
    # least t long; every pair of region corners inside both friction cones (the chord
    # within atan(mu) of each inward normal: two half-planes per cone, linear in the ends)
    from scipy.optimize import linprog
    beta = np.arctan(mu)
    A, B = poly.starts[[e1, e2]], poly.tangents[[e1, e2]]
    L = poly.lengths[[e1, e2]]
    f = -poly.normals[[e1, e2]]
    rot = lambda v, a: np.array([np.cos(a) * v[0] - np.sin(a) * v[1],
                                 np.sin(a) * v[0] + np.cos(a) * v[1]])
    cross = lambda g, d: g[0] * d[1] - g[1] * d[0]
    gens1 = [rot(f[0], -beta), -rot(f[0], beta)]
    gens2 = [-rot(f[1], -beta), rot(f[1], beta)]
    rows, rhs = [], []
    for i in (0, 1):            # X = A0 + x B0 with x = s1 or e1
        for j in (2, 3):        # Y = A1 + y B1 with y = s2 or e2
            for g in gens1 + gens2:
                # cross(g, Y - X) >= 0  ->  -cross(g, B1) y + cross(g, B0) x <= cross(g, A1 - A0)
                row = np.zeros(5)
                row[j] -= cross(g, B[1])
                row[i] += cross(g, B[0])
                rows.append(row)
                rhs.append(cross(g, A[1] - A[0]))
    rows += [[1, -1, 0, 0, 1], [0, 0, 1, -1, 1]]
    rhs += [0, 0]
    res = linprog([0, 0, 0, 0, -1], A_ub=rows, b_ub=rhs,
                  bounds=[(0, L[0])] * 2 + [(0, L[1])] * 2 + [(0, None)], method="highs")
    return -res.fun

def previous_kernels():
    # the previous compiled search, kept here as the baseline: every cell of each row's
    # window of angles read (the window scan), every row's windows widened, every edge's
    # single-edge windows read
    from fcgrasp.model.stretches import _kernels as K
    from fcgrasp.model.stretches import _rounds as Q
    windows, single = K.windows, Q._single
    K.vertex_runs_tree = K.vertex_runs_scan
    K.windows = lambda *a: windows(*a[:10])
    Q._single = lambda *a: single(*a[:6])

part_for = {"star1k": lambda: star(1000, 0.01), "ellipse10k": lambda: ellipse(10000),
            "blob100k": lambda: blob(100000), "star100k": lambda: star(100000, 0.001),
            "star10k": lambda: star(10000, 0.003), "blob10k": lambda: blob(10000),
            "blob1k": lambda: blob(1000), "blob3k": lambda: blob(3000)}

def run(row):
    if row in part_for:
        poly = part_for[row]()
        if os.environ.get("FCGRASP_JIT") != "0":   # warm: numba's cached code loaded
            os.environ["FCGRASP_JIT"] = "1"
            fc.plan(blob(40), fingers=2, mu=0.3, top=1)
            del os.environ["FCGRASP_JIT"]
        if os.environ.get("FCGRASP_BENCH_PREVIOUS"):
            previous_kernels()
        t0 = time.process_time()
        fc.plan(poly, fingers=2, mu=0.3, max_memory=16 * 10**9)
        return time.process_time() - t0
    if row == "numba":
        os.environ["FCGRASP_JIT"] = "1"
        t0 = time.process_time()
        fc.plan(blob(40), fingers=2, mu=0.3, top=1)
        return time.process_time() - t0
    if row == "single10k":
        poly = star(10000, 0.003)
        t0 = time.process_time()
        fc.plan(poly, fingers=2, mu=0.3, along_boundary=False)
        return time.process_time() - t0
    if row in ("jaw_cam", "jaw_washer"):
        poly = fc.read_part("demo:" + row.split("_")[1])
        jaw = fc.ParallelJaw(stroke=(5, 60), pad_width=8, mu=0.5)
        if os.environ.get("FCGRASP_JIT") != "0":   # warm: numba's cached code loaded
            fc.plan(fc.read_part("demo:triangle"), gripper=jaw, top=1)
        t0 = time.process_time()
        fc.plan(poly, gripper=jaw, top=5)
        return time.process_time() - t0
    if row in ("f3_200", "f3_cam"):
        poly = blob(200) if row == "f3_200" else fc.read_part("demo:cam")
        if os.environ.get("FCGRASP_JIT") != "0":   # warm: numba's cached code loaded
            fc.plan(blob(40), fingers=3, mu=0.3, top=1)
        t0 = time.process_time()
        fc.plan(poly, fingers=3, mu=0.3)
        return time.process_time() - t0
    if row == "f4_500":
        poly = blob(500)
        t0 = time.process_time()
        fc.plan(poly, fingers=4, along_boundary=False)
        return time.process_time() - t0
    if row == "f4_circle500":
        # a regular 500-gon, a flattened circle: every set of four edges ties on the
        # search's bound (the edge length), and every normal meets the centre
        a = np.linspace(0, 2 * np.pi, 500, endpoint=False)
        poly = fc.Polygon(np.c_[50 * np.cos(a), 50 * np.sin(a)])
        fc.plan(blob(12), fingers=4, along_boundary=False, top=1)   # numba's code loaded
        if os.environ.get("FCGRASP_BENCH_PREVIOUS"):
            # the previous search: every row streamed, no pairs of opposite edges
            from fcgrasp.pipeline._pair_rows import PairRows
            PairRows.applies = staticmethod(lambda *a, **k: False)
        t0 = time.process_time()
        fc.plan(poly, fingers=4, along_boundary=False)
        return time.process_time() - t0
    if row == "f4_100":
        poly = blob(100)
        if os.environ.get("FCGRASP_JIT") != "0":   # warm: numba's cached code loaded
            fc.plan(blob(12), fingers=4, top=1)
        t0 = time.process_time()
        fc.plan(poly, fingers=4)
        return time.process_time() - t0
    if row == "f4_blob":
        poly = fc.read_part("demo:blob")
        fc.plan(poly, fingers=4)
        t0 = time.perf_counter()
        for _ in range(5):
            fc.plan(poly, fingers=4)
        return (time.perf_counter() - t0) / 5
    if row in ("closure", "closure_lp"):
        rng = np.random.default_rng(0)
        grasps = []
        for _ in range(200):
            p, q = rng.random((2, 2)) * 10
            n1, n2 = rng.normal(size=(2, 2))
            grasps.append(fc.Grasp([fc.FrictionPoint(p, n1 / np.hypot(*n1), 0.5),
                                    fc.FrictionPoint(q, n2 / np.hypot(*n2), 0.5)]))
        ws = [g.wrenches for g in grasps]
        t0 = time.perf_counter()
        if row == "closure":
            for g in grasps:
                g.is_force_closure()
        else:
            for w in ws:
                lp_closure(np.asarray(w))
        return (time.perf_counter() - t0) / len(grasps)
    if row == "pairs1k":
        # the closed form of every pair of features of a 1,000-edge blob (algorithm 7.1's
        # largest smallest region and the better mode), one call, compiled unless
        # FCGRASP_JIT=0 (the numpy baseline)
        from fcgrasp.core.kernels import pair_scores
        from fcgrasp.core.tolerances import SOLVER_TOL
        from fcgrasp.pipeline._candidates import features

        if os.environ.get("FCGRASP_JIT") != "0":   # compiled, whatever the batch's size
            os.environ["FCGRASP_JIT"] = "1"
        F = features(blob(1000), 0.3)
        i, j = np.triu_indices(len(F.a), 1)
        i, j = i.astype(np.int64), j.astype(np.int64)
        margin = float(np.radians(0.5))
        pair_scores(F.a, F.b, F.center, F.half, i[:10], j[:10], margin, SOLVER_TOL)
        t0 = time.process_time()
        pair_scores(F.a, F.b, F.center, F.half, i, j, margin, SOLVER_TOL)
        return (time.process_time() - t0) / i.size
    if row in ("regions", "regions_lp"):
        sq = fc.Polygon([[0, 0], [10, 0], [10, 3], [0, 3]])
        n = 1000
        # a long-lived process: the kernels loaded (fc.compile_kernels(), as both README
        # commands run it; without it the first 200 calls run on Python floats, about
        # 40 us each, and the 200th loads them); the first call imports the planner
        fc.compile_kernels()
        fc.independent_regions(sq, (0, 2), mu=0.3)
        lp_regions(sq, 0, 2, 0.3)
        t0 = time.perf_counter()
        for _ in range(n):
            if row == "regions":
                fc.independent_regions(sq, (0, 2), mu=0.3)
            else:
                lp_regions(sq, 0, 2, 0.3)
        return (time.perf_counter() - t0) / n
    raise SystemExit(f"unknown row {row}")

print(json.dumps(run(sys.argv[1])))
"""

#: (key, workload, target, unit, baseline: how it is run or None)
ROWS = [
    ("star1k", "2 fingers along the boundary, noisy star, 1,000 edges", 0.1, "s", "jit0"),
    ("ellipse10k", "2 fingers along the boundary, ellipse, 10,000 edges", 0.5, "s", "jit0"),
    ("star10k", "2 fingers along the boundary, noisy star, 10,000 edges", 0.5, "s", "jit0"),
    ("blob10k", "2 fingers along the boundary, blob, 10,000 edges", 0.5, "s", "jit0"),
    ("blob100k", "2 fingers along the boundary, blob, 100,000 edges", 10.0, "s", "previous"),
    ("star100k", "2 fingers along the boundary, noisy star, 100,000 edges", 10.0, "s",
     "previous"),
    ("numba", "numba's start-up, once per process (import, cached code)", 0.5, "s", None),
    ("single10k", "2 fingers single-edge, noisy star, 10,000 edges", 0.3, "s", None),
    ("jaw_cam", "parallel jaw, `demo:cam`, top 5 (stroke 5-60, pads 8, mu 0.5)", 2.0, "s",
     "jit0"),
    ("jaw_washer", "parallel jaw, `demo:washer`", 0.2, "s", "jit0"),
    ("f3_200", "3 fingers with friction, 200-edge blob", 1.0, "s", "jit0"),
    ("f3_cam", "3 fingers with friction, `demo:cam`", 2.0, "s", "jit0"),
    ("f4_500", "4 fingers single-edge, smooth 500-edge blob", 5.0, "s", None),
    ("f4_circle500", "4 fingers single-edge, a regular 500-gon (every set of four edges "
     "ties on the bound)", 5.0, "s", "previous"),
    ("f4_100", "4 fingers along the boundary, 100-edge blob", 1.0, "s", "jit0"),
    ("f4_blob", "4 fingers, the six-edge blob, in process (wall)", 0.001, "s", None),
    ("pairs1k", "closed form per edge pair, all pairs of a 1,000-edge blob (CPU, one core)",
     10e-9, "s", "jit0"),
    ("closure", "`Grasp.is_force_closure()`, one grasp (wall)", 20e-6, "s", "closure_lp"),
    ("regions", "`independent_regions`, one edge pair (wall)", 20e-6, "s", "regions_lp"),
]

#: Rows whose baseline or workload takes minutes: left out by ``--quick``.
SLOW = {"star10k", "ellipse10k", "blob10k", "blob100k", "star100k", "jaw_cam", "jaw_washer",
        "f3_cam", "f4_500", "f4_circle500"}
#: CPU seconds after which a row's process is stopped (reported as stopped, not met).
LIMIT = 120.0


def measure(row: str, jit: str | None = None, previous: bool = False) -> float:
    """The row's figure, measured in a fresh process; inf where it was stopped after
    :data:`LIMIT` seconds."""
    env = dict(os.environ, FCGRASP_BENCH_DIR=os.path.dirname(os.path.abspath(__file__)))
    if jit is not None:
        env["FCGRASP_JIT"] = jit
    if previous:
        env["FCGRASP_BENCH_PREVIOUS"] = "1"
    try:
        out = subprocess.run([sys.executable, "-c", CHILD, row], capture_output=True,
                             text=True, env=env, timeout=LIMIT)
    except subprocess.TimeoutExpired:
        return float("inf")
    if out.returncode:
        raise SystemExit(f"row {row} failed:\n{out.stderr[-2000:]}")
    return float(json.loads(out.stdout.strip().splitlines()[-1]))


def startup() -> float:
    """``fcgrasp plan demo:blob`` as a process, wall seconds, median of 5."""
    times = []
    for _ in range(5):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "fcgrasp.apps.cli", "plan", "demo:blob"],
                       capture_output=True, check=True)
        times.append(time.perf_counter() - t0)
    return sorted(times)[2]


def fmt(x: float) -> str:
    if x == float("inf"):
        return f"stopped after {LIMIT:g} s"
    if x < 1e-6:
        return f"{x * 1e9:.1f} ns"
    return f"{x * 1e6:.1f} us" if x < 1e-3 else f"{x * 1e3:.1f} ms" if x < 0.1 else f"{x:.2f} s"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="leave out the minutes-long rows")
    ap.add_argument("--rows", default="", help="comma-separated row keys (default: all)")
    args = ap.parse_args()
    wanted = set(filter(None, args.rows.split(",")))
    print("| workload | target | now | baseline | baseline / now | met |")
    print("| --- | --- | --- | --- | --- | --- |")
    for key, name, target, _, base in ROWS:
        if (wanted and key not in wanted) or (args.quick and key in SLOW and not wanted):
            continue
        now = measure(key)
        if base == "jit0":
            b = measure(key, jit="0")
            label = ("HiGHS programs" if key[:2] in ("f3", "f4")
                     else "numpy pose model" if key.startswith("jaw")
                     else "numpy" if key == "pairs1k" else "numpy search")
        elif base == "previous":
            b = measure(key, previous=True)
            label = "the previous compiled search" if key != "f4_circle500" else \
                "every row streamed, no pairs"
        elif base:
            b = measure(base)
            label = "HiGHS LP"
        else:
            b, label = None, "not reworked"
        ratio = "-" if not b else f"> {LIMIT / now:.0f}x" if b == float("inf") \
            else f"{b / now:.1f}x"
        base_s = f"{fmt(b)} ({label})" if b else label
        print(f"| {name} | <= {fmt(target)} | {fmt(now)} | {base_s} | {ratio} | "
              f"{'yes' if now <= target else 'no'} |", flush=True)
    if not wanted or "exponent" in wanted:
        # the time exponent of the stretch search from 1,000 to 10,000 edges (blob)
        import math
        t1, t10 = measure("blob1k"), measure("blob10k")
        b1, b10 = (None, None) if args.quick else (measure("blob1k", "0"), measure("blob10k", "0"))
        e = math.log(t10 / t1, 10)
        base_s = f"{math.log(b10 / b1, 10):.2f} (numpy search)" if b1 else "(--quick)"
        print(f"| 2 fingers along the boundary, time exponent 1,000 -> 10,000 edges (blob) | "
              f"<= 1.2 | {e:.2f} ({fmt(t1)} -> {fmt(t10)}) | {base_s} | - | "
              f"{'yes' if e <= 1.2 else 'no'} |", flush=True)
    if not wanted or "startup" in wanted:
        s = startup()
        print(f"| `fcgrasp plan demo:blob` as a process (wall) | <= 150.0 ms | {fmt(s)} | - | - "
              f"| {'yes' if s <= 0.15 else 'no'} |")


if __name__ == "__main__":
    main()
