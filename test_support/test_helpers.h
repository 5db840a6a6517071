#ifndef FCL_SUPERELLIPSOID_TEST_TEST_HELPERS_H
#define FCL_SUPERELLIPSOID_TEST_TEST_HELPERS_H

// Shared test support: scalar-dependent tolerances, seeded sampling, and an independent
// long-double reference of the gauge (written from docs/math.md, not from src/).

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "fcl_superellipsoid/superellipsoid.h"
#include "reference_distance.h"

namespace fcl_superellipsoid {
namespace test {

using Scalars = ::testing::Types<float, double>;

/// Relative tolerance for quantities computed with a handful of pow() calls: a few hundred
/// ulps of the scalar (pow of a number near 1 to a large exponent amplifies rounding).
template <typename S>
S evalTolerance() {
  return std::is_same<S, float>::value ? S(2e-5) : S(1e-12);
}

/// The Exact solver's accuracy target, relative to the shape's size: 1e-9 in double for
/// ε ∈ [0.1, 1.9], 1e-6 at the ends of the range (0.02, 1.98); in float the same number of
/// ulps-ish scaled to float (≈ 1e-4 and 1e-3).
template <typename S>
double exactTarget(double e1, double e2) {
  const bool extreme = std::min(e1, e2) < 0.1 || std::max(e1, e2) > 1.9;
  if (std::is_same<S, float>::value) return extreme ? 1e-3 : 1e-4;
  return extreme ? 1e-6 : 1e-9;
}

/// The exponent grid of the hard cases, from 0.02 to 1.98.
inline std::vector<double> exponentGrid() {
  return {0.02, 0.1, 0.3, 0.65, 1.0, 1.35, 1.7, 1.9, 1.98};
}

/// Radii with aspect ratios up to 1000:1 (and the extreme scales 1e-4, 1e4).
inline std::vector<std::array<double, 3>> radiiSet() {
  return {{1, 1, 1},    {3.5, 3.0, 2.0},      {1000, 1, 1},     {1, 1000, 1},
          {1, 1, 1e-3}, {1e-4, 2e-4, 1.5e-4}, {1e4, 0.5e4, 2e4}};
}

/// True for a cigar-like shape: one radius more than 5× the middle one. (A flat, disk-like
/// shape, one radius 1000× smaller, is not elongated in this sense.)
inline bool isElongated(const std::array<double, 3>& a) {
  std::array<double, 3> s = a;
  std::sort(s.begin(), s.end());
  return s[2] > 5 * s[1];
}

/// Independent reference of G = F^(ε2/2) in long double (reference_distance.h).
inline long double referenceGauge(const std::array<long double, 3>& a, long double e1,
                                  long double e2, const std::array<long double, 3>& x) {
  return ReferenceDistance(a, e1, e2).gauge(x);
}

template <typename S>
long double referenceGauge(const Superellipsoid<S>& s, const Vector3<S>& x) {
  return referenceGauge({s.radii()[0], s.radii()[1], s.radii()[2]}, s.eps1(), s.eps2(),
                        {x[0], x[1], x[2]});
}

/// A random pose: a rotation from a normal quaternion, a translation of normal coordinates
/// times `scale`.
template <typename S>
fcl::Transform3<S> randomPose(std::mt19937& rng, S scale) {
  std::normal_distribution<double> g;
  const Eigen::Quaternion<S> q(S(g(rng)), S(g(rng)), S(g(rng)), S(g(rng)));
  fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = scale * Vector3<S>(S(g(rng)), S(g(rng)), S(g(rng)));
  return X;
}

/// Uniform angles of the parametric surface (paper Eq. 4), seeded.
struct AngleSampler {
  explicit AngleSampler(unsigned seed) : rng(seed) {}
  std::pair<double, double> operator()() {
    std::uniform_real_distribution<double> eta(-M_PI / 2, M_PI / 2), omega(-M_PI, M_PI);
    return {eta(rng), omega(rng)};
  }
  std::mt19937 rng;
};

template <typename S>
std::string describe(const Superellipsoid<S>& s) {
  std::ostringstream out;
  out << s;
  return out.str();
}

}  // namespace test
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_TEST_TEST_HELPERS_H
