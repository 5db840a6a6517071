// The public pair gradient (pair_derivatives.h): the pair's row of pair_kinds.h answers the hit
// and gives the other geometry's support (its region body's, or a plane's) and its feature at
// the witness; the gradient and the tie test are narrowphase/pair_gradient.h's, the Jacobians
// narrowphase/pair_jacobians.h's.

#include "fcl_superellipsoid/pair_derivatives.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/coordinate_range.h"
#include "fcl_glue/pair_kinds.h"
#include "narrowphase/pair_gradient.h"
#include "narrowphase/pair_jacobians.h"
#include "narrowphase/support_map.h"

namespace fcl_superellipsoid {
namespace {

/// The support function of the flat geometry {x : u·x = c} (`two_sided`, a plane) or
/// {x : u·x ≤ c} (a halfspace), u unit, world: λ·c along v = λ·u (λ ≥ 0 for a halfspace), ∞
/// along any other direction (to the direction's rounding).
template <typename S>
S flatSupport(const Vector3<S>& u, S c, bool two_sided, const Vector3<S>& v) {
  const S along = v.dot(u);
  const S off = (v - along * u).norm();
  const S rounding = std::sqrt(std::numeric_limits<S>::epsilon()) * v.norm();
  if (off > rounding || (!two_sided && along < S(0))) return std::numeric_limits<S>::infinity();
  return along * c;
}

template <typename S, typename Flat>
detail::SupportValue<S> flatSupportOf(const Flat& flat, const fcl::Transform3<S>& X_WO,
                                      bool two_sided) {
  const Vector3<S> u = X_WO.linear() * flat.n;
  const S c = flat.d + u.dot(X_WO.translation());
  return [u, c, two_sided](const Vector3<S>& v) { return flatSupport(u, c, two_sided, v); };
}

}  // namespace

template <typename S>
PairDistanceDerivatives<S> pairDistanceDerivatives(
    const Superellipsoid<S>& shape, const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
    const fcl::CollisionGeometry<S>& other, const detail::NonDeduced<fcl::Transform3<S>>& X_WO,
    DerivativeOrder order) {
  constexpr const char* kWhere = "pairDistanceDerivatives";
  if (order != DerivativeOrder::kGradient && order != DerivativeOrder::kJacobians) {
    detail::throwInvalidArgument(kWhere, "order must be a DerivativeOrder",
                                 static_cast<int>(order));
  }
  detail::checkPose(kWhere, "X_WS", X_WS);
  detail::checkPose(kWhere, "X_WO", X_WO);
  const detail::Pair<S> pair = detail::makePair<S>(&shape, X_WS, &other, X_WO);
  const detail::PairKind<S>* kind = detail::findPairKind<S>(pair.other_type);
  std::optional<detail::PairHit<S>> hit;
  if (kind != nullptr && kind->form == detail::PairForm::kShape) hit = kind->answer(pair, kWhere);
  if (!hit) detail::throwUnsupportedPartner(kWhere, other);

  PairDistanceDerivatives<S> out;
  const Superellipsoid<S>* other_shape = detail::asSuperellipsoid(&other, pair.other_type);
  detail::pairGradient(pair, *hit, other_shape, out);
  if (order == DerivativeOrder::kJacobians) {
    const Eigen::Matrix<S, 3, 3> H_S =
        detail::SupportMap<S>(shape, X_WS).evaluate(hit->normal).hessian;
    const detail::PairJacobians<S> J = detail::pairJacobians(*hit, H_S, kind->feature(pair, *hit));
    out.has_jacobians = true;
    out.on_shape_d_pose = J.on_shape.template leftCols<6>();
    out.on_shape_d_other_pose = J.on_shape.template rightCols<6>();
    out.on_other_d_pose = J.on_other.template leftCols<6>();
    out.on_other_d_other_pose = J.on_other.template rightCols<6>();
    out.normal_d_pose = J.normal.template leftCols<6>();
    out.normal_d_other_pose = J.normal.template rightCols<6>();
    out.differentiable = J.regular;
  } else {
    for (auto* m : {&out.on_shape_d_pose, &out.on_shape_d_other_pose, &out.on_other_d_pose,
                    &out.on_other_d_other_pose, &out.normal_d_pose, &out.normal_d_other_pose}) {
      m->setZero();
    }
  }

  // The tie test, for an overlap (a separated pair's witnesses are unique): the other
  // geometry's support, its region body's where bounded.
  // Ties: within 4 × the shape's query tolerance (with its rounding floor) at the pair's scale.
  const S reach = (X_WO.translation() - X_WS.translation()).norm();
  const auto tieAt = [&](S scale) {
    return S(4) * detail::exact_rules::absoluteTolerance(shape.queryOptions().tolerance, scale,
                                                         reach + scale);
  };
  S scale = shape.size();
  S tie = tieAt(scale);
  if (hit->distance > tie) return out;
  detail::SupportValue<S> other_support;
  std::unique_ptr<detail::RegionBody<S>> body;
  if (pair.other_type == fcl::GEOM_PLANE) {
    other_support = flatSupportOf(*detail::geometryAs<fcl::Plane<S>>(&other), X_WO, true);
  } else if (pair.other_type == fcl::GEOM_HALFSPACE) {
    other_support = flatSupportOf(*detail::geometryAs<fcl::Halfspace<S>>(&other), X_WO, false);
  } else {
    body = kind->region(pair, *hit);
    if (body->size() > scale) {
      scale = body->size();
      tie = tieAt(scale);
    }
    other_support = [&body](const Vector3<S>& v) { return body->support(v).dot(v); };
  }
  out.differentiable = out.differentiable &&
                       !detail::hasSeveralSeparatingMoves(pair, *hit, other_support, tie, scale);
  return out;
}

#define FSE_INSTANTIATE_PAIR_DERIVATIVES(S)                                                  \
  template PairDistanceDerivatives<S> pairDistanceDerivatives(                               \
      const Superellipsoid<S>&, const fcl::Transform3<S>&, const fcl::CollisionGeometry<S>&, \
      const fcl::Transform3<S>&, DerivativeOrder);
FSE_INSTANTIATE_PAIR_DERIVATIVES(float)
FSE_INSTANTIATE_PAIR_DERIVATIVES(double)

}  // namespace fcl_superellipsoid
