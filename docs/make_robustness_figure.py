"""Make docs/robustness.png, the README's picture of what a plan carries and how likely it
is to hold: on ``demo:quad`` with two fingers (mu 0.3), the best plans (two here)' regions
coloured by the load scale every grasp of them carries (0.3 kg, fingers of at most 10 N,
accelerations up to 2 m/s^2 in x and y: fc.region_payload, certified), and each plan's
probability of holding against the placement error along the boundary (exact,
fc.placement_probability) and against the part's pose error (fc.pose_probability, with
its 99 % interval):

    .venv/bin/python docs/make_robustness_figure.py
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import fcgrasp as fc  # noqa: E402
from fcgrasp.plotting import draw_part, save_figure  # noqa: E402

OUT = Path(__file__).resolve().parent / "robustness.png"
COLORS = ["#d62728", "#1f77b4", "#2ca02c"]


def main() -> None:
    part = fc.read_part("demo:quad")
    plans = fc.plan(part, fingers=2, mu=0.3, top=3)
    load = fc.Load(mass=0.3, accel=(2.0, 2.0))
    scales = [fc.region_payload(part, p, load, force_limit=10).lower for p in plans]
    fig, (left, mid, right) = plt.subplots(1, 3, figsize=(13, 4.2), layout="compressed")
    draw_part(left, part, numbers=False, units="mm")
    cmap = plt.get_cmap("viridis")
    top = max(scales)
    for p, s in zip(plans, scales, strict=True):
        for reg in p.regions:
            left.plot(*np.asarray(reg).T, color=cmap(s / top), lw=6, solid_capstyle="butt")
    sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(0, top))
    fig.colorbar(sm, ax=left, label="load scale every grasp carries (x 0.3 kg)")
    left.set_title("regions by the load they carry (10 N fingers)", fontsize=9)
    sig = np.linspace(0.25, 8, 24)
    for k, (p, c) in enumerate(zip(plans, COLORS, strict=False)):
        label = f"rank {k + 1}: edges {list(p.edges)}"
        mid.plot(sig, [fc.placement_probability(part, p, s) for s in sig], color=c,
                 label=label)
        est = [fc.pose_probability(part, p, (s, s, s)) for s in sig]
        right.errorbar(sig, [e.probability for e in est], yerr=[e.error for e in est],
                       color=c, label=label, capsize=2)
    mid.set_xlabel("placement error along the boundary, sigma (mm)")
    right.set_xlabel("pose error, sigma (mm in x and y, degrees)")
    for ax in (mid, right):
        ax.set_ylabel("probability that the grasp holds")
        ax.set_ylim(0, 1.02)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="lower left")
    mid.set_title("fingers off target (exact)", fontsize=9)
    right.set_title("part off its pose (quasi-Monte Carlo, 99 % interval)", fontsize=9)
    save_figure(fig, str(OUT))
    plt.close(fig)


if __name__ == "__main__":
    main()
