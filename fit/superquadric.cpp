#include "superquadric.h"

#include <fcl_superellipsoid/point_distance.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace fse_fit {

namespace fse = fcl_superellipsoid;

fse::Superellipsoidd Superquadric::shape() const { return fse::Superellipsoidd(radii, eps1, eps2); }

fcl::Transform3d Superquadric::pose() const {
  fcl::Transform3d X_WS = fcl::Transform3d::Identity();
  X_WS.linear() = rotation.normalized().toRotationMatrix();
  X_WS.translation() = translation;
  return X_WS;
}

std::vector<double> signedDistances(const Superquadric& sq,
                                    const std::vector<Eigen::Vector3d>& p_W) {
  const fse::Superellipsoidd shape = sq.shape();
  const fcl::Transform3d X_WS = sq.pose();
  std::vector<double> out;
  out.reserve(p_W.size());
  for (const Eigen::Vector3d& p : p_W) out.push_back(fse::pointDistance(shape, X_WS, p).distance);
  return out;
}

Superquadric equivalentNearest(const Superquadric& sq, const Superquadric& reference) {
  const Eigen::Quaterniond q = sq.rotation.normalized();
  const Eigen::Quaterniond reference_q = reference.rotation.normalized();
  Superquadric best = sq;
  double best_angle = 10;
  for (int swap = 0; swap < 2; ++swap) {
    Superquadric base = sq;
    if (swap == 1) {  // S' = S rotated a quarter turn about z: x' = y, y' = −x, so a1' = a2
      base.rotation = q * Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
      std::swap(base.radii[0], base.radii[1]);
    }
    const std::array<Eigen::Quaterniond, 4> half_turns = {
        Eigen::Quaterniond::Identity(), Eigen::Quaterniond(0, 1, 0, 0),
        Eigen::Quaterniond(0, 0, 1, 0), Eigen::Quaterniond(0, 0, 0, 1)};
    for (const Eigen::Quaterniond& h : half_turns) {
      Superquadric candidate = base;
      candidate.rotation = (base.rotation * h).normalized();
      const double angle = candidate.rotation.angularDistance(reference_q);
      if (angle < best_angle) {
        best_angle = angle;
        best = candidate;
      }
    }
  }
  return best;
}

ParameterError parameterError(const Superquadric& fitted, const Superquadric& truth) {
  const Superquadric f = equivalentNearest(fitted, truth);
  ParameterError e;
  e.centre = (f.translation - truth.translation).norm() / truth.size();
  e.radii = (f.radii - truth.radii).cwiseAbs().maxCoeff() / truth.size();
  e.exponents = std::max(std::abs(f.eps1 - truth.eps1), std::abs(f.eps2 - truth.eps2));
  e.rotation = f.rotation.angularDistance(truth.rotation.normalized());
  e.largest = std::max({e.centre, e.radii, e.exponents, e.rotation});
  return e;
}

}  // namespace fse_fit
