#include "physics/cloth_contact_solver.h"

#include <algorithm>
#include <cmath>

namespace fse_sim {

Contacts::Contacts(const Scene& scene, const SimulationOptions& options)
    : tolerance_(scene.collision->tolerance),
      skin_(kSkinPerTolerance * scene.collision->tolerance),
      friction_(scene.friction.has_value()) {
  const int n = scene.cloth.nx * scene.cloth.ny;
  for (std::size_t i = 0; i < scene.shapes.size(); ++i) {
    detectors_.push_back(makeContactDetector(scene.shapes[i], int(i), n, options));
  }
  if (friction_) {
    mu_static_ = scene.friction->static_;
    mu_dynamic_ = scene.friction->dynamic;
  }
}

void Contacts::detect(const Eigen::Matrix3Xd& x, double max_speed, double max_acceleration,
                      double step) {
  // The farthest a vertex can get in the step from its velocity and the applied acceleration,
  // doubled for what constraints may add: a vertex beyond tolerance + travel cannot reach the
  // surface before the next detection.
  const double travel = 2 * (max_speed * step + max_acceleration * step * step);
  const double margin = tolerance_ + travel;
  candidates_.clear();
  for (auto& detector : detectors_) detector->detect(x, margin, candidates_);
  active_.clear();
  push_.clear();
}

void Contacts::project(Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& x_start,
                       const Eigen::VectorXd& inverse_mass) {
  active_.clear();
  push_.clear();
  for (std::size_t k = 0; k < candidates_.size(); ++k) {
    const ContactCandidate& c = candidates_[k];
    if (inverse_mass[c.vertex] <= 0) continue;
    auto xv = x.col(c.vertex);
    const double C = c.normal.dot(xv - c.point) - skin_;
    if (C >= 0) continue;
    xv -= C * c.normal;
    if (friction_) {
      // Static friction: undo the tangential slip of this substep while it is small enough.
      Eigen::Vector3d slip = xv - x_start.col(c.vertex);
      slip -= slip.dot(c.normal) * c.normal;
      if (slip.norm() < mu_static_ * -C) xv -= slip;
    }
    active_.push_back(int(k));
    push_.push_back(-C);
  }
}

void Contacts::applyFriction(Eigen::Matrix3Xd& v, double h) const {
  if (!friction_) return;
  for (std::size_t a = 0; a < active_.size(); ++a) {
    const ContactCandidate& c = candidates_[active_[a]];
    auto vv = v.col(c.vertex);
    const Eigen::Vector3d vt = vv - vv.dot(c.normal) * c.normal;
    const double speed = vt.norm();
    if (speed <= 0) continue;
    vv -= vt * (std::min(mu_dynamic_ * push_[a] / h, speed) / speed);
  }
}

}  // namespace fse_sim
