"""Distinct alternatives of any plan kind (fcgrasp.core.alternatives): the rounds that
ask a ranked search for longer lists keep the plans of suppression along the whole
ranked list, written out here as a plain loop over the list."""

import numpy as np
import pytest

from fcgrasp.core.alternatives import Rounds, distinct_rounds, keep_distinct
from fcgrasp.core.budget import deadline, incomplete


def _suppressed(ranked, close):
    """Suppression along the whole list, by hand: a plan is kept unless it is close to
    a plan kept before it."""
    kept = []
    for p in ranked:
        if not any(close(k, p) for k in kept):
            kept.append(p)
    return kept


def _case(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(0, 60))
    ranked = sorted(rng.uniform(0, 100, n).round(1).tolist(), reverse=True)
    width = float(rng.choice([0.0, 0.5, 3.0, 20.0]))

    def close(a, b):
        return abs(a - b) <= width

    return rng, ranked, close


@pytest.mark.parametrize("seed", range(300))
def test_the_rounds_keep_suppressions_plans_of_the_whole_list(seed):
    rng, ranked, close = _case(seed)
    top = int(rng.integers(1, 12))
    rounds = Rounds(first=int(rng.integers(1, 5)), factor=int(rng.integers(2, 5)),
                    share=bool(rng.integers(2)))
    asked = []

    def search(n):
        asked.append(n)
        return ranked[:n]

    def suppress(ps):
        return [g[0] for g in keep_distinct(ps, close)]

    kept, last, stopped = distinct_rounds(search, suppress, top, rounds)
    assert stopped is None
    assert kept == _suppressed(ranked, close)[:top]
    assert asked[0] == rounds.first * top
    assert all(b >= rounds.factor * a for a, b in zip(asked, asked[1:], strict=False))
    assert list(last) == ranked[:asked[-1]]
    # every request but the last found too few, and the last is the only one that could
    # stop: top kept or the list read to its end
    for n in asked[:-1]:
        assert len(_suppressed(ranked[:n], close)) < top and n <= len(ranked)
    assert len(kept) == top or asked[-1] > len(ranked)


@pytest.mark.parametrize("seed", range(100))
def test_a_depth_or_a_search_that_stops_gives_the_answers_first_plans(seed):
    rng, ranked, close = _case(seed)
    top = int(rng.integers(1, 12))
    depth = int(rng.integers(1, 6))
    stop_at = int(rng.integers(1, 80))

    def search(n):
        got = ranked[:n]
        return incomplete(got[:stop_at], "time_limit", None) if n > stop_at else got

    def suppress(ps):
        return _suppressed(ps, close)

    want = _suppressed(ranked, close)[:top]
    kept, last, stopped = distinct_rounds(search, suppress, top, Rounds(depth=depth))
    assert kept == want[:len(kept)]
    if stopped is None:
        assert kept == want
    elif stopped == "depth":
        assert len(last) == depth * top and len(kept) < top
    else:
        assert stopped == "search" and not last.complete and len(kept) < top
    with deadline(None, checks=0):                 # out of time after the first list
        kept, _, stopped = distinct_rounds(lambda n: ranked[:n], suppress, top)
    assert kept == want[:len(kept)]
    assert stopped is None or (stopped == "time_limit" and len(kept) < top)


def test_every_plan_when_top_is_none():
    ranked = [9, 8, 5, 1]
    kept, last, stopped = distinct_rounds(lambda n: ranked if n is None else ranked[:n],
                                          lambda ps: _suppressed(ps, lambda a, b: a - b < 2),
                                          None)
    assert (kept, list(last), stopped) == ([9, 5, 1], ranked, None)


@pytest.mark.parametrize(("field", "kw"), [("first", {"first": 0}),
                                           ("factor", {"factor": 1}),
                                           ("depth", {"depth": 0}),
                                           ("first", {"first": 1.5})])
def test_bad_rounds_name_the_field(field, kw):
    with pytest.raises(ValueError, match=field):
        Rounds(**kw)
