"""Flattening that follows the geometry: the edges a curved drawing becomes,
the CPU seconds of reading it and of planning it with two fingers (default options),
with the equal-turn flattening of :func:`fcgrasp.io._drawing.flatten_curve` against the
binary halving it replaced (``tests/previous_flatten.py``, the baseline), in one process.

    python benchmarks/bench_flatten.py [--files PAT] [--no-plan]

Inputs: every SVG and DXF of ``benchmarks/corpus`` with curves, and a traced outline (a
gear-like shape of 600 short cubic Bezier pieces, as a tracer such as potrace writes
them: the halving cut every piece in four at least).  Target: a tiny icon
gets hundreds of edges, not thousands, the regions within 1% (``tests/test_flatten.py``).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import fcgrasp as fc  # noqa: E402
from fcgrasp.io import _drawing, _read_dxf, _read_svg  # noqa: E402
from tests.previous_flatten import previous_flatten  # noqa: E402


def traced_svg(n: int = 600) -> str:
    """A 16 px gear-like outline of ``n`` cubic Bezier pieces (Catmull-Rom through
    points of ``r = 8 (1 + 0.08 cos 12 theta)``)."""
    th = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 8 * (1 + 0.08 * np.cos(12 * th))
    p = np.stack([8 + r * np.cos(th), 8 + r * np.sin(th)], axis=1)
    d = [f"M {p[0, 0]:.5f} {p[0, 1]:.5f}"]
    for i in range(n):
        p0, p1, p2, p3 = p[i - 1], p[i], p[(i + 1) % n], p[(i + 2) % n]
        c1, c2 = p1 + (p2 - p0) / 6, p2 - (p3 - p1) / 6
        d.append(f"C {c1[0]:.5f} {c1[1]:.5f} {c2[0]:.5f} {c2[1]:.5f} {p2[0]:.5f} {p2[1]:.5f}")
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="16" height="16" '
            f'viewBox="0 0 16 16"><path d="{" ".join(d)} Z"/></svg>')


def measure(path: Path, flatten, plan: bool) -> tuple[int, float, float]:
    _read_svg.flatten_curve = flatten
    _read_dxf.flatten_curve = flatten
    t0 = time.process_time()
    part = fc.load_part(str(path)).polygon
    read = time.process_time() - t0
    if not plan:
        return part.n_edges, read, float("nan")
    t0 = time.process_time()
    fc.plan(part, fingers=2, mu=0.3)
    return part.n_edges, read, time.process_time() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--files", default="", help="only files whose path contains this")
    ap.add_argument("--no-plan", action="store_true", help="edges and reading only")
    args = ap.parse_args()
    corpus = ROOT / "benchmarks" / "corpus"
    paths = sorted(p for p in corpus.rglob("*") if p.suffix.lower() in (".svg", ".dxf"))
    tmp = Path(tempfile.mkdtemp())
    (tmp / "traced-gear.svg").write_text(traced_svg())
    paths.append(tmp / "traced-gear.svg")
    paths = [p for p in paths if args.files in str(p)]
    fc.plan(fc.read_part("demo:blob"), fingers=2, mu=0.3)  # imports and kernels loaded
    print("| drawing | edges (halving -> equal turn) | read s | plan s, 2 fingers | "
          "edges ratio |")
    print("| --- | --- | --- | --- | --- |")
    tot = np.zeros(2)
    for p in paths:
        old = measure(p, previous_flatten, not args.no_plan)
        new = measure(p, _drawing.flatten_curve, not args.no_plan)
        if old[0] == new[0] and p.suffix != ".svg" and "traced" not in p.name:
            continue                                    # no curves (gears' arcs aside)
        name = p.name if "traced" in p.name else str(p.relative_to(corpus))
        tot += (old[0], new[0])
        print(f"| {name} | {old[0]} -> {new[0]} | {old[1]:.3f} -> {new[1]:.3f} | "
              f"{old[2]:.2f} -> {new[2]:.2f} | {new[0] / old[0]:.2f} |", flush=True)
    print(f"\nedges in all: {int(tot[0])} -> {int(tot[1])} ({tot[1] / tot[0]:.2f})")


if __name__ == "__main__":
    main()
