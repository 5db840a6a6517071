#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_CONTACT_MANIFOLD_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_CONTACT_MANIFOLD_H

// Internal: the contact manifold of a pair that the dispatcher has recognised, for the public
// call (contact_manifold.cpp) and for FCL's collide with several contacts (pairs.cpp).

#include "fcl_glue/pair_kinds.h"

namespace fcl_superellipsoid {
namespace detail {

/// The manifold of `pair` (its row `kind`, which has a region, and its hit), with options
/// checked; a patch tolerance < 0 is 1e-3 × the shape's size. `warm` may be null.
template <typename S>
ContactManifold<S> pairManifold(const Pair<S>& pair, const PairKind<S>& kind, const PairHit<S>& hit,
                                const ManifoldOptions<S>& options,
                                ManifoldWarmStart<S>* warm = nullptr);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_CONTACT_MANIFOLD_H
