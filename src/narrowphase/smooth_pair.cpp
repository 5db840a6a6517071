#include "narrowphase/smooth_pair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "common/tangent_basis.h"
#include "narrowphase/rolling_certificate.h"
#include "narrowphase/sphere_newton.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

/// How many of the start directions are refined when the first run does not find the shapes
/// separated.
constexpr int kRefinedStarts = 4;
/// Fibonacci-sphere directions added to the starts when the shapes overlap.
constexpr int kSphereStarts = 32;

/// Directions spread evenly over the sphere (a Fibonacci lattice).
template <typename S>
Vector3<S> sphereDirection(int i, int n) {
  const double golden = 2.39996322972865332;  // π(3 − √5)
  const double z = 1.0 - (2.0 * i + 1.0) / n;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vector3<S>(S(r * std::cos(golden * i)), S(r * std::sin(golden * i)), S(z));
}

/// The witnesses at Newton's last direction v. The support points a = ∇h_A(v), b = ∇h_B(−v) are
/// on their surfaces, but their difference is along v only at the minimiser v* = v + δ; to first
/// order they move there by H_A·δ and −H_B·δ (H the support functions' Hessians), with δ solving
/// P(H_A + H_B)P·δ = −P(a − b) in the tangent plane (P its projector). Newton stops near v*, but
/// beside a nearly flat face (a box-like superellipsoid's face centre, where the Hessian, the
/// radius of curvature, grows without bound) a support point moves by that distance times the
/// radius: 1e-13 rad moves a support point metres across a 40 m floor's face, and the first-order
/// move, which a face's slight curvature makes wrong by as much, leaves the pair where the faces
/// are farther apart than the distance. So the better-determined witness (the smaller move) stays
/// where its support point is, and the other is put on its body's surface along v through it:
/// their difference is along v, and their gap is the distance to second order in the kept
/// witness's move. Without this the difference was 3e-5 off the normal on one box-like pair,
/// which the distance does not see (F is flat at its minimum) and the gradient's rotation parts
/// do (pair_derivatives.h). The distance and the normal are kept.
template <typename S>
void consistentWitnesses(const SupportMap<S>& A, const SupportMap<S>& B, const Probe<S>& p,
                         Vector3<S>& on_a, Vector3<S>& on_b) {
  const SupportEval<S> ea = A.evaluate(p.v, true), eb = B.evaluate(Vector3<S>(-p.v), true);
  on_a = ea.point;
  on_b = eb.point;
  const std::array<Vector3<S>, 2> basis = tangentBasis(p.v);
  const Vector3<S>&t1 = basis[0], &t2 = basis[1];
  const Vector3<S> gap = ea.point - eb.point;
  const Eigen::Matrix<S, 3, 3> K3 = ea.hessian + eb.hessian;
  const S k11 = t1.dot(K3 * t1), k22 = t2.dot(K3 * t2), k12 = t1.dot(K3 * t2);
  const S g1 = t1.dot(gap), g2 = t2.dot(gap);
  const S det = k11 * k22 - k12 * k12;
  const S x1 = -(k22 * g1 - k12 * g2) / det, x2 = -(k11 * g2 - k12 * g1) / det;
  if (!(det > S(0)) || !std::isfinite(x1) || !std::isfinite(x2)) return;
  const Vector3<S> delta = x1 * t1 + x2 * t2;
  const S move_a = (ea.hessian * delta).squaredNorm(), move_b = (eb.hessian * delta).squaredNorm();
  if (!std::isfinite(move_a) || !std::isfinite(move_b)) return;
  // a − b = F(v)·v at the minimiser (F = h_A(v) + h_B(−v) = v·(a − b) there).
  const S f = p.v.dot(gap);
  if (move_b <= move_a) {
    on_a = A.ontoSurfaceAlong(Vector3<S>(on_b + f * p.v), p.v);
  } else {
    on_b = B.ontoSurfaceAlong(Vector3<S>(on_a - f * p.v), Vector3<S>(-p.v));
  }
}

}  // namespace

/// The answer for A and B; where they overlap, `rolling_radius()` gives ρ_A + ρ_B and
/// `tolerance` bounds the tangential gradient for the certificate (rolling_certificate.h).
template <typename S, typename RollingRadius>
SmoothPairAnswer<S> solveSmoothPair(const SupportMap<S>& A, const SupportMap<S>& B,
                                    const RollingRadius& rolling_radius, S tolerance) {
  const Vector3<S> centres = B.centre() - A.centre();
  const Vector3<S> first = centres.squaredNorm() > S(0) ? centres : Vector3<S>::UnitZ();
  Probe<S> best = localMinimum(A, B, first);
  // Not found separated: overlapping (or touching). The first run's minimum is the depth where
  // the rolling balls certify it; otherwise F may have several local minima, and Newton runs
  // from the lowest of: both frames' axes, a lattice over the sphere.
  if (!(best.f < S(0)) && !rollingCertified(best, rolling_radius(), tolerance)) {
    std::vector<Probe<S>> starts;
    auto add = [&](const Vector3<S>& v) { starts.push_back(probe(A, B, v, false)); };
    for (int i = 0; i < 3; ++i) {
      for (S sign : {S(1), S(-1)}) {
        add(sign * A.pose().linear().col(i));
        add(sign * B.pose().linear().col(i));
      }
    }
    for (int i = 0; i < kSphereStarts; ++i) add(sphereDirection<S>(i, kSphereStarts));
    const int refined = std::min<int>(kRefinedStarts, static_cast<int>(starts.size()));
    std::partial_sort(starts.begin(), starts.begin() + refined, starts.end(),
                      [](const Probe<S>& x, const Probe<S>& y) { return x.f < y.f; });
    for (int k = 0; k < refined; ++k) {
      const Probe<S> p = localMinimum(A, B, starts[k].v);
      if (p.f < best.f) best = p;
    }
  }
  SmoothPairAnswer<S> out;
  out.distance = -best.f;
  consistentWitnesses(A, B, best, out.on_a, out.on_b);
  out.normal = best.v;
  return out;
}

namespace {

/// The pair of smooth shapes, `other` of size `other_size`.
template <typename S, typename Other>
std::optional<PairHit<S>> smoothHit(const ShapePair<S>& pair, const Other& other, S other_size) {
  const SupportMap<S> shape(*pair.shape, *pair.X_WS);
  // The rolling radii are asked for only where the first run finds an overlap: a
  // superellipsoid's is computed on its first use.
  const S tolerance = S(kRollingGradientTolerance) * std::max(pair.shape->size(), other_size);
  const SmoothPairAnswer<S> r = solveSmoothPair(
      shape, SupportMap<S>(other, *pair.X_WO),
      [&] { return rollingRadius(*pair.shape) + rollingRadius(other); }, tolerance);
  return PairHit<S>{r.distance, r.on_b, r.on_a, r.normal, -1};
}

}  // namespace

template <typename S>
std::optional<PairHit<S>> superellipsoidHit(const ShapePair<S>& pair,
                                            const Superellipsoid<S>& other) {
  return smoothHit(pair, other, other.size());
}

template <typename S>
std::optional<PairHit<S>> ellipsoidHit(const ShapePair<S>& pair, const fcl::Ellipsoid<S>& other) {
  return smoothHit(pair, other, other.radii.maxCoeff());
}

#define FSE_INSTANTIATE_SMOOTH_HIT(S)                                             \
  template std::optional<PairHit<S>> superellipsoidHit(const ShapePair<S>&,       \
                                                       const Superellipsoid<S>&); \
  template std::optional<PairHit<S>> ellipsoidHit(const ShapePair<S>&, const fcl::Ellipsoid<S>&);
FSE_INSTANTIATE_SMOOTH_HIT(float)
FSE_INSTANTIATE_SMOOTH_HIT(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
