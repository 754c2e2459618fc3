"""The JSON family of part formats: fcgrasp's JSON (vertices and holes), GeoJSON and
WKT, and :func:`read_json`, the one reader of every JSON input."""

from __future__ import annotations

import json
from dataclasses import replace
from typing import Any

import numpy as np

from ..model.polygon import Polygon
from ._drawing import Drawing, Shape
from .units import FILE_UNITS, check_units

# ----------------------------------------------------------------------------- JSON family


def _as_shape(outer: Any, holes: list[Any], where: str, sid: str | None = None,
              tags: tuple[str, ...] = ()) -> Shape:
    try:
        poly = Polygon(outer, holes)
    except (ValueError, TypeError) as exc:
        raise ValueError(f"{where}: {exc}") from None
    return Shape(poly.to_shapely(), sid, tags)


def _rings_depth(data: Any) -> int:
    d = 0
    while isinstance(data, list) and data:
        data, d = data[0], d + 1
    return d


def _json_drawing(data: Any, where: str) -> Drawing:
    if isinstance(data, list):                  # bare rings
        depth = _rings_depth(data)
        if depth == 2:
            return Drawing([_as_shape(data, [], where)])
        if depth == 3:
            return Drawing([_as_shape(data[0], data[1:], where)])
        raise ValueError(f"{where}: a bare JSON part is a ring [[x, y], ...] or rings "
                         f"[[[x, y], ...], ...] (outer ring, then holes)")
    if not isinstance(data, dict):
        raise ValueError(f"{where}: expected an object with 'vertices' or a GeoJSON "
                         f"geometry, got {type(data).__name__}")
    if "vertices" in data:
        extra = sorted(set(data) - {"vertices", "holes", "units"})
        if extra:
            raise ValueError(f"{where}: unknown key {extra[0]!r} (a part is "
                             f"{{'vertices': [...], 'holes': [...], 'units': 'mm'}})")
        holes = data.get("holes", [])
        if not isinstance(holes, list):
            raise ValueError(f"{where}: 'holes' must be a list of rings")
        units = data.get("units")
        if units is not None:
            try:
                check_units(units, "'units'", FILE_UNITS)
            except (TypeError, ValueError) as exc:
                raise ValueError(f"{where}: {exc}") from None
        return Drawing([_as_shape(data["vertices"], holes, where)], units,
                       f"'units' of the JSON: {units}" if units else "not given by the file")
    if "type" in data:
        shapes = _geojson_shapes(data, where)
        return Drawing(shapes, notes=_z_notes(shapes))
    raise ValueError(f"{where}: no 'vertices' and no GeoJSON 'type'")


def _feature_tags(feat: dict[str, Any], k: int) -> tuple[str, ...]:
    tags = []
    if feat.get("id") is not None:
        tags.append(str(feat["id"]))
    props = feat.get("properties")
    if isinstance(props, dict):
        for key, v in props.items():
            if key.lower() in ("name", "id", "label", "part", "admin", "name_en") and \
                    isinstance(v, (str, int)) and not isinstance(v, bool):
                tags.append(str(v))
    return tuple(dict.fromkeys(tags)) or (f"feature{k}",)


def _geojson_shapes(data: dict[str, Any], where: str) -> list[Shape]:
    import shapely.geometry
    from shapely.errors import ShapelyError

    kind = data.get("type")
    items: list[tuple[Any, tuple[str, ...], str]] = []
    if kind == "FeatureCollection":
        feats = data.get("features")
        if not isinstance(feats, list):
            raise ValueError(f"{where}: a FeatureCollection needs a 'features' list")
        for k, feat in enumerate(feats):
            if not isinstance(feat, dict) or feat.get("type") != "Feature":
                raise ValueError(f"{where} features[{k}]: expected a Feature object")
            items.append((feat.get("geometry"), _feature_tags(feat, k),
                          f"{where} features[{k}]"))
    elif kind == "Feature":
        items.append((data.get("geometry"), _feature_tags(data, 0), f"{where} geometry"))
    else:
        items.append((data, (), where))
    shapes: list[Shape] = []
    kinds = set()
    for geom, tags, w in items:
        if geom is None:
            continue
        if not isinstance(geom, dict):
            raise ValueError(f"{w}: geometry must be an object")
        try:
            with np.errstate(invalid="ignore"):   # NaN: refused below, in one line
                g = shapely.geometry.shape(geom)
        except (ShapelyError, ValueError, TypeError, KeyError, IndexError,
                AttributeError) as exc:
            raise ValueError(f"{w}: not a valid GeoJSON geometry ({exc})") from None
        kinds.add(g.geom_type)
        shapes += _polygons_of(g, w, tags)
    if not shapes:
        raise ValueError(f"{where}: no Polygon or MultiPolygon (found "
                         f"{', '.join(sorted(kinds)) or 'no geometry'})")
    return shapes


def _polygons_of(g: Any, where: str, tags: tuple[str, ...]) -> list[Shape]:
    import shapely

    polys = [p for p in shapely.get_parts(g) if p.geom_type == "Polygon" and not p.is_empty]
    had_z = [bool(shapely.has_z(p)) for p in polys]
    polys = [shapely.force_2d(p) for p in polys]           # a planar part: Z is dropped
    out = []
    base = tags[0] if tags else None
    for j, p in enumerate(polys):
        sid = base if len(polys) == 1 else (f"{base}#{j + 1}" if base else f"#{j + 1}")
        holes = [np.asarray(h.coords) for h in p.interiors]
        shape = _as_shape(np.asarray(p.exterior.coords), holes,
                          where + (f" polygon {j + 1}" if len(polys) > 1 else ""), sid,
                          (*tags, sid) if sid else tags)
        out.append(replace(shape, had_z=had_z[j]))
    return out


def _z_notes(shapes: list[Shape]) -> list[str]:
    """The note a drawing gets when Z coordinates were dropped from its polygons."""
    return ["Z coordinates dropped: a part is planar, its outline taken in x, y"] \
        if any(s.had_z for s in shapes) else []


def _wkt_drawing(text: str, where: str) -> Drawing:
    import shapely
    from shapely.errors import ShapelyError

    def parse(t: str) -> Any:
        with np.errstate(invalid="ignore"):       # NaN: refused below, in one line
            return shapely.from_wkt(t.strip())

    geoms: list[tuple[Any, str, str | None]]
    try:
        geoms = [(parse(text), where, None)]
    except (ShapelyError, ValueError):
        geoms = []
        for k, line in enumerate(text.splitlines(), start=1):
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            try:
                geoms.append((parse(line), f"{where} line {k}", f"line{k}"))
            except (ShapelyError, ValueError) as exc:
                raise ValueError(f"{where} line {k}: not valid WKT "
                                 f"({str(exc).splitlines()[0]})") from None
    if not geoms:
        raise ValueError(f"{where}: empty WKT file")
    shapes: list[Shape] = []
    kinds = set()
    for g, w, tag in geoms:
        if g is None or g.is_empty:
            continue
        kinds.add(g.geom_type)
        shapes += _polygons_of(g, w, (tag,) if tag else ())
    if not shapes:
        raise ValueError(f"{where}: no polygon (found {', '.join(sorted(kinds)) or 'empty'})")
    return Drawing(shapes, notes=_z_notes(shapes))


def _text(data: bytes, spec: str) -> str:
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ValueError(f"{spec}: not UTF-8 text (byte {exc.start})") from None


def read_json(data: bytes | str, spec: str) -> Any:
    """The value of a JSON text (bytes in UTF-8, a BOM allowed): the one reader of every
    JSON input (part files, contacts, the explorer's requests).  Malformed, nested too
    deeply or not UTF-8: a one-line :class:`ValueError` starting with ``spec``."""
    text = _text(data, spec) if isinstance(data, bytes) else data
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise ValueError(f"{spec}: not valid JSON ({exc.msg} at line {exc.lineno} column "
                         f"{exc.colno})") from None
    except RecursionError:
        raise ValueError(f"{spec}: JSON nested too deeply") from None

