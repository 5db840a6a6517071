#ifndef FSE_SIM_PEER_BULLET_CLOTH_H
#define FSE_SIM_PEER_BULLET_CLOTH_H

// The peer an engineer would pick instead: Bullet's soft-body cloth (btSoftRigidDynamicsWorld,
// btSoftBodyHelpers::CreatePatch) falling on the superellipsoids, each a Bullet convex shape
// with the exact support point. Settings matched to the scene (docs/scenes.md → "The peer").

#include <Eigen/Core>
#include <memory>

#include "model/scene.h"

namespace fse_sim {

class BulletCloth {
 public:
  explicit BulletCloth(const Scene& scene);
  ~BulletCloth();
  BulletCloth(const BulletCloth&) = delete;
  BulletCloth& operator=(const BulletCloth&) = delete;

  /// One step of Scene::time.step: Bullet's substeps, one iteration each. Returns its seconds.
  double step();
  /// The cloth's node positions (Bullet computes in float).
  Eigen::Matrix3Xd positions() const;

 private:
  struct World;
  std::unique_ptr<World> world_;
  double step_;
  int substeps_;
};

}  // namespace fse_sim

#endif  // FSE_SIM_PEER_BULLET_CLOTH_H
