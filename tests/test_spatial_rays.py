"""Every region of every solid gripper on real CAD meshes, cast onto the mesh by a ray
test of this module's own: the regions meet the part and every grasp inside them holds.

The corpus is ``benchmarks/corpus/meshes/`` (CAD parts with pockets, bosses and through
holes, from trimesh's test models; ``benchmarks/corpus/SOURCES.md``).  Each gripper plans
from the file as ``fcgrasp plan`` does (:func:`~fcgrasp.planning.request.plan_document`),
and the test reads only the JSON report.  Each region is sampled: its centre, its corners
pulled in by a hair, the corners of its holes pushed out by a hair, points along its
edges and seeded points inside.  Nothing of fcgrasp decides a sample:

- **meets the part**: a ray from just outside the sample, along the region's inward
  normal, hits the mesh (Moller-Trumbore over every triangle, written here) at the sample;
  the normal used below is the hit triangle's own;
- **holds**: two soft fingers when the segment between the contacts lies strictly inside
  both friction cones (the classical condition for soft contacts); three fingers with
  friction when the 6-D wrenches of their friction pyramids (32 sides, inscribed in the
  cones) positively span the wrench space, the oracle's LP (HiGHS); the jaw when rays along its
  closing axis from outside the part meet it first at the two contacts, whose normals
  hold the axis inside their cones.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from fcgrasp.core.tolerances import PLANAR_TOL
from fcgrasp.planning.request import PlanRequest, plan_document

from .oracle import closure_margin_lp

trimesh = pytest.importorskip("trimesh")
shapely = pytest.importorskip("shapely")

CORPUS = Path(__file__).resolve().parents[1] / "benchmarks" / "corpus" / "meshes"
MESHES = sorted(p.name for p in CORPUS.iterdir() if p.suffix.lower() in (".stl", ".ply", ".obj"))
MU = 0.5
SIDES = 32                          # the friction pyramid inscribed in each cone
#: how far a region's corners are pulled in (of the part's size), far above the ray
#: test's ties (the distances along a ray taken as one point)
HAIR = 1e-5
TIE = 5e-7
#: a region point lies on its facet's plane, and a facet's triangles lie within
#: ``PLANAR_TOL`` of the part's size of that plane (merged so): a point is on the part
#: when a triangle is hit that near it (the fandisk's curved faces come that close)
ON_PART = PLANAR_TOL + TIE
#: the cases of the default suite (the rest under -m slow)
QUICK = {("angle_block.STL", "pair"), ("idler_riser.STL", "jaw")}


def _mesh(name):
    mesh = trimesh.load(CORPUS / name, force="mesh", process=False)
    return np.asarray(mesh.vertices, float)[np.asarray(mesh.faces)]


def _hits(tri, origin, direction):
    """Distances along the ray to every triangle it crosses (Moller-Trumbore), with the
    triangles' indices, nearest first."""
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    e1, e2 = b - a, c - a
    p = np.cross(direction, e2)
    det = np.einsum("ij,ij->i", e1, p)
    ok = np.abs(det) > 1e-15 * np.linalg.norm(e1, axis=1) * np.linalg.norm(e2, axis=1)
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = origin - a
    u = np.einsum("ij,ij->i", s, p) * inv
    q = np.cross(s, e1)
    v = (q @ direction) * inv
    t = np.einsum("ij,ij->i", e2, q) * inv
    slack = 1e-9
    hit = ok & (u >= -slack) & (v >= -slack) & (u + v <= 1 + slack)
    idx = np.nonzero(hit)[0]
    order = np.argsort(t[idx])
    return t[idx][order], idx[order]


def _unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def _outward(tri):
    n = np.cross(tri[1] - tri[0], tri[2] - tri[0])
    return n / np.linalg.norm(n)


def _frame(ring):
    """An orthonormal frame of a planar ring (its Newell normal)."""
    ring = np.asarray(ring, float)
    n = np.zeros(3)
    for p, q in zip(ring, np.roll(ring, -1, axis=0), strict=True):
        n += np.cross(p, q)
    n = _unit(n)
    u = _unit(np.cross(n, [1.0, 0, 0] if abs(n[0]) < 0.9 else [0, 1.0, 0]))
    return ring.mean(axis=0), u, np.cross(n, u)


def _samples(rng, ring, holes, size, n):
    """Points of a planar region: its centre, its corners pulled in by a hair, its holes'
    corners pushed out by a hair, its edges' midpoints and ``n`` seeded points inside."""
    o, u, v = _frame(ring)
    flat = lambda r: np.column_stack([(np.asarray(r) - o) @ u, (np.asarray(r) - o) @ v])  # noqa: E731
    poly = shapely.Polygon(flat(ring), [flat(h) for h in holes])
    poly = poly.buffer(0) if not poly.is_valid else poly
    inner = poly.buffer(-HAIR * size)
    pts = [np.array(poly.representative_point().coords[0])]
    for piece in shapely.get_parts(inner):
        for r in (piece.exterior, *piece.interiors):
            c = np.asarray(r.coords)[:-1]
            pts += list(c) + list((c + np.roll(c, -1, axis=0)) / 2)
    lo_x, lo_y, hi_x, hi_y = poly.bounds
    if not inner.is_empty:
        for _ in range(50):                     # seeded points inside, n of them
            batch = rng.uniform([lo_x, lo_y], [hi_x, hi_y], size=(64, 2))
            pts += list(batch[shapely.contains_xy(inner, batch[:, 0], batch[:, 1])])
            if len(pts) >= n + 1:
                break
    pts = np.array(pts)
    return o + pts[:, :1] * u + pts[:, 1:] * v


def _surface_samples(rng, triangles, size, n):
    """Points of a region made of triangles on the mesh, with each one's triangle: the
    triangles' centroids, their corners moved in until they are a hair from both of the
    corner's edges, and ``n`` seeded points weighted by area (degenerate triangles
    left out)."""
    T = np.asarray(triangles, float)
    area = np.linalg.norm(np.cross(T[:, 1] - T[:, 0], T[:, 2] - T[:, 0]), axis=1) / 2
    T = T[area > 1e-12 * size * size]
    area = area[area > 1e-12 * size * size]
    # the heights onto each corner's opposite edge: a barycentric weight w on a corner
    # puts the point w times its height from that edge
    edge = np.linalg.norm(np.roll(T, -1, axis=1) - np.roll(T, 1, axis=1), axis=2)
    height = 2 * area[:, None] / edge
    w = np.minimum(HAIR * size / height, 1 / 3)               # (m, 3)
    corners = []
    for i in range(3):
        bary = w.copy()
        bary[:, i] = 1 - (w.sum(axis=1) - w[:, i])
        corners.append(np.einsum("mk,mkd->md", bary, T))
    c = T.mean(axis=1)
    pick = rng.choice(len(T), size=n, p=area / area.sum())
    r = rng.uniform(size=(n, 2))
    flip = r.sum(axis=1) > 1
    r[flip] = 1 - r[flip]
    inner = T[pick, 0] + r[:, :1] * (T[pick, 1] - T[pick, 0]) + r[:, 1:] * (T[pick, 2] - T[pick, 0])
    which = np.concatenate([np.arange(len(T)), np.tile(np.arange(len(T)), 3), pick])
    return np.vstack([c, *corners, inner]), T[which]


def _region_points(rng, grasp, k, size, n):
    """The samples of the ``k``-th region of a report's grasp, and the direction in which
    each is cast onto the mesh (the region's inward normal there)."""
    claimed = -_unit(grasp["normals"][k])          # the report's normals point out
    tris = grasp.get("surface_triangles")
    if tris is not None and len(tris[k]):
        P, T = _surface_samples(rng, tris[k], size, n)
        N = np.cross(T[:, 1] - T[:, 0], T[:, 2] - T[:, 0])
        N /= np.linalg.norm(N, axis=1)[:, None]
        N *= np.where(N @ claimed < 0, -1.0, 1.0)[:, None]
        return P, N
    holes = (grasp.get("holes") or [[]] * len(grasp["regions"]))[k]
    P = _samples(rng, grasp["regions"][k], holes, size, n)
    return P, np.broadcast_to(claimed, P.shape)


def _on_mesh(tri, size, points, inward):
    """Each point cast onto the mesh along its inward normal from just outside it (a
    fifth of the hair by which corners are pulled in, so that a neighbouring face meeting
    the region's edge at a reflex angle is not crossed on the way): the outward normals
    of the triangles hit at the point (a point on an edge of the mesh meets two), or an
    assertion that it is not on the part."""
    d = HAIR / 5 * size
    normals = []
    for p, n in zip(points, inward, strict=True):
        t, idx = _hits(tri, p - d * n, n)
        front = t > 0
        t, idx = t[front], idx[front]
        at = idx[np.abs(t - d) <= ON_PART * size]
        assert len(at), f"a region point {p} is not on the part (hits at {t[:3] - d})"
        # nothing of the part between the point and just outside it
        assert not np.any(t < d - ON_PART * size), f"the part covers the region point {p}"
        normals.append([_outward(tri[i]) for i in at])
    return normals


def _inside_cone(direction, outward, mu):
    """The pushing direction strictly inside the friction cone of a contact of this
    outward normal."""
    c = float(np.dot(_unit(direction), -outward))
    return c > 0 and math.atan2(math.sqrt(max(0.0, 1 - c * c)), c) < math.atan(mu)


def _wrenches(points, inward, mu, centre, size):
    rows = []
    for p, n in zip(points, inward, strict=True):
        n = _unit(n)
        u = _unit(np.cross(n, [1.0, 0, 0] if abs(n[0]) < 0.9 else [0, 1.0, 0]))
        v = np.cross(n, u)
        for a in np.arange(SIDES) * 2 * math.pi / SIDES:
            f = n + mu * (math.cos(a) * u + math.sin(a) * v)
            rows.append(np.concatenate([f, np.cross((p - centre) / size, f)]))
    return np.array(rows)


def _report(name, **options):
    doc = plan_document(PlanRequest(part=str(CORPUS / name), mu=MU, **options))
    return json.loads(json.dumps(doc.report))


def _size(tri):
    pts = tri.reshape(-1, 3)
    return float(np.linalg.norm(pts.max(axis=0) - pts.min(axis=0)))


def _check_pair(rng, tri, size, grasp):
    regions = []
    for k in range(2):
        P, N = _region_points(rng, grasp, k, size, 12)
        regions.append((P, _on_mesh(tri, size, P, N)))
    (P1, N1), (P2, N2) = regions
    for p, ns in zip(P1, N1, strict=True):
        for q, ms in zip(P2, N2, strict=True):
            assert all(_inside_cone(q - p, n, MU) for n in ns), (p, q)
            assert all(_inside_cone(p - q, m, MU) for m in ms), (p, q)
    return len(P1) * len(P2)


def _check_triple(rng, tri, size, grasp):
    regions = []
    for k in range(3):
        P, N = _region_points(rng, grasp, k, size, 8)
        regions.append((P, _on_mesh(tri, size, P, N)))
    count = 0
    for _ in range(40):
        pick = [int(rng.integers(len(P))) for P, _ in regions]
        points = np.array([regions[k][0][i] for k, i in enumerate(pick)])
        for normals in _every(regions, pick):
            w = _wrenches(points, [-n for n in normals], MU, points.mean(axis=0), size)
            assert closure_margin_lp(w) > 0, points
            count += 1
    return count


def _every(regions, pick):
    """Each choice of outward normal at the picked points (two where a point lies on an
    edge of the mesh)."""
    choices = [regions[k][1][i] for k, i in enumerate(pick)]
    out = [[]]
    for c in choices:
        out = [o + [n] for o in out for n in c]
    return out


def _check_jaw(rng, tri, size, grasp):
    axis = _unit(grasp["axis"])
    opening = grasp["opening"]
    P, _ = _region_points(rng, grasp, 0, size, 20)
    far = 4 * size
    for x in P:
        y = x + opening * axis
        # the first pad: from outside the part along the axis, the part is met at x first
        t, idx = _hits(tri, x - far * axis, axis)
        assert len(t) and abs(t[0] - far) <= TIE * size, f"the axis at {x} meets {t[:2]}"
        first = [_outward(tri[i]) for i in idx[np.abs(t - t[0]) <= TIE * size]]
        # the second pad: from outside along the axis reversed, met at y first
        t2, idx2 = _hits(tri, y + far * axis, -axis)
        assert len(t2) and abs(t2[0] - far) <= TIE * size, f"the axis at {y} meets {t2[:2]}"
        second = [_outward(tri[i]) for i in idx2[np.abs(t2 - t2[0]) <= TIE * size]]
        # a flat pad presses on the face it is flush with: where the axis meets an edge
        # of the mesh (a region's corner), one of the faces there
        assert any(_inside_cone(axis, n, MU) for n in first), x
        assert any(_inside_cone(-axis, n, MU) for n in second), x
    return len(P)


def _gripper_options(kind, size):
    if kind == "pair":
        return {"fingers": 2, "soft": True, "top": 3}
    if kind == "triple":
        return {"fingers": 3, "top": 2}
    return {"gripper": "jaw", "stroke": (0.02 * size, size), "pad": 0.04 * size, "top": 3}


CHECKS = {"pair": _check_pair, "triple": _check_triple, "jaw": _check_jaw}


@pytest.mark.parametrize(("name", "kind"), [
    (n, k) if (n, k) in QUICK else pytest.param(n, k, marks=pytest.mark.slow)
    for n in MESHES for k in sorted(CHECKS)])
def test_every_region_on_a_real_mesh_meets_the_part_and_holds(name, kind):
    rng = np.random.default_rng(sum(map(ord, name + kind)))
    tri = _mesh(name)
    size = _size(tri)
    report = _report(name, **_gripper_options(kind, size))
    assert report["grasps"], report.get("reason")
    checked = sum(CHECKS[kind](rng, tri, size, g) for g in report["grasps"])
    assert checked > 0


@pytest.mark.parametrize(("name", "scale"), [
    ("idler_riser.STL", 1.0),
    pytest.param("idler_riser.STL", 0.6, marks=pytest.mark.slow),
    pytest.param("featuretype.STL", 1.0, marks=pytest.mark.slow),
    pytest.param("featuretype.STL", 0.6, marks=pytest.mark.slow)])
def test_twenty_jaw_plans_on_parts_with_holes(name, scale):
    """Twenty plans of the jaw on CAD parts with through holes (where the regions'
    unions met shapely's "unable to assign free hole to a shell" and "Scale factor must
    be non-zero"): every region holds."""
    rng = np.random.default_rng(20)
    tri = _mesh(name)
    size = _size(tri)
    report = _report(name, gripper="jaw", stroke=(0.02 * scale * size, scale * size),
                     pad=0.04 * scale * size, top=20, time_limit=0)
    assert len(report["grasps"]) >= 5
    assert sum(_check_jaw(rng, tri, size, g) for g in report["grasps"]) > 0


def test_the_ray_test_can_fail():
    """A region moved off its facet by a tenth of the part, or a friction cone narrowed
    below the plan's, is caught."""
    rng = np.random.default_rng(7)
    tri = _mesh("angle_block.STL")
    size = _size(tri)
    grasp = _report("angle_block.STL", fingers=2, soft=True, top=1)["grasps"][0]
    moved = dict(grasp, regions=[(np.asarray(grasp["regions"][0]) + 0.1 * size *
                                  np.asarray(grasp["normals"][0])).tolist(),
                                 grasp["regions"][1]])
    moved.pop("surface_triangles", None)
    with pytest.raises(AssertionError):
        _check_pair(rng, tri, size, moved)
    narrow = math.tan(math.atan(MU) * 0.2)
    P, N = _region_points(rng, grasp, 0, size, 4)
    Q, _ = _region_points(rng, grasp, 1, size, 4)
    n = _on_mesh(tri, size, P, N)
    assert not all(_inside_cone(q - p, m, narrow) for p, ns in zip(P, n, strict=True)
                   for q in Q for m in ns)
