// Superellipsoid.signed_distance, closest_points, within_margin and distance_gradients: one
// point through pointDistance() (pointDistanceDerivatives()), (N, 3) arrays through
// batchDistance() / verticesWithinMargin() (batchDistanceDerivatives()) with the GIL released
// (docs/python.md → "Point queries").
#include <fcl_superellipsoid/batch_distance.h>
#include <fcl_superellipsoid/point_derivatives.h>
#include <fcl_superellipsoid/point_distance.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>

#include "arrays.h"
#include "bindings.h"
#include "result_buffers.h"

namespace fcl_superellipsoid {
namespace python {

namespace {

/// The result types (resultType()), made at import.
py::handle point_query_type;
py::handle margin_query_type;
py::handle gradients_type;

/// The keyword options every point query takes, as Python gives them.
struct QueryArguments {
  std::string method;
  std::optional<double> tolerance;
  std::optional<int> max_iterations;
  int threads;
  bool vectorize;

  template <typename S>
  BatchOptions<S> options() const {
    DistanceMethod m;
    if (method == "exact") {
      m = DistanceMethod::kExact;
    } else if (method == "paper") {
      m = DistanceMethod::kPaper;
    } else if (method == "radial") {
      m = DistanceMethod::kRadial;
    } else {
      throw py::value_error("method must be 'exact', 'paper' or 'radial', got '" + method + "'");
    }
    if (threads < 0) {
      throw py::value_error("threads must be >= 0 (0: as many as TBB offers), got " +
                            std::to_string(threads));
    }
    BatchOptions<S> batch;
    batch.distance = DistanceOptions<S>::of(m);
    if (tolerance) batch.distance.tolerance = static_cast<S>(*tolerance);
    if (max_iterations) batch.distance.max_iterations = *max_iterations;
    batch.threads = threads;
    batch.vectorize = vectorize;
    return batch;
  }
};

template <typename S>
const Superellipsoid<S>& shapeIn(const PythonShape& shape) {
  if constexpr (std::is_same<S, float>::value) {
    return shape.asFloat();
  } else {
    return shape;
  }
}

enum class Answer { kDistance, kClosest };

template <typename S>
py::object pointQuery(const PythonShape& python_shape, const py::array& array,
                      const py::handle& pose, const QueryArguments& arguments, Answer answer) {
  const Superellipsoid<S>& shape = shapeIn<S>(python_shape);
  const fcl::Transform3<S> X_WS = poseOf(pose, "pose").cast<S>();
  const BatchOptions<S> options = arguments.options<S>();
  const PointColumns<S> points(array);
  if (points.single()) {
    const PointDistanceResult<S> r =
        pointDistance(shape, X_WS, Vector3<S>(points.view().col(0)), options.distance);
    if (answer == Answer::kDistance) return py::float_(r.distance);
    py::array_t<S> nearest(3), normal(3);
    for (int k = 0; k < 3; ++k) {
      nearest.mutable_at(k) = r.nearest_point(k);
      normal.mutable_at(k) = r.normal(k);
    }
    return point_query_type(r.distance, nearest, normal);
  }
  const Eigen::Index n = points.count();
  std::unique_ptr<BatchDistanceResult<S>> result = ResultBuffers<S>::take(n);
  {
    py::gil_scoped_release release;
    batchDistance(shape, X_WS, points.view(), *result, options);
  }
  const BatchDistanceResult<S>* r = result.get();
  py::capsule owner(result.release(), [](void* p) {
    ResultBuffers<S>::give(static_cast<BatchDistanceResult<S>*>(p));
  });
  py::array_t<S> distance = arrayOver(r->distance.data(), n, false, owner);
  if (answer == Answer::kDistance) return std::move(distance);
  return point_query_type(distance, arrayOver(r->nearest_point.data(), n, true, owner),
                          arrayOver(r->normal.data(), n, true, owner));
}

template <typename S>
py::object marginQuery(const PythonShape& python_shape, const py::array& array, double margin,
                       const py::handle& pose, const QueryArguments& arguments) {
  const Superellipsoid<S>& shape = shapeIn<S>(python_shape);
  const fcl::Transform3<S> X_WS = poseOf(pose, "pose").cast<S>();
  const BatchOptions<S> options = arguments.options<S>();
  const PointColumns<S> points(array);
  std::vector<VertexContact<S>> contacts;
  {
    py::gil_scoped_release release;
    verticesWithinMargin(shape, X_WS, points.view(), static_cast<S>(margin), contacts, options);
  }
  const auto k = static_cast<py::ssize_t>(contacts.size());
  py::array_t<std::int64_t> index(k);
  py::array_t<S> distance(k);
  py::array_t<S> nearest({k, py::ssize_t{3}});
  py::array_t<S> normal({k, py::ssize_t{3}});
  for (py::ssize_t i = 0; i < k; ++i) {
    const VertexContact<S>& c = contacts[static_cast<std::size_t>(i)];
    index.mutable_at(i) = c.index;
    distance.mutable_at(i) = c.distance;
    for (int j = 0; j < 3; ++j) {
      nearest.mutable_at(i, j) = c.nearest_point(j);
      normal.mutable_at(i, j) = c.normal(j);
    }
  }
  return margin_query_type(index, distance, nearest, normal);
}

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

py::object dispatch(const PythonShape& shape, const py::handle& points, const py::handle& pose,
                    const QueryArguments& arguments, Answer answer) {
  auto [array, precision] = pointsArray(points, "points");
  if (precision == Precision::kFloat)
    return pointQuery<float>(shape, array, pose, arguments, answer);
  return pointQuery<double>(shape, array, pose, arguments, answer);
}

const char* const kOptionsDoc = R"doc(
points: (N, 3) or (3,) array, float32 or float64 (integers are read as float64), any strides;
        a C-contiguous array is read in place. float32 points run the library in float.
pose: the shape's pose in the world (the points' frame): None (identity), a (4, 4) matrix,
      or (R, t). Results are in the world frame.
method: 'exact' (default; to machine precision), 'paper' (the reference paper's iteration,
        tolerance 1e-3), 'radial' (one evaluation along the ray from the centre).
tolerance: relative to the shape's size; None for the method's default (exact: 1e-12 in
           float64, 1e-6 in float32; paper: 1e-3).
max_iterations: None for the method's default (exact 250, paper 30).
threads: 0 for as many as TBB offers, 1 for the calling thread only, n for at most n.
vectorize: the exact method on SIMD lanes (default); False runs every point through the
           scalar solver (bitwise the answers of one-point calls).
The sign: distance > 0 outside, < 0 inside (FCL's and Open3D's convention; trimesh's is the
opposite). Raises ValueError for a non-finite point (naming its index), a bad shape or option;
TypeError for another dtype.)doc";

/// Binds signed_distance or closest_points: the points, the pose, then the keyword options.
void defPointQuery(ShapeClass& shape, const char* name, Answer answer, const std::string& doc) {
  shape.def(
      name,
      [answer](const PythonShape& s, const py::handle& points, const py::handle& pose,
               std::string method, std::optional<double> tolerance,
               std::optional<int> max_iterations, int threads, bool vectorize) {
        return dispatch(
            s, points, pose,
            QueryArguments{std::move(method), tolerance, max_iterations, threads, vectorize},
            answer);
      },
      py::arg("points"), py::arg("pose") = py::none(), py::kw_only(), py::arg("method") = "exact",
      py::arg("tolerance") = py::none(), py::arg("max_iterations") = py::none(),
      py::arg("threads") = 0, py::arg("vectorize") = true, doc.c_str());
}

}  // namespace

void bindPointQueries(py::module_& m, ShapeClass& shape) {
  point_query_type = resultType(m, "PointQuery", {"distance", "nearest_point", "normal"},
                                "Per point: signed distance (< 0 inside), nearest surface point "
                                "and unit outward normal there, world frame.");
  margin_query_type = resultType(
      m, "MarginQuery", {"index", "distance", "nearest_point", "normal"},
      "The points within the margin, in increasing index order: their indices in the input, "
      "signed distances, nearest surface points and normals.");

  // pybind11 keeps a pointer to a docstring: these live as long as the process.
  static const std::string distance_doc =
      "Signed distance of each point to the surface: (N,) array, or a float for one (3,) "
      "point.\n" +
      std::string(kOptionsDoc);
  static const std::string closest_doc =
      "PointQuery(distance (N,), nearest_point (N, 3), normal (N, 3)) for (N, 3) points; "
      "(float, (3,), (3,)) for one (3,) point.\n" +
      std::string(kOptionsDoc);
  static const std::string margin_doc =
      "MarginQuery(index, distance, nearest_point, normal) of the points whose signed distance "
      "is <= margin; points farther than the margin from the shape's bounding box are dropped "
      "without a solver call (a cloth's or a cloud's contacts in one call).\n" +
      std::string(kOptionsDoc);
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
  defPointQuery(shape, "signed_distance", Answer::kDistance, distance_doc);
  defPointQuery(shape, "closest_points", Answer::kClosest, closest_doc);
  shape.def(
      "within_margin",
      [](const PythonShape& s, const py::handle& points, double margin, const py::handle& pose,
         std::string method, std::optional<double> tolerance, std::optional<int> max_iterations,
         int threads, bool vectorize) {
        auto [array, precision] = pointsArray(points, "points");
        const QueryArguments a{std::move(method), tolerance, max_iterations, threads, vectorize};
        if (precision == Precision::kFloat) return marginQuery<float>(s, array, margin, pose, a);
        return marginQuery<double>(s, array, margin, pose, a);
      },
      py::arg("points"), py::arg("margin"), py::arg("pose") = py::none(), py::kw_only(),
      py::arg("method") = "exact", py::arg("tolerance") = py::none(),
      py::arg("max_iterations") = py::none(), py::arg("threads") = 0, py::arg("vectorize") = true,
      margin_doc.c_str());
}

}  // namespace python
}  // namespace fcl_superellipsoid
