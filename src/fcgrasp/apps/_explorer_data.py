"""What the explorer's page sends and receives: parts as the page holds them, its plan
options as a :class:`~fcgrasp.planning.PlanRequest`, the grasp-set overlays of plans
and the verdict of a grasp placed by hand (part of :mod:`fcgrasp.apps.serve`)."""

from __future__ import annotations

import json
import math
import os
import tempfile
import threading
from collections import OrderedDict
from dataclasses import replace
from typing import Any, TypeGuard

import numpy as np

from ..core.tolerances import ROUND_TOL
from ..errors import RequestError
from ..io.report import json_ready

# ----------------------------------------------------------------------------- parts


#: The page's gripper choices, as plan-request options.
GRIPPERS: dict[str, dict[str, Any]] = {
    "2": {"fingers": 2}, "3": {"fingers": 3}, "3g": {"fingers": 3, "gravity": (0.0, -1.0)},
    "4": {"fingers": 4}, "jaw": {"gripper": "jaw", "certify": True}}
_COMMON = ("margin", "rank_by", "top", "distinct", "time_limit")
#: The page's options each of its gripper choices uses (the page sends them all).
_PAGE_OPTIONS = {"2": ("mu", "along_boundary", *_COMMON),
                 "3": ("mu", "along_boundary", "bound", *_COMMON),
                 "3g": ("gravity", "along_boundary", *_COMMON),
                 "4": ("along_boundary", "bound", *_COMMON),
                 "jaw": ("mu", "stroke", "pad", "certify", "hand", "table", "thickness",
                         "in_plane", *_COMMON)}


def solid_choices() -> dict[str, tuple[str, ...]]:
    """The page's gripper choices that plan a solid (a mesh: two soft fingers, three
    fingers with friction, a parallel jaw), each with the options its gripper takes
    there: asked of the grippers (:func:`~fcgrasp.grippers.solids.plans_solids`, their
    ``solid_options``)."""
    from ..grippers.base import gripper_type
    from ..grippers.solids import plans_solids

    out = {}
    for key, kind in GRIPPERS.items():
        cls = gripper_type(kind.get("gripper", "fingers"), kind)
        if cls is not None and plans_solids(cls):
            out[key] = tuple(getattr(cls, "solid_options", ()))
    return out


def part_json(polygon: Any, units: str, name: str = "", notes: Any = ()) -> dict[str, Any]:
    """A part as the page holds it: a planar part's rings, units and a few measures for
    drawing; a solid's triangles (:func:`solid_json`)."""
    from ..grippers.solids import is_solid

    if is_solid(polygon):
        return solid_json(polygon, name)
    return json_ready({"outer": polygon.vertices, "holes": list(polygon.holes),
                       "units": units, "name": name, "edges": polygon.n_edges,
                       "size": polygon.size, "centroid": polygon.centroid,
                       "notes": list(notes)})


def solid_json(solid: Any, name: str) -> dict[str, Any]:
    """A solid as the page holds it: its triangles (``vertices``, ``faces``), units, the
    ``source`` it is planned from (``demo:NAME``, or the uploaded file's name: the page
    sends the triangles back) and a few measures for drawing."""
    mesh = solid.mesh
    return json_ready({"solid": True, "source": solid.source or name, "name": name,
                       "units": solid.units, "vertices": np.asarray(mesh.vertices),
                       "faces": np.asarray(mesh.faces), "facets": len(solid.facets),
                       "triangles": int(len(mesh.faces)), "size": solid.size,
                       "center": solid.center,
                       "notes": [solid.units_note] if solid.units_note else []})


def solid_of(data: dict[str, Any]) -> tuple[Any, str, str]:
    """The :class:`~fcgrasp.spatial.solid.Solid`, units and source of a solid sent by
    the page (:func:`solid_json`): a built-in solid read again by name, any other
    from its triangles (checked as a mesh file's are).  A :class:`RequestError` (field
    ``part``) says what is wrong."""
    from ..io.meshes import MESH_SUFFIXES, read_solid
    from ..io.units import UNITS
    from ..spatial.solid import DEMO_SOLIDS, solid_from_mesh

    source, units = data.get("source"), data.get("units", "mm")
    if not isinstance(source, str) or not (
            source[5:] in DEMO_SOLIDS if source.startswith("demo:")
            else source.lower().endswith(MESH_SUFFIXES)):
        raise RequestError(f"part.source must be demo:NAME of a built-in solid or a mesh "
                           f"file's name, got {_short(source)}", "part")
    if units not in UNITS:
        raise RequestError(f"part.units must be one of {', '.join(UNITS)}, got "
                           f"{_short(units)}", "part")
    try:
        if source.startswith("demo:"):
            return read_solid(source, units=units), units, source
        import trimesh

        v = np.asarray(data.get("vertices"), dtype=float)
        f = np.asarray(data.get("faces"), dtype=np.int64)
        if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3 \
                or f.size == 0 or f.min() < 0 or f.max() >= len(v):
            raise ValueError(f"vertices must be [x, y, z] points and faces [i, j, k] "
                             f"indices into them, got arrays of shapes {v.shape} and "
                             f"{f.shape}")
        mesh = trimesh.Trimesh(v, f, process=False)
        return solid_from_mesh(mesh, units, source), units, source
    except (ValueError, TypeError) as exc:
        raise RequestError(f"the solid is not valid: {exc}", "part") from None


def page_part(data: Any) -> tuple[Any, str, str]:
    """The part the page sends with a plan or a stress test, whichever it holds: a
    planar outline (:func:`polygon_of`, planned as ``explorer``) or a solid
    (:func:`solid_of`, planned from its source): the part (a :class:`~fcgrasp.Polygon`
    or a :class:`~fcgrasp.spatial.solid.Solid`), its units and its source."""
    if isinstance(data, dict) and data.get("solid") is True:
        return solid_of(data)
    polygon, units = polygon_of(data)
    return polygon, units, "explorer"


def as_part(shape: Any, source: str, units: str) -> Any:
    """The page's part (:func:`page_part`) as :func:`~fcgrasp.planning.plan_document`
    takes it: a part read from the page, an outline or a solid."""
    from ..grippers.solids import is_solid
    from ..io.parts import Part

    if is_solid(shape):
        return Part(None, source, "mesh", units=units, units_note=shape.units_note,
                    solid=shape)
    return Part(polygon=shape, source=source, format="explorer", units=units)


def demo_json(name: str) -> dict[str, Any]:
    """A built-in part or solid as the page holds it (:func:`part_json`), or a
    :class:`RequestError` naming them all (404)."""
    from ..io.parts import DEMO_PARTS, load_part
    from ..spatial.solid import DEMO_SOLIDS, demo_solid

    if name in DEMO_SOLIDS:
        return part_json(demo_solid(name), "mm", f"demo:{name}")
    if name not in DEMO_PARTS:
        raise RequestError(f"no built-in part {name!r} (one of "
                           f"{', '.join([*DEMO_PARTS, *DEMO_SOLIDS])})", "part", 404)
    p = load_part(f"demo:{name}")
    return part_json(p.polygon, p.units, p.source, p.notes)


def _is_pair(value: Any) -> TypeGuard[list[float]]:
    """Whether ``value`` is a JSON list of two finite numbers."""
    return (isinstance(value, list) and len(value) == 2
            and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                    and math.isfinite(v) for v in value))


def _ring(value: Any, name: str) -> list[list[float]]:
    if not isinstance(value, list) or len(value) < 3:
        raise RequestError(f"{name} must be a list of at least 3 [x, y] points, got "
                           f"{_short(value)}", "part")
    for k, p in enumerate(value):
        if not _is_pair(p):
            raise RequestError(f"{name}[{k}] must be [x, y] finite numbers, got {_short(p)}",
                               "part")
    return value


def _short(value: Any) -> str:
    text = json.dumps(value) if _jsonable(value) else repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _jsonable(value: Any) -> bool:
    try:
        json.dumps(value)
    except (TypeError, ValueError):
        return False
    return True


#: The parts :func:`polygon_of` checked last (by their JSON text): the page sends its
#: part with every plan, and a 2,000-edge outline takes 25 ms to check.
_CHECKED: OrderedDict[str, tuple[Any, str]] = OrderedDict()
_CHECKED_SIZE = 8
_CHECKED_LOCK = threading.Lock()


def polygon_of(data: Any) -> tuple[Any, str]:
    """The :class:`~fcgrasp.Polygon` and units of a part sent by the page
    (``{"outer": [[x, y], ...], "holes": [[[x, y], ...], ...], "units": "mm"}``).
    Raises :class:`RequestError` (field ``part``) saying what is wrong: a crossing edge,
    too few vertices, a malformed point.  A part sent again as the same JSON (the same
    numbers, the same types) is not checked again."""
    try:
        key = json.dumps(data, sort_keys=True, allow_nan=False)
    except (TypeError, ValueError):
        return _polygon_of(data)            # not JSON: the checks say what is wrong
    with _CHECKED_LOCK:
        got = _CHECKED.get(key)
        if got is not None:
            _CHECKED.move_to_end(key)
            return got
    got = _polygon_of(data)
    with _CHECKED_LOCK:
        _CHECKED[key] = got
        while len(_CHECKED) > _CHECKED_SIZE:
            _CHECKED.popitem(last=False)
    return got


def _polygon_of(data: Any) -> tuple[Any, str]:
    """:func:`polygon_of`, checked."""
    from ..io.units import UNITS
    from ..model.polygon import Polygon

    if not isinstance(data, dict):
        raise RequestError(f"part must be an object with 'outer', got {_short(data)}", "part")
    outer = _ring(data.get("outer"), "part.outer")
    holes = data.get("holes", [])
    if not isinstance(holes, list):
        raise RequestError(f"part.holes must be a list of rings, got {_short(holes)}", "part")
    holes = [_ring(h, f"part.holes[{k}]") for k, h in enumerate(holes)]
    units = data.get("units", "mm")
    if units not in UNITS and units != "px":
        raise RequestError(f"part.units must be one of {', '.join(UNITS)} or px, got "
                           f"{_short(units)}", "part")
    try:
        return Polygon(outer, holes), units
    except (ValueError, TypeError) as exc:
        raise RequestError(f"the outline is not valid: {exc}", "part") from None


def read_upload(body: bytes, name: str, part: str | None = None,
                units: str | None = None) -> dict[str, Any]:
    """A part of an uploaded file (any format ``fcgrasp plan`` reads), as
    :func:`part_json`: ``part`` (an index or an id, as ``--part``; default the largest,
    as the command line chooses) in ``units`` (as ``--units``; default mm), with the
    file's ``parts`` listed (index, id, layer, edges, area, whether usable, as
    ``fcgrasp parts`` lists them) and the index of the one taken."""
    from ..io.meshes import MESH_SUFFIXES, read_solid
    from ..io.parts import FORMATS, choose_part, list_parts
    from ..io.units import UNITS

    base = os.path.basename(name) or "upload"
    if units is not None and units not in UNITS:
        raise RequestError(f"units must be one of {', '.join(UNITS)}, got {_short(units)}",
                           "units")
    suffix = os.path.splitext(base)[1].lower()
    if suffix not in FORMATS and suffix not in MESH_SUFFIXES:
        suffix = ""            # the reader sniffs the content
    with tempfile.TemporaryDirectory(prefix="fcgrasp-upload-") as tmp:
        path = os.path.join(tmp, "part" + suffix)
        with open(path, "wb") as fh:
            fh.write(body)
        try:
            if suffix in MESH_SUFFIXES:       # a solid: its largest watertight body
                solid = read_solid(path, units=units, select=part)
                return part_json(replace(solid, source=base), solid.units, base)
            parts = list_parts(path, units=units)
            chosen = choose_part(parts, part)
        except (ValueError, TypeError, OSError) as exc:
            msg = str(exc).replace(path, base)
            raise RequestError(f"cannot read {base}: {msg}", "file") from None
    out = part_json(chosen.polygon, chosen.units, base, chosen.notes)
    out["part"] = chosen.index
    out["parts"] = [{"index": p.index, "id": p.id, "layer": p.layer,
                     "edges": None if p.polygon is None else p.polygon.n_edges,
                     "area": float(p.area), "usable": p.polygon is not None}
                    for p in parts]
    return out


# ----------------------------------------------------------------------------- plans


def plan_request(options: Any, name: str = "explorer", units: str | None = None) -> Any:
    """The :class:`~fcgrasp.planning.PlanRequest` of the page's ``options``::

        {"gripper": "2" | "3" | "3g" | "4" | "jaw", "mu": 0.3, "margin": 0.5,
         "rank_by": "min_region", "top": 10, "along_boundary": true,
         "stroke": [10, 50], "pad": 8, "certify": true, "gravity": [0, -1],
         "distinct": 0.5, "bound": true, "time_limit": 10,
         "hand": "franka", "table": true, "thickness": 6, "in_plane": false}

    (with ``hand``, a built-in hand's name, its own stroke and pads are used).

    checked whole here, before a job starts, with the command line's messages (a
    :class:`~fcgrasp.errors.RequestError` naming the option).  The page sends every
    option whatever the gripper; those of another gripper are not used.

    >>> plan_request({"gripper": "4", "top": 3}).to_argv()
    ['--fingers', '4', '--top', '3']
    """
    from ..io.meshes import is_solid_source
    from ..planning import PlanRequest

    solid = is_solid_source(name)
    kw = _request_options(options, solid)
    if units is not None and solid:
        # a mesh is read again in its units; an outline carries its own
        kw["units"] = units
    try:
        return PlanRequest(part=name, **kw)
    except RequestError:
        raise
    except (TypeError, ValueError) as exc:    # a value of the wrong type: its option
        field = getattr(exc, "field", None)
        raise RequestError(str(exc), field if field in _KNOWN else "options") from None


#: The keys of the page's options.
_KNOWN = ("gripper", "mu", "margin", "rank_by", "top", "along_boundary", "stroke", "pad",
          "gravity", "certify", "distinct", "bound", "time_limit", "hand", "table",
          "thickness", "in_plane")


def _request_options(options: Any, solid: bool = False) -> dict[str, Any]:
    """The page's options as :class:`~fcgrasp.planning.PlanRequest` keywords (those of
    the chosen gripper only; on a ``solid``, those it takes there: :func:`solid_choices`),
    or a RequestError for an unknown key, gripper or top."""
    if not isinstance(options, dict):
        raise RequestError(f"options must be an object, got {_short(options)}", "options")
    extra = sorted(set(options) - set(_KNOWN))
    if extra:
        raise RequestError(f"options: unknown option {extra[0]!r} (expected "
                           f"{', '.join(sorted(_KNOWN))})", "options")
    gripper = options.get("gripper", "2")
    used = solid_choices() if solid else _PAGE_OPTIONS
    if gripper not in used:
        what = "on a solid " if solid else ""
        raise RequestError(f"options.gripper {what}must be one of {', '.join(used)}, "
                           f"got {_short(gripper)}", "gripper")
    # the choice's kind, and its fixed options the gripper takes on this part
    kw: dict[str, Any] = {k: v for k, v in GRIPPERS[gripper].items()
                          if k in ("gripper", "fingers", "gravity") or k in used[gripper]}
    kw.update({k: options[k] for k in used[gripper] if options.get(k) is not None})
    if "along_boundary" in kw:
        kw["single_edge"] = kw.pop("along_boundary") is False
    kw.update({k: tuple(kw[k]) for k in ("stroke", "gravity") if isinstance(kw.get(k), list)})
    if kw.get("hand") is not None:
        # a page names a built-in hand, never a file of the server's
        from ..model.hands import HANDS

        if kw["hand"] not in HANDS:
            raise RequestError(f"options.hand must be one of {', '.join(sorted(HANDS))}, "
                               f"got {_short(kw['hand'])}", "hand")
        kw.pop("stroke", None)          # the hand's own stroke and pads
        kw.pop("pad", None)
    else:
        kw.pop("table", None)
        kw.pop("thickness", None)
        kw.pop("in_plane", None)
    top = kw.get("top")
    if top is not None and (isinstance(top, bool) or not isinstance(top, int)
                            or not 1 <= top <= 100):
        raise RequestError(f"options.top must be a whole number from 1 to 100, got "
                           f"{_short(top)}", "top")
    return kw


def overlay(polygon: Any, plan: Any) -> dict[str, Any] | None:
    """The grasp set of a plan's edges as shapes to draw (None where there is none):
    ``segments`` (the restricted edges ``e'_i``, theorem 6.3, for two fingers), ``polygons``
    (``Pi_12`` and ``Pi_34`` of algorithm 6.1 for four fingers or three with gravity) and
    ``cones`` (the two-sided sector ``C`` at the point between them: ``apex``, ``angle``,
    ``half`` in radians)."""
    from ..model.graspsets import FrictionGraspSet, grasp_set

    if not hasattr(plan, "edges"):            # a jaw's box, a solid's regions: none
        return None
    edges = list(plan.edges)
    try:
        if len(edges) == 2 and plan.contact_type == "friction":
            gs: Any = grasp_set(polygon, edges, mu=plan.mu)
        elif len(edges) == 4:
            gs = grasp_set(polygon, edges)
        elif len(edges) == 3 and plan.gravity is not None:
            gs = grasp_set(polygon, edges, gravity=plan.gravity["direction"])
        else:
            return None
    except ValueError:
        return None
    if isinstance(gs, FrictionGraspSet):
        segs = [np.asarray(s).tolist() for f in (0, 1) for s in gs.restricted_segments(f)]
        return {"kind": "e'", "segments": segs, "polygons": [], "cones": []}
    if gs.pi12 is None or gs.pi34 is None:
        return {"kind": "Pi", "segments": [], "polygons": [], "cones": []}
    polys, segs = [], []
    for g in (gs.pi12, gs.pi34):              # a parallelogram, or a segment or point
        if g.geom_type == "Polygon":
            polys.append(np.asarray(g.exterior.coords)[:-1].tolist())
        elif not g.is_empty:
            segs.append(np.asarray(g.coords).tolist())
    a = np.asarray(gs.pi12.centroid.coords[0])
    b = np.asarray(gs.pi34.centroid.coords[0])
    cone = {"apex": ((a + b) / 2).tolist(), "angle": gs.sector[0], "half": gs.sector[1]}
    return {"kind": "Pi", "segments": segs, "polygons": polys,
            "cones": [cone] if gs.sector[1] > 0 else []}


# ----------------------------------------------------------------------------- checks


#: Grasps of a plan the explorer's stress test runs (one disturbance each): with the
#: animation of one, a few seconds of CPU.
STRESS_SAMPLES = 4


def stress_result(part: Any, units: str, plan: Any) -> dict[str, Any]:
    """The explorer's stress test of one plan (a report's grasp) in MuJoCo
    (:func:`fcgrasp.physics.simulate`): :data:`STRESS_SAMPLES` grasps of it, each under
    one seeded disturbance, how many held to their certified payload and the least
    ratio of slip load to certified payload, and the animation of one of them (an
    animated GIF, base64).  A :class:`RequestError` (field ``plan``) for a plan the test
    does not take, or without MuJoCo."""
    import base64
    import os
    import tempfile

    if not isinstance(plan, dict):
        raise RequestError(f"plan must be a plan of the report, got {_short(plan)}", "plan")
    try:
        from ..physics import recorded_run, simulate

        rows = simulate(part, [plan], samples=STRESS_SAMPLES, directions=1, seed=0,
                        units=units, workers=1)
        row = rows[0]
        gif = None
        if row["grasps"]:
            got = recorded_run(part, plan, row["grasps"][0]["wrench_direction"], units=units)
            if got is not None:
                with tempfile.TemporaryDirectory() as tmp:
                    path = os.path.join(tmp, "stress.gif")
                    got[1](path)
                    with open(path, "rb") as fh:
                        gif = base64.b64encode(fh.read()).decode("ascii")
    except ImportError:
        raise RequestError("the stress test needs MuJoCo: pip install 'fcgrasp[sim]'",
                           "plan") from None
    except (ValueError, TypeError, KeyError, IndexError) as exc:
        raise RequestError(f"plan: {' '.join(str(exc).split()) or type(exc).__name__}",
                           "plan") from None
    return json_ready({"rank": plan.get("rank"), "runs": row["runs"], "held": row["held"],
                       "worst_ratio": row["worst_ratio"], "gif": gif})


def check_result(polygon: Any, data: dict[str, Any]) -> dict[str, Any]:
    """The verdict on a hand-placed grasp (theorem 6.1 by :meth:`~fcgrasp.Grasp.explain`):
    ``data`` holds ``contacts`` (and optionally ``gravity``) as in a contacts file."""
    from ..core.grasp import Grasp
    from ..core.screws import rotation_center
    from ..io.parts import contacts_from_data

    body = {k: data[k] for k in ("contacts", "gravity") if k in data and data[k] is not None}
    try:
        contacts, described = contacts_from_data(body, polygon, "check")
    except ValueError as exc:
        raise RequestError(str(exc), "contacts") from None
    rep = Grasp(contacts).explain()
    twist = rep.escape_twist
    centre = None
    if twist is not None and \
            abs(float(twist[0])) > ROUND_TOL * max(1.0, float(np.abs(twist).max())):
        centre = rotation_center(twist)
    return json_ready({"force_closure": rep.force_closure, "failed": rep.failed,
                       "verdict": str(rep), "escape": rep.escape_description,
                       "escape_twist": twist, "rotation_center": centre,
                       "contacts": described})
