"""DXF drawings (ezdxf, extra ``dxf``): closed entities and loops of entities met end to
end, blocks expanded, nested into parts and holes."""

from __future__ import annotations

import io
import math
from collections.abc import Callable
from typing import Any

import numpy as np
from shapely.geometry import Point
from shapely.geometry import Polygon as ShapelyPolygon

from ..core._geom import signed_area
from ..core.tolerances import GAP_REL, TINY
from ..model.outline import fill_rings
from ._drawing import CurvePoints, Drawing, Shape, TolOf, flatten_curve
from .limits import DEFAULT_LIMITS, Limits

#: $INSUNITS codes and their unit names (0, unitless, says nothing).
INSUNITS = {1: "in", 2: "ft", 3: "mi", 4: "mm", 5: "cm", 6: "m", 7: "km", 8: "uin",
            9: "mil", 10: "yd", 12: "nm", 13: "um", 14: "dm"}

_CURVES = {"LINE", "ARC", "CIRCLE", "ELLIPSE", "SPLINE", "LWPOLYLINE", "POLYLINE"}


def _expand(entities: Any, depth: int = 0) -> Any:
    """Entities with block references expanded (recursively); an entity on layer 0 inside a
    block takes the layer of its reference, as CAD programs draw it."""
    for e in entities:
        if e.dxftype() == "INSERT" and depth < 32:
            layer = e.dxf.get("layer", "0")
            for v in _expand(e.virtual_entities(), depth + 1):
                if v.dxf.get("layer", "0") == "0":
                    v.dxf.layer = layer
                yield v
        else:
            yield e


def _expanded_count(entities: Any, doc: Any, limit: int,
                    memo: dict[str, int] | None = None, depth: int = 0) -> int:
    """How many entities :func:`_expand` would give, counted without expanding: each
    block's count once, times its INSERTs (and a MINSERT's rows and columns); the count
    stops once it passes ``limit``.  A block that inserts itself (directly or through
    others) is refused, a ValueError, as CAD programs refuse it."""
    memo = {} if memo is None else memo
    n = 0
    for e in entities:
        if e.dxftype() == "INSERT" and depth < 32:
            name = str(e.dxf.get("name", ""))
            if memo.get(name, 0) < 0:
                raise ValueError(f"block {name!r} inserts itself")
            if name not in memo:
                memo[name] = -1                     # being counted
                block = doc.blocks.get(name)
                memo[name] = 0 if block is None else \
                    _expanded_count(block, doc, limit, memo, depth + 1)
            copies = max(1, int(e.dxf.get("row_count", 1) or 1)) * \
                max(1, int(e.dxf.get("column_count", 1) or 1))
            n += copies * memo[name]
        else:
            n += 1
        if n > limit:
            break
    return n


def _canonical(ring: np.ndarray) -> np.ndarray:
    """The ring counter-clockwise, starting at its lowest-leftmost vertex (edgeminer's chains
    start and run wherever its search happened to)."""
    if len(ring) > 1 and np.array_equal(ring[0], ring[-1]):
        ring = ring[:-1]
    if signed_area(ring) < 0:
        ring = ring[::-1]
    return np.roll(ring, -int(np.lexsort((ring[:, 0], ring[:, 1]))[0]), axis=0)


def _bezier_points(curve: Any) -> CurvePoints:
    """``ts -> points`` of an ezdxf Bezier curve (quadratic or cubic, Bernstein form of
    its control points), as complex numbers."""
    ctrl = np.array([complex(v.x, v.y) for v in curve.control_points])
    deg = len(ctrl) - 1
    coef = [math.comb(deg, i) for i in range(deg + 1)]

    def points(ts: np.ndarray) -> np.ndarray:
        t = np.asarray(ts, dtype=float)[:, None]
        i = np.arange(deg + 1)
        basis = np.array(coef) * t ** i * (1.0 - t) ** (deg - i)
        return basis @ ctrl
    return points


def _flatten_path(path: Any, tol: float) -> np.ndarray:
    """The points of an ezdxf path (lines and Bezier curves), curves flattened by
    :func:`fcgrasp.io._drawing.flatten_curve` (chord and turn)."""
    from ezdxf.math import Bezier3P, Bezier4P, Vec3
    from ezdxf.path import Command

    start = Vec3(path.start)
    pts = [complex(start.x, start.y)]
    for cmd in path.commands():
        end = Vec3(cmd.end)
        if cmd.type == Command.CURVE4_TO:
            curve: Any = Bezier4P([start, Vec3(cmd.ctrl1), Vec3(cmd.ctrl2), end])
        elif cmd.type == Command.CURVE3_TO:
            curve = Bezier3P([start, Vec3(cmd.ctrl), end])
        else:
            curve = None
            pts.append(complex(end.x, end.y))
        if curve is not None:
            flatten_curve(_bezier_points(curve), tol, pts)
        start = end
    return np.array([[z.real, z.imag] for z in pts])


def _extents(entities: list[Any]) -> float:
    from ezdxf import bbox

    box = bbox.extents(entities, fast=True)
    if not box.has_data:
        return 0.0
    return float(max(box.size.x, box.size.y))


def read_dxf(data: bytes, tol_of: TolOf, layer: str | None = None,
             gap_of: Callable[[str | None], float | None] | None = None,
             limits: Limits = DEFAULT_LIMITS) -> Drawing:
    """Loops of a DXF's modelspace (or of ``layer``): closed LWPOLYLINE, POLYLINE, CIRCLE,
    ELLIPSE and SPLINE entities, and chains of LINE, ARC, ELLIPSE, SPLINE and open
    polylines joined end to end (ezdxf's edgesmith and edgeminer) within ``gap_of(units)``
    (file units; default :data:`GAP_REL` of the drawing's extents).  Every curve (ezdxf's
    paths of Bezier curves) is flattened by one rule, the SVG reader's: at most the
    tolerance between curve and chord and at most
    :data:`~fcgrasp.io._drawing.MAX_TURN_DEG` of turn per edge; loops are nested into parts
    and holes by the even-odd rule.  Block references are counted before they are
    expanded: more than ``limits.max_elements`` entities in all is refused."""
    try:
        from ezdxf import edgeminer as em
        from ezdxf import edgesmith as es
        from ezdxf import path as dxfpath
        from ezdxf import recover
    except ImportError as exc:  # pragma: no cover - depends on the install
        raise ValueError("reading DXF needs ezdxf: pip install 'fcgrasp[dxf]'") from exc
    try:
        doc, _ = recover.read(io.BytesIO(data))
    except Exception as exc:  # ezdxf raises DXFStructureError and others
        raise ValueError(f"not a readable DXF ({str(exc).splitlines()[0][:120]})") from exc
    code = int(doc.header.get("$INSUNITS", 0) or 0)
    units = INSUNITS.get(code)
    note = f"$INSUNITS {code} ({units})" if units else \
        f"$INSUNITS {code} (unitless: taken as the units asked)"
    limits.elements(_expanded_count(doc.modelspace(), doc, limits.max_elements),
                    "the DXF's entities with its block references expanded")
    ents = [e for e in _expand(doc.modelspace()) if e.dxftype() in _CURVES]
    layers = sorted({e.dxf.get("layer", "0") for e in ents})
    if layer is not None:
        ents = [e for e in ents if e.dxf.get("layer", "0").lower() == layer.lower()]
        if not ents:
            raise ValueError(f"no curve on layer {layer!r} (layers with curves: "
                             f"{', '.join(layers) or 'none'})")
    extent = _extents(ents)
    gap = None if gap_of is None else gap_of(units)
    gap_tol = GAP_REL * extent if gap is None else gap
    rings: list[np.ndarray] = []
    meta: list[tuple[str, str, float]] = []   # (handle, layer, flattening) of each ring

    order = {id(e): k for k, e in enumerate(ents)}
    found: list[tuple[int, np.ndarray, Any, float]] = []

    def add(p: Any, members: list[Any]) -> None:
        size = float(np.max(np.ptp(np.array([[v.x, v.y] for v in p.control_vertices()]),
                                   axis=0))) if len(p) else 0.0
        if not size > 0:
            return
        tol = tol_of(size, units)
        first = min(members, key=lambda e: order[id(e)])
        found.append((order[id(first)], _canonical(_flatten_path(p, tol)), first, tol))

    edges = []
    loose = 0
    for e in ents:
        if es.is_closed_entity(e):
            add(dxfpath.make_path(e), [e])
            continue
        edge = es.make_edge_2d(e, gap_tol=gap_tol)
        if edge is not None:
            edges.append(edge)
            continue
        # not flagged closed, yet its ends meet within the gap (a polyline whose last
        # vertex repeats its first, a hair off): a loop of its own, as ezdxf sees it
        p = dxfpath.make_path(e)
        if len(p) and p.start.isclose(p.end, abs_tol=gap_tol):
            add(p, [e])
        else:
            loose += 1
    notes: list[str] = []
    if edges:
        deposit = em.Deposit(edges, gap_tol=gap_tol)
        for chain in em.find_all_simple_chains(deposit):
            if em.is_loop(chain, gap_tol=gap_tol):
                add(es.path2d_from_chain(chain), [edge.payload for edge in chain])
            else:
                loose += len(chain)
    if loose:
        notes.append(f"{loose} entities not in a closed loop (gap tolerance "
                     f"{gap_tol:.3g}) were left out")
    # loops in file order (of their first entity), each from its lowest vertex, counter-
    # clockwise: the same file gives the same parts and edge numbers on every run
    for _, ring, first, tol in sorted(found, key=lambda f: f[0]):
        rings.append(ring)
        meta.append((str(first.dxf.get("handle", "")), first.dxf.get("layer", "0"), tol))
    if not rings:
        which = f" on layer {layer!r}" if layer else ""
        raise ValueError(f"no closed loop{which}: no closed polyline, circle, ellipse or "
                         f"spline, and no entities meeting end to end within {gap_tol:.3g}")
    ring_polys = [ShapelyPolygon(r) if len(r) >= 3 else None for r in rings]
    shapes = []
    for poly in fill_rings(rings, "evenodd"):
        outer_area = ShapelyPolygon(poly.exterior).area
        probe = Point(poly.exterior.coords[0])
        best, err = 0, np.inf
        for i, rp in enumerate(ring_polys):
            if rp is None or rp.distance(probe) > GAP_REL * max(extent, TINY):
                continue
            e_ = abs(abs(rp.area) - outer_area)
            if e_ < err:
                best, err = i, e_
        handle, lay, tol = meta[best]
        shapes.append(Shape(poly, handle, (handle, lay), layer=lay, flatten=tol))
    return Drawing(shapes, units, note, y_down=False, notes=notes)
