"""Build ``demo:mug``'s mesh, ``src/fcgrasp/spatial/data/mug.npz``: a cup (outer radius
40 mm, wall 4 mm, height 90 mm, bottom 6 mm, 48 sections) with a handle (half a ring of
an elliptic tube, 8 x 5 mm, of radius 26 mm, on the +x side at mid height), joined by
manifold3d's exact boolean union (a tool for this script only, not a dependency of
fcgrasp: ``pip install manifold3d``).  The package reads the vertices and triangles
saved here, so ``demo:mug`` needs nothing more than ``demo:box``.

    .venv/bin/python docs/make_mug.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

OUT = Path(__file__).resolve().parents[1] / "src" / "fcgrasp" / "spatial" / "data" / "mug.npz"
SECTIONS = 48


def mug_mesh() -> tuple[np.ndarray, np.ndarray]:
    """Vertices (n, 3) and triangles (m, 3) of the mug, merged and watertight."""
    import manifold3d as m3
    import trimesh

    cup = m3.Manifold.cylinder(90.0, 40.0, 40.0, SECTIONS) - \
        m3.Manifold.cylinder(90.0, 36.0, 36.0, SECTIONS).translate((0.0, 0.0, 6.0))
    tube = m3.CrossSection.circle(5.0, 24).scale((1.6, 1.0)).translate((26.0, 0.0))
    ring = m3.Manifold.revolve(tube, SECTIONS, 360.0).rotate((90.0, 0.0, 0.0)) \
        .translate((38.0, 0.0, 45.0))
    handle = ring - m3.Manifold.cylinder(90.0, 39.0, 39.0, SECTIONS)
    mesh = (cup + handle).to_mesh64()
    merged = trimesh.Trimesh(np.asarray(mesh.vert_properties)[:, :3],
                             np.asarray(mesh.tri_verts), process=True)
    assert merged.is_watertight and merged.is_winding_consistent and merged.volume > 0
    return np.asarray(merged.vertices, float), np.asarray(merged.faces, np.int32)


def main() -> None:
    vertices, faces = mug_mesh()
    OUT.parent.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(OUT, vertices=vertices, faces=faces)
    print(f"wrote {OUT}: {len(vertices)} vertices, {len(faces)} triangles")


if __name__ == "__main__":
    main()
