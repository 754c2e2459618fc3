"""Every mesh of the corpus (``benchmarks/corpus/meshes``: CAD parts with pockets and
holes, a round part) with every gripper that plans solids, each run in a fresh process
as the command line runs it (``fcgrasp plan MESH ... --json OUT``): CPU seconds and
peak memory of the process, the plans returned and whether the answer is complete,
beside the ranked list (``--distinct 0``) measured in the same invocation, as a ratio.

    python benchmarks/bench_meshes.py [--mu 0.5] [--grippers 2f,3f,jaw] [--files round]
                                      [--torus 10000,100000] [--previous DIR]

``--previous DIR`` (a checkout of an earlier commit, ``git worktree add DIR REV``) runs
the same default command with that checkout's package too, beside it in the same
invocation: its CPU, the ratio, and whether the plans are the same.

``--torus`` adds tori of about those many triangles (major radius 40 mm, minor 12 mm,
``trimesh.creation.torus``): a curved solid of 10,000 to 100,000 triangles with no two
facets parallel.

The jaw's stroke and pads follow each mesh's size (its stroke from 2 % to 150 % of the
largest extent, pads 10 % of it: the meshes come in millimetres and in inches).
Prints a Markdown table and how many runs take more than 2 s.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from bench_defaults import cell, run, warm

HERE = Path(__file__).resolve().parent
MESHES = HERE / "corpus" / "meshes"


def gripper_args(g: str, size: float) -> list[str]:
    if g == "2f":
        return ["--fingers", "2"]
    if g == "3f":
        return ["--fingers", "3"]
    return ["--gripper", "jaw", "--stroke", f"{0.02 * size:.6g},{1.5 * size:.6g}",
            "--pad", f"{0.1 * size:.6g}"]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mu", default="0.5")
    ap.add_argument("--grippers", default="2f,3f,jaw")
    ap.add_argument("--files", default="", help="only meshes whose name contains this")
    ap.add_argument("--torus", default="", help="tori of about these many triangles")
    ap.add_argument("--previous", default=None,
                    help="a checkout of an earlier commit to run beside the default")
    args = ap.parse_args()
    import tempfile

    import trimesh

    tmp = tempfile.TemporaryDirectory()
    previous = None if args.previous is None else str(Path(args.previous).resolve() / "src")
    warm(previous)
    files = sorted(p for p in MESHES.iterdir()
                   if p.suffix.lower() in (".stl", ".ply", ".obj", ".off")
                   and args.files in p.name)
    for n in map(int, filter(None, args.torus.split(","))):
        minor = max(8, int(round((n / 10) ** 0.5)))         # 2 * major * minor = n
        major = max(8, n // (2 * minor))
        path = Path(tmp.name) / f"torus-{2 * major * minor}.stl"
        trimesh.creation.torus(major_radius=40, minor_radius=12, major_sections=major,
                               minor_sections=minor).export(str(path))
        files.append(path)
    head = ["mesh", "triangles", "gripper", "default (CPU, peak)", "plans", "complete",
            "ranked", "ratio"] + (["previous", "ratio", "same plans"] if previous else [])
    print("| " + " | ".join(head) + " |")
    print("|" + " --- |" * len(head))
    over = total = 0
    for path in files:
        mesh = trimesh.load(str(path), force="mesh")
        size = float(max(mesh.extents))
        for g in filter(None, args.grippers.split(",")):
            argv = ["plan", str(path), *gripper_args(g, size), "--mu", args.mu]
            d = run(argv, None)
            b = run(argv + ["--distinct", "0"], None)
            ratio = "-" if d.get("cpu") is None or b.get("cpu") is None \
                else f"{d['cpu'] / max(b['cpu'], 1e-9):.2f}"
            total += 1
            over += d.get("cpu") is None or d["cpu"] > 2.0
            row = [path.name, str(len(mesh.faces)), g, cell(d, None), str(d.get("plans", "-")),
                   "yes" if d.get("complete") else "no", cell(b, None), ratio]
            if previous:
                p = run(argv, None, previous)
                row += [cell(p, None),
                        "-" if d.get("cpu") is None or p.get("cpu") is None
                        else f"{d['cpu'] / max(p['cpu'], 1e-9):.2f}",
                        "yes" if d.get("grasps") == p.get("grasps") else "no"]
            print("| " + " | ".join(row) + " |", flush=True)
    print(f"\n{total - over} of {total} runs within 2 s of CPU")
    return 0


if __name__ == "__main__":
    sys.exit(main())
