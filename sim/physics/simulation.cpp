#include "physics/simulation.h"

namespace fse_sim {

void Simulation::declarePhases(bool position_constraints, bool contact_constraints,
                               bool velocity_constraints, bool collision_detection) {
  phases_.clear();
  phases_.push_back(Phase::kIntegration);
  if (position_constraints) phases_.push_back(Phase::kPositionConstraints);
  if (contact_constraints) phases_.push_back(Phase::kContactConstraints);
  phases_.push_back(Phase::kVelocityUpdate);
  if (velocity_constraints) phases_.push_back(Phase::kVelocityConstraints);
  if (collision_detection) phases_.push_back(Phase::kCollisionDetection);
  phases_.push_back(Phase::kTotal);
  detects_ = collision_detection;
}

void Simulation::step() {
  times_.fill(0);
  {
    ScopedPhase total(times_, Phase::kTotal);
    const double h = time_spec_.step;
    if (detects_) {
      ScopedPhase timer(times_, Phase::kCollisionDetection);
      detect(h);
    }
    const int n = time_spec_.substeps;
    runSubsteps(n, h / n);
  }
  time_ = time_spec_.step * double(++steps_);
}

void Simulation::runSubsteps(int n, double h) {
  for (int s = 0; s < n; ++s) substep(h);
}

}  // namespace fse_sim
