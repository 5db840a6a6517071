#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SPHERE_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SPHERE_PAIR_H

// Internal: the superellipsoid against fcl::Sphere, exactly, as a vertex with a radius: the
// sphere's centre is answered by the point solver (the shape's queryOptions()), and the
// distance is the centre's signed distance minus the radius.

#include <fcl/geometry/shape/sphere.h>

#include <optional>

#include "narrowphase/shape_pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// The superellipsoid against a sphere.
template <typename S>
std::optional<PairHit<S>> sphereHit(const ShapePair<S>& pair, const fcl::Sphere<S>& sphere);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SPHERE_PAIR_H
