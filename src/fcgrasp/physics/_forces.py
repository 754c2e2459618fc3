"""The stress test's forces and grasps of a planar part (part of :mod:`fcgrasp.physics`):
grasps sampled in the plans' regions, the fingers' squeeze, the forces inside the
friction cones that balance a load (a linear program per level), and a grasp's margin to
its cones (theorem 6.1's closure test, by bisection)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core._checks import FloatArray
from ..core.tolerances import ON_EDGE_TOL, SQUEEZE_TOL, TINY

#: The fingertips' radius (share of the part's size) where the report gives none.
TIP_RADIUS = 0.002


#: Load levels at which the balancing fingers' forces are solved along the ramp (the
#: forces between two levels interpolated: a convex combination of two balancing
#: forces balances the load between them).
BALANCE_LEVELS = 24


#: The precision (degrees) of a grasp's reported margin to its friction cones.
CONE_MARGIN_STEP = 0.01


def cone_margin(closed: Any, mu: float) -> float | None:
    """The grasp's margin to its friction cones, in degrees: how far every cone's half
    angle ``atan(mu)`` can narrow with the grasp still force closure (``closed(m)``: is
    it with friction ``m``), by bisection to :data:`CONE_MARGIN_STEP` degrees; 0 for a
    grasp that is not force closure, None without friction."""
    if mu <= 0:
        return None
    half = math.atan(mu)
    if not closed(mu):
        return 0.0
    if closed(0.0):
        return math.degrees(half)
    lo, hi = 0.0, half                       # closed at a narrowing of lo, not of hi
    while math.degrees(hi - lo) > CONE_MARGIN_STEP:
        mid = (lo + hi) / 2
        if closed(math.tan(half - mid)):
            lo = mid
        else:
            hi = mid
    return math.degrees(lo)


def planar_closed(points: Any, normals: Any) -> Any:
    """``closed(m)`` of :func:`cone_margin` for point contacts on a planar part (the
    closure test of theorem 6.1 on the cones' edges)."""
    from ..core.closure import closure_escape

    p, n = np.asarray(points, float), np.asarray(normals, float)
    n = n / np.linalg.norm(n, axis=1)[:, None]
    return lambda m: bool(closure_escape(_edges(p, n, m)[2])[0])


def sample_grasps(polygon: Any, regions: Any, count: int, rng: np.random.Generator,
                  normals: Any = None, tip: float | None = None
                  ) -> list[tuple[FloatArray, FloatArray]]:
    """``count`` grasps of one point per region (a polyline along the boundary): the
    regions' starts, their ends, their middles, then seeded points; each with the
    outward normal of the edge it lies on.  Points are kept three fingertip radii off
    the vertices of the region's polyline (its ends included), moved along the region
    (a third of the edge at most): a fingertip on a corner touches both edges, where the
    certificate reads the contact on one.  A region that is a point (a given contact)
    keeps its own normal (``normals``, one per region), as does a region no longer than
    six fingertip radii (a corner).  ``tip``: the fingertips' radius (part units;
    default :data:`TIP_RADIUS` of the part's size)."""
    import shapely

    radius = TIP_RADIUS * polygon.size if tip is None else float(tip)
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
            if L <= 6 * radius and normals is not None:
                # a region no longer than a fingertip: a corner, held with the plan's
                # normal there (a fingertip on a corner pushes along the fan's)
                given = np.asarray(normals[j], float)
                pts.append(r[0] + (r[-1] - r[0]) / 2 if len(r) == 2 else r[len(r) // 2])
                nrm.append(given / np.linalg.norm(given))
                continue
            s = (u if u is not None else float(rng.uniform())) * L
            s = min(max(s, eps), L - eps) if L > 2 * eps else L / 2
            i = int(np.clip(np.searchsorted(c, s, side="right") - 1, 0, len(r) - 2))
            off = min(3 * radius, (c[i + 1] - c[i]) / 3)
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


def balance_forces(points: Any, normals: Any, mu: float, limits: Any, load: Any,
                   top: float, levels: int = BALANCE_LEVELS, fingers: Any = None,
                   axes: Any = None) -> tuple[FloatArray, FloatArray]:
    """The forces with which fingers that measure their load hold it (grasp force
    optimisation): at each of ``levels + 1`` loads ``k load`` from 0 to ``top`` (``load``
    the disturbance's wrench per newton about the origin, torque in N x part unit), the
    contact forces in their friction cones that balance it, each finger's push at most
    its ``limits``, with every force as far inside its cone as it can be (each friction
    edge's coefficient at least ``s``, ``s`` as large as it can be; a linear program).
    A finger's push is the sum of its contacts' forces along its ``axes``, where
    ``fingers[j]`` is the finger of contact ``j`` (a jaw's pads, pushing along the
    closing direction); by default one finger per contact, pushing along its inward
    normal.
    Returns the loads reached and each one's pushes (rows); the loads stop at the first
    level no such forces balance (the grasp's payload with these limits,
    :func:`fcgrasp.grasp_payload`, lies between it and the one before)."""
    from scipy.optimize import linprog

    p, n = np.asarray(points, float), np.asarray(normals, float)
    n = n / np.linalg.norm(n, axis=1)[:, None]
    F, contact, W = _edges(p, n, mu)
    own = np.arange(len(p)) if fingers is None else np.asarray(fingers, int)
    push = -n if axes is None else np.asarray(axes, float)
    o = own[contact]
    share = np.einsum("ij,ij->i", F, push[o])
    scale = max(float(np.max(np.abs(p))), TINY)
    Wn, w = W.copy(), np.array(load, float)
    Wn[:, 2] /= scale
    w[2] /= scale
    m, k = len(F), len(push)
    A_ub = np.zeros((m + k, m + 1))
    A_ub[:m, :m] = -np.eye(m)                                # s <= c_e
    A_ub[:m, m] = 1.0
    for i in range(k):
        A_ub[m + i, :m] = (o == i) * share                   # normal_i <= limit_i
    b_ub = np.r_[np.zeros(m), np.asarray(limits, float)]
    A_eq = np.c_[Wn.T, np.zeros(3)]
    c = np.zeros(m + 1)
    c[m] = -1.0
    reached, forces = [], []
    for level in np.linspace(0.0, top, levels + 1):
        res = linprog(c, A_ub=A_ub, b_ub=b_ub, A_eq=A_eq, b_eq=-level * w,
                      bounds=[(0, None)] * (m + 1), method="highs")
        if res.status != 0:
            break
        reached.append(level)
        forces.append([float(np.sum(res.x[:m][o == i] * share[o == i])) for i in range(k)])
    return np.array(reached), np.array(forces).reshape(-1, k)
