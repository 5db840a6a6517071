#ifndef FCL_SUPERELLIPSOID_SRC_BATCH_BATCH_KERNEL_H
#define FCL_SUPERELLIPSOID_SRC_BATCH_BATCH_KERNEL_H

// Internal: the Exact solver's Newton iteration on SIMD lanes, one vertex per lane, for the
// batched queries (batch_distance.cpp). The body is batch/batch_kernel.cpp, compiled once per
// instruction set with Highway and chosen at run time for the CPU that runs it.
//
// The kernel does what the scalar solver (solvers/exact_solver.cpp) does on its common path, with
// the same formulas, and hands every other case back to it:
//  - outside pass: Newton in the shape's smooth formulation (primal where ε ≤ 1, dual where
//    ε ≥ 1: primalIsSmoother in solvers.h) and, where it stalls, in the other (ExactSolver::
//    refine), from the caller's warm start, if any, else from the radial projection. Outside the
//    problem is convex, so a start that converges gives the scalar solver's answer to the
//    tolerance. Lanes found inside are marked kLaneInside (the caller sorts lanes by a
//    classifying pass first, so that these are rare).
//  - inside pass: Newton from the radial projection and the three axis projections (the
//    scalar solver's first four starts), the latter only on lanes whose answer is not yet
//    certified global (the rolling ball, exact_rules::certifiedGlobal, on the lanes; else the
//    Hessian ball and then the direction cover, solvers/ball_certificate.h, lane by lane, the
//    cover on at most exact_rules::kCoverAttempts answers per lane); the nearest converged
//    answer wins, and the nearest other one is the runner-up (LaneArrays::runner_up).
// A lane goes back to the scalar solver (kLaneScalar) whenever the scalar solver would do
// more than that: a start that converges in neither formulation (the scalar solver then tries
// further starts and, outside, the bracketed projection), an inside query near a coordinate plane
// (tilted starts), deep inside (the centre's candidates, and the cross-section diagonals of
// elongated shapes), the exact centre, or an iteration count over the caller's cap (inside: at it).
//
// Powers are exp(p·log x) with Highway's vectorised exp/log (≤ 4 ulp). Every power the solver
// takes is of a ratio t ∈ [0, 1] inside a p-norm m·(1 + t^p)^(1/p): an error δ in t^p moves the
// norm by (1/p)·t^p/(1 + t^p)·δ ≤ δ/p, and the rounding of p·log t grows δ only by |log t^p|,
// whose product with t^p stays below 1/e. So the nested norms come out within a few ulps. The
// second level's ratio is taken from logarithms (EvaluateLevels in the .cpp: a shorter chain of
// exp/log for a latency-bound loop), which adds a few ulps of |log| of the coordinates.

#include <cstddef>
#include <cstdint>

#include "shape/nested_norm.h"

namespace fcl_superellipsoid {
namespace detail {

/// The widest vector the kernel uses, in lanes (AVX-512 with float). Lane arrays need room for
/// n rounded up to a multiple of this; the caller fills the padding with copies of a real lane.
constexpr std::size_t kMaxLanes = 16;

/// The widest vector of T the kernel uses, in lanes (kMaxLanes for float, half that for double).
template <typename T>
constexpr std::size_t kVectorLanes = kMaxLanes * sizeof(float) / sizeof(T);

/// What the kernel needs of the shape and the options.
template <typename S>
struct LaneProblem {
  NestedNorm<S> primal, dual;  // G and the support function h (nested_norm.h)
  Vector3<S> radii;
  bool primal_first;  // the smooth formulation for these exponents
  S tolerance;  // options.tolerance × size, length units (the rounding floor is added per lane)
  S size;       // the largest radius
  int max_iterations;  // the caller's cap on all starts together
  S rolling_radius;    // Superellipsoid::minRadiusOfCurvature(): the inside certificate's radius
  // The shape, for its direction cover (the inside certificate where the balls fail; built on
  // first use, Superellipsoid::directionCover).
  const Superellipsoid<S>* shape;
};

enum LaneStatus : std::int32_t {
  kLaneSolved = 0,  // point, normal and error hold the answer
  kLaneInside = 1,  // outside pass: the vertex is inside; give it to the inside pass
  kLaneScalar = 2,  // the scalar solver must answer this vertex
};

/// Structure-of-arrays lanes, first octant of the shape's frame.
template <typename S>
struct LaneArrays {
  const S* query[3];  // in: |Q| per coordinate
  const S* hint[3];   // in (outside pass): |warm start| per coordinate, NaN = none; or nullptr
  S* point[3];        // out: the nearest surface point
  S* normal[3];       // out: the unit outward normal there
  S* error;           // out: paper Eq. 7 error of the answer
  std::int32_t* status;
  /// The gauge's evaluation at Q, written by the classifying pass, from which the others build
  /// their radial start (the query's own ray onto the surface): G(Q), ∇G (3), ∇²G (xx, xy, xz,
  /// yy, yz, zz).
  static constexpr int kRadialArrays = 10;
  S* radial[kRadialArrays];
  /// out (inside pass), if set: the distance from Q of the nearest other converged answer among
  /// the lane's starts (farther than √(tolerance·size) from the kept one), ∞ for none: the
  /// scalar solver's runner-up (solvers.h, Query::runner_up) over the starts the lanes try.
  S* runner_up = nullptr;
};

/// The kernel's passes. kClassify sets each lane's status, kLaneInside where G(Q) < 1 (the
/// outside pass's own test) and kLaneSolved elsewhere, so that the caller can give each pass
/// whole vectors of its own lanes (a vector's Newton runs as long as its slowest lane); it also
/// keeps the gauge's evaluation at Q, from which both passes build their first start
/// (LaneArrays::radial).
enum class LanePass { kClassify, kOutside, kInside };

/// Runs the pass on lanes [0, n) with the best instruction set of this CPU (Highway dynamic
/// dispatch). The outside and inside passes read what the classifying pass wrote for their
/// lanes; lanes of the inside pass must be inside the shape (kLaneInside).
void solveLanes(const LaneProblem<float>& problem, const LaneArrays<float>& lanes, std::size_t n,
                LanePass pass);
void solveLanes(const LaneProblem<double>& problem, const LaneArrays<double>& lanes, std::size_t n,
                LanePass pass);

/// The nested norm `primal` at n first-octant points query[0..2][i], lane by lane, into
/// gauge[i], with the kernel's powers (within a few ulps of NestedNorm::value). n must be a
/// multiple of kVectorLanes<T>. The BVH traversal (fcl_glue/vertex_traversal.cpp) classifies a
/// subtree's vertices with the gauge G, and bounds its BVs with the support function h.
void gaugeLanes(const NestedNorm<float>& primal, const float* const query[3], float* gauge,
                std::size_t n);
void gaugeLanes(const NestedNorm<double>& primal, const double* const query[3], double* gauge,
                std::size_t n);

/// The gradient of the distance with respect to the shape's parameters (a1, a2, a3, ε1, ε2) at n
/// first-octant surface points point[0..2][i] with their unit outward normals normal[0..2][i],
/// lane by lane, into d_shape[0..4][i]: solvers/point_gradient.h's shapeGradient with the
/// kernel's logarithms (within a few ulps). n must be a multiple of kVectorLanes<T>. The batched
/// derivatives (batchDistanceDerivatives) take their parameter columns from it.
void shapeGradientLanes(const NestedNorm<float>& primal, const float* const point[3],
                        const float* const normal[3], float* const d_shape[5], std::size_t n);
void shapeGradientLanes(const NestedNorm<double>& primal, const double* const point[3],
                        const double* const normal[3], double* const d_shape[5], std::size_t n);

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_BATCH_BATCH_KERNEL_H
