"""The one angle wrap (fcgrasp.core._angles), tested at +-10 pi and +-eps as
pytransform3d tests its norm_angle, and as the kernels compile it."""

from __future__ import annotations

import numpy as np
import pytest

from fcgrasp.core import kernels
from fcgrasp.core._angles import wrap, wrap_floor, wrap_positive

EPS = np.finfo(float).eps
SPECIAL = np.array([0.0, EPS, -EPS, np.pi, -np.pi, np.pi - EPS, -np.pi + EPS, 2 * np.pi,
                    -2 * np.pi, 10 * np.pi, -10 * np.pi, 10 * np.pi + 1e-9, 1e6, -1e6])


@pytest.mark.parametrize(("fn", "low"), [(wrap, -np.pi), (wrap_positive, 0.0),
                                         (wrap_floor, -np.pi)])
def test_a_wrap_is_in_its_range_and_congruent(fn, low):
    rng = np.random.default_rng(0)
    angles = np.concatenate([SPECIAL, rng.uniform(-50, 50, 10_000)])
    out = fn(angles)
    # in [low, low + 2 pi]: the upper end only by rounding of an angle just below low
    assert np.all(out >= low) and np.all(out <= low + 2 * np.pi)
    turns = (angles - out) / (2 * np.pi)
    assert np.allclose(turns, np.round(turns), atol=1e-9 * (1 + np.abs(angles)))
    inside = (angles >= low) & (angles < low + 2 * np.pi)
    # unchanged, up to the rounding of adding and removing pi (wrap's '%')
    assert np.allclose(out[inside], angles[inside], rtol=0, atol=4 * np.spacing(np.pi))
    for a, o in zip(SPECIAL, out[:len(SPECIAL)], strict=True):
        assert fn(float(a)) == o          # a float, one at a time: the same numbers


def test_the_ends_of_the_range():
    for fn in (wrap, wrap_floor):
        assert fn(np.pi) == -np.pi and fn(-np.pi) == -np.pi
        assert abs(fn(10 * np.pi)) < 1e-13 and abs(fn(-10 * np.pi)) < 1e-13
    assert wrap_positive(2 * np.pi) == 0.0 and wrap_positive(0.0) == 0.0


def test_the_kernels_wrap_is_the_floor_one_and_agrees_to_an_ulp():
    assert kernels._wrap is wrap_floor
    a = np.random.default_rng(1).uniform(-40, 40, 100_000)
    d = np.abs(wrap_floor(a) - wrap(a))
    # equal to within a few ulps of the angle, or a whole turn apart right at -pi
    assert np.all((d <= 8 * np.spacing(np.abs(a) + np.pi)) |
                  (np.abs(d - 2 * np.pi) <= 8 * np.spacing(np.abs(a) + np.pi)))
