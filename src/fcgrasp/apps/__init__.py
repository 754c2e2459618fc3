"""The front ends: each builds a :class:`~fcgrasp.planning.PlanRequest` from its own
input and plans through :func:`~fcgrasp.planning.plan_document`.

- :mod:`~fcgrasp.apps.cli`: ``fcgrasp`` (plan, check, parts, demo; the launcher of batch
  and serve);
- :mod:`~fcgrasp.apps.batch`: :func:`~fcgrasp.plan_many`, ``fcgrasp batch`` (a local pool
  or Dask);
- :mod:`~fcgrasp.apps.serve`: ``fcgrasp serve``, the explorer, and its page in
  ``explorer/``.

The batch runner and the explorer never import the command line or each other.
"""
