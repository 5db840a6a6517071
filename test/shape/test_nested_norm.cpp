// NestedNorm::evaluate's value, gradient and Hessian against the closed forms in long double
// with pow(), for the gauge and the support function, over ratios of the arguments from 1 to
// 1e-4 (evaluate takes its powers from exp2 and log2: docs/math.md → "Support function and the
// dual shape"). At subnormal exponents (2/ε infinite) it gives the box's max norm, also where
// two coordinates tie.
//
// The duality the Exact solver relies on when it hands a primal evaluation to the dual
// formulation (docs/math.md → "The Exact solver"): at a surface point N with unit normal n, the
// support function's Hessian ∇²h(n), restricted to the tangent plane, is the inverse of the
// shape operator W = Tᵀ∇²G(N)·T/‖∇G(N)‖, and ∇²h(n)·n = 0. Ground truth: the identity itself,
// between two independent evaluations (h from the dual superellipsoid's nested norm, G from the
// shape's), on random points of random shapes away from the coordinate planes (where one of the
// two Hessians is unbounded).

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

#include "fcl_superellipsoid/superellipsoid.h"
#include "shape/nested_norm.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

/// ‖(a, b)‖_p, its gradient and Hessian in long double, straight from the definitions.
struct Norm2L {
  long double n, da, db, daa, dab, dbb;
};
Norm2L norm2L(long double a, long double b, long double p) {
  using L = long double;
  const L n = std::pow(std::pow(a, p) + std::pow(b, p), 1 / p);
  const L da = std::pow(a / n, p - 1), db = std::pow(b / n, p - 1);
  const L daa = (p - 1) / n * std::pow(a / n, p - 2) * std::pow(b / n, p);
  const L dbb = (p - 1) / n * std::pow(b / n, p - 2) * std::pow(a / n, p);
  const L dab = -(p - 1) / n * da * db;
  return {n, da, db, daa, dab, dbb};
}

/// N(w) = ‖(‖(u1, u2)‖_p1, u3)‖_p2 with u = scale ⊙ w, and its gradient and Hessian by the
/// chain rule, in long double.
struct ReferenceEval {
  long double value;
  Eigen::Matrix<long double, 3, 1> gradient;
  Eigen::Matrix<long double, 3, 3> hessian;
};
ReferenceEval referenceEval(const detail::NestedNorm<double>& norm, const Vector3<double>& w) {
  using L = long double;
  using M3 = Eigen::Matrix<L, 3, 3>;
  const Eigen::Matrix<L, 3, 1> s = norm.scale.cast<L>();
  const Eigen::Matrix<L, 3, 1> u = s.cwiseProduct(w.cast<L>());
  const Norm2L inner = norm2L(u[0], u[1], L(norm.p1));
  const Norm2L outer = norm2L(inner.n, u[2], L(norm.p2));
  const Eigen::Matrix<L, 3, 1> dr(inner.da, inner.db, 0);
  M3 drr = M3::Zero();
  drr(0, 0) = inner.daa;
  drr(1, 1) = inner.dbb;
  drr(0, 1) = drr(1, 0) = inner.dab;
  const Eigen::Matrix<L, 3, 1> e3(0, 0, 1);
  const Eigen::Matrix<L, 3, 1> gradient = outer.da * dr + outer.db * e3;
  const M3 hessian = outer.daa * dr * dr.transpose() + outer.da * drr +
                     outer.dab * (dr * e3.transpose() + e3 * dr.transpose()) +
                     outer.dbb * e3 * e3.transpose();
  return {outer.n, gradient.cwiseProduct(s), s.asDiagonal() * hessian * s.asDiagonal()};
}

TEST(NestedNormTest, EvaluateMatchesTheLongDoubleNorm) {
  using L = long double;
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> exponent(0.1, 1.9), radius(0.2, 5.0), log_ratio(-4, 0);
  double worst_value = 0, worst_gradient = 0, worst_hessian = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Superellipsoid<double> shape(radius(rng), radius(rng), radius(rng), exponent(rng),
                                       exponent(rng));
    const auto norm = trial % 2 ? detail::NestedNorm<double>::gauge(shape)
                                : detail::NestedNorm<double>::support(shape);
    const Vector3<double> w(std::pow(10.0, log_ratio(rng)), std::pow(10.0, log_ratio(rng)),
                            std::pow(10.0, log_ratio(rng)));
    const detail::NestedNormEval<double> e = norm.evaluate(w, true);
    const ReferenceEval reference = referenceEval(norm, w);
    const L value = reference.value;
    const Eigen::Matrix<L, 3, 1>& gradient = reference.gradient;
    const Eigen::Matrix<L, 3, 3>& hessian = reference.hessian;
    const double value_error = double(std::abs(L(e.value) - value) / value);
    const double gradient_error =
        double((e.gradient.cast<L>() - gradient).norm() / gradient.norm());
    const double hessian_error = double((e.hessian.cast<L>() - hessian).norm() / hessian.norm());
    worst_value = std::max(worst_value, value_error);
    worst_gradient = std::max(worst_gradient, gradient_error);
    worst_hessian = std::max(worst_hessian, hessian_error);
  }
  const double ulp = std::numeric_limits<double>::epsilon();
  EXPECT_LE(worst_value, 8 * ulp);
  EXPECT_LE(worst_gradient, 16 * ulp);
  EXPECT_LE(worst_hessian, 1e-13);
  std::printf("evaluate: worst value %.2f ulps, gradient %.2f ulps, Hessian %.3g (relative)\n",
              worst_value / ulp, worst_gradient / ulp, worst_hessian);
}

// Subnormal exponents make the gauge's powers 2/ε infinite: the gauge is then the box's max
// norm, max_i |w_i|/a_i. Where two scaled coordinates are equal the ratio t is 1 and the powers'
// p·log2 t is ∞·0 (NaN, had it been formed: a fuzz find); where all three are, the second
// level's ratio is 1 by rounding but below 1 by its logarithm, and the two had weighed both of
// its arguments fully (a gradient twice too long). Ground truth: the max norm, by construction,
// and Euler's identity ∇N·w = N for its gradient (a subgradient of the max norm there). The
// Hessian is unbounded at p = ∞ and is not checked.
template <typename S>
void expectMaxNormAtTies(S eps) {
  const Vector3<S> radii(S(1.5), S(1), S(2));
  const Superellipsoid<S> shape(radii, eps, eps);
  const detail::NestedNorm<S> gauge = detail::NestedNorm<S>::gauge(shape);
  ASSERT_FALSE(std::isfinite(gauge.p1)) << "ε = " << eps << " should make 2/ε infinite";
  for (const Vector3<S>& w : {Vector3<S>(S(1.5), S(1), S(2)), Vector3<S>(S(1.5), S(1), S(1)),
                              Vector3<S>(S(0.75), S(0.5), S(2)), Vector3<S>(S(3), S(1), S(2))}) {
    const S expected = w.cwiseQuotient(radii).maxCoeff();
    const detail::NestedNormEval<S> e = gauge.evaluate(w, true);
    const S tolerance = S(4) * std::numeric_limits<S>::epsilon() * expected;
    EXPECT_NEAR(e.value, expected, tolerance) << "at " << w.transpose() << ", ε = " << eps;
    EXPECT_NEAR(shape.gauge(w), expected, tolerance) << "at " << w.transpose();
    EXPECT_TRUE(e.gradient.allFinite()) << "gradient at " << w.transpose();
    // The gradient is a subgradient of the max norm: it reproduces the value (Euler).
    EXPECT_NEAR(e.gradient.dot(w), expected, tolerance) << "at " << w.transpose();
  }
}

// A level with p = 2 (ε = 1, a round cross-section) on a coordinate plane of that level: the
// power t^(p−2) of the zero ratio is 1 there (the circle's curvature 1/r in ∂²N/∂y²), where the
// quotient t^(p−1)/t that other exponents take would give 0/floor = 0. The Exact solver works on
// the plane y = 0 of a surface of revolution (exact_solver.cpp), so this is where its Newton
// steps and the dual's derived Hessian look. Ground truth: the long-double closed form, whose
// pow(0, 0) is 1.
TEST(NestedNormTest, ARoundLevelKeepsItsCurvatureOnItsPlanes) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> exponent(0.1, 1.9), radius(0.2, 5.0), coordinate(0.1, 2);
  double worst = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const bool outer = trial % 2 == 1;  // ε2 = 1 with z = 0, else ε1 = 1 with y = 0
    const Superellipsoid<double> shape(radius(rng), radius(rng), radius(rng),
                                       outer ? exponent(rng) : 1.0, outer ? 1.0 : exponent(rng));
    const auto norm = trial % 4 < 2 ? detail::NestedNorm<double>::gauge(shape)
                                    : detail::NestedNorm<double>::support(shape);
    Vector3<double> w(coordinate(rng), coordinate(rng), coordinate(rng));
    w[outer ? 2 : 1] = 0;
    const detail::NestedNormEval<double> e = norm.evaluate(w, true);
    const ReferenceEval reference = referenceEval(norm, w);
    ASSERT_TRUE(e.hessian.allFinite()) << "at " << w.transpose();
    worst = std::max(worst, double((e.hessian.cast<long double>() - reference.hessian).norm() /
                                   reference.hessian.norm()));
  }
  EXPECT_LE(worst, 1e-13);
}

TEST(NestedNormTest, SubnormalExponentsGiveTheMaxNormAtTies) {
  expectMaxNormAtTies<double>(1e-323);
  expectMaxNormAtTies<float>(3e-45f);
}

// A direction whose components are 1e250 to 1e300 apart, on a shape of radius 1e-11 or 1e-49:
// the products w_i·a_i of its small components are subnormal or 0, and the ratios the levels
// are made of lost their digits (finding 28 in docs/hardening.md: a far query's support point
// 1.8e-8 off the surface). Ground truth: the long-double closed form, whose range holds the
// products. Value and gradient component by component (the small ones, where normal numbers,
// are the support point's small coordinates), relative.
TEST(NestedNormTest, SupportOfADirectionWithComponentsFarApartOnATinyShape) {
  const double exponents[][2] = {{1, 2.2204460492503131e-16}, {1, 0.5}, {0.3, 1.2}, {1.7, 0.02}};
  double worst = 0;
  for (const double a : {1.4536645324972875e-11, 1.001e-49}) {
    for (const auto& e : exponents) {
      const Superellipsoid<double> shape(a, 0.7 * a, 1.3 * a, e[0], e[1]);
      const detail::NestedNorm<double> support = detail::NestedNorm<double>::support(shape);
      for (const double delta : {1e-300, 1e-250}) {
        for (const Vector3<double>& w :
             {Vector3<double>(0.867 * delta, 0.498 * delta, 1),
              Vector3<double>(1, delta, 0.5 * delta), Vector3<double>(delta, 1, 0.3)}) {
          SCOPED_TRACE(testing::Message() << "radius " << a << ", eps (" << e[0] << ", " << e[1]
                                          << "), w " << w.transpose());
          const detail::NestedNormEval<double> got = support.evaluate(w, false);
          const ReferenceEval truth = referenceEval(support, w);
          const long double value_error = std::fabs(got.value - truth.value) / truth.value;
          EXPECT_LE(value_error, 1e-13L);
          worst = std::max(worst, double(value_error));
          for (int i = 0; i < 3; ++i) {
            // (A component below double's normal range has no digits to compare.)
            if (std::fabs(truth.gradient[i]) < std::numeric_limits<double>::min()) {
              EXPECT_LE(std::fabs(got.gradient[i]), std::numeric_limits<double>::min());
              continue;
            }
            const long double error =
                std::fabs(got.gradient[i] - truth.gradient[i]) / std::fabs(truth.gradient[i]);
            EXPECT_LE(error, 1e-12L) << "gradient component " << i << ": " << got.gradient[i]
                                     << ", truth " << double(truth.gradient[i]);
            worst = std::max(worst, double(error));
            EXPECT_EQ(support.gradient(w)[i], got.gradient[i]);  // supportPoint's path
          }
        }
      }
    }
  }
  RecordProperty("worst_relative_error", testing::PrintToString(worst));
}

// ‖(a, b)‖_p and its gradient (∂/∂a, ∂/∂b) in long double from the ratio t = lo/m, which
// stays in range for exponents near the format's limit (2/ε = 2.5e23), where a^p overflows.
struct RatioNorm2L {
  long double n, da, db;
};
RatioNorm2L ratioNorm2L(long double a, long double b, long double p) {
  const long double m = std::max(a, b), lo = std::min(a, b);
  if (m == 0) return {0, 0, 0};
  const long double t = lo / m, q = std::pow(t, p);
  const long double pow_m = std::pow(1 + q, (1 - p) / p);  // (m/N)^(p−1)
  const long double pow_lo = lo > 0 ? std::pow(t, p - 1) * pow_m : 0;
  return {m * std::pow(1 + q, 1 / p), a >= b ? pow_m : pow_lo, a >= b ? pow_lo : pow_m};
}

// The gauge of a box-like shape (ε2 down to 7.9e-24 in float, 1e-300 in double) at points where
// the first level's norm r = ‖(u1, u2)‖_p1 and u3 tie to within an ulp (u1 = u3, u2 a little
// smaller): the second level's ratio, from r rounded, exceeded 1 by an ulp where its logarithm
// said it was below 1, and its power with p2 = 2/ε2 was ∞ (finding 29 in docs/hardening.md: a
// query deep inside such a shape was answered as outside, at the centre). Ground truth: the
// ratio form in long double at the same scaled arguments u (rounded as evaluate rounds them).
// The value is well conditioned (relative, 8 ulps). The gradient is not: near a tie its
// components change by p ulps when u moves by one, so the check is backward: each component lies
// within the range the truth takes over u's coordinates moved by up to 4 ulps each (a rounding
// of the ratios is such a move), ± 16 ulps. Euler's identity ∇N·w = N holds to rounding. The
// Hessian has no NaN (at an exact tie under p2 = 2e300 its true value, about p2/N·scale², is
// beyond double's range).
template <typename S>
void expectFiniteAtLevelTies(const std::vector<S>& eps2s, const std::vector<S>& eps1s) {
  using L = long double;
  using VectorL = Eigen::Matrix<L, 3, 1>;
  const S ulp = std::numeric_limits<S>::epsilon();
  auto truth = [](const detail::NestedNorm<S>& gauge, const VectorL& u) {
    const RatioNorm2L inner = ratioNorm2L(u[0], u[1], gauge.p1);
    const RatioNorm2L outer = ratioNorm2L(inner.n, u[2], gauge.p2);
    return std::make_pair(outer.n, VectorL(outer.da * inner.da, outer.da * inner.db, outer.db));
  };
  L worst_value = 0;
  for (const S eps2 : eps2s) {
    for (const S eps1 : eps1s) {
      for (const Vector3<S>& radii :
           {Vector3<S>(Vector3<S>::Constant(S(3.49456182e-4))), Vector3<S>(S(1), S(0.7), S(1.3))}) {
        const detail::NestedNorm<S> gauge =
            detail::NestedNorm<S>::gauge(Superellipsoid<S>(radii, eps1, eps2));
        for (const S c : {S(0.0144914), S(0.3), S(0.9)}) {
          for (const S shrink : {S(0), S(ulp), S(4 * ulp), S(1e-6), S(1e-3), S(0.3)}) {
            for (const S stretch : {S(0), S(ulp), S(-ulp)}) {
              // u1 = u3 = c (up to the radii's rounding), u2 = c·(1 − shrink).
              const Vector3<S> w(c * radii[0], c * (1 - shrink) * radii[1],
                                 c * (1 + stretch) * radii[2]);
              SCOPED_TRACE(testing::Message() << "eps (" << eps1 << ", " << eps2 << "), radii "
                                              << radii.transpose() << ", w " << w.transpose());
              const detail::NestedNormEval<S> got = gauge.evaluate(w, true);
              ASSERT_TRUE(std::isfinite(got.value));
              ASSERT_TRUE(got.gradient.allFinite());
              ASSERT_FALSE(got.hessian.hasNaN());
              const VectorL u = w.cwiseProduct(gauge.scale).template cast<L>();
              const L value = truth(gauge, u).first;
              const L value_error = std::fabs(got.value - value) / value;
              EXPECT_LE(value_error, L(8 * ulp));
              worst_value = std::max(worst_value, value_error);
              EXPECT_NEAR(gauge.value(w), got.value, 8 * ulp * got.value);
              EXPECT_NEAR(got.gradient.dot(w), got.value, 8 * ulp * got.value);  // Euler
              VectorL low = VectorL::Constant(2), high = VectorL::Constant(-1);
              for (int corner = 0; corner < 27; ++corner) {
                VectorL moved = u;
                for (int i = 0, k = corner; i < 3; ++i, k /= 3)
                  moved[i] *= 1 + L(4 * ulp) * (k % 3 - 1);
                const VectorL g = truth(gauge, moved).second;
                low = low.cwiseMin(g);
                high = high.cwiseMax(g);
              }
              for (int i = 0; i < 3; ++i) {
                const L component = got.gradient[i] / gauge.scale[i];
                EXPECT_GE(component, low[i] - 16 * ulp) << "gradient component " << i;
                EXPECT_LE(component, high[i] + 16 * ulp) << "gradient component " << i;
              }
            }
          }
        }
      }
    }
  }
  testing::Test::RecordProperty("worst_value_error", testing::PrintToString(double(worst_value)));
}

TEST(NestedNormTest, AGaugeStaysFiniteWhereItsLevelsTieUnderAHugeExponent) {
  expectFiniteAtLevelTies<float>({7.91498304e-24f, 1e-20f, 1e-12f}, {1.36506321e-6f, 1e-3f, 0.5f});
  expectFiniteAtLevelTies<double>({1e-300, 1e-200, 1e-30}, {1e-12, 1e-6, 0.5});
}

TEST(NestedNormTest, DualHessianIsTheInverseShapeOperator) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> radius(0.2, 2.0), exponent(0.3, 1.9), angle(0.15, 1.42);
  double worst = 0, worst_radial = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Superellipsoid<double> shape(radius(rng), radius(rng), radius(rng), exponent(rng),
                                       exponent(rng));
    const auto gauge = detail::NestedNorm<double>::gauge(shape);
    const auto support = detail::NestedNorm<double>::support(shape);
    const Vector3<double> point = shape.surfacePoint(angle(rng), angle(rng));
    const auto g = gauge.evaluate(point, true);
    const Vector3<double> n = g.gradient.normalized();
    const auto h = support.evaluate(n, true);
    Eigen::Matrix<double, 3, 2> t;
    t.col(0) = n.unitOrthogonal();
    t.col(1) = n.cross(Vector3<double>(t.col(0)));
    const Eigen::Matrix2d w = t.transpose() * g.hessian * t / g.gradient.norm();
    const Eigen::Matrix2d dual = t.transpose() * h.hessian * t;
    const Eigen::Matrix2d product = dual * w;
    worst = std::max(worst, (product - Eigen::Matrix2d::Identity()).norm());
    worst_radial = std::max(worst_radial, (h.hessian * n).norm() / h.hessian.norm());
    ASSERT_LT((product - Eigen::Matrix2d::Identity()).norm(), 1e-8)
        << shape << " at " << point.transpose() << ": ∇²h·W =\n"
        << product;
    ASSERT_LT((h.hessian * n).norm(), 1e-10 * h.hessian.norm()) << shape;
    // ∇h(n) is the point itself.
    ASSERT_LT((h.gradient - point).norm(), 1e-12 * shape.size()) << shape;
  }
  std::printf("worst |∇²h·W − I| %g, worst |∇²h·n|/|∇²h| %g\n", worst, worst_radial);
}

}  // namespace
}  // namespace fcl_superellipsoid
