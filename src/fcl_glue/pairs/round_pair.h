#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_ROUND_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_ROUND_PAIR_H

// Internal: the superellipsoid against fcl::Cylinder and fcl::Cone, exactly when they are
// separated (docs/math.md → "Shape pairs"). Their features: the flat ends (the superellipsoid's
// support point against the disc's normal, if it lands on the disc), the side (a one-parameter
// family of normals: a search over its angle), the rims (a search along the circle with the
// point solver) and the cone's apex (the point solver). The candidates are the features within
// a margin of the start's witness (our GJK, gjk.h); as for polytopes (polytope_pair.h) each is
// certified by its duality gap, and overlapping shapes, or no certified candidate, get the least
// F over candidate directions (depth_candidates.h).

#include <optional>

#include "fcl_glue/pairs/pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// The hit if the other geometry is a Cylinder or a Cone; std::nullopt otherwise.
template <typename S>
std::optional<PairHit<S>> roundHit(const Pair<S>& pair);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_ROUND_PAIR_H
