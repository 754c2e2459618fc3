"""The stress test of a solid held by point or soft fingers (part of
:mod:`fcgrasp.physics`): a convex mesh as it is, any other by the convex pieces of its
facets under the fingers."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core._checks import FloatArray
from ..core.tolerances import PLANAR_TOL, TOL
from ..errors import ArgumentError
from ._forces import TIP_RADIUS, _internal, cone_margin
from ._planar import (
    _METRES,
    _SETTINGS,
    PART_MASS,
    RAMP_TIME,
    RECORD_TIME,
    ROLL_FRICTION,
    SERVO_COMPLIANCE,
    SLIP_DISPLACEMENT,
    SLIP_ROTATION_DEG,
    StressResult,
    _finger_bodies,
    _mujoco,
    _settle,
    _steps,
    vary,
)

# ----------------------------------------------------------------------------- solids

#: A soft fingertip's torsional friction: the moment about the normal it resists per
#: newton of normal force, as a share of the part's size (MuJoCo's torsional friction
#: coefficient, and the certificate's ``torsion``).
TORSION = 0.005


def solid_squeeze(points: Any, inward: Any, mu: float, torsion: float, grip_force: float,
                  center: Any, radius: float) -> FloatArray | None:
    """:func:`squeeze_forces` on a solid: the normal forces of fingers (point contacts
    with friction, or soft with ``torsion``) in equilibrium within their pyramids of
    :func:`fcgrasp.spatial.contacts.contact_wrench_generators` (unit normal components),
    the smallest as large as it can be, scaled so the largest is ``grip_force``."""
    from ..spatial.contacts import contact_wrench_generators

    gens = contact_wrench_generators(points, inward, mu, torsion, center=center,
                                     radius=radius)                  # (k, g, 6)
    k, g = gens.shape[:2]
    # the generators' normal components are 1
    return _internal(gens.reshape(k * g, 6), np.ones(k * g), np.repeat(np.arange(k), g), k,
                     grip_force)


def solid_stress_test(solid: Any, points: Any, normals: Any, mu: float, direction: Any,
                      soft: bool = False, grip_force: float = 10.0, ramp: float = 3.0,
                      record: bool = False, torsion: float | None = None,
                      variant: str = "default") -> StressResult:
    """One grasp of a solid (points and outward normals in the solid's units;
    ``soft``: soft fingers with :data:`TORSION`, or ``torsion``: the moment they resist
    per newton, in the solid's units) under a disturbance ``direction`` (a
    force and a torque per newton, ``(fx, fy, fz, tx, ty, tz)``, the torque in N x the
    solid's unit), as :func:`stress_test` runs a planar part: the part free in space
    (no gravity), each finger a sphere on a servoed slide along its inward normal.  The
    certified payload is the grasp's Ferrari-Canny L1 measure
    (:func:`fcgrasp.spatial.spatial_quality`, pyramids inscribed in the cones; torques
    over the part's size) times the smallest squeeze: the normal forces of a wrench
    within the measure's ball sum to at most that, so no finger exceeds its own.
    ``record``: keep the part's motion every 5 ms (``history``: time, load,
    displacement, rotation in degrees, the centre's shift x, y, z, the rotation as a
    unit quaternion w, x, y, z; :func:`animate_solid` draws it).  ``variant``: the
    simulator's settings, varied (:data:`~fcgrasp.physics.VARIANTS`)."""
    from ..spatial.closure import closure_margin
    from ..spatial.quality import spatial_quality

    mujoco = _mujoco()
    mesh = solid.mesh
    p, n = np.asarray(points, float), np.asarray(normals, float)
    n = n / np.linalg.norm(n, axis=1)[:, None]
    if not bool(mesh.is_convex):
        # a point sampled in a region across facets may lie off the surface: the finger
        # touches where it meets the part along its normal (on a convex mesh the
        # finger's slide finds it)
        p = np.array([_meets(solid, q, -m) for q, m in zip(p, n, strict=True)])
    u = np.asarray(direction, float)
    metres = _METRES.get(str(solid.units), _METRES["mm"])
    size_u = float(np.linalg.norm(mesh.extents))
    size = size_u * metres
    centre = np.asarray(solid.center, float)
    gamma = (TORSION * size_u if torsion is None else float(torsion)) if soft else 0.0
    preload = solid_squeeze(p, -n, mu, gamma, grip_force, centre, size_u)
    if preload is None:
        preload = np.full(len(p), float(grip_force))
        cert = 0.0
    else:
        eps = spatial_quality(p, -n, mu, gamma, center=centre, radius=size_u).epsilon_l1
        cert = float(eps * preload.min())
    kp = preload / (SERVO_COMPLIANCE * size)
    spin = gamma * metres
    friction = (f'friction="{max(mu, TOL):.9g} {max(spin, TOL):.9g} {ROLL_FRICTION}" '
                f'condim="{(4 if soft else 3) if mu > 0 else 1}"')
    fingers, actuators = _finger_bodies(p * metres, n, TIP_RADIUS * size, kp, preload,
                                        friction)
    assets, geoms = _part_geoms(solid, p, n, metres, friction)
    xml = (f'<mujoco>{_SETTINGS}<asset>{assets}</asset>'
           f'<worldbody><body name="part"><freejoint/>{geoms}</body>'
           f'{"".join(fingers)}</worldbody><actuator>{"".join(actuators)}</actuator>'
           f'</mujoco>')
    model = vary(mujoco.MjModel.from_xml_string(xml), variant)
    data = _settle(model, preload, kp)
    body = model.body("part").id
    x0, q0 = data.xpos[body].copy(), data.xquat[body].copy()

    def motion() -> tuple[float, float]:
        dq = float(abs(np.dot(data.xquat[body], q0)))
        return float(np.linalg.norm(data.xpos[body] - x0)), 2 * math.acos(min(dq, 1.0))

    settle = float(np.linalg.norm(x0 - model.qpos0[:3]))
    top = ramp * cert if cert > 0 else float(grip_force)
    n_ramp = _steps(model, RAMP_TIME)
    every = _steps(model, RECORD_TIME)
    slip = None
    if settle > SLIP_DISPLACEMENT * size:
        slip, n_ramp = 0.0, 0
    hist: list[tuple[float, ...]] = []
    for k in range(1, n_ramp + 1):
        load_now = top * k / n_ramp
        data.xfrc_applied[body, :3] = load_now * u[:3]
        data.xfrc_applied[body, 3:] = load_now * u[3:] * metres
        mujoco.mj_step(model, data)
        moved, turned = motion()
        if record and k % every == 0:
            # the part's motion from its squeezed pose: its centre's shift (part units)
            # and its rotation (a unit quaternion w, x, y, z)
            dq = np.empty(4)
            mujoco.mju_mulQuat(dq, data.xquat[body], np.array([q0[0], *(-q0[1:])]))
            hist.append((k * float(model.opt.timestep), load_now, moved / metres,
                         math.degrees(turned), *((data.xpos[body] - x0) / metres), *dq))
        if moved > SLIP_DISPLACEMENT * size or turned > math.radians(SLIP_ROTATION_DEG):
            slip = load_now
            break
    moved, turned = motion()

    def closed(m: float) -> bool:                # (a finger without friction: no torsion)
        return bool(closure_margin(p, -n, m, gamma if m > 0 else 0.0, center=centre,
                                   radius=size_u).closure)

    return StressResult(p, n, preload, cert, slip, moved / metres, math.degrees(turned),
                        settle / metres, u, np.array(hist).reshape(-1, 11),
                        cone_margin(closed, mu))


def _mesh_asset(name: str, vertices: Any, faces: Any = None) -> str:
    verts = " ".join(f"{x:.12g}" for x in np.asarray(vertices, float).ravel())
    if faces is None:                   # MuJoCo takes the points' convex hull
        return f'<mesh name="{name}" vertex="{verts}"/>'
    face = " ".join(str(int(i)) for i in np.asarray(faces).ravel())
    return f'<mesh name="{name}" vertex="{verts}" face="{face}"/>'


def _part_geoms(solid: Any, points: FloatArray, normals: FloatArray, metres: float,
                friction: str) -> tuple[str, str]:
    """The part's collision geometry: a convex mesh as it is (MuJoCo collides a mesh's
    convex hull); a mesh that is not convex as convex prisms under each contact, the
    convex pieces of the facet under the finger near it
    (:attr:`fcgrasp.spatial.solid.Facet.pieces`, :func:`_contact_prisms`), with the
    mesh's own mass and inertia (:data:`PART_MASS`).  The fingers meet the part only at
    their contacts, and a grasp that slips is seen to before a finger leaves its facet's
    pieces (:data:`SLIP_DISPLACEMENT`)."""
    mesh = solid.mesh
    if bool(mesh.is_convex):
        return (_mesh_asset("part", np.asarray(mesh.vertices) * metres, mesh.faces),
                f'<geom type="mesh" mesh="part" mass="{PART_MASS}" {friction}/>')
    props = mesh.mass_properties
    scale = PART_MASS / float(props["volume"])
    inertia = np.asarray(props["inertia"], float) * scale * metres ** 2
    com = np.asarray(props["center_mass"], float) * metres
    inertial = (f'<inertial pos="{com[0]:.12g} {com[1]:.12g} {com[2]:.12g}" '
                f'mass="{PART_MASS}" fullinertia="{inertia[0, 0]:.12g} {inertia[1, 1]:.12g} '
                f'{inertia[2, 2]:.12g} {inertia[0, 1]:.12g} {inertia[0, 2]:.12g} '
                f'{inertia[1, 2]:.12g}"/>')
    assets, geoms = [], [inertial]
    for k, (pt, out) in enumerate(zip(points, normals, strict=True)):
        for j, prism in enumerate(_contact_prisms(solid, pt, out)):
            assets.append(_mesh_asset(f"piece{k}_{j}", prism * metres))
            geoms.append(f'<geom type="mesh" mesh="piece{k}_{j}" {friction}/>')
    return "".join(assets), "".join(geoms)


#: The facet's convex pieces within this share of the part's size of a contact each
#: make a prism under it (the finger may slide a little before the part is seen to slip).
NEAR_PIECES = 0.1
#: The least cosine between a facet's inward normal and a finger's push for the facet's
#: pieces to make prisms under it: a curved surface's neighbouring facets, not the walls
#: of a corner the fingertip sits in.
FACING = 0.5


def _contact_prisms(solid: Any, point: FloatArray, outward: FloatArray) -> list[FloatArray]:
    """The points of the convex prisms under a contact: where the finger, coming along
    the contact's inward normal, meets the mesh, every convex piece of a facet that
    faces the finger (:attr:`fcgrasp.spatial.solid.Facet.pieces`) within
    :data:`NEAR_PIECES` of that point and turned from the push by less than
    :data:`FACING`'s angle, each with the same piece moved inward by half the
    part's thickness (a ray's run inside, at the contact and at the piece's centre).
    On a flat facet they are its pieces around the contact; on a curved surface, the
    facets of its tessellation around it."""
    import shapely

    size = float(np.linalg.norm(solid.mesh.extents))
    inward = -np.asarray(outward, float) / float(np.linalg.norm(outward))
    hit = _meets(solid, point, inward)
    at = _thickness(solid, hit, inward)
    out = []
    for f in solid.facets:
        if float(f.normal @ inward) <= FACING:
            continue                    # a facet the finger does not push on
        off = float((hit - f.origin) @ f.normal)
        q = shapely.Point(f.to_2d(hit))
        for piece in f.pieces:
            if math.hypot(float(piece.distance(q)), off) > NEAR_PIECES * size:
                continue
            ring = f.to_3d(np.asarray(piece.exterior.coords)[:-1])
            middle = f.to_3d(np.asarray(piece.representative_point().coords)[0])
            depth = min(at, _thickness(solid, middle, f.normal)) / 2
            out.append(np.concatenate([ring, ring + depth * f.normal]))
    return out


def _first_hit(solid: Any, start: FloatArray, direction: FloatArray) -> FloatArray | None:
    """Where a ray from ``start`` along ``direction`` first meets the mesh (None: it
    does not)."""
    hits, _, _ = solid.mesh.ray.intersects_location([start], [direction])
    if not len(hits):
        return None
    return np.asarray(hits[int(np.argmin(np.linalg.norm(hits - start, axis=1)))], float)


def _meets(solid: Any, point: FloatArray, inward: FloatArray) -> FloatArray:
    """Where a finger coming along ``inward`` from outside, through ``point``, first
    meets the mesh (from :data:`NEAR_PIECES` of the part's size out)."""
    inward = np.asarray(inward, float) / float(np.linalg.norm(inward))
    size = float(np.linalg.norm(solid.mesh.extents))
    hit = _first_hit(solid, np.asarray(point, float) - inward * NEAR_PIECES * size, inward)
    if hit is None:
        raise ArgumentError("a finger of the grasp meets no part of the solid along its "
                            "normal", "points")
    return hit


def _thickness(solid: Any, point: FloatArray, inward: FloatArray) -> float:
    """How far a ray from ``point`` into the part along ``inward`` runs before it
    leaves."""
    size = float(np.linalg.norm(solid.mesh.extents))
    start = point + PLANAR_TOL * size * inward
    hit = _first_hit(solid, start, inward)
    return size / 10 if hit is None else float(np.linalg.norm(hit - start))


def solid_plan_of(plan: Any) -> tuple[list[FloatArray], list[FloatArray], float, bool]:
    """A solid's finger plan (a plan object or a report's grasp) as its regions'
    corners, the regions' outward normals (per corner for a region across facets), its
    friction and whether the fingers are soft; a jaw is refused."""
    get = (lambda k, d=None: plan.get(k, d)) if isinstance(plan, dict) else \
        (lambda k, d=None: getattr(plan, k, d))
    kind = get("contact_type")
    if isinstance(plan, dict):
        outward = [np.asarray(nn, float) for nn in plan["normals"]]
    else:                                     # a plan object's normals point inward
        outward = [-np.asarray(nn, float) for nn in plan.normals]
        kind = "soft" if type(plan).__name__.startswith(("SoftPair", "SurfacePair")) \
            else "jaw" if hasattr(plan, "axis") else "friction"
    regions = [np.asarray(r, float) for r in get("regions")]
    return regions, outward, float(get("mu")), kind in ("soft", "jaw")


def solid_jaw_torsion(plan: Any) -> float | None:
    """A solid jaw plan's pads as soft contacts: the moment a round flat pad of diameter
    ``pad`` resists per newton under an even pressure, ``mu pad / 3`` (two thirds of
    ``mu`` times its radius); None for fingers."""
    get = (lambda k, d=None: plan.get(k, d)) if isinstance(plan, dict) else \
        (lambda k, d=None: getattr(plan, k, d))
    if get("contact_type") != "jaw" and not hasattr(plan, "axis"):
        return None
    return float(get("mu")) * float(get("pad")) / 3


def sample_solid_grasps(plan: Any, count: int, rng: np.random.Generator
                        ) -> list[tuple[FloatArray, FloatArray]]:
    """``count`` grasps of a solid's finger plan: the regions' centres, then each
    region's corners pulled a tenth of the way to its centre, then seeded points (convex
    combinations of the corners); each with its region's outward normal.  A jaw's:
    those points of its region on the first facet, each with the point of the second
    on the same closing axis."""
    regions, outward, _, _ = solid_plan_of(plan)
    if solid_jaw_torsion(plan) is not None:
        # the jaw: one closing axis through both pads, sampled on the first facet
        centers = plan["centers"] if isinstance(plan, dict) else plan.centers
        shift = np.asarray(centers[1], float) - np.asarray(centers[0], float)
        units = [nn / np.linalg.norm(nn) for nn in outward]
        return [(np.array([a, a + shift]), np.array(units))
                for a in _region_points(regions[0], np.asarray(centers[0], float), units[0],
                                        count, rng)]
    out = []
    for k in range(count):
        pts = []
        for reg in regions:
            centre = reg.mean(axis=0)
            if k == 0:
                pts.append(centre)
            elif k <= len(reg):
                pts.append(reg[k - 1] + 0.1 * (centre - reg[k - 1]))
            else:
                w = rng.dirichlet(np.ones(len(reg)))
                pts.append(w @ reg)
        out.append((np.array(pts), np.array([nn / np.linalg.norm(nn) for nn in outward])))
    return out


def _region_points(reg: FloatArray, centre: FloatArray, normal: FloatArray, count: int,
                   rng: np.random.Generator) -> list[FloatArray]:
    """``count`` points of a planar region (its ring ``reg``, ``centre`` a point inside,
    ``normal`` its plane's): the centre, its corners pulled a tenth of the way to the
    centre, then seeded convex combinations of its corners; each inside the region (a
    region need not be convex: a point outside is drawn again, the centre after a
    hundred tries)."""
    import shapely

    a = np.cross(normal, [1.0, 0.0, 0.0] if abs(normal[0]) < 0.9 else [0.0, 1.0, 0.0])
    a /= np.linalg.norm(a)
    b = np.cross(normal, a)

    def flat(q: FloatArray) -> Any:
        return np.stack([(q - centre) @ a, (q - centre) @ b], axis=-1)

    poly = shapely.Polygon(flat(reg)).buffer(0)
    out: list[FloatArray] = []
    for k in range(count):
        if k == 0:
            out.append(centre)
            continue
        q = reg[k - 1] + 0.1 * (centre - reg[k - 1]) if k <= len(reg) else None
        for _ in range(100):
            if q is not None and poly.covers(shapely.Point(flat(q))):
                break
            q = rng.dirichlet(np.ones(len(reg))) @ reg
        else:
            q = centre
        out.append(q)
    return out


def solid_escape(solid: Any, points: Any, normals: Any, mu: float, soft: bool) -> FloatArray:
    """A disturbance (force and torque per newton, as :func:`solid_stress_test` takes
    it) that the grasp does not resist (:func:`fcgrasp.spatial.closure_margin`'s
    ``unresisted`` wrench); an ``ArgumentError`` for a grasp in force closure."""
    from ..spatial.closure import closure_margin

    size_u = float(np.linalg.norm(solid.mesh.extents))
    gamma = TORSION * size_u if soft else 0.0
    verdict = closure_margin(points, -np.asarray(normals, float), mu, gamma,
                             center=np.asarray(solid.center, float), radius=size_u)
    if verdict.closure or verdict.unresisted is None:
        raise ArgumentError("the grasp is force closure: it has no escape", "points")
    w = np.asarray(verdict.unresisted, float)
    return np.r_[w[:3], w[3:] * size_u]
