"""Figure 1.a: the best independent regions of two fingers with friction (mu 0.3)."""
import matplotlib.pyplot as plt

import fcgrasp as fc
from fcgrasp.plotting import draw_plan

part = fc.read_part("demo:blob")
best = fc.plan(part, fingers=2, mu=0.3, top=1)[0]
fig, ax = plt.subplots(figsize=(4, 4))
draw_plan(ax, part, best, title=f"two fingers, mu 0.3: edges {best.edges}")
