"""Catalogue planning: parts per second of ``fc.plan_many`` on generated part
files, with the local process pool and with a Dask LocalCluster, 1 and 2 workers.

The parts are random star-shaped outlines written as JSON files (``--edges`` edges each,
default 8; two fingers with friction, mu 0.4, top 3, regions along the boundary).  The
cluster's start-up (spawning its workers) is timed apart from the planning.

    python benchmarks/bench_batch.py [--parts 1000] [--edges 8] [--quick]
"""

from __future__ import annotations

import argparse
import json
import os
import tempfile
import time

import numpy as np

import fcgrasp as fc


def write_parts(folder: str, count: int, edges: int, seed: int = 0) -> list[str]:
    rng = np.random.default_rng(seed)
    paths = []
    for k in range(count):
        ang = np.sort(rng.uniform(0, 2 * np.pi, edges))
        r = rng.uniform(20, 40, edges)
        v = np.c_[r * np.cos(ang), r * np.sin(ang)].round(4).tolist()
        path = os.path.join(folder, f"part{k:05d}.json")
        with open(path, "w") as f:
            json.dump({"vertices": v}, f)
        paths.append(path)
    return paths


OPTIONS = {"fingers": 2, "mu": 0.4, "top": 3}


def run(paths: list[str], **kw: object) -> tuple[float, int]:
    t0 = time.perf_counter()
    n = sum(1 for r in fc.plan_many(paths, **kw, **OPTIONS) if r["error"] is None)
    return time.perf_counter() - t0, n


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--parts", type=int, default=1000)
    ap.add_argument("--edges", type=int, default=8)
    ap.add_argument("--quick", action="store_true", help="100 parts")
    args = ap.parse_args()
    count = 100 if args.quick else args.parts
    print(f"{count} parts of {args.edges} edges, {OPTIONS}, {os.cpu_count()} cores")
    print("| runner | workers | start-up s | planning s | parts/s |")
    print("| --- | --- | --- | --- | --- |")
    with tempfile.TemporaryDirectory() as tmp:
        paths = write_parts(tmp, count, args.edges)
        for workers in (1, 2):
            dt, n = run(paths, workers=workers)
            print(f"| local pool | {workers} | - | {dt:.2f} | {n / dt:.1f} |")
        try:
            from distributed import Client, LocalCluster
        except ImportError:
            print("| LocalCluster | - | distributed not installed | | |")
            return
        for workers in (1, 2):
            t0 = time.perf_counter()
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None)
            client = Client(cluster)
            up = time.perf_counter() - t0
            dt, n = run(paths, client=client)
            client.close()
            cluster.close()
            print(f"| LocalCluster | {workers} | {up:.2f} | {dt:.2f} | {n / dt:.1f} |")


if __name__ == "__main__":
    main()
