#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_HALFSPACE_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_HALFSPACE_PAIR_H

// Internal: the superellipsoid against fcl::Halfspace and fcl::Plane, in closed form through
// the support function (docs/math.md → "Shape pairs"). For the plane n·x = d (unit n, world):
//   lowest = −h(−n) = min over the shape of n·x,  highest = h(n),
// at the support points s(−n), s(n).
// - Halfspace n·x ≤ d: signed distance lowest − d, witness s(−n) and its projection on the
//   boundary plane; the shape's normal towards the halfspace is −n.
// - Plane: the distance to the nearer side (lowest − d above the plane, d − highest below it);
//   a shape that straddles it is pushed out to the side it needs the shorter move to, and its
//   depth is that move: min(d − lowest, highest − d).
// Contact pos: halfway between the witness and its projection on the plane.

#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>

#include <optional>

#include "narrowphase/shape_pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// The superellipsoid against a halfspace, a plane.
template <typename S>
std::optional<PairHit<S>> halfspaceHit(const ShapePair<S>& pair,
                                       const fcl::Halfspace<S>& halfspace);
template <typename S>
std::optional<PairHit<S>> planeHit(const ShapePair<S>& pair, const fcl::Plane<S>& plane);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_HALFSPACE_PAIR_H
