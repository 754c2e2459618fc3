"""Curves are flattened finely enough that regions along the boundary do not depend on
the flattening tolerance: the same regions, to 2%, at ``--flatten`` of 1/200
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

    for tol in (1e-2, 1e-3, 1e-5):
        out = [1 + 0j]
        flatten_curve(lambda t: np.exp(1j * np.pi * t), tol, out)     # a half circle
        pts = np.array(out)
        turn = np.degrees(np.abs(np.angle(np.diff(pts)[1:] / np.diff(pts)[:-1])))
        assert turn.max() <= MAX_TURN_DEG and abs(pts[-1] + 1) < 1e-12


def test_a_curve_finer_than_the_tolerance_is_not_cut_much_finer_than_it():
    """The turn rule gives way where the pieces would be shorter than a quarter
    of the tolerance (a fillet smaller than the tolerance gets a few edges, not 180)."""
    from fcgrasp.io._drawing import flatten_curve

    tol = 1e-3
    for r in (1e-4, 1e-3, 3e-3):
        out = [complex(r, 0)]
        flatten_curve(lambda t, r=r: r * np.exp(1j * np.pi * t), tol, out)
        edges = np.abs(np.diff(np.array(out)))
        assert len(edges) <= np.pi * r / (tol / 8) + 2


# --- pieces of equal turn, against the binary halving kept as the reference ---

def _bezier(ctrl):
    ctrl = np.asarray(ctrl, dtype=complex)

    def points(ts):
        t = np.asarray(ts, dtype=float)[:, None]
        i = np.arange(4)
        return (np.array([1, 3, 3, 1]) * t ** i * (1 - t) ** (3 - i)) @ ctrl
    return points


def _arc(r, a0, a1, c=0j):
    return lambda ts: c + r * np.exp(1j * (a0 + (a1 - a0) * np.asarray(ts, dtype=float)))


def _curves(n, seed):
    """Seeded curves: cubic Beziers (some with coincident, collinear or nearly crossing
    controls: cusps, loops, straight ones), circular arcs of every size and turn."""
    rng = np.random.default_rng(seed)
    out = []
    for k in range(n):
        kind = k % 5
        if kind == 4:
            r = 10.0 ** rng.uniform(-3, 3)
            a0 = rng.uniform(-np.pi, np.pi)
            out.append((_arc(r, a0, a0 + rng.choice([-1, 1]) * rng.uniform(1e-3, 2 * np.pi)),
                        r * 10.0 ** rng.uniform(-4, -1)))
            continue
        c = rng.normal(size=4) + 1j * rng.normal(size=4)
        if kind == 1:
            c[1] = c[0] + 1e-9 * (rng.normal() + 1j * rng.normal())   # a stationary start
        elif kind == 2:
            c[1:3] = c[0] + (c[3] - c[0]) * np.sort(rng.uniform(size=2)) \
                + 1e-7 * rng.normal(size=2)                           # nearly straight
        elif kind == 3:
            c[2] = c[1] + (c[1] - c[2]) * 1e-3                         # near a cusp
        out.append((_bezier(c), 10.0 ** rng.uniform(-5, -1) * np.abs(c).max()))
    return out


def _normal_errors(points, params):
    """The largest angle (degrees) between each piece's chord and the curve's tangent
    anywhere along it (by 64 samples of each piece, all pieces at once), and each
    piece's chord length."""
    t = np.asarray(params)
    s = t[:-1, None] + (t[1:] - t[:-1])[:, None] * np.linspace(0, 1, 65)
    z = points(s.ravel()).reshape(s.shape)
    tangent = np.diff(z, axis=1)
    chord = z[:, -1] - z[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        ang = np.degrees(np.abs(np.angle(tangent / chord[:, None])))
    return np.where(np.abs(tangent) > 0, ang, 0.0).max(axis=1), np.abs(chord)


def _distance_to_polyline(q, pts):
    """Distance of each point ``q`` (complex) to the polyline ``pts`` (GEOS)."""
    import shapely

    line = shapely.LineString(np.c_[pts.real, pts.imag])
    return shapely.distance(shapely.points(np.c_[q.real, q.imag]), line)


@pytest.mark.parametrize("seed, count", [(0, 12), pytest.param(1, 400, marks=pytest.mark.slow),
                                         pytest.param(2, 400, marks=pytest.mark.slow)])
def test_equal_turn_flattening_keeps_both_rules_with_fewer_edges(seed, count):
    """Every piece's chord within ``tol`` of the curve and within
    :data:`MAX_TURN_DEG` of its tangent all along it (but where it is no longer than a
    quarter of ``tol``: a cusp, a curve finer than the tolerance), with fewer edges than
    the halving kept as reference."""
    from fcgrasp.io._drawing import flatten_curve

    from .previous_flatten import previous_flatten

    n_new = n_old = more = 0
    for points, tol in _curves(count, seed):
        start = complex(points(np.array([0.0]))[0])
        new, old, params = [start], [start], [0.0]
        flatten_curve(points, tol, new, params)
        previous_flatten(points, tol, old)
        new_pts = np.array(new)
        assert len(params) == len(new) and params[-1] == 1.0
        assert np.all(np.diff(params) > 0)
        assert np.abs(points(np.array(params)) - new_pts).max() == 0
        dense = points(np.linspace(0, 1, 20001))
        assert _distance_to_polyline(dense, new_pts).max() <= tol
        err, chord = _normal_errors(points, params)
        assert np.all((err <= MAX_TURN_DEG + 1e-6) | (chord <= tol / 4))
        # more only where the chord rule decides (checked along the piece here, at
        # its middle by the halving)
        assert len(new) <= 1.25 * len(old) + 1
        more += len(new) > len(old)
        n_new, n_old = n_new + len(new), n_old + len(old)
    assert n_new <= 0.8 * n_old and more <= 0.1 * count


@pytest.mark.parametrize("mu", [0.3, pytest.param(0.6, marks=pytest.mark.slow)])
def test_two_finger_regions_stay_with_the_halving_and_the_curve(drawing, mu, monkeypatch):
    """With the equal-turn flattening the two-finger plan's smallest region on
    the curved test parts is within 1% of the binary halving's (the rule per piece is
    the same, the pieces fewer), and every region as near the curve's own (a flattening
    ten times finer in turn) as the halving's, to 1%."""
    from fcgrasp.io import _drawing, _read_dxf, _read_svg

    from .previous_flatten import previous_flatten

    path, kw = drawing
    new = fc.read_part(path, **kw)
    with monkeypatch.context() as m:
        m.setattr(_read_svg, "flatten_curve", previous_flatten)
        m.setattr(_read_dxf, "flatten_curve", previous_flatten)
        old = fc.read_part(path, **kw)
    with monkeypatch.context() as m:
        m.setattr(_drawing, "MAX_TURN_DEG", MAX_TURN_DEG / 10)
        curve = fc.read_part(path, **kw)
    assert new.n_edges < 0.8 * old.n_edges and curve.n_edges > 5 * new.n_edges
    a, b, c = (fc.plan(p, mu=mu, top=1, distinct=0)[0] for p in (new, old, curve))
    assert a.min_length == pytest.approx(b.min_length, rel=0.01)
    # as near the curve's own regions as the halving is, to 1% of them
    err_new = np.abs(np.sort(a.lengths) - np.sort(c.lengths))
    err_old = np.abs(np.sort(b.lengths) - np.sort(c.lengths))
    assert np.all(err_new <= err_old + 0.01 * np.sort(c.lengths))
