// The rolling-ball certificate of smooth overlaps (src/fcl_glue/pairs/rolling_certificate.h): a
// local minimum of F(v) = h_A(v) + h_B(−v) that it accepts must be the global one. Rounded
// superellipsoids and ellipsoids (exponents ≤ 1, so both rolling radii are positive), elongated
// up to 10:1 so that F has several local minima, overlapping from 0.005 to 1.5 × the smaller
// radius; Newton on the sphere (sphere_newton.h) from 44 directions finds local minima, global
// and not, and the global depth comes from the independent long-double search of
// pair_construction.h. The ellipsoid's rolling radius is checked against its radii of curvature
// sampled over its surface.

#include <fcl/geometry/shape/ellipsoid.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "enumerated_depth.h"
#include "fcl_glue/pairs/rolling_certificate.h"
#include "fcl_glue/pairs/support_map.h"
#include "fcl_superellipsoid/point_distance.h"
#include "pair_construction.h"
#include "polytope_depth.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

using test::LD;
using test::V3;

/// 44 start directions: both frames' axes and a 32-direction Fibonacci lattice.
std::vector<Vector3<double>> startDirections(const fcl::Transform3d& X_A,
                                             const fcl::Transform3d& X_B) {
  std::vector<Vector3<double>> out;
  for (int i = 0; i < 3; ++i) {
    for (double sign : {1.0, -1.0}) {
      out.push_back(sign * X_A.linear().col(i));
      out.push_back(sign * X_B.linear().col(i));
    }
  }
  for (const V3& v : test::fibonacciLattice(32)) out.push_back(v.cast<double>());
  return out;
}

TEST(RollingCertificate, CertifiesOnlyTheGlobalOverlap) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> exponent(0.3, 1.0), radius(0.25, 1.0), size(0.5, 5.0),
      depth(0.005, 1.5);
  int certified = 0, local_only = 0, local_certified = 0;
  double worst = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const LD scale = LD(size(rng));
    const test::Construction c = test::constructShape(rng, scale, 0.3, 1.0);
    test::RandomShape partner{
        V3(scale * LD(radius(rng)), scale * LD(radius(rng)), scale * LD(radius(rng))),
        LD(exponent(rng)), LD(exponent(rng))};
    const bool ellipsoid = trial % 3 == 2;
    if (ellipsoid) partner.e1 = partner.e2 = 1;
    const test::SurfacePoint b = test::randomSurfacePoint(partner, rng);
    const LD smaller = std::min(c.shape.radii.minCoeff(), partner.radii.minCoeff());
    const fcl::Transform3d X_WB = test::placePartner(c, -LD(depth(rng)) * smaller, b.x, b.n, rng);

    const Superellipsoidd shape(Vector3<double>(c.shape.radii.cast<double>()), double(c.shape.e1),
                                double(c.shape.e2));
    const SupportMap<double> A(shape, c.X_WA);
    const Superellipsoidd other_se(Vector3<double>(partner.radii.cast<double>()),
                                   double(partner.e1), double(partner.e2));
    const fcl::Ellipsoidd other_el(Vector3<double>(partner.radii.cast<double>()));
    const SupportMap<double> B =
        ellipsoid ? SupportMap<double>(other_el, X_WB) : SupportMap<double>(other_se, X_WB);
    const double rolling =
        rollingRadius(shape) + (ellipsoid ? rollingRadius(other_el) : rollingRadius(other_se));
    ASSERT_GT(rolling, 0) << "trial " << trial;

    const double size_max = double(std::max(c.shape.radii.maxCoeff(), partner.radii.maxCoeff()));
    const double global = double(test::referenceDepth(
        test::supportFunction(shape, c.X_WA),
        ellipsoid ? test::supportFunction(other_el, X_WB) : test::supportFunction(other_se, X_WB)));
    ASSERT_GT(global, 0) << "trial " << trial;
    for (const Vector3<double>& start : startDirections(c.X_WA, X_WB)) {
      const Probe<double> m = localMinimum(A, B, start);
      const bool is_global = m.f <= global + 1e-9 * size_max;
      if (!is_global) ++local_only;
      if (!rollingCertified(m, rolling, kRollingGradientTolerance * size_max)) continue;
      ++certified;
      if (!is_global) ++local_certified;
      worst = std::max(worst, (m.f - global) / size_max);
      EXPECT_TRUE(is_global) << "trial " << trial << ": certified F " << m.f << ", depth " << global
                             << ", rolling radius " << rolling;
    }
  }
  std::cout << "rolling certificate: " << certified << " certified minima (worst " << worst
            << " × size above the depth), " << local_only << " local minima that are not global, "
            << local_certified << " of them certified\n";
  // The sample has both: minima the certificate accepts, and traps it must refuse.
  EXPECT_GT(certified, 100);
  EXPECT_GT(local_only, 20);
}

// The flat partners' form: rounded superellipsoids overlapping boxes by 0.0001 to 0.03 × size.
// At each candidate the overlap search makes (each face's normal; each vertex's escape direction,
// the outward normal at its nearest point by the point query), F, the witness b = a − F·v and how
// far b lies beyond the box's faces are computed here, and wherever the certificate accepts the
// candidate, F must be the depth by enumeration (polytope_depth.h). Without the rolling radius
// (any F accepted) some accepted candidates are not the depth: the radius is what certifies.
TEST(RollingCertificate, FlatPartnersCertifyOnlyTheGlobalOverlap) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> size(0.5, 5.0), gap(-0.3, -0.001);
  int certified = 0, wrong_without_radius = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const LD scale = LD(size(rng));
    const test::Construction c = test::constructShape(rng, scale, 0.3, 1.0);
    const Superellipsoidd shape(Vector3<double>(c.shape.radii.cast<double>()), double(c.shape.e1),
                                double(c.shape.e2));
    const SupportMap<double> A(shape, c.X_WA);
    const double rho = rollingRadius(shape);
    for (const test::FlatPartner& partner : test::flatPartners(rng, scale)) {
      const LD d = LD(gap(rng)) * scale * LD(0.1);
      const fcl::Transform3d X_WB = test::placePartner(c, d, partner.b_L, partner.m_L, rng);
      const auto* box = dynamic_cast<const fcl::Boxd*>(partner.geometry.get());
      if (box == nullptr || std::string(partner.name) != "box") continue;  // not "box face"
      const Vector3<double> half = box->side / 2;
      const std::vector<V3> corners = test::polytopeVertices(*box, X_WB);
      const double depth =
          double(test::polytopeDepth(test::supportFunction(shape, c.X_WA), corners));
      const double size_max = std::max(double(c.shape.radii.maxCoeff()), half.norm());
      std::vector<Vector3<double>> candidates;
      for (int i = 0; i < 3; ++i) {
        candidates.push_back(X_WB.linear().col(i));
        candidates.push_back(-X_WB.linear().col(i));
      }
      for (const V3& w : corners) {
        candidates.push_back(
            pointDistance(shape, c.X_WA, Vector3<double>(w.cast<double>())).normal);
      }
      for (const Vector3<double>& v : candidates) {
        const Vector3<double> a = A.evaluate(v).point;
        double h_b = -std::numeric_limits<double>::infinity();
        for (const V3& w : corners) h_b = std::max(h_b, -v.dot(w.cast<double>()));
        const double f = v.dot(a) + h_b;
        const Vector3<double> b = a - f * v;
        const Vector3<double> local = X_WB.linear().transpose() * (b - X_WB.translation());
        const double outside = (local.cwiseAbs() - half).maxCoeff();
        const double tolerance = kRollingOutsideTolerance * size_max;
        const bool is_depth = f <= depth + 1e-9 * size_max;
        if (rollingCertified(f, std::numeric_limits<double>::infinity(), outside, tolerance) &&
            !is_depth) {
          ++wrong_without_radius;
        }
        if (!rollingCertified(f, rho, outside, tolerance)) continue;
        ++certified;
        EXPECT_TRUE(is_depth) << "trial " << trial << ": certified F " << f << ", depth " << depth
                              << ", rolling radius " << rho;
      }
    }
  }
  std::cout << "flat partners: " << certified << " certified candidates, " << wrong_without_radius
            << " accepted without the radius that are not the depth\n";
  EXPECT_GT(certified, 20);
  EXPECT_GT(wrong_without_radius, 0);
}

// The ellipsoid's rolling radius c²/a is its smallest principal radius of curvature: on a grid
// of normals u, the radii of curvature are the eigenvalues of ∇²h(u) on u's tangent plane, with
// h(u) = ‖D·u‖ (closed form, long double, in the test); none is below c²/a, and the smallest
// found is within 1e-3 of it.
TEST(RollingCertificate, EllipsoidRadiusIsItsSmallestRadiusOfCurvature) {
  std::mt19937 rng(18);
  std::uniform_real_distribution<double> radius(0.1, 3.0);
  for (int trial = 0; trial < 20; ++trial) {
    const V3 d(LD(radius(rng)), LD(radius(rng)), LD(radius(rng)));
    const fcl::Ellipsoidd e(Vector3<double>(d.cast<double>()));
    const LD rho = LD(rollingRadius(e));
    LD smallest = std::numeric_limits<LD>::infinity();
    for (const V3& u : test::fibonacciLattice(20000)) {
      const V3 du = d.cwiseProduct(u);
      const LD h = du.norm();
      const V3 g = d.cwiseProduct(du) / h;
      const test::M3 H = (test::M3(d.cwiseProduct(d).asDiagonal()) - g * g.transpose()) / h;
      const V3 t1 = u.unitOrthogonal(), t2 = u.cross(t1);
      const LD b11 = t1.dot(H * t1), b22 = t2.dot(H * t2), b12 = t1.dot(H * t2);
      const LD low = (b11 + b22) / 2 - std::hypot((b11 - b22) / 2, b12);
      smallest = std::min(smallest, low);
    }
    EXPECT_GE(smallest, rho * (1 - 1e-12)) << "trial " << trial;
    EXPECT_LE(smallest, rho * (1 + 1e-3)) << "trial " << trial;
  }
}

}  // namespace
}  // namespace detail
}  // namespace fcl_superellipsoid
