#ifndef FSE_SIM_PHYSICS_CLOTH_SIMULATION_H
#define FSE_SIM_PHYSICS_CLOTH_SIMULATION_H

// A cloth scene stepped with XPBD and substeps (docs/scenes.md → "The step"). Only the
// effects the scene declares are constructed; a step runs only their code, and the phases
// they own (phases.h) exist only when one of them is declared.

#include <tbb/task_arena.h>

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "contact/cloth_contact.h"
#include "model/cloth_mesh.h"
#include "model/scene.h"
#include "physics/cloth_contact_solver.h"
#include "physics/distance_constraints.h"
#include "physics/simulation.h"

namespace fse_sim {

class ClothSimulation final : public Simulation {
 public:
  ClothSimulation(const Scene& scene, const SimulationOptions& options = {});

  const ClothMesh& mesh() const { return mesh_; }
  const Eigen::Matrix3Xd& positions() const { return x_; }
  const Eigen::Matrix3Xd& velocities() const { return v_; }
  double vertexMass() const { return vertex_mass_; }

  /// The contacts (nullptr without `collision`).
  const Contacts* contacts() const { return contacts_.get(); }

  /// Largest edge strain |L/L0 − 1| over the cloth's edges (with or without `stretch`).
  double maxEdgeStrain() const;
  /// Kinetic + gravitational potential (+ elastic, for compliant constraints) energy, J.
  double energy() const;

 private:
  void detect(double h) override;
  void runSubsteps(int n, double h) override;  ///< on the run's threads
  void substep(double h) override;

  Scene scene_;
  ClothMesh mesh_;
  Eigen::Matrix3Xd x_, v_, x_start_;
  Eigen::VectorXd w_;  ///< inverse masses (0: fixed)
  double vertex_mass_;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
  std::optional<DistanceConstraints> stretch_, bending_;
  std::vector<AttachmentSpec> attachments_;
  std::unique_ptr<Contacts> contacts_;
  double damping_ = 0;
  bool velocity_pass_ = false, position_pass_ = false;
  DistanceConstraints edges_;               ///< every edge, for measuring strain only
  std::unique_ptr<tbb::task_arena> arena_;  ///< the run's threads (none: the calling thread)
};

}  // namespace fse_sim

#endif  // FSE_SIM_PHYSICS_CLOTH_SIMULATION_H
