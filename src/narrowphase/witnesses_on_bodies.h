#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_WITNESSES_ON_BODIES_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_WITNESSES_ON_BODIES_H

// Internal: a pair's witnesses, each on its own body (docs/math.md → "Shape pairs", witnesses
// on flat faces). Where both bodies' support sets along the normal are faces (a box-like body
// lying on a floor, a box face down on a box-like face), the distance and the normal are
// unique but the witnesses are not, and a solver that builds one witness from the other
// (on_other = on_shape + d·n) or moves them to first order along huge support Hessians can
// hand back a point beside the other body's face. Such a pair is replaced by one that is on
// both bodies and as far apart, found above a point of either face.

#include <algorithm>
#include <cmath>
#include <optional>

#include "fcl_superellipsoid/superellipsoid.h"
#include "narrowphase/contact_region.h"
#include "narrowphase/shape_pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// Whether x is a point of `body` at its supporting plane along the unit m: on its surface
/// (the gauge, for a smooth body) or where the body ends along m on the line through x (a line
/// that misses the body, or ends elsewhere, is not), within `tolerance` (length).
template <typename S>
bool atSupportPlane(const RegionBody<S>& body, const Vector3<S>& x, const Vector3<S>& m,
                    S tolerance) {
  S value;
  Vector3<S> gradient;
  Matrix3<S> hessian;
  if (body.gauge(x, value, gradient, hessian)) {
    return std::abs(value - S(1)) * body.size() <= tolerance;
  }
  const std::optional<S> end = body.extent(x, m);
  return end && std::abs(*end) <= tolerance;
}

/// The hit with its witnesses on both bodies, d·n apart: as it is where they are (within 1e-8 ×
/// the larger body's size), else the first pair that is, of: the other's support point along −n
/// with the point d·n before it, the shape's support point along n with the point d·n beyond it,
/// and the middle of those two pairs; as it is if none is (the distance and normal are kept
/// always).
template <typename S>
PairHit<S> witnessesOnBodies(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS,
                             const RegionBody<S>& other, const PairHit<S>& hit) {
  const Vector3<S> n = hit.normal.normalized();
  const S tolerance = S(1e-8) * std::max(shape.size(), other.size());
  const auto onBoth = [&](const Vector3<S>& on_shape, const Vector3<S>& on_other) {
    // A point farther from the shape's centre than twice its largest radius is not on it (and
    // is not measured: a far partner's line extents can overflow).
    const Vector3<S> local = X_WS.linear().transpose() * (on_shape - X_WS.translation());
    if (!(local.norm() <= S(2) * shape.size()) || !on_other.allFinite()) return false;
    return std::abs(shape.gauge(local) - S(1)) * shape.size() <= tolerance &&
           atSupportPlane(other, on_other, Vector3<S>(-n), tolerance);
  };
  const S d = hit.distance;
  if (!n.allFinite() || (onBoth(hit.on_shape, hit.on_other) &&
                         (hit.on_other - hit.on_shape - d * n).norm() <= tolerance)) {
    return hit;
  }
  const Vector3<S> other_face = other.support(Vector3<S>(-n));
  const Vector3<S> shape_face =
      X_WS * shape.supportPoint(Vector3<S>(X_WS.linear().transpose() * n));
  const Vector3<S> middle = S(0.5) * (other_face - d * n + shape_face);
  for (const Vector3<S>& on_shape : {Vector3<S>(other_face - d * n), shape_face, middle}) {
    const Vector3<S> on_other = on_shape + d * n;
    if (onBoth(on_shape, on_other)) {
      PairHit<S> out = hit;
      out.on_shape = on_shape;
      out.on_other = on_other;
      return out;
    }
  }
  return hit;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_WITNESSES_ON_BODIES_H
