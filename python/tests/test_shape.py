"""The shape's own members: parameters, mass properties against closed forms, support points,
tessellation, containment, pickling, and the errors of its constructor."""
import math
import pickle

import numpy as np
import pytest

import fcl_superellipsoid as fse

from conftest import unit_directions


def test_parameters_are_kept():
    s = fse.Superellipsoid(radii=[3.5, 3.0, 2.0], exponents=(0.4, 0.3))
    assert s.radii.tolist() == [3.5, 3.0, 2.0]
    assert s.exponents == (0.4, 0.3)
    assert s.size == 3.5
    assert repr(s) == "Superellipsoid(radii=(3.5, 3.0, 2.0), exponents=(0.4, 0.3))"
    assert isinstance(s, fse.Shape)


@pytest.mark.parametrize("a,b,c", [(1.0, 1.0, 1.0), (2.0, 0.5, 1.5)])
def test_an_ellipsoids_volume_and_inertia_are_the_closed_forms(a, b, c):
    s = fse.Superellipsoid((a, b, c), (1.0, 1.0))
    volume = 4.0 / 3.0 * math.pi * a * b * c
    assert s.volume == pytest.approx(volume, rel=1e-12)
    expected = volume / 5.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])
    np.testing.assert_allclose(s.inertia, expected, rtol=1e-12, atol=1e-12 * volume)


def test_a_near_box_has_nearly_the_boxs_volume():
    s = fse.Superellipsoid((1.0, 2.0, 3.0), (0.02, 0.02))
    assert s.volume == pytest.approx(8 * 1.0 * 2.0 * 3.0, rel=0.03)
    assert s.volume < 48.0


def test_support_points_maximise_the_direction_over_the_surface(shape):
    u = unit_directions(200, seed=3)
    s = shape.support(u)
    assert s.shape == (200, 3)
    vertices, _ = shape.tessellate(2000)
    reach = np.max(vertices @ u.T, axis=0)  # each direction's best vertex
    assert np.all(np.einsum("ij,ij->i", s, u) >= reach - 1e-12 * shape.size)
    # on the surface: the support point of u is its own nearest point, at distance 0
    np.testing.assert_allclose(shape.signed_distance(s), 0.0, atol=1e-12 * shape.size)
    np.testing.assert_array_equal(shape.support(u[0]), s[0])


def test_the_zero_direction_has_a_support_point():
    s = fse.Superellipsoid((2.0, 1.0, 1.0), (0.5, 0.5))
    assert s.support([0.0, 0.0, 0.0]).tolist() == [2.0, 0.0, 0.0]


def test_tessellation_counts_and_lies_on_the_surface(shape):
    vertices, faces = shape.tessellate(272)
    assert vertices.shape == (272, 3) and vertices.dtype == np.float64
    assert faces.shape == (540, 3) and faces.dtype == np.int64
    assert faces.min() == 0 and faces.max() == 271
    np.testing.assert_allclose(shape.signed_distance(vertices), 0.0, atol=1e-12 * shape.size)
    # counter-clockwise seen from outside: every face's normal points away from the centre
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    outward = np.einsum("ij,ij->i", np.cross(b - a, c - a), (a + b + c) / 3)
    assert np.all(outward > 0)


def test_contains():
    s = fse.Superellipsoid((1.0, 1.0, 1.0), (1.0, 1.0))
    assert s.contains([0.5, 0.0, 0.0]) is True
    assert s.contains([1.5, 0.0, 0.0]) is False
    inside = s.contains(np.array([[0.0, 0.0, 0.99], [0.0, 0.0, 1.01]], dtype=np.float32))
    assert inside.dtype == np.bool_ and inside.tolist() == [True, False]


def test_pickles():
    s = fse.Superellipsoid((3.5, 3.0, 2.0), (0.4, 0.3))
    t = pickle.loads(pickle.dumps(s))
    assert repr(t) == repr(s)
    p = np.array([[4.0, 1.0, 0.5]])
    assert t.signed_distance(p)[0] == s.signed_distance(p)[0]


@pytest.mark.parametrize(
    "radii,exponents,message",
    [
        ((0.0, 1.0, 1.0), (1.0, 1.0), "a1 must be finite and > 0"),
        ((1.0, float("nan"), 1.0), (1.0, 1.0), r"radii\[1\] must be finite"),
        ((1.0, 1.0, 1.0), (0.0, 1.0), "eps1"),
        ((1.0, 1.0, 1.0), (1.0, 2.0), "eps2"),
        ((1.0, 1e9, 1.0), (1.0, 1.0), "largest radius"),
        ((1.0, 1.0), (1.0, 1.0), "expected 3 numbers"),
        ((1.0, 1.0, 1.0), (1.0,), "expected 2 numbers"),
    ],
)
def test_bad_parameters_raise_value_error_naming_them(radii, exponents, message):
    with pytest.raises(ValueError, match=message):
        fse.Superellipsoid(radii, exponents)


def test_non_numbers_raise_type_error():
    with pytest.raises(TypeError):
        fse.Superellipsoid(["a", "b", "c"], (1.0, 1.0))
    with pytest.raises(TypeError):
        fse.Superellipsoid((1.0, 1.0, 1.0))


def test_bad_tessellation_counts_and_directions():
    s = fse.Superellipsoid((1.0, 1.0, 1.0), (1.0, 1.0))
    with pytest.raises(ValueError, match="num_vertices"):
        s.tessellate(4)
    with pytest.raises(ValueError, match=r"directions\[1\] must be finite"):
        s.support([[1.0, 0.0, 0.0], [np.inf, 0.0, 0.0]])
    with pytest.raises(ValueError, match=r"points\[0\] must be finite"):
        s.contains([np.nan, 0.0, 0.0])
