"""The parallel jaw's pose model: what the pads touch at a pose and whether it holds
(theorem 6.3 per pose), on batches of poses; the grid's constants."""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...core._angles import shrunk_half_angle, wrap_positive
from ...core._checks import FloatArray, check_mu_scalar, check_scalar
from ...core.tolerances import CONTACT_TOL, ROUND_TOL, SLICE_TOL, TOL
from ...model.polygon import Polygon, check_polygon
from ...model.regions import DEFAULT_MARGIN_DEG
from . import _kernels

#: Angular step of the pose grid (degrees).
THETA_STEP_DEG = 0.5
#: Offsets sampled across the part (its diameter plus a pad width).
OFFSET_STEPS = 160
#: The found box is checked on a grid this many times finer (and shrunk until it holds).
CHECK_DENSITY = 4
#: Sub-boxes :func:`certify_box` may use to prove a planned box (``jaw_plans``); the box
#: as found gets an eighth of them (found on the grid, it usually touches the holding
#: set's boundary: refused at once by a failing pose, or proved one step smaller).
CERTIFY_BOXES = 4000
#: Grid steps a planned box may be shrunk by until it is proved.
CERTIFY_SHRINKS = 2
#: At most this many contact features per pad are compared (more: not held, safely).
MAX_CONTACTS = _kernels.K_MAX
#: Edges within this many contact tolerances of a box's strips are kept as near it.
NEAR_STRIP = 10
#: Poses evaluated at a time (memory: a few arrays of this many rows times the edges).
POSE_BATCH = 20000



def _sin_range(a: Any, b: Any, t0: Any, t1: Any
               ) -> tuple[FloatArray, FloatArray]:
    """Exact range of ``a cos(t) + b sin(t)`` over ``t in [t0, t1]`` (``t1 - t0 < 2 pi``),
    elementwise: the ends, and the extremes ``+-hypot(a, b)`` where their angle falls
    inside."""
    v0 = a * np.cos(t0) + b * np.sin(t0)
    v1 = a * np.cos(t1) + b * np.sin(t1)
    r = np.hypot(a, b)
    phi = np.arctan2(b, a)                              # the maximum is at t = phi
    has_max = wrap_positive(phi - t0) <= t1 - t0
    has_min = wrap_positive(phi + np.pi - t0) <= t1 - t0
    return (np.where(has_min, -r, np.minimum(v0, v1)),
            np.where(has_max, r, np.maximum(v0, v1)))


@dataclass(frozen=True)
class JawParameters:
    """The parameters of a parallel-jaw gripper, checked, as the pose model reads them:
    its stroke ``(min_opening, max_opening)``, the width of its flat pads and their
    friction coefficient ``mu`` (lengths in the part's units); ``certify``: whether its
    boxes are proved.  :class:`~fcgrasp.grippers.jaw.ParallelJaw` is the gripper.

    >>> JawParameters(stroke=(10, 50), pad_width=12, mu=0.4).stroke
    (10.0, 50.0)
    """

    stroke: tuple[float, float]
    pad_width: float
    mu: float
    #: prove every box (:func:`certify_box`); False: boxes verified on a fine grid only
    certify: bool = True

    def __post_init__(self) -> None:
        if not isinstance(self.certify, bool):
            raise TypeError(f"certify must be a bool, got {self.certify!r}")
        if isinstance(self.stroke, (str, bytes)) or np.ndim(self.stroke) != 1 \
                or len(self.stroke) != 2:
            raise ValueError(f"stroke must be (min_opening, max_opening), got {self.stroke!r}")
        lo = check_scalar(self.stroke[0], "stroke[0]", nonnegative=True)
        hi = check_scalar(self.stroke[1], "stroke[1]", positive=True)
        if hi < lo:
            raise ValueError(f"stroke must have min_opening <= max_opening, got "
                             f"{self.stroke!r}")
        object.__setattr__(self, "stroke", (lo, hi))
        object.__setattr__(self, "pad_width",
                           check_scalar(self.pad_width, "pad_width", positive=True))
        mu = check_mu_scalar(self.mu, "mu")
        if mu <= 0:
            raise ValueError(f"a parallel jaw holds by friction: mu must be > 0, got "
                             f"{self.mu!r}")
        object.__setattr__(self, "mu", mu)


@dataclass
class PoseContacts:
    """What the pads touch at a batch of poses (see :func:`jaw_poses`).

    ``top``, ``bottom`` (P,): the pads' stops (``x . u`` relative to the centroid);
    ``opening`` (P,); ``kind_a``, ``kind_b`` (P,): 0 nothing (or too many features),
    1 vertices and edges parallel to the pad, 2 a pad corner on an edge among them;
    ``lat_a``, ``lat_b`` (P, K, 2): lateral intervals of the contact features (NaN
    where fewer); ``psi_a``, ``psi_b`` (P, K): the angle of each feature's contact force
    from its pad's (0 but on a pad corner);
    ``holds`` (P,): force closure and the opening within the stroke;
    ``edge_a``, ``edge_b`` (P, K): the part's edge of each contact feature (a vertex
    appears as each of its edges that reaches the stop; -1 where fewer).
    """

    top: FloatArray
    bottom: FloatArray
    opening: FloatArray
    kind_a: np.ndarray
    kind_b: np.ndarray
    lat_a: FloatArray
    lat_b: FloatArray
    psi_a: FloatArray
    psi_b: FloatArray
    holds: np.ndarray
    edge_a: np.ndarray
    edge_b: np.ndarray


def _pad(y_a: FloatArray, y_b: FloatArray, x_a: FloatArray, x_b: FloatArray,
         s0: FloatArray, s1: FloatArray, sign: float, tol: float,
         force: tuple[FloatArray, FloatArray], use: np.ndarray | None = None
         ) -> tuple[FloatArray, np.ndarray, FloatArray, FloatArray, np.ndarray]:
    """One pad: the extreme of ``sign * y`` over the edges clipped to the strip
    ``[s0, s1]`` (arrays (P, E) of edge ends, (P, 1) strip sides).  Returns the stop
    (P,), whether it touches anything (P,), the contact features' lateral intervals
    (P, K, 2), the angle of each feature's contact force from the pad's (P, K):
    0 on a vertex or an edge parallel to the pad, the edge's (``arctan2(*force)``, each
    (P, E)) where the pad's corner touches an edge, and the column of each feature's
    edge (P, K; -1 where fewer).  ``use`` (P, E): the edges the pad can meet (default
    all).  Only the extreme is taken over every edge; the features are described from
    the (at most :data:`MAX_CONTACTS`) touching columns gathered: K = MAX_CONTACTS
    always (NaN and -1 where fewer), whatever the number of edges."""
    ya, yb = sign * y_a, sign * y_b
    lo_x = np.minimum(x_a, x_b)
    hi_x = np.maximum(x_a, x_b)
    inside = (hi_x >= s0) & (lo_x <= s1)
    if use is not None:
        inside &= use
    cl_lo = np.clip(lo_x, s0, s1)
    cl_hi = np.clip(hi_x, s0, s1)
    dx = x_b - x_a
    flat_lat = np.abs(dx) <= tol
    with np.errstate(divide="ignore", invalid="ignore"):
        slope = np.where(flat_lat, 0.0, (yb - ya) / np.where(flat_lat, 1.0, dx))
    # heights at the clipped ends (an edge along u: its higher end)
    h_lo = np.where(flat_lat, np.maximum(ya, yb), ya + (cl_lo - x_a) * slope)
    h_hi = np.where(flat_lat, np.maximum(ya, yb), ya + (cl_hi - x_a) * slope)
    h_lo = np.where(inside, h_lo, -np.inf)
    h_hi = np.where(inside, h_hi, -np.inf)
    stop = np.maximum(h_lo.max(axis=1), h_hi.max(axis=1))
    at_lo = h_lo >= stop[:, None] - tol
    at_hi = h_hi >= stop[:, None] - tol
    touch = (at_lo | at_hi) & np.isfinite(stop)[:, None]    # nothing in the strip: none
    # the touching columns in order, at most MAX_CONTACTS (the k-th where the running
    # count of touching columns first reaches k)
    count = np.cumsum(touch, axis=1)
    order = np.stack([np.argmax(touch & (count == k + 1), axis=1)
                      for k in range(MAX_CONTACTS)], axis=1)
    tk = count[:, -1:] > np.arange(MAX_CONTACTS)
    rows = np.arange(len(stop))[:, None]

    def g(a: Any) -> Any:
        return a[rows, order]

    a_lo, a_hi = g(at_lo), g(at_hi)
    g_lo, g_hi = g(cl_lo), g(cl_hi)
    level = np.abs(g(ya) - g(yb)) <= tol                 # an edge parallel to the pad
    # a clipped end strictly inside the edge's lateral span is where the strip's side
    # cuts the edge: the pad's corner touches the edge there, unless the edge is
    # parallel to the pad (then the whole clipped edge touches the pad's face)
    along = g(flat_lat)
    cut_lo = (g_lo > g(lo_x) + tol) & ~level & ~along
    cut_hi = (g_hi < g(hi_x) - tol) & ~level & ~along
    corner = (a_lo & cut_lo) | (a_hi & cut_hi)
    both = level & a_lo & a_hi
    lat_lo = np.where(both, g_lo, np.where(a_lo, g_lo, g_hi))
    lat_hi = np.where(both, g_hi, np.where(a_hi, g_hi, g_lo))
    psi = np.where(corner, np.arctan2(g(force[0]), g(force[1])), 0.0)
    lat = np.stack([np.where(tk, lat_lo, np.nan), np.where(tk, lat_hi, np.nan)], axis=-1)
    ok = np.isfinite(stop) & (count[:, -1] <= MAX_CONTACTS)
    return (sign * stop, ok, lat, np.where(tk, psi, np.nan), np.where(tk, order, -1))


def convex_holes(polygon: Polygon) -> list[int]:
    """The convex holes of a part (in one, the pads' stops do not depend on where the
    closed jaws are put in; internal grips are planned in every hole)."""
    import shapely

    out = []
    for k, h in enumerate(polygon.holes):
        ring = shapely.Polygon(h)
        if ring.convex_hull.area <= ring.area * (1 + TOL):
            out.append(k)
    return out


def _check_jaw_args(polygon: Any, jaw: Any, margin: Any) -> float:
    """The common arguments checked; the margin as a float."""
    polygon = check_polygon(polygon)
    if not isinstance(jaw, JawParameters):
        raise TypeError(f"jaw must be a ParallelJaw, got {type(jaw).__name__}")
    return check_scalar(margin, "margin", nonnegative=True)


def _grip_edges(polygon: Polygon, hole: Any) -> np.ndarray:
    """The edges a grip meets: those of the outer ring (external, ``hole=None``: a
    hole's material is never a pad's extreme, the topmost point of the part on every
    line along ``u`` being on the outer ring) or those of a hole."""
    if hole is None:
        return np.asarray(polygon.rings == 0)
    if isinstance(hole, bool) or not isinstance(hole, (int, np.integer)) \
            or not 0 <= int(hole) < len(polygon.holes):
        raise ValueError(f"hole must be the index of a hole of the part (internal grips), "
                         f"got {hole!r}; the part has {len(polygon.holes)} holes")
    return np.asarray(polygon.rings == int(hole) + 1)


def insertion_point(polygon: Polygon, hole: int) -> FloatArray:
    """Where the closed jaws go into the hole ``hole`` for an internal grip: the hole's
    pole of inaccessibility (shapely's ``polylabel``: the point inside it farthest from
    its boundary, where the widest closed jaws fit), to 1e-6 of the part's size.

    >>> from fcgrasp.io.parts import demo_part
    >>> part = demo_part("washer")
    >>> bool(np.hypot(*(insertion_point(part, 0) - part.holes[0].mean(axis=0))) < 0.5)
    True
    """
    _grip_edges(polygon, hole)
    ring = np.ascontiguousarray(polygon.holes[int(hole)], dtype=float)
    return np.array(_pole(ring.tobytes(), float(polygon.size)))


@functools.lru_cache(maxsize=256)
def _pole(ring: bytes, size: float) -> tuple[float, float]:
    import shapely
    from shapely.ops import polylabel

    pt = polylabel(shapely.Polygon(np.frombuffer(ring).reshape(-1, 2)), tolerance=SLICE_TOL * size)
    return float(pt.x), float(pt.y)


def jaw_poses(polygon: Polygon, jaw: JawParameters, theta: Any, offset: Any,
              margin: float = DEFAULT_MARGIN_DEG, hole: int | None = None) -> PoseContacts:
    """The contacts and the verdict of the jaw at a batch of poses (the model of this
    module's docstring), exact at each pose.

    ``theta`` (P,): closing directions (radians); ``offset`` (P,): lateral offsets from
    the centroid; ``margin`` in degrees.  External grip (``hole=None``): every edge of
    the outer ring is clipped to each pose's strip (a hole's material is never the
    extreme).  Internal grip in the hole ``hole`` (an index into ``polygon.holes``):
    the closed jaws, on the strip's segment at the height of the hole's
    :func:`insertion_point` (free and inside the hole, or the pose fails), open until
    pad A (facing ``+u``) meets the first boundary above and pad B the first below.

    >>> from fcgrasp.io.parts import demo_part

    >>> from fcgrasp.grippers.jaw import ParallelJaw
    >>> part = demo_part("rectangle")              # 80 x 30
    >>> jaw = ParallelJaw(stroke=(10, 50), pad_width=12, mu=0.4)
    >>> r = jaw_poses(part, jaw, [np.pi / 2, 0.0], [0.0, 0.0])
    >>> r.opening.round(6).tolist(), r.holds.tolist()    # across 30 mm; along, 80 mm
    ([30.0, 80.0], [True, False])
    """
    th = np.atleast_1d(np.asarray(theta, dtype=float)).ravel()
    c = np.atleast_1d(np.asarray(offset, dtype=float)).ravel()
    if th.shape != c.shape:
        raise ValueError(f"theta and offset must have the same length, got {th.size} and "
                         f"{c.size}")
    return _evaluate(polygon, jaw, th, c, margin, hole)[0]


def _evaluate(polygon: Polygon, jaw: JawParameters, th: FloatArray, c: FloatArray,
              margin: float, hole: int | None) -> tuple[PoseContacts, FloatArray]:
    """:func:`jaw_poses` on checked arrays, with the verdict's slacks (:func:`_verdict`):
    by the compiled loop of :mod:`._kernels` where it runs, else by numpy
    (:func:`_evaluate_numpy`, the reference)."""
    ring = _grip_edges(polygon, hole)
    if th.size and np.ptp(th) < np.pi / 2:
        ring = _near_strip(polygon, ring, float(th.min()), float(th.max()), float(c.min()),
                           float(c.max()), jaw.pad_width / 2)
    if _kernels.available():
        out = _kernels.poses(th, c, *_pose_args(polygon, jaw, margin, hole, ring))
        if out is not None:
            top, bottom, ok_a, ok_b, lat_a, lat_b, psi_a, psi_b, e_a, e_b, holds, slacks = out
            return _contacts(ring, top, bottom, ok_a, ok_b, lat_a, lat_b, psi_a, psi_b, e_a,
                             e_b, holds), slacks
    return _evaluate_numpy(polygon, jaw, th, c, margin, hole, ring)


def _pose_args(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None,
               ring: np.ndarray
               ) -> tuple[FloatArray, FloatArray, FloatArray, float, float, FloatArray | None,
                          tuple[float, float], float, float]:
    """The pose model's numbers as the compiled loops take them (:func:`._kernels.poses`,
    :func:`._kernels.slices`): the edges of ``ring`` from the centroid, their contact
    forces (inward normals), half the pad's width, the contact tolerance, the insertion
    point from the centroid (None for an external grip), the stroke, the friction cone's
    shrunk half-angle and the rounding slack."""
    cen = polygon.centroid
    q = None if hole is None else insertion_point(polygon, hole) - cen
    return (polygon.starts[ring] - cen, polygon.ends[ring] - cen, -polygon.normals[ring],
            jaw.pad_width / 2, CONTACT_TOL * polygon.size, q, jaw.stroke,
            float(shrunk_half_angle(jaw.mu, margin)), ROUND_TOL)


def _contacts(ring: np.ndarray, top: FloatArray, bottom: FloatArray, ok_a: np.ndarray,
              ok_b: np.ndarray, lat_a: FloatArray, lat_b: FloatArray, psi_a: FloatArray,
              psi_b: FloatArray, e_a: np.ndarray, e_b: np.ndarray, holds: np.ndarray
              ) -> PoseContacts:
    """The pads' findings as :class:`PoseContacts` (columns of ``ring`` made the part's
    edges)."""
    with np.errstate(invalid="ignore"):
        opening = top - bottom
    kind_a = np.where(ok_a, np.where(np.nanmax(np.abs(psi_a), axis=1, initial=0.0) > 0, 2, 1),
                      0)
    kind_b = np.where(ok_b, np.where(np.nanmax(np.abs(psi_b), axis=1, initial=0.0) > 0, 2, 1),
                      0)
    ids = np.flatnonzero(ring)
    return PoseContacts(top, bottom, opening, kind_a, kind_b, lat_a, lat_b, psi_a, psi_b,
                        holds, np.where(e_a >= 0, ids[e_a], -1),
                        np.where(e_b >= 0, ids[e_b], -1))


def _evaluate_numpy(polygon: Polygon, jaw: JawParameters, th: FloatArray, c: FloatArray,
                    margin: float, hole: int | None, ring: np.ndarray
                    ) -> tuple[PoseContacts, FloatArray]:
    """:func:`_evaluate` by numpy over the edges ``ring`` (the reference of the compiled
    loop)."""
    internal = hole is not None
    rel_a = polygon.starts[ring] - polygon.centroid
    rel_b = polygon.ends[ring] - polygon.centroid
    # coordinates along u = (cos, sin) and n = (-sin, cos), products summed in one
    # order (as the compiled loop does; a matrix product may fuse them differently)
    cs, sn = np.cos(th)[:, None], np.sin(th)[:, None]

    def along_u(v: FloatArray) -> FloatArray:
        return cs * v[:, 0] + sn * v[:, 1]

    def along_n(v: FloatArray) -> FloatArray:
        return -sn * v[:, 0] + cs * v[:, 1]

    y_a, y_b = along_u(rel_a), along_u(rel_b)
    x_a, x_b = along_n(rel_a), along_n(rel_b)
    half = jaw.pad_width / 2
    s0, s1 = (c - half)[:, None], (c + half)[:, None]
    tol = CONTACT_TOL * polygon.size
    # the contact force on an edge (its inward normal) as an angle from each pad's force,
    # positive towards +n: pad A pushes along -u, pad B along +u
    f = -polygon.normals[ring]
    fx, fy = along_n(f), along_u(f)
    if hole is not None:
        # the closed jaws go in at the insertion point's height y_q: the segment the
        # strip cuts there must be free (no edge of the hole's boundary crosses it) and
        # inside the hole; opening, pad A (pushing along +u) meets the first boundary
        # above it, pad B the first below, each an edge facing it
        y_q = along_u((insertion_point(polygon, hole) - polygon.centroid)[None, :])
        above, below, free = _sides_of(y_a, y_b, x_a, x_b, s0, s1, y_q, tol)
        top, ok_a, lat_a, psi_a, e_a = _pad(y_a, y_b, x_a, x_b, s0, s1, -1.0, tol,
                                       (fx, fy), (fy > 0) & above)
        bottom, ok_b, lat_b, psi_b, e_b = _pad(y_a, y_b, x_a, x_b, s0, s1, 1.0, tol,
                                          (fx, -fy), (fy < 0) & below)
        ok_a &= free & _inside(y_a, y_b, x_a, x_b, c[:, None], y_q)
    else:
        top, ok_a, lat_a, psi_a, e_a = _pad(y_a, y_b, x_a, x_b, s0, s1, 1.0, tol,
                                       (fx, -fy))
        bottom, ok_b, lat_b, psi_b, e_b = _pad(y_a, y_b, x_a, x_b, s0, s1, -1.0, tol,
                                          (fx, fy))
    with np.errstate(invalid="ignore"):
        opening = top - bottom
    holds, slacks = _verdict(opening, lat_a, lat_b, psi_a, psi_b, ok_a, ok_b, jaw, margin,
                             internal)
    return _contacts(ring, top, bottom, ok_a, ok_b, lat_a, lat_b, psi_a, psi_b, e_a, e_b,
                     holds), slacks


def _near_strip(polygon: Polygon, ring: np.ndarray, t0: float, t1: float, c0: float,
                c1: float, half: float) -> np.ndarray:
    """The edges of ``ring`` that may meet the strip at some pose of the box
    ``[t0, t1] x [c0, c1]`` (``t1 - t0`` under a quarter turn): an edge none of whose
    points enters the strip there never touches a pad, never blocks the closed jaws
    and is never crossed by the ray from their middle."""
    a = polygon.starts - polygon.centroid
    b = polygon.ends - polygon.centroid
    xa_lo, xa_hi = _sin_range(a[:, 1], -a[:, 0], t0, t1)
    xb_lo, xb_hi = _sin_range(b[:, 1], -b[:, 0], t0, t1)
    pad = NEAR_STRIP * CONTACT_TOL * polygon.size
    near = (np.maximum(xa_hi, xb_hi) >= c0 - half - pad) \
        & (np.minimum(xa_lo, xb_lo) <= c1 + half + pad)
    # (none near: the ring as it is, so that every pose has edges to say nothing holds)
    return ring & near if np.any(ring & near) else ring


def _sides_of(y_a: FloatArray, y_b: FloatArray, x_a: FloatArray, x_b: FloatArray,
              s0: FloatArray, s1: FloatArray, level: FloatArray, tol: float
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Which edges (P, E) meet the strip ``[s0, s1]`` wholly above the height ``level``
    (P, 1) there, which wholly below (the heights of each edge's part in the strip, its
    clipped ends; an edge along ``u`` is clipped to itself), and whether every edge that
    meets the strip is one or the other (P,): the strip's segment at ``level`` is free."""
    lo_x, hi_x = np.minimum(x_a, x_b), np.maximum(x_a, x_b)
    meets = (hi_x >= s0) & (lo_x <= s1)
    flat = np.abs(x_b - x_a) <= tol
    with np.errstate(divide="ignore", invalid="ignore"):
        slope = np.where(flat, 0.0, (y_b - y_a) / np.where(flat, 1.0, x_b - x_a))
    h0 = np.where(flat, y_a, y_a + (np.clip(lo_x, s0, s1) - x_a) * slope)
    h1 = np.where(flat, y_b, y_a + (np.clip(hi_x, s0, s1) - x_a) * slope)
    above = meets & (np.minimum(h0, h1) > level + tol)
    below = meets & (np.maximum(h0, h1) < level - tol)
    return above, below, ~np.any(meets & ~above & ~below, axis=1)


def _inside(y_a: FloatArray, y_b: FloatArray, x_a: FloatArray, x_b: FloatArray,
            x: FloatArray, y: FloatArray) -> np.ndarray:
    """Whether the points ``(x, y)`` (P, 1) are inside the ring of edges (P, E) (even-odd:
    the ray along ``+u`` from each crosses it an odd number of times)."""
    straddle = (x_a > x) != (x_b > x)
    with np.errstate(divide="ignore", invalid="ignore"):
        y_at = y_a + (x - x_a) * (y_b - y_a) / (x_b - x_a)
    return np.sum(straddle & (y_at > y), axis=1) % 2 == 1


def _verdict(opening: FloatArray, lat_a: FloatArray, lat_b: FloatArray, psi_a: FloatArray,
             psi_b: FloatArray, ok_a: np.ndarray, ok_b: np.ndarray, jaw: JawParameters,
             margin: float, internal: bool) -> tuple[np.ndarray, FloatArray]:
    """Whether the poses hold, from what the pads touch (theorem 6.3 and the stroke), and
    the slacks the verdict is made of, (P, 2 K**2 + 2): per pair of features the two
    lateral conditions (> 0 where met; NaN where a feature is missing or the pair's
    cones do not meet), then ``opening - min_opening`` and ``max_opening - opening``
    (>= 0 where met).  The pose holds when both pads touch, some pair has both lateral
    slacks positive, and both stroke slacks are >= 0.

    Two friction contacts (theorem 6.3): the direction from a point of A's feature to
    one of B's, at angle psi from -u (positive towards +n), must be within beta of both
    forces: psi in (lo, hi); over the features' lateral spans the offset dx = xb - xa
    ranges over [b0 - a1, b1 - a0] and psi = atan(dx / opening).  Inside a hole the pads
    push apart: the same test with both angles negated."""
    beta = shrunk_half_angle(jaw.mu, margin)
    flip = -1.0 if internal else 1.0
    pa = flip * psi_a[:, :, None]
    pb = -flip * psi_b[:, None, :]
    lo = np.maximum(pa, pb) - beta
    hi = np.minimum(pa, pb) + beta
    d = opening[:, None, None]
    a0, a1 = lat_a[:, :, None, 0], lat_a[:, :, None, 1]
    b0, b1 = lat_b[:, None, :, 0], lat_b[:, None, :, 1]
    with np.errstate(invalid="ignore"):
        meet = lo < hi
        s_hi = np.where(meet, d * np.tan(np.minimum(hi, np.pi / 2 - ROUND_TOL)) - (b0 - a1),
                        np.nan)
        s_lo = np.where(meet, (b1 - a0) - d * np.tan(np.maximum(lo, -np.pi / 2 + ROUND_TOL)),
                        np.nan)
        pair = (s_hi > 0) & (s_lo > 0)
        s_min, s_max = opening - jaw.stroke[0], jaw.stroke[1] - opening
        holds = (ok_a & ok_b & (beta > 0) & np.any(pair, axis=(1, 2))
                 & (s_min >= 0) & (s_max >= 0))
    P = len(opening)
    slacks = np.concatenate([s_hi.reshape(P, -1), s_lo.reshape(P, -1), s_min[:, None],
                             s_max[:, None]], axis=1)
    return holds, slacks


def _contact_points(polygon: Polygon, theta: float, lat: FloatArray, stop: float
                    ) -> FloatArray:
    """A pad's contact points at one pose: its stop ``stop`` along ``u`` and each end of
    its contacts' extents ``lat`` along ``n`` (rows of finite ends)."""
    u = np.array([np.cos(theta), np.sin(theta)])
    n = np.array([-u[1], u[0]])
    ends = lat[np.isfinite(lat[:, 0])]
    pts = [polygon.centroid + stop * u + x * n for row in ends for x in np.unique(row)]
    return np.array(pts).reshape(-1, 2)
