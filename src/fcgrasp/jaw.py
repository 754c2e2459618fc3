r"""A parallel-jaw gripper: where two flat pads on one slide can close on a part (issue 14).

**Model.**  Two flat pads of width ``pad_width``, parallel, close along the direction
``u = (cos theta, sin theta)``, centred on the line at lateral offset ``c`` from the
part's centroid (``c = (x - centroid) . n`` with ``n = (-sin theta, cos theta)``): the
pads sweep the strip ``|(x - centroid) . n - c| <= pad_width / 2``.  Closing, each pad
stops on the part's extreme material within the strip: pad ``A`` (coming from ``+u``)
at the largest ``x . u``, pad ``B`` at the smallest.  A pad touches

* a **vertex** inside the strip: a point contact with friction whose normal is the
  pad's (``-u`` for ``A``, ``+u`` for ``B``), or
* an **edge parallel to the pad**: an edge contact with friction (figure 4.d), or
* an edge at the pad's **corner** (the extreme lies on the strip's side, as on a flat
  face slightly turned from the pad): a point contact with friction whose normal is
  the edge's, not the pad's.

The pose holds when the two contacts are force closure (theorem 6.3, two fingers with
friction: some point of one contact sees some point of the other strictly inside both
friction cones, shrunk by ``margin``; between the pads' own normals this is
``|lateral offset| < tan(atan(mu) - margin) * opening``) and the opening (the part's
width in the strip along ``u``) is within the stroke.  External grips close on the outline;
internal grips open inside a convex hole (pad ``A``, facing ``+u``, meets the hole's
boundary above it, pad ``B`` the boundary below; the strip must lie inside the hole's
width; on a curved hole a flat pad meets the boundary at its corners).

**Tolerance boxes.**  The answer is not one pose but a box of poses
``theta in [t0, t1]``, ``c in [c0, c1]`` every pose of which holds, the analogue of
independent regions.  The set of holding poses is evaluated exactly at every pose of a
grid (:data:`THETA_STEP_DEG`, :data:`OFFSET_STEPS` across the part) by
:func:`jaw_poses`; the largest box of holding grid poses by the measure
``min(c1 - c0, (t1 - t0) * radius)`` (the offset range, and the angular range as the
arc it sweeps at the part's radius: both lengths) is then checked on a grid
:data:`CHECK_DENSITY` times finer and shrunk by grid steps until every checked pose
holds.  It is therefore a box *verified on a fine grid*, not an exact one: the exact
boundary of the set (the support functions of the part restricted to the strip,
piecewise-smooth curves) is not computed.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ._checks import FloatArray, check_int, check_mu_scalar, check_scalar
from ._json import json_ready
from .polygon import Polygon
from .quality import characteristic_length
from .regions import DEFAULT_MARGIN_DEG

__all__ = ["ParallelJaw", "JawPlan", "jaw_poses", "jaw_plans", "THETA_STEP_DEG",
           "OFFSET_STEPS", "CHECK_DENSITY"]

#: Angular step of the pose grid (degrees).
THETA_STEP_DEG = 0.5
#: Offsets sampled across the part (its diameter plus a pad width).
OFFSET_STEPS = 160
#: The found box is checked on a grid this many times finer (and shrunk until it holds).
CHECK_DENSITY = 4
#: Heights within this (times the part's size) are one contact (ties of the extreme).
CONTACT_TOL = 1e-9
#: At most this many contact features per pad are compared (more: not held, safely).
MAX_CONTACTS = 4


@dataclass(frozen=True)
class ParallelJaw:
    """A parallel-jaw gripper: its stroke ``(min_opening, max_opening)``, the width of
    its flat pads and their friction coefficient ``mu`` (lengths in the part's units).

    >>> ParallelJaw(stroke=(10, 50), pad_width=12, mu=0.4).stroke
    (10.0, 50.0)
    """

    stroke: tuple[float, float]
    pad_width: float
    mu: float

    def __post_init__(self) -> None:
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
    ``holds`` (P,): force closure and the opening within the stroke.
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


def _pad(y_a: FloatArray, y_b: FloatArray, x_a: FloatArray, x_b: FloatArray,
         s0: FloatArray, s1: FloatArray, sign: float, tol: float, psi_edge: FloatArray,
         use: np.ndarray | None = None
         ) -> tuple[FloatArray, np.ndarray, FloatArray, FloatArray]:
    """One pad: the extreme of ``sign * y`` over the edges clipped to the strip
    ``[s0, s1]`` (arrays (P, E) of edge ends, (P, 1) strip sides).  Returns the stop
    (P,), whether it touches anything (P,), the contact features' lateral intervals
    (P, K, 2) and the angle of each feature's contact force from the pad's (P, K):
    0 on a vertex or an edge parallel to the pad, the edge's (``psi_edge`` (P, E))
    where the pad's corner touches an edge.  ``use`` (P, E): the edges the pad can meet
    (default all)."""
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
    level = np.abs(ya - yb) <= tol                       # an edge parallel to the pad
    # a clipped end strictly inside the edge's lateral span is where the strip's side
    # cuts the edge: the pad's corner touches the edge there, unless the edge is
    # parallel to the pad (then the whole clipped edge touches the pad's face)
    cut_lo = (cl_lo > lo_x + tol) & ~level & ~flat_lat
    cut_hi = (cl_hi < hi_x - tol) & ~level & ~flat_lat
    corner = (at_lo & cut_lo) | (at_hi & cut_hi)
    touch = at_lo | at_hi
    both = level & at_lo & at_hi
    lat_lo = np.where(both, cl_lo, np.where(at_lo, cl_lo, cl_hi))
    lat_hi = np.where(both, cl_hi, np.where(at_hi, cl_hi, cl_lo))
    psi = np.where(corner, psi_edge, 0.0)
    # keep the touching features first (at most MAX_CONTACTS)
    order = np.argsort(~touch, axis=1, kind="stable")[:, :MAX_CONTACTS]
    rows = np.arange(len(stop))[:, None]
    tk = touch[rows, order]
    lat = np.stack([np.where(tk, lat_lo[rows, order], np.nan),
                    np.where(tk, lat_hi[rows, order], np.nan)], axis=-1)
    ok = np.isfinite(stop) & (touch.sum(axis=1) <= MAX_CONTACTS)
    return sign * stop, ok, lat, np.where(tk, psi[rows, order], np.nan)


def convex_holes(polygon: Polygon) -> list[int]:
    """The holes of a part in which the jaws can open (internal grips): the convex ones."""
    import shapely

    out = []
    for k, h in enumerate(polygon.holes):
        ring = shapely.Polygon(h)
        if ring.convex_hull.area <= ring.area * (1 + 1e-9):
            out.append(k)
    return out


def jaw_poses(polygon: Polygon, jaw: ParallelJaw, theta: Any, offset: Any,
              margin: float = DEFAULT_MARGIN_DEG, hole: int | None = None) -> PoseContacts:
    """The contacts and the verdict of the jaw at a batch of poses (the model of this
    module's docstring), exact at each pose.

    ``theta`` (P,): closing directions (radians); ``offset`` (P,): lateral offsets from
    the centroid; ``margin`` in degrees.  External grip (``hole=None``): every edge of
    the part (holes included: their material is never the extreme) is clipped to each
    pose's strip.  Internal grip in the convex hole ``hole`` (an index into
    ``polygon.holes``): the jaws, inside the hole, open until pad A (facing ``+u``) meets
    the hole's boundary above and pad B the boundary below; the strip must lie inside
    the hole's width.

    >>> from fcgrasp.parts import demo_part
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
    internal = hole is not None
    ring = np.ones(polygon.n_edges, dtype=bool)
    if hole is not None:
        if isinstance(hole, bool) or not isinstance(hole, (int, np.integer)) \
                or int(hole) not in convex_holes(polygon):
            raise ValueError(f"hole must be the index of a convex hole of the part (internal "
                             f"grips), got {hole!r}; convex holes: {convex_holes(polygon)}")
        ring = polygon.rings == int(hole) + 1
    rel_a = polygon.starts[ring] - polygon.centroid
    rel_b = polygon.ends[ring] - polygon.centroid
    u = np.stack([np.cos(th), np.sin(th)], axis=1)
    n = np.stack([-u[:, 1], u[:, 0]], axis=1)
    y_a, y_b = u @ rel_a.T, u @ rel_b.T
    x_a, x_b = n @ rel_a.T, n @ rel_b.T
    half = jaw.pad_width / 2
    s0, s1 = (c - half)[:, None], (c + half)[:, None]
    tol = CONTACT_TOL * polygon.size
    # the contact force on an edge (its inward normal) as an angle from each pad's force,
    # positive towards +n: pad A pushes along -u, pad B along +u
    f = -polygon.normals[ring]
    fx, fy = n @ f.T, u @ f.T
    if internal:
        # inside a hole pad A pushes along +u on the boundary above it (where the part's
        # outward normal points down), pad B along -u on the boundary below
        above, below = fy > 0, fy < 0
        top, ok_a, lat_a, psi_a = _pad(y_a, y_b, x_a, x_b, s0, s1, -1.0, tol,
                                       np.arctan2(fx, fy), above)
        bottom, ok_b, lat_b, psi_b = _pad(y_a, y_b, x_a, x_b, s0, s1, 1.0, tol,
                                          np.arctan2(fx, -fy), below)
        # the pads fit only if the strip lies inside the hole's width
        ok_a &= (s0[:, 0] > np.minimum(x_a, x_b).min(axis=1)) \
            & (s1[:, 0] < np.maximum(x_a, x_b).max(axis=1))
    else:
        top, ok_a, lat_a, psi_a = _pad(y_a, y_b, x_a, x_b, s0, s1, 1.0, tol,
                                       np.arctan2(fx, -fy))
        bottom, ok_b, lat_b, psi_b = _pad(y_a, y_b, x_a, x_b, s0, s1, -1.0, tol,
                                          np.arctan2(fx, fy))
    with np.errstate(invalid="ignore"):
        opening = top - bottom
    beta = np.arctan(jaw.mu) - np.radians(margin)
    # two friction contacts (theorem 6.3): the direction from a point of A's feature to
    # one of B's, at angle psi from -u (positive towards +n), must be within beta of
    # both forces: psi in (lo, hi); over the features' lateral spans the offset
    # dx = xb - xa ranges over [b0 - a1, b1 - a0] and psi = atan(dx / opening)
    # (inside a hole the pads push apart: the same test with both angles negated)
    flip = -1.0 if internal else 1.0
    pa = flip * psi_a[:, :, None]
    pb = -flip * psi_b[:, None, :]
    lo = np.maximum(pa, pb) - beta
    hi = np.minimum(pa, pb) + beta
    d = opening[:, None, None]
    a0, a1 = lat_a[:, :, None, 0], lat_a[:, :, None, 1]
    b0, b1 = lat_b[:, None, :, 0], lat_b[:, None, :, 1]
    with np.errstate(invalid="ignore"):
        pair = ((lo < hi) & (b0 - a1 < d * np.tan(np.minimum(hi, np.pi / 2 - 1e-12)))
                & (b1 - a0 > d * np.tan(np.maximum(lo, -np.pi / 2 + 1e-12))))
        holds = (ok_a & ok_b & (beta > 0) & np.any(pair, axis=(1, 2))
                 & (opening >= jaw.stroke[0]) & (opening <= jaw.stroke[1]))
    kind_a = np.where(ok_a, np.where(np.nanmax(np.abs(psi_a), axis=1, initial=0.0) > 0, 2, 1),
                      0)
    kind_b = np.where(ok_b, np.where(np.nanmax(np.abs(psi_b), axis=1, initial=0.0) > 0, 2, 1),
                      0)
    return PoseContacts(top, bottom, opening, kind_a, kind_b, lat_a, lat_b, psi_a, psi_b,
                        holds)


@dataclass
class JawPlan:
    """A box of jaw poses that hold: ``theta`` (t0, t1) in radians, ``offset`` (c0, c1)
    from the centroid, the ``opening`` range over the box's checked poses (every pose of
    the box fits the stroke; between checked poses the opening may pass the range by a
    little), the contacts at the box's
    centre pose (``contacts``: per pad, the contact points; ``kinds``: ``"vertex"``,
    ``"edge"`` or ``"corner"``; ``stops``: where pads A and B stop, along ``u`` from the
    centroid), the ranking ``measure``: ``min(c1 - c0, (t1 - t0) * radius)``, and the
    grip: ``mode`` ``"external"`` (closing on the outline) or ``"internal"`` (opening in
    the hole ``hole``, an index into the part's holes)."""

    theta: tuple[float, float]
    offset: tuple[float, float]
    opening: tuple[float, float]
    contacts: list[FloatArray]
    kinds: tuple[str, str]
    stops: tuple[float, float]
    measure: float
    jaw: ParallelJaw
    centroid: FloatArray = field(repr=False)
    radius: float = field(repr=False)
    mode: str = "external"
    hole: int | None = None

    @property
    def centre(self) -> tuple[float, float]:
        """The box's centre pose ``(theta, offset)``."""
        return (sum(self.theta) / 2, sum(self.offset) / 2)

    def sample(self, n: int, rng: np.random.Generator | None = None) -> FloatArray:
        """``n`` poses uniform in the box, shape (n, 2): ``(theta, offset)``."""
        rng = np.random.default_rng() if rng is None else rng
        u = rng.random((n, 2))
        return np.c_[self.theta[0] + u[:, 0] * (self.theta[1] - self.theta[0]),
                     self.offset[0] + u[:, 1] * (self.offset[1] - self.offset[0])]

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready description (angles also in degrees)."""
        return json_ready({
            "gripper": "parallel_jaw", "mode": self.mode, "hole": self.hole,
            "theta_rad": list(self.theta), "theta_deg": list(np.degrees(self.theta)),
            "offset": list(self.offset), "opening": list(self.opening),
            "contacts": {"a": {"kind": self.kinds[0], "points": self.contacts[0],
                               "stop": self.stops[0]},
                         "b": {"kind": self.kinds[1], "points": self.contacts[1],
                               "stop": self.stops[1]}},
            "measure": self.measure, "centre": list(self.centre), "centroid": self.centroid,
            "stroke": list(self.jaw.stroke), "pad_width": self.jaw.pad_width,
            "mu": self.jaw.mu,
        })


def _box_scores(H: np.ndarray, dth: float, dc: float, radius: float, max_rows: int
                ) -> tuple[float, int, int, int, int]:
    """The largest box of True cells of the pose grid ``H`` (theta rows, cyclic; offset
    columns) by ``min(offset range, theta range * radius)``: ``(score, k0, k1, j0, j1)``
    with inclusive grid indices (``k1`` may pass the last row: it wraps).

    For each first row ``k0``, the rows from it are AND-ed cumulatively and the longest
    run of True of every prefix is read off at once (run lengths by cumulative sums)."""
    K, M = H.shape
    best = (-1.0, 0, 0, 0, 0)
    span = np.arange(max_rows)
    for k0 in np.flatnonzero(H.any(axis=1)):
        acc = np.logical_and.accumulate(H[(k0 + span) % K], axis=0)
        alive = acc.any(axis=1)
        rows = int(np.argmin(alive)) if not alive.all() else max_rows
        acc = acc[:rows]
        count = np.cumsum(acc, axis=1)
        last_false = np.maximum.accumulate(np.where(acc, 0, count), axis=1)
        run = count - last_false                     # length of the run ending here
        length = run.max(axis=1)
        score = np.minimum((length - 1) * dc, np.arange(rows) * dth * radius)
        r = int(np.argmax(score))
        if score[r] > best[0]:
            end = int(np.argmax(run[r]))
            best = (float(score[r]), int(k0), int(k0 + r), end - int(length[r]) + 1, end)
    return best


def _kind(lat: FloatArray, psi: FloatArray, size: float) -> str:
    """How a pad touches at one pose: on a pad corner, an edge flat on it, or vertices."""
    real = np.isfinite(lat[:, 0])
    if np.any(np.abs(psi[real]) > 0):
        return "corner"
    return "edge" if np.any(lat[real, 1] - lat[real, 0] > CONTACT_TOL * size) else "vertex"


def _contact_points(polygon: Polygon, theta: float, lat: FloatArray, stop: float
                    ) -> FloatArray:
    u = np.array([np.cos(theta), np.sin(theta)])
    n = np.array([-u[1], u[0]])
    ends = lat[np.isfinite(lat[:, 0])]
    pts = [polygon.centroid + stop * u + x * n for row in ends for x in np.unique(row)]
    return np.array(pts).reshape(-1, 2)


def jaw_plans(polygon: Polygon, jaw: ParallelJaw, top: int = 5,
              margin: float = DEFAULT_MARGIN_DEG, internal: bool = True) -> list[JawPlan]:
    """The ``top`` largest boxes of jaw poses that hold, best first (see the module's
    docstring): external grips, and with ``internal`` grips inside each convex hole
    (:func:`convex_holes`).  For each grip, each found box's poses are removed from the
    grid before the next is sought, with their mirror (``theta + pi``, ``-c``: the same
    grasp, pads swapped).

    >>> from fcgrasp.parts import demo_part
    >>> jaw = ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
    >>> best = jaw_plans(demo_part("rectangle"), jaw, top=1)[0]   # across the 30 mm
    >>> [round(float(np.degrees(t))) % 180 for t in best.theta], best.kinds
    ([78, 102], ('edge', 'edge'))
    """
    if not isinstance(polygon, Polygon):
        raise TypeError(f"polygon must be a Polygon, got {type(polygon).__name__}")
    if not isinstance(jaw, ParallelJaw):
        raise TypeError(f"jaw must be a ParallelJaw, got {type(jaw).__name__}")
    margin = check_scalar(margin, "margin", nonnegative=True)
    top = check_int(top, "top", minimum=1)
    if not isinstance(internal, bool):
        raise TypeError(f"internal must be a bool, got {internal!r}")
    holes: list[int | None] = [None]
    if internal:
        holes += convex_holes(polygon)
    plans = [p for h in holes for p in _grip_plans(polygon, jaw, top, margin, h)]
    plans.sort(key=lambda p: -p.measure)
    return plans[:top]


def _grip_plans(polygon: Polygon, jaw: ParallelJaw, top: int, margin: float,
                hole: int | None) -> list[JawPlan]:
    """The best boxes of one grip (external, or internal in ``hole``)."""
    radius = characteristic_length(polygon.vertices, polygon.centroid)
    K = int(round(360 / THETA_STEP_DEG))
    M = OFFSET_STEPS
    thetas = np.arange(K) * (2 * np.pi / K)
    reach = radius + jaw.pad_width / 2
    offsets = np.linspace(-reach, reach, M)
    dth, dc = 2 * np.pi / K, offsets[1] - offsets[0]
    tt, cc = np.meshgrid(thetas, offsets, indexing="ij")
    H = np.concatenate([jaw_poses(polygon, jaw, tt.ravel()[i:i + 20000],
                                  cc.ravel()[i:i + 20000], margin, hole).holds
                        for i in range(0, tt.size, 20000)]).reshape(K, M)
    plans: list[JawPlan] = []
    while len(plans) < top:
        score, k0, k1, j0, j1 = _box_scores(H, dth, dc, radius, K // 2)
        if score <= 0:
            break
        H[np.arange(k0, k1 + 1) % K, j0:j1 + 1] = False
        H[(np.arange(k0, k1 + 1) + K // 2) % K, M - 1 - j1:M - j0] = False
        box = _checked_box(polygon, jaw, margin, hole,
                           thetas[k0] + np.array([0, k1 - k0]) * dth, offsets[[j0, j1]],
                           dth, dc)
        if box is None:
            continue
        (t0, t1), (c0, c1), opening = box
        tc, ccen = (t0 + t1) / 2, (c0 + c1) / 2
        r = jaw_poses(polygon, jaw, [tc], [ccen], margin, hole)
        pts = [_contact_points(polygon, tc, r.lat_a[0], float(r.top[0])),
               _contact_points(polygon, tc, r.lat_b[0], float(r.bottom[0]))]
        kinds = (_kind(r.lat_a[0], r.psi_a[0], polygon.size),
                 _kind(r.lat_b[0], r.psi_b[0], polygon.size))
        plans.append(JawPlan((float(t0), float(t1)), (float(c0), float(c1)), opening, pts,
                             kinds, (float(r.top[0]), float(r.bottom[0])),
                             min(c1 - c0, (t1 - t0) * radius), jaw,
                             polygon.centroid.copy(), radius,
                             "external" if hole is None else "internal", hole))
    return plans


def _checked_box(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
                 th: FloatArray, off: FloatArray, dth: float, dc: float
                 ) -> tuple[tuple[float, float], tuple[float, float],
                            tuple[float, float]] | None:
    """Shrink a box by grid steps until every pose of a grid :data:`CHECK_DENSITY`
    times finer holds; returns ``(theta range, offset range, opening range)`` or None."""
    (t0, t1), (c0, c1) = th, off
    for _ in range(4):
        if t1 < t0 or c1 < c0:
            return None
        nt = max(2, int(round((t1 - t0) / dth)) * CHECK_DENSITY + 1)
        nc = max(2, int(round((c1 - c0) / dc)) * CHECK_DENSITY + 1)
        tt, cc = np.meshgrid(np.linspace(t0, t1, nt), np.linspace(c0, c1, nc), indexing="ij")
        r = jaw_poses(polygon, jaw, tt.ravel(), cc.ravel(), margin, hole)
        if np.all(r.holds):
            return (t0, t1), (c0, c1), (float(r.opening.min()), float(r.opening.max()))
        t0, t1, c0, c1 = t0 + dth, t1 - dth, c0 + dc, c1 - dc
    return None
