#ifndef FCL_SUPERELLIPSOID_SRC_SHAPE_NESTED_NORM_H
#define FCL_SUPERELLIPSOID_SRC_SHAPE_NESTED_NORM_H

// Internal: the nested p-norm behind both faces of a superellipsoid, inline so the solvers'
// inner loops see through it.
//
//   N(w) = ‖( ‖(s1·w1, s2·w2)‖_p1, s3·w3 )‖_p2,   w in the first octant (w_i ≥ 0).
//
// Primal (the gauge G):       s = 1/a, p1 = 2/ε1,        p2 = 2/ε2.
// Dual (the support fn. h):   s = a,   p1 = 2/(2 − ε1),  p2 = 2/(2 − ε2).
// (docs/math.md: h is the gauge of the "dual" superellipsoid with radii 1/a, exponents 2 − ε.)
//
// Both are convex and 1-homogeneous; a level with exponent p ≥ 2 is C² with a bounded
// Hessian, a level with p < 2 has a Hessian that grows like t^(p−2) near that level's
// coordinate planes. The primal is smooth where ε ≤ 1, the dual where ε ≥ 1.
//
// Each p-norm is evaluated after dividing by its largest argument, so every power is of a
// ratio in [0, 1] and nothing overflows (ε → 0, far points, extreme radii).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "fcl_superellipsoid/superellipsoid.h"
#include "shape/evaluation_count.h"

namespace fcl_superellipsoid {
namespace detail {

/// ‖(a, b)‖_p for a, b ≥ 0, evaluated as m·(1 + (lo/m)^p)^(1/p) with m = max(a, b).
template <typename S>
inline S pnorm2(S a, S b, S p, S inv_p) {
  const S m = std::max(a, b);
  if (m == S(0)) return S(0);
  const S lo = std::min(a, b);
  return m * std::pow(S(1) + std::pow(lo / m, p), inv_p);
}

/// The powers (a/N)^(p−1), (b/N)^(p−1) of N = ‖(a, b)‖_p from base-2 logarithms, for
/// NestedNorm::levels: given which argument is the larger (a_is_max), the ratio t = lo/m of
/// the smaller to the larger and log2 t (0 and −∞ where lo = 0). With q = t^p = exp2(p·log2 t)
/// and L = log2(1 + q):
///   (m/N)^(p−1) = (1 + q)^(1/p − 1) = exp2((1/p − 1)·L),   (lo/N)^(p−1) = (q/t)·(m/N)^(p−1),
/// one exp2 after L and no division by (1 + q) on the way; N itself is m·(1 + q)·(m/N)^(p−1).
/// Only ratios in [0, 1] are raised to powers, never N (a product q·N once underflowed for a
/// tiny shape: docs/hardening.md → "Findings", 4 and 10). L is returned too: a second level
/// takes its ratio's logarithm from it before this level's norm is known.
template <typename S>
struct PowersLog2 {
  S pow_a, pow_b;  // (a/N)^(p−1), (b/N)^(p−1)
  S q, log2_1pq;   // t^p, log2(1 + t^p)
  S log2_ratio;    // log2 t (−∞ where t = 0), for the derivatives (shape/gauge_derivatives.h)
  bool a_is_max;
};

template <typename S>
inline PowersLog2<S> pnorm2PowersLog2(bool a_is_max, S ratio, S log2_ratio, S p, S inv_p) {
  // t = 1 gives q = 1 for every p, also p = ∞ (ε subnormal), where p·log2 t would be ∞·0.
  const S q = ratio > S(0) ? (log2_ratio == S(0) ? S(1) : std::exp2(p * log2_ratio)) : S(0);
  const S log2_one_plus_q = std::log2(S(1) + q);
  const S pow_m = std::exp2((inv_p - S(1)) * log2_one_plus_q);
  S pow_lo = S(0);
  if (ratio > S(0)) {
    // q ≥ min implies t ≥ q (p > 1), so the quotient is a normal number in [0, 1]. Below,
    // q carries too few digits; for t < 1/2 pow() gives t^(p−1) instead (docs/hardening.md →
    // "Findings", 4 and 10). For t ≥ 1/2, t^(p−1) ≤ 2q is as small as q, and the quotient
    // keeps its digits; the second level's ratio, from rounded norms, can also exceed 1 there
    // by an ulp where its logarithm says it is below 1, and with p near the format's range a
    // power of it would be ∞ (finding 29). For p = ∞ a q of 0 says t < 1, so t^(p−1) is 0
    // too (pow(1, ∞) = 1 would weigh that argument fully beside the other).
    pow_lo = (q >= std::numeric_limits<S>::min() || ratio >= S(0.5) ? q / ratio
              : std::isinf(p)                                       ? S(0)
                                                                    : std::pow(ratio, p - S(1))) *
             pow_m;
  }
  return a_is_max ? PowersLog2<S>{pow_m, pow_lo, q, log2_one_plus_q, log2_ratio, true}
                  : PowersLog2<S>{pow_lo, pow_m, q, log2_one_plus_q, log2_ratio, false};
}

/// sgn(c)·|c|^e, the signed power of the parametric form.
template <typename S>
inline S signedPow(S c, S e) {
  const S m = std::pow(std::abs(c), e);
  return c < S(0) ? -m : m;
}

template <typename S>
struct NestedNormEval {
  S value;
  Vector3<S> gradient;             // ∂N/∂w, 0-homogeneous, bounded
  Eigen::Matrix<S, 3, 3> hessian;  // ∂²N/∂w², (−1)-homogeneous; only if requested
};

template <typename S>
struct NestedNorm {
  Vector3<S> scale;
  S p1, p2, inv_p1, inv_p2;

  /// The primal gauge G of a shape.
  static NestedNorm gauge(const Superellipsoid<S>& shape) {
    return {shape.radii().cwiseInverse(), S(2) / shape.eps1(), S(2) / shape.eps2(),
            shape.eps1() / S(2), shape.eps2() / S(2)};
  }
  /// The support function h of a shape.
  static NestedNorm support(const Superellipsoid<S>& shape) {
    // 1/q = (2 − ε)/2: one rounding, where 1/(2/(2 − ε)) would take two more and a division.
    const S d1 = S(2) - shape.eps1(), d2 = S(2) - shape.eps2();
    return {shape.radii(), S(2) / d1, S(2) / d2, d1 / S(2), d2 / S(2)};
  }

  S value(const Vector3<S>& w) const {
    countShapeEvaluation();
    const Vector3<S> u = w.cwiseProduct(scale);
    return pnorm2(pnorm2(u[0], u[1], p1, inv_p1), u[2], p2, inv_p2);
  }

  /// The powers of both levels at u = w ⊙ scale ≥ 0, u ≠ 0, from base-2 logarithms: each
  /// level's powers are exp2 of logarithms (pnorm2PowersLog2), and the second level's ratio is
  /// taken from logarithms, log2(r/u3) = log2(m1/u3) + log2(1 + q1)/p1 (r the first level's
  /// norm), the first term computed beside the first level (the SIMD kernel's idea,
  /// batch_kernel.h); its sign says which of r, u3 is the larger. So the second level's chain
  /// of libm calls waits on neither the first level's norm nor its powers, and no pow() is
  /// called (exp2 and log2 cost a fraction of it). Within a few ulps of the powers pow() gives
  /// (docs/math.md → "Support function and the dual shape").
  struct Levels {
    PowersLog2<S> level1, level2;
    S r;     // the first level's norm ‖(u1, u2)‖_p1
    S norm;  // N = ‖(r, u3)‖_p2
  };
  Levels levels(const Vector3<S>& u) const {
    countShapeEvaluation();  // every evaluation but value()'s comes here
    const S inf = std::numeric_limits<S>::infinity();
    const S m1 = std::max(u[0], u[1]), lo1 = std::min(u[0], u[1]);
    // log2(m1/u3) of the quotient, not as a difference of logarithms: its error stays an ulp
    // of the result at any scale (a difference of two logarithms near −1000, on a shape of
    // radius 1e-300, would carry ulps of 1000). An over- or underflowing quotient gives ±∞,
    // and so the ratio 0 it stands for.
    const S log2_m1_u3 = m1 > S(0) && u[2] > S(0) ? std::log2(m1 / u[2]) : -inf;
    const S ratio1 = m1 > S(0) ? lo1 / m1 : S(0);
    const PowersLog2<S> level1 =
        pnorm2PowersLog2(u[0] >= u[1], ratio1, lo1 > S(0) ? std::log2(ratio1) : -inf, p1, inv_p1);
    // log2(r/u3) = log2(m1/u3) + log2(1 + q1)/p1; r = 0 or u3 = 0 make the ratio 0.
    const S log2_r_u3 = log2_m1_u3 + inv_p1 * level1.log2_1pq;
    const bool r_is_max = !(u[2] > S(0)) || (m1 > S(0) && log2_r_u3 >= S(0));
    // ‖(a, b)‖_p = m·(1 + q)^(1/p) = m·(m/N)^(p−1)·(1 + q), from a level's powers: r for the
    // second level's ratio itself (only its last step waits on it), and N.
    const S r = m1 * std::max(level1.pow_a, level1.pow_b) * (S(1) + level1.q);
    const S ratio2 = !(m1 > S(0)) || !(u[2] > S(0)) ? S(0) : r_is_max ? u[2] / r : r / u[2];
    const PowersLog2<S> level2 =
        pnorm2PowersLog2(r_is_max, ratio2, ratio2 > S(0) ? -std::abs(log2_r_u3) : -inf, p2, inv_p2);
    const S norm = (r_is_max ? r : u[2]) * std::max(level2.pow_a, level2.pow_b) * (S(1) + level2.q);
    return {level1, level2, r, norm};
  }

  /// u = factor·(w ⊙ scale) for w ≥ 0: factor = 1, unless a nonzero product would be subnormal
  /// (a direction whose components are 1e300 apart, on a shape of radius 1e-11: the digits of
  /// its small components, which the ratios below are made of, would be lost; docs/hardening.md
  /// → finding 28). Then w is multiplied by a power of 2 first (exactly), so that the largest
  /// product is near 1 and the others stay normal as far as their ratios to it allow.
  struct Scaled {
    Vector3<S> u;
    S factor;
  };
  Scaled scaled(const Vector3<S>& w) const {
    const Vector3<S> u = w.cwiseProduct(scale);
    const S largest = u.maxCoeff();
    bool subnormal = false;
    for (int i = 0; i < 3; ++i) subnormal |= w[i] > S(0) && u[i] < std::numeric_limits<S>::min();
    if (!subnormal || !(largest >= std::numeric_limits<S>::min()) || !std::isfinite(largest)) {
      return {u, S(1)};
    }
    const S factor = std::ldexp(S(1), -std::ilogb(largest));
    return {(w * factor).cwiseProduct(scale), factor};
  }

  /// The gradient alone at w ≥ 0, as evaluate(w, false).gradient, for callers that wait on
  /// it (Superellipsoid::supportPoint: the halfspace and plane pairs, GJK's support).
  Vector3<S> gradient(const Vector3<S>& w) const {
    const Vector3<S> u = scaled(w).u;  // (the gradient is 0-homogeneous)
    if (!(std::max(u[0], u[1]) > S(0)) && !(u[2] > S(0))) return Vector3<S>::Zero();  // the origin
    const Levels l = levels(u);
    return Vector3<S>(l.level2.pow_a * l.level1.pow_a, l.level2.pow_a * l.level1.pow_b,
                      l.level2.pow_b)
        .cwiseProduct(scale);
  }

  /// Value, gradient and (if with_hessian) Hessian at w ≥ 0, from levels().
  NestedNormEval<S> evaluate(const Vector3<S>& w, bool with_hessian) const {
    NestedNormEval<S> out;
    // N is 1-homogeneous, its gradient 0-homogeneous, its Hessian (−1)-homogeneous: the value
    // and the Hessian of the scaled argument are taken back by its factor at the end.
    const auto [u, factor] = scaled(w);
    if (!(std::max(u[0], u[1]) > S(0)) && !(u[2] > S(0))) {
      // the origin: N is not differentiable; report zeros
      out.value = S(0);
      out.gradient.setZero();
      out.hessian.setZero();
      return out;
    }
    const Levels l = levels(u);
    out.value = l.norm;
    // Ratios t ∈ [0, 1] of each argument to its norm, and their powers. With
    // N(a, b) = ‖(a, b)‖_p:  ∂N/∂a = (a/N)^(p−1),
    //   ∂²N/∂a² = (p−1)/N·(a/N)^(p−2)·(b/N)^p,  ∂²N/∂a∂b = −(p−1)/N·(a/N)^(p−1)·(b/N)^(p−1)
    // (using 1 − (a/N)^p = (b/N)^p, which avoids the cancellation).
    const S r1 = l.level1.pow_a, r2 = l.level1.pow_b;    // t1^(p1−1), t2^(p1−1)
    const S g_r = l.level2.pow_a, g_3 = l.level2.pow_b;  // tr^(p2−1), t3^(p2−1)
    const Vector3<S> grad_u(g_r * r1, g_r * r2, g_3);
    out.gradient = grad_u.cwiseProduct(scale);
    if (!with_hessian) {
      if (factor != S(1)) out.value /= factor;
      return out;
    }
    out.hessian = hessian(u, l);
    if (factor != S(1)) {
      out.value /= factor;
      out.hessian *= factor;
    }
    return out;
  }

  /// ∂²N/∂w² at u = w ⊙ scale ≥ 0 (u ≠ 0) from its levels l = levels(u) (evaluate's, and the
  /// derivatives' in gauge_derivatives.h).
  Eigen::Matrix<S, 3, 3> hessian(const Vector3<S>& u, const Levels& l) const {
    const S r = l.r;
    const S r1 = l.level1.pow_a, r2 = l.level1.pow_b;    // t1^(p1−1), t2^(p1−1)
    const S g_r = l.level2.pow_a, g_3 = l.level2.pow_b;  // tr^(p2−1), t3^(p2−1)
    const S t1 = r > S(0) ? u[0] / r : S(0), t2 = r > S(0) ? u[1] / r : S(0);
    const S tr = r / l.norm, t3 = u[2] / l.norm;

    // (t)^(p−2) = t^(p−1)/t; a floor on t keeps it finite when p < 2 (the Hessian is
    // unbounded there: this is the singularity the solver works around, not hides). For p = 2
    // (ε = 1) it is 1, also at t = 0, where the quotient would give 0/floor = 0: on the plane
    // y = 0 of a round cross-section that lost the circle's curvature 1/r from ∂²G/∂y².
    const S floor = std::sqrt(std::numeric_limits<S>::min());
    auto powMinus2 = [floor](S t, S pow_pm1, S p) {
      return p == S(2) ? S(1) : pow_pm1 / std::max(t, floor);
    };
    Eigen::Matrix<S, 3, 3> h_u = Eigen::Matrix<S, 3, 3>::Zero();
    if (r > S(0)) {
      const S c1 = (p1 - S(1)) / r;
      const S r11 = c1 * powMinus2(t1, r1, p1) * (t2 * r2);  // (t2)^p1 = t2·t2^(p1−1)
      const S r22 = c1 * powMinus2(t2, r2, p1) * (t1 * r1);
      const S r12 = -c1 * r1 * r2;
      const S c2 = (p2 - S(1)) / l.norm;
      const S g_rr = c2 * powMinus2(tr, g_r, p2) * (t3 * g_3);
      const S g_r3 = -c2 * g_r * g_3;
      h_u(0, 0) = g_rr * r1 * r1 + g_r * r11;
      h_u(1, 1) = g_rr * r2 * r2 + g_r * r22;
      h_u(0, 1) = h_u(1, 0) = g_rr * r1 * r2 + g_r * r12;
      h_u(0, 2) = h_u(2, 0) = g_r3 * r1;
      h_u(1, 2) = h_u(2, 1) = g_r3 * r2;
    }
    const S c2 = (p2 - S(1)) / l.norm;
    h_u(2, 2) = c2 * powMinus2(t3, g_3, p2) * (tr * g_r);
    return scale.asDiagonal() * h_u * scale.asDiagonal();
  }
};

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SHAPE_NESTED_NORM_H
