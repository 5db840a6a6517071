// Superellipsoid's own members in Python: parameters, mass properties, support points,
// tessellation, containment (docs/python.md → "The shape").
#include <fcl_superellipsoid/tessellation.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstring>
#include <sstream>
#include <vector>

#include "arrays.h"
#include "bindings.h"

namespace fcl_superellipsoid {
namespace python {

namespace {

std::shared_ptr<PythonShape> makeShape(const py::handle& radii, const py::handle& exponents) {
  const Eigen::VectorXd r = finiteVector(radii, 3, "Superellipsoid: radii");
  const Eigen::VectorXd e = finiteVector(exponents, 2, "Superellipsoid: exponents");
  return std::make_shared<PythonShape>(Eigen::Vector3d(r), e(0), e(1));
}

void checkFinite(const Eigen::Vector3d& v, Eigen::Index i, const char* name) {
  if (!v.allFinite()) {
    std::ostringstream text;
    text.precision(17);
    text << name << "[" << i << "] must be finite, got (" << v(0) << ", " << v(1) << ", " << v(2)
         << ")";
    throw py::value_error(text.str());
  }
}

/// Calls f(v) for each row v of an (N, 3) or (3,) array, read as double and checked finite;
/// returns whether it was one (3,) point.
template <typename F>
bool forEachRow(const py::handle& values, const char* name, F f) {
  const py::array array =
      py::array_t<double, py::array::forcecast>::ensure(pointsArray(values, name).first);
  const PointColumns<double> rows(array);  // a view of `array`, which outlives it here
  for (Eigen::Index i = 0; i < rows.count(); ++i) {
    const Eigen::Vector3d v = rows.view().col(i);
    checkFinite(v, i, name);
    f(v);
  }
  return rows.single();
}

}  // namespace

ShapeClass bindShape(py::module_& m) {
  py::class_<fcl::CollisionGeometry<double>, std::shared_ptr<fcl::CollisionGeometry<double>>>(
      m, "Shape", "A collision geometry: the base class of Superellipsoid and FCL's shapes.");

  ShapeClass shape(m, "Superellipsoid", R"doc(
A superellipsoid centred at the origin of its frame, axis-aligned in that frame.

F(x) = (|x/a1|^(2/e1) + |y/a2|^(2/e1))^(e1/e2) + |z/a3|^(2/e2); the surface is F = 1.

radii: (a1, a2, a3), each > 0, the largest at most 1e8 times the smallest.
exponents: (e1, e2), each in (0, 2): e1 shapes the xy-plane, e2 the z direction.
Raises ValueError naming a bad value.)doc");
  shape.def(py::init(&makeShape), py::arg("radii"), py::arg("exponents"));
  shape.def_property_readonly(
      "radii", [](const PythonShape& s) { return Eigen::Vector3d(s.radii()); },
      "(a1, a2, a3) as an array of 3.");
  shape.def_property_readonly(
      "exponents", [](const PythonShape& s) { return py::make_tuple(s.eps1(), s.eps2()); },
      "(e1, e2).");
  shape.def_property_readonly("size", &PythonShape::size,
                              "The largest radius: the unit of every relative tolerance.");
  shape.def_property_readonly("volume", &PythonShape::computeVolume, "The enclosed volume.");
  shape.def_property_readonly(
      "inertia", [](const PythonShape& s) { return Eigen::Matrix3d(s.computeMomentofInertia()); },
      "The 3 x 3 moment of inertia about the centre, in the shape's frame, at unit density "
      "(multiply by the density; the mass is volume x density).");
  shape.def(
      "support",
      [](const PythonShape& s, const py::handle& directions) {
        std::vector<Eigen::Vector3d> support;
        const bool single =
            forEachRow(directions, "support: directions",
                       [&](const Eigen::Vector3d& u) { support.push_back(s.supportPoint(u)); });
        const auto n = static_cast<py::ssize_t>(support.size());
        py::array_t<double> out =
            single ? py::array_t<double>(3) : py::array_t<double>({n, py::ssize_t{3}});
        for (py::ssize_t i = 0; i < n; ++i) {
          std::memcpy(out.mutable_data() + 3 * i, support[std::size_t(i)].data(),
                      3 * sizeof(double));
        }
        return out;
      },
      py::arg("directions"), R"doc(
The support points: for each direction u (a row of an (N, 3) array, or one (3,) vector, any
length) the surface point x that maximises u . x, in the shape's frame. The zero direction
gives (a1, 0, 0).)doc");
  shape.def(
      "contains",
      [](const PythonShape& s, const py::handle& points) -> py::object {
        std::vector<bool> inside;
        const bool single = forEachRow(points, "contains: points", [&](const Eigen::Vector3d& p) {
          inside.push_back(s.contains(p));
        });
        if (single) return py::bool_(inside[0]);
        py::array_t<bool> out(static_cast<py::ssize_t>(inside.size()));
        for (std::size_t i = 0; i < inside.size(); ++i) out.mutable_at(py::ssize_t(i)) = inside[i];
        return std::move(out);
      },
      py::arg("points"),
      "Whether each point (shape frame) is inside or on the surface: (N,) bools, or one bool.");
  shape.def(
      "tessellate",
      [](const PythonShape& s, int num_vertices) {
        const TriangleMesh<double> mesh =
            tessellate(static_cast<const Superellipsoid<double>&>(s), num_vertices);
        const auto nv = static_cast<py::ssize_t>(mesh.vertices.size());
        const auto nf = static_cast<py::ssize_t>(mesh.triangles.size());
        py::array_t<double> vertices({nv, py::ssize_t{3}});
        py::array_t<std::int64_t> faces({nf, py::ssize_t{3}});
        for (py::ssize_t i = 0; i < nv; ++i) {
          for (int k = 0; k < 3; ++k) vertices.mutable_at(i, k) = mesh.vertices[i](k);
        }
        for (py::ssize_t i = 0; i < nf; ++i) {
          for (int k = 0; k < 3; ++k) faces.mutable_at(i, k) = mesh.triangles[i][k];
        }
        return py::make_tuple(vertices, faces);
      },
      py::arg("num_vertices"), R"doc(
A closed triangle mesh with exactly num_vertices vertices (5 to 1e8), every one on the surface:
(vertices (n, 3) float64, faces (m, 3) int64), faces counter-clockwise seen from outside.)doc");
  shape.def("__repr__", [](const PythonShape& s) {
    const auto number = [](double x) { return py::repr(py::float_(x)).cast<std::string>(); };
    return "Superellipsoid(radii=(" + number(s.radii()(0)) + ", " + number(s.radii()(1)) + ", " +
           number(s.radii()(2)) + "), exponents=(" + number(s.eps1()) + ", " + number(s.eps2()) +
           "))";
  });
  shape.def(py::pickle(
      [](const PythonShape& s) {
        return py::make_tuple(Eigen::Vector3d(s.radii()), py::make_tuple(s.eps1(), s.eps2()));
      },
      [](const py::tuple& state) { return makeShape(state[0], state[1]); }));
  return shape;
}

}  // namespace python
}  // namespace fcl_superellipsoid
