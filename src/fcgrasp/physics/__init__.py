r"""A physics stress test of planned grasps: the part and the fingers in MuJoCo, loads
ramped up until the part slips (the paper's section 8: how much a grasp resists).

fcgrasp proves that every grasp of a plan's regions is force closure and certifies the
load it carries with force-limited fingers (:func:`fcgrasp.grasp_payload`).  This module
checks those figures in a physics simulator that shares none of that code: for each
grasp sampled in a plan's regions (the regions' ends included) and each of a few seeded
disturbance directions, it reports whether the part held, the load at which it slipped
and how far it moved, beside the certified payload.

**The model** (SI units inside; lengths in the part's units outside).  The planar part
is extruded into a prism of uniform density moving in its plane (two slides and a hinge:
no gravity in the plane).  Each finger is a sphere on a slide along its contact's inward
normal (a jaw's pads: two boxes on slides along the closing direction).  The squeeze
first sets each finger's force to its share of a squeeze that balances the others (a
linear program over the friction cones: the internal forces of the grasp, the largest
smallest one, scaled so the largest is ``grip_force``; none exists when the grasp cannot
be squeezed).  The certificate is computed with each finger's squeeze as its force
limit.  A grasp's contact forces are statically indeterminate (three fingers with
friction have more unknowns than the plane has equations), and the certificate is that
of the best ones; so the fingers are force controlled and **balance the load they
measure** (grasp force optimisation, :func:`balance_forces`: at each load along the ramp
the forces inside the friction cones, as deep inside as they can be, that balance it),
each pushing up to twice its squeeze: a grasp whose contacts are what the certificate
reads holds to twice its certified payload and slips there.  ``control="servo"`` puts
each finger on a stiff position servo instead (saturating at twice its squeeze), the
load shared as the stiffness of contacts and servos shares it; frictionless fingers
always are (force control leaves their part nothing to hold it in place).  The
disturbance is a wrench of fixed direction (a force at the centre of mass and a torque,
per newton) ramped from 0 to ``ramp`` times the certified payload over ``ramp_time``
seconds; the part **slipped** when it moved more than ``SLIP_DISPLACEMENT`` of the
part's size or turned more than ``SLIP_ROTATION_DEG``.

**Settings that make the answer physics, not artefacts:** elliptic friction cones (the
Coulomb cone itself, not a pyramid); the noslip solver (MuJoCo's regularised friction
creeps without it: a grasp below its limit would slowly slide); stiff contacts
(``solref`` 1 ms, ``solimp`` 0.95-0.99: fingers close together resist a torque by forces
that grow as their spacing shrinks, and a softer contact lets the part turn past the
slip threshold without slipping) and friction as stiff as the normal (``impratio`` 10);
a 0.25 ms time step, a quarter of the contact's time constant; the servo's stiffness
puts the full preload at 0.2 % of the part's size (the fingers' own motion stays well
below the slip threshold) with critical damping.

**What it can and cannot tell:** it checks loads, not the exact ends of the regions (a
grasp at a region's end is at the margin of its friction cone, and a simulator's
contact is soft); a non-force-closure control slips under the disturbance along its
escape motion at loads far below any grip force.  MuJoCo is an optional dependency
(``pip install mujoco``, the ``sim`` extra).
"""

from __future__ import annotations

from ._forces import balance_forces, cone_margin, sample_grasps, squeeze_forces
from ._planar import (
    SLIP_DISPLACEMENT,
    SLIP_ROTATION_DEG,
    VARIANTS,
    StressResult,
    jaw_contacts,
    jaw_stress_test,
    stress_test,
)
from ._runs import (
    animate,
    animate_solid,
    control,
    control_runs,
    escape_direction,
    jaw_of,
    recorded_run,
    sample_poses,
    sensitivity,
    simulate,
)
from ._solids import (
    sample_solid_grasps,
    solid_escape,
    solid_jaw_torsion,
    solid_plan_of,
    solid_squeeze,
    solid_stress_test,
)

__all__ = ["simulate", "stress_test", "sample_grasps", "squeeze_forces", "balance_forces",
           "StressResult",
           "control", "escape_direction", "SLIP_DISPLACEMENT", "SLIP_ROTATION_DEG",
           "animate", "jaw_stress_test", "jaw_contacts", "jaw_of", "sample_poses",
           "solid_stress_test", "solid_squeeze", "sample_solid_grasps", "solid_plan_of",
           "solid_jaw_torsion", "animate_solid", "recorded_run",
           "solid_escape", "control_runs", "sensitivity", "VARIANTS", "cone_margin"]
