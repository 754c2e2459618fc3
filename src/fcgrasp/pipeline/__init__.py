"""The planning pipeline: candidates -> solve -> rank (sections 6, 7 and 8).

Three public steps, each on batches of numpy arrays, in the shape of shapely's array
functions under thin objects; :func:`fcgrasp.plan` is these three calls::

    spec = plan_spec(fingers=2, mu=0.3, top=5)
    solved = (solve(part, spec, batch) for batch in candidates(part, spec))
    plans = rank(part, spec, solved)

* :func:`candidates` streams :class:`EdgeSets`: batches of candidate edge sets (feature
  indices, picklable, at most ``batch_size`` rows each, so memory stays bounded however
  large the part).
* :func:`solve` builds the grasp sets of a batch (the sectors of section 6, by
  :mod:`fcgrasp.core.sectors`), prunes it with the force-direction constraint, and solves the
  optimal regions of the rows that can still reach the top (theorem 7.1, by
  :mod:`fcgrasp.model.regions`).  A batch solved anywhere (another process, another machine)
  gives the same :class:`Solved` as solved in place.
* :func:`rank` merges solved batches, keeps the best by the leximin order and the chosen
  measure (:mod:`fcgrasp.model.ranking`), places the regions and returns
  :class:`~fcgrasp.GraspPlan` objects, best first.

Private modules: ``_spec`` (:class:`PlanSpec`, the constants of the search),
``_candidates`` (features, candidate edge sets, the memory estimate), ``_solve`` (regions of
a batch), ``_search`` (:class:`TopK`, the branch and bound, :func:`rank`).

Units: lengths in the polygon's units; ``margin`` in **degrees** in :class:`PlanSpec`
(radians only inside this module's solvers).
"""

from __future__ import annotations

from ..errors import SearchTooLarge
from ._candidates import (
    Candidates,
    EdgeSets,
    candidates,
    grasp_geometry,
)
from ._features import Features, features
from ._search import TopK, every_plan, rank, search
from ._size import SearchSize, check_search, search_size
from ._solve import Solved, region_levels, solve
from ._spec import (
    BATCH_SIZE,
    FIRST_BATCH,
    GROW_SEEDS,
    KEEP_STRETCHES,
    MAP_WINDOW,
    MAX_MEMORY,
    TUPLE_BATCH_SIZE,
    PlanSpec,
    check_disturbance,
    plan_spec,
)

__all__ = ["PlanSpec", "plan_spec", "check_disturbance", "EdgeSets", "Features",
           "Candidates", "Solved", "features", "candidates", "grasp_geometry", "solve",
           "rank", "region_levels", "BATCH_SIZE", "TUPLE_BATCH_SIZE", "MAX_MEMORY",
           "SearchSize", "SearchTooLarge", "search_size", "check_search", "KEEP_STRETCHES",
           "GROW_SEEDS", "TopK", "search", "every_plan", "FIRST_BATCH", "MAP_WINDOW"]
