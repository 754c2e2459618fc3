"""What a reader finds in a file, before units, flips and clean-up (private to parts)."""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable
from dataclasses import dataclass, field

from shapely.geometry import Polygon as ShapelyPolygon

#: Largest turn of the tangent along one flattened edge, in degrees: curves are split
#: until every piece is within the flattening tolerance of its chord *and* turns at most
#: this much, so that the contact normals follow the curve and regions along the boundary
#: do not depend on the tolerance (issue 12: within 2% at 1/200 and 1/5000 of the size).
MAX_TURN_DEG = 1.0


def flatten_curve(point: Callable[[float], complex], tol: float, out: list[complex],
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
        flatten_curve(point, tol, out, depth + 1, t0, tm)
        flatten_curve(point, tol, out, depth + 1, tm, t1)
    else:
        out.append(p1)


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
