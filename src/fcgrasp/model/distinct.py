"""Distinct alternatives among ranked plans: non-maximum suppression, as object detectors
do, on the regions of contact.

Two plans of point fingers are **the same alternative** when their fingers can be paired
so that every finger's region overlaps its partner's by more than ``fraction`` of the
shorter of the two (overlap measured along the boundary, exactly: the length of the
common part of the two polylines).  A plan shifted along the outline by an edge is then
the same alternative; a plan that moves even one finger elsewhere is another.  Regions
reduced to a point (gravity's, at the centroid) overlap when they coincide.

:func:`distinct_plans` keeps, in rank order, each plan that is not the same alternative
as a plan already kept, and records on each kept plan the plans it stands for
(``GraspPlan.similar``: their edges).  ``fraction=0`` keeps every plan.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import replace
from functools import cache
from itertools import permutations
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from ..core._checks import FloatArray
from ..core.alternatives import keep_distinct
from ..core.tolerances import COORD_ROUNDING, REACH_PAD, ROUND_TOL, SLICE_TOL, TOL
from .plans import GraspPlan
from .polygon import Polygon

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = ["DEFAULT_DISTINCT", "region_overlap", "same_alternative", "Suppression",
           "distinct_plans",
           "part_symmetries", "grip_symmetries", "box_images", "same_box", "distinct_boxes"]

#: The documented default of ``distinct=`` / ``--distinct``: half of the shorter region.
DEFAULT_DISTINCT = 0.5


def region_overlap(a: ArrayLike, b: ArrayLike, tol: float) -> float:
    """Length of the common part of two region polylines along the boundary (points
    within ``tol`` of each other are on both).

    >>> region_overlap([[0, 0], [4, 0]], [[3, 0], [6, 0]], 1e-9)
    1.0
    """
    return _common(np.asarray(a, float), _zone(np.asarray(b, float), tol))


def _zone(b: FloatArray, tol: float) -> Any:
    """The points within ``tol`` of the polyline ``b`` (flat ends: none beyond them)."""
    return shapely.buffer(shapely.LineString(b), tol, cap_style="flat")


def _common(a: FloatArray, zone: Any) -> float:
    """Length of the polyline ``a`` inside ``zone``."""
    return float(shapely.intersection(shapely.LineString(a), zone).length)


class _Overlaps:
    """:func:`region_overlap` at one tolerance, each pair of regions computed once and
    each second region buffered once (the same operations, so the same numbers): a
    search that reads plans in rounds compares the regions of many copies, which repeat
    (three fingers on ``icons/droplet.svg``: 10,446 overlaps of 3,315 pairs).  Two
    regions whose boxes are further apart than the tolerance have nothing in common
    (the zone ends within it of the second): 0, from each region's box, kept as
    floats."""

    def __init__(self, tol: float) -> None:
        self.tol = tol
        self._ids: dict[bytes, int] = {}        # each region's points once, numbered
        self._boxes: list[tuple[float, float, float, float]] = []
        self._zones: dict[int, Any] = {}
        self._pairs: dict[tuple[int, int], float] = {}
        self._pieces: dict[int, tuple[Any, ...] | None] = {}
        #: each region as :func:`_overlaps` reads it (its points, length and edges),
        #: numbered once (:meth:`region`), and the numbers by what they stand for
        self._regions: list[tuple[FloatArray, float, tuple[int, ...] | None]] = []
        self._numbers: dict[tuple[Any, ...], int] = {}
        #: :func:`_overlaps`' answers by the regions' numbers and the fraction
        self._decided: dict[tuple[int, int, float], bool] = {}
        #: each region's segments as :meth:`reach` reads them, by the region's id
        self._segments: dict[int, tuple[Any, ...]] = {}

    def region(self, a: ArrayLike, length: float, edges: Iterable[int] | None = None) -> int:
        """The number of a region as :meth:`decide_regions` reads it: its points, its
        length and its edges (None: not labelled); one number for the same three."""
        a = np.asarray(a, float)
        labels = None if edges is None else tuple(edges)
        key = (self._id(a), float(length), labels)
        got = self._numbers.get(key)
        if got is None:
            got = self._numbers[key] = len(self._regions)
            self._regions.append((a, float(length), labels))
        return got

    def decide_regions(self, ra: int, rb: int, fraction: float) -> bool:
        """:func:`_overlaps` of two regions numbered by :meth:`region`, each answer kept:
        a ranked list's copies repeat the same regions (three fingers on
        ``icons/droplet.svg``: 15,000 tests of about 3,000 pairs)."""
        key = (ra, rb, fraction)
        got = self._decided.get(key)
        if got is None:
            (a, la, ea), (b, lb, eb) = self._regions[ra], self._regions[rb]
            got = self._decided[key] = _overlaps(a, b, la, lb, fraction, self.tol, self,
                                                 ea, eb)
        return got

    def decide(self, a: ArrayLike, b: ArrayLike, la: float, lb: float, fraction: float,
               ea: Iterable[int] | None = None, eb: Iterable[int] | None = None) -> bool:
        """:func:`_overlaps` of two regions with this measure (:meth:`decide_regions`:
        each answer kept by what it reads, the regions' points, lengths and edges, and
        the fraction)."""
        return self.decide_regions(self.region(a, la, ea), self.region(b, lb, eb), fraction)

    def shared(self, a: FloatArray, ea: Any, b: FloatArray, eb: Any) -> float:
        """A lower bound of :meth:`__call__` ``(a, b)`` without the buffer
        (:func:`_shared_length`; ``ea``, ``eb`` the regions' edges), each region read
        once (each pair is asked once: :meth:`decide_regions` keeps the answers)."""
        pa, pb = self._read(self._id(a), a, ea), self._read(self._id(b), b, eb)
        return 0.0 if pa is None or pb is None else _shared_length(pa, pb, self.tol)

    def _read(self, k: int, region: FloatArray, edges: Any) -> tuple[Any, ...] | None:
        if k not in self._pieces:
            self._pieces[k] = _pieces(region, edges)
        return self._pieces[k]

    def _id(self, region: FloatArray) -> int:
        key = region.tobytes()
        got = self._ids.get(key)
        if got is None:
            got = self._ids[key] = len(self._boxes)
            lo, hi = region.min(axis=0), region.max(axis=0)
            self._boxes.append((float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])))
        return got

    def reach(self, a: FloatArray, b: FloatArray) -> float:
        """An upper bound of :meth:`__call__` ``(a, b)``: the length of ``a`` inside the
        box of ``b`` grown by twice the tolerance (the zone of ``b`` lies inside it),
        raised by :data:`~fcgrasp.core.tolerances.REACH_PAD` of itself and by the
        tolerance, far above the rounding of either length.  Most pairs of a ranked
        list's regions that are near but not the same alternative are decided by it
        without a buffer (three fingers on ``icons/droplet.svg``: 2,573 of 2,585).
        Each segment of ``a`` whose box meets the box is clipped to it (Liang and
        Barsky)."""
        ka, kb = self._id(a), self._id(b)
        segs = self._segments.get(ka)
        if segs is None:
            d = a[1:] - a[:-1]
            segs = self._segments[ka] = (np.minimum(a[:-1], a[1:]), np.maximum(a[:-1], a[1:]),
                                         np.hypot(d[:, 0], d[:, 1]).tolist(), a.tolist())
        lo, hi, lengths, pts = segs
        pad = 2 * self.tol
        bx0, by0, bx1, by1 = self._boxes[kb]
        x0, y0, x1, y1 = bx0 - pad, by0 - pad, bx1 + pad, by1 + pad
        meet = np.flatnonzero((hi[:, 0] >= x0) & (lo[:, 0] <= x1)
                              & (hi[:, 1] >= y0) & (lo[:, 1] <= y1))
        total = 0.0
        for k in meet.tolist():
            (px, py), (qx, qy) = pts[k], pts[k + 1]
            dx, dy = qx - px, qy - py
            t0, t1 = 0.0, 1.0
            for den, num in ((-dx, px - x0), (dx, x1 - px), (-dy, py - y0), (dy, y1 - py)):
                if den == 0.0:
                    if num < 0.0:
                        t1 = -1.0           # parallel to a side, outside it
                        break
                elif den < 0.0:
                    t0 = max(t0, num / den)
                else:
                    t1 = min(t1, num / den)
            if t1 > t0:
                total += (t1 - t0) * lengths[k]
        return total * (1 + REACH_PAD) + self.tol

    def __call__(self, a: FloatArray, b: FloatArray) -> float:
        ka, kb = self._id(a), self._id(b)
        got = self._pairs.get((ka, kb))
        if got is None:
            (ax0, ay0, ax1, ay1), (bx0, by0, bx1, by1) = self._boxes[ka], self._boxes[kb]
            tol = self.tol
            if ax0 > bx1 + tol or ay0 > by1 + tol or bx0 > ax1 + tol or by0 > ay1 + tol:
                return 0.0
            zone = self._zones.get(kb)
            if zone is None:
                zone = self._zones[kb] = _zone(b, self.tol)
            got = self._pairs[ka, kb] = _common(a, zone)
        return got


def _pieces(region: FloatArray, edges: Any) -> tuple[Any, ...] | None:
    """What :func:`_shared_length` reads of a region: its points as tuples, its
    segments' lengths, each edge's segment (``edges``: the edge of each segment, in
    order) and the largest coordinate; None where the labels do not fit the points (not
    one edge per segment, an edge twice)."""
    pts = [tuple(p) for p in region.tolist()]
    if len(pts) != len(edges) + 1 or not len(edges):
        return None
    where = {int(e): k for k, e in enumerate(edges)}
    if len(where) != len(edges):
        return None
    lengths = [math.hypot(x1 - x0, y1 - y0)
               for (x0, y0), (x1, y1) in zip(pts[:-1], pts[1:], strict=True)]
    return pts, lengths, where, float(np.abs(region).max())


def _shared_length(a: tuple[Any, ...], b: tuple[Any, ...], tol: float) -> float:
    """A lower bound of :func:`region_overlap` ``(a, b, tol)`` (the length of region
    ``a`` within ``tol`` of region ``b``) from their pieces on the same edges (each
    region read by :func:`_pieces`).

    Two pieces on one edge are read as one line when every end of the shorter is within
    a tenth of ``tol`` of the longer's line (a region's points lie on its edges to the
    floats' rounding; the pieces inside both regions are the same whole edge, its
    vertices' very floats): where they overlap along it, ``a`` is within ``tol`` of
    ``b``, inside its buffer (whose boundary is at least 0.98 ``tol`` away but at
    ``b``'s flat ends), so the buffer's intersection counts that length; ``2 tol`` less
    per piece covers the ends.  Nothing is counted where a piece is off the other's line
    or too short to give its direction, or where the coordinates are so far from the
    origin that their rounding is not small against ``tol`` (the buffer itself is then
    rounded).  0 when nothing is shared."""
    pa, la, where_a, reach_a = a
    pb, _, where_b, reach_b = b
    if max(reach_a, reach_b) * COORD_ROUNDING > 0.01 * tol:
        return 0.0
    total = 0.0
    for e, k in where_a.items():
        m = where_b.get(e)
        if m is None:
            continue
        a0, a1, b0, b1 = pa[k], pa[k + 1], pb[m], pb[m + 1]
        if a0 == b0 and a1 == b1:           # one whole edge in both
            common = la[k]
        else:
            (ax0, ay0), (ax1, ay1), (bx0, by0), (bx1, by1) = a0, a1, b0, b1
            lb = math.hypot(bx1 - bx0, by1 - by0)
            # the longer piece is the line (its direction the better known)
            if la[k] >= lb:
                ox, oy, L, dx, dy = ax0, ay0, la[k], ax1 - ax0, ay1 - ay0
                (px, py), (qx, qy) = b0, b1
            else:
                ox, oy, L, dx, dy = bx0, by0, lb, bx1 - bx0, by1 - by0
                (px, py), (qx, qy) = a0, a1
            if L <= 1e3 * tol:
                continue
            ux, uy = dx / L, dy / L
            if abs(ux * (py - oy) - uy * (px - ox)) > 0.1 * tol \
                    or abs(ux * (qy - oy) - uy * (qx - ox)) > 0.1 * tol:
                continue
            ta0, ta1 = ux * (ax0 - ox) + uy * (ay0 - oy), ux * (ax1 - ox) + uy * (ay1 - oy)
            tb0, tb1 = ux * (bx0 - ox) + uy * (by0 - oy), ux * (bx1 - ox) + uy * (by1 - oy)
            common = min(max(ta0, ta1), max(tb0, tb1)) - max(min(ta0, ta1), min(tb0, tb1))
        if common > 2 * tol:
            total += common - 2 * tol
    return total


def _overlaps(a: Any, b: Any, la: float, lb: float, fraction: float, tol: float,
              overlap: _Overlaps, ea: Any = None, eb: Any = None) -> bool:
    short = min(la, lb)
    if short <= tol:                            # a point region (gravity): coincide
        return la <= tol and lb <= tol and \
            float(np.hypot(*(np.mean(a, axis=0) - np.mean(b, axis=0)))) <= tol
    a, b = np.asarray(a, float), np.asarray(b, float)
    # what the pieces on shared edges surely have in common decides most pairs that
    # are the same alternative without the buffer (:func:`_shared_length`)
    if ea is not None and eb is not None and overlap.shared(a, ea, b, eb) > fraction * short:
        return True
    # what ``a`` can have in common at most (its length inside ``b``'s box) decides
    # most of the others without the buffer (:meth:`_Overlaps.reach`)
    if a.ndim == 2 and len(a) > 1 and overlap.reach(a, b) <= fraction * short:
        return False
    # (boxes apart by more than the tolerance: nothing in common, most pairs of a list)
    return overlap(a, b) > fraction * short


@cache
def _perms(k: int) -> np.ndarray:
    """Every permutation of ``range(k)``, one a row (:func:`itertools.permutations`'
    order), made once per ``k`` (read only: shared by every call)."""
    got = np.array(list(permutations(range(k))), dtype=np.intp).reshape(-1, k)
    got.flags.writeable = False
    return got


def same_alternative(p: GraspPlan, q: GraspPlan, fraction: float, tol: float,
                     measure: _Overlaps | None = None) -> bool:
    """Whether two plans are the same alternative (see the module's docstring);
    ``measure``: :func:`region_overlap` at ``tol``, remembered (:class:`_Overlaps`;
    one for this call where none is given)."""
    k = len(p.regions)
    if k != len(q.regions):
        return False
    measure = _Overlaps(tol) if measure is None else measure
    labelled = len(p.region_edges) == k and len(q.region_edges) == k
    return _paired(measure, _numbers(measure, p, labelled), _numbers(measure, q, labelled),
                   fraction)


def _numbers(measure: _Overlaps, p: GraspPlan, labelled: bool) -> list[int]:
    """The numbers of ``p``'s regions in ``measure`` (:meth:`_Overlaps.region`), with
    their edges where ``labelled``."""
    return [measure.region(r, float(n), e if labelled else None)
            for r, n, e in zip(p.regions, p.lengths,
                               p.region_edges if labelled else [None] * len(p.regions),
                               strict=True)]


def _paired(measure: _Overlaps, rp: list[int], rq: list[int], fraction: float) -> bool:
    """:func:`same_alternative` of two plans by their regions' numbers: some pairing
    (:func:`itertools.permutations`' order) overlaps region by region, each pair of
    regions decided once (:meth:`_Overlaps.decide_regions`) and only where asked."""
    decide = measure.decide_regions
    return any(all(decide(rp[i], rq[j], fraction) for i, j in enumerate(perm))
               for perm in _perm_tuples(len(rp)))


@cache
def _perm_tuples(k: int) -> tuple[tuple[int, ...], ...]:
    """Every permutation of ``range(k)``, in :func:`itertools.permutations`' order."""
    return tuple(permutations(range(k)))


class Suppression:
    """Suppression fed in rank order, in as many calls as the caller likes (a search
    that reads the ranked list in rounds): :meth:`add` keeps a plan that is not the same
    alternative as a plan kept before, else files it under that plan; :attr:`kept` the
    plans kept so far; :meth:`plans` them, each with ``similar`` (copies)."""

    def __init__(self, fraction: float, size: float) -> None:
        self.fraction, self.tol = fraction, ROUND_TOL * size
        self._overlap = _Overlaps(self.tol)
        self.kept: list[Any] = []
        #: the kept plans' region numbers (:func:`_numbers`), by place and labelling
        self._kept_numbers: dict[tuple[int, bool], list[int]] = {}
        self._stands: dict[int, list[tuple[int, ...]]] = {}
        #: per number of regions: the kept plans' places in ``kept`` and their regions'
        #: boxes (n, regions, 4: x and y least, then greatest), rows beyond n spare
        self._boxes: dict[int, tuple[list[int], FloatArray]] = {}

    @staticmethod
    def _region_boxes(p: GraspPlan) -> FloatArray:
        """Each region's box (regions, 4: x and y least, then greatest), the regions'
        points read in one array (a plan's few regions: numpy's calls cost more than
        the arithmetic)."""
        regions = [np.asarray(r, float).reshape(-1, 2) for r in p.regions]
        starts = np.cumsum([0] + [len(r) for r in regions[:-1]])
        pts = np.concatenate(regions)
        return np.concatenate((np.minimum.reduceat(pts, starts, axis=0),
                               np.maximum.reduceat(pts, starts, axis=0)), axis=1)

    def _may_match(self, p: GraspPlan, box: FloatArray) -> list[int]:
        """The places in ``kept`` of the plans that may be ``p``'s alternative, in order:
        those whose regions' boxes pair with ``p``'s, each within the tolerance (two
        regions whose boxes are further apart do not overlap, :func:`_overlaps`), tested
        for every kept plan at once."""
        k = len(p.regions)
        if k not in self._boxes:
            return []
        places, boxes = self._boxes[k]
        B, tol = boxes[:len(places)], self.tol
        # near[q, i, j]: p's region i and kept plan q's region j within the tolerance
        apart = np.logical_or((box[None, :, None, :2] > B[:, None, :, 2:] + tol).any(axis=-1),
                              (B[:, None, :, :2] > box[None, :, None, 2:] + tol).any(axis=-1))
        near = np.logical_not(apart)
        # every pairing of the regions at once: near[q, i, perm[i]] for each perm
        may = np.any(np.all(near[:, np.arange(k), _perms(k)], axis=2), axis=1)
        return [places[q] for q in np.flatnonzero(may)]

    def add(self, p: Any, keep: bool = True) -> bool:
        """Whether ``p`` was kept (plans that are not :class:`~fcgrasp.GraspPlan`, such
        as a jaw's boxes, are); with ``keep`` False, ``p`` is only filed under the plan
        it is the same alternative as, if any (the kept plans are enough).  The first
        kept plan it is the same alternative as, read among those whose boxes allow it
        (:meth:`_may_match`)."""
        if isinstance(p, GraspPlan):
            box = self._region_boxes(p)
            twin = None
            mine: dict[bool, list[int]] = {}    # p's region numbers, labelled or not
            for q in self._may_match(p, box):
                kept = self.kept[q]
                labelled = len(p.region_edges) == len(p.regions) == \
                    len(kept.region_edges)
                if labelled not in mine:
                    mine[labelled] = _numbers(self._overlap, p, labelled)
                theirs = self._kept_numbers.get((q, labelled))
                if theirs is None:
                    theirs = self._kept_numbers[q, labelled] = \
                        _numbers(self._overlap, kept, labelled)
                if _paired(self._overlap, theirs, mine[labelled], self.fraction):
                    twin = kept
                    break
            if twin is not None:
                self._stands[id(twin)].append(tuple(p.edges))
                return False
            if not keep:
                return False
            self._stands[id(p)] = []
            self._file(len(p.regions), box)
        elif not keep:
            return False
        self.kept.append(p)
        return True

    def _file(self, k: int, box: FloatArray) -> None:
        """File the boxes of the plan about to be kept (its place: ``len(kept)``)."""
        places, boxes = self._boxes.get(k, ([], np.empty((8, k, 4))))
        if len(places) == len(boxes):
            boxes = np.concatenate([boxes, np.empty_like(boxes)])
        boxes[len(places)] = box
        places.append(len(self.kept))
        self._boxes[k] = (places, boxes)

    def plans(self) -> list[Any]:
        # copies: the plans given are left as they are
        return [replace(p, similar=tuple(self._stands[id(p)])) if id(p) in self._stands
                else p for p in self.kept]


def distinct_plans(plans: list[Any], fraction: float, size: float,
                   limit: int | None = None) -> list[Any]:
    """The ranked ``plans`` less those that are the same alternative as a better one,
    each kept plan's ``similar`` listing the edges of the plans it stands for.  Plans
    that are not :class:`~fcgrasp.GraspPlan` (a jaw's boxes) are kept as they are.
    ``size`` is the part's size (the tolerance is :data:`ROUND_TOL` of it).  With
    ``limit``, the first ``limit`` kept plans only, the same as without (suppression in
    rank order keeps a plan by the plans kept before it), each with every plan it
    stands for; the plans after them are compared with those alone.

    >>> import fcgrasp as fc
    >>> part = fc.read_part("demo:cam")                 # a curved outline of 360 edges
    >>> plans = fc.plan(part, fingers=2, mu=0.3, top=10, distinct=0)   # as ranked
    >>> kept = distinct_plans(plans, 0.5, part.size)
    >>> len(plans), len(kept), len(kept[0].similar)     # ten shifts of one grasp
    (10, 1, 9)
    """
    if not 0 <= fraction <= 1:
        raise ValueError(f"distinct must be a fraction in [0, 1], got {fraction!r}")
    if fraction == 0:
        return list(plans)
    suppression = Suppression(fraction, size)
    for p in plans:
        suppression.add(p, keep=limit is None or len(suppression.kept) < limit)
    return suppression.plans()


def part_symmetries(polygon: Polygon, tol: float = TOL) -> list[tuple[str, float]]:
    """The isometries about the centroid that map the part onto itself: ``("rot",
    alpha)`` (a rotation by ``alpha``; the identity is ``("rot", 0.0)``) and ``("ref",
    phi)`` (the reflection across the line through the centroid at angle ``phi``), every
    vertex of every ring landing within ``tol`` times the part's size of a vertex.

    >>> from fcgrasp.model.polygon import Polygon
    >>> [k for k, _ in part_symmetries(Polygon([[0, 0], [4, 0], [4, 2], [0, 2]]))]
    ['rot', 'rot', 'ref', 'ref']
    """
    g = np.asarray(polygon.centroid, float)
    v = np.concatenate([polygon.vertices, *polygon.holes]) - g
    r = np.hypot(v[:, 0], v[:, 1])
    eps = tol * float(polygon.size)
    far = np.flatnonzero(r >= r.max() - eps)
    a0 = float(np.arctan2(v[far[0], 1], v[far[0], 0]))
    candidates = [("rot", float(np.arctan2(v[j, 1], v[j, 0])) - a0) for j in far]
    candidates += [("ref", 0.5 * (a0 + float(np.arctan2(v[j, 1], v[j, 0])))) for j in far]
    tree = shapely.STRtree(shapely.points(v))
    out: list[tuple[str, float]] = []
    keys: set[tuple[str, float]] = set()   # those found, by their angle rounded
    for kind, ang in candidates:
        w = v @ _matrix(kind, ang).T
        _, dist = tree.query_nearest(shapely.points(w), return_distance=True)
        if len(dist) == len(w) and float(np.max(dist)) <= eps:
            key = (kind, round(float(np.mod(ang, np.pi if kind == "ref" else 2 * np.pi)), 9))
            if key not in keys:
                keys.add(key)
                out.append((kind, ang))
    return out


def _matrix(kind: str, ang: float) -> np.ndarray:
    """The linear part of a symmetry of :func:`part_symmetries` (about the centroid)."""
    c, s = np.cos(ang), np.sin(ang)
    return np.array([[c, -s], [s, c]]) if kind == "rot" else \
        np.array([[np.cos(2 * ang), np.sin(2 * ang)], [np.sin(2 * ang), -np.cos(2 * ang)]])


def grip_symmetries(polygon: Polygon, insert: ArrayLike | None = None, tol: float = 10 * SLICE_TOL
                    ) -> list[tuple[str, float]]:
    """The symmetries under which a grip's boxes have images (:func:`box_images`): all of
    :func:`part_symmetries` for an external grip (``insert`` None); for an internal grip,
    those that fix its insertion point ``insert`` (within ``tol`` of the part's size,
    the point's own accuracy), so that they map its hole onto itself and the jaws go in
    at the same point (a symmetry that takes the hole to another one, or moves the point,
    gives poses that start elsewhere).

    >>> from fcgrasp.io.parts import demo_part
    >>> part = demo_part("washer")                   # a ring: the hole on the centroid
    >>> len(grip_symmetries(part)) == len(grip_symmetries(part, part.centroid))
    True
    >>> grip_symmetries(part, part.centroid + [1.0, 0.0])  # off the centre: the identity
    [('rot', 0.0)]
    """
    syms = part_symmetries(polygon)
    if insert is None:
        return syms
    v = np.asarray(insert, float) - np.asarray(polygon.centroid, float)
    eps = tol * float(polygon.size)
    return [(kind, ang) for kind, ang in syms
            if float(np.hypot(*(_matrix(kind, ang) @ v - v))) <= eps]


def box_images(theta: tuple[float, float], offset: tuple[float, float],
                symmetries: list[tuple[str, float]]) -> list[tuple[float, float, float, float]]:
    """A box of jaw poses ``(t0, t1, c0, c1)`` under every symmetry of the part, and under
    the jaw's own (``theta + pi``, ``-c``: the pads swapped)."""
    t0, t1 = theta
    c0, c1 = offset
    out = []
    for kind, ang in symmetries:
        box = (t0 + ang, t1 + ang, c0, c1) if kind == "rot" else \
            (2 * ang - t1, 2 * ang - t0, -c1, -c0)
        out += [box, (box[0] + np.pi, box[1] + np.pi, -box[3], -box[2])]
    return out


def _interval_overlap(a0: float, a1: float, b0: float, b1: float, period: float,
                      gaps: bool = False) -> float:
    """Overlap of two angle intervals (each shorter than the period), mod ``period``;
    with ``gaps``, negative where they are apart: minus the smallest gap between them."""
    shift = b0 - a0 - period * np.floor((b0 - a0) / period)       # b moved to start >= a0
    best = -np.inf if gaps else 0.0
    for s in (shift, shift - period, shift + period):
        lo, hi = max(a0, a0 + s), min(a1, a0 + s + (b1 - b0))
        best = max(best, hi - lo)
    return float(best)


def _features(p: Any) -> tuple[tuple[int, ...], ...]:
    """The edges each pad of a jaw box touches, as a key."""
    return tuple(tuple(sorted(f)) for f in p.features)


def same_box(p: Any, q: Any, fraction: float, symmetries: list[tuple[str, float]],
             adjacent: tuple[float, float] | None = None) -> bool:
    """Whether two jaw boxes are the same alternative: some image of ``q`` under the
    part's symmetries and the jaw's (see :func:`part_symmetries`) overlaps ``p`` by more
    than ``fraction`` of the smaller box's area (angle x offset); or, with ``adjacent``
    ``(angle step, offset step)``, the pads touch the same edges in both and the boxes
    are neighbours, apart by at most a step each way (one contact configuration cut into
    boxes: a slanted band of holding poses is covered by slices).  Boxes of different
    grips (external, or internal in different holes) never are."""
    if (p.mode, p.hole) != (q.mode, q.hole):
        return False
    if adjacent is not None and _features(p) == _features(q):
        gap_t = -_interval_overlap(p.theta[0], p.theta[1], q.theta[0], q.theta[1],
                                   2 * np.pi, gaps=True)
        gap_c = max(p.offset[0], q.offset[0]) - min(p.offset[1], q.offset[1])
        if gap_t <= adjacent[0] * (1 + ROUND_TOL) and gap_c <= adjacent[1] * (1 + ROUND_TOL):
            return True
    t0, t1 = p.theta
    c0, c1 = p.offset
    area = min((t1 - t0) * (c1 - c0), (q.theta[1] - q.theta[0]) * (q.offset[1] - q.offset[0]))
    for b0, b1, d0, d1 in box_images(q.theta, q.offset, symmetries):
        dc = min(c1, d1) - max(c0, d0)
        if dc > 0 and _interval_overlap(t0, t1, b0, b1, 2 * np.pi) * dc > fraction * area:
            return True
    return False


def distinct_boxes(polygon: Polygon, plans: list[Any], fraction: float,
                   adjacent: tuple[float, float] | None = None) -> list[Any]:
    """The ranked jaw boxes less those that are the same alternative as a better one
    (:func:`same_box`, up to the part's symmetries; with ``adjacent``, neighbouring boxes
    of the same contacts too), each kept box's ``similar`` counting the boxes it stands
    for.  A box joins the group of the first kept box it is the same alternative as, or
    as any box of that group: a chain of adjacent slices is one alternative."""
    if not 0 <= fraction <= 1:
        raise ValueError(f"distinct must be a fraction in [0, 1], got {fraction!r}")
    if fraction == 0:
        return list(plans)
    syms: dict[Any, list[tuple[str, float]]] = {}     # per grip (:func:`grip_symmetries`)

    def same(q: Any, p: Any) -> bool:
        if p.hole not in syms:
            syms[p.hole] = grip_symmetries(polygon, getattr(p, "insert", None))
        return same_box(q, p, fraction, syms[p.hole], adjacent)

    # the same alternative as any box of a group (a band of adjacent slices is one)
    groups = keep_distinct(plans, same, chain=True)
    return [replace(g[0], similar=len(g) - 1) for g in groups]
