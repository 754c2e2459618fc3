"""Regions along the boundary: two-finger plans of curved outlines, each run
in a fresh process, with its time (seconds, the planning call alone), peak resident
memory of the process and the smallest region of the best plan, for the single-edge
regions (``fc.plan(..., along_boundary=False)``, before) and the regions along the
boundary (``fc.plan``'s default, after), ``top=1``.
Targets on the project's 2-core machine: 2 s and 500 MB at 2,000 edges.

Run: ``.venv/bin/python benchmarks/bench_stretches.py``.
"""

from __future__ import annotations

import json
import subprocess
import sys

CHILD = r"""
import json, resource, sys, time
import numpy as np
import fcgrasp as fc
kind, n, how = sys.argv[1], int(sys.argv[2]), sys.argv[3]
a = np.linspace(0, 2 * np.pi, n, endpoint=False)
r = 50.0 if kind == "disc" else 50 + 8 * np.sin(3 * a) + 5 * np.cos(7 * a)
poly = fc.Polygon(np.c_[r * np.cos(a), r * np.sin(a)])
t0 = time.perf_counter()
best = fc.plan(poly, fingers=2, mu=0.3, top=1,
               along_boundary=how != "single edges")[0].min_length
dt = time.perf_counter() - t0
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
print(json.dumps([dt, peak, best]))
"""


def main() -> None:
    print("| outline | edges | regions | seconds | peak RSS (MB) | smallest region (mm) |")
    print("| --- | --- | --- | --- | --- | --- |")
    for kind, n in (("disc R50", 360), ("disc R50", 1000), ("curved", 500), ("curved", 2000)):
        for how in ("single edges", "along the boundary"):
            out = subprocess.run([sys.executable, "-c", CHILD, kind.split()[0], str(n), how],
                                 capture_output=True, text=True, check=True).stdout
            dt, peak, best = json.loads(out)
            print(f"| {kind} | {n} | {how} | {dt:.2f} | {peak:.0f} | {best:.3f} |")


if __name__ == "__main__":
    main()
