// The power-free bound of a superellipsoid's support function (contact/support_bound.h), which
// culls the bowl's faces: never below the support function (so it culls only faces the support
// point would), exact for an ellipsoid, no looser than the bounding box's Σ aᵢ|dᵢ|, which it
// replaced, and within its tables' cells of the support function. The truth is the support
// function's closed form in long double, the nested dual norm ‖(‖(a1·d1, a2·d2)‖_q1, a3·d3)‖_q2
// with q = 2/(2 − ε).

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "contact/support_bound.h"

namespace fse_sim {
namespace {

namespace fse = fcl_superellipsoid;

long double qNorm(long double x, long double y, long double eps) {
  const long double q = 2.0L / (2.0L - eps);
  return std::pow(std::pow(std::fabs(x), q) + std::pow(std::fabs(y), q), 1.0L / q);
}

long double support(const fse::Superellipsoidd& shape, const Eigen::Vector3d& d) {
  const Eigen::Vector3d& a = shape.radii();
  return qNorm(qNorm((long double)a[0] * d[0], (long double)a[1] * d[1], shape.eps1()),
               (long double)a[2] * d[2], shape.eps2());
}

const double kExponents[] = {0.1, 0.3, 0.7, 0.99, 1.0, 1.3, 1.9};

TEST(SupportBound, NeverBelowTheSupportFunctionAndNoLooserThanTheBox) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> radius(0.2, 2.0), unit(-1, 1);
  for (double e1 : kExponents) {
    for (double e2 : kExponents) {
      const fse::Superellipsoidd shape(radius(rng), radius(rng), radius(rng), e1, e2);
      const SupportBound bound(shape);
      for (int k = 0; k < 500; ++k) {
        Eigen::Vector3d d(unit(rng), unit(rng), unit(rng));
        if (k < 6) d = Eigen::Vector3d::Unit(k % 3) * (k < 3 ? 1 : -1);  // the axes too
        const long double h = support(shape, d);
        const double b = bound(d);
        EXPECT_GE(b, double(h) * (1 - 1e-14))
            << "ε = (" << e1 << ", " << e2 << "), d = " << d.transpose();
        EXPECT_LE(b, shape.radii().dot(d.cwiseAbs()) * (1 + 1e-14))
            << "ε = (" << e1 << ", " << e2 << "), d = " << d.transpose();
      }
    }
  }
}

TEST(SupportBound, ExactForAnEllipsoid) {
  const fse::Superellipsoidd shape(0.7, 1.3, 0.4, 1.0, 1.0);
  const SupportBound bound(shape);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d d(unit(rng), unit(rng), unit(rng));
    EXPECT_NEAR(bound(d), double(support(shape, d)), 1e-14 * shape.size()) << d.transpose();
  }
}

// Each level's table of (1 + t^q)^(1/q) (a slope of at most 1, 64 cells) is within 1/64 of the
// larger argument of the level's norm, and the outer level adds the inner one's excess at most:
// the bound is within 2/64 of Σ aᵢ|dᵢ| of the support function, for every exponent.
TEST(SupportBound, WithinItsTablesCellOfTheSupportFunction) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> radius(0.2, 2.0), unit(-1, 1), exponent(0.05, 1.95);
  for (int s = 0; s < 60; ++s) {
    const fse::Superellipsoidd shape(radius(rng), radius(rng), radius(rng), exponent(rng),
                                     exponent(rng));
    const SupportBound bound(shape);
    for (int k = 0; k < 300; ++k) {
      const Eigen::Vector3d d(unit(rng), unit(rng), unit(rng));
      const long double h = support(shape, d);
      EXPECT_LE(bound(d) - double(h), 2.0 / 64 * shape.radii().dot(d.cwiseAbs()))
          << "ε = (" << shape.eps1() << ", " << shape.eps2() << "), d = " << d.transpose();
    }
  }
}

// Where one exponent is below 1 and the other above (the box bound's worst case, half the
// bowl's bodies), the bound is well inside the box's along the diagonals.
TEST(SupportBound, TighterThanTheBoxForMixedExponents) {
  for (const auto& [e1, e2] : {std::pair{0.3, 1.7}, std::pair{1.7, 0.3}, std::pair{0.9, 1.0}}) {
    const fse::Superellipsoidd shape(1.0, 0.8, 0.6, e1, e2);
    const SupportBound bound(shape);
    const Eigen::Vector3d d = Eigen::Vector3d(1, 1, 1).normalized();
    const double box = shape.radii().dot(d);
    EXPECT_LT(bound(d), 0.9 * box) << "ε = (" << e1 << ", " << e2 << ")";
    EXPECT_LT(bound(d) - double(support(shape, d)), 0.5 * (box - double(support(shape, d))))
        << "ε = (" << e1 << ", " << e2 << ")";
  }
}

}  // namespace
}  // namespace fse_sim
