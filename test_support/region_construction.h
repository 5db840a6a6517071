#ifndef FCL_SUPERELLIPSOID_TEST_SUPPORT_REGION_CONSTRUCTION_H
#define FCL_SUPERELLIPSOID_TEST_SUPPORT_REGION_CONSTRUCTION_H

// Closed forms of contact regions for the manifold tests (test_contact_manifold.cpp,
// test_mesh_manifold.cpp): a superellipsoid's cross-section below its top, the area of a
// superellipse, the area of a polygon of places.

#include <cmath>
#include <vector>

#include "fcl_superellipsoid/contact_manifold.h"

namespace fcl_superellipsoid {
namespace test {

/// The area of the polygon of places, seen along n (shoelace in a basis of the plane ⊥ n).
template <typename S>
double polygonArea(const std::vector<ManifoldPoint<S>>& places, const Vector3<S>& n) {
  const Eigen::Vector3d nd = n.template cast<double>();
  const Eigen::Vector3d e1 = nd.unitOrthogonal(), e2 = nd.cross(e1);
  double area = 0;
  for (std::size_t i = 0; i < places.size(); ++i) {
    const Eigen::Vector3d p = places[i].position.template cast<double>();
    const Eigen::Vector3d q = places[(i + 1) % places.size()].position.template cast<double>();
    area += p.dot(e1) * q.dot(e2) - p.dot(e2) * q.dot(e1);
  }
  return 0.5 * area;
}

/// The area of |x/a|^(2/ε) + |y/b|^(2/ε) ≤ 1: 4ab·Γ(1 + ε/2)²/Γ(1 + ε).
inline double superellipseArea(double a, double b, double eps) {
  return 4 * a * b * std::tgamma(1 + eps / 2) * std::tgamma(1 + eps / 2) / std::tgamma(1 + eps);
}

/// The scale s of the cross-section at depth τ below the top z = a3 (radii a1·s, a2·s).
inline double sectionScale(double a3, double eps2, double tau) {
  const double c = 1 - std::pow((a3 - tau) / a3, 2 / eps2);
  return std::pow(c, eps2 / 2);
}

/// The half-width in y of |x/a|^n + |y/b|^n ≤ 1 at x (0 outside).
inline double halfWidth(double a, double b, double n, double x) {
  const double r = std::abs(x / a);
  return r >= 1 ? 0 : b * std::pow(1 - std::pow(r, n), 1 / n);
}

}  // namespace test
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_TEST_SUPPORT_REGION_CONSTRUCTION_H
