"""Scale: every row of the issue's table, new against old, each run in a fresh
process (seconds of the call, peak resident memory of the process).

*new* is what a user gets: ``fc.plan(...)``, whose single-edge search is the exact branch
and bound of :func:`fcgrasp.pipeline.search`.  *old* is every candidate row solved and
ranked (``rank(part, spec, (solve(part, spec, b) for b in candidates(part, spec)))``, the
search before the branch and bound), measured with ``--old``; without it, and for rows
that cannot run at all, the figure recorded in the issue is printed, marked "(issue)".
The parts are the star-shaped blob of ``bench_regions.py`` flattened to n edges.

    python benchmarks/bench_search.py [--old] [--quick]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

CHILD = r"""
import json, resource, sys, time
import numpy as np
import fcgrasp as fc
from fcgrasp.pipeline import candidates, plan_spec, rank, solve
job = json.loads(sys.argv[1])
n = job["n"]
ang = np.linspace(0, 2 * np.pi, n, endpoint=False)
r = 1 + 0.3 * np.sin(3 * ang) + 0.1 * np.cos(5 * ang + 1)
part = fc.Polygon(np.column_stack([r * np.cos(ang), r * np.sin(ang)]) * 50.0)
kw = dict(fingers=job["fingers"], mu=job.get("mu", 0.0), top=job.get("top", 10))
if "gravity" in job:
    kw["gravity"] = tuple(job["gravity"])
if "max_memory" in job:
    kw["max_memory"] = job["max_memory"]
reps = job.get("repeat", 1)
times = []
for _ in range(reps):
    t0 = time.perf_counter()
    if job["how"] == "old":
        spec = plan_spec(**kw, along_boundary=False, max_memory=2 ** 34)
        plans = rank(part, spec, (solve(part, spec, b) for b in candidates(part, spec)))
    elif job["how"] == "boundary":
        plans = fc.plan(part, **kw)
    else:
        plans = fc.plan(part, **kw, along_boundary=False)
    times.append(time.perf_counter() - t0)
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
print(json.dumps({"seconds": sorted(times)[len(times) // 2], "peak_mb": peak,
                  "plans": len(plans), "best": plans[0].min_length if plans else None}))
"""

KERNEL = r"""
import json, time
import numpy as np
import fcgrasp as fc
from fcgrasp.core import kernels
from fcgrasp.pipeline import EdgeSets, features, grasp_geometry, plan_spec, region_levels
n = 200
ang = np.linspace(0, 2 * np.pi, n, endpoint=False)
r = 1 + 0.3 * np.sin(3 * ang) + 0.1 * np.cos(5 * ang + 1)
part = fc.Polygon(np.column_stack([r * np.cos(ang), r * np.sin(ang)]) * 50.0)
spec = plan_spec(fingers=2, mu=0.5, top=None)
i, j = np.triu_indices(n, 1)
sets = EdgeSets(np.stack([i, j], axis=1))
F = features(part, 0.5)
best = [np.inf, np.inf, np.inf]
for _ in range(7):   # the first run loads numba and its cache (FCGRASP_JIT=1)
    t0 = time.perf_counter()
    kernels.pair_scores(F.a, F.b, F.center, F.half, i, j, spec.margin_rad)
    t1 = time.perf_counter()
    c = grasp_geometry(part, spec, sets)
    t2 = time.perf_counter()
    region_levels(c, np.arange(len(c.score)), spec)
    t3 = time.perf_counter()
    best = [min(best[0], t1 - t0), min(best[1], t2 - t1), min(best[2], t3 - t1)]
print(json.dumps({"kernel": best[0] / i.size, "smallest": best[1] / i.size,
                  "levels": best[2] / i.size}))
"""

#: (workload, job, issue's old figure, target)
ROWS = [
    ("two-finger plan, 10,000 edges (single edges)",
     dict(n=10_000, fingers=2, mu=0.3, top=10), "18-20 s, 574-855 MB", "<= 1 s, <= 300 MB"),
    ("two-finger plan, 10,000 edges (along the boundary)",
     dict(n=10_000, fingers=2, mu=0.3, top=10, how="boundary"), "", "<= 1 s, <= 300 MB"),
    ("two-finger plan, 10,000 edges (along the boundary, --max-memory 64G)",
     dict(n=10_000, fingers=2, mu=0.3, top=10, how="boundary", max_memory=2 ** 36), "",
     "<= 1 s, <= 300 MB"),
    ("four-finger plan, 60 edges", dict(n=60, fingers=4), "7.5 s, 975 MB", ""),
    ("four-finger plan, 100 edges", dict(n=100, fingers=4), "74 s, 6.3 GB", "<= 2 s"),
    ("four-finger plan, 500 edges", dict(n=500, fingers=4), "impossible (2.6e9 tuples)",
     "<= 60 s, <= 1 GB"),
    ("three-finger plan, 200 edges (frictionless, gravity)",
     dict(n=200, fingers=3, gravity=(0.0, -1.0)), "197 s", "<= 5 s"),
    ("three-finger plan, 200 edges (friction mu = 0.5)", dict(n=200, fingers=3, mu=0.5),
     "", ""),
    ("four-finger plan of the six-edge blob", dict(n=6, fingers=4, repeat=21), "13 ms",
     "<= 1 ms"),
]
#: rows whose old way is run with --old (the others would take minutes to hours)
OLD_FEASIBLE = {"two-finger plan, 10,000 edges (single edges)", "four-finger plan, 60 edges",
                "four-finger plan of the six-edge blob"}


def run(job: dict) -> dict | str:
    out = subprocess.run([sys.executable, "-c", CHILD, json.dumps(job)], capture_output=True,
                         text=True)
    if out.returncode:
        last = out.stderr.strip().splitlines()[-1]
        return "refused: " + last.split("would need")[1].split(",")[0].strip() \
            if "SearchTooLarge" in last else last[:90]
    return json.loads(out.stdout.strip().splitlines()[-1])


def fmt(d: dict | str) -> str:
    if isinstance(d, str):
        return d
    t = d["seconds"]
    ts = f"{t * 1e3:.3g} ms" if t < 1 else f"{t:.3g} s"
    return f"{ts}, {d['peak_mb']:.0f} MB"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--old", action="store_true", help="also time every row solved")
    ap.add_argument("--quick", action="store_true",
                    help="skip the rows of a minute (500 edges, 10,000 along the boundary)")
    args = ap.parse_args()
    print("| workload | old | new | target |")
    print("| --- | --- | --- | --- |")
    for name, job, issue_old, target in ROWS:
        if args.quick and (job["n"] == 500 or "max_memory" in job):
            continue
        new = run(dict(job, how=job.get("how", "single")))
        old = f"{issue_old} (issue)" if issue_old else ""
        if args.old and name in OLD_FEASIBLE:
            old = fmt(run(dict(job, how="old")))
        print(f"| {name} | {old} | {fmt(new)} | {target} |", flush=True)
    for n, reps in ((6, 5), (100, 1)):
        grown = run(dict(n=n, fingers=4, repeat=reps, how="boundary"))
        print(f"| four-finger plan, {n} edges, grown along the boundary (the default) | | "
              f"{fmt(grown)} | |", flush=True)
    for jit, label in (("1", "compiled (numba)"), ("0", "numpy, FCGRASP_JIT=0")):
        env = dict(os.environ, FCGRASP_JIT=jit)
        k = json.loads(subprocess.run([sys.executable, "-c", KERNEL], capture_output=True,
                                      text=True, check=True, env=env).stdout)
        old = "450-630 ns (1,000 ns with leximin levels) (issue)" if jit == "1" else ""
        print(f"| closed-form region per edge pair (batched, 200 edges), {label} | {old} | "
              f"{k['kernel'] * 1e9:.0f} ns ({k['smallest'] * 1e9:.0f} ns with the problems "
              f"of the pairs that hold, {k['levels'] * 1e9:.0f} ns with leximin levels) | "
              f"{'<= 60 ns' if jit == '1' else '(for comparison)'} |", flush=True)
    # as installed: modules read from their bytecode cache (a first run writes it, even
    # where the environment asks Python not to, as some sandboxes do)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    times = []
    for _ in range(6):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "fcgrasp", "plan", "demo:blob", "--quiet"],
                       check=True, capture_output=True, env=env)
        times.append(time.perf_counter() - t0)
    times = times[1:]
    print(f"| `fcgrasp plan demo:blob` as a process | about 0.8 s (issue) | "
          f"{statistics.median(times):.2f} s | <= 0.3 s |")


if __name__ == "__main__":
    main()
