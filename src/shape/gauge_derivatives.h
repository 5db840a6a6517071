#ifndef FCL_SUPERELLIPSOID_SRC_SHAPE_GAUGE_DERIVATIVES_H
#define FCL_SUPERELLIPSOID_SRC_SHAPE_GAUGE_DERIVATIVES_H

// Internal: the gauge G and its derivatives with respect to the point and to the shape's five
// parameters θ = (a1, a2, a3, ε1, ε2), at a point of any octant: what the derivatives of the
// distance (solvers/point_derivatives.cpp) are made of (docs/math.md → "Derivatives of the
// distance").
//
// With u = w ⊙ (1/a) (w = |x|), the two levels r = ‖(u1, u2)‖_p1, G = ‖(r, u3)‖_p2 and each
// level's ratios t = argument / norm:
//   ∂M/∂p = (M/p)·L,   L = Σ t^p ln t            (M = ‖·‖_p of a level; t^p ln t → 0 at t = 0)
//   ∂(t^(p−1))/∂p = t^(p−1)·(ln t − (p − 1)·L/p) (holding the level's arguments)
//   ∂G/∂a_j = −(∂G/∂w_j)·w_j/a_j,   ∂(∇G)_i/∂a_j = −(δ_ij (∇G)_i + H_ij w_j)/a_j,
//   ∂/∂ε_k = −(p_k²/2)·∂/∂p_k.
// Only ratios in [0, 1] and their logarithms appear, all from one evaluation of the levels
// (NestedNorm::levels); a ratio of 0 contributes 0.

#include <Eigen/Core>
#include <array>
#include <cmath>

#include "shape/nested_norm.h"

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
struct GaugeDerivatives {
  S value;                                       // G
  Vector3<S> gradient;                           // ∇G
  Eigen::Matrix<S, 3, 3> hessian;                // ∇²G (floored where unbounded: nested_norm.h)
  Eigen::Matrix<S, 1, 5> d_parameters;           // ∂G/∂θ
  Eigen::Matrix<S, 3, 5> gradient_d_parameters;  // ∂(∇G)/∂θ
  // Directions e_i along which the surface's curvature is unbounded at the point: a coordinate
  // plane of a level whose exponent p < 2 (ε > 1), where the point lies (a crease).
  std::array<bool, 3> crease{};
};

/// G's derivatives at x (any octant); the second-order ones (hessian, gradient_d_parameters,
/// crease) only if `second_order` (else zero).
template <typename S>
GaugeDerivatives<S> gaugeDerivatives(const Superellipsoid<S>& shape, const Vector3<S>& x,
                                     bool second_order) {
  const NestedNorm<S> g = NestedNorm<S>::gauge(shape);
  const Vector3<S> w = x.cwiseAbs();
  const Vector3<S> sign(x[0] < S(0) ? S(-1) : S(1), x[1] < S(0) ? S(-1) : S(1),
                        x[2] < S(0) ? S(-1) : S(1));
  GaugeDerivatives<S> out;
  out.hessian.setZero();
  out.d_parameters.setZero();
  out.gradient_d_parameters.setZero();
  // u = factor·(w ⊙ scale), factor = 1 unless a product would be subnormal (NestedNorm::scaled):
  // the ratios are u's, the value and r are taken back by the factor, the Hessian by 1/factor.
  const auto [u, factor] = g.scaled(w);
  if (!(std::max(u[0], u[1]) > S(0)) && !(u[2] > S(0))) {  // the centre
    out.value = S(0);
    out.gradient.setZero();
    return out;
  }
  // One evaluation of the levels gives G, ∇G, ∇²G and every power and logarithm below
  // (nested_norm.h: ∂G/∂u = (g_r·r1, g_r·r2, g_3), r1 = t1^(p1−1), ...).
  const typename NestedNorm<S>::Levels l = g.levels(u);
  const S norm = l.norm / factor, r = l.r / factor;
  const S r1 = l.level1.pow_a, r2 = l.level1.pow_b, g_r = l.level2.pow_a, g_3 = l.level2.pow_b;
  out.value = norm;
  const Vector3<S> gradient_w = Vector3<S>(g_r * r1, g_r * r2, g_3).cwiseProduct(g.scale);
  out.gradient = gradient_w.cwiseProduct(sign);
  Eigen::Matrix<S, 3, 3> hessian_w = Eigen::Matrix<S, 3, 3>::Zero();
  if (second_order) {
    hessian_w = g.hessian(u, l) * factor;
    out.hessian = sign.asDiagonal() * hessian_w * sign.asDiagonal();
  }
  // ln t of a level's arguments: the larger's is −ln(1 + q)/p, the smaller's ln(ratio) more.
  const S ln2 = S(0.693147180559945309417232121458176568L);
  auto logs = [ln2](const PowersLog2<S>& level, S inv_p) {
    const S larger = -level.log2_1pq * inv_p * ln2;
    const S smaller = level.log2_ratio * ln2 + larger;  // −∞ for a 0 argument
    return level.a_is_max ? std::pair<S, S>{larger, smaller} : std::pair<S, S>{smaller, larger};
  };
  const auto [ln_t1, ln_t2] = logs(l.level1, g.inv_p1);
  const auto [ln_tr, ln_t3] = logs(l.level2, g.inv_p2);
  const S t1 = l.r > S(0) ? u[0] / l.r : S(0), t2 = l.r > S(0) ? u[1] / l.r : S(0);
  const S tr = l.r / l.norm, t3 = u[2] / l.norm;
  // t^(p−1)·ln t, 0 where t = 0. (Where the levels' quotient of the arguments overflowed, a
  // ratio below the format's range that is not 0 has ln t = −∞ there: its own logarithm.)
  auto powLog = [](S t, S pow_pm1, S ln_t) {
    if (!(pow_pm1 > S(0)) || !(t > S(0))) return S(0);
    return pow_pm1 * (std::isfinite(ln_t) ? ln_t : std::log(t));
  };
  const S log_t1 = powLog(t1, r1, ln_t1), log_t2 = powLog(t2, r2, ln_t2);
  const S log_tr = powLog(tr, g_r, ln_tr), log_t3 = powLog(t3, g_3, ln_t3);
  const S l1 = t1 * log_t1 + t2 * log_t2;  // Σ t^p1 ln t
  const S l2 = tr * log_tr + t3 * log_t3;
  const S dp1 = -g.p1 * g.p1 / S(2), dp2 = -g.p2 * g.p2 / S(2);  // ∂p/∂ε

  // Radii, then the exponents (∂r/∂p1 = r·l1/p1, and G depends on r through ∂G/∂r = g_r).
  const Vector3<S>& a = shape.radii();
  for (int j = 0; j < 3; ++j) out.d_parameters[j] = -gradient_w[j] * w[j] / a[j];
  out.d_parameters[3] = dp1 * g_r * r * l1 / g.p1;
  out.d_parameters[4] = dp2 * norm * l2 / g.p2;
  if (!second_order) return out;

  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      const S diagonal = i == j ? gradient_w[i] : S(0);
      out.gradient_d_parameters(i, j) = -(diagonal + hessian_w(i, j) * w[j]) / a[j];
    }
  }
  // ∂(∇_u G)/∂p1: the first level's powers change, and r with them (∂g_r/∂r·∂r/∂p1 =
  // (p2 − 1)·g_r·t3^p2·l1/p1, ∂g_3/∂r·∂r/∂p1 = −(p2 − 1)·g_r·g_3·(r/G)·l1/p1).
  const S rho1 = r1 > S(0) ? log_t1 - r1 * (g.p1 - S(1)) * l1 / g.p1 : S(0);
  const S rho2 = r2 > S(0) ? log_t2 - r2 * (g.p1 - S(1)) * l1 / g.p1 : S(0);
  const S dgr_dp1 = (g.p2 - S(1)) * g_r * (t3 * g_3) * l1 / g.p1;
  const S dg3_dp1 = -(g.p2 - S(1)) * g_r * g_3 * tr * l1 / g.p1;
  const Vector3<S> du_dp1(dgr_dp1 * r1 + g_r * rho1, dgr_dp1 * r2 + g_r * rho2, dg3_dp1);
  // ∂(∇_u G)/∂p2: the second level's powers.
  const S gamma_r = log_tr - g_r * (g.p2 - S(1)) * l2 / g.p2;
  const S gamma_3 = log_t3 - g_3 * (g.p2 - S(1)) * l2 / g.p2;
  const Vector3<S> du_dp2(r1 * gamma_r, r2 * gamma_r, gamma_3);
  out.gradient_d_parameters.col(3) = dp1 * du_dp1.cwiseProduct(g.scale);
  out.gradient_d_parameters.col(4) = dp2 * du_dp2.cwiseProduct(g.scale);
  for (int j = 0; j < 3; ++j) out.gradient_d_parameters.row(j) *= sign[j];

  // Creases: a level with p < 2 has unbounded curvature across its coordinate planes.
  if (g.p1 < S(2) && l.r > S(0)) {
    out.crease[0] = u[0] == S(0);
    out.crease[1] = u[1] == S(0);
  }
  if (g.p2 < S(2)) {
    out.crease[2] = u[2] == S(0) && l.r > S(0);
    if (!(l.r > S(0))) out.crease[0] = out.crease[1] = true;
  }
  return out;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SHAPE_GAUGE_DERIVATIVES_H
