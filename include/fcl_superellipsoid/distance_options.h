#ifndef FCL_SUPERELLIPSOID_DISTANCE_OPTIONS_H
#define FCL_SUPERELLIPSOID_DISTANCE_OPTIONS_H

/// @file
/// The point-distance methods and their options (the defaults live here, units written out).

#include <type_traits>

#include "fcl_superellipsoid/export.h"

namespace fcl_superellipsoid {

enum class DistanceMethod {
  /// Paper Eq. 3: one evaluation along the ray from the centre. Exact only where that ray is
  /// normal to the surface (spheres, the axes); an approximation elsewhere.
  kRadial,
  /// The reference paper's iterative normal averaging (tolerance 1e-3 in the paper).
  kPaper,
  /// Our solver (the default): Newton on the optimality conditions, primal or dual, to
  /// machine-level accuracy.
  kExact,
};

FSE_EXPORT const char* toString(DistanceMethod method);

/// Query options. Tolerances are relative to the shape's size (its largest radius): a query
/// converges when its error estimate (paper Eq. 7, ‖N + d·n(N) − Q‖) is at most
/// tolerance × size. For the paper's unit-size shapes this is the paper's absolute tolerance.
template <typename S>
struct DistanceOptions {
  DistanceMethod method = DistanceMethod::kExact;
  S tolerance = defaultTolerance(DistanceMethod::kExact);
  int max_iterations = defaultMaxIterations(DistanceMethod::kExact);

  /// Defaults per method: Exact 1e-12 (double) / 1e-6 (float), 250 iterations shared by all
  /// its starts, at most 60 per start (outside points use 3–6 in all; inside points try up
  /// to 10 starts);
  /// Paper 1e-3 and 30 iterations, as the paper; Radial takes no iterations.
  static S defaultTolerance(DistanceMethod method) {
    if (method == DistanceMethod::kExact) return std::is_same<S, float>::value ? S(1e-6) : S(1e-12);
    return S(1e-3);
  }
  static int defaultMaxIterations(DistanceMethod method) {
    return method == DistanceMethod::kExact ? 250 : 30;
  }
  /// The defaults of a method.
  static DistanceOptions of(DistanceMethod method) {
    return {method, defaultTolerance(method), defaultMaxIterations(method)};
  }
};

/// Checks options: tolerance finite and > 0, max_iterations ≥ 1.
/// @throws std::invalid_argument naming the bad value.
template <typename S>
FSE_EXPORT void validateOptions(const DistanceOptions<S>& options);

extern template FSE_EXPORT void validateOptions(const DistanceOptions<float>&);
extern template FSE_EXPORT void validateOptions(const DistanceOptions<double>&);

}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_DISTANCE_OPTIONS_H
