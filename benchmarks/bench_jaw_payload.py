"""The load a parallel jaw's box carries (``fcgrasp.jaw_payload``): for the top
boxes of each built-in part (stroke 5-60, pads 8 wide, mu 0.5; 0.5 kg, 10 N per pad), the
certified scale, the worst pose met, the gap, the sub-boxes and the seconds, beside the
baseline measured in the same run: the least payload of 100 random poses of the box (an
estimate from above, no guarantee; each pose's contacts by the pose model and its
payload by ``grasp_payload``).

    .venv/bin/python benchmarks/bench_jaw_payload.py [--parts triangle,quad] [--top 3]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import fcgrasp as fc
from fcgrasp.grippers.jaw._payload import _pose_scale


def _sampled(part, box, load, limit, n, rng):
    """The least payload of ``n`` random poses of the box (the pose model's contacts)."""
    worst = np.inf
    for t, c in box.sample(n, rng):
        got = _pose_scale(part, box, float(t), float(c), load, limit, None)
        if got is not None:
            worst = min(worst, got[0])
    return worst


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--parts", default="triangle,quad,blob,bracket,rectangle,washer")
    ap.add_argument("--top", type=int, default=3)
    args = ap.parse_args()
    fc.compile_kernels()
    jaw = fc.ParallelJaw(stroke=(5, 60), pad_width=8, mu=0.5)
    load, limit = fc.Load(0.5), 10.0
    rng = np.random.default_rng(0)
    print("| part | box | certified scale | worst pose met | gap | sub-boxes | s | "
          "baseline: least of 100 sampled poses | its s | certified / sampled |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for name in args.parts.split(","):
        part = fc.read_part(f"demo:{name}")
        for k, box in enumerate(fc.plan(part, gripper=jaw, top=args.top), 1):
            t0 = time.perf_counter()
            got = fc.jaw_payload(part, box, load, force_limit=limit)
            t1 = time.perf_counter()
            base = _sampled(part, box, load, limit, 100, rng)
            t2 = time.perf_counter()
            print(f"| {name} | {k} | {got.lower:.4g} | {got.upper:.4g} | "
                  f"{100 * got.gap:.1f} % | {got.boxes} | {t1 - t0:.2f} | {base:.4g} | "
                  f"{t2 - t1:.2f} | {got.lower / base:.3f} |", flush=True)


if __name__ == "__main__":
    main()
