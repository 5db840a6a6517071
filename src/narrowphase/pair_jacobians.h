#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_PAIR_JACOBIANS_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_PAIR_JACOBIANS_H

// Internal: the Jacobians of a pair's witness points and normal with respect to both poses
// (pair_derivatives.h, DerivativeOrder::kJacobians), by the implicit function theorem on the
// pair's optimality conditions. The mathematics: docs/math.md → "Jacobians of a pair's
// witnesses".
//
// With n the normal (superellipsoid S towards the other geometry O), d the signed distance, the
// witnesses are S's support point along n and O's along −n, and N_O − N_S = d·n. A twist
// (ω, v) of a pose moves the support point along a fixed direction m by ω × N − H(ω × m) + v
// (H: the support function's Hessian at m); a change dn of the direction moves it by H·dn.
// Differentiating N_O − N_S = d·n gives dn from a 2 × 2 system in the plane ⊥ n, whose form
// depends on O's support set along −n (witness_feature.h): a point, an edge, a face.

#include <Eigen/Core>
#include <cmath>
#include <limits>

#include "common/cross_product.h"
#include "narrowphase/shape_pair.h"
#include "narrowphase/witness_feature.h"

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
using Matrix3x12 = Eigen::Matrix<S, 3, 12>;

/// The Jacobians with respect to (ξ_S, ξ_O), ξ = (ω, v) world twists; `regular` is false where
/// the system is singular (the witnesses are not differentiable there: an overlap whose depth
/// is not a strict local minimum over directions); they are then finite, of a regularised
/// system.
template <typename S>
struct PairJacobians {
  Matrix3x12<S> normal, on_shape, on_other;
  bool regular = true;
};

/// From the hit, the superellipsoid's support Hessian H_S at n (world) and O's feature.
template <typename S>
PairJacobians<S> pairJacobians(const PairHit<S>& hit, const Eigen::Matrix<S, 3, 3>& H_S,
                               const WitnessFeature<S>& feature) {
  using Kind = typename WitnessFeature<S>::Kind;
  const Vector3<S>& n = hit.normal;
  const Vector3<S>& N_S = hit.on_shape;
  const Vector3<S>& N_O = hit.on_other;
  const S d = hit.distance;
  const Vector3<S> t1 = n.unitOrthogonal(), t2 = crossOf(n, t1);
  // A floor for the systems' pivots, relative to their scale: below it the system is singular.
  const S scale =
      std::max({H_S.norm(), feature.hessian.norm(), std::abs(d), N_S.norm(), N_O.norm(), S(1e-30)});
  const S floor = S(64) * std::numeric_limits<S>::epsilon() * scale;
  PairJacobians<S> out;

  // The point feature's 2 × 2 system in the plane ⊥ n: (H_S + H_O + d·I)·dn = P·b, b the
  // witnesses' separation by the twists along the fixed direction n.
  Eigen::Matrix<S, 2, 2> K = Eigen::Matrix<S, 2, 2>::Identity();
  if (feature.kind == Kind::kPoint) {
    const Eigen::Matrix<S, 3, 3> H = H_S + feature.hessian;
    K << t1.dot(H * t1) + d, t1.dot(H * t2), t2.dot(H * t1), t2.dot(H * t2) + d;
    const S det = K.determinant();
    if (!(det > floor * floor && K.trace() > S(0))) {
      out.regular = false;
      K += (std::abs(K.trace()) + floor) * Eigen::Matrix<S, 2, 2>::Identity();
    }
  }
  const Eigen::Matrix<S, 2, 2> K_inverse = K.inverse();
  // The edge feature: n stays ⊥ e; the witness N_O = A + s·e slides along the line and moves
  // off it by −R·dn (R: the rounding's Hessian), and by R·(ω_O × n) where the rounding turns
  // with the other geometry.
  Vector3<S> e = Vector3<S>::Zero(), e2 = Vector3<S>::Zero();
  Eigen::Matrix<S, 3, 3> H_edge = H_S;
  S edge_pivot = S(1), s = S(0);
  if (feature.kind == Kind::kEdge) {
    e = feature.direction;
    e2 = crossOf(n, e);
    s = e.dot(N_O - feature.point);
    H_edge = H_S + feature.hessian;
    edge_pivot = e2.dot(H_edge * e2) + d;
    if (!(edge_pivot > floor)) {
      out.regular = false;
      edge_pivot = std::abs(edge_pivot) + floor;
    }
  }

  // Each column solves for the direction's change relative to a shape's own frame, δ_S = dn −
  // ω_S × n (δ_O likewise), whose right-hand sides hold no H_S (no H_O): beside a nearly flat
  // face that shape's support Hessian is huge, and H·dn would cancel H·(ω × n) in the rigid
  // motion to no digits left.
  for (int k = 0; k < 12; ++k) {
    Eigen::Matrix<S, 12, 1> xi = Eigen::Matrix<S, 12, 1>::Zero();
    xi[k] = S(1);
    const Vector3<S> w_S = xi.template segment<3>(0), v_S = xi.template segment<3>(3);
    const Vector3<S> w_O = xi.template segment<3>(6), v_O = xi.template segment<3>(9);
    // Each witness and the normal carried rigidly by its own geometry's twist.
    const Vector3<S> moved_S = crossOf(w_S, N_S) + v_S, moved_O = crossOf(w_O, N_O) + v_O;
    const Vector3<S> n_S = crossOf(w_S, n), n_O = crossOf(w_O, n);
    Vector3<S> dn = Vector3<S>::Zero(), dN_S = dn, dN_O = dn;
    switch (feature.kind) {
      case Kind::kPoint: {
        const auto solve = [&](const Vector3<S>& b) {
          const Eigen::Matrix<S, 2, 1> x = K_inverse * Eigen::Matrix<S, 2, 1>(t1.dot(b), t2.dot(b));
          return Vector3<S>(x[0] * t1 + x[1] * t2);
        };
        const Vector3<S> gap = moved_O - moved_S;
        const Vector3<S> delta_S = solve(gap + feature.hessian * (n_O - n_S) - d * n_S);
        const Vector3<S> delta_O = solve(gap + H_S * (n_S - n_O) - d * n_O);
        dn = delta_S + n_S;
        dN_S = H_S * delta_S + moved_S;
        dN_O = moved_O - feature.hessian * delta_O;
        break;
      }
      case Kind::kEdge: {
        // The line's point and direction, carried by the other geometry.
        const Vector3<S> dA = crossOf(w_O, feature.point) + v_O, de = crossOf(w_O, e);
        // The rounding's own turn with the other geometry (a cone's generator).
        const Vector3<S> turned = feature.rounding_turns_with_other
                                      ? Vector3<S>(feature.hessian * n_O)
                                      : Vector3<S>::Zero();
        const Vector3<S> c = dA + s * de + turned - moved_S - feature.hessian * n_S - d * n_S;
        const S alpha = (w_O - w_S).dot(e2);  // e·δ_S: keeps n ⊥ e
        const S beta = (e2.dot(c) - alpha * e2.dot(H_edge * e)) / edge_pivot;
        const Vector3<S> delta_S = alpha * e + beta * e2;
        dn = delta_S + n_S;
        const S ds = e.dot(H_edge * delta_S) + d * alpha - e.dot(c);
        dN_S = H_S * delta_S + moved_S;
        dN_O = dA + ds * e + s * de + turned - feature.hessian * dn;
        break;
      }
      case Kind::kFace: {
        dn = n_O;  // the face turns with the other geometry
        dN_S = H_S * (n_O - n_S) + moved_S;
        // dd: the gradient's (n × N_S, −n)·ξ_S + (N_O × n, n)·ξ_O.
        const S dd = w_S.dot(crossOf(n, N_S)) - n.dot(v_S) + w_O.dot(crossOf(N_O, n)) + n.dot(v_O);
        dN_O = dN_S + dd * n + d * dn;
        break;
      }
    }
    out.normal.col(k) = dn;
    out.on_shape.col(k) = dN_S;
    out.on_other.col(k) = dN_O;
  }
  return out;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_PAIR_JACOBIANS_H
