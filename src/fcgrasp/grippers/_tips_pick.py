r"""Point fingers picking a planar part from above: the part a plate on a table (or held
alone), each finger a vertical cylinder whose side touches the plate's side
(:class:`~fcgrasp.model.hands.FingerTips`, the chopsticks of section 8.2), and why every
placement of a plan's regions is collision free.

**The scene** is the jaw's (:class:`~fcgrasp.grippers.jaw._pick.Scene`): the plate fills
``0 <= z <= thickness`` over the part's outline, the table is the plane ``z = 0``.  Each
finger comes down along ``-z`` over its contact and stops with its end ``clearance``
above the table (at the plate's bottom without one); its side then touches the plate's
side from there to the top (``contact_height``), its axis at ``p + radius n`` for a
contact ``p`` of outward normal ``n``.

**Why every placement is collision free (exactly, not sampled).**  The regions are those
of section 8.2's hand with the tip's radius (:class:`fcgrasp.Hand`, ``finger_radius``):
the disc of that radius touching the outline at ``p`` meets the part nowhere else
(:meth:`fcgrasp.Hand.feasible_intervals`, exact: a line against capsules).  The plate is
a prism, so the cylinder over that disc meets it only along its contact line at every
height, on the way down as at the contact; its end stays ``clearance`` above the table;
whatever holds the finger is above the plate's top by ``clearance`` when the finger is
long enough (``length >= thickness - end + clearance``), and there is no pick otherwise.

**Held in its plane** (``in_plane``): each finger lies in the plate's plane at its
mid-height along its contact's outward normal, a round tip of the radius and a body
``length`` long behind it, and comes in along the inward normal from ``approach`` away.
The regions are those of section 8.2's hand with a body (:class:`fcgrasp.Hand`,
``finger_length`` = the length and the approach): every centre of the segment from the
tip's centre back to where the finger starts its approach is at least the radius from
every other edge (exact, as the tip's disc is), so the finger's whole sweep in the plane
meets the part only at its contact.  With a table the fingers' lowest points must clear
it by ``clearance``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..model.hands import FingerTips

__all__ = ["tips_reach", "tips_pick"]


def tips_reach(tips: FingerTips, scene: Any) -> tuple[float, float] | str:
    """The height of the fingers' ends and the band of the plate's side they touch
    (``contact_height``), or why they cannot pick the plate (the module's docstring);
    held in the plane, the height of the fingers' axes (the plate's mid-height) and the
    band their round tips touch (the plate's side, at most the tip's diameter)."""
    T, c = scene.thickness, scene.clearance
    if tips.in_plane:
        if scene.table and T / 2 - tips.radius < c:
            return (f"fingers of radius {tips.radius:g} in the plane of a {T:g} thick plate "
                    f"on a table would come within {c:g} of it: hold it off the table "
                    f"(no --table) or pick it from above")
        return T / 2, min(T, 2 * tips.radius)
    end = c if scene.table else 0.0
    if end >= T:
        return (f"the fingers' ends stay {c:g} above the table, over the {T:g} thick "
                f"plate's top: they cannot touch its side")
    if end + tips.length < T + c:
        return (f"the fingers are {tips.length:g} long: what holds them would meet the "
                f"plate, whose top is {T - end:g} above their ends (they need "
                f"{T - end + c:g} with the clearance)")
    return end, T - end


def tips_pick(plan: Any, tips: FingerTips, scene: Any, end: float, band: float
              ) -> dict[str, Any]:
    """The pick of a plan's representative grasp: each finger's end (the centre of its
    flat end, part frame), where it comes down from, the approach and the retreat; held
    in the plane, each finger's tip centre, where it comes in from and its own approach
    and retreat; every placement of the regions is collision free (the module's
    docstring)."""
    pts, nrm = np.asarray(plan.contacts, float), np.asarray(plan.normals, float)
    nrm = nrm / np.linalg.norm(nrm, axis=1)[:, None]
    axis = pts + tips.radius * nrm
    if tips.in_plane:
        # each finger comes in along its inward normal, in the plane, from `approach`
        # away, and leaves the way it came (over the retreat distance)
        fingers = []
        for (x, y), (nx, ny) in zip(axis, nrm, strict=True):
            fingers.append({
                "position": [float(x), float(y), float(end)],
                "pre_grasp": [float(x + scene.approach * nx), float(y + scene.approach * ny),
                              float(end)],
                **scene.motions((-nx, -ny, 0.0), (nx, ny, 0.0))})
        return {"fingertips": fingers, "collision_free": True, "contact_height": band}
    fingertips = [{"position": [float(x), float(y), float(end)],
                   "pre_grasp": [float(x), float(y), float(end + scene.approach)]}
                  for x, y in axis]
    return {"fingertips": fingertips, **scene.motions((0.0, 0.0, -1.0), (0.0, 0.0, 1.0)),
            "collision_free": True, "contact_height": band}
