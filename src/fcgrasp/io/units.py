"""Units of length: what a part's coordinates mean, and conversions between them.

A part read from a file is converted to one of :data:`UNITS` (``--units``, default
millimetres) from what the file says: SVG lengths are CSS pixels at 96 per inch unless the
drawing gives real units (``width="100mm"`` with a ``viewBox``), DXF drawings carry
``$INSUNITS``, images have no unit until a pixel size is given (their coordinates are then
``"px"``).  JSON, GeoJSON and WKT carry no unit: their coordinates are taken to be in the
units asked, unless ``file_units`` says otherwise.

Examples
--------
>>> conversion("in", "mm")
25.4
>>> round(conversion("px", "in"), 6)      # 96 CSS pixels per inch
0.010417
"""

from __future__ import annotations

from typing import Any

__all__ = ["UNITS", "FILE_UNITS", "MM_PER", "check_units", "conversion", "disturbance_step"]

#: Millimetres per unit, for every unit a file may be in.
MM_PER: dict[str, float] = {
    "nm": 1e-6, "um": 1e-3, "mm": 1.0, "cm": 10.0, "dm": 100.0, "m": 1000.0, "km": 1e6,
    "in": 25.4, "ft": 304.8, "yd": 914.4, "mi": 1609344.0, "mil": 0.0254, "uin": 2.54e-5,
    "px": 25.4 / 96.0, "pt": 25.4 / 72.0, "pc": 25.4 / 6.0,
}
#: Units a part can be converted to (``--units``).
UNITS = ("mm", "cm", "m", "in")
#: Units a file may be declared in (``--file-units``).
FILE_UNITS = tuple(MM_PER)


def check_units(value: Any, name: str = "units", allowed: tuple[str, ...] = UNITS) -> str:
    """A unit name from ``allowed``, or a ValueError naming the argument and the value."""
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a unit name ({', '.join(allowed)}), got {value!r}")
    if value not in allowed:
        raise ValueError(f"{name} must be one of {', '.join(allowed)}, got {value!r}")
    return value


def conversion(source: str, target: str) -> float:
    """Factor that turns a length in ``source`` units into ``target`` units."""
    return MM_PER[check_units(source, "source", FILE_UNITS)] / \
        MM_PER[check_units(target, "target", FILE_UNITS)]


def disturbance_step(units: str) -> float:
    """The translation of the resistance measure's disturbance (section 8.1): 1 cm in the
    part's units, or 10 pixels for an image without a pixel size."""
    return 10.0 if units == "px" else conversion("cm", units)
