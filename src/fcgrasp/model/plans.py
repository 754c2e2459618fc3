"""A grasp plan, the result of :func:`fcgrasp.plan`, and the keys that order plans.

:class:`Plan` is what the plans of every gripper offer, on a polygon or a solid.

:class:`GraspPlan` holds an edge per finger and an independent region on each
(definition 7.1), with its quality (section 8.1) computed on first use.  Plans are
sorted by :func:`rank_key`: the chosen measure of :mod:`fcgrasp.model.ranking`, the leximin
order of the region lengths (:func:`leximin_key`), then :func:`geometric_key`, which does
not depend on how the part's vertices are numbered.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol, cast, runtime_checkable

import numpy as np

from ..core._checks import FloatArray
from ..core._geom import RANK_DIGITS as _DIGITS
from ..core._geom import along, geometric_key, leximin_key
from ..core._json import json_ready
from ..core.budget import PlanList
from ..core.contacts import FrictionlessPoint, FrictionPoint, Gravity
from ..core.grasp import Grasp
from ..core.tolerances import TINY
from .polygon import Polygon, check_polygon
from .quality import quality_of
from .ranking import MEASURES

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = ["Plan", "GraspPlan", "PlanList", "leximin_key", "geometric_key", "rank_key",
           "check_point_plan"]


@runtime_checkable
class Plan(Protocol):
    """What every plan offers, whatever its gripper and its part (a typing protocol:
    :class:`GraspPlan` of point fingers, :class:`~fcgrasp.grippers.jaw.JawPlan` of the
    parallel jaw, and a solid's :class:`~fcgrasp.spatial.SoftPairPlan`,
    :class:`~fcgrasp.spatial.PointTriplePlan` and :class:`~fcgrasp.spatial.SolidJawPlan`).

    ``measure``: the size of its independent regions, larger is better (the smallest
    region's length of point fingers, definition 7.1; the jaw's box ``min(c1 - c0, (t1 -
    t0) radius)``; a solid's regions' radius); ``regions``: each finger's region (a
    polyline along the outline, a ring of 3-D points on a facet; the jaw's box of poses
    ``(theta, offset)``, each a range); ``contacts``: its representative grasp's contact
    points, one per finger (each of the jaw's pads: its points at the box's centre
    pose); ``similar``: the plans it stands for as a distinct alternative; ``to_dict()``:
    its JSON object in the plan report (``fcgrasp/schema``)."""

    @property
    def measure(self) -> float: ...

    @property
    def regions(self) -> Any: ...

    @property
    def contacts(self) -> Any: ...

    @property
    def similar(self) -> Any: ...

    def to_dict(self) -> dict[str, Any]: ...


@dataclass
class GraspPlan:
    """One planned grasp: an edge per finger and an independent region on each.

    Attributes
    ----------
    edges : tuple of int
        Per finger, the edge holding its representative contact (input numbering).
    regions : tuple of ndarray, shape (m_i, 2)
        Each region as a polyline along the boundary, from one end to the other through
        the vertices it covers (two points when it stays on one edge).  An array of
        shape (fingers, 2, 2) is taken as regions on single edges.
    lengths : ndarray, shape (fingers,)
        Arc lengths of the regions.
    contacts : ndarray, shape (fingers, 2)
        The representative grasp: each region's point halfway along it.
    normals : ndarray, shape (fingers, 2)
        Outward normals at the representative contacts (the fingers push along
        ``-normal``).
    contact_type : {"friction", "frictionless"}
    mu : float
    mode : str
        ``"squeeze"``/``"expand"`` for two fingers; ``"+C"``/``"-C"`` for four.
    margin : float
        Safety margin in degrees.
    gravity : dict or None
        ``{"center": [x, y], "direction": [gx, gy]}`` when gravity is a contact.
    centroid, radius, disturbance
        The inputs of the quality measures: the part's centroid and radius (largest
        distance from the centroid to a vertex) and the disturbance (translation in the
        part's units, rotation in degrees) of the resistance measure.
    quality : dict
        ``min_region``, ``resistance``, ``resistance_approx``, ``epsilon_l1``,
        ``epsilon_linf`` (see :mod:`fcgrasp.model.quality`).
    region_edges : tuple of tuple of int
        The edges each region covers, in order along it (default: ``(edges[i],)``).
    similar : tuple of tuple of int
        With distinct plans (``plan(..., distinct=)``), the edges of the lower-ranked
        plans this one stands for (the same alternative); in the JSON as ``similar``.
    payload : RegionPayload or None
        With a load (``plan(..., load=)``), the scale of it every grasp of the regions
        carries within the finger force limits (:func:`fcgrasp.region_payload`).
    """

    edges: tuple[int, ...]
    regions: Any
    lengths: FloatArray
    contacts: FloatArray
    normals: FloatArray
    contact_type: str
    mu: float
    mode: str
    margin: float
    gravity: dict[str, Any] | None = None
    centroid: FloatArray | None = field(default=None, repr=False, compare=False)
    radius: float | None = field(default=None, repr=False, compare=False)
    disturbance: tuple[float, float] = field(default=(10.0, 15.0), repr=False, compare=False)
    region_edges: tuple[tuple[int, ...], ...] = ()
    _quality: dict[str, float] | None = field(default=None, repr=False, compare=False)
    #: the edges of the lower-ranked plans this one stands for (:mod:`fcgrasp.model.distinct`)
    similar: tuple[tuple[int, ...], ...] = field(default=(), repr=False, compare=False)
    #: with a load (``plan(..., load=)``), the scale of it certified over every grasp of
    #: the regions (:class:`~fcgrasp.model.loads.RegionPayload`); in the JSON as ``payload``
    payload: Any = field(default=None, repr=False, compare=False)
    #: picked from above by fingers on finger bodies: where each comes down, the
    #: approach and retreat (:func:`fcgrasp.grippers._tips_pick.tips_pick`)
    pick: Any = field(default=None, repr=False, compare=False)

    def __post_init__(self) -> None:
        self.regions = tuple(np.asarray(r, dtype=float).reshape(-1, 2) for r in self.regions)
        if not self.region_edges:
            self.region_edges = tuple((int(e),) for e in self.edges)
        self.region_edges = tuple(tuple(map(int, r)) for r in self.region_edges)

    @property
    def ends(self) -> FloatArray:
        """Each region's two end points, shape (fingers, 2, 2)."""
        return np.array([[r[0], r[-1]] for r in self.regions]).reshape(-1, 2, 2)

    def segment_normals(self) -> tuple[FloatArray, ...]:
        """Outward normal of every segment of every region (shape (m_i - 1, 2))."""
        out = []
        for line, n in zip(self.regions, self.normals, strict=True):
            d = np.diff(line, axis=0)
            L = np.hypot(d[:, 0], d[:, 1])
            t = d / np.where(L > 0, L, 1.0)[:, None]
            cand = np.c_[t[:, 1], -t[:, 0]]
            # the ring's orientation is the same along a region: take the side that
            # the representative contact's normal takes on its segment
            k = int(np.argmax(np.abs(cand @ n)))   # not a zero-length segment
            sign = 1.0 if cand[k] @ n >= 0 else -1.0
            out.append(sign * cand)
        return tuple(out)

    def normals_at(self, points: ArrayLike) -> FloatArray:
        """Outward normal at a finger position in each region (the nearest segment's;
        at a vertex inside a region either edge's), shape (fingers, 2)."""
        pts = np.asarray(points, dtype=float).reshape(self.fingers, 2)
        out = np.array(self.normals, dtype=float)
        for i, (line, sn) in enumerate(zip(self.regions, self.segment_normals(),
                                           strict=True)):
            if len(line) > 2:
                out[i] = sn[_nearest_segment(line, pts[i])]
        return out

    @property
    def quality(self) -> dict[str, float]:
        """Quality metrics at the representative grasp (computed on first use)."""
        if self._quality is None:
            self._quality = self._compute_quality()
        return self._quality

    def _compute_quality(self) -> dict[str, float]:
        if self.centroid is None or self.radius is None:
            return {"min_region": self.min_length}
        grasp = self.grasp()
        finger = np.concatenate([np.full(len(ct.points), i) for i, ct in
                                 enumerate(grasp.contacts)])
        q = quality_of(grasp.points, grasp.forces, finger, self.centroid, self.radius,
                       self.disturbance[0], self.disturbance[1], finger < self.fingers)
        q["min_region"] = self.min_length
        return q

    @property
    def min_length(self) -> float:
        """Length of the smallest region (the paper's tolerance measure)."""
        return float(np.min(self.lengths))

    @property
    def measure(self) -> float:
        """The :class:`Plan` measure: :attr:`min_length`."""
        return self.min_length

    @property
    def fingers(self) -> int:
        return len(self.edges)

    def contacts_for(self, points: ArrayLike, normals: ArrayLike | None = None) -> list[Any]:
        """The contacts of a grasp with the fingers at ``points`` (normals: the
        region's edge at each point unless given)."""
        pts = np.asarray(points, dtype=float)
        nrm = self.normals_at(pts) if normals is None else np.asarray(normals, float)
        out: list[Any] = []
        for p, n in zip(pts, nrm, strict=True):
            if self.contact_type == "friction":
                out.append(FrictionPoint(p, n, self.mu))
            else:
                out.append(FrictionlessPoint(p, n))
        if self.gravity is not None:
            out.append(Gravity(self.gravity["center"], self.gravity["direction"]))
        return out

    def grasp(self, points: ArrayLike | None = None) -> Grasp:
        """The :class:`~fcgrasp.Grasp` at ``points`` (default: the representative grasp)."""
        if points is None:
            return Grasp(self.contacts_for(self.contacts, self.normals))
        return Grasp(self.contacts_for(points))

    def sample(self, n: int, rng: np.random.Generator | None = None) -> FloatArray:
        """``n`` grasps with each finger uniform (in arc length) in its region, shape
        (n, fingers, 2)."""
        rng = np.random.default_rng() if rng is None else rng
        u = rng.random((n, self.fingers))
        return np.stack([along(line, u[:, i])[0] for i, line in enumerate(self.regions)],
                        axis=1)

    def corners(self) -> FloatArray:
        """All corner grasps of the box of regions (each finger at one end of its
        region), shape (2**fingers, fingers, 2)."""
        idx = np.array(list(np.ndindex(*(2,) * self.fingers)))
        return cast("FloatArray", self.ends[np.arange(self.fingers)[None, :], idx])

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready description (floats rounded to 12 significant digits)."""
        d: dict[str, Any] = {
            "edges": [int(e) for e in self.edges],
            "contact_type": self.contact_type,
            "mu": self.mu,
            "mode": self.mode,
            "regions": [r for r in self.regions],
            "region_edges": [list(r) for r in self.region_edges],
            "region_lengths": self.lengths,
            "min_region_length": self.min_length,
            "contacts": self.contacts,
            "normals": self.normals,
            "quality": dict(sorted(self.quality.items())),
        }
        if self.gravity is not None:
            d["gravity"] = dict(self.gravity)
        if self.similar:
            d["similar"] = [list(e) for e in self.similar]
        if self.payload is not None:
            d["payload"] = self.payload.to_dict()
        if self.pick is not None:
            d.update(self.pick)
        return cast("dict[str, Any]", json_ready(d))


def _nearest_segment(line: FloatArray, p: FloatArray) -> int:
    a, d = line[:-1], np.diff(line, axis=0)
    dd = np.einsum("ij,ij->i", d, d)
    s = np.clip(np.einsum("ij,ij->i", p - a, d) / np.maximum(dd, TINY), 0.0, 1.0)
    q = a + s[:, None] * d
    return int(np.argmin(np.where(dd > 0, np.hypot(*(q - p).T), np.inf)))


def rank_key(p: GraspPlan, polygon: Polygon, rank_by: str = "min_region",
             score: float | None = None) -> tuple[Any, ...]:
    """The sort key of :func:`plan` (smaller is better), independent of numbering.

    ``min_region``: the leximin order of the region lengths (definition 7.1); any other
    measure of :data:`fcgrasp.model.ranking.MEASURES`: its score (larger first, to 9
    significant digits), then the leximin order.  Remaining ties are broken by
    :func:`geometric_key`.
    """
    lex = leximin_key(p.lengths, polygon.size)
    geo = geometric_key(p.ends, polygon)
    if rank_by == "min_region":
        return (lex, geo)
    q = MEASURES[rank_by].score([p])[0] if score is None else score
    q = -1.0 if not np.isfinite(q) else float(f"{q:.{_DIGITS}g}")
    return (-q, lex, geo)


def check_point_plan(polygon: Polygon, plan: Any, no_gravity: str | None = None) -> Polygon:
    """``polygon`` checked, and ``plan`` a :class:`GraspPlan` of point fingers (else
    TypeError); with ``no_gravity`` (why), a plan that relies on gravity is refused
    (ValueError).  What the functions judging a plan's grasps (its payload, its chance
    of holding, its stability) check first."""
    checked: Polygon = check_polygon(polygon)
    if not isinstance(plan, GraspPlan):
        raise TypeError(f"plan must be a GraspPlan of point fingers, got "
                        f"{type(plan).__name__}")
    if no_gravity is not None and plan.gravity is not None:
        raise ValueError(f"plan must not rely on gravity: {no_gravity}")
    return checked
