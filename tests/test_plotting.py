"""Figures (fcgrasp.plotting): written atomically in every format, regions drawn."""

from __future__ import annotations

import pytest

import fcgrasp as fc

pytest.importorskip("matplotlib")


@pytest.mark.parametrize("ext", [".png", ".svg", ".pdf"])
def test_plan_figure_formats(tmp_path, ext):
    from fcgrasp.plotting import plan_figure

    part = fc.read_part("demo:washer")
    out = tmp_path / f"fig{ext}"
    plan_figure(part, fc.plan(part, fingers=2, mu=0.2, top=2), str(out))
    assert out.stat().st_size > 1000
    assert sorted(p.name for p in tmp_path.iterdir()) == [out.name]


def test_svg_figure_draws_every_region(tmp_path):
    from fcgrasp.plotting import plan_figure

    part = fc.read_part("demo:quad")
    plans = fc.plan(part, fingers=4, top=1)
    out = tmp_path / "fig.svg"
    plan_figure(part, plans, str(out))
    text = out.read_text()
    assert text.count("<path") > 4 + 4          # the part, its edges, four regions


def test_grasp_figure(tmp_path):
    from fcgrasp.plotting import grasp_figure

    part = fc.read_part("demo:rectangle")
    g = fc.Grasp([fc.FrictionlessPoint([0, 15], [-1, 0]), fc.FrictionlessPoint([80, 15],
                                                                               [1, 0])])
    out = tmp_path / "g.png"
    grasp_figure(part, g, str(out))
    assert out.stat().st_size > 1000


def _disc(n, r=50.0):
    import numpy as np

    a = np.linspace(0, 2 * np.pi, n + 1)[:-1]
    return fc.Polygon(np.c_[r * np.cos(a), r * np.sin(a)])


def test_edge_labels_thinned_to_legible():
    import numpy as np

    from fcgrasp.plotting import LABEL_SPACING, MAX_LABELS, edge_labels

    part = _disc(600)
    labels = edge_labels(part, keep=[7, 300])
    assert 7 in labels and 300 in labels and len(labels) <= MAX_LABELS + 2
    mid = (part.starts + part.ends) / 2
    others = [i for i in labels if i not in (7, 300)]
    d = np.hypot(*(mid[others][:, None] - mid[others][None]).transpose(2, 0, 1))
    assert d[np.triu_indices(len(others), 1)].min() >= LABEL_SPACING * part.size * 0.999
    assert edge_labels(fc.read_part("demo:blob")) == list(range(6))    # small parts: all


def test_panel_legends_do_not_overlap_titles_and_axes_have_units(tmp_path):
    from fcgrasp.plotting import _pyplot, plan_figure

    plt = _pyplot()
    part = _disc(40)
    plans = fc.plan(part, fingers=2, mu=0.3, top=6)
    captured = {}
    orig = plt.close

    def keep(fig):
        captured["fig"] = fig

    plt.close = keep
    try:
        plan_figure(part, plans, str(tmp_path / "p.png"), units="in")
    finally:
        plt.close = orig
    fig = captured["fig"]
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    axes = [ax for ax in fig.axes if ax.get_legend() is not None]
    assert len(axes) == 6
    for ax in axes:
        assert ax.get_xlabel() == "x (in)" and ax.get_ylabel() == "y (in)"
        box = ax.get_legend().get_window_extent(r)
        for other in axes:
            title = other.title.get_window_extent(r)
            assert not box.overlaps(title)
    plt.close(fig)


# ------------------------------------------------------------- layout

def _drawn(monkeypatch, draw):
    """The figure a plotting function made, kept open and drawn."""
    from fcgrasp.plotting import _pyplot

    plt = _pyplot()
    kept = []
    monkeypatch.setattr(plt, "close", kept.append)
    draw()
    fig = kept[-1]
    fig.canvas.draw()
    return fig


def _dense(xy, step=0.5):
    """Points every ``step`` pixels along a polyline (display coordinates)."""
    import numpy as np

    out = [xy[:1]]
    for a, b in zip(xy[:-1], xy[1:], strict=True):
        k = max(int(np.hypot(*(b - a)) / step), 1)
        out.append(a + (b - a) * (np.arange(1, k + 1) / k)[:, None])
    return np.concatenate(out)


def _inside(box, pts, shrink=0.5):
    return (pts[:, 0] > box.x0 + shrink) & (pts[:, 0] < box.x1 - shrink) & \
        (pts[:, 1] > box.y0 + shrink) & (pts[:, 1] < box.y1 - shrink)


FIGURE_CASES = [("washer", dict(fingers=2, mu=0.2)), ("cam", dict(fingers=2, mu=0.3)),
                ("bracket", dict(fingers=3, mu=0.4)), ("quad", dict(fingers=4)),
                ("rectangle", dict(fingers=2, mu=0.3))]


@pytest.mark.parametrize("name, grip", [
    c if c[0] in ("washer", "cam", "bracket") else pytest.param(*c, marks=pytest.mark.slow)
    for c in FIGURE_CASES], ids=[c[0] for c in FIGURE_CASES])
def test_figure_text_never_overlaps(tmp_path, monkeypatch, name, grip):
    """Rendered figures of plans: the edge numbers overlap neither one another, nor the
    outline, the regions or the V's, and stay inside their drawing, under the V's; each
    legend lies outside every drawing and clear of every title and other legend."""
    import numpy as np

    from fcgrasp.plotting import plan_figure

    part = fc.read_part(f"demo:{name}")
    plans = fc.plan(part, top=3, **grip)
    fig = _drawn(monkeypatch, lambda: plan_figure(part, plans, str(tmp_path / "f.png"),
                                                  units="mm", title=name))
    r = fig.canvas.get_renderer()
    axes = [ax for ax in fig.axes if ax.get_legend() is not None]
    assert len(axes) == min(len(plans), 6) and axes
    frames = [ax.get_window_extent(r) for ax in axes]
    legends = [ax.get_legend().get_window_extent(r) for ax in axes]
    titles = [ax.title.get_window_extent(r) for ax in axes]
    for i, box in enumerate(legends):
        assert not any(box.overlaps(f) for f in frames), (name, i)
        assert not any(box.overlaps(t) for t in titles), (name, i)
        assert not any(box.overlaps(o) for j, o in enumerate(legends) if j != i)
    numbers = 0
    for ax, frame in zip(axes, frames, strict=True):
        labels = [t for t in ax.texts if t.get_gid() == "edge-label"]
        boxes = [t.get_window_extent(r) for t in labels]
        numbers += len(labels)
        lines = [ln for ln in ax.get_lines() if ln.get_zorder() >= 3]
        pts = [_dense(ax.transData.transform(np.asarray(ln.get_xydata(), float)))
               for ln in lines]
        outline = [_dense(ax.transData.transform(np.vstack([ring, ring[:1]])))
                   for ring in (part.vertices, *part.holes)]
        for k, box in enumerate(boxes):
            assert frame.x0 <= box.x0 and box.x1 <= frame.x1
            assert frame.y0 <= box.y0 and box.y1 <= frame.y1
            assert not any(box.overlaps(o) for o in boxes[k + 1:]), (name, labels[k])
            for p in pts + outline:
                assert not _inside(box, p).any(), (name, labels[k].get_text())
        assert all(t.get_zorder() < min(ln.get_zorder() for ln in lines) for t in labels)
    assert numbers >= len(axes) * min(part.n_edges, 6)
    fig.clf()


def test_panels_follow_the_parts_aspect(tmp_path, monkeypatch):
    """A wide thin part gets wide short panels with the legend below (no blank bands);
    a tall one, narrow panels with the legend to the right."""
    import numpy as np

    from fcgrasp.plotting import plan_figure

    for w, h in ((120.0, 12.0), (12.0, 120.0)):
        part = fc.Polygon([[0, 0], [w, 0], [w, h], [0, h]])
        plans = fc.plan(part, fingers=2, mu=0.3, top=3)
        fig = _drawn(monkeypatch, lambda part=part, plans=plans: plan_figure(
            part, plans, str(tmp_path / "f.png"), units="mm"))
        r = fig.canvas.get_renderer()
        ax = fig.axes[0]
        frame, legend = ax.get_window_extent(r), ax.get_legend().get_window_extent(r)
        width, height = fig.get_size_inches()
        if w > h:
            assert legend.y1 <= frame.y0 and height < 0.6 * width
        else:
            assert legend.x0 >= frame.x1
        # the drawing fills its panel: the axes hold the part's box, padded, no more
        ratio = (frame.height / frame.width) / (h + 0.24 * part.size) * (w + 0.24 * part.size)
        assert np.isclose(ratio, 1.0, rtol=0.02)
        fig.clf()
