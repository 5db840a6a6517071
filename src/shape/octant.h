#ifndef FCL_SUPERELLIPSOID_SRC_SHAPE_OCTANT_H
#define FCL_SUPERELLIPSOID_SRC_SHAPE_OCTANT_H

// Internal: the reflection between the first octant and any other, the one rule behind every
// "solve for |Q|, then reflect back" in the library.
//
// A superellipsoid is symmetric in each coordinate plane of its frame, so G, h and the nearest
// point problem are solved for |Q| (componentwise) and their vector answers are reflected back
// into Q's octant. A coordinate of Q that is exactly 0 counts as positive: that is the
// tie-break of point_distance.h for queries on a symmetry plane. Used by the shape
// (gaugeGradient, supportPoint), the scalar Exact solver and the batched path.

#include <cstdint>
#include <cstring>
#include <type_traits>

#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {
namespace detail {

/// −x where `negate`, else x; bit for bit what the unary minus gives, without a branch (the
/// batched path reflects answers for queries whose signs are random, and a mispredicted branch
/// per coordinate costs more than the rest of the reflection).
template <typename S>
S negatedWhere(bool negate, S x) {
  static_assert(std::is_floating_point<S>::value && (sizeof(S) == 4 || sizeof(S) == 8),
                "an IEEE float or double");
  using Bits = std::conditional_t<sizeof(S) == 8, std::uint64_t, std::uint32_t>;
  Bits bits;
  std::memcpy(&bits, &x, sizeof(S));
  bits ^= Bits(negate) << (8 * sizeof(S) - 1);  // the sign bit
  std::memcpy(&x, &bits, sizeof(S));
  return x;
}

/// v (a first-octant vector) reflected into the octant of q: component i negated where
/// q[i] < 0.
template <typename S>
Vector3<S> intoOctantOf(const Vector3<S>& q, const Vector3<S>& v) {
  Vector3<S> out;
  for (int i = 0; i < 3; ++i) out[i] = negatedWhere(q[i] < S(0), v[i]);
  return out;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SHAPE_OCTANT_H
