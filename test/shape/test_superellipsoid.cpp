// The shape's own mathematics: surface, gauge, gradient, volume, inertia, validation.

#include <fcl/geometry/shape/ellipsoid.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "fcl_superellipsoid/point_distance.h"
#include "fcl_superellipsoid/superellipsoid.h"
#include "solvers/direction_cover.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

using test::evalTolerance;

template <typename S>
class SuperellipsoidTest : public ::testing::Test {};
TYPED_TEST_SUITE(SuperellipsoidTest, test::Scalars);

TYPED_TEST(SuperellipsoidTest, ParametricPointsSatisfyTheImplicitEquation) {
  using S = TypeParam;
  test::AngleSampler angles(1);
  for (const auto& a : test::radiiSet()) {
    for (double e1 : test::exponentGrid()) {
      for (double e2 : test::exponentGrid()) {
        const Superellipsoid<S> shape{S(a[0]), S(a[1]), S(a[2]), S(e1), S(e2)};
        SCOPED_TRACE(test::describe(shape));
        for (int k = 0; k < 40; ++k) {
          const auto [eta, omega] = angles();
          const Vector3<S> p = shape.surfacePoint(S(eta), S(omega));
          // Ground truth is independent: the long-double gauge of the point as computed.
          EXPECT_NEAR(double(test::referenceGauge(shape, p)), 1.0, 4 * evalTolerance<S>());
          EXPECT_NEAR(shape.gauge(p), S(1), 4 * evalTolerance<S>());
          ASSERT_TRUE(std::isfinite(shape.gauge(p)));
        }
      }
    }
  }
}

TYPED_TEST(SuperellipsoidTest, GaugeMatchesTheIndependentReferenceOffTheSurface) {
  using S = TypeParam;
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (const auto& a : test::radiiSet()) {
    for (double e1 : test::exponentGrid()) {
      for (double e2 : test::exponentGrid()) {
        const Superellipsoid<S> shape{S(a[0]), S(a[1]), S(a[2]), S(e1), S(e2)};
        SCOPED_TRACE(test::describe(shape));
        for (double scale : {1e-12, 1e-3, 0.5, 1.0, 7.0, 1e6}) {
          const Vector3<S> x(S(unit(rng) * a[0] * scale), S(unit(rng) * a[1] * scale),
                             S(unit(rng) * a[2] * scale));
          const long double ref = test::referenceGauge(shape, x);
          const S g = shape.gauge(x);
          ASSERT_TRUE(std::isfinite(g));
          EXPECT_NEAR(double(g / ref), 1.0, 4 * evalTolerance<S>()) << "scale " << scale;
        }
      }
    }
  }
}

TYPED_TEST(SuperellipsoidTest, ImplicitFunctionIsOneOnTheSurfaceAndAPowerOfTheGauge) {
  using S = TypeParam;
  const Superellipsoid<S> shape{S(1), S(2), S(0.5), S(0.4), S(1.6)};
  const Vector3<S> p = shape.surfacePoint(S(0.3), S(2.0));
  EXPECT_NEAR(shape.implicitFunction(p), S(1), 4 * evalTolerance<S>());
  const Vector3<S> x(S(0.3), S(-1.1), S(0.2));
  EXPECT_NEAR(shape.implicitFunction(x) / std::pow(shape.gauge(x), S(2) / shape.eps2()), S(1),
              4 * evalTolerance<S>());
}

TYPED_TEST(SuperellipsoidTest, NormalAgreesWithAFiniteDifferenceGradient) {
  using S = TypeParam;
  test::AngleSampler angles(3);
  for (const auto& a : test::radiiSet()) {
    for (double e1 : test::exponentGrid()) {
      for (double e2 : test::exponentGrid()) {
        const Superellipsoid<S> shape{S(a[0]), S(a[1]), S(a[2]), S(e1), S(e2)};
        SCOPED_TRACE(test::describe(shape));
        const std::array<long double, 3> ra{a[0], a[1], a[2]};
        for (int k = 0; k < 10; ++k) {
          const auto [eta, omega] = angles();
          const Vector3<S> p = shape.surfacePoint(S(eta), S(omega));
          // Central differences of the long-double reference gauge, with a step of 1e-6 × |p_i|
          // per component: the gradient of G varies on the scale of the distance to the
          // coordinate plane (a cusp there as ε → 2), so a step must not cross the plane.
          long double fd[3];
          for (int i = 0; i < 3; ++i) {
            const long double h = 1e-6L * std::fabs((long double)p[i]) + 1e-30L;
            std::array<long double, 3> xp{p[0], p[1], p[2]}, xm{p[0], p[1], p[2]};
            xp[i] += h;
            xm[i] -= h;
            fd[i] = (test::referenceGauge(ra, e1, e2, xp) - test::referenceGauge(ra, e1, e2, xm)) /
                    (2 * h);
          }
          const long double fd_norm = std::sqrt(fd[0] * fd[0] + fd[1] * fd[1] + fd[2] * fd[2]);
          const Vector3<S> n = shape.normal(p);
          const Vector3<S> grad = shape.gaugeGradient(p);
          EXPECT_NEAR(n.norm(), S(1), 4 * evalTolerance<S>());
          for (int i = 0; i < 3; ++i) {
            // Finite differences are only as good as the gradient is smooth over the step;
            // for ε near 2 the gradient has a cusp on the coordinate planes.
            EXPECT_NEAR(double(n[i]), double(fd[i] / fd_norm),
                        (std::is_same<S, float>::value ? 1e-4 : 1e-6))
                << "component " << i << " at " << p.transpose();
            EXPECT_NEAR(double(grad[i]), double(fd[i]),
                        (std::is_same<S, float>::value ? 1e-4 : 1e-6) * double(fd_norm))
                << "component " << i;
          }
        }
      }
    }
  }
}

TYPED_TEST(SuperellipsoidTest, ImplicitGradientIsTheScaledGaugeGradient) {
  using S = TypeParam;
  const Superellipsoid<S> shape{S(1.5), S(0.7), S(1.2), S(0.8), S(1.3)};
  const Vector3<S> x(S(0.4), S(-0.3), S(0.9));
  const S p2 = S(2) / shape.eps2();
  const Vector3<S> expected = p2 * std::pow(shape.gauge(x), p2 - 1) * shape.gaugeGradient(x);
  EXPECT_TRUE(shape.implicitGradient(x).isApprox(expected, 4 * evalTolerance<S>()));
}

TYPED_TEST(SuperellipsoidTest, GradientAndNormalStayFiniteAtExtremes) {
  using S = TypeParam;
  for (double e1 : test::exponentGrid()) {
    for (double e2 : test::exponentGrid()) {
      const Superellipsoid<S> shape{S(2), S(1), S(0.5), S(e1), S(e2)};
      for (const Vector3<S>& x : {Vector3<S>(S(1e-12), S(0), S(0)), Vector3<S>(S(0), S(0), S(1e6)),
                                  Vector3<S>(S(1e6), S(-1e6), S(3e5)), Vector3<S>(S(0), S(0), S(0)),
                                  Vector3<S>(S(1e-12), S(1e-12), S(1e-12))}) {
        const Vector3<S> n = shape.normal(x);
        ASSERT_TRUE(n.allFinite()) << x.transpose();
        EXPECT_NEAR(n.norm(), S(1), 4 * evalTolerance<S>());
        ASSERT_TRUE(std::isfinite(shape.radialDistance(x)));
        ASSERT_TRUE(shape.gaugeGradient(x).allFinite());
      }
    }
  }
}

TYPED_TEST(SuperellipsoidTest, RadialDistanceAndProjection) {
  using S = TypeParam;
  const Superellipsoid<S> sphere{S(2), S(2), S(2), S(1), S(1)};
  EXPECT_NEAR(sphere.radialDistance(Vector3<S>(S(3), S(4), S(0))), S(3), 4 * evalTolerance<S>());
  EXPECT_NEAR(sphere.radialDistance(Vector3<S>(S(0), S(0), S(-0.5))), S(-1.5),
              4 * evalTolerance<S>());
  const Superellipsoid<S> shape{S(3), S(1), S(2), S(0.3), S(1.7)};
  EXPECT_EQ(shape.radialDistance(Vector3<S>::Zero()), S(-1));  // −(smallest radius)
  const Vector3<S> x(S(0.2), S(5), S(-1));
  const Vector3<S> p = shape.radialProjection(x);
  EXPECT_NEAR(shape.gauge(p), S(1), 4 * evalTolerance<S>());
  EXPECT_NEAR(p.normalized().dot(x.normalized()), S(1), 4 * evalTolerance<S>());
  EXPECT_NEAR(shape.radialDistance(x), (x - p).norm(), 10 * evalTolerance<S>() * x.norm());
  EXPECT_TRUE(shape.contains(p * S(0.999)));
  EXPECT_FALSE(shape.contains(p * S(1.001)));
}

TYPED_TEST(SuperellipsoidTest, VolumeAndInertiaMatchTheEllipsoidExactly) {
  using S = TypeParam;
  const Superellipsoid<S> unit{S(1), S(1), S(1), S(1), S(1)};
  EXPECT_NEAR(unit.computeVolume(), S(4 * M_PI / 3), 4 * evalTolerance<S>());
  EXPECT_TRUE(unit.computeMomentofInertia().isApprox(
      fcl::Matrix3<S>(fcl::Vector3<S>::Constant(S(8 * M_PI / 15)).asDiagonal()),
      4 * evalTolerance<S>()));
  // FCL's own Ellipsoid is an independent implementation of the ε = (1, 1) case.
  const fcl::Ellipsoid<S> ellipsoid(S(1.5), S(0.5), S(2.5));
  const Superellipsoid<S> shape{S(1.5), S(0.5), S(2.5), S(1), S(1)};
  EXPECT_NEAR(shape.computeVolume() / ellipsoid.computeVolume(), S(1), 4 * evalTolerance<S>());
  EXPECT_TRUE(shape.computeMomentofInertia().isApprox(ellipsoid.computeMomentofInertia(),
                                                      4 * evalTolerance<S>()));
  EXPECT_TRUE(shape.computeCOM().isZero());
}

// Seeded Monte Carlo over the bounding box, with the long-double reference gauge as the
// membership test; the tolerance is 5 standard errors of the estimate.
TYPED_TEST(SuperellipsoidTest, VolumeAndInertiaMatchMonteCarloIntegration) {
  using S = TypeParam;
  const std::vector<std::array<double, 5>> shapes = {{1, 1, 1, 0.3, 0.3},
                                                     {1, 2, 0.5, 1.0, 0.3},
                                                     {1, 1, 1, 1.7, 1.7},
                                                     {2, 1, 1.5, 0.1, 1.9},
                                                     {0.7, 1.3, 1, 1.9, 0.1}};
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (const auto& c : shapes) {
    const Superellipsoid<S> shape{S(c[0]), S(c[1]), S(c[2]), S(c[3]), S(c[4])};
    SCOPED_TRACE(test::describe(shape));
    const int n = 400000;
    const double box = 8 * c[0] * c[1] * c[2];
    double hits = 0, ixx = 0, iyy = 0, izz = 0, ixx2 = 0, izz2 = 0;
    for (int k = 0; k < n; ++k) {
      const double x = unit(rng) * c[0], y = unit(rng) * c[1], z = unit(rng) * c[2];
      if (test::referenceGauge({c[0], c[1], c[2]}, c[3], c[4], {x, y, z}) > 1) continue;
      hits += 1;
      ixx += y * y + z * z;
      iyy += x * x + z * z;
      izz += x * x + y * y;
      ixx2 += (y * y + z * z) * (y * y + z * z);
      izz2 += (x * x + y * y) * (x * x + y * y);
    }
    const double f = hits / n;
    const double volume_mc = box * f;
    const double volume_se = box * std::sqrt(f * (1 - f) / n);
    EXPECT_NEAR(shape.computeVolume(), volume_mc, 5 * volume_se);
    const auto inertia = shape.computeMomentofInertia();
    const double ixx_mc = box * ixx / n, izz_mc = box * izz / n;
    const double ixx_se = box * std::sqrt((ixx2 / n - (ixx / n) * (ixx / n)) / n);
    const double izz_se = box * std::sqrt((izz2 / n - (izz / n) * (izz / n)) / n);
    EXPECT_NEAR(inertia(0, 0), ixx_mc, 5 * ixx_se);
    EXPECT_NEAR(inertia(1, 1), box * iyy / n, 5 * std::max(ixx_se, izz_se) * 2);
    EXPECT_NEAR(inertia(2, 2), izz_mc, 5 * izz_se);
    EXPECT_EQ(inertia(0, 1), S(0));
  }
}

TYPED_TEST(SuperellipsoidTest, SupportPointIsTheFarthestSurfacePointAlongTheDirection) {
  using S = TypeParam;
  std::mt19937 rng(5);
  std::normal_distribution<double> gauss;
  test::AngleSampler angles(6);
  for (const auto& a : test::radiiSet()) {
    for (double e1 : test::exponentGrid()) {
      for (double e2 : test::exponentGrid()) {
        const Superellipsoid<S> shape{S(a[0]), S(a[1]), S(a[2]), S(e1), S(e2)};
        SCOPED_TRACE(test::describe(shape));
        std::vector<Vector3<S>> surface;
        for (int k = 0; k < 200; ++k) {
          const auto [eta, omega] = angles();
          surface.push_back(shape.surfacePoint(S(eta), S(omega)));
        }
        for (int k = 0; k < 20; ++k) {
          Vector3<S> d(S(gauss(rng)), S(gauss(rng)), S(gauss(rng)));
          if (k == 0) d = Vector3<S>(S(0), S(0), S(-3));  // on an axis
          if (k == 1) d = Vector3<S>(S(1), S(-1), S(0));  // in a coordinate plane
          d *= S(k % 3 == 0 ? 1e-6 : 1e6);                // any length
          const Vector3<S> s = shape.supportPoint(d);
          ASSERT_TRUE(s.allFinite());
          // On the surface (independent long-double gauge) ...
          EXPECT_NEAR(double(test::referenceGauge(shape, s)), 1.0, 8 * evalTolerance<S>());
          // ... and no sampled surface point reaches farther along d.
          const Vector3<S> u = d.normalized();
          for (const Vector3<S>& p : surface) {
            ASSERT_LE(u.dot(p), u.dot(s) + 8 * evalTolerance<S>() * shape.size());
          }
          // Where the surface is smooth at s, its normal there is the direction.
          if (std::min(e1, e2) >= 0.3 && std::max(e1, e2) <= 1.7 && !test::isElongated(a)) {
            EXPECT_GT(shape.normal(s).dot(u), S(1) - S(100) * evalTolerance<S>());
          }
        }
      }
    }
  }
}

// The support point against ∇h in long double, straight from its formula (docs/math.md →
// "Support function and the dual shape"), over the whole radius range, the aspect ratios up to
// 10:1 and ε in [0.1, 1.9]: within a few ulps of the size, and its support value u·s(u) too.
// (The library takes the powers through base-2 logarithms, the second level's from a quotient,
// so that the errors do not grow with the scale.)
TYPED_TEST(SuperellipsoidTest, SupportPointMatchesTheLongDoubleGradient) {
  using S = TypeParam;
  using L = long double;
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> exponent(0.1, 1.9), unit(0, 1);
  std::normal_distribution<double> gauss;
  const double log_min = std::log10(double(NumericRange<S>::kMinRadius)) + 1.1;
  const double log_max = std::log10(double(NumericRange<S>::kMaxRadius)) - 1.1;
  double worst_point = 0, worst_value = 0;
  for (int i = 0; i < 20000; ++i) {
    const double scale = std::pow(10.0, log_min + (log_max - log_min) * unit(rng));
    const std::array<S, 3> a = {S(scale), S(scale * std::pow(10.0, -unit(rng))),
                                S(scale * std::pow(10.0, -unit(rng)))};
    const S e1 = S(exponent(rng)), e2 = S(exponent(rng));
    const Superellipsoid<S> shape(a[0], a[1], a[2], e1, e2);
    Vector3<S> u(S(gauss(rng)), S(gauss(rng)), S(gauss(rng)));
    if (i % 10 == 0) u[i % 3] = S(0);           // in a coordinate plane
    if (i % 7 == 0) u[(i + 1) % 3] *= S(1e-6);  // nearly in one
    const Vector3<S> s = shape.supportPoint(u);
    // ∇h(u) for h(u) = ‖(‖(a1 u1, a2 u2)‖_q1, a3 u3)‖_q2, q = 2/(2 − ε), first octant.
    const L q1 = L(2) / (L(2) - L(e1)), q2 = L(2) / (L(2) - L(e2));
    const L x = L(a[0]) * std::abs(L(u[0])), y = L(a[1]) * std::abs(L(u[1])),
            z = L(a[2]) * std::abs(L(u[2]));
    const L r = std::pow(std::pow(x, q1) + std::pow(y, q1), 1 / q1);
    const L h = std::pow(std::pow(r, q2) + std::pow(z, q2), 1 / q2);
    const L g_r = std::pow(r / h, q2 - 1);
    const std::array<L, 3> expected = {
        std::copysign(L(a[0]) * g_r * std::pow(x / r, q1 - 1), L(u[0])),
        std::copysign(L(a[1]) * g_r * std::pow(y / r, q1 - 1), L(u[1])),
        std::copysign(L(a[2]) * std::pow(z / h, q2 - 1), L(u[2]))};
    const L size = L(shape.size());
    L value = 0, expected_value = 0;
    for (int k = 0; k < 3; ++k) {
      worst_point = std::max(worst_point, double(std::abs(L(s[k]) - expected[k]) / size));
      value += L(u[k]) * L(s[k]);
      expected_value += L(u[k]) * expected[k];
    }
    worst_value =
        std::max(worst_value, double(std::abs(value - expected_value) / (size * L(u.norm()))));
  }
  const double ulp = std::numeric_limits<S>::epsilon();
  EXPECT_LE(worst_point, 16 * ulp);
  EXPECT_LE(worst_value, 8 * ulp);
  std::cout << "support point: worst error " << worst_point / ulp << " ulps of the size, u·s(u) "
            << worst_value / ulp << " ulps\n";
}

// At both ends of the radius range, with direction components near the smallest normal value:
// on the surface, and supporting: u·N is the unit shape's support value, scaled. (The point
// itself may differ from the scaled unit one where a component times a radius underflows: on a
// box-like face every point supports to rounding.) fuzz_point_query found a tiny box-like shape
// whose support point left the surface: a product of the norm's powers underflowed
// (docs/hardening.md → "Findings").
TYPED_TEST(SuperellipsoidTest, SupportPointAtTheEndsOfTheRange) {
  using S = TypeParam;
  const S tiny = std::numeric_limits<S>::min() * S(1e9);  // 1e-299 in double, 1e-29 in float
  // The fuzzer's shape (double): radius 4.14e-25, where a component times the radius is
  // subnormal while the norm's power q stays normal.
  const S fuzzed = std::is_same<S, double>::value ? S(4.1400713344256291e-25) : S(1);
  for (S eps : {S(2.1994041161654495e-05), S(0.02), S(1), S(1.9)}) {
    const Superellipsoid<S> unit(S(1), S(1), S(1), eps, eps);
    for (S scale : {NumericRange<S>::kMinRadius, fuzzed, NumericRange<S>::kMaxRadius}) {
      const Superellipsoid<S> shape(scale, scale, scale, eps, eps);
      const S subnormal_product = S(4) * std::numeric_limits<S>::denorm_min() / scale;
      for (const Vector3<S>& u :
           {Vector3<S>(-tiny, -1, 0), Vector3<S>(tiny, tiny, 1),
            Vector3<S>(S(0.3), S(-0.5), S(0.8)), Vector3<S>(-subnormal_product, -1, 0)}) {
        const Vector3<S> n = shape.supportPoint(u);
        SCOPED_TRACE(test::describe(shape));
        EXPECT_NEAR(double(test::referenceGauge(shape, n)), 1.0, 4 * test::evalTolerance<S>());
        const double h_unit = double(u.dot(unit.supportPoint(u)));
        EXPECT_NEAR(double(u.dot(n / scale)), h_unit, 4 * test::evalTolerance<S>() * h_unit);
      }
    }
  }
}

// A direction whose small components are subnormal, on a small shape (docs/hardening.md →
// "Findings", 10: the fuzzer's far Radial query, where the direction's x and y components were
// 1.7e-314 and −5.7e-316 and the radius 9.5e-7): the first level's norm is subnormal, and a
// power formed from it kept only a few digits; the support point was 6.5e-5 off the surface.
TYPED_TEST(SuperellipsoidTest, SupportPointAlongASubnormalDirection) {
  using S = TypeParam;
  const S denorm = std::numeric_limits<S>::denorm_min();
  const S radius = std::is_same<S, double>::value ? S(9.53697182115238e-07) : S(1e-5);
  std::vector<std::array<S, 2>> exponents = {{S(0.7), S(0.02)}, {S(1.5), S(1)}, {S(0.3), S(1.9)}};
  // The fuzzer's exponents, double only: with ε2 = 4e-17 the reference gauge raises |z|/a to
  // the power 5e16, which overflows for a float point one ulp outside.
  if (std::is_same<S, double>::value)
    exponents.push_back({S(0.69803926255553939), S(4.3584927333917278e-17)});
  for (const std::array<S, 2>& eps : exponents) {
    for (S scale : {radius, S(1), NumericRange<S>::kMinRadius}) {
      const Superellipsoid<S> shape(scale, scale, scale, eps[0], eps[1]);
      SCOPED_TRACE(test::describe(shape));
      for (const Vector3<S>& u : {Vector3<S>(S(1e5) * denorm, S(-3e3) * denorm, S(1)),
                                  Vector3<S>(S(40) * denorm, S(7) * denorm, S(-1)),
                                  Vector3<S>(S(1e3) * denorm, S(1), S(1e3) * denorm)}) {
        const Vector3<S> n = shape.supportPoint(u);
        ASSERT_TRUE(n.allFinite());
        EXPECT_NEAR(double(test::referenceGauge(shape, n)), 1.0, 4 * test::evalTolerance<S>());
      }
    }
  }
  // The fuzzer's query itself: a far point nearly on the +z axis, Radial method.
  if (std::is_same<S, double>::value) {
    const Superellipsoid<S> shape(radius, radius, radius, S(0.69803926255553939),
                                  S(4.3584927333917278e-17));
    const Vector3<S> x(S(2.9275062608084037e-12), S(-9.7690493643014336e-14),
                       S(1.7144548770260988e+302));
    const auto r = pointDistance(shape, x, DistanceOptions<S>::of(DistanceMethod::kRadial));
    EXPECT_NEAR(double(test::referenceGauge(shape, r.nearest_point)), 1.0,
                4 * test::evalTolerance<S>());
  }
}

TYPED_TEST(SuperellipsoidTest, SupportPointOfTheZeroDirection) {
  using S = TypeParam;
  const Superellipsoid<S> shape{S(2), S(1), S(0.5), S(0.4), S(1.5)};
  EXPECT_EQ(shape.supportPoint(Vector3<S>::Zero()), Vector3<S>(S(2), S(0), S(0)));
}

// The rolling radius (minRadiusOfCurvature) against closed forms: a sphere's radius, an
// ellipsoid's a_min²/a_max (at the tip of its longest axis); 0 where an exponent is > 1. The
// bound may be up to 10 % low by design (curvature.cpp), never high.
TYPED_TEST(SuperellipsoidTest, RollingRadiusMatchesClosedForms) {
  using S = TypeParam;
  const double tol = std::is_same<S, float>::value ? 1e-6 : 1e-9;
  const std::vector<std::array<double, 3>> ellipsoids = {
      {1, 1, 1}, {2.5, 2.5, 2.5}, {3, 2, 1}, {1, 1, 1e-3}, {1000, 1, 1}, {0.2, 7, 3}};
  for (const auto& a : ellipsoids) {
    const Superellipsoid<S> shape{S(a[0]), S(a[1]), S(a[2]), S(1), S(1)};
    const double lo = *std::min_element(a.begin(), a.end());
    const double hi = *std::max_element(a.begin(), a.end());
    const double exact = lo * lo / hi;
    const double r = shape.minRadiusOfCurvature();
    EXPECT_LE(r, exact * (1 + tol)) << test::describe(shape);
    EXPECT_GE(r, 0.9 * exact * (1 - tol)) << test::describe(shape);
  }
  for (const auto& e : std::vector<std::array<double, 2>>{{1.01, 0.5}, {0.5, 1.5}, {1.9, 1.9}}) {
    EXPECT_EQ(Superellipsoid<S>(S(1), S(2), S(3), S(e[0]), S(e[1])).minRadiusOfCurvature(), S(0));
  }
}

// The rolling radius is computed on first use and kept; threads that ask at once all get the
// same value, and so does a copy of the shape (run under ThreadSanitizer by the TSan build).
TYPED_TEST(SuperellipsoidTest, RollingRadiusIsComputedOnceForAllThreads) {
  using S = TypeParam;
  const Superellipsoid<S> reference{S(3.5), S(3), S(2), S(0.4), S(0.3)};
  const S expected = reference.minRadiusOfCurvature();
  const Superellipsoid<S> shape{S(3.5), S(3), S(2), S(0.4), S(0.3)};
  std::vector<S> seen(8);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < seen.size(); ++t) {
    threads.emplace_back([&shape, &seen, t] { seen[t] = shape.minRadiusOfCurvature(); });
  }
  for (std::thread& t : threads) t.join();
  for (S value : seen) EXPECT_EQ(value, expected);
  const Superellipsoid<S> copy = shape;
  EXPECT_EQ(copy.minRadiusOfCurvature(), expected);
}

// The direction cover (the Exact solver's, src/solvers/direction_cover.h) is built on first use
// and kept: threads that ask at once all get the one stored first, threads that copy the shape
// meanwhile get a working shape, and a copy made afterwards shares it (run under
// ThreadSanitizer by the TSan build).
TYPED_TEST(SuperellipsoidTest, DirectionCoverIsBuiltOnceForAllThreads) {
  using S = TypeParam;
  const Superellipsoid<S> shape{S(3.5), S(3), S(2), S(0.4), S(0.3)};
  const Vector3<S> y(S(0.5), S(0.4), S(0.3));
  std::vector<const void*> seen(6);
  std::vector<Vector3<S>> copied_start(2);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < seen.size(); ++t) {
    threads.emplace_back([&shape, &seen, t] { seen[t] = &detail::directionCover(shape); });
  }
  for (std::size_t t = 0; t < copied_start.size(); ++t) {
    threads.emplace_back([&shape, &copied_start, &y, t] {
      const Superellipsoid<S> copy = shape;
      copied_start[t] = detail::directionCover(copy).startNear(y);
    });
  }
  for (std::thread& t : threads) t.join();
  for (const void* cover : seen) EXPECT_EQ(cover, seen[0]);
  const Superellipsoid<S> copy = shape;
  EXPECT_EQ(static_cast<const void*>(&detail::directionCover(copy)), seen[0]);
  const Vector3<S> start = detail::directionCover(shape).startNear(y);
  for (const Vector3<S>& s : copied_start) EXPECT_EQ(s, start);
}

// The cover's support points are evaluated when first read, four siblings at a time
// (solvers/direction_cover.h): threads reading the same cells of a new shape at once (starts and
// caps at points all over the shape) get what one thread gets on another new shape, bitwise,
// and each group is evaluated by one of them (the TSan build runs this).
TYPED_TEST(SuperellipsoidTest, DirectionCoverIsBuiltOnceCellByCellForAllThreads) {
  using S = TypeParam;
  const Vector3<S> radii(S(3.5), S(3), S(2));
  std::vector<Vector3<S>> ys;
  for (int k = 0; k < 24; ++k) {
    const S t = S(0.1) + S(0.8) * S(k % 6) / S(5);
    ys.push_back(
        t * Vector3<S>(S(1 + k % 3), S(1 + k % 5), S(1 + k % 4)).normalized().cwiseProduct(radii) *
        S(0.5));
  }
  struct Answer {
    Vector3<S> start;
    S radius;
    std::size_t count;
  };
  auto answers = [&](const Superellipsoid<S>& shape, std::size_t first, std::size_t step) {
    std::vector<Answer> out(ys.size());
    const detail::DirectionCover<S>& cover = detail::directionCover(shape);
    for (std::size_t k = first; k < ys.size(); k += step) {
      const Vector3<S> start = cover.startNear(ys[k]);
      const Vector3<S> n = (start - ys[k]).normalized();
      const auto cap = cover.cap(ys[k], n, (start - ys[k]).norm(), S(10));
      out[k] = {start, cap.radius, cap.count};
    }
    return out;
  };
  const Superellipsoid<S> alone{radii, S(0.4), S(0.3)};
  const std::vector<Answer> expected = answers(alone, 0, 1);
  std::size_t read_deeper = 0;  // caps that read cells below the coarsest level
  for (const Answer& a : expected) read_deeper += a.count > 0 && std::isfinite(a.radius);
  EXPECT_GT(read_deeper, ys.size() / 2);
  const Superellipsoid<S> shared{radii, S(0.4), S(0.3)};
  constexpr int kThreads = 6;
  std::vector<std::vector<Answer>> got(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    // Every thread reads every point, starting at a different one.
    threads.emplace_back([&, t] {
      got[t].resize(ys.size());
      for (std::size_t r = 0; r < ys.size(); ++r) {
        const std::size_t k = (r + std::size_t(t) * 4) % ys.size();
        got[t][k] = answers(shared, k, ys.size())[k];
      }
    });
  }
  for (std::thread& t : threads) t.join();
  for (int t = 0; t < kThreads; ++t) {
    for (std::size_t k = 0; k < ys.size(); ++k) {
      EXPECT_EQ(got[t][k].start, expected[k].start) << "thread " << t << ", point " << k;
      EXPECT_EQ(got[t][k].radius, expected[k].radius) << "thread " << t << ", point " << k;
      EXPECT_EQ(got[t][k].count, expected[k].count) << "thread " << t << ", point " << k;
    }
  }
}

// The rolling-ball property by construction, against the independent long-double gauge: the
// ball of the rolling radius that touches the surface from inside lies inside the shape, over
// the exponent grid (ε ≤ 1) and the radii set, at random surface points.
TYPED_TEST(SuperellipsoidTest, TheRollingBallLiesInside) {
  using S = TypeParam;
  test::AngleSampler angles(31);
  std::mt19937 rng(32);
  std::normal_distribution<double> gauss;
  for (const auto& a : test::radiiSet()) {
    for (double e1 : test::exponentGrid()) {
      for (double e2 : test::exponentGrid()) {
        if (e1 > 1 || e2 > 1) continue;
        const Superellipsoid<S> shape{S(a[0]), S(a[1]), S(a[2]), S(e1), S(e2)};
        SCOPED_TRACE(test::describe(shape));
        const double r = shape.minRadiusOfCurvature();
        // A lower bound; 0 (the certificate off) is allowed at the extreme exponents, where the
        // search's samples underflow, never from 0.1 up.
        if (std::min(e1, e2) >= 0.1) EXPECT_GT(r, 0.0);
        if (r == 0) continue;
        for (int k = 0; k < 6; ++k) {
          const auto [eta, omega] = angles();
          const Vector3<double> p =
              Superellipsoid<double>(a[0], a[1], a[2], e1, e2).surfacePoint(eta, omega);
          const Vector3<double> n = Superellipsoid<double>(a[0], a[1], a[2], e1, e2).normal(p);
          const Vector3<double> centre = p - r * n;
          for (int m = 0; m < 64; ++m) {
            const Vector3<double> v =
                Vector3<double>(gauss(rng), gauss(rng), gauss(rng)).normalized();
            const Vector3<double> x = centre + r * v;
            const long double g =
                test::referenceGauge({a[0], a[1], a[2]}, e1, e2, {x[0], x[1], x[2]});
            // On the surface at the touching point: G = 1 up to the rounding of x (ulps of |x|
            // relative to the smallest radius, which scales the gauge).
            EXPECT_LE(double(g), 1 + 1e-9) << "ball point outside, k = " << k;
          }
        }
      }
    }
  }
}

// The smallest principal radius of curvature at the surface point of parametric angles (η, ω) in
// the first octant, from the surface's fundamental forms in long double: an independent
// computation (the library works with the support function's Hessian on the sphere of normals).
long double parametricSmallestRadius(const std::array<double, 3>& a, long double e1, long double e2,
                                     long double eta, long double omega) {
  struct Power {  // c(t)^e or s(t)^e and its first two derivatives in t
    long double v, d1, d2;
  };
  // b(t)^e with b = cos or sin, b' its derivative (b'' = −b): one pow, the rest by division.
  auto power = [](long double b, long double db, long double e) {
    const long double v = std::pow(b, e);
    return Power{v, e * v / b * db, e * (e - 1) * v / (b * b) * db * db - e * v};
  };
  const long double ce = std::cos(eta), se = std::sin(eta), co = std::cos(omega),
                    so = std::sin(omega);
  const Power c2 = power(ce, -se, e2), s2 = power(se, ce, e2), c1 = power(co, -so, e1),
              s1 = power(so, co, e1);
  using V = Eigen::Matrix<long double, 3, 1>;
  const V x_e(a[0] * c2.d1 * c1.v, a[1] * c2.d1 * s1.v, a[2] * s2.d1);
  const V x_o(a[0] * c2.v * c1.d1, a[1] * c2.v * s1.d1, 0);
  const V x_ee(a[0] * c2.d2 * c1.v, a[1] * c2.d2 * s1.v, a[2] * s2.d2);
  const V x_eo(a[0] * c2.d1 * c1.d1, a[1] * c2.d1 * s1.d1, 0);
  const V x_oo(a[0] * c2.v * c1.d2, a[1] * c2.v * s1.d2, 0);
  const V n = x_e.cross(x_o).normalized();
  const long double E = x_e.dot(x_e), F = x_e.dot(x_o), G = x_o.dot(x_o);
  const long double L = x_ee.dot(n), M = x_eo.dot(n), N = x_oo.dot(n);
  const long double det = E * G - F * F;
  const long double gauss = (L * N - M * M) / det;
  const long double mean = std::abs(E * N - 2 * F * M + G * L) / (2 * det);
  const long double largest_curvature = mean + std::sqrt(std::max(mean * mean - gauss, 0.0L));
  return 1 / largest_curvature;
}

// The rolling radius is a lower bound on every principal radius of the surface: below the
// smallest radius over a fine set of surface points (smallestParametricRadius), and close to it
// (within the safety factor and what such a set can miss) wherever the exponents are moderate.
/// The smallest principal radius over a fine set of surface points (parametric angles in the
/// octant: 64 uniform ones, which crowd where box-like shapes bend most, and geometric ones
/// towards both ends, down to 1e-8 rad, where flat and elongated shapes have their rims and tips).
long double smallestParametricRadius(const std::array<double, 3>& a, double e1, double e2) {
  constexpr long double kHalfPi = 1.57079632679489661923132169163975144L;
  std::vector<long double> angles;
  for (int i = 0; i < 64; ++i) angles.push_back((i + 0.5L) * kHalfPi / 64);
  for (long double t = 2e-2L; t >= 1e-8L; t /= 2) {
    angles.push_back(t);
    angles.push_back(kHalfPi - t);
  }
  long double smallest = std::numeric_limits<long double>::infinity();
  for (long double eta : angles) {
    for (long double omega : angles) {
      const long double r = parametricSmallestRadius(a, e1, e2, eta, omega);
      if (std::isfinite(r)) smallest = std::min(smallest, r);
    }
  }
  return smallest;
}

TEST(RollingRadius, BelowEveryRadiusOfCurvatureAndCloseToTheSmallest) {
  for (const auto& a : test::radiiSet()) {
    for (double e1 : {0.02, 0.1, 0.3, 0.65, 1.0}) {
      for (double e2 : {0.02, 0.1, 0.3, 0.65, 1.0}) {
        const Superellipsoid<double> shape{a[0], a[1], a[2], e1, e2};
        SCOPED_TRACE(test::describe(shape));
        const long double smallest = smallestParametricRadius(a, e1, e2);
        const double bound = shape.minRadiusOfCurvature();
        EXPECT_LE(bound, double(smallest) * (1 + 1e-12));
        if (std::min(e1, e2) >= 0.3) EXPECT_GE(bound, 0.85 * double(smallest));
      }
    }
  }
}

// The same bound on shapes more elongated than 1000:1 (docs/hardening.md, finding 24): the
// search's grid, fine enough up to that aspect, found minima up to 3.7 times the smallest radius
// on random shapes beyond it (these among them), so the rolling ball certified inside answers it
// should not have.
TEST(RollingRadius, BelowEveryRadiusOfCurvatureOnElongatedShapes) {
  const std::array<double, 5> shapes[] = {
      {1.55378e-05, 0.0669112, 0.0383264, 0.270677, 0.890368},
      {0.0137929, 4.55755e-06, 0.00199165, 0.598152, 0.944018},
      {0.0428968, 2.39194e-06, 0.0885745, 0.401245, 0.6377},
      {9.10287e-07, 3.03668e-10, 0.000166513, 0.518085, 0.836271},
      {0.671916, 2181.24, 4780.31, 0.496709, 0.741248}};
  for (const auto& p : shapes) {
    const std::array<double, 3> a = {p[0], p[1], p[2]};
    const Superellipsoid<double> shape{a[0], a[1], a[2], p[3], p[4]};
    SCOPED_TRACE(test::describe(shape));
    const long double smallest = smallestParametricRadius(a, p[3], p[4]);
    EXPECT_LE(shape.minRadiusOfCurvature(), double(smallest) * (1 + 1e-12));
  }
}

// Bad parameters: test/bad_input/test_bad_input.cpp (the catalogue, docs/hardening.md).

TYPED_TEST(SuperellipsoidTest, StreamsItsParameters) {
  using S = TypeParam;
  std::ostringstream out;
  out << Superellipsoid<S>(S(1), S(2), S(3), S(0.5), S(1.5));
  EXPECT_EQ(out.str(), "Superellipsoid(a=(1, 2, 3), eps1=0.5, eps2=1.5)");
}

}  // namespace
}  // namespace fcl_superellipsoid
