// FCL's shapes in Python and the pair queries distance() and collide() through the library's
// front end (docs/python.md → "Pair queries").
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <fcl_superellipsoid/fcl_integration.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <sstream>

#include "arrays.h"
#include "bindings.h"

namespace fcl_superellipsoid {
namespace python {

namespace {

using Geometry = fcl::CollisionGeometry<double>;

py::handle pair_distance_type;
py::handle contact_type;

double positive(double value, const char* name) {
  if (!(std::isfinite(value) && value > 0)) {
    std::ostringstream text;
    text.precision(17);
    text << name << " must be finite and > 0, got " << value;
    throw py::value_error(text.str());
  }
  return value;
}

Eigen::Vector3d point3(const py::handle& values, const char* name) {
  return Eigen::Vector3d(finiteVector(values, 3, name));
}

Eigen::Vector3d unitNormal(const py::handle& values, const char* name) {
  const Eigen::Vector3d n = point3(values, name);
  if (n.norm() == 0 || !std::isfinite(n.norm())) {
    throw py::value_error(std::string(name) + " must be a non-zero finite vector");
  }
  return n.normalized();
}

std::shared_ptr<fcl::Convex<double>> makeConvex(const py::handle& vertices,
                                                const py::handle& faces) {
  py::array_t<double> v =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(vertices);
  if (!v || v.ndim() != 2 || v.shape(1) != 3 || v.shape(0) < 4) {
    throw py::value_error("Convex: vertices must be an (N, 3) array with N >= 4");
  }
  py::array f = py::array::ensure(faces);
  if (!f || (f.dtype().kind() != 'i' && f.dtype().kind() != 'u')) {
    throw py::type_error("Convex: faces must be an (F, k) array of integers");
  }
  py::array_t<std::int64_t> fi =
      py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(f);
  if (fi.ndim() != 2 || fi.shape(1) < 3 || fi.shape(0) < 4) {
    throw py::value_error(
        "Convex: faces must be an (F, k) array, F >= 4 faces of k >= 3 "
        "vertex indices each, counter-clockwise seen from outside");
  }
  auto points = std::make_shared<std::vector<Eigen::Vector3d>>();
  for (py::ssize_t i = 0; i < v.shape(0); ++i) {
    const Eigen::Vector3d p(v.at(i, 0), v.at(i, 1), v.at(i, 2));
    if (!p.allFinite()) {
      throw py::value_error("Convex: vertices[" + std::to_string(i) + "] must be finite");
    }
    points->push_back(p);
  }
  auto encoded = std::make_shared<std::vector<int>>();
  for (py::ssize_t i = 0; i < fi.shape(0); ++i) {
    encoded->push_back(static_cast<int>(fi.shape(1)));
    for (py::ssize_t k = 0; k < fi.shape(1); ++k) {
      const std::int64_t index = fi.at(i, k);
      if (index < 0 || index >= v.shape(0)) {
        throw py::value_error("Convex: faces[" + std::to_string(i) + ", " + std::to_string(k) +
                              "] = " + std::to_string(index) + " is not a vertex index (0 to " +
                              std::to_string(v.shape(0) - 1) + ")");
      }
      encoded->push_back(static_cast<int>(index));
    }
  }
  return std::make_shared<fcl::Convex<double>>(points, static_cast<int>(fi.shape(0)), encoded,
                                               false);
}

/// The outward normal of a superellipsoid posed by X at a world point on its surface.
Eigen::Vector3d worldNormal(const PythonShape& shape, const fcl::Transform3<double>& X,
                            const Eigen::Vector3d& p_W) {
  return X.linear() * shape.normal(X.inverse() * p_W);
}

py::object pairDistance(const std::shared_ptr<Geometry>& a, const py::handle& pose_a,
                        const std::shared_ptr<Geometry>& b, const py::handle& pose_b) {
  if (!a || !b) throw py::type_error("distance: the shapes must not be None");
  bool first = true;
  const PythonShape& shape = superellipsoidOfPair(*a, *b, first, "distance");
  const fcl::Transform3<double> X_a = poseOf(pose_a, "pose1");
  const fcl::Transform3<double> X_b = poseOf(pose_b, "pose2");
  fcl::DistanceRequest<double> request(true);
  request.enable_signed_distance = true;
  fcl::DistanceResult<double> result;
  {
    py::gil_scoped_release release;
    fcl_superellipsoid::distance(a.get(), X_a, b.get(), X_b, request, result);
  }
  const Eigen::Vector3d p1 = result.nearest_points[0];
  const Eigen::Vector3d p2 = result.nearest_points[1];
  const double d = result.min_distance;
  Eigen::Vector3d gap = d >= 0 ? Eigen::Vector3d(p2 - p1) : Eigen::Vector3d(p1 - p2);
  Eigen::Vector3d normal;
  if (gap.norm() > 0) {
    normal = gap.normalized();
  } else if (first) {  // touching: the superellipsoid's own normal at its witness
    normal = worldNormal(shape, X_a, p1);
  } else {
    normal = -worldNormal(shape, X_b, p2);
  }
  return pair_distance_type(d, p1, p2, normal);
}

py::list pairCollide(const std::shared_ptr<Geometry>& a, const py::handle& pose_a,
                     const std::shared_ptr<Geometry>& b, const py::handle& pose_b,
                     int max_contacts) {
  if (!a || !b) throw py::type_error("collide: the shapes must not be None");
  if (max_contacts < 1) {
    throw py::value_error("collide: max_contacts must be >= 1, got " +
                          std::to_string(max_contacts));
  }
  bool first = true;
  superellipsoidOfPair(*a, *b, first, "collide");
  const fcl::Transform3<double> X_a = poseOf(pose_a, "pose1");
  const fcl::Transform3<double> X_b = poseOf(pose_b, "pose2");
  fcl::CollisionRequest<double> request(static_cast<std::size_t>(max_contacts), true);
  fcl::CollisionResult<double> result;
  {
    py::gil_scoped_release release;
    fcl_superellipsoid::collide(a.get(), X_a, b.get(), X_b, request, result);
  }
  py::list contacts;
  for (std::size_t i = 0; i < result.numContacts(); ++i) {
    const fcl::Contact<double>& c = result.getContact(i);
    contacts.append(
        contact_type(Eigen::Vector3d(c.pos), Eigen::Vector3d(c.normal), c.penetration_depth));
  }
  return contacts;
}

template <typename Shape>
using FclClass = py::class_<Shape, Geometry, std::shared_ptr<Shape>>;

/// A shape of a normal and an offset (halfspace, plane): the normal made unit, the offset
/// divided by the normal's length, so the set is the one the caller wrote.
template <typename Shape>
void bindNormalOffset(py::module_& m, const char* name, const char* doc) {
  FclClass<Shape>(m, name, doc)
      .def(py::init([where = std::string(name)](const py::handle& n, double d) {
             if (!std::isfinite(d)) throw py::value_error(where + ": offset must be finite");
             const Eigen::Vector3d raw = point3(n, (where + ": normal").c_str());
             const Eigen::Vector3d unit = unitNormal(n, (where + ": normal").c_str());
             return std::make_shared<Shape>(unit, d / raw.norm());
           }),
           py::arg("normal"), py::arg("offset"));
}

/// A shape of a radius and a length along z (capsule, cylinder, cone).
template <typename Shape>
void bindRadiusLength(py::module_& m, const char* name, const char* doc) {
  FclClass<Shape>(m, name, doc)
      .def(py::init([radius = std::string(name) + ": radius",
                     length = std::string(name) + ": length"](double r, double l) {
             return std::make_shared<Shape>(positive(r, radius.c_str()),
                                            positive(l, length.c_str()));
           }),
           py::arg("radius"), py::arg("length"))
      .def_readonly("radius", &Shape::radius)
      .def_readonly("length", &Shape::lz);
}

}  // namespace

void bindPairQueries(py::module_& m) {
  pair_distance_type = resultType(
      m, "PairDistance", {"distance", "point1", "point2", "normal"},
      "Signed distance (< 0: the penetration depth), the two witness points (world frame), and "
      "the unit normal from shape 1 to shape 2.");
  contact_type = resultType(m, "Contact", {"position", "normal", "depth"},
                            "A contact: its position (world frame), the unit normal from shape 1 "
                            "to shape 2, the penetration depth (> 0).");

  FclClass<fcl::Box<double>>(m, "Box", "FCL's box: side lengths x, y, z, centred at the origin.")
      .def(py::init([](double x, double y, double z) {
             return std::make_shared<fcl::Box<double>>(positive(x, "Box: x"), positive(y, "Box: y"),
                                                       positive(z, "Box: z"));
           }),
           py::arg("x"), py::arg("y"), py::arg("z"))
      .def_property_readonly("side",
                             [](const fcl::Box<double>& s) { return Eigen::Vector3d(s.side); });
  FclClass<fcl::Sphere<double>>(m, "Sphere", "FCL's sphere, centred at the origin.")
      .def(py::init([](double r) {
             return std::make_shared<fcl::Sphere<double>>(positive(r, "Sphere: radius"));
           }),
           py::arg("radius"))
      .def_readonly("radius", &fcl::Sphere<double>::radius);
  FclClass<fcl::Ellipsoid<double>>(m, "Ellipsoid", "FCL's ellipsoid: radii along x, y, z.")
      .def(py::init([](double a, double b, double c) {
             return std::make_shared<fcl::Ellipsoid<double>>(positive(a, "Ellipsoid: a"),
                                                             positive(b, "Ellipsoid: b"),
                                                             positive(c, "Ellipsoid: c"));
           }),
           py::arg("a"), py::arg("b"), py::arg("c"))
      .def_property_readonly(
          "radii", [](const fcl::Ellipsoid<double>& s) { return Eigen::Vector3d(s.radii); });
  bindRadiusLength<fcl::Capsule<double>>(
      m, "Capsule", "FCL's capsule: radius, and the length of its axis segment along z.");
  bindRadiusLength<fcl::Cylinder<double>>(m, "Cylinder",
                                          "FCL's cylinder: radius, and length along z.");
  bindRadiusLength<fcl::Cone<double>>(
      m, "Cone", "FCL's cone: base radius, and length along z (apex at +length/2).");
  FclClass<fcl::Convex<double>>(m, "Convex", R"doc(
FCL's convex polytope: vertices (N, 3) and faces (F, k) of vertex indices, each face a convex
polygon counter-clockwise seen from outside (a tessellation's triangles do).)doc")
      .def(py::init(&makeConvex), py::arg("vertices"), py::arg("faces"));
  FclClass<fcl::TriangleP<double>>(m, "Triangle", "FCL's triangle (TriangleP): three vertices.")
      .def(py::init([](const py::handle& a, const py::handle& b, const py::handle& c) {
             return std::make_shared<fcl::TriangleP<double>>(
                 point3(a, "Triangle: a"), point3(b, "Triangle: b"), point3(c, "Triangle: c"));
           }),
           py::arg("a"), py::arg("b"), py::arg("c"));
  bindNormalOffset<fcl::Halfspace<double>>(
      m, "Halfspace", "FCL's halfspace {x : normal . x <= offset}, normal made unit.");
  bindNormalOffset<fcl::Plane<double>>(m, "Plane",
                                       "FCL's plane {x : normal . x = offset}, normal made unit.");

  m.def("distance", &pairDistance, py::arg("shape1"), py::arg("pose1"), py::arg("shape2"),
        py::arg("pose2"), R"doc(
The signed distance between two posed shapes, one of them a Superellipsoid (float64):
PairDistance(distance, point1, point2, normal). Separated: the distance and the closest points.
Overlapping: minus the penetration depth (the shortest translation that separates them); each
point is its shape's support point along the normal, so moving shape 2 by point1 - point2
leaves them touching. normal: unit, from shape 1 to shape 2. Poses: None, (4, 4) or (R, t).)doc");
  m.def("collide", &pairCollide, py::arg("shape1"), py::arg("pose1"), py::arg("shape2"),
        py::arg("pose2"), py::arg("max_contacts") = 1, R"doc(
The contacts of two overlapping posed shapes, one of them a Superellipsoid: a list of
Contact(position, normal, depth), empty when they touch or are apart. One contact: position
halfway between the witnesses, normal from shape 1 to shape 2, depth the penetration depth
(= -distance). max_contacts > 1: the places of the pair's contact region (at most four, the
deepest first, each with its own depth; contact_manifolds() gives the whole region).)doc");
}

}  // namespace python
}  // namespace fcl_superellipsoid
