"""Three and four frictionless fingers along the boundary: the gap of the grown
plans (``fc.plan``'s default, a proven safe lower bound) to the exhaustive optimum over
every configuration that holds (``all_frictionless_stretches`` started from every
single-edge set that holds), on small curved outlines of the test corpus's families
(ellipse, star, cam, rounded rectangle), with the single-edge optimum for scale.

Columns: the smallest region of the best plan on single edges, grown along the boundary
and exhaustive; the gap ``1 - grown / exhaustive``; seconds of ``fc.plan`` (grown) and
of the exhaustive search.

Run: ``.venv/bin/python benchmarks/bench_frictionless_stretches.py [--quick]``.
"""

from __future__ import annotations

import sys
import time

import numpy as np
from shapely.geometry import Polygon as ShapelyPolygon

import fcgrasp as fc
from fcgrasp.model.frictionless_stretches import all_frictionless_stretches


def outline(kind: str, n: int) -> fc.Polygon:
    """A counter-clockwise ring of about ``n`` vertices on a smooth closed curve."""
    th = np.linspace(0, 2 * np.pi, n, endpoint=False)
    if kind == "ellipse":
        pts = np.c_[40 * np.cos(th), 25 * np.sin(th)]
    elif kind == "star":
        r = 40 * (1 + 0.05 * np.cos(3 * th) + 0.03 * np.cos(5 * th + 1))
        pts = np.c_[r * np.cos(th), r * np.sin(th)]
    elif kind == "cam":
        r = 30 * (1 + 0.35 * np.exp(-(np.angle(np.exp(1j * th)) / 0.7) ** 2))
        pts = np.c_[r * np.cos(th), r * np.sin(th)]
    else:
        box = ShapelyPolygon([(0, 0), (60, 0), (60, 35), (0, 35)]).buffer(
            8, quad_segs=max(1, (n - 4) // 4))
        pts = np.asarray(box.exterior.coords)[:-1]
        if not ShapelyPolygon(pts).exterior.is_ccw:
            pts = pts[::-1]
    return fc.Polygon(pts)


def main() -> None:
    quick = "--quick" in sys.argv
    sizes = (12,) if quick else (12, 16)
    print("| outline | edges | fingers | single edges | grown | exhaustive | gap | "
          "seconds (grown) | seconds (exhaustive) |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    gaps = []
    for kind in ("ellipse", "star", "cam", "rounded"):
        for n in sizes:
            poly = outline(kind, n)
            for fingers in (3, 4):
                flat = fc.plan(poly, fingers=fingers, top=None, along_boundary=False)
                t0 = time.perf_counter()
                grown = fc.plan(poly, fingers=fingers, top=1)
                t1 = time.perf_counter()
                rows = [p.edges for p in flat if len(set(p.edges)) == len(p.edges)]
                g = (0.0, -1.0) if fingers == 3 else None
                ex = all_frictionless_stretches(poly, rows, gravity=g) if rows else None
                t2 = time.perf_counter()
                a = flat[0].min_length if flat else 0.0
                b = grown[0].min_length if grown else 0.0
                c = max(ex.min_length if ex else 0.0, a)
                gap = 1 - b / c if c > 0 else 0.0
                gaps.append(gap)
                print(f"| {kind} | {poly.n_edges} | {fingers} | {a:.3f} | {b:.3f} | {c:.3f} | "
                      f"{100 * gap:.1f}% | {t1 - t0:.2f} | {t2 - t1:.1f} |")
    print(f"\nmean gap {100 * np.mean(gaps):.1f}%, largest {100 * np.max(gaps):.1f}%")


if __name__ == "__main__":
    main()
