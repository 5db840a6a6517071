#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_HALFSPACE_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_HALFSPACE_PAIR_H

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

#include <optional>

#include "fcl_glue/pairs/pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// The hit if the other geometry is an fcl::Halfspace or an fcl::Plane; std::nullopt otherwise.
template <typename S>
std::optional<PairHit<S>> halfspaceHit(const Pair<S>& pair);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_HALFSPACE_PAIR_H
