#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_CAPSULE_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_CAPSULE_PAIR_H

// Internal: the superellipsoid against fcl::Capsule, exactly while the capsule's axis stays
// outside the shape: the capsule is its axis segment grown by its radius, so the signed
// distance is the segment's least signed distance (segment_search.h) minus the radius. That
// covers separation and every penetration shallower than the radius (the axis still outside),
// the contacts of a simulation. Deeper, the shortest separating translation of a segment is not
// its deepest point's: those go through libccd (libccd_pair.h).

#include <fcl/geometry/shape/capsule.h>

#include <optional>

#include "narrowphase/shape_pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// The superellipsoid against a capsule.
template <typename S>
std::optional<PairHit<S>> capsuleHit(const ShapePair<S>& pair, const fcl::Capsule<S>& capsule);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_CAPSULE_PAIR_H
