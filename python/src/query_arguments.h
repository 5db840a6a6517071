#ifndef FSE_PYTHON_QUERY_ARGUMENTS_H
#define FSE_PYTHON_QUERY_ARGUMENTS_H
/// @file
/// What every point query takes beside its points (docs/python.md → "Point queries"): the
/// keyword options as Python gives them, their docstring, and the shape in the points'
/// precision.
#include <fcl_superellipsoid/batch_distance.h>
#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <type_traits>

#include "python_shape.h"

namespace fcl_superellipsoid {
namespace python {

namespace py = pybind11;

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

/// The shape a query on points of type S runs on: the double shape, or its float copy.
template <typename S>
const Superellipsoid<S>& shapeIn(const PythonShape& shape) {
  if constexpr (std::is_same<S, float>::value) {
    return shape.asFloat();
  } else {
    return shape;
  }
}

/// The docstring of the keywords above, appended to each point query's own.
inline constexpr const char* kOptionsDoc = R"doc(
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

}  // namespace python
}  // namespace fcl_superellipsoid

#endif  // FSE_PYTHON_QUERY_ARGUMENTS_H
