"""A parallel jaw on demo:rectangle: the best proved box of poses."""
import matplotlib.pyplot as plt

import fcgrasp as fc
from fcgrasp.plotting import draw_jaw_plan

jaw = fc.ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
part = fc.read_part("demo:rectangle")
box = fc.plan(part, gripper=jaw, top=1)[0]
fig, ax = plt.subplots(figsize=(5, 3))
draw_jaw_plan(ax, part, box, title=f"a proved box: {box.measure:.3g} mm")
