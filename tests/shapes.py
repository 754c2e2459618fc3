"""Seeded random parts for the tests: convex, star-shaped (non-convex), with holes,
rectangles (parallel edges) and regular polygons."""

from __future__ import annotations

import numpy as np

from fcgrasp.model.polygon import Polygon


def convex(rng, n=None):
    n = int(rng.integers(3, 9)) if n is None else n
    ang = np.sort(rng.uniform(0, 2 * np.pi, n))
    return np.column_stack([np.cos(ang), np.sin(ang)]) * rng.uniform(0.5, 2.0)


def star(rng, n=None):
    n = int(rng.integers(5, 12)) if n is None else n
    ang = np.sort(rng.uniform(0, 2 * np.pi, n))
    r = rng.uniform(0.4, 1.0, n)
    return np.column_stack([r * np.cos(ang), r * np.sin(ang)])


def rectangle(rng):
    w, h = rng.uniform(0.3, 2.0, 2)
    pts = np.array([[0, 0], [w, 0], [w, h], [0, h]], float)
    a = rng.choice([0.0, rng.uniform(0, np.pi)])
    rot = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
    return pts @ rot.T


def random_polygon(rng, kind=None):
    kind = kind or str(rng.choice(["convex", "star", "holes", "rectangle", "regular"]))
    for _ in range(100):
        try:
            if kind == "convex":
                return Polygon(convex(rng))
            if kind == "star":
                return Polygon(star(rng))
            if kind == "rectangle":
                return Polygon(rectangle(rng)[::rng.choice([1, -1])])
            if kind == "regular":
                n = int(rng.integers(3, 9))
                a = np.arange(n) * 2 * np.pi / n + rng.uniform(0, 1)
                return Polygon(np.column_stack([np.cos(a), np.sin(a)]))
            if kind == "holes":
                outer = convex(rng, int(rng.integers(4, 9))) * 3
                hole = star(rng, int(rng.integers(3, 7))) * 0.5
                if rng.random() < 0.5:
                    hole = hole[::-1]
                return Polygon(outer, [hole])
        except ValueError:
            continue
    raise AssertionError("could not draw a valid polygon")


# ------------------------------------------------------------ exactly parallel edges


def _zonotope(gens):
    """Vertices of the zonotope of integer generators (exactly parallel opposite sides)."""
    g = np.asarray(gens, float)
    g = np.where((g[:, 1] < 0)[:, None] | ((g[:, 1] == 0) & (g[:, 0] < 0))[:, None], -g, g)
    g = g[np.argsort(np.arctan2(g[:, 1], g[:, 0]))]
    steps = np.concatenate([g, -g])
    return np.cumsum(steps, axis=0)


def parallel_ring(rng, kind):
    """Integer vertices of a part whose edges come in exactly parallel families."""
    r = lambda lo, hi: int(rng.integers(lo, hi))  # noqa: E731
    if kind == "rectangle":
        w, h = r(2, 60), r(2, 60)
        return [[0, 0], [w, 0], [w, h], [0, h]]
    if kind == "L":
        a, d = r(10, 80), r(10, 80)
        c, b = r(2, a - 2), r(2, d - 2)
        return [[0, 0], [a, 0], [a, b], [c, b], [c, d], [0, d]]
    if kind == "T":
        w, H = r(12, 80), r(12, 80)
        s0 = r(1, w // 2 - 1)
        s1 = r(w // 2 + 1, w - 1)
        h = r(2, H - 2)
        return [[s0, 0], [s1, 0], [s1, h], [w, h], [w, H], [0, H], [0, h], [s0, h]]
    if kind == "U":
        w, H = r(12, 80), r(12, 80)
        t = r(1, w // 2 - 1)
        b = r(1, H - 2)
        return [[0, 0], [w, 0], [w, H], [w - t, H], [w - t, b], [t, b], [t, H], [0, H]]
    if kind == "Z":
        W, H = r(12, 80), r(12, 80)
        t = r(1, H // 3)
        p = r(1, W // 2)
        return [[0, 0], [W, 0], [W, t], [p, t], [W, H - t], [W, H], [0, H], [0, H - t],
                [W - p, H - t], [0, t]]
    if kind in ("zonotope", "hexagon"):
        k = 3 if kind == "hexagon" else r(2, 5)
        gens = rng.integers(-20, 21, size=(k, 2))
        return _zonotope(gens).tolist()
    raise ValueError(kind)


PARALLEL_KINDS = ("rectangle", "L", "T", "U", "Z", "zonotope", "hexagon")


def parallel_polygon(rng, kind=None):
    """A seeded part with exactly parallel edges: axis-aligned or turned by a quarter turn
    (still exact), either orientation, scaled by a power of two (exact)."""
    for _ in range(200):
        k = kind or str(rng.choice(PARALLEL_KINDS))
        pts = np.array(parallel_ring(rng, k), float)
        quarter = int(rng.integers(0, 4))
        for _ in range(quarter):
            pts = pts @ np.array([[0.0, 1.0], [-1.0, 0.0]])
        if rng.random() < 0.5:
            pts = pts[::-1]
        pts = pts * 2.0 ** int(rng.integers(-3, 4))
        try:
            return Polygon(pts)
        except ValueError:
            continue
    raise AssertionError("could not draw a valid polygon with parallel edges")
