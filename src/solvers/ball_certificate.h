#ifndef FCL_SUPERELLIPSOID_SRC_SOLVERS_BALL_CERTIFICATE_H
#define FCL_SUPERELLIPSOID_SRC_SOLVERS_BALL_CERTIFICATE_H

// Internal: the Hessian-ball certificate of an inside answer (docs/math.md → "The Hessian-ball
// certificate"). Inside, Newton converges to a local nearest point N at distance d from Q; it
// is the global one if no surface point is nearer, that is if the ball B(Q, d) lies inside the
// shape. With n the unit normal at N and Q' = N − d·n (Q itself up to paper Eq. 7's error),
// Taylor's theorem on the segment from N to a point P of B(Q', d) gives, since G(N) = 1,
//
//   G(P) ≤ 1 + ∇G(N)·(P − N) + ½·M·‖P − N‖²,   M ≥ ‖∇²G‖ everywhere on B(Q', d).
//
// With P = Q' + d·u (u a unit vector, c = u·n): ∇G(N)·(P − N) = −‖∇G(N)‖·d·(1 − c) and
// ‖P − N‖² = 2·d²·(1 − c), so G(P) ≤ 1 − d·(1 − c)·(‖∇G(N)‖ − M·d) ≤ 1 whenever
//
//   M·d ≤ ‖∇G(N)‖.
//
// Then B(Q', d) lies inside the shape, every surface point is at least d from Q' and at least
// d − ‖Q − Q'‖ from Q: N is the global answer up to the error it already carries. Unlike the
// rolling-ball certificate it needs no global curvature bound, only one over the small ball,
// so it also holds on creased shapes (ε > 1), where ∇²G is unbounded near the creases (below).
//
// M comes from a closed form. For a 2-argument p-norm N(a, b) with ratios ta = a/N, tb = b/N,
//   ∇²N = (p − 1)/N · (ta·tb)^(p−2) · (tb, −ta)(tb, −ta)ᵀ,
// a rank-one matrix, so for the nested gauge G = N2(N1(s1·x, s2·y), s3·z) (nested_norm.h;
// r = N1, t1 = s1·x/r, t2 = s2·y/r, tr = r/G, t3 = s3·z/G) the chain rule gives
//   ‖∇²G‖ ≤ tr^(p2−1)·(p1 − 1)/r·(t1·t2)^(p1−2)·(s1²·t2² + s2²·t1²)
//         + (p2 − 1)/G·(tr·t3)^(p2−2)·(t3²·(s1²·t1^(2p1−2) + s2²·t2^(2p1−2)) + tr²·s3²).
// Over a box [lo, hi] of the first octant every quantity is monotone in each coordinate (the
// norms grow with every argument; a ratio grows with its own argument and falls with the
// other), so each is bounded by evaluating it at the box's corners, and each power by the end
// of its range that makes it largest.
//
// A box that reaches a coordinate plane whose level has p < 2 (a crease, ε > 1) has no finite
// bound: there (t1·t2)^(p1−2) grows like x^(p1−2) (or y, or z^(p2−2) for the outer level). That
// power is integrable along a segment (p − 2 > −1), so the bound is split instead,
//   ‖∇²G(P)‖ ≤ M0 + cx·Px^(p1−2) + cy·Py^(p1−2) + cz·Pz^(p2−2),
// with t1 ≥ s1·x/r_max (so t1^(p1−2) ≤ (s1/r_max)^(p1−2)·x^(p1−2)) and likewise t3, and
// Taylor's theorem with the integral remainder replaces ½·M·‖P − N‖²:
//   G(P) ≤ 1 + ∇G(N)·(P − N) + ‖P − N‖²·∫₀¹ (1 − t)·‖∇²G(N + t·(P − N))‖ dt.
// For a segment from N to a point P of the octant (Px ≥ 0) and k = p − 2 ∈ (−1, 0),
// ∫₀¹ (1 − t)·(Nx + t·(Px − Nx))^k dt is largest at Px = 0, where it is Nx^k/(2 + k). So the
// certificate holds with M = M0 + 2·Σ c_i·N_i^(k_i)/(2 + k_i): N itself must stay off the
// crease, the ball may cross it. (A box reaching the z axis, where r → 0, is not certified.)

#include <algorithm>
#include <cmath>
#include <limits>

#include "shape/nested_norm.h"
#include "shape/symmetric2.h"
#include "solvers/direction_cover.h"

namespace fcl_superellipsoid {
namespace detail {

/// x^k for x ≥ 0 as exp2(k·log2 x): within a few ulps of pow() (the 1 % margin of the bounds
/// below covers them) at a fraction of its cost; the bounds take 20–30 powers each. 0^k is 0 for
/// k > 0 and ∞ for k < 0, as pow() gives; x^0 and 1^k are 1 (where k·log2 x would be 0·∞).
template <typename S>
inline S boundPow(S x, S k) {
  if (k == S(0) || x == S(1)) return S(1);
  return std::exp2(k * std::log2(x));
}

/// ‖(a, b)‖_p for a, b ≥ 0 from boundPow, as pnorm2 (nested_norm.h) computes it.
template <typename S>
inline S boundNorm(S a, S b, S p, S inv_p) {
  const S m = std::max(a, b);
  if (m == S(0)) return S(0);
  return m * boundPow(S(1) + boundPow(std::min(a, b) / m, p), inv_p);
}

/// An upper bound of ‖∇²G‖ (spectral norm) over a box of the first octant: at a point P of the
/// box, regular + crease[0]·Px^(p1−2) + crease[1]·Py^(p1−2) + crease[2]·Pz^(p2−2). A crease
/// coefficient is non-zero only where the box reaches that plane of a crease (p < 2).
template <typename S>
struct HessianBound {
  S regular = S(0);
  Vector3<S> crease = Vector3<S>::Zero();
};

/// Two-sided bounds lo ≤ ‖(a, b)‖_p ≤ hi of a 2-argument p-norm at one of a box's corners.
template <typename S>
struct NormBracket {
  S lo, hi;
};

/// A 2-argument p-norm bracketed without a power: between the 2-norm and the 1-norm (p ≤ 2) or
/// the max norm and the 2-norm (p ≥ 2), narrowed by the constants of Hölder's inequality for two
/// arguments, ‖v‖_p ≤ 2^(1/p − 1/2)·‖v‖_2 and ‖v‖_1 ≤ 2^(1 − 1/p)·‖v‖_p (p ≤ 2),
/// ‖v‖_2 ≤ 2^(1/2 − 1/p)·‖v‖_p and ‖v‖_p ≤ 2^(1/p)·‖v‖_∞ (p ≥ 2): each bracket within a factor
/// 2^0.21 ≈ 1.16 of the norm, widened by a few ulps for its rounding. One exp2 per level, then
/// a square root per norm.
template <typename S>
class HolderBracket {
 public:
  HolderBracket(S p, S inv_p)
      : below_two_(p <= S(2)),
        c_(std::exp2(inv_p - S(0.5))),                 // 2^(1/p − 1/2)
        f_(below_two_ ? c_ / kRoot2 : c_ * kRoot2) {}  // 2^(1/p − 1), 2^(1/p)

  NormBracket<S> operator()(S a, S b) const {
    const S two = hypot2(a, b);
    const S lo = below_two_ ? std::max(two, f_ * (a + b)) : std::max(std::max(a, b), c_ * two);
    const S hi = below_two_ ? std::min(a + b, c_ * two) : std::min(two, f_ * std::max(a, b));
    const S widen = S(8) * std::numeric_limits<S>::epsilon();
    return {lo * (S(1) - widen), hi * (S(1) + widen)};
  }

 private:
  static constexpr S kRoot2 = S(1.41421356237309504880);
  bool below_two_;
  S c_, f_;
};

/// The norms evaluated (boundNorm): a bracket of width 0.
template <typename S>
auto exactNorm(S p, S inv_p) {
  return [p, inv_p](S a, S b) {
    const S n = boundNorm(a, b, p, inv_p);
    return NormBracket<S>{n, n};
  };
}

/// The bound below from its corners' norms, however they are known: `n1(a, b)` and `n2(a, b)`
/// bracket the first and the second level's norms, and every quantity is taken at the end of
/// its norms' brackets that makes the bound larger (`upper`) or smaller (not `upper`: then
/// the result is no bound of ‖∇²G‖, but the exact bound is not below it). Each quantity is
/// monotone in each norm it reads, so either way the exact bound lies between the two.
template <typename S, typename Norm1, typename Norm2>
HessianBound<S> hessianBoundFromCorners(const NestedNorm<S>& gauge, const Vector3<S>& lo,
                                        const Vector3<S>& hi, bool upper, const Norm1& n1,
                                        const Norm2& n2) {
  const Vector3<S> ul = lo.cwiseProduct(gauge.scale), uh = hi.cwiseProduct(gauge.scale);
  HessianBound<S> bound;
  if (ul[0] == S(0) && ul[1] == S(0)) {  // the z axis: no finite bound
    bound.regular = std::numeric_limits<S>::infinity();
    return bound;
  }
  const S p1 = gauge.p1, p2 = gauge.p2;
  const S k1 = p1 - S(2), k2 = p2 - S(2);
  // A norm where the bound wants it small (a denominator) and where it wants it large.
  auto small = [upper](const NormBracket<S>& b) { return upper ? b.lo : b.hi; };
  auto large = [upper](const NormBracket<S>& b) { return upper ? b.hi : b.lo; };
  // t^k for t in [t_lo, t_hi] ⊂ [0, 1], at its largest.
  auto power = [](S t_lo, S t_hi, S k) {
    return k >= S(0) ? boundPow(t_hi, k) : boundPow(t_lo, k);
  };
  const S one = S(1);
  // The first level: r and the ratios t1, t2.
  const NormBracket<S> r_12 = n1(ul[0], uh[1]), r_21 = n1(uh[0], ul[1]);  // mixed corners
  const S r_lo = small(n1(ul[0], ul[1])), r_hi = large(n1(uh[0], uh[1]));
  const S t1_lo = ul[0] / large(r_12), t1_hi = std::min(one, uh[0] / small(r_21));
  const S t2_lo = ul[1] / large(r_21), t2_hi = std::min(one, uh[1] / small(r_12));
  // The second level: G and the ratios tr, t3 (r/G grows with r, z/G falls with it).
  const NormBracket<S> g_r3 = n2(r_lo, uh[2]), g_3r = n2(r_hi, ul[2]);  // mixed corners
  const S g_lo = small(n2(r_lo, ul[2])), g_hi = large(n2(r_hi, uh[2]));
  const S tr_lo = r_lo / large(g_r3), tr_hi = std::min(one, r_hi / small(g_3r));
  const S t3_lo = ul[2] / large(g_3r), t3_hi = std::min(one, uh[2] / small(g_r3));
  const S s1 = gauge.scale[0] * gauge.scale[0], s2 = gauge.scale[1] * gauge.scale[1];
  const S s3 = gauge.scale[2] * gauge.scale[2];
  // The first rank-one term: factor · (t1·t2)^k1.
  const S first =
      power(tr_lo, tr_hi, p2 - one) * (p1 - one) / r_lo * (s1 * t2_hi * t2_hi + s2 * t1_hi * t1_hi);
  if (k1 < S(0) && ul[0] == S(0)) {  // t1 ≥ s1·x/r_hi
    bound.crease[0] = first * boundPow(gauge.scale[0] / r_hi, k1) * boundPow(t2_lo, k1);
  } else if (k1 < S(0) && ul[1] == S(0)) {
    bound.crease[1] = first * boundPow(gauge.scale[1] / r_hi, k1) * boundPow(t1_lo, k1);
  } else {
    bound.regular += first * power(t1_lo * t2_lo, t1_hi * t2_hi, k1);
  }
  // The second: factor · (tr·t3)^k2.
  const S second = (p2 - one) / g_lo *
                   (t3_hi * t3_hi *
                        (s1 * power(t1_lo, t1_hi, S(2) * p1 - S(2)) +
                         s2 * power(t2_lo, t2_hi, S(2) * p1 - S(2))) +
                    tr_hi * tr_hi * s3);
  if (k2 < S(0) && ul[2] == S(0)) {  // t3 ≥ s3·z/g_hi
    bound.crease[2] = second * boundPow(gauge.scale[2] / g_hi, k2) * boundPow(tr_lo, k2);
  } else {
    bound.regular += second * power(tr_lo * t3_lo, tr_hi * t3_hi, k2);
  }
  return bound;
}

/// The bound above for the box [lo, hi] (0 ≤ lo ≤ hi) and the gauge G of `gauge`, its 8 norms
/// evaluated (boundNorm); its regular part is +∞ where none is finite (a box reaching the z
/// axis).
template <typename S>
HessianBound<S> hessianNormBound(const NestedNorm<S>& gauge, const Vector3<S>& lo,
                                 const Vector3<S>& hi) {
  return hessianBoundFromCorners(gauge, lo, hi, true, exactNorm(gauge.p1, gauge.inv_p1),
                                 exactNorm(gauge.p2, gauge.inv_p2));
}

/// The same with every norm bracketed without a power (HolderBracket): `upper`, a bound of
/// ‖∇²G‖ (looser than hessianNormBound's); not `upper`, a value hessianNormBound's is not
/// below. Two exp2 calls and 8 square roots in place of 32 calls to exp2 and log2.
template <typename S>
HessianBound<S> bracketedHessianNormBound(const NestedNorm<S>& gauge, const Vector3<S>& lo,
                                          const Vector3<S>& hi, bool upper) {
  return hessianBoundFromCorners(gauge, lo, hi, upper, HolderBracket<S>(gauge.p1, gauge.inv_p1),
                                 HolderBracket<S>(gauge.p2, gauge.inv_p2));
}

/// A cheaper, looser bound of the same form (at most two powers instead of 8 norms and 5
/// powers): every 2-argument p-norm N(a, b) (p ≥ 1) over the box is bounded by
/// max(a, b) ≤ N ≤ 2·max(a, b), every power of a ratio t ∈ [0, 1] with a non-negative exponent
/// by 1, so only the negative powers of the two levels (p < 2) are taken, at the ratios' lower
/// bounds. Tried first: on shallow points the ball is small and the looser bound still holds.
template <typename S>
HessianBound<S> quickHessianNormBound(const NestedNorm<S>& gauge, const Vector3<S>& lo,
                                      const Vector3<S>& hi) {
  const S k1 = gauge.p1 - S(2), k2 = gauge.p2 - S(2);
  const Vector3<S> ul = lo.cwiseProduct(gauge.scale), uh = hi.cwiseProduct(gauge.scale);
  HessianBound<S> bound;
  if (ul[0] == S(0) && ul[1] == S(0)) {
    bound.regular = std::numeric_limits<S>::infinity();
    return bound;
  }
  const S r_lo = std::max(ul[0], ul[1]), r_hi = S(2) * std::max(uh[0], uh[1]);
  const S g_lo = std::max(r_lo, ul[2]), g_hi = S(2) * std::max(r_hi, uh[2]);
  // Lower bounds of the ratios t1 = u0/r, t2 = u1/r, tr = r/G, t3 = u2/G over the box.
  const S t1_lo = ul[0] / r_hi, t2_lo = ul[1] / r_hi, tr_lo = r_lo / g_hi, t3_lo = ul[2] / g_hi;
  const S s1 = gauge.scale[0] * gauge.scale[0], s2 = gauge.scale[1] * gauge.scale[1];
  const S s3 = gauge.scale[2] * gauge.scale[2];
  // The first term: (p1 − 1)/r·(t1·t2)^k1·(s1·t2² + s2·t1²), tr^(p2−1) ≤ 1.
  const S first = (gauge.p1 - S(1)) / r_lo * (s1 + s2);
  if (k1 >= S(0)) {
    bound.regular += first;
  } else if (ul[0] == S(0)) {  // t1 ≥ s1·x/r_hi
    bound.crease[0] = first * boundPow(gauge.scale[0] / r_hi * t2_lo, k1);
  } else if (ul[1] == S(0)) {
    bound.crease[1] = first * boundPow(gauge.scale[1] / r_hi * t1_lo, k1);
  } else {
    bound.regular += first * boundPow(t1_lo * t2_lo, k1);
  }
  // The second: (p2 − 1)/G·(tr·t3)^k2·(t3²·(s1·t1^(2p1−2) + s2·t2^(2p1−2)) + tr²·s3).
  const S second = (gauge.p2 - S(1)) / g_lo * (s1 + s2 + s3);
  if (k2 >= S(0)) {
    bound.regular += second;
  } else if (ul[2] == S(0)) {  // t3 ≥ s3·z/g_hi
    bound.crease[2] = second * boundPow(gauge.scale[2] / g_hi * tr_lo, k2);
  } else {
    bound.regular += second * boundPow(tr_lo * t3_lo, k2);
  }
  return bound;
}

/// True if M·d ≤ ‖∇G(N)‖ holds (with a 1 % margin for the bound's rounding) for M from `bound`,
/// a bound over a box that holds every segment from N (the answer, on the surface) to a point of
/// the ball it has to certify: its regular part plus each crease term integrated along such a
/// segment, 2·c_i·N_i^k_i/(2 + k_i) (k: the crease exponents per axis, p − 2 of its level).
template <typename S>
bool hessianBoundCertifies(const HessianBound<S>& bound, const Vector3<S>& k,
                           const Vector3<S>& nearest, const Vector3<S>& gradient_at_n, S distance,
                           S margin = S(1.01)) {
  S m = bound.regular;
  for (int i = 0; i < 3; ++i) {
    if (bound.crease[i] == S(0)) continue;
    m += S(2) * bound.crease[i] * boundPow(nearest[i], k[i]) / (S(2) + k[i]);  // ∞ at N on it
  }
  return margin * m * distance <= gradient_at_n.norm();
}

/// The certificate over the first-octant box [lo, hi] with the gauge's bounds, the quick one
/// first.
template <typename S>
bool hessianBoxCertifies(const NestedNorm<S>& gauge, const Vector3<S>& lo, const Vector3<S>& hi,
                         const Vector3<S>& nearest, const Vector3<S>& gradient_at_n, S distance) {
  if (lo[0] == S(0) && lo[1] == S(0)) return false;  // the z axis: decided without pow()
  const Vector3<S> k(gauge.p1 - S(2), gauge.p1 - S(2), gauge.p2 - S(2));
  auto holds = [&](const HessianBound<S>& bound, S margin = S(1.01)) {
    return hessianBoundCertifies(bound, k, nearest, gradient_at_n, distance, margin);
  };
  if (holds(quickHessianNormBound(gauge, lo, hi))) return true;
  if (holds(bracketedHessianNormBound(gauge, lo, hi, true))) return true;
  // Where even the value below the exact bound fails (a 1 % margin the other way for the
  // rounding), the exact one does too: not evaluated.
  if (!holds(bracketedHessianNormBound(gauge, lo, hi, false), S(0.99))) return false;
  return holds(hessianNormBound(gauge, lo, hi));
}

/// The certificate above for a converged inside answer, in the first octant: Q (y), its
/// nearest point N (on the surface) with the gauge's gradient there, the distance d = ‖Q − N‖
/// and Eq. 7's error. The ball B(Q', d) lies within d + error of Q; its box is clamped to the
/// octant (the gauge is mirror-symmetric, so a ball reaching across a plane is inside the shape
/// if its part in the octant is: the rest mirrors into it). The bound is exact in real
/// arithmetic; a 1 % margin covers its rounding.
template <typename S>
bool hessianBallCertified(const NestedNorm<S>& gauge, const Vector3<S>& y,
                          const Vector3<S>& nearest, const Vector3<S>& gradient_at_n, S distance,
                          S error) {
  const S reach = distance + error;
  const Vector3<S> lo = (y.array() - reach).max(S(0)).matrix();
  const Vector3<S> hi = (y.array() + reach).matrix();
  return hessianBoxCertifies(gauge, lo, hi, nearest, gradient_at_n, distance);
}

/// The Hessian bound of a surface of revolution's meridian section: with ε1 = 1 and equal x and
/// y radii a, the solid is {g(s, z) ≤ 1}, s the distance from the z axis and
/// g(s, z) = ‖(s/a, z/c)‖_p2 (G on the plane y = 0). Its Hessian is the rank-one
///   ∇²g = (p2 − 1)/g·(ts·tz)^(p2−2)·(tz/a, −ts/c)(tz/a, −ts/c)ᵀ,  ts = (s/a)/g, tz = (z/c)/g,
/// bounded over the box [lo, hi] of the (s, z) quadrant like the second level of
/// hessianNormBound, from its corners' norms bracketed by `norm` (each quantity at the end that
/// makes the bound larger), with crease[0] for the axis s = 0 (the tip of a shape with
/// ε2 > 1: ts → 0) and crease[2] for z = 0. No circle's curvature 1/s: that is the third
/// dimension's, which the meridian disc does not need (hessianDiscCertified). Regular part +∞
/// where the box reaches both (the centre of a creased section).
template <typename S, typename Norm>
HessianBound<S> meridianBoundFromCorners(const NestedNorm<S>& gauge, S s_lo, S s_hi, S z_lo, S z_hi,
                                         Norm norm) {
  const S p = gauge.p2, k = p - S(2), one = S(1);
  const S ul = s_lo * gauge.scale[0], uh = s_hi * gauge.scale[0];
  const S vl = z_lo * gauge.scale[2], vh = z_hi * gauge.scale[2];
  const S g_lo = norm(ul, vl).lo, g_hi = norm(uh, vh).hi;
  const NormBracket<S> g_sz = norm(ul, vh), g_zs = norm(uh, vl);  // mixed corners
  const S ts_lo = ul / g_sz.hi, ts_hi = std::min(one, uh / g_zs.lo);
  const S tz_lo = vl / g_zs.hi, tz_hi = std::min(one, vh / g_sz.lo);
  const S a2 = gauge.scale[0] * gauge.scale[0], c2 = gauge.scale[2] * gauge.scale[2];
  const S factor = (p - one) / g_lo * (tz_hi * tz_hi * a2 + ts_hi * ts_hi * c2);
  HessianBound<S> bound;
  if (k >= S(0)) {
    bound.regular = factor * boundPow(ts_hi * tz_hi, k);
  } else if (ul == S(0) && vl == S(0)) {
    bound.regular = std::numeric_limits<S>::infinity();
  } else if (ul == S(0)) {  // ts ≥ (s/a)/g_hi
    bound.crease[0] = factor * boundPow(gauge.scale[0] / g_hi * tz_lo, k);
  } else if (vl == S(0)) {  // tz ≥ (z/c)/g_hi
    bound.crease[2] = factor * boundPow(gauge.scale[2] / g_hi * ts_lo, k);
  } else {
    bound.regular = factor * boundPow(ts_lo * tz_lo, k);
  }
  return bound;
}

/// The bound above with its 4 norms evaluated, or (`quick`, tried first) bracketed without a
/// power (HolderBracket).
template <typename S>
HessianBound<S> meridianHessianBound(const NestedNorm<S>& gauge, S s_lo, S s_hi, S z_lo, S z_hi,
                                     bool quick = false) {
  if (quick) {
    return meridianBoundFromCorners(gauge, s_lo, s_hi, z_lo, z_hi,
                                    HolderBracket<S>(gauge.p2, gauge.inv_p2));
  }
  return meridianBoundFromCorners(gauge, s_lo, s_hi, z_lo, z_hi, exactNorm(gauge.p2, gauge.inv_p2));
}

/// The Hessian-ball certificate on a surface of revolution about z, in Q's meridian plane
/// (docs/math.md → "The Hessian-ball certificate"): y = (ρ, 0, z) and the answer N = (s, 0, z)
/// on the plane y = 0. The ball B(Q', d) lies inside the solid exactly when its meridian disc,
/// the disc of radius d about (ρ', z') in the (s, z) plane with s < 0 included, lies inside the
/// section {g(|s|, |z|) ≤ 1}: a point of the ball at height z'' is at most ρ' + w from the axis
/// (w the radius of the ball's slice there), and the section, convex and symmetric in s,
/// holds the whole segment from −(ρ' + w) to ρ' + w once it holds the disc's two points of that
/// height. The disc is certified as the ball is in 3D, with meridianHessianBound: the segments
/// from N are straight in (s, z), so a crease at the axis (the tip, ε2 > 1) is integrated
/// along them like one at a coordinate plane, where the 3D bound has none (its box reaches the
/// z axis) — the shallow points below a tip are certified here.
template <typename S>
bool hessianDiscCertified(const NestedNorm<S>& gauge, const Vector3<S>& y,
                          const Vector3<S>& nearest, const Vector3<S>& gradient_at_n, S distance,
                          S error) {
  const S reach = distance + error;
  const S s_lo = std::max(S(0), y[0] - reach), z_lo = std::max(S(0), y[2] - reach);
  const Vector3<S> k = Vector3<S>::Constant(gauge.p2 - S(2));  // crease[1] stays 0 here
  auto holds = [&](const HessianBound<S>& bound) {
    return hessianBoundCertifies(bound, k, nearest, gradient_at_n, distance);
  };
  return holds(meridianHessianBound(gauge, s_lo, y[0] + reach, z_lo, y[2] + reach, true)) ||
         holds(meridianHessianBound(gauge, s_lo, y[0] + reach, z_lo, y[2] + reach));
}

/// The same certificate for the part of the ball within `radius` of N only (docs/math.md →
/// "The direction cover"). A point P of B(Q', d) with ‖P − N‖ ≤ r is N − a·n + b (b ⊥ n,
/// ‖b‖ ≤ r) with a ≥ ‖P − N‖²/(2d); on the sphere a = ‖P − N‖²/(2d) ≤ r²/(2d). Mirrored into
/// the octant (G takes the same value there) P stays in the ball, no farther from N, and a
/// does not grow (n ≥ 0), so it lies in the slab 0 ≤ a ≤ r²/(2d), ‖b‖ ≤ r of the octant, as
/// does its segment from N. Over that slab's box the Taylor bound holds when M·d ≤ ‖∇G(N)‖
/// (for a ≥ ‖P − N‖²/(2d), ½·M·‖P − N‖² ≤ M·d·a ≤ ‖∇G(N)‖·a), so G ≤ 1 on the sphere's points
/// within r of N; the direction cover's cap (DirectionCover::cap) places the rest of
/// the sphere inside, and G, convex, is at most 1 over the whole ball.
template <typename S>
bool hessianCapCertified(const NestedNorm<S>& gauge, const Vector3<S>& nearest,
                         const Vector3<S>& normal, const Vector3<S>& gradient_at_n, S distance,
                         S radius) {
  const S depth = radius * radius / (S(2) * distance);
  Vector3<S> lo, hi;
  for (int i = 0; i < 3; ++i) {
    // ‖b‖ ≤ r with b ⊥ n: |b_i| ≤ r·√(1 − n_i²).
    const S lateral = radius * std::sqrt(std::max(S(0), S(1) - normal[i] * normal[i]));
    lo[i] = std::max(S(0), nearest[i] - depth * normal[i] - lateral);
    hi[i] = nearest[i] + lateral;
  }
  return hessianBoxCertifies(gauge, lo, hi, nearest, gradient_at_n, distance);
}

/// The direction cover's certificate (docs/math.md → "The direction cover") for a converged
/// inside answer N (normal n, gauge gradient there) at distance d from y, all in the first
/// octant: the ball B(Q', d) with Q' = N − d·n lies inside the shape if every direction with
/// F(n) = h(n) − n·y < d + ‖y − Q'‖ lies within θ of n (DirectionCover::cap, given up beyond
/// `cap_limit`, or a fraction of it by DirectionCover::capWithin where the stored cap's slab
/// fails) and the Hessian bound holds over the slab of r = 2·d·θ at N
/// (hessianCapCertified; 2.01 covers the chord's rounding). Needs Q' in the first octant (the
/// mirror argument); a rounding outside it is not certified. `split_budget`: the support points
/// the query may still spend on split cells (DirectionCover::kSplitSupportPoints per query),
/// decremented.
template <typename S>
bool directionCoverCertified(const DirectionCover<S>& cover, const NestedNorm<S>& gauge,
                             const Vector3<S>& y, const Vector3<S>& nearest,
                             const Vector3<S>& normal, const Vector3<S>& gradient_at_n, S distance,
                             S cap_limit, int* split_budget) {
  const Vector3<S> centre = nearest - distance * normal;
  if (!(centre.minCoeff() >= S(0))) return false;
  const S need = distance + (centre - y).norm();
  const typename DirectionCover<S>::Cap cap = cover.cap(y, normal, need, cap_limit);
  const S theta = cap.radius;
  if (!(theta <= cap_limit)) return false;
  auto slab = [&](S radius) {
    return hessianCapCertified(gauge, nearest, normal, gradient_at_n, distance,
                               S(2.01) * distance * radius);
  };
  if (slab(theta)) return true;
  // The stored cells' cap is too wide for the slab: a half, a quarter or an eighth of it may do,
  // if the cells that reach beyond it pass once split further (DirectionCover::capWithin). The
  // slab of the eighth first: the slabs are nested, so where it fails none of them holds (an
  // answer beside a crease or a sharp rim), and the check ends after two bounds, not four.
  const S smallest = S(0.125) * theta;
  if (!slab(smallest)) return false;
  for (const S target : {S(0.5) * theta, S(0.25) * theta}) {
    if (slab(target)) return cover.capWithin(cap, y, normal, need, target, split_budget);
  }
  return cover.capWithin(cap, y, normal, need, smallest, split_budget);
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SOLVERS_BALL_CERTIFICATE_H
