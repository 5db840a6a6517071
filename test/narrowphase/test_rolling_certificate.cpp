// The rolling-ball certificate of smooth overlaps (src/narrowphase/rolling_certificate.h): a
// local minimum of F(v) = h_A(v) + h_B(−v) that it accepts must be the global one. Rounded
// superellipsoids and ellipsoids (exponents ≤ 1, so both rolling radii are positive), elongated
// up to 10:1 so that F has several local minima, overlapping from 0.005 to 1.5 × the smaller
// radius; Newton on the sphere (sphere_newton.h) from 44 directions finds local minima, global
// and not, and the global depth comes from the independent long-double search of
// pair_construction.h. The ellipsoid's rolling radius is checked against its radii of curvature
// sampled over its surface.

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "enumerated_depth.h"
#include "fcl_superellipsoid/point_distance.h"
#include "narrowphase/rolling_certificate.h"
#include "narrowphase/support_map.h"
#include "pair_construction.h"
#include "polytope_depth.h"
#include "round_depth.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

using test::LD;
using test::V3;

/// The library's shape of a test shape (rounded to double).
Superellipsoidd superellipsoidOf(const test::RandomShape& s) {
  return Superellipsoidd(Vector3<double>(s.radii.cast<double>()), double(s.e1), double(s.e2));
}

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

// How far x (world) lies beyond the bounding planes or surfaces of a box, a cylinder or a cone
// posed X_WB, and, inside it, minus its distance to the boundary: the test's own formulas.
double outsideOf(const fcl::CollisionGeometryd& g, const fcl::Transform3d& X_WB,
                 const Vector3<double>& x) {
  const Vector3<double> p = X_WB.linear().transpose() * (x - X_WB.translation());
  if (const auto* b = dynamic_cast<const fcl::Boxd*>(&g)) {
    return (p.cwiseAbs() - b->side / 2).maxCoeff();
  }
  const double radial = std::hypot(p[0], p[1]);
  if (const auto* b = dynamic_cast<const fcl::Cylinderd*>(&g)) {
    return std::max(radial - b->radius, std::abs(p[2]) - b->lz / 2);
  }
  const auto& k = dynamic_cast<const fcl::Coned&>(g);
  const double h = k.lz / 2, slant = std::hypot(k.lz, k.radius);
  return std::max(-h - p[2], (radial - k.radius * (h - p[2]) / k.lz) * k.lz / slant);
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

    const Superellipsoidd shape = superellipsoidOf(c.shape);
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
    const Superellipsoidd shape = superellipsoidOf(c.shape);
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
        const double outside = outsideOf(*box, X_WB, b);
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

// The two balls (twoBallsCertified, as the overlaps use it): a ball inside the other shape tangent
// at b = a − F·v and the local ball (localBallCertified) inside the superellipsoid tangent at its
// support point a along v, of radii summing to F(v). Superellipsoids of every exponent in
// [0.1, 1.9] (most creased, where the rolling radius is 0) overlap boxes, cylinders and cones by
// 0.0001 to 1 × its smallest radius. Candidates v: the construction's normal and small turns of
// it, the other shape's face, disc and side normals, 32 lattice directions, and the local minima
// of F a long-double pattern search reaches from the best lattice directions. F(v) is computed
// with the other shape's support function in long double; b must lie in the other shape (to
// within the pairs' 1e-12 × size); where the certificate accepts, F(v) must be the depth by
// enumeration (polytope_depth.h, round_depth.h). It must accept some candidates, some of them
// only with the other shape's ball (the local ball alone refuses them), and some candidates with
// b inside that are not the depth must exist (b's position alone certifies nothing). The balls'
// own tests are LocalBallLiesInsideTheShape and InsideBallLiesInsideTheOtherShape.
TEST(RollingCertificate, BallsCertifyOnlyTheGlobalOverlap) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> size(0.5, 5.0), log_gap(std::log(1e-4), std::log(1.0)),
      turn(-1.0, 1.0);
  int certified = 0, creased_certified = 0, wrong_without_ball = 0, tried = 0, needs_other = 0;
  double worst = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const LD scale = LD(size(rng));
    const test::Construction c = test::constructShape(rng, scale, 0.1, 1.9);
    const Superellipsoidd shape = superellipsoidOf(c.shape);
    const SupportMap<double> A(shape, c.X_WA);
    const bool creased = c.shape.e1 > 1 || c.shape.e2 > 1;
    const std::function<LD(const V3&)> h_a = test::supportFunction(shape, c.X_WA);
    for (const test::FlatPartner& partner : test::flatPartners(rng, scale)) {
      const std::string name = partner.name;
      const bool box = name.rfind("box", 0) == 0, cylinder = name.rfind("cylinder", 0) == 0,
                 cone = name.rfind("cone", 0) == 0;
      if (!box && !cylinder && !cone) continue;
      const LD d = -LD(std::exp(log_gap(rng))) * c.shape.radii.minCoeff();
      const fcl::Transform3d X_WB = test::placePartner(c, d, partner.b_L, partner.m_L, rng);
      const fcl::CollisionGeometryd& g = *partner.geometry;
      const double depth = double(box ? test::polytopeDepth(h_a, test::polytopeVertices(g, X_WB))
                                      : test::roundDepth(h_a, g, X_WB));
      if (!(depth > 0)) continue;  // a thin shape pierced through: not an overlap here
      const std::function<LD(const V3&)> h_b = test::supportFunction(g, X_WB);
      auto F = [&](const V3& v) { return h_a(v) + h_b(V3(-v)); };
      auto outside = [&](const Vector3<double>& x) { return outsideOf(g, X_WB, x); };
      const double size_max = std::max(double(c.shape.radii.maxCoeff()), g.aabb_radius);
      const double tolerance = kRollingOutsideTolerance * size_max;

      std::vector<V3> candidates = {c.u};
      for (double angle : {1e-9, 1e-6, 1e-4, 1e-2}) {
        const V3 t = c.u.unitOrthogonal(), w = c.u.cross(t);
        const LD phi = LD(M_PI * turn(rng));
        candidates.push_back(
            (c.u + LD(angle) * (std::cos(phi) * t + std::sin(phi) * w)).normalized());
      }
      // The other shape's face, disc and side normals (where b = a − F·v lands on that face).
      const test::M3 R_B = X_WB.linear().cast<LD>();
      for (int i = 0; i < 3 && box; ++i) {
        candidates.push_back(V3(R_B.col(i)));
        candidates.push_back(V3(-R_B.col(i)));
      }
      if (cylinder || cone) {
        const auto& r = dynamic_cast<const fcl::Cylinderd*>(&g);
        const auto& k = dynamic_cast<const fcl::Coned*>(&g);
        const LD radius = r ? r->radius : k->radius, length = r ? r->lz : k->lz;
        candidates.push_back(V3(R_B.col(2)));
        if (cylinder) candidates.push_back(V3(-R_B.col(2)));
        for (int j = 0; j < 8; ++j) {
          const LD t = LD(M_PI / 4) * j;
          const V3 radial = std::cos(t) * R_B.col(0) + std::sin(t) * R_B.col(1);
          // −v is the side's outward normal: v points into the other shape.
          candidates.push_back(
              cylinder ? V3(-radial) : V3(-(length * radial + radius * R_B.col(2)).normalized()));
        }
      }
      std::vector<std::pair<LD, V3>> lattice;
      for (const V3& v : test::fibonacciLattice(32)) {
        candidates.push_back(v);
        lattice.push_back({F(v), v});
      }
      std::sort(lattice.begin(), lattice.end(),
                [](const auto& x, const auto& y) { return x.first < y.first; });
      for (int k = 0; k < 2; ++k) {
        V3 v = lattice[std::size_t(k)].second;
        LD f = lattice[std::size_t(k)].first;
        test::patternSearch(F, v, f, 12, LD(1e-11));
        candidates.push_back(v);
      }

      for (const V3& u : candidates) {
        const Vector3<double> v = u.cast<double>().normalized();
        const Vector3<double> a = A.evaluate(v).point;
        const double f = double(v.cast<LD>().dot(a.cast<LD>()) + h_b(V3(-v.cast<LD>())));
        const double out = outside(Vector3<double>(a - f * v));
        if (!(f >= 0) || !(out <= tolerance)) continue;
        ++tried;
        const bool is_depth = f <= depth + 1e-9 * size_max;
        if (!is_depth) ++wrong_without_ball;
        if (!twoBallsCertified(shape, c.X_WA, v, a, f, outside, rollingRadius(shape), tolerance)) {
          continue;
        }
        ++certified;
        if (!localBallCertified(shape, c.X_WA, v, a, f, tolerance - std::max(out, 0.0))) {
          ++needs_other;
        }
        if (creased) ++creased_certified;
        worst = std::max(worst, (f - depth) / size_max);
        EXPECT_TRUE(is_depth) << "trial " << trial << ", " << name << ": certified F " << f
                              << ", depth " << depth << ", exponents " << double(c.shape.e1) << ", "
                              << double(c.shape.e2);
      }
    }
  }
  std::cout << "two balls: " << tried << " candidates with b inside, " << certified
            << " certified (" << creased_certified << " on creased shapes, " << needs_other
            << " only with the other shape's ball; worst " << worst << " × size above the depth), "
            << wrong_without_ball << " not the depth\n";
  EXPECT_GT(certified, 100);
  EXPECT_GT(needs_other, 10);
  EXPECT_GT(creased_certified, 50);
  EXPECT_GT(wrong_without_ball, 20);
}

// The other shape's ball on its own (insideBall): tangent to a box's face, a cylinder's disc or
// side, a cone's base or side at a random point b, along the inward normal v, with the test's
// outsideOf. Ground truth by construction, in closed form: the largest such ball's radius (a
// box's face: the least of its half thickness and b's distances to the other faces' planes; a
// disc: of the half height and b's distance to the side; a side: of the radius and b's distance
// to the discs; a cone's base: 2h·(r − ρ_b)/(slant + r), ρ_b b's distance to the axis; a cone's
// side: the least of the radius that reaches the base and the one that reaches the axis). The
// radius found may not exceed it (by more than the 1e-12 × size budget) and must reach it to
// 1e-7 of the longest radius searched (the bisection's 24 halvings); the ball it gives lies in the
// shape at 200 points of its sphere, by the shapes' own inequalities. At a cylinder's rim (v
// between the disc's and the side's normals) there is no ball.
TEST(RollingCertificate, InsideBallLiesInsideTheOtherShape) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> length(0.2, 4.0), unit(0.0, 1.0);
  const std::vector<V3> lattice = test::fibonacciLattice(200);
  int balls = 0, rims = 0;
  for (int trial = 0; trial < 30; ++trial) {
    fcl::Transform3d X = fcl::Transform3d::Identity();
    X.linear() = test::randomRotation(rng).cast<double>();
    X.translation() = Vector3<double>(unit(rng), unit(rng), unit(rng)) * 3.0;
    const Vector3<double> sides(length(rng), length(rng), length(rng));
    const fcl::Boxd box(sides);
    const fcl::Cylinderd cylinder(sides[0] / 2, sides[1]);
    const fcl::Coned cone(sides[0] / 2, sides[1]);
    const double r = sides[0] / 2, h = sides[1] / 2, slant = std::hypot(2 * h, r);
    const double size = sides.norm(), budget = 0.5e-12 * size;
    for (int k = 0; k < 12; ++k) {
      // b and the inward v in the shape's frame, and the largest radius, for one of six cases.
      const int which = k % 6;
      const fcl::CollisionGeometryd& g =
          which == 0   ? static_cast<const fcl::CollisionGeometryd&>(box)
          : which <= 2 ? static_cast<const fcl::CollisionGeometryd&>(cylinder)
                       : static_cast<const fcl::CollisionGeometryd&>(cone);
      const double theta = 2 * M_PI * unit(rng), c = std::cos(theta), s = std::sin(theta);
      Vector3<double> b, v;
      double largest = 0;
      if (which == 0) {
        const int i = std::min(2, int(3 * unit(rng)));  // the face's axis
        const double sign = unit(rng) < 0.5 ? -1 : 1;
        b = (Vector3<double>(unit(rng), unit(rng), unit(rng)) * 2 - Vector3<double>::Ones())
                .cwiseProduct(sides / 2);
        b[i] = sign * sides[i] / 2;
        v = -sign * Vector3<double>::Unit(i);
        largest = sides[i] / 2;
        for (int j = 0; j < 3; ++j) {
          if (j != i) largest = std::min(largest, sides[j] / 2 - std::abs(b[j]));
        }
      } else if (which == 1) {  // a cylinder's disc
        const double rho = r * std::sqrt(unit(rng)), sign = unit(rng) < 0.5 ? -1 : 1;
        b = Vector3<double>(rho * c, rho * s, sign * h);
        v = Vector3<double>(0, 0, -sign);
        largest = std::min(h, r - rho);
      } else if (which == 2) {  // a cylinder's side
        const double z = h * (2 * unit(rng) - 1);
        b = Vector3<double>(r * c, r * s, z);
        v = Vector3<double>(-c, -s, 0);
        largest = std::min(r, h - std::abs(z));
      } else if (which == 3 || which == 4) {  // a cone's base
        const double rho = r * std::sqrt(unit(rng));
        b = Vector3<double>(rho * c, rho * s, -h);
        v = Vector3<double>(0, 0, 1);
        largest = 2 * h * (r - rho) / (slant + r);
      } else {  // a cone's side, at height z: its radius there r·(h − z)/(2h)
        const double z = h * (2 * unit(rng) - 1), rho = r * (h - z) / (2 * h);
        b = Vector3<double>(rho * c, rho * s, z);
        v = -Vector3<double>(2 * h * c, 2 * h * s, r) / slant;
        largest = std::min((z + h) / (1 + r / slant), rho * slant / (2 * h));
      }
      const Vector3<double> b_W = X * b, v_W = X.linear() * v;
      auto outside = [&](const Vector3<double>& x) { return outsideOf(g, X, x); };
      const double most = 2 * size;
      const std::optional<InsideBall> ball = insideBall(outside, b_W, v_W, most, budget);
      ASSERT_TRUE(ball.has_value()) << "trial " << trial << ", case " << which;
      ++balls;
      EXPECT_LE(ball->radius, largest + 1e-12 * size) << "trial " << trial << ", case " << which;
      EXPECT_GE(ball->radius, largest - 1e-7 * most) << "trial " << trial << ", case " << which;
      EXPECT_LE(ball->deficit, budget);
      const Vector3<double> centre = b + ball->radius * v;
      const double radius = ball->radius - ball->deficit;
      for (const V3& w : lattice) {
        const Vector3<double> p = centre + radius * w.cast<double>();
        const double radial = std::hypot(p[0], p[1]), slack = 1e-12 * size;
        const bool in = which == 0 ? ((p.cwiseAbs() - sides / 2).array() <= slack).all()
                        : which <= 2
                            ? radial <= r + slack && std::abs(p[2]) <= h + slack
                            : p[2] >= -h - slack && radial <= r * (h - p[2]) / (2 * h) + slack;
        ASSERT_TRUE(in) << "trial " << trial << ", case " << which << ": radius " << radius;
      }
      if (which == 1) {  // the disc's rim, v between the disc's and the side's inward normals
        const double t = unit(rng);
        const Vector3<double> rim(r * c, r * s, h),
            inward = Vector3<double>(-t * c, -t * s, -(1 - t)).normalized();
        const std::optional<InsideBall> none = insideBall(
            outside, Vector3<double>(X * rim), Vector3<double>(X.linear() * inward), most, budget);
        ASSERT_TRUE(none.has_value());
        EXPECT_LE(none->radius - none->deficit, 2 * budget) << "trial " << trial;
        ++rims;
      }
    }
  }
  std::cout << "inside balls: " << balls << " tangent balls, " << rims << " rims\n";
}

// The local ball's claim on its own: where localBallCertified accepts the ball of radius f
// tangent at a surface point a (outward normal v), centred at a − f·v, every point of it is
// inside the superellipsoid. Exponents in [0.1, 1.9], radii from 0.001 to 0.6 × the smallest
// semi-axis. Ground truth in long double from the implicit function
// G = ((|x/a1|^(2/ε1) + |y/a2|^(2/ε1))^(ε1/ε2) + |z/a3|^(2/ε2)) (the construction's point and
// normal, pair_construction.h): its largest value on the ball's sphere, by a 200-direction lattice
// and a pattern search from the best three, must stay at most 1 (to 1e-9). The balls it refuses
// include some the lattice alone finds poking out (the bound has teeth) and some that fit.
TEST(RollingCertificate, LocalBallLiesInsideTheShape) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> size(0.5, 5.0);
  int accepted = 0, refused_outside = 0, refused_inside = 0;
  LD worst = 0;
  const std::vector<V3> lattice = test::fibonacciLattice(200);
  for (int trial = 0; trial < 40; ++trial) {
    const LD scale = LD(size(rng));
    const test::Construction c = test::constructShape(rng, scale, 0.1, 1.9);
    const test::RandomShape& s = c.shape;
    const Superellipsoidd shape = superellipsoidOf(s);
    const test::M3 R = c.X_WA.linear().cast<LD>();
    const V3 t = c.X_WA.translation().cast<LD>();
    auto G = [&](const V3& p_W) {
      const V3 p = R.transpose() * (p_W - t);
      const LD xy = std::pow(std::abs(p[0] / s.radii[0]), 2 / s.e1) +
                    std::pow(std::abs(p[1] / s.radii[1]), 2 / s.e1);
      return std::pow(xy, s.e1 / s.e2) + std::pow(std::abs(p[2] / s.radii[2]), 2 / s.e2);
    };
    for (int point = 0; point < 20; ++point) {
      const test::SurfacePoint q = test::randomSurfacePoint(s, rng);
      const V3 a = R * q.x + t, n = R * q.n;
      for (double k : {0.001, 0.01, 0.05, 0.1, 0.3, 0.6}) {
        const LD f = LD(k) * s.radii.minCoeff();
        const V3 centre = a - f * n;
        auto on_sphere = [&](const V3& w) { return G(V3(centre + f * w.normalized())); };
        std::vector<std::pair<LD, V3>> samples;
        for (const V3& w : lattice) samples.push_back({on_sphere(w), w});
        std::partial_sort(samples.begin(), samples.begin() + 3, samples.end(),
                          [](const auto& x, const auto& y) { return x.first > y.first; });
        const bool ok = localBallCertified(shape, c.X_WA, Vector3<double>(n.cast<double>()),
                                           Vector3<double>(a.cast<double>()), double(f),
                                           1e-12 * double(s.radii.maxCoeff()));
        if (!ok) {
          ++(samples[0].first > 1 + 1e-9 ? refused_outside : refused_inside);
          continue;
        }
        ++accepted;
        LD highest = samples[0].first;
        for (int j = 0; j < 3; ++j) {
          V3 w = samples[std::size_t(j)].second;
          LD minus = -samples[std::size_t(j)].first;
          test::patternSearch([&](const V3& x) { return -on_sphere(x); }, w, minus, 12, LD(1e-9));
          highest = std::max(highest, -minus);
        }
        worst = std::max(worst, highest - 1);
        EXPECT_LE(highest, 1 + 1e-9)
            << "trial " << trial << ", exponents " << double(s.e1) << ", " << double(s.e2)
            << ", radius " << k << " × the smallest semi-axis";
      }
    }
  }
  std::cout << "local ball: " << accepted << " balls accepted (largest G on them 1 + "
            << double(worst) << "), " << refused_outside << " refused that poke out, "
            << refused_inside << " refused that fit by the lattice\n";
  EXPECT_GT(accepted, 500);
  EXPECT_GT(refused_outside, 100);
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
