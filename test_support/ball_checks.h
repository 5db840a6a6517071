#ifndef FCL_SUPERELLIPSOID_TEST_SUPPORT_BALL_CHECKS_H
#define FCL_SUPERELLIPSOID_TEST_SUPPORT_BALL_CHECKS_H

// What the inside certificates' tests (test_ball_certificate.cpp, test_direction_cover.cpp)
// share: stationary points of the distance by construction, and the check of a certified ball
// against the independent long-double reference.

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include "fcl_superellipsoid/superellipsoid.h"
#include "reference_distance.h"

namespace fcl_superellipsoid {
namespace test {

/// The largest value of the reference gauge over `samples` random points of the sphere of
/// radius d around y: at most 1 (to rounding) if the sphere, and so the ball, lies inside.
inline long double worstGaugeOnSphere(const ReferenceDistance& reference, const Vector3<double>& y,
                                      double d, int samples, std::mt19937& rng) {
  std::normal_distribution<double> g(0, 1);
  long double worst = 0;
  for (int j = 0; j < samples; ++j) {
    const Vector3<double> on_sphere = y + d * Vector3<double>(g(rng), g(rng), g(rng)).normalized();
    worst = std::max(worst, reference.gauge({on_sphere[0], on_sphere[1], on_sphere[2]}));
  }
  return worst;
}

/// A stationary point of the distance inside the shape, by construction: Q = N − d·n for a
/// surface point N of the first octant and its outward normal n.
struct StationaryPoint {
  Vector3<double> y, n_point, normal;
  double d;
};

/// A stationary point from the next angles (η, ω) of `angles` and a depth d = min_radius ×
/// 10^(lo + span·u), u uniform in [0, 1) from `rng`: from shallow to beyond the smallest radius,
/// where N is mostly a local minimum or a saddle, not the global answer. std::nullopt where Q
/// leaves the first octant (another octant's point).
template <typename Angles>
std::optional<StationaryPoint> stationaryPoint(const Superellipsoid<double>& shape, Angles& angles,
                                               std::mt19937& rng, double lo, double span) {
  std::uniform_real_distribution<double> u(0, 1);
  const auto [eta, omega] = angles();
  const Vector3<double> n_point = shape.surfacePoint(eta, omega).cwiseAbs();
  const Vector3<double> normal = shape.normal(n_point);
  const double d = shape.radii().minCoeff() * std::pow(10.0, lo + span * u(rng));
  const Vector3<double> y = n_point - d * normal;
  if ((y.array() < 0).any()) return std::nullopt;
  return StationaryPoint{y, n_point, normal, d};
}

}  // namespace test
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_TEST_SUPPORT_BALL_CHECKS_H
