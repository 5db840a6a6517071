#ifndef FCL_SUPERELLIPSOID_GJK_SUPPORT_H
#define FCL_SUPERELLIPSOID_GJK_SUPPORT_H

/// @file
/// The superellipsoid in FCL's libccd algorithms (GJK, EPA, MPR): a specialisation of
/// fcl::detail::GJKInitializer whose support function is the shape's exact support point
/// (Superellipsoid::supportPoint), not a tessellation. With this header included, any FCL code
/// that runs libccd on a Superellipsoid sees the exact shape, for example
///
///     fcl::detail::GJKSolver_libccd<double> solver;
///     solver.shapeSignedDistance(superellipsoid, X_W1, box, X_W2, &d, &p1, &p2);
///
/// libccd's accuracy is libccd's own (docs/fcl-notes.md → "libccd with the exact support"):
/// the library's own pair solvers (fcl_integration.h) answer the pairs it knows better.
/// The centre libccd's MPR starts from is the shape's centre.

#include <fcl/narrowphase/detail/convexity_based_algorithm/gjk_libccd.h>

#include "fcl_superellipsoid/export.h"
#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl {
namespace detail {

template <typename S>
class FSE_EXPORT GJKInitializer<S, fcl_superellipsoid::Superellipsoid<S>> {
 public:
  static GJKSupportFunction getSupportFunction();
  static GJKCenterFunction getCenterFunction();
  /// The shape must outlive the object; the pose is copied.
  static void* createGJKObject(const fcl_superellipsoid::Superellipsoid<S>& s,
                               const Transform3<S>& tf);
  static void deleteGJKObject(void* o);
};

extern template class GJKInitializer<float, fcl_superellipsoid::Superellipsoid<float>>;
extern template class GJKInitializer<double, fcl_superellipsoid::Superellipsoid<double>>;

}  // namespace detail
}  // namespace fcl

#endif  // FCL_SUPERELLIPSOID_GJK_SUPPORT_H
