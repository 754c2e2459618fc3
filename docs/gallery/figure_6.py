"""Figure 6 (theorem 4.2): three forces resist every translation exactly when their
directions, drawn from one point, leave no half-plane empty: every angle between
neighbours is below pi, their tips' triangle holds the origin."""
import matplotlib.pyplot as plt
import numpy as np

import fcgrasp as fc

cases = {"closure": (90, 210, 330), "no closure": (60, 120, 200)}
fig, axes = plt.subplots(1, 2, figsize=(7, 3.5))
for ax, (name, degrees) in zip(axes, cases.items(), strict=True):
    angles = np.radians(degrees)
    tips = np.c_[np.cos(angles), np.sin(angles)]
    holds = bool(fc.force_direction_closure(tips))
    for t in tips:
        ax.annotate("", xy=t, xytext=(0, 0), arrowprops={"arrowstyle": "-|>", "lw": 2})
    ax.fill(*tips.T, alpha=0.2, color="C2" if holds else "C3")
    ax.plot(0, 0, "ko")
    ax.set_title(f"{name}: force_direction_closure is {holds}", fontsize=9)
    ax.set_aspect("equal")
    ax.set_xlim(-1.3, 1.3)
    ax.set_ylim(-1.3, 1.3)
    ax.axis("off")
