"""Readers (fcgrasp.io.parts): part files of every format and contact files."""

from __future__ import annotations

import json

import numpy as np
import pytest

import fcgrasp as fc
from fcgrasp.io.parts import DEMO_PARTS, read_contacts

RING = [[0, 0], [40, -6], [62, 18], [45, 44], [8, 38]]


@pytest.mark.parametrize("name", list(DEMO_PARTS))
def test_demo_parts(name):
    part = fc.read_part(f"demo:{name}")
    assert part.area > 0


@pytest.mark.parametrize("suffix, text", [
    (".json", json.dumps({"vertices": RING})),
    (".geojson", json.dumps({"type": "Polygon", "coordinates": [RING + [RING[0]]]})),
    (".wkt", "POLYGON ((" + ", ".join(f"{x} {y}" for x, y in RING + [RING[0]]) + "))"),
])
def test_text_formats_read_the_same_ring(tmp_path, suffix, text):
    f = tmp_path / f"part{suffix}"
    f.write_text(text)
    np.testing.assert_allclose(fc.read_part(f).vertices, RING)


def test_read_contacts(tmp_path):
    part = fc.Polygon(RING)
    f = tmp_path / "c.json"
    f.write_text(json.dumps({"contacts": [{"point": [20, -3], "mu": 0.5},
                                          {"point": [26.5, 41], "mu": 0.5}],
                             "gravity": {}}))
    contacts, described = read_contacts(f, part)
    assert len(contacts) == 3 and described[-1]["type"] == "gravity"
    assert described[0]["edge"] == 0


def test_read_contacts_soft_finger(tmp_path):
    part = fc.Polygon(RING)
    f = tmp_path / "c.json"
    f.write_text(json.dumps({"contacts": [{"type": "soft", "vertex": 2, "mu": 0.3}]}))
    contacts, _ = read_contacts(f, part)
    assert isinstance(contacts[0], fc.SoftFinger)


def test_a_number_is_an_index_before_the_layer_named_0(tmp_path):
    """Every CAD file's default layer is named "0": ``--part 0`` is the part at index 0,
    and ``id:0`` the largest part on that layer."""
    import ezdxf

    from fcgrasp.io.parts import list_parts, load_part

    doc = ezdxf.new()
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (4, 0), (4, 4), (0, 4)], close=True)
    msp.add_lwpolyline([(10, 0), (40, 0), (40, 20), (10, 20)], close=True)
    path = tmp_path / "two.dxf"
    doc.saveas(path)
    parts = list_parts(str(path))
    assert [p.layer for p in parts] == ["0", "0"]
    small = min(range(2), key=lambda k: parts[k].area)
    assert load_part(str(path), str(small)).index == small
    assert load_part(str(path), small).index == small
    assert load_part(str(path), "id:0").area == max(p.area for p in parts)
