#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_SPHERE_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_SPHERE_PAIR_H

// Internal: the superellipsoid against fcl::Sphere, exactly, as a vertex with a radius: the
// sphere's centre is answered by the point solver (the shape's queryOptions()), and the
// distance is the centre's signed distance minus the radius.

#include <optional>

#include "fcl_glue/pairs/pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// The hit if the other geometry is an fcl::Sphere; std::nullopt otherwise.
template <typename S>
std::optional<PairHit<S>> sphereHit(const Pair<S>& pair);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_SPHERE_PAIR_H
