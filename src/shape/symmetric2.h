#ifndef FCL_SUPERELLIPSOID_SRC_SHAPE_SYMMETRIC2_H
#define FCL_SUPERELLIPSOID_SRC_SHAPE_SYMMETRIC2_H

// Internal: the eigenvalues of a symmetric 2×2 block [b11, b12; b12, b22], as the principal
// radii (shape/curvature.cpp) and the Newton matrix's tangent curvatures (solvers/exact_rules.h)
// need them: without cancellation where one is many orders of magnitude above the other (near
// a face or a crease, where mean − half-gap rounds the smaller one to nothing).

#include <cmath>

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
struct Eigenvalues2 {
  S lowest, highest;
};

/// The eigenvalue of larger magnitude is mean ± half-gap (no cancellation); the other is
/// det / that one.
template <typename S>
Eigenvalues2<S> eigenvalues2(S b11, S b12, S b22) {
  const S mean = (b11 + b22) / 2, half_gap = std::hypot((b11 - b22) / 2, b12);
  const S det = std::fma(b11, b22, -b12 * b12);
  const bool positive = mean >= S(0);
  const S big = positive ? mean + half_gap : mean - half_gap;
  const S small = big != S(0) ? det / big : S(0);
  return positive ? Eigenvalues2<S>{small, big} : Eigenvalues2<S>{big, small};
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SHAPE_SYMMETRIC2_H
