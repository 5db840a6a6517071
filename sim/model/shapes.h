#ifndef FSE_SIM_MODEL_SHAPES_H
#define FSE_SIM_MODEL_SHAPES_H

// A scene's superellipsoid (ShapeSpec) as the library's shape, and its pose.

#include <fcl_superellipsoid/superellipsoid.h>

#include <Eigen/Geometry>

#include "model/scene.h"

namespace fse_sim {

/// The pose of a scene shape: translation, then rotations about fixed x, y, z.
Eigen::Isometry3d shapePose(const ShapeSpec& spec);
/// The same pose as FCL's transform (what the library's calls take).
fcl::Transform3d shapeTransform(const ShapeSpec& spec);
/// The library's shape of the spec's radii and exponents.
fcl_superellipsoid::Superellipsoidd makeShape(const ShapeSpec& spec);

}  // namespace fse_sim

#endif  // FSE_SIM_MODEL_SHAPES_H
