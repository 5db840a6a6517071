#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_LIBCCD_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_LIBCCD_PAIR_H

// Internal: the superellipsoid against FCL's shapes with flat faces, edges or rims (fcl::Box,
// Capsule, Cylinder, Cone, Convex, TriangleP) through libccd, with the shape's exact support
// function (gjk_support.h): GJK's distance where they are apart, MPR's depth and normal where
// they overlap, in the iteration limits and tolerances of a default GJKSolver_libccd. Its
// accuracy is libccd's (docs/fcl-notes.md → "libccd with the exact support"). The pairs with
// flat features start from it: its witness picks the features to try (candidates.h), its normal
// is one of the overlap's candidate directions (depth_candidates.h).

#include <optional>

#include "fcl_glue/pairs/pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// libccd's hit for the pair if the other geometry is one of the shapes above (the exact
/// pairs use it where they hand over); std::nullopt otherwise.
template <typename S>
std::optional<PairHit<S>> libccdHit(const Pair<S>& pair);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_PAIRS_LIBCCD_PAIR_H
