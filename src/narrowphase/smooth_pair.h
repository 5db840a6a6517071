#ifndef FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SMOOTH_PAIR_H
#define FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SMOOTH_PAIR_H

// Internal: the superellipsoid against another smooth convex shape (fcl_superellipsoid::
// Superellipsoid, fcl::Ellipsoid), exactly: Newton's method on the sphere of directions for the
// support function of the Minkowski difference (docs/math.md → "Shape pairs").
//
//   F(v) = h_A(v) + h_B(−v),  |v| = 1;   signed distance = −min F,
//
// the minimiser v* is the unit normal of A at its witness a = ∇h_A(v*), pointing to B's witness
// b = ∇h_B(−v*). Separated shapes: F < 0 somewhere, every local minimum there is the global one,
// and each v gives the bounds −F(v) ≤ distance ≤ |a − b| (the gap between them certifies the
// answer). Overlapping shapes: min F is the penetration depth (the shortest translation that
// separates them); F may have several local minima, so Newton runs from the best few of a set of
// start directions.

#include <optional>

#include "narrowphase/shape_pair.h"
#include "narrowphase/support_map.h"

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
struct SmoothPairAnswer {
  S distance;         // signed: −(penetration depth) when overlapping
  Vector3<S> on_a;    // A's witness ∇h_A(v*)
  Vector3<S> on_b;    // B's witness ∇h_B(−v*)
  Vector3<S> normal;  // v*: A's outward unit normal at on_a, towards B
};

/// The superellipsoid against another superellipsoid, an ellipsoid.
template <typename S>
std::optional<PairHit<S>> superellipsoidHit(const ShapePair<S>& pair,
                                            const Superellipsoid<S>& other);
template <typename S>
std::optional<PairHit<S>> ellipsoidHit(const ShapePair<S>& pair, const fcl::Ellipsoid<S>& other);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_NARROWPHASE_SMOOTH_PAIR_H
