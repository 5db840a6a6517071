// The duality the Exact solver relies on when it hands a primal evaluation to the dual
// formulation (docs/math.md → "The Exact solver"): at a surface point N with unit normal n, the
// support function's Hessian ∇²h(n), restricted to the tangent plane, is the inverse of the
// shape operator W = Tᵀ∇²G(N)·T/‖∇G(N)‖, and ∇²h(n)·n = 0. Ground truth: the identity itself,
// between two independent evaluations (h from the dual superellipsoid's nested norm, G from the
// shape's), on random points of random shapes away from the coordinate planes (where one of the
// two Hessians is unbounded).

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "fcl_superellipsoid/superellipsoid.h"
#include "shape/nested_norm.h"
#include "test_helpers.h"

namespace fcl_superellipsoid {
namespace {

TEST(NestedNormTest, DualHessianIsTheInverseShapeOperator) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> radius(0.2, 2.0), exponent(0.3, 1.9), angle(0.15, 1.42);
  double worst = 0, worst_radial = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Superellipsoid<double> shape(radius(rng), radius(rng), radius(rng), exponent(rng),
                                       exponent(rng));
    const auto gauge = detail::NestedNorm<double>::gauge(shape);
    const auto support = detail::NestedNorm<double>::support(shape);
    const Vector3<double> point = shape.surfacePoint(angle(rng), angle(rng));
    const auto g = gauge.evaluate(point, true);
    const Vector3<double> n = g.gradient.normalized();
    const auto h = support.evaluate(n, true);
    Eigen::Matrix<double, 3, 2> t;
    t.col(0) = n.unitOrthogonal();
    t.col(1) = n.cross(Vector3<double>(t.col(0)));
    const Eigen::Matrix2d w = t.transpose() * g.hessian * t / g.gradient.norm();
    const Eigen::Matrix2d dual = t.transpose() * h.hessian * t;
    const Eigen::Matrix2d product = dual * w;
    worst = std::max(worst, (product - Eigen::Matrix2d::Identity()).norm());
    worst_radial = std::max(worst_radial, (h.hessian * n).norm() / h.hessian.norm());
    ASSERT_LT((product - Eigen::Matrix2d::Identity()).norm(), 1e-8)
        << shape << " at " << point.transpose() << ": ∇²h·W =\n"
        << product;
    ASSERT_LT((h.hessian * n).norm(), 1e-10 * h.hessian.norm()) << shape;
    // ∇h(n) is the point itself.
    ASSERT_LT((h.gradient - point).norm(), 1e-12 * shape.size()) << shape;
  }
  std::printf("worst |∇²h·W − I| %g, worst |∇²h·n|/|∇²h| %g\n", worst, worst_radial);
}

}  // namespace
}  // namespace fcl_superellipsoid
