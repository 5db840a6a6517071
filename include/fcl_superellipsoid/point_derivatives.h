#ifndef FCL_SUPERELLIPSOID_POINT_DERIVATIVES_H
#define FCL_SUPERELLIPSOID_POINT_DERIVATIVES_H

/// @file
/// Derivatives of the exact signed distance from a point to a superellipsoid: with respect to
/// the query point, the shape's pose and the shape's five parameters (a1, a2, a3, ε1, ε2); on
/// request also the Jacobians of the nearest point and of the normal. The mathematics:
/// docs/math.md → "Derivatives of the distance"; usage: docs/usage.md → "Derivatives".
///
/// Frames and signs as in point_distance.h. The pose derivatives are those of a twist
/// ξ = (ω, v) applied to the shape's pose in the frame the query is given in (the world W for
/// the world-frame call, S for the shape-frame one): X_WS ← exp(ξ)·X_WS, which moves a point p
/// of the shape by ω × p + v. So ∂d/∂v = −n and ∂d/∂ω = n × N.
///
/// Where the derivative does not exist, `differentiable` is false and the derivatives are
/// those of the branch of the returned nearest point (exact in every direction in which that
/// point stays the nearest; never NaN):
///  - Q has several nearest points (inside: on the medial axis, e.g. the centre of a sphere, a
///    symmetry plane with the nearest point off it, the diagonal plane of a box-like shape);
///    detected where another nearest point is within the solver's tolerance of the distance;
///  - Q is at the shape's centre;
///  - with DerivativeOrder::kJacobians, also where Q is at a centre of curvature of its nearest
///    point (1 + d·κ ≈ 0 for a principal curvature κ): the distance is differentiable there,
///    the nearest point is not (its Jacobian is unbounded; returned large and finite).
/// Outside the shape the distance is always differentiable. On a crease (a coordinate plane of
/// a level with exponent ε > 1, where the curvature is unbounded) the nearest point does not
/// move across the crease to first order: its Jacobian is 0 in that direction, the limit from
/// both sides.

#include <Eigen/Core>

#include "fcl_superellipsoid/point_distance.h"

namespace fcl_superellipsoid {

template <typename S>
using Vector5 = Eigen::Matrix<S, 5, 1>;
template <typename S>
using Vector6 = Eigen::Matrix<S, 6, 1>;

/// What a derivative query computes beyond the value.
enum class DerivativeOrder {
  kGradient,   ///< ∂d/∂Q, ∂d/∂ξ, ∂d/∂θ
  kJacobians,  ///< also the Jacobians of the nearest point and of the normal
};

template <typename S>
struct PointDistanceDerivatives {
  PointDistanceResult<S> value;  ///< as pointDistance() with the Exact method returns it
  Vector3<S> d_query;            ///< ∂d/∂Q (the outward normal)
  Vector6<S> d_pose;             ///< ∂d/∂ξ, ξ = (ω, v): (n × N, −n)
  Vector5<S> d_shape;            ///< ∂d/∂(a1, a2, a3, ε1, ε2)
  bool differentiable = true;    ///< false where the derivative does not exist (file comment)
  bool has_jacobians = false;    ///< the Jacobians below were computed (else zero)
  Eigen::Matrix<S, 3, 3> nearest_point_d_query;  ///< ∂N/∂Q
  Eigen::Matrix<S, 3, 6> nearest_point_d_pose;   ///< ∂N/∂ξ
  Eigen::Matrix<S, 3, 5> nearest_point_d_shape;  ///< ∂N/∂θ
  Eigen::Matrix<S, 3, 3> normal_d_query;         ///< ∂n/∂Q
  Eigen::Matrix<S, 3, 6> normal_d_pose;          ///< ∂n/∂ξ
  Eigen::Matrix<S, 3, 5> normal_d_shape;         ///< ∂n/∂θ
};

/// The signed distance from p_SQ (shape frame) with its derivatives, in the shape's frame.
/// options.method must be DistanceMethod::kExact (the derivatives are those of the exact
/// distance); tolerance and iterations as for pointDistance().
/// @throws std::invalid_argument as pointDistance(), or for another method, naming it.
template <typename S>
FSE_EXPORT PointDistanceDerivatives<S> pointDistanceDerivatives(
    const Superellipsoid<S>& shape, const detail::NonDeduced<Vector3<S>>& p_SQ,
    DerivativeOrder order = DerivativeOrder::kGradient,
    const detail::NonDeduced<DistanceOptions<S>>& options = {});

/// The same for a world point p_WQ and the shape's pose X_WS: every vector and Jacobian in the
/// world frame W (the twist ξ too); d_shape as in the shape frame.
template <typename S>
FSE_EXPORT PointDistanceDerivatives<S> pointDistanceDerivatives(
    const Superellipsoid<S>& shape, const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
    const detail::NonDeduced<Vector3<S>>& p_WQ, DerivativeOrder order = DerivativeOrder::kGradient,
    const detail::NonDeduced<DistanceOptions<S>>& options = {});

extern template FSE_EXPORT PointDistanceDerivatives<float> pointDistanceDerivatives(
    const Superellipsoid<float>&, const Vector3<float>&, DerivativeOrder,
    const DistanceOptions<float>&);
extern template FSE_EXPORT PointDistanceDerivatives<double> pointDistanceDerivatives(
    const Superellipsoid<double>&, const Vector3<double>&, DerivativeOrder,
    const DistanceOptions<double>&);
extern template FSE_EXPORT PointDistanceDerivatives<float> pointDistanceDerivatives(
    const Superellipsoid<float>&, const fcl::Transform3<float>&, const Vector3<float>&,
    DerivativeOrder, const DistanceOptions<float>&);
extern template FSE_EXPORT PointDistanceDerivatives<double> pointDistanceDerivatives(
    const Superellipsoid<double>&, const fcl::Transform3<double>&, const Vector3<double>&,
    DerivativeOrder, const DistanceOptions<double>&);

}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_POINT_DERIVATIVES_H
