#ifndef FCL_SUPERELLIPSOID_SRC_GAUGE_KERNEL_H
#define FCL_SUPERELLIPSOID_SRC_GAUGE_KERNEL_H

// Internal: the nested-p-norm arithmetic behind Superellipsoid::gauge() and the solvers,
// inline so the solvers' inner loops see through it. Works on the first octant: every
// argument is ≥ 0 (callers reflect with |x|).

#include <algorithm>
#include <cmath>

#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {
namespace detail {

/// ‖(a, b)‖_p for a, b ≥ 0, evaluated as m·(1 + (lo/m)^p)^(1/p) with m = max(a, b), so the
/// only power of a large argument is of (1 + s), s ∈ [0, 1].
template <typename S>
inline S pnorm2(S a, S b, S p, S inv_p) {
  const S m = std::max(a, b);
  if (m == S(0)) return S(0);
  const S lo = std::min(a, b);
  return m * std::pow(S(1) + std::pow(lo / m, p), inv_p);
}

/// ∂‖(a, b)‖_p/∂a = (a/N)^(p−1), N = ‖(a, b)‖_p; in [0, 1]. Zero where N = 0 (p > 1).
template <typename S>
inline S pnormPartial(S a, S norm, S p) {
  return norm > S(0) ? std::pow(a / norm, p - S(1)) : S(0);
}

/// Precomputed constants of a shape: inverse radii and the two p-norm exponents.
template <typename S>
struct GaugeParams {
  explicit GaugeParams(const Superellipsoid<S>& shape)
      : inv_a(shape.radii().cwiseInverse()),
        p1(S(2) / shape.eps1()),
        p2(S(2) / shape.eps2()),
        inv_p1(shape.eps1() / S(2)),
        inv_p2(shape.eps2() / S(2)) {}
  Vector3<S> inv_a;
  S p1, p2, inv_p1, inv_p2;
};

/// G and ∂G/∂u at u = (|x|/a1, |y|/a2, |z|/a3) (all ≥ 0). dG_du is 0-homogeneous.
template <typename S>
struct GaugeEval {
  S g;
  Vector3<S> dG_du;
};

template <typename S>
inline S gaugeOfScaled(const GaugeParams<S>& c, const Vector3<S>& u) {
  const S r = pnorm2(u[0], u[1], c.p1, c.inv_p1);
  return pnorm2(r, u[2], c.p2, c.inv_p2);
}

template <typename S>
inline GaugeEval<S> gaugeAndGradientOfScaled(const GaugeParams<S>& c, const Vector3<S>& u) {
  GaugeEval<S> out;
  // G = N2(r, u3) with r = N1(u1, u2); chain rule through the nested norms. Each factor is
  // a ratio in [0, 1] raised to p − 1 > 0, so the gradient stays bounded everywhere.
  const S r = pnorm2(u[0], u[1], c.p1, c.inv_p1);
  out.g = pnorm2(r, u[2], c.p2, c.inv_p2);
  const S dG_dr = pnormPartial(r, out.g, c.p2);
  out.dG_du[0] = dG_dr * pnormPartial(u[0], r, c.p1);
  out.dG_du[1] = dG_dr * pnormPartial(u[1], r, c.p1);
  out.dG_du[2] = pnormPartial(u[2], out.g, c.p2);
  return out;
}

/// sgn(c)·|c|^e, the signed power of the parametric form.
template <typename S>
inline S signedPow(S c, S e) {
  const S m = std::pow(std::abs(c), e);
  return c < S(0) ? -m : m;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_GAUGE_KERNEL_H
