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


def _enumerated_radius(points, tol=1e-12):
    """The previous ball_radius for every number of points (the reference of its qhull
    path): every plane through three points with all the others on one side."""
    from itertools import combinations

    from fcgrasp.core._geom import unique_rows
    from fcgrasp.core.tolerances import DEGENERATE_TOL, RANK_RTOL, TINY

    P = unique_rows(np.asarray(points, float))
    if len(P) < 4:
        return 0.0
    scale = max(float(np.max(np.abs(P))), TINY)
    Q = P / scale
    if np.linalg.matrix_rank(Q - Q.mean(axis=0), tol=RANK_RTOL) < 3:
        return 0.0
    t = np.array(list(combinations(range(len(Q)), 3)))
    a, b, c = Q[t[:, 0]], Q[t[:, 1]], Q[t[:, 2]]
    n = np.cross(b - a, c - a)
    nn = np.linalg.norm(n, axis=1)
    keep = nn > RANK_RTOL
    a, n = a[keep], n[keep] / nn[keep, None]
    side = np.einsum("tkd,td->tk", Q[None, :, :] - a[:, None, :], n)
    below = np.all(side <= DEGENERATE_TOL, axis=1)
    above = np.all(side >= -DEGENERATE_TOL, axis=1)
    n = np.where(above[:, None] & ~below[:, None], -n, n)
    support = below | above
    if not support.any():
        return 0.0
    return float(max(0.0, np.einsum("ij,ij->i", a[support], n[support]).min())) * scale


def _qhull_radius(pts):
    """The radius from qhull's facets (scipy): the reference of the enumeration."""
    from scipy.spatial import ConvexHull

    P = np.unique(np.asarray(pts, float), axis=0)
    scale = float(np.abs(P).max())
    eq = ConvexHull(P / scale).equations
    return max(0.0, float((-eq[:, 3]).min())) * scale


def _clouds(k, rng):
    """Random clouds of ``k`` points, clouds on a sphere (every point a vertex), the
    origin near a facet or outside, repeated points and tiny and huge scales."""
    for i in range(60):
        pts = rng.normal(size=(k, 3))
        if i % 3 == 1:
            pts /= np.linalg.norm(pts, axis=1)[:, None]
        shift = rng.normal(scale=[0.3, 1.0, 3.0][i % 3], size=3)
        pts = (pts + shift) * 10.0 ** rng.uniform(-6, 6)
        if i % 5 == 0:
            pts = np.vstack([pts, pts[:3]])
        yield pts


#: Cloud sizes on both sides of HULL_POINTS.
SIZES = (13, 27, 33, 40)
CLOUDS = (*SIZES, *(pytest.param(k, marks=pytest.mark.slow) for k in (16, 32, 64)))


@pytest.mark.parametrize("k", CLOUDS)
def test_ball_radius_is_the_other_methods(k, rng):
    """Up to HULL_POINTS points (four frictionless fingers' 16 L-infinity sums, three
    fingers with friction's 27) the facets are enumerated without scipy: the same radius
    as qhull's facets; from HULL_POINTS points they come from qhull: the same radius as
    every plane through three points.  On random clouds, clouds on a sphere (every point
    a vertex), the origin near a facet or outside, repeated points and tiny scales."""
    from fcgrasp.model.quality import HULL_POINTS

    assert min(SIZES) <= HULL_POINTS < max(SIZES)          # both ways are tested
    reference = _qhull_radius if k <= HULL_POINTS else _enumerated_radius
    inside = 0
    for pts in _clouds(k, rng):
        want = reference(pts)
        assert ball_radius(pts) == pytest.approx(want, rel=1e-9, abs=1e-12 * np.abs(pts).max())
        inside += want > 0
    assert 10 <= inside < 60


def test_ball_radius_degenerate():
    flat = np.array([[1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0]], float)
    assert ball_radius(flat) == 0.0
    assert ball_radius(np.eye(3)) == 0.0
    cube = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    assert ball_radius(cube * 1e-80) == pytest.approx(1e-80)
    assert ball_radius(np.vstack([cube, cube])) == pytest.approx(1.0)
