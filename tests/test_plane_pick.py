"""A real hand holding a plate in its plane (the jaw with ``--in-plane``): the bound on
the outline in a band is exact (against shapely's clipping), every sampled pose of every
cut box is collision free along the whole motion by an independent collision library
(python-fcl through trimesh on the extruded plate), force closure by the general test,
and the same check finds collisions in the boxes the cut leaves out."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.grippers.jaw import ParallelJaw, jaw_poses
from fcgrasp.grippers.jaw._pick import Scene
from fcgrasp.grippers.jaw._plane_pick import PlaneReach, band_support, plane_cut
from fcgrasp.io.moveit import tool_rotation
from fcgrasp.model.hands import hand_named

trimesh = pytest.importorskip("trimesh")
pytest.importorskip("fcl")
shapely = pytest.importorskip("shapely")

from fcgrasp.grippers.jaw._plane_pick import _bands, _cell_clear  # noqa: E402
from fcgrasp.grippers.jaw._plans import _kind  # noqa: E402
from fcgrasp.grippers.jaw._poses import _grip_edges  # noqa: E402
from tests.shapes import star  # noqa: E402
from tests.test_hand_pick import SHRINK, _closes, _collides, _manager, _planned  # noqa: E402


def _swept(hand, origin_from, origin_to, R, open_from, open_to):
    """Each box's swept volume as the hand moves from one placement to another by a
    translation (the convex hull of its corners at both ends: exact for a box)."""
    out = []
    for b0, b1 in zip(hand.boxes(open_from), hand.boxes(open_to), strict=True):
        pts = [o + (c @ R.T) for o, b in ((origin_from, b0), (origin_to, b1))
               for c in [b.corners(SHRINK)]]
        out.append(trimesh.convex.convex_hull(np.vstack(pts)))
    return out


def _sweep_collides(manager, part, jaw, reach, side, theta, offset) -> bool | None:
    """Whether the pick of one pose in the plane meets the part or the table anywhere on
    its way (coming in open from the approach distance, then closing), by fcl on the
    boxes' exact swept volumes; None where the pose's opening passes the stroke."""
    r = jaw_poses(part, jaw, [theta], [offset])
    top, bottom = float(r.top[0]), float(r.bottom[0])
    if not np.isfinite(top - bottom) or top - bottom > jaw.hand.stroke[1]:
        return None
    u = np.array([math.cos(theta), math.sin(theta)])
    n = np.array([-u[1], u[0]])
    zc = sum(jaw.hand.pad_span) / 2
    xy = part.centroid + (top + bottom) / 2 * u + (offset + side * zc) * n
    R = tool_rotation(np.r_[u, 0.0], np.r_[-side * n, 0.0])
    origin = np.r_[xy, reach.height[side]]
    far = origin + np.r_[side * jaw.scene.approach * n, 0.0]
    widest = jaw.hand.stroke[1]
    return _collides(manager, _swept(jaw.hand, far, origin, R, widest, widest)
                     + _swept(jaw.hand, origin, origin, R, widest, top - bottom))


@pytest.mark.parametrize("seed", range(3))
def test_the_band_support_is_shapelys_clipped_outline(seed):
    """The largest ``a`` of segments clipped to a band, against shapely's intersection of
    each segment with the band's box (seeded, with bands on the ends and flat segments)."""
    rng = np.random.default_rng(seed)
    for _ in range(300):
        E = int(rng.integers(1, 12))
        pts = rng.integers(-5, 6, size=(E, 2, 2)).astype(float) * rng.choice([1.0, 0.37])
        if rng.random() < 0.3:
            pts[:, 1, 1] = pts[:, 0, 1]                # flat in b
        a, b = pts[..., 0], pts[..., 1]
        lo, hi = sorted(rng.integers(-6, 7, size=2).astype(float) * rng.choice([1.0, 0.5]))
        got = band_support(a, b, lo, hi)
        box = shapely.box(-1e3, lo, 1e3, hi) if hi > lo else \
            shapely.LineString([(-1e3, lo), (1e3, lo)])
        want = -math.inf
        for seg in pts:
            cut = shapely.LineString(seg).intersection(box) if np.any(seg[0] != seg[1]) \
                else (shapely.Point(seg[0]) if box.covers(shapely.Point(seg[0]))
                      else shapely.Point())
            if not cut.is_empty:
                want = max(want, float(np.asarray(cut.bounds)[[0, 2]].max()))
        assert got == pytest.approx(want, abs=1e-9), (seed, pts, lo, hi)


CASES = [("bracket", 0.6, None, False),
         pytest.param("rectangle", 0.5, None, False, marks=pytest.mark.slow),
         pytest.param("washer", 0.5, 60.0, True, marks=pytest.mark.slow),
         pytest.param("cam", 0.8, None, False, marks=pytest.mark.slow),
         pytest.param("blob", 0.6, 60.0, True, marks=pytest.mark.slow)]


@pytest.mark.parametrize("name,mu,thickness,table", CASES)
def test_every_sampled_pose_of_a_plan_in_the_plane_is_collision_free(name, mu, thickness,
                                                                       table):
    hand = hand_named("franka")
    scene = Scene(hand.pad_width if thickness is None else thickness, table=table,
                  in_plane=True)
    part, jaw, plans, manager = _planned(name, hand, mu, scene, PlaneReach)
    reach = jaw.pick
    rng = np.random.default_rng(11)
    checked = 0
    for p in plans:
        assert p.side in (1, -1) and p.mode == "external"
        # a cut box describes its own centre pose: where the pads stop, how they touch
        r = jaw_poses(part, jaw, [p.centre[0]], [p.centre[1]])
        assert p.stops == (float(r.top[0]), float(r.bottom[0]))
        assert p.kinds == (_kind(r.lat_a[0], r.psi_a[0], part.size),
                           _kind(r.lat_b[0], r.psi_b[0], part.size)), (name, p.kinds)
        for theta, offset in p.sample(8, rng):
            assert jaw_poses(part, jaw, [theta], [offset]).holds[0], (name, theta, offset)
            assert _closes(part, jaw, mu, theta, offset), (name, theta, offset)
            assert _sweep_collides(manager, part, jaw, reach, p.side, theta, offset) is False, \
                (name, theta, offset)
            checked += 1
    assert checked >= 16


@pytest.mark.parametrize("seed,parts", [(0, 2)] + [pytest.param(s, 12, marks=pytest.mark.slow)
                                                   for s in range(1, 5)])
def test_proved_cells_of_random_parts_are_clear_by_fcl(seed, parts):
    """Random cells of jaw poses on seeded star-shaped parts of the hand's size (bumps
    beside the strip, material behind the palm): every sampled pose of a cell the bound
    proves clears the part along its whole sweep by fcl, and poses it does not prove do
    collide (so a weaker bound fails here)."""
    rng = np.random.default_rng(seed)
    hand = hand_named("franka")
    proved = refused_hits = 0
    for _ in range(parts):
        part = None
        while part is None:
            try:
                part = fc.Polygon(star(rng) * rng.uniform(20.0, 60.0))
            except ValueError:              # a star drawn not simple: draw again
                continue
        table = bool(rng.random() < 0.3)
        scene = Scene(60.0 if table else hand.pad_width, table=table, in_plane=True)
        jaw = ParallelJaw.of_hand(hand, 0.5, scene)
        reach = jaw.pick
        manager = _manager(part, scene)
        ring = _grip_edges(part, None)
        rel = np.stack([part.starts[ring] - part.centroid, part.ends[ring] - part.centroid],
                       axis=1)
        rho = float(np.linalg.norm(rel.reshape(-1, 2), axis=1).max())
        for _ in range(4 if parts < 12 else 8):
            t0 = rng.uniform(0, 2 * np.pi)
            c0 = rng.uniform(-0.8, 0.8) * part.radius
            for side in (1, -1):
                bands = _bands(hand, scene, side, reach.height[side], jaw.pad_width)

                def cell(k: int, t0=t0, c0=c0):
                    return (t0, t0 + 0.004 * 2 ** k), (c0, c0 + 0.25 * 2 ** k)

                # the largest cell the bound proves, doubled from a small one: its
                # corners are where a bound too weak would fail
                k = -1
                while k < 7 and _cell_clear(rel, *cell(k + 1), bands, jaw.pad_width, rho):
                    k += 1
                ok = k >= 0
                (ta, tb), (ca, cb) = cell(max(k, 0))
                for j in range(6 if ok else 1):
                    th = (ta, tb)[j % 2] if j < 4 else rng.uniform(ta, tb)
                    c = (ca, cb)[j // 2 % 2] if j < 4 else rng.uniform(ca, cb)
                    hit = _sweep_collides(manager, part, jaw, reach, side, th, c)
                    if hit is None:
                        continue
                    if ok:
                        assert not hit, (seed, part.vertices.tolist(), side, th, c, table)
                        proved += 1
                    else:
                        refused_hits += bool(hit)
    assert proved >= 12 * parts and refused_hits >= parts, (proved, refused_hits)


def test_the_check_finds_collisions_in_what_the_cut_leaves_out():
    """The bare jaw's boxes the cut drops or shrinks hold poses whose pick in the plane
    collides by fcl (the rectangle gripped across its middle: the palm meets the part's
    far end on either side), so the cut is not vacuous."""
    part = fc.read_part("demo:rectangle")
    hand = hand_named("franka")
    scene = Scene(hand.pad_width, table=False, in_plane=True)
    jaw = ParallelJaw.of_hand(hand, 0.5, scene)
    reach = jaw.pick
    manager = _manager(part, scene)
    theta, offset = math.pi / 2, 0.0                       # across the middle
    assert plane_cut(part, hand, scene, reach, (theta - 1e-3, theta + 1e-3),
                     (offset - 0.1, offset + 0.1), jaw.pad_width) is None
    assert jaw_poses(part, jaw, [theta], [offset]).holds[0]
    for side in (1, -1):
        assert _sweep_collides(manager, part, jaw, reach, side, theta, offset), side


def test_a_plane_pick_report_validates_and_exports_to_moveit(tmp_path, capsys):
    from fcgrasp.apps.cli import main
    from fcgrasp.io.schema import validate as validate_report

    out, grasps = tmp_path / "p.json", tmp_path / "g.yaml"
    rc = main(["plan", "demo:bracket", "--gripper", "jaw", "--hand", "franka", "--in-plane",
               "--mu", "0.6", "--top", "2", "--json", str(out), "--moveit", str(grasps)])
    assert rc == 0, capsys.readouterr().err
    report = json.loads(out.read_text())
    validate_report(report)
    assert report["scene"]["held"] == "in_plane"
    assert report["grasps"]
    for g in report["grasps"]:
        assert g["held"] == "in_plane" and g["collision_free"]
        d = np.asarray(g["approach"]["direction"])
        assert d[2] == 0 and np.linalg.norm(d) == pytest.approx(1.0)
        q = np.asarray(g["pose"]["orientation"])
        assert np.linalg.norm(q) == pytest.approx(1.0)
        # the tool's z is the approach, in the plate's plane
        from fcgrasp.io.moveit import rotation
        assert rotation(q)[:, 2] == pytest.approx(d)
    assert "grasp_pose" in grasps.read_text()


@pytest.mark.parametrize("argv,words", [
    (["demo:box", "--gripper", "jaw", "--hand", "franka", "--in-plane"], "not --in-plane"),
    (["demo:rectangle", "--gripper", "jaw", "--stroke", "10,50", "--pad", "8",
      "--in-plane"], "--hand"),
])
def test_in_plane_jaw_refusals_are_one_line(capsys, argv, words):
    from fcgrasp.apps.cli import main

    rc = main(["plan", *argv])
    err = capsys.readouterr().err
    assert rc == 2 and words in err and len(err.strip().splitlines()) == 1, err


def test_a_thin_plate_on_a_table_has_no_pick_in_the_plane_and_says_why(capsys):
    """The Franka Hand's palm is 63 mm wide: in the plane of a plate as thick as its pad
    is wide, on a table, the hand cannot clear the table and still touch the plate."""
    from fcgrasp.apps.cli import main

    rc = main(["plan", "demo:rectangle", "--gripper", "jaw", "--hand", "franka",
               "--in-plane", "--table"])
    out = capsys.readouterr().out
    assert rc == 0 and out.startswith("no grasp: ") and "off the table" in out, out
