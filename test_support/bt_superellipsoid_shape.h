#ifndef FCL_SUPERELLIPSOID_SUPPORT_BT_SUPERELLIPSOID_SHAPE_H
#define FCL_SUPERELLIPSOID_SUPPORT_BT_SUPERELLIPSOID_SHAPE_H

// The superellipsoid as a Bullet convex shape, for the peers the benchmark and the scene
// runner measure against: Bullet's GJK/EPA, soft bodies and rigid bodies see the exact
// surface through its closed-form support point (Superellipsoid::supportPoint, in double).
// Debian's Bullet is single precision (btScalar = float).

#include <BulletCollision/CollisionShapes/btConvexInternalShape.h>
#include <fcl_superellipsoid/superellipsoid.h>

namespace fcl_superellipsoid {
namespace support {

inline btVector3 toBt(const Vector3<double>& v) {
  return btVector3(btScalar(v[0]), btScalar(v[1]), btScalar(v[2]));
}
inline Vector3<double> fromBt(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

/// A Bullet convex shape given by the superellipsoid's support point; no collision margin
/// unless the caller sets one.
class BtSuperellipsoidShape final : public btConvexInternalShape {
 public:
  explicit BtSuperellipsoidShape(const Superellipsoid<double>& shape) : shape_(shape) {
    m_shapeType = CUSTOM_CONVEX_SHAPE_TYPE;
    setMargin(0);
  }

  btVector3 localGetSupportingVertexWithoutMargin(const btVector3& direction) const override {
    return toBt(shape_.supportPoint(fromBt(direction)));
  }
  void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* directions,
                                                         btVector3* out, int count) const override {
    for (int i = 0; i < count; ++i) out[i] = localGetSupportingVertexWithoutMargin(directions[i]);
  }
  void getAabb(const btTransform& t, btVector3& aabb_min, btVector3& aabb_max) const override {
    getAabbSlow(t, aabb_min, aabb_max);
  }
  void calculateLocalInertia(btScalar mass, btVector3& inertia) const override {
    const fcl::Matrix3<double> unit_density = shape_.computeMomentofInertia();
    const double scale = mass / shape_.computeVolume();
    inertia = btVector3(btScalar(scale * unit_density(0, 0)), btScalar(scale * unit_density(1, 1)),
                        btScalar(scale * unit_density(2, 2)));
  }
  const char* getName() const override { return "Superellipsoid"; }

 private:
  Superellipsoid<double> shape_;
};

}  // namespace support
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SUPPORT_BT_SUPERELLIPSOID_SHAPE_H
