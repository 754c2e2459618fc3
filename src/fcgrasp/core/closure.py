r"""Force-closure tests (paper sections 4, 5 and 6).

Two families live here, and they share no code:

* the **general test** :func:`is_force_closure` (theorem 6.1: the wrench convexe is
  total, equivalently no twist is reciprocal or repelling to every wrench), exact for
  any number of generators;
* the paper's **geometric tests**, each its own function: :func:`force_direction_closure`
  (theorem 4.2 / corollary 4.1, the triangle containing the origin),
  :func:`torque_closure` (theorem 5.2 / corollary 5.2, the four-force pairing) and
  :func:`friction_pair_closure` (theorem 6.3, two point contacts with friction).

All take batches: arrays with any number of leading batch axes, and return a boolean
array of the batch shape (a single grasp is a batch of one, or a plain call on
unbatched arrays returning a 0-d array).

Ties are decided one way everywhere: a configuration on a boundary, or within ``tol``
of it, is **not** force closure (see :mod:`fcgrasp.core.tolerances`).

Two places where the paper's "vice versa" needs care, documented and tested:

* Theorem 4.2 claims that forces spanning all directions always contain a triple
  whose triangle strictly contains the origin.  The four normals of a rectangle,
  ``+-a, +-b``, are a counterexample (every triple has the origin on its boundary;
  Steinitz's bound in the plane is 4, not 3).  :func:`force_direction_closure` adds that
  case explicitly: two non-parallel pairs of opposite forces.
* Theorem 5.2 claims four forces suffice for torque closure.  For four forces it is
  exact; for more, forces that oppose each other along one line (a squeezing pair) can
  give closure that no four of them give.  :func:`torque_closure` searches every
  four-subset as the theorem states and is therefore *conservative* for more than four
  forces in that degenerate case: it may say "no" to a closure grasp, never "yes" to a
  grasp that is not.  :func:`is_force_closure` is exact.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from itertools import combinations
from typing import TYPE_CHECKING, cast

import numpy as np

from . import kernels
from ._checks import FloatArray, check_array, check_mu, check_tol
from ._geom import cross2 as _cross2
from .sectors import PAIRINGS, line_meet
from .tolerances import DEGENERATE_TOL, LENGTH_RESOLUTION, TINY, TOL

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = [
    "is_force_closure",
    "closure_escape",
    "force_direction_closure",
    "direction_closure",
    "torque_closure",
    "friction_pair_closure",
    "friction_pair_modes",
    "normalize_wrenches",
    "closure_one",
]

_CHUNK = 1 << 21  # floats per working array when chunking batches



def _unit(v: FloatArray) -> FloatArray:
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(n > 0, v / np.where(n > 0, n, 1.0), 0.0)


# ----------------------------------------------------------------------------- general


def normalize_wrenches(wrenches: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Re-centre and scale planar wrenches so that the closure test is scale-aware.

    The origin is moved to the point nearest (in least squares) to all lines of force,
    torques are divided by the largest lever arm ``L`` about that centre, and
    each wrench is normalised to unit length.  None of this changes whether the cone is
    total (it is a positive linear change of coordinates), but it makes ``tol`` mean
    "an angle" whatever the units and the position of the part.

    Returns
    -------
    unit : ndarray, shape (..., k, 3)
    center : ndarray, shape (..., 2)
    length : ndarray, shape (...)
    """
    f = wrenches[..., :2]
    tau = wrenches[..., 2]
    fn2 = np.sum(f * f, axis=-1)
    isf = fn2 > 0
    with np.errstate(invalid="ignore", divide="ignore"):
        k = np.where(isf, tau / np.where(isf, fn2, 1.0), 0.0)
    r0 = np.stack([k * f[..., 1], -k * f[..., 0]], axis=-1)   # foot of each line
    # least-squares point nearest to all lines (regularised towards the feet's mean)
    fh = _unit(f)
    proj = np.eye(2) - fh[..., :, None] * fh[..., None, :]           # (..., k, 2, 2)
    proj = proj * isf[..., None, None]
    a = np.sum(proj, axis=-3)
    b = np.sum(r0, axis=-2)
    cnt = np.maximum(np.sum(isf, axis=-1), 1)
    mean = b / cnt[..., None]
    lam = TOL * np.maximum(np.trace(a, axis1=-2, axis2=-1), TINY)
    a = a + lam[..., None, None] * np.eye(2)
    center = np.linalg.solve(a, (b + lam[..., None] * mean)[..., None])[..., 0]
    tau_c = tau - _cross2(center[..., None, :], f)
    with np.errstate(invalid="ignore", divide="ignore"):
        arm = np.where(isf, np.abs(tau_c) / np.sqrt(np.where(isf, fn2, 1.0)), 0.0)
    length = np.max(arm, axis=-1) if arm.shape[-1] else np.ones(arm.shape[:-1])
    # torques carry a rounding error of about eps * |r| (|r|: distance of the lines from
    # the origin the wrenches were written about); lever arms below that noise divided
    # by the tolerance are not resolved, so the scale never drops under it
    dist = np.sqrt(np.sum(r0 * r0, axis=-1))
    floor = LENGTH_RESOLUTION * np.max(dist, axis=-1, initial=0.0)
    length = np.maximum(length, floor)
    length = np.where(length > 0, length, 1.0)
    scaled = np.concatenate([f, (tau_c / length[..., None])[..., None]], axis=-1)
    return _unit(scaled), center, length


def _closure_chunk(u: FloatArray, tol: float) -> tuple[np.ndarray, FloatArray]:
    """Core of the general test on unit wrenches (n, k, 3): closure flags and escapes."""
    n, k, _ = u.shape
    pairs = np.array(list(combinations(range(k), 2)), dtype=int).reshape(-1, 2)
    c = np.cross(u[:, pairs[:, 0]], u[:, pairs[:, 1]])           # (n, P, 3)
    cn = np.linalg.norm(c, axis=-1)
    valid = cn > DEGENERATE_TOL
    c = c / np.where(valid, cn, 1.0)[..., None]
    dots = np.einsum("npd,nkd->npk", c, u)
    mn = dots.min(axis=-1, initial=np.inf)
    mx = dots.max(axis=-1, initial=-np.inf)
    esc_pos = valid & (mn >= -tol)
    esc_neg = valid & (mx <= tol)
    closure = valid.any(axis=-1) & ~(esc_pos | esc_neg).any(axis=-1)
    # escape direction y (in the normalised frame): u . y >= -tol for every wrench
    y = np.zeros((n, 3))
    has_pos = esc_pos.any(axis=-1)
    has_neg = esc_neg.any(axis=-1)
    if pairs.shape[0]:                  # one wrench has no pair (and no closure)
        ip = np.argmax(esc_pos, axis=-1)
        ineg = np.argmax(esc_neg, axis=-1)
        rows = np.arange(n)
        y[has_pos] = c[rows, ip][has_pos]
        only_neg = ~has_pos & has_neg
        y[only_neg] = -c[rows, ineg][only_neg]
    # no valid pair: every wrench is parallel to one line (or zero): any orthogonal y
    none = ~valid.any(axis=-1) & ~closure
    if np.any(none):
        first = u[none][np.arange(int(none.sum())), np.argmax(np.linalg.norm(u[none], axis=-1) > 0,
                                                              axis=-1)]
        trial = np.cross(first[:, None, :], np.eye(3)[None, :, :])   # (m, 3, 3)
        best = np.argmax(np.linalg.norm(trial, axis=-1), axis=-1)
        yy = _unit(trial[np.arange(first.shape[0]), best])
        zero = np.linalg.norm(first, axis=-1) == 0
        yy[zero] = [1.0, 0.0, 0.0]
        y[none] = yy
    y[closure] = np.nan
    return closure, y


def closure_escape(wrenches: ArrayLike, tol: float = TOL) -> tuple[np.ndarray, FloatArray]:
    r"""General force-closure test with a witness (theorem 6.1).

    A grasp is force closure when its wrench convexe is the whole space, i.e. when no
    non-zero twist ``t`` satisfies :math:`[W] t^s \ge 0` (eq. 12, 19).  If the cone is
    not total it lies in a closed half-space whose boundary plane is spanned by two
    generators, so it suffices to try the normals ``w_i x w_j`` of all generator pairs:
    the grasp is force closure iff every such plane has generators strictly on both
    sides (by more than ``tol`` in the normalised frame of :func:`normalize_wrenches`).

    Parameters
    ----------
    wrenches : array_like, shape (..., k, 3)
        Generating wrenches ``(fx, fy, tau)`` of each grasp.
    tol : float
        Decision tolerance (default :data:`fcgrasp.core.tolerances.TOL`).

    Returns
    -------
    closure : ndarray of bool, shape (...)
    escape : ndarray, shape (..., 3)
        For grasps that are not force closure, a non-zero twist ``(omega, vx, vy)``
        reciprocal or repelling to every wrench (within ``tol``): a motion that breaks
        the grasp.  NaN where the grasp is force closure.
    """
    tol = check_tol(tol)
    w = check_array(wrenches, "wrenches", last=3, min_ndim=2)
    batch = w.shape[:-2]
    k = w.shape[-2]
    w = w.reshape(-1, k, 3)
    n = w.shape[0]
    closure = np.zeros(n, dtype=bool)
    escape = np.zeros((n, 3))
    if n == 0:
        return closure.reshape(batch), escape.reshape(batch + (3,))
    per = max(1, _CHUNK // max(1, (k * (k - 1) // 2) * max(k, 3)))
    for s in range(0, n, per):
        u, center, length = normalize_wrenches(w[s:s + per])
        cl, y = _closure_chunk(u, tol)
        # back to a twist about the true origin: t^s = (y0, y1, y2 / L) about the centre
        om = y[:, 2] / length
        vx = y[:, 0] + om * center[:, 1]
        vy = y[:, 1] - om * center[:, 0]
        t = np.stack([om, vx, vy], axis=-1)
        closure[s:s + per] = cl
        escape[s:s + per] = t
    return closure.reshape(batch), escape.reshape(batch + (3,))


#: Wrenches up to which one grasp is decided by :func:`closure_one` (plain floats: its
#: pairs times wrenches stay a few hundred operations); more go through the batch.
ONE_GRASP_WRENCHES = 12


def closure_one(wrenches: list[tuple[float, float, float]], tol: float = TOL) -> bool:
    """:func:`is_force_closure` of one grasp, in plain float arithmetic (theorem 6.1).

    The same steps as the batched test (:func:`normalize_wrenches`, then every plane
    spanned by two generators must have generators strictly on both sides), on Python
    floats: a single grasp pays no numpy call, and stops at the first plane with every
    generator on one side.  The numbers agree with the batch to rounding (the batch
    solves its 2 x 2 system by LAPACK, this one by Cramer's rule), so only grasps within
    a few ulps of ``tol`` of the boundary can be decided differently; tested against
    the batch on random and degenerate grasps.  ``tol`` is not checked here."""
    k = len(wrenches)
    feet, unit_f = [], []
    a00 = a01 = a11 = b0 = b1 = 0.0
    cnt = 0
    for fx, fy, tau in wrenches:
        fn2 = fx * fx + fy * fy
        if fn2 > 0:
            q = tau / fn2
            rx, ry = q * fy, -q * fx
            n = math.sqrt(fn2)
            hx, hy = fx / n, fy / n
            a00 += 1.0 - hx * hx
            a01 -= hx * hy
            a11 += 1.0 - hy * hy
            cnt += 1
        else:
            rx = ry = 0.0
        b0 += rx
        b1 += ry
        feet.append((rx, ry))
        unit_f.append(fn2)
    cnt = max(cnt, 1)
    lam = TOL * max(a00 + a11, TINY)
    a00 += lam
    a11 += lam
    r0, r1 = b0 + lam * (b0 / cnt), b1 + lam * (b1 / cnt)
    det = a00 * a11 - a01 * a01
    cx, cy = (r0 * a11 - a01 * r1) / det, (a00 * r1 - a01 * r0) / det
    length, dist = 0.0, 0.0
    taus = []
    for (fx, fy, tau), fn2, (rx, ry) in zip(wrenches, unit_f, feet, strict=True):
        tc = tau - (cx * fy - cy * fx)
        taus.append(tc)
        if fn2 > 0:
            length = max(length, abs(tc) / math.sqrt(fn2))
        dist = max(dist, math.sqrt(rx * rx + ry * ry))
    length = max(length, LENGTH_RESOLUTION * dist)
    if not length > 0:
        length = 1.0
    u = []
    for (fx, fy, _), tc in zip(wrenches, taus, strict=True):
        z = tc / length
        n = math.sqrt(fx * fx + fy * fy + z * z)
        u.append((fx / n, fy / n, z / n) if n > 0 else (0.0, 0.0, 0.0))
    any_valid = False
    for i in range(k):
        ax, ay, az = u[i]
        for j in range(i + 1, k):
            bx, by, bz = u[j]
            cx_, cy_, cz_ = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx
            cn = math.sqrt(cx_ * cx_ + cy_ * cy_ + cz_ * cz_)
            if not cn > DEGENERATE_TOL:
                continue
            any_valid = True
            cx_, cy_, cz_ = cx_ / cn, cy_ / cn, cz_ / cn
            lo, hi = math.inf, -math.inf
            for ux, uy, uz in u:
                d = cx_ * ux + cy_ * uy + cz_ * uz
                lo, hi = min(lo, d), max(hi, d)
                if lo < -tol and hi > tol:
                    break
            if lo >= -tol or hi <= tol:
                return False            # every generator on one side of this plane
    return any_valid


def is_force_closure(wrenches: ArrayLike, tol: float = TOL) -> np.ndarray:
    """General force-closure test (theorem 6.1): is the wrench convexe total?

    Parameters
    ----------
    wrenches : array_like, shape (..., k, 3)
        Generating wrenches ``(fx, fy, tau)``, any ``k``.
    tol : float
        Decision tolerance; configurations within ``tol`` of the boundary are not closure.

    Returns
    -------
    ndarray of bool, shape (...)

    Notes
    -----
    Write the wrenches about a point near the grasp for the finest resolution
    (:class:`~fcgrasp.Grasp` does): about an origin at distance ``D`` from the lines,
    lever arms are resolved down to ``TOL * LENGTH_RESOLUTION * D`` and decisions closer
    to the boundary than that are "not force closure".

    Examples
    --------
    Two opposite fingers with friction squeezing a unit square:

    >>> from fcgrasp import FrictionPoint, wrench_from_force
    >>> w = np.concatenate([FrictionPoint([0, .5], [-1, 0], 0.3).wrenches,
    ...                     FrictionPoint([1, .5], [1, 0], 0.3).wrenches])
    >>> bool(is_force_closure(w))
    True
    >>> bool(is_force_closure(w[:3]))   # one friction edge missing
    False
    """
    return closure_escape(wrenches, tol)[0]


# ----------------------------------------------------------------------------- theorem 4.2


def force_direction_closure(forces: ArrayLike, tol: float = TOL) -> np.ndarray:
    """Force-direction closure by corollary 4.1 (theorem 4.2).

    The forces can generate any direction iff three of them have end points drawing a
    non-zero triangle that strictly contains their common origin: the three pairwise
    cross products ``f1 x f2``, ``f2 x f3``, ``f3 x f1`` have one strict sign.  The
    rectangle case, two non-parallel pairs of opposite forces, is added (see the module
    notes): it spans all directions though no triangle does.

    Parameters
    ----------
    forces : array_like, shape (..., k, 2)
        Force directions (their magnitudes do not matter).
    tol : float
        Sines of angles within ``tol`` of zero count as zero.

    Returns
    -------
    ndarray of bool, shape (...)

    Examples
    --------
    >>> force_direction_closure([[1, 0], [-1, 1], [-1, -1]]).item()
    True
    >>> force_direction_closure([[1, 0], [0, 1], [-1, 0]]).item()    # origin on the boundary
    False
    >>> force_direction_closure([[1, 0], [0, 1], [-1, 0], [0, -1]]).item()  # rectangle
    True
    """
    tol = check_tol(tol)
    f = check_array(forces, "forces", last=2, min_ndim=2)
    u = _unit(f)
    k = u.shape[-2]
    out = np.zeros(u.shape[:-2], dtype=bool)
    if k >= 3:
        tri = np.array(list(combinations(range(k), 3)), dtype=int)
        a, b, c = u[..., tri[:, 0], :], u[..., tri[:, 1], :], u[..., tri[:, 2], :]
        s1, s2, s3 = _cross2(a, b), _cross2(b, c), _cross2(c, a)
        pos = (s1 > tol) & (s2 > tol) & (s3 > tol)
        neg = (s1 < -tol) & (s2 < -tol) & (s3 < -tol)
        out |= np.any(pos | neg, axis=-1)
    if k >= 4:
        pr = np.array(list(combinations(range(k), 2)), dtype=int)
        a, b = u[..., pr[:, 0], :], u[..., pr[:, 1], :]
        nonzero = (np.linalg.norm(a, axis=-1) > 0) & (np.linalg.norm(b, axis=-1) > 0)
        anti = nonzero & (np.abs(_cross2(a, b)) <= tol) & (np.sum(a * b, axis=-1) < 0)
        pp = np.array(list(combinations(range(len(pr)), 2)), dtype=int)
        cross_pairs = np.abs(_cross2(a[..., pp[:, 0], :], a[..., pp[:, 1], :])) > tol
        out |= np.any(anti[..., pp[:, 0]] & anti[..., pp[:, 1]] & cross_pairs, axis=-1)
    return out


def direction_closure(forces: FloatArray, tol: float = TOL) -> np.ndarray:
    """:func:`force_direction_closure` of a batch of force sets (B, k, 2): the same
    booleans, by :func:`rows_closure` with the forces as their own table (compiled where
    the batch repays it, :func:`fcgrasp.core.kernels.use_jit`; numpy else)."""
    f = np.ascontiguousarray(forces, dtype=float)
    if f.ndim != 3:
        return force_direction_closure(f, tol)
    B, k = f.shape[:2]
    return rows_closure(f.reshape(-1, 2), np.arange(B * k).reshape(B, k), tol)


def rows_closure(unit: FloatArray, rows: np.ndarray, tol: float = TOL) -> np.ndarray:
    """:func:`force_direction_closure` of the force sets ``unit[rows]`` (``rows``: (B, k)
    indices into the table of forces ``unit``), the same booleans: by the compiled loop,
    which reads each row's forces from the table instead of gathering them (a search's
    rows are millions, most of which fail the test), where the batch repays it
    (:func:`fcgrasp.core.kernels.use_jit`), by numpy else."""
    u = np.ascontiguousarray(unit, dtype=float)
    r = np.ascontiguousarray(rows, dtype=np.int64)
    if r.ndim == 2 and r.shape[0] and kernels.use_jit(r.shape[0]):
        out = np.empty(r.shape[0], dtype=np.bool_)
        if kernels._run("_rows_closure_loop", u, r, float(tol), out):
            return out
    return force_direction_closure(u[r], tol)


# ----------------------------------------------------------------------------- theorem 5.2



def _in_open_cone(fa: FloatArray, fb: FloatArray, sab: FloatArray, d: FloatArray,
                  tol: float) -> np.ndarray:
    """d strictly inside the cone of fa, fb (the sector of angle < pi)."""
    return (sab * _cross2(fa, d) > tol) & (sab * _cross2(d, fb) > tol)


def _pairing_test(p: FloatArray, f: FloatArray, order: Sequence[int], tol: float) -> np.ndarray:
    a, b, c, d = (int(i) for i in order)
    pa, pb, pc, pd = p[..., a, :], p[..., b, :], p[..., c, :], p[..., d, :]
    fa, fb, fc, fd = f[..., a, :], f[..., b, :], f[..., c, :], f[..., d, :]
    xab, xcd = _cross2(fa, fb), _cross2(fc, fd)
    ok = (np.abs(xab) > tol) & (np.abs(xcd) > tol)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        p12 = line_meet(pa, fa, pb, fb)      # masked by ok where the pair is parallel
        p34 = line_meet(pc, fc, pd, fd)
    p12 = np.where(ok[..., None], p12, 0.0)
    p34 = np.where(ok[..., None], p34, 0.0)
    seg = p34 - p12
    sn = np.linalg.norm(seg, axis=-1)
    ok &= sn > tol
    dh = seg / np.where(sn > 0, sn, 1.0)[..., None]
    sab, scd = np.sign(xab), np.sign(xcd)
    out_12 = _in_open_cone(fa, fb, sab, dh, tol)     # P12 -> P34 points out of C12 ...
    into_34 = _in_open_cone(fc, fd, scd, -dh, tol)    # ... and into C34
    out_34 = _in_open_cone(fc, fd, scd, dh, tol)
    into_12 = _in_open_cone(fa, fb, sab, -dh, tol)
    return cast("np.ndarray", ok & ((out_12 & into_34) | (into_12 & out_34)))


def torque_closure(points: ArrayLike, forces: ArrayLike, tol: float = TOL) -> np.ndarray:
    r"""Torque closure of pure forces by corollary 5.2 (theorem 5.2).

    Four forces generate clockwise and counter-clockwise torques iff for some pairing
    ``[(w1, w2), (w3, w4)]`` the segment from ``P12`` (where the lines of ``w1``, ``w2``
    meet) to ``P34`` points out of one of the cones ``C12``, ``C34`` and into the other:
    :math:`P_{34} - P_{12} = \pm(\alpha f_1 + \beta f_2) = \mp(\gamma f_3 + \delta f_4)`
    with all coefficients strictly positive (eq. 32).  All three pairings are tried
    (corollary 5.1 says one non-degenerate pairing decides, and the tests check it).
    For pure forces this condition also gives force-direction closure, so it is the
    paper's geometric test of force closure (section 6).  With more than four forces
    every four-subset is tried (conservative, see the module notes).

    Parameters
    ----------
    points : array_like, shape (..., k, 2)
        A point on each line of action.
    forces : array_like, shape (..., k, 2)
        Force directions.
    tol : float
        Sines of angles, and lengths relative to the spread of the points, within
        ``tol`` of zero count as zero.

    Returns
    -------
    ndarray of bool, shape (...)

    Examples
    --------
    Four fingers pinching a unit square, two on each side, offset:

    >>> pts = [[0, .2], [0, .8], [1, .2], [1, .8]]
    >>> torque_closure(pts, [[1, 0], [1, 0], [-1, 0], [-1, 0]]).item()  # no vertical force
    False
    >>> pts = [[0, .5], [.3, 0], [1, .7], [.7, 1]]     # the two couples turn both ways
    >>> torque_closure(pts, [[1, 0], [0, 1], [-1, 0], [0, -1]]).item()
    True
    """
    tol = check_tol(tol)
    p = check_array(points, "points", last=2, min_ndim=2)
    f = check_array(forces, "forces", last=2, min_ndim=2)
    if p.shape[-2] != f.shape[-2]:
        raise ValueError(f"points and forces must have the same number of lines, got "
                         f"{p.shape[-2]} and {f.shape[-2]}")
    p, f = np.broadcast_arrays(p, f)
    k = p.shape[-2]
    out = np.zeros(p.shape[:-2], dtype=bool)
    if k < 4:
        return out
    u = _unit(f)
    center = p.mean(axis=-2, keepdims=True)
    spread = np.max(np.linalg.norm(p - center, axis=-1), axis=-1)
    spread = np.where(spread > 0, spread, 1.0)
    q = (p - center) / spread[..., None, None]
    for sub in combinations(range(k), 4):
        idx = list(sub)
        qs, us = q[..., idx, :], u[..., idx, :]
        for order in PAIRINGS:
            out |= _pairing_test(qs, us, order, tol)
    return out


# ----------------------------------------------------------------------------- theorem 6.3


def _angle(a: FloatArray, b: FloatArray) -> FloatArray:
    return cast("FloatArray", np.arctan2(np.abs(_cross2(a, b)), np.sum(a * b, axis=-1)))


def friction_pair_modes(p: ArrayLike, normal_p: ArrayLike, q: ArrayLike, normal_q: ArrayLike,
                        mu: ArrayLike, mu_q: ArrayLike | None = None, tol: float = TOL
                        ) -> tuple[np.ndarray, np.ndarray]:
    """Theorem 6.3 split by mode: (squeezing, expanding) boolean arrays.

    *Squeezing*: the finger at P pushes towards Q and the one at Q towards P (the
    segment PQ lies strictly inside both friction cones).  *Expanding*: the fingers
    push apart, from the inside of a hole.  See :func:`friction_pair_closure`.
    """
    tol = check_tol(tol)
    p = check_array(p, "p", last=2)
    q = check_array(q, "q", last=2)
    npn = check_array(normal_p, "normal_p", last=2)
    nqn = check_array(normal_q, "normal_q", last=2)
    for name, v in (("normal_p", npn), ("normal_q", nqn)):
        if np.any(np.linalg.norm(v, axis=-1) == 0):
            raise ValueError(f"{name} must be non-zero vectors, got a zero vector")
    mu_p = check_mu(mu, "mu")
    mu_q_arr = mu_p if mu_q is None else check_mu(mu_q, "mu_q")
    named = {"p": p.shape[:-1], "normal_p": npn.shape[:-1], "q": q.shape[:-1],
             "normal_q": nqn.shape[:-1], "mu": mu_p.shape, "mu_q": mu_q_arr.shape}
    try:
        np.broadcast_shapes(*named.values())
    except ValueError:
        shapes = ", ".join(f"{k} {v}" for k, v in named.items())
        raise ValueError(f"p, normal_p, q, normal_q and mu must broadcast to one batch "
                         f"shape, got {shapes}") from None
    phi_p, phi_q = np.arctan(mu_p), np.arctan(mu_q_arr)
    d = q - p
    dn = np.linalg.norm(d, axis=-1)
    scale = np.maximum(np.maximum(np.linalg.norm(p, axis=-1), np.linalg.norm(q, axis=-1)), dn)
    ok = dn > tol * scale
    dh = d / np.where(dn > 0, dn, 1.0)[..., None]
    fp, fq = -_unit(npn), -_unit(nqn)
    squeeze = ok & (_angle(dh, fp) < phi_p - tol) & (_angle(-dh, fq) < phi_q - tol)
    expand = ok & (_angle(-dh, fp) < phi_p - tol) & (_angle(dh, fq) < phi_q - tol)
    return squeeze, expand


def friction_pair_closure(p: ArrayLike, normal_p: ArrayLike, q: ArrayLike, normal_q: ArrayLike,
                          mu: ArrayLike,
                          mu_q: ArrayLike | None = None, tol: float = TOL) -> np.ndarray:
    """Two point contacts with friction by theorem 6.3.

    The grasp at P and Q is force closure iff the segment PQ points out of the friction
    cone at P and into the friction cone at Q (strictly): the squeezing grasp, where
    the fingers push towards each other, or the expanding grasp from the inside of a
    hole, where they push apart.

    Parameters
    ----------
    p, q : array_like, shape (..., 2)
        Contact points.
    normal_p, normal_q : array_like, shape (..., 2)
        Outward normals of the object at P and Q (any length but zero).
    mu : array_like, shape (...)
        Friction coefficient at P (and at Q unless ``mu_q`` is given).
    mu_q : array_like, optional
        Friction coefficient at Q.
    tol : float
        Angles within ``tol`` radians of a friction-cone edge count as outside.

    Returns
    -------
    ndarray of bool, shape (...)

    Examples
    --------
    >>> friction_pair_closure([0, 0], [-1, 0], [1, 0.2], [1, 0], 0.3).item()
    True
    >>> friction_pair_closure([0, 0], [-1, 0], [1, 0.5], [1, 0], 0.3).item()
    False
    """
    squeeze, expand = friction_pair_modes(p, normal_p, q, normal_q, mu, mu_q, tol)
    return cast("np.ndarray", squeeze | expand)
