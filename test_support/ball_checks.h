#ifndef FCL_SUPERELLIPSOID_TEST_SOLVERS_BALL_CHECKS_H
#define FCL_SUPERELLIPSOID_TEST_SOLVERS_BALL_CHECKS_H

// What the inside certificates' tests (test_ball_certificate.cpp, test_direction_cover.cpp)
// check of a certified ball against the independent long-double reference.

#include <algorithm>
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

}  // namespace test
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_TEST_SOLVERS_BALL_CHECKS_H
