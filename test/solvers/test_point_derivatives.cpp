// The derivatives of the point distance against central finite differences of the independent
// long-double reference (test_support/polished_reference.h), the non-differentiable flag on
// constructed configurations, and finite answers everywhere.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "fcl_superellipsoid/batch_distance.h"
#include "fcl_superellipsoid/point_derivatives.h"
#include "polished_reference.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace test {
namespace {

using MatL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;

/// The reference's distance, nearest point and normal at one configuration, as one column
/// (d, N, n): what the finite differences difference.
using Probe = Eigen::Matrix<long double, 7, 1>;

Probe probe(const PolishedResult& r) {
  Probe p;
  p << r.distance, r.nearest, r.normal;
  return p;
}

/// Central difference with one Richardson step: (4·D(h/2) − D(h))/3, error O(h⁴).
template <typename F>
Probe centralDifference(F&& at, long double h) {
  const Probe d1 = (at(h) - at(-h)) / (2 * h);
  const Probe d2 = (at(h / 2) - at(-h / 2)) / h;
  return (4 * d2 - d1) / 3;
}

struct Config {
  std::array<double, 3> radii;
  double e1, e2;
  Eigen::Vector3d q;  // shape frame
  std::string what;
};

std::string describe(const Config& c) {
  std::ostringstream out;
  out.precision(17);
  out << c.what << ": radii (" << c.radii[0] << ", " << c.radii[1] << ", " << c.radii[2]
      << "), eps (" << c.e1 << ", " << c.e2 << "), Q (" << c.q.transpose() << ")";
  return out.str();
}

/// Random shapes (exponents 0.1–1.9 and their ends, sizes 1e-3–1e3, aspect ratios to 100:1) and
/// points inside and outside, some near the surface and some near a crease (a coordinate plane
/// of a level with ε > 1).
std::vector<Config> randomConfigs(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Config> out;
  for (int k = 0; k < count; ++k) {
    Config c;
    const double edge[] = {0.1, 1.9};
    c.e1 = k % 7 == 3 ? edge[k % 2] : 0.1 + 1.8 * unit(rng);
    c.e2 = k % 5 == 1 ? edge[(k / 2) % 2] : 0.1 + 1.8 * unit(rng);
    const double size = std::pow(10.0, -3 + 6 * unit(rng));
    for (double& a : c.radii) a = size * std::pow(10.0, -2 * unit(rng));
    c.radii[k % 3] = size;
    // A direction, sometimes with a component near 0 (near a crease where that ε > 1).
    Eigen::Vector3d dir(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
    if (k % 4 == 2) dir[k % 3] *= 1e-3;
    dir = dir.cwiseProduct(Eigen::Vector3d(c.radii[0], c.radii[1], c.radii[2]));
    const long double g = ReferenceDistance({c.radii[0], c.radii[1], c.radii[2]}, c.e1, c.e2)
                              .gauge({dir[0], dir[1], dir[2]});
    const Eigen::Vector3d surface = dir / static_cast<double>(g);
    switch (k % 3) {
      case 0:  // inside
        c.q = surface * (0.3 + 0.68 * unit(rng));
        c.what = "inside";
        break;
      case 1:  // outside, up to three sizes away
        c.q = surface * (1.02 + 2 * unit(rng));
        c.what = "outside";
        break;
      default:  // near the surface, either side
        c.q = surface * (1 + 0.1 * (unit(rng) - 0.5));
        c.what = "near the surface";
    }
    out.push_back(c);
  }
  return out;
}

/// ‖a − b‖ relative to ‖b‖ (floored: a derivative near 0 is compared at the floor's scale).
long double relative(const MatL& a, const MatL& b, long double floor) {
  return (a - b).norm() / std::max(b.norm(), floor);
}

template <typename S>
MatL toLong(const Eigen::MatrixBase<S>& m) {
  return m.template cast<long double>();
}

/// The worst relative error of the first-order derivatives (of d) and of the second-order ones
/// (the Jacobians of N and n).
struct Worst {
  long double gradient = 0, jacobians = 0;
};

/// Checks every derivative of one configuration in the shape frame and, for a pose, in the world
/// frame, the gradient against `gradient_bound`, the Jacobians against `jacobian_bound`.
template <typename S>
void checkConfig(const Config& c, const Eigen::Isometry3d& pose, double gradient_bound,
                 double jacobian_bound, Worst* worst) {
  const double bound = gradient_bound;
  SCOPED_TRACE(describe(c));
  const Superellipsoid<S> shape(S(c.radii[0]), S(c.radii[1]), S(c.radii[2]), S(c.e1), S(c.e2));
  // The reference sees the shape and the query exactly as the library does (rounded to S).
  const ReferenceShape ref{
      {shape.radii()[0], shape.radii()[1], shape.radii()[2]}, shape.eps1(), shape.eps2()};
  const Vector3<S> q = c.q.cast<S>();
  const Vec3L ql = q.template cast<long double>();
  const PolishedResult base = polishedReference(ref, ql);
  EXPECT_TRUE(base.ok);
  if (!base.ok) return;
  const long double size = shape.size();

  const PointDistanceDerivatives<S> got =
      pointDistanceDerivatives(shape, q, DerivativeOrder::kJacobians);
  EXPECT_TRUE(got.differentiable);
  EXPECT_TRUE(got.has_jacobians);
  EXPECT_NEAR(static_cast<long double>(got.value.distance), base.distance, bound * size);

  const long double hq = 1e-6L * size;
  MatL dq(7, 3), dtheta(7, 5);
  for (int i = 0; i < 3; ++i) {
    dq.col(i) = centralDifference(
        [&](long double h) { return probe(polish(ref, ql + h * Vec3L::Unit(i), base.nearest)); },
        hq);
  }
  for (int j = 0; j < 5; ++j) {
    const long double step = j < 3 ? 1e-6L * ref.a[j] : 1e-6L;
    dtheta.col(j) = centralDifference(
        [&](long double h) {
          ReferenceShape s = ref;
          if (j < 3) s.a[j] += h;
          if (j == 3) s.e1 += h;
          if (j == 4) s.e2 += h;
          return probe(polish(s, ql, base.nearest));
        },
        step);
  }
  auto expectClose = [&](const char* what, const MatL& analytic, const MatL& numeric,
                         long double floor) {
    const long double e = relative(analytic, numeric, floor);
    const bool first_order = std::string(what).rfind("d_", 0) == 0;
    long double& w = first_order ? worst->gradient : worst->jacobians;
    w = std::max(w, e);
    EXPECT_LE(e, first_order ? gradient_bound : jacobian_bound) << what << "\nanalytic\n"
                                                                << analytic << "\nreference\n"
                                                                << numeric;
  };
  expectClose("d_query", toLong(got.d_query), dq.row(0).transpose(), 1);
  expectClose("d_shape (radii)", toLong(got.d_shape.template head<3>()),
              dtheta.row(0).head(3).transpose(), 1e-3L);
  expectClose("d_shape (exponents)", toLong(got.d_shape.template tail<2>()),
              dtheta.row(0).tail(2).transpose(), 1e-3L * size);
  expectClose("nearest_point_d_query", toLong(got.nearest_point_d_query), dq.middleRows(1, 3),
              1e-3L);
  expectClose("nearest_point_d_shape (radii)", toLong(got.nearest_point_d_shape.leftCols(3)),
              dtheta.block(1, 0, 3, 3), 1e-3L);
  expectClose("nearest_point_d_shape (exponents)", toLong(got.nearest_point_d_shape.rightCols(2)),
              dtheta.block(1, 3, 3, 2), 1e-3L * size);
  expectClose("normal_d_query", toLong(got.normal_d_query), dq.bottomRows(3), 1e-3L / size);
  expectClose("normal_d_shape (radii)", toLong(got.normal_d_shape.leftCols(3)),
              dtheta.block(4, 0, 3, 3), 1e-3L / size);
  expectClose("normal_d_shape (exponents)", toLong(got.normal_d_shape.rightCols(2)),
              dtheta.block(4, 3, 3, 2), 1e-3L);

  // The world frame: the pose's twist ξ = (ω, v), X_WS ← exp(ξ)·X_WS.
  const fcl::Transform3<S> x_ws = pose.cast<S>();
  const Vector3<S> q_w = x_ws * q;
  const PointDistanceDerivatives<S> world =
      pointDistanceDerivatives(shape, x_ws, q_w, DerivativeOrder::kJacobians);
  const Eigen::Transform<long double, 3, Eigen::Isometry> xl = x_ws.template cast<long double>();
  const Vec3L q_wl = q_w.template cast<long double>();
  MatL dpose(7, 6);
  for (int k = 0; k < 6; ++k) {
    const long double step = k < 3 ? 1e-6L : 1e-6L * size;
    dpose.col(k) = centralDifference(
        [&](long double h) {
          const Eigen::Transform<long double, 3, Eigen::Isometry> moved = twisted(xl, k, h);
          const PolishedResult r = polish(ref, moved.inverse() * q_wl, base.nearest);
          Probe p;
          p << r.distance, moved * r.nearest, moved.linear() * r.normal;
          return p;
        },
        step);
  }
  expectClose("d_pose (rotation)", toLong(world.d_pose.template head<3>()),
              dpose.row(0).head(3).transpose(), size);
  expectClose("d_pose (translation)", toLong(world.d_pose.template tail<3>()),
              dpose.row(0).tail(3).transpose(), 1);
  expectClose("nearest_point_d_pose", toLong(world.nearest_point_d_pose), dpose.middleRows(1, 3),
              1e-3L * size);
  expectClose("normal_d_pose", toLong(world.normal_d_pose), dpose.bottomRows(3), 1e-3L);
  const Eigen::Matrix<long double, 3, 3> r = xl.linear();
  expectClose("world nearest_point_d_query", toLong(world.nearest_point_d_query),
              r * toLong(got.nearest_point_d_query) * r.transpose(), 1e-3L);
  expectClose("d_shape (world)", toLong(world.d_shape), toLong(got.d_shape), 1e-3L);
}

Eigen::Isometry3d randomPose(std::mt19937& rng, double size) {
  std::uniform_real_distribution<double> unit(-1, 1);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.rotate(Eigen::Quaterniond(unit(rng), unit(rng), unit(rng), unit(rng)).normalized());
  pose.pretranslate(size * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
  return pose;
}

std::string formatError(long double e) {
  std::ostringstream out;
  out.precision(3);
  out << std::scientific << static_cast<double>(e);
  return out.str();
}

void recordWorst(const Worst& worst) {
  ::testing::Test::RecordProperty("worst_gradient_error", formatError(worst.gradient));
  ::testing::Test::RecordProperty("worst_jacobian_error", formatError(worst.jacobians));
}

/// Every derivative of `count` random configurations (randomConfigs(count, seed)) within the
/// bounds; the worst errors recorded as the test's properties.
template <typename S>
void checkRandomConfigs(int count, unsigned seed, double gradient_bound, double jacobian_bound) {
  std::mt19937 rng(seed);
  Worst worst;
  for (const Config& c : randomConfigs(count, seed)) {
    const double size = std::max({c.radii[0], c.radii[1], c.radii[2]});
    checkConfig<S>(c, randomPose(rng, size), gradient_bound, jacobian_bound, &worst);
  }
  recordWorst(worst);
}

TEST(PointDerivatives, MatchFiniteDifferencesOfTheReferenceInDouble) {
  checkRandomConfigs<double>(150, 5301, 1e-6, 1e-6);
}

TEST(PointDerivatives, MatchFiniteDifferencesOfTheReferenceInFloat) {
  // Float carries 7 digits, and the float solve's nearest point and normal are good to its
  // tolerance (1e-6 × size in Eq. 7): near the surface of a box-like shape the normal's
  // direction to about 1e-3; the Jacobians take that through the curvature (t^(2/ε − 2) beside
  // a crease). Measured on 600 configurations of another seed: 2.1e-3 and 4.2e-2.
  checkRandomConfigs<float>(60, 5302, 5e-3, 1e-1);
}

/// The analytic gradient of the distance without Jacobians is the one with them.
TEST(PointDerivatives, GradientAloneIsTheGradientOfTheFullQuery) {
  for (const Config& c : randomConfigs(30, 5303)) {
    const Superellipsoid<double> shape(c.radii[0], c.radii[1], c.radii[2], c.e1, c.e2);
    const auto g = pointDistanceDerivatives(shape, c.q, DerivativeOrder::kGradient);
    const auto j = pointDistanceDerivatives(shape, c.q, DerivativeOrder::kJacobians);
    EXPECT_EQ(g.d_shape, j.d_shape) << describe(c);
    EXPECT_EQ(g.d_pose, j.d_pose);
    EXPECT_FALSE(g.has_jacobians);
    EXPECT_TRUE(g.nearest_point_d_query.isZero(0));
  }
}

/// Configurations built to have several nearest points, or a nearest point whose Jacobian is
/// unbounded: the flag is set, and every number is finite.
TEST(PointDerivatives, FlagSetWhereTheDerivativeDoesNotExist) {
  struct Case {
    const char* what;
    std::array<double, 3> radii;
    double e1, e2;
    Eigen::Vector3d q;
  };
  const Case cases[] = {
      {"the centre of a sphere", {1, 1, 1}, 1, 1, {0, 0, 0}},
      {"the centre of a box-like shape", {1, 2, 3}, 0.3, 0.2, {0, 0, 0}},
      {"an ellipsoid's symmetry plane, nearest points off it", {3, 2, 1}, 1, 1, {0.5, 0.3, 0}},
      {"a box-like shape's diagonal plane (x = y)", {1, 1, 1.5}, 0.1, 0.1, {0.3, 0.3, 0.2}},
      {"a spheroid's axis, a ring of nearest points", {1, 1, 2}, 1, 0.5, {0, 0, 0.3}},
      {"the centre of curvature of an ellipsoid's tip", {2, 1, 1}, 1, 1, {1.5, 0, 0}},
      {"a pinched shape's symmetry plane", {1, 1, 1}, 1.7, 1.7, {0.2, 0.1, 0}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const Superellipsoid<double> shape(c.radii[0], c.radii[1], c.radii[2], c.e1, c.e2);
    const auto r = pointDistanceDerivatives(shape, c.q, DerivativeOrder::kJacobians);
    EXPECT_FALSE(r.differentiable);
    EXPECT_TRUE(r.d_shape.allFinite() && r.d_pose.allFinite() && r.d_query.allFinite());
    EXPECT_TRUE(r.nearest_point_d_query.allFinite() && r.nearest_point_d_shape.allFinite() &&
                r.normal_d_query.allFinite() && r.normal_d_shape.allFinite() &&
                r.nearest_point_d_pose.allFinite() && r.normal_d_pose.allFinite());
    // Moved off the tie (or the centre of curvature), the flag clears.
    const Eigen::Vector3d off = c.q + 1e-3 * Eigen::Vector3d(0.31, 0.17, 0.23);
    EXPECT_TRUE(pointDistanceDerivatives(shape, off, DerivativeOrder::kJacobians).differentiable)
        << "at " << off.transpose();
  }
}

/// On a crease (a coordinate plane of a level with ε > 1, where the curvature is unbounded) the
/// nearest point does not move across it: that column of its Jacobian is 0, the others match the
/// reference.
TEST(PointDerivatives, OnACreaseTheNearestPointStaysOnIt) {
  const Superellipsoid<double> shape(1.0, 0.7, 0.5, 1.6, 1.4);
  const ReferenceShape ref{{1.0, 0.7, 0.5}, 1.6, 1.4};
  for (const Eigen::Vector3d& q :
       {Eigen::Vector3d(1.3, 0.4, 0), Eigen::Vector3d(0, 0.6, 0.7), Eigen::Vector3d(0.9, 0, 0.5)}) {
    SCOPED_TRACE(q.transpose());
    const auto r = pointDistanceDerivatives(shape, q, DerivativeOrder::kJacobians);
    EXPECT_TRUE(r.differentiable);
    const int plane = q[0] == 0 ? 0 : q[1] == 0 ? 1 : 2;
    EXPECT_LE(r.nearest_point_d_query.col(plane).norm(), 1e-12);
    const Vec3L ql = q.cast<long double>();
    const PolishedResult base = polishedReference(ref, ql);
    ASSERT_TRUE(base.ok);
    for (int i = 0; i < 3; ++i) {
      if (i == plane) continue;
      const Probe fd = centralDifference(
          [&](long double h) { return probe(polish(ref, ql + h * Vec3L::Unit(i), base.nearest)); },
          1e-6L);
      EXPECT_LE((r.nearest_point_d_query.col(i).cast<long double>() - fd.segment<3>(1)).norm(),
                1e-6L * std::max(1.0L, fd.segment<3>(1).norm()));
      EXPECT_LE((r.normal_d_query.col(i).cast<long double>() - fd.tail<3>()).norm(),
                1e-6L * std::max(1.0L, fd.tail<3>().norm()));
    }
  }
}

/// Awkward queries (the centre and just beside it, far away, on the surface and its creases,
/// the exponents' and radii's extremes): every number is finite, in float and double.
template <typename S>
void expectFiniteEverywhere() {
  const S big = std::is_same<S, float>::value ? S(1e5) : S(1e12);
  const S tiny = std::is_same<S, float>::value ? S(1e-6) : S(1e-200);
  for (const S e1 : {S(0.02), S(0.5), S(1), S(1.5), S(1.98)}) {
    for (const S e2 : {S(0.02), S(1), S(1.98)}) {
      for (const Vector3<S>& a :
           {Vector3<S>(1, 1, 1), Vector3<S>(100, 1, 3), Vector3<S>(S(1e-3), S(2e-3), S(1e-3))}) {
        const Superellipsoid<S> shape(a, e1, e2);
        for (const Vector3<S>& q :
             {Vector3<S>(0, 0, 0), Vector3<S>(tiny, 0, 0), Vector3<S>(big, -big, big),
              Vector3<S>(a[0], 0, 0), Vector3<S>(0, 0, -a[2]), Vector3<S>(a[0], a[1], 0),
              Vector3<S>(S(0.5) * a[0], 0, S(0.5) * a[2]), Vector3<S>(0, S(2) * a[1], 0)}) {
          const auto r = pointDistanceDerivatives(shape, q, DerivativeOrder::kJacobians);
          EXPECT_TRUE(r.d_shape.allFinite() && r.d_pose.allFinite() && r.d_query.allFinite() &&
                      r.nearest_point_d_query.allFinite() && r.nearest_point_d_shape.allFinite() &&
                      r.normal_d_query.allFinite() && r.normal_d_shape.allFinite() &&
                      r.nearest_point_d_pose.allFinite() && r.normal_d_pose.allFinite())
              << test::describe(shape) << " at " << q.transpose();
        }
      }
    }
  }
}

TEST(PointDerivatives, FiniteEverywhereInFloat) { expectFiniteEverywhere<float>(); }

// A share of a level below the format's range (docs/hardening.md → "Findings", 32): on a large
// box-like shape in float, the nearest point's normal has a subnormal component, so one level's
// share over the other's rounds to 0 while the share itself is not 0; its s·ln s is 0, not NaN.
TEST(PointDerivatives, ShareBelowTheFormatsRangeInFloat) {
  const Superellipsoid<float> shape(1e6f, 9e5f, 8e5f, 0.1f, 0.3f);
  const Vector3<float> q(304871.5f, -132820.875f, -0.125f);
  for (const DerivativeOrder order : {DerivativeOrder::kGradient, DerivativeOrder::kJacobians}) {
    const auto r = pointDistanceDerivatives(shape, q, order);
    EXPECT_TRUE(r.d_shape.allFinite()) << r.d_shape.transpose();
  }
  Matrix3X<float> points(3, 1);
  points.col(0) = q;
  for (const bool vectorize : {false, true}) {
    BatchOptions<float> options;
    options.vectorize = vectorize;
    BatchDerivativesResult<float> rows;
    batchDistanceDerivatives(shape, fcl::Transform3f::Identity(), points, rows, options);
    EXPECT_TRUE(rows.d_shape.allFinite()) << "vectorize " << vectorize << ": " << rows.d_shape;
  }
}
TEST(PointDerivatives, FiniteEverywhereInDouble) { expectFiniteEverywhere<double>(); }

}  // namespace
}  // namespace test
}  // namespace fcl_superellipsoid
