r"""Convexes: polyhedral convex cones and their algebra (paper section 2.3).

A *convexe* :math:`C^<` is the set of non-negative combinations of its generating
vectors (definition 2.3, eq. 5).  :class:`Cone` stores one in R^d (d = 2, 3, 6 or any
other) and implements

* convex addition (definition 2.4, the Minkowski sum): ``c1 + c2``;
* intersection (definition 2.5): ``c1 & c2``;
* the dual (definition 2.6, eq. 8): ``c.dual()``.  Between planar wrenches
  ``(fx, fy, tau)`` and planar twists ``(omega, vx, vy)`` (and between spatial
  wrenches and twists) it uses the spatial transpose, so the dual of a wrench cone is
  the twist cone of the motions that are reciprocal or repelling to every wrench:
  the *total freedom*.  For a cone without a space it is the ordinary dual cone
  :math:`\{y : Gy \ge 0\}`;
* ``is_null()``, ``is_total()``, ``contains(v)``, equality and ``minimal()``.

Non-pointed and lower-dimensional cones are handled: a cone is represented after
``minimal()`` by its extreme rays (orthogonal to its lineality space) and an
orthonormal basis of its lineality space (``lines``), each line standing for the two
opposite generators ``+l`` and ``-l``; a free rotation thus appears once, as one
bidirectional twist.

Lemma 2.1 holds for these operations; its item 3 holds in the form
``C & C.polar()`` null and ``C + C.polar()`` total, with the polar cone
``C.polar() = {y : x . y <= 0}`` (Moreau's decomposition).  Read literally with the
dual (``>= 0``) item 3 is false: the positive orthant of R^2 is its own dual.

The algebra uses exact combinatorics on unit-normalised generators with the
tolerance :data:`fcgrasp.core.tolerances.CONE_TOL`: extreme rays of ``{y : Ay >= 0}`` are
enumerated as the null vectors of (rank - 1)-subsets of the rows (no cdd needed), and
membership is a non-negative least-squares problem (``scipy.optimize.nnls``).
"""

from __future__ import annotations

from itertools import combinations
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from ._checks import FloatArray, check_array, check_tol
from .tolerances import CONE_TOL, DEGENERATE_TOL, ROUND_TOL

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


__all__ = ["Cone", "SPACES"]

#: Spaces a cone may live in, with their dimension and the space of their dual.
SPACES: dict[str | None, tuple[int | None, str | None]] = {
    None: (None, None),
    "wrench": (3, "twist"),
    "twist": (3, "wrench"),
    "spatial_wrench": (6, "spatial_twist"),
    "spatial_twist": (6, "spatial_wrench"),
}

# For a cone of the key's space, the dual's defining rows are A with A[:, perm] = G:
# virtual work w . t^s written as a dot product in the dual vector's own coordinates.
_DUAL_PERM = {
    "wrench": [1, 2, 0],          # w . (vx, vy, omega) -> columns of t = (omega, vx, vy)
    "twist": [2, 0, 1],           # t . (tau, fx, fy)
    "spatial_wrench": [3, 4, 5, 0, 1, 2],
    "spatial_twist": [3, 4, 5, 0, 1, 2],
}

_MAX_COMBINATIONS = 3_000_000


def _unit_rows(g: FloatArray) -> FloatArray:
    """Drop zero rows (relative to the longest, below DEGENERATE_TOL) and normalise the others."""
    if g.shape[0] == 0:
        return g
    norm = np.linalg.norm(g, axis=1)
    keep = norm > max(float(norm.max()) * DEGENERATE_TOL, 0.0)
    return cast("FloatArray", g[keep] / norm[keep, None])


def _dedupe(rays: FloatArray, tol: float) -> FloatArray:
    """Remove unit rays that repeat another (up to ``tol``)."""
    out: list[FloatArray] = []
    for r in rays:
        if not any(float(r @ s) > 1.0 - tol for s in out):
            out.append(r)
    return np.array(out).reshape(-1, rays.shape[1])


def halfspace_rays(a: ArrayLike, dim: int | None = None, tol: float = CONE_TOL
                   ) -> tuple[FloatArray, FloatArray]:
    r"""Minimal generators of the cone :math:`\{y \in R^d : A y \ge 0\}`.

    Parameters
    ----------
    a : array_like, shape (m, d)
        One inequality per row.
    dim : int, optional
        ``d``, needed only when ``m == 0``.
    tol : float
        Rank and feasibility tolerance on unit-normalised rows.

    Returns
    -------
    rays : ndarray, shape (p, d)
        Unit extreme rays, orthogonal to the lineality space.
    lines : ndarray, shape (q, d)
        Orthonormal basis of the lineality space (the null space of ``A``).

    Examples
    --------
    >>> rays, lines = halfspace_rays([[1.0, 0.0], [0.0, 1.0]])
    >>> rays.round(6).tolist(), lines.shape
    ([[0.0, 1.0], [1.0, 0.0]], (0, 2))
    """
    a = np.asarray(a, dtype=float)
    if a.ndim != 2:
        if dim is None:
            raise ValueError(f"a must have shape (m, d), got shape {a.shape}")
        a = a.reshape(0, dim)
    d = a.shape[1]
    a = _unit_rows(a)
    if a.shape[0] == 0:
        return np.zeros((0, d)), np.eye(d)
    _, s, vt = np.linalg.svd(a)
    rank = int(np.sum(s > tol * max(1.0, s[0])))
    lines = vt[rank:]
    q = vt[:rank]                       # orthonormal basis of the row space
    b = a @ q.T                         # (m, rank): the pointed part in row-space coords
    if rank == 1:
        cand = np.array([[1.0], [-1.0]])
    else:
        b = _dedupe(_unit_rows(b), tol)
        m = b.shape[0]
        n_comb = _n_choose(m, rank - 1)
        if n_comb > _MAX_COMBINATIONS:
            raise ValueError(f"cone too large for exact enumeration: {m} inequalities in "
                             f"dimension {rank} give {n_comb} subsets")
        idx = np.array(list(combinations(range(m), rank - 1)), dtype=int)
        sub = b[idx]                                        # (n, rank-1, rank)
        _, ss, vv = np.linalg.svd(sub)
        ok = ss[:, -1] > tol
        cand = vv[ok, -1, :]
    vals = cand @ b.T                                       # (n, m)
    scale = np.max(np.abs(vals), axis=1)
    keep = scale > tol
    pos = np.all(vals >= -tol, axis=1) & keep
    neg = np.all(vals <= tol, axis=1) & keep
    rays_u = np.concatenate([cand[pos], -cand[neg]])
    rays = rays_u @ q
    rays = _dedupe(_unit_rows(rays), tol) if rays.shape[0] else rays.reshape(0, d)
    return rays, lines


def _n_choose(n: int, k: int) -> int:
    from math import comb
    return comb(n, k) if 0 <= k <= n else 0


def _in_cone(unit_gens: FloatArray, v: FloatArray, tol: float) -> bool:
    norm = float(np.linalg.norm(v))
    if norm == 0.0:
        return True
    if unit_gens.shape[0] == 0:
        return False
    from scipy.optimize import nnls  # imported on first use: import fcgrasp stays light

    _, res = nnls(unit_gens.T, v / norm)
    return bool(res <= tol * 10.0 + ROUND_TOL)


class Cone:
    """A polyhedral convex cone (a *convexe*, definition 2.3) in R^d.

    Parameters
    ----------
    generators : array_like, shape (k, d)
        Generating vectors; the cone is their non-negative combinations.  ``k`` may be
        zero (the null cone), then give ``dim``.
    space : {None, "wrench", "twist", "spatial_wrench", "spatial_twist"}
        What the vectors are.  It decides how :meth:`dual` pairs vectors.
    lines : array_like, shape (q, d), optional
        Bidirectional generators (each ``l`` stands for ``+l`` and ``-l``).
    dim : int, optional
        Ambient dimension when there are no generators.
    tol : float
        Tolerance of the cone algebra (see :mod:`fcgrasp.core.tolerances`).

    Examples
    --------
    A frictionless point contact at the origin pushing down (outward normal +y):

    >>> from fcgrasp import wrench_from_force
    >>> w = Cone([wrench_from_force([0.0, -1.0], [0.0, 0.0])], space="wrench")
    >>> t = w.dual().minimal()
    >>> len(t.lines), len(t.rays)          # two free motions, one unisense lift-off
    (2, 1)
    >>> t.rays.round(6).tolist()           # move down, away from the finger
    [[0.0, 0.0, -1.0]]
    """

    __hash__ = None  # type: ignore[assignment]

    def __init__(self, generators: ArrayLike, space: str | None = None, *,
                 lines: ArrayLike | None = None,
                 dim: int | None = None, tol: float = CONE_TOL) -> None:
        if space not in SPACES:
            raise ValueError(f"space must be one of {sorted(map(str, SPACES))}, got {space!r}")
        self.tol = check_tol(tol)
        g = check_array(generators, "generators", min_ndim=1)
        if g.ndim == 1:
            g = g.reshape(1, -1) if g.size else g.reshape(0, dim or 0)
        if g.ndim != 2:
            raise ValueError(f"generators must have shape (k, d), got shape {g.shape}")
        d = g.shape[1] if g.shape[0] or dim is None else dim
        if g.shape[0] == 0:
            if dim is None and g.shape[1] == 0:
                raise ValueError("generators is empty: give dim for the null cone")
            d = dim if dim is not None else g.shape[1]
            g = g.reshape(0, d)
        want = SPACES[space][0]
        if want is not None and d != want:
            raise ValueError(f"a {space} cone needs vectors of length {want}, got {d}")
        if lines is None:
            ln = np.zeros((0, d))
        else:
            ln = check_array(lines, "lines", min_ndim=1).reshape(-1, d) if np.size(lines) \
                else np.zeros((0, d))
        self.space = space
        self.dim = int(d)
        self.rays: FloatArray = g
        self.lines: FloatArray = ln

    # -------------------------------------------------------------- basics
    @property
    def generators(self) -> FloatArray:
        """All generators, with each line as the two rays ``+l`` and ``-l``, shape (k, d)."""
        return np.concatenate([self.rays, self.lines, -self.lines])

    def _unit(self) -> FloatArray:
        return _unit_rows(self.generators)

    def __repr__(self) -> str:
        return (f"Cone(rays={self.rays.round(6).tolist()}, lines={self.lines.round(6).tolist()}, "
                f"space={self.space!r})")

    def _same_kind(self, other: Any, op: str) -> Cone:
        if not isinstance(other, Cone):
            raise TypeError(f"cannot apply {op} to Cone and {type(other).__name__}")
        if other.dim != self.dim or other.space != self.space:
            raise ValueError(f"cannot apply {op} to a {self.space} cone in R^{self.dim} and a "
                             f"{other.space} cone in R^{other.dim}")
        return other

    # -------------------------------------------------------------- operations
    def __add__(self, other: Cone) -> Cone:
        """Convex addition, the Minkowski sum (definition 2.4, eq. 6)."""
        other = self._same_kind(other, "+")
        return Cone(np.concatenate([self.rays, other.rays]), self.space,
                    lines=np.concatenate([self.lines, other.lines]), dim=self.dim, tol=self.tol)

    def _inequalities(self) -> FloatArray:
        """Rows D with ``self = {x : D x >= 0}`` (generators of the ordinary dual cone)."""
        rays, lines = halfspace_rays(self._unit().reshape(-1, self.dim), self.dim, self.tol)
        return np.concatenate([rays, lines, -lines])

    def __and__(self, other: Cone) -> Cone:
        """Intersection (definition 2.5, eq. 7)."""
        other = self._same_kind(other, "&")
        a = np.concatenate([self._inequalities(), other._inequalities()])
        rays, lines = halfspace_rays(a.reshape(-1, self.dim), self.dim, self.tol)
        return Cone(rays, self.space, lines=lines, dim=self.dim, tol=self.tol)

    def dual(self) -> Cone:
        """The dual convexe (definition 2.6, eq. 8): vectors reciprocal or repelling to all.

        For a wrench cone this is the twist cone of the total freedom; for a twist cone,
        the wrench cone.  The result is in minimal form.
        """
        g = self.generators
        perm = _DUAL_PERM.get(self.space or "")
        if perm is None:
            a = g
        else:
            a = np.empty_like(g)
            a[:, perm] = g
        rays, lines = halfspace_rays(a.reshape(-1, self.dim), self.dim, self.tol)
        return Cone(rays, SPACES[self.space][1], lines=lines, dim=self.dim, tol=self.tol)

    def polar(self) -> Cone:
        """The polar cone ``{y : x . y <= 0 for all x in self}``, in the same space."""
        g = np.concatenate([self.rays, self.lines, -self.lines])
        rays, lines = halfspace_rays(-_unit_rows(g).reshape(-1, self.dim), self.dim, self.tol)
        return Cone(rays, self.space, lines=lines, dim=self.dim, tol=self.tol)

    def minimal(self) -> Cone:
        """A minimal generating set: extreme rays plus a basis of the lineality space.

        The rays are the given generators (normalised) when the cone is pointed, and their
        projections orthogonal to the lineality space otherwise.
        """
        unit = self._unit()
        if unit.shape[0] == 0:
            return Cone(np.zeros((0, self.dim)), self.space, dim=self.dim, tol=self.tol)
        _, lines = halfspace_rays(self._inequalities().reshape(-1, self.dim), self.dim, self.tol)
        proj = unit - (unit @ lines.T) @ lines if lines.shape[0] else unit
        proj = _unit_rows(np.where(np.linalg.norm(proj, axis=1, keepdims=True) > self.tol,
                                   proj, 0.0))
        proj = _dedupe(proj, self.tol) if proj.shape[0] else proj
        keep = list(range(proj.shape[0]))
        for i in range(proj.shape[0]):
            others = [j for j in keep if j != i]
            basis = np.concatenate([proj[others], lines, -lines])
            if _in_cone(basis, proj[i], self.tol):
                keep.remove(i)
        return Cone(proj[keep].reshape(-1, self.dim), self.space, lines=lines, dim=self.dim,
                    tol=self.tol)

    # -------------------------------------------------------------- predicates
    def is_null(self) -> bool:
        """True when the cone is ``{0}``."""
        return bool(self._unit().shape[0] == 0)

    def is_total(self) -> bool:
        """True when the cone is the whole space (its dual is null)."""
        rays, lines = halfspace_rays(self._unit().reshape(-1, self.dim), self.dim, self.tol)
        return bool(rays.shape[0] == 0 and lines.shape[0] == 0)

    def contains(self, v: ArrayLike) -> Any:
        """Membership of ``v`` (shape (d,) or (n, d)); returns a bool or a bool array."""
        arr = check_array(v, "v", last=self.dim)
        unit = self._unit()
        flat = arr.reshape(-1, self.dim)
        out = np.array([_in_cone(unit, x, self.tol) for x in flat], dtype=bool)
        return bool(out[0]) if arr.ndim == 1 else out.reshape(arr.shape[:-1])

    def __contains__(self, v: ArrayLike) -> bool:
        return bool(self.contains(v))

    def issubset(self, other: Cone) -> bool:
        """True when every generator of ``self`` lies in ``other``."""
        other = self._same_kind(other, "issubset")
        g = self._unit()
        return bool(np.all(other.contains(g))) if g.shape[0] else True

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Cone):
            return NotImplemented
        if other.dim != self.dim or other.space != self.space:
            return False
        return self.issubset(other) and other.issubset(self)

    @property
    def lineality_dim(self) -> int:
        """Dimension of the largest linear subspace inside the cone."""
        return int(self.minimal().lines.shape[0])
