#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_POLYTOPE_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_POLYTOPE_PAIR_H

// Internal: the superellipsoid against a polytope (fcl::Box, fcl::Convex, fcl::TriangleP),
// exactly when they are separated (docs/math.md → "Shape pairs"). The distance to a polytope is
// reached on one of its features: a face (the superellipsoid's support point against the face's
// normal, if it projects inside the face), an edge (segment_search.h) or a vertex (the point
// solver). A start (our GJK, gjk.h) picks the candidates: the features spanned by the vertices
// that are within a margin of the polytope's support along its normal. Each candidate is a pair
// of real surface points, so its distance is an upper bound; the support functions along its
// normal give a lower bound; the first candidate whose bounds meet (the duality gap below
// 1e-12 × size) is the answer. Overlapping, or with no candidate certified, the least F over
// candidate directions (depth_candidates.h); feature_pair.h chains the two.

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/triangle_p.h>

#include <optional>

#include "narrowphase/shape_pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// The superellipsoid against a box, a convex polytope, a triangle (std::nullopt only where no
/// start can be found: libccd failed).
template <typename S>
std::optional<PairHit<S>> boxHit(const ShapePair<S>& pair, const fcl::Box<S>& box);
template <typename S>
std::optional<PairHit<S>> convexHit(const ShapePair<S>& pair, const fcl::Convex<S>& convex);
template <typename S>
std::optional<PairHit<S>> triangleHit(const ShapePair<S>& pair, const fcl::TriangleP<S>& triangle);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_POLYTOPE_PAIR_H
