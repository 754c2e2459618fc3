"""The parallel-jaw gripper: the exact slices of the holding set, and plans.

For each built-in part (stroke 5-60, pads 8 wide, mu 0.5): the time of the exact slices
of 720 closing angles (``holding_offsets``), of a plan of the top 5 boxes proved and grown
to the exact boundary (the default) and of one on the grid alone (``certify=False``), and
the measure of the best box each way.

    python benchmarks/bench_jaw.py [--parts rectangle,quad,...]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import fcgrasp as fc
from fcgrasp.grippers.jaw import holding_offsets


def _timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--parts", default="rectangle,quad,triangle,blob,washer")
    args = ap.parse_args()
    jaw = fc.ParallelJaw(stroke=(5, 60), pad_width=8, mu=0.5)
    thetas = np.linspace(0, 2 * np.pi, 720, endpoint=False)
    print("| part | edges | exact slices, 720 angles: s | plan, proved + grown: s | best "
          "measure | plan, grid only: s | best measure (grid, unproved) |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    # numba's cached code loaded first (the compiled loops: fcgrasp.compile_kernels)
    holding_offsets(fc.read_part("demo:triangle"), jaw, thetas[:2])
    for name in args.parts.split(","):
        part = fc.read_part(f"demo:{name}")
        _, t_slices = _timed(lambda part=part: holding_offsets(part, jaw, thetas))
        proved, t_proved = _timed(lambda part=part: fc.plan(part, gripper=jaw, top=5))
        grid, t_grid = _timed(lambda part=part: fc.jaw_plans(part, jaw, top=5,
                                                             certify=False))
        best = f"{proved[0].measure:.2f}" if proved else "-"
        best_grid = f"{grid[0].measure:.2f}" if grid else "-"
        print(f"| {name} | {part.n_edges} | {t_slices:.2f} | {t_proved:.2f} | {best} | "
              f"{t_grid:.2f} | {best_grid} |")


if __name__ == "__main__":
    main()
