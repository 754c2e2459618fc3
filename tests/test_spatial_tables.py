"""A solid's facets and pieces table, made in batches (groups of coplanar triangles
united at once, the pieces of one vertex count read at once), are those made one at a
time, bit for bit: the corpus's CAD meshes, tori (50,000 quads at 100,000 triangles:
two coplanar triangles each), subdivided boxes (large coplanar groups) and extruded
random outlines (non-convex caps cut into pieces)."""

from __future__ import annotations

from dataclasses import fields
from pathlib import Path

import numpy as np
import pytest

from fcgrasp.spatial import _pieces
from fcgrasp.spatial import solid as solids
from fcgrasp.spatial.solid import solid_from_mesh

trimesh = pytest.importorskip("trimesh")
shapely = pytest.importorskip("shapely")

CORPUS = Path(__file__).resolve().parents[1] / "benchmarks" / "corpus" / "meshes"


def _same(a, b):
    if isinstance(a, np.ndarray):
        return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()
    if isinstance(a, list | tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, dict):
        return True                     # the tables' caches, empty when made
    if hasattr(a, "geom_type"):
        return shapely.to_wkb(a) == shapely.to_wkb(b)
    return a == b


def _mesh(seed):
    rng = np.random.default_rng(seed)
    kind = seed % 4
    if kind == 0:
        return trimesh.creation.torus(major_radius=float(rng.uniform(20, 50)),
                                      minor_radius=float(rng.uniform(3, 15)),
                                      major_sections=int(rng.integers(8, 60)),
                                      minor_sections=int(rng.integers(6, 30)))
    if kind == 1:
        mesh = trimesh.creation.box(rng.uniform(5, 40, 3))
        for _ in range(int(rng.integers(1, 4))):
            mesh = mesh.subdivide()
        return mesh
    if kind == 2:
        n = int(rng.integers(5, 14))
        ang = np.sort(rng.uniform(0, 2 * np.pi, n))
        pts = np.c_[np.cos(ang), np.sin(ang)] * rng.uniform(5, 20, n)[:, None]
        return trimesh.creation.extrude_polygon(shapely.Polygon(pts).buffer(0),
                                                float(rng.uniform(2, 20)))
    return trimesh.creation.cylinder(radius=float(rng.uniform(2, 20)),
                                     height=float(rng.uniform(3, 30)),
                                     sections=int(rng.integers(5, 40)))


@pytest.mark.parametrize("seed", [*range(4), *(pytest.param(s, marks=pytest.mark.slow)
                                              for s in range(4, 80))])
def test_batched_facets_and_pieces_are_those_made_one_at_a_time(seed):
    solid = solid_from_mesh(_mesh(seed), "mm", f"mesh{seed}")
    _check(solid)


@pytest.mark.parametrize("name", ["angle_block.STL", "plate_holes.STL",
                                  pytest.param("fandisk.obj", marks=pytest.mark.slow),
                                  pytest.param("octagonal_pocket.ply", marks=pytest.mark.slow)])
def test_batched_tables_of_the_corpus_meshes(name):
    from fcgrasp.io.meshes import read_solid

    _check(read_solid(str(CORPUS / name)))


def _check(solid):
    batched, each = solids._facets(solid.mesh), solids._facets(solid.mesh, batched=False)
    assert len(batched) == len(each)
    for f, g in zip(batched, each, strict=True):
        assert all(_same(getattr(f, x.name), getattr(g, x.name)) for x in fields(f)), f.index
    a, b = _pieces._piece_table(solid), _pieces._piece_table(solid, batched=False)
    bad = [x.name for x in fields(a) if not _same(getattr(a, x.name), getattr(b, x.name))]
    assert not bad, bad
