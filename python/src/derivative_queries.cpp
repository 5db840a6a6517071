// The derivative queries (docs/python.md → "Point queries", "Pair queries"):
// Superellipsoid.distance_gradients and distance_jacobians on points, through
// pointDistanceDerivatives() and batchDistanceDerivatives(); the module's distance_gradients and
// distance_jacobians on pairs, through pairDistanceDerivatives(). The GIL is released while the
// library works.
#include <fcl_superellipsoid/batch_distance.h>
#include <fcl_superellipsoid/pair_derivatives.h>
#include <fcl_superellipsoid/point_derivatives.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "arrays.h"
#include "bindings.h"
#include "query_arguments.h"

namespace fcl_superellipsoid {
namespace python {

namespace {

using Geometry = fcl::CollisionGeometry<double>;

/// The result types (resultType()), made at import.
py::handle gradients_type;
py::handle jacobians_type;
py::handle pair_gradients_type;
py::handle pair_jacobians_type;

/// (rows, columns) array of S: column j of the k × N matrix m as row j (a copy).
template <typename S, int K>
py::array_t<S> rowsOf(const Eigen::Matrix<S, K, Eigen::Dynamic>& m) {
  py::array_t<S> out({py::ssize_t(m.cols()), py::ssize_t{K}});
  auto view = out.template mutable_unchecked<2>();
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    for (int k = 0; k < K; ++k) view(j, k) = m(k, j);
  }
  return out;
}

template <typename S, int K>
py::array_t<S> vectorOf(const Eigen::Matrix<S, K, 1>& v) {
  py::array_t<S> out(K);
  for (int k = 0; k < K; ++k) out.mutable_at(k) = v[k];
  return out;
}

/// distance_gradients: one point through pointDistanceDerivatives(), (N, 3) arrays through
/// batchDistanceDerivatives() with the GIL released.
template <typename S>
py::object gradientQuery(const PythonShape& python_shape, const py::array& array,
                         const py::handle& pose, const QueryArguments& arguments) {
  const Superellipsoid<S>& shape = shapeIn<S>(python_shape);
  const fcl::Transform3<S> X_WS = poseOf(pose, "pose").cast<S>();
  const BatchOptions<S> options = arguments.options<S>();
  const PointColumns<S> points(array);
  if (points.single()) {
    const PointDistanceDerivatives<S> r =
        pointDistanceDerivatives(shape, X_WS, Vector3<S>(points.view().col(0)),
                                 DerivativeOrder::kGradient, options.distance);
    return gradients_type(r.value.distance, vectorOf<S, 3>(r.value.nearest_point),
                          vectorOf<S, 3>(r.value.normal), vectorOf<S, 6>(r.d_pose),
                          vectorOf<S, 5>(r.d_shape), py::bool_(r.differentiable));
  }
  BatchDerivativesResult<S> r;
  {
    py::gil_scoped_release release;
    batchDistanceDerivatives(shape, X_WS, points.view(), r, options);
  }
  const Eigen::Index n = points.count();
  py::array_t<S> distance(n);
  py::array_t<bool> differentiable(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    distance.mutable_at(i) = r.distance[i];
    differentiable.mutable_at(i) = r.differentiable[i];
  }
  return gradients_type(distance, rowsOf<S, 3>(r.nearest_point), rowsOf<S, 3>(r.normal),
                        rowsOf<S, 6>(r.d_pose), rowsOf<S, 5>(r.d_shape), differentiable);
}

/// (rows, columns) array of S, a copy of m.
template <typename S, int R, int C>
py::array_t<S> matrixOf(const Eigen::Matrix<S, R, C>& m) {
  py::array_t<S> out({py::ssize_t{R}, py::ssize_t{C}});
  auto view = out.template mutable_unchecked<2>();
  for (int r = 0; r < R; ++r) {
    for (int c = 0; c < C; ++c) view(r, c) = m(r, c);
  }
  return out;
}

/// (N, rows, columns) array of S: item i is `of(results[i])`.
template <typename S, int R, int C, typename Of>
py::array_t<S> stackOf(const std::vector<PointDistanceDerivatives<S>>& results, Of of) {
  const auto n = static_cast<py::ssize_t>(results.size());
  py::array_t<S> out({n, py::ssize_t{R}, py::ssize_t{C}});
  auto view = out.template mutable_unchecked<3>();
  for (py::ssize_t i = 0; i < n; ++i) {
    const Eigen::Matrix<S, R, C>& m = of(results[static_cast<std::size_t>(i)]);
    for (int r = 0; r < R; ++r) {
      for (int c = 0; c < C; ++c) view(i, r, c) = m(r, c);
    }
  }
  return out;
}

/// distance_jacobians: every point through pointDistanceDerivatives() with
/// DerivativeOrder::kJacobians, on the calling thread with the GIL released.
template <typename S>
py::object jacobianQuery(const PythonShape& python_shape, const py::array& array,
                         const py::handle& pose, const QueryArguments& arguments) {
  const Superellipsoid<S>& shape = shapeIn<S>(python_shape);
  const fcl::Transform3<S> X_WS = poseOf(pose, "pose").cast<S>();
  const DistanceOptions<S> options = arguments.options<S>().distance;
  const PointColumns<S> points(array);
  const auto n = static_cast<std::size_t>(points.count());
  std::vector<PointDistanceDerivatives<S>> results(n);
  {
    py::gil_scoped_release release;
    for (std::size_t i = 0; i < n; ++i) {
      try {
        results[i] = pointDistanceDerivatives(
            shape, X_WS, Vector3<S>(points.view().col(static_cast<Eigen::Index>(i))),
            DerivativeOrder::kJacobians, options);
      } catch (const std::invalid_argument& e) {
        if (points.single()) throw;
        throw std::invalid_argument("points[" + std::to_string(i) + "]: " + e.what());
      }
    }
  }
  if (points.single()) {
    const PointDistanceDerivatives<S>& r = results[0];
    return jacobians_type(r.value.distance, vectorOf<S, 3>(r.value.nearest_point),
                          vectorOf<S, 3>(r.value.normal), vectorOf<S, 6>(r.d_pose),
                          vectorOf<S, 5>(r.d_shape), py::bool_(r.differentiable),
                          matrixOf(r.nearest_point_d_query), matrixOf(r.nearest_point_d_pose),
                          matrixOf(r.nearest_point_d_shape), matrixOf(r.normal_d_query),
                          matrixOf(r.normal_d_pose), matrixOf(r.normal_d_shape));
  }
  using D = PointDistanceDerivatives<S>;
  const auto rows = static_cast<py::ssize_t>(n);
  py::array_t<S> distance(rows);
  py::array_t<bool> differentiable(rows);
  Eigen::Matrix<S, 3, Eigen::Dynamic> nearest(3, n), normal(3, n);
  Eigen::Matrix<S, 6, Eigen::Dynamic> d_pose(6, n);
  Eigen::Matrix<S, 5, Eigen::Dynamic> d_shape(5, n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto j = static_cast<Eigen::Index>(i);
    distance.mutable_at(j) = results[i].value.distance;
    differentiable.mutable_at(j) = results[i].differentiable;
    nearest.col(j) = results[i].value.nearest_point;
    normal.col(j) = results[i].value.normal;
    d_pose.col(j) = results[i].d_pose;
    d_shape.col(j) = results[i].d_shape;
  }
  return jacobians_type(
      distance, rowsOf<S, 3>(nearest), rowsOf<S, 3>(normal), rowsOf<S, 6>(d_pose),
      rowsOf<S, 5>(d_shape), differentiable,
      stackOf<S, 3, 3>(
          results, [](const D& r) -> const auto& { return r.nearest_point_d_query; }),
      stackOf<S, 3, 6>(
          results, [](const D& r) -> const auto& { return r.nearest_point_d_pose; }),
      stackOf<S, 3, 5>(
          results, [](const D& r) -> const auto& { return r.nearest_point_d_shape; }),
      stackOf<S, 3, 3>(
          results, [](const D& r) -> const auto& { return r.normal_d_query; }),
      stackOf<S, 3, 6>(
          results, [](const D& r) -> const auto& { return r.normal_d_pose; }),
      stackOf<S, 3, 5>(
          results, [](const D& r) -> const auto& { return r.normal_d_shape; }));
}

/// The pair's signed distance and its derivatives (pair_derivatives.h), in the caller's order:
/// the library answers (superellipsoid, other); where the superellipsoid is shape 2 the normal
/// turns and the two sides swap. `order` kJacobians adds the witnesses' and the normal's.
py::object pairDerivatives(const std::shared_ptr<Geometry>& a, const py::handle& pose_a,
                           const std::shared_ptr<Geometry>& b, const py::handle& pose_b,
                           DerivativeOrder order, const char* name) {
  if (!a || !b) throw py::type_error(std::string(name) + ": the shapes must not be None");
  bool first = true;
  const PythonShape& shape = superellipsoidOfPair(*a, *b, first, name);
  const fcl::Transform3<double> X_a = poseOf(pose_a, "pose1");
  const fcl::Transform3<double> X_b = poseOf(pose_b, "pose2");
  PairDistanceDerivatives<double> g;
  {
    py::gil_scoped_release release;
    g = first ? pairDistanceDerivatives<double>(shape, X_a, *b, X_b, order)
              : pairDistanceDerivatives<double>(shape, X_b, *a, X_a, order);
  }
  const py::object none = py::none();
  const py::object d_shape = py::cast(Eigen::VectorXd(g.d_shape));
  const py::object d_other_shape =
      g.other_is_superellipsoid ? py::cast(Eigen::VectorXd(g.d_other_shape)) : none;
  const Eigen::VectorXd d_pose = g.d_pose, d_other_pose = g.d_other_pose;
  using J = Eigen::MatrixXd;
  if (order == DerivativeOrder::kGradient) {
    if (first) {
      return pair_gradients_type(g.distance, g.on_shape, g.on_other, g.normal, d_pose, d_other_pose,
                                 d_shape, d_other_shape, g.differentiable);
    }
    return pair_gradients_type(g.distance, g.on_other, g.on_shape, Eigen::Vector3d(-g.normal),
                               d_other_pose, d_pose, d_other_shape, d_shape, g.differentiable);
  }
  if (first) {
    return pair_jacobians_type(
        g.distance, g.on_shape, g.on_other, g.normal, d_pose, d_other_pose, d_shape, d_other_shape,
        g.differentiable, J(g.on_shape_d_pose), J(g.on_shape_d_other_pose), J(g.on_other_d_pose),
        J(g.on_other_d_other_pose), J(g.normal_d_pose), J(g.normal_d_other_pose));
  }
  return pair_jacobians_type(g.distance, g.on_other, g.on_shape, Eigen::Vector3d(-g.normal),
                             d_other_pose, d_pose, d_other_shape, d_shape, g.differentiable,
                             J(g.on_other_d_other_pose), J(g.on_other_d_pose),
                             J(g.on_shape_d_other_pose), J(g.on_shape_d_pose),
                             J(-g.normal_d_other_pose), J(-g.normal_d_pose));
}

}  // namespace

void bindDerivativeQueries(py::module_& m, ShapeClass& shape) {
  gradients_type = resultType(
      m, "DistanceGradients",
      {"distance", "nearest_point", "normal", "d_pose", "d_shape", "differentiable"},
      "Per point: signed distance, nearest surface point, unit outward normal (also the "
      "gradient with respect to the point), the gradient with respect to the shape's pose as a "
      "twist (ω, v) in the world frame (6), with respect to its parameters (a1, a2, a3, ε1, ε2) "
      "(5), and whether the distance is differentiable there (False where the point has several "
      "nearest points: the gradients are then those of the returned one).");
  static const std::string gradients_doc =
      "DistanceGradients(distance (N,), nearest_point (N, 3), normal (N, 3), d_pose (N, 6), "
      "d_shape (N, 5), differentiable (N,)) of the exact signed distance for (N, 3) points; "
      "(float, (3,), (3,), (6,), (5,), bool) for one (3,) point. The pose twist (ω, v) moves the "
      "shape's points p by ω × p + v (world frame): d_pose = (n × N, −n).\n" +
      std::string(kOptionsDoc) +
      "\nmethod must be 'exact' (the derivatives are the exact distance's).";
  shape.def(
      "distance_gradients",
      [](const PythonShape& s, const py::handle& points, const py::handle& pose, std::string method,
         std::optional<double> tolerance, std::optional<int> max_iterations, int threads,
         bool vectorize) {
        if (method != "exact") {
          throw py::value_error("distance_gradients: method must be 'exact', got '" + method + "'");
        }
        auto [array, precision] = pointsArray(points, "points");
        const QueryArguments a{std::move(method), tolerance, max_iterations, threads, vectorize};
        if (precision == Precision::kFloat) return gradientQuery<float>(s, array, pose, a);
        return gradientQuery<double>(s, array, pose, a);
      },
      py::arg("points"), py::arg("pose") = py::none(), py::kw_only(), py::arg("method") = "exact",
      py::arg("tolerance") = py::none(), py::arg("max_iterations") = py::none(),
      py::arg("threads") = 0, py::arg("vectorize") = true, gradients_doc.c_str());
  jacobians_type = resultType(
      m, "DistanceJacobians",
      {"distance", "nearest_point", "normal", "d_pose", "d_shape", "differentiable",
       "nearest_point_d_point", "nearest_point_d_pose", "nearest_point_d_shape", "normal_d_point",
       "normal_d_pose", "normal_d_shape"},
      "Per point: the fields of DistanceGradients, and the Jacobians of the nearest point and of "
      "the normal with respect to the query point (3 × 3), the shape's pose twist (3 × 6) and its "
      "parameters (3 × 5), world frame. differentiable is also False where the point is at a "
      "centre of curvature of its nearest point (the nearest point's Jacobian is unbounded there: "
      "large and finite).");
  static const std::string jacobians_doc =
      "DistanceJacobians(distance, nearest_point, normal, d_pose, d_shape, differentiable, "
      "nearest_point_d_point (N, 3, 3), nearest_point_d_pose (N, 3, 6), nearest_point_d_shape "
      "(N, 3, 5), normal_d_point (N, 3, 3), normal_d_pose (N, 3, 6), normal_d_shape (N, 3, 5)) "
      "of the exact signed distance for (N, 3) points, the first six fields as "
      "distance_gradients gives them; for one (3,) point each Jacobian is a (3, k) array. Row r, "
      "column c of a Jacobian is the derivative of component r with respect to variable c; the "
      "twist as in distance_gradients. The points run one after the other on the calling thread "
      "with the GIL released (split a large array across Python threads for more cores).\n"
      "points, pose, tolerance, max_iterations: as for signed_distance. Raises ValueError naming "
      "a non-finite point's index.";
  shape.def(
      "distance_jacobians",
      [](const PythonShape& s, const py::handle& points, const py::handle& pose,
         std::optional<double> tolerance, std::optional<int> max_iterations) {
        auto [array, precision] = pointsArray(points, "points");
        const QueryArguments a{"exact", tolerance, max_iterations, 1, false};
        if (precision == Precision::kFloat) return jacobianQuery<float>(s, array, pose, a);
        return jacobianQuery<double>(s, array, pose, a);
      },
      py::arg("points"), py::arg("pose") = py::none(), py::kw_only(),
      py::arg("tolerance") = py::none(), py::arg("max_iterations") = py::none(),
      jacobians_doc.c_str());
  pair_gradients_type = resultType(
      m, "PairDistanceGradients",
      {"distance", "point1", "point2", "normal", "d_pose1", "d_pose2", "d_shape1", "d_shape2",
       "differentiable"},
      "A pair's signed distance, witnesses and normal (as PairDistance), with its gradient: "
      "d_pose1, d_pose2 (6,) with respect to a twist (omega, v) of each pose in the world frame; "
      "d_shape1, d_shape2 (5,) with respect to a Superellipsoid's (a1, a2, a3, eps1, eps2), None "
      "for another shape; differentiable, False where the pair has two shortest separating "
      "moves.");
  pair_jacobians_type = resultType(
      m, "PairDistanceJacobians",
      {"distance", "point1", "point2", "normal", "d_pose1", "d_pose2", "d_shape1", "d_shape2",
       "differentiable", "point1_d_pose1", "point1_d_pose2", "point2_d_pose1", "point2_d_pose2",
       "normal_d_pose1", "normal_d_pose2"},
      "PairDistanceGradients' fields, and the Jacobians (3, 6) of each witness point and of the "
      "normal with respect to each pose's twist (omega, v), world frame.");
  m.def(
      "distance_gradients",
      [](const std::shared_ptr<Geometry>& a, const py::handle& pose_a,
         const std::shared_ptr<Geometry>& b, const py::handle& pose_b) {
        return pairDerivatives(a, pose_a, b, pose_b, DerivativeOrder::kGradient,
                               "distance_gradients");
      },
      py::arg("shape1"), py::arg("pose1"), py::arg("shape2"), py::arg("pose2"), R"doc(
The signed distance of two posed shapes, one of them a Superellipsoid (float64), with its
gradient: PairDistanceGradients(distance, point1, point2, normal, d_pose1, d_pose2, d_shape1,
d_shape2, differentiable). distance, points and normal as distance() gives them. d_pose1 and
d_pose2 (6,): the derivatives with respect to a twist (omega, v) applied to each pose in the world
frame (pose <- exp(twist) pose: a point p of the shape moves by omega x p + v). d_shape1 and
d_shape2 (5,): with respect to a Superellipsoid's (a1, a2, a3, eps1, eps2), None for another
shape. differentiable: False where an overlapping pair has two shortest separating moves
(coincident centres, a partner centred on a symmetry plane); the gradient is then that of the
returned normal.)doc");
  m.def(
      "distance_jacobians",
      [](const std::shared_ptr<Geometry>& a, const py::handle& pose_a,
         const std::shared_ptr<Geometry>& b, const py::handle& pose_b) {
        return pairDerivatives(a, pose_a, b, pose_b, DerivativeOrder::kJacobians,
                               "distance_jacobians");
      },
      py::arg("shape1"), py::arg("pose1"), py::arg("shape2"), py::arg("pose2"), R"doc(
The fields of distance_gradients(), and the Jacobians of both witness points and of the normal
with respect to both pose twists: PairDistanceJacobians(..., point1_d_pose1, point1_d_pose2,
point2_d_pose1, point2_d_pose2, normal_d_pose1, normal_d_pose2), each (3, 6): row r, column c is
the derivative of component r with respect to twist component c (omega, v), world frame. They
are those of the feature that holds each witness (a point of a smooth surface, a vertex, an
edge, a face). differentiable is also False where the witnesses do not move smoothly (an overlap
whose depth is not a strict local minimum over directions); the Jacobians are then finite, of a
regularised system.)doc");
}

}  // namespace python
}  // namespace fcl_superellipsoid
