#include "aspect_sweep.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>

#include "fcl_superellipsoid/point_distance.h"

namespace fcl_superellipsoid {
namespace bench {

int runAspectSweep(int points_per_shape) {
  const double grid[] = {0.02, 0.1, 0.3, 0.65, 1.0, 1.35, 1.7, 1.9, 1.98};
  std::printf(
      "Exact solver, outside points by construction (offsets 1e-3, 0.05, 1 x size),\n"
      "%d points x 3 offsets per exponent pair, 81 pairs per radii\n\n",
      points_per_shape);
  std::printf("%-16s %14s %18s %16s\n", "radii", "miss target", "miss, eps in", "worst error");
  std::printf("%-16s %14s %18s %16s\n", "", "(all eps)", "[0.1, 1.9]", "(x size)");
  for (const std::array<double, 3>& a : {std::array<double, 3>{1, 1, 1},
                                         {3.5, 3, 2},
                                         {1, 1, 1e-3},
                                         {10, 1, 1},
                                         {30, 1, 1},
                                         {100, 1, 1},
                                         {1, 100, 1},
                                         {1, 1, 100},
                                         {300, 1, 1},
                                         {1000, 1, 1}}) {
    int miss = 0, miss_mid = 0, n = 0, n_mid = 0;
    double worst = 0;
    for (double e1 : grid) {
      for (double e2 : grid) {
        const Superellipsoid<double> shape(a[0], a[1], a[2], e1, e2);
        const bool extreme = std::min(e1, e2) < 0.1 || std::max(e1, e2) > 1.9;
        const double target = extreme ? 1e-6 : 1e-9;
        std::mt19937 rng(5);
        std::uniform_real_distribution<double> omega(-M_PI, M_PI), eta(-M_PI / 2, M_PI / 2);
        for (int k = 0; k < points_per_shape; ++k) {
          for (double offset : {1e-3, 0.05, 1.0}) {
            const Vector3<double> p = shape.surfacePoint(eta(rng), omega(rng));
            const Vector3<double> x = p + offset * shape.size() * shape.normal(p);
            const double err =
                std::abs(pointDistance(shape, x).distance - offset * shape.size()) / shape.size();
            ++n;
            n_mid += !extreme;
            worst = std::max(worst, err);
            if (err > target) {
              ++miss;
              miss_mid += !extreme;
            }
          }
        }
      }
    }
    char name[48];
    std::snprintf(name, sizeof name, "(%g, %g, %g)", a[0], a[1], a[2]);
    std::printf("%-16s %7.3f%% (%4d) %10.3f%% (%4d) %16.2e\n", name, 100.0 * miss / n, miss,
                100.0 * miss_mid / n_mid, miss_mid, worst);
  }
  return 0;
}

}  // namespace bench
}  // namespace fcl_superellipsoid
