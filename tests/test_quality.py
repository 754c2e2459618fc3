"""Quality measures (section 8.1): the Ferrari-Canny hull radius against scipy's qhull."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import ConvexHull, QhullError

from fcgrasp.model.quality import ball_radius


def qhull_radius(points):
    try:
        hull = ConvexHull(points)
    except (QhullError, ValueError):
        return 0.0
    return max(0.0, float((-hull.equations[:, -1]).min()))


@pytest.mark.parametrize("k", [4, 5, 9, 16, 27])
def test_ball_radius_matches_qhull(k, rng):
    for _ in range(200):
        pts = rng.normal(size=(k, 3)) + rng.normal(scale=0.5, size=3)
        assert ball_radius(pts) == pytest.approx(qhull_radius(pts), rel=1e-9, abs=1e-12)


def test_ball_radius_degenerate():
    flat = np.array([[1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0]], float)
    assert ball_radius(flat) == 0.0
    assert ball_radius(np.eye(3)) == 0.0
    cube = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    assert ball_radius(cube * 1e-80) == pytest.approx(1e-80)
    assert ball_radius(np.vstack([cube, cube])) == pytest.approx(1.0)
