#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SHAPE_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SHAPE_PAIR_H

// Internal: what the narrowphase sees of a pair, and what it answers. The superellipsoid and
// its pose; the other geometry comes beside it, as FCL's shape class (fcl::Box, fcl::Capsule,
// …), and its pose. No FCL dispatch, request or result: the FCL glue (fcl_glue/pairs.cpp)
// recognises the other geometry, calls the pair kind's function and writes the answer into
// FCL's result in the caller's order.

#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {
namespace detail {

/// The superellipsoid S with its pose X_WS, and the pose X_WO of the other geometry O.
template <typename S>
struct ShapePair {
  const Superellipsoid<S>* shape = nullptr;
  const fcl::Transform3<S>* X_WS = nullptr;
  const fcl::Transform3<S>* X_WO = nullptr;
};

/// A pair's answer, in world coordinates: the signed distance (< 0: overlapping, minus the
/// depth), the point on the other geometry, the point on the shape, the shape's outward normal
/// towards the other, and the other's primitive (−1 where it has none).
template <typename S>
struct PairHit {
  S distance;
  Vector3<S> on_other, on_shape, normal;
  int other_primitive;
};

/// The superellipsoid's support point along the world direction v.
template <typename S>
Vector3<S> shapeSupport(const ShapePair<S>& pair, const Vector3<S>& v) {
  return *pair.X_WS * pair.shape->supportPoint(Vector3<S>(pair.X_WS->linear().transpose() * v));
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SHAPE_PAIR_H
