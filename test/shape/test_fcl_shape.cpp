// The shape inside FCL: collision objects, bounding volumes and a broadphase manager.

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/utility.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision_object.h>

#include <memory>
#include <set>

#include "fcl_superellipsoid/superellipsoid.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

template <typename S>
fcl::Transform3<S> randomPose(std::mt19937& rng, double spread) {
  std::uniform_real_distribution<double> unit(-1, 1);
  const Eigen::Quaternion<double> q =
      Eigen::Quaternion<double>(unit(rng), unit(rng), unit(rng), unit(rng)).normalized();
  fcl::Transform3<S> tf = fcl::Transform3<S>::Identity();
  tf.linear() = q.toRotationMatrix().cast<S>();
  tf.translation() =
      Vector3<S>(S(unit(rng) * spread), S(unit(rng) * spread), S(unit(rng) * spread));
  return tf;
}

template <typename S>
class FclShapeTest : public ::testing::Test {};
TYPED_TEST_SUITE(FclShapeTest, test::Scalars);

TYPED_TEST(FclShapeTest, LocalAabbIsTight) {
  using S = TypeParam;
  const Superellipsoid<S> shape{S(3), S(2), S(1), S(0.3), S(1.6)};
  EXPECT_EQ(shape.aabb_local.min_, Vector3<S>(S(-3), S(-2), S(-1)));
  EXPECT_EQ(shape.aabb_local.max_, Vector3<S>(S(3), S(2), S(1)));
  EXPECT_TRUE(shape.aabb_center.isZero());
  EXPECT_NEAR(shape.aabb_radius, std::sqrt(S(14)), 4 * test::evalTolerance<S>());
  EXPECT_EQ(shape.getNodeType(), fcl::BV_UNKNOWN);
  EXPECT_EQ(shape.getObjectType(), fcl::OT_GEOM);
  // Tight: the extreme points of the surface reach every face of the box.
  EXPECT_NEAR(shape.surfacePoint(S(0), S(0))[0], S(3), 4 * test::evalTolerance<S>());
  EXPECT_NEAR(shape.surfacePoint(S(0), S(M_PI / 2))[1], S(2), 4 * test::evalTolerance<S>());
  EXPECT_NEAR(shape.surfacePoint(S(M_PI / 2), S(0))[2], S(1), 4 * test::evalTolerance<S>());
}

TYPED_TEST(FclShapeTest, WorldBoundingVolumesContainTheSurfaceUnderRandomPoses) {
  using S = TypeParam;
  std::mt19937 rng(5);
  test::AngleSampler angles(6);
  for (double e1 : {0.1, 1.0, 1.9}) {
    for (double e2 : {0.1, 1.0, 1.9}) {
      auto shape = std::make_shared<Superellipsoid<S>>(S(2), S(0.5), S(1), S(e1), S(e2));
      SCOPED_TRACE(test::describe(*shape));
      for (int pose = 0; pose < 20; ++pose) {
        const fcl::Transform3<S> tf = randomPose<S>(rng, 10);
        fcl::CollisionObject<S> object(shape, tf);
        object.computeAABB();
        fcl::OBB<S> obb;
        fcl::computeBV(*shape, tf, obb);  // generic path: getBoundVertices()
        fcl::OBBRSS<S> obbrss;
        fcl::computeBV(*shape, tf, obbrss);
        for (int k = 0; k < 50; ++k) {
          const auto [eta, omega] = angles();
          const Vector3<S> p_W = tf * shape->surfacePoint(S(eta), S(omega));
          // A relative slack of a few ulps of the coordinates for the posing arithmetic.
          fcl::AABB<S> grown = object.getAABB();
          grown.expand(Vector3<S>::Constant(S(1e-5) * S(20)));
          EXPECT_TRUE(grown.contain(p_W)) << p_W.transpose();
          EXPECT_TRUE(obb.contain(p_W)) << p_W.transpose();
        }
      }
    }
  }
}

// A callback that records which managed objects the broadphase reports for a probe.
template <typename S>
bool recordCandidate(fcl::CollisionObject<S>* a, fcl::CollisionObject<S>* b, void* data) {
  auto* found = static_cast<std::set<const void*>*>(data);
  found->insert(a->getUserData() ? a->getUserData() : b->getUserData());
  return false;
}

TYPED_TEST(FclShapeTest, BroadphaseFindsTheObjectWhereItShould) {
  using S = TypeParam;
  std::mt19937 rng(7);
  test::AngleSampler angles(8);
  std::vector<std::unique_ptr<fcl::CollisionObject<S>>> objects;
  std::vector<std::shared_ptr<Superellipsoid<S>>> shapes;
  fcl::DynamicAABBTreeCollisionManager<S> manager;
  for (int i = 0; i < 12; ++i) {
    shapes.push_back(std::make_shared<Superellipsoid<S>>(S(1 + 0.1 * i), S(0.5), S(0.8),
                                                         S(0.1 + 0.15 * i), S(1.9 - 0.15 * i)));
    objects.push_back(
        std::make_unique<fcl::CollisionObject<S>>(shapes.back(), randomPose<S>(rng, 30)));
    objects.back()->setUserData(objects.back().get());
    manager.registerObject(objects.back().get());
  }
  manager.setup();
  auto probe_shape = std::make_shared<fcl::Sphere<S>>(S(1e-3));
  for (const auto& object : objects) {
    const auto& shape = static_cast<const Superellipsoid<S>&>(*object->collisionGeometry());
    for (int k = 0; k < 20; ++k) {
      const auto [eta, omega] = angles();
      fcl::Transform3<S> at = fcl::Transform3<S>::Identity();
      at.translation() = object->getTransform() * shape.surfacePoint(S(eta), S(omega));
      fcl::CollisionObject<S> probe(probe_shape, at);
      probe.computeAABB();
      std::set<const void*> found;
      manager.collide(&probe, &found, recordCandidate<S>);
      EXPECT_EQ(found.count(object.get()), 1u) << "surface probe not reported";
    }
  }
  fcl::Transform3<S> far = fcl::Transform3<S>::Identity();
  far.translation() = Vector3<S>(S(500), S(500), S(500));
  fcl::CollisionObject<S> probe(probe_shape, far);
  probe.computeAABB();
  std::set<const void*> found;
  manager.collide(&probe, &found, recordCandidate<S>);
  EXPECT_TRUE(found.empty());
}

}  // namespace
}  // namespace fcl_superellipsoid
