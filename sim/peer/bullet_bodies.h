#ifndef FSE_SIM_PEER_BULLET_BODIES_H
#define FSE_SIM_PEER_BULLET_BODIES_H

// The rigid-body scenes' peer, what an engineer would pick instead: Bullet's rigid bodies
// (btDiscreteDynamicsWorld, sequential-impulse solver), each body a Bullet convex shape with the
// superellipsoid's exact support point, the bowl a btBvhTriangleMeshShape. Settings matched to
// the scene (docs/scenes.md → "The peer"). It offers what the runner measures of a
// RigidSimulation: the bodies (Bullet's poses and velocities copied into our RigidBody after
// each step, outside the timed step), energy, speed, and the least distance on the exact
// surfaces.

#include <memory>
#include <optional>
#include <vector>

#include "contact/rigid_contact.h"
#include "model/rigid_body.h"
#include "model/scene.h"
#include "model/static_mesh.h"
#include "physics/phases.h"

namespace fse_sim {

class BulletBodies {
 public:
  /// `threads` for the exact measurement only (Bullet steps on one thread).
  BulletBodies(const Scene& scene, int threads);
  ~BulletBodies();
  BulletBodies(const BulletBodies&) = delete;
  BulletBodies& operator=(const BulletBodies&) = delete;

  /// One step of Scene::time.step: Bullet's substeps (each its own collision detection).
  void step();

  double time() const { return time_; }
  const std::vector<RigidBody>& bodies() const { return bodies_; }
  const StaticMesh* bowl() const { return bowl_ ? &*bowl_ : nullptr; }
  /// Bullet's step is timed whole and its collision detection (every substep's) apart.
  const std::vector<Phase>& phases() const { return phases_; }
  const PhaseTimes& lastStepTimes() const { return times_; }
  /// Contact points in Bullet's persistent manifolds after the step.
  int activeContactCount() const { return contacts_; }
  double energy() const { return movingEnergy(bodies_, gravity_); }
  double maxSpeed() const { return maxPointSpeed(bodies_); }
  /// As RigidSimulation::leastDistance: on the exact surfaces.
  double leastDistance(double reach) const { return measure_->leastDistance(bodies_, reach); }

 private:
  struct World;
  std::unique_ptr<World> world_;
  Scene scene_;
  std::vector<RigidBody> bodies_;
  std::optional<StaticMesh> bowl_;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
  std::unique_ptr<RigidContactFinder> measure_;
  std::vector<Phase> phases_{Phase::kCollisionDetection, Phase::kTotal};
  PhaseTimes times_{};
  int contacts_ = 0;
  double time_ = 0;
  long steps_ = 0;
};

}  // namespace fse_sim

#endif  // FSE_SIM_PEER_BULLET_BODIES_H
