#ifndef FSE_FIT_SYNTHETIC_CLOUD_H
#define FSE_FIT_SYNTHETIC_CLOUD_H

// Point clouds of known superquadrics, as a depth sensor would see them: points spread evenly
// over the surface (or only over the side facing a viewer), Gaussian noise, outliers.
// docs/fitting.md → "The study".

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "superquadric.h"

namespace fse_fit {

/// Points uniformly distributed by area over the surface, each on it to rounding: a fine
/// tessellation's triangles drawn in proportion to their area, a uniform point in the triangle,
/// projected onto the surface along its ray from the centre. World frame.
std::vector<Eigen::Vector3d> surfaceSamples(const Superquadric& sq, int count, std::uint64_t seed);

struct CloudSpec {
  Superquadric truth;
  int points = 1000;     ///< in the cloud, outliers included
  bool partial = false;  ///< only the surface whose outward normal faces `view`
  Eigen::Vector3d view = Eigen::Vector3d(1, 1, 1).normalized();  ///< toward the viewer (world)
  double noise = 0;     ///< σ of the Gaussian noise of each coordinate, × the size
  double outliers = 0;  ///< the fraction of the points spread uniformly over the box of
                        ///< 1.5 × the shape's world bounding box
  std::uint64_t seed = 1;
};

struct SyntheticCloud {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3d> inliers;  ///< the points that are not outliers
};

SyntheticCloud makeCloud(const CloudSpec& spec);

/// The distance between two surfaces, as a fraction of `reference`'s size: the root mean square
/// of the exact distances from `count` samples of each surface to the other.
double surfaceError(const Superquadric& fitted, const Superquadric& reference, int count = 2000);

/// The root mean square of the exact distances of the points from the superquadric's surface.
double surfaceRms(const Superquadric& sq, const std::vector<Eigen::Vector3d>& points);

}  // namespace fse_fit

#endif  // FSE_FIT_SYNTHETIC_CLOUD_H
