"""The parallel jaw's pose model compiled: :func:`poses` evaluates a batch of
poses in one loop, pose by pose and edge by edge, with the same formulas, in the same
order, as the numpy model of :mod:`._poses` (``_pad``, ``_sides_of``, ``_inside``,
``_verdict``), which stays the reference (``FCGRASP_JIT=0``, and the tests: verdicts
equal wherever a slack is not within rounding of zero, values to 1e-12 of the size).

numpy spends its time on calls over arrays of a few elements (a pose batch of a grid
tile, a cell's three points, a box's centre); the loop pays none of them and allocates
only its outputs.  Compiled by numba on first use, cached on disk beside the loops'
modules (:mod:`._pose_kernels`, :mod:`._proof_kernels`, :mod:`._slice_kernels`)
(:func:`fcgrasp.compile_kernels` does it ahead of time); without numba, or with
``FCGRASP_JIT=0``, :func:`available` is False and the numpy model runs.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...core.jit import CompiledLoops
from . import _pose_kernels, _proof_kernels, _slice_kernels
from ._pose_kernels import (
    K_MAX,
    _features,
    _hole_sides,
    _inside_ring,
    _outer_pads,
    _pad_loop,
    _pose_at,
    _pose_one,
)
from ._proof_kernels import (
    _as_corners,
    _below,
    _corners_hold,
    _nan_max,
    _nan_min,
    _pool_add,
    _range,
    _sin_range,
    _vrange,
    _wrap_positive,
)
from ._slice_kernels import (
    _affine,
    _affine3,
    _kind,
    _kink,
    _quantities,
    _stop_reach,
)


def poses(th: Any, c: Any, a: Any, b: Any, f: Any, half: float, tol: float,
          q: Any, stroke: tuple[float, float], beta: float, round_tol: float
          ) -> tuple[Any, ...] | None:
    """Every pose ``(th[p], c[p])`` of the batch against the edges ``a``-``b`` (E, 2,
    from the centroid) whose contact forces are ``f`` (E, 2); ``q``: the insertion point
    from the centroid (internal grip) or None.  Returns ``(top, bottom, ok_a, ok_b,
    lat_a, lat_b, psi_a, psi_b, col_a, col_b, holds, slacks)`` as ``_poses._evaluate``
    builds them, or None when the compiled loop cannot run."""
    P, K = th.shape[0], K_MAX
    top, bottom = np.empty(P), np.empty(P)
    ok_a, ok_b = np.zeros(P, bool), np.zeros(P, bool)
    lat_a, lat_b = np.full((P, K, 2), np.nan), np.full((P, K, 2), np.nan)
    psi_a, psi_b = np.full((P, K), np.nan), np.full((P, K), np.nan)
    col_a, col_b = np.full((P, K), -1, np.int64), np.full((P, K), -1, np.int64)
    holds = np.zeros(P, bool)
    slacks = np.full((P, 2 * K * K + 2), np.nan)
    internal = q is not None
    qq = np.zeros(2) if q is None else np.ascontiguousarray(q, dtype=float)
    if not _run("_poses_loop", np.ascontiguousarray(th, dtype=float),
                np.ascontiguousarray(c, dtype=float),
                np.ascontiguousarray(a, dtype=float),
                np.ascontiguousarray(b, dtype=float),
                np.ascontiguousarray(f, dtype=float), float(half), float(tol),
                internal, qq, float(stroke[0]), float(stroke[1]), float(beta),
                -1.0 if internal else 1.0, float(round_tol), top, bottom, ok_a,
                ok_b, lat_a, lat_b, psi_a, psi_b, col_a, col_b, holds, slacks):
        return None
    return (top, bottom, ok_a, ok_b, lat_a, lat_b, psi_a, psi_b, col_a, col_b, holds,
            slacks)


def grid(th: Any, c: Any, a: Any, b: Any, f: Any, half: float, tol: float, q: Any,
         stroke: tuple[float, float], beta: float, round_tol: float,
         details: bool = False) -> Any:
    """Whether each pose of the grid ``th x c`` (``c`` evenly spaced, increasing) holds,
    (K, M) booleans (:func:`_grid_loop`: the verdicts of :func:`poses`, each pose
    reading only the edges near its strip); with ``details``, ``(holds, opening,
    edge_a, edge_b)`` (the edges as indices of ``a``, -1 for none); None when the
    compiled loop cannot run."""
    K, M = len(th), len(c)
    H = np.zeros((K, M), dtype=np.bool_)
    shape = (K, M) if details else (1, 1)
    opening = np.full(shape, np.nan)
    edge_a = np.full((*shape, K_MAX), -1, np.int64)
    edge_b = np.full((*shape, K_MAX), -1, np.int64)
    internal = q is not None
    qq = np.zeros(2) if q is None else np.ascontiguousarray(q, dtype=float)
    if not _run("_grid_loop", np.ascontiguousarray(th, dtype=float),
                np.ascontiguousarray(c, dtype=float), np.ascontiguousarray(a, dtype=float),
                np.ascontiguousarray(b, dtype=float), np.ascontiguousarray(f, dtype=float),
                float(half), float(tol), internal, qq, float(stroke[0]), float(stroke[1]),
                float(beta), -1.0 if internal else 1.0, float(round_tol), H, bool(details),
                opening, edge_a, edge_b):
        return None
    return (H, opening, edge_a, edge_b) if details else H


def box_scores(H: Any, dth: float, dc: float, radius: float, max_rows: int
               ) -> tuple[float, int, int, int, int] | None:
    """The largest box of True cells of the pose grid ``H`` (``_grid._box_scores``),
    compiled; None when the loop cannot run."""
    out = np.array([-1.0, 0, 0, 0, 0])
    if not _run("_box_loop", np.ascontiguousarray(H, dtype=np.bool_), float(dth), float(dc),
                float(radius), int(max_rows), out):
        return None
    return float(out[0]), int(out[1]), int(out[2]), int(out[3]), int(out[4])


def _proof_args(boxes: Any, a: Any, b: Any, nrm: Any, uniq: Any, inv: Any, half: float,
                zero: float, contact_tol: float, tol: float, q: Any, beta: float,
                stroke: tuple[float, float], pooled: bool) -> tuple[Any, ...]:
    """The arguments :func:`_prove_loop` and :func:`_certify_loop` begin with, typed."""
    def floats(x: Any) -> Any:
        return np.ascontiguousarray(x, dtype=float)

    qq = np.zeros(2) if q is None else floats(q)
    return (floats(boxes), floats(a), floats(b), floats(nrm), floats(uniq),
            np.ascontiguousarray(inv, dtype=np.int64), float(half), float(zero),
            float(contact_tol), float(tol), q is not None, qq, float(beta),
            float(stroke[0]), float(stroke[1]), bool(pooled))


def prove(boxes: Any, a: Any, b: Any, nrm: Any, uniq: Any, inv: Any, half: float,
          zero: float, contact_tol: float, tol: float, q: Any, beta: float,
          stroke: tuple[float, float], pooled: bool) -> tuple[Any, Any, Any] | None:
    """The proofs of a batch of boxes (``_certify._box_proofs_numpy``): ``(proved,
    o_lo, o_hi)``, compiled; None when the loop cannot run."""
    B = boxes.shape[0]
    proved, o_lo, o_hi = np.zeros(B, bool), np.empty(B), np.empty(B)
    if not _run("_prove_loop", *_proof_args(boxes, a, b, nrm, uniq, inv, half, zero,
                                            contact_tol, tol, q, beta, stroke, pooled),
                proved, o_lo, o_hi):
        return None
    return proved, o_lo, o_hi


def slices(cell_t: Any, cell_lo: Any, cell_hi: Any, th: Any, a: Any, b: Any, f: Any,
           half: float, tol: float, q: Any, stroke: tuple[float, float], beta: float,
           round_tol: float, slice_tol: float, tiny: float, atol: float, near: float,
           stop_gap: float = 0.0, failed: Any = None, upward: bool = False,
           prune: bool = True) -> Any:
    """The holding pieces of the cells (``_slices.holding_offsets``; sorted by angle),
    compiled: rows ``(angle index, lo, hi)``; None when the loop cannot run.
    ``stop_gap`` > 0: an angle is given up at its first piece longer than that which does
    not hold (``failed``, a boolean array over the angles, set there), each angle read
    from its lowest offset up with ``upward`` (else from the highest down)."""
    internal = q is not None
    if failed is None:
        failed = np.zeros(len(th), dtype=np.bool_)
    qq = np.zeros(2) if q is None else np.ascontiguousarray(q, dtype=float)
    out: list[Any] = []
    if not _run("_slices_loop",
                np.ascontiguousarray(cell_t, dtype=np.int64),
                np.ascontiguousarray(cell_lo, dtype=float),
                np.ascontiguousarray(cell_hi, dtype=float),
                np.ascontiguousarray(th, dtype=float), np.ascontiguousarray(a, dtype=float),
                np.ascontiguousarray(b, dtype=float), np.ascontiguousarray(f, dtype=float),
                float(half), float(tol), internal, qq, float(stroke[0]), float(stroke[1]),
                float(beta), -1.0 if internal else 1.0, float(round_tol), float(slice_tol),
                float(tiny), float(atol), float(near), float(stop_gap), failed,
                bool(upward), bool(prune) and not internal, answer=out):
        return None
    return out[0]


# ----------------------------------------------------------------------------- loading

#: The loops called per pose, per edge or per cell that allocate nothing and make no
#: view: compiled without reference counts (:func:`~fcgrasp.core.jit.njit_all`).
_BORROWING = (_features, _pad_loop, _outer_pads, _hole_sides, _inside_ring, _pose_at,
              _pose_one, _sin_range, _range, _wrap_positive, _vrange, _nan_min, _nan_max,
              _below, _corners_hold, _as_corners, _pool_add, _kind, _affine3, _affine,
              _quantities, _kink, _stop_reach)

_LOOPS = CompiledLoops.of_modules((_pose_kernels, _proof_kernels, _slice_kernels),
                                   borrowing=_BORROWING)


def _run(name: str, *args: Any, answer: list[Any] | None = None) -> bool:
    """Run the compiled loop ``name`` (:meth:`CompiledLoops.run`; its return value
    appended to ``answer``): False when it cannot run (numpy then)."""
    ok, got = _LOOPS.run(name, *args)
    if ok and answer is not None:
        answer.append(got)
    return ok


def available() -> bool:
    """Are the jaw's poses evaluated compiled here?  Always, but with ``FCGRASP_JIT=0``
    or without a working numba (then by the numpy model)."""
    return _LOOPS.available()


def certify(boxes: Any, a: Any, b: Any, nrm: Any, uniq: Any, inv: Any, half: float,
            zero: float, contact_tol: float, tol: float, q: Any, beta: float,
            stroke: tuple[float, float], pooled: bool, max_boxes: int, radius: float,
            near: float, round_tol: float) -> tuple[bool, float, float, int] | None:
    """``_certify.certify_box``'s subdivision from the boxes ``boxes`` (B, 4), compiled
    (:func:`_certify_loop`): ``(proved, lo, hi, boxes examined)``; None when the loop
    cannot run."""
    out = np.zeros(4)
    if not _run("_certify_loop", *_proof_args(boxes, a, b, nrm, uniq, inv, half, zero,
                                              contact_tol, tol, q, beta, stroke, pooled),
                int(max_boxes), float(radius), float(near), float(round_tol), out):
        return None
    return bool(out[0]), float(out[1]), float(out[2]), int(out[3])
