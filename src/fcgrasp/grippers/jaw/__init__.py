r"""A parallel-jaw gripper: where two flat pads on one slide can close on a part.

**Model.**  Two flat pads of width ``pad_width``, parallel, close along the direction
``u = (cos theta, sin theta)``, centred on the line at lateral offset ``c`` from the
part's centroid (``c = (x - centroid) . n`` with ``n = (-sin theta, cos theta)``): the
pads sweep the strip ``|(x - centroid) . n - c| <= pad_width / 2``.  Closing, each pad
stops on the part's extreme material within the strip: pad ``A`` (coming from ``+u``)
at the largest ``x . u``, pad ``B`` at the smallest.  A pad touches

* a **vertex** inside the strip: a point contact with friction whose normal is the
  pad's (``-u`` for ``A``, ``+u`` for ``B``), or
* an **edge parallel to the pad**: an edge contact with friction (figure 4.d), or
* an edge at the pad's **corner** (the extreme lies on the strip's side, as on a flat
  face slightly turned from the pad): a point contact with friction whose normal is
  the edge's, not the pad's.

The pose holds when the two contacts are force closure (theorem 6.3, two fingers with
friction: some point of one contact sees some point of the other strictly inside both
friction cones, shrunk by ``margin``; between the pads' own normals this is
``|lateral offset| < tan(atan(mu) - margin) * opening``) and the opening (the part's
width in the strip along ``u``) is within the stroke.  External grips close on the outline;
internal grips open inside a hole: the closed jaws go in at the hole's
:func:`insertion_point` (its pole of inaccessibility, fixed in the part), so at a pose
they sit on the strip's segment at that point's height, which must be free (no edge of
the hole crosses it) and inside the hole; opening, pad ``A`` (facing ``+u``) meets the
first boundary above that height, pad ``B`` the first below (in a non-convex hole the
nearest of several; on a curved hole a flat pad meets the boundary at its corners).

**Tolerance boxes.**  The answer is not one pose but a box of poses
``theta in [t0, t1]``, ``c in [c0, c1]`` every pose of which holds, the analogue of
independent regions.  The set of holding poses is evaluated exactly at every pose of a
grid (:data:`THETA_STEP_DEG`, :data:`OFFSET_STEPS` across the part) by
:func:`jaw_poses`; the largest box of holding grid poses by the measure
``min(c1 - c0, (t1 - t0) * radius)`` (the offset range, and the angular range as the
arc it sweeps at the part's radius: both lengths) is then checked on a grid
:data:`CHECK_DENSITY` times finer and shrunk by grid steps until every checked pose
holds.  :func:`certify_box` then *proves* that every pose of the box holds, between the
grid points too (sound, not complete; a box it cannot prove is shrunk, then dropped).

**The exact set.**  At a fixed closing angle the set's slice is computed exactly
(:func:`holding_offsets`: every quantity of the model is piecewise affine in the offset,
so the slice's ends are roots of the verdict's slacks, found in closed form, or kinks of
a pad's stop, located by halving).  The box's shape is searched on the exact set itself
(for the ``REFINE_TOP`` best boxes of each grip): on a raster of the exact
slices' intervals through an anchor offset (every grid step, finer near the run's ends:
a five-hundredth of the box's measure), the run of angles and the offset interval inside
all of them with the largest measure (then the largest area) near the grid's box, apart
from the plans found before and their images; moved in from the raster's boundary by
0.25 % of each side (else 0.5 %, 1 %) and proved, it replaces the grid's box where it
measures more.  Where it does not, or gains under 5 %, the grid's box is also grown to
the set's exact boundary: its offset range to the nearest ends of the slices at
:data:`CHECK_DENSITY` angles per grid step across it, its angle range by bisection on
the slices; the box on the boundary cannot be proved (its sub-boxes would have to
shrink to nothing there), so it is moved in by a quarter of a grid step (else a half,
:data:`GROW_BACKOFF`), proved, and kept where it measures more and overlaps no plan found
before.  On the built-in parts the top box is within 1 % of the largest box of a
0.1-degree raster of the exact set (the grown grid box was up to 8 % short), and no
returned box overlaps another or its images.
:func:`jaw_plans` returns proved boxes unless asked not to (``certify=False``: boxes
verified on the fine grid only, neither proved nor grown).

**Compiled.**  The pose model, the grid's largest box, the proofs and the slices run as
numba loops (:mod:`._kernels`, compiled once and cached; :func:`fcgrasp.compile_kernels`)
with the formulas of the numpy model, which stays the reference (``FCGRASP_JIT=0`` or
no numba: the same boxes, tested).
"""

from __future__ import annotations

from ...core.tolerances import SLICE_TOL
from ._certify import certify_box
from ._grid import grid_anchor
from ._pareto import jaw_pareto
from ._payload import jaw_payload
from ._pick import Scene, TopPick, top_pick
from ._plans import JawPlan, ParallelJaw, jaw_from_options, jaw_plans
from ._poses import (
    CERTIFY_BOXES,
    CERTIFY_SHRINKS,
    CHECK_DENSITY,
    OFFSET_STEPS,
    THETA_STEP_DEG,
    PoseContacts,
    convex_holes,
    insertion_point,
    jaw_poses,
)
from ._slices import holding_offsets

__all__ = ["ParallelJaw", "jaw_from_options", "JawPlan", "PoseContacts", "convex_holes",
           "jaw_poses",
           "holding_offsets", "insertion_point", "jaw_plans", "jaw_pareto", "certify_box",
           "jaw_payload", "grid_anchor", "THETA_STEP_DEG", "Scene", "TopPick", "top_pick",
           "SLICE_TOL", "OFFSET_STEPS", "CHECK_DENSITY", "CERTIFY_BOXES", "CERTIFY_SHRINKS"]
