"""A grasp plan, the result of :func:`fcgrasp.plan`, and the keys that order plans.

:class:`GraspPlan` holds an edge per finger and an independent region on each
(definition 7.1), with its quality (section 8.1) computed on first use.  Plans are
sorted by :func:`rank_key`: the chosen measure of :mod:`fcgrasp.ranking`, the leximin
order of the region lengths (:func:`leximin_key`), then :func:`geometric_key`, which does
not depend on how the part's vertices are numbered.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ._checks import FloatArray
from ._json import json_ready
from .contacts import FrictionlessPoint, FrictionPoint, Gravity
from .grasp import Grasp
from .polygon import Polygon
from .quality import quality_of
from .ranking import MEASURES
from .tolerances import RANK_TOL

__all__ = ["GraspPlan", "leximin_key", "geometric_key", "rank_key"]

_DIGITS = int(round(-np.log10(RANK_TOL)))


@dataclass
class GraspPlan:
    """One planned grasp: an edge per finger and an independent region on each.

    Attributes
    ----------
    edges : tuple of int
        Edge index per finger (input numbering).
    regions : ndarray, shape (fingers, 2, 2)
        Each region's two end points.
    lengths : ndarray, shape (fingers,)
    contacts : ndarray, shape (fingers, 2)
        The representative grasp: each region's midpoint.
    normals : ndarray, shape (fingers, 2)
        Outward normals of the edges (the fingers push along ``-normal``).
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
        ``epsilon_linf`` (see :mod:`fcgrasp.quality`).
    """

    edges: tuple[int, ...]
    regions: FloatArray
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
    _quality: dict[str, float] | None = field(default=None, repr=False, compare=False)

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
    def fingers(self) -> int:
        return len(self.edges)

    def contacts_for(self, points: Any) -> list[Any]:
        pts = np.asarray(points, dtype=float)
        out: list[Any] = []
        for p, n in zip(pts, self.normals, strict=True):
            if self.contact_type == "friction":
                out.append(FrictionPoint(p, n, self.mu))
            else:
                out.append(FrictionlessPoint(p, n))
        if self.gravity is not None:
            out.append(Gravity(self.gravity["center"], self.gravity["direction"]))
        return out

    def grasp(self, points: Any = None) -> Grasp:
        """The :class:`~fcgrasp.Grasp` at ``points`` (default: the representative grasp)."""
        return Grasp(self.contacts_for(self.contacts if points is None else points))

    def sample(self, n: int, rng: np.random.Generator | None = None) -> FloatArray:
        """``n`` grasps with each finger uniform in its region, shape (n, fingers, 2)."""
        rng = np.random.default_rng() if rng is None else rng
        u = rng.random((n, self.fingers))
        a, b = self.regions[:, 0], self.regions[:, 1]
        return a[None] + u[..., None] * (b - a)[None]

    def corners(self) -> FloatArray:
        """All corner grasps of the box of regions, shape (2**fingers, fingers, 2)."""
        idx = np.array(list(np.ndindex(*(2,) * self.fingers)))
        return self.regions[np.arange(self.fingers)[None, :], idx]

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready description (floats rounded to 12 significant digits)."""
        d: dict[str, Any] = {
            "edges": [int(e) for e in self.edges],
            "contact_type": self.contact_type,
            "mu": self.mu,
            "mode": self.mode,
            "regions": self.regions,
            "region_lengths": self.lengths,
            "min_region_length": self.min_length,
            "contacts": self.contacts,
            "normals": self.normals,
            "quality": dict(sorted(self.quality.items())),
        }
        if self.gravity is not None:
            d["gravity"] = dict(self.gravity)
        return json_ready(d)


def leximin_key(lengths: FloatArray, size: float) -> tuple[float, ...]:
    """Sort key of the leximin order (definition 7.1): smaller is better."""
    return tuple(-np.round(np.sort(np.asarray(lengths, float)) / size, _DIGITS))


def geometric_key(regions: FloatArray, polygon: Polygon) -> tuple[float, ...]:
    """A key of a set of regions that does not depend on how the part is numbered.

    Each region's two ends are sorted, the regions are sorted, and the coordinates
    (relative to the part's centroid and size, rounded to 1e-9) are read in that order.
    Used to break ties between equally good plans or placements.
    """
    rel = np.round((np.asarray(regions, float) - polygon.centroid) / polygon.size, _DIGITS) + 0.0
    segs = sorted(tuple(sorted(map(tuple, r.tolist()))) for r in rel)
    return tuple(x for seg in segs for pt in seg for x in pt)


def rank_key(p: GraspPlan, polygon: Polygon, rank_by: str = "min_region",
             score: float | None = None) -> tuple[Any, ...]:
    """The sort key of :func:`plan` (smaller is better), independent of numbering.

    ``min_region``: the leximin order of the region lengths (definition 7.1); any other
    measure of :data:`fcgrasp.ranking.MEASURES`: its score (larger first, to 9
    significant digits), then the leximin order.  Remaining ties are broken by
    :func:`geometric_key`.
    """
    lex = leximin_key(p.lengths, polygon.size)
    geo = geometric_key(p.regions, polygon)
    if rank_by == "min_region":
        return (lex, geo)
    q = MEASURES[rank_by].score([p])[0] if score is None else score
    q = -1.0 if not np.isfinite(q) else float(f"{q:.{_DIGITS}g}")
    return (-q, lex, geo)
