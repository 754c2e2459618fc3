"""Figure 8 (theorem 6.2, algorithm 6.1): four frictionless fingers on four edges.
Pairing the fingers two by two, the meets of each pair's lines of force fill a
parallelogram; the grasp holds where a point of one sees a point of the other through
the two-sided cone of the pairs' sectors: the regions R_12, R_34 of eq. 40."""
import matplotlib.pyplot as plt
import shapely

import fcgrasp as fc
from fcgrasp.plotting import draw_part

part = fc.read_part("demo:quad")
best = fc.plan(part, fingers=4, top=1)[0]
gs = fc.grasp_set(part, best.edges)
fig, ax = plt.subplots(figsize=(4.5, 4.5))
draw_part(ax, part, keep=best.edges)
for geom, label in ((gs.pi12, "parallelograms Pi_12, Pi_34"), (gs.pi34, None)):
    ring = shapely.get_coordinates(geom.boundary if geom.area > 0 else geom)
    ax.plot(*ring.T, "--", color="C0", lw=1.5, label=label)
for geom, label in ((gs.r12, "regions R_12, R_34 (eq. 40)"), (gs.r34, None)):
    if not geom.is_empty:
        ring = shapely.get_coordinates(geom.boundary if geom.area > 0 else geom)
        ax.fill(*ring.T, alpha=0.3, color="C3", label=label)
ax.legend(fontsize=7, loc="lower right")
ax.set_title(f"four edges {best.edges}: the grasp set", fontsize=9)
ax.set_aspect("equal")
