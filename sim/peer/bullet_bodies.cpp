#include "peer/bullet_bodies.h"

#include <btBulletDynamicsCommon.h>

#include <cmath>

#include "bt_superellipsoid_shape.h"
#include "physics/rigid_contact_solver.h"

namespace fse_sim {

namespace support = fcl_superellipsoid::support;

namespace {

btTransform toBt(const Eigen::Vector3d& x, const Eigen::Quaterniond& q) {
  return btTransform(
      btQuaternion(btScalar(q.x()), btScalar(q.y()), btScalar(q.z()), btScalar(q.w())),
      support::toBt(x));
}

/// Bullet's world with its collision detection timed (it runs once per Bullet substep).
class TimedWorld final : public btDiscreteDynamicsWorld {
 public:
  TimedWorld(btDispatcher* dispatcher, btBroadphaseInterface* broadphase,
             btConstraintSolver* solver, btCollisionConfiguration* configuration, PhaseTimes& times)
      : btDiscreteDynamicsWorld(dispatcher, broadphase, solver, configuration), times_(times) {}
  void performDiscreteCollisionDetection() override {
    ScopedPhase timer(times_, Phase::kCollisionDetection);
    btDiscreteDynamicsWorld::performDiscreteCollisionDetection();
  }

 private:
  PhaseTimes& times_;
};

}  // namespace

struct BulletBodies::World {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  std::unique_ptr<TimedWorld> world;
  // The bowl's triangles as Bullet reads them (its shape keeps pointers into these: declared
  // before the shapes, they outlive them).
  std::vector<btScalar> bowl_vertices;
  std::vector<int> bowl_indices;
  std::unique_ptr<btTriangleIndexVertexArray> bowl_array;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motion_states;
  std::vector<std::unique_ptr<btRigidBody>> bodies;  ///< the scene's, then the bowl

  ~World() {
    for (auto& body : bodies) world->removeRigidBody(body.get());
  }
};

BulletBodies::BulletBodies(const Scene& scene, int threads)
    : world_(std::make_unique<World>()), scene_(scene) {
  for (const BodySpec& spec : sceneBodies(*scene.rigid_bodies)) {
    bodies_.push_back(makeBody(spec, scene.rigid_bodies->density));
  }
  if (scene.bowl) bowl_ = makeBowl(*scene.bowl);
  if (scene.gravity) gravity_ = scene.gravity->acceleration;
  measure_ = std::make_unique<RigidContactFinder>(bodies_, bowl(), ContactModel::kExact,
                                                  scene.rigid_bodies->mesh_vertices, threads);

  World& w = *world_;
  w.world = std::make_unique<TimedWorld>(&w.dispatcher, &w.broadphase, &w.solver, &w.configuration,
                                         times_);
  w.world->setGravity(support::toBt(gravity_));
  // Matched to our solver: its Gauss–Seidel sweeps per substep.
  w.world->getSolverInfo().m_numIterations = RigidContactSolver::kPositionIterations;
  // Bullet combines two bodies' coefficients by their product: each gets the square root, so
  // that every pair has the scene's.
  const double friction = scene.friction ? std::sqrt(scene.friction->dynamic) : 0;
  const double restitution = scene.restitution ? std::sqrt(scene.restitution->coefficient) : 0;
  // Bullet's damping c takes (1 − c)^h of the velocity per step h; ours e^(−d·h).
  const double damping = scene.damping ? 1 - std::exp(-scene.damping->linear) : 0;
  auto add = [&](std::unique_ptr<btCollisionShape> shape, double mass,
                 const Eigen::Vector3d& inertia, const btTransform& pose) {
    w.shapes.push_back(std::move(shape));
    w.motion_states.push_back(std::make_unique<btDefaultMotionState>(pose));
    btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), w.motion_states.back().get(),
                                                  w.shapes.back().get(), support::toBt(inertia));
    info.m_friction = btScalar(friction);
    info.m_restitution = btScalar(restitution);
    info.m_linearDamping = btScalar(damping);
    info.m_angularDamping = btScalar(damping);
    w.bodies.push_back(std::make_unique<btRigidBody>(info));
    if (!scene.rigid_contact) {
      // The scene declares no contacts: Bullet's pairs are found but not resolved.
      w.bodies.back()->setCollisionFlags(w.bodies.back()->getCollisionFlags() |
                                         btCollisionObject::CF_NO_CONTACT_RESPONSE);
    }
    w.world->addRigidBody(w.bodies.back().get());
    return w.bodies.back().get();
  };
  for (const RigidBody& b : bodies_) {
    btRigidBody* body =
        add(std::make_unique<support::BtSuperellipsoidShape>(*b.shape), b.fixed() ? 0.0 : b.mass,
            b.fixed() ? Eigen::Vector3d::Zero() : b.inertia, toBt(b.x, b.q));
    body->setLinearVelocity(support::toBt(b.v));
    body->setAngularVelocity(support::toBt(b.omega));
  }
  if (bowl_) {
    for (Eigen::Index v = 0; v < bowl_->vertices.cols(); ++v) {
      for (int k = 0; k < 3; ++k) w.bowl_vertices.push_back(btScalar(bowl_->vertices(k, v)));
    }
    for (const auto& t : bowl_->triangles)
      w.bowl_indices.insert(w.bowl_indices.end(), t.begin(), t.end());
    w.bowl_array = std::make_unique<btTriangleIndexVertexArray>(
        int(bowl_->triangles.size()), w.bowl_indices.data(), int(3 * sizeof(int)),
        int(bowl_->vertices.cols()), w.bowl_vertices.data(), int(3 * sizeof(btScalar)));
    add(std::make_unique<btBvhTriangleMeshShape>(w.bowl_array.get(), true), 0,
        Eigen::Vector3d::Zero(), btTransform::getIdentity());
  }
}

BulletBodies::~BulletBodies() = default;

void BulletBodies::step() {
  times_.fill(0);
  {
    ScopedPhase total(times_, Phase::kTotal);
    const int n = scene_.time.substeps;
    world_->world->stepSimulation(btScalar(scene_.time.step), n, btScalar(scene_.time.step / n));
  }
  time_ = scene_.time.step * double(++steps_);
  // Bullet's state into ours, for the measurements (not timed).
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const btRigidBody& body = *world_->bodies[i];
    const btTransform& pose = body.getCenterOfMassTransform();
    const btQuaternion q = pose.getRotation();
    RigidBody& b = bodies_[i];
    b.x = support::fromBt(pose.getOrigin());
    b.q = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized();
    b.v = support::fromBt(body.getLinearVelocity());
    b.omega = support::fromBt(body.getAngularVelocity());
  }
  contacts_ = 0;
  btCollisionDispatcher& dispatcher = world_->dispatcher;
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    contacts_ += dispatcher.getInternalManifoldPointer()[m]->getNumContacts();
  }
}

}  // namespace fse_sim
