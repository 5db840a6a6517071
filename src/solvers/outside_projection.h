#ifndef FCL_SUPERELLIPSOID_SRC_SOLVERS_OUTSIDE_PROJECTION_H
#define FCL_SUPERELLIPSOID_SRC_SOLVERS_OUTSIDE_PROJECTION_H

// Internal: a slow but certain projection of an outside point onto the superellipsoid, the
// Exact solver's last resort when Newton stalls (mixed exponents such as (0.1, 1.9) on a
// 1000:1 cigar are singular in both of its formulations).
//
// It uses the shape's nesting. With R(x, y) = ‖(x/a1, y/a2)‖_p1 (p1 = 2/ε1) the xy level,
// the shape is {R ≤ ρ, |z| ≤ ζ(ρ)} over ρ ∈ [0, 1], ζ(ρ) = a3·(1 − ρ^p2)^(1/p2). So for Q in
// the first octant
//
//     dist²(Q) = min over ρ ∈ [0, 1] of  φ(ρ) = dist²((Qx, Qy), ρ·K) + max(0, Qz − ζ(ρ))²,
//
// with K the unit xy superellipse. The set {(x, y, z, ρ): R ≤ ρ, |z| ≤ ζ(ρ)} is convex (ζ is
// concave), so φ is convex and its minimiser is the root of the monotone
//
//     φ'(ρ) = −2·(q − x*)·x*/ρ  +  2·max(0, Qz − ζ)·(−ζ'(ρ))      (envelope theorem),
//
// x* the projection of q = (Qx, Qy) onto ρK. That projection is a 2-D problem solved the same
// way: along the quadrant arc x(t) = (A·(1−t), B·t)/‖(1−t, t)‖_p1 (A = ρa1, B = ρa2) the
// tangential component of q − x(t) falls from ≥ 0 at t = 0 to ≤ 0 at t = 1, crossing zero once,
// at the nearest point. Both roots are found by bracketing (Illinois regula falsi, bisection
// when a bracket value is infinite), so the answer is as exact as the arithmetic allows, at a
// cost of a few hundred power evaluations.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "shape/nested_norm.h"

namespace fcl_superellipsoid {
namespace detail {

/// The root of a function that is ≥ 0 at lo and ≤ 0 at hi (or the reverse; only the sign
/// change matters), to the resolution of S. f_lo, f_hi are its values at the ends.
template <typename S, typename F>
S bracketedRoot(F&& f, S lo, S hi, S f_lo, S f_hi) {
  if (f_lo == S(0)) return lo;
  if (f_hi == S(0)) return hi;
  int side = 0;  // Illinois: which end moved last; halve the other end's value if it repeats
  for (int i = 0; i < 400 && hi - lo > S(4) * std::numeric_limits<S>::epsilon() * hi; ++i) {
    S mid = S(0.5) * (lo + hi);
    if (std::isfinite(f_lo) && std::isfinite(f_hi)) {
      const S secant = lo + (hi - lo) * (f_lo / (f_lo - f_hi));
      if (secant > lo && secant < hi) mid = secant;
    }
    const S f_mid = f(mid);
    if (f_mid == S(0) || std::isnan(f_mid)) return mid;
    if ((f_mid > S(0)) == (f_hi > S(0))) {
      hi = mid;
      f_hi = f_mid;
      if (side == -1) f_lo *= S(0.5);
      side = -1;
    } else {
      lo = mid;
      f_lo = f_mid;
      if (side == 1) f_hi *= S(0.5);
      side = 1;
    }
  }
  return S(0.5) * (lo + hi);
}

/// The nearest point to q ≥ 0 on the quadrant arc of the superellipse ‖(x/A, y/B)‖_p = 1
/// (q is outside it; A, B > 0).
template <typename S>
Eigen::Matrix<S, 2, 1> projectOntoSuperellipse(const Eigen::Matrix<S, 2, 1>& q, S a, S b, S p) {
  using V2 = Eigen::Matrix<S, 2, 1>;
  const S inv_p = S(1) / p;
  auto point = [&](S t, V2* gradient) {
    const S u = S(1) - t, v = t;  // direction in scaled coordinates
    const S n = pnorm2(u, v, p, inv_p);
    const S c1 = u / n, c2 = v / n;  // in [0, 1]
    // ∇‖(x/A, y/B)‖_p at the point, up to a positive factor.
    *gradient = V2(std::pow(c1, p - S(1)) / a, std::pow(c2, p - S(1)) / b);
    return V2(a * c1, b * c2);
  };
  // Tangential (counter-clockwise) component of q − x(t).
  auto tangential = [&](S t) {
    V2 g;
    const V2 x = point(t, &g);
    return -g[1] * (q[0] - x[0]) + g[0] * (q[1] - x[1]);
  };
  const S t = bracketedRoot(tangential, S(0), S(1), q[1] / a, -q[0] / b);
  V2 g;
  return point(t, &g);
}

/// The nearest surface point to an outside y ≥ 0 (first octant), per the comment at the top.
template <typename S>
Vector3<S> projectOutside(const Superellipsoid<S>& shape, const Vector3<S>& y) {
  using V2 = Eigen::Matrix<S, 2, 1>;
  const Vector3<S> a = shape.radii();
  const S p1 = S(2) / shape.eps1(), p2 = S(2) / shape.eps2(), inv_p2 = S(1) / p2;
  const V2 q(y[0], y[1]);
  auto zeta = [&](S rho) {
    return a[2] * std::pow(std::max(S(0), S(1) - std::pow(rho, p2)), inv_p2);
  };
  // x* for a level ρ > 0 (q itself when q is inside ρK).
  auto xyProjection = [&](S rho) -> V2 {
    if (pnorm2(q[0] / a[0], q[1] / a[1], p1, S(1) / p1) <= rho) return q;
    return projectOntoSuperellipse(q, rho * a[0], rho * a[1], p1);
  };
  auto slope = [&](S rho) {  // φ'(ρ)/2
    const V2 x = xyProjection(rho);
    const S z_gap = y[2] - zeta(rho);
    S s = -(q - x).dot(x) / rho;
    if (z_gap > S(0)) {
      const S rp = std::pow(rho, p2);
      // −ζ'(ρ) = a3·ρ^(p2−1)·(1 − ρ^p2)^(1/p2 − 1)
      s += z_gap * a[2] * rp / rho * std::pow(std::max(S(0), S(1) - rp), inv_p2 - S(1));
    }
    return s;
  };
  S rho;
  if (q.squaredNorm() == S(0)) {
    rho = S(0);  // on the z axis: the tip
  } else if (y[2] == S(0)) {
    rho = S(1);  // in the xy plane: the equator
  } else {
    // φ'(0⁺) < 0 (moving off the axis helps) and φ'(1⁻) = +∞ (the crease is flat in z);
    // the bracket's end values only need the right sign.
    rho = bracketedRoot(slope, S(0), S(1), -std::numeric_limits<S>::infinity(),
                        std::numeric_limits<S>::infinity());
  }
  const V2 x = rho > S(0) ? xyProjection(rho) : V2::Zero();
  return Vector3<S>(x[0], x[1], std::min(y[2], zeta(rho)));
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SOLVERS_OUTSIDE_PROJECTION_H
