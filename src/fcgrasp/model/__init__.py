"""The part and the paper's constructions on it (sections 6-8).

- :mod:`~fcgrasp.model.polygon`: :class:`~fcgrasp.Polygon`, the part, and
  :func:`~fcgrasp.model.polygon.check_polygon`;
- :mod:`~fcgrasp.model.outline`: fill rules, clean-up and simplification of outlines;
- :mod:`~fcgrasp.model.graspsets`: grasp sets on chosen edges (6, theorems 6.2-6.4);
- :mod:`~fcgrasp.model.regions`: optimal independent regions (7, theorem 7.1);
- :mod:`~fcgrasp.model.stretches`, :mod:`~fcgrasp.model.frictionless_stretches`: regions
  along the boundary, across vertices;
- :mod:`~fcgrasp.model.hand`: workspace and finger radius (8.2);
- :mod:`~fcgrasp.model.quality`, :mod:`~fcgrasp.model.ranking`: the measures (8.1) and
  their registry; :mod:`~fcgrasp.model.plans`: :class:`~fcgrasp.GraspPlan` and its keys;
- :mod:`~fcgrasp.model.loads`: loads with finger force limits, for a grasp and over a
  plan's regions; :mod:`~fcgrasp.model.robustness`: the probability that a two-finger
  plan holds under placement errors; :mod:`~fcgrasp.model.stability`: fingers as
  springs, the grasp stiffness and its stability.
"""
