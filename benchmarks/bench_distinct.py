"""Distinct alternatives: CPU seconds of ``fc.plan(..., top=10, distinct=0.5)``
against the ranked list (``distinct=0``, the baseline, same process) on the built-in
parts, per gripper, with how many distinct plans were found.  Two fingers along the
boundary search for distinct plans directly (each kept plan's copies left out); the
other grippers ask their search for more plans until ten distinct ones are found.

    python benchmarks/bench_distinct.py [--parts cam,blob] [--fraction 0.5] [--smooth 1000]
                                        [--corpus icons/shield.svg,icons/cloud.svg]

``--smooth N`` adds an ellipse and a blob of ``N`` equal-angle edges, two fingers only
(where one grasp's shifted copies fill the ranked list: the hard case of the search).
``--corpus FILES`` adds files of ``benchmarks/corpus`` (paths inside it), two fingers
only (flattened curves of the icons: hundreds of edges, a grasp's copies by the dozen).

``--three FILES`` (files of ``benchmarks/corpus``): three fingers with friction, the
search that leaves each kept plan's copies out
(:func:`fcgrasp.grippers.three_fingers.distinct_three_finger_plans`) against the previous
implementation, kept here as the baseline (suppression along the ranked list, the search
asked for more plans until ten are distinct or its depth is read: the same gripper
without its ``distinct_search``), with how many alternatives each found and whether the
first ones agree.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

import fcgrasp as fc
from fcgrasp.grippers.fingers import ThreeFingers

#: The previous implementation of ``distinct=`` for three fingers: suppression along the
#: ranked list (the planner's generic path, taken by a gripper without ``distinct_search``).
PreviousThreeFingers = type("PreviousThreeFingers", (ThreeFingers,), {"distinct_search": None})

GRIPPERS = {
    "2 fingers, mu 0.3": dict(fingers=2, mu=0.3),
    "3 fingers, mu 0.3": dict(fingers=3, mu=0.3),
    "4 frictionless": dict(fingers=4),
    "3 frictionless + gravity": dict(fingers=3, gravity=(0, -1)),
}


def _cpu(part, fraction, kw):
    t0 = time.process_time()
    plans = fc.plan(part, top=10, distinct=fraction, **kw)
    return time.process_time() - t0, len(plans)


def _row(name, label, part, kw, fraction):
    """One line of the table: the ranked list, then distinct plans, of one part."""
    base, _ = _cpu(part, 0.0, kw)
    got, n = _cpu(part, fraction, kw)
    print(f"| {name} | {label} | {base:.3f} | {got:.3f} | "
          f"{got / max(base, 1e-9):.1f}x | {n} |", flush=True)


def _three(name, part, fraction):
    """One line of the three-finger comparison: the previous implementation, then this."""
    t0 = time.process_time()
    old = fc.plan(part, gripper=PreviousThreeFingers(mu=0.3), top=10, distinct=fraction)
    t1 = time.process_time()
    new = fc.plan(part, fingers=3, mu=0.3, top=10, distinct=fraction)
    t2 = time.process_time()
    k = min(len(old), len(new))
    agree = all(a.region_edges == b.region_edges for a, b in zip(old[:k], new[:k], strict=True))
    print(f"| {name} | {t1 - t0:.2f} | {t2 - t1:.2f} | {(t2 - t1) / max(t1 - t0, 1e-9):.2f}x | "
          f"{len(old)} | {len(new)} | {'yes' if agree else 'NO'} |", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--parts", default="cam,blob,washer,quad")
    ap.add_argument("--fraction", type=float, default=0.5)
    ap.add_argument("--smooth", type=int, default=0)
    ap.add_argument("--corpus", default="", help="files of benchmarks/corpus, comma-separated")
    ap.add_argument("--three", default="", help="files of benchmarks/corpus: three fingers, "
                    "this search against the previous implementation")
    args = ap.parse_args()
    fc.compile_kernels()
    print("| part | gripper | ranked list (s) | distinct (s) | ratio | distinct plans |")
    print("| --- | --- | --- | --- | --- | --- |")
    for name in args.parts.split(","):
        part = fc.read_part(f"demo:{name}")
        for label, kw in GRIPPERS.items():
            _row(name, label, part, kw, args.fraction)
    if args.smooth:
        a = np.linspace(0, 2 * np.pi, args.smooth, endpoint=False)
        r = 50 + 8 * np.sin(3 * a) + 5 * np.cos(7 * a)
        for name, xy in ((f"ellipse {args.smooth}", np.c_[40 * np.cos(a), 25 * np.sin(a)]),
                         (f"blob {args.smooth}", np.c_[r * np.cos(a), r * np.sin(a)])):
            label = "2 fingers, mu 0.3"
            _row(name, label, fc.Polygon(xy), GRIPPERS[label], args.fraction)
    corpus = Path(__file__).with_name("corpus")
    for name in filter(None, args.corpus.split(",")):
        label = "2 fingers, mu 0.3"
        _row(name, label, fc.load_part(str(corpus / name)).polygon, GRIPPERS[label],
             args.fraction)
    if args.three:
        print()
        print("| file | previous (s) | this search (s) | ratio | previous found | found | "
              "first ones agree |")
        print("| --- | --- | --- | --- | --- | --- | --- |")
        for name in filter(None, args.three.split(",")):
            _three(name, fc.load_part(str(corpus / name)).polygon, args.fraction)


if __name__ == "__main__":
    main()
