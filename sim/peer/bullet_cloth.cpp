#include "peer/bullet_cloth.h"

#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <chrono>
#include <vector>

#include "bt_superellipsoid_shape.h"
#include "contact/cloth_contact.h"

namespace fse_sim {

namespace support = fcl_superellipsoid::support;

struct BulletCloth::World {
  btSoftBodyRigidBodyCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btSoftRigidDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
  std::vector<std::unique_ptr<support::BtSuperellipsoidShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motion_states;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  btSoftBody* cloth = nullptr;  // owned here, deleted before the world

  ~World() {
    if (cloth != nullptr) {
      world.removeSoftBody(cloth);
      delete cloth;
    }
    for (auto& body : bodies) world.removeRigidBody(body.get());
  }
};

BulletCloth::BulletCloth(const Scene& scene)
    : world_(std::make_unique<World>()), step_(scene.time.step), substeps_(scene.time.substeps) {
  const Eigen::Vector3d g = scene.gravity ? scene.gravity->acceleration : Eigen::Vector3d::Zero();
  const btVector3 gravity = support::toBt(g);
  world_->world.setGravity(gravity);
  btSoftBodyWorldInfo& info = world_->world.getWorldInfo();
  info.m_gravity = gravity;
  info.air_density = 0;
  info.water_density = 0;
  info.m_sparsesdf.Initialize();
  const double tolerance = scene.collision ? scene.collision->tolerance : 0.025;
  // The sparse signed-distance grid Bullet samples the rigid shapes on: its default voxel
  // (0.25) is ten times the tolerance and rounds the superellipsoid's edges away.
  info.m_sparsesdf.voxelsz = btScalar(tolerance);

  const ClothSpec& c = scene.cloth;
  const auto corner = [&](double sx, double sy) {
    return support::toBt(c.centre + Eigen::Vector3d(sx * c.size_x / 2, sy * c.size_y / 2, 0));
  };
  // Node (i, j) at index i + nx·j, as in our grid; diagonals generated (stretch along them too).
  btSoftBody* cloth = btSoftBodyHelpers::CreatePatch(
      info, corner(-1, -1), corner(1, -1), corner(-1, 1), corner(1, 1), c.nx, c.ny, 0, true);
  world_->cloth = cloth;
  cloth->m_cfg.piterations = 1;  // one iteration per substep, as ours
  cloth->m_cfg.kDF = btScalar(scene.friction ? scene.friction->dynamic : 0);
  cloth->m_cfg.kDP =
      btScalar(scene.damping ? 1 - std::exp(-scene.damping->linear * step_ / substeps_) : 0);
  cloth->getCollisionShape()->setMargin(btScalar(tolerance));
  cloth->m_materials[0]->m_kLST = btScalar(scene.stretch ? 1 : 0);
  if (scene.bending) {
    btSoftBody::Material* bend = cloth->appendMaterial();
    // Bullet's stiffness is a per-iteration fraction in [0, 1], not a compliance: hard
    // bending (compliance 0) is 1; a compliance α, as a spring of the same softness per
    // substep, is 1 / (1 + α / (w h²)) with w the vertex's inverse mass.
    const double h = step_ / substeps_;
    const double w = c.nx * c.ny / c.mass;
    bend->m_kLST = btScalar(1 / (1 + scene.bending->compliance / (w * h * h)));
    cloth->generateBendingConstraints(2, bend);
  }
  cloth->setTotalMass(btScalar(c.mass), false);
  if (scene.pinning) {
    for (int v : scene.pinning->fixed) cloth->setMass(v, 0);
  }
  for (Eigen::Index v = 0; v < cloth->m_nodes.size(); ++v) {
    cloth->m_nodes[int(v)].m_v = support::toBt(c.velocity);
  }
  world_->world.addSoftBody(cloth);

  if (scene.collision) {
    for (const ShapeSpec& spec : scene.shapes) {
      world_->shapes.push_back(std::make_unique<support::BtSuperellipsoidShape>(makeShape(spec)));
      const Eigen::Isometry3d pose = shapePose(spec);
      const Eigen::Quaterniond q(pose.linear());
      const btTransform transform(
          btQuaternion(btScalar(q.x()), btScalar(q.y()), btScalar(q.z()), btScalar(q.w())),
          support::toBt(pose.translation()));
      world_->motion_states.push_back(std::make_unique<btDefaultMotionState>(transform));
      btRigidBody::btRigidBodyConstructionInfo body(0, world_->motion_states.back().get(),
                                                    world_->shapes.back().get());
      body.m_friction = btScalar(scene.friction ? scene.friction->dynamic : 0);
      world_->bodies.push_back(std::make_unique<btRigidBody>(body));
      world_->world.addRigidBody(world_->bodies.back().get());
    }
  }
}

BulletCloth::~BulletCloth() = default;

double BulletCloth::step() {
  const auto start = std::chrono::steady_clock::now();
  world_->world.stepSimulation(btScalar(step_), substeps_, btScalar(step_ / substeps_));
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Eigen::Matrix3Xd BulletCloth::positions() const {
  const btSoftBody* cloth = world_->cloth;
  Eigen::Matrix3Xd x(3, cloth->m_nodes.size());
  for (int i = 0; i < cloth->m_nodes.size(); ++i) x.col(i) = support::fromBt(cloth->m_nodes[i].m_x);
  return x;
}

}  // namespace fse_sim
