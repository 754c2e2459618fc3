"""Named tolerances, in one place.

Every geometric predicate of fcgrasp takes a ``tol=`` keyword whose default is one
of the constants below.  All of them are *relative*: they compare normalised
quantities (unit directions, sines of angles, lengths divided by the size of the
problem), never raw coordinates, so a part drawn in metres and the same part drawn
in micrometres get the same answers.

Ties are decided one way everywhere: a configuration that lies on a boundary, or
within ``tol`` of it, is **not** force closure (the paper's strict inequalities,
theorems 4.2, 5.2 and 6.3).  A tolerance can therefore only turn a borderline
"force closure" into "not force closure", never the reverse.
"""

from __future__ import annotations

#: Default decision tolerance for the closure tests.  It is compared with sines of
#: angles between unit vectors (about 1e-9 rad) and with lengths divided by the
#: characteristic length of the configuration.
TOL = 1e-9

#: Tolerance used by the convex-cone algebra of :mod:`fcgrasp.core.convexes` (membership
#: residuals, rank decisions) on unit-normalised generators.
CONE_TOL = 1e-9

#: Two generators (or lines) closer than this, relative to the problem size, are
#: treated as parallel / coincident when enumerating candidate facets.
DEGENERATE_TOL = 1e-12

#: Floor of the characteristic length of the general closure test, relative to the
#: distance of the lines of force from the origin their wrenches are written about.
#: Torques carry a rounding error of a few 1e-16 of that distance; dividing them by a
#: length no smaller than this keeps the noise (about 1e-11) far below ``TOL``.  It does
#: not limit resolution: a lever arm is still resolved down to ``TOL`` times the floor.
LENGTH_RESOLUTION = 1e-5

#: Relative slack of the exact region solver (:mod:`fcgrasp.model.regions`): knapsack budgets
#: and breakpoints are compared with this times the problem's own scale (the sum of
#: weighted edge lengths), and a coefficient this small relative to its velocity is zero.
SOLVER_TOL = 1e-12

#: Relative step of the leximin stages: a region "can grow" when it reaches this much
#: (times the longest edge) beyond the current level.
LEXIMIN_STEP = 1e-9

#: Relative tolerance of the placement on the optimal face (vertex enumeration).
FACE_TOL = 1e-9

#: Relative tolerance of rankings: region lengths and scores that agree to this are tied
#: and the next key decides (the leximin order, then the regions' coordinates).
RANK_TOL = 1e-9

#: A contact point given by coordinates lies on an edge when within this fraction of
#: the part's size (contact files of ``fcgrasp check``).
ON_EDGE_TOL = 1e-6

#: A ring has zero area when all its vertices lie within this fraction of its size of
#: one line.
COLLINEAR_TOL = 1e-12

#: The documented range of inputs: coordinates (and every other input number) of
#: magnitude at most this, and parts at least ``1 / MAX_MAGNITUDE`` across.  Within it,
#: squares and products of coordinates stay far from float64 overflow and underflow, so
#: a part gives the same answer at every scale; outside it, inputs are refused with a
#: ``ValueError`` naming the argument.
MAX_MAGNITUDE = 1e100

__all__ = ["TOL", "CONE_TOL", "DEGENERATE_TOL", "LENGTH_RESOLUTION", "MAX_MAGNITUDE",
           "SOLVER_TOL", "LEXIMIN_STEP", "FACE_TOL", "RANK_TOL", "ON_EDGE_TOL", "COLLINEAR_TOL"]
