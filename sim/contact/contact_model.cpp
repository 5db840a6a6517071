#include "contact/contact_model.h"

#include <cmath>

namespace fse_sim {

// Defined beside their models (library_contact.cpp, mesh_contact.cpp).
std::unique_ptr<ContactDetector> makeLibraryContact(const ShapeSpec&, int, int,
                                                    const SimulationOptions&);
std::unique_ptr<ContactDetector> makeMeshContact(const ShapeSpec&, int, const SimulationOptions&);

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

std::unique_ptr<ContactDetector> makeContactDetector(const ShapeSpec& spec, int index,
                                                     int vertex_count,
                                                     const SimulationOptions& options) {
  if (options.model == ContactModel::kMesh) return makeMeshContact(spec, index, options);
  return makeLibraryContact(spec, index, vertex_count, options);
}

}  // namespace fse_sim
