#ifndef FCL_SUPERELLIPSOID_SRC_SOLVERS_EXACT_RULES_H
#define FCL_SUPERELLIPSOID_SRC_SOLVERS_EXACT_RULES_H

// Internal: the rules of the Exact method that its two implementations share, the scalar
// solver (solvers/exact_solver.cpp) and the SIMD kernel (batch/batch_kernel.cpp). Both read
// these constants and helpers; neither keeps a copy. A change here changes both, and the batch
// tests (test/batch/) check that their answers still agree. The reasoning behind each number
// is in docs/math.md → "The Exact solver".

#include <cmath>
#include <limits>

namespace fcl_superellipsoid {
namespace detail {
namespace exact_rules {

/// The rounding floor of the error estimate, in ulps of ‖Q‖ + size: below a few ulps of the
/// query's magnitude no method can resolve paper Eq. 7's ‖N + d·n − Q‖, so a query whose
/// estimate reaches it counts as converged (every method, not only Exact: point_distance.cpp).
constexpr double kRoundingFloorUlps = 8;

/// The absolute tolerance of one query, in length units: the caller's relative tolerance
/// times the shape's size (its largest radius), plus the rounding floor.
template <typename S>
S absoluteTolerance(S relative_tolerance, S size, S query_norm) {
  return relative_tolerance * size +
         S(kRoundingFloorUlps) * std::numeric_limits<S>::epsilon() * (query_norm + size);
}

/// Each start may use at most this many iterations of the query's shared budget
/// (DistanceOptions::max_iterations), so one start creeping along a saddle cannot starve the
/// start that leads to the answer.
constexpr int kIterationsPerStart = 60;

/// A Newton step that does not reduce the error is halved: the full step and this many − 1
/// halvings are tried (step, step/2, …, step/16) before the formulation counts as stalled.
constexpr int kStepTrials = 5;

/// An iterate component that would turn negative (leave the first octant) shrinks to this
/// fraction of its previous value instead.
constexpr double kOctantShrink = 0.1;

/// Convexification of the Newton matrix in the tangent plane: where its smallest tangent
/// eigenvalue is below kConvexifyBelow × scale (inside, beyond a focal point), it is shifted
/// up to kConvexifyTo × scale. Where that eigenvalue is still positive (just before a focal
/// point: Q near the centre of a near-sphere), the unshifted step is tried first, and the
/// shifted one only if no halving of it reduces the error.
constexpr double kConvexifyBelow = 1e-4;
constexpr double kConvexifyTo = 0.1;

/// The tangent basis t1 = n × helper takes helper = x̂ where |n_x| < this, else ŷ.
constexpr double kTangentHelperSwitch = 0.6;

/// Inside, a query with G(Q) below this is "deep": the centre's candidates may be nearer.
constexpr double kDeepGauge = 0.5;

/// Inside, when the answer is farther than this fraction of a cross-section's smaller radius,
/// the solver also starts along that cross-section's diagonal.
constexpr double kDiagonalStartDepth = 0.25;

/// Inside, a query within nearPlaneFraction × radius of a coordinate plane gets starts tilted
/// off that plane (Newton never leaves a mirror plane by itself).
template <typename S>
S nearPlaneFraction() {
  return std::sqrt(std::numeric_limits<S>::epsilon());
}

/// The rolling-ball certificate (docs/math.md → "The rolling-ball certificate"). A converged
/// inside answer N at distance d from Q is the global nearest point if the ball of radius d
/// around Q lies inside the shape, which holds when d is at most the radius of the ball that
/// rolls freely inside it (Superellipsoid::minRadiusOfCurvature(), 0 where it has creases). The
/// answer is exact to the tolerance, so the test leaves that much room.
template <typename S>
bool certifiedGlobal(S distance, S tolerance, S rolling_radius) {
  return distance + tolerance <= rolling_radius;
}

}  // namespace exact_rules
}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SOLVERS_EXACT_RULES_H
