#include "shape/curvature.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "shape/nested_norm.h"
#include "shape/symmetric2.h"

namespace fcl_superellipsoid {
namespace detail {
namespace {

constexpr double kHalfPi = 1.57079632679489661923;
/// Samples per axis over the first octant's directions (polar angle from +z, azimuth from +x),
/// at the midpoints of as many cells over [0, π/2]: 5.6° apart. The smallest radius varies
/// smoothly with the normal where both exponents are ≤ 1, with one basin per feature (a tip, an
/// edge, a corner), and a 16 × 16 grid puts a sample in each (measured against a 128 × 128 grid
/// over 1,331 shapes, ε from 0.02 to 1 and aspect to 1000: same minima to 3e-6; even 6 × 6 does).
constexpr int kGrid = 16;
/// The grid's local minima refined by the pattern search, lowest first, and the step at which it
/// stops (radians): at a minimum the radius is quadratic in the step, so the search ends within
/// far less than the safety factor's 10 % (3e-6 relative over the same 1,331 shapes).
constexpr int kRefined = 3;
constexpr double kFinestStep = 1e-3;
constexpr int kMovesPerStep = 8;
/// The reported bound is this fraction of the smallest radius found. Where both exponents are
/// ≤ 1 the radii vary smoothly over the sphere and the refined minimum is accurate to far better
/// than this (the tests check it against closed forms and against the principal radii of the
/// parametric surface at 11,236 points per shape, test/shape/test_superellipsoid.cpp).
constexpr double kSafety = 0.9;
/// The search is trusted up to this ratio of the largest to the smallest radius. Beyond it a
/// shape's smallest radii sit at normals crowded into so small a part of the octant that the
/// grids can miss their basin: on 5,000 random shapes with aspect ratios up to 1e4 and 1e8
/// (exponents 0.02–1) it found minima up to 1.28 and 3.7 times the one a 64 × 64 search finds,
/// and the 10 % safety factor no longer covered them (docs/hardening.md, finding 24); up to 1000
/// the two agree within 0.9 %. Beyond it the bound is 0: the rolling-ball certificate is off,
/// as on shapes with creases, and the other certificates answer.
constexpr double kMaxSearchedAspect = 1000;
/// Directions stay this far (radians) inside the octant: on a coordinate plane the dual norm's
/// Hessian is singular (infinite radii where ε < 1) and its evaluation reports zeros there.
/// Radii are continuous up to the planes where ε = 1, so the limit is kept.
constexpr double kEdge = 1e-7;

/// The smallest principal radius of curvature at the surface point of unit normal u (first
/// octant, off the coordinate planes).
double smallestRadiusAt(const NestedNorm<double>& support, const Eigen::Vector3d& u) {
  const Eigen::Matrix3d h = support.evaluate(u, true).hessian;
  const Eigen::Vector3d helper =
      std::abs(u[0]) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d t1 = u.cross(helper).normalized();
  const Eigen::Vector3d t2 = u.cross(t1);
  const double b11 = t1.dot(h * t1), b22 = t2.dot(h * t2), b12 = t1.dot(h * t2);
  // Near a face the other radius is many orders of magnitude larger (symmetric2.h).
  const double lowest = eigenvalues2(b11, b12, b22).lowest;
  return std::isfinite(lowest) ? std::max(lowest, 0.0) : 0.0;
}

Eigen::Vector3d unit(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

/// The smallest radius over the octant for one parametrisation of the normals, (θ, φ) ∈
/// [0, π/2]² → normal(θ, φ): a grid, then a pattern search from its lowest samples.
template <typename Normal>
double searchMinimum(const NestedNorm<double>& support, const Normal& normal) {
  auto radius = [&](double theta, double phi) {
    const Eigen::Vector3d u =
        normal(std::clamp(theta, kEdge, kHalfPi - kEdge), std::clamp(phi, kEdge, kHalfPi - kEdge));
    // A normal with a component that is 0 or subnormal lies on a coordinate plane, where the
    // norm's evaluation reports zeros instead of the true radius (infinite where ε < 1, the
    // limit of nearby samples where ε = 1): not a sample.
    if (!u.allFinite()) return 0.0;
    if (!(u.minCoeff() > std::numeric_limits<double>::min())) {
      return std::numeric_limits<double>::infinity();
    }
    return smallestRadiusAt(support, u);
  };
  const double step = kHalfPi / kGrid;
  std::vector<std::pair<double, std::array<double, 2>>> samples;
  samples.reserve(kGrid * kGrid);
  for (int i = 0; i < kGrid; ++i) {
    for (int j = 0; j < kGrid; ++j) {
      const double theta = (i + 0.5) * step, phi = (j + 0.5) * step;
      samples.push_back({radius(theta, phi), {theta, phi}});
    }
  }
  // The grid's local minima (no lower sample among the 8 neighbours): one start per basin, where
  // the lowest samples would often be neighbours in a single basin. The grid's lowest sample is
  // always among them (samples are never NaN: smallestRadiusAt reports 0 for a non-finite one).
  std::vector<std::pair<double, std::array<double, 2>>> minima;
  for (int i = 0; i < kGrid; ++i) {
    for (int j = 0; j < kGrid; ++j) {
      const double v = samples[i * kGrid + j].first;
      bool lowest = true;
      for (int a = std::max(i - 1, 0); a <= std::min(i + 1, kGrid - 1); ++a) {
        for (int b = std::max(j - 1, 0); b <= std::min(j + 1, kGrid - 1); ++b) {
          if (samples[a * kGrid + b].first < v) lowest = false;
        }
      }
      if (lowest) minima.push_back(samples[i * kGrid + j]);
    }
  }
  const int refined = std::min<int>(kRefined, static_cast<int>(minima.size()));
  std::partial_sort(minima.begin(), minima.begin() + refined, minima.end(),
                    [](const auto& a, const auto& b) { return a.first < b.first; });
  double best = minima.front().first;
  for (int k = 0; k < refined; ++k) {
    auto [value, at] = minima[k];
    for (double s = step; s > kFinestStep; s *= 0.5) {
      bool moved = true;
      for (int moves = 0; moved && moves < kMovesPerStep; ++moves) {
        moved = false;
        for (const auto& [dt, dp] : {std::pair<double, double>{1, 0},
                                     {-1, 0},
                                     {0, 1},
                                     {0, -1},
                                     {1, 1},
                                     {1, -1},
                                     {-1, 1},
                                     {-1, -1}}) {
          const double theta = std::clamp(at[0] + s * dt, 0.0, kHalfPi);
          const double phi = std::clamp(at[1] + s * dp, 0.0, kHalfPi);
          const double v = radius(theta, phi);
          if (v < value) {
            value = v;
            at = {theta, phi};
            moved = true;
          }
        }
      }
    }
    best = std::min(best, value);
  }
  return best;
}

}  // namespace

double minRadiusOfCurvature(const Eigen::Vector3d& radii, double eps1, double eps2) {
  if (eps1 > 1 || eps2 > 1) return 0;
  if (radii.maxCoeff() > kMaxSearchedAspect * radii.minCoeff()) return 0;
  const double q1 = 2 / (2 - eps1), q2 = 2 / (2 - eps2);
  const NestedNorm<double> support{radii, q1, q2, 1 / q1, 1 / q2};
  const NestedNorm<double> gauge{radii.cwiseInverse(), 2 / eps1, 2 / eps2, eps1 / 2, eps2 / 2};
  auto normalOfPoint = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d {
    return gauge.evaluate(x, false).gradient.normalized();
  };
  // Three parametrisations of the normals, so that a small radius is sampled wherever it hides:
  // uniform in the normal's direction; the normal at the surface point on a stretched ray
  // (uniform over the surface, as the tessellation samples it); and the normal at the paper's
  // Eq. 4 angles, which crowd at the edges of box-like shapes, where the radii are smallest.
  const double by_normal = searchMinimum(support, unit);
  const double by_surface = searchMinimum(support, [&](double theta, double phi) {
    return normalOfPoint(unit(theta, phi).cwiseProduct(radii));
  });
  const double by_angles = searchMinimum(support, [&](double eta, double omega) {
    const double ce = std::pow(std::cos(eta), eps2);
    return normalOfPoint(Eigen::Vector3d(radii[0] * ce * std::pow(std::cos(omega), eps1),
                                         radii[1] * ce * std::pow(std::sin(omega), eps1),
                                         radii[2] * std::pow(std::sin(eta), eps2)));
  });
  return kSafety * std::min({by_normal, by_surface, by_angles});
}

}  // namespace detail
}  // namespace fcl_superellipsoid
