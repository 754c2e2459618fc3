"""Imported once by the explorer's fork server (:class:`fcgrasp.apps._serve_jobs.Jobs`): every
numba kernel compiled or loaded from its cache there (:func:`fcgrasp.compile_kernels`,
about a second), so that each planning process forked from it runs them from its first
plan instead of numpy's many small calls (four fingers on a 2,000-edge part
103 -> 73 ms in process)."""

from __future__ import annotations

from ..planning.compiled import compile_kernels

compile_kernels()
