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
