#ifndef FSE_SIM_REPORT_MEASUREMENTS_H
#define FSE_SIM_REPORT_MEASUREMENTS_H

// What a run records after every step, measured outside the timed phases and always against
// the exact surfaces (the library's Exact solver), whatever contact model the run used.

#include <fcl_superellipsoid/superellipsoid.h>

#include <vector>

#include "physics/cloth_simulation.h"

namespace fse_sim {

struct StepRecord {
  double time = 0;                ///< s, at the end of the step
  PhaseTimes seconds{};           ///< per phase
  double max_penetration = 0;     ///< m, deepest vertex inside any shape (0 if none)
  int contacts = 0;               ///< vertices held on a contact plane in the last substep
  double contact_error_max = 0;   ///< m, max |true distance| over those vertices
  double contact_error_mean = 0;  ///< m, their mean |true distance|
  double max_edge_strain = 0;
  double energy = 0;     ///< J
  double max_speed = 0;  ///< m/s
};

class Measurer {
 public:
  explicit Measurer(const Scene& scene);
  StepRecord measure(const ClothSimulation& simulation) const;
  /// Deepest penetration (m, ≥ 0) of positions x into the scene's shapes.
  double maxPenetration(const Eigen::Matrix3Xd& x) const;

 private:
  std::vector<fcl_superellipsoid::Superellipsoidd> shapes_;
  std::vector<fcl::Transform3d> poses_;
};

}  // namespace fse_sim

#endif  // FSE_SIM_REPORT_MEASUREMENTS_H
