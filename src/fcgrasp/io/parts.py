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

import os
import sys
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core._checks import check_scalar
from ..core.tolerances import FLATTEN_FINEST, SLIVER_REL, TINY
from ..model.outline import CLEAN_TOL, clean_outline, simplify_outline
from ..model.polygon import Polygon
from ._drawing import Drawing, Shape
from ._read_contacts import (
    contacts_from_data,
    read_contacts,
)
from ._read_json import (
    _json_drawing,
    _text,
    _wkt_drawing,
    read_json,
)
from .demo import (
    DEMO_PARTS,
    demo_part,
)
from .limits import DEFAULT_LIMITS, Limits
from .units import FILE_UNITS, UNITS, check_units, conversion

if TYPE_CHECKING:
    from ..spatial.solid import Solid

__all__ = ["read_part", "load_part", "list_parts", "choose_part", "Part", "read_contacts",
           "contacts_from_data", "read_json", "DEMO_PARTS",
           "demo_part", "sniff_format", "FLATTEN_DEFAULT", "FLATTEN_FINEST", "FORMATS"]

#: Default curve flattening tolerance, relative to the size of the curve's element.
FLATTEN_DEFAULT = 1e-3
#: Default simplification of traced images, in pixels.
IMAGE_TOLERANCE_PX = 1.0


# ----------------------------------------------------------------------------- the result


@dataclass(frozen=True)
class Part:
    """One part of a file, as read: the polygon (or the solid) and how it was obtained.

    Attributes
    ----------
    polygon : Polygon or None
        None when this part of the file is not a valid outline (``error`` says why), or
        for a solid.
    solid : Solid or None
        A mesh's part (:class:`fcgrasp.spatial.solid.Solid`), read by
        :func:`fcgrasp.io.meshes.read_solid`; None for a planar part.
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
        Whether ``y`` was flipped (y-down sources: an SVG page or an image is flipped
        about its height, so y runs up from its bottom edge and stays positive; a file
        read with ``y_down=True`` has ``y`` negated).
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
    solid: Any = None

    @property
    def shape(self) -> Any:
        """What is planned: the polygon, or the solid (None: not usable)."""
        return self.polygon if self.solid is None else self.solid

    def notices(self) -> list[str]:
        """What a front end tells the user about this part: which one of the file was
        taken when it holds several, and the reader's notes (one line each)."""
        out = []
        if self.count > 1:
            name = f" ({self.id})" if self.id else ""
            out.append(f"fcgrasp: {self.source}: took part {self.index}{name}, {self.chosen} "
                       f"(see fcgrasp parts)")
        return out + [f"fcgrasp: {self.source}: {note}" for note in self.notes]

    def to_dict(self) -> dict[str, Any]:
        """Where the part came from, for the JSON reports (a solid: its ``path``, which
        :func:`fcgrasp.io.report.report_part` reads it again from)."""
        if self.solid is not None:
            return {"path": self.source}
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


def _read_bytes(spec: str, limits: Limits = DEFAULT_LIMITS) -> bytes:
    """The bytes of a file or of standard input (``-``), no more than ``limits.max_bytes``
    read (an endless stream such as ``/dev/zero`` is refused at the limit)."""
    if spec == "-":
        data = sys.stdin.buffer.read(limits.max_bytes + 1)
    else:
        p = Path(spec)
        if not p.exists():
            raise ValueError(f"{spec}: no such file")
        if p.is_dir():
            raise ValueError(f"{spec}: is a folder, not a part file")
        try:
            with open(p, "rb") as f:
                data = f.read(limits.max_bytes + 1)
        except OSError as exc:
            raise ValueError(f"{spec}: cannot read ({exc.strerror or exc})") from None
    limits.bytes(len(data), f"{spec}: the file's bytes")
    return data


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
    limits: Limits = DEFAULT_LIMITS


def _options(units: Any, file_units: Any, flatten: Any, layer: Any, gap: Any,
             pixel_size: Any, threshold: Any, y_down: Any, clean: Any,
             simplify: Any, limits: Limits = DEFAULT_LIMITS) -> _Options:
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
                    bool(clean), _positive(simplify, "simplify (--simplify)"), limits)


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


def _pairs_in(value: Any) -> int:
    """How many coordinate pairs a JSON value can hold: its numbers, halved (counted
    before any geometry is built)."""
    count, stack = 0, [value]
    while stack:
        v = stack.pop()
        if isinstance(v, list):
            if v and not isinstance(v[0], (list, dict)):
                count += len(v)
            else:
                stack.extend(v)
        elif isinstance(v, dict):
            stack.extend(v.values())
    return count // 2


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
        value = read_json(data, spec)
        opt.limits.vertices(_pairs_in(value), "the JSON's vertices")
        return _json_drawing(value, spec)
    if fmt == "wkt":
        return _wkt_drawing(_text(data, spec), spec)
    if fmt == "svg":
        from ._read_svg import read_svg

        return read_svg(data, tol_of, opt.limits)
    if fmt == "dxf":
        from ._read_dxf import read_dxf

        def gap_of(file_units: str | None) -> float | None:
            if opt.gap is None:
                return None
            return opt.gap / _scale(fmt, opt.file_units or file_units, opt)[1]

        return read_dxf(data, tol_of, opt.layer, gap_of, opt.limits)
    from ._read_image import read_image

    return read_image(data, tol_of, opt.threshold)




def _vertex_count(shape: Shape) -> int:
    """Vertices of a shape's rings (its exterior and holes)."""
    geom = shape.polygon          # each ring's last point repeats its first
    return len(geom.exterior.coords) - 1 + sum(len(r.coords) - 1 for r in geom.interiors)


def _part(shape: Shape, k: int, count: int, spec: str, fmt: str, d: Drawing,
          opt: _Options) -> Part:
    file_units = opt.file_units or d.units
    units, scale = _scale(fmt, file_units, opt)
    flip = d.y_down != opt.y_down            # a y-down file read with y_down flips back
    sy = -scale if flip else scale
    # a y-down page flips about its height: y up from the page's bottom edge, positive
    dy = scale * d.height if flip and d.height is not None and d.y_down else 0.0
    outer = np.asarray(shape.polygon.exterior.coords)[:-1] * [scale, sy] + [0.0, dy]
    holes = [np.asarray(h.coords)[:-1] * [scale, sy] + [0.0, dy]
             for h in shape.polygon.interiors]
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
               simplify: float | None = None, max_bytes: int | None = None,
               max_elements: int | None = None,
               max_vertices: int | None = None) -> list[Part]:
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
    max_bytes, max_elements, max_vertices : int, optional
        The readers' limits (:mod:`fcgrasp.io.limits`; None: the defaults, 256 MiB,
        20,000 elements, 500,000 vertices): a file past one is refused with a
        :class:`~fcgrasp.io.limits.LimitExceeded`, before the work it would cause.

    Returns
    -------
    list of Part
        A part whose outline is not valid has ``polygon`` None and an ``error``.
    """
    if not isinstance(source, (str, os.PathLike)):
        raise TypeError(f"part must be a path, '-' or 'demo:NAME', got {source!r}")
    spec = os.fspath(source)
    limits = Limits.given(max_bytes, max_elements, max_vertices)
    opt = _options(units, file_units, flatten, layer, gap, pixel_size, threshold, y_down,
                   clean, simplify, limits)
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
    data = _read_bytes(spec, limits)
    try:
        fmt = sniff_format(spec, data[:512])
        d = _drawing(data, spec, fmt, opt)
        limits.elements(len(d.shapes), "the file's parts")
        limits.vertices(sum(_vertex_count(s) for s in d.shapes),
                        "the vertices of the file's outlines")
        if not d.shapes:
            raise ValueError("no closed outline found")
        d = _without_slivers(d)
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


def _without_slivers(d: Drawing) -> Drawing:
    """The drawing less its slivers: pieces thinner (twice the area over the perimeter)
    than :data:`~fcgrasp.core.tolerances.SLIVER_REL` of the largest piece's size, which
    no gripper could hold and which are left by drafting (a note says how many)."""
    if len(d.shapes) < 2:
        return d
    big = max(d.shapes, key=lambda s: s.polygon.area).polygon
    x0, y0, x1, y1 = big.bounds
    floor = SLIVER_REL * max(x1 - x0, y1 - y0)
    kept = [s for s in d.shapes
            if s.polygon.length == 0 or 2 * s.polygon.area / s.polygon.length >= floor]
    if len(kept) == len(d.shapes):
        return d
    gone = len(d.shapes) - len(kept)
    return replace(d, shapes=kept, notes=[*d.notes, f"{gone} sliver{'s' * (gone > 1)} "
                                          f"(thinner than {SLIVER_REL:g} of the largest "
                                          f"part) left out"])


def choose_part(parts: list[Part], part: int | str | None = None) -> Part:
    """The part asked for: by index (an int or a string of digits, always an index: every
    CAD file's default layer is named "0"), by id (an element id, group id, handle,
    layer, feature id or name: the largest of those it selects; ``id:NAME`` for an id
    made of digits), or by default the largest usable part that is not a background.
    ``chosen`` says why."""
    if not parts:
        raise ValueError("the file holds no part")
    src = parts[0].source
    n = len(parts)
    if isinstance(part, bool) or (part is not None and not isinstance(part, (int, str))):
        raise TypeError(f"part must be an index or an id, got {part!r}")
    if isinstance(part, str) and part.strip().isdigit():
        part = int(part)
    elif isinstance(part, str) and part.startswith("id:"):
        part = part[3:]
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
    """One part of a file with how it was read: an outline of a drawing or an image
    (see :func:`list_parts` for the options and :func:`choose_part` for ``part``), or
    the solid of a mesh file or of ``demo:NAME`` a built-in solid
    (:func:`fcgrasp.io.meshes.read_solid`: ``part`` the body's index, default the
    largest watertight one; the options
    :data:`fcgrasp.io.meshes.SOLID_OPTIONS`).

    Examples
    --------
    >>> p = load_part("demo:rectangle", units="in")
    >>> p.units, round(p.scale, 6), p.polygon.vertices.max(axis=0).round(4).tolist()
    ('in', 0.03937, [3.1496, 1.1811])
    >>> load_part("demo:box").solid.mesh.extents.tolist()
    [40.0, 20.0, 10.0]
    """
    from .meshes import is_solid_source

    if isinstance(source, (str, os.PathLike)) and is_solid_source(os.fspath(source)):
        return _solid_part(os.fspath(source), part, options)
    options.pop("repair", None)             # a drawing has nothing to repair
    return choose_part(list_parts(source, **options), part)


def _solid_part(spec: str, part: int | str | None, options: dict[str, Any]) -> Part:
    """:func:`load_part` of a mesh file or a built-in solid."""
    from .meshes import read_solid_with

    solid = read_solid_with(spec, part, options)
    return Part(None, spec, "demo" if spec.startswith("demo:") else "mesh",
                units=solid.units, units_note=solid.units_note, solid=solid)


def read_part(source: str | os.PathLike[str], part: int | str | None = None,
              **options: Any) -> Polygon | Solid:
    """The part of a file that is planned (see :func:`load_part`): a drawing's or an
    image's polygon, or a mesh's solid; either goes to :func:`fcgrasp.plan`.

    Examples
    --------
    >>> read_part("demo:blob").n_edges
    6
    >>> type(read_part("demo:cylinder")).__name__
    'Solid'
    """
    p = load_part(source, part, **options).shape
    assert p is not None
    return p
