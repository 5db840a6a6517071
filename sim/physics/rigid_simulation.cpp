#include "physics/rigid_simulation.h"

#include <algorithm>
#include <cmath>

namespace fse_sim {
namespace {

/// Fixed-point iterations of the substep's angular velocity (RigidSimulation::substep).
constexpr int kGyroscopicIterations = 3;

/// q turned by the rotation ω·h, exactly (the first-order q += ½h[ω, 0]q followed by
/// normalising turns by 2·atan(|ω|h/2), and the velocity update then finds a slower ω every
/// substep).
Eigen::Quaterniond turnedBy(const Eigen::Quaterniond& q, const Eigen::Vector3d& omega, double h) {
  const double angle = omega.norm() * h;
  if (!(angle > 0)) return q;
  return (Eigen::Quaterniond(Eigen::AngleAxisd(angle, omega / omega.norm())) * q).normalized();
}

}  // namespace

RigidSimulation::RigidSimulation(const Scene& scene, const SimulationOptions& options)
    : Simulation(scene.time), scene_(scene) {
  for (const BodySpec& spec : sceneBodies(*scene.rigid_bodies)) {
    bodies_.push_back(makeBody(spec, scene.rigid_bodies->density));
  }
  if (scene.bowl) bowl_ = makeBowl(*scene.bowl);
  if (scene.gravity) gravity_ = scene.gravity->acceleration;
  if (scene.damping) damping_ = scene.damping->linear;
  if (scene.rigid_contact) {
    finder_ = std::make_unique<RigidContactFinder>(
        bodies_, bowl(), options.model, scene.rigid_bodies->mesh_vertices, options.threads);
    solver_.emplace(scene);
  }
  // Measurement on the exact surfaces, whatever the model (not timed; report/).
  measure_ = std::make_unique<RigidContactFinder>(
      bodies_, bowl(), ContactModel::kExact, scene.rigid_bodies->mesh_vertices, options.threads);
  declarePhases(false, solver_.has_value(), solver_ || damping_ > 0, finder_ != nullptr);
}

void RigidSimulation::detect(double h) {
  // The farthest a body's point can get in the step, doubled for what contacts may add:
  // beyond tolerance + both travels a pair cannot touch before the next detection.
  travel_.resize(bodies_.size());
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const RigidBody& b = bodies_[i];
    travel_[i] = b.fixed() ? 0 : 2 * (b.pointSpeedBound() * h + gravity_.norm() * h * h);
  }
  finder_->find(bodies_, scene_.rigid_contact->tolerance, travel_, contacts_);
  // A support contact follows the support point only where a body's turn in the step can
  // move its points by more than half the tolerance: otherwise the point found at
  // detection stays the lowest to well within the tolerance, and a fixed material point is
  // what lets static friction hold a resting body (a point that follows the support lets
  // it roll freely and rock on its faces).
  const double tolerance = scene_.rigid_contact->tolerance;
  auto turns = [&](int i) {
    if (i < 0) return false;
    const RigidBody& b = bodies_[std::size_t(i)];
    return b.omega.norm() * h * b.bounding_radius > 0.5 * tolerance;
  };
  for (RigidContact& c : contacts_) {
    c.follows_support = c.follows_support && (turns(c.a) || turns(c.b));
  }
  // A pair held by its persistent places needs its support contact only while it turns fast.
  contacts_.erase(
      std::remove_if(contacts_.begin(), contacts_.end(),
                     [](const RigidContact& c) { return c.turning_only && !c.follows_support; }),
      contacts_.end());
}

void RigidSimulation::substep(double h) {
  if (solver_) {
    // Support contacts at the substep's poses, and the contacts' normal velocities before it
    // (restitution), timed as contact work.
    const ScopedPhase timer = timed(Phase::kContactConstraints);
    for (RigidContact& c : contacts_) {
      if (c.follows_support) followSupport(bodies_, c);
    }
    solver_->begin(bodies_, contacts_);
  }
  {
    const ScopedPhase timer = timed(Phase::kIntegration);
    for (RigidBody& b : bodies_) {
      b.x_prev = b.x;
      b.q_prev = b.q;
      if (b.fixed()) continue;
      b.v += h * gravity_;
      b.x += h * b.v;
      // Torque-free, the angular momentum L = I_w(q)·ω is what the Euler equations keep. The
      // substep turns by the ω that carries this L at the orientation it turns to (a fixed-
      // point iteration: ω ← I_w(q')⁻¹·L, q' = q turned by ω·h), so that L is kept to second
      // order in the change of ω rather than drifting with an explicit gyroscopic term.
      const Eigen::Quaterniond start = b.q;
      const Eigen::Vector3d L = b.angularMomentum();
      for (int iteration = 0; iteration < kGyroscopicIterations; ++iteration) {
        const Eigen::Quaterniond turned = turnedBy(start, b.omega, h);
        const Eigen::Matrix3d R = turned.toRotationMatrix();
        b.omega = R * b.inverse_inertia.cwiseProduct(R.transpose() * L).eval();
      }
      b.q = turnedBy(start, b.omega, h);
    }
  }
  if (solver_) {
    const ScopedPhase timer = timed(Phase::kContactConstraints);
    solver_->projectPositions(bodies_, contacts_, h);
  }
  {
    const ScopedPhase timer = timed(Phase::kVelocityUpdate);
    for (RigidBody& b : bodies_) {
      if (b.fixed()) continue;
      b.v = (b.x - b.x_prev) / h;
      // ω from the rotation q·q_prev⁻¹, by its exact angle (the inverse of the integration).
      Eigen::Quaterniond dq = b.q * b.q_prev.inverse();
      if (dq.w() < 0) dq.coeffs() = -dq.coeffs();
      const double sine = dq.vec().norm();
      b.omega = sine > 0 ? Eigen::Vector3d(dq.vec() * (2 * std::atan2(sine, dq.w()) / (sine * h)))
                         : Eigen::Vector3d::Zero();
    }
  }
  if (solver_ || damping_ > 0) {
    const ScopedPhase timer = timed(Phase::kVelocityConstraints);
    if (solver_) solver_->solveVelocities(bodies_, contacts_, h);
    if (damping_ > 0) {
      const double decay = std::exp(-damping_ * h);
      for (RigidBody& b : bodies_) {
        b.v *= decay;
        b.omega *= decay;
      }
    }
  }
}

double RigidSimulation::energy() const { return movingEnergy(bodies_, gravity_); }

double RigidSimulation::maxSpeed() const { return maxPointSpeed(bodies_); }

double RigidSimulation::leastDistance(double reach) const {
  return measure_->leastDistance(bodies_, reach);
}

}  // namespace fse_sim
