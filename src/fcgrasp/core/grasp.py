"""Grasps: a set of contacts, its wrench convexe and its total freedom (paper section 3.2).

:class:`Grasp` is a thin object over the array functions of :mod:`fcgrasp.core.closure`
and :mod:`fcgrasp.core.convexes`.  Besides the verdict it says *why* a grasp is not force
closure (theorem 6.1: force closure is force-direction closure, theorem 4.1, and
torque closure, theorem 5.1) and gives an escape twist: a motion of the object that
is reciprocal or repelling to every contact wrench.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from ._checks import FloatArray, check_tol
from .closure import ONE_GRASP_WRENCHES, closure_escape, closure_one, normalize_wrenches
from .contacts import Contact
from .convexes import Cone
from .screws import rotation_center
from .tolerances import TOL

__all__ = ["Grasp", "ClosureReport", "FORCE_DIRECTION", "TORQUE"]

FORCE_DIRECTION = "force-direction"
TORQUE = "torque"


@dataclass(frozen=True)
class ClosureReport:
    """Verdict on a grasp.

    Attributes
    ----------
    force_closure : bool
    failed : str or None
        ``"force-direction"`` when some translation is free or breaks contact
        (theorem 4.1), else ``"torque"`` when some rotation does (theorem 5.1), ``None``
        for a force-closure grasp.
    escape_twist : ndarray, shape (3,) or None
        A non-zero twist ``(omega, vx, vy)`` reciprocal or repelling to every wrench.
    """

    force_closure: bool
    failed: str | None
    escape_twist: FloatArray | None

    @property
    def escape_description(self) -> str:
        """The escape motion in words."""
        if self.escape_twist is None:
            return "none: every motion is resisted by a contact force"
        om, vx, vy = (float(x) for x in np.round(self.escape_twist, 12) + 0.0)
        if om == 0.0:
            n = float(np.hypot(vx, vy))
            return f"translation along ({vx / n + 0.0:.4g}, {vy / n + 0.0:.4g})"
        cx, cy = (float(x) for x in rotation_center(self.escape_twist))
        sense = "counter-clockwise" if om > 0 else "clockwise"
        return f"{sense} rotation about ({cx:.6g}, {cy:.6g})"

    def __str__(self) -> str:
        if self.force_closure:
            return "force closure"
        return (f"not force closure: {self.failed} closure fails; "
                f"escape: {self.escape_description}")


class Grasp:
    """A grasp: contacts on one object (section 3.2).

    Parameters
    ----------
    contacts : iterable of Contact
        Contacts from :mod:`fcgrasp.core.contacts`.

    Examples
    --------
    >>> from fcgrasp import FrictionlessPoint
    >>> g = Grasp([FrictionlessPoint([0, .5], [-1, 0]), FrictionlessPoint([1, .5], [1, 0])])
    >>> g.is_force_closure()
    False
    >>> print(g.explain())
    not force closure: force-direction closure fails; escape: translation along (0, 1)
    """

    def __init__(self, contacts: Iterable[Contact]) -> None:
        if isinstance(contacts, Contact):
            contacts = [contacts]
        try:
            items = list(contacts)
        except TypeError as exc:
            raise TypeError(f"contacts must be an iterable of Contact, got {contacts!r}") from exc
        if not items:
            raise ValueError("contacts must hold at least one contact, got []")
        for i, c in enumerate(items):
            if not isinstance(c, Contact):
                raise TypeError(f"contacts[{i}] must be a Contact, got {c!r}")
        self.contacts = items

    @property
    def points(self) -> FloatArray:
        """Points on the lines of action of all generating forces, shape (k, 2)."""
        return np.concatenate([c.points for c in self.contacts])

    @property
    def forces(self) -> FloatArray:
        """Directions of all generating forces, shape (k, 2)."""
        return np.concatenate([c.forces for c in self.contacts])

    @property
    def wrenches(self) -> FloatArray:
        """All generating wrenches (the convex addition of the contacts), shape (k, 3)."""
        return np.concatenate([c.wrenches for c in self.contacts])

    def wrench_cone(self) -> Cone:
        """The wrench convexe of the grasp: the convex addition of the contacts' convexes."""
        return Cone(self.wrenches, space="wrench")

    def total_freedom(self) -> Cone:
        """The twist convexe of the grasp: motions reciprocal or repelling to all wrenches.

        Null exactly when the grasp is force closure (theorem 6.1, clause 3).
        """
        return self.wrench_cone().dual().minimal()

    def is_force_closure(self, tol: float = TOL) -> bool:
        """General test (theorem 6.1): the wrench convexe is total.

        A grasp of a few contacts is decided in plain float arithmetic
        (:func:`~fcgrasp.core.closure.closure_one`), with no numpy call per wrench."""
        tol = check_tol(tol)
        w = []
        for c in self.contacts:
            for (px, py), (fx, fy) in zip(c.points.tolist(), c.forces.tolist(), strict=True):
                w.append((fx, fy, px * fy - py * fx))
        if len(w) <= ONE_GRASP_WRENCHES:
            return closure_one(w, tol)
        return bool(closure_escape(np.array(w), tol)[0])

    def force_direction_closure(self, tol: float = TOL) -> bool:
        """Theorem 4.1: the forces can be combined into any direction (general test).

        True iff the largest angular gap between consecutive force directions is less
        than pi (by more than ``tol``).
        """
        return self._translation_escape(check_tol(tol)) is None

    def torque_closure(self, tol: float = TOL) -> bool:
        """Theorem 5.1: no rotation (about any point) is free or breaks contact.

        Computed on the total freedom: every twist of the dual convexe must have zero
        angular velocity (relative to ``tol`` in the normalised frame).
        """
        return self._rotation_escape(check_tol(tol)) is None

    def _translation_escape(self, tol: float) -> FloatArray | None:
        f = self.forces
        f = f[np.hypot(f[:, 0], f[:, 1]) > 0]
        if f.shape[0] == 0:
            return np.array([0.0, 1.0, 0.0])
        ang = np.sort(np.arctan2(f[:, 1], f[:, 0]))
        gaps = np.diff(np.concatenate([ang, ang[:1] + 2 * np.pi]))
        i = int(np.argmax(gaps))
        if gaps[i] < np.pi - tol:
            return None
        beta = ang[i] + gaps[i] / 2.0 + np.pi
        return np.array([0.0, np.cos(beta), np.sin(beta)])

    def _rotation_escape(self, tol: float) -> FloatArray | None:
        unit, center, length = normalize_wrenches(self.wrenches)
        free = Cone(unit, space="wrench").dual()
        gens = np.concatenate([free.rays, free.lines])
        if gens.shape[0] == 0:
            return None
        i = int(np.argmax(np.abs(gens[:, 0])))
        y = gens[i]
        if abs(y[0]) <= tol:
            return None
        # twist in the normalised frame -> twist about the true origin
        om = y[0] / float(length)
        return np.array([om, y[1] + om * center[1], y[2] - om * center[0]])

    def explain(self, tol: float = TOL) -> ClosureReport:
        """Verdict with the reason and an escape twist when not force closure."""
        tol = check_tol(tol)
        closure, escape = closure_escape(self.wrenches, tol)
        if bool(closure):
            return ClosureReport(True, None, None)
        trans = self._translation_escape(tol)
        if trans is not None:
            return ClosureReport(False, FORCE_DIRECTION, trans)
        rot = self._rotation_escape(tol)
        return ClosureReport(False, TORQUE, rot if rot is not None else np.asarray(escape))

    def __repr__(self) -> str:
        return f"Grasp({self.contacts!r})"
