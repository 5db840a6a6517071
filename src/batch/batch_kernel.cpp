// The batched Exact solver on SIMD lanes (see batch_kernel.h for what it solves and what it
// hands back to the scalar solver). Highway compiles the part between HWY_BEFORE_NAMESPACE and
// HWY_AFTER_NAMESPACE once per instruction set (foreach_target.h re-includes this file); the
// HWY_ONCE part at the end picks one at run time.
//
// Every formula mirrors solvers/exact_solver.cpp and shape/nested_norm.h, lane by lane; masks
// stand in for its branches; the rules both share (tolerance floor, budgets, halvings,
// thresholds) are read from solvers/exact_rules.h. Like the scalar solver it solves the
// bordered Newton system in the tangent plane (ExactSolver::tangentSteps). Differences: the dual
// iteration keeps the dual's normal for its answer instead of re-deriving the primal's at the
// end where it has not converged (they agree to rounding; the scalar solver keeps it where it
// has), and a refused full step is halved without
// the scalar solver's second-order correction (exact_rules::kStepTrials; the lanes that do not
// converge go to the scalar solver).

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch/batch_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
// (foreach_target.h first: it re-includes this file once per target.)
#include <hwy/contrib/math/math-inl.h>
#include <hwy/highway.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "batch/batch_kernel.h"
#include "batch/simd_targets_for_test.h"
#include "fcl_superellipsoid/batch_distance.h"
#include "solvers/ball_certificate.h"
#include "solvers/exact_rules.h"

HWY_BEFORE_NAMESPACE();
namespace fcl_superellipsoid {
namespace detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace rules = exact_rules;

/// A nested norm's numbers (nested_norm.h), one copy broadcast to every lane.
template <class D>
struct NormLanes {
  using V = hn::Vec<D>;
  V s0, s1, s2, p1, p2, inv_p1, inv_p2, p1_m1, p2_m1;
  NormLanes(D d, const NestedNorm<hn::TFromD<D>>& n)
      : s0(hn::Set(d, n.scale[0])),
        s1(hn::Set(d, n.scale[1])),
        s2(hn::Set(d, n.scale[2])),
        p1(hn::Set(d, n.p1)),
        p2(hn::Set(d, n.p2)),
        inv_p1(hn::Set(d, n.inv_p1)),
        inv_p2(hn::Set(d, n.inv_p2)),
        p1_m1(hn::Set(d, n.p1 - 1)),
        p2_m1(hn::Set(d, n.p2 - 1)) {}
};

template <class D>
struct Vec3 {
  hn::Vec<D> x, y, z;
};

template <class D>
HWY_INLINE hn::Vec<D> Dot(const Vec3<D>& a, const Vec3<D>& b) {
  return hn::MulAdd(a.x, b.x, hn::MulAdd(a.y, b.y, hn::Mul(a.z, b.z)));
}
template <class D>
HWY_INLINE Vec3<D> Plus(const Vec3<D>& a, const Vec3<D>& b) {
  return {hn::Add(a.x, b.x), hn::Add(a.y, b.y), hn::Add(a.z, b.z)};
}
template <class D>
HWY_INLINE Vec3<D> Minus(const Vec3<D>& a, const Vec3<D>& b) {
  return {hn::Sub(a.x, b.x), hn::Sub(a.y, b.y), hn::Sub(a.z, b.z)};
}
template <class D>
HWY_INLINE Vec3<D> Times(hn::Vec<D> s, const Vec3<D>& a) {
  return {hn::Mul(s, a.x), hn::Mul(s, a.y), hn::Mul(s, a.z)};
}
/// a + s·b
template <class D>
HWY_INLINE Vec3<D> PlusTimes(const Vec3<D>& a, hn::Vec<D> s, const Vec3<D>& b) {
  return {hn::MulAdd(s, b.x, a.x), hn::MulAdd(s, b.y, a.y), hn::MulAdd(s, b.z, a.z)};
}
template <class D>
HWY_INLINE Vec3<D> Cross(const Vec3<D>& a, const Vec3<D>& b) {
  return {hn::NegMulAdd(a.z, b.y, hn::Mul(a.y, b.z)), hn::NegMulAdd(a.x, b.z, hn::Mul(a.z, b.x)),
          hn::NegMulAdd(a.y, b.x, hn::Mul(a.x, b.y))};
}
template <class D>
HWY_INLINE Vec3<D> Select(hn::Mask<D> m, const Vec3<D>& a, const Vec3<D>& b) {
  return {hn::IfThenElse(m, a.x, b.x), hn::IfThenElse(m, a.y, b.y), hn::IfThenElse(m, a.z, b.z)};
}
template <class D>
HWY_INLINE hn::Mask<D> AllFinite(const Vec3<D>& a) {
  return hn::And(hn::IsFinite(a.x), hn::And(hn::IsFinite(a.y), hn::IsFinite(a.z)));
}

/// x^p for x ≥ 0 and p > 0, as exp(p·log x); 0^p = 0.
template <class D>
HWY_INLINE hn::Vec<D> Pow(D d, hn::Vec<D> x, hn::Vec<D> p) {
  const auto positive = hn::Gt(x, hn::Zero(d));
  const hn::Vec<D> safe = hn::IfThenElse(positive, x, hn::Set(d, 1));
  return hn::IfThenElseZero(positive, hn::Exp(d, hn::Mul(p, hn::Log(d, safe))));
}

/// ‖(a, b)‖_p and its gradient's powers (a/N)^(p−1), (b/N)^(p−1), lane-wise (NestedNorm::levels
/// takes them from exp2 and log2 in the same way);
/// also log(1 + q), q = (lo/m)^p, from which the nested norm's second level takes its ratio.
template <class D>
struct PNorm2Lanes {
  hn::Vec<D> norm, pow_a, pow_b, log_1pq;
};

/// log_ratio, if given, is log(min(a, b)/max(a, b)) (any value where min(a, b) = 0).
template <class D>
HWY_INLINE PNorm2Lanes<D> PNorm2WithPowers(D d, hn::Vec<D> a, hn::Vec<D> b, hn::Vec<D> p,
                                           hn::Vec<D> inv_p, hn::Vec<D> p_minus_1,
                                           const hn::Vec<D>* log_ratio = nullptr) {
  using T = hn::TFromD<D>;
  const hn::Vec<D> zero = hn::Zero(d), one = hn::Set(d, 1);
  const hn::Vec<D> m = hn::Max(a, b), lo = hn::Min(a, b);
  const auto m_positive = hn::Gt(m, zero), lo_positive = hn::Gt(lo, zero);
  const hn::Vec<D> ratio = hn::Div(lo, hn::IfThenElse(m_positive, m, one));  // lo/m ∈ [0, 1]
  const hn::Vec<D> log_t =
      log_ratio != nullptr ? *log_ratio : hn::Log(d, hn::IfThenElse(lo_positive, ratio, one));
  const hn::Vec<D> q = hn::IfThenElseZero(lo_positive, hn::Exp(d, hn::Mul(p, log_t)));
  const hn::Vec<D> one_plus_q = hn::Add(one, q);
  // w = (1 + q)^(1/p), N = m·w. log(1 + q) rounds 1 + q first; its absolute error of an ulp
  // moves N by a relative ulp/p, so log1p is not needed.
  const hn::Vec<D> log_1pq = hn::Log(d, one_plus_q);
  const hn::Vec<D> w = hn::Exp(d, hn::Mul(inv_p, log_1pq));
  const hn::Vec<D> n = hn::Mul(m, w);
  // (m/N)^(p−1) = N/(m·(1 + q)) = w/(1 + q);  (lo/N)^(p−1) = (lo/m)^(p−1)·(m/N)^(p−1), with
  // (lo/m)^(p−1) = q/ratio, or a power of its own where q is subnormal (nested_norm.h).
  const hn::Vec<D> pow_m = hn::Div(w, one_plus_q);
  hn::Vec<D> ratio_pow = hn::Div(q, hn::IfThenElse(lo_positive, ratio, one));
  const auto subnormal = hn::And(lo_positive, hn::Lt(q, hn::Set(d, std::numeric_limits<T>::min())));
  if (!hn::AllFalse(d, subnormal)) {
    ratio_pow = hn::IfThenElse(subnormal, Pow(d, ratio, p_minus_1), ratio_pow);
  }
  const hn::Vec<D> pow_lo = hn::IfThenElseZero(lo_positive, hn::Mul(ratio_pow, pow_m));
  const auto a_larger = hn::Ge(a, b);
  return {n, hn::IfThenElseZero(m_positive, hn::IfThenElse(a_larger, pow_m, pow_lo)),
          hn::IfThenElseZero(m_positive, hn::IfThenElse(a_larger, pow_lo, pow_m)), log_1pq};
}

/// Both levels of the nested norm at u = (scaled) w ≥ 0. The second level's ratio is
/// min(r, u2)/max(r, u2) with r = m1·(1 + q1)^(1/p1) the first level's norm; its logarithm is
/// taken as −|log m1 + log(1 + q1)/p1 − log u2|, from logarithms that do not wait for r. Each
/// level is a chain log → exp → log → exp, and a vector's Newton iteration waits on its
/// evaluations (nothing else is in flight), so this shortens the evaluation's critical path
/// from four such steps per level and a division between the levels to three in all: log m1 and
/// log u2 are computed beside the first level, and w1 = exp(log(1 + q1)/p1) beside the second.
/// The log's absolute error, a few ulps of |log m1| + |log u2|, moves q2 by p2 times as much
/// relatively, and N by at most that error (N's relative change is (1/p2)·q2/(1 + q2) times
/// q2's): within a few ulps for the kernel's queries (the far and near-centre ones go to the
/// scalar solver).
template <class D>
struct NestedLevels {
  PNorm2Lanes<D> level1, level2;
};

template <class D>
HWY_INLINE NestedLevels<D> EvaluateLevels(D d, const NormLanes<D>& c, hn::Vec<D> u0, hn::Vec<D> u1,
                                          hn::Vec<D> u2) {
  const hn::Vec<D> zero = hn::Zero(d), one = hn::Set(d, 1);
  auto safe_log = [&](hn::Vec<D> x) { return hn::Log(d, hn::IfThenElse(hn::Gt(x, zero), x, one)); };
  const hn::Vec<D> log_m1 = safe_log(hn::Max(u0, u1)), log_u2 = safe_log(u2);
  NestedLevels<D> out;
  out.level1 = PNorm2WithPowers(d, u0, u1, c.p1, c.inv_p1, c.p1_m1);
  const hn::Vec<D> log_r = hn::MulAdd(c.inv_p1, out.level1.log_1pq, log_m1);
  const hn::Vec<D> log_ratio2 = hn::Neg(hn::Abs(hn::Sub(log_r, log_u2)));
  out.level2 = PNorm2WithPowers(d, out.level1.norm, u2, c.p2, c.inv_p2, c.p2_m1, &log_ratio2);
  return out;
}

/// A symmetric 3×3 matrix by its upper triangle.
template <class D>
struct Sym3 {
  hn::Vec<D> xx, xy, xz, yy, yz, zz;
  Vec3<D> times(const Vec3<D>& v) const {
    return {hn::MulAdd(xx, v.x, hn::MulAdd(xy, v.y, hn::Mul(xz, v.z))),
            hn::MulAdd(xy, v.x, hn::MulAdd(yy, v.y, hn::Mul(yz, v.z))),
            hn::MulAdd(xz, v.x, hn::MulAdd(yz, v.y, hn::Mul(zz, v.z)))};
  }
};

template <class D>
HWY_INLINE Sym3<D> Select(hn::Mask<D> m, const Sym3<D>& a, const Sym3<D>& b) {
  return {hn::IfThenElse(m, a.xx, b.xx), hn::IfThenElse(m, a.xy, b.xy),
          hn::IfThenElse(m, a.xz, b.xz), hn::IfThenElse(m, a.yy, b.yy),
          hn::IfThenElse(m, a.yz, b.yz), hn::IfThenElse(m, a.zz, b.zz)};
}

/// NestedNormEval, lane-wise.
template <class D>
struct NormEval {
  hn::Vec<D> value;
  Vec3<D> gradient;
  Sym3<D> hessian;
};

template <class D>
HWY_INLINE NormEval<D> Select(hn::Mask<D> m, const NormEval<D>& a, const NormEval<D>& b) {
  return {hn::IfThenElse(m, a.value, b.value), Select(m, a.gradient, b.gradient),
          Select(m, a.hessian, b.hessian)};
}

/// NestedNorm::evaluate with the Hessian, lane-wise (the same formulas; see nested_norm.h).
template <class D>
HWY_INLINE NormEval<D> Evaluate(D d, const NormLanes<D>& c, const Vec3<D>& w) {
  using T = hn::TFromD<D>;
  using V = hn::Vec<D>;
  const V zero = hn::Zero(d), one = hn::Set(d, 1);
  const V u0 = hn::Mul(w.x, c.s0), u1 = hn::Mul(w.y, c.s1), u2 = hn::Mul(w.z, c.s2);
  const NestedLevels<D> levels = EvaluateLevels(d, c, u0, u1, u2);
  const PNorm2Lanes<D>& level1 = levels.level1;
  const V r = level1.norm;
  const PNorm2Lanes<D>& level2 = levels.level2;
  NormEval<D> out;
  out.value = level2.norm;
  const auto value_positive = hn::Gt(out.value, zero), r_positive = hn::Gt(r, zero);
  const V inv_value = hn::Div(one, hn::IfThenElse(value_positive, out.value, one));
  const V inv_r = hn::IfThenElseZero(r_positive, hn::Div(one, hn::IfThenElse(r_positive, r, one)));
  const V t1 = hn::Mul(u0, inv_r), t2 = hn::Mul(u1, inv_r);
  const V tr = hn::Mul(r, inv_value), t3 = hn::Mul(u2, inv_value);
  const V r1 = level1.pow_a, r2 = level1.pow_b, g_r = level2.pow_a, g_3 = level2.pow_b;
  out.gradient = {hn::IfThenElseZero(value_positive, hn::Mul(hn::Mul(g_r, r1), c.s0)),
                  hn::IfThenElseZero(value_positive, hn::Mul(hn::Mul(g_r, r2), c.s1)),
                  hn::IfThenElseZero(value_positive, hn::Mul(g_3, c.s2))};

  // t^(p−2) = t^(p−1)/t with a floor on t (nested_norm.h).
  const V floor = hn::Set(d, std::sqrt(std::numeric_limits<T>::min()));
  auto pow_minus_2 = [&](V t, V pow_pm1) { return hn::Div(pow_pm1, hn::Max(t, floor)); };
  const V c1 = hn::Mul(c.p1_m1, inv_r);
  const V r11 = hn::Mul(hn::Mul(c1, pow_minus_2(t1, r1)), hn::Mul(t2, r2));
  const V r22 = hn::Mul(hn::Mul(c1, pow_minus_2(t2, r2)), hn::Mul(t1, r1));
  const V r12 = hn::Neg(hn::Mul(hn::Mul(c1, r1), r2));
  const V c2 = hn::Mul(c.p2_m1, inv_value);
  const V g_rr = hn::Mul(hn::Mul(c2, pow_minus_2(tr, g_r)), hn::Mul(t3, g_3));
  const V g_r3 = hn::Neg(hn::Mul(hn::Mul(c2, g_r), g_3));
  const auto both = hn::And(value_positive, r_positive);
  Sym3<D> h;
  h.xx = hn::IfThenElseZero(both, hn::MulAdd(hn::Mul(g_rr, r1), r1, hn::Mul(g_r, r11)));
  h.yy = hn::IfThenElseZero(both, hn::MulAdd(hn::Mul(g_rr, r2), r2, hn::Mul(g_r, r22)));
  h.xy = hn::IfThenElseZero(both, hn::MulAdd(hn::Mul(g_rr, r1), r2, hn::Mul(g_r, r12)));
  h.xz = hn::IfThenElseZero(both, hn::Mul(g_r3, r1));
  h.yz = hn::IfThenElseZero(both, hn::Mul(g_r3, r2));
  h.zz = hn::IfThenElseZero(value_positive,
                            hn::Mul(hn::Mul(c2, pow_minus_2(t3, g_3)), hn::Mul(tr, g_r)));
  // diag(s)·H_u·diag(s)
  out.hessian = {hn::Mul(h.xx, hn::Mul(c.s0, c.s0)), hn::Mul(h.xy, hn::Mul(c.s0, c.s1)),
                 hn::Mul(h.xz, hn::Mul(c.s0, c.s2)), hn::Mul(h.yy, hn::Mul(c.s1, c.s1)),
                 hn::Mul(h.yz, hn::Mul(c.s1, c.s2)), hn::Mul(h.zz, hn::Mul(c.s2, c.s2))};
  return out;
}

/// ExactSolver's Candidate, lane-wise.
template <class D>
struct Candidate {
  Vec3<D> point, normal, gradient;  // gradient and hessian: the primal's ∇G, ∇²G at point
  Sym3<D> hessian;
  hn::Vec<D> error;
};

template <class D>
HWY_INLINE Candidate<D> Select(hn::Mask<D> m, const Candidate<D>& a, const Candidate<D>& b) {
  return {Select(m, a.point, b.point), Select(m, a.normal, b.normal),
          Select(m, a.gradient, b.gradient), Select(m, a.hessian, b.hessian),
          hn::IfThenElse(m, a.error, b.error)};
}

/// One vector of queries: ExactSolver's state and steps, with masks for its branches.
template <class D>
class LaneSolver {
  using T = hn::TFromD<D>;
  using V = hn::Vec<D>;
  using M = hn::Mask<D>;

 public:
  LaneSolver(D d, const LaneProblem<T>& problem, const Vec3<D>& y, T sign)
      : d_(d),
        problem_(problem),
        primal_(d, problem.primal),
        dual_(d, problem.dual),
        y_(y),
        sign_(hn::Set(d, sign)),
        // exact_rules::absoluteTolerance, per lane.
        tolerance_(hn::MulAdd(
            hn::Set(d, T(rules::kRoundingFloorUlps) * std::numeric_limits<T>::epsilon()),
            hn::Add(hn::Sqrt(Dot(y, y)), hn::Set(d, problem.size)), hn::Set(d, problem.tolerance))),
        iterations_(hn::Zero(d)) {}

  V iterations() const { return iterations_; }
  /// The absolute tolerance per lane (exact_rules::absoluteTolerance).
  V tolerance() const { return tolerance_; }

  /// ExactSolver::candidateOnRay.
  Candidate<D> candidateOnRay(const Vec3<D>& ray) const {
    return candidateFrom(ray, Evaluate(d_, primal_, ray));
  }

  /// The same from the gauge's evaluation `e` at `ray`.
  Candidate<D> candidateFrom(const Vec3<D>& ray, const NormEval<D>& e) const {
    Candidate<D> c;
    const V inv_value = hn::Div(hn::Set(d_, 1), e.value);
    c.point = Times(inv_value, ray);
    c.gradient = e.gradient;
    c.hessian = {hn::Mul(e.value, e.hessian.xx), hn::Mul(e.value, e.hessian.xy),
                 hn::Mul(e.value, e.hessian.xz), hn::Mul(e.value, e.hessian.yy),
                 hn::Mul(e.value, e.hessian.yz), hn::Mul(e.value, e.hessian.zz)};
    const V length = hn::Sqrt(Dot(e.gradient, e.gradient));
    const auto positive = hn::Gt(length, hn::Zero(d_));
    const V inv_length = hn::Div(hn::Set(d_, 1), hn::IfThenElse(positive, length, hn::Set(d_, 1)));
    c.normal = Select(positive, Times(inv_length, e.gradient),
                      Vec3<D>{hn::Zero(d_), hn::Zero(d_), hn::Set(d_, 1)});
    c.error = errorAt(c.point, c.normal);
    return c;
  }

  /// ExactSolver::refine on the lanes of `lanes`: Newton in the smooth formulation, and where
  /// that stalls, in the other, from where the first stopped and then from the start; each
  /// start has at most exact_rules::kIterationsPerStart iterations of the caller's cap. Returns the
  /// candidate; `converged` gets the lanes whose error reached the tolerance.
  Candidate<D> refine(const Candidate<D>& start, M lanes, M* converged) {
    const V limit = hn::Min(hn::Add(iterations_, hn::Set(d_, T(rules::kIterationsPerStart))),
                            hn::Set(d_, T(problem_.max_iterations)));
    const bool primal_first = problem_.primal_first;
    Candidate<D> c =
        primal_first ? newtonPrimal(start, lanes, limit) : newtonDual(start, lanes, limit);
    M retry = stillGoing(lanes, c, limit);
    if (!hn::AllFalse(d_, retry)) {
      if (!primal_first) c = Select(retry, asPrimal(c), c);
      const Candidate<D> warm =
          primal_first ? newtonDual(c, retry, limit) : newtonPrimal(c, retry, limit);
      c = Select(hn::And(retry, betterThanUnconverged(warm, c)), warm, c);
      retry = stillGoing(retry, c, limit);
      if (!hn::AllFalse(d_, retry)) {
        const Candidate<D> fresh =
            primal_first ? newtonDual(start, retry, limit) : newtonPrimal(start, retry, limit);
        c = Select(hn::And(retry, betterThanUnconverged(fresh, c)), fresh, c);
      }
    }
    *converged = hn::And(lanes, hn::Le(c.error, tolerance_));
    return c;
  }

  /// ExactSolver::errorAt: paper Eq. 7 with d = ±‖Q − N‖; infinite where not finite.
  V errorAt(const Vec3<D>& point, const Vec3<D>& normal) const {
    const Vec3<D> to_query = Minus(y_, point);
    const V distance = hn::Mul(sign_, hn::Sqrt(Dot(to_query, to_query)));
    const Vec3<D> residual = Minus(PlusTimes(point, distance, normal), y_);
    const V e = hn::Sqrt(Dot(residual, residual));
    return hn::IfThenElse(hn::IsFinite(e), e, hn::Set(d_, std::numeric_limits<T>::infinity()));
  }

 private:
  M stillGoing(M lanes, const Candidate<D>& c, V limit) const {
    return hn::And(lanes, hn::And(hn::Gt(c.error, tolerance_), hn::Lt(iterations_, limit)));
  }

  /// ExactSolver::isBetter(a, b) where b has not converged: a has, or its error is smaller.
  M betterThanUnconverged(const Candidate<D>& a, const Candidate<D>& b) const {
    return hn::Or(hn::Le(a.error, tolerance_), hn::Lt(a.error, b.error));
  }

  /// The end of ExactSolver::newtonDual: the primal's view of the dual's point (its gradient
  /// and Hessian, for primal iterations that follow), keeping the dual's error where it is
  /// the smaller.
  Candidate<D> asPrimal(const Candidate<D>& c) const {
    Candidate<D> out = candidateOnRay(c.point);
    const M keep_dual = hn::Gt(out.error, c.error);
    out.point = Select(keep_dual, c.point, out.point);
    out.normal = Select(keep_dual, c.normal, out.normal);
    out.error = hn::IfThenElse(keep_dual, c.error, out.error);
    return out;
  }

  /// ExactSolver::stayInOctant.
  Vec3<D> stayInOctant(const Vec3<D>& from, const Vec3<D>& to) const {
    const V zero = hn::Zero(d_), tenth = hn::Set(d_, T(rules::kOctantShrink));
    // !(to ≥ 0) also catches NaN, as in the scalar code.
    return {hn::IfThenElse(hn::Ge(to.x, zero), to.x, hn::Mul(tenth, from.x)),
            hn::IfThenElse(hn::Ge(to.y, zero), to.y, hn::Mul(tenth, from.y)),
            hn::IfThenElse(hn::Ge(to.z, zero), to.z, hn::Mul(tenth, from.z))};
  }

  /// The Newton steps of the bordered system [A, n; nᵀ, 0]·[δ; λ] = [r; 0] (n a unit normal),
  /// solved in the tangent plane of n, with exact_rules::convexifiedTangentBlock's rule (the same
  /// formulas, lane by lane): where a tangent eigenvalue is below kConvexifyBelow·scale (and
  /// finite), `shifted` is the step with that eigenvalue replaced by kConvexifyTo·scale along its
  /// eigenvector, else the plain Newton step; on the lanes of `full_first` (the smallest
  /// eigenvalue replaced was positive) the unmodified step `full` is tried first.
  struct TangentSteps {
    Vec3<D> shifted, full;
    M full_first;
  };
  TangentSteps tangentSteps(const Sym3<D>& a, const Vec3<D>& n, const Vec3<D>& r, V scale) const {
    const V zero = hn::Zero(d_), one = hn::Set(d_, 1), half = hn::Set(d_, T(0.5));
    // t1 = n × helper, helper = x̂ where |n_x| < 0.6, else ŷ; t2 = n × t1.
    const auto use_x = hn::Lt(hn::Abs(n.x), hn::Set(d_, T(rules::kTangentHelperSwitch)));
    Vec3<D> t1 = Select(use_x, Vec3<D>{zero, n.z, hn::Neg(n.y)}, Vec3<D>{hn::Neg(n.z), zero, n.x});
    t1 = Times(hn::Div(one, hn::Sqrt(Dot(t1, t1))), t1);
    const Vec3<D> t2 = Cross(n, t1);
    const V b11 = Dot(t1, a.times(t1)), b22 = Dot(t2, a.times(t2));
    const V b12 = Dot(t1, a.times(t2));
    const V below = hn::Mul(hn::Set(d_, T(rules::kConvexifyBelow)), scale);
    const V c1 = Dot(t1, r), c2 = Dot(t2, r);
    // The 2×2 solve of a tangent block.
    auto solve = [&](V s11, V s12, V s22) {
      const V inv_det = hn::Div(one, hn::NegMulAdd(s12, s12, hn::Mul(s11, s22)));
      const V alpha = hn::Mul(hn::NegMulAdd(s12, c2, hn::Mul(s22, c1)), inv_det);
      const V beta = hn::Mul(hn::NegMulAdd(s12, c1, hn::Mul(s11, c2)), inv_det);
      return PlusTimes(Times(alpha, t1), beta, t2);
    };
    // Where B − below·I is positive definite on every lane (its diagonal and determinant say
    // so, as in exact_rules::convexifiedTangentBlock), no eigenvalue is replaced: the plain step.
    const V d11 = hn::Sub(b11, below), d22 = hn::Sub(b22, below), d_det = hn::Mul(d11, d22);
    const M clear = hn::And(hn::And(hn::Gt(d11, zero), hn::Gt(d22, zero)),
                            hn::And(hn::Gt(d_det, hn::Mul(b12, b12)), hn::IsFinite(d_det)));
    if (hn::AllTrue(d_, clear)) {
      return {solve(b11, b12, b22), Vec3<D>{zero, zero, zero}, hn::MaskFromVec(zero)};
    }
    const V mean = hn::Mul(half, hn::Add(b11, b22)), half_diff = hn::Mul(half, hn::Sub(b11, b22));
    const V half_gap = Hypot(half_diff, b12);
    // The eigenvalue of larger magnitude without cancellation, the other as det/that one.
    const V det = hn::MulAdd(b11, b22, hn::Neg(hn::Mul(b12, b12)));
    const M mean_positive = hn::Ge(mean, zero);
    const V big = hn::IfThenElse(mean_positive, hn::Add(mean, half_gap), hn::Sub(mean, half_gap));
    const M big_nonzero = hn::Ne(big, zero);
    const V small =
        hn::IfThenElseZero(big_nonzero, hn::Div(det, hn::IfThenElse(big_nonzero, big, one)));
    const V lowest = hn::IfThenElse(mean_positive, small, big);
    const V highest = hn::IfThenElse(mean_positive, big, small);
    const V wanted = hn::Mul(hn::Set(d_, T(rules::kConvexifyTo)), scale);
    const M shift_it = hn::And(hn::Lt(lowest, below), hn::IsFinite(lowest));
    // The lowest eigenvalue's unit eigenvector (c, s), without cancellation.
    const M diff_negative = hn::Lt(half_diff, zero);
    V c = hn::IfThenElse(diff_negative, hn::Sub(half_diff, half_gap), b12);
    V s = hn::IfThenElse(diff_negative, b12, hn::Neg(hn::Add(half_diff, half_gap)));
    const V length = Hypot(c, s);
    const M has_length = hn::Gt(length, zero);
    const V inv_length = hn::Div(one, hn::IfThenElse(has_length, length, one));
    c = hn::IfThenElse(has_length, hn::Mul(c, inv_length), one);
    s = hn::IfThenElseZero(has_length, hn::Mul(s, inv_length));
    const V high = hn::IfThenElse(hn::Lt(highest, below), wanted, highest);
    // M = wanted·(c, s)(c, s)ᵀ + high·(−s, c)(−s, c)ᵀ on the shifted lanes, B elsewhere.
    const V cc = hn::Mul(c, c), ss = hn::Mul(s, s);
    const V m11 = hn::IfThenElse(shift_it, hn::MulAdd(wanted, cc, hn::Mul(high, ss)), b11);
    const V m22 = hn::IfThenElse(shift_it, hn::MulAdd(wanted, ss, hn::Mul(high, cc)), b22);
    const V m12 = hn::IfThenElse(shift_it, hn::Mul(hn::Sub(wanted, high), hn::Mul(c, s)), b12);
    const M full_first = hn::And(shift_it, hn::Gt(lowest, zero));
    return {solve(m11, m12, m22),
            hn::AllFalse(d_, full_first) ? Vec3<D>{zero, zero, zero} : solve(b11, b12, b22),
            full_first};
  }

  /// The step halving of both formulations, with the unshifted step first where tangentSteps
  /// says so (ExactSolver::newtonPrimal / newtonDual): returns the lanes that improved.
  template <typename Attempt>
  M stepFrom(M active, const TangentSteps& steps, const Attempt& attempt) const {
    M improved = hn::MaskFromVec(hn::Zero(d_));
    const M full_lanes = hn::And(active, steps.full_first);
    if (!hn::AllFalse(d_, full_lanes)) improved = halveUntilBetter(full_lanes, steps.full, attempt);
    return hn::Or(improved, halveUntilBetter(hn::AndNot(improved, active), steps.shifted, attempt));
  }

  /// √(a² + b²) without overflow (the tangent block can be huge near a crease).
  V Hypot(V a, V b) const {
    const V m = hn::Max(hn::Abs(a), hn::Abs(b));
    const auto positive = hn::Gt(m, hn::Zero(d_));
    const V inv = hn::Div(hn::Set(d_, 1), hn::IfThenElse(positive, m, hn::Set(d_, 1)));
    const V sa = hn::Mul(a, inv), sb = hn::Mul(b, inv);
    return hn::Mul(m, hn::Sqrt(hn::MulAdd(sa, sa, hn::Mul(sb, sb))));
  }

  /// The step halving of both formulations (ExactSolver::tryStep and the loop in newtonDual):
  /// on the lanes of `lanes` whose step is finite, attempt(step, trying) tries step, step/2, …
  /// (exact_rules::kStepTrials in all) until it improves, applying the trial on the lanes it
  /// accepts and returning them.
  /// Returns the lanes that improved.
  template <typename Attempt>
  M halveUntilBetter(M lanes, Vec3<D> step, const Attempt& attempt) const {
    M trying = hn::And(lanes, AllFinite(step));
    M improved = hn::MaskFromVec(hn::Zero(d_));
    for (int trial_step = 0; trial_step < rules::kStepTrials && !hn::AllFalse(d_, trying);
         ++trial_step) {
      const M accepted = attempt(step, trying);
      improved = hn::Or(improved, accepted);
      trying = hn::AndNot(accepted, trying);
      step = Times(hn::Set(d_, T(0.5)), step);
    }
    return improved;
  }

  /// ExactSolver::newtonPrimal with its step halving (tryStep).
  Candidate<D> newtonPrimal(Candidate<D> c, M lanes, V limit) {
    const V one = hn::Set(d_, 1);
    M active = stillGoing(lanes, c, limit);
    while (!hn::AllFalse(d_, active)) {
      iterations_ = hn::Add(iterations_, hn::IfThenElseZero(active, one));
      const Vec3<D> to_query = Minus(y_, c.point);
      const V mu = hn::Div(Dot(c.gradient, to_query), Dot(c.gradient, c.gradient));
      const Vec3<D> residual = Minus(to_query, Times(mu, c.gradient));
      Sym3<D> a = {hn::MulAdd(mu, c.hessian.xx, one), hn::Mul(mu, c.hessian.xy),
                   hn::Mul(mu, c.hessian.xz),         hn::MulAdd(mu, c.hessian.yy, one),
                   hn::Mul(mu, c.hessian.yz),         hn::MulAdd(mu, c.hessian.zz, one)};
      const TangentSteps steps = tangentSteps(a, c.normal, residual, one);
      // The trial point is re-projected radially onto the surface (candidateOnRay).
      const M improved = stepFrom(active, steps, [&](const Vec3<D>& s, M trying) {
        const Vec3<D> p = stayInOctant(c.point, Plus(c.point, s));
        const M valid = hn::And(AllFinite(p), hn::Gt(Dot(p, p), hn::Zero(d_)));
        const Candidate<D> trial = candidateOnRay(p);
        const M accept = hn::And(hn::And(trying, valid), hn::Lt(trial.error, c.error));
        c = Select(accept, trial, c);
        return accept;
      });
      active = stillGoing(improved, c, limit);
    }
    return c;
  }

  /// ExactSolver::dualAtCandidate: inside, h's evaluation at the candidate's normal from its
  /// primal evaluation (∇h(n) = N; on the tangent plane ∇²h(n) = W⁻¹, W = Tᵀ∇²G·T/‖∇G‖), where
  /// W is positive definite on every lane of `lanes`; otherwise (and outside) h evaluated.
  NormEval<D> dualAtCandidate(const Candidate<D>& c, M lanes) const {
    const Vec3<D>& n = c.normal;
    if (hn::GetLane(sign_) > T(0)) return Evaluate(d_, dual_, n);
    const V zero = hn::Zero(d_), one = hn::Set(d_, 1);
    const auto use_x = hn::Lt(hn::Abs(n.x), hn::Set(d_, T(rules::kTangentHelperSwitch)));
    Vec3<D> t1 = Select(use_x, Vec3<D>{zero, n.z, hn::Neg(n.y)}, Vec3<D>{hn::Neg(n.z), zero, n.x});
    t1 = Times(hn::Div(one, hn::Sqrt(Dot(t1, t1))), t1);
    const Vec3<D> t2 = Cross(n, t1);
    const V inv_g = hn::Div(one, hn::Sqrt(Dot(c.gradient, c.gradient)));
    const V w11 = hn::Mul(Dot(t1, c.hessian.times(t1)), inv_g);
    const V w22 = hn::Mul(Dot(t2, c.hessian.times(t2)), inv_g);
    const V w12 = hn::Mul(Dot(t1, c.hessian.times(t2)), inv_g);
    const V det = hn::MulAdd(w11, w22, hn::Neg(hn::Mul(w12, w12)));
    const M usable = hn::And(hn::And(hn::Gt(w11, zero), hn::Gt(det, zero)),
                             hn::IsFinite(hn::Add(det, hn::Add(w11, hn::Add(w22, w12)))));
    if (!hn::AllTrue(d_, hn::Or(usable, hn::Not(lanes)))) return Evaluate(d_, dual_, n);
    // W⁻¹ = [w22, −w12; −w12, w11]/det, as T·W⁻¹·Tᵀ.
    const V inv_det = hn::Div(one, det);
    const V i11 = hn::Mul(w22, inv_det), i22 = hn::Mul(w11, inv_det);
    const V i12 = hn::Neg(hn::Mul(w12, inv_det));
    auto entry = [&](V a1, V a2, V b1, V b2) {  // (T·W⁻¹·Tᵀ) at (a, b): a = (t1_a, t2_a)
      return hn::MulAdd(
          i11, hn::Mul(a1, b1),
          hn::MulAdd(i22, hn::Mul(a2, b2), hn::Mul(i12, hn::MulAdd(a1, b2, hn::Mul(a2, b1)))));
    };
    NormEval<D> e;
    e.value = Dot(n, c.point);
    e.gradient = c.point;
    e.hessian = {entry(t1.x, t2.x, t1.x, t2.x), entry(t1.x, t2.x, t1.y, t2.y),
                 entry(t1.x, t2.x, t1.z, t2.z), entry(t1.y, t2.y, t1.y, t2.y),
                 entry(t1.y, t2.y, t1.z, t2.z), entry(t1.z, t2.z, t1.z, t2.z)};
    return e;
  }

  /// ExactSolver::newtonDual: the iterate is the unit normal n, its surface point ∇h(n).
  Candidate<D> newtonDual(Candidate<D> c, M lanes, V limit) {
    const V one = hn::Set(d_, 1);
    Vec3<D> n = c.normal;
    NormEval<D> e = dualAtCandidate(c, lanes);
    M active = stillGoing(lanes, c, limit);
    while (!hn::AllFalse(d_, active)) {
      iterations_ = hn::Add(iterations_, hn::IfThenElseZero(active, one));
      const Vec3<D>& point = e.gradient;
      const V distance = Dot(n, Minus(y_, point));
      const Vec3<D> residual = Minus(Minus(y_, point), Times(distance, n));
      const Sym3<D> a = {
          hn::Add(e.hessian.xx, distance), e.hessian.xy, e.hessian.xz,
          hn::Add(e.hessian.yy, distance), e.hessian.yz, hn::Add(e.hessian.zz, distance)};
      const TangentSteps steps = tangentSteps(a, n, residual, hn::Abs(distance));
      // The trial normal is re-normalised; its surface point is ∇h of it.
      const M improved = stepFrom(active, steps, [&](const Vec3<D>& s, M trying) {
        Vec3<D> trial_n = stayInOctant(n, Plus(n, s));
        trial_n = Times(hn::Div(one, hn::Sqrt(Dot(trial_n, trial_n))), trial_n);
        const NormEval<D> trial = Evaluate(d_, dual_, trial_n);
        const V error = errorAt(trial.gradient, trial_n);
        const M accept = hn::And(trying, hn::Lt(error, c.error));
        c.point = Select(accept, trial.gradient, c.point);
        c.normal = Select(accept, trial_n, c.normal);
        c.error = hn::IfThenElse(accept, error, c.error);
        n = Select(accept, trial_n, n);
        e = Select(accept, trial, e);
        return accept;
      });
      active = stillGoing(improved, c, limit);
    }
    return c;
  }

  D d_;
  const LaneProblem<T>& problem_;
  NormLanes<D> primal_, dual_;
  Vec3<D> y_;
  V sign_, tolerance_;
  V iterations_;  // all starts share one count, as in ExactSolver
};

template <class D>
Vec3<D> LoadVec3(D d, const hn::TFromD<D>* const* arrays, std::size_t i) {
  return {hn::LoadU(d, arrays[0] + i), hn::LoadU(d, arrays[1] + i), hn::LoadU(d, arrays[2] + i)};
}

/// The radial start of the lanes at i (candidateOnRay(y)) from the classifying pass's
/// evaluation, and G(Q).
template <class D>
Candidate<D> RadialStart(D d, const LaneSolver<D>& solver, const Vec3<D>& y,
                         const LaneArrays<hn::TFromD<D>>& lanes, std::size_t i, hn::Vec<D>* gauge) {
  hn::Vec<D> v[LaneArrays<hn::TFromD<D>>::kRadialArrays];
  for (int k = 0; k < LaneArrays<hn::TFromD<D>>::kRadialArrays; ++k) {
    v[k] = hn::LoadU(d, lanes.radial[k] + i);
  }
  *gauge = v[0];
  return solver.candidateFrom(y, {v[0], {v[1], v[2], v[3]}, {v[4], v[5], v[6], v[7], v[8], v[9]}});
}

template <class D>
void StoreAnswer(D d, const Candidate<D>& c, hn::Mask<D> solved, hn::Mask<D> inside,
                 const LaneArrays<hn::TFromD<D>>& lanes, std::size_t i) {
  hn::StoreU(c.point.x, d, lanes.point[0] + i);
  hn::StoreU(c.point.y, d, lanes.point[1] + i);
  hn::StoreU(c.point.z, d, lanes.point[2] + i);
  hn::StoreU(c.normal.x, d, lanes.normal[0] + i);
  hn::StoreU(c.normal.y, d, lanes.normal[1] + i);
  hn::StoreU(c.normal.z, d, lanes.normal[2] + i);
  hn::StoreU(c.error, d, lanes.error + i);
  // Masks have no portable per-lane read: go through a vector of status codes.
  using T = hn::TFromD<D>;
  const hn::Vec<D> code = hn::IfThenElse(
      inside, hn::Set(d, T(kLaneInside)),
      hn::IfThenElse(solved, hn::Set(d, T(kLaneSolved)), hn::Set(d, T(kLaneScalar))));
  HWY_ALIGN T codes[kMaxLanes];
  static_assert(hn::MaxLanes(D()) <= kMaxLanes, "kMaxLanes is too small for this target");
  hn::Store(code, d, codes);
  for (std::size_t k = 0; k < hn::Lanes(d); ++k) lanes.status[i + k] = std::int32_t(codes[k]);
}

/// The outside pass on one vector of lanes at i.
template <class D>
void SolveOutsideVector(D d, const LaneProblem<hn::TFromD<D>>& problem,
                        const LaneArrays<hn::TFromD<D>>& lanes, std::size_t i) {
  using T = hn::TFromD<D>;
  const Vec3<D> y = LoadVec3(d, lanes.query, i);
  LaneSolver<D> solver(d, problem, y, T(1));
  hn::Vec<D> gauge;
  Candidate<D> start = RadialStart(d, solver, y, lanes, i, &gauge);
  const auto inside = hn::Lt(gauge, hn::Set(d, 1));
  const auto outside = hn::Not(inside);
  if (lanes.hint[0] != nullptr) {
    // The caller's warm start goes first outside (ExactSolver::solve); NaN or 0 = none.
    const Vec3<D> hint = LoadVec3(d, lanes.hint, i);
    const auto warm =
        hn::And(hn::And(outside, AllFinite(hint)), hn::Gt(Dot(hint, hint), hn::Zero(d)));
    if (!hn::AllFalse(d, warm)) start = Select(warm, solver.candidateOnRay(hint), start);
  }
  hn::Mask<D> solved;
  const Candidate<D> c = solver.refine(start, outside, &solved);
  StoreAnswer(d, c, solved, inside, lanes, i);
}

/// ball_certificate.h's certificates on the lanes of `lanes`, one lane at a time through the
/// scalar solver's own functions (ExactSolver::searchInside): the Hessian ball, and where it
/// fails the direction cover's, on at most exact_rules::kCoverAttempts answers per lane
/// (`cover_attempts`, per lane, as the split cells' support points, `split_budgets`); converged
/// inside candidates `c` at `distance` from the queries `y`.
template <class D>
hn::Mask<D> CertifiedLanes(D d, const LaneProblem<hn::TFromD<D>>& problem, const Vec3<D>& y,
                           const Candidate<D>& c, hn::Vec<D> distance, hn::Mask<D> lanes,
                           int* cover_attempts, int* split_budgets) {
  using T = hn::TFromD<D>;
  // After dual iterations a candidate's gradient is its start's: ∇G at the point is n/(n·N)
  // (the gauge's gradient at the boundary point of normal n; ExactSolver::newtonDual).
  const Vec3<D> gradient = Times(hn::Div(hn::Set(d, T(1)), Dot(c.normal, c.point)), c.normal);
  T lane[15][kMaxLanes];
  const hn::Vec<D> values[15] = {
      y.x,        y.y,        y.z,        c.point.x,
      c.point.y,  c.point.z,  gradient.x, gradient.y,
      gradient.z, distance,   c.error,    hn::IfThenElseZero(lanes, hn::Set(d, T(1))),
      c.normal.x, c.normal.y, c.normal.z};
  for (int k = 0; k < 15; ++k) hn::StoreU(values[k], d, lane[k]);
  for (std::size_t k = 0; k < hn::Lanes(d); ++k) {
    if (lane[11][k] == T(0)) continue;
    auto vector = [&](int row) {
      return Vector3<T>(lane[row][k], lane[row + 1][k], lane[row + 2][k]);
    };
    bool holds = hessianBallCertified(problem.primal, vector(0), vector(3), vector(6), lane[9][k],
                                      lane[10][k]);
    if (!holds && cover_attempts[k] < rules::kCoverAttempts) {
      ++cover_attempts[k];
      holds = directionCoverCertified(directionCover(*problem.shape), problem.primal, vector(0),
                                      vector(3), vector(12), vector(6), lane[9][k],
                                      T(rules::kCoverCapLimit), &split_budgets[k]);
    }
    lane[11][k] = holds ? T(1) : T(0);
  }
  return hn::Gt(hn::LoadU(d, lane[11]), hn::Zero(d));
}

/// The lanes the inside pass solves: inside, not deep (g ≥ kDeepGauge: the scalar solver's
/// candidates at the centre), and off the coordinate planes (the scalar solver's tilted
/// starts).
template <class D>
hn::Mask<D> InsideWork(D d, const LaneProblem<hn::TFromD<D>>& problem, const Vec3<D>& y,
                       hn::Vec<D> gauge) {
  using T = hn::TFromD<D>;
  const hn::Vec<D> near_plane = hn::Set(d, rules::nearPlaneFraction<T>());
  hn::Mask<D> work =
      hn::And(hn::Lt(gauge, hn::Set(d, 1)), hn::Ge(gauge, hn::Set(d, T(rules::kDeepGauge))));
  work = hn::And(work, hn::Gt(y.x, hn::Mul(near_plane, hn::Set(d, problem.radii[0]))));
  work = hn::And(work, hn::Gt(y.y, hn::Mul(near_plane, hn::Set(d, problem.radii[1]))));
  work = hn::And(work, hn::Gt(y.z, hn::Mul(near_plane, hn::Set(d, problem.radii[2]))));
  return work;
}

/// The certificate of the lanes' answers as global (exact_rules::certifiedGlobal): the rolling
/// ball lane-wise (d + tolerance ≤ the rolling radius), else the Hessian ball and the direction
/// cover (ball_certificate.h) lane by lane through the scalar solver's own functions, each
/// lane's cover attempts and split budget kept across its candidates.
template <class D>
class InsideCertificate {
 public:
  using T = hn::TFromD<D>;
  InsideCertificate(D d, const LaneProblem<T>& problem, const LaneSolver<D>& solver,
                    const Vec3<D>& y)
      : d_(d), problem_(problem), solver_(solver), y_(y) {
    std::fill(split_budgets_, split_budgets_ + kMaxLanes, DirectionCover<T>::kSplitSupportPoints);
  }

  /// The lanes whose candidate c is certified; `fresh`: the lanes whose candidate is new since
  /// the last check (the balls are tested once per candidate, as in ExactSolver::searchInside).
  hn::Mask<D> operator()(const Candidate<D>& c, hn::Mask<D> converged, hn::Mask<D> fresh) {
    const Vec3<D> to_c = Minus(y_, c.point);
    const hn::Vec<D> distance = hn::Sqrt(Dot(to_c, to_c));
    const hn::Vec<D> reach = hn::Add(distance, solver_.tolerance());
    const hn::Mask<D> rolling =
        hn::And(converged, hn::Le(reach, hn::Set(d_, problem_.rolling_radius)));
    const hn::Mask<D> open = hn::And(fresh, hn::AndNot(rolling, converged));
    if (hn::AllFalse(d_, open)) return rolling;
    return hn::Or(rolling, hn::And(open, CertifiedLanes(d_, problem_, y_, c, distance, open,
                                                        cover_attempts_, split_budgets_)));
  }

 private:
  D d_;
  const LaneProblem<T>& problem_;
  const LaneSolver<D>& solver_;
  const Vec3<D> y_;
  int cover_attempts_[kMaxLanes] = {};
  int split_budgets_[kMaxLanes];
};

/// The three axis projections (ExactSolver::axisProjections): one coordinate of Q moved outward
/// until G = 1, in the primal's scaled coordinates u = y/a.
template <class D>
std::array<Vec3<D>, 3> AxisProjections(D d, const LaneProblem<hn::TFromD<D>>& problem,
                                       const Vec3<D>& y) {
  using V = hn::Vec<D>;
  const V zero = hn::Zero(d), one = hn::Set(d, 1);
  const NestedNorm<hn::TFromD<D>>& g = problem.primal;
  const V s0 = hn::Set(d, g.scale[0]), s1 = hn::Set(d, g.scale[1]), s2 = hn::Set(d, g.scale[2]);
  const V p1 = hn::Set(d, g.p1), p2 = hn::Set(d, g.p2);
  const V inv_p1 = hn::Set(d, g.inv_p1), inv_p2 = hn::Set(d, g.inv_p2);
  auto complement = [&](V t, V p, V inv_p) {  // s with ‖(t, s)‖_p = 1, t ≤ 1
    return Pow(d, hn::Max(zero, hn::Sub(one, Pow(d, t, p))), inv_p);
  };
  const V u0 = hn::Mul(y.x, s0), u1 = hn::Mul(y.y, s1), u2 = hn::Mul(y.z, s2);
  const V r = PNorm2WithPowers(d, u0, u1, p1, inv_p1, hn::Sub(p1, one)).norm;
  const V r_target = complement(u2, p2, inv_p2);
  const V safe_target = hn::IfThenElse(hn::Gt(r_target, zero), r_target, one);
  auto move = [&](V other, V own) {
    return hn::IfThenElse(hn::Lt(other, r_target),
                          hn::Mul(r_target, complement(hn::Div(other, safe_target), p1, inv_p1)),
                          own);
  };
  return {Vec3<D>{hn::Div(move(u1, u0), s0), y.y, y.z},
          Vec3<D>{y.x, hn::Div(move(u0, u1), s1), y.z},
          Vec3<D>{y.x, y.y, hn::Div(complement(hn::Min(r, one), p2, inv_p2), s2)}};
}

/// The lanes whose answer the inside pass keeps: converged, and neither deep in an elongated
/// shape (farther than a quarter of a cross-section's smaller radius: the scalar solver adds
/// the cross-sections' diagonal starts there) unless certified, nor at the caller's iteration
/// cap (the scalar solver counts its second-order corrections as iterations,
/// exact_rules::kStepTrials, so under a tight cap it may stop where the lane, certified after
/// fewer iterations, would have answered).
template <class D>
hn::Mask<D> InsideSolved(D d, const LaneProblem<hn::TFromD<D>>& problem,
                         const LaneSolver<D>& solver, const Vec3<D>& y, const Candidate<D>& best,
                         hn::Mask<D> done, hn::Mask<D> work, hn::Mask<D> all_converged) {
  using T = hn::TFromD<D>;
  const Vec3<D> to_best = Minus(y, best.point);
  const hn::Vec<D> best_distance = hn::Sqrt(Dot(to_best, to_best));
  // (of every cross-section's radii: the smallest radius is a lower bound on all of them)
  const T quarter_min = T(rules::kDiagonalStartDepth) *
                        std::min({problem.radii[0], problem.radii[1], problem.radii[2]});
  const hn::Mask<D> deep = hn::AndNot(done, hn::Gt(best_distance, hn::Set(d, quarter_min)));
  const hn::Mask<D> over_budget =
      hn::Ge(solver.iterations(), hn::Set(d, T(problem.max_iterations)));
  return hn::AndNot(hn::Or(deep, over_budget), hn::And(work, all_converged));
}

/// The inside pass on one vector of lanes at i: the radial start, then, on the lanes no
/// certificate settled, the three axis projections, each answer kept where it is nearer;
/// what the lanes do not settle goes back to the scalar solver.
template <class D>
void SolveInsideVector(D d, const LaneProblem<hn::TFromD<D>>& problem,
                       const LaneArrays<hn::TFromD<D>>& lanes, std::size_t i) {
  using M = hn::Mask<D>;
  const Vec3<D> y = LoadVec3(d, lanes.query, i);
  LaneSolver<D> solver(d, problem, y, hn::TFromD<D>(-1));
  hn::Vec<D> gauge;
  const Candidate<D> radial = RadialStart(d, solver, y, lanes, i, &gauge);
  const M none = hn::MaskFromVec(hn::Zero(d));
  const M work = InsideWork(d, problem, y, gauge);
  if (hn::AllFalse(d, work)) {  // (every lane to the scalar solver)
    StoreAnswer(d, radial, none, none, lanes, i);
    if (lanes.runner_up != nullptr) {
      hn::StoreU(hn::Set(d, std::numeric_limits<hn::TFromD<D>>::infinity()), d,
                 lanes.runner_up + i);
    }
    return;
  }

  M all_converged;
  Candidate<D> best = solver.refine(radial, work, &all_converged);
  // The converged answers of the starts, for the runner-up (ExactSolver::noteConverged).
  std::array<Vec3<D>, 4> seen;
  std::array<M, 4> seen_converged;
  std::size_t seen_count = 0;
  seen[seen_count] = best.point;
  seen_converged[seen_count++] = hn::And(work, all_converged);
  InsideCertificate<D> certified(d, problem, solver, y);
  M done = certified(best, all_converged, work);
  M more = hn::AndNot(done, work);
  // (The projections' powers only where a lane still needs them: the first start is certified
  // on most shallow lanes.)
  if (!hn::AllFalse(d, more)) {
    for (const Vec3<D>& start : AxisProjections(d, problem, y)) {
      if (hn::AllFalse(d, more)) break;
      M converged;
      const Candidate<D> c = solver.refine(solver.candidateOnRay(start), more, &converged);
      seen[seen_count] = c.point;
      seen_converged[seen_count++] = hn::And(more, converged);
      all_converged = hn::And(all_converged, hn::Or(converged, done));
      // ExactSolver::isBetter between converged candidates: strictly nearer wins.
      const Vec3<D> to_c = Minus(y, c.point), to_best = Minus(y, best.point);
      const M nearer = hn::And(converged, hn::Lt(Dot(to_c, to_c), Dot(to_best, to_best)));
      best = Select(nearer, c, best);
      const M now_done = certified(best, hn::And(more, all_converged), nearer);
      done = hn::Or(done, now_done);
      more = hn::AndNot(now_done, more);
    }
  }
  StoreAnswer(d, best, InsideSolved(d, problem, solver, y, best, done, work, all_converged), none,
              lanes, i);
  if (lanes.runner_up == nullptr) return;
  // As ExactSolver::finish: the nearest converged answer farther than √(tolerance·size) from
  // the kept one.
  using V = hn::Vec<D>;
  const V separation = hn::Mul(solver.tolerance(), hn::Set(d, problem.size));  // squared
  V runner_up = hn::Set(d, std::numeric_limits<hn::TFromD<D>>::infinity());
  for (std::size_t k = 0; k < seen_count; ++k) {
    const Vec3<D> apart = Minus(seen[k], best.point), to_seen = Minus(y, seen[k]);
    const M other = hn::And(seen_converged[k], hn::Gt(Dot(apart, apart), separation));
    runner_up =
        hn::IfThenElse(other, hn::Min(runner_up, hn::Sqrt(Dot(to_seen, to_seen))), runner_up);
  }
  hn::StoreU(runner_up, d, lanes.runner_up + i);
}

/// The classifying pass on one vector of lanes at i: G(Q) < 1, and the gauge's evaluation at Q
/// stored for the passes' radial start.
template <class D>
void ClassifyVector(D d, const LaneProblem<hn::TFromD<D>>& problem,
                    const LaneArrays<hn::TFromD<D>>& lanes, std::size_t i) {
  using T = hn::TFromD<D>;
  const NormEval<D> e = Evaluate(d, NormLanes<D>(d, problem.primal), LoadVec3(d, lanes.query, i));
  const hn::Vec<D> values[LaneArrays<T>::kRadialArrays] = {
      e.value,      e.gradient.x, e.gradient.y, e.gradient.z, e.hessian.xx,
      e.hessian.xy, e.hessian.xz, e.hessian.yy, e.hessian.yz, e.hessian.zz};
  for (int k = 0; k < LaneArrays<T>::kRadialArrays; ++k) {
    hn::StoreU(values[k], d, lanes.radial[k] + i);
  }
  const hn::Vec<D> code =
      hn::IfThenElse(hn::Lt(e.value, hn::Set(d, T(1))), hn::Set(d, T(kLaneInside)), hn::Zero(d));
  HWY_ALIGN T codes[kMaxLanes];
  hn::Store(code, d, codes);
  for (std::size_t k = 0; k < hn::Lanes(d); ++k) lanes.status[i + k] = std::int32_t(codes[k]);
}

/// G at n first-octant points (gaugeLanes).
template <typename T>
void GaugeLanes(const NestedNorm<T>& primal, const T* const query[3], T* gauge, std::size_t n) {
  using D = hn::ScalableTag<T>;
  const D d;
  static_assert(hn::MaxLanes(D()) <= kVectorLanes<T>, "kVectorLanes is too small for this target");
  const NormLanes<D> c(d, primal);
  for (std::size_t i = 0; i < n; i += hn::Lanes(d)) {
    const Vec3<D> y = LoadVec3(d, query, i);
    const NestedLevels<D> levels =
        EvaluateLevels(d, c, hn::Mul(y.x, c.s0), hn::Mul(y.y, c.s1), hn::Mul(y.z, c.s2));
    hn::StoreU(levels.level2.norm, d, gauge + i);
  }
}

/// ∂d/∂θ at n first-octant surface points with their normals (shapeGradientLanes):
/// point_gradient.h's shapeGradient, lane-wise.
template <typename T>
void ShapeGradientLanes(const NestedNorm<T>& primal, const T* const point[3],
                        const T* const normal[3], T* const d_shape[5], std::size_t n) {
  using D = hn::ScalableTag<T>;
  using V = hn::Vec<D>;
  const D d;
  static_assert(hn::MaxLanes(D()) <= kVectorLanes<T>, "kVectorLanes is too small for this target");
  const V zero = hn::Zero(d), one = hn::Set(d, 1), half = hn::Set(d, T(0.5));
  const V s0 = hn::Set(d, primal.scale[0]), s1 = hn::Set(d, primal.scale[1]);
  const V s2 = hn::Set(d, primal.scale[2]);
  // φ(x, y) = ln(1 + q) − q·ln q/(1 + q), q = min(x, y)/max(x, y); 0 where q is (also where it
  // rounds to 0).
  auto phi = [&](V x, V y) {
    const V larger = hn::Max(x, y);
    const V q_raw = hn::Div(hn::Min(x, y), hn::IfThenElse(hn::Gt(larger, zero), larger, one));
    const auto positive = hn::Gt(q_raw, zero);
    const V q = hn::IfThenElse(positive, q_raw, one);
    const V value = hn::Sub(hn::Log1p(d, q), hn::Div(hn::Mul(q, hn::Log(d, q)), hn::Add(one, q)));
    return hn::IfThenElseZero(positive, value);
  };
  for (std::size_t i = 0; i < n; i += hn::Lanes(d)) {
    const Vec3<D> p = LoadVec3(d, point, i), m = LoadVec3(d, normal, i);
    const V b0 = hn::Abs(hn::Mul(p.x, m.x)), b1 = hn::Abs(hn::Mul(p.y, m.y));
    const V b2 = hn::Abs(hn::Mul(p.z, m.z));
    const V b01 = hn::Add(b0, b1);
    const V out[5] = {hn::Neg(hn::Mul(b0, s0)), hn::Neg(hn::Mul(b1, s1)), hn::Neg(hn::Mul(b2, s2)),
                      hn::Mul(hn::Mul(half, b01), phi(b0, b1)),
                      hn::Mul(hn::Mul(half, hn::Add(b01, b2)), phi(b01, b2))};
    for (int k = 0; k < 5; ++k) hn::StoreU(out[k], d, d_shape[k] + i);
  }
}

void ShapeGradientLanesFloat(const NestedNorm<float>& primal, const float* const point[3],
                             const float* const normal[3], float* const d_shape[5], std::size_t n) {
  ShapeGradientLanes(primal, point, normal, d_shape, n);
}
void ShapeGradientLanesDouble(const NestedNorm<double>& primal, const double* const point[3],
                              const double* const normal[3], double* const d_shape[5],
                              std::size_t n) {
  ShapeGradientLanes(primal, point, normal, d_shape, n);
}

void GaugeLanesFloat(const NestedNorm<float>& primal, const float* const query[3], float* gauge,
                     std::size_t n) {
  GaugeLanes(primal, query, gauge, n);
}
void GaugeLanesDouble(const NestedNorm<double>& primal, const double* const query[3], double* gauge,
                      std::size_t n) {
  GaugeLanes(primal, query, gauge, n);
}

template <typename T>
void SolveLanes(const LaneProblem<T>& problem, const LaneArrays<T>& lanes, std::size_t n,
                LanePass pass) {
  const hn::ScalableTag<T> d;
  const std::size_t step = hn::Lanes(d);
  for (std::size_t i = 0; i < n; i += step) {
    switch (pass) {
      case LanePass::kClassify:
        ClassifyVector(d, problem, lanes, i);
        break;
      case LanePass::kOutside:
        SolveOutsideVector(d, problem, lanes, i);
        break;
      case LanePass::kInside:
        SolveInsideVector(d, problem, lanes, i);
        break;
    }
  }
}

void SolveLanesFloat(const LaneProblem<float>& problem, const LaneArrays<float>& lanes,
                     std::size_t n, LanePass pass) {
  SolveLanes(problem, lanes, n, pass);
}
void SolveLanesDouble(const LaneProblem<double>& problem, const LaneArrays<double>& lanes,
                      std::size_t n, LanePass pass) {
  SolveLanes(problem, lanes, n, pass);
}

}  // namespace HWY_NAMESPACE
}  // namespace detail
}  // namespace fcl_superellipsoid
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace fcl_superellipsoid {
namespace detail {

HWY_EXPORT(SolveLanesFloat);
HWY_EXPORT(SolveLanesDouble);
HWY_EXPORT(GaugeLanesFloat);
HWY_EXPORT(GaugeLanesDouble);
HWY_EXPORT(ShapeGradientLanesFloat);
HWY_EXPORT(ShapeGradientLanesDouble);

void shapeGradientLanes(const NestedNorm<float>& primal, const float* const point[3],
                        const float* const normal[3], float* const d_shape[5], std::size_t n) {
  HWY_DYNAMIC_DISPATCH(ShapeGradientLanesFloat)(primal, point, normal, d_shape, n);
}
void shapeGradientLanes(const NestedNorm<double>& primal, const double* const point[3],
                        const double* const normal[3], double* const d_shape[5], std::size_t n) {
  HWY_DYNAMIC_DISPATCH(ShapeGradientLanesDouble)(primal, point, normal, d_shape, n);
}

void gaugeLanes(const NestedNorm<float>& primal, const float* const query[3], float* gauge,
                std::size_t n) {
  HWY_DYNAMIC_DISPATCH(GaugeLanesFloat)(primal, query, gauge, n);
}
void gaugeLanes(const NestedNorm<double>& primal, const double* const query[3], double* gauge,
                std::size_t n) {
  HWY_DYNAMIC_DISPATCH(GaugeLanesDouble)(primal, query, gauge, n);
}

void solveLanes(const LaneProblem<float>& problem, const LaneArrays<float>& lanes, std::size_t n,
                LanePass pass) {
  HWY_DYNAMIC_DISPATCH(SolveLanesFloat)(problem, lanes, n, pass);
}
void solveLanes(const LaneProblem<double>& problem, const LaneArrays<double>& lanes, std::size_t n,
                LanePass pass) {
  HWY_DYNAMIC_DISPATCH(SolveLanesDouble)(problem, lanes, n, pass);
}

std::vector<std::pair<std::int64_t, std::string>> simdTargetsOfThisCpu() {
  std::vector<std::pair<std::int64_t, std::string>> out;
  for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    out.emplace_back(target, hwy::TargetName(target));
  }
  return out;
}

void restrictSimdTargets(std::int64_t targets) { hwy::SetSupportedTargetsForTest(targets); }

}  // namespace detail

const char* simdInstructionSet() {
  const std::int64_t targets = hwy::SupportedTargets() & HWY_TARGETS;
  return hwy::TargetName(targets & -targets);  // the lowest bit is the best target
}
}  // namespace fcl_superellipsoid
#endif  // HWY_ONCE
