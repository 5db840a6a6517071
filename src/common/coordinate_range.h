#ifndef FCL_SUPERELLIPSOID_SRC_COMMON_COORDINATE_RANGE_H
#define FCL_SUPERELLIPSOID_SRC_COMMON_COORDINATE_RANGE_H

// Internal: the largest coordinate a query point, vertex or pose translation may have (docs/
// hardening.md → "Numeric range"): a quarter of the largest finite value. A point of such
// coordinates moved by such a translation still has a finite norm (at most √3/2 of the largest
// value), so every distance the library returns is finite.

#include <Eigen/Geometry>
#include <limits>
#include <string>

#include "common/invalid_argument.h"

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
constexpr S maxCoordinate() {
  return std::numeric_limits<S>::max() / 4;
}

/// True if every coefficient of v is within ±maxCoordinate<S>() (false for NaN).
template <typename Derived>
bool withinCoordinateRange(const Derived& v) {
  using S = typename Derived::Scalar;
  return (v.array().abs() <= maxCoordinate<S>()).all();
}

/// The error checkPose throws, out of line: the message's string building stays off the
/// callers' path, whose stack set-up would otherwise be a visible part of a cheap pair query.
template <typename S>
[[noreturn, gnu::cold, gnu::noinline]] void throwBadPose(
    const char* where, const char* name, const Eigen::Matrix<S, 3, 1>& translation) {
  throwInvalidArgument(where,
                       std::string("the pose ") + name +
                           " must be finite, its translation at most " +
                           formatValue(maxCoordinate<S>()) + " in magnitude",
                       translation);
}

/// Refuses a pose that is not finite or whose translation is beyond maxCoordinate():
/// "<where>: the pose <name> must be finite, its translation at most ..., got (x, y, z)".
template <typename S>
void checkPose(const char* where, const char* name,
               const Eigen::Transform<S, 3, Eigen::Isometry>& pose) {
  // x·0 is 0 for a finite x and NaN otherwise: one branch-free sum instead of 16 branches.
  const S zero = (pose.matrix().array() * S(0)).sum();
  if (!(zero == S(0)) || !withinCoordinateRange(pose.translation())) {
    throwBadPose<S>(where, name, pose.translation());
  }
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_COMMON_COORDINATE_RANGE_H
