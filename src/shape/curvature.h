#ifndef FCL_SUPERELLIPSOID_SRC_SHAPE_CURVATURE_H
#define FCL_SUPERELLIPSOID_SRC_SHAPE_CURVATURE_H

// Internal: the smallest radius of curvature of a superellipsoid's surface, the radius of the
// largest ball that rolls freely inside it (docs/math.md → "The rolling-ball certificate").
//
// At the surface point of unit normal u the principal radii of curvature are the eigenvalues of
// the support function's Hessian ∇²h(u) on the tangent plane of u (h is 1-homogeneous, so
// ∇²h(u)·u = 0). The smallest over the sphere of directions is found on a grid over the first
// octant's directions (the shape is symmetric), refined by a pattern search around the lowest
// samples, and lowered by a safety factor that covers what the search could have missed.
//
// Positive exactly where both exponents are ≤ 1 and the radii's aspect ratio is at most 1000.
// Where an exponent is > 1 the surface has a crease of unbounded curvature (docs/math.md → "The
// gauge") and the radius is 0; beyond that aspect the search is not trusted and the bound is 0.

#include <Eigen/Core>

namespace fcl_superellipsoid {
namespace detail {

/// A lower bound on the smallest principal radius of curvature of the superellipsoid with these
/// radii and exponents (exponents in (0, 2)); 0 where an exponent exceeds 1 or the aspect ratio
/// 1000. Evaluated in
/// double; it costs thousands of evaluations, so the shape computes it once, on first use.
double minRadiusOfCurvature(const Eigen::Vector3d& radii, double eps1, double eps2);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SHAPE_CURVATURE_H
