// Superellipsoid.signed_distance, closest_points and within_margin: one point through
// pointDistance(), (N, 3) arrays through batchDistance() / verticesWithinMargin() with the GIL
// released (docs/python.md → "Point queries"). Their derivatives: derivative_queries.cpp.
#include <fcl_superellipsoid/batch_distance.h>
#include <fcl_superellipsoid/point_distance.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>

#include "arrays.h"
#include "bindings.h"
#include "query_arguments.h"
#include "result_buffers.h"

namespace fcl_superellipsoid {
namespace python {

namespace {

/// The result types (resultType()), made at import.
py::handle point_query_type;
py::handle margin_query_type;

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

py::object dispatch(const PythonShape& shape, const py::handle& points, const py::handle& pose,
                    const QueryArguments& arguments, Answer answer) {
  auto [array, precision] = pointsArray(points, "points");
  if (precision == Precision::kFloat)
    return pointQuery<float>(shape, array, pose, arguments, answer);
  return pointQuery<double>(shape, array, pose, arguments, answer);
}

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
