"""Contact regions against constructions: a superellipsoid pressed into a halfspace or a
tessellated floor has its cross-section at that depth (its area in closed form); the order of
the shapes turns the normal and swaps the points; meshes and refusals."""
import math

import numpy as np
import pytest

import fcl_superellipsoid as fse


def section_area(a1, a2, a3, e1, e2, tau):
    """The area of the cross-section tau below the top of a superellipsoid along its z axis."""
    s = (1 - ((a3 - tau) / a3) ** (2 / e2)) ** (e2 / 2)
    return 4 * a1 * a2 * s * s * math.gamma(1 + e1 / 2) ** 2 / math.gamma(1 + e1)


def polygon_area(places, n):
    """The area of a polygon of places seen along n (positive when counter-clockwise about n)."""
    e1 = np.cross(n, [1.0, 0.0, 0.0] if abs(n[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(n, e1)
    x, y = places.position @ e1, places.position @ e2
    return 0.5 * float(np.sum(x * np.roll(y, -1) - y * np.roll(x, -1)))


def floor_mesh(cells, half):
    """A grid of cells x cells squares of two triangles in the plane z = 0."""
    ticks = np.linspace(-half, half, cells + 1)
    vertices = np.array([[x, y, 0.0] for x in ticks for y in ticks])
    triangles = []
    for i in range(cells):
        for j in range(cells):
            a = i * (cells + 1) + j
            triangles += [[a, a + cells + 1, a + cells + 2], [a, a + cells + 2, a + 1]]
    return fse.Mesh(vertices, np.array(triangles))


@pytest.mark.parametrize("e1,e2", [(0.2, 0.2), (1.0, 1.0), (0.5, 1.5)])
def test_pressed_into_a_floor_the_region_is_the_cross_section(e1, e2):
    a1, a2, a3, depth = 0.5, 0.4, 0.3, 0.01
    shape = fse.Superellipsoid((a1, a2, a3), (e1, e2))
    pose = (np.eye(3), np.array([0.13, -0.07, a3 - depth]))
    expected = section_area(a1, a2, a3, e1, e2, depth + 1e-3 * a1)
    for other in (fse.Halfspace((0, 0, 1), 0.0), floor_mesh(7, 2.0)):
        regions = fse.contact_manifolds(shape, pose, other, None)
        assert len(regions) == 1
        m = regions[0]
        np.testing.assert_allclose(m.normal, [0, 0, -1], atol=1e-14)
        assert m.distance == pytest.approx(-depth, abs=1e-12)
        assert m.patch_tolerance == pytest.approx(1e-3 * a1)
        assert polygon_area(m.polygon, m.normal) == pytest.approx(expected, rel=0.01)
        assert m.points.position.shape[1] == 3 and 1 <= len(m.points.depth) <= 4
        assert m.points.depth[0] == pytest.approx(depth, abs=1e-12)
        # point1 on the superellipsoid, point2 on the floor, depth their overlap along n.
        np.testing.assert_allclose(m.polygon.point2[:, 2], 0.0, atol=1e-12)
        overlap = (m.polygon.point1 - m.polygon.point2) @ m.normal
        np.testing.assert_allclose(m.polygon.depth, overlap, atol=1e-12)


def test_the_order_of_the_shapes_turns_the_normal_and_swaps_the_points():
    shape = fse.Superellipsoid((0.5, 0.4, 0.3), (0.3, 0.3))
    floor = floor_mesh(4, 1.5)
    pose = (np.eye(3), np.array([0.1, 0.0, 0.29]))
    [a] = fse.contact_manifolds(shape, pose, floor, None)
    [b] = fse.contact_manifolds(floor, None, shape, pose)
    np.testing.assert_allclose(b.normal, -a.normal)
    assert b.distance == a.distance
    np.testing.assert_allclose(b.points.point1, a.points.point2)
    np.testing.assert_allclose(b.points.point2, a.points.point1)
    # The outline stays counter-clockwise about the normal it comes with.
    assert polygon_area(a.polygon, a.normal) > 0
    assert polygon_area(b.polygon, b.normal) == pytest.approx(polygon_area(a.polygon, a.normal))


def test_the_witnesses_are_the_distances_nearest_points():
    shape = fse.Superellipsoid((0.5, 0.4, 0.3), (0.3, 0.8))
    rng = np.random.default_rng(5)
    others = (
        fse.Sphere(0.3),
        fse.Box(0.6, 0.5, 0.4),
        fse.Superellipsoid((0.4, 0.3, 0.3), (1.2, 0.4)),
    )
    checked = 0
    for other in others:
        for k in range(10):
            pose = (np.eye(3), rng.uniform(-0.1, 0.1, 3) + [0.0, 0.0, 0.55 + 0.1 * k / 10])
            d = fse.distance(shape, None, other, pose)
            regions = fse.contact_manifolds(shape, None, other, pose, patch_tolerance=0.2)
            if not regions:
                continue
            [m] = regions
            assert m.distance == d.distance
            np.testing.assert_array_equal(m.point1, d.point1)
            np.testing.assert_array_equal(m.point2, d.point2)
            # And in the other order.
            [r] = fse.contact_manifolds(other, pose, shape, None, patch_tolerance=0.2)
            np.testing.assert_array_equal(r.point1, d.point2)
            np.testing.assert_array_equal(r.point2, d.point1)
            checked += 1
    assert checked >= 20


def test_apart_no_region_and_a_sphere_one():
    shape = fse.Superellipsoid((0.5, 0.4, 0.3), (0.5, 0.5))
    assert fse.contact_manifolds(shape, None, fse.Sphere(0.2), (np.eye(3), [0.8, 0, 0])) == []
    [m] = fse.contact_manifolds(shape, None, fse.Sphere(0.2), (np.eye(3), [0.69, 0, 0]))
    assert m.distance == pytest.approx(-0.01, abs=1e-9)
    np.testing.assert_allclose(m.normal, [1, 0, 0], atol=1e-9)


def test_meshes_and_bad_calls_raise():
    shape = fse.Superellipsoid((0.5, 0.4, 0.3), (0.5, 0.5))
    with pytest.raises(ValueError, match="Mesh: vertices must be an"):
        fse.Mesh(np.zeros((2, 3)), [[0, 1, 1]])
    with pytest.raises(ValueError, match=r"triangles\[0, 2\] = 5 is not a vertex index"):
        fse.Mesh(np.eye(3), [[0, 1, 5]])
    with pytest.raises(TypeError, match="triangles must be a"):
        fse.Mesh(np.eye(3), [[0.0, 1.0, 2.0]])
    with pytest.raises(ValueError, match="must be finite"):
        fse.Mesh([[0, 0, 0], [1, 0, 0], [0, math.nan, 0]], [[0, 1, 2]])
    floor = floor_mesh(2, 1.0)
    assert floor.num_vertices == 9 and floor.num_triangles == 8
    with pytest.raises(TypeError, match="one of the two shapes must be a Superellipsoid"):
        fse.contact_manifolds(fse.Sphere(1.0), None, floor, None)
    with pytest.raises(ValueError, match="patch_tolerance must be finite and > 0"):
        fse.contact_manifolds(shape, None, floor, None, patch_tolerance=0.0)
    with pytest.raises(ValueError, match="options.max_points must be >= 1"):
        fse.contact_manifolds(shape, None, floor, None, max_points=0)
    with pytest.raises(ValueError, match="options.merge_angle must be in"):
        fse.contact_manifolds(shape, None, floor, None, merge_angle=3.0)
    # distance() meets a mesh by its vertices (the paper's model): the grid's centre vertex.
    d = fse.distance(shape, (np.eye(3), [0, 0, 1.0]), floor, None)
    assert d.distance == pytest.approx(0.7, abs=1e-12)
