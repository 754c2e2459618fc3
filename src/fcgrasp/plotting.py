"""Figures (a leaf module: matplotlib is imported inside the functions).

Drawings follow the paper's figures: a small V at each contact showing the direction
in which the finger pushes (figure 1), friction cones as wedges (figure 3), and an
escape motion as an arrow or a curved arrow about its centre of rotation.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .core._geom import signed_area
from .core.contacts import Contact
from .core.grasp import Grasp
from .core.tolerances import ROUND_TOL


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
        if abs(om) < ROUND_TOL:
            v = np.array([vx, vy]) / np.hypot(vx, vy) * size * 2
            ax.annotate("", xy=center + v, xytext=center,
                        arrowprops={"arrowstyle": "-|>", "color": "C0", "lw": 2})
        else:
            pivot = np.array([-vy / om, vx / om])
            ax.plot(*pivot, marker="x", color="C0", ms=8)
    ax.set_aspect("equal")
    ax.set_title(title or str(report).split(";")[0], fontsize=8)
    ax.tick_params(labelsize=6)


def save_figure(fig: Any, path: str, outputs: Any = None) -> None:
    """Save a matplotlib figure atomically (format from the extension), or stage it in
    ``outputs`` (an output set written all or none)."""
    from .io.outputs import OutputSet

    def write(tmp: str) -> None:
        fig.savefig(tmp, dpi=120, bbox_inches="tight")

    if outputs is not None:
        outputs.add(path, write)
        return
    with OutputSet() as out:
        out.add(path, write)


# ----------------------------------------------------------------------------- plans

_FINGER_COLORS = ["#d62728", "#1f77b4", "#2ca02c", "#9467bd"]


#: At most this many edge numbers are drawn on a part; labels closer than
#: ``LABEL_SPACING`` of the part's size to one already drawn are left out.
MAX_LABELS = 40
LABEL_SPACING = 0.06


def edge_labels(polygon: Any, keep: Any = ()) -> list[int]:
    """The edges whose numbers stay legible: the edges in ``keep`` (those a plan uses),
    then the longest others, skipping any whose label would crowd one already placed."""
    mid = (polygon.starts + polygon.ends) / 2
    chosen: list[int] = []
    keep = [int(e) for e in keep if 0 <= int(e) < polygon.n_edges]
    order = keep + [int(i) for i in np.argsort(-polygon.lengths, kind="stable")
                    if int(i) not in keep and polygon.usable[i]]
    gap = LABEL_SPACING * polygon.size
    for i in order:
        if len(chosen) >= MAX_LABELS and i not in keep:
            break
        if i in keep or all(np.hypot(*(mid[i] - mid[j])) >= gap for j in chosen):
            chosen.append(i)
    return sorted(set(chosen))


def draw_part(ax: Any, polygon: Any, numbers: bool = True, keep: Any = (),
              units: str = "") -> None:
    """The part, holes cut out, with the numbers of its edges (input numbering) where they
    stay legible (:func:`edge_labels`; the edges in ``keep`` always), axes in ``units``."""
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path as MplPath

    def oriented(r: Any, ccw: bool) -> Any:
        return r if (signed_area(r) > 0) == ccw else r[::-1]

    # outer ring counter-clockwise, holes clockwise: the non-zero fill rule cuts them out
    rings = [oriented(polygon.vertices, True), *(oriented(h, False) for h in polygon.holes)]
    verts, codes = [], []
    for r in rings:
        verts += list(r) + [r[0]]
        codes += [MplPath.MOVETO] + [MplPath.LINETO] * (len(r) - 1) + [MplPath.CLOSEPOLY]
    ax.add_patch(PathPatch(MplPath(verts, codes), facecolor="0.88", edgecolor="0.25",
                           lw=1.0 if polygon.n_edges < 400 else 0.6, zorder=0))
    if numbers:
        mid = (polygon.starts + polygon.ends) / 2
        off = 0.025 * polygon.size
        for i in edge_labels(polygon, keep):
            p = mid[i] + off * polygon.normals[i]
            ax.text(p[0], p[1], str(i), fontsize=6, color="0.35", ha="center", va="center")
    lo = np.min(polygon.vertices, axis=0)
    hi = np.max(polygon.vertices, axis=0)
    pad = 0.12 * polygon.size
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    if units:
        ax.set_xlabel(f"x ({units})", fontsize=7)
        ax.set_ylabel(f"y ({units})", fontsize=7)


def draw_plan(ax: Any, polygon: Any, plan: Any, title: str | None = None,
              units: str = "", numbers: bool = True) -> None:
    """Figure 1 style: regions drawn bold, a small V at each finger showing its push; the
    legend sits inside the axes, where it cannot run into a neighbour's title."""
    keep = sorted({e for r in plan.region_edges for e in (r[0], r[-1]) if e >= 0})
    draw_part(ax, polygon, numbers, keep=keep, units=units)
    v = 0.05 * polygon.size
    for i, (reg, c, n) in enumerate(zip(plan.regions, plan.contacts, plan.normals,
                                        strict=True)):
        col = _FINGER_COLORS[i % len(_FINGER_COLORS)]
        covered = plan.region_edges[i]
        where = f"edge {covered[0]}" if len(covered) == 1 else \
            f"edges {covered[0]}-{covered[-1]}"
        # the region bold along the boundary, through the vertices it covers
        ax.plot(reg[:, 0], reg[:, 1], color=col, lw=4.5, solid_capstyle="butt",
                solid_joinstyle="round", zorder=3,
                label=f"finger {i + 1}: {where}, {plan.lengths[i]:.3g} {units}".rstrip())
        for sgn in (1.0, -1.0):
            ang = sgn * np.radians(28)
            d = np.array([n[0] * np.cos(ang) - n[1] * np.sin(ang),
                          n[0] * np.sin(ang) + n[1] * np.cos(ang)])
            ax.plot([c[0], c[0] + v * d[0]], [c[1], c[1] + v * d[1]], color="k", lw=1.2,
                    zorder=4)
    if plan.gravity is not None:
        g = np.asarray(plan.gravity["center"])
        d = np.asarray(plan.gravity["direction"]) * 1.5 * v
        ax.annotate("", xy=g + d, xytext=g, arrowprops={"arrowstyle": "-|>", "color": "0.2"})
    mu_txt = f"mu = {plan.mu:g}" if plan.contact_type == "friction" else "frictionless"
    ax.set_title(title or f"min region {plan.min_length:.3g} {units}, {mu_txt}", fontsize=8)
    ax.legend(fontsize=6, loc="best", framealpha=0.85, handlelength=1.2)
    ax.tick_params(labelsize=6)


def draw_jaw_plan(ax: Any, polygon: Any, plan: Any, title: str | None = None,
                  units: str = "") -> None:
    """A parallel-jaw box (:class:`~fcgrasp.JawPlan`): the part, the two pads at the box's
    centre pose, the strip the pads sweep over the offset range (shaded) and the fan of
    the angle range (the closing directions at its ends, through the centre)."""
    from matplotlib.patches import Polygon as MplPolygon

    draw_part(ax, polygon, numbers=False, units=units)
    theta, c = plan.centre
    u = np.array([np.cos(theta), np.sin(theta)])
    n = np.array([-u[1], u[0]])
    cen = np.asarray(plan.centroid, float)
    half = plan.jaw.pad_width / 2
    rel = polygon.vertices - cen
    reach = float(np.max(np.abs(rel @ u))) + 0.1 * polygon.size
    lo, hi = plan.offset[0] - half, plan.offset[1] + half
    band = [cen + lo * n - reach * u, cen + hi * n - reach * u, cen + hi * n + reach * u,
            cen + lo * n + reach * u]
    ax.add_patch(MplPolygon(band, closed=True, facecolor="#1f77b4", alpha=0.12, lw=0,
                            zorder=1, label=f"offsets {plan.offset[0]:.3g} to "
                                            f"{plan.offset[1]:.3g} {units}".rstrip()))
    thick = 0.03 * polygon.size
    for k, stop in enumerate(plan.stops):
        # a pad's body lies behind its face: outside the part's material
        sgn = (1.0 if k == 0 else -1.0) * (-1.0 if plan.mode == "internal" else 1.0)
        base = cen + c * n + stop * u
        pad = [base - half * n, base + half * n, base + half * n + sgn * thick * u,
               base - half * n + sgn * thick * u]
        ax.add_patch(MplPolygon(pad, closed=True, facecolor="0.3", edgecolor="k", zorder=4,
                                label="pads at the centre pose" if k == 0 else None))
    for pts in plan.contacts:
        ax.plot(*np.asarray(pts).T, "o", color="#d62728", ms=4, zorder=5)
    if plan.insert is not None:
        # inside a hole: where the closed jaws go in (fcgrasp.grippers.jaw.insertion_point)
        ax.plot(*np.asarray(plan.insert), "+", color="k", ms=7, zorder=5,
                label="jaws put in here")
    mid = cen + c * n
    for t in plan.theta:
        d = np.array([np.cos(t), np.sin(t)]) * reach
        ax.plot(*np.c_[mid - d, mid + d], color="#2ca02c", lw=1.0, ls="--", zorder=3)
    ax.plot([], [], color="#2ca02c", ls="--",
            label=f"closing {np.degrees(plan.theta[0]):.1f} to "
                  f"{np.degrees(plan.theta[1]):.1f} deg")
    ax.set_title(title or f"box measure {plan.measure:.3g} {units}", fontsize=8)
    ax.legend(fontsize=6, loc="best", framealpha=0.85, handlelength=1.2)
    ax.tick_params(labelsize=6)


def plan_figure(polygon: Any, plans: list[Any], path: str, units: str = "",
                title: str | None = None, panel: int = 3, outputs: Any = None) -> None:
    """Write a figure of the best plan (figure 1), or with several plans a panel of the best
    and worst ranked ones (figure 15), atomically; format from the extension."""
    from .grippers.jaw import JawPlan

    plt = _pyplot()
    if not plans:
        fig, ax = plt.subplots(figsize=(4, 4))
        draw_part(ax, polygon, units=units)
        ax.set_title(title or "no force-closure grasp", fontsize=9)
    else:
        idx = list(range(len(plans)))
        shown = idx if len(idx) <= 2 * panel else idx[:panel] + idx[-panel:]
        cols = min(len(shown), panel)
        nrows = (len(shown) + cols - 1) // cols
        fig, axes = plt.subplots(nrows, cols, figsize=(3.4 * cols, 3.9 * nrows), squeeze=False)
        for ax in axes.ravel()[len(shown):]:
            ax.axis("off")
        for ax, k in zip(axes.ravel(), shown, strict=False):
            p = plans[k]
            if isinstance(p, JawPlan):
                draw_jaw_plan(ax, polygon, p, units=units,
                              title=f"rank {k + 1}: box {p.measure:.3g} {units}, "
                                    f"mu={p.jaw.mu:g}")
                continue
            mu_txt = f"mu={p.mu:g}" if p.contact_type == "friction" else "frictionless"
            draw_plan(ax, polygon, p, units=units,
                      title=f"rank {k + 1}: edges {list(p.edges)}\nmin region "
                            f"{p.min_length:.3g} {units}, {mu_txt}")
        if title:
            fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    save_figure(fig, path, outputs)
    plt.close(fig)


def grasp_figure(polygon: Any, grasp: Grasp, path: str, units: str = "",
                 outputs: Any = None) -> None:
    """The part with a checked grasp: contact forces, verdict, escape motion (atomically)."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(4.5, 4.5))
    draw_part(ax, polygon, units=units)
    draw_grasp(ax, grasp, size=0.08 * polygon.size)
    draw_part(ax, polygon, numbers=False, units=units)      # restore the limits of the part
    fig.tight_layout()
    save_figure(fig, path, outputs)
    plt.close(fig)


def document_figure(doc: Any, path: str, title: str | None = None,
                    outputs: Any = None) -> None:
    """The figure of a plan document (:func:`fcgrasp.planning.plan_document`): a solid's
    3-D panels (:func:`solid_plan_figure`), else a polygon's (:func:`plan_figure`);
    ``title`` defaults to the document's."""
    from .spatial.solid import Solid

    title = doc.title if title is None else title
    if isinstance(doc.polygon, Solid):
        solid_plan_figure(doc.polygon, doc.plans, path, title=title, outputs=outputs)
    else:
        plan_figure(doc.polygon, doc.plans, path, units=doc.units, title=title,
                    outputs=outputs)


def solid_plan_figure(solid: Any, plans: list[Any], path: str, title: str | None = None,
                      panel: int = 3, outputs: Any = None) -> None:
    """Regions of two soft fingers (:func:`fcgrasp.spatial.soft_pair_plans`) or three
    fingers with friction (:func:`fcgrasp.spatial.point_triple_plans`) on a solid: one
    3-D panel per plan (at most ``panel``): the mesh, the octagon regions, the fingers'
    approach (the inward normals at the centres) and the lines between the centres."""
    plt = _pyplot()
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    shown = plans[:panel] or [None]
    fig = plt.figure(figsize=(4.2 * len(shown), 4.4))
    tris = solid.mesh.vertices[solid.mesh.faces]
    lo, hi = solid.mesh.bounds
    span = float(np.max(hi - lo))
    for k, plan in enumerate(shown):
        ax = fig.add_subplot(1, len(shown), k + 1, projection="3d")
        ax.add_collection3d(Poly3DCollection(tris, facecolor="0.85", edgecolor="0.6",
                                             linewidth=0.2, alpha=0.25))
        if plan is not None:
            for reg, c, n, color in zip(plan.regions, plan.centers, plan.normals,
                                        _FINGER_COLORS, strict=False):
                ax.add_collection3d(Poly3DCollection([reg], facecolor=color, alpha=0.8,
                                                     edgecolor=color))
                tail = c - 0.35 * span * n
                ax.quiver(*tail, *(0.3 * span * n), color=color, linewidth=1.5)
            ring = np.vstack([plan.centers, plan.centers[:1]]) if len(plan.centers) > 2 \
                else plan.centers
            ax.plot(*ring.T, color="0.2", linestyle=":", linewidth=1)
            facets = ", ".join(str(f) for f in plan.facets)
            ax.set_title(f"{k + 1}: facets {facets}  r {plan.radius:.3g}", fontsize=9)
        mid = 0.5 * (lo + hi)
        for setter, m in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), mid, strict=True):
            setter(m - 0.6 * span, m + 0.6 * span)
        ax.set_box_aspect((1, 1, 1))
        ax.tick_params(labelsize=7)
    if title:
        fig.suptitle(title, fontsize=10)
    save_figure(fig, path, outputs)
