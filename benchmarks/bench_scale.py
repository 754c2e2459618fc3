"""Scale of parts: two-finger plans of finely flattened outlines on single edges
(the exact branch and bound of ``fcgrasp.pipeline.search``), with the time and the peak
memory of each run (each size in a fresh process, peak resident set size).  Regions along
the boundary at these sizes: ``bench_stretches.py``.

    python benchmarks/bench_scale.py [--sizes 1000,3000,10000]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys

CHILD = r"""
import json, resource, sys, time
import numpy as np
from fcgrasp import Polygon, plan
n = int(sys.argv[1])
ang = np.linspace(0, 2 * np.pi, n, endpoint=False)
r = 1 + 0.3 * np.sin(3 * ang) + 0.1 * np.cos(5 * ang + 1)
part = Polygon(np.column_stack([r * np.cos(ang), r * np.sin(ang)]) * 50.0)
t0 = time.perf_counter()
plans = plan(part, fingers=2, mu=0.3, top=5, along_boundary=False)
dt = time.perf_counter() - t0
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
print(json.dumps({"n": n, "seconds": dt, "peak_mb": peak, "plans": len(plans),
                  "best": plans[0].min_length if plans else None}))
"""


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="1000,3000,10000")
    args = ap.parse_args()
    print(f"{'vertices':>9} {'edge pairs':>12} {'time':>9} {'peak RSS':>10} {'best region':>12}")
    for n in (int(x) for x in args.sizes.split(",")):
        out = subprocess.run([sys.executable, "-c", CHILD, str(n)], capture_output=True,
                             text=True, check=True)
        d = json.loads(out.stdout.strip().splitlines()[-1])
        print(f"{d['n']:>9} {n * (n - 1) // 2:>12,} {d['seconds']:>8.2f}s "
              f"{d['peak_mb']:>8.0f}MB {d['best']:>12.4g}")


if __name__ == "__main__":
    main()
