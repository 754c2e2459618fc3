"""The stretch search's closed form over every ordered pair of rows (``_lp._eliminate``'s
Fourier-Motzkin step and ``_lp._t_bounds``), before each configuration's rows of either
sign were gathered into blocks: the oracle of ``tests/test_stretches.py`` (the same rows
and bounds, bit for bit).  Frozen: do not edit."""

from __future__ import annotations

import numpy as np

from fcgrasp.model.stretches._windows import _EPS


def t_bounds_every_pair(r):
    c0, cu, ct = r[:, :, 0], r[:, :, 1], r[:, :, 2]
    pos, neg = cu > _EPS, cu < -_EPS
    with np.errstate(divide="ignore", invalid="ignore"):
        al = np.where(pos | neg, -c0 / cu, 0.0)
        ga = np.where(pos | neg, -ct / cu, 0.0)
    D = ga[:, :, None] - ga[:, None, :]
    E = al[:, None, :] - al[:, :, None]
    valid = pos[:, :, None] & neg[:, None, :]
    zero = ~(pos | neg)
    with np.errstate(divide="ignore", invalid="ignore"):
        q = E / D
        qz = -c0 / ct
    hi = np.min(np.where(valid & (D > _EPS), q, np.inf), axis=(1, 2))
    lo = np.max(np.where(valid & (D < -_EPS), q, -np.inf), axis=(1, 2))
    hi = np.minimum(hi, np.min(np.where(zero & (ct < -_EPS), qz, np.inf), axis=1))
    lo = np.maximum(lo, np.max(np.where(zero & (ct > _EPS), qz, -np.inf), axis=1))
    flat = np.minimum(np.min(np.where(valid & (np.abs(D) <= _EPS), E, np.inf), axis=(1, 2)),
                      np.min(np.where(zero & (np.abs(ct) <= _EPS), c0, np.inf), axis=1))
    return lo, hi, flat


def eliminate_every_pair(rows, var):
    B, R, K = rows.shape
    a = rows[:, :, var]
    pos, neg = a > _EPS, a < -_EPS
    with np.errstate(divide="ignore", invalid="ignore"):
        rp = np.where(pos[..., None], rows / np.abs(a)[..., None], 0.0)
        rn = np.where(neg[..., None], rows / np.abs(a)[..., None], 0.0)
    pairs = (rp[:, :, None, :] + rn[:, None, :, :]).reshape(B, R * R, K)
    valid = (pos[:, :, None] & neg[:, None, :]).reshape(B, R * R)
    zero = ~(pos | neg)
    out = np.concatenate([pairs, np.where(zero[..., None], rows, 0.0)], axis=1)
    valid = np.concatenate([valid, zero], axis=1)
    keep = np.delete(out, var, axis=2)
    trivial = np.zeros(K - 1)
    trivial[0] = 1.0
    keep = np.where(valid[..., None], keep, trivial)
    width = max(int(valid.sum(axis=1).max(initial=0)), 1)
    order = np.argsort(~valid, axis=1, kind="stable")[:, :width]
    return np.take_along_axis(keep, order[..., None], axis=1)
