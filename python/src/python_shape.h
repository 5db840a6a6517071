#ifndef FSE_PYTHON_PYTHON_SHAPE_H
#define FSE_PYTHON_PYTHON_SHAPE_H
/// @file
/// The Superellipsoid as Python holds it: the double shape (what pair queries and float64
/// points use) and, made on first use, the same shape in float for float32 points.
#include <fcl_superellipsoid/superellipsoid.h>

#include <memory>
#include <mutex>

namespace fcl_superellipsoid {
namespace python {

class PythonShape : public Superellipsoid<double> {
 public:
  PythonShape(const Vector3<double>& radii, double eps1, double eps2)
      : Superellipsoid<double>(radii, eps1, eps2) {}

  /// The shape in float (its parameters rounded to float). Thread-safe; built once.
  /// @throws std::invalid_argument if the rounded parameters are outside float's range.
  const Superellipsoid<float>& asFloat() const {
    std::lock_guard<std::mutex> lock(float_mutex_);
    if (!float_) {
      float_ = std::make_shared<const Superellipsoid<float>>(
          radii().cast<float>().eval(), static_cast<float>(eps1()), static_cast<float>(eps2()));
    }
    return *float_;
  }

 private:
  mutable std::mutex float_mutex_;
  mutable std::shared_ptr<const Superellipsoid<float>> float_;
};

}  // namespace python
}  // namespace fcl_superellipsoid

#endif  // FSE_PYTHON_PYTHON_SHAPE_H
