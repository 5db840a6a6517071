#include "fcl_glue/pairs/sphere_pair.h"

#include <fcl/geometry/shape/sphere.h>

#include "fcl_superellipsoid/point_distance.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

/// The sphere as a vertex with a radius: its centre's distance minus the radius.
template <typename S>
PairHit<S> sphereHit(const Pair<S>& pair, const fcl::Sphere<S>& sphere) {
  const Vector3<S> centre_W = pair.X_WO->translation();
  const PointDistanceResult<S> r =
      pointDistance(*pair.shape, *pair.X_WS, centre_W, pair.shape->queryOptions());
  return {r.distance - sphere.radius, centre_W - sphere.radius * r.normal, r.nearest_point,
          r.normal, -1};
}

}  // namespace

template <typename S>
std::optional<S> sphereDistance(const Pair<S>& pair, const fcl::DistanceRequest<S>& request,
                                fcl::DistanceResult<S>& result) {
  const auto* sphere = dynamic_cast<const fcl::Sphere<S>*>(pair.other);
  if (sphere == nullptr) return std::nullopt;
  updateDistance(pair, sphereHit(pair, *sphere), request, result);
  return result.min_distance;
}

template <typename S>
bool sphereCollide(const Pair<S>& pair, const fcl::CollisionRequest<S>& request,
                   std::size_t /*room: one contact at most*/, fcl::CollisionResult<S>& result) {
  const auto* sphere = dynamic_cast<const fcl::Sphere<S>*>(pair.other);
  if (sphere == nullptr) return false;
  const PairHit<S> hit = sphereHit(pair, *sphere);
  if (hit.distance < S(0)) {
    addContact(pair, hit, Vector3<S>(S(0.5) * (hit.on_shape + hit.on_other)),
               request.enable_contact, result);
  }
  return true;
}

#define FSE_INSTANTIATE_SPHERE_PAIR(S)                                                      \
  template std::optional<S> sphereDistance(const Pair<S>&, const fcl::DistanceRequest<S>&,  \
                                           fcl::DistanceResult<S>&);                        \
  template bool sphereCollide(const Pair<S>&, const fcl::CollisionRequest<S>&, std::size_t, \
                              fcl::CollisionResult<S>&);
FSE_INSTANTIATE_SPHERE_PAIR(float)
FSE_INSTANTIATE_SPHERE_PAIR(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
