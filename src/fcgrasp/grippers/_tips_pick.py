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
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..model.hands import FingerTips

__all__ = ["tips_reach", "tips_pick"]


def tips_reach(tips: FingerTips, scene: Any) -> tuple[float, float] | str:
    """The height of the fingers' ends and the band of the plate's side they touch
    (``contact_height``), or why they cannot pick the plate (the module's docstring)."""
    T, c = scene.thickness, scene.clearance
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
    flat end, part frame), where it comes down from, the approach and the retreat; every
    placement of the regions is collision free (the module's docstring)."""
    pts, nrm = np.asarray(plan.contacts, float), np.asarray(plan.normals, float)
    nrm = nrm / np.linalg.norm(nrm, axis=1)[:, None]
    axis = pts + tips.radius * nrm
    fingertips = [{"position": [float(x), float(y), float(end)],
                   "pre_grasp": [float(x), float(y), float(end + scene.approach)]}
                  for x, y in axis]
    return {"fingertips": fingertips,
            "approach": {"direction": [0.0, 0.0, -1.0], "distance": scene.approach,
                         "frame": "part"},
            "retreat": {"direction": [0.0, 0.0, 1.0], "distance": scene.retreat,
                        "frame": "part"},
            "collision_free": True, "contact_height": band}
