#include "fcl_superellipsoid/point_distance.h"

#include "common/coordinate_range.h"
#include "common/invalid_argument.h"
#include "solvers/exact_rules.h"
#include "solvers/solvers.h"

namespace fcl_superellipsoid {
namespace {

template <typename T>
[[noreturn]] void throwInvalid(const std::string& requirement, const T& value) {
  detail::throwInvalidArgument("pointDistance", requirement, value);
}

}  // namespace

namespace detail {
template <typename S>
void validateQuery(const char* function, const Vector3<S>& p, const DistanceOptions<S>& options) {
  if (!p.allFinite()) throwInvalidArgument(function, "the query point must be finite", p);
  if (!withinCoordinateRange(p)) {
    throwInvalidArgument(function,
                         "the query point's coordinates must be at most " +
                             formatValue(maxCoordinate<S>()) + " in magnitude",
                         p);
  }
  validateOptions(options);
}
template void validateQuery(const char*, const Vector3<float>&, const DistanceOptions<float>&);
template void validateQuery(const char*, const Vector3<double>&, const DistanceOptions<double>&);
}  // namespace detail

namespace {
template <typename S>
void validate(const Vector3<S>& p, const DistanceOptions<S>& options) {
  detail::validateQuery("pointDistance", p, options);
}
}  // namespace

template <typename S>
void validateOptions(const DistanceOptions<S>& options) {
  if (!(std::isfinite(options.tolerance) && options.tolerance > S(0))) {
    throwInvalid("options.tolerance must be finite and > 0", options.tolerance);
  }
  if (options.max_iterations < 1) {
    throwInvalid("options.max_iterations must be >= 1", options.max_iterations);
  }
  switch (options.method) {
    case DistanceMethod::kRadial:
    case DistanceMethod::kPaper:
    case DistanceMethod::kExact:
      return;
  }
  throwInvalid("options.method must be a DistanceMethod", static_cast<int>(options.method));
}

template void validateOptions(const DistanceOptions<float>&);
template void validateOptions(const DistanceOptions<double>&);

const char* toString(DistanceMethod method) {
  switch (method) {
    case DistanceMethod::kRadial:
      return "Radial";
    case DistanceMethod::kPaper:
      return "Paper";
    case DistanceMethod::kExact:
      return "Exact";
  }
  return "unknown";
}

template <typename S>
PointDistanceResult<S> pointDistance(const Superellipsoid<S>& shape,
                                     const detail::NonDeduced<Vector3<S>>& p_SQ,
                                     const detail::NonDeduced<DistanceOptions<S>>& options) {
  validate(p_SQ, options);
  return detail::solve<S>(shape, p_SQ, nullptr, options);
}

namespace detail {

template <typename S>
PointDistanceResult<S> solveFar(const Superellipsoid<S>& shape, const Vector3<S>& p_SQ,
                                S relative_tolerance) {
  // ‖Q‖ > 2^digits·size: the nearest point differs from the support point in Q's direction by
  // less than size²/‖Q‖ < ulp(size), and the error estimate (about the support point's offset
  // across u, at most size) is below the rounding floor 8·ε·‖Q‖ ≥ 16·size.
  const S scale = p_SQ.cwiseAbs().maxCoeff();
  const Vector3<S> u = (p_SQ / scale).normalized();
  PointDistanceResult<S> r;
  r.nearest_point = shape.supportPoint(u);
  r.normal = u;
  r.distance = (p_SQ - r.nearest_point).stableNorm();
  r.error = (r.nearest_point + r.distance * r.normal - p_SQ).stableNorm();
  r.iterations = 0;
  r.converged = r.error <=
                exact_rules::absoluteTolerance(relative_tolerance, shape.size(), p_SQ.stableNorm());
  return r;
}

template PointDistanceResult<float> solveFar(const Superellipsoid<float>&, const Vector3<float>&,
                                             float);
template PointDistanceResult<double> solveFar(const Superellipsoid<double>&, const Vector3<double>&,
                                              double);

template <typename S>
PointDistanceResult<S> solve(const Superellipsoid<S>& shape, const Vector3<S>& p_SQ,
                             const Vector3<S>* hint, const DistanceOptions<S>& options,
                             S* runner_up) {
  if (runner_up != nullptr) *runner_up = std::numeric_limits<S>::infinity();
  if (isFarQuery(shape, p_SQ)) return solveFar(shape, p_SQ, options.tolerance);
  // Below a few ulps of the query's magnitude no method can resolve the error estimate: the
  // tolerance has a rounding floor (exact_rules.h), for every method.
  const detail::Query<S> q{
      shape,
      p_SQ,
      exact_rules::absoluteTolerance(options.tolerance, shape.size(), p_SQ.norm()),
      options.max_iterations,
      hint,
      runner_up};
  // At the exact centre the radial direction is undefined, so every method answers with the
  // Exact solver's centre search (documented in point_distance.h).
  if (p_SQ.isZero(S(0))) return detail::solveExact(q);
  // So close to the centre that the query's coordinates are below the rounding of the shape's
  // own (subnormal ones included), its direction is noise: every method answers with the
  // centre's nearest point, reflected into the query's octant (docs/math.md → "Points near the
  // centre, points far away").
  if (detail::isNearCentreQuery(shape, p_SQ)) {
    const detail::Query<S> centre{shape, Vector3<S>::Zero(), q.tolerance, q.max_iterations,
                                  nullptr};
    const PointDistanceResult<S> c = detail::solveExact(centre);
    return detail::resultAt(q, detail::intoOctantOf(p_SQ, c.nearest_point), true, c.iterations);
  }
  switch (options.method) {
    case DistanceMethod::kRadial:
      return detail::solveRadial(q);
    case DistanceMethod::kPaper:
      return detail::solvePaper(q);
    case DistanceMethod::kExact:
      return detail::solveExact(q);
  }
  throwInvalid("options.method is not a DistanceMethod", static_cast<int>(options.method));
}

template PointDistanceResult<float> solve(const Superellipsoid<float>&, const Vector3<float>&,
                                          const Vector3<float>*, const DistanceOptions<float>&,
                                          float*);
template PointDistanceResult<double> solve(const Superellipsoid<double>&, const Vector3<double>&,
                                           const Vector3<double>*, const DistanceOptions<double>&,
                                           double*);

template <typename S>
PointDistanceResult<S> pointDistanceWithHint(const Superellipsoid<S>& shape, const Vector3<S>& p_SQ,
                                             const Vector3<S>& hint_S,
                                             const DistanceOptions<S>& options) {
  validate(p_SQ, options);
  return solve(shape, p_SQ, hint_S.allFinite() ? &hint_S : nullptr, options);
}

template PointDistanceResult<float> pointDistanceWithHint(const Superellipsoid<float>&,
                                                          const Vector3<float>&,
                                                          const Vector3<float>&,
                                                          const DistanceOptions<float>&);
template PointDistanceResult<double> pointDistanceWithHint(const Superellipsoid<double>&,
                                                           const Vector3<double>&,
                                                           const Vector3<double>&,
                                                           const DistanceOptions<double>&);

}  // namespace detail

template <typename S>
PointDistanceResult<S> pointDistance(const Superellipsoid<S>& shape,
                                     const detail::NonDeduced<fcl::Transform3<S>>& X_WS,
                                     const detail::NonDeduced<Vector3<S>>& p_WQ,
                                     const detail::NonDeduced<DistanceOptions<S>>& options) {
  validate(p_WQ, options);
  detail::checkPose("pointDistance", "X_WS", X_WS);
  const Vector3<S> p_SQ = X_WS.inverse(Eigen::Isometry) * p_WQ;
  PointDistanceResult<S> r = pointDistance<S>(shape, p_SQ, options);
  r.nearest_point = X_WS * r.nearest_point;
  r.normal = X_WS.linear() * r.normal;
  return r;
}

namespace detail {

template <typename S>
PointDistanceResult<S> solveRadial(const Query<S>& q) {
  // Paper Eq. 3: the surface point on the ray from the centre through Q.
  const S g = q.shape.gauge(q.x);
  return resultAt(q, q.shape.radialProjection(q.x), g < S(1), 0);
}

template PointDistanceResult<float> solveRadial(const Query<float>&);
template PointDistanceResult<double> solveRadial(const Query<double>&);

}  // namespace detail

template PointDistanceResult<float> pointDistance(const Superellipsoid<float>&,
                                                  const Vector3<float>&,
                                                  const DistanceOptions<float>&);
template PointDistanceResult<double> pointDistance(const Superellipsoid<double>&,
                                                   const Vector3<double>&,
                                                   const DistanceOptions<double>&);
template PointDistanceResult<float> pointDistance(const Superellipsoid<float>&,
                                                  const fcl::Transform3<float>&,
                                                  const Vector3<float>&,
                                                  const DistanceOptions<float>&);
template PointDistanceResult<double> pointDistance(const Superellipsoid<double>&,
                                                   const fcl::Transform3<double>&,
                                                   const Vector3<double>&,
                                                   const DistanceOptions<double>&);

}  // namespace fcl_superellipsoid
