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

#: The largest friction coefficient a friction cone is built with: a cone of ``mu`` above
#: it has sides within ``1 / mu`` radians of the contact's tangent, where the closure
#: tests' sines (:data:`TOL`) cannot tell them from a half-plane's, so an antipodal
#: grasp at ``mu = 1e10`` would read as degenerate.  Built with ``MU_CLOSED`` instead,
#: the cone is a little narrower than asked: never a false force closure.
MU_CLOSED = 1e6

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

#: Relative pad on a distinct search's threshold
#: (:meth:`fcgrasp.model.stretches._exclusion._Exclusion.threshold`) before a configuration
#: is deferred: far above the rounding of the threshold, so a deferred configuration
#: whose smallest region exceeds it is surely a kept plan's copy by the exclusion's own test too.
DEFER_PAD = 1e-9

#: Relative margin below a distinct round's floor under which its compiled collection
#: leaves a kept plan's copies out (:meth:`fcgrasp.model.stretches._exclusion._Exclusion.
#: copy_columns`): far above the rounding of the stretches' arcs, which the collection
#: reads from the arc positions directly.
COPY_PAD = 1e-9

#: Relative slack of the exact region solver (:mod:`fcgrasp.model.regions`): knapsack budgets
#: and breakpoints are compared with this times the problem's own scale (the sum of
#: weighted edge lengths), and a coefficient this small relative to its velocity is zero.
SOLVER_TOL = 1e-12

#: Four frictionless fingers' estimate of a row's score (:mod:`fcgrasp.model._quad_estimates`):
#: the knapsacks' budgets are raised by this times the problem's scale (the solver's
#: slack is :data:`SOLVER_TOL`: a larger budget only raises the level), a row is left
#: out only when its estimate is below the floor by more than ``ESTIMATE_PAD`` of the
#: part's size, and a pair's sine (against :data:`TOL`) or the shrunk sector's
#: half-width (radians, against 0) within ``ESTIMATE_BAND`` of its threshold, or a
#: coefficient within ``ESTIMATE_ZERO_BAND`` (relative) of the solver's rounding to
#: zero, makes the estimate infinite (all far above the rounding of what they compare).
ESTIMATE_TOL = 1e-6
ESTIMATE_PAD = 1e-7
ESTIMATE_BAND = 1e-12
ESTIMATE_ZERO_BAND = 0.5

#: The compiled placement (:func:`fcgrasp.model.regions.place_regions_sure`) is sure to
#: find numpy's vertices when no active set's determinant is between
#: ``PLACE_NOISE_DET`` (below: singular up to rounding, for numpy too, far below the
#: singular test's :data:`SOLVER_TOL`) and ``PLACE_SURE_DET`` of its scale (a
#: near-singular set: its vertex is rounding), and no vertex is within
#: ``PLACE_SURE_BAND`` of a test's tolerance of that tolerance; a placement compared
#: with a threshold is sure when its margin exceeds ``PLACE_SURE_GAP`` of the edge.
PLACE_NOISE_DET = 1e-14
PLACE_SURE_DET = 1e-6
PLACE_SURE_BAND = 0.5
PLACE_SURE_GAP = 1e-7

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

#: Two neighbouring edges of a ring whose turn's sine exceeds this (their cross product
#: over their lengths' product, some thousand roundings clear of zero) meet only at their
#: common vertex: the simple-outline check leaves them out of shapely's intersections.
NEIGHBOUR_TURN = 1e-12

#: The documented range of inputs: coordinates (and every other input number) of
#: magnitude at most this, and parts at least ``1 / MAX_MAGNITUDE`` across.  Within it,
#: squares and products of coordinates stay far from float64 overflow and underflow, so
#: a part gives the same answer at every scale; outside it, inputs are refused with a
#: ``ValueError`` naming the argument.
MAX_MAGNITUDE = 1e100

#: A floor for divisors and scales that may be zero on a degenerate input: far below
#: anything fcgrasp resolves, it only turns ``0 / 0`` into ``0``.
TINY = 1e-300

#: Rounding slack of comparisons between quantities already relative to the problem's
#: size (a few thousand float64 ulps): nearly equal numbers compare equal, so ties are
#: decided by the next rule, not by noise.
ROUND_TOL = 1e-12

#: Relative rank tolerance of the quality measures' wrench sets (8.1): singular values
#: below this times the largest are zero.
RANK_RTOL = 1e-10

#: Parallel jaw: pad stops within this (times the part's size) are one contact (ties of
#: the extreme).
CONTACT_TOL = 1e-9

#: Parallel jaw: :func:`~fcgrasp.grippers.jaw.holding_offsets` is exact up to this (times
#: the part's size): it samples a cell this far inside its ends (past the contact
#: tolerance's bands around a vertex entering the strip), and a cell around a kink is
#: split (where one kink explains it, else halved) until it is 4 times this long; a
#: hole's insertion point is found to this too.
SLICE_TOL = 1e-6

#: Three fingers with friction: feasibility tolerance of the linear programs (HiGHS), in
#: units of the part's size.
LP_TOL = 1e-10

#: Three fingers with friction: a corner grasp whose witness misses a cone by more than
#: this (times the size) is not accepted (the solver's answer is checked, not trusted).
CHECK_TOL = 1e-8

#: Three fingers with friction, solved in closed form
#: (:mod:`fcgrasp.grippers.three_fingers._concurrency`):
#: the simplex's pivot threshold (programs in units of the part's size), how far Harris's
#: ratio test lets a basic variable dip below zero, a null combination of three normals
#: this small (or two lines' determinant: ``PARALLEL_TOL``) counts as none, and pieces
#: whose smallest regions agree to ``PIECE_TIE`` of the part's size tie (the first is
#: taken, whichever solver found them).
SIMPLEX_PIVOT = 1e-9
SIMPLEX_SLACK = 1e-12
NULL_TOL = 1e-14
PARALLEL_TOL = 1e-12
PIECE_TIE = 1e-9
#: A row of a linear program whose largest coefficient is below this fraction of the
#: program's largest is rounding noise: the dense simplex does not scale it up into a
#: constraint (four fingers' growth leaves such programs to HiGHS).
NOISE_ROW = 1e-9

#: Three fingers along the boundary: regions within this (relative) of the smallest are
#: the ones that must grow for the smallest to grow.
LEVEL_TIE = 1e-6

#: A gap between force directions this much above half a turn (radians) certainly
#: leaves them unable to span the plane; closer to it, rows are left to the exact test.
SPAN_SLACK = 1e-9

#: A soft finger's arc of force directions is capped this far (radians) below a
#: half-plane (conservative: a grasp that holds with the smaller arc holds with the
#: larger one).
ANGLE_CAP_GAP = 1e-6

#: Relative tolerance of :func:`~fcgrasp.model.outline.clean_outline` (times the part's
#: size).
CLEAN_TOL = 1e-7

#: DXF: ends of entities closer than this, relative to the drawing's extents, meet.
GAP_REL = 1e-6

#: Flattening: samples of a curve closer than this to the last one kept, relative to the
#: curve's extent, are one point (their chord's direction would be rounding noise).
CURVE_RESOLUTION = 1e-11

#: Finest curve flattening tolerance accepted, relative to the element's size: finer
#: would only multiply edges (a circle at 1e-6 already has about 2,000).
FLATTEN_FINEST = 1e-6

#: A drawn piece thinner than this (twice its area over its perimeter), relative to the
#: size of the file's largest piece, is a sliver of the drawing, not a part.
SLIVER_REL = 1e-4

#: The relative tolerance of a hand's box lying in its pad's strip
#: (:meth:`fcgrasp.model.hands.ParallelHand.in_strip`): a description's meshes are stored
#: in single precision, a relative 6e-8.
STRIP_TOL = 1e-6

__all__ = ["TOL", "CONE_TOL", "DEGENERATE_TOL", "LENGTH_RESOLUTION", "CURVE_RESOLUTION",
           "MAX_MAGNITUDE",
           "SOLVER_TOL", "ESTIMATE_TOL", "ESTIMATE_PAD", "ESTIMATE_BAND", "ESTIMATE_ZERO_BAND",
           "PLACE_NOISE_DET",
           "PLACE_SURE_DET", "PLACE_SURE_BAND", "PLACE_SURE_GAP", "LEXIMIN_STEP", "FACE_TOL",
           "RANK_TOL", "ON_EDGE_TOL", "COLLINEAR_TOL",
           "TINY", "ROUND_TOL", "RANK_RTOL", "CONTACT_TOL", "SLICE_TOL", "LP_TOL", "CHECK_TOL",
           "LEVEL_TIE", "SIMPLEX_PIVOT", "SIMPLEX_SLACK", "NULL_TOL", "PARALLEL_TOL",
           "PIECE_TIE", "NOISE_ROW", "SPAN_SLACK", "ANGLE_CAP_GAP", "CLEAN_TOL", "GAP_REL",
           "FLATTEN_FINEST", "SLIVER_REL", "ANGLE_SLACK", "CONE_PROGRAM_TOL",
           "INRADIUS_STEP", "FIT_ROUNDING", "PROJECTED_AXIS", "PLANAR_TOL",
           "ROUNDING_SHRINK", "SURFACE_TOL", "SURFACE_STEP",
           "SURFACE_CENTRE", "REACH_PAD", "SQUEEZE_TOL", "STRIP_TOL"]

#: Distinct alternatives: the upper bound of a region's overlap with another (its
#: length inside the other's box, :meth:`fcgrasp.model.distinct._Overlaps.reach`) is
#: raised by this fraction of itself (and by the overlap's tolerance): far above the
#: rounding of the clipped lengths and of the lengths shapely measures.
REACH_PAD = 1e-9

#: Radians added to the angular windows of the compiled two-finger stretch search
#: (:mod:`fcgrasp.model.stretches._kernels`): far above the rounding of the angles it
#: compares, so no cell the exact test would hold is left unread.
ANGLE_SLACK = 1e-6

#: Solid grasps: a margin of the force-closure cone program (Clarabel, interior point,
#: accurate to about 1e-8 with unit total normal force) below this is a tie, not force
#: closure.
CONE_PROGRAM_TOL = 1e-7

#: Solid grasps: the pieces' inscribed circles (the search's bound) are found to this
#: fraction of their size, and the bound adds it.
INRADIUS_STEP = 1e-3

#: Solid grasps: a solution a rounding outside its constraints (an interior point's, or
#: a closed-form fit's) is tried again shrunk by up to this fraction (first 1e-5 of it,
#: then 1e-2 of it, then all of it) before anything slower.
ROUNDING_SHRINK = 1e-7

#: Solid parts: triangles are one planar facet when every vertex lies within this
#: fraction of the mesh's size of the facet's plane (above the float32 rounding of STL
#: files, below the turn between the sides of a finely tessellated cylinder).
PLANAR_TOL = 1e-6

#: Solid grasps: the octagons' fits in triangles computed in a batch are bounds for the
#: exact fits once raised by this fraction (their rounding).
FIT_ROUNDING = 1e-9

#: Solid grasps across facets (:mod:`fcgrasp.spatial.surfaces`): relative rounding of
#: a patch's projected triangles (their union's area against the sum of theirs, its
#: collinear corners, the check that a convex piece lies inside it) and of a facing
#: line along a plane.
SURFACE_TOL = 1e-9

#: Solid grasps across facets: a region's radius is bisected to this fraction.
SURFACE_STEP = 1e-6

#: Solid grasps across facets: a patch's inscribed centre (where its convex piece is cut
#: from: any point well inside will do) is found to this fraction of its size.
SURFACE_CENTRE = 1e-2

#: Solid grasps: below this length, a facet's first axis projected into another facet's
#: plane is not a direction; the octagon turns along that facet's own axis instead.
PROJECTED_AXIS = 1e-3

#: Relative rounding of a 6-D hull's facets (qhull), taken off the certified radius of
#: three point contacts (:mod:`fcgrasp.spatial.triples`) and required of its offsets.
HULL_ROUNDING = 1e-9

#: The zero-force slice of three contacts' wrenches read from its vertices
#: (:mod:`fcgrasp.spatial._slice`): a support's weights at least minus this, its forces'
#: balance and its weights' sum within it, a pivot below it a singular support, and two
#: vertices within it one (the generators' entries are at most 1).
SLICE_WEIGHT_TOL = 1e-12

#: Solid parts: two facets are opposite parallel faces a parallel jaw's flat pads can
#: close on when their normals are opposite within this angle, radians (float32 meshes
#: round a small facet's normal to about 1e-6).
PARALLEL_FACETS = 1e-4

#: A test contact of the optimality bound (:mod:`fcgrasp.model.bounds`) closer than this
#: fraction of the part's size to a vertex is moved inside its edge, so it has one normal.
VERTEX_HAIR = 1e-9

#: Four frictionless fingers' pairs of opposite edges (:mod:`fcgrasp.pipeline._pair_rows`):
#: a force circuit's weight (a cross product of unit forces) within this of zero still
#: counts, so that rounding never loses a row's bound.
PAIR_RAY_TOL = 1e-12

#: The same: what a row's bound and the floor are padded by (relative), and the pairs'
#: window of angles (radians), for rounding.
PAIR_PAD = 1e-9

#: A bound on the relative rounding of a float coordinate (a few units in the last place
#: of a double, 2.2e-16): :func:`fcgrasp.model.distinct._shared_length` reads two regions'
#: shared pieces only where the coordinates' rounding is small against the buffer's width.
COORD_ROUNDING = 1e-15

#: The stress test's squeeze (:func:`fcgrasp.physics.squeeze_forces`): a grasp whose
#: smallest normal force in equilibrium is at most this share of the largest cannot be
#: squeezed.
SQUEEZE_TOL = 1e-6

#: Relative to a solid's size: a pair of pieces is proved to hold no two soft fingers
#: only where a direction separates them from the friction cones by this much
#: (:func:`fcgrasp.spatial._pieces.separated`); closer pairs go to the cone program.
SEPARATION_PAD = 1e-9

#: Relative to the reach of the rule of the same alternative on solids: a plan whose
#: centres are known only to lie in their pieces is decided the same alternative as a
#: kept plan (or not) only where the pieces' farthest (nearest) points are this much
#: inside (outside) the reach (:mod:`fcgrasp.spatial._grown`); else it is grown.
SIMILAR_PAD = 1e-9
