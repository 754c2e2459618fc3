"""Curves are flattened finely enough that regions along the boundary do not depend on
the flattening tolerance (issue 12): the same regions, to 2%, at ``--flatten`` of 1/200
and of 1/5,000 of the part's size, for SVG paths (Bezier curves, arcs), SVG ellipses and
DXF arcs; and no piece of a flattened curve turns more than the limit."""

from __future__ import annotations

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.io._drawing import MAX_TURN_DEG

SVG = """<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm"
 viewBox="0 0 100 100">
<path id="blade" d="M 10 50 C 10 20, 40 10, 60 15 C 85 20, 95 45, 85 70
 A 20 15 0 0 1 40 85 Q 10 80 10 50 Z"/>
<ellipse id="oval" cx="50" cy="50" rx="40" ry="25"/></svg>"""


def _dxf(path):
    ezdxf = pytest.importorskip("ezdxf")
    doc = ezdxf.new()
    msp = doc.modelspace()
    msp.add_line((0, 0), (60, 0))
    msp.add_arc((60, 20), 20, -90, 90)
    msp.add_line((60, 40), (0, 40))
    msp.add_arc((0, 20), 20, 90, 270)
    doc.saveas(path)


@pytest.fixture(params=["svg:blade", "svg:oval", "dxf"])
def drawing(request, tmp_path):
    if request.param == "dxf":
        path = tmp_path / "slot.dxf"
        _dxf(path)
        return path, {}
    pytest.importorskip("svgelements")
    path = tmp_path / "part.svg"
    path.write_text(SVG)
    return path, {"part": request.param.split(":")[1]}


@pytest.mark.parametrize("mu", [0.3, pytest.param(0.6, marks=pytest.mark.slow)])
def test_regions_do_not_depend_on_the_flattening(drawing, mu):
    path, kw = drawing
    size = fc.read_part(path, **kw).size
    coarse = fc.read_part(path, flatten=size / 200, **kw)
    fine = fc.read_part(path, flatten=size / 5000, **kw)
    a = fc.plan(coarse, mu=mu, top=1)[0]
    b = fc.plan(fine, mu=mu, top=1)[0]
    assert a.min_length == pytest.approx(b.min_length, rel=0.02)
    assert np.sort(a.lengths) == pytest.approx(np.sort(b.lengths), rel=0.02)
    # the same places: each region's middle within 2% of the size
    d = np.hypot(*(a.contacts[:, None] - b.contacts[None]).T).T
    assert min(d[0, 0] + d[1, 1], d[0, 1] + d[1, 0]) <= 0.04 * size


def test_every_curve_piece_turns_at_most_the_limit():
    from fcgrasp.io._drawing import flatten_curve

    out = [1 + 0j]
    flatten_curve(lambda t: np.exp(1j * np.pi * t), 0.5, out)     # a half circle
    pts = np.array(out)
    turn = np.degrees(np.abs(np.angle(np.diff(pts)[1:] / np.diff(pts)[:-1])))
    assert turn.max() <= MAX_TURN_DEG and abs(pts[-1] + 1) < 1e-12
