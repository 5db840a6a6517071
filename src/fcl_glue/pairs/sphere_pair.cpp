#include "fcl_glue/pairs/sphere_pair.h"

#include <fcl/geometry/shape/sphere.h>

#include "fcl_superellipsoid/point_distance.h"

namespace fcl_superellipsoid {
namespace detail {
/// The sphere as a vertex with a radius: its centre's distance minus the radius.
template <typename S>
std::optional<PairHit<S>> sphereHit(const Pair<S>& pair) {
  const auto* sphere = otherAs<fcl::Sphere<S>>(pair, fcl::GEOM_SPHERE);
  if (sphere == nullptr) return std::nullopt;
  const Vector3<S> centre_W = pair.X_WO->translation();
  const PointDistanceResult<S> r =
      pointDistance(*pair.shape, *pair.X_WS, centre_W, pair.shape->queryOptions());
  return PairHit<S>{r.distance - sphere->radius, centre_W - sphere->radius * r.normal,
                    r.nearest_point, r.normal, -1};
}

#define FSE_INSTANTIATE_SPHERE_HIT(S) template std::optional<PairHit<S>> sphereHit(const Pair<S>&);
FSE_INSTANTIATE_SPHERE_HIT(float)
FSE_INSTANTIATE_SPHERE_HIT(double)

}  // namespace detail
}  // namespace fcl_superellipsoid
