// The point-query contract (include/fcl_superellipsoid/point_distance.h), checked on one answer.
#ifndef FCL_SUPERELLIPSOID_FUZZ_POINT_CONTRACT_H
#define FCL_SUPERELLIPSOID_FUZZ_POINT_CONTRACT_H

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "fcl_superellipsoid/point_distance.h"
#include "fuzz_input.h"

namespace fuzz {

using fcl_superellipsoid::DistanceMethod;
using fcl_superellipsoid::DistanceOptions;
using fcl_superellipsoid::PointDistanceResult;
using fcl_superellipsoid::Superellipsoid;

template <typename S>
std::string describe(const Superellipsoid<S>& shape, const Vector3<S>& p_S,
                     const DistanceOptions<S>& options, const PointDistanceResult<S>& r) {
  std::ostringstream out;
  out.precision(std::numeric_limits<S>::max_digits10);
  out << (sizeof(S) == 4 ? "float" : "double") << " radii (" << shape.radii().transpose()
      << ") eps (" << shape.eps1() << ", " << shape.eps2() << ") query (" << p_S.transpose()
      << ") method " << toString(options.method) << " tolerance " << options.tolerance
      << " max_iterations " << options.max_iterations << " -> distance " << r.distance
      << " nearest (" << r.nearest_point.transpose() << ") normal (" << r.normal.transpose()
      << ") iterations " << r.iterations << " converged " << r.converged << " error " << r.error;
  return out.str();
}

/// Where the library claims full accuracy: double, exponents in [0.02, 1.98], aspect ≤ 1000
/// (superellipsoid.h). There the Exact method must converge.
template <typename S>
bool inFullAccuracyRange(const Superellipsoid<S>& shape) {
  auto ok = [](S e) { return e >= S(0.02) && e <= S(1.98); };
  return sizeof(S) == 8 && ok(shape.eps1()) && ok(shape.eps2()) &&
         shape.radii().maxCoeff() <= S(1000) * shape.radii().minCoeff();
}

/// The answer r for p_S (shape frame) meets the contract: finite; N on the surface; unit normal;
/// ‖Q − N‖ = |d|; the sign agrees with the inside test outside the tolerance band; iterations
/// within the cap; a converged answer's error within the tolerance (with its rounding floor).
template <typename S>
void checkPointContract(const Superellipsoid<S>& shape, const Vector3<S>& p_S,
                        const DistanceOptions<S>& options, const PointDistanceResult<S>& r) {
  const auto what = [&](const char* broken) {  // the message, formatted only if it broke
    return [&, broken] { return std::string(broken) + ": " + describe(shape, p_S, options, r); };
  };
  const S eps = std::numeric_limits<S>::epsilon();
  require(std::isfinite(r.distance) && r.nearest_point.allFinite() && r.normal.allFinite() &&
              std::isfinite(r.error),
          what("not finite"));
  const S size = shape.size();
  const S q_norm = p_S.stableNorm();
  const S floor = S(8) * eps * (q_norm + size);
  const S absolute_tolerance = options.tolerance * size + floor;
  require(std::abs(r.normal.norm() - S(1)) <= S(64) * eps, what("normal not unit"));
  require(std::abs(shape.gauge(r.nearest_point) - S(1)) <= (sizeof(S) == 4 ? S(1e-3) : S(1e-8)),
          what("nearest point not on the surface"));
  require(std::abs((p_S - r.nearest_point).stableNorm() - std::abs(r.distance)) <= S(2) * floor,
          what("|Q - N| != |distance|"));
  const S band = std::max(S(4) * std::max(r.error, absolute_tolerance),
                          options.method == DistanceMethod::kExact ? S(0) : S(1e-3) * size);
  if (std::abs(r.distance) > band) {
    require((r.distance < S(0)) == (shape.gauge(p_S) < S(1)),
            what("sign disagrees with inside test"));
  }
  require(r.iterations >= 0 && r.iterations <= options.max_iterations,
          what("iterations over the cap"));
  if (r.converged)
    require(r.error <= absolute_tolerance * S(1.0001), what("converged above tolerance"));
  if (options.method == DistanceMethod::kExact && inFullAccuracyRange(shape) &&
      options.max_iterations >= DistanceOptions<S>::defaultMaxIterations(DistanceMethod::kExact)) {
    require(r.converged, what("Exact did not converge in its full-accuracy range"));
  }
}

}  // namespace fuzz

#endif  // FCL_SUPERELLIPSOID_FUZZ_POINT_CONTRACT_H
