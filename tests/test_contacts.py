"""Figure 4 as the paper's text describes it (section 3.1)."""

import numpy as np
import pytest

import fcgrasp as fc


def _has_line(cone, twist):
    """The twist is a free (bidirectional) motion of the cone."""
    return cone.contains(twist) and cone.contains(-np.asarray(twist))


def test_frictionless_point_figure_4a():
    c = fc.FrictionlessPoint([2.0, 1.0], [0.0, 1.0])
    t = c.twist_cone()
    assert t.space == "twist"
    assert len(t.lines) == 2 and len(t.rays) == 1
    assert _has_line(t, fc.twist_about_point([2.0, 1.0]))          # free rotation about P
    assert _has_line(t, fc.twist_translation([1.0, 0.0]))           # free slide along the edge
    down = fc.twist_translation([0.0, -1.0])
    assert t.contains(down) and not t.contains(-down)                # unisense lift-off
    assert fc.classify_twist_wrench(down, c.wrenches[0]) == fc.REPELLING


def test_friction_point_figure_4b():
    mu = 0.4
    c = fc.FrictionPoint([0.5, 0.0], [0.0, 1.0], mu)
    t = c.twist_cone()
    assert len(t.lines) == 1 and len(t.rays) == 2
    assert _has_line(t, fc.twist_about_point([0.5, 0.0]))
    assert not t.contains(fc.twist_translation([1.0, 0.0]))         # no free slide
    # each unisense translation is reciprocal to one cone edge and repelling to the other
    for ray in t.rays:
        # reduce the ray modulo the free rotation about P to a pure translation
        tr = ray - ray[0] * fc.twist_about_point([0.5, 0.0])
        assert abs(tr[0]) < 1e-12
        kinds = sorted(str(k) for k in fc.classify_twist_wrench(tr, c.wrenches))
        assert kinds == [fc.RECIPROCAL, fc.REPELLING]


def test_frictionless_edge_figure_4c():
    a, b = np.array([-1.0, 0.0]), np.array([1.0, 0.0])
    c = fc.FrictionlessEdge(a, b, [0.0, 1.0])
    t = c.twist_cone()
    assert len(t.lines) == 1 and len(t.rays) == 2
    assert _has_line(t, fc.twist_translation([1.0, 0.0]))           # free slide
    cw_a, ccw_b = fc.twist_about_point(a, -1.0), fc.twist_about_point(b, 1.0)
    assert t.contains(cw_a) and t.contains(ccw_b)
    assert not t.contains(fc.twist_about_point(a, 1.0))
    assert not t.contains(fc.twist_about_point(b, -1.0))
    # each rotation breaks contact at the other end
    assert fc.classify_twist_wrench(cw_a, c.wrenches[1]) == fc.REPELLING
    assert fc.classify_twist_wrench(ccw_b, c.wrenches[0]) == fc.REPELLING
    # the downward translation is the sum of the two rotations, not a minimal generator
    assert t.contains(fc.twist_translation([0.0, -1.0]))
    assert (t + fc.Cone([fc.twist_translation([0.0, -1.0])], "twist")) == t


def test_friction_edge_figure_4d():
    a, b = np.array([-1.0, 0.0]), np.array([1.0, 0.0])
    c = fc.FrictionEdge(a, b, [0.0, 1.0], 0.3)
    t = c.twist_cone()
    assert len(t.lines) == 0                                         # no free slide any more
    assert not t.contains(fc.twist_translation([1.0, 0.0]))
    assert t.contains(fc.twist_about_point(a, -1.0)) and t.contains(fc.twist_about_point(b, 1.0))
    assert not t.contains(fc.twist_about_point(a, 1.0))


def test_soft_finger_on_edge_is_friction_edge():
    s = fc.SoftFinger([-1, 0], [1, 0], [0, 1], 0.3)
    e = fc.FrictionEdge([-1, 0], [1, 0], [0, 1], 0.3)
    assert s.wrench_cone() == e.wrench_cone()


def _corner(interior_deg, mu):
    """Soft finger around a convex corner at the origin: side 1 is the top edge from
    (-1, 0), side 2 leaves the corner turning clockwise by the exterior angle."""
    turn = np.radians(180.0 - interior_deg)
    d2 = np.array([np.cos(-turn), np.sin(-turn)])
    n2 = np.array([-d2[1], d2[0]])          # left normal of the clockwise boundary: outward
    c = fc.SoftFinger.corner([-1, 0], [0, 0], d2, [0, 1], n2, mu)
    return c, d2, n2


def test_soft_finger_corner_figure_4e_six_wrenches():
    c, _, _ = _corner(135.0, 0.3)
    assert c.wrenches.shape == (8, 3)
    m = c.wrench_cone().minimal()
    assert len(m.rays) == 6 and len(m.lines) == 0
    assert m == c.wrench_cone()
    # the two inner forces at the corner are the redundant ones
    kept = {tuple(np.round(r, 9)) for r in m.rays}
    unit = c.wrenches / np.linalg.norm(c.wrenches, axis=1, keepdims=True)
    dropped = [i for i, w in enumerate(unit) if tuple(np.round(w, 9)) not in kept]
    assert sorted(dropped) == [3, 4]


def test_soft_finger_corner_no_rotation_about_its_ends():
    # true when the exterior angle plus the friction angle exceeds 90 degrees
    c, d2, _ = _corner(90.0, 0.3)
    t = c.twist_cone()
    for omega in (-1.0, 1.0):
        assert not t.contains(fc.twist_about_point([-1, 0], omega))
        assert not t.contains(fc.twist_about_point(d2, omega))


def test_soft_finger_corner_slides_down_unless_sharp_or_rough():
    # the slide along the bisector is repelling to every wrench unless angle < 2 atan(mu)
    down = lambda d2: -(np.array([0.0, 1.0]) + np.array([-d2[1], d2[0]]))  # noqa: E731
    c, d2, _ = _corner(135.0, 0.3)
    assert c.twist_cone().contains(fc.twist_translation(down(d2)))
    c, d2, _ = _corner(135.0, 3.0)          # large friction cone
    assert not c.twist_cone().contains(fc.twist_translation(down(d2)))
    c, d2, _ = _corner(25.0, 0.3)           # corner angle below twice the friction angle
    assert not c.twist_cone().contains(fc.twist_translation(down(d2)))


def test_gravity_is_frictionless_point_at_center():
    g = fc.Gravity([1.0, 2.0])
    assert np.allclose(g.wrenches, fc.FrictionlessPoint([1.0, 2.0], [0, 1]).wrenches)
    g2 = fc.Gravity([1.0, 2.0], direction=(3.0, 0.0))
    assert np.allclose(g2.forces, [[1.0, 0.0]])


def test_box_on_table_with_gravity_is_immobile_in_plane():
    # figure 2 in the plane: a box on a frictionless table, held down by gravity
    box = fc.Grasp([fc.FrictionlessEdge([0, 0], [2, 0], [0, -1]), fc.Gravity([1, 0.5])])
    free = box.total_freedom()
    assert _has_line(free, fc.twist_translation([1, 0]))            # slides freely
    assert not free.contains(fc.twist_translation([0, 1]))           # cannot float up
    assert not box.is_force_closure()


@pytest.mark.parametrize("make, match", [
    (lambda: fc.FrictionlessPoint([0, 0], [0, 0]), "normal"),
    (lambda: fc.FrictionPoint([0, 0], [0, 1], -0.1), "mu"),
    (lambda: fc.FrictionPoint([0, np.inf], [0, 1], 0.1), "point"),
    (lambda: fc.FrictionlessEdge([0, 0], [0, 0], [0, 1]), "distinct"),
    (lambda: fc.FrictionlessEdge([0, 0], [1, 0], [1, 1]), "perpendicular"),
    (lambda: fc.FrictionEdge([0, 0], [1, 0], [0, 1], float("nan")), "mu"),
    (lambda: fc.Gravity([0, 0], direction=[0, 0]), "direction"),
    (lambda: fc.FrictionPoint([0, 0, 0], [0, 1], 0.1), "point"),
])
def test_bad_contacts_raise_value_error_naming_argument(make, match):
    with pytest.raises(ValueError, match=match):
        make()


def test_mu_must_be_a_number():
    with pytest.raises(TypeError, match="mu"):
        fc.FrictionPoint([0, 0], [0, 1], "0.3")
