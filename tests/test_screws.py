import numpy as np
import pytest

import fcgrasp as fc


def test_wrench_torque_is_r_cross_f():
    w = fc.wrench_from_force([3.0, 4.0], [1.0, 2.0])
    assert w.tolist() == [3.0, 4.0, 1.0 * 4.0 - 2.0 * 3.0]


def test_wrench_batches_broadcast():
    f = np.ones((5, 7, 2))
    p = np.zeros((7, 2))
    assert fc.wrench_from_force(f, p).shape == (5, 7, 3)


def test_twist_about_point_moves_center_not():
    rng = np.random.default_rng(1)
    c = rng.normal(size=(100, 2))
    t = fc.twist_about_point(c, omega=rng.normal(size=100))
    assert np.allclose(fc.velocity_at(t, c), 0.0)
    assert np.allclose(fc.rotation_center(t), c)


def test_virtual_work_matches_definition_and_transpose():
    rng = np.random.default_rng(2)
    w, t = rng.normal(size=(2, 1000, 3))
    ref = w[:, 0] * t[:, 1] + w[:, 1] * t[:, 2] + w[:, 2] * t[:, 0]
    assert np.allclose(fc.virtual_work(w, t), ref)
    assert np.allclose(np.sum(w * fc.twist_transpose(t), axis=1), ref)


def test_work_of_force_against_rotation_is_force_times_point_velocity():
    # the work of a force through p against any twist is f . v(p): eq. 3 and 10 agree
    rng = np.random.default_rng(3)
    f, p = rng.normal(size=(2, 500, 2))
    t = rng.normal(size=(500, 3))
    lhs = fc.virtual_work(fc.wrench_from_force(f, p), t)
    rhs = np.sum(f * fc.velocity_at(t, p), axis=1)
    assert np.allclose(lhs, rhs)


def test_classify_definition_2_2():
    push_down = fc.wrench_from_force([0, -1], [0, 0])
    assert fc.classify_twist_wrench(fc.twist_translation([0, -1]), push_down) == fc.REPELLING
    assert fc.classify_twist_wrench(fc.twist_translation([0, 1]), push_down) == fc.CONTRARY
    assert fc.classify_twist_wrench(fc.twist_translation([1, 0]), push_down) == fc.RECIPROCAL
    assert fc.classify_twist_wrench(fc.twist_about_point([0, 0]), push_down) == fc.RECIPROCAL
    # rotation about a point to the right, counter-clockwise: the contact point moves down
    assert fc.classify_twist_wrench(fc.twist_about_point([1, 0], 1.0), push_down) == fc.REPELLING


def test_classify_is_scale_free():
    w = fc.wrench_from_force([0, -1], [0, 0]) * 1e-8
    t = fc.twist_translation([1e-7, 1e6])
    assert fc.classify_twist_wrench(t, w) == fc.CONTRARY


def test_spatial_forms_reduce_to_planar():
    rng = np.random.default_rng(4)
    f2, p2 = rng.normal(size=(2, 200, 2))
    f3 = np.column_stack([f2, np.zeros(200)])
    p3 = np.column_stack([p2, np.zeros(200)])
    ws = fc.spatial_wrench_from_force(f3, p3)
    wp = fc.wrench_from_force(f2, p2)
    assert np.allclose(ws[:, [0, 1, 5]], wp)
    assert np.allclose(ws[:, [2, 3, 4]], 0.0)
    c = rng.normal(size=(200, 2))
    ts = fc.spatial_twist_about_axis([0, 0, 1], np.column_stack([c, np.zeros(200)]))
    tp = fc.twist_about_point(c)
    assert np.allclose(ts[:, [2, 3, 4]], tp)
    assert np.allclose(fc.spatial_virtual_work(ws, ts), fc.virtual_work(wp, tp))


def test_spatial_transpose_and_work():
    rng = np.random.default_rng(5)
    w, t = rng.normal(size=(2, 50, 6))
    assert np.allclose(fc.spatial_virtual_work(w, t), np.sum(w * fc.spatial_transpose(t), axis=1))
    assert np.allclose(fc.spatial_transpose(fc.spatial_transpose(t)), t)
    v = rng.normal(size=(50, 3))
    assert np.allclose(fc.spatial_twist_translation(v)[:, 3:], v)


@pytest.mark.parametrize("bad, exc", [
    ([np.nan, 1.0], ValueError), ([1.0, 2.0, 3.0], ValueError), ("ab", TypeError),
    ([[1, 2], ["x", 3]], (TypeError, ValueError)),
])
def test_bad_force_is_named(bad, exc):
    with pytest.raises(exc, match="force"):
        fc.wrench_from_force(bad, [0.0, 0.0])


def test_zero_axis_rejected():
    with pytest.raises(ValueError, match="direction"):
        fc.spatial_twist_about_axis([0, 0, 0], [0, 0, 0])
