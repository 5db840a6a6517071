// The superellipsoid against FCL's shapes and another superellipsoid, through the front end
// and FCL's tables, both argument orders. Ground truth by construction (test_support/
// pair_construction.h: a known distance and known witnesses). Penetration depths of smooth pairs
// are checked against a long-double search over the sphere of directions of the Minkowski
// difference's support function (its supports written in pair_construction.h, from
// docs/math.md); those of polytopes also against an enumeration of the polytope's features
// (polytope_depth.h).

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
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
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "fcl_superellipsoid/fcl_integration.h"
#include "pair_construction.h"
#include "polytope_depth.h"
#include "round_depth.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

using namespace test;  // pair_construction.h

template <typename S>
std::shared_ptr<Superellipsoid<S>> makeShape(const RandomShape& s) {
  return std::make_shared<Superellipsoid<S>>(Vector3<S>(s.radii.cast<S>()), S(s.e1), S(s.e2));
}

struct Answer {
  double distance;
  Vector3<double> on_shape, on_other;
  std::size_t contacts;
  Vector3<double> normal;  // from the shape to the other, if a contact
  double depth;
};

/// The front end's answer and FCL's table's, in both orders, with the shape's witness and the
/// other's sorted back; expects the four to agree with each other to `agree` (and on the
/// contact, unless the shapes touch).
template <typename S>
Answer ask(const std::shared_ptr<fcl::CollisionGeometry<S>>& shape, const fcl::Transform3<S>& X_WA,
           const std::shared_ptr<fcl::CollisionGeometry<S>>& other, const fcl::Transform3<S>& X_WB,
           double agree, bool touching = false) {
  fcl::CollisionObject<S> a(shape, X_WA), b(other, X_WB);
  fcl::detail::GJKSolver_libccd<S> solver;
  Answer first{};
  bool have = false;
  for (bool front : {true, false}) {
    for (bool shape_first : {true, false}) {
      const fcl::CollisionObject<S>* o1 = shape_first ? &a : &b;
      const fcl::CollisionObject<S>* o2 = shape_first ? &b : &a;
      fcl::DistanceRequest<S> request(true, true);
      fcl::DistanceResult<S> result;
      if (front) {
        fcl_superellipsoid::distance(o1, o2, request, result);
      } else {
        fcl::distance(o1, o2, &solver, request, result);
      }
      fcl::CollisionResult<S> contacts;
      const fcl::CollisionRequest<S> crequest(1, true);
      if (front) {
        fcl_superellipsoid::collide(o1, o2, crequest, contacts);
      } else {
        fcl::collide(o1, o2, &solver, crequest, contacts);
      }
      Answer ans{};
      ans.distance = result.min_distance;
      ans.on_shape = result.nearest_points[shape_first ? 0 : 1].template cast<double>();
      ans.on_other = result.nearest_points[shape_first ? 1 : 0].template cast<double>();
      ans.contacts = contacts.numContacts();
      if (ans.contacts > 0) {
        const auto& c = contacts.getContact(0);
        ans.normal = (shape_first ? c.normal : Vector3<S>(-c.normal)).template cast<double>();
        ans.depth = c.penetration_depth;
      }
      EXPECT_TRUE(std::isfinite(ans.distance));
      if (!have) {
        first = ans;
        have = true;
      } else {
        EXPECT_NEAR(ans.distance, first.distance, agree);
        // Touching, contact or not are both right: the sign is rounding's.
        if (!touching) EXPECT_EQ(ans.contacts, first.contacts);
      }
    }
  }
  return first;
}

// Separated superellipsoid pairs and superellipsoid–ellipsoid pairs: distance, witnesses and
// normal against the construction, to the targets (1e-10 × size, 1e-8 rad).
TEST(ShapePairs, SeparatedSmoothPairsMatchTheConstruction) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> gap(0.001, 1.0), size(0.5, 50.0);
  double worst_distance = 0, worst_witness = 0, worst_normal = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const LD scale = LD(size(rng));
    const Construction c = constructShape(rng, scale);
    const bool ellipsoid = trial % 3 == 2;
    RandomShape partner = randomShape(rng, scale * LD(size(rng)) / 25);
    if (ellipsoid) partner.e1 = partner.e2 = 1;
    const SurfacePoint b = randomSurfacePoint(partner, rng);
    const LD d = LD(gap(rng)) * scale;
    const fcl::Transform3d X_WB = placePartner(c, d, b.x, b.n, rng);
    std::shared_ptr<fcl::CollisionGeometryd> other;
    if (ellipsoid) {
      other = std::make_shared<fcl::Ellipsoidd>(Vector3<double>(partner.radii.cast<double>()));
    } else {
      other = makeShape<double>(partner);
    }
    const double size_max = std::max<double>(c.shape.radii.maxCoeff(), partner.radii.maxCoeff());
    const Answer r = ask<double>(makeShape<double>(c.shape), c.X_WA, other, X_WB, 1e-10 * size_max);
    const double e_d = std::abs(r.distance - double(d)) / size_max;
    const double e_w = std::max((r.on_shape - c.a.cast<double>()).norm(),
                                (r.on_other - (c.a + d * c.u).cast<double>()).norm()) /
                       size_max;
    const Vector3<double> n = (r.on_other - r.on_shape).normalized();
    // (The chord, not acos: acos near 1 resolves only √ε ≈ 1.5e-8 rad.)
    const double e_n = (n - c.u.cast<double>()).norm();
    worst_distance = std::max(worst_distance, e_d);
    worst_witness = std::max(worst_witness, e_w);
    worst_normal = std::max(worst_normal, e_n);
    EXPECT_LE(e_d, 1e-10) << "trial " << trial;
    EXPECT_LE(e_w, 1e-10) << "trial " << trial;
    EXPECT_LE(e_n, 1e-8) << "trial " << trial;
    EXPECT_EQ(r.contacts, 0u);
  }
  std::cout << "separated smooth pairs: worst distance " << worst_distance << " × size, witness "
            << worst_witness << " × size, normal " << worst_normal << " rad\n";
}

// Overlapping superellipsoids (and ellipsoids): the depth is the shortest separating
// translation, against the long-double search; the contact's normal and depth agree with the
// signed distance; collide finds the contact in both orders.
TEST(ShapePairs, PenetratingSmoothPairsMatchTheReference) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> depth(0.01, 0.5), size(0.5, 5.0);
  double worst = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const LD scale = LD(size(rng));
    const Construction c = constructShape(rng, scale);
    RandomShape partner = randomShape(rng, scale);
    if (trial % 4 == 3) partner.e1 = partner.e2 = 1;
    const SurfacePoint b = randomSurfacePoint(partner, rng);
    const double size_max = std::max<double>(c.shape.radii.maxCoeff(), partner.radii.maxCoeff());
    const fcl::Transform3d X_WB =
        placePartner(c, -LD(depth(rng)) * c.shape.radii.minCoeff(), b.x, b.n, rng);
    std::shared_ptr<fcl::CollisionGeometryd> other;
    if (trial % 4 == 3) {
      other = std::make_shared<fcl::Ellipsoidd>(Vector3<double>(partner.radii.cast<double>()));
    } else {
      other = makeShape<double>(partner);
    }
    const LD expected = -referenceDepth(supportFunction(*makeShape<double>(c.shape), c.X_WA),
                                        supportFunction(*other, X_WB));
    const Answer r = ask<double>(makeShape<double>(c.shape), c.X_WA, other, X_WB, 1e-9 * size_max);
    ASSERT_LT(expected, 0) << "trial " << trial;
    const double e = std::abs(r.distance - double(expected)) / size_max;
    worst = std::max(worst, e);
    EXPECT_LE(e, 1e-9) << "trial " << trial << ": " << r.distance << " vs " << double(expected);
    ASSERT_EQ(r.contacts, 1u) << "trial " << trial;
    EXPECT_NEAR(r.depth, -r.distance, 1e-12 * size_max);
    // Moving the other shape by depth along the normal leaves them touching: the witnesses'
    // difference is that translation.
    EXPECT_LE((r.on_shape - r.on_other - r.depth * r.normal).norm(), 1e-9 * size_max);
  }
  std::cout << "penetrating smooth pairs: worst depth error " << worst << " × size\n";
}

// Halfspace and plane: the construction (the tangent plane at a, moved by d along u) in both
// signs, to rounding; a plane the shape straddles is left on the side of the shorter move.
TEST(ShapePairs, HalfspaceAndPlaneAreClosedForms) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> gap(-0.5, 1.0), size(0.01, 100.0);
  for (int trial = 0; trial < 200; ++trial) {
    const LD scale = LD(size(rng));
    const Construction c = constructShape(rng, scale);
    const LD d = LD(gap(rng)) * c.shape.radii.minCoeff();
    const double size_max = double(c.shape.radii.maxCoeff());
    // The halfspace −u·x ≤ −(u·a + d): its boundary is the tangent plane moved by d.
    const Vector3<double> n = -c.u.cast<double>();
    const double offset = double(-(c.u.dot(c.a) + d));
    const fcl::Transform3d X_WO = pose<double>(randomRotation(rng), V3::Zero());
    const Vector3<double> n_O = X_WO.linear().transpose() * n;
    const auto halfspace = std::make_shared<fcl::Halfspaced>(n_O, offset);
    const Answer h =
        ask<double>(makeShape<double>(c.shape), c.X_WA, halfspace, X_WO, 1e-14 * size_max);
    EXPECT_NEAR(h.distance, double(d), 4e-15 * size_max) << "trial " << trial;
    EXPECT_LE((h.on_shape - c.a.cast<double>()).norm(), 1e-13 * size_max);
    EXPECT_EQ(h.contacts, d < 0 ? 1u : 0u);
    if (h.contacts == 1) {
      EXPECT_LE((h.normal - c.u.cast<double>()).norm(), 1e-14);
      EXPECT_NEAR(h.depth, -double(d), 4e-15 * size_max);
    }
    // The same plane, two-sided: above it the same distance; straddling, the shorter way out.
    const auto plane = std::make_shared<fcl::Planed>(n_O, offset);
    const Answer p = ask<double>(makeShape<double>(c.shape), c.X_WA, plane, X_WO, 1e-14 * size_max);
    const V3 u = c.u;
    // The shape's extent along u: from the far side's support to a.
    const M3 RA = c.X_WA.linear().cast<LD>();
    const LD width =
        superellipsoidSupport(c.shape.radii, c.shape.e1, c.shape.e2, RA.transpose() * u) +
        superellipsoidSupport(c.shape.radii, c.shape.e1, c.shape.e2, RA.transpose() * (-u));
    const LD expected = d >= 0 ? d : std::max(d, -width - d);
    EXPECT_NEAR(p.distance, double(expected), 1e-14 * size_max) << "trial " << trial;
    EXPECT_EQ(p.contacts, expected < 0 ? 1u : 0u);
  }
}

// Box, capsule, cylinder, cone, convex and triangle, on vertices, edges, rims, faces, sides and
// the apex: separated, the distance and both witnesses match the construction to the issue's
// 1e-10 × size; overlapping, the depth is never more than the construction's overlap nor than a
// long-double search's over directions; the four ways of asking agree, and distance and collide
// agree on the sign.
TEST(ShapePairs, ShapesWithFlatFacesAndEdgesMatchTheConstruction) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> gap(-0.3, 1.0), size(0.5, 5.0);
  std::map<std::string, double> worst, worst_depth;
  for (int trial = 0; trial < 60; ++trial) {
    const LD scale = LD(size(rng));
    const Construction c = constructShape(rng, scale);
    for (const FlatPartner& partner : flatPartners(rng, scale)) {
      const LD d = LD(gap(rng)) * scale * LD(0.1);
      const fcl::Transform3d X_WB = placePartner(c, d, partner.b_L, partner.m_L, rng);
      const double size_max = 2 * double(scale);
      const Answer r =
          ask<double>(makeShape<double>(c.shape), c.X_WA, partner.geometry, X_WB, 1e-4 * size_max);
      EXPECT_TRUE(r.on_shape.allFinite() && r.on_other.allFinite());
      if (d > 0) {
        const double e = std::abs(r.distance - double(d)) / size_max;
        const double e_w = std::max((r.on_shape - c.a.cast<double>()).norm(),
                                    (r.on_other - (c.a + d * c.u).cast<double>()).norm()) /
                           size_max;
        worst[partner.name] = std::max({worst[partner.name], e, e_w});
        EXPECT_LE(e, 1e-10) << partner.name << " trial " << trial;
        EXPECT_LE(e_w, 1e-10) << partner.name << " trial " << trial;
        EXPECT_EQ(r.contacts, 0u) << partner.name << " trial " << trial;
      } else if (d < -1e-3 * scale) {
        // Overlapping along u by |d| at least: the depth is positive and at most |d|. Every
        // direction's F is a separating translation, so both our depth and the long-double
        // search's are upper bounds on the true depth; on these kinked F (the search's pattern
        // stalls on the kinks where the other shape's supporting feature changes) ours must be
        // no deeper than the search's.
        EXPECT_LT(r.distance, 0) << partner.name << " trial " << trial;
        EXPECT_GE(r.distance, double(d) - 1e-12 * size_max) << partner.name << " trial " << trial;
        EXPECT_EQ(r.contacts, 1u) << partner.name << " trial " << trial;
        if (trial % 3 == 0) {  // (the search costs milliseconds)
          const LD search = -referenceDepth(supportFunction(*makeShape<double>(c.shape), c.X_WA),
                                            supportFunction(*partner.geometry, X_WB), 2000);
          const double behind = (double(search) - r.distance) / size_max;  // > 0: ours deeper
          worst_depth[partner.name] = std::max(worst_depth[partner.name], behind);
          EXPECT_LE(behind, 1e-12) << partner.name << " trial " << trial << ": " << r.distance
                                   << " vs " << double(search);
        }
        EXPECT_NEAR(r.depth, -r.distance, 1e-12 * size_max);
        EXPECT_LE((r.on_shape - r.on_other - r.depth * r.normal).norm(), 1e-9 * size_max);
      }
    }
  }
  for (const auto& [name, e] : worst)
    std::cout << name << ": worst distance or witness error " << e << " × size\n";
  for (const auto& [name, e] : worst_depth)
    std::cout << name << ": most depth beyond the search's " << e << " × size\n";
}

/// Ours against an exact depth by enumeration (`enumerated(h_a, partner, X_WB)`), on overlapping
/// partners of `names` (flatPartners), overlapping by `gap` × 0.1 × size: what holds for every
/// pair: ours is a real separating translation, so never shallower than the enumeration, and the
/// enumeration is never above the pattern search (a check of the reference); and ours is the
/// enumerated depth to 1e-9 × size (the worst per partner is printed). The environment variables
/// PREFIX_TRIALS (default `trials`) and PREFIX_SEED (default 41) give a larger sample. The
/// superellipsoid's exponents are drawn from `exponents`; `gap(rng)` draws the gap.
template <typename Gap>
void expectTheEnumeratedDepth(
    const std::vector<std::string>& names, const std::string& prefix, Gap gap,
    const std::function<LD(const std::function<LD(const V3&)>&, const fcl::CollisionGeometryd&,
                           const fcl::Transform3d&)>& enumerated_depth,
    int default_trials = 20, std::pair<double, double> exponents = {0.1, 1.9}) {
  const char* trials_env = std::getenv((prefix + "_TRIALS").c_str());
  const char* seed_env = std::getenv((prefix + "_SEED").c_str());
  const int trials = trials_env != nullptr ? std::atoi(trials_env) : default_trials;
  std::mt19937 rng(seed_env != nullptr ? std::atoi(seed_env) : 41);
  std::uniform_real_distribution<double> size(0.5, 5.0);
  std::map<std::string, double> worst;
  int checked = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const LD scale = LD(size(rng));
    const Construction c = constructShape(rng, scale, exponents.first, exponents.second);
    for (const FlatPartner& partner : flatPartners(rng, scale)) {
      const std::string name = partner.name;
      const LD d = LD(gap(rng)) * scale * LD(0.1);
      const fcl::Transform3d X_WB = placePartner(c, d, partner.b_L, partner.m_L, rng);
      if (std::find(names.begin(), names.end(), name) == names.end()) continue;
      const double size_max = 2 * double(scale);
      const Answer r =
          ask<double>(makeShape<double>(c.shape), c.X_WA, partner.geometry, X_WB, 1e-4 * size_max);
      const auto h_a = supportFunction(*makeShape<double>(c.shape), c.X_WA);
      const LD enumerated = enumerated_depth(h_a, *partner.geometry, X_WB);
      const LD searched = referenceDepth(h_a, supportFunction(*partner.geometry, X_WB), 2000);
      EXPECT_LE(double(enumerated), double(searched) + 1e-12 * size_max) << name << " " << trial;
      // Our distance is −(our depth): never above −(the enumerated depth).
      EXPECT_LE(r.distance, -double(enumerated) + 1e-12 * size_max) << name << " " << trial;
      const double e = std::abs(r.distance + double(enumerated)) / size_max;
      worst[name] = std::max(worst[name], e);
      EXPECT_LE(e, 1e-9) << name << " trial " << trial << ": " << r.distance << " vs "
                         << -double(enumerated);
      ++checked;
    }
  }
  EXPECT_EQ(checked, int(names.size()) * trials);
  for (const auto& [name, e] : worst)
    std::cout << name << ": worst depth error " << e << " × size\n";
}

// Overlapping polytopes (box, convex, triangle) against the depth by enumeration of the
// polytope's faces, edges and vertices (test_support/polytope_depth.h), which does not stall on
// F's kinks as the pattern search does. Not the face variants (exact in the other tests: a face's
// normal is a candidate), nor the round shapes. A larger sample: FSE_POLYTOPE_TRIALS=60
// FSE_POLYTOPE_SEED=43 (each seed's 60 trials take about a minute).
TEST(ShapePairs, PolytopeOverlapsAgainstTheEnumeratedDepth) {
  expectTheEnumeratedDepth({"box", "convex", "triangle"}, "FSE_POLYTOPE",
                           std::uniform_real_distribution<double>(-0.3, -0.01),
                           [](const auto& h_a, const auto& g, const auto& X) {
                             return polytopeDepth(h_a, polytopeVertices(g, X));
                           });
}

// Overlapping cylinders and cones against the depth by enumeration of their smooth pieces (rims,
// the apex: test_support/round_depth.h), overlapping by 0.001 to 0.1 × size (the benchmark's
// deepest bucket). A larger sample: FSE_ROUND_TRIALS=60 FSE_ROUND_SEED=43.
TEST(ShapePairs, RoundOverlapsAgainstTheEnumeratedDepth) {
  expectTheEnumeratedDepth({"cylinder", "cone"}, "FSE_ROUND",
                           std::uniform_real_distribution<double>(-1.0, -0.01), roundDepth);
}

// Overlaps shallower than 1e-3 × size, where resting bodies are (1e-8 to 1e-3 × size, spread
// evenly in the logarithm), on every flat and round partner at each of its features (faces, sides
// and discs too) and exponents 0.1–1.9: the start-free candidates' certified depth is the answer
// there too (feature_pair.h), against the enumerations.
TEST(ShapePairs, ShallowOverlapsAgainstTheEnumeratedDepth) {
  const auto gap = [](std::mt19937& rng) {
    return -std::pow(10.0, std::uniform_real_distribution<double>(-7.0, -2.0)(rng));
  };
  expectTheEnumeratedDepth({"box", "convex", "triangle", "box face", "triangle face"},
                           "FSE_SHALLOW_POLYTOPE", gap,
                           [](const auto& h_a, const auto& g, const auto& X) {
                             return polytopeDepth(h_a, polytopeVertices(g, X));
                           });
  expectTheEnumeratedDepth(
      {"cylinder", "cone", "cylinder side", "cylinder disc", "cone side", "cone apex"},
      "FSE_SHALLOW_ROUND", gap, roundDepth);
}

// Rounded superellipsoids (exponents ≤ 1), whose rolling ball certifies many of these overlaps
// before the vertices' and rims' point queries (rolling_certificate.h), against the same
// enumerations, overlapping by 0.001 to 0.1 × size.
TEST(ShapePairs, RoundedOverlapsAgainstTheEnumeratedDepth) {
  const std::uniform_real_distribution<double> gap(-1.0, -0.01);
  expectTheEnumeratedDepth({"box", "convex", "triangle"}, "FSE_ROUNDED_POLYTOPE", gap,
                           [](const auto& h_a, const auto& g, const auto& X) {
                             return polytopeDepth(h_a, polytopeVertices(g, X));
                           },
                           10, {0.3, 1.0});
  expectTheEnumeratedDepth({"cylinder", "cone"}, "FSE_ROUNDED_ROUND", gap, roundDepth, 10,
                           {0.3, 1.0});
}

/// A pose from its rotation's rows and its translation (the replayed overlaps below).
fcl::Transform3d replayPose(const std::array<double, 9>& r, const V3& t) {
  fcl::Transform3d X = fcl::Transform3d::Identity();
  X.linear() << r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8];
  X.translation() = t.cast<double>();
  return X;
}

/// An overlap replayed exactly (hex floats): the shape and the other geometry, posed.
struct ReplayedOverlap {
  std::shared_ptr<Superellipsoidd> shape;
  fcl::Transform3d X_WA, X_WB;
  std::shared_ptr<fcl::CollisionGeometryd> other;
};

/// A replayed overlap of the shape and a polytope: ours is the enumerated depth
/// (test_support/polytope_depth.h) to 1e-9 × size.
void expectTheEnumeratedPolytopeDepth(const ReplayedOverlap& c) {
  const double size = 2 * c.shape->radii().maxCoeff();
  const Answer r = ask<double>(c.shape, c.X_WA, c.other, c.X_WB, 1e-4 * size);
  const LD enumerated =
      polytopeDepth(supportFunction(*c.shape, c.X_WA), polytopeVertices(*c.other, c.X_WB));
  ASSERT_GT(enumerated, 0);
  EXPECT_NEAR(r.distance, -double(enumerated), 1e-9 * size) << *c.shape;
}

/// A replayed overlap of the shape and a cylinder or cone: ours is the enumerated depth
/// (test_support/round_depth.h) to 1e-9 × size.
void expectTheEnumeratedRoundDepth(const std::shared_ptr<Superellipsoidd>& shape,
                                   const fcl::Transform3d& X_WA,
                                   const std::shared_ptr<fcl::CollisionGeometryd>& other,
                                   const fcl::Transform3d& X_WB) {
  const double size = 2 * shape->radii().maxCoeff();
  const Answer r = ask<double>(shape, X_WA, other, X_WB, 1e-4 * size);
  const LD enumerated = roundDepth(supportFunction(*shape, X_WA), *other, X_WB);
  ASSERT_GT(enumerated, 0);
  EXPECT_NEAR(r.distance, -double(enumerated), 1e-9 * size);
}

// The two overlaps on which the depth once stopped at a local minimum (1 in 90 of the larger
// sample above, FSE_POLYTOPE_SEED=43: trials 30 and 37), replayed exactly: creased shapes where
// F's minimum lies on an edge's circle of directions, inside the arc where that edge supports the
// polytope, while the circle's own lowest point lies outside the arc, 35° away, with a maximum
// between them. The family search bracketed only its lowest sample and ended 8.6e-5 and 4.4e-8 ×
// size too deep; now every sign change of the derivative is bracketed.
// A capsule through the centre of a box-like superellipsoid (ε1 or ε2 ≤ 0.3), rotated at
// random: the depth's minimiser lies inside an end's region, at a local minimum of that end's
// h_A(v) − v·w below one of the shape's flat faces, while the end's escape direction lies below
// another face (docs/hardening.md, finding 30: the depth came out 2.6e-4 × size too deep).
// Ground truth: the least F found by the enumeration of the capsule's pieces (polytope_depth.h,
// its segment with the ball's radius added to the superellipsoid's support function) and by
// fine pattern searches (64 directions, to 1e-15 rad) from the best 8 of 20,000 lattice
// directions: beside a box-like shape's flat faces F is nearly kinked, and either search alone
// can stop 1e-8 to 3e-5 short. Every direction's F is a translation that separates the shapes,
// so the least found bounds the depth from above, as the library's does: its depth must not
// exceed the truth's by more than 1e-9 × size, nor fall below it. Disabled: finding 30 is open
// (one of the 24 pairs is still 2.5e-6 × size too deep, and the truth stops 3e-8 short on
// another).
TEST(ShapePairs, DISABLED_CapsuleThroughABoxLikeShapesCentre) {
  std::mt19937 rng(30);
  std::uniform_real_distribution<double> unit(-1, 1), box_like(0.1, 0.3), any(0.2, 1.8),
      length(0.2, 1.0), offset(-0.1, 0.1);
  double worst = 0;
  for (int trial = 0; trial < 24; ++trial) {
    RandomShape s = randomShape(rng, 1);
    (trial % 2 == 0 ? s.e1 : s.e2) = LD(box_like(rng));
    (trial % 2 == 0 ? s.e2 : s.e1) = LD(any(rng));
    const auto shape = makeShape<double>(s);
    const V3 centre(unit(rng), unit(rng), unit(rng));
    const fcl::Transform3d X_WA = pose<double>(randomRotation(rng), centre);
    const fcl::Transform3d X_WB = pose<double>(
        randomRotation(rng), centre + V3(LD(offset(rng)), LD(offset(rng)), LD(offset(rng))));
    const double r = 0.5 * length(rng), lz = length(rng);
    const auto capsule = std::make_shared<fcl::Capsuled>(r, lz);
    const V3 axis = X_WB.linear().cast<LD>().col(2) * (LD(lz) / 2);
    const V3 c = X_WB.translation().cast<LD>();
    const std::function<LD(const V3&)> h_a = supportFunction(*shape, X_WA);
    const std::function<LD(const V3&)> h_ball = [&](const V3& w) {
      return h_a(w) + LD(r) * w.norm();
    };
    const std::function<LD(const V3&)> h_segment = [&](const V3& w) {
      return std::max(w.dot(V3(c + axis)), w.dot(V3(c - axis)));
    };
    LD depth = polytopeDepth(h_ball, {V3(c + axis), V3(c - axis)});
    std::vector<std::pair<LD, V3>> starts;
    for (const V3& v : fibonacciLattice(20000))
      starts.push_back({h_ball(v) + h_segment(V3(-v)), v});
    std::partial_sort(starts.begin(), starts.begin() + 8, starts.end(),
                      [](const auto& x, const auto& y) { return x.first < y.first; });
    for (int k = 0; k < 8; ++k) {
      depth = std::min(depth, referenceDepthNear(h_ball, h_segment, starts[k].second, LD(0.05)));
    }
    const LD expected = -depth;
    const double size_max = std::max<double>(s.radii.maxCoeff(), r + lz / 2);
    const Answer got = ask<double>(shape, X_WA, capsule, X_WB, 1e-9 * size_max);
    const double e = (double(expected) - got.distance) / size_max;  // > 0: too deep
    worst = std::max(worst, std::abs(e));
    EXPECT_LE(e, 1e-9) << "trial " << trial << ": " << got.distance << " vs " << double(expected);
    EXPECT_GE(e, -1e-9) << "trial " << trial << ": " << got.distance << " vs " << double(expected);
  }
  std::cout << "capsule through a box-like centre: worst depth error " << worst << " × size\n";
}

TEST(ShapePairs, EdgeCirclesWithSeveralLocalMinima) {
  const std::vector<ReplayedOverlap> cases = {
      {std::make_shared<Superellipsoidd>(0x1.9a48dd9b235d7p+1, 0x1.2c7a3c4e7c0cfp-1,
                                         0x1.7e2c8de9c09cap+0, 0x1.64fcdcdbf38bep+0,
                                         0x1.c7afa2a903808p+0),
       replayPose({0x1.617cd7cdff717p-1, 0x1.13366b423bad8p-3, 0x1.6bf224843777fp-1,
                   0x1.4844209606f9fp-1, -0x1.2336c1d1dffcbp-1, -0x1.07c7a5a17f48cp-1,
                   0x1.571d35be64588p-2, 0x1.9f7503f1c0bcap-1, -0x1.ea5642fff5ef5p-2},
                  V3(-0x1.e9ff81cc8677fp+0, -0x1.e34a057fab4aap-2, 0x1.ea711825505fcp+0)),
       replayPose({0x1.633e12ab03bb8p-2, 0x1.4d57d1ba98f8bp-1, 0x1.59a794b812116p-1,
                   0x1.d8f2dde8ece8ep-1, -0x1.ccf63c5c337fp-4, -0x1.76ee813e6a5fap-2,
                   -0x1.4c9b766541efp-3, 0x1.805367e99409bp-1, -0x1.47e85e2bd2114p-1},
                  V3(-0x1.2a168e283cc8bp+2, 0x1.0e03cfe9ae9d3p+2, 0x1.13f38a3c4594p-1)),
       std::make_shared<fcl::Boxd>(0x1.b155e52a1a53dp+2, 0x1.9ad402683296dp+2,
                                   0x1.4fb189c8489acp+1)},
      {std::make_shared<Superellipsoidd>(0x1.f451f33a0a37fp+0, 0x1.1a15269268d85p+1,
                                         0x1.410672324e105p+1, 0x1.719cde8d726b4p+0,
                                         0x1.95cad1ef043e4p+0),
       replayPose({-0x1.61540e1bc4c9ap-1, -0x1.17cea65d1d4e5p-1, 0x1.e5d7f5fc0cafdp-2,
                   -0x1.b968dcb8daa48p-3, 0x1.8fe2973e9578cp-1, 0x1.2c18d80bd6511p-1,
                   -0x1.61bb11410bdf6p-1, 0x1.3579c96d2e4cfp-2, -0x1.504412b18c935p-1},
                  V3(-0x1.1f9be3ac57fb6p+2, -0x1.7e023c75b4f04p+1, 0x1.2c18b15fbb0c6p+2)),
       replayPose({-0x1.e78730c8d57a6p-7, 0x1.fbe3deb878462p-1, 0x1.012c1e27dcb9dp-3,
                   -0x1.f5aae31a6bb2dp-1, 0x1.5a6af7efd939fp-7, -0x1.98ca8ff89c685p-3,
                   -0x1.983a875ed29b5p-3, -0x1.021083ab8e846p-3, 0x1.f18f5f9cc0e86p-1},
                  V3(-0x1.0c8a836f755fdp+3, 0x1.139c811fd7576p+2, -0x1.ac54806b8972p-1)),
       std::make_shared<fcl::Convexd>(
           std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
               {0x1.39fa77c032055p+2, 0x1.1c4df30cd2aa6p+2, 0x1.6a1cdadf44ee3p+2},
               {0x1.67f1332b183a5p+2, -0x1.1c04e11cd0b1cp+2, -0x1.56c90ad8df75bp+2},
               {-0x1.252f4dafea492p+2, 0x1.10cd61d04a948p+2, -0x1.379fa962b2469p+2},
               {-0x1.6e2a3e795923p+2, -0x1.06aead568f5ap+2, 0x1.5faf0cff5984cp+2}}),
           4,
           std::make_shared<const std::vector<int>>(
               std::vector<int>{3, 0, 1, 2, 3, 0, 3, 1, 3, 0, 2, 3, 3, 1, 3, 2}))},
  };
  for (const ReplayedOverlap& c : cases) expectTheEnumeratedPolytopeDepth(c);
}

// A rounded shape's overlap with a triangle (the larger sample of
// RoundedOverlapsAgainstTheEnumeratedDepth, FSE_ROUNDED_POLYTOPE_SEED=70: trial 25), replayed
// exactly: a (0.47, 1.53, 2.29) shape, ε = (0.57, 0.62), with a triangle's vertex inside it,
// 0.295 from its −x side and 0.305 from its −z face. That vertex's escape direction (to the −x
// side) lies outside the vertex's region, and the descents from it mirrored across each
// coordinate plane end elsewhere; F's minimum is the vertex's local minimum towards the −z face,
// inside its region. Our depth was 2.3e-4 × size too deep (an edge's best); now the vertex also
// descends from each of the shape's axis directions in its region.
TEST(ShapePairs, VertexMinimumBelowAnotherFace) {
  const auto triangle = std::make_shared<fcl::TrianglePd>(
      fcl::Vector3d(0x1.0f3ce6929cbb6p+2, 0, 0),
      fcl::Vector3d(-0x1.0f3ce6929cbb6p+1, 0x1.b1fb0a842df8ap+1, 0),
      fcl::Vector3d(-0x1.0f3ce6929cbb6p+1, -0x1.b1fb0a842df8ap+1, 0));
  expectTheEnumeratedPolytopeDepth(
      {std::make_shared<Superellipsoidd>(0x1.dcc6d81dfbbecp-2, 0x1.8756f0eaeb405p+0,
                                         0x1.25014fb5826f8p+1, 0x1.216499e54a788p-1,
                                         0x1.3db80d739d84dp-1),
       replayPose({-0x1.706e538cbac13p-2, -0x1.dc8c850dd5da4p-1, 0x1.0a824c315b696p-4,
                   -0x1.ea7a3c7a8ceb6p-4, -0x1.7a6453aad37b3p-6, -0x1.fc2dac5e705a7p-1,
                   0x1.d9c2e537c754ap-1, -0x1.75a8c73c91f28p-2, -0x1.a67b0c6e795bap-4},
                  V3(-0x1.a07090bbb3876p+1, 0x1.b18595e58b1d9p+1, 0x1.ec72fd138b1fap+1)),
       replayPose({0x1.adc17338ec25p-1, -0x1.1468b25a0aab9p-2, -0x1.e321375a2cff5p-2,
                   -0x1.9ac929c166ddep-2, -0x1.c961ed0e2c2e3p-1, -0x1.9ee6f0ed85207p-3,
                   -0x1.7798380f2ab6ep-2, 0x1.6ff057c7f7226p-2, -0x1.b75a79964ed05p-1},
                  V3(-0x1.d1d4d1375036ap+2, 0x1.c2bfe3111feccp+2, 0x1.5c414f0a3bb25p+2)),
       triangle});
}

// The cylinder overlap on which the depth once stopped at a local minimum (1 in 360 of the larger
// sample of RoundOverlapsAgainstTheEnumeratedDepth, FSE_ROUND_SEED=49: trial 5), replayed
// exactly. Every start on the rim F's minimum lies on (the rim's deepest points, its least-F
// point, the side's best) descended to a lower minimum of the rim's f_P outside the rim's region,
// where F is not f_P; F's minimum is f_P's second local minimum inside the region, that one's
// mirror image across the side's normals. Our depth was 4.1e-4 × size too deep; now a rim's
// descent that ends outside its region below the best F also descends from its mirror image.
TEST(ShapePairs, RimMinimaMirroredAcrossTheSide) {
  const auto shape = std::make_shared<Superellipsoidd>(0x1.9ed2f19b49a47p+0, 0x1.5102cc15f048ep-2,
                                                       0x1.26b3011eb401ep+1, 0x1.316043113d8aep-1,
                                                       0x1.2e9dc2ac3f736p+0);
  const fcl::Transform3d X_WA =
      replayPose({-0x1.07b9e2de3b306p-1, -0x1.56102d09c7214p-1, -0x1.12ed8623a1f42p-1,
                  -0x1.9f2764c2a1287p-1, 0x1.2a70a7c41dcb4p-1, 0x1.aebfdcbb1778bp-5,
                  0x1.1c8881b13bcdbp-2, 0x1.d99558fb60e34p-2, -0x1.af15a62d2acf6p-1},
                 V3(-0x1.9f4b3f9a4e07cp-3, -0x1.5561cbdf67decp+0, -0x1.5378f23b580dp-3));
  const fcl::Transform3d X_WB =
      replayPose({0x1.6858c36a5bc24p-2, 0x1.b1e5064f70674p-1, 0x1.9705fd050896p-2,
                  0x1.17b5eddd5209ap-2, 0x1.40b481b499b07p-2, -0x1.d1b1d74bcde25p-1,
                  -0x1.ca6405b26923bp-1, 0x1.b6eff9bb7a41fp-2, -0x1.f0bcdeab11d69p-4},
                 V3(-0x1.c9c24014fac95p+0, -0x1.094dbcf72127ep+1, 0x1.31886c1114e9dp+1));
  const auto cylinder =
      std::make_shared<fcl::Cylinderd>(0x1.cb44c8a595b24p+0, 0x1.01cd9445b4736p+1);
  expectTheEnumeratedRoundDepth(shape, X_WA, cylinder, X_WB);
}

// A rim whose f_P has two local minima 0.08 rad apart in elevation, 4.96e-6 × size apart in value
// (the larger sample of RoundOverlapsAgainstTheEnumeratedDepth, FSE_ROUND_SEED=56: trial 27, a
// creased shape (1.38; 1.69) on a cylinder's disc), replayed exactly. Every start (the rim's
// deepest points, its least-F point, the best so far) descended to the minimum farther from the
// rim's axis; F's minimum is the one nearer the axis. Now the rim also descends from halfway
// between the best so far and its axis.
TEST(ShapePairs, RimMinimumNearerTheAxis) {
  const auto shape = std::make_shared<Superellipsoidd>(0x1.1b4ff6857f8d9p+1, 0x1.d22316851579ep-1,
                                                       0x1.06e5cac4558bep+0, 0x1.61cb9eaa66b0ap+0,
                                                       0x1.b1e91acb0ce3fp+0);
  const fcl::Transform3d X_WA =
      replayPose({-0x1.7760d8293e494p-1, -0x1.e193af24c94c2p-3, -0x1.46b620da47711p-1,
                  -0x1.1ad2112f59ae6p-2, 0x1.ebba5a77f4a76p-1, -0x1.2ba860eaeef0fp-5,
                  0x1.3e2dfadf6a7e5p-1, 0x1.32041741913b3p-3, -0x1.89c47d748dcd2p-1},
                 V3(-0x1.151af2b61e379p+1, -0x1.57752d8123f9ap+0, -0x1.7afa7ae2323ap-1));
  const fcl::Transform3d X_WB =
      replayPose({-0x1.e2cd71ccd8ed3p-1, 0x1.0e1ec902cb06p-2, -0x1.9fc753227d38p-3,
                  0x1.54450d828791ap-2, 0x1.9042b211e94bbp-1, -0x1.0e2a7b0306611p-1,
                  0x1.3fc4bb2cc3eaap-6, -0x1.214cb3edd6954p-1, -0x1.a6509d3eab0a9p-1},
                 V3(-0x1.0922a90ca00fep+2, -0x1.7e292878f7f23p+0, -0x1.5b802cb8290d2p+0));
  const auto cylinder =
      std::make_shared<fcl::Cylinderd>(0x1.5ba2c88f176ecp+0, 0x1.120ffc5e106d5p-1);
  expectTheEnumeratedRoundDepth(shape, X_WA, cylinder, X_WB);
}

// Two overlaps where F's minimum is a rim's local minimum near the rim's axis, and the best
// candidate sat at or near the axis (the larger sample of RoundOverlapsAgainstTheEnumeratedDepth),
// replayed exactly: FSE_ROUND_SEED=69, trial 8, a creased shape (1.88; 0.56) on a cone's base,
// the minimum 0.21 rad off the axis and the base's normal the best (5.6e-4 × size too deep);
// FSE_ROUND_SEED=81, trial 55, a shape (0.41; 1.82) on a cylinder's disc, the minimum 0.036 rad
// off the axis and a descent's end 0.019 rad off it the best (4.3e-4 × size too deep). f_P is not
// smooth at the rim's axis, and around it Newton's basins are fragments (of 12 starts tilted
// 0.05–0.5 rad off the cone's axis, 2 to 5 reached the minimum). Now a best within 0.1 rad of a
// rim's axis that the balls do not certify is followed by the rim's meridians, along which F is
// smooth.
TEST(ShapePairs, RimMinimaAroundTheAxisKink) {
  const std::vector<ReplayedOverlap> cases = {
      {std::make_shared<Superellipsoidd>(0x1.95db3f56ff905p+0, 0x1.25900f0caaa76p+1,
                                         0x1.57e59566c329fp+1, 0x1.e17ad113174f6p+0,
                                         0x1.20b27c23be485p-1),
       replayPose({0x1.de5a863bfb1f8p-1, -0x1.f783341d267bbp-4, 0x1.56b2b6cf631c4p-2,
                   0x1.6cfa7075cc966p-2, 0x1.610abe8f3e0ap-2, -0x1.bc9d5009eaf18p-1,
                   -0x1.1ae2a423e81c9p-7, 0x1.dc782591bf5afp-1, 0x1.76b525711cd3ap-2},
                  V3(-0x1.d61e36ebb6d21p-2, -0x1.dbf6dcce4c9d5p+0, 0x1.2971bd810aef1p+0)),
       replayPose({0x1.459e27e4ca889p-2, -0x1.077a21d3e4992p-2, 0x1.d334f2aac689p-1,
                   0x1.b9917a2de29a1p-1, 0x1.e9c2665db7f28p-2, -0x1.534d87222b7ddp-3,
                   -0x1.9342a58993bb4p-2, 0x1.ade90bb4cb753p-1, 0x1.7ef826a9ec747p-2},
                  V3(0x1.44ef52fa3414dp+1, -0x1.7ded33a5b0f05p+0, 0x1.af1be6643380ep+2)),
       std::make_shared<fcl::Coned>(0x1.268d5972f639bp+2, 0x1.38b8aeda0d115p+2)},
      {std::make_shared<Superellipsoidd>(0x1.007b62765013cp+1, 0x1.c457f5299ee31p-2,
                                         0x1.b836fcfde030ep+0, 0x1.9ffcba1da5054p-2,
                                         0x1.d1c2814869fa9p+0),
       replayPose({-0x1.dd59a59025cc7p-2, 0x1.9e5e861dbd047p-1, 0x1.6dee49537c119p-2,
                   0x1.6bd89200684a3p-1, 0x1.2a90a16ce93a4p-1, -0x1.93155d130892ap-2,
                   -0x1.0dcddfeafb80dp-1, 0x1.2090f1e9e5677p-4, -0x1.b1a54ca9cb6eap-1},
                  V3(0x1.8bcf7ee386d16p-1, 0x1.9fb548f2dfb78p+0, 0x1.05f5e798ec0d3p-1)),
       replayPose({0x1.2ebe92f1aa23p-3, -0x1.e12f115e367dap-1, -0x1.3b74101358411p-2,
                   0x1.cde7e7cc60f2ap-1, 0x1.05ea0d910ab41p-2, -0x1.63bca5bde7ab7p-2,
                   0x1.9f02dce3da6c9p-2, -0x1.d0016ce04d648p-3, 0x1.c576a51958bc2p-1},
                  V3(0x1.7c2061df24899p+0, 0x1.c51066df86b32p+0, -0x1.7b449a34aad05p-1)),
       std::make_shared<fcl::Cylinderd>(0x1.2b574ad6fe5afp-1, 0x1.0a488a647c399p-1)},
  };
  for (const ReplayedOverlap& c : cases)
    expectTheEnumeratedRoundDepth(c.shape, c.X_WA, c.other, c.X_WB);
}

// Degenerate configurations stay finite and correct: touching, coincident centres, a flat face
// on a flat face, boxes without a face, far apart (1e6 × size).
TEST(ShapePairs, DegenerateConfigurations) {
  std::mt19937 rng(5);
  // Touching: d = 0 by construction, for a smooth partner and a box.
  for (int trial = 0; trial < 20; ++trial) {
    const Construction c = constructShape(rng, 1);
    const RandomShape partner = randomShape(rng, 1);
    const SurfacePoint b = randomSurfacePoint(partner, rng);
    const fcl::Transform3d X_WB = placePartner(c, 0, b.x, b.n, rng);
    const Answer r = ask<double>(makeShape<double>(c.shape), c.X_WA, makeShape<double>(partner),
                                 X_WB, 1e-12, true);
    EXPECT_LE(std::abs(r.distance), 1e-12) << "trial " << trial;
    EXPECT_TRUE(r.on_shape.allFinite() && r.on_other.allFinite());
  }
  // Coincident centres: the depth is the smallest width, against the long-double search. Here F's
  // minimum is at its flattest and the search's pattern can end above it: under clang our
  // minimum came out 1.3e-9 lower than the search's (a better, real F value). So: never deeper
  // than the search (every F is a separating translation), and shallower by no more than 1e-6
  // (a wrong local minimum would be off by far more).
  for (int trial = 0; trial < 10; ++trial) {
    const RandomShape a = randomShape(rng, 1), b = randomShape(rng, 1);
    const fcl::Transform3d X_WA = pose<double>(randomRotation(rng), V3(0.3, -0.2, 0.1));
    const fcl::Transform3d X_WB = pose<double>(randomRotation(rng), V3(0.3, -0.2, 0.1));
    const LD expected = -referenceDepth(supportFunction(*makeShape<double>(a), X_WA),
                                        supportFunction(*makeShape<double>(b), X_WB));
    const Answer r = ask<double>(makeShape<double>(a), X_WA, makeShape<double>(b), X_WB, 1e-9);
    EXPECT_GE(r.distance, double(expected) - 1e-12) << "trial " << trial;
    EXPECT_LE(r.distance, double(expected) + 1e-6) << "trial " << trial;
    EXPECT_EQ(r.contacts, 1u);
  }
  // A box's face on the flat top of a box-like superellipsoid (ε = 0.1), both faces parallel:
  // the witnesses are not unique on the box, the distance is. The same top against polytopes
  // whose faces are degenerate or flat, so that they do not take the topology a box or triangle
  // shares (polytope_pair.cpp, finishShared) but build their own: a square (a box of height 0),
  // a box 1e-12 thin (its two large faces flat within the tolerance), and a triangle whose
  // corners lie on one line (edges only). Each one's lowest face or edge lies in z = 0.5 + d.
  {
    const auto shape = std::make_shared<Superellipsoidd>(1.0, 0.7, 0.5, 0.1, 0.1);
    struct Partner {
      const char* name;
      std::shared_ptr<fcl::CollisionGeometryd> geometry;
      double half_height;  // of its centre above its lowest face (0 for the flat ones)
    };
    const std::vector<Partner> partners = {
        {"box", std::make_shared<fcl::Boxd>(0.4, 0.4, 0.2), 0.1},
        {"square", std::make_shared<fcl::Boxd>(0.4, 0.4, 0.0), 0.0},
        {"thin box", std::make_shared<fcl::Boxd>(0.4, 0.4, 1e-12), 0.0},
        {"collinear triangle",
         std::make_shared<fcl::TrianglePd>(Vector3<double>(-0.2, 0, 0), Vector3<double>(0.2, 0, 0),
                                           Vector3<double>(0.05, 0, 0)),
         0.0}};
    for (const Partner& partner : partners) {
      for (double d : {0.25, 1e-6, 0.0, -0.05}) {
        const fcl::Transform3d X_WB(fcl::Translation3d(0.1, -0.2, 0.5 + partner.half_height + d));
        const Answer r =
            ask<double>(shape, fcl::Transform3d::Identity(), partner.geometry, X_WB, 1e-12, d == 0);
        EXPECT_NEAR(r.distance, d, d < 0 ? 1e-6 : 1e-12) << partner.name << ", d = " << d;
        if (d != 0) EXPECT_EQ(r.contacts, d < 0 ? 1u : 0u) << partner.name << ", d = " << d;
      }
    }
  }
  // Boxes without a face (two or three sides 0: a segment, a point) overlapping the shape: no
  // point lies inside them, so no candidate's witness may count as inside (every point once did,
  // and a point 0.1 × size deep came out 0.028 × size too deep). Against the long-double search,
  // as for the coincident centres.
  for (const Vector3<double>& sides : {Vector3<double>(0, 0, 2), Vector3<double>(0, 0, 0)}) {
    for (double e : {0.5, 1.0, 1.5}) {
      for (double x : {0.2, 0.5, 0.9}) {
        const auto shape = std::make_shared<Superellipsoidd>(1.0, 1.0, 1.0, e, e);
        const auto box = std::make_shared<fcl::Boxd>(sides);
        const fcl::Transform3d X_WA = fcl::Transform3d::Identity();
        const fcl::Transform3d X_WB(fcl::Translation3d(x, 0.1, 0));
        const LD expected =
            -referenceDepth(supportFunction(*shape, X_WA), supportFunction(*box, X_WB));
        const Answer r = ask<double>(shape, X_WA, box, X_WB, 1e-9);
        const std::string at = "sides " + std::to_string(sides[2]) + ", ε " + std::to_string(e) +
                               ", x " + std::to_string(x);
        EXPECT_GE(r.distance, double(expected) - 1e-12) << at;
        EXPECT_LE(r.distance, double(expected) + 1e-6) << at;
      }
    }
  }
  // Far apart: 1e6 × size, every kind of partner; the distance to its rounding.
  {
    const auto shape = std::make_shared<Superellipsoidd>(1.0, 0.7, 0.5, 0.6, 1.3);
    const double far = 1e6;
    std::vector<std::pair<std::shared_ptr<fcl::CollisionGeometryd>, double>> partners = {
        {std::make_shared<Superellipsoidd>(0.5, 0.5, 0.5, 1.0, 1.0), 0.5},
        {std::make_shared<fcl::Ellipsoidd>(0.5, 0.4, 0.3), 0.5},
        {std::make_shared<fcl::Boxd>(1.0, 1.0, 1.0), 0.5},
        {std::make_shared<fcl::Capsuled>(0.5, 1.0), 0.5},
        {std::make_shared<fcl::Cylinderd>(0.5, 1.0), 0.5},
        {std::make_shared<fcl::Coned>(0.5, 1.0), 0.5}};
    for (const auto& [geometry, reach] : partners) {
      // Along x: the shape reaches 1.0, the partner `reach` (its radius along x; the cone turned
      // so that its base faces the shape).
      fcl::Transform3d X_WB(fcl::Translation3d(far, 0, 0));
      if (geometry->getNodeType() == fcl::GEOM_CONE) {
        X_WB.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3<double>::UnitY()).toRotationMatrix();
      }
      const Answer r = ask<double>(shape, fcl::Transform3d::Identity(), geometry, X_WB, 1e-6);
      EXPECT_NEAR(r.distance, far - 1.0 - reach, 16 * far * std::numeric_limits<double>::epsilon())
          << "node type " << geometry->getNodeType();
    }
  }
}

// A small body lying face down on a far larger flat face (a box-like body on the floor): the
// pair's witnesses may be any points of the two faces, but each must lie on its own body and the
// two must be the distance apart. Both argument orders, the front end and FCL's table.
TEST(ShapePairs, FaceOnFaceWitnessesLieOnTheirBodies) {
  std::mt19937 rng(529);
  std::uniform_real_distribution<double> across(-5, 5), turn(-M_PI, M_PI);
  const auto floor = std::make_shared<Superellipsoidd>(20.0, 20.0, 0.5, 0.1, 0.1);
  const auto small_shape = std::make_shared<Superellipsoidd>(0.3, 0.3, 0.2, 0.1, 0.1);
  const auto small_box = std::make_shared<fcl::Boxd>(0.6, 0.6, 0.4);
  const double tolerance = 1e-9 * 20;
  // How far x (world) lies off body g's surface at X (a superellipsoid's: its gauge in long
  // double, test_helpers.h).
  const auto offSurface = [](const fcl::CollisionGeometryd& g, const fcl::Transform3d& X,
                             const Vector3<double>& x) {
    const Vector3<double> local = X.inverse() * x;
    if (const auto* box = dynamic_cast<const fcl::Boxd*>(&g)) {
      const Vector3<double> outside = local.cwiseAbs() - 0.5 * box->side;
      return std::abs(outside.maxCoeff());
    }
    const auto& shape = dynamic_cast<const Superellipsoidd&>(g);
    return double(std::abs(test::referenceGauge(shape, local) - 1)) * shape.size();
  };
  fcl::detail::GJKSolver_libccd<double> solver;
  for (int trial = 0; trial < 12; ++trial) {
    for (const double gap : {1e-4, 0.05, -5e-3}) {
      for (const std::shared_ptr<fcl::CollisionGeometryd>& small :
           {std::shared_ptr<fcl::CollisionGeometryd>(small_shape),
            std::shared_ptr<fcl::CollisionGeometryd>(small_box)}) {
        const fcl::Transform3d X = pose<double>(randomRotation(rng), V3(0.3, -0.2, 0.1));
        fcl::Transform3d X_FB = fcl::Transform3d::Identity();
        X_FB.linear() = Eigen::AngleAxisd(turn(rng), Vector3<double>::UnitZ()).toRotationMatrix();
        X_FB.translation() = Vector3<double>(across(rng), across(rng), 0.5 + 0.2 + gap);
        const fcl::CollisionObjectd a(floor, X), b(small, X * X_FB);
        for (const bool front : {true, false}) {
          for (const bool floor_first : {true, false}) {
            SCOPED_TRACE(::testing::Message()
                         << "trial " << trial << " gap " << gap << " partner "
                         << (small == small_box ? "box" : "superellipsoid") << " front " << front
                         << " floor first " << floor_first);
            const fcl::CollisionObjectd* o1 = floor_first ? &a : &b;
            const fcl::CollisionObjectd* o2 = floor_first ? &b : &a;
            fcl::DistanceRequestd request(true, true);
            fcl::DistanceResultd result;
            if (front) {
              fcl_superellipsoid::distance(o1, o2, request, result);
            } else {
              fcl::distance(o1, o2, &solver, request, result);
            }
            EXPECT_NEAR(result.min_distance, gap, 1e-9);
            const Vector3<double>& p1 = result.nearest_points[0];
            const Vector3<double>& p2 = result.nearest_points[1];
            EXPECT_LE(offSurface(*o1->collisionGeometry(), o1->getTransform(), p1), tolerance)
                << p1.transpose();
            EXPECT_LE(offSurface(*o2->collisionGeometry(), o2->getTransform(), p2), tolerance)
                << p2.transpose();
            EXPECT_NEAR((p1 - p2).norm(), std::abs(gap), tolerance);
          }
        }
      }
    }
  }
}

// A tetrahedron 1e285 across around a box-like superellipsoid (the fuzzer's input,
// docs/hardening.md, finding 14): libccd's GJK distance, which the overlap path once called,
// aborted the process on an assertion inside libfcl. Every call answers: an overlap, finite.
TEST(ShapePairs, HugeTetrahedronAroundTheShapeNeverAborts) {
  const auto shape =
      std::make_shared<Superellipsoidd>(0x1.7a7bp+3, 0x1.d9d9d9d9d9d9ep+3, 0x1.d9d9d9d9d9ffp+2,
                                        0x1.fffffff676767p-5, 0x1.b3b3b3b3b3b3bp+0);
  const double l = 0x1.69eca45b4b8b8p+948;
  auto vertices = std::make_shared<std::vector<Vector3<double>>>(
      std::vector<Vector3<double>>{{l, l, l}, {l, -l, -l}, {-l, l, -l}, {-l, -l, l}});
  auto faces = std::make_shared<std::vector<int>>(
      std::vector<int>{3, 0, 1, 2, 3, 0, 3, 1, 3, 0, 2, 3, 3, 1, 3, 2});
  const auto tetrahedron = std::make_shared<fcl::Convexd>(vertices, 4, faces);
  fcl::Matrix3d turn;
  turn << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  fcl::Transform3d X_WA = fcl::Transform3d::Identity(), X_WB = fcl::Transform3d::Identity();
  X_WA.linear() = X_WB.linear() = turn;
  X_WA.translation().setConstant(0x1.d9d9d9d9d9d9ep+4);
  X_WB.translation().setConstant(0x1.6363636363636p+5);
  const fcl::CollisionObjectd a(shape, X_WA), b(tetrahedron, X_WB);
  fcl::detail::GJKSolver_libccdd solver;
  for (bool shape_first : {true, false}) {
    const fcl::CollisionObjectd* o1 = shape_first ? &a : &b;
    const fcl::CollisionObjectd* o2 = shape_first ? &b : &a;
    fcl::DistanceRequestd request(true, true);
    request.enable_signed_distance = true;
    fcl::DistanceResultd front, table;
    fcl_superellipsoid::distance(o1, o2, request, front);
    fcl::distance(o1, o2, &solver, request, table);
    for (const fcl::DistanceResultd* r : {&front, &table}) {
      EXPECT_TRUE(std::isfinite(r->min_distance));
      EXPECT_LT(r->min_distance, 0.0) << "the shape is inside the tetrahedron";
    }
    fcl::CollisionResultd contacts;
    fcl_superellipsoid::collide(o1, o2, fcl::CollisionRequestd(1, true), contacts);
    EXPECT_TRUE(contacts.isCollision());
  }
}

// The ends of what the other shape may be (docs/hardening.md, findings 22 and 23): an ellipsoid
// with radii at the superellipsoid's largest (the smooth pair forms their squares), and a
// triangle `triangle_size` × the shape's size around it (libccd's MPR overflowed there and asked
// for the support of a NaN direction, which the support function refused with an exception
// thrown through libccd). Against the slimmest needle the range allows, in random poses:
// every answer finite, the front end and FCL's table agreeing in both orders; apart from the
// triangle along its normal, at the constructed distance.
template <typename S>
void checkPartnersAtTheEndOfTheRange(S triangle_size) {
  const S R = NumericRange<S>::kMaxRadius, eps = std::numeric_limits<S>::epsilon();
  const S thin = S(1) / NumericRange<S>::kMaxAspectRatio;
  const auto needle = std::make_shared<Superellipsoid<S>>(thin, thin, S(1), S(1.35), S(0.02));
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> u(-1, 1);
  auto rotation = [&] {
    return Eigen::Quaternion<S>(S(u(rng)), S(u(rng)), S(u(rng)), S(u(rng)))
        .normalized()
        .toRotationMatrix();
  };
  const std::shared_ptr<fcl::CollisionGeometry<S>> ellipsoids[] = {
      std::make_shared<fcl::Ellipsoid<S>>(S(2.34), S(0.095), R),
      std::make_shared<fcl::Ellipsoid<S>>(R, R / 3, R)};
  for (const auto& ellipsoid : ellipsoids) {
    for (int trial = 0; trial < 20; ++trial) {
      fcl::Transform3<S> X_WA = fcl::Transform3<S>::Identity(), X_WB = X_WA;
      X_WA.linear() = rotation();
      X_WB.linear() = rotation();
      const S reach = trial % 2 ? S(2) * R : S(3);
      X_WA.translation() = reach * Vector3<S>(S(u(rng)), S(u(rng)), S(u(rng)));
      ask<S>(needle, X_WA, ellipsoid, X_WB, double(64 * eps * std::max(R, reach)), true);
    }
  }
  const S L = triangle_size;
  const auto triangle = std::make_shared<fcl::TriangleP<S>>(
      Vector3<S>(-L, -L, 0), Vector3<S>(L, -L, 0), Vector3<S>(0, L, 0));
  for (int trial = 0; trial < 200; ++trial) {
    // Apart: the needle upright (turned about z only) at height h above the triangle's plane,
    // where the distance is h − 1 (the needle's half length). Across: both turned at random,
    // the needle within 3 of the triangle's centre.
    fcl::Transform3<S> X_WA = fcl::Transform3<S>::Identity(), X_WB = X_WA;
    const bool apart = trial % 2 == 0;
    const S h = apart ? L / 4 : S(3 * u(rng));
    if (apart) {
      X_WA.linear() = Eigen::AngleAxis<S>(S(3 * u(rng)), Vector3<S>::UnitZ()).toRotationMatrix();
    } else {
      X_WA.linear() = rotation();
      X_WB.linear() = rotation();
    }
    X_WA.translation() = Vector3<S>(S(3 * u(rng)), S(3 * u(rng)), h);
    const double rounding = double(64 * eps * L);
    const Answer a = ask<S>(needle, X_WA, triangle, X_WB, rounding, true);
    if (apart) EXPECT_NEAR(a.distance, double(h - S(1)), rounding);
  }
}

TEST(ShapePairs, PartnersAtTheEndOfTheirRange) {
  checkPartnersAtTheEndOfTheRange<float>(1e19f);
  checkPartnersAtTheEndOfTheRange<double>(1e50);
}

// Float: every kind of partner agrees with the double answer to float's precision.
TEST(ShapePairs, FloatAgreesWithDouble) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> gap(-0.2, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Construction c = constructShape(rng, 1);
    std::vector<FlatPartner> partners = flatPartners(rng, 1);
    const RandomShape smooth = randomShape(rng, 1);
    const SurfacePoint sp = randomSurfacePoint(smooth, rng);
    partners.push_back({"superellipsoid", makeShape<double>(smooth), sp.x, sp.n});
    for (const FlatPartner& partner : partners) {
      const fcl::Transform3d X_WB =
          placePartner(c, LD(gap(rng)) * 0.2, partner.b_L, partner.m_L, rng);
      const Answer d =
          ask<double>(makeShape<double>(c.shape), c.X_WA, partner.geometry, X_WB, 1e-6);
      // The same geometry in float.
      std::shared_ptr<fcl::CollisionGeometryf> other;
      const fcl::CollisionGeometryd* g = partner.geometry.get();
      if (auto* x = dynamic_cast<const Superellipsoidd*>(g)) {
        other = std::make_shared<Superellipsoidf>(Vector3<float>(x->radii().cast<float>()),
                                                  float(x->eps1()), float(x->eps2()));
      } else if (auto* x = dynamic_cast<const fcl::Boxd*>(g)) {
        other = std::make_shared<fcl::Boxf>(Vector3<float>(x->side.cast<float>()));
      } else if (auto* x = dynamic_cast<const fcl::Capsuled*>(g)) {
        other = std::make_shared<fcl::Capsulef>(float(x->radius), float(x->lz));
      } else if (auto* x = dynamic_cast<const fcl::Cylinderd*>(g)) {
        other = std::make_shared<fcl::Cylinderf>(float(x->radius), float(x->lz));
      } else if (auto* x = dynamic_cast<const fcl::Coned*>(g)) {
        other = std::make_shared<fcl::Conef>(float(x->radius), float(x->lz));
      } else if (auto* x = dynamic_cast<const fcl::TrianglePd*>(g)) {
        other = std::make_shared<fcl::TrianglePf>(x->a.cast<float>(), x->b.cast<float>(),
                                                  x->c.cast<float>());
      } else {
        continue;  // (convex: FCL's float Convex is not needed here)
      }
      const Answer f = ask<float>(makeShape<float>(c.shape), c.X_WA.cast<float>(), other,
                                  X_WB.cast<float>(), 1e-3);
      EXPECT_NEAR(f.distance, d.distance, 2e-4) << partner.name << " trial " << trial;
    }
  }
}

// The broadphase callbacks: a scene of superellipsoids, boxes, capsules and a ground halfspace;
// the manager's contacts are the pairwise collide()'s with the same request (several contacts
// per pair: their manifolds), and its distance the pairwise minimum.
TEST(ShapePairs, BroadphaseFindsEveryPair) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> position(-2, 2);
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> geometries;
  for (int i = 0; i < 12; ++i) {
    if (i % 3 == 0) {
      geometries.push_back(makeShape<double>(randomShape(rng, 0.8)));
    } else if (i % 3 == 1) {
      geometries.push_back(std::make_shared<fcl::Boxd>(0.6, 0.4, 0.8));
    } else {
      geometries.push_back(std::make_shared<fcl::Capsuled>(0.2, 0.6));
    }
  }
  geometries.push_back(std::make_shared<fcl::Halfspaced>(Vector3<double>(0, 0, 1), -1.5));
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  for (const auto& g : geometries) {
    objects.push_back(std::make_unique<fcl::CollisionObjectd>(
        g, pose<double>(randomRotation(rng),
                        V3(LD(position(rng)), LD(position(rng)), LD(position(rng))))));
  }
  fcl::DynamicAABBTreeCollisionManagerd manager;
  for (auto& o : objects) manager.registerObject(o.get());
  manager.setup();
  fcl::DefaultCollisionData<double> cdata;
  cdata.request.num_max_contacts = 1000;
  cdata.request.enable_contact = true;
  manager.collide(&cdata, defaultCollisionFunction<double>);
  std::size_t expected = 0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    for (std::size_t j = i + 1; j < objects.size(); ++j) {
      const bool shapes = dynamic_cast<const Superellipsoidd*>(geometries[i].get()) ||
                          dynamic_cast<const Superellipsoidd*>(geometries[j].get());
      if (!shapes) continue;  // FCL's own pairs: counted by FCL, not by us
      fcl::CollisionResultd r;
      expected += fcl_superellipsoid::collide(objects[i].get(), objects[j].get(), cdata.request, r);
    }
  }
  std::size_t found = 0;
  std::vector<fcl::Contactd> contacts;
  cdata.result.getContacts(contacts);
  for (const auto& c : contacts) {
    found +=
        dynamic_cast<const Superellipsoidd*>(c.o1) || dynamic_cast<const Superellipsoidd*>(c.o2);
  }
  EXPECT_GT(expected, 0u);
  EXPECT_EQ(found, expected);
}

}  // namespace
}  // namespace fcl_superellipsoid
