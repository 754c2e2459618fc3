"""A clock that ends a search's time budget after a given number of looks at it, for
the tests of searches stopped inside (no test depends on how busy the machine is)."""

from __future__ import annotations

from fcgrasp.core import budget


def clock_ending_after(looks):
    """A stand-in for :func:`fcgrasp.core.budget.cut_if_over` that says the budget has
    ended from the ``looks + 1``-th call on (recording the search as cut short, as the
    real one does), and before that asks the real one."""
    real = budget.cut_if_over
    calls = [0]

    def clock(counted=True):
        calls[0] += 1
        if calls[0] > looks:
            budget.cut_short()
            return True
        return real(counted)

    return clock
