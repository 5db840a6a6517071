#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_POLYTOPE_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_POLYTOPE_PAIR_H

// Internal: the superellipsoid against a polytope (fcl::Box, fcl::Convex, fcl::TriangleP),
// exactly when they are separated (docs/math.md → "Shape pairs"). The distance to a polytope is
// reached on one of its features: a face (the superellipsoid's support point against the face's
// normal, if it projects inside the face), an edge (segment_search.h) or a vertex (the point
// solver). A start (our GJK, gjk.h) picks the candidates: the features spanned by the vertices
// that are within a margin of the polytope's support along its normal. Each candidate is a pair
// of real surface points, so its distance is an upper bound; the support functions along its
// normal give a lower bound; the first candidate whose bounds meet (the duality gap below
// 1e-12 × size) is the answer. Overlapping, or with no candidate certified, the least F over
// candidate directions (depth_candidates.h); candidates.h chains the two.

#include <optional>

#include "fcl_glue/pairs/pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// The hit if the other geometry is a Box, Convex or TriangleP; std::nullopt otherwise.
template <typename S>
std::optional<PairHit<S>> polytopeHit(const Pair<S>& pair);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_POLYTOPE_PAIR_H
