#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_ROLLING_CERTIFICATE_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_ROLLING_CERTIFICATE_H

// Internal: the rolling-ball certificate of a smooth overlap's depth (docs/math.md → "Smooth
// partners: Newton on the sphere", "The rolling balls of an overlap").
//
// For overlapping convex A and B, F(v) = h_A(v) + h_B(−v) is the support function of the
// Minkowski difference K = A − B, which holds the origin, and min F over unit v is the origin's
// depth in K. If a ball of radius ρ_A rolls freely inside A (every principal radius of curvature
// is at least ρ_A) and one of radius ρ_B inside B, one of radius ρ_A + ρ_B rolls freely inside K
// (the radii of curvature of K in a direction are those of A and B added). A direction v whose
// F(v) is at most ρ_A + ρ_B and whose tangential gradient t·(a − b) has length δ then bounds the
// depth from both sides: F(v) − δ ≤ min F ≤ F(v). It is the point query's rolling-ball argument
// (docs/math.md → "The rolling-ball certificate") with the origin as the query point and K as
// the shape. So the overlap's multi-start search can stop at the first local minimum it finds
// with F(v) within the two radii.
//
// A partner with flat faces, edges or rims has no rolling ball (ρ_B = 0) and F has kinks there,
// so the certificate takes another form: at a candidate v with A's support point a, the point
// b = a − F(v)·v lies on B's supporting plane along −v; if b lies in B, then a − b = F(v)·v is
// K's support point along v, and the ball of radius ρ_A inside K that touches there holds the
// origin's ball of radius F(v) where F(v) ≤ ρ_A: min F = F(v). If b lies δ outside B, that ball's
// centre moves by δ, and min F ≥ F(v) − δ.
//
// The ball need not roll everywhere: the one of radius F(v) tangent to A at a is enough. If it
// lies in A and b lies in B, K holds the ball of radius F(v) around the origin, and again
// min F = F(v). Whether it lies in A is the point query's inside certificate
// (solvers/ball_certificate.h: a bound on the gauge's Hessian over the ball), with the ball's
// centre b as the query point and a as its nearest surface point; it needs no global curvature
// bound, so it also holds for creased shapes (an exponent > 1, where ρ_A = 0) wherever the
// ball keeps away from the creases.
//
// B can carry a share of F(v): if a ball of radius ρ_B lies in B tangent at b (centred at
// b + ρ_B·v) and one of radius F(v) − ρ_B lies in A tangent at a, their difference is the ball of
// radius F(v) about the origin, inside K (docs/math.md → "The other shape's ball"). Deep
// overlaps, whose local ball pokes out of a thin A, are certified this way where b lies on a
// face or a side of B.

#include <fcl/geometry/shape/ellipsoid.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "common/tangent_basis.h"
#include "fcl_superellipsoid/superellipsoid.h"
#include "narrowphase/sphere_newton.h"
#include "shape/nested_norm.h"
#include "shape/symmetric2.h"
#include "solvers/ball_certificate.h"
#include "solvers/exact_rules.h"

namespace fcl_superellipsoid {
namespace detail {

/// The tolerances, × the larger shape's size: on the tangential gradient of a smooth pair's
/// minimum, and on how far a flat partner's witness may lie beyond its bounding planes (the pairs'
/// depth target is 1e-9 × size).
constexpr double kRollingGradientTolerance = 1e-10;
constexpr double kRollingOutsideTolerance = 1e-12;

/// How far the balls of an overlap may fall short (twoBallsCertified): kRollingOutsideTolerance ×
/// the larger of the superellipsoid's size and the other shape's.
template <typename S>
S overlapTolerance(const Superellipsoid<S>& shape, S other_size) {
  return S(kRollingOutsideTolerance) * std::max(shape.size(), other_size);
}

/// The radius of a ball that rolls freely inside the shape: the superellipsoid's lower bound on
/// its smallest principal radius of curvature (0 where an exponent is > 1; computed on the
/// shape's first use, then kept).
template <typename S>
S rollingRadius(const Superellipsoid<S>& shape) {
  return shape.minRadiusOfCurvature();
}

/// An ellipsoid's smallest principal radius of curvature: c²/a for its smallest and largest
/// semi-axes c and a (at the ends of the longest axis).
template <typename S>
S rollingRadius(const fcl::Ellipsoid<S>& shape) {
  const S largest = shape.radii.maxCoeff(), smallest = shape.radii.minCoeff();
  return largest > S(0) ? smallest * (smallest / largest) : S(0);
}

/// Whether p, a direction of an overlap's F, gives its minimum to within `tolerance` by the
/// rolling balls of radii summing to `rolling_radius` (above): 0 ≤ F(v) ≤ rolling_radius and a
/// tangential gradient of length at most `tolerance`.
template <typename S>
bool rollingCertified(const Probe<S>& p, S rolling_radius, S tolerance) {
  if (!(p.f >= S(0) && p.f <= rolling_radius)) return false;
  const std::array<Vector3<S>, 2> basis = tangentBasis(p.v);
  const Vector3<S>&t1 = basis[0], &t2 = basis[1];
  const Vector3<S> g = p.a - p.b;
  return hypot2(t1.dot(g), t2.dot(g)) <= tolerance;
}

/// The flat partners' form (above): F(v) = f at a candidate whose witness b = a − f·v lies
/// `outside` beyond B's bounding planes or surfaces (a lower bound on b's distance from B, equal to
/// it up to a factor set by B's angles: `tolerance` is of the order of rounding), with ρ_A =
/// `rolling_radius`.
template <typename S>
bool rollingCertified(S f, S rolling_radius, S outside, S tolerance) {
  return f >= S(0) && f <= rolling_radius && outside <= tolerance;
}

/// Whether the ball of radius f tangent to the superellipsoid (posed X_WS) at its support point
/// a along the unit direction v, centred at a − f·v, lies inside it (above), to within `slack`:
/// the ball's centre may sit that far from where the normal at a puts it. In the shape's frame,
/// mirrored into the first octant by the centre's signs (the gauge is mirror-symmetric; a of
/// another octant is not certified).
template <typename S>
bool localBallCertified(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS,
                        const Vector3<S>& v, const Vector3<S>& a, S f, S slack) {
  if (f == S(0)) return true;  // a point ball
  if (!(f > S(0))) return false;
  const Vector3<S> a_L = X_WS.linear().transpose() * (a - X_WS.translation());
  const Vector3<S> centre = a_L - f * (X_WS.linear().transpose() * v);
  Vector3<S> y, nearest;
  for (int i = 0; i < 3; ++i) {
    const bool flip = centre[i] < S(0) || (centre[i] == S(0) && a_L[i] < S(0));
    y[i] = flip ? -centre[i] : centre[i];
    nearest[i] = flip ? -a_L[i] : a_L[i];
  }
  if (!(nearest.minCoeff() >= S(0))) return false;
  const NestedNorm<S> gauge = NestedNorm<S>::gauge(shape);
  const Vector3<S> gradient = gauge.gradient(nearest);
  const S length = gradient.norm();
  if (!(length > S(0)) || !std::isfinite(length)) return false;
  // The ball the Hessian bound certifies is centred where the normal at a puts it.
  const Vector3<S> normal = gradient / length;
  const S error = (y - (nearest - f * normal)).norm();
  if (!(error <= slack)) return false;
  if (hessianBallCertified(gauge, y, nearest, gradient, f, error)) return true;
  int split_budget = DirectionCover<S>::kSplitSupportPoints;
  return directionCoverCertified(directionCover(shape), gauge, y, nearest, normal, gradient, f,
                                 S(exact_rules::kCoverCapLimit), &split_budget);
}

/// The other shape's share of a candidate's ball (above): the largest ρ in [0, most] found for
/// which the ball of radius ρ − deficit centred at b + ρ·v lies in B, b on B's supporting plane
/// along −v, with deficit = outside(b + ρ·v) + ρ ≤ `budget` (the ball's radius short of ρ).
/// `outside(x)` must be, for x inside B, minus x's distance to B's boundary: the largest signed
/// distance to a face plane of a polytope, to the discs' planes and the side of a cylinder or a
/// cone (each an intersection of half-spaces or of a half-space, a slab and a round surface,
/// whose interior distance is the least of the pieces'). Bisection on the deficit, which is
/// convex in ρ (outside is a maximum of convex functions); each accepted ρ is one whose deficit
/// was evaluated. Nothing where b's own deficit exceeds the budget or is not finite.
struct InsideBall {
  double radius, deficit;
};
template <typename S, typename Outside>
std::optional<InsideBall> insideBall(const Outside& outside, const Vector3<S>& b,
                                     const Vector3<S>& v, S most, S budget) {
  auto deficit = [&](S rho) { return S(outside(Vector3<S>(b + rho * v))) + rho; };
  const S at_b = deficit(S(0));
  if (!(at_b <= budget) || !std::isfinite(at_b)) return std::nullopt;
  InsideBall best{0.0, double(std::max(at_b, S(0)))};
  const S at_most = deficit(most);
  if (at_most <= budget) return InsideBall{double(most), double(std::max(at_most, S(0)))};
  constexpr int kHalvings = 24;  // ρ to 6e-8 of `most`: the rest is the superellipsoid's share
  S lo = S(0), hi = most;
  for (int k = 0; k < kHalvings; ++k) {
    const S mid = S(0.5) * (lo + hi);
    const S d = deficit(mid);
    if (d <= budget) {
      lo = mid;
      best = {double(mid), double(std::max(d, S(0)))};
    } else {
      hi = mid;
    }
  }
  return best;
}

/// Whether the candidate v of an overlap, F(v) = f with the superellipsoid's support point a, is
/// the depth to within `tolerance`, by a ball inside K = A − B of radius f around the origin
/// (above): the ball of radius ρ_B inside B tangent at b = a − f·v (insideBall, within half the
/// tolerance), and the ball of radius f − ρ_B inside A tangent at a, by the rolling radius or
/// localBallCertified (within the rest of it). Their difference is the ball K needs.
template <typename S, typename Outside>
bool twoBallsCertified(const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS,
                       const Vector3<S>& v, const Vector3<S>& a, S f, const Outside& outside,
                       S rolling_radius, S tolerance) {
  if (!(f >= S(0))) return false;
  const Vector3<S> b = a - f * v;
  const S out = S(outside(b));
  if (!(out <= tolerance)) return false;
  std::optional<InsideBall> in_b = insideBall(outside, b, v, f, S(0.5) * tolerance);
  if (!in_b) in_b = InsideBall{0.0, double(std::max(out, S(0)))};
  const S rho_a = f - S(in_b->radius);
  if (rollingCertified(rho_a, rolling_radius, S(in_b->deficit), tolerance)) return true;
  return localBallCertified(shape, X_WS, v, a, rho_a, tolerance - S(in_b->deficit));
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_ROLLING_CERTIFICATE_H
