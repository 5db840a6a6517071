#ifndef FCL_SUPERELLIPSOID_SRC_SHAPE_SYMMETRIC2_H
#define FCL_SUPERELLIPSOID_SRC_SHAPE_SYMMETRIC2_H

// Internal: the eigenvalues of a symmetric 2×2 block [b11, b12; b12, b22], as the principal
// radii (shape/curvature.cpp) and the Newton matrix's tangent curvatures (solvers/exact_rules.h)
// need them: without cancellation where one is many orders of magnitude above the other (near
// a face or a crease, where mean − half-gap rounds the smaller one to nothing).

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace fcl_superellipsoid {
namespace detail {

/// 2^e, for the constants below.
template <typename S>
constexpr S powerOfTwo(int e) {
  S r = S(1);
  for (; e > 0; --e) r *= S(2);
  for (; e < 0; ++e) r /= S(2);
  return r;
}

/// √(a² + b²) without overflow or underflow. std::hypot scales its arguments on every call and
/// costs as much as a power; the Newton iterations take two or three of these each. Where the
/// larger magnitude m lies within 2^±(max_exponent/2 − 2) (2^±510 in double), the squares
/// neither overflow nor lose m's digits (the smaller square may underflow only where it is
/// below m's last digit), so the plain formula is within an ulp of std::hypot; outside that
/// range, and for infinities and NaN, std::hypot answers.
template <typename S>
S hypot2(S a, S b) {
  constexpr int kHalf = std::numeric_limits<S>::max_exponent / 2 - 2;
  constexpr S kLow = powerOfTwo<S>(-kHalf), kHigh = powerOfTwo<S>(kHalf);
  const S m = std::max(std::abs(a), std::abs(b));
  if (m >= kLow && m <= kHigh) return std::sqrt(a * a + b * b);
  return std::hypot(a, b);
}

template <typename S>
struct Eigenvalues2 {
  S lowest, highest;
  S half_gap;  // √(((b11 − b22)/2)² + b12²), half their distance
};

/// The eigenvalue of larger magnitude is mean ± half-gap (no cancellation); the other is
/// det / that one.
template <typename S>
Eigenvalues2<S> eigenvalues2(S b11, S b12, S b22) {
  const S mean = (b11 + b22) / 2, half_gap = hypot2((b11 - b22) / 2, b12);
  const S det = std::fma(b11, b22, -b12 * b12);
  const bool positive = mean >= S(0);
  const S big = positive ? mean + half_gap : mean - half_gap;
  const S small = big != S(0) ? det / big : S(0);
  return positive ? Eigenvalues2<S>{small, big, half_gap} : Eigenvalues2<S>{big, small, half_gap};
}

/// The unit eigenvector (c, s) of the lower eigenvalue, up to sign, from `half_gap` of
/// eigenvalues2: the column of B − lowest·I with no cancellation, (b12, −(half_diff + half_gap))
/// where b11 ≥ b22, else (half_diff − half_gap, b12), with half_diff = (b11 − b22)/2. The higher
/// eigenvalue's is (−s, c). Where half_gap = 0 the block is a multiple of I and every unit vector
/// is one: (1, 0).
template <typename S>
std::pair<S, S> lowerEigenvector(S b11, S b12, S b22, S half_gap) {
  const S half_diff = (b11 - b22) / 2;
  S c = b12, s = -(half_diff + half_gap);
  if (half_diff < S(0)) {
    c = half_diff - half_gap;
    s = b12;
  }
  const S length = hypot2(c, s);
  if (!(length > S(0))) return {S(1), S(0)};
  return {c / length, s / length};
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SHAPE_SYMMETRIC2_H
