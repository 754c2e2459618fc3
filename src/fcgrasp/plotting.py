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
        # the tight box measured here (savefig's "tight" first draws the whole figure
        # without output to measure it): the same box, one draw less
        import matplotlib

        fig.set_dpi(120)
        box = fig.get_tightbbox(fig.canvas.get_renderer()).padded(
            matplotlib.rcParams["savefig.pad_inches"])
        fig.savefig(tmp, dpi=120, bbox_inches=box)

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
    stay legible (:func:`edge_labels`; the edges in ``keep`` first), each placed by
    :func:`place_edge_labels` off the outline and clear of every other label; axes in
    ``units``.  A figure laid out again (or given more drawing on top) calls
    :func:`place_edge_labels` once more to place them for the final geometry."""
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
    lo = np.min(polygon.vertices, axis=0)
    hi = np.max(polygon.vertices, axis=0)
    pad = 0.12 * polygon.size
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    if units:
        ax.set_xlabel(f"x ({units})", fontsize=7)
        ax.set_ylabel(f"y ({units})", fontsize=7)
    if numbers:
        idx = edge_labels(polygon, keep)
        mid = (polygon.starts + polygon.ends) / 2
        segs = [np.vstack([r, r[:1]]) for r in (polygon.vertices, *polygon.holes)]
        ax._fcgrasp_labels = {"edges": idx, "mid": mid[idx], "normal": polygon.normals[idx],
                              "outline": segs}
        place_edge_labels(ax)


#: Edge numbers: font size (points), and the gaps tried between a number's box and its
#: edge, in multiples of the box's height.
LABEL_FONT = 6.0
LABEL_GAPS = (0.35, 1.1, 2.0, 3.2)


def _label_size(text: str, dpi: float) -> tuple[float, float]:
    """Width and height in pixels of a number in :data:`LABEL_FONT` (DejaVu Sans digits
    are 0.64 em wide), with a small margin."""
    em = LABEL_FONT * dpi / 72.0
    return 0.64 * em * len(text) + 0.5 * em, 1.25 * em


def place_edge_labels(ax: Any) -> int:
    """Place (again) the edge numbers :func:`draw_part` left on ``ax``: each number tries
    spots off its edge on the outward side (growing gaps, then slid along the edge) and
    takes the first whose box is inside the axes and clear of the outline, of every line
    drawn over the part (regions, the fingers' V's) and of every number placed before;
    a number with no such spot is left out.  Positions are computed in pixels for the
    axes' current size, so a figure calls this again after its layout.  Returns how
    many numbers were drawn."""
    import shapely

    info = getattr(ax, "_fcgrasp_labels", None)
    if info is None:
        return 0
    for t in info.get("texts", []):
        t.remove()
    info["texts"] = []
    fig = ax.figure
    ax.apply_aspect()
    frame = ax.get_window_extent()
    to_px = ax.transData.transform
    lines = [to_px(seg) for seg in info["outline"]]
    lines += [to_px(np.asarray(line.get_xydata(), float)) for line in ax.get_lines()
              if line.get_zorder() >= 3 and len(line.get_xydata()) >= 2]
    obstacles = [shapely.LineString(p) for p in lines if np.all(np.isfinite(p))]
    tree = shapely.STRtree(obstacles)
    placed: list[Any] = []
    dpi = float(fig.dpi)
    for e, m, n in zip(info["edges"], info["mid"], info["normal"], strict=True):
        text = str(int(e))
        w, h = _label_size(text, dpi)
        a = to_px(m)
        d = to_px(m + n) - a
        d = d / (float(np.hypot(*d)) or 1.0)
        t = np.array([-d[1], d[0]])
        # the box's reach along the normal: its half-extent in that direction
        reach = 0.5 * (abs(d[0]) * w + abs(d[1]) * h)
        spot = None
        for gap in LABEL_GAPS:
            for slide in (0.0, 0.6, -0.6, 1.2, -1.2):
                c = a + d * (reach + gap * h) + t * slide * w
                box = shapely.box(c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2)
                inside = frame.x0 <= c[0] - w / 2 and c[0] + w / 2 <= frame.x1 and \
                    frame.y0 <= c[1] - h / 2 and c[1] + h / 2 <= frame.y1
                if inside and not len(tree.query(box, predicate="intersects")) and \
                        not any(box.intersects(b) for b in placed):
                    spot = c, box
                    break
            if spot is not None:
                break
        if spot is None:
            continue
        c, box = spot
        placed.append(box)
        x, y = ax.transData.inverted().transform(c)
        info["texts"].append(ax.text(x, y, text, fontsize=LABEL_FONT, color="0.35",
                                     ha="center", va="center", zorder=2,
                                     gid="edge-label"))
    return len(info["texts"])


def _panel_size(polygon: Any, legend_rows: int) -> tuple[float, float, bool]:
    """Width and height (inches) of one plan panel from the part's aspect ratio, and
    whether its legend goes below the drawing (a wide part) or to its right."""
    lo = np.min(polygon.vertices, axis=0)
    hi = np.max(polygon.vertices, axis=0)
    w, h = hi - lo + 0.24 * polygon.size
    aspect = float(np.clip(h / w, 0.25, 2.5))          # w > 0: it holds the padding
    below = aspect <= 1.0
    draw_w = 3.0 if below else 3.0 / max(aspect, 1.0) ** 0.5
    draw_h = draw_w * aspect
    if below:
        return draw_w + 0.6, draw_h + 1.0 + 0.14 * legend_rows, True
    return draw_w + 2.2, max(draw_h, 0.16 * legend_rows) + 1.0, False


def _legend(ax: Any, polygon: Any) -> None:
    """A panel's legend outside its drawing: below a wide part (under the x axis's
    numbers and label), right of a tall one."""
    if _panel_size(polygon, 0)[2]:
        ax.legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, 0.0),
                  borderaxespad=4.6, framealpha=0.85, handlelength=1.2)
    else:
        ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.0, 1.0),
                  borderaxespad=1.0, framealpha=0.85, handlelength=1.2)


def draw_plan(ax: Any, polygon: Any, plan: Any, title: str | None = None,
              units: str = "", numbers: bool = True) -> None:
    """Figure 1 style: regions drawn bold, a small V at each finger showing its push
    (above the edge numbers, which are placed clear of both); the legend outside the
    drawing (below a wide part, right of a tall one)."""
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
    _legend(ax, polygon)
    ax.tick_params(labelsize=6)
    place_edge_labels(ax)                       # clear of the regions and the V's now


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
    if getattr(plan.jaw, "hand", None) is not None:
        _draw_hand(ax, plan)
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
    _legend(ax, polygon)
    ax.tick_params(labelsize=6)


def _draw_hand(ax: Any, plan: Any) -> None:
    """The hand (:mod:`fcgrasp.model.hands`) seen from above at the box's centre pose
    (its tool frame, :func:`fcgrasp.io.moveit.jaw_tool_pose`: picked from above, or held
    in the plane on ``plan.side`` of the strip): each finger box's footprint at the
    grasp's opening, the palm's dashed."""
    from matplotlib.patches import Polygon as MplPolygon
    from scipy.spatial import ConvexHull

    from .io.moveit import jaw_tool_pose

    hand = plan.jaw.hand
    opening = plan.stops[0] - plan.stops[1]
    n_palm = len(hand.palm)
    side = getattr(plan, "side", 0)
    where, axes = jaw_tool_pose(plan.centroid, plan.centre[0], plan.centre[1], plan.stops,
                                0.0, side, sum(hand.pad_span) / 2)
    origin, R = where[:2], axes[:2]
    seen = []
    for k, box in enumerate(hand.boxes(opening)):
        pts = origin + box.corners() @ R.T
        if k >= n_palm:
            seen.append(pts)
        ring = pts[ConvexHull(pts).vertices]
        palm = k < n_palm
        ax.add_patch(MplPolygon(ring, closed=True, fill=False, lw=0.6, zorder=4,
                                edgecolor="0.45" if palm else "0.2",
                                ls="--" if palm else "-",
                                label=(f"{hand.name}: palm" if k == 0 else
                                       f"{hand.name}: fingers" if k == n_palm else None)))
    if side:
        # held in the plane the fingers reach past the part: the view takes them in
        pts = np.vstack(seen)
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        ax.set_xlim(min(x0, pts[:, 0].min()), max(x1, pts[:, 0].max()))
        ax.set_ylim(min(y0, pts[:, 1].min()), max(y1, pts[:, 1].max()))


def plan_figure(polygon: Any, plans: list[Any], path: str, units: str = "",
                title: str | None = None, panel: int = 3, outputs: Any = None) -> None:
    """Write a figure of the best plan (figure 1), or with several plans a panel of the best
    and worst ranked ones (figure 15), atomically; format from the extension."""
    from .grippers.jaw import JawPlan

    plt = _pyplot()
    if not plans:
        w, h, _ = _panel_size(polygon, 0)
        fig, ax = plt.subplots(figsize=(w, h))
        draw_part(ax, polygon, units=units)
        ax.set_title(title or "no force-closure grasp", fontsize=9)
    else:
        idx = list(range(len(plans)))
        shown = idx if len(idx) <= 2 * panel else idx[:panel] + idx[-panel:]
        cols = min(len(shown), panel)
        nrows = (len(shown) + cols - 1) // cols
        # each panel sized from the part's aspect ratio, room for its legend outside
        rows = max(4 if isinstance(p, JawPlan) else len(p.regions) for p in plans)
        w, h, _ = _panel_size(polygon, rows)
        fig, axes = plt.subplots(nrows, cols, figsize=(w * cols, h * nrows + 0.3 * bool(title)),
                                 squeeze=False, layout="compressed")
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
    engine = fig.get_layout_engine()
    if engine is None:
        fig.tight_layout()
    else:
        engine.execute(fig)
    for ax in fig.axes:                     # the numbers placed for the final layout
        place_edge_labels(ax)
    if engine is not None:                  # that layout kept: saving does not redo it
        fig.set_layout_engine(None)
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
    place_edge_labels(ax)
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
    3-D panel per plan (at most ``panel``): the mesh, the octagon regions (a region
    across the facets of a curved surface by its outline on it), the fingers' approach
    (the inward normals at the centres) and the lines between the centres."""
    plt = _pyplot()
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    shown = plans[:panel] or [None]
    fig = plt.figure(figsize=(4.2 * len(shown), 4.4))
    tris = solid.mesh.vertices[solid.mesh.faces]
    lo, hi = solid.mesh.bounds
    span = float(np.max(hi - lo))
    for k, plan in enumerate(shown):
        ax = fig.add_subplot(1, len(shown), k + 1, projection="3d")
        ax.computed_zorder = False            # the regions over the mesh, seen through it
        ax.add_collection3d(Poly3DCollection(tris, facecolor="0.85", edgecolor="0.6",
                                             linewidth=0.2, alpha=0.25, zorder=1))
        if plan is not None:
            # a region across facets is drawn by its triangles on the curved surface
            drawn = getattr(plan, "surface_triangles", ()) or [[r] for r in plan.regions]
            for reg, c, n, color in zip(drawn, plan.centers, plan.normals,
                                        _FINGER_COLORS, strict=False):
                ax.add_collection3d(Poly3DCollection(list(reg), facecolor=color, alpha=0.8,
                                                     edgecolor=color, linewidth=0.3,
                                                     zorder=3))
                tail = c - 0.35 * span * n
                ax.quiver(*tail, *(0.3 * span * n), color=color, linewidth=1.5)
            ring = np.vstack([plan.centers, plan.centers[:1]]) if len(plan.centers) > 2 \
                else plan.centers
            ax.plot(*ring.T, color="0.2", linestyle=":", linewidth=1)
            facets = ", ".join(str(f) for f in plan.facets)
            where = "across facets from" if getattr(plan, "surface_triangles", ()) \
                else "facets"
            ax.set_title(f"{k + 1}: {where} {facets}  r {plan.radius:.3g}", fontsize=9)
        mid = 0.5 * (lo + hi)
        for setter, m in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), mid, strict=True):
            setter(m - 0.6 * span, m + 0.6 * span)
        ax.set_box_aspect((1, 1, 1))
        ax.tick_params(labelsize=7)
    if title:
        fig.suptitle(title, fontsize=10)
    save_figure(fig, path, outputs)
