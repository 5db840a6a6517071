"""The module answers what the C++ library answers, bitwise: the batched queries on the same
input, one-point calls, the point Jacobians, and the pair queries with their Jacobians (the C++
side is cpp_reference.cpp)."""
import json
import os
import subprocess

import numpy as np
import pytest

import fcl_superellipsoid as fse

from conftest import SHAPE_PARAMETERS, random_rotation

REFERENCE = os.environ.get("FSE_CPP_REFERENCE")
pytestmark = pytest.mark.skipif(not REFERENCE, reason="FSE_CPP_REFERENCE is set by ctest")


def reference(request):
    # The reference links its own sanitizer runtime in a sanitized build: nothing is preloaded.
    env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}
    out = subprocess.run([REFERENCE], input=json.dumps(request), capture_output=True, text=True,
                         check=True, env=env)
    return json.loads(out.stdout) if out.stdout else None


def pose_matrix(seed):
    X = np.eye(4)
    X[:3, :3], X[:3, 3] = random_rotation(seed), np.array([0.3, -1.0, 2.0]) * seed
    return X


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
@pytest.mark.parametrize("method", ["exact", "paper", "radial"])
@pytest.mark.parametrize("vectorize", [True, False])
@pytest.mark.parametrize("radii,exponents", SHAPE_PARAMETERS[1:4])
def test_batched_queries_are_bitwise_the_libraries(tmp_path, dtype, method, vectorize, radii,
                                                   exponents):
    rng = np.random.default_rng(21)
    size = max(radii)
    points = np.concatenate([rng.uniform(-2 * size, 2 * size, size=(3000, 3)),
                             rng.uniform(-0.5 * size, 0.5 * size, size=(1000, 3))]).astype(dtype)
    X = pose_matrix(2)
    world = (points.astype(np.float64) @ X[:3, :3].T + X[:3, 3]).astype(dtype)
    world.tofile(tmp_path / "points.bin")
    reference({"query": "batch", "dtype": np.dtype(dtype).name, "radii": radii,
               "exponents": exponents, "pose": X[:3].tolist(), "method": method,
               "vectorize": vectorize, "points": str(tmp_path / "points.bin"),
               "out": str(tmp_path / "out.bin")})
    raw = np.fromfile(tmp_path / "out.bin", dtype=dtype)
    n = len(points)
    s = fse.Superellipsoid(radii, exponents)
    q = s.closest_points(world, X, method=method, vectorize=vectorize)
    np.testing.assert_array_equal(q.distance, raw[:n])
    np.testing.assert_array_equal(q.nearest_point, raw[n:4 * n].reshape(n, 3))
    np.testing.assert_array_equal(q.normal, raw[4 * n:].reshape(n, 3))


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_one_point_calls_are_bitwise_the_scalar_library(tmp_path, dtype):
    radii, exponents = SHAPE_PARAMETERS[1]
    points = np.random.default_rng(22).uniform(-6, 6, size=(300, 3)).astype(dtype)
    X = pose_matrix(3)
    points.tofile(tmp_path / "points.bin")
    reference({"query": "scalar", "dtype": np.dtype(dtype).name, "radii": radii,
               "exponents": exponents, "pose": X[:3].tolist(), "method": "exact",
               "vectorize": False, "points": str(tmp_path / "points.bin"),
               "out": str(tmp_path / "out.bin")})
    raw = np.fromfile(tmp_path / "out.bin", dtype=dtype)
    n = len(points)
    s = fse.Superellipsoid(radii, exponents)
    for i in range(n):
        q = s.closest_points(points[i], X)
        assert q.distance == raw[i]
        np.testing.assert_array_equal(q.nearest_point, raw[n + 3 * i:n + 3 * i + 3])
        np.testing.assert_array_equal(q.normal, raw[4 * n + 3 * i:4 * n + 3 * i + 3])


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_point_jacobians_are_bitwise_the_libraries(tmp_path, dtype):
    radii, exponents = SHAPE_PARAMETERS[2]
    points = np.random.default_rng(23).uniform(-4, 4, size=(200, 3)).astype(dtype)
    X = pose_matrix(5)
    points.tofile(tmp_path / "points.bin")
    reference({"query": "jacobians", "dtype": np.dtype(dtype).name, "radii": radii,
               "exponents": exponents, "pose": X[:3].tolist(), "method": "exact",
               "vectorize": False, "points": str(tmp_path / "points.bin"),
               "out": str(tmp_path / "out.bin")})
    raw = np.fromfile(tmp_path / "out.bin", dtype=dtype).reshape(len(points), -1)
    j = fse.Superellipsoid(radii, exponents).distance_jacobians(points, X)
    columns = np.cumsum([0, 1, 3, 3, 6, 5, 9, 18, 15, 9, 18, 15])
    fields = ["distance", "nearest_point", "normal", "d_pose", "d_shape", "nearest_point_d_point",
              "nearest_point_d_pose", "nearest_point_d_shape", "normal_d_point", "normal_d_pose",
              "normal_d_shape"]
    for k, field in enumerate(fields):
        ours = getattr(j, field).reshape(len(points), -1)
        np.testing.assert_array_equal(ours, raw[:, columns[k]:columns[k + 1]], err_msg=field)


OTHERS = [
    ("box", [1.0, 2.0, 0.5], lambda v: fse.Box(*v)),
    ("sphere", [0.7], lambda v: fse.Sphere(*v)),
    ("ellipsoid", [1.0, 0.5, 0.8], lambda v: fse.Ellipsoid(*v)),
    ("capsule", [0.4, 1.5], lambda v: fse.Capsule(*v)),
    ("cylinder", [0.6, 1.2], lambda v: fse.Cylinder(*v)),
    ("cone", [0.6, 1.2], lambda v: fse.Cone(*v)),
    ("halfspace", [0.0, 0.0, 1.0, -2.5], lambda v: fse.Halfspace(v[:3], v[3])),
    ("plane", [0.0, 0.6, 0.8, 0.5], lambda v: fse.Plane(v[:3], v[3])),
    ("superellipsoid", [1.0, 0.7, 0.5, 0.5, 1.5],
     lambda v: fse.Superellipsoid(v[:3], v[3:])),
]


@pytest.mark.parametrize("kind,values,make", OTHERS, ids=[o[0] for o in OTHERS])
@pytest.mark.parametrize("offset", [4.0, 1.5])  # apart, overlapping
def test_pair_queries_are_bitwise_the_libraries(kind, values, make, offset):
    radii, exponents = SHAPE_PARAMETERS[1]
    X1, X2 = pose_matrix(1), pose_matrix(4)
    X2[:3, 3] = X1[:3, 3] + offset * np.array([0.6, 0.0, 0.8])
    expected = reference({"query": "pair", "radii": radii, "exponents": exponents,
                          "pose": X1[:3].tolist(), "other": {"kind": kind, "values": values},
                          "other_pose": X2[:3].tolist()})
    s, other = fse.Superellipsoid(radii, exponents), make(values)
    d = fse.distance(s, X1, other, X2)
    assert d.distance == expected["distance"]
    assert d.point1.tolist() == expected["point1"] and d.point2.tolist() == expected["point2"]
    contacts = fse.collide(s, X1, other, X2)
    assert len(contacts) == len(expected["contacts"])
    for c, e in zip(contacts, expected["contacts"]):
        assert c.position.tolist() == e["position"] and c.normal.tolist() == e["normal"]
        assert c.depth == e["depth"]
    # The Jacobians, in either order of the shapes. The library answers the superellipsoid
    # first: the other order swaps the sides and turns the normal, bitwise; two
    # superellipsoids in the other order are answered from the other one's side (to 1e-6).
    e = expected["jacobians"]
    j = fse.distance_jacobians(s, X1, other, X2)
    k = fse.distance_jacobians(other, X2, s, X1)
    assert j.distance == e["distance"] and j.differentiable == e["differentiable"]
    assert j.normal.tolist() == e["normal"]
    assert j.d_pose1.tolist() == e["d_pose"] and j.d_pose2.tolist() == e["d_other_pose"]
    assert j.d_shape1.tolist() == e["d_shape"]
    swapped = ((j.point1_d_pose1, k.point2_d_pose2, "on_shape_d_pose"),
               (j.point1_d_pose2, k.point2_d_pose1, "on_shape_d_other_pose"),
               (j.point2_d_pose1, k.point1_d_pose2, "on_other_d_pose"),
               (j.point2_d_pose2, k.point1_d_pose1, "on_other_d_other_pose"),
               (j.normal_d_pose1, -k.normal_d_pose2, "normal_d_pose"),
               (j.normal_d_pose2, -k.normal_d_pose1, "normal_d_other_pose"),
               (j.d_pose1, k.d_pose2, "d_pose"), (j.d_pose2, k.d_pose1, "d_other_pose"),
               (j.normal, -k.normal, "normal"))
    for ours, theirs, name in swapped:
        assert ours.ravel().tolist() == e[name], name
        if kind == "superellipsoid":
            np.testing.assert_allclose(theirs, ours, rtol=1e-6, atol=1e-8, err_msg=name)
        else:
            assert theirs.ravel().tolist() == e[name], name
