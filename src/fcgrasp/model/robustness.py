r"""How likely a two-finger plan is to hold when the fingers land off target.

Each finger lands with a Gaussian error of standard deviation ``placement_sigma`` (the
part's units) *along the boundary* around its region's centre (the plan's representative
contact), independently; it may land on a neighbouring edge.  The grasp holds when the
two contacts are force closure with friction ``mu`` (theorem 6.3: the chord between them
inside both friction cones, squeezing or expanding; no margin).

**Exact.**  On a pair of edges, with the fingers at arc positions ``u1``, ``u2`` along
them, the chord is affine in ``(u1, u2)`` and each cone condition is two half-planes: the
force-closure set of the pair is a convex polygon in the two positions (section 6), one
per mode.  The probability is the sum over the edge pairs within eight standard
deviations of the two centres (the rest weighs less than ``1e-15``) of the Gaussian's
integral over those polygons: an integral along ``u1`` of the density times the
difference of two normal distribution functions, piecewise smooth between the
polygon's vertices, each piece integrated by Gauss-Legendre on steps of half a
deviation (error far below ``1e-13``).  With ``mu_range``,
friction uniform in the range: the average over ``mu``, integrated the same way.

Tested against a Monte Carlo estimate (``friction_pair_closure`` on a million sampled
landings, no code shared) within its confidence interval.

>>> import fcgrasp as fc
>>> part = fc.read_part("demo:quad")
>>> best = fc.plan(part, fingers=2, mu=0.4, top=1)[0]
>>> p = placement_probability(part, best, placement_sigma=0.5)
>>> 0.9 < p <= 1.0
True
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core._checks import FloatArray, check_mu_scalar, check_scalar
from ..core.tolerances import LP_TOL, TOL

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from .polygon import Polygon


__all__ = ["placement_probability", "pair_probability", "pose_probability", "Estimate",
           "robustness"]

#: Standard deviations of placement error beyond which an edge is not read.
REACH = 8.0


def _clip(poly: list[tuple[float, float]], a: float, b: float, c: float
          ) -> list[tuple[float, float]]:
    """The part of a convex polygon where ``a x + b y + c > 0`` (Sutherland-Hodgman)."""
    out: list[tuple[float, float]] = []
    for k in range(len(poly)):
        p, q = poly[k], poly[(k + 1) % len(poly)]
        fp, fq = a * p[0] + b * p[1] + c, a * q[0] + b * q[1] + c
        if fp > 0:
            out.append(p)
        if (fp > 0) != (fq > 0):
            t = fp / (fp - fq)
            out.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
    return out


def _phi_cdf(x: float) -> float:
    return 0.5 * math.erfc(-x / math.sqrt(2.0))


#: Gauss-Legendre nodes and weights on [-1, 1] of the integrals along ``u1``.
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(24)


def _gauss_over(poly: list[tuple[float, float]], sigma: float) -> float:
    """Integral of the density of two independent N(0, sigma^2) over a convex polygon:
    along ``x`` between consecutive vertices the polygon spans ``lo(x) < y < hi(x)``,
    both affine, and the integrand ``phi(x) (Phi(hi(x)) - Phi(lo(x)))`` is analytic;
    each piece is cut into steps of at most half a deviation, each integrated by
    24-point Gauss-Legendre (error far below 1e-13)."""
    from scipy.special import ndtr  # on first use

    if len(poly) < 3:
        return 0.0
    pts = np.array(poly)
    n = len(pts)
    xs = np.unique(pts[:, 0])
    total = 0.0
    cut = (REACH + 2) * sigma            # the density is negligible beyond
    for x0, x1 in zip(xs[:-1], xs[1:], strict=True):
        a, b = max(x0, -cut), min(x1, cut)
        if b <= a:
            continue
        xm = 0.5 * (x0 + x1)
        lines = []
        for k in range(n):
            p, q = pts[k], pts[(k + 1) % n]
            if min(p[0], q[0]) <= xm <= max(p[0], q[0]) and p[0] != q[0]:
                slope = (q[1] - p[1]) / (q[0] - p[0])
                lines.append((slope, p[1] - slope * p[0]))
        if len(lines) < 2:
            continue
        lines.sort(key=lambda ln: ln[0] * xm + ln[1])
        (s0, c0), (s1, c1) = lines[0], lines[-1]
        steps = max(1, int(math.ceil((b - a) / (0.5 * sigma))))
        edges = np.linspace(a, b, steps + 1)
        mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
        x = (mid[:, None] + half[:, None] * _NODES[None, :]).ravel()
        w = (half[:, None] * _WEIGHTS[None, :]).ravel()
        dens = np.exp(-0.5 * (x / sigma) ** 2) / (sigma * math.sqrt(2 * math.pi))
        total += float(np.sum(w * dens * (ndtr((s1 * x + c1) / sigma)
                                          - ndtr((s0 * x + c0) / sigma))))
    return total


def _cone_halfplanes(f: FloatArray, beta: float) -> list[tuple[FloatArray, float]]:
    """``d`` strictly within ``beta`` of the direction ``f``: ``g . d > 0`` for each
    returned normal ``g`` (two half-planes, beta < pi / 2)."""
    c, s = math.cos(beta), math.sin(beta)
    lo = np.array([c * f[0] + s * f[1], -s * f[0] + c * f[1]])     # f turned by -beta
    hi = np.array([c * f[0] - s * f[1], s * f[0] + c * f[1]])      # f turned by +beta
    # cross(lo, d) > 0 and cross(d, hi) > 0, as dot products with normals
    return [(np.array([-lo[1], lo[0]]), 0.0), (np.array([hi[1], -hi[0]]), 0.0)]


def pair_probability(a1: ArrayLike, t1: ArrayLike, f1: ArrayLike, lo1: float, hi1: float,
                     a2: ArrayLike, t2: ArrayLike,
                     f2: ArrayLike, lo2: float, hi2: float, mu: float, sigma: float) -> float:
    """Probability that fingers at ``a_i + s_i t_i`` (``s_i ~ N(0, sigma^2)``), kept
    where ``lo_i < s_i < hi_i`` (their edge), pushing along ``f_i`` with friction ``mu``,
    are force closure (squeezing or expanding)."""
    a1, t1, f1, a2, t2, f2 = (np.asarray(v, float) for v in (a1, t1, f1, a2, t2, f2))
    beta = math.atan(mu)
    if beta <= 0:
        return 0.0
    rect = [(lo1, lo2), (hi1, lo2), (hi1, hi2), (lo1, hi2)]
    total = 0.0
    for sign in (1.0, -1.0):            # squeeze: Q - P within beta of f1, P - Q of f2
        poly = rect
        # d = (a2 - a1) + s2 t2 - s1 t1
        for f, flip in ((f1, sign), (f2, -sign)):
            for g, _ in _cone_halfplanes(f, beta):
                g = flip * g
                # g . d > 0  <=>  -(g.t1) s1 + (g.t2) s2 + g.(a2 - a1) > 0
                poly = _clip(poly, -float(g @ t1), float(g @ t2), float(g @ (a2 - a1)))
                if not poly:
                    break
            if not poly:
                break
        total += _gauss_over(poly, sigma)
    return total


def _ring_walk(polygon: Polygon, edge: int, point: FloatArray, sigma: float
               ) -> list[tuple[int, float, float]]:
    """The edges of ``edge``'s ring within REACH deviations of ``point`` along it:
    ``(edge, lo, hi)`` with the landing offset ``s`` on that edge for ``lo < s < hi``
    (offsets from ``point`` along the boundary, measured from the start of each edge)."""
    ring = np.flatnonzero(polygon.rings == polygon.rings[edge])
    L = polygon.lengths[ring]
    pos = int(np.flatnonzero(ring == edge)[0])
    start = float(np.hypot(*(point - polygon.starts[edge])))
    reach = REACH * sigma
    out = []
    # forward from the point, then backward (an edge met both ways round is two
    # landing ranges of the offset: both count)
    acc, j = -start, pos
    while acc < reach:
        out.append((int(ring[j]), acc, acc + float(L[j])))
        acc += float(L[j])
        j = (j + 1) % len(ring)
    acc, j = -start, pos
    while acc > -reach:
        j = (j - 1) % len(ring)
        acc -= float(L[j])
        out.append((int(ring[j]), acc, acc + float(L[j])))
    return [(e, lo, hi) for e, lo, hi in out if hi > -reach and lo < reach]


def placement_probability(polygon: Polygon, plan: Any, placement_sigma: ArrayLike | None,
                          mu_range: Sequence[float] | None = None,
                          mu: ArrayLike | None = None) -> float:
    """Probability that a two-finger plan holds when each finger lands with a Gaussian
    error of ``placement_sigma`` along the boundary around its representative contact
    (see the module docstring); ``mu_range=(low, high)``: friction uniform in it;
    ``mu``: friction known but other than the plan's (the plan's otherwise)."""
    from .plans import GraspPlan
    from .polygon import check_polygon

    polygon = check_polygon(polygon)
    if not isinstance(plan, GraspPlan) or len(plan.edges) != 2 \
            or plan.contact_type != "friction":
        raise ValueError(f"plan must be a two-finger plan with friction, got "
                         f"{type(plan).__name__} with {len(getattr(plan, 'edges', ()))} "
                         f"fingers")
    sigma = check_scalar(placement_sigma, "placement_sigma", positive=True)
    per_ring = [float(polygon.lengths[polygon.rings == polygon.rings[e]].sum())
                for e in plan.edges]
    if REACH * sigma >= 0.5 * min(per_ring):
        raise ValueError(f"placement_sigma must be below 1/16 of the ring's perimeter "
                         f"({min(per_ring) / 16:g}), got {placement_sigma!r}")
    walks = [_ring_walk(polygon, int(e), np.asarray(c, float), sigma)
             for e, c in zip(plan.edges, plan.contacts, strict=True)]

    def at(mu: float) -> float:
        total = 0.0
        for e1, lo1, hi1 in walks[0]:
            for e2, lo2, hi2 in walks[1]:
                if e1 == e2:
                    continue
                total += pair_probability(
                    polygon.starts[e1] - lo1 * polygon.tangents[e1], polygon.tangents[e1],
                    -polygon.normals[e1], lo1, hi1,
                    polygon.starts[e2] - lo2 * polygon.tangents[e2], polygon.tangents[e2],
                    -polygon.normals[e2], lo2, hi2, mu, sigma)
        return min(1.0, total)

    if mu_range is None:
        return at(float(plan.mu) if mu is None else check_mu_scalar(mu, "mu"))
    lo, hi = (check_mu_scalar(m, "mu_range") for m in mu_range)
    if not lo < hi:
        raise ValueError(f"mu_range must be (low, high) with low < high, got {mu_range!r}")
    from scipy.integrate import quad

    return float(quad(at, lo, hi, epsabs=LP_TOL, epsrel=TOL, limit=50)[0] / (hi - lo))


# ------------------------------------------------------------------ pose error (QMC)

@dataclass(frozen=True)
class Estimate:
    """A probability estimated by randomized quasi-Monte Carlo: ``probability`` the mean
    over ``replicas`` independent scramblings of a Sobol sequence (``samples`` points in
    all), ``error`` the half-width of its 99 % confidence interval (Student's t over the
    replicas' means)."""

    probability: float
    error: float
    samples: int
    replicas: int

    def to_dict(self) -> dict[str, Any]:
        return {"probability": round(self.probability, 12), "error": round(self.error, 12),
                "samples": self.samples, "replicas": self.replicas}


def _pose_sigmas(pose_sigma: ArrayLike) -> tuple[float, float, float]:
    """``pose_sigma``: a distance (x and y) or ``(sx, sy, s_theta_deg)``."""
    if np.ndim(pose_sigma) == 0:
        s = check_scalar(pose_sigma, "pose_sigma", nonnegative=True)
        out = (s, s, 0.0)
    else:
        arr = np.asarray(pose_sigma, dtype=float) if np.size(pose_sigma) == 3 else None
        if arr is None or not np.all(np.isfinite(arr)) or np.any(arr < 0):
            raise ValueError(f"pose_sigma must be a distance or (sx, sy, s_theta_deg), each "
                             f">= 0, got {pose_sigma!r}")
        out = (float(arr[0]), float(arr[1]), math.radians(float(arr[2])))
    if not any(out):
        raise ValueError(f"pose_sigma must have a deviation > 0, got {pose_sigma!r}")
    return out


def _land(polygon: Polygon, origin: FloatArray, direction: FloatArray
          ) -> tuple[FloatArray, np.ndarray]:
    """Where rays (origin, direction: (S, 2)) first enter the part's material, and the
    edge they enter by (-1: the ray misses, or starts inside the material)."""
    a, b = polygon.starts, polygon.ends
    e = b - a                                                    # (E, 2)
    rel = a[None] - origin[:, None]                              # (S, E, 2)
    den = direction[:, None, 0] * e[None, :, 1] - direction[:, None, 1] * e[None, :, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (rel[..., 0] * e[None, :, 1] - rel[..., 1] * e[None, :, 0]) / den
        s = (rel[..., 0] * direction[:, None, 1] - rel[..., 1] * direction[:, None, 0]) / den
    hit = (den != 0) & (t >= 0) & (s >= 0) & (s <= 1)
    t = np.where(hit, t, np.inf)
    first = np.argmin(t, axis=1)
    tmin = t[np.arange(len(t)), first]
    # entering: the ray runs against the outward normal of the edge it meets first
    entering = np.einsum("ij,ij->i", direction, polygon.normals[first]) < 0
    edge = np.where(np.isfinite(tmin) & entering, first, -1)
    return origin + np.where(np.isfinite(tmin), tmin, 0.0)[:, None] * direction, edge


def _slide(polygon: Polygon, point: FloatArray, edge: np.ndarray, shift: FloatArray
           ) -> tuple[FloatArray, np.ndarray]:
    """Points moved by ``shift`` (arc length, along the edges' direction) round their
    rings from ``point`` on ``edge``."""
    out, new = point.copy(), edge.copy()
    for r in np.unique(polygon.rings[edge[edge >= 0]]):
        ring = np.flatnonzero(polygon.rings == r)
        cum = np.concatenate([[0.0], np.cumsum(polygon.lengths[ring])])
        on = np.flatnonzero((edge >= 0) & (polygon.rings[np.maximum(edge, 0)] == r))
        pos = np.searchsorted(ring, edge[on])
        along = np.einsum("ij,ij->i", point[on] - polygon.starts[edge[on]],
                          polygon.tangents[edge[on]])
        s = np.mod(cum[pos] + along + shift[on], cum[-1])
        j = np.clip(np.searchsorted(cum, s, side="right") - 1, 0, len(ring) - 1)
        new[on] = ring[j]
        out[on] = polygon.starts[ring[j]] + (s - cum[j])[:, None] * polygon.tangents[ring[j]]
    return out, new


def _closure(polygon: Polygon, points: FloatArray, edges: np.ndarray, mu: FloatArray
             ) -> np.ndarray:
    """Force closure of grasps (S, k) of point contacts at ``points`` (S, k, 2) on
    ``edges``, friction ``mu`` (S,) (0: frictionless): the friction cones' edges as
    wrenches about the centroid, lengths in the part's size (theorem 6.1)."""
    from ..core.closure import is_force_closure
    from ..core.contacts import friction_cone_edges

    ok = np.all(edges >= 0, axis=1)
    n = polygon.normals[np.maximum(edges, 0)]                    # (S, k, 2) outward
    r = (points - polygon.centroid) / polygon.size
    if np.all(mu == 0):
        forces = -n[:, :, None]                                  # (S, k, 1, 2)
    else:
        forces = friction_cone_edges(n, mu[:, None])             # (S, k, 2, 2)
    rr = np.broadcast_to(r[:, :, None], forces.shape)
    tau = rr[..., 0] * forces[..., 1] - rr[..., 1] * forces[..., 0]
    w = np.concatenate([forces, tau[..., None]], axis=-1).reshape(len(points), -1, 3)
    closed: np.ndarray = ok & is_force_closure(w)
    return closed


def pose_probability(polygon: Polygon, plan: Any, pose_sigma: ArrayLike,
                     placement_sigma: ArrayLike | None = None,
                     mu_range: Sequence[float] | None = None, mu: ArrayLike | None = None,
                     samples: int = 8192, replicas: int = 16, seed: int = 0) -> Estimate:
    """Probability that a plan's grasp holds when the part sits with a Gaussian pose
    error: ``pose_sigma`` a distance (x and y) or ``(sx, sy, s_theta_deg)``,
    the rotation about the part's centroid.  Each finger closes along its approach line
    (through its representative contact, against the outward normal there, from
    ``6`` deviations out) and lands where that line first enters the displaced part
    (a finger that misses, or starts inside the material, fails the grasp); then, with
    ``placement_sigma``, it slides by a Gaussian error along the boundary; friction is
    the plan's, ``mu``, or uniform in ``mu_range``.  The grasp holds when the landed
    contacts are force closure (theorem 6.1 on their friction cones' edges; no margin).

    No closed form: randomized quasi-Monte Carlo (scrambled Sobol points, scipy's
    ``qmc.Sobol``) over the pose, placement and friction, ``replicas`` independent
    scramblings of ``samples // replicas`` points each; the :class:`Estimate` carries
    the 99 % confidence half-width.  Plans of point fingers (two or three with friction,
    three or four frictionless; not with gravity).

    >>> import fcgrasp as fc
    >>> part = fc.read_part("demo:quad")
    >>> best = fc.plan(part, fingers=2, mu=0.4, top=1)[0]
    >>> est = pose_probability(part, best, pose_sigma=(0.5, 0.5, 1.0))
    >>> 0.9 < est.probability <= 1.0 and est.error < 0.01
    True
    """
    from scipy.special import ndtri as normal_ppf
    from scipy.stats import qmc
    from scipy.stats import t as student

    from .plans import check_point_plan

    polygon = check_point_plan(polygon, plan, no_gravity="a pose error moves the load too")
    sx, sy, st = _pose_sigmas(pose_sigma)
    sp = 0.0 if placement_sigma is None else \
        check_scalar(placement_sigma, "placement_sigma", positive=True)
    if mu_range is not None:
        lo, hi = (check_mu_scalar(m, "mu_range") for m in mu_range)
        if not lo < hi:
            raise ValueError(f"mu_range must be (low, high) with low < high, got "
                             f"{mu_range!r}")
    else:
        lo = hi = float(plan.mu) if mu is None else check_mu_scalar(mu, "mu")
    if not isinstance(samples, int | np.integer) or samples < 2 * replicas:
        raise ValueError(f"samples must be an integer >= 2 * replicas, got {samples!r}")
    if not isinstance(replicas, int | np.integer) or replicas < 2:
        raise ValueError(f"replicas must be an integer >= 2, got {replicas!r}")
    k = plan.fingers
    contacts = np.asarray(plan.contacts, float)
    normals = np.asarray(plan.normals, float)
    normals = normals / np.hypot(normals[:, 0], normals[:, 1])[:, None]
    cen = np.asarray(polygon.centroid, float)
    reach = float(np.max(np.hypot(*(contacts - cen).T)))
    standoff = 6.0 * (math.hypot(sx, sy) + st * reach + sp)
    n_per = 1 << max(1, int(math.ceil(math.log2(samples / replicas))))
    dims = 3 + k + 1
    means = []
    for rep in range(replicas):
        u = qmc.Sobol(dims, scramble=True, seed=np.random.default_rng([seed, rep])
                      ).random(n_per)
        eps = float(np.finfo(float).eps)          # a point at 0 or 1 maps to -inf, inf
        z = normal_ppf(np.clip(u[:, :3 + k], eps, 1 - eps))
        dx, dy, th = z[:, 0] * sx, z[:, 1] * sy, z[:, 2] * st
        mus = lo + (hi - lo) * u[:, -1]
        c, s = np.cos(th), np.sin(th)
        pts = np.empty((n_per, k, 2))
        eds = np.empty((n_per, k), dtype=np.int64)
        for i in range(k):
            # the finger's ray in the part's frame: undo the pose (x -> R(x - cen) + cen + d)
            o = contacts[i] + standoff * normals[i] - cen - np.c_[dx, dy]
            o = np.c_[c * o[:, 0] + s * o[:, 1], -s * o[:, 0] + c * o[:, 1]] + cen
            d = -normals[i]
            d = np.c_[c * d[0] + s * d[1], -s * d[0] + c * d[1]]
            p, e = _land(polygon, o, d)
            if sp > 0:
                p, e = _slide(polygon, p, e, z[:, 3 + i] * sp)
            pts[:, i], eds[:, i] = p, e
        means.append(float(np.mean(_closure(polygon, pts, eds, mus))))
    m = float(np.mean(means))
    half = float(student.ppf(0.995, replicas - 1) * np.std(means, ddof=1) / math.sqrt(replicas))
    return Estimate(m, half, n_per * replicas, replicas)


def robustness(polygon: Polygon, plan: Any, placement_sigma: ArrayLike | None = None,
               pose_sigma: ArrayLike | None = None,
               mu_range: Sequence[float] | None = None, mu: ArrayLike | None = None,
               samples: int = 8192,
               replicas: int = 16, seed: int = 0) -> Estimate:
    """The probability that a plan's grasp holds under the given uncertainty
    (``fc.robustness``): each finger landing with a Gaussian error of ``placement_sigma``
    along the boundary around its region's centre, the part's pose off by a Gaussian of
    ``pose_sigma`` (a distance, or ``(sx, sy, s_theta_deg)``), friction uniform in
    ``mu_range`` (or ``mu`` instead of the plan's).  Two fingers without a pose error:
    exact (:func:`placement_probability`, to 1e-9; ``error`` 0, no samples); otherwise
    randomized quasi-Monte Carlo with its 99 % interval (:func:`pose_probability`).

    >>> import fcgrasp as fc
    >>> part = fc.read_part("demo:quad")
    >>> best = fc.plan(part, fingers=2, mu=0.4, top=1)[0]
    >>> r = robustness(part, best, placement_sigma=0.5, mu_range=(0.3, 0.5))
    >>> r.probability == placement_probability(part, best, 0.5, mu_range=(0.3, 0.5))
    True
    """
    if placement_sigma is None and pose_sigma is None:
        raise ValueError("robustness needs an uncertainty: placement_sigma (along the "
                         "boundary) or pose_sigma (the part's pose), got neither")
    if pose_sigma is None:
        p = placement_probability(polygon, plan, placement_sigma, mu_range=mu_range, mu=mu)
        return Estimate(float(p), 0.0, 0, 0)
    return pose_probability(polygon, plan, pose_sigma, placement_sigma=placement_sigma,
                            mu_range=mu_range, mu=mu, samples=samples, replicas=replicas,
                            seed=seed)
