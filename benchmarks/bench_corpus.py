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
                                      [--distinct F]

``--distinct F`` plans with ``distinct=F`` (distinct alternatives) instead of
the default.

Target: every run within 2 s of CPU.
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
path, gripper, distinct = sys.argv[1], sys.argv[2], sys.argv[3]
t0 = time.process_time()
part = fc.load_part(path)
read = time.process_time() - t0
poly = part.polygon
lo, hi = poly.vertices.min(axis=0), poly.vertices.max(axis=0)
size = float((hi - lo).max())
kw = {"2f": dict(fingers=2, mu=0.3), "3f": dict(fingers=3, mu=0.3),
      "3g": dict(fingers=3, gravity=(0, -1)), "4f": dict(fingers=4),
      # a jaw that opens wider than the part, with pads a tenth of its size
      "jaw": dict(gripper=fc.ParallelJaw(stroke=(0.0, 1.2 * size), pad_width=0.1 * size,
                                         mu=0.3))}[gripper]
if distinct:
    kw["distinct"] = float(distinct)
t0 = time.process_time()
plans = fc.plan(poly, **kw)
print(json.dumps({"edges": poly.n_edges, "read": read, "cpu": time.process_time() - t0,
                  "plans": len(plans)}))
"""

GRIPPERS = {"2f": "2 fingers, mu 0.3", "3f": "3 fingers, mu 0.3",
            "3g": "3 frictionless + gravity", "4f": "4 frictionless", "jaw": "parallel jaw"}


def files(pattern: str) -> list[Path]:
    return sorted(p for p in CORPUS.rglob("*") if p.suffix.lower() in FORMATS
                  and pattern in str(p.relative_to(CORPUS)))


def run(path: Path, gripper: str, limit: float, distinct: str = "") -> dict[str, object]:
    try:
        out = subprocess.run([sys.executable, "-c", CHILD, str(path), gripper, distinct],
                             capture_output=True, text=True, timeout=limit)
    except subprocess.TimeoutExpired:
        return {"cpu": None, "note": f"stopped after {limit:g} s"}
    if out.returncode:
        last = (out.stderr.strip().splitlines() or ["?"])[-1]
        return {"cpu": None, "note": last[:80]}
    return dict(json.loads(out.stdout.strip().splitlines()[-1]), note="")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--limit", type=float, default=30.0, help="seconds before a run is stopped")
    ap.add_argument("--grippers", default=",".join(GRIPPERS))
    ap.add_argument("--files", default="", help="only files whose path contains this")
    ap.add_argument("--worst", type=int, default=10)
    ap.add_argument("--distinct", default="", help="plan with distinct=F (default: as fc.plan)")
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
    print("| file | edges | gripper | CPU s | plans | note |")
    print("| --- | --- | --- | --- | --- | --- |")
    for path in files(args.files):
        for g in grippers:
            r = run(path, g, args.limit, args.distinct)
            name = path.relative_to(CORPUS).as_posix()
            cpu = r["cpu"]
            rows.append((float("inf") if cpu is None else float(cpu), name, g, r))
            cpu_s = "-" if cpu is None else f"{cpu:.2f}"
            print(f"| {name} | {r.get('edges', '-')} | {GRIPPERS[g]} | {cpu_s} | "
                  f"{r.get('plans', '-')} | {r['note']} |", flush=True)
    done = [r for r in rows if r[0] != float("inf")]
    over = [r for r in rows if r[0] > TARGET]
    print(f"\n{len(rows)} runs on {len({r[1] for r in rows})} files; {len(over)} over "
          f"{TARGET:g} s (or stopped/failed); median CPU "
          f"{sorted(r[0] for r in done)[len(done) // 2] if done else float('nan'):.2f} s")
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
