"""What a search plans (:class:`PlanSpec`, validated by :func:`plan_spec`) and the
constants that size its batches and its memory (part of :mod:`fcgrasp.pipeline`)."""

from __future__ import annotations

from dataclasses import dataclass
from math import comb
from typing import Any

import numpy as np

from ..core._angles import margin_radians
from ..core._checks import (
    check_direction,
    check_int,
    check_margin,
    check_mu_scalar,
    check_scalar,
    check_tol,
)
from ..core.tolerances import SOLVER_TOL
from ..model.hand import Hand
from ..model.ranking import MEASURES
from ..model.regions import (
    DEFAULT_MARGIN_DEG,
)

#: Candidate rows per batch of two fingers: large parts are streamed in batches of at most
#: this size (fewer when the memory budget asks for it, see :func:`search_size`).
BATCH_SIZE = 262_144
#: The same for three or four fingers, whose rows are about four times heavier: batches
#: that stay in cache (measured on a 500-edge outline: 42 s at 32,768 rows, 56 s at
#: 262,144, 60 s at 2,000,000).
TUPLE_BATCH_SIZE = 32_768
#: :func:`rank` folds the solved batches into their running top whenever it holds this many
#: rows beyond it, so what it keeps does not grow with the number of batches.
REDUCE_ROWS = 20_000
#: Default memory budget of a search, in bytes (``max_memory``, ``--max-memory``).
MAX_MEMORY = 2 ** 31
#: Smallest memory budget accepted.
MIN_MEMORY = 2 ** 24
#: Measured peak bytes per candidate row while a batch is solved (two fingers; three or
#: four), rounded up (``benchmarks/bench_scale.py`` prints them).
ROW_BYTES = {2: 450, 3: 1700, 4: 1700}
#: Bytes kept per candidate row when every plan is asked for (``top=None``): the solved
#: row and its GraspPlan, rounded up.
KEPT_ROW_BYTES = 3000
#: Peak bytes of the stretch search (regions along the boundary) per pair of edges, in
#: the worst case: every edge long enough to hold a region on its own, so the end
#: intervals of every edge against every vertex are held at once (measured 57; a curved
#: outline needs about 3: 61 MB of peak resident memory at 2,000 edges).
STRETCH_BYTES = 64
#: Peak bytes per edge of the compiled stretch search (large rings: no array of every
#: pair of edges): measured 2.5 KB (a smooth 10,000-edge blob, 25 MB) to 5.4 KB (a noisy
#: 10,000-edge star, 54 MB), rounded up.
STRETCH_KERNEL_BYTES = 8192
#: With a ranking measure other than ``min_region``, how many stretch configurations
#: (by their leximin order) are scored besides the single-edge plans.
KEEP_STRETCHES = 200
#: Three or four fingers along the boundary: how many of the best single-edge plans are
#: grown into stretches (:func:`fcgrasp.model.frictionless_stretches.grow_stretches`).
GROW_SEEDS = 10
#: Batches a search hands to a ``map`` at a time (see :func:`search`).
MAP_WINDOW = 8
#: Rows of the first batch of a search with a ``top`` (then doubling up to the batch size).
FIRST_BATCH = 4096
#: Rows of four frictionless fingers (or three with gravity) that pass the force-direction
#: test, gathered across batches before they are solved together (a search without a
#: ``map`` and not ``strict``, whose answer does not depend on how its rows are batched):
#: on a curved outline about 3 % of a batch passes, and a batch of a few hundred rows
#: costs the geometry's hundred numpy calls all the same.
GATHER_ROWS = 4096
#: Measured seconds per candidate row (two fingers; three or four), for the time estimate.
ROW_SECONDS = {2: 1e-6, 3: 3e-5, 4: 3e-5}
#: With a measure other than ``min_region`` and a ``top``, the rows of a batch kept for
#: the measure: the best by the smallest region (the measures are computed per plan).
KEEP_FOR_MEASURE = 20_000


# ----------------------------------------------------------------------------- the spec


@dataclass(frozen=True)
class SearchShape:
    """How the search enumerates the candidates of one kind of point fingers (the table
    :data:`SHAPES`, read through :attr:`PlanSpec.shape`).

    ``label`` names the search in messages; ``contact_type`` is ``friction`` or
    ``frictionless``; ``widths``: how many features a row draws besides its shortest,
    per layout (the first alone without ``three_edge``); ``three_edge``: four fingers
    also on three edges, three on two, one doubled (two fingers side by side on it);
    ``layout``: rows ``as_is``, plus the ``gravity`` contact (-1), or ``doubled`` (the
    narrower rows' features each in turn taken twice, in columns 0 and ``twin``); ``pairs``:
    rows are solved by the two-finger closed forms (theorem 6.4, algorithm 7.1; else the
    four-finger problems of theorem 7.1); ``lp``: rows are solved by linear programs
    (three fingers with friction, :mod:`fcgrasp.grippers.three_fingers`);
    ``tuple_batches``: batches of :data:`TUPLE_BATCH_SIZE`, not :data:`BATCH_SIZE`;
    ``row_terms``: the candidate count ``sum(m * comb(n, k))`` over ``(k, m)``;
    ``unused_mu``: why a frictionless search refuses a ``mu`` (``{mu}``: the value)."""

    label: str
    contact_type: str
    widths: tuple[int, ...]
    layout: str = "as_is"
    three_edge: bool = False
    twin: int = 2
    pairs: bool = False
    lp: bool = False
    tuple_batches: bool = True
    row_terms: tuple[tuple[int, int], ...] = ()
    unused_mu: str = ""

    def rows(self, n: int) -> int:
        """Candidate rows over ``n`` features."""
        return sum(m * comb(n, k) for k, m in self.row_terms)


#: The search of each kind of point fingers, by ``(fingers, with gravity)``.
SHAPES: dict[tuple[int, bool], SearchShape] = {
    (2, False): SearchShape("two-finger", "friction", (1,), pairs=True, tuple_batches=False,
                            row_terms=((2, 1),)),
    (3, False): SearchShape("three-finger", "friction", (2, 1), layout="doubled",
                            three_edge=True, twin=1, lp=True, row_terms=((3, 1), (2, 2))),
    (3, True): SearchShape("three-finger", "frictionless", (2,), layout="gravity",
                           row_terms=((3, 1),),
                           unused_mu="three fingers with gravity are frictionless: mu would "
                                     "not be used, got mu={mu!r} (drop gravity to plan three "
                                     "fingers with friction)"),
    (4, False): SearchShape("four-finger", "frictionless", (3, 2), layout="doubled",
                            three_edge=True, row_terms=((4, 1), (3, 3)),
                            unused_mu="four fingers are planned frictionless (theorem 7.1): mu "
                                      "would not be used, got mu={mu!r}"),
}


@dataclass(frozen=True)
class PlanSpec:
    """What to plan: the gripper, the margin and the ranking (validated by
    :func:`plan_spec`).  Picklable, so a batch can be solved elsewhere.

    ``margin`` is in degrees; ``gravity`` is a unit direction (three frictionless fingers
    and gravity) or None (with three fingers: three fingers with friction);
    ``disturbance`` is (translation in the part's units, rotation in degrees).
    """

    fingers: int = 2
    mu: float = 0.0
    margin: float = DEFAULT_MARGIN_DEG
    top: int | None = 10
    rank_by: str = "min_region"
    hand: Hand | None = None
    gravity: tuple[float, float] | None = None
    disturbance: tuple[float, float] = (10.0, 15.0)
    tol: float = SOLVER_TOL
    max_memory: int = 2 ** 31
    along_boundary: bool = True

    @property
    def shape(self) -> SearchShape:
        """How the search enumerates this gripper's candidates (:data:`SHAPES`)."""
        return SHAPES[(self.fingers, self.gravity is not None)]

    @property
    def stretches(self) -> bool:
        """Whether the two-finger stretch search runs (two fingers without a hand)."""
        return self.along_boundary and self.shape.pairs and self.hand is None

    @property
    def grows(self) -> bool:
        """Whether single-edge plans of three or four fingers are grown along the
        boundary (without a hand)."""
        return (self.along_boundary and self.contact_type == "frictionless"
                and self.hand is None)

    @property
    def margin_rad(self) -> float:
        return float(margin_radians(self.margin))

    @property
    def contact_type(self) -> str:
        return self.shape.contact_type


def plan_spec(fingers: Any = 2, mu: Any = 0.0, top: Any = 10, rank_by: Any = "min_region",
              hand: Any = None, margin: Any = DEFAULT_MARGIN_DEG, gravity: Any = None,
              disturbance: Any = (10.0, 15.0), tol: Any = SOLVER_TOL,
              max_memory: Any = None, along_boundary: Any = True) -> PlanSpec:
    """A validated :class:`PlanSpec` (arguments as for :func:`fcgrasp.plan`).

    Raises :class:`TypeError` or :class:`ValueError` naming the argument, also for an
    argument the planner would not use: a ``mu`` with four fingers or with gravity, a
    ``gravity`` with two or four fingers.  Three fingers are three fingers with friction
    (``mu > 0``) or, with ``gravity``, three frictionless fingers and gravity.

    >>> plan_spec(fingers=2, mu=0.3).contact_type
    'friction'
    """
    mu_v = check_mu_scalar(mu, "mu")
    margin_v = check_margin(margin)
    if hand is not None and not isinstance(hand, Hand):
        raise TypeError(f"hand must be a Hand or None, got {type(hand).__name__}")
    fingers = check_int(fingers, "fingers", choices=(2, 3, 4))
    if not isinstance(rank_by, str):
        raise TypeError(f"rank_by must be a string, got {rank_by!r}")
    if rank_by not in MEASURES:
        raise ValueError(f"rank_by must be one of {', '.join(MEASURES)}, got {rank_by!r}")
    if rank_by == "payload":
        raise ValueError("rank_by='payload' needs a load: fcgrasp.plan(..., load=) ranks by "
                         "it, the search itself does not, got rank_by='payload'")
    if top is not None:
        top = check_int(top, "top", minimum=1)
    dist = check_disturbance(disturbance)
    shape = SHAPES.get((fingers, gravity is not None))
    if shape is None:
        raise ValueError(f"gravity is a contact of three frictionless fingers; with "
                         f"{fingers} fingers it would not be used, got gravity={gravity!r}")
    g = None
    if gravity is not None:
        gv = check_direction(gravity, "gravity")
        g = (float(gv[0]), float(gv[1]))
    if shape.contact_type == "frictionless" and mu_v != 0:
        raise ValueError(shape.unused_mu.format(mu=mu))
    if shape.lp and mu_v == 0:
        raise ValueError("three fingers need friction (mu > 0), or gravity=(gx, gy) for "
                         "three frictionless fingers and gravity; got mu=0 and no gravity")
    budget = MAX_MEMORY if max_memory is None else check_int(max_memory, "max_memory",
                                                              minimum=MIN_MEMORY)
    if not isinstance(along_boundary, bool):
        raise TypeError(f"along_boundary must be a bool, got {along_boundary!r}")
    return PlanSpec(fingers, mu_v, margin_v, top, rank_by, hand, g,
                    dist, check_tol(tol), budget, along_boundary)


def check_disturbance(disturbance: Any) -> tuple[float, float]:
    if isinstance(disturbance, (str, bytes)) or np.ndim(disturbance) != 1 \
            or len(disturbance) != 2:
        raise ValueError(f"disturbance must be (translation, rotation in degrees), got "
                         f"{disturbance!r}")
    return (check_scalar(disturbance[0], "disturbance[0]", positive=True),
            check_scalar(disturbance[1], "disturbance[1]", positive=True))
