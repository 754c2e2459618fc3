"""The jaw's boxes proved, grown to the holding set's exact boundary and refined on a
raster of its exact slices (part of :mod:`fcgrasp.grippers.jaw`)."""

from __future__ import annotations

import numpy as np

from ...core import budget
from ...core._checks import FloatArray
from ...core.tolerances import CONTACT_TOL, RANK_TOL, TOL
from ...model.distinct import (
    _interval_overlap,
)
from ...model.polygon import Polygon
from ._certify import (
    certify_box,
)
from ._grid import (
    _measure,
)
from ._poses import (
    CERTIFY_BOXES,
    CERTIFY_SHRINKS,
    CHECK_DENSITY,
    JawParameters,
)
from ._slices import (
    holds_across,
    near_intervals,
)


def _proved(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None,
            th: tuple[float, float], off: tuple[float, float], dth: float, dc: float
            ) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The box, shrunk by whole grid steps (at most :data:`CERTIFY_SHRINKS`) until
    :func:`certify_box` proves it; None when it cannot."""
    for k in range(CERTIFY_SHRINKS + 1):
        t = (th[0] + k * dth, th[1] - k * dth)
        c = (off[0] + k * dc, off[1] - k * dc)
        if t[1] < t[0] or c[1] < c[0] or (k and _past_time()):
            return None
        boxes = CERTIFY_BOXES if k else CERTIFY_BOXES // 8
        if certify_box(polygon, jaw, t, c, margin, hole, max_boxes=boxes):
            return t, c
    return None


#: A grown box is moved in from the set's boundary by these fractions of a grid step
#: until it is proved (a box on the boundary cannot be: its sub-boxes would have to
#: shrink to nothing there), each try with that many times :data:`CERTIFY_BOXES`
#: sub-boxes (the sub-boxes a proof needs grow as the inverse of the back-off:
#: ``demo:rectangle`` 7,900 at half a step, 15,800 at a quarter, 32,200 at an eighth).
GROW_BACKOFF = ((0.25, 5.0), (0.5, 2.5))


def _reach(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None,
           thetas: FloatArray, anchor: float, step: float, side: int) -> float | None:
    """How far from ``anchor`` (an offset at which every angle of ``thetas`` holds) the
    exact slices (:func:`~fcgrasp.grippers.jaw.holding_offsets`) hold at every one of
    ``thetas``, towards ``side`` (+1: larger offsets): the nearest end of the slices'
    intervals through ``anchor`` (:func:`._slices.near_intervals`).  Windows of
    ``2 * step`` are added until it is found (None: no interval through the anchor at
    some angle)."""
    tol = CONTACT_TOL * polygon.size
    far = anchor
    reach_max = polygon.radius + jaw.pad_width
    while True:
        near, far = far, far + side * 2 * step
        window = (min(near, far), max(near, far))
        # the interval through the window's end next to the anchor, at each angle
        ends = near_intervals(polygon, jaw, thetas, margin, hole, window, side)
        if np.isnan(ends).any():
            return None if near == anchor else near
        end = float(ends.min() if side > 0 else ends.max())
        if abs(end - far) > tol or abs(far) > reach_max:
            return end


def _holds_across(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None,
                  thetas: FloatArray, c0: float, c1: float) -> np.ndarray:
    """Whether the exact slice at each angle holds at every offset of ``[c0, c1]``
    (:func:`._slices.holds_across`)."""
    return holds_across(polygon, jaw, thetas, margin, hole, (c0, c1))


def _grown(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None,
           th: tuple[float, float], off: tuple[float, float], dth: float, dc: float
           ) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """A box found on the grid grown to the exact boundary of the holding set, the
    dimension that limits its measure first: its offset range to the nearest ends of the
    exact slices at :data:`CHECK_DENSITY` angles per grid step across it
    (:func:`~fcgrasp.grippers.jaw.holding_offsets`), and its angle range, with the offset
    range fixed, by bisection (to 1/4096 of a fine step) to the first angle whose slice
    does not hold across it.  None when the slices disagree with the grid."""
    (t0, t1), (c0, c1) = th, off
    radius = polygon.radius
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


def _past_time() -> bool:
    """Whether the time budget has ended (its clock only, not a counted check): a box
    is then kept as proved so far, neither refined nor grown further, and the answer
    says it was cut short (:func:`fcgrasp.core.budget.cut_short`)."""
    return budget.cut_if_over(counted=False)


def _proved_grown(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None,
                  th: tuple[float, float], off: tuple[float, float], dth: float, dc: float
                  ) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The grown box (:func:`_grown`) moved in from the boundary by each of
    :data:`GROW_BACKOFF` (fractions of a grid step) until :func:`certify_box` proves it;
    None when it cannot (the grid box is then proved instead)."""
    if _past_time():
        return None
    grown = _grown(polygon, jaw, margin, hole, th, off, dth, dc)
    if grown is None:
        return None
    (t0, t1), (c0, c1) = grown
    for f, boxes in GROW_BACKOFF:
        t = (t0 + f * dth, t1 - f * dth)
        c = (c0 + f * dc, c1 - f * dc)
        if t[1] < t[0] or c[1] < c[0] or _past_time():
            return None
        if certify_box(polygon, jaw, t, c, margin, hole,
                       max_boxes=int(boxes * CERTIFY_BOXES)):
            return t, c
    return None


#: The raster of exact slices a box is refined on (:func:`_refined`): an angle step whose
#: arc at the part's radius is this fraction of the grid box's measure (at least
#: ``1/REFINE_DENSITY`` of a grid step, at most a quarter of one).
REFINE_STEP, REFINE_DENSITY = 0.002, 8


#: The best boxes of each grip (external, or in each hole) searched on the raster; the
#: rest are grown from the grid (the raster's slices cost most on curved outlines).
REFINE_TOP = 3


#: The grid box is also grown (:func:`_proved_grown`) where the raster's box gains less
#: than this fraction over it, and the larger kept.
GROW_TOO = 0.05


#: The raster is widened while its best run reaches an end, until the run's angle range
#: (as an arc at the part's radius) is this many times its offset range: longer runs add
#: area, not measure.
REFINE_SPAN = 2.0


#: A refined box is moved in from the raster's boundary by these fractions of each
#: side at each end, in turn, until it is proved, each try with that many times
#: :data:`CERTIFY_BOXES` sub-boxes: it keeps at least 99.5 % of its measure, else 99 %,
#: else 98 %.
REFINE_BACKOFF = ((0.0025, 25.0), (0.005, 10.0), (0.01, 5.0))


def _ends(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None,
          lines: FloatArray, anchor: float, width: float, side: int) -> FloatArray:
    """Per angle of ``lines``, the end towards ``side`` (+1: larger offsets) of the
    exact slice's interval through ``anchor`` (:func:`._slices.near_intervals`, which
    reads each angle's cells from the anchor on and stops where the interval ends: in a
    window of ``width``, then, for the angles whose interval reaches its end, one four
    times wider, up to where no pad touches); NaN where the slice does not hold at
    ``anchor``."""
    tol = CONTACT_TOL * polygon.size
    limit = side * (polygon.radius + jaw.pad_width)        # no pad touches beyond
    out = np.full(lines.size, np.nan)
    todo = np.arange(lines.size)
    near = anchor
    while todo.size and (limit - near) * side > 0:
        far = near + side * width
        if (far - limit) * side >= 0:
            far = limit
        ends = near_intervals(polygon, jaw, lines[todo], margin, hole,
                              (min(near, far), max(near, far)), side)
        done = np.isnan(ends) | (np.abs(ends - far) > tol) | (far == limit)
        # NaN past the first window: the interval ended at the window's near end
        got = np.where(np.isnan(ends), np.nan if near == anchor else near, ends)
        out[todo[done]] = got[done]
        todo = todo[~done]
        near, width = far, 4 * width
    return out


def _best_run(lines: FloatArray, lo: FloatArray, hi: FloatArray, radius: float,
              max_span: float, pad: float = 0.0
              ) -> tuple[float, int, int, float, float] | None:
    """The box of largest measure whose angles are a run ``lines[i .. j]`` and whose
    offsets the run's intervals ``[lo, hi]`` (NaN: none) all contain, of largest area
    among those of that measure (to :data:`RANK_TOL`): ``(measure, i, j, c0, c1)``,
    or None; its angle range under ``max_span``.  ``pad``: each run's angle range
    counted that much longer."""
    best: tuple[float, float, int, int, float, float] | None = None
    held = ~np.isnan(lo) & ~np.isnan(hi)
    for i in np.flatnonzero(held):
        stop = i + (int(np.argmin(held[i:])) if not held[i:].all() else held.size - i)
        c0 = np.maximum.accumulate(lo[i:stop])
        c1 = np.minimum.accumulate(hi[i:stop])
        span = lines[i:stop] - lines[i]
        score = np.where(span < max_span, np.minimum(c1 - c0, (span + pad) * radius), -1.0)
        top = float(score.max())
        if top <= 0 or (best is not None and top < best[0] * (1 - RANK_TOL)):
            continue
        area = np.where(score >= top * (1 - RANK_TOL), (c1 - c0) * span, -1.0)
        r = int(np.argmax(area))
        if best is None or top > best[0] * (1 + RANK_TOL) or area[r] > best[1]:
            best = (top, float(area[r]), int(i), int(i + r), float(c0[r]), float(c1[r]))
    return None if best is None else (best[0], best[2], best[3], best[4], best[5])


def _clip(lines: FloatArray, lo: FloatArray, hi: FloatArray, anchor: float,
          taken: list[tuple[float, float, float, float]]) -> None:
    """Cut the intervals ``[lo, hi]`` through ``anchor`` at each angle of ``lines`` (in
    place) where a box of ``taken`` (``(t0, t1, c0, c1)``, angles cyclic) covers that
    angle: to the gap beside it that holds the anchor, NaN when it holds the anchor."""
    for t0, t1, c0, c1 in taken:
        inside = np.mod(lines - t0, 2 * np.pi) <= t1 - t0
        inside &= (lo < c1) & (hi > c0)
        if anchor <= c0:
            hi[inside] = np.minimum(hi[inside], c0)
        elif anchor >= c1:
            lo[inside] = np.maximum(lo[inside], c1)
        else:
            lo[inside] = hi[inside] = np.nan


def _through(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None,
             lines: FloatArray, anchor: float, width: float,
             taken: list[tuple[float, float, float, float]]
             ) -> tuple[FloatArray, FloatArray]:
    """The exact slices' intervals ``(lo, hi)`` through ``anchor`` at the angles
    ``lines`` (:func:`_ends`, its first windows ``width``), less the boxes ``taken``."""
    lo = _ends(polygon, jaw, margin, hole, lines, anchor, width, -1)
    hi = _ends(polygon, jaw, margin, hole, lines, anchor, width, +1)
    _clip(lines, lo, hi, anchor, taken)
    return lo, hi


def _refined(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None,
             th: tuple[float, float], off: tuple[float, float], dth: float, dc: float,
             taken: list[tuple[float, float, float, float]], floor: float = 0.0
             ) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The largest box by the measure near a grid box, on a raster of the exact slices
    (:func:`~fcgrasp.grippers.jaw.holding_offsets`, their intervals through an anchor
    offset; :func:`_best_run`), apart from the boxes ``taken`` (the plans found so far
    and their images): first every grid step from two grid steps before the box to two
    after (its middle offset the anchor), widened, twice as far each time, while the
    best run reaches an end and is shorter than :data:`REFINE_SPAN` times its offset
    range; then, within a grid step of that run's ends, every :data:`REFINE_STEP` of its
    measure (as an arc at the part's radius; at least ``1/REFINE_DENSITY`` of a grid
    step).  Every angle and offset of the box returned holds on the raster, not between
    (:func:`_proved_refined` proves it).  None when no run holds, or when no run could
    measure more than ``floor`` (a finer run contains a run of the grid's angles at most
    two steps shorter)."""
    radius = polygon.radius
    coarse = dth
    max_span = np.pi - 2 * dth                      # certify_box: under half a turn
    anchor = (off[0] + off[1]) / 2
    lines = np.arange(th[0] - 2 * dth, th[1] + 2 * dth + coarse / 2, coarse)
    # (the first windows reach a little past the grid box's offsets)
    width = (off[1] - off[0]) / 2 + 2 * dc
    lo, hi = _through(polygon, jaw, margin, hole, lines, anchor, width, taken)
    grow = 8
    while True:
        run = _best_run(lines, lo, hi, radius, max_span)
        if run is None:
            return None
        m, i, j, c0, c1 = run
        ahead = coarse * np.arange(1.0, grow + 1)
        new: list[FloatArray] = [lines[0] - ahead[::-1] if i == 0 else ahead[:0],
                                 lines[-1] + ahead if j == lines.size - 1 else ahead[:0]]
        if not (new[0].size or new[1].size) or lines[-1] - lines[0] >= max_span \
                or (lines[j] - lines[i]) * radius >= REFINE_SPAN * (c1 - c0):
            break
        parts = [_through(polygon, jaw, margin, hole, t, anchor, width, taken) for t in new]
        lines = np.concatenate([new[0], lines, new[1]])
        lo = np.concatenate([parts[0][0], lo, parts[1][0]])
        hi = np.concatenate([parts[0][1], hi, parts[1][1]])
        grow *= 2
    box = (float(lines[i]), float(lines[j])), (c0, c1)
    # a finer run contains a run of these angles at most two steps shorter, whose
    # intervals contain its own
    bound = _best_run(lines, lo, hi, radius, max_span, 2 * coarse)
    if max(coarse * radius, bound[0] if bound is not None else 0.0) <= floor:
        return None
    step = min(max(REFINE_STEP * m / radius, dth / REFINE_DENSITY), coarse)
    if step > coarse / 2:
        return box
    # finer near the run's two ends (the coarse angles between are kept: the run's
    # intervals through the anchor are the same ones)
    a, b = max(i - 1, 0), min(j + 1, lines.size - 1)
    ends = [np.arange(lines[a], lines[min(a + 2, b)], step),
            np.arange(lines[max(b - 2, a + 2)], lines[b] + step / 2, step)]
    keep = np.arange(min(a + 2, b), max(b - 2, a + 2))
    got = [_through(polygon, jaw, margin, hole, t, anchor, (c1 - c0) / 2 + 2 * dc, taken)
           for t in ends]
    fine = np.concatenate([ends[0], lines[keep], ends[1]])
    run = _best_run(fine, np.concatenate([got[0][0], lo[keep], got[1][0]]),
                    np.concatenate([got[0][1], hi[keep], got[1][1]]), radius, max_span)
    if run is not None and run[0] > m:
        box = (float(fine[run[1]]), float(fine[run[2]])), (run[3], run[4])
    return box


def _clear_of(box: tuple[tuple[float, float], tuple[float, float]],
              taken: list[tuple[float, float, float, float]]) -> bool:
    """Whether ``box`` overlaps none of the boxes ``taken`` by more than
    :data:`~fcgrasp.core.tolerances.TOL` of its area (angles cyclic)."""
    (t0, t1), (c0, c1) = box
    area = (t1 - t0) * (c1 - c0)
    for b0, b1, d0, d1 in taken:
        dc = min(c1, d1) - max(c0, d0)
        if dc > 0 and _interval_overlap(t0, t1, b0, b1, 2 * np.pi) * dc > TOL * area:
            return False
    return True


def _proved_refined(polygon: Polygon, jaw: JawParameters, margin: float, hole: int | None,
                    th: tuple[float, float], off: tuple[float, float], dth: float,
                    dc: float, taken: list[tuple[float, float, float, float]],
                    floor: float = 0.0
                    ) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The refined box (:func:`_refined`) moved in from the raster's boundary by each of
    :data:`REFINE_BACKOFF` (fractions of each side) until :func:`certify_box` proves
    it; where its angle range is longer than its measure needs and no back-off is
    proved, the same with the angle range cut to what the measure needs, around the
    grid box's middle (a pose that fails at one angle, which no raster sees, may lie in
    the rest).  None when neither is proved, or when it would not measure more than
    ``floor``."""
    if _past_time():
        return None
    # (what cannot measure more than the floor once moved in is not refined)
    found = _refined(polygon, jaw, margin, hole, th, off, dth, dc, taken,
                     floor / (1 - 2 * REFINE_BACKOFF[0][0]))
    if found is None:
        return None
    radius = polygon.radius
    (t0, t1), (c0, c1) = found
    tries = [(t0, t1)]
    need = (c1 - c0) / radius
    if t1 - t0 > need * (1 + 2 * REFINE_BACKOFF[-1][0]):
        mid = min(max((th[0] + th[1]) / 2, t0 + need / 2), t1 - need / 2)
        tries.append((mid - need / 2, mid + need / 2))
    for a0, a1 in tries:
        for f, boxes in REFINE_BACKOFF:
            t = (a0 + f * (a1 - a0), a1 - f * (a1 - a0))
            c = (c0 + f * (c1 - c0), c1 - f * (c1 - c0))
            if t[1] <= t[0] or c[1] <= c[0] or _measure(t, c, radius) <= floor:
                break
            if _past_time():
                return None
            if certify_box(polygon, jaw, t, c, margin, hole,
                           max_boxes=int(boxes * CERTIFY_BOXES)):
                return t, c
    return None
