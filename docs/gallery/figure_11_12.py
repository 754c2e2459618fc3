"""Figures 11 and 12 (theorems 6.3, 6.4 and algorithm 7.1): two fingers with friction
on two edges. Left, the grasp set: the edges' friction cones, and the restricted edges
e'_1, e'_2 from which the fingers see each other through both cones (squeezing, and
expanding where the part allows it). Right, the optimal independent regions inside them:
any finger anywhere in its region holds the part."""
import matplotlib.pyplot as plt
import numpy as np

import fcgrasp as fc
from fcgrasp.plotting import draw_part

part = fc.read_part("demo:blob")
mu = 0.3
best = fc.plan(part, fingers=2, mu=mu, top=1)[0]
gs = fc.grasp_set(part, best.edges, mu=mu)
regions = fc.independent_regions(part, best.edges, mu=mu)

fig, axes = plt.subplots(1, 2, figsize=(8, 4))
draw_part(axes[0], part, keep=best.edges)
half = np.arctan(mu)
for finger, edge in enumerate(best.edges):
    mid = (part.starts[edge] + part.ends[edge]) / 2
    inward = -part.normals[edge]
    for side in (-1, 1):                        # the cone's two extreme rays
        c, s = np.cos(side * half), np.sin(side * half)
        ray = np.array([c * inward[0] - s * inward[1], s * inward[0] + c * inward[1]])
        axes[0].plot(*np.c_[mid, mid + 0.25 * part.size * ray], color="C1", lw=1)
    for seg in gs.restricted_segments(finger):
        axes[0].plot(*seg.T, color="C3", lw=4, solid_capstyle="butt")
axes[0].set_title(f"grasp set on edges {best.edges}, mu {mu}", fontsize=9)
draw_part(axes[1], part, keep=best.edges)
for region in regions.regions:
    axes[1].plot(*np.asarray(region).T, color="C2", lw=5, solid_capstyle="butt")
axes[1].set_title(f"independent regions, {regions.min_length:.1f} mm each", fontsize=9)
for ax in axes:
    ax.set_aspect("equal")
