"""Start-up cost: ``import fcgrasp`` against ``import numpy, shapely`` (target:
under 1.5x), and a small ``fcgrasp plan`` as a process.  Median of fresh interpreters."""

from __future__ import annotations

import statistics
import subprocess
import sys
import time


def best_of(code: list[str], runs: int = 7) -> float:
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        subprocess.run(code, check=True, capture_output=True)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    py = sys.executable
    base = best_of([py, "-c", "pass"])
    ns = best_of([py, "-c", "import numpy, shapely"]) - base
    fc = best_of([py, "-c", "import fcgrasp"]) - base
    plan = best_of([py, "-m", "fcgrasp", "plan", "demo:blob", "--quiet"], runs=5)
    print("| workload | seconds | note |")
    print("| --- | --- | --- |")
    print(f"| import numpy, shapely | {ns:.3f} | baseline |")
    print(f"| import fcgrasp | {fc:.3f} | {fc / ns:.2f}x the baseline (target < 1.5x) |")
    print(f"| fcgrasp plan demo:blob (process) | {plan:.3f} | target <= 0.3 s |")


if __name__ == "__main__":
    main()
