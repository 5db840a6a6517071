// The interposer (include/fcl_superellipsoid/interpose.h), linked before libfcl as a user
// would (test/CMakeLists.txt): FCL's plain calls answer superellipsoid pairs as the
// solver-taking calls do, and every other pair exactly as libfcl's own plain calls, which the
// tests call directly (dlsym in libfcl.so) as the independent reference.

#include <dlfcn.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl_superellipsoid/fcl_integration.h>
#include <fcl_superellipsoid/interpose.h>
#include <fcl_superellipsoid/tessellation.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "pair_construction.h"

namespace fcl_superellipsoid {
namespace {

using test::LD;
using test::V3;

// libfcl's own plain calls, looked up in libfcl.so itself (not through the process's global
// scope, where the interposer wins).
struct LibfclPlainCalls {
  using Distance = double (*)(const fcl::CollisionObjectd*, const fcl::CollisionObjectd*,
                              const fcl::DistanceRequestd&, fcl::DistanceResultd&);
  using Collide = std::size_t (*)(const fcl::CollisionObjectd*, const fcl::CollisionObjectd*,
                                  const fcl::CollisionRequestd&, fcl::CollisionResultd&);
  Distance distance = nullptr;
  Collide collide = nullptr;
  LibfclPlainCalls() {
    void* libfcl = dlopen("libfcl.so.0.7", RTLD_LAZY | RTLD_NOLOAD);
    if (libfcl == nullptr) return;
    distance = reinterpret_cast<Distance>(
        dlsym(libfcl,
              "_ZN3fcl8distanceIdEET_PKNS_15CollisionObjectIS1_EES5_RKNS_15DistanceRequestIS1_"
              "EERNS_14DistanceResultIS1_EE"));
    collide = reinterpret_cast<Collide>(
        dlsym(libfcl,
              "_ZN3fcl7collideIdEEmPKNS_15CollisionObjectIT_EES5_RKNS_16CollisionRequestIS2_EERNS_"
              "15CollisionResultIS2_EE"));
    dlclose(libfcl);  // RTLD_NOLOAD took a reference; the executable still holds its own
  }
};

/// A random pose: a random rotation (pair_construction.h) and a translation in [−spread, spread]³.
fcl::Transform3d randomPose(std::mt19937& rng, double spread) {
  std::uniform_real_distribution<double> t(-spread, spread);
  return test::pose<double>(test::randomRotation(rng), V3(LD(t(rng)), LD(t(rng)), LD(t(rng))));
}

/// A point cloud of n vertices in [−extent, extent]³.
TriangleMesh<double> randomCloud(std::mt19937& rng, int n, double extent) {
  std::uniform_real_distribution<double> t(-extent, extent);
  TriangleMesh<double> cloud;
  for (int i = 0; i < n; ++i) cloud.vertices.emplace_back(t(rng), t(rng), t(rng));
  return cloud;
}

/// `defined`: whether FCL's answer is defined. FCL's mesh–shape distance on an overlapping pair
/// is not: it leaves the nearest points as whatever was on the stack, and its distance and
/// triangle indices differ between a gcc and a clang build of the same FCL code (seen: −0.05
/// against −0.32), so only separated mesh pairs are compared (their contacts always are).
void expectSameDistance(const fcl::DistanceResultd& a, const fcl::DistanceResultd& b,
                        bool defined = true) {
  if (!defined) return;
  EXPECT_EQ(a.min_distance, b.min_distance);
  EXPECT_EQ(a.nearest_points[0], b.nearest_points[0]);
  EXPECT_EQ(a.nearest_points[1], b.nearest_points[1]);
  EXPECT_EQ(a.b1, b.b1);
  EXPECT_EQ(a.b2, b.b2);
}

void expectSameContacts(const fcl::CollisionResultd& a, const fcl::CollisionResultd& b) {
  ASSERT_EQ(a.numContacts(), b.numContacts());
  for (std::size_t i = 0; i < a.numContacts(); ++i) {
    EXPECT_EQ(a.getContact(i).pos, b.getContact(i).pos);
    EXPECT_EQ(a.getContact(i).normal, b.getContact(i).normal);
    EXPECT_EQ(a.getContact(i).penetration_depth, b.getContact(i).penetration_depth);
  }
}

TEST(Interpose, PlainCallsResolveToTheInterposer) { EXPECT_TRUE(plainCallsInterposed()); }

// Constructed pairs (test_support/pair_construction.h): the superellipsoid against a box, a
// capsule, a cylinder, a cone, a convex, a triangle at a known distance. The plain call
// returns the construction's distance, and bitwise the solver-taking call's answer, for both
// solver types and both argument orders; collide agrees on overlaps.
TEST(Interpose, PlainCallsAnswerSuperellipsoidPairsExactly) {
  std::mt19937 rng(2026);
  int pairs = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const test::Construction c = test::constructShape(rng, 1);
    const auto shape = std::make_shared<Superellipsoidd>(
        double(c.shape.radii[0]), double(c.shape.radii[1]), double(c.shape.radii[2]),
        double(c.shape.e1), double(c.shape.e2));
    for (const test::FlatPartner& partner : test::flatPartners(rng, 1)) {
      for (const LD d : {LD(0.25), LD(-0.01)}) {
        const fcl::CollisionObjectd a(shape, c.X_WA);
        const fcl::CollisionObjectd b(partner.geometry,
                                      test::placePartner(c, d, partner.b_L, partner.m_L, rng));
        for (const fcl::GJKSolverType type : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
          fcl::DistanceRequestd request(true);
          request.enable_signed_distance = true;
          request.gjk_solver_type = type;
          for (const bool swapped : {false, true}) {
            const fcl::CollisionObjectd* o1 = swapped ? &b : &a;
            const fcl::CollisionObjectd* o2 = swapped ? &a : &b;
            fcl::DistanceResultd plain, table;
            fcl::distance(o1, o2, request, plain);
            fcl::detail::GJKSolver_libccd<double> solver;
            fcl::distance(o1, o2, &solver, request, table);
            expectSameDistance(plain, table);
            if (d > 0) {
              EXPECT_NEAR(plain.min_distance, double(d), 1e-12) << partner.name;
            } else {
              EXPECT_LT(plain.min_distance, 0) << partner.name;
            }
            fcl::CollisionRequestd crequest(1, true);
            crequest.gjk_solver_type = type;
            fcl::CollisionResultd cplain, ctable;
            fcl::collide(o1, o2, crequest, cplain);
            fcl::collide(o1, o2, &solver, crequest, ctable);
            expectSameContacts(cplain, ctable);
            EXPECT_EQ(cplain.numContacts(), d < 0 ? 1u : 0u) << partner.name;
            ++pairs;
          }
        }
      }
    }
  }
  EXPECT_GT(pairs, 400);
}

// The geometry + pose forms, a mesh and another superellipsoid: the solver-taking calls'
// answers (for a shape–mesh pair FCL's order: the mesh first).
TEST(Interpose, GeometryFormsMeshesAndSuperellipsoidPairs) {
  std::mt19937 rng(7);
  const auto shape = std::make_shared<Superellipsoidd>(1, 0.8, 0.6, 0.4, 1.5);
  const auto other = std::make_shared<Superellipsoidd>(0.5, 0.7, 0.9, 1.7, 0.3);
  const auto mesh = makeBVHModel<fcl::OBBRSSd>(randomCloud(rng, 300, 0.8));
  for (int trial = 0; trial < 20; ++trial) {
    const fcl::Transform3d X1 = randomPose(rng, 1.0), X2 = randomPose(rng, 1.0);
    for (const fcl::CollisionGeometryd* partner :
         {static_cast<const fcl::CollisionGeometryd*>(other.get()),
          static_cast<const fcl::CollisionGeometryd*>(mesh.get())}) {
      fcl::DistanceRequestd request(true);
      request.enable_signed_distance = true;
      fcl::DistanceResultd plain, table;
      fcl::detail::GJKSolver_libccd<double> solver;
      fcl::distance(shape.get(), X1, partner, X2, request, plain);
      fcl::distance(shape.get(), X1, partner, X2, &solver, request, table);
      expectSameDistance(plain, table);
      EXPECT_LT(plain.min_distance, std::numeric_limits<double>::max());
      fcl::CollisionRequestd crequest(50, true);
      fcl::CollisionResultd cplain, ctable;
      fcl::collide(shape.get(), X1, partner, X2, crequest, cplain);
      fcl::collide(shape.get(), X1, partner, X2, &solver, crequest, ctable);
      expectSameContacts(cplain, ctable);
    }
  }
}

// Pairs without a superellipsoid: bitwise libfcl's own plain calls, for both solver types
// (which give different answers on these pairs: the solver type is honoured).
TEST(Interpose, OtherPairsGetLibfclsAnswerForBothSolverTypes) {
  const LibfclPlainCalls libfcl;
  ASSERT_NE(libfcl.distance, nullptr);
  ASSERT_NE(libfcl.collide, nullptr);
  ASSERT_NE(reinterpret_cast<void*>(libfcl.distance),
            dlsym(RTLD_DEFAULT,
                  "_ZN3fcl8distanceIdEET_PKNS_15CollisionObjectIS1_EES5_RKNS_15DistanceRequestIS1_"
                  "EERNS_14DistanceResultIS1_EE"));
  std::mt19937 rng(11);
  const std::vector<std::shared_ptr<fcl::CollisionGeometryd>> shapes = {
      std::make_shared<fcl::Boxd>(1, 0.6, 0.4),
      std::make_shared<fcl::Capsuled>(0.3, 1.0),
      std::make_shared<fcl::Cylinderd>(0.4, 0.8),
      std::make_shared<fcl::Coned>(0.5, 0.9),
      std::make_shared<fcl::Sphered>(0.35),
      makeBVHModel<fcl::OBBRSSd>(tessellate(Superellipsoidd(0.7, 0.5, 0.4, 0.6, 0.9), 200))};
  int differing = 0, compared = 0, compared_distances = 0;
  for (int trial = 0; trial < 30; ++trial) {
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      const std::size_t j = (i + 1 + trial) % shapes.size();
      const fcl::CollisionObjectd a(shapes[i], randomPose(rng, 0.8));
      const fcl::CollisionObjectd b(shapes[j], randomPose(rng, 0.8));
      double by_type[2] = {0, 0};
      for (const fcl::GJKSolverType type : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
        fcl::CollisionRequestd crequest(20, true);
        crequest.gjk_solver_type = type;
        fcl::CollisionResultd cours, ctheirs;
        fcl::collide(&a, &b, crequest, cours);
        libfcl.collide(&a, &b, crequest, ctheirs);
        expectSameContacts(cours, ctheirs);
        fcl::DistanceRequestd request(true);
        request.gjk_solver_type = type;
        fcl::DistanceResultd ours, theirs;
        by_type[type] = fcl::distance(&a, &b, request, ours);
        libfcl.distance(&a, &b, request, theirs);
        const bool mesh = a.getObjectType() == fcl::OT_BVH || b.getObjectType() == fcl::OT_BVH;
        expectSameDistance(ours, theirs, !(mesh && cours.isCollision()));
        compared_distances += !(mesh && cours.isCollision());
        ++compared;
      }
      if (by_type[0] != by_type[1]) ++differing;
    }
  }
  EXPECT_EQ(compared, 360);
  EXPECT_GT(compared_distances, 300);
  EXPECT_GT(differing, 10);
}

// FCL's own broadphase callbacks call the plain functions: with the interposer they see the
// superellipsoid.
TEST(Interpose, FclsOwnBroadphaseCallbacksSeeTheShape) {
  const auto shape = std::make_shared<Superellipsoidd>(1, 1, 0.5, 0.3, 0.3);
  const auto box = std::make_shared<fcl::Boxd>(0.4, 0.4, 0.4);
  fcl::CollisionObjectd s(shape), touching(box, fcl::Transform3d(fcl::Translation3d(0, 0, 0.6))),
      apart(box, fcl::Transform3d(fcl::Translation3d(5, 0, 0)));
  fcl::DynamicAABBTreeCollisionManagerd manager;
  manager.registerObjects({&s, &touching, &apart});
  manager.setup();
  fcl::DefaultCollisionData<double> collision;
  collision.request.num_max_contacts = 10;
  collision.request.enable_contact = true;
  manager.collide(&collision, fcl::DefaultCollisionFunction<double>);
  // The box's bottom face at z = 0.4 against the flat top at z = 0.5: depth 0.1 (less a few
  // micrometres at the corners, where the top has begun to curve), held at its four corners.
  ASSERT_EQ(collision.result.numContacts(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const fcl::Contactd& c = collision.result.getContact(i);
    EXPECT_NEAR(c.penetration_depth, 0.1, 1e-5);
    EXPECT_NEAR(std::abs(c.pos.x()), 0.2, 1e-12);
    EXPECT_NEAR(std::abs(c.pos.y()), 0.2, 1e-12);
  }

  fcl::DistanceRequestd request(true);
  request.enable_signed_distance = true;
  fcl::DefaultDistanceData<double> distance;
  distance.request = request;
  fcl::DynamicAABBTreeCollisionManagerd far_manager;
  far_manager.registerObjects({&s, &apart});
  far_manager.setup();
  far_manager.distance(&distance, fcl::DefaultDistanceFunction<double>);
  // The box's face at x = 4.8 against the shape's tip at x = 1.
  EXPECT_NEAR(distance.result.min_distance, 3.8, 1e-12);
}

// What threads share (run under ThreadSanitizer by scripts/test.sh --tsan; ctest runs each test
// in its own process, so these are the process's first calls): the first use of both solver
// types' tables and of the superellipsoid entries, from four threads at once, each with its own
// objects on shared geometries. Every thread gets the single-threaded answers.
TEST(Interpose, FirstCallsRaceOnSeveralThreads) {
  const auto shape = std::make_shared<Superellipsoidd>(1, 0.7, 0.5, 0.4, 1.2);
  const auto box = std::make_shared<fcl::Boxd>(0.5, 0.4, 0.3);
  const auto capsule = std::make_shared<fcl::Capsuled>(0.2, 0.6);
  const fcl::Transform3d X(fcl::Translation3d(2, 0.3, -0.2));
  constexpr int kThreads = 4;
  std::vector<std::array<double, 4>> answers(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      const fcl::CollisionObjectd s(shape), b(box, X), c(capsule, X);
      for (const fcl::GJKSolverType type : {fcl::GST_INDEP, fcl::GST_LIBCCD}) {
        fcl::DistanceRequestd request;
        request.gjk_solver_type = type;
        fcl::DistanceResultd with_shape, without;
        answers[t][2 * type] = fcl::distance(&s, &b, request, with_shape);
        answers[t][2 * type + 1] = fcl::distance(&b, &c, request, without);
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 1; t < kThreads; ++t) EXPECT_EQ(answers[t], answers[0]);
  // The box's face at x = 1.75 against the shape's side near x = 1 (its answer with either
  // solver type: the superellipsoid's own pair).
  EXPECT_GT(answers[0][0], 0.7);
  EXPECT_LT(answers[0][0], 0.8);
  EXPECT_EQ(answers[0][0], answers[0][2]);
}

// The bad-input catalogue's row for the interposer (docs/hardening.md → "Bad input"). It lives
// here, not in test/bad_input/: linking the interposer changes every plain call of a binary.
TEST(Interpose, NullObjectsAreRefused) {
  const auto shape = std::make_shared<Superellipsoidd>(1, 1, 1, 1, 1);
  const fcl::CollisionObjectd a(shape);
  const fcl::CollisionObjectd* none = nullptr;
  const fcl::Transform3d X = fcl::Transform3d::Identity();
  const auto message = [](const std::function<void()>& call) -> std::string {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no exception";
  };
  fcl::DistanceResultd result;
  fcl::CollisionResultd cresult;
  EXPECT_EQ(message([&] { fcl::distance(&a, none, fcl::DistanceRequestd(), result); }),
            "fcl::distance (fcl_superellipsoid_interpose): o1 and o2 must not be null, got o2 = "
            "null");
  EXPECT_EQ(message([&] { fcl::collide(none, &a, fcl::CollisionRequestd(), cresult); }),
            "fcl::collide (fcl_superellipsoid_interpose): o1 and o2 must not be null, got o1 = "
            "null");
  EXPECT_EQ(message([&] {
              fcl::distance(static_cast<const fcl::CollisionGeometryd*>(nullptr), X, shape.get(), X,
                            fcl::DistanceRequestd(), result);
            }),
            "fcl::distance (fcl_superellipsoid_interpose): o1 and o2 must not be null, got o1 = "
            "null");
  EXPECT_EQ(message([&] {
              fcl::collide(shape.get(), X, static_cast<const fcl::CollisionGeometryd*>(nullptr), X,
                           fcl::CollisionRequestd(), cresult);
            }),
            "fcl::collide (fcl_superellipsoid_interpose): o1 and o2 must not be null, got o2 = "
            "null");
}

// float: no interposer needed with libccd (the plain float call is the caller's and reads
// the caller-side table that holds the entries).
TEST(Interpose, FloatPlainCallsReadTheCallerSideTable) {
  const auto shape = std::make_shared<Superellipsoidf>(1, 1, 1, 1, 1);
  const auto sphere = std::make_shared<fcl::Spheref>(0.5f);
  const fcl::CollisionObjectf a(shape), b(sphere, fcl::Transform3f(fcl::Translation3f(3, 0, 0)));
  fcl::DistanceResultf result;
  EXPECT_NEAR(fcl::distance(&a, &b, fcl::DistanceRequestf(), result), 1.5f, 1e-6f);
}

}  // namespace
}  // namespace fcl_superellipsoid
