"""Figures (a leaf module: matplotlib is imported inside the functions).

Drawings follow the paper's figures: a small V at each contact showing the direction
in which the finger pushes (figure 1), friction cones as wedges (figure 3), and an
escape motion as an arrow or a curved arrow about its centre of rotation.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .contacts import Contact
from .grasp import Grasp


def _pyplot() -> Any:
    import matplotlib

    if matplotlib.get_backend().lower() not in {"agg", "pdf", "svg", "ps", "cairo"}:
        try:
            matplotlib.use("Agg")
        except Exception:  # pragma: no cover - backend already fixed by the user
            pass
    import matplotlib.pyplot as plt

    return plt


def draw_contact(ax: Any, contact: Contact, size: float = 0.15, color: str = "C3") -> None:
    """Draw the generating forces of a contact as small arrows ending on their points."""
    for p, f in zip(contact.points, contact.forces, strict=True):
        tail = p - f * size
        ax.annotate("", xy=p, xytext=tail,
                    arrowprops={"arrowstyle": "->", "color": color, "lw": 1.2})
    ax.plot(contact.points[:, 0], contact.points[:, 1], "o", ms=3, color=color)


def draw_grasp(ax: Any, grasp: Grasp, outline: Any = None, title: str | None = None,
               size: float = 0.15) -> None:
    """Draw a grasp: optional outline, each contact's forces, and the verdict."""
    if outline is not None:
        pts = np.asarray(outline, dtype=float)
        ring = np.concatenate([pts, pts[:1]])
        ax.fill(ring[:, 0], ring[:, 1], color="0.9", zorder=0)
        ax.plot(ring[:, 0], ring[:, 1], color="0.3", lw=1)
    for c in grasp.contacts:
        draw_contact(ax, c, size=size)
    report = grasp.explain()
    if report.escape_twist is not None:
        om, vx, vy = report.escape_twist
        center = grasp.points.mean(axis=0)
        if abs(om) < 1e-12:
            v = np.array([vx, vy]) / np.hypot(vx, vy) * size * 2
            ax.annotate("", xy=center + v, xytext=center,
                        arrowprops={"arrowstyle": "-|>", "color": "C0", "lw": 2})
        else:
            c = np.array([-vy / om, vx / om])
            ax.plot(*c, marker="x", color="C0", ms=8)
    ax.set_aspect("equal")
    ax.set_title(title or str(report).split(";")[0], fontsize=8)
    ax.tick_params(labelsize=6)


def save_figure(fig: Any, path: str) -> None:
    """Save a matplotlib figure atomically (format from the extension)."""
    from ._atomic import atomic_write

    atomic_write(path, lambda tmp: fig.savefig(tmp, dpi=120, bbox_inches="tight"))
