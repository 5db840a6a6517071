// The bad-input catalogue (docs/hardening.md → "Bad input"), one test per row: every public
// entry point, every kind of bad input, and what it gets. A refusal is std::invalid_argument
// with "<where>: <requirement>, got <value>"; each test checks all three parts.

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <type_traits>

#include "fcl_superellipsoid/batch_distance.h"
#include "fcl_superellipsoid/contact_manifold.h"
#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_superellipsoid/pair_derivatives.h"
#include "fcl_superellipsoid/point_derivatives.h"
#include "fcl_superellipsoid/point_distance.h"
#include "fcl_superellipsoid/tessellation.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

/// call() must throw std::invalid_argument whose message starts with "<where>: ", contains the
/// requirement, and names the value after ", got " (all of it, or the telling part of a vector).
void expectRefused(const std::function<void()>& call, const std::string& where,
                   const std::string& requirement, const std::string& value) {
  try {
    call();
    ADD_FAILURE() << "no exception; expected " << where << ": " << requirement;
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(where + ": ", 0), 0u) << what;
    EXPECT_NE(what.find(requirement), std::string::npos) << what;
    const std::size_t got = what.rfind(", got ");
    ASSERT_NE(got, std::string::npos) << what;
    EXPECT_NE(what.find(value, got), std::string::npos)
        << what << "\n  expected after ', got ': " << value;
  }
}

template <typename S>
class BadInputTest : public ::testing::Test {
 protected:
  static constexpr S nan = std::numeric_limits<S>::quiet_NaN();
  static constexpr S inf = std::numeric_limits<S>::infinity();
};
TYPED_TEST_SUITE(BadInputTest, test::Scalars);

TYPED_TEST(BadInputTest, SuperellipsoidRadiiAndExponents) {
  using S = TypeParam;
  const S nan = TestFixture::nan, inf = TestFixture::inf;
  const std::string where = "Superellipsoid";
  auto make = [](S a1, S a2, S a3, S e1, S e2) {
    return [=] { Superellipsoid<S>(a1, a2, a3, e1, e2); };
  };
  expectRefused(make(S(-1), 1, 1, 1, 1), where, "radius a1 must be finite and > 0", "-1");
  expectRefused(make(1, S(0), 1, 1, 1), where, "radius a2 must be finite and > 0", "0");
  expectRefused(make(1, 1, nan, 1, 1), where, "radius a3 must be finite and > 0", "nan");
  expectRefused(make(inf, 1, 1, 1, 1), where, "radius a1 must be finite and > 0", "inf");
  expectRefused(make(1, 1, 1, S(0), 1), where, "exponent eps1 must be in the open interval (0, 2)",
                "0");
  expectRefused(make(1, 1, 1, S(2), 1), where, "exponent eps1 must be in the open interval (0, 2)",
                "2");
  expectRefused(make(1, 1, 1, 1, S(2.5)), where,
                "exponent eps2 must be in the open interval (0, 2)", "2.5");
  expectRefused(make(1, 1, 1, 1, -S(0.125)), where, "exponent eps2", "-0.125");
  expectRefused(make(1, 1, 1, nan, 1), where, "exponent eps1", "nan");
  expectRefused(make(1, 1, 1, 1, inf), where, "exponent eps2", "inf");
  // The other constructor refuses the same way.
  expectRefused([] { Superellipsoid<S>(Vector3<S>(1, -2, 1), 1, 1); }, where,
                "radius a2 must be finite and > 0", "-2");
}

// The numeric range (NumericRange<S>): just outside each end of the radius range, and an aspect
// ratio just above the limit. (The ends themselves: test_numeric_range.cpp.)
TYPED_TEST(BadInputTest, SuperellipsoidOutsideTheNumericRange) {
  using S = TypeParam;
  using Range = NumericRange<S>;
  const std::string where = "Superellipsoid";
  const S below = std::nextafter(Range::kMinRadius, S(0));
  const S above = std::nextafter(Range::kMaxRadius, TestFixture::inf);
  try {
    Superellipsoid<S>(below, below, below, 1, 1);
    ADD_FAILURE() << "radius below the range accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("radius a1 must be in the supported range"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(Superellipsoid<S>(1, above, 1, 1, 1), std::invalid_argument);
  const S thin = std::nextafter(S(4) / Range::kMaxAspectRatio, S(0));  // (itself in range)
  try {
    Superellipsoid<S>(4, 4, thin, 1, 1);
    ADD_FAILURE() << "aspect ratio above the limit accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the largest radius may be at most"), std::string::npos)
        << e.what();
  }
}

TYPED_TEST(BadInputTest, ShapeEvaluationsRefuseANonFinitePoint) {
  using S = TypeParam;
  const Superellipsoid<S> shape(1, 2, 3, S(0.5), S(1.5));
  const Vector3<S> p(S(1), TestFixture::nan, S(0));
  const std::string got = "(1, nan, 0)";
  expectRefused([&] { shape.gauge(p); }, "Superellipsoid::gauge", "the point must be finite", got);
  expectRefused([&] { shape.implicitFunction(p); }, "Superellipsoid::implicitFunction", "finite",
                got);
  expectRefused([&] { shape.gaugeGradient(p); }, "Superellipsoid::gaugeGradient", "finite", got);
  expectRefused([&] { shape.implicitGradient(p); }, "Superellipsoid::implicitGradient", "finite",
                got);
  expectRefused([&] { shape.normal(p); }, "Superellipsoid::normal", "finite", got);
  expectRefused([&] { shape.radialDistance(p); }, "Superellipsoid::radialDistance", "finite", got);
  expectRefused([&] { shape.radialProjection(p); }, "Superellipsoid::radialProjection", "finite",
                got);
  expectRefused([&] { shape.contains(p); }, "Superellipsoid::contains", "finite", got);
  expectRefused([&] { shape.surfacePoint(TestFixture::inf, S(0)); }, "Superellipsoid::surfacePoint",
                "eta and omega must be finite", "(inf, 0)");
  expectRefused([&] { shape.supportPoint(Vector3<S>(TestFixture::inf, 0, 0)); },
                "Superellipsoid::supportPoint", "direction must be finite", "(inf, 0, 0)");
}

TYPED_TEST(BadInputTest, DistanceOptions) {
  using S = TypeParam;
  Superellipsoid<S> shape(1, 1, 1, 1, 1);
  for (auto method : {DistanceMethod::kExact, DistanceMethod::kPaper, DistanceMethod::kRadial}) {
    DistanceOptions<S> bad = DistanceOptions<S>::of(method);
    bad.tolerance = S(0);
    expectRefused([&] { validateOptions(bad); }, "pointDistance",
                  "options.tolerance must be finite and > 0", "0");
    bad.tolerance = TestFixture::nan;
    expectRefused([&] { shape.setQueryOptions(bad); }, "pointDistance", "options.tolerance", "nan");
    bad = DistanceOptions<S>::of(method);
    bad.max_iterations = 0;
    expectRefused([&] { pointDistance(shape, Vector3<S>::Ones(), bad); }, "pointDistance",
                  "options.max_iterations must be >= 1", "0");
  }
  DistanceOptions<S> bad;
  bad.method = static_cast<DistanceMethod>(7);
  expectRefused([&] { validateOptions(bad); }, "pointDistance",
                "options.method must be a DistanceMethod", "7");
}

TYPED_TEST(BadInputTest, PointDistance) {
  using S = TypeParam;
  const Superellipsoid<S> shape(1, 1, 1, 1, 1);
  for (auto method : {DistanceMethod::kExact, DistanceMethod::kPaper, DistanceMethod::kRadial}) {
    const auto ok = DistanceOptions<S>::of(method);
    expectRefused([&] { pointDistance(shape, Vector3<S>(TestFixture::nan, 0, 0), ok); },
                  "pointDistance", "the query point must be finite", "(nan, 0, 0)");
    expectRefused([&] { pointDistance(shape, Vector3<S>(0, -TestFixture::inf, 0), ok); },
                  "pointDistance", "the query point must be finite", "(0, -inf, 0)");
    // Coordinates beyond a quarter of the largest finite value (docs/hardening.md).
    const S beyond = std::nextafter(std::numeric_limits<S>::max() / 4, TestFixture::inf);
    expectRefused([&] { pointDistance(shape, Vector3<S>(0, 0, -beyond), ok); }, "pointDistance",
                  "the query point's coordinates must be at most", "(0, 0, -");
    EXPECT_NO_THROW(pointDistance(shape, Vector3<S>(0, 0, -std::numeric_limits<S>::max() / 4), ok));
    fcl::Transform3<S> pose = fcl::Transform3<S>::Identity();
    expectRefused([&] { pointDistance(shape, pose, Vector3<S>(1, TestFixture::nan, 0), ok); },
                  "pointDistance", "the query point must be finite", "(1, nan, 0)");
    pose.translation() = Vector3<S>(TestFixture::inf, 0, 0);
    expectRefused([&] { pointDistance(shape, pose, Vector3<S>::Ones(), ok); }, "pointDistance",
                  "the pose X_WS must be finite", "(inf, 0, 0)");
    pose.translation() = Vector3<S>(beyond, 0, 0);
    expectRefused([&] { pointDistance(shape, pose, Vector3<S>::Ones(), ok); }, "pointDistance",
                  "its translation at most", "(");
  }
}

/// The refusals every call on one pair of shapes shares (contactManifold,
/// pairDistanceDerivatives): `call(shape, X_WS, other, X_WO)` with a pose that is not finite, a
/// mesh (its node type named, with `mesh_requirement`) and another shape's bad parameters (as
/// for every pair query).
template <typename S, typename Call>
void expectPairRefusals(
    const std::string& where, Call call,
    const std::string& mesh_requirement = "the other geometry must be a Superellipsoid") {
  const S nan = std::numeric_limits<S>::quiet_NaN();
  const Superellipsoid<S> shape(1, 1, 1, S(0.5), S(0.5));
  const fcl::Sphere<S> sphere(S(0.5));
  const fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
  fcl::Transform3<S> bad = X;
  bad.translation() = Vector3<S>(nan, 0, 0);
  expectRefused([&] { call(shape, bad, sphere, X); }, where, "the pose X_WS must be finite",
                "(nan, 0, 0)");
  expectRefused([&] { call(shape, X, sphere, bad); }, where, "the pose X_WO must be finite",
                "(nan, 0, 0)");
  const auto mesh = makeBVHModel<fcl::OBBRSS<S>>(tessellate(shape, 8));
  expectRefused([&] { call(shape, X, *mesh, X); }, where, mesh_requirement, "BV_OBBRSS");
  const fcl::Sphere<S> bad_sphere(nan);
  expectRefused([&] { call(shape, X, bad_sphere, X); }, where,
                "the other shape's radius must be finite", "nan");
}

TYPED_TEST(BadInputTest, ContactManifold) {
  using S = TypeParam;
  const S nan = TestFixture::nan;
  const std::string where = "contactManifold";
  expectPairRefusals<S>(
      where, [](const auto&... args) { contactManifold(args...); },
      "a BVH model may touch the shape in several regions: ask contactManifolds");
  const Superellipsoid<S> shape(1, 1, 1, S(0.5), S(0.5));
  const fcl::Sphere<S> sphere(S(0.5));
  const fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
  const auto with = [&](auto change) {
    ManifoldOptions<S> options;
    change(options);
    return [=, &shape, &sphere] { contactManifold(shape, X, sphere, X, options); };
  };
  expectRefused(with([&](ManifoldOptions<S>& o) { o.patch_tolerance = nan; }), where,
                "options.patch_tolerance must be finite and > 0", "nan");
  expectRefused(with([](ManifoldOptions<S>& o) { o.patch_tolerance = 0; }), where,
                "options.patch_tolerance", "0");
  expectRefused(with([](ManifoldOptions<S>& o) { o.outline_samples = 2; }), where,
                "options.outline_samples must be in [3, 4096]", "2");
  expectRefused(with([](ManifoldOptions<S>& o) { o.outline_area_tolerance = 0; }), where,
                "options.outline_area_tolerance must be finite and > 0", "0");
  expectRefused(with([](ManifoldOptions<S>& o) { o.max_points = 0; }), where,
                "options.max_points must be >= 1", "0");
  expectRefused(with([](ManifoldOptions<S>& o) { o.merge_angle = S(-0.1); }), where,
                "options.merge_angle must be in [0, pi/2]", "-0.1");
}

TYPED_TEST(BadInputTest, ContactManifolds) {
  using S = TypeParam;
  const S nan = TestFixture::nan;
  const std::string where = "contactManifolds";
  const Superellipsoid<S> shape(1, 1, 1, S(0.5), S(0.5));
  const fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
  fcl::Transform3<S> bad = X;
  bad.translation() = Vector3<S>(nan, 0, 0);
  const auto mesh = makeBVHModel<fcl::OBBRSS<S>>(tessellate(Superellipsoid<S>(2, 2, 2, 1, 1), 40));
  expectRefused([&] { contactManifolds(shape, bad, *mesh, X); }, where,
                "the pose X_WS must be finite", "(nan, 0, 0)");
  expectRefused([&] { contactManifolds(shape, X, *mesh, bad); }, where,
                "the pose X_WO must be finite", "(nan, 0, 0)");
  ManifoldOptions<S> options;
  options.merge_angle = S(2);
  expectRefused([&] { contactManifolds(shape, X, *mesh, X, options); }, where,
                "options.merge_angle must be in [0, pi/2]", "2");
  fcl::BVHModel<fcl::OBBRSS<S>> cloud;
  cloud.beginModel();
  for (int k = 0; k < 4; ++k) cloud.addVertex(Vector3<S>(S(k & 1), S(k >> 1), S(0.1 * k)));
  cloud.endModel();
  expectRefused([&] { contactManifolds(shape, X, cloud, X); }, where,
                "the other geometry must be a triangle mesh", "BVH_MODEL_POINTCLOUD");
  // A vertex that is not finite in a triangle the model's BVH reaches (the BVH built before the
  // vertex went bad: FCL's BVs of such a vertex bound nothing).
  fcl::BVHModel<fcl::OBBRSS<S>> bad_mesh;
  bad_mesh.beginModel();
  bad_mesh.addTriangle(Vector3<S>(-2, -2, S(0.5)), Vector3<S>(2, -2, S(0.5)),
                       Vector3<S>(0, 2, S(0.5)));
  bad_mesh.endModel();
  bad_mesh.vertices[2].x() = nan;
  expectRefused([&] { contactManifolds(shape, X, bad_mesh, X); }, where,
                "the other shape's vertex c must be finite", "(nan, 2, 0.5)");
  const fcl::Sphere<S> bad_sphere(nan);
  expectRefused([&] { contactManifolds(shape, X, bad_sphere, X); }, where,
                "the other shape's radius must be finite", "nan");
  Superellipsoid<S> settable(1, 1, 1, S(0.5), S(0.5));
  expectRefused([&] { settable.setMeshContacts(static_cast<MeshContacts>(7)); }, "setMeshContacts",
                "contacts must be kVertices or kRegions", "7");
}

TYPED_TEST(BadInputTest, PairDerivatives) {
  using S = TypeParam;
  expectPairRefusals<S>("pairDistanceDerivatives",
                        [](const auto&... args) { pairDistanceDerivatives(args...); });
  const Superellipsoid<S> shape(1, 1, 1, S(0.5), S(0.5));
  const fcl::Sphere<S> sphere(1);
  fcl::Transform3<S> apart = fcl::Transform3<S>::Identity();
  apart.translation() = Vector3<S>(3, 0, 0);
  expectRefused(
      [&] {
        pairDistanceDerivatives(shape, fcl::Transform3<S>::Identity(), sphere, apart,
                                static_cast<DerivativeOrder>(7));
      },
      "pairDistanceDerivatives", "order must be a DerivativeOrder", "7");
}

TYPED_TEST(BadInputTest, PointDerivatives) {
  using S = TypeParam;
  const Superellipsoid<S> shape(1, 1, 1, S(0.5), S(0.5));
  const auto gradient = DerivativeOrder::kGradient;
  expectRefused([&] { pointDistanceDerivatives(shape, Vector3<S>(TestFixture::nan, 0, 0)); },
                "pointDistanceDerivatives", "the query point must be finite", "(nan, 0, 0)");
  fcl::Transform3<S> pose = fcl::Transform3<S>::Identity();
  expectRefused([&] { pointDistanceDerivatives(shape, pose, Vector3<S>(0, TestFixture::inf, 0)); },
                "pointDistanceDerivatives", "the query point must be finite", "(0, inf, 0)");
  pose.translation() = Vector3<S>(0, TestFixture::nan, 0);
  expectRefused([&] { pointDistanceDerivatives(shape, pose, Vector3<S>::Ones()); },
                "pointDistanceDerivatives", "the pose X_WS must be finite", "(0, nan, 0)");
  for (auto method : {DistanceMethod::kPaper, DistanceMethod::kRadial}) {
    expectRefused(
        [&] {
          pointDistanceDerivatives(shape, Vector3<S>(2, 0, 0), gradient,
                                   DistanceOptions<S>::of(method));
        },
        "pointDistanceDerivatives", "options.method must be DistanceMethod::kExact",
        toString(method));
  }
  expectRefused(
      [&] {
        pointDistanceDerivatives(shape, Vector3<S>(2, 0, 0), static_cast<DerivativeOrder>(7));
      },
      "pointDistanceDerivatives", "order must be a DerivativeOrder", "7");
}

TYPED_TEST(BadInputTest, TessellateAndMeshes) {
  using S = TypeParam;
  const Superellipsoid<S> shape(1, 1, 1, 1, 1);
  expectRefused([&] { tessellate(shape, 4); }, "tessellate",
                "num_vertices must be in [5, 100000000]", "4");
  expectRefused([&] { tessellate(shape, kMaxTessellationVertices + 1); }, "tessellate",
                "num_vertices", std::to_string(kMaxTessellationVertices + 1));
  TriangleMesh<S> mesh;
  expectRefused([&] { makeBVHModel<fcl::OBBRSS<S>>(mesh); }, "makeBVHModel",
                "the mesh must have a vertex", "0");
  mesh = tessellate(shape, 20);
  mesh.triangles[3] = fcl::Triangle(0, 1, 20);
  expectRefused([&] { makeBVHModel<fcl::AABB<S>>(mesh); }, "makeBVHModel",
                "triangle 3 must index the 20 vertices", "(0, 1, 20)");
  mesh = tessellate(shape, 20);
  mesh.vertices[5][2] = TestFixture::nan;
  expectRefused([&] { makeBVHModel<fcl::KDOP<S, 16>>(mesh); }, "makeBVHModel",
                "vertex 5 must be finite", "nan)");
  // writeObj: a file that cannot be written is a std::runtime_error naming the path.
  try {
    writeObj(tessellate(shape, 20), std::string("/nonexistent-folder/mesh.obj"));
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/mesh.obj"), std::string::npos);
  }
}

TYPED_TEST(BadInputTest, BatchedQueries) {
  using S = TypeParam;
  const Superellipsoid<S> shape(1, 2, 3, S(0.5), S(1.5));
  const fcl::Transform3<S> X_WS = fcl::Transform3<S>::Identity();
  Matrix3X<S> bad = Matrix3X<S>::Ones(3, 5);
  bad(1, 3) = TestFixture::nan;
  BatchDistanceResult<S> result;
  expectRefused([&] { batchDistance(shape, X_WS, bad, result); }, "batchDistance",
                "vertex 3 must be finite", "(1, nan, 1)");
  expectRefused([&] { verticesWithinMargin(shape, X_WS, bad, S(1)); }, "verticesWithinMargin",
                "vertex 3 must be finite", "(1, nan, 1)");
  Matrix3X<S> far = Matrix3X<S>::Ones(3, 3);
  far(0, 2) = std::nextafter(std::numeric_limits<S>::max() / 4, TestFixture::inf);
  expectRefused([&] { batchDistance(shape, X_WS, far, result); }, "batchDistance",
                "vertex 2's coordinates must be at most", "(");
  const Matrix3X<S> ok = Matrix3X<S>::Ones(3, 2);
  expectRefused([&] { verticesWithinMargin(shape, X_WS, ok, TestFixture::inf); },
                "verticesWithinMargin", "the margin must be finite", "inf");
  BatchOptions<S> options;
  options.distance.tolerance = S(-1);
  expectRefused([&] { batchDistance(shape, X_WS, ok, result, options); }, "pointDistance",
                "options.tolerance must be finite and > 0", "-1");
  options = {};
  options.threads = -1;
  expectRefused([&] { batchDistance(shape, X_WS, ok, result, options); }, "batchDistance",
                "options.threads must be >= 0", "-1");
  options = {};
  const Matrix3X<S> warm(3, 3);
  options.warm_start_W = &warm;
  expectRefused([&] { batchDistance(shape, X_WS, ok, result, options); }, "batchDistance",
                "the warm start must have one column per vertex (2 columns)", "3");
  fcl::Transform3<S> nan_pose = X_WS;
  nan_pose.translation()[2] = TestFixture::nan;
  expectRefused([&] { verticesWithinMargin(shape, nan_pose, ok, S(1)); }, "verticesWithinMargin",
                "the pose X_WS must be finite", "(0, 0, nan)");
}

TYPED_TEST(BadInputTest, FclFrontEndAndTables) {
  using S = TypeParam;
  const auto shape = std::make_shared<Superellipsoid<S>>(1, 1, 1, 1, 1);
  const auto sphere = std::make_shared<fcl::Sphere<S>>(S(0.5));
  const fcl::CollisionObject<S> a(shape),
      b(sphere, fcl::Transform3<S>(fcl::Translation3<S>(3, 0, 0)));
  fcl::DistanceResult<S> dresult;
  fcl::CollisionResult<S> cresult;
  expectRefused(
      [&] { fcl_superellipsoid::distance<S>(&a, nullptr, fcl::DistanceRequest<S>(), dresult); },
      "fcl_superellipsoid::distance", "o1 and o2 must not be null", "o2 = null");
  expectRefused(
      [&] { fcl_superellipsoid::collide<S>(nullptr, &b, fcl::CollisionRequest<S>(), cresult); },
      "fcl_superellipsoid::collide", "o1 and o2 must not be null", "o1 = null");
  const fcl::Transform3<S> I = fcl::Transform3<S>::Identity();
  expectRefused(
      [&] {
        fcl_superellipsoid::distance<S>(shape.get(), I, nullptr, I, fcl::DistanceRequest<S>(),
                                        dresult);
      },
      "fcl_superellipsoid::distance", "must not be null", "o2 = null");
  // A pose that is not finite: the front end and FCL's own call with the solver (our table
  // entry) refuse it alike.
  fcl::Transform3<S> nan_pose = I;
  nan_pose.translation() = Vector3<S>(TestFixture::nan, 0, 0);
  expectRefused(
      [&] {
        fcl_superellipsoid::distance<S>(shape.get(), nan_pose, sphere.get(), I,
                                        fcl::DistanceRequest<S>(), dresult);
      },
      "superellipsoid distance", "the pose of o1 must be finite", "(nan, 0, 0)");
  expectRefused(
      [&] {
        fcl_superellipsoid::collide<S>(shape.get(), I, sphere.get(), nan_pose,
                                       fcl::CollisionRequest<S>(), cresult);
      },
      "superellipsoid collide", "the pose of o2 must be finite", "(nan, 0, 0)");
  fcl::detail::GJKSolver_libccd<S> solver;
  const fcl::CollisionObject<S> moved(shape, nan_pose);
  EXPECT_THROW(fcl::distance(&moved, &b, &solver, fcl::DistanceRequest<S>(), dresult),
               std::invalid_argument);
  // The broadphase callbacks: null data.
  fcl::CollisionObject<S> c(shape), d(sphere);
  S dist = 0;
  expectRefused([&] { defaultCollisionFunction<S>(&c, &d, nullptr); },
                "fcl_superellipsoid::defaultCollisionFunction", "data must point to", "null");
  expectRefused([&] { defaultDistanceFunction<S>(&c, &d, nullptr, dist); },
                "fcl_superellipsoid::defaultDistanceFunction", "data must point to", "null");
}

// Another shape with a parameter that is not finite, a negative length, or a coordinate beyond
// max/16 (an ellipsoid's radii: beyond NumericRange<S>::kMaxRadius): refused by distance and
// collide, front end and FCL's call alike, naming the value.
TYPED_TEST(BadInputTest, ShapePairPartners) {
  using S = TypeParam;
  const auto shape = std::make_shared<Superellipsoid<S>>(1, 1, 1, 1, 1);
  const fcl::Transform3<S> I = fcl::Transform3<S>::Identity();
  const S nan = TestFixture::nan, huge = std::numeric_limits<S>::max() / 2;
  auto refuse = [&](const fcl::CollisionGeometry<S>& other, const std::string& requirement,
                    const std::string& value) {
    fcl::DistanceResult<S> dresult;
    fcl::CollisionResult<S> cresult;
    expectRefused(
        [&] {
          fcl_superellipsoid::distance<S>(shape.get(), I, &other, I, fcl::DistanceRequest<S>(),
                                          dresult);
        },
        "superellipsoid distance", requirement, value);
    expectRefused(
        [&] {
          fcl_superellipsoid::collide<S>(&other, I, shape.get(), I, fcl::CollisionRequest<S>(),
                                         cresult);
        },
        "superellipsoid collide", requirement, value);
    fcl::detail::GJKSolver_libccd<S> solver;
    EXPECT_THROW(
        fcl::distance(shape.get(), I, &other, I, &solver, fcl::DistanceRequest<S>(), dresult),
        std::invalid_argument);
  };
  refuse(fcl::Capsule<S>(S(1), nan), "the other shape's lz must be finite", "nan");
  refuse(fcl::Box<S>(S(1), S(-2), S(1)), "the other shape's side must be finite, >= 0", "-2");
  refuse(fcl::Cylinder<S>(huge, S(1)), "the other shape's radius", "e+");
  refuse(fcl::Cone<S>(S(1), std::numeric_limits<S>::infinity()), "the other shape's lz", "inf");
  refuse(fcl::Sphere<S>(nan), "the other shape's radius", "nan");
  refuse(fcl::Ellipsoid<S>(S(1), S(-1), S(1)), "the other shape's radii", "-1");
  // An ellipsoid's radii: at most the superellipsoid's largest radius (the smooth pair).
  const bool is_float = std::is_same_v<S, float>;
  refuse(fcl::Ellipsoid<S>(S(1), S(1), S(2) * NumericRange<S>::kMaxRadius),
         std::string("the other shape's radii must be finite, >= 0 and <= ") +
             (is_float ? "1e+06" : "1e+50"),
         is_float ? "2000000" : "2.0000000000000002e+50");
  refuse(fcl::TriangleP<S>(Vector3<S>(0, 0, 0), Vector3<S>(nan, 0, 0), Vector3<S>(0, 1, 0)),
         "the other shape's vertex b must be finite", "nan");
  refuse(fcl::Halfspace<S>(Vector3<S>(0, 0, 1), huge), "the other shape's |d|", "e+");
}

}  // namespace
}  // namespace fcl_superellipsoid
