r"""Contacts on a solid part and the wrenches they apply (the paper's section 3
and its conclusion's "grasps of 3D objects").

A contact touches the part at ``point`` and pushes along the **inward** unit ``normal``
(into the part).  Three models, as in Mason and Salisbury's catalogue:

* **frictionless point**: a force ``f_n n``, ``f_n >= 0``;
* **point with friction** (Coulomb): ``f = f_n n + f_1 t_1 + f_2 t_2`` with
  :math:`\sqrt{f_1^2 + f_2^2} \le \mu f_n`, a circular cone (the exact quadratic cone;
  the linearised pyramid of :func:`contact_wrench_generators` is an option);
* **soft finger**: a point with friction plus a moment ``m_n`` about the normal, with the
  elliptic limit surface :math:`\sqrt{f_1^2 + f_2^2 + (\mu m_n / \gamma)^2} \le \mu f_n`
  (``torsion = gamma``, a length: the torsional friction per unit normal force).  Its
  linearisation bounds ``|m_n| <= gamma f_n`` separately.

Wrenches are spatial, ``w = (f, m)`` with ``m = (p - c) x f + m_n n`` about a reference
point ``c`` (:func:`fcgrasp.core.screws.spatial_wrench_from_force` order: force first).
Force components are written in each contact's frame ``(n, t_1, t_2)``
(:func:`contact_frames`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core._checks import FloatArray, check_array
from ..core.tolerances import TOL

__all__ = ["SpatialContact", "contact_frames", "contact_maps", "contact_wrench_generators",
           "check_spatial_contacts", "check_spatial_grasp", "FRICTIONLESS", "FRICTION",
           "SOFT"]

FRICTIONLESS = "frictionless"
FRICTION = "friction"
SOFT = "soft"


@dataclass(frozen=True)
class SpatialContact:
    """One contact: ``point`` (3,), inward unit ``normal`` (3,), friction ``mu`` (0:
    frictionless) and ``torsion`` (soft finger: the torsional friction length ``gamma``
    of the elliptic limit surface; 0: a point contact)."""

    point: tuple[float, float, float]
    normal: tuple[float, float, float]
    mu: float = 0.0
    torsion: float = 0.0

    def __post_init__(self) -> None:
        p, n, mu, tor = check_spatial_contacts([self.point], [self.normal], self.mu,
                                               self.torsion)
        object.__setattr__(self, "point", tuple(float(v) for v in p[0]))
        object.__setattr__(self, "normal", tuple(float(v) for v in n[0]))
        object.__setattr__(self, "mu", float(mu[0]))
        object.__setattr__(self, "torsion", float(tor[0]))

    @property
    def kind(self) -> str:
        """``"frictionless"``, ``"friction"`` or ``"soft"``."""
        if self.mu == 0:
            return FRICTIONLESS
        return SOFT if self.torsion > 0 else FRICTION


def check_spatial_contacts(points: Any, normals: Any, mu: Any = 0.0, torsion: Any = 0.0
                           ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Points (..., k, 3), unit inward normals (..., k, 3), and ``mu`` and ``torsion``
    broadcast to (..., k): checked (finite, normals nonzero, ``mu >= 0``, ``torsion >=
    0``, torsion only with friction); normals are normalised."""
    p = check_array(points, "points", last=3, min_ndim=2)
    n = check_array(normals, "normals", last=3, min_ndim=2)
    if p.shape != n.shape:
        raise ValueError(f"points and normals must have the same shape, got {p.shape} and "
                         f"{n.shape}")
    length = np.linalg.norm(n, axis=-1)
    if np.any(length <= TOL):
        raise ValueError(f"normals must be nonzero vectors, got {normals!r}")
    n = n / length[..., None]
    m = np.broadcast_to(check_array(mu, "mu"), p.shape[:-1]).astype(float)
    if np.any(m < 0):
        raise ValueError(f"mu must be >= 0, got {mu!r}")
    return p, n, m, check_torsion(torsion, m, mu)


def check_torsion(torsion: Any, m: FloatArray, mu: Any) -> FloatArray:
    """A soft finger's ``torsion`` (a length) broadcast to the contacts' checked friction
    ``m`` (..., k), checked: ``>= 0``, and only with friction (``mu``: as the caller
    gave it, for the error)."""
    tor = np.broadcast_to(check_array(torsion, "torsion"), m.shape).astype(float)
    if np.any(tor < 0):
        raise ValueError(f"torsion must be >= 0 (a length), got {torsion!r}")
    if np.any((tor > 0) & (m == 0)):
        raise ValueError(f"torsion (a soft finger) needs friction: mu > 0 where torsion > 0, "
                         f"got mu={mu!r}, torsion={torsion!r}")
    return tor


def check_spatial_grasp(points: Any, normals: Any, mu: Any, torsion: Any, center: Any,
                        radius: float | None) -> tuple[FloatArray, FloatArray, FloatArray,
                                                       FloatArray, FloatArray, float]:
    """One grasp of ``k`` contacts checked (:func:`check_spatial_contacts`, shape (k, 3)),
    with the point torques are taken about (``center``, default the contacts' mean) and
    the ``radius`` that divides them (default the largest distance of a contact from
    it): ``(points, normals, mu, torsion, center, radius)``."""
    p, n, m, tor = check_spatial_contacts(points, normals, mu, torsion)
    if p.ndim != 2:
        raise ValueError(f"points must be one grasp, shape (k, 3), got {p.shape}")
    c = p.mean(axis=0) if center is None else check_array(center, "center", last=3)
    if radius is None:
        radius = max(float(np.max(np.linalg.norm(p - c, axis=1))), TOL)
    return p, n, m, tor, c, float(radius)


def contact_frames(normals: Any) -> tuple[FloatArray, FloatArray]:
    """Two unit tangents ``t_1, t_2`` (..., 3) completing each unit normal to a
    right-handed frame ``(n, t_1, t_2)``; a smooth choice away from ``n = -z``
    (Frisvad's construction with the singular branch handled).

    >>> t1, t2 = contact_frames([[0.0, 0.0, 1.0]])
    >>> (t1 + 0.0).tolist(), (t2 + 0.0).tolist()
    ([[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]])
    """
    n = np.asarray(normals, dtype=float)
    x, y, z = n[..., 0], n[..., 1], n[..., 2]
    sign = np.where(z >= 0, 1.0, -1.0)
    a = -1.0 / (sign + z)
    b = x * y * a
    t1 = np.stack([1.0 + sign * x * x * a, sign * b, -sign * x], axis=-1)
    t2 = np.stack([b, sign + y * y * a, -y], axis=-1)
    # (n, t1, t2) right-handed: t1 x t2 = n
    flip = np.einsum("...i,...i->...", np.cross(t1, t2), n) < 0
    t2 = np.where(flip[..., None], -t2, t2)
    return t1, t2


def contact_maps(points: Any, normals: Any, torsion: Any = 0.0, center: Any = None,
                 radius: float = 1.0) -> FloatArray:
    """Each contact's wrench map ``G_i`` (..., k, 6, 4): the spatial wrench (force,
    moment about ``center`` divided by ``radius``) of the local force ``(f_n, f_1, f_2,
    m_n)``; the fourth column is the torsional moment (zero unless the contact is soft).

    ``center`` defaults to the contacts' mean (per grasp); ``radius`` scales torques to
    forces (the part's radius makes the measures unit-free, Ferrari and Canny's ``lambda``).
    """
    p = np.asarray(points, float)
    n = np.asarray(normals, float)
    t1, t2 = contact_frames(n)
    c = p.mean(axis=-2, keepdims=True) if center is None else \
        np.asarray(center, float)[..., None, :]
    r = (p - c) / float(radius)
    tor = np.broadcast_to(np.asarray(torsion, float), p.shape[:-1])
    G = np.zeros(p.shape[:-1] + (6, 4))
    for j, d in enumerate((n, t1, t2)):
        G[..., :3, j] = d
        G[..., 3:, j] = np.cross(r, d)
    G[..., 3:, 3] = np.where(tor[..., None] > 0, n / float(radius), 0.0)
    return G


def contact_wrench_generators(points: Any, normals: Any, mu: Any = 0.0, torsion: Any = 0.0,
                              facets: int = 8, center: Any = None, radius: float = 1.0,
                              outer: bool = False) -> FloatArray:
    """The wrenches spanning each contact's linearised cone, (..., k, g, 6) with ``g =
    facets`` (friction), ``2 facets`` (soft: the pyramid's edges with ``+-gamma f_n``
    torsion) or ``facets`` copies of the normal (frictionless, so every contact has the
    same count).  Forces have a unit normal component (``n + mu (cos a t_1 + sin a
    t_2)``, as Dex-Net's and GraspIt!'s generators).

    ``outer=False``: the pyramid inscribed in the cone (a grasp it proves in force
    closure is); ``outer=True``: the circumscribed one (``mu / cos(pi / facets)``; a grasp
    it refutes is not in force closure).  The soft finger's generators linearise the
    limit surface by the box ``|f_t| <= mu f_n``, ``|m_n| <= gamma f_n`` (outer) or by
    its inscribed points ``(mu cos a, mu sin a, 0)`` and ``(0, 0, +-gamma)`` (inner).
    """
    p, n, m, tor = check_spatial_contacts(points, normals, mu, torsion)
    if not isinstance(facets, (int, np.integer)) or facets < 3:
        raise ValueError(f"facets must be an integer >= 3, got {facets!r}")
    G = contact_maps(p, n, tor, center, radius)
    a = 2 * np.pi * np.arange(facets) / facets
    widen = 1.0 / np.cos(np.pi / facets) if outer else 1.0
    mus = m[..., None] * widen                                   # (..., k, 1)
    local = np.zeros(p.shape[:-1] + (facets, 4))
    local[..., 0] = 1.0
    local[..., 1] = mus * np.cos(a)
    local[..., 2] = mus * np.sin(a)
    if np.any(tor > 0):
        # soft contacts: the torsion's two extremes with every force edge (outer), or the
        # force edges and the two pure torsions (inner): 2 facets generators each
        tw = np.where(tor > 0, tor, 0.0)[..., None]
        if outer:
            plus, minus = local.copy(), local.copy()
            plus[..., 3], minus[..., 3] = tw, -tw
            local = np.concatenate([plus, minus], axis=-2)
        else:
            extra = np.zeros(p.shape[:-1] + (facets, 4))
            extra[..., 0] = 1.0
            half = facets // 2
            extra[..., :half, 3] = tw
            extra[..., half:, 3] = -tw
            soft = (tor > 0)[..., None]
            extra[..., 1] = np.where(soft, 0.0, local[..., 1])
            extra[..., 2] = np.where(soft, 0.0, local[..., 2])
            local = np.concatenate([local, extra], axis=-2)
    return np.einsum("...ij,...gj->...gi", G, local)
