import numpy as np
import pytest

from fcgrasp.model.polygon import Polygon

from .shapes import random_polygon


def test_edge_numbering_follows_input_in_either_orientation():
    ccw = Polygon([[0, 0], [2, 0], [2, 1], [0, 1]])
    cw = Polygon([[0, 0], [0, 1], [2, 1], [2, 0]])
    assert ccw.normals.round(12).tolist() == [[0, -1], [1, 0], [0, 1], [-1, 0]]
    assert cw.normals.round(12).tolist() == [[-1, 0], [0, 1], [1, 0], [0, -1]]
    assert np.allclose(cw.starts, [[0, 0], [0, 1], [2, 1], [2, 0]])
    assert ccw.lengths.tolist() == [2, 1, 2, 1]
    assert ccw.area == cw.area == 2.0


def test_hole_edges_numbered_after_outer_and_normals_point_into_hole():
    hole = [[1, 1], [2, 1], [2, 2], [1, 2]]
    for h in (hole, hole[::-1]):
        p = Polygon([[0, 0], [3, 0], [3, 3], [0, 3]], holes=[h])
        assert p.n_edges == 8 and p.rings.tolist() == [0] * 4 + [1] * 4
        mid = (p.starts[4:] + p.ends[4:]) / 2
        inside_hole = mid + 0.1 * p.normals[4:]
        assert np.all(np.abs(inside_hole - 1.5).max(axis=1) < 0.5)


def test_outward_normals_point_out_of_the_part():
    rng = np.random.default_rng(0)
    for _ in range(200):
        p = random_polygon(rng)
        mid = (p.starts + p.ends) / 2
        eps = 1e-6 * p.size
        out = p.contains(mid + eps * p.normals)
        inn = p.contains(mid - eps * p.normals)
        assert not out.any() and inn.all()


def test_repeated_closing_vertex_is_dropped():
    p = Polygon([[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]])
    assert p.n_edges == 4


def test_duplicate_vertex_keeps_numbering_as_zero_length_edge():
    p = Polygon([[0, 0], [1, 0], [1, 0], [1, 1], [0, 1]])
    assert p.n_edges == 5
    assert p.usable.tolist() == [True, False, True, True, True]
    assert np.allclose(p.normals[2], [1, 0])
    with pytest.raises(ValueError, match="zero-length"):
        p.check_edges([1])


def test_collinear_edges_are_kept():
    p = Polygon([[0, 0], [1, 0], [2, 0], [2, 1], [0, 1]])
    assert p.n_edges == 5
    assert np.allclose(p.normals[0], p.normals[1])


def test_convex_vertices():
    p = Polygon([[0, 0], [2, 0], [2, 2], [1, 1], [0, 2]])
    # vertex at the end of edge i
    assert p.convex_vertices().tolist() == [True, True, False, True, True]
    q = Polygon([[0, 0], [2, 0], [2, 2], [1, 1], [0, 2]][::-1])
    assert q.convex_vertices().tolist() == [False, True, True, True, True]


@pytest.mark.parametrize("verts, holes, match", [
    ([[0, 0], [1, 1], [1, 0], [0, 1]], (), r"edges 0 and 2 intersect"),
    ([[0, 0], [1, 0], [2, 0]], (), "zero area"),
    ([[0, 0], [1, 0]], (), "at least 3 distinct"),
    ([[0, 0], [1, 0], [1, 0], [0, 0]], (), "at least 3 distinct"),
    ([[0, 0], [1, 0], [np.nan, 1]], (), "non-finite coordinate at vertex 2"),
    ([[0, 0], [1, 0], [np.inf, 1]], (), "vertex 2"),
    ([[0, 0], [1, 0], [1, 1]], ([[[5, 5], [6, 5], [6, 6]]]), "holes.0. is not inside"),
    ([[0, 0], [4, 0], [4, 4], [0, 4]], ([[[1, 1], [2, 1], [2, 2]], [[1.5, 1.2], [3, 1.2], [3, 3]]]),
     "intersect"),
    ([[0, 0], [1, 0, 3], [1, 1]], (), "shape"),
    ([[[0, 0], [1, 0], [1, 1]]], (), "shape"),
    ([], (), "shape"),
])
def test_invalid_outlines_say_what_and_where(verts, holes, match):
    with pytest.raises(ValueError, match=match):
        Polygon(verts, holes)


def test_non_numeric_vertices_type_error():
    with pytest.raises((TypeError, ValueError), match="vertices"):
        Polygon([[0, 0], ["a", 0], [1, 1]])
    with pytest.raises(TypeError, match="vertices"):
        Polygon("0,0 1,0 1,1")


def test_edge_accessors():
    p = Polygon([[0, 0], [2, 0], [2, 1], [0, 1]])
    e = p.edge(1)
    assert e.length == 1 and np.allclose(e.normal, [1, 0])
    assert np.allclose(e.point_at(0.5), [2, 0.5])
    with pytest.raises(ValueError, match="edge index"):
        p.edge(4)
    with pytest.raises(TypeError):
        p.edge(1.5)


def test_a_shapely_polygon_or_geo_interface_is_a_part():
    """``fc.plan(shapely.box(0, 0, 10, 5))`` said "polygon must be a Polygon, got Polygon"."""
    import shapely

    import fcgrasp as fc
    from fcgrasp.model.polygon import check_polygon

    box = shapely.box(0, 0, 10, 5).difference(shapely.box(4, 2, 6, 3))

    class Feature:
        __geo_interface__ = shapely.geometry.mapping(box)

    for value in (box, Feature()):
        p = check_polygon(value)
        assert p.n_edges == 8 and len(p.holes) == 1
        assert abs(p.area - box.area) < 1e-12
        assert [q.edges for q in fc.plan(value, mu=0.3, top=2)] == \
            [q.edges for q in fc.plan(p, mu=0.3, top=2)]
    for bad in ("x", shapely.Point(0, 0), None):
        with pytest.raises(TypeError, match="polygon must be a fcgrasp Polygon"):
            fc.plan(bad)


def _crossing_by_every_pair(rings, offsets):
    """The first pair of edges that intersect other than at a shared vertex, by
    intersecting every pair of edges that intersect (shapely's predicate): the
    reference of the outline check, which leaves out the neighbours that turn."""
    import shapely

    p0, p1, edge, ring_of = [], [], [], []
    for r, (ring, off) in enumerate(zip(rings, offsets, strict=True)):
        nxt = np.roll(ring, -1, axis=0)
        keep = np.flatnonzero(np.any(ring != nxt, axis=1))
        p0 += list(ring[keep])
        p1 += list(nxt[keep])
        edge += list(off + keep)
        ring_of += [r] * keep.size
    p0, p1, edge, ring_of = map(np.asarray, (p0, p1, edge, ring_of))
    segs = shapely.linestrings(np.stack([p0, p1], axis=1))
    for i in range(len(segs)):
        for j in range(i + 1, len(segs)):
            if not shapely.intersects(segs[i], segs[j]):
                continue
            inter = shapely.intersection(segs[i], segs[j])
            if shapely.get_type_id(inter) == 0:
                xy = shapely.get_coordinates(inter)[0]
                ends_i = [tuple(p0[i]), tuple(p1[i])]
                ends_j = [tuple(p0[j]), tuple(p1[j])]
                if ring_of[i] == ring_of[j]:
                    if tuple(xy) in ends_i and tuple(xy) in ends_j:
                        continue
                elif tuple(xy) in ends_i or tuple(xy) in ends_j:
                    continue
            return int(edge[i]), int(edge[j])
    return None


def _awkward_rings(rng):
    """Rings with spikes (an edge folding back on its neighbour), collinear and repeated
    vertices, self-touching vertices, bow ties and slight turns, and a hole."""
    n = int(rng.integers(4, 14))
    a = np.sort(rng.uniform(0, 2 * np.pi, n))
    ring = np.c_[np.cos(a), np.sin(a)] * rng.uniform(0.5, 1.5, (n, 1))
    ring = np.round(ring * 8) / 8 if rng.random() < 0.5 else ring
    kind = rng.integers(6)
    k = int(rng.integers(n))
    if kind == 0:                                  # a spike back along the edge
        ring = np.insert(ring, k + 1, ring[k] + 0.5 * (ring[k] - ring[(k - 1) % n]), axis=0)
        ring = np.insert(ring, k + 2, ring[k], axis=0)
    elif kind == 1:                                # a repeated and a collinear vertex
        ring = np.insert(ring, k, ring[k], axis=0)
        m = 0.5 * (ring[0] + ring[-1])
        ring = np.vstack([ring, m])
    elif kind == 2:                                # two vertices swapped: a bow tie
        j = (k + 1) % n
        ring[[k, j]] = ring[[j, k]]
    elif kind == 3:                                # a turn of a hair
        m = 0.5 * (ring[k] + ring[(k + 1) % n])
        d = ring[(k + 1) % n] - ring[k]
        ring = np.insert(ring, k + 1, m + 1e-14 * np.array([-d[1], d[0]]), axis=0)
    elif kind == 4:                                # a vertex touching another edge
        j = (k + n // 2) % n
        ring = np.insert(ring, k + 1, 0.5 * (ring[j] + ring[(j + 1) % n]), axis=0)
    holes = [0.2 * ring[::-1][:max(3, len(ring) // 2)]] if rng.random() < 0.3 else []
    return ring, holes


def test_the_outline_check_leaves_out_only_neighbours_that_meet_at_their_vertex():
    """The simple-outline check (neighbours that turn not intersected) finds the first
    crossing pair that intersecting every intersecting pair finds, on 600 seeded rings
    with spikes, repeated, collinear and touching vertices, bow ties and hair turns."""
    from fcgrasp.model.polygon import _crossing_edges

    rng = np.random.default_rng(11)
    crossing = 0
    for _ in range(600):
        ring, holes = _awkward_rings(rng)
        rings = [ring, *holes]
        offsets = list(np.cumsum([0] + [len(r) for r in rings[:-1]]))
        got = _crossing_edges(rings, offsets)
        want = _crossing_by_every_pair(rings, offsets)
        assert (got[:2] if got else None) == want, (ring.tolist(), holes)
        crossing += want is not None
    assert 100 < crossing < 500, crossing
