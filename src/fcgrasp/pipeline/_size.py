"""How large a search is before it runs: its candidate edge sets, rows, seconds and
memory, and the refusal of one past the memory budget (part of
:mod:`fcgrasp.pipeline`)."""

from __future__ import annotations

from dataclasses import dataclass
from math import comb
from typing import Any

from ..errors import SearchTooLarge
from ..model.polygon import Polygon
from ..model.stretches import stretch_kernels_for
from . import _spec  # _spec: the search's tunables, read when used
from ._features import (
    features,
)
from ._spec import (
    KEEP_STRETCHES,
    KEPT_ROW_BYTES,
    ROW_BYTES,
    ROW_SECONDS,
    STRETCH_BYTES,
    STRETCH_KERNEL_BYTES,
    PlanSpec,
)


@dataclass(frozen=True)
class SearchSize:
    """How big a search is, before it starts (see :func:`search_size`).

    ``rows``: candidate edge sets (an upper bound when a hand splits edges); ``batch_rows``:
    rows per streamed batch; ``peak_bytes``: memory of one batch being solved;
    ``kept_bytes``: memory of what is kept across batches (every row's plan with
    ``top=None``, else the top of each batch); ``seconds``: a rough time on one core.
    """

    features: int
    rows: int
    batch_rows: int
    peak_bytes: int
    kept_bytes: int
    seconds: float
    budget: int

    @property
    def fits(self) -> bool:
        return self.peak_bytes + self.kept_bytes <= self.budget


def _estimate(spec: PlanSpec, n: int) -> tuple[int, int, int, int]:
    """(rows, batch rows, peak bytes, kept bytes) of a search over ``n`` features."""
    if spec.stretches:
        # the stretch search holds a few (n, n) arrays per ring pair; every
        # configuration of a curved outline (top=None) is about n**3 / 36 of them
        rows = n ** 3 // 36 if spec.top is None else comb(n, 2)
        held = rows if spec.top is None else min(rows, 2 * max(spec.top, KEEP_STRETCHES))
        # large rings run compiled, with nothing of size n x n
        peak = STRETCH_KERNEL_BYTES * n if stretch_kernels_for(n * n) else STRETCH_BYTES * n * n
        return rows, rows, peak, held * KEPT_ROW_BYTES
    rows = spec.shape.rows(n)
    per = ROW_BYTES[spec.fingers]
    cap = _spec.TUPLE_BATCH_SIZE if spec.shape.tuple_batches else _spec.BATCH_SIZE
    batch = int(max(1, min(cap, spec.max_memory // 2 // per)))
    peak = min(rows, batch) * per
    if spec.top is None:
        held = rows
    else:
        keep = spec.top if spec.rank_by == "min_region" else _spec.KEEP_FOR_MEASURE
        held = min(rows, _reduce_rows(spec) + 2 * keep)
    return rows, batch, peak, held * KEPT_ROW_BYTES


def _reduce_rows(spec: PlanSpec) -> int:
    """Rows :func:`rank` holds beyond its running top before folding them in."""
    return int(min(_spec.REDUCE_ROWS, max(1000, spec.max_memory // 4 // KEPT_ROW_BYTES)))


def search_size(polygon: Polygon, spec: PlanSpec, edges: Any = None) -> SearchSize:
    """The size of the search :func:`candidates` -> :func:`solve` -> :func:`rank` will do,
    and the batch size that keeps it within ``spec.max_memory``.

    Batches take at most half the budget (``ROW_BYTES`` per row, at most
    :data:`BATCH_SIZE` rows of two fingers, :data:`TUPLE_BATCH_SIZE` of three or four);
    what :func:`rank` keeps across batches must fit as well (``KEPT_ROW_BYTES`` per
    row): its running top, at most ``REDUCE_ROWS`` (fewer on small
    budgets) plus twice the top, or with ``top=None`` every row; see :func:`check_search`.

    >>> from fcgrasp.io.parts import demo_part
    >>> from fcgrasp.pipeline import plan_spec
    >>> s = search_size(demo_part("quad"), plan_spec(fingers=4))
    >>> s.rows, s.fits
    (13, True)
    """
    n = len(features(polygon, spec.mu, spec.hand, edges).edge)
    rows, batch, peak, kept = _estimate(spec, n)
    return SearchSize(n, rows, batch, peak, kept, rows * ROW_SECONDS[spec.fingers],
                      spec.max_memory)


def _fmt_bytes(b: float) -> str:
    for unit in ("B", "KB", "MB", "GB", "TB"):
        if b < 1024:
            return f"{b:.3g} {unit}"
        b /= 1024
    return f"{b:.3g} PB"


def check_search(polygon: Polygon, spec: PlanSpec) -> SearchSize:
    """The :func:`search_size` of a plan, or :class:`SearchTooLarge` (a ValueError) when it
    cannot fit ``spec.max_memory``, saying what would: how many edges fit, a ``top``, fewer
    fingers."""
    size = search_size(polygon, spec)
    if size.fits:
        return size
    fit = 2
    while fit < size.features and sum(_estimate(spec, fit + 1)[2:]) <= spec.max_memory:
        fit += 1
    what = spec.shape.label
    hint = "plan on single edges (along_boundary=False, --single-edge), or " \
        if spec.stretches and spec.top is not None else \
        "give a top (--top K), or " if spec.top is None else \
        "ask for fewer plans (--top), " if spec.top * KEPT_ROW_BYTES > spec.max_memory // 4 \
        else ""
    raise SearchTooLarge(
        f"a {what} search of this part ({size.features} edges, {size.rows:.3g} candidate "
        f"edge sets) would need about {_fmt_bytes(size.peak_bytes + size.kept_bytes)}, above "
        f"the memory budget of {_fmt_bytes(spec.max_memory)} (max_memory, --max-memory): "
        f"{hint}simplify the outline to at most about {fit} edges (--simplify TOL), or plan "
        f"with fewer fingers")
