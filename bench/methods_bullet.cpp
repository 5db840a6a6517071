// Bullet's GJK/EPA against a convex shape whose support function is the exact
// superellipsoid's: what a physics-engine user would reach for. Debian's Bullet is built in
// single precision (btScalar = float), so this row carries float rounding as well as GJK's
// own tolerances (1e-4 in btGjkEpa2).

#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>

#include <cmath>

#include "bt_superellipsoid_shape.h"
#include "methods.h"

namespace fcl_superellipsoid {
namespace bench {
namespace {

class BulletMethod final : public Method {
 public:
  explicit BulletMethod(const BenchShape& shape)
      : Method(kBullet, "exact support, float", NAN, true, 5 * sizeof(double)),
        shape_(shape.make()) {}

  Answer query(const Vector3<double>& x) const override {
    btGjkEpaSolver2::sResults result;
    const btScalar d = btGjkEpaSolver2::SignedDistance(support::toBt(x), 0, &shape_,
                                                       btTransform::getIdentity(), result);
    // On failure Bullet returns SIMD_INFINITY, which is FLT_MAX (finite) in single precision.
    if (!(d < SIMD_INFINITY)) return {NAN, Vector3<double>::Constant(NAN), -1};
    return {double(d), support::fromBt(result.witnesses[0]), -1};
  }

 private:
  support::BtSuperellipsoidShape shape_;
};

}  // namespace

std::unique_ptr<Method> makeBulletMethod(const BenchShape& shape) {
  return std::make_unique<BulletMethod>(shape);
}

}  // namespace bench
}  // namespace fcl_superellipsoid
