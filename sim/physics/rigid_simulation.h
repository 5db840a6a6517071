#ifndef FSE_SIM_PHYSICS_RIGID_SIMULATION_H
#define FSE_SIM_PHYSICS_RIGID_SIMULATION_H

// A rigid-body scene stepped with XPBD and substeps (Müller et al. 2020; docs/scenes.md →
// "Rigid bodies"): once per step, collision detection gathers the contacts any body can reach
// in the step; each substep integrates (gravity, the gyroscopic term), runs the contacts'
// position pass, derives the velocities from the poses, and runs the velocity pass (friction,
// restitution, damping). As for the cloth, only the declared effects are built and run.

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "contact/rigid_contact.h"
#include "model/rigid_body.h"
#include "model/scene.h"
#include "model/static_mesh.h"
#include "physics/rigid_contact_solver.h"
#include "physics/simulation.h"

namespace fse_sim {

class RigidSimulation final : public Simulation {
 public:
  /// options.model: exact, vertices, paper or mesh (contact/rigid_contact.h).
  RigidSimulation(const Scene& scene, const SimulationOptions& options = {});

  const std::vector<RigidBody>& bodies() const { return bodies_; }
  /// The fixed bowl (nullptr: the scene has none).
  const StaticMesh* bowl() const { return bowl_ ? &*bowl_ : nullptr; }
  /// Contacts gathered for the last step, and those resolved in its last substep.
  const std::vector<RigidContact>& contacts() const { return contacts_; }
  int contactCount() const { return int(contacts_.size()); }
  int activeContactCount() const { return solver_ ? solver_->activeCount() : 0; }

  /// Kinetic + gravitational potential energy of the moving bodies, J.
  double energy() const;
  /// A bound on the speed of any point of a moving body (|v| + |ω|·bounding radius), m/s.
  double maxSpeed() const;
  /// The least signed distance between bodies and between a body and the bowl on the exact
  /// surfaces (negative: the deepest interpenetration), among pairs within `reach`.
  double leastDistance(double reach) const;

 private:
  void detect(double h) override;
  void substep(double h) override;

  Scene scene_;
  std::vector<RigidBody> bodies_;
  std::optional<StaticMesh> bowl_;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
  double damping_ = 0;
  std::unique_ptr<RigidContactFinder> finder_;
  std::unique_ptr<RigidContactFinder> measure_;  ///< exact surfaces, for leastDistance()
  std::optional<RigidContactSolver> solver_;
  std::vector<RigidContact> contacts_;
  std::vector<double> travel_;  ///< per body, this step (collision detection)
};

}  // namespace fse_sim

#endif  // FSE_SIM_PHYSICS_RIGID_SIMULATION_H
