"""JSON reports of plans and checks: versioned, deterministic (sorted keys, rounded floats).

Layout of a plan report (``format_version`` 3)::

    {
      "fcgrasp": "0.1.0", "format_version": 3, "units": "mm",
      "part": {"vertices": [[x, y], ...], "holes": [...], "edges": E},
      "parameters": {"fingers": 2, "mu": 0.3, "top": 10, "rank_by": "min_region",
                     "margin_deg": 0.5, "workspace": null, "finger_radius": 0.0,
                     "disturbance": {"translation": 10.0, "rotation_deg": 15.0}},
      "grasps": [{"rank": 1, "edges": [i, j], "contact_type": "friction", "mu": 0.3,
                  "mode": "squeeze", "regions": [[[x, y], [x, y], ...], ...],
                  "region_edges": [[i, ...], [j, ...]],
                  "region_lengths": [...], "min_region_length": l,
                  "contacts": [[x, y], ...], "normals": [[nx, ny], ...],
                  "quality": {"min_region": ..., "resistance": ..., "resistance_approx": ...,
                              "epsilon_l1": ..., "epsilon_linf": ...}}, ...],
      "reason": null, "complete": true,
      "source": {"file": "part.svg", "format": "svg", "index": 2, "parts_in_file": 3,
                 "id": "gear", "layer": null, "chosen": "the largest of 3 parts",
                 "units": "mm", "file_units": "px", "units_note": "...", "scale": 0.2646,
                 "flip_y": true, "flatten": 0.05, "cleaned_vertices": 0,
                 "clean_tolerance": 1e-05, "simplify": null}
    }

``edges`` use the input vertex order (hole edges numbered after the outer ring's) and
give, per finger, the edge of its representative contact (``contacts``, the point
halfway along its region); ``regions`` are polylines along the boundary through the
vertices they cover, ``region_edges`` the edges they cover and ``region_lengths`` arc
lengths.  A solid's report (``part.solid``) has each plan's facets, centres, regions
in 3-D and ``normals`` pointing out of the part, as every report's do.  Version 1 had
two-point regions on one edge each and no ``region_edges``, version 2 a solid's normals
pointing into it: :func:`migrate_report` reads either as version 3;
``grasps`` is empty when no grasp exists, and ``reason`` then says why.  ``source``
(absent for parts built in Python) records how the part was read: the file, which of its
parts, the units it was in and the scale applied, the flip of y-down sources, the
flattening tolerance and the clean-up (see :class:`fcgrasp.io.parts.Part`).  Options
``complete`` is false when the search stopped early (its time limit, its memory
budget or the depth of a distinct search): the grasps are then an exact prefix of the
complete answer, and ``gap`` says why it stopped (``stopped_by``: ``"time_limit"``,
``"max_memory"`` or ``"depth"``), how many grasps it proved (``found``) and ``bound``:
every further alternative's smallest region is at most that long (null where the search
proved no such length); a report without ``complete`` (written before it existed) is
read as complete.  Options that ask for more add their entries: ``--bound`` an
``"optimality"`` object (``upper_bound``: no regions that long hold, ``gap``: ``1 -``
the best plan's smallest region over it, ``nodes``: :meth:`fcgrasp.UpperBound.to_dict`).
"""

from __future__ import annotations

import json
from typing import Any

from .. import __version__
from ..core._json import json_ready

FORMAT_VERSION = 3


def migrate_report(report: dict[str, Any]) -> dict[str, Any]:
    """A report of any earlier ``format_version`` as the current version (a copy).

    Version 1 -> 2: every grasp's region (two end points on one edge) is a two-point
    polyline and gets ``region_edges`` ``[[edge], ...]``.  Version 2 -> 3: a solid's
    grasps (``part.solid``) have outward normals, as a planar part's always had (version
    2 wrote a solid's pointing into it).

    >>> old = {"format_version": 1, "grasps": [{"edges": [1, 3], "regions": []}]}
    >>> migrate_report(old)["grasps"][0]["region_edges"], migrate_report(old)["format_version"]
    ([[1], [3]], 3)
    >>> solid = {"format_version": 2, "part": {"solid": True},
    ...          "grasps": [{"normals": [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]]}]}
    >>> migrate_report(solid)["grasps"][0]["normals"]
    [[-1.0, -0.0, -0.0], [1.0, -0.0, -0.0]]
    """
    version = report.get("format_version")
    if version not in (1, 2, FORMAT_VERSION):
        raise ValueError(f"report has format_version {version!r}; this fcgrasp reads "
                         f"versions 1 to {FORMAT_VERSION}")
    out = json.loads(json.dumps(report))
    if "grasps" in out:
        out.setdefault("complete", True)
    if version == 1:
        for g in out.get("grasps", []):
            g["region_edges"] = [[e] for e in g["edges"]]
    if version in (1, 2) and (out.get("part") or {}).get("solid"):
        for g in out.get("grasps", []):
            if "normals" in g:
                g["normals"] = [[-float(x) for x in n] for n in g["normals"]]
    out["format_version"] = FORMAT_VERSION
    return out


def dumps(report: dict[str, Any]) -> str:
    """Deterministic JSON text (sorted keys, two-space indent, trailing newline)."""
    return json.dumps(json_ready(report), sort_keys=True, indent=2, allow_nan=False) + "\n"


def part_dict(shape: Any) -> dict[str, Any]:
    """The report's ``part``: a polygon's rings and edges, or a solid's facets,
    triangles, bounds and centre of mass."""
    from ..model.polygon import Polygon

    if isinstance(shape, Polygon):
        return {"vertices": shape.vertices, "holes": list(shape.holes),
                "edges": shape.n_edges}
    lo, hi = shape.mesh.bounds
    return {"solid": True, "facets": len(shape.facets), "triangles": int(len(shape.mesh.faces)),
            "bounds": [lo.tolist(), hi.tolist()], "center_of_mass": shape.center.tolist(),
            "units_note": shape.units_note}


def plan_report(shape: Any, plans: list[Any], parameters: dict[str, Any], units: str,
                reason: str | None = None, source: dict[str, Any] | None = None
                ) -> dict[str, Any]:
    """The JSON document of ranked plans: each plan's ``to_dict()`` with its rank, the
    part (:func:`part_dict` of ``shape``, a polygon or a solid), the parameters, why
    there is no plan, and where the part came from."""
    grasps = []
    for k, p in enumerate(plans):
        d = p.to_dict()
        d["rank"] = k + 1
        grasps.append(d)
    # a hand's geometry and its scene are the report's own (any reader checks a pose
    # from them)
    parameters = dict(parameters)
    scene: dict[str, Any] = {k: parameters.pop(k) for k in ("hand", "scene")
                             if k in parameters}
    out = {"fcgrasp": __version__, "format_version": FORMAT_VERSION, "units": units,
           "part": part_dict(shape), "parameters": parameters,
           **scene,
           "grasps": grasps, "reason": None if plans else (reason or "no force-closure grasp"),
           "complete": bool(getattr(plans, "complete", True))}
    gap = getattr(plans, "gap", None)
    if callable(gap) and gap() is not None:
        out["gap"] = gap()
    if source is not None:
        out["source"] = source
    return out


def check_report(polygon: Any, contacts: list[dict[str, Any]], verdict: Any, freedom: Any,
                 units: str, source: dict[str, Any] | None = None) -> dict[str, Any]:
    """The report of ``fcgrasp check``: the contacts as read, the verdict of
    :meth:`~fcgrasp.Grasp.explain` and the total freedom (a twist cone)."""
    out = {"fcgrasp": __version__, "format_version": FORMAT_VERSION, "units": units,
           "part": part_dict(polygon), "contacts": contacts,
           "force_closure": verdict.force_closure, "failed": verdict.failed,
           "escape_twist": verdict.escape_twist, "escape": verdict.escape_description,
           "total_freedom": {"rays": freedom.rays, "lines": freedom.lines}}
    if source is not None:
        out["source"] = source
    return out


def parts_report(parts: list[Any], default: int) -> dict[str, Any]:
    """The report of ``fcgrasp parts``: every part of a file with its outline, and which
    one is the default (-1: none is usable)."""
    items = []
    for p in parts:
        d = p.to_dict()
        d["background"] = p.background
        d["error"] = p.error
        d["part"] = None if p.polygon is None else part_dict(p.polygon)
        d["area"] = None if p.polygon is None else p.polygon.area
        items.append(d)
    return {"fcgrasp": __version__, "format_version": FORMAT_VERSION,
            "units": parts[0].units if parts else None, "default": default, "parts": items,
            "notes": list(parts[0].notes) if parts else []}


def report_part(report: dict[str, Any]) -> tuple[Any, str]:
    """The part a plan report was planned on, and its units: a planar part's polygon
    from the report's ``part``, a solid read again from its ``source.path`` (an
    :class:`~fcgrasp.errors.ArgumentError` on ``source`` where the report does not say)."""
    from ..errors import ArgumentError

    units = str(report.get("units") or "mm")
    part = report.get("part") or {}
    if part.get("solid"):
        from .meshes import read_solid

        path = (report.get("source") or {}).get("path")
        if not path:
            raise ArgumentError("the solid's report does not say where its mesh is "
                                "(source.path)", "source")
        return read_solid(path, units=report.get("units")), units
    from ..model.polygon import Polygon

    return Polygon(part["vertices"], part.get("holes") or []), units


def bodies_report(source: str, bodies: list[Any], units: str, note: str) -> dict[str, Any]:
    """The report of ``fcgrasp parts`` on a mesh: its connected bodies (triangles,
    watertight, volume, bounds) and the default, the largest watertight one."""
    from .meshes import default_body

    default = default_body(bodies).index if bodies else 0
    return {"source": source, "units": units, "units_note": note, "default": default,
            "bodies": [{"index": b.index, "triangles": b.triangles,
                        "watertight": b.watertight, "volume": b.volume,
                        "bounds": b.bounds.tolist()} for b in bodies]}


def part_listing(source: str, **reading: Any) -> dict[str, Any]:
    """The report of ``fcgrasp parts``: a drawing's parts (:func:`parts_report`, the
    reading options those of :func:`fcgrasp.io.parts.list_parts`) or a mesh file's
    bodies (:func:`bodies_report`)."""
    from .limits import Limits
    from .meshes import is_solid_source, read_bodies
    from .parts import choose_part, list_parts

    if is_solid_source(source):
        bodies, units, note = read_bodies(source, reading.get("units"),
                                          reading.get("file_units"),
                                          Limits.of_options(reading))
        return bodies_report(source, bodies, units, note)
    parts = list_parts(source, **reading)
    try:
        default = choose_part(parts).index
    except ValueError:
        default = -1
    return parts_report(parts, default)


def demo_summary(plans: list[dict[str, Any]], units: str) -> dict[str, Any]:
    """The index ``demo.json`` of ``fcgrasp demo``: one entry per built-in plan."""
    return {"fcgrasp": __version__, "format_version": FORMAT_VERSION, "units": units,
            "plans": plans}


def duration(seconds: float) -> str:
    """A duration for people: seconds, minutes, hours or days."""
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    if seconds < 2 * 86400:
        return f"{seconds / 3600:.1f} h"
    return f"{seconds / 86400:.0f} days"
