#include "physics/cloth_simulation.h"

#include <algorithm>
#include <cmath>

namespace fse_sim {

ClothSimulation::ClothSimulation(const Scene& scene, const SimulationOptions& options)
    : Simulation(scene.time),
      scene_(scene),
      mesh_(makeClothMesh(scene.cloth)),
      x_(mesh_.rest_positions),
      v_(3, mesh_.vertexCount()),
      x_start_(x_),
      w_(mesh_.vertexCount()),
      vertex_mass_(scene.cloth.mass / mesh_.vertexCount()),
      edges_(mesh_.edges, mesh_.rest_positions, 0) {
  v_.colwise() = scene.cloth.velocity;
  w_.setConstant(1 / vertex_mass_);
  if (scene.gravity) gravity_ = scene.gravity->acceleration;
  if (scene.stretch) stretch_.emplace(mesh_.edges, mesh_.rest_positions, scene.stretch->compliance);
  if (scene.bending) {
    bending_.emplace(mesh_.bending_pairs, mesh_.rest_positions, scene.bending->compliance);
  }
  if (scene.pinning) {
    for (int vertex : scene.pinning->fixed) {
      w_[vertex] = 0;
      v_.col(vertex).setZero();
    }
    attachments_ = scene.pinning->attached;
  }
  if (scene.collision) contacts_ = std::make_unique<Contacts>(scene, options);
  if (scene.damping) damping_ = scene.damping->linear;
  position_pass_ = stretch_ || bending_ || !attachments_.empty();
  velocity_pass_ = scene.friction || scene.damping;
  if (options.threads != 1) {
    arena_ = options.threads > 1 ? std::make_unique<tbb::task_arena>(options.threads)
                                 : std::make_unique<tbb::task_arena>();
  }

  declarePhases(position_pass_, contacts_ != nullptr, velocity_pass_, contacts_ != nullptr);
}

void ClothSimulation::detect(double h) {
  double max_speed2 = 0;
  for (Eigen::Index i = 0; i < v_.cols(); ++i) {
    max_speed2 = std::max(max_speed2, v_.col(i).squaredNorm());
  }
  contacts_->detect(x_, std::sqrt(max_speed2), gravity_.norm(), h);
}

void ClothSimulation::runSubsteps(int n, double h) {
  if (arena_) {
    arena_->execute([&] { Simulation::runSubsteps(n, h); });
  } else {
    Simulation::runSubsteps(n, h);
  }
}

void ClothSimulation::substep(double h) {
  const Eigen::Index n = x_.cols();
  {
    const ScopedPhase timer = timed(Phase::kIntegration);
    x_start_ = x_;
    if (scene_.gravity) {
      const Eigen::Vector3d dv = h * gravity_;
      for (Eigen::Index i = 0; i < n; ++i) {
        if (w_[i] > 0) v_.col(i) += dv;
      }
    }
    x_ += h * v_;  // fixed vertices have v = 0
  }
  if (position_pass_) {
    const ScopedPhase timer = timed(Phase::kPositionConstraints);
    const bool parallel = arena_ != nullptr;
    if (stretch_) stretch_->project(x_, w_, h, parallel);
    if (bending_) bending_->project(x_, w_, h, parallel);
    for (const AttachmentSpec& a : attachments_) {
      // C = |x − target| toward 0: a zero-length spring of compliance α to a fixed point.
      const double wi = w_[a.vertex];
      if (wi <= 0) continue;
      const double alpha_tilde = a.compliance / (h * h);
      x_.col(a.vertex) += (a.target - x_.col(a.vertex)) * (wi / (wi + alpha_tilde));
    }
  }
  if (contacts_) {
    const ScopedPhase timer = timed(Phase::kContactConstraints);
    contacts_->project(x_, x_start_, w_);
  }
  {
    const ScopedPhase timer = timed(Phase::kVelocityUpdate);
    v_ = (x_ - x_start_) / h;
  }
  if (velocity_pass_) {
    const ScopedPhase timer = timed(Phase::kVelocityConstraints);
    if (contacts_) contacts_->applyFriction(v_, h);
    if (damping_ > 0) v_ *= std::exp(-damping_ * h);
  }
}

double ClothSimulation::maxEdgeStrain() const { return edges_.maxStrain(x_); }

double ClothSimulation::energy() const {
  double kinetic = 0, potential = 0;
  for (Eigen::Index i = 0; i < x_.cols(); ++i) {
    if (w_[i] <= 0) continue;
    kinetic += 0.5 * vertex_mass_ * v_.col(i).squaredNorm();
    potential -= vertex_mass_ * gravity_.dot(x_.col(i));
  }
  double elastic = 0;
  if (stretch_) elastic += stretch_->energy(x_);
  if (bending_) elastic += bending_->energy(x_);
  return kinetic + potential + elastic;
}

}  // namespace fse_sim
