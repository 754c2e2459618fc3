"""Optimality bounds: for three fingers with friction and four frictionless
fingers on the built-in parts (and a 24-edge ellipse), the best plan's smallest region,
the proved upper bound on any plan's (:func:`fcgrasp.optimum_upper_bound`), the gap
``1 - plan / bound`` and the seconds the bound took (the plan's own seconds beside it).

    .venv/bin/python benchmarks/bench_bounds.py
"""

from __future__ import annotations

import time

import numpy as np

import fcgrasp as fc
from fcgrasp.io.parts import demo_part


def parts() -> list[tuple[str, fc.Polygon]]:
    t = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    out = [(name, demo_part(name)) for name in ("triangle", "quad", "blob", "rectangle",
                                                "bracket", "washer")]
    return out + [("ellipse 40 x 25, 24 edges", fc.Polygon(np.c_[40 * np.cos(t),
                                                                  25 * np.sin(t)]))]


def main() -> None:
    print("| part | fingers | best plan | upper bound | gap | plan (s) | bound (s) | boxes |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for name, poly in parts():
        for fingers, mu in ((3, 0.5), (4, 0.0)):
            t0 = time.perf_counter()
            plans = fc.plan(poly, fingers=fingers, top=1, **({"mu": mu} if mu else {}))
            t1 = time.perf_counter()
            best = plans[0].min_length if plans else 0.0
            b = fc.optimum_upper_bound(poly, fingers, mu, lower=best)
            t2 = time.perf_counter()
            label = f"{fingers}" + (f", mu {mu:g}" if mu else ", frictionless")
            print(f"| {name} | {label} | {best:.4g} | {b.value:.4g} | {100 * b.gap:.1f} % "
                  f"| {t1 - t0:.2f} | {t2 - t1:.2f} | {b.nodes} |", flush=True)


if __name__ == "__main__":
    main()
