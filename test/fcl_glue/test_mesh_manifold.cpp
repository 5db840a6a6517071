// A triangle mesh's contact regions (contactManifolds), against constructions: a superellipsoid
// pressed into a tessellated floor has the cross-section at that depth as its one region, however
// the floor is cut into triangles and whatever its BV type; hung over the floor's edge, the part
// of the section over the floor; in a corner, one region per face; on a table's edge, the top's
// region and none from the side; the regions turn with the pair; where the mesh is a plane they
// are the halfspace's; FCL's collide with MeshContacts::kRegions gives the regions' places.

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/geometric_shape_to_BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "fcl_superellipsoid/contact_manifold.h"
#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_superellipsoid/tessellation.h"
#include "reference_distance.h"
#include "region_construction.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

using test::halfWidth;
using test::polygonArea;
using test::randomPose;
using test::referenceGauge;
using test::sectionScale;
using test::superellipseArea;

/// Triangles of a flat grid in the plane z = 0 over [x0, x1] × [y0, y1], nx × ny cells of two
/// triangles each (the diagonals alternate), in a BVHModel of the BV type `kind` (0..5).
template <typename S>
std::shared_ptr<fcl::CollisionGeometry<S>> grid(double x0, double x1, double y0, double y1, int nx,
                                                int ny, int kind) {
  std::vector<Vector3<S>> vertices;
  std::vector<fcl::Triangle> triangles;
  for (int i = 0; i <= nx; ++i) {
    for (int j = 0; j <= ny; ++j) {
      vertices.emplace_back(S(x0 + (x1 - x0) * i / nx), S(y0 + (y1 - y0) * j / ny), S(0));
    }
  }
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      const int a = i * (ny + 1) + j, b = a + 1, c = a + ny + 1, d = c + 1;
      if ((i + j) % 2 == 0) {
        triangles.emplace_back(a, c, d);
        triangles.emplace_back(a, d, b);
      } else {
        triangles.emplace_back(a, c, b);
        triangles.emplace_back(b, c, d);
      }
    }
  }
  const auto build = [&](auto model) {
    model->beginModel();
    model->addSubModel(vertices, triangles);
    model->endModel();
    return std::shared_ptr<fcl::CollisionGeometry<S>>(model);
  };
  switch (kind % 6) {
    case 0:
      return build(std::make_shared<fcl::BVHModel<fcl::OBBRSS<S>>>());
    case 1:
      return build(std::make_shared<fcl::BVHModel<fcl::AABB<S>>>());
    case 2:
      return build(std::make_shared<fcl::BVHModel<fcl::RSS<S>>>());
    case 3:
      return build(std::make_shared<fcl::BVHModel<fcl::KDOP<S, 24>>>());
    case 4:
      return build(std::make_shared<fcl::BVHModel<fcl::OBB<S>>>());
    default:
      return build(std::make_shared<fcl::BVHModel<fcl::kIOS<S>>>());
  }
}

/// The area of the part x ≤ x_max of |x/a|^n + |y/b|^n ≤ 1 (midpoint rule over exact widths).
double sectionAreaUpTo(double a, double b, double n, double x_max) {
  const double hi = std::min(a, x_max);
  if (hi <= -a) return 0;
  const int steps = 200000;
  const double dx = (hi + a) / steps;
  double area = 0;
  for (int i = 0; i < steps; ++i) area += 2 * halfWidth(a, b, n, -a + (i + 0.5) * dx) * dx;
  return area;
}

/// The height of the shape's top surface above (x, y) in its frame: G = 1 solved for z ≥ 0.
double topHeight(double a1, double a2, double a3, double e1, double e2, double x, double y) {
  const double inner =
      std::pow(std::pow(std::abs(x / a1), 2 / e1) + std::pow(std::abs(y / a2), 2 / e1), e1 / e2);
  return inner >= 1 ? 0 : a3 * std::pow(1 - inner, e2 / 2);
}

// --- A tessellated floor ----------------------------------------------------------------------

template <typename S>
class MeshRegions : public ::testing::Test {};
TYPED_TEST_SUITE(MeshRegions, test::Scalars);

TYPED_TEST(MeshRegions, PressedIntoATessellatedFloorTheRegionIsTheCrossSection) {
  using S = TypeParam;
  constexpr bool single = std::is_same<S, float>::value;
  std::mt19937 rng(5201);
  std::uniform_real_distribution<double> uniform(0, 1);
  const double a1 = 0.8, a2 = 0.5, a3 = 0.6;
  int cases = 0;
  for (double e1 : {0.1, 0.5, 1.0, 1.9}) {
    for (double e2 : {0.1, 0.5, 1.0, 1.9}) {
      for (double depth : {1e-3, 2e-2}) {
        const Superellipsoid<S> shape{S(a1), S(a2), S(a3), S(e1), S(e2)};
        const fcl::Transform3<S> X = randomPose<S>(rng, S(2));
        // The floor's plane at the shape's z = a3 − δ, its grid turned about z and shifted.
        const int cells = 1 + int(uniform(rng) * 9);
        const auto floor = grid<S>(-2, 2, -2, 2, cells, cells + 1, cases);
        fcl::Transform3<S> X_SM = fcl::Transform3<S>::Identity();
        X_SM.linear() =
            Eigen::AngleAxis<S>(S(6.28 * uniform(rng)), Vector3<S>::UnitZ()).toRotationMatrix();
        X_SM.translation() =
            Vector3<S>(S(0.6 * uniform(rng) - 0.3), S(0.6 * uniform(rng) - 0.3), S(a3 - depth));
        const std::vector<ContactManifold<S>> regions =
            contactManifolds(shape, X, *floor, fcl::Transform3<S>(X * X_SM));
        SCOPED_TRACE(::testing::Message() << "e1 " << e1 << " e2 " << e2 << " depth " << depth
                                          << " cells " << cells << " BV kind " << cases % 6);
        ++cases;
        ASSERT_EQ(regions.size(), 1u);
        const ContactManifold<S>& m = regions[0];
        const double tol = m.patch_tolerance;
        EXPECT_NEAR(tol, 1e-3 * a1, 1e-9);
        const Eigen::Vector3d up = (X.linear() * Vector3<S>::UnitZ()).template cast<double>();
        EXPECT_GT(m.normal.template cast<double>().dot(up), 1 - (single ? 1e-6 : 1e-14));
        EXPECT_NEAR(m.distance, -depth, single ? 1e-5 : 1e-12);
        const double s = sectionScale(a3, e2, depth + tol);
        const double expected = superellipseArea(a1 * s, a2 * s, e1);
        const double area = polygonArea(m.polygon, m.normal);
        EXPECT_NEAR(area / expected, 1.0, 0.01) << "area " << area << " of " << expected;
        const fcl::Transform3<double> X_SW = X.template cast<double>().inverse();
        for (const ManifoldPoint<S>& p : m.polygon) {
          const Eigen::Vector3d on_shape = X_SW * p.on_shape.template cast<double>();
          const Eigen::Vector3d on_other = X_SW * p.on_other.template cast<double>();
          EXPECT_NEAR(double(referenceGauge(shape, Vector3<S>(on_shape.cast<S>()))), 1.0,
                      single ? 1e-4 : 1e-9);
          EXPECT_NEAR(on_other.z(), a3 - depth, single ? 1e-5 : 1e-12);
          EXPECT_NEAR(double(p.depth), on_shape.z() - (a3 - depth), single ? 1e-5 : 1e-12);
          EXPECT_GE(p.depth, -tol * (1 + 1e-3) - (single ? 1e-6 : 0));
          EXPECT_LE(p.depth, depth * (1 + 1e-6) + (single ? 1e-6 : 0));
        }
        ASSERT_FALSE(m.points.empty());
        EXPECT_LE(m.points.size(), 4u);
        EXPECT_NEAR(m.points[0].depth, depth, single ? 1e-5 : 1e-12);
        if (m.polygon.size() >= 4) EXPECT_EQ(m.points.size(), 4u);
      }
    }
  }
  EXPECT_EQ(cases, 32);
}

// --- Over the floor's edge ----------------------------------------------------------------------

TEST(MeshRegionsEdges, HungOverTheFloorsEdgeThePartOverTheFloor) {
  // Random shapes pressed into a floor that covers their x ≤ edge (shape frame), the edge from
  // beyond the shape's axis to well short of it.
  std::mt19937 rng(5202);
  std::uniform_real_distribution<double> uniform(0, 1);
  int regions_checked = 0, apart = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const double a1 = 0.2 + 0.8 * uniform(rng), a2 = 0.2 + 0.8 * uniform(rng),
                 a3 = 0.2 + 0.8 * uniform(rng), e1 = 0.05 + 1.9 * uniform(rng),
                 e2 = 0.05 + 1.9 * uniform(rng), depth = 0.03 * a3 * uniform(rng),
                 edge = a1 * (0.9 * uniform(rng) - 0.6);
    const Superellipsoid<double> shape(a1, a2, a3, e1, e2);
    const fcl::Transform3d X = randomPose<double>(rng, 1.0);
    const auto floor = grid<double>(-5, edge, -5, 5, 1 + trial % 6, 1 + trial % 5, trial);
    fcl::Transform3d X_SM = fcl::Transform3d::Identity();
    X_SM.translation().z() = a3 - depth;
    const std::vector<ContactManifold<double>> regions =
        contactManifolds(shape, X, *floor, X * X_SM);
    SCOPED_TRACE(::testing::Message()
                 << "trial " << trial << " e1 " << e1 << " e2 " << e2 << " edge/a1 " << edge / a1);
    // The deepest place over the floor: the shape's lowest point, or where the floor's edge
    // passes under the shape's axis plane y = 0 (the top is deepest there along the edge).
    const double deepest = edge >= 0 ? depth : topHeight(a1, a2, a3, e1, e2, edge, 0) - a3 + depth;
    const double size = shape.size(), tol = 1e-3 * size;
    if (deepest < -tol) {  // the shape's top is apart from the floor by more than that
      EXPECT_TRUE(regions.empty());
      ++apart;
      continue;
    }
    ASSERT_EQ(regions.size(), 1u);
    ++regions_checked;
    const ContactManifold<double>& m = regions[0];
    // The area, to the outline's tolerance of the whole cap's (a part cut thin is a sliver).
    const double s = sectionScale(a3, e2, depth + tol);
    const double whole = superellipseArea(a1 * s, a2 * s, e1);
    EXPECT_NEAR(polygonArea(m.polygon, m.normal), sectionAreaUpTo(a1 * s, a2 * s, 2 / e1, edge),
                0.01 * whole);
    for (const ManifoldPoint<double>& p : m.polygon) {
      EXPECT_LE((X.inverse() * p.on_other).x(), edge + 1e-9 * size);
    }
    // 1e-8 × size: one pose (of clang's random draws) gives 3.8e-9 × size, where the search's
    // points on the floor's boundary edge near the deepest place miss every facet by more than
    // rounding and are measured pulled inwards (the identity pose is exact; the cause is open).
    EXPECT_NEAR(m.distance, -deepest, 1e-8 * size);
    // The first point is the deepest place, or a vertex within the tolerance of it (a flat
    // contact is held at its corners); none is deeper.
    double most = -1;
    for (const ManifoldPoint<double>& p : m.points) most = std::max(most, p.depth);
    EXPECT_LE(most, deepest + 1e-8 * size);
    EXPECT_GE(m.points[0].depth, deepest - tol * (1 + 1e-9));
    EXPECT_LE(m.points.size(), 4u);
  }
  EXPECT_GE(regions_checked, 60);
  EXPECT_GE(apart, 20);
}

/// A floor z = 0 (x ≥ 0) and a wall x = 0 (z ≥ 0), triangles 0–1 and 2–3.
std::shared_ptr<fcl::BVHModel<fcl::OBBRSS<double>>> cornerMesh() {
  auto corner = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  std::vector<Vector3<double>> v{{0, -1, 0}, {0, 1, 0},  {2, -1, 0},
                                 {2, 1, 0},  {0, -1, 2}, {0, 1, 2}};
  std::vector<fcl::Triangle> t{{0, 2, 3}, {0, 3, 1}, {0, 1, 5}, {0, 5, 4}};
  corner->beginModel();
  corner->addSubModel(v, t);
  corner->endModel();
  return corner;
}

TEST(MeshRegionsEdges, InACornerOneRegionPerFace) {
  // A floor z = 0 (x ≥ 0) and a wall x = 0 (z ≥ 0) meeting in a concave edge, as one mesh; the
  // shape pressed δf into the floor and δw into the wall. Equal exponents: every axis's
  // cross-section is then a superellipse of exponent 2/ε.
  const auto corner = cornerMesh();
  const double a1 = 0.5, a2 = 0.4, a3 = 0.3, floor_depth = 0.01, wall_depth = 0.005;
  std::mt19937 rng(5203);
  for (double e : {0.2, 0.6, 1.0}) {
    const Superellipsoid<double> shape(a1, a2, a3, e, e);
    fcl::Transform3d X_WS = fcl::Transform3d::Identity();
    X_WS.translation() = Vector3<double>(a1 - wall_depth, 0, a3 - floor_depth);
    const fcl::Transform3d T = randomPose<double>(rng, 1.0);  // the whole scene moved
    const std::vector<ContactManifold<double>> regions =
        contactManifolds(shape, T * X_WS, *corner, T);
    SCOPED_TRACE(::testing::Message() << "e " << e);
    ASSERT_EQ(regions.size(), 2u);
    const double tol = regions[0].patch_tolerance;
    // Deepest first: the floor, then the wall.
    EXPECT_GT(regions[0].normal.dot(T.linear() * Vector3<double>(0, 0, -1)), 1 - 1e-14);
    EXPECT_GT(regions[1].normal.dot(T.linear() * Vector3<double>(-1, 0, 0)), 1 - 1e-14);
    EXPECT_NEAR(regions[0].distance, -floor_depth, 1e-12);
    EXPECT_NEAR(regions[1].distance, -wall_depth, 1e-12);
    const double s_floor = sectionScale(a3, e, floor_depth + tol);
    const double s_wall = sectionScale(a1, e, wall_depth + tol);
    EXPECT_NEAR(polygonArea(regions[0].polygon, regions[0].normal) /
                    superellipseArea(a1 * s_floor, a2 * s_floor, e),
                1.0, 0.01);
    EXPECT_NEAR(polygonArea(regions[1].polygon, regions[1].normal) /
                    superellipseArea(a2 * s_wall, a3 * s_wall, e),
                1.0, 0.01);
  }
}

TEST(MeshRegionsEdges, OnATablesEdgeTheTopHoldsItAndTheSideDoesNot) {
  // A table top z = 0 over x ≤ 0 (a box's mesh, 12 triangles, and a finer one of its top), the
  // shape resting on it δ deep, its centre over the top or beyond the edge. Its region is the
  // part of its section over the top; the side x = 0 never gives one (it would push the shape
  // sideways by its overhang).
  const auto box = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  fcl::Transform3d X_box = fcl::Transform3d::Identity();
  X_box.translation() = Vector3<double>(-1, 0, -0.5);
  fcl::generateBVHModel(*box, fcl::Box<double>(2, 2, 1), X_box);
  const double a1 = 0.5, a2 = 0.4, a3 = 0.3, depth = 0.01;
  std::mt19937 rng(5204);
  int cases = 0;
  for (double e : {0.2, 1.0}) {
    for (double centre : {-0.3, -0.1, 0.1, 0.3}) {
      const Superellipsoid<double> shape(a1, a2, a3, e, e);
      fcl::Transform3d X_WS = fcl::Transform3d::Identity();
      X_WS.translation() = Vector3<double>(centre, 0, a3 - depth);
      const fcl::Transform3d T = randomPose<double>(rng, 1.0);
      const std::vector<ContactManifold<double>> regions =
          contactManifolds(shape, T * X_WS, *box, T);
      SCOPED_TRACE(::testing::Message() << "e " << e << " centre " << centre);
      ++cases;
      const double deepest =
          centre <= 0 ? depth : topHeight(a1, a2, a3, e, e, -centre, 0) - a3 + depth;
      if (deepest < -1e-3 * a1) {  // apart from the top by more than the tolerance
        EXPECT_TRUE(regions.empty());
        continue;
      }
      ASSERT_EQ(regions.size(), 1u);
      const ContactManifold<double>& m = regions[0];
      EXPECT_GT(m.normal.dot(T.linear() * Vector3<double>(0, 0, -1)), 1 - 1e-14);
      const double s = sectionScale(a3, e, depth + m.patch_tolerance);
      EXPECT_NEAR(
          polygonArea(m.polygon, m.normal) / sectionAreaUpTo(a1 * s, a2 * s, 2 / e, -centre), 1.0,
          0.01);
      EXPECT_NEAR(m.distance, -deepest, 1e-9);
    }
  }
  EXPECT_EQ(cases, 8);
}

// --- Pose, and agreement with the halfspace -------------------------------------------------

TEST(MeshRegionsPose, SameRegionsForThePairMovedAndTurned) {
  // The shape pressed against a tessellated superellipsoid (a closed, curved mesh) and against
  // a grid; the scene moved and turned must give the same regions, moved.
  std::mt19937 rng(5205);
  const Superellipsoid<double> body(0.9, 0.7, 0.5, 0.4, 0.6);
  const auto curved = makeBVHModel<fcl::OBBRSS<double>>(tessellate(body, 600));
  const auto flat = grid<double>(-2, 2, -2, 2, 6, 5, 0);
  int compared = 0;
  for (const auto& mesh : {std::shared_ptr<fcl::CollisionGeometry<double>>(curved), flat}) {
    for (const auto& [e1, e2] : {std::pair{0.3, 0.3}, std::pair{1.0, 0.8}}) {
      const Superellipsoid<double> shape(0.3, 0.25, 0.2, e1, e2);
      // A rounded shape's places turn with the pair to 1e-12 × size (the deepest place on a
      // rim too: where the depth is flat, its slope locates it). On a box-like shape's flattish
      // side the extreme point along a direction slides along the side with the rounding
      // (docs/math.md → "Contact regions", accuracy): its places agree to 1e-6 × size, as in
      // test_contact_manifold.cpp's pose test, and the region as a set (its area) to 1e-9.
      const double point_bound = (e1 < 0.5 ? 1e-6 : 1e-12) * shape.size();
      for (int trial = 0; trial < 4; ++trial) {
        // The shape's lowest point 0.02 below the mesh's surface (the body's top, or the
        // grid's plane z = 0.5); the facets, chords of the body, lie within 1e-3 of it.
        fcl::Transform3d X_WS = randomPose<double>(rng, 0.0);
        const Vector3<double> xy(0.1 * trial - 0.15, 0.05 * trial - 0.1, 0);
        const Vector3<double> lowest =
            X_WS.linear() *
            shape.supportPoint(X_WS.linear().transpose() * Vector3<double>(0, 0, -1));
        const double surface = compared < 8 ? topHeight(0.9, 0.7, 0.5, 0.4, 0.6,
                                                        xy.x() + lowest.x(), xy.y() + lowest.y())
                                            : 0.5;
        X_WS.translation() = xy + Vector3<double>(0, 0, surface - 0.02 - lowest.z());
        fcl::Transform3d X_WO = fcl::Transform3d::Identity();
        if (compared >= 8) X_WO.translation().z() = 0.5;
        const std::vector<ContactManifold<double>> m = contactManifolds(shape, X_WS, *mesh, X_WO);
        const fcl::Transform3d T = randomPose<double>(rng, 3.0);
        const std::vector<ContactManifold<double>> mt =
            contactManifolds(shape, T * X_WS, *mesh, T * X_WO);
        SCOPED_TRACE(::testing::Message()
                     << "mesh " << compared / 8 << " e1 " << e1 << " trial " << trial);
        ASSERT_FALSE(m.empty());
        ASSERT_EQ(m.size(), mt.size());
        for (std::size_t r = 0; r < m.size(); ++r) {
          EXPECT_LE((T.linear() * m[r].normal - mt[r].normal).norm(), 1e-12);
          EXPECT_NEAR(m[r].distance, mt[r].distance, 1e-12);
          EXPECT_NEAR(polygonArea(mt[r].polygon, mt[r].normal),
                      polygonArea(m[r].polygon, m[r].normal),
                      1e-9 * polygonArea(m[r].polygon, m[r].normal) + 1e-15);
          ASSERT_EQ(m[r].points.size(), mt[r].points.size());
          for (std::size_t i = 0; i < m[r].points.size(); ++i) {
            EXPECT_LE((T * m[r].points[i].position - mt[r].points[i].position).norm(), point_bound);
            EXPECT_NEAR(m[r].points[i].depth, mt[r].points[i].depth, 1e-12);
          }
        }
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 16);
}

TEST(MeshRegionsPose, WhereTheMeshIsAPlaneTheRegionIsTheHalfspaces) {
  // Random shapes, tilted, pressed into a tessellated floor: the halfspace's region, to
  // rounding (the same cap, outlined the same way; the triangles' edges add only collinear
  // vertices, which the hull drops).
  std::mt19937 rng(5206);
  std::uniform_real_distribution<double> uniform(0, 1);
  const fcl::Halfspace<double> ground(Vector3<double>(0, 0, 1), 0);
  for (int trial = 0; trial < 24; ++trial) {
    const Superellipsoid<double> shape(0.2 + 0.6 * uniform(rng), 0.2 + 0.6 * uniform(rng),
                                       0.2 + 0.6 * uniform(rng), 0.1 + 1.8 * uniform(rng),
                                       0.1 + 1.8 * uniform(rng));
    fcl::Transform3d X_WS = randomPose<double>(rng, 0.3);
    const ContactManifold<double> apart =
        contactManifold(shape, X_WS, ground, fcl::Transform3d::Identity());
    X_WS.translation().z() -= apart.distance + 0.03 * uniform(rng);
    const ContactManifold<double> h =
        contactManifold(shape, X_WS, ground, fcl::Transform3d::Identity());
    const auto floor = grid<double>(-3, 3, -3, 3, 1 + trial % 7, 2 + trial % 5, trial);
    fcl::Transform3d X_WO = fcl::Transform3d::Identity();
    X_WO.translation() = Vector3<double>(0.3 * uniform(rng), 0.3 * uniform(rng), 0);
    const std::vector<ContactManifold<double>> regions =
        contactManifolds(shape, X_WS, *floor, X_WO);
    SCOPED_TRACE(::testing::Message() << "trial " << trial);
    ASSERT_EQ(regions.size(), 1u);
    const ContactManifold<double>& m = regions[0];
    EXPECT_LE((m.normal - h.normal).norm(), 1e-15);
    EXPECT_NEAR(m.distance, h.distance, 1e-15);
    const double area = polygonArea(h.polygon, h.normal);
    EXPECT_NEAR(polygonArea(m.polygon, m.normal), area, 1e-9 * area);
    ASSERT_FALSE(m.points.empty());
    EXPECT_NEAR(m.points[0].depth, h.points[0].depth, 1e-15);
    EXPECT_EQ(m.points.size(), h.points.size());
  }
}

// --- Through FCL's collide ---------------------------------------------------------------------

TEST(MeshRegionsThroughFcl, CollideWithRegionsGivesTheRegionsPlaces) {
  const auto shape = std::make_shared<Superellipsoid<double>>(0.5, 0.4, 0.3, 0.2, 0.2);
  const auto corner = cornerMesh();
  fcl::Transform3d X = fcl::Transform3d::Identity();
  X.translation() = Vector3<double>(0.5 - 0.005, 0, 0.3 - 0.01);
  fcl::CollisionObjectd body(shape, X), mesh(corner, fcl::Transform3d::Identity());
  // The vertices' model (the default): no vertex of the corner is inside the body.
  {
    fcl::CollisionResultd result;
    fcl::collide(&body, &mesh, fcl::CollisionRequestd(8, true), result);
    EXPECT_EQ(result.numContacts(), 0u);
  }
  EXPECT_THROW(shape->setMeshContacts(static_cast<MeshContacts>(7)), std::invalid_argument);
  shape->setMeshContacts(MeshContacts::kRegions);
  ManifoldOptions<double> places_only;
  places_only.outline_area_tolerance = 1;
  const std::vector<ContactManifold<double>> regions =
      contactManifolds(*shape, X, *corner, fcl::Transform3d::Identity(), places_only);
  ASSERT_EQ(regions.size(), 2u);
  for (bool shape_first : {true, false}) {
    SCOPED_TRACE(shape_first ? "shape first" : "mesh first");
    fcl::CollisionResultd result;
    if (shape_first) {
      fcl::collide(&body, &mesh, fcl::CollisionRequestd(8, true), result);
    } else {
      fcl::collide(&mesh, &body, fcl::CollisionRequestd(8, true), result);
    }
    ASSERT_EQ(result.numContacts(), regions[0].points.size() + regions[1].points.size());
    std::size_t k = 0;
    for (std::size_t r = 0; r < 2; ++r) {
      for (const ManifoldPoint<double>& p : regions[r].points) {
        const fcl::Contactd& c = result.getContact(k++);
        // FCL calls a shape–mesh pair as (mesh, shape) in either order and keeps that order:
        // its normal points from o1 to o2, the mesh's primitive is its region's triangle.
        const bool mesh_first = c.o1 == corner.get();
        EXPECT_TRUE(mesh_first);
        EXPECT_LE((c.normal - (mesh_first ? -1.0 : 1.0) * regions[r].normal).norm(), 1e-15);
        EXPECT_NEAR(c.penetration_depth, std::max(p.depth, 0.0), 1e-15);
        EXPECT_LE((c.pos - p.position).norm(), 1e-15);
        const int triangle = mesh_first ? c.b1 : c.b2;
        EXPECT_EQ(triangle / 2, int(r)) << "triangle " << triangle;
        EXPECT_EQ(mesh_first ? c.b2 : c.b1, int(fcl::Contactd::NONE));
      }
    }
    EXPECT_NEAR(result.getContact(0).penetration_depth, 0.01, 1e-12);
  }
  // Room for three: the floor's places first (the normal from the mesh up into the body).
  fcl::CollisionResultd three;
  fcl::collide(&body, &mesh, fcl::CollisionRequestd(3, true), three);
  ASSERT_EQ(three.numContacts(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_GT(three.getContact(i).normal.z(), 0.999);
  // One: the deepest.
  fcl::CollisionResultd one;
  fcl::collide(&body, &mesh, fcl::CollisionRequestd(1, true), one);
  ASSERT_EQ(one.numContacts(), 1u);
  EXPECT_NEAR(one.getContact(0).penetration_depth, 0.01, 1e-12);
  // Apart by more than the regions' tolerance: none.
  fcl::CollisionObjectd lifted(shape, fcl::Transform3d(Eigen::Translation3d(0.6, 0, 0.31)));
  fcl::CollisionResultd none;
  fcl::collide(&lifted, &mesh, fcl::CollisionRequestd(8, true), none);
  EXPECT_EQ(none.numContacts(), 0u);
}

// --- Nothing to answer, and the other geometries (refusals: test_bad_input.cpp) -----------------

TEST(MeshRegionsOthers, ApartNothingAndOtherGeometriesTheirOneRegion) {
  const Superellipsoid<double> shape(0.5, 0.4, 0.3, 0.5, 0.5);
  const fcl::Transform3d X = fcl::Transform3d::Identity();
  fcl::Transform3d below = X;
  below.translation().z() = -0.31;  // 0.01 below the shape: farther than the tolerance
  EXPECT_TRUE(contactManifolds(shape, X, *grid<double>(-1, 1, -1, 1, 3, 3, 0), below).empty());
  // An empty mesh: no regions.
  fcl::BVHModel<fcl::OBBRSS<double>> empty;
  empty.beginModel();
  empty.endModel();
  EXPECT_TRUE(contactManifolds(shape, X, empty, X).empty());
  // A sphere: contactManifold's region, or none when apart.
  const fcl::Sphere<double> sphere(0.2);
  fcl::Transform3d near = X;
  near.translation().x() = 0.69;
  const ContactManifold<double> one = contactManifold(shape, X, sphere, near);
  const std::vector<ContactManifold<double>> all = contactManifolds(shape, X, sphere, near);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].distance, one.distance);
  EXPECT_EQ(all[0].points.size(), one.points.size());
  near.translation().x() = 0.8;
  EXPECT_TRUE(contactManifolds(shape, X, sphere, near).empty());
}

// Finding 33 (docs/hardening.md → "Findings"): a closed triangle mesh with a vertex inside a
// box-like shape, met as a surface (MeshContacts::kRegions), where collide reported no contact:
// the face whose plane the shape was pressed against held the contact, but collide's outline (its
// first eight directions, not refined) missed the small part of the face inside the shape. The
// configuration fuzz_fcl found, in float and in double: the shape (1, 0.9, 0.8; 0.02, 1) and the
// 12-vertex tessellation of (0.5, 1, 0.2; 1, 1) in an OBB tree. Collide's deepest contact is at
// least as deep as the deepest vertex (by the long-double reference distance), and FCL's own
// signed distance (which calls collide after a negative distance and reads its deepest contact,
// of an empty result before) is minus that depth.
template <typename S>
void expectTheMeshWithAVertexInsideCollides() {
  auto shape = std::make_shared<Superellipsoid<S>>(S(1), S(0.9), S(0.8), S(0.02), S(1));
  shape->setMeshContacts(MeshContacts::kRegions);
  const auto mesh = tessellate(Superellipsoid<S>(S(0.5), S(1), S(0.2), S(1), S(1)), 12);
  const auto model = makeBVHModel<fcl::OBB<S>>(mesh);
  auto pose = [](std::initializer_list<double> rows) {
    fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
    auto v = rows.begin();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) X.matrix()(r, c) = S(*v++);
    }
    return X;
  };
  const fcl::Transform3<S> X_WS =
      pose({0.896780908, -0.425747961, 0.120510146, 0.41568625, 0.433593422, 0.791265249,
            -0.431156725, 0.353186131, 0.0882086009, 0.438905507, 0.894193053, 0.41568625});
  const fcl::Transform3<S> X_WM =
      pose({-0.471538663, 0.35694164, 0.806376934, 0.153408229, 0.80639261, 0.5446226, 0.230471402,
            1.70643377, -0.356906265, 0.75893271, -0.544645786, 0.530055463});
  int inside = 0;
  for (const auto& v : mesh.vertices) {
    const Vector3<S> q = X_WS.inverse(Eigen::Isometry) * (X_WM * v);
    inside += referenceGauge(*shape, q) < 0.99L;
  }
  ASSERT_GE(inside, 1) << "the construction lost its inside vertex";
  const fcl::CollisionObject<S> o_mesh(model, X_WM), o_shape(shape, X_WS);
  fcl::CollisionRequest<S> request(1, true);
  fcl::CollisionResult<S> result;
  fcl_superellipsoid::collide(&o_mesh, &o_shape, request, result);
  ASSERT_TRUE(result.isCollision()) << inside << " vertices inside";
  const test::ReferenceDistance reference({1.0L, 0.9L, 0.8L}, 0.02L, 1.0L);
  long double deepest = 0;
  for (const auto& v : mesh.vertices) {
    const Eigen::Matrix<long double, 3, 1> q =
        (X_WS.inverse(Eigen::Isometry) * (X_WM * v)).template cast<long double>();
    deepest = std::max(deepest, -reference.query({q.x(), q.y(), q.z()}).distance);
  }
  const double rounding = std::is_same<S, float>::value ? 1e-5 : 1e-12;
  EXPECT_GE(double(result.getContact(0).penetration_depth), double(deepest) - rounding);
  fcl::detail::GJKSolver_libccd<S> solver;
  fcl::DistanceRequest<S> signed_request(true);
  signed_request.enable_signed_distance = true;
  fcl::DistanceResult<S> signed_result;
  fcl::distance(&o_mesh, &o_shape, &solver, signed_request, signed_result);
  EXPECT_NEAR(double(signed_result.min_distance), -double(result.getContact(0).penetration_depth),
              rounding);
}

TEST(MeshRegions, AMeshWithAVertexInsideCollidesInFloat) {
  expectTheMeshWithAVertexInsideCollides<float>();
}
TEST(MeshRegions, AMeshWithAVertexInsideCollidesInDouble) {
  expectTheMeshWithAVertexInsideCollides<double>();
}

// Finding 33's second configuration (fuzz_fcl, float): a vertex of the 80-vertex tessellation of
// the needle (0.2, 0.2, 1; 1.98, 0.65) 9.6e-4 inside the shape (1, 0.9, 0.8; 0.02, 0.3), within
// the regions' tolerance of its surface. A face region covered the vertex, but collide's coarse
// outline put it apart (distance ≥ 0), so it gave no contact and held the vertex from making one.
// Collide now reports a contact at least as deep as the vertex, and FCL's signed distance is
// minus its depth.
TEST(MeshRegions, AVertexJustInsideUnderAFaceRegionApartCollides) {
  using S = float;
  auto shape = std::make_shared<Superellipsoid<S>>(1.0f, 0x1.ccccccp-1f, 0x1.99999ap-1f,
                                                   0x1.47ae14p-6f, 0x1.333334p-2f);
  shape->setMeshContacts(MeshContacts::kRegions);
  const auto mesh = tessellate(Superellipsoid<S>(0.2f, 0.2f, 1.0f, 1.98f, 0.65f), 80);
  const auto model = makeBVHModel<fcl::OBB<S>>(mesh);
  const auto pose = [](const std::array<float, 12>& rows) {
    fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 4; ++j) X.matrix()(i, j) = rows[std::size_t(4 * i + j)];
    }
    return X;
  };
  const fcl::Transform3<S> X_WS =
      pose({-0x1.c2a3p-7f, 0x1.f705c2p-1f, -0x1.7ccbap-3f, 0x1p+1f, -0x1.ea815ep-1f, -0x1.0f2c2p-4f,
            -0x1.1da774p-2f, 0x1p+1f, -0x1.254022p-2f, 0x1.64f3bap-3f, 0x1.e25eeep-1f, 0x1p+1f});
  const fcl::Transform3<S> X_WM =
      pose({0x1.ec2be8p-3f, 0x1.7be62cp-1f, 0x1.40705ep-1f, 0x1.7fc5e4p+1f, 0x1.e807f8p-2f,
            0x1.e2d018p-2f, -0x1.7be62cp-1f, 0x1.9395ccp-1f, -0x1.b0f7aep-1f, 0x1.e807f8p-2f,
            -0x1.ec2bep-3f, 0x1.90ddccp-1f});
  const test::ReferenceDistance reference(
      {1.0L, (long double)0x1.ccccccp-1f, (long double)0x1.99999ap-1f}, (long double)0x1.47ae14p-6f,
      (long double)0x1.333334p-2f);
  long double deepest = 0;
  for (const auto& v : mesh.vertices) {
    const Eigen::Matrix<long double, 3, 1> q =
        (X_WS.inverse(Eigen::Isometry) * (X_WM * v)).cast<long double>();
    deepest = std::max(deepest, -reference.query({q.x(), q.y(), q.z()}).distance);
  }
  ASSERT_GT(deepest, 0) << "the construction lost its inside vertex";
  const fcl::CollisionObject<S> o_mesh(model, X_WM), o_shape(shape, X_WS);
  for (std::size_t room = 1; room <= 8; ++room) {
    fcl::CollisionResult<S> result;
    fcl::collide(&o_shape, &o_mesh, fcl::CollisionRequest<S>(room, true), result);
    ASSERT_TRUE(result.isCollision()) << "room " << room;
    double most = 0;
    for (std::size_t i = 0; i < result.numContacts(); ++i) {
      most = std::max(most, double(result.getContact(i).penetration_depth));
    }
    EXPECT_GE(most, double(deepest) - 1e-5);
  }
  fcl::detail::GJKSolver_libccd<S> solver;
  fcl::DistanceRequest<S> request(true);
  request.enable_signed_distance = true;
  fcl::DistanceResult<S> result;
  fcl::distance(&o_shape, &o_mesh, &solver, request, result);
  EXPECT_LT(result.min_distance, 0.0f);
  EXPECT_TRUE(result.nearest_points[0].allFinite());
}

}  // namespace
}  // namespace fcl_superellipsoid
