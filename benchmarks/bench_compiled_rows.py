"""This round's compiled loops against the numpy they replace, in one process,
each way in turn (best of ``--repeat`` runs, CPU seconds), with whether the plans are the
same: the rows of four frictionless fingers' programs (and three with gravity;
``fcgrasp.model._frictionless_kernels``) and the jaw's pose grid
(``fcgrasp.grippers.jaw._kernels.grid``).  The numpy ways are switched on by making the
compiled entry points say they cannot run, as they do without numba.

    python benchmarks/bench_compiled_rows.py [--parts demo:cam,benchmarks/corpus/icons/bell.svg]
"""

from __future__ import annotations

import argparse
import time

import fcgrasp as fc
from fcgrasp.grippers.jaw import _kernels as jaw_kernels
from fcgrasp.model import _frictionless_kernels

GRIPPERS = {
    "4 frictionless": (dict(fingers=4), _frictionless_kernels, "system_rows"),
    "3 frictionless + gravity": (dict(fingers=3, gravity=(0, -1)), _frictionless_kernels,
                                 "system_rows"),
    "parallel jaw": (None, jaw_kernels, "grid"),
}


def _part(name: str) -> fc.Polygon:
    return fc.read_part(name) if name.startswith("demo:") else fc.load_part(name).polygon


def _run(part: fc.Polygon, kw: dict | None) -> tuple[float, list]:
    if kw is None:                       # a jaw wider than the part, pads a tenth of it
        size = part.size
        kw = dict(gripper=fc.ParallelJaw(stroke=(0.0, 1.2 * size), pad_width=0.1 * size,
                                         mu=0.3))
    t0 = time.process_time()
    plans = fc.plan(part, **kw)
    return time.process_time() - t0, [repr(p.to_dict()) for p in plans]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--parts", default="demo:blob,demo:cam,demo:washer,"
                    "benchmarks/corpus/icons/bell.svg")
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args()
    fc.compile_kernels()
    print("| part | gripper | numpy (s) | compiled (s) | numpy / compiled | same plans |")
    print("| --- | --- | --- | --- | --- | --- |")
    for name in args.parts.split(","):
        part = _part(name)
        for label, (kw, module, entry) in GRIPPERS.items():
            compiled = getattr(module, entry)
            best = {}
            plans = {}
            for _ in range(args.repeat):
                for way in ("numpy", "compiled"):
                    setattr(module, entry, compiled if way == "compiled"
                            else (lambda *a, **k: None))
                    try:
                        t, p = _run(part, kw)
                    finally:
                        setattr(module, entry, compiled)
                    best[way] = min(best.get(way, t), t)
                    plans[way] = p
            print(f"| {name} | {label} | {best['numpy']:.3f} | {best['compiled']:.3f} | "
                  f"{best['numpy'] / max(best['compiled'], 1e-9):.1f}x | "
                  f"{'yes' if plans['numpy'] == plans['compiled'] else 'NO'} |", flush=True)


if __name__ == "__main__":
    main()
