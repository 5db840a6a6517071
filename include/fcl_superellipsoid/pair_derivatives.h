#ifndef FCL_SUPERELLIPSOID_PAIR_DERIVATIVES_H
#define FCL_SUPERELLIPSOID_PAIR_DERIVATIVES_H

/// @file
/// The gradient of a pair's signed distance: the superellipsoid against another superellipsoid
/// or any FCL shape the library answers (fcl_integration.h lists them), with respect to both
/// poses and to each superellipsoid's five parameters (a1, a2, a3, ε1, ε2). The mathematics:
/// docs/math.md → "Derivatives of a pair's distance"; usage: docs/usage.md → "Derivatives".
///
/// The signed distance d is the pair's (fcl_integration.h: the distance, or minus the
/// shortest separating translation where they overlap), as the front end answers it. Twists
/// as in point_derivatives.h, in the world frame: ξ = (ω, v) applied to a pose, X ← exp(ξ)·X,
/// moves a point p of that geometry by ω × p + v. With n the unit normal from the
/// superellipsoid towards the other and N_S, N_O the witness points:
///
///     ∂d/∂ξ_S = (n × N_S, −n),   ∂d/∂ξ_O = (N_O × n, n),
///     ∂d/∂θ   = (∂G/∂θ)/‖∇G‖ at the superellipsoid's witness (its frame),
///
/// and the same for a second superellipsoid at its witness. Both hold for separated and
/// overlapping pairs (the distance is the optimum over contact directions of a function whose
/// partial derivatives these are: the envelope theorem).
///
/// Where the derivative does not exist, `differentiable` is false and the gradient is that of
/// the returned contact direction (exact in every direction of change that keeps it optimal;
/// never NaN): an overlapping pair whose shortest separating translation is not unique, found
/// where one of the contact direction's mirror images across the superellipsoid's symmetry
/// planes (−n among them) separates the pair within the tolerance of the same move (coincident
/// centres, a partner centred on a symmetry plane); a plane the shape straddles by equal depths
/// on both sides. A separated pair's witnesses are unique (the superellipsoid is strictly
/// convex), so its distance is differentiable.
///
/// With DerivativeOrder::kJacobians, also the Jacobians of both witness points and of the
/// normal with respect to both twists (the implicit function theorem on the pair's optimality
/// conditions, N_O − N_S = d·n with each witness its geometry's support point). They are those
/// of the other geometry's feature that holds its witness: a point of a smooth surface or a
/// vertex, an edge (n stays ⊥ it), a face (n turns with it); at the border between two
/// features, the one the witness is found on within a tolerance. Where the witnesses do not
/// move smoothly (an overlap whose depth is not a strict local minimum over directions),
/// `differentiable` is false and the Jacobians are finite, of a regularised system.
///
/// Not handled: meshes and point clouds (their vertices are point queries:
/// pointDistanceDerivatives, batchDistanceDerivatives).

#include <fcl/geometry/collision_geometry.h>

#include "fcl_superellipsoid/point_derivatives.h"

namespace fcl_superellipsoid {

template <typename S>
struct PairDistanceDerivatives {
  S distance;           ///< signed: < 0 where the pair overlaps (minus the depth)
  Vector3<S> on_shape;  ///< the superellipsoid's witness point, world
  Vector3<S> on_other;  ///< the other geometry's witness point, world
  Vector3<S> normal;    ///< unit, world, from the superellipsoid towards the other (∂d/∂v_O)
  Vector6<S> d_pose;    ///< ∂d/∂ξ_S, the superellipsoid's pose: (n × N_S, −n)
  Vector6<S> d_other_pose;   ///< ∂d/∂ξ_O, the other's pose: (N_O × n, n)
  Vector5<S> d_shape;        ///< ∂d/∂(a1, a2, a3, ε1, ε2) of the superellipsoid
  Vector5<S> d_other_shape;  ///< the same for the other, if it is a Superellipsoid (else zero)
  bool other_is_superellipsoid = false;
  bool differentiable = true;  ///< false where the derivative does not exist (file comment)
  bool has_jacobians = false;  ///< the Jacobians below were computed (else zero)
  Eigen::Matrix<S, 3, 6> on_shape_d_pose;        ///< ∂N_S/∂ξ_S
  Eigen::Matrix<S, 3, 6> on_shape_d_other_pose;  ///< ∂N_S/∂ξ_O
  Eigen::Matrix<S, 3, 6> on_other_d_pose;        ///< ∂N_O/∂ξ_S
  Eigen::Matrix<S, 3, 6> on_other_d_other_pose;  ///< ∂N_O/∂ξ_O
  Eigen::Matrix<S, 3, 6> normal_d_pose;          ///< ∂n/∂ξ_S
  Eigen::Matrix<S, 3, 6> normal_d_other_pose;    ///< ∂n/∂ξ_O
};

/// The signed distance of the pair (shape at X_WS, other at X_WO) and its gradient, in the
/// world frame; with `order` kJacobians also the Jacobians of the witnesses and of the normal.
/// The other geometry is a Superellipsoid or an fcl::Sphere, Ellipsoid, Box, Convex,
/// TriangleP, Capsule, Cylinder, Cone, Halfspace or Plane.
/// @throws std::invalid_argument for a pose that is not finite, another geometry (naming its
///         node type), or the other geometry's bad parameters (as the front end refuses them).
template <typename S>
FSE_EXPORT PairDistanceDerivatives<S> pairDistanceDerivatives(
    const Superellipsoid<S>& shape, const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
    const fcl::CollisionGeometry<S>& other, const detail::NonDeduced<fcl::Transform3<S>>& X_WO,
    DerivativeOrder order = DerivativeOrder::kGradient);

extern template FSE_EXPORT PairDistanceDerivatives<float> pairDistanceDerivatives(
    const Superellipsoid<float>&, const fcl::Transform3<float>&,
    const fcl::CollisionGeometry<float>&, const fcl::Transform3<float>&, DerivativeOrder);
extern template FSE_EXPORT PairDistanceDerivatives<double> pairDistanceDerivatives(
    const Superellipsoid<double>&, const fcl::Transform3<double>&,
    const fcl::CollisionGeometry<double>&, const fcl::Transform3<double>&, DerivativeOrder);

}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_PAIR_DERIVATIVES_H
