#include "narrowphase/sphere_pair.h"

#include "fcl_superellipsoid/point_distance.h"

namespace fcl_superellipsoid {
namespace detail {
/// The sphere as a vertex with a radius: its centre's distance minus the radius.
template <typename S>
std::optional<PairHit<S>> sphereHit(const ShapePair<S>& pair, const fcl::Sphere<S>& sphere) {
  const Vector3<S> centre_W = pair.X_WO->translation();
  const PointDistanceResult<S> r =
      pointDistance(*pair.shape, *pair.X_WS, centre_W, pair.shape->queryOptions());
  return PairHit<S>{r.distance - sphere.radius, centre_W - sphere.radius * r.normal,
                    r.nearest_point, r.normal, -1};
}

#define FSE_INSTANTIATE_SPHERE_HIT(S) \
  template std::optional<PairHit<S>> sphereHit(const ShapePair<S>&, const fcl::Sphere<S>&);
FSE_INSTANTIATE_SPHERE_HIT(float)
FSE_INSTANTIATE_SPHERE_HIT(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
