"""A parallel gripper's hand read from its URDF description (yourdfpy for the
description, trimesh for its collision meshes): the palm and the fingers as boxes in
the tool frame of :class:`~fcgrasp.model.hands.ParallelHand`.

**What is read.**  The two fingers are the child links of the description's two
prismatic joints (the second usually a ``mimic`` of the first), moving in opposite
directions along one axis from a common parent link, the palm; every other link fixed
to the palm is part of it.  The approach direction is the palm link's ``z`` axis (the
convention of the Franka Hand, the Robotiq Hand-E and most descriptions: the fingers
point along it); the closing axis is the joints' axis.

**The boxes.**  A collision box is kept as it is; a sphere, a cylinder or a mesh is
covered by boxes, one per slab of :data:`SLAB` millimetres along the approach (each the
bounding box of the geometry's part in that slab, in the tool frame's axes), so a
finger that narrows towards its tip keeps its shape and every box covers what it
stands for: a pose collision free for the boxes is collision free for the hand.  The
pad is finger 1's material nearest the other finger: the slabs whose inner face lies
within :data:`PAD_TOL` of the innermost, joined into one box.

**The tool frame** has its origin between the two pads' faces, at the pad's centre
across and along the approach, ``y`` along the closing axis towards finger 1, ``z``
the approach; ``ee_frame`` is the palm link, and :attr:`ParallelHand.ee_offset` where
its origin lies in the tool frame.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from ..core.tolerances import ROUND_TOL, TOL
from ..errors import ArgumentError
from ..model.hands import HandBox, ParallelHand

__all__ = ["hand_from_urdf", "SLAB", "PAD_TOL"]

#: The thickness (mm) of the slabs a mesh is covered by, along the approach.
SLAB = 2.0
#: How close (mm) to the innermost face a slab's inner face is to count as the pad.
PAD_TOL = 0.05


def _load(path: str) -> Any:
    try:
        import yourdfpy
    except ImportError:
        raise ArgumentError("reading a hand's URDF needs yourdfpy and trimesh (pip "
                            "install 'fcgrasp[robot]')", "hand") from None
    if not os.path.isfile(path):
        raise ArgumentError(f"hand: no such URDF file: {path!r}", "hand")
    try:
        return yourdfpy.URDF.load(path, build_scene_graph=False, load_meshes=False,
                                  build_collision_scene_graph=False,
                                  load_collision_meshes=False)
    except Exception as exc:            # the library's own parse errors, named here
        raise ArgumentError(f"hand: {path!r} is not a URDF this reader takes: {exc}",
                            "hand") from None


def _mesh_file(name: str, urdf: Path) -> Path:
    """A collision mesh's file: relative to the URDF, or ``package://NAME/...`` found
    as a folder NAME among the URDF's parents."""
    if name.startswith("package://"):
        package, _, rest = name[len("package://"):].partition("/")
        for parent in urdf.resolve().parents:
            if parent.name == package:
                return parent / rest
        raise ArgumentError(f"hand: the mesh {name!r} names the package {package!r}, which "
                            f"is no folder above {str(urdf)!r}", "hand")
    if name.startswith("file://"):
        name = name[len("file://"):]
    p = Path(name)
    return p if p.is_absolute() else urdf.parent / p


def _geometry_points(geometry: Any, urdf: Path) -> tuple[str, Any]:
    """A collision geometry as a box ``("box", size)`` or as a mesh's vertices and faces
    ``("mesh", trimesh)`` in its own frame (metres)."""
    import trimesh

    if geometry.box is not None:
        return "box", np.asarray(geometry.box.size, float)
    if geometry.sphere is not None:
        return "mesh", trimesh.creation.icosphere(radius=float(geometry.sphere.radius),
                                                  subdivisions=2)
    if geometry.cylinder is not None:
        return "mesh", trimesh.creation.cylinder(radius=float(geometry.cylinder.radius),
                                                 height=float(geometry.cylinder.length))
    if geometry.mesh is not None:
        f = _mesh_file(geometry.mesh.filename, urdf)
        if not f.is_file():
            raise ArgumentError(f"hand: the collision mesh {str(f)!r} is missing", "hand")
        m = trimesh.load(str(f), force="mesh")
        if geometry.mesh.scale is not None:
            m.apply_scale(np.asarray(geometry.mesh.scale, float))
        return "mesh", m
    raise ArgumentError("hand: a collision geometry is none of box, sphere, cylinder, mesh",
                        "hand")


def _boxes(kind: str, shape: Any, T: np.ndarray, R_tool: np.ndarray, name: str
           ) -> list[tuple[str, np.ndarray, np.ndarray, np.ndarray]]:
    """Boxes ``(name, centre, size, rotation)`` in the tool frame's axes (``R_tool``: its
    axes as columns in the palm frame) covering one geometry placed by ``T`` (4 x 4,
    palm frame, millimetres): a box as it is, a mesh by slabs along the approach."""
    if kind == "box":
        R = R_tool.T @ T[:3, :3]
        return [(name, R_tool.T @ T[:3, 3], shape * 1000.0, R)]
    pts = (np.asarray(shape.vertices, float) * 1000.0) @ T[:3, :3].T + T[:3, 3]
    pts = pts @ R_tool                   # tool axes
    faces = np.asarray(shape.faces)
    z0, z1 = float(pts[:, 2].min()), float(pts[:, 2].max())
    n = max(1, math.ceil((z1 - z0) / SLAB))
    edges = np.linspace(z0, z1, n + 1)
    out = []
    tri = pts[faces]                     # (F, 3, 3)
    for k in range(n):
        lo, hi = edges[k], edges[k + 1]
        part = _clip_bounds(tri, lo, hi)
        if part is None:
            continue
        a, b = part
        out.append((f"{name}_{k}", (a + b) / 2, b - a, np.eye(3)))
    return out


def _clip_bounds(tri: np.ndarray, lo: float, hi: float) -> tuple[np.ndarray, np.ndarray] | None:
    """The bounds of the triangles' parts with ``lo <= z <= hi`` (exact: each triangle
    clipped to the slab, its corners and its edges' crossings of the two planes)."""
    pts = [tri.reshape(-1, 3)]
    for level in (lo, hi):
        for i, j in ((0, 1), (1, 2), (2, 0)):
            p, q = tri[:, i], tri[:, j]
            dz = q[:, 2] - p[:, 2]
            with np.errstate(divide="ignore", invalid="ignore"):
                s = (level - p[:, 2]) / dz
            ok = (dz != 0) & (s >= 0) & (s <= 1)
            pts.append(p[ok] + s[ok, None] * (q[ok] - p[ok]))
    allp = np.concatenate(pts)
    pad = ROUND_TOL * max(1.0, abs(lo), abs(hi))
    inside = allp[(allp[:, 2] >= lo - pad) & (allp[:, 2] <= hi + pad)]
    if not len(inside):
        return None
    return inside.min(axis=0), inside.max(axis=0)


def _origin(joint: Any) -> np.ndarray:
    return np.eye(4) if joint.origin is None else np.asarray(joint.origin, float)


def hand_from_urdf(path: str | os.PathLike[str], name: str | None = None) -> ParallelHand:
    """The hand of a URDF description (the module's docstring), in millimetres.

    Raises :class:`~fcgrasp.errors.ArgumentError` (field ``hand``) for a file that is
    not a URDF, a missing mesh, or a description without two opposite prismatic finger
    joints on one link."""
    urdf = Path(path)
    u = _load(str(urdf))
    joints = [j for j in u.robot.joints if j.type == "prismatic"]
    if len(joints) != 2 or joints[0].parent != joints[1].parent:
        raise ArgumentError(f"hand: {str(urdf)!r} must have two prismatic finger joints on "
                            f"one link (a parallel gripper), got "
                            f"{[j.name for j in joints] or 'none'}", "hand")
    j1, j2 = joints
    palm_link = j1.parent
    a1 = _origin(j1)[:3, :3] @ np.asarray(j1.axis, float)
    a2 = _origin(j2)[:3, :3] @ np.asarray(j2.axis, float)
    if a1 @ a2 > -1 + TOL or abs(a1[2]) > TOL:
        raise ArgumentError(f"hand: the finger joints of {str(urdf)!r} must move in opposite "
                            f"directions across the palm's z axis", "hand")
    lo, hi = float(j1.limit.lower), float(j1.limit.upper)
    m1 = 1.0 if j2.mimic is None else float(j2.mimic.multiplier)
    off2 = 0.0 if j2.mimic is None else float(j2.mimic.offset)
    # where each finger's collision geometry lies in the palm frame at joint value q
    by_link: dict[str, list[Any]] = {}
    for link in u.robot.links:
        by_link[link.name] = list(link.collisions)
    fixed_to_palm = {palm_link} | {j.child for j in u.robot.joints
                                   if j.type == "fixed" and j.parent == palm_link}

    shapes: dict[tuple[str, int], tuple[str, Any]] = {}     # each geometry read once

    def placed(link: str, base: np.ndarray) -> list[tuple[str, Any, np.ndarray]]:
        out = []
        for k, c in enumerate(by_link.get(link, [])):
            if (link, k) not in shapes:
                shapes[link, k] = _geometry_points(c.geometry, urdf)
            kind, shape = shapes[link, k]
            T = base @ (np.eye(4) if c.origin is None else np.asarray(c.origin, float))
            T = T.copy()
            T[:3, 3] *= 1000.0
            out.append((f"{link}_{k}", (kind, shape), T))
        return out

    def finger_at(joint: Any, q: float) -> np.ndarray:
        T = _origin(joint).copy()
        T[:3, 3] = T[:3, 3] + q * (T[:3, :3] @ np.asarray(joint.axis, float))
        return T

    # the tool axes: y towards finger 1 (the side its material is on), z the approach
    z = np.array([0.0, 0.0, 1.0])
    y = np.array([a1[0], a1[1], 0.0]) / math.hypot(a1[0], a1[1])
    R_tool = np.stack([np.cross(y, z), y, z], axis=1)     # tool axes in the palm frame

    def boxes_of(links: list[tuple[str, Any, np.ndarray]]) -> list[Any]:
        out = []
        for nm, (kind, shape), T in links:
            out += _boxes(kind, shape, T, R_tool, nm)
        return out

    def pad_of(boxes: list[Any]) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
        """A finger's pad: from its deepest slab up, the boxes whose inner face is within
        :data:`PAD_TOL` of the deepest's (the face, its bounds, which boxes)."""
        lo_b = np.array([c - _half(s, R) for _, c, s, R in boxes])
        hi_b = np.array([c + _half(s, R) for _, c, s, R in boxes])
        deepest = int(np.argmax(hi_b[:, 2]))
        face = float(lo_b[deepest, 1])
        mask = np.zeros(len(boxes), bool)
        reach = float(lo_b[deepest, 2])
        for k in np.argsort(-hi_b[:, 2], kind="stable"):
            if hi_b[k, 2] < reach - PAD_TOL:
                break                   # a gap along the approach: the pad ends
            if abs(lo_b[k, 1] - face) <= PAD_TOL:
                mask[k] = True
                reach = min(reach, float(lo_b[k, 2]))
        face = float(lo_b[mask, 1].min())
        return face, lo_b[mask].min(axis=0), hi_b[mask].max(axis=0), mask

    def face2(q: float) -> float:
        """Finger 2's pad face at joint value ``q``: seen from its side (y reflected),
        the largest y of its pad."""
        f2 = boxes_of(placed(j2.child, finger_at(j2, m1 * q + off2)))
        return -pad_of([(n, c * [1, -1, 1], s, R) for n, c, s, R in f2])[0]

    def faces(q: float) -> tuple[float, float]:
        return pad_of(boxes_of(placed(j1.child, finger_at(j1, q))))[0], face2(q)

    # finger 1's material on the tool's +y side (else the axes turned half about z)
    probe = boxes_of(placed(j1.child, finger_at(j1, lo)))
    if probe and np.mean([c[1] for _, c, _, _ in probe]) < 0:
        y = -y
        R_tool = np.stack([np.cross(y, z), y, z], axis=1)

    # the opening at the joint's two limits (affine in q between them)
    y1a, y2a = faces(lo)
    y1b, y2b = faces(hi)
    open_lo, open_hi = y1a - y2a, y1b - y2b
    if min(open_lo, open_hi) < -PAD_TOL or abs(open_hi - open_lo) < PAD_TOL:
        raise ArgumentError(f"hand: the fingers of {str(urdf)!r} do not open and close "
                            f"along their joints", "hand")
    per = (hi - lo) / (open_hi - open_lo)                  # joint per mm of opening
    q_closed = lo - per * open_lo                          # the joint at opening 0
    stroke = (max(0.0, min(open_lo, open_hi)), max(open_lo, open_hi))
    # finger 1 at opening 0, and its pad
    f1 = boxes_of(placed(j1.child, finger_at(j1, q_closed)))
    inner, lo_pad, hi_pad, is_pad = pad_of(f1)
    # the tool frame's origin: between the pads' faces, at the pad's centre across and
    # along the approach
    mid = np.array([(lo_pad[0] + hi_pad[0]) / 2, (inner + face2(q_closed)) / 2,
                    (lo_pad[2] + hi_pad[2]) / 2])

    def to_tool(items: list[Any], dy: float) -> tuple[HandBox, ...]:
        out = []
        for nm, c, s, R in items:
            c2 = np.asarray(c, float) - mid + np.array([0.0, dy, 0.0])
            out.append(HandBox(nm, tuple(float(v) for v in c2),  # type: ignore[arg-type]
                               tuple(float(v) for v in s),  # type: ignore[arg-type]
                               tuple(tuple(float(v) for v in r) for r in R)))
        return tuple(out)

    dy1 = -(inner - mid[1])
    finger = [b for b, k in zip(f1, is_pad, strict=True) if not k]
    lo_pad[1] = inner
    pad = ("pad", (lo_pad + hi_pad) / 2, hi_pad - lo_pad, np.eye(3))
    palm_items: list[Any] = []
    for link in sorted(fixed_to_palm):
        base = np.eye(4)
        for j in u.robot.joints:
            if j.type == "fixed" and j.child == link and j.parent == palm_link:
                base = _origin(j)
        palm_items += boxes_of(placed(link, base))
    palm = to_tool(palm_items, 0.0)
    fingers = to_tool([pad, *finger], dy1)
    ee = -mid
    return ParallelHand(
        name or u.robot.name or urdf.stem, stroke, palm, fingers, "pad",
        joints=(j1.name, j2.name), joint_per_opening=per, joint_offset=q_closed,
        source=str(urdf), licence="see the description", ee_frame=palm_link,
        ee_offset=tuple(float(v) for v in ee),  # type: ignore[arg-type]
        ee_axes=tuple(tuple(float(v) for v in row) for row in R_tool))


def _half(size: np.ndarray, R: np.ndarray) -> np.ndarray:
    """Half the extent along the tool axes of a box of ``size`` turned by ``R``."""
    return np.abs(np.asarray(R, float)) @ (np.asarray(size, float) / 2)


def _half_y(size: np.ndarray, R: np.ndarray) -> float:
    return float(_half(size, R)[1])
