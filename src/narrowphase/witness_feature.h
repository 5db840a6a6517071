#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_WITNESS_FEATURE_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_WITNESS_FEATURE_H

// Internal: the other geometry's shape around its witness point, as the Jacobians of a pair's
// witnesses and normal need it (pair_jacobians.h; docs/math.md → "Jacobians of a pair's
// witnesses"). The other geometry's support set along −n (n: the pair's normal, from the
// superellipsoid towards the other) is one of:
//   a point   whose support point moves with the direction by the Hessian of the support
//             function there (a smooth shape's; a circular rim's; 0 at a vertex), rounded by
//             a ball (a capsule's end): Hessian + r·(I − n·nᵀ);
//   an edge   a segment of a line through `point` along `direction` (⊥ n) that moves with the
//             other geometry; n stays ⊥ it as the pair moves. A rounding moves the witness
//             off the line as n turns, by −R·dn (R: `hessian`): a capsule's ball and a
//             cylinder's disc about the axis (the line), R = r·(I − n·nᵀ); a cone's side, the
//             generator from the apex (the line) whose rim end follows n round the base, in
//             the cone's frame (so a turn ω of the cone moves the witness by R·(ω × n) too);
//   a face    a flat piece with normal −n: n turns with the other geometry.
// Which one is decided from the hit within a tolerance relative to the geometry's size: the
// solver's normal is accurate far below it, and a support set that is an edge or a face is
// the common case (a shape resting on a face), not a rare one.

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "common/cross_product.h"
#include "fcl_superellipsoid/superellipsoid.h"
#include "narrowphase/shape_pair.h"
#include "narrowphase/support_map.h"

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
struct WitnessFeature {
  enum class Kind { kPoint, kEdge, kFace };
  Kind kind = Kind::kPoint;
  /// kPoint: ∇²h_O at −n (world), the rounding included; kEdge: the rounding's R.
  Eigen::Matrix<S, 3, 3> hessian = Eigen::Matrix<S, 3, 3>::Zero();
  Vector3<S> point = Vector3<S>::Zero();      ///< kEdge: a point of the line (world)
  Vector3<S> direction = Vector3<S>::Zero();  ///< kEdge: the line's unit direction (world)
  bool rounding_turns_with_other = false;     ///< kEdge: the rounding is the other's (a cone)
};

/// The tolerance, relative to the geometry's size, within which a witness lies on an edge or a
/// face, or a normal is perpendicular to an edge or along a face's normal.
template <typename S>
S featureTolerance() {
  return S(64) * std::sqrt(std::numeric_limits<S>::epsilon());
}

template <typename S>
WitnessFeature<S> pointFeature(const Eigen::Matrix<S, 3, 3>& hessian) {
  WitnessFeature<S> f;
  f.hessian = hessian;
  return f;
}

template <typename S>
WitnessFeature<S> edgeFeature(const Vector3<S>& point, const Vector3<S>& direction,
                              const Eigen::Matrix<S, 3, 3>& rounding) {
  WitnessFeature<S> f;
  f.kind = WitnessFeature<S>::Kind::kEdge;
  f.point = point;
  f.direction = direction.normalized();
  f.hessian = rounding;
  return f;
}

template <typename S>
WitnessFeature<S> faceFeature() {
  WitnessFeature<S> f;
  f.kind = WitnessFeature<S>::Kind::kFace;
  return f;
}

/// A ball's contribution to a support Hessian at unit direction n: r·(I − n·nᵀ).
template <typename S>
Eigen::Matrix<S, 3, 3> ballHessian(S r, const Vector3<S>& n) {
  return r * (Eigen::Matrix<S, 3, 3>::Identity() - n * n.transpose());
}

/// A smooth shape (a superellipsoid, an ellipsoid, a sphere): its support Hessian at −n.
template <typename S, typename Smooth>
WitnessFeature<S> smoothFeature(const Smooth& other, const fcl::Transform3<S>& X_WO,
                                const PairHit<S>& hit) {
  return pointFeature(SupportMap<S>(other, X_WO).evaluate(Vector3<S>(-hit.normal)).hessian);
}

/// The vertices of a polytope (world) within the tolerance of its supporting plane along −n:
/// one is a vertex, two an edge, more a face.
template <typename S>
WitnessFeature<S> polytopeFeature(const std::vector<Vector3<S>>& vertices_W,
                                  const PairHit<S>& hit) {
  const Vector3<S> m = -hit.normal;
  S top = -std::numeric_limits<S>::infinity(), size = S(0);
  for (const Vector3<S>& v : vertices_W) top = std::max(top, m.dot(v));
  for (const Vector3<S>& v : vertices_W) size = std::max(size, (v - vertices_W[0]).norm());
  const S tol = featureTolerance<S>() * size;
  std::vector<Vector3<S>> on;
  for (const Vector3<S>& v : vertices_W) {
    if (m.dot(v) >= top - tol) on.push_back(v);
  }
  if (on.size() <= 1) return pointFeature<S>(Eigen::Matrix<S, 3, 3>::Zero());
  // Two vertices, or several on one line: an edge (its two farthest apart).
  std::size_t a = 0, b = 1;
  for (std::size_t i = 0; i < on.size(); ++i) {
    for (std::size_t j = i + 1; j < on.size(); ++j) {
      if ((on[i] - on[j]).norm() > (on[a] - on[b]).norm()) a = i, b = j;
    }
  }
  const Vector3<S> e = (on[b] - on[a]).normalized();
  for (const Vector3<S>& v : on) {
    const Vector3<S> off = (v - on[a]) - (v - on[a]).dot(e) * e;
    if (off.norm() > tol) return faceFeature<S>();
  }
  return edgeFeature<S>(on[a], e, Eigen::Matrix<S, 3, 3>::Zero());
}

template <typename S>
WitnessFeature<S> boxFeature(const fcl::Box<S>& box, const fcl::Transform3<S>& X_WO,
                             const PairHit<S>& hit) {
  std::vector<Vector3<S>> corners;
  for (int k = 0; k < 8; ++k) {
    const Vector3<S> c((k & 1) ? S(0.5) : S(-0.5), (k & 2) ? S(0.5) : S(-0.5),
                       (k & 4) ? S(0.5) : S(-0.5));
    corners.push_back(X_WO * Vector3<S>(c.cwiseProduct(box.side)));
  }
  return polytopeFeature(corners, hit);
}

template <typename S>
WitnessFeature<S> convexFeature(const fcl::Convex<S>& convex, const fcl::Transform3<S>& X_WO,
                                const PairHit<S>& hit) {
  std::vector<Vector3<S>> vertices;
  for (const Vector3<S>& v : convex.getVertices()) vertices.push_back(X_WO * v);
  return polytopeFeature(vertices, hit);
}

template <typename S>
WitnessFeature<S> triangleFeature(const fcl::TriangleP<S>& tri, const fcl::Transform3<S>& X_WO,
                                  const PairHit<S>& hit) {
  return polytopeFeature<S>({X_WO * tri.a, X_WO * tri.b, X_WO * tri.c}, hit);
}

/// A capsule: its segment's end (a ball) or its side (the segment, rounded).
template <typename S>
WitnessFeature<S> capsuleFeature(const fcl::Capsule<S>& capsule, const fcl::Transform3<S>& X_WO,
                                 const PairHit<S>& hit) {
  const Vector3<S> axis = X_WO.linear().col(2);
  const S along = -hit.normal.dot(axis);
  const S size = capsule.lz / 2 + capsule.radius;
  if (std::abs(along) * capsule.lz / 2 <= featureTolerance<S>() * size) {
    return edgeFeature<S>(X_WO.translation(), axis, ballHessian(capsule.radius, hit.normal));
  }
  return pointFeature(ballHessian(capsule.radius, hit.normal));
}

/// A cylinder: a cap (a face), its side (the axis, rounded by the disc) or a rim (a circle's
/// support Hessian).
template <typename S>
WitnessFeature<S> cylinderFeature(const fcl::Cylinder<S>& cylinder, const fcl::Transform3<S>& X_WO,
                                  const PairHit<S>& hit) {
  const Vector3<S> m = X_WO.linear().transpose() * Vector3<S>(-hit.normal);
  const S radial = std::hypot(m[0], m[1]), h = cylinder.lz / 2;
  const S tol = featureTolerance<S>() * (h + cylinder.radius);
  const Vector3<S> axis = X_WO.linear().col(2);
  if (radial * cylinder.radius <= tol) return faceFeature<S>();
  if (std::abs(m[2]) * h <= tol) {
    return edgeFeature<S>(X_WO.translation(), axis, ballHessian(cylinder.radius, hit.normal));
  }
  const Vector3<S> rim_centre = X_WO.translation() + (m[2] > S(0) ? h : -h) * axis;
  return pointFeature(SupportMap<S>::ofCircle(rim_centre, axis, cylinder.radius)
                          .evaluate(Vector3<S>(-hit.normal))
                          .hessian);
}

/// A cone (apex at +lz/2 on its axis): its apex (a vertex), its base (a face), its base's rim
/// (a circle) or a generator of its side from the apex to the rim (an edge). As n turns about
/// the axis the generator turns with it: the witness, s along a generator of length L, moves
/// like a point of the rim scaled by s/L, whose support Hessian along e2 = n × e is r/ρ (ρ: the
/// part of −n ⊥ the axis).
template <typename S>
WitnessFeature<S> coneFeature(const fcl::Cone<S>& cone, const fcl::Transform3<S>& X_WO,
                              const PairHit<S>& hit) {
  const Vector3<S> m = X_WO.linear().transpose() * Vector3<S>(-hit.normal);
  const S radial = std::hypot(m[0], m[1]), h = cone.lz / 2;
  const S tol = featureTolerance<S>() * (h + cone.radius);
  const Vector3<S> axis = X_WO.linear().col(2);
  const Vector3<S> apex = X_WO.translation() + h * axis;
  const Vector3<S> base = X_WO.translation() - h * axis;
  const S at_apex = h * m[2], at_rim = cone.radius * radial - h * m[2];
  if (radial * cone.radius <= tol && at_rim > at_apex) return faceFeature<S>();
  if (at_apex > at_rim + tol) return pointFeature<S>(Eigen::Matrix<S, 3, 3>::Zero());
  if (at_apex >= at_rim - tol) {
    const Vector3<S> outward = X_WO.linear() * Vector3<S>(m[0] / radial, m[1] / radial, S(0));
    const Vector3<S> generator = base + cone.radius * outward - apex;
    const S length = generator.norm();
    const Vector3<S> e = generator / length;
    const S s = std::clamp(e.dot(hit.on_other - apex), S(0), length);
    const Vector3<S> e2 = crossOf(hit.normal, e);
    WitnessFeature<S> f = edgeFeature<S>(
        apex, e,
        Eigen::Matrix<S, 3, 3>((s / length) * (cone.radius / radial) * e2 * e2.transpose()));
    f.rounding_turns_with_other = true;
    return f;
  }
  return pointFeature(
      SupportMap<S>::ofCircle(base, axis, cone.radius).evaluate(Vector3<S>(-hit.normal)).hessian);
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_WITNESS_FEATURE_H
