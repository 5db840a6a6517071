#ifndef FCL_SUPERELLIPSOID_POINT_DISTANCE_H
#define FCL_SUPERELLIPSOID_POINT_DISTANCE_H

/// @file
/// Distance from a point to a superellipsoid's surface: signed distance, nearest surface
/// point and outward normal, by one of three methods.
///
/// Frames (Drake/FCL notation): S is the shape's frame, W the world; p_SQ is the query point
/// Q measured in S, X_WS the pose of S in W.
///
/// Sign convention: distance > 0 outside, < 0 inside, 0 on the surface. For every method the
/// returned nearest_point N is on the surface (G(N) = 1 to rounding) and
///   Q = N + distance·normal   holds up to the reported error (paper Eq. 7).
///
/// Tie-break where the nearest point is not unique (a point on the medial axis, e.g. the
/// centre of a sphere): the distance is still exact; the returned point is one of the nearest
/// points, the one in the query's own octant (coordinates of the query that are exactly 0
/// count as positive). At the exact centre, where the radial direction is undefined, every
/// method answers with the Exact solver's centre search: the nearest of the axis tips and of
/// the stationary points reached from the diagonal directions, ties going to the first in
/// the order +x, +y, +z tip, then (1,1,1), (1,1,0), (1,0,1), (0,1,1). A sphere's centre
/// returns (a, 0, 0), distance −a; an octahedron-like shape (ε > 1) returns a face point.

#include <fcl/math/geometry.h>

#include <stdexcept>
#include <string>

#include "fcl_superellipsoid/distance_options.h"
#include "fcl_superellipsoid/export.h"
#include "fcl_superellipsoid/superellipsoid.h"

namespace fcl_superellipsoid {

namespace detail {
/// Keeps a parameter out of template deduction, so Eigen expressions (Vector3d::Zero(), a + b)
/// can be passed where a Vector3<S> is expected; S is deduced from the shape alone.
template <typename T>
struct TypeIdentity {
  using type = T;
};
template <typename T>
using NonDeduced = typename TypeIdentity<T>::type;
}  // namespace detail

template <typename S>
struct PointDistanceResult {
  S distance{};              ///< signed: > 0 outside, < 0 inside
  Vector3<S> nearest_point;  ///< on the surface, in the query's frame
  Vector3<S> normal;         ///< unit outward surface normal at nearest_point
  int iterations = 0;        ///< iterations used (0 for Radial)
  bool converged = false;    ///< error ≤ tolerance × size (or the rounding floor, see below)
  S error{};                 ///< final error estimate, ‖N + d·n(N) − Q‖, length units
};

/// Distance from p_SQ (in the shape's frame S) to the surface.
///
/// The rounding floor: for a far point the error estimate cannot drop below a few ulps of
/// ‖p_SQ‖; a query whose estimate reaches 8·ε_machine·(‖p_SQ‖ + size) counts as converged.
///
/// @throws std::invalid_argument if p_SQ is not finite, the tolerance is not finite and > 0,
///         or max_iterations < 1; the message names the value. Never returns NaN.
template <typename S>
FSE_EXPORT PointDistanceResult<S> pointDistance(
    const Superellipsoid<S>& shape, const detail::NonDeduced<Vector3<S>>& p_SQ,
    const detail::NonDeduced<DistanceOptions<S>>& options = {});

/// The same for a world point p_WQ and the shape's pose X_WS; nearest_point and normal are
/// returned in the world frame W.
template <typename S>
FSE_EXPORT PointDistanceResult<S> pointDistance(
    const Superellipsoid<S>& shape, const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
    const detail::NonDeduced<Vector3<S>>& p_WQ,
    const detail::NonDeduced<DistanceOptions<S>>& options = {});

extern template FSE_EXPORT PointDistanceResult<float> pointDistance(const Superellipsoid<float>&,
                                                                    const Vector3<float>&,
                                                                    const DistanceOptions<float>&);
extern template FSE_EXPORT PointDistanceResult<double> pointDistance(
    const Superellipsoid<double>&, const Vector3<double>&, const DistanceOptions<double>&);
extern template FSE_EXPORT PointDistanceResult<float> pointDistance(const Superellipsoid<float>&,
                                                                    const fcl::Transform3<float>&,
                                                                    const Vector3<float>&,
                                                                    const DistanceOptions<float>&);
extern template FSE_EXPORT PointDistanceResult<double> pointDistance(
    const Superellipsoid<double>&, const fcl::Transform3<double>&, const Vector3<double>&,
    const DistanceOptions<double>&);

}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_POINT_DISTANCE_H
