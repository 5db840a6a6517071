#ifndef FCL_SUPERELLIPSOID_SRC_SHAPE_SHAPE_CACHES_H
#define FCL_SUPERELLIPSOID_SRC_SHAPE_SHAPE_CACHES_H

// Internal: what the solvers compute once per shape and then keep, behind the one opaque
// handle a Superellipsoid holds (superellipsoid.h). Copies of a shape share it: it depends only
// on the radii and exponents, which a shape never changes. Thread-safe: threads that race on a
// first use each compute the value and the first stored is the one kept, so a reference handed
// out stays valid as long as the shape.

#include <atomic>
#include <limits>
#include <memory>

#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
class DirectionCover;  // solvers/direction_cover.h

template <typename S>
class ShapeCaches {
 public:
  /// The caches of `shape`.
  static const ShapeCaches& of(const Superellipsoid<S>& shape) { return *shape.caches_; }

  /// The smallest radius of curvature (Superellipsoid::minRadiusOfCurvature), computed by
  /// `compute()` on first use.
  template <typename Compute>
  S minRadiusOfCurvature(const Compute& compute) const {
    S v = min_radius_of_curvature_.load(std::memory_order_relaxed);
    if (v != v) {  // NaN: not computed yet
      v = compute();
      min_radius_of_curvature_.store(v, std::memory_order_relaxed);
    }
    return v;
  }

  /// The smallest radius of curvature if computed already; NaN if not.
  S knownMinRadiusOfCurvature() const {
    return min_radius_of_curvature_.load(std::memory_order_relaxed);
  }

  /// The direction cover (solvers/direction_cover.h), built by `build()` (a
  /// std::shared_ptr<const DirectionCover<S>>) on first use.
  template <typename Build>
  const DirectionCover<S>& directionCover(const Build& build) const {
    std::shared_ptr<const DirectionCover<S>> cover = std::atomic_load(&direction_cover_);
    if (!cover) {
      std::shared_ptr<const DirectionCover<S>> built = build();
      // Keeps the first one stored; `cover` receives it if another thread won.
      if (std::atomic_compare_exchange_strong(&direction_cover_, &cover, built)) cover = built;
    }
    return *cover;
  }

 private:
  mutable std::atomic<S> min_radius_of_curvature_{std::numeric_limits<S>::quiet_NaN()};
  mutable std::shared_ptr<const DirectionCover<S>> direction_cover_;
};

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SHAPE_SHAPE_CACHES_H
