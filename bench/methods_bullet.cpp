// Bullet's GJK/EPA against a convex shape whose support function is the exact
// superellipsoid's: what a physics-engine user would reach for. Debian's Bullet is built in
// single precision (btScalar = float), so this row carries float rounding as well as GJK's
// own tolerances (1e-4 in btGjkEpa2).

#include <BulletCollision/CollisionShapes/btConvexInternalShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>

#include <cmath>

#include "methods.h"

namespace fcl_superellipsoid {
namespace bench {
namespace {

btVector3 toBt(const Vector3<double>& v) {
  return btVector3(btScalar(v[0]), btScalar(v[1]), btScalar(v[2]));
}
Vector3<double> fromBt(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

/// A Bullet convex shape given by the closed-form support point of the superellipsoid
/// (Superellipsoid::supportPoint, computed in double), with no collision margin.
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

class BulletMethod final : public Method {
 public:
  explicit BulletMethod(const BenchShape& shape)
      : Method(kBullet, "exact support, float", NAN, true, 5 * sizeof(double)),
        shape_(shape.make()) {}

  Answer query(const Vector3<double>& x) const override {
    btGjkEpaSolver2::sResults result;
    const btScalar d =
        btGjkEpaSolver2::SignedDistance(toBt(x), 0, &shape_, btTransform::getIdentity(), result);
    // On failure Bullet returns SIMD_INFINITY, which is FLT_MAX (finite) in single precision.
    if (!(d < SIMD_INFINITY)) return {NAN, Vector3<double>::Constant(NAN), -1};
    return {double(d), fromBt(result.witnesses[0]), -1};
  }

 private:
  BtSuperellipsoidShape shape_;
};

}  // namespace

std::unique_ptr<Method> makeBulletMethod(const BenchShape& shape) {
  return std::make_unique<BulletMethod>(shape);
}

}  // namespace bench
}  // namespace fcl_superellipsoid
