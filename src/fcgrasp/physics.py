r"""A physics stress test of planned grasps: the part and the fingers in MuJoCo, loads
ramped up until the part slips (the paper's section 8: how much a grasp resists).

fcgrasp proves that every grasp of a plan's regions is force closure and certifies the
load it carries with force-limited fingers (:func:`fcgrasp.grasp_payload`).  This module
checks those figures in a physics simulator that shares none of that code: for each
grasp sampled in a plan's regions (the regions' ends included) and each of a few seeded
disturbance directions, it reports whether the part held, the load at which it slipped
and how far it moved, beside the certified payload.

**The model** (SI units inside; lengths in the part's units outside).  The planar part
is extruded into a prism of uniform density moving in its plane (two slides and a hinge:
no gravity in the plane).  Each finger is a sphere on a slide along its contact's inward
normal, driven by a stiff position servo: the squeeze phase sets each finger's preload
to a force that balances the others (a linear program over the friction cones: the
internal forces of the grasp, the largest smallest one, scaled so the largest is
``grip_force``; none exists when the grasp cannot be squeezed), and the servo saturates
at twice that.  Fingers that hold their position up to a limit of force are what the
certificate assumes: it is computed with each finger's preload as its force limit, so
the simulated fingers can always supply it (they can push harder, up to the
saturation).  The disturbance is a wrench of fixed direction (a force at the centre of
mass and a torque, per newton) ramped from 0 to ``ramp`` times the certified payload
over ``ramp_time`` seconds; the part **slipped** when it moved more than
``SLIP_DISPLACEMENT`` of the part's size or turned more than ``SLIP_ROTATION_DEG``.

**Settings that make the answer physics, not artefacts:** elliptic friction cones (the
Coulomb cone itself, not a pyramid); the noslip solver (MuJoCo's regularised friction
creeps without it: a grasp below its limit would slowly slide); stiff contacts
(``solref`` 2 ms, ``solimp`` 0.95-0.99) and friction as stiff as the normal
(``impratio`` 10); a 0.5 ms time step, a quarter of the contact's time constant; the
servo's stiffness puts the full preload at 0.2 % of the part's size (the fingers' own
motion stays well below the slip threshold) with critical damping.

**What it can and cannot tell:** it checks loads, not the exact ends of the regions (a
grasp at a region's end is at the margin of its friction cone, and a simulator's
contact is soft); a non-force-closure control slips under the disturbance along its
escape motion at loads far below any grip force.  MuJoCo is an optional dependency
(``pip install mujoco``, the ``sim`` extra).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from functools import partial
from typing import Any

import numpy as np

from .core._checks import FloatArray, check_int, check_scalar
from .core.tolerances import ON_EDGE_TOL, SQUEEZE_TOL, TINY, TOL
from .errors import ArgumentError

__all__ = ["simulate", "stress_test", "sample_grasps", "squeeze_forces", "StressResult",
           "control", "escape_direction", "SLIP_DISPLACEMENT", "SLIP_ROTATION_DEG",
           "animate", "jaw_stress_test", "jaw_contacts", "jaw_of", "sample_poses",
           "solid_stress_test", "solid_squeeze", "sample_solid_grasps", "solid_plan_of",
           "solid_escape", "control_runs"]

#: The part slipped when its centre moved more than this share of its size ...
SLIP_DISPLACEMENT = 0.01
#: ... or it turned more than this many degrees.
SLIP_ROTATION_DEG = 1.0
#: Simulation settings (see the module docstring for why each).
TIMESTEP = 5e-4
SETTLE_TIME = 0.2
RAMP_TIME = 1.0
#: The finger servo's full preload at this share of the part's size.
SERVO_COMPLIANCE = 2e-3
#: The part's mass (kg, whatever its size: the test is quasi-static, and a part of a
#: few milligrams between fingers of a tenth of a kilogram makes the dynamics stiff),
#: its prism's thickness (share of its size) and the fingertips' radius (share of the
#: size).
PART_MASS = 0.2
THICKNESS = 0.2
TIP_RADIUS = 0.002
#: A finger's mass (kg): at least this, and enough that its servo's period spans
#: :data:`SERVO_STEPS` time steps.
FINGER_MASS = 0.1
SERVO_STEPS = 20
#: A jaw pad's depth along the closing direction (share of the part's size).
PAD_DEPTH = 0.05
#: MuJoCo's torsional and rolling friction coefficients of the contacts (the motion is
#: planar: neither acts, but MuJoCo takes three coefficients).
SPIN_FRICTION = 0.005
ROLL_FRICTION = 0.0001
#: Millimetres and the other units a report may use, in metres.
_METRES = {"mm": 1e-3, "cm": 1e-2, "m": 1.0, "in": 0.0254, "px": 0.25e-3}


@dataclass
class StressResult:
    """One grasp under one disturbance: the contacts (part units) and their outward
    normals, the grip forces (N, per finger), the certified payload along the
    disturbance (N; 0 for a grasp that is not force closure), the load at which the
    part slipped (N; None: it held up to the ramp's end), how far it moved (part units;
    rotation in degrees) at the end, how far the squeeze moved it, and the direction
    (force and torque per newton, torque in N x part unit)."""

    contacts: FloatArray
    normals: FloatArray
    grip_force: FloatArray
    certified_payload: float
    slip_load: float | None
    displacement: float
    rotation_deg: float
    settle_motion: float
    direction: FloatArray
    history: FloatArray = field(repr=False, default_factory=lambda: np.zeros((0, 6)))

    @property
    def held(self) -> bool:
        """Whether the part held up to its certified payload (no slip at or below it)."""
        return self.slip_load is None or self.slip_load >= self.certified_payload

    def to_dict(self) -> dict[str, Any]:
        return {"contacts": self.contacts.tolist(), "normals": self.normals.tolist(),
                "grip_force": self.grip_force.tolist(),
                "certified_payload": self.certified_payload, "slip_load": self.slip_load,
                "displacement": self.displacement, "rotation_deg": self.rotation_deg,
                "settle_motion": self.settle_motion,
                "wrench_direction": _wrench_dict(self.direction)}


def _wrench_dict(d: FloatArray) -> dict[str, Any]:
    """A disturbance direction as the JSON says it: force and torque per newton (a
    planar torque is a number, a solid's a vector)."""
    if len(d) == 6:
        return {"force": d[:3].tolist(), "torque": d[3:].tolist()}
    return {"force": d[:2].tolist(), "torque": float(d[2])}


def _mujoco() -> Any:
    try:
        import mujoco  # type: ignore[import-untyped]
    except ImportError as exc:  # pragma: no cover - depends on the install
        raise ImportError("the stress test needs MuJoCo: pip install 'fcgrasp[sim]'") \
            from exc
    return mujoco


# ----------------------------------------------------------------------------- grasps

def sample_grasps(polygon: Any, regions: Any, count: int, rng: np.random.Generator,
                  normals: Any = None) -> list[tuple[FloatArray, FloatArray]]:
    """``count`` grasps of one point per region (a polyline along the boundary): the
    regions' starts, their ends, their middles, then seeded points; each with the
    outward normal of the edge it lies on.  Points are kept three fingertip radii off
    the vertices of the region's polyline (its ends included), moved along the region
    (a third of the edge at most): a fingertip on a corner touches both edges, where the
    certificate reads the contact on one.  A region that is a point (a given contact)
    keeps its own normal (``normals``, one per region), as does a region no longer than
    six fingertip radii (a corner)."""
    import shapely

    poly = shapely.Polygon(polygon.vertices, list(polygon.holes))
    eps = ON_EDGE_TOL * polygon.size
    lines = [np.asarray(r, float) for r in regions]
    cum = [np.r_[0.0, np.cumsum(np.hypot(*np.diff(r, axis=0).T))] for r in lines]
    fixed = [0.0, 1.0, 0.5]
    out = []
    for k in range(count):
        u = fixed[k] if k < len(fixed) else None
        pts, nrm = [], []
        for j, (r, c) in enumerate(zip(lines, cum, strict=True)):
            L = c[-1]
            if L <= 6 * TIP_RADIUS * polygon.size and normals is not None:
                # a region no longer than a fingertip: a corner, held with the plan's
                # normal there (a fingertip on a corner pushes along the fan's)
                given = np.asarray(normals[j], float)
                pts.append(r[0] + (r[-1] - r[0]) / 2 if len(r) == 2 else r[len(r) // 2])
                nrm.append(given / np.linalg.norm(given))
                continue
            s = (u if u is not None else float(rng.uniform())) * L
            s = min(max(s, eps), L - eps) if L > 2 * eps else L / 2
            i = int(np.clip(np.searchsorted(c, s, side="right") - 1, 0, len(r) - 2))
            off = min(3 * TIP_RADIUS * polygon.size, (c[i + 1] - c[i]) / 3)
            s = min(max(s, c[i] + off), c[i + 1] - off)
            t = (s - c[i]) / max(c[i + 1] - c[i], TINY)
            p = r[i] + t * (r[i + 1] - r[i])
            d = r[i + 1] - r[i]
            n = np.array([d[1], -d[0]]) / max(float(np.hypot(*d)), TINY)
            if poly.contains(shapely.Point(p + eps * 10 * n)):
                n = -n                            # outward: away from the part
            pts.append(p)
            nrm.append(n)
        out.append((np.array(pts), np.array(nrm)))
    return out


def _edges(points: FloatArray, normals: FloatArray, mu: float) -> tuple[FloatArray, ...]:
    """Each finger's force edges (its friction cone's two edges; the normal alone
    without friction), the finger of each, and the wrenches they exert."""
    forces, owner = [], []
    half = math.atan(mu)
    for i, n in enumerate(normals):
        f = -n / np.linalg.norm(n)
        for a in ((half, -half) if mu > 0 else (0.0,)):
            c, s = math.cos(a), math.sin(a)
            forces.append([c * f[0] - s * f[1], s * f[0] + c * f[1]])
            owner.append(i)
    F = np.array(forces)
    o = np.array(owner)
    P = points[o]
    W = np.c_[F, P[:, 0] * F[:, 1] - P[:, 1] * F[:, 0]]
    return F, o, W


def squeeze_forces(points: Any, normals: Any, mu: float, grip_force: float
                   ) -> FloatArray | None:
    """The normal forces of a squeeze that holds the part still: finger forces in their
    friction cones with zero net wrench whose smallest normal force is as large as it
    can be (a linear program), scaled so the largest is ``grip_force``; None when no
    squeeze has every normal force positive (the grasp cannot be squeezed)."""
    p, n = np.asarray(points, float), np.asarray(normals, float)
    F, o, W = _edges(p, n, mu)
    inward = -n / np.linalg.norm(n, axis=1)[:, None]
    Wn = W.copy()
    Wn[:, 2] /= max(float(np.max(np.abs(p))), TINY)
    # each edge's share of its finger's normal force
    return _internal(Wn, np.einsum("ij,ij->i", F, inward[o]), o, len(p), grip_force)


def _internal(columns: FloatArray, share: FloatArray, owner: FloatArray, k: int,
              grip_force: float) -> FloatArray | None:
    """The linear program of a squeeze: coefficients ``c >= 0`` of the force edges
    ``columns`` (m, d: their wrenches) with zero net wrench, each finger's normal force
    ``sum c share`` over its edges (``owner``) at most 1 and at least ``t``, ``t`` as
    large as it can be; the normal forces scaled so the largest is ``grip_force``, or
    None where ``t`` is not positive."""
    from scipy.optimize import linprog

    m, d = columns.shape
    A_eq = np.zeros((d, m + 1))
    A_eq[:, :m] = columns.T
    A_ub, b_ub = [], []
    for i in range(k):
        row = np.zeros(m + 1)
        row[:m] = -((owner == i) * share)
        row[m] = 1.0                                         # t <= normal_i
        A_ub.append(row)
        b_ub.append(0.0)
        row = np.zeros(m + 1)
        row[:m] = (owner == i) * share                       # normal_i <= 1
        A_ub.append(row)
        b_ub.append(1.0)
    c = np.zeros(m + 1)
    c[m] = -1.0
    res = linprog(c, A_ub=np.array(A_ub), b_ub=b_ub, A_eq=A_eq, b_eq=np.zeros(d),
                  bounds=[(0, None)] * m + [(None, None)], method="highs")
    if res.status != 0 or res.x[m] <= SQUEEZE_TOL:
        return None
    normal = np.array([float(np.sum(res.x[:m][owner == i] * share[owner == i]))
                       for i in range(k)])
    return np.asarray(grip_force * normal / normal.max(), float)


# ----------------------------------------------------------------------------- model

def _prism_inertia(tris: list[FloatArray], h: float) -> tuple[float, FloatArray, FloatArray]:
    """Mass, centre of mass and principal moments (x, y, z; about axes through the
    centre of mass, the product of inertia of the plane neglected) of the part's
    triangles extruded ``h`` thick, of uniform density and mass :data:`PART_MASS`,
    exact per triangle."""
    area = mx = my = sxx = syy = 0.0
    for t in tris:
        (ux, uy), (vx, vy) = t[1] - t[0], t[2] - t[0]
        a = 0.5 * abs(float(ux * vy - uy * vx))
        c = t.mean(axis=0)
        area += a
        mx += a * c[0]
        my += a * c[1]
        # the second moments of a triangle: a/12 (sum x_i^2 + (sum x_i)^2)
        sxx += a / 12 * (float(np.sum(t[:, 0] ** 2)) + float(np.sum(t[:, 0])) ** 2)
        syy += a / 12 * (float(np.sum(t[:, 1] ** 2)) + float(np.sum(t[:, 1])) ** 2)
    cx, cy = mx / area, my / area
    ixx_area = syy - area * cy * cy           # about the centroid's x axis: y^2
    iyy_area = sxx - area * cx * cx
    rho = PART_MASS / area
    mass = PART_MASS
    thick = mass * h * h / 12
    return mass, np.array([cx, cy]), np.array([rho * ixx_area + thick, rho * iyy_area + thick,
                                               rho * (ixx_area + iyy_area)])


#: The simulator's settings (module docstring), shared by every model.
_SETTINGS = (f'<option timestep="{TIMESTEP}" gravity="0 0 0" cone="elliptic" impratio="10" '
             f'noslip_iterations="20"/>'
             f'<default><geom solref="0.002 1" solimp="0.95 0.99 0.0001"/></default>')


def _servo_mass(kp: Any) -> Any:
    """A finger's mass: at least :data:`FINGER_MASS`, and heavy enough that its servo's
    period spans :data:`SERVO_STEPS` time steps."""
    return np.maximum(FINGER_MASS, np.asarray(kp) * (SERVO_STEPS * TIMESTEP / (2 * math.pi)) ** 2)


def _servo(i: int, kp: float, preload: float) -> str:
    """Finger ``i``'s position servo, saturating at twice its squeeze."""
    return (f'<position name="a{i}" joint="j{i}" kp="{kp:.9g}" '
            f'forcerange="{-2 * preload:.9g} {2 * preload:.9g}" forcelimited="true"/>')


def _finger_bodies(points: FloatArray, normals: FloatArray, r: float, kp: FloatArray,
                   preload: FloatArray, friction: str) -> tuple[list[str], list[str]]:
    """Spherical fingertips of radius ``r`` touching the part at ``points`` (metres,
    3-D), each on a slide along its inward normal driven by its servo."""
    masses = _servo_mass(kp)
    bodies, actuators = [], []
    for i, (c, n) in enumerate(zip(points, normals, strict=True)):
        pos = c + r * n
        mf = float(masses[i])
        tip = f"{0.4 * mf * r * r:.9g}"              # a solid sphere's moment
        bodies.append(
            f'<body name="f{i}" pos="{pos[0]:.12g} {pos[1]:.12g} {pos[2]:.12g}">'
            f'<inertial pos="0 0 0" mass="{mf:.9g}" diaginertia="{tip} {tip} {tip}"/>'
            f'<joint name="j{i}" type="slide" axis="{-n[0]:.12g} {-n[1]:.12g} '
            f'{-n[2]:.12g}" damping="{2 * math.sqrt(kp[i] * mf):.9g}"/>'
            f'<geom type="sphere" size="{r:.9g}" {friction}/></body>')
        actuators.append(_servo(i, float(kp[i]), float(preload[i])))
    return bodies, actuators


def _settle(model: Any, preload: FloatArray, kp: FloatArray) -> Any:
    """The squeeze: each servo's target set for its preload, then corrected half way
    so that each finger's squeeze is its preload once the contacts have sunk in."""
    mujoco = _mujoco()
    data = mujoco.MjData(model)
    data.ctrl[:] = preload / kp
    steps = int(SETTLE_TIME / TIMESTEP)
    for _ in range(steps // 2):
        mujoco.mj_step(model, data)
    data.ctrl[:] += (preload - data.actuator_force) / kp
    for _ in range(steps - steps // 2):
        mujoco.mj_step(model, data)
    return data


def _model(polygon: Any, points: FloatArray, normals: FloatArray, mu: float,
           preload: FloatArray, metres: float, pads: Any = None) -> tuple[Any, FloatArray]:
    """The MJCF model: the part's triangles (a constrained Delaunay triangulation)
    extruded, a finger per contact (or, with ``pads`` = ``(jaw, theta, offset, top,
    bottom, grip)``, the jaw's two flat pads); and each finger's servo stiffness
    (N/m)."""
    import shapely

    mujoco = _mujoco()
    poly = shapely.Polygon(polygon.vertices, list(polygon.holes))
    size = polygon.size * metres
    h = THICKNESS * size
    # (MuJoCo's torsional and rolling friction: small, for the planar contacts' sake)
    friction = (f'friction="{max(mu, TOL):.9g} {SPIN_FRICTION} {ROLL_FRICTION}" '
                f'condim="{3 if mu > 0 else 1}"')
    assets, geoms = [], []
    # the part as triangles that follow its edges and holes (MuJoCo collides convex
    # pieces); a sliver of no volume is left out, its edges shared by its neighbours
    pieces = shapely.get_parts(shapely.constrained_delaunay_triangles(poly))
    floor = TOL * polygon.size ** 2
    tris = [np.asarray(t.exterior.coords)[:3] * metres for t in pieces if t.area > floor]
    for k, xy in enumerate(tris):
        v = np.vstack([np.c_[xy, np.full(3, -h / 2)], np.c_[xy, np.full(3, h / 2)]])
        coords = " ".join(f"{x:.12g}" for x in v.ravel())
        # (its inertia is the part's, given whole: a sliver's volume is not needed)
        assets.append(f'<mesh name="p{k}" inertia="shell" vertex="{coords}"/>')
        geoms.append(f'<geom type="mesh" mesh="p{k}" mass="0" {friction}/>')
    mass, com, inertia = _prism_inertia(tris, h)
    r = TIP_RADIUS * size
    kp = preload / (SERVO_COMPLIANCE * size)
    unit = normals / np.maximum(np.linalg.norm(normals, axis=1), TINY)[:, None]
    fingers, actuators = _finger_bodies(np.c_[points * metres, np.zeros(len(points))],
                                        np.c_[unit, np.zeros(len(unit))], r, kp, preload,
                                        friction)
    if pads is not None:
        fingers, actuators = _pad_bodies(polygon, pads, metres, h, friction)
    xml = (f'<mujoco><compiler inertiafromgeom="false"/>{_SETTINGS}'
           f'<asset>{"".join(assets)}</asset><worldbody><body name="part">'
           f'<inertial pos="{com[0]:.12g} {com[1]:.12g} 0" mass="{mass:.12g}" '
           f'diaginertia="{inertia[0]:.12g} {inertia[1]:.12g} {inertia[2]:.12g}"/>'
           f'<joint name="px" type="slide" axis="1 0 0"/>'
           f'<joint name="py" type="slide" axis="0 1 0"/>'
           f'<joint name="pz" type="hinge" axis="0 0 1"/>{"".join(geoms)}</body>'
           f'{"".join(fingers)}</worldbody><actuator>{"".join(actuators)}</actuator>'
           f'</mujoco>')
    return mujoco.MjModel.from_xml_string(xml), kp


def _pad_bodies(polygon: Any, pads: Any, metres: float, h: float, friction: str
                ) -> tuple[list[str], list[str]]:
    """The jaw's pads as MJCF bodies: boxes :data:`PAD_DEPTH` of the part's size deep,
    the pad's width wide, their faces at the pads' stops, each on a slide along the
    closing direction driven by a servo that squeezes with ``grip`` and saturates at
    twice it."""
    jaw, theta, offset, top, bottom, grip = pads
    size = polygon.size * metres
    u = np.array([math.cos(theta), math.sin(theta)])
    n = np.array([-u[1], u[0]])
    c0 = np.asarray(polygon.centroid, float) * metres
    depth = PAD_DEPTH * size
    kp = grip / (SERVO_COMPLIANCE * size)
    mass = float(_servo_mass(kp))
    quat = f"{math.cos(theta / 2):.12g} 0 0 {math.sin(theta / 2):.12g}"
    box = f"{depth / 2:.9g} {jaw.pad_width * metres / 2:.9g} {0.6 * h:.9g}"
    moment = f"{mass * (depth ** 2 + (jaw.pad_width * metres) ** 2) / 12:.9g}"
    bodies, actuators = [], []
    for i, (stop, side) in enumerate(((top, 1.0), (bottom, -1.0))):
        pos = c0 + offset * metres * n + (stop * metres + side * depth / 2) * u
        bodies.append(
            f'<body name="f{i}" pos="{pos[0]:.12g} {pos[1]:.12g} 0" quat="{quat}">'
            f'<inertial pos="0 0 0" mass="{mass:.9g}" diaginertia="{moment} {moment} '
            f'{moment}"/>'
            f'<joint name="j{i}" type="slide" axis="{-side:.0f} 0 0" '
            f'damping="{2 * math.sqrt(kp * mass):.9g}"/>'
            f'<geom type="box" size="{box}" {friction}/></body>')
        actuators.append(_servo(i, kp, grip))
    return bodies, actuators


def stress_test(polygon: Any, points: Any, normals: Any, mu: float, direction: Any,
                grip_force: float = 10.0, ramp: float = 3.0, units: str = "mm",
                certified: float | None = None, record: bool = False) -> StressResult:
    """One grasp (points and outward normals, part units) under a disturbance of
    ``direction`` (force and torque per newton, torque in N x part unit) ramped to
    ``ramp`` times the certified payload (or to ``grip_force`` where that is 0): the
    load at which the part slipped, or None where it held (module docstring).
    ``record``: keep the part's pose and the load every 5 ms (``history``: time, load,
    displacement, rotation in degrees, and the displacement's x and y)."""
    from .model.loads import Load, grasp_payload

    p, n = np.asarray(points, float), np.asarray(normals, float)
    n = n / np.linalg.norm(n, axis=1)[:, None]
    u = np.asarray(direction, float)
    metres = _METRES.get(units, _METRES["mm"])
    preload = squeeze_forces(p, n, mu, grip_force)
    if preload is None:                       # not squeezable: every finger alike
        preload = np.full(len(p), float(grip_force))
        cert = 0.0
    elif certified is not None:
        cert = float(certified)
    else:
        cx, cy = (float(v) for v in polygon.centroid)
        load = Load(1.0, com=(cx, cy), gravity=(float(u[0]), float(u[1])),
                    torque=(float(u[2]), float(u[2])))
        cert = float(grasp_payload(p, -n, mu, load, force_limit=list(preload)).scale)
    model, kp = _model(polygon, p, n, mu, preload, metres)
    return _run(model, polygon, preload, kp, metres, u, cert, ramp, grip_force, record, p,
                n, preload)


def _run(model: Any, polygon: Any, preload: FloatArray, kp: FloatArray, metres: float,
         u: FloatArray, cert: float, ramp: float, grip_force: float, record: bool,
         p: FloatArray, n: FloatArray, grips: FloatArray) -> StressResult:
    """The squeeze, then the ramp of the disturbance ``u`` until the part slips."""
    mujoco = _mujoco()
    data = _settle(model, preload, kp)
    q0 = data.qpos[:3].copy()
    settle = float(math.hypot(q0[0], q0[1])) / metres
    body = model.body("part").id
    size = polygon.size * metres
    top = ramp * cert if cert > 0 else float(grip_force)
    n_ramp = int(RAMP_TIME / TIMESTEP)
    slip, hist = None, []
    if math.hypot(q0[0], q0[1]) > SLIP_DISPLACEMENT * size or \
            abs(q0[2]) > math.radians(SLIP_ROTATION_DEG):
        # the squeeze alone moved the part (a grasp that is not in equilibrium): it
        # slipped at no load, whatever pose the servos then hold it in
        slip, n_ramp = 0.0, 0
    for k in range(1, n_ramp + 1):
        load_now = top * k / n_ramp
        data.xfrc_applied[body, :] = 0.0
        data.xfrc_applied[body, 0:2] = load_now * u[:2]
        data.xfrc_applied[body, 5] = load_now * u[2] * metres
        mujoco.mj_step(model, data)
        dq = data.qpos[:3] - q0
        moved, turned = math.hypot(dq[0], dq[1]), abs(dq[2])
        if record and k % 10 == 0:
            hist.append((k * TIMESTEP, load_now, moved / metres, math.degrees(dq[2]),
                         dq[0] / metres, dq[1] / metres))
        if moved > SLIP_DISPLACEMENT * size or turned > math.radians(SLIP_ROTATION_DEG):
            slip = load_now
            break
    dq = data.qpos[:3] - q0
    return StressResult(p, n, grips, cert, slip, float(math.hypot(dq[0], dq[1])) / metres,
                        float(math.degrees(abs(dq[2]))), settle, u,
                        np.array(hist).reshape(-1, 6))


# ----------------------------------------------------------------------------- the jaw

def jaw_contacts(polygon: Any, jaw: Any, theta: float, offset: float
                 ) -> tuple[FloatArray, FloatArray, FloatArray, float, float] | None:
    """What the jaw's pads touch at the pose ``(theta, offset)``
    (:func:`fcgrasp.grippers.jaw.jaw_poses`): the contact points, the part's outward
    normals there (a pad pushes along the pad's normal, or a pad's corner along the
    edge's), which pad each is on (0: pad A, 1: pad B), and the pads' stops along
    ``u``; None where the pose does not hold."""
    from .grippers.jaw import jaw_poses

    pc = jaw_poses(polygon, jaw, [theta], [offset])
    if not bool(pc.holds[0]):
        return None
    u = np.array([math.cos(theta), math.sin(theta)])
    n = np.array([-u[1], u[0]])
    c0 = np.asarray(polygon.centroid, float)
    pts, nrm, pad = [], [], []
    for k, (stop, lat, psi, push) in enumerate(((pc.top[0], pc.lat_a[0], pc.psi_a[0], -u),
                                                (pc.bottom[0], pc.lat_b[0], pc.psi_b[0], u))):
        for (lo, hi), a in zip(lat, psi, strict=True):
            if not np.isfinite(lo):
                continue
            f = math.cos(a) * push + math.sin(a) * n       # the contact force's line
            for x in np.unique([lo, hi]):
                pts.append(c0 + stop * u + x * n)
                nrm.append(-f)
                pad.append(k)
    return (np.array(pts), np.array(nrm), np.array(pad), float(pc.top[0]),
            float(pc.bottom[0]))


def _jaw_model(polygon: Any, jaw: Any, theta: float, offset: float, top: float,
               bottom: float, mu: float, grip: float, metres: float) -> tuple[Any, float]:
    """The part and the jaw's two flat pads (boxes on slides along the closing
    direction, each a stiff servo), as :func:`_model` builds fingers."""
    model, _ = _model(polygon, np.zeros((0, 2)), np.zeros((0, 2)), mu, np.zeros(0),
                      metres, pads=(jaw, theta, offset, top, bottom, grip))
    size = polygon.size * metres
    return model, grip / (SERVO_COMPLIANCE * size)


def jaw_stress_test(polygon: Any, jaw: Any, theta: float, offset: float, direction: Any,
                    grip_force: float = 10.0, ramp: float = 3.0, units: str = "mm",
                    mu: float | None = None, record: bool = False) -> StressResult | None:
    """One pose of a parallel jaw (flat pads of ``jaw.pad_width``, friction ``jaw.mu``
    or ``mu``) under a disturbance, as :func:`stress_test` runs fingers: each pad
    squeezes with ``grip_force``; the certified payload is that of the pose's contacts
    (:func:`fcgrasp.grasp_payload`, each pad's force shared by its contact points).
    None where the pose does not hold by the jaw's own model."""
    from .model.loads import Load, grasp_payload

    got = jaw_contacts(polygon, jaw, theta, offset)
    if got is None:
        return None
    pts, nrm, pad, top, bottom = got
    mu_v = float(jaw.mu if mu is None else mu)
    u = np.asarray(direction, float)
    per = [grip_force / int(np.sum(pad == k)) for k in pad]
    cx, cy = (float(v) for v in polygon.centroid)
    load = Load(1.0, com=(cx, cy), gravity=(float(u[0]), float(u[1])),
                torque=(float(u[2]), float(u[2])))
    cert = float(grasp_payload(pts, -nrm, mu_v, load, force_limit=per).scale) \
        if mu_v > 0 else 0.0
    metres = _METRES.get(units, _METRES["mm"])
    model, kp = _jaw_model(polygon, jaw, theta, offset, top, bottom, mu_v, grip_force,
                           metres)
    preload = np.full(2, float(grip_force))
    return _run(model, polygon, preload, np.full(2, kp), metres, u, cert, ramp,
                grip_force, record, pts, nrm, np.asarray(per, float))


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
    from .spatial.contacts import contact_wrench_generators

    gens = contact_wrench_generators(points, inward, mu, torsion, center=center,
                                     radius=radius)                  # (k, g, 6)
    k, g = gens.shape[:2]
    # the generators' normal components are 1
    return _internal(gens.reshape(k * g, 6), np.ones(k * g), np.repeat(np.arange(k), g), k,
                     grip_force)


def solid_stress_test(solid: Any, points: Any, normals: Any, mu: float, direction: Any,
                      soft: bool = False, grip_force: float = 10.0, ramp: float = 3.0,
                      record: bool = False) -> StressResult:
    """One grasp of a convex solid (points and outward normals in the solid's units;
    ``soft``: soft fingers with :data:`TORSION`) under a disturbance ``direction`` (a
    force and a torque per newton, ``(fx, fy, fz, tx, ty, tz)``, the torque in N x the
    solid's unit), as :func:`stress_test` runs a planar part: the part free in space
    (no gravity), each finger a sphere on a servoed slide along its inward normal.  The
    certified payload is the grasp's Ferrari-Canny L1 measure
    (:func:`fcgrasp.spatial.spatial_quality`, pyramids inscribed in the cones; torques
    over the part's size) times the smallest squeeze: the normal forces of a wrench
    within the measure's ball sum to at most that, so no finger exceeds its own."""
    from .spatial.quality import spatial_quality

    mujoco = _mujoco()
    mesh = solid.mesh
    if not bool(mesh.is_convex):
        raise ArgumentError("the stress test of a solid needs a convex mesh so far (MuJoCo "
                            "collides a mesh's convex hull)", "solid")
    p, n = np.asarray(points, float), np.asarray(normals, float)
    n = n / np.linalg.norm(n, axis=1)[:, None]
    u = np.asarray(direction, float)
    metres = _METRES.get(str(solid.units), _METRES["mm"])
    size_u = float(np.linalg.norm(mesh.extents))
    size = size_u * metres
    centre = np.asarray(solid.center, float)
    gamma = TORSION * size_u if soft else 0.0
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
    v = np.asarray(mesh.vertices, float) * metres
    verts = " ".join(f"{x:.12g}" for x in v.ravel())
    faces = " ".join(str(int(i)) for i in np.asarray(mesh.faces).ravel())
    fingers, actuators = _finger_bodies(p * metres, n, TIP_RADIUS * size, kp, preload,
                                        friction)
    xml = (f'<mujoco>{_SETTINGS}'
           f'<asset><mesh name="part" vertex="{verts}" face="{faces}"/></asset>'
           f'<worldbody><body name="part"><freejoint/>'
           f'<geom type="mesh" mesh="part" mass="{PART_MASS}" {friction}/></body>'
           f'{"".join(fingers)}</worldbody><actuator>{"".join(actuators)}</actuator>'
           f'</mujoco>')
    model = mujoco.MjModel.from_xml_string(xml)
    data = _settle(model, preload, kp)
    body = model.body("part").id
    x0, q0 = data.xpos[body].copy(), data.xquat[body].copy()

    def motion() -> tuple[float, float]:
        dq = float(abs(np.dot(data.xquat[body], q0)))
        return float(np.linalg.norm(data.xpos[body] - x0)), 2 * math.acos(min(dq, 1.0))

    settle = float(np.linalg.norm(x0 - model.qpos0[:3]))
    top = ramp * cert if cert > 0 else float(grip_force)
    n_ramp = int(RAMP_TIME / TIMESTEP)
    slip = None
    if settle > SLIP_DISPLACEMENT * size:
        slip, n_ramp = 0.0, 0
    for k in range(1, n_ramp + 1):
        load_now = top * k / n_ramp
        data.xfrc_applied[body, :3] = load_now * u[:3]
        data.xfrc_applied[body, 3:] = load_now * u[3:] * metres
        mujoco.mj_step(model, data)
        moved, turned = motion()
        if moved > SLIP_DISPLACEMENT * size or turned > math.radians(SLIP_ROTATION_DEG):
            slip = load_now
            break
    moved, turned = motion()
    return StressResult(p, n, preload, cert, slip, moved / metres, math.degrees(turned),
                        settle / metres, u)


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
    if kind == "jaw":
        raise ArgumentError("the stress test of a solid runs fingers so far, not the jaw",
                            "plans")
    regions = [np.asarray(r, float) for r in get("regions")]
    return regions, outward, float(get("mu")), kind == "soft"


def sample_solid_grasps(plan: Any, count: int, rng: np.random.Generator
                        ) -> list[tuple[FloatArray, FloatArray]]:
    """``count`` grasps of a solid's finger plan: the regions' centres, then each
    region's corners pulled a tenth of the way to its centre, then seeded points (convex
    combinations of the corners); each with its region's outward normal."""
    regions, outward, _, _ = solid_plan_of(plan)
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


def solid_escape(solid: Any, points: Any, normals: Any, mu: float, soft: bool) -> FloatArray:
    """A disturbance (force and torque per newton, as :func:`solid_stress_test` takes
    it) that the grasp does not resist (:func:`fcgrasp.spatial.closure_margin`'s
    ``unresisted`` wrench); an ``ArgumentError`` for a grasp in force closure."""
    from .spatial.closure import closure_margin

    size_u = float(np.linalg.norm(solid.mesh.extents))
    gamma = TORSION * size_u if soft else 0.0
    verdict = closure_margin(points, -np.asarray(normals, float), mu, gamma,
                             center=np.asarray(solid.center, float), radius=size_u)
    if verdict.closure or verdict.unresisted is None:
        raise ArgumentError("the grasp is force closure: it has no escape", "points")
    w = np.asarray(verdict.unresisted, float)
    return np.r_[w[:3], w[3:] * size_u]


def _is_solid(part: Any) -> bool:
    return type(part).__module__.startswith("fcgrasp.spatial")


def _directions6(rng: np.random.Generator, count: int, size: float) -> FloatArray:
    """``count`` seeded unit disturbances on a solid: a force and a torque whose arm is
    the part's size (``|(f, tau / size)| = 1``)."""
    u = rng.normal(size=(count, 6))
    u /= np.linalg.norm(u, axis=1)[:, None]
    u[:, 3:] *= size
    return u


def _directions(rng: np.random.Generator, count: int, size: float) -> FloatArray:
    """``count`` seeded unit disturbance directions: a force and a torque whose arm is
    the part's size (``|(fx, fy, tau / size)| = 1``)."""
    u = rng.normal(size=(count, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    u[:, 2] *= size
    return u


def control(points: Any, normals: Any, mu: float) -> tuple[FloatArray, FloatArray, float]:
    """A grasp that is not force closure made from one that is: the same contacts
    without friction (two or three fingers: never force closure in the plane), or,
    without friction already, the first finger taken away (three frictionless fingers
    never are either)."""
    p, n = np.asarray(points, float), np.asarray(normals, float)
    if mu > 0:
        return p, n, 0.0
    return p[1:], n[1:], 0.0


def escape_direction(polygon: Any, points: Any, normals: Any, mu: float) -> FloatArray:
    """A disturbance (force and torque per newton, as :func:`stress_test` takes it) that
    pushes the part along a motion the grasp does not resist (the escape twist of
    :func:`fcgrasp.closure_escape`, theorem 6.1); an ``ArgumentError`` for a grasp in
    force closure."""
    from .core.closure import closure_escape

    p, n = np.asarray(points, float), np.asarray(normals, float)
    _, _, W = _edges(p, n / np.linalg.norm(n, axis=1)[:, None], mu)
    closed, escape = closure_escape(W)
    if bool(closed):
        raise ArgumentError("the grasp is force closure: it has no escape", "points")
    omega, vx, vy = (float(v) for v in escape)
    size = polygon.size
    f = np.array([vx, vy])                      # work f . v + tau omega > 0
    tau_origin = omega * size * size
    cx, cy = (float(v) for v in polygon.centroid)
    u = np.array([f[0], f[1], tau_origin - (cx * f[1] - cy * f[0])])
    return u / math.sqrt(u[0] ** 2 + u[1] ** 2 + (u[2] / size) ** 2)


def control_runs(part: Any, plans: Any, *, grip_force: float = 10.0, seed: int = 0,
                 units: str = "mm", count: int = 3) -> list[dict[str, Any]]:
    """The controls of each plan (a plan object or a report's grasp): ``count`` of its
    grasps made not force closure (:func:`control`; a jaw's poses and a solid's grasps
    without friction), each pushed along a wrench it does not resist; per control its
    plan's ``rank``, its ``mu``, :meth:`StressResult.to_dict` and whether it
    ``slipped``."""
    rng = np.random.default_rng(seed)
    out = []

    def add(r: int, mu: float, res: StressResult | None) -> None:
        if res is not None:
            out.append({"rank": r + 1, "mu": mu, **res.to_dict(),
                        "slipped": res.slip_load is not None})

    for r, plan in enumerate(plans):
        if _is_solid(part):             # the same contacts without friction
            for pts, nrm in sample_solid_grasps(plan, count, rng):
                add(r, 0.0, solid_stress_test(part, pts, nrm, 0.0,
                                              solid_escape(part, pts, nrm, 0.0, False),
                                              grip_force=grip_force))
            continue
        jaw = jaw_of(plan)
        if jaw is not None:             # the same poses without friction
            for theta, offset in sample_poses((jaw[1], jaw[2]), count, rng):
                got = jaw_contacts(part, jaw[0], theta, offset)
                if got is not None:
                    add(r, 0.0, jaw_stress_test(part, jaw[0], theta, offset,
                                                escape_direction(part, got[0], got[1], 0.0),
                                                grip_force=grip_force, units=units, mu=0.0))
            continue
        get: Callable[[str], Any] = plan.__getitem__ if isinstance(plan, dict) else \
            partial(getattr, plan)
        for pts, nrm in sample_grasps(part, get("regions"), count, rng, get("normals")):
            cp, cn, cmu = control(pts, nrm, float(get("mu")))
            add(r, cmu, stress_test(part, cp, cn, cmu, escape_direction(part, cp, cn, cmu),
                                    grip_force=grip_force, units=units))
    return out


def _one(args: tuple[Any, ...]) -> StressResult | None:
    if args[0] == "jaw":
        return jaw_stress_test(*args[1:])
    if args[0] == "solid":
        return solid_stress_test(*args[1:])
    return stress_test(*args[1:])


def jaw_of(plan: Any) -> tuple[Any, tuple[float, float], tuple[float, float]] | None:
    """A jaw plan's jaw and its box of poses (``theta``, ``offset``), from a
    :class:`~fcgrasp.grippers.jaw.JawPlan` or a report's grasp; None for fingers.  An
    internal grip (opening in a hole) is refused."""
    if isinstance(plan, dict):
        if plan.get("gripper") != "parallel_jaw":
            return None
        if plan.get("mode", "external") != "external":
            raise ArgumentError("the stress test runs the jaw's external grips so far, not "
                                "one opening in a hole", "plans")
        from .grippers.jaw import ParallelJaw

        jaw = ParallelJaw(stroke=tuple(plan["stroke"]), pad_width=plan["pad_width"],
                          mu=plan["mu"])
        return jaw, tuple(plan["theta_rad"]), tuple(plan["offset"])
    if not hasattr(plan, "jaw"):
        return None
    if plan.mode != "external":
        raise ArgumentError("the stress test runs the jaw's external grips so far, not one "
                            "opening in a hole", "plans")
    return plan.jaw, tuple(plan.theta), tuple(plan.offset)


def sample_poses(box: tuple[tuple[float, float], tuple[float, float]], count: int,
                 rng: np.random.Generator) -> list[tuple[float, float]]:
    """``count`` poses of a jaw's box: its centre, its corners pulled in by 2 % of each
    side, then seeded poses inside."""
    (t0, t1), (c0, c1) = box
    dt, dc = 0.02 * (t1 - t0), 0.02 * (c1 - c0)
    fixed = [((t0 + t1) / 2, (c0 + c1) / 2), (t0 + dt, c0 + dc), (t1 - dt, c1 - dc),
             (t0 + dt, c1 - dc), (t1 - dt, c0 + dc)]
    out = fixed[:count]
    while len(out) < count:
        out.append((float(rng.uniform(t0, t1)), float(rng.uniform(c0, c1))))
    return out


def simulate(polygon: Any, plans: Any, *, grip_force: float = 10.0, samples: int = 20,
             directions: int = 2, seed: int = 0, units: str = "mm",
             workers: int | None = None,
             progress: Callable[[int, int], None] | None = None) -> list[dict[str, Any]]:
    """The stress test of each plan (a :class:`~fcgrasp.GraspPlan` of point fingers, a
    :class:`~fcgrasp.JawPlan`, or a report's grasp of either): ``samples`` grasps in
    its regions (:func:`sample_grasps`: ends and middle first) or poses of its box
    (:func:`sample_poses`), each under ``directions`` seeded disturbances, run on
    ``workers`` processes (default: every core).  One summary per plan: its rank, the
    grasps (:meth:`StressResult.to_dict`), how many held up to their certified payload
    and the smallest ratio of slip load to certified payload."""
    check_int(samples, "samples", minimum=1)
    check_int(directions, "directions", minimum=1)
    check_scalar(grip_force, "grip_force", positive=True)
    rng = np.random.default_rng(check_int(seed, "seed", minimum=0))
    jobs: list[tuple[Any, ...]] = []
    owners: list[int] = []
    solid = _is_solid(polygon)
    for r, plan in enumerate(plans):
        if solid:
            _, _, mu_s, soft = solid_plan_of(plan)
            size_u = float(np.linalg.norm(polygon.mesh.extents))
            for pts, nrm in sample_solid_grasps(plan, samples, rng):
                for u in _directions6(rng, directions, size_u):
                    jobs.append(("solid", polygon, pts, nrm, mu_s, u, soft, grip_force, 3.0))
                    owners.append(r)
            continue
        jaw = jaw_of(plan)
        if jaw is not None:
            for theta, offset in sample_poses((jaw[1], jaw[2]), samples, rng):
                for u in _directions(rng, directions, polygon.size):
                    jobs.append(("jaw", polygon, jaw[0], theta, offset, u, grip_force, 3.0,
                                 units))
                    owners.append(r)
            continue
        regions = plan["regions"] if isinstance(plan, dict) else plan.regions
        mu = float(plan["mu"] if isinstance(plan, dict) else plan.mu)
        if isinstance(plan, dict) and "facets" in plan or not len(regions) or \
                np.asarray(regions[0]).shape[-1] != 2:
            raise ArgumentError("the stress test runs point fingers on planar parts: "
                                f"plan {r + 1} is not one", "plans")
        given = plan["normals"] if isinstance(plan, dict) else plan.normals
        for pts, nrm in sample_grasps(polygon, regions, samples, rng, given):
            for u in _directions(rng, directions, polygon.size):
                jobs.append(("fingers", polygon, pts, nrm, mu, u, grip_force, 3.0, units))
                owners.append(r)
    results: list[StressResult | None] = []
    if workers == 1 or len(jobs) < 4:
        for k, job in enumerate(jobs):
            results.append(_one(job))
            if progress is not None:
                progress(k + 1, len(jobs))
    else:
        with ProcessPoolExecutor(max_workers=workers) as pool:
            for k, res in enumerate(pool.map(_one, jobs, chunksize=4)):
                results.append(res)
                if progress is not None:
                    progress(k + 1, len(jobs))
    out = []
    for r in range(len(plans)):
        # (a jaw's pose that does not hold by its own model is left out)
        mine = [res for res, o in zip(results, owners, strict=True)
                if o == r and res is not None]
        ratios = [res.slip_load / res.certified_payload for res in mine
                  if res.slip_load is not None and res.certified_payload > 0]
        dirs = np.unique(np.array([m.direction for m in mine]).round(12), axis=0)
        out.append({"rank": r + 1, "grasps": [{"rank": r + 1, **m.to_dict()} for m in mine],
                    "held": sum(m.held for m in mine), "runs": len(mine),
                    "worst_ratio": min(ratios) if ratios else None,
                    "wrench_directions": [_wrench_dict(d) for d in dirs]})
    return out


# ----------------------------------------------------------------------------- pictures

def animate(polygon: Any, result: StressResult, path: str, units: str = "mm",
            frames: int = 24) -> None:
    """An animated GIF of one stress test recorded with ``record=True``, in ``frames``
    frames: the part displaced (magnified so a slip shows) under the rising load, the
    fingers, and the load against the part's displacement beside it."""
    import imageio.v3 as iio
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    h = result.history
    if not len(h):
        raise ArgumentError("result has no history: run stress_test(..., record=True)",
                            "result")
    check_int(frames, "frames", minimum=1)
    images = []
    v = np.vstack([polygon.vertices, polygon.vertices[:1]])
    for k in np.unique(np.linspace(0, len(h) - 1, frames).round().astype(int)):
        t, load, moved, turned, dx, dy = h[k]
        fig, (ax, bx) = plt.subplots(1, 2, figsize=(8, 3.6), dpi=80)
        ax.plot(v[:, 0], v[:, 1], color="0.6", lw=1)
        a = math.radians(turned) * 10
        c = np.asarray(polygon.centroid)
        rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        shift = np.array([dx, dy]) * 10
        w = (v - c) @ rot.T + c + shift
        ax.fill(w[:, 0], w[:, 1], color="0.8")
        for p, n in zip(result.contacts, result.normals, strict=True):
            ax.plot(*p, "o", color="tab:red")
            ax.arrow(*(p + 0.15 * polygon.size * n), *(-0.1 * polygon.size * n),
                     head_width=0.02 * polygon.size, color="tab:red")
        ax.set_aspect("equal")
        ax.set_title(f"load {load:.2f} N (motion x10)")
        bx.plot(h[:k + 1, 1], h[:k + 1, 2], color="tab:blue")
        bx.axvline(result.certified_payload, color="tab:green", ls="--",
                   label="certified payload")
        bx.set_xlabel("load (N)")
        bx.set_ylabel(f"displacement ({units})")
        bx.legend(loc="upper left")
        fig.tight_layout()
        fig.canvas.draw()
        images.append(np.asarray(fig.canvas.buffer_rgba())[..., :3].copy())  # type: ignore[attr-defined]
        plt.close(fig)
    iio.imwrite(path, np.stack(images), extension=".gif", duration=120, loop=0)
