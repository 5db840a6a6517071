// The superellipsoid against a point, a segment or a disc apart from it
// (src/narrowphase/feature_newton.h), against constructions
// (test_support/pair_construction.h): a surface point a with outward normal u from the
// parametric form in long double, and features placed on the plane u·x = u·a + d, which
// separates them from the shape; where a feature touches that plane only at p = a + d·u, the
// distance is d and the witnesses are a and p (the shape is strictly convex). One segment per
// branch of segmentApart: of no length, in the plane through p (p inside the segment), leaving the
// plane from p (p an end, the line missing the shape), the same with the line pointing into the
// shape (the line meets it), and a segment through the shape (nothing found); segmentInteriorApart
// on the first two (the answer, then nothing); a disc whose rim touches the plane at p.

#include <gtest/gtest.h>

#include <random>

#include "narrowphase/feature_newton.h"
#include "pair_construction.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

using test::LD;
using test::V3;

struct Case {
  Superellipsoid<double> shape;
  fcl::Transform3<double> X_WA;
  V3 a, u;
};

Case makeCase(std::mt19937& rng) {
  const test::Construction c = test::constructShape(rng, 1);
  return {
      Superellipsoid<double>(c.shape.radii.cast<double>(), double(c.shape.e1), double(c.shape.e2)),
      c.X_WA, c.a, c.u};
}

/// The hit's distance (to 1e-12 × size), witnesses (1e-10 × size) and normal (1e-8 rad) against
/// the construction's.
void expectHit(const std::optional<PairHit<double>>& hit, const Case& c, LD d, const V3& p,
               const char* what) {
  ASSERT_TRUE(hit.has_value()) << what << " of " << c.shape;
  const double size = c.shape.size();
  EXPECT_NEAR(hit->distance, double(d), 1e-12 * size) << what << " of " << c.shape;
  EXPECT_LT(double((hit->on_shape.cast<LD>() - c.a).norm()), 1e-10 * size)
      << what << " of " << c.shape;
  EXPECT_LT(double((hit->on_other.cast<LD>() - p).norm()), 1e-10 * size)
      << what << " of " << c.shape;
  EXPECT_LT(double((hit->normal.cast<LD>() - c.u).norm()), 1e-8) << what << " of " << c.shape;
}

TEST(FeatureNewton, PointsAndSegmentsAgainstTheConstruction) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> log_d(-3, 0), half(0.05, 1.0), tilt(0.2, 1.2);
  for (int trial = 0; trial < 400; ++trial) {
    const Case c = makeCase(rng);
    const LD d = std::pow(LD(10), LD(log_d(rng))) * LD(c.shape.size());
    const V3 p = c.a + d * c.u;
    const V3 t = c.u.unitOrthogonal();
    const V3 t2 = c.u.cross(t);
    const V3 side = (t * LD(std::cos(trial)) + t2 * LD(std::sin(trial))).normalized();
    const Vector3<double> start = (p - c.X_WA.translation().cast<LD>()).cast<double>();
    // The point itself.
    expectHit(pointApart(c.shape, c.X_WA, Vector3<double>(p.cast<double>()), start), c, d, p,
              "point");
    expectHit(pointApart(c.shape, c.X_WA, Vector3<double>(p.cast<double>()), noHint<double>()), c,
              d, p, "point, cold");
    // A segment of no length: the point.
    expectHit(segmentApart(c.shape, c.X_WA, Vector3<double>(p.cast<double>()),
                           Vector3<double>(p.cast<double>()), start),
              c, d, p, "segment of no length");
    // A segment in the plane, p between its ends.
    const LD h = LD(half(rng)) * LD(c.shape.size());
    const LD f = LD(std::uniform_real_distribution<double>(-0.8, 0.8)(rng));
    const Vector3<double> e0 = (p - (1 + f) * h * side).cast<double>();
    const Vector3<double> e1 = (p + (1 - f) * h * side).cast<double>();
    expectHit(segmentApart(c.shape, c.X_WA, e0, e1, start), c, d, p, "segment in the plane");
    expectHit(segmentInteriorApart(c.shape, c.X_WA, e0, e1, start), c, d, p,
              "segment in the plane, its interior alone");
    // A segment from p leaving the plane, either end first; the line behind it may miss or meet
    // the shape.
    const LD angle = LD(tilt(rng));
    const V3 away = (std::cos(angle) * side + std::sin(angle) * c.u).normalized();
    const V3 q = p + 2 * h * away;
    expectHit(segmentApart(c.shape, c.X_WA, Vector3<double>(p.cast<double>()),
                           Vector3<double>(q.cast<double>()), start),
              c, d, p, "segment leaving the plane");
    expectHit(segmentApart(c.shape, c.X_WA, Vector3<double>(q.cast<double>()),
                           Vector3<double>(p.cast<double>()), start),
              c, d, p, "segment leaving the plane, reversed");
    // Its interior alone: the nearest point is an end, so nothing (or that end, to rounding).
    const std::optional<PairHit<double>> interior =
        segmentInteriorApart(c.shape, c.X_WA, Vector3<double>(p.cast<double>()),
                             Vector3<double>(q.cast<double>()), start);
    EXPECT_FALSE(interior.has_value() &&
                 (interior->on_other - p.cast<double>()).norm() > 1e-9 * c.shape.size())
        << "the interior of a segment leaving the plane at its end gave a point "
        << (interior->on_other - p.cast<double>()).norm() << " from that end";
    // Along the normal: its line goes through the shape.
    const V3 r = p + 2 * h * c.u;
    expectHit(segmentApart(c.shape, c.X_WA, Vector3<double>(r.cast<double>()),
                           Vector3<double>(p.cast<double>()), start),
              c, d, p, "segment along the normal");
    // A disc whose rim touches the plane at p, tilted away from the shape.
    const LD phi = LD(tilt(rng));
    const V3 axis = (std::cos(phi) * c.u + std::sin(phi) * side).normalized();
    const V3 in_plane = (c.u - c.u.dot(axis) * axis).normalized();
    const V3 centre = p + h * in_plane;
    // Started as the pairs start it, from GJK's normal: near the answer (a disc's support has a
    // kink along its axis, where a search from far away can stop).
    const V3 near_normal = (c.u + LD(0.05) * side + LD(0.03) * t2).normalized();
    expectHit(discApart(c.shape, c.X_WA, Vector3<double>(centre.cast<double>()),
                        Vector3<double>(axis.cast<double>()), double(h),
                        Vector3<double>(near_normal.cast<double>())),
              c, d, p, "disc");
    // Through the shape: nothing, or an answer no farther than touching.
    const V3 inside = c.a - LD(0.01) * LD(c.shape.size()) * c.u;
    const std::optional<PairHit<double>> through =
        segmentApart(c.shape, c.X_WA, Vector3<double>(r.cast<double>()),
                     Vector3<double>((2 * inside - r).cast<double>()), start);
    EXPECT_FALSE(through.has_value() && through->distance > 1e-12 * c.shape.size())
        << "a segment through " << c.shape << " found apart by " << through->distance;
  }
}

}  // namespace
}  // namespace detail
}  // namespace fcl_superellipsoid
