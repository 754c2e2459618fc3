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

#: Tolerance used by the convex-cone algebra of :mod:`fcgrasp.convexes` (membership
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

#: The documented range of inputs: coordinates (and every other input number) of
#: magnitude at most this, and parts at least ``1 / MAX_MAGNITUDE`` across.  Within it,
#: squares and products of coordinates stay far from float64 overflow and underflow, so
#: a part gives the same answer at every scale; outside it, inputs are refused with a
#: ``ValueError`` naming the argument.
MAX_MAGNITUDE = 1e100

__all__ = ["TOL", "CONE_TOL", "DEGENERATE_TOL", "LENGTH_RESOLUTION", "MAX_MAGNITUDE"]
