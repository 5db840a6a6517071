#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_LIBCCD_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_LIBCCD_PAIR_H

// Internal: the superellipsoid against FCL's shapes with flat faces, edges or rims (fcl::Box,
// Capsule, Cylinder, Cone, Convex, TriangleP) through libccd's MPR, with the shape's exact
// support function (gjk_support.h): depth and normal where they overlap, in the iteration limits
// and tolerances of a default GJKSolver_libccd; its accuracy is libccd's (docs/fcl-notes.md →
// "libccd with the exact support"). The pairs with flat features start from it where their own
// GJK (gjk.h) finds no separation: its normal is one of the overlap's candidate directions
// (depth_candidates.h). Not libccd's GJK distance: FCL 0.7's, as Debian builds it (assertions
// on), aborts the process on some inputs (docs/hardening.md → "Findings", 14).

#include <optional>

#include "narrowphase/shape_pair.h"

namespace fcl_superellipsoid {
namespace detail {

/// libccd's overlap of the superellipsoid and `other`, one of the shapes above: MPR's depth (a
/// negative distance), normal and witnesses; where MPR finds no overlap, distance 0 at the
/// shape's support point on the line of the centres (touching, or apart by more than MPR sees).
/// Instantiated for float and double and the six shapes above.
template <typename S, typename Other>
std::optional<PairHit<S>> libccdHit(const ShapePair<S>& pair, const Other& other);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_LIBCCD_PAIR_H
