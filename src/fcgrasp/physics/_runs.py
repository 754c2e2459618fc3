"""The stress test's runs: sampled grasps of every plan, the controls, the summary and
the animation (part of :mod:`fcgrasp.physics`)."""

from __future__ import annotations

import math
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from functools import partial
from typing import Any

import numpy as np

from ..core._checks import FloatArray, check_int, check_scalar
from ..errors import ArgumentError
from ._forces import _edges, sample_grasps
from ._planar import (
    VARIANTS,
    StressResult,
    _wrench_dict,
    check_control,
    check_variant,
    jaw_contacts,
    jaw_stress_test,
    stress_test,
)
from ._solids import (
    sample_solid_grasps,
    solid_escape,
    solid_jaw_torsion,
    solid_plan_of,
    solid_stress_test,
)


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
    from ..core.closure import closure_escape

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
                 units: str = "mm", count: int = 3, variant: str = "default",
                 tip_radius: float | None = None) -> list[dict[str, Any]]:
    """The controls of each plan (a plan object or a report's grasp): ``count`` of its
    grasps made not force closure (:func:`control`; a jaw's poses and a solid's grasps
    without friction), each pushed along a wrench it does not resist; per control its
    plan's ``rank``, its ``mu``, :meth:`StressResult.to_dict` and whether it
    ``slipped``; ``variant`` as :func:`simulate`'s."""
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
                                              grip_force=grip_force, variant=variant))
            continue
        jaw = jaw_of(plan)
        if jaw is not None:             # the same poses without friction
            for theta, offset in sample_poses((jaw[1], jaw[2]), count, rng):
                got = jaw_contacts(part, jaw[0], theta, offset)
                if got is not None:
                    add(r, 0.0, jaw_stress_test(part, jaw[0], theta, offset,
                                                escape_direction(part, got[0], got[1], 0.0),
                                                grip_force=grip_force, units=units, mu=0.0,
                                                variant=variant))
            continue
        get: Callable[[str], Any] = plan.__getitem__ if isinstance(plan, dict) else \
            partial(getattr, plan)
        for pts, nrm in sample_grasps(part, get("regions"), count, rng, get("normals"),
                                      tip_radius):
            cp, cn, cmu = control(pts, nrm, float(get("mu")))
            add(r, cmu, stress_test(part, cp, cn, cmu, escape_direction(part, cp, cn, cmu),
                                    grip_force=grip_force, units=units, variant=variant,
                                    tip_radius=tip_radius))
    return out


def _one(job: tuple[str, tuple[Any, ...], dict[str, Any]]) -> StressResult | None:
    kind, args, kwargs = job
    if kind == "jaw":
        return jaw_stress_test(*args, **kwargs)
    if kind == "solid":
        return solid_stress_test(*args, **kwargs)
    return stress_test(*args, **kwargs)


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
        from ..grippers.jaw import ParallelJaw

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
             workers: int | None = None, control: str = "balance", variant: str = "default",
             tip_radius: float | None = None,
             progress: Callable[[int, int], None] | None = None) -> list[dict[str, Any]]:
    """The stress test of each plan (a :class:`~fcgrasp.GraspPlan` of point fingers, a
    :class:`~fcgrasp.JawPlan`, or a report's grasp of either): ``samples`` grasps in
    its regions (:func:`sample_grasps`: ends and middle first) or poses of its box
    (:func:`sample_poses`), each under ``directions`` seeded disturbances, run on
    ``workers`` processes (default: every core).  One summary per plan: its rank, the
    grasps (:meth:`StressResult.to_dict`), how many held up to their certified payload
    and the smallest ratio of slip load to certified payload.  ``control``: how a planar
    part's fingers and pads push (:func:`stress_test`: ``"balance"``, the forces that
    balance the load they measure, or ``"servo"``, stiff position servos); a solid's
    fingers are servos.  ``variant``: the simulator's settings, varied
    (:data:`VARIANTS`; :func:`sensitivity` runs them all).  ``tip_radius``: a planar
    part's fingertips' (part units; a report's ``--hand tip=R``)."""
    check_int(samples, "samples", minimum=1)
    check_control(control)
    check_variant(variant)
    check_int(directions, "directions", minimum=1)
    check_scalar(grip_force, "grip_force", positive=True)
    rng = np.random.default_rng(check_int(seed, "seed", minimum=0))
    jobs: list[tuple[str, tuple[Any, ...], dict[str, Any]]] = []
    owners: list[int] = []
    solid = _is_solid(polygon)
    for r, plan in enumerate(plans):
        if solid:
            _, _, mu_s, soft = solid_plan_of(plan)
            pads = solid_jaw_torsion(plan)          # a jaw's pads as soft contacts
            size_u = float(np.linalg.norm(polygon.mesh.extents))
            for pts, nrm in sample_solid_grasps(plan, samples, rng):
                for u in _directions6(rng, directions, size_u):
                    jobs.append(("solid", (polygon, pts, nrm, mu_s, u, soft, grip_force,
                                           3.0, False, pads), {"variant": variant}))
                    owners.append(r)
            continue
        jaw = jaw_of(plan)
        if jaw is not None:
            for theta, offset in sample_poses((jaw[1], jaw[2]), samples, rng):
                for u in _directions(rng, directions, polygon.size):
                    jobs.append(("jaw", (polygon, jaw[0], theta, offset, u, grip_force,
                                         3.0, units),
                                 {"control": control, "variant": variant}))
                    owners.append(r)
            continue
        regions = plan["regions"] if isinstance(plan, dict) else plan.regions
        mu = float(plan["mu"] if isinstance(plan, dict) else plan.mu)
        if isinstance(plan, dict) and "facets" in plan or not len(regions) or \
                np.asarray(regions[0]).shape[-1] != 2:
            raise ArgumentError("the stress test runs point fingers on planar parts: "
                                f"plan {r + 1} is not one", "plans")
        given = plan["normals"] if isinstance(plan, dict) else plan.normals
        for pts, nrm in sample_grasps(polygon, regions, samples, rng, given, tip_radius):
            for u in _directions(rng, directions, polygon.size):
                jobs.append(("fingers", (polygon, pts, nrm, mu, u, grip_force, 3.0, units),
                             {"control": control, "variant": variant,
                              "tip_radius": tip_radius}))
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


def sensitivity(part: Any, plans: Any, *, variants: Any = None, grip_force: float = 10.0,
                seed: int = 0, units: str = "mm", **options: Any) -> list[dict[str, Any]]:
    """The stress test of ``plans`` (:func:`simulate`, its ``options``) once under each
    setting of ``variants`` (default: every one of :data:`VARIANTS`), the same grasps
    and disturbances each time, with the controls: per variant its name, the
    ``change`` it makes, the ``runs``, how many ``held`` to their certified payload, the
    ``least_ratio`` and ``median_ratio`` of slip load to certified payload (a run that
    held to the end of its ramp counts as the ramp's 3) and how many controls
    ``slipped`` of ``controls``.  An answer that is physics changes little from one
    setting to the next."""
    chosen = list(VARIANTS) if variants is None else list(variants)
    rows = []
    for name in chosen:
        out = simulate(part, plans, grip_force=grip_force, seed=seed, units=units,
                       variant=name, **options)
        grasps = [g for o in out for g in o["grasps"] if g["certified_payload"] > 0]
        ratios = [(g["slip_load"] if g["slip_load"] is not None else
                   3.0 * g["certified_payload"]) / g["certified_payload"] for g in grasps]
        ctl = control_runs(part, plans, grip_force=grip_force, seed=seed + 1, units=units,
                           variant=name, tip_radius=options.get("tip_radius"))
        rows.append({"variant": name, "change": VARIANTS[name],
                     "runs": sum(o["runs"] for o in out),
                     "held": sum(o["held"] for o in out),
                     "least_ratio": min(ratios) if ratios else None,
                     "median_ratio": float(np.median(ratios)) if ratios else None,
                     "controls": len(ctl), "slipped": sum(c["slipped"] for c in ctl)})
    return rows


# ----------------------------------------------------------------------------- pictures

def recorded_run(part: Any, plan: Any, direction: dict[str, Any], *,
                 grip_force: float = 10.0, units: str = "mm"
                 ) -> tuple[StressResult, Callable[[str], None]] | None:
    """One grasp of ``plan`` (a report's grasp: a planar part's fingers or box, or a
    solid's regions) recorded under the disturbance ``direction`` (a result's
    ``wrench_direction``), and the function that draws it as an animated GIF at a path
    (:func:`animate`, :func:`animate_solid`); None where the jaw's sampled pose does not
    hold.  The grasp: a solid's first sampled, a box's first sampled pose, a planar
    plan's third sampled grasp (the first region's end)."""
    torque = direction["torque"]
    if _is_solid(part):
        _, _, mu_s, soft = solid_plan_of(plan)
        pts, nrm = sample_solid_grasps(plan, 1, np.random.default_rng(0))[0]
        run = solid_stress_test(part, pts, nrm, mu_s, np.array([*direction["force"], *torque]),
                                soft, grip_force=grip_force, record=True,
                                torsion=solid_jaw_torsion(plan))
        return run, (lambda path: animate_solid(part, run, path, units=units))
    u = np.array([*direction["force"], torque])
    jaw = jaw_of(plan)
    if jaw is not None:
        theta, offset = sample_poses((jaw[1], jaw[2]), 1, np.random.default_rng(0))[0]
        got = jaw_stress_test(part, jaw[0], theta, offset, u, grip_force=grip_force,
                              units=units, record=True)
    else:
        pts, nrm = sample_grasps(part, plan["regions"], 3, np.random.default_rng(0),
                                 plan["normals"])[2]
        got = stress_test(part, pts, nrm, float(plan["mu"]), u, grip_force=grip_force,
                          units=units, record=True)
    if got is None:
        return None
    res = got
    return res, (lambda path: animate(part, res, path, units=units))


def _load_panel(bx: Any, h: FloatArray, result: StressResult, units: str) -> list[Any]:
    """The load against the displacement (the whole history ``h`` sets the panel's
    ranges) on ``bx``, beside the certified payload: the curve and the legend, which
    each frame draws again (:func:`_frames`)."""
    (curve,) = bx.plot(h[:, 1], h[:, 2], color="tab:blue")
    bx.axvline(result.certified_payload, color="tab:green", ls="--", label="certified payload")
    bx.set_xlabel("load (N)")
    bx.set_ylabel(f"displacement ({units})")
    return [curve, bx.legend(loc="upper left")]


#: Frames drawn over one drawing of the still figure (False: each frame draws the whole
#: figure, the reference the tests compare with).
BLIT = True


def _steps(h: FloatArray, frames: int) -> list[int]:
    """The records of the history ``h`` an animation of ``frames`` frames shows."""
    return [int(k) for k in np.unique(np.linspace(0, len(h) - 1, frames).round())]


def _frames(fig: Any, update: Callable[[int], list[Any]], steps: list[int]
            ) -> list[np.ndarray]:
    """The images of an animation of one figure, a frame per record ``k`` of ``steps``,
    set by ``update(k)``, which returns the artists that frame draws, in their order
    (those it changed and those drawn over them).  The figure is laid out and drawn
    once without those artists (its axes, ticks and every still artist: the last step
    sets the widest labels, the ranges hold every step, so nothing jumps), and each
    frame is that image with the artists drawn over it (matplotlib's blitting)."""
    import matplotlib.pyplot as plt

    moving = update(steps[-1])
    for a in moving:
        a.set_animated(BLIT)
    fig.tight_layout()
    canvas = fig.canvas
    canvas.draw()
    still = canvas.copy_from_bbox(fig.bbox)
    images = []
    for k in steps:
        if not BLIT:                        # the reference: the whole figure drawn
            update(k)
            canvas.draw()
        else:
            canvas.restore_region(still)
            for a in update(k):
                if hasattr(a, "do_3d_projection"):      # a 3-D artist, projected
                    a.do_3d_projection()
                fig.draw_artist(a)
        images.append(np.asarray(canvas.buffer_rgba())[..., :3].copy())
    plt.close(fig)
    return images


def _limits(ax: Any, *points: FloatArray) -> None:
    """``ax``'s ranges set to hold every point given (each an array of rows), with
    matplotlib's margins: the ranges of every frame at once."""
    pts = np.vstack([np.asarray(p, float).reshape(-1, np.asarray(p).shape[-1])
                     for p in points])
    ax.update_datalim(pts[:, :2])
    ax.autoscale_view()


def animate_solid(solid: Any, result: StressResult, path: str, units: str = "mm",
                  frames: int = 24) -> None:
    """An animated GIF of one stress test of a solid recorded with ``record=True``
    (:func:`solid_stress_test`), in ``frames`` frames: the mesh moved as the part moved
    (magnified ten times so a slip shows) under the rising load, its rest pose in
    outline, the fingers pushing, and the load against the part's displacement beside
    it."""
    import imageio.v3 as iio
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    from scipy.spatial.transform import Rotation

    h = result.history
    if not len(h) or h.shape[1] != 11:
        raise ArgumentError("result has no history of a solid: run "
                            "solid_stress_test(..., record=True)", "result")
    check_int(frames, "frames", minimum=1)
    mesh = solid.mesh
    tri = np.asarray(mesh.vertices, float)[np.asarray(mesh.faces)]
    centre = np.asarray(mesh.center_mass, float)
    size = float(np.linalg.norm(mesh.extents))
    lo, hi = mesh.bounds[0] - 0.3 * size, mesh.bounds[1] + 0.3 * size

    fig = plt.figure(figsize=(8, 3.6), dpi=80)
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    ax.add_collection3d(Poly3DCollection(tri, facecolor="none", edgecolor="0.75", lw=0.3))
    part = Poly3DCollection(tri, facecolor="0.8", edgecolor="0.4", lw=0.3, alpha=0.8)
    ax.add_collection3d(part)
    fingers = []                            # drawn over the moved part
    for q, nn in zip(result.contacts, result.normals, strict=True):
        fingers.append(ax.scatter(*q, color="tab:red", s=12))
        a, b = q + 0.25 * size * nn, q + 0.05 * size * nn
        fingers += ax.plot(*np.c_[a, b], color="tab:red")
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(tuple(hi - lo))
    ax.tick_params(labelsize=6)
    title = ax.set_title("", fontsize=9)
    panel = _load_panel(fig.add_subplot(1, 2, 2), h, result, units)

    def update(k: int) -> list[Any]:
        load, shift, quat = h[k, 1], h[k, 4:7], h[k, 7:11]
        # the motion magnified: ten times the shift and the rotation's angle
        rot = Rotation.from_quat([*quat[1:], quat[0]]).as_rotvec() * 10
        R = Rotation.from_rotvec(rot).as_matrix()
        part.set_verts((tri - centre) @ R.T + centre + 10 * shift)
        title.set_text(f"load {load:.2f} N (motion x10)")
        panel[0].set_data(h[:k + 1, 1], h[:k + 1, 2])
        return [part, *fingers, title, *panel]

    images = _frames(fig, update, _steps(h, frames))
    iio.imwrite(path, np.stack(images), extension=".gif", duration=120, loop=0)


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
    v = np.vstack([polygon.vertices, polygon.vertices[:1]])
    c = np.asarray(polygon.centroid)

    def moved(k: int) -> FloatArray:
        # the motion magnified: ten times the shift and the turn
        a = math.radians(h[k, 3]) * 10
        rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        return np.asarray((v - c) @ rot.T + c + h[k, 4:6] * 10)

    steps = _steps(h, frames)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(8, 3.6), dpi=80)
    (part,) = ax.fill(v[:, 0], v[:, 1], color="0.8")
    over = ax.plot(v[:, 0], v[:, 1], color="0.6", lw=1)        # drawn over the moved part
    tips = []
    for p, n in zip(result.contacts, result.normals, strict=True):
        over += ax.plot(*p, "o", color="tab:red")
        tips.append(p + 0.15 * polygon.size * n)
        over.append(ax.arrow(*tips[-1], *(-0.1 * polygon.size * n),
                             head_width=0.02 * polygon.size, color="tab:red"))
    ax.set_aspect("equal")
    _limits(ax, v, np.array(tips), *(moved(k) for k in steps))
    title = ax.set_title("")
    panel = _load_panel(bx, h, result, units)

    def update(k: int) -> list[Any]:
        part.set_xy(moved(k))
        title.set_text(f"load {h[k, 1]:.2f} N (motion x10)")
        panel[0].set_data(h[:k + 1, 1], h[:k + 1, 2])
        return [part, *over, title, *panel]

    images = _frames(fig, update, steps)
    iio.imwrite(path, np.stack(images), extension=".gif", duration=120, loop=0)
