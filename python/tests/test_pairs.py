"""Pair queries against constructed truth: a shape placed at a known distance along the
superellipsoid's normal, a halfspace's depth from the support function; conventions and errors."""
import numpy as np
import pytest

import fcl_superellipsoid as fse

from conftest import random_rotation, skew, unit_directions


def frame_with_z(n):
    """A rotation whose third column is the unit vector n."""
    helper = np.array([1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = np.cross(helper, n)
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(n, x), n])


def touching_along(shape, u, gap, half_height):
    """A pose for a shape whose extent along its -z is half_height, with its -z face or tip
    at the support point of u moved out by gap along u."""
    R = frame_with_z(u)
    return (R, shape.support(u) + (gap + half_height) * u)


@pytest.mark.parametrize(
    "other,half_height",
    [(fse.Sphere(0.5), 0.5), (fse.Box(0.4, 0.6, 0.8), 0.4), (fse.Cylinder(0.3, 1.0), 0.5),
     (fse.Capsule(0.3, 1.0), 0.8)],
    ids=["sphere", "box", "cylinder", "capsule"])
def test_separated_distance_and_witnesses_match_the_construction(shape, other, half_height):
    for i, u in enumerate(unit_directions(12, seed=31)):
        gap = 0.05 + 0.3 * i / 12 * shape.size
        pose = touching_along(shape, u, gap, half_height)
        d = fse.distance(shape, None, other, pose)
        assert d.distance == pytest.approx(gap, abs=1e-9 * shape.size)
        np.testing.assert_allclose(d.point1, shape.support(u), atol=1e-7 * shape.size)
        np.testing.assert_allclose(d.normal, u, atol=1e-6)
        np.testing.assert_allclose(d.point2 - d.point1, d.distance * d.normal, atol=1e-9)
        assert fse.collide(shape, None, other, pose) == []


def test_halfspace_depth_is_the_support_function(shape):
    for n in unit_directions(20, seed=32):
        offset = 0.3 * shape.size  # the halfspace {x : n . x <= offset}, before the pose
        expected = float(n @ shape.support(-n)) - offset  # min over the shape of n . x, - offset
        R, t = random_rotation(5), np.array([1.0, -2.0, 0.5])
        world = fse.Halfspace(R @ n, offset + float((R @ n) @ t))
        d = fse.distance(shape, (R, t), world, None)
        assert d.distance == pytest.approx(expected, abs=1e-9 * shape.size)
        np.testing.assert_allclose(d.normal, -(R @ n), atol=1e-9)
        contacts = fse.collide(shape, (R, t), world, None)
        if expected < 0:
            assert len(contacts) == 1
            assert contacts[0].depth == pytest.approx(-expected, abs=1e-9 * shape.size)
            np.testing.assert_allclose(contacts[0].normal, -(R @ n), atol=1e-9)  # into the halfspace


def test_the_order_of_the_shapes_flips_the_normal():
    s = fse.Superellipsoid((1.0, 0.7, 0.5), (0.5, 1.5))
    b = fse.Box(1.0, 1.0, 1.0)
    pose = (np.eye(3), [0.3, 0.2, 0.9])  # overlapping
    d12 = fse.distance(s, None, b, pose)
    d21 = fse.distance(b, pose, s, None)
    assert d12.distance < 0 and d12.distance == pytest.approx(d21.distance, abs=1e-12)
    np.testing.assert_allclose(d12.normal, -d21.normal, atol=1e-9)
    np.testing.assert_allclose(d12.point1 - d12.point2, -d12.distance * d12.normal, atol=1e-9)
    c12, c21 = fse.collide(s, None, b, pose), fse.collide(b, pose, s, None)
    assert len(c12) == len(c21) == 1
    np.testing.assert_allclose(c12[0].normal, -c21[0].normal, atol=1e-9)
    assert c12[0].depth == pytest.approx(-d12.distance, abs=1e-12)


def test_two_superellipsoids_and_a_convex_polytope():
    s = fse.Superellipsoid((1.0, 1.0, 1.0), (1.0, 1.0))
    t = fse.Superellipsoid((0.5, 0.5, 0.5), (1.0, 1.0))
    d = fse.distance(s, None, t, (np.eye(3), [3.0, 0.0, 0.0]))
    assert d.distance == pytest.approx(1.5, abs=1e-12)
    cube = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
    faces = np.array([[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4],
                      [1, 5, 7, 3]])
    convex = fse.Convex(cube * 0.5, faces)
    d = fse.distance(s, None, convex, (np.eye(3), [2.0, 0.0, 0.0]))
    assert d.distance == pytest.approx(0.5, abs=1e-12)
    vertices, triangles = fse.Superellipsoid((0.5, 0.5, 0.5), (1.0, 1.0)).tessellate(100)
    d = fse.distance(s, None, fse.Convex(vertices, triangles), (np.eye(3), [0.0, 0.0, 2.0]))
    assert d.distance == pytest.approx(0.5, abs=1e-3)  # the mesh's poles are on the axis
    tri = fse.Triangle([3.0, -1.0, -1.0], [3.0, 1.0, -1.0], [3.0, 0.0, 1.0])
    assert fse.distance(s, None, tri, None).distance == pytest.approx(2.0, abs=1e-12)
    plane = fse.Plane([0.0, 0.0, 2.0], 1.0)  # z = 0.5: straddled, pushed out the short way
    assert fse.distance(s, None, plane, None).distance == pytest.approx(-0.5, abs=1e-12)


def test_touching_shapes_have_a_normal():
    s = fse.Superellipsoid((1.0, 1.0, 1.0), (1.0, 1.0))
    d = fse.distance(s, None, fse.Halfspace([-1.0, 0.0, 0.0], -1.0), None)
    assert d.distance == pytest.approx(0.0, abs=1e-15)
    assert np.all(np.isfinite(d.normal)) and np.linalg.norm(d.normal) == pytest.approx(1.0)


@pytest.mark.parametrize(
    "make,error,message",
    [
        (lambda: fse.Box(1.0, -1.0, 1.0), ValueError, "Box: y must be finite and > 0, got -1"),
        (lambda: fse.Sphere(float("nan")), ValueError, "Sphere: radius"),
        (lambda: fse.Capsule(1.0, 0.0), ValueError, "Capsule: length"),
        (lambda: fse.Cone(float("inf"), 1.0), ValueError, "Cone: radius"),
        (lambda: fse.Cylinder(0.0, 1.0), ValueError, "Cylinder: radius"),
        (lambda: fse.Ellipsoid(1.0, 1.0, -2.0), ValueError, "Ellipsoid: c"),
        (lambda: fse.Halfspace([0.0, 0.0, 0.0], 1.0), ValueError, "non-zero"),
        (lambda: fse.Plane([0.0, 1.0, 0.0], float("nan")), ValueError, "offset"),
        (lambda: fse.Triangle([0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]), ValueError,
         "expected 3 numbers"),
        (lambda: fse.Convex(np.zeros((3, 3)), np.zeros((4, 3), dtype=int)), ValueError, "N >= 4"),
        (lambda: fse.Convex(np.eye(4, 3), np.array([[0, 1, 9]] * 4)), ValueError,
         r"faces\[0, 2\] = 9 is not a vertex index"),
        (lambda: fse.Convex(np.eye(4, 3), np.zeros((4, 3))), TypeError, "integers"),
    ],
)
def test_bad_shapes_raise(make, error, message):
    with pytest.raises(error, match=message):
        make()


def test_bad_pair_calls_raise():
    s = fse.Superellipsoid((1.0, 1.0, 1.0), (1.0, 1.0))
    with pytest.raises(TypeError, match="one of the two shapes must be a Superellipsoid"):
        fse.distance(fse.Box(1, 1, 1), None, fse.Sphere(1), None)
    with pytest.raises(TypeError):
        fse.distance(s, None, "box", None)
    with pytest.raises(ValueError, match="pose2"):
        fse.distance(s, None, fse.Sphere(1.0), np.ones((4, 4)))
    with pytest.raises(ValueError, match="max_contacts must be >= 1"):
        fse.collide(s, None, fse.Sphere(1.0), None, max_contacts=0)


def test_pair_gradients_of_two_spheres_are_the_closed_form():
    """A round superellipsoid (a sphere of radius r1) and a Sphere of radius r2, apart and
    overlapping: d = |c2 - c1| - r1 - r2, n = (c2 - c1)/|c2 - c1|; a twist (omega, v) of pose k
    moves its witness p_k, so d_pose2 = (p2 x n, n) and d_pose1 = (n x p1, -n); a radius a_i of
    the superellipsoid moves its surface at the witness by n_i^2 (local frame), so
    d_shape1[:3] = -n_local**2."""
    r1, r2 = 0.7, 0.4
    ball = fse.Superellipsoid((r1, r1, r1), (1.0, 1.0))
    rng = np.random.default_rng(53)
    for i, u in enumerate(unit_directions(10, seed=33)):
        R1 = random_rotation(40 + i)
        c1 = rng.normal(size=3)
        reach = (r1 + r2) * (0.6 + 0.9 * i / 10)  # overlapping for the first few
        c2 = c1 + reach * u
        g = fse.distance_gradients(ball, (R1, c1), fse.Sphere(r2), (np.eye(3), c2))
        assert g.distance == pytest.approx(reach - r1 - r2, abs=1e-9)
        np.testing.assert_allclose(g.normal, u, atol=1e-9)
        p1, p2 = c1 + r1 * u, c2 - r2 * u
        np.testing.assert_allclose(g.point1, p1, atol=1e-9)
        np.testing.assert_allclose(g.point2, p2, atol=1e-9)
        np.testing.assert_allclose(g.d_pose2, np.concatenate([np.cross(p2, u), u]), atol=1e-9)
        np.testing.assert_allclose(g.d_pose1, np.concatenate([np.cross(u, p1), -u]), atol=1e-9)
        n_local = R1.T @ u
        np.testing.assert_allclose(g.d_shape1[:3], -n_local**2, atol=1e-8)
        assert np.all(np.isfinite(g.d_shape1))
        assert g.d_shape2 is None
        assert g.differentiable


def test_pair_gradients_follow_the_order_of_the_shapes():
    a = fse.Superellipsoid((1.0, 0.7, 0.5), (0.5, 1.5))
    b = fse.Superellipsoid((0.6, 0.6, 0.9), (1.2, 0.3))
    pose_a = (random_rotation(7), np.array([0.1, 0.2, 0.3]))
    pose_b = (random_rotation(8), np.array([1.2, -0.4, 0.9]))
    ab = fse.distance_gradients(a, pose_a, b, pose_b)
    ba = fse.distance_gradients(b, pose_b, a, pose_a)
    assert ab.distance == pytest.approx(ba.distance, abs=1e-9)
    np.testing.assert_allclose(ab.normal, -ba.normal, atol=1e-7)
    np.testing.assert_allclose(ab.point1, ba.point2, atol=1e-7)
    np.testing.assert_allclose(ab.d_pose1, ba.d_pose2, atol=1e-6)
    np.testing.assert_allclose(ab.d_shape1, ba.d_shape2, atol=1e-6)
    np.testing.assert_allclose(ab.d_shape2, ba.d_shape1, atol=1e-6)
    # A rigid motion of both changes nothing: the two pose gradients cancel.
    np.testing.assert_allclose(ab.d_pose1 + ab.d_pose2, np.zeros(6), atol=1e-8)
    # With a box second, its parameters have no gradient.
    g = fse.distance_gradients(a, pose_a, fse.Box(0.4, 0.5, 0.6), pose_b)
    assert g.d_shape2 is None and g.d_shape1.shape == (5,)


def test_pair_gradients_flag_coincident_centres():
    a = fse.Superellipsoid((1.0, 0.7, 0.5), (0.5, 1.5))
    centre = np.array([0.3, -0.2, 0.1])
    g = fse.distance_gradients(a, (random_rotation(3), centre), fse.Box(0.4, 0.5, 0.6),
                               (random_rotation(4), centre))
    assert g.distance < 0
    assert not g.differentiable
    assert np.all(np.isfinite(g.d_pose1)) and np.all(np.isfinite(g.d_pose2))
    g = fse.distance_gradients(a, (random_rotation(3), centre), fse.Box(0.4, 0.5, 0.6),
                               (random_rotation(4), centre + [0.4, 0.3, 0.0]))
    assert g.differentiable


def test_pair_gradients_refuse_two_other_shapes():
    with pytest.raises(TypeError, match="Superellipsoid"):
        fse.distance_gradients(fse.Sphere(1.0), None, fse.Box(1.0, 1.0, 1.0), None)


def test_pair_jacobians_of_two_spheres_are_the_closed_form():
    """The spheres above: n = (c2 - c1)/L with L = |c2 - c1|, so dn/dc2 = P/L = -dn/dc1 with
    P = I - n n^T; a twist of pose k moves its centre by dc_k = [-[c_k]x, I] (a sphere turning
    about its centre moves no witness); p1 = c1 + r1 n, p2 = c2 - r2 n."""
    r1, r2 = 0.7, 0.4
    ball = fse.Superellipsoid((r1, r1, r1), (1.0, 1.0))
    rng = np.random.default_rng(54)
    for i, u in enumerate(unit_directions(10, seed=34)):
        R1, c1 = random_rotation(50 + i), rng.normal(size=3)
        L = (r1 + r2) * (0.6 + 0.9 * i / 10)
        c2 = c1 + L * u
        j = fse.distance_jacobians(ball, (R1, c1), fse.Sphere(r2), (random_rotation(60 + i), c2))
        P = np.eye(3) - np.outer(u, u)
        moves1 = np.hstack([-skew(c1), np.eye(3)])
        moves2 = np.hstack([-skew(c2), np.eye(3)])
        n_d1, n_d2 = -(P / L) @ moves1, (P / L) @ moves2
        np.testing.assert_allclose(j.normal_d_pose1, n_d1, atol=1e-8)
        np.testing.assert_allclose(j.normal_d_pose2, n_d2, atol=1e-8)
        np.testing.assert_allclose(j.point1_d_pose1, moves1 + r1 * n_d1, atol=1e-8)
        np.testing.assert_allclose(j.point1_d_pose2, r1 * n_d2, atol=1e-8)
        np.testing.assert_allclose(j.point2_d_pose1, -r2 * n_d1, atol=1e-8)
        np.testing.assert_allclose(j.point2_d_pose2, moves2 - r2 * n_d2, atol=1e-8)
        assert j.differentiable


def rotation_about(axis, angle):
    k = np.zeros(3)
    k[axis] = 1.0
    K = skew(k)
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def moved(pose, component, h):
    """pose <- exp(h e_component) pose: a turn about a world axis through the origin (0-2) or a
    move along it (3-5)."""
    R, t = pose
    if component < 3:
        turn = rotation_about(component, h)
        return (turn @ R, turn @ t)
    step = np.zeros(3)
    step[component - 3] = h
    return (R, t + step)


@pytest.mark.parametrize("other,other_pose", [
    (fse.Ellipsoid(0.5, 0.3, 0.4), (random_rotation(71), np.array([1.6, 0.4, -0.3]))),
    (fse.Superellipsoid((0.6, 0.4, 0.5), (0.7, 1.2)),
     (random_rotation(72), np.array([0.9, 0.8, 0.2]))),
    (fse.Superellipsoid((0.6, 0.4, 0.5), (0.7, 1.2)),
     (random_rotation(73), np.array([0.5, 0.3, 0.1]))),
], ids=["ellipsoid apart", "superellipsoid apart", "superellipsoid overlapping"])
def test_pair_jacobians_match_differences_of_the_witnesses_in_either_order(other, other_pose):
    a = fse.Superellipsoid((1.0, 0.7, 0.5), (0.5, 1.5))
    pose_a = (random_rotation(70), np.array([0.1, 0.2, 0.3]))
    j = fse.distance_jacobians(a, pose_a, other, other_pose)
    assert j.differentiable
    h = 1e-6
    for which, pose in ((1, pose_a), (2, other_pose)):
        for c in range(6):
            def answer(step):
                p = moved(pose, c, step)
                return (fse.distance(a, p, other, other_pose) if which == 1
                        else fse.distance(a, pose_a, other, p))
            plus, minus = answer(h), answer(-h)
            for field, name in (("point1", "point1"), ("point2", "point2"), ("normal", "normal")):
                column = getattr(j, f"{name}_d_pose{which}")[:, c]
                difference = (getattr(plus, field) - getattr(minus, field)) / (2 * h)
                np.testing.assert_allclose(column, difference, atol=2e-6,
                                           err_msg=f"{name}_d_pose{which}[:, {c}]")
    # In the other order, the same Jacobians with the sides swapped and the normal turned.
    if isinstance(other, fse.Superellipsoid):
        return
    k = fse.distance_jacobians(other, other_pose, a, pose_a)
    np.testing.assert_array_equal(k.point1_d_pose1, j.point2_d_pose2)
    np.testing.assert_array_equal(k.point2_d_pose1, j.point1_d_pose2)
    np.testing.assert_array_equal(k.point1_d_pose2, j.point2_d_pose1)
    np.testing.assert_array_equal(k.normal_d_pose1, -j.normal_d_pose2)
    np.testing.assert_array_equal(k.normal_d_pose2, -j.normal_d_pose1)


def test_pair_jacobians_of_a_box_follow_the_order_of_the_shapes():
    a = fse.Superellipsoid((1.0, 0.7, 0.5), (0.5, 1.5))
    box = fse.Box(0.4, 0.5, 0.6)
    pose_a = (random_rotation(74), np.array([0.1, 0.2, 0.3]))
    pose_b = (random_rotation(75), np.array([1.4, -0.5, 0.6]))
    j = fse.distance_jacobians(a, pose_a, box, pose_b)
    k = fse.distance_jacobians(box, pose_b, a, pose_a)
    g = fse.distance_gradients(a, pose_a, box, pose_b)
    for field in ("distance", "point1", "point2", "normal", "d_pose1", "d_pose2", "d_shape1"):
        np.testing.assert_array_equal(getattr(j, field), getattr(g, field))
    assert j.d_shape2 is None and k.d_shape1 is None
    np.testing.assert_array_equal(k.point1_d_pose1, j.point2_d_pose2)
    np.testing.assert_array_equal(k.point2_d_pose2, j.point1_d_pose1)
    np.testing.assert_array_equal(k.normal_d_pose2, -j.normal_d_pose1)
    for m in (j.point1_d_pose1, j.point2_d_pose2, j.normal_d_pose1):
        assert m.shape == (3, 6) and np.isfinite(m).all()
    with pytest.raises(TypeError, match="Superellipsoid"):
        fse.distance_jacobians(box, None, fse.Sphere(1.0), None)
