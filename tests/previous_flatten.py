"""The flattening of curves by binary halving, kept as the reference the
tests compare the equal-turn flattening of :mod:`fcgrasp.io._drawing` with."""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable

import numpy as np

from fcgrasp.io._drawing import MAX_TURN_DEG


def flatten_halving(point: Callable[[float], complex], tol: float, out: list[complex],
                    depth: int = 0, t0: float = 0.0, t1: float = 1.0) -> None:
    """Append the points of a curve ``point(t)``, ``t`` in [t0, t1], after its start:
    pieces are halved until the midpoint of each is within ``tol`` of its chord and the
    piece turns at most :data:`MAX_TURN_DEG` (twice the angle between its half-chords)."""
    p0, p1 = point(t0), point(t1)
    tm = 0.5 * (t0 + t1)
    pm = point(tm)
    chord = p1 - p0
    if abs(chord) > 0:
        dev = abs((pm - p0).real * chord.imag - (pm - p0).imag * chord.real) / abs(chord)
    else:
        dev = abs(pm - p0)
    turn = 0.0
    if abs(pm - p0) > 0 and abs(p1 - pm) > 0:
        turn = 2.0 * abs(cmath.phase((p1 - pm) / (pm - p0)))
    if depth < 18 and (dev > tol or math.degrees(turn) > MAX_TURN_DEG or depth < 2):
        flatten_halving(point, tol, out, depth + 1, t0, tm)
        flatten_halving(point, tol, out, depth + 1, tm, t1)
    else:
        out.append(p1)


def previous_flatten(points: Callable[[np.ndarray], np.ndarray], tol: float,
                     out: list[complex]) -> None:
    """:func:`flatten_halving` with the vectorized curve of the readers."""
    flatten_halving(lambda t: complex(points(np.array([t]))[0]), tol, out)
