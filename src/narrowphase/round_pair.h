#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_ROUND_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_ROUND_PAIR_H

// Internal: the superellipsoid against fcl::Cylinder and fcl::Cone, exactly when they are
// separated (docs/math.md → "Shape pairs"). Their features: the flat ends (the superellipsoid's
// support point against the disc's normal, if it lands on the disc), the side (a one-parameter
// family of normals: a search over its angle), the rims (a search along the circle with the
// point solver) and the cone's apex (the point solver). The candidates are the features within
// a margin of the start's witness (our GJK, gjk.h); as for polytopes (polytope_pair.h) each is
// certified by its duality gap, and overlapping shapes, or no certified candidate, get the least
// F over candidate directions (depth_candidates.h).

#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>

#include <optional>

#include "narrowphase/shape_pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// The superellipsoid against a cylinder, a cone (std::nullopt only where no start can be
/// found: libccd failed).
template <typename S>
std::optional<PairHit<S>> cylinderHit(const ShapePair<S>& pair, const fcl::Cylinder<S>& cylinder);
template <typename S>
std::optional<PairHit<S>> coneHit(const ShapePair<S>& pair, const fcl::Cone<S>& cone);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_ROUND_PAIR_H
