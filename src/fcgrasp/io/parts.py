"""Reading parts: JSON, GeoJSON, WKT, SVG, DXF, raster silhouettes and built-in examples.

A file may hold several parts: :func:`list_parts` returns them all (like ``ogrinfo`` or
``ezdxf info``), :func:`load_part` picks one (by index, by id, or by default the largest)
with a record of how it was read, and :func:`read_part` returns just its
:class:`~fcgrasp.Polygon`.  A source is a path, ``-`` for standard input, or
``demo:NAME``; the format comes from the extension, else from the contents.

What each format gives:

==========  ==============================================================================
JSON        ``{"vertices": [[x, y], ...], "holes": [...], "units": "in"}`` (``units``
            optional), or bare rings ``[[x, y], ...]`` / ``[[[x, y], ...], ...]`` (outer
            ring, then holes)
GeoJSON     every Polygon of a geometry, Feature or FeatureCollection (MultiPolygons
            give one part per polygon); ids from the feature's ``id`` or its ``name``
WKT         one or several geometries (the whole file, or one per line); every polygon
SVG         every visible shape (svgelements), subpaths filled by ``fill-rule`` as a
            viewer does, groups' ids select their shapes, a canvas-filling background
            is never the default; CSS px at 96 per inch, y flipped
DXF         closed entities and loops of LINE, ARC, ELLIPSE, SPLINE and polylines met end
            to end (ezdxf), blocks expanded, loops nested into parts and holes; units
            from ``$INSUNITS``
images      PNG, GIF, JPEG, BMP, TIFF, WebP silhouettes (scikit-image): every blob not
            touching the border, with its holes; pixels until ``pixel_size`` is given
==========  ==============================================================================

Then, for every format: coordinates are converted to ``units`` (:mod:`fcgrasp.io.units`),
y is flipped for y-down sources (SVG, images, or ``y_down=True``), the outline is cleaned
(:func:`fcgrasp.model.outline.clean_outline`: collinear runs merged, sub-tolerance edges
dropped) and optionally simplified.  Lengths given to the readers (``flatten``,
``simplify``, ``gap``, ``pixel_size``) are in the output ``units``.

Every problem is a :class:`ValueError` saying what is wrong and where (the file, the
element, the vertex), so the command line can print it on one line.
"""

from __future__ import annotations

import json
import os
import sys
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from ..core._checks import check_scalar
from ..core.contacts import FrictionlessPoint, FrictionPoint, Gravity
from ..core.tolerances import FLATTEN_FINEST, ON_EDGE_TOL, TINY
from ..model.outline import CLEAN_TOL, clean_outline, simplify_outline
from ..model.polygon import Polygon
from ._drawing import Drawing, Shape
from .units import FILE_UNITS, UNITS, check_units, conversion

__all__ = ["read_part", "load_part", "list_parts", "Part", "read_contacts", "DEMO_PARTS",
           "demo_part", "sniff_format", "FLATTEN_DEFAULT", "FLATTEN_FINEST", "FORMATS"]


def _regular(n: int, r: float = 1.0, phase: float = 0.0) -> list[list[float]]:
    a = phase + np.arange(n) * 2 * np.pi / n
    return np.round(np.column_stack([r * np.cos(a), r * np.sin(a)]), 12).tolist()


def _cam(n: int = 360) -> list[list[float]]:
    """A smooth cam (base circle of radius 40 mm with a lobe), flattened to ``n`` edges."""
    a = np.arange(n) * 2 * np.pi / n
    r = 40.0 * (1 + 0.3 * np.exp(-(np.angle(np.exp(1j * (a - 1.0))) / 0.6) ** 2))
    return np.round(np.column_stack([r * np.cos(a), r * np.sin(a)]), 12).tolist()


#: Built-in parts, in millimetres, in the spirit of the paper's figure 1 (and a curved
#: part, whose regions run along the boundary).
DEMO_PARTS: dict[str, dict[str, Any]] = {
    # figure 1.a: grasps with friction on two edges of an irregular blob
    "blob": {"vertices": [[0, 0], [42, -6], [70, 14], [64, 46], [30, 58], [-4, 36]]},
    # figure 1.b: frictionless grasps on three edges
    "triangle": {"vertices": [[0, 0], [60, 0], [22, 48]]},
    # figure 1.c: frictionless grasps on four edges
    "quad": {"vertices": [[0, 0], [56, 8], [50, 44], [6, 38]]},
    "bracket": {"vertices": [[0, 0], [60, 0], [60, 14], [16, 14], [16, 50], [0, 50]]},
    "washer": {"vertices": _regular(12, 30.0, 0.1),
               "holes": [_regular(8, 12.0, 0.3)]},
    "rectangle": {"vertices": [[0, 0], [80, 0], [80, 30], [0, 30]]},
    "cam": {"vertices": _cam()},
}


def demo_part(name: str) -> Polygon:
    """A built-in part by name (see :data:`DEMO_PARTS`)."""
    if name not in DEMO_PARTS:
        raise ValueError(f"unknown demo part {name!r}: choose from {', '.join(DEMO_PARTS)}")
    d = DEMO_PARTS[name]
    return Polygon(d["vertices"], d.get("holes", ()))


#: Default curve flattening tolerance, relative to the size of the curve's element.
FLATTEN_DEFAULT = 1e-3
#: Default simplification of traced images, in pixels.
IMAGE_TOLERANCE_PX = 1.0


# ----------------------------------------------------------------------------- the result


@dataclass(frozen=True)
class Part:
    """One part of a file, as read: the polygon and how it was obtained.

    Attributes
    ----------
    polygon : Polygon or None
        None when this part of the file is not a valid outline (``error`` says why).
    source, format : str
        The path (``-`` for standard input, ``demo:NAME``) and the format read.
    index : int
        Position among the parts of the file (file order, from 0).
    id, layer : str or None
        Element id, entity handle, feature id or blob number; DXF layer.
    units : str
        Units of the polygon's coordinates (``"px"`` for an image without pixel size).
    file_units : str or None
        Units the file is in (None when it says nothing: coordinates taken as ``units``).
    scale : float
        Factor applied to the file's coordinates.
    flip_y : bool
        Whether ``y`` was negated (y-down sources).
    flatten : float or None
        Flattening (or image simplification) tolerance used, in ``units``.
    cleaned : int
        Vertices removed by :func:`~fcgrasp.model.outline.clean_outline`.
    """

    polygon: Polygon | None
    source: str
    format: str
    index: int = 0
    count: int = 1
    id: str | None = None
    layer: str | None = None
    tags: tuple[str, ...] = ()
    units: str = "mm"
    file_units: str | None = None
    units_note: str = ""
    scale: float = 1.0
    flip_y: bool = False
    flatten: float | None = None
    cleaned: int = 0
    clean_tol: float | None = None
    simplify: float | None = None
    background: bool = False
    error: str | None = None
    chosen: str = ""
    notes: tuple[str, ...] = field(default_factory=tuple)

    def to_dict(self) -> dict[str, Any]:
        """Where the part came from, for the JSON reports."""
        return {"file": self.source, "format": self.format, "index": self.index,
                "parts_in_file": self.count, "id": self.id, "layer": self.layer,
                "chosen": self.chosen, "units": self.units, "file_units": self.file_units,
                "units_note": self.units_note, "scale": self.scale, "flip_y": self.flip_y,
                "flatten": self.flatten, "cleaned_vertices": self.cleaned,
                "clean_tolerance": self.clean_tol, "simplify": self.simplify}

    @property
    def area(self) -> float:
        """Area of the polygon (0 for a part that is not usable)."""
        return 0.0 if self.polygon is None else self.polygon.area


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
        return Drawing(_geojson_shapes(data, where))
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
    out = []
    base = tags[0] if tags else None
    for j, p in enumerate(polys):
        sid = base if len(polys) == 1 else (f"{base}#{j + 1}" if base else f"#{j + 1}")
        out.append(_as_shape(np.asarray(p.exterior.coords),
                             [np.asarray(h.coords) for h in p.interiors],
                             where + (f" polygon {j + 1}" if len(polys) > 1 else ""), sid,
                             (*tags, sid) if sid else tags))
    return out


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
    return Drawing(shapes)


# ----------------------------------------------------------------------------- dispatch

#: Formats by file extension.
FORMATS = {".json": "json", ".geojson": "json", ".wkt": "wkt", ".svg": "svg", ".dxf": "dxf",
           ".png": "image", ".gif": "image", ".jpg": "image", ".jpeg": "image",
           ".bmp": "image", ".tif": "image", ".tiff": "image", ".webp": "image"}
_MAGIC = (b"\x89PNG", b"\xff\xd8", b"GIF87a", b"GIF89a", b"BM", b"II*\x00", b"MM\x00*")


def sniff_format(name: str, head: bytes) -> str:
    """Format from the name's extension, else from the first bytes of the file."""
    ext = os.path.splitext(name)[1].lower()
    if ext in FORMATS:
        return FORMATS[ext]
    if head.startswith(_MAGIC) or (head[:4] == b"RIFF" and head[8:12] == b"WEBP"):
        return "image"
    if head.startswith(b"AutoCAD Binary DXF"):
        return "dxf"
    text = head[:512].decode("utf-8", "replace").lstrip("\ufeff \t\r\n").lower()
    if text.startswith(("{", "[")):
        return "json"
    if text.startswith("<") and "<svg" in text or text.startswith("<svg"):
        return "svg"
    if text.startswith(("polygon", "multipolygon", "geometrycollection")):
        return "wkt"
    if text.startswith("0") and "section" in text:
        return "dxf"
    raise ValueError("unknown part format (use .json, .geojson, .wkt, .svg, .dxf or an "
                     "image: .png, .gif, .jpg, .bmp, .tif, .webp)")


def _read_bytes(spec: str) -> bytes:
    if spec == "-":
        return sys.stdin.buffer.read()
    p = Path(spec)
    if not p.exists():
        raise ValueError(f"{spec}: no such file")
    if p.is_dir():
        raise ValueError(f"{spec}: is a folder, not a part file")
    try:
        return p.read_bytes()
    except OSError as exc:
        raise ValueError(f"{spec}: cannot read ({exc.strerror or exc})") from None


def _text(data: bytes, spec: str) -> str:
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ValueError(f"{spec}: not UTF-8 text (byte {exc.start})") from None


def _positive(value: Any, name: str) -> float | None:
    return None if value is None else check_scalar(value, name, positive=True)


@dataclass(frozen=True)
class _Options:
    units: str | None
    file_units: str | None
    flatten: float | None
    layer: str | None
    gap: float | None
    pixel_size: float | None
    threshold: float | None
    y_down: bool
    clean: bool
    simplify: float | None


def _options(units: Any, file_units: Any, flatten: Any, layer: Any, gap: Any,
             pixel_size: Any, threshold: Any, y_down: Any, clean: Any,
             simplify: Any) -> _Options:
    if units is not None:
        check_units(units, "units", UNITS)
    if file_units is not None:
        check_units(file_units, "file_units", FILE_UNITS)
    if layer is not None and not isinstance(layer, str):
        raise TypeError(f"layer must be a string, got {layer!r}")
    if threshold is not None and not 0 < check_scalar(threshold, "threshold") < 1:
        raise ValueError(f"threshold (--threshold) is a grey level in (0, 1), got "
                         f"{threshold!r}")
    for name, v in (("y_down", y_down), ("clean", clean)):
        if not isinstance(v, (bool, np.bool_)):
            raise TypeError(f"{name} must be True or False, got {v!r}")
    return _Options(units, file_units, _positive(flatten, "flatten (--flatten)"), layer,
                    _positive(gap, "gap (--gap)"), _positive(pixel_size,
                                                               "pixel_size (--pixel-size)"),
                    None if threshold is None else float(threshold), bool(y_down),
                    bool(clean), _positive(simplify, "simplify (--simplify)"))


def _scale(fmt: str, file_units: str | None, opt: _Options) -> tuple[str, float]:
    """Output units and the factor from file units to them."""
    if fmt == "image":
        if opt.pixel_size is None:
            if opt.units is not None:
                raise ValueError(f"an image has no physical size: give pixel_size "
                                 f"(--pixel-size, in {opt.units} per pixel) to read it in "
                                 f"{opt.units}")
            return "px", 1.0
        return opt.units or "mm", opt.pixel_size
    units = opt.units or "mm"
    if file_units is None or file_units == units:
        return units, 1.0
    return units, conversion(file_units, units)


def _drawing(data: bytes, spec: str, fmt: str, opt: _Options) -> Drawing:
    if fmt != "image" and (opt.pixel_size is not None or opt.threshold is not None):
        raise ValueError("pixel_size (--pixel-size) and threshold (--threshold) apply to "
                         f"images, not {fmt.upper()}")
    if fmt != "dxf" and (opt.layer is not None or opt.gap is not None):
        raise ValueError(f"layer (--layer) and gap (--gap) apply to DXF, not {fmt.upper()}")
    if fmt in ("json", "wkt") and opt.flatten is not None:
        raise ValueError(f"flatten (--flatten) applies to SVG, DXF and images, not "
                         f"{fmt.upper()} (its edges are already straight)")
    if fmt == "image" and opt.file_units is not None:
        raise ValueError("an image's units come from pixel_size (--pixel-size), not "
                         "file_units")

    def tol_of(size: float, file_units: str | None) -> float:
        units = opt.file_units or file_units
        _, scale = _scale(fmt, units, opt)
        if opt.flatten is not None:
            tol = opt.flatten / scale
            if tol < FLATTEN_FINEST * size:
                raise ValueError(f"flattening tolerance {opt.flatten:g} is below "
                                 f"{FLATTEN_FINEST:g} of the drawing's size "
                                 f"({size * scale:.6g})")
            return tol
        if fmt == "image":
            return IMAGE_TOLERANCE_PX
        return max(size, TINY) * FLATTEN_DEFAULT

    if fmt == "json":
        return _json_drawing(_json_data(data, spec), spec)
    if fmt == "wkt":
        return _wkt_drawing(_text(data, spec), spec)
    if fmt == "svg":
        from ._read_svg import read_svg

        return read_svg(data, tol_of)
    if fmt == "dxf":
        from ._read_dxf import read_dxf

        def gap_of(file_units: str | None) -> float | None:
            if opt.gap is None:
                return None
            return opt.gap / _scale(fmt, opt.file_units or file_units, opt)[1]

        return read_dxf(data, tol_of, opt.layer, gap_of)
    from ._read_image import read_image

    return read_image(data, tol_of, opt.threshold)


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


_json_data = read_json


def _part(shape: Shape, k: int, count: int, spec: str, fmt: str, d: Drawing,
          opt: _Options) -> Part:
    file_units = opt.file_units or d.units
    units, scale = _scale(fmt, file_units, opt)
    flip = d.y_down != opt.y_down            # a y-down file read with y_down flips back
    sy = -scale if flip else scale
    outer = np.asarray(shape.polygon.exterior.coords)[:-1] * [scale, sy]
    holes = [np.asarray(h.coords)[:-1] * [scale, sy] for h in shape.polygon.interiors]
    where = spec + (f" part {k}" if count > 1 else "") + (f" ({shape.id})" if shape.id
                                                         and count > 1 else "")
    if fmt == "image":
        note = f"pixel size {opt.pixel_size:g} {units}" if opt.pixel_size else d.units_note
    else:
        note = f"--file-units {opt.file_units}" if opt.file_units else d.units_note
    base = Part(None, spec, fmt, index=k, count=count, id=shape.id, layer=shape.layer,
                tags=shape.tags, units=units,
                file_units="px" if fmt == "image" else file_units, units_note=note,
                scale=scale, flip_y=flip,
                flatten=None if shape.flatten is None else shape.flatten * scale,
                simplify=opt.simplify, background=shape.background, notes=tuple(d.notes))
    try:
        poly = Polygon(outer, holes)
        removed, tol = 0, None
        if opt.clean:
            tol = CLEAN_TOL * poly.size
            poly, removed = clean_outline(poly, tol)
        if opt.simplify is not None:
            poly = simplify_outline(poly, opt.simplify)
    except ValueError as exc:
        return replace(base, error=f"{where}: {exc}")
    return replace(base, polygon=poly, cleaned=removed, clean_tol=tol)


def list_parts(source: str | os.PathLike[str], *, units: str | None = None,
               file_units: str | None = None, flatten: float | None = None,
               layer: str | None = None, gap: float | None = None,
               pixel_size: float | None = None, threshold: float | None = None,
               y_down: bool = False, clean: bool = True,
               simplify: float | None = None) -> list[Part]:
    """Every part of a file, in file order (see the module docstring for the formats).

    Parameters
    ----------
    source : str or path
        A path, ``-`` (standard input) or ``demo:NAME``.
    units : {"mm", "cm", "m", "in"}, optional
        Units to convert to (default millimetres; pixels for an image without
        ``pixel_size``).
    file_units : str, optional
        Units the file is in, overriding what it says (or saying it for JSON, WKT and
        unitless DXF); one of :data:`fcgrasp.io.units.FILE_UNITS`.
    flatten : float, optional
        Curve flattening tolerance (SVG, DXF) or outline simplification of a traced image,
        in ``units``; default :data:`FLATTEN_DEFAULT` of each element's size (one pixel
        for images).
    layer : str, optional
        DXF: only the entities of this layer.
    gap : float, optional
        DXF: ends of entities closer than this meet (in ``units``; default 1e-6 of the
        drawing's extents).
    pixel_size : float, optional
        Images: size of a pixel in ``units``.
    threshold : float, optional
        Images: grey level in (0, 1) between part and background (default Otsu's).
    y_down : bool
        The file's y axis points down (screen coordinates): flip it.  SVG and images are
        always read as y-down, so ``y_down=True`` leaves them unflipped.
    clean : bool
        Merge collinear runs and drop sub-tolerance edges (default True).
    simplify : float, optional
        Douglas-Peucker tolerance in ``units``, topology preserved.

    Returns
    -------
    list of Part
        A part whose outline is not valid has ``polygon`` None and an ``error``.
    """
    if not isinstance(source, (str, os.PathLike)):
        raise TypeError(f"part must be a path, '-' or 'demo:NAME', got {source!r}")
    spec = os.fspath(source)
    opt = _options(units, file_units, flatten, layer, gap, pixel_size, threshold, y_down,
                   clean, simplify)
    if spec.startswith("demo:"):
        if any(v is not None for v in (file_units, flatten, layer, gap, pixel_size,
                                       threshold, simplify)) or y_down:
            raise ValueError("reading options (flatten, layer, pixel size, ...) do not apply "
                             "to built-in parts")
        poly = demo_part(spec[5:])
        u = opt.units or "mm"
        scale = conversion("mm", u)
        if scale != 1.0:
            poly = Polygon(poly.vertices * scale, [h * scale for h in poly.holes])
        return [Part(poly, spec, "demo", units=u, file_units="mm",
                     units_note="built-in parts are in mm", scale=scale)]
    data = _read_bytes(spec)
    try:
        fmt = sniff_format(spec, data[:512])
        d = _drawing(data, spec, fmt, opt)
        return [_part(s, k, len(d.shapes), spec, fmt, d, opt) for k, s in enumerate(d.shapes)]
    except (ValueError, TypeError) as exc:
        msg = str(exc)
        raise ValueError(msg if msg.startswith(spec) else f"{spec}: {msg}") from None
    except MemoryError:
        raise ValueError(f"{spec}: too large to read") from None
    except RecursionError:
        raise ValueError(f"{spec}: nested too deeply to read") from None
    except Exception as exc:  # noqa: BLE001 - malformed files surface in many ways
        raise ValueError(f"{spec}: cannot read ({type(exc).__name__}: "
                         f"{' '.join(str(exc).split())[:120]})") from None


def choose_part(parts: list[Part], part: int | str | None = None) -> Part:
    """The part asked for: by index (an int or a string of digits), by id (an element id,
    group id, handle, layer, feature id or name: the largest of those it selects), or by
    default the largest usable part that is not a background.  ``chosen`` says why."""
    if not parts:
        raise ValueError("the file holds no part")
    src = parts[0].source
    n = len(parts)
    if isinstance(part, bool) or (part is not None and not isinstance(part, (int, str))):
        raise TypeError(f"part must be an index or an id, got {part!r}")
    if isinstance(part, str) and part.strip().isdigit() and \
            not any(part in p.tags for p in parts):
        part = int(part)
    if isinstance(part, int):
        if not 0 <= part < n:
            raise ValueError(f"{src}: part {part} does not exist: the file holds {n} "
                             f"part{'s' * (n != 1)} (0 to {n - 1}; see fcgrasp parts)")
        pool, why = [parts[part]], f"index {part}"
    elif isinstance(part, str):
        pool = [p for p in parts if part in p.tags
                or (p.layer is not None and part.lower() == p.layer.lower())]
        if not pool:
            ids = sorted({t for p in parts for t in p.tags})
            shown = ", ".join(ids[:12]) + (", ..." if len(ids) > 12 else "")
            raise ValueError(f"{src}: no part with id {part!r} (ids: {shown or 'none'})")
        why = f"id {part!r}" + (f", the largest of {len(pool)}" if len(pool) > 1 else "")
    else:
        pool = [p for p in parts if not p.background] or parts
        why = f"the largest of {n} parts" if n > 1 else "the only part"
        if len(pool) < n:
            why += f" ({n - len(pool)} canvas background{'s' * (n - len(pool) > 1)} left out)"
    usable = [p for p in pool if p.polygon is not None]
    if not usable:
        raise ValueError(pool[0].error or f"{src}: no usable part")
    best = max(usable, key=lambda p: (p.area, -p.index))
    return replace(best, chosen=why)


def load_part(source: str | os.PathLike[str], part: int | str | None = None,
              **options: Any) -> Part:
    """One part of a file with how it was read (see :func:`list_parts` for the options
    and :func:`choose_part` for ``part``).

    Examples
    --------
    >>> p = load_part("demo:rectangle", units="in")
    >>> p.units, round(p.scale, 6), p.polygon.vertices.max(axis=0).round(4).tolist()
    ('in', 0.03937, [3.1496, 1.1811])
    """
    return choose_part(list_parts(source, **options), part)


def read_part(source: str | os.PathLike[str], part: int | str | None = None,
              **options: Any) -> Polygon:
    """The polygon of one part of a file (see :func:`load_part`).

    Examples
    --------
    >>> read_part("demo:blob").n_edges
    6
    """
    p = load_part(source, part, **options).polygon
    assert p is not None
    return p


# ----------------------------------------------------------------------------- contact files

_CONTACTS_KEYS = {"contacts", "gravity"}
_CONTACT_KEYS = {"point", "type", "mu", "edge", "normal", "vertex"}
_GRAVITY_KEYS = {"direction"}


def _unknown(d: dict[str, Any], allowed: set[str], where: str) -> None:
    extra = sorted(set(d) - allowed)
    if extra:
        raise ValueError(f"{where}: unknown key {extra[0]!r} (expected "
                       f"{', '.join(sorted(allowed))})")


def _index(value: Any, name: str, where: str, upto: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value < upto:
        raise ValueError(f"{where}: {name} must be an index from 0 to {upto - 1}, got "
                       f"{json.dumps(value)}")
    return value


def _number_pair(value: Any, name: str, where: str) -> np.ndarray:
    if (not isinstance(value, list) or len(value) != 2
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)
            or not all(np.isfinite(value))):
        raise ValueError(f"{where}: {name} must be [x, y] finite numbers, got "
                       f"{json.dumps(value)}")
    return np.asarray(value, dtype=float)


def read_contacts(path: str | os.PathLike[str], polygon: Polygon
                  ) -> tuple[list[Any], list[dict[str, Any]]]:
    """Read a contacts file (the input of ``fcgrasp check``) for ``polygon``.

    Layout: ``{"contacts": [{"point": [x, y], "type": "friction", "mu": 0.3,
    "edge": 2}, ...], "gravity": {"direction": [0, -1]}}``; ``type`` is ``friction``,
    ``frictionless`` or ``soft`` (a soft finger on the convex vertex ``"vertex": k``, the
    start of edge ``k``); the normal comes from ``edge``, the nearest edge, or
    ``"normal"``.  Read strictly: an unknown key is a :class:`ValueError` naming it.

    Returns the contacts (for :class:`~fcgrasp.Grasp`) and their JSON description.
    """
    path = os.fspath(path)
    try:
        raw = sys.stdin.buffer.read() if path == "-" else Path(path).read_bytes()
    except FileNotFoundError:
        raise ValueError(f"{path}: no such file") from None
    except OSError as exc:
        raise ValueError(f"{path}: cannot read ({exc.strerror or exc})") from None
    return contacts_from_data(read_json(raw, path), polygon, path)


def contacts_from_data(data: Any, polygon: Polygon, where: str = "contacts"
                       ) -> tuple[list[Any], list[dict[str, Any]]]:
    """Contacts from the decoded JSON of a contacts file (see :func:`read_contacts`),
    checked as strictly; ``where`` names the source in error messages.

    >>> from fcgrasp.io.parts import demo_part
    >>> cs, _ = contacts_from_data({"contacts": [{"point": [0, 15], "mu": 0.3}]},
    ...                            demo_part("rectangle"))
    >>> type(cs[0]).__name__, cs[0].normal.tolist() == [-1, 0]
    ('FrictionPoint', True)
    """
    path = where
    if isinstance(data, dict):
        _unknown(data, _CONTACTS_KEYS, path)
    items = data.get("contacts") if isinstance(data, dict) else data
    if not isinstance(items, list) or not items:
        raise ValueError(f"{path}: expected {{'contacts': [...]}} with at least one contact")
    contacts: list[Any] = []
    described: list[dict[str, Any]] = []
    for k, c in enumerate(items):
        where = f"{path} contacts[{k}]"
        if not isinstance(c, dict):
            raise ValueError(f"{where}: expected an object, got {type(c).__name__}")
        _unknown(c, _CONTACT_KEYS, where)
        kind = c.get("type", "friction" if "mu" in c else "frictionless")
        mu = c.get("mu", 0.0)
        if not isinstance(mu, (int, float)) or isinstance(mu, bool) or not mu >= 0 \
                or not np.isfinite(mu):
            raise ValueError(f"{where}: mu must be a finite number >= 0, got {json.dumps(mu)}")
        if kind == "soft":
            if "vertex" not in c:
                raise ValueError(f"{where}: a soft contact needs 'vertex' (a vertex index)")
            k_v = _index(c["vertex"], "vertex", where, polygon.n_edges)
            try:
                contacts.append(polygon.soft_finger_at(k_v, mu))
            except ValueError as exc:
                raise ValueError(f"{where}: {exc}") from None
            described.append({"type": "soft", "vertex": k_v, "point": polygon.starts[k_v],
                              "mu": mu})
            continue
        if kind not in ("friction", "frictionless"):
            raise ValueError(f"{where}: type must be friction, frictionless or soft, got "
                           f"{json.dumps(kind)}")
        if "vertex" in c:
            raise ValueError(f"{where}: 'vertex' goes with a soft contact, not {kind}")
        if "point" not in c:
            raise ValueError(f"{where}: missing 'point'")
        pt = _number_pair(c["point"], "point", where)
        if "normal" in c:
            n = _number_pair(c["normal"], "normal", where)
            if not np.any(n):
                raise ValueError(f"{where}: normal must be a non-zero vector")
            edge = None if "edge" not in c else _index(c["edge"], "edge", where,
                                                       polygon.n_edges)
        else:
            dist = polygon.distance_to_edges(pt)
            if "edge" in c:
                e = _index(c["edge"], "edge", where, polygon.n_edges)
                if not polygon.usable[e]:
                    raise ValueError(f"{where}: edge {e} has zero length")
            else:
                e = int(np.argmin(dist))
            d_e = float(dist[e])
            if d_e > ON_EDGE_TOL * polygon.size:
                raise ValueError(f"{where}: point {pt.tolist()} is not on edge {e} "
                               f"(distance {d_e:.3g})")
            n = polygon.normals[e]
            edge = e
        if kind == "friction":
            contacts.append(FrictionPoint(pt, n, mu))
        else:
            contacts.append(FrictionlessPoint(pt, n))
        described.append({"type": kind, "point": pt, "normal": n, "edge": edge, "mu": mu})
    g = data.get("gravity") if isinstance(data, dict) else None
    if g is not None:
        if not isinstance(g, dict):
            raise ValueError(f"{path}: gravity must be an object such as "
                           f'{{"direction": [0, -1]}}, got {json.dumps(g)}')
        _unknown(g, _GRAVITY_KEYS, f"{path} gravity")
        direction = _number_pair(g.get("direction", [0, -1]), "direction", f"{path} gravity")
        if not np.any(direction):
            raise ValueError(f"{path} gravity: direction must be a non-zero vector")
        contacts.append(Gravity(polygon.centroid, direction))
        described.append({"type": "gravity", "point": polygon.centroid, "direction": direction})
    return contacts, described
