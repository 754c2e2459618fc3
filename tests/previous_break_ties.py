"""The tie-break of four-finger plans before it was batched (issue 30: one placement per
tied option and row, in a Python loop), kept as the reference of
:func:`fcgrasp.pipeline._solve._break_ties` (``tests/test_pipeline.py``)."""

from __future__ import annotations

from typing import Any

import numpy as np

from fcgrasp.core.sectors import PAIRINGS
from fcgrasp.core.tolerances import RANK_TOL
from fcgrasp.model._regiongeom import four_finger_problems
from fcgrasp.model.plans import geometric_key
from fcgrasp.model.regions import leximin, max_min_length
from fcgrasp.pipeline._candidates import _lex_greater
from fcgrasp.pipeline._solve import _place, _region_ends


def break_ties(polygon, c, rows, a, b, lengths, mode, margin):
    """Among pairings and modes with the same leximin levels (corollary 5.1 makes them
    equivalent without a margin), place the regions of each and keep the placement of
    least :func:`geometric_key`, so that a renumbered part gets the same regions.

    Updates ``c.perm`` for ``rows`` and returns the modes.  Rows where two fingers share
    an edge keep their split search's answer.
    """
    mode = mode.copy()
    if c.feats.shape[1] != 4 or rows.size == 0:
        return mode
    sel = np.flatnonzero(c.feats[rows, 0] != c.feats[rows, 2])
    if sel.size == 0:
        return mode
    # stage 1 first: only rows where a second option reaches the same smallest region
    # need the whole leximin order of every option
    built = []
    reach = np.zeros(sel.size, dtype=int)
    smallest = np.min(np.where(lengths[sel] > 0, lengths[sel], np.inf), axis=1)
    for P in PAIRINGS:
        perm = np.broadcast_to(P, (sel.size, 4)).copy()
        probs = four_finger_problems(a[sel], b[sel], c.center[rows[sel]], perm, margin)[0]
        for m, pr in enumerate(probs):
            mm = np.where(pr.separable, max_min_length(pr, c.tol), -1.0)
            reach += mm >= smallest - RANK_TOL * np.maximum(smallest, polygon.size)
            built.append((P, m, perm, pr))
    keep = reach >= 2
    if not keep.any():
        return mode
    sel = sel[keep]
    options = []                                   # (pairing, mode, levels in finger order)
    for P, m, perm, pr in built:
        inv = np.argsort(perm[keep], axis=1)
        lev = np.where(pr.separable[keep][:, None], leximin(pr.take(keep), c.tol), -1.0)
        options.append((P, m, lev[np.arange(sel.size)[:, None], inv]))
    for i, r in enumerate(sel):
        want = np.maximum(lengths[r], 0.0)[None]
        tied = [(P, m) for P, m, lev in options
                if not _lex_greater(want, lev[i:i + 1])[0]
                and not _lex_greater(lev[i:i + 1], want)[0]]
        if len(tied) < 2:
            continue
        best: tuple[Any, ...] | None = None
        for P, m in tied:
            c.perm[rows[r]] = P
            params = _place(c, rows[r:r + 1], a[r:r + 1], b[r:r + 1], lengths[r:r + 1],
                            np.array([m]), margin)[0]
            real = c.feats[rows[r]] >= 0
            key = geometric_key(_region_ends(a[r][real], b[r][real], params[real]), polygon)
            if best is None or key < best[0]:
                best = (key, P, m)
        assert best is not None
        c.perm[rows[r]] = best[1]
        mode[r] = best[2]
    return mode

