r"""Force closure of grasps of solid parts, in the six dimensions of spatial wrenches
(the paper's definition 2.4 and theorem 3.1, in 3-D).

A grasp is in **force closure** when its contacts' wrench cones sum to all of
:math:`\mathbb{R}^6`.  Writing ``G`` for the linear map from the contacts' local forces
(:func:`~fcgrasp.spatial.contacts.contact_maps`) to wrenches and ``K`` for the product
of their cones, ``G K = R^6`` exactly when

1. ``G`` has rank 6 (the contacts' wrench directions span the space), and
2. some force strictly inside ``K`` has zero wrench (internal forces with every contact
   strictly inside its cone: ``G (int K)`` is then an open cone containing 0, the space).

:func:`closure_margin` decides the second by one second-order cone program (Clarabel):
the largest ``t`` with ``G f = 0``, the normal forces summing to 1, and every contact
``t`` inside its cone (``mu f_n - t >= |(f_1, f_2)|``, or with a soft finger's torsion
``mu f_n - t >= |(f_1, f_2, mu m_n / gamma)|``; ``f_n >= t`` frictionless).  The exact
quadratic cones, no linearisation.  When the grasp fails, a second program finds a wrench
``d`` that no contact force opposes (every contact wrench does work ``>= 0`` on it:
``G_i^T d`` in the dual of each cone), or with rank below 6 a wrench orthogonal to them
all: the external wrench ``d`` is not resisted (``unresisted``), the 3-D counterpart of
:meth:`fcgrasp.Grasp.explain`'s reason.

Two soft fingers, the most useful 3-D primitive (the paper's conclusion), have a closed
form, batched by :func:`two_soft_closure`: force closure exactly when the segment
joining the contacts lies strictly inside both friction cones (Nguyen's 3-D theorem; its
torque about the segment is the torsional friction's).  Two points with friction are
never in force closure (nothing resists the rotation about the segment).

Ties (a contact on its cone's boundary, rank deficient grasps) are not force closure,
as in the plane.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core._checks import FloatArray, check_array
from ..core.tolerances import CONE_PROGRAM_TOL, TOL
from ._program import solve_linear
from .contacts import check_spatial_contacts, check_spatial_grasp, contact_maps

__all__ = ["SpatialClosure", "closure_margin", "spatial_force_closure", "two_soft_closure"]


@dataclass(frozen=True)
class SpatialClosure:
    """The verdict on one grasp: ``closure`` (bool), ``margin`` (the program's ``t``:
    how far inside their cones internal forces of unit total normal force can keep every
    contact; 0 when rank deficient), ``rank`` of the wrench map, and when not in force
    closure ``unresisted``: a unit wrench (force, moment over the radius) that no
    combination of contact forces resists."""

    closure: bool
    margin: float
    rank: int
    unresisted: FloatArray | None = field(default=None, repr=False)

    def explain(self) -> str:
        """One line: the verdict and its reason."""
        if self.closure:
            return f"force closure: internal forces keep every contact {self.margin:.3g} " \
                   f"inside its cone (unit total normal force)"
        if self.rank < 6:
            return f"not force closure: the contact wrenches span only {self.rank} of the " \
                   f"6 dimensions; the wrench {_fmt(self.unresisted)} is not resisted"
        return f"not force closure: no internal forces hold every contact strictly inside " \
               f"its cone; the wrench {_fmt(self.unresisted)} is not resisted"


def _fmt(w: FloatArray | None) -> str:
    return "?" if w is None else "(" + ", ".join(f"{v:.3g}" for v in w) + ")"


def _dims(mu: FloatArray, torsion: FloatArray) -> list[int]:
    """Local force components per contact: 1 (frictionless), 3 (friction), 4 (soft)."""
    return [1 if m == 0 else (4 if t > 0 else 3) for m, t in zip(mu, torsion, strict=True)]


def closure_margin(points: Any, normals: Any, mu: Any = 0.0, torsion: Any = 0.0,
                   center: Any = None, radius: float | None = None) -> SpatialClosure:
    """Force closure of one grasp of ``k`` contacts (module docstring): ``points`` and
    inward ``normals`` (k, 3), ``mu`` and ``torsion`` per contact or one for all.

    ``center`` and ``radius`` (default: the contacts' mean and largest distance from it)
    only scale torques; the verdict does not depend on them.

    >>> sq = [[1, 0, 0], [-1, 0, 0]]
    >>> closure_margin(sq, [[-1, 0, 0], [1, 0, 0]], mu=0.5, torsion=0.01).closure
    True
    >>> closure_margin(sq, [[-1, 0, 0], [1, 0, 0]], mu=0.5).explain()[:40]
    'not force closure: the contact wrenches '
    """
    import clarabel

    p, n, m, tor, c, radius = check_spatial_grasp(points, normals, mu, torsion, center,
                                                  radius)
    G4 = contact_maps(p, n, tor, c, radius)                     # (k, 6, 4)
    dims = _dims(m, tor)
    G = np.concatenate([G4[i, :, :d] for i, d in enumerate(dims)], axis=1)   # (6, N)
    sv = np.linalg.svd(G, compute_uv=False)
    rank = int(np.sum(sv > TOL * max(1.0, float(sv[0]) if sv.size else 1.0)))
    N = G.shape[1]
    # variables x = (f, t); minimise -t
    q = np.zeros(N + 1)
    q[-1] = -1.0
    rows: list[FloatArray] = []
    b: list[float] = []
    cones: list[Any] = []
    for i in range(6):                                          # G f = 0
        rows.append(np.r_[G[i], 0.0])
        b.append(0.0)
    total = np.zeros(N + 1)
    starts = np.cumsum([0, *dims])[:-1]
    total[starts] = 1.0                                         # sum of normal forces = 1
    rows.append(total)
    b.append(1.0)
    cones.append(clarabel.ZeroConeT(7))
    lin = [i for i, d in enumerate(dims) if d == 1]
    for i in lin:                                               # f_n - t >= 0
        r = np.zeros(N + 1)
        r[starts[i]], r[-1] = -1.0, 1.0
        rows.append(r)
        b.append(0.0)
    if lin:
        cones.append(clarabel.NonnegativeConeT(len(lin)))
    for i, d in enumerate(dims):                                # (mu f_n - t, f_t, ...) in SOC
        if d == 1:
            continue
        s = starts[i]
        r = np.zeros(N + 1)
        r[s], r[-1] = -m[i], 1.0
        rows.append(r)
        b.append(0.0)
        for j in range(1, d):
            r = np.zeros(N + 1)
            r[s + j] = -(m[i] / tor[i] if j == 3 else 1.0)      # m_n: a moment
            rows.append(r)
            b.append(0.0)
        cones.append(clarabel.SecondOrderConeT(d))
    sol = solve_linear(q, rows, b, cones)
    status = str(sol.status)
    t = float(sol.x[-1]) if status.startswith("Solved") or "Almost" in status else 0.0
    if "Infeasible" in status:
        t = -np.inf
    closed = rank == 6 and t > CONE_PROGRAM_TOL
    unresisted = None
    if not closed:
        unresisted = _unresisted(G, dims, m, tor) if rank == 6 else \
            np.linalg.svd(G)[0][:, -1]
    return SpatialClosure(bool(closed), max(t, 0.0) if rank == 6 else 0.0, rank, unresisted)


def _unresisted(G: FloatArray, dims: list[int], mu: FloatArray, torsion: FloatArray
                ) -> FloatArray:
    """A unit wrench ``d`` that every contact wrench does work >= 0 on (``G_i^T d`` in
    the dual of each contact's cone: ``y_n >= mu |y_t|``, the torsion's component scaled
    by ``torsion / mu``), with the largest total normal work: the certificate that the
    external wrench ``d`` is not resisted.  One more cone program."""
    import clarabel

    rows: list[FloatArray] = []
    cones: list[Any] = []
    q = np.zeros(6)
    start = 0
    for i, d in enumerate(dims):
        block = G[:, start:start + d].T                          # (d, 6): G_i^T
        start += d
        q -= block[0]                                           # maximise sum of y_n
        if d == 1:
            rows.append(-block[0])
            cones.append(clarabel.NonnegativeConeT(1))
            continue
        rows.append(-block[0])
        rows += [-mu[i] * block[j] for j in (1, 2)]
        if d == 4:
            rows.append(-torsion[i] * block[3])
        cones.append(clarabel.SecondOrderConeT(d))
    rows.append(np.zeros(6))                                    # |d| <= 1
    rows += list(-np.eye(6))
    cones.append(clarabel.SecondOrderConeT(7))
    b = np.zeros(len(rows))
    b[-7] = 1.0
    sol = solve_linear(q, rows, b, cones)
    found = np.asarray(sol.x, float)
    norm = float(np.linalg.norm(found))
    return found / norm if norm > 0 else found


def two_soft_closure(points: Any, normals: Any, mu: Any, margin: float = 0.0,
                     tol: float = TOL) -> FloatArray:
    """Force closure of two soft fingers, batched: ``points`` and inward ``normals``
    (..., 2, 3), ``mu`` broadcast to (...); torsion is assumed positive (soft fingers).

    In force closure exactly when the segment joining the contacts points strictly
    inside both friction cones: the angle between ``p_2 - p_1`` and ``n_1``, and between
    ``p_1 - p_2`` and ``n_2``, below ``atan(mu)`` less ``margin`` (radians), decided
    with ``tol`` on the sines.  Returns booleans of shape (...).

    >>> two_soft_closure([[[0, 0, 0], [0, 0, 2]]], [[[0, 0, 1], [0, 0.2, -1]]], 0.3).tolist()
    [True]
    """
    p = check_array(points, "points", last=3, min_ndim=2)
    n = check_array(normals, "normals", last=3, min_ndim=2)
    if p.shape[-2] != 2 or n.shape != p.shape:
        raise ValueError(f"points and normals must have shape (..., 2, 3), got {p.shape} "
                         f"and {n.shape}")
    m = np.broadcast_to(check_array(mu, "mu"), p.shape[:-2])
    if np.any(m < 0):
        raise ValueError(f"mu must be >= 0, got {mu!r}")
    d = p[..., 1, :] - p[..., 0, :]
    length = np.linalg.norm(d, axis=-1)
    u = d / np.where(length > 0, length, 1.0)[..., None]
    n = n / np.maximum(np.linalg.norm(n, axis=-1), TOL)[..., None]
    half = np.arctan(m) - margin
    cos1 = np.einsum("...i,...i->...", u, n[..., 0, :])
    cos2 = -np.einsum("...i,...i->...", u, n[..., 1, :])
    sin1 = np.linalg.norm(np.cross(u, n[..., 0, :]), axis=-1)
    sin2 = np.linalg.norm(np.cross(u, n[..., 1, :]), axis=-1)
    # angle < half  <=>  sin(half - angle) > 0 with the angle in [0, pi]
    ch, sh = np.cos(half), np.sin(half)
    in1 = (sh * cos1 - ch * sin1 > tol) & (half > 0)
    in2 = (sh * cos2 - ch * sin2 > tol) & (half > 0)
    far = length > tol * np.maximum(1.0, np.linalg.norm(p, axis=(-1, -2)))
    return np.asarray(in1 & in2 & far)


def spatial_force_closure(points: Any, normals: Any, mu: Any = 0.0, torsion: Any = 0.0
                          ) -> FloatArray:
    """Force closure of a batch of grasps (..., k, 3): two soft fingers by the closed
    form (:func:`two_soft_closure`, any batch size), two contacts without torsion never,
    other grasps by :func:`closure_margin` one at a time.  Booleans of shape (...)."""
    p, n, m, tor = check_spatial_contacts(points, normals, mu, torsion)
    batch = p.shape[:-2]
    k = p.shape[-2]
    # a flat batch (one grasp of shape (k, 3) is a batch of one)
    flat_p, flat_n = p.reshape(-1, k, 3), n.reshape(-1, k, 3)
    flat_m, flat_t = m.reshape(-1, k), tor.reshape(-1, k)
    if k == 2:
        soft = np.all(flat_t > 0, axis=-1)
        same = np.all(flat_m == flat_m[:, :1], axis=-1)
        out = np.zeros(flat_p.shape[0], dtype=bool)
        fast = soft & same
        if np.any(fast):
            out[fast] = two_soft_closure(flat_p[fast], flat_n[fast], flat_m[fast][:, 0])
        for i in np.flatnonzero(soft & ~same):
            out[i] = closure_margin(flat_p[i], flat_n[i], flat_m[i], flat_t[i]).closure
        return out.reshape(batch)
    out = np.array([closure_margin(flat_p[i], flat_n[i], flat_m[i], flat_t[i]).closure
                    for i in range(flat_p.shape[0])], dtype=bool)
    return out.reshape(batch)
