#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_PAIR_GRADIENT_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_PAIR_GRADIENT_H

// Internal: the gradient of a pair's signed distance from its hit (pair_derivatives.h), and
// the test for a second shortest separating move (the `differentiable` flag). The
// mathematics: docs/math.md → "Derivatives of a pair's distance".

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <limits>

#include "fcl_superellipsoid/pair_derivatives.h"
#include "narrowphase/shape_pair.h"
#include "solvers/exact_rules.h"
#include "solvers/point_gradient.h"

namespace fcl_superellipsoid {
namespace detail {

/// ∂d/∂θ of a superellipsoid at its witness point p_W with its outward normal n_W there (world),
/// posed by X_WS: the rate at which the surface moves inwards (point_gradient.h, shapeGradient).
template <typename S>
Vector5<S> witnessShapeGradient(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS,
                                const Vector3<S>& p_W, const Vector3<S>& n_W) {
  const Vector3<S> p_S = X_WS.inverse(Eigen::Isometry) * p_W;
  return shapeGradient(shape, p_S, Vector3<S>(X_WS.linear().transpose() * n_W));
}

/// The support function of the other geometry, h_O(v) = max over it of v·x (world; +∞ where
/// unbounded along v).
template <typename S>
using SupportValue = std::function<S(const Vector3<S>&)>;

/// True where an overlapping pair has a second shortest separating move: the depth is the least
/// F(m) = h_S(m) + h_O(−m) over unit m, attained at the hit's normal n; a mirror image m of n
/// across the superellipsoid's symmetry planes (−n among them, all three planes at once), apart
/// from n, with F(m) within `tie` of F(n) attains it too. A separated pair (d > tie) has unique
/// witnesses (the superellipsoid is strictly convex) and is not tested.
template <typename S>
bool hasSeveralSeparatingMoves(const ShapePair<S>& pair, const PairHit<S>& hit,
                               const SupportValue<S>& other_support, S tie, S scale) {
  if (hit.distance > tie) return false;
  const Vector3<S>& n = hit.normal;
  // The superellipsoid's support function about its centre c is the same at n and at each of
  // n's mirror images m: h_S(m) = h_S(n) − n·c + m·c, one support point for all eight.
  const Vector3<S>& c = pair.X_WS->translation();
  const S about_centre = shapeSupport(pair, n).dot(n) - n.dot(c);
  const auto F = [&](const Vector3<S>& m) {
    return about_centre + m.dot(c) + other_support(Vector3<S>(-m));
  };
  const S at_n = F(n);
  if (!std::isfinite(at_n)) return false;
  // Directions closer than this to n are n's own neighbourhood: F rises from its minimum by
  // about scale·|m − n|²/2 there, which stays below the tie.
  const S apart = S(4) * std::sqrt(tie / scale);
  const Matrix3<S> R = pair.X_WS->linear();
  const Vector3<S> n_S = R.transpose() * n;
  for (int mask = 1; mask < 8; ++mask) {
    Vector3<S> m_S = n_S;
    for (int i = 0; i < 3; ++i) {
      if (mask & (1 << i)) m_S[i] = -m_S[i];
    }
    const Vector3<S> m = R * m_S;
    if ((m - n).norm() <= apart) continue;
    if (F(m) - at_n <= tie) return true;
  }
  return false;
}

/// The gradient of the pair's signed distance from its hit, into `out` (pair_derivatives.h):
/// the poses' from the normal and the witnesses, the shapes' at their witnesses;
/// `other_shape` (posed by X_WO) where the other geometry is a superellipsoid, else null.
template <typename S>
void pairGradient(const ShapePair<S>& pair, const PairHit<S>& hit,
                  const Superellipsoid<S>* other_shape, PairDistanceDerivatives<S>& out) {
  out.distance = hit.distance;
  out.on_shape = hit.on_shape;
  out.on_other = hit.on_other;
  out.normal = hit.normal;
  out.d_pose = poseGradient(hit.normal, hit.on_shape);         // (n × N_S, −n)
  out.d_other_pose = -poseGradient(hit.normal, hit.on_other);  // (N_O × n, n)
  out.d_shape = witnessShapeGradient(*pair.shape, *pair.X_WS, hit.on_shape, hit.normal);
  out.other_is_superellipsoid = other_shape != nullptr;
  out.d_other_shape =
      other_shape != nullptr
          ? witnessShapeGradient(*other_shape, *pair.X_WO, hit.on_other, Vector3<S>(-hit.normal))
          : Vector5<S>::Zero();
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_PAIR_GRADIENT_H
