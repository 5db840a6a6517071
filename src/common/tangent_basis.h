#ifndef FCL_SUPERELLIPSOID_SRC_COMMON_TANGENT_BASIS_H
#define FCL_SUPERELLIPSOID_SRC_COMMON_TANGENT_BASIS_H

// Internal: an orthonormal basis of the plane ⊥ a unit vector, for the Newton steps on the
// sphere of directions (narrowphase/), the exact solver's tangent steps (solvers/, and their SIMD
// lanes in batch/) and the point derivatives' tangent plane.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>

namespace fcl_superellipsoid {
namespace detail {

/// The basis takes t1 = n × helper, helper = x̂ where |n_x| < this, else ŷ: |n × helper| ≥ 0.6
/// either way, so t1 never degenerates.
constexpr double kTangentHelperSwitch = 0.6;

/// (t1, t2): unit vectors completing the unit n to a right-handed orthonormal frame
/// (t1 = n × helper normalised, t2 = n × t1).
template <typename S>
std::array<Eigen::Matrix<S, 3, 1>, 2> tangentBasis(const Eigen::Matrix<S, 3, 1>& n) {
  using V = Eigen::Matrix<S, 3, 1>;
  const V helper = std::abs(n[0]) < S(kTangentHelperSwitch) ? V::UnitX() : V::UnitY();
  const V t1 = n.cross(helper).normalized();
  return {t1, n.cross(t1)};
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_COMMON_TANGENT_BASIS_H
