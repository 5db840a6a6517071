#ifndef FSE_SIM_CONTACT_SUPPORT_BOUND_H
#define FSE_SIM_CONTACT_SUPPORT_BOUND_H

// An upper bound of a superellipsoid's support function without a power, for culling: the
// rigid contacts test it against each of the bowl's faces near a body before they ask the
// shape for its support point (docs/scenes.md → "Rigid contact").
//
// The support function is a nested norm of the scaled direction,
//   h(d) = ‖(‖(a1·d1, a2·d2)‖_q1, a3·d3)‖_q2,  q = 2/(2 − ε),
// (the dual of the gauge's p = 2/ε), and each level's q-norm of (x, y) ≥ 0 is bounded without a
// power, by the least of:
//   - the 2-norm where ε ≥ 1 (q ≥ 2); where ε < 1 (1 < q < 2) the 1-norm and 2^(1/q − 1/2) =
//     2^((1 − ε)/2) times the 2-norm;
//   - m·g(t) with m = max(x, y), t = min/max and g(t) = (1 + t^q)^(1/q), which rises with t
//     with a slope of at most 1: its value at the end of t's cell in a table of kCells cells
//     over [0, 1], so within 1/kCells of m of the norm.
// A norm grows with each argument's magnitude, so bounding the inner level and then the outer
// bounds h. Exact for ε1 = ε2 = 1 (an ellipsoid).

#include <fcl_superellipsoid/superellipsoid.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace fse_sim {

class SupportBound {
 public:
  explicit SupportBound(const fcl_superellipsoid::Superellipsoidd& shape)
      : radii_(shape.radii()), level1_(shape.eps1()), level2_(shape.eps2()) {}

  /// ≥ max over the shape of d·x, for d in the shape's frame.
  double operator()(const Eigen::Vector3d& d) const {
    const Eigen::Vector3d w = radii_.cwiseProduct(d).cwiseAbs();
    return level2_(level1_(w[0], w[1]), w[2]);
  }

 private:
  /// Cells of each level's table of g over t ∈ [0, 1].
  static constexpr int kCells = 64;
  /// One level's bound of ‖(x, y)‖_q for x, y ≥ 0.
  struct Level {
    explicit Level(double eps) : round(eps >= 1), factor(std::exp2(0.5 * (1 - eps))) {
      const double q = 2 / (2 - eps);
      // A few ulps above g at each cell's end: pow's and the product's roundings.
      const double up = 1 + 8 * std::numeric_limits<double>::epsilon();
      for (int k = 0; k <= kCells; ++k) {
        g[std::size_t(k)] = up * std::pow(1 + std::pow(double(k) / kCells, q), 1 / q);
      }
    }
    double operator()(double x, double y) const {
      const double euclid = std::sqrt(x * x + y * y);
      const double power_free = round ? euclid : std::min(x + y, factor * euclid);
      const double m = std::max(x, y), t = std::min(x, y) / m;
      if (!(t >= 0)) return power_free;  // m = 0 (or not finite)
      const double cell = std::ceil(t * kCells);
      return std::min(power_free, m * g[std::size_t(std::min<double>(cell, kCells))]);
    }
    bool round;                        // ε ≥ 1: the 2-norm bounds the q-norm
    double factor;                     // 2^((1 − ε)/2), for ε < 1
    std::array<double, kCells + 1> g;  // g(k/kCells), rounded up
  };
  Eigen::Vector3d radii_;
  Level level1_, level2_;
};

}  // namespace fse_sim

#endif  // FSE_SIM_CONTACT_SUPPORT_BOUND_H
