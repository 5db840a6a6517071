#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_H

// Internal: distance and collision of a Superellipsoid with another geometry, results in the
// order (o1, o2) given. The FCL table entries and the front end both call these; the
// conventions are documented in fcl_integration.h. pairs.cpp dispatches to one file per pair
// kind (sphere, halfspace, smooth, libccd, mesh); docs/design.md → "Adding a pair".

#include <fcl/narrowphase/collision_request.h>
#include <fcl/narrowphase/collision_result.h>
#include <fcl/narrowphase/distance_request.h>
#include <fcl/narrowphase/distance_result.h>

#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {
namespace detail {

/// True if either geometry is a Superellipsoid<S>.
template <typename S>
bool involvesSuperellipsoid(const fcl::CollisionGeometry<S>* o1,
                            const fcl::CollisionGeometry<S>* o2);

/// FCL's table-entry contract: returns result.min_distance; an unsupported pair prints FCL's
/// warning and returns std::numeric_limits<S>::max() with result untouched.
template <typename S>
S pairDistance(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
               const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
               const fcl::DistanceRequest<S>& request, fcl::DistanceResult<S>& result);

/// Returns result.numContacts(); an unsupported pair prints FCL's warning and returns 0.
template <typename S>
std::size_t pairCollide(const fcl::CollisionGeometry<S>* o1, const fcl::Transform3<S>& tf1,
                        const fcl::CollisionGeometry<S>* o2, const fcl::Transform3<S>& tf2,
                        const fcl::CollisionRequest<S>& request, fcl::CollisionResult<S>& result);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_H
