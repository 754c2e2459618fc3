"""Regression tests of the input contract: each named after the defect it keeps
fixed.  Library functions raise ValueError/TypeError naming the argument; the CLI prints
one line and exits 2, writes nothing on failure and never overwrites an input."""

from __future__ import annotations

import json
import os
import stat

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.apps.cli import main
from fcgrasp.model.quality import resistance_metrics
from fcgrasp.planning.planner import geometric_key

from ._highs import linprog
from .grippers import grip
from .shapes import random_polygon

BLOB = fc.read_part("demo:blob")


def cli(capsys, *args):
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


def assert_one_line_error(code, err, *words):
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    for w in words:
        assert w in err, err


# ------------------------------------------------------------------ library arguments

@pytest.mark.parametrize("call, exc, word", [
    (lambda: fc.plan(BLOB, fingers=2.0), TypeError, "fingers"),
    (lambda: fc.plan(BLOB, fingers=5), ValueError, "fingers"),
    (lambda: fc.plan(BLOB, margin="1"), TypeError, "margin"),
    (lambda: fc.plan(BLOB, disturbance=(1,)), ValueError, "disturbance"),
    (lambda: fc.plan(BLOB, mu=[0.3, 0.4]), TypeError, "mu"),
    (lambda: fc.plan(BLOB, progress=5), TypeError, "progress"),
    (lambda: fc.plan(BLOB, top=2.5), TypeError, "top"),
    (lambda: fc.plan(BLOB, rank_by=3), TypeError, "rank_by"),
    (lambda: fc.Polygon([["0", "0"], [1, 0], [1, 1]]), TypeError, "vertices"),
    (lambda: fc.Polygon([[True, 0], [1, 0], [1, 1]]), TypeError, "vertices"),
    (lambda: fc.Polygon([[0, 0], [1, 0], [1, 1]], holes=None), TypeError, "holes"),
    (lambda: fc.Polygon([[0, 0], [1, 0], [1, 1]], holes=5), TypeError, "holes"),
    (lambda: fc.FrictionPoint([0, 0], [1, 0], mu=[0.1, 0.2]), TypeError, "mu"),
    (lambda: fc.friction_pair_closure(np.zeros((3, 2)), [1, 0], np.ones((4, 2)), [-1, 0],
                                      0.3), ValueError, "normal_q"),
    (lambda: fc.independent_regions(BLOB, (fc.Vertex(2), 4), mu=0.5), ValueError, "Vertex"),
    (lambda: fc.read_part("demo:blob", flatten=0.1), ValueError, "flatten"),
])
def test_errors_name_the_argument(call, exc, word):
    with pytest.raises(exc, match=word):
        call()


def test_independent_regions_refuses_vertex_soft_finger():
    with pytest.raises(ValueError, match="soft finger"):
        fc.independent_regions(BLOB, (fc.Vertex(2), 4), mu=0.5)
    # the soft finger is planned by grasp_sets, and the plain edges still work
    assert fc.independent_regions(BLOB, (2, 5), mu=0.5) is not None


@pytest.mark.parametrize("scale", [1e101, 1e200, 1e300])
def test_huge_coordinates_refused_clearly(scale):
    with pytest.raises(ValueError, match="documented range"):
        fc.Polygon(np.array(BLOB.vertices) * scale / 70)
    with pytest.raises(ValueError, match="documented range"):
        fc.friction_pair_closure([0, 0], [-1, 0], [scale, 0], [1, 0], 0.3)


def test_tiny_parts_refused_clearly():
    with pytest.raises(ValueError, match="documented range"):
        fc.Polygon(np.array(BLOB.vertices) * 1e-103)


@pytest.mark.parametrize("scale", [1e-99, 1e-40, 1e40, 1e98])
def test_every_scale_in_range_gives_the_same_plans(scale):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for fingers, mu in ((2, 0.3), (4, 0.0), (3, 0.0)):
            ref = fc.plan(BLOB, **grip(fingers, mu), top=3)
            got = fc.plan(fc.Polygon(np.array(BLOB.vertices) * scale), **grip(fingers, mu),
                          top=3)
            assert [p.edges for p in got] == [p.edges for p in ref]
            for a, b in zip(got, ref, strict=True):
                np.testing.assert_allclose(a.ends / scale, b.ends, rtol=1e-9,
                                           atol=1e-9 * BLOB.size)
                assert a.grasp().is_force_closure()
                assert np.isfinite(a.quality["epsilon_l1"])


# ------------------------------------------------------------------ quality and reports

def _least_total_force_lp(w, target):
    res = linprog(np.ones(len(w)), A_eq=w.T, b_eq=target, bounds=[(0, None)] * len(w),
                  method="highs")
    return res.fun if res.status == 0 else None


def test_resistance_defined_for_every_grasp_plan_returns():
    for fingers, mu in ((2, 0.3), (3, 0.0), (4, 0.0)):
        for p in fc.plan(BLOB, **grip(fingers, mu), top=3) + fc.plan(BLOB, fingers=3, mu=0.5,
                                                                     top=2):
            q = p.quality
            assert np.isfinite(q["resistance"]) and q["resistance"] > 0, (fingers, q)
            assert q["resistance_approx"] <= q["resistance"] + 1e-12


def test_resistance_with_six_generating_forces_matches_lp(rng):
    """Three fingers with friction: six generators; the least-total-force distribution of
    every disturbance agrees with an LP (HiGHS)."""
    checked = 0
    for _ in range(30):
        ang = np.sort(rng.uniform(0, 2 * np.pi, 3))
        pts = np.column_stack([np.cos(ang), np.sin(ang)])
        g = fc.Grasp([fc.FrictionPoint(pt, pt, 0.4) for pt in pts])
        if not g.is_force_closure():
            continue
        fingers = np.repeat(np.arange(3), 2)
        centroid = np.zeros(2)
        r = resistance_metrics(g.points, g.forces, fingers, centroid, 1.0, 1.0, 15.0)
        assert np.isfinite(r["resistance"]) and r["resistance"] > 0
        p_, f_ = g.points, g.forces
        w = np.column_stack([f_, p_[:, 0] * f_[:, 1] - p_[:, 1] * f_[:, 0]])
        for tgt in ([-1, 0, 0], [0, 0, -1], [0, 0, 1], [0.6, -0.8, 0]):
            assert _least_total_force_lp(w, np.array(tgt, float)) is not None
        checked += 1
    assert checked >= 5


def test_resistance_of_non_closure_grasp_is_zero():
    pts = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], float)
    forces = np.array([[1, 0], [-1, 0], [1, 0], [-1, 0]], float)
    r = resistance_metrics(pts, forces, np.arange(4), pts.mean(0), 1.0, 1.0, 15.0)
    assert r["resistance"] == 0.0


@pytest.mark.parametrize("scale", [1e-6, 1e-3, 1.0, 1e6])
def test_to_dict_rounds_to_significant_digits(scale):
    part = fc.Polygon(np.array(BLOB.vertices) * scale * (1 + 1 / 3))
    d = fc.plan(part, fingers=2, mu=0.3, top=1)[0].to_dict()
    x = d["regions"][0][0][0]
    mantissa = repr(abs(x)).split("e")[0].replace(".", "").lstrip("0").rstrip("0")
    digits = len(mantissa)
    assert digits == 12, x         # 12 significant digits, not 12 decimals
    assert x == float(f"{x:.12g}")


# ------------------------------------------------------------------ numbering

def _renumbered(poly, rng):
    v = np.array(poly.vertices)
    k = int(rng.integers(0, len(v)))
    v = np.roll(v, k, axis=0)
    return fc.Polygon(v[::-1] if rng.random() < 0.5 else v)


@pytest.mark.parametrize("kind", ["rectangle", "regular", "convex", "star"])
def test_ranking_independent_of_vertex_numbering(kind, rng):
    for _ in range(3):
        poly = random_polygon(rng, kind)
        other = _renumbered(poly, rng)
        for fingers, mu in ((2, 0.8), (4, 0.0)):
            if fingers == 4 and poly.n_edges > 8:
                continue
            a = [geometric_key(p.regions, poly) for p in fc.plan(poly, **grip(fingers, mu),
                                                                 top=4)]
            b = [geometric_key(p.regions, other) for p in fc.plan(other, **grip(fingers, mu),
                                                                  top=4)]
            assert a == b, (kind, fingers, poly)


@pytest.mark.parametrize("starts", [(0, 1, 5, 6, 11), pytest.param(range(12),
                                                                      marks=pytest.mark.slow)])
def test_tied_placement_independent_of_numbering_i_glyph(starts):
    glyph = np.array([[0, 0], [30, 0], [30, 6], [19, 6], [19, 34], [30, 34], [30, 40],
                      [0, 40], [0, 34], [11, 34], [11, 6], [0, 6]], float)
    keys = set()
    for k in starts:
        for v in (np.roll(glyph, k, axis=0), np.roll(glyph, k, axis=0)[::-1]):
            poly = fc.Polygon(v)
            p = fc.plan(poly, fingers=4, mu=0, top=1)[0]
            keys.add(geometric_key(p.regions, poly))
    assert len(keys) == 1


# ------------------------------------------------------------------ CLI

def _part(tmp_path):
    p = tmp_path / "part.json"
    p.write_text(json.dumps({"vertices": BLOB.vertices.tolist()}))
    return p


def _contacts(tmp_path, data):
    c = tmp_path / "grasp.json"
    c.write_text(json.dumps(data))
    return c


TWO = [{"point": [21, -3], "mu": 0.5}, {"point": [47, 52], "mu": 0.5}]


@pytest.mark.parametrize("gravity", [[0, -1], True, {"directon": [0, -1]}, {"direction": 5}])
def test_check_gravity_malformed_is_an_error(tmp_path, capsys, gravity):
    c = _contacts(tmp_path, {"contacts": TWO, "gravity": gravity})
    code, _, err = cli(capsys, "check", _part(tmp_path), "--contacts", c)
    assert_one_line_error(code, err, "gravity")


@pytest.mark.parametrize("data, key", [
    ({"contacts": TWO, "gravty": {}}, "gravty"),
    ({"contacts": [{"point": [21, -3], "mu": 0.5, "normall": [0, 1]}]}, "normall"),
])
def test_unknown_keys_in_contacts_file(tmp_path, capsys, data, key):
    code, _, err = cli(capsys, "check", _part(tmp_path), "--contacts", _contacts(tmp_path, data))
    assert_one_line_error(code, err, key)


def test_unknown_keys_in_part_file(tmp_path, capsys):
    p = tmp_path / "part.json"
    p.write_text(json.dumps({"vertices": BLOB.vertices.tolist(), "hoels": []}))
    code, _, err = cli(capsys, "plan", p)
    assert_one_line_error(code, err, "hoels")


def test_contacts_edge_true_is_an_error(tmp_path, capsys):
    c = _contacts(tmp_path, {"contacts": [{"point": [21, -3], "mu": 0.5, "edge": True},
                                          TWO[1]]})
    code, _, err = cli(capsys, "check", _part(tmp_path), "--contacts", c)
    assert_one_line_error(code, err, "edge")


def test_output_path_equal_to_input_is_refused(tmp_path, capsys):
    part = _part(tmp_path)
    before = part.read_bytes()
    code, _, err = cli(capsys, "plan", part, "--json", part)
    assert_one_line_error(code, err, "input")
    c = _contacts(tmp_path, {"contacts": TWO})
    cbefore = c.read_bytes()
    code, _, err = cli(capsys, "check", part, "--contacts", c, "--json", c)
    assert_one_line_error(code, err, "input")
    code, _, err = cli(capsys, "check", part, "--contacts", c, "--plot",
                       tmp_path / "." / "part.json")
    assert code == 2
    assert part.read_bytes() == before and c.read_bytes() == cbefore


def test_options_validated_before_any_output(tmp_path, capsys):
    out = tmp_path / "out.json"
    code, _, err = cli(capsys, "plan", _part(tmp_path), "--json", out, "--plot",
                       tmp_path / "out.txt")
    assert_one_line_error(code, err, "--plot")
    assert not out.exists()


@pytest.mark.parametrize("value", ["-1", "0", "nan", "inf"])
def test_flatten_is_checked(tmp_path, capsys, value):
    code, _, err = cli(capsys, "plan", _part(tmp_path), f"--flatten={value}")
    assert_one_line_error(code, err, "flatten")


def test_flatten_does_not_apply_to_json(tmp_path, capsys):
    code, _, err = cli(capsys, "plan", _part(tmp_path), "--flatten", "0.5")
    assert_one_line_error(code, err, "flatten")


def test_geojson_non_object_feature_is_one_line(tmp_path, capsys):
    p = tmp_path / "part.geojson"
    p.write_text(json.dumps({"type": "FeatureCollection", "features": [5]}))
    code, _, err = cli(capsys, "plan", p)
    assert_one_line_error(code, err, "features[0]")


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_read_only_folder_error_names_the_users_path(tmp_path, capsys):
    d = tmp_path / "ro"
    d.mkdir()
    d.chmod(stat.S_IRUSR | stat.S_IXUSR)
    try:
        code, _, err = cli(capsys, "plan", _part(tmp_path), "--json", d / "out.json")
        assert_one_line_error(code, err, str(d / "out.json"))
        assert ".fcgrasp-tmp" not in err
    finally:
        d.chmod(stat.S_IRWXU)


def test_output_error_names_the_users_path(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    target = blocker / "out.json"          # a folder that is a file: cannot write
    code, _, err = cli(capsys, "plan", _part(tmp_path), "--json", target)
    assert_one_line_error(code, err, str(target))
    assert ".fcgrasp-tmp" not in err


def test_outputs_written_as_a_set(tmp_path, capsys, monkeypatch):
    import fcgrasp.plotting as plotting

    def broken(fig, path, outputs=None):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(plotting, "save_figure", broken)
    out, fig = tmp_path / "out.json", tmp_path / "out.png"
    code, _, err = cli(capsys, "plan", _part(tmp_path), "--json", out, "--plot", fig)
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert sorted(os.listdir(tmp_path)) == ["part.json"]   # no JSON without its figure


def test_stale_temporaries_of_a_killed_run_are_removed(tmp_path, capsys):
    out = tmp_path / "out.json"
    stale = tmp_path / ".out.json.fcgrasp-tmp-abc123.json"
    stale.write_text("{half")
    code, _, _ = cli(capsys, "plan", _part(tmp_path), "--json", out, "--quiet")
    assert code == 0
    assert sorted(os.listdir(tmp_path)) == ["out.json", "part.json"]


def test_outputs_follow_the_umask(tmp_path, capsys):
    old = os.umask(0o022)
    try:
        out = tmp_path / "out.json"
        assert cli(capsys, "plan", _part(tmp_path), "--json", out, "--quiet")[0] == 0
        assert stat.S_IMODE(out.stat().st_mode) == 0o644
    finally:
        os.umask(old)
