// The regions of a mesh's vertices and ridges that poke into the shape where no face region
// covers them (narrowphase/mesh_features.h), against constructions on a unit sphere posed at
// random: a steep pyramid's apex is one place, the apex itself, with the sphere's normal there;
// a steep tent's ridge is a region along the ridge, from its deepest place to where the sphere
// reaches within the tolerance of it; a covered facet's vertices and edges make none, nor do a
// flat continuation's edges, nor features farther than the tolerance.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "narrowphase/mesh_features.h"
#include "narrowphase/region_bodies.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

/// The facets of the triangles over the vertices, posed by X, normals towards the sphere's
/// centre c (as the mesh's regions take them).
template <typename S>
std::vector<Facet<S>> facetsOf(const std::vector<Vector3<S>>& vertices,
                               const std::vector<std::array<int, 3>>& triangles,
                               const fcl::Transform3<S>& X, const Vector3<S>& c) {
  std::vector<Facet<S>> facets;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    Facet<S> f{int(t), triangles[t], {}, {}};
    for (int k = 0; k < 3; ++k) f.p[k] = X * vertices[std::size_t(triangles[t][k])];
    f.normal = (f.p[1] - f.p[0]).cross(f.p[2] - f.p[0]).normalized();
    if (f.normal.dot(c - f.p[0]) < S(0)) f.normal = -f.normal;
    facets.push_back(f);
  }
  return facets;
}

/// A steep pyramid's apex at (0, 0, −h) pointing up, its four faces falling 2 for 1.
template <typename S>
std::vector<Vector3<S>> pyramid(double h) {
  return {Vector3<S>(S(0), S(0), S(-h)), Vector3<S>(S(-1), S(-1), S(-h - 2)),
          Vector3<S>(S(1), S(-1), S(-h - 2)), Vector3<S>(S(1), S(1), S(-h - 2)),
          Vector3<S>(S(-1), S(1), S(-h - 2))};
}
const std::vector<std::array<int, 3>> kPyramidTriangles = {
    {0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}};

/// The region's normal straight down in the sphere's frame (X_SW: world to it), and its distance
/// −δ.
template <typename S>
void expectStraightDownAndDeep(const ContactManifold<S>& m, const fcl::Transform3<double>& X_SW,
                               double delta, double rounding) {
  EXPECT_LE((X_SW.linear() * m.normal.template cast<double>() + Eigen::Vector3d::UnitZ()).norm(),
            rounding);
  EXPECT_NEAR(double(m.distance), -delta, rounding);
}

/// Facet `i` of `count` in a region of that distance and normal.
template <typename S>
std::vector<FaceCover<S>> coveredBy(std::size_t count, std::size_t i, S distance,
                                    const Vector3<S>& normal) {
  std::vector<FaceCover<S>> cover(count);
  cover[i] = {true, distance, normal};
  return cover;
}

template <typename S>
class MeshFeatures : public ::testing::Test {};
TYPED_TEST_SUITE(MeshFeatures, test::Scalars);

TYPED_TEST(MeshFeatures, AnApexInsideIsOnePlaceWithTheShapesNormal) {
  using S = TypeParam;
  const double rounding = std::is_same<S, float>::value ? 1e-5 : 1e-12;
  std::mt19937 rng(3301);
  const Superellipsoid<S> sphere(S(1), S(1), S(1), S(1), S(1));
  const S tolerance = S(1e-3);
  for (const double delta : {1e-4, 0.01, 0.2}) {
    const double h = 1 - delta;
    const std::vector<Vector3<S>> vertices = pyramid<S>(h);
    for (int trial = 0; trial < 4; ++trial) {
      SCOPED_TRACE(::testing::Message() << "delta " << delta << " trial " << trial);
      const fcl::Transform3<S> X = test::randomPose<S>(rng, S(2));
      const auto body = regionBody(sphere, X);
      const std::vector<Facet<S>> facets =
          facetsOf(vertices, kPyramidTriangles, X, Vector3<S>(X.translation()));
      const std::vector<FeatureRegion<S>> regions =
          featureRegions(sphere, X, *body, facets, edgesOf(facets),
                         std::vector<FaceCover<S>>(facets.size()), tolerance, ManifoldOptions<S>{});
      ASSERT_EQ(regions.size(), 1u);
      const ContactManifold<S>& m = regions[0].region;
      const fcl::Transform3<double> X_SW = X.template cast<double>().inverse();
      expectStraightDownAndDeep(m, X_SW, delta, rounding);
      ASSERT_EQ(m.points.size(), 1u);
      ASSERT_EQ(m.polygon.size(), 1u);
      const ManifoldPoint<S>& p = m.points[0];
      EXPECT_LE((X_SW * p.on_other.template cast<double>() - Eigen::Vector3d(0, 0, -h)).norm(),
                rounding);
      EXPECT_LE((X_SW * p.on_shape.template cast<double>() - Eigen::Vector3d(0, 0, -1)).norm(),
                rounding);
      EXPECT_NEAR(double(p.depth), delta, rounding);
      EXPECT_LE((X_SW * p.position.template cast<double>() - Eigen::Vector3d(0, 0, -1 + delta / 2))
                    .norm(),
                rounding);
      EXPECT_GE(regions[0].triangle, 0);
      EXPECT_LT(regions[0].triangle, 4);
      // Held by a region of one of the apex's facets that overlaps as deep as the apex: none.
      // Not by one that does not overlap, nor by one shallower by more than the tolerance.
      const Vector3<S> down = X.linear() * -Vector3<S>::UnitZ();
      const auto count = [&](double distance) {
        return featureRegions(sphere, X, *body, facets, edgesOf(facets),
                              coveredBy(facets.size(), 1, S(distance), down), tolerance,
                              ManifoldOptions<S>{})
            .size();
      };
      EXPECT_EQ(count(-delta), 0u);
      EXPECT_EQ(count(1e-4), 1u);
      if (delta > 2 * double(tolerance)) EXPECT_EQ(count(-delta + 2 * double(tolerance)), 1u);
    }
  }
  // Apart by more than the tolerance: none; within it (apart by half of it): the place, apart.
  for (const double gap : {2e-3, 5e-4}) {
    const double h = 1 + gap;
    const std::vector<Vector3<S>> vertices = pyramid<S>(h);
    const fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
    const auto body = regionBody(sphere, X);
    const std::vector<Facet<S>> facets = facetsOf(
        vertices, std::vector<std::array<int, 3>>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}}, X,
        Vector3<S>(X.translation()));
    const std::vector<FeatureRegion<S>> regions =
        featureRegions(sphere, X, *body, facets, edgesOf(facets),
                       std::vector<FaceCover<S>>(facets.size()), tolerance, ManifoldOptions<S>{});
    if (gap > double(tolerance)) {
      EXPECT_TRUE(regions.empty());
    } else {
      ASSERT_EQ(regions.size(), 1u);
      EXPECT_NEAR(double(regions[0].region.distance), gap, rounding);
      EXPECT_NEAR(double(regions[0].region.points[0].depth), -gap, rounding);
    }
  }
}

TYPED_TEST(MeshFeatures, ARidgeInsideIsARegionAlongItToTheTolerance) {
  using S = TypeParam;
  const double rounding = std::is_same<S, float>::value ? 1e-5 : 1e-12;
  std::mt19937 rng(3302);
  const Superellipsoid<S> sphere(S(1), S(1), S(1), S(1), S(1));
  for (const double delta : {0.01, 0.2}) {
    const double h = 1 - delta;
    // The ridge along x at z = −h from x = −3 to x = 3 (its ends far outside), its faces falling
    // 2 for 1 on either side; each face's far side is split by a diagonal (a flat
    // continuation, not a ridge).
    const std::vector<Vector3<S>> vertices = {
        Vector3<S>(S(-3), S(0), S(-h)),      Vector3<S>(S(3), S(0), S(-h)),
        Vector3<S>(S(-3), S(-1), S(-h - 2)), Vector3<S>(S(3), S(-1), S(-h - 2)),
        Vector3<S>(S(-3), S(1), S(-h - 2)),  Vector3<S>(S(3), S(1), S(-h - 2))};
    const std::vector<std::array<int, 3>> tent_triangles = {
        {0, 1, 3}, {0, 3, 2}, {0, 4, 5}, {0, 5, 1}};
    for (int trial = 0; trial < 4; ++trial) {
      SCOPED_TRACE(::testing::Message() << "delta " << delta << " trial " << trial);
      const fcl::Transform3<S> X = test::randomPose<S>(rng, S(2));
      const auto body = regionBody(sphere, X);
      const std::vector<Facet<S>> facets =
          facetsOf(vertices, tent_triangles, X, Vector3<S>(X.translation()));
      for (const S tolerance : {S(1e-3), S(0.05)}) {
        for (const int max_points : {1, 2, 4}) {
          ManifoldOptions<S> options;
          options.max_points = max_points;
          const std::vector<FeatureRegion<S>> regions =
              featureRegions(sphere, X, *body, facets, edgesOf(facets),
                             std::vector<FaceCover<S>>(facets.size()), tolerance, options);
          ASSERT_EQ(regions.size(), 1u);
          const ContactManifold<S>& m = regions[0].region;
          const fcl::Transform3<double> X_SW = X.template cast<double>().inverse();
          expectStraightDownAndDeep(m, X_SW, delta, rounding);
          ASSERT_EQ(m.points.size(), std::size_t(std::min(max_points, 3)));
          ASSERT_EQ(m.polygon.size(), 3u);
          EXPECT_NEAR(double(m.points[0].depth), delta, rounding);
          // The ends: on the ridge, within the tolerance t along it inside the exact ends
          // x = ±√(1 − (h − t)²), where the sphere's surface over the ridge is t above it.
          const double t = double(tolerance);
          const double end = std::sqrt(1 - (h - t) * (h - t));
          const Eigen::Vector3d first = X_SW * m.polygon.front().on_other.template cast<double>();
          const Eigen::Vector3d last = X_SW * m.polygon.back().on_other.template cast<double>();
          EXPECT_LT(first.x() * last.x(), 0);
          for (const ManifoldPoint<S>* p : {&m.polygon.front(), &m.polygon.back()}) {
            const Eigen::Vector3d o = X_SW * p->on_other.template cast<double>();
            const Eigen::Vector3d s = X_SW * p->on_shape.template cast<double>();
            EXPECT_NEAR(o.y(), 0, rounding);
            EXPECT_NEAR(o.z(), -h, rounding);
            EXPECT_LE(std::abs(o.x()), end + rounding);
            EXPECT_GE(std::abs(o.x()), end - t - rounding);
            EXPECT_NEAR(s.norm(), 1, rounding);
            EXPECT_NEAR(double(p->depth), -(s.z() + h), rounding);
            EXPECT_GE(double(p->depth), -t - rounding);
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace detail
}  // namespace fcl_superellipsoid
