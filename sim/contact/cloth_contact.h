#ifndef FSE_SIM_CONTACT_CLOTH_CONTACT_H
#define FSE_SIM_CONTACT_CLOTH_CONTACT_H

// How cloth vertices find the surface of one rigid superellipsoid: the scene's collision
// detection. Three models, chosen per run (scene.h → ContactModel): the library's Exact
// solver, the paper's method, and a tessellated mesh in FCL. Each answers the same question
// the same way, so that a run shows what accuracy costs in time.

#include <fcl_superellipsoid/superellipsoid.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "model/scene.h"
#include "model/shapes.h"

namespace fse_sim {

/// A vertex near the surface: the plane through `point` with outward unit `normal` is where
/// the contact holds it (contacts.h).
struct ContactCandidate {
  int vertex;
  int shape;               ///< index in Scene::shapes
  double distance;         ///< signed, as the model sees it (< 0 inside)
  Eigen::Vector3d point;   ///< nearest surface point the model found, world frame
  Eigen::Vector3d normal;  ///< outward unit normal there, world frame
};

class ContactDetector {
 public:
  virtual ~ContactDetector() = default;
  /// Appends to `out` every vertex of `x` whose signed distance to the shape is ≤ margin (as
  /// far as the model can tell), in increasing vertex order.
  virtual void detect(const Eigen::Matrix3Xd& x, double margin,
                      std::vector<ContactCandidate>& out) = 0;
};

/// The detector of shape `index` of the scene for `options.model`.
std::unique_ptr<ContactDetector> makeContactDetector(const ShapeSpec& spec, int index,
                                                     int vertex_count,
                                                     const SimulationOptions& options);

}  // namespace fse_sim

#endif  // FSE_SIM_CONTACT_CLOTH_CONTACT_H
