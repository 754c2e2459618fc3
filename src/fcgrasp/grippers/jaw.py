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
internal grips open inside a hole: the closed jaws go in at the hole's
:func:`insertion_point` (its pole of inaccessibility, fixed in the part), so at a pose
they sit on the strip's segment at that point's height, which must be free (no edge of
the hole crosses it) and inside the hole; opening, pad ``A`` (facing ``+u``) meets the
first boundary above that height, pad ``B`` the first below (in a non-convex hole the
nearest of several; on a curved hole a flat pad meets the boundary at its corners).

**Tolerance boxes.**  The answer is not one pose but a box of poses
``theta in [t0, t1]``, ``c in [c0, c1]`` every pose of which holds, the analogue of
independent regions.  The set of holding poses is evaluated exactly at every pose of a
grid (:data:`THETA_STEP_DEG`, :data:`OFFSET_STEPS` across the part) by
:func:`jaw_poses`; the largest box of holding grid poses by the measure
``min(c1 - c0, (t1 - t0) * radius)`` (the offset range, and the angular range as the
arc it sweeps at the part's radius: both lengths) is then checked on a grid
:data:`CHECK_DENSITY` times finer and shrunk by grid steps until every checked pose
holds.  :func:`certify_box` then *proves* that every pose of the box holds, between the
grid points too (sound, not complete; a box it cannot prove is shrunk, then dropped).

**The exact set.**  At a fixed closing angle the set's slice is computed exactly
(:func:`holding_offsets`: every quantity of the model is piecewise affine in the offset,
so the slice's ends are roots of the verdict's slacks, found in closed form, or kinks of
a pad's stop, located by halving).  A proved box is grown to the set's exact boundary:
its offset range to the nearest ends of the slices at :data:`CHECK_DENSITY` angles per
grid step across it, its angle range by bisection on the slices; the box on the
boundary cannot be proved (its sub-boxes would have to shrink to nothing there), so it
is moved in by a quarter of a grid step (else a half, :data:`GROW_BACKOFF`), proved, and
kept where it measures more than the grid's box.  The boxes are therefore maximal up to
that back-off in the directions grown, not the global optimum over all boxes of the
exact set: the box's shape (which rows of angles) is still chosen on the grid.
:func:`jaw_plans` returns proved boxes unless asked not to (``certify=False``: boxes
verified on the fine grid only, neither proved nor grown).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..core._angles import shrunk_half_angle, wrap, wrap_positive
from ..core._checks import FloatArray, check_int, check_mu_scalar, check_scalar
from ..core._json import json_ready
from ..core.tolerances import CONTACT_TOL, ROUND_TOL, SLICE_TOL, TOL
from ..model.polygon import Polygon, check_polygon
from ..model.quality import characteristic_length
from ..model.regions import DEFAULT_MARGIN_DEG
from .base import register

__all__ = ["ParallelJaw", "jaw_from_options", "JawPlan", "jaw_poses", "holding_offsets",
           "insertion_point", "jaw_plans", "certify_box", "THETA_STEP_DEG", "SLICE_TOL",
           "OFFSET_STEPS", "CHECK_DENSITY", "CERTIFY_BOXES", "CERTIFY_SHRINKS"]

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
MAX_CONTACTS = 4
#: Poses evaluated at a time (memory: a few arrays of this many rows times the edges).
POSE_BATCH = 20000


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
    #: prove every box (:func:`certify_box`); False: boxes verified on a fine grid only
    certify: bool = True
    name: ClassVar[str] = "jaw"

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

    # the gripper interface (fcgrasp.grippers.base.Gripper)
    def plan(self, polygon: Polygon, options: Any) -> list[JawPlan]:
        """The jaw's boxes (:func:`jaw_plans`) for a plan's search options."""
        if options.top is None:
            raise ValueError("a parallel jaw needs a top (how many boxes), got top=None")
        if options.rank_by != "min_region":
            raise ValueError(f"a parallel jaw ranks its boxes by their measure: "
                             f"rank_by={options.rank_by!r} would not be used")
        return jaw_plans(polygon, self, top=options.top, margin=options.margin,
                         certify=self.certify)

    def check_part(self, polygon: Polygon, options: Any) -> None:
        """Nothing to refuse before the search."""

    def parameters(self, options: Any) -> dict[str, Any]:
        return {"gripper": "parallel_jaw", "stroke": list(self.stroke),
                "pad_width": self.pad_width, "mu": self.mu, "top": options.top,
                "margin_deg": options.margin, "certify": self.certify}

    def no_grasp_reason(self, margin: float) -> str:
        return (f"no pose of the jaw holds the part (stroke {self.stroke[0]:g} to "
                f"{self.stroke[1]:g}, pads {self.pad_width:g} wide, mu = {self.mu:g}, "
                f"margin {margin:g} degrees)")

    @property
    def title(self) -> str:
        return "parallel jaw"


def jaw_from_options(options: Mapping[str, Any]) -> ParallelJaw:
    """The parallel jaw of a plan request (``--gripper jaw``): ``stroke``, ``pad``,
    ``mu`` (default 0.3), ``certify`` (default True); none of the point fingers'
    options."""
    for opt, given in (("--fingers", options.get("fingers") is not None),
                       ("--gravity", options.get("gravity") is not None),
                       ("--workspace", options.get("workspace") is not None),
                       ("--finger-radius", bool(options.get("finger_radius"))),
                       ("--rank-by", options.get("rank_by", "min_region") != "min_region"),
                       ("--single-edge", bool(options.get("single_edge")))):
        if given:
            raise ValueError(f"{opt} is an option of point fingers, not of --gripper jaw")
    stroke, pad = options.get("stroke"), options.get("pad")
    if stroke is None or pad is None:
        missing = "--stroke MIN,MAX" if stroke is None else "--pad WIDTH"
        raise ValueError(f"{missing} is needed: --gripper jaw needs --stroke MIN,MAX and "
                         f"--pad WIDTH (in the part's units)")
    mu = 0.3 if options.get("mu") is None else options["mu"]
    if not (math.isfinite(mu) and mu > 0):
        raise ValueError(f"--mu of a parallel jaw must be a finite number > 0, got {mu:g}")
    return ParallelJaw(stroke=(stroke[0], stroke[1]), pad_width=pad, mu=mu,
                       certify=options.get("certify") is not False)


register("jaw", jaw_from_options)


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
    if not isinstance(jaw, ParallelJaw):
        raise TypeError(f"jaw must be a ParallelJaw, got {type(jaw).__name__}")
    return check_scalar(margin, "margin", nonnegative=True)


def _grip_edges(polygon: Polygon, hole: Any) -> np.ndarray:
    """The edges a grip meets: all (external, ``hole=None``) or those of a hole."""
    if hole is None:
        return np.ones(polygon.n_edges, dtype=bool)
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


def jaw_poses(polygon: Polygon, jaw: ParallelJaw, theta: Any, offset: Any,
              margin: float = DEFAULT_MARGIN_DEG, hole: int | None = None) -> PoseContacts:
    """The contacts and the verdict of the jaw at a batch of poses (the model of this
    module's docstring), exact at each pose.

    ``theta`` (P,): closing directions (radians); ``offset`` (P,): lateral offsets from
    the centroid; ``margin`` in degrees.  External grip (``hole=None``): every edge of
    the part (holes included: their material is never the extreme) is clipped to each
    pose's strip.  Internal grip in the hole ``hole`` (an index into ``polygon.holes``):
    the closed jaws, on the strip's segment at the height of the hole's
    :func:`insertion_point` (free and inside the hole, or the pose fails), open until
    pad A (facing ``+u``) meets the first boundary above and pad B the first below.

    >>> from fcgrasp.io.parts import demo_part
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


def _evaluate(polygon: Polygon, jaw: ParallelJaw, th: FloatArray, c: FloatArray,
              margin: float, hole: int | None) -> tuple[PoseContacts, FloatArray]:
    """:func:`jaw_poses` on checked arrays, with the verdict's slacks (:func:`_verdict`)."""
    internal = hole is not None
    ring = _grip_edges(polygon, hole)
    if th.size and np.ptp(th) < np.pi / 2:
        ring = _near_strip(polygon, ring, float(th.min()), float(th.max()), float(c.min()),
                           float(c.max()), jaw.pad_width / 2)
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
    if hole is not None:
        # the closed jaws go in at the insertion point's height y_q: the segment the
        # strip cuts there must be free (no edge of the hole's boundary crosses it) and
        # inside the hole; opening, pad A (pushing along +u) meets the first boundary
        # above it, pad B the first below, each an edge facing it
        y_q = (u @ (insertion_point(polygon, hole) - polygon.centroid))[:, None]
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
    kind_a = np.where(ok_a, np.where(np.nanmax(np.abs(psi_a), axis=1, initial=0.0) > 0, 2, 1),
                      0)
    kind_b = np.where(ok_b, np.where(np.nanmax(np.abs(psi_b), axis=1, initial=0.0) > 0, 2, 1),
                      0)
    ids = np.flatnonzero(ring)
    return PoseContacts(top, bottom, opening, kind_a, kind_b, lat_a, lat_b, psi_a, psi_b,
                        holds, np.where(e_a >= 0, ids[e_a], -1),
                        np.where(e_b >= 0, ids[e_b], -1)), slacks


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
    pad = 10 * CONTACT_TOL * polygon.size
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
             psi_b: FloatArray, ok_a: np.ndarray, ok_b: np.ndarray, jaw: ParallelJaw,
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


def holding_offsets(polygon: Polygon, jaw: ParallelJaw, theta: Any,
                    margin: float = DEFAULT_MARGIN_DEG, hole: int | None = None,
                    offsets: tuple[float, float] | None = None) -> list[FloatArray]:
    """The exact slices of the set of holding poses: for each closing angle of ``theta``
    (T,), the offsets at which the jaw holds (the model of :func:`jaw_poses`), as sorted
    disjoint intervals, an array (k, 2) per angle.  ``offsets`` ``(lo, hi)`` limits the
    slices to a window (an interval reaching its end is cut there; default: every offset
    at which a pad can touch the part).

    At a fixed angle every quantity of the model is piecewise affine in the offset ``c``:
    a vertex enters or leaves the strip at ``c = x +- pad_width / 2`` (these cut the
    slice into *cells*), and inside a cell a pad's stop is the largest (pad B: smallest)
    of affine functions - a vertex's height, the height of an edge cut by a side of the
    strip - so it is convex (concave) and kinks where the extreme passes from one
    feature to another.  A cell on which the stops and the contacts' lateral spans are
    affine at three points (near its ends and at its middle: a convex function affine at
    three points is affine between them) has affine verdict slacks (theorem 6.3's two
    lateral conditions per pair of contacts, and the stroke), so the verdict changes only
    at their roots, found in closed form; the pieces between roots are decided by
    :func:`jaw_poses` at their middles.  A cell holding a kink is halved until it is
    shorter than ``4 * SLICE_TOL`` times the part's size, then decided at its middle.
    Exact up to :data:`SLICE_TOL` of the part's size: the three points stand that far
    inside a cell's ends (where a vertex entering the strip ties with the stop within
    :data:`CONTACT_TOL`), so a kink closer to an end than that is not seen.

    >>> from fcgrasp.io.parts import demo_part
    >>> jaw = ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
    >>> sl = holding_offsets(demo_part("rectangle"), jaw, [np.pi / 2])[0]   # across 30 mm
    >>> sl.round(6).tolist()    # on the long faces, while the pads overlap them (80 + 8)
    [[-44.0, 44.0]]
    """
    margin = _check_jaw_args(polygon, jaw, margin)
    th = np.atleast_1d(np.asarray(theta, dtype=float)).ravel()
    if not np.all(np.isfinite(th)):
        raise ValueError(f"theta must be finite angles, got {theta!r}")
    ring = _grip_edges(polygon, hole)
    pts = np.unique(np.concatenate([polygon.starts[ring], polygon.ends[ring]]), axis=0)
    rel = pts - polygon.centroid
    X = -np.sin(th)[:, None] * rel[:, 0] + np.cos(th)[:, None] * rel[:, 1]    # (T, V)
    half = jaw.pad_width / 2
    if offsets is None:
        w_lo, w_hi = X.min(axis=1) - half, X.max(axis=1) + half
    else:
        lo_hi = np.asarray(offsets, dtype=float)
        if lo_hi.shape != (2,) or not np.all(np.isfinite(lo_hi)) or lo_hi[1] < lo_hi[0]:
            raise ValueError(f"offsets must be an increasing range (lo, hi), got "
                             f"{offsets!r}")
        w_lo, w_hi = np.full(th.size, lo_hi[0]), np.full(th.size, lo_hi[1])
    cuts = [X - half, X + half]
    if hole is not None:
        # inside a hole the closed jaws' segment is blocked while an edge crosses the
        # insertion height within the strip: where an edge crosses that height, +- w/2
        q = insertion_point(polygon, int(hole)) - polygon.centroid
        cs, sn = np.cos(th)[:, None], np.sin(th)[:, None]
        a = polygon.starts[ring] - polygon.centroid
        b = polygon.ends[ring] - polygon.centroid
        ya, yb = cs * a[:, 0] + sn * a[:, 1], cs * b[:, 0] + sn * b[:, 1]
        xa, xb = -sn * a[:, 0] + cs * a[:, 1], -sn * b[:, 0] + cs * b[:, 1]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (cs * q[0] + sn * q[1] - ya) / (yb - ya)
        xc = np.where((t >= 0) & (t <= 1), xa + t * (xb - xa), w_lo[:, None])
        cuts += [xc - half, xc + half, xc]
    brk = np.sort(np.clip(np.concatenate(cuts + [w_lo[:, None], w_hi[:, None]], axis=1),
                          w_lo[:, None], w_hi[:, None]), axis=1)
    tiny = ROUND_TOL * polygon.size
    keep = brk[:, 1:] - brk[:, :-1] > tiny
    rows = np.nonzero(keep)
    cell_t, cell_lo, cell_hi = rows[0], brk[:, :-1][rows], brk[:, 1:][rows]
    found: list[FloatArray] = []                        # rows (angle index, lo, hi)
    atol = CONTACT_TOL * polygon.size
    while cell_t.size:
        inset = np.minimum((cell_hi - cell_lo) / 4, SLICE_TOL * polygon.size)
        ends = np.stack([cell_lo + inset, (cell_lo + cell_hi) / 2, cell_hi - inset])  # (3, C)
        r, slack = _evaluate_batched(polygon, jaw, np.tile(th[cell_t], 3), ends.ravel(),
                                     margin, hole)
        C = cell_t.size
        q = np.concatenate([r.top[:, None], r.bottom[:, None], r.lat_a.reshape(3 * C, -1),
                            r.lat_b.reshape(3 * C, -1)], axis=1).reshape(3, C, -1)
        fin = np.isfinite(q)
        qz = np.where(fin, q, 0.0)
        psi = np.nan_to_num(np.concatenate([r.psi_a, r.psi_b], axis=1), nan=9.0)
        psi = psi.reshape(3, C, -1)
        kinds = np.stack([r.kind_a, r.kind_b], axis=1).reshape(3, C, 2)
        affine = (np.all(fin[0] == fin[1], axis=1) & np.all(fin[1] == fin[2], axis=1)
                  & np.all(psi[0] == psi[1], axis=1) & np.all(psi[1] == psi[2], axis=1)
                  & np.all(kinds[0] == kinds[1], axis=1) & np.all(kinds[1] == kinds[2], axis=1)
                  & np.all(np.abs(qz[1] - (qz[0] + qz[2]) / 2) <= atol, axis=1))
        holds_mid = r.holds.reshape(3, C)[1]
        last = ~affine & (cell_hi - cell_lo <= 4 * SLICE_TOL * polygon.size)
        found.append(np.column_stack([cell_t[last & holds_mid], cell_lo[last & holds_mid],
                                      cell_hi[last & holds_mid]]))
        # affine cells: the roots of the slacks, then the pieces between them decided
        s = slack.reshape(3, C, -1)
        s0, s2 = s[0][affine], s[2][affine]
        a_t, a_lo, a_hi = cell_t[affine], cell_lo[affine], cell_hi[affine]
        p0, p2 = ends[0][affine], ends[2][affine]
        with np.errstate(invalid="ignore", divide="ignore"):
            cross = (s0 * s2 < 0) | ((s0 == 0) != (s2 == 0))
            frac = np.where(cross, s0 / (s0 - s2), np.nan)
        ci, si = np.nonzero(cross)
        roots = p0[ci] + frac[ci, si] * (p2[ci] - p0[ci])
        which = np.concatenate([np.arange(a_t.size), np.arange(a_t.size), ci])
        where = np.concatenate([a_lo, a_hi, np.clip(roots, a_lo[ci], a_hi[ci])])
        order = np.lexsort((where, which))
        which, where = which[order], where[order]
        piece = (which[1:] == which[:-1]) & (where[1:] - where[:-1] > tiny)
        plo, phi, pc = where[:-1][piece], where[1:][piece], which[:-1][piece]
        if plo.size:
            verdict = _evaluate_batched(polygon, jaw, th[a_t[pc]], (plo + phi) / 2, margin,
                                        hole)[0].holds
            found.append(np.column_stack([a_t[pc][verdict], plo[verdict], phi[verdict]]))
        split = ~affine & ~last
        mid = ends[1][split]
        cell_t = np.concatenate([cell_t[split], cell_t[split]])
        cell_lo, cell_hi = (np.concatenate([cell_lo[split], mid]),
                            np.concatenate([mid, cell_hi[split]]))
    # pieces apart by less than the contact tolerance are one (at a vertex entering the
    # strip a contact's span starts from zero: its slack's root is the cell's end, give
    # or take rounding)
    return _merge_intervals(np.concatenate(found) if found else np.zeros((0, 3)), th.size,
                            atol)


def _evaluate_batched(polygon: Polygon, jaw: ParallelJaw, th: FloatArray, c: FloatArray,
                      margin: float, hole: int | None) -> tuple[PoseContacts, FloatArray]:
    """:func:`_evaluate` in batches of :data:`POSE_BATCH` poses, joined."""
    parts = [_evaluate(polygon, jaw, th[i:i + POSE_BATCH], c[i:i + POSE_BATCH], margin, hole)
             for i in range(0, max(th.size, 1), POSE_BATCH)]
    if len(parts) == 1:
        return parts[0]
    fields = {k: np.concatenate([getattr(p[0], k) for p in parts])
              for k in PoseContacts.__dataclass_fields__}
    return PoseContacts(**fields), np.concatenate([p[1] for p in parts])


def _merge_intervals(rows: FloatArray, count: int, tol: float) -> list[FloatArray]:
    """Rows ``(index, lo, hi)`` joined into sorted disjoint intervals per index (pieces
    that touch within ``tol`` are one)."""
    out: list[list[list[float]]] = [[] for _ in range(count)]
    for k, lo, hi in rows[np.lexsort((rows[:, 1], rows[:, 0]))]:
        cur = out[int(k)]
        if cur and lo <= cur[-1][1] + tol:
            cur[-1][1] = max(cur[-1][1], hi)
        else:
            cur.append([lo, hi])
    return [np.array(c, dtype=float).reshape(-1, 2) for c in out]


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
    the hole ``hole``, an index into the part's holes, the closed jaws put in at
    ``insert``: :func:`insertion_point`); ``features``: the part's edges each pad touches
    at some checked pose of the box (the contact features over the box; a vertex as the
    edges that meet there)."""

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
    certified: bool = False
    insert: FloatArray | None = None
    features: tuple[list[int], list[int]] = ([], [])

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
            "insert": self.insert,
            "theta_rad": list(self.theta), "theta_deg": list(np.degrees(self.theta)),
            "offset": list(self.offset), "opening": list(self.opening),
            "contacts": {"a": {"kind": self.kinds[0], "points": self.contacts[0],
                               "stop": self.stops[0], "edges": self.features[0]},
                         "b": {"kind": self.kinds[1], "points": self.contacts[1],
                               "stop": self.stops[1], "edges": self.features[1]}},
            "measure": self.measure, "centre": list(self.centre), "centroid": self.centroid,
            "certified": self.certified,
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


# ----------------------------------------------------------------------------- certificates


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


def _arc_of(vectors: FloatArray) -> tuple[FloatArray, FloatArray, np.ndarray]:
    """The smallest arcs (centre, half-width) holding the directions of each row of
    ``vectors`` (B, k, 2) (corners of a convex set), and where there is none (the set may
    hold the origin)."""
    ang = np.arctan2(vectors[..., 1], vectors[..., 0])
    rel = wrap(ang - ang[:, :1])
    lo, hi = rel.min(axis=1), rel.max(axis=1)
    none = (hi - lo >= np.pi - TOL) | (np.min(np.hypot(vectors[..., 0], vectors[..., 1]),
                                               axis=1) <= 0)
    return ang[:, 0] + (lo + hi) / 2, (hi - lo) / 2, none


@dataclass
class _Candidates:
    """Everything a pad may touch at some pose of each box of a batch (B boxes): up to
    :data:`MAX_CONTACTS` point sets (segments ``p0-p1`` (B, K, 2), a point when equal)
    with their contact force's direction as an arc (``centre``, ``half`` (B, K)),
    ``valid`` (B, K); bounds ``lo``, ``hi`` (B,) of the pad's stop over the box; ``ok``
    (B,): False where no feature surely reaches the strip or too many may touch."""

    p0: FloatArray
    p1: FloatArray
    centre: FloatArray
    half: FloatArray
    valid: np.ndarray
    lo: FloatArray
    hi: FloatArray
    ok: np.ndarray


def _pad_candidates(polygon: Polygon, ring: np.ndarray, sign: float, internal: bool,
                    boxes: FloatArray, half: float, ahead: np.ndarray | None = None
                    ) -> _Candidates:
    """The pad of ``sign`` (+1: pad A of an external grip, the extreme of ``sign * y``)
    over each box ``(t0, t1, c0, c1)`` of ``boxes`` (B, 4): a superset of its contacts
    (``ok`` False when too many features could touch: more than :data:`MAX_CONTACTS`,
    as :func:`jaw_poses`).  Inside a hole, ``ahead`` (B, m): the edges ahead of the pad
    (on its side of the closed jaws) at every pose of the box."""
    t0, t1, c0, c1 = (boxes[:, k:k + 1] for k in range(4))        # (B, 1) each
    B = len(boxes)
    cen = polygon.centroid
    a = polygon.starts[ring] - cen
    b = polygon.ends[ring] - cen
    m = len(a)
    f = -polygon.normals[ring]                          # the force on the part at an edge
    # y = p . u = px cos t + py sin t;  x = p . n = -px sin t + py cos t
    if internal:                                        # the edges this pad can meet
        fy_lo, fy_hi = _sin_range(f[:, 0], f[:, 1], t0, t1)
        pad_force = -sign                               # the force's sign along u
        maybe = fy_hi > 0 if pad_force > 0 else fy_lo < 0
        surely = fy_lo > 0 if pad_force > 0 else fy_hi < 0
        if ahead is not None:
            maybe, surely = maybe & ahead, surely & ahead
    else:
        # only an edge facing the pad (outward normal towards it) can hold its extreme:
        # below the strip's side line a part's boundary point faces away
        nu_lo, nu_hi = _sin_range(sign * polygon.normals[ring][:, 0],
                                  sign * polygon.normals[ring][:, 1], t0, t1)
        maybe = nu_hi > CONTACT_TOL
        surely = np.ones((B, m), dtype=bool)
    ends = np.concatenate([a, b])
    y_lo, y_hi = _sin_range(sign * ends[:, 0], sign * ends[:, 1], t0, t1)      # (B, 2m)
    x_lo, x_hi = _sin_range(ends[:, 1], -ends[:, 0], t0, t1)
    ok2 = np.concatenate([maybe, maybe], axis=1)
    sure2 = np.concatenate([surely, surely], axis=1)
    # a lower bound of the stop: a vertex inside the strip at every pose of the box
    always = sure2 & (x_lo >= c1 - half) & (x_hi <= c0 + half)
    lower = np.max(np.where(always, y_lo, -np.inf), axis=1)
    # an edge point inside the strip at every pose: the one at the strip's centre line
    # at the box's centre pose, if its lateral range stays inside
    tm, cm = (t0 + t1) / 2, (c0 + c1) / 2
    xa_m = -a[:, 0] * np.sin(tm) + a[:, 1] * np.cos(tm)
    xb_m = -b[:, 0] * np.sin(tm) + b[:, 1] * np.cos(tm)
    dx_m = xb_m - xa_m
    with np.errstate(divide="ignore", invalid="ignore"):
        tt = np.where(np.abs(dx_m) > 0, (cm - xa_m) / dx_m, np.nan)
    good = surely & (tt >= 0) & (tt <= 1)
    ttg = np.where(good, tt, 0.0)
    pts = a + ttg[..., None] * (b - a)                                         # (B, m, 2)
    px_lo, px_hi = _sin_range(pts[..., 1], -pts[..., 0], t0, t1)
    py_lo, _ = _sin_range(sign * pts[..., 0], sign * pts[..., 1], t0, t1)
    inside = good & (px_lo >= c1 - half) & (px_hi <= c0 + half)
    lower = np.maximum(lower, np.max(np.where(inside, py_lo, -np.inf), axis=1))
    # vertices that may be in the strip and reach the lower bound (one entry per point:
    # an edge's end is the next edge's start)
    vert = ok2 & (x_hi >= c0 - half) & (x_lo <= c1 + half) & (y_hi >= lower[:, None])
    uniq, inv = np.unique(ends, axis=0, return_inverse=True)
    vmask = np.zeros((B, len(uniq)), dtype=bool)
    rows, cols = np.nonzero(vert)
    vmask[rows, inv.ravel()[cols]] = True
    high = np.max(np.where(vert, y_hi, -np.inf), axis=1)
    # a vertex (or a level edge) touches the pad's face: its force is the pad's, -sign u
    face = ((t0 + t1) / 2)[:, 0] + (0.0 if sign < 0 else np.pi)
    face_half = ((t1 - t0) / 2)[:, 0]
    P0 = [np.broadcast_to(uniq, (B, len(uniq), 2))]
    P1 = [P0[0]]
    cen_f = [np.broadcast_to(face[:, None], vmask.shape)]
    half_f = [np.broadcast_to(face_half[:, None], vmask.shape)]
    use = [vmask]
    # edge cuts by the strip's sides: the pad's corner on the edge (the lateral ranges of
    # the edges' ends are those of the vertices above: starts first, then ends)
    xa_lo, xa_hi = x_lo[:, :m], x_hi[:, :m]
    dxr_lo, dxr_hi = _sin_range(b[:, 1] - a[:, 1], -(b[:, 0] - a[:, 0]), t0, t1)
    e_lo, e_hi = np.minimum(xa_lo, x_lo[:, m:]), np.maximum(xa_hi, x_hi[:, m:])
    # a cut is the extreme of its clipped edge only if the edge rises (for this pad)
    # towards the strip's side there: drop the cuts where it surely falls
    dy_lo, dy_hi = _sin_range(sign * (b[:, 0] - a[:, 0]), sign * (b[:, 1] - a[:, 1]), t0, t1)
    # (an edge along u at the box's edge, dx = 0, has its extreme at a vertex: its cut is
    # dropped with the side it leans to inside the box, soundly; a level edge keeps both)
    zero = CONTACT_TOL * polygon.size                   # dx = 0 at a critical angle
    rise_sign = np.where(dy_lo > 0, 1, np.where(dy_hi < 0, -1, 0)) * \
        np.where(dxr_lo >= -zero, 1, np.where(dxr_hi <= zero, -1, 0))
    # the edge may turn along u: its cut can be anywhere on it
    turns = (dxr_lo <= 0) & (dxr_hi >= 0)
    edge_force = np.arctan2(f[:, 1], f[:, 0])
    for side in (-half, half):
        s_lo, s_hi = c0 + side, c1 + side
        falls = rise_sign * np.sign(side) < 0
        sel = maybe & (e_hi >= s_lo) & (e_lo <= s_hi) & ~falls
        with np.errstate(divide="ignore", invalid="ignore"):
            q = np.stack([(s_lo - xa_hi) / dxr_lo, (s_hi - xa_lo) / dxr_lo,
                          (s_lo - xa_hi) / dxr_hi, (s_hi - xa_lo) / dxr_hi])
        t_lo = np.where(turns, 0.0, np.maximum(0.0, q.min(axis=0)))
        t_hi = np.where(turns, 1.0, np.minimum(1.0, q.max(axis=0)))
        sel &= t_lo <= t_hi
        t_lo, t_hi = np.where(sel, t_lo, 0.0), np.where(sel, t_hi, 0.0)
        p0 = a + t_lo[..., None] * (b - a)
        p1 = a + t_hi[..., None] * (b - a)
        _, h0 = _sin_range(sign * p0[..., 0], sign * p0[..., 1], t0, t1)
        _, h1 = _sin_range(sign * p1[..., 0], sign * p1[..., 1], t0, t1)
        hh = np.maximum(h0, h1)
        sel &= hh >= lower[:, None]
        high = np.maximum(high, np.max(np.where(sel, hh, -np.inf), axis=1))
        P0.append(p0)
        P1.append(p1)
        cen_f.append(np.broadcast_to(edge_force, sel.shape))
        half_f.append(np.zeros(sel.shape))
        use.append(sel)
    use_all = np.concatenate(use, axis=1)
    count = use_all.sum(axis=1)
    ok = np.isfinite(lower) & (count >= 1) & (count <= MAX_CONTACTS)
    # the candidates first, at most MAX_CONTACTS of them
    order = np.argsort(~use_all, axis=1, kind="stable")[:, :MAX_CONTACTS]
    r = np.arange(B)[:, None]

    def pick(parts: list[Any]) -> Any:
        return np.concatenate(parts, axis=1)[r, order]

    return _Candidates(pick(P0), pick(P1), pick(cen_f), pick(half_f), use_all[r, order],
                       lower, high, ok)


def _pairs_hold(ca: _Candidates, cb: _Candidates, beta: float, expand: bool) -> np.ndarray:
    """Per box: every pair of candidate contacts is force closure at every pose of it
    (theorem 6.3: the segment joining the contacts lies strictly inside both friction
    cones, with the directions of both ranging over arcs; squeezing for an external grip,
    expanding inside a hole).  The directions of a pair's chords are the smallest arc
    holding its four corner chords (the chords of two segments form a convex set); none
    when the set may hold the origin."""
    turn = np.pi if expand else 0.0
    holds = np.ones(len(ca.lo), dtype=bool)
    for i in range(ca.valid.shape[1]):
        for j in range(cb.valid.shape[1]):
            corners = np.stack([cb.p0[:, j] - ca.p0[:, i], cb.p0[:, j] - ca.p1[:, i],
                                cb.p1[:, j] - ca.p0[:, i], cb.p1[:, j] - ca.p1[:, i]],
                               axis=1)                                         # (B, 4, 2)
            d, hd, no_arc = _arc_of(corners)
            # squeezing, A's force is within beta of every direction A -> B and B's of
            # B -> A; expanding, of the opposite directions
            fail = (no_arc
                    | (np.abs(wrap(d + turn - ca.centre[:, i])) + hd + ca.half[:, i] >= beta)
                    | (np.abs(wrap(d + np.pi + turn - cb.centre[:, j])) + hd
                       + cb.half[:, j] >= beta))
            holds &= ~(ca.valid[:, i] & cb.valid[:, j] & fail)
    return holds


def _hole_sides(polygon: Polygon, ring: np.ndarray, q: FloatArray, boxes: FloatArray,
                half: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Over each box (B, 4) of an internal grip with insertion point ``q`` (from the
    centroid): the hole's edges wholly above the insertion height at every pose, those
    wholly below (B, m), and whether every edge that may meet the strip is one or the
    other (B,): the closed jaws' segment is then free at every pose."""
    t0, t1, c0, c1 = (boxes[:, k:k + 1] for k in range(4))
    a = polygon.starts[ring] - polygon.centroid
    b = polygon.ends[ring] - polygon.centroid
    ya_lo, ya_hi = _sin_range(a[:, 0], a[:, 1], t0, t1)
    yb_lo, yb_hi = _sin_range(b[:, 0], b[:, 1], t0, t1)
    xa_lo, xa_hi = _sin_range(a[:, 1], -a[:, 0], t0, t1)
    xb_lo, xb_hi = _sin_range(b[:, 1], -b[:, 0], t0, t1)
    yq_lo, yq_hi = _sin_range(q[0], q[1], t0, t1)
    may_meet = (np.maximum(xa_hi, xb_hi) >= c0 - half) & (np.minimum(xa_lo, xb_lo) <= c1 + half)
    up = np.minimum(ya_lo, yb_lo) > yq_hi
    down = np.maximum(ya_hi, yb_hi) < yq_lo
    return up, down, ~np.any(may_meet & ~up & ~down, axis=1)


#: Sub-boxes :func:`certify_box` examines at a time.
CERTIFY_BATCH = 512


def certify_box(polygon: Polygon, jaw: ParallelJaw, theta: Any, offset: Any,
                margin: float = DEFAULT_MARGIN_DEG, hole: int | None = None,
                max_boxes: int = 4096) -> tuple[float, float] | None:
    """Prove that **every** pose of the box ``theta = (t0, t1)``, ``offset = (c0, c1)``
    holds (the model of :func:`jaw_poses`): the box is cut into sub-boxes until, in each,
    the features each pad may touch at some pose (vertices that may lie in the strip and
    reach a lower bound of the pad's stop; the strip's sides cut edges on segments
    enclosed by interval arithmetic; all bounds of ``a cos t + b sin t`` exact) are
    few, every pair of them is force closure over all its positions and directions
    (theorem 6.3 on arcs of directions), and the opening's enclosure is within the
    stroke.  Returns that enclosure of the opening over the box, or None when the proof
    fails within ``max_boxes`` sub-boxes, or when a sub-box's centre pose does not hold
    (then the box does not hold either).  Sound, not complete: None does not say that
    some pose fails.  The sub-boxes are examined in batches, level by level.

    >>> from fcgrasp.io.parts import demo_part
    >>> jaw = ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
    >>> lo, hi = certify_box(demo_part("rectangle"), jaw, np.radians([80, 100]), (-30, 30))
    >>> bool(10 <= lo <= 30 and 30 / np.cos(np.radians(10)) <= hi <= 50)   # encloses 30-30.46
    True
    """
    t0, t1 = (float(v) for v in theta)
    c0, c1 = (float(v) for v in offset)
    if not (t1 >= t0 and c1 >= c0 and t1 - t0 < np.pi):
        raise ValueError(f"theta and offset must be increasing ranges (theta under pi), "
                         f"got {theta!r}, {offset!r}")
    margin = _check_jaw_args(polygon, jaw, margin)
    max_boxes = check_int(max_boxes, "max_boxes", minimum=1)
    internal = hole is not None
    ring = _grip_edges(polygon, hole)
    if t1 - t0 < np.pi / 2:
        ring = _near_strip(polygon, ring, t0, t1, c0, c1, jaw.pad_width / 2)
    beta = float(shrunk_half_angle(jaw.mu, margin))
    if beta <= 0:
        return None
    half = jaw.pad_width / 2
    radius = characteristic_length(polygon.vertices, polygon.centroid)
    q = None if hole is None else insertion_point(polygon, hole) - polygon.centroid
    # cut the box at the critical angles, where an edge turns parallel to u (its facing
    # and its lateral direction change sign there): no sub-box straddles one
    d = polygon.ends[ring] - polygon.starts[ring]
    crit = np.mod(np.arctan2(d[:, 1], d[:, 0]), np.pi)
    crit = np.concatenate([crit + k * np.pi for k in range(int(np.floor(t0 / np.pi)) - 1,
                                                             int(np.ceil(t1 / np.pi)) + 1)])
    cuts = np.unique(np.r_[t0, crit[(crit > t0) & (crit < t1)], t1])
    todo = np.column_stack([cuts[:-1], cuts[1:], np.full(cuts.size - 1, c0),
                            np.full(cuts.size - 1, c1)])
    lo_open, hi_open = np.inf, -np.inf
    done = 0
    sa, sb = (-1.0, 1.0) if internal else (1.0, -1.0)
    while len(todo):
        centre_holds = None
        boxes, todo = todo[:CERTIFY_BATCH], todo[CERTIFY_BATCH:]
        done += len(boxes)
        if done > max_boxes:
            return None
        if q is not None:
            # the closed jaws' segment free at every pose (each edge that may meet the
            # strip wholly above or below the insertion height), and inside the hole at
            # the centre pose, hence at every pose (the segment's middle would have to
            # cross an edge to leave); pad A meets only edges above, pad B below
            up, down, free = _hole_sides(polygon, ring, q, boxes, half)
            ca = _pad_candidates(polygon, ring, sa, internal, boxes, half, up)
            cb = _pad_candidates(polygon, ring, sb, internal, boxes, half, down)
            centre_holds = jaw_poses(polygon, jaw, (boxes[:, 0] + boxes[:, 1]) / 2,
                                     (boxes[:, 2] + boxes[:, 3]) / 2, margin, hole).holds
            proved = ca.ok & cb.ok & free & centre_holds
        else:
            ca = _pad_candidates(polygon, ring, sa, internal, boxes, half)
            cb = _pad_candidates(polygon, ring, sb, internal, boxes, half)
            proved = ca.ok & cb.ok
        # the stops as heights along u: sign * stop lies in [lo, hi]
        a_lo, a_hi = np.minimum(sa * ca.lo, sa * ca.hi), np.maximum(sa * ca.lo, sa * ca.hi)
        b_lo, b_hi = np.minimum(sb * cb.lo, sb * cb.hi), np.maximum(sb * cb.lo, sb * cb.hi)
        with np.errstate(invalid="ignore"):
            o_lo, o_hi = a_lo - b_hi, a_hi - b_lo
            proved &= (jaw.stroke[0] <= o_lo) & (o_hi <= jaw.stroke[1])
        proved &= _pairs_hold(ca, cb, beta, internal)
        if proved.any():
            lo_open = min(lo_open, float(o_lo[proved].min()))
            hi_open = max(hi_open, float(o_hi[proved].max()))
        rest = boxes[~proved]
        if not len(rest):
            continue
        # a sub-box whose centre pose fails cannot be proved: neither can the box (inside
        # a hole every centre pose was evaluated above)
        if centre_holds is None:
            centre_holds = jaw_poses(polygon, jaw, (rest[:, 0] + rest[:, 1]) / 2,
                                     (rest[:, 2] + rest[:, 3]) / 2, margin, hole).holds
        else:
            centre_holds = centre_holds[~proved]
        if not centre_holds.all():
            return None
        bt0, bt1, bc0, bc1 = rest.T
        by_angle = (bt1 - bt0) * radius >= bc1 - bc0
        mt, mc = (bt0 + bt1) / 2, (bc0 + bc1) / 2
        first = np.column_stack([bt0, np.where(by_angle, mt, bt1), bc0,
                                 np.where(by_angle, bc1, mc)])
        second = np.column_stack([np.where(by_angle, mt, bt0), bt1,
                                  np.where(by_angle, bc0, mc), bc1])
        todo = np.concatenate([todo, first, second])
    return lo_open, hi_open


def jaw_plans(polygon: Polygon, jaw: ParallelJaw, top: int = 5,
              margin: float = DEFAULT_MARGIN_DEG, internal: bool = True,
              certify: bool = True) -> list[JawPlan]:
    """The ``top`` largest boxes of jaw poses that hold, best first (see the module's
    docstring): external grips, and with ``internal`` grips inside each hole (the jaws
    put in at its :func:`insertion_point`).  For each grip, each found box's poses are
    removed from the grid before the next is sought, with their mirror (``theta + pi``,
    ``-c``: the same grasp, pads swapped).  With ``certify`` (the default) each box is
    also *proved* by :func:`certify_box` (shrunk by up to :data:`CERTIFY_SHRINKS` grid
    steps until the proof succeeds within :data:`CERTIFY_BOXES` sub-boxes; a box it cannot prove is
    dropped and the next one sought), then grown to the exact boundary of the set
    (:func:`holding_offsets`), moved in by :data:`GROW_BACKOFF` and proved again, kept
    where it measures more: every returned plan then has ``certified`` True.
    ``certify=False`` returns the boxes verified on the fine grid only.

    >>> from fcgrasp.io.parts import demo_part
    >>> jaw = ParallelJaw(stroke=(10, 50), pad_width=8, mu=0.5)
    >>> best = jaw_plans(demo_part("rectangle"), jaw, top=1)[0]   # across the 30 mm
    >>> [round(float(np.degrees(t)), 1) % 180 for t in best.theta], best.kinds
    ([77.9, 102.1], ('edge', 'edge'))
    >>> best.certified, round(best.offset[1], 2)       # proved: every pose of the box holds
    (True, 39.78)
    >>> grid = jaw_plans(demo_part("rectangle"), jaw, top=1, certify=False)[0]
    >>> [round(float(np.degrees(t))) % 180 for t in grid.theta], grid.certified
    ([78, 102], False)
    """
    margin = _check_jaw_args(polygon, jaw, margin)
    top = check_int(top, "top", minimum=1)
    if not isinstance(internal, bool):
        raise TypeError(f"internal must be a bool, got {internal!r}")
    if not isinstance(certify, bool):
        raise TypeError(f"certify must be a bool, got {certify!r}")
    holes: list[int | None] = [None]
    if internal:
        holes += list(range(len(polygon.holes)))
    plans = [p for h in holes for p in _grip_plans(polygon, jaw, top, margin, h, certify)]
    plans.sort(key=lambda p: -p.measure)
    return plans[:top]


def _proved(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
            th: tuple[float, float], off: tuple[float, float], dth: float, dc: float
            ) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The box, shrunk by whole grid steps (at most :data:`CERTIFY_SHRINKS`) until
    :func:`certify_box` proves it; None when it cannot."""
    for k in range(CERTIFY_SHRINKS + 1):
        t = (th[0] + k * dth, th[1] - k * dth)
        c = (off[0] + k * dc, off[1] - k * dc)
        if t[1] < t[0] or c[1] < c[0]:
            return None
        budget = CERTIFY_BOXES if k else CERTIFY_BOXES // 8
        if certify_box(polygon, jaw, t, c, margin, hole, max_boxes=budget):
            return t, c
    return None


#: A grown box is moved in from the set's boundary by these fractions of a grid step
#: until it is proved (a box on the boundary cannot be: its sub-boxes would have to
#: shrink to nothing there), each try with that many times :data:`CERTIFY_BOXES`
#: sub-boxes (the sub-boxes a proof needs grow as the inverse of the back-off:
#: ``demo:rectangle`` 7,900 at half a step, 15,800 at a quarter, 32,200 at an eighth).
GROW_BACKOFF = ((0.25, 5.0), (0.5, 2.5))


def _reach(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
           thetas: FloatArray, anchor: float, step: float, side: int) -> float | None:
    """How far from ``anchor`` (an offset at which every angle of ``thetas`` holds) the
    exact slices (:func:`holding_offsets`) hold at every one of ``thetas``, towards
    ``side`` (+1: larger offsets): the nearest end of the slices' intervals through
    ``anchor``.  Windows of ``2 * step`` are added until it is found (None: no interval
    through the anchor at some angle)."""
    tol = CONTACT_TOL * polygon.size
    far = anchor
    reach_max = characteristic_length(polygon.vertices, polygon.centroid) + jaw.pad_width
    while True:
        near, far = far, far + side * 2 * step
        window = (min(near, far), max(near, far))
        slices = holding_offsets(polygon, jaw, thetas, margin, hole, window)
        ends = []
        for iv in slices:
            # the interval through the window's end next to the anchor
            at = (iv[:, 0] <= window[0] + tol) if side > 0 else (iv[:, 1] >= window[1] - tol)
            if not at.any():
                return None if near == anchor else near
            ends.append(iv[at][0, 1] if side > 0 else iv[at][-1, 0])
        end = min(ends) if side > 0 else max(ends)
        if abs(end - far) > tol or abs(far) > reach_max:
            return end


def _holds_across(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
                  thetas: FloatArray, c0: float, c1: float) -> np.ndarray:
    """Whether the exact slice at each angle holds at every offset of ``[c0, c1]``."""
    tol = CONTACT_TOL * polygon.size
    return np.array([iv.shape[0] == 1 and iv[0, 0] <= c0 + tol and iv[0, 1] >= c1 - tol
                     for iv in holding_offsets(polygon, jaw, thetas, margin, hole,
                                               (c0, c1))])


def _grown(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
           th: tuple[float, float], off: tuple[float, float], dth: float, dc: float
           ) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """A box found on the grid grown to the exact boundary of the holding set, the
    dimension that limits its measure first: its offset range to the nearest ends of the
    exact slices at :data:`CHECK_DENSITY` angles per grid step across it
    (:func:`holding_offsets`), and its angle range, with the offset range fixed, by
    bisection (to 1/4096 of a fine step) to the first angle whose slice does not hold
    across it.  None when the slices disagree with the grid."""
    (t0, t1), (c0, c1) = th, off
    radius = characteristic_length(polygon.vertices, polygon.centroid)
    fine = dth / CHECK_DENSITY

    def offsets(t0: float, t1: float, c0: float, c1: float) -> tuple[float, float] | None:
        lines = np.linspace(t0, t1, max(2, int(round((t1 - t0) / fine)) + 1))
        mid = (c0 + c1) / 2
        lo = _reach(polygon, jaw, margin, hole, lines, min(c0 + dc, mid), dc, -1)
        hi = _reach(polygon, jaw, margin, hole, lines, max(c1 - dc, mid), dc, +1)
        return None if lo is None or hi is None or hi <= lo else (lo, hi)

    def angles(t0: float, t1: float, c0: float, c1: float) -> tuple[float, float]:
        grown = [t0, t1]
        for k, side in ((1, 1), (0, -1)):
            edge = grown[k]
            probes = edge + side * fine * np.arange(1, 2 * CHECK_DENSITY + 1)
            room = np.pi - 2 * dth - (grown[1] - grown[0])   # certify_box: under half a turn
            probes = probes[np.abs(probes - edge) < room]
            ok = _holds_across(polygon, jaw, margin, hole, probes, c0, c1)
            n_ok = int(np.argmin(ok)) if not ok.all() else ok.size
            good = edge + side * fine * n_ok
            if n_ok < probes.size:
                bad = probes[n_ok]
                for _ in range(12):
                    t = (good + bad) / 2
                    if _holds_across(polygon, jaw, margin, hole, np.array([t]), c0, c1)[0]:
                        good = t
                    else:
                        bad = t
            grown[k] = good
        return grown[0], grown[1]

    if (t1 - t0) * radius < c1 - c0:
        t0, t1 = angles(t0, t1, c0, c1)
    found = offsets(t0, t1, c0, c1)
    if found is None:
        return None
    c0, c1 = found
    t0, t1 = angles(t0, t1, c0, c1)
    return (t0, t1), (c0, c1)


def _proved_grown(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
                  th: tuple[float, float], off: tuple[float, float], dth: float, dc: float
                  ) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The grown box (:func:`_grown`) moved in from the boundary by each of
    :data:`GROW_BACKOFF` (fractions of a grid step) until :func:`certify_box` proves it;
    None when it cannot (the grid box is then proved instead)."""
    grown = _grown(polygon, jaw, margin, hole, th, off, dth, dc)
    if grown is None:
        return None
    (t0, t1), (c0, c1) = grown
    for f, budget in GROW_BACKOFF:
        t = (t0 + f * dth, t1 - f * dth)
        c = (c0 + f * dc, c1 - f * dc)
        if t[1] < t[0] or c[1] < c[0]:
            return None
        if certify_box(polygon, jaw, t, c, margin, hole,
                       max_boxes=int(budget * CERTIFY_BOXES)):
            return t, c
    return None


def _measure(theta: tuple[float, float], offset: tuple[float, float], radius: float
             ) -> float:
    """The ranking measure of a box: ``min(c1 - c0, (t1 - t0) * radius)``."""
    return min(offset[1] - offset[0], (theta[1] - theta[0]) * radius)


def _grip_plans(polygon: Polygon, jaw: ParallelJaw, top: int, margin: float,
                hole: int | None, certify: bool = True) -> list[JawPlan]:
    """The best boxes of one grip (external, or internal in ``hole``)."""
    radius = characteristic_length(polygon.vertices, polygon.centroid)
    K = int(round(360 / THETA_STEP_DEG))
    M = OFFSET_STEPS
    thetas = np.arange(K) * (2 * np.pi / K)
    reach = radius + jaw.pad_width / 2
    offsets = np.linspace(-reach, reach, M)
    dth, dc = 2 * np.pi / K, offsets[1] - offsets[0]
    H = _pose_grid(polygon, jaw, margin, hole, thetas, offsets)
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
        if certify:
            # the grid box proved (shrunk by grid steps), then grown to the exact
            # boundary and proved, kept where that measures more (the back-off from
            # the boundary can cost more than the growth gives)
            proved = _proved(polygon, jaw, margin, hole, box[0], box[1], dth, dc)
            if proved is not None:
                grown = _proved_grown(polygon, jaw, margin, hole, box[0], box[1], dth, dc)
                if grown is not None and _measure(*grown, radius) > _measure(*proved, radius):
                    proved = grown
            if proved is None:
                continue
            # the opening range over the proved box's checked poses
            box = _checked_box(polygon, jaw, margin, hole, np.array(proved[0]),
                               np.array(proved[1]), dth, dc)
            if box is None:
                continue
        (t0, t1), (c0, c1), opening, features = box
        tc, ccen = (t0 + t1) / 2, (c0 + c1) / 2
        r = jaw_poses(polygon, jaw, [tc], [ccen], margin, hole)
        pts = [_contact_points(polygon, tc, r.lat_a[0], float(r.top[0])),
               _contact_points(polygon, tc, r.lat_b[0], float(r.bottom[0]))]
        kinds = (_kind(r.lat_a[0], r.psi_a[0], polygon.size),
                 _kind(r.lat_b[0], r.psi_b[0], polygon.size))
        plans.append(JawPlan((float(t0), float(t1)), (float(c0), float(c1)), opening, pts,
                             kinds, (float(r.top[0]), float(r.bottom[0])),
                             _measure((t0, t1), (c0, c1), radius), jaw,
                             polygon.centroid.copy(), radius,
                             "external" if hole is None else "internal", hole, certify,
                             None if hole is None else insertion_point(polygon, hole),
                             features))
    return plans


#: A part with more edges than this evaluates the pose grid in tiles (each tile's poses
#: meet only the edges near its strips); fewer, in large batches.
TILE_AFTER_EDGES = 64
#: Grid rows and columns of a tile.
TILE = (16, 20)


def _pose_grid(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
               thetas: np.ndarray, offsets: np.ndarray) -> np.ndarray:
    """Whether each pose of the grid ``thetas x offsets`` holds (K, M)."""
    K, M = thetas.size, offsets.size
    if polygon.n_edges <= TILE_AFTER_EDGES:
        tt, cc = np.meshgrid(thetas, offsets, indexing="ij")
        return np.concatenate([
            jaw_poses(polygon, jaw, tt.ravel()[i:i + POSE_BATCH], cc.ravel()[i:i + POSE_BATCH],
                      margin, hole).holds
            for i in range(0, tt.size, POSE_BATCH)]).reshape(K, M)
    H = np.zeros((K, M), dtype=bool)
    for k in range(0, K, TILE[0]):
        for j in range(0, M, TILE[1]):
            tt, cc = np.meshgrid(thetas[k:k + TILE[0]], offsets[j:j + TILE[1]], indexing="ij")
            H[k:k + TILE[0], j:j + TILE[1]] = jaw_poses(
                polygon, jaw, tt.ravel(), cc.ravel(), margin, hole).holds.reshape(tt.shape)
    return H


def _checked_box(polygon: Polygon, jaw: ParallelJaw, margin: float, hole: int | None,
                 th: FloatArray, off: FloatArray, dth: float, dc: float
                 ) -> tuple[tuple[float, float], tuple[float, float],
                            tuple[float, float], tuple[list[int], list[int]]] | None:
    """Shrink a box by grid steps until every pose of a grid :data:`CHECK_DENSITY`
    times finer holds; returns ``(theta range, offset range, opening range, the edges
    each pad touches at those poses)`` or None."""
    (t0, t1), (c0, c1) = th, off
    for _ in range(4):
        if t1 < t0 or c1 < c0:
            return None
        nt = max(2, int(round((t1 - t0) / dth)) * CHECK_DENSITY + 1)
        nc = max(2, int(round((c1 - c0) / dc)) * CHECK_DENSITY + 1)
        grid = np.meshgrid(np.linspace(t0, t1, nt), np.linspace(c0, c1, nc), indexing="ij")
        tt, cc = grid[0].ravel(), grid[1].ravel()
        opening = [np.inf, -np.inf]
        edges: tuple[set[int], set[int]] = (set(), set())
        # in batches, stopping at the first pose that fails
        for i in range(0, tt.size, POSE_BATCH):
            r = jaw_poses(polygon, jaw, tt[i:i + POSE_BATCH], cc[i:i + POSE_BATCH], margin,
                          hole)
            if not np.all(r.holds):
                break
            opening = [min(opening[0], float(r.opening.min())),
                       max(opening[1], float(r.opening.max()))]
            edges[0].update(r.edge_a[r.edge_a >= 0].tolist())
            edges[1].update(r.edge_b[r.edge_b >= 0].tolist())
        else:
            return ((t0, t1), (c0, c1), (opening[0], opening[1]),
                    (sorted(edges[0]), sorted(edges[1])))
        t0, t1, c0, c1 = t0 + dth, t1 - dth, c0 + dc, c1 - dc
    return None
