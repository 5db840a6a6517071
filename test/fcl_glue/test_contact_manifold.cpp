// The contact manifold (contact_manifold.h), against constructions: a superellipsoid pressed
// into a halfspace along its axis has the cross-section at that depth as its region (its area
// in closed form, docs/math.md → "Contact regions"); two flat faces pressed together have the
// overlap of their cross-sections (its area by quadrature here), a small body on a far larger
// face its places over its own face, a capsule or cylinder on a flat
// face its own cap (a strip, a stadium, a disc); every vertex's points on the
// two surfaces (the gauge in long double, the plane); the answer turns with the pair; FCL's
// collide with several contacts gives the manifold's overlapping places in its conventions.

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <fcl/narrowphase/collision.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "fcl_superellipsoid/contact_manifold.h"
#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_superellipsoid/tessellation.h"
#include "region_construction.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

using test::halfWidth;
using test::polygonArea;
using test::referenceGauge;
using test::sectionScale;
using test::superellipseArea;

template <typename S>
fcl::Transform3<S> randomPose(std::mt19937& rng, double reach) {
  std::normal_distribution<double> normal(0, 1);
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  q.normalize();
  fcl::Transform3d X = fcl::Transform3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = reach * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  return X.cast<S>();
}

// --- A superellipsoid pressed into a halfspace along its axis ------------------------------

template <typename S>
class ManifoldOnPlane : public ::testing::Test {};
TYPED_TEST_SUITE(ManifoldOnPlane, test::Scalars);

TYPED_TEST(ManifoldOnPlane, RegionIsTheCrossSectionAtTheDepth) {
  using S = TypeParam;
  constexpr bool single = std::is_same<S, float>::value;
  std::mt19937 rng(52);
  const double a1 = 0.8, a2 = 0.5, a3 = 0.6;
  const double area_bound = 0.01;
  int cases = 0;
  for (double e1 : {0.1, 0.4, 1.0, 1.6, 1.9}) {
    for (double e2 : {0.1, 0.4, 1.0, 1.6, 1.9}) {
      for (double depth : {1e-3, 2e-2, 0.2}) {
        for (bool plane : {false, true}) {
          const Superellipsoid<S> shape{S(a1), S(a2), S(a3), S(e1), S(e2)};
          const fcl::Transform3<S> X = randomPose<S>(rng, 2.0);
          // In the shape's frame, the halfspace z ≥ a3 − δ (n = −z), pressing on its top.
          const S top = S(a3 - depth);
          std::unique_ptr<fcl::CollisionGeometry<S>> other;
          if (plane) {
            other = std::make_unique<fcl::Plane<S>>(Vector3<S>(0, 0, -1), -top);
          } else {
            other = std::make_unique<fcl::Halfspace<S>>(Vector3<S>(0, 0, -1), -top);
          }
          const ContactManifold<S> m = contactManifold(shape, X, *other, X);
          SCOPED_TRACE(::testing::Message() << "e1 " << e1 << " e2 " << e2 << " depth " << depth
                                            << (plane ? " plane" : " halfspace"));
          const double tol = m.patch_tolerance;
          EXPECT_NEAR(tol, 1e-3 * 0.8, 1e-9);
          const Eigen::Vector3d up = (X.linear() * Vector3<S>::UnitZ()).template cast<double>();
          EXPECT_GT(m.normal.template cast<double>().dot(up), 1 - 1e-5);
          EXPECT_NEAR(m.distance, -depth, 1e-4 * (single ? 10 : 1e-6));
          // The cap of thickness δ + tolerance: its base's cross-section.
          const double s = sectionScale(a3, e2, depth + tol);
          const double expected = superellipseArea(a1 * s, a2 * s, e1);
          const double area = polygonArea(m.polygon, m.normal);
          EXPECT_NEAR(area / expected, 1.0, area_bound) << "area " << area << " of " << expected;
          // Each vertex: on the shape's surface, its other point on the plane, its depth the
          // height of the surface above the plane, within the tolerance of it.
          const fcl::Transform3<double> Xd = X.template cast<double>();
          for (const ManifoldPoint<S>& p : m.polygon) {
            const Eigen::Vector3d on_shape = Xd.inverse() * p.on_shape.template cast<double>();
            const Eigen::Vector3d on_other = Xd.inverse() * p.on_other.template cast<double>();
            const double g = double(referenceGauge(shape, Vector3<S>(on_shape.cast<S>())));
            EXPECT_NEAR(g, 1.0, single ? 1e-4 : 1e-9);
            EXPECT_NEAR(on_other.z(), double(top), single ? 1e-5 : 1e-12);
            EXPECT_NEAR(double(p.depth), on_shape.z() - double(top), single ? 1e-5 : 1e-12);
            EXPECT_GE(p.depth, -tol * (1 + 1e-3) - (single ? 1e-6 : 0));
            EXPECT_LE(p.depth, depth * (1 + 1e-6) + (single ? 1e-6 : 0));
          }
          // The reduced points: the deepest first, at most four, spanning the region.
          ASSERT_FALSE(m.points.empty());
          EXPECT_LE(m.points.size(), 4u);
          EXPECT_NEAR(m.points[0].depth, depth, single ? 1e-5 : 1e-12);
          if (m.polygon.size() >= 4 && area > 0) {
            EXPECT_EQ(m.points.size(), 4u);
          }
          ++cases;
        }
      }
    }
  }
  EXPECT_EQ(cases, 150);
}

// --- Two flat faces pressed together ---------------------------------------------------------

/// The area of the intersection of |x/a|^n + |y/b|^n ≤ 1 with the same shape of radii (c, d),
/// exponent m, centred at (ox, oy), by the midpoint rule along x over exact intervals in y.
double overlapArea(double a, double b, double n, double c, double d, double m, double ox,
                   double oy) {
  const double lo = std::max(-a, ox - c), hi = std::min(a, ox + c);
  if (hi <= lo) return 0;
  const int steps = 200000;
  const double dx = (hi - lo) / steps;
  double area = 0;
  for (int i = 0; i < steps; ++i) {
    const double x = lo + (i + 0.5) * dx;
    const double w1 = halfWidth(a, b, n, x), w2 = halfWidth(c, d, m, x - ox);
    area += std::max(0.0, std::min(w1, oy + w2) - std::max(-w1, oy - w2)) * dx;
  }
  return area;
}

TEST(ManifoldFaceToFace, TwoSuperellipsoidsOverlapOfTheirFaces) {
  std::mt19937 rng(521);
  const double depth = 0.01;
  for (double e1a : {0.1, 1.0}) {
    for (double e1b : {0.1, 0.6}) {
      for (const Eigen::Vector2d& offset :
           {Eigen::Vector2d(0.3, 0.1), Eigen::Vector2d(-0.2, 0.35), Eigen::Vector2d(0, 0)}) {
        const Superellipsoid<double> a(0.6, 0.4, 0.3, e1a, 0.1), b(0.5, 0.45, 0.25, e1b, 0.1);
        const fcl::Transform3d X = randomPose<double>(rng, 1.0);
        fcl::Transform3d X_AB = fcl::Transform3d::Identity();
        X_AB.translation() = Eigen::Vector3d(offset.x(), offset.y(), 0.3 + 0.25 - depth);
        const ContactManifold<double> m = contactManifold(a, X, b, X * X_AB);
        SCOPED_TRACE(::testing::Message()
                     << "e1 " << e1a << ", " << e1b << " offset " << offset.transpose());
        EXPECT_GT(m.normal.dot(X.linear().col(2)), 1 - 1e-6);
        const double tau = -m.distance + m.patch_tolerance;
        const double sa = sectionScale(0.3, 0.1, tau), sb = sectionScale(0.25, 0.1, tau);
        const double expected = overlapArea(0.6 * sa, 0.4 * sa, 2 / e1a, 0.5 * sb, 0.45 * sb,
                                            2 / e1b, offset.x(), offset.y());
        EXPECT_NEAR(polygonArea(m.polygon, m.normal) / expected, 1.0, 0.01);
        ASSERT_EQ(m.points.size(), 4u);
      }
    }
  }
}

TEST(ManifoldFaceToFace, SuperellipsoidOnABoxFace) {
  std::mt19937 rng(522);
  const double depth = 0.02;
  for (double e1 : {0.1, 1.0, 1.8}) {
    for (const Eigen::Vector2d& offset :
         {Eigen::Vector2d(0.35, 0.1), Eigen::Vector2d(-0.1, -0.3), Eigen::Vector2d(0, 0)}) {
      const Superellipsoid<double> a(0.6, 0.4, 0.3, e1, 0.1);
      const fcl::Box<double> box(0.8, 0.5, 0.4);
      const fcl::Transform3d X = randomPose<double>(rng, 1.0);
      fcl::Transform3d X_AB = fcl::Transform3d::Identity();
      X_AB.translation() = Eigen::Vector3d(offset.x(), offset.y(), 0.3 + 0.2 - depth);
      const ContactManifold<double> m = contactManifold(a, X, box, X * X_AB);
      SCOPED_TRACE(::testing::Message() << "e1 " << e1 << " offset " << offset.transpose());
      EXPECT_GT(m.normal.dot(X.linear().col(2)), 1 - 1e-6);
      const double tau = -m.distance + m.patch_tolerance;
      const double sa = sectionScale(0.3, 0.1, tau);
      // The box's face as a superellipse of a huge exponent is its rectangle.
      const double expected =
          overlapArea(0.6 * sa, 0.4 * sa, 2 / e1, 0.4, 0.25, 4000, offset.x(), offset.y());
      EXPECT_NEAR(polygonArea(m.polygon, m.normal) / expected, 1.0, 0.01);
      // The box's face is flat: every vertex's other point is on it.
      for (const ManifoldPoint<double>& p : m.polygon) {
        EXPECT_NEAR((X * X_AB).inverse().operator*(p.on_other).z(), -0.2, 1e-12);
      }
    }
  }
}

// A small box-like body on a far larger flat face (a body on the floor): the pair's witnesses are
// then any two points of the two faces, not one above the other. Every place, the hit's among
// the reduced points too, must be one point of each surface along the normal, over the small
// body's face.
TEST(ManifoldFaceToFace, PlacesOfASmallBodyOnALargeFaceAreOverItsFace) {
  std::mt19937 rng(523);
  std::uniform_real_distribution<double> across(-5, 5), turn(-M_PI, M_PI);
  const Superellipsoid<double> floor(20, 20, 0.5, 0.1, 0.1);
  const Superellipsoid<double> small_shape(0.3, 0.3, 0.2, 0.1, 0.1);
  const fcl::Box<double> small_box(0.6, 0.6, 0.4);
  for (int trial = 0; trial < 12; ++trial) {
    for (const double gap : {1e-4, -5e-3}) {
      for (const fcl::CollisionGeometry<double>* small :
           std::initializer_list<const fcl::CollisionGeometry<double>*>{&small_shape, &small_box}) {
        const fcl::Transform3d X = randomPose<double>(rng, 1.0);
        fcl::Transform3d X_FB = fcl::Transform3d::Identity();
        X_FB.linear() = Eigen::AngleAxisd(turn(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix();
        X_FB.translation() = Eigen::Vector3d(across(rng), across(rng), 0.5 + 0.2 + gap);
        const fcl::Transform3d X_WB = X * X_FB;
        SCOPED_TRACE(::testing::Message() << "trial " << trial << " gap " << gap << " partner "
                                          << (small == &small_box ? "box" : "superellipsoid"));
        std::vector<ContactManifold<double>> answers{contactManifold(floor, X, *small, X_WB)};
        if (small == &small_shape) answers.push_back(contactManifold(small_shape, X_WB, floor, X));
        for (const ContactManifold<double>& m : answers) {
          ASSERT_FALSE(m.points.empty());
          std::vector<ManifoldPoint<double>> places = m.polygon;
          places.insert(places.end(), m.points.begin(), m.points.end());
          for (std::size_t k = 0; k < places.size(); ++k) {
            const ManifoldPoint<double>& p = places[k];
            SCOPED_TRACE(k < m.polygon.size() ? "polygon vertex" : "reduced point");
            const Eigen::Vector3d apart = p.on_other - p.on_shape;
            EXPECT_LT((apart - apart.dot(m.normal) * m.normal).norm(), 1e-9 * 20);
            EXPECT_NEAR((p.position - 0.5 * (p.on_shape + p.on_other)).norm(), 0, 1e-9 * 20);
            const Eigen::Vector3d local = X_WB.inverse() * p.position;
            EXPECT_LE(std::abs(local.x()), 0.3 * (1 + 1e-9)) << local.transpose();
            EXPECT_LE(std::abs(local.y()), 0.3 * (1 + 1e-9)) << local.transpose();
          }
        }
      }
    }
  }
}

// --- A capsule and a cylinder on a flat face --------------------------------------------------

TEST(ManifoldFaceToFace, CapsuleAndCylinderOnAFlatFace) {
  std::mt19937 rng(524);
  // A wide box-like face, flat to 1e-7 over the footprints below.
  const Superellipsoid<double> a(0.9, 0.8, 0.3, 0.2, 0.1);
  const double r = 0.1, length = 0.6, depth = 0.01;
  const fcl::Capsule<double> capsule(r, length);
  const fcl::Cylinder<double> cylinder(r, length);
  for (int trial = 0; trial < 4; ++trial) {
    const fcl::Transform3d X = randomPose<double>(rng, 1.0);
    const Eigen::Vector2d offset(0.1 * trial - 0.15, 0.05 * trial - 0.1);
    // Lying along x (the capsule, the cylinder), and standing on its disc (the cylinder).
    fcl::Transform3d lying = fcl::Transform3d::Identity();
    lying.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
    lying.translation() = Eigen::Vector3d(offset.x(), offset.y(), 0.3 + r - depth);
    fcl::Transform3d standing = fcl::Transform3d::Identity();
    standing.translation() = Eigen::Vector3d(offset.x(), offset.y(), 0.3 + 0.5 * length - depth);
    struct Case {
      const fcl::CollisionGeometry<double>* other;
      fcl::Transform3d X_AB;
      const char* name;
    };
    for (const Case& c :
         {Case{&capsule, lying, "capsule lying"}, Case{&cylinder, lying, "cylinder lying"},
          Case{&cylinder, standing, "cylinder standing"}}) {
      const ContactManifold<double> m = contactManifold(a, X, *c.other, X * c.X_AB);
      SCOPED_TRACE(::testing::Message() << c.name << " trial " << trial);
      EXPECT_GT(m.normal.dot(X.linear().col(2)), 1 - 1e-9);
      EXPECT_NEAR(m.distance, -depth, 1e-12);
      // The other's cap of thickness τ: a lying body's strip of half-width w (a capsule's with
      // half discs at its ends); a standing cylinder's whole disc.
      const double tau = -m.distance + m.patch_tolerance;
      const double w = std::sqrt(2 * r * tau - tau * tau);
      const double expected = c.other == &capsule            ? 2 * w * length + M_PI * w * w
                              : c.X_AB.linear().isIdentity() ? M_PI * r * r
                                                             : 2 * w * length;
      EXPECT_NEAR(polygonArea(m.polygon, m.normal) / expected, 1.0, 0.01);
      // Every vertex's point on the other is on its surface: r from the axis (the segment, for
      // the capsule), or on the standing cylinder's disc.
      const fcl::Transform3d X_WB = X * c.X_AB;
      for (const ManifoldPoint<double>& p : m.polygon) {
        const Eigen::Vector3d q = X_WB.inverse() * p.on_other;
        if (c.other == &capsule) {
          const double along = std::clamp(q.z(), -0.5 * length, 0.5 * length);
          EXPECT_NEAR((q - Eigen::Vector3d(0, 0, along)).norm(), r, 1e-9);
        } else if (c.X_AB.linear().isIdentity()) {
          EXPECT_NEAR(q.z(), -0.5 * length, 1e-12);
        } else {
          EXPECT_NEAR(q.head<2>().norm(), r, 1e-9);
        }
        // Within the tolerance of the other's lowest point, over a face that has dropped by
        // `dip` there (its top is a3·(1 − ρ^(ε1/ε2))^(ε2/2), ρ the superellipse's sum).
        const Eigen::Vector3d on_a = X.inverse() * p.on_shape;
        const double rho = std::pow(std::abs(on_a.x() / 0.9), 2 / 0.2) +
                           std::pow(std::abs(on_a.y() / 0.8), 2 / 0.2);
        const double dip = 0.3 - 0.3 * std::pow(1 - std::pow(rho, 0.2 / 0.1), 0.1 / 2);
        EXPECT_GE(p.depth, -m.patch_tolerance - dip - 1e-12);
        EXPECT_NEAR(p.depth, (p.on_shape - p.on_other).dot(m.normal), 1e-12);
      }
      // Held at four places; on the standing disc, flat on flat, all as deep as the overlap.
      ASSERT_EQ(m.points.size(), 4u);
      if (c.X_AB.linear().isIdentity()) {
        for (const ManifoldPoint<double>& p : m.points) EXPECT_NEAR(p.depth, depth, 1e-7);
      }
    }
  }
}

TEST(ManifoldFaceToFace, ConeOnItsBaseOnItsSideAndOnItsApex) {
  std::mt19937 rng(526);
  const Superellipsoid<double> a(0.9, 0.8, 0.3, 0.2, 0.1);  // flat to 1e-7 where the cone is
  const double depth = 0.01;
  // A slender cone and a squat one (its half-angle above 45°: the side across from the lowest
  // generator leans back beyond the apex).
  for (const auto& [r, lz] : {std::pair<double, double>{0.1, 0.4}, {0.15, 0.12}}) {
    const double h = 0.5 * lz;
    const double alpha = std::atan(r / lz);  // the half-angle
    const double slant = std::hypot(lz, r);
    const fcl::Cone<double> cone(r, lz);
    for (int trial = 0; trial < 4; ++trial) {
      const fcl::Transform3d X = randomPose<double>(rng, 1.0);
      const Eigen::Vector3d offset(0.1 * trial - 0.15, 0.05 * trial - 0.1, 0);
      // On its base; on its side (turned about y so that a generator lies lowest); apex down.
      fcl::Transform3d base = fcl::Transform3d::Identity();
      base.linear() = Eigen::AngleAxisd(0.7 * trial, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      base.translation() = offset + Eigen::Vector3d(0, 0, 0.3 + h - depth);
      fcl::Transform3d side = base;
      side.linear() =
          base.linear() *
          Eigen::AngleAxisd(M_PI / 2 + alpha, Eigen::Vector3d::UnitY()).toRotationMatrix();
      side.translation().z() = 0.3 - depth + h * std::sin(alpha);
      fcl::Transform3d apex = base;
      apex.linear() =
          base.linear() * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
      for (int pose = 0; pose < 3; ++pose) {
        const fcl::Transform3d X_AB = pose == 0 ? base : pose == 1 ? side : apex;
        const fcl::Transform3d X_WB = X * X_AB;
        const ContactManifold<double> m = contactManifold(a, X, cone, X_WB);
        SCOPED_TRACE(::testing::Message()
                     << "cone " << r << " " << lz << " pose " << pose << " trial " << trial);
        EXPECT_GT(m.normal.dot(X.linear().col(2)), 1 - 1e-9);
        EXPECT_NEAR(m.distance, -depth, 1e-12);
        const double tau = depth + m.patch_tolerance;
        const double area = polygonArea(m.polygon, m.normal);
        if (pose == 0) {  // the whole base disc
          EXPECT_NEAR(area / (M_PI * r * r), 1.0, 0.01);
        } else if (pose == 2) {  // the cone's tip of height τ: a disc of radius τ·tan(α)
          EXPECT_NEAR(area / (M_PI * std::pow(tau * std::tan(alpha), 2)), 1.0, 0.01);
        } else {
          // A sliver along the lowest generator, from the base's rim to the apex, and beyond
          // it where the far side leans back (rising at π − 2α: τ/tan(π − 2α)).
          const Eigen::Vector3d g = X_WB.linear() * Eigen::Vector3d(r, 0, -lz) / slant;
          double lo = std::numeric_limits<double>::infinity(), hi = -lo;
          for (const auto& p : m.polygon) {
            lo = std::min(lo, p.position.dot(g));
            hi = std::max(hi, p.position.dot(g));
          }
          const double behind = 2 * alpha > M_PI / 2 ? tau / std::tan(M_PI - 2 * alpha) : 0;
          EXPECT_NEAR((hi - lo) / (slant + behind), 1.0, 2e-3);
          EXPECT_GT(area, 0.0);
        }
        for (const ManifoldPoint<double>& p : m.polygon) {
          // On the cone's surface: its base, or its side r·(h − z)/lz from the axis.
          const Eigen::Vector3d q = X_WB.inverse() * p.on_other;
          const double off_side = q.head<2>().norm() - r * (h - q.z()) / lz;
          EXPECT_TRUE(std::abs(q.z() + h) <= 1e-12 || std::abs(off_side) <= 1e-9)
              << q.transpose() << " off the side by " << off_side;
          EXPECT_LE(off_side, 1e-9);
          EXPECT_NEAR(p.depth, (p.on_shape - p.on_other).dot(m.normal), 1e-12);
          // Flat on flat: as deep as the overlap; a curved rim: the tolerance away.
          if (pose == 0) EXPECT_NEAR(p.depth, depth, 1e-7);
          if (pose == 2) EXPECT_NEAR(p.depth, -m.patch_tolerance, 1e-7);
        }
        // Held at four places.
        EXPECT_EQ(m.points.size(), 4u);
      }
    }
  }
}

// Every vertex's point on a cylinder or cone is on its surface and in its cap: within the cap's
// thickness τ = tolerance − d of its support along −n (closed forms here). Random poses of a
// rounded and a box-like shape, overlapping by 0.02: the lines through the region's vertices
// often run along an end disc's plane, where a vertex measured past the disc's rim by the
// rounding of a tiny slope landed inside the disc, 0.14–0.46 below its cap.
TEST(ManifoldFaceToFace, VerticesOnACylinderOrConeAreInItsCap) {
  std::mt19937 rng(527);
  const double r = 0.3, lz = 0.4, h = 0.5 * lz;
  const fcl::Cylinder<double> cylinder(r, lz);
  const fcl::Cone<double> cone(r, lz);
  int checked = 0;
  for (const bool box_like : {false, true}) {
    const Superellipsoid<double> shape(0.5, 0.35, 0.3, box_like ? 0.2 : 0.7, box_like ? 0.3 : 0.8);
    for (const fcl::CollisionGeometry<double>* other :
         {static_cast<const fcl::CollisionGeometry<double>*>(&cylinder),
          static_cast<const fcl::CollisionGeometry<double>*>(&cone)}) {
      const bool is_cone = other == &cone;
      for (int trial = 0; trial < 100; ++trial) {
        const fcl::Transform3d X_WS = randomPose<double>(rng, 0.1);
        const fcl::Transform3d probe = X_WS * randomPose<double>(rng, 0);
        const ContactManifold<double> at_origin = contactManifold(shape, X_WS, *other, probe);
        fcl::Transform3d X_WO = probe;
        X_WO.translation() -= (at_origin.distance + 0.02) * at_origin.normal;
        const ContactManifold<double> m = contactManifold(shape, X_WS, *other, X_WO);
        SCOPED_TRACE(::testing::Message() << (box_like ? "box-like" : "rounded") << " "
                                          << (is_cone ? "cone" : "cylinder") << " trial " << trial);
        // B's support along −n, in B's frame.
        const Eigen::Vector3d w = X_WO.linear().transpose() * -m.normal;
        const double side = w.head<2>().norm();
        const double support =
            is_cone ? std::max(h * w.z(), r * side - h * w.z()) : r * side + h * std::abs(w.z());
        const double tau = m.patch_tolerance - m.distance;
        for (const ManifoldPoint<double>& p : m.polygon) {
          const Eigen::Vector3d q = X_WO.inverse() * p.on_other;
          EXPECT_GE(q.dot(w), support - tau - 1e-9) << q.transpose();
          const double rim = is_cone ? r * (h - q.z()) / lz : r;
          const bool on_end =
              std::abs(std::abs(q.z()) - h) <= 1e-9 && q.head<2>().norm() <= rim + 1e-9;
          EXPECT_TRUE(on_end || std::abs(q.head<2>().norm() - rim) <= 1e-9) << q.transpose();
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 2000);
}

// --- The answer turns with the pair -----------------------------------------------------------

/// The largest distance from a vertex of one polygon to the other's outline, both ways.
double hausdorff(const std::vector<ManifoldPoint<double>>& p,
                 const std::vector<ManifoldPoint<double>>& q) {
  const auto toOutline = [](const Eigen::Vector3d& x, const std::vector<ManifoldPoint<double>>& r) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < r.size(); ++i) {
      const Eigen::Vector3d a = r[i].position, e = r[(i + 1) % r.size()].position - a;
      const double t =
          e.squaredNorm() > 0 ? std::clamp((x - a).dot(e) / e.squaredNorm(), 0.0, 1.0) : 0;
      best = std::min(best, (x - a - t * e).norm());
    }
    return best;
  };
  double worst = 0;
  for (const auto& x : p) worst = std::max(worst, toOutline(x.position, q));
  for (const auto& x : q) worst = std::max(worst, toOutline(x.position, p));
  return worst;
}

TEST(ManifoldPose, SameRegionForThePairMovedAndTurned) {
  std::mt19937 rng(523);
  std::vector<Vector3<double>> cube;
  for (int k = 0; k < 8; ++k) {
    cube.emplace_back(k & 1 ? 0.3 : -0.3, k & 2 ? 0.2 : -0.2, k & 4 ? 0.25 : -0.25);
  }
  auto faces = std::make_shared<std::vector<int>>(std::vector<int>{
      4, 0, 2, 6, 4, 4, 1, 5, 7, 3, 4, 0, 4, 5, 1, 4, 2, 3, 7, 6, 4, 0, 1, 3, 2, 4, 4, 6, 7, 5});
  const auto vertices = std::make_shared<std::vector<Vector3<double>>>(cube);
  std::vector<std::unique_ptr<fcl::CollisionGeometry<double>>> others;
  others.push_back(std::make_unique<Superellipsoid<double>>(0.4, 0.4, 0.2, 0.3, 0.2));
  others.push_back(std::make_unique<fcl::Box<double>>(0.8, 0.6, 0.4));
  others.push_back(std::make_unique<fcl::Sphere<double>>(0.3));
  others.push_back(std::make_unique<fcl::Ellipsoid<double>>(0.5, 0.3, 0.2));
  others.push_back(std::make_unique<fcl::Convex<double>>(vertices, 6, faces));
  others.push_back(std::make_unique<fcl::TriangleP<double>>(
      Vector3<double>(-0.6, -0.5, 0), Vector3<double>(0.7, -0.4, 0), Vector3<double>(0, 0.6, 0)));
  others.push_back(std::make_unique<fcl::Halfspace<double>>(Vector3<double>(0, 0, 1), 0.0));
  others.push_back(std::make_unique<fcl::Capsule<double>>(0.2, 0.6));
  others.push_back(std::make_unique<fcl::Cylinder<double>>(0.3, 0.4));
  // The pair's normal is the narrowphase's: for overlapping pairs its direction is good to
  // about 1e-8 (a depth good to 1e-12 fixes its direction only to about the square root of
  // that). Where the two normals agree to the last bits, the regions must agree to 1e-12 × size
  // (vertices to 4e-12 × size: where two outlines cross at a small angle, their crossing moves
  // by the rounding over that angle's sine; the worst seen is 1.5e-12 × size) on a rounded
  // shape. On a box-like shape's flattish side the extreme point along a direction slides
  // along the side with the rounding (every point of a flat side is nearly extreme): there the
  // regions must agree as sets, to the outline's own tolerance, in area and in the distance of
  // each vertex from the other's outline. Elsewhere a cap's rim on a flattish face moves by
  // much more than the normal's turn (its height changes by the turn times the size, over a
  // small slope), and they must agree to 1e-6.
  const double size = 0.5, normal_bound = 1e-8;
  int exact_rounded = 0, compared = 0;
  for (const bool box_like : {false, true}) {
    const Superellipsoid<double> shape(0.5, 0.35, 0.3, box_like ? 0.2 : 0.7, box_like ? 0.3 : 0.8);
    for (const auto& other : others) {
      for (int trial = 0; trial < 6; ++trial) {
        const fcl::Transform3d X_WS = randomPose<double>(rng, 0.1);
        // The other turned about the shape's z (not onto a symmetry of the pair: ties between
        // equal candidates may go either way) and placed so that they overlap by 0.02.
        fcl::Transform3d X_SO = fcl::Transform3d::Identity();
        X_SO.linear() =
            Eigen::AngleAxisd(0.3 * trial + 0.1, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
            Eigen::AngleAxisd(0.05 * trial + 0.01, Eigen::Vector3d::UnitX()).toRotationMatrix();
        const fcl::Transform3d probe = X_WS * X_SO;
        const ContactManifold<double> at_origin = contactManifold(shape, X_WS, *other, probe);
        fcl::Transform3d X_WO = probe;
        X_WO.translation() -= (at_origin.distance + 0.02) * at_origin.normal;
        const ContactManifold<double> m = contactManifold(shape, X_WS, *other, X_WO);
        const fcl::Transform3d T = randomPose<double>(rng, 3.0);
        const ContactManifold<double> mt = contactManifold(shape, T * X_WS, *other, T * X_WO);
        SCOPED_TRACE(::testing::Message() << (box_like ? "box-like" : "rounded") << " other "
                                          << other->getNodeType() << " trial " << trial);
        ASSERT_GE(m.polygon.size(), 3u);
        ASSERT_FALSE(m.points.empty());
        ASSERT_FALSE(mt.points.empty());
        const double turn = (T.linear() * m.normal - mt.normal).norm();
        EXPECT_LE(turn, normal_bound);
        const bool exact = turn <= 1e-14;
        const double area = polygonArea(m.polygon, m.normal);
        const double area_t = polygonArea(mt.polygon, mt.normal);
        std::vector<ManifoldPoint<double>> moved = m.polygon;
        for (ManifoldPoint<double>& p : moved) p.position = T * p.position;
        EXPECT_NEAR(m.points[0].depth, mt.points[0].depth, exact ? 1e-12 * size : 1e-6 * size);
        if (exact && !box_like) {
          ++exact_rounded;
          ASSERT_EQ(m.polygon.size(), mt.polygon.size());
          ASSERT_EQ(m.points.size(), mt.points.size());
          for (std::size_t i = 0; i < m.polygon.size(); ++i) {
            EXPECT_LE((moved[i].position - mt.polygon[i].position).norm(), 4e-12 * size) << i;
            EXPECT_NEAR(m.polygon[i].depth, mt.polygon[i].depth, 1e-12 * size);
          }
          EXPECT_NEAR(area_t, area, 1e-12 * area);
          for (std::size_t i = 0; i < m.points.size(); ++i) {
            EXPECT_NEAR(m.points[i].depth, mt.points[i].depth, 1e-12 * size) << i;
          }
        } else {
          // As sets: the default outline leaves out at most about 0.5 % of the area, and no
          // edge lies farther than about that share of the width from the outline.
          EXPECT_NEAR(area_t, area, 0.01 * area);
          EXPECT_LE(hausdorff(moved, mt.polygon), 0.01 * std::sqrt(area));
        }
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 108);
  EXPECT_GE(exact_rounded, 15);
}

// --- Through FCL's collide -------------------------------------------------------------------

TEST(ManifoldThroughFcl, CollideWithSeveralContactsGivesTheOverlappingPlaces) {
  const auto shape = std::make_shared<Superellipsoid<double>>(0.5, 0.4, 0.3, 0.1, 0.1);
  const auto ground = std::make_shared<fcl::Halfspace<double>>(Vector3<double>(0, 0, 1), 0.0);
  // A box-like body tilted a little about x, its lowest edge 0.01 into the ground.
  fcl::Transform3d X = fcl::Transform3d::Identity();
  X.linear() = Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitX()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(0.2, -0.1, 0);
  const double lowest =
      (X * shape->supportPoint(-(X.linear().transpose() * Vector3<double>::UnitZ()))).z();
  X.translation().z() += -lowest - 0.01;
  fcl::CollisionObjectd body(shape, X), floor(ground, fcl::Transform3d::Identity());
  for (bool shape_first : {true, false}) {
    fcl::CollisionRequestd request(8, true);
    fcl::CollisionResultd result;
    if (shape_first) {
      fcl::collide(&body, &floor, request, result);
    } else {
      fcl::collide(&floor, &body, request, result);
    }
    SCOPED_TRACE(shape_first ? "shape first" : "ground first");
    // The deepest place first, then places on the rim of the region (the face's outline where
    // it comes within the tolerance of the ground): four, touching (depth 0) or deeper.
    ASSERT_EQ(result.numContacts(), 4u);
    EXPECT_NEAR(result.getContact(0).penetration_depth, 0.01, 1e-12);
    const double tolerance = 1e-3 * 0.5;
    for (std::size_t i = 0; i < result.numContacts(); ++i) {
      const fcl::Contactd& c = result.getContact(i);
      // FCL's normal points from o1 to o2: from the body down into the ground, or up.
      EXPECT_NEAR(c.normal.z(), shape_first ? -1.0 : 1.0, 1e-12);
      EXPECT_GE(c.penetration_depth, 0.0);
      // pos is halfway between the surfaces: within the tolerance of the ground, below it by
      // half the depth where they overlap.
      EXPECT_LE(c.pos.z(), 0.5 * tolerance + 1e-12);
      EXPECT_GE(c.pos.z(), -0.5 * c.penetration_depth - 1e-12);
      if (i > 0) {
        EXPECT_EQ(c.penetration_depth, 0.0);
        // On the body's surface where it is within the tolerance of the ground.
        const Eigen::Vector3d on_shape(c.pos.x(), c.pos.y(), 2 * c.pos.z());
        EXPECT_NEAR(shape->gauge(X.inverse() * on_shape), 1.0, 1e-9);
      }
    }
    // The places spread across the face's part in the ground: more than a thin strip.
    double span = 0;
    for (std::size_t i = 1; i < result.numContacts(); ++i) {
      span = std::max(span, (result.getContact(i).pos - result.getContact(0).pos).norm());
    }
    EXPECT_GT(span, 0.5);
  }
  // One contact requested: one, the deepest.
  fcl::CollisionRequestd one(1, true);
  fcl::CollisionResultd result;
  fcl::collide(&body, &floor, one, result);
  ASSERT_EQ(result.numContacts(), 1u);
  EXPECT_NEAR(result.getContact(0).penetration_depth, 0.01, 1e-12);
}

// --- Warm starts across steps ---------------------------------------------------------------

/// The largest difference between two manifolds' places (positions, surface points, depths);
/// infinite where their counts differ.
double manifoldDifference(const ContactManifold<double>& a, const ContactManifold<double>& b) {
  if (a.polygon.size() != b.polygon.size() || a.points.size() != b.points.size()) {
    return std::numeric_limits<double>::infinity();
  }
  double worst = (a.normal - b.normal).norm();
  for (const auto& [p, q] : {std::pair{&a.polygon, &b.polygon}, std::pair{&a.points, &b.points}}) {
    for (std::size_t i = 0; i < p->size(); ++i) {
      const ManifoldPoint<double>&x = (*p)[i], &y = (*q)[i];
      worst = std::max({worst, (x.position - y.position).norm(), (x.on_shape - y.on_shape).norm(),
                        (x.on_other - y.on_other).norm(), std::abs(x.depth - y.depth)});
    }
  }
  return worst;
}

// Along a path of small steps (a box-like body turning by about 1e-3 rad and moving 1 % of its
// size a step on a face), the warm-started manifold is the fresh one; so is it after a jump
// across the face, from another pair's warm start, and from a warm start of NaNs or of another
// number of directions; and the warm start holds one point per direction of each bounded cap.
TEST(ManifoldWarmStart, SameAnswerAsAFreshCall) {
  const Superellipsoid<double> body(0.5, 0.4, 0.3, 0.2, 0.3);
  const double size = 0.5;
  std::vector<std::unique_ptr<fcl::CollisionGeometry<double>>> others;
  others.push_back(std::make_unique<fcl::Halfspace<double>>(Vector3<double>(0, 0, 1), 0.0));
  others.push_back(std::make_unique<Superellipsoid<double>>(0.6, 0.5, 0.3, 0.3, 0.2));
  others.push_back(std::make_unique<fcl::Box<double>>(1.2, 1.0, 0.6));
  others.push_back(std::make_unique<fcl::Cylinder<double>>(0.8, 0.6));
  const double below[] = {0, 0.3, 0.3, 0.3};  // the other's half-height under the face
  for (std::size_t o = 0; o < others.size(); ++o) {
    for (const double area_tolerance : {0.005, 1.0}) {
      ManifoldOptions<double> options;
      options.outline_area_tolerance = area_tolerance;
      fcl::Transform3d X_WO = fcl::Transform3d::Identity();
      X_WO.translation().z() = -below[o];
      ManifoldWarmStart<double> warm;
      double worst = 0;
      for (int k = 0; k < 60; ++k) {
        fcl::Transform3d X = fcl::Transform3d::Identity();
        const double phase = 0.1 * k + (k >= 40 ? 2.0 : 0.0);  // a jump at step 40
        X.linear() = (Eigen::AngleAxisd(0.01 * std::sin(phase), Eigen::Vector3d::UnitX()) *
                      Eigen::AngleAxisd(0.01 * std::cos(phase), Eigen::Vector3d::UnitY()) *
                      Eigen::AngleAxisd(0.3 * phase, Eigen::Vector3d::UnitZ()))
                         .toRotationMatrix();
        X.translation() = Eigen::Vector3d(0.05 * std::cos(phase), 0.05 * std::sin(phase), 0);
        X.translation().z() =
            -(X * body.supportPoint(-(X.linear().transpose() * Vector3<double>::UnitZ()))).z() -
            0.002;
        if (k == 50) {  // NaNs, then another number of directions
          for (Vector3<double>& p : warm.shape_points) p.x() = std::nan("");
        }
        if (k == 55) warm.shape_points.pop_back();
        const ContactManifold<double> fresh = contactManifold(body, X, *others[o], X_WO, options);
        const ContactManifold<double> warmed =
            contactManifold(body, X, *others[o], X_WO, options, warm);
        SCOPED_TRACE(::testing::Message() << "other " << others[o]->getNodeType() << " area "
                                          << area_tolerance << " step " << k);
        ASSERT_FALSE(fresh.points.empty());
        worst = std::max(worst, manifoldDifference(fresh, warmed));
        EXPECT_EQ(warm.shape_points.size(), std::size_t(options.outline_samples));
        EXPECT_EQ(warm.other_points.size(), o == 0 ? 0u : std::size_t(options.outline_samples));
      }
      EXPECT_LE(worst, 1e-11 * size) << "other " << others[o]->getNodeType();
    }
  }
  // Another pair's warm start: the answer is still this pair's.
  ManifoldWarmStart<double> other_pair;
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  fcl::Transform3d X_WB = I;
  X_WB.translation().z() = 0.299;
  contactManifold(body, X_WB, *others[1], fcl::Transform3d(Eigen::Translation3d(0, 0, -0.3)), {},
                  other_pair);
  fcl::Transform3d X_tilted = X_WB;
  X_tilted.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitX()).toRotationMatrix();
  X_tilted.translation().z() = 0.25;
  const ContactManifold<double> fresh = contactManifold(body, X_tilted, *others[0], I);
  const ContactManifold<double> warmed =
      contactManifold(body, X_tilted, *others[0], I, {}, other_pair);
  EXPECT_LE(manifoldDifference(fresh, warmed), 1e-11 * size);
}

// --- The pair's witnesses ---------------------------------------------------------------------

// The manifold's distance and witness points are what the signed distance query reports for the
// pair, so a simulator that takes a manifold needs no distance query beside it: against every
// partner with a region, apart (within the patch tolerance and beyond it) and overlapping. And
// by construction: the shape's witness on its surface (the long-double gauge), the two witnesses
// |distance| apart.
TEST(ManifoldWitnesses, AreTheSignedDistancesNearestPoints) {
  const Superellipsoid<double> shape(0.5, 0.4, 0.3, 0.3, 0.8);
  std::vector<std::shared_ptr<fcl::CollisionGeometry<double>>> others = {
      std::make_shared<Superellipsoid<double>>(0.6, 0.5, 0.3, 0.2, 1.4),
      std::make_shared<fcl::Box<double>>(0.8, 0.6, 0.5),
      std::make_shared<fcl::Sphere<double>>(0.35),
      std::make_shared<fcl::Ellipsoid<double>>(0.4, 0.3, 0.2),
      std::make_shared<fcl::Capsule<double>>(0.2, 0.6),
      std::make_shared<fcl::Cylinder<double>>(0.3, 0.5),
      std::make_shared<fcl::Cone<double>>(0.3, 0.6),
      std::make_shared<fcl::Halfspace<double>>(Vector3<double>(0.2, -0.3, 1).normalized(), -0.1)};
  std::mt19937 rng(404);
  int apart = 0, overlapping = 0;
  for (const auto& other : others) {
    for (int k = 0; k < 30; ++k) {
      const fcl::Transform3d X_WS = randomPose<double>(rng, 0.3);
      const fcl::Transform3d X_WO = randomPose<double>(rng, 0.3);
      fcl::DistanceRequestd request;
      request.enable_signed_distance = true;
      request.enable_nearest_points = true;
      fcl::DistanceResultd result;
      const double d =
          fcl_superellipsoid::distance(&shape, X_WS, other.get(), X_WO, request, result);
      const ContactManifold<double> m = contactManifold(shape, X_WS, *other, X_WO);
      SCOPED_TRACE(::testing::Message()
                   << "other " << other->getNodeType() << ", pose " << k << ", distance " << d);
      (d >= 0 ? apart : overlapping) += 1;
      EXPECT_EQ(m.distance, d);
      EXPECT_EQ(m.on_shape, result.nearest_points[0]);
      EXPECT_EQ(m.on_other, result.nearest_points[1]);
      const Vector3<double> on_shape = X_WS.inverse() * m.on_shape;
      EXPECT_NEAR(double(referenceGauge(shape, on_shape)), 1.0, 1e-12);
      EXPECT_NEAR((m.on_shape - m.on_other).norm(), std::abs(d), 1e-12);
    }
  }
  EXPECT_GE(apart, 40);
  EXPECT_GE(overlapping, 40);
}

// --- Partners far larger or smaller than the shape -------------------------------------------

template <typename S>
class ManifoldRange : public ::testing::Test {};
TYPED_TEST_SUITE(ManifoldRange, test::Scalars);

/// Every manifold entry finite.
template <typename S>
bool finite(const ContactManifold<S>& m) {
  bool ok = m.normal.allFinite() && std::isfinite(m.distance);
  for (const auto* places : {&m.polygon, &m.points}) {
    for (const ManifoldPoint<S>& p : *places) {
      ok = ok && p.position.allFinite() && p.on_shape.allFinite() && p.on_other.allFinite() &&
           std::isfinite(p.depth);
    }
  }
  return ok;
}

/// Every contact finite, with a non-negative depth.
template <typename S>
bool finiteContacts(const fcl::CollisionResult<S>& result) {
  bool ok = true;
  for (std::size_t i = 0; i < result.numContacts(); ++i) {
    const fcl::Contact<S>& c = result.getContact(i);
    ok = ok && c.pos.allFinite() && c.normal.allFinite() && std::isfinite(c.penetration_depth) &&
         c.penetration_depth >= S(0);
  }
  return ok;
}

/// A sphere, a box, a capsule, a cylinder and a cone of size r.
template <typename S>
std::vector<std::shared_ptr<fcl::CollisionGeometry<S>>> partnersOfSize(S r) {
  return {std::make_shared<fcl::Sphere<S>>(r), std::make_shared<fcl::Box<S>>(r, r / 2, r),
          std::make_shared<fcl::Capsule<S>>(r, r), std::make_shared<fcl::Cylinder<S>>(r, r),
          std::make_shared<fcl::Cone<S>>(r, r)};
}

// Partners from the smallest size to the largest a pair accepts (max/16), posed across the
// shape's surface: every answer finite, with at least one place where they overlap, the first
// as deep as the pair. (A float sphere of radius 3.7e30 around a unit shape overflowed a vertex's
// measurement: docs/hardening.md → "Findings", 26.)
TYPED_TEST(ManifoldRange, PartnersFarLargerOrSmallerThanTheShapeGiveFiniteManifolds) {
  using S = TypeParam;
  const Superellipsoid<S> shape(S(1), S(0.5), S(0.25), S(1.35), S(1.35));
  std::mt19937 rng(26);
  std::uniform_real_distribution<double> u(-1, 1);
  const int top = std::numeric_limits<S>::max_exponent10 - 2;  // below max/16
  const int bottom = std::numeric_limits<S>::min_exponent10 + 8;
  int checked = 0;
  for (int k = bottom; k <= top; k += (sizeof(S) == 4 ? 1 : 10)) {
    const S r = S(3) * std::pow(S(10), S(k));
    for (const auto& partner : partnersOfSize(r)) {
      for (int trial = 0; trial < 4; ++trial) {
        const fcl::Transform3<S> X_WS = randomPose<S>(rng, 1);
        // The partner's centre beyond the shape's surface point along a random direction by
        // its own reach, give or take half the shape: the surfaces meet, or nearly.
        Vector3<S> v(S(u(rng)), S(u(rng)), S(u(rng)));
        v.normalize();
        const Vector3<S> on = X_WS * shape.supportPoint(X_WS.linear().transpose() * v);
        fcl::Transform3<S> X_WO = randomPose<S>(rng, 0);
        const S reach = partner->getNodeType() == fcl::GEOM_SPHERE ? r : S(0.5) * r;
        X_WO.translation() = on + (reach + S(0.5 * u(rng))) * v;
        SCOPED_TRACE(::testing::Message()
                     << "size " << r << " node " << partner->getNodeType() << " trial " << trial);
        const ContactManifold<S> m = contactManifold(shape, X_WS, *partner, X_WO);
        EXPECT_TRUE(finite(m));
        if (m.distance < S(0)) {
          ASSERT_FALSE(m.points.empty());
          // The first place is within the patch tolerance of the deepest, the hit's or deeper.
          EXPECT_GE(m.points.front().depth, -m.distance - m.patch_tolerance);
        }
        fcl::CollisionObject<S> a(std::make_shared<Superellipsoid<S>>(shape), X_WS);
        fcl::CollisionObject<S> b(partner, X_WO);
        fcl::CollisionRequest<S> request(4, true);
        fcl::CollisionResult<S> result;
        fcl::collide(&a, &b, request, result);
        EXPECT_TRUE(finiteContacts(result));
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 100);
}

// The shape swallowed whole by a partner up to the largest size a pair accepts, anywhere inside
// it: collide (through FCL's call with its solver, and the front end) reports the overlap with
// finite contacts and throws nothing, and the manifold is finite. (A float sphere of radius
// 5.7e31 around a unit shape put a point of (−inf, inf, NaN) into the shape's extent, whose
// gauge refused it from inside collide: docs/hardening.md → "Findings", 34.)
TYPED_TEST(ManifoldRange, AShapeSwallowedByAFarLargerPartnerCollidesFinitely) {
  using S = TypeParam;
  const Superellipsoid<S> shape(S(1), S(0.9), S(0.8), S(0.1), S(0.1));
  std::mt19937 rng(34);
  std::uniform_real_distribution<double> u(-1, 1);
  const int top = std::numeric_limits<S>::max_exponent10 - 2;  // below max/16
  int checked = 0;
  for (int k = 3; k <= top; k += (sizeof(S) == 4 ? 1 : 10)) {
    const S r = S(5.7) * std::pow(S(10), S(k - 1));
    for (const auto& partner : partnersOfSize(r)) {
      for (int trial = 0; trial < 4; ++trial) {
        const fcl::Transform3<S> X_WS = randomPose<S>(rng, 2);
        fcl::Transform3<S> X_WO = randomPose<S>(rng, 0);
        // Within a fifth of the partner's size from the shape (the shape is inside it), or,
        // in the first trial, a shape's size or two away.
        const S offset = trial == 0 ? S(2) : S(0.1) * r;
        X_WO.translation() =
            X_WS.translation() + offset * Vector3<S>(S(u(rng)), S(u(rng)), S(u(rng)));
        SCOPED_TRACE(::testing::Message()
                     << "size " << r << " node " << partner->getNodeType() << " trial " << trial);
        const ContactManifold<S> m = contactManifold(shape, X_WS, *partner, X_WO);
        EXPECT_TRUE(finite(m));
        EXPECT_LT(m.distance, S(0));
        fcl::CollisionObject<S> a(std::make_shared<Superellipsoid<S>>(shape), X_WS);
        fcl::CollisionObject<S> b(partner, X_WO);
        for (const bool shape_first : {true, false}) {
          const fcl::CollisionObject<S>* o1 = shape_first ? &a : &b;
          const fcl::CollisionObject<S>* o2 = shape_first ? &b : &a;
          for (const bool front_end : {false, true}) {
            fcl::CollisionRequest<S> request(4, true);
            fcl::CollisionResult<S> result;
            fcl::detail::GJKSolver_libccd<S> solver;
            if (front_end) {
              EXPECT_NO_THROW(fcl_superellipsoid::collide(o1, o2, request, result));
            } else {
              EXPECT_NO_THROW(fcl::collide(o1, o2, &solver, request, result));
            }
            EXPECT_TRUE(result.isCollision());
            EXPECT_TRUE(finiteContacts(result));
          }
        }
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 100);
}

// Finding 34's own configuration, to the bit (float; FCL's call with its solver, the sphere
// first, six contacts without details).
TEST(ManifoldRangeFloat, TheFindingsSphereAroundABoxLikeShapeCollides) {
  const auto pose = [](const std::array<float, 12>& rows) {
    fcl::Transform3f X = fcl::Transform3f::Identity();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 4; ++j) X.matrix()(i, j) = rows[std::size_t(4 * i + j)];
    }
    return X;
  };
  const fcl::Transform3f X_WS =
      pose({0x1.953a8p-4f, 0x1.cd2136p-1f, 0x1.b14d3cp-2f, 0x1.71717p-3f, 0x1.b14d3cp-2f,
            -0x1.b1192p-2f, 0x1.9a4274p-1f, 0x1.fe2ffep+0f, 0x1.cd2136p-1f, 0x1.98b1e8p-4f,
            -0x1.b1192p-2f, 0x1.fea6a4p-1f});
  const fcl::Transform3f X_WO =
      pose({-0x1.c52f6cp-1f, 0x1.d50ffcp-2f, -0x1.4fd7fp-4f, -0x1.8ebab8p+0f, 0x1.3e13b4p-4f,
            0x1.46c7c8p-2f, 0x1.e3990ap-1f, 0x1.7ea3fep+1f, 0x1.d5d5f8p-2f, 0x1.a8c91ap-1f,
            -0x1.45aafp-2f, 0x1.7d82fep+0f});
  const fcl::CollisionObject<float> shape(
      std::make_shared<Superellipsoid<float>>(1.0f, 0.9f, 0.8f, 0.1f, 0.1f), X_WS);
  const fcl::CollisionObject<float> sphere(std::make_shared<fcl::Sphere<float>>(0x1.67589cp+105f),
                                           X_WO);
  fcl::detail::GJKSolver_libccd<float> solver;
  const fcl::CollisionRequest<float> request(6, false);
  fcl::CollisionResult<float> result;
  EXPECT_NO_THROW(fcl::collide(&sphere, &shape, &solver, request, result));
  EXPECT_TRUE(result.isCollision());
  EXPECT_TRUE(finiteContacts(result));
}

// --- Refusals --------------------------------------------------------------------------------

TEST(ManifoldRefusals, GeometriesWithoutARegionAndBadOptionsAreRefused) {
  const Superellipsoid<double> shape(0.5, 0.4, 0.3, 0.5, 0.5);
  const fcl::Transform3d X = fcl::Transform3d::Identity();
  const auto mesh = makeBVHModel<fcl::OBBRSS<double>>(tessellate(shape, 8));
  EXPECT_THROW(contactManifold(shape, X, *mesh, X), std::invalid_argument);
  const fcl::Sphere<double> sphere(0.2);
  ManifoldOptions<double> options;
  options.outline_samples = 2;
  EXPECT_THROW(contactManifold(shape, X, sphere, X, options), std::invalid_argument);
  options = {};
  options.max_points = 0;
  EXPECT_THROW(contactManifold(shape, X, sphere, X, options), std::invalid_argument);
  options = {};
  options.patch_tolerance = std::nan("");
  EXPECT_THROW(contactManifold(shape, X, sphere, X, options), std::invalid_argument);
  // Apart by more than the tolerance: no region.
  fcl::Transform3d far = X;
  far.translation().x() = 2;
  const ContactManifold<double> m = contactManifold(shape, X, sphere, far);
  EXPECT_TRUE(m.polygon.empty());
  EXPECT_TRUE(m.points.empty());
  EXPECT_NEAR(m.distance, 2 - 0.5 - 0.2, 1e-12);
}

}  // namespace
}  // namespace fcl_superellipsoid
