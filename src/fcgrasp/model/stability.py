r"""Is a grasp stable? Fingers as springs (the paper's section 8.2 and
Nguyen's "constructing stable grasps"; Cutkosky and Kao's grasp stiffness).

Each finger is a linear spring pressing its tip on the part: stiffness ``k`` along the
contact normal (and, for a finger that sticks, ``k_t`` along the edge), preloaded with
the force it pushes with at rest.  The part moves by a small planar motion
``q = (dx, dy, dtheta)`` (a rotation about ``about``, the part's centroid by default,
then a translation); the fingertips stay where they are.  The compression of finger
``i`` on a flat edge (outward normal ``n``, contact ``p``, tip radius ``rho``) is

.. math:: c_i(q) = \rho\,(1 - n \cdot R n) + (R n) \cdot (R p + t - p),

its tangential stretch ``s_i(q) = u \cdot (R p + t - p)`` (a tip that sticks: the
material point's displacement along the edge's direction ``u`` at rest),
and the potential energy ``U = sum_i k_i (c_i + f_i / k_i)^2 / 2 + k_{t,i} (s_i -
g_i / k_{t,i})^2 / 2`` with the preload's forces on the part: ``f_i`` pushing along
``-n``, ``g_i`` along ``u`` (signed).
At rest in equilibrium the gradient is zero and the **grasp stiffness** is the Hessian

.. math:: K = \sum_i k_i w_i w_i^T + k_{t,i} v_i v_i^T + f_i H_i - g_i G_i,

``w_i = (n, p \times n)`` and ``v_i = (u, p \times u)`` (the wrenches of the springs),
``H_i`` and ``G_i`` the second derivatives of ``c_i`` and ``s_i``: the *geometric* terms
the preload brings, which are what make a pinch of two flat faces stable in rotation and
a pinch of two tips on a disc neutral.  The grasp is **stable** when ``K`` is positive
definite (a strict minimum of the energy); its margin is the smallest eigenvalue, and
its eigenvector the motion the grasp resists least.

Units: lengths in the part's units, stiffnesses in N per unit, forces in N.  Tested
against central differences of the energy computed from the moved geometry.

>>> # two fingers pinching the flat faces x = -10 and x = 10, 5 N each
>>> pinch = ([[-10, 0], [10, 0]], [[-1, 0], [1, 0]])
>>> grasp_stability(*pinch, stiffness=100, preload=[5, 5]).reason    # tips that slide
'neutral: no restoring stiffness along translation along y (the weakest motion [0.0, 1.0, 0.0])'
>>> st = grasp_stability(*pinch, stiffness=100, preload=[5, 5], tangential=100)
>>> st.stable, st.matrix.diagonal().tolist()                         # tips that stick
(True, [200.0, 200.0, 20100.0])
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core._checks import FloatArray, check_array, check_contact_points, check_scalar
from ..core.tolerances import CHECK_TOL, TINY, TOL
from .polygon import Polygon

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = ["Stability", "grasp_stiffness", "grasp_stability", "least_stiffness",
           "squeeze_preload", "PlanStability", "plan_stability"]


def _per_finger(value: Any, name: str, k: int, nonnegative: bool = True) -> FloatArray:
    try:
        a = np.asarray(value, float)
    except (TypeError, ValueError):
        a = np.full(0, np.nan)
    if a.ndim > 1 or a.size not in (1, k) or not np.all(np.isfinite(a)) \
            or (nonnegative and np.any(a < 0)):
        raise ValueError(f"{name} must be a number >= 0 or one per finger ({k}), got "
                         f"{value!r}")
    return np.broadcast_to(a.ravel(), (k,)).astype(float)


def _geometry(points: ArrayLike, normals: ArrayLike, about: ArrayLike | None
              ) -> tuple[FloatArray, FloatArray]:
    p, n = check_contact_points(points, normals)
    c = np.zeros(2) if about is None else check_array(about, "about", last=2)
    if c.shape != (2,):
        raise ValueError(f"about must be a point (x, y), got {about!r}")
    return p - c, n


def grasp_stiffness(points: ArrayLike, normals: ArrayLike, stiffness: ArrayLike, preload: ArrayLike,
                    tangential: ArrayLike = 0.0, tangential_preload: ArrayLike = 0.0,
                    finger_radius: ArrayLike = 0.0, about: ArrayLike | None = None) -> FloatArray:
    """The grasp stiffness matrix ``K`` (3 x 3, in ``(dx, dy, dtheta)`` about
    ``about``; see the module docstring).

    ``points``, ``normals``: contacts and the part's *outward* normals there;
    ``stiffness``: each finger's normal stiffness; ``preload``: the normal force each
    pushes with at rest; ``tangential``: the stiffness along the edge's direction ``u``
    (the outward normal turned a quarter counter-clockwise) of fingers that stick (0:
    they slide) and ``tangential_preload`` the force each exerts on the part along
    ``u`` at rest (signed: friction); ``finger_radius``: the tips' radius.
    """
    p, n = _geometry(points, normals, about)
    k = len(p)
    kn = _per_finger(stiffness, "stiffness", k)
    f = _per_finger(preload, "preload", k)
    kt = _per_finger(tangential, "tangential", k)
    g = _per_finger(tangential_preload, "tangential_preload", k, nonnegative=False)
    rho = _per_finger(finger_radius, "finger_radius", k)
    u = np.stack([-n[:, 1], n[:, 0]], axis=1)
    K = np.zeros((3, 3))
    for i in range(k):
        w = np.array([n[i, 0], n[i, 1], p[i, 0] * n[i, 1] - p[i, 1] * n[i, 0]])
        v = np.array([u[i, 0], u[i, 1], p[i, 0] * u[i, 1] - p[i, 1] * u[i, 0]])
        # second derivatives at rest of the compression and of the tangential stretch
        H = np.array([[0.0, 0.0, -n[i, 1]],
                      [0.0, 0.0, n[i, 0]],
                      [-n[i, 1], n[i, 0], float(n[i] @ p[i]) + rho[i]]])
        G = np.zeros((3, 3))
        G[2, 2] = -float(u[i] @ p[i])
        K += kn[i] * np.outer(w, w) + kt[i] * np.outer(v, v) + f[i] * H - g[i] * G
    return K


@dataclass(frozen=True)
class Stability:
    """A grasp's stiffness ``matrix``, its ``eigenvalues`` (ascending) and the motion of
    the smallest (``weakest``, a unit vector in ``(dx, dy, dtheta)``); ``stable``: all
    eigenvalues above ``tol`` times the largest; ``margin``: the smallest eigenvalue;
    ``equilibrium``: how far the preload is from balancing (0 in equilibrium);
    ``reason``: a sentence."""

    matrix: FloatArray
    eigenvalues: FloatArray
    weakest: FloatArray
    stable: bool
    equilibrium: float
    reason: str

    @property
    def margin(self) -> float:
        return float(self.eigenvalues[0])


def grasp_stability(points: ArrayLike, normals: ArrayLike, stiffness: ArrayLike, preload: ArrayLike,
                    tangential: ArrayLike = 0.0, tangential_preload: ArrayLike = 0.0,
                    finger_radius: ArrayLike = 0.0, about: ArrayLike | None = None,
                    tol: float = CHECK_TOL) -> Stability:
    """Whether a grasp of fingers as springs sits at a strict minimum of its energy
    (:func:`grasp_stiffness` positive definite), with the reason; the preload must be
    in equilibrium (else ValueError: a grasp that is not at rest has no stiffness)."""
    p, n = _geometry(points, normals, about)
    k = len(p)
    f = _per_finger(preload, "preload", k)
    g = _per_finger(tangential_preload, "tangential_preload", k, nonnegative=False)
    u = np.stack([-n[:, 1], n[:, 0]], axis=1)
    # the fingers push along -n (and g along u): their wrenches must cancel
    force = -(f[:, None] * n).sum(axis=0) + (g[:, None] * u).sum(axis=0)
    torque = float(np.sum(-f * (p[:, 0] * n[:, 1] - p[:, 1] * n[:, 0])
                          + g * (p[:, 0] * u[:, 1] - p[:, 1] * u[:, 0])))
    scale = max(1.0, float(np.abs(f).sum() + np.abs(g).sum()))
    size = max(1.0, float(np.abs(p).max()))
    off = float(max(np.hypot(*force), abs(torque) / size) / scale)
    if off > TOL * 1e3:
        raise ValueError(f"preload must balance (the fingers' forces and torques sum to "
                         f"zero at rest), got a residual force {force.round(9).tolist()} "
                         f"and torque {torque:.6g}")
    K = grasp_stiffness(points, normals, stiffness, preload, tangential, tangential_preload,
                        finger_radius, about)
    vals, vecs = np.linalg.eigh(K)
    top = max(float(np.abs(vals).max()), TINY)
    stable = bool(vals[0] > tol * top)
    weak = vecs[:, 0] / np.linalg.norm(vecs[:, 0])
    names = ("translation along x", "translation along y", "rotation")
    kind = names[int(np.argmax(np.abs(weak)))]
    if stable:
        reason = f"stable: the energy rises in every direction; least along {kind} " \
                 f"({vals[0]:.6g})"
    elif vals[0] > -tol * top:
        reason = f"neutral: no restoring stiffness along {kind} (the weakest motion " \
                 f"{weak.round(6).tolist()})"
    else:
        reason = f"unstable: the energy falls along {kind} (the weakest motion " \
                 f"{weak.round(6).tolist()}, stiffness {vals[0]:.6g})"
    return Stability(K, vals, weak, stable, off, reason)


def least_stiffness(points: ArrayLike, normals: ArrayLike, preload: ArrayLike,
                    margin: ArrayLike = 1.0,
                    tangential_ratio: ArrayLike = 0.0, tangential_preload: ArrayLike = 0.0,
                    finger_radius: ArrayLike = 0.0, about: ArrayLike | None = None) -> float:
    """The least common finger stiffness ``k`` (tangential ``tangential_ratio * k``)
    that makes the grasp's stiffness at least ``margin`` in every direction (the
    smallest eigenvalue of :func:`grasp_stiffness`; it rises with ``k``, so bisection
    to a relative 1e-9); ``inf`` when no stiffness does (the springs' wrenches do not
    span the plane's motions)."""
    m = check_scalar(margin, "margin", positive=True)
    ratio = check_scalar(tangential_ratio, "tangential_ratio", nonnegative=True)

    def low(kk: float) -> float:
        K = grasp_stiffness(points, normals, kk, preload, ratio * kk, tangential_preload,
                            finger_radius, about)
        return float(np.linalg.eigvalsh(K)[0])

    lo, hi = 0.0, 1.0
    while low(hi) < m:
        hi *= 2
        if hi > 1e12:
            return float("inf")
    if low(lo) >= m:
        return 0.0
    while hi - lo > TOL * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if low(mid) >= m else (mid, hi)
    return hi


# ------------------------------------------------------------------ plans

def squeeze_preload(points: ArrayLike, normals: ArrayLike, mu: ArrayLike,
                    grip_force: ArrayLike = 1.0,
                    about: ArrayLike | None = None) -> tuple[FloatArray, FloatArray]:
    """The fingers' forces at rest in a grasp that squeezes the part and nothing else:
    normal forces ``f`` (summing to ``grip_force``) and tangential ``g`` (``|g| <= mu f``)
    whose wrenches cancel, with the smallest normal force as large as it can be (an LP,
    scipy's HiGHS, its solution projected onto the balance exactly).  Force closure
    (theorem 6.1) is what makes such internal forces exist with every ``f > 0``; a grasp
    without them raises ValueError."""
    from scipy.optimize import linprog

    p, n = _geometry(points, normals, about)
    k = len(p)
    m = _per_finger(mu, "mu", k)
    total = check_scalar(grip_force, "grip_force", positive=True)
    u = np.stack([-n[:, 1], n[:, 0]], axis=1)
    size = max(float(np.abs(p).max()), TINY)
    # the balance: sum_i -f_i n_i + g_i u_i = 0 and the torques (lever arms in the size)
    A = np.zeros((3, 2 * k + 1))
    A[0, :k], A[1, :k] = -n[:, 0], -n[:, 1]
    A[0, k:2 * k], A[1, k:2 * k] = u[:, 0], u[:, 1]
    A[2, :k] = -(p[:, 0] * n[:, 1] - p[:, 1] * n[:, 0]) / size
    A[2, k:2 * k] = (p[:, 0] * u[:, 1] - p[:, 1] * u[:, 0]) / size
    sums = np.zeros((1, 2 * k + 1))
    sums[0, :k] = 1.0
    eye = np.eye(k)
    ub = np.vstack([np.c_[-eye, np.zeros((k, k)), np.ones(k)],          # t <= f_i
                    np.c_[-np.diag(m), eye, np.zeros(k)],                # g_i <= mu f_i
                    np.c_[-np.diag(m), -eye, np.zeros(k)]])              # -g_i <= mu f_i
    c = np.zeros(2 * k + 1)
    c[-1] = -1.0
    res = linprog(c, A_ub=ub, b_ub=np.zeros(3 * k), A_eq=np.vstack([A, sums]),
                  b_eq=np.r_[np.zeros(3), total],
                  bounds=[(0, None)] * k + [(None, None)] * k + [(None, None)],
                  method="highs")
    if res.status != 0 or -res.fun <= CHECK_TOL * total:
        raise ValueError("the grasp cannot squeeze the part with every finger pushing (it "
                         "is not force closure): no preload at rest")
    x = np.asarray(res.x[:2 * k], float)
    Ab = A[:, :2 * k]
    x = x - Ab.T @ np.linalg.solve(Ab @ Ab.T, Ab @ x)        # exactly balanced
    return x[:k], x[k:]


@dataclass(frozen=True)
class PlanStability:
    """A plan's stability with finger springs: at its representative grasp
    (``stable``, ``margin``, ``reason``, the ``preload`` of :func:`squeeze_preload` and
    its ``tangential_preload``) and at every corner grasp of its regions
    (``corners_stable``: all of them; ``corners_margin``: the smallest margin)."""

    stable: bool
    margin: float
    reason: str
    preload: FloatArray
    tangential_preload: FloatArray
    corners_stable: bool
    corners_margin: float

    def to_dict(self) -> dict[str, Any]:
        return {"stable": self.stable, "margin": round(self.margin, 9), "reason": self.reason,
                "preload_n": [round(float(v), 9) for v in self.preload],
                "tangential_preload_n": [round(float(v), 9) for v in self.tangential_preload],
                "corners_stable": self.corners_stable,
                "corners_margin": round(self.corners_margin, 9)}


#: The fingers' total squeeze (newtons) when a plan's stability is asked without one.
DEFAULT_GRIP_FORCE = 10.0


def plan_stability(polygon: Polygon, plan: Any, stiffness: ArrayLike,
                   grip_force: ArrayLike = DEFAULT_GRIP_FORCE,
                   tangential: ArrayLike | None = None,
                   finger_radius: ArrayLike = 0.0) -> PlanStability:
    """Whether a plan's grasps are stable with fingers as springs of ``stiffness``
    (N per unit of the part) squeezing with ``grip_force`` newtons in all (section 8.2;
    :func:`grasp_stability` about the centroid, the preload of :func:`squeeze_preload`):
    at the representative grasp and at every corner grasp of the regions.  Fingers with
    friction stick (tangential stiffness ``tangential``, by default ``stiffness``);
    frictionless ones slide (0).  Plans with gravity are refused (their preload balances
    the weight, not only itself)."""
    from .plans import check_point_plan

    polygon = check_point_plan(polygon, plan,
                               no_gravity="its fingers' preload balances the weight")
    k_n = check_scalar(stiffness, "stiffness", positive=True)
    mu = float(plan.mu) if plan.contact_type == "friction" else 0.0
    k_t = (k_n if mu > 0 else 0.0) if tangential is None else \
        check_scalar(tangential, "tangential", nonnegative=True)
    about = np.asarray(polygon.centroid, float)

    def one(points: ArrayLike, normals: ArrayLike) -> tuple[Stability, FloatArray, FloatArray]:
        f, g = squeeze_preload(points, normals, mu, grip_force, about)
        st = grasp_stability(points, normals, k_n, f, k_t, g, finger_radius, about)
        return st, f, g

    rep, f, g = one(plan.contacts, plan.normals)
    corners = [one(c, plan.normals_at(c))[0] for c in plan.corners()]
    return PlanStability(rep.stable, rep.margin, rep.reason, f, g,
                         all(s.stable for s in corners), min(s.margin for s in corners))
