#ifndef FCL_SUPERELLIPSOID_SRC_SOLVERS_SOLVERS_H
#define FCL_SUPERELLIPSOID_SRC_SOLVERS_SOLVERS_H

// Internal: the three point-distance methods behind pointDistance(). Each takes a validated
// query in the shape's frame and an absolute tolerance (already scaled by the shape's size and
// floored at the rounding level of the query).

#include <algorithm>
#include <cmath>
#include <limits>

#include "fcl_superellipsoid/point_distance.h"
#include "shape/octant.h"

namespace fcl_superellipsoid {
namespace detail {

template <typename S>
struct Query {
  const Superellipsoid<S>& shape;
  Vector3<S> x;  // the query point, shape frame
  S tolerance;   // absolute, length units
  int max_iterations;
  // Exact method only: a point near the expected answer (shape frame), e.g. the previous
  // simulation step's nearest point; nullptr for none. Used as the first start outside, where
  // the problem is convex and any converged start gives the one answer; ignored inside.
  const Vector3<S>* hint = nullptr;
  // Exact method only, if set: receives the distance from Q of the nearest converged answer
  // that is not the returned one (farther from it than √(tolerance·size)), ∞ if none. A value
  // within the tolerance of the distance says Q has several nearest points (a tie: the
  // derivatives' flag, solvers/point_derivatives.cpp). Not set for far and near-centre
  // queries, which are answered without the search.
  S* runner_up = nullptr;
};

/// True for a query point so far from the shape (beyond 2^digits × size along an axis) that the
/// support point in its direction is the nearest point to rounding; every method answers it with
/// solveFar. Squaring its coordinates could overflow, which solveFar never does.
template <typename S>
bool isFarQuery(const Superellipsoid<S>& shape, const Vector3<S>& p_SQ) {
  // 2/ε = 2^digits exactly: a multiplication, not a libm call, on the batched queries' hot path.
  return p_SQ.cwiseAbs().maxCoeff() > shape.size() * (S(2) / std::numeric_limits<S>::epsilon());
}

/// True for a query point within 2^−digits × size of the centre along every axis (but not the
/// centre itself): its direction is below the rounding of the shape's coordinates, and every
/// method answers it with the centre's nearest point, reflected into its octant.
template <typename S>
bool isNearCentreQuery(const Superellipsoid<S>& shape, const Vector3<S>& p_SQ) {
  const S largest = p_SQ.cwiseAbs().maxCoeff();
  return largest > S(0) && largest < shape.size() * (std::numeric_limits<S>::epsilon() / S(2));
}

/// The answer for a far query (docs/math.md → "Points near the centre, points far away"): the
/// support point N in the query's direction u, the normal u, the distance ‖Q − N‖; norms taken
/// without overflow.
template <typename S>
PointDistanceResult<S> solveFar(const Superellipsoid<S>& shape, const Vector3<S>& p_SQ,
                                S relative_tolerance);

template <typename S>
PointDistanceResult<S> solveRadial(const Query<S>& q);
template <typename S>
PointDistanceResult<S> solvePaper(const Query<S>& q);
template <typename S>
PointDistanceResult<S> solveExact(const Query<S>& q);

/// pointDistance() with a warm-start hint for the Exact method (see Query::hint): p_SQ and
/// hint_S in the shape's frame; a non-finite hint counts as none. Validates like pointDistance.
template <typename S>
PointDistanceResult<S> pointDistanceWithHint(const Superellipsoid<S>& shape, const Vector3<S>& p_SQ,
                                             const Vector3<S>& hint_S,
                                             const DistanceOptions<S>& options);

/// Checks a query as pointDistance() does (p finite and within the coordinate range, the
/// options valid); the error names `function` and the bad value.
template <typename S>
void validateQuery(const char* function, const Vector3<S>& p, const DistanceOptions<S>& options);

/// pointDistance() after validation: a far or near-centre query's closed form, else the
/// options' method; hint and runner_up as in Query (nullptr for none).
template <typename S>
PointDistanceResult<S> solve(const Superellipsoid<S>& shape, const Vector3<S>& p_SQ,
                             const Vector3<S>* hint, const DistanceOptions<S>& options,
                             S* runner_up = nullptr);

/// The primal formulation (gauge G) is smooth where ε ≤ 1, the dual (support function h) where
/// ε ≥ 1: the Exact method starts with the one whose worst exponent strays less from its smooth
/// side.
template <typename S>
bool primalIsSmoother(const Superellipsoid<S>& shape) {
  const S e1 = shape.eps1(), e2 = shape.eps2();
  const S primal_roughness = std::max({S(0), e1 - S(1), e2 - S(1)});
  const S dual_roughness = std::max({S(0), S(1) - e1, S(1) - e2});
  return primal_roughness <= dual_roughness;
}

/// The Exact method works on |Q| (the shape is symmetric in each coordinate plane): takes its
/// first-octant answer N, n back to Q's own octant (shape/octant.h) and sets d = ±‖Q − N‖ on
/// Q's side. Error, iterations and convergence are the caller's.
template <typename S>
PointDistanceResult<S> fromFirstOctant(const Vector3<S>& q, const Vector3<S>& point,
                                       const Vector3<S>& normal, bool inside) {
  PointDistanceResult<S> r;
  r.nearest_point = intoOctantOf(q, point);
  r.normal = intoOctantOf(q, normal);
  r.distance = negatedWhere(inside, (q - r.nearest_point).norm());
  return r;
}

/// Fills a result from a surface point N: d = ±‖Q − N‖ (the sign of the query's side),
/// n = the unit normal at N, and the paper's error ‖N + d·n − Q‖ (Eq. 7).
template <typename S>
PointDistanceResult<S> resultAt(const Query<S>& q, const Vector3<S>& nearest, bool inside,
                                int iterations) {
  PointDistanceResult<S> r;
  r.nearest_point = nearest;
  r.normal = q.shape.normal(nearest);
  const S len = (q.x - nearest).norm();
  r.distance = inside ? -len : len;
  r.error = (nearest + r.distance * r.normal - q.x).norm();
  r.iterations = iterations;
  r.converged = r.error <= q.tolerance;
  return r;
}

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_SOLVERS_SOLVERS_H
