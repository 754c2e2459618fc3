"""Figures 1.b and 1.c: four frictionless fingers on three edges (a triangle) and on four
edges (a quadrilateral)."""
import matplotlib.pyplot as plt

import fcgrasp as fc
from fcgrasp.plotting import draw_plan

fig, axes = plt.subplots(1, 2, figsize=(8, 4))
for ax, name in zip(axes, ("triangle", "quad"), strict=True):
    part = fc.read_part(f"demo:{name}")
    best = fc.plan(part, fingers=4, top=1)[0]
    draw_plan(ax, part, best, title=f"demo:{name}: edges {best.edges}")
