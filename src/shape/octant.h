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

#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {
namespace detail {

/// v (a first-octant vector) reflected into the octant of q: component i negated where
/// q[i] < 0.
template <typename S>
Vector3<S> intoOctantOf(const Vector3<S>& q, const Vector3<S>& v) {
  Vector3<S> out;
  for (int i = 0; i < 3; ++i) out[i] = q[i] < S(0) ? -v[i] : v[i];
  return out;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SHAPE_OCTANT_H
