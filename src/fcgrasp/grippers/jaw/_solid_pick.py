r"""A solid picked by a real hand: the solid alone or resting on a table in its most
stable pose, the hand's boxes (:class:`~fcgrasp.model.hands.ParallelHand`), and each
jaw region (:class:`~fcgrasp.spatial.jaw.SolidJawPlan`) kept where every placement of
the hand in it is collision free.

**The pose.**  Plans, poses and the table are in the part's frame; on a table the part
rests in its most stable pose (:func:`resting_pose`, the scene's ``part_pose``).  The
closing axis is the region's; the tool frame's ``y`` points from the midpoint between
the facets to facet ``A``, its ``z`` (the approach) is the direction across the axis
nearest to straight down onto the table (sideways where the axis is vertical), its
origin midway between the two facets at the region's centre.  The hand comes along ``z``
from ``approach`` away, opened ``2 clearance`` wider than the facets are apart (at most
its stroke), and closes.

**Why every placement of a region is collision free.**  A placement is the pose moved
by ``v - c`` for an axis point ``v`` of the region (centre ``c``); the region and the
hand's boxes are convex or covered by convex hulls, and the hand's motion (the approach,
the closing) is a segment, so the set a box sweeps over the region and the motion is
the convex hull of its corners moved by the region's hull's vertices and by the
motion's ends (a Minkowski sum of convex sets: exact for the hull).  Each such hull is
tested against the solid and the table by python-fcl; where one meets them, the region
is cut to the disc of its inscribed circle (its radius, the plan's measure, unchanged)
and tested again; a region that fails then is dropped.  At the grasp itself the pads,
and every finger box within the pad's circle around the axis, lie in a column the jaw's
region keeps clear of material beyond each facet (:mod:`fcgrasp.spatial.jaw`, with the
pad's diameter the pad box's diagonal), so they are not swept there: they touch the
facets.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np

from ...core.tolerances import STRIP_TOL
from ...errors import ArgumentError
from ...model.hands import ParallelHand
from ...spatial.jaw import largest_piece, region_fields
from ._pick import Scene

__all__ = ["resting_pose", "solid_tool_frame", "collision_free_plan", "pad_diameter",
           "scene_manager", "pick_dict", "hand_solid_plans"]

#: Sides of the polygon that stands for a region's inscribed disc (circumscribing it).
DISC_SIDES = 24


def pad_diameter(hand: ParallelHand) -> float:
    """The round pad of the solid jaw that covers the hand's pad box's face."""
    w, _, h = hand.pad_box.size
    return float(math.hypot(w, h))


def resting_pose(solid: Any, rest: int = 0) -> np.ndarray:
    """The solid's ``rest``-th most likely resting pose on the plane ``z = 0``
    (``trimesh.poses.compute_stable_poses``, most likely first): the transform (4 x 4)
    from the part's frame to the table's."""
    return _rest(solid, rest)[0]


def _rest(solid: Any, rest: int, orientation: Any = None) -> tuple[np.ndarray, float | None]:
    """:func:`resting_pose` and its likelihood; or, with an ``orientation`` (a unit
    quaternion x, y, z, w from the part's frame to the table's), the part so turned and
    lowered onto the table (its likelihood None: given, not computed)."""
    mesh = solid.mesh.copy()
    if orientation is not None:
        from ...io.moveit import rotation

        T = np.eye(4)
        T[:3, :3] = rotation(orientation)
        T[2, 3] = -float((mesh.vertices @ T[:3, :3].T)[:, 2].min())
        return T, None
    transforms, probs = mesh.compute_stable_poses()
    if not 0 <= rest < len(transforms):
        raise ArgumentError(f"rest must be from 0 to {len(transforms) - 1} (the part's "
                            f"stable poses), got {rest}", "rest")
    T = np.asarray(transforms[rest], float)
    lowest = float((mesh.vertices @ T[:3, :3].T + T[:3, 3])[:, 2].min())
    T[2, 3] -= lowest
    return T, float(probs[rest])


def up_in_part(T: np.ndarray | None) -> np.ndarray:
    """The table's upward normal in the part's frame (``z`` without a table)."""
    if T is None:
        return np.array([0.0, 0.0, 1.0])
    return np.asarray(T[:3, :3], float).T @ np.array([0.0, 0.0, 1.0])


def solid_tool_frame(plan: Any, up: Any = (0.0, 0.0, 1.0)) -> tuple[np.ndarray, np.ndarray]:
    """The tool frame of a region's centre (the module's docstring; ``up`` the table's
    normal in the part's frame): origin and axes as columns ``x, y, z``."""
    c = np.asarray(plan.centers, float)
    origin = c.mean(axis=0)
    y = c[0] - origin
    y /= np.linalg.norm(y)
    down = -np.asarray(up, float)
    z = down - (down @ y) * y
    if np.linalg.norm(z) < 0.1:                # a vertical axis: come from the side
        side = np.eye(3)[int(np.argmin(np.abs(y)))]
        z = side - (side @ y) * y
    z /= np.linalg.norm(z)
    return origin, np.stack([np.cross(y, z), y, z], axis=1)


def _fcl() -> Any:
    try:
        import fcl  # noqa: F401
        import trimesh
    except ImportError:
        raise ArgumentError("a hand on a solid needs python-fcl and trimesh (pip install "
                            "'fcgrasp[robot]')", "hand") from None
    return trimesh


def _hull(points: np.ndarray) -> Any:
    import trimesh

    return trimesh.convex.convex_hull(points)


def _wide(hand: ParallelHand, scene: Scene, opening: float) -> float:
    """The opening the hand comes at: ``2 clearance`` wider than the grasp's, at most
    its stroke."""
    return float(min(hand.stroke[1], opening + 2 * scene.clearance))


def _in_column(hand: ParallelHand, box: Any, radius: float) -> bool:
    """A finger box within the pad's circle around the closing axis (tool ``x``, ``z``
    at most ``radius`` from the pad's centre line) and behind the pad's face."""
    c = box.corners()
    px = (np.asarray(hand.pad_box.corners())[:, [0, 2]]).mean(axis=0)
    tol = STRIP_TOL * max(1.0, float(np.abs(c).max()))
    return bool(np.all(np.hypot(c[:, 0] - px[0], c[:, 2] - px[1]) <= radius + tol)
                and np.all(c[:, 1] >= -tol))


def scene_manager(solid: Any, rest: np.ndarray | None) -> Any:
    """python-fcl's collision manager of the solid and the table under it (the table's
    slab in the part's frame, ``rest`` the part's pose on it), or of the solid alone."""
    trimesh = _fcl()
    manager = trimesh.collision.CollisionManager()
    manager.add_object("part", solid.mesh)
    if rest is not None:
        slab = trimesh.creation.box(extents=(1e6, 1e6, 10.0))
        slab.apply_translation((0.0, 0.0, -5.0))
        slab.apply_transform(np.linalg.inv(rest))
        manager.add_object("table", slab)
    return manager


def collision_free_plan(plan: Any, solid: Any, hand: ParallelHand, scene: Scene,
                        manager: Any, rest: np.ndarray | None = None) -> Any:
    """The plan with its region cut to where the hand is collision free (the module's
    docstring; ``manager`` :func:`scene_manager`'s, ``rest`` the part's pose on the
    table), or None."""
    import shapely

    origin, R = solid_tool_frame(plan, up_in_part(rest))
    h = float(plan.opening)
    if h > hand.stroke[1]:
        return None
    facet = solid.facets[plan.facets[0]]
    centre = np.asarray(plan.centers[0], float)
    # each box's corners (tool frame, pulled in a hair: a pad touching its facet is no
    # collision) at the wide opening the hand comes at and at the grasp; the palm does
    # not move while the hand closes, and the boxes in the pad's column touch
    shrink = STRIP_TOL * solid.size
    radius = pad_diameter(hand) / 2
    wide = [b.corners(shrink) for b in hand.boxes(_wide(hand, scene, h))]
    closed = [b.corners(shrink) for b in hand.boxes(h)]
    moving = [False] * len(hand.palm) + 2 * [not _in_column(hand, b, radius)
                                             for b in hand.finger]

    def hulls_clear(shift: np.ndarray, origin: np.ndarray, R: np.ndarray) -> bool:
        """Every box's sweep over the region's hull vertices ``shift`` (k, 3) from the
        pose ``origin``, ``R`` clear of the part and the table: coming along the
        approach at the wide opening, then closing."""
        approach = -scene.approach * R[:, 2]
        sweeps = [[origin + c @ R.T + a for a in (0.0, approach)] for c in wide]
        sweeps += [[origin + c @ R.T, origin + d @ R.T]
                   for c, d, m in zip(wide, closed, moving, strict=True) if m]
        for ends in sweeps:
            pts = np.concatenate([e[:, None, :] + shift[None, :, :] for e in ends])
            if manager.in_collision_single(_hull(pts.reshape(-1, 3))):
                return False
        return True

    piece = shapely.Polygon(facet.to_2d(np.asarray(plan.regions[0], float)),
                            [facet.to_2d(np.asarray(hh, float)) for hh in plan.holes[0]])
    if rest is not None:
        # the table: a placement moved by v - c lowers the hand by (v - c) . up, so the
        # placements above the table by ``clearance`` are a half-plane of the region
        up = up_in_part(rest)
        floor = float(np.linalg.inv(rest)[:3, 3] @ up)          # the table's height
        lowest = min(float(np.min((origin + b.corners() @ R.T) @ up))
                     for b in hand.boxes(_wide(hand, scene, h)) + hand.boxes(h))
        need = floor + scene.clearance - lowest                  # (v - c) . up >= need
        if need > 0:
            e = facet.to_2d(centre + up) - facet.to_2d(centre)  # up, seen in A's plane
            if np.hypot(*e) <= STRIP_TOL:
                return None                 # the plane is level: no placement rises
            e = e / float(np.hypot(*e) ** 2)
            # (v - c) . up = (q - q_c) . e' in A's coordinates, e' the projection of up
            far = 4 * solid.size
            q0 = facet.to_2d(centre) + need * e
            t = np.array([-e[1], e[0]]) / np.hypot(*e)
            n2 = e / np.hypot(*e)
            half = shapely.Polygon([q0 - far * t, q0 + far * t, q0 + far * t + far * n2,
                                    q0 - far * t + far * n2])
            piece = shapely.intersection(piece, half)
    for attempt in range(2):
        if isinstance(piece, shapely.MultiPolygon):
            piece = max(piece.geoms, key=lambda g: g.area)
        if not isinstance(piece, shapely.Polygon) or piece.is_empty or piece.area <= 0:
            return None
        _, r, c2 = largest_piece(piece)
        if r <= 0:
            return None
        shift = np.asarray(plan.centers[1], float) - centre
        got = replace(plan, radius=float(r), **region_fields(facet, piece, c2, shift))
        o2, R2 = solid_tool_frame(got, up_in_part(rest))
        hull = facet.to_3d(np.asarray(piece.convex_hull.exterior.coords)[:-1])
        if hulls_clear(hull - np.asarray(got.centers[0]), o2, R2):
            return got
        if attempt == 0:
            # the inscribed disc (a polygon around it), the plan's radius unchanged
            ang = np.linspace(0, 2 * np.pi, DISC_SIDES, endpoint=False)
            r_out = r / math.cos(math.pi / DISC_SIDES)
            piece = shapely.intersection(piece, shapely.Polygon(
                c2 + r_out * np.c_[np.cos(ang), np.sin(ang)]))
    return None


def pick_dict(plan: Any, hand: ParallelHand, scene: Scene,
              rest: np.ndarray | None = None) -> dict[str, Any]:
    """The pose, the opening the hand comes at, its approach and retreat, of a region's
    centre, in the part's frame (``rest``: its pose on the table)."""
    from ...io.moveit import quaternion

    up = up_in_part(rest)
    origin, R = solid_tool_frame(plan, up)
    return {"pose": {"position": [float(v) for v in origin],
                     "orientation": list(quaternion(R)), "frame": "part"},
            "pre_grasp_opening": _wide(hand, scene, float(plan.opening)),
            **scene.motions(R[:, 2], up),
            "collision_free": True}


def hand_solid_plans(jaw: Any, solid: Any, top: int, margin: float, fraction: float) -> Any:
    """The jaw's regions on a solid kept where its hand is collision free
    (:func:`collision_free_plan`), distinct, best first: the search asked for four times
    ``top`` and four times more until ``top`` are kept or it has no more."""
    from ...core.budget import PlanList
    from ...spatial.alternatives import distinct_solid_plans
    from ...spatial.jaw import solid_jaw_plans

    hand, scene = jaw.hand, jaw.scene
    rest, likely = _rest(solid, scene.rest, scene.orientation) if scene.table else (None, None)
    manager = scene_manager(solid, rest)
    n = 4 * top
    while True:
        raw = solid_jaw_plans(solid, jaw.stroke, pad_diameter(hand), jaw.mu, top=n,
                              margin=margin)
        ok = []
        for p in raw:
            got = collision_free_plan(p, solid, hand, scene, manager, rest)
            if got is not None:
                ok.append(replace(got, pick=pick_dict(got, hand, scene, rest)))
        # a region cut for the hand may rank lower: by its radius again (stable)
        ok.sort(key=lambda q: -q.radius)
        kept = distinct_solid_plans(ok, fraction) if fraction else ok
        if len(kept) >= top or len(raw) < n or not getattr(raw, "complete", True):
            out = PlanList(kept[:top])
            placed = {k: v for k, v in scene.to_dict().items() if k != "thickness"}
            if likely is not None:
                placed["rest_probability"] = likely
            out.details = {"scene": {**placed, "part_pose": _pose_dict(rest)}}
            return out
        n *= 4


def _pose_dict(T: np.ndarray | None) -> dict[str, Any]:
    from ...io.moveit import quaternion

    if T is None:
        return {"position": [0.0, 0.0, 0.0], "orientation": [0.0, 0.0, 0.0, 1.0]}
    return {"position": [float(v) for v in T[:3, 3]],
            "orientation": list(quaternion(np.asarray(T[:3, :3])))}
