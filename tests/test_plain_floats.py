"""Plain-float forms of per-plan helpers (a plan's few numbers, where numpy's
calls cost more than the arithmetic) against their previous numpy forms, kept here or
beside them: the same numbers, bit for bit, on seeded cases, values at the rounding's
halfway points included."""

from __future__ import annotations

import numpy as np

from fcgrasp.core import _geom


class _Part:
    def __init__(self, centroid: np.ndarray, size: float) -> None:
        self.centroid, self.size = centroid, size


def _halfway_values(rng: np.random.Generator, shape: tuple[int, ...]) -> np.ndarray:
    """Values whose scaled rounding falls on a half (``k + 0.5`` ten-billionths)."""
    return (np.round(rng.normal(size=shape) * 1e9) + 0.5) / 1e9


def test_keys_are_the_numpy_keys() -> None:
    rng = np.random.default_rng(11)
    tested = 0
    for _ in range(4000):
        part = _Part(rng.normal(size=2) * rng.choice([1.0, 1e3, 1e-3]),
                     float(rng.uniform(0.01, 1e4)))
        regions = []
        for _ in range(int(rng.integers(1, 5))):
            m = int(rng.integers(1, 5))
            unit = _halfway_values(rng, (m, 2)) if rng.random() < 0.3 else \
                rng.normal(size=(m, 2))
            regions.append(unit * part.size + part.centroid)
        got, want = _geom.geometric_key(regions, part), \
            _geom._geometric_key_numpy(regions, part)
        assert got == want
        assert [np.signbit(x) for x in got] == [np.signbit(x) for x in want]
        lengths = (_halfway_values(rng, (len(regions),)) if rng.random() < 0.3 else
                   rng.uniform(0, 2, len(regions))) * part.size
        got, want = _geom.leximin_key(lengths, part.size), \
            _geom._leximin_key_numpy(lengths, part.size)
        assert got == want
        assert [np.signbit(x) for x in got] == [np.signbit(x) for x in want]
        assert _geom.leximin_key(list(lengths), part.size) == want
        tested += 1
    assert tested == 4000
    # not finite: the numpy forms answer
    part = _Part(np.zeros(2), 1.0)
    inf = [np.array([[np.inf, 0.0], [1.0, 1.0]])]
    assert _geom.geometric_key(inf, part) == _geom._geometric_key_numpy(inf, part)
    assert _geom.leximin_key([np.inf, 1.0], 1.0) == _geom._leximin_key_numpy([np.inf, 1.0], 1.0)


def _previous_stretch_ends(ring, i, k, s0, t):
    """``stretches._stretch_ends`` before it read plain floats (numpy points, its
    ``_span`` written in)."""
    from fcgrasp.core.tolerances import ROUND_TOL

    m = ring.m
    first = ring.a[i % m] + s0 * ring.t[i % m]
    if k == 0:
        return np.stack((first, first + t * ring.t[i % m]))
    j = i % m + m
    off = ring.L[i % m] - s0 + float(ring.U[j + k] - ring.U[j + 1])
    last = ring.a[(i + k) % m] + (t - off) * ring.t[(i + k) % m]
    tiny = ROUND_TOL * float(ring.U[m])
    inner_first, inner_last = ring.a[(i + 1) % m], ring.a[(i + k) % m]
    covered = k + 1
    if np.hypot(*(inner_first - first)) <= tiny:
        first, covered = inner_first, covered - 1
    if covered > 1 and np.hypot(*(last - inner_last)) <= tiny:
        last = inner_last
    return np.stack((first, last))


def test_stretch_ends_are_the_previous_ends() -> None:
    """Outlines of 3-59 edges, starts around the ring and beyond, regions from a vertex
    and ending at one (trimmed), crossing up to every vertex; and the ends of the
    region polyline itself."""
    from fcgrasp.model.stretches._placement import _polyline, _stretch_ends

    from .test_stretches import random_ring

    rng = np.random.default_rng(5)
    trimmed = 0
    for _ in range(150):
        ring = random_ring(rng)
        for _ in range(40):
            i, k = int(rng.integers(0, 3 * ring.m)), int(rng.integers(0, ring.m - 1))
            L = float(ring.L[i % ring.m])
            s0 = float(rng.choice([0.0, L, L * (1 - 1e-15), float(rng.uniform(0, L))]))
            if rng.random() < 0.3 and k:    # to end at (or just by) the last vertex
                j = i % ring.m + ring.m
                t = float(L - s0 + ring.U[j + k] - ring.U[j + 1]) * (1 + rng.choice([0, 1e-15]))
            else:
                t = float(rng.uniform(0, 10))
            got = np.array(_stretch_ends(ring, i, k, s0, t))
            want = _previous_stretch_ends(ring, i, k, s0, t)
            assert np.array_equal(got, want)
            pts, _ = _polyline(ring, i, k, s0, t)
            assert np.array_equal(got, pts[[0, -1]])
            trimmed += len(pts) < k + 2
    assert trimmed > 100
