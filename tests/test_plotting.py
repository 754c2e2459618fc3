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
    plan_figure(part, fc.plan(part, fingers=2, mu=0.2, top=4), str(out))
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
