#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SPHERE_NEWTON_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SPHERE_NEWTON_H

// Internal: Newton's method on the unit sphere for F(v) = h_A(v) + h_B(−v), two smooth support
// functions (support_map.h; B may be a single point, h_B(−v) = −v·b, or a circle): the smooth
// pairs' search (smooth_pair.cpp) and the overlaps' descents of a polytope's vertex, a rim and a
// cone's apex (depth_candidates.h). docs/math.md → "Smooth partners: Newton on the sphere".

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "common/tangent_basis.h"
#include "narrowphase/support_map.h"
#include "shape/symmetric2.h"

namespace fcl_superellipsoid {
namespace detail {

/// Newton iterations per start at most.
constexpr int kSphereNewtonIterations = 200;
/// A full Newton step (no shift, no backtracking) shorter than this (rad) is the last: where
/// Newton converges quadratically the error after it is of order this squared, far below
/// rounding, and the steps after it only wander in F's rounding noise (docs/math.md → "Smooth
/// partners: Newton on the sphere"). In float, whose noise is above 1e-9 rad, √ε/16 instead
/// (2.2e-5 rad: its square is 4e-10, still far below float's rounding).
constexpr double kSphereNewtonConverged = 1e-9;
template <typename S>
S sphereNewtonConverged() {
  return std::max(S(kSphereNewtonConverged), std::sqrt(std::numeric_limits<S>::epsilon()) / 16);
}

/// The Riemannian Hessian's lowest eigenvalue is shifted up to this fraction of its scale where
/// it is lower. Beside a nearly flat face the scale is the face's radius of curvature (up to
/// 1e11 times the size) while the eigenvalue across an edge is of order one: a higher floor
/// shortened each step there by the ratio, and Newton crawled linearly (200 iterations on a
/// fifth of a box-like pair's hits). In float, a tenth of ε, as far as its rounding allows.
template <typename S>
S sphereNewtonFloor() {
  return std::max(S(1e-12), S(0.1) * std::numeric_limits<S>::epsilon());
}

template <typename S>
struct Probe {
  S f;                             // F(v)
  Vector3<S> v;                    // unit
  Vector3<S> a, b;                 // the witnesses
  Eigen::Matrix<S, 3, 3> hessian;  // ∇²F(v)
};

/// F at the unit v, with its Hessian if `with_hessian` (else NaN; F and the witnesses are the
/// same).
template <typename S>
Probe<S> probe(const SupportMap<S>& A, const SupportMap<S>& B, const Vector3<S>& v,
               bool with_hessian = true) {
  const SupportEval<S> ea = A.evaluate(v, with_hessian), eb = B.evaluate(-v, with_hessian);
  return {ea.value + eb.value, v, ea.point, eb.point, ea.hessian + eb.hessian};
}

/// Newton's method for F on the unit sphere from v0, with a backtracking line search and the
/// Riemannian Hessian shifted to positive definite where F is not locally convex; at most
/// `max_iterations` steps, and none after an iterate p (a Probe) with stop(p).
template <typename S, typename Stop = bool (*)(const Probe<S>&)>
Probe<S> localMinimum(
    const SupportMap<S>& A, const SupportMap<S>& B, const Vector3<S>& v0,
    int max_iterations = kSphereNewtonIterations,
    Stop stop = [](const Probe<S>&) { return false; }) {
  Probe<S> p = probe(A, B, Vector3<S>(v0.normalized()));
  const S eps = std::numeric_limits<S>::epsilon();
  for (int it = 0; it < max_iterations; ++it) {
    const std::array<Vector3<S>, 2> basis = tangentBasis(p.v);
    const Vector3<S>&t1 = basis[0], &t2 = basis[1];
    // Riemannian gradient and Hessian: P·∇F and P·∇²F·P − (v·∇F)·P, with v·∇F = F (F is
    // 1-homogeneous).
    const Vector3<S> g = p.a - p.b;
    const S g1 = t1.dot(g), g2 = t2.dot(g);
    S h11 = t1.dot(p.hessian * t1) - p.f, h22 = t2.dot(p.hessian * t2) - p.f;
    const S h12 = t1.dot(p.hessian * t2);
    const S scale = std::abs(h11) + std::abs(h22) + std::abs(p.f) + std::numeric_limits<S>::min();
    const S lowest = S(0.5) * (h11 + h22) - hypot2(S(0.5) * (h11 - h22), h12);
    const S floor = sphereNewtonFloor<S>() * scale;
    const bool shifted = !(lowest > floor);
    if (shifted) {
      const S shift = floor - (std::isfinite(lowest) ? lowest : -scale);
      h11 += shift;
      h22 += shift;
    }
    const S det = h11 * h22 - h12 * h12;
    S x1 = -(h22 * g1 - h12 * g2) / det, x2 = -(h11 * g2 - h12 * g1) / det;
    if (!std::isfinite(x1) || !std::isfinite(x2)) break;
    // A step of more than a quarter turn is not Newton's any more.
    const S length = hypot2(x1, x2);
    if (length > S(0.5)) {
      x1 *= S(0.5) / length;
      x2 *= S(0.5) / length;
    }
    const S slope = g1 * x1 + g2 * x2;  // ≤ 0: the Hessian is positive definite
    // F's rounding: support values are sums of terms as large as |a|, |b|.
    const S noise = S(16) * eps * (p.a.norm() + p.b.norm() + std::abs(p.f));
    bool moved = false, full = false;
    // The full step's probe comes with its Hessian (it is usually taken); the backtracking
    // trials' without, and the one taken gets it afterwards. A trial that rounds to v itself
    // ends the search: it cannot lower F, nor can the shorter ones after it (in float that
    // happens long before α reaches its floor).
    for (S alpha = S(1); alpha > S(1e-12); alpha *= S(0.5)) {
      const Vector3<S> v = (p.v + alpha * (x1 * t1 + x2 * t2)).normalized();
      if (alpha < S(1) && v == p.v) break;
      const Probe<S> q = probe(A, B, v, alpha == S(1));
      if (q.f <= p.f + S(1e-4) * alpha * slope || (q.f <= p.f + noise && alpha == S(1))) {
        moved = (q.v - p.v).norm() > S(0);
        full = alpha == S(1);
        p = full ? q : probe(A, B, v);
        break;
      }
    }
    const bool converged = full && !shifted && length < sphereNewtonConverged<S>();
    if (!moved || length < S(64) * eps || converged || stop(p)) break;
  }
  return p;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SPHERE_NEWTON_H
