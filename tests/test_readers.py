"""Real drawing files: every form a user brings, generated with ezdxf's writer,
imageio, and by hand for SVG, JSON and WKT; what is read (outline, holes, units, which part)
is compared with the known part, and each format runs end to end through fcgrasp plan."""

from __future__ import annotations

import io
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import shapely

import fcgrasp as fc
from fcgrasp.io.parts import choose_part, list_parts, load_part, read_part
from fcgrasp.model.outline import clean_ring, fill_rings

ezdxf = pytest.importorskip("ezdxf")
iio = pytest.importorskip("imageio.v3")


def run(*args, stdin=None):
    env = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run([sys.executable, "-m", "fcgrasp", *map(str, args)], input=stdin,
                          capture_output=True, timeout=600, env=env)


def bounds(poly):
    return np.r_[poly.vertices.min(axis=0), poly.vertices.max(axis=0)]


# ----------------------------------------------------------------------------- DXF


def dxf_doc(units=4):
    doc = ezdxf.new()
    doc.units = units
    return doc, doc.modelspace()


def add_arch(msp, x0=0.0, layer="0"):
    """A 10 x 5 rectangle capped by a half disc of radius 5: four separate entities."""
    msp.add_line((x0, 0), (x0 + 10, 0), dxfattribs={"layer": layer})
    msp.add_line((x0 + 10, 0), (x0 + 10, 5), dxfattribs={"layer": layer})
    msp.add_arc((x0 + 5, 5), 5, 0, 180, dxfattribs={"layer": layer})
    msp.add_line((x0, 5), (x0, 0), dxfattribs={"layer": layer})


ARCH_AREA = 50 + math.pi * 25 / 2


def test_dxf_separate_entities_joined_with_a_circle_hole(tmp_path):
    doc, msp = dxf_doc()
    add_arch(msp)
    msp.add_circle((5, 4), 1.5)
    f = tmp_path / "arch.dxf"
    doc.saveas(f)
    part = load_part(f)
    assert part.count == 1 and part.units == "mm" and part.scale == 1.0
    assert len(part.polygon.holes) == 1
    want = ARCH_AREA - math.pi * 1.5 ** 2
    assert abs(part.polygon.area - want) / want < 5e-3
    assert np.allclose(bounds(part.polygon), [0, 0, 10, 10], atol=1e-6)


def test_dxf_insunits_inches_converted(tmp_path):
    doc, msp = dxf_doc(units=1)            # inches
    add_arch(msp)
    f = tmp_path / "inch.dxf"
    doc.saveas(f)
    mm = load_part(f)
    assert mm.file_units == "in" and mm.scale == pytest.approx(25.4)
    assert np.allclose(bounds(mm.polygon), [0, 0, 254, 254], atol=1e-6)
    inch = load_part(f, units="in")
    assert inch.scale == 1.0 and np.allclose(bounds(inch.polygon), [0, 0, 10, 10])
    # a unitless file is taken in the units asked, unless --file-units says otherwise
    doc.units = 0
    doc.saveas(f)
    assert load_part(f).scale == 1.0 and load_part(f).file_units is None
    assert load_part(f, file_units="cm").scale == pytest.approx(10.0)


def test_dxf_layers_blocks_splines_ellipses(tmp_path):
    doc, msp = dxf_doc()
    add_arch(msp, layer="OUTLINE")
    blk = doc.blocks.new("TAB")
    blk.add_lwpolyline([(0, 0), (4, 0), (4, 2), (0, 2)], close=True)
    msp.add_blockref("TAB", (30, 0), dxfattribs={"layer": "TABS"})
    msp.add_ellipse((60, 0), major_axis=(6, 0), ratio=0.5, dxfattribs={"layer": "E"})
    fit = [(80, 0), (84, 2), (82, 5), (79, 3), (80, 0)]
    msp.add_spline(fit, dxfattribs={"layer": "S"}).closed = True
    f = tmp_path / "mixed.dxf"
    doc.saveas(f)
    parts = list_parts(f)
    assert {p.layer for p in parts} == {"OUTLINE", "TABS", "E", "S"}
    block = load_part(f, "TABS")
    assert block.polygon.area == pytest.approx(8.0)
    assert np.allclose(bounds(block.polygon), [30, 0, 34, 2])
    ell = load_part(f, layer="E")
    assert ell.count == 1 and abs(ell.polygon.area / (math.pi * 6 * 3) - 1) < 5e-3
    assert load_part(f).layer == "OUTLINE"                  # the largest
    with pytest.raises(ValueError, match="layer 'nope'"):
        list_parts(f, layer="nope")


def test_dxf_gap_tolerance(tmp_path):
    doc, msp = dxf_doc()
    msp.add_line((0, 0), (10, 0))
    msp.add_line((10, 0), (10, 10))
    msp.add_line((10, 10), (0, 10))
    msp.add_line((0, 10), (0, 0.01))                        # a 0.01 gap
    f = tmp_path / "gap.dxf"
    doc.saveas(f)
    with pytest.raises(ValueError, match="no closed loop"):
        read_part(f)
    assert read_part(f, gap=0.02).area == pytest.approx(100.0, rel=1e-3)


@pytest.mark.parametrize("closed", [False, True])
def test_dxf_polylines_closing_a_hair_off_are_holes(tmp_path, closed):
    """A disc with four hexagonal holes, each drawn as a polyline whose last vertex
    repeats its first 1e-6 off (flagged closed or not): four holes of a hexagon's area,
    no sliver ring; without any other open entity the reader has no edges to chain."""
    doc, msp = dxf_doc()
    msp.add_circle((0, 0), 11)
    a = np.linspace(0, 2 * np.pi, 7)[:-1]
    for cx, cy in [(5, 0), (-5, 0), (0, 5), (0, -5)]:
        pts = [(cx + 2 * math.cos(t), cy + 2 * math.sin(t)) for t in a]
        msp.add_lwpolyline(pts + [(cx + 2 + 1e-6, cy)], close=closed)
    f = tmp_path / "bottle.dxf"
    doc.saveas(f)
    parts = list_parts(f)
    assert len(parts) == 1
    poly = parts[0].polygon
    assert len(poly.holes) == 4
    hexagon = 1.5 * math.sqrt(3) * 2 ** 2
    assert poly.area == pytest.approx(math.pi * 11 ** 2 - 4 * hexagon, rel=1e-3)


# ----------------------------------------------------------------------------- SVG


def svg(body, attrs='width="200" height="200"'):
    return f'<svg xmlns="http://www.w3.org/2000/svg" {attrs}>{body}</svg>'


def write(tmp_path, name, text):
    f = tmp_path / name
    f.write_text(text) if isinstance(text, str) else f.write_bytes(text)
    return f


def test_svg_units_px_and_real_units(tmp_path):
    # 18 inches = 1728 px = 457.2 mm
    disc = write(tmp_path, "disc.svg", svg('<circle cx="900" cy="900" r="864"/>',
                                           'width="1800" height="1800"'))
    p = load_part(disc)
    assert p.file_units == "px" and p.flip_y
    w = np.ptp(p.polygon.vertices[:, 0])
    assert w == pytest.approx(457.2, rel=1e-6)
    assert np.ptp(load_part(disc, units="in").polygon.vertices[:, 0]) == pytest.approx(18.0)
    mm = write(tmp_path, "mm.svg", svg('<rect x="10" y="10" width="60" height="20"/>',
                                       'width="100mm" height="50mm" viewBox="0 0 100 50"'))
    poly = read_part(mm)
    # y flipped about the page's height: up from its bottom edge
    assert np.allclose(bounds(poly), [10, 20, 70, 40], atol=1e-9)


def test_svg_parts_sit_on_the_page_with_y_up(tmp_path):
    """An SVG part keeps the page's positive coordinates, y up from its
    bottom edge (an icon's viewBox, a page in mm, a page without a size)."""
    px = 25.4 / 96                                          # mm per CSS px
    for attrs, h, mm in (('width="24" height="24" viewBox="0 0 24 24"', 24, px),
                         ('width="100mm" height="50mm" viewBox="0 0 100 50"', 50, 1.0),
                         ('width="48" height="48" viewBox="0 0 24 24"', 24, 2 * px)):
        f = write(tmp_path, "p.svg", svg('<path d="M2 3 L20 3 L11 21 Z"/>', attrs))
        box = bounds(read_part(f)) / mm                     # in the drawing's own units
        assert np.allclose(box, [2, h - 21, 20, h - 3], atol=1e-6), attrs
    # the corpus's icons: every vertex on the page
    v = read_part(Path(__file__).resolve().parents[1] / "benchmarks" / "corpus" / "icons"
                  / "bell.svg").vertices / px
    assert v.min() >= 0 and v[:, 1].max() <= 24 + 1e-9


def test_svg_compound_paths_by_fill_rule(tmp_path):
    outer = "M0 0 H40 V40 H0 Z"
    same = "M10 10 H30 V30 H10 Z"            # same orientation as the outer square
    rev = "M10 10 V30 H30 V10 Z"             # reversed
    for rule, inner, area, holes in (("evenodd", same, 1200, 1), ("nonzero", same, 1600, 0),
                                     ("nonzero", rev, 1200, 1), (None, rev, 1200, 1)):
        attr = f' fill-rule="{rule}"' if rule else ""
        f = write(tmp_path, "c.svg", svg(f'<path d="{outer} {inner}"{attr}/>',
                                         'width="40mm" height="40mm" viewBox="0 0 40 40"'))
        poly = read_part(f)
        assert poly.area == pytest.approx(area) and len(poly.holes) == holes, rule
    # a glyph-like path: two separate islands are two parts, the larger chosen
    f = write(tmp_path, "i.svg", svg('<path id="i" d="M0 0 H4 V20 H0 Z M0 24 H4 V28 H0 Z"/>'))
    parts = list_parts(f)
    assert [p.id for p in parts] == ["i#1", "i#2"]
    assert load_part(f).id == "i#1"


def test_svg_groups_backgrounds_and_outlines(tmp_path):
    body = ('<path d="M0 0h512v512H0z"/>'                           # icon background
            '<g id="icon" transform="translate(100 100)">'
            '<path id="blade" fill="#fff" d="M0 0 L200 0 L200 50 L0 50 Z"/>'
            '<circle id="dot" fill="#fff" cx="100" cy="150" r="30"/></g>'
            '<path id="outline" fill="none" stroke="#000" d="M300 300 h100 v100 h-100 z"/>')
    f = write(tmp_path, "icon.svg", svg(body, 'width="512" height="512" viewBox="0 0 512 512"'))
    parts = list_parts(f)
    assert [p.background for p in parts] == [True, False, False, False]
    assert load_part(f).id == "blade"                  # not the background
    assert load_part(f, "icon").id == "blade"          # a group: the largest of its shapes
    assert load_part(f, "dot").id == "dot"
    assert load_part(f, "0").background                # asked for by index: given
    assert load_part(f, "outline").polygon.area == pytest.approx((100 * 25.4 / 96) ** 2)
    with pytest.raises(ValueError, match="no part with id 'nope'"):
        load_part(f, "nope")


# ----------------------------------------------------------------------------- GeoJSON, WKT, JSON


def test_geojson_multipolygon_takes_the_largest_and_names(tmp_path):
    small = [[[0, 0], [1, 0], [1, 1], [0, 0]]]
    big = [[[10, 0], [20, 0], [20, 10], [10, 10], [10, 0]]]
    fc_ = {"type": "FeatureCollection", "features": [
        {"type": "Feature", "id": "uk", "properties": {"name": "United Kingdom"},
         "geometry": {"type": "MultiPolygon", "coordinates": [small, big]}},
        {"type": "Feature", "properties": {"name": "Isle"},
         "geometry": {"type": "Polygon", "coordinates": [[[30, 0], [33, 0], [33, 3],
                                                           [30, 0]]]}}]}
    f = write(tmp_path, "w.geojson", json.dumps(fc_))
    parts = list_parts(f)
    assert [p.id for p in parts] == ["uk#1", "uk#2", "Isle"]
    assert load_part(f).id == "uk#2"
    assert load_part(f, "United Kingdom").polygon.area == pytest.approx(100)
    assert load_part(f, "Isle").polygon.area == pytest.approx(4.5)


def test_wkt_one_geometry_per_line_and_multipolygons(tmp_path):
    f = write(tmp_path, "m.wkt", "POLYGON ((0 0, 1 0, 1 1, 0 0))\n\nMULTIPOLYGON "
                                 "(((0 0, 5 0, 5 5, 0 5, 0 0)), ((9 9, 10 9, 9 10, 9 9)))\n")
    parts = list_parts(f)
    assert len(parts) == 3 and load_part(f).polygon.area == pytest.approx(25)
    assert load_part(f, "line1").polygon.area == pytest.approx(0.5)
    bad = write(tmp_path, "bad.wkt", "POLYGON ((0 0, 1 0, 1 1, 0 0))\nPOLYGON ((0 0, 1\n")
    with pytest.raises(ValueError, match="line 2: not valid WKT"):
        read_part(bad)


def test_bare_json_rings_units_and_touching_hole(tmp_path):
    ring = [[0, 0], [10, 0], [10, 10], [0, 10]]
    assert read_part(write(tmp_path, "r.json", json.dumps(ring))).area == 100
    hole = [[5, 0], [7, 3], [3, 3]]                      # touches the outer ring at (5, 0)
    p = read_part(write(tmp_path, "h.json", json.dumps([ring, hole])))
    assert p.area == pytest.approx(94) and len(p.holes) == 1
    inch = load_part(write(tmp_path, "u.json", json.dumps({"vertices": ring, "units": "in"})))
    assert inch.scale == pytest.approx(25.4) and inch.polygon.area == pytest.approx(64516)
    with pytest.raises(ValueError, match="bare JSON part"):
        read_part(write(tmp_path, "x.json", json.dumps([[[[0, 0]]]])))


def test_y_down_inputs_flipped(tmp_path):
    f = write(tmp_path, "s.json", json.dumps([[0, 0], [10, 0], [0, 5]]))
    up, down = load_part(f), load_part(f, y_down=True)
    assert not up.flip_y and down.flip_y
    assert np.allclose(down.polygon.vertices, up.polygon.vertices * [1, -1])


# ----------------------------------------------------------------------------- images


def silhouette(shape=(120, 160)):
    img = np.full(shape, 255, np.uint8)
    yy, xx = np.mgrid[:shape[0], :shape[1]]
    img[(xx > 30) & (xx < 130) & (yy > 30) & (yy < 90)] = 0          # a plate
    img[(xx - 60) ** 2 + (yy - 60) ** 2 < 15 ** 2] = 255             # with a hole
    img[:, :8] = 0                                                   # a dark band at the border
    return img


@pytest.mark.parametrize("ext", [".png", ".gif", ".bmp"])
def test_image_silhouettes_with_holes_not_the_border(tmp_path, ext):
    f = tmp_path / f"plate{ext}"
    iio.imwrite(f, silhouette())
    p = load_part(f)
    assert p.units == "px" and len(p.polygon.holes) == 1
    assert np.allclose(np.ptp(p.polygon.vertices, axis=0), [98, 58], atol=2)
    # y up from the image's bottom row: the plate (rows 31-89 of 120) at y 30-89
    assert np.allclose(bounds(p.polygon)[[1, 3]], [120 - 89.5, 120 - 30.5], atol=1)
    mm = load_part(f, pixel_size=0.5)
    assert mm.units == "mm" and np.allclose(np.ptp(mm.polygon.vertices, axis=0), [49, 29],
                                            atol=1)
    assert np.allclose(bounds(mm.polygon)[[1, 3]], [15.25, 44.75], atol=0.5)
    with pytest.raises(ValueError, match="pixel_size"):
        load_part(f, units="mm")


@pytest.mark.parametrize("seed", [0, *(pytest.param(s, marks=pytest.mark.slow)
                                       for s in range(1, 20))])
def test_the_chain_approximation_is_scikit_images_bit_for_bit(seed):
    """The image reader's Douglas-Peucker (``_read_image.approximate_chain``) keeps the
    points, bit for bit, that scikit-image's ``measure.approximate_polygon`` keeps (the
    reference): on the contours of 20 random blobs per seed (closed chains, staircases
    of pixel edges) and on random walks with straight runs, repeated points and a chain
    that turns back on itself, at tolerances from 0 to beyond the chain."""
    from skimage.measure import approximate_polygon, find_contours

    from fcgrasp.io._read_image import approximate_chain

    rng = np.random.default_rng(70 + seed)
    chains = []
    for _ in range(20):
        blob = np.zeros((40, 40))
        for _ in range(int(rng.integers(1, 6))):
            r, c, w = rng.integers(5, 35), rng.integers(5, 35), rng.integers(2, 9)
            yy, xx = np.mgrid[:40, :40]
            blob[(yy - r) ** 2 + (xx - c) ** 2 * rng.uniform(0.3, 3) < w ** 2] = 1
        chains += find_contours(np.pad(blob, 1), 0.5)
    for _ in range(40):
        steps = rng.normal(size=(int(rng.integers(2, 80)), 2))
        steps[rng.random(len(steps)) < 0.3] = steps[0]            # straight runs
        steps[rng.random(len(steps)) < 0.1] = 0.0                 # repeated points
        walk = np.cumsum(steps, axis=0)
        chains += [walk, np.concatenate([walk, walk[::-1]])]
    checked = 0
    for chain in chains:
        for tol in (0.0, 1e-9, 0.5, 1.0, 2.5, 1e3):
            want = approximate_polygon(chain, tolerance=tol)
            got = approximate_chain(chain, tol)
            assert got.shape == want.shape and np.array_equal(got, want), tol
            checked += 1
    assert checked > 500


def test_reading_an_image_leaves_scipy_signal_unimported(tmp_path):
    """A fresh process that reads a silhouette does not import ``scipy.signal`` (which
    scikit-image's polygon module imports: 0.6 s of its start)."""
    f = tmp_path / "plate.png"
    iio.imwrite(f, silhouette())
    code = ("import sys\nimport fcgrasp as fc\n"
            f"p = fc.load_part({str(f)!r})\n"
            "print(len(p.polygon.holes), 'scipy.signal' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == ["1", "False"]


def test_image_light_part_on_dark_and_threshold(tmp_path):
    img = 255 - silhouette()
    img[:, :8] = 0
    f = tmp_path / "inv.png"
    iio.imwrite(f, img)
    assert np.allclose(np.ptp(read_part(f).vertices, axis=0), [98, 58], atol=2)
    assert np.allclose(np.ptp(read_part(f, threshold=0.3).vertices, axis=0), [98, 58], atol=2)


# ----------------------------------------------------------------------------- clean-up


def test_collinear_runs_merged_and_plans_distinct(tmp_path):
    # a straight 19.5-long side drawn as 11 pieces
    side = [[19.5 * k / 11, 0.0] for k in range(11)]
    ring = side + [[19.5, 0.0], [19.5, 8.0], [0.0, 8.0]]
    raw = fc.Polygon(ring)
    part = load_part(write(tmp_path, "split.json", json.dumps(ring)))
    assert part.cleaned == 10 and part.polygon.n_edges == 4
    plans = fc.plan(part.polygon, mu=0.3, top=10)
    assert plans[0].min_length > 1.77 * 1.5          # no longer capped by a piece
    keys = {tuple(sorted(p.edges)) for p in plans}
    assert len(keys) == len(plans)
    # without clean-up the pieces stay, as asked
    assert load_part(write(tmp_path, "s2.json", json.dumps(ring)),
                     clean=False).polygon.n_edges == raw.n_edges


def test_clean_ring_keeps_curves_and_shape():
    rng = np.random.default_rng(3)
    for _ in range(200):
        n = int(rng.integers(3, 40))
        a = np.sort(rng.uniform(0, 2 * np.pi, n))
        r = rng.uniform(0.5, 1.5, n)
        ring = np.c_[r * np.cos(a), r * np.sin(a)]
        # insert collinear points on every edge
        mids = (ring + np.roll(ring, -1, axis=0)) / 2
        dense = np.empty((2 * n, 2))
        dense[0::2], dense[1::2] = ring, mids
        out = clean_ring(dense, 1e-9)
        assert len(out) <= n
        # the outline is the same set (area of the symmetric difference ~ 0)
        p, q = shapely.Polygon(dense), shapely.Polygon(out)
        if p.is_valid:
            assert p.symmetric_difference(q).area < 1e-9


def test_fill_rings_against_crossing_count():
    rng = np.random.default_rng(11)
    for _ in range(15):
        rings = [rng.uniform(0, 10, (int(rng.integers(3, 7)), 2)) for _ in range(3)]
        pts = rng.uniform(0, 10, (400, 2))
        for rule in ("evenodd", "nonzero"):
            filled = shapely.unary_union(fill_rings(rings, rule))
            got = shapely.contains_xy(filled, pts[:, 0], pts[:, 1])
            want = _reference_fill(rings, pts, rule)
            near = np.array([min(shapely.LinearRing(r).distance(shapely.Point(p))
                                 for r in rings) for p in pts]) < 1e-6
            assert np.array_equal(got[~near], want[~near]), rule


def _reference_fill(rings, pts, rule):
    """Sum of signed crossings of a ray to +x (written without fcgrasp)."""
    total = np.zeros(len(pts), int)
    for r in rings:
        for (x0, y0), (x1, y1) in zip(r, np.roll(r, -1, axis=0), strict=True):
            for k, (px, py) in enumerate(pts):
                if (y0 <= py) != (y1 <= py):
                    x = x0 + (py - y0) * (x1 - x0) / (y1 - y0)
                    if x > px:
                        total[k] += 1 if y1 > y0 else -1
    return total != 0 if rule == "nonzero" else total % 2 == 1


def test_choose_part_errors():
    with pytest.raises(ValueError, match="no part"):
        choose_part([])
    parts = list_parts("demo:blob")
    with pytest.raises(ValueError, match="part 3 does not exist"):
        choose_part(parts, 3)
    with pytest.raises(TypeError, match="part must be"):
        choose_part(parts, 1.5)


# ----------------------------------------------------------------------------- end to end


def _files(tmp_path):
    doc, msp = dxf_doc()
    add_arch(msp)
    doc.saveas(tmp_path / "a.dxf")
    iio.imwrite(tmp_path / "a.gif", silhouette())
    return {
        "a.dxf": [],
        "a.svg": write(tmp_path, "a.svg", svg('<path d="M0 0 H40 V30 H0 Z M10 10 H20 V20 H10 Z"'
                                              ' fill-rule="evenodd"/>')),
        "a.geojson": write(tmp_path, "a.geojson", json.dumps(
            {"type": "MultiPolygon", "coordinates": [[[[0, 0], [9, 0], [9, 4], [0, 0]]],
                                                     [[[20, 0], [60, 0], [60, 30], [20, 30],
                                                       [20, 0]]]]})),
        "a.wkt": write(tmp_path, "a.wkt", "POLYGON ((0 0, 40 0, 40 30, 0 30, 0 0))\n"
                                          "POLYGON ((50 0, 51 0, 51 1, 50 0))\n"),
        "a.json": write(tmp_path, "a.json", json.dumps([[0, 0], [40, 0], [40, 30], [0, 30]])),
        "a.gif": [],
    }


@pytest.mark.parametrize("name", ["a.dxf", "a.svg", "a.geojson", "a.wkt", "a.json", "a.gif"])
def test_every_format_through_fcgrasp_plan(tmp_path, capsys, name):
    """Each format read and planned by the command (in this process: the command in a
    process of its own is :func:`test_stdin_and_stdout`'s)."""
    from fcgrasp.apps.cli import main

    _files(tmp_path)
    f = tmp_path / name
    capsys.readouterr()
    assert main(["plan", str(f), "--top", "3", "--json", "-"]) == 0
    data = json.loads(capsys.readouterr().out)        # --json -: only JSON on stdout
    part = load_part(f)
    assert data["source"]["file"] == str(f) and data["source"]["index"] == part.index
    assert np.allclose(data["part"]["vertices"], part.polygon.vertices, atol=1e-9)
    want = fc.plan(part.polygon, mu=0.3, top=3, disturbance=(10.0, 15.0))
    assert [g["edges"] for g in data["grasps"]] == [list(p.edges) for p in want]
    assert main(["parts", str(f)]) == 0 and "*" in capsys.readouterr().out


def test_stdin_and_stdout(tmp_path):
    ring = json.dumps([[0, 0], [40, 0], [40, 30], [0, 30]]).encode()
    r = run("plan", "-", "--json", "-", "--top", "2", stdin=ring)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["source"]["file"] == "-"
    svg_bytes = svg('<rect width="40" height="30"/>').encode()
    assert run("plan", "-", "--quiet", stdin=svg_bytes).returncode == 0
    buf = io.BytesIO()
    iio.imwrite(buf, silhouette(), extension=".png")
    r = run("parts", "-", stdin=buf.getvalue())
    assert r.returncode == 0 and b"px" in r.stdout


def test_check_exit_codes(tmp_path):
    good = write(tmp_path, "g.json", json.dumps({"contacts": [{"point": [0, 15], "mu": 0.3},
                                                              {"point": [80, 15], "mu": 0.3}]}))
    bad = write(tmp_path, "b.json", json.dumps({"contacts": [{"point": [0, 15]},
                                                             {"point": [80, 15]}]}))
    assert run("check", "demo:rectangle", "--contacts", good).returncode == 0
    assert run("check", "demo:rectangle", "--contacts", bad).returncode == 1
    assert run("check", "demo:rectangle", "--contacts", tmp_path / "none.json").returncode == 2


def test_version_is_fast():
    code = ("import sys; from fcgrasp.apps.cli import main; main(['--version']); "
            "print(sorted(m for m in ('numpy', 'shapely', 'scipy') if m in sys.modules))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       check=True)
    assert r.stdout.splitlines() == [f"fcgrasp {fc.__version__}", "[]"]


def test_every_option_has_help():
    from fcgrasp.apps.cli import build_parser

    parser = build_parser()
    subs = next(a for a in parser._actions if a.dest == "command").choices
    for name, p in [("fcgrasp", parser), *subs.items()]:
        for a in p._actions:
            if a.dest != "help":
                assert a.help, (name, a.dest)


@pytest.mark.parametrize(("name", "text"), [
    ("z.wkt", "POLYGON Z ((0 0 1, 10 0 1, 10 5 2, 0 5 2, 0 0 1))"),
    ("z.geojson", '{"type": "Polygon", "coordinates": '
                  '[[[0, 0, 1], [10, 0, 1], [10, 5, 2], [0, 5, 2], [0, 0, 1]]]}'),
])
def test_z_coordinates_are_dropped_and_said(tmp_path, name, text):
    """WKT (or GeoJSON) with Z values was refused with an array dump."""
    from fcgrasp.io.parts import load_part

    path = tmp_path / name
    path.write_text(text)
    part = load_part(str(path))
    assert part.polygon.vertices.shape == (4, 2) and abs(part.polygon.area - 50) < 1e-12
    assert any("Z coordinates dropped" in n for n in part.notes)
    flat = tmp_path / ("flat" + path.suffix)
    flat.write_text(text.replace(" Z", "").replace(", 1]", "]").replace(", 2]", "]")
                    .replace(" 1,", ",").replace(" 2,", ",").replace(" 1))", "))"))
    assert np.allclose(load_part(str(flat)).polygon.vertices, part.polygon.vertices)
    assert not load_part(str(flat)).notes


def test_an_opaque_rgba_image_with_clear_corners_is_read_by_its_colours(tmp_path):
    """An RGBA PNG opaque but for a few corner pixels read as "no silhouette found",
    even with --threshold."""
    from PIL import Image

    from fcgrasp.io.parts import load_part

    rgba = np.full((60, 80, 4), 255, np.uint8)
    rgba[20:40, 25:55, :3] = 0                       # a dark 30 x 20 rectangle
    rgba[0, 0, 3] = rgba[0, -1, 3] = rgba[-1, 0, 3] = 0
    path = tmp_path / "icon.png"
    Image.fromarray(rgba, "RGBA").save(path)
    for threshold in (None, 0.5):
        part = load_part(str(path), threshold=threshold)
        assert abs(part.polygon.area - 600) < 60, part.polygon.area
    clear = rgba.copy()
    clear[..., 3] = 0
    clear[20:40, 25:55, 3] = 255                     # a transparent background: alpha rules
    Image.fromarray(clear, "RGBA").save(path)
    assert abs(load_part(str(path)).polygon.area - 600) < 60


def test_slivers_are_not_parts(tmp_path):
    """Sliver parts of 5e-4 mm (drafting leftovers beside a plate) were listed as parts."""
    from fcgrasp.io.parts import list_parts

    path = tmp_path / "plate.wkt"
    path.write_text("MULTIPOLYGON (((0 0, 100 0, 100 50, 0 50, 0 0)),"
                    " ((200 0, 210 0, 210 0.0005, 200 0.0005, 200 0)),"
                    " ((300 0, 303 0, 303 3, 300 3, 300 0)))")
    parts = list_parts(str(path))
    assert [round(p.polygon.area, 6) for p in parts] == [5000.0, 9.0]   # the 3 mm one stays
    assert any("1 sliver" in n for n in parts[0].notes)
    path.write_text("POLYGON ((200 0, 210 0, 210 0.0005, 200 0.0005, 200 0))")
    assert len(list_parts(str(path))) == 1             # alone, a thin part is the part
