"""The real-file corpus: every file of ``benchmarks/corpus`` (public drawings nobody
here drew: CAD plates and polylines, icons, country outlines; see its SOURCES.md) planned
with every gripper at default options, as a user would (``fcgrasp.load_part`` then
``fcgrasp.plan``).  Each (file, gripper) runs in a fresh process, timed in CPU seconds
(the planning call; the import and the file's reading apart), with a limit after which it
is stopped and reported as over it.  The compiled kernels are compiled (or loaded from
numba's cache) once before the runs, as ``python3 tasks.py`` does after an install.
Prints the table of every run, a summary per gripper (runs within the target, over
it, stopped; the sum of CPU, a stopped run counted as the limit), then the worst.

    python benchmarks/bench_corpus.py [--limit 30] [--grippers 2f,3f,3g,4f,jaw] [--files PAT]
                                      [--distinct F] [--mu 0.5]

``--distinct F`` plans with ``distinct=F`` (distinct alternatives) instead of
the default; ``--mu`` sets the friction of two and three fingers and the jaw (0.3 by
default).  Besides the planning call's CPU, each run's whole process (the import, the
reading, the plan: what a user of the command line waits for) is timed too.

Target: every run within 2 s of CPU, the whole process's median within 1 s.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

CORPUS = Path(__file__).with_name("corpus")
FORMATS = {".svg", ".dxf", ".json", ".geojson", ".wkt", ".png"}
TARGET = 2.0

CHILD = r"""
import json, sys, time
import fcgrasp as fc
path, gripper, distinct, mu = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
t0 = time.process_time()
part = fc.load_part(path)
read = time.process_time() - t0
poly = part.polygon
lo, hi = poly.vertices.min(axis=0), poly.vertices.max(axis=0)
size = float((hi - lo).max())
kw = {"2f": dict(fingers=2, mu=mu), "3f": dict(fingers=3, mu=mu),
      "3g": dict(fingers=3, gravity=(0, -1)), "4f": dict(fingers=4),
      # a jaw that opens wider than the part, with pads a tenth of its size
      "jaw": dict(gripper=fc.ParallelJaw(stroke=(0.0, 1.2 * size), pad_width=0.1 * size,
                                         mu=mu))}[gripper]
if distinct:
    kw["distinct"] = float(distinct)
t0 = time.process_time()
plans = fc.plan(poly, **kw)
print(json.dumps({"edges": poly.n_edges, "read": read, "cpu": time.process_time() - t0,
                  "plans": len(plans)}))
# the process ends as the fcgrasp command does (fcgrasp.apps.cli.run): its heap frozen,
# which the interpreter's finalization then does not collect
import gc
gc.freeze()
"""

GRIPPERS = {"2f": "2 fingers", "3f": "3 fingers",
            "3g": "3 frictionless + gravity", "4f": "4 frictionless", "jaw": "parallel jaw"}


def files(pattern: str) -> list[Path]:
    return sorted(p for p in CORPUS.rglob("*") if p.suffix.lower() in FORMATS
                  and pattern in str(p.relative_to(CORPUS)))


def run(path: Path, gripper: str, limit: float, distinct: str = "",
        mu: float = 0.3) -> dict[str, object]:
    import resource

    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    try:
        out = subprocess.run([sys.executable, "-c", CHILD, str(path), gripper, distinct,
                              repr(mu)], capture_output=True, text=True, timeout=limit)
    except subprocess.TimeoutExpired:
        return {"cpu": None, "note": f"stopped after {limit:g} s"}
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode:
        last = (out.stderr.strip().splitlines() or ["?"])[-1]
        return {"cpu": None, "note": last[:80]}
    process = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return dict(json.loads(out.stdout.strip().splitlines()[-1]), process=process, note="")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--limit", type=float, default=30.0, help="seconds before a run is stopped")
    ap.add_argument("--grippers", default=",".join(GRIPPERS))
    ap.add_argument("--files", default="", help="only files whose path contains this")
    ap.add_argument("--worst", type=int, default=10)
    ap.add_argument("--distinct", default="", help="plan with distinct=F (default: as fc.plan)")
    ap.add_argument("--mu", type=float, default=0.3, help="friction of 2f, 3f and the jaw")
    args = ap.parse_args()
    grippers = [g for g in args.grippers.split(",") if g]
    rows = []
    # the compiled kernels compiled (or loaded) once before the runs, as tasks.py does
    # after an install: a kernel whose cache is stale (its module edited) would
    # otherwise be compiled inside the first run that needs it, tens of seconds
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", "import fcgrasp; fcgrasp.compile_kernels()"],
                   check=True)
    print(f"kernels compiled or loaded: {time.perf_counter() - t0:.1f} s\n")
    print(f"mu {args.mu:g} (two and three fingers, the jaw)\n")
    print("| file | edges | gripper | CPU s | process CPU s | plans | note |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for path in files(args.files):
        for g in grippers:
            r = run(path, g, args.limit, args.distinct, args.mu)
            name = path.relative_to(CORPUS).as_posix()
            cpu = r["cpu"]
            rows.append((float("inf") if cpu is None else float(cpu), name, g, r))
            cpu_s = "-" if cpu is None else f"{cpu:.2f}"
            whole = "-" if cpu is None else f"{r['process']:.2f}"
            print(f"| {name} | {r.get('edges', '-')} | {GRIPPERS[g]} | {cpu_s} | {whole} | "
                  f"{r.get('plans', '-')} | {r['note']} |", flush=True)
    done = [r for r in rows if r[0] != float("inf")]
    over = [r for r in rows if r[0] > TARGET]
    print(f"\n{len(rows)} runs on {len({r[1] for r in rows})} files; {len(over)} over "
          f"{TARGET:g} s (or stopped/failed); median CPU "
          f"{sorted(r[0] for r in done)[len(done) // 2] if done else float('nan'):.2f} s, "
          f"of the whole process "
          f"{sorted(r[3]['process'] for r in done)[len(done) // 2] if done else float('nan'):.2f}"
          f" s")
    # per gripper: runs within the target, over it, stopped or failed; the sum of CPU
    # counts a stopped run as the limit
    print(f"\n| gripper | within {TARGET:g} s | over | stopped or failed | sum of CPU s |")
    print("| --- | --- | --- | --- | --- |")
    for g in grippers:
        mine = [r[0] for r in rows if r[2] == g]
        ok = sum(c <= TARGET for c in mine)
        gone = sum(c == float("inf") for c in mine)
        total = sum(min(c, args.limit) for c in mine)
        print(f"| {GRIPPERS[g]} | {ok} | {len(mine) - ok - gone} | {gone} | {total:.1f} |")
    print(f"| all | {sum(r[0] <= TARGET for r in rows)} | "
          f"{sum(TARGET < r[0] < float('inf') for r in rows)} | "
          f"{sum(r[0] == float('inf') for r in rows)} | "
          f"{sum(min(r[0], args.limit) for r in rows):.1f} |")
    print("\nworst:")
    for cpu, name, g, r in sorted(rows, key=lambda r: -r[0])[:args.worst]:
        print(f"  {'stopped' if cpu == float('inf') else f'{cpu:.2f} s':>10}  {name} "
              f"({GRIPPERS[g]}) {r['note']}")


if __name__ == "__main__":
    main()
