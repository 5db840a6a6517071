// Triangle meshes in Python, and the contact regions of a Superellipsoid and another shape or
// mesh: contact_manifolds() (docs/python.md → "Contact regions").
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl_superellipsoid/contact_manifold.h>
#include <fcl_superellipsoid/tessellation.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "arrays.h"
#include "bindings.h"

namespace fcl_superellipsoid {
namespace python {

namespace {

using Geometry = fcl::CollisionGeometry<double>;
using Mesh = fcl::BVHModel<fcl::OBBRSS<double>>;

py::handle manifold_type;
py::handle places_type;

/// An (N, 3) float64 array of vertices and a (T, 3) integer array of triangles as a mesh.
std::shared_ptr<Mesh> makeMesh(const py::handle& vertices, const py::handle& triangles) {
  py::array_t<double> v =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(vertices);
  if (!v || v.ndim() != 2 || v.shape(1) != 3 || v.shape(0) < 3) {
    throw py::value_error("Mesh: vertices must be an (N, 3) array with N >= 3");
  }
  py::array t = py::array::ensure(triangles);
  if (!t || (t.dtype().kind() != 'i' && t.dtype().kind() != 'u')) {
    throw py::type_error("Mesh: triangles must be a (T, 3) array of integers");
  }
  py::array_t<std::int64_t> ti =
      py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(t);
  if (ti.ndim() != 2 || ti.shape(1) != 3 || ti.shape(0) < 1) {
    throw py::value_error("Mesh: triangles must be a (T, 3) array of vertex indices, T >= 1");
  }
  TriangleMesh<double> mesh;
  for (py::ssize_t i = 0; i < v.shape(0); ++i) {
    mesh.vertices.emplace_back(v.at(i, 0), v.at(i, 1), v.at(i, 2));
  }
  for (py::ssize_t i = 0; i < ti.shape(0); ++i) {
    std::size_t corner[3];
    for (py::ssize_t k = 0; k < 3; ++k) {
      const std::int64_t index = ti.at(i, k);
      if (index < 0 || index >= v.shape(0)) {
        throw py::value_error("Mesh: triangles[" + std::to_string(i) + ", " + std::to_string(k) +
                              "] = " + std::to_string(index) + " is not a vertex index (0 to " +
                              std::to_string(v.shape(0) - 1) + ")");
      }
      corner[k] = static_cast<std::size_t>(index);
    }
    mesh.triangles.emplace_back(corner[0], corner[1], corner[2]);
  }
  return makeBVHModel<fcl::OBBRSS<double>>(mesh);  // refuses a vertex that is not finite
}

/// Places as arrays: position, the surfaces' points in the caller's order, depth.
py::object placesOf(const std::vector<ManifoldPoint<double>>& places, bool shape_first) {
  const Eigen::Index n = Eigen::Index(places.size());
  Eigen::MatrixX3d position(n, 3), point1(n, 3), point2(n, 3);
  Eigen::VectorXd depth(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const ManifoldPoint<double>& p = places[std::size_t(i)];
    position.row(i) = p.position.transpose();
    point1.row(i) = (shape_first ? p.on_shape : p.on_other).transpose();
    point2.row(i) = (shape_first ? p.on_other : p.on_shape).transpose();
    depth[i] = p.depth;
  }
  return places_type(position, point1, point2, depth);
}

py::list contactManifolds(const std::shared_ptr<Geometry>& a, const py::handle& pose_a,
                          const std::shared_ptr<Geometry>& b, const py::handle& pose_b,
                          std::optional<double> patch_tolerance, int max_points,
                          int outline_samples, double outline_area_tolerance, double merge_angle) {
  if (!a || !b) throw py::type_error("contact_manifolds: the shapes must not be None");
  bool shape_first = true;
  const PythonShape& shape = superellipsoidOfPair(*a, *b, shape_first, "contact_manifolds");
  const fcl::Transform3<double> X_a = poseOf(pose_a, "pose1");
  const fcl::Transform3<double> X_b = poseOf(pose_b, "pose2");
  ManifoldOptions<double> options;
  if (patch_tolerance) {
    if (!(*patch_tolerance > 0)) {
      throw py::value_error(
          "contact_manifolds: patch_tolerance must be finite and > 0 (None: "
          "the default), got " +
          std::to_string(*patch_tolerance));
    }
    options.patch_tolerance = *patch_tolerance;
  }
  options.max_points = max_points;
  options.outline_samples = outline_samples;
  options.outline_area_tolerance = outline_area_tolerance;
  options.merge_angle = merge_angle;
  std::vector<ContactManifold<double>> regions;
  {
    py::gil_scoped_release release;
    regions = shape_first
                  ? fcl_superellipsoid::contactManifolds<double>(shape, X_a, *b, X_b, options)
                  : fcl_superellipsoid::contactManifolds<double>(shape, X_b, *a, X_a, options);
  }
  py::list out;
  for (const ContactManifold<double>& m : regions) {
    // Seen from shape 1 the normal turns where the Superellipsoid is shape 2, and the outline
    // is reversed to stay counter-clockwise about it.
    const Eigen::Vector3d normal = shape_first ? m.normal : Eigen::Vector3d(-m.normal);
    std::vector<ManifoldPoint<double>> polygon = m.polygon;
    if (!shape_first) std::reverse(polygon.begin(), polygon.end());
    const Eigen::Vector3d& point1 = shape_first ? m.on_shape : m.on_other;
    const Eigen::Vector3d& point2 = shape_first ? m.on_other : m.on_shape;
    out.append(manifold_type(normal, m.distance, point1, point2, m.patch_tolerance,
                             placesOf(polygon, shape_first), placesOf(m.points, shape_first)));
  }
  return out;
}

}  // namespace

void bindManifoldQueries(py::module_& m) {
  places_type = resultType(
      m, "ManifoldPlaces", {"position", "point1", "point2", "depth"},
      "Places of a contact region: position (k, 3) on the contact plane, point1 and point2 "
      "(k, 3) on shape 1's and shape 2's surfaces along the normal there, depth (k,): their "
      "overlap along the normal (< 0: apart, by at most the patch tolerance).");
  manifold_type = resultType(
      m, "ContactManifold",
      {"normal", "distance", "point1", "point2", "patch_tolerance", "polygon", "points"},
      "A contact region: the unit normal from shape 1 to shape 2, the region's signed distance "
      "(< 0: overlapping), its witnesses on shape 1 and shape 2 (distance()'s nearest points "
      "for a pair of shapes; a mesh region's deepest place), the patch tolerance used, its "
      "outline (ManifoldPlaces, "
      "counter-clockwise about the normal) and at most max_points reduced places "
      "(ManifoldPlaces, the deepest first).");

  py::class_<Mesh, Geometry, std::shared_ptr<Mesh>>(m, "Mesh", R"doc(
A triangle mesh (FCL's BVHModel with OBBRSS bounding volumes): vertices (N, 3) and triangles
(T, 3) of vertex indices. distance() and collide() meet it by its vertices (the reference paper's
model); contact_manifolds() as a surface.)doc")
      .def(py::init(&makeMesh), py::arg("vertices"), py::arg("triangles"))
      .def_property_readonly("num_vertices", [](const Mesh& mesh) { return mesh.num_vertices; })
      .def_property_readonly("num_triangles", [](const Mesh& mesh) { return mesh.num_tris; });

  m.def("contact_manifolds", &contactManifolds, py::arg("shape1"), py::arg("pose1"),
        py::arg("shape2"), py::arg("pose2"), py::kw_only(), py::arg("patch_tolerance") = py::none(),
        py::arg("max_points") = 4, py::arg("outline_samples") = 8,
        py::arg("outline_area_tolerance") = 0.005, py::arg("merge_angle") = 0.05, R"doc(
The contact regions of two posed shapes, one of them a Superellipsoid, the other any shape or a
Mesh: a list of ContactManifold, deepest first, empty where they are apart by more than the
patch tolerance (None: 1e-3 x the Superellipsoid's largest radius). Against a shape, at most one
region; against a Mesh, one per group of triangles facing within merge_angle (radians) of each
other. Each region: normal (from shape 1 to shape 2), distance, patch_tolerance, polygon and
points (ManifoldPlaces: at most max_points, the deepest first, spanning the region). The outline
starts from outline_samples directions and leaves out about outline_area_tolerance of the area
(>= 1: not refined, the cheapest, for the points alone).
docs/usage.md -> "Contact manifolds".)doc");
}

}  // namespace python
}  // namespace fcl_superellipsoid
