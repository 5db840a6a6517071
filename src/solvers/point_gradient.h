#ifndef FCL_SUPERELLIPSOID_SRC_SOLVERS_POINT_GRADIENT_H
#define FCL_SUPERELLIPSOID_SRC_SOLVERS_POINT_GRADIENT_H

// Internal: the first-order derivatives of the point distance from the Exact solver's answer,
// and the test for several nearest points (the `differentiable` flag), shared by the single
// query (point_derivatives.cpp) and the batched one (batch/batch_distance.cpp). The mathematics:
// docs/math.md → "Derivatives of the distance".

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "fcl_superellipsoid/point_derivatives.h"
#include "fcl_superellipsoid/superellipsoid.h"
#include "solvers/exact_rules.h"

namespace fcl_superellipsoid {
namespace detail {

/// ∂d/∂ξ = (n × N, −n), N and n in the frame of the twist ξ = (ω, v) (point_derivatives.h).
template <typename S>
Vector6<S> poseGradient(const Vector3<S>& normal, const Vector3<S>& point) {
  // (Written out: Eigen's vectorised cross product of two float 3-vectors loads 4 floats.)
  Vector6<S> out;
  out << normal[1] * point[2] - normal[2] * point[1], normal[2] * point[0] - normal[0] * point[2],
      normal[0] * point[1] - normal[1] * point[0], -normal;
  return out;
}

/// ∂d/∂θ = (∂G/∂θ)/‖∇G‖ at a surface point N with its unit outward normal n (the shape's frame,
/// any octant), written in N and n alone (docs/math.md → "Derivatives of the distance"): with
/// b_i = |N_i·n_i|, whose sum is N·n = G/‖∇G‖ (Euler), and
/// φ(x, y) = ln(1 + q) − q·ln q/(1 + q), q = min(x, y)/max(x, y) (−Σ s·ln s over the shares
/// s = x/(x + y), y/(x + y) of a level),
///   ∂d/∂a_j = −b_j/a_j,
///   ∂d/∂ε1 = ½·(b1 + b2)·φ(b1, b2),
///   ∂d/∂ε2 = ½·(b1 + b2 + b3)·φ(b1 + b2, b3):
/// two logarithms a level, no power.
template <typename S>
Vector5<S> shapeGradient(const Superellipsoid<S>& shape, const Vector3<S>& point,
                         const Vector3<S>& normal) {
  const Vector3<S> b = point.cwiseProduct(normal).cwiseAbs();
  const auto phi = [](S x, S y) {
    // A share of 0 (or both), also one whose quotient q rounds to 0: s·ln s → 0.
    const S q = std::max(x, y) > S(0) ? std::min(x, y) / std::max(x, y) : S(0);
    if (!(q > S(0))) return S(0);
    // ln(1 + q) from the rounded u = 1 + q, as ln(u)·q/(u − 1) (u − 1 is exact): within a few
    // ulps, as log1p, at the cost of a log.
    const S u = S(1) + q;
    const S ln_u = u == S(1) ? q : std::log(u) * (q / (u - S(1)));
    return ln_u - q * std::log(q) / u;
  };
  const Vector3<S>& a = shape.radii();
  const S b12 = b[0] + b[1];
  Vector5<S> out;
  out << -b[0] / a[0], -b[1] / a[1], -b[2] / a[2], S(0.5) * b12 * phi(b[0], b[1]),
      S(0.5) * (b12 + b[2]) * phi(b12, b[2]);
  return out;
}

/// True where the query q (shape frame) has several nearest points, up to the solver's
/// tolerance: q at the centre; the solver's runner-up (Query::runner_up, ∞ for none) within the
/// tolerance of the distance; or N's mirror image across a coordinate plane that q lies on (or
/// nearly), whose distance exceeds |d| by 4|q_i·N_i|/(d' + |d|).
template <typename S>
bool hasSeveralNearestPoints(S size, const Vector3<S>& q, const Vector3<S>& point, S distance,
                             S runner_up, S relative_tolerance) {
  const S tolerance = exact_rules::absoluteTolerance(relative_tolerance, size, q.norm());
  const S separation = std::sqrt(tolerance * size);
  const S tie = S(4) * tolerance;
  const S depth = std::abs(distance);
  if (q.isZero(S(0)) || runner_up - depth <= tie) return true;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(point[i]) <= separation) continue;
    const S product = S(4) * std::abs(q[i] * point[i]);
    const S mirrored = std::sqrt(distance * distance + product);
    if (product / (mirrored + depth) <= tie) return true;
  }
  return false;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SOLVERS_POINT_GRADIENT_H
