// The superellipsoid inside FCL: the front end and FCL's own tables against brute force over
// all vertices with the Exact solver, for every BV type, both argument orders, float and double.

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/sphere.h>
#include <gtest/gtest.h>

#include <random>

#include "fcl_glue/bvh_node.h"
#include "fcl_superellipsoid/diagnostics.h"
#include "fcl_superellipsoid/fcl_integration.h"
#include "fcl_superellipsoid/point_distance.h"
#include "fcl_superellipsoid/tessellation.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

template <typename S>
fcl::Transform3<S> randomPose(std::mt19937& rng, S spread) {
  std::uniform_real_distribution<double> u(-1, 1);
  fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
  const Eigen::Quaternion<S> q(S(u(rng)), S(u(rng)), S(u(rng)), S(u(rng)));
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = spread * Vector3<S>(S(u(rng)), S(u(rng)), S(u(rng)));
  return X;
}

/// A cloud around the shape: some vertices inside, most outside, a few far.
template <typename S>
TriangleMesh<S> randomCloud(std::mt19937& rng, int n, S extent) {
  std::uniform_real_distribution<double> u(-1, 1);
  TriangleMesh<S> mesh;
  for (int i = 0; i < n; ++i) {
    mesh.vertices.emplace_back(S(extent * u(rng)), S(extent * u(rng)), S(extent * u(rng)));
  }
  return mesh;
}

/// Brute force: every vertex through the point solver, in the world frame.
template <typename S>
struct Brute {
  S distance = std::numeric_limits<S>::infinity();
  int vertex = -1;
  Vector3<S> point_W, nearest_W;
  std::vector<std::pair<S, int>> inside;  // (distance, vertex), deepest first
};

template <typename S>
Brute<S> bruteForce(const TriangleMesh<S>& mesh, const fcl::Transform3<S>& X_WM,
                    const Superellipsoid<S>& shape, const fcl::Transform3<S>& X_WS) {
  Brute<S> b;
  for (int v = 0; v < static_cast<int>(mesh.vertices.size()); ++v) {
    const Vector3<S> p_W = X_WM * mesh.vertices[v];
    const auto r = pointDistance(shape, X_WS, p_W);
    if (r.distance < b.distance) {
      b.distance = r.distance;
      b.vertex = v;
      b.point_W = p_W;
      b.nearest_W = r.nearest_point;
    }
    if (shape.gauge(X_WS.inverse(Eigen::Isometry) * p_W) < S(1))
      b.inside.push_back({r.distance, v});
  }
  std::sort(b.inside.begin(), b.inside.end());
  return b;
}

template <typename S>
S tolerance() {
  return std::is_same<S, float>::value ? S(2e-4) : S(1e-9);
}

template <typename BV>
void checkAgainstBruteForce(bool point_cloud) {
  using S = typename BV::S;
  std::mt19937 rng(point_cloud ? 3 : 4);
  const auto shape = std::make_shared<Superellipsoid<S>>(S(1.2), S(0.8), S(0.6), S(0.4), S(1.3));
  const TriangleMesh<S> mesh =
      point_cloud ? randomCloud<S>(rng, 400, S(2))
                  : tessellate(Superellipsoid<S>(S(0.9), S(1.1), S(0.7), S(1), S(1)), 200);
  const auto model = makeBVHModel<BV>(mesh);
  for (int trial = 0; trial < 6; ++trial) {
    const fcl::Transform3<S> X_WS = randomPose<S>(rng, S(0.5));
    const fcl::Transform3<S> X_WM = randomPose<S>(rng, trial < 3 ? S(0.5) : S(3));
    const Brute<S> truth = bruteForce(mesh, X_WM, *shape, X_WS);
    SCOPED_TRACE("trial " + std::to_string(trial) + ", truth " + std::to_string(truth.distance));
    for (bool shape_first : {true, false}) {
      SCOPED_TRACE(shape_first ? "shape first" : "mesh first");
      fcl::CollisionObject<S> o_shape(shape, X_WS), o_mesh(model, X_WM);
      const auto* o1 = shape_first ? &o_shape : &o_mesh;
      const auto* o2 = shape_first ? &o_mesh : &o_shape;
      const int mesh_index = shape_first ? 1 : 0;

      // Distance, signed, with nearest points: the front end, caller order.
      fcl::DistanceRequest<S> request(true, true);
      fcl::DistanceResult<S> result;
      const S d = fcl_superellipsoid::distance(o1, o2, request, result);
      EXPECT_NEAR(d, truth.distance, tolerance<S>());
      EXPECT_EQ(result.o1, o1->collisionGeometry().get());
      EXPECT_EQ(mesh_index == 0 ? result.b1 : result.b2, truth.vertex);
      EXPECT_EQ(mesh_index == 0 ? result.b2 : result.b1, int(fcl::DistanceResult<S>::NONE));
      EXPECT_LT((result.nearest_points[mesh_index] - truth.point_W).norm(), tolerance<S>());
      EXPECT_LT((result.nearest_points[1 - mesh_index] - truth.nearest_W).norm(),
                10 * tolerance<S>());

      // Through FCL's own call with its solver: FCL's (mesh, shape) order, and for a
      // penetration its signed-distance fallback (collide with one contact).
      fcl::detail::GJKSolver_libccd<S> solver;
      fcl::DistanceResult<S> fcl_result;
      fcl::distance(o1, o2, &solver, request, fcl_result);
      EXPECT_NEAR(fcl_result.min_distance, truth.distance, tolerance<S>());
      EXPECT_EQ(fcl_result.o1, o_mesh.collisionGeometry().get());

      // Unsigned: −1 on penetration (FCL's convention), the distance otherwise.
      fcl::DistanceResult<S> unsigned_result;
      fcl_superellipsoid::distance(o1, o2, fcl::DistanceRequest<S>(), unsigned_result);
      EXPECT_EQ(unsigned_result.min_distance,
                truth.distance < 0 ? S(-1) : unsigned_result.min_distance);
      if (truth.distance >= 0)
        EXPECT_NEAR(unsigned_result.min_distance, truth.distance, tolerance<S>());

      // Collision: the deepest num_max_contacts penetrating vertices, deepest first.
      for (std::size_t max_contacts : {std::size_t(1), std::size_t(5), std::size_t(100000)}) {
        fcl::CollisionRequest<S> crequest(max_contacts, true);
        fcl::CollisionResult<S> cresult;
        fcl_superellipsoid::collide(o1, o2, crequest, cresult);
        const std::size_t expected = std::min(max_contacts, truth.inside.size());
        ASSERT_EQ(cresult.numContacts(), expected) << "max_contacts " << max_contacts;
        for (std::size_t k = 0; k < expected; ++k) {
          const fcl::Contact<S>& c = cresult.getContact(k);
          EXPECT_EQ(c.o1, o1->collisionGeometry().get());
          EXPECT_NEAR(c.penetration_depth, -truth.inside[k].first, tolerance<S>());
          const Vector3<S> vertex_W = X_WM * mesh.vertices[mesh_index == 0 ? c.b1 : c.b2];
          EXPECT_LT((c.pos - vertex_W).norm(), tolerance<S>());
          // Moving o2 along the normal separates: the vertex leaves along the shape's normal.
          const auto r = pointDistance(*shape, X_WS, vertex_W);
          const Vector3<S> expected_normal = shape_first ? r.normal : Vector3<S>(-r.normal);
          EXPECT_LT((c.normal - expected_normal).norm(), 10 * tolerance<S>());
        }
        // Through FCL's own call: the same count (FCL's order).
        fcl::CollisionResult<S> fcl_cresult;
        fcl::collide(o1, o2, &solver, crequest, fcl_cresult);
        EXPECT_EQ(fcl_cresult.numContacts(), expected);
      }
      // enable_contact = false: the count, and no uninitialised fields.
      fcl::CollisionRequest<S> bare(3, false);
      fcl::CollisionResult<S> bare_result;
      fcl_superellipsoid::collide(o1, o2, bare, bare_result);
      EXPECT_EQ(bare_result.numContacts(), std::min<std::size_t>(3, truth.inside.size()));
      for (std::size_t k = 0; k < bare_result.numContacts(); ++k) {
        EXPECT_EQ(bare_result.getContact(k).pos, Vector3<S>::Zero());
        EXPECT_EQ(bare_result.getContact(k).normal, Vector3<S>::Zero());
        EXPECT_EQ(bare_result.getContact(k).penetration_depth, S(0));
      }
    }
  }
}

template <typename S>
class FclIntegrationTest : public ::testing::Test {};
TYPED_TEST_SUITE(FclIntegrationTest, test::Scalars);

// Every BV type of FCL's BVHModel, in float and double, against brute force.
template <typename BV>
class FclIntegrationBvTest : public ::testing::Test {};
using BvTypes =
    ::testing::Types<fcl::AABB<float>, fcl::OBB<float>, fcl::RSS<float>, fcl::kIOS<float>,
                     fcl::OBBRSS<float>, fcl::KDOP<float, 16>, fcl::KDOP<float, 18>,
                     fcl::KDOP<float, 24>, fcl::AABB<double>, fcl::OBB<double>, fcl::RSS<double>,
                     fcl::kIOS<double>, fcl::OBBRSS<double>, fcl::KDOP<double, 16>,
                     fcl::KDOP<double, 18>, fcl::KDOP<double, 24>>;
TYPED_TEST_SUITE(FclIntegrationBvTest, BvTypes);

TYPED_TEST(FclIntegrationBvTest, MatchesBruteForce) {
  for (bool cloud : {true, false}) {
    SCOPED_TRACE(cloud ? "point cloud" : "triangle mesh");
    checkAgainstBruteForce<TypeParam>(cloud);
  }
}

// A sphere is a vertex with a radius: exact through the point solver, either order.
TYPED_TEST(FclIntegrationTest, SphereIsAVertexWithARadius) {
  using S = TypeParam;
  std::mt19937 rng(9);
  const auto shape = std::make_shared<Superellipsoid<S>>(S(1), S(0.7), S(0.5), S(1.5), S(0.3));
  const auto sphere = std::make_shared<fcl::Sphere<S>>(S(0.25));
  for (int trial = 0; trial < 20; ++trial) {
    const fcl::Transform3<S> X_WS = randomPose<S>(rng, S(0.3));
    const fcl::Transform3<S> X_WB = randomPose<S>(rng, S(1.5));
    const auto r = pointDistance(*shape, X_WS, X_WB.translation());
    const S expected = r.distance - sphere->radius;
    fcl::CollisionObject<S> a(shape, X_WS), b(sphere, X_WB);
    for (bool shape_first : {true, false}) {
      const auto* o1 = shape_first ? &a : &b;
      const auto* o2 = shape_first ? &b : &a;
      fcl::DistanceResult<S> result;
      fcl_superellipsoid::distance(o1, o2, fcl::DistanceRequest<S>(true, true), result);
      EXPECT_NEAR(result.min_distance, expected, tolerance<S>());
      const int on_sphere = shape_first ? 1 : 0;
      EXPECT_NEAR((result.nearest_points[on_sphere] - X_WB.translation()).norm(), sphere->radius,
                  tolerance<S>());
      fcl::detail::GJKSolver_libccd<S> solver;
      fcl::DistanceResult<S> fcl_result;
      fcl::distance(o1, o2, &solver, fcl::DistanceRequest<S>(true, true), fcl_result);
      EXPECT_NEAR(fcl_result.min_distance, expected, tolerance<S>());
      fcl::CollisionResult<S> cresult;
      fcl_superellipsoid::collide(o1, o2, fcl::CollisionRequest<S>(1, true), cresult);
      EXPECT_EQ(cresult.numContacts(), expected < 0 ? 1u : 0u);
      if (cresult.numContacts() == 1) {
        EXPECT_NEAR(cresult.getContact(0).penetration_depth, -expected, tolerance<S>());
        // The normal points from o1 to o2: toward the sphere when the shape is o1.
        const Vector3<S> n = shape_first ? r.normal : Vector3<S>(-r.normal);
        EXPECT_LT((cresult.getContact(0).normal - n).norm(), 10 * tolerance<S>());
      }
    }
  }
}

/// A user's own geometry: FCL gives it BV_UNKNOWN, the superellipsoid's node type, and the
/// library has no answer for it.
template <typename S>
struct UserGeometry : fcl::CollisionGeometry<S> {
  void computeLocalAABB() override {
    this->aabb_local = fcl::AABB<S>(Vector3<S>::Constant(-1), Vector3<S>::Constant(1));
  }
};

// Pairs without an answer are refused with FCL's warning, never a crash.
TYPED_TEST(FclIntegrationTest, UnsupportedPairsAreRefused) {
  using S = TypeParam;
  const auto shape = std::make_shared<Superellipsoid<S>>(S(1), S(1), S(1), S(1), S(1));
  const auto user = std::make_shared<UserGeometry<S>>();
  fcl::CollisionObject<S> a(shape), b(user);
  for (bool shape_first : {true, false}) {
    const auto* o1 = shape_first ? &a : &b;
    const auto* o2 = shape_first ? &b : &a;
    fcl::DistanceResult<S> result;
    EXPECT_EQ(fcl_superellipsoid::distance(o1, o2, fcl::DistanceRequest<S>(), result),
              std::numeric_limits<S>::max());
    fcl::CollisionResult<S> cresult;
    EXPECT_EQ(fcl_superellipsoid::collide(o1, o2, fcl::CollisionRequest<S>(), cresult), 0u);
    fcl::detail::GJKSolver_libccd<S> solver;
    fcl::DistanceResult<S> fcl_result;
    fcl::distance(o1, o2, &solver, fcl::DistanceRequest<S>(), fcl_result);
    EXPECT_EQ(fcl_result.min_distance, std::numeric_limits<S>::max());
    EXPECT_EQ(fcl::collide(o1, o2, &solver, fcl::CollisionRequest<S>(), cresult), 0u);
  }
}

// Far apart, at the edge of the numeric range (docs/hardening.md → "Numeric range": coordinates
// up to a quarter of the largest finite value; here an eighth, so that the partner's vertices
// stay inside): a sphere, a point cloud and a triangle mesh, either order, through the front end
// and FCL's call; the distance is the separation less the radii, to rounding.
TYPED_TEST(FclIntegrationTest, FarApartObjects) {
  using S = TypeParam;
  const S far = std::numeric_limits<S>::max() / 8;
  const auto shape = std::make_shared<Superellipsoid<S>>(S(1), S(0.5), S(0.5), S(0.6), S(0.9));
  const auto sphere = std::make_shared<fcl::Sphere<S>>(S(0.5));
  TriangleMesh<S> cloud;
  cloud.vertices = {Vector3<S>(0, 0, 0), Vector3<S>(S(3), S(1), 0), Vector3<S>(0, S(2), S(1))};
  const auto points = makeBVHModel<fcl::OBBRSS<S>>(cloud);
  const auto mesh = makeBVHModel<fcl::RSS<S>>(tessellate(Superellipsoid<S>(1, 1, 1, 1, 1), 50));
  const fcl::Transform3<S> X_far(fcl::Translation3<S>(far, 0, 0));
  const fcl::CollisionObject<S> o_shape(shape), o_sphere(sphere, X_far), o_points(points, X_far),
      o_mesh(mesh, X_far);
  const S rounding = 16 * std::numeric_limits<S>::epsilon() * far;
  fcl::detail::GJKSolver_libccd<S> solver;
  for (const auto* other : {&o_sphere, &o_points, &o_mesh}) {
    // (The mesh's nearest vertex is 1 from its centre: lost to rounding at this distance.)
    const S expected = far - S(1) - (other == &o_sphere ? S(0.5) : S(0));
    for (bool shape_first : {true, false}) {
      const auto* o1 = shape_first ? &o_shape : other;
      const auto* o2 = shape_first ? other : &o_shape;
      fcl::DistanceResult<S> front, table;
      const fcl::DistanceRequest<S> request(true, true);
      EXPECT_NEAR(fcl_superellipsoid::distance(o1, o2, request, front), expected, rounding);
      EXPECT_TRUE(front.nearest_points[0].allFinite() && front.nearest_points[1].allFinite());
      fcl::distance(o1, o2, &solver, request, table);
      EXPECT_NEAR(table.min_distance, expected, rounding);
      fcl::CollisionResult<S> contacts;
      EXPECT_EQ(fcl_superellipsoid::collide(o1, o2, fcl::CollisionRequest<S>(10, true), contacts),
                0u);
    }
  }
}

// Debian's plain fcl::distance runs in libfcl with its private tables: a warning, no crash.
TEST(FclIntegration, PlainFclCallWarnsWithoutCrashing) {
  const auto shape = std::make_shared<Superellipsoidd>(1, 1, 1, 1, 1);
  const auto sphere = std::make_shared<fcl::Sphered>(0.5);
  fcl::CollisionObjectd a(shape), b(sphere, fcl::Transform3d(fcl::Translation3d(3, 0, 0)));
  fcl::DistanceResultd result;
  fcl::distance(&a, &b, fcl::DistanceRequestd(), result);
  fcl::CollisionResultd cresult;
  EXPECT_EQ(fcl::collide(&a, &b, fcl::CollisionRequestd(), cresult), 0u);
  // Pairs without a superellipsoid still go to plain FCL through the front end.
  fcl::CollisionObjectd c(sphere, fcl::Transform3d(fcl::Translation3d(0.5, 0, 0)));
  fcl::CollisionObjectd d(sphere, fcl::Transform3d(fcl::Translation3d(3.5, 0, 0)));
  fcl::DistanceResultd r2;
  EXPECT_NEAR(fcl_superellipsoid::distance(&c, &d, fcl::DistanceRequestd(), r2), 2.0, 1e-6);
}

// A broadphase scene with the front end's callbacks: a superellipsoid, a cloth-like mesh
// and a point cloud.
TYPED_TEST(FclIntegrationTest, BroadphaseWithTheCallbacks) {
  using S = TypeParam;
  std::mt19937 rng(12);
  const auto shape = std::make_shared<Superellipsoid<S>>(S(1), S(0.8), S(0.6), S(0.5), S(1.2));
  const TriangleMesh<S> cloth_mesh =
      tessellate(Superellipsoid<S>(S(2), S(2), S(0.05), S(1), S(0.2)), 300);
  const TriangleMesh<S> cloud = randomCloud<S>(rng, 500, S(0.5));
  const auto cloth = makeBVHModel<fcl::OBBRSS<S>>(cloth_mesh);
  const auto points = makeBVHModel<fcl::OBBRSS<S>>(cloud);
  const fcl::Transform3<S> X_WS = randomPose<S>(rng, S(0.1));
  fcl::Transform3<S> X_WC = fcl::Transform3<S>::Identity();
  X_WC.translation() = Vector3<S>(0, 0, S(0.55));
  fcl::Transform3<S> X_WP = fcl::Transform3<S>::Identity();
  // Clear of the cloth: FCL itself cannot collide a point cloud with a mesh.
  X_WP.translation() = Vector3<S>(S(0.3), 0, S(-0.3));
  fcl::CollisionObject<S> o_shape(shape, X_WS), o_cloth(cloth, X_WC), o_points(points, X_WP);
  fcl::DynamicAABBTreeCollisionManager<S> manager;
  manager.registerObjects({&o_shape, &o_cloth, &o_points});
  manager.setup();

  fcl::DefaultCollisionData<S> cdata;
  cdata.request.num_max_contacts = 1000000;
  cdata.request.enable_contact = true;
  manager.collide(&cdata, defaultCollisionFunction<S>);
  const std::size_t expected = bruteForce(cloth_mesh, X_WC, *shape, X_WS).inside.size() +
                               bruteForce(cloud, X_WP, *shape, X_WS).inside.size();
  EXPECT_GT(expected, 0u);
  EXPECT_EQ(cdata.result.numContacts(), expected);

  // Distance from the shape to the scene (the shape against the manager), moved clear of both,
  // against the pairwise minimum.
  fcl::Transform3<S> far = X_WS;
  far.translation() += Vector3<S>(0, 0, S(-4));
  o_shape.setTransform(far);
  o_shape.computeAABB();
  manager.unregisterObject(&o_shape);
  fcl::DefaultDistanceData<S> ddata;
  ddata.request.enable_signed_distance = true;
  manager.distance(&o_shape, &ddata, defaultDistanceFunction<S>);
  const S expected_distance = std::min({bruteForce(cloth_mesh, X_WC, *shape, far).distance,
                                        bruteForce(cloud, X_WP, *shape, far).distance});
  EXPECT_NEAR(ddata.result.min_distance, expected_distance, tolerance<S>());
}

/// Checks the inline node accessors (fcl_glue/bvh_node.h) against libfcl's on every node of a
/// model; returns its number of leaves.
template <typename BV>
int checkNodeAccessors(const fcl::BVHModel<BV>& model) {
  int leaves = 0;
  for (int i = 0; i < model.getNumBVs(); ++i) {
    const fcl::BVNodeBase& n = model.getBV(i);
    EXPECT_EQ(detail::isLeaf(n), n.isLeaf()) << "node " << i;
    if (n.isLeaf()) {
      ++leaves;
      EXPECT_EQ(detail::primitiveId(n), n.primitiveId()) << "node " << i;
    } else {
      EXPECT_EQ(detail::leftChild(n), n.leftChild()) << "node " << i;
      EXPECT_EQ(detail::rightChild(n), n.rightChild()) << "node " << i;
    }
  }
  return leaves;
}

// The traversal reads fcl's node encoding inline: it must agree with libfcl's own accessors,
// on a point cloud's tree and on a mesh's (one leaf per vertex, per triangle).
TEST(FclIntegration, InlineNodeAccessorsAgreeWithLibfcl) {
  std::mt19937 rng(9);
  const TriangleMesh<double> cloud = randomCloud<double>(rng, 3000, 2);
  const TriangleMesh<double> mesh = tessellate(Superellipsoidd(1, 2, 3, 0.4, 1.6), 500);
  EXPECT_EQ(checkNodeAccessors(*makeBVHModel<fcl::OBBRSSd>(cloud)), 3000);
  EXPECT_EQ(checkNodeAccessors(*makeBVHModel<fcl::AABBd>(mesh)), int(mesh.triangles.size()));
}

// Culling: a large cloud far from most of the shape is answered from a small part of it.
TEST(FclIntegration, TraversalCullsFarVertices) {
  std::mt19937 rng(5);
  const auto shape = std::make_shared<Superellipsoidd>(1, 1, 1, 0.5, 0.5);
  const TriangleMesh<double> cloud = randomCloud<double>(rng, 20000, 10);
  const auto model = makeBVHModel<fcl::OBBRSSd>(cloud);
  fcl::CollisionObjectd a(shape), b(model);
  vertexTraversalStats() = {};
  fcl::DistanceResultd result;
  fcl_superellipsoid::distance(&a, &b, fcl::DistanceRequestd(true, true), result);
  EXPECT_LT(vertexTraversalStats().vertices_solved, 200u);
  EXPECT_NEAR(result.min_distance,
              bruteForce(cloud, fcl::Transform3d::Identity(), *shape, fcl::Transform3d::Identity())
                  .distance,
              1e-9);
}

// Many penetrating vertices: the traversal hands them to the batched queries, which cut them
// into chunks on several threads. Every contact and the distance still match brute force, for
// a smooth and a creased shape (the inside certificate on and off), float and double.
TYPED_TEST(FclIntegrationTest, ManyContactsMatchBruteForce) {
  using S = TypeParam;
  std::mt19937 rng(6);
  for (const auto& e : std::vector<std::array<double, 2>>{{0.4, 0.3}, {1.3, 0.7}}) {
    const auto shape = std::make_shared<Superellipsoid<S>>(S(1.2), S(1), S(0.8), S(e[0]), S(e[1]));
    SCOPED_TRACE(test::describe(*shape));
    const TriangleMesh<S> cloud = randomCloud<S>(rng, 6000, S(1.3));
    const auto model = makeBVHModel<fcl::OBBRSS<S>>(cloud);
    const fcl::Transform3<S> X_WS = randomPose<S>(rng, S(0.1));
    fcl::CollisionObject<S> o_shape(shape, X_WS), o_cloud(model);
    const Brute<S> truth = bruteForce(cloud, fcl::Transform3<S>::Identity(), *shape, X_WS);
    ASSERT_GT(truth.inside.size(), 1100u);  // enough for the batched queries' threads
    fcl::CollisionResult<S> result;
    fcl_superellipsoid::collide(&o_shape, &o_cloud, fcl::CollisionRequest<S>(100000, true), result);
    ASSERT_EQ(result.numContacts(), truth.inside.size());
    for (std::size_t k = 0; k < truth.inside.size(); ++k) {
      EXPECT_NEAR(result.getContact(k).penetration_depth, -truth.inside[k].first, tolerance<S>());
    }
    fcl::DistanceResult<S> distance;
    fcl_superellipsoid::distance(&o_shape, &o_cloud, fcl::DistanceRequest<S>(true, true), distance);
    EXPECT_NEAR(distance.min_distance, truth.distance, tolerance<S>());
  }
}

// A distance query against a cloud deep in the shape solves its survivors nearest lower bound
// first and skips those that cannot beat the best solved distance: the same vertex as brute
// force, also when the deepest vertex is there twice (the lower index wins), while solving a
// small fraction of the penetrating vertices.
TYPED_TEST(FclIntegrationTest, DistanceSolvesFewOfManyPenetratingVertices) {
  using S = TypeParam;
  std::mt19937 rng(8);
  for (const auto& e : std::vector<std::array<double, 2>>{{0.4, 0.3}, {1.3, 0.7}, {1, 1}}) {
    const auto shape = std::make_shared<Superellipsoid<S>>(S(1.2), S(1), S(0.8), S(e[0]), S(e[1]));
    SCOPED_TRACE(test::describe(*shape));
    TriangleMesh<S> cloud = randomCloud<S>(rng, 3000, S(1.3));
    const fcl::Transform3<S> X_WS = randomPose<S>(rng, S(0.1));
    const Brute<S> first = bruteForce(cloud, fcl::Transform3<S>::Identity(), *shape, X_WS);
    ASSERT_GT(first.inside.size(), 500u);
    // The deepest vertex again, at the end: a tie that the lower index must win.
    cloud.vertices.push_back(cloud.vertices[std::size_t(first.vertex)]);
    const Brute<S> truth = bruteForce(cloud, fcl::Transform3<S>::Identity(), *shape, X_WS);
    ASSERT_EQ(truth.vertex, first.vertex);
    const auto model = makeBVHModel<fcl::OBBRSS<S>>(cloud);
    for (bool shape_first : {true, false}) {
      fcl::CollisionObject<S> o_shape(shape, X_WS), o_cloud(model);
      vertexTraversalStats() = {};
      fcl::DistanceResult<S> result;
      if (shape_first) {
        fcl_superellipsoid::distance(&o_shape, &o_cloud, fcl::DistanceRequest<S>(true, true),
                                     result);
      } else {
        fcl_superellipsoid::distance(&o_cloud, &o_shape, fcl::DistanceRequest<S>(true, true),
                                     result);
      }
      EXPECT_NEAR(result.min_distance, truth.distance, tolerance<S>());
      EXPECT_EQ(shape_first ? result.b2 : result.b1, truth.vertex);
      EXPECT_LT(vertexTraversalStats().vertices_solved, truth.inside.size() / 10);
    }
  }
}

// Per-shape options reach the vertex queries.
TEST(FclIntegration, ShapeOptionsReachTheQueries) {
  const auto shape = std::make_shared<Superellipsoidd>(1, 0.6, 0.4, 1.7, 0.3);
  shape->setQueryOptions(DistanceOptions<double>::of(DistanceMethod::kRadial));
  EXPECT_THROW(shape->setQueryOptions({DistanceMethod::kExact, -1.0, 10}), std::invalid_argument);
  const auto sphere = std::make_shared<fcl::Sphered>(0.1);
  const fcl::Transform3d X_WB(fcl::Translation3d(0.9, 0.7, 0.5));
  fcl::CollisionObjectd a(shape), b(sphere, X_WB);
  fcl::DistanceResultd result;
  fcl_superellipsoid::distance(&a, &b, fcl::DistanceRequestd(), result);
  const auto radial = pointDistance(*shape, Vector3<double>(0.9, 0.7, 0.5),
                                    DistanceOptions<double>::of(DistanceMethod::kRadial));
  EXPECT_DOUBLE_EQ(result.min_distance, radial.distance - 0.1);
}

}  // namespace
}  // namespace fcl_superellipsoid
