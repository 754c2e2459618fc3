"""JSON reports of plans and checks: versioned, deterministic (sorted keys, rounded floats).

Layout of a plan report (``format_version`` 1)::

    {
      "fcgrasp": "0.1.0", "format_version": 1, "units": "mm",
      "part": {"vertices": [[x, y], ...], "holes": [...], "edges": E},
      "parameters": {"fingers": 2, "mu": 0.3, "top": 10, "rank_by": "min_region",
                     "margin_deg": 0.5, "workspace": null, "finger_radius": 0.0,
                     "disturbance": {"translation": 10.0, "rotation_deg": 15.0}},
      "grasps": [{"rank": 1, "edges": [i, j], "contact_type": "friction", "mu": 0.3,
                  "mode": "squeeze", "regions": [[[x, y], [x, y]], ...],
                  "region_lengths": [...], "min_region_length": l,
                  "contacts": [[x, y], ...], "normals": [[nx, ny], ...],
                  "quality": {"min_region": ..., "resistance": ..., "resistance_approx": ...,
                              "epsilon_l1": ..., "epsilon_linf": ...}}, ...],
      "reason": null
    }

``edges`` use the input vertex order (hole edges numbered after the outer ring's);
``grasps`` is empty when no grasp exists, and ``reason`` then says why.
"""

from __future__ import annotations

import json
from typing import Any

from . import __version__
from ._json import json_ready

FORMAT_VERSION = 1


def dumps(report: dict[str, Any]) -> str:
    """Deterministic JSON text (sorted keys, two-space indent, trailing newline)."""
    return json.dumps(json_ready(report), sort_keys=True, indent=2, allow_nan=False) + "\n"


def part_dict(polygon: Any) -> dict[str, Any]:
    return {"vertices": polygon.vertices, "holes": list(polygon.holes),
            "edges": polygon.n_edges}


def plan_report(polygon: Any, plans: list[Any], parameters: dict[str, Any], units: str,
                reason: str | None = None) -> dict[str, Any]:
    grasps = []
    for k, p in enumerate(plans):
        d = p.to_dict()
        d["rank"] = k + 1
        grasps.append(d)
    return {"fcgrasp": __version__, "format_version": FORMAT_VERSION, "units": units,
            "part": part_dict(polygon), "parameters": parameters, "grasps": grasps,
            "reason": None if plans else (reason or "no force-closure grasp")}


def check_report(polygon: Any, contacts: list[dict[str, Any]], verdict: Any, freedom: Any,
                 units: str) -> dict[str, Any]:
    """The report of ``fcgrasp check``: the contacts as read, the verdict of
    :meth:`~fcgrasp.Grasp.explain` and the total freedom (a twist cone)."""
    return {"fcgrasp": __version__, "format_version": FORMAT_VERSION, "units": units,
            "part": part_dict(polygon), "contacts": contacts,
            "force_closure": verdict.force_closure, "failed": verdict.failed,
            "escape_twist": verdict.escape_twist, "escape": verdict.escape_description,
            "total_freedom": {"rays": freedom.rays, "lines": freedom.lines}}


def demo_summary(plans: list[dict[str, Any]], units: str) -> dict[str, Any]:
    """The index ``demo.json`` of ``fcgrasp demo``: one entry per built-in plan."""
    return {"fcgrasp": __version__, "format_version": FORMAT_VERSION, "units": units,
            "plans": plans}
