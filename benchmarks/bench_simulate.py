"""The physics stress test over the built-in parts and the drawings of the corpus: for each
part and gripper, the top plans' grasps sampled in their regions (ends and middles
first) under seeded disturbances in MuJoCo (:mod:`fcgrasp.physics`), and controls that
are not force closure pushed along their escape motion (the same contacts without
friction, or a frictionless finger fewer; the jaw's poses without friction).

Prints, per part and gripper: the runs, how many held every load up to their certified
payload, the load at slip over the certified payload (least and median; a run that held
to the end of its ramp, three times the payload, counts as 3), the controls that slipped,
and the CPU seconds per run (each run one grasp, one direction, in this process).

    python benchmarks/bench_simulate.py [--samples 10] [--directions 2] [--top 2]
                                        [--files icons/hexagon.svg,gears/teeth-12.dxf]
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

import fcgrasp as fc
from fcgrasp.io.parts import demo_part, load_part
from fcgrasp.physics import control_runs, simulate

HERE = Path(__file__).resolve().parent
GRIPPERS = {"2f": dict(fingers=2, mu=0.5), "3f": dict(fingers=3, mu=0.5),
            "4f": dict(fingers=4), "jaw": None}
PARTS = ["blob", "quad", "triangle", "rectangle", "bracket", "cam", "washer"]


def row(name: str, poly: object, gripper: str, args: argparse.Namespace) -> str:
    kw = GRIPPERS[gripper]
    if kw is None:                      # a jaw sized to the part
        size = poly.size
        kw = dict(gripper=fc.ParallelJaw(stroke=(0.05 * size, 1.5 * size),
                                         pad_width=0.1 * size, mu=0.5))
    plans = fc.plan(poly, top=args.top, **kw)
    if not plans:
        return f"| {name} | {gripper} | no plan | | | | |"
    start = time.process_time()
    out = simulate(poly, plans, samples=args.samples, directions=args.directions, seed=1,
                   workers=1)
    cpu = time.process_time() - start
    runs = sum(o["runs"] for o in out)
    held = sum(o["held"] for o in out)
    ratios = [(g["slip_load"] if g["slip_load"] is not None else 3 * g["certified_payload"])
              / g["certified_payload"] for o in out for g in o["grasps"]]
    controls = control_runs(poly, plans, seed=2)
    slipped, total = sum(c["slipped"] for c in controls), len(controls)
    return (f"| {name} | {gripper} | {runs} | {held} ({100 * held / runs:.0f} %) | "
            f"{min(ratios):.2f} / {statistics.median(ratios):.2f} | {slipped} of {total} | "
            f"{cpu / runs * 1000:.0f} ms |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--samples", type=int, default=10)
    ap.add_argument("--directions", type=int, default=2)
    ap.add_argument("--top", type=int, default=2)
    ap.add_argument("--files", default="icons/hexagon.svg,icons/shield.svg,gears/teeth-12.dxf")
    ap.add_argument("--grippers", default=",".join(GRIPPERS))
    args = ap.parse_args()
    print("| part | gripper | runs | held to the certified payload | slip / certified "
          "(least / median) | controls slipped | CPU per run |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    parts = [(n, demo_part(n)) for n in PARTS]
    parts += [(f, load_part(str(HERE / "corpus" / f)).polygon)
              for f in args.files.split(",") if f]
    for name, poly in parts:
        for gripper in args.grippers.split(","):
            print(row(name, poly, gripper, args), flush=True)


if __name__ == "__main__":
    main()
