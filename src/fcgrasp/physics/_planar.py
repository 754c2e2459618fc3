"""The stress test's MuJoCo models of a planar part: the prism, the fingertips or the jaw's
pads on servos, the squeeze and the ramped disturbance (part of :mod:`fcgrasp.physics`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core._checks import FloatArray
from ..core.tolerances import TINY, TOL
from ..errors import ArgumentError
from ._forces import TIP_RADIUS, balance_forces, cone_margin, planar_closed, squeeze_forces

#: The part slipped when its centre moved more than this share of its size ...
SLIP_DISPLACEMENT = 0.01


#: ... or it turned more than this many degrees.
SLIP_ROTATION_DEG = 1.0


#: Simulation settings (see the module docstring for why each).
TIMESTEP = 2.5e-4


#: The contacts' time constant (s; MuJoCo's ``solref``): four time steps.
CONTACT_TIME = 1e-3


#: A recorded run keeps the part's pose every this long (s).
RECORD_TIME = 5e-3


#: The settings a sensitivity study varies (:func:`vary`), each with what it changes:
#: the answer is physics where it does not hinge on one of them.
VARIANTS = {
    "default": "the settings of the module docstring",
    "soft contacts": "contacts four times softer (solref 4 ms)",
    "fine steps": "the time step halved (0.125 ms)",
    "pyramidal cones": "MuJoCo's pyramidal friction cones for the elliptic ones",
    "no noslip": "the noslip solver off (MuJoCo's regularised friction alone)",
}


SETTLE_TIME = 0.2


RAMP_TIME = 1.0


#: The finger servo's full preload at this share of the part's size.
SERVO_COMPLIANCE = 2e-3


#: The part's mass (kg, whatever its size: the test is quasi-static, and a part of a
#: few milligrams between fingers of a tenth of a kilogram makes the dynamics stiff),
#: and its prism's thickness (share of its size).
PART_MASS = 0.2


THICKNESS = 0.2


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
    (force and torque per newton, torque in N x part unit); and the grasp's margin to
    its friction cones (:func:`cone_margin`; None without friction)."""

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
    cone_margin_deg: float | None = None

    @property
    def held(self) -> bool:
        """Whether the part held up to its certified payload (no slip at or below it)."""
        return self.slip_load is None or self.slip_load >= self.certified_payload

    def to_dict(self) -> dict[str, Any]:
        return {"contacts": self.contacts.tolist(), "normals": self.normals.tolist(),
                "grip_force": self.grip_force.tolist(),
                "certified_payload": self.certified_payload, "slip_load": self.slip_load,
                "displacement": self.displacement, "rotation_deg": self.rotation_deg,
                "settle_motion": self.settle_motion, "cone_margin_deg": self.cone_margin_deg,
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
             f'<default><geom solref="{CONTACT_TIME} 1" solimp="0.95 0.99 0.0001"/></default>')


def _servo_mass(kp: Any) -> Any:
    """A finger's mass: at least :data:`FINGER_MASS`, and heavy enough that its servo's
    period spans :data:`SERVO_STEPS` time steps."""
    return np.maximum(FINGER_MASS, np.asarray(kp) * (SERVO_STEPS * TIMESTEP / (2 * math.pi)) ** 2)


def _servo(i: int, kp: float, preload: float) -> str:
    """Finger ``i``'s position servo, saturating at twice its squeeze."""
    return (f'<position name="a{i}" joint="j{i}" kp="{kp:.9g}" '
            f'forcerange="{-2 * preload:.9g} {2 * preload:.9g}" forcelimited="true"/>')


def _motor(i: int, preload: float) -> str:
    """Finger ``i``'s force actuator (a balancing finger), pushing up to twice its
    squeeze."""
    return (f'<motor name="a{i}" joint="j{i}" gear="1" ctrllimited="true" '
            f'ctrlrange="0 {2 * preload:.9g}"/>')


def _finger_bodies(points: FloatArray, normals: FloatArray, r: float, kp: FloatArray,
                   preload: FloatArray, friction: str, balance: bool = False
                   ) -> tuple[list[str], list[str]]:
    """Spherical fingertips of radius ``r`` touching the part at ``points`` (metres,
    3-D), each on a slide along its inward normal driven by its servo (or, ``balance``,
    by a force actuator, the servo's damping kept)."""
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
        actuators.append(_motor(i, float(preload[i])) if balance else
                         _servo(i, float(kp[i]), float(preload[i])))
    return bodies, actuators


def check_variant(variant: str) -> str:
    """``variant`` where it is a key of :data:`VARIANTS`, else an ``ArgumentError``."""
    if variant not in VARIANTS:
        raise ArgumentError(f"variant must be one of {', '.join(VARIANTS)}, not "
                            f"{variant!r}", "variant")
    return variant


def check_control(control: str) -> str:
    """``control`` where it is ``"balance"`` or ``"servo"`` (:func:`stress_test`), else
    an ``ArgumentError``."""
    if control not in ("balance", "servo"):
        raise ArgumentError(f"control must be 'balance' or 'servo', not {control!r}",
                            "control")
    return control


def vary(model: Any, variant: str) -> Any:
    """``model`` with the setting of ``variant`` (a key of :data:`VARIANTS`) changed."""
    mujoco = _mujoco()
    check_variant(variant)
    if variant == "soft contacts":
        model.geom_solref[:, 0] *= 4
    elif variant == "fine steps":
        model.opt.timestep /= 2
    elif variant == "pyramidal cones":
        model.opt.cone = mujoco.mjtCone.mjCONE_PYRAMIDAL
    elif variant == "no noslip":
        model.opt.noslip_iterations = 0
    return model


def _steps(model: Any, seconds: float) -> int:
    """The model's time steps in ``seconds``."""
    return int(round(seconds / float(model.opt.timestep)))


def _settle(model: Any, preload: FloatArray, kp: FloatArray) -> Any:
    """The squeeze: each servo's target set for its preload, then corrected half way
    so that each finger's squeeze is its preload once the contacts have sunk in."""
    mujoco = _mujoco()
    data = mujoco.MjData(model)
    data.ctrl[:] = preload / kp
    steps = _steps(model, SETTLE_TIME)
    for _ in range(steps // 2):
        mujoco.mj_step(model, data)
    data.ctrl[:] += (preload - data.actuator_force) / kp
    for _ in range(steps - steps // 2):
        mujoco.mj_step(model, data)
    return data


def _model(polygon: Any, points: FloatArray, normals: FloatArray, mu: float,
           preload: FloatArray, metres: float, pads: Any = None, balance: bool = False,
           tip: float | None = None) -> tuple[Any, FloatArray]:
    """The MJCF model: the part's triangles (a constrained Delaunay triangulation)
    extruded, a finger per contact (force controlled where ``balance``; or, with
    ``pads`` = ``(jaw, theta, offset, top, bottom, grip)``, the jaw's two flat pads); and
    each finger's servo stiffness (N/m)."""
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
    r = TIP_RADIUS * size if tip is None else float(tip) * metres
    kp = preload / (SERVO_COMPLIANCE * size)
    unit = normals / np.maximum(np.linalg.norm(normals, axis=1), TINY)[:, None]
    fingers, actuators = _finger_bodies(np.c_[points * metres, np.zeros(len(points))],
                                        np.c_[unit, np.zeros(len(unit))], r, kp, preload,
                                        friction, balance)
    if pads is not None:
        fingers, actuators = _pad_bodies(polygon, pads, metres, h, friction, balance)
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


def _pad_bodies(polygon: Any, pads: Any, metres: float, h: float, friction: str,
                balance: bool = False) -> tuple[list[str], list[str]]:
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
        actuators.append(_motor(i, grip) if balance else _servo(i, kp, grip))
    return bodies, actuators


def _schedule(control: str, mu: float, cert: float, polygon: Any, points: FloatArray,
              normals: FloatArray, limits: FloatArray, u: FloatArray, top: float,
              **fingers: Any) -> tuple[FloatArray, FloatArray] | None:
    """The balancing fingers' forces along the ramp to ``top`` (:func:`balance_forces`,
    ``fingers`` its ``fingers`` and ``axes``) where ``control`` is ``"balance"``, there
    is friction and a positive certificate, and some level balances; else None (the
    fingers on servos)."""
    if check_control(control) == "servo" or not (cert > 0 and mu > 0):
        return None
    cx, cy = (float(v) for v in polygon.centroid)
    wrench = np.array([u[0], u[1], u[2] + cx * u[1] - cy * u[0]])   # about the origin
    reached, forces = balance_forces(points, normals, mu, limits, wrench, top, **fingers)
    return (reached, forces) if len(reached) else None


def _unit_load(polygon: Any, u: FloatArray) -> Any:
    """A disturbance of one newton along ``u`` (a force at the part's centroid and a
    torque) as the certificate takes it (:class:`fcgrasp.Load`)."""
    from ..model.loads import Load

    cx, cy = (float(v) for v in polygon.centroid)
    return Load(1.0, com=(cx, cy), gravity=(float(u[0]), float(u[1])),
                torque=(float(u[2]), float(u[2])))


def stress_test(polygon: Any, points: Any, normals: Any, mu: float, direction: Any,
                grip_force: float = 10.0, ramp: float = 3.0, units: str = "mm",
                certified: float | None = None, record: bool = False,
                control: str = "balance", variant: str = "default",
                tip_radius: float | None = None) -> StressResult:
    """One grasp (points and outward normals, part units) under a disturbance of
    ``direction`` (force and torque per newton, torque in N x part unit) ramped to
    ``ramp`` times the certified payload (or to ``grip_force`` where that is 0): the
    load at which the part slipped, or None where it held (module docstring).
    ``control``: ``"balance"`` (force-controlled fingers that measure the load and push
    with the forces of :func:`balance_forces`, each up to twice its squeeze: a grasp's
    forces are statically indeterminate, and the certificate is that of the best ones)
    or ``"servo"`` (stiff position servos: the load shared as the stiffness of contacts
    and servos shares it).  ``variant``: the simulator's settings, varied
    (:data:`VARIANTS`).  ``tip_radius``: the fingertips' (part units; default
    :data:`TIP_RADIUS` of the part's size; a report's ``--hand tip=R``).
    ``record``: keep the part's pose and the load every 5 ms (``history``: time, load,
    displacement, rotation in degrees, and the displacement's x and y)."""
    from ..model.loads import grasp_payload

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
        cert = float(grasp_payload(p, -n, mu, _unit_load(polygon, u),
                                   force_limit=list(preload)).scale)
    schedule = _schedule(control, mu, cert, polygon, p, n, 2 * preload, u, ramp * cert)
    model, kp = _model(polygon, p, n, mu, preload, metres, balance=schedule is not None,
                       tip=tip_radius)
    vary(model, variant)
    out = _run(model, polygon, preload, kp, metres, u, cert, ramp, grip_force, record, p,
               n, preload, schedule)
    out.cone_margin_deg = cone_margin(planar_closed(p, n), mu)
    return out


def _run(model: Any, polygon: Any, preload: FloatArray, kp: FloatArray, metres: float,
         u: FloatArray, cert: float, ramp: float, grip_force: float, record: bool,
         p: FloatArray, n: FloatArray, grips: FloatArray,
         schedule: tuple[FloatArray, FloatArray] | None = None) -> StressResult:
    """The squeeze, then the ramp of the disturbance ``u`` until the part slips; with a
    ``schedule`` (:func:`balance_forces`), force-controlled fingers pushing with its
    forces at the load of the moment (interpolated; past its last load, the last)."""
    mujoco = _mujoco()
    if schedule is None:
        data = _settle(model, preload, kp)
    else:
        data = mujoco.MjData(model)
        data.ctrl[:] = schedule[1][0]
        for _ in range(_steps(model, SETTLE_TIME)):
            mujoco.mj_step(model, data)
    q0 = data.qpos[:3].copy()
    settle = float(math.hypot(q0[0], q0[1])) / metres
    body = model.body("part").id
    size = polygon.size * metres
    top = ramp * cert if cert > 0 else float(grip_force)
    n_ramp = _steps(model, RAMP_TIME)
    every = _steps(model, RECORD_TIME)
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
        if schedule is not None:
            data.ctrl[:] = [np.interp(load_now, schedule[0], f) for f in schedule[1].T]
        mujoco.mj_step(model, data)
        dq = data.qpos[:3] - q0
        moved, turned = math.hypot(dq[0], dq[1]), abs(dq[2])
        if record and k % every == 0:
            hist.append((k * float(model.opt.timestep), load_now, moved / metres,
                         math.degrees(dq[2]), dq[0] / metres, dq[1] / metres))
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
    from ..grippers.jaw import jaw_poses

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
               bottom: float, mu: float, grip: float, metres: float, balance: bool = False
               ) -> tuple[Any, float]:
    """The part and the jaw's two flat pads (boxes on slides along the closing
    direction, each a stiff servo or, ``balance``, force controlled), as :func:`_model`
    builds fingers."""
    model, _ = _model(polygon, np.zeros((0, 2)), np.zeros((0, 2)), mu, np.zeros(0),
                      metres, pads=(jaw, theta, offset, top, bottom, grip), balance=balance)
    size = polygon.size * metres
    return model, grip / (SERVO_COMPLIANCE * size)


def jaw_stress_test(polygon: Any, jaw: Any, theta: float, offset: float, direction: Any,
                    grip_force: float = 10.0, ramp: float = 3.0, units: str = "mm",
                    mu: float | None = None, record: bool = False,
                    control: str = "balance", variant: str = "default"
                    ) -> StressResult | None:
    """One pose of a parallel jaw (flat pads of ``jaw.pad_width``, friction ``jaw.mu``
    or ``mu``) under a disturbance, as :func:`stress_test` runs fingers: each pad
    squeezes with ``grip_force``; the certified payload is that of the pose's contacts
    (:func:`fcgrasp.grasp_payload`, each pad's force shared by its contact points).
    ``control`` and ``variant`` as :func:`stress_test`'s (``"balance"``: the pads
    balance the load, each pushing up to twice the grip force).
    None where the pose does not hold by the jaw's own model."""
    from ..model.loads import grasp_payload

    got = jaw_contacts(polygon, jaw, theta, offset)
    if got is None:
        return None
    pts, nrm, pad, top, bottom = got
    mu_v = float(jaw.mu if mu is None else mu)
    u = np.asarray(direction, float)
    per = [grip_force / int(np.sum(pad == k)) for k in pad]
    cert = float(grasp_payload(pts, -nrm, mu_v, _unit_load(polygon, u),
                               force_limit=per).scale) if mu_v > 0 else 0.0
    metres = _METRES.get(units, _METRES["mm"])
    preload = np.full(2, float(grip_force))
    closing = np.array([math.cos(theta), math.sin(theta)])
    schedule = _schedule(control, mu_v, cert, polygon, pts, nrm, 2 * preload, u,
                         ramp * cert, fingers=pad, axes=[-closing, closing])
    model, kp = _jaw_model(polygon, jaw, theta, offset, top, bottom, mu_v, grip_force,
                           metres, balance=schedule is not None)
    vary(model, variant)
    out = _run(model, polygon, preload, np.full(2, kp), metres, u, cert, ramp,
               grip_force, record, pts, nrm, np.asarray(per, float), schedule)
    out.cone_margin_deg = cone_margin(planar_closed(pts, nrm), mu_v)
    return out
