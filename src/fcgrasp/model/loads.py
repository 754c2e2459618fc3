r"""Loads a grasp must carry, with fingers that push only so hard.

Force closure says a grasp resists *any* wrench with *some* finger forces; a gripper's
fingers push at most so many newtons.  This module answers "will it hold this part?":

* :class:`Load` is the *task wrench set*: the weight of a part of ``mass`` kilograms at
  its centre of mass ``com``, carried with every linear acceleration of a box
  ``|a_x| <= accel[0]``, ``|a_y| <= accel[1]`` (m/s^2) or of the ellipse with those
  semi-axes (``accel_shape="ellipse"``: an acceleration of at most so much in any
  direction), plus an external torque in a range.  The wrench the fingers must supply
  is ``-(F, com x F + tau)`` with ``F = mass (gravity - a)``: an affine image of a box,
  so a polytope whose vertices are the box's corners (:meth:`Load.wrenches`), or of an
  ellipse times a range (its support function in closed form: :meth:`Load.support`).
* Finger forces: each finger pushes inside its Coulomb cone (``mu``; 0: along the
  normal), its **normal force** at most ``force_limit`` newtons (one value or one per
  finger: a gripper's grip force) and, with ``total_limit``, the normal forces sum to at
  most that (the L1 total a single motor gives).
* :func:`grasp_payload` is the **largest scale** ``s`` such that every wrench of ``s``
  times the load is resisted within the limits (the paper's section 8 resistance, now
  with limits; Dex-Net's ``wrench_resistance`` with ``force_limits``, for a set of
  wrenches instead of one).  Resisting a polytope of wrenches is resisting its vertices
  (the forces resisting a convex combination are the combination of theirs), so it is one
  linear program: a scale and a set of finger forces per vertex.  ``s >= 1``: the grasp
  carries the load; ``s = inf``: no limit given and every scale is resisted.  The
  least-peak-force distribution resisting the load (``s = 1``) comes with it.
  An ellipse of accelerations is not a polytope; with limits the wrenches the fingers
  can supply are (the forces' set is a polytope: each finger's triangle of cone
  coefficients, cut by the total), so ``s`` is exact from that polytope's facets
  ``h . w <= b`` (qhull): ``s = min b / sigma_W(-h)`` (the fingers supply the load's
  opposite), ``sigma_W`` the load's support function.  Where the limits leave that set
  unbounded (no limit on some finger and no total) the load's circumscribed polygon of
  :data:`ELLIPSE_SIDES` sides stands for the ellipse: a lower bound within
  ``1 / cos(pi / sides) - 1`` of the scale.
* :func:`region_payload` is the scale guaranteed over **every** grasp of a plan's
  regions (one finger anywhere in each region), certified: a lower bound from boxes of
  finger positions (below), an upper bound from the worst grasp met, refined by branch
  and bound until they are within ``gap``.

**The lower bound of a box.**  A finger at ``x = a + u t`` on an edge (tangent ``t``,
inward normal ``n``) with force ``f = c_n n + c_t t`` exerts the torque
``a x f + u c_n (t x n)``: bilinear in the position ``u`` and the normal force ``c_n``
only.  Take forces at the corners ``u^k`` of a box of positions and, at a point
``u = sum_k l_k u^k`` inside, their combination with the same weights: its force
balance is exact and its torque is off by
``delta = sum_i sum_k l_k (u_i - u^k_i)(c^k_i - cbar_i) (t_i x n_i)`` for any ``cbar``,
so ``|delta| <= E = sum_i w_i d_i`` when every corner's normal force ``c^k_i`` is
within ``d_i`` of a common ``cbar_i`` (``w_i``: the box's width).  Each corner then
resists the load's wrench with the torque offset by ``+E`` and by ``-E``; at ``u`` the
combination of the ``+E`` and ``-E`` solutions whose offset cancels ``delta`` exists
(the offset runs from ``-E + delta`` to ``E + delta``, continuously, through 0).  So
one linear program over the box's corners (variables: the scale, ``cbar``, ``d``,
``E`` and two sets of forces per corner and load vertex) gives a scale every grasp of
the box reaches: a certified lower bound, tight as the box shrinks (``E -> 0``).
A finger on a vertex its region covers pushes, whatever the normal of the fan between
its two edges, inside the cone common to all of them (half-angle ``atan(mu)`` less half
the fan's turn), its normal force measured along the fan's bisector.

Units: lengths in the part's units, masses in kg, accelerations in m/s^2, forces in N,
torques in N times the part's unit.

>>> import numpy as np
>>> load = Load(mass=0.5, com=(0.0, 0.0))
>>> # two fingers squeezing a 40-wide part from the sides, mu 0.5, 10 N each at most
>>> p = grasp_payload([[-20, 0], [20, 0]], [[1, 0], [-1, 0]], 0.5, load, force_limit=10)
>>> round(p.scale, 4)        # friction holds 2 x 0.5 x 10 N = 10 N against 4.905 N
2.0394
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from ..core._checks import (
    FloatArray,
    check_array,
    check_contact_points,
    check_mu_scalar,
    check_scalar,
)
from ..core.tolerances import TOL
from ._payload_programs import (
    _cone_edges,
    _force_vertices,
    _limits,
    _program,
    _scale,
    _wrench_edges,
)
from .polygon import Polygon

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = ["Load", "Payload", "RegionPayload", "grasp_payload", "region_payload",
           "ACCEL_SHAPES"]

#: Standard gravity, m/s^2.
G0 = 9.80665

#: Sides of the polygon that stands for an ellipse of accelerations in a linear program
#: (circumscribed: every grasp that resists it resists the ellipse; a scale so found is
#: at most a factor ``1 / cos(pi / 64)`` (0.12 %) below the exact one).
ELLIPSE_SIDES = 64

#: The shapes of a load's set of accelerations.
ACCEL_SHAPES = ("box", "ellipse")


def _pair(value: Any, name: str, nonnegative: bool = False) -> tuple[float, float]:
    a = check_array(value, name, last=2)
    if a.shape != (2,) or not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be two finite numbers, got {value!r}")
    if nonnegative and np.any(a < 0):
        raise ValueError(f"{name} must be two non-negative numbers, got {value!r}")
    return float(a[0]), float(a[1])


@dataclass(frozen=True)
class Load:
    """A task wrench set: a part's weight and inertia under a box of accelerations, and
    a range of external torque.

    Parameters
    ----------
    mass : float
        Kilograms (> 0).
    com : (float, float), optional
        Centre of mass in the part's coordinates; None: the part's centroid (given by the
        caller that knows the part, such as :func:`region_payload`).
    gravity : (float, float)
        Gravity's acceleration, m/s^2 (default ``(0, -9.80665)``: y up).
    accel : (float, float)
        Half-widths of the box of the part's linear accelerations, m/s^2
        (``|a_x| <= accel[0]``, ``|a_y| <= accel[1]``), or the semi-axes of their
        ellipse.
    torque : (float, float)
        Range ``(low, high)`` of an external torque on the part, N x the part's unit.
    accel_shape : {"box", "ellipse"}
        The set of accelerations: the box, or the ellipse
        ``(a_x / accel[0])^2 + (a_y / accel[1])^2 <= 1`` (a circle of radius ``r``:
        ``accel=(r, r)``, every direction alike).

    >>> Load(1.0, com=(0, 0), accel=(2, 0)).wrenches().round(3).tolist()
    [[-2.0, -9.807, 0.0], [2.0, -9.807, 0.0]]
    """

    mass: float
    com: tuple[float, float] | None = None
    gravity: tuple[float, float] = (0.0, -G0)
    accel: tuple[float, float] = (0.0, 0.0)
    torque: tuple[float, float] = (0.0, 0.0)
    accel_shape: str = "box"

    def __post_init__(self) -> None:
        if self.accel_shape not in ACCEL_SHAPES:
            raise ValueError(f"accel_shape must be one of {', '.join(ACCEL_SHAPES)}, got "
                             f"{self.accel_shape!r}")
        object.__setattr__(self, "mass", check_scalar(self.mass, "mass", positive=True))
        if self.com is not None:
            object.__setattr__(self, "com", _pair(self.com, "com"))
        object.__setattr__(self, "gravity", _pair(self.gravity, "gravity"))
        object.__setattr__(self, "accel", _pair(self.accel, "accel", nonnegative=True))
        lo, hi = _pair(self.torque, "torque")
        if lo > hi:
            raise ValueError(f"torque must be a range (low, high) with low <= high, got "
                             f"{self.torque!r}")
        object.__setattr__(self, "torque", (lo, hi))

    @property
    def is_polytope(self) -> bool:
        """The load's wrenches are a polytope (a box of accelerations, or an ellipse
        flattened to a segment or a point)."""
        return self.accel_shape == "box" or min(self.accel) == 0.0

    def _affine(self, com: ArrayLike | None) -> tuple[FloatArray, FloatArray]:
        """The wrench at zero acceleration and torque ``w0`` (3,) and the map ``M``
        (3, 2) of the acceleration's unit coordinates: ``w = w0 + M u + (0, 0, tau)``."""
        c = self.com if self.com is not None else com
        if c is None:
            raise ValueError("the load has no centre of mass (com=None): give com, or "
                             "plan it on a part (its centroid)")
        cx, cy = _pair(c, "com")
        m, (gx, gy), (ax, ay) = self.mass, self.gravity, self.accel
        w0 = np.array([m * gx, m * gy, cx * m * gy - cy * m * gx])
        M = np.array([[-m * ax, 0.0], [0.0, -m * ay], [cy * m * ax, -cx * m * ay]])
        return w0, M

    def wrenches(self, com: ArrayLike | None = None, outer: bool = True,
                 sides: int = ELLIPSE_SIDES) -> FloatArray:
        """The vertices ``(fx, fy, tau)`` of the set of wrenches the load applies to the
        part (the fingers supply their opposite), duplicates removed; ``com`` where the
        load has none.  An ellipse of accelerations becomes a polygon of ``sides``
        sides: circumscribed (``outer``: a superset of the load) or inscribed (its
        vertices are wrenches of the load)."""
        w0, M = self._affine(com)
        if self.is_polytope:
            u = np.array(list(itertools.product((-1.0, 1.0), repeat=2)))
        else:
            a = 2 * np.pi * np.arange(sides) / sides
            r = 1.0 / np.cos(np.pi / sides) if outer else 1.0
            u = r * np.c_[np.cos(a), np.sin(a)]
        base = w0 + u @ M.T
        out = [b + [0.0, 0.0, tau] for b in base for tau in self.torque]
        return np.unique(np.round(np.array(out), 12), axis=0)

    def support(self, h: ArrayLike, com: ArrayLike | None = None) -> FloatArray:
        """The support function of the load's wrenches, ``max h . w`` over the set, for
        each row ``h`` (n, 3): in closed form (the box's corners, or the ellipse's
        ``|M^T h|``, plus the torque range's end)."""
        H = np.atleast_2d(np.asarray(h, float))
        w0, M = self._affine(com)
        proj = H @ M                                   # (n, 2)
        spread = np.abs(proj).sum(axis=1) if self.accel_shape == "box" \
            else np.hypot(proj[:, 0], proj[:, 1])
        lo, hi = self.torque
        return cast("FloatArray", H @ w0 + spread + np.maximum(H[:, 2] * lo, H[:, 2] * hi))


@dataclass(frozen=True)
class Payload:
    """What one grasp carries: ``scale`` (the largest multiple of the load resisted
    within the limits; ``inf`` when nothing limits it, 0 when the grasp cannot resist
    it at all); ``forces`` (V, k, 2): the least-peak-force distribution resisting each
    vertex wrench of the load itself (an ellipse of accelerations: at
    :data:`ELLIPSE_SIDES` points on it; ``scale >= 1``; else None); ``peak``: its
    largest normal force."""

    scale: float
    forces: FloatArray | None = None
    peak: float | None = None

    @property
    def holds(self) -> bool:
        """The grasp carries the load (``scale >= 1``)."""
        return self.scale >= 1.0


@dataclass(frozen=True)
class RegionPayload:
    """The scale a plan's regions guarantee: every grasp of them carries ``lower`` times
    the load (certified), and the grasp ``worst`` (one point per finger) carries only
    ``upper`` times it; ``gap = 1 - lower / upper``."""

    lower: float
    upper: float
    worst: FloatArray = field(repr=False)
    boxes: int = 0

    @property
    def gap(self) -> float:
        if not np.isfinite(self.upper) or self.upper <= 0:
            return 0.0 if self.lower == self.upper else 1.0
        return max(0.0, 1.0 - self.lower / self.upper)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``scale`` (certified), ``worst_grasp_scale``, ``gap``, ``boxes``;
        None stands for an infinite scale (no force limit)."""
        def finite(x: float) -> float | None:
            return float(x) if np.isfinite(x) else None
        return {"scale": finite(self.lower), "worst_grasp_scale": finite(self.upper),
                "gap": float(self.gap), "boxes": int(self.boxes)}


def _facet_scale(E: FloatArray, load: Load, com: ArrayLike | None, per: FloatArray, total: float
                 ) -> float | None:
    """The exact largest scale of ``load`` (any convex set with a support function)
    that one grasp resists: the fingers' wrenches within the limits are a polytope
    ``P`` (the image of :func:`_force_vertices`); they must supply the opposite of the
    load, and ``-s W`` is inside ``P`` iff ``s sigma_W(-h) <= b`` on each facet
    ``h . w <= b`` of ``P``.  None where ``P`` is unbounded or flat (the caller then
    solves the program on polygon vertices)."""
    from scipy.spatial import ConvexHull, QhullError

    V = _force_vertices(per, total)
    if V is None:
        return None
    pts = np.einsum("nkj,kjd->nd", V, E)
    unit = np.abs(pts).max(axis=0)                 # columns scaled: N and N x length
    if not np.all(unit > 0):
        return None
    try:
        hull = ConvexHull(pts / unit)
    except QhullError:
        return None
    h = hull.equations[:, :3] / unit               # h . w + d <= 0 inside, in wrenches
    b = np.maximum(-hull.equations[:, 3], 0.0)     # the origin (no force) is in P
    sigma = load.support(-h, com)
    pos = sigma > TOL * np.abs(b).max()
    if not pos.any():                              # pragma: no cover - P is bounded
        return float("inf")
    return float(np.min(b[pos] / sigma[pos]))


def _load_scale(E: FloatArray, load: Load, com: ArrayLike | None, per: FloatArray, total: float,
                upper: bool = False, vertices: FloatArray | None = None) -> float:
    """The largest scale of ``load`` one grasp resists: the program over the load's
    vertices (a polytope; ``vertices``: ``load.wrenches(com)`` when the caller has
    them), the facets of the fingers' polytope (an ellipse, limits given), else the
    program over the ellipse's circumscribed polygon (a lower bound; ``upper``: the
    inscribed one, an upper bound).  Without any limit the scale is 0 or infinite:
    infinite iff some positive scale is resisted with unit limits."""
    if load.is_polytope:
        return _scale(E, load.wrenches(com) if vertices is None else vertices, per, total)
    if not np.isfinite(per).any() and not np.isfinite(total):
        s1 = _facet_scale(E, load, com, np.ones(len(per)), np.inf)
        if s1 is not None:
            return float("inf") if s1 > 0 else 0.0
    s = _facet_scale(E, load, com, per, total)
    if s is not None:
        return s
    return _scale(E, load.wrenches(com, outer=not upper), per, total)


def grasp_payload(points: ArrayLike, normals: ArrayLike, mu: ArrayLike, load: Load,
                  force_limit: ArrayLike | None = None,
                  total_limit: ArrayLike | None = None, com: ArrayLike | None = None) -> Payload:
    """The largest scale of ``load`` one grasp resists within the finger force limits
    (see the module docstring), and the least-peak-force distribution for the load.

    Parameters
    ----------
    points, normals : array_like, shape (k, 2)
        Contact points and *inward* normals (the direction each finger pushes).
    mu : float
        Friction coefficient of every finger (0: frictionless).
    load : Load
    force_limit : float or sequence of k floats, optional
        Largest normal force of each finger, N.
    total_limit : float, optional
        Largest sum of the normal forces, N.
    com : (float, float), optional
        The centre of mass where the load has none.
    """
    if not isinstance(load, Load):
        raise TypeError(f"load must be a fcgrasp Load, got {type(load).__name__}")
    p, n = check_contact_points(points, normals)
    mu_v = check_mu_scalar(mu, "mu")
    per, total = _limits(force_limit, total_limit, len(p))
    # the forces are those of the load's vertices (an ellipse's: points on it)
    W = load.wrenches(com, outer=False)
    edges = _cone_edges(n, np.full(len(p), np.arctan(mu_v)))
    E = _wrench_edges(p, edges)
    s = _load_scale(E, load, com, per, total)
    if s < 1.0:
        return Payload(s)
    res = _program(E, W, per, total, minimize_peak=True)
    if res.status != 0:                           # pragma: no cover - feasible at s >= 1
        return Payload(s)
    c = res.x[1:].reshape(len(W), len(p), 2)
    forces = np.einsum("vkj,kjd->vkd", c, edges)
    return Payload(s, forces, float(res.x[0]))


# ----------------------------------------------------------------------------- regions


@dataclass(frozen=True)
class _Piece:
    """Where one finger may be: a segment ``a + u t``, ``u`` in ``[0, length]``, pushing
    along ``n`` inside a cone of half-angle ``half`` (a vertex: length 0)."""

    a: FloatArray
    t: FloatArray
    length: float
    n: FloatArray
    half: float


def _pieces(region: FloatArray, inward: FloatArray, mu: float) -> list[_Piece]:
    """A region (a polyline along the boundary, with the inward normal of the edge
    under each segment) as segments and the vertices between them."""
    beta = float(np.arctan(mu))
    out = []
    for j in range(len(region) - 1):
        d = region[j + 1] - region[j]
        L = float(np.hypot(*d))
        t = d / L if L > 0 else np.array([-inward[j][1], inward[j][0]])
        out.append(_Piece(region[j], t, L, inward[j], beta))
        if j + 1 < len(region) - 1:               # a vertex the region covers
            a, b = inward[j], inward[j + 1]
            turn = float(np.arccos(np.clip(a @ b, -1.0, 1.0)))
            mid = (a + b) / np.hypot(*(a + b))
            out.append(_Piece(region[j + 1], np.array([-mid[1], mid[0]]), 0.0, mid,
                              beta - 0.5 * turn))
    return out


def _box_scale(rows: list[tuple[FloatArray, FloatArray]], widths: FloatArray,
               W: FloatArray, per: FloatArray, total: float,
               eps: FloatArray | None = None) -> float:
    """The certified scale of a box (the module docstring's lower bound): ``rows`` the
    cone edges' wrenches at its corners, ``widths`` its width along each finger.
    ``eps``: a finger may also sit up to ``eps_i`` along its edge off the corners'
    combination (a parallel jaw's pad corner as the angle turns): its normal force,
    at most ``cbar_i + d_i``, then adds a torque of at most ``eps_i (cbar_i + d_i)``,
    which ``E`` covers too."""
    from scipy.optimize import linprog  # on first use
    from scipy.sparse import coo_matrix

    P, V = len(rows), len(W)
    k = rows[0][0].shape[0]
    # variables: s | per v: cbar (k), d (k), E | per (v, p, sign): coefficients (k, 2)
    head = 1 + V * (2 * k + 1)
    nvar = head + V * P * 2 * 2 * k
    eq: list[tuple[int, int, float]] = []
    ub: list[tuple[int, int, float]] = []
    b_ub: list[float] = []
    n_eq = 0

    def coef(v: int, p: int, sg: int, i: int, j: int) -> int:
        return int(head + (((v * P + p) * 2 + sg) * k + i) * 2 + j)

    for v in range(V):
        cbar, dvar, evar = 1 + v * (2 * k + 1), 1 + v * (2 * k + 1) + k, 1 + v * (2 * k + 1) + 2 * k
        for p, (E, _) in enumerate(rows):
            for sg, sign in enumerate((1.0, -1.0)):
                for r in range(3):
                    for i in range(k):
                        for j in range(2):
                            eq.append((n_eq, coef(v, p, sg, i, j), float(E[i, j, r])))
                    eq.append((n_eq, 0, float(W[v, r])))
                    if r == 2:
                        eq.append((n_eq, evar, sign))
                    n_eq += 1
                row_total = len(b_ub)
                if np.isfinite(total):
                    b_ub.append(total)
                for i in range(k):
                    a, b = coef(v, p, sg, i, 0), coef(v, p, sg, i, 1)
                    r0 = len(b_ub)           # c - cbar <= d and cbar - c <= d
                    ub += [(r0, a, 1.0), (r0, b, 1.0), (r0, cbar + i, -1.0), (r0, dvar + i, -1.0),
                           (r0 + 1, a, -1.0), (r0 + 1, b, -1.0), (r0 + 1, cbar + i, 1.0),
                           (r0 + 1, dvar + i, -1.0)]
                    b_ub += [0.0, 0.0]
                    if np.isfinite(per[i]):
                        ub += [(len(b_ub), a, 1.0), (len(b_ub), b, 1.0)]
                        b_ub.append(float(per[i]))
                    if np.isfinite(total):
                        ub += [(row_total, a, 1.0), (row_total, b, 1.0)]
        r0 = len(b_ub)                      # sum_i w_i d_i (+ eps_i (cbar_i + d_i)) <= E
        ub += [(r0, dvar + i, float(widths[i]) + (0.0 if eps is None else float(eps[i])))
               for i in range(k)] + [(r0, evar, -1.0)]
        if eps is not None:
            ub += [(r0, cbar + i, float(eps[i])) for i in range(k) if eps[i] > 0]
        b_ub.append(0.0)

    def matrix(items: list[tuple[int, int, float]], rows_n: int) -> Any:
        r, c, x = zip(*items, strict=True)
        return coo_matrix((x, (r, c)), shape=(rows_n, nvar)).tocsr()

    cost = np.zeros(nvar)
    cost[0] = -1.0
    res = linprog(cost, A_ub=matrix(ub, len(b_ub)), b_ub=np.array(b_ub),
                  A_eq=matrix(eq, n_eq), b_eq=np.zeros(n_eq), bounds=[(0, None)] * nvar,
                  method="highs")
    if res.status == 3:
        return float("inf")
    return max(0.0, float(-res.fun)) if res.status == 0 else 0.0


def _box_rows(pieces: tuple[_Piece, ...], lo: FloatArray, hi: FloatArray
              ) -> list[tuple[FloatArray, FloatArray]]:
    """The cone edges' wrenches at every corner of a box of positions."""
    n = np.array([q.n for q in pieces])
    E = _cone_edges(n, np.array([max(q.half, 0.0) for q in pieces]))
    rows = []
    for corner in itertools.product(*[(a, b) if b > a else (a,) for a, b in
                                      zip(lo, hi, strict=True)]):
        p = np.array([q.a + u * q.t for q, u in zip(pieces, corner, strict=True)])
        rows.append((_wrench_edges(p, E), p))
    return rows


def region_payload(polygon: Polygon, plan: Any, load: Load, force_limit: ArrayLike | None = None,
                   total_limit: ArrayLike | None = None, gap: float = 0.01, max_boxes: int = 200
                   ) -> RegionPayload:
    """The scale of ``load`` guaranteed over every grasp of a plan's regions (one finger
    anywhere in each region), within the finger force limits: a certified lower bound
    and the worst grasp found, refined by branch and bound (boxes of finger positions,
    the widest split in half) until ``1 - lower / upper <= gap`` or ``max_boxes`` boxes
    were solved (see the module docstring).

    ``polygon``: the part (its centroid is the centre of mass of a load without one);
    ``plan``: a :class:`~fcgrasp.GraspPlan` of point fingers (friction ``plan.mu``;
    gravity's contact, if any, is part of the load instead: its region is a point).
    Each box costs a linear program over its corners (two fingers: about 15 ms; four:
    about 70 ms; an ellipse of accelerations, whose circumscribed polygon has
    :data:`ELLIPSE_SIDES` vertices instead of a box's four, about ten times more);
    four frictionless fingers converge slowest (their corners' forces
    are determined, so the bound needs small boxes): ``upper`` and ``gap`` say how far
    the certified ``lower`` is from the worst grasp found.
    """
    from .plans import check_point_plan

    polygon = check_point_plan(polygon, plan)
    if not isinstance(load, Load):
        raise TypeError(f"load must be a fcgrasp Load, got {type(load).__name__}")
    gap_v = check_scalar(gap, "gap", nonnegative=True)
    mu = float(plan.mu) if plan.contact_type != "frictionless" else 0.0
    fingers = [(np.asarray(r, float), e) for r, e in
               zip(plan.regions, plan.region_edges, strict=True)
               if len(r) > 1 or np.hypot(*(np.asarray(r[0]) - polygon.centroid)) > TOL]
    per, total = _limits(force_limit, total_limit, len(fingers))
    W = load.wrenches(polygon.centroid)            # an ellipse's circumscribed polygon
    choices = [_pieces(r, -polygon.normals[list(e)], mu) for r, e in fingers]

    best_upper, worst = np.inf, np.zeros((len(fingers), 2))
    heap: list[tuple[float, int, tuple[_Piece, ...], FloatArray, FloatArray]] = []
    count = 0
    import heapq

    def solve(pieces: tuple[_Piece, ...], lo: FloatArray, hi: FloatArray) -> None:
        nonlocal best_upper, worst, count
        count += 1
        rows = _box_rows(pieces, lo, hi)
        corners = []
        for E, p in rows:                          # each corner is a grasp: an upper bound
            corners.append(_load_scale(E, load, polygon.centroid, per, total, upper=True,
                                       vertices=W))
            if corners[-1] < best_upper:
                best_upper, worst = corners[-1], p
        if len(rows) > 1:
            low = _box_scale(rows, hi - lo, W, per, total)
        else:                                      # one grasp: its own scale, certified
            low = corners[0] if load.is_polytope else _load_scale(
                rows[0][0], load, polygon.centroid, per, total)
        heapq.heappush(heap, (low, count, pieces, lo, hi))

    for pieces in itertools.product(*choices):
        solve(pieces, np.zeros(len(pieces)), np.array([q.length for q in pieces]))
    while heap:
        low, _, pieces, lo, hi = heap[0]
        if low >= best_upper * (1 - gap_v) or count >= max_boxes or low == np.inf:
            break
        heapq.heappop(heap)
        j = int(np.argmax(hi - lo))
        if hi[j] - lo[j] <= 0:                     # a point: its bound is exact
            heapq.heappush(heap, (best_upper, count, pieces, lo, hi))
            break
        mid = 0.5 * (lo[j] + hi[j])
        for a, b in ((lo[j], mid), (mid, hi[j])):
            l2, h2 = lo.copy(), hi.copy()
            l2[j], h2[j] = a, b
            solve(pieces, l2, h2)
    lower = min(min(h[0] for h in heap), best_upper) if heap else best_upper
    return RegionPayload(float(lower), float(best_upper), worst, count)
