#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_SPHERE_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_SPHERE_PAIR_H

// Internal: the superellipsoid against fcl::Sphere, exactly, as a vertex with a radius: the
// sphere's centre is answered by the point solver (the shape's queryOptions()), and the
// distance is the centre's signed distance minus the radius. Contact pos is halfway between
// the two surfaces along the shape's normal.

#include <cstddef>
#include <optional>

#include "fcl_glue/pairs/pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// Answers the pair if the other geometry is an fcl::Sphere: returns result.min_distance;
/// std::nullopt if it is not a sphere.
template <typename S>
std::optional<S> sphereDistance(const Pair<S>& pair, const fcl::DistanceRequest<S>& request,
                                fcl::DistanceResult<S>& result);

/// Adds the contact if the other geometry is an fcl::Sphere and they overlap; false if it is
/// not a sphere. `room` ≥ 1 is how many contacts the request still takes.
template <typename S>
bool sphereCollide(const Pair<S>& pair, const fcl::CollisionRequest<S>& request, std::size_t room,
                   fcl::CollisionResult<S>& result);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_SPHERE_PAIR_H
