"""SVG drawings (svgelements, extra ``svg``): every visible shape, filled by its rule."""

from __future__ import annotations

import io
from typing import Any

import numpy as np
import shapely

from ..model.outline import fill_rings
from ._drawing import CurvePoints, Drawing, Shape, TolOf, flatten_curve
from .limits import DEFAULT_LIMITS, Limits

#: CSS pixels per inch: the unit of SVG user space after its viewBox and width/height.
PPI = 96.0
#: A shape covering at least this fraction of the canvas, as a rectangle, is a background.
BACKGROUND_FRACTION = 0.98


def _z(point: Any) -> complex:
    """An svgelements point as a Python complex number."""
    return complex(float(point.x), float(point.y))


def _curve_points(seg: Any) -> CurvePoints:
    """``ts -> points`` of an svgelements segment (its vectorized ``npoint``), as complex
    numbers."""
    def points(ts: np.ndarray) -> np.ndarray:
        xy = np.asarray(seg.npoint(ts), dtype=float).reshape(-1, 2)
        return xy[:, 0] + 1j * xy[:, 1]
    return points


def _rings(path: Any, tol: float, filled: bool) -> list[np.ndarray]:
    """The subpaths of a path that enclose something: closed ones, and open ones when the
    shape is filled (a viewer closes them) or when they end where they start."""
    from svgelements import Close, Line, Move

    rings: list[np.ndarray] = []
    cur: list[complex] = []
    start: complex | None = None

    def finish(pts: list[complex], closed: bool) -> None:
        if len(pts) >= 3 and (closed or filled or abs(pts[-1] - pts[0]) <= tol):
            rings.append(np.array([[z.real, z.imag] for z in pts]))

    for s in path.segments():
        if isinstance(s, Move):
            finish(cur, False)
            cur = [_z(s.end)]
            start = cur[0]
        elif isinstance(s, Close):
            finish(cur, True)
            cur = []
        else:
            if not cur and start is not None:
                cur = [start]
            if isinstance(s, Line):
                cur.append(_z(s.end))
            else:
                flatten_curve(_curve_points(s), tol, cur)
    finish(cur, False)
    return rings


def _walk(group: Any, ancestors: tuple[str, ...]) -> Any:
    """Every shape below ``group`` with the ids of the groups around it; a ``<use>``
    holds its copy of what it refers to, as a group does."""
    from svgelements import Group, Use
    from svgelements import Shape as SvgShape

    for child in group:
        if isinstance(child, (Group, Use)):
            gid = child.values.get("id")
            yield from _walk(child, ancestors + ((gid,) if gid else ()))
        elif isinstance(child, SvgShape):
            yield child, ancestors


def _visible(value: Any) -> bool:
    return value is not None and str(value).lower() not in ("none", "transparent") and \
        getattr(value, "alpha", 255) != 0


def _expanded_count(data: bytes, limit: int) -> int:
    """How many elements an SVG draws once its ``<use>`` references are expanded,
    counted on the XML without expanding (each referenced element's count once); the
    count stops once it passes ``limit``.  A reference to itself or an ancestor is
    refused (a ValueError), as is XML nested too deep to count."""
    import xml.etree.ElementTree as ET

    try:
        root = ET.fromstring(data)
    except ET.ParseError as exc:
        raise ValueError(f"not a readable SVG ({exc})") from None
    ids = {el.get("id"): el for el in root.iter() if el.get("id")}
    memo: dict[int, int] = {}
    open_: set[int] = set()

    def size(el: Any) -> int:
        key = id(el)
        if key in memo:
            return memo[key]
        if key in open_:
            raise ValueError("not a readable SVG (a <use> refers to itself or an "
                             "element around it)")
        open_.add(key)
        n = 1
        for child in el:
            n += size(child)
            if n > limit:
                break
        if el.tag.rsplit("}", 1)[-1] == "use" and n <= limit:
            href = el.get("href") or el.get("{http://www.w3.org/1999/xlink}href") or ""
            target = ids.get(href[1:]) if href.startswith("#") else None
            if target is not None:
                n += size(target)
        open_.discard(key)
        memo[key] = n
        return n

    try:
        return size(root)
    except RecursionError:
        raise ValueError("not a readable SVG (elements nested too deep)") from None


def read_svg(data: bytes, tol_of: TolOf, limits: Limits = DEFAULT_LIMITS) -> Drawing:
    """Shapes of an SVG: paths, polygons, rects, circles, ellipses; transforms applied,
    curves flattened, subpaths filled by the element's ``fill-rule`` (``evenodd`` for
    outlines drawn without fill), in CSS px (96 per inch) with y down.  The elements
    are counted with their ``<use>`` copies before anything is expanded: more than
    ``limits.max_elements`` is refused."""
    try:
        from svgelements import SVG
        from svgelements import Path as SvgPath
    except ImportError as exc:  # pragma: no cover - depends on the install
        raise ValueError("reading SVG needs svgelements: pip install 'fcgrasp[svg]'") from exc
    limits.elements(_expanded_count(data, limits.max_elements),
                    "the SVG's elements with its <use> copies")
    try:
        svg = SVG.parse(io.BytesIO(data), reify=True, ppi=PPI)
    except Exception as exc:  # svgelements raises many kinds of errors on bad XML
        raise ValueError(f"not a readable SVG ({str(exc).splitlines()[0][:120]})") from exc
    if not isinstance(svg, SVG):            # another XML document (its root not <svg>)
        raise ValueError("not an SVG: its root element is not <svg>")
    shapes: list[Shape] = []
    for k, (el, ancestors) in enumerate(_walk(svg, ())):
        filled = _visible(el.fill)
        if not filled and not _visible(el.stroke):
            continue
        if str(el.values.get("display", "")).lower() == "none":
            continue
        path = SvgPath(el)
        bbox = path.bbox()
        if bbox is None:
            continue
        size = max(bbox[2] - bbox[0], bbox[3] - bbox[1])
        if not size > 0:
            continue
        tol = tol_of(size, "px")
        rings = _rings(path, tol, filled)
        if not rings:
            continue
        rule = str(el.values.get("fill-rule", "nonzero")).strip().lower() if filled \
            else "evenodd"
        pieces = fill_rings(rings, rule if rule in ("nonzero", "evenodd") else "nonzero")
        eid = el.values.get("id")
        name = eid or f"{type(el).__name__.lower()}{k}"
        for j, poly in enumerate(pieces):
            pid = name if len(pieces) == 1 else f"{name}#{j + 1}"
            tags = tuple(dict.fromkeys((*ancestors, *((eid,) if eid else ()), pid)))
            shapes.append(Shape(poly, pid, tags, flatten=tol))
    if not shapes:
        raise ValueError("no closed path, polygon, rect, circle or ellipse found (nor a "
                         "filled open path)")
    # svgelements turns mm and cm into px with 1/25.4 rounded to 0.0393701 (0.5 ppm off);
    # drawings sized in those units are put back on the exact 96 px per inch
    width = str(svg.values.get("width", "")).strip().lower()
    fix = 1.0 / (25.4 * 0.0393701) if width.endswith(("mm", "cm")) else 1.0
    if fix != 1.0:
        for sh in shapes:
            sh.polygon = shapely.transform(sh.polygon, lambda c: c * fix)
            sh.flatten = None if sh.flatten is None else sh.flatten * fix
    canvas = float(svg.width or 0) * float(svg.height or 0) * fix * fix
    if len(shapes) > 1 and canvas > 0:
        for s in shapes:
            x0, y0, x1, y1 = s.polygon.bounds
            box = (x1 - x0) * (y1 - y0)
            if s.polygon.area >= BACKGROUND_FRACTION * canvas and \
                    s.polygon.area >= BACKGROUND_FRACTION * box:
                s.background = True
    height = float(svg.height or 0) * fix
    if not height > 0:                     # no size given: the drawing's own extent
        height = max(s.polygon.bounds[3] for s in shapes)
    return Drawing(shapes, "px", f"CSS px ({PPI:g} per inch, after viewBox and width/height)",
                   y_down=True, height=height)
