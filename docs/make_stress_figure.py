"""Draw docs/stress.png: the last frame of a stress test's animation (fcgrasp.physics):
the best two-finger plan of demo:blob at mu 0.5, a grasp at its regions' middles, a
seeded disturbance ramped until the part slips, beside the certified payload.

    .venv/bin/python docs/make_stress_figure.py
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import imageio.v3 as iio
import numpy as np

import fcgrasp as fc
from fcgrasp.io.parts import demo_part
from fcgrasp.physics import animate, sample_grasps, stress_test

poly = demo_part("blob")
plan = fc.plan(poly, fingers=2, mu=0.5, top=1)[0]
pts, nrm = sample_grasps(poly, plan.regions, 3, np.random.default_rng(0))[2]
res = stress_test(poly, pts, nrm, 0.5, [0.6, 0.8, 0.0], record=True)
with tempfile.TemporaryDirectory() as tmp:
    gif = Path(tmp) / "stress.gif"
    animate(poly, res, str(gif), frames=8)
    iio.imwrite(Path(__file__).with_name("stress.png"), iio.imread(gif, index=None)[-1])
print(f"certified {res.certified_payload:.2f} N, slipped at {res.slip_load} N")
