"""Memory of large searches: a four-finger plan of a 300-vertex traced-like
outline, as a process, with its peak resident memory.  A search that cannot fit is refused
at once; one that fits streams within ``--max-memory`` (run for at most ``SECONDS``, then
interrupted); without the streaming the same run allocates about 11 GB, and without the
exact pruning it runs for hours.

Run: ``.venv/bin/python benchmarks/bench_memory.py``.
"""

from __future__ import annotations

import json
import os
import resource
import signal
import subprocess
import sys
import tempfile
import time

import numpy as np

SECONDS = 30


def outline(n: int = 300) -> list[list[float]]:
    a = np.linspace(0, 2 * np.pi, n + 1)[:-1]
    r = 50 + 8 * np.sin(3 * a) + 5 * np.cos(7 * a)
    return np.c_[r * np.cos(a), r * np.sin(a)].tolist()


def run(args: list[str], limit: float | None) -> tuple[int, float, float]:
    """Exit code, seconds and peak RSS (MB) of one fcgrasp process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    t0 = time.perf_counter()
    p = subprocess.Popen([sys.executable, "-m", "fcgrasp", *args],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        p.wait(timeout=limit)
    except subprocess.TimeoutExpired:
        p.send_signal(signal.SIGINT)
        p.wait()
    dt = time.perf_counter() - t0
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    return p.returncode, dt, max(peak, before) / 1024


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        part = os.path.join(tmp, "outline300.json")
        with open(part, "w") as fh:
            json.dump(outline(), fh)
        rows = [
            ("4 fingers, --top 100000000 (cannot fit)", [part, "--fingers", "4", "--top",
                                                         "100000000"], None),
            ("4 fingers, --top 10, --max-memory 100M", [part, "--fingers", "4", "--top", "10",
                                                       "--max-memory", "100M"], SECONDS),
            ("4 fingers, --top 10 (default budget 2G)", [part, "--fingers", "4", "--top",
                                                         "10"], SECONDS),
        ]
        print("| workload (300 edges) | exit | seconds | peak RSS (MB) |")
        print("| --- | --- | --- | --- |")
        for name, args, limit in rows:
            code, dt, mb = run(["plan", *args, "--quiet"], limit)
            what = "interrupted" if code == 130 else str(code)
            print(f"| {name} | {what} | {dt:.1f} | {mb:.0f} |")


if __name__ == "__main__":
    main()
