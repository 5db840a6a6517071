"""Point queries on arrays: answers against construction, every dtype, stride and shape case,
poses, methods, the margin form, and every error."""
import gc

import numpy as np
import pytest

import fcl_superellipsoid as fse

from conftest import outside_points, random_rotation, skew, unit_directions


def test_outside_distances_match_the_construction(shape):
    points, d, surface, u = outside_points(shape, 500, seed=11)
    q = shape.closest_points(points)
    np.testing.assert_allclose(q.distance, d, rtol=0, atol=1e-9 * shape.size)
    np.testing.assert_allclose(q.nearest_point, surface, rtol=0, atol=1e-9 * shape.size)
    np.testing.assert_allclose(q.normal, u, rtol=0, atol=1e-7)
    np.testing.assert_allclose(shape.signed_distance(points), q.distance, rtol=0, atol=0)


def test_a_spheres_inside_and_outside_distances():
    s = fse.Superellipsoid((2.0, 2.0, 2.0), (1.0, 1.0))
    rng = np.random.default_rng(5)
    p = rng.uniform(-4, 4, size=(2000, 3))
    r = np.linalg.norm(p, axis=1)
    q = s.closest_points(p)
    np.testing.assert_allclose(q.distance, r - 2.0, atol=1e-12)
    np.testing.assert_allclose(q.nearest_point, 2.0 * p / r[:, None], atol=1e-12)
    np.testing.assert_allclose(q.normal, p / r[:, None], atol=1e-12)


def test_float32_points_run_in_float_and_agree_to_its_precision(shape):
    points, d, _, _ = outside_points(shape, 300, seed=12)
    q32 = shape.closest_points(points.astype(np.float32))
    assert q32.distance.dtype == np.float32 and q32.nearest_point.dtype == np.float32
    np.testing.assert_allclose(q32.distance, d, rtol=0, atol=1e-4 * shape.size)


LAYOUTS = {
    "fortran": lambda p: np.asfortranarray(p),
    "every other row": lambda p: np.repeat(p, 2, axis=0)[::2],
    "negative strides": lambda p: np.ascontiguousarray(p[::-1])[::-1],
    "padded rows": lambda p: np.hstack([p, np.zeros((len(p), 2))])[:, :3],
    "read-only": lambda p: _read_only(p),
    "unaligned": lambda p: _unaligned(p),
    "list": lambda p: p.tolist(),
    "columns of a transposed array": lambda p: np.ascontiguousarray(p.T).T,
}


def _read_only(p):
    q = p.copy()
    q.setflags(write=False)
    return q


def _unaligned(p):
    buffer = np.zeros(p.size * 8 + 1, dtype=np.uint8)
    q = np.frombuffer(buffer.data, dtype=np.float64, count=p.size, offset=1).reshape(p.shape)
    q[...] = p
    assert not q.flags.aligned
    return q


@pytest.mark.parametrize("layout", sorted(LAYOUTS))
def test_every_layout_gives_the_answers_of_a_contiguous_array(layout):
    s = fse.Superellipsoid((3.5, 3.0, 2.0), (0.4, 0.3))
    p = np.random.default_rng(7).uniform(-5, 5, size=(300, 3))
    expected = s.closest_points(p)
    q = s.closest_points(LAYOUTS[layout](p))
    for a, b in zip(q, expected):
        np.testing.assert_array_equal(a, b)


def test_a_broadcast_array_reads_its_one_row_everywhere():
    s = fse.Superellipsoid((3.5, 3.0, 2.0), (0.4, 0.3))
    row = np.array([4.0, 1.0, 0.5])
    broadcast = np.broadcast_to(row, (50, 3))
    assert broadcast.strides[0] == 0
    np.testing.assert_array_equal(s.signed_distance(broadcast), s.signed_distance(broadcast.copy()))


def test_integer_points_are_read_as_float64():
    s = fse.Superellipsoid((1.0, 1.0, 1.0), (1.0, 1.0))
    d = s.signed_distance(np.array([[3, 0, 0], [0, 0, 0]], dtype=np.int32))
    assert d.dtype == np.float64 and d[0] == 2.0 and d[1] == pytest.approx(-1.0, abs=1e-15)


def test_one_point_and_no_points():
    s = fse.Superellipsoid((1.0, 1.0, 1.0), (1.0, 1.0))
    d = s.signed_distance([3.0, 0.0, 0.0])
    assert isinstance(d, float) and d == 2.0
    q = s.closest_points(np.array([0.0, 3.0, 0.0], dtype=np.float32))
    assert isinstance(q.distance, float) and q.nearest_point.shape == (3,)
    assert q.nearest_point.dtype == np.float32
    empty = s.closest_points(np.zeros((0, 3)))
    assert empty.distance.shape == (0,) and empty.nearest_point.shape == (0, 3)
    assert s.within_margin(np.zeros((0, 3)), 1.0).index.shape == (0,)


def test_results_outlive_each_other():
    s = fse.Superellipsoid((1.0, 1.0, 1.0), (1.0, 1.0))
    p = np.array([[3.0, 0.0, 0.0]] * 100)
    q = s.closest_points(p)
    distance, normal = q.distance, q.normal
    del q
    gc.collect()
    assert distance.tolist() == [2.0] * 100 and normal[:, 0].tolist() == [1.0] * 100
    assert not distance.flags.writeable or distance.base is not None


def test_recycled_result_buffers_are_never_shared():
    """A result's buffers are reused by a later call of the same size only once every array
    over them is gone (python/src/result_buffers.h)."""
    s = fse.Superellipsoid((1.0, 1.0, 1.0), (1.0, 1.0))
    near, far = np.full((2000, 3), 1.0), np.full((2000, 3), 5.0)
    expected_near, expected_far = np.sqrt(3.0) - 1.0, 5.0 * np.sqrt(3.0) - 1.0
    kept = [s.signed_distance(near) for _ in range(4)]
    normals = s.closest_points(far).normal  # the other arrays of its result are dropped
    for _ in range(6):  # results dropped at once: their buffers come back and are reused
        np.testing.assert_allclose(s.signed_distance(far), expected_far, rtol=1e-14)
    for d in kept:
        np.testing.assert_allclose(d, expected_near, rtol=1e-14)
    np.testing.assert_allclose(normals, 1.0 / np.sqrt(3.0), rtol=1e-14)


@pytest.mark.parametrize("form", ["matrix", "pair"])
def test_a_pose_moves_the_shape(shape, form):
    R, t = random_rotation(3), np.array([0.5, -2.0, 7.0])
    pose = (R, t) if form == "pair" else np.block([[R, t[:, None]], [np.zeros((1, 3)), 1.0]])
    points, d, surface, u = outside_points(shape, 200, seed=13)
    world = points @ R.T + t
    q = shape.closest_points(world, pose)
    np.testing.assert_allclose(q.distance, d, rtol=0, atol=1e-9 * (shape.size + 10))
    np.testing.assert_allclose(q.nearest_point, surface @ R.T + t, atol=1e-9 * (shape.size + 10))
    np.testing.assert_allclose(q.normal, u @ R.T, atol=1e-7)


def test_the_two_pose_forms_agree_bitwise():
    s = fse.Superellipsoid((3.5, 3.0, 2.0), (0.4, 0.3))
    R, t = random_rotation(4), np.array([1.0, 2.0, 3.0])
    X = np.eye(4)
    X[:3, :3], X[:3, 3] = R, t
    p = np.random.default_rng(8).uniform(-6, 6, size=(100, 3))
    np.testing.assert_array_equal(s.signed_distance(p, X), s.signed_distance(p, (R, t)))
    np.testing.assert_array_equal(s.signed_distance(p, pose=None), s.signed_distance(p, np.eye(4)))


@pytest.mark.parametrize("method,tolerance", [("paper", 1e-3), ("radial", None)])
def test_other_methods(shape, method, tolerance):
    points, d, _, _ = outside_points(shape, 200, seed=14)
    q = shape.closest_points(points, method=method)
    assert np.all(np.isfinite(q.distance)) and np.all(q.distance > 0)
    np.testing.assert_allclose(np.linalg.norm(q.normal, axis=1), 1.0, atol=1e-9)
    assert np.all(q.distance >= d - 1e-9 * shape.size)  # never nearer than the nearest point
    if tolerance is not None:  # the paper's method converges to its tolerance on most points
        assert np.median(np.abs(q.distance - d)) <= 10 * tolerance * shape.size


def test_options_are_passed():
    s = fse.Superellipsoid((3.5, 3.0, 2.0), (0.4, 0.3))
    p = np.random.default_rng(9).uniform(-5, 5, size=(3000, 3))
    exact = s.signed_distance(p)
    loose = s.signed_distance(p, tolerance=1e-4)
    assert np.max(np.abs(loose - exact)) > 0  # a looser solve, a different answer
    np.testing.assert_allclose(loose, exact, rtol=0, atol=1e-3 * s.size)
    capped = s.closest_points(p, max_iterations=1, vectorize=False)
    assert np.max(np.abs(capped.distance - exact)) > 0 and np.all(np.isfinite(capped.distance))
    scalar = s.signed_distance(p, vectorize=False, threads=1)
    one_by_one = np.array([s.signed_distance(x) for x in p[:200]])
    np.testing.assert_array_equal(scalar[:200], one_by_one)
    np.testing.assert_array_equal(s.signed_distance(p, threads=1), s.signed_distance(p, threads=2))


def test_within_margin_is_the_subset_of_the_distances():
    s = fse.Superellipsoid((3.5, 3.0, 2.0), (0.4, 0.3))
    p = np.random.default_rng(10).uniform(-6, 6, size=(5000, 3))
    all_points = s.closest_points(p)
    m = s.within_margin(p, 0.5)
    expected = np.flatnonzero(all_points.distance <= 0.5)
    np.testing.assert_array_equal(m.index, expected)
    assert m.index.dtype == np.int64
    np.testing.assert_allclose(m.distance, all_points.distance[expected], atol=1e-12 * s.size)
    np.testing.assert_allclose(m.nearest_point, all_points.nearest_point[expected], atol=1e-9)
    m32 = s.within_margin(p.astype(np.float32), 0.5)
    assert m32.distance.dtype == np.float32


BAD_POINTS = [
    (np.zeros((4, 2)), ValueError, r"expected shape \(N, 3\) or \(3,\), got \(4, 2\)"),
    (np.zeros((2, 3, 3)), ValueError, r"got \(2, 3, 3\)"),
    (np.zeros(4), ValueError, r"got \(4,\)"),
    (np.float64(1.0), ValueError, r"got \(\)"),
    (np.zeros((3, 3), dtype=np.complex128), TypeError, "complex128"),
    (np.zeros((3, 3), dtype=np.float16), TypeError, "float16"),
    (np.zeros((3, 3), dtype=bool), TypeError, "bool"),
    (np.array([["a", "b", "c"]]), TypeError, "<U1"),
    (np.array([[0.0, np.nan, 0.0]]), ValueError, "vertex 0 must be finite"),
    (np.array([[0.0, 0.0, 0.0], [np.inf, 0.0, 0.0]], dtype=np.float32), ValueError, "vertex 1"),
    (np.array([np.nan, 0.0, 0.0]), ValueError, "finite"),
    ("abc", TypeError, "dtype"),
    (None, TypeError, "dtype"),
    (np.zeros(3, dtype=[("a", "f8")]), TypeError, "dtype"),
    (np.array([[1.0, 2.0, 3.0], None], dtype=object), TypeError, "object"),
    (np.zeros((0, 4)), ValueError, r"got \(0, 4\)"),
    (np.zeros((1, 3, 1)), ValueError, r"got \(1, 3, 1\)"),
    (np.array([[1e308, 0.0, 0.0]]), ValueError, "vertex 0"),
]


@pytest.mark.parametrize("points,error,message", BAD_POINTS, ids=lambda x: str(x)[:20])
def test_bad_points_raise(points, error, message):
    s = fse.Superellipsoid((1.0, 1.0, 1.0), (1.0, 1.0))
    for query in (s.signed_distance, s.closest_points, lambda p: s.within_margin(p, 0.1)):
        with pytest.raises(error, match=message):
            query(points)


BAD_OPTIONS = [
    (dict(method="fast"), ValueError, "method must be 'exact', 'paper' or 'radial', got 'fast'"),
    (dict(tolerance=-1.0), ValueError, "tolerance must be finite and > 0, got -1"),
    (dict(tolerance=float("nan")), ValueError, "tolerance"),
    (dict(max_iterations=0), ValueError, "max_iterations must be >= 1"),
    (dict(threads=-1), ValueError, "threads must be >= 0"),
    (dict(pose=np.eye(3)), ValueError, r"\(4, 4\) matrix or a pair"),
    (dict(pose=2 * np.eye(4)), ValueError, "last row"),
    (dict(pose=(2 * np.eye(3), np.zeros(3))), ValueError, "not a rotation"),
    (dict(pose=(np.diag([1.0, 1.0, -1.0]), np.zeros(3))), ValueError, "det R = -1"),
    (dict(pose=(np.eye(3), [0.0, np.nan, 0.0])), ValueError, "finite"),
    (dict(pose=(np.eye(3), np.zeros(2))), ValueError, r"t of shape \(3,\)"),
    (dict(pose="identity"), TypeError, "real numbers"),
    (dict(method=3), TypeError, "incompatible"),
]


@pytest.mark.parametrize("options,error,message", BAD_OPTIONS, ids=lambda x: str(x)[:30])
def test_bad_options_raise(options, error, message):
    s = fse.Superellipsoid((1.0, 1.0, 1.0), (1.0, 1.0))
    for points in (np.ones((5, 3)), np.ones(3), np.ones((5, 3), dtype=np.float32)):
        with pytest.raises(error, match=message):
            s.signed_distance(points, **options)


def test_bad_margin():
    s = fse.Superellipsoid((1.0, 1.0, 1.0), (1.0, 1.0))
    with pytest.raises(ValueError, match="margin"):
        s.within_margin(np.ones((5, 3)), float("nan"))


def test_float_range_is_checked_for_float32_points():
    s = fse.Superellipsoid((1e-20, 1e-20, 1e-20), (1.0, 1.0))  # fine in double
    assert s.signed_distance(np.ones((2, 3)))[0] > 0
    with pytest.raises(ValueError, match="supported range"):
        s.signed_distance(np.ones((2, 3), dtype=np.float32))


def test_never_nan_on_extreme_points(shape):
    u = unit_directions(50, seed=15)
    for scale in (1e-300, 1e-12, 1.0, 1e6, 1e150):
        p = u * scale * shape.size
        d = shape.signed_distance(p)
        assert np.all(np.isfinite(d))
    assert np.isfinite(shape.signed_distance(np.zeros(3)))


def test_distance_gradients_of_a_posed_sphere_match_the_construction():
    # A sphere of radius R centred at t: d = |p − t| − R, ∂d/∂p = n, the pose twist (ω, v)
    # moves the centre by ω × t + v: ∂d/∂v = −n, ∂d/∂ω = n × N = n × t; scaling radius a_i
    # moves the surface by n_i² along n (n in the shape's frame): ∂d/∂a_i = −n_i².
    R, rotation, t = 1.5, random_rotation(21), np.array([0.3, -0.7, 1.1])
    s = fse.Superellipsoid((R, R, R), (1.0, 1.0))
    rng = np.random.default_rng(22)
    p = t + rng.uniform(-3, 3, size=(400, 3))
    g = s.distance_gradients(p, (rotation, t))
    offset = p - t
    r = np.linalg.norm(offset, axis=1)
    n = offset / r[:, None]
    np.testing.assert_allclose(g.distance, r - R, atol=1e-12)
    np.testing.assert_allclose(g.normal, n, atol=1e-12)
    np.testing.assert_allclose(g.nearest_point, t + R * n, atol=1e-12)
    np.testing.assert_allclose(g.d_pose[:, 3:], -n, atol=1e-12)
    np.testing.assert_allclose(g.d_pose[:, :3], np.cross(n, t), atol=1e-12)
    n_shape = n @ rotation  # rows: Rᵀ n
    np.testing.assert_allclose(g.d_shape[:, :3], -n_shape**2, atol=1e-10)
    assert g.differentiable.dtype == np.bool_ and g.differentiable.all()
    assert g.d_pose.shape == (400, 6) and g.d_shape.shape == (400, 5)


def test_distance_gradients_exponent_columns_match_differences_of_the_distance():
    # The exponent columns against central differences of signed_distance over new shapes
    # (outside points: the distance is smooth there).
    radii, exponents = np.array([1.2, 0.8, 0.5]), np.array([0.4, 1.3])
    s = fse.Superellipsoid(radii, exponents)
    points, _, _, _ = outside_points(s, 50, seed=23)
    g = s.distance_gradients(points)
    h = 1e-6
    for k in range(2):
        step = np.zeros(2)
        step[k] = h
        plus = fse.Superellipsoid(radii, exponents + step).signed_distance(points)
        minus = fse.Superellipsoid(radii, exponents - step).signed_distance(points)
        np.testing.assert_allclose(g.d_shape[:, 3 + k], (plus - minus) / (2 * h), atol=1e-7)


def test_distance_gradients_of_one_point_are_its_row_and_float32_runs_in_float(shape):
    points, _, _, _ = outside_points(shape, 20, seed=24)
    points = np.vstack([points, 0.5 * points])  # inside too
    g = shape.distance_gradients(points)
    one = shape.distance_gradients(points[3])
    assert isinstance(one.distance, float) and isinstance(one.differentiable, bool)
    assert one.d_pose.shape == (6,) and one.d_shape.shape == (5,)
    np.testing.assert_allclose(one.d_shape, g.d_shape[3], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(one.d_pose, g.d_pose[3], rtol=1e-9, atol=1e-12)
    g32 = shape.distance_gradients(points.astype(np.float32))
    assert g32.d_shape.dtype == np.float32 and g32.d_pose.dtype == np.float32
    np.testing.assert_allclose(g32.d_pose, g.d_pose, atol=5e-3 * shape.size)


def test_distance_gradients_flag_the_centre_and_refuse_other_methods():
    s = fse.Superellipsoid((1.0, 0.8, 0.6), (0.5, 0.5))
    g = s.distance_gradients(np.array([[0.0, 0.0, 0.0], [0.1, 0.2, 0.3]]))
    assert list(g.differentiable) == [False, True]
    assert np.isfinite(g.d_shape).all() and np.isfinite(g.d_pose).all()
    with pytest.raises(ValueError, match="method must be 'exact', got 'radial'"):
        s.distance_gradients([1.0, 2.0, 3.0], method="radial")
    with pytest.raises(ValueError, match="1"):
        s.distance_gradients(np.array([[1.0, np.nan, 0.0]]))


def test_distance_jacobians_of_a_posed_sphere_match_the_construction():
    # A sphere of radius R centred at t, a point p at r = |p − t| along u: N = t + R u, n = u.
    # ∂u/∂p = P / r with P = I − u uᵀ, so ∂N/∂p = R P / r, ∂n/∂p = P / r. The twist (ω, v)
    # moves the centre by ω × t + v, ∂t/∂ξ = [−[t]×, I], and the sphere turning about its
    # centre moves neither: ∂N/∂ξ = (I − R P / r) ∂t/∂ξ, ∂n/∂ξ = −(P / r) ∂t/∂ξ.
    R, rotation, t = 1.5, random_rotation(25), np.array([0.3, -0.7, 1.1])
    s = fse.Superellipsoid((R, R, R), (1.0, 1.0))
    rng = np.random.default_rng(26)
    p = t + rng.uniform(-3, 3, size=(200, 3))
    j = s.distance_jacobians(p, (rotation, t))
    g = s.distance_gradients(p, (rotation, t))
    for field in ("distance", "nearest_point", "normal", "d_pose", "d_shape", "differentiable"):
        np.testing.assert_allclose(getattr(j, field), getattr(g, field), rtol=0, atol=1e-12)
    assert j.nearest_point_d_point.shape == (200, 3, 3)
    assert j.nearest_point_d_pose.shape == (200, 3, 6)
    assert j.nearest_point_d_shape.shape == (200, 3, 5)
    moves_centre = np.hstack([-skew(t), np.eye(3)])
    for i in range(len(p)):
        offset = p[i] - t
        r = np.linalg.norm(offset)
        u = offset / r
        P = np.eye(3) - np.outer(u, u)
        np.testing.assert_allclose(j.nearest_point_d_point[i], R * P / r, atol=1e-9)
        np.testing.assert_allclose(j.normal_d_point[i], P / r, atol=1e-9)
        np.testing.assert_allclose(j.nearest_point_d_pose[i],
                                   (np.eye(3) - R * P / r) @ moves_centre, atol=1e-9)
        np.testing.assert_allclose(j.normal_d_pose[i], -(P / r) @ moves_centre, atol=1e-9)


def test_distance_jacobians_shape_columns_match_differences_of_the_nearest_points():
    # Each parameter's column against central differences of closest_points over new shapes,
    # posed (outside points: the nearest point moves smoothly there).
    radii, exponents = np.array([1.2, 0.8, 0.5]), np.array([0.4, 1.3])
    pose = (random_rotation(27), np.array([0.5, 0.1, -0.3]))
    s = fse.Superellipsoid(radii, exponents)
    points, _, _, _ = outside_points(s, 40, seed=28)
    points = points @ pose[0].T + pose[1]
    j = s.distance_jacobians(points, pose)
    assert j.differentiable.all()
    h = 1e-6
    for k in range(5):
        step = np.zeros(5)
        step[k] = h
        plus = fse.Superellipsoid(radii + step[:3], exponents + step[3:]).closest_points(
            points, pose)
        minus = fse.Superellipsoid(radii - step[:3], exponents - step[3:]).closest_points(
            points, pose)
        np.testing.assert_allclose(j.nearest_point_d_shape[:, :, k],
                                   (plus.nearest_point - minus.nearest_point) / (2 * h),
                                   atol=1e-6)
        np.testing.assert_allclose(j.normal_d_shape[:, :, k],
                                   (plus.normal - minus.normal) / (2 * h), atol=1e-6)


def test_distance_jacobians_of_one_point_are_its_item_and_float32_runs_in_float(shape):
    points, _, _, _ = outside_points(shape, 10, seed=29)
    points = np.vstack([points, 0.5 * points])  # inside too
    j = shape.distance_jacobians(points)
    one = shape.distance_jacobians(points[4])
    assert isinstance(one.distance, float) and isinstance(one.differentiable, bool)
    assert one.nearest_point_d_pose.shape == (3, 6) and one.normal_d_shape.shape == (3, 5)
    for field in ("nearest_point_d_point", "nearest_point_d_pose", "nearest_point_d_shape",
                  "normal_d_point", "normal_d_pose", "normal_d_shape"):
        np.testing.assert_array_equal(getattr(one, field), getattr(j, field)[4])
        assert np.isfinite(getattr(j, field)).all()
    j32 = shape.distance_jacobians(points.astype(np.float32))
    assert j32.nearest_point_d_point.dtype == np.float32 and j32.distance.dtype == np.float32


def test_distance_jacobians_flag_the_centre_and_name_a_bad_point():
    s = fse.Superellipsoid((1.0, 0.8, 0.6), (0.5, 0.5))
    j = s.distance_jacobians(np.array([[0.0, 0.0, 0.0], [0.1, 0.2, 0.3]]))
    assert list(j.differentiable) == [False, True]
    assert np.isfinite(j.nearest_point_d_point).all() and np.isfinite(j.normal_d_pose).all()
    with pytest.raises(ValueError, match=r"points\[2\]"):
        s.distance_jacobians(np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, np.inf, 0.0]]))
    with pytest.raises(TypeError):
        s.distance_jacobians([1.0, 2.0, 3.0], method="exact")
