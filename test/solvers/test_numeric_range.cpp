// The numeric range (NumericRange<S>, docs/hardening.md → "Numeric range"): shapes at both ends
// of the radius range and at the aspect-ratio limit answer as exactly as a unit shape; query
// points from the smallest subnormal to the largest finite value give correct, finite answers,
// through the single and the batched queries. Ground truth: the independent long-double
// reference (reference_distance.h) scaled by construction, and closed forms on the axes.

#include <limits>

#include "fcl_superellipsoid/batch_distance.h"
#include "fcl_superellipsoid/point_distance.h"
#include "reference_distance.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

template <typename S>
class NumericRangeTest : public ::testing::Test {};
TYPED_TEST_SUITE(NumericRangeTest, test::Scalars);

const DistanceMethod kMethods[] = {DistanceMethod::kRadial, DistanceMethod::kPaper,
                                   DistanceMethod::kExact};

/// Radii (4, 2, 1) × scale: both ends of the range reachable with power-of-two factors.
template <typename S>
Superellipsoid<S> scaled(S scale, S e1, S e2) {
  return Superellipsoid<S>(S(4) * scale, S(2) * scale, scale, e1, e2);
}

// At each end of the radius range the Exact answer is the unit shape's reference answer, scaled:
// inside, near the surface and outside, for a rounded, a box-like and a pinched shape.
TYPED_TEST(NumericRangeTest, BothEndsOfTheRadiusRangeAnswerLikeTheUnitShape) {
  using S = TypeParam;
  using Range = NumericRange<S>;
  const std::array<std::array<double, 2>, 3> exponents = {{{1, 1}, {0.1, 0.3}, {1.7, 1.9}}};
  const std::array<std::array<double, 3>, 5> unit_points = {
      {{0.5, 0.3, 0.2}, {3.1, 1.2, 0.4}, {-4.5, 0.1, 0.05}, {1.0, -2.5, 1.5}, {0.2, 0.1, -0.9}}};
  for (S scale : {Range::kMinRadius, Range::kMaxRadius / S(4)}) {
    for (const auto& e : exponents) {
      const Superellipsoid<S> shape = scaled<S>(scale, S(e[0]), S(e[1]));
      const test::ReferenceDistance reference({4, 2, 1}, e[0], e[1]);
      for (const auto& q : unit_points) {
        const Vector3<S> p = scale * Vector3<S>(S(q[0]), S(q[1]), S(q[2]));
        SCOPED_TRACE(test::describe(shape) + " at (" + std::to_string(q[0]) + ", " +
                     std::to_string(q[1]) + ", " + std::to_string(q[2]) + ") x scale");
        // The reference at the point as S rounded it, brought back to unit scale.
        const long double truth = reference
                                      .query({p[0] / (long double)scale, p[1] / (long double)scale,
                                              p[2] / (long double)scale})
                                      .distance;
        for (DistanceMethod m : kMethods) {
          const auto r = pointDistance(shape, p, DistanceOptions<S>::of(m));
          ASSERT_TRUE(std::isfinite(r.distance) && r.nearest_point.allFinite() &&
                      r.normal.allFinite())
              << toString(m);
          if (m != DistanceMethod::kExact) continue;
          EXPECT_TRUE(r.converged);
          EXPECT_NEAR(double(r.distance / scale), double(truth),
                      4 * test::exactTarget<S>(e[0], e[1]));
        }
      }
    }
  }
}

// At the aspect-ratio limit: points on the axes, where the nearest point is the axis tip by
// construction (the tip's normal is the axis; a convex shape lies behind its tangent plane).
TYPED_TEST(NumericRangeTest, TheAspectRatioLimitAnswersOnTheAxes) {
  using S = TypeParam;
  const S thin = S(4) / NumericRange<S>::kMaxAspectRatio;
  for (const auto& e : std::vector<std::array<double, 2>>{{1, 1}, {0.3, 0.5}, {1.5, 1.5}}) {
    const Superellipsoid<S> shape(4, 2, thin, S(e[0]), S(e[1]));
    SCOPED_TRACE(test::describe(shape));
    for (S t : {S(1.5), S(3), S(100)}) {
      for (int axis = 0; axis < 3; ++axis) {
        Vector3<S> p = Vector3<S>::Zero();
        p[axis] = t * shape.radii()[axis];
        const auto r = pointDistance(shape, p);
        EXPECT_TRUE(r.converged);
        EXPECT_NEAR(double(r.distance), double((t - 1) * shape.radii()[axis]),
                    double(64 * std::numeric_limits<S>::epsilon() * t * shape.radii()[axis]) +
                        1e-9 * shape.size())
            << "axis " << axis << ", t " << t;
      }
    }
  }
}

// Far points, up to the largest coordinate a query may have (a quarter of the largest finite
// value): every method is finite and converged; on the axes the distance is |p| − a_i to rounding;
// off the axes it lies between |p| − size and |p| − (smallest radius), and it grows one for one
// with |p| across the far-point switch.
TYPED_TEST(NumericRangeTest, FarPointsUpToTheLargestCoordinate) {
  using S = TypeParam;
  const S eps = std::numeric_limits<S>::epsilon();
  for (S scale : {S(1), NumericRange<S>::kMaxRadius / S(4), NumericRange<S>::kMinRadius}) {
    const Superellipsoid<S> shape = scaled<S>(scale, S(0.4), S(1.3));
    const S size = shape.size();
    const S switch_at = std::ldexp(size, std::numeric_limits<S>::digits);
    // Up to the largest coordinate a query may have: a quarter of the largest finite value.
    std::vector<S> magnitudes = {switch_at / 4,
                                 switch_at / 2,
                                 switch_at * 2,
                                 switch_at * 64,
                                 std::numeric_limits<S>::max() / 8,
                                 std::numeric_limits<S>::max() / 4};
    for (S t : magnitudes) {
      for (const Vector3<S>& dir : {Vector3<S>(1, 0, 0), Vector3<S>(0, -1, 0), Vector3<S>(0, 0, 1),
                                    Vector3<S>(S(0.6), S(-0.48), S(0.64))}) {
        const Vector3<S> p = t * dir;  // |dir| = 1 (the last one to rounding)
        ASSERT_TRUE(p.allFinite());
        for (DistanceMethod m : kMethods) {
          SCOPED_TRACE(std::string(toString(m)) + ", |p| " + std::to_string(double(t)) +
                       ", scale " + std::to_string(double(scale)));
          const auto r = pointDistance(shape, p, DistanceOptions<S>::of(m));
          ASSERT_TRUE(std::isfinite(r.distance) && r.nearest_point.allFinite() &&
                      r.normal.allFinite() && std::isfinite(r.error));
          // Radial and Paper are approximations nearer in; beyond the switch every method
          // gives the far-point answer.
          if (m == DistanceMethod::kExact || t > switch_at) EXPECT_TRUE(r.converged);
          EXPECT_NEAR(double(r.normal.norm()), 1.0, 1e-6);
          const long double length =
              std::hypot((long double)p[0], (long double)p[1], (long double)p[2]);
          const long double slack = 16 * eps * length;
          const int axis =
              dir.cwiseAbs().maxCoeff() == S(1)
                  ? int(std::distance(
                        dir.data(),
                        std::max_element(dir.data(), dir.data() + 3,
                                         [](S a, S b) { return std::abs(a) < std::abs(b); })))
                  : -1;
          if (axis >= 0) {
            EXPECT_NEAR(double(r.distance), double(length - shape.radii()[axis]), double(slack));
          } else {
            EXPECT_GE(r.distance, S(length - size - slack));
            EXPECT_LE(r.distance, S(length - shape.radii().minCoeff() + slack));
          }
        }
      }
    }
    // Across the switch: the distance grows as |p| does (to rounding of |p|), no jump.
    const Vector3<S> dir = Vector3<S>(S(0.6), S(-0.48), S(0.64));
    const S below = switch_at * S(0.999), above = switch_at * S(1.001);
    const auto rb = pointDistance(shape, Vector3<S>(below * dir));
    const auto ra = pointDistance(shape, Vector3<S>(above * dir));
    EXPECT_TRUE(rb.converged && ra.converged);
    EXPECT_NEAR(double(ra.distance - rb.distance), double(above - below), double(64 * eps * above));
  }
}

// Near the centre, down to the smallest subnormal coordinate: the centre's answer, on the
// surface. (Found by fuzz_point_query: a float query at (0, 1e-45, 0) on a shape of radius 2.016
// came back with a "surface" point at radius 2, its direction lost to subnormal rounding.)
TYPED_TEST(NumericRangeTest, TinyPointsNearTheCentre) {
  using S = TypeParam;
  for (const Superellipsoid<S>& shape :
       {Superellipsoid<S>(S(1), S(0.7), S(0.5), S(0.8), S(0.6)),
        Superellipsoid<S>(S(2.01639104), S(2.01639104), S(2.01639104), S(0.196078435),
                          S(0.196078435))}) {
    const auto centre = pointDistance(shape, Vector3<S>::Zero());
    for (S t : {std::numeric_limits<S>::denorm_min(), std::numeric_limits<S>::min(), S(1e-30)}) {
      for (const Vector3<S>& p :
           {Vector3<S>(t, t, -t), Vector3<S>(0, t, 0), Vector3<S>(-t, 0, 0)}) {
        for (DistanceMethod m : kMethods) {
          const auto r = pointDistance(shape, p, DistanceOptions<S>::of(m));
          ASSERT_TRUE(std::isfinite(r.distance) && r.nearest_point.allFinite()) << toString(m);
          EXPECT_NEAR(double(test::referenceGauge(shape, r.nearest_point)), 1.0,
                      4 * test::evalTolerance<S>())
              << toString(m);
          EXPECT_NEAR(double(r.distance), double(centre.distance),
                      4 * test::exactTarget<S>(0.5, 0.5) * shape.size())
              << toString(m);
        }
      }
    }
  }
}

// The batched queries route far vertices to the far-point answer too: finite, equal to the
// single query, and the within-margin cull does not overflow.
TYPED_TEST(NumericRangeTest, BatchedQueriesWithFarVertices) {
  using S = TypeParam;
  const Superellipsoid<S> shape(S(1), S(0.7), S(0.5), S(0.4), S(1.3));
  const S huge = std::numeric_limits<S>::max() / 4;  // the largest coordinate allowed
  Matrix3X<S> p(3, 6);
  p << S(0.3), huge, S(2), -huge, S(1e3), S(0),  //
      S(0.1), S(0), S(0), huge, S(0), S(0.2),    //
      S(0), S(1), S(0), S(0), huge, S(-0.1);
  for (bool vectorize : {true, false}) {
    BatchOptions<S> options;
    options.vectorize = vectorize;
    BatchDistanceResult<S> batch;
    batchDistance(shape, fcl::Transform3<S>::Identity(), p, batch, options);
    for (Eigen::Index i = 0; i < p.cols(); ++i) {
      const auto single = pointDistance(shape, Vector3<S>(p.col(i)));
      ASSERT_TRUE(std::isfinite(batch.distance[i])) << "vertex " << i;
      EXPECT_NEAR(double(batch.distance[i]), double(single.distance),
                  1e-9 * double(shape.size()) + 8 * double(std::numeric_limits<S>::epsilon()) *
                                                    double(std::abs(single.distance)))
          << "vertex " << i;
    }
    // A margin as large as the far vertices' distance takes them in; the cull must not
    // overflow into "infinitely far".
    const auto within = verticesWithinMargin(shape, fcl::Transform3<S>::Identity(), p,
                                             std::numeric_limits<S>::max(), options);
    EXPECT_EQ(within.size(), std::size_t(p.cols()));
  }
}

}  // namespace
}  // namespace fcl_superellipsoid
