#ifndef FSE_PYTHON_ARRAYS_H
#define FSE_PYTHON_ARRAYS_H
/// @file
/// numpy arrays in and out of the library (docs/python.md → "Arrays"): the checks every call
/// makes on its arguments, the result types, and result arrays that own the library's buffers.
#include <fcl/geometry/collision_geometry.h>
#include <fcl/math/geometry.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <initializer_list>
#include <string>

#include "python_shape.h"

namespace fcl_superellipsoid {
namespace python {

namespace py = pybind11;

/// The element type of a query: float32 arrays run the float library, everything else double.
enum class Precision { kFloat, kDouble };

/// Points given to a query, as the library reads them: a 3 × N column-major matrix whose
/// columns are the points, over the caller's buffer where its layout allows, else over a copy.
template <typename S>
class PointColumns {
 public:
  using Matrix = Eigen::Matrix<S, 3, Eigen::Dynamic>;
  using View = Eigen::Map<const Matrix, 0, Eigen::OuterStride<>>;

  /// `array` has been checked by pointsPrecision(): (N, 3) or (3,), of S's dtype.
  explicit PointColumns(const py::array& array);

  Eigen::Index count() const { return view_.cols(); }
  bool single() const { return single_; }  ///< given as one point of shape (3,)
  const View& view() const { return view_; }

 private:
  static View viewOf(const py::array& array, Matrix& copy, bool& single);

  bool single_ = false;
  Matrix copy_;
  View view_;
};

/// Reads `points` as query points: a numpy array (or anything numpy turns into one) of shape
/// (N, 3) or (3,). float32 and float64 arrays are used as they are; integer arrays and
/// non-arrays (lists, tuples) become float64. Any other dtype raises TypeError; a wrong shape
/// raises ValueError naming it. Returns the array to read and its precision.
std::pair<py::array, Precision> pointsArray(const py::handle& points, const char* name);

/// A pose: None (the identity), a 4 × 4 homogeneous matrix, or a pair (R, t) of a 3 × 3
/// rotation and a translation of 3. ValueError when it is not finite, not of those shapes,
/// its last row is not (0, 0, 0, 1), or R is not a rotation (RᵀR = I and det R = 1 to 1e-6).
fcl::Transform3<double> poseOf(const py::handle& pose, const char* name);

/// A vector of `n` finite numbers (a radius list, a normal, a vertex): ValueError otherwise.
Eigen::VectorXd finiteVector(const py::handle& values, Eigen::Index n, const char* name);

/// The Superellipsoid of a pair query's two shapes: `a` if it is one (shape_first = true), else
/// `b`. TypeError naming `call` where neither is.
const PythonShape& superellipsoidOfPair(const fcl::CollisionGeometry<double>& a,
                                        const fcl::CollisionGeometry<double>& b, bool& shape_first,
                                        const char* call);

/// A result type: a collections.namedtuple class `name` of `fields`, set as the module's
/// attribute. The handle stays valid for the process (the module holds the class).
py::handle resultType(py::module_& m, const char* name, std::initializer_list<const char*> fields,
                      const char* doc);

/// A new (rows,) or (rows, 3) array of S over the given memory, owned by `owner`.
template <typename S>
py::array_t<S> arrayOver(const S* data, Eigen::Index rows, bool vector3, py::object owner);

}  // namespace python
}  // namespace fcl_superellipsoid

#endif  // FSE_PYTHON_ARRAYS_H
