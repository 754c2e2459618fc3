"""The cone program's rows one pair of corners at a time, as
``fcgrasp.spatial.regions._cone_rows`` built them before it built every pair at once:
the reference its rows are compared with, number for number."""

from __future__ import annotations

import math


def cone_rows_loop(f1, f2, alpha, pairs, rows, rhs, cones):
    import clarabel
    import numpy as np

    alphas = (alpha, alpha) if isinstance(alpha, float | int) else alpha
    for axis, half in ((f1.normal, alphas[0]), (-f2.normal, alphas[1])):
        cos_half = math.cos(half)
        for b, m in pairs:
            M = np.zeros((3, 5))
            M[:, 0:2] = -f1.axes.T
            M[:, 2:4] = f2.axes.T
            M[:, 4] = m
            rows.append(-(axis @ M) / cos_half)
            rhs.append(float(axis @ b) / cos_half)
            for k in range(3):
                rows.append(-M[k])
                rhs.append(float(b[k]))
            cones.append(clarabel.SecondOrderConeT(4))
