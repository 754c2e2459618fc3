"""The tie-break of four-finger plans before it was batched (one placement per
tied option and row, in a Python loop), kept as the reference of
:func:`fcgrasp.pipeline._solve._break_ties` (``tests/test_pipeline.py``).  Its first stage
(which options reach the same smallest region) was not changed by the batching and is
shared: :func:`fcgrasp.pipeline._solve.tie_options`."""

from __future__ import annotations

from typing import Any

import numpy as np

from fcgrasp.model.plans import geometric_key
from fcgrasp.pipeline._candidates import _lex_greater
from fcgrasp.pipeline._solve import _place, _region_ends, tie_options


def break_ties(polygon, c, rows, a, b, lengths, mode, margin):
    """Among pairings and modes with the same leximin levels (corollary 5.1 makes them
    equivalent without a margin), place the regions of each and keep the placement of
    least :func:`geometric_key`, so that a renumbered part gets the same regions.

    Updates ``c.perm`` for ``rows`` and returns the modes.  Rows where two fingers share
    an edge keep their split search's answer.
    """
    mode = mode.copy()
    found = tie_options(polygon, c, rows, a, b, lengths, margin)     # unchanged stage 1
    if found is None:
        return mode
    sel, options = found
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

