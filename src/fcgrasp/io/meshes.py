"""Mesh files: the bodies of a file and a solid part read from one.

Anything trimesh reads (STL, OBJ, PLY, GLB, 3MF, OFF) is split into its connected
**bodies**, converted to the units asked (``--units``, default millimetres) from the
file's own units where it records them (GLB and 3MF do), from ``file_units``, or else
taken in the units asked, and the body chosen (default: the largest watertight one) is
checked and cut into facets by :func:`fcgrasp.spatial.solid.solid_from_mesh`.
"""

from __future__ import annotations

import os
import warnings
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..core._checks import FloatArray
from ..spatial.solid import DEMO_SOLIDS, Solid, demo_mesh, demo_solid, solid_from_mesh
from .limits import Limits
from .units import FILE_UNITS, UNITS, check_units, conversion

__all__ = ["Body", "read_bodies", "default_body", "read_solid", "is_solid_source",
           "MESH_SUFFIXES"]

#: File suffixes read as meshes (by trimesh).
MESH_SUFFIXES = (".stl", ".obj", ".ply", ".glb", ".gltf", ".3mf", ".off")


def is_solid_source(source: str) -> bool:
    """``source`` names a solid: ``demo:`` one of :data:`DEMO_SOLIDS`, or a mesh file."""
    if source.startswith("demo:"):
        return source[5:] in DEMO_SOLIDS
    return source.lower().endswith(MESH_SUFFIXES)


@dataclass(frozen=True)
class Body:
    """One connected body of a mesh file: ``index``, its ``mesh`` (in the units asked),
    ``triangles``, ``watertight``, ``volume`` (0 when not watertight) and ``bounds``
    (2, 3)."""

    index: int
    mesh: Any = field(repr=False)
    triangles: int = 0
    watertight: bool = False
    volume: float = 0.0
    bounds: FloatArray = field(default_factory=lambda: np.zeros((2, 3)), repr=False)


def _file_scale(loaded: Any, source: str, units: str, file_units: str | None
                ) -> tuple[float, str]:
    """The factor from the file's units to ``units`` and a note saying where they came
    from (``file_units``, the file's own, or none: the units asked)."""
    import trimesh

    if file_units is not None:
        check_units(file_units, "file_units", FILE_UNITS)
        return conversion(file_units, units), f"file units {file_units} (asked)"
    own = getattr(loaded, "units", None)
    if own:
        try:
            mm = 25.4 * trimesh.units.to_inch(str(own))
        except (ValueError, KeyError, AttributeError):
            raise ValueError(f"{source}: the file's units {own!r} are not known: give "
                             f"file_units (--file-units)") from None
        return mm / conversion(units, "mm"), f"file units {own} (the file's own)"
    return 1.0, f"no units in the file: coordinates taken as {units}"


def _load_mesh(source: str, limits: Limits) -> Any:
    """trimesh's mesh of a file, its vertices merged by position (an exported OBJ splits
    them by normal and texture coordinate, which would open every seam), within
    ``limits`` (the file's bytes, its triangles).  Any failure of the format's reader is
    a ValueError naming the file."""
    import trimesh

    try:
        size = os.path.getsize(source)
    except OSError as exc:
        raise ValueError(f"{source}: not a readable mesh ({exc.strerror or exc})") from None
    limits.bytes(size, f"{source}: the file's bytes")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")         # a reader's warnings: the error says
            with np.errstate(all="ignore"):
                loaded = trimesh.load(source, force="mesh")
    except ImportError as exc:
        raise ValueError(f"{source}: reading this format needs {exc.name or 'a package'}: "
                         f"pip install 'fcgrasp[solid]'") from None
    except MemoryError:
        raise ValueError(f"{source}: not a readable mesh (it asks for more memory than "
                         f"there is)") from None
    except Exception as exc:        # trimesh's readers raise many kinds on broken files
        text = str(exc).splitlines()[0][:120] if str(exc) else type(exc).__name__
        raise ValueError(f"{source}: not a readable mesh ({text})") from None
    if not isinstance(loaded, trimesh.Trimesh) or len(loaded.faces) == 0:
        raise ValueError(f"{source}: no triangles in the file")
    limits.vertices(len(loaded.faces), f"{source}: the mesh's triangles")
    loaded.merge_vertices(merge_tex=True, merge_norm=True)
    return loaded


def default_body(bodies: list[Body]) -> Body:
    """The body a mesh file is planned on when none is chosen: the largest watertight
    one (:func:`read_bodies` lists them largest first), else the largest."""
    return next((b for b in bodies if b.watertight), bodies[0])


def read_bodies(source: str, units: str | None = None, file_units: str | None = None,
                limits: Limits | None = None) -> tuple[list[Body], str, str]:
    """The connected bodies of a mesh file (anything trimesh reads: STL, OBJ, PLY, GLB,
    3MF, OFF) or of ``demo:NAME`` a built-in solid, converted to ``units`` (default mm)
    from the file's own units (GLB, 3MF record them; ``file_units`` overrides; none:
    taken as ``units``), largest volume first; the units and a note on where they came
    from.  Vertices are merged by position; ``limits`` (:mod:`fcgrasp.io.limits`) bounds
    the file's bytes and triangles."""
    if not isinstance(source, str):
        raise TypeError(f"source must be a path, got {type(source).__name__}")
    units = check_units("mm" if units is None else units, "units", UNITS)
    if source.startswith("demo:"):                       # a built-in solid, in mm
        loaded = demo_mesh(source[5:])
        scale, note = conversion("mm", units), "built-in solids are in mm"
    else:
        loaded = _load_mesh(source, Limits.of(limits))
        scale, note = _file_scale(loaded, source, units, file_units)
    if scale != 1.0:
        loaded.apply_scale(scale)
    parts = loaded.split(only_watertight=False)
    bodies = [Body(0, m, int(len(m.faces)), bool(m.is_watertight),
                   abs(float(m.volume)) if m.is_watertight else 0.0,
                   np.asarray(m.bounds, float)) for m in parts]
    bodies.sort(key=lambda b: (-b.volume, -b.triangles))
    return [replace(b, index=k) for k, b in enumerate(bodies)], units, note


def read_solid(source: str, units: str | None = None, repair: bool = False,
               file_units: str | None = None, select: int | str | None = None,
               limits: Limits | None = None) -> Solid:
    """A solid from a mesh file or ``demo:NAME``: the body ``select`` (an index of
    :func:`read_bodies`; default the largest watertight one) in ``units`` (default mm;
    ``file_units`` as in :func:`read_bodies`), checked and cut into facets."""
    if not isinstance(source, str):
        raise TypeError(f"source must be a path or demo:NAME, got {type(source).__name__}")
    if source.startswith("demo:"):
        if units in (None, "mm"):
            return demo_solid(source[5:])
        target = check_units(units, "units", UNITS)
        mesh = demo_mesh(source[5:])
        mesh.apply_scale(conversion("mm", target))
        return solid_from_mesh(mesh, target, source)
    bodies, target, note = read_bodies(source, units, file_units, limits)
    if select is None:
        body = default_body(bodies)
    else:
        try:
            k = int(select)
        except (TypeError, ValueError):
            raise ValueError(f"select must be a body's index (see fcgrasp parts), got "
                             f"{select!r}") from None
        if not 0 <= k < len(bodies):
            raise ValueError(f"{source}: body {k} does not exist: the file holds "
                             f"{len(bodies)} (0 to {len(bodies) - 1}; see fcgrasp parts)")
        body = bodies[k]
    solid = solid_from_mesh(body.mesh, target, source, repair)
    solid.units_note = note
    return solid


#: The reading options a solid takes (:func:`read_solid`, as :func:`read_solid_with`
#: takes them); the others read drawings and images.
SOLID_OPTIONS = ("units", "file_units", "repair", "max_bytes", "max_elements",
                 "max_vertices")


def read_solid_with(source: str, select: int | str | None, options: dict[str, Any]) -> Solid:
    """:func:`read_solid` given :func:`fcgrasp.io.parts.load_part`'s keywords: those of
    :data:`SOLID_OPTIONS`; one that reads drawings (given a value other than its
    default) is refused by name."""
    unused = sorted(k for k, v in options.items() if k not in SOLID_OPTIONS
                    and v is not None and not (k == "clean" and v is True)
                    and not (k == "y_down" and v is False))
    if unused:
        raise ValueError(f"{source}: a solid is read with {', '.join(SOLID_OPTIONS)}: "
                         f"{', '.join(unused)} read drawings and images")
    return read_solid(source, units=options.get("units"), file_units=options.get("file_units"),
                      select=select, limits=Limits.of_options(options),
                      repair=bool(options.get("repair", False)))
