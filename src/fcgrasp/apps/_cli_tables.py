"""The command line's table of a plan report: one line per plan, with the columns of the
plan's kind (point fingers on a planar part, the jaw's boxes, regions on a solid's
facets), read from the report itself (the JSON contract), so that the command line
prints every gripper on every part through one function (part of
:mod:`fcgrasp.apps.cli`)."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

__all__ = ["plan_table", "listing_table", "report_kind", "demo_entry"]


def _fingers(report: dict[str, Any]) -> list[str]:
    """Point fingers on a planar part: the edges, the regions and their quality."""
    units = report["units"]
    # the resistance is 1 / work (section 8.1): per unit force and per unit of length
    lines = [f"{'rank':>4}  {'edges':<20} {'min region':>11}  {'regions (' + units + ')':<24} "
             f"{'resistance (1/' + units + ')':>18} {'eps L1':>8}"]
    for k, g in enumerate(report["grasps"]):
        q = g["quality"]
        regs = ", ".join(f"{x:.3g}" for x in g["region_lengths"])
        # a region along the boundary shows the edges it covers, first-last
        edges = " ".join(str(r[0]) if len(r) == 1 else f"{r[0]}-{r[-1]}"
                         for r in g["region_edges"])
        lines.append(f"{k + 1:>4}  {edges:<20} {g['min_region_length']:>11.4g}  {regs:<24} "
                     f"{q['resistance']:>18.4g} {q['epsilon_l1']:>8.4g}")
    return lines


def _jaw_boxes(report: dict[str, Any]) -> list[str]:
    """The parallel jaw on a planar part: its boxes of closing angles and offsets."""
    units = report["units"]
    lines = [f"{'rank':>4}  {'grip':<9} {'closing (deg)':<16} {'offset (' + units + ')':<20} "
             f"{'opening (' + units + ')':<18} {'contacts':<16} {'measure':>8}"]
    for k, g in enumerate(report["grasps"]):
        t = [math.degrees(x) for x in g["theta_rad"]]
        (c0, c1), (o0, o1) = g["offset"], g["opening"]
        kinds = g["contacts"]["a"]["kind"] + "/" + g["contacts"]["b"]["kind"]
        lines.append(f"{k + 1:>4}  {g['mode']:<9} {t[0]:6.1f} to {t[1]:<6.1f} "
                     f"{c0:7.3g} to {c1:<7.3g} {o0:6.3g} to {o1:<6.3g} "
                     f"{kinds:<16} {g['measure']:8.3g}")
    return lines


def _facets(report: dict[str, Any]) -> list[str]:
    """Two soft fingers, three fingers with friction or a parallel jaw on a solid: the
    facets, the regions' radius and centres."""
    units = report["units"]
    params = report["parameters"]
    jaw = params.get("contact_type") == "jaw"
    soft = params.get("contact_type") == "soft"
    lines = [f"rank  facets          radius ({units})" + ("  opening" if jaw else "")
             + ("  radii (leximin)" if soft else "") + "  centres"]
    for g in report["grasps"]:
        centres = "  ".join("(" + ", ".join(f"{v:.4g}" for v in c) + ")"
                            for c in g["centers"])
        facets = " ".join(str(f) for f in g["facets"])
        opening = f"  {g['opening']:>7.4g}" if jaw else ""
        if soft:
            opening = "  " + f"{', '.join(f'{v:.4g}' for v in g['radii']):<16s}"
        lines.append(f"{g['rank']:>4}  {facets:<14s}  {g['radius']:>12.4g}{opening}  "
                     f"{centres}")
    if params.get("contact_type") == "friction":
        how = "every triple of pieces the bound left open" if params["exhaustive"] else \
            f"the first {params['certified_triples']} triples of pieces (not exhaustive)"
        lines.append(f"three fingers: certified regions (a lower bound on the largest), "
                     f"searched {how}")
    elif jaw:
        lines.append("parallel jaw: the closing axis anywhere in the region on the first "
                     "facet (radius: its inscribed circle); the pads close flush on both "
                     "facets")
    return lines


#: Each plan kind's table (:func:`plan_kind`).
TABLES: dict[str, Callable[[dict[str, Any]], list[str]]] = {
    "fingers": _fingers, "jaw_boxes": _jaw_boxes, "facets": _facets}


def plan_kind(grasp: dict[str, Any]) -> str:
    """A report's plan kind, from the fields of one of its grasps: regions on a solid's
    ``facets``, the jaw's boxes (``gripper`` ``parallel_jaw``) or point fingers."""
    if "facets" in grasp:
        return "facets"
    return "jaw_boxes" if grasp.get("gripper") == "parallel_jaw" else "fingers"


def report_kind(report: dict[str, Any]) -> str:
    """A report's plan kind (:func:`plan_kind`), from its parameters where it has no
    plan: a solid's grippers name their ``contact_type``, the planar jaw is the
    ``parallel_jaw``."""
    if report["grasps"]:
        return plan_kind(report["grasps"][0])
    params = report["parameters"]
    if "contact_type" in params:
        return "facets"
    return "jaw_boxes" if params.get("gripper") == "parallel_jaw" else "fingers"


def demo_entry(part: str, report: dict[str, Any], reason: str | None
               ) -> tuple[dict[str, Any], str]:
    """``fcgrasp demo``'s summary entry of one plan report (its best plan's measure and
    where it is, by the plan's kind) and the line printed for it."""
    params = report["parameters"]
    best = report["grasps"][0] if report["grasps"] else None
    kind = report_kind(report)
    entry: dict[str, Any] = {}
    if kind == "facets":
        contact = params["contact_type"]
        who = "jaw" if contact == "jaw" else f"{params['fingers']} {contact}"
        entry.update({"gripper": params.get("gripper", "fingers"),
                      "fingers": params.get("fingers"), "contact_type": contact,
                      "mu": params["mu"],
                      "best_facets": None if best is None else list(best["facets"]),
                      "best_radius": None if best is None else best["radius"]})
        if best is None:
            return entry, f"{part:14s} {who:10s} no grasp: {reason}"
        shape = "a region" if contact == "jaw" else "octagons"
        return entry, (f"{part:14s} {who:10s} best facets {list(best['facets'])!s:16s}"
                       f"{shape} of radius {best['radius']:.3g} mm")
    if kind == "jaw_boxes":
        entry.update({"gripper": params["gripper"], "mu": params["mu"],
                      "best_theta_deg": None if best is None else list(best["theta_deg"]),
                      "best_offset": None if best is None else list(best["offset"]),
                      "best_measure": None if best is None else best["measure"]})
        if best is None:
            return entry, f"{part:14s} jaw        no grasp: {reason}"
        (t0, t1), (c0, c1) = best["theta_deg"], best["offset"]
        return entry, (f"{part:14s} jaw        closing {t0:.1f}-{t1:.1f} deg, "
                       f"offsets {c0:.1f}-{c1:.1f} mm")
    n = params["fingers"]
    entry.update({"fingers": n, "mu": params["mu"],
                  "best_edges": None if best is None else list(best["edges"]),
                  "best_min_region": None if best is None else best["min_region_length"]})
    if best is None:
        return entry, f"{part:14s} {n} fingers  no grasp: {reason}"
    return entry, (f"{part:14s} {n} fingers  best edges {list(best['edges'])!s:16s} "
                   f"min region {best['min_region_length']:7.3f} mm")


def plan_table(report: dict[str, Any]) -> list[str]:
    """The lines of a plan report's table (none without a plan)."""
    grasps = report["grasps"]
    return TABLES[plan_kind(grasps[0])](report) if grasps else []


def _parts(doc: dict[str, Any]) -> list[str]:
    """A drawing's parts: each outline's edges, holes, size and area."""
    parts = doc["parts"]
    if not parts:
        return []
    first = parts[0]
    lines = [f"{first['file']}: {len(parts)} part{'s' * (len(parts) != 1)} "
             f"({first['format']}, units {first['units']}: {first['units_note']}); * = the "
             f"default (the largest)",
             f"  {'index':>5}  {'id':<18} {'layer':<10} {'edges':>6} {'holes':>5}  "
             f"{'width x height':>22}  {'area':>11}"]
    for p in parts:
        mark = "*" if p["index"] == doc["default"] else " "
        ident = (p["id"] or "-")[:18]
        layer = (p["layer"] or "-")[:10]
        if p["part"] is None:
            lines.append(f"{mark} {p['index']:>5}  {ident:<18} {layer:<10} not usable: "
                         f"{p['error']}")
            continue
        v = [list(map(float, q)) for q in p["part"]["vertices"]]
        w = max(q[0] for q in v) - min(q[0] for q in v)
        h = max(q[1] for q in v) - min(q[1] for q in v)
        extra = "  (background)" if p["background"] else ""
        lines.append(f"{mark} {p['index']:>5}  {ident:<18} {layer:<10} "
                     f"{p['part']['edges']:>6} {len(p['part']['holes']):>5}  "
                     f"{f'{w:.4g} x {h:.4g}':>22}  {p['area']:>11.4g}{extra}")
    lines += [f"note: {note}" for note in doc.get("notes", [])]
    return lines


def _bodies(doc: dict[str, Any]) -> list[str]:
    """A mesh file's bodies: triangles, watertight, size and volume."""
    bodies = doc["bodies"]
    lines = [f"{doc['source']}: {len(bodies)} bod{'ies' if len(bodies) != 1 else 'y'} "
             f"(mesh, units {doc['units']}: {doc['units_note']}); * = the default (the "
             f"largest watertight)",
             f"  {'index':>5}  {'triangles':>9}  {'watertight':>10}  {'size':>26}  "
             f"{'volume':>11}"]
    for b in bodies:
        mark = "*" if b["index"] == doc["default"] else " "
        (x0, y0, z0), (x1, y1, z1) = b["bounds"]
        size = f"{x1 - x0:.4g} x {y1 - y0:.4g} x {z1 - z0:.4g}"
        lines.append(f"{mark} {b['index']:>5}  {b['triangles']:>9}  "
                     f"{'yes' if b['watertight'] else 'no':>10}  {size:>26}  "
                     f"{b['volume']:>11.4g}")
    return lines


def listing_table(doc: dict[str, Any]) -> list[str]:
    """The lines of ``fcgrasp parts``'s table (:func:`fcgrasp.io.report.part_listing`):
    a drawing's parts or a mesh's bodies."""
    return _bodies(doc) if "bodies" in doc else _parts(doc)
