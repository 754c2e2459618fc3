"""Mechanics of planar grasps, with no notion of a part or a gripper (sections 2-6).

- :mod:`~fcgrasp.core.screws`: wrenches, twists, virtual work (2.1, 2.2, 2.4);
- :mod:`~fcgrasp.core.convexes`: cones, their sum, intersection and dual (2.3);
- :mod:`~fcgrasp.core.contacts`: primitive contacts and their total freedom (3.1);
- :mod:`~fcgrasp.core.grasp`: :class:`~fcgrasp.Grasp`, its verdict, reason and escape (3.2);
- :mod:`~fcgrasp.core.closure`: the general test and the geometric tests (4, 5, 6);
- :mod:`~fcgrasp.core.sectors`: section 6 on arrays (pairings, sectors, pair arcs);
- :mod:`~fcgrasp.core.kernels`: the two-finger closed forms, numpy or compiled by numba;
- :mod:`~fcgrasp.core.tolerances`: every named tolerance; ``_checks`` (boundary checks),
  ``_angles`` (the one angle wrap), ``_geom`` and ``_json`` are private helpers.
"""
