#include "model/shapes.h"

#include <cmath>

namespace fse_sim {

Eigen::Isometry3d shapePose(const ShapeSpec& spec) {
  const Eigen::Vector3d r = spec.rotation_deg * (M_PI / 180);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(r[2], Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(r[1], Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(r[0], Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  pose.translation() = spec.position;
  return pose;
}

fcl::Transform3d shapeTransform(const ShapeSpec& spec) {
  const Eigen::Isometry3d pose = shapePose(spec);
  fcl::Transform3d X = fcl::Transform3d::Identity();
  X.linear() = pose.linear();
  X.translation() = pose.translation();
  return X;
}

fcl_superellipsoid::Superellipsoidd makeShape(const ShapeSpec& spec) {
  return fcl_superellipsoid::Superellipsoidd(spec.radii[0], spec.radii[1], spec.radii[2], spec.eps1,
                                             spec.eps2);
}

}  // namespace fse_sim
