"""What a reader finds in a file, before units, flips and clean-up (private to parts)."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from shapely.geometry import Polygon as ShapelyPolygon

from ..core.tolerances import CURVE_RESOLUTION

#: Largest turn of the tangent along one flattened edge, in degrees: curves are cut into
#: pieces within the flattening tolerance of their chords that turn at most this much, so
#: that the contact normals follow the curve and regions along the boundary do not depend
#: on the tolerance (within 2% at 1/200 and 1/5000 of the size).  An edge's
#: normal is then within this turn of the curve's normal at every point it stands for
#: (within half of it on a circular arc: the default safety margin, 0.5 degrees).
MAX_TURN_DEG = 1.0

#: The dense samples a curve's turn is measured on turn at most this fraction of
#: :data:`MAX_TURN_DEG` each, and the curve strays from their chords by at most
#: ``1 - _TOL_SHARE`` of the tolerance (intervals are halved until they do, but for the turn
#: not below ``1 - _TOL_SHARE`` of the tolerance, at most :data:`_MAX_HALVINGS` times;
#: a sample still turning more is a corner: a cusp, a fillet finer than the tolerance);
#: a piece's chord keeps its samples within ``_TOL_SHARE`` of it.
_SAMPLE_TURN = 1.0 / 64
_MAX_HALVINGS = 24
_TOL_SHARE = 15.0 / 16.0
#: A piece no longer than this share of the tolerance may turn more than the limit.
_SHORT = 0.25

#: ``points(ts)``: the points of a curve at the parameters ``ts`` (a float array in
#: [0, 1]), as a complex array.
CurvePoints = Callable[[np.ndarray], np.ndarray]


def _dense(points: CurvePoints, tol: float,
           step: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Parameters and points of the curve, every interval halved (all at once, round by
    round) while its middle strays more than ``tol / 16`` from its chord, or while it or
    a sample at its ends turns more than ``step`` and it is longer than ``tol / 16``;
    repeated points dropped.  Also each interval's own turn."""
    ts = np.linspace(0.0, 1.0, 65)
    z = np.asarray(points(ts), dtype=complex)
    for _ in range(_MAX_HALVINGS):
        tm = 0.5 * (ts[:-1] + ts[1:])
        zm = np.asarray(points(tm), dtype=complex)
        h1, h2 = zm - z[:-1], z[1:] - zm
        chord = z[1:] - z[:-1]
        with np.errstate(divide="ignore", invalid="ignore"):
            inner = np.abs(np.angle(h2 / h1))               # twice: the interval's turn
            dev = np.where(np.abs(chord) > 0,
                           np.abs((h1 * chord.conjugate()).imag) / np.abs(chord), np.abs(h1))
            at = np.abs(np.angle(chord[1:] / chord[:-1]))   # at the interior samples
        inner = np.nan_to_num(inner)
        at = np.nan_to_num(at)
        turns = 2 * inner > step
        turns[:-1] |= at > step
        turns[1:] |= at > step
        # no finer than a sixteenth of the tolerance for the turn (a fillet smaller than
        # the tolerance, a cusp): the chord rule holds there already
        split = (turns & (np.abs(chord) > (1.0 - _TOL_SHARE) * tol)) | \
            (dev > (1.0 - _TOL_SHARE) * tol)
        if not split.any():
            break
        where = np.flatnonzero(split) + 1
        ts, z = np.insert(ts, where, tm[split]), np.insert(z, where, zm[split])
    # samples closer than rounding to the last one kept (a stationary point's noise,
    # whose chords point anywhere) are dropped; the curve's end stays
    res = CURVE_RESOLUTION * max(float(np.abs(z - z[0]).max()), float(np.abs(z[0])))
    if np.any(np.abs(np.diff(z)) <= res):
        keep = [0]
        for i in range(1, len(z)):
            if abs(z[i] - z[keep[-1]]) > res:
                keep.append(i)
        if keep[-1] != len(z) - 1 and len(keep) > 1:
            keep[-1] = len(z) - 1
        ts, z = ts[keep], z[keep]
    # each interval's own turn (twice the angle between its half-chords)
    zm = np.asarray(points(0.5 * (ts[:-1] + ts[1:])), dtype=complex)
    with np.errstate(divide="ignore", invalid="ignore"):
        own = np.nan_to_num(2 * np.abs(np.angle((z[1:] - zm) / (zm - z[:-1]))))
    return ts, z, own


def flatten_curve(points: CurvePoints, tol: float, out: list[complex],
                  params: list[float] | None = None) -> None:
    """Append the points of a curve after its start, with as few edges as the two rules
    allow: each piece's tangent turns at most :data:`MAX_TURN_DEG` and its chord is within
    ``tol`` of the curve (flattening that follows the geometry).  ``params``,
    if given, gets the parameter of every point appended.

    The curve is sampled densely (:func:`_dense`); the samples' turn is summed and cut
    into the fewest pieces that keep each piece's turn within the limit, at equal turn
    where that many allow it (:func:`_equal_turn_cuts`), and a piece whose chord strays
    more than ``tol`` from its samples is cut again, each part reaching as far as it
    can (:func:`_split_by_tol`).  A circular arc of 90 degrees gets 92 edges (the
    binary halving before gave 128: every piece turned 0.7 degrees)."""
    limit = math.radians(MAX_TURN_DEG)
    step = _SAMPLE_TURN * limit
    ts, z, own = _dense(points, tol, step)
    if len(z) < 2:                              # a curve that stays at one point
        return
    d = np.diff(z)
    turn = np.abs(np.angle(d[1:] / d[:-1]))     # at the interior samples
    ends = _equal_turn_cuts(z, turn, own, limit, _SHORT * tol)
    start = 0
    for e in ends:
        _split_by_tol(z, ts, start, e, tol, out, params)
        start = e


def _equal_turn_cuts(z: np.ndarray, turn: np.ndarray, own: np.ndarray, limit: float,
                     short: float) -> list[int]:
    """The sample indices that end the pieces (the last sample included): as few pieces
    as keep each piece's tangent turn within ``limit`` (or its chord within ``short``: no
    finer for the turn), cut at equal turn where that count allows it, else where the
    greedy fill cut.

    A piece from sample ``i`` to ``j`` turns at its interior samples (``turn``) and within
    its first and last intervals (``own``): at most ``c[j-1] - c[i] + own[i] + own[j-1]``,
    ``c`` the running sum of ``turn`` (``c[m]`` the turn at samples 1 .. m)."""
    n = len(z)
    c = np.concatenate([[0.0], np.cumsum(turn)])

    def fits(i: np.ndarray | int, j: np.ndarray) -> np.ndarray:
        return (c[j - 1] - c[i] + own[i] + own[j - 1] <= limit) | \
            (np.abs(z[j] - z[i]) <= short)

    greedy, i = [], 0
    while i < n - 1:
        width = 256
        while True:
            j = np.arange(i + 1, min(n, i + 1 + width))
            bad = np.flatnonzero(~fits(i, j))
            if len(bad) or j[-1] == n - 1:
                break
            width *= 4
        i = int(j[bad[0] - 1]) if len(bad) and bad[0] > 0 else \
            (int(j[0]) if len(bad) else int(j[-1]))
        greedy.append(i)
    k, total = len(greedy), float(c[-1])
    if k > 1:
        at = np.searchsorted(c[1:], total * np.arange(1, k) / k) + 1
        cuts = np.array([0, *sorted(set(at.tolist()) - {0, n - 1}), n - 1])
        if len(cuts) == k + 1 and fits(cuts[:-1], cuts[1:]).all():
            return cuts[1:].tolist()
    return greedy


def _split_by_tol(z: np.ndarray, ts: np.ndarray, a: int, b: int, tol: float,
                  out: list[complex], params: list[float] | None) -> None:
    """Append the samples that end the pieces of ``z[a..b]``, ``z[b]`` last: as few as keep
    every sample within ``tol * 15/16`` of its piece's chord (the curve strays at most
    ``tol / 16`` more between samples), each piece reaching as far as it can (found by
    bisection on its end)."""
    def fits(i: int, j: int) -> bool:
        chord = z[j] - z[i]
        rel = z[i + 1:j] - z[i]
        if not len(rel):
            return True
        dev = np.abs((rel * chord.conjugate()).imag) / abs(chord) if abs(chord) > 0 \
            else np.abs(rel)
        return bool(dev.max() <= _TOL_SHARE * tol)

    i = a
    while i < b:
        j = b
        if not fits(i, b):
            lo, hi = i + 1, b             # fits(i, lo) holds, fits(i, hi) does not
            while hi - lo > 1:
                mid = (lo + hi) // 2
                lo, hi = (mid, hi) if fits(i, mid) else (lo, mid)
            j = lo
        out.append(complex(z[j]))
        if params is not None:
            params.append(float(ts[j]))
        i = j


#: ``tol_of(size, file_units)``: the flattening tolerance, in file units, for a drawing
#: ``size`` across (file units), in a file whose units are ``file_units`` (None: unsaid).
TolOf = Callable[[float, "str | None"], float]


@dataclass
class Shape:
    """One filled piece of a drawing, in file coordinates."""

    polygon: ShapelyPolygon
    id: str | None = None                 # element id, handle, feature id, line, blob
    tags: tuple[str, ...] = ()            # every name that selects it (groups, layer, ...)
    layer: str | None = None
    flatten: float | None = None          # flattening tolerance used (file units)
    background: bool = False              # a canvas-filling background (SVG icons)
    had_z: bool = False                   # Z coordinates were dropped (WKT, GeoJSON)


@dataclass
class Drawing:
    """Every shape of a file, with what the file says about its units."""

    shapes: list[Shape]
    units: str | None = None              # file units (see fcgrasp.io.units.MM_PER), None: unsaid
    units_note: str = "not given by the file"
    y_down: bool = False                  # the file's y axis points down
    #: the canvas's height (file units) of a y-down source: y is flipped about it, so the
    #: part keeps the page's positive coordinates (y up from the bottom edge)
    height: float | None = None
    notes: list[str] = field(default_factory=list)
