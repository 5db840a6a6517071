#ifndef FCL_SUPERELLIPSOID_SRC_COMMON_CROSS_PRODUCT_H
#define FCL_SUPERELLIPSOID_SRC_COMMON_CROSS_PRODUCT_H

// Internal: a × b of 3-vectors, written out. Eigen's vectorised cross product of float
// 3-vectors loads 4 floats, one past the end of a vector (AddressSanitizer reports it).

#include <Eigen/Core>

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
Eigen::Matrix<S, 3, 1> crossOf(const Eigen::Matrix<S, 3, 1>& a, const Eigen::Matrix<S, 3, 1>& b) {
  return Eigen::Matrix<S, 3, 1>(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                                a[0] * b[1] - a[1] * b[0]);
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_COMMON_CROSS_PRODUCT_H
