#ifndef FCL_SUPERELLIPSOID_SRC_SOLVERS_EXACT_RULES_H
#define FCL_SUPERELLIPSOID_SRC_SOLVERS_EXACT_RULES_H

// Internal: the rules of the Exact method that its two implementations share, the scalar
// solver (solvers/exact_solver.cpp) and the SIMD kernel (batch/batch_kernel.cpp). Both read
// these constants and helpers; neither keeps a copy. A change here changes both, and the batch
// tests (test/batch/) check that their answers still agree. The reasoning behind each number
// is in docs/math.md → "The Exact solver".

#include <cmath>
#include <limits>

#include "common/tangent_basis.h"
#include "shape/symmetric2.h"

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

/// Outside, where the primal formulation goes first (exponents ≤ 1 or nearly), a radial start
/// whose paper Eq. 7 error exceeds this × size (far from a box-like shape, where the radial
/// projection lands near a corner) competes with the support point of Q's direction; the one
/// of smaller error goes first. (The dual-first shapes' radial start fares better there, and
/// this start's two evaluations would cost more than its iterations save.)
constexpr double kSupportStartError = 1;

/// Each start may use at most this many iterations of the query's shared budget
/// (DistanceOptions::max_iterations), so one start creeping along a saddle cannot starve the
/// start that leads to the answer.
constexpr int kIterationsPerStart = 60;

/// Inside, a Newton run whose error has not fallen below kStallFactor × its value kStallWindow
/// iterations earlier counts as stalled and stops: creeping along a flat valley (a focal ring, a
/// near-sphere's centre) cuts the error by far less, converging Newton by far more.
constexpr int kStallWindow = 10;
constexpr double kStallFactor = 0.5;

/// Inside, a start rotated onto Q's meridian about an axis (the scalar solver's ring starts,
/// ExactSolver::tryRingRotations) converges in one to three iterations where the nearest points
/// form a ring; it gets this many, so it cannot starve the other starts where they do not.
constexpr int kRingStartIterations = 8;

/// A Newton step that does not reduce the error is halved: the full step and this many − 1
/// halvings are tried (step, step/2, …, step/16) before the formulation counts as stalled.
/// Second-order correction (scalar solver): before a refused full Newton step is halved, one
/// more Newton step is taken from the point it reached, and the pair is accepted (counted as one
/// more iteration) if that reduces the error. A straight step along a valley that is flat one way
/// and curved the other lands at the right place along it but off its floor; the next step puts
/// it back, where halving would creep (docs/hardening.md, finding 13). Where the tangent block
/// is positive definite but flat one way (its eigenvalues' ratio below kValleyRatio) and that
/// correction fails too, the valley itself is curved: a straight step along a ring of nearly
/// nearest points leaves the ring by the step's square over its radius, which its own next step
/// repeats. Then each trial (the full step and its halvings) is followed by restoring steps,
/// Newton's steps along the tangent block's stiffer eigenvector only, back to the floor without
/// moving along it (finding 25), up to kRestoringSteps while they reduce the error. The SIMD kernel
/// does neither: the queries it does not converge go to the scalar solver.
constexpr int kStepTrials = 5;
constexpr int kRestoringSteps = 4;
constexpr double kValleyRatio = 1e-2;

/// An iterate component that would turn negative (leave the first octant) shrinks to this
/// fraction of its previous value instead.
constexpr double kOctantShrink = 0.1;

/// Convexification of the Newton matrix in the tangent plane: each tangent eigenvalue below
/// kConvexifyBelow × scale (inside, beyond a focal point) is replaced by kConvexifyTo × scale,
/// along its own eigenvector; the other eigenvalue keeps its value. Where the smallest one is
/// still positive (just before a focal point: Q near the centre of a near-sphere), the
/// unmodified step is tried first, and the convexified one only if no halving of it reduces the
/// error.
constexpr double kConvexifyBelow = 1e-4;
constexpr double kConvexifyTo = 0.1;

/// The tangent block [m11, m12; m12, m22] after convexification, in the tangent basis it was
/// given in.
template <typename S>
struct TangentBlock {
  S m11, m12, m22;
  bool modified;         // an eigenvalue was replaced
  bool full_step_first;  // ... and the smallest was positive: try the unmodified step first
};

/// Convexifies the symmetric tangent block [b11, b12; b12, b22] (the rule above). The block is
/// rebuilt from its eigenvectors, not shifted, so a replaced eigenvalue is exact even where the
/// other is huge (near a crease). The scalar solver calls this; the SIMD kernel
/// (batch_kernel.cpp, tangentSteps) computes the same formulas lane by lane, with the same
/// first check (taken where every lane passes it).
template <typename S>
TangentBlock<S> convexifiedTangentBlock(S b11, S b12, S b22, S scale) {
  const S below = S(kConvexifyBelow) * scale, wanted = S(kConvexifyTo) * scale;
  // Both eigenvalues ≥ below exactly when B − below·I is positive semidefinite: decided from
  // its diagonal and determinant first, which is all most Newton steps need (the eigenvalues
  // cost a square root and a division).
  const S d11 = b11 - below, d22 = b22 - below;
  if (d11 > S(0) && d22 > S(0) && d11 * d22 > b12 * b12 && std::isfinite(d11 * d22)) {
    return {b11, b12, b22, false, false};
  }
  const auto [lowest, highest, half_gap] = eigenvalues2(b11, b12, b22);  // no cancellation
  if (!(lowest < below) || !std::isfinite(lowest)) return {b11, b12, b22, false, false};
  // Where half_gap = 0 the block is a multiple of I and both eigenvalues are replaced below, so
  // any unit vector serves as (c, s).
  const auto [c, s] = lowerEigenvector(b11, b12, b22, half_gap);
  const S high = highest < below ? wanted : highest;
  // M = wanted·(c, s)(c, s)ᵀ + high·(−s, c)(−s, c)ᵀ.
  return {wanted * c * c + high * s * s, (wanted - high) * c * s, wanted * s * s + high * c * c,
          true, lowest > S(0)};
}

/// The tangent basis's helper switch (common/tangent_basis.h), for the SIMD lanes' copy of it.
using detail::kTangentHelperSwitch;

/// Inside, a query with G(Q) below this is "deep": the centre's candidates may be nearer.
constexpr double kDeepGauge = 0.5;

/// Inside, a query with G(Q) below this ("deeper") takes the direction cover's start: it is
/// compared with the radial one and the nearer goes first. Above it, near the surface, the
/// radial start goes first and the cover's is not tried (the axis projections find the other
/// basins as often). The cover's certificate is tried at every depth where the Hessian ball's
/// fails.
constexpr double kCoverGauge = 0.9;

/// The direction cover's certificate gives up on a cap wider than this chord (about 44°): the
/// Hessian bound over a box of half-width 2·d·θ about the answer then rarely holds, and the
/// search for the cap's cells would cost more than the starts it could save.
constexpr double kCoverCapLimit = 0.75;

/// The direction cover's certificate is tried on at most this many answers of one query (the
/// first converged answer and the first better one): where it fails on both, the answer is
/// near a crease or a tie of competing minima, and each further try costs about a Newton start.
constexpr int kCoverAttempts = 2;

/// Outside, where the contact direction's duality gap leaves an answer uncertified, the dual
/// problem's lower bound is raised by at most this many steps of projected gradient ascent
/// (ExactSolver::dualLowerBound), each halved at most kDualAscentHalvings − 1 times until it
/// raises the bound. A step that settles a component too small for the format (finding 21)
/// takes one or two; the cap bounds the cost where none helps.
constexpr int kDualAscentSteps = 8;
constexpr int kDualAscentHalvings = 40;

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
