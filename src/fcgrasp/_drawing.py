"""What a reader finds in a file, before units, flips and clean-up (private to parts)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from shapely.geometry import Polygon as ShapelyPolygon

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


@dataclass
class Drawing:
    """Every shape of a file, with what the file says about its units."""

    shapes: list[Shape]
    units: str | None = None              # file units (see fcgrasp.units.MM_PER), None: unsaid
    units_note: str = "not given by the file"
    y_down: bool = False                  # the file's y axis points down
    notes: list[str] = field(default_factory=list)
