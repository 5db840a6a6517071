// The GJKInitializer specialisation (gjk_support.h): libccd asks for support points in world
// coordinates through a C function pointer and an opaque object.
#include "fcl_superellipsoid/gjk_support.h"

namespace fcl {
namespace detail {
namespace {

template <typename S>
struct PosedSuperellipsoid {
  const fcl_superellipsoid::Superellipsoid<S>* shape;
  Transform3<S> X_WS;
};

template <typename S>
void supportSuperellipsoid(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  const auto* o = static_cast<const PosedSuperellipsoid<S>*>(object);
  const Vector3<S> d_W(S(direction->v[0]), S(direction->v[1]), S(direction->v[2]));
  const Vector3<S> p_W =
      o->X_WS * o->shape->supportPoint(Vector3<S>(o->X_WS.linear().transpose() * d_W));
  for (int i = 0; i < 3; ++i) out->v[i] = p_W[i];
}

template <typename S>
void centreSuperellipsoid(const void* object, ccd_vec3_t* out) {
  const auto* o = static_cast<const PosedSuperellipsoid<S>*>(object);
  for (int i = 0; i < 3; ++i) out->v[i] = o->X_WS.translation()[i];
}

}  // namespace

template <typename S>
GJKSupportFunction GJKInitializer<S, fcl_superellipsoid::Superellipsoid<S>>::getSupportFunction() {
  return &supportSuperellipsoid<S>;
}

template <typename S>
GJKCenterFunction GJKInitializer<S, fcl_superellipsoid::Superellipsoid<S>>::getCenterFunction() {
  return &centreSuperellipsoid<S>;
}

template <typename S>
void* GJKInitializer<S, fcl_superellipsoid::Superellipsoid<S>>::createGJKObject(
    const fcl_superellipsoid::Superellipsoid<S>& s, const Transform3<S>& tf) {
  return new PosedSuperellipsoid<S>{&s, tf};
}

template <typename S>
void GJKInitializer<S, fcl_superellipsoid::Superellipsoid<S>>::deleteGJKObject(void* o) {
  delete static_cast<PosedSuperellipsoid<S>*>(o);
}

template class GJKInitializer<float, fcl_superellipsoid::Superellipsoid<float>>;
template class GJKInitializer<double, fcl_superellipsoid::Superellipsoid<double>>;

}  // namespace detail
}  // namespace fcl
