"""Seeded random parts for the tests: convex, star-shaped (non-convex), with holes,
rectangles (parallel edges) and regular polygons."""

from __future__ import annotations

import numpy as np

from fcgrasp.polygon import Polygon


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
