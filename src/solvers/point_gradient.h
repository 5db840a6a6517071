#ifndef FCL_SUPERELLIPSOID_SRC_SOLVERS_POINT_GRADIENT_H
#define FCL_SUPERELLIPSOID_SRC_SOLVERS_POINT_GRADIENT_H

// Internal: the first-order derivatives of the point distance from the Exact solver's answer,
// and the test for several nearest points (the `differentiable` flag), shared by the single
// query (point_derivatives.cpp) and the batched one (batch/batch_distance.cpp). The mathematics:
// docs/math.md → "Derivatives of the distance".

#include <Eigen/Core>
#include <cmath>

#include "fcl_superellipsoid/point_derivatives.h"
#include "shape/gauge_derivatives.h"
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

/// ∂d/∂θ = (∂G/∂θ)/‖∇G‖ at the nearest point (the shape's frame), from G's derivatives there.
template <typename S>
Vector5<S> shapeGradient(const GaugeDerivatives<S>& gauge) {
  return gauge.d_parameters.transpose() / gauge.gradient.norm();
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
