#ifndef FSE_PYTHON_BINDINGS_H
#define FSE_PYTHON_BINDINGS_H
/// @file
/// The module's parts, one per file; module.cpp calls them in this order.
#include <fcl/geometry/collision_geometry.h>
#include <pybind11/pybind11.h>

#include <memory>

#include "python_shape.h"

namespace fcl_superellipsoid {
namespace python {

namespace py = pybind11;

using ShapeClass =
    py::class_<PythonShape, fcl::CollisionGeometry<double>, std::shared_ptr<PythonShape>>;

/// shape_bindings.cpp: the base class Shape and Superellipsoid's parameters, mass properties,
/// support points and tessellation.
ShapeClass bindShape(py::module_& m);
/// point_queries.cpp: Superellipsoid.signed_distance, closest_points, within_margin.
void bindPointQueries(py::module_& m, ShapeClass& shape);
/// pair_queries.cpp: FCL's shapes and the pair queries distance() and collide().
void bindPairQueries(py::module_& m);
/// derivative_queries.cpp: Superellipsoid.distance_gradients and distance_jacobians, and the
/// pair queries distance_gradients() and distance_jacobians().
void bindDerivativeQueries(py::module_& m, ShapeClass& shape);
/// manifold_queries.cpp: Mesh and contact_manifolds().
void bindManifoldQueries(py::module_& m);

}  // namespace python
}  // namespace fcl_superellipsoid

#endif  // FSE_PYTHON_BINDINGS_H
