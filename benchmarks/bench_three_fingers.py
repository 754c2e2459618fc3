"""Three fingers with friction: time per plan, the best smallest region against
two fingers, and the gap of the safe bound.

The planner's regions are a safe lower bound (convex pieces of the closure set,
:mod:`fcgrasp.grippers.three_fingers`).  The *gap* column measures how far from the true boundary
the best plan is: every region is lengthened about its middle by a factor ``1 + g``
(within its edge) for growing ``g``, and the largest ``g`` at which all of 200 sampled
grasps (the corners and random ones) still pass the general test
(:func:`fcgrasp.is_force_closure` on the contact wrenches) is printed: 0 means the box is
already at the boundary; 0.5 means the regions could be about 50% longer (a bound from
samples, not a proof).

Curved outlines (finely flattened, where regions run along the boundary) get a second
table: the best plan, the best ``concurrent`` plan grown along the boundary, and the
default two-finger plan (its regions along the boundary too); the gap is not measured
there (regions that cross vertices).

    python benchmarks/bench_three_fingers.py [--quick]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import fcgrasp as fc
from fcgrasp.grippers.three_fingers import grow_concurrent
from fcgrasp.io.parts import demo_part

GROWTH = (0.0, 0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0)


def holds(plan: fc.GraspPlan, points: np.ndarray, normals: np.ndarray) -> bool:
    contacts = [fc.FrictionPoint(p, n, plan.mu) for p, n in zip(points, normals, strict=True)]
    return bool(fc.Grasp(contacts).is_force_closure())


def gap(part: fc.Polygon, plan: fc.GraspPlan, rng: np.random.Generator) -> float:
    """Largest tried growth of the regions at which every sampled grasp still holds."""
    ends = plan.ends
    mid = ends.mean(axis=1)
    half = (ends[:, 1] - ends[:, 0]) / 2
    starts, stops = part.starts[list(plan.edges)], part.ends[list(plan.edges)]
    L = part.lengths[list(plan.edges)]
    tan = (stops - starts) / L[:, None]
    best = 0.0
    u = rng.random((200, 3))
    u[:8] = np.array(list(np.ndindex(2, 2, 2)))
    for g in GROWTH[1:]:
        lo = np.einsum("ij,ij->i", mid - (1 + g) * half - starts, tan).clip(0, L)
        hi = np.einsum("ij,ij->i", mid + (1 + g) * half - starts, tan).clip(0, L)
        s = lo + u * (hi - lo)
        pts = starts[None] + s[..., None] * tan[None]
        if not all(holds(plan, p, plan.normals) for p in pts):
            break
        best = g
    return best


def parts(quick: bool) -> list[tuple[str, fc.Polygon]]:
    out = [(f"demo:{n}", demo_part(n)) for n in ("triangle", "quad", "rectangle", "blob")]
    if not quick:
        out.append(("demo:washer", demo_part("washer")))
        rng = np.random.default_rng(0)
        for k in range(6):
            n = int(rng.integers(5, 11))
            ang = np.sort(rng.uniform(0, 2 * np.pi, n))
            r = rng.uniform(20, 50, n)
            out.append((f"random star {k} ({n} edges)",
                        fc.Polygon(np.c_[r * np.cos(ang), r * np.sin(ang)])))
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--mu", type=float, default=0.5)
    args = ap.parse_args()
    rng = np.random.default_rng(1)
    print(f"mu = {args.mu}, margin 0.5 degrees, top 1 (seconds of fc.plan after a warm-up)")
    print("| part | edges | 3 fingers: s | mode | smallest region | 2 fingers | gap |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    fc.plan(demo_part("triangle"), fingers=3, mu=args.mu, top=1)      # imports, warm-up
    for name, part in parts(args.quick):
        t0 = time.perf_counter()
        three = fc.plan(part, fingers=3, mu=args.mu, top=1)
        dt = time.perf_counter() - t0
        two = fc.plan(part, fingers=2, mu=args.mu, top=1, along_boundary=False)
        two_s = f"{two[0].min_length:.3f}" if two else "none"
        if not three:
            print(f"| {name} | {part.n_edges} | {dt:.2f} | none | | {two_s} | |")
            continue
        p = three[0]
        on_edges = max(len(e) for e in p.region_edges) == 1
        g = f"{gap(part, p, rng):.2f}" if on_edges else "(along the boundary)"
        print(f"| {name} | {part.n_edges} | {dt:.2f} | {p.mode} | {p.min_length:.3f} | "
              f"{two_s} | {g} |")
    main_curved((0.2, 0.3) if args.quick else (0.2, 0.3, 0.5))


def curved() -> list[tuple[str, fc.Polygon]]:
    a90 = np.linspace(0, 2 * np.pi, 90, endpoint=False)
    a120 = np.linspace(0, 2 * np.pi, 120, endpoint=False)
    tri = 40 * (1 + 0.12 * np.cos(3 * a90))
    return [("rounded triangle (90 edges)", fc.Polygon(np.c_[tri * np.cos(a90),
                                                              tri * np.sin(a90)])),
            ("ellipse 50 x 30 (120 edges)", fc.Polygon(np.c_[50 * np.cos(a120),
                                                              30 * np.sin(a120)]))]


def main_curved(mu_values: tuple[float, ...]) -> None:
    print()
    print("curved outlines, top 10 (seconds of fc.plan; regions along the boundary)")
    print("| part | mu | 3 fingers: s | best (mode) | best concurrent in the top 10 | "
          "best single-edge concurrent, grown | 2 fingers |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for name, part in curved():
        for mu in mu_values:
            t0 = time.perf_counter()
            three = fc.plan(part, fingers=3, mu=mu, top=10)
            dt = time.perf_counter() - t0
            two = fc.plan(part, fingers=2, mu=mu, top=1)
            conc = [p for p in three if p.mode == "concurrent"]
            c_s = (f"{conc[0].min_length:.3f} ({max(len(e) for e in conc[0].region_edges)} "
                   f"edges)" if conc else "not in the top 10")
            best = f"{three[0].min_length:.3f} ({three[0].mode})" if three else "none"
            single = [p for p in fc.plan(part, fingers=3, mu=mu, top=10, along_boundary=False)
                      if p.mode == "concurrent"]
            grown = "none"
            if single:
                got = grow_concurrent(part, single[0].edges, mu, np.radians(0.5))
                if got is not None:
                    grown = (f"{single[0].min_length:.3f} -> {got[1].levels.min():.3f} "
                             f"({max(len(e) for e in got[0])} edges)")
            print(f"| {name} | {mu} | {dt:.2f} | {best} | {c_s} | {grown} | "
                  f"{two[0].min_length if two else 0:.3f} |", flush=True)


if __name__ == "__main__":
    main()
