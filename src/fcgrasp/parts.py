"""Reading parts: JSON, GeoJSON, WKT, SVG, DXF, PNG silhouettes and built-in examples.

:func:`read_part` takes a path (or ``demo:NAME``) and returns a :class:`Polygon`.  The
format is taken from the extension, or from the contents when the extension says
nothing.  Every problem is a :class:`ValueError` saying what is wrong and where (the
file, the element, the vertex), so the command line can print it on one line.

Formats:

* JSON ``{"vertices": [[x, y], ...], "holes": [[[x, y], ...], ...]}``;
* GeoJSON: a Polygon, or a Feature or FeatureCollection holding one (the first
  polygon; a MultiPolygon gives its first polygon);
* WKT: ``POLYGON ((...), (...))``;
* SVG: the first closed path, polygon, rect, circle or ellipse, or the one with
  ``id``; transforms are applied, curves flattened to ``tolerance`` (default: 1/1000 of
  the drawing's size), and ``y`` is flipped so the part reads as in a viewer;
* DXF (``ezdxf``, extra ``dxf``): the first closed LWPOLYLINE or POLYLINE (or the one
  whose handle or layer is ``id``), arcs and bulges flattened;
* PNG/JPEG silhouettes (``scikit-image``, extra ``image``): the largest dark blob on a
  light background (or light on dark, whichever is the minority), traced and
  simplified to ``tolerance`` pixels (default 1), one pixel per unit, ``y`` up.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

import numpy as np

from .contacts import FrictionlessPoint, FrictionPoint, Gravity
from .polygon import Polygon
from .tolerances import ON_EDGE_TOL

__all__ = ["read_part", "read_contacts", "DEMO_PARTS", "demo_part", "polygon_from_geojson"]


def _regular(n: int, r: float = 1.0, phase: float = 0.0) -> list[list[float]]:
    a = phase + np.arange(n) * 2 * np.pi / n
    return np.round(np.column_stack([r * np.cos(a), r * np.sin(a)]), 12).tolist()


#: Built-in parts, in millimetres, in the spirit of the paper's figure 1.
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
}


def demo_part(name: str) -> Polygon:
    """A built-in part by name (see :data:`DEMO_PARTS`)."""
    if name not in DEMO_PARTS:
        raise ValueError(f"unknown demo part {name!r}: choose from {', '.join(DEMO_PARTS)}")
    d = DEMO_PARTS[name]
    return Polygon(d["vertices"], d.get("holes", ()))


# ----------------------------------------------------------------------------- JSON family


def polygon_from_json(data: Any, where: str = "JSON") -> Polygon:
    """A Polygon from our JSON layout or from GeoJSON."""
    if not isinstance(data, dict):
        raise ValueError(f"{where}: expected an object with 'vertices' or a GeoJSON "
                         f"geometry, got {type(data).__name__}")
    if "vertices" in data:
        extra = sorted(set(data) - {"vertices", "holes"})
        if extra:
            raise ValueError(f"{where}: unknown key {extra[0]!r} (a part is "
                             f"{{'vertices': [...], 'holes': [...]}})")
        holes = data.get("holes", [])
        if not isinstance(holes, list):
            raise ValueError(f"{where}: 'holes' must be a list of rings")
        return Polygon(data["vertices"], holes)
    if "type" in data:
        return polygon_from_geojson(data, where)
    raise ValueError(f"{where}: no 'vertices' and no GeoJSON 'type'")


def polygon_from_geojson(data: Any, where: str = "GeoJSON") -> Polygon:
    kind = data.get("type")
    if kind == "FeatureCollection":
        feats = data.get("features")
        if not isinstance(feats, list):
            raise ValueError(f"{where}: a FeatureCollection needs a 'features' list")
        for i, feat in enumerate(feats):
            if not isinstance(feat, dict):
                raise ValueError(f"{where} features[{i}]: expected a Feature object, got "
                                 f"{type(feat).__name__}")
            geom = feat.get("geometry") or {}
            if not isinstance(geom, dict):
                raise ValueError(f"{where} features[{i}]: geometry must be an object")
            if geom.get("type") in ("Polygon", "MultiPolygon"):
                return polygon_from_geojson(geom, f"{where} features[{i}]")
        raise ValueError(f"{where}: the FeatureCollection holds no Polygon")
    if kind == "Feature":
        geom = data.get("geometry")
        if not isinstance(geom, dict):
            raise ValueError(f"{where}: the Feature has no geometry")
        return polygon_from_geojson(geom, f"{where} geometry")
    if kind == "MultiPolygon":
        polys = data.get("coordinates") or []
        if not isinstance(polys, list) or not polys:
            raise ValueError(f"{where}: empty MultiPolygon")
        return polygon_from_geojson({"type": "Polygon", "coordinates": polys[0]}, where)
    if kind == "Polygon":
        rings = data.get("coordinates")
        if not isinstance(rings, list) or not rings:
            raise ValueError(f"{where}: a Polygon needs 'coordinates' with at least one ring")
        return Polygon(rings[0], rings[1:])
    raise ValueError(f"{where}: geometry type {kind!r} is not a polygon")


def polygon_from_wkt(text: str, where: str = "WKT") -> Polygon:
    import shapely
    from shapely.errors import ShapelyError

    try:
        geom = shapely.from_wkt(text.strip())
    except (ShapelyError, ValueError) as exc:
        raise ValueError(f"{where}: not valid WKT ({str(exc).splitlines()[0]})") from exc
    if geom is None or geom.is_empty:
        raise ValueError(f"{where}: empty geometry")
    if geom.geom_type == "MultiPolygon":
        geom = geom.geoms[0]
    if geom.geom_type != "Polygon":
        raise ValueError(f"{where}: geometry type {geom.geom_type} is not a polygon")
    return Polygon(np.asarray(geom.exterior.coords), [np.asarray(r.coords)
                                                     for r in geom.interiors])


# ----------------------------------------------------------------------------- SVG

#: Default curve flattening tolerance, relative to the drawing's size.
FLATTEN_DEFAULT = 1e-3
#: Finest flattening tolerance accepted, relative to the drawing's size: finer would
#: only multiply edges (a circle at 1e-6 already has about 2,000).
FLATTEN_FINEST = 1e-6


def _flatten_tolerance(tolerance: float | None, size: float, where: str) -> float:
    if tolerance is None:
        return max(size, 1e-300) * FLATTEN_DEFAULT
    if tolerance < FLATTEN_FINEST * size:
        raise ValueError(f"{where}: flattening tolerance {tolerance:g} is below "
                         f"{FLATTEN_FINEST:g} of the drawing's size ({size:.6g})")
    return tolerance



def _flatten_segment(seg: Any, tol: float, out: list[complex], depth: int = 0,
                     t0: float = 0.0, t1: float = 1.0) -> None:
    """Append the end point of ``seg`` restricted to [t0, t1], subdividing until the
    midpoint is within ``tol`` of the chord."""
    p0, p1 = complex(seg.point(t0)), complex(seg.point(t1))
    tm = 0.5 * (t0 + t1)
    pm = complex(seg.point(tm))
    chord = p1 - p0
    if abs(chord) > 0:
        dev = abs((pm - p0).real * chord.imag - (pm - p0).imag * chord.real) / abs(chord)
    else:
        dev = abs(pm - p0)
    if depth < 16 and (dev > tol or depth < 2):
        _flatten_segment(seg, tol, out, depth + 1, t0, tm)
        _flatten_segment(seg, tol, out, depth + 1, tm, t1)
    else:
        out.append(p1)


def polygon_from_svg(path: str, element_id: str | None = None,
                     tolerance: float | None = None) -> Polygon:
    try:
        from svgelements import SVG, Close, Line, Move, Shape
        from svgelements import Path as SvgPath
    except ImportError as exc:  # pragma: no cover - depends on the install
        raise ValueError("reading SVG needs svgelements: pip install 'fcgrasp[svg]'") from exc
    try:
        svg = SVG.parse(path, reify=True)
    except Exception as exc:  # svgelements raises many kinds of errors on bad XML
        raise ValueError(f"{path}: not a readable SVG ({str(exc).splitlines()[0][:120]})") from exc
    shapes = [e for e in svg.elements() if isinstance(e, Shape)]
    if element_id is not None:
        shapes = [e for e in shapes if getattr(e, "id", None) == element_id]
        if not shapes:
            raise ValueError(f"{path}: no shape with id {element_id!r}")
    for shape in shapes:
        p = SvgPath(shape)
        segs = [s for s in p.segments()]
        if not segs or not any(isinstance(s, Close) for s in segs):
            if type(shape).__name__ not in ("Rect", "Circle", "Ellipse", "Polygon"):
                continue
        bbox = p.bbox()
        if bbox is None:
            continue
        size = max(bbox[2] - bbox[0], bbox[3] - bbox[1])
        tol = _flatten_tolerance(tolerance, size, f"{path} element "
                                 f"{getattr(shape, 'id', None) or type(shape).__name__}")
        rings: list[list[complex]] = []
        cur: list[complex] = []
        for s in segs:
            if isinstance(s, Move):
                if len(cur) >= 3:
                    rings.append(cur)
                cur = [complex(s.end)]
            elif isinstance(s, Close):
                if len(cur) >= 3:
                    rings.append(cur)
                cur = []
            elif isinstance(s, Line):
                cur.append(complex(s.end))
            else:
                _flatten_segment(s, tol, cur)
        if len(cur) >= 3:
            rings.append(cur)
        if not rings:
            continue
        arrs = [np.array([[z.real, -z.imag] for z in r]) for r in rings]
        areas = [abs(_area(a)) for a in arrs]
        k = int(np.argmax(areas))
        outer = arrs[k]
        holes = [a for i, a in enumerate(arrs) if i != k]
        where = f"{path} element {getattr(shape, 'id', None) or type(shape).__name__}"
        try:
            return Polygon(outer, holes)
        except ValueError as exc:
            raise ValueError(f"{where}: {exc}") from exc
    raise ValueError(f"{path}: no closed path or polygon found")


def _area(a: np.ndarray) -> float:
    x, y = a[:, 0], a[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


# ----------------------------------------------------------------------------- DXF


def polygon_from_dxf(path: str, element_id: str | None = None,
                     tolerance: float | None = None) -> Polygon:
    try:
        import ezdxf
        from ezdxf import path as dxfpath
    except ImportError as exc:
        raise ValueError("reading DXF needs ezdxf: pip install 'fcgrasp[dxf]'") from exc
    try:
        doc = ezdxf.readfile(path)
    except (OSError, ezdxf.DXFError) as exc:
        raise ValueError(f"{path}: not a readable DXF ({str(exc).splitlines()[0][:120]})") from exc
    for e in doc.modelspace():
        kind = e.dxftype()
        if kind not in ("LWPOLYLINE", "POLYLINE"):
            continue
        if element_id is not None and element_id not in (e.dxf.handle,
                                                         e.dxf.get("layer", None)):
            continue
        if not getattr(e, "closed", False) and not getattr(e, "is_closed", False):
            continue
        p = dxfpath.make_path(e)
        ext = p.control_vertices()
        arr = np.array([[v.x, v.y] for v in ext]) if len(ext) else np.zeros((0, 2))
        size = float(np.max(np.ptp(arr, axis=0))) if len(arr) else 1.0
        tol = _flatten_tolerance(tolerance, size, f"{path} {kind} {e.dxf.handle}")
        pts = np.array([[v.x, v.y] for v in p.flattening(tol)])
        try:
            return Polygon(pts)
        except ValueError as exc:
            raise ValueError(f"{path} {kind} {e.dxf.handle}: {exc}") from exc
    which = f" with handle or layer {element_id!r}" if element_id else ""
    raise ValueError(f"{path}: no closed LWPOLYLINE or POLYLINE{which}")


# ----------------------------------------------------------------------------- images


def polygon_from_image(path: str, tolerance: float | None = None) -> Polygon:
    try:
        from skimage import color, filters, io, measure
    except ImportError as exc:
        raise ValueError("reading images needs scikit-image: pip install 'fcgrasp[image]'") \
            from exc
    try:
        img = io.imread(path)
    except Exception as exc:  # imageio raises several kinds
        raise ValueError(f"{path}: not a readable image ({str(exc).splitlines()[0][:120]})") \
            from exc
    img = np.asarray(img)
    if img.ndim == 3:
        if img.shape[2] == 4:
            img = img[..., :3]
        img = color.rgb2gray(img)
    img = img.astype(float)
    if img.ndim != 2 or min(img.shape) < 3 or np.ptp(img) == 0:
        raise ValueError(f"{path}: the image has no contrast, no silhouette to trace")
    thr = filters.threshold_otsu(img)
    mask = img < thr
    if mask.mean() > 0.5:           # the part is the minority class
        mask = ~mask
    labels = measure.label(mask, connectivity=2)
    if labels.max() == 0:
        raise ValueError(f"{path}: no silhouette found")
    sizes = np.bincount(labels.ravel())
    sizes[0] = 0
    blob = labels == int(np.argmax(sizes))
    padded = np.pad(blob, 1).astype(float)
    contours = measure.find_contours(padded, 0.5)
    if not contours:
        raise ValueError(f"{path}: no closed outline found")
    c = max(contours, key=len)
    c = measure.approximate_polygon(c, tolerance=1.0 if tolerance is None else tolerance)
    pts = np.column_stack([c[:, 1] - 1, -(c[:, 0] - 1)])        # (x, y) with y up
    try:
        return Polygon(pts)
    except ValueError as exc:
        raise ValueError(f"{path}: traced outline is not usable: {exc}") from exc


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
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise ValueError(f"{path}: no such file") from None
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path}: not valid JSON ({exc.msg} at line {exc.lineno})") from None
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not UTF-8 text (byte {exc.start})") from None
    except OSError as exc:
        raise ValueError(f"{path}: cannot read ({exc.strerror or exc})") from None
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


# ----------------------------------------------------------------------------- dispatch

_EXT = {".json": "json", ".geojson": "json", ".wkt": "wkt", ".svg": "svg", ".dxf": "dxf",
        ".png": "image", ".jpg": "image", ".jpeg": "image", ".bmp": "image", ".tif": "image",
        ".tiff": "image"}


def sniff_format(path: str) -> str:
    """Format from the extension, else from the first bytes of the file."""
    ext = os.path.splitext(path)[1].lower()
    if ext in _EXT:
        return _EXT[ext]
    with open(path, "rb") as fh:
        head = fh.read(512)
    if head.startswith(b"\x89PNG") or head.startswith(b"\xff\xd8"):
        return "image"
    text = head.decode("utf-8", "replace").lstrip().lower()
    if text.startswith("{") or text.startswith("["):
        return "json"
    if text.startswith("<?xml") or text.startswith("<svg") or "<svg" in text:
        return "svg"
    if text.startswith("polygon") or text.startswith("multipolygon"):
        return "wkt"
    if text.startswith("0") and "section" in text:
        return "dxf"
    raise ValueError(f"{path}: unknown part format (use .json, .geojson, .wkt, .svg, .dxf "
                     f"or .png)")


def read_part(spec: str, element_id: str | None = None,
              tolerance: float | None = None) -> Polygon:
    """Read a part from a file or ``demo:NAME``.

    Parameters
    ----------
    spec : str
        A path, or ``demo:NAME`` for a built-in part.
    element_id : str, optional
        SVG element id, or DXF entity handle or layer, to choose among several.
    tolerance : float, optional
        Flattening tolerance for curves (SVG, DXF) or simplification tolerance in
        pixels (images).
    """
    if not isinstance(spec, (str, os.PathLike)):
        raise TypeError(f"part must be a path or 'demo:NAME', got {spec!r}")
    spec = os.fspath(spec)
    if tolerance is not None:
        if isinstance(tolerance, bool) or not isinstance(tolerance, (int, float, np.number)):
            raise TypeError(f"tolerance must be a number, got {tolerance!r}")
        if not (np.isfinite(tolerance) and tolerance > 0):
            raise ValueError(f"tolerance (--flatten) must be a finite number > 0, got "
                             f"{tolerance!r}")
    if element_id is not None and not isinstance(element_id, str):
        raise TypeError(f"element_id must be a string, got {element_id!r}")
    if spec.startswith("demo:"):
        if tolerance is not None or element_id is not None:
            raise ValueError("tolerance (--flatten) and element_id (--id) do not apply to "
                             "built-in parts")
        return demo_part(spec[5:])
    p = Path(spec)
    if not p.exists():
        raise ValueError(f"{spec}: no such file")
    if p.is_dir():
        raise ValueError(f"{spec}: is a folder, not a part file")
    try:
        fmt = sniff_format(spec)
    except OSError as exc:
        raise ValueError(f"{spec}: cannot read ({exc.strerror})") from exc
    try:
        return _read_format(spec, p, fmt, element_id, tolerance)
    except (ValueError, TypeError) as exc:
        if str(exc).startswith(spec):
            raise
        raise ValueError(f"{spec}: {exc}") from exc
    except MemoryError:
        raise ValueError(f"{spec}: too large to read") from None
    except Exception as exc:  # noqa: BLE001 - malformed files surface in many ways
        raise ValueError(f"{spec}: cannot read as {fmt} ({type(exc).__name__}: "
                         f"{' '.join(str(exc).split())[:120]})") from exc


def _read_format(spec: str, p: Path, fmt: str, element_id: str | None,
                 tolerance: float | None) -> Polygon:
    if fmt == "image" and element_id is not None:
        raise ValueError(f"{spec}: element_id (--id) applies to SVG and DXF, not images")
    if fmt in ("json", "wkt") and (tolerance is not None or element_id is not None):
        raise ValueError(f"{spec}: tolerance (--flatten) and element_id (--id) apply to SVG, "
                         f"DXF and images, not {fmt.upper()}")
    if fmt in ("json", "wkt"):
        try:
            text = p.read_text(encoding="utf-8")
        except UnicodeDecodeError as exc:
            raise ValueError(f"{spec}: not UTF-8 text (byte {exc.start})") from exc
        except OSError as exc:
            raise ValueError(f"{spec}: cannot read ({exc.strerror})") from exc
        if fmt == "wkt":
            return polygon_from_wkt(text, spec)
        try:
            data = json.loads(text)
        except json.JSONDecodeError as exc:
            raise ValueError(f"{spec}: not valid JSON ({exc.msg} at line {exc.lineno} "
                             f"column {exc.colno})") from exc
        try:
            return polygon_from_json(data, spec)
        except TypeError as exc:
            raise ValueError(f"{spec}: {exc}") from exc
    if fmt == "svg":
        return polygon_from_svg(spec, element_id, tolerance)
    if fmt == "dxf":
        return polygon_from_dxf(spec, element_id, tolerance)
    return polygon_from_image(spec, tolerance)
